"""The exact algebra of intersect_exact on python-flint (hazmat/exact_flint.py), issue #29:
its real-root isolation, resultants and subresultants against SymPy's; tangencies of
quintics and sextics decided exactly (past the standard-library budget of a product of
degrees 9), checked against SymPy's resultants and their real roots; the standard-library
algebra (PURE) still the fallback, giving the same answers where both run."""

from __future__ import annotations

import random
from fractions import Fraction as F

import pytest
import sympy as sp
from exact_curves import point_and_tangent, reflect_line
from hypothesis import given, settings
from hypothesis import strategies as st

import lambda_bezier as lb
from lambda_bezier.hazmat import exact_flint
from lambda_bezier.hazmat import exact_poly as xp
from lambda_bezier.hazmat import intersect_exact as ie

X = sp.Symbol("x")
S, T = sp.symbols("s t")
ALGEBRAS = [ie.PURE, ie.FLINT]


def rational(c: F) -> sp.Rational:
    return sp.Rational(c.numerator, c.denominator)


# ------------------------------------------------------------------------- real roots
@settings(max_examples=25, derandomize=True, deadline=None)
@given(
    st.lists(st.fractions(F(-1), F(2), max_denominator=12), min_size=0, max_size=5),
    st.lists(st.integers(1, 3), min_size=5, max_size=5),
    st.integers(-3, 3),
    st.sampled_from([(F(0), F(1)), (F(-1), F(2)), (F(1, 3), F(5, 7))]),
)
def test_real_roots_isolate_sympys_roots(rational_roots, multiplicities, shift, bounds):
    """A product of (x − r)^m (rational roots, some repeated, some at the bounds) and
    x² − 2 − shift/4 (irrational or complex roots): both algebras return one entry per
    distinct real root in [lo, hi] (SymPy's), increasing, a Fraction equal to the root or an
    open interval with non-root ends holding exactly that one root."""
    lo, hi = bounds
    expr = (X**2 - 2 - sp.Rational(shift, 4)) * sp.prod(
        [(X - rational(r)) ** m for r, m in zip(rational_roots, multiplicities, strict=False)]
    )
    poly = sp.Poly(sp.expand(expr), X)
    coeffs = [F(str(c)) for c in reversed(poly.all_coeffs())]
    want = sorted({r for r in poly.real_roots() if rational(lo) <= r <= rational(hi)}, key=float)
    for alg in ALGEBRAS:
        got = alg.real_roots(coeffs, lo, hi)
        assert len(got) == len(want), (alg.name, got, want)
        for entry, root in zip(got, want, strict=True):
            if isinstance(entry, F):
                assert rational(entry) == root
                continue
            a, b = entry
            assert a < b and rational(a) < root < rational(b), (alg.name, entry, root)
            assert xp.evaluate(coeffs, a) != 0 and xp.evaluate(coeffs, b) != 0
            assert len({r for r in poly.real_roots() if rational(a) < r < rational(b)}) == 1


def test_real_roots_of_zero_and_constants():
    for alg in ALGEBRAS:
        with pytest.raises(ValueError, match="zero polynomial"):
            alg.real_roots([F(0)], F(0), F(1))
        assert alg.real_roots([F(3)], F(0), F(1)) == []


# ------------------------------------------------------------------------- resultants
def bivariate(expr) -> xp.Bivariate:
    return {k: F(str(v)) for k, v in sp.Poly(expr, S, T).as_dict().items()}


PAIRS = [
    ((T - S) ** 2 - 1, T**2 - S**2 - 3),
    (S**3 * T - sp.Rational(1, 3) * T**2 + S - 2, sp.Rational(5, 7) * T**3 - S**2 * T + 1),
    (S**4 - 2 * S * T**3 + sp.Rational(1, 2), T**2 + S**3 - S * T - sp.Rational(7, 3)),
]


@pytest.mark.parametrize("f, g", PAIRS)
def test_flint_resultants_are_positive_multiples_of_sympys(f, g):
    """Res_t and Res_s from fmpz_mpoly: SymPy's resultant times a positive constant."""
    for var, (eliminated, kept) in ((1, (T, S)), (0, (S, T))):
        want = sp.Poly(sp.resultant(f, g, eliminated), kept)
        got = sp.Poly(
            sum(
                rational(c) * kept**k
                for k, c in enumerate(exact_flint.resultant(bivariate(f), bivariate(g), var))
            ),
            kept,
        )
        ratio = got.LC() / want.LC()
        assert ratio > 0 and sp.expand(got.as_expr() - ratio * want.as_expr()) == 0


@pytest.mark.parametrize("f, g", PAIRS)
def test_flint_first_subresultant_is_a_positive_multiple_of_the_pure_one(f, g):
    for var in (0, 1):
        pure = xp.first_subresultant(bivariate(f), bivariate(g), var)
        fast = exact_flint.first_subresultant(bivariate(f), bivariate(g), var)
        assert (pure is None) == (fast is None)
        if pure is None or fast is None:
            continue
        ratio = fast[0][-1] / pure[0][-1]
        assert ratio > 0
        for p, q in zip(pure, fast, strict=True):
            assert [ratio * c for c in p] == q


def test_gcd_and_squarefree_match_sympy():
    p = sp.Poly(sp.expand((X - sp.Rational(1, 3)) ** 3 * (X**2 - 2) * (X + 5)), X)
    q = sp.Poly(sp.expand((X - sp.Rational(1, 3)) * (X**2 - 2) ** 2 * (X - 7)), X)
    pc, qc = ([F(str(c)) for c in reversed(h.all_coeffs())] for h in (p, q))
    want_gcd = sp.Poly(sp.gcd(p, q), X).monic()
    assert exact_flint.gcd(pc, qc) == [F(str(c)) for c in reversed(want_gcd.all_coeffs())]
    square_free = sp.Poly(sp.quo(p, sp.gcd(p, p.diff(X))), X)
    got = exact_flint.squarefree(pc)
    assert sp.Poly(sum(rational(c) * X**k for k, c in enumerate(got)), X).monic() == (
        square_free.monic()
    )


# -------------------------------------------------------------- reflected tangencies


def reflected(n: int, seed: int, t0: F, offset: F = F(0)):
    """A random integer curve of degree n and its reflection in its own tangent line at t0
    (moved by `offset` along the normal): the two touch at (t0, t0) when offset is 0."""
    rnd = random.Random(seed)
    rows = [(F(rnd.randint(-9, 9)), F(rnd.randint(-9, 9))) for _ in range(n + 1)]
    reflect = reflect_line(*point_and_tangent(rows, [F(1)] * len(rows), t0), offset)
    return rows, [reflect(v) for v in rows]


def sympy_crossings(p_rows, q_rows):
    """Every common point (s, t) in [0, 1]² of the two curves, from SymPy: the real roots
    of Res_t and Res_s in [0, 1] paired where p(s) − q(t) vanishes (50 digits), each with
    |det J| there (0 at a tangency)."""
    pp = [
        sum(rational(c) * S**k for k, c in enumerate(ie.power_coefficients(p_rows, a)))
        for a in (0, 1)
    ]
    qq = [
        sum(rational(c) * T**k for k, c in enumerate(ie.power_coefficients(q_rows, a)))
        for a in (0, 1)
    ]
    fx, fy = sp.expand(pp[0] - qq[0]), sp.expand(pp[1] - qq[1])
    s_roots = [r for r in sp.Poly(sp.resultant(fx, fy, T), S).real_roots() if 0 <= r <= 1]
    t_roots = [r for r in sp.Poly(sp.resultant(fx, fy, S), T).real_roots() if 0 <= r <= 1]
    det = sp.expand(sp.diff(fx, S) * sp.diff(fy, T) - sp.diff(fx, T) * sp.diff(fy, S))
    out = []
    for s in sorted(set(s_roots), key=float):
        for t in sorted(set(t_roots), key=float):
            at = {S: sp.N(s, 50), T: sp.N(t, 50)}
            if max(abs(fx.evalf(50, subs=at)), abs(fy.evalf(50, subs=at))) < 1e-30:
                out.append((float(sp.N(s, 30)), float(sp.N(t, 30)), abs(det.evalf(50, subs=at))))
    return out


def check_against_sympy(p_rows, q_rows, boxes):
    want = sympy_crossings(p_rows, q_rows)
    assert len(boxes) == len(want), (boxes, want)
    for box, (s, t, det) in zip(boxes, sorted(want), strict=True):
        assert box.certified
        assert box.s[0] <= F(s) + F(1, 10**15) and F(s) - F(1, 10**15) <= box.s[1]
        assert box.t[0] <= F(t) + F(1, 10**15) and F(t) - F(1, 10**15) <= box.t[1]
        # a tangency makes det J vanish; elsewhere it is far from 0 at 50 digits
        assert box.tangent == (det < 1e-30), (box, det)
        assert box.tangent or det > 1e-8


@pytest.mark.parametrize(("n", "seed"), [(5, 1), (6, 2)])
def test_reflected_tangencies_of_quintics_and_sextics(n, seed):
    """Products of degrees 25 and 36: intersect_exact proves the touching point (t0, t0)
    tangent and every other crossing transversal, SymPy's crossings one for one; intersect
    answers from it (the float path alone saw a "tangent" hit)."""
    t0 = F(7, 23)
    p_rows, q_rows = reflected(n, seed, t0)
    boxes = ie.isolate(p_rows, q_rows, ie.NARROW, ie.FLINT)
    check_against_sympy(p_rows, q_rows, boxes)
    (touch,) = [b for b in boxes if b.s[0] <= t0 <= b.s[1] and b.t[0] <= t0 <= b.t[1]]
    assert touch.tangent
    assert n * n <= ie.FLINT.decide_degree
    hits = lb.BezierCurve(p_rows).intersect(lb.BezierCurve(q_rows))
    assert [(h.s, h.t, h.kind == "tangent") for h in hits] == ie.exact_answer(p_rows, q_rows)


@pytest.mark.parametrize("offset", [F(1, 10**20), F(-1, 10**20)])
def test_a_sextic_pair_moved_off_its_tangency(offset):
    """The sextic pair moved apart (or into each other) by 1e-20 along the normal: no
    contact near t0, or two transversal crossings there (SymPy's, one for one)."""
    t0 = F(7, 23)
    p_rows, q_rows = reflected(6, 1, t0, offset)
    boxes = ie.isolate(p_rows, q_rows, ie.NARROW, ie.FLINT)
    check_against_sympy(p_rows, q_rows, boxes)
    near = [b for b in boxes if abs(b.s[0] - t0) < F(1, 10**6)]
    assert len(near) in (0, 2) and not any(b.tangent for b in boxes)


@pytest.mark.parametrize(("n", "seed"), [(3, 3), (4, 1)])
def test_both_algebras_give_the_same_answer(n, seed):
    p_rows, q_rows = reflected(n, seed, F(5, 17))
    assert ie.exact_answer(p_rows, q_rows, ie.PURE) == ie.exact_answer(p_rows, q_rows, ie.FLINT)


def test_without_flint_the_standard_library_decides_within_its_budget(monkeypatch):
    """python-flint missing: algebra() is PURE (a product of degrees 9), FLINT's steps say
    what to install; two quartics touching are then left to the float answer (a tangent hit),
    which FLINT decides exactly (no contact: SymPy)."""
    quartic_rows, mirror_rows = reflected(4, 1, F(7, 23), F(1, 10**20))
    quartic, mirror = lb.BezierCurve(quartic_rows), lb.BezierCurve(mirror_rows)
    check_against_sympy(quartic_rows, mirror_rows, ie.isolate(quartic_rows, mirror_rows))
    exact = quartic.intersect(mirror)
    assert ie.algebra() is ie.FLINT and not any(h.kind == "tangent" for h in exact)
    monkeypatch.setattr(exact_flint, "_FLINT", [None])
    assert ie.algebra() is ie.PURE and not exact_flint.available()
    with pytest.raises(RuntimeError, match="python-flint is not installed"):
        exact_flint.real_roots([F(1), F(1)], F(0), F(1))
    assert any(h.kind == "tangent" for h in quartic.intersect(mirror))


def test_evaluate_in_integers_matches_sympy():
    """exact_poly.evaluate's integer path (integer coefficients, the form exact_flint gives)
    and its Fraction path, against SymPy's exact value."""
    rnd = random.Random(5)
    for _ in range(50):
        coeffs = [F(rnd.randint(-(10**6), 10**6)) for _ in range(rnd.randint(1, 12))]
        coeffs[0] += F(rnd.choice([0, 1]), rnd.choice([1, 3]))  # a Fraction now and then
        x = F(rnd.randint(-(2**70), 2**70), 2 ** rnd.randint(0, 80))
        want = sp.Poly(list(reversed([rational(c) for c in coeffs])), X).eval(rational(x))
        assert rational(xp.evaluate(coeffs, x)) == want
