"""The self-intersections of a curve that lies on a line and turns back along it (issue #29):
it meets itself along stretches, reported like two curves sharing a stretch, by the end
pairs of each.

The curve's position along the line, u(s) = (p(s) − P_0)·d (d = P_far − P_0, exact in
Fractions: every float is a rational), is a polynomial. The real roots of u′ in (0, 1) where
u′ changes sign (Sturm sequences, exact_poly) cut [0, 1] into monotone pieces; every two
pieces i < j whose ranges of u overlap along an interval [L, H] of positive length share
that stretch, reported by its two ends: for each end value v, the s on piece i and the t on
piece j with u(s) = u(t) = v (bisection with u evaluated exactly, to the last bit). Two
neighbouring pieces meet at their turning point, where that end pair is s = t.
"""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction

from . import exact_poly as xp
from .intersect_exact import power_coefficients

TURN_WIDTH = Fraction(1, 2**64)  # turning points are refined to this width, then rounded


def folded_stretches(
    rows: Sequence[Sequence[Fraction | int | float]],
) -> list[tuple[float, float]]:
    """End pairs (s, t), s ≤ t, of the stretches a curve on a line (control points `rows`,
    taken exactly) shares with itself, two per stretch, sorted, each pair once (one that ends two
    stretches, at the end of a monotone piece, is listed once); [] when it runs one way."""
    base = [Fraction(x) for x in rows[0]]
    rel = [[Fraction(x) - b for x, b in zip(row, base, strict=True)] for row in rows]
    far = max(rel, key=lambda r: sum(x * x for x in r))
    u_rows = [[sum((x * d for x, d in zip(r, far, strict=True)), Fraction(0))] for r in rel]
    u = xp.trim(power_coefficients(u_rows, 0))
    du = xp.derivative(u)
    if len(du) <= 1:  # u linear or constant: one way (or a point)
        return []
    cuts = [Fraction(0)]
    for root in xp.real_roots(du, Fraction(0), Fraction(1)):
        if isinstance(root, Fraction):
            at = root
        else:
            got = xp.refine(xp.squarefree(du), root, TURN_WIDTH)
            at = got if isinstance(got, Fraction) else (got[0] + got[1]) / 2
        if 0 < at < 1:
            cuts.append(at)
    cuts.append(Fraction(1))
    # keep only the cuts where u′ changes sign (a stationary point of even order runs on)
    pieces: list[tuple[Fraction, Fraction, int]] = []
    for a, b in zip(cuts, cuts[1:], strict=False):
        mid = xp.evaluate(du, (a + b) / 2)
        sign = (mid > 0) - (mid < 0)
        if pieces and pieces[-1][2] == sign:
            pieces[-1] = (pieces[-1][0], b, sign)
        else:
            pieces.append((a, b, sign))
    if len(pieces) < 2:
        return []
    ranges = [sorted((xp.evaluate(u, a), xp.evaluate(u, b))) for a, b, _ in pieces]
    out: list[tuple[float, float]] = []
    for i in range(len(pieces)):
        for j in range(i + 1, len(pieces)):
            lo = max(ranges[i][0], ranges[j][0])
            hi = min(ranges[i][1], ranges[j][1])
            if hi <= lo:
                continue
            for v in (lo, hi):
                out.append((_solve(u, pieces[i], v), _solve(u, pieces[j], v)))
    return sorted(set(out))  # a pair ending two stretches (at a piece's end) once


def _solve(u: list[Fraction], piece: tuple[Fraction, Fraction, int], v: Fraction) -> float:
    """The s in the monotone piece with u(s) = v (v within the piece's range), to the last
    bit: bisection on u − v evaluated exactly."""
    a, b, sign = piece
    if xp.evaluate(u, a) == v:
        return float(a)
    if xp.evaluate(u, b) == v:
        return float(b)
    for _ in range(200):  # until a and b round to neighbouring floats (or one)
        if float(a) == float(b) or b - a < Fraction(1, 2**80):
            break
        mid = (a + b) / 2
        value = xp.evaluate(u, mid) - v
        if value == 0:
            return float(mid)
        if (value > 0) == (sign > 0):
            b = mid
        else:
            a = mid
    return float((a + b) / 2)
