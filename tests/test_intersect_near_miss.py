"""Issue #29: near misses, where the certificate and the careful path once disagreed.

The rule (hazmat/intersect.py, "Meeting points"): two curves meet where the exact distance
between them is within the rounding of evaluating them, `_root_bound` (64 eps per unit of
degree and of the control points' size), and nowhere else. It once held only for the hits
Newton found: end points counted as on the other curve within a fixed 1e-10 of its size, so
the careful path answered a tangent hit for two segments 1e-10 apart that the certificate
(rightly) left apart.

Each pair below has its exact gap in Fractions (every float is a rational): the segment
pairs' distance, a parabola's lowest point above a line. Every path must report one meeting
point when the gap is within the bound and none beyond it: the public `intersect` (the
certificate, then the compiled careful path), the compiled careful path alone, the careful
path in Python alone, and `intersect` with numpy alone.
"""

from __future__ import annotations

from fractions import Fraction as F

import numpy as np
from conftest import careful_path as careful
from hypothesis import assume, example, given
from hypothesis import strategies as st

import lambda_bezier as lb
from lambda_bezier.hazmat import intersect as engine
from lambda_bezier.hazmat import intersect_certify as cert
from lambda_bezier.hazmat import intersect_subdivide

# gaps this close to the bound are decided by the last bits of a float norm: not asserted
BAND = 0.01


def every_answer(a, b) -> dict[str, list[engine.Intersection]]:
    answers = {"careful": careful(a, b)}
    before = intersect_subdivide.USE_COMPILED
    try:
        intersect_subdivide.USE_COMPILED = False
        answers["numpy"] = lb.BezierCurve(a).intersect(lb.BezierCurve(b))
        if _has_numba():
            intersect_subdivide.USE_COMPILED = True
            answers["intersect"] = lb.BezierCurve(a).intersect(lb.BezierCurve(b))
            p, q = np.array(a, dtype=float), np.array(b, dtype=float)
            settled = cert.settle_one(p, q, engine.SETTLE)
            if settled is not None:
                answers["settle"] = [
                    engine.Intersection(s, t, engine._KINDS[k]) for s, t, k in settled
                ]
    finally:
        intersect_subdivide.USE_COMPILED = before
    return answers


def _has_numba() -> bool:
    try:
        import numba  # noqa: F401
    except ImportError:
        return False
    return True


def bound_of(a, b) -> float:
    return engine._root_bound(lb.BezierCurve(a)._prepared, lb.BezierCurve(b)._prepared)


# ---------------------------------------------------------------------------- exact gaps
def _point_segment2(x, b0, b1) -> F:
    """The squared distance from x to the segment b0 b1, exactly."""
    d = [v - u for u, v in zip(b0, b1, strict=True)]
    rel = [v - u for u, v in zip(b0, x, strict=True)]
    length2 = sum(c * c for c in d)
    t = min(max(sum(r * c for r, c in zip(rel, d, strict=True)) / length2, F(0)), F(1))
    return sum((r - t * c) ** 2 for r, c in zip(rel, d, strict=True))


def _orient(p, q, r) -> F:
    return (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])


def segment_gap2(a, b) -> F:
    """The squared distance between two plane segments, exactly (0 where they meet)."""
    a0, a1 = [tuple(map(F, x)) for x in a]
    b0, b1 = [tuple(map(F, x)) for x in b]
    o1, o2 = _orient(a0, a1, b0), _orient(a0, a1, b1)
    o3, o4 = _orient(b0, b1, a0), _orient(b0, b1, a1)
    if o1 * o2 < 0 and o3 * o4 < 0:
        return F(0)
    return min(
        _point_segment2(a0, b0, b1),
        _point_segment2(a1, b0, b1),
        _point_segment2(b0, a0, a1),
        _point_segment2(b1, a0, a1),
    )


def parabola_gap(arch, height) -> F:
    """How far the lowest point of the parabola arch (three control points, y quadratic in s
    with its minimum inside) lies above the line y = height, exactly."""
    y0, y1, y2 = (F(p[1]) for p in arch)
    return y0 - (y0 - y1) ** 2 / (y0 - 2 * y1 + y2) - F(height)


def check(a, b, gap2: F, lo: float, hi: float) -> dict[str, list[engine.Intersection]]:
    """Every path: no meeting point when the exact gap is beyond hi; when it is within lo,
    the same meeting points on every path, at least one. lo, hi: the rounding bounds the
    pair's meeting points are held to (one number, _root_bound, for a hit Newton finds; for
    an end of one curve located on the other, the rounding of evaluating that other curve
    where it is located, _rounding_at)."""
    gap = float(gap2) ** 0.5
    assume(gap < (1 - BAND) * lo or gap > (1 + BAND) * hi)
    answers = every_answer(a, b)
    for path, got in answers.items():
        if gap > hi:
            assert got == [], (path, got, gap, hi)
        else:
            assert got and [h.kind for h in got] == [h.kind for h in answers["careful"]], (
                path,
                answers,
                gap,
                lo,
            )
    return answers


def segment_bounds(a, b) -> tuple[float, float]:
    """The least and the largest rounding bound a meeting point of two segments is held to:
    ROOT_RESIDUAL (|b_i| averaged + |p'|) of either segment, or ROOT_RESIDUAL times the
    control points' size."""
    lengths = [float(np.hypot(*np.subtract(c[1], c[0]))) for c in (a, b)]
    return engine.ROOT_RESIDUAL * min(lengths), 3 * bound_of(a, b)


# ---------------------------------------------------------------------------- shapes
gaps = st.floats(-14, -6).map(lambda e: 10.0**e)
coords = st.floats(-4, 4, allow_nan=False).map(lambda x: round(x, 3))


@given(
    b0=st.tuples(coords, coords),
    b1=st.tuples(coords, coords),
    u=st.floats(0.05, 0.95),
    away=st.tuples(st.floats(0.2, 2), st.floats(-2, 2)),
    gap=gaps,
)
@example(b0=(0.0, 1.0), b1=(0.0, 2.0), u=0.0, away=(1.0, 1.0), gap=-1.0)  # the case
@example(b0=(0.0, 0.0), b1=(2.0, 0.0), u=0.5, away=(1.0, 0.0), gap=1e-15)  # within: one hit
# a root just past the end, clamped to it, was reported beside the located end (1e-13 apart)
@example(b0=(0.0, 0.0), b1=(0.0, 1.0), u=0.25, away=(0.2, 2.0), gap=1e-14)
def test_an_end_near_a_segment(b0, b1, u, away, gap):
    """A segment ending gap (relative) beside another, on its normal: no hit beyond the
    rounding bound. gap < 0 builds the issue's pair: a segment from the origin to
    (float32(1e-10), 1) against (0, 1) - (0, 2)."""
    if gap < 0:
        a = [(0.0, 0.0), (float(np.float32(1e-10)), 1.0)]
        b = [b0, b1]
    else:
        d = np.subtract(b1, b0)
        length = float(np.hypot(*d))
        assume(length > 0.1)
        normal = np.array([-d[1], d[0]]) / length
        foot = np.add(b0, u * d)
        size = max(np.abs([b0, b1]).max(), length)
        end = foot + gap * size * normal
        start = end + away[0] * normal + away[1] * d / length
        a = [tuple(start.tolist()), tuple(end.tolist())]
        b = [b0, b1]
    answers = check(a, b, segment_gap2(a, b), *segment_bounds(a, b))
    assert all(len(got) <= 1 for got in answers.values())


@given(
    delta=gaps,
    lo=st.floats(-0.9, 0.9),
)
@example(delta=float(np.float32(1e-10)), lo=-0.5)
def test_nearly_collinear_segments(delta, lo):
    """Segments nearly on one line, delta apart at most: not "on one line and overlapping"
    (a ValueError once, the curves being within 1e-10 of one line), and no meeting point
    unless within the bound."""
    a = [(0.0, 0.0), (delta, 1.0)]
    b = [(0.0, 1.0 + lo), (0.0, 2.0)]  # lo < 0: the two overlap along y
    check(a, b, segment_gap2(a, b), *segment_bounds(a, b))


@given(
    x0=coords,
    h=coords,
    w=st.floats(0.25, 3),
    k=st.floats(0.25, 3),
    gap=gaps,
)
@example(x0=0.0, h=0.0, w=1.0, k=1.0, gap=1e-14)  # within the bound: the tangency, once
@example(x0=0.0, h=0.0, w=1.0, k=1.0, gap=1e-12)
def test_a_parabola_just_above_a_line(x0, h, w, k, gap):
    """A parabola whose lowest point is gap (relative) above a line: a near-tangency, which
    the certificate declines; a tangent hit within the bound, none beyond it."""
    arch = [(x0 - w, h + k), (x0, h - k), (x0 + w, h + k)]
    size = max(abs(x0) + 2 * w, abs(h) + k)
    lowest = float(h)  # y0 - (y0 - y1)^2 / (y0 - 2 y1 + y2) = h in the reals
    height = lowest - gap * size
    line = [(x0 - 2 * w, height), (x0 + 2 * w, height)]
    exact = parabola_gap(arch, height)
    assume(exact > 0)  # rounding may put the line above the arch's floats: two crossings
    bound = bound_of(arch, line)
    answers = check(arch, line, exact * exact, bound, bound)
    assert all([h.kind for h in got] in ([], ["tangent"]) for got in answers.values())


# a degree-9 piece of an at_cubic curve whose line through P0 has a triple contact at s = 0
# (test_atom_intersect's triple-root draw): the distance is within rounding for s up to about
# 3e-5, the subdivision isolated a "crossing" there, and the careful path in Python refined it
# to a second hit at s = 2.9e-5 (the compiled path did not). One contact, on every path.
TRIPLE_PIECE = [
    [-0.12500000000000075, -1.5643485829757547e-16],
    [-0.4358867730114853, -0.22907446432425352],
    [-0.7410508139789381, -0.4539321787213169],
    [-1.0396510238167453, -0.6741525936483408],
    [-1.3308673157551119, -0.8893306423213804],
    [-1.6139049389371787, -1.0990789025132826],
    [-1.8879986400121602, -1.3030296389789326],
    [-2.1524166071199056, -1.500836698699392],
    [-2.406464144952044, -1.692177234287026],
    [-2.649487037696564, -1.876753235882178],
]


def test_a_triple_contact_at_an_end_is_one_hit_on_every_path():
    line = [[18.875, 14.0], [-19.125, -14.0]]
    for path, got in every_answer(TRIPLE_PIECE, line).items():
        assert len(got) == 1, (path, got)
        assert got[0].s == 0.0 and abs(got[0].t - 0.5) < 1e-12, (path, got)
