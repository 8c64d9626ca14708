"""optimal_lambda's batch pass without numba (hazmat/batch_numpy.py, issue #29): the same
decisions as the careful path it replaces on every chunk (admissibility, the polygons it
rescales, the errors naming a polygon), the same numbers to rounding, against exact
Fractions, and answers that do not depend on the number of threads."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

import lambda_bezier as lb
from lambda_bezier import energy
from lambda_bezier.hazmat import batch_numpy, kernels


@pytest.fixture(autouse=True)
def _numpy_path(monkeypatch):
    monkeypatch.setattr(kernels, "USE_COMPILED", False)


def _fields(r):
    return (r.lam, r.unconstrained, r.admissible, r.unconstrained_admissible, r.energy,
            r.unconstrained_energy)  # fmt: skip


def _careful(pts, k, family, clamp, monkeypatch):
    """optimal_lambda with the pass declining every chunk: the careful path on each (what
    the numpy fallback was before the pass)."""
    with monkeypatch.context() as patch:
        patch.setattr(batch_numpy, "energy_optimum", lambda *args: 0)
        return lb.optimal_lambda(pts, k, family, clamp=clamp)


def _odd_batch(rng, m, n, dim):
    """Polygons of mixed sizes, and in the middle and at the end ones the careful path must
    take: coordinates near the float limits (rescaled there), and tiny ones."""
    pts = rng.normal(size=(m, n + 1, dim)) * rng.choice([1e-3, 1.0, 1e4], size=(m, 1, 1))
    pts[17] = rng.normal(size=(n + 1, dim)) * 1e-170
    pts[m // 2] = rng.normal(size=(n + 1, dim)) * 1e-200
    pts[m - 1] = rng.normal(size=(n + 1, dim)) * 1e140
    return pts


@pytest.mark.parametrize("family", ["same_degree", "bernstein_like"])
@pytest.mark.parametrize("n", [3, 5, 7])
@pytest.mark.parametrize("dim", [1, 2, 3])
@pytest.mark.parametrize("threads", [1, 2])
def test_pass_matches_the_careful_path(family, n, dim, threads, monkeypatch):
    """Every polygon's λ and energies to rounding, its admissibility exactly, unclamped and
    clamped, over several chunks (some of which the pass leaves to the careful path)."""
    monkeypatch.setattr(kernels, "CHUNK_ELEMENTS", 500)
    monkeypatch.setattr(batch_numpy, "THREADS", threads)
    monkeypatch.setattr(batch_numpy, "_MIN_SLAB", 64)
    rng = np.random.default_rng(1000 * n + 10 * dim + threads)
    pts = _odd_batch(rng, 1500, n, dim)
    assert len(energy._chunks(pts, 2, family)) >= 4
    for k in (1, 2, 3):
        a0, a1, a2 = lb.energy_coefficients(pts, k, family)
        with np.errstate(all="ignore"):  # 0/0 where a₀, a₂ underflow: equal there (below)
            scale = np.sqrt(a0 / a2)  # λ's size where a₁ cancels
        for clamp in (False, True):
            got = _fields(lb.optimal_lambda(pts, k, family, clamp=clamp))
            want = _fields(_careful(pts, k, family, clamp, monkeypatch))
            for lam_got, lam_want in (got[0], want[0]), (got[1], want[1]):
                near = np.abs(lam_got - lam_want) <= 1e-12 * (np.abs(lam_want) + scale)
                assert np.all(near | (lam_got == lam_want))
            np.testing.assert_array_equal(got[2], want[2])
            np.testing.assert_array_equal(got[3], want[3])
            np.testing.assert_allclose(got[4], want[4], rtol=1e-11, atol=0)
            np.testing.assert_allclose(got[5], want[5], rtol=1e-11, atol=0)


def test_pass_is_the_careful_path_bit_for_bit(monkeypatch):
    """On ordinary polygons (no chunk declined) the pass computes what the careful path
    does, in its layout and order: equal bit for bit, unclamped and clamped, though the pass
    cuts its product into blocks and shares the chunks between threads."""
    monkeypatch.setattr(kernels, "CHUNK_ELEMENTS", 4000)
    monkeypatch.setattr(batch_numpy, "_MIN_SLAB", 16)
    monkeypatch.setattr(batch_numpy, "THREADS", 2)
    pts = np.random.default_rng(17).normal(size=(3000, 6, 2))
    for clamp in (False, True):
        got = _fields(lb.optimal_lambda(pts, 2, clamp=clamp))
        want = _fields(_careful(pts, 2, "same_degree", clamp, monkeypatch))
        for a, b in zip(got, want, strict=True):
            np.testing.assert_array_equal(a, b)


def test_answers_do_not_depend_on_threads(monkeypatch):
    """One thread or four: bit for bit (each thread takes whole chunks, and every product
    is cut into the same blocks)."""
    monkeypatch.setattr(kernels, "CHUNK_ELEMENTS", 4000)
    monkeypatch.setattr(batch_numpy, "_MIN_SLAB", 16)
    pts = _odd_batch(np.random.default_rng(7), 3000, 5, 2)
    results = []
    for threads in (1, 4):
        monkeypatch.setattr(batch_numpy, "THREADS", threads)
        results.append(_fields(lb.optimal_lambda(pts, 2, clamp=True)))
    for a, b in zip(*results, strict=True):
        np.testing.assert_array_equal(a, b)


@pytest.mark.parametrize("threads", [1, 3])
def test_errors_name_the_polygon(threads, monkeypatch):
    """A polygon the careful path refuses, in a later chunk or slab, is named by its place
    in the batch: λ without effect (all points equal: a₂ = 0; or a small shape translated
    far away, a₂ within its rounding bound), and NaN."""
    monkeypatch.setattr(kernels, "CHUNK_ELEMENTS", 500)
    monkeypatch.setattr(batch_numpy, "THREADS", threads)
    monkeypatch.setattr(batch_numpy, "_MIN_SLAB", 8)
    pts = np.random.default_rng(1).normal(size=(400, 6, 2))
    pts[333] = 3.0
    with pytest.raises(ValueError, match=r"polygon 333\)"):
        lb.optimal_lambda(pts, 2)
    pts[333] = np.random.default_rng(2).normal(size=(6, 2)) * 1e-9 + 1e4
    with pytest.raises(ValueError, match=r"polygon 333\)"):
        lb.optimal_lambda(pts, 2)
    pts[333, 2, 1] = np.nan
    with pytest.raises(ValueError, match="polygon 333, control point 2 has a non-finite"):
        lb.optimal_lambda(pts, 2)


def test_chunk_beyond_its_bound_goes_to_the_careful_path(monkeypatch):
    """A small shape (a₂ far above its own rounding bound) beside a polygon 1e4 times
    larger: the chunk's bound, from its largest coordinate, declines the chunk; the careful
    path answers it (only that chunk), equal to the exact optimum."""
    monkeypatch.setattr(kernels, "CHUNK_ELEMENTS", 480)  # 30 quintics a chunk (16 columns)
    pts = np.random.default_rng(3).normal(size=(200, 6, 2))
    pts[50] = np.round(np.random.default_rng(4).normal(size=(6, 2)) * 1e3) / 1e4
    pts[51] *= 1e4
    redone = []
    careful = energy._float_optimum_chunk
    monkeypatch.setattr(
        energy,
        "_float_optimum_chunk",
        lambda arr, lo, *rest: (redone.append(lo), careful(arr, lo, *rest)),
    )
    got = lb.optimal_lambda(pts, 2)
    assert redone == [30]
    exact = lb.optimal_lambda([[Fraction(x) for x in p] for p in pts[50]], 2)
    assert abs(got.unconstrained[50] - float(exact.unconstrained)) <= 1e-12 * abs(exact.lam)


@pytest.mark.parametrize("family", ["same_degree", "bernstein_like"])
def test_pass_against_exact_fractions(family, monkeypatch):
    """Integer polygons (exact in floats): λ* and E(λ*) of the float batch within a few ulps
    of a scale of the exact optimum (Fractions, the single-polygon exact path)."""
    monkeypatch.setattr(kernels, "CHUNK_ELEMENTS", 300)
    monkeypatch.setattr(batch_numpy, "THREADS", 2)
    monkeypatch.setattr(batch_numpy, "_MIN_SLAB", 8)
    rng = np.random.default_rng(11)
    pts = rng.integers(-50, 51, size=(120, 6, 2)).astype(float)
    got = lb.optimal_lambda(pts, 2, family, clamp=True)
    for j in range(0, 120, 7):
        exact = lb.optimal_lambda(pts[j].astype(int).tolist(), 2, family, clamp=True)
        a0, a1, a2 = lb.energy_coefficients(pts[j].astype(int).tolist(), 2, family)
        scale = float(abs(exact.unconstrained)) + (float(a0) / float(a2)) ** 0.5
        assert abs(got.unconstrained[j] - float(exact.unconstrained)) <= 1e-13 * scale
        assert abs(got.lam[j] - float(exact.lam)) <= 1e-13 * scale
        assert got.admissible[j] == exact.admissible
        assert got.unconstrained_energy[j] == pytest.approx(
            float(exact.unconstrained_energy), rel=1e-12, abs=1e-12 * float(a0)
        )
