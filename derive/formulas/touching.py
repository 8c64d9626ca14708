"""Non-negativity where a basis function touches zero inside its domain (issue #30): the cases
the branch and bound of atom_nonnegative.py cannot settle, since no enclosure of b around a
zero of b is > 0.

**Trigonometric bases** (any dependence on the parameters). On each quarter period
[x0, x0 + pi/(2w)] of the domain, b = N(u, x) / (1 + u^2)^M exactly, u = tan(w (t - x0)/2) in
[0, 1] (atom_family.half_angle_numerator, one parameter monomial at a time), so b >= 0 there
is N >= 0 on [0, 1] x box: a polynomial question decided exactly by real_box.nonnegative_poly
(odd-multiplicity factors, cells off the discriminant locus, exact root isolation).

**Hyperbolic bases** (any dependence on the parameters): b = z^(-H) P(z, x) exactly with
z = e^(w t), on z in [e^(w lo), e^(w hi)], whose ends are transcendental (except 1). P >= 0 on
a rational interval enclosing the z-range proves b >= 0; a negative point inside a rational
interval enclosed by it is a counterexample (real_box.nonnegative_poly on each; the ends are
enclosed within 2^-250 by mpmath's interval arithmetic).

`nonnegative_over_box` is the whole decision for an atom family: atom_family's (exact at the
vertices, or atom_nonnegative.py's arb branch and bound, which itself certifies rational
touching points, touching_points.py), then, where that leaves a reason, the exact forms above.
"""

from __future__ import annotations

from fractions import Fraction

import sympy as sp

from ..algebra import atoms as A
from ..families.definition import Definition
from ..families.spaces import Space
from . import atom_family as F
from . import real_box
from .atom_family import _exp_enclosure, _rate_text, _top_multiple, half_angle_numerator


def nonnegative_over_box(defn: Definition, space: Space) -> dict:
    """Every b_i >= 0 on the domain for every parameter value of the box? (module docstring)"""
    got = F.nonnegative_over_box(defn, space)
    if "reason" not in got:
        return got
    if space.name == "trigonometric":
        return trig_nonnegative_exact(defn, space)
    if space.name == "hyperbolic":
        return hyperbolic_nonnegative_exact(defn, space)
    return got


def trig_nonnegative_exact(defn: Definition, space: Space) -> dict:
    """{"nonnegative": True, "method": ...}, a counterexample, or a reason (module
    docstring); for a trigonometric space."""
    frame = space.frame
    quarters = 2 * frame.rate * (frame.hi - frame.lo)
    if quarters.denominator != 1:
        return {"reason": "the domain is not a whole number of quarter periods"}
    step = (frame.hi - frame.lo) / int(quarters)
    top = _top_multiple(space)
    u = sp.Symbol("u")
    gens = (u, *defn.symbols)
    box = [(Fraction(0), Fraction(1)), *[(q.lo, q.hi) for q in defn.params]]
    monos = A.monomials(space.functions)
    for idx, b in enumerate(space.functions):
        for piece in range(int(quarters)):
            x0 = frame.lo + piece * step
            total = sp.Integer(0)
            for mono in monos:
                num = half_angle_numerator(A.part(b, mono), frame, x0, top)
                weight = sp.Mul(*[s**e for s, e in zip(defn.symbols, mono, strict=True)])
                total += weight * sum(
                    (sp.Rational(c.numerator, c.denominator) * u**j for j, c in enumerate(num)),
                    sp.Integer(0),
                )
            poly = sp.Poly(sp.expand(total), *gens)
            try:
                got = real_box.nonnegative_poly(poly, box)
            except real_box.Undecided as exc:
                return {"reason": f"b_{idx}: {exc}"}
            if got["holds"]:
                continue
            uv, *values = got["point"]
            where = f"{x0}*pi" if frame.dom_pi else str(x0)
            value = Fraction(*_fraction(poly.eval(tuple(sp.Rational(v) for v in got["point"]))))
            return {
                "nonnegative": False,
                "counterexample": {
                    "n": len(space.functions) - 1,
                    "i": idx,
                    "t": f"{where} + 2*atan({uv})/({_rate_text(space, 1)})",
                    **{q.name: str(v) for q, v in zip(defn.params, values, strict=True)},
                    "value": str(value / (1 + uv**2) ** top),
                },
            }
    return {
        "nonnegative": True,
        "method": "exact: per quarter period, the half-angle numerator N(tan, parameters) >= 0 "
        "on [0, 1] x box by exact root isolation on the cells off its discriminant locus",
    }


def hyperbolic_nonnegative_exact(defn: Definition, space: Space) -> dict:
    """{"nonnegative": True, "method": ...}, a counterexample, or a reason (module
    docstring); for a hyperbolic space."""
    frame = space.frame
    if any(key[1] or key[2] or key[4] for b in space.functions for key in b):
        return {"reason": "not a polynomial in e^(w t) and e^(-w t)"}
    top = max((abs(key[3]) for b in space.functions for key in b), default=0)
    (a_lo, a_hi), (b_lo, b_hi) = (_exp_enclosure(frame.rate * x) for x in (frame.lo, frame.hi))
    z = sp.Symbol("z")
    gens = (z, *defn.symbols)
    params = [(q.lo, q.hi) for q in defn.params]
    for idx, b in enumerate(space.functions):
        total = sp.Integer(0)
        for (mono, _c, _k, h, _m, _kind), v in b.items():
            weight = sp.Mul(*[s**e for s, e in zip(defn.symbols, mono, strict=True)])
            total += sp.Rational(v.numerator, v.denominator) * weight * z ** (h + top)
        poly = sp.Poly(sp.expand(total), *gens)
        try:
            if real_box.nonnegative_poly(poly, [(a_lo, b_hi), *params])["holds"]:
                continue
            got = real_box.nonnegative_poly(poly, [(a_hi, b_lo), *params])
        except real_box.Undecided as exc:
            return {"reason": f"b_{idx}: {exc}"}
        if got["holds"]:
            return {
                "reason": f"b_{idx}: negative only within 2^-250 of a transcendental end of "
                "the domain (e^(w t) there)"
            }
        zv, *values = got["point"]
        return F.negative_at_log(defn, space, idx, zv, values)
    return {
        "nonnegative": True,
        "method": "exact: b = e^(-H w t) P(e^(w t), parameters) with P >= 0 on a rational "
        "interval enclosing the range of e^(w t), by exact root isolation on the cells off "
        "its discriminant locus",
    }


def _fraction(x: sp.Rational) -> tuple[int, int]:
    return int(x.p), int(x.q)
