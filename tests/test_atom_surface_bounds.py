"""Certified boxes and closest points of surfaces of mixed (algebraic-trigonometric) families,
which have no rational form (issue #30): hazmat.atom_surface_bounds against dense sampling
refined by Newton in mpmath (40 digits) from the exact basis, over random nets. Both test
families, at_cubic ({1, t, cos t, sin t}) and at_pi_cubic ({1, t, cos(πt/2), sin(πt/2)}), are
mixed."""

from __future__ import annotations

import mpmath as mp
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from test_atom_certified_geometry import mp_curve
from test_trig_runtime import DATA

import lambda_bezier as lb
from lambda_bezier.hazmat import atom_bounds as ab
from lambda_bezier.hazmat import atom_surface_bounds as asb

mp.mp.dps = 40
GRID = 61  # the dense grid of the references, refined by Newton


@pytest.fixture(scope="module")
def families():
    return lb.load_family(DATA / "at_cubic.toml"), lb.load_family(DATA / "at_pi_cubic.toml")


# ------------------------------------------------------------------------------ references
class MpSurface:
    """S^(a, b)(u, v) of the surface in mpmath, from each direction's exact basis (the
    probes: curves whose control points are the unit vectors) and the float net."""

    def __init__(self, s) -> None:
        self.s = s
        self.net = [[[mp.mpf(float(x)) for x in p] for p in row] for row in s.net]
        self.dim = s.dimension

    def __call__(self, u, v, a: int = 0, b: int = 0) -> list[mp.mpf]:
        bu = mp_curve(self.s._probes[0], u, a)
        bv = mp_curve(self.s._probes[1], v, b)
        return [
            mp.fsum(
                bu[i] * bv[j] * self.net[i][j][c] for i in range(len(bu)) for j in range(len(bv))
            )
            for c in range(self.dim)
        ]


def _mp_domain(lo: float, hi: float) -> tuple[mp.mpf, mp.mpf]:
    top = mp.pi / 2 if abs(hi - float(mp.pi / 2)) < 1e-15 else mp.mpf(hi)
    return mp.mpf(lo), top


def mp_refine(surface: MpSurface, f, u: float, v: float):
    """Newton in mpmath on the free derivatives of f(S, S_u, S_v, S_uu, S_uv, S_vv) -> (f,
    gradient, Hessian), from (u, v); a direction whose iterate leaves the domain is clamped to
    its end and fixed (the extreme is then on that edge). Returns f at the end point."""
    doms = [_mp_domain(*surface.s.domain_u), _mp_domain(*surface.s.domain_v)]
    x = [mp.mpf(u), mp.mpf(v)]
    free = [not (x[k] <= doms[k][0] or x[k] >= doms[k][1]) for k in range(2)]
    for _ in range(40):
        idx = [k for k in range(2) if free[k]]
        if not idx:
            break
        parts = [surface(x[0], x[1], a, b) for a, b in ((0, 0), (1, 0), (0, 1), (2, 0), (1, 1), (0, 2))]
        _, g, h = f(*parts)
        gs = mp.matrix([g[k] for k in idx])
        hs = mp.matrix([[h[k][m] for m in idx] for k in idx])
        try:
            step = mp.lu_solve(hs, gs)
        except ZeroDivisionError:
            break
        moved = False
        for n, k in enumerate(idx):
            new = x[k] - step[n]
            if new <= doms[k][0] or new >= doms[k][1]:
                new = doms[k][0] if new <= doms[k][0] else doms[k][1]
                free[k] = False
            moved = moved or abs(new - x[k]) > mp.mpf(10) ** -35
            x[k] = new
        if not moved:
            break
    parts = [surface(x[0], x[1], a, b) for a, b in ((0, 0), (1, 0), (0, 1), (2, 0), (1, 1), (0, 2))]
    return f(*parts)[0]


def coordinate_f(c: int, sign: int):
    def f(s, su, sv, suu, suv, svv):
        return (
            sign * s[c],
            [sign * su[c], sign * sv[c]],
            [[sign * suu[c], sign * suv[c]], [sign * suv[c], sign * svv[c]]],
        )

    return f


def distance_f(q):
    q = [mp.mpf(float(x)) for x in q]

    def f(s, su, sv, suu, suv, svv):
        r = [a - b for a, b in zip(s, q, strict=True)]

        def dot(a, b):
            return mp.fsum(x * y for x, y in zip(a, b, strict=True))

        return (
            dot(r, r),
            [2 * dot(r, su), 2 * dot(r, sv)],
            [
                [2 * (dot(su, su) + dot(r, suu)), 2 * (dot(su, sv) + dot(r, suv))],
                [2 * (dot(su, sv) + dot(r, suv)), 2 * (dot(sv, sv) + dot(r, svv))],
            ],
        )

    return f


def _grid(s):
    us, vs = np.linspace(*s.domain_u, GRID), np.linspace(*s.domain_v, GRID)
    return us, vs, s.evaluate_grid(us, vs)


def _surface(families, raw, lam_u, lam_v, pick):
    fam = families[pick]
    net = np.array(raw).reshape(4, 4, 3)
    return fam.surface(net, params_u={"lam": lam_u}, params_v={"lam": lam_v})


nets = st.lists(st.floats(-3, 3), min_size=48, max_size=48)
lams = st.floats(-0.9, 0.9)


# ------------------------------------------------------------------------------ the box
@settings(max_examples=8, deadline=None)
@given(nets, lams, lams, st.integers(0, 1))
def test_box_contains_the_surface_and_is_tight(families, raw, lam_u, lam_v, pick):
    """Every sampled point lies in the box; each bound is within the stated slack of the
    extreme found by the dense grid refined by Newton in mpmath (which is a value of the
    surface, so the bound may not be inside it either)."""
    s = _surface(families, raw, abs(lam_u), abs(lam_v), pick)
    data = s._surface_data()
    stats = ab.Stats()
    inner_lo, inner_hi, lo, hi = asb.coordinate_extremes(data, stats)
    assert stats.narrow == 0
    assert np.array_equal(np.array(s.bounding_box()), np.array([lo, hi]))
    us, vs, grid = _grid(s)
    flat = grid.reshape(-1, 3)
    assert (lo <= flat.min(axis=0)).all() and (hi >= flat.max(axis=0)).all()
    assert (lo <= inner_lo).all() and (inner_hi <= hi).all()
    slack = data.slack()
    ref = MpSurface(s)
    for c in range(3):
        for sign, bound in ((1, hi[c]), (-1, lo[c])):
            i, j = np.unravel_index(int(np.argmax(sign * grid[:, :, c])), grid.shape[:2])
            best = sign * mp_refine(ref, coordinate_f(c, sign), us[i], vs[j])
            # the refined extreme (exact) lies inside the box, the box within the slack of it
            assert sign * (bound - float(best)) >= -1e-15 * max(1.0, abs(bound))
            assert sign * (bound - float(best)) <= slack[c] + 1e-15 * max(1.0, abs(bound))


def test_box_of_a_constant_coordinate_and_a_plane(families):
    """Flat coordinates (the whole domain a critical set) end by the value test."""
    fam = families[1]
    net = np.zeros((4, 4, 3))
    net[:, :, 0] = 2.5
    net[:, :, 1] = np.arange(4)[:, None]
    net[:, :, 2] = np.arange(4)[None, :] * 0.5
    s = fam.surface(net, params_u={"lam": 0.25}, params_v={"lam": 0.5})
    stats = ab.Stats()
    *_, lo, hi = asb.coordinate_extremes(s._surface_data(), stats)
    assert stats.narrow == 0
    assert np.allclose(lo, [2.5, 0, 0], atol=1e-13) and np.allclose(hi, [2.5, 3, 1.5], atol=1e-13)
    assert (lo <= [2.5, 0, 0]).all() and (hi >= [2.5, 3, 1.5]).all()


# ------------------------------------------------------------------------------ closest point
@settings(max_examples=8, deadline=None)
@given(nets, lams, lams, st.integers(0, 1), st.lists(st.floats(-4, 4), min_size=3, max_size=3))
def test_closest_point_is_no_worse_than_refined_sampling(families, raw, lam_u, lam_v, pick, q):
    """The distance is at most the best grid point refined by Newton in mpmath (plus the
    stated slack), and the certified lower bound is below that exact value."""
    s = _surface(families, raw, abs(lam_u), abs(lam_v), pick)
    q = np.array(q)
    data = s._surface_data()
    stats = ab.Stats()
    u0, v0, best, lower = asb.closest(data, q, stats)
    assert stats.narrow == 0
    cp = s.closest_point(q)
    us, vs, grid = _grid(s)
    d2 = ((grid - q) ** 2).sum(axis=-1)
    i, j = np.unravel_index(int(np.argmin(d2)), d2.shape)
    ref = mp.sqrt(mp_refine(MpSurface(s), distance_f(q), us[i], vs[j]))
    tol = float(data.slack().max())
    allowed = 3 * tol + 1e-14 * max(1.0, float(ref))
    assert cp.distance <= float(ref) + allowed
    assert cp.lower_bound <= float(ref) + 1e-15 * max(1.0, float(ref))
    assert cp.distance - cp.lower_bound <= allowed
    (ua, ub), (va, vb) = s.domain_u, s.domain_v
    assert ua <= cp.u <= ub and va <= cp.v <= vb
    assert np.allclose(s.evaluate(cp.u, cp.v), cp.point, atol=1e-13)


def test_closest_point_on_the_surface_and_batch(families):
    """A point of the surface is found at distance ~0, at its parameters; a batch gives the
    same answers as one query at a time."""
    rng = np.random.default_rng(30)
    s = families[0].surface(rng.normal(size=(4, 4, 3)), params_u={"lam": 0.5}, params_v={"lam": -0.5})
    on = s.evaluate(0.7, 1.1)
    cp = s.closest_point(on)
    assert cp.distance < 1e-12 and cp.lower_bound <= cp.distance
    qs = np.vstack([on, on + 1.0, on - [0.5, 2.0, 0.0]])
    batch = s.closest_point(qs)
    for k, q in enumerate(qs):
        one = s.closest_point(q)
        assert np.isclose(batch.distance[k], one.distance, rtol=0, atol=1e-14)
