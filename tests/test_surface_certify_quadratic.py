"""hazmat.surface_certify's quadratic test: "q0 + q1 t + q2 t² > slack on [a, b]" decided by
the quadratic's least value on the interval (its ends and its vertex), in numpy and in the
compiled twin (hazmat.surface_batch_compiled), and the certificates built on it.

References: the exact least value of each quadratic in Fractions (the float coefficients
and ends taken exactly) on adversarial quadratics (minimum at an end or a face, double
roots, vertex one ulp either side of an end, near-zero and zero q2, huge q1²/q2), dense
sampling on random ones, the Bernstein-coefficient test it replaced (written out here: it
must pass only a subset), and the independent vectorised certificate of hazmat.box_batch on
the at_cubic nets the sharper test now certifies and the Bernstein one declined."""

from __future__ import annotations

from fractions import Fraction
from importlib.util import find_spec

import numpy as np
import pytest

import lambda_bezier as lb
from lambda_bezier import param_surface_optimum as po
from lambda_bezier.hazmat import surface_certify as sc
from lambda_bezier.hazmat.surface_fixed_cost import fixed_cost_minimum
from lambda_bezier.param_surface_energy import _direction

AT = "tests/data/families/at_cubic.toml"


def exact_least(q0, q1, q2, a, b):
    """min over [a, b] of q, exactly, for the floats' exact values."""
    q0, q1, q2, a, b = (Fraction(float(v)) for v in (q0, q1, q2, a, b))
    candidates = [a, b]
    if q2 > 0 and a <= -q1 / (2 * q2) <= b:
        candidates.append(-q1 / (2 * q2))
    return min(q0 + q1 * t + q2 * t * t for t in candidates)


def bernstein_positive(q0, q1, q2, a, b, slack):
    """The test surface_certify used before: the three Bernstein coefficients on [a, b]."""
    at_a = q0 + (q1 + q2 * a) * a
    at_b = q0 + (q1 + q2 * b) * b
    middle = at_a + (b - a) * (q1 + 2 * a * q2) / 2
    return (at_a > slack) & (at_b > slack) & (middle > slack)


def adversarial():
    """(q0, q1, q2, a, b, slack) rows whose exact least value on [a, b] is at or near slack."""
    rows = []
    tiny = 2.0**-52
    for a, b in ((-1.0, 1.0), (0.0, 1.0), (-3.0, 0.5), (0.25, 0.3)):
        for v in (a, b, 0.5 * (a + b), np.nextafter(a, -np.inf), np.nextafter(b, np.inf),
                  np.nextafter(a, np.inf), np.nextafter(b, -np.inf), a - 0.1, b + 0.1):  # fmt: skip
            for q2 in (1.0, 3.0, 1e-8, 1e-300, 5e-324):
                for m in (0.0, tiny, -tiny, 1e-12, -1e-12, 1e-3):
                    # q = q2 (t − v)² + m: a double root at v when m = 0
                    q1 = -2 * q2 * v
                    q0 = q2 * v * v + m
                    for slack in (0.0, 1e-15):
                        rows.append((q0, q1, q2, a, b, slack))
            rows.append((1e-3, 1e200, 1e-200, a, b, 0.0))  # q1²/(4 q2) overflows
            rows.append((1.0, 0.0, 0.0, a, b, 0.0))  # constant
            rows.append((1.0, 0.3, -2.0, a, b, 0.0))  # concave: least at an end
            rows.append((1e-14, -1e-14, 0.0, a, b, 0.0))  # linear, near zero
    return np.array(rows).T


def compiled_quadratic():
    if find_spec("numba") is None:
        pytest.skip("numba is not installed (pip install '.[fast]'): the compiled twin")
    from lambda_bezier.hazmat import surface_batch_compiled as sbc

    return sbc._CERTIFY["_quadratic_positive"]


def test_the_quadratic_test_is_sound_and_sharp_against_exact_least_values():
    q0, q1, q2, a, b, slack = adversarial()
    with np.errstate(all="ignore"):
        got = sc._quadratic_positive(q0, q1, q2, a, b, slack)
    exact = [
        exact_least(*row[:5]) - Fraction(row[5])
        for row in zip(q0, q1, q2, a, b, slack, strict=True)
    ]
    size = (
        np.abs(q0) + np.abs(q1) * np.maximum(abs(a), abs(b)) + np.abs(q2) * np.maximum(a * a, b * b)
    )
    unit = 2.0**-53
    for i, margin in enumerate(exact):
        # sound: passed only where the exact least value exceeds slack, up to the rounding
        # of q's value at a point of [a, b] (4 units of its size; the callers' slack covers
        # 64 units and more). A q1² that underflows (q1, q2 below 1e-154) broke this once.
        if got[i]:
            assert margin > -4 * unit * size[i], (i, q0[i], q1[i], q2[i], a[i], b[i], slack[i])
        elif margin > 8 * unit * size[i] + 2.0**-1060:  # sharp: above rounding and underflow
            raise AssertionError(("declined", i, q0[i], q1[i], q2[i], a[i], b[i], float(margin)))
    # both outcomes occur among the adversarial rows (no test that cannot fail)
    assert 0 < np.count_nonzero(got) < got.size


def test_the_compiled_twin_decides_every_quadratic_alike():
    fn = compiled_quadratic()
    rows = adversarial()
    with np.errstate(all="ignore"):
        vectorised = sc._quadratic_positive(*rows)
    scalar = np.array([fn(*(float(v) for v in row)) for row in rows.T])
    assert np.array_equal(vectorised, scalar)


def test_random_quadratics_against_sampling_and_the_bernstein_test():
    rng = np.random.default_rng(11)
    q0, q1, q2 = rng.normal(size=(3, 4000))
    q0 = q0 + 0.5  # about half of them positive on the interval
    a, b = -1.0, 1.0
    t = np.linspace(a, b, 2001)
    least = (q0[:, None] + q1[:, None] * t + q2[:, None] * t * t).min(axis=1)
    sharp = sc._quadratic_positive(q0, q1, q2, a, b, 0.0)
    loose = bernstein_positive(q0, q1, q2, a, b, 0.0)
    assert not np.any(sharp & (least <= 0))  # never positive where a sample is not
    assert np.all(sharp[loose])  # sharper: whatever the Bernstein test passes
    assert np.count_nonzero(sharp & ~loose) > 100  # and the quadratics it could not decide
    assert np.all(sharp[least > 1e-6])


def _at_cubic_coefficients(nets, energy):
    d = _direction(lb.load_family(AT), 3)
    coeffs = po.energy_coefficients(nets, d, d, energy)
    return [coeffs[(a, b)] for a in range(3) for b in range(3)]


def test_every_set_the_bernstein_test_certified_is_certified_at_the_same_point(monkeypatch):
    nets = np.random.default_rng(5).normal(size=(400, 4, 4, 3))
    c = _at_cubic_coefficients(nets, "membrane")
    box = np.array([-1.0, 1.0, -1.0, 1.0])
    x1, y1, _, ok1, edge1 = fixed_cost_minimum(c, box, 1e-12)
    monkeypatch.setattr(sc, "_quadratic_positive", bernstein_positive)
    x0, y0, _, ok0, edge0 = fixed_cost_minimum(c, box, 1e-12)
    assert np.all(ok1[ok0]) and np.count_nonzero(ok1 & ~ok0) > 0
    same = ok0 & ~edge0 & ~edge1  # interior both times: the same computation, the same point
    assert np.array_equal(x0[same], x1[same]) and np.array_equal(y0[same], y1[same])
    both = ok0 & ok1  # certified by either test: within 1e-12 of the one minimiser
    assert np.abs(x0[both] - x1[both]).max() <= 2e-12
    assert np.abs(y0[both] - y1[both]).max() <= 2e-12


def test_the_newly_certified_sets_are_the_vectorised_box_certificates(monkeypatch):
    """On at_cubic nets the Bernstein test declined, the sets the sharper test certifies
    against hazmat.box_batch's certificate of the same nets (from its own float search):
    both within 1e-12 of the minimiser, so within 2e-12 of each other; on both engines the
    fixed-cost stage (po.fixed_cost) certifies exactly those sets."""
    fam = lb.load_family(AT)
    d = _direction(fam, 3)
    rng = np.random.default_rng(4)
    nets = rng.normal(size=(600, 4, 4, 3))
    nets[..., 0] += np.arange(4)[:, None]
    nets[..., 1] += np.arange(4)[None, :]
    c = _at_cubic_coefficients(nets, "thin_plate")
    box = np.array([-1.0, 1.0, -1.0, 1.0])
    x, y, energy, ok, on_edge = fixed_cost_minimum(c, box, 1e-12)
    stage = po.fixed_cost(nets, d, d, "thin_plate")
    # the engine's own coefficients (numba: emitted code with fused multiply-adds) differ
    # from numpy's in rounding, so a net at a threshold may differ (none does here)
    assert np.count_nonzero(stage[3] != ok) <= 3
    with monkeypatch.context() as patch:
        patch.setattr(sc, "_quadratic_positive", bernstein_positive)
        _, _, _, loose, _ = fixed_cost_minimum(c, box, 1e-12)
    new = np.flatnonzero(ok & ~loose)
    assert new.size > 0.05 * nets.shape[0] and np.count_nonzero(on_edge[new]) > 0
    boxed = po._careful_batch(nets[new], "thin_plate", (fam, fam), d, d)
    assert boxed.fallbacks <= 2
    assert np.abs(boxed.values[:, 0] - x[new]).max() <= 2e-12
    assert np.abs(boxed.values[:, 1] - y[new]).max() <= 2e-12
    assert np.allclose(boxed.energy, energy[new], rtol=1e-12, atol=0)


def adversarial_energies():
    """Nine coefficient arrays of E = A(y) x² + B(y) x + C(y) over [−1, 1]², every
    coefficient a dyadic float (so exact): A = (y − y0)² + α, with a double root in the box,
    at a face, just outside it, or near-zero least value α; B = −2 x1 + σ y, an
    unconstrained minimiser inside, on a face or outside; C = β y² − 2 y1 y + y1²."""
    rows = []
    for y0 in (-1.0, 0.0, 0.5, 1.0, 1.0 + 2.0**-20):
        for alpha in (0.0, 2.0**-40, 2.0**-10, 1.0):
            for x1 in (-1.0, 0.25, 1.0, 1.5):
                for sigma in (0.0, 0.125):
                    for y1 in (-1.0, 0.375, 1.25):
                        for beta in (1.0, 2.0**-30):
                            a = (y0 * y0 + alpha, -2 * y0, 1.0)
                            b = (-2 * x1, sigma, 0.0)
                            c = (y1 * y1, -2 * y1, beta)
                            # c[3 i + j]: x^i y^j
                            rows.append((*c, *b, *a))
    return [np.array(col) for col in zip(*rows, strict=True)]


def test_certified_minima_of_adversarial_energies_are_the_least_on_a_fine_grid():
    """Where either certificate accepts, the returned point's energy, exactly (Fractions),
    is no more than the least value of E over a fine grid of the box (each grid line's
    exact minimum over x in closed form, in floats): a certificate that accepted a point
    that is not the box's minimum (a local one, or one misplaced by a loose A > 0) fails.
    And every quadratic A here is nonnegative: where A has a root in the box no interior
    minimum may rest on A > 0 there."""
    c = adversarial_energies()
    box = np.array([-1.0, 1.0, -1.0, 1.0])
    x, y, value, ok, on_edge = fixed_cost_minimum(c, box, 1e-12)
    assert 0.2 * ok.size < np.count_nonzero(ok) < ok.size  # both outcomes occur
    assert np.count_nonzero(on_edge) > 0 and np.count_nonzero(ok & ~on_edge) > 0
    ys = np.unique(np.concatenate([np.linspace(-1, 1, 4097), np.clip(c[7] / -2, -1, 1)]))
    e = [v[:, None] for v in c]
    big_a = e[6] + (e[7] + e[8] * ys) * ys
    big_b = e[3] + (e[4] + e[5] * ys) * ys
    big_c = e[0] + (e[1] + e[2] * ys) * ys
    vertex = np.clip(-big_b / np.where(big_a > 0, 2 * big_a, 1.0), -1, 1)
    least = np.inf
    for xs in (-1.0, 1.0, vertex):
        least = np.minimum(least, big_c + (big_b + big_a * xs) * xs)
    grid = least.min(axis=1)
    for k in np.flatnonzero(ok):
        p, q = Fraction(float(x[k])), Fraction(float(y[k]))
        assert -1 <= p <= 1 and -1 <= q <= 1
        exact = sum(
            Fraction(float(c[3 * i + j][k])) * p**i * q**j for i in range(3) for j in range(3)
        )
        scale = 1 + abs(grid[k])
        assert float(exact) <= grid[k] + 1e-10 * scale, (k, float(exact), grid[k])
        assert abs(float(exact) - value[k]) <= 1e-13 * scale
