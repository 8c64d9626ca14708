"""The batch optimum of (λ_u, λ_v) on both paths (numpy and the numba-compiled kernel), against
each other and against the exact method; the compiled kernel's root finder on its own."""

from __future__ import annotations

from importlib.util import find_spec

import numpy as np
import pytest

import lambda_bezier as lb
from lambda_bezier.hazmat import surface_kernels

needs_numba = pytest.mark.skipif(
    find_spec("numba") is None, reason="numba is not installed (pip install '.[fast]')"
)


def random_nets(seed, count, m=3, n=3, d=3):
    nets = np.random.default_rng(seed).normal(size=(count, m + 1, n + 1, d))
    nets[..., 0] += np.arange(m + 1)[:, None]
    nets[..., 1] += np.arange(n + 1)[None, :]
    return nets


@pytest.fixture(params=["numpy", "numba"])
def path(request, monkeypatch):
    if request.param == "numba" and find_spec("numba") is None:
        pytest.skip("numba is not installed (pip install '.[fast]'): the compiled path")
    monkeypatch.setattr(surface_kernels, "USE_COMPILED", request.param == "numba")
    return request.param


@pytest.mark.parametrize("fam", ["same_degree", "bernstein_like"])
@pytest.mark.parametrize("energy", ["membrane", "thin_plate"])
def test_batch_agrees_with_the_exact_method(path, fam, energy):
    nets = random_nets(5, 120, 3, 4)
    res = lb.optimal_parameters(nets, energy, fam)
    assert res["lam_u"].shape == (120,) and res["where"].shape == (120,)
    for i in range(0, 120, 23):
        one = lb.optimal_parameters(nets[i], energy, fam)
        assert abs(one["lam_u_float"] - res["lam_u"][i]) <= 1e-12
        assert abs(one["lam_v_float"] - res["lam_v"][i]) <= 1e-12
        assert res["where"][i] == one["where"]
        assert abs(float(one["energy"]) - res["energy"][i]) <= 1e-12 * max(1, abs(res["energy"][i]))


@needs_numba
@pytest.mark.parametrize("fam", ["same_degree", "bernstein_like"])
def test_compiled_and_numpy_paths_agree(monkeypatch, fam):
    nets = random_nets(11, 2000, 3, 3)
    monkeypatch.setattr(surface_kernels, "USE_COMPILED", True)
    fast = lb.optimal_parameters(nets, "thin_plate", fam)
    monkeypatch.setattr(surface_kernels, "USE_COMPILED", False)
    slow = lb.optimal_parameters(nets, "thin_plate", fam)
    np.testing.assert_allclose(fast["lam_u"], slow["lam_u"], atol=1e-12, rtol=0)
    np.testing.assert_allclose(fast["lam_v"], slow["lam_v"], atol=1e-12, rtol=0)
    np.testing.assert_allclose(fast["energy"], slow["energy"], rtol=1e-12)
    assert (fast["where"] == slow["where"]).all()
    assert (fast["admissible"] == slow["admissible"]).all()


def test_ties_and_planar_nets_go_to_the_exact_method(path):
    # a planar grid in the plane z = 0 whose energy does not depend on λ at all, and a net
    # mirrored in u (a symmetric energy in λ_u: no tie, but a check of the same answer)
    flat = np.zeros((3, 4, 4, 3))
    flat[..., 0] = np.arange(4)[:, None]
    flat[..., 1] = np.arange(4)[None, :]
    res = lb.optimal_parameters(flat, "membrane", "same_degree")
    assert np.isfinite(res["energy"]).all()
    exact = lb.optimal_parameters(flat[0], "membrane", "same_degree")
    assert res["lam_u"][0] == exact["lam_u_float"] and res["lam_v"][0] == exact["lam_v_float"]


@needs_numba
def test_compiled_root_finder_on_known_roots():
    from lambda_bezier.hazmat import surface_compiled as comp

    ders, pts, out = np.empty((6, 6)), np.empty(7), np.empty(6)
    rng = np.random.default_rng(2)
    for _ in range(200):
        roots = np.sort(rng.uniform(-3, 2, size=5))
        coeffs = np.polynomial.polynomial.polyfromroots(roots) * rng.choice([-1.0, 3.0])
        count, near = comp._roots_in(coeffs, -2.0, 1.0, out, ders, pts)
        inside = roots[(roots > -2) & (roots < 1)]
        if np.min(np.diff(roots)) < 0.1:
            continue  # clustered roots may legitimately be flagged as nearly double
        assert not near
        assert count == inside.size
        np.testing.assert_allclose(out[:count], inside, atol=1e-11)
    # a pair of roots about to leave the real axis (R touches zero without crossing), or two
    # roots 1e-7 apart: nearly double (the caller then solves the net exactly)
    for shift, roots in ((1e-12, [-0.5, -0.5]), (0.0, [-0.5, -0.5 + 1e-7])):
        coeffs = np.polynomial.polynomial.polyfromroots([*roots, 0.25, 3.0, 4.0])
        coeffs[0] -= shift  # R(-0.5) = -shift: R comes within 1e-12 of zero without crossing
        count, near = comp._roots_in(coeffs, -2.0, 1.0, out, ders, pts)
        assert near, (shift, count)
    # a polynomial of lower degree, and the zero polynomial (no isolated roots: undecided)
    count, near = comp._roots_in(np.array([1.0, -2.0, 0, 0, 0, 0]), -2.0, 1.0, out, ders, pts)
    assert (count, near) == (1, False) and out[0] == 0.5
    count, near = comp._roots_in(np.zeros(6), -2.0, 1.0, out, ders, pts)
    assert (count, near) == (0, True)


def test_grid_evaluation_on_both_paths(path):
    # the compiled products and numpy's matmul, against evaluation at paired points
    net = random_nets(3, 1, 3, 4)[0]
    s = lb.Surface(net, 0.25, -0.75, family=("same_degree", "bernstein_like"))
    us, vs = np.linspace(0, 1, 37), np.linspace(0, 1, 23) ** 2
    grid = s.evaluate_grid(us, vs)
    assert grid.shape == (37, 23, 3)
    uu, vv = np.meshgrid(us, vs, indexing="ij")
    want = s.evaluate(uu.ravel(), vv.ravel()).reshape(37, 23, 3)
    np.testing.assert_allclose(grid, want, rtol=0, atol=1e-13)
    np.testing.assert_allclose(
        s.evaluate_grid(us, vs, 1, 2),
        s.derivative(uu.ravel(), vv.ravel(), 1, 2).reshape(37, 23, 3),
        rtol=0,
        atol=1e-11,
    )
    assert s.evaluate_grid([], vs).shape == (0, 23, 3)


@pytest.mark.parametrize(
    "shape", [(4, 4, 3), (1, 1, 1), (2, 3, 2), (6, 5, 3), (3, 8, 1), (9, 9, 2)]
)
def test_grid_kernel_against_exact_sums(path, shape):
    # every degree pattern of the compiled kernel's passes over a row (one pass up to N = 3,
    # then three coefficients a pass; the zero padding above the degree), strided parameter
    # arrays, against the Taylor sums in Fractions: the inputs are floats, so the exact value
    # is known and the error is bounded by a few ulps of the sum of the absolute terms
    from fractions import Fraction

    rng = np.random.default_rng(sum(shape))
    coeffs = rng.normal(size=shape)
    us = np.linspace(0, 1, 11)[::2]
    vs = np.concatenate([[0.0, 1.0], rng.random(5)])
    got = surface_kernels.evaluate_grid(coeffs, us, vs)
    assert got.shape == (us.size, vs.size, shape[2])
    big_m, big_n, _ = shape
    half = Fraction(1, 2)
    for a, u in enumerate(us):
        for b, v in enumerate(vs):
            su, sv = Fraction(u) - half, Fraction(v) - half
            for c in range(shape[2]):
                terms = [
                    Fraction(coeffs[i, k, c]) * su**i * sv**k
                    for i in range(big_m)
                    for k in range(big_n)
                ]
                size = float(sum(abs(t) for t in terms))
                err = abs(Fraction(got[a, b, c]) - sum(terms))
                assert err <= 4 * (big_m + big_n) * 2.0**-52 * size, (a, b, c)


def test_far_from_origin_compiled_matches_numpy():
    """The compiled corner pass that picks the nets to move to the origin (surface_optimum
    ._centred) picks the same nets as its numpy column-by-column version."""
    pytest.importorskip("numba")
    from lambda_bezier import surface_optimum as so
    from lambda_bezier.hazmat import surface_batch_compiled as sbc

    rng = np.random.default_rng(7)
    nets = rng.normal(size=(500, 4, 5, 2)) * 10.0 ** rng.integers(-3, 4, (500, 1, 1, 1))
    nets += rng.normal(size=(500, 1, 1, 2)) * 10.0 ** rng.integers(-2, 7, (500, 1, 1, 1))
    mats = so._batch_setup(*so._as_family_pair("same_degree"), (3, 4), "thin_plate")[0]
    assert so._depends_on_differences(mats)
    np.testing.assert_array_equal(so._centred(nets, mats, sbc), so._centred(nets, mats, None))
    far = sbc.far_from_origin(nets, 4.0)
    assert 50 < far.sum() < 450
