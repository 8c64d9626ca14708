"""Point location on a classical Bézier curve (`locate_all`; `locate_point` for a user's point,
scaled near 1 and snapped to exact turning points), the end points of a pair of
curves located on each other (`_isolate_ends`), and the clusters of unresolved pieces that give
Newton its starting points (`_starts`): the one-dimensional half of the intersection engine
(hazmat/intersect.py), which imports it; the tolerances both halves share live here."""

from __future__ import annotations

import math
from collections.abc import Sequence
from fractions import Fraction

import numpy as np

from . import intersect_refold as refold
from . import intersect_subdivide as sub
from .intersect_prepared import NORMAL_EXPONENT, Prepared, _exact_difference, _integer_point

# relative distance below which `locate` counts a user's point as on a curve. Intersection
# does not use it: two curves meet only where they are within the rounding of evaluating
# them, _root_bound (see "Meeting points" in the module's note)
ON_CURVE = 1e-10
SAME_ROOT = 1e-9  # parameters closer than this are one intersection
# relative, per degree: how far from zero a refined root's exact residual may be
ROOT_RESIDUAL = 64 * float(np.finfo(float).eps)
# a piece locate_all is left with that is wider than this is flat, not unresolved at depth
WIDE_PIECE = 1e-6


# ---------------------------------------------------------------------------- clusters
def _interval_clusters(s0: np.ndarray, t0: np.ndarray, width: np.ndarray) -> list[np.ndarray]:
    """Groups of unresolved pairs of pieces whose s and t intervals touch (transitively): a
    sweep over the pairs sorted by s0, so no K x K table."""
    count = s0.size
    parent = list(range(count))

    def root(k: int) -> int:
        while parent[k] != k:
            parent[k] = parent[parent[k]]
            k = parent[k]
        return k

    order = np.argsort(s0, kind="stable").tolist()
    s_lo, t_lo, w = s0.tolist(), t0.tolist(), width.tolist()
    active: list[int] = []
    for k in order:
        active = [j for j in active if s_lo[j] + w[j] >= s_lo[k] - 1e-15]
        for j in active:
            if t_lo[j] <= t_lo[k] + w[k] + 1e-15 and t_lo[k] <= t_lo[j] + w[j] + 1e-15:
                parent[root(j)] = root(k)
        active.append(k)
    groups: dict[int, list[int]] = {}
    for k in range(count):
        groups.setdefault(root(k), []).append(k)
    return [np.array(members) for members in groups.values()]


def _starts(
    s0: np.ndarray, t0: np.ndarray, width: np.ndarray, per_cluster: int = 6
) -> list[tuple[float, float]]:
    """Newton starting points for unresolved pairs of pieces (a tangency, or a contact
    subdivision could not split): the middle pair of each cluster, and for a cluster longer
    than a few pieces pairs spread along it."""
    out = []
    for members in _interval_clusters(s0, t0, width):
        centre_s, centre_t = s0[members] + width[members] / 2, t0[members] + width[members] / 2
        order = members[np.argsort(centre_s + centre_t, kind="stable")]
        picks = [order[order.size // 2]]
        if order.size <= per_cluster:  # a few flat pieces: each may hold its own crossing
            picks = list(order)
        elif order.size > 3:
            spread = np.linspace(0, order.size - 1, min(per_cluster, order.size)).astype(int)
            picks += [k for k in order[np.unique(spread)] if k != picks[0]]
        out += [(float(s0[k] + width[k] / 2), float(t0[k] + width[k] / 2)) for k in picks]
    return out


def locate_all(
    p: Prepared,
    point: np.ndarray,
    exact_point: Sequence[Fraction | int | float] | None = None,
    within: float | None = None,
    exact_end: bool = False,
    iso: sub.Isolated | None = None,
) -> list[float]:
    """Every t in [0, 1] with p(t) = point: within ON_CURVE of the curve's scale, or within
    the distance `within`, or (exact_end: the point is exact, an end of another curve)
    within the rounding of evaluating p at t (_rounding_at). iso: the subdivision's
    candidates for this point (_isolate_ends), where already found with others'."""
    point = np.asarray(point, dtype=float)
    exact_target = _integer_point(exact_point if exact_point is not None else point.tolist())
    tol = _locate_tolerance(p, point)
    on_curve = ON_CURVE * max(p.size, float(np.abs(point).max(initial=0.0)))
    accept = on_curve if within is None else within
    found: list[float] = []
    if p.is_point:
        if np.linalg.norm(p.pts[0] - point) <= tol:
            raise ValueError("the curve is a single point: every t gives it")
        return found
    for end in (0, 1):  # (numerators, lcm of reduced denominators) is canonical
        if _integer_point(p.exact_row(-1 if end else 0)) == exact_target:
            found.append(float(end))
    # candidates from the subdivision engine: Newton roots on one-to-one pieces, and the
    # middles of pieces that stay flat around the point (a zero of the speed there)
    if iso is None:
        iso = sub.isolate_points(p.pts[None], point[None], np.array([tol]))
    # a wide piece left over is flat to rounding and runs forward along its chord (a curve
    # on a line, say): one Newton start in its middle can overshoot out of the domain, so
    # bracket the point's projection on the chord, which is monotone along such a piece
    wide = iso.left_width > WIDE_PIECE
    starts = iso.root_s.tolist()
    starts += [
        _chord_bracket(p, point, s0, s0 + w)
        for s0, w in zip(iso.left_s0[wide].tolist(), iso.left_width[wide].tolist(), strict=True)
    ]
    narrow = ~wide
    starts += [
        s for s, _ in _starts(iso.left_s0[narrow], iso.left_t0[narrow], iso.left_width[narrow])
    ]
    for start in starts:
        t = _locate_newton(p, point, exact_target, start)
        if t is None or any(abs(t - u) < SAME_ROOT for u in found):
            continue
        # on the curve: the exact distance, relative to the curve's own size (its control
        # polygon can be far larger: a Chebyshev polynomial's Bernstein coefficients)
        if _exact_distance(p, t, exact_target) > (_rounding_at(p, t) if exact_end else accept):
            continue
        # one location if the curve stays at the point all the way between (a flat
        # spot, p' = p'' = 0, leaves the residual below tolerance around the root, over
        # a stretch as wide as tolerance^(1/order): 0.02 for a zero of order 6)
        same = [
            j
            for j, u in enumerate(found)
            if all(
                np.linalg.norm(p.at(u + x * (t - u)) - point) <= on_curve
                for x in np.linspace(0.0, 1.0, 17)
            )
        ]
        if not same:
            found.append(float(t))
        elif _exact_distance(p, t, exact_target) < _exact_distance(p, found[same[0]], exact_target):
            found[same[0]] = float(t)
    return sorted(found)


def _locate_tolerance(p: Prepared, point: np.ndarray) -> float:
    """The distance within which locate_all's subdivision keeps pieces around the point."""
    return ON_CURVE * max(p.scale, float(np.abs(point).max(initial=0.0)))


def _isolate_ends(
    curves: Sequence[Prepared], others: Sequence[Prepared]
) -> list[tuple[sub.Isolated | None, sub.Isolated | None]]:
    """The subdivision's candidates for the two end points of others[j] on curves[j], every
    j in one isolate_points call (the curves of one degree and dimension). Each row is
    subdivided on its own, so each point's candidates are those a call of its own gives, in
    the same order; the numpy loop's cost is per level, not per row. (None, None) where the
    curve is a point (locate_all decides that case without subdividing)."""
    rows = [j for j, q in enumerate(curves) if not q.is_point]
    found: list[tuple[sub.Isolated | None, sub.Isolated | None]] = [(None, None)] * len(curves)
    if not rows:
        return found
    points = np.concatenate([others[j].pts[[0, -1]] for j in rows])
    tols = np.array(
        [
            _locate_tolerance(curves[j], points[2 * r + e])
            for r, j in enumerate(rows)
            for e in (0, 1)
        ]
    )
    iso = sub.isolate_points(np.stack([curves[j].pts for j in rows for _ in (0, 1)]), points, tols)
    each = sub.split_rows(iso, 2 * len(rows))
    for r, j in enumerate(rows):
        found[j] = (each[2 * r], each[2 * r + 1])
    return found


def _rounding_at(p: Prepared, t: float) -> float:
    """How far p(t) can be off when evaluated at a float t: ROOT_RESIDUAL times n sum |b_i|
    B_i(t) (de Casteljau's rounding, from the control points) plus |p'(t)| (t's own)."""
    work = np.linalg.norm(p.pts, axis=1)
    while work.size > 1:
        work = work[:-1] + t * (work[1:] - work[:-1])
    return float(ROOT_RESIDUAL * (p.degree * work[0] + np.linalg.norm(p.at(t, 1))))


def _chord_bracket(p: Prepared, point: np.ndarray, s0: float, s1: float) -> float:
    """A start for the foot point on a piece [s0, s1] that runs forward along its chord c:
    bisection on (p(s) - point)·c, nondecreasing there, down to width WIDE_PIECE."""
    chord = p.at(s1) - p.at(s0)
    while s1 - s0 > WIDE_PIECE:
        middle = 0.5 * (s0 + s1)
        if float((p.at(middle) - point) @ chord) < 0.0:
            s0 = middle
        else:
            s1 = middle
    return 0.5 * (s0 + s1)


def _exact_distance(p: Prepared, t: float, target: tuple[list[int], int]) -> float:
    return float(np.linalg.norm(_exact_difference(p.exact_at(t), target)))


def _locate_newton(
    p: Prepared, point: np.ndarray, target: tuple[list[int], int], t: float
) -> float | None:
    """Newton on (p(t) - point)·p'(t) = 0 (the foot point): in floats until the steps stop
    shrinking, then up to three steps with the residual p(t) - point evaluated exactly."""
    for exact, iterations in ((False, 40), (True, 3)):
        prev = np.inf
        for it in range(iterations):
            diff = _exact_difference(p.exact_at(t), target) if exact else p.at(t) - point
            d1 = p.at(t, 1)
            slope = float(d1 @ d1 + diff @ p.at(t, 2))
            if slope == 0.0:
                break
            step = float(diff @ d1) / slope
            t -= step
            if not -0.5 < t < 1.5:
                return None
            if abs(step) < 1e-16 or (it > 5 and abs(step) > 0.5 * prev):
                break
            prev = abs(step)
    if -1e-12 <= t <= 1 + 1e-12:
        return min(max(t, 0.0), 1.0)
    return None


# ---------------------------------------------------------------------------- drivers


def locate_point(
    p: Prepared, point: np.ndarray, exact_point: tuple[Fraction, ...] | None
) -> list[float]:
    """locate_all for a point the user gives (Curve.locate), curve and point scaled near 1
    when the curve's size is beyond 2^±NORMAL_EXPONENT (at 1e300 on-curve points came back
    None, at 1e-300 1e-10 off). A point 2^64 times farther out than the curve's largest
    coordinate is not on it."""
    shift = p.exponent
    if -NORMAL_EXPONENT <= shift <= NORMAL_EXPONENT:
        return _at_turning_points(p, point, exact_point, locate_all(p, point, exact_point))
    big = float(np.abs(point).max(initial=0.0))
    if big and math.frexp(big)[1] - shift > 64:
        return []
    scaled_point = np.ldexp(point, -shift)
    if exact_point is not None:
        exact_point = tuple(Fraction(x) * Fraction(2) ** -shift for x in exact_point)
        # from the exact point: its floats near 2^-1074 are subnormal (a few bits, or 0)
        scaled_point = np.array([float(x) for x in exact_point])
    p = p.scaled(shift)
    found = locate_all(p, scaled_point, exact_point)
    return _at_turning_points(p, scaled_point, exact_point, found)


def _at_turning_points(
    p: Prepared, point: np.ndarray, exact_point: tuple[Fraction, ...] | None, found: list[float]
) -> list[float]:
    """found, each t where the curve nearly stops moved to its exact turning point
    (intersect_refold.turning_points) when that is no farther from the point, exactly: there
    the point is a double root of the location, found to about 1e-8 only (the tip of a
    curve folded back along a line: 0.4999999917 for 1/2), as _at_turning_point does for
    the ends of a shared stretch."""
    out = []
    for t in found:
        if t not in (0.0, 1.0) and np.linalg.norm(p.at(t, 1)) <= 1e-6 * p.scale:
            target = [Fraction(x) for x in (exact_point or point.tolist())]
            rows = [[Fraction(x) for x in row] for row in (p._given_rows or p.pts.tolist())]
            for m in refold.turning_points(rows):
                moved = float(m)
                if abs(moved - t) < 1e-6 and _gap(p, moved, target) <= _gap(p, t, target):
                    t = moved
        out.append(t)
    return out


def _gap(p: Prepared, u: float, target: list[Fraction]) -> Fraction:
    """|p(u) − target|², exactly."""
    nums, den = p.exact_at(u)
    diffs = [Fraction(a, den) - b for a, b in zip(nums, target, strict=True)]
    return sum((d * d for d in diffs), Fraction(0))
