"""Facts about the bases derived exactly by derive/properties.py: where a basis is singular.

``singular_parameters(family, n)`` reads the emitted table (generated/properties.py); nothing
here computes a root numerically except ``IsolatedRoot.__float__``, which bisects inside the
exact isolating interval.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

from ._lazy import generated

_properties = generated("properties")


@dataclass(frozen=True)
class IsolatedRoot:
    """An irrational λ: the only root of Σ coefficients[j] λ^j in the open interval (lo, hi)."""

    lo: Fraction
    hi: Fraction
    coefficients: tuple[int, ...]  # integers, lowest degree first

    def polynomial(self, x: Fraction) -> Fraction:
        return sum((c * Fraction(x) ** j for j, c in enumerate(self.coefficients)), Fraction(0))

    def __float__(self) -> float:
        lo, hi = self.lo, self.hi
        sign_lo = self.polynomial(lo) > 0
        for _ in range(64):  # exact bisection: the interval halves, the root stays inside
            mid = (lo + hi) / 2
            if (self.polynomial(mid) > 0) == sign_lo:
                lo = mid
            else:
                hi = mid
        return float((lo + hi) / 2)

    def __contains__(self, x: Fraction | float) -> bool:
        return self.lo < Fraction(x) < self.hi


def singular_parameters(family: object, n: int) -> tuple[Fraction | IsolatedRoot, ...]:
    """The λ inside the family's range at which its degree-n basis is linearly dependent:
    exact Fractions, or IsolatedRoot intervals with rational ends around irrational roots.

    A curve of that degree and λ has no unique control points for a given shape (and
    ``from_bezier`` refuses it). The classical Bézier basis has no parameter: ``()``.
    `family` is a built-in family's name or a family from ``load_family`` (whose derived
    document carries the same table, from the same exact procedure).
    """
    from .curves import family_class  # numpy: imported when first asked

    cls = family_class(family)  # a built-in family's name, a family from load_family, a class
    if not cls._has_lambda:  # the classical Bézier basis
        return ()
    if isinstance(n, bool) or not isinstance(n, int):
        raise TypeError(f"n must be an integer degree, not {type(n).__name__}")
    degrees = tuple(cls._data.DEGREES)
    if n not in degrees:
        raise ValueError(
            f"n: degree {n} is outside the {cls.family} range {degrees[0]}..{degrees[-1]}"
        )
    # a family from load_family carries its table; a built-in one's is in generated/
    table = getattr(cls._data, "SINGULAR", None)
    if table is not None:
        roots: tuple[Fraction | IsolatedRoot, ...] = table[n]
        return roots
    out: list[Fraction | IsolatedRoot] = []
    for entry in _properties.SINGULAR[cls.family][n]:
        if isinstance(entry, tuple):
            (lo, hi), coefficients = entry
            out.append(IsolatedRoot(Fraction(lo), Fraction(hi), tuple(coefficients)))
        else:
            out.append(Fraction(entry))
    return tuple(out)


def is_singular(family: object, n: int, lam: Fraction | float) -> bool:
    """True when the degree-n basis of `family` is linearly dependent at this λ: exact for an
    exact λ; a float λ counts as singular within 1e-12 of a singular parameter."""
    for root in singular_parameters(family, n):
        if isinstance(lam, float):
            if abs(float(root) - lam) <= 1e-12 * max(1.0, abs(lam)):
                return True
        elif isinstance(root, Fraction) and Fraction(lam) == root:
            return True
        # an exact rational λ is never an irrational root
    return False
