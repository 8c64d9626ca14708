"""Tensor-product surfaces against independent computations: the papers' basis definitions
(tests/reference.py), OCCT's Geom_BezierSurface, finite differences, exact Bernstein sums,
dense sampling."""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest
from conftest import FAMILIES as REF
from hypothesis import given
from hypothesis import strategies as st

import lambda_bezier as lb
from lambda_bezier.surfaces import Surface

F = Fraction


def random_net(rng, m, n, d=3):
    net = rng.normal(size=(m + 1, n + 1, d))
    net[:, :, 0] += np.arange(m + 1)[:, None]
    net[:, :, 1] += np.arange(n + 1)[None, :]
    return net


def make(fam, net, lu, lv):
    if fam == "bezier":
        return lb.BezierSurface(net)
    return Surface(net, lu, lv, family=fam)


def lams(fam):
    return {"bezier": (None, None), "same_degree": (0.5, -1.25), "bernstein_like": (-0.5, 0.75)}[
        fam
    ]


def reference_value(fam, net, lu, lv, u, v):
    """Σ P_ij b_i(u) b_j(v) with the papers' definitions of the bases."""
    ref = REF[fam]
    bu = ref.basis(net.shape[0] - 1, np.array([u]), lu)[0]
    bv = ref.basis(net.shape[1] - 1, np.array([v]), lv)[0]
    return np.einsum("i,ijd,j->d", bu, net, bv)


def exact_bernstein(net, u, v):
    m, n = len(net) - 1, len(net[0]) - 1
    return tuple(
        sum(
            math.comb(m, i)
            * u**i
            * (1 - u) ** (m - i)
            * math.comb(n, j)
            * v**j
            * (1 - v) ** (n - j)
            * net[i][j][c]
            for i in range(m + 1)
            for j in range(n + 1)
        )
        for c in range(len(net[0][0]))
    )


# ---------------------------------------------------------------------- construction, evaluation
@pytest.mark.parametrize("fam", ["bezier", "same_degree", "bernstein_like"])
def test_evaluate_matches_the_papers_basis_definitions(fam):
    rng = np.random.default_rng(3)
    m, n = 3, 4
    net = random_net(rng, m, n)
    lu, lv = lams(fam)
    s = make(fam, net, lu, lv)
    u, v = rng.random(20), rng.random(20)
    got = s.evaluate(u, v)
    want = np.array([reference_value(fam, net, lu, lv, a, b) for a, b in zip(u, v, strict=True)])
    np.testing.assert_allclose(got, want, rtol=1e-12, atol=1e-12)
    grid = s.evaluate_grid(u[:5], v[:7])
    pts = s.evaluate(np.repeat(u[:5], 7), np.tile(v[:7], 5)).reshape(5, 7, 3)
    np.testing.assert_allclose(grid, pts, rtol=1e-13, atol=1e-13)


@pytest.mark.parametrize("fam", ["same_degree", "bernstein_like"])
def test_to_bezier_is_exact(fam):
    net = [[(i, j, (i * j) % 3 - 1) for j in range(4)] for i in range(5)]
    s = Surface(net, F(1, 3), F(-1, 2), family=fam)
    bez = s.to_bezier()
    exact = bez.control_net()
    assert all(isinstance(c, Fraction) for row in exact for p in row for c in p)
    for u, v in ((F(1, 3), F(2, 7)), (F(0), F(1)), (F(5, 9), F(1, 2))):
        want = reference_value(fam, np.array(net, float), 1 / 3, -1 / 2, float(u), float(v))
        got = exact_bernstein(exact, u, v)
        np.testing.assert_allclose([float(c) for c in got], want, rtol=1e-13)


@pytest.mark.parametrize("fam", ["bezier", "same_degree", "bernstein_like"])
def test_evaluation_and_derivatives_match_occt(fam):
    from OCP.gp import gp_Pnt, gp_Vec

    from lambda_bezier.surface_export import occt_bezier_surface

    rng = np.random.default_rng(5)
    s = make(fam, random_net(rng, 3, 4), *lams(fam))
    occ = occt_bezier_surface(s)
    scale = np.abs(s.to_bezier().net).max()
    for u, v in rng.random((6, 2)):
        p, du, dv, duu, dvv, duv = gp_Pnt(), *(gp_Vec() for _ in range(5))
        occ.D2(u, v, p, du, dv, duu, dvv, duv)
        for (a, b), vec in zip(
            ((1, 0), (0, 1), (2, 0), (0, 2), (1, 1)), (du, dv, duu, dvv, duv), strict=True
        ):
            got = s.derivative(u, v, a, b)
            np.testing.assert_allclose(got, [vec.X(), vec.Y(), vec.Z()], atol=1e-11 * scale * 50)
        np.testing.assert_allclose(s.evaluate(u, v), [p.X(), p.Y(), p.Z()], atol=1e-12 * scale)
        third = occ.DN(u, v, 2, 1)
        np.testing.assert_allclose(
            s.derivative(u, v, 2, 1), [third.X(), third.Y(), third.Z()], atol=1e-10 * scale * 100
        )


def test_derivatives_match_finite_differences():
    rng = np.random.default_rng(7)
    s = lb.BernsteinLikeSurface(random_net(rng, 3, 3), 0.3, -0.6)
    h = 1e-6
    u, v = 0.37, 0.61
    fd_u = (s.evaluate(u + h, v) - s.evaluate(u - h, v)) / (2 * h)
    fd_v = (s.evaluate(u, v + h) - s.evaluate(u, v - h)) / (2 * h)
    fd_uv = (s.derivative(u, v + h, 1, 0) - s.derivative(u, v - h, 1, 0)) / (2 * h)
    np.testing.assert_allclose(s.derivative(u, v, 1, 0), fd_u, rtol=1e-7, atol=1e-7)
    np.testing.assert_allclose(s.derivative(u, v, 0, 1), fd_v, rtol=1e-7, atol=1e-7)
    np.testing.assert_allclose(s.derivative(u, v, 1, 1), fd_uv, rtol=1e-6, atol=1e-6)
    # past the degrees (5 = 3 + 2 in each direction) every derivative is zero
    assert not s.derivative(u, v, 6, 0).any()


def test_curvatures_of_a_sphere_like_patch_and_a_saddle():
    # z = x y on the unit square (bilinear net): K = -1/(1 + x² + y²)², H from the formula
    net = [[(x, y, x * y) for y in (0, 1)] for x in (0, 1)]
    s = lb.BezierSurface(net)
    u, v = np.array([0.2, 0.7]), np.array([0.9, 0.4])
    gauss, mean = s.curvatures(u, v)
    w = 1 + u**2 + v**2
    np.testing.assert_allclose(gauss, -1 / w**2, rtol=1e-13)
    np.testing.assert_allclose(mean, -u * v / w**1.5, rtol=1e-13)
    n = s.normal(0.2, 0.9)
    np.testing.assert_allclose(n, np.array([-0.9, -0.2, 1]) / math.sqrt(w[0]), rtol=1e-13)


def test_degenerate_normal_is_an_error_not_nan():
    # a net whose first row collapses to one point: S_v = 0 along u = 0
    net = [[(0, 0, 0)] * 3, [(1, j, 0) for j in range(3)], [(2, j, 1) for j in range(3)]]
    s = lb.BezierSurface(net)
    with pytest.raises(ValueError, match="normal is undefined"):
        s.normal(0.0, 0.5)
    with pytest.raises(ValueError, match="normal is undefined"):
        s.curvatures([0.5, 0.0], [0.5, 0.5])
    with pytest.raises(ValueError, match="dimension 2"):
        lb.BezierSurface([[(0, 0), (1, 0)], [(0, 1), (1, 1)]]).normal(0.5, 0.5)


@pytest.mark.parametrize("fam", ["same_degree", "bernstein_like"])
def test_isoparametric_curves_are_exact_curves_of_the_family(fam):
    net = [[(i, j, (i + 2 * j) % 3) for j in range(4)] for i in range(4)]
    s = Surface(net, F(1, 2), F(-1, 3), family=fam)
    cu = s.curve_at_u(F(1, 3))
    assert isinstance(cu, lb.FAMILIES[fam]) and cu.lam == F(-1, 3) and cu.is_exact
    cv = s.curve_at_v(F(2, 5))
    assert cv.lam == F(1, 2) and cv.is_exact
    bez = s.to_bezier().control_net()
    for t in (F(0), F(1, 4), F(3, 4)):
        on_curve = exact_bernstein([[p] for p in cu.to_bezier().control_points()], t, F(0))
        assert on_curve == exact_bernstein(bez, F(1, 3), t)
        on_curve = exact_bernstein([[p] for p in cv.to_bezier().control_points()], t, F(0))
        assert on_curve == exact_bernstein(bez, t, F(2, 5))


def test_split_and_elevation_keep_the_surface_exactly():
    net = [[(i, j, (i * j) % 2) for j in range(4)] for i in range(4)]
    s = lb.SameDegreeSurface(net, F(1, 2), F(-1, 2))
    bez = s.to_bezier().control_net()
    left, right = s.split_u(F(1, 3))
    low, high = s.split_v(F(3, 4))
    for a, b in ((F(1, 2), F(1, 5)), (F(0), F(1))):
        assert exact_bernstein(left.control_net(), a, b) == exact_bernstein(bez, a / 3, b)
        assert exact_bernstein(right.control_net(), a, b) == exact_bernstein(
            bez, F(1, 3) + a * F(2, 3), b
        )
        assert exact_bernstein(low.control_net(), a, b) == exact_bernstein(bez, a, b * F(3, 4))
        assert exact_bernstein(high.control_net(), a, b) == exact_bernstein(bez, a, F(3, 4) + b / 4)
    up = s.elevate_u().elevate_v()
    assert up.degrees == (4, 4)
    for a, b in ((F(1, 7), F(5, 6)),):
        assert exact_bernstein(up.control_net(), a, b) == exact_bernstein(bez, a, b)


def test_bounding_box_against_dense_sampling():
    rng = np.random.default_rng(11)
    s = lb.BernsteinLikeSurface(random_net(rng, 3, 3), 0.5, -0.5)
    lo, hi = s.bounding_box()
    t = np.linspace(0, 1, 401)
    pts = s.evaluate_grid(t, t).reshape(-1, 3)
    assert (pts >= lo - 1e-12).all() and (pts <= hi + 1e-12).all()
    # tight: the dense samples come within the grid's resolution of every face of the box
    slack = 1e-4 * np.abs(s.to_bezier().net).max()
    assert (pts.min(0) - lo <= slack).all() and (hi - pts.max(0) <= slack).all()


def test_closest_point_against_dense_sampling():
    rng = np.random.default_rng(13)
    s = lb.SameDegreeSurface(random_net(rng, 3, 3), 0.25, 0.75)
    t = np.linspace(0, 1, 601)
    pts = s.evaluate_grid(t, t).reshape(-1, 3)
    for q in rng.normal(size=(4, 3)) * 3 + 1.5:
        res = s.closest_point(q)
        dense = np.linalg.norm(pts - q, axis=1).min()
        assert res.lower_bound <= res.distance <= dense + 1e-12
        assert res.distance - res.lower_bound <= 1e-11 * (np.abs(s.to_bezier().net).max() + 3)
        np.testing.assert_allclose(np.linalg.norm(res.point - q), res.distance, rtol=1e-12)
        assert dense - res.distance < 1e-2  # the grid's spacing
    queries = rng.normal(size=(3, 3))
    batch = s.closest_point(queries)
    assert batch.u.shape == (3,) and batch.point.shape == (3, 3)
    for k, q in enumerate(queries):
        assert batch.distance[k] == s.closest_point(q).distance


# ---------------------------------------------------------------------- energies
@pytest.mark.parametrize("fam", ["same_degree", "bernstein_like"])
@pytest.mark.parametrize("kind", ["membrane", "thin_plate"])
def test_energy_against_mpmath_quadrature(fam, kind):
    import mpmath

    net = [[(i, j, ((i + 1) * (j + 2)) % 3) for j in range(4)] for i in range(4)]
    s = Surface(net, F(1, 2), F(-1, 4), family=fam)
    exact = lb.surface_energy(s, kind)
    assert isinstance(exact, Fraction)
    terms = {"membrane": ((1, 0, 1), (0, 1, 1)), "thin_plate": ((2, 0, 1), (1, 1, 2), (0, 2, 1))}

    def integrand(u, v):
        total = 0.0
        for a, b, w in terms[kind]:
            d = s.derivative(float(u), float(v), a, b)
            total += w * float(d @ d)
        return total

    # the integrand is a polynomial of degree <= 2M = 10 in each variable: Gauss-Legendre with
    # 12 nodes (mpmath's degree 3) is exact for it
    quad = mpmath.quad(integrand, [0, 1], [0, 1], method="gauss-legendre", maxdegree=3)
    assert abs(float(quad) - float(exact)) <= 1e-11 * float(exact)


@pytest.mark.parametrize("fam", ["same_degree", "bernstein_like"])
def test_energy_matrices_equal_the_direct_bezier_gram_form(fam):
    """The Kronecker-product matrices against the energy of the Bézier form computed with the
    Bernstein Gram matrices directly (no λ split, no Kronecker products)."""
    from lambda_bezier.hazmat.forms import hodograph_matrix
    from lambda_bezier.surface_energies import _gram

    net = [[(i, j, (i * 3 + j) % 4) for j in range(4)] for i in range(5)]
    s = Surface(net, F(2, 5), F(-1, 3), family=fam)
    bez = s.to_bezier().control_net()

    def deriv_net(rows, a, b):
        rows = [list(r) for r in rows]
        for axis, k in ((0, a), (1, b)):
            for _ in range(k):
                if axis == 0:
                    h = hodograph_matrix(len(rows) - 1)
                    rows = [
                        [
                            tuple(
                                sum((w * rows[i][j][c] for i, w in enumerate(hr)), F(0))
                                for c in range(3)
                            )
                            for j in range(len(rows[0]))
                        ]
                        for hr in h
                    ]
                else:
                    h = hodograph_matrix(len(rows[0]) - 1)
                    rows = [
                        [
                            tuple(
                                sum((w * r[j][c] for j, w in enumerate(hr)), F(0)) for c in range(3)
                            )
                            for hr in h
                        ]
                        for r in rows
                    ]
        return rows

    def gram_energy(rows):
        gu, gv = _gram(len(rows) - 1), _gram(len(rows[0]) - 1)
        return sum(
            gu[i][k] * gv[j][q] * sum(x * y for x, y in zip(rows[i][j], rows[k][q], strict=True))
            for i in range(len(rows))
            for k in range(len(rows))
            for j in range(len(rows[0]))
            for q in range(len(rows[0]))
        )

    direct = (
        gram_energy(deriv_net(bez, 2, 0))
        + 2 * gram_energy(deriv_net(bez, 1, 1))
        + gram_energy(deriv_net(bez, 0, 2))
    )
    assert lb.surface_energy(s, "thin_plate") == direct
    mats = lb.surface_energy_matrices((4, 3), "thin_plate", fam)
    scale, upper = mats.terms[(1, 1)]
    assert isinstance(scale, Fraction) and all(isinstance(x, int) for row in upper for x in row)
    assert all(upper[r][c] == 0 for r in range(len(upper)) for c in range(r))


def test_energy_is_quadratic_in_each_parameter_and_quartic_jointly():
    mats = lb.surface_energy_matrices((3, 3), "membrane", "same_degree")
    assert set(mats.terms) <= {(a, b) for a in range(3) for b in range(3)}
    assert (2, 2) in mats.terms


# ---------------------------------------------------------------------- optimal parameters
def dense_minimum(poly, box_u, box_v, steps=801):
    xs = np.linspace(*box_u, steps)
    ys = np.linspace(*box_v, steps)
    x, y = np.meshgrid(xs, ys, indexing="ij")
    e = sum(float(c) * x**a * y**b for (a, b), c in poly.items())
    i = np.unravel_index(e.argmin(), e.shape)
    return x[i], y[i], e[i]


@pytest.mark.parametrize("fam, box", [("same_degree", (-2, 1)), ("bernstein_like", (-1, 1))])
@pytest.mark.parametrize("kind", ["membrane", "thin_plate"])
def test_exact_optimum_is_the_global_minimum(fam, box, kind):
    from scipy.optimize import minimize

    rng = np.random.default_rng(17)
    for _ in range(3):
        net = [
            [tuple(int(c) for c in rng.integers(-3, 4, 3) + (i, j, 0)) for j in range(4)]
            for i in range(4)
        ]
        res = lb.optimal_parameters(net, kind, fam)
        poly = lb.surface_energy_matrices((3, 3), kind, fam).polynomial(net)
        x, y, e = dense_minimum(poly, box, box)

        def f(p, poly=poly):
            return sum(float(c) * p[0] ** a * p[1] ** b for (a, b), c in poly.items())

        polished = minimize(
            f, [x, y], bounds=[box, box], method="L-BFGS-B", options={"ftol": 1e-15, "gtol": 1e-12}
        )
        best = min(e, polished.fun)
        assert float(res.energy) <= best + 1e-9 * max(1.0, abs(best))
        assert abs(float(res.energy) - f([res["lam_u_float"], res["lam_v_float"]])) <= 1e-9 * max(
            1, abs(best)
        )
        for key in ("lam_u", "lam_v"):
            value = res[key]
            assert isinstance(value, Fraction | lb.IsolatedRoot)
            if isinstance(value, lb.IsolatedRoot):  # a genuine isolating interval
                assert value.polynomial(value.lo) * value.polynomial(value.hi) < 0
                assert value.lo < res[key + "_float"] < value.hi


def test_optimum_with_a_free_parameter():
    # every row of the net is the same: S does not depend on λ_u, only on λ_v
    row = [(0, 0, 0), (1, 2, 1), (3, 2, -1), (4, 0, 0)]
    net = [row for _ in range(4)]
    res = lb.optimal_parameters(net, "membrane", "same_degree")
    assert res.free_u and not res.free_v and res["lam_u"] == 1  # the Bézier value


def test_batch_agrees_with_the_exact_method_and_is_certified():
    rng = np.random.default_rng(19)
    nets = np.stack([random_net(rng, 3, 3) for _ in range(300)])
    for fam in ("same_degree", "bernstein_like"):
        res = lb.optimal_parameters(nets, "thin_plate", fam)
        assert res.lam_u.shape == (300,)
        for i in range(0, 300, 37):
            one = lb.optimal_parameters(nets[i], "thin_plate", fam)
            assert abs(one.lam_u_float - res.lam_u[i]) <= 1e-12
            assert abs(one.lam_v_float - res.lam_v[i]) <= 1e-12


def test_batch_falls_back_to_exact_on_a_planar_net():
    # a planar net at λ-independent energy ties: the certificate must not guess
    flat = np.zeros((2, 4, 4, 3))
    flat[:, :, :, 0] = np.arange(4)[:, None]
    flat[:, :, :, 1] = np.arange(4)[None, :]
    res = lb.optimal_parameters(flat, "membrane", "same_degree")
    assert res.exact_fallbacks >= 1 or np.isfinite(res.lam_u).all()
    assert np.isfinite(res.energy).all()


# ---------------------------------------------------------------------- joins
@pytest.mark.parametrize("cont, order", [("C1", 1), ("C2", 2), ("G1", 1)])
@pytest.mark.parametrize("side", ["u", "v"])
def test_join_surface_continuity(cont, order, side):
    a = lb.SameDegreeSurface(
        [[(i, j, (i * j) % 3) for j in range(4)] for i in range(4)], F(1, 2), F(1, 3)
    )
    solved = order + 1
    if side == "u":
        rest = [[(4 + k, j, 0) for j in range(4)] for k in range(4 - solved)]
    else:
        rest = [[(i, 4 + k, 0) for k in range(5 - solved)] for i in range(4)]
    b = lb.join_surface(
        a,
        side,
        cont,
        3 if side == "u" else 4,
        F(-1, 2),
        rest=rest,
        alpha=2,
        family="same_degree" if side == "u" else "bernstein_like",
    )
    assert b.is_exact
    t = np.linspace(0, 1, 7)
    one, zero = np.ones(7), np.zeros(7)
    if side == "u":
        da = [a.derivative(one, t, r, 0) for r in range(order + 1)]
        db = [b.derivative(zero, t, r, 0) for r in range(order + 1)]
    else:
        da = [a.derivative(t, one, 0, r) for r in range(order + 1)]
        db = [b.derivative(t, zero, 0, r) for r in range(order + 1)]
    alpha = 2 if cont == "G1" else 1
    for r in range(order + 1):
        np.testing.assert_allclose(da[r], alpha**r * db[r], atol=1e-12)
    report = lb.CompositeSurface([[a], [b]] if side == "u" else [[a, b]]).report()
    assert [r.continuity for r in report] == [cont if cont != "C1" else "C1"] or (
        cont == "C1" and report[0].continuity in ("C1", "C2")
    )


def test_composite_report_finds_gaps_and_corners():
    a = lb.BezierSurface([[(i, j, 0) for j in range(3)] for i in range(3)])
    moved = lb.BezierSurface([[(2 + i, j, 1) for j in range(3)] for i in range(3)])
    kinked = lb.BezierSurface(
        [
            [(2, j, 0) for j in range(3)],
            [(2, j, 1) for j in range(3)],
            [(2, j, 2) for j in range(3)],
        ]
    )
    assert lb.CompositeSurface([[a], [moved]]).report()[0].continuity == "none"
    assert lb.CompositeSurface([[a], [kinked]]).report()[0].continuity == "C0"


# ---------------------------------------------------------------------- export
def test_step_is_read_back_by_occt(tmp_path):
    from OCP.BRep import BRep_Tool
    from OCP.STEPControl import STEPControl_Reader
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS

    from lambda_bezier.surface_export import to_step_surface

    s = lb.BernsteinLikeSurface(
        [[(i, j, (i * j) % 3) for j in range(4)] for i in range(5)], F(1, 2), F(-1, 3)
    )
    path = to_step_surface(s, tmp_path / "s.step")
    reader = STEPControl_Reader()
    reader.ReadFile(str(path))
    reader.TransferRoots()
    face = TopoDS.Face(TopExp_Explorer(reader.OneShape(), TopAbs_FACE).Current())
    occ = BRep_Tool.Surface_s(face)
    for u, v in ((0.3, 0.7), (0.0, 1.0), (0.9, 0.15)):
        p = occ.Value(u, v)
        np.testing.assert_allclose([p.X(), p.Y(), p.Z()], s.evaluate(u, v), atol=1e-12)
    # 17 significant digits in the file: the poles' doubles read back unchanged
    net = s.to_bezier().control_net()
    got = [
        [tuple(getattr(occ.Pole(i + 1, j + 1), c)() for c in "XYZ") for j in range(len(row))]
        for i, row in enumerate(net)
    ]
    assert got == [[tuple(float(v) for v in p) for p in row] for row in net]


def test_mesh_respects_its_tolerance(tmp_path):
    import trimesh

    from lambda_bezier.surface_export import mesh, to_mesh_file

    rng = np.random.default_rng(23)
    s = lb.SameDegreeSurface(random_net(rng, 3, 3), 0.5, -0.5)
    tol = 1e-2
    m = mesh(s, tol)
    assert m.deviation_bound <= tol
    # the triangles' centroids against the surface at the centroids' parameters
    cen = m.vertices[m.faces].mean(axis=1)
    uv = m.parameters[m.faces].mean(axis=1)
    dev = np.linalg.norm(cen - s.evaluate(uv[:, 0], uv[:, 1]), axis=1)
    assert 0 < dev.max() <= m.deviation_bound
    for suffix in ("obj", "stl"):
        path = to_mesh_file(s, tmp_path / f"s.{suffix}", tol)
        back = trimesh.load(str(path), process=False)
        assert len(back.faces) == len(m.faces)


def test_json_round_trip_is_exact():
    from lambda_bezier.surface_export import surface_from_json, surface_to_json

    s = lb.Surface(
        [[(i, F(j, 3), 1) for j in range(4)] for i in range(3)],
        None,
        F(-1, 3),
        family=("bezier", "bernstein_like"),
    )
    back = surface_from_json(surface_to_json(s))
    assert back.control_net() == s.control_net() and back.lam_v == F(-1, 3) and back.lam_u is None
    assert back.family == ("bezier", "bernstein_like")
    with pytest.raises(ValueError, match="surface.family"):
        surface_from_json(surface_to_json(s).replace("bernstein_like", "nope"))


# ---------------------------------------------------------------------- families, bad input
def test_user_family_surface():
    from lambda_bezier import examples

    fam = lb.load_family(examples.path("nouri_saeidian.toml"))
    net = [[(i, j, (i * j) % 2) for j in range(4)] for i in range(4)]
    s = fam.surface(net, F(1, 2), F(1, 4))
    assert s.family == "nouri_saeidian" and s.is_exact
    cu = s.curve_at_u(F(1, 3))
    assert cu.family == "nouri_saeidian" and cu.is_exact
    np.testing.assert_allclose(cu.evaluate(0.4), s.evaluate(1 / 3, 0.4), rtol=1e-13)
    res = lb.optimal_parameters(net, "membrane", fam)
    assert 0 <= res["lam_u_float"] <= 1


@pytest.mark.parametrize(
    "call, match",
    [
        (lambda: lb.SameDegreeSurface([[(0, 0)] * 4] * 4, 5, 0), "lam_u"),
        (lambda: lb.SameDegreeSurface([[(0, 0)] * 4] * 4, 0, "x"), "lam_v"),
        (lambda: lb.SameDegreeSurface([[(0, 0)] * 2] * 4, 0, 0), "direction v"),
        (lambda: lb.BezierSurface([[(0, float("nan"))] * 2] * 2), "non-finite"),
        (lambda: lb.BezierSurface([1, 2, 3]), "net"),
        (lambda: lb.BezierSurface([[(0, 0)] * 2] * 2).evaluate(1.5, 0), "u = 1.5"),
        (lambda: lb.BezierSurface([[(0, 0)] * 2] * 2).evaluate([0, 1], [0, 1, 0.5]), "same length"),
        (lambda: lb.BezierSurface([[(0, 0)] * 2] * 2).split_u(1), "0 < u < 1"),
        (lambda: lb.optimal_parameters([[(0, 0)] * 4] * 4, "bending"), "energy"),
        (lambda: lb.optimal_parameters([[(0, 0)] * 2] * 2, family="bezier"), "neither"),
        (lambda: lb.surface_energy_matrices((3,), "membrane"), "degrees"),
        (lambda: lb.join_surface(lb.BezierSurface([[(0, 0)] * 2] * 2), "w", "C1", 3), "side"),
        (lambda: lb.join_surface(lb.BezierSurface([[(0, 0)] * 2] * 2), "u", "G2", 3), "continuity"),
    ],
)
def test_bad_input_is_named(call, match):
    with pytest.raises((ValueError, TypeError), match=match):
        call()


coord = st.integers(-5, 5)


@given(
    st.integers(1, 4),
    st.integers(1, 4),
    st.lists(coord, min_size=75, max_size=75),
    st.fractions(-1, 1, max_denominator=7),
    st.fractions(-1, 1, max_denominator=7),
    st.fractions(0, 1, max_denominator=9),
    st.fractions(0, 1, max_denominator=9),
)
def test_random_exact_nets_bernstein_like(m, n, values, lu, lv, u, v):
    net = [
        [tuple(values[3 * (i * 5 + j) + c] for c in range(3)) for j in range(n + 1)]
        for i in range(m + 1)
    ]
    s = lb.BernsteinLikeSurface(net, lu, lv) if m >= 2 and n >= 2 else lb.BezierSurface(net)
    exact = exact_bernstein(s.to_bezier().control_net(), u, v)
    np.testing.assert_allclose(
        s.evaluate(float(u), float(v)), [float(c) for c in exact], atol=1e-12 * 50
    )
    iso = s.curve_at_u(u).to_bezier().control_points()
    assert exact_bernstein([[p] for p in iso], v, F(0)) == exact


def test_plot_surface_draws_the_surface_and_its_net():
    import matplotlib

    matplotlib.use("Agg")
    from lambda_bezier.surface_plot import plot_surface

    s = lb.SameDegreeSurface([[(i, j, (i * j) % 2) for j in range(4)] for i in range(4)], 0.5, 0.5)
    ax = plot_surface(s, curvature="mean", samples=12)
    assert len(ax.collections) == 1 and len(ax.lines) == 8  # the surface; 4 + 4 net lines
    with pytest.raises(ValueError, match="curvature"):
        plot_surface(s, curvature="sectional")
    with pytest.raises(ValueError, match="dimension 2"):
        plot_surface(lb.BezierSurface([[(0, 0), (1, 0)], [(0, 1), (1, 1)]]))


# ---------------------------------------------------------------------- emitted vs Kronecker
@pytest.mark.parametrize("fam", ["bezier", "same_degree", "bernstein_like"])
@pytest.mark.parametrize("kind", ["membrane", "thin_plate"])
def test_emitted_energy_matrices_equal_the_kronecker_construction(fam, kind):
    from lambda_bezier import surface_energies as se
    from lambda_bezier._lazy import generated

    table = generated("surface_energy").SURFACE_ENERGY[fam]
    cls = se.family_class(fam)
    degrees = sorted({(m, n) for (m, n, e) in table if e == kind})
    assert degrees, f"no emitted {kind} matrices for {fam}"
    for m, n in degrees:
        read = se._emitted_matrices(cls, cls, m, n, kind)
        assert read is not None
        assert se.surface_energy_matrices((m, n), kind, fam).full == read.full
        kron = se.kronecker_matrices(cls, cls, m, n, kind)
        assert read.full == kron.full, (fam, kind, m, n)
        assert read.terms == kron.terms, (fam, kind, m, n)  # one normalisation of (s, U)


def test_mixed_families_fall_back_to_the_kronecker_form():
    from lambda_bezier import surface_energies as se

    u, v = se.family_class("same_degree"), se.family_class("bezier")
    assert se._emitted_matrices(u, v, 3, 3, "membrane") is None
    assert se.surface_energy_matrices((3, 3), "membrane", (u, v)).full == (
        se.kronecker_matrices(u, v, 3, 3, "membrane").full
    )
