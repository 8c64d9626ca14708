"""The surface classes of the built-in families: the generic `Surface` with the family fixed.

Like builtin_curves, the one runtime module (besides the package's name table) that names a
built-in family; everything else reaches a family through `Surface(..., family=...)`.
"""

from __future__ import annotations

from fractions import Fraction

from .builtin_curves import BernsteinLikeCurve, SameDegreeCurve
from .curves import BezierCurve, Curve
from .surfaces import BezierSurface, NetLike, Surface


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


def most_specific(
    net: NetLike,
    lam_u: Fraction | float | None,
    lam_v: Fraction | float | None,
    *,
    classes: tuple[type[Curve], type[Curve]],
    check_range: bool = True,
) -> Surface:
    """The surface of the curve classes (u, v) as the class a user builds it with:
    SameDegreeSurface, BernsteinLikeSurface or BezierSurface when one built-in family runs in
    both directions, else the generic Surface (so that a JSON round trip keeps the class)."""
    u_cls, v_cls = classes
    if u_cls is v_cls is SameDegreeCurve:
        return SameDegreeSurface(net, lam_u, lam_v, check_range=check_range)  # type: ignore[arg-type]
    if u_cls is v_cls is BernsteinLikeCurve:
        return BernsteinLikeSurface(net, lam_u, lam_v, check_range=check_range)  # type: ignore[arg-type]
    if u_cls is v_cls is BezierCurve and lam_u is None and lam_v is None:
        return BezierSurface(net)
    return Surface(net, lam_u, lam_v, family=classes, check_range=check_range)
