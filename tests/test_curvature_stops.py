"""Curvature at a stop or a cusp whose computed C'(t) is rounding, not 0: every curve class
treats |C'(t)| within the rounding of its evaluation as 0 and raises the ValueError naming t
(never 1e+31), while a tight but regular turn keeps its curvature, checked against an exact
or 50-digit computation independent of the class's evaluation."""

from __future__ import annotations

from collections.abc import Callable
from fractions import Fraction as F

import mpmath
import numpy as np
import pytest
import sympy as sp

import lambda_bezier as lb
from lambda_bezier import examples

_TRIG = lb.load_family(examples.path("han_trig_cubic.toml"))
_CB = lb.load_family(examples.path("c_bezier_cubic.toml"))

MAKERS: dict[str, Callable[[object], object]] = {
    "bezier": lambda p: lb.BezierCurve(p),
    "same_degree": lambda p: lb.SameDegreeCurve(p, lam=F(1, 2)),
    "rational": lambda p: lb.RationalBezierCurve(p, [1, 2, 1, 3]),
    "atom_trig": lambda p: _TRIG.curve(p, lam=F(1, 2), mu=0),
    "c_bezier": lambda p: _CB.curve(p, alpha=2.0),
}


def _domain(curve: object) -> tuple[float, float]:
    lo, hi = getattr(curve, "domain", (0.0, 1.0))
    return float(lo), float(hi)


# ---------------------------------------------------------------------- stops at an end
@pytest.mark.parametrize("name", sorted(MAKERS))
@pytest.mark.parametrize(
    "points, end",
    [
        ([(0, 0), (0, 0), (3, 2), (4, 0)], 0),  # the lead's example: P0 = P1
        ([(0.1, 0.7), (0.1, 0.7), (3.3, 2.1), (4.9, -0.3)], 0),
        ([(0, 0), (1, 2), (4.3, 0.1), (4.3, 0.1)], 1),  # P2 = P3: stops at the end
    ],
)
def test_a_stop_at_an_end_raises_naming_t(name, points, end):
    curve = MAKERS[name](points)
    t = _domain(curve)[end]
    with pytest.raises(ValueError, match=f"undefined at t = {t}"):
        curve.curvature(t)
    assert np.isnan(curve._curvature(t))  # plots and joint reports: a gap, not 1e31
    inner = (t + _domain(curve)[1 - end]) / 2
    assert np.isfinite(curve.curvature(inner))


@pytest.mark.parametrize("name", sorted(MAKERS))
def test_a_stop_in_3d_has_no_torsion(name):
    curve = MAKERS[name]([(0, 0, 0), (0, 0, 0), (3, 2, 1), (4, 0, 2)])
    with pytest.raises(ValueError, match="undefined at t = 0.0"):
        curve.torsion(0.0)
    with pytest.raises(ValueError, match="undefined at t = 0.0"):
        curve.curvature(0.0)


def test_the_atom_tangent_at_a_stop_is_undefined():
    curve = MAKERS["atom_trig"]([(0, 0), (0, 0), (3, 2), (4, 0)])
    with pytest.raises(ValueError, match="tangent is undefined"):
        curve.tangent(0.0)
    assert np.isclose(np.linalg.norm(curve.tangent(0.4)), 1.0)


# ---------------------------------------------------------------------- interior cusps
@pytest.mark.parametrize("name", sorted(MAKERS))
def test_an_interior_cusp_raises(name):
    """P2 solved from C'(t0) = Σ b_i'(t0) P_i = 0 (C' is linear in the points for fixed
    weights and parameters; b_i'(t0) read off the curves of the unit points), t0 not dyadic
    so the computed C'(t0) is rounding, not 0."""
    make = MAKERS[name]
    lo, hi = _domain(make([(0, 0), (1, 0), (2, 1), (3, 0)]))
    t0 = lo + 0.37 * (hi - lo)
    unit = [make([(1.0, 0.0) if j == i else (0.0, 0.0) for j in range(4)]) for i in range(4)]
    b1 = [float(c.derivative(t0)[0]) for c in unit]
    p0, p1, p3 = np.array([0.0, 0.0]), np.array([1.0, 2.0]), np.array([4.0, 0.5])
    p2 = -(b1[0] * p0 + b1[1] * p1 + b1[3] * p3) / b1[2]
    curve = make([p0, p1, p2, p3])
    with pytest.raises(ValueError, match=f"undefined at t = {t0}"):
        curve.curvature(np.array([lo + 0.1 * (hi - lo), t0]))
    assert np.isnan(curve._curvature(t0))
    near = curve.curvature(np.array([t0 - 0.01 * (hi - lo), t0 + 0.01 * (hi - lo)]))
    assert np.isfinite(near).all()  # regular beside the cusp


# ---------------------------------------------------------------------- tight regular turns
def _kappa(d1, d2) -> float:
    x1, y1 = (mpmath.mpf(sp.Rational(v).p) / sp.Rational(v).q for v in d1)
    x2, y2 = (mpmath.mpf(sp.Rational(v).p) / sp.Rational(v).q for v in d2)
    return float((x1 * y2 - y1 * x2) / mpmath.power(x1 * x1 + y1 * y1, 1.5))


def _exact_kappa_at(numerators, weights, s):
    """κ at s of Σ w_i P_i B_i / Σ w_i B_i in SymPy (Fractions in, exact derivatives)."""
    t = sp.Symbol("t")
    n = len(numerators) - 1
    bern = [sp.binomial(n, i) * t**i * (1 - t) ** (n - i) for i in range(n + 1)]
    w = sum(sp.Rational(wi) * b for wi, b in zip(weights, bern, strict=True))
    xy = [
        sum(
            sp.Rational(wi) * sp.Rational(p[k]) * b
            for wi, p, b in zip(weights, numerators, bern, strict=True)
        )
        / w
        for k in range(2)
    ]
    d1 = [sp.diff(c, t).subs(t, s) for c in xy]
    d2 = [sp.diff(c, t, 2).subs(t, s) for c in xy]
    return _kappa(d1, d2)


@pytest.mark.parametrize("delta", [F(1, 10**5), F(1, 10**9)])
def test_a_tight_regular_turn_keeps_its_curvature(delta):
    """P1 = P0 + δ (1, 0): κ(0) grows like 1/δ but is defined. Relative error of the float
    value ~ eps |P| / |C'(0)| ~ 1e-16 / δ, so rtol = 1e4 eps / δ (2e-7 at δ = 1e-5)."""
    pts = [
        (F(1, 10), F(7, 10)),
        (F(1, 10) + delta, F(7, 10)),
        (F(33, 10), F(21, 10)),
        (F(49, 10), F(-3, 10)),
    ]
    rtol = max(1e-9, 1e4 * np.finfo(float).eps / float(delta))
    fpts = [tuple(float(v) for v in p) for p in pts]

    expected = _exact_kappa_at(pts, [1, 1, 1, 1], 0)
    assert lb.BezierCurve(pts).curvature(0.0) == pytest.approx(expected, rel=rtol)
    expected = _exact_kappa_at(pts, [1, 2, 1, 3], 0)
    assert lb.RationalBezierCurve(fpts, [1, 2, 1, 3]).curvature(0.0) == pytest.approx(
        expected, rel=rtol
    )

    same = lb.SameDegreeCurve(pts, lam=F(1, 2))
    m = same.basis_bernstein_matrix(exact=True)  # the Bézier points Q = M^T P, exact
    q = [tuple(sum(F(m[i][j]) * pts[i][k] for i in range(4)) for k in range(2)) for j in range(4)]
    assert lb.SameDegreeCurve(fpts, lam=F(1, 2)).curvature(0.0) == pytest.approx(
        _exact_kappa_at(q, [1, 1, 1, 1], 0), rel=rtol
    )

    # the trigonometric curve: its exact rational form (t = 0 is s = 0, s increasing in t:
    # signed curvature is a property of the oriented geometry)
    trig = _TRIG.curve(pts, lam=F(1, 2), mu=0)
    rat = trig.to_rational_bezier()
    assert float(trig.s_of_t(0.0)) == 0.0
    expected = _exact_kappa_at(rat.control_points(), rat.weights.tolist(), 0)
    assert _TRIG.curve(fpts, lam=F(1, 2), mu=0).curvature(0.0) == pytest.approx(expected, rel=rtol)


@pytest.mark.parametrize("delta", [1e-5, 1e-9])
def test_a_tight_c_bezier_turn_matches_50_digits(delta):
    """C-Bézier: the family's float basis coefficients over its atoms (cos t, 1, t, sin t)
    differentiated and summed at t = 0 in 50-digit mpmath, not through the curve's centred
    evaluation."""
    pts = np.array([(0.1, 0.7), (0.1 + delta, 0.7), (3.3, 2.1), (4.9, -0.3)])
    curve = _CB.curve(pts, alpha=2.0)
    coeffs = curve.basis_coefficients  # (n+1, atoms) in t on [0, alpha]
    derivs = {
        1: {("cos", 1): 0, ("pow", 0): 0, ("pow", 1): 1, ("sin", 1): 1},
        2: {("cos", 1): -1, ("pow", 0): 0, ("pow", 1): 0, ("sin", 1): 0},
    }
    with mpmath.workdps(50):
        d = {
            k: [
                sum(
                    mpmath.mpf(float(coeffs[i, a])) * derivs[k][atom] * mpmath.mpf(float(pts[i, c]))
                    for i in range(4)
                    for a, atom in enumerate(_CB.atoms)
                )
                for c in range(2)
            ]
            for k in (1, 2)
        }
        (x1, y1), (x2, y2) = d[1], d[2]
        expected = float((x1 * y2 - y1 * x2) / mpmath.power(x1 * x1 + y1 * y1, 1.5))
    rtol = max(1e-9, 1e4 * np.finfo(float).eps / delta)
    assert curve.curvature(0.0) == pytest.approx(expected, rel=rtol)


def test_a_composite_joint_report_keeps_an_atom_stop_undefined():
    stops = MAKERS["atom_trig"]([(0, 0), (1, 2), (3, 2), (3, 2)])  # stops at its end
    after = MAKERS["atom_trig"]([(3, 2), (4, 1), (5, 3), (6, 0)])
    report = lb.CompositeCurve([stops, after]).report()[0]
    assert np.isnan(report.curvature[0])  # was -1e+31: the joint's "undefined" field
    assert np.isfinite(report.curvature[1])
