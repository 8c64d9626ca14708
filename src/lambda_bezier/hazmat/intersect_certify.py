"""The fast path of curve intersection: the common transversal case, with a certificate.

Most pairs of curves cross transversally away from their ends, or not at all. For those the
careful path of `intersect` (end points located on the other curve, shared stretches,
Newton polished with the residual in exact rationals, tangent refinement) costs far more than
the answer needs. `certify` runs a pair's whole pipeline in one call, compiled with numba
when it is installed (certify_compiled; numpy otherwise, through intersect_subdivide), and
returns its crossings only when every step is covered by the certificate below; otherwise it
returns None and the caller runs the careful path on that pair. The answers are the careful
path's: the fast path only answers where the two agree by construction.

The certificate, for a pair p, q of classical Bézier curves with float control points:

1. subdivision ends with every pair of pieces either *dropped* (boxes, or fat lines in the
   plane, apart by more than the slack: no common point) or *isolated* (each piece's
   hodograph in a pointed cone, the two cones sharing no line: the Jacobian [p', -q'] has
   full rank on the whole pair of pieces, so it holds at most one common point) with local
   Newton converged inside the pieces. Nothing is left unresolved (a tangency, a shared
   stretch, crossings closer than 2^-DEPTH = 2^-16, a piece flat to rounding) and no guard
   tripped;
2. each root, refined by Newton on the whole curves with the residual p(s) - q(t) evaluated by
   compensated de Casteljau (as accurate as twice the working precision, so the root is
   right to the last bits, as the careful path's exact residual makes it): its last step is
   below 1e-12, it stays within DRIFT of the isolated start (it is the root of that pair of
   pieces, not a neighbour's), its residual is within the careful path's ROOT_RESIDUAL bound,
   and the sine of the angle between p'(s) and q'(t) exceeds SINE_MIN (with the residual r,
   a common point lies within r / sine of it: a near-double crossing goes the careful way);
3. each root lies at least END_MARGIN inside both parameter ranges: roots at or next to an
   end are the careful path's (it locates the ends exactly and tells tangencies there),
   but for a T-junction: one root (and no other, and no shared corner) next to an end of
   one curve only, the other parameter inside by END_MARGIN, the tangents' sine above
   SHARED_SINE. The careful path reports there the end point as it locates it on the other
   curve, and drops its own root there as that hit; the certificate locates it with the
   careful path's own location (compiled: settle_compiled's; numpy: intersect_locate's)
   and answers that hit when it is located once, within DRIFT of the root, the root within
   SAME / 8 of it (intersect_shared_ends.end_merged), no other root within SHARED_NEAR, and
   the control points not on one line;
4. but for an end point of one curve that is an end point of the other exactly: there the
   end tangents must be clearly apart (the sine of their angle above SHARED_SINE, far above
   the careful path's TANGENT_SINE, so both call it a crossing), the pair of pieces holding
   that corner of the parameter square must end up isolated (its cones apart: the shared
   point is its only common point, recorded exactly, with no Newton), and no other root may
   lie within SHARED_NEAR of it in both parameters (the careful path's MERGE_RADIUS, within
   which it compares hits for being one).

Roots found in two neighbouring pairs of pieces (at their shared edge) merge when both
parameters agree within SAME, the careful path's rule for isolated roots (ISOLATED_SAME).
"""

from __future__ import annotations

from types import ModuleType

import numpy as np

from . import intersect_subdivide as sub
from .intersect_locate import locate_all
from .intersect_prepared import Prepared
from .intersect_shared_ends import collinear, end_crossing, end_merged, shared_corners

END_MARGIN = 1e-9  # roots closer than this to an end of either curve: the careful path
DRIFT = 1e-9  # refinement moving a root farther than this from its start: the careful path
SINE_MIN = 1e-6  # the careful path's TANGENT_SINE: smaller angles are refined as tangencies
SAME = 1e-13  # the careful path's ISOLATED_SAME
MAX_PIECES = 20_000  # pairs of pieces examined per pair of curves before giving up
MAX_ROWS = 400  # the numpy path's guard: pairs of pieces alive at one level, per pair
# halvings at most: a pair of pieces still unresolved at width 2^-16 (a tangency, a shared
# stretch, crossings closer than ~1.5e-5, whose small angle SINE_MIN would refuse anyway) is
# the careful path's, which subdivides to 2^-32; stopping here saves half of that work
DEPTH = 16
SHARED_SINE = 1e-4  # a shared end point's end tangents: a smaller sine is the careful path's
SHARED_NEAR = 1e-3  # intersect.MERGE_RADIUS: another root this near a shared end point declines
_SPLITTER = 134217729.0
# the compiled kernels' knobs, in the order certify_compiled.Settings names them
SETTINGS = (
    DEPTH,
    MAX_PIECES,
    sub.NEWTON_STEPS,
    sub.INSIDE,
    sub.CONE_MARGIN,
    END_MARGIN,
    DRIFT,
    SAME,
    SINE_MIN,
    SHARED_SINE,
    SHARED_NEAR,
)


# the careful path compiled (settle_one) where the certificate declines; a switch for tests,
# which compare it with the careful path in Python
USE_SETTLE = True


def in_use() -> bool:
    """Whether intersect runs the certificate first: only compiled. The numpy version below
    is the readable reference the kernel is tested against; run by intersect it would cost
    more than it saves (measured on the `bezier` fixtures: certified pairs 20% faster than
    the careful path, declined ones 55% slower, having paid for their subdivision twice)."""
    return _compiled() is not None


# the kernels once imported: an import statement per call costs a share of a small pair's
# whole intersection (issue #29)
_kernels: dict[str, ModuleType] = {}


def _compiled() -> ModuleType | None:
    if not sub.USE_COMPILED:
        return None
    kernel = _kernels.get("certify")
    if kernel is None:
        from . import certify_compiled

        kernel = _kernels["certify"] = certify_compiled
    return kernel


def _settle_compiled() -> ModuleType | None:
    if not (sub.USE_COMPILED and USE_SETTLE):
        return None
    kernel = _kernels.get("settle")
    if kernel is None:
        from . import settle_compiled

        kernel = _kernels["settle"] = settle_compiled
    return kernel


def settle_one(
    a: np.ndarray, b: np.ndarray, knobs: tuple[float | int, ...]
) -> list[tuple[float, float, int]] | None:
    """The careful path compiled (settle_compiled) on one pair of float curves (n+1, d),
    (m+1, d) that are the curves exactly, d >= 2: its hits (s, t, kind code: -1
    coincident, 0 tangent, 1 transversal) in the careful path's order, or None where it
    declines (a stretch the curves may share under a parameterisation that is not affine,
    curves on one line, a curve that is a point) or is not compiled. knobs:
    intersect.SETTLE."""
    compiled = _settle_compiled()
    if compiled is None:
        return None
    count, hits = compiled.settle(
        sub.read_only(a),
        sub.read_only(b),
        knobs,
        sub.half_matrices(a.shape[0] - 1),
        sub.half_matrices(b.shape[0] - 1),
    )
    if count < 0:
        return None
    return [(s, t, int(kind)) for s, t, kind in hits.tolist()]


def certify(
    a: np.ndarray,
    b: np.ndarray,
    slack: np.ndarray,
    bound: np.ndarray,
    knobs: tuple[float | int, ...],
) -> list[tuple[list[float], list[float]] | None]:
    """P pairs of curves of equal degrees, a (P, n+1, d) and b (P, m+1, d) in floats; slack
    (P,): the distance within which boxes still touch; bound (P,): the largest residual
    |p(s) - q(t)| of a root; knobs: the careful path's (intersect.SETTLE: a T-junction's end
    point is located as it locates it). For each pair its crossings (s sorted, t) when
    certified, else None."""
    compiled = _compiled()
    if compiled is not None:
        counts, out_s, out_t = compiled.certify(
            np.ascontiguousarray(a, dtype=float),
            np.ascontiguousarray(b, dtype=float),
            np.ascontiguousarray(slack, dtype=float),
            np.ascontiguousarray(bound, dtype=float),
            SETTINGS,
            knobs,
        )
        results: list[tuple[list[float], list[float]] | None] = []
        for k, count in enumerate(counts.tolist()):
            if count < 0:
                results.append(None)
                continue
            order = np.argsort(out_s[k, :count], kind="stable")
            results.append((out_s[k, order].tolist(), out_t[k, order].tolist()))
        return results
    return _certify_numpy(a, b, slack, bound)


def certify_one(
    a: np.ndarray,
    b: np.ndarray,
    box_slack: float,
    root_residual: float,
    knobs: tuple[float | int, ...],
) -> tuple[list[float], list[float]] | None:
    """One pair (n+1, d), (m+1, d) of float curves: its crossings (s sorted, t) when
    certified, else None. The slack and the residual bound are the careful path's, from
    the relative box_slack and root_residual (per unit of degree and of the curves' size);
    knobs: the careful path's (intersect.SETTLE), for a T-junction's end point."""
    compiled = _compiled()
    if compiled is not None:
        count, roots = compiled.certify_one(a, b, box_slack, root_residual, SETTINGS, knobs)
        if count < 0:
            return None
        s: list[float]
        t: list[float]
        s, t = roots.tolist()
        return s, t
    spans = [float(np.ptp(c, axis=0).max()) for c in (a, b)]
    if min(spans) == 0.0:
        return None
    scale = max(spans + [float(np.abs(a).max()), float(np.abs(b).max()), 1e-300])
    degree = max(a.shape[0], b.shape[0]) - 1
    return _certify_numpy(
        a[None],
        b[None],
        np.array([box_slack * degree * scale]),
        np.array([root_residual * degree * scale]),
    )[0]


def _certify_numpy(
    a: np.ndarray, b: np.ndarray, slack: np.ndarray, bound: np.ndarray
) -> list[tuple[list[float], list[float]] | None]:
    """The same certificate on intersect_subdivide's numpy loop, refinement vectorised over
    every root of every pair."""
    # the row guard at the compiled kernel's budget: a shared stretch or a tangency, where
    # pieces survive in numbers, is the careful path's, and is declined cheaply here
    corners = np.array([shared_corners(x, y, SHARED_SINE) for x, y in zip(a, b, strict=True)])
    iso = sub.isolate(
        a, b, slack, depth=DEPTH, max_rows=MAX_ROWS * a.shape[0], corners=np.maximum(corners, 0)
    )
    good = corners >= 0
    good[iso.left_pair] = False
    pair = iso.root_pair
    # a shared end point, reported exactly by its isolated pair of pieces: kept as it is
    held = (iso.root_s % 1 == 0) & (iso.root_t % 1 == 0)
    bit = np.where(held, 2 * np.where(held, iso.root_s, 0) + np.where(held, iso.root_t, 0), 0)
    held &= (corners[pair] >> bit.astype(np.int64)) & 1 == 1
    s, t, step, res, sine = refine(a[pair], b[pair], iso.root_s, iso.root_t)
    ok = (step < 1e-12) & (res <= bound[pair]) & (sine > SINE_MIN)
    ok &= (np.abs(s - iso.root_s) <= DRIFT) & (np.abs(t - iso.root_t) <= DRIFT)
    pairs_st = zip(s.tolist(), t.tolist(), strict=True)
    ends = np.array([end_crossing(x, y, END_MARGIN) for x, y in pairs_st], dtype=np.int64)
    tee = ok & (ends >= 0) & ~held  # at an end of one curve: located below
    ok &= ends == -1
    s, t = np.where(held, iso.root_s, s), np.where(held, iso.root_t, t)
    ok |= held
    for k in np.flatnonzero(held).tolist():  # the careful path may merge hits this close
        near = ~held & (pair == pair[k])
        near &= (np.abs(s - s[k]) < SHARED_NEAR) & (np.abs(t - t[k]) < SHARED_NEAR)
        ok[near] = False
    for k in sorted(set(pair[tee].tolist())):  # a T-junction: the careful path's end hit
        mine = np.flatnonzero(tee & (pair == k))
        hit = _end_hit_numpy(
            a[k], b[k], int(corners[k]), bound[k], ends[mine], s[mine], t[mine], sine[mine]
        )
        others = (pair == k) & ~tee
        if hit is None or np.any(
            others & (np.abs(s - hit[0]) < SHARED_NEAR) & (np.abs(t - hit[1]) < SHARED_NEAR)
        ):
            good[k] = False
            continue
        s[mine], t[mine], ok[mine] = hit[0], hit[1], True
    good[pair[~ok]] = False
    results: list[tuple[list[float], list[float]] | None] = []
    for k in range(a.shape[0]):
        if not good[k]:
            results.append(None)
            continue
        mine = (pair == k) & ~held & ~tee
        kept: list[tuple[float, float]] = []
        for x, y in zip(s[mine].tolist(), t[mine].tolist(), strict=True):
            if not any(abs(x - u) < SAME and abs(y - v) < SAME for u, v in kept):
                kept.append((x, y))
        # the shared end points last, in the order of (s, t), then a T-junction's end hit,
        # as the compiled kernel has them
        mine = (pair == k) & held
        kept += sorted(zip(s[mine].tolist(), t[mine].tolist(), strict=True))
        mine = (pair == k) & tee
        kept += [(float(s[mine][0]), float(t[mine][0]))] if mine.any() else []
        kept.sort(key=lambda h: h[0])
        results.append(([h[0] for h in kept], [h[1] for h in kept]))
    return results


def _end_hit_numpy(
    a: np.ndarray,
    b: np.ndarray,
    corners: int,
    bound: float,
    ends: np.ndarray,
    s: np.ndarray,
    t: np.ndarray,
    sine: np.ndarray,
) -> tuple[float, float] | None:
    """certify_compiled._end_hit's rules on one pair whose refined roots (s, t) lie next to
    an end of one curve only (ends: end_crossing's codes): one root (those in the next pair
    of pieces within SAME of it), tangents clearly apart, no shared corner, not on one line,
    the end point located once by the careful path in Python (intersect_locate.locate_all,
    as _pair_setup calls it), within DRIFT of the root, which merges into it. The hit
    (s, t), or None (declined)."""
    x0, y0, end = float(s[0]), float(t[0]), int(ends[0])
    if corners or np.any((ends != end) | (np.abs(s - x0) >= SAME) | (np.abs(t - y0) >= SAME)):
        return None
    if not sine[0] > SHARED_SINE or collinear(a, b, bound):
        return None
    e = end & 1
    own, other = (a, b) if end >> 1 == 0 else (b, a)
    x, y = (x0, y0) if end >> 1 == 0 else (y0, x0)
    located = locate_all(Prepared(other, None), own[-1 if e else 0], None, None, True)
    if len(located) != 1 or not abs(located[0] - y) <= DRIFT:
        return None
    if not end_merged(x, y, float(e), located[0], SAME):
        return None
    return (float(e), located[0]) if end >> 1 == 0 else (located[0], float(e))


def _two_sum(x: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    total = x + y
    v = total - x
    return total, (x - (total - v)) + (y - v)


def _two_prod(x: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    product = x * y
    c = _SPLITTER * x
    xh = c - (c - x)
    xl = x - xh
    c = _SPLITTER * y
    yh = c - (c - y)
    yl = y - yh
    return product, ((xh * yh - product) + xh * yl + xl * yh) + xl * yl


def compensated(ctrl: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Compensated de Casteljau (Graillat, Langlois and Louvet) on K curves (K, n+1, d) at
    their own t (K,): (hi, lo, slope), p(t) = hi + lo as accurately as if evaluated in twice
    the working precision, and p'(t) in floats. Curves of degree >= 1."""
    degree = ctrl.shape[1] - 1
    r, rho = _two_sum(np.ones_like(t), -t)
    r, rho, tt = r[:, None, None], rho[:, None, None], t[:, None, None]
    hi = ctrl.copy()
    lo = np.zeros_like(ctrl)
    slope = np.zeros((ctrl.shape[0], ctrl.shape[2]))
    for level in range(degree):
        if level == degree - 1:
            slope = degree * (hi[:, 1] - hi[:, 0])
        p1, e1 = _two_prod(r, hi[:, :-1])
        p2, e2 = _two_prod(tt, hi[:, 1:])
        total, e3 = _two_sum(p1, p2)
        lo = r * lo[:, :-1] + tt * lo[:, 1:] + (e1 + e2 + e3 + rho * hi[:, :-1])
        hi = total
    return hi[:, 0], lo[:, 0], slope


def _residual(
    a: np.ndarray, b: np.ndarray, s: np.ndarray, t: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    ah, al, da = compensated(a, s)
    bh, bl, db = compensated(b, t)
    d, e = _two_sum(ah, -bh)
    return d + (e + (al - bl)), da, db


def refine(
    a: np.ndarray, b: np.ndarray, s: np.ndarray, t: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Newton (Gauss-Newton for d > 2) on p(s) - q(t) with the compensated residual, for K
    pairs (K, n+1, d), (K, m+1, d) from (s, t): (s, t, last step, residual norm, sine of the
    tangents' angle); inf steps where Newton fails or leaves the domain."""
    s, t = s.astype(float), t.astype(float)
    step = np.full(s.shape, np.inf)
    prev = np.full(s.shape, np.inf)
    active = np.ones(s.shape, dtype=bool)
    failed = np.zeros(s.shape, dtype=bool)
    with np.errstate(all="ignore"):
        for it in range(16):
            if not active.any():
                break
            f, da, db = _residual(a, b, s, t)
            aa = (da * da).sum(-1)
            ab = -(da * db).sum(-1)
            bb = (db * db).sum(-1)
            ga = -(da * f).sum(-1)
            gb = (db * f).sum(-1)
            det = aa * bb - ab * ab
            ds = np.where(active, (bb * ga - ab * gb) / det, 0.0)
            dt = np.where(active, (aa * gb - ab * ga) / det, 0.0)
            failed |= active & ~(det > 0.0)
            s, t = s + ds, t + dt
            size = np.abs(ds) + np.abs(dt)
            step = np.where(active, size, step)
            failed |= active & ~((s > -0.5) & (s < 1.5) & (t > -0.5) & (t < 1.5))
            done = (size < 1e-17) | ((it >= 4) & (size >= prev)) | failed
            prev = np.where(active, size, prev)
            active &= ~done
        f, da, db = _residual(a, b, s, t)
        nu, nv = (da * da).sum(-1), (db * db).sum(-1)
        cross2 = np.maximum(nu * nv - (da * db).sum(-1) ** 2, 0.0)
        sine = np.where(nu * nv > 0, np.sqrt(cross2) / np.sqrt(nu * nv), 0.0)
    res = np.sqrt((f * f).sum(-1))
    step = np.where(failed, np.inf, step)
    res = np.where(failed, np.inf, res)
    return s, t, step, res, sine
