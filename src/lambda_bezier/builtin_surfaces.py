"""The surface classes of the built-in families: the generic `Surface` with the family fixed.

Like builtin_curves, the one runtime module (besides the package's name table) that names a
built-in family; everything else reaches a family through `Surface(..., family=...)`.
"""

from __future__ import annotations

from fractions import Fraction

from .surfaces import NetLike, Surface


class SameDegreeSurface(Surface):
    """The tensor-product surface of the same-degree family (000) in both directions."""

    def __init__(
        self,
        net: NetLike,
        lam_u: Fraction | float,
        lam_v: Fraction | float,
        *,
        check_range: bool = True,
    ) -> None:
        super().__init__(net, lam_u, lam_v, family="same_degree", check_range=check_range)


class BernsteinLikeSurface(Surface):
    """The tensor-product surface of the Bernstein-like family (001) in both directions."""

    def __init__(
        self,
        net: NetLike,
        lam_u: Fraction | float,
        lam_v: Fraction | float,
        *,
        check_range: bool = True,
    ) -> None:
        super().__init__(net, lam_u, lam_v, family="bernstein_like", check_range=check_range)
