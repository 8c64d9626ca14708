"""Intersections, self-intersections and point location for classical Bézier curves.

The method is the established geometric one (Sederberg & Nishita's subdivision with bounding
boxes, as in the `bezier` package's geometric strategy), followed by Newton's method on the
exact polynomials:

1. Subdivision: both curves are halved level by level; a pair of pieces survives while
   their axis-aligned bounding boxes (which contain the pieces, by the convex hull
   property) overlap. Surviving pairs at the last level are grouped into clusters of
   neighbouring pieces; each cluster gives Newton starting points.
2. Newton on F(s, t) = p(s) - q(t) (Gauss-Newton when d > 2), in floats, then polished with
   the residual evaluated exactly in Fractions (every float is a rational, so the curves'
   exact values are known): the parameters are then right to a few ulps even where the
   float residual is all rounding (nearly parallel curves).
3. Tangent intersections make F's Jacobian singular, so Newton on F stalls near sqrt(eps).
   There Gauss-Newton runs on F stacked with the cross products of p'(s) and q'(t), whose
   root is regular when the curvatures differ; when they agree too (a crossing of higher
   contact) the exact residuals let the linear convergence run to full precision.
4. End points are located on the other curve first (a one-dimensional, well-posed problem).
   When two such end point pairs bound pieces that are the same curve, the curves are
   coincident there: the two pairs are reported with kind "coincident", and subdivision
   skips the shared stretch (where boxes would never separate).

Meeting points: the curves meet only where they are within the rounding of evaluating them,
a bound from the control points (never a fixed 1e-10): a Newton hit's exact residual within
_root_bound, an end within _rounding_at of the other curve where it is located; shared
stretches and common lines at _root_bound. The certificate holds its roots to _root_bound.
"""

from __future__ import annotations

import functools
from fractions import Fraction
from typing import NamedTuple

import numpy as np

from . import intersect_certify as cert
from . import intersect_exact as _exact_iso
from . import intersect_kind as _kind
from . import intersect_pairs as _pairs_engine
from . import intersect_refold as refold
from . import intersect_subdivide as sub
from .intersect_locate import (  # the point location half, and the tolerances both share
    ON_CURVE,
    ROOT_RESIDUAL,
    SAME_ROOT,
    WIDE_PIECE,
    _isolate_ends,
    _starts,
)
from .intersect_locate import locate_all as locate_all  # Curve.locate's entry
from .intersect_locate import locate_point as locate_point  # (a user's point)
from .intersect_prepared import NORMAL_EXPONENT, _exact_difference
from .intersect_prepared import Prepared as Prepared

# relative, per unit of degree: pieces whose boxes or fat lines are this close still overlap.
# It covers the rounding of repeated halving (a few ulps of the control points' size per
# level and degree) and no more, so that curves 1e-13 of their size apart are still told apart
BOX_SLACK = 64 * float(np.finfo(float).eps)
ISOLATED_SAME = 1e-13  # two polished roots of isolated pieces this close are one (a shared edge)
MERGE_RADIUS = 1e-3  # hits closer than this are compared for being one (see _add)
# ... and are one when the curves stay this close (relative, per unit of degree) all the way
# between them: a contact of high order, which refinement approaches only linearly, so that
# starts stop at different points of it. Rounding level, so that two crossings of curves that
# separate by more than ~1e-13 of their size between them stay two.
MERGE_GAP = 64 * float(np.finfo(float).eps)
NEAR_FOUND = 1e-6  # float Newton this close to a refined root has found that root
TANGENT_SINE = 1e-6  # below this sine of the angle between tangents, refine as tangent
# exact input: a hit whose tangents' sine is below this may be two crossings merged (_add
# merges hits whose curves stay within MERGE_GAP between them: crossings 1e-7 apart on a
# parabola), so the exact isolation decides it, as it decides a "tangent" hit. Two crossings
# merged at that gap have a sine of about sqrt(curvature x gap): 1e-4 covers curvatures up to
# ~1e4 of the size
EXACT_CHECK_SINE = 1e-4
# relative, per unit of degree: a self-intersection "loop" whose points all lie this close to
# each other is what rounding makes of a cusp (p(s) - p(t) vanishes to third order there), not
# a crossing. Evaluating a degree-n curve rounds by at most about n eps of its size (de
# Casteljau: n levels of one convex combination each), so two points of a cusp can seem apart
# by twice that; 8 eps per degree leaves a factor of 4. A loop above it is real at the
# precision of the input: the cubic (0,0), (a,1), (1-a,1), (1,0) with a = 1 + 8/3 10^-14
# crosses itself at s = 1/2 -+ 1e-7 and its loop spans 3e-14 of its size, 18 times the bound.
# It was 1e-8 (undocumented), which dropped that cubic's loop up to a = 1 + 8/3 10^-9.
CUSP_LOOP = 8 * float(np.finfo(float).eps)
# a self-crossing that rounding of the points (SELF_ROUNDING per degree of the size: n eps
# for de Casteljau's n levels, times 4) can move by more than SELF_PLACED in parameter is,
# for float input, polished on the divided difference (intersect_self_polish), and for
# exact rational input decided exactly. A crossing at a clear angle, with speeds near the
# size, is placed to ~1e-15 and keeps its answer and speed.
SELF_PLACED = 1e-13
SELF_ROUNDING = 4 * float(np.finfo(float).eps)
# the tolerances above and the subdivision's, as the compiled careful path takes them
# (settle_compiled.Knobs names the order)
SETTLE = (
    ON_CURVE,
    SAME_ROOT,
    ISOLATED_SAME,
    MERGE_RADIUS,
    MERGE_GAP,
    ROOT_RESIDUAL,
    BOX_SLACK,
    WIDE_PIECE,
    NEAR_FOUND,
    TANGENT_SINE,
    sub.DEPTH,
    sub.MAX_ROWS,
    sub.NEWTON_STEPS,
    sub.INSIDE,
    sub.CONE_MARGIN,
)
_KINDS = {-1: "coincident", 0: "tangent", 1: "transversal"}  # settle_compiled's kind codes


class Intersection(NamedTuple):
    """One intersection: p(s) = q(t). kind is "transversal", "tangent" or "coincident"
    (the two ends of a stretch the curves share)."""

    s: float
    t: float
    kind: str


# ---------------------------------------------------------------------------- Newton
def _residual(p: Prepared, q: Prepared, s: float, t: float, exact: bool) -> np.ndarray:
    if exact:
        return _exact_difference(p.exact_at(s), q.exact_at(t))
    diff: np.ndarray = p.at(s) - q.at(t)
    return diff


def _gauss_newton_step(u: np.ndarray, v: np.ndarray, f: np.ndarray) -> tuple[float, float]:
    """The least-squares (ds, dt) of u ds + v dt = -f, from the 2x2 normal equations
    (lstsq when they are singular)."""
    a, b, c = float(u @ u), float(u @ v), float(v @ v)
    det = a * c - b * b
    if det > 1e-24 * a * c:
        g, h = -float(u @ f), -float(v @ f)
        return (c * g - b * h) / det, (a * h - b * g) / det
    step = np.linalg.lstsq(np.column_stack([u, v]), -f, rcond=None)[0]
    return float(step[0]), float(step[1])


def _newton(p: Prepared, q: Prepared, s: float, t: float) -> tuple[float, float, str]:
    """Newton (Gauss-Newton for d > 2) on p(s) - q(t). Status "out" when it leaves the
    domain, "converged", or "slow" when convergence is only linear (a tangency, refined by
    _tangent_refine) or the iterations ran out."""
    prev = np.inf
    for it in range(40):
        ps, dps = p.at_with_tangent(s)
        qt, dqt = q.at_with_tangent(t)
        ds, dt = _gauss_newton_step(dps, -dqt, ps - qt)
        s, t = s + ds, t + dt
        if not (-0.5 < s < 1.5 and -0.5 < t < 1.5) or not (np.isfinite(s) and np.isfinite(t)):
            return s, t, "out"
        size = abs(ds) + abs(dt)
        if size < 1e-15:
            return s, t, "converged"
        if it >= 8 and size > 0.25 * prev:
            break
        prev = size
    return s, t, "slow"


def _polish(
    p: Prepared, q: Prepared, s: float, t: float, steps: int = 4
) -> tuple[float, float, bool]:
    """Newton steps with the residual evaluated exactly; True when they converged (the
    last step below 1e-15: quadratic convergence, a regular root)."""
    for _ in range(steps):
        ds, dt = _gauss_newton_step(p.at(s, 1), -q.at(t, 1), _residual(p, q, s, t, True))
        s, t = s + ds, t + dt
        if abs(ds) + abs(dt) < 1e-17:
            break
    return s, t, abs(ds) + abs(dt) < 1e-15


@functools.cache
def _pairs(dim: int) -> tuple[np.ndarray, np.ndarray]:
    return np.triu_indices(dim, 1)


def _cross_terms(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """u_i v_j - u_j v_i for i < j: zero exactly when u and v are parallel."""
    i, j = _pairs(u.shape[-1])
    cross: np.ndarray = u[..., i] * v[..., j] - u[..., j] * v[..., i]
    return cross


def _tangent_residual(
    p: Prepared, q: Prepared, s: float, t: float, weight: float, exact: bool
) -> np.ndarray:
    if exact:
        diff = _exact_difference(p.exact_at(s), q.exact_at(t))
        (a, da), (b, db) = p.exact_at(s, 1), q.exact_at(t, 1)
        dim = len(a)
        cross = [
            (a[i] * b[j] - a[j] * b[i]) / (da * db) * weight
            for i in range(dim)
            for j in range(i + 1, dim)
        ]
        return np.concatenate([diff, cross])
    return np.concatenate([p.at(s) - q.at(t), _cross_terms(p.at(s, 1), q.at(t, 1)) * weight])


def _tangent_refine(
    p: Prepared, q: Prepared, s: float, t: float, phases: tuple[bool, ...] = (False, True)
) -> tuple[float, float]:
    """Gauss-Newton on [p(s) - q(t); w (p'(s) x q'(t))], first with float residuals, then
    with exact ones (which stay meaningful where floats are all rounding, so the linear
    convergence at a root of higher contact runs on). Each phase ends when its steps stop
    shrinking; the point after the smallest step is kept."""
    d1p, d1q = p.at(s, 1), q.at(t, 1)
    weight = max(p.scale, q.scale) / max(float(np.linalg.norm(d1p) * np.linalg.norm(d1q)), 1e-300)
    for exact in phases:
        best = (np.inf, s, t)
        stalled = 0
        for _ in range(100):
            res = _tangent_residual(p, q, s, t, weight, exact)
            if not res.any():
                best = (0.0, s, t)
                break
            d1p, d1q = p.at(s, 1), q.at(t, 1)
            d2p, d2q = p.at(s, 2), q.at(t, 2)
            jac = np.vstack(
                [
                    np.column_stack([d1p, -d1q]),
                    np.column_stack([_cross_terms(d2p, d1q), _cross_terms(d1p, d2q)]) * weight,
                ]
            )
            step = np.linalg.lstsq(jac, -res, rcond=None)[0]
            if not np.all(np.isfinite(step)):
                break
            s, t = s + float(step[0]), t + float(step[1])
            size = abs(float(step[0])) + abs(float(step[1]))
            if size < best[0]:
                best, stalled = (size, s, t), 0
            else:
                stalled += 1
            if size < 1e-17 * (1 + abs(s) + abs(t)) or stalled >= 3:
                break
        s, t = best[1], best[2]
    return s, t


def _sine(p: Prepared, q: Prepared, s: float, t: float) -> float:
    u, v = p.at(s, 1), q.at(t, 1)
    nu, nv = float(np.linalg.norm(u)), float(np.linalg.norm(v))
    if nu == 0.0 or nv == 0.0:
        return 0.0
    return float(np.linalg.norm(_cross_terms(u, v))) / (nu * nv)


def _near_found(s: float, t: float, found: list[Intersection]) -> bool:
    return any(abs(s - f.s) < NEAR_FOUND and abs(t - f.t) < NEAR_FOUND for f in found)


def _on_both(p: Prepared, q: Prepared, s: float, t: float) -> bool:
    """p(s) = q(t) to rounding: the exact residual within ROOT_RESIDUAL of the curves' size."""
    return bool(np.linalg.norm(_residual(p, q, s, t, True)) <= _root_bound(p, q))


def _solve_from(
    p: Prepared, q: Prepared, s: float, t: float, found: list[Intersection], isolated: bool = False
) -> Intersection | None:
    """The intersection Newton reaches from (s, t), refined. isolated: (s, t) is already a
    float root in pieces that hold no other (see intersect_subdivide), so no shortcut may
    identify it with a root found before."""
    s0, t0 = s, t
    s, t, status = _newton(p, q, s, t)
    if status == "out":
        # float Newton is thrown far off near a tangency (the Jacobian is nearly singular);
        # the tangent system is regular there, so refine from the start instead
        s, t = _tangent_refine(p, q, s0, t0, (False,))
        if not (-0.5 < s < 1.5 and -0.5 < t < 1.5):
            return None
    # Newton in floats stalls within ~1e-8 of a tangent root: a start that lands that close
    # to a root already refined is that root (skips the costly exact refinement)
    if not isolated and _near_found(s, t, found):
        return None
    scale = max(p.scale, q.scale)
    if np.linalg.norm(_residual(p, q, s, t, False)) > 1e-6 * scale:
        return None  # Newton wandered off; a real root near a start converges closer
    # a root from isolated pieces is transversal (a tangency puts one tangent line in both
    # pieces' cones, which isolation rules out), however small the angle: two crossings 1e-6
    # apart meet at a sine below TANGENT_SINE. Elsewhere a small sine means a tangency, where
    # exact-residual Newton can stall at a point that merely looks converged
    polished = False
    if isolated or _sine(p, q, s, t) > TANGENT_SINE:
        # an isolated root may sit close to others (a near-double crossing), where float
        # Newton's root is off by far more than an ulp: allow polishing the time to get there
        ps, pt, polished = _polish(p, q, s, t, 12 if isolated else 4)
        # ... where, with the columns of the float Jacobian nearly parallel, its last steps
        # can cycle at a few ulps; the residual then says whether it got there
        polished = polished or (isolated and _on_both(p, q, ps, pt))
    if polished:
        s, t, kind = ps, pt, "transversal"
    else:
        s, t = _tangent_refine(p, q, s, t, (False,))
        if _near_found(s, t, found):  # before the costly exact phase
            return None
        s, t = _tangent_refine(p, q, s, t, (True,))
        kind = "tangent" if _sine(p, q, s, t) <= TANGENT_SINE else "transversal"
    # a root: the exact residual at rounding level (a tangency refined through the regular
    # tangent system converges as far as a crossing does; a point that stays farther off is
    # a near miss, or a stall next to a root of another kind)
    if not _on_both(p, q, s, t):
        return None
    tol = 1e-12
    if not (-tol <= s <= 1 + tol and -tol <= t <= 1 + tol):
        return None
    return Intersection(float(min(max(s, 0.0), 1.0)), float(min(max(t, 0.0), 1.0)), kind)


# ---------------------------------------------------------------------------- locate
def _same_piece(p: Prepared, q: Prepared, s0: float, s1: float, t0: float, t1: float) -> bool:
    """p over [s0, s1] and q over [t0, t1] are one curve: the polynomials agree at
    max degree + 2 points."""
    u = np.linspace(0.05, 0.95, max(p.degree, q.degree) + 2)
    tol = _root_bound(p, q)
    return all(
        np.linalg.norm(p.at(s0 + x * (s1 - s0)) - q.at(t0 + x * (t1 - t0))) <= tol for x in u
    )


def _same_image(p: Prepared, q: Prepared, s0: float, s1: float, t0: float, t1: float) -> bool:
    """p over [s0, s1] and q over [t0, t1] trace one arc under some parameterisation (not
    only an affine one, which _same_piece checks): each stretch runs along the other."""
    return _runs_along(p, q, s0, s1, t0, t1) and _runs_along(q, p, t0, t1, s0, s1)


def _runs_along(p: Prepared, q: Prepared, s0: float, s1: float, t0: float, t1: float) -> bool:
    """degree(p) degree(q) + 1 points of p's stretch lie on q's stretch, each at exactly one
    t, in the same order. By Bezout, that many common points put p's stretch on q's
    algebraic curve; the order rules out a stretch that folds back over q. It does not rule
    out q's stretch reaching beyond p's (on a line that q folds back along, q's stretch can
    cover p's and more): _same_image asks both ways."""
    count = max(p.degree * q.degree + 1, 3)
    fractions = (np.arange(count) + 0.5) / count
    middle_first = [count // 2] + [k for k in range(count) if k != count // 2]
    lo, hi = min(t0, t1) - SAME_ROOT, max(t0, t1) + SAME_ROOT
    located: dict[int, float] = {}
    for k in middle_first:
        point = p.at(s0 + fractions[k] * (s1 - s0))
        on_q = [t for t in locate_all(q, point, within=_root_bound(p, q)) if lo <= t <= hi]
        if len(on_q) != 1:
            return False
        located[k] = on_q[0]
    steps = np.diff([located[k] for k in range(count)]) * np.sign(t1 - t0)
    return bool(np.all(steps > 0))


def _dedupe(found: list[Intersection], new: Intersection, same: float = SAME_ROOT) -> bool:
    return any(abs(new.s - old.s) < same and abs(new.t - old.t) < same for old in found)


def _dedupe_isolated(found: list[Intersection], new: Intersection) -> bool:
    """An isolated piece's root is one already found within ISOLATED_SAME; or, held at an
    end of one curve where a hit at that same end was already located, within SAME_ROOT
    in the other parameter: the other curve passes through that end point once there
    (twice within 1e-9 would need a cusp). Without this, a piece whose root lies just past
    an end (a segment ending 1e-14 beside another) was clamped to the end and reported a
    second time, 1e-13 from the located end."""
    if _dedupe(found, new, ISOLATED_SAME):
        return True
    return any(
        (new.s == old.s and new.s in (0.0, 1.0) and abs(new.t - old.t) < SAME_ROOT)
        or (new.t == old.t and new.t in (0.0, 1.0) and abs(new.s - old.s) < SAME_ROOT)
        for old in found
    )


Box = tuple[float, float, float, float]  # s0, s1, t0, t1 of a coincident stretch


def normalised(p: Prepared, q: Prepared) -> tuple[Prepared, Prepared]:
    """p and q divided by one power of two (exact: the same parameters) when their size is
    beyond 2^±NORMAL_EXPONENT: the tests multiply up to four coordinates, so lines crossing at
    1e-100 came back "tangent", at 1e-200 1e-10 off, and at 5e307 not at all."""
    top = max(p.exponent, q.exponent)
    if -NORMAL_EXPONENT <= top <= NORMAL_EXPONENT:
        return p, q
    return p.scaled(top), q.scaled(top)


def intersect(p: Prepared, q: Prepared) -> list[Intersection]:
    """Every intersection of p and q, sorted by s: the certified fast path when both are
    floats exactly, else (or where it does not certify) the careful path: compiled
    (settle_one) where it can, in Python otherwise."""
    p, q = normalised(p, q)
    found = _compiled_pair(p, q)
    if found is not None:
        return _decided_exactly(p, q, found)
    _check_pair(p, q)
    results: list[list[Intersection]] = [[]]
    _careful_pairs([(p, q)], [0], results)  # declined (or exact input): not certified again
    return _decided_exactly(p, q, results[0])


def _decided_exactly(p: Prepared, q: Prepared, hits: list[Intersection]) -> list[Intersection]:
    """hits, or the exact answer where intersect_exact.decided gives one; where a curve
    stops (zero speed), its kind from the one-sided tangent (intersect_kind)."""
    got = _decided(p, q, hits)
    if all(h.kind != "tangent" for h in got):  # a stop is classified "tangent" first
        return got
    return _kind.one_sided(got, p.pts, q.pts, max(p.scale, q.scale))


def _decided(p: Prepared, q: Prepared, hits: list[Intersection]) -> list[Intersection]:
    if p._given_rows is None or q._given_rows is None:  # float input: decided gives none
        return hits
    kinds = [
        "tangent" if h.kind == "transversal" and p.dim <= 3 and _ill_posed(p, q, h) else h.kind
        for h in hits
    ]
    got = _exact_iso.decided(p._given_rows, q._given_rows, p.dim, q.dim, kinds)
    if got is None:
        return hits
    return [Intersection(s, t, "tangent" if flat else "transversal") for s, t, flat in got]


def _ill_posed(p: Prepared, q: Prepared, h: Intersection) -> bool:
    """A crossing that may stand for several merged ones (_add): the tangents nearly parallel
    (sine below EXACT_CHECK_SINE), or one curve nearly stopped there (speed below
    EXACT_CHECK_SINE of its degree times its extent: by a near-cusp, whose tiny loop
    crosses a line through it twice more within the merge gap, 1e-5 apart)."""
    if _sine(p, q, h.s, h.t) < EXACT_CHECK_SINE:
        return True
    return any(
        float(np.linalg.norm(c.at(x, 1))) < EXACT_CHECK_SINE * c.degree * c._span
        for c, x in ((p, h.s), (q, h.t))
    )


def _compiled_pair(p: Prepared, q: Prepared) -> list[Intersection] | None:
    """The pair's answer from the compiled kernels (numba): the certificate, then the careful
    path compiled where it declines, in one call (intersect_pairs); None when neither
    answers (not compiled, input that is not floats exactly, or declined by both). Both
    kernels decline a curve that is a point, so _check_pair (its error) runs only on the way
    to the careful path in Python: on a fresh curve it costs a share of a small pair's whole
    time."""
    if not (cert.in_use() and p.floats_exact and q.floats_exact and p.dim == q.dim >= 2):
        return None
    found = _pairs_engine.pair(p.pts, q.pts, BOX_SLACK, ROOT_RESIDUAL, SETTLE)
    if found is None:
        return None
    return [Intersection(x, y, _KINDS[int(kind)]) for x, y, kind in found]


def float_pair(a: np.ndarray, b: np.ndarray) -> list[Intersection] | None:
    """intersect's answer for two curves whose float Bézier points a, b (a curve's own: C
    order) are the curves exactly, their largest |coordinate| within 2^±100 (the caller
    knows: normalised leaves them as they are), with no Prepared built (a share of a small
    pair's whole time, issue #29): the compiled kernels' answer where they run (numba, one
    dimension >= 2) and answer; None otherwise, and intersect on the Prepared forms then
    gives the answer (trying the kernels again where they declined: such a pair takes the
    careful path in Python, whose cost that try does not change)."""
    if not (a.shape[1] == b.shape[1] >= 2 and cert.in_use()):
        return None
    found = _pairs_engine.pair(a, b, BOX_SLACK, ROOT_RESIDUAL, SETTLE, own=True)
    if found is None:
        return None
    return [Intersection(x, y, _KINDS[int(kind)]) for x, y, kind in found]


def compiled_in_use() -> bool:
    """Whether the compiled kernels run (numba installed and not disabled)."""
    return cert.in_use()


def float_pairs(
    curves: list[np.ndarray], first: list[int], second: list[int]
) -> list[list[Intersection] | None]:
    """float_pair for many pairs in one compiled call: pair k is curves[first[k]] against
    curves[second[k]], each pair one float_pair takes (the caller checks its conditions),
    all of one dimension; None for a pair both kernels decline."""
    found = _pairs_engine.pairs(curves, first, second, BOX_SLACK, ROOT_RESIDUAL, SETTLE)
    return [
        None if hits is None else [Intersection(x, y, _KINDS[int(kind)]) for x, y, kind in hits]
        for hits in found
    ]


def intersect_pairs(
    pairs: list[tuple[Prepared, Prepared]], compiled: list[bool] | None = None
) -> list[list[Intersection]]:
    """Every intersection of each pair, sorted by s. With numba, each pair whose floats are
    the curves exactly goes through the compiled kernels as intersect takes it (unless
    compiled[k] is False: the kernels declined it already, in intersect_many's batch). The
    rest, and those both kernels decline, take the careful way in Python together, pairs of
    equal degrees and dimension in one group: the end points and shared stretches pair by
    pair, the subdivision in one set of arrays (intersect_subdivide.isolate), then
    refinement pair by pair."""
    pairs = [normalised(p, q) for p, q in pairs]
    results: list[list[Intersection]] = [[] for _ in pairs]
    groups: dict[tuple[int, int, int], list[int]] = {}
    for k, (p, q) in enumerate(pairs):
        compiled_hits = _compiled_pair(p, q) if compiled is None or compiled[k] else None
        if compiled_hits is not None:
            results[k] = compiled_hits
        else:
            _check_pair(p, q)
            groups.setdefault((p.degree, q.degree, p.dim), []).append(k)
    for members in groups.values():
        _careful_pairs(pairs, members, results)
    # exact input: a tangency is decided exactly, whichever path found it (a Fraction whose
    # float is exact takes the compiled kernels too)
    return [_decided_exactly(p, q, hits) for (p, q), hits in zip(pairs, results, strict=True)]


def _careful_pairs(
    pairs: list[tuple[Prepared, Prepared]], members: list[int], results: list[list[Intersection]]
) -> None:
    # the end points' subdivisions of every pair of the group in two calls (one where the
    # two curves of each pair have one degree)
    ps, qs = [pairs[k][0] for k in members], [pairs[k][1] for k in members]
    if ps[0].degree == qs[0].degree:
        on_both = _isolate_ends(qs + ps, ps + qs)
        on_q, on_p = on_both[: len(members)], on_both[len(members) :]
    else:
        on_q, on_p = _isolate_ends(qs, ps), _isolate_ends(ps, qs)
    setups = {k: _pair_setup(*pairs[k], on_q[g], on_p[g]) for g, k in enumerate(members)}
    iso = sub.isolate(
        np.stack([pairs[k][0].pts for k in members]),
        np.stack([pairs[k][1].pts for k in members]),
        np.array([_slack(*pairs[k]) for k in members]),
        [(g, *box) for g, k in enumerate(members) for box in setups[k][1]],
    )
    for g, k in enumerate(members):
        p, q = pairs[k]
        found, skip = setups[k]
        roots = iso.root_pair == g
        left = iso.left_pair == g
        results[k] = _pair_finish(
            p,
            q,
            found,
            skip,
            list(zip(iso.root_s[roots].tolist(), iso.root_t[roots].tolist(), strict=True)),
            _starts(iso.left_s0[left], iso.left_t0[left], iso.left_width[left]),
        )


def _slack(p: Prepared, q: Prepared) -> float:
    return float(BOX_SLACK * max(p.degree, q.degree) * max(p.scale, q.scale))


def _root_bound(p: Prepared, q: Prepared) -> float:
    return float(ROOT_RESIDUAL * max(p.degree, q.degree) * max(p.scale, q.scale))


def _check_pair(p: Prepared, q: Prepared) -> None:
    if p.dim != q.dim:
        raise ValueError(f"cannot intersect curves of dimensions {p.dim} and {q.dim}")
    if p.dim < 2:
        raise ValueError(
            "intersection needs dimension >= 2: curves on a line meet along whole intervals"
        )
    for name, c in (("the first", p), ("the second", q)):
        if c.is_point:
            raise ValueError(f"{name} curve is a single point: use locate() on the other")


def _pair_setup(
    p: Prepared,
    q: Prepared,
    on_q: tuple[sub.Isolated | None, sub.Isolated | None] = (None, None),
    on_p: tuple[sub.Isolated | None, sub.Isolated | None] = (None, None),
) -> tuple[list[Intersection], list[Box]]:
    """The end points located on the other curve, and the shared stretches they bound:
    (hits so far, rectangles of shared stretches for subdivision to skip). on_q, on_p: the
    subdivision's candidates for p's end points on q and q's on p (_isolate_ends), where
    found together with other pairs'; locate_all subdivides for those that are None."""
    ends: list[Intersection] = []
    for s_end in (0, 1):
        for t in locate_all(
            q, p.pts[-1 if s_end else 0], p.exact_row(-1 if s_end else 0), None, True, on_q[s_end]
        ):
            cand = Intersection(float(s_end), t, "transversal")
            if not _dedupe(ends, cand):
                ends.append(cand)
    for t_end in (0, 1):
        for s in locate_all(
            p, q.pts[-1 if t_end else 0], q.exact_row(-1 if t_end else 0), None, True, on_p[t_end]
        ):
            cand = Intersection(s, float(t_end), "transversal")
            if not _dedupe(ends, cand):
                ends.append(cand)
    ends = [
        e._replace(kind="tangent") if _sine(p, q, e.s, e.t) <= TANGENT_SINE else e for e in ends
    ]
    skip: list[Box] = []
    coincident: list[Intersection] = []
    for i, a in enumerate(ends):
        for b in ends[i + 1 :]:
            if abs(a.s - b.s) < SAME_ROOT or abs(a.t - b.t) < SAME_ROOT:
                continue
            if _same_piece(p, q, a.s, b.s, a.t, b.t) or _same_image(p, q, a.s, b.s, a.t, b.t):
                lo, hi = sorted((a, b))
                # an end pair bounding two stretches (a curve turning back along the other)
                # is listed once, as self_intersections lists it
                coincident += [
                    h._replace(kind="coincident")
                    for h in (lo, hi)
                    if h._replace(kind="coincident") not in coincident
                ]
                skip.append((lo.s, hi.s, min(a.t, b.t), max(a.t, b.t)))
    if coincident:
        coincident = [_at_turning_point(p, q, h) for h in coincident]
    found = list(coincident)
    for e in ends:
        if not _dedupe(found, e):
            _add(found, e, p, q)
    if not coincident:
        _refuse_collinear_overlap(p, q)
    return found, skip


def _at_turning_point(p: Prepared, q: Prepared, hit: Intersection) -> Intersection:
    """An end of a shared stretch where one curve turns back along the other (its whole
    derivative vanishes: a double root of the location, found only to about 1e-8) moved to
    that turning point, exact in rationals (intersect_refold.turning_points), when the exact
    residual there is no larger."""
    for curve, value, other in ((p, hit.s, hit.t), (q, hit.t, hit.s)):
        if value in (0.0, 1.0) or np.linalg.norm(curve.at(value, 1)) > 1e-6 * curve.scale:
            continue
        rows = [[Fraction(x) for x in row] for row in (curve._given_rows or curve.pts.tolist())]
        for m in refold.turning_points(rows):
            moved = float(m)
            if abs(moved - value) < 1e-6:
                s, t = (moved, other) if curve is p else (other, moved)
                before = np.linalg.norm(_residual(p, q, hit.s, hit.t, True))
                if np.linalg.norm(_residual(p, q, s, t, True)) <= before:
                    hit = hit._replace(s=s, t=t)
    return hit


def _pair_finish(
    p: Prepared,
    q: Prepared,
    found: list[Intersection],
    skip: list[Box],
    isolated: list[tuple[float, float]],
    starts: list[tuple[float, float]],
) -> list[Intersection]:
    """Refine the subdivision's roots (isolated: one per pair of pieces, transversal) and
    Newton from the starts of unresolved pieces (tangencies), into found."""
    for s, t in isolated:
        hit = _solve_from(p, q, s, t, found, isolated=True)
        if hit is not None and not _dedupe_isolated(found, hit):
            _add(found, hit, p, q)
    for s, t in starts:
        if any(s0 <= s <= s1 and t0 <= t <= t1 for s0, s1, t0, t1 in skip):
            continue
        hit = _solve_from(p, q, s, t, found)
        if hit is None or _dedupe(found, hit):
            continue
        if any(s0 < hit.s < s1 for s0, s1, _, _ in skip):
            continue
        _add(found, hit, p, q)
    return sorted(found)


def _add(found: list[Intersection], hit: Intersection, p: Prepared, q: Prepared) -> None:
    """Append hit, unless it is one already found: near it, with the curves staying within
    MERGE_GAP of each other all the way between the two. At a contact of high order the
    residual is below tolerance over a whole small neighbourhood and refinement converges
    only linearly, so starts stop at different points of it; the one with the smaller
    exact residual stays."""
    for k, old in enumerate(found):
        if abs(hit.s - old.s) < MERGE_RADIUS and abs(hit.t - old.t) < MERGE_RADIUS:
            x = np.linspace(0.0, 1.0, 9)
            gap = max(
                q.normal_offset(p.at(old.s + u * (hit.s - old.s)), old.t + u * (hit.t - old.t))
                for u in x
            )
            if gap <= MERGE_GAP * max(p.degree, q.degree) * max(p.scale, q.scale):
                if old.kind != "coincident" and _quality(p, q, hit) < _quality(p, q, old):
                    found[k] = hit
                return
    found.append(hit)


def _quality(p: Prepared, q: Prepared, hit: Intersection) -> float:
    return float(np.linalg.norm(_tangent_residual(p, q, hit.s, hit.t, 1.0, True)))


def _common_line(pts: np.ndarray, tol: float) -> tuple[np.ndarray, float] | None:
    """(unit direction, extent) of the line all the points lie on (within tol), or None."""
    base = pts[0]
    far = pts[np.argmax(np.linalg.norm(pts - base, axis=1))]
    length = float(np.linalg.norm(far - base))
    if length == 0.0:
        return None
    unit = (far - base) / length
    rel = pts - base
    off_line = np.linalg.norm(rel - np.outer(rel @ unit, unit), axis=1).max()
    return (unit, length) if off_line <= tol else None


def _refuse_collinear_overlap(p: Prepared, q: Prepared) -> None:
    """Two curves on one line whose images overlap along an interval meet in a continuum of
    parameter pairs; unless they are one curve up to an affine change of parameter
    (reported as coincident above) there are no end pairs to report, so say so."""
    line = _common_line(np.vstack([p.pts, q.pts]), _root_bound(p, q))
    if line is None:
        return
    unit, length = line
    u = np.linspace(0.0, 1.0, 1025)
    image_p = np.array([p.at(x) for x in u]) @ unit
    image_q = np.array([q.at(x) for x in u]) @ unit
    overlap = min(image_p.max(), image_q.max()) - max(image_p.min(), image_q.min())
    if overlap > 1e-9 * length:
        raise ValueError(
            "the curves lie on one line and overlap along an interval, with parametrisations "
            "that are not affinely related: their intersection is not a set of points"
        )
