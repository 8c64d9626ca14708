"""A curve that turns back along itself off a line (issue #29): P(s) = Q(g(s)) with g not
monotone, e.g. g(s) = 4s(1 − s), retraces Q. Its self-intersections are a continuum, to be
reported as shared stretches (kind "coincident", by their end pairs), as intersect reports two
curves sharing a stretch under any parameterisation and intersect_fold reports a curve on a
line turning back; the subdivision alone gave arbitrary "tangent" points.

A polynomial curve can turn back only where its whole derivative vanishes (P′ = Q′(g) g′ with
g′ = 0 there). Those parameters are the real roots in (0, 1) of the gcd of the coordinates'
derivatives, found exactly (every float is a rational); the curve cut there gives monotone
pieces, and every two pieces go through intersect, which reports a stretch they share.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from fractions import Fraction

from . import exact_poly as xp
from .intersect_exact import power_coefficients

TURN_WIDTH = Fraction(1, 2**64)  # an irrational turning point is refined to this, then halved

Rows = list[list[Fraction]]


def turning_points(rows: Sequence[Sequence[Fraction]]) -> list[Fraction]:
    """The s in (0, 1) where every coordinate's derivative vanishes, exactly (or to
    TURN_WIDTH where irrational), increasing."""
    common: list[Fraction] = []
    for axis in range(len(rows[0])):
        du = xp.derivative(xp.trim(power_coefficients(rows, axis)))
        common = xp.gcd(common, du)
    if len(common) <= 1:  # a constant gcd (or a point: every coordinate constant)
        return []
    cuts = []
    for root in xp.real_roots(common, Fraction(0), Fraction(1)):
        if not isinstance(root, Fraction):
            got = xp.refine(xp.squarefree(common), root, TURN_WIDTH)
            root = got if isinstance(got, Fraction) else (got[0] + got[1]) / 2
        if 0 < root < 1:
            cuts.append(root)
    return cuts


def piece(rows: Sequence[Sequence[Fraction]], a: Fraction, b: Fraction) -> Rows:
    """The control points of the curve on [a, b], exactly (de Casteljau twice)."""

    def split(pts: Rows, t: Fraction) -> tuple[Rows, Rows]:
        left, right = [pts[0]], [pts[-1]]
        while len(pts) > 1:
            pts = [
                [(1 - t) * x + t * y for x, y in zip(p, q, strict=True)]
                for p, q in zip(pts, pts[1:], strict=False)
            ]
            left.append(pts[0])
            right.append(pts[-1])
        return left, right[::-1]

    pts = [[Fraction(x) for x in row] for row in rows]
    if b < 1:
        pts = split(pts, b)[0]
    if a > 0:
        pts = split(pts, a / b)[1]
    return pts


def refolded(
    rows: Sequence[Sequence[Fraction]],
    intersect: Callable[[Rows, Rows], list[tuple[float, float, str]]],
) -> tuple[list[tuple[float, float, str]], list[tuple[float, float, float, float]]] | None:
    """(hits, boxes) of a curve that turns back along itself: the end pairs (s, t,
    "coincident"), s ≤ t, of the stretches it shares with itself and the isolated crossings
    of its monotone pieces with each other, from intersect(piece_i, piece_j); boxes (s0, s1,
    t0, t1) hold each shared stretch. None when it has no turning point or no two of its
    pieces share a stretch (the subdivision's answer stands)."""
    cuts = [Fraction(0), *turning_points(rows), Fraction(1)]
    if len(cuts) == 2:
        return None
    spans = list(zip(cuts, cuts[1:], strict=False))
    pieces = [piece(rows, a, b) for a, b in spans]
    found: list[tuple[float, float, str]] = []
    boxes: list[tuple[float, float, float, float]] = []
    for i in range(len(pieces)):
        for j in range(i + 1, len(pieces)):
            (a0, a1), (b0, b1) = spans[i], spans[j]
            ends: list[tuple[float, float]] = []
            for s, t, kind in intersect(pieces[i], pieces[j]):
                if kind != "coincident" and j == i + 1 and s == 1.0 and t == 0.0:
                    continue  # the turning point itself, where the two pieces join
                hit = (
                    float(a0 + (a1 - a0) * Fraction(s)),
                    float(b0 + (b1 - b0) * Fraction(t)),
                    kind,
                )
                if kind == "coincident":
                    ends.append(hit[:2])
                if hit not in found:
                    found.append(hit)
            # intersect gives a shared stretch's two end pairs together, sorted by s
            for (s0, t0), (s1, t1) in zip(ends[::2], ends[1::2], strict=False):
                boxes.append((s0, s1, min(t0, t1), max(t0, t1)))
    return (sorted(found), boxes) if boxes else None
