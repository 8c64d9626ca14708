"""Shared stretches of rational and trigonometric curves under any parameterisation
(hazmat.coincide, issue #29): a curve against its own Möbius reparameterisation, a piece of
it, its reversal, a trigonometric curve against its rational form, two pieces overlapping,
each reported by the stretch's two end pairs, "coincident", with the parameters known exactly
by construction; and curves that only nearly share one are not."""

from __future__ import annotations

import math
import sys
from fractions import Fraction as F
from pathlib import Path

import mpmath as mp
import numpy as np
import pytest
from hypothesis import assume, example, given, settings
from hypothesis import strategies as st

import lambda_bezier as lb
from lambda_bezier.hazmat import coincide as co

sys.path.insert(0, str(Path(__file__).parent))
from test_acceptance_29_classes import ATOM_PARAMS, _family  # noqa: E402

R = lb.RationalBezierCurve


def _inverse_mobius(rho: F, t: F) -> F:
    """The s of reparameterize(rho) at the original's t: t = rho s / ((1 − s) + rho s)."""
    return t / (rho + t - rho * t)


def _stretch(curve, other) -> list[tuple[float, float, str]]:
    got = curve.intersect(other)
    assert all(h.kind == "coincident" for h in got), got
    return [(h.s, h.t, h.kind) for h in got]


def _close(got, want, tol: float) -> None:
    assert len(got) == len(want), (got, want)
    for (gs, gt, gk), (ws, wt, wk) in zip(got, want, strict=True):
        assert abs(gs - ws) <= tol and abs(gt - wt) <= tol and gk == wk, (got, want)


points = st.lists(
    st.tuples(st.integers(-9, 9), st.integers(-9, 9)), min_size=3, max_size=5, unique=True
)


def _curved(pts) -> bool:
    """Not all on one line (a curve folding back along a line has no single stretch)."""
    (x0, y0), (x1, y1) = pts[0], pts[-1]
    return any((x1 - x0) * (y - y0) - (y1 - y0) * (x - x0) for x, y in pts[1:-1])


@settings(max_examples=8, deadline=None)
@given(
    pts=points,
    weights=st.lists(st.integers(1, 9), min_size=5, max_size=5),
    rho=st.builds(F, st.integers(1, 9), st.integers(1, 9)),
    cut=st.tuples(st.integers(0, 3), st.integers(5, 8)),
    reverse=st.booleans(),
)
@example(
    pts=[(0, 0), (1, 3), (3, -2), (4, 1)], weights=[1] * 5, rho=F(2), cut=(0, 8), reverse=False
)
@example(  # found by fuzzing: c crosses itself across the stretch's end (a real crossing)
    pts=[(-2, 0), (0, -4), (0, 0), (-3, -2)], weights=[1] * 5, rho=F(1), cut=(0, 5), reverse=False
)
def test_a_piece_against_a_mobius_reparameterisation_exact(pts, weights, rho, cut, reverse):
    """p = c over [a, b] (affine in c's t), q = c reparameterised by rho (and reversed): p
    lies on q from end to end, at q's t = φ⁻¹(a) and φ⁻¹(b), exactly known. Where c crosses
    itself with one branch inside [a, b] and the other outside, p and q cross there too,
    once (c's self-crossings located by its own engine)."""
    assume(_curved(pts))
    curve = R(pts, weights[: len(pts)])
    a, b = F(cut[0], 8), F(cut[1], 8)
    p = curve.segment(a, b) if (a, b) != (0, 1) else curve
    q = curve.reparameterize(rho)

    def on_q(u: float) -> float:
        v = u / (float(rho) + u - float(rho) * u)
        return 1 - v if reverse else v

    t0, t1 = _inverse_mobius(rho, a), _inverse_mobius(rho, b)
    if reverse:
        q, t0, t1 = q.reverse(), 1 - t0, 1 - t1
    ends = [(0.0, float(t0), "coincident"), (1.0, float(t1), "coincident")]
    extra = []
    for x in curve.self_intersections():
        for ua, ub in ((x.s, x.t), (x.t, x.s)):
            if a <= ua <= b and not a <= ub <= b:
                extra.append(((ua - float(a)) / float(b - a), on_q(ub), "transversal"))
    got = [(h.s, h.t, h.kind) for h in p.intersect(q)]
    _close([g for g in got if g[2] == "coincident"], ends, 1e-15)
    _close([g for g in got if g[2] != "coincident"], sorted(extra), 1e-9)
    back = [(h.s, h.t, h.kind) for h in q.intersect(p)]
    _close([g for g in back if g[2] == "coincident"], sorted((t, s, k) for s, t, k in ends), 1e-15)
    _close([g for g in back if g[2] != "coincident"], sorted((t, s, k) for s, t, k in extra), 1e-9)


@pytest.mark.parametrize("rho", [2.0, 0.3, 7.5])
def test_a_float_curve_against_its_float_reparameterisation(rho):
    """Float weights: decided to the rounding of evaluation (the polynomial path's rule)."""
    curve = R([(0, 0), (1, 3), (3, -2), (4, 1)], [1.0, 2.5, 0.5, 1.25])
    q = curve.reparameterize(rho)
    _close(_stretch(curve, q), [(0.0, 0.0, "coincident"), (1.0, 1.0, "coincident")], 1e-12)
    piece = curve.segment(0.25, 0.75)
    want = [(0.0, 0.25 / (rho + 0.25 - rho * 0.25), "coincident")]
    want.append((1.0, 0.75 / (rho + 0.75 - rho * 0.75), "coincident"))
    _close(_stretch(piece, q), want, 1e-12)


def test_two_pieces_that_overlap_and_cross_elsewhere():
    """c = a loop cubic; p = c over [0, 1/2] reparameterised by rho = 2, q = c over [1/4, 1]:
    they share c's [1/4, 1/2] (p's s from 1/3 to 1, q's t from 0 to 1/3), and cross once more
    where c crosses itself, at u = (1 ∓ √(3/5)) / 2."""
    loop = lb.BezierCurve([(0, 0), (4, 3), (-2, 3), (2, 0)])
    c = R.from_bezier(loop)
    p = c.segment(0, F(1, 2)).reparameterize(F(2))
    q = c.segment(F(1, 4), 1)
    mp.mp.dps = 50
    u1, u2 = (1 - mp.sqrt(mp.mpf(3) / 5)) / 2, (1 + mp.sqrt(mp.mpf(3) / 5)) / 2
    s_cross = float(2 * u1 / (2 + 2 * u1 - 2 * 2 * u1))  # φ⁻¹(2 u1) at rho = 2
    t_cross = float((u2 - mp.mpf(1) / 4) * 4 / 3)
    got = [(h.s, h.t, h.kind) for h in p.intersect(q)]
    want = [
        (s_cross, t_cross, "transversal"),
        (1 / 3, 0.0, "coincident"),
        (1.0, 1 / 3, "coincident"),
    ]
    _close(got, want, 1e-12)


@pytest.mark.parametrize("k", [1, 3])
def test_a_nearby_curve_shares_no_stretch(k):
    """A control point moved by 1e-12 (exact): not on the same algebraic curve, so the
    exact decision says no. Such curves stay within 1e-12 of each other all along, closer
    than the certified search resolves: the exact isolation (intersect_exact on the
    cross-multiplied system) answers, SymPy's crossings one for one (moving the second
    point: the common start, transversal, and the common end, where they touch; the fourth:
    the common start only, touching); as floats, refused, saying so (not a stretch)."""
    pts = [(F(0), F(0)), (F(1), F(3)), (F(3), F(-2)), (F(4), F(1))]
    c = R(pts, [1, 2, 4, 8])
    moved_pts = list(pts)
    moved_pts[k] = (pts[k][0], pts[k][1] + F(1, 10**12))
    moved = R(moved_pts, [1, 2, 4, 8])
    rows = [c.to_homogeneous().control_points(), moved.to_homogeneous().control_points()]
    assert co.exact_same_curve(rows[0], rows[0])
    assert not co.exact_same_curve(rows[0], rows[1])
    assert not co.exact_same_curve(rows[1], rows[0])
    want = {1: [(0.0, 0.0, "transversal"), (1.0, 1.0, "tangent")], 3: [(0.0, 0.0, "tangent")]}
    assert [tuple(h) for h in c.intersect(moved)] == want[k]
    from test_exact_rational_tangency import assert_matches_sympy  # tests/ is on sys.path

    assert_matches_sympy(c, moved, c.intersect(moved))
    as_floats = [
        R([tuple(float(v) for v in r) for r in x], [1.0, 2.0, 4.0, 8.0]) for x in (pts, moved_pts)
    ]
    with pytest.raises(ValueError, match=r"share no stretch \(decided to the rounding"):
        as_floats[0].intersect(as_floats[1])


def test_exact_location_is_exact():
    """The end of one curve located on another through the gcd of A − x w: a rational root
    comes out exactly, an irrational one within an ulp of the 50-digit value."""
    quarter = R([(1, 0), (1, 1), (0, 1)], [1, 1, 2])  # ((1 − u²), 2u) / (1 + u²)
    rows = quarter.to_homogeneous().control_points()
    assert co.exact_locate(rows, (F(3, 5), F(4, 5)), 0.0, 1.0) == [0.5]
    assert co.exact_locate(rows, (F(1), F(1)), 0.0, 1.0) == []
    assert co.on_curve(rows, (F(-1), F(0)))  # the same circle, outside the quarter's t
    # a point at t = 1/√3 (irrational in the quarter's parameter): 2u/(1+u²) = √3/2, so use
    # the parabola (u, u²) and the point (√2 − 1)-free check on a conic with a double point
    par = R([(0, 0), (F(1, 2), 0), (1, 1)], [1, 1, 1])  # (u, u²)
    got = co.exact_locate(par.to_homogeneous().control_points(), (F(1, 3), F(1, 9)), 0.0, 1.0)
    assert got == [1 / 3]


@pytest.mark.parametrize("rho", [None, F(2), F(1, 3)])
def test_a_trigonometric_curve_against_its_rational_form(rho):
    """The Han trigonometric cubic and its exact rational form (t = 2 arctan(s) on [0, π/2]),
    also reparameterised: one stretch, end to end."""
    fam = _family("han_trig_cubic")
    curve = fam.curve([(0, 0), (1, 2), (2, -1), (3, 1)], **ATOM_PARAMS["han_trig_cubic"])
    form = curve.to_rational_bezier()
    assert form.is_exact
    if rho is not None:
        form = form.reparameterize(rho)
    hi = math.pi / 2
    got = [(h.s, h.t, h.kind) for h in curve.intersect(form)]
    _close(got, [(0.0, 0.0, "coincident"), (hi, 1.0, "coincident")], 1e-12)
    back = [(h.s, h.t, h.kind) for h in form.intersect(curve)]
    _close(back, [(0.0, 0.0, "coincident"), (1.0, hi, "coincident")], 1e-12)


def test_the_float_rule_is_the_rounding_of_evaluation():
    """A float copy 1e-9 of its size away is not the same curve; within rounding it is."""
    curve = R([(0, 0), (1, 3), (3, -2), (4, 1)], [1.0, 2.0, 4.0, 8.0])
    rows = np.array(curve.to_homogeneous().points, dtype=float)
    side = co.float_side(rows / rows[:, -1].max(), 64 * 2.0**-52 * 3 * 4)
    shifted = np.array(curve.evaluate(0.5)) + [0.0, 4e-9]
    assert side.locate(curve.evaluate(0.5), 0.0, 1.0) == pytest.approx([0.5], abs=1e-12)
    assert side.locate(shifted, 0.0, 1.0) == []


@pytest.mark.parametrize("name", ["at_cubic", "at_pi_cubic", "hyp_cubic"])
def test_a_curve_without_a_rational_form_against_itself_is_one_stretch(name):
    """Mixed and hyperbolic families decide it on their polynomial pieces: each pair of equal
    pieces is a stretch, and the neighbours' stretches are joined into one, end to end (the
    pieces' boundaries used to be reported as coincident ends, and a spurious tangent point
    inside)."""
    fam = _family(name)
    curve = fam.curve([(0, 0), (1, 2), (2, -1), (3, 1)], **ATOM_PARAMS[name])
    assert not curve.has_rational_form
    lo, hi = (float(v) for v in curve.domain)
    got = [(h.s, h.t, h.kind) for h in curve.intersect(curve)]
    _close(got, [(lo, lo, "coincident"), (hi, hi, "coincident")], 1e-12)


def test_a_contact_of_high_order_at_a_common_end_is_one_tangency():
    """Two rational cubics with the same first three rows, differing in the last point: they
    agree to second order at s = t = 0 and meet nowhere else (the resultant in t of the
    crossing equations is s^3 times factors without a root in [0, 1], exactly). The search
    gives up on the flat contact; Newton from the subdivision's starts then stopped all along
    it (90 "tangent" points within 1e-5). Now hits within 1e-3 along which the curves stay
    within rounding are one contact."""
    import sympy as sp

    pts, weights = [(0, 0), (1, 2), (3, -1), (4, 1)], [1, F(2), F(1, 2), 1]
    c, other = R(pts, weights), R([*pts[:3], (4, 2)], weights)
    s, t = sp.symbols("s t")

    def homogeneous(points, x):
        n = len(points) - 1
        basis = [sp.binomial(n, i) * x**i * (1 - x) ** (n - i) for i in range(n + 1)]
        w = sum(sp.Rational(wi) * b for wi, b in zip(weights, basis, strict=True))
        num = [
            sum(sp.Rational(weights[i] * p[k]) * basis[i] for i, p in enumerate(points))
            for k in range(2)
        ]
        return num, w

    (ax, ay), wc = homogeneous(pts, s)
    (bx, by), wo = homogeneous([*pts[:3], (4, 2)], t)
    res = sp.Poly(sp.resultant(sp.expand(ax * wo - bx * wc), sp.expand(ay * wo - by * wc), t), s)
    roots = {float(r) for r in res.real_roots() if 0 <= r <= 1}
    assert roots == {0.0}
    assert [(h.s, h.t, h.kind) for h in c.intersect(other)] == [(0.0, 0.0, "tangent")]


def test_a_rational_curve_against_itself_at_s_squared():
    """P(s) = Q(s²) (degree 6, not a Möbius map of Q): the same image, one stretch, end to end
    (the issue's "non-affine reparameterisation" case, on a rational curve)."""
    from math import comb

    from test_acceptance_29 import _compose

    from lambda_bezier.hazmat.intersect_exact import power_coefficients

    q = R([(0, 0), (1, 2), (3, -1), (4, 1)], [1, 2, 3, 1])
    rows = q.to_homogeneous().control_points()
    power = [_compose(power_coefficients(rows, k), [F(0), F(0), F(1)]) for k in range(3)]
    n = len(power[0]) - 1
    p = R.from_homogeneous(
        [
            tuple(sum(F(comb(j, k), comb(n, k)) * col[k] for k in range(j + 1)) for col in power)
            for j in range(n + 1)
        ]
    )
    np.testing.assert_allclose(p.evaluate(0.5), q.evaluate(0.25), rtol=1e-15)
    assert _stretch(p, q) == [(0.0, 0.0, "coincident"), (1.0, 1.0, "coincident")]
    back = q.reparameterize(F(1, 3)).reverse()
    assert _stretch(p, back) == [(0.0, 1.0, "coincident"), (1.0, 0.0, "coincident")]
