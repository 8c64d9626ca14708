"""Rational curves whose weights span many binades, evaluated near the end where the weights
are tiny: the float rational form of a fast-decaying hyperbolic family (weights 1 .. 7e-17)
was 3e-8 off near t = 1, because the homogeneous de Casteljau ran in the form a + t (b - a),
which is not relatively accurate there. References: mpmath at 40 digits, from the family's
definition and from the rational form's own points and weights."""

from __future__ import annotations

from fractions import Fraction
from pathlib import Path

import mpmath as mp
import numpy as np
import pytest

import lambda_bezier as lb

FAMILIES = Path(__file__).parent / "data" / "families"
POINTS = [(0, 0), (1, 2), (3, 1)]


def _definition(t: float, lam: float) -> list[float]:
    """The hyp_fast_decay curve from its functions (its TOML), in mpmath."""
    with mp.workdps(40):
        x = mp.mpf(t)
        b0 = mp.e ** (-40 * x)
        b2 = mp.mpf(lam) * (mp.e ** (-20 * x) - mp.e ** (-40 * x))
        b = (b0, 1 - b0 - b2, b2)
        return [float(sum(b[i] * POINTS[i][k] for i in range(3))) for k in range(2)]


def _rational(points: np.ndarray, weights: np.ndarray, s: float) -> list[float]:
    with mp.workdps(40):
        x = mp.mpf(s)
        n = len(weights) - 1
        num = [mp.mpf(0)] * points.shape[1]
        den = mp.mpf(0)
        for i in range(n + 1):
            b = mp.binomial(n, i) * x**i * (1 - x) ** (n - i) * mp.mpf(weights[i])
            den += b
            for k in range(points.shape[1]):
                num[k] += b * mp.mpf(points[i, k])
        return [float(v / den) for v in num]


@pytest.fixture(scope="module")
def fast_decay():
    fam = lb.load_family(FAMILIES / "hyp_fast_decay.toml")
    return fam.curve(POINTS, lam=0.5)


def test_float_rational_form_near_the_end(fast_decay):
    form = fast_decay.to_rational_bezier()
    assert float(form.weights.min()) < 1e-15  # the case: weights over ~17 binades
    t = np.concatenate([np.linspace(0, 1, 201), 1 - np.logspace(-1, -9, 41)])
    got = form.evaluate(fast_decay.s_of_t(t))
    want = np.array([_definition(x, 0.5) for x in t])
    assert np.abs(got - want).max() < 1e-14 * 3  # the curve's size is about 3


@pytest.mark.parametrize("method", ["evaluate", "de_casteljau"])
def test_wide_weights_against_mpmath(method):
    weights = np.array([1.0, 1e-4, 1e-9, 1e-17])
    points = np.array([[0.0, 0.0], [1.0, 3.0], [2.0, -1.0], [1.5, 0.25]])
    curve = lb.RationalBezierCurve(points, weights)
    s = np.concatenate([np.linspace(0, 1, 51), 1 - np.logspace(-2, -12, 21)])
    got = getattr(curve, method)(s)
    want = np.array([_rational(points, weights, x) for x in s])
    # relative to the points' size: the positive combinations keep every digit
    assert np.abs(got - want).max() < 1e-14 * 3
    assert np.allclose(getattr(curve, method)(float(s[-1])), want[-1], rtol=0, atol=3e-14)


def test_exact_wide_weights_unchanged():
    """Exact rows, weights 1 .. 1e-16: float evaluation near the end against C(s) in Fractions."""
    w = [Fraction(1), Fraction(1, 10**6), Fraction(1, 10**16)]
    pts = [(Fraction(0), Fraction(0)), (Fraction(1), Fraction(2)), (Fraction(2), Fraction(1, 3))]
    curve = lb.RationalBezierCurve(pts, w)
    s = Fraction(0.999999)  # a float, exactly: C changes 1e6 times faster than s here
    exact = curve.exact_derivative(s, 0)  # C(s) in Fractions
    got = curve.evaluate(float(s))
    assert np.abs(got - np.array([float(v) for v in exact])).max() < 1e-14
