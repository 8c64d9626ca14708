"""Issue #29: the certified fast paths, on both engines (numba and numpy).

- intersection: the certificate (hazmat.intersect_certify) answers only where the careful
  path gives the same answer, and declines (None) at ends, tangencies, near-double crossings
  and shared stretches;
- closest_point: the compiled branch and bound gives the global minimum (never above the
  companion-matrix path or a dense sampling) on random curves and queries.
"""

from __future__ import annotations

from fractions import Fraction as F

import numpy as np
import pytest
from conftest import careful_path as careful
from hypothesis import given, settings
from hypothesis import strategies as st

import lambda_bezier as lb
from lambda_bezier.hazmat import extremes
from lambda_bezier.hazmat import intersect as engine
from lambda_bezier.hazmat import intersect_certify as cert

pytestmark = pytest.mark.usefixtures("intersect_engine")


def certified(p: lb.BezierCurve, q: lb.BezierCurve):
    return cert.certify_one(
        p._prepared.pts, q._prepared.pts, engine.BOX_SLACK, engine.ROOT_RESIDUAL, engine.SETTLE
    )


float_curve = st.integers(1, 5).flatmap(
    lambda n: st.lists(
        st.tuples(
            st.floats(-4, 4, allow_nan=False, width=32), st.floats(-4, 4, allow_nan=False, width=32)
        ),
        min_size=n + 1,
        max_size=n + 1,
    )
)


@settings(max_examples=60, deadline=None)
@given(a=float_curve, b=float_curve)
def test_certified_answers_are_the_careful_answers(a, b):
    p, q = lb.BezierCurve(a), lb.BezierCurve(b)
    try:
        slow = careful(p, q)
    except ValueError:
        return  # a point, or curves on one line: refused by both (checked before the fast path)
    got = certified(p, q)
    if got is None:
        return  # declined: intersect gives the careful answer
    # flat lists: pytest.approx takes no nested (s, t) tuples
    assert [x for h in slow for x in (h.s, h.t)] == pytest.approx(
        [x for pair in zip(*got, strict=True) for x in pair], abs=1e-15
    )
    assert all(h.kind == "transversal" for h in slow)
    if cert.in_use():  # compiled: intersect answers with the certificate itself
        assert p.intersect(q) == [
            engine.Intersection(s, t, "transversal") for s, t in zip(*got, strict=True)
        ]


def test_most_crossings_are_certified():
    """Random cubics crossing in their interiors: the fast path answers nearly all (else it
    would be no faster), and its answers are the careful path's to the last bit."""
    rng = np.random.default_rng(29)
    answered = 0
    for _ in range(40):
        p = lb.BezierCurve(rng.uniform(-1, 1, size=(4, 2)))
        q = lb.BezierCurve(rng.uniform(-1, 1, size=(4, 2)))
        got = certified(p, q)
        if got is None:
            continue
        answered += 1
        slow = careful(p, q)
        assert [(h.s, h.t) for h in slow] == list(zip(*got, strict=True))
    assert answered >= 35


@pytest.mark.parametrize(
    ("a", "b", "why"),
    [
        # both ends of one curve on the other: two end hits, located by the careful path
        ([(0.25, 0.375), (0.75, 0.375)], [(0, 0), (0.5, 1), (1, 0)], "ends"),
        # a tangency: the parabola touches the line
        ([(-1, 1), (0, -1), (1, 1)], [(-1, 0), (1, 0)], "tangent"),
        # crossings 1e-3 apart (sine ~ 1e-3 ok) and 2e-7 apart (sine below SINE_MIN)
        ([(-1, 1.21), (0, -0.99), (1, 0.81)], [(-1, 1e-14), (1, 1e-14)], "near-double"),
        # a shared stretch
        ([(0, 0), (1, 2), (2, 0)], [(0, 0), (1, 2), (2, 0)], "coincident"),
    ],
)
def test_the_certificate_declines(a, b, why):
    p, q = lb.BezierCurve(a), lb.BezierCurve(b)
    assert certified(p, q) is None, why
    assert p.intersect(q) == careful(p, q)


def test_an_end_on_the_other_curve_is_certified_as_located():
    """A T-junction (round 21): the end point as the careful path locates it, to the bit."""
    p = lb.BezierCurve([(1, 0.5), (1, 2)])
    q = lb.BezierCurve([(0, 1), (1, 0), (2, 1)])
    got = certified(p, q)
    assert got is not None
    assert list(zip(*got, strict=True)) == [(h.s, h.t) for h in careful(p, q)] == [(0.0, 0.5)]


def test_crossings_1e3_apart_are_certified_and_exact():
    """The issue's parabola against y = 1e-6 (as floats): two transversal crossings the fast
    path isolates and refines to the careful path's bits."""
    p = lb.BezierCurve([(-1, 1.21), (0, -0.99), (1, 0.81)])
    q = lb.BezierCurve([(-1, 1e-6), (1, 1e-6)])
    got = certified(p, q)
    assert got is not None
    assert list(zip(*got, strict=True)) == [(h.s, h.t) for h in careful(p, q)]
    assert got[0] == pytest.approx([0.5495, 0.5505], abs=1e-12)


def test_exact_input_that_is_not_floats_goes_the_careful_way():
    p = lb.BezierCurve([(0, 0), (1, F(1, 3)), (2, 0)])
    q = lb.BezierCurve([(0, F(1, 10)), (2, F(1, 10))])
    assert not p._prepared.floats_exact
    assert q._prepared.floats_exact is False
    hits = p.intersect(q)
    assert len(hits) == 2 and hits == careful(p, q)
    # Fractions that are doubles are taken as the doubles they are
    assert lb.BezierCurve([(0, 0), (1, F(1, 4)), (2, 0)])._prepared.floats_exact


def test_the_certificate_runs_only_compiled(intersect_engine):
    assert cert.in_use() == (intersect_engine == "numba")


def test_intersect_many_uses_the_same_certificate():
    rng = np.random.default_rng(7)
    a = [lb.BezierCurve(rng.uniform(-1, 1, size=(4, 2))) for _ in range(12)]
    b = [lb.BezierCurve(rng.uniform(-1, 1, size=(4, 2))) for _ in range(12)]
    assert lb.intersect_many(a, b) == [p.intersect(q) for p, q in zip(a, b, strict=True)]


def test_three_dimensional_near_miss_is_not_a_crossing():
    """Skew curves passing 1e-9 apart: Gauss-Newton converges to the nearest approach, whose
    residual is far above the bound, so nothing is certified as a crossing."""
    p = lb.BezierCurve([(0, 0, 0), (1, 1, 0), (2, 0, 0)])
    q = lb.BezierCurve([(1, -1, 1e-9), (1, 2, 1e-9)])
    got = certified(p, q)
    assert got is None or got == ([], [])
    assert p.intersect(q) == careful(p, q)


# ---------------------------------------------------------------------------- closest point
@pytest.fixture(params=["compiled", "companion"])
def closest_engine(request):
    from importlib.util import find_spec

    if request.param == "compiled" and find_spec("numba") is None:
        pytest.skip("numba is not installed (pip install '.[fast]'): the compiled path")
    saved = extremes.USE_COMPILED
    extremes.USE_COMPILED = request.param == "compiled"
    yield request.param
    extremes.USE_COMPILED = saved


@pytest.mark.parametrize("degree", [1, 2, 3, 5, 8])
@pytest.mark.parametrize("dim", [2, 3])
def test_closest_point_is_the_global_minimum(closest_engine, degree, dim):
    rng = np.random.default_rng(degree * 10 + dim)
    curve = lb.BezierCurve(rng.normal(size=(degree + 1, dim)))
    queries = rng.normal(size=(300, dim)) * 2
    got = curve.closest_point(queries)
    u = np.linspace(0.0, 1.0, 20001)
    dense = np.sqrt(((curve.evaluate(u)[None] - queries[:, None]) ** 2).sum(-1)).min(axis=1)
    assert np.all(got.distance <= dense + 1e-12)
    assert np.all(got.distance >= dense - 1e-4)  # the samples are 5e-5 apart
    np.testing.assert_allclose(curve.evaluate(got.t), got.point, atol=1e-13)
    single = curve.closest_point(queries[0])
    assert single.distance == pytest.approx(got.distance[0], abs=1e-14)


def test_closest_point_engines_agree():
    from importlib.util import find_spec

    if find_spec("numba") is None:
        pytest.skip("numba is not installed: only one engine")
    rng = np.random.default_rng(3)
    saved = extremes.USE_COMPILED
    try:
        for degree in (3, 4, 7):
            curve = lb.SameDegreeCurve(rng.normal(size=(degree + 1, 2)), 0.5)
            queries = rng.normal(size=(200, 2))
            extremes.USE_COMPILED = True
            fast = curve.closest_point(queries)
            extremes.USE_COMPILED = False
            slow = curve.closest_point(queries)
            np.testing.assert_allclose(fast.distance, slow.distance, rtol=0, atol=1e-12)
    finally:
        extremes.USE_COMPILED = saved


def test_closest_point_hard_cases(closest_engine):
    # two equally near points (a symmetric arch, the query on its axis): either is the minimum
    arch = lb.BezierCurve([(-1, 0), (-1, 2), (1, 2), (1, 0)])
    hit = arch.closest_point((0, -5))
    assert hit.distance == pytest.approx(np.hypot(1, 5), abs=1e-12)
    # the query on the curve, at a cusp
    cusp = lb.BezierCurve([(0, 0), (2, 2), (0, 2), (2, 0)])
    on = cusp.evaluate(0.5)
    assert cusp.closest_point(on).distance <= 1e-12
    # a line, queries beyond either end
    line = lb.BezierCurve([(0, 0), (1, 0)])
    assert line.closest_point((-3, 1)).t == 0.0 and line.closest_point((4, 1)).t == 1.0
    # huge coordinates (the points are scaled by a power of two first)
    big = lb.BezierCurve(np.array([(0, 0), (1, 2), (2, 0)]) * 2.0**600)
    far = big.closest_point(np.array([1, 3]) * 2.0**600)
    assert far.t == pytest.approx(0.5, abs=1e-8) and far.distance == pytest.approx(2.0**601)


# ---------------------------------------------------------------------------- exact isolation
def test_exact_isolation_of_the_near_double_crossing():
    """The issue's parabola and line, exactly: two certified boxes, each holding one of the
    exact crossings s = t = 0.5495 and 0.5505 (checked in Fractions), and apart."""
    parabola = lb.BezierCurve([(-1, F(121, 100)), (0, F(-99, 100)), (1, F(81, 100))])
    line = lb.BezierCurve([(-1, F(1, 10**6)), (1, F(1, 10**6))])
    got = lb.intersect_exact(parabola, line)
    assert [c.certified for c in got] == [True, True]
    for box, root in zip(got, (F(5495, 10**4), F(5505, 10**4)), strict=True):
        assert box.s[0] <= root <= box.s[1] and box.t[0] <= root <= box.t[1]
    assert got[0].s[1] < got[1].s[0]


@settings(max_examples=25, deadline=None)
@given(
    a=st.lists(st.tuples(st.integers(-6, 6), st.integers(-6, 6)), min_size=3, max_size=4),
    b=st.lists(st.tuples(st.integers(-6, 6), st.integers(-6, 6)), min_size=2, max_size=3),
)
def test_exact_boxes_hold_the_float_crossings(a, b):
    """Every transversal crossing the float engine reports lies in exactly one certified box
    (and every certified box holds one of them), for random integer curves."""
    p, q = lb.BezierCurve(a), lb.BezierCurve(b)
    try:
        boxes = lb.intersect_exact(p, q)
        hits = p.intersect(q)
    except ValueError:
        return  # a shared component, a point, or a line folded on another: refused
    if any(h.kind != "transversal" for h in hits) or not all(c.certified for c in boxes):
        return  # tangencies: the boxes are not certified there
    slack = 1e-12
    for h in hits:
        inside = [
            c
            for c in boxes
            if c.s[0] - slack <= h.s <= c.s[1] + slack and c.t[0] - slack <= h.t <= c.t[1] + slack
        ]
        assert len(inside) == 1, (h, boxes)
    assert len(boxes) == len(hits), (boxes, hits)


def test_exact_isolation_bad_input():
    exact = lb.BezierCurve([(0, 0), (1, 1)])
    with pytest.raises(ValueError, match="not exact"):
        lb.intersect_exact(lb.BezierCurve([(0.5, 0), (1, 1)]), exact)
    with pytest.raises(ValueError, match="planar"):
        lb.intersect_exact(lb.BezierCurve([(0, 0, 0), (1, 1, 1)]), exact)
    with pytest.raises(TypeError, match="curve_b"):
        lb.intersect_exact(exact, [(0, 0), (1, 1)])
    with pytest.raises(ValueError, match="share a component"):
        lb.intersect_exact(
            lb.BezierCurve([(0, 0), (1, 2), (2, 0)]), lb.BezierCurve([(0, 0), (1, 2), (2, 0)])
        )


def test_compiled_cone_blur_is_the_numpy_one():
    pytest.importorskip("numba")
    from lambda_bezier.hazmat import intersect_subdivide, pieces_compiled

    assert pieces_compiled.BLUR == intersect_subdivide.BLUR
