"""Surfaces of several-parameter, indexed and trigonometric/hyperbolic/mixed families
(param_surfaces, atom_surfaces, param_surface_energy), against independent numerics: the
families' bases written out here from the papers' formulas and evaluated with mpmath,
finite differences, Gauss-Legendre quadrature of those explicit bases, dense sampling, and
OCCT reading the STEP file back."""

from __future__ import annotations

import math
from fractions import Fraction as F

import mpmath
import numpy as np
import pytest
from conftest import occt_surface, surface_families
from han_surface_reference import NET, PU, han, mp

import lambda_bezier as lb
from lambda_bezier import examples
from lambda_bezier import surface_export as se
from lambda_bezier.atom_surfaces import AtomSurface, RationalBezierSurface
from lambda_bezier.param_surfaces import ParamSurface

TRIG, TWO, QB, HYP, MIXED = surface_families()

PV = {"lam": 0, "mu": F(1, 3)}


def han_surface(u: object, v: object, du: int = 0, dv: int = 0) -> np.ndarray:
    """Σ P_ij b_i(u) b_j(v) (or a partial derivative, mpmath.diff of the explicit basis)."""
    bu = [mpmath.diff(lambda t, i=i: han(i, t, *map(mp, PU.values())), u, du) for i in range(4)]
    bv = [mpmath.diff(lambda t, j=j: han(j, t, *map(mp, PV.values())), v, dv) for j in range(4)]
    out = [
        sum(float(bu[i] * bv[j]) * float(NET[i][j][c]) for i in range(4) for j in range(4))
        for c in range(3)
    ]
    return np.array(out)


def trig_surface() -> AtomSurface:
    s = TRIG.surface(NET, params_u=PU, params_v=PV)
    assert isinstance(s, AtomSurface)
    return s


# ---------------------------------------------------------------------- the API
def test_every_kind_of_family_has_a_surface():
    assert isinstance(TWO.surface(NET, params_u=PU, params_v=PV), ParamSurface)
    q = QB.surface(NET, [1, F(1, 2), -1], params_v={"lam": [0, 0, 0]})
    assert isinstance(q, ParamSurface)
    assert q.parameters()["lam_u"] == (1, F(1, 2), -1)
    assert isinstance(trig_surface(), AtomSurface)
    nouri = lb.load_family(examples.path("nouri_saeidian.toml"))
    one = nouri.surface(NET, F(1, 2), params_v={"sigma": F(1, 4)})
    assert one.parameters() == {"sigma_u": F(1, 2), "sigma_v": F(1, 4)}
    # the one-parameter form keeps giving the generic Surface
    assert type(nouri.surface(NET, F(1, 2), F(1, 4))) is lb.Surface
    assert repr(trig_surface()).startswith("AtomSurface(han_trig_cubic x han_trig_cubic")


@pytest.mark.parametrize(
    ("kwargs", "exc", "words"),
    [
        ({"params_u": {"lam": 0, "nu": 0}, "params_v": PV}, TypeError, "params_u: 'nu'"),
        ({"params_u": {"lam": 0}, "params_v": PV}, TypeError, "params_u: a han_trig_cubic"),
        ({"params_u": PU, "params_v": {"lam": 2, "mu": 0}}, ValueError, "params_v: lam = 2"),
        ({"params_u": PU, "params_v": "lam"}, TypeError, "params_v must be a dict"),
        ({"lam_u": 0, "params_v": PV}, TypeError, "params_u"),
    ],
)
def test_bad_parameters_are_named(kwargs, exc, words):
    with pytest.raises(exc, match=words):
        TRIG.surface(NET, **kwargs)
    fam = TWO
    with pytest.raises(exc):
        fam.surface(NET, **kwargs)


def test_indexed_direction_needs_one_value_per_index():
    with pytest.raises(ValueError, match="params_u: lam: degree 3 has 3 parameters"):
        QB.surface(NET, [1, 2], params_v={"lam": [0, 0, 0]})
    with pytest.raises(TypeError, match="params_v: the q_bezier direction needs lam"):
        QB.surface(NET, [0, 0, 0])
    with pytest.raises(TypeError, match="params_u: 'mu' is not a parameter"):
        QB.surface(NET, params_u={"mu": [0, 0, 0]}, params_v={"lam": [0, 0, 0]})


def test_domain_and_degree_are_checked():
    s = trig_surface()
    with pytest.raises(ValueError, match=r"u = 2.0 is outside the han_trig_cubic domain"):
        s.evaluate(2.0, 0.1)
    with pytest.raises(ValueError, match="direction v"):
        TRIG.surface([row[:3] for row in NET], params_u=PU, params_v=PV)
    with pytest.raises(ValueError, match="to_rational_bezier"):
        s.to_bezier()


# ---------------------------------------------------------------------- evaluation
@pytest.mark.parametrize(("du", "dv"), [(0, 0), (1, 0), (0, 1), (1, 1), (2, 0), (0, 2), (2, 1)])
def test_trig_surface_against_the_explicit_basis(du, dv):
    s = trig_surface()
    for u, v in ((0.0, 0.0), (0.3, 1.1), (math.pi / 2, 0.7), (1.2, math.pi / 2)):
        want = han_surface(u, v, du, dv)
        got = s.derivative(u, v, du, dv)
        assert np.allclose(got, want, rtol=1e-12, atol=1e-12), (u, v, got, want)


def test_scattered_grid_and_finite_differences_agree():
    s = trig_surface()
    us, vs = np.linspace(0, math.pi / 2, 7), np.linspace(0, math.pi / 2, 5)
    grid = s.evaluate_grid(us, vs, 1, 1)
    uu, vv = np.meshgrid(us, vs, indexing="ij")
    assert np.allclose(grid.reshape(-1, 3), s.derivative(uu.ravel(), vv.ravel(), 1, 1), atol=1e-13)
    h = 1e-5
    u, v = 0.7, 0.4
    fd = (s.evaluate(u + h, v) - s.evaluate(u - h, v)) / (2 * h)
    assert np.allclose(fd, s.derivative(u, v, 1, 0), atol=1e-8)


def test_param_surface_against_its_curves():
    s = TWO.surface(NET, params_u=PU, params_v=PV)
    u, v = 0.3, 0.8
    col = [TWO.curve([NET[i][j] for i in range(4)], params=PU).evaluate(u) for j in range(4)]
    want = TWO.curve(col, params=PV).evaluate(v)
    assert np.allclose(s.evaluate(u, v), want, atol=1e-14)
    b = s.to_bezier()
    assert all(isinstance(c, F) for row in b.control_net() for p in row for c in p)


def test_normal_and_curvatures_from_the_explicit_basis():
    s = trig_surface()
    u, v = 0.6, 0.9
    su, sv = han_surface(u, v, 1, 0), han_surface(u, v, 0, 1)
    n = np.cross(su, sv)
    n /= np.linalg.norm(n)
    assert np.allclose(s.normal(u, v), n, atol=1e-12)
    e, f, g = su @ su, su @ sv, sv @ sv
    l_, m_, nn = (han_surface(u, v, a, b) @ n for a, b in ((2, 0), (1, 1), (0, 2)))
    k, h = s.curvatures(u, v)
    assert math.isclose(k, (l_ * nn - m_ * m_) / (e * g - f * f), rel_tol=1e-10)
    assert math.isclose(h, (e * nn - 2 * f * m_ + g * l_) / (2 * (e * g - f * f)), rel_tol=1e-10)


def test_iso_curves_are_curves_of_the_family():
    s = trig_surface()
    c = s.curve_at_u(0.4)
    assert c.parameter_values == {"lam": 0, "mu": F(1, 3)}
    assert np.allclose(c.evaluate(1.0), s.evaluate(0.4, 1.0), atol=1e-14)
    d = s.curve_at_v(1.0)
    assert np.allclose(d.evaluate(0.4), s.evaluate(0.4, 1.0), atol=1e-14)
    # exact at a rational s of the rational form: t = 2 atan(s)
    e = s.curve_at_u(s=F(1, 2))
    assert all(isinstance(x, F) for p in e.control_points() for x in p)
    assert np.allclose(e.evaluate(0.9), s.evaluate(2 * math.atan(0.5), 0.9), atol=1e-14)
    with pytest.raises(TypeError, match="once"):
        s.curve_at_u(0.4, s=F(1, 2))
    q = QB.surface(NET, [1, F(1, 2), -1], params_v={"lam": [0, F(1, 2), 0]})
    qc = q.curve_at_u(F(1, 3))
    assert type(qc).parameter_values == {"lam_1": 0, "lam_2": F(1, 2), "lam_3": 0}
    assert all(isinstance(x, F) for p in qc.control_points() for x in p)


# ---------------------------------------------------------------------- the rational form
def test_rational_form_is_exact_and_the_same_surface():
    s = trig_surface()
    r = s.to_rational_bezier()
    assert isinstance(r, RationalBezierSurface) and r.degrees == (6, 6)
    assert all(isinstance(w, F) for row in r.control_weights() for w in row)
    us = np.array([0.0, 0.2, 0.9, math.pi / 2])
    vs = np.array([0.1, 1.3, 0.5, 0.0])
    got = r.evaluate(s.s_of_t(0, us), s.s_of_t(1, vs))
    assert np.allclose(got, s.evaluate(us, vs), atol=1e-13)


def test_split_gives_the_rational_pieces():
    s = trig_surface()
    left, right = s.split_u(0.5)
    s_mid = s.s_of_t(0, 0.5)
    for x in (0.0, 0.3, 1.0):
        t_left = s.t_of_s(0, x * s_mid)
        assert np.allclose(left.evaluate(x, 0.4), s.evaluate(t_left, s.t_of_s(1, 0.4)), atol=1e-12)
        t_right = s.t_of_s(0, s_mid + x * (1 - s_mid))
        assert np.allclose(
            right.evaluate(x, 0.4), s.evaluate(t_right, s.t_of_s(1, 0.4)), atol=1e-12
        )


@pytest.mark.parametrize("fam", [TRIG, HYP, MIXED])
def test_bounding_box_and_closest_point_against_dense_sampling(fam):
    params = {name: 0 for name in fam.parameters}
    s = fam.surface(NET, params_u=params, params_v=params)
    (a, b), (c, d) = s.domain_u, s.domain_v
    us, vs = np.linspace(a, b, 201), np.linspace(c, d, 201)
    dense = s.evaluate_grid(us, vs).reshape(-1, 3)
    lo, hi = s.bounding_box()
    assert (lo <= dense.min(axis=0) + 1e-12).all() and (hi >= dense.max(axis=0) - 1e-12).all()
    assert np.allclose(lo, dense.min(axis=0), atol=1e-4)
    q = np.array([1.2, 2.1, 1.5])
    cp = s.closest_point(q)
    sampled = np.linalg.norm(dense - q, axis=1).min()
    assert cp.distance <= sampled + 1e-12
    assert np.allclose(s.evaluate(cp.u, cp.v), cp.point, atol=1e-13)
    assert cp.lower_bound <= cp.distance
    if fam is not MIXED:  # certified through the rational form
        assert cp.distance - cp.lower_bound < 1e-9


# ---------------------------------------------------------------------- energies
def _gauss_legendre_energy(energy: str) -> float:
    """∫∫ over [0, π/2]² of the energy density of the explicit basis, by a tensor Gauss-
    Legendre rule of 24 nodes (exact to about 1e-14 for these trigonometric polynomials)."""
    x, w = np.polynomial.legendre.leggauss(24)
    t = (x + 1) * math.pi / 4
    wt = w * math.pi / 4

    def table(params: dict, k: int) -> np.ndarray:
        vals = [mp(x) for x in params.values()]
        return np.array(
            [
                [float(mpmath.diff(lambda y, i=i: han(i, y, *vals), ti, k)) for i in range(4)]
                for ti in t
            ]
        )

    net = np.array(NET, dtype=float)
    terms = {"membrane": ((1, 0, 1), (0, 1, 1)), "thin_plate": ((2, 0, 1), (1, 1, 2), (0, 2, 1))}
    total = 0.0
    for a, b, weight in terms[energy]:
        d = np.einsum("ki,ijc,lj->klc", table(PU, a), net, table(PV, b))
        total += weight * float(np.einsum("k,l,klc->", wt, wt, d * d))
    return total


@pytest.mark.parametrize("energy", ["membrane", "thin_plate"])
def test_trig_energy_is_exact_in_pi_and_matches_quadrature(energy):
    got = lb.surface_energy(trig_surface(), energy)
    assert isinstance(got, lb.ConstantFraction)  # an exact element of Q(pi)
    assert math.isclose(float(got), _gauss_legendre_energy(energy), rel_tol=1e-11)


@pytest.mark.parametrize("fam", [HYP, MIXED, QB])
@pytest.mark.parametrize("energy", ["membrane", "thin_plate"])
def test_energy_of_other_families_matches_quadrature(fam, energy):
    """The Gram route (the derived document's Gram matrices, or Bernstein tables) against a
    Gauss-Legendre quadrature of the surface's own partial derivatives over its domain."""
    if fam is QB:
        s = fam.surface(NET, [1, F(1, 2), -1], [0, F(1, 3), 0])
        (a, b), (c, d) = (0.0, 1.0), (0.0, 1.0)
    else:
        params = {k: F(i + 1, 5) for i, k in enumerate(fam.parameters)}
        s = fam.surface(NET, params_u=params, params_v=params)
        (a, b), (c, d) = s.domain_u, s.domain_v
    x, w = np.polynomial.legendre.leggauss(30)
    us, wu = a + (x + 1) * (b - a) / 2, w * (b - a) / 2
    vs, wv = c + (x + 1) * (d - c) / 2, w * (d - c) / 2
    terms = {"membrane": ((1, 0, 1), (0, 1, 1)), "thin_plate": ((2, 0, 1), (1, 1, 2), (0, 2, 1))}
    want = sum(
        k * float(np.einsum("i,j,ijc->", wu, wv, s.evaluate_grid(us, vs, p, q) ** 2))
        for p, q, k in terms[energy]
    )
    got = lb.surface_energy(s, energy)
    assert isinstance(got, F | lb.ConstantFraction)
    assert math.isclose(float(got), want, rel_tol=1e-11)


def test_several_parameter_energy_matches_the_kronecker_form():
    s = TWO.surface(NET, params_u=PU, params_v=PV)
    generic = lb.Surface(NET, None, None, family=(s._u_cls, s._v_cls))
    for energy in ("membrane", "thin_plate"):
        got = lb.surface_energy(s, energy)
        assert isinstance(got, F)
        assert got == lb.surface_energy(generic, energy)


# ---------------------------------------------------------------------- the optimum
def test_optimal_parameters_by_name_certified():
    net = [[(i, j, F((i + 2 * j) % 3, 2)) for j in range(4)] for i in range(4)]
    r = lb.optimal_parameters(net, "membrane", family=TRIG)
    assert set(r.parameters) == {"lam_u", "mu_u", "lam_v", "mu_v"}
    assert r.certified and r.lower_bound <= r.energy
    assert float(r.energy - r.lower_bound) <= 1e-12 * float(r.energy)
    at = TRIG.surface(
        net,
        params_u={"lam": r["lam_u"], "mu": r["mu_u"]},
        params_v={"lam": r["lam_v"], "mu": r["mu_v"]},
    )
    assert lb.surface_energy(at, "membrane") == r.energy
    rng = np.random.default_rng(3)
    for _ in range(30):  # no point of the box does better than the certified bound
        p = {k: F(int(rng.integers(-20, 11)), 10) for k in ("a", "b", "c", "d")}
        other = TRIG.surface(
            net, params_u={"lam": p["a"], "mu": p["b"]}, params_v={"lam": p["c"], "mu": p["d"]}
        )
        assert float(lb.surface_energy(other, "membrane")) >= float(r.lower_bound)


def test_optimal_parameters_of_an_indexed_family():
    net = [[(i, j, F((i * j) % 2)) for j in range(3)] for i in range(3)]
    r = lb.optimal_parameters(net, "membrane", family=QB)
    assert isinstance(r["lam_u"], tuple) and len(r["lam_u"]) == 2
    assert r.certified
    with pytest.raises(KeyError, match="the parameters are lam_u, lam_v"):
        r["mu_u"]


# ---------------------------------------------------------------------- joins
@pytest.mark.parametrize("fam", [TRIG, TWO, QB, HYP])
@pytest.mark.parametrize(("continuity", "rows"), [("C1", 2), ("G1", 2), ("C2", 1)])
def test_join_surface_matches_cross_derivatives(fam, continuity, rows):
    if fam is QB:
        pu, pv, new = {"lam": [1, F(1, 2), -1]}, {"lam": [0, F(1, 3), 0]}, {"lam": [0, 0, 0]}
    else:
        pu = {k: F(i + 1, 4) for i, k in enumerate(fam.parameters)}
        pv = {k: -F(i + 1, 3) for i, k in enumerate(fam.parameters)}
        new = {k: 0 for k in fam.parameters}
    a = fam.surface(NET, params_u=pu, params_v=pv)
    alpha = F(1, 2) if continuity == "G1" else 1
    rest = [[(5 + k, j, F(j, 3)) for j in range(4)] for k in range(rows)]
    b = lb.join_surface(a, "u", continuity, 3, rest=rest, alpha=alpha, params=new)
    assert type(b) is type(a)
    assert b.parameters()[f"{fam.parameters[0]}_v"] == a.parameters()[f"{fam.parameters[0]}_v"]
    hi = a.domain_u[1] if isinstance(a, AtomSurface) else 1.0
    lo = b.domain_u[0] if isinstance(b, AtomSurface) else 0.0
    vs = np.linspace(*(a.domain_v if isinstance(a, AtomSurface) else (0, 1)), 7)
    for k in range(3 if continuity == "C2" else 2):
        want = a.derivative(hi, vs, k, 0)
        got = b.derivative(lo, vs, k, 0) * float(alpha) ** k
        assert np.allclose(got, want, atol=1e-12), (k, got, want)
    if isinstance(b, ParamSurface):  # exact in, exact out
        assert all(isinstance(c, F) for row in b.control_net() for p in row for c in p)


def test_join_surface_refuses_lam_for_parameters_by_name():
    with pytest.raises(ValueError, match="params="):
        lb.join_surface(
            trig_surface(), "u", "C1", 3, F(1, 2), rest=[[(5, j, 0) for j in range(4)]] * 2
        )


# ---------------------------------------------------------------------- export
@pytest.mark.parametrize(
    ("fam", "pu", "pv"),
    [
        (TRIG, PU, {"lam": 0, "mu": 0.25}),
        (TWO, PU, PV),
        (QB, {"lam": [1, F(1, 2), -1]}, {"lam": [0, 0, 0]}),
    ],
)
def test_json_round_trip(fam, pu, pv):
    s = fam.surface(NET, params_u=pu, params_v=pv)
    back = se.surface_from_json(se.surface_to_json(s), family=fam)
    assert type(back) is type(s)
    assert back.control_net() == s.control_net()
    assert back.parameters() == s.parameters()
    assert np.array_equal(back.evaluate(0.3, 0.4), s.evaluate(0.3, 0.4))
    with pytest.raises(ValueError, match="not built in"):
        se.surface_from_json(se.surface_to_json(s))


def test_step_export_read_back_by_occt(tmp_path):
    s = trig_surface()
    path = se.to_step_surface(s, tmp_path / "trig.step")
    surf = occt_surface(path)
    assert surf.IsURational() and surf.IsVRational()  # the weights are kept
    for u, v in ((0.1, 0.2), (1.0, 0.4), (0.7, 1.5)):
        p = surf.Value(float(s.s_of_t(0, u)), float(s.s_of_t(1, v)))
        assert np.allclose([p.X(), p.Y(), p.Z()], s.evaluate(u, v), atol=1e-12)


@pytest.mark.parametrize("fam", [TRIG, HYP, MIXED])
def test_mesh_deviation_bound_holds(fam):
    params = {name: 0 for name in fam.parameters}
    s = fam.surface(NET, params_u=params, params_v=params)
    m = se.mesh(s, 1e-2)
    assert m.deviation_bound <= 1e-2
    (a, b), (c, d) = s.domain_u, s.domain_v
    assert m.parameters[:, 0].min() == a and m.parameters[:, 0].max() == b
    # the surface at the parameters of points inside the triangles, against the triangles
    rng = np.random.default_rng(0)
    bary = rng.dirichlet((1, 1, 1), size=len(m.faces))
    pts = np.einsum("fk,fkd->fd", bary, m.vertices[m.faces])
    par = np.einsum("fk,fkd->fd", bary, m.parameters[m.faces])
    dev = np.linalg.norm(s.evaluate(par[:, 0], par[:, 1]) - pts, axis=1).max()
    assert dev <= m.deviation_bound
    # the bounds of the second derivatives hold at dense samples
    muu, muv, mvv = s.derivative_bounds()
    us, vs = np.linspace(a, b, 301), np.linspace(c, d, 301)
    for (p, q), bound in zip(((2, 0), (1, 1), (0, 2)), (muu, muv, mvv), strict=True):
        assert np.linalg.norm(s.evaluate_grid(us, vs, p, q), axis=-1).max() <= bound


def test_plot_covers_the_whole_domain():
    pytest.importorskip("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    from lambda_bezier.surface_plot import plot_surface

    s = trig_surface()
    ax = plot_surface(s, curvature="mean", net=False)
    _, hi = s.bounding_box()
    top = float(ax.xy_dataLim.intervalx[1])  # the data the surface was drawn with
    assert math.isclose(top, hi[0], abs_tol=1e-9)  # it reaches u = pi/2, not only u = 1
