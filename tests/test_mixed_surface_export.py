"""Export and split of surfaces of mixed algebraic-trigonometric families, which have no
rational form: STEP as a bicubic B-spline within a stated tolerance (surface_approx), read
back by OCCT and compared with the surface at points the construction never looked at; a
triangle mesh within its tolerance; split refused by name. The exact forms (trigonometric,
polynomial) keep their exact STEP paths."""

from __future__ import annotations

from fractions import Fraction as F

import numpy as np
import pytest
from conftest import ROOT, occt_surface

import lambda_bezier as lb
from lambda_bezier import surface_approx as sa
from lambda_bezier import surface_export as se

DATA = ROOT / "tests" / "data" / "families"
AT = lb.load_family(DATA / "at_cubic.toml")
AT_PI = lb.load_family(DATA / "at_pi_cubic.toml")
NET = [[(i, j, F((i * j) % 3, 2) - F(i, 4)) for j in range(4)] for i in range(4)]


def surfaces():
    yield AT.surface(NET, params_u={"lam": F(1, 2)}, lam_v=F(1, 3), family_v="same_degree")
    yield AT_PI.surface(NET, params_u={"lam": F(1, 4)}, params_v={"lam": F(1, 2)})
    yield lb.param_surfaces.family_surface(
        NET, ("bernstein_like", AT), lam_u=F(-1, 2), params_v={"lam": 0}
    )


SURFACES = list(surfaces())
IDS = ["at x same_degree", "at_pi x at_pi", "bernstein_like x at"]


def random_points(s: lb.Surface, k: int, seed: int) -> list[tuple[float, float]]:
    (a, b), (c, d) = s.domain_u, s.domain_v
    rng = np.random.default_rng(seed)
    return [(a + (b - a) * x, c + (d - c) * y) for x, y in rng.random((k, 2))]


@pytest.mark.parametrize("s", SURFACES, ids=IDS)
@pytest.mark.parametrize("tol", [1e-4, 1e-8])
def test_the_spline_is_within_the_tolerance_at_points_it_never_saw(s, tol):
    sp = sa.hermite_bspline(s, tol)
    assert sp.deviation <= tol
    worst = max(
        np.linalg.norm(sp.evaluate(u, v) - s.evaluate(u, v)) for u, v in random_points(s, 400, 3)
    )
    assert worst <= tol
    # the grid is no finer than it needs: the coarser grid (half the cells) misses tol
    if sp.cells[0] > 4:
        half = sa._poles(
            s, *(np.linspace(*dom, sp.cells[0] // 2 + 1) for dom in (s.domain_u, s.domain_v))
        )
        coarse = sa.HermiteSpline(
            half,
            np.linspace(*s.domain_u, sp.cells[0] // 2 + 1),
            np.linspace(*s.domain_v, sp.cells[0] // 2 + 1),
            0.0,
            0,
        )
        worst_coarse = max(
            np.linalg.norm(coarse.evaluate(u, v) - s.evaluate(u, v))
            for u, v in random_points(s, 400, 4)
        )
        assert worst_coarse > worst


@pytest.mark.parametrize("s", SURFACES, ids=IDS)
def test_step_of_a_mixed_surface_read_back_by_occt(s, tmp_path):
    tol = 1e-7
    path = se.to_step_surface(s, tmp_path / "mixed.step", tolerance=tol)
    back = occt_surface(path)
    u1, u2, v1, v2 = back.Bounds()
    assert np.allclose([u1, u2, v1, v2], [*s.domain_u, *s.domain_v], atol=1e-15)
    for u, v in [*random_points(s, 200, 5), (s.domain_u[1], s.domain_v[0])]:
        p = back.Value(u, v)  # the families' own (u, v): the knots are their t
        assert np.linalg.norm([p.X(), p.Y(), p.Z()] - s.evaluate(u, v)) <= tol
    # a coarser tolerance is honoured as coarser: its spline deviates more than tol
    coarse = occt_surface(se.to_step_surface(s, tmp_path / "coarse.step", tolerance=1e-3))
    worst = max(
        np.linalg.norm(
            np.array([coarse.Value(u, v).X(), coarse.Value(u, v).Y(), coarse.Value(u, v).Z()])
            - s.evaluate(u, v)
        )
        for u, v in random_points(s, 200, 6)
    )
    assert tol < worst <= 1e-3


@pytest.mark.parametrize("s", SURFACES[:2], ids=IDS[:2])
def test_mesh_of_a_mixed_surface_is_within_its_tolerance(s):
    tol = 1e-3
    m = se.mesh(s, tol)
    assert m.deviation_bound <= tol
    rng = np.random.default_rng(8)
    picks = rng.choice(len(m.faces), size=300, replace=False)
    for f in picks:
        w = rng.dirichlet([1, 1, 1])
        tri = m.faces[f]
        point = w @ m.vertices[tri]
        u, v = w @ m.parameters[tri]
        assert np.linalg.norm(point - s.evaluate(u, v)) <= m.deviation_bound


@pytest.mark.parametrize("s", SURFACES, ids=IDS)
def test_split_of_a_mixed_surface_is_refused_by_name(s):
    for name, call in (("split_u", s.split_u), ("split_v", s.split_v)):
        with pytest.raises(ValueError, match=f"{name}: a surface of .* has no rational form"):
            call(0.5)


def test_bad_tolerances_are_named():
    s = SURFACES[0]
    for bad in (0, -1, float("nan"), "x"):
        with pytest.raises((ValueError, TypeError), match="tolerance"):
            sa.hermite_bspline(s, bad)
    with pytest.raises(ValueError, match="tolerance 1e-14: .* choose a larger tolerance"):
        sa.hermite_bspline(s, 1e-14)
    with pytest.raises(TypeError, match="surf must be"):
        sa.hermite_bspline("surface", 1e-3)


def test_trigonometric_and_polynomial_surfaces_keep_their_exact_step(tmp_path):
    poly = lb.SameDegreeSurface(NET, F(1, 2), 0)
    back = occt_surface(se.to_step_surface(poly, tmp_path / "p.step", tolerance=1e-1))
    p = back.Value(0.3, 0.6)  # exact form: the tolerance is not used
    assert np.allclose([p.X(), p.Y(), p.Z()], poly.evaluate(0.3, 0.6), atol=1e-13)
