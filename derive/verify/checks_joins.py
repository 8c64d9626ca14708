"""Checkers of join claims (issue 4): C1, C2, G1, G2 conditions symbolically in n, m and per
degree pair, against derive/formulas/joins.py.
"""

from __future__ import annotations

import itertools
from fractions import Fraction
from functools import cache, lru_cache

import flint
import sympy as sp
from sympy.core.function import AppliedUndef

from .. import algebra as _algebra
from ..families.registry import REFERENCE
from .checks_core import (
    Outcome,
    S,
    checker,
    claim_kind,
    derive_module,
)
from .checks_energy import (
    _records_by_id,
)
from .checks_equations import (
    _orig,
)
from .claim_families import (
    has_closed_forms,
)
from .compare import (
    compare,
    equal,
)
from .context import (
    Context,
    Tally,
)
from .expr_parse import (
    POINT_LIKE,
    as_sympy,
    fn_name,
    parse,
)
from .scalar import (
    Sc,
    Undefined,
    _is_zero,
    as_int,
    fast_factor,
)
from .values import (
    Form,
    v_add,
    v_mul,
)

# --------------------------------------------------------------------------- joins (issue 4)

JOIN_CONTINUITY = {"g1_join": "G1", "c1_join": "C1", "c2_join": "C2", "g2_join": "G2"}


def _diff_text(a, b) -> str:
    """printed vs derived; when both are long, their (factored) difference instead."""
    fa, fb = fast_factor(a), fast_factor(b)
    if len(str(fa)) + len(str(fb)) <= 240:
        return f"printed {_orig(fa)}, derived {_orig(fb)}"
    return f"printed - derived = {_orig(fast_factor(a - b))}"


def _join_specs(record: dict, ctx: Context):
    """(first, second) as (curve, degree symbol, shape symbol, points name); 000 names its
    first curve's degree m and the second's n (eq. 17), 001 the other way round (eq. 12)."""
    if record.get("first") and record.get("second"):
        return tuple(
            (sp_["curve"], parse(sp_["degree"]), parse(sp_["shape"]), sp_["points"])
            for sp_ in (record["first"], record["second"])
        )
    pts, degs = ctx.family.points, ctx.family.join_degrees
    return tuple((f"p{w}", S[degs[w - 1]], S[f"lam{w}"], f"{pts}{w}") for w in (1, 2))


def _printed_rows(record: dict, second_points: str) -> dict[int, sp.Expr]:
    """{r: printed right side of P_{r,2}}, with the rows of `uses` records and every reference
    to an earlier row of the second curve resolved."""
    rows: dict[int, sp.Expr] = {}
    sources = [records_by_id_safe(u) for u in record.get("uses", [])] + [record]
    for rec in sources:
        for eq in rec.get("equations", []):
            lhs = parse(eq["lhs"])
            if fn_name(lhs) == second_points and lhs.args[0].is_Integer:
                rows[int(lhs.args[0])] = parse(eq["rhs"])
    fn = sp.Function(second_points)
    for _ in range(3):
        for r in list(rows):
            rows[r] = rows[r].xreplace({fn(q): rows[q] for q in rows if q != r})
    return rows


def records_by_id_safe(rid: str) -> dict:
    by_id = _records_by_id(None)
    if rid not in by_id:
        raise KeyError(f"record {rid} (named in `uses`) does not exist")
    return by_id[rid]


@cache
def _join_rows(family: str, order: int):
    return derive_module("joins").solve(family, family, order)


def _join_derived(family: str, continuity: str) -> list[dict]:
    """Derived weights of P_{r,2}: {("first", j) | ("second", 3): Expr in the derive symbols}."""
    out = []
    order = 1 if continuity in ("C1", "G1") else 2
    for row in _join_rows(family, order):
        d = {}
        for key, w in row.items():
            e = w.as_expr()
            if continuity in ("C1", "C2"):  # C = G at α = 1, d = 0
                e = e.xreplace({S["alpha"]: 1, S["d"]: 0})
            d[key] = e
        out.append(d)
    return out


@lru_cache(maxsize=1024)
def _coefficient(rhs, point):
    """∂rhs/∂point: the weight of a control point in a formula linear in the points (used by
    the symbolic and the per-degree join checks of the same rows). Taken with respect to a
    Dummy in the point's place, which is what SymPy does for a function argument, directly."""
    d = sp.Dummy()
    return sp.diff(rhs.xreplace({point: d}), d).xreplace({d: point})


@lru_cache(maxsize=1024)
def _compiled(exprs: tuple, syms: tuple):
    """exact_function, once per formula (a printed record and its erratum share most rows)."""
    return _algebra.exact_function(list(exprs), syms, number=flint.fmpq)


def linear_in_points(rhs, syms: tuple):
    """rhs = Σ w·P(idx) with weights and indices rational functions of `syms`, compiled to a
    function of their values that returns what the realiser would (a Form), or None when rhs
    is not of that shape. The printed vertex formulas are evaluated at ~100 degree pairs and
    samples per record, and Fraction arithmetic is far cheaper than walking the expression."""
    pts = sorted({a for a in sp.preorder_traversal(rhs) if isinstance(a, AppliedUndef)}, key=str)
    if not pts or any(fn_name(p) not in POINT_LIKE or len(p.args) != 1 for p in pts):
        return None
    weights = [_coefficient(rhs, p) for p in pts]
    exprs = [*weights, *(p.args[0] for p in pts)]
    if rhs.xreplace(dict.fromkeys(pts, 0)) != 0 or any(
        e.has(*pts) or not e.free_symbols <= set(syms) for e in exprs
    ):
        return None
    fn = _compiled(tuple(exprs), tuple(syms))
    names = [fn_name(p) for p in pts]

    def realise(values) -> Form:
        try:
            out = fn(*values)
        except ZeroDivisionError:
            raise Undefined("division by zero") from None
        terms: dict = {}
        for name, w, idx in zip(names, out[: len(pts)], out[len(pts) :], strict=True):
            key = ((name, as_int(idx)),)
            terms[key] = terms.get(key, Sc.of(0)) + Sc.of(w)
        return Form(terms)

    return realise


def _weights(rhs, first_pts: str, second_pts: str, n_first) -> tuple[dict, sp.Expr]:
    """Printed weights keyed like derive/formulas/joins.py: ("first", j) for P_{n-j,1}."""
    pts = {a for a in sp.preorder_traversal(rhs) if fn_name(a) in (first_pts, second_pts)}
    out: dict = {}
    for pt in pts:
        c = _coefficient(rhs, pt)
        if fn_name(pt) == first_pts:
            key = ("first", sp.expand(n_first - pt.args[0]))
        else:
            key = ("second", pt.args[0])
        out[key] = out.get(key, 0) + c
    rest = rhs.xreplace({pt: 0 for pt in pts})
    return out, rest


def join_symbolic(record, ctx, rows, specs, continuity) -> tuple[list[str], dict]:
    (_, n1, l1, pts1), (_, n2, l2, pts2) = specs
    to_j = {n1: _algebra.n, n2: _algebra.m, l1: S["lam1"], l2: S["lam2"]}
    derived = _join_derived(ctx.family.name, continuity)
    diffs = []
    for r, rhs in sorted(rows.items()):
        printed, rest = _weights(rhs, pts1, pts2, n1)
        if rest != 0:
            diffs.append(f"symbolic: P_{r},2 has a term {rest} without a control point")
        want = derived[r]
        keys = {(s_, int(j)) for s_, j in printed if as_sympy(j).is_Integer} | set(want)
        for key in sorted(keys):
            a = printed.get((key[0], sp.Integer(key[1])), 0)
            a = as_sympy(a).xreplace(to_j)
            b = want.get(key, sp.Integer(0))
            if not _is_zero(a - b):
                name = f"{pts1}({n1} - {key[1]})" if key[0] == "first" else f"{pts2}({key[1]})"
                diffs.append(f"symbolic: {pts2}({r}): weight of {name}: " + _diff_text(a, b))
    return diffs, derived


def _degree_pairs(ctx: Context):
    """Every degree of the range for each curve, against the smallest and the largest of the
    other (and the diagonal)."""
    degs = list(ctx.family.degrees)
    ends = (degs[0], degs[-1])
    return sorted({(a, b) for a in degs for b in degs if a == b or a in ends or b in ends})


def _substitute(value, sub: dict):
    if not isinstance(value, Form):
        return value
    out = Sc.of(0)
    for key, c in value.terms.items():
        if len(key) == 1 and key[0] in sub:
            out = v_add(out, v_mul(c, sub[key[0]]))
        else:
            out = v_add(out, Form({key: c}))
    return out


# Exact parameter values for the per-degree join checks (inside both λ ranges, α ≠ 1, d ≠ 0):
# the weights are compared for general n, m, λ1, λ2, α, d symbolically; per degree pair the
# printed conditions are evaluated exactly at these values, as derive/formulas/joins.py checks
# its own.
JOIN_SAMPLES = (
    {
        "lam1": Fraction(1, 3),
        "lam2": Fraction(-2, 5),
        "alpha": Fraction(3, 2),
        "d": Fraction(-7, 4),
    },
    {"lam1": Fraction(-5, 7), "lam2": Fraction(4, 9), "alpha": Fraction(2, 5), "d": Fraction(5, 3)},
)


def join_per_degree(record, ctx, rows, specs, conventions, label="convention") -> Tally:
    """The printed conditions hold, per degree pair (and at JOIN_SAMPLES), for the curves
    built from the derived basis polynomials with the printed vertex formulas substituted."""
    (_, n1, l1, _), (_, n2, l2, pts2) = specs
    tally = Tally(f"per-degree {label}")
    env_syms = (n1, n2, l1, l2, S["alpha"], S["d"])
    compiled = {r: linear_in_points(rhs, env_syms) for r, rhs in rows.items()}
    real = ctx.realiser()
    for (a, b), sample in itertools.product(_degree_pairs(ctx), JOIN_SAMPLES):
        real.reset()  # the pieces' models read the λ samples, which memo keys do not hold
        values = (a, b, sample["lam1"], sample["lam2"], sample["alpha"], sample["d"])
        env = dict(zip(env_syms, values, strict=True))
        try:
            sub = {
                (pts2, r): real(rhs, env) if compiled[r] is None else compiled[r](values)
                for r, rhs in rows.items()
            }
        except Undefined:
            continue
        row = []
        for eq in conventions:
            left = _substitute(real(parse(eq["lhs"]), env), sub)
            right = _substitute(real(parse(eq["rhs"]), env), sub)
            if not equal(left, right):
                if tally.failures or row:  # details for the first failure only
                    row.append("differs")
                    continue
                row += [
                    f"`{eq['lhs']} = {eq['rhs']}`: "
                    + d.replace("printed", "right side").replace("derived", "left side")
                    for d in compare(right, left)[:1]
                ]
        tally.add(env, row)
    return tally


@checker(
    "c1_join",
    "c2_join",
    "g1_join",
    "g2_join",
    requires=("joins",),
)
def check_join(record: dict, ctx: Context) -> Outcome:
    """Vertex formulas of 001's C1/C2/G1/G2 theorems: each weight against derive/formulas/joins.py's
    solve() symbolically in n, m, λ1, λ2 (α, d), and, per degree pair, the printed continuity
    conditions with the printed vertices substituted."""
    continuity = JOIN_CONTINUITY[claim_kind(record["claim"])]
    specs = _join_specs(record, ctx)
    rows = _printed_rows(record, specs[1][3])
    family = ctx.family.name
    symbolic = family == REFERENCE or has_closed_forms(family, 2 if continuity[1] == "2" else 1)
    diffs = join_symbolic(record, ctx, rows, specs, continuity)[0] if symbolic else []
    tally = join_per_degree(record, ctx, rows, specs, record.get("convention", []))
    diffs += tally.lines()
    checked = [
        "symbolic: weights vs joins.solve()"
        if symbolic
        else f"symbolic: none ({family} has no closed end forms in n)",
        f"per-degree conditions: {tally.total} pairs",
    ]
    return Outcome("mismatch" if diffs else "match", diffs, checked)
