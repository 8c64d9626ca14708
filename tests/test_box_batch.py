"""The vectorised certified minimum of many polynomials over one box (hazmat.box_batch),
the certificate of batches of nets with several parameters a direction (issue #31 item 2).

References: exact minimisers of quadratics with rational data (interior, and on a face where
the unconstrained one lies outside the box); a polynomial with two global minima, which no
certificate of a unique minimiser may accept; and, for surface energies, each net's one-net
certified minimum (exact Bernstein branch and bound, param_surface_energy) on the same nets.
"""

from __future__ import annotations

import numpy as np
import pytest
from conftest import surface_families

import lambda_bezier as lb
from lambda_bezier.hazmat import box_batch

TRIG, TWO, _, _, _ = surface_families()


def _quadratic(a: np.ndarray, c: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(coeffs (1, M), exponents (M, P)) of (x − c)ᵀ A (x − c), expanded into monomials."""
    dims = len(c)
    rows: dict[tuple[int, ...], float] = {}

    def add(e: list[int], v: float) -> None:
        rows[tuple(e)] = rows.get(tuple(e), 0.0) + v

    for i in range(dims):
        for j in range(dims):
            e = [0] * dims
            e[i] += 1
            e[j] += 1
            add(e, a[i, j])
            e1 = [0] * dims
            e1[i] += 1
            add(e1, -a[i, j] * c[j])
            e2 = [0] * dims
            e2[j] += 1
            add(e2, -a[i, j] * c[i])
            add([0] * dims, a[i, j] * c[i] * c[j])
    keys = sorted(rows)
    return np.array([[rows[k] for k in keys]]), np.array(keys)


A = np.array([[4.0, 1.0, 0.5, 0.0], [1.0, 3.0, 0.25, 0.5], [0.5, 0.25, 2.0, 0.0], [0, 0.5, 0, 1]])
LO, HI = np.full(4, -2.0), np.full(4, 2.0)


def test_an_interior_minimiser_is_found_within_the_tolerance():
    c = np.array([0.5, -0.75, 1.25, 0.125])  # exact in binary: the minimiser exactly
    coeffs, exponents = _quadratic(A, c)
    start = np.zeros((1, 4))
    x, e, delta, ok = box_batch.certified_minimum(coeffs, exponents, LO, HI, start, 1e-12)
    assert ok[0] and delta[0] <= 1e-12
    assert np.abs(x[0] - c).max() <= delta[0]
    assert abs(e[0]) <= 1e-12


def test_a_minimiser_on_a_face_is_found_with_the_face_held():
    """c outside the box in its first coordinate: with A diagonal the minimiser is c clipped
    (x_1 = 2, the others c's)."""
    a = np.diag([4.0, 3.0, 2.0, 1.0])
    c = np.array([3.0, -0.75, 1.25, 0.125])
    coeffs, exponents = _quadratic(a, c)
    x, e, delta, ok = box_batch.certified_minimum(
        coeffs, exponents, LO, HI, np.zeros((1, 4)), 1e-12
    )
    assert ok[0]
    assert x[0, 0] == 2.0 and np.abs(x[0, 1:] - c[1:]).max() <= delta[0]
    assert e[0] == pytest.approx(4.0, rel=1e-14)  # 4 (2 − 3)²


def test_two_global_minima_are_declined():
    """x⁴ − 2x² + y² + z² + w² has its minimum −1 at x = ±1: no unique minimiser, so the
    certificate must decline whatever its start."""
    exponents = np.array([[4, 0, 0, 0], [2, 0, 0, 0], [0, 2, 0, 0], [0, 0, 2, 0], [0, 0, 0, 2]])
    coeffs = np.array([[1.0, -2.0, 1.0, 1.0, 1.0]] * 3)
    starts = np.array([[0.9, 0.1, 0.0, 0.0], [-1.1, 0.0, 0.2, 0.0], [0.0, 0.0, 0.0, 0.0]])
    _, _, _, ok = box_batch.certified_minimum(coeffs, exponents, LO, HI, starts, 1e-12)
    assert not ok.any()


@pytest.mark.parametrize(("fam", "energy"), [(TRIG, "membrane"), (TWO, "thin_plate")])
def test_the_vectorised_certificate_agrees_with_each_nets_exact_branch_and_bound(fam, energy):
    nets = np.random.default_rng(23).normal(size=(6, 4, 4, 3))
    got = lb.optimal_parameters(nets, energy, family=fam)
    assert got.careful_fallbacks < len(nets)  # the vectorised certificate took some
    names = sorted(got.parameters)
    for i in range(len(nets)):
        one = lb.optimal_parameters(nets[i], energy, family=fam)
        lower, best = float(one.lower_bound), float(one.energy)
        slack = 1e-12 * abs(best)
        assert lower - slack <= got.energy[i] <= best + slack
        for name in names:  # the one-net point is certified in energy only: ~sqrt(1e-12)
            assert abs(float(one[name]) - got[name][i]) <= 1e-5
        assert got.boundary[i] == one.boundary


def test_a_minimiser_near_a_face_is_certified_with_r_cut_at_the_face():
    """c inside the box but nearer its face x_1 = 2 than any R's half-width (1/128 of the
    side is 1/32): certified at c (exact in binary), R cut at the face."""
    c = np.array([2 - 2.0**-8, -0.75, 1.25, 2.0**-9 - 2])
    coeffs, exponents = _quadratic(A, c)
    x, e, delta, ok = box_batch.certified_minimum(
        coeffs, exponents, LO, HI, np.zeros((1, 4)), 1e-12
    )
    assert ok[0] and delta[0] <= 1e-12
    assert np.abs(x[0] - c).max() <= delta[0]


def test_a_minimiser_within_half_the_tolerance_of_a_face_is_put_on_it():
    """c a few ulps inside the face x_1 = 2: the returned point is on the face, and c within
    its δ (the certificate is of the point on the face, not of the float search's)."""
    c = np.array([2 - 2.0**-45, -0.75, 1.25, 0.125])
    coeffs, exponents = _quadratic(np.diag([4.0, 3.0, 2.0, 1.0]), c)
    x, _, delta, ok = box_batch.certified_minimum(
        coeffs, exponents, LO, HI, np.zeros((1, 4)), 1e-12
    )
    assert ok[0] and x[0, 0] == 2.0
    assert np.abs(x[0] - c).max() <= delta[0] <= 1e-12


@pytest.mark.parametrize("shape", [(3, 3), (3, 3, 3, 3), (5, 2, 3)])
def test_the_exact_gradient_is_the_fractions_one_rounded(shape):
    """_exact_gradient (integers times powers of two) against the gradient computed in
    Fractions (box_convex.derivative, box_forms.value) and rounded once: equal bit for bit,
    on coefficients and points over ten decades, with zeros among them."""
    from fractions import Fraction

    from lambda_bezier.hazmat.box_convex import derivative
    from lambda_bezier.hazmat.box_forms import value

    rng = np.random.default_rng(1)
    power = rng.normal(size=(20, *shape)) * 10.0 ** rng.integers(-5, 5, size=(20, *shape))
    power[rng.random(power.shape) < 0.2] = 0.0
    x = rng.normal(size=(20, len(shape))) * 10.0 ** rng.integers(-3, 3, size=(20, len(shape)))
    x[0, 0] = 0.0
    got, bound = box_batch._exact_gradient(power, x)
    for k in range(20):
        exact = np.empty(shape, dtype=object)
        for idx, c in np.ndenumerate(power[k]):
            exact[idx] = Fraction(float(c))
        point = tuple(Fraction(float(v)) for v in x[k])
        for i in range(len(shape)):
            want = value(derivative(exact, i), point)
            assert got[k, i] == float(want)
            assert abs(Fraction(float(got[k, i])) - want) <= Fraction(float(bound[k, i]))
