"""Certified bounding box and closest point of a surface with a mixed (algebraic-trigonometric)
family in one direction and a polynomial family in the other, in either order (issues #30,
#31): hazmat.atom_surface_bounds with the polynomial direction written over the powers of
t − 1/2 (`bernstein_direction`). The references are independent of that form: the surface in
mpmath (40 digits) from the atom direction's exact atom coefficients and the polynomial
direction's Bernstein coefficients (its derivatives by the hodograph, its values by the
Bernstein polynomials), checked against the surface's own evaluation, and its extremes found
by Newton in mpmath from the best points of a dense grid (tests/test_atom_surface_bounds.py).
Nets: random, flat and degenerate, in dimensions 1, 2 and 3, float and exact; queries random,
on the surface, far away and at the corners."""

from __future__ import annotations

from fractions import Fraction as F
from math import comb

import mpmath as mp
import numpy as np
import pytest
from conftest import examples_per_profile
from hypothesis import example, given, settings
from hypothesis import strategies as st
from surface_box_check import check_box as shared_check_box
from test_atom_surface_bounds import (
    GRID,
    PINNED_NET,
    SHAPES,
    U_ONLY_NET,
    MpSurface,
    _net,
    coordinate_f,
    distance_f,
    reference_min,
)

import lambda_bezier as lb
from lambda_bezier import _poly_direction as pd
from lambda_bezier import examples
from lambda_bezier.atom_surfaces import AtomSurface
from lambda_bezier.hazmat import atom_bounds as ab
from lambda_bezier.hazmat import atom_surface_bounds as asb
from lambda_bezier.param_surfaces import family_surface

TOL = 1e-12
TWO = lb.load_family(examples.path("two_shape_cubic.toml"))
# the polynomial directions: built-in one-parameter families, the classical Bézier, and a
# family from load_family in two parameters (the names of its parameters, by position)
POLY = (
    ("same_degree", ("lam",)),
    ("bernstein_like", ("lam",)),
    ("bezier", ()),
    (TWO, ("lam", "mu")),
)


# ------------------------------------------------------------------------------ references
def _mp_bernstein(rows, t: mp.mpf, order: int) -> list[mp.mpf]:
    """b_i^(order)(t) of b_i = Σ_k B_ik B_k^N(t): the order-th hodograph's coefficients (exact
    differences of the Fractions or floats) against the Bernstein polynomials of degree N −
    order, in mpmath."""
    coeffs = [[mp.mpf(F(x).numerator) / F(x).denominator for x in row] for row in rows]
    big = len(coeffs[0]) - 1
    for j in range(order):
        coeffs = [
            [(big - j) * (b - a) for a, b in zip(row, row[1:], strict=False)] for row in coeffs
        ]
    deg = big - order
    if deg < 0:
        return [mp.mpf(0)] * len(rows)
    basis = [comb(deg, k) * t**k * (1 - t) ** (deg - k) for k in range(deg + 1)]
    return [mp.fsum(c * b for c, b in zip(row, basis, strict=True)) for row in coeffs]


class MpMixedSurface(MpSurface):
    """The surface in mpmath: the atom direction as in MpSurface (its exact atom basis), the
    polynomial direction from its Bernstein form."""

    def __init__(self, s: AtomSurface) -> None:
        super().__init__(s)
        self.rows = [p.bernstein() if isinstance(p, pd.PolyProbe) else None for p in s._probes]

    def _basis(self, axis: int, t, order: int) -> list[mp.mpf]:
        if self.rows[axis] is not None:
            return _mp_bernstein(self.rows[axis], mp.mpf(t), order)
        from test_atom_certified_geometry import mp_curve

        return mp_curve(self.s._probes[axis], t, order)

    def __call__(self, u, v, a: int = 0, b: int = 0) -> list[mp.mpf]:
        bu, bv = self._basis(0, u, a), self._basis(1, v, b)
        return [
            mp.fsum(
                bu[i] * bv[j] * self.net[i][j][c] for i in range(len(bu)) for j in range(len(bv))
            )
            for c in range(self.dim)
        ]


def _grid(s: AtomSurface, ref: MpMixedSurface) -> np.ndarray:
    """The dense grid the references start from, after checking that the mpmath surface is
    the surface (a few grid points against its own evaluation)."""
    us, vs = np.linspace(*s.domain_u, GRID), np.linspace(*s.domain_v, GRID)
    grid = s.evaluate_grid(us, vs)
    size = max(float(np.abs(s.net).max()), 1e-300)
    for i, j in ((0, 0), (GRID - 1, 7), (13, GRID - 1), (20, 29)):
        want = [float(x) for x in ref(*ref.grid_point(i, j))]
        assert np.allclose(grid[i, j], want, rtol=0, atol=1e-13 * size)
    return grid


def surface(atom, poly: int, raw, lams, atom_in_u: bool, shape="random", dim=3) -> AtomSurface:
    """The atom family's surface across POLY[poly] (in v, or in u when not atom_in_u) on the
    net `_net(raw, shape)` cut to `dim` coordinates (or on `raw` itself, a net)."""
    net = raw if shape is None else _net(raw, shape)[:, :, :dim]
    fam, names = POLY[poly]
    params = dict(zip(names, lams[1:], strict=False))
    atom_params = {"lam": lams[0]}
    if atom_in_u:
        s = family_surface(net, (atom, fam), params_u=atom_params, params_v=params)
    else:
        s = family_surface(net, (fam, atom), params_u=params, params_v=atom_params)
    assert isinstance(s, AtomSurface) and not s._has_form()
    return s


# ------------------------------------------------------------------------------ the box
def check_box(s: AtomSurface) -> None:
    """surface_box_check.check_box against this file's reference (the polynomial direction
    from its Bernstein form)."""
    ref = MpMixedSurface(s)

    def extreme(c: int, sign: int, values: np.ndarray) -> mp.mpf:
        return reference_min(ref, coordinate_f(c, sign), values)

    shared_check_box(s, _grid(s, ref), extreme)


nets = st.lists(st.floats(-3, 3), min_size=48, max_size=48)
lams = st.tuples(st.floats(0, 0.9), st.floats(-0.9, 0.9), st.floats(-0.9, 0.9))
pairs = st.tuples(st.integers(0, 1), st.integers(0, len(POLY) - 1), st.booleans())


@settings(max_examples=examples_per_profile(8, 40), deadline=None)
@given(nets, lams, pairs, st.sampled_from(SHAPES), st.integers(1, 3))
@example(PINNED_NET, (0.0, 0.0, 0.0), (0, 0, True), "random", 3)
@example(U_ONLY_NET, (0.5, 0.25, -0.5), (1, 1, False), "u_only", 3)
@example(U_ONLY_NET, (0.5, 0.25, 0.5), (0, 3, True), "v_only", 2)
@example(U_ONLY_NET, (0.25, 0.5, 0.0), (1, 2, False), "plane", 3)
@example(U_ONLY_NET, (0.25, 0.5, 0.0), (0, 0, False), "point", 1)
def test_box_is_certified_and_tight(at_family, at_pi_family, raw, lam, pair, shape, dim):
    """Each bound holds the extreme found by mpmath and is within max(1e-12 × size, the
    rounding floor) of it, in both orders, on random, flat and degenerate nets, d = 1..3."""
    atom = (at_family, at_pi_family)[pair[0]]
    check_box(surface(atom, pair[1], raw, lam, pair[2], shape, dim))


@pytest.mark.parametrize("atom_in_u", [True, False])
def test_exact_net_and_parameters_and_constant_coordinates(at_pi_family, atom_in_u):
    """An exact net at exact parameters: a constant coordinate is that constant exactly (both
    bases sum to one exactly), one depending on one direction only ends in a few rounds, and
    the others are certified as above."""
    net = [[(F(5, 2), F(i, 3), F(j * j, 4) - F(i * j, 5)) for j in range(4)] for i in range(4)]
    s = surface(at_pi_family, 0, net, (F(1, 2), F(1, 3)), atom_in_u, None)
    assert s.is_exact
    data = s._surface_data()
    assert data.unity
    stats = ab.Stats()
    *_, lo, hi = asb.coordinate_extremes(data, TOL, stats)
    assert lo[0] == hi[0] == 2.5
    assert stats.narrow == 0
    check_box(s)


def test_polynomial_direction_over_powers_is_its_basis():
    """bernstein_direction's powers of t − 1/2 give the polynomial basis and its derivatives
    (against the curve class's own evaluation), and say whether the basis sums to one."""
    probe = pd.PolyProbe(pd.polynomial_family("bernstein_like"), {"lam": F(1, 3)}, 4, True)
    data, unity = asb.bernstein_direction(probe.bernstein())
    assert unity
    t = np.linspace(0, 1, 33)
    for order in range(4):
        want = probe.basis(t, order)
        got = data.values(order, t - 0.5).T
        assert np.allclose(got, want, rtol=0, atol=1e-13)
    lo, hi = data.enclose(0, t[:-1] - 0.5, t[1:] - 0.5)
    fine = np.linspace(0, 1, 3201)
    vals = probe.basis(fine, 0)
    for k in range(32):
        inside = vals[100 * k : 100 * k + 101]
        assert (lo[:, k] <= inside.min(axis=0)).all() and (inside.max(axis=0) <= hi[:, k]).all()
    # a basis that does not sum to one is not taken for one
    rows = [[F(1), F(1, 2)], [F(0), F(1, 3)]]
    assert not asb.bernstein_direction(rows)[1]


# ------------------------------------------------------------------------------ closest point
def check_closest(s: AtomSurface, q: np.ndarray) -> None:
    data = s._surface_data()
    stats = ab.Stats()
    asb.closest(data, q, TOL, stats)
    assert stats.narrow == 0
    cp = s.closest_point(q)
    assert all(np.isfinite(x).all() for x in (cp.u, cp.v, cp.point, cp.distance, cp.lower_bound))
    ref = MpMixedSurface(s)
    d2 = ((_grid(s, ref) - q) ** 2).sum(axis=-1)
    exact = float(mp.sqrt(reference_min(ref, distance_f(q), d2)))
    size = data.size() + float(np.abs(q).max())
    allowed = max(TOL * size, float(data.floor().max())) + 1e-14 * size
    assert cp.distance <= exact + allowed  # the global minimum, within the tolerance
    assert cp.lower_bound <= exact + 1e-14 * size  # never above the distance
    assert 0 <= cp.distance - cp.lower_bound <= allowed
    (ua, ub), (va, vb) = s.domain_u, s.domain_v
    assert ua <= cp.u <= ub and va <= cp.v <= vb
    assert np.allclose(s.evaluate(cp.u, cp.v), cp.point, rtol=0, atol=1e-13 * size)


QUERIES = ("random", "on", "far", "corner")


def _query(s: AtomSurface, kind: str, xs, at) -> np.ndarray:
    (ua, ub), (va, vb) = s.domain_u, s.domain_v
    u, v = ua + at[0] * (ub - ua), va + at[1] * (vb - va)
    xs = np.array(xs[: s.dimension])
    if kind == "on":
        return np.asarray(s.evaluate(u, v))
    if kind == "far":
        return 1e3 * xs + 1.0
    if kind == "corner":  # a corner, pushed away from the surface
        corner = s.evaluate(ua if at[0] < 0.5 else ub, va if at[1] < 0.5 else vb)
        return np.asarray(corner) + 0.25 * xs
    return xs


@settings(max_examples=examples_per_profile(8, 40), deadline=None)
@given(
    nets,
    lams,
    pairs,
    st.sampled_from(SHAPES),
    st.integers(1, 3),
    st.sampled_from(QUERIES),
    st.lists(st.floats(-4, 4), min_size=3, max_size=3),
    st.tuples(st.floats(0, 1), st.floats(0, 1)),
)
@example(PINNED_NET, (0.0, 0.0, 0.0), (0, 0, True), "random", 3, "random", [0.5] * 3, (0, 0))
@example(U_ONLY_NET, (0.5, 0.25, 0.5), (1, 3, False), "u_only", 3, "on", [0.0] * 3, (0.3, 0.6))
@example(U_ONLY_NET, (0.5, 0.2, 0.0), (0, 1, True), "plane", 2, "corner", [1, -1, 1], (1, 0))
@example(U_ONLY_NET, (0.5, 0.2, 0.0), (1, 2, True), "point", 3, "far", [1, 2, 3], (0, 0))
@example(U_ONLY_NET, (0.1, 0.7, 0.0), (0, 0, False), "random", 1, "on", [0, 0, 0], (0.7, 0.2))
def test_closest_point_is_the_global_minimum(
    at_family, at_pi_family, raw, lam, pair, shape, dim, kind, xs, at
):
    """The distance is within max(1e-12 × size, the floor) of the global minimum found by
    mpmath and the certified lower bound is never above it, in both orders, for queries at
    random, on the surface, far away and beyond a corner, d = 1..3."""
    atom = (at_family, at_pi_family)[pair[0]]
    s = surface(atom, pair[1], raw, lam, pair[2], shape, dim)
    check_closest(s, _query(s, kind, xs, at))


@pytest.mark.parametrize("atom_in_u", [True, False])
def test_on_the_surface_and_a_batch(at_family, atom_in_u):
    """A point of the surface is found at distance ~0 at its parameters; a batch gives the
    answers of one query at a time."""
    rng = np.random.default_rng(31)
    s = surface(at_family, 1, rng.normal(size=48), (0.5, -0.5), atom_in_u)
    u, v = (0.7, 0.4) if atom_in_u else (0.4, 0.7)
    on = s.evaluate(u, v)
    cp = s.closest_point(on)
    assert cp.distance < 1e-11 and cp.lower_bound <= cp.distance
    assert abs(cp.u - u) < 1e-6 and abs(cp.v - v) < 1e-6
    qs = np.vstack([on, on + 1.0, on - [0.5, 2.0, 0.0], 100 * on])
    batch = s.closest_point(qs)
    for k, q in enumerate(qs):
        one = s.closest_point(q)
        assert abs(batch.distance[k] - one.distance) <= 1e-12 * max(1.0, one.distance)
        assert batch.lower_bound[k] <= batch.distance[k]


def test_the_polynomial_direction_on_the_dense_grid(at_pi_family):
    """A box against dense sampling with the certified margin, for a quintic polynomial
    direction (bernstein_like, degree 5) across the mixed cubic: every sampled point lies in
    the box, and each bound is within the margin of the sampled extreme plus the grid's
    reach."""
    rng = np.random.default_rng(5)
    net = rng.normal(size=(4, 6, 3))
    s = at_pi_family.surface(net, params_u={"lam": 0.5}, lam_v=F(1, 4), family_v="bernstein_like")
    lo, hi = s.bounding_box()
    data = s._surface_data()
    margin = max(TOL * data.size(), float(data.floor().max()))
    dense = s.evaluate_grid(np.linspace(*s.domain_u, 401), np.linspace(*s.domain_v, 401))
    dense = dense.reshape(-1, 3)
    assert (lo <= dense.min(axis=0) + margin).all() and (dense.max(axis=0) - margin <= hi).all()
    assert np.allclose(lo, dense.min(axis=0), atol=1e-4) and np.allclose(
        hi, dense.max(axis=0), atol=1e-4
    )


@pytest.mark.parametrize("poly", [None, "same_degree"])
def test_a_level_curve_in_one_dimension_ends_certified(at_family, poly):
    """In one dimension a query inside the surface's range is at distance 0 on a whole level
    curve S = q, where no cell is ever narrow (|S − q|² is ~ |∇S|² h² wide on a cell of size
    h): the value test settles those cells. Before it, this search ended at its cell limit
    with 46,510 cells settled uncertified (two atom directions, 5 s)."""
    rng = np.random.default_rng(3)
    net = rng.normal(size=(4, 4, 1))
    if poly is None:
        s = at_family.surface(net, params_u={"lam": 0.5}, params_v={"lam": 0.2})
    else:
        s = at_family.surface(net, params_u={"lam": 0.5}, lam_v=F(1, 3), family_v=poly)
    q = s.evaluate(0.7, 0.6)
    stats = ab.Stats()
    asb.closest(s._surface_data(), np.atleast_2d(q), TOL, stats)
    assert stats.narrow == 0 and stats.rounds < 10
    cp = s.closest_point(q)
    assert cp.lower_bound <= cp.distance <= TOL * (float(np.abs(net).max()) + abs(q[0]))
