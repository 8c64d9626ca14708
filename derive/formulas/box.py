"""Exact decisions over a box of several shape parameters (issue #30, items 2 and 3).

The method is Bernstein-expansion branch and bound in exact rational arithmetic
(lambda_bezier.hazmat.box_bernstein; the kernel on arrays lives there, shared with the
runtime's certified energy minimum). This module turns SymPy polynomials into those arrays
and, where a polynomial changes sign between two exact points, isolates the zero on the
segment between them with SymPy's exact real-root isolation.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import sympy as sp

from lambda_bezier.hazmat import box_bernstein

BUDGET = 3000  # boxes examined before giving up (then: "not decided")
MAX_COEFFICIENTS = 200_000  # of one tensor-product Bernstein expansion


class TooLarge(ValueError):
    """A Bernstein expansion with more coefficients than MAX_COEFFICIENTS."""


def dense(poly: sp.Poly) -> np.ndarray:
    """The power coefficients of a Poly as a dense object array indexed by exponents."""
    degs = tuple(max(0, d) for d in poly.degree_list())
    size = 1
    for d in degs:
        size *= d + 1
    if size > MAX_COEFFICIENTS:
        raise TooLarge(f"a Bernstein expansion of {size} coefficients (degrees {degs})")
    out = np.empty(tuple(d + 1 for d in degs), dtype=object)
    out.fill(Fraction(0))
    for mono, c in poly.terms():
        out[mono] = Fraction(int(c.p), int(c.q))
    return out


def _exact(x: Fraction) -> sp.Rational:
    return sp.Rational(x.numerator, x.denominator)


def sign_over_box(poly: sp.Poly, box: list[tuple[Fraction, Fraction]], *, strict: bool) -> dict:
    """box_bernstein.sign_search on a Poly (its gens in the box's order)."""
    return box_bernstein.sign_search(dense(poly), box, strict=strict, budget=BUDGET)


def zero_in_box(poly: sp.Poly, box: list[tuple[Fraction, Fraction]]) -> dict:
    """box_bernstein.zero_search on a Poly; a sign change between two exact points becomes a
    root on the segment p + s (q - p), s in an isolating interval of width <= 1e-12."""
    found = box_bernstein.zero_search(dense(poly), box, BUDGET)
    if "negative" not in found:
        return found
    p, q = found["negative"], found["positive"]
    s = sp.Symbol("s")
    at = {
        g: _exact(a) + s * (_exact(b) - _exact(a)) for g, a, b in zip(poly.gens, p, q, strict=True)
    }
    line = sp.Poly(poly.as_expr().xreplace(at), s)
    (lo, hi), _ = line.intervals(inf=0, sup=1, eps=sp.Rational(1, 10**12))[0]
    return {"zero": True, "segment": (p, q), "isolating": (Fraction(str(lo)), Fraction(str(hi)))}
