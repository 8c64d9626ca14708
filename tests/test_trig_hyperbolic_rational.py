"""The rational Bézier form of hyperbolic curves in floats (issue #30): u = tanh(ω0 (t − lo)/2)
makes a hyperbolic curve rational, but its scale tanh(ω0 (hi − lo)/2) is irrational, so the
form is given in floats. Checked against the typed-in definitions at 30 digits (mpmath)."""

from __future__ import annotations

import math
from fractions import Fraction as F
from pathlib import Path

import mpmath
import numpy as np
import pytest
from test_trig_runtime import hyp  # the hyp_cubic family's basis in mpmath

import lambda_bezier as lb
from lambda_bezier import _atom_geometry as ag

DATA = Path(__file__).parent / "data" / "families"


def hyp_shift(t, lam):
    e = mpmath.cosh(2 * t) - mpmath.sinh(2 * t)
    return [e, 1 - e - lam * mpmath.sinh(t) ** 2, lam * mpmath.sinh(t) ** 2]


CASES = [
    ("hyp_cubic", hyp, {"lam": F(1, 3), "mu": F(3, 4)}, [(0, 0), (1, 3), (3, -1), (4, 1)]),
    (
        "hyp_cubic",
        hyp,
        {"lam": 0.9, "mu": 0.05},
        [(1e3, -2e3), (3e3, 1e3), (-1e3, 4e3), (2e3, 2e3)],
    ),
    ("hyp_shift_quadratic", hyp_shift, {"lam": F(1, 2)}, [(0, 0, 1), (1, 2, -1), (3, 1, 2)]),
]


@pytest.mark.parametrize(("name", "basis", "params", "points"), CASES)
def test_float_rational_form_within_1e14(name, basis, params, points):
    fam = lb.load_family(DATA / f"{name}.toml")
    curve = fam.curve(points, **params)
    rat = curve.to_rational_bezier()
    assert not rat.is_exact and (np.asarray(rat.weights) > 0).all()
    lo, hi = fam.domain
    t = np.linspace(lo, hi, 301)
    got = rat.evaluate(curve.s_of_t(t))
    mpmath.mp.dps = 30
    vals = [float(v) for v in params.values()]
    want = np.array(
        [
            [
                float(
                    sum(b * p[c] for b, p in zip(basis(mpmath.mpf(x), *vals), points, strict=True))
                )
                for c in range(len(points[0]))
            ]
            for x in t
        ]
    )
    size = np.abs(np.asarray(points, float)).max()
    assert np.abs(got - want).max() <= 1e-14 * size
    # the ends of the domain are s = 0 and s = 1 exactly
    assert curve.s_of_t(lo) == 0.0 and curve.s_of_t(hi) == 1.0
    assert np.allclose(curve.t_of_s(curve.s_of_t(t)), t, rtol=0, atol=1e-14)


def test_geometry_goes_through_the_float_form():
    fam = lb.load_family(DATA / "hyp_cubic.toml")
    curve = fam.curve([(0, 0), (1, 3), (3, -1), (4, 1)], lam=F(1, 2), mu=F(1, 4))
    q = np.random.default_rng(2).normal(size=(20, 2)) * 3
    fast, slow = curve.closest_point(q), ag.closest_point(curve, q)
    assert np.abs(fast.distance - slow.distance).max() < 1e-12
    assert np.allclose(curve.evaluate(fast.t), fast.point, atol=1e-12)
    lo_r, hi_r = curve.bounding_box()
    lo_n, hi_n = ag.bounding_box(curve)
    assert np.allclose(lo_r, lo_n, atol=1e-13) and np.allclose(hi_r, hi_n, atol=1e-13)
    # split, refused before (no exact rational form), is now the float form split at s(t)
    left, right = curve.split(0.4)
    assert np.allclose(left.evaluate(1.0), curve.evaluate(0.4), atol=1e-14)
    assert np.allclose(right.evaluate(1.0), curve.evaluate(1.0), atol=1e-14)
    assert curve.locate(curve.evaluate(0.7)) == pytest.approx(0.7, abs=1e-10)
    assert curve.arc_length() == pytest.approx(curve.to_rational_bezier().arc_length(), rel=1e-12)


def test_export_writes_one_nurbs_span():
    from lambda_bezier import export

    fam = lb.load_family(DATA / "hyp_cubic.toml")
    curve = fam.curve([(0, 0), (1, 3), (3, -1), (4, 1)], lam=F(1, 2), mu=F(1, 4))
    spline = export.to_bspline(curve)
    assert (
        spline.weights is not None
        and len(spline.control_points) == curve.to_rational_bezier().degree + 1
    )
    s = 0.37
    assert np.allclose(
        np.asarray(spline.point(s), float), curve.evaluate(curve.t_of_s(s)), atol=1e-14
    )
    assert math.isclose(float(curve.t_of_s(1.0)), 1.0, rel_tol=1e-15)
