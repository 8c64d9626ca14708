"""The singular-parameter tables of the bases, read for a curve class (below the curve
classes, so that ``Curve.from_bezier`` can refuse a singular λ without importing the public
``properties`` module, which resolves family names and so sits above them)."""

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

    def __repr__(self) -> str:
        # the isolating interval may be as wide as the whole range (one root in it): the
        # value it stands for is what a reader looks for first
        return (
            f"IsolatedRoot(lo={self.lo!r}, hi={self.hi!r}, coefficients={self.coefficients!r}, "
            f"≈ {float(self)!r})"
        )


def roots(family: str, data: object, n: int) -> tuple[Fraction | IsolatedRoot, ...]:
    """The singular λ of the degree-n basis of a family (its name and its tables; n already
    checked to be one of its degrees)."""
    # a family from load_family carries its table; a built-in one's is in generated/
    table = getattr(data, "SINGULAR", None)
    if table is not None:
        found: tuple[Fraction | IsolatedRoot, ...] = table[n]
        return found
    out: list[Fraction | IsolatedRoot] = []
    for entry in _properties.SINGULAR[family][n]:
        if isinstance(entry, tuple):
            (lo, hi), coefficients = entry
            out.append(IsolatedRoot(Fraction(lo), Fraction(hi), tuple(coefficients)))
        else:
            out.append(Fraction(entry))
    return tuple(out)


def is_root(found: tuple[Fraction | IsolatedRoot, ...], lam: Fraction | float) -> bool:
    """True when lam is one of `found`: exact for an exact λ; a float λ counts within 1e-12."""
    for root in found:
        if isinstance(lam, float):
            if abs(float(root) - lam) <= 1e-12 * max(1.0, abs(lam)):
                return True
        elif isinstance(root, Fraction) and Fraction(lam) == root:
            return True
        # an exact rational λ is never an irrational root
    return False
