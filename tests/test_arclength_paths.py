"""The arc-length rule's first level compiled (numba, the `fast` extra) and in numpy: the same
lengths, each against the independent mpmath reference of test_arclength, on the cases that
decide the first level's branches (accepted at once, refined, a hidden dip sent to the full
rule, a constant curve, coordinates near the float limits)."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
from test_arclength import (
    assert_close,
    hidden_dip_curve,
    kinked_curve,
    reference_length,
)

import lambda_bezier as lb
from lambda_bezier import geometry
from lambda_bezier.hazmat import arclength, kernels


@pytest.fixture(params=["numba", "numpy"])
def arc_path(request, monkeypatch):
    if request.param == "numba":
        pytest.importorskip("numba")
    monkeypatch.setattr(kernels, "USE_COMPILED", request.param == "numba")
    return request.param


def _fresh(curve):
    curve.__dict__.pop("_geometry_poly", None)  # nothing cached from the other path
    return curve


@pytest.mark.parametrize("x", [Fraction(3, 10), Fraction(5, 24), Fraction(0)])
@pytest.mark.parametrize("y", [0, Fraction(1, 10**3), Fraction(1, 10**9)])
def test_near_cusps_on_both_paths(arc_path, x, y):
    curve, deriv = kinked_curve(x, y, seed=3)
    assert_close(_fresh(curve).arc_length(), reference_length(deriv, 0, 1, x))


def test_a_hidden_dip_on_both_paths(arc_path):
    """A near-double zero of p' between the first level's nodes: the least speed there sends
    the curve to the full rule (the branch the compiled level must report the same way)."""
    curve, deriv, x = hidden_dip_curve()
    assert_close(_fresh(curve).arc_length(), reference_length(deriv, 0, 1, x))


@pytest.mark.parametrize("scale", [2.0**600, 1e-200])
def test_constant_and_extreme_curves_on_both_paths(arc_path, scale):
    assert _fresh(lb.BezierCurve([(1.0, 2.0)] * 4)).arc_length() == 0.0
    pts = np.array([(0.0, 0.0), (1.0, 2.0), (3.0, -1.0), (4.0, 0.5)])
    want = lb.BezierCurve(pts).arc_length()
    got = _fresh(lb.BezierCurve(pts * scale)).arc_length()
    assert got == pytest.approx(want * scale, rel=1e-13)


def test_compiled_and_numpy_first_levels_agree(monkeypatch):
    """Random curves of degrees 2..12 in 1..3 dimensions: the two first levels' lengths agree
    to rounding, and each path rejects the same pieces (but for a piece on the fence)."""
    pytest.importorskip("numba")
    rng = np.random.default_rng(29)
    for _ in range(200):
        degree, dim = int(rng.integers(2, 13)), int(rng.integers(1, 4))
        coeffs = geometry._poly(lb.BezierCurve(rng.normal(size=(degree + 1, dim))))[0]
        lengths, rejected = [], []
        for compiled in (True, False):
            monkeypatch.setattr(kernels, "USE_COMPILED", compiled)
            lengths.append(arclength.unit_integral(coeffs, 1e-12))
            scaled, _, _ = arclength._scaled(coeffs)
            first, weights, ones, *_ = arclength._unit_levels(scaled.shape[1])
            if compiled:
                size = np.empty((arclength._PIECES, 2))
                kernels.compiled().first_level(scaled, first, weights, arclength._PIECES, size)
            else:
                speed = arclength._norms(scaled.dot(first))
                size = np.abs(speed.reshape(arclength._PIECES, -1).dot(weights))
            rejected.append(size)
        assert lengths[0] == pytest.approx(lengths[1], rel=1e-14, abs=0)
        total = rejected[1][:, 1].sum()
        # the pieces' values to rounding; their rule differences (what rejects a piece, at
        # 1e-12 / 24 of the total) equal down to the rounding of the values, 1e-15 of it
        np.testing.assert_allclose(rejected[0][:, 1], rejected[1][:, 1], rtol=1e-13)
        np.testing.assert_allclose(rejected[0][:, 0], rejected[1][:, 0], atol=1e-15 * total)
        threshold = 1e-12 * total / arclength._PIECES
        far = np.abs(rejected[1][:, 0] - threshold) > 1e-15 * total  # not on the fence
        assert ((rejected[0][:, 0] > threshold) == (rejected[1][:, 0] > threshold))[far].all()


def test_compiled_first_decisions_are_unit_integrals(monkeypatch):
    """kernels_compiled.unit_first_level decides as unit_integral's Python steps on the
    same level: a length at once (code 0: accepted, or 0 for a constant curve) exactly when
    they return the level's total, scaling first (code 1) exactly when _scaled rescales,
    and otherwise the same sums for the rule to go on from (code 2), on random curves of
    degrees 2..12, near-cusps (rejected pieces) and huge and tiny coordinates among them."""
    pytest.importorskip("numba")
    rng = np.random.default_rng(13)
    compiled = kernels.compiled() or pytest.fail("numba is installed but not used")
    codes = set()
    for trial in range(300):
        degree, dim = int(rng.integers(2, 13)), int(rng.integers(1, 4))
        pts = rng.normal(size=(degree + 1, dim))
        if trial % 7 == 0:
            pts[1:] = pts[1]  # a straight segment, then a stop
        if trial % 11 == 0:
            pts = np.repeat(pts[:1], degree + 1, axis=0)  # constant
        if trial % 5 == 0:
            curve, _ = kinked_curve(Fraction(int(rng.integers(1, 9)), 10), 0, seed=trial)
            pts = np.array(curve.points, dtype=float)
        coeffs = geometry._poly(lb.BezierCurve(pts))[0] * float(rng.choice([1.0, 2.0**500]))
        first, weights, *_ = arclength._unit_levels(coeffs.shape[1])
        unit = arclength._hidden_unit(coeffs.shape[1])
        size = np.empty((arclength._PIECES, 2))
        code, spent, total, least, peak = compiled.unit_first_level(
            coeffs, first, weights, arclength._PIECES, 1e-12, unit, size
        )
        codes.add(code)
        scaled, factor, want_peak = arclength._scaled(coeffs)
        assert (code == 1) == (factor != 1.0)
        if code == 1:
            continue
        assert peak == want_peak
        level = np.empty((arclength._PIECES, 2))
        want = compiled.first_level(coeffs, first, weights, arclength._PIECES, level)
        assert (spent, total, least) == want
        np.testing.assert_array_equal(size, level)
        at_once = not want[1] > 0.0 or (
            want[2] > unit * dim * peak / arclength._PIECES**2 and want[0] <= 1e-12 * want[1]
        )
        assert (code == 0) == at_once
        hides = not want[2] > unit * dim * peak / arclength._PIECES**2
        if want[1] > 0.0 and want[0] > 0.0 and not hides:
            # a tolerance just either side of this curve's own spent / total
            for scale, accepted in ((0.99, False), (1.01, True)):
                rtol = want[0] / want[1] * scale
                args = (coeffs, first, weights, arclength._PIECES, rtol, unit, size)
                assert (compiled.unit_first_level(*args)[0] == 0) == accepted
    assert codes == {0, 1, 2}


def test_compiled_second_level_is_numpys():
    """kernels_compiled.second_level against unit_integral's numpy steps on the same
    rejected pieces (one, two or more of them): the parts' signed sums and least speeds to
    rounding, the totals and the least speed likewise."""
    pytest.importorskip("numba")
    compiled = kernels.compiled() or pytest.fail("numba is installed but not used")
    rng = np.random.default_rng(31)
    seen = 0
    for trial in range(60):
        x = Fraction(int(rng.integers(1, 99)), 100)
        curve, _ = kinked_curve(x, Fraction(1, 10 ** int(rng.integers(2, 6))), seed=trial)
        coeffs = geometry._poly(curve)[0]
        _, _, _, second, second_weights = arclength._unit_levels(coeffs.shape[1])
        bad = np.unique(rng.integers(0, arclength._PIECES, size=int(rng.integers(1, 4))))
        sums = np.empty((bad.size * arclength._SPLIT, 2))
        low = np.empty(bad.size * arclength._SPLIT)
        spent, total, least = compiled.second_level(coeffs, second, second_weights, bad, sums, low)
        speed = arclength._norms(np.concatenate([coeffs.dot(second[k]) for k in bad], axis=-1))
        want = speed.reshape(bad.size * arclength._SPLIT, -1).dot(second_weights)
        scale = np.abs(want[:, 1]).sum()
        np.testing.assert_allclose(sums, want, rtol=0, atol=1e-15 * scale)
        # speeds to rounding relative to the largest (p' is a sum of cancelling terms)
        top = speed.max()
        np.testing.assert_allclose(low, speed.reshape(low.size, -1).min(axis=1), atol=1e-14 * top)
        assert (spent, total) == pytest.approx(tuple(np.abs(want).sum(axis=0)), rel=1e-13)
        assert least == pytest.approx(speed.min(), rel=0, abs=1e-14 * top)
        seen += bad.size > 1
    assert seen
