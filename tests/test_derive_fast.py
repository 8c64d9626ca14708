"""The fast paths of `derive --check` (issue #29): FLINT rational functions in the family
engine and the joins solve, FLINT factoring in SymPy's form, FLINT Taylor shifts, and the
joins derived in a second process. Each must give exactly what the SymPy path gave (the
printed text of generated/ depends on it), and the second process must give the same bytes
and the same failures as a serial run."""

from __future__ import annotations

import importlib
from fractions import Fraction
from math import comb

import pytest
import sympy as sp
from conftest import ROOT
from hypothesis import given, settings
from hypothesis import strategies as st
from sympy.polys.fields import field
from sympy.polys.rings import ring
from test_derive import assert_check_passes

from lambda_bezier import _derive_runner

pytestmark = pytest.mark.skipif(
    not (ROOT / "derive" / "algebra" / "ratfunc.py").is_file(), reason="needs the source checkout"
)


def _derive_module(name: str):
    return importlib.import_module(f"{_derive_runner.load_derive(ROOT).__name__}.{name}")


SYMS = sp.symbols("n m lam1 lam2")

rationals = st.fractions(min_value=-6, max_value=6, max_denominator=5)
monomials = st.tuples(*(st.integers(0, 2) for _ in SYMS))
polys = st.dictionaries(monomials, rationals, min_size=1, max_size=4)


def _expr(terms: dict) -> sp.Expr:
    return sp.Add(
        *(
            sp.Rational(c.numerator, c.denominator)
            * sp.Mul(*(s**e for s, e in zip(SYMS, m, strict=True)))
            for m, c in terms.items()
        )
    )


@settings(max_examples=30)
@given(polys, polys, polys, st.integers(-2, 2))
def test_rational_functions_in_sympys_normal_form(a, b, c, power):
    """Any sum/product/quotient/power, computed in FLINT and handed to SymPy's field, is the
    element SymPy's own arithmetic gives: the same numerator and denominator (so the same
    printed text), not only an equal value."""
    ratfunc = _derive_module("algebra.ratfunc")
    qq_field = field(list(SYMS), sp.QQ)[0]
    fa, fb, fc = (ratfunc.from_expr(_expr(x), SYMS) for x in (a, b, c))
    sa, sb, sc = (qq_field(_expr(x)) for x in (a, b, c))
    base = sa * sb - sc
    divisor = sb if sb != 0 else sa + 1
    if (base == 0 and power <= 0) or divisor == 0:  # 0**0 and 0**-k: SymPy raises
        return
    got = (fa * fb - fc) ** power / (fb if sb != 0 else fa + 1) + 3
    want = qq_field(base**power / divisor + 3)  # SymPy may leave a zero as an int
    mine = ratfunc.to_sympy_field(got, qq_field)
    assert mine == want
    assert (mine.numer, mine.denom) == (want.numer, want.denom)
    assert str(mine.as_expr()) == str(want.as_expr())


@settings(max_examples=30)
@given(polys, polys, st.booleans())
def test_factored_is_sympys_factor_list(a, b, negate):
    """FLINT's factorisation, printed, is SymPy's factor_list of the same polynomial."""
    ratfunc = _derive_module("algebra.ratfunc")
    qq_ring = ring(list(SYMS), sp.QQ)[0]
    p = qq_ring(_expr(a)) * qq_ring(_expr(b)) * (-1 if negate else 1)
    if not p:
        return
    const, factors = p.factor_list()
    want = sp.Mul(qq_ring.domain.to_sympy(const), *(f.as_expr() ** k for f, k in factors))
    terms = {m: Fraction(int(c.numerator), int(c.denominator)) for m, c in p.terms()}
    got = ratfunc.factored(terms, SYMS)
    assert got == want
    assert str(got) == str(want)


def test_rational_function_arithmetic_is_exact():
    ratfunc = _derive_module("algebra.ratfunc")
    x = ratfunc.RationalFunction.variable(2, 0)
    y = ratfunc.RationalFunction.variable(2, 1)
    value = (x**2 - y**2) / (x - y)  # cancels to x + y
    assert value.is_polynomial
    assert value.terms() == {(1, 0): Fraction(1), (0, 1): Fraction(1)}
    assert x / x == 1 and (x - x) == 0 and 1 / (x + 1) * (x + 1) == 1
    assert ((x + 1) ** -2).as_pair() == ({(0, 0): Fraction(1)}, {(2, 0): 1, (1, 0): 2, (0, 0): 1})
    with pytest.raises(ZeroDivisionError):
        _ = x / (y - y)
    with pytest.raises(ZeroDivisionError):
        _ = (x - x) ** -1
    with pytest.raises(ValueError, match="not a rational function"):
        ratfunc.from_expr(sp.sqrt(SYMS[0]), SYMS)


@given(
    st.lists(rationals, min_size=1, max_size=14),
    st.fractions(min_value=-3, max_value=3, max_denominator=4),
)
def test_centred_row_is_the_taylor_shift(row, centre):
    """The FLINT Taylor shift against the binomial sum it replaced."""
    core = _derive_module("algebra.core")
    size = len(row)
    want = tuple(
        sum((row[q] * comb(q, e) * centre ** (q - e) for q in range(e, size)), Fraction(0))
        for e in range(size)
    )
    got = core.centred_row(tuple(row), centre)
    assert got == want
    assert all(type(v) is Fraction for v in got)


def test_bernstein_poly_is_sympys_arithmetic_on_the_axiom():
    """The FLINT product in bernstein_poly against SymPy's own Poly arithmetic on the axiom:
    the same Poly (generators, domain, representation), inside and outside 0..degree."""
    bern = _derive_module("algebra.bernstein")
    for degree in range(16):
        for index in range(-1, degree + 2):
            got = bern.bernstein_poly(degree, index)
            want = bern.bernstein_basis(degree, index, bern.X)
            assert got == want and type(got) is type(want), (degree, index)
            if isinstance(want, sp.Poly):
                assert (got.gens, got.domain, got.rep) == (want.gens, want.domain, want.rep)


def test_linear_in_lambda():
    core = _derive_module("algebra.core")
    lam, n, i = core.lam, core.n, core.i
    assert core.linear_in_lambda(lam * n / (n + 1) + 3)
    assert core.linear_in_lambda(lam * (lam + 1) / (lam + 1))  # cancelled: linear
    assert core.linear_in_lambda(sp.binomial(n, i) * lam)  # SymPy's path
    assert core.linear_in_lambda(sp.Integer(0))
    assert not core.linear_in_lambda(lam**2 * n)
    assert not core.linear_in_lambda(lam / (lam + n))
    assert not core.linear_in_lambda(sp.binomial(n, i) * lam**2)


def test_endpoint_weight_check_catches_a_wrong_closed_form():
    bernstein = _derive_module("algebra.bernstein")
    start, end = bernstein.endpoint_weights()
    bernstein.check_endpoint_weights(start, end, range(1, 9))
    for wrong in (
        (start * 2, end),
        (start, end.subs(bernstein.i, bernstein.i + 1)),
        (start.subs(bernstein.n, bernstein.n + 1), end),
    ):
        with pytest.raises(AssertionError, match="endpoint weights disagree"):
            bernstein.check_endpoint_weights(*wrong, range(1, 9))


# --------------------------------------------------------------------------- two processes


def _render(name: str) -> str:
    if name == "boom":
        raise AssertionError("a check failed in the second process")
    return f"text of {name}\n"


def test_two_processes_give_the_serial_result(monkeypatch):
    workers = _derive_module("emit.workers")
    names = ("a", "joins", "b")
    monkeypatch.setenv("LAMBDA_BEZIER_DERIVE_JOBS", "1")
    serial = workers.render_groups(names, _render)
    monkeypatch.setenv("LAMBDA_BEZIER_DERIVE_JOBS", "2")
    seen: list[str] = []
    parallel = workers.render_groups(names, _render, seen.append, lambda: seen.append("shared"))
    assert parallel == serial
    assert list(parallel) == list(names)
    if workers.jobs() == 2:
        assert seen == ["shared", "a", "joins (second process)", "b"]


def test_a_failure_in_the_second_process_is_raised(monkeypatch):
    workers = _derive_module("emit.workers")
    monkeypatch.setenv("LAMBDA_BEZIER_DERIVE_JOBS", "2")
    monkeypatch.setattr(workers, "SECOND", ("boom",))
    with pytest.raises(AssertionError, match="a check failed in the second process"):
        workers.render_groups(("a", "boom"), _render)


def test_a_failure_here_stops_the_second_process(monkeypatch):
    workers = _derive_module("emit.workers")
    monkeypatch.setenv("LAMBDA_BEZIER_DERIVE_JOBS", "2")

    def render(name):
        if name == "joins":
            import time

            time.sleep(60)  # killed, not waited for
        raise AssertionError(f"{name} failed here")

    import time

    start = time.monotonic()
    with pytest.raises(AssertionError, match="a failed here"):
        workers.render_groups(("a", "joins"), render)
    assert time.monotonic() - start < 30


def test_jobs_setting(monkeypatch):
    workers = _derive_module("emit.workers")
    monkeypatch.setenv("LAMBDA_BEZIER_DERIVE_JOBS", "1")
    assert workers.jobs() == 1
    monkeypatch.setenv("LAMBDA_BEZIER_DERIVE_JOBS", "3")
    with pytest.raises(ValueError, match="LAMBDA_BEZIER_DERIVE_JOBS must be 1 or 2"):
        workers.jobs()


def test_serial_check_passes_too():
    """`derive --check --no-cache` in one process matches generated/ as the default (two
    processes where there are two cores) does (tests/test_derive.py)."""
    assert_check_passes(LAMBDA_BEZIER_DERIVE_JOBS="1", PYTHONHASHSEED="7")


@pytest.mark.parametrize("continuity", ["C2", "G2", "C1"])
def test_per_degree_join_check_catches_a_wrong_emitted_weight(continuity):
    """The per-degree check (the emitted functions and the sums around them in fmpq) still
    fails on one weight off by 1e-9 in one emitted function."""
    emit_joins = _derive_module("emit.joins")
    formulas_joins = _derive_module("formulas.joins")
    table = formulas_joins.joins()
    namespace: dict = {}
    exec(compile(emit_joins.render(), "generated/joins.py", "exec"), namespace)  # noqa: S102
    key = ("same_degree", "bernstein_like", continuity)
    fn, args = namespace["JOINS"][key]

    def wrong(*values):
        weights = dict(fn(*values))
        last = max(weights)
        weights[last] = weights[last] + type(weights[last])(1, 10**9)  # fmpq there
        return weights

    namespace["JOINS"][key] = (wrong, args)
    with pytest.raises(AssertionError, match=f"{continuity} same_degree .* fails"):
        emit_joins._check_per_degree(namespace, table)
