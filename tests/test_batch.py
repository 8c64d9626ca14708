"""evaluate_many against single-curve evaluation."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import make_curve
from reference import FAMILIES

import lambda_bezier as lb


@pytest.mark.parametrize("name", list(FAMILIES))
@pytest.mark.parametrize("k", [0, 1, 2, 9])
def test_batch_matches_single(name, k):
    fam = FAMILIES[name]
    rng = np.random.default_rng(k)
    n, m = fam.degrees[0] + 2, 7
    pts = rng.normal(size=(m, n + 1, 3))
    t = np.linspace(0, 1, 13)
    lams = None if name == "bezier" else rng.uniform(*fam.lam_range, size=m)
    got = lb.evaluate_many(pts, t, name, lams, k=k)
    assert got.shape == (m, t.size, 3)
    for idx in range(m):
        curve = make_curve(fam, pts[idx], None if lams is None else lams[idx])
        np.testing.assert_allclose(got[idx], curve.derivative(t, k), atol=1e-10 * (1 + k) ** 6)
    if name != "bezier":
        same = lb.evaluate_many(pts, 0.25, name, 0.5)
        assert same.shape == (m, 3)
        np.testing.assert_allclose(same[2], make_curve(fam, pts[2], 0.5).evaluate(0.25))


@pytest.mark.parametrize(
    ("args", "kwargs", "message"),
    [
        ((np.zeros((2, 4, 2)), [0.5], "same_degree"), {}, "needs a shape parameter"),
        ((np.zeros((2, 4, 2)), [0.5], "bezier", 0.5), {}, "no shape parameter"),
        ((np.zeros((2, 4, 2)), [0.5], "same_degree", [0.5, -3.0]), {}, r"curve 1.*\(-2, 1\]"),
        ((np.zeros((2, 4, 2)), [0.5], "same_degree", [0.5, 0.5, 0.5]), {}, "array of 2"),
        ((np.zeros((4, 2)), [0.5], "bezier"), {}, r"\(m, n\+1, d\)"),
        ((np.full((2, 4, 2), np.nan), [0.5], "bezier"), {}, "non-finite"),
        ((np.zeros((2, 4, 2)), [1.5], "bezier"), {}, "outside"),
        ((np.zeros((2, 4, 2)), [0.5], "spline"), {}, "unknown family"),
        ((np.zeros((2, 2, 2)), [0.5], "same_degree", 0.5), {}, "at least 4"),
    ],
)
def test_batch_bad_input(args, kwargs, message):
    with pytest.raises(ValueError, match=message):
        lb.evaluate_many(*args, **kwargs)


@pytest.fixture
def tiny_chunks(monkeypatch):
    """Chunks of a few curves each, so a small batch crosses many chunk boundaries."""
    from lambda_bezier.hazmat import kernels

    monkeypatch.setattr(kernels, "CHUNK_ELEMENTS", 40)


@pytest.mark.parametrize("name", list(FAMILIES))
@pytest.mark.parametrize("k", [0, 2])
def test_chunked_batch_matches_single(name, k, tiny_chunks):
    """Curves in different chunks (some scaled near the float limits) against one by one."""
    from lambda_bezier.hazmat import kernels

    fam = FAMILIES[name]
    rng = np.random.default_rng(11 + k)
    n, m = fam.degrees[0] + 1, 23
    pts = rng.normal(size=(m, n + 1, 2))
    pts[5] *= 1e300  # one chunk computed on scaled points
    pts[6] *= 1e-300
    t = np.linspace(0, 1, 5)
    assert len(kernels.chunk_ranges(m, t.size * 2)) > 5
    lams = None if name == "bezier" else rng.uniform(*fam.lam_range, size=m)
    got = lb.evaluate_many(pts, t, name, lams, k=k)
    assert got.shape == (m, t.size, 2)
    for idx in range(m):
        want = make_curve(fam, pts[idx], None if lams is None else lams[idx]).derivative(t, k)
        np.testing.assert_allclose(got[idx], want, rtol=1e-9, atol=1e-9 * np.abs(want).max())


def test_chunked_de_casteljau_and_non_finite_index(tiny_chunks):
    """Past the tables (de Casteljau) chunk by chunk; a NaN in a late chunk is named by its
    curve index in the whole batch, not in its chunk."""
    rng = np.random.default_rng(3)
    pts = rng.normal(size=(17, 21, 3))
    t = np.linspace(0, 1, 4)
    got = lb.evaluate_many(pts, t, "bezier", k=1)
    for idx in range(17):
        np.testing.assert_allclose(got[idx], lb.BezierCurve(pts[idx]).derivative(t, 1), atol=1e-9)
    pts[13, 2, 1] = np.nan
    with pytest.raises(ValueError, match="curve 13, control point 2 has a non-finite"):
        lb.evaluate_many(pts, t, "bezier")
    with pytest.raises(ValueError, match="curve 13, control point 2 has a non-finite"):
        lb.evaluate_many(pts[:, :5], t, "bezier")


@pytest.fixture(params=["numba", "numpy"])
def batch_path(request, monkeypatch):
    """Both paths of the batch energy coefficients: the compiled kernel (the `fast` extra)
    and the numpy fallback."""
    from importlib.util import find_spec

    from lambda_bezier.hazmat import kernels

    if request.param == "numba" and find_spec("numba") is None:
        pytest.skip("numba is not installed (pip install '.[fast]'): the compiled path")
    monkeypatch.setattr(kernels, "USE_COMPILED", request.param == "numba")
    return request.param


@pytest.mark.parametrize("family", ["same_degree", "bernstein_like"])
@pytest.mark.parametrize("dim", [1, 2, 3])
def test_compiled_and_numpy_energy_coefficients_agree(family, dim, monkeypatch):
    """The compiled kernel against the numpy products, term for term, on every order, with
    large and tiny polygons (the tiny one redone scaled) in the batch."""
    pytest.importorskip("numba")
    from lambda_bezier.hazmat import kernels

    rng = np.random.default_rng(dim)
    batch = rng.normal(size=(40, 6, dim))
    batch[3] *= 1e140
    batch[4] *= 1e-200
    for k in (1, 2, 3):
        monkeypatch.setattr(kernels, "USE_COMPILED", True)
        fast = lb.energy_coefficients(batch, k, family)
        opt_fast = lb.optimal_lambda(batch, k, family, clamp=True)
        monkeypatch.setattr(kernels, "USE_COMPILED", False)
        slow = lb.energy_coefficients(batch, k, family)
        opt_slow = lb.optimal_lambda(batch, k, family, clamp=True)
        for a, b in zip(fast, slow, strict=True):
            np.testing.assert_allclose(a, b, rtol=1e-13)
        np.testing.assert_allclose(opt_fast.unconstrained, opt_slow.unconstrained, rtol=1e-12)
        np.testing.assert_allclose(opt_fast.energy, opt_slow.energy, rtol=1e-12)
        assert (opt_fast.admissible == opt_slow.admissible).all()


def test_chunked_optimal_lambda_matches_single(tiny_chunks, batch_path):
    from lambda_bezier.hazmat import kernels

    rng = np.random.default_rng(8)
    batch = rng.normal(size=(31, 6, 2))
    assert len(kernels.chunk_ranges(31, 24)) > 5
    for k in (1, 2, 3):
        result = lb.optimal_lambda(batch, k)
        for idx in range(31):
            single = lb.optimal_lambda(batch[idx], k)
            np.testing.assert_allclose(result.unconstrained[idx], single.unconstrained, rtol=1e-12)
            np.testing.assert_allclose(result.energy[idx], single.energy, rtol=1e-12)
    batch[20, 1, 0] = np.inf  # named by its place in the batch, not in its chunk
    with pytest.raises(ValueError, match="polygon 20, control point 1 has a non-finite"):
        lb.optimal_lambda(batch, 2)
    batch[20] = 0.0  # no effect of λ on a point: named likewise
    with pytest.raises(ValueError, match=r"polygon 20\)"):
        lb.optimal_lambda(batch, 2)
    clamped = lb.optimal_lambda(batch[:19], 2, clamp=True)
    assert clamped.lam.shape == (19,) and clamped.lam is not clamped.unconstrained
    for idx in (0, 7, 18):
        one = lb.optimal_lambda(batch[idx], 2, clamp=True)
        assert clamped.lam[idx] == pytest.approx(one.lam, rel=1e-12)
        assert clamped.admissible[idx] == one.admissible
        assert clamped.energy[idx] == pytest.approx(one.energy, rel=1e-12)


def test_mixed_magnitudes_in_one_batch():
    """A curve near 1e-300 beside one near 1e300 keeps its own values: each curve is scaled
    by its own power of two (one scale for the batch underflowed the small one to 0)."""
    pts = np.array([[(0, 0), (1, 2), (3, 2), (4, 1)]] * 3, dtype=float)
    pts[0] *= 1e300
    pts[1] *= 1e-300
    got = lb.evaluate_many(pts, [0.0, 0.3, 1.0], "same_degree", lam=0.5)
    for idx in range(3):
        want = lb.SameDegreeCurve(pts[idx], 0.5).evaluate([0.0, 0.3, 1.0])
        size = np.abs(pts[idx]).max()  # rounding relative to the curve's own magnitude
        np.testing.assert_allclose(got[idx], want, rtol=1e-12, atol=1e-14 * size)
    assert np.all(got[1][1] > 1e-301)
