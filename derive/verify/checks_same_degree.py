"""Verify's checkers of the claims only 000 (the same_degree family's paper) makes.

000 prints closed forms no generic rule gives: the three-term Bernstein form of its basis
(eq. 7, and eq. 1 compared with it symbolically), the ratios of its geometric construction
(Prop. 8) and a sufficient G1 condition with a free constant C (Prop. 9, eq. 18) and its
proof. derive/families/same_degree.toml names this module under `checks`; verify/registry.py
imports it after the shared checkers, so a record of another family never reaches these.
"""

from __future__ import annotations

import itertools

import sympy as sp

from .. import algebra as _algebra
from ..families import same_degree as sd
from .checks_core import (
    SLAM,
    Outcome,
    S,
    T,
    checker,
    claim_kind,
)
from .checks_energy import (
    _records_by_id,
)
from .checks_equations import (
    _from_derive,
    _orig,
    check_equations,
)
from .checks_joins import (
    _degree_pairs,
    _join_derived,
    _join_specs,
    _printed_rows,
    _substitute,
    _weights,
    join_per_degree,
)
from .claim_families import (
    _bernstein_mats,
    symbolic_zero,
    to_derive,
)
from .compare import (
    equal,
    show,
)
from .context import (
    Context,
    Tally,
    equations_outcome,
)
from .expr_parse import (
    as_sympy,
    fn_name,
    parse,
)
from .scalar import (
    Sc,
    Undefined,
    _is_zero,
    _NotRational,
    as_fraction,
    cancelled,
)
from .values import (
    v_mul,
)

DEFINITION = sd.DEFINITION
NAME = DEFINITION.name

# Kinds of 000 checked by the shared models, but meaningful for this family only.
checker("basis_split", family=NAME, only="A = (b - B)/(1 - λ) needs λ = 1 to give Bernstein")(
    check_equations
)
checker("geometric_step", family=NAME, only="it is 000's evaluation algorithm (Prop. 8)")(
    check_equations
)


# --------------------------------------------------------------------------- three-term form


def bernstein_terms_of(expr) -> dict:
    """{shift: coefficient} of b_i^n = Σ coeff B_{i+shift}^n from a printed explicit form."""
    e = to_derive(expr)
    terms = _algebra.bernstein_terms(e, _algebra.n)
    return {sp.expand(a - _algebra.i): c for a, c in terms.items()}


def b_function_terms(expr) -> dict:
    """{shift: coefficient} from a printed Σ coeff·B(i + shift, n, t)."""
    out: dict = {}
    for term in sp.Add.make_args(sp.expand(to_derive(expr))):
        fns = [f for f in sp.Mul.make_args(term) if fn_name(f) == "B"]
        if len(fns) != 1:
            raise ValueError(f"term {term} is not a multiple of one B(...)")
        f = fns[0]
        shift = sp.expand(f.args[0] - _algebra.i)  # an index: linear in i
        out[shift] = out.get(shift, 0) + term / f
    return out


def symbolic_three_term(printed: dict) -> list[str]:
    alpha, beta, gamma = sd.three_term_form()
    derived = {sp.Integer(-1): alpha, sp.Integer(0): beta, sp.Integer(1): gamma}
    diffs = []
    for shift in sorted(set(printed) | set(derived), key=str):
        a = printed.get(shift, 0)
        d = derived.get(shift, 0)
        if not symbolic_zero(a - d):
            a_s = sp.factor(sp.combsimp(sp.expand_func(a)))
            diffs.append(
                f"symbolic: coefficient of B(i{_signed(shift)}, n, t): printed {_orig(a_s)}, "
                f"derived {_orig(sp.factor(d))}"
            )
    return diffs


def _signed(s) -> str:
    s = int(s)
    return "" if s == 0 else f" + {s}" if s > 0 else f" - {-s}"


@checker("three_term_bernstein", family=NAME, only="it is 000's closed form of its own basis")
def check_three_term(record: dict, ctx: Context) -> Outcome:
    """Eq. 7: the left side must be b_i^n, and each coefficient of B_{i-1}, B_i, B_{i+1} must
    equal three_term_form() symbolically and, with the papers' binomials, the derived Bernstein
    matrix entry for every n and i (a coefficient beside a B outside 0..n is not looked at)."""
    eq = record["equations"][0]
    lhs, rhs = parse(eq["lhs"]), parse(eq["rhs"])
    diffs = []
    i, n, t = S["i"], S["n"], T
    if lhs != sp.Function("b")(i, n, t):
        diffs.append(f"left side: printed {eq['lhs']}, the derived identity is for b(i, n, t)")
    try:
        printed = b_function_terms(rhs)
    except ValueError as exc:
        return Outcome("mismatch", diffs + [f"right side: {exc}"])
    diffs += symbolic_three_term(printed)
    real = ctx.realiser()
    tally = Tally("per-degree coefficients")
    for deg in ctx.family.degrees:
        mats = _bernstein_mats(NAME, deg)
        for ii in range(deg + 1):
            env = {n: sp.Integer(deg), i: sp.Integer(ii)}
            row = []
            for shift, coeff in printed.items():
                jj = ii + int(shift)
                if not 0 <= jj <= deg:
                    continue
                want = sum((SLAM**p * mats[p][ii][jj] for p in range(len(mats))), Sc.of(0))
                try:
                    got = real(_from_derive(coeff), env)
                except Undefined as exc:
                    row.append(f"coefficient of B({jj}, {deg}, t): printed undefined ({exc})")
                    continue
                if not _is_zero(got - want):
                    row.append(
                        # only the first failing case is shown in full (Tally.lines)
                        "differs"
                        if tally.failures
                        else f"coefficient of B({jj}, {deg}, t): printed {show(got)}, "
                        f"derived {show(want)}"
                    )
            tally.add(env, row)
    diffs += tally.lines()
    checked = ["symbolic: coefficients vs three_term_form()", f"per-degree: {tally.total} cases"]
    return Outcome("mismatch" if diffs else "match", diffs, checked)


@checker("basis_general", family=NAME)
def check_definition(record: dict, ctx: Context) -> Outcome:
    """Eq. 1 for every degree and index, and its Bernstein coefficients against
    three_term_form() symbolically."""
    try:
        extra = symbolic_three_term(bernstein_terms_of(parse(record["equations"][0]["rhs"])))
    except ArithmeticError as exc:
        extra = [f"symbolic: not a combination of degree-n Bernstein functions ({exc})"]
    out = check_equations(record, ctx, extra)
    out.checked.insert(0, "symbolic: Bernstein coefficients vs three_term_form()")
    return out


# --------------------------------------------------------------------------- Prop. 8


@checker("geometric_ratio", family=NAME, only="it is 000's evaluation algorithm (Prop. 8)")
def check_ratio(record: dict, ctx: Context) -> Outcome:
    """A point dividing start→end in ratio p:q is start + p/(p+q)·(end - start)."""
    eqs = []
    for r in record["ratios"]:
        p, q = r["ratio"]
        eqs.append(
            {
                "lhs": r["point"],
                "rhs": f"({r['start']}) + ({p})/(({p}) + ({q}))*(({r['end']}) - ({r['start']}))",
            }
        )
    return equations_outcome(record, ctx, eqs)


# --------------------------------------------------------------------------- Prop. 9


def _corner_positive(expr, syms) -> bool:
    """A rational function, multilinear in the λs, positive on λ ∈ (-2, 1]^k (000's range):
    numerator and denominator (in lowest terms) each keep one sign on the closed box, checked
    at its corners (a zero is allowed only at a corner with some λ = -2, which the range
    excludes), and the two signs agree."""
    try:
        num, den, symbols = as_fraction(as_sympy(expr))
    except _NotRational:
        return False
    num, den = cancelled(num, den)
    if any(
        part.degrees()[pos] > (1 if sym in syms else 0)
        for part in (num, den)
        for pos, sym in enumerate(symbols)
    ):
        return False  # not multilinear in the λs, or it depends on something else
    index = {sym: pos for pos, sym in enumerate(symbols)}
    top_signs = []
    for part in (num, den):
        signs, top = set(), None
        for corner in _corners(len(syms)):
            point = [0] * len(symbols)
            for sym, value in zip(syms, corner, strict=True):
                if sym in index:
                    point[index[sym]] = value
            value = part(*point)
            sign = (value > 0) - (value < 0)
            if all(c == 1 for c in corner):
                top = sign
            if sign:
                signs.add(sign)
        if len(signs) != 1 or not top:
            return False
        top_signs.append(top)
    return top_signs[0] == top_signs[1]


def _corners(k: int):
    ends = (DEFINITION.lo, DEFINITION.hi)  # 000's range ends, integers (FLINT evaluates there)
    assert all(e.denominator == 1 for e in ends)
    return list(itertools.product([int(e) for e in ends], repeat=k))


def _solve_moebius(a, b, x):
    """The one x with a = b(x), b = (p0 + p1·x)/(q0 + q1·x) (a derived G1 weight); None when
    b is not of that form or no single x solves it. (Done by hand because sp.solve imports
    sympy.physics on first use, half a second of a verify worker.)"""
    num, den = (sp.Poly(e, x) for e in sp.fraction(sp.together(b)))
    if num.degree() > 1 or den.degree() > 1:
        return None
    p0, p1 = num.coeff_monomial(1), num.coeff_monomial(x)
    q0, q1 = den.coeff_monomial(1), den.coeff_monomial(x)
    slope = a * q1 - p1
    if _is_zero(slope):
        return None
    sol = sp.cancel((p0 - a * q0) / slope)
    return None if _is_zero(q0 + q1 * sol) else sol


@checker(
    "g1_join", requires=("joins",), family=NAME, fits=lambda record: "convention" not in record
)
def check_join_000(record: dict, ctx: Context) -> Outcome:
    """Eq. (18) of 000: a sufficient G1 condition with a free C > 0. It is the derived G1
    solution (derive/formulas/joins.py, α > 0) exactly when some α > 0 reproduces it for every
    C > 0: α is solved from one weight, the others must then agree, and α must be positive on the
    λ ranges for every degree pair; per degree, p2'(0) = β p1'(1) with β > 0 is checked too."""
    specs = _join_specs(record, ctx)
    (_, n1, l1, pts1), (_, n2, l2, pts2) = specs
    rows = _printed_rows(record, pts2)
    alpha, Csym = S["alpha"], S["C"]
    to_j = {n1: _algebra.n, n2: _algebra.m}
    derived = _join_derived(NAME, "G1")
    diffs = []
    sol = None
    for r, rhs in sorted(rows.items()):
        printed, rest = _weights(rhs, pts1, pts2, n1)
        printed = {(k[0], int(k[1])): as_sympy(v).xreplace(to_j) for k, v in printed.items()}
        want = derived[r]
        for key in sorted(set(printed) | set(want)):
            a, b = printed.get(key, sp.Integer(0)), want.get(key, sp.Integer(0))
            if sol is None and b.has(alpha):
                sol = _solve_moebius(a, b, alpha)
            b = b.xreplace({alpha: sol}) if sol is not None else b
            if not _is_zero(as_sympy(a) - b):
                diffs.append(
                    f"symbolic: {pts2}({r}): weight of {pts1}({n1} - {key[1]}): printed "
                    f"{sp.factor(a)}, derived {sp.factor(b)}"
                )
    if sol is None:
        diffs.append("symbolic: no α reproduces the printed vertices")
    tally = Tally("per-degree α > 0 and p2'(0) = β p1'(1), β > 0")
    real = ctx.realiser()
    lam_syms = [S["lam1"], S["lam2"]]
    for a_, b_ in _degree_pairs(ctx):
        env = {n1: sp.Integer(a_), n2: sp.Integer(b_)}
        row = []
        if sol is not None:
            ac = as_sympy(sol * Csym).xreplace({_algebra.n: a_, _algebra.m: b_})
            if not _corner_positive(ac, lam_syms):
                row.append(f"α·C = {sp.factor(ac)} is not positive on the λ ranges")
        sub = {(pts2, r): real(rhs, env) for r, rhs in rows.items()}
        d1 = _substitute(real(parse("Subs(Derivative(p2(t), t), t, 0)"), env), sub)
        e1 = real(parse("Subs(Derivative(p1(t), t), t, 1)"), env)
        p0 = _substitute(real(parse("p2(0)"), env), sub)
        if not equal(p0, real(parse("p1(1)"), env)):
            row.append("p2(0) != p1(1)")
        key = next(k for k in sorted(e1.terms) if not e1.terms[k].is_zero())
        beta = d1.terms.get(key, Sc.of(0)) / e1.terms[key]
        if not equal(d1, v_mul(beta, e1)):
            row.append("p2'(0) is not a multiple of p1'(1)")
        elif not _corner_positive(beta.to_expr() / Csym, lam_syms):
            row.append(f"β = {sp.factor(beta.to_expr())} is not positive for C > 0")
        tally.add(env, row)
    diffs += tally.lines()
    checked = ["symbolic: weights vs joins.solve() at the α solved", f"per-degree: {tally.total}"]
    return Outcome("mismatch" if diffs else "match", diffs, checked)


@checker("g1_join_ratio", requires=("joins",), family=NAME, only="it is 000's proof of Prop. 9")
def check_join_ratio(record: dict, ctx: Context) -> Outcome:
    """Proof of Prop. 9: the end values and derivatives (per degree pair, with the curves of
    eq. 17), and p2'(0) = β p1'(1) with the printed β once eq. (18) holds (its vertices, from
    the same_degree.g1_join record, substituted)."""
    specs = _join_specs(record, ctx)
    pts2 = specs[1][3]
    g1 = next(
        r
        for r in _records_by_id(None).values()
        if claim_kind(r["claim"]) == "g1_join" and r["family"] == NAME
    )
    rows = _printed_rows(g1, pts2)
    beta = S["beta"]
    defs = {parse(e["lhs"]): parse(e["rhs"]) for e in record["equations"]}
    conditions = []
    for eq in record["equations"]:
        lhs, rhs = parse(eq["lhs"]), parse(eq["rhs"])
        if lhs == beta:
            continue  # the definition of β, used below
        conditions.append(
            {
                "lhs": str(lhs.xreplace({beta: defs.get(beta, beta)})),
                "rhs": str(rhs.xreplace({beta: defs.get(beta, beta)})),
            }
        )
    tally = join_per_degree(record, ctx, rows, specs, conditions, "equations")
    diffs = tally.lines()
    return Outcome("mismatch" if diffs else "match", diffs, [f"per-degree: {tally.total} pairs"])
