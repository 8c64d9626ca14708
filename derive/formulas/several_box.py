"""Linear independence and non-negativity of a basis over a whole box of several parameters.

**Linear independence.** Let M(x) be the matrix of the degree-n functions' power coefficients
in t: n + 1 rows and n + offset + 1 columns, with entries polynomial in the parameters x. The
functions are linearly dependent exactly where every maximal minor of M vanishes. Let G be the
gcd of the minors. The singular set is the zero set of G, together with the common zeros of
the cofactors m_k / G, which have no common factor. Each irreducible factor of G is tested for
a zero in the box, and so is each cofactor, one at a time: if one cofactor has no zero, there
is no common zero. If every cofactor has a zero, their sum of squares is tested instead. All of
this is exact (derive/formulas/box.py). A zero is reported as an exact point, or as a segment
between two exact points together with an isolating interval of the root on that segment.
Where a zero set only touches the box (the branch and bound's budget runs out), exact real
algebra decides (real_box.py: a point on a face or a critical point, algebraic coordinates
given exactly and as floats).

**Non-negativity**, for a basis that is not affine in the parameters. This is checked for
each function, over [0, 1] x box. Factors t and 1 - t are dropped, since they are >= 0 on
[0, 1]. So are factors of even multiplicity. The product of the rest is then tested for
>= 0 by the same branch and bound; where it touches zero and the budget runs out, by the
exact cells off its discriminant locus (real_box.nonnegative_poly). A basis that is affine
in the parameters keeps the vertex argument of families/engine.py.

The box is the closure of the parameter ranges. A point on an open end is labelled as such.
"""

from __future__ import annotations

import itertools
from fractions import Fraction

import sympy as sp

from ..families.definition import Definition
from ..families.engine import basis_polys, nonnegative_over_box
from . import box, real_box

MAX_MINORS = 400


def _box(defn: Definition) -> list[tuple[Fraction, Fraction]]:
    return [(q.lo, q.hi) for q in defn.params]


def _point(defn: Definition, values: tuple[Fraction, ...], extra: dict | None = None) -> dict:
    out = {name: str(v) for name, v in zip(defn.parameters, values, strict=True)}
    excluded = [
        q.name
        for q, v in zip(defn.params, values, strict=True)
        if (v == q.lo and not q.lo_closed) or (v == q.hi and not q.hi_closed)
    ]
    if excluded:
        out["on_excluded_end"] = excluded  # type: ignore[assignment]
    return {**(extra or {}), **out}


def _found(defn: Definition, deg: int, found: dict, what: str) -> dict:
    if "point" in found:
        return {"n": deg, "where": what, **_point(defn, found["point"])}
    p, q = found["segment"]
    lo, hi = found["isolating"]
    return {
        "n": deg,
        "where": what,
        "segment": [_point(defn, p), _point(defn, q)],
        "s_isolating": [str(lo), str(hi)],
        "text": "a zero at p + s (q - p) for an s in the isolating interval",
    }


def _exact_point(defn: Definition, deg: int, point: tuple, factor: sp.Poly | None) -> dict:
    """A counterexample at an exact (possibly algebraic) point, with its floats."""
    where = "every maximal minor = 0" if factor is None else f"{factor.as_expr()} = 0"
    out: dict = {"n": deg, "where": where}
    for q, v in zip(defn.params, point, strict=True):
        out[q.name] = str(v)
        if not v.is_Rational:
            out[f"{q.name}_float"] = f"{float(sp.N(v, 30)):.17g}"
    excluded = [
        q.name
        for q, v in zip(defn.params, point, strict=True)
        if v.is_Rational
        and (
            (v == real_box._q(q.lo) and not q.lo_closed)
            or (v == real_box._q(q.hi) and not q.hi_closed)
        )
    ]
    if excluded:
        out["on_excluded_end"] = excluded
    return out


def _minors(polys: list[sp.Poly], gens: tuple, big: int) -> list[sp.Poly]:
    t = polys[0].gens[0]
    rows = [[sp.Poly(p.as_expr(), t).coeff_monomial(t**c) for c in range(big + 1)] for p in polys]
    size = len(rows)
    out = []
    for cols in itertools.combinations(range(big + 1), size):
        mat = sp.Matrix([[row[c] for c in cols] for row in rows])
        det = sp.Poly(sp.expand(mat.det(method="berkowitz")), *gens)
        if not det.is_zero:
            out.append(det)
    return out


def independence_over_box(defn: Definition) -> dict:
    """{"independent": True, "method": ...}, or {"independent": False, "counterexample":
    {...}}, or {"independent": None, "reason": ...}, every degree of the family."""
    gens = defn.symbols
    parts = []
    for deg in defn.degrees:
        polys = basis_polys(defn, deg)
        big = deg + defn.offset
        from math import comb

        if comb(big + 1, deg + 1) > MAX_MINORS:
            return {"independent": None, "reason": f"n = {deg}: too many minors to decide"}
        minors = _minors(polys, gens, big)
        if not minors:
            return {
                "independent": False,
                "counterexample": {"n": deg, "where": "every parameter value"},
            }
        g = minors[0]
        for m in minors[1:]:
            g = g.gcd(m)
        try:
            _, factors = g.factor_list()
            for factor, _mult in factors:
                if factor.is_ground:
                    continue
                found = box.zero_in_box(factor, _box(defn))
                if found["zero"]:
                    return {
                        "independent": False,
                        "counterexample": _found(defn, deg, found, f"{factor.as_expr()} = 0"),
                    }
                if found["zero"] is None:
                    try:  # a touching zero: exact real algebra (real_box.py)
                        point = real_box.hypersurface_point(factor, _box(defn))
                    except real_box.Undecided as exc:
                        return {
                            "independent": None,
                            "reason": f"n = {deg}: a zero of {factor.as_expr()} in the box: {exc}",
                        }
                    if point is not None:
                        return {
                            "independent": False,
                            "counterexample": _exact_point(defn, deg, point, factor),
                        }
            rest = [sp.Poly(sp.div(m, g)[0], *gens) for m in minors]
            if any(r.is_ground for r in rest):
                parts.append(f"n = {deg}: the minors' gcd has no zero in the box")
                continue
            decided = False
            for r in rest:
                if box.zero_in_box(r, _box(defn))["zero"] is False:
                    parts.append(
                        f"n = {deg}: the minors' gcd and the cofactor {r.as_expr()} have no "
                        "zero in the box"
                    )
                    decided = True
                    break
            if decided:
                continue
            total = sum((r**2 for r in rest[1:]), rest[0] ** 2)
            found = box.zero_in_box(total, _box(defn))
            if found["zero"]:
                return {
                    "independent": False,
                    "counterexample": _found(defn, deg, found, "every maximal minor = 0"),
                }
            if found["zero"] is None:
                try:  # common zeros where the sum of squares only touches 0: exact
                    point = real_box.ideal_point(rest, _box(defn))
                except real_box.Undecided as exc:
                    return {"independent": None, "reason": f"n = {deg}: {exc}"}
                if point is not None:
                    return {
                        "independent": False,
                        "counterexample": _exact_point(defn, deg, point, None),
                    }
                parts.append(f"n = {deg}: the cofactors have no common zero in the box (exact)")
                continue
            parts.append(f"n = {deg}: the cofactors' sum of squares has no zero in the box")
        except box.TooLarge as exc:
            return {"independent": None, "reason": f"n = {deg}: {exc}"}
    return {
        "independent": True,
        "method": "maximal minors of the power coefficients; their gcd's factors and "
        "cofactors shown zero-free on the closed box by exact Bernstein branch and bound",
        "proved": parts,
    }


def _odd_part(p: sp.Poly) -> tuple[sp.Poly, list[str]]:
    """p with factors t, 1 - t and even powers dropped (nonnegative on [0, 1] x box), the
    sign of the constant kept; the dropped factors, as text."""
    t = p.gens[0]
    const, factors = p.factor_list()
    keep = sp.Poly(const, *p.gens)
    dropped = []
    for f, mult in factors:
        expr = f.as_expr()
        if expr in (t, t - 1, 1 - t) or mult % 2 == 0:
            if expr == t - 1 and mult % 2 == 1:
                keep = -keep  # (t - 1) = -(1 - t)
            dropped.append(f"({expr})**{mult}")
            continue
        keep = keep * f**mult
    return keep, dropped


def _negative_near(p: sp.Poly, point: tuple, t_box: list) -> tuple:
    """A point where p itself is < 0, near `point` where its odd part is: the factors set
    aside are >= 0 and vanish only on a thinner set, so a step towards the box's centre
    (halved until it works) leaves it."""
    centre = tuple((lo + hi) / 2 for lo, hi in t_box)
    for k in range(0, 80):
        step = Fraction(1, 2**k) if k else Fraction(0)
        q = tuple(x + (c - x) * step for x, c in zip(point, centre, strict=True))
        at = {s: box._exact(v) for s, v in zip(p.gens, q, strict=True)}
        if p.as_expr().xreplace(at) < 0:
            return q
    return point  # pragma: no cover - the odd part is < 0 on an open set around `point`


def nonnegativity(defn: Definition) -> dict:
    """Every basis function >= 0 for t in [0, 1] and every point of the box: the vertex
    argument for a basis affine in the parameters (families/engine.py), the exact Bernstein
    branch and bound otherwise; a counterexample point when it fails."""
    affine = nonnegative_over_box(defn)
    if "reason" not in affine:
        return {**affine, "method": "affine in the parameters: every vertex, exact roots in t"}
    t_box = [(Fraction(0), Fraction(1)), *_box(defn)]
    exact_cells: list[str] = []
    for deg in defn.degrees:
        for idx, p in enumerate(basis_polys(defn, deg)):
            odd, _ = _odd_part(p)
            try:
                got = box.sign_over_box(odd, t_box, strict=False)
            except box.TooLarge:
                got = {"holds": None}
            if got["holds"] is None:  # a touching zero: the exact cells of real_box.py
                try:
                    got = real_box.nonnegative_poly(p, t_box)
                except real_box.Undecided as exc:
                    return {"nonnegative": None, "reason": f"n = {deg}, b_{idx}: {exc}"}
                if got["holds"]:
                    exact_cells.append(f"n = {deg}, b_{idx}")
            if got["holds"] is False:
                point = _negative_near(p, got["point"], t_box)
                tv, *values = point
                at = {s: box._exact(v) for s, v in zip(p.gens, point, strict=True)}
                return {
                    "nonnegative": False,
                    "counterexample": {
                        "n": deg,
                        "i": idx,
                        "t": str(tv),
                        **_point(defn, tuple(values)),
                        "value": str(p.as_expr().xreplace(at)),
                    },
                }
    method = (
        "exact Bernstein branch and bound over [0, 1] x the box (factors t, 1 - t and even "
        "powers set aside)"
    )
    if exact_cells:
        method += (
            "; where a function touches zero ("
            + ", ".join(exact_cells)
            + "), exact sample points of the cells off its discriminant locus"
        )
    return {"nonnegative": True, "method": method}
