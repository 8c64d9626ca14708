"""Endpoint closed forms (derived in general n) against numeric differentiation of curves."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import curves
from hypothesis import given
from hypothesis import strategies as st
from lambda_bezier._generated import bernstein, bernstein_like, same_degree
from reference import FAMILIES

MODULES = {"same_degree": same_degree, "bernstein_like": bernstein_like}


def _closed_form_derivative(module, curve, r: int, end: str) -> np.ndarray:
    pts, n, lam = curve.points, curve.degree, curve.lam
    table = (module.endpoint_start if end == "start" else module.endpoint_end)(n, lam)
    out = np.zeros(curve.dimension)
    for (order, idx), weight in table.items():
        if order == r:
            out += float(weight) * pts[idx if end == "start" else n - idx]
    return out


def _one_sided(curve, r: int, end: str, h: float = 1e-3) -> np.ndarray:
    """Finite differences from inside [0, 1] (fourth-order accurate one-sided stencils)."""
    sign = 1 if end == "start" else -1
    t0 = 0.0 if end == "start" else 1.0
    f = [curve.evaluate(t0 + sign * s * h) for s in range(6)]
    if r == 0:
        return f[0]
    if r == 1:
        d = (-25 * f[0] + 48 * f[1] - 36 * f[2] + 16 * f[3] - 3 * f[4]) / (12 * h)
        return sign * d
    d2 = (45 * f[0] - 154 * f[1] + 214 * f[2] - 156 * f[3] + 61 * f[4] - 10 * f[5]) / (12 * h**2)
    return d2


@pytest.mark.parametrize("name", list(MODULES))
@given(data=st.data())
def test_endpoint_closed_forms_against_finite_differences(name, data):
    curve, pts, _ = data.draw(curves(FAMILIES[name], max_degree=9))
    scale = (1 + np.abs(curve.points).max()) * (curve.polynomial_degree + 1) ** 6
    for end in ("start", "end"):
        for r, tol in ((0, 1e-12), (1, 1e-9), (2, 1e-6)):
            want = _one_sided(curve, r, end)
            got = _closed_form_derivative(MODULES[name], curve, r, end)
            np.testing.assert_allclose(got, want, atol=tol * scale, err_msg=f"{end} r={r}")


@pytest.mark.parametrize("name", list(MODULES))
def test_endpoint_closed_forms_every_degree_exactly(name):
    """For every degree, the closed forms equal the runtime's derivatives at the ends, which
    come from the per-degree tables (a different derivation path)."""
    import lambda_bezier as lb

    module = MODULES[name]
    rng = np.random.default_rng(7)
    for n in module.DEGREES:
        pts = rng.normal(size=(n + 1, 2))
        curve = lb.FAMILIES[name](pts, 0.375)
        for end, t in (("start", 0.0), ("end", 1.0)):
            for r in range(3):
                np.testing.assert_allclose(
                    _closed_form_derivative(module, curve, r, end),
                    curve.derivative(t, r),
                    atol=1e-8 * (n + 3) ** 2,
                    err_msg=f"n={n} {end} r={r}",
                )


def test_bezier_kth_derivative_every_order():
    import lambda_bezier as lb

    rng = np.random.default_rng(3)
    for n in bernstein.DEGREES:
        pts = rng.normal(size=(n + 1, 3))
        curve = lb.BezierCurve(pts)
        for k in range(n + 1):
            start = sum(
                float(bernstein.endpoint_weight_start(n, k, i)) * pts[i] for i in range(k + 1)
            )
            end = sum(
                float(bernstein.endpoint_weight_end(n, k, i)) * pts[n - i] for i in range(k + 1)
            )
            tol = 1e-9 * abs(float(bernstein.endpoint_weight_start(n, k, 0))) * 2**k
            np.testing.assert_allclose(curve.derivative(0.0, k), start, atol=tol)
            np.testing.assert_allclose(curve.derivative(1.0, k), end, atol=tol)
