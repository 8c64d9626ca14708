"""Fifth acceptance pass of issue #31 (surfaces): the defects found, each against a
reference that does not use the code under test.

Found and fixed here:
- `CompositeSurface.report` called a G1 boundary "C0" unless B's cross derivative was a
  constant or linear multiple of A's. G1 (tangent planes that agree along the boundary, B on
  the far side) is B_u = μ A_u + ν A_v with μ(v) > 0 and ν(v) free: the boundary of a patch
  whose cross derivative leans along the boundary (ν ≠ 0) is G1 and was reported "C0";
- `mesh(surf, tolerance)` used 6 to 12 times more triangles than its own tolerance needs: it
  bounded linear interpolation's error on a triangle by (M_uu h_u² + 2 M_uv h_u h_v +
  M_vv h_v²) / 2, four times the sharp / 8, and then gave each term a third of the tolerance.
  The measured deviation (dense sampling) was 12-21 times below the tolerance."""

from __future__ import annotations

import math
from fractions import Fraction as F

import numpy as np
import pytest
from exact_curves import exact_point, hodograph

import lambda_bezier as lb
from lambda_bezier.surface_export import mesh


# -------------------------------------------------------------- G1 with a leaning cross term
def _product(a, b):
    """Bernstein coefficients of the product of two Bernstein polynomials (scalars a, points b)."""
    m, n = len(a) - 1, len(b) - 1
    return [
        tuple(
            sum(
                (
                    F(math.comb(m, i) * math.comb(n, k - i), math.comb(m + n, k))
                    * a[i]
                    * b[k - i][c]
                    for i in range(max(0, k - n), min(m, k) + 1)
                ),
                F(0),
            )
            for c in range(len(b[0]))
        )
        for k in range(m + n + 1)
    ]


def _elevate(points, degree):
    while len(points) - 1 < degree:
        n = len(points) - 1
        points = [
            tuple(
                F(k, n + 1) * (points[k - 1][c] if k else 0)
                + (1 - F(k, n + 1)) * (points[k][c] if k <= n else 0)
                for c in range(len(points[0]))
            )
            for k in range(n + 2)
        ]
    return points


def _add(p, q):
    size = max(len(p), len(q)) - 1
    return [
        tuple(x + y for x, y in zip(a, b, strict=True))
        for a, b in zip(_elevate(p, size), _elevate(q, size), strict=True)
    ]


A_NET = [[(F(i), F(j), F((i * j + i) % 3, 2) + F(i * i, 4)) for j in range(4)] for i in range(4)]


def _next_patch(a_net, mu, nu, lift=None):
    """B of degree 1 across, continuing A (its Bézier net, A's u = 1 side) with cross derivative
    B_u(0, v) = μ(v) A_u(1, v) + ν(v) A_v(1, v) (+ lift, a constant vector): μ, ν Bernstein
    coefficient lists. Built from A's net alone (exact_curves' hodograph)."""
    m = len(a_net) - 1
    last, prev = a_net[m], a_net[m - 1]
    cross = [
        tuple(m * (x - y) for x, y in zip(p, q, strict=True))
        for p, q in zip(last, prev, strict=True)
    ]
    tangent = hodograph(last)
    c = _add(_product(mu, cross), _product(nu, tangent))
    if lift is not None:
        c = [tuple(x + y for x, y in zip(p, lift, strict=True)) for p in c]
    row0 = _elevate(list(last), len(c) - 1)
    row1 = [tuple(x + y for x, y in zip(p, q, strict=True)) for p, q in zip(row0, c, strict=True)]
    return [row0, row1]


def _triple(a_net, b_net, v):
    """det[A_u(1, v), A_v(1, v), B_u(0, v)], exactly (independent evaluation)."""
    m = len(a_net) - 1
    cross = exact_point(
        [
            [m * (x - y) for x, y in zip(p, q, strict=True)]
            for p, q in zip(a_net[m], a_net[m - 1], strict=True)
        ],
        v,
    )
    along = exact_point(hodograph(a_net[m]), v)
    other = exact_point(
        [
            [x - y for x, y in zip(p, q, strict=True)]
            for p, q in zip(b_net[1], b_net[0], strict=True)
        ],
        v,
    )
    rows = [cross, along, other]
    return (
        rows[0][0] * (rows[1][1] * rows[2][2] - rows[1][2] * rows[2][1])
        - rows[0][1] * (rows[1][0] * rows[2][2] - rows[1][2] * rows[2][0])
        + rows[0][2] * (rows[1][0] * rows[2][1] - rows[1][1] * rows[2][0])
    )


def _transpose(net):
    return [list(col) for col in zip(*net, strict=True)]


# μ = 1 + v, ν = v − 1/2 (Bernstein coefficients of degree 1): the cross derivative leans
# along the boundary by a varying amount, so no constant or linear factor relates B_u to A_u
_MU, _NU = [F(1), F(2)], [F(-1, 2), F(1, 2)]


@pytest.mark.parametrize("exact", [True, False])
def test_a_leaning_g1_boundary_is_g1_in_both_directions(exact):
    b_net = _next_patch(A_NET, _MU, _NU)
    for v in (F(0), F(1, 3), F(1)):  # the reference: B_u in the plane of A_u and A_v
        assert _triple(A_NET, b_net, v) == 0
    nets = (A_NET, b_net) if exact else (np.array(A_NET, float), np.array(b_net, float))
    a, b = lb.BezierSurface(nets[0]), lb.BezierSurface(nets[1])
    assert [r.continuity for r in lb.CompositeSurface([[a], [b]]).report()] == ["G1"]  # was C0
    # the same across v = 1
    at, bt = (
        lb.BezierSurface(
            np.swapaxes(np.asarray(n, dtype=object if exact else float), 0, 1).tolist()
        )
        for n in nets
    )
    assert [r.continuity for r in lb.CompositeSurface([[at, bt]]).report()] == ["G1"]
    # and the normals agree along it (the library's normals, a second check)
    vs = np.linspace(0, 1, 7)
    assert np.allclose(a.normal(np.ones(7), vs), b.normal(np.zeros(7), vs), atol=1e-12)


@pytest.mark.parametrize("exact", [True, False])
@pytest.mark.parametrize(
    ("mu", "nu", "lift"),
    [
        ([F(-1), F(-2)], _NU, None),  # μ < 0: B folds back over A
        ([F(-1, 2), F(1, 2)], _NU, None),  # μ changes sign at v = 1/2
        ([F(0), F(0)], _NU, None),  # μ = 0: B_u along the boundary, a degenerate B
        (_MU, _NU, (F(0), F(0), F(1, 1000))),  # out of the tangent plane
    ],
)
def test_a_boundary_that_is_not_g1_stays_c0(exact, mu, nu, lift):
    b_net = _next_patch(A_NET, mu, nu, lift)
    nets = (A_NET, b_net) if exact else (np.array(A_NET, float), np.array(b_net, float))
    a, b = lb.BezierSurface(nets[0]), lb.BezierSurface(nets[1])
    assert [r.continuity for r in lb.CompositeSurface([[a], [b]]).report()] == ["C0"]


def test_a_leaning_g1_boundary_between_two_families():
    """A a same_degree patch (its exact Bézier net the reference's input), B Bézier."""
    a = lb.SameDegreeSurface(A_NET, F(1, 2), F(-1, 3))
    b_net = _next_patch(a.to_bezier().control_net(), _MU, _NU)
    assert _triple(a.to_bezier().control_net(), b_net, F(2, 5)) == 0
    b = lb.BezierSurface(b_net)
    assert [r.continuity for r in lb.CompositeSurface([[a], [b]]).report()] == ["G1"]


# ---------------------------------------------------------------------- mesh triangle count
def _measured_deviation(surf, m, k=10):
    """max over k(k+3)/2 + 1 barycentric points of every triangle of |mesh point − S(u, v)|."""
    w = np.array(
        [(1 - a / k - b / k, a / k, b / k) for a in range(k + 1) for b in range(k + 1 - a)]
    )
    xyz = np.einsum("wk,tkd->twd", w, m.vertices[m.faces])[..., : surf.dimension]
    uv = np.einsum("wk,tkd->twd", w, m.parameters[m.faces])
    s = surf.evaluate(uv[..., 0].ravel(), uv[..., 1].ravel()).reshape(xyz.shape)
    return float(np.linalg.norm(xyz - s, axis=-1).max())


def test_a_twisted_patch_meshes_with_the_fewest_uniform_triangles():
    """S = (2u, 2v, (2u − 1)(2v − 1)): on a right triangle of legs h linear interpolation errs
    by exactly h² at most (4 uv interpolated: h²/4 · 4), so a uniform grid needs 1/n² ≤ tol:
    tol = 0.012 needs n = 10, 200 triangles. Before: 2,048 (n = 32)."""
    s = lb.BezierSurface([[(i, j, (i - 1) * (j - 1)) for j in range(3)] for i in range(3)])
    m = mesh(s, 0.012)
    assert len(m.faces) == 200
    dev = _measured_deviation(s, m)
    assert dev == pytest.approx(0.01, rel=1e-9)  # h = 1/10: h², attained
    # the bound is attained here, so only the rounding of the measurement (1e-16) separates
    # the two; the tolerance is kept with room to spare
    assert dev <= m.deviation_bound * (1 + 1e-12) and m.deviation_bound <= 0.012


@pytest.mark.parametrize("tol", [1e-2, 1e-3])
def test_a_bicubic_mesh_is_not_far_finer_than_its_tolerance(tol):
    """The deviation measured by dense sampling is within the tolerance and no more than 5
    times below it (the triangle count goes as tolerance / deviation at a fixed shape; the
    rest of the gap is the convex hull bound of the second derivatives' nets, about 3 for
    this net). Before: 21 times below, 19,110 triangles at 1e-2 (now 2,720; the coarsest
    uniform grid meeting 1e-2 by dense sampling has 784)."""
    s = lb.SameDegreeSurface(np.random.default_rng(1).normal(size=(4, 4, 3)), 0.5, -0.5)
    m = mesh(s, tol)
    dev = _measured_deviation(s, m, k=6)
    assert dev <= m.deviation_bound <= tol
    assert dev >= tol / 5, (dev, len(m.faces))


# ------------------------------------------------------------------------- an empty batch
@pytest.mark.parametrize("family", ["same_degree", ("bernstein_like", "same_degree")])
def test_an_empty_batch_names_net(family):
    """Before: "a batch of nets must have shape (k, m+1, n+1, d), got (0, 4, 4, 3)", a shape
    of that very form."""
    with pytest.raises(ValueError, match=r"net: an empty batch of nets \(shape \(0, 4, 4, 3\)\)"):
        lb.optimal_parameters(np.zeros((0, 4, 4, 3)), "membrane", family)


def test_an_empty_batch_of_an_own_family_names_net():
    from lambda_bezier import examples

    two = lb.load_family(examples.path("two_shape_cubic.toml"))
    with pytest.raises(ValueError, match="net: an empty batch of nets"):
        lb.optimal_parameters(np.zeros((0, 4, 4, 3)), "membrane", two)


def test_a_leaning_g1_boundary_between_trigonometric_patches():
    """Two han_trig_cubic patches (compared in their own parameters, at sample points): A's
    boundary u = π/2 is its last row, (3, j, 0), on the line x = 3, z = 0, so A_v there is
    along e_y. Moving B's second row by e_y / 2 adds a constant multiple of e_y to B_u (the
    basis sums to one), which stays in A's tangent plane: G1 (before: C0). Moving it in z
    leaves the plane: C0."""
    from lambda_bezier import examples

    trig = lb.load_family(examples.path("han_trig_cubic.toml"))
    net = [[(F(i), F(j), F((i * j) % 3, 2)) for j in range(4)] for i in range(4)]
    assert all(p[0] == 3 and p[2] == 0 for p in net[3])  # the boundary lies on a line along y
    pu, pv = {"lam": F(1, 2), "mu": -1}, {"lam": 0, "mu": F(1, 3)}
    a = trig.surface(net, params_u=pu, params_v=pv)
    rest = [[(6 + k, j, 0) for j in range(4)] for k in range(2)]
    b = lb.join_surface(a, "u", "C1", 3, rest=rest, params=pu)
    rows = [list(r) for r in b.control_net()]
    leaning = [rows[0], [(p[0], p[1] + F(1, 2), p[2]) for p in rows[1]], *rows[2:]]
    lifted = [rows[0], [(p[0], p[1], p[2] + F(1, 100)) for p in rows[1]], *rows[2:]]
    for moved, want in ((leaning, "G1"), (lifted, "C0")):
        other = trig.surface(moved, params_u=pu, params_v=pv)
        assert [r.continuity for r in lb.CompositeSurface([[a], [other]]).report()] == [want]


# ------------------------------------------------------- an empty batch of closest points
def _surfaces_of_every_kind():
    from lambda_bezier import examples

    trig = lb.load_family(examples.path("han_trig_cubic.toml"))
    pu, pv = {"lam": F(1, 2), "mu": -1}, {"lam": 0, "mu": F(1, 3)}
    return [
        lb.SameDegreeSurface(A_NET, F(1, 2), F(-1, 2)),
        lb.BezierSurface(np.zeros((2, 3, 4))),
        trig.surface(A_NET, params_u=pu, params_v=pv),
        trig.surface(A_NET, params_u=pu, lam_v=F(1, 3), family_v="same_degree"),
    ]


@pytest.mark.parametrize("index", range(4))
def test_an_empty_batch_of_queries_gives_points_of_shape_0_d(index):
    """A batch of k queries gives points (k, d); k = 0 gave (0,), and a (0, 2) batch for a
    3-D surface was taken (the curves give (0, d) and name the width)."""
    surf = _surfaces_of_every_kind()[index]
    d = surf.dimension
    r = surf.closest_point(np.zeros((0, d)))
    assert r.point.shape == (0, d)
    assert r.u.shape == r.v.shape == r.distance.shape == r.lower_bound.shape == (0,)
    with pytest.raises(ValueError, match=rf"q: a batch of queries must have shape \(k, {d}\)"):
        surf.closest_point(np.zeros((0, d - 1)))
