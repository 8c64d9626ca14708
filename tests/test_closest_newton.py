"""closest_point without numba (hazmat/closest_numpy.py, issue #29): the compiled kernel's
certified branch and bound on the Bernstein form of |p − q|², breadth first over a batch in
numpy, or query by query on Python floats for a few queries. Checked in exact rationals (the
control points' floats are exact Fractions; the Bernstein form at a Fraction t is exact):
an interior answer is a critical point of the distance to near the rounding of g, and no
point of a fine exact grid is nearer than the answer beyond rounding."""

from __future__ import annotations

from fractions import Fraction
from math import comb

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

import lambda_bezier as lb
from lambda_bezier.hazmat import extremes


def _exact_g(pts: np.ndarray, q: np.ndarray, t: float) -> tuple[Fraction, Fraction]:
    """(g(t), the scale of its rounding, (|p(t)| + |q|)·|p'(t)| summed over coordinates),
    exactly."""
    n = len(pts) - 1
    x = Fraction(t)
    rows = [[Fraction(float(v)) for v in row] for row in pts]

    def bern(ctrl, degree):
        return [
            sum(
                comb(degree, i) * x**i * (1 - x) ** (degree - i) * ctrl[i][c]
                for i in range(degree + 1)
            )
            for c in range(len(ctrl[0]))
        ]

    p = bern(rows, n)
    hodo = [[n * (b - a) for a, b in zip(rows[i], rows[i + 1], strict=True)] for i in range(n)]
    dp = bern(hodo, n - 1)
    off = [p[c] - Fraction(float(q[c])) for c in range(len(p))]
    g = sum(o * d for o, d in zip(off, dp, strict=True))
    scale = sum(
        (abs(v) + abs(Fraction(float(w)))) * abs(d) for v, w, d in zip(p, q, dp, strict=True)
    )
    return g, scale


def _numpy_closest(pts: np.ndarray, queries: np.ndarray, few: bool):
    """closest_point without numba, breadth first (few=False) or query by query."""
    saved = extremes.USE_COMPILED, extremes.BREADTH_FIRST_FROM
    extremes.USE_COMPILED = False
    extremes.BREADTH_FIRST_FROM = 10**9 if few else 1
    try:
        return lb.BezierCurve(pts).closest_point(queries)
    finally:
        extremes.USE_COMPILED, extremes.BREADTH_FIRST_FROM = saved


def _exact_distance2(pts: np.ndarray, q: np.ndarray, t: Fraction) -> Fraction:
    n = len(pts) - 1
    rows = [[Fraction(float(v)) for v in row] for row in pts]
    point = [
        sum(comb(n, i) * t**i * (1 - t) ** (n - i) * rows[i][c] for i in range(n + 1))
        for c in range(len(rows[0]))
    ]
    return sum((x - Fraction(float(y))) ** 2 for x, y in zip(point, q, strict=True))


@pytest.mark.parametrize("few", [False, True])
@given(degree=st.integers(3, 8), dim=st.integers(2, 3), seed=st.integers(0, 2**32 - 1))
@example(degree=8, dim=2, seed=29)
def test_interior_answers_are_critical_points(few, degree, dim, seed):
    """Bracketed Newton inside a settled interval reaches g = 0 to 1e-10 of its scale."""
    rng = np.random.default_rng(seed)
    pts = rng.normal(size=(degree + 1, dim))
    queries = rng.normal(size=(6, dim)) * 1.5
    got = _numpy_closest(pts, queries, few)
    for q, t in zip(queries, got.t, strict=True):
        if 1e-9 < t < 1 - 1e-9:
            g, scale = _exact_g(pts, q, float(t))
            assert abs(g) <= 1e-10 * scale + 1e-300, (float(g), float(scale))


@pytest.mark.parametrize("few", [False, True])
@settings(max_examples=25, deadline=None)
@given(degree=st.integers(1, 8), dim=st.integers(2, 3), seed=st.integers(0, 2**32 - 1))
@example(degree=4, dim=2, seed=5)
def test_no_grid_point_is_nearer(few, degree, dim, seed):
    """The answer is the global minimum: at none of 129 exact grid points t = k/128 is the
    exact squared distance smaller than the answer's by more than its rounding (an answer at
    a local minimum only, or a dropped interval, is beaten there by far more)."""
    rng = np.random.default_rng(seed)
    pts = rng.normal(size=(degree + 1, dim))
    queries = rng.normal(size=(3, dim)) * 1.5
    got = _numpy_closest(pts, queries, few)
    for q, t, dist in zip(queries, got.t, got.distance, strict=True):
        answer = _exact_distance2(pts, q, Fraction(float(t)))
        assert abs(float(answer) - float(dist) ** 2) <= 1e-12 * (1 + float(answer))
        grid = min(_exact_distance2(pts, q, Fraction(k, 128)) for k in range(129))
        assert answer <= grid + Fraction(1, 10**12), (float(answer), float(grid))


def test_the_three_engines_agree():
    """Breadth first, query by query and (where installed) compiled: the same distances."""
    rng = np.random.default_rng(8)
    for degree in (1, 2, 3, 5, 8, 12):
        for dim in (2, 3):
            pts = rng.normal(size=(degree + 1, dim))
            queries = rng.normal(size=(300, dim)) * 2
            wide = _numpy_closest(pts, queries, few=False)
            one_by_one = _numpy_closest(pts, queries, few=True)
            np.testing.assert_allclose(wide.distance, one_by_one.distance, rtol=0, atol=1e-13)
            if extremes.USE_COMPILED:
                fast = lb.BezierCurve(pts).closest_point(queries)
                np.testing.assert_allclose(fast.distance, wide.distance, rtol=0, atol=1e-13)


def test_blocks_and_crowded_queries_give_the_same_answers(monkeypatch):
    """Queries split into blocks, and those with many live intervals finished depth first
    (closest_numpy.BLOCK, CROWDED, here forced small), answer as one breadth-first search."""
    from lambda_bezier.hazmat import closest_numpy

    rng = np.random.default_rng(12)
    pts = rng.normal(size=(8, 2))
    queries = rng.normal(size=(200, 2)) * 1.5
    whole = _numpy_closest(pts, queries, few=False)
    monkeypatch.setattr(closest_numpy, "BLOCK", 7)
    monkeypatch.setattr(closest_numpy, "CROWDED", 1)
    calls = []
    few = closest_numpy.closest_few
    monkeypatch.setattr(
        closest_numpy, "closest_few", lambda *args: calls.append(len(args[2])) or few(*args)
    )
    cut = _numpy_closest(pts, queries, few=False)
    assert sum(calls) > 0  # some queries were crowded
    np.testing.assert_allclose(cut.distance, whole.distance, rtol=0, atol=1e-13)
