"""The fixed-cost certified batch optimum of (λ_u, λ_v) (hazmat.surface_certify, compiled in
hazmat.surface_batch_compiled): against the exact method on exact nets, against a dense grid
with local refinement on random float nets, on energies with two local minima, and the
declined nets counted and solved by the careful path; both engines."""

from __future__ import annotations

from fractions import Fraction
from importlib.util import find_spec

import numpy as np
import pytest
from scipy.optimize import minimize

import lambda_bezier as lb
from lambda_bezier.hazmat import surface_kernels
from lambda_bezier.hazmat.surface_certify import certified_minimum
from lambda_bezier.surface_energies import _float_polynomial, surface_energy_matrices


@pytest.fixture(params=["numpy", "numba"])
def engine(request, monkeypatch):
    if request.param == "numba" and find_spec("numba") is None:
        pytest.skip("numba is not installed (pip install '.[fast]'): the compiled engine")
    monkeypatch.setattr(surface_kernels, "USE_COMPILED", request.param == "numba")
    return request.param


def grid_nets(seed, count):
    nets = np.random.default_rng(seed).normal(size=(count, 4, 4, 3))
    nets[..., 0] += np.arange(4)[:, None]
    nets[..., 1] += np.arange(4)[None, :]
    return nets


def coefficient_arrays(e):
    return [np.array([float(e.get((a, b), 0.0))]) for a in range(3) for b in range(3)]


def reference_minimum(e, lo=-2.0, hi=1.0):
    """A dense grid, then local refinement (L-BFGS-B in the box) from its best few points."""
    ts = np.linspace(lo, hi, 301)
    xg, yg = np.meshgrid(ts, ts, indexing="ij")

    def energy(x, y):
        return sum(e[a, b] * x**a * y**b for a in range(3) for b in range(3))

    values = energy(xg, yg).ravel()
    best = (np.inf, 0.0, 0.0)
    for i in np.argsort(values)[:8]:
        start = np.array([xg.ravel()[i], yg.ravel()[i]])
        r = minimize(
            lambda p: energy(p[0], p[1]),
            start,
            method="L-BFGS-B",
            bounds=[(lo, hi), (lo, hi)],
            options={"ftol": 1e-15, "gtol": 1e-12, "maxiter": 500},
        )
        if r.fun < best[0]:
            best = (float(r.fun), float(r.x[0]), float(r.x[1]))
    return best


@pytest.mark.parametrize("energy", ["thin_plate", "membrane"])
def test_batch_agrees_with_a_dense_grid_and_refinement(engine, energy):
    nets = grid_nets(31, 40)
    res = lb.optimal_parameters(nets, energy)
    mats = surface_energy_matrices((3, 3), energy)
    coeffs = _float_polynomial(mats, nets.reshape(40, 16, 3))
    certified = 40 - res["careful_fallbacks"]
    assert certified >= 30  # the fixed-cost path answers most of these nets
    for i in range(40):
        e = np.zeros((3, 3))
        for (a, b), c in coeffs.items():
            e[a, b] = c[i]
        value, x, y = reference_minimum(e)
        # the reference is only a local optimiser's precision; ours is certified tighter
        assert res["energy"][i] <= value + 1e-10 * max(1.0, abs(value))
        assert abs(res["lam_u"][i] - x) <= 1e-5 and abs(res["lam_v"][i] - y) <= 1e-5


def test_batch_agrees_with_the_exact_method_on_exact_nets(engine):
    rng = np.random.default_rng(7)
    ints = rng.integers(-4, 5, size=(12, 4, 4, 3)).astype(float)
    ints[..., 0] += 3 * np.arange(4)[:, None]
    ints[..., 1] += 3 * np.arange(4)[None, :]
    res = lb.optimal_parameters(ints, "thin_plate")
    assert res["careful_fallbacks"] < 12
    for i in range(12):
        exact_net = [[[Fraction(int(c)) for c in p] for p in row] for row in ints[i]]
        one = lb.optimal_parameters(exact_net, "thin_plate")
        assert abs(one["lam_u_float"] - res["lam_u"][i]) <= 1e-12
        assert abs(one["lam_v_float"] - res["lam_v"][i]) <= 1e-12
        assert res["where"][i] == one["where"]


@pytest.mark.parametrize(
    "c1, c2",
    [(0.05, 0.05), (-0.05, -0.05), (0.05, -0.1), (-0.1, -0.05), (0.0, -0.05), (0.1, 0.1)],
)
def test_two_local_minima_are_never_certified_wrong(c1, c2):
    # (xy − 1)² + (x² + y²) / 2 + c1 x + c2 y: two basins about ±(0.7, 0.7), both strongly
    # convex; the start falls into the (−, −) one, the worse one for some (c1, c2), where the
    # certificate must decline (its local part alone would accept)
    e = {(2, 2): 1.0, (1, 1): -2.0, (0, 0): 1.0, (2, 0): 0.5, (0, 2): 0.5, (1, 0): c1, (0, 1): c2}
    x, y, value, delta, ok = certified_minimum(*coefficient_arrays(e), -2.0, 1.0, -2.0, 1.0, 1e-12)
    ref_value, ref_x, ref_y = reference_minimum(
        np.array([[e.get((a, b), 0.0) for b in range(3)] for a in range(3)])
    )
    assert delta[0] <= 1e-12  # converged to a strongly convex local minimum
    if value[0] > ref_value + 1e-3:
        assert not ok[0]  # the worse basin
    if ok[0]:
        assert abs(x[0] - ref_x) <= 1e-6 and abs(y[0] - ref_y) <= 1e-6


def test_a_strictly_convex_energy_is_certified_within_its_bound():
    # (x - 0.3)² + 2 (y + 0.7)² + 0.1 x y, as coefficients: the minimum is interior
    e = {(2, 0): 1.0, (1, 0): -0.6, (0, 0): 0.09 + 0.98, (0, 2): 2.0, (0, 1): 2.8, (1, 1): 0.1}
    x, y, _, delta, ok = certified_minimum(*coefficient_arrays(e), -2.0, 1.0, -2.0, 1.0, 1e-12)
    assert ok[0] and delta[0] <= 1e-12
    # the exact critical point of the quadratic: 2x − 0.6 + 0.1y = 0, 4y + 2.8 + 0.1x = 0
    det = 2 * 4 - 0.1 * 0.1
    assert abs(x[0] - (0.6 * 4 - 0.1 * -2.8) / det) <= 1e-14 + delta[0]
    assert abs(y[0] - (2 * -2.8 - 0.1 * 0.6) / det) <= 1e-14 + delta[0]


def test_edge_minima_are_certified_or_solved_carefully(engine):
    """Edge and corner minima: edge_minimum certifies some (fewer nets are left to the
    careful path than lie off the interior), and every answer is the exact method's."""
    nets = grid_nets(3, 600)
    res = lb.optimal_parameters(nets, "membrane")
    off_interior = res["where"] != "interior"
    assert off_interior.any()  # the batch has minima on edges and corners
    assert 0 < res["careful_fallbacks"] < off_interior.sum()
    for i in np.flatnonzero(off_interior)[:12]:
        one = lb.optimal_parameters(nets[i], "membrane")
        assert one["where"] == res["where"][i]
        assert abs(one["lam_u_float"] - res["lam_u"][i]) <= 1e-12


@pytest.mark.parametrize("bad", [np.nan, np.inf, 1e200])
def test_bad_coordinates_are_refused_on_both_engines(engine, bad):
    nets = grid_nets(1, 200)
    nets[150, 2, 1, 0] = bad
    with pytest.raises(ValueError, match="NaN or infinity|coordinates above"):
        lb.optimal_parameters(nets, "thin_plate")


def test_the_compiled_kernels_record_the_certificate_they_inline():
    # numba caches the kernels by their own file: an edit of surface_certify.py must come with
    # its new hash in surface_batch_compiled.py, which invalidates the cache
    pytest.importorskip("numba")
    from lambda_bezier.hazmat import surface_batch_compiled as sbc

    assert sbc.certify_source_sha256() == sbc.CERTIFY_SHA256, (
        "surface_certify.py changed: set CERTIFY_SHA256 in surface_batch_compiled.py to "
        f"{sbc.certify_source_sha256()}"
    )
