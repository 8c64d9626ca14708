"""Issue #29, an independent audit (round 20) beside tests/test_acceptance_29*.py, which it does
not repeat: a line through the tiny loop of a cubic near its cusp (three exact crossings 1e-5
to 1e-7 apart, one on a line parallel to an axis), exact space curves in one plane (crossings
1e-7 apart, touching, missing by 1e-20), exact curves whose floats are subnormal, trigonometric,
mixed and C-Bézier meetings at the ends of their domains, a non-curve refused by every class,
locate at a turning point or cusp, and an exact trigonometric curve against a line 1e-13 above
its minimum. Every expected answer is exact by construction or computed by mpmath at 50 digits
(the trigonometric one from its exact rational form); none comes from the code under test."""

from __future__ import annotations

from fractions import Fraction as F

import mpmath as mp
import pytest
from conftest import family_file

import lambda_bezier as lb
from lambda_bezier import examples


# ------------------------------------------- a line through the tiny loop of a near-cusp cubic
def _near_cusp(k: int) -> tuple[lb.BezierCurve, list[tuple[mp.mpf, mp.mpf]]]:
    """(0,0), (a,1), (1−a,1), (1,0) with a = 1 + 8/3 10^-k: x(1/2 + w) − 1/2 = −(3/2)(a − 1) w
    + (6a − 2) w³ and y = 3s(1 − s), so the curve makes a loop of height 3·10^-k, crossing
    itself at s = 1/2 ± w, w² = 10^-k / (1 + 4·10^-k). The line x = 1/2, y from −1 to 2 meets
    it at s = 1/2 (t = 7/12, where the curve's speed is 4·10^-k) and at s = 1/2 ± w (both at
    the loop's crossing point, t = 7/12 − w²), where the curve is within 1e-15 of the line."""
    a = 1 + F(8, 3) / 10**k
    curve = lb.BezierCurve([(0, 0), (a, 1), (1 - a, 1), (1, 0)])
    mp.mp.dps = 50
    w2 = mp.mpf(10) ** -k / (1 + 4 * mp.mpf(10) ** -k)
    w = mp.sqrt(w2)
    t0 = mp.mpf(7) / 12
    return curve, [(mp.mpf(1) / 2 - w, t0 - w2), (mp.mpf(1) / 2, t0), (mp.mpf(1) / 2 + w, t0 - w2)]


@pytest.mark.parametrize("k", [10, 12])
def test_a_line_through_the_tiny_loop_of_a_near_cusp_meets_it_three_times(k):
    """The float search merged the three (the curves stay within MERGE_GAP between them) into
    one "transversal" crossing at s = 1/2, where the tangents are not parallel, so the exact
    isolation never ran (k = 10); from k = 11 on it ran and left the two loop crossings
    uncertified (over their common t the line's x − 1/2 does not depend on t, and the
    decision had no subresultant for it), so one "tangent" hit stood."""
    curve, want = _near_cusp(k)
    line = lb.BezierCurve([(F(1, 2), -1), (F(1, 2), 2)])
    got = curve.intersect(line)
    assert [(h.s, h.t, h.kind) for h in got] == [
        (float(s), float(t), "transversal") for s, t in want
    ]
    assert sorted((h.t, h.s) for h in line.intersect(curve)) == [(h.s, h.t) for h in got]
    assert lb.intersect_many([curve], [line]) == [got]
    boxes = lb.intersect_exact(curve, line)
    assert [(c.certified, c.tangent) for c in boxes] == [(True, False)] * 3
    for c, (s, t) in zip(boxes, want, strict=True):
        assert _mp(c.s[0]) <= s <= _mp(c.s[1]) and _mp(c.t[0]) <= t <= _mp(c.t[1])


def _mp(x: F) -> mp.mpf:
    return mp.mpf(x.numerator) / x.denominator


# -------------------------------------------- exact space curves in one plane: decided exactly
def _in_space(curve: lb.BezierCurve) -> lb.BezierCurve:
    """(x, y) -> (3x/5 + 1, y + 2, 4x/5 + 3): the same curve, exactly, in a tilted plane of
    space (an isometry onto it, so the same parameters meet)."""
    return lb.BezierCurve(
        [(F(3, 5) * x + 1, y + 2, F(4, 5) * x + 3) for x, y in curve.control_points()]
    )


@pytest.mark.parametrize("gap_exponent", [7, 9])
def test_exact_space_curves_in_one_plane_cross_twice_close_together(gap_exponent):
    """A graph with roots a and a + 10^-k against its axis, in a tilted plane: the planar
    pair gives both crossings (the exact isolation), the space pair gave one "tangent" hit
    (the exact isolation was for planar curves only)."""
    a = F(437, 1000)
    b = a + F(1, 10**gap_exponent)
    # (s, 3 (s − a)(s − b)) on s in [0, 1], as a Bézier quadratic, against y = 0
    y = [3 * a * b, 3 * a * b - F(3, 2) * (a + b), 3 * a * b - 3 * (a + b) + 3]
    graph = lb.BezierCurve([(F(k, 2), y[k]) for k in range(3)])
    axis = lb.BezierCurve([(F(-1, 10), 0), (F(11, 10), 0)])
    want = [(float(r), float((r + F(1, 10)) / F(12, 10)), "transversal") for r in (a, b)]
    assert [tuple(h) for h in graph.intersect(axis)] == want
    assert [tuple(h) for h in _in_space(graph).intersect(_in_space(axis))] == want
    assert lb.intersect_many([_in_space(graph)], [_in_space(axis)]) == [
        _in_space(graph).intersect(_in_space(axis))
    ]


@pytest.mark.parametrize(
    ("lift", "want"),
    [
        (F(1, 10**20), []),  # 1e-20 above the arch's apex: no common point
        (F(0), [(0.5, 0.5, "tangent")]),  # touching at the apex
        # 1e-20 below: (2s − 1)² = 10^-20, s = 1/2 ∓ 5·10^-11, both transversal
        (F(-1, 10**20), "two"),
    ],
)
def test_exact_space_curves_in_one_plane_touch_or_miss_exactly(lift, want):
    """The arch (0,0), (1,2), (2,0) (height 4s(1 − s)) against y = 1 + lift, in a tilted plane
    of space: as in the plane (the float answer, a "tangent" at 1e-20 above, stood in space)."""
    arch = _in_space(lb.BezierCurve([(0, 0), (1, 2), (2, 0)]))
    line = _in_space(lb.BezierCurve([(0, 1 + lift), (2, 1 + lift)]))
    got = [tuple(h) for h in arch.intersect(line)]
    if want == "two":
        mp.mp.dps = 50
        r = mp.sqrt(mp.mpf(10) ** -20) / 2  # 4s(1 − s) = 1 + lift <=> (2s − 1)² = −lift
        want = [
            (float(mp.mpf(1) / 2 + sg * r), float(mp.mpf(1) / 2 + sg * r), "transversal")
            for sg in (-1, 1)
        ]
    assert got == want


# ------------------------------------------- exact curves whose floats are subnormal (< 2^-1022)
@pytest.mark.parametrize("exponent", [-1060, -1040])
def test_exact_curves_below_the_normal_floats_keep_every_digit(exponent):
    """The issue's parabola and line, times 2^k, in Fractions: the same crossings, s = 0.5495
    and 0.5505, exactly. Their floats are subnormal (1e-6 · 2^-1060 is 0), and the pair,
    scaled up by a power of two, was rebuilt from those floats: no crossing at all. A point
    on the parabola, exact, was not located either (t = 3/5)."""
    scale = F(2) ** exponent
    par = lb.BezierCurve(
        [(-scale, F(121, 100) * scale), (0, F(-99, 100) * scale), (scale, F(81, 100) * scale)]
    )
    line = lb.BezierCurve([(-scale, scale / 10**6), (scale, scale / 10**6)])
    want = [(0.5495, 0.5495, "transversal"), (0.5505, 0.5505, "transversal")]
    assert [tuple(h) for h in par.intersect(line)] == want
    assert [tuple(h) for h in lb.intersect_many([par], [line])[0]] == want
    # y(3/5) = 4 (3/5)² − 4.4 (3/5) + 1.21 = 1/100, x(3/5) = 1/5
    assert par.locate((scale / 5, scale / 100)) == 0.6


# ------------------------------------- trigonometric, mixed, C-Bézier: meetings at the domain ends
def _atom(name: str, points: list[tuple[int, int]]) -> object:
    if name == "c_bezier_cubic":
        return lb.load_family(examples.path("c_bezier_cubic.toml")).curve(points, alpha=1.0)
    params = {"han_trig_cubic": {"lam": F(1, 2), "mu": F(1, 2)}, "at_pi_cubic": {"lam": F(1, 2)}}
    return lb.load_family(family_file(name)).curve(points, **params[name])


ATOMS = ["han_trig_cubic", "at_pi_cubic", "c_bezier_cubic"]


@pytest.mark.parametrize("name", ATOMS)
def test_two_pieces_of_a_spline_meet_at_their_join_exactly(name):
    """P = (0,0), (1,2), (2,2), (3,0) and its image under (x, y) -> (6 − x, −y), reversed: a
    curve of a family symmetric under reversal that starts where the first ends, with the
    same tangent (a C1 join at (3, 0)); the first lies above y = 0, the second below. They
    meet once, at (end of the first, start of the second), "tangent". It came back at
    t = 1.1e-16 (trigonometric), 5.6e-17 (mixed), s = 0.9999999999999998 (C-Bézier)."""
    pts = [(0, 0), (1, 2), (2, 2), (3, 0)]
    first = _atom(name, pts)
    second = _atom(name, [(6 - x, -y) for x, y in reversed(pts)])
    lo, hi = first.domain
    assert first.intersect(second) == [(hi, lo, "tangent")]
    assert second.intersect(first) == [(lo, hi, "tangent")]


@pytest.mark.parametrize("name", ["han_trig_cubic", "at_pi_cubic"])
def test_a_curve_against_its_reversal_shares_it_end_to_end_exactly(name):
    """The family is symmetric under reversal (λ = μ for the trigonometric one): the curve of
    the reversed control points is the same curve run backwards, t -> lo + hi − t. The mixed
    family's stretch ended at t = 0.9999999999999999."""
    pts = [(0, 0), (1, 2), (3, 2), (4, -1)]
    curve = _atom(name, pts)
    lo, hi = curve.domain
    assert curve.intersect(_atom(name, pts[::-1])) == [
        (lo, hi, "coincident"),
        (hi, lo, "coincident"),
    ]


# ------------------------------------------------------------- bad input, the same on every class
@pytest.mark.parametrize("name", ATOMS)
def test_intersect_takes_a_composite_and_refuses_other_objects_by_name_on_every_class(name):
    """CompositeCurve had no intersect; every class refused it with "other must be a curve"
    but the trigonometric/mixed/C-Bézier ones, which raised a bare AttributeError. Since
    round 21 a composite intersects (through its segments): every class hands it there, s and
    t exchanged; anything else is refused by name."""
    from lambda_bezier.hazmat.intersect import Intersection

    comp = lb.CompositeCurve([lb.BezierCurve([(0, 0), (1, 1)])])
    for curve in (_atom(name, [(0, 0), (1, 2), (2, 2), (3, 0)]), lb.BezierCurve([(0, 1), (1, 0)])):
        assert curve.intersect(comp) == [
            Intersection(h.t, h.s, h.kind) for h in comp.intersect(curve)
        ]
        with pytest.raises(TypeError, match="other must be a curve, got object"):
            curve.intersect(object())


# ------------------------------------------------------ locate where the curve turns or stops
@pytest.mark.parametrize(
    ("points", "point", "want"),
    [
        ([(0, 0), (1, 1), (0, 0)], (F(1, 2), F(1, 2)), 0.5),  # out along y = x and back
        ([(0, 0), (1, 1), (0, 0)], (0.5, 0.5), 0.5),
        ([(0, 0, 0), (1, 1, 1), (0, 0, 0)], (F(1, 2), F(1, 2), F(1, 2)), 0.5),
        ([[0], [1], [0]], [F(1, 2)], 0.5),  # a curve on the real line
        ([(0, 0), (1, 1), (0, 1), (1, 0)], (F(1, 2), F(3, 4)), 0.5),  # a cusp
    ],
)
def test_locate_at_a_turning_point_or_a_cusp_is_exact(points, point, want):
    """Where the curve's whole derivative vanishes the point is a double root of the
    location, which Newton found to about 1e-8 only (0.49999999172697857); the exact turning
    point (the common root of the derivative's coordinates) is the answer."""
    assert lb.BezierCurve(points).locate(point) == want


def test_locate_at_an_irrational_turning_point():
    """x = y = 3s + 3s² − 4s³ turns at s = (1 + √5)/4, its tip located to the last bits."""
    curve = lb.BezierCurve([(0, 0), (1, 1), (3, 3), (2, 2)])
    mp.mp.dps = 50
    m = (1 + mp.sqrt(5)) / 4
    tip = 3 * m + 3 * m**2 - 4 * m**3
    got = curve.locate((float(tip), float(tip)))
    assert abs(got - m) <= 2e-16


# ------------------------------ exact trigonometric curves: a tangency cluster decided exactly
@pytest.mark.parametrize("heights", [[3, 6, -9, 6], [2, -1, -6, 6], [-4, 6, -7, -3]])
def test_exact_trig_curve_and_a_line_1e13_above_its_minimum_cross_twice(heights):
    """A Han trigonometric cubic with exact points and parameters against y = its least
    interior value + 1e-13 (to the float evaluation's rounding): two crossings 3e-7 to 5e-7
    apart, against the exact rational form's roots (Y(s) − level W(s) = 0 at 50 digits,
    t = t_of_s(s)). The certified search reported them as one "tangent" hit; the exact
    isolation on the curves' exact rational forms now decides such a hit."""
    from test_acceptance_29_classes import (
        ATOM_PARAMS,
        _family,
        _level_above_minimum,
        _trig_pair_reference,
    )

    curve = _family("han_trig_cubic").curve(
        [(F(i), F(h, 4)) for i, h in enumerate(heights)], **ATOM_PARAMS["han_trig_cubic"]
    )
    lo, hi = (float(v) for v in curve.domain)
    t = [lo + (hi - lo) * k / 4000 for k in range(4001)]
    y = curve.evaluate(t)[:, 1]
    inner = [i for i in range(1, 4000) if y[i] < y[i - 1] and y[i] <= y[i + 1]]
    level = _level_above_minimum(curve, t[inner[0] - 1], t[inner[0] + 1]) - F(1, 10**7)
    level += F(1, 10**13)
    want = _trig_pair_reference(curve, level)
    assert len(want) >= 2
    got = curve.intersect(lb.BezierCurve([(-1, level), (4, level)]))
    assert len(got) == len(want), (got, want)
    for h, w in zip(got, want, strict=True):
        assert abs(h.s - w) <= 1e-12 and h.kind == "transversal"
