"""The kind of a meeting where one curve stops (issue #29, round 21).

A hit is "tangent" when the curves' tangent lines there are parallel. Where a curve's
derivative vanishes (an end whose first control points repeat, or a cusp) the derivative
gives no direction, and the classifiers took the zero vector for parallel to anything: a
curve starting on a line with zero speed, leaving it at a right angle, was "tangent". The
tangent line of a curve where it stops is that of its first derivative that does not
vanish there (the one-sided tangent at an end: p(s) − p(0) = p^(k)(0) s^k / k! + ...; the
cusp's tangent inside), and the kind is decided from it, on every class and path: a
derivative counts as vanishing when its difference rows at that parameter are within
STOPPED per degree of the size (the rounding rule of the meeting tolerance)."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any, TypeVar

import numpy as np

STOPPED = 64 * float(np.finfo(float).eps)  # relative, per unit of degree: a zero speed
TANGENT_SINE = 1e-6  # intersect.TANGENT_SINE: below this sine of the tangents' angle, "tangent"

H = TypeVar("H")


def _at(rows: np.ndarray, s: float) -> np.ndarray:
    work = rows
    while work.shape[0] > 1:
        work = work[:-1] + s * (work[1:] - work[:-1])
    out: np.ndarray = work[0]
    return out


def _stopped(rows: np.ndarray, s: float, size: float) -> bool:
    """The first difference rows at s within STOPPED per degree of the size (on Python
    floats: a few rows, for which numpy's per-call cost is most of the time)."""
    pts: list[list[float]] = rows.tolist()
    n = len(pts) - 1
    if n < 1:
        return False
    work = [
        [b - a for a, b in zip(r0, r1, strict=True)] for r0, r1 in zip(pts, pts[1:], strict=False)
    ]
    while len(work) > 1:
        work = [
            [a + s * (b - a) for a, b in zip(r0, r1, strict=True)]
            for r0, r1 in zip(work, work[1:], strict=False)
        ]
    bound = STOPPED * n * size
    return sum(x * x for x in work[0]) <= bound * bound


def direction(rows: np.ndarray, s: float, size: float) -> np.ndarray | None:
    """The tangent direction of the Bernstein curve `rows` (float, (n + 1, d)) at s: its
    first derivative (of order k, from the k-th differences of the rows, within a positive
    factor) above the rounding of the size; None where every one vanishes (a point)."""
    n = rows.shape[0] - 1
    work = rows
    for _ in range(n):
        work = np.diff(work, axis=0)
        v = _at(work, s)
        if float(np.linalg.norm(v)) > STOPPED * n * size:
            return v
    return None


def sine(u: np.ndarray, v: np.ndarray) -> float:
    nu, nv = float(np.linalg.norm(u)), float(np.linalg.norm(v))
    if u.size == 2:
        cross = abs(float(u[0] * v[1] - u[1] * v[0]))
    else:
        cross = float(np.linalg.norm(np.cross(u, v)))
    return cross / (nu * nv)


def _moving(rows: np.ndarray, weights: np.ndarray | None, s: float) -> np.ndarray:
    """Rows whose Bernstein curve H has H(u) = w(u) (C(u) − C(s)) for the rational curve C of
    rows and weights (C itself when weights is None: shifting by C(s) does not change its
    derivatives). C(u) − C(s) = H(u) / w(u) with w > 0, and H(s) = 0: the first derivative of
    H not vanishing at s has the direction of C's, and H'(s) = w(s) C'(s)."""
    if weights is None:
        return rows
    point = _at(rows * weights[:, None], s) / float(_at(weights[:, None], s)[0])
    out: np.ndarray = weights[:, None] * (rows - point)
    return out


def one_sided(
    hits: Sequence[H],
    p_rows: np.ndarray,
    q_rows: np.ndarray,
    size: float,
    weights: tuple[np.ndarray | None, np.ndarray | None] = (None, None),
    tangent_sine: float = TANGENT_SINE,
) -> list[H]:
    """hits (Intersection-like: s, t, kind, _replace), each "tangent" hit where either
    curve stops (p_rows at s, q_rows at t: float Bernstein rows, parameters in
    [0, 1]; rational with `weights`) classified again by the tangent directions of
    `direction`."""
    out: list[H] = []
    for h in hits:
        hit: Any = h
        # a zero derivative is taken for parallel to anything (the sine is 0), so a stop is
        # always classified "tangent" first: only those hits are looked at again (cheap)
        if hit.kind == "tangent":
            a = _moving(p_rows, weights[0], hit.s)
            b = _moving(q_rows, weights[1], hit.t)
            sa = size * (1.0 if weights[0] is None else float(np.abs(weights[0]).max()))
            sb = size * (1.0 if weights[1] is None else float(np.abs(weights[1]).max()))
            if _stopped(a, hit.s, sa) or _stopped(b, hit.t, sb):
                u, v = direction(a, hit.s, sa), direction(b, hit.t, sb)
                if u is not None and v is not None:
                    kind = "tangent" if sine(u, v) <= tangent_sine else "transversal"
                    hit = hit._replace(kind=kind)
        out.append(hit)
    return out


STOPPED_END = 1e-6  # relative to the domain: a hit this close to an end is tried at the end


def at_ends(
    hits: Sequence[H],
    p_at: Callable[[float], np.ndarray],
    q_at: Callable[[float], np.ndarray],
    domains: tuple[tuple[float, float], tuple[float, float]],
    bound: float,
) -> list[H]:
    """hits, each parameter within STOPPED_END of its domain's end moved to that end when the
    end point is no farther from the other curve's point than the hit's own plus `bound`
    (the meeting rounding): where a curve stops at its end (a repeated end control point)
    its distance to the other grows like the parameter's square, and the searches placed
    such a meeting 1.8e-9 (trigonometric) or 5e-17 to 2.2e-16 (rational) from the end
    (issue #29 round 21). A crossing at a clear speed that far from the end is that speed
    times its distance away, far beyond the bound."""
    out: list[H] = []
    for h in hits:
        hit: Any = h
        if hit.kind != "coincident":
            for which, (lo, hi) in enumerate(domains):
                x = hit.s if which == 0 else hit.t
                y = hit.t if which == 0 else hit.s
                own, other = (p_at, q_at) if which == 0 else (q_at, p_at)
                for end in (lo, hi):
                    if x == end or abs(x - end) > STOPPED_END * (hi - lo):
                        continue
                    there = other(y)
                    gap_end = float(np.linalg.norm(own(end) - there))
                    if gap_end <= float(np.linalg.norm(own(x) - there)) + bound:
                        hit = hit._replace(s=end) if which == 0 else hit._replace(t=end)
                        break
        out.append(hit)
    return out
