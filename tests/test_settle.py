"""Issue #29: the careful path compiled (hazmat.settle_compiled, run by intersect where the
certificate declines) gives the careful path's answers: the same hits, the same kinds, the
parameters to the last bits (it evaluates residuals by compensated de Casteljau where the
careful path uses rationals), reports a stretch shared as one polynomial piece as the careful
path does, and declines where it says it does (a shared image under another
parameterisation, curves on one line), leaving those to the careful path in Python."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import careful_path as careful
from hypothesis import given, settings
from hypothesis import strategies as st

import lambda_bezier as lb
from lambda_bezier.hazmat import intersect as engine
from lambda_bezier.hazmat import intersect_certify as cert

pytest.importorskip("numba")


@pytest.fixture(autouse=True)
def _compiled_engine():
    from lambda_bezier.hazmat import intersect_subdivide

    before = intersect_subdivide.USE_COMPILED
    intersect_subdivide.USE_COMPILED = True
    yield
    intersect_subdivide.USE_COMPILED = before


def settled(a, b) -> list[engine.Intersection] | None:
    p, q = lb.BezierCurve(a)._prepared, lb.BezierCurve(b)._prepared
    got = cert.settle_one(p.pts, q.pts, engine.SETTLE)
    if got is None:
        return None
    return [engine.Intersection(s, t, engine._KINDS[k]) for s, t, k in got]


def assert_same(fast: list[engine.Intersection], slow: list[engine.Intersection]) -> None:
    assert [h.kind for h in fast] == [h.kind for h in slow], (fast, slow)
    for x, y in zip(fast, slow, strict=True):
        # a crossing to the last bit; a tangency's parameters are a double root's, known to
        # ~sqrt(eps) of the residual's rounding, so there a few ulps (the parity tests' 32)
        tol = 0.0 if x.kind == "transversal" else 32 * np.spacing(1.0)
        assert abs(x.s - y.s) <= tol and abs(x.t - y.t) <= tol, (fast, slow)


# pairs the certificate declines, each with its careful answer's kinds
SHAPES = {
    # an end of one curve on the other, transversal
    "end": ([(1.0, 0.5), (1.0, 2.0)], [(0.0, 1.0), (1.0, 0.0), (2.0, 1.0)], ["transversal"]),
    # the curves share an end point
    "shared end": ([(0.0, 0.0), (1.0, 2.0), (2.0, 0.0)], [(2.0, 0.0), (3.0, 1.0)], ["transversal"]),
    # a parabola touching a line
    "tangent": ([(-1.0, 1.0), (0.0, -1.0), (1.0, 1.0)], [(-1.0, 0.0), (1.0, 0.0)], ["tangent"]),
    # two arches touching at their tops
    "tangent arches": (
        [(0.0, 0.0), (0.5, 1.0), (1.0, 0.0)],
        [(0.0, 1.0), (0.5, 0.0), (1.0, 1.0)],
        ["tangent"],
    ),
    # tangent at an end of one curve
    "tangent at an end": (
        [(0.0, 0.0), (1.0, 0.0)],
        [(0.5, 0.0), (1.0, 0.0), (1.5, 1.0)],
        ["tangent"],
    ),
    # a tangency and two crossings (a cubic against the tangent at its inflection's side)
    "tangent and crossings": (
        [(0.0, 0.0), (1.0, 3.0), (2.0, -3.0), (3.0, 0.0)],
        [(0.0, 0.75), (3.0, 0.75)],
        None,
    ),
    # crossings 1e-3 apart: the certificate's sine bound declines, isolation separates them
    "near-double": (
        [(-1.0, 1.21), (0.0, -0.99), (1.0, 0.81)],
        [(-1.0, 1e-6), (1.0, 1e-6)],
        ["transversal", "transversal"],
    ),
    # three dimensions: an end on the other curve
    "3d end": (
        [(0.0, 0.0, 0.0), (1.0, 1.0, 1.0)],
        [(0.5, 0.5, 0.5), (1.0, 0.0, 2.0), (2.0, 1.0, 0.0)],
        ["transversal"],
    ),
}


@pytest.mark.parametrize("name", list(SHAPES))
def test_settled_is_the_careful_answer(name):
    a, b, kinds = SHAPES[name]
    slow = careful(a, b)
    fast = settled(a, b)
    assert fast is not None, "the compiled careful path declined"
    assert_same(fast, slow)
    if kinds is not None:
        assert [h.kind for h in fast] == kinds
    # and intersect answers with it
    assert lb.BezierCurve(a).intersect(lb.BezierCurve(b)) == fast


@pytest.mark.parametrize(
    ("a", "b"),
    [
        # one curve: a shared stretch
        ([(0.0, 0.0), (1.0, 2.0), (2.0, 0.0)], [(0.0, 0.0), (1.0, 2.0), (2.0, 0.0)]),
        # a piece of it, reversed
        ([(0.0, 0.0), (1.0, 2.0), (2.0, 0.0)], [(1.5, 0.75), (1.0, 1.25), (0.5, 0.75)]),
        # overlapping past its end: p([1/4, 1]) == q([0, 3/4]) (the shape of the bezier
        # package's fixture case 20), q(t) = p(t + 1/4)
        ([(0.0, 0.0), (2.0, 4.0), (4.0, 0.0)], [(1.0, 1.5), (3.0, 3.5), (5.0, -2.5)]),
    ],
)
def test_settled_shared_piece_is_the_careful_answer(a, b):
    """A stretch shared as one polynomial piece (an affine change of parameter): both ends,
    coincident, as the careful path reports them."""
    slow = careful(a, b)
    assert [h.kind for h in slow] == ["coincident", "coincident"]
    fast = settled(a, b)
    assert fast is not None, "the compiled careful path declined"
    assert fast == slow
    assert lb.BezierCurve(a).intersect(lb.BezierCurve(b)) == fast


@pytest.mark.parametrize(
    ("a", "b"),
    [
        # one arc under a parameterisation that is not affine: P(s) = Q(s^2)
        (
            [(0.0, 0.0), (0.0, 0.0), (1.0, 2.0), (3.0, 6.0), (6.0, 0.0)],
            [(0.0, 0.0), (3.0, 6.0), (6.0, 0.0)],
        ),
        # two segments of one line overlapping
        ([(0.0, 0.0), (2.0, 0.0)], [(1.0, 0.0), (3.0, 0.0)]),
    ],
)
def test_settle_declines_shared_images_and_lines(a, b):
    assert settled(a, b) is None
    try:
        want = careful(a, b)
    except ValueError:
        with pytest.raises(ValueError):
            lb.BezierCurve(a).intersect(lb.BezierCurve(b))
        return
    assert lb.BezierCurve(a).intersect(lb.BezierCurve(b)) == want


coordinate = st.integers(-6, 6).map(lambda k: k / 2)
small_curve = st.integers(1, 4).flatmap(
    lambda n: st.lists(st.tuples(coordinate, coordinate), min_size=n + 1, max_size=n + 1)
)


@settings(max_examples=80, deadline=None)
@given(a=small_curve, b=small_curve)
def test_settled_answers_are_careful_answers(a, b):
    """Small half-integer grids: shared ends, ends on the other curve, tangencies and
    shared stretches come up often."""
    try:
        slow = careful(a, b)
    except ValueError:
        return  # a point, or curves on one line: refused before either path runs
    fast = settled(a, b)
    if fast is None:
        assert any(h.kind == "coincident" for h in slow) or _on_one_line(a, b)
        return
    assert_same(fast, slow)


def _on_one_line(a, b) -> bool:
    pts = np.array(a + b, dtype=float)
    rel = pts - pts[0]
    return bool(np.linalg.matrix_rank(rel, tol=1e-9) <= 1)


def test_settle_is_not_run_without_numba_or_when_switched_off():
    a, b, _ = SHAPES["tangent"]
    from lambda_bezier.hazmat import intersect_subdivide

    intersect_subdivide.USE_COMPILED = False
    assert settled(a, b) is None
    intersect_subdivide.USE_COMPILED = True
    cert.USE_SETTLE = False
    try:
        assert settled(a, b) is None
    finally:
        cert.USE_SETTLE = True


@settings(max_examples=40, deadline=None)
@given(
    curve=small_curve,
    where=st.one_of(st.integers(0, 4).map(lambda k: k / 4), st.tuples(coordinate, coordinate)),
)
def test_point_isolation_is_the_batched_one(curve, where):
    """settle_compiled._isolate_point (depth first, for the end points) gives what
    intersect_compiled.isolate_points gives for one curve and one point: the same roots and
    left pieces, in the same order; a point on the curve (at u) or anywhere on the grid."""
    from lambda_bezier.hazmat import intersect_compiled, intersect_subdivide, settle_compiled

    pts = np.array(curve, dtype=float)
    if np.ptp(pts, axis=0).max() == 0.0:
        return  # a point: settle never gets one (the row guard would trip: the fallback)
    if isinstance(where, float):
        work = pts.copy()
        while work.shape[0] > 1:
            work = work[:-1] + where * (work[1:] - work[:-1])
        point = work[0]
    else:
        point = np.array(where, dtype=float)
    knobs = engine.SETTLE
    tol = engine.ON_CURVE * max(np.abs(pts).max(), np.abs(point).max())
    halves = intersect_subdivide.half_matrices(pts.shape[0] - 1)
    ok, root_s, left_s0, left_w = settle_compiled._isolate_point(
        pts, point, tol, *knobs[10:15], halves
    )
    _, want_s, _, want_s0, want_w = intersect_compiled.isolate_points(
        pts[None].copy(), point[None].copy(), np.array([tol]), *knobs[10:15], halves
    )
    assert ok
    assert root_s.tolist() == want_s.tolist()
    assert left_s0.tolist() == want_s0.tolist() and left_w.tolist() == want_w.tolist()
