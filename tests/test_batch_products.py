"""evaluate_many on the tables (batch._products_many, issue #29): blocks of the result as
matrix products with the monomials Kronecker the identity, against each curve on its own and
against de Casteljau; the fast tests for curves near the float limits (numpy's over a chunk,
numba's one pass, batch_compiled.odd_curves); `out=`. The products need no numba: these tests
run on both paths."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import make_curve
from hypothesis import given
from hypothesis import strategies as st
from reference import FAMILIES

import lambda_bezier as lb
from lambda_bezier import batch
from lambda_bezier.hazmat import kernels


@pytest.fixture(params=["numba", "numpy"])
def path(request, monkeypatch):
    """Both tests of the curves' magnitudes: numba's one pass and numpy's."""
    if request.param == "numba":
        pytest.importorskip("numba")
    monkeypatch.setattr(kernels, "USE_COMPILED", request.param == "numba")
    return request.param


def _single(name, pts, lams, t, k):
    fam = FAMILIES[name]
    return np.stack(
        [
            make_curve(fam, pts[j], None if lams is None else lams[j]).derivative(t, k)
            for j in range(len(pts))
        ]
    )


@pytest.mark.parametrize("name", ["bezier", "same_degree", "bernstein_like"])
@pytest.mark.parametrize("dim", [1, 2, 3])
@pytest.mark.parametrize("chunk", [1 << 18, 300])
def test_products_match_each_curve(name, dim, chunk, monkeypatch, path):
    """Every derivative order (past the degree too), curves near 2^±1000 (scaled per curve)
    beside ordinary ones, one λ per curve, one λ for all (folded into the product, given as
    a number and as equal values), and (small chunks) the parameters cut into blocks."""
    monkeypatch.setattr(kernels, "CHUNK_ELEMENTS", chunk)
    fam = lb.FAMILIES[name]
    rng = np.random.default_rng(dim)
    for n in fam._data.DEGREES[:3]:
        pts = rng.normal(size=(9, n + 1, dim))
        pts[2] *= 1e300
        pts[4] *= 1e-300
        t = np.linspace(0.0, 1.0, 41)
        per_curve = None if name == "bezier" else rng.uniform(-0.9, 0.9, size=9)
        shared = None if name == "bezier" else np.full(9, per_curve[0])
        for lams in (per_curve, shared):
            for k in range(n + 3):
                got = lb.evaluate_many(pts, t, name, lams, k=k)
                want = _single(name, pts, lams, t, k)
                assert got.shape == (9, t.size, dim)
                assert got.flags.c_contiguous
                # rounding relative to each curve's own magnitude (near-zero values cancel)
                size = np.abs(want).max(axis=(1, 2), keepdims=True)
                assert (np.abs(got - want) <= 1e-12 * size).all(), (n, k)
        lam = None if name == "bezier" else 0.25
        one = lb.evaluate_many(pts, 0.25, name, lam)  # a scalar t: (m, d)
        want = _single(name, pts, None if lam is None else [lam] * 9, np.array([0.25]), 0)
        assert one.shape == (9, dim)
        assert (np.abs(one - want[:, 0]) <= 1e-12 * np.abs(want).max(axis=(1, 2))[:, None]).all()


@given(
    n=st.integers(0, 9),
    dim=st.integers(1, 3),
    m=st.integers(1, 40),
    k=st.integers(0, 4),
    t=st.lists(st.floats(0, 1), min_size=1, max_size=30),
    seed=st.integers(0, 2**32 - 1),
)
def test_products_match_de_casteljau(n, dim, m, k, t, seed):
    """Classical curves of any tabled degree against de Casteljau on the hodograph (the
    path past the tables), which shares no arithmetic with the products."""
    pts = np.random.default_rng(seed).uniform(-10, 10, size=(m, n + 1, dim))
    tt = np.array(t)
    got = lb.evaluate_many(pts, tt, "bezier", k=k)
    want = batch._de_casteljau_many(pts, tt, k, False)
    scale = 10.0 * (1 + n) ** k
    np.testing.assert_allclose(got, want, rtol=0, atol=1e-12 * scale)


def test_scaling_test_is_per_curve(path):
    """The fast test over a whole chunk only lets through chunks where no curve needs
    scaling: a tiny coordinate in an ordinary curve is left as it is, a curve whose largest
    coordinate is tiny is scaled (its values kept, not flushed to zero), a zero curve is
    zero, a NaN is named by its curve."""
    pts = np.random.default_rng(4).normal(size=(6, 4, 2))
    pts[1, 2, 0] = 1e-310  # a subnormal beside ordinary coordinates
    pts[3] *= 1e-305  # the whole curve tiny
    pts[4] = 0.0
    assert batch._curve_scales(pts[:1], 0) is None
    scales = batch._curve_scales(pts, 0)
    assert scales is not None
    assert scales[1] == 1.0 and scales[4] == 1.0 and scales[3] != 1.0
    t = np.linspace(0, 1, 7)
    got = lb.evaluate_many(pts, t, "bezier", k=1)
    want = _single("bezier", pts, None, t, 1)
    assert np.abs(got[3]).min() > 0
    for j in range(6):
        np.testing.assert_allclose(got[j], want[j], rtol=1e-12, atol=1e-12 * np.abs(want[j]).max())
    assert batch._curve_scales(pts[:1] * 2.0**899, 0) is None
    assert batch._curve_scales(pts[:1] * 2.0**901, 0) is not None
    pts[5, 1, 1] = np.inf
    with pytest.raises(ValueError, match="curve 5, control point 1 has a non-finite"):
        lb.evaluate_many(pts, t, "bezier")


def test_non_finite_and_overflow_are_named(monkeypatch, path):
    """A NaN late in the batch is named by its curve; an overflow when extrapolating, or
    with a λ outside the range, is refused by name."""
    monkeypatch.setattr(kernels, "CHUNK_ELEMENTS", 64)
    pts = np.random.default_rng(2).normal(size=(50, 4, 2))
    pts[41, 3, 0] = np.nan
    with pytest.raises(ValueError, match="curve 41, control point 3 has a non-finite"):
        lb.evaluate_many(pts, [0.0, 1.0], "bezier")
    pts[41] = np.random.default_rng(3).normal(size=(4, 2)) * 1e306
    with pytest.raises(ValueError, match="overflows the float range"):
        lb.evaluate_many(pts, [0.0, 30.0], "bezier", extrapolate=True)
    big = pts[:40] * 1e200
    for lam in (1e150, np.linspace(1e150, 2e150, 40)):  # one λ (folded), one per curve
        with pytest.raises(ValueError, match="overflows the float range"):
            lb.evaluate_many(big, [0.5], "same_degree", lam, check_range=False)


def test_evaluate_many_out():
    """out= writes the result into the caller's buffer and returns it, on every path (the
    tables, de Casteljau past them), scalar t included."""
    rng = np.random.default_rng(5)
    t = np.linspace(0, 1, 7)
    cases = [
        (rng.normal(size=(6, 4, 2)), "same_degree", 0.5),
        (rng.normal(size=(6, 4, 2)), "same_degree", rng.uniform(-1, 1, 6)),
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


def test_numbas_magnitude_test_is_numpys():
    """batch_compiled.odd_curves counts exactly the curves batch._curve_scales scales or
    refuses: NaN and infinities, largest coordinates each side of 2^900 and 2^-901, zero
    curves, subnormals beside ordinary coordinates, in any position of the curve."""
    pytest.importorskip("numba")
    from lambda_bezier.hazmat import batch_compiled

    rng = np.random.default_rng(8)
    specials = [np.nan, np.inf, -np.inf, 2.0**900, -(2.0**900), np.nextafter(2.0**900, 0)]
    tiny = [2.0**-901, np.nextafter(2.0**-901, 0), 1e-310, 5e-324, 0.0]
    for _ in range(300):
        pts = rng.normal(size=(int(rng.integers(1, 6)), int(rng.integers(1, 5)), 3))
        odd = 0
        for j in range(pts.shape[0]):
            kind = rng.integers(0, 4)
            i, c = rng.integers(0, pts.shape[1]), rng.integers(0, 3)
            if kind == 1:
                pts[j, i, c] = rng.choice(specials)
            elif kind == 2:  # the whole curve tiny: its largest coordinate decides
                pts[j] = 0.0
                pts[j, i, c] = rng.choice(tiny) * rng.choice([1, -1])
            elif kind == 3:
                pts[j, i, c] = rng.choice(tiny)  # beside ordinary coordinates: ordinary
        try:
            scales = batch._curve_scales(pts, 0)
            odd = 0 if scales is None else int((scales != 1.0).sum())
        except ValueError:  # a non-finite coordinate: at least one
            odd = -1
        got = batch_compiled.odd_curves(pts)
        assert got == odd if odd >= 0 else got >= 1
