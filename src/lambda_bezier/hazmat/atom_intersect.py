r"""Certified intersections of curves given by enclosures: a curve over centred atoms (mixed
families, hazmat.atom_bounds) with another such curve, with a polynomial or rational Bézier
curve, or with itself.

Every curve taking part is a `Part` (hazmat.atom_intersect_parts): its parameter interval,
point values and derivatives, and rigorous enclosures of the curve and of its first
derivative over many parameter intervals at once (`AtomPart`, `BernsteinPart`).

**Branch and bound** on pairs of parameter intervals (S, T), all of a round at once:

1. *Exclusion.* With x̃ = (s̃, t̃) the middles, r_s, r_t the half widths, and a direction n,
   the mean value form n·F(S, T) ⊂ n·F(x̃) ± (|n·P'(S)| r_s + |n·Q'(T)| r_t), F(s, t) =
   P(s) − Q(t), n·F(x̃) enclosed at the point. The pair is dropped when this excludes 0 for
   one of the directions: the coordinate axes, and the normals of the two tangents at x̃
   (in 3D, the common normal P' × Q' and the normals in each tangent's plane). Along the
   normals the form is of second order in the widths, so at a tangency the surviving pairs
   stay few per level instead of growing as the band where the curves are within the
   enclosures' width.
2. *Uniqueness* (Krawczyk). On X, the pair inflated by 1/8 of its widths on each side (so
   that a root on the edge of a pair, or at the end of a domain, is inside one X):
   K = x̃ − Y F(x̃) + (I − Y J(X))(X − x̃), Y ≈ J(x̃)^-1, J(X) = [P'(S) | −Q'(T)] enclosed.
   K ⊂ interior X proves exactly one root of F in X (and it lies in K); K ∩ X = ∅ proves
   none. In 3D, F has three rows: Krawczyk runs on the two rows of J(x̃) with the largest
   determinant, and a unique root of those two is an intersection when the third row's
   enclosure over K holds 0 and Newton's root has |F| within ON_CURVE of the size (the
   third row excluding 0 proves it is not).
3. Every proven root is polished by Newton's method (it stays in K) and kept when it lies
   in the domains: K inside them, or, K across an end, a second Krawczyk box about Newton's
   point too small to reach the end proves on which side it is (`_in_domains`; only within
   the rounding of F of the end, about 1e-14 of the domain, is it undecided, and kept).
   Roots closer than SAME (relative) are one, and so are two whose K lies in the other's X.
   A root reported at an end (clamped) keeps its partner: the other parameter is re-solved
   with the first held at the end (`onto_domains`).
4. Pairs that neither test settles are halved in s and t. Below TINY (relative to each
   domain) they are *unresolved*: the curves are within the enclosures' width there but
   no single root is proven, i.e. a tangency or crossings closer than TINY. Each cluster of
   touching unresolved pairs gives one intersection (the pair with the least |F| at its
   middle, polished by Gauss-Newton), kind "tangent" when the tangents there are parallel
   within TANGENT_SINE (then polished on the tangent system over BAND × TINY each side, so
   the clusters of one flat tangency meet at one point), else "transversal"; a cluster whose
   least |F| is above ON_CURVE of the size gives none.

So every crossing of the curves is found: each lies in a pair that is never excluded, and
ends either in a proven box (one root, reported once) or in an unresolved cluster (reported
once). Shared stretches (the curves coincide along an arc) make the pairs multiply without
end: past MAX_PAIRS open pairs the search returns None and the caller takes another route.

**Self-intersections** (`self_pairs`): pairs S ≤ T of one curve. A pair whose intervals
touch or overlap (the diagonal s = t is always a root there) is dropped when the curve is
injective on the hull of the two intervals, proven by a direction v with v·C'(I) > 0
(v = C' at the middle); diagonal pairs (S = T) are split into three (the halves with
themselves and with each other).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from . import atom_bounds as ab
from .atom_intersect_parts import (
    AtomPart,
    BernsteinPart,
    Bounds,
    Part,
    _add,
    _dot,
    _mag,
)

__all__ = ["AtomPart", "BernsteinPart", "Found", "Part", "pairs", "self_pairs"]

_U = 2.0**-53
TINY = 2.0**-30  # pairs narrower than this (relative to each domain) are unresolved
INFLATE = 0.125  # Krawczyk's box: the pair widened by this fraction of its width each side
MAX_PAIRS = 1 << 13  # open pairs beyond this, spread along the curves: a shared stretch (None)
# past MAX_PAIRS, open pairs within SPREAD of each domain are a flat contact, not a shared
# stretch (a curve and its mirror in its tangent near an inflection: 11,196 open at most),
# and the search goes on, up to HARD_MAX_PAIRS
SPREAD = 1e-3
HARD_MAX_PAIRS = 1 << 15
MAX_ROUNDS = 200
SAME = 1e-9  # relative to the domain: roots this close are one
ON_CURVE = 1e-10  # relative to the size: |P(s) − Q(t)| below this is a meeting point
TANGENT_SINE = 1e-6  # below this sine of the angle between the tangents: "tangent"
START = 8  # intervals per domain at the first level
# a tangency's unresolved clusters are polished over this many TINY each side: where the
# curves part slowly (curvatures alike) the band within the enclosures' width of the other
# curve is that wide, and it can break into clusters (found by fuzzing, 3.4e-7 apart)
BAND = 1024


# ---------------------------------------------------------------------- one round
@dataclass
class Pairs:
    """Open pairs of intervals [s0, s1] × [t0, t1]."""

    s0: np.ndarray
    s1: np.ndarray
    t0: np.ndarray
    t1: np.ndarray

    def take(self, keep: np.ndarray) -> Pairs:
        return Pairs(self.s0[keep], self.s1[keep], self.t0[keep], self.t1[keep])

    @property
    def size(self) -> int:
        return int(self.s0.size)


def _directions(dp: np.ndarray, dq: np.ndarray) -> list[np.ndarray]:
    """Unit directions (d, m) for the exclusion test: the axes, and the tangents' normals."""
    d, m = dp.shape
    out = [np.broadcast_to(np.eye(d)[:, [c]], (d, m)) for c in range(d)]

    def unit(v: np.ndarray) -> np.ndarray:
        norm = np.linalg.norm(v, axis=0)
        return np.where(norm > 0, v / np.where(norm > 0, norm, 1.0), 0.0)

    if d == 2:
        out += [unit(np.stack([-dp[1], dp[0]])), unit(np.stack([-dq[1], dq[0]]))]
    elif d == 3:
        common = np.cross(dp.T, dq.T).T
        out += [unit(common), unit(np.cross(dp.T, common.T).T), unit(np.cross(dq.T, common.T).T)]
    return out


@dataclass
class Centres:
    """At the pairs' middles x̃ = (s̃, t̃): F(x̃) enclosed, (d, m) each, and the tangents
    P'(s̃), Q'(t̃) (d, m). The exclusion and Krawczyk's test share them (x̃ lies in both
    boxes; Krawczyk's radii are measured from it)."""

    sm: np.ndarray
    tm: np.ndarray
    f_lo: np.ndarray
    f_hi: np.ndarray
    dp: np.ndarray
    dq: np.ndarray

    @staticmethod
    def of(p: Part, q: Part, pr: Pairs) -> Centres:
        sm, tm = 0.5 * (pr.s0 + pr.s1), 0.5 * (pr.t0 + pr.t1)
        pc_lo, pc_hi = p.enclose(0, sm, sm)
        qc_lo, qc_hi = q.enclose(0, tm, tm)
        f_lo, f_hi = _add(pc_lo, pc_hi, -qc_hi, -qc_lo)
        return Centres(sm, tm, f_lo, f_hi, p.values(1, sm), q.values(1, tm))

    def take(self, keep: np.ndarray) -> Centres:
        return Centres(
            self.sm[keep],
            self.tm[keep],
            self.f_lo[:, keep],
            self.f_hi[:, keep],
            self.dp[:, keep],
            self.dq[:, keep],
        )


def _excluded(p: Part, q: Part, pr: Pairs, c: Centres) -> np.ndarray:
    """(m,) bool: pairs proven to hold no root of P(s) − Q(t) (mean value forms)."""
    sm, tm = c.sm, c.tm
    rs = np.maximum(pr.s1 - sm, sm - pr.s0) * (1 + 4 * _U)
    rt = np.maximum(pr.t1 - tm, tm - pr.t0) * (1 + 4 * _U)
    plo, phi = p.enclose(0, pr.s0, pr.s1)
    qlo, qhi = q.enclose(0, pr.t0, pr.t1)
    out: np.ndarray = np.asarray(((plo > qhi) | (qlo > phi)).any(axis=0))
    dp_lo, dp_hi = p.enclose(1, pr.s0, pr.s1)
    dq_lo, dq_hi = q.enclose(1, pr.t0, pr.t1)
    for n in _directions(c.dp, c.dq):
        c_lo, c_hi = _dot(n, c.f_lo, c.f_hi)
        a = _mag(*_dot(n, dp_lo, dp_hi)) * rs
        b = _mag(*_dot(n, dq_lo, dq_hi)) * rt
        reach = (a + b) * (1 + 8 * _U)
        out |= (c_lo - reach > 0) | (c_hi + reach < 0)
    return out


def _krawczyk(
    p: Part, q: Part, pr: Pairs, centres: Centres | None = None
) -> tuple[np.ndarray, np.ndarray, Bounds, Bounds]:
    """(unique, empty, K_s, K_t) per pair: Krawczyk's test on the pair inflated by INFLATE
    (on the two rows of J with the largest determinant at the middle, in 3D), about the
    pairs' middles (computed when not given)."""
    ctr = centres if centres is not None else Centres.of(p, q, pr)
    ws, wt = pr.s1 - pr.s0, pr.t1 - pr.t0
    xs0, xs1 = pr.s0 - INFLATE * ws, pr.s1 + INFLATE * ws
    xt0, xt1 = pr.t0 - INFLATE * wt, pr.t1 + INFLATE * wt
    sm, tm = ctr.sm, ctr.tm
    rs = np.maximum(xs1 - sm, sm - xs0) * (1 + 4 * _U)
    rt = np.maximum(xt1 - tm, tm - xt0) * (1 + 4 * _U)
    f_lo, f_hi = ctr.f_lo, ctr.f_hi  # F(x̃), (d, m)
    dp_lo, dp_hi = p.enclose(1, xs0, xs1)
    dq_lo, dq_hi = q.enclose(1, xt0, xt1)
    jp, jq = ctr.dp, -ctr.dq  # J(x̃) columns, (d, m)
    d, m = jp.shape
    cols = np.arange(m)
    if d == 2:
        rows = np.zeros((m, 2), dtype=int)
        rows[:, 1] = 1
    else:
        choices = [(i, j) for i in range(d) for j in range(i + 1, d)]
        dets = np.stack([np.abs(jp[i] * jq[j] - jp[j] * jq[i]) for i, j in choices])
        best = np.argmax(dets, axis=0)
        rows = np.array(choices)[best]
    r0, r1 = rows[:, 0], rows[:, 1]
    a, b = jp[r0, cols], jq[r0, cols]
    c, e = jp[r1, cols], jq[r1, cols]
    det = a * e - b * c
    ok = np.isfinite(det) & (np.abs(det) > 0)
    safe = np.where(ok, det, 1.0)
    y = np.array([[e, -b], [-c, a]]) / safe  # (2, 2, m)
    # J(X) rows r0, r1: [P'_r(S), −Q'_r(T)] intervals
    jl = np.array([[dp_lo[r0, cols], -dq_hi[r0, cols]], [dp_lo[r1, cols], -dq_hi[r1, cols]]])
    jh = np.array([[dp_hi[r0, cols], -dq_lo[r0, cols]], [dp_hi[r1, cols], -dq_lo[r1, cols]]])
    fl = np.array([f_lo[r0, cols], f_lo[r1, cols]])
    fh = np.array([f_hi[r0, cols], f_hi[r1, cols]])
    radius = np.array([rs, rt])
    centre = np.array([sm, tm])
    k_lo, k_hi = [], []
    for i in range(2):
        yf_lo, yf_hi = _dot(y[i], fl, fh)  # (Y F(x̃))_i
        reach = np.zeros(m)
        for k in range(2):
            # (I − Y J)_ik = δ_ik − Σ_j Y_ij J_jk, an interval; times [−r_k, r_k]
            s_lo, s_hi = _dot(y[i], jl[:, k], jh[:, k])
            e_lo, e_hi = _add(np.full(m, float(i == k)), np.full(m, float(i == k)), -s_hi, -s_lo)
            reach = reach + _mag(e_lo, e_hi) * radius[k]
        reach = reach * (1 + 8 * _U)
        lo_i, hi_i = _add(centre[i] - yf_hi, centre[i] - yf_lo, -reach, reach)
        k_lo.append(lo_i)
        k_hi.append(hi_i)
    box = [(xs0, xs1), (xt0, xt1)]
    inside = ok.copy()
    for i in range(2):
        inside &= (k_lo[i] > box[i][0]) & (k_hi[i] < box[i][1])
    empty_any = np.zeros(m, dtype=bool)
    for i in range(2):
        empty_any |= ok & ((k_lo[i] > box[i][1]) | (k_hi[i] < box[i][0]))
    inside &= np.isfinite(np.array(k_lo)).all(axis=0) & np.isfinite(np.array(k_hi)).all(axis=0)
    if d > 2:
        # a unique root of two rows: an intersection only if the other rows can vanish on K
        ks = (np.maximum(k_lo[0], xs0), np.minimum(k_hi[0], xs1))
        kt = (np.maximum(k_lo[1], xt0), np.minimum(k_hi[1], xt1))
        sel = np.nonzero(inside)[0]
        if sel.size:
            plo, phi = p.enclose(0, ks[0][sel], ks[1][sel])
            qlo, qhi = q.enclose(0, kt[0][sel], kt[1][sel])
            apart = ((plo > qhi) | (qlo > phi)).any(axis=0)
            empty_any[sel[apart]] = True
            inside[sel[apart]] = False
    return inside, empty_any, (np.array(k_lo[0]), np.array(k_hi[0])), (k_lo[1], k_hi[1])


# ---------------------------------------------------------------------- Newton
System = Callable[[float, float], tuple[np.ndarray, np.ndarray]]
Box = tuple[float, float, float, float]


def _gauss_newton(system: System, s: float, t: float, box: Box) -> tuple[float, float]:
    """Gauss-Newton on `system` (s, t) ↦ (residual, Jacobian) from (s, t), each step kept in
    box (s0, s1, t0, t1); it stops when a step no longer moves the point."""
    for _ in range(40):
        g, jac = system(s, t)
        step, *_ = np.linalg.lstsq(jac, -g, rcond=None)
        if not np.isfinite(step).all():
            break
        ns = min(max(s + float(step[0]), box[0]), box[1])
        nt = min(max(t + float(step[1]), box[2]), box[3])
        if ns == s and nt == t:
            break
        s, t = ns, nt
    return s, t


def onto_domains(system: System, s: float, t: float, domains: Box) -> tuple[float, float]:
    """(s, t) clamped into the domains (s0, s1, t0, t1); when only one parameter moves onto
    its end it is held there and the other re-solved (Gauss-Newton, the held parameter's
    column zero), so that the pair stays a meeting point: at a multiple root next to an end
    Newton's point can lie 1e-6 past it, and the other parameter with it."""
    cs = min(max(s, domains[0]), domains[1])
    ct = min(max(t, domains[2]), domains[3])
    if (cs == s) == (ct == t):
        return cs, ct
    free = np.array([0.0, 1.0]) if cs != s else np.array([1.0, 0.0])

    def held(s: float, t: float) -> tuple[np.ndarray, np.ndarray]:
        g, jac = system(s, t)
        return g, jac * free

    return _gauss_newton(
        held, cs, ct, (cs, cs, *domains[2:]) if cs != s else (*domains[:2], ct, ct)
    )


def _f_system(p: Part, q: Part) -> System:
    """(s, t) ↦ (P(s) − Q(t), its Jacobian [P'(s) | −Q'(t)])."""

    def system(s: float, t: float) -> tuple[np.ndarray, np.ndarray]:
        sx, tx = np.array([s]), np.array([t])
        f = p.values(0, sx)[:, 0] - q.values(0, tx)[:, 0]
        return f, np.stack([p.values(1, sx)[:, 0], -q.values(1, tx)[:, 0]], axis=1)

    return system


def _newton(p: Part, q: Part, s: float, t: float, box: Box) -> tuple[float, float]:
    """Gauss-Newton on P(s) − Q(t) = 0 from (s, t), kept in box (s0, s1, t0, t1)."""
    return _gauss_newton(_f_system(p, q), s, t, box)


def _tangent_system(p: Part, q: Part, s: float, t: float) -> np.ndarray:
    """F(s, t) = P(s) − Q(t) stacked with the tangents' cross product(s), scaled to F's
    units: at a tangency of different curvatures its root is regular."""
    sx, tx = np.array([s]), np.array([t])
    a, b = p.values(1, sx)[:, 0], q.values(1, tx)[:, 0]
    f = p.values(0, sx)[:, 0] - q.values(0, tx)[:, 0]
    # in 2D the scalar cross product by hand: numpy 2 deprecates np.cross of 2-vectors
    cross = (np.array([a[0] * b[1] - a[1] * b[0]]) if a.size == 2 else np.cross(a, b)) / max(
        float(np.linalg.norm(b)), 1e-300
    )
    return np.concatenate([f, cross])


def _tangent_newton(p: Part, q: Part, s: float, t: float, box: Box) -> tuple[float, float]:
    """Gauss-Newton on the tangent system (Jacobian by central differences: the residual is
    the system itself, so the root is the system's), kept in box."""
    hs = 1e-7 * max(box[1] - box[0], 1e-300) + 1e-9 * (p.hi - p.lo)
    ht = 1e-7 * max(box[3] - box[2], 1e-300) + 1e-9 * (q.hi - q.lo)

    def system(s: float, t: float) -> tuple[np.ndarray, np.ndarray]:
        ds = _tangent_system(p, q, s + hs, t) - _tangent_system(p, q, s - hs, t)
        dt = _tangent_system(p, q, s, t + ht) - _tangent_system(p, q, s, t - ht)
        return _tangent_system(p, q, s, t), np.stack([ds / (2 * hs), dt / (2 * ht)], axis=1)

    return _gauss_newton(system, s, t, box)


def _residual(p: Part, q: Part, s: float, t: float) -> float:
    return float(
        np.linalg.norm(p.values(0, np.array([s]))[:, 0] - q.values(0, np.array([t]))[:, 0])
    )


def _sine(p: Part, q: Part, s: float, t: float) -> float:
    a, b = p.values(1, np.array([s]))[:, 0], q.values(1, np.array([t]))[:, 0]
    na, nb = float(np.linalg.norm(a)), float(np.linalg.norm(b))
    if na == 0 or nb == 0:
        return 0.0
    if a.size == 2:
        return abs(float(a[0] * b[1] - a[1] * b[0])) / (na * nb)
    return float(np.linalg.norm(np.cross(a, b))) / (na * nb)


# ---------------------------------------------------------------------- the search
def _inflated(pr: Pairs, j: int) -> Box:
    """Krawczyk's box X for pair j: the pair widened by INFLATE of its widths each side."""
    ws, wt = float(pr.s1[j] - pr.s0[j]), float(pr.t1[j] - pr.t0[j])
    return (
        float(pr.s0[j]) - INFLATE * ws,
        float(pr.s1[j]) + INFLATE * ws,
        float(pr.t0[j]) - INFLATE * wt,
        float(pr.t1[j]) + INFLATE * wt,
    )


def _inside(a: tuple[float, ...], b: tuple[float, ...]) -> bool:
    """Box a (s0, s1, t0, t1) within box b."""
    return b[0] <= a[0] and a[1] <= b[1] and b[2] <= a[2] and a[3] <= b[3]


def _same_root(f: Found, g: Found) -> bool:
    """Proven roots f and g are one when either's K lies in the other's X (where the root
    is unique): ill-conditioned crossings are polished by Newton to points far apart."""
    if f.k is None or g.k is None or f.x is None or g.x is None:
        return False
    return _inside(f.k, g.x) or _inside(g.k, f.x)


def _in_domains(p: Part, q: Part, s: float, t: float, box: Box, pr: Pairs, j: int) -> bool:
    """Whether the root proven in K = `box` (unique in pair j of `pr` inflated by INFLATE,
    Newton's approximation (s, t)) lies in the domains. K inside them: yes; K outside: no.
    K across an end: Krawczyk again on a box about (s, t) too small to reach that end (half
    the distance to it), inside the first box, so that the root it proves is the same one;
    when that settles nothing the root is within the rounding of F of the end (the float
    input does not decide) and it is kept: a meeting point that cannot be excluded."""
    lo_s, hi_s, lo_t, hi_t = box
    if hi_s < p.lo or lo_s > p.hi or hi_t < q.lo or lo_t > q.hi:
        return False
    if p.lo <= lo_s and hi_s <= p.hi and q.lo <= lo_t and hi_t <= q.hi:
        return True
    ws, wt = p.hi - p.lo, q.hi - q.lo
    ds = min(s - p.lo, p.hi - s)  # signed: negative outside the domain
    dt = min(t - q.lo, q.hi - t)
    rho = 0.5 * min(abs(ds) / ws, abs(dt) / wt)
    if rho == 0:
        return True
    hs, ht = rho * ws, rho * wt
    tight = Pairs(np.array([s - hs]), np.array([s + hs]), np.array([t - ht]), np.array([t + ht]))
    # Krawczyk's box (the pair inflated by INFLATE) inside the first one, whose root is unique
    reach_s, reach_t = (1 + 2 * INFLATE) * hs, (1 + 2 * INFLATE) * ht
    first = _inflated(pr, j)
    if not (
        first[0] < s - reach_s
        and s + reach_s < first[1]
        and first[2] < t - reach_t
        and t + reach_t < first[3]
    ):
        return True
    unique, _, _, _ = _krawczyk(p, q, tight)
    if not unique[0]:
        return True  # not settled: within the rounding of the end
    return ds > 0 and dt > 0


@dataclass
class Found:
    """An intersection (s, t, kind), and whether a single root was proven there."""

    s: float
    t: float
    kind: str
    proven: bool
    # a proven root: Krawczyk's K (s0, s1, t0, t1) that holds it and the box X in which it is
    # the only root
    k: Box | None = None
    x: Box | None = None


def _clusters(pr: Pairs) -> list[np.ndarray]:
    from .intersect_locate import _interval_clusters

    width = np.maximum(pr.s1 - pr.s0, pr.t1 - pr.t0)
    return _interval_clusters(pr.s0, pr.t0, width)


def _search(
    p: Part,
    q: Part,
    pr: Pairs,
    split: Callable[[Pairs], Pairs],
    near: Callable[[Pairs], np.ndarray],
    stats: ab.Stats,
    give_up: int = HARD_MAX_PAIRS,
) -> tuple[list[Found], Pairs] | None:
    """The branch and bound from the open pairs `pr`: the proven roots, and the unresolved
    pairs. `near` marks pairs settled otherwise (self-intersections: the diagonal). Past
    `give_up` open pairs (at least MAX_PAIRS), None even for a contact's narrow band."""
    ws, wt = p.hi - p.lo, q.hi - q.lo
    found: list[Found] = []
    stuck: list[Pairs] = []
    size = max(p.size, q.size)
    for _ in range(MAX_ROUNDS):
        if pr.size == 0:
            break
        if pr.size > MAX_PAIRS and (pr.size > give_up or _spread(pr, ws, wt)):
            return None
        stats.rounds += 1
        stats.intervals += pr.size
        keep = ~near(pr)
        pr = pr.take(keep)
        if pr.size == 0:
            break
        centres = Centres.of(p, q, pr)
        kept = ~_excluded(p, q, pr, centres)
        pr = pr.take(kept)
        if pr.size == 0:
            break
        unique, empty, ks, kt = _krawczyk(p, q, pr, centres.take(kept))
        for j in np.nonzero(unique)[0]:
            box = (float(ks[0][j]), float(ks[1][j]), float(kt[0][j]), float(kt[1][j]))
            s, t = _newton(p, q, 0.5 * (box[0] + box[1]), 0.5 * (box[2] + box[3]), box)
            if not _in_domains(p, q, s, t, box, pr, int(j)):
                continue
            if p.values(0, np.array([s])).shape[0] > 2 and _residual(p, q, s, t) > ON_CURVE * size:
                continue  # 3D: the two rows' root, not a meeting point
            s, t = onto_domains(_f_system(p, q), s, t, (p.lo, p.hi, q.lo, q.hi))
            kind = "tangent" if _sine(p, q, s, t) <= TANGENT_SINE else "transversal"
            found.append(Found(s, t, kind, True, box, _inflated(pr, int(j))))
        pr = pr.take(~(unique | empty))
        small = ((pr.s1 - pr.s0) <= TINY * ws) & ((pr.t1 - pr.t0) <= TINY * wt)
        if small.any():
            stuck.append(pr.take(small))
            pr = pr.take(~small)
        pr = split(pr)
    else:
        if pr.size:
            stuck.append(pr)
            stats.narrow += pr.size
    empty_pairs = Pairs(*(np.empty(0) for _ in range(4)))
    rest = _concat(stuck) if stuck else empty_pairs
    return found, rest


def _covered(lo: np.ndarray, hi: np.ndarray) -> float:
    """The length of the union of the intervals [lo, hi]."""
    order = np.argsort(lo)
    lo, hi = lo[order], np.maximum.accumulate(hi[order])
    # each interval adds what reaches past the furthest end before it
    before = np.concatenate([[lo[0]], hi[:-1]])
    return float(np.maximum(hi - np.maximum(lo, before), 0.0).sum())


def _spread(pr: Pairs, ws: float, wt: float) -> bool:
    """Whether the open pairs cover more than SPREAD of either domain: a shared stretch
    (whose pairs line its whole length) rather than one contact point's band."""
    return _covered(pr.s0, pr.s1) > SPREAD * ws or _covered(pr.t0, pr.t1) > SPREAD * wt


def _concat(parts: list[Pairs]) -> Pairs:
    return Pairs(
        np.concatenate([x.s0 for x in parts]),
        np.concatenate([x.s1 for x in parts]),
        np.concatenate([x.t0 for x in parts]),
        np.concatenate([x.t1 for x in parts]),
    )


def _halve(pr: Pairs) -> Pairs:
    """Each pair into four (both intervals halved)."""
    sm, tm = 0.5 * (pr.s0 + pr.s1), 0.5 * (pr.t0 + pr.t1)
    s0 = np.concatenate([pr.s0, pr.s0, sm, sm])
    s1 = np.concatenate([sm, sm, pr.s1, pr.s1])
    t0 = np.concatenate([pr.t0, tm, pr.t0, tm])
    t1 = np.concatenate([tm, pr.t1, tm, pr.t1])
    return Pairs(s0, s1, t0, t1)


def _grid(lo: float, hi: float) -> tuple[np.ndarray, np.ndarray]:
    edges = np.linspace(lo, hi, START + 1)
    edges[0], edges[-1] = lo, hi
    return edges[:-1], edges[1:]


def _settle(p: Part, q: Part, found: list[Found], stuck: Pairs) -> list[Found]:
    """One intersection per cluster of unresolved pairs (see the module's step 4); proven
    roots closer than SAME are one."""
    size = max(p.size, q.size)
    ws, wt = p.hi - p.lo, q.hi - q.lo
    out = list(found)
    proven = [(f.s, f.t) for f in found]
    if stuck.size:
        for members in _clusters(stuck):
            # a cluster next to a proven root is that root's neighbourhood, where the
            # curves are within the enclosures' width of each other: not another root
            reach_s, reach_t = 64 * TINY * ws, 64 * TINY * wt
            s_lo, s_hi = stuck.s0[members].min() - reach_s, stuck.s1[members].max() + reach_s
            t_lo, t_hi = stuck.t0[members].min() - reach_t, stuck.t1[members].max() + reach_t
            if any(s_lo <= x <= s_hi and t_lo <= y <= t_hi for x, y in proven):
                continue
            sm = 0.5 * (stuck.s0[members] + stuck.s1[members])
            tm = 0.5 * (stuck.t0[members] + stuck.t1[members])
            res = np.linalg.norm(p.values(0, sm) - q.values(0, tm), axis=0)
            k = int(np.argmin(res))
            box = (
                float(stuck.s0[members].min()),
                float(stuck.s1[members].max()),
                float(stuck.t0[members].min()),
                float(stuck.t1[members].max()),
            )
            s, t = float(sm[k]), float(tm[k])
            s2, t2 = _newton(p, q, s, t, box)
            if _residual(p, q, s2, t2) <= _residual(p, q, s, t):
                s, t = s2, t2
            if _sine(p, q, s, t) <= TANGENT_SINE:
                # a flat tangency's band of unresolved pairs can break into clusters (the
                # float curves cross twice there, closer than the band is wide): each is
                # polished over the band's reach, to the one point of tangency
                span_s = max(box[1] - box[0], BAND * TINY * ws)
                span_t = max(box[3] - box[2], BAND * TINY * wt)
                wide = (box[0] - span_s, box[1] + span_s, box[2] - span_t, box[3] + span_t)
                s2, t2 = _tangent_newton(p, q, s, t, wide)
                if _residual(p, q, s2, t2) <= max(_residual(p, q, s, t), 4 * _U * size):
                    s, t = s2, t2
            if _residual(p, q, s, t) > ON_CURVE * size:
                continue
            s, t = onto_domains(_f_system(p, q), s, t, (p.lo, p.hi, q.lo, q.hi))
            kind = "tangent" if _sine(p, q, s, t) <= TANGENT_SINE else "transversal"
            out.append(Found(s, t, kind, False))
    out.sort(key=lambda f: (f.s, f.t))
    merged: list[Found] = []
    for f in out:
        same = [
            g
            for g in merged
            if (abs(g.s - f.s) <= SAME * ws and abs(g.t - f.t) <= SAME * wt)
            or _same_root(f, g)
            or _same_contact(p, q, f, g)
        ]
        if same:
            g = same[0]
            if (f.proven and not g.proven) or (
                not g.proven and _residual(p, q, f.s, f.t) < _residual(p, q, g.s, g.t)
            ):
                merged[merged.index(g)] = f
            continue
        merged.append(f)
    return merged


def _same_contact(p: Part, q: Part, f: Found, g: Found) -> bool:
    """Two unresolved clusters are one contact when the curves stay within ON_CURVE of
    each other all the way between them (sampled on the segment from one (s, t) to the
    other): a contact of high order (a triple root at an end: clusters 7e-5 apart) breaks
    into clusters wherever the enclosures cannot tell the curves apart."""
    if f.proven or g.proven:
        return False
    u = np.linspace(0.0, 1.0, 33)
    s, t = f.s + u * (g.s - f.s), f.t + u * (g.t - f.t)
    gap = np.linalg.norm(p.values(0, s) - q.values(0, t), axis=0)
    return bool(gap.max() <= ON_CURVE * max(p.size, q.size))


def pairs(
    p: Part, q: Part, stats: ab.Stats | None = None, give_up: int = HARD_MAX_PAIRS
) -> list[Found] | None:
    """Every intersection of P(s), s ∈ [p.lo, p.hi], and Q(t), t ∈ [q.lo, q.hi] (sorted by
    s), or None when the curves share a stretch (see the module's note), or past `give_up`
    open pairs (a caller with an exact answer to fall back on gives up at MAX_PAIRS)."""
    stats = stats if stats is not None else ab.Stats()
    a, b = _grid(p.lo, p.hi)
    c, e = _grid(q.lo, q.hi)
    i, j = np.meshgrid(np.arange(a.size), np.arange(c.size), indexing="ij")
    start = Pairs(a[i.ravel()], b[i.ravel()], c[j.ravel()], e[j.ravel()])
    got = _search(p, q, start, _halve, lambda pr: np.zeros(pr.size, dtype=bool), stats, give_up)
    if got is None:
        return None
    return _settle(p, q, *got)


# ---------------------------------------------------------------------- self-intersections
def _injective(p: Part, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """(m,) bool: proven that C is one-to-one on [lo, hi]: v·C'(I) > 0 for v = C'(middle)."""
    mid = 0.5 * (lo + hi)
    v = p.values(1, mid)
    d_lo, d_hi = p.enclose(1, lo, hi)
    low, _ = _dot(v, d_lo, d_hi)
    out: np.ndarray = low > 0
    return out


def _self_split(pr: Pairs) -> Pairs:
    """Halve every pair; a diagonal pair (S = T) keeps only its halves with S ≤ T."""
    diag = (pr.s0 == pr.t0) & (pr.s1 == pr.t1)
    four = _halve(pr.take(~diag))
    d = pr.take(diag)
    m = 0.5 * (d.s0 + d.s1)
    three = Pairs(
        np.concatenate([d.s0, d.s0, m]),
        np.concatenate([m, m, d.s1]),
        np.concatenate([d.s0, m, m]),
        np.concatenate([m, d.s1, d.s1]),
    )
    return _concat([four, three])


def self_pairs(p: Part, stats: ab.Stats | None = None) -> list[Found] | None:
    """Every pair s < t with C(s) = C(t) (sorted by s), or None when the curve runs over a
    stretch of itself."""
    stats = stats if stats is not None else ab.Stats()
    width = p.hi - p.lo
    a, b = _grid(p.lo, p.hi)
    i, j = np.triu_indices(a.size)
    start = Pairs(a[i], b[i], a[j], b[j])

    def near(pr: Pairs) -> np.ndarray:
        touching = pr.s1 >= pr.t0
        out = np.zeros(pr.size, dtype=bool)
        sel = np.nonzero(touching)[0]
        if sel.size:
            lo = np.minimum(pr.s0[sel], pr.t0[sel])
            hi = np.maximum(pr.s1[sel], pr.t1[sel])
            out[sel] = _injective(p, lo, hi)
            # narrower than TINY and still not injective: a cusp, not a crossing
            out[sel] |= (hi - lo) <= 2 * TINY * width
        return out

    got = _search(p, p, start, _self_split, near, stats)
    if got is None:
        return None
    found, stuck = got
    found = [f for f in found if f.t - f.s > SAME * width]
    stuck = stuck.take(stuck.t0 - stuck.s1 > 0)
    out = _settle(p, p, found, stuck)
    return [f for f in out if f.t - f.s > SAME * width]
