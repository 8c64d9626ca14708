"""Checkers of energy claims (issue 3): the energy equations, matrices, the optimal λ
formula and worked examples, against derive/formulas/energy.py.
"""

from __future__ import annotations

from fractions import Fraction
from functools import cache

import sympy as sp

from ..formulas import properties
from .checks_core import (
    LAM,
    SLAM,
    Outcome,
    S,
    checker,
    derive_module,
    is_param,
)
from .checks_examples import (
    _frac,
    _pts,
)
from .claim_families import (
    FAMILIES,
)
from .compare import (
    _proportional_pairs,
    compare,
    v_is_zero,
)
from .context import (
    Context,
    Tally,
    _int,
    check_equation,
    instances,
)
from .expr_parse import (
    parse,
)
from .index import (
    records_by_id,
)
from .scalar import (
    Sc,
    Undefined,
)
from .values import (
    Form,
    Ratio,
    v_add,
    v_apply,
    v_mul,
    v_neg,
)

# --------------------------------------------------------------------------- energy (issue 3)


def _energy():
    return derive_module("energy")


def quad_form(matrix, points="P") -> Form:
    """Dᵀ M D = Σ_{a,b} M[a][b] P_a·P_b, read as printed (README: not symmetrised)."""
    terms: dict = {}
    for a, row in enumerate(matrix):
        for b, v in enumerate(row):
            if v:
                key = tuple(sorted(((points, a), (points, b))))
                terms[key] = terms.get(key, Sc.of(0)) + Sc.of(Fraction(str(v)))
    return Form(terms)


def _energy_degree(family: str, n: int) -> int:
    if n not in FAMILIES[family].degrees:
        degrees = FAMILIES[family].degrees
        raise Undefined(f"{family} degree {n} outside {degrees.start}..{degrees.stop - 1}")
    return n


@cache
def _published(family: str, n: int, k: int):
    c, X, Y = _energy().published_form(family, _energy_degree(family, n), k)
    return Fraction(c), X, Y


@cache
def _energy_forms(family: str, n: int, k: int):
    return _energy().energy_forms(family, _energy_degree(family, n), k)


@cache
def _energy_quad(family: str, n: int, k: int, points: str) -> Form:
    """E_k(λ) = ∫f·f - 2λ∫f·g + λ²∫g·g from energy_forms(), as a quadratic form in the points."""
    forms = _energy_forms(family, n, k)
    out = Sc.of(0)
    for key, weight in (("ff", Sc.of(1)), ("fg", SLAM * -2), ("gg", SLAM**2)):
        scale, U = forms[key]
        out = v_add(out, v_mul(weight * Sc.of(Fraction(scale)), quad_form(U, points)))
    return out


def energy_model(ctx: Context):
    def E(a, env):
        e = _energy_quad(ctx.family.name, ctx.degree(env), _int(a[0]), ctx.family.points)
        if len(a) > 1 and not is_param(a[1], LAM):
            e = v_apply(e, lambda s: s.subs(LAM, a[1]))
        return e

    return E


def lambda_star(family: str, n: int, k: int, points: str) -> Ratio:
    c, X, Y = _published(family, n, k)
    return Ratio(v_mul(Sc.of(Fraction(c)), quad_form(X, points)), quad_form(Y, points))


@checker(
    "energy_definition",
    "energy_functional",
    "energy_lambda",
    requires=("energy",),
)
def check_energy_equations(record: dict, ctx: Context) -> Outcome:
    """E_k, its quadratic form in λ and the stationary λ, for every n and k = 1, 2, 3, with
    E(k[, λ]) from energy_forms(): a left side `lam` is the derived minimiser
    c·DᵀXD/DᵀYD of published_form(), and `dE/dλ = 0` is checked at that minimiser."""
    real = ctx.realiser({"E": energy_model(ctx)})
    tallies: list[Tally] = []
    for pos, eq in enumerate(record["equations"]):
        lhs, rhs = parse(eq["lhs"]), parse(eq["rhs"])
        label = f"equation {pos + 1} `{eq['lhs']} = …`"
        if lhs == LAM or (rhs == 0 and lhs.has(sp.Derivative) and LAM in lhs.free_symbols):
            tally = Tally(label)
            for env in instances(record, ctx, (lhs, rhs, parse("p(t)")), eq):
                n, k = int(env[S["n"]]), int(env[S["k"]])
                try:
                    star = lambda_star(ctx.family.name, n, k, ctx.family.points)
                except ZeroDivisionError as exc:  # Y = 0: E_k does not depend on λ
                    tally.add(env, [f"{exc}: no λ minimises E_{k}"])
                    continue
                if lhs == LAM:
                    diffs = compare(real(rhs, env), star)
                else:  # a + λ b = 0 at λ = num/den  <=>  a·den + b·num = 0
                    val = real(lhs, env)
                    a = v_apply(val, lambda s: s.subs(LAM, 0))
                    b = v_apply(val, lambda s: s.diff(LAM))
                    # a + λ b = 0 at λ = num/den: b = μ·den and a = -μ·num suffices (cheap);
                    # otherwise a·den + b·num = 0 as a quartic form decides
                    ok = _proportional_pairs(
                        Ratio(v_neg(a), b), Ratio(star.num, star.den)
                    ) or v_is_zero(v_add(v_mul(a, star.den), v_mul(b, star.num)))
                    diffs = [] if ok else ["dE/dλ does not vanish at the derived minimiser"]
                tally.add(env, diffs)
            tallies.append(tally)
        else:
            check_equation(record, ctx, eq, real, f"equation {pos + 1}", tallies)
    diffs = [line for t in tallies for line in t.lines()]
    checked = [f"{t.label.split(' `')[0]}: {t.total} cases" for t in tallies]
    return Outcome("mismatch" if diffs else "match", diffs, checked)


def _records_by_id(record):
    return records_by_id()


def _normalised(matrix):
    """(q, primitive matrix with first nonzero diagonal entry positive), matrix = q·primitive."""
    from math import gcd

    flat = [int(v) for row in matrix for v in row]
    g = 0
    for v in flat:
        g = gcd(g, v)
    if g == 0:
        return Fraction(0), matrix
    diag = [int(matrix[a][a]) for a in range(len(matrix)) if int(matrix[a][a])]
    sign = -1 if diag and diag[0] < 0 else 1
    return Fraction(sign * g), tuple(tuple(int(v) // (sign * g) for v in row) for row in matrix)


@checker("energy_matrix", requires=("energy",))
def check_energy_matrix(record: dict, ctx: Context) -> Outcome:
    """A printed X_n^k or Y_n^k, entry by entry, against published_form()."""
    n, k, family = int(record["n"]), int(record["k"]), ctx.family.name
    # X and Y straight from the forms: they exist even where Y = 0 (E_k does not depend on λ,
    # e.g. E_3 of a quadratic basis), where published_form() has no scale c = s_fg / s_gg
    forms = _energy_forms(family, n, k)
    derived = forms["fg" if record["name"] == "X" else "gg"][1]
    printed = record["matrix"]
    diffs = []
    if len(printed) != n + 1 or any(len(row) != n + 1 for row in printed):
        return Outcome("mismatch", [f"printed shape is not {n + 1}×{n + 1}"])
    for a in range(n + 1):
        for b in range(n + 1):
            if int(printed[a][b]) != int(derived[a][b]):
                diffs.append(f"entry [{a}][{b}]: printed {printed[a][b]}, derived {derived[a][b]}")
    if diffs:
        q, prim = _normalised(printed)
        if prim == tuple(tuple(int(v) for v in row) for row in derived):
            diffs = [f"printed matrix = {q} × derived (entries otherwise proportional)"]
    scale = _frac(record["scale"])
    checked = [f"entries vs published_form({family!r}, {n}, {k})"]
    return Outcome("mismatch" if diffs else "match", diffs, checked + [f"scale {scale}"])


@checker("energy_lambda_nk", requires=("energy",))
def check_energy_formula(record: dict, ctx: Context) -> Outcome:
    """λ = scale·DᵀXD/DᵀYD with the printed scale and matrices, against the derived minimiser
    c·DᵀX'D/DᵀY'D (equal as rational functions of the control points)."""
    n, k = int(record["n"]), int(record["k"])
    by_id = _records_by_id(record)
    Xp = by_id[record["numerator"]]["matrix"]
    Yp = by_id[record["denominator"]]["matrix"]
    scale = _frac(record["scale"])
    pts = [parse(p) for p in record["vector"]]
    if pts != [sp.Function("P")(a) for a in range(n + 1)]:
        return Outcome("mismatch", [f"vector {record['vector']} is not P(0)..P({n})"])
    printed = Ratio(v_mul(Sc.of(Fraction(scale)), quad_form(Xp)), quad_form(Yp))
    try:
        c, X, Y = _published(ctx.family.name, n, k)
    except ZeroDivisionError as exc:  # Y = 0: E_k does not depend on λ
        return Outcome("mismatch", [f"{exc}: no λ minimises E_{k}"])
    diffs = compare(printed, lambda_star(ctx.family.name, n, k, "P"))
    if diffs:
        qx, px = _normalised(Xp)
        qy, py = _normalised(Yp)
        diffs = []
        implied = scale * qx / qy if qy else None
        if implied is not None and implied != c:
            diffs.append(
                f"scale: printed {scale} (implied {implied} for primitive matrices), derived {c}"
            )
        for name, prim, der in (("X", px, X), ("Y", py, Y)):
            bad = [
                f"{name}[{a}][{b}]: printed {prim[a][b]}, derived {der[a][b]}"
                for a in range(n + 1)
                for b in range(n + 1)
                if int(prim[a][b]) != int(der[a][b])
            ]
            diffs += bad
    return Outcome("mismatch" if diffs else "match", diffs, [f"λ vs published_form({n}, {k})"])


@checker("energy_example", requires=("energy",))
def check_energy_example(record: dict, ctx: Context) -> Outcome:
    pts = _pts(record["control_points"])
    n, k = int(record["n"]), int(record["k"])
    diffs = []
    if len(pts) != n + 1:
        diffs.append(f"{len(pts)} control points for degree {n}")
    derived = Fraction(_energy().optimal_lambda_exact(pts, k, family=ctx.family.name))
    printed = _frac(record["lambda"])
    if printed != derived:
        diffs.append(f"λ: printed {printed}, derived {derived}")
    checked = [f"λ vs optimal_lambda_exact(points, k={k})"]
    if not diffs:
        caveat = _range_caveat(record, ctx, pts, k, derived)
        if caveat:
            return Outcome("caveat", caveat, [*checked, "λ against the stated parameter range"])
    return Outcome("mismatch" if diffs else "match", diffs, checked)


def _range_caveat(record: dict, ctx: Context, pts, k: int, lam: Fraction) -> list[str]:
    """Why an exactly right λ* is still not the answer the example states: it lies outside
    the paper's parameter range, where E_k (a quadratic in λ) has no minimiser at all."""
    family = ctx.family.name
    text = record.get("parameter_range")
    iv = properties.Interval.parse(text) if text else properties.FAMILY_RANGES[family]
    if iv.contains(lam):
        return []
    forms = _energy().energy_forms(family, len(pts) - 1, k)
    scale, gg = forms["gg"]
    leading = scale * _energy()._quadratic(gg, pts)  # E_k(λ) = ... + leading·λ², exactly
    side = iv.lo if lam <= iv.lo else iv.hi
    closed = (not iv.lo_open) if side == iv.lo else (not iv.hi_open)
    lines = [
        f"λ* = {lam} (≈ {float(lam):.6g}) is the exact minimiser of E_{k}, but it lies outside "
        f"the stated range {iv}",
        f"E_{k}(λ) = E_{k}(λ*) + {leading}·(λ - λ*)² is convex, so on {iv} it is smallest at "
        f"the end λ = {side}"
        + (
            ""
            if closed
            else f", which the range excludes: E_{k} has NO minimum on {iv} "
            f"(its infimum is approached as λ → {side})"
        ),
    ]
    bad = properties.nonnegative(family, len(pts) - 1, properties.Interval(lam, lam))
    if bad is not None:
        lines.append(f"at λ* the basis is not non-negative ({bad.text}): no convex-hull property")
    return lines
