"""The batch kernels of hazmat/batch_compiled.py (issue #29): the fused optimal-λ pass is
bit for bit the chunked careful path on the same coefficients, wherever in a batch the
polygons it declines sit; the exact admissibility bounds; evaluate_many's compiled Horner
kernel and its `out=` argument against the numpy path."""

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


@pytest.fixture
def numpy_and_compiled(monkeypatch):
    """Calls evaluate_many on the numpy path and on the compiled one."""

    def both(*args, **kwargs):
        monkeypatch.setattr(kernels, "USE_COMPILED", False)
        slow = lb.evaluate_many(*args, **kwargs)
        monkeypatch.setattr(kernels, "USE_COMPILED", True)
        fast = lb.evaluate_many(*args, **kwargs)
        return slow, fast

    return both


@pytest.mark.parametrize("name", ["bezier", "same_degree", "bernstein_like"])
@pytest.mark.parametrize("dim", [1, 2, 3])
def test_compiled_evaluate_many_matches_numpy(name, dim, numpy_and_compiled):
    """Every derivative order (past the degree too), curves near 2^±1000 (scaled per curve)
    beside ordinary ones, more parameters than one span, one λ per curve."""
    from lambda_bezier.hazmat import batch_compiled

    fam = lb.FAMILIES[name]
    rng = np.random.default_rng(dim)
    for n in fam._data.DEGREES[:3]:
        pts = rng.normal(size=(9, n + 1, dim))
        pts[2] *= 1e300
        pts[4] *= 1e-300
        t = np.linspace(0.0, 1.0, batch_compiled._SPAN + 37)
        lam = None if name == "bezier" else rng.uniform(-0.9, 0.9, size=9)
        for k in range(n + 3):
            slow, fast = numpy_and_compiled(pts, t, name, lam, k=k)
            assert fast.shape == slow.shape == (9, t.size, dim)
            assert fast.flags.c_contiguous
            # rounding relative to each curve's own magnitude (near-zero values cancel)
            size = np.abs(slow).max(axis=(1, 2), keepdims=True)
            assert (np.abs(fast - slow) <= 1e-12 * size).all()
        one, one_fast = numpy_and_compiled(pts, 0.25, name, lam)  # a scalar t: (m, d)
        assert one.shape == one_fast.shape == (9, dim)
        assert (np.abs(one_fast - one) <= 1e-12 * np.abs(one).max(axis=1, keepdims=True)).all()


def test_compiled_evaluate_many_declines_and_names(numpy_and_compiled, monkeypatch):
    """A NaN late in the batch is named by its curve; an overflow when extrapolating is
    refused by the numpy path it is handed to, with the same message."""
    monkeypatch.setattr(kernels, "CHUNK_ELEMENTS", 64)
    pts = np.random.default_rng(2).normal(size=(50, 4, 2))
    pts[41, 3, 0] = np.nan
    for use in (False, True):
        monkeypatch.setattr(kernels, "USE_COMPILED", use)
        with pytest.raises(ValueError, match="curve 41, control point 3 has a non-finite"):
            lb.evaluate_many(pts, [0.0, 1.0], "bezier")
    pts[41] = np.random.default_rng(3).normal(size=(4, 2)) * 1e306
    for use in (False, True):
        monkeypatch.setattr(kernels, "USE_COMPILED", use)
        with pytest.raises(ValueError, match="overflows the float range"):
            lb.evaluate_many(pts, [0.0, 30.0], "bezier", extrapolate=True)
    pts[41] = 1.0
    slow, fast = numpy_and_compiled(pts, np.linspace(0, 1, 5), "bezier")
    np.testing.assert_allclose(fast, slow, rtol=1e-12)


@pytest.mark.parametrize("use_compiled", [False, True])
def test_evaluate_many_out(use_compiled, monkeypatch):
    """out= writes the result into the caller's buffer and returns it, on every path (the
    tables, de Casteljau past them, a trigonometric family), scalar t included."""
    monkeypatch.setattr(kernels, "USE_COMPILED", use_compiled)
    rng = np.random.default_rng(5)
    t = np.linspace(0, 1, 7)
    cases = [
        (rng.normal(size=(6, 4, 2)), "same_degree", 0.5),
        (rng.normal(size=(6, 6, 3)), "bezier", None),
        (rng.normal(size=(6, 25, 2)), "bezier", None),  # past the tables: de Casteljau
    ]
    for pts, name, lam in cases:
        want = lb.evaluate_many(pts, t, name, lam, k=1)
        buf = np.full((6, 7, pts.shape[2]), np.nan)
        got = lb.evaluate_many(pts, t, name, lam, k=1, out=buf)
        assert got is buf
        np.testing.assert_array_equal(buf, want)
        scalar = np.empty((6, pts.shape[2]))
        assert lb.evaluate_many(pts, 0.5, name, lam, out=scalar) is scalar
        np.testing.assert_array_equal(scalar, lb.evaluate_many(pts, 0.5, name, lam))


def test_evaluate_many_out_of_an_atom_family():
    from pathlib import Path

    fam = lb.load_family(Path(__file__).parent / "data/families/han_trig_cubic.toml")
    pts = np.random.default_rng(1).normal(size=(3, 4, 2))
    want = lb.evaluate_many(pts, [0.0, 0.5], fam, params={"lam": 0.5, "mu": -1.0})
    buf = np.empty((3, 2, 2))
    assert lb.evaluate_many(pts, [0.0, 0.5], fam, params={"lam": 0.5, "mu": -1.0}, out=buf) is buf
    np.testing.assert_array_equal(buf, want)


def test_evaluate_many_out_is_checked():
    """numpy's out= rules, each refused by name before anything is written."""
    pts = np.random.default_rng(0).normal(size=(4, 4, 2))
    t = np.linspace(0, 1, 3)
    bad = [
        ([[0.0]], TypeError, "out must be a numpy array, got list"),
        (np.empty((4, 3, 2), dtype=np.float32), TypeError, "out must have dtype float64"),
        (np.empty((4, 3, 3)), ValueError, r"out must have the result's shape \(4, 3, 2\)"),
        (np.empty((4, 2, 3)).transpose(0, 2, 1), ValueError, "out must be C-contiguous"),
    ]
    frozen = np.zeros((4, 3, 2))
    frozen.setflags(write=False)
    bad.append((frozen, ValueError, "out is read-only"))
    for out, error, message in bad:
        with pytest.raises(error, match=message):
            lb.evaluate_many(pts, t, "bezier", out=out)
    assert (frozen == 0).all()
    # the result may not overwrite its own input
    shared = np.zeros(4 * 3 * 2 + 4 * 4 * 2)
    inputs = shared[:32].reshape(4, 4, 2)
    inputs[...] = pts
    with pytest.raises(ValueError, match="out must not overlap the control points or t"):
        lb.evaluate_many(inputs, t, "bezier", out=shared[8:32].reshape(4, 3, 2))
    grid = np.zeros(4 * 3 * 2 + 3)
    grid[:3] = t
    with pytest.raises(ValueError, match="out must not overlap the control points or t"):
        lb.evaluate_many(pts, grid[:3], "bezier", out=grid[:24].reshape(4, 3, 2))
