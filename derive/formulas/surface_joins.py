"""Joining two tensor-product patches along a common boundary: C1, G1 and C2 (issue #31).

Patch 1 has the family F1 (degree n, shape λ1) across the boundary u = 1 and G (degree l,
shape μ) along it; patch 2 has F2 (degree m, shape λ2) across, starting at its u = 0, and the
same G, l and μ along. With b_i, c_i the across bases and g_j the along basis,

    ∂^r S1/∂u^r (1, v) = Σ_j [Σ_i P1_ij b_i^(r)(1)] g_j(v),
    ∂^r S2/∂u^r (0, v) = Σ_j [Σ_i P2_ij c_i^(r)(0)] g_j(v).

The g_j are linearly independent (derive/formulas/properties.py), so the surface conditions

    C1:  S1 = S2 and S1_u = S2_u on the boundary
    G1:  S1 = S2 and S1_u = α S2_u on the boundary, α > 0 constant along it
    C2:  C1 and S1_uu = S2_uu on the boundary

hold for every v exactly when, for every column j, the curve with points P1_0j … P1_nj and the
curve with points P2_0j … P2_mj meet the curve condition of the same name (joins.py). So the
conditions ARE the curve join weights, applied column by column:

    P2_rj = Σ_k w_{r,k}(n, m, λ1, λ2, α) P1_{n-k, j}      (r = 0..order, every j)

with the weights of joins.joins()[(F1, F2, continuity)]. They are not emitted a second time:
the runtime's join_surface applies the emitted curve join column by column.

`check_columnwise` proves the reduction exactly on sample degrees, shapes and nets: it applies
the weights to each column, builds both patches from the tensor-product basis
(surface_energy.tensor_basis) and compares the cross-boundary derivatives of the two surfaces
as polynomials in v. The join records of verify (surface_continuity) are checked against
`conditions`.

For a family defined by data, `family_artifacts` writes the same conditions into its derived
document (``surface_joins``), against itself and every built-in family in both orders, each
proved by the same column-wise check on the family's own basis. The weights are stored as
data the runtime evaluates without a parser: numerator and denominator polynomials in
(n, m, λ1, λ2, α), each a list of [coefficient, exponents...] terms.
"""

from __future__ import annotations

from fractions import Fraction
from functools import cache

import flint
import sympy as sp

from . import joins as curve_joins
from .surface_energy import _curve_basis, _direction, tensor_basis

CONTINUITIES = ("C1", "G1", "C2")
ORDER = {"C1": 1, "G1": 1, "C2": 2}
# the along-direction family and degree of the check (any: the reduction does not use it)
_ALONG = ("bezier", 2)
_SAMPLE = {"lam1": Fraction(1, 3), "lam2": Fraction(-2, 5), "alpha": Fraction(3, 2)}


def conditions(first: str, second: str, continuity: str) -> dict[tuple[int, str, int], sp.Expr]:
    """{(row, source, k): weight}: P2_{row, j} = Σ weight · X for every column j, X = P1_{n-k, j}
    (source "first") or P2_{k, j} (source "second", a row given); n, m the degrees across.
    KeyError when a family has no closed end forms in n of that order (then conditions_at,
    degree by degree)."""
    if continuity not in CONTINUITIES:
        raise ValueError(f"continuity must be one of {CONTINUITIES}, got {continuity!r}")
    built_in = _curve_joins().get((first, second, continuity))
    if built_in is not None:
        return built_in
    # a family defined by data (registered with curve_joins): solved here, as for its document
    try:
        solved = curve_joins.solve(first, second, ORDER[continuity])
    except AssertionError as exc:  # end derivatives of this order have no closed form in n
        raise KeyError(str(exc)) from None
    return _weights(solved, continuity)


def conditions_at(
    first: str, second: str, continuity: str, n: int, m: int
) -> dict[tuple[int, str, int], sp.Expr]:
    """`conditions` at the degrees n (patch 1) and m (patch 2) across the boundary, solved
    from the families' own bases at those degrees (for a family without closed end forms in
    n): the rows P2_0..P2_order from Σ_i b_i^(r)(1; λ1) P1_i = α^r Σ_i c_i^(r)(0; λ2) P2_i,
    r = 0..order (α = 1 for C1, C2), the rows P2_k past the order left free ("second")."""
    if continuity not in CONTINUITIES:
        raise ValueError(f"continuity must be one of {CONTINUITIES}, got {continuity!r}")
    order = ORDER[continuity]
    t = sp.Symbol("t")

    def ends(family: str, degree: int, shape: sp.Symbol, at: int) -> list[list[sp.Expr]]:
        basis = [
            sum(
                (
                    sp.Rational(c.numerator, c.denominator) * t**pt * shape**pl
                    for (pt, pl), c in b.items()
                ),
                sp.Integer(0),
            )
            for b in _curve_basis(family, degree)
        ]
        return [[sp.expand(sp.diff(b, t, r).subs(t, at)) for b in basis] for r in range(order + 1)]

    e1 = ends(first, n, curve_joins.lam1, 1)
    e2 = ends(second, m, curve_joins.lam2, 0)
    p1 = sp.symbols(f"p0:{n + 1}")
    p2 = sp.symbols(f"q0:{m + 1}")
    scale = curve_joins.alpha if continuity == "G1" else sp.Integer(1)
    eqs = [
        sum((e1[r][i] * p1[i] for i in range(n + 1)), sp.Integer(0))
        - scale**r * sum((e2[r][i] * p2[i] for i in range(m + 1)), sp.Integer(0))
        for r in range(order + 1)
    ]
    unknown = p2[: order + 1]
    solved = sp.solve(eqs, unknown, dict=True)
    if len(solved) != 1 or set(solved[0]) != set(unknown):
        raise ValueError(
            f"{continuity} of a {first} patch (degree {n}) to a {second} patch (degree {m}): "
            "the end derivatives do not determine the rows next to the boundary"
        )
    out: dict[tuple[int, str, int], sp.Expr] = {}
    for row, q in enumerate(unknown):
        expr = sp.expand(solved[0][q])
        for k in range(n + 1):
            w = sp.factor(expr.coeff(p1[n - k]))
            if w != 0:
                out[(row, "first", k)] = w
        for k in range(order + 1, m + 1):
            w = sp.factor(expr.coeff(p2[k]))
            if w != 0:
                out[(row, "second", k)] = w
    return out


def _weights(solved: list, continuity: str) -> dict[tuple[int, str, int], sp.Expr]:
    """{(row, source, k): weight} of curve_joins.solve's rows (the G form at α = 1, d = 0
    for a C continuity), factored, zeros left out."""
    weights = {}
    for row, combo in enumerate(solved):
        for (src, j), w in sorted(combo.items()):
            e = w.as_expr()
            if continuity.startswith("C"):
                e = e.xreplace({curve_joins.alpha: 1, curve_joins.d: 0})
            e = sp.factor(e)
            if e != 0:
                weights[(row, src, j)] = e
    return weights


@cache
def _curve_joins() -> dict:
    return curve_joins.joins()  # recomputed on each call there: read once here


def apply(
    first: str,
    second: str,
    continuity: str,
    net1,
    n: int,
    m: int,
    values: dict,
    given=None,
    weights: dict | None = None,
) -> list:
    """The rows 0..order of patch 2 (scalar nets, exact) from patch 1's net by `conditions`
    (or `weights` of that form), at the values of lam1, lam2, alpha; `given` = {row: points}
    holds the rows of patch 2 a weight refers to (P2_3 in 000's C2)."""
    subs = {curve_joins.n: n, curve_joins.m: m}
    subs |= {getattr(curve_joins, name): sp.Rational(str(v)) for name, v in values.items()}
    rows: dict[int, list[Fraction]] = {}
    if weights is None:
        weights = conditions(first, second, continuity)
    for (row, source, k), weight in weights.items():
        w = sp.Rational(weight.subs(subs))
        points = net1[n - k] if source == "first" else (given or {})[k]
        acc = rows.setdefault(row, [Fraction(0)] * len(net1[0]))
        for j, p in enumerate(points):
            acc[j] += Fraction(int(w.p), int(w.q)) * p
    return [rows[r] for r in sorted(rows)]


def _surface(basis, net) -> flint.fmpq_mpoly:
    flat = [p for row in net for p in row]
    out = basis[0] * 0
    for b, p in zip(basis, flat, strict=True):
        out += b * flint.fmpq(p.numerator, p.denominator)
    return out


def _across(p: flint.fmpq_mpoly, r: int, at: int, lam: Fraction) -> flint.fmpq_mpoly:
    for _ in range(r):
        p = p.derivative(0)
    return p.subs({"u": at, "lam_u": flint.fmpq(lam.numerator, lam.denominator)})


@cache
def check_columnwise(first: str, second: str, continuity: str) -> None:
    """Raise unless the column-wise weights make the two patches meet with `continuity`
    along the whole boundary (exactly, on sample degrees and a sample net)."""
    _check_weights(first, second, continuity, tensor_basis, conditions(first, second, continuity))


def check_pair(first: str, second: str, continuity: str) -> None:
    """check_columnwise for any two registered families: cached for built-in ones, not where
    a family defined by data takes part (it may be registered again under the same name)."""
    if first in curve_joins.FAMILIES and second in curve_joins.FAMILIES:
        return check_columnwise(first, second, continuity)
    _check_weights(first, second, continuity, tensor_basis, conditions(first, second, continuity))


def check_columnwise_at(first: str, second: str, continuity: str, n: int, m: int) -> None:
    """check_columnwise with the weights of conditions_at(n, m), for families without closed
    end forms in n (λ1, λ2 at the sample values: a family without λ ignores them)."""
    weights = conditions_at(first, second, continuity, n, m)
    _check_weights(first, second, continuity, tensor_basis, weights, (n, m))


def _check_weights(
    first: str, second: str, continuity: str, basis, weights: dict, degrees=None
) -> None:
    along, l_deg = _ALONG
    if degrees is not None:
        n, m = degrees
        lam1, lam2 = _SAMPLE["lam1"], _SAMPLE["lam2"]
    else:
        n = curve_joins.DEGREES[first][0]
        m = (
            curve_joins.DEGREES[second][-1]
            if len(curve_joins.DEGREES[second]) < 3
            else (curve_joins.DEGREES[second][2])
        )
        lam1 = _SAMPLE["lam1"] if curve_joins.HAS_LAMBDA[first] else Fraction(0)
        lam2 = _SAMPLE["lam2"] if curve_joins.HAS_LAMBDA[second] else Fraction(0)
    alpha = _SAMPLE["alpha"] if continuity == "G1" else Fraction(1)
    net1 = [
        [Fraction((7 * i + 3 * j * j + i * j) % 11 - 5, 1 + j) for j in range(l_deg + 1)]
        for i in range(n + 1)
    ]
    rest = {
        i: [Fraction(i * j - 2, 3) for j in range(l_deg + 1)]
        for i in range(ORDER[continuity] + 1, m + 1)
    }
    values = {"lam1": lam1, "lam2": lam2, "alpha": alpha}
    head = apply(first, second, continuity, net1, n, m, values, rest, weights)
    net2 = head + [rest[i] for i in sorted(rest)]
    s1 = _surface(basis(first, along, n, l_deg), net1)
    s2 = _surface(basis(second, along, m, l_deg), net2)
    for r in range(ORDER[continuity] + 1):
        left = _across(s1, r, 1, lam1)
        right = _across(s2, r, 0, lam2) * flint.fmpq(alpha.numerator, alpha.denominator) ** r
        if left != right:
            raise AssertionError(
                f"{continuity} join of a {first} patch to a {second} patch: the column-wise "
                f"weights do not match the derivative of order {r} along the boundary"
            )


def check_all() -> None:
    """check_columnwise for every ordered pair of families and every continuity."""
    for first in curve_joins.FAMILIES:
        for second in curve_joins.FAMILIES:
            for continuity in CONTINUITIES:
                check_columnwise(first, second, continuity)


# ---------------------------------------------------------------------- families defined by data
VARIABLES = ("n", "m", "lam1", "lam2", "alpha")
RULE = (
    "Patch 2 continues patch 1 across its boundary u = 1 (v = 1 likewise), with the same "
    "family, degree and shape parameter along the boundary. The conditions hold along the "
    "whole boundary exactly when, for every column j (the control points across the boundary), "
    "P2_{r,j} = sum over k of w[r,src,k] X_k for r = 0..order, X_k = P1_{n-k,j} (src first) or "
    "the given P2_{k,j} (src second); n and m are the degrees across, lam1 and lam2 the shape "
    "parameters across, alpha the G1 factor (S1_u = alpha S2_u). Each weight is "
    "[numerator, denominator], polynomials in the variables as [coefficient, exponents...] "
    "terms. G1 has one constant alpha along the boundary."
)


def _poly_terms(expr: sp.Expr) -> list:
    gens = [getattr(curve_joins, name) for name in VARIABLES]
    poly = sp.Poly(expr, *gens)
    return [
        [str(sp.Rational(c)), *map(int, exps)]
        for exps, c in sorted(poly.terms(), key=lambda t: t[0])
    ]


def _weight_data(expr: sp.Expr) -> list:
    num, den = sp.fraction(sp.cancel(sp.together(expr)))
    return [_poly_terms(num), _poly_terms(den)]


def _own_basis(name: str, defn_basis):
    """tensor_basis with the family `name` read from its definition (defn_basis(degree))."""

    def curve_basis(family: str, degree: int):
        if family != name:
            return _curve_basis(family, degree)
        return tuple(
            {(int(e[0]), int(e[1])): Fraction(int(c.p), int(c.q)) for e, c in p.terms()}
            for p in defn_basis(degree)
        )

    def basis(family_u: str, family_v: str, m: int, n: int):
        bu = [_direction(b, 0) for b in curve_basis(family_u, m)]
        bv = [_direction(c, 1) for c in curve_basis(family_v, n)]
        return tuple(b * c for b in bu for c in bv)

    return basis


def family_artifacts(name: str, defn_basis, others, order: int) -> dict:
    """The document's ``surface_joins`` of the family `name`, which must be registered with
    curve_joins (joins.extra_family) with closed end forms up to derivative `order`: for each
    ordered pair with `others` and each continuity whose curve weights have a closed form,
    the weights as polynomial data, proved column by column on the family's basis."""
    basis = _own_basis(name, defn_basis)
    pairs: dict = {}
    for other in others:
        for first, second in ((name, other), (other, name)):
            key = f"{first}>{second}"
            if key in pairs:
                continue
            entry: dict = {}
            reasons = []
            solved: dict = {}
            for continuity in CONTINUITIES:
                k = ORDER[continuity]
                if k > order:
                    reasons.append(
                        f"{continuity}: the end derivatives of order {k} have no closed form "
                        "in n (the runtime joins per degree)"
                    )
                    continue
                try:
                    if k not in solved:
                        solved[k] = curve_joins.solve(first, second, k)
                except (AssertionError, KeyError, ZeroDivisionError) as exc:
                    reasons.append(f"{continuity}: no closed form: {exc}")
                    continue
                weights = _weights(solved[k], continuity)
                _check_weights(first, second, continuity, basis, weights)
                entry[continuity] = {
                    f"{row},{src},{j}": _weight_data(w) for (row, src, j), w in weights.items()
                }
            if reasons:
                entry["reason"] = "; ".join(reasons)
            pairs[key] = entry
    return {"rule": RULE, "variables": list(VARIABLES), "pairs": pairs}
