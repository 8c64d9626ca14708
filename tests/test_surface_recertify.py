"""hazmat.surface_recertify: surface_certify's fixed-cost certificates with the positivity of
a quadratic on an interval decided by its least value (not its Bernstein coefficients).

References: dense sampling of each quadratic (no quadratic is called positive where a
sampled value is not), surface_certify's own certificates (every set they certify, the
sharper one certifies at the same point), and the independent vectorised certificate of
hazmat.box_batch on the at_cubic benchmark nets the compiled stage declines."""

from __future__ import annotations

import numpy as np

import lambda_bezier as lb
from lambda_bezier import param_surface_optimum as po
from lambda_bezier.hazmat import surface_certify as sc
from lambda_bezier.hazmat import surface_recertify as sr
from lambda_bezier.hazmat.surface_fixed_cost import fixed_cost_minimum
from lambda_bezier.param_surface_energy import _direction


def test_a_quadratic_is_called_positive_only_where_it_is():
    rng = np.random.default_rng(11)
    q0, q1, q2 = rng.normal(size=(3, 4000))
    q0 = q0 + 0.5  # about half of them positive on the interval
    a, b = -1.0, 1.0
    t = np.linspace(a, b, 2001)
    least = (q0[:, None] + q1[:, None] * t + q2[:, None] * t * t).min(axis=1)
    sharp = sr._quadratic_positive(q0, q1, q2, a, b, 0.0)
    bernstein = sc._quadratic_positive(q0, q1, q2, a, b, 0.0)
    assert not np.any(sharp & (least <= 0))  # never positive where a sample is not
    assert np.all(sharp[bernstein])  # sharper: whatever the Bernstein test passes
    # and it decides the quadratics the Bernstein coefficients cannot (clear of the samples)
    assert np.count_nonzero(sharp & ~bernstein) > 100
    assert np.all(sharp[least > 1e-6])


def test_every_set_surface_certify_certifies_the_sharper_one_certifies_alike():
    nets = np.random.default_rng(5).normal(size=(400, 4, 4, 3))
    d = _direction(lb.load_family("tests/data/families/at_cubic.toml"), 3)
    coeffs = po.energy_coefficients(nets, d, d, "membrane")
    c = [coeffs[(a, b)] for a in range(3) for b in range(3)]
    box = np.array([-1.0, 1.0, -1.0, 1.0])
    x0, y0, _, ok0, edge0 = fixed_cost_minimum(c, box, 1e-12)
    x1, y1, _, ok1, edge1 = sr.recertified_minimum(c, box, 1e-12)
    assert np.all(ok1[ok0]) and np.count_nonzero(ok1 & ~ok0) > 0
    same = ok0 & ~edge0 & ~edge1  # interior both times: the same computation, the same point
    assert np.array_equal(x0[same], x1[same]) and np.array_equal(y0[same], y1[same])
    both = ok0 & ok1  # certified by either test: within 1e-12 of the one minimiser
    assert np.abs(x0[both] - x1[both]).max() <= 2e-12
    assert np.abs(y0[both] - y1[both]).max() <= 2e-12


def test_its_answers_are_the_vectorised_box_certificates():
    """On the at_cubic benchmark nets the compiled stage declines, the sets this pass
    certifies against hazmat.box_batch's certificate of the same nets (from its own float
    search): both within 1e-12 of the minimiser, so within 2e-12 of each other."""
    fam = lb.load_family("tests/data/families/at_cubic.toml")
    d = _direction(fam, 3)
    rng = np.random.default_rng(4)
    nets = rng.normal(size=(600, 4, 4, 3))
    nets[..., 0] += np.arange(4)[:, None]
    nets[..., 1] += np.arange(4)[None, :]
    _, _, _, ok, _ = po.fixed_cost(nets, d, d, "thin_plate")
    declined = np.flatnonzero(~ok)
    coeffs = po.energy_coefficients(nets[declined], d, d, "thin_plate")
    c = [coeffs[(a, b)] for a in range(3) for b in range(3)]
    x, y, energy, rok, on_edge = sr.recertified_minimum(c, np.array([-1.0, 1, -1, 1]), 1e-12)
    assert np.count_nonzero(rok) > declined.size / 2 and np.count_nonzero(rok & on_edge) > 0
    boxed = po._careful_batch(nets[declined], "thin_plate", (fam, fam), d, d)
    assert boxed.fallbacks <= 2
    assert np.abs(boxed.values[rok, 0] - x[rok]).max() <= 2e-12
    assert np.abs(boxed.values[rok, 1] - y[rok]).max() <= 2e-12
    assert np.allclose(boxed.energy[rok], energy[rok], rtol=1e-12, atol=0)
