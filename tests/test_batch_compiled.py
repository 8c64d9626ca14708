"""The batch kernels of hazmat/batch_compiled.py (issue #29): the fused optimal-λ pass is
bit for bit the chunked careful path on the same coefficients, wherever in a batch the
polygons it declines sit; the exact admissibility bounds. (evaluate_many has no compiled
kernel since issue #29's round 13: tests/test_batch_products.py.)"""

from __future__ import annotations

from fractions import Fraction
from types import SimpleNamespace

import numpy as np
import pytest

import lambda_bezier as lb
from lambda_bezier import energy
from lambda_bezier.hazmat import kernels

numba = pytest.importorskip("numba")


def _careful(pts, k, family, clamp):
    """optimal_lambda's arrays (λ, λ*, λ ok, λ* ok, E(λ), E(λ*)) chunk by chunk by the
    careful path on the compiled coefficients: what the fused pass replaced."""
    arr, _ = energy._as_polygons(pts, family)
    m = arr.shape[0]
    out = tuple(np.empty(m, dtype=d) for d in (float, float, bool, bool, float, float))
    for lo, hi in energy._chunks(arr, k, family):
        energy._float_optimum_chunk(
            arr, lo, hi, k, family, clamp, energy._family_data(family), False, out
        )
    return out


@pytest.mark.parametrize("family", ["same_degree", "bernstein_like"])
@pytest.mark.parametrize("n", [3, 5, 7])
@pytest.mark.parametrize("dim", [1, 2, 3])
@pytest.mark.parametrize("clamp", [False, True])
def test_fused_optimum_is_the_careful_path_bit_for_bit(family, n, dim, clamp, monkeypatch):
    """Every polygon's λ, admissibility and energies equal the careful path's exactly, with
    polygons the pass declines (underflow, near the float limits: rescaled) in the middle and
    at the end of the batch, so the pass restarts after each."""
    monkeypatch.setattr(kernels, "USE_COMPILED", True)
    monkeypatch.setattr(kernels, "CHUNK_ELEMENTS", 1000)  # several chunks, several restarts
    rng = np.random.default_rng(100 * n + 10 * dim + clamp)
    m = 1500
    pts = rng.normal(size=(m, n + 1, dim)) * rng.choice([1e-3, 1.0, 1e4], size=(m, 1, 1))
    pts[17] = rng.normal(size=(n + 1, dim)) * 1e-170
    pts[900] = rng.normal(size=(n + 1, dim)) * 1e-200
    pts[m - 1] = rng.normal(size=(n + 1, dim)) * 1e140
    assert len(energy._chunks(pts, 2, family)) >= 3
    for k in (1, 2, 3):
        got = lb.optimal_lambda(pts, k, family, clamp=clamp)
        fused = (
            got.lam,
            got.unconstrained,
            got.admissible,
            got.unconstrained_admissible,
            got.energy,
            got.unconstrained_energy,
        )
        want = _careful(pts, k, family, clamp)
        for index in range(6) if clamp else (1, 3, 5):
            np.testing.assert_array_equal(fused[index], want[index])


def test_fused_optimum_errors_name_the_polygon(monkeypatch):
    """A polygon the careful path refuses, found by the fused pass in a later chunk, is
    named by its place in the batch."""
    monkeypatch.setattr(kernels, "USE_COMPILED", True)
    monkeypatch.setattr(kernels, "CHUNK_ELEMENTS", 500)
    pts = np.random.default_rng(1).normal(size=(400, 6, 2))
    pts[333] = 0.0  # λ has no effect
    with pytest.raises(ValueError, match=r"polygon 333\)"):
        lb.optimal_lambda(pts, 2)
    pts[333, 2, 1] = np.nan
    with pytest.raises(ValueError, match="polygon 333, control point 2 has a non-finite"):
        lb.optimal_lambda(pts, 2)


@pytest.mark.parametrize(
    ("lo", "hi", "closed"),
    [
        (Fraction(-1, 3), Fraction(2, 3), (True, True)),
        (Fraction(-1, 3), Fraction(2, 3), (False, False)),
        (-2, 1, (False, True)),
        (Fraction(-1, 10), Fraction(7, 10), (False, True)),
        (Fraction(1, 2), Fraction(3, 4), (True, False)),
    ],
)
def test_admissible_bounds_decide_as_the_exact_ends(lo, hi, closed):
    """The float bounds of the compiled pass decide admissibility exactly as the comparisons
    with the exact (int or Fraction, open or closed) ends do, at the floats nearest the ends."""
    data = SimpleNamespace(LAMBDA_RANGE=(lo, hi), LAMBDA_CLOSED=closed)
    clip_lo, clip_hi, least, greatest = energy._admissible_bounds(data)
    assert (clip_lo, clip_hi) == (float(lo), float(hi))
    for end in (lo, hi):
        near = float(end)
        for x in map(float, (np.nextafter(near, -np.inf), near, np.nextafter(near, np.inf))):
            above = x >= lo if closed[0] else x > lo
            below = x <= hi if closed[1] else x < hi
            assert (least <= x <= greatest) == (above and below), (x, end)


def _ordered_reference(pts, compact, rows, rounding_weight):
    """The compiled kernel's sums in numpy, one term at a time in the kernel's order (each
    elementwise operation correctly rounded, so the result is the kernel's bit for bit)."""
    m, size, dim = pts.shape
    s0, s1, s2, norm = (np.zeros(m) for _ in range(4))
    for e in range(size * dim):
        x = pts[:, e // dim, e % dim]
        norm = norm + x * x
    for c in range(dim):
        for r in range(rows):
            f, g = np.zeros(m), np.zeros(m)
            for i in range(size):
                f = f + compact[i, r] * pts[:, i, c]
                g = g + compact[i, rows + r] * pts[:, i, c]
            s0, s1, s2 = s0 + f * f, s1 + f * g, s2 + g * g
    return np.array([s0, 2.0 * s1, s2, norm * rounding_weight])


@pytest.mark.parametrize("family", ["same_degree", "bernstein_like"])
@pytest.mark.parametrize("n", [3, 4, 5, 6, 7])
@pytest.mark.parametrize("dim", [1, 2, 3])
def test_compiled_coefficients_keep_their_summation_order(family, n, dim):
    """The blocked kernel (three terms a pass; six-point forms in one pass) adds each
    polygon's terms in the one fixed order, so its results do not depend on the blocking:
    equal to the term-by-term sums bit for bit, across block boundaries."""
    from lambda_bezier.hazmat import batch_compiled

    pts = np.random.default_rng(n * dim).normal(size=(700, n + 1, dim))
    for k in (1, 2, 3):
        compact, rows, weight = energy._compact_forms(family, n, k)
        out = np.empty((4, len(pts)))
        batch_compiled.energy_coefficients(pts, compact, rows, 1e-12 * weight, out)
        np.testing.assert_array_equal(out, _ordered_reference(pts, compact, rows, 1e-12 * weight))
