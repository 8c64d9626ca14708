"""Issue #29, an independent audit (round 20) beside tests/test_acceptance_29*.py, which it does
not repeat: a line through the tiny loop of a cubic near its cusp (three crossings 1e-5 to
1e-7 apart on exact input, the middle one where the curve nearly stops), crossings of lines
parallel to an axis decided by the exact isolation, ... Every expected answer is exact by
construction or computed by mpmath at 50 digits; none comes from the code under test."""

from __future__ import annotations

from fractions import Fraction as F

import mpmath as mp
import pytest

import lambda_bezier as lb


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


@pytest.mark.parametrize("k", [10, 12, 14])
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
    assert lb.intersect_many([curve, line], [line, curve]) == [got, line.intersect(curve)]
    boxes = lb.intersect_exact(curve, line)
    assert [(c.certified, c.tangent) for c in boxes] == [(True, False)] * 3
    for c, (s, t) in zip(boxes, want, strict=True):
        assert _mp(c.s[0]) <= s <= _mp(c.s[1]) and _mp(c.t[0]) <= t <= _mp(c.t[1])


def _mp(x: F) -> mp.mpf:
    return mp.mpf(x.numerator) / x.denominator
