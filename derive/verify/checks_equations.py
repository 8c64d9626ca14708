"""Checkers of equations: a general form of the basis, end values and derivatives (per index
and of the curve), per degree and, where derive has closed forms in n, symbolically.
"""

from __future__ import annotations

import sympy as sp

from .. import algebra as _algebra
from ..families.registry import REFERENCE
from .checks_core import (
    Outcome,
    S,
    checker,
)
from .claim_families import (
    TO_DERIVE,
    bezier_closed,
    bezier_weights,
    closed_forms,
    has_closed_forms,
    symbolic_zero,
    to_derive,
)
from .compare import (
    show,
)
from .context import (
    Context,
    Tally,
    _solve_linear,
    equations_outcome,
)
from .expr_parse import (
    as_sympy,
    fn_name,
    parse,
)
from .realiser import (
    symbolic_delta,
)
from .scalar import (
    Sc,
    _is_zero,
    as_int,
)

# --------------------------------------------------------------------------- generic claims


@checker(
    "basis_general",
    "recursion",
    "basis_list",
    "basis_in_bernstein",
    "curve_definition",
    "energy_split",
    "energy_qw",
    "energy_derivative",
    "join_setup",
    "original_curve",
    "original_basis",
    "original_basis_list",
    "original_to_bernstein",
    "bernstein_definition",
    "bernstein_list",
    "partition_of_unity",
    "symmetry",
    "bernstein_derivative",
    "degree_elevation",
    "subdivision_identity",
    "integral",
    "power_to_bernstein",
    "bernstein_to_power",
    "endpoint_interpolation",
    "decasteljau",
    "decasteljau_intermediate",
    "hodograph",
    "end_curvature",
    "derivative_decasteljau",
    "derivative_decasteljau_example",
    "subdivision",
)
def check_equations(record: dict, ctx: Context, extra_lines=()) -> Outcome:
    """Every printed equality, for every degree of the range and every index, with the models
    (`extra_lines`: a family checker's own findings, e.g. a symbolic comparison)."""
    eqs = list(record["equations"]) + list(record.get("conventions") or [])
    return equations_outcome(record, ctx, eqs, extra_lines=extra_lines)


def _orig(e) -> str:
    return str(e.xreplace({v: k for k, v in TO_DERIVE.items()}))


def _from_derive(e):
    return e.xreplace({v: k for k, v in TO_DERIVE.items()})


# --------------------------------------------------------------------------- endpoint cases


def _index_bounds(text: str):
    if text == "otherwise":
        return None
    if ".." in text:
        lo, hi = text.split("..")
        return parse(lo), parse(hi)
    e = parse(text)
    return e, e


def _generic_le(a, b) -> bool:
    """a <= b for every large n (a, b linear in n)."""
    d = sp.expand(b - a)
    c = d.coeff(S["n"])
    return c > 0 or (c == 0 and d.subs(S["n"], 0) >= 0)


@checker("endpoint_values", "endpoint_d1", "endpoint_d2")
def check_cases(record: dict, ctx: Context) -> Outcome:
    """By-index results (eqs. 8-11 of 000/001, B(0), B(1) of 002): every printed case against
    the derived closed forms symbolically, and every index 0..n of every degree against the
    derived derivative, including indices the printed cases do not cover."""
    func = parse(record["function"])
    var = S[record.get("variable", "t")]
    at = parse(record["at"])
    order = int(record["order"])
    end = "start" if at == 0 else "end"
    cases = [(_index_bounds(c["index"]), parse(c["value"]), c) for c in record["cases"]]
    fam = ctx.family.name if fn_name(func) == "b" else REFERENCE
    diffs = symbolic_cases(fam, end, order, cases)
    real = ctx.realiser()
    tally = Tally("per-degree")
    n = S["n"]
    for deg in ctx.family.degrees:
        env0 = {n: sp.Integer(deg)}
        covered: dict = {}
        for bounds, value, case in cases:
            if bounds is None:
                continue
            lo = as_int(real(bounds[0], env0))
            hi = as_int(real(bounds[1], env0))
            for ii in range(max(lo, 0), min(hi, deg) + 1):
                covered.setdefault(ii, []).append((value, case))
        rest = [(v, c) for b, v, c in cases if b is None]
        for ii in range(deg + 1):
            env = {**env0, S[record["index"]]: sp.Integer(ii)}
            val = real(func, env)
            want = val.diff(var, order).subs(var, Sc.of(at))
            hits = covered.get(ii) or rest
            row = []
            if not hits:
                row.append(f"index {ii} is not covered by any printed case (derived {show(want)})")
            if len(hits) > 1:
                first, *others = (real(v, env) for v, _ in hits)
                if any(not _is_zero(first - other) for other in others):
                    values = {show(first), *map(show, others)}
                    row.append(
                        f"index {ii} is covered by cases with different values {sorted(values)}"
                    )
            for v, c in hits[:1]:
                got = real(v, env)
                if not _is_zero(got - want):
                    row.append(f"case `{c['index']}`: printed {show(got)}, derived {show(want)}")
            tally.add(env, row)
    diffs += tally.lines()
    checked = [
        "symbolic: cases vs derived closed forms"
        if fam == REFERENCE or has_closed_forms(fam, order)
        else f"symbolic: none ({fam} has no closed end forms in n of order {order})",
        f"per-degree: {tally.total} cases",
    ]
    return Outcome("mismatch" if diffs else "match", diffs, checked)


def symbolic_cases(family: str, end: str, order: int, cases) -> list[str]:
    n = S["n"]
    if family == REFERENCE:
        keys = {(end, order, idx): bezier_closed(end, order, idx) for idx in range(order + 1)}
    elif not has_closed_forms(family, order):
        return []  # a family without general-n end forms: checked per degree only
    else:
        keys = {key: v for key, v in closed_forms(family).items() if key[:2] == (end, order)}
    keys = {k: v for k, v in keys.items() if v != 0}

    def index_of(idx):
        return sp.Integer(idx) if end == "start" else n - idx

    def covers(bounds, index) -> bool:
        lo, hi = bounds
        return _generic_le(lo, index) and _generic_le(index, hi)

    diffs = []
    explicit = [(b, v, c) for b, v, c in cases if b is not None]
    other = [(b, v, c) for b, v, c in cases if b is None]
    for key, derived in sorted(keys.items(), key=str):
        index = index_of(key[2])
        hits = [(v, c) for b, v, c in explicit if covers(b, index)] or [(v, c) for _, v, c in other]
        if not hits:
            diffs.append(f"symbolic: index {index} (derived {sp.factor(derived)}) is not covered")
            continue
        for v, c in hits:
            if not symbolic_zero(v - _from_any(derived)):
                diffs.append(
                    f"symbolic: case `{c['index']}`: printed {v}, derived "
                    f"{sp.factor(sp.combsimp(derived))}"
                )
    # explicit single-index cases whose derived value is zero
    for b, v, c in explicit:
        if b[0] != b[1]:
            continue
        index = b[0]
        offset = sp.expand(index if end == "start" else n - index)
        if not offset.is_Integer:
            continue
        if (end, order, int(offset)) not in keys and not symbolic_zero(v):
            diffs.append(f"symbolic: case `{c['index']}`: printed {v}, derived 0")
    return diffs


def _from_any(e):
    return _from_derive(e)


# --------------------------------------------------------------------------- endpoint curves


def _endpoint_lhs(lhs):
    """(end, order) of p(0), p(1), Subs(Derivative(p(t), (t, r)), t, 0/1); else None."""
    if fn_name(lhs) == "p" and lhs.args[0] in (0, 1):
        return ("start" if lhs.args[0] == 0 else "end"), sp.Integer(0)
    if isinstance(lhs, sp.Subs) and isinstance(lhs.expr, sp.Derivative):
        d = lhs.expr
        if fn_name(d.expr) == "p" and len(d.variable_count) == 1:
            point = lhs.point[0]
            return ("start" if point == 0 else "end"), d.variable_count[0][1]
    return None


def symbolic_endpoint(family: str, eq: dict) -> list[str]:
    """p^(r)(0) / p^(r)(1) printed as a combination of control points vs the closed forms."""
    lhs, rhs = parse(eq["lhs"]), parse(eq["rhs"])
    which = _endpoint_lhs(lhs)
    if which is None or (family != REFERENCE and not has_closed_forms(family)):
        return []  # not an end value, or a family checked per degree only
    end, order = which
    n = S["n"]
    rhs = symbolic_delta(rhs)
    if not order.is_Integer or rhs.has(sp.Sum):
        return symbolic_endpoint_sum(family, end, order, lhs, rhs, eq)
    order = int(order)
    if family != REFERENCE and not has_closed_forms(family, order):
        return []  # this order has no general-n form: checked per degree only
    pts = {a for a in sp.preorder_traversal(rhs) if fn_name(a) in ("P", "V", "b")}
    coeffs = sp.collect(sp.expand(rhs), list(pts), evaluate=False) if pts else {}
    printed = {}
    for p_app, c in coeffs.items():
        if p_app == 1:
            if c != 0:
                return [f"symbolic: `{eq['lhs']}`: printed has a term {c} without a point"]
            continue
        off = sp.expand(p_app.args[0] if end == "start" else n - p_app.args[0])
        printed[int(off)] = printed.get(int(off), 0) + c
    derived = {}
    for idx in range(order + 2):
        if family == REFERENCE:
            v = bezier_closed(end, order, idx)
        else:
            v = closed_forms(family).get((end, order, idx), 0)
        if v != 0:
            derived[idx] = _from_derive(v)
    diffs = []
    for idx in sorted(set(printed) | set(derived)):
        a, b = (
            as_sympy(printed.get(idx, 0)),
            as_sympy(derived.get(idx, 0)),
        )
        if not symbolic_zero(a - b):
            name = f"{idx}" if end == "start" else f"n - {idx}" if idx else "n"
            diffs.append(
                f"symbolic: `{eq['lhs']}`: coefficient of point {name}: printed "
                f"{sp.factor(a)}, derived {sp.factor(sp.combsimp(b))}"
            )
    return diffs


def symbolic_endpoint_sum(family, end, order, lhs, rhs, eq) -> list[str]:
    """A printed C·Σ_{v=lo}^{hi} c(v)·point(e(v)) with a symbolic order, against the Bézier
    weights: reindexed by s (point s at t=0, point n - s at t=1)."""
    if family != REFERENCE:
        return []
    n = S["n"]
    sums = [a for a in sp.preorder_traversal(rhs) if isinstance(a, sp.Sum)]
    if len(sums) != 1:
        return []
    s_ = sums[0]
    outer = sp.Mul(*[a for a in sp.Mul.make_args(rhs) if a != s_])
    if outer.has(sp.Sum) or any(fn_name(a) for a in sp.preorder_traversal(outer)):
        return []
    (v, lo, hi), body = s_.limits[0], s_.function
    pts = [a for a in sp.preorder_traversal(body) if fn_name(a) == "b"]
    if len(pts) != 1:
        return []
    pt = pts[0]
    coeff = body / pt
    s = sp.Symbol("s", integer=True, nonnegative=True)
    index = pt.args[0]
    target = s if end == "start" else n - s
    vs = _solve_linear(index, target, v)
    if vs is None:
        return []
    c_s = (outer * coeff).subs(v, vs)
    ends = [_solve_linear(vs, lo, s), _solve_linear(vs, hi, s)]
    if None in ends:
        return []
    bounds = sorted((sp.expand(e) for e in ends), key=str)
    w_start, w_end = bezier_weights()
    w = (w_start if end == "start" else w_end).subs(_algebra.i, s)
    w = _from_derive(w).subs(S["k"], order)
    diffs = []
    if set(bounds) != {sp.Integer(0), order}:
        diffs.append(
            f"symbolic: `{eq['lhs']}`: summation covers points {bounds}, derived 0..{order}"
        )
    if not symbolic_zero(to_derive(c_s - w)):
        name = "s" if end == "start" else "n - s"
        diffs.append(
            f"symbolic: `{eq['lhs']}`: weight of point {name}: printed {c_s}, "
            f"derived {sp.factor(w)}"
        )
    return diffs


@checker("endpoint_curve", "endpoint_d1", "endpoint_d2", "endpoint_dk", "endpoint_dr_delta")
def check_endpoint_equations(record: dict, ctx: Context) -> Outcome:
    """End points and end derivatives of the curve: symbolically against the closed forms
    (eq. 4 of 001; the Bernstein endpoint weights for 002) and per degree."""
    extra = []
    for eq in record["equations"]:
        extra += symbolic_endpoint(ctx.family.name, eq)
    out = equations_outcome(record, ctx, record["equations"], extra_lines=extra)
    fam = ctx.family.name
    out.checked.insert(
        0,
        "symbolic: vs derived endpoint closed forms"
        if fam == REFERENCE or has_closed_forms(fam)
        else f"symbolic: none ({fam} has no closed end forms in n)",
    )
    return out
