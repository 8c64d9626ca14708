"""Batches of float nets for families with two or more parameters in a direction (issue #31):
the vectorised stage (every net's energy coefficients at once from Kronecker weights, a grid
and one-parameter sweeps), the vectorised certificate of all nets at once
(hazmat.box_batch), then the nets it declines certified by the one-net path, counted in
``careful_fallbacks``.

References independent of the runtime's energy: for han_trig_cubic a dense float grid over
the four-parameter box with each grid point's energy by a float Gauss-Legendre rule on the
basis functions lambdified from the definition text by SymPy (test_trig_x_hyp_optimum); for
every family the exact surface energy at the batch's point (lb.surface_energy of the surface
built there) and each net's one-net certified result.
"""

from __future__ import annotations

from fractions import Fraction as F

import numpy as np
import pytest
from conftest import surface_families

import lambda_bezier as lb
from lambda_bezier import param_surface_optimum as po
from lambda_bezier.param_surface_energy import _direction, _energy_in_parameters

pytest.importorskip("sympy")
from test_trig_x_hyp_optimum import TRIG as TRIG_PATH  # noqa: E402
from test_trig_x_hyp_optimum import _grid_energies  # noqa: E402

TRIG, TWO, QB, _, _ = surface_families()
NETS = np.random.default_rng(17).normal(size=(3, 4, 4, 3))


def _params(res, i: int, names: tuple[str, ...], suffix: str) -> dict:
    return {x: F(float(res[f"{x}_{suffix}"][i])) for x in names}


@pytest.mark.parametrize("energy", ["membrane", "thin_plate"])
def test_a_trig_batch_is_certified_against_a_dense_grid(energy):
    got = lb.optimal_parameters(NETS, energy, family=TRIG)
    assert isinstance(got, po.SurfaceParameterBatch)
    assert sorted(got.parameters) == ["lam_u", "lam_v", "mu_u", "mu_v"]
    assert got["mu_v"].shape == got.energy.shape == (3,)
    assert got.careful_fallbacks == 0  # all three by the vectorised certificate
    for i in range(3):
        grid, _ = _grid_energies(NETS[i], energy, 13, (TRIG_PATH, TRIG_PATH))
        # attained: the exact energy of the surface at the batch's (rational) point
        surf = TRIG.surface(
            NETS[i],
            params_u=_params(got, i, ("lam", "mu"), "u"),
            params_v=_params(got, i, ("lam", "mu"), "v"),
        )
        attained = float(lb.surface_energy(surf, energy))
        assert abs(attained - got.energy[i]) <= 1e-12 * attained
        # no grid point over the box beats it (the float rule's rounding aside)
        assert attained <= grid.min() + 1e-11 * grid.max()


@pytest.mark.parametrize(
    ("fam", "names", "energy", "picked"),
    [(TWO, ("lam", "mu"), "thin_plate", [0, 1, 2]), (QB, ("lam",), "membrane", [2])],
    ids=["two", "indexed"],
)
def test_several_and_indexed_batches_match_each_nets_certified_minimum(fam, names, energy, picked):
    """q_bezier at degree 3 has three parameters a direction, six in the branch and bound:
    one net, whose one-net certificate takes a few seconds (a net over the budget makes a
    batch raise, naming it)."""
    nets = NETS[picked]
    count = len(picked)
    got = lb.optimal_parameters(nets, energy, family=fam)
    assert 0 <= got.careful_fallbacks <= count
    for i in range(count):
        one = lb.optimal_parameters(nets[i], energy, family=fam)
        lower, best = float(one.lower_bound), float(one.energy)
        slack = 1e-12 * abs(best)
        assert lower - slack <= got.energy[i] <= best + slack
        if fam is QB:  # an indexed family's values are one row per net
            assert got["lam_u"].shape == (count, 3)
            pu = {"lam": [F(float(x)) for x in got["lam_u"][i]]}
            pv = {"lam": [F(float(x)) for x in got["lam_v"][i]]}
        else:
            pu, pv = _params(got, i, names, "u"), _params(got, i, names, "v")
        surf = fam.surface(nets[i], params_u=pu, params_v=pv)
        attained = float(lb.surface_energy(surf, energy))
        assert abs(attained - got.energy[i]) <= 1e-12 * attained


def test_the_vectorised_coefficients_are_the_exact_polynomial():
    """Every net's float energy coefficients (one batched product with the Kronecker weights)
    against the exact energy polynomial of the same net, key by key."""
    d = _direction(TRIG, 3)
    exponents, weights = po._monomial_weights(TRIG, 3, TRIG, 3, "membrane")
    flat = NETS.reshape(3, -1, 3)
    coeffs = np.matmul(flat, flat.transpose(0, 2, 1)).reshape(3, -1) @ weights
    for k in range(3):
        rows = tuple(tuple(tuple(F(float(c)) for c in p) for p in row) for row in NETS[k])
        poly, constants, _ = _energy_in_parameters(rows, d, d, "membrane")
        assert constants == ("pi",)
        want: dict[tuple[int, ...], float] = {}
        for key, q in poly.items():
            want[key[:4]] = want.get(key[:4], 0.0) + float(q) * np.pi ** key[4]
        scale = max(abs(v) for v in want.values())
        for row, key in enumerate(map(tuple, exponents)):
            assert coeffs[k, row] == pytest.approx(want.get(key, 0.0), abs=1e-12 * scale)


def test_the_float_search_finds_a_known_minimum():
    """float_search on (x - 1/3)² + 2 (y + 1/2)² + x² y² (minimum near (1/3, -1/2) in the box
    [-1, 1]²), against a dense grid's minimiser."""
    exponents = np.array([[0, 0], [1, 0], [2, 0], [0, 1], [0, 2], [2, 2]])
    c = np.array([[1 / 9 + 0.5, -2 / 3, 1.0, 2.0, 2.0, 1.0]])
    got = po.float_search(c, exponents, np.array([-1.0, -1.0]), np.array([1.0, 1.0]))
    xs = np.linspace(-1, 1, 2001)
    X, Y = np.meshgrid(xs, xs, indexing="ij")
    E = (X - 1 / 3) ** 2 + 2 * (Y + 0.5) ** 2 + X**2 * Y**2
    k = np.unravel_index(np.argmin(E), E.shape)
    assert abs(got[0, 0] - X[k]) < 2e-3 and abs(got[0, 1] - Y[k]) < 2e-3
