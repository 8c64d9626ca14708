"""Tangencies of exact rational curves decided exactly (issue #29): intersect_exact and
RationalBezierCurve.intersect on the cross-multiplied system X_p(s) W_q(t) − X_q(t) W_p(s):
a touching point reported once as "tangent", a near-tangency with no real contact not
reported, near-double crossings split; checked against SymPy (its own resultants of the
curves' rational functions, built here from the Bernstein form, and their real roots)."""

from __future__ import annotations

import random
from fractions import Fraction as F

import pytest
import sympy as sp
from exact_curves import point_and_tangent, reflect_line
from hypothesis import given, settings
from hypothesis import strategies as st

import lambda_bezier as lb
from lambda_bezier.hazmat import intersect_exact as ie

S, T = sp.symbols("s t")

# the unit circle's quarter x = (1 − u²)/(1 + u²), y = 2u/(1 + u²), u in [0, 1]
QUARTER = lb.RationalBezierCurve([(1, 0), (1, 1), (0, 1)], [1, 1, 2])


def q(c: F) -> sp.Rational:
    return sp.Rational(c.numerator, c.denominator)


def sp_rational(curve: lb.RationalBezierCurve, x: sp.Symbol) -> list[sp.Expr]:
    """(x(x), y(x)) of the rational Bézier curve, from its control points and weights."""
    rows, weights = curve.control_points(), curve.control_weights()
    n = len(rows) - 1
    basis = [sp.binomial(n, i) * x**i * (1 - x) ** (n - i) * q(F(w)) for i, w in enumerate(weights)]
    den = sum(basis)
    return [sum(b * q(F(r[c])) for b, r in zip(basis, rows, strict=True)) / den for c in (0, 1)]


def sympy_crossings(a: lb.RationalBezierCurve, b: lb.RationalBezierCurve):
    """Every common point (s, t) in [0, 1]² of the two curves, from SymPy: the numerators of
    a(s) − b(t), their resultants' real roots in [0, 1] paired where both numerators vanish
    (150 digits), each with |det J| of the numerators there relative to its coefficients
    (0 exactly at a tangency)."""
    pa, pb = sp_rational(a, S), sp_rational(b, T)
    fx, fy = (sp.expand(sp.numer(sp.together(u - v))) for u, v in zip(pa, pb, strict=True))
    s_roots = {r for r in sp.Poly(sp.resultant(fx, fy, T), S).real_roots() if 0 <= r <= 1}
    t_roots = {r for r in sp.Poly(sp.resultant(fx, fy, S), T).real_roots() if 0 <= r <= 1}
    det = sp.expand(sp.diff(fx, S) * sp.diff(fy, T) - sp.diff(fx, T) * sp.diff(fy, S))

    def scale(e):
        return max(abs(c) for c in sp.Poly(e, S, T).coeffs()) if e != 0 else 1

    f_scale, det_scale = max(scale(fx), scale(fy)), scale(det)
    out = []
    for s in sorted(s_roots, key=float):
        for t in sorted(t_roots, key=float):
            at = {S: sp.N(s, 150), T: sp.N(t, 150)}
            residual = max(abs(fx.evalf(150, subs=at)), abs(fy.evalf(150, subs=at)))
            if residual <= sp.Float(10, 150) ** -100 * f_scale:
                out.append((sp.N(s, 30), sp.N(t, 30), abs(det.evalf(150, subs=at)) / det_scale))
    return out


def assert_matches_sympy(a, b, hits):
    """hits (intersect's) are SymPy's crossings one for one, to 1e-15, "tangent" exactly where
    det J vanishes (below 1e-100 of its coefficients at 150 digits; above 1e-60 elsewhere)."""
    want = sympy_crossings(a, b)
    assert len(hits) == len(want), (hits, want)
    for h, (s, t, det) in zip(hits, want, strict=True):
        assert abs(h.s - float(s)) <= 1e-15 and abs(h.t - float(t)) <= 1e-15, (h, s, t)
        assert (h.kind == "tangent") == (det < 1e-100), (h, det)
        assert h.kind == "tangent" or det > 1e-60


def tangent_line(u0: F, offset: F) -> lb.BezierCurve:
    """The tangent line of QUARTER at u0 (its point P, a unit vector: the normal), moved by
    `offset` along it (outwards when positive), as a segment 2 long centred on P."""
    px, py = (1 - u0**2) / (1 + u0**2), 2 * u0 / (1 + u0**2)
    cx, cy = px * (1 + offset), py * (1 + offset)
    return lb.BezierCurve([(cx + py, cy - px), (cx - py, cy + px)])


def test_a_circle_touching_its_tangent_line():
    """The quarter circle touches its tangent line at (3/5, 4/5) (u = 1/2, t = 1/2 on the
    line): one certified tangent box holding (1/2, 1/2), and one "tangent" hit, from either
    side; the float curves' answer also says "tangent" there."""
    line = tangent_line(F(1, 2), F(0))
    (box,) = lb.intersect_exact(QUARTER, line)
    assert box.certified and box.tangent
    assert box.s[0] <= F(1, 2) <= box.s[1] and box.t[0] <= F(1, 2) <= box.t[1]
    assert QUARTER.intersect(line) == [(0.5, 0.5, "tangent")]
    assert [tuple(h) for h in line.intersect(QUARTER)] == [(0.5, 0.5, "tangent")]
    assert_matches_sympy(QUARTER, lb.RationalBezierCurve.from_bezier(line), QUARTER.intersect(line))


@pytest.mark.parametrize("gap", [F(1, 10**15), F(1, 10**20), F(1, 10**40)])
def test_a_circle_near_its_tangent_line(gap):
    """The tangent line moved out by gap meets the circle nowhere (SymPy: no real root);
    moved in, it crosses twice (two transversal hits, SymPy's), where the float answer of the
    exact input used to be one tangency (gap within the float tolerance)."""
    outside, inside = tangent_line(F(1, 2), gap), tangent_line(F(1, 2), -gap)
    assert lb.intersect_exact(QUARTER, outside) == []
    assert QUARTER.intersect(outside) == []
    assert sympy_crossings(QUARTER, lb.RationalBezierCurve.from_bezier(outside)) == []
    hits = QUARTER.intersect(inside)
    assert [h.kind for h in hits] == ["transversal", "transversal"]
    assert_matches_sympy(QUARTER, lb.RationalBezierCurve.from_bezier(inside), hits)
    boxes = lb.intersect_exact(QUARTER, inside)
    assert [(b.certified, b.tangent) for b in boxes] == [(True, False), (True, False)]


# ------------------------------------------------------------------ reflected tangencies


def reflected(rows, weights, t0: F, offset: F = F(0)) -> lb.RationalBezierCurve:
    """The rational curve reflected in its own tangent line at t0 (an affine map: it acts on
    the control points, the weights stay), moved by `offset` along the normal."""
    reflect = reflect_line(*point_and_tangent(rows, weights, t0), offset)
    return lb.RationalBezierCurve([reflect(v) for v in rows], weights)


@pytest.mark.parametrize(("n", "seed"), [(2, 0), (3, 1), (4, 2)])
def test_reflected_rational_tangencies(n, seed):
    """A random exact rational curve against its reflection in its tangent line at t0 = 7/23:
    touching at (t0, t0), "tangent" once; every crossing SymPy's; moved off by ±1e-20, no
    contact near t0 or two transversal crossings there (quartics: products of degrees 16)."""
    rnd = random.Random(seed)
    rows = [(F(rnd.randint(-9, 9)), F(rnd.randint(-9, 9))) for _ in range(n + 1)]
    weights = [F(rnd.randint(1, 4), rnd.randint(1, 3)) for _ in range(n + 1)]
    curve, t0 = lb.RationalBezierCurve(rows, weights), F(7, 23)
    hits = curve.intersect(reflected(rows, weights, t0))
    near = [h for h in hits if abs(h.s - float(t0)) < 1e-6]
    assert [(h.s, h.t, h.kind) for h in near] == [(float(t0), float(t0), "tangent")]
    assert_matches_sympy(curve, reflected(rows, weights, t0), hits)
    for offset in (F(1, 10**20), F(-1, 10**20)):
        moved = reflected(rows, weights, t0, offset)
        hits = curve.intersect(moved)
        assert_matches_sympy(curve, moved, hits)
        assert len([h for h in hits if abs(h.s - float(t0)) < 1e-6]) in (0, 2)


def test_rational_budget_without_flint(monkeypatch):
    """Without python-flint two rational cubics are past the budget (PURE: a product of
    degrees 4): the float answer stands (a tangent hit for the pair moved apart by 1e-20,
    which FLINT shows has no contact there)."""
    rnd = random.Random(1)
    rows = [(F(rnd.randint(-9, 9)), F(rnd.randint(-9, 9))) for _ in range(4)]
    weights = [F(rnd.randint(1, 4), rnd.randint(1, 3)) for _ in range(4)]
    curve, t0 = lb.RationalBezierCurve(rows, weights), F(7, 23)
    apart = [F(1, 10**20), F(-1, 10**20)]
    hits = {o: curve.intersect(reflected(rows, weights, t0, o)) for o in apart}
    (none_side,) = [o for o in apart if not any(abs(h.s - float(t0)) < 1e-6 for h in hits[o])]
    monkeypatch.setattr(ie, "algebra", lambda: ie.PURE)
    float_answer = curve.intersect(reflected(rows, weights, t0, none_side))
    assert [h.kind for h in float_answer if abs(h.s - float(t0)) < 1e-6] == ["tangent"]


# ------------------------------------------------------------------ hypothesis
@settings(max_examples=12, derandomize=True, deadline=None)
@given(
    st.fractions(F(1, 20), F(19, 20), max_denominator=30),
    st.sampled_from([0, 1, -1]),
    st.integers(12, 40),
)
def test_circle_against_lines_near_tangent(u0, side, digits):
    """Near-double crossings and near-tangencies on a conic: the quarter circle against its
    tangent line at u0 moved outwards (side 1: no contact), not at all (0: one "tangent" hit
    at (u0, 1/2) exactly) or inwards (−1: two transversal crossings), by 10^-digits; as SymPy
    says."""
    line = tangent_line(u0, F(side, 10**digits))
    hits = QUARTER.intersect(line)
    kinds = {1: [], 0: ["tangent"], -1: ["transversal", "transversal"]}[side]
    assert [h.kind for h in hits] == kinds
    if side == 0:
        assert [(h.s, h.t) for h in hits] == [(float(u0), 0.5)]
    assert_matches_sympy(QUARTER, lb.RationalBezierCurve.from_bezier(line), hits)


small = st.integers(-6, 6)


@settings(max_examples=6, derandomize=True, deadline=None)
@given(
    st.integers(2, 3).flatmap(
        lambda n: st.tuples(
            st.lists(st.tuples(small, small), min_size=n + 1, max_size=n + 1),
            st.lists(
                st.fractions(F(1, 2), F(3), max_denominator=4), min_size=n + 1, max_size=n + 1
            ),
        )
    ),
    st.fractions(F(1, 10), F(9, 10), max_denominator=20),
)
def test_reflected_tangencies_of_random_rational_curves(curve_data, t0):
    """Reflected tangencies of random exact rational conics and cubics: the touching point
    (t0, t0) is reported once as "tangent", at t0 rounded; every crossing SymPy's."""
    points, weights = curve_data
    rows = [(F(x), F(y)) for x, y in points]
    curve = lb.RationalBezierCurve(rows, weights)
    if point_and_tangent(rows, weights, t0)[1] == (0, 0):
        return  # a cusp or a point curve at t0: no tangent line
    mirror = reflected(rows, weights, t0)
    try:
        hits = curve.intersect(mirror)
    except ValueError as exc:  # the curve is a line, or symmetric about it: one component
        assert "stretch" in str(exc) or "line" in str(exc), exc
        return
    if any(h.kind == "coincident" for h in hits):
        return  # symmetric about its tangent line: the mirror is the same curve
    near = [h for h in hits if abs(h.s - float(t0)) < 1e-6 and abs(h.t - float(t0)) < 1e-6]
    assert [(h.s, h.t, h.kind) for h in near] == [(float(t0), float(t0), "tangent")]
    assert_matches_sympy(curve, mirror, hits)
