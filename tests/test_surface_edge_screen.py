"""The screened edge pass of the fixed-cost stage (hazmat.surface_edge_screen): its screen
never skips an edge that surface_certify._edge certifies, and the stage's answers are
surface_batch_compiled.optimise_batch's bit for bit."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import family_file

import lambda_bezier as lb

numba = pytest.importorskip("numba", reason="numba is not installed (pip install '.[fast]')")
from lambda_bezier.hazmat import surface_certify as sc  # noqa: E402
from lambda_bezier.hazmat import surface_edge_screen as ses  # noqa: E402

_edge, _may, _largest = ses._edge, ses._edge_may, ses._largest


@numba.njit(cache=True)
def both(coeffs, box, tol):
    """(n, 4) flags: _edge's certified one and the screen's, per net and edge (edge_minimum's
    order: x = xlo, x = xhi, y = ylo, y = yhi)."""
    xlo, xhi, ylo, yhi = box[0], box[1], box[2], box[3]
    r = sc.RADIUS * max(xhi - xlo, yhi - ylo)
    ok = np.zeros((coeffs.shape[0], 4), np.bool_)
    screened = np.zeros((coeffs.shape[0], 4), np.bool_)
    for k in range(coeffs.shape[0]):
        e00, e01, e02, e10, e11, e12, e20, e21, e22 = coeffs[k]
        emax = _largest(e00, e01, e02, e10, e11, e12, e20, e21, e22)
        for side in range(4):
            if side < 2:
                s0, lo, hi = (xlo if side == 0 else xhi), ylo, yhi
                a0, a1, a2, b0, b1, b2, c0, c1, c2 = e20, e21, e22, e10, e11, e12, e00, e01, e02
            else:
                s0, lo, hi = (ylo if side == 2 else yhi), xlo, xhi
                a0, a1, a2, b0, b1, b2, c0, c1, c2 = e02, e12, e22, e01, e11, e21, e00, e10, e20
            inward = 1.0 if side % 2 == 0 else -1.0
            ok[k, side] = _edge(
                a0, a1, a2, b0, b1, b2, c0, c1, c2, s0, inward, lo, hi, r, emax, tol
            )[3]
            screened[k, side] = _may(
                a0, a1, a2, b0, b1, b2, c1, c2, s0, inward, lo, hi, r, emax, tol
            )
    return ok, screened


def test_the_screen_keeps_every_edge_the_certificate_certifies():
    # energies whose linear terms push the minimiser to or past the box's edges (the edge
    # certificate's own tests' distribution), at several scales, and tiny/huge ones
    rng = np.random.default_rng(20)
    n = 20_000
    c = (
        np.column_stack(
            [
                rng.integers(-60, 61, n),
                rng.integers(-40, 41, n),
                rng.integers(1, 10, n),
                rng.integers(-40, 41, n),
                rng.integers(-4, 5, n),
                rng.integers(-2, 3, n),
                rng.integers(1, 10, n),
                rng.integers(-2, 3, n),
                rng.integers(-1, 2, n),
            ]
        )
        / 8.0
    )
    c *= 10.0 ** rng.integers(-150, 150, n)[:, None]
    for box in (np.array([-2.0, 1.0, -2.0, 1.0]), np.array([-1.0, 1.0, -1.0, 1.0])):
        ok, screened = both(c, box, 1e-12)
        assert ok.sum() > 2_000  # the test sees many certified edges
        assert not (ok & ~screened).any()  # none of them screened out
        assert (~screened).sum() > 0.5 * ok.size  # and the screen skips most edges


def test_the_stage_is_optimise_batch_bit_for_bit():
    # at_cubic's thin plate and membrane weights (about 1 net in 11 reaches the edge pass) and
    # the built-in bicubic's, on the benchmark's kind of nets; 2,048 nets: the emitted code
    from lambda_bezier import param_surface_optimum as po
    from lambda_bezier.hazmat import surface_batch_compiled as sbc
    from lambda_bezier.param_surface_energy import _direction

    fam = lb.load_family(family_file("at_cubic"))
    rng = np.random.default_rng(31)
    nets = rng.normal(size=(2048, 4, 4, 3))
    nets[..., 0] += np.arange(4)[:, None]
    nets[..., 1] += np.arange(4)[None, :]
    flat = np.ascontiguousarray(nets.reshape(len(nets), -1))
    d = _direction(fam, 3)
    (xlo, xhi), (ylo, yhi) = po._box(d), po._box(d)
    box = np.array([float(xlo), float(xhi), float(ylo), float(yhi)])
    for energy in ("thin_plate", "membrane"):
        w = po._batch_weights(d.family, 3, d.family, 3, energy)
        args = (flat, 3, w, box, po.CERTIFIED_TOLERANCE, po.MAX_COORDINATE)
        got = ses.optimise_batch(*args)
        want = sbc.optimise_batch(*args, use_emitted=True)
        for a, b in zip(got[:5], want[:5], strict=True):
            np.testing.assert_array_equal(a, b)
        assert got[5] == want[5]
        status = got[4]
        assert (status == 2.0).sum() > 20 and (status == 0.0).sum() > 20, energy
        # and on fewer nets than the emitted code takes: optimise_batch's own answer
        small = ses.optimise_batch(flat[:100], *args[1:])
        np.testing.assert_array_equal(small[4], sbc.optimise_batch(flat[:100], *args[1:])[4])
