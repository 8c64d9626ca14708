"""Bad input never escapes (issue 18): every reproducer of the issue, then hypothesis fuzzing of
every public function and the command line with bad and near-valid input. Each call either
returns a finite, correct result or raises ValueError/TypeError whose message names the
argument; any other exception, a warning (numpy's overflow or complex-cast warnings), NaN or
infinity fails."""

from __future__ import annotations

import math
import re
import warnings
from decimal import Decimal
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import lambda_bezier as lb
from lambda_bezier.cli import main
from lambda_bezier.hazmat import kernels as alg

pytestmark = pytest.mark.filterwarnings("error")  # a RuntimeWarning is an escape too

P = [(0, 0), (1, 2), (3, 2), (4, 0)]
EXAMPLE = [(0, 6), (0, 2), (5, 2), (7, 0), (2, 0), (6, 8)]
HUGE = 10**400
POLYGON = [(0, 0), (1, 2), (3, 2), (4, 0), (6, -1), (7, 3), (9, 1)]


def raises(match: str):
    return pytest.raises(ValueError, match=match)


# ------------------------------------------------------------------ the issue's reproducers


@pytest.mark.parametrize(
    ("call", "match"),
    [
        (lambda: lb.SameDegreeCurve([(HUGE, 0), (1, 2), (3, 2), (4, 0)], lam=0), "control point"),
        (lambda: lb.BernsteinLikeCurve([(0, 0), (1, Fraction(HUGE, 3)), (3, 2)], lam=0), "float"),
        (lambda: lb.BezierCurve([(0, 0), (1, -HUGE)]), "too large for a float"),
        (lambda: lb.SameDegreeCurve(P, lam=0).evaluate(Fraction(HUGE)), r"^t = .*too large"),
        (lambda: lb.SameDegreeCurve(P, lam=0).derivative([0.5, HUGE]), r"^t at index \(1,\)"),
        (lambda: lb.SameDegreeCurve(P, lam=HUGE, check_range=False), r"^lam = .*too large"),
        (lambda: lb.BezierCurve(P).basis(-Fraction(HUGE, 7)), r"^t = .*too large"),
        (lambda: lb.CompositeCurve([lb.BezierCurve(P)]).evaluate(Fraction(HUGE)), r"^u = "),
        (
            lambda: lb.join(lb.SameDegreeCurve(P, 0.5), "C1", 3, lam=0, rest=[(HUGE, 1), (2, 2)]),
            r"^rest at index \(0, 0\)",
        ),
        (
            lambda: lb.join(lb.SameDegreeCurve(P, 0.5), "G2", 4, lam=0, alpha=1e-300, rest=P[:2]),
            r"^alpha = 1e-300.*too extreme",
        ),
        (
            lambda: lb.join(lb.SameDegreeCurve(P, 0.5), "G1", 3, lam=0, alpha=HUGE, rest=P[:2]),
            r"^alpha = .*too extreme",
        ),
        (lambda: lb.BezierCurve(np.array(P) + 0j), "control points must be real"),
        (lambda: lb.BezierCurve(P).evaluate(np.array([0.5 + 1e-9j])), "t must be real"),
        (
            lambda: lb.join(lb.BezierCurve(P), "C1", 3, rest=np.array(P[2:]) * (1 + 0j)),
            "rest must be real",
        ),
        (lambda: lb.CompositeCurve([lb.BezierCurve(P)]).evaluate(0.5 + 1j), "u must be real"),
        (lambda: lb.optimal_lambda(np.array(EXAMPLE) + 0j, 2), "control points must be real"),
        (lambda: lb.evaluate_many(np.array([P]) + 0j, [0.5]), "control points must be real"),
        (
            lambda: lb.SameDegreeCurve(P, lam=Fraction(1, 2)).geometric_levels(5),
            r"t = 5 is outside \[0, 1\]",
        ),
        (lambda: lb.SameDegreeCurve(P, lam=1).geometric_levels(-1), r"t = -1 is outside"),
        (lambda: lb.evaluate_many([P], [0.5], "same_degree", lam=True), "lam must be numbers"),
        (lambda: lb.evaluate_many([P], [0.5], "same_degree", lam="0.5"), "lam must be numbers"),
        (lambda: lb.evaluate_many([P], [0.5], "same_degree", lam=[np.bool_(1)]), "lam"),
        (lambda: _two().report(tol=math.nan), "tol must be finite"),
        (lambda: _two().report(tol=-1), "tol must be >= 0"),
        (lambda: _two().report(tol="1e-9"), "tol must be a real number"),
        (lambda: lb.energy_matrices([3], 1), "degree n must be an integer"),
        (lambda: lb.energy_matrices(3, np.array([1, 2])), "energy order k"),
        (lambda: lb.energy_matrices(3, 1, family=["same_degree"]), "unknown family"),
        (lambda: lb.evaluate_many([P], [0.5], []), "unknown family"),
        (lambda: lb.BezierCurve(P).evaluate(0.5, extrapolate="no"), "extrapolate must be True"),
        (lambda: lb.optimal_lambda(EXAMPLE, 2, clamp="yes"), "clamp must be True or False"),
        (lambda: lb.SameDegreeCurve(P, 2, check_range="no"), "check_range must be True"),
        (lambda: lb.BezierCurve([("0", "0"), ("1", "1")]), "control points must be numbers"),
        (lambda: lb.BezierCurve([(True, False), (1, 1)]), "control points must be numbers"),
        (lambda: lb.BezierCurve([(0, 0), (1, 1, 1)]), "control points must be a regular array"),
        (lambda: lb.BezierCurve([(0, None), (1, 1)]), r"control points at index \(0, 1\)"),
        (lambda: lb.BezierCurve([(0, Decimal("1e400")), (1, 1)]), "too large for a float"),
        (lambda: _two().with_lambda(True, 0.5), "index must be an integer"),
        (lambda: _two().with_lambda(0, 0.5, resolve=None), "resolve must be True or False"),
        (lambda: lb.join(lb.BezierCurve(P), "C1", 3.0, rest=P[2:]), "degree must be an integer"),
        (lambda: lb.Joint("G1", alpha=True), "alpha must be a real number"),
        (lambda: lb.Joint("G2", alpha=1, d=1j), "d must be a real number"),
    ],
)
def test_issue_reproducers_raise_named_errors(call, match):
    with raises(match):
        call()


def _two():
    return lb.CompositeCurve([lb.BezierCurve(P), lb.BezierCurve(P)])


def test_coordinates_near_the_float_limit_are_evaluated_right():
    c = lb.BezierCurve([(0, 0), (1e308, 2), (-1e308, 2), (4, 0)])
    # exact: 3/8·1e308 − 3/8·1e308 + 1/8·4 = 0.5 (to rounding at the 1e308 scale)
    assert np.allclose(c.evaluate(0.5), [0.5, 1.5], rtol=0, atol=1e292)
    assert np.isfinite(c.curvature([0.25, 0.5])).all()
    s = lb.SameDegreeCurve(np.array(P) / 4 * 1.5e308, lam=-1.5)
    u = lb.SameDegreeCurve(np.array(P) / 4, lam=-1.5)
    t = np.linspace(0, 1, 9)
    assert np.allclose(s.evaluate(t) / 1.5e308, u.evaluate(t), rtol=1e-14, atol=1e-15)
    assert np.allclose(s.evaluate_geometric(t) / 1.5e308, u.evaluate(t), atol=1e-15)
    assert np.allclose(s.curvature(t) * 1.5e308, u.curvature(t), rtol=1e-12)
    with raises("overflows the float range"):
        s.derivative(0.5, 3)  # |p'''| is beyond 1.8e308 here: refused, not inf
    with raises("overflows"):
        s.energy(2)
    tiny = lb.BernsteinLikeCurve(np.array(P) * 1e-300, lam=0.5)
    ref = lb.BernsteinLikeCurve(P, lam=0.5)
    assert np.allclose(tiny.curvature(t) * 1e-300, ref.curvature(t), rtol=1e-12)
    with raises("curvature overflows"):  # κ ~ 1e310
        lb.BernsteinLikeCurve(np.array(P) * 1e-310, lam=0.5).curvature(t)


def test_optimal_lambda_with_huge_and_tiny_coordinates():
    pts = np.array([[0, 0], [1e200, 0], [2, 3], [4, 0]])
    exact = lb.optimal_lambda([[Fraction(v) for v in row] for row in pts], 2)
    got = lb.optimal_lambda(pts, 2)
    assert got.lam == pytest.approx(float(exact.lam), rel=1e-12)
    for scale in (1e-200, 1e-300, 1e150, 1e-320):
        r = lb.optimal_lambda(np.array(EXAMPLE) * scale, 2)
        assert r.unconstrained == pytest.approx(-690 / 319, rel=1e-12)
    batch = np.stack([np.array(EXAMPLE) * s for s in (1.0, 1e-250, 1e100)])
    assert np.allclose(lb.optimal_lambda(batch, 2).unconstrained, -690 / 319, rtol=1e-12)
    with raises(r"E_2: beyond the float range.*scale the points down"):
        lb.optimal_lambda(np.array(EXAMPLE) * 1e300, 2, clamp=True).energy  # noqa: B018
    # exact input of any magnitude stays exact
    big = lb.optimal_lambda([(x * HUGE, y * HUGE) for x, y in EXAMPLE], 2)
    assert big.lam == Fraction(-690, 319)


def test_join_with_exact_extreme_alpha_is_exact():
    first = lb.SameDegreeCurve(P, lam=Fraction(1, 2))
    far = lb.join(first, "G1", 3, lam=0, alpha=HUGE, rest=[(9, -1), (10, 1)]).control_points()
    one = lb.join(first, "G1", 3, lam=0, alpha=1, rest=[(9, -1), (10, 1)]).control_points()
    # C1'(1) = alpha C2'(0): P_{1,2} - P_{0,2} scales with 1/alpha, exactly
    assert [b - a for a, b in zip(far[0], far[1], strict=True)] == [
        (b - a) / HUGE for a, b in zip(one[0], one[1], strict=True)
    ]


# ------------------------------------------------------------------ strategies

BAD_SCALARS = st.one_of(
    st.sampled_from(
        [
            math.nan,
            math.inf,
            -math.inf,
            True,
            np.bool_(False),
            "0.5",
            "",
            b"1",
            None,
            [],
            [0.5, 0.25],
            {},
            1j,
            np.complex128(0.5 + 0j),
            Decimal("nan"),
            Decimal("1e400"),
            HUGE,
            -HUGE,
            Fraction(HUGE, 3),
            Fraction(-1, HUGE),
            np.array([[0.5]]),
            object(),
        ]
    ),
    st.complex_numbers(max_magnitude=10, allow_nan=False, allow_infinity=False),
    st.text(max_size=4),
)
NEAR_VALID_SCALARS = st.one_of(
    st.floats(allow_nan=False, allow_infinity=False),
    st.floats(-2, 2),
    st.sampled_from([0, 1, -1, 0.0, 1.0, -0.0, 5e-324, 1e-300, 1e300, 1.7e308, -2, 1 + 1e-15]),
    st.fractions(max_denominator=10**6).filter(lambda q: abs(q) < 10**6),
    st.integers(-(10**6), 10**6),
    st.sampled_from([np.float32(0.5), np.int64(1), np.uint8(0), np.float64(0.25), Decimal("0.5")]),
)
ANY_SCALAR = st.one_of(BAD_SCALARS, NEAR_VALID_SCALARS)


@st.composite
def bad_points(draw, size: int):
    """Control points that are wrong in one way, or near-valid (extreme scales, exact values,
    other dtypes, one odd coordinate)."""
    base = np.array(POLYGON[:size], dtype=float)
    kind = draw(st.integers(0, 6))
    if kind == 0:  # one coordinate replaced
        out = base.astype(object)
        out[draw(st.integers(0, size - 1)), draw(st.integers(0, 1))] = draw(ANY_SCALAR)
        return out.tolist() if draw(st.booleans()) else out
    if kind == 1:  # scaled to an extreme
        return base / 10 * 10.0 ** draw(st.integers(-320, 308))
    if kind == 2:  # exact and possibly huge
        factor = draw(st.sampled_from([1, 3, HUGE, Fraction(1, HUGE), Fraction(7, 3)]))
        return [[Fraction(int(v)) * factor for v in row] for row in base]
    if kind == 3:  # another dtype
        dtype = draw(st.sampled_from([np.float32, np.int64, complex, bool, str, object]))
        return base.astype(dtype)
    if kind == 4:  # wrong shape
        shape = draw(st.sampled_from([(size,), (size, 1), (size, 4), (1, 2), (2, size, 2), ()]))
        return np.zeros(shape)
    if kind == 5:  # ragged or not an array at all
        return draw(st.sampled_from([[(0, 0), (1,)], "points", None, 3.0, [[(0, 0)], (1, 1)]]))
    return base  # valid


def check(call, pattern: str, *, nan_ok: bool = False):
    """Run `call`: a result must be finite (NaN allowed where documented), an error must be a
    ValueError/TypeError whose message matches `pattern` (names the argument)."""
    try:
        out = call()
    except (ValueError, TypeError) as exc:
        assert re.search(pattern, str(exc)), f"message does not name {pattern!r}: {exc}"
        return None
    assert_finite(out, nan_ok)
    return out


def assert_finite(out, nan_ok: bool = False) -> None:
    if isinstance(out, np.ndarray | float | np.floating):
        arr = np.asarray(out, dtype=float)
        assert not np.isinf(arr).any(), out
        assert nan_ok or not np.isnan(arr).any(), out
    elif isinstance(out, tuple | list):
        for item in out:
            assert_finite(item, nan_ok)
    elif isinstance(out, lb.JointReport):
        assert_finite([out.position_gap, out.first_derivative_gap, out.speed_ratio], True)
    elif isinstance(out, lb.OptimalLambda):
        assert_finite([out.lam, out.unconstrained, out.energy, out.unconstrained_energy])


def exact_value(curve, t: float, k: int) -> np.ndarray:
    """p^(k)(t) in Fractions from the exact Bernstein form (an independent path)."""
    pts = tuple(tuple(Fraction(float(v)) for v in row) for row in curve.points)
    if curve.lam is None:
        weights = tuple(
            tuple(Fraction(int(i == j)) for j in range(len(pts))) for i in range(len(pts))
        )
    else:
        twin = type(curve)(curve.points, Fraction(curve.lam), check_range=False)
        weights = tuple(zip(*twin.basis_bernstein_matrix(exact=True), strict=True))
    b = [list(r) for r in alg.exact_matmul(weights, pts)]
    for _ in range(min(k, len(b))):  # k may be huge: the derivative is then 0
        big = len(b) - 1
        b = [
            [big * (y - x) for x, y in zip(r0, r1, strict=True)]
            for r0, r1 in zip(b[:-1], b[1:], strict=True)
        ]
    if not b:
        return np.zeros(curve.dimension), 0.0
    tri = alg.de_casteljau_triangle(b, Fraction(t))
    scale = max(abs(float(v)) for row in b for v in row) if b else 0.0
    return np.array([float(v) for v in tri[-1][0]]), scale


# ------------------------------------------------------------------ fuzzing the API

LAM = {"bezier": None, "same_degree": 0.5, "bernstein_like": -0.5}
SIZES = {"bezier": 4, "same_degree": 5, "bernstein_like": 4}


@settings(max_examples=150)
@given(
    family=st.sampled_from(list(lb.FAMILIES)),
    data=st.data(),
)
def test_fuzz_constructors_and_evaluation(family, data):
    cls = lb.FAMILIES[family]
    size = SIZES[family]
    points = data.draw(bad_points(size), label="points")
    lam = LAM[family]
    if family != "bezier" and data.draw(st.booleans()):
        lam = data.draw(ANY_SCALAR, label="lam")
    args = (points,) if family == "bezier" else (points, lam)
    curve = check(lambda: cls(*args), r"control point|degree|\blam\b")
    if curve is None:
        return
    t = data.draw(st.one_of(ANY_SCALAR, st.lists(NEAR_VALID_SCALARS, max_size=3)), label="t")
    k = data.draw(st.one_of(st.integers(0, 4), BAD_SCALARS), label="k")
    out = check(lambda: curve.derivative(t, k), r"\bt\b|\bk\b|overflow")
    if out is not None:
        ts = np.atleast_1d(np.asarray(t, dtype=float))
        got = np.atleast_2d(out)
        for row, tv in zip(got, ts, strict=True):
            want, scale = exact_value(curve, float(tv), int(k))
            bound = 1e-12 * max(scale, 1e-300) * (2 * (curve.polynomial_degree + 1)) ** 2
            assert np.all(np.abs(row - want) <= bound), (row, want, bound)
    check(lambda: curve.curvature(t), r"\bt\b|overflow|dimension", nan_ok=True)
    check(lambda: curve.basis(t), r"\bt\b")
    check(lambda: curve.energy(k), r"\bk\b|overflow")
    check(lambda: curve.to_bezier(), "overflow")
    if family == "same_degree":
        check(lambda: curve.evaluate_geometric(t), r"\bt\b|overflow")
        check(lambda: curve.geometric_levels(t), r"\bt\b|single t")
    if family == "bezier":
        check(lambda: curve.de_casteljau(t), r"\bt\b|overflow")
        check(lambda: curve.split(t), r"\bt\b")
        check(lambda: curve.segment(0, t), r"\bt2\b|t1 < t2")
        check(lambda: curve.hodograph(), "overflow|hodograph")


@settings(max_examples=120)
@given(family=st.sampled_from(["same_degree", "bernstein_like"]), data=st.data())
def test_fuzz_energy(family, data):
    points = data.draw(
        st.one_of(bad_points(6), st.just(np.stack([np.array(EXAMPLE, float)] * 2))), label="p"
    )
    k = data.draw(st.one_of(st.sampled_from([1, 2, 3]), ANY_SCALAR), label="k")
    fam = data.draw(st.one_of(st.just(family), ANY_SCALAR), label="family")
    clamp = data.draw(st.one_of(st.booleans(), ANY_SCALAR), label="clamp")
    pattern = r"control point|degree|\bk\b|family|clamp|no effect|overflow"
    result = check(lambda: lb.optimal_lambda(points, k, fam, clamp=clamp), pattern)
    if result is not None and isinstance(result.unconstrained, float):  # the float path
        exact_pts = [[Fraction(float(v)) for v in row] for row in np.asarray(points, dtype=float)]
        want = lb.optimal_lambda(exact_pts, k, fam).unconstrained
        assert result.unconstrained == pytest.approx(float(want), rel=1e-8, abs=1e-12)
    check(lambda: lb.energy_coefficients(points, k, fam), pattern)
    n = data.draw(st.one_of(st.integers(0, 14), ANY_SCALAR), label="n")
    check(lambda: lb.energy_matrices(n, k, fam), r"degree|\bk\b|family")


@settings(max_examples=100)
@given(family=st.sampled_from(list(lb.FAMILIES)), data=st.data())
def test_fuzz_evaluate_many(family, data):
    size = SIZES[family]
    base = np.stack([np.array(POLYGON[:size], dtype=float)] * 2)
    points = data.draw(
        st.one_of(
            st.just(base),
            st.integers(-320, 308).map(lambda e: base / 10 * 10.0**e),
            bad_points(size),
            st.just(base.astype(complex)),
        ),
        label="points",
    )
    t = data.draw(st.one_of(st.lists(st.floats(0, 1), max_size=3), ANY_SCALAR), label="t")
    lam = LAM[family]
    if data.draw(st.booleans()):
        lam = data.draw(st.one_of(ANY_SCALAR, st.lists(ANY_SCALAR, max_size=3)), label="lam")
    k = data.draw(st.one_of(st.integers(0, 3), BAD_SCALARS), label="k")
    fam = data.draw(st.one_of(st.just(family), BAD_SCALARS), label="family")
    pattern = r"control point|curve \d|degree|\bt\b|\blam\b|\bk\b|family|shape param|overflow"
    check(lambda: lb.evaluate_many(points, t, fam, lam, k=k), pattern)


@settings(max_examples=120)
@given(data=st.data())
def test_fuzz_join_and_composite(data):
    first = data.draw(
        st.sampled_from(
            [
                lb.SameDegreeCurve(P, lam=Fraction(1, 2)),
                lb.BernsteinLikeCurve(np.array(P) * 1e300, lam=0.25),
                lb.BezierCurve(np.array(P) * 1e-300),
                lb.SameDegreeCurve(P, lam=0.5),
            ]
        ),
        label="first",
    )
    cont = data.draw(st.one_of(st.sampled_from(["C1", "C2", "G1", "G2"]), BAD_SCALARS))
    alpha = data.draw(st.one_of(st.just(1), ANY_SCALAR), label="alpha")
    d = data.draw(st.one_of(st.just(0), ANY_SCALAR), label="d")
    if isinstance(cont, str) and cont.startswith("C"):
        alpha, d = 1, 0
    lam = data.draw(st.one_of(st.just(0), ANY_SCALAR), label="lam")
    degree = data.draw(st.one_of(st.integers(1, 5), BAD_SCALARS), label="degree")
    rest = data.draw(
        st.one_of(
            st.just([(9, -1), (10, 1)]),
            st.just([(9, -1)]),
            st.just(np.array([(9.0, -1.0), (10.0, 1.0)]) * 1e300),
            st.lists(st.tuples(ANY_SCALAR, ANY_SCALAR), max_size=3),
            BAD_SCALARS,
        ),
        label="rest",
    )
    fam = data.draw(st.one_of(st.none(), st.sampled_from(list(lb.FAMILIES)), BAD_SCALARS))
    pattern = (
        r"continuity|alpha|\bd\b|\blam\b|degree|rest|family|control point|degenerate|"
        r"cannot solve|shape parameter|overflow|too extreme"
    )
    comp = lb.CompositeCurve([first])
    grown = check(lambda: comp.join(cont, degree, lam, alpha, d, rest, fam), pattern)
    if grown is None:
        return
    u = data.draw(st.one_of(ANY_SCALAR, st.lists(st.floats(0, 2), max_size=3)), label="u")
    check(lambda: grown.evaluate(u), r"\bu\b|overflow")
    check(lambda: grown.curvature(u), r"\bu\b|overflow", nan_ok=True)
    tol = data.draw(st.one_of(st.just(1e-9), ANY_SCALAR), label="tol")
    check(lambda: grown.report(tol), r"\btol\b|overflow")
    index = data.draw(st.one_of(st.integers(-1, 2), BAD_SCALARS), label="index")
    check(lambda: grown.with_lambda(index, lam), r"index|\blam\b|cannot keep|classical")


@settings(max_examples=100)
@given(
    continuity=st.one_of(st.sampled_from(["C1", "g2", " G1 "]), BAD_SCALARS),
    alpha=st.one_of(st.just(1), ANY_SCALAR),
    d=st.one_of(st.just(0), ANY_SCALAR),
    joints=st.one_of(st.none(), st.lists(st.one_of(st.none(), BAD_SCALARS), max_size=2)),
    name=st.one_of(st.sampled_from(["C0", "G1"]), BAD_SCALARS),
)
def test_fuzz_joint_and_composite_construction(continuity, alpha, d, joints, name):
    joint = check(lambda: lb.Joint(continuity, alpha, d), r"continuity|alpha|\bd\b")
    if joint is not None:
        assert joint.continuity in ("C1", "C2", "G1", "G2")
    segs = [lb.BezierCurve(P), lb.BezierCurve(np.array(P) + [4, 0])]
    comp = check(lambda: lb.CompositeCurve(segs, joints), r"joint|continuity")
    if comp is not None:
        report = comp.report()[0]
        check(lambda: report.holds(name), "continuity")


# ------------------------------------------------------------------ the command line

WORDS = st.one_of(
    st.sampled_from(
        [
            "0,6",
            "-1,2",
            "-.5,-0.25",
            "1/2,-3/4",
            "5,2,1",
            "7,0",
            "2,0",
            "6,8",
            "1" * 400 + ",2",
            "0,１",
            "٣,1",
            "1e5,0",
            "nan,0",
            "1/0,2",
            "-",
            "--",
            "-1",
            "--clamp",
            "--json",
            "--family",
            "bernstein_like",
            "-k",
            "２",
            "4",
            "--energy=3",
            "--bogus",
            "",
        ]
    ),
    st.text(alphabet="0123456789-+./,ab １", max_size=8),
)


FIXTURE_OK = [HealthCheck.function_scoped_fixture]  # capsys is read (and so reset) per example


@settings(max_examples=150, suppress_health_check=FIXTURE_OK)
@given(words=st.lists(WORDS, max_size=9))
def test_fuzz_cli_optimal_lambda(words, capsys):
    try:
        code = main(["optimal-lambda", *words])
    except SystemExit as exc:  # argparse: usage error (2) or --help (0)
        code = exc.code
    out, err = capsys.readouterr()
    assert code in (0, 2), (code, err)
    assert "Traceback" not in out + err
    if code == 2:
        assert "error" in err


@settings(max_examples=40, suppress_health_check=FIXTURE_OK)
@given(
    command=st.sampled_from(["derive", "verify", "nothing", ""]),
    words=st.lists(
        st.sampled_from(
            [
                "--check",
                "--root",
                "/nonexistent",
                "-q",
                "--only",
                "x",
                "--format",
                "yaml",
                "--strict",
                "--errata",
                "-1,2",
                "--bogus",
                "１",
            ]
        ),
        max_size=4,
    ),
)
def test_fuzz_cli_other_subcommands_parse_cleanly(command, words, monkeypatch, capsys):
    """Parsing and dispatch only (derive and verify themselves have their own tests)."""
    from lambda_bezier import _derive_runner, _verify_runner

    monkeypatch.setattr(_derive_runner, "run", lambda **kw: 0)
    monkeypatch.setattr(_verify_runner, "run_from_args", lambda args: 0)
    try:
        code = main([command, *words])
    except SystemExit as exc:
        code = exc.code
    assert code in (0, 2)
    assert "Traceback" not in capsys.readouterr().err


def test_cli_negative_coordinates_as_typed(capsys):
    assert main(["optimal-lambda", "0,6", "-1,2", "5,2", "7,0", "2,0", "6,8"]) == 0
    assert "optimal λ       -1507/683" in capsys.readouterr().out
    assert main(["optimal-lambda", "--clamp", "-.5,-1/2", "-1,2", "5,-2", "-k", "1"]) in (0, 2)
    assert "unrecognized" not in capsys.readouterr().err


def test_cli_400_digit_coordinate(capsys):
    big = "1" + "0" * 399
    assert main(["optimal-lambda", "0,6", f"{big},2", "5,2", "7,0", "2,0", "6,8"]) == 0
    out = capsys.readouterr().out
    energy = lb.optimal_lambda([(0, 6), (int(big), 2), (5, 2), (7, 0), (2, 0), (6, 8)], 2)
    mantissa = float(energy.unconstrained_energy / 10**799)  # the energy is far beyond a float
    assert f"≈ {mantissa:.11f}e+799" in out, out[-300:]
    assert main(["optimal-lambda", "--json", "0,6", f"{big},2", "5,2", "7,0", "2,0", "6,8"]) == 0
    assert '"energy_decimal": null' in capsys.readouterr().out


@pytest.mark.parametrize("word", ["0,１", "٣,1", "1,2\u00a0", "-k２"])
def test_cli_refuses_non_ascii_digits(word, capsys):
    argv = ["optimal-lambda", "0,6", "5,2", "7,0", "2,0"]
    argv += ["-k", "２"] if word == "-k２" else [word]
    try:
        code = main(argv)
    except SystemExit as exc:
        code = exc.code
    assert code == 2
    assert "not a number" in capsys.readouterr().err or word == "-k２"


def test_cli_version(capsys):
    with pytest.raises(SystemExit) as info:
        main(["--version"])
    assert info.value.code == 0
    assert capsys.readouterr().out.strip() == f"lambda-bezier {lb.__version__}"


def test_report_of_a_join_near_the_float_limit_warns_nothing():
    # found by test_fuzz_join_and_composite: a C2 join whose free points are ~1e301 made the
    # joint report's norms overflow (numpy RuntimeWarning in the squares); the norms are now
    # taken scaled, and every number in the report is finite
    comp = lb.CompositeCurve([lb.SameDegreeCurve(P, lam=Fraction(1, 2))])
    grown = comp.join("C2", 4, 0, 1, 0, np.array([(9.0, -1.0), (10.0, 1.0)]) * 1e300, None)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        (report,) = grown.report(1e-9)
    assert "C0" in report.achieved
    assert all(
        math.isfinite(x)
        for x in (report.position_gap, report.first_derivative_gap, report.speed_ratio)
    )
