"""Classical Bézier toolkit: the lecture notes' worked examples, exactly, and properties."""

from __future__ import annotations

from fractions import Fraction as F

import numpy as np
import pytest
from conftest import curves
from hypothesis import given
from hypothesis import strategies as st
from reference import FAMILIES

import lambda_bezier as lb


def test_subdivision_example_t_one_third():
    """002, §三 分割实例: p(1/3) of (0,0),(1,3),(2,1),(3,3)."""
    c = lb.BezierCurve([(0, 0), (1, 3), (2, 1), (3, 3)])
    left, right = c.split(F(1, 3))
    assert left.control_points() == ((0, 0), (F(1, 3), 1), (F(2, 3), F(13, 9)), (1, F(5, 3)))
    assert right.control_points() == ((1, F(5, 3)), (F(5, 3), F(19, 9)), (F(7, 3), F(5, 3)), (3, 3))


def test_segment_example_quarter_to_three_quarters():
    """002, §三 任意分割 example: the piece between P(1/4) and P(3/4)."""
    c = lb.BezierCurve([(-9, 0), (-3, 6), (3, 6), (9, 0)])
    first, _ = c.split(F(3, 4))
    assert first.control_points() == (
        (-9, 0),
        (F(-9, 2), F(9, 2)),
        (0, F(45, 8)),
        (F(9, 2), F(27, 8)),
    )
    seg = c.segment(F(1, 4), F(3, 4))
    assert seg.control_points() == (
        (F(-9, 2), F(27, 8)),
        (F(-3, 2), F(39, 8)),
        (F(3, 2), F(39, 8)),
        (F(9, 2), F(27, 8)),
    )


@given(data=st.data())
def test_split_and_segment_reparametrise(data):
    curve, pts, _ = data.draw(curves(FAMILIES["bezier"]))
    t = data.draw(st.floats(0.05, 0.95))
    left, right = curve.split(t)
    u = np.linspace(0, 1, 9)
    np.testing.assert_allclose(left.evaluate(u), curve.evaluate(t * u), atol=1e-9 * 20)
    np.testing.assert_allclose(right.evaluate(u), curve.evaluate(t + (1 - t) * u), atol=1e-9 * 20)
    t1, t2 = sorted(data.draw(st.tuples(st.floats(0, 0.45), st.floats(0.55, 1))))
    seg = curve.segment(t1, t2)
    np.testing.assert_allclose(seg.evaluate(u), curve.evaluate(t1 + (t2 - t1) * u), atol=1e-8 * 20)


@given(data=st.data())
def test_elevation_and_hodograph(data):
    curve, pts, _ = data.draw(curves(FAMILIES["bezier"], max_degree=13))
    u = np.linspace(0, 1, 9)
    up = curve.elevate()
    assert up.degree == curve.degree + 1
    np.testing.assert_allclose(up.evaluate(u), curve.evaluate(u), atol=1e-9 * 20)
    if curve.degree >= 2:
        hod = curve.hodograph()
        assert hod.degree == curve.degree - 1
        np.testing.assert_allclose(hod.evaluate(u), curve.derivative(u), atol=1e-8 * 200)


def test_exact_elevation_and_hodograph():
    c = lb.BezierCurve([(0, 0), (1, 3), (2, 1), (3, 3)])
    assert c.hodograph().control_points() == ((3, 9), (3, -6), (3, 6))
    assert c.elevate().control_points()[1] == (F(3, 4), F(9, 4))


def test_de_casteljau_matches_evaluate():
    c = lb.BezierCurve([(0, 0), (1, 3), (2, 1), (3, 3), (5, 0)])
    t = np.linspace(0, 1, 11)
    np.testing.assert_allclose(c.de_casteljau(t), c.evaluate(t), atol=1e-12)


def test_bad_split_arguments():
    c = lb.BezierCurve([(0, 0), (1, 3), (2, 1), (3, 3)])
    for t in (0, 1, F(3, 2)):
        with pytest.raises(ValueError, match="0 < t < 1"):
            c.split(t)
    with pytest.raises(ValueError, match="t1 < t2"):
        c.segment(F(1, 2), F(1, 4))
    with pytest.raises(ValueError, match="no shape parameter"):
        lb.BezierCurve.__mro__[1].__init__(c, [(0, 0), (1, 1)], 0.5)
