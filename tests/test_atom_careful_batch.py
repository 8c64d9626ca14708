"""The nets of a batch of atom-family nets (one parameter a direction) that the fixed-cost
stage's first two certificates decline, whose minima lie inside the box, within r of a face,
on an edge or at a corner: certified without the one-net path, by the stage's retries
(hazmat.surface_certify.retry_minimum, retry_edges; round 21) and by the vectorised careful
path (param_surface_optimum._careful_batch, hazmat.box_batch), which took them all before
(issue #31).

References, independent of the batch's float coefficients and certificate: each net's
one-net certified minimum (the exact energy polynomial in ℚ[π, 1/π], Bernstein branch and
bound with a proven lower bound), the surface's own energy at the batch's point
(lb.surface_energy), and the exact critical point near the batch's point, by Newton's
method in mpmath (60 digits) on the exact energy polynomial of the net read as exact
binary fractions (on an edge, along it; at a corner, the corner itself).
"""

from __future__ import annotations

from fractions import Fraction as F

import mpmath
import numpy as np
import pytest

import lambda_bezier as lb
from lambda_bezier import param_surface_optimum as po
from lambda_bezier.hazmat import surface_certify as sc
from lambda_bezier.param_surface_energy import _direction, energy_polynomial

AT = lb.load_family("tests/data/families/at_cubic.toml")  # trigonometric, lam in [-1, 1]
D = _direction(AT, 3)
R = 1 / 32  # the fixed-cost certificate's R half-width on [-1, 1]: nearer a face it declines


def _nets(count: int) -> np.ndarray:
    """The benchmark's nets (benchmarks/bench_surfaces.py, bench_param_surfaces): the first
    `count`."""
    rng = np.random.default_rng(4)
    nets = rng.normal(size=(count, 4, 4, 3))
    nets[..., 0] += np.arange(4)[:, None]
    nets[..., 1] += np.arange(4)[None, :]
    return nets


def _first_two_decline(nets: np.ndarray, energy: str) -> np.ndarray:
    """Which nets the fixed-cost stage's interior and edge certificates both decline (numpy,
    on the nets' float coefficients): the nets its retries, or the careful path, take."""
    coeffs = po.energy_coefficients(nets, D, D, energy)
    c = [coeffs.get((a, b), np.zeros(len(nets))) for a in range(3) for b in range(3)]
    with np.errstate(all="ignore"):
        *_, first = sc.certified_minimum(*c, -1.0, 1.0, -1.0, 1.0, 1e-12)
        *_, edge = sc.edge_minimum(*c, -1.0, 1.0, -1.0, 1.0, 1e-12)
    declined: np.ndarray = ~(np.asarray(first) | np.asarray(edge))
    return declined


def _without_retries(monkeypatch: pytest.MonkeyPatch) -> None:
    """The public call as before round 21: the nets the first two certificates decline go
    to the careful path (the compiled kernel's retries cannot be switched off inside it)."""
    real = po._fixed_cost

    def first_two(nets, du, dv, energy):
        bx, by, bval, ok, on_edge, valid = real(nets, du, dv, energy)
        declined = _first_two_decline(nets, energy)
        return bx, by, bval, ok & ~declined, on_edge & ~declined, valid

    monkeypatch.setattr(po, "_fixed_cost", first_two)


def _classes(x: np.ndarray) -> dict[str, np.ndarray]:
    """Rows of x (points of [-1, 1]²) by where they lie."""
    gap = np.min(1 - np.abs(x), axis=1)
    corner = np.all(np.abs(x) == 1, axis=1)
    return {
        "interior": np.flatnonzero(gap >= R),
        "near a face": np.flatnonzero((gap > 0) & (gap < R)),
        "edge": np.flatnonzero((gap == 0) & ~corner),
        "corner": np.flatnonzero(corner),
    }


def _exact_critical_point(net: np.ndarray, energy: str, x: np.ndarray) -> np.ndarray:
    """The critical point of the exact energy of `net` (its floats as exact fractions) nearest
    the float point x, free in the coordinates not at ±1: Newton in mpmath at 60 digits."""
    rows = tuple(tuple(tuple(F(float(c)) for c in p) for p in row) for row in net)
    poly, constant = energy_polynomial(rows, D, D, energy)
    assert constant == "pi"
    with mpmath.workdps(60):
        pi = mpmath.pi
        e = {}
        for key, v in poly.items():
            c = mpmath.mpf(v.numerator) / v.denominator * pi ** (key[2] - key[3])
            e[key[:2]] = e.get(key[:2], 0) + c
        free = [j for j in range(2) if abs(x[j]) != 1]
        p = [mpmath.mpf(float(t)) for t in x]

        def d(a: int, b: int, i: int, j: int) -> object:  # ∂^i_x ∂^j_y E at p
            total = mpmath.mpf(0)
            for (ea, eb), c in e.items():
                if ea >= i and eb >= j:
                    fa = mpmath.ff(ea, i) * p[0] ** (ea - i)
                    fb = mpmath.ff(eb, j) * p[1] ** (eb - j)
                    total += c * fa * fb
            return total

        for _ in range(8):
            g = [d(0, 0, 1, 0), d(0, 0, 0, 1)]
            h = [[d(0, 0, 2, 0), d(0, 0, 1, 1)], [d(0, 0, 1, 1), d(0, 0, 0, 2)]]
            if len(free) == 2:
                step = mpmath.lu_solve(mpmath.matrix(h), mpmath.matrix(g))
                p = [p[0] - step[0], p[1] - step[1]]
            elif len(free) == 1:
                j = free[0]
                p[j] = p[j] - g[j] / h[j][j]
        return np.array([float(t) for t in p])


@pytest.mark.parametrize("energy", ["thin_plate", "membrane"])
def test_the_nets_both_fixed_cost_certificates_decline_are_certified_vectorised(energy):
    nets = _nets(400)
    declined = np.flatnonzero(_first_two_decline(nets, energy))
    got = lb.optimal_parameters(nets, energy, family=AT)
    x = np.stack([got["lam_u"], got["lam_v"]], axis=1)
    # the careful path on the same nets (it took them all before the retries): the same
    # boundary notes, energies within 1e-12 and points within twice the certified 1e-12
    careful = po._careful_batch(nets[declined], energy, (AT, AT), D, D)
    assert careful.fallbacks <= 1
    assert np.all(careful.boundary == got.boundary[declined])
    assert np.allclose(careful.energy, got.energy[declined], rtol=1e-12, atol=0)
    assert np.abs(careful.values - x[declined]).max() <= 2e-12
    classes = _classes(x[declined])
    # the benchmark's nets hold declined interior and edge minima; the fixed-cost stage
    # certifies every corner minimum among them (thin plate has none; membrane's take the
    # careful path in the next test) and, since its R shrinks near a face (round 20,
    # hazmat.surface_certify), the minima within the fixed R of a face: those are checked
    # here all the same, whichever stage certified them
    assert classes["interior"].size and classes["edge"].size, {
        k: v.size for k, v in classes.items()
    }
    near = _classes(x)["near a face"]
    assert near.size
    checked = {
        "interior": declined[classes["interior"][:2]],
        "edge": declined[classes["edge"][:2]],
        "near a face": near[:2],
    }
    # the one-net path takes only a few of them (counted before the retries: one membrane
    # net of the 400, of the 9 declined); the retries and the careful path the rest
    assert got.careful_fallbacks <= 1 < declined.size
    for kind, rows in checked.items():
        for i in rows:
            one = lb.optimal_parameters(nets[i], energy, family=AT)
            lower, best = float(one.lower_bound), float(one.energy)
            slack = 1e-12 * abs(best)
            assert lower - slack <= got.energy[i] <= best + slack, (kind, i)
            assert got.boundary[i] == one.boundary, (kind, i)
            surface = AT.surface(
                nets[i], params_u={"lam": F(float(x[i, 0]))}, params_v={"lam": F(float(x[i, 1]))}
            )
            attained = float(lb.surface_energy(surface, energy))
            assert abs(attained - got.energy[i]) <= 1e-12 * abs(attained), (kind, i)
            # the certified 1e-12 of the minimiser, against the exact critical point
            exact = _exact_critical_point(nets[i], energy, x[i])
            assert np.abs(exact - x[i]).max() <= 1e-12, (kind, i, exact - x[i])


def test_corner_minima_are_certified_alike_by_the_fixed_cost_stage_and_the_careful_path():
    """Membrane's corner minima among the benchmark's nets, certified by the fixed-cost
    stage's edge certificate, against the careful path (param_surface_optimum._careful_batch)
    on the same nets and against each net's one-net certified minimum (the first two)."""
    nets = _nets(400)
    x, y, energy, ok, on_edge = po.fixed_cost(nets, D, D, "membrane")
    corners = np.flatnonzero(ok & on_edge & (np.abs(x) == 1) & (np.abs(y) == 1))
    assert corners.size >= 2
    careful = po._careful_batch(nets[corners], "membrane", (AT, AT), D, D)
    assert careful.fallbacks <= 1
    assert np.array_equal(careful.values[:, 0], x[corners])
    assert np.array_equal(careful.values[:, 1], y[corners])
    assert np.allclose(careful.energy, energy[corners], rtol=1e-12, atol=0)
    got = lb.optimal_parameters(nets[corners], "membrane", family=AT)
    assert np.all(got.boundary == careful.boundary) and got.careful_fallbacks == 0
    for k, i in enumerate(corners[:2]):
        one = lb.optimal_parameters(nets[i], "membrane", family=AT)
        lower, best = float(one.lower_bound), float(one.energy)
        assert lower - 1e-12 * abs(best) <= energy[i] <= best + 1e-12 * abs(best)
        assert got.boundary[k] == one.boundary


def test_careful_fallbacks_counts_every_net_solved_one_by_one(monkeypatch):
    """The counter is the number of one-net calls; with the vectorised certificate declining
    every net, every net the compiled stage declined is solved one by one, to the same
    answers."""
    nets = _nets(60)
    calls = []
    one_net = po.certified_parameters

    def counted(*args, **kwargs):
        calls.append(1)
        return one_net(*args, **kwargs)

    monkeypatch.setattr(po, "certified_parameters", counted)
    _without_retries(monkeypatch)  # so that the careful path has nets to decline
    got = lb.optimal_parameters(nets, "thin_plate", family=AT)
    assert got.careful_fallbacks == len(calls)
    declined = np.flatnonzero(_first_two_decline(nets, "thin_plate"))
    assert declined.size > 0

    def declines_all(coeffs, exponents, lo, hi, start, tol):
        x = np.clip(start, lo, hi)
        return x, np.zeros(len(x)), np.full(len(x), np.inf), np.zeros(len(x), bool)

    calls.clear()
    monkeypatch.setattr(po.box_batch, "certified_minimum", declines_all)
    slow = lb.optimal_parameters(nets, "thin_plate", family=AT)
    assert slow.careful_fallbacks == len(calls) == declined.size
    assert np.all(slow.boundary == got.boundary)
    assert np.allclose(slow.energy, got.energy, rtol=1e-12, atol=0)
    for name in ("lam_u", "lam_v"):  # the one-net point is certified in energy: ~sqrt(1e-12)
        assert np.abs(slow[name] - got[name]).max() <= 1e-5


@pytest.mark.parametrize(
    ("file", "energy"),
    [("lit_hyp_quad.toml", "thin_plate"), ("lit_hyp_quad.toml", "membrane")],
)
def test_hyperbolic_families_batches_agree_with_each_nets_certified_minimum(file, energy):
    """One-parameter hyperbolic families (constant e^W): the same stages, against each net's
    one-net certified minimum (every eighth net) and the surface's own energy."""
    fam = lb.load_family("tests/data/families/" + file)
    nets = np.random.default_rng(9).normal(size=(24, 3, 3, 3))
    got = lb.optimal_parameters(nets, energy, family=fam)
    assert got.careful_fallbacks <= 2
    for i in range(0, 24, 8):
        one = lb.optimal_parameters(nets[i], energy, family=fam)
        lower, best = float(one.lower_bound), float(one.energy)
        slack = 1e-12 * abs(best)
        assert lower - slack <= got.energy[i] <= best + slack
        assert got.boundary[i] == one.boundary
        surface = fam.surface(
            nets[i],
            params_u={"lam": F(float(got["lam_u"][i]))},
            params_v={"lam": F(float(got["lam_v"][i]))},
        )
        attained = float(lb.surface_energy(surface, energy))
        assert abs(attained - got.energy[i]) <= 1e-12 * abs(attained)
