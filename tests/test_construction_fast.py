"""Issue #29: the short way a small float array takes into a curve (as_points and
power_of_two_scale skip numpy's per-call cost there) gives what the general way gives: the
same read-only copy, the same refusals, the same scale."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import lambda_bezier as lb
from lambda_bezier import _validate as val

DEGREES = (0, 10**6)


def general(points: np.ndarray) -> np.ndarray:
    """as_points the general way: the same values given as nested lists."""
    return val.as_points(points.tolist(), family="bezier", degrees=DEGREES)


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
@pytest.mark.parametrize("where", [(0, 0), (1, 1), (2, 0)])
def test_non_finite_refused_by_name(bad, where):
    points = np.array([[0.0, 1.0], [2.0, 3.0], [4.0, 5.0]])
    points[where] = bad
    with pytest.raises(ValueError, match=rf"control point {where[0]} has a non-finite"):
        lb.BezierCurve(points)


def test_inf_and_minus_inf_refused():
    """inf + -inf is NaN: still not finite, still refused."""
    with pytest.raises(ValueError, match="non-finite"):
        lb.BezierCurve(np.array([[np.inf, 0.0], [-np.inf, 0.0]]))


def test_finite_points_whose_sum_overflows_are_accepted():
    """The sum overflows, every coordinate is finite: the general way decides (accepted)."""
    big = np.array([[1.7e308, 0.0], [1.7e308, 1.0], [1.7e308, 2.0]])
    curve = lb.BezierCurve(big)
    assert np.array_equal(curve.points, big)
    assert curve._scale == val.scale_for_magnitude(1.7e308) != 1.0


def test_a_read_only_c_contiguous_copy():
    given_points = np.asfortranarray(np.array([[0.0, 1.0], [2.0, 3.0], [4.0, 5.0]]))
    curve = lb.BezierCurve(given_points)
    given_points[0, 0] = 99.0  # the caller's array changes; the curve does not
    assert curve.points[0, 0] == 0.0
    assert curve.points.flags.c_contiguous and not curve.points.flags.writeable


def test_shape_refused_by_name():
    with pytest.raises(ValueError, match=r"shape \(n\+1, d\)"):
        lb.BezierCurve(np.zeros((3, 0)))


coordinate = st.floats(allow_nan=True, allow_infinity=True) | st.sampled_from(
    [1e300, -1e300, 5e-310, 1.7e308, -1.7e308, 0.0, -0.0]
)


@settings(max_examples=200, deadline=None)
@given(
    st.integers(1, 8).flatmap(
        lambda rows: st.lists(
            st.lists(coordinate, min_size=2, max_size=2), min_size=rows, max_size=rows
        )
    )
)
def test_short_way_is_the_general_way(rows):
    points = np.array(rows, dtype=float)
    try:
        expected = general(points)
    except ValueError as exc:
        with pytest.raises(ValueError, match=str(exc).split("(")[0]):
            val.as_points(points, family="bezier", degrees=DEGREES)
        return
    got = val.as_points(points, family="bezier", degrees=DEGREES)
    assert np.array_equal(got, expected) and not got.flags.writeable
    magnitude = float(np.abs(points).max())
    assert val.power_of_two_scale(got) == val.scale_for_magnitude(magnitude)
    assert math.isfinite(val.power_of_two_scale(got))


def test_large_arrays_take_the_general_way():
    points = np.linspace(0.0, 1.0, 200).reshape(100, 2)
    points[57, 1] = np.nan
    with pytest.raises(ValueError, match="control point 57 has a non-finite"):
        lb.BezierCurve(points)
    points[57, 1] = 2.0**1000
    assert val.power_of_two_scale(points) == 2.0**1000


finite = st.floats(-1e300, 1e300) | st.sampled_from([0.0, -0.0, 5e-324, -5e-324])


@settings(max_examples=200, deadline=None)
@given(
    st.integers(1, 40).flatmap(
        lambda rows: st.integers(2, 3).flatmap(
            lambda dim: st.lists(
                st.lists(finite, min_size=dim, max_size=dim), min_size=rows, max_size=rows
            )
        )
    )
)
def test_prepared_extent_is_numpys(rows):
    """The intersection solvers' span and scale, over lists for a few points and by numpy
    past that (40 rows of 2 or 3: both sides of the switch), are numpy's values."""
    from lambda_bezier.hazmat.intersect_prepared import Prepared

    pts = np.array(rows, dtype=float)
    prepared = Prepared(pts, None)
    assert prepared._span == float(np.ptp(pts, axis=0).max())
    assert prepared.scale == float(max(np.ptp(pts, axis=0).max(), np.abs(pts).max(), 1e-300))
    assert prepared.is_point == (float(np.ptp(pts, axis=0).max()) == 0.0)
