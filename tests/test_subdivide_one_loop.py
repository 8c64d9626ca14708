"""Issue #29: intersect_subdivide's numpy loop is one loop (_subdivide) for pairs of curves
and for curves against points. Each use is compared here with the compiled loops
(intersect_compiled.isolate and isolate_points, written separately) on inputs where every
branch is taken: points on the curves (roots), points at self-crossings and ends, tangent
pairs (pieces left at the depth), shared-stretch rectangles skipped, a curve against itself."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import assert_same_isolated as same
from conftest import on_both_subdivision_paths as both

from lambda_bezier.hazmat import intersect_subdivide as sub

pytest.importorskip("numba", reason="numba is not installed (pip install '.[fast]'): no twin")


def on_curve(curves: np.ndarray, t: np.ndarray) -> np.ndarray:
    work = curves.copy()
    while work.shape[1] > 1:
        work = work[:, :-1] + t[:, None, None] * (work[:, 1:] - work[:, :-1])
    return work[:, 0]


@pytest.mark.parametrize("degree", [1, 2, 3, 5])
def test_points_on_the_curves(degree):
    rng = np.random.default_rng(degree)
    curves = rng.normal(size=(60, degree + 1, 2))
    t = np.concatenate([rng.uniform(0, 1, 40), np.zeros(10), np.ones(10)])
    points = on_curve(curves, t)
    slow, fast = both(lambda: sub.isolate_points(curves, points, np.full(60, 1e-13)))
    same(slow, fast)
    assert slow.root_pair.size + slow.left_pair.size >= 60  # every point is found


def test_points_at_a_self_crossing_and_a_cusp():
    loop = np.array([[[0.0, 0.0], [2.0, 2.0], [-1.0, 2.0], [1.0, 0.0]]])  # crosses itself
    cusp = np.array([[[0.0, 0.0], [1.0, 1.0], [0.0, 1.0], [1.0, 0.0]]])  # p' = 0 at 1/2
    curves = np.concatenate([loop, cusp])
    points = np.array([[0.5, 0.5], on_curve(cusp, np.array([0.5]))[0]])
    crossing = points.copy()
    # the loop's self-crossing point: where its two branches meet (found by the engine)
    import lambda_bezier as lb

    hits = lb.BezierCurve(loop[0]).self_intersections()
    crossing[0] = on_curve(loop, np.array([hits[0].s]))[0]
    slow, fast = both(lambda: sub.isolate_points(curves, crossing, np.full(2, 1e-13)))
    same(slow, fast)
    assert np.count_nonzero(slow.root_pair == 0) == 2  # both branches


def test_tangent_pairs_leave_pieces_at_the_depth():
    rng = np.random.default_rng(7)
    a = rng.normal(size=(12, 4, 2))
    # each curve reflected in its own tangent line at t = 0.4: tangent there
    t = np.full(12, 0.4)
    work = a.copy()
    while work.shape[1] > 2:
        work = work[:, :-1] + t[:, None, None] * (work[:, 1:] - work[:, :-1])
    point = work[:, 0] + t[:, None] * (work[:, 1] - work[:, 0])
    tangent = work[:, 1] - work[:, 0]
    unit = tangent / np.linalg.norm(tangent, axis=1)[:, None]
    rel = a - point[:, None]
    along = np.einsum("kid,kd->ki", rel, unit)[..., None] * unit[:, None]
    b = point[:, None] + 2 * along - rel
    slow, fast = both(lambda: sub.isolate(a, b, np.full(12, 1e-13), depth=20))
    same(slow, fast)
    assert slow.left_pair.size > 0


def test_skipped_rectangles_and_a_curve_against_itself():
    rng = np.random.default_rng(11)
    a = rng.normal(size=(20, 5, 2))
    b = a.copy()  # each pair shares all of itself: the rectangle is skipped
    skip = [(k, 0.0, 0.5, 0.0, 0.5) for k in range(20)]
    slow, fast = both(lambda: sub.isolate(a, b, np.full(20, 1e-13), skip, depth=12))
    same(slow, fast)
    slow, fast = both(lambda: sub.isolate(a, None, np.full(20, 1e-13)))
    same(slow, fast)
