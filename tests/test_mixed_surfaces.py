"""Surfaces with a trigonometric, hyperbolic or mixed family in one direction and a polynomial
family in the other (atom_surfaces with _poly_direction), against independent numerics: both
directions' bases written out here from the papers' formulas and evaluated with mpmath, the
Kronecker form of each direction's Gram matrices from Gauss-Legendre quadrature of those
explicit bases, dense sampling, finite differences and OCCT reading the STEP file back."""

from __future__ import annotations

import math
from fractions import Fraction as F

import mpmath
import numpy as np
import pytest
from conftest import occt_surface, surface_families
from han_surface_reference import NET, PU, han, mp

import lambda_bezier as lb
from lambda_bezier import surface_export as se
from lambda_bezier.atom_surfaces import AtomSurface, RationalBezierSurface
from lambda_bezier.param_surfaces import family_surface

DATA = "tests/data/families/"
TRIG, TWO, _, HYP, MIXED = surface_families()

LAM_V = F(1, 3)
HALF_PI = mpmath.pi / 2


def han_at_pu(i: int, t: object) -> object:
    """Han, Ma and Huang's cubic trigonometric basis at PU (mpmath)."""
    return han(i, t, mp(PU["lam"]), mp(PU["mu"]))


def same_degree(i: int, t: object, n: int = 3) -> object:
    """Eq. (1) of paper 000 at λ = LAM_V, written out (mpmath; binomials 0 outside range)."""

    def c(a: int, b: int) -> int:
        return math.comb(a, b) if 0 <= b <= a else 0

    lam, s = mp(LAM_V), 1 - t
    value = c(n, i) * s ** (n - i) * t**i
    for coeff, ps, pt in (
        (c(n - 3, i - 3), n - i + 1, i - 1),
        (-c(n - 2, i - 1), n - i, i),
        (c(n - 3, i), n - i - 1, i + 1),
    ):
        if coeff:
            value += (1 - lam) * coeff * s**ps * t**pt
    return value


def mixed_surface() -> AtomSurface:
    s = TRIG.surface(NET, params_u=PU, lam_v=LAM_V, family_v="same_degree")
    assert isinstance(s, AtomSurface)
    return s


def explicit(u: float, v: float, du: int, dv: int) -> np.ndarray:
    bu = [mpmath.diff(lambda t, i=i: han_at_pu(i, t), u, du) for i in range(4)]
    bv = [mpmath.diff(lambda t, j=j: same_degree(j, t), v, dv) for j in range(4)]
    return np.array(
        [
            sum(float(bu[i] * bv[j]) * float(NET[i][j][c]) for i in range(4) for j in range(4))
            for c in range(3)
        ]
    )


# ---------------------------------------------------------------------- the API
def test_each_direction_takes_its_own_family_and_parameters():
    s = mixed_surface()
    assert s.family == ("han_trig_cubic", "same_degree")
    assert s.parameters() == {"lam_u": F(1, 2), "mu_u": -1, "lam_v": F(1, 3)}
    assert s.domain_u == (0.0, math.pi / 2) and s.domain_v == (0.0, 1.0)
    assert s.is_exact
    # the same surface from the pair, and the polynomial family in u
    pair = family_surface(NET, (TRIG, "same_degree"), params_u=PU, lam_v=LAM_V)
    assert np.array_equal(pair.evaluate(0.3, 0.4), s.evaluate(0.3, 0.4))
    swapped = family_surface(
        [list(col) for col in zip(*NET, strict=True)], ("same_degree", TRIG), LAM_V, params_v=PU
    )
    assert swapped.family == ("same_degree", "han_trig_cubic")
    assert np.allclose(swapped.evaluate(0.4, 0.3), s.evaluate(0.3, 0.4), atol=1e-14)
    # several-parameter polynomial, classical Bézier and a family object across
    for other, kw in ((TWO, {"params_v": {"lam": 0, "mu": F(1, 3)}}), ("bezier", {})):
        got = TRIG.surface(NET, params_u=PU, family_v=other, **kw)
        assert isinstance(got, AtomSurface)
    assert TWO.surface(NET, params_u={"lam": 0, "mu": 0}, family_v=TRIG, params_v=PU).family == (
        "two_shape_cubic",
        "han_trig_cubic",
    )


@pytest.mark.parametrize(
    ("kwargs", "exc", "words"),
    [
        ({"family_v": "same_degree"}, TypeError, "params_v: the same_degree direction needs"),
        ({"family_v": "same_degree", "lam_v": 5}, ValueError, r"params_v: lam: lam = 5 is outs"),
        ({"family_v": "bezier", "lam_v": 1}, TypeError, "params_v: the bezier direction takes"),
        ({"family_v": "same_degree", "params_v": {"mu": 1}}, TypeError, "'mu' is not a param"),
        ({"family_v": "nope", "lam_v": 0}, ValueError, "unknown family 'nope'"),
    ],
)
def test_bad_polynomial_directions_are_named(kwargs, exc, words):
    with pytest.raises(exc, match=words):
        TRIG.surface(NET, params_u=PU, **kwargs)


def test_degree_of_the_polynomial_direction_is_checked():
    net = [[(i, j, 0) for j in range(3)] for i in range(4)]  # degree 2 in v
    with pytest.raises(ValueError, match="direction v: 3 control points make degree 2"):
        TRIG.surface(net, params_u=PU, lam_v=0, family_v="same_degree")


# ---------------------------------------------------------------------- geometry
@pytest.mark.parametrize(("du", "dv"), [(0, 0), (1, 0), (0, 1), (1, 1), (2, 0), (0, 2)])
def test_values_and_partials_against_the_explicit_bases(du, dv):
    s = mixed_surface()
    for u, v in ((0.0, 0.0), (0.3, 0.7), (1.2, 0.25), (math.pi / 2, 1.0)):
        want = explicit(u, v, du, dv)
        assert np.allclose(s.derivative(u, v, du, dv), want, rtol=1e-12, atol=1e-12)
    grid = s.evaluate_grid([0.1, 0.9], [0.2, 0.6], du, dv)
    assert np.allclose(grid[1, 0], explicit(0.9, 0.2, du, dv), rtol=1e-12, atol=1e-12)


def test_normal_and_curvatures_by_finite_differences():
    s = mixed_surface()
    u, v, h = 0.8, 0.45, 1e-5
    su = (s.evaluate(u + h, v) - s.evaluate(u - h, v)) / (2 * h)
    sv = (s.evaluate(u, v + h) - s.evaluate(u, v - h)) / (2 * h)
    n = np.cross(su, sv)
    assert np.allclose(s.normal(u, v), n / np.linalg.norm(n), atol=1e-8)
    gauss, mean = s.curvatures(u, v)
    assert math.isfinite(float(gauss)) and math.isfinite(float(mean))


def test_iso_curves_are_curves_of_each_directions_family():
    s = mixed_surface()
    along_u = s.curve_at_v(F(1, 4))  # exact: the polynomial direction at a rational v
    assert type(along_u).__name__ == "HanTrigCubicCurve"
    assert all(isinstance(c, F) for p in along_u.control_points() for c in p)
    along_v = s.curve_at_u(s=F(1, 2))  # exact at a rational s of the trigonometric form
    assert type(along_v).__name__ == "SameDegreeCurve" and along_v.lam == LAM_V
    assert all(isinstance(c, F) for p in along_v.control_points() for c in p)
    u = float(s.t_of_s(0, 0.5))
    for t in (0.0, 0.35, 1.0):
        assert np.allclose(along_u.evaluate(t * math.pi / 2), s.evaluate(t * math.pi / 2, 0.25))
        assert np.allclose(along_v.evaluate(t), s.evaluate(u, t), atol=1e-13)


def test_rational_form_is_exact_and_the_same_surface():
    s = mixed_surface()
    r = s.to_rational_bezier()
    assert isinstance(r, RationalBezierSurface) and r.degrees == (6, 3)
    assert all(isinstance(w, F) for row in r.control_weights() for w in row)
    us, vs = np.array([0.0, 0.2, 0.9, math.pi / 2]), np.array([0.1, 1.0, 0.5, 0.0])
    assert np.allclose(r.evaluate(s.s_of_t(0, us), vs), s.evaluate(us, vs), atol=1e-13)
    with pytest.raises(ValueError, match="to_rational_bezier"):
        s.to_bezier()
    with pytest.raises(ValueError, match="degree elevation"):
        s.elevate_u()


@pytest.mark.parametrize("axis", [0, 1])
def test_split_in_either_direction_gives_the_rational_pieces(axis):
    s = mixed_surface()
    t = 0.5 if axis == 0 else 0.3
    left, right = s.split_u(t) if axis == 0 else s.split_v(t)
    mid = float(s.s_of_t(axis, t))
    other = float(s.s_of_t(1 - axis, 0.7))  # the other direction's s at its t = 0.7
    for x in (0.0, 0.4, 1.0):
        for piece, at in ((left, x * mid), (right, mid + x * (1 - mid))):
            tt = float(s.t_of_s(axis, at))
            if axis == 0:
                got, want = piece.evaluate(x, other), s.evaluate(tt, 0.7)
            else:
                got, want = piece.evaluate(other, x), s.evaluate(0.7, tt)
            assert np.allclose(got, want, atol=1e-12)


@pytest.mark.parametrize("fam", [TRIG, HYP])
def test_box_and_closest_point_certified_against_dense_sampling(fam):
    params = {name: 0 for name in fam.parameters}
    s = fam.surface(NET, params_u=params, lam_v=F(1, 2), family_v="bernstein_like")
    (a, b), (c, d) = s.domain_u, s.domain_v
    dense = s.evaluate_grid(np.linspace(a, b, 201), np.linspace(c, d, 201)).reshape(-1, 3)
    lo, hi = s.bounding_box()
    assert (lo <= dense.min(axis=0) + 1e-12).all() and (hi >= dense.max(axis=0) - 1e-12).all()
    assert np.allclose(lo, dense.min(axis=0), atol=1e-4)
    q = np.array([1.2, 2.1, 1.5])
    cp = s.closest_point(q)
    assert cp.distance <= np.linalg.norm(dense - q, axis=1).min() + 1e-12
    assert np.allclose(s.evaluate(cp.u, cp.v), cp.point, atol=1e-13)
    assert 0 <= cp.distance - cp.lower_bound < 1e-9


def test_mixed_atom_across_polynomial_has_no_rational_form():
    """It evaluates, and refuses a rational form it has not; its certified box and closest
    point are tested in tests/test_mixed_poly_surface_bounds.py."""
    s = MIXED.surface(NET, params_u={"lam": F(1, 2)}, lam_v=0, family_v="same_degree")
    assert np.isfinite(s.evaluate(0.3, 0.4)).all()
    with pytest.raises(ValueError, match="no (exact )?rational (Bézier )?form"):
        s.to_rational_bezier()


# ---------------------------------------------------------------------- energies
def _gram(basis, lo, hi, k: int, nodes: int = 24) -> np.ndarray:
    """G[i][l] = ∫ b_i^(k) b_l^(k) over [lo, hi] by Gauss-Legendre on the explicit basis."""
    x, w = np.polynomial.legendre.leggauss(nodes)
    ts = lo + (hi - lo) * (x + 1) / 2
    vals = np.array(
        [[float(mpmath.diff(lambda y, i=i: basis(i, y), t, k)) for i in range(4)] for t in ts]
    )
    return (vals.T * (w * (hi - lo) / 2)) @ vals


@pytest.mark.parametrize("energy", ["membrane", "thin_plate"])
def test_energy_exact_in_pi_matches_the_kronecker_form_of_each_directions_grams(energy):
    s = mixed_surface()
    got = lb.surface_energy(s, energy)
    assert "pi" in str(got)  # an exact element of Q(pi), not a float
    gu = [_gram(han_at_pu, 0.0, math.pi / 2, k) for k in range(3)]
    gv = [_gram(same_degree, 0.0, 1.0, k) for k in range(3)]
    terms = [(1, 0, 1), (0, 1, 1)] if energy == "membrane" else [(2, 0, 1), (1, 1, 2), (0, 2, 1)]
    form = sum(w * np.kron(gu[p], gv[q]) for p, q, w in terms)
    net = np.array(NET, dtype=float)
    want = sum(net[:, :, c].ravel() @ form @ net[:, :, c].ravel() for c in range(3))
    assert math.isclose(float(got), want, rel_tol=1e-11)


def test_certified_optimum_over_both_directions():
    res = lb.optimal_parameters(NET, "membrane", family=(TRIG, "same_degree"))
    assert sorted(res.parameters) == ["lam_u", "lam_v", "mu_u"] and res.certified
    assert all(isinstance(x, F) for x in res.parameters.values())
    at = TRIG.surface(
        NET,
        params_u={"lam": res["lam_u"], "mu": res["mu_u"]},
        lam_v=res["lam_v"],
        family_v="same_degree",
        check_range=False,
    )
    assert lb.surface_energy(at, "membrane") == res.energy  # exact, at the point it names
    assert float(res.energy - res.lower_bound) <= 1e-12 * float(res.energy)
    for lam_u, mu_u, lam_v in ((0, 0, 0), (1, -1, F(1, 2)), (-1, 1, -1)):
        other = TRIG.surface(
            NET, params_u={"lam": lam_u, "mu": mu_u}, lam_v=lam_v, family_v="same_degree"
        )
        assert float(lb.surface_energy(other, "membrane")) >= float(res.lower_bound)


def test_batch_optimum_agrees_with_each_nets_certified_minimum():
    at = lb.load_family(DATA + "at_cubic.toml")
    nets = np.random.default_rng(5).normal(size=(6, 4, 4, 3))
    got = lb.optimal_parameters(nets, "thin_plate", family=(at, "bernstein_like"))
    for i in (0, 3):
        one = lb.optimal_parameters(nets[i], "thin_plate", family=(at, "bernstein_like"))
        surf = at.surface(
            nets[i],
            params_u={"lam": F(float(got["lam_u"][i]))},
            lam_v=F(float(got["lam_v"][i])),
            family_v="bernstein_like",
            check_range=False,
        )
        attained = float(lb.surface_energy(surf, "thin_plate"))
        assert abs(attained - got.energy[i]) <= 1e-11 * abs(attained)
        assert float(one.lower_bound) - 1e-12 * attained <= attained
        assert attained <= float(one.energy) * (1 + 1e-12)


# ---------------------------------------------------------------------- joins and export
@pytest.mark.parametrize(
    ("side", "continuity", "rest", "params"),
    [
        ("u", "C1", [[(4 + k, j, 0) for j in range(4)] for k in range(2)], {"lam": 0, "mu": 0}),
        ("u", "C2", [[(4, j, 0) for j in range(4)]], {"lam": 0, "mu": 0}),
        ("v", "C1", [[(i, 4 + k, 0) for k in range(2)] for i in range(4)], {"lam": F(1, 2)}),
        ("v", "C2", [[(i, 4, 0)] for i in range(4)], {"lam": F(1, 2)}),
    ],
)
def test_join_surface_and_report_across_either_direction(side, continuity, rest, params):
    s = mixed_surface()
    b = lb.join_surface(s, side, continuity, 3, rest=rest, params=params)
    assert b.family == s.family
    grid = [[s], [b]] if side == "u" else [[s, b]]
    assert [r.continuity for r in lb.CompositeSurface(grid).report()] == [continuity]
    # the cross derivatives agree along the boundary (the patches' own parameters)
    order = 2 if continuity == "C2" else 1
    for x in (0.1, 0.5):
        for r in range(order + 1):
            if side == "u":
                a_, b_ = s.derivative(math.pi / 2, x, r, 0), b.derivative(0.0, x, r, 0)
            else:
                a_, b_ = s.derivative(x, 1.0, 0, r), b.derivative(x, 0.0, 0, r)
            assert np.allclose(a_, b_, atol=1e-11)


def test_json_round_trip_is_exact():
    s = mixed_surface()
    back = se.surface_from_json(se.surface_to_json(s), family=TRIG)
    assert back.family == s.family and back.parameters() == s.parameters()
    assert back.control_net() == s.control_net()
    assert np.array_equal(back.evaluate(0.3, 0.4), s.evaluate(0.3, 0.4))


def test_step_export_read_back_by_occt(tmp_path):
    s = mixed_surface()
    path = se.to_step_surface(s, tmp_path / "mixed.step")
    surf = occt_surface(path)
    for u, v in ((0.1, 0.2), (1.0, 0.4), (0.7, 1.0)):
        p = surf.Value(float(s.s_of_t(0, u)), v)
        assert np.allclose([p.X(), p.Y(), p.Z()], s.evaluate(u, v), atol=1e-12)
