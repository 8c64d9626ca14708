"""Checkers of the classical notes' claims: the cubic matrix, the Bernstein maximum, the
worked subdivision and segment examples, the convexity example.
"""

from __future__ import annotations

from fractions import Fraction
from functools import lru_cache

import flint
import sympy as sp
from sympy.solvers.inequalities import reduce_rational_inequalities

from .. import algebra as _algebra
from ..algebra import bernstein as bz
from .checks_core import (
    Outcome,
    S,
    T,
    checker,
)
from .compare import (
    compare,
)
from .context import (
    Context,
    Tally,
)
from .expr_parse import (
    parse,
)
from .realiser import (
    Realiser,
)
from .scalar import (
    Sc,
    _is_zero,
)
from .values import (
    v_add,
    v_mul,
)

# --------------------------------------------------------------------------- geometric ratio


# --------------------------------------------------------------------------- cubic matrix


@checker("cubic_matrix")
def check_cubic_matrix(record: dict, ctx: Context) -> Outcome:
    n = int(record["n"])
    row = [parse(x) for x in record["row"]]
    pts = [parse(x) for x in record["points"]]
    mat = record["matrix"]
    real = ctx.realiser()
    env = {S["n"]: sp.Integer(n)}
    printed = sp.Integer(0)
    for r, rv in enumerate(row):
        for c, pv in enumerate(pts):
            printed = v_add(printed, v_mul(real(rv, env) * mat[r][c], real(pv, env)))
    derived = real(parse("p(t)"), env)
    diffs = compare(printed, derived)
    if (
        diffs
        and all(row[e] == T**e for e in range(n + 1))
        and all(pts[c] == sp.Function("b")(c) for c in range(n + 1))
    ):
        power = _algebra.bernstein_power_matrix(n)  # power[j][e]: coefficient of t^e in B_j
        diffs = [
            f"entry [{e}][{j}] (t^{e}, b{j}): printed {mat[e][j]}, derived {power[j][e]}"
            for e in range(n + 1)
            for j in range(n + 1)
            if Fraction(mat[e][j]) != power[j][e]
        ]
    return Outcome("mismatch" if diffs else "match", diffs, ["p(t) = row·M·points vs Σ b_j B_j"])


# --------------------------------------------------------------------------- Bernstein maximum


@checker("bernstein_maximum")
def check_maximum(record: dict, ctx: Context) -> Outcome:
    func = parse(record["function"])
    arg = parse(record["argmax"])
    var = S[record.get("variable", "u")]
    real = ctx.realiser()
    tally = Tally("per-degree")
    for deg in ctx.family.degrees:
        for ii in range(deg + 1):
            env = {S["n"]: sp.Integer(deg), S["i"]: sp.Integer(ii)}
            value = real(func, env)
            a = sp.Rational(str(real(arg, env).ground()))
            f = value.univariate(var)
            if f is not None:  # exact in FLINT when every critical point is rational
                f = flint.fmpq_poly([flint.fmpq(c.numerator, c.denominator) for c in f])
                roots = _rational_roots(f.derivative())
            if f is None or roots is None:
                f = sp.Poly(value.to_expr(), var)
                roots = f.diff(var).real_roots()
            cands = {sp.Integer(0), sp.Integer(1)} | {r for r in roots if 0 <= r <= 1}
            at_value = {c: _poly_at(f, c) for c in cands}
            best = max(at_value.values())
            row = []
            if not (0 <= a <= 1) or _poly_at(f, a) != best:
                at = sorted(c for c in cands if at_value[c] == best)
                row.append(f"printed maximum at {a}, derived at {', '.join(map(str, at))}")
            tally.add(env, row)
    return Outcome(
        "mismatch" if tally.failures else "match",
        tally.lines(),
        [f"per-degree: {tally.total} cases"],
    )


def _rational_roots(poly) -> list[sp.Rational] | None:
    """The real roots of an fmpq_poly when all of them are rational (FLINT factors it), else
    None."""
    if poly.degree() < 1:
        return []
    roots = []
    for factor, _ in poly.factor()[1]:
        if factor.degree() != 1:
            return None
        b, a = factor.coeffs()
        root = -flint.fmpq(b) / a
        roots.append(sp.Rational(int(root.p), int(root.q)))
    return roots


def _poly_at(f, x):
    if isinstance(f, sp.Poly):
        return f.eval(x)
    y = f(flint.fmpq(int(x.p), int(x.q)))
    return sp.Rational(int(y.p), int(y.q))


# --------------------------------------------------------------------------- worked examples


def _frac(s) -> Fraction:
    e = parse(str(s))
    if not e.is_Rational:
        raise ValueError(f"{s!r} is not an exact number")
    return Fraction(int(e.p), int(e.q))


def _pts(rows) -> list[tuple[Fraction, ...]]:
    return [tuple(_frac(x) for x in row) for row in rows]


def _pt_str(p) -> str:
    return "(" + ", ".join(str(x) for x in p) + ")"


def decasteljau_levels(points, t) -> list[list[tuple]]:
    """The de Casteljau triangle (the notes' recursion (*)), exactly."""
    rows = [list(points)]
    while len(rows[-1]) > 1:
        prev = rows[-1]
        rows.append(
            [
                tuple((1 - t) * a + t * b for a, b in zip(p, q, strict=True))
                for p, q in zip(prev, prev[1:], strict=False)
            ]
        )
    return rows


def reparametrised(points, a, b) -> list[tuple]:
    """Control points of the piece u -> p(a + (b - a) u), from the power form of
    p(a + (b-a)u) and derive's power→Bernstein matrix (independent of de Casteljau)."""
    n = len(points) - 1
    u = sp.Symbol("u")
    conv = _algebra.power_to_bernstein_matrix(n)
    out_coords = []
    for c in range(len(points[0])):
        expr = sum(
            sp.Rational(points[i][c].numerator, points[i][c].denominator)
            * bz.bernstein_basis(
                n,
                i,
                sp.Rational(a.numerator, a.denominator)
                + sp.Rational((b - a).numerator, (b - a).denominator) * u,
            )
            for i in range(n + 1)
        )
        coeffs = sp.Poly(sp.expand(expr), u).all_coeffs()[::-1]
        coeffs += [0] * (n + 1 - len(coeffs))
        power = [Fraction(int(sp.Rational(x).p), int(sp.Rational(x).q)) for x in coeffs]
        out_coords.append([sum(power[e] * conv[e][j] for e in range(n + 1)) for j in range(n + 1)])
    return [tuple(col[j] for col in out_coords) for j in range(n + 1)]


def _compare_points(label, printed, derived) -> list[str]:
    if len(printed) != len(derived):
        return [f"{label}: printed {len(printed)} points, derived {len(derived)}"]
    return [
        f"{label}[{j}]: printed {_pt_str(p)}, derived {_pt_str(d)}"
        for j, (p, d) in enumerate(zip(printed, derived, strict=True))
        if p != d
    ]


def _compare_levels(label, printed_levels, points, t) -> list[str]:
    derived = decasteljau_levels(points, t)
    out = []
    if len(printed_levels) != len(derived):
        out.append(f"{label}: printed {len(printed_levels)} levels, derived {len(derived)}")
    for k, (p, d) in enumerate(zip(printed_levels, derived, strict=False)):
        out += _compare_points(f"{label}[{k}]", _pts(p), d)
    return out


@checker("subdivision_example")
def check_subdivision_example(record: dict, ctx: Context) -> Outcome:
    pts = _pts(record["control_points"])
    t = _frac(record["parameter"])
    diffs = []
    if len(pts) != int(record["degree"]) + 1:
        diffs.append(f"degree {record['degree']} but {len(pts)} control points")
    diffs += _compare_levels("levels", record["levels"], pts, t)
    diffs += _compare_points("left", _pts(record["left"]), reparametrised(pts, Fraction(0), t))
    diffs += _compare_points("right", _pts(record["right"]), reparametrised(pts, t, Fraction(1)))
    checked = ["levels vs de Casteljau", "pieces vs reparametrisation p(t* u), p(t* + (1-t*)u)"]
    return Outcome("mismatch" if diffs else "match", diffs, checked)


@checker("segment_example")
def check_segment_example(record: dict, ctx: Context) -> Outcome:
    pts = _pts(record["control_points"])
    t1, t2 = _frac(record["t1"]), _frac(record["t2"])
    diffs = []
    current = pts
    lo, hi = Fraction(0), Fraction(1)  # the original parameter interval of `current`
    for name in ("step1", "step2"):
        step = record[name]
        par = _frac(step["parameter"])
        if "parameter_printed" in step and _frac(step["parameter_printed"]) != par:
            diffs.append(f"{name}.parameter_printed {step['parameter_printed']} != {par}")
        diffs += _compare_points(f"{name}.control_points", _pts(step["control_points"]), current)
        diffs += _compare_levels(f"{name}.levels", step["levels"], current, par)
        flat = sorted(p for level in _pts_levels(step["levels"]) for p in level)
        if sorted(_pts(step["printed_sequence"])) != flat:
            diffs.append(f"{name}.printed_sequence is not the points of {name}.levels")
        # the split point in the original parameter, and the piece kept
        split = lo + (hi - lo) * par
        piece = (lo, split) if step["keep"] == "left" else (split, hi)
        derived = reparametrised(pts, *piece)
        diffs += _compare_points(f"{name}.result", _pts(step["result"]), derived)
        current, (lo, hi) = derived, piece
    if (lo, hi) != (t1, t2):
        diffs.append(f"the two steps keep [{lo}, {hi}], not [t1, t2] = [{t1}, {t2}]")
    diffs += _compare_points("result", _pts(record["result"]), reparametrised(pts, t1, t2))
    checked = ["each step's levels vs de Casteljau", "pieces vs reparametrisation"]
    return Outcome("mismatch" if diffs else "match", diffs, checked)


def _pts_levels(levels):
    return [_pts(level) for level in levels]


# --------------------------------------------------------------------------- convexity example


@checker("convexity_example")
def check_convexity(record: dict, ctx: Context) -> Outcome:
    """Quartic with a free ω: x(t), y(x), y''(x) against the derived curve; the conclusions
    against the ω-sets where the derived y'' keeps its sign / changes sign twice on [0, 1]
    (`convex`, `two_inflections`: equal sets, the printed pair being a dichotomy) and where the
    control polygon is not convex but the curve is (`concave_polygon_convex_curve`: printed as
    an example range, so it must lie inside the derived set)."""
    omega, x = S["omega"], S["x"]
    coords = [[parse(str(c)) for c in row] for row in record["control_points"]]
    n = int(record["degree"])
    if len(coords) != n + 1:
        return Outcome("mismatch", [f"degree {n} but {len(coords)} control points"])
    comp = [sum(coords[i][c] * bz.bernstein_basis(n, i, T) for i in range(n + 1)) for c in (0, 1)]
    xt, yt = (sp.expand(c) for c in comp)
    derived = {
        "x": xt,
        "y": sp.expand(yt.subs(T, x)),
        "y2": sp.expand(sp.diff(yt, T, 2).subs(T, x)),
    }
    diffs = []
    if sp.expand(xt - T) != 0:
        diffs.append(f"x(t) is {xt}, not t: y cannot be written as a function of x = t")
    real = Realiser({"y": lambda a, env: Sc.of(derived["y"].subs(x, a[0].to_expr()))})
    for pos, eq in enumerate(record["equations"]):
        lhs, rhs = parse(eq["lhs"]), parse(eq["rhs"])
        want = xt if lhs == x else real(lhs, {}).to_expr()
        got = real(rhs, {}).to_expr()
        if not _is_zero(got - want):
            diffs.append(
                f"equation {pos + 1} `{eq['lhs']} = …`: printed {sp.factor(got)}, derived "
                f"{sp.factor(want)} (difference {sp.factor(got - want)})"
            )
    y2 = derived["y2"]
    convex_set = _omega_set(lambda w: _sign_changes(y2.subs(omega, w), x) == 0, [y2], x, omega)
    two_set = _omega_set(lambda w: _sign_changes(y2.subs(omega, w), x) == 2, [y2], x, omega)
    turns = _turns(coords)
    poly_convex = _omega_set(
        lambda w: (
            all(c.subs(omega, w) >= 0 for c in turns) or all(c.subs(omega, w) <= 0 for c in turns)
        ),
        turns,
        None,
        omega,
    )
    concave_convex = sp.Intersection(sp.Complement(sp.S.Reals, poly_convex), convex_set)
    concl = record.get("conclusions", {})
    for key, want, mode in (
        ("convex", convex_set, "equal"),
        ("two_inflections", two_set, "equal"),
        ("concave_polygon_convex_curve", concave_convex, "subset"),
    ):
        if key not in concl:
            continue
        got = _condition_set(concl[key])
        ok = got == want if mode == "equal" else got.is_subset(want)
        if not ok:
            rel = "is" if mode == "equal" else "lies inside"
            diffs.append(f"conclusion {key}: printed omega in {got}, derived set {rel} {want}")
    checked = ["x, y, y'' vs the derived quartic", "conclusions vs derived ω-sets"]
    return Outcome("mismatch" if diffs else "match", diffs, checked)


@lru_cache(maxsize=64)
def _condition_set(text: str):
    """A printed condition on ω as a set (the record and its erratum share conclusions)."""
    return _as_set(parse(text))


def _as_set(cond):
    """cond.as_set(), with each polynomial inequality in one variable solved as a rational
    inequality: Relational.as_set first asks whether the relation is periodic, which calls
    simplify, whose first use imports sympy.physics (half a second of a worker)."""
    if isinstance(cond, sp.And):
        return sp.Intersection(*(_as_set(a) for a in cond.args))
    if isinstance(cond, sp.Or):
        return sp.Union(*(_as_set(a) for a in cond.args))
    if isinstance(cond, sp.Not):
        return sp.Complement(sp.S.Reals, _as_set(cond.args[0]))
    if isinstance(cond, sp.core.relational.Relational) and len(cond.free_symbols) == 1:
        (var,) = cond.free_symbols
        if all(side.is_polynomial(var) for side in cond.args):
            return reduce_rational_inequalities([[cond]], var, relational=False)
    return cond.as_set()


def _turns(coords):
    out = []
    for a, b, c in zip(coords, coords[1:], coords[2:], strict=False):
        e1 = (b[0] - a[0], b[1] - a[1])
        e2 = (c[0] - b[0], c[1] - b[1])
        out.append(sp.expand(e1[0] * e2[1] - e1[1] * e2[0]))
    return out


def _sign_changes(poly_expr, x) -> int:
    p = sp.Poly(sp.expand(poly_expr), x)
    if p.is_zero:
        return 0
    changes = 0
    for factor, mult in p.sqf_list()[1]:
        if mult % 2:
            changes += sum(1 for r in factor.real_roots() if 0 < r < 1)
    return changes


def _omega_set(pred, exprs, x, omega):
    """The set of ω where pred holds, from exact samples between the critical values."""
    crit = set()
    for e in exprs:
        e = sp.expand(e)
        polys = [e] if x is None else [e.subs(x, 0), e.subs(x, 1), sp.discriminant(e, x)]
        if x is not None:
            polys.append(sp.Poly(e, x).LC())
        for p in polys:
            p = sp.Poly(p, omega)
            if p.degree() > 0:
                crit |= {r for r in p.real_roots()}
    crit = sorted(crit)
    pieces = []
    if not crit:
        return sp.S.Reals if pred(sp.Integer(0)) else sp.S.EmptySet
    bounds = [-sp.oo, *crit, sp.oo]
    for a, b in zip(bounds, bounds[1:], strict=False):
        mid = a + 1 if b == sp.oo else b - 1 if a == -sp.oo else (a + b) / 2
        if pred(mid):
            pieces.append(sp.Interval.open(a, b))
    pieces += [sp.FiniteSet(c) for c in crit if pred(c)]
    return sp.Union(*pieces) if pieces else sp.S.EmptySet
