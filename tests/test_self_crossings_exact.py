"""Issue #29, "correct first": self-crossings of exact curves closer than floats separate.

For exact (int, Fraction) input, self_intersections lost or merged self-crossings closer than
about 1e-6 in parameter and dropped small loops as cusps (round 19's audit; main before this
module: two crossings 1e-6 apart came back as one, 1e-7 to 1e-12 apart as one "tangent"
between them, a loop 1e-5 wide in parameter as nothing). Now an exact planar curve whose float
answer is in doubt is decided exactly (hazmat/intersect_self_exact.py: the divided differences
(p(s) − p(t)) / (s − t), their resultant, exact real-root isolation and Krawczyk's test). Every
case here has its exact answer by construction (rational crossing parameters), or from SymPy's
resultant and real roots, computed independently of the module; each runs on the numpy and the
numba subdivision, and with python-flint's algebra and the standard library's.
"""

from __future__ import annotations

from fractions import Fraction as F
from math import comb

import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

import lambda_bezier as lb
from lambda_bezier.hazmat import exact_flint
from lambda_bezier.hazmat import exact_poly as xp
from lambda_bezier.hazmat import intersect_exact as ie
from lambda_bezier.hazmat import intersect_self_exact as se

pytestmark = pytest.mark.usefixtures("intersect_engine")

HALF_ULP = F(1, 2**53)  # a rounded answer in [0, 1] within 2^-54 of a box 2^-64 wide
ROTATIONS = [(F(1), F(0)), (F(3, 5), F(4, 5)), (F(-5, 13), F(12, 13)), (F(8, 17), F(-15, 17))]
S, T = sp.symbols("s t")


@pytest.fixture(params=["flint", "fractions"])
def algebra(request, monkeypatch):
    """The exact algebra: python-flint's (when installed) or the standard library's."""
    if request.param == "flint":
        if not exact_flint.available():
            pytest.skip("python-flint is not installed (pip install '.[exact]')")
    else:
        monkeypatch.setattr(exact_flint, "_FLINT", [None])
    return ie.algebra()


# ------------------------------------------------------------------------ constructions
def compose(p: list[F], w: list[F]) -> list[F]:
    """p(w(t)) in the power basis (Horner on coefficient lists)."""
    out = [F(0)]
    for c in reversed(p):
        prod = [F(0)] * (len(out) + len(w) - 1)
        for i, a in enumerate(out):
            for j, b in enumerate(w):
                prod[i + j] += a * b
        prod[0] += c
        out = prod
    return xp.trim(out)  # p(w) of p's degree: the Bézier form not elevated


def bezier_from_power(x: list[F], y: list[F], rotation=(F(1), F(0))) -> lb.BezierCurve:
    """The Bézier curve with these power-basis coordinates, rotated by (cos, sin)."""
    n = max(len(x), len(y)) - 1
    x, y = x + [F(0)] * (n + 1 - len(x)), y + [F(0)] * (n + 1 - len(y))
    c, s = rotation
    rows = []
    for i in range(n + 1):
        bx, by = (sum(F(comb(i, k), comb(n, k)) * a[k] for k in range(i + 1)) for a in (x, y))
        rows.append((c * bx - s * by, s * bx + c * by))
    return lb.BezierCurve(rows)


W = [F(-1), F(2)]  # w = 2t - 1


def folded(r1: F, r2: F, rotation=(F(1), F(0))) -> lb.BezierCurve:
    """x = w², y = w (w² − r1²)(w² − r2²): symmetric about the x axis, crossing itself there
    at w = ±r1 and ±r2, i.e. (s, t) = ((1 − r)/2, (1 + r)/2); r1 = r2: touching itself."""
    a, b = r1 * r1, r2 * r2
    x = compose([F(0), F(0), F(1)], W)
    return bezier_from_power(x, compose([F(0), a * b, F(0), -(a + b), F(0), F(1)], W), rotation)


def loop(r: F, rotation=(F(1), F(0))) -> lb.BezierCurve:
    """x = w², y = w³ − r² w: a loop crossing itself at w = ±r, (s, t) = ((1 − r)/2,
    (1 + r)/2), whose size is r² across; r = 0: a cusp (not a crossing)."""
    x = compose([F(0), F(0), F(1)], W)
    return bezier_from_power(x, compose([F(0), -r * r, F(0), F(1)], W), rotation)


def crossing(r: F) -> tuple[F, F]:
    return (1 - r) / 2, (1 + r) / 2


def assert_exactly(hits, want: list[tuple[F, F, str]]) -> None:
    assert len(hits) == len(want), (hits, want)
    for h, (s, t, kind) in zip(hits, want, strict=True):
        assert abs(F(h.s) - s) <= HALF_ULP and abs(F(h.t) - t) <= HALF_ULP, (h, s, t)
        assert h.kind == kind, (h, kind)


# ------------------------------------------------------------------------ the divided differences
@settings(max_examples=15, derandomize=True, deadline=None)
@given(
    st.lists(
        st.tuples(st.integers(-9, 9), st.integers(-9, 9), st.integers(1, 5)),
        min_size=2,
        max_size=5,
    )
)
def test_divided_differences_are_sympys(points):
    """G_c = (X_c(s) W(t) − X_c(t) W(s)) / (s − t) for Bézier rows and weights, against SymPy's
    exact division of the same expression (polynomial curves: all weights 1)."""
    rows = [(F(x), F(y)) for x, y, _ in points]
    n = len(rows) - 1
    for weights in ([F(1)] * len(rows), [F(w) for _, _, w in points]):

        def form(values, var):
            return sum(
                sp.Rational(v.numerator, v.denominator) * comb(n, i) * var**i * (1 - var) ** (n - i)
                for i, v in enumerate(values)
            )

        got = se.divided_differences(rows, weights)
        for axis in (0, 1):
            homogeneous = [r[axis] * w for r, w in zip(rows, weights, strict=True)]
            h = form(homogeneous, S) * form(weights, T) - form(homogeneous, T) * form(weights, S)
            quotient, remainder = sp.div(sp.Poly(sp.expand(h), S, T), sp.Poly(S - T, S, T))
            assert remainder.is_zero
            want = {
                k: F(int(c.p), int(c.q))
                for k, c in zip(quotient.monoms(), quotient.coeffs(), strict=True)
                if c
            }
            assert got[axis] == want


def test_a_polynomial_off_the_diagonal_is_refused():
    with pytest.raises(ValueError, match="diagonal"):
        se.divided_by_diagonal({(1, 0): F(1)})


# ------------------------------------------------------------------------ the audit's cases
CASES = {
    # two crossings closer than floats separate: main gave one crossing, or one "tangent"
    **{
        f"folded gap {g}": (
            folded(F(1, 2), F(1, 2) + g),
            [(*crossing(F(1, 2) + g), "transversal"), (*crossing(F(1, 2)), "transversal")],
        )
        for g in (F(1, 10**6), F(1, 10**7), F(1, 10**9), F(1, 10**12))
    },
    "folded touching": (folded(F(1, 2), F(1, 2)), [(F(1, 4), F(3, 4), "tangent")]),
    # small loops are crossings (main dropped those from 1e-5 across down, as cusps)
    **{f"loop {r}": (loop(r), [(*crossing(r), "transversal")]) for r in (F(1, 10**3),)},
    **{
        f"loop {r}": (loop(r, (F(3, 5), F(4, 5))), [(*crossing(r), "transversal")])
        for r in (F(1, 10**5), F(1, 10**7), F(1, 10**9))
    },
    "cusp": (loop(F(0)), []),  # p'(1/2) = 0: no crossing
    "cusp rotated": (loop(F(0), (F(-5, 13), F(12, 13))), []),
}


@pytest.mark.parametrize("name", list(CASES))
def test_the_audits_cases_have_their_exact_answers(name, algebra):
    curve, want = CASES[name]
    assert_exactly(curve.self_intersections(), want)


def test_a_regular_curve_keeps_the_float_path(monkeypatch):
    """A transversal crossing at a large angle is not in doubt: no exact isolation runs."""

    def refuse(*args, **kwargs):
        raise AssertionError("the exact isolation ran")

    monkeypatch.setattr(se, "self_decided", refuse)
    hits = lb.BezierCurve([(0, 0), (4, 2), (-1, 2), (3, 0)]).self_intersections()
    root = (3 - sp.sqrt(3)) / 6  # the README's cubic: s = (3 ∓ √3)/6
    assert [h.kind for h in hits] == ["transversal"]
    assert hits[0].s == pytest.approx(float(root), abs=1e-15)


def test_a_lambda_curve_with_a_tiny_loop():
    """A λ-curve (SameDegreeCurve, λ = 1/3) whose control points are chosen so that its Bézier
    form is the loop of width 1e-8 in parameter: the λ-basis matrix inverted exactly."""
    lam = F(1, 3)
    target = loop(F(1, 10**8), (F(8, 17), F(-15, 17))).control_points()
    columns = []
    for k in range(4):  # the Bézier rows of the k-th unit control point, one coordinate
        unit = [(F(int(i == k)), F(0)) for i in range(4)]
        columns.append([r[0] for r in lb.SameDegreeCurve(unit, lam).to_bezier().control_points()])
    m = sp.Matrix(
        4, 4, lambda i, k: sp.Rational(columns[k][i].numerator, columns[k][i].denominator)
    )
    inverse = m.inv()
    points = []
    for i in range(4):
        row = []
        for axis in (0, 1):
            value = sum(inverse[i, k] * sp.Rational(str(target[k][axis])) for k in range(4))
            row.append(F(int(value.p), int(value.q)))
        points.append(tuple(row))
    curve = lb.SameDegreeCurve(points, lam)
    assert curve.to_bezier().control_points() == target
    assert_exactly(curve.self_intersections(), [(*crossing(F(1, 10**8)), "transversal")])


# ------------------------------------------------------------------------ against SymPy
def _sympy_divided(rows) -> list[sp.Expr]:
    n = len(rows) - 1
    g = []
    for axis in (0, 1):

        def form(var, axis=axis):
            return sum(
                sp.Rational(str(r[axis])) * comb(n, i) * var**i * (1 - var) ** (n - i)
                for i, r in enumerate(rows)
            )

        g.append(sp.cancel((form(S) - form(T)) / (S - T)))
    return g


def sympy_self_crossings(rows) -> list[tuple[sp.Expr, sp.Expr]]:
    """The pairs s < t in [0, 1] with p(s) = p(t), from SymPy alone: the divided differences by
    exact division, their resultant's real roots, each pair checked at 60 digits."""
    g = _sympy_divided(rows)
    resultant = sp.Poly(sp.resultant(g[0], g[1], T), S)
    roots = [r for r in resultant.real_roots() if 0 <= r <= 1]
    roots = sorted(set(roots), key=lambda r: float(r))
    out = []
    for i, a in enumerate(roots):
        for b in roots[i + 1 :]:
            va, vb = sp.N(a, 60), sp.N(b, 60)
            if all(abs(sp.N(gc.subs({S: va, T: vb}), 60)) < sp.Float(10) ** -40 for gc in g):
                out.append((a, b))
    return out


@settings(max_examples=6, derandomize=True, deadline=None)
@given(
    r=st.sampled_from([F(1, 10**6), F(3, 10**7), F(1, 10**9)]),
    rotation=st.sampled_from(ROTATIONS),
    shear=st.fractions(F(-2), F(2), max_denominator=7),
    shift=st.fractions(F(-1, 20), F(1, 20), max_denominator=40),
)
def test_small_loops_against_sympy(r, rotation, shear, shift):
    """Loops 1e-6 to 1e-9 wide (in parameter) moved off the middle (w = 2t − 1 + shift) and
    sheared: one crossing, SymPy's."""
    w = [F(-1) + shift, F(2)]
    x = compose([F(0), F(0), F(1)], w)
    y = compose([F(0), -r * r, F(0), F(1)], w)
    y = [b + shear * a for a, b in zip(x + [F(0)] * (len(y) - len(x)), y, strict=True)]
    curve = bezier_from_power(x, y, rotation)
    want = sympy_self_crossings(curve.control_points())
    hits = curve.self_intersections()
    assert len(hits) == len(want) == 1, (hits, want)
    for h, (s, t) in zip(hits, want, strict=True):
        assert abs(h.s - sp.N(s, 30)) <= 2**-53 and abs(h.t - sp.N(t, 30)) <= 2**-53
        assert h.kind == "transversal"


# ------------------------------------------------------------------------ near-double crossings
@settings(max_examples=8, derandomize=True, deadline=None)
@given(
    r1=st.fractions(F(1, 10), F(9, 10), max_denominator=100),
    gap=st.sampled_from([F(1, 10**7), F(1, 10**9), F(1, 10**12), F(0)]),
    rotation=st.sampled_from(ROTATIONS),
)
def test_near_double_self_crossings(r1, gap, rotation):
    """Two self-crossings gap apart (gap 0: one self-tangency), in exact rationals."""
    curve = folded(r1, r1 + gap, rotation)
    if gap:
        want = sorted([(*crossing(r), "transversal") for r in (r1, r1 + gap)], key=lambda w: w[0])
    else:
        want = [(*crossing(r1), "tangent")]
    assert_exactly(curve.self_intersections(), want)


def test_both_algebras_isolate_the_same_boxes():
    """The symmetric system on FLINT's algebra and the standard library's: the same boxes."""
    rows = folded(F(1, 3), F(1, 3) + F(1, 10**9), ROTATIONS[2]).to_bezier().control_points()
    got = [se.isolate_self(rows, ie.NARROW, alg) for alg in (ie.PURE, ie.FLINT)]
    if not exact_flint.available():
        pytest.skip("python-flint is not installed")
    assert [(c.certified, c.tangent) for c in got[0]] == [(True, False)] * 2
    for a, b in zip(*got, strict=True):  # each box holds its one root: the boxes overlap
        assert a.s[0] <= b.s[1] and b.s[0] <= a.s[1] and a.t[0] <= b.t[1] and b.t[0] <= a.t[1]


def test_past_the_budget_the_float_answer_stands(monkeypatch):
    monkeypatch.setitem(se.SELF_DEGREE, ie.algebra().name, 4)
    hits = folded(F(1, 2), F(1, 2) + F(1, 10**9)).self_intersections()
    assert len(hits) == 1  # the float answer: the two crossings as one (the documented limit)


# ------------------------------------------------------------------------ the engine itself
def test_a_triple_point_gives_its_three_pairs(algebra):
    """x = m(w), y = w m(w) with m = (w − a)(w − b)(w − c): p(a) = p(b) = p(c), three branches
    through one point; the exact isolation pairs every two of them (one s over two t)."""
    a, b, c = F(-1, 2), F(1, 10), F(3, 5)
    m = [-a * b * c, a * b + a * c + b * c, -(a + b + c), F(1)]
    curve = bezier_from_power(compose(m, W), compose([F(0), *m], W), ROTATIONS[1])
    want = [((u + 1) / 2, (v + 1) / 2, False) for u, v in ((a, b), (a, c), (b, c))]
    got = se.self_exact_answer(curve.control_points(), algebra)
    assert got == [(float(s), float(t), flat) for s, t, flat in want]
    assert_exactly(curve.self_intersections(), [(s, t, "transversal") for s, t, _ in want])


LOOPED = st.tuples(*[st.integers(0, 3)] * 6).map(
    lambda d: [(0, 0), (4 + d[0], 2 + d[1]), (-1 - d[2], 2 + d[3]), (3 + d[4], d[5] - 1)]
)
RANDOM = st.lists(st.tuples(st.integers(-6, 6), st.integers(-6, 6)), min_size=4, max_size=5)


@settings(max_examples=10, derandomize=True, deadline=None)
@given(st.one_of(LOOPED, RANDOM))
def test_random_curves_against_sympy(points):
    """Cubics around the README's loop (a crossing, mostly) and random small-integer cubics and
    quartics: the exact isolation's pairs (both algebras) are SymPy's, to the rounding of the
    2^-64 boxes."""
    rows = [(F(x), F(y)) for x, y in points]
    if len({r[0] for r in rows}) == 1 or len({r[1] for r in rows}) == 1:
        return  # a coordinate constant: on a line (self_intersections answers it elsewhere)
    try:
        want = sympy_self_crossings(rows)
    except sp.PolynomialError:
        return
    for alg in (ie.PURE, ie.FLINT) if exact_flint.available() else (ie.PURE,):
        got = se.self_exact_answer(rows, alg)
        if got is None:  # no finite set (the curve runs back along itself): SymPy's resultant is 0
            assert sp.resultant(*_sympy_divided(rows), T) == 0
            continue
        assert len(got) == len(want), (alg.name, got, want)
        for (s, t, _), (a, b) in zip(got, want, strict=True):
            assert abs(s - sp.N(a, 30)) <= 2**-53 and abs(t - sp.N(b, 30)) <= 2**-53
