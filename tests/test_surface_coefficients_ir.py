"""The batch optimum's energy coefficients from emitted vector code
(hazmat.surface_coefficients_ir): against the exact energy polynomial of each net
(Fractions), whole blocks and a padded tail, several families, shapes and dimensions; the
coordinates' check it carries; and the large batch path
(surface_batch_compiled.optimise_batch) against the generic compiled kernel and the exact
method."""

from __future__ import annotations

from fractions import Fraction
from importlib.util import find_spec

import numpy as np
import pytest

import lambda_bezier as lb
from lambda_bezier.surface_energies import MAX_COORDINATE, surface_energy_matrices
from lambda_bezier.surface_optimum import CERTIFIED_TOLERANCE, _batch_weights
from lambda_bezier.surfaces import _as_family_pair

pytestmark = pytest.mark.skipif(
    find_spec("numba") is None, reason="numba is not installed (pip install '.[fast]')"
)

CASES = [  # family, degrees, energy, dim: the rows R = points x dim span 0-9 whole tiles of 8
    ("same_degree", (3, 3), "thin_plate", 3),
    ("bernstein_like", (3, 3), "thin_plate", 1),
    (("same_degree", "bezier"), (4, 3), "thin_plate", 2),
    (("bezier", "bernstein_like"), (3, 5), "membrane", 3),
]


def weights_for(family, degrees, energy, dim):
    u_cls, v_cls = _as_family_pair(family)
    mats = surface_energy_matrices(degrees, energy, (u_cls, v_cls))
    return mats, _batch_weights(mats, u_cls, v_cls, dim)


def exact_coefficients(mats, net):
    poly = mats.polynomial([[[Fraction(x) for x in p] for p in row] for row in net])
    return np.array([float(poly.get((a, b), 0)) for a in range(3) for b in range(3)])


@pytest.mark.parametrize(("family", "degrees", "energy", "dim"), CASES)
def test_emitted_coefficients_are_each_nets_exact_energy_polynomial(family, degrees, energy, dim):
    from lambda_bezier.hazmat import surface_coefficients_ir as ir

    mats, w = weights_for(family, degrees, energy, dim)
    count = 2 * ir.LANES + 3  # two whole blocks and a tail
    rng = np.random.default_rng(7)
    nets = rng.normal(size=(count, degrees[0] + 1, degrees[1] + 1, dim)) * rng.uniform(
        0.1, 10, size=(count, 1, 1, 1)
    )
    flat = np.ascontiguousarray(nets.reshape(count, -1))
    fn = ir.kernel(w, dim, flat.shape[1])
    assert fn is not None  # built here: the fallback to the generic kernel is not silent in CI
    out = np.full((9, count), np.nan)
    assert ir.coefficients(fn, flat, 0, count, out, MAX_COORDINATE)
    part = np.full((9, count - 5), np.nan)  # an offset start, ending in a tail
    assert ir.coefficients(fn, flat, 5, count, part, MAX_COORDINATE)
    for k in range(count):
        want = exact_coefficients(mats, nets[k])
        size = np.abs(want).sum()
        assert np.abs(out[:, k] - want).max() <= 1e-13 * size, k
        if k >= 5:
            assert np.array_equal(part[:, k - 5], out[:, k])


@pytest.mark.parametrize("where", [3, 2 * 8 + 1])  # in a whole block, in the padded tail
@pytest.mark.parametrize("bad", [np.nan, np.inf, -2 * MAX_COORDINATE])
def test_emitted_code_reports_a_coordinate_out_of_range(where, bad):
    from lambda_bezier.hazmat import surface_coefficients_ir as ir

    _, w = weights_for("same_degree", (3, 3), "thin_plate", 3)
    flat = np.random.default_rng(1).normal(size=(19, 48))
    fn = ir.kernel(w, 3, 48)
    assert fn is not None
    out = np.empty((9, 19))
    assert ir.coefficients(fn, flat, 0, 19, out, MAX_COORDINATE)
    flat[where, 47] = bad
    assert not ir.coefficients(fn, flat, 0, 19, out, MAX_COORDINATE)
    flat[where, 47] = MAX_COORDINATE  # the limit itself is allowed
    assert ir.coefficients(fn, flat, 0, 19, out, MAX_COORDINATE)


def test_large_batch_path_agrees_with_the_generic_kernel_and_the_exact_method(monkeypatch):
    """optimise_batch with the emitted coefficients against optimise (the generic compiled
    kernel, the coefficients summed in another order): the same certificate verdicts on
    3,000 nets here, answers within the certified 1e-12; and the public call on a batch large
    enough to take that path against the exact method on a few of its nets."""
    from lambda_bezier.hazmat import surface_batch_compiled as sbc

    rng = np.random.default_rng(12)
    count = 3000
    nets = rng.normal(size=(count, 4, 4, 3))
    nets[..., 0] += np.arange(4)[:, None]
    nets[..., 1] += np.arange(4)[None, :]
    _, w = weights_for("same_degree", (3, 3), "thin_plate", 3)
    flat = np.ascontiguousarray(nets.reshape(count, 48))
    box = np.array([-2.0, 1.0, -2.0, 1.0])
    new = sbc.optimise_batch(flat, 3, w, box, CERTIFIED_TOLERANCE, MAX_COORDINATE)
    old = sbc.optimise(flat, 3, w, box, CERTIFIED_TOLERANCE, MAX_COORDINATE)
    assert new[5] and old[5]
    assert np.array_equal(new[4], old[4])
    monkeypatch.setattr(sbc, "ONE_PASS", 1000)  # in spans of 1,024 (the last one shorter)
    monkeypatch.setattr(sbc, "SPAN", 1024)
    spans = sbc.optimise_batch(flat, 3, w, box, CERTIFIED_TOLERANCE, MAX_COORDINATE)
    for a, b in zip(spans, new, strict=True):
        assert np.array_equal(a, b)  # the same arithmetic, net by net
    monkeypatch.undo()
    assert (new[4] > 0).mean() > 0.95
    done = new[4] > 0
    for i in (0, 1):  # both certified within 1e-12 of the same unique minimiser
        assert np.abs(new[i][done] - old[i][done]).max() <= 2 * CERTIFIED_TOLERANCE
    assert np.allclose(new[2][done], old[2][done], rtol=1e-13, atol=0)
    result = lb.optimal_parameters(nets, "thin_plate")
    assert np.array_equal(result["lam_u"][done], new[0][done])
    for k in np.flatnonzero(done)[:2].tolist() + np.flatnonzero(~done)[:1].tolist():
        exact = lb.optimal_parameters(
            [[[Fraction(c) for c in p] for p in row] for row in nets[k]], "thin_plate"
        )
        assert abs(result["lam_u"][k] - exact["lam_u_float"]) <= 1e-12
        assert abs(result["lam_v"][k] - exact["lam_v_float"]) <= 1e-12


@pytest.mark.parametrize(
    ("bad", "message"), [(np.nan, "NaN or infinity"), (1e200, "above 1e\\+140")]
)
def test_a_large_batch_with_a_bad_coordinate_is_refused_by_name(bad, message):
    """The emitted code's check (a batch large enough to take it) raises the same errors as
    the numpy path, naming the problem."""
    from lambda_bezier.hazmat import surface_batch_compiled as sbc

    nets = np.random.default_rng(3).normal(size=(sbc.EMITTED_MIN_NETS + 5, 4, 4, 3))
    nets[sbc.EMITTED_MIN_NETS + 2, 2, 1, 0] = bad  # in the padded tail
    with pytest.raises(ValueError, match=message):
        lb.optimal_parameters(nets, "thin_plate")
