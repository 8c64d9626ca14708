"""What is derived for a family defined by data, generic over its derivation: the energy
forms, the closed-form join weights against every built-in family (of curves, and of surface
patches column by column), the singular parameters, and making the family known to the
formula tables for this process (register_formulas).
"""

from __future__ import annotations

import sympy as sp

from ..algebra import lambda_degree
from ..families.definition import CONTINUITIES, ENERGY_ORDERS, Definition
from ..families.engine import basis_polys, closed_endpoint_forms, closed_endpoint_order
from ..families.registry import builtin_names
from . import energy, joins, properties, surface_energy, surface_joins


def energy_artifacts(defn: Definition) -> dict:
    """{"n,k": {"ff": [scale, U], "fg": [...], "gg": [...]}} and the published (c, X, Y), or a
    reason when the basis is not linear in the parameter."""
    if defn.several:
        return _energy_several(defn)
    out: dict = {}
    for deg in defn.degrees:
        polys = basis_polys(defn, deg)
        if lambda_degree(polys) == 0:
            return {"reason": f"the basis does not depend on {defn.parameter}: nothing to optimise"}
        if lambda_degree(polys) > 1:
            return {
                "reason": f"the basis is of degree {lambda_degree(polys)} in "
                f"{defn.parameter} at n = {deg}: E_k is not a quadratic in it"
            }
        for k in ENERGY_ORDERS:
            forms = energy.forms_from_polys(polys, deg + defn.offset, k)
            entry = {key: [str(s), [list(r) for r in u]] for key, (s, u) in forms.items()}
            (s_fg, x), (s_gg, y) = forms["fg"], forms["gg"]
            if s_gg != 0:
                entry["published"] = [str(s_fg / s_gg), [list(r) for r in x], [list(r) for r in y]]
            out[f"{deg},{k}"] = entry
    return out


def _energy_several(defn: Definition) -> dict:
    """E_k of a family in several parameters x_1..x_J whose basis is affine in them jointly,
    b = c_0 + sum_j x_j c_j: {"n,k": {"a,b": G}} with G[i][l] = int_0^1 c_a,i^(k) c_b,l^(k) dt
    (a <= b in 0..J, part 0 the constant one), exact; E_k = sum_ab w_a w_b tr(P^T G_ab P)
    with w_0 = 1, w_j = x_j (the off-diagonal pairs counted twice). A reason otherwise."""
    from ..families.engine import monomial_split

    names = defn.parameters
    units = [tuple(int(j == k) for j in range(len(names))) for k in range(len(names))]
    zero = tuple(0 for _ in names)
    out: dict = {}
    for deg in defn.degrees:
        split = monomial_split(defn, deg)
        higher = [m for m in split if sum(m) > 1]
        if higher:
            mono = "*".join(
                f"{x}**{e}" if e > 1 else x for x, e in zip(names, higher[0], strict=True) if e
            )
            return {
                "reason": f"the basis is not affine in the parameters jointly at n = {deg} "
                f"(it has a term in {mono}): E_k is not a quadratic in them"
            }
        t = sp.Symbol("t")
        parts = []
        for mono in (zero, *units):
            polys = split.get(mono)
            parts.append(
                [sp.Integer(0)] * (deg + 1)
                if polys is None
                else [sp.Poly(p.as_expr(), t) for p in polys]
            )
        for k in ENERGY_ORDERS:
            entry = {}
            for a in range(len(parts)):
                for b in range(a, len(parts)):
                    gram = [[str(_inner(pa, pb, k, t)) for pb in parts[b]] for pa in parts[a]]
                    entry[f"{a},{b}"] = gram
            out[f"{deg},{k}"] = entry
    return out


def _inner(p, q, k: int, t: sp.Symbol) -> sp.Rational:
    """int_0^1 p^(k)(t) q^(k)(t) dt, exact."""
    if not isinstance(p, sp.Poly) or not isinstance(q, sp.Poly):
        return sp.Integer(0)
    prod = (p.diff((t, k)) * q.diff((t, k))).integrate()
    return prod.eval(1) - prod.eval(0)


def join_artifacts(defn: Definition, closed: dict) -> dict:
    """Closed-form join weights (derive/formulas/joins.py's solve) of the family after and before
    itself and every built-in family, each checked per degree pair; a pair whose stencil the
    closed-form solve does not cover is named with the reason (the runtime still joins it,
    per degree)."""
    out: dict = {}
    order = closed_endpoint_order(defn)
    with joins.extra_family(defn.name, closed, tuple(defn.degrees), True, order):
        for other in (*builtin_names(), defn.name):
            for first, second in ((defn.name, other), (other, defn.name)):
                if (first, second) == (defn.name, defn.name) and f"{first}>{second}" in out:
                    continue
                solved, reasons = {}, []
                for k in (1, 2):
                    if k > order:
                        reasons.append(
                            f"{'C2/G2' if k == 2 else 'C1/G1'}: the end derivatives of order "
                            f"{k} have no closed form in n (the runtime joins per degree)"
                        )
                        continue
                    try:
                        solved[k] = joins.solve(first, second, k)
                    except (AssertionError, KeyError, ZeroDivisionError) as exc:
                        reasons.append(f"{'C2/G2' if k == 2 else 'C1/G1'}: no closed form: {exc}")
                weights = {}
                for cont in CONTINUITIES:
                    if joins.ORDER[cont] not in solved:
                        continue
                    for r, combo in enumerate(solved[joins.ORDER[cont]]):
                        for (src, j), w in sorted(combo.items()):
                            e = w.as_expr()
                            if cont in ("C1", "C2"):
                                e = e.xreplace({joins.alpha: 1, joins.d: 0})
                            e = sp.factor(e)
                            if e != 0:
                                weights[f"{cont},{r},{src},{j}"] = str(e)
                entry: dict = {"weights": weights} if solved else {}
                if reasons:
                    entry["reason"] = "; ".join(reasons)
                out[f"{first}>{second}"] = entry
    return out


def surface_join_artifacts(defn: Definition, closed: dict) -> dict:
    """The C1, G1 and C2 conditions between two surface patches of the family and every
    built-in family (derive/formulas/surface_joins.py), for the derived document."""
    order = closed_endpoint_order(defn)
    with joins.extra_family(defn.name, closed, tuple(defn.degrees), True, order):
        return surface_joins.family_artifacts(
            defn.name,
            lambda degree: basis_polys(defn, degree),
            (*builtin_names(), defn.name),
            order,
        )


def _register_properties(defn: Definition) -> None:
    interval = properties.Interval(defn.lo, defn.hi, not defn.lo_closed, not defn.hi_closed)
    properties.register(
        defn.name, lambda degree: basis_polys(defn, degree), defn.offset, defn.degrees, interval
    )


def singular_artifacts(defn: Definition) -> dict[str, list]:
    """{n: [root, ...]}: the parameters inside the range where the degree-n basis is linearly
    dependent (derive/formulas/properties.py: the determinant of the Bernstein coefficients,
    exact root isolation); a root is an exact "p/q" or [[lo, hi], [c_0, ..., c_k]] around an
    irrational root of the integer polynomial Σ c_j λ^j."""
    _register_properties(defn)
    iv = properties.FAMILY_RANGES[defn.name]
    out = {}
    for deg in defn.degrees:
        out[str(deg)] = [
            str(r.exact)
            if r.exact is not None
            else [[str(r.lo), str(r.hi)], [int(c) for c in r.factor]]
            for r in properties.singular_roots(defn.name, deg, iv)
        ]
    return out


class _EnergyBasis:
    """What derive/formulas/energy.py reads of a family module, for a family defined by data."""

    def __init__(self, defn: Definition):
        self.defn = defn
        self.DEGREE_OFFSET = defn.offset
        self.DEGREES = defn.degrees

    def basis_polys(self, degree: int) -> list[sp.Poly]:
        return basis_polys(self.defn, degree)


def register_formulas(defn: Definition) -> None:
    """Make the family known to the formula tables for this process (energies, properties,
    joins where the engine found closed end forms); verify registers its checkers itself."""
    closed = closed_endpoint_forms(defn)
    energy.EXTRA[defn.name] = _EnergyBasis(defn)
    surface_energy.register(defn.name, energy.EXTRA[defn.name])  # surface records (#31)
    _register_properties(defn)
    if closed is not None:
        joins.register(defn.name, closed, tuple(defn.degrees), True, closed_endpoint_order(defn))
