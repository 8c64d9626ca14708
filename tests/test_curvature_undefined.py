"""Curvature where the first derivative vanishes is undefined: every curve class says so by a
ValueError naming the parameter, never NaN; where it is defined the value is the formula's."""

from fractions import Fraction

import numpy as np
import pytest

import lambda_bezier as lb
from lambda_bezier import examples


def test_a_rational_curve_that_stops_names_t():
    still = lb.RationalBezierCurve([(1, 1), (1, 1), (1, 1)], [1, 2, 1])
    with pytest.raises(ValueError, match=r"undefined at t = 0\.25"):
        still.curvature([0.25, 0.5])


def test_a_rational_cusp_is_undefined_only_at_the_cusp():
    # x = 2t(1 - t)w1 / w, y likewise: a curve that goes out and comes back along one line
    cusp = lb.RationalBezierCurve([(0, 0), (1, 1), (0, 0)], [1, 3, 1])
    with pytest.raises(ValueError, match=r"undefined at t = 0\.5"):
        cusp.curvature(0.5)
    assert np.allclose(cusp.curvature([0.2, 0.8]), 0.0)  # straight elsewhere


def test_an_atom_curve_that_stops_names_t():
    fam = lb.load_family(examples.path("han_trig_cubic.toml"))
    still = fam.curve([(2, 3)] * 4, lam=0, mu=0)
    with pytest.raises(ValueError, match="undefined at t"):
        still.curvature(0.3)
    # a genuine curve of the family: finite everywhere on a grid
    arc = fam.curve([(0, 0), (1, 0), (2, 1), (2, 2)], lam=Fraction(1, 2), mu=0)
    assert np.isfinite(arc.curvature(np.linspace(0.0, np.pi / 2, 9))).all()


def test_a_composite_names_u_and_its_report_says_undefined():
    cusp = lb.BezierCurve([(0, 0), (2, 0), (0, 0)])  # p'(1/2) = 0: a cusp at u = 0.5
    b = lb.BezierCurve([(0, 0), (0, 1), (1, 2)])
    with pytest.raises(ValueError, match=r"undefined at u = 0\.5"):
        lb.CompositeCurve([cusp, b]).curvature([0.25, 0.5, 1.5])
    stops = lb.BezierCurve([(0, 0), (1, 0), (1, 0)])  # p'(1) = 0 at the joint
    comp = lb.CompositeCurve([stops, lb.BezierCurve([(1, 0), (2, 0), (3, 1)])])
    report = comp.report()[0]
    assert np.isnan(report.curvature[0])  # the joint report keeps "undefined" as a field
    assert np.isfinite(report.curvature[1])
