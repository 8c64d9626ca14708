"""Batches of nets for the energy-optimal parameters of surfaces of atom families
(param_surface_optimum), against each net's certified minimum (its proven lower bound) and the
exact surface energy; the Bézier form of polynomial several-parameter and indexed surfaces
against their evaluation; and the refusals (atom across polynomial, to_bezier of atom
surfaces) named clearly (batches in several parameters: test_several_batch_optimum)."""

from __future__ import annotations

from fractions import Fraction as F

import numpy as np
import pytest
from conftest import surface_families

import lambda_bezier as lb
from lambda_bezier import param_surface_optimum as po
from lambda_bezier.param_surfaces import ParamSurface, family_surface

DATA = "tests/data/families/"
TRIG, TWO, QB, _, MIXED = surface_families()  # MIXED: at_pi_cubic, one parameter in [0, 1)
AT = lb.load_family(DATA + "at_cubic.toml")  # trigonometric, one parameter, [0, π/2]

NET = [[(i, j, F((i * j) % 3, 2) - F(i, 4)) for j in range(4)] for i in range(4)]


# ---------------------------------------------------------------------- batches
@pytest.mark.parametrize("fam", [AT, MIXED])
@pytest.mark.parametrize("energy", ["membrane", "thin_plate"])
def test_batch_agrees_with_each_nets_certified_minimum(fam, energy):
    nets = np.random.default_rng(7).normal(size=(10, 4, 4, 3))
    got = lb.optimal_parameters(nets, energy, family=fam)
    assert isinstance(got, po.SurfaceParameterBatch)
    assert got["lam_u"].shape == got["lam_v"].shape == got.energy.shape == (10,)
    assert 0 <= got.careful_fallbacks <= 10
    for i in range(0, 10, 3):
        one = lb.optimal_parameters(nets[i], energy, family=fam)
        assert one.method == "certified" and one.certified
        lower, best = float(one.lower_bound), float(one.energy)
        slack = 1e-12 * abs(best) + 1e-13
        # the batch's energy is attained (the surface's own energy at its point, exactly) ...
        at = fam.surface(
            nets[i],
            params_u={"lam": F(float(got["lam_u"][i]))},
            params_v={"lam": F(float(got["lam_v"][i]))},
            check_range=False,  # the excluded end lam = 1 of at_pi_cubic, as the minimum
        )
        attained = float(lb.surface_energy(at, energy))
        assert abs(attained - got.energy[i]) <= 1e-11 * abs(attained) + 1e-13
        # ... and no lower than the net's proven lower bound, nor above its certified minimum
        assert lower - slack <= attained <= best + slack


def test_batch_names_a_minimum_on_an_excluded_end_as_one_net_does():
    """A net whose minimum sits on the excluded end lam = 1 of at_pi_cubic is declined by the
    fixed-cost interior certificate; the vectorised careful path (hazmat.box_batch, the face
    held) certifies it there and names the end as the one-net path does."""
    nets = np.random.default_rng(7).normal(size=(6, 4, 4, 3))
    got = lb.optimal_parameters(nets, "thin_plate", family=MIXED)
    on_end = got.boundary != ""
    assert np.count_nonzero(on_end) > 0 and got.careful_fallbacks == 0
    for i in np.flatnonzero(on_end)[:2]:
        one = lb.optimal_parameters(nets[i], "thin_plate", family=MIXED)
        assert got.boundary[i] == one.boundary
        slack = 1e-12 * abs(float(one.energy))
        assert float(one.lower_bound) - slack <= got.energy[i] <= float(one.energy) + slack
    assert np.all((got["lam_u"][on_end] == 1.0) | (got["lam_v"][on_end] == 1.0))
    assert all("excluded: not attained" in b for b in got.boundary[on_end])


def test_batch_energy_coefficients_are_the_exact_polynomial():
    """The vectorised float coefficients of each net against the exact energy polynomial."""
    from lambda_bezier.param_surface_energy import _direction, energy_polynomial

    nets = np.random.default_rng(3).integers(-4, 5, size=(3, 4, 4, 2)).astype(float)
    d = _direction(AT, 3)
    coeffs = po.energy_coefficients(nets, d, d, "thin_plate")
    for k in range(3):
        rows = tuple(tuple(tuple(F(int(c)) for c in p) for p in row) for row in nets[k])
        poly, constant = energy_polynomial(rows, d, d, "thin_plate")
        assert constant == "pi"
        for (a, b), arr in coeffs.items():
            want = sum(
                float(v) * np.pi ** (key[2] - key[3])
                for key, v in poly.items()
                if key[:2] == (a, b)
            )
            assert arr[k] == pytest.approx(want, rel=1e-12, abs=1e-9)


def test_batch_refusals_name_the_problem():
    nets = np.zeros((2, 4, 4, 3))
    with pytest.raises(ValueError, match="NaN"):
        lb.optimal_parameters(np.full((2, 4, 4, 3), np.nan), "membrane", family=AT)
    with pytest.raises(ValueError, match="direction u: 5 control points make degree 4"):
        lb.optimal_parameters(np.zeros((2, 5, 4, 3)), "membrane", family=AT)
    with pytest.raises(ValueError, match="energy"):
        lb.optimal_parameters(nets, "bending", family=AT)


# ---------------------------------------------------------------------- Bézier forms
@pytest.mark.parametrize(
    ("fam", "pu", "pv"),
    [
        (TWO, {"lam": F(1, 2), "mu": -1}, {"lam": 0, "mu": F(1, 3)}),
        (QB, {"lam": [1, F(1, 2), -1]}, {"lam": [0, F(1, 3), F(-1, 2)]}),
    ],
)
def test_to_bezier_of_polynomial_surfaces_is_exact(fam, pu, pv):
    s = fam.surface(NET, params_u=pu, params_v=pv)
    assert isinstance(s, ParamSurface)
    b = s.to_bezier()
    assert all(isinstance(c, F) for row in b.control_net() for p in row for c in p)
    us, vs = np.linspace(0, 1, 7), np.linspace(0, 1, 5)
    # against the surface as curves of the family (each column, then the row through them)
    for u in us:
        cols = [fam.curve([NET[i][j] for i in range(4)], **_given(fam, pu)) for j in range(4)]
        row = fam.curve([c.evaluate(u) for c in cols], **_given(fam, pv))
        assert np.allclose(b.evaluate(np.full(5, u), vs), row.evaluate(vs), atol=1e-13)


def _given(fam, params):
    return {"lam": params["lam"]} if fam is QB else {"params": params}


@pytest.mark.parametrize(
    ("fam", "words"),
    [(TRIG, "to_rational_bezier"), (MIXED, "no rational form either")],
)
def test_to_bezier_of_atom_surfaces_says_what_to_use(fam, words):
    pu = {k: 0 for k in fam.parameters}
    s = fam.surface(NET, params_u=pu, params_v=pu)
    with pytest.raises(ValueError, match=words):
        s.to_bezier()


def test_atom_across_polynomial_is_an_atom_surface_either_way():
    """Once refused; now the surface of each direction's family (tests/test_mixed_surfaces.py
    checks its quantities)."""
    pu = {"lam": 0, "mu": 0}
    for pair, fams in (
        ((TRIG, TWO), ("han_trig_cubic", "two_shape_cubic")),
        ((TWO, TRIG), ("two_shape_cubic", "han_trig_cubic")),
    ):
        s = family_surface(NET, pair, params_u=pu, params_v=pu)
        assert s.family == fams


def test_batch_engines_agree(monkeypatch):
    """The compiled kernel (numba; its generic coefficients, and the coefficients emitted
    for these weights as a large batch takes them) and the numpy engine on the same nets."""
    from lambda_bezier.hazmat import surface_kernels as ker
    from lambda_bezier.param_surface_energy import _direction

    nets = np.random.default_rng(11).normal(size=(200, 4, 4, 3))
    nets[..., 0] += np.arange(4)[:, None]
    d = _direction(AT, 3)
    compiled = po.fixed_cost(nets, d, d, "thin_plate")
    fast = po._batch_compiled()
    if fast is not None:  # the emitted coefficients, as for a batch of 1,024 nets or more
        with monkeypatch.context() as patch:
            patch.setattr(fast, "EMITTED_MIN_NETS", 1)
            emitted = po.fixed_cost(nets, d, d, "thin_plate")
        assert np.array_equal(emitted[3], compiled[3])
        assert np.array_equal(emitted[4], compiled[4])
        ok = compiled[3]
        for a, b in zip(emitted[:3], compiled[:3], strict=True):
            assert np.allclose(a[ok], b[ok], rtol=1e-12, atol=1e-12)
    monkeypatch.setattr(ker, "USE_COMPILED", False)
    plain = po.fixed_cost(nets, d, d, "thin_plate")
    assert po._batch_compiled() is None
    assert compiled[3].sum() > 100  # most nets certified
    assert np.array_equal(compiled[3], plain[3])
    assert np.array_equal(compiled[4], plain[4])  # the same nets certified on an edge
    ok = plain[3]
    for a, b in zip(compiled[:3], plain[:3], strict=True):
        assert np.allclose(a[ok], b[ok], rtol=1e-12, atol=1e-12)


def test_edge_certified_nets_name_their_ends_and_meet_the_one_net_bound():
    """Nets the interior certificate declines and the edge certificate takes (status 2 of the
    kernel): the point is the one-net certified path's (which stops within its tolerance of the
    edge, so its own note is empty), the energy lies between that path's proven lower bound and
    its energy, and the boundary note names the end the point is on."""
    from lambda_bezier.param_surface_energy import _direction

    nets = np.random.default_rng(1).normal(size=(300, 4, 4, 3))
    d = _direction(AT, 3)
    *_, on_edge = po.fixed_cost(nets, d, d, "thin_plate")
    assert on_edge.sum() >= 5
    got = lb.optimal_parameters(nets, "thin_plate", family=AT)
    for i in np.flatnonzero(on_edge)[:5]:
        one = lb.optimal_parameters(nets[i], "thin_plate", family=AT)
        assert abs(got["lam_u"][i] - float(one["lam_u"])) <= 1e-9
        assert abs(got["lam_v"][i] - float(one["lam_v"])) <= 1e-9
        lower, best = float(one.lower_bound), float(one.energy)
        slack = 1e-12 * abs(best) + 1e-13
        assert lower - slack <= got.energy[i] <= best + slack
        ends = [
            f"lam_{s} = {int(v)} ({'upper' if v > 0 else 'lower'} end)"
            for s, v in (("u", got["lam_u"][i]), ("v", got["lam_v"][i]))
            if abs(v) == 1.0
        ]
        assert ends and got.boundary[i] == "; ".join(ends)
