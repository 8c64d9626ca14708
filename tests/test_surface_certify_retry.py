"""The fixed-cost certificates' retry (hazmat.surface_certify.retry_minimum: a searched start,
more Newton steps, the sides beyond R cleared piece by piece, a face the energy grows from;
then the edge certificate at narrower bands, retry_edges) on what the interior and edge
certificates decline. Checked against the exact global minimiser over the box
(surface_energies.minimise_polynomial on the float coefficients' exact rational values), in
both engines, on at_cubic's energies (where it took 305 of the benchmark's 306 declined nets
and the face test the last) and on near ties, where it must decline or name the exact one."""

from __future__ import annotations

from fractions import Fraction
from importlib.util import find_spec

import numpy as np
import pytest

import lambda_bezier as lb
from lambda_bezier import param_surface_optimum as po
from lambda_bezier.hazmat import surface_certify as sc
from lambda_bezier.hazmat.surface_fixed_cost import fixed_cost_minimum, retry_edges
from lambda_bezier.param_surface_energy import _direction
from lambda_bezier.surface_energies import minimise_polynomial

BOX = (-1.0, 1.0, -1.0, 1.0)  # at_cubic's λ range in both directions
TOL = 1e-12
DATA = "tests/data/families/"
# net 9921 of the benchmark's 10,000 (bench_surfaces.bench_param_surfaces), its thin-plate
# coefficients e_ab at index 3a + b (rounded to 8 decimals: the same shape of energy): the
# interior minimum at (0.6454, 0.4989); min over every real λ_v of E(λ_u, ·) is below it near
# λ_u = −0.3, where the minimiser in λ_v lies below the box (λ_v < −1), so only the face
# λ_v = −1 (E growing from it into the box) clears that side
LAST = (80.14282374, 6.65543027, 5.17742057, -14.18144908, -30.06225627, 0.99867935,
        17.35714767, 3.61358687, 13.07238679)  # fmt: skip
TIE = 0.618142115963148  # LAST + TIE · λ_u: the interior and the face minimum nearly equal


def _engines():
    yield "numpy"
    if find_spec("numba") is not None:
        yield "numba"


def exact_minimiser(c):
    """The exact global minimiser over BOX of Σ c[3a + b] x^a y^b (floats taken exactly)."""
    poly = {(a, b): Fraction(float(c[3 * a + b])) for a in range(3) for b in range(3)}
    x, y, _ = minimise_polynomial(
        {k: v for k, v in poly.items() if v},
        (Fraction(BOX[0]), Fraction(BOX[1])),
        (Fraction(BOX[2]), Fraction(BOX[3])),
    )
    return float(x), float(y)


def run(engine, c):
    """(x, y, energy, status) of every set of c (nine arrays, c[3a + b] of x^a y^b): status
    1 certified inside, 2 on an edge or at a corner, 0 declined (the compiled engine: its
    certificate stage, which runs the retries on what the first two decline)."""
    if engine == "numba":
        from lambda_bezier.hazmat import surface_batch_compiled as sbc

        acc = np.ascontiguousarray(np.stack(c))
        out = np.empty((5, acc.shape[1]))
        sbc._certify_chunk(acc, acc.shape[1], np.array(BOX), TOL, out)
        return out[0], out[1], out[2], out[4].astype(int)
    x, y, energy, ok, on_edge = fixed_cost_minimum(c, np.array(BOX), TOL)
    return x, y, energy, np.where(on_edge, 2, np.where(ok, 1, 0))


@pytest.fixture(scope="module")
def at_cubic_sets():
    """Thin-plate coefficient sets of 1,500 at_cubic nets drawn as the benchmark draws them,
    and which of them the first two certificates decline."""
    fam = lb.load_family(DATA + "at_cubic.toml")
    rng = np.random.default_rng(4)
    nets = rng.normal(size=(1500, 4, 4, 3))
    nets[..., 0] += np.arange(4)[:, None]
    nets[..., 1] += np.arange(4)[None, :]
    d = _direction(fam, 3)
    coeffs = po.energy_coefficients(nets, d, d, "thin_plate")
    c = [coeffs.get((a, b), np.zeros(len(nets))) for a in range(3) for b in range(3)]
    with np.errstate(all="ignore"):
        *_, first = sc.certified_minimum(*c, *BOX, TOL)
        *_, edge = sc.edge_minimum(*c, *BOX, TOL)
    return c, ~(first | edge)


def test_the_retry_takes_what_both_certificates_decline(at_cubic_sets):
    """On the declined sets, the retries certify all but a few, and each answer they give
    (four inside, three on an edge) is the exact minimiser within its δ."""
    c, declined = at_cubic_sets
    assert declined.sum() >= 25  # about 3% of at_cubic's nets
    sub = [v[declined] for v in c]
    x, y, energy, status = run("numpy", sub)
    assert (status > 0).sum() >= declined.sum() - 1
    inside, edge = np.flatnonzero(status == 1), np.flatnonzero(status == 2)
    assert inside.size >= 4 and edge.size >= 3
    with np.errstate(all="ignore"):
        *_, delta, _ = sc.retry_minimum(*sub, *BOX, TOL)
        *_, edge_delta, _ = retry_edges(sub, np.array(BOX), TOL)
    for k in (*inside[:4], *edge[:3]):
        ex, ey = exact_minimiser([v[k] for v in sub])
        d = delta[k] if status[k] == 1 else edge_delta[k]
        assert d <= TOL
        assert abs(x[k] - ex) <= d + 2.0**-52 * abs(ex), (k, x[k], ex)
        assert abs(y[k] - ey) <= d + 2.0**-52 * abs(ey), (k, y[k], ey)


@pytest.mark.skipif(find_spec("numba") is None, reason="numba is not installed: compiled only")
def test_the_engines_agree_on_the_retry(at_cubic_sets):
    """The compiled kernel's retries (net by net, bands in turn) and the numpy engine's (every
    band at once) on the same coefficients: the same verdicts, the same points and energies."""
    c, declined = at_cubic_sets
    sub = [v[declined] for v in c]
    got, want = run("numba", sub), run("numpy", sub)
    assert np.array_equal(got[3], want[3])
    ok = want[3] > 0
    for a, b in zip(got[:3], want[:3], strict=True):
        assert np.allclose(a[ok], b[ok], rtol=4e-16, atol=1e-15)


@pytest.mark.parametrize("engine", list(_engines()))
def test_the_face_clears_a_side_whose_real_minimum_lies_outside_the_box(engine):
    """LAST: every earlier test declined it (the whole-side quartic, and the quartic piece by
    piece, since min over every real λ_v drops below the minimum near λ_u = −0.3); the face
    λ_v = −1 clears it, and the answer is the exact minimiser within 1e-12."""
    c = [np.array([v]) for v in LAST]
    with np.errstate(all="ignore"):
        *_, first = sc.certified_minimum(*c, *BOX, TOL)
    assert not first[0]
    x, y, _, status = run(engine, c)
    assert status[0] == 1
    ex, ey = exact_minimiser(LAST)
    assert abs(x[0] - ex) <= 2 * TOL and abs(y[0] - ey) <= 2 * TOL


@pytest.mark.parametrize("engine", list(_engines()))
@pytest.mark.parametrize("shift", [-1e-2, -1e-6, 0.0, 1e-6, 1e-3])
def test_a_near_tie_is_declined_or_named_exactly(engine, shift):
    """LAST + (TIE + shift) λ_u: an interior minimum and one on the face λ_v = −1 within
    about 1e-2 · |shift| of each other. Whatever is certified is the exact minimiser."""
    c = list(LAST)
    c[3] += TIE + shift
    x, y, _, status = run(engine, [np.array([v]) for v in c])
    if status[0]:
        ex, ey = exact_minimiser(c)
        assert abs(x[0] - ex) <= 2 * TOL and abs(y[0] - ey) <= 2 * TOL
    if shift >= 1e-3:  # the face's minimum clearly lower: certified there
        assert status[0] == 2 and y[0] == -1.0
