"""evaluate_many's products on threads (batch._products_threaded, issue #29): each thread takes
a slab of whole curves, so the answers are the one-thread answers bit for bit, and an error
names the same curve as one thread does. The chunks and slabs are made small here so that
small batches are split."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import lambda_bezier as lb
from lambda_bezier import batch
from lambda_bezier.hazmat import kernels


@pytest.fixture(params=["numba", "numpy"])
def path(request, monkeypatch):
    """Both tests of the curves' magnitudes (numba's one pass, numpy's), on four threads
    with slabs from one result element up."""
    if request.param == "numba":
        pytest.importorskip("numba")
    monkeypatch.setattr(kernels, "USE_COMPILED", request.param == "numba")
    monkeypatch.setattr(batch, "_MIN_SLAB", 1)
    monkeypatch.setattr(kernels, "CHUNK_ELEMENTS", 64)
    return request.param


def _both(monkeypatch, *args, **kwargs):
    """evaluate_many on one thread and on four."""
    monkeypatch.setattr(batch, "THREADS", 1)
    one = lb.evaluate_many(*args, **kwargs)
    monkeypatch.setattr(batch, "THREADS", 4)
    return one, lb.evaluate_many(*args, **kwargs)


@given(
    m=st.integers(1, 40),
    size=st.integers(3, 8),
    dim=st.integers(1, 3),
    count=st.integers(1, 9),
    k=st.integers(0, 3),
    shared=st.booleans(),
    seed=st.integers(0, 2**32 - 1),
    chunk=st.sampled_from([8, 64, 200, 1000]),
)
@settings(suppress_health_check=[HealthCheck.function_scoped_fixture])  # THREADS set per call
@pytest.mark.parametrize("family", ["bezier", "same_degree", "bernstein_like"])
def test_threads_give_the_one_thread_answers(
    path, monkeypatch, family, m, size, dim, count, k, shared, seed, chunk
):
    """Every family, λ shared or one per curve (a slab of one curve keeps the per-curve
    products: the folding is decided over the whole batch), derivatives, curves near 2^±900
    (scaled per curve), chunks of a few curves: equal bit for bit, and to `out=`."""
    monkeypatch.setattr(kernels, "CHUNK_ELEMENTS", chunk)
    rng = np.random.default_rng(seed)
    size = size if family == "bezier" else max(size, 4)  # the λ families from degree 3
    pts = rng.normal(size=(m, size, dim))
    pts[rng.integers(0, m)] *= 2.0**950
    t = rng.uniform(0, 1, count)
    lam = None
    if family != "bezier":
        lam = 0.5 if shared else rng.uniform(-0.9, 0.9, m)
    one, four = _both(monkeypatch, pts, t, family, lam, k=k)
    np.testing.assert_array_equal(one, four)
    buffer = np.full(one.shape, np.nan)
    assert lb.evaluate_many(pts, t, family, lam, k=k, out=buffer) is buffer
    np.testing.assert_array_equal(buffer, one)


def test_a_slab_of_one_curve_is_not_folded(path, monkeypatch):
    """Per-curve λ on as many threads as curves: each slab holds one curve and one λ, which
    must still take the per-curve products (not the shared-λ fold), as one thread does."""
    monkeypatch.setattr(kernels, "CHUNK_ELEMENTS", 12)  # chunks of one curve
    rng = np.random.default_rng(5)
    pts = rng.normal(size=(4, 6, 2))
    lams = np.array([0.3, -0.7, 0.9, 0.1])
    one, four = _both(monkeypatch, pts, np.linspace(0, 1, 33), "same_degree", lams)
    np.testing.assert_array_equal(one, four)


def test_errors_name_the_first_bad_curve(path, monkeypatch):
    """A non-finite coordinate in a later slab is named by its index in the whole batch; with
    bad curves in two slabs the earlier one is named, as one thread names it."""
    pts = np.random.default_rng(2).normal(size=(40, 4, 2))
    t = np.linspace(0, 1, 5)
    pts[37, 2, 1] = np.inf
    for threads in (1, 4):
        monkeypatch.setattr(batch, "THREADS", threads)
        with pytest.raises(ValueError, match="curve 37, control point 2 has a non-finite"):
            lb.evaluate_many(pts, t, "bezier")
    pts[12, 1, 0] = np.nan
    for threads in (1, 4):
        monkeypatch.setattr(batch, "THREADS", threads)
        with pytest.raises(ValueError, match="curve 12, control point 1 has a non-finite"):
            lb.evaluate_many(pts, t, "bezier")


def test_small_results_stay_on_one_thread(monkeypatch):
    """Below _MIN_SLAB result elements per thread no thread is started (their start would
    cost more than the products); above, slabs of whole chunks."""
    calls = []
    real = batch._products_many

    def counted(*args, **kwargs):
        calls.append(args[0].shape[0])
        return real(*args, **kwargs)

    monkeypatch.setattr(batch, "_products_many", counted)
    monkeypatch.setattr(batch, "THREADS", 2)
    monkeypatch.setattr(kernels, "CHUNK_ELEMENTS", 480)  # chunks of 10 curves
    pts = np.random.default_rng(1).normal(size=(100, 6, 2))
    lb.evaluate_many(pts, np.linspace(0, 1, 64), "bezier")
    assert calls == [100]
    calls.clear()
    monkeypatch.setattr(batch, "_MIN_SLAB", 1000)
    lb.evaluate_many(pts, np.linspace(0, 1, 64), "bezier")
    assert calls == [50, 50]


def test_a_forked_child_makes_its_own_threads(monkeypatch):
    """After fork the child has the parent's pool object but none of its threads: the child
    must start its own (else its jobs never run and evaluate_many waits for ever)."""
    import multiprocessing

    if "fork" not in multiprocessing.get_all_start_methods():
        pytest.skip("no fork on this platform")
    monkeypatch.setattr(batch, "_MIN_SLAB", 1)
    monkeypatch.setattr(batch, "THREADS", 2)
    monkeypatch.setattr(kernels, "CHUNK_ELEMENTS", 48)
    pts = np.random.default_rng(4).normal(size=(20, 4, 3))
    t = np.linspace(0, 1, 9)
    want = lb.evaluate_many(pts, t, "bezier")  # the parent's pool now has threads
    with multiprocessing.get_context("fork").Pool(1) as child:
        got = child.apply_async(lb.evaluate_many, (pts, t, "bezier")).get(timeout=120)
    np.testing.assert_array_equal(got, want)
