"""optimal_parameters for a trigonometric family not affine in its parameter (issue #30):
E_k has entries in ℚ[π] and is a quartic in lam; the answer is the certified minimum over the
range (π bounded by a rational interval). Checked against an independent grid search of
E_k by Gauss-Legendre quadrature of the typed-in definition."""

from __future__ import annotations

from fractions import Fraction as F
from pathlib import Path

import numpy as np
import pytest

import lambda_bezier as lb
from lambda_bezier.hazmat.constants import ConstantFraction

FAMILY = Path(__file__).parent / "data" / "families" / "trig_square_quadratic.toml"


NODES, WEIGHTS = np.polynomial.legendre.leggauss(40)


def second_derivative_energy(points, lam):
    """E_2 = ∫_0^(π/2) |C''(t)|² dt of the definition typed in (numpy, Gauss-Legendre)."""
    w = WEIGHTS
    t = (NODES + 1) * np.pi / 4
    s, c = np.sin(t), np.cos(t)
    # second derivatives of the three functions (sin'' = -sin, cos'' = -cos, (sc)'' = -4sc)
    sc2 = -4 * s * c
    b = np.array([s - lam**2 * sc2, -s - c + (lam**2 + lam) * sc2, c - lam * sc2])
    d2 = b.T @ np.asarray(points, float)
    return float((w * (d2**2).sum(axis=1)).sum() * np.pi / 4)


@pytest.mark.parametrize(
    "points", [[(0, 0), (1, 3), (4, 0)], [(0, 0), (2, -1), (3, 5)], [(1, 1), (0, 4), (-3, 2)]]
)
def test_certified_minimum_against_a_grid(points):
    fam = lb.load_family(FAMILY)
    res = lb.optimal_parameters(points, 2, family=fam)
    lam = res["lam"]
    assert isinstance(lam, F) and -1 <= lam <= 1
    assert isinstance(res.energy, ConstantFraction | F)
    grid = np.linspace(-1, 1, 20001)
    values = np.array([second_derivative_energy(points, g) for g in grid])
    assert float(res.energy) == pytest.approx(
        second_derivative_energy(points, float(lam)), rel=1e-12
    )
    assert float(res.energy) <= values.min() * (1 + 1e-12)
    assert abs(float(lam) - grid[values.argmin()]) < 2e-3 or float(res.energy) == pytest.approx(
        values.min(), rel=1e-9
    )
    # the proven lower bound is within 1e-12 of the exact energy at the point
    assert res.lower_bound <= res.energy
    assert float(res.energy) - float(res.lower_bound) <= 1e-12 * max(1.0, float(res.energy))
    # the exact energy is the curve's own E_2 at that parameter
    assert res.energy == fam.curve(points, lam=lam).energy(2)


def test_float_points_give_floats():
    fam = lb.load_family(FAMILY)
    res = lb.optimal_parameters([(0.0, 0.0), (1.0, 3.0), (4.0, 0.0)], 2, family=fam)
    assert isinstance(res["lam"], float) and isinstance(res.energy, float)
    exact = lb.optimal_parameters([(0, 0), (1, 3), (4, 0)], 2, family=fam)
    assert res["lam"] == pytest.approx(float(exact["lam"]), abs=1e-9)


def test_hyperbolic_not_affine_against_a_grid():
    """Energies Laurent in e: e and 1/e are two more variables of the box."""
    fam = lb.load_family(FAMILY.parent / "hyp_square_quadratic.toml")
    points = [(0, 0), (1, 3), (4, 0)]
    res = lb.optimal_parameters(points, 2, family=fam)
    assert res.lower_bound <= res.energy
    assert float(res.energy) - float(res.lower_bound) <= 1e-12 * max(1.0, float(res.energy))
    # The grid of the curve's own E_2 at 2001 parameters. Each exact E_2 in ℚ(e) costs about
    # 15 ms, so the grid is read off E_2's polynomial in lam instead (degree <= 4: each basis
    # function is quadratic in lam), interpolated exactly through the curve's own energies at
    # five parameters, confirmed exactly at two more, and at eleven grid points against the
    # float-points energy the grid used to call (2001 such calls took 30 s, quiet)
    nodes = [F(k, 2) for k in range(-2, 3)]
    newton = [fam.curve(points, lam=x).energy(2) for x in nodes]
    for j in range(1, len(nodes)):  # divided differences, exact in ℚ(e)
        for i in range(len(nodes) - 1, j - 1, -1):
            newton[i] = (newton[i] - newton[i - 1]) / (nodes[i] - nodes[i - j])

    def quartic(x):
        value = newton[-1]
        for c, node in zip(newton[-2::-1], nodes[-2::-1], strict=True):
            value = value * (x - node) + c
        return value

    for x in (F(1, 3), F(-7, 9)):
        assert quartic(x) == fam.curve(points, lam=x).energy(2)
    grid = np.linspace(-1, 1, 2001)
    coef = [float(c) for c in newton]
    values = np.full_like(grid, coef[-1])
    for c, node in zip(coef[-2::-1], nodes[-2::-1], strict=True):
        values = values * (grid - float(node)) + c
    floats = [(0.0, 0.0), (1.0, 3.0), (4.0, 0.0)]
    for i in sorted({*range(0, 2001, 200), int(values.argmin())}):
        runtime = float(fam.curve(floats, lam=grid[i]).energy(2))
        assert values[i] == pytest.approx(runtime, rel=1e-13)
    assert float(res.energy) <= values.min() * (1 + 1e-12)
