"""Certified boxes and closest points of mixed (algebraic-trigonometric) curves, which have no
rational form (issue #30): hazmat.atom_bounds against mpmath at 40 digits, the enclosures
checked point by point, and an adversarial curve whose box the former fixed sampling grid got
wrong (two derivative roots inside one grid step at the end of the domain)."""

from __future__ import annotations

from fractions import Fraction as F

import mpmath as mp
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from test_trig_runtime import DATA

from lambda_bezier import _atom_geometry as ag
from lambda_bezier.hazmat import atom_bounds as ab
from lambda_bezier.hazmat import atoms as ak

AT = DATA / "at_cubic.toml"
AT_PI = DATA / "at_pi_cubic.toml"
mp.mp.dps = 40


# ------------------------------------------------------------------------------ references
def _mp_atom(atom: ak.Atom, t: mp.mpf, order: int) -> mp.mpf:
    """d^order/dt^order of one atom at t, in mpmath."""
    if atom.kind == "1":
        return mp.mpf(1) if order == 0 else mp.mpf(0)
    if atom.kind == "t":
        k = atom.power
        return mp.ff(k, order) * t ** (k - order) if order <= k else mp.mpf(0)
    w = mp.mpf(atom.omega.numerator) / atom.omega.denominator * (mp.pi if atom.pi else 1)
    # the k-th derivative of cos is cos(x + k pi/2): cos, -sin, -cos, sin, ...; sin is its
    # third entry (sin, cos, -sin, -cos, ...)
    cycle = [mp.cos, lambda x: -mp.sin(x), lambda x: -mp.cos(x), mp.sin]
    start = {"cos": 0, "sin": 3}[atom.kind]
    return w**order * cycle[(start + order) % 4](w * t)


def mp_curve(curve, t, order: int = 0) -> list[mp.mpf]:
    """The curve's order-th derivative at t from its exact basis and the atoms, in mpmath."""
    t = mp.mpf(t)
    atoms = [_mp_atom(a, t, order) for a in curve.shape.atoms]
    basis = [
        mp.fsum(mp.mpf(c.numerator) / c.denominator * a for c, a in zip(row, atoms, strict=True))
        for row in curve.basis_coefficients
    ]
    return [
        mp.fsum(b * mp.mpf(float(p)) for b, p in zip(basis, curve.points[:, c], strict=True))
        for c in range(curve.dimension)
    ]


def mp_box(curve, count: int = 400):
    """Every coordinate's extremes: a dense grid, each sign change of the derivative refined
    by mpmath's root finder (smooth random curves: no two roots in one step)."""
    lo, hi = curve.domain
    ts = [mp.mpf(lo) + (mp.mpf(hi) - lo) * k / count for k in range(count + 1)]
    ts[-1] = mp.pi / 2 if abs(hi - float(mp.pi / 2)) < 1e-15 else mp.mpf(hi)
    out = []
    for c in range(curve.dimension):
        cand = [ts[0], ts[-1]]
        d = [mp_curve(curve, t, 1)[c] for t in ts]
        for i in range(count):
            if d[i] * d[i + 1] < 0:
                cand.append(
                    mp.findroot(
                        lambda x, c=c: mp_curve(curve, x, 1)[c], (ts[i], ts[i + 1]), "illinois"
                    )
                )
        vals = [mp_curve(curve, t)[c] for t in cand]
        out.append((min(vals), max(vals)))
    return out


def mp_closest(curve, q, count: int = 400) -> mp.mpf:
    lo, hi = curve.domain
    q = [mp.mpf(float(x)) for x in q]

    def dist2(t):
        return mp.fsum((a - b) ** 2 for a, b in zip(mp_curve(curve, t), q, strict=True))

    def slope(t):
        p, d = mp_curve(curve, t), mp_curve(curve, t, 1)
        return mp.fsum((a - b) * e for a, b, e in zip(p, q, d, strict=True))

    ts = [mp.mpf(lo) + (mp.mpf(hi) - lo) * k / count for k in range(count + 1)]
    cand = [ts[0], ts[-1]]
    g = [slope(t) for t in ts]
    for i in range(count):
        if g[i] < 0 <= g[i + 1]:
            cand.append(mp.findroot(slope, (ts[i], ts[i + 1]), "illinois"))
    return min(dist2(t) for t in cand)


def _size(curve) -> float:
    return float(np.abs(curve.points).max())


# ------------------------------------------------------------------------------ enclosures
@settings(max_examples=40)
@given(
    st.integers(0, 3),
    st.integers(1, 4),
    st.booleans(),
    st.lists(st.floats(-4, 4), min_size=24, max_size=24),
    st.floats(-2, 1.5),
    st.floats(1e-6, 1.0),
    st.integers(0, 3),
)
def test_enclosures_hold_at_every_point(powers, harmonics, hyperbolic, raw, left, width, k):
    """The enclosure of the k-th derivative on [lo, hi] holds at 33 points of it, each the
    exact (mpmath) value of the float coefficients' curve."""
    size = 1 + powers + 2 * harmonics
    coeffs = np.array(raw[:size] + [0.0] * (size - len(raw[:size]))).reshape(size, 1)
    data = ab.AtomCurveData(coeffs, 0.75, powers, harmonics, hyperbolic)
    lo, hi = left, left + width
    low, high = data.enclose(k, np.array([lo]), np.array([hi]))
    g = data.order(k)[:, 0]
    w = mp.mpf(0.75)
    for x in np.linspace(lo, hi, 33):
        t = mp.mpf(float(x))
        vals = [mp.mpf(1)] + [t**p for p in range(1, powers + 1)]
        for j in range(1, harmonics + 1):
            pair = (mp.cosh, mp.sinh) if hyperbolic else (mp.cos, mp.sin)
            vals += [pair[0](j * w * t), pair[1](j * w * t)]
        exact = mp.fsum(mp.mpf(float(c)) * v for c, v in zip(g, vals, strict=True))
        assert low[0, 0] <= exact <= high[0, 0], (x, exact, low, high)


def test_enclosures_tighten_with_the_interval():
    """Halving the interval shrinks the enclosure (what the branch and bound relies on)."""
    data = ab.AtomCurveData(np.array([[1.0], [0.5], [2.0], [-1.0]]), 1.0, 1, 1, False)
    widths = []
    for h in (0.4, 0.2, 0.1, 0.05):
        low, high = data.enclose(0, np.array([0.3 - h]), np.array([0.3 + h]))
        widths.append(float(high[0, 0] - low[0, 0]))
    assert all(b < 0.6 * a for a, b in zip(widths, widths[1:], strict=False))


# ------------------------------------------------------------------------------ boxes
@settings(max_examples=12)
@given(
    st.lists(st.floats(-10, 10), min_size=8, max_size=8),
    st.sampled_from([F(-1), F(-1, 2), F(1, 3), F(1)]),
    st.booleans(),
)
def test_box_matches_mpmath(at_family, at_pi_family, raw, lam, pi_family):
    fam = at_pi_family if pi_family else at_family
    if pi_family:
        lam = abs(lam) if abs(lam) < 1 else F(0)  # at_pi_cubic: lam in [0, 1)
    curve = fam.curve(np.array(raw).reshape(4, 2), lam=lam)
    lo, hi = curve.bounding_box()
    tol = 1e-14 * max(_size(curve), 1e-300)
    for c, (want_lo, want_hi) in enumerate(mp_box(curve)):
        assert abs(lo[c] - float(want_lo)) <= tol
        assert abs(hi[c] - float(want_hi)) <= tol


def test_box_is_certified_without_settling_by_middles(at_family):
    curve = at_family.curve([(0, 0), (1, 3), (3, -2), (4, 1)], lam=F(1, 2))
    data = ag._bounds_data(curve)
    stats = ab.Stats()
    lo, hi = curve.domain
    ab.coordinate_extremes(data, lo - curve._mid, hi - curve._mid, stats)
    assert stats.narrow == 0 and stats.intervals < 400


def _adversarial(fam):
    """x(t) = -(sin(t - phi) - t cos(delta)), y = t on [0, pi/2]: x' = -(cos(t - phi) -
    cos(delta)) < 0 only between its roots phi -+ delta, both inside the last step of the
    former 64-points-per-piece grid; x's maximum is at the first root (inside the domain),
    not at the end."""
    lam = F(1, 2)
    basis = np.array(fam.curve(np.eye(4), lam=lam).basis_coefficients, dtype=float)
    hi = np.pi / 2
    delta, r2 = 0.0025, hi - 1e-5
    phi = r2 - delta
    ax = [0.0, np.cos(delta), np.sin(phi), -np.cos(phi)]  # atoms 1, t, cos t, sin t
    ay = [0.0, 1.0, 0.0, 0.0]
    points = np.linalg.solve(basis.T, np.array([ax, ay]).T)
    curve = fam.curve(points, lam=lam)
    top = -(mp.sin(mp.mpf(phi) - delta - phi) - (mp.mpf(phi) - delta) * mp.cos(delta))
    return curve, float(top), phi - delta


def _former_box(curve, samples: int = 64):
    """The box as _atom_geometry computed it before: sign changes of x' on a fixed grid of
    `samples` points per polynomial piece, each refined by bisection."""
    lo, hi = curve.domain
    t = np.linspace(lo, hi, len(ag.pieces(curve)) * samples + 1)
    d = curve.derivative(t, 1)
    cands = [lo, hi]
    for c in range(curve.dimension):
        col = d[:, c]
        for i in np.nonzero(np.sign(col[:-1]) * np.sign(col[1:]) < 0)[0]:
            a, b = float(t[i]), float(t[i + 1])
            fa = col[i]
            for _ in range(200):
                m = 0.5 * (a + b)
                fm = float(curve.derivative(m, 1)[c])
                if (fm > 0) == (fa > 0):
                    a, fa = m, fm
                else:
                    b = m
            cands.append(0.5 * (a + b))
    v = curve.evaluate(np.array(cands))
    return v.min(axis=0), v.max(axis=0)


def test_adversarial_box_the_grid_missed(at_family):
    curve, top, where = _adversarial(at_family)
    step = (np.pi / 2) / (len(ag.pieces(curve)) * 64)
    assert np.pi / 2 - step < where  # both roots of x' inside the grid's last step
    assert float(mp_curve(curve, mp.mpf(where))[0]) == pytest.approx(top, abs=1e-13)
    former = _former_box(curve)[1][0]
    assert top - former > 1e-9  # the grid missed the maximum by about 1e-8
    assert abs(curve.bounding_box()[1][0] - top) <= 1e-14


def test_closest_point_at_the_adversarial_maximum(at_family):
    """Far out along +x at the height of the hidden maximum, the nearest point is there."""
    curve, top, where = _adversarial(at_family)
    q = np.array([50.0, where])
    got = curve.closest_point(q)
    assert abs(got.t - where) < 1e-6
    assert got.distance**2 == pytest.approx(float(mp_closest(curve, q)), rel=1e-13)


# ------------------------------------------------------------------------------ closest points
@settings(max_examples=12)
@given(
    st.lists(st.floats(-10, 10), min_size=8, max_size=8),
    st.lists(st.floats(-12, 12), min_size=2, max_size=2),
    st.sampled_from([F(-1), F(0), F(1, 3), F(1)]),
)
def test_closest_point_matches_mpmath(at_family, raw, q, lam):
    curve = at_family.curve(np.array(raw).reshape(4, 2), lam=lam)
    got = curve.closest_point(q)
    want = float(mp.sqrt(mp_closest(curve, q)))
    assert abs(got.distance - want) <= 1e-13 * max(_size(curve), abs(max(q, key=abs)), 1.0)
    assert np.allclose(got.point, curve.evaluate(got.t))


def test_closest_point_batch_and_stats(at_pi_family):
    curve = at_pi_family.curve([(0, 0), (1, 2), (2, -1), (3, 1)], lam=F(1, 4))
    qs = np.array([[1.0, 1.0], [3.0, 3.0], [-1.0, 0.5]])
    batch = curve.closest_point(qs)
    for k, q in enumerate(qs):
        one = curve.closest_point(q)
        assert one.t == batch.t[k]
        assert one.distance == pytest.approx(batch.distance[k], rel=1e-15)
    data = ag._bounds_data(curve)
    stats = ab.Stats()
    lo, hi = curve.domain
    ab.closest(data, qs[0] / curve._scale, lo - curve._mid, hi - curve._mid, stats)
    assert stats.narrow == 0


def test_locate_on_a_mixed_curve(at_family):
    curve = at_family.curve([(0, 0), (1, 3), (3, -2), (4, 1)], lam=F(1, 2))
    t = 0.7310
    assert curve.locate(curve.evaluate(t)) == pytest.approx(t, abs=1e-9)
    assert curve.locate(curve.evaluate(t) + 0.01) is None
