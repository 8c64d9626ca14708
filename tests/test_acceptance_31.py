"""Acceptance of issue #31 (surfaces) as a new user meets it: the failures found, each against
a reference that does not use the code under test (exact Fractions, cross products of the
exact Bézier form's derivatives, the energy interpolated from exact values)."""

from __future__ import annotations

from fractions import Fraction as F

import numpy as np
import pytest

import lambda_bezier as lb
from lambda_bezier import examples
from lambda_bezier.surface_export import surface_from_json, surface_to_json

# row 0 of the net is one point: the edge u = 0 collapses, S_v(0, v) = 0 and the normal is
# undefined there, although float evaluation gives S_v about 1e-16 instead of 0
COLLAPSED = [[(0, 0, 0)] * 4] + [[(i, j, (i * j) % 3) for j in range(4)] for i in range(1, 4)]


def _collapsed_surfaces() -> list[lb.Surface]:
    trig = lb.load_family(examples.path("han_trig_cubic.toml"))
    return [
        lb.SameDegreeSurface(COLLAPSED, 0, 0),
        lb.SameDegreeSurface(COLLAPSED, F(1, 2), F(-1, 3)),
        lb.BernsteinLikeSurface(COLLAPSED, F(1, 3), F(1, 5)),
        lb.BezierSurface(COLLAPSED),
        trig.surface(COLLAPSED, params_u={"lam": F(1, 2), "mu": -1}, params_v={"lam": 0, "mu": 0}),
    ]


@pytest.mark.parametrize("k", range(5))
def test_a_collapsed_edge_has_no_normal(k):
    """Before: SameDegreeSurface(COLLAPSED, 0, 0).normal(0, 0.5) returned [0.6, 0, -0.8],
    the direction of S_u x (rounding noise)."""
    s = _collapsed_surfaces()[k]
    for v in (0.1, 0.5, 0.9):
        with pytest.raises(ValueError, match="normal is undefined"):
            s.normal(0, v)
        with pytest.raises(ValueError, match="normal is undefined"):
            s.curvatures(0, v)
    with pytest.raises(ValueError, match="normal is undefined"):
        s.normal(np.array([0.4, 0.0]), np.array([0.5, 0.5]))


@pytest.mark.parametrize("k", range(4))
def test_normals_away_from_the_collapsed_edge_are_the_exact_ones(k):
    """The guard refuses only the degenerate points: elsewhere the normal is the cross product
    of the exact Bézier form's partial derivatives (Fractions, by forward differences)."""
    s = _collapsed_surfaces()[k]
    net = s.to_bezier().control_net()
    m, n = len(net) - 1, len(net[0]) - 1

    def partial(u: F, v: F, axis: int) -> np.ndarray:
        from math import comb

        total = [F(0)] * 3
        du, dv = (1, 0) if axis == 0 else (0, 1)
        for i in range(m + 1 - du):
            for j in range(n + 1 - dv):
                a, b = net[i + du][j + dv], net[i][j]
                deg_u, deg_v = m - du, n - dv
                w = (
                    comb(deg_u, i) * u**i * (1 - u) ** (deg_u - i)
                    * comb(deg_v, j) * v**j * (1 - v) ** (deg_v - j)
                    * (m if axis == 0 else n)
                )  # fmt: skip
                total = [t + w * (x - y) for t, x, y in zip(total, a, b, strict=True)]
        return np.array([float(t) for t in total])

    for u, v in ((F(1, 10**6), F(1, 2)), (F(1, 100), F(1, 3)), (F(1, 2), F(1, 2)), (F(1), F(1, 4))):
        c = np.cross(partial(u, v, 0), partial(u, v, 1))
        np.testing.assert_allclose(s.normal(float(u), float(v)), c / np.linalg.norm(c), atol=1e-9)


def _energy_polynomial(cls, net, kind):
    """E(x, y) = Σ e_ab x^a y^b (a, b <= 2), interpolated exactly from nine exact energies."""
    nodes = (F(-1), F(0), F(1))
    values = {
        (x, y): lb.surface_energy(cls(net, x, y, check_range=False), kind)
        for x in nodes
        for y in nodes
    }

    def lagrange(t: F, k: int) -> list[F]:  # coefficients of the k-th Lagrange basis polynomial
        others = [nodes[i] for i in range(3) if i != k]
        den = (nodes[k] - others[0]) * (nodes[k] - others[1])
        return [others[0] * others[1] / den, -(others[0] + others[1]) / den, F(1) / den]

    e = {(a, b): F(0) for a in range(3) for b in range(3)}
    for i, x in enumerate(nodes):
        for j, y in enumerate(nodes):
            lx, ly = lagrange(x, i), lagrange(y, j)
            for a in range(3):
                for b in range(3):
                    e[a, b] += values[x, y] * lx[a] * ly[b]
    return e


def _edge_cases():
    rng = np.random.default_rng(7)
    found = []
    for _ in range(40):
        cls, fam = (lb.BernsteinLikeSurface, "bernstein_like")
        net = [
            [
                tuple(F(int(rng.integers(-9, 10)), int(rng.integers(1, 5))) for _ in range(3))
                for _ in range(4)
            ]
            for _ in range(4)
        ]
        for kind in ("membrane", "thin_plate"):
            r = lb.optimal_parameters(net, energy=kind, family=fam)
            if r["where"] == "edge":
                found.append((cls, net, kind, r))
        if len(found) >= 3:
            break
    return found


def test_an_edge_optimum_is_an_exact_fraction():
    """Before: the vertex of an edge's quadratic (rational) came back as an IsolatedRoot of a
    linear polynomial, which promises an irrational number."""
    cases = _edge_cases()
    assert len(cases) >= 3
    for cls, net, kind, r in cases:
        e = _energy_polynomial(cls, net, kind)
        lu, lv = r["lam_u"], r["lam_v"]
        assert isinstance(lu, F) and isinstance(lv, F), (lu, lv)
        assert (float(lu), float(lv)) == (r["lam_u_float"], r["lam_v_float"])
        # on the edge held fixed, the free parameter is the vertex of an exact quadratic
        if lu in (-1, 1):
            a = sum(e[i, 2] * lu**i for i in range(3))
            b = sum(e[i, 1] * lu**i for i in range(3))
            assert lv == -b / (2 * a)
        else:
            assert lv in (-1, 1)
            a = sum(e[2, j] * lv**j for j in range(3))
            b = sum(e[1, j] * lv**j for j in range(3))
            assert lu == -b / (2 * a)
        assert r["energy"] == sum(c * lu**a * lv**b for (a, b), c in e.items())


def test_an_interior_optimum_is_irrational_or_a_fraction():
    net = [[(i, j, (i * j) % 2) for j in range(4)] for i in range(4)]
    r = lb.optimal_parameters(net, "thin_plate")
    for x in (r["lam_u"], r["lam_v"]):
        if not isinstance(x, F):
            assert len(x.coefficients) > 2  # not a rational root in disguise
            assert x.polynomial(x.lo) * x.polynomial(x.hi) < 0


@pytest.mark.parametrize(
    "surf",
    [
        lb.SameDegreeSurface([[(i, j, i * j) for j in range(4)] for i in range(4)], F(1, 2), 0),
        lb.BernsteinLikeSurface([[(i, j) for j in range(3)] for i in range(4)], F(1, 3), -1),
        lb.BezierSurface([[(i, j, F(i, 3)) for j in range(3)] for i in range(3)]),
        lb.SameDegreeSurface(np.arange(48.0).reshape(4, 4, 3), 0.25, -0.5),
    ],
    ids=["same_degree", "bernstein_like", "bezier", "float"],
)
def test_json_round_trip_keeps_the_class(surf):
    """Before: every surface read back as the generic Surface."""
    back = surface_from_json(surface_to_json(surf))
    assert type(back) is type(surf)
    assert repr(back) == repr(surf)
    assert back.control_net() == surf.control_net()
    assert (back.lam_u, back.lam_v) == (surf.lam_u, surf.lam_v)


def test_a_mixed_pair_reads_back_as_the_generic_surface():
    surf = lb.Surface(
        [[(i, j) for j in range(4)] for i in range(4)],
        None,
        F(1, 4),
        family=("bezier", "same_degree"),
    )
    back = surface_from_json(surface_to_json(surf))
    assert type(back) is lb.Surface and back.family == ("bezier", "same_degree")


def test_bad_input_names_the_argument():
    s = lb.SameDegreeSurface([[(i, j, 0) for j in range(4)] for i in range(4)], 0, 0)
    with pytest.raises(ValueError, match="order du must"):
        s.derivative(0.5, 0.5, -1, 0)
    with pytest.raises(ValueError, match="order dv must"):
        s.derivative(0.5, 0.5, 0, 1.5)
    with pytest.raises(ValueError, match="order dv must"):
        s.evaluate_grid([0.5], [0.5], 0, True)
    with pytest.raises(TypeError, match="surf must be a lambda_bezier surface, got list"):
        lb.surface_energy([[(0, 0)]], "membrane")
    with pytest.raises(ValueError, match=r"degrees = \(-1, 3\)"):
        lb.surface_energy_matrices((-1, 3), "membrane")


@pytest.mark.parametrize(
    "net",
    [
        [[i * j - 2 * i for j in range(4)] for i in range(4)],  # a scalar field as a 2-D grid
        np.arange(16).reshape(4, 4),
        np.arange(48).reshape(4, 4, 3),  # integers in numpy are exact, as for curves
    ],
    ids=["grid-of-ints", "int-array-2d", "int-array-3d"],
)
def test_integer_nets_give_exact_surfaces(net):
    """Before: a 2-D grid of ints or an integer array gave a float surface (exact in, float out)."""
    s = lb.SameDegreeSurface(net, F(1, 2), F(-1, 3))
    assert s.is_exact
    rows = np.asarray(net).reshape(4, 4, -1)
    assert s.control_net() == tuple(tuple(tuple(F(int(c)) for c in p) for p in r) for r in rows)
    # the corner interpolates, the iso-curve and the Bézier form are Fractions, the energy too
    assert s.to_bezier().control_net()[3][3] == tuple(F(int(c)) for c in rows[3][3])
    assert all(isinstance(c, F) for p in s.curve_at_u(F(1, 3)).control_points() for c in p)
    assert isinstance(lb.surface_energy(s, "membrane"), F)


@pytest.mark.parametrize("seed", range(12))
def test_closest_point_lower_bound_never_exceeds_the_distance(seed):
    """Before: where the nearest point is a corner, lower_bound came out an ulp above the
    distance (4.4e-16), a "certified lower bound" above the attained value. The reference is
    dense sampling of the surface."""
    rng = np.random.default_rng(seed)
    cls = (lb.SameDegreeSurface, lb.BernsteinLikeSurface)[seed % 2]
    s = cls(
        rng.normal(size=(4, 5, 3)), float(rng.uniform(-0.9, 0.9)), float(rng.uniform(-0.9, 0.9))
    )
    grid = np.linspace(0, 1, 301)
    points = s.evaluate_grid(grid, grid).reshape(-1, 3)
    for q in rng.normal(size=(6, 3)) * 2:
        cp = s.closest_point(q)
        assert cp.lower_bound <= cp.distance
        assert cp.distance <= np.linalg.norm(points - q, axis=1).min() + 1e-12
        assert cp.distance - cp.lower_bound <= 1e-11


def test_atom_closest_point_lower_bound_never_exceeds_the_distance():
    """The same through the rational form (han_trig_cubic): before, 3.6e-15 above at (0, 0)."""
    trig = lb.load_family(examples.path("han_trig_cubic.toml"))
    rng = np.random.default_rng(1)
    for _ in range(6):
        t = trig.surface(
            rng.normal(size=(4, 4, 3)),
            params_u={"lam": 0.5, "mu": -1},
            params_v={"lam": 0, "mu": 0.3},
        )
        for q in rng.normal(size=(5, 3)) * 2:
            cp = t.closest_point(q)
            assert cp.lower_bound <= cp.distance
            assert abs(np.linalg.norm(t.evaluate(cp.u, cp.v) - q) - cp.distance) < 1e-12
