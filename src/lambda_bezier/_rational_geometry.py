"""Geometry of rational Bézier curves: arc length and its inverse, bounding boxes, closest
points and intersections (the methods of lambda_bezier.rational.RationalBezierCurve).

With A(t) the numerator and w(t) > 0 the denominator of C = A / w (Bernstein coefficients:
the homogeneous rows), C' = N / w² with N = A' w − A w' a polynomial of degree <= 2n − 2.
So the questions that reduce to roots reduce to roots of polynomials:

- bounding box: the extremes of coordinate c are at the ends and at the roots of N_c;
- closest point to q: the critical points of |C − q|² are the roots of (A − q w) · N, a
  polynomial of degree <= 3n − 2. The best candidate is then certified: with D its distance,
  |A − q w|² − D² w² (degree 2n) is checked >= 0 on [0, 1] through its Bernstein
  coefficients, subdividing where they are not (convex hull property); any piece that stays
  below yields a new candidate, so a missed root cannot go unnoticed;
- arc length: the speed |N| / w² is smooth (w > 0), integrated adaptively (Gauss–Legendre on
  each piece against the sum over its halves), with pieces ending at the local minima of
  |N|² (near-cusps, where the speed has a kink or nearly so);
- intersections: subdivision of both homogeneous forms until the boxes of the surviving
  pairs of pieces are small (with positive weights a piece lies in the convex hull of its
  projected control points, so a pair whose boxes are apart holds no intersection), then
  Newton (Gauss–Newton in 3D) from each pair, deduplicated.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from fractions import Fraction
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from . import _validate as val
from .geometry import (
    ClosestPoint,
    _queries,  # the same query validation as every curve
    length_queries,
    lengths_within,
    no_queries,
)
from .hazmat import atom_intersect as ai
from .hazmat import coincide as co
from .hazmat import intersect_exact as ie
from .hazmat import intersect_self_exact as se
from .hazmat import rational_kernels as rk
from .hazmat.intersect import EXACT_CHECK_SINE, SELF_PLACED, SELF_ROUNDING, Intersection

if TYPE_CHECKING:
    from .rational import RationalBezierCurve

RTOL = 1e-12
SAME_ROOT = 1e-7  # intersection parameters closer than this are one intersection
TANGENT_SINE = 1e-5  # below this sine of the angle between tangents an intersection is tangent
ON_CURVE = 1e-10  # Newton's residual must be below this times the curves' size
# relative, per degree: points this close are on both curves when deciding a shared stretch
# (hazmat.intersect.ROOT_RESIDUAL, the polynomial path's rounding of evaluation)
ROOT_RESIDUAL = 64 * float(np.finfo(float).eps)
MERGE_RADIUS = 1e-3  # hits closer than this are compared for being one contact (_one_contact)


def _float_rows(curve: RationalBezierCurve) -> np.ndarray:
    """The homogeneous rows in floats with the largest weight 1 (the curve is unchanged by a
    common factor of the weights; w² then stays near 1)."""
    rows = np.array(curve.to_homogeneous().points, dtype=float)
    out: np.ndarray = rows / rows[:, -1].max()
    return out


def _unit(
    curve: RationalBezierCurve, big: float | None = None
) -> tuple[RationalBezierCurve, float, float]:
    """(unit, f, ρ): the same curve in standard form (w_0 = w_n = 1, by the Möbius map of
    `normalized`: unit(s) = curve(t) with t = ρ s / ((1 − s) + ρ s)) with its points
    divided by f. The standard form spreads the parameter as evenly as such a map can (weights
    of very different size crowd the whole curve into a tiny interval of t, which no
    quadrature or root finder would see); f is a power of two bringing coordinates beyond
    2^±400 near 1, so that |C'|² neither overflows nor underflows (1.0 otherwise). Lengths,
    boxes and distances do not depend on the parameterisation; they scale by f. `big`: the
    magnitude f is chosen for, when other coordinates than the curve's matter (queries)."""
    cached: tuple[RationalBezierCurve, float, float] | None = (
        curve.__dict__.get("_unit") if big is None else None
    )
    if cached is None:
        unit, rho = curve.normalized() if curve.degree else (curve, 1)
        own = big is None
        big = float(np.abs(curve.points).max()) if big is None else big
        factor = 1.0
        if big != 0.0 and not 2.0**-400 <= big <= 2.0**400:
            # 2^1024 is not a float: coordinates near the top of the range get 2^1023
            factor = math.ldexp(1.0, min(math.frexp(big)[1], 1023))
            rows = unit.control_points()
            points = (
                [[v / Fraction(factor) for v in row] for row in rows]
                if unit.is_exact
                else unit.points / factor
            )
            unit = type(curve)(points, unit.control_weights())
        cached = (unit, factor, float(rho))
        if own:
            curve.__dict__["_unit"] = cached
    return cached


def _to_unit(rho: float, t: np.ndarray | float) -> np.ndarray:
    """The unit curve's parameter s at the curve's t (the inverse Möbius map)."""
    out: np.ndarray = np.clip(rk.mobius(1 / rho, np.asarray(t, dtype=float)), 0.0, 1.0)
    return out


def _from_unit(rho: float, s: np.ndarray) -> np.ndarray:
    """The curve's t at the unit curve's parameter s."""
    out: np.ndarray = np.clip(rk.mobius(rho, s), 0.0, 1.0)
    return out


def _exact_or_float_rows(curve: RationalBezierCurve) -> np.ndarray:
    if curve.is_exact:
        return np.array(curve.to_homogeneous().control_points(), dtype=object)
    return _float_rows(curve)


def _roots(coeffs: np.ndarray) -> np.ndarray:
    """Candidate roots in [0, 1] of a scalar polynomial given by Bernstein coefficients
    (Fractions: converted exactly to the centred power form, then rounded once)."""
    centred = rk.bernstein_to_centred(coeffs)
    return rk.roots_in_unit(np.array([float(v) for v in centred]))


def _parameter(value: object, name: str) -> float:
    x = float(val.real_number(value, name, keep_exact=False))
    if not 0 <= x <= 1:
        raise ValueError(f"{name} = {value} is outside [0, 1]")
    return x


# ---------------------------------------------------------------------- arc length
def _table(
    f: Callable[[np.ndarray], np.ndarray], kinks: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    try:
        return rk.adaptive_table(f, RTOL / 4, kinks)
    except ArithmeticError as exc:
        raise ValueError(f"arc length to 1e-12 failed: {exc}") from None


def _speed(curve: RationalBezierCurve):  # type: ignore[no-untyped-def]
    def speed(t: np.ndarray) -> np.ndarray:
        out: np.ndarray = np.linalg.norm(curve.derivative(np.clip(t, 0.0, 1.0), 1), axis=-1)
        return out

    return speed


def _kinks(curve: RationalBezierCurve) -> np.ndarray:
    """The local minima of |N|² in [0, 1] (roots of N · N'): where the speed can bend sharply."""
    if curve.degree < 2:
        return np.empty(0)
    num = rk.derivative_numerator(_float_rows(curve))
    dot = rk.product(num, rk.hodograph(num)).sum(axis=1)
    return _roots(dot)


def arc_length(curve: RationalBezierCurve, t0: Fraction | float, t1: Fraction | float) -> float:
    a, b = _parameter(t0, "t0"), _parameter(t1, "t1")
    if a > b:
        raise ValueError(f"arc_length needs t0 <= t1, got t0={t0}, t1={t1}")
    if a == b:
        return 0.0
    if a == 0.0 and b == 1.0:
        return _finite_length(float(_length_table(curve)[1][-1]))
    curve, factor, rho = _unit(curve)
    a, b = float(_to_unit(rho, a)), float(_to_unit(rho, b))
    if a >= b:
        return 0.0
    speed = _speed(curve)
    kinks = (_kinks(curve) - a) / (b - a)

    def scaled(u: np.ndarray) -> np.ndarray:
        out: np.ndarray = speed(a + (b - a) * u) * (b - a)
        return out

    return _finite_length(factor * float(_table(scaled, kinks)[1][-1]))


def _finite_length(length: float) -> float:
    if not math.isfinite(length):
        raise ValueError(
            "the arc length overflows the float range (above 1.798e+308) for these control "
            "points; scale them down"
        )
    return length


def _length_table(curve: RationalBezierCurve) -> tuple[np.ndarray, np.ndarray]:
    """The accepted partition of [0, 1] and cumulative lengths (cached on the curve)."""
    cached: tuple[np.ndarray, np.ndarray] | None = curve.__dict__.get("_length_table")
    if cached is None:
        unit, factor, _ = _unit(curve)  # the table is in the unit curve's parameter
        edges, cum = _table(_speed(unit), _kinks(unit))
        with np.errstate(over="ignore"):  # a length beyond the floats: arc_length says so
            cached = (edges, cum * factor)
        curve.__dict__["_length_table"] = cached
    return cached


def parameter_at_length(curve: RationalBezierCurve, s: npt.ArrayLike) -> np.ndarray | float:
    arr, scalar = length_queries(s)
    edges, cum = _length_table(curve)
    total = float(cum[-1])
    arr = lengths_within(arr, total)
    unit, factor, rho = _unit(curve)
    speed = _speed(unit)
    k = np.clip(np.searchsorted(cum, arr, side="right") - 1, 0, edges.size - 2)
    base, lo, hi, start = cum[k], edges[k].copy(), edges[k + 1].copy(), edges[k]
    span = cum[k + 1] - base
    with np.errstate(divide="ignore", invalid="ignore"):
        frac = np.where(span > 0, (arr - base) / span, 0.0)
    t = lo + np.clip(frac, 0, 1) * (hi - lo)
    goal = RTOL * total / 16
    for _ in range(100):  # safeguarded Newton inside the accepted piece holding s
        f = base + factor * rk.gauss_pieces(speed, start, t) - arr
        done = np.abs(f) <= goal
        if done.all():
            break
        lo = np.where(f < 0, t, lo)
        hi = np.where(f > 0, t, hi)
        with np.errstate(divide="ignore", invalid="ignore"):
            step = t - f / (factor * speed(t))
        inside = np.isfinite(step) & (step > lo) & (step < hi)
        nxt = np.where(done, t, np.where(inside, step, (lo + hi) / 2))
        if np.array_equal(nxt, t):
            break
        t = nxt
    t = _from_unit(rho, t)
    return float(t[0]) if scalar else t


# ---------------------------------------------------------------------- bounding box
def bounding_box(curve: RationalBezierCurve) -> tuple[np.ndarray, np.ndarray]:
    ends = curve.points[[0, -1]]
    if curve.degree == 0:
        return ends.min(axis=0), ends.max(axis=0)
    unit, factor, _ = _unit(curve)
    num = rk.derivative_numerator(_exact_or_float_rows(unit))
    s = np.concatenate([np.empty(0), *(_roots(num[:, c]) for c in range(curve.dimension))])
    s = s[(s > 1e-12) & (s < 1 - 1e-12)]
    values = np.vstack([ends, unit.evaluate(s) * factor]) if s.size else ends
    return values.min(axis=0), values.max(axis=0)


# ---------------------------------------------------------------------- closest point
def closest_point(curve: RationalBezierCurve, q: npt.ArrayLike) -> ClosestPoint:
    queries, single = _queries(q, curve.dimension)
    if not queries.shape[0]:
        return no_queries(curve.dimension)
    big = max(float(np.abs(curve.points).max()), float(np.abs(queries).max()))
    curve, factor, rho = _unit(curve, big)
    queries = queries / factor
    rows = _float_rows(curve)
    a, w = rows[:, :-1], rows[:, -1:]
    m = queries.shape[0]
    diff = a[:, None, :] - queries[None, :, :] * w[:, :, None]  # (n+1, m, d): A − q w
    cands = [np.zeros(m), np.ones(m)]
    per_query: list[list[np.ndarray]] = [[] for _ in range(m)]
    if curve.degree >= 1:
        num = rk.derivative_numerator(rows)  # (2n, d)
        g = rk.product(diff, num[:, None, :]).sum(axis=-1)  # (3n, m): (A − q w) · N
        centred = rk.bernstein_to_centred(g)
        for j in range(m):
            per_query[j].append(rk.roots_in_unit(centred[:, j]))
    best_t, best_d2 = _best(curve, queries, cands, per_query)
    if curve.degree >= 1:  # the certificate: |A − q w|² − D² w² >= 0 on [0, 1]
        square = rk.product(diff, diff).sum(axis=-1)  # (2n+1, m)
        w2 = rk.product(w, w)[:, 0]
        again = False
        for j in range(m):
            f = square[:, j] - best_d2[j] * w2
            floor = -1e-12 * max(float(np.abs(square[:, j]).max()), 1e-300)
            witnesses = rk.negative_intervals(f, floor)
            if witnesses:
                per_query[j].append(_polish(curve, queries[j], np.array(witnesses)))
                again = True
        if again:
            best_t, best_d2 = _best(curve, queries, cands, per_query)
    points = curve.evaluate(best_t) * factor
    dist = np.sqrt(best_d2) * factor
    best_t = _from_unit(rho, best_t)
    if single:
        return ClosestPoint(float(best_t[0]), points[0], float(dist[0]))
    return ClosestPoint(best_t, points, dist)


def on_curve_parameters(curve: RationalBezierCurve, q: np.ndarray, tol: float) -> list[float]:
    """Every t with |C(t) − q| <= tol, one per root (locate): the ends and the critical
    points of |C − q|² (where C passes through q, d/dt |C − q|² = 0, a simple root wherever
    C' does not vanish), each within tol, parameters closer than 1e-9 taken as one (the
    closest of them). A self-crossing's point is reached at two t, as on the polynomial
    classes (issue #29 round 21: closest_point's one t came back)."""
    if not curve.degree:
        return [0.0] if float(np.linalg.norm(curve.points[0] - q)) <= tol else []
    unit, factor, rho = _unit(curve, max(float(np.abs(curve.points).max()), float(np.abs(q).max())))
    qs = q / factor
    rows = _float_rows(unit)
    a, w = rows[:, :-1], rows[:, -1:]
    diff = a - qs[None, :] * w
    g = rk.product(diff[:, None, :], rk.derivative_numerator(rows)[:, None, :]).sum(axis=-1)
    roots = rk.roots_in_unit(rk.bernstein_to_centred(g)[:, 0])
    t = _polish(unit, qs, np.concatenate([[0.0, 1.0], roots]))
    d = np.linalg.norm(unit.evaluate(t) - qs, axis=-1) * factor
    keep = np.argsort(t)
    out: list[tuple[float, float]] = []  # (t, distance)
    for k in keep:
        if not d[k] <= tol:
            continue
        if out and t[k] - out[-1][0] < 1e-9:
            if d[k] < out[-1][1]:
                out[-1] = (float(t[k]), float(d[k]))
            continue
        out.append((float(t[k]), float(d[k])))
    return [float(_from_unit(rho, np.array([u]))[0]) for u, _ in out]


def _best(
    curve: RationalBezierCurve,
    queries: np.ndarray,
    cands: list[np.ndarray],
    per_query: list[list[np.ndarray]],
) -> tuple[np.ndarray, np.ndarray]:
    m = queries.shape[0]
    best_t = np.empty(m)
    best_d2 = np.empty(m)
    for j in range(m):
        t = np.concatenate([np.array([c[j] for c in cands]), *per_query[j]])
        d2 = np.square(curve.evaluate(t) - queries[j]).sum(axis=-1)
        k = int(np.argmin(d2))
        best_t[j], best_d2[j] = t[k], d2[k]
    return best_t, best_d2


def _polish(curve: RationalBezierCurve, q: np.ndarray, t: np.ndarray) -> np.ndarray:
    """Newton steps on (C − q) · C' = 0 from each t (kept in [0, 1]); the start too."""
    out = [t]
    for _ in range(8):
        c, d1, d2 = (curve.derivative(t, k) for k in range(3))
        g = ((c - q) * d1).sum(-1)
        dg = (d1 * d1).sum(-1) + ((c - q) * d2).sum(-1)
        with np.errstate(divide="ignore", invalid="ignore"):
            step = g / dg
        t = np.where(np.isfinite(step), np.clip(t - step, 0.0, 1.0), t)
        out.append(t)
    return np.concatenate(out)


# ---------------------------------------------------------------------- intersections
def _newton(
    p: RationalBezierCurve, q: RationalBezierCurve, s: np.ndarray, t: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Gauss–Newton on p(s) − q(t) = 0 from every (s, t) at once: (s, t, residual)."""
    for _ in range(80):
        f = p.evaluate(s) - q.evaluate(t)
        jac = np.stack([p.derivative(s, 1), -q.derivative(t, 1)], axis=-1)  # (k, d, 2)
        step = np.einsum("kij,kj->ki", np.linalg.pinv(jac), f)
        s_new = np.clip(s - step[:, 0], 0.0, 1.0)
        t_new = np.clip(t - step[:, 1], 0.0, 1.0)
        if np.array_equal(s_new, s) and np.array_equal(t_new, t):
            break
        s, t = s_new, t_new
    res = np.linalg.norm(p.evaluate(s) - q.evaluate(t), axis=-1)
    return s, t, res


def _kind(p: RationalBezierCurve, q: RationalBezierCurve, s: float, t: float) -> str:
    u, v = p.derivative(s, 1), q.derivative(t, 1)
    nu, nv = float(np.linalg.norm(u)), float(np.linalg.norm(v))
    if nu == 0 or nv == 0:
        return "tangent"
    cross = abs(u[0] * v[1] - u[1] * v[0]) if u.size == 2 else float(np.linalg.norm(np.cross(u, v)))
    return "tangent" if cross / (nu * nv) < TANGENT_SINE else "transversal"


def _size(*curves: RationalBezierCurve) -> float:
    pts = np.vstack([c.points for c in curves])
    return max(float(np.abs(pts).max()), float(np.ptp(pts, axis=0).max()), 1e-300)


def _collect(
    p: RationalBezierCurve,
    q: RationalBezierCurve,
    starts: np.ndarray,
    size: float,
    keep: object = None,
) -> list[Intersection]:
    if not starts.size:
        return []
    s, t, res = _newton(p, q, starts[:, 0], starts[:, 1])
    good = res <= ON_CURVE * size
    if callable(keep):
        good &= keep(s, t)
    order = np.lexsort((res, s))
    found: list[tuple[float, float]] = []
    gap = ROOT_RESIDUAL * max(p.degree, q.degree, 1) * size
    for i in order[good[order]]:
        si, ti = float(s[i]), float(t[i])
        if any(abs(si - a) <= SAME_ROOT and abs(ti - b) <= SAME_ROOT for a, b in found):
            continue
        if any(_one_contact(p, q, (a, b), (si, ti), gap) for a, b in found):
            continue
        found.append((si, ti))
    found.sort()
    return [Intersection(a, b, _kind(p, q, a, b)) for a, b in found]


def _one_contact(
    p: RationalBezierCurve,
    q: RationalBezierCurve,
    a: tuple[float, float],
    b: tuple[float, float],
    gap: float,
) -> bool:
    """Two hits closer than 1e-3 in both parameters are one contact of high order when the
    curves stay within `gap` (the rounding of evaluation) all the way between them: the
    polynomial path's rule (hazmat.intersect._add, MERGE_RADIUS and MERGE_GAP). Newton from
    many starts otherwise stopped all along such a contact (90 "tangent" points within 1e-5
    where two cubics agree to second order at a common end)."""
    if abs(a[0] - b[0]) >= MERGE_RADIUS or abs(a[1] - b[1]) >= MERGE_RADIUS:
        return False
    u = np.linspace(0.0, 1.0, 9)
    between = p.evaluate(a[0] + u * (b[0] - a[0])) - q.evaluate(a[1] + u * (b[1] - a[1]))
    return bool(np.linalg.norm(between, axis=-1).max() <= gap)


def _check_dimension(curve: RationalBezierCurve) -> None:
    if curve.dimension not in (2, 3):
        raise ValueError(
            f"intersections are computed for planar and space curves (dimension 2 or 3), "
            f"this curve has dimension {curve.dimension}"
        )


def intersect(p: RationalBezierCurve, q: RationalBezierCurve) -> list[Intersection]:
    _check_dimension(p)
    # the certified branch and bound (hazmat.atom_intersect: exclusion, Krawczyk uniqueness,
    # one answer per unresolved cluster) finds every crossing; Newton from the subdivision's
    # starts below merged crossings 1e-4 apart (issue #29). It gives up (None) on a shared
    # stretch, which hazmat.coincide then decides under any parameterisation (_shared); a
    # give-up it cannot explain is refused by name by the subdivision.
    size = _size(p, q)
    try:
        # the pieces' boxes first (cheap): all apart (with slack) proves no intersection, by
        # the convex hull property; curves far apart then cost 0.2 ms, not the search's 3-10
        starts: np.ndarray | None = rk.overlap_starts(_float_rows(p), _float_rows(q), size)
    except ValueError:
        starts = None  # too many overlapping pieces: the search tells a contact from a stretch
    if starts is not None and not starts.size:
        return []
    # too many overlapping pieces hint at a shared stretch: decided first (50 ms exact),
    # since the search spends seconds before it gives up on one
    shared = _shared(p, q, size) if starts is None else []
    if shared:
        return _with_stretches(p, q, shared)
    exact = _exact_pair(p, q)
    # with an exact answer to fall back on, the search gives up at MAX_PAIRS open pairs: a
    # contact of high order (a band of pairs too narrow to be a stretch) took it 4-40 s to
    # HARD_MAX_PAIRS, the exact isolation 0.06 s (tests/test_coincide.py)
    found = ai.pairs(
        ai.BernsteinPart(_float_rows(p)),
        ai.BernsteinPart(_float_rows(q)),
        give_up=ai.MAX_PAIRS if exact is not None else ai.HARD_MAX_PAIRS,
    )
    if found is not None:
        return _decided_exactly(p, q, [Intersection(f.s, f.t, f.kind) for f in found])
    shared = _shared(p, q, size) if starts is not None else []
    if shared:
        return _with_stretches(p, q, shared)
    if exact is not None:  # no stretch: the exact isolation answers (None: left undecided)
        got = ie.exact_answer(exact[0][0], exact[0][1], None, exact[1])
        if got is not None:
            return [Intersection(s, t, "tangent" if flat else "transversal") for s, t, flat in got]
    if starts is None:  # pieces overlap all along, yet no shared stretch: refused by name
        how = "exactly" if p.is_exact and q.is_exact else "to the rounding of evaluation"
        raise ValueError(
            f"the curves share no stretch (decided {how}) but stay too close along one for "
            "the certified search to isolate where they meet (more than 20000 pairs of "
            "pieces overlap): rational curves report isolated intersections only"
        )
    return _decided_exactly(p, q, _collect(p, q, starts, size))


Rows = tuple[tuple[Fraction, ...], ...]


def _exact_pair(
    p: RationalBezierCurve, q: RationalBezierCurve
) -> tuple[tuple[Rows, Rows], tuple[tuple[Fraction, ...], tuple[Fraction, ...]]] | None:
    """(the control points, the weights) of two exact planar curves within the exact
    isolation's budget (intersect_exact.algebra().decide_degree_rational), else None."""
    pw, qw = p._exact_weights, q._exact_weights
    if p._exact_points is None or q._exact_points is None or pw is None or qw is None:
        return None
    if p.dimension != 2 or p.degree * q.degree > ie.algebra().decide_degree_rational:
        return None
    return (p._exact_points, q._exact_points), (pw, qw)


def _decided_exactly(
    p: RationalBezierCurve, q: RationalBezierCurve, hits: list[Intersection]
) -> list[Intersection]:
    """hits, or for exact planar curves with a "tangent" hit the exact answer
    (hazmat.intersect_exact on the cross-multiplied system, within its degree budget):
    a touching point proved once, a near-tangency without contact dropped, near-double
    crossings split (issue #29)."""
    exact = _exact_pair(p, q)
    if exact is None:
        return hits
    (p_rows, q_rows), weights = exact
    # a crossing at a small angle may be two merged (as in hazmat.intersect._decided_exactly),
    # and its float parameter is only as good as 1/sine: the exact isolation answers there too
    kinds = [
        "tangent"
        if h.kind == "transversal" and _sine(p, q, h.s, h.t) < EXACT_CHECK_SINE
        else h.kind
        for h in hits
    ]
    got = ie.decided(p_rows, q_rows, 2, 2, kinds, weights=weights)
    if got is None:
        return hits
    return [Intersection(s, t, "tangent" if flat else "transversal") for s, t, flat in got]


def _sine(p: RationalBezierCurve, q: RationalBezierCurve, s: float, t: float) -> float:
    """|sin| of the angle between the tangents at p(s) and q(t); 0 where one vanishes."""
    u, v = p.derivative(s), q.derivative(t)
    size = float(np.linalg.norm(u) * np.linalg.norm(v))
    return abs(float(u[0] * v[1] - u[1] * v[0])) / size if size else 0.0


def _shared(p: RationalBezierCurve, q: RationalBezierCurve, size: float) -> list[co.Stretch]:
    """The stretches p and q share, under any parameterisation (hazmat.coincide): decided
    exactly for exact curves; for float ones, points within the rounding of evaluating the
    curves (the polynomial path's _root_bound: 64 ulps per degree of their size) are on both."""
    if p.is_exact and q.is_exact:
        rp = _exact_rows(p)
        rq = _exact_rows(q)
        if not co.exact_same_curve(rp, rq):
            return []
        return co.stretches(co.exact_side(rp), co.exact_side(rq), 3)
    tol = float(ROOT_RESIDUAL * max(p.degree, q.degree, 1) * size)
    side_p, side_q = co.float_side(_float_rows(p), tol), co.float_side(_float_rows(q), tol)
    return co.stretches(side_p, side_q, max(p.degree * q.degree + 1, 3))


def _exact_rows(curve: RationalBezierCurve) -> tuple[tuple[Fraction, ...], ...]:
    return tuple(tuple(Fraction(v) for v in row) for row in curve.to_homogeneous().control_points())


def _outside(ranges: list[tuple[float, float]]) -> list[tuple[float, float]]:
    """The parts of [0, 1] outside the ranges, wider than SAME_ROOT."""
    out, at = [], 0.0
    for lo, hi in sorted(ranges):
        if lo - at > SAME_ROOT:
            out.append((at, lo))
        at = max(at, hi)
    if 1.0 - at > SAME_ROOT:
        out.append((at, 1.0))
    return out


def _piece(curve: RationalBezierCurve, lo: float, hi: float) -> np.ndarray:
    if (lo, hi) == (0.0, 1.0):
        return _float_rows(curve)
    return _float_rows(curve.segment(Fraction(lo), Fraction(hi)))


def _with_stretches(
    p: RationalBezierCurve, q: RationalBezierCurve, shared: list[co.Stretch]
) -> list[Intersection]:
    """Each shared stretch as its two end pairs ("coincident"), and the isolated crossings of
    the rest: each curve's parts outside its stretches against the whole other curve, by
    the certified search (a part that still gives up is refused by name)."""
    hits = [Intersection(a.s0, a.t0, "coincident") for a in shared]
    hits += [Intersection(a.s1, a.t1, "coincident") for a in shared]
    whole_p, whole_q = ai.BernsteinPart(_float_rows(p)), ai.BernsteinPart(_float_rows(q))
    t_ranges = [(min(a.t0, a.t1), max(a.t0, a.t1)) for a in shared]
    for lo, hi in _outside([(a.s0, a.s1) for a in shared]):
        got = ai.pairs(ai.BernsteinPart(_piece(p, lo, hi)), whole_q)
        if got is None:
            raise ValueError(_REFUSED)
        hits += [Intersection(lo + f.s * (hi - lo), f.t, f.kind) for f in got]
    for lo, hi in _outside(t_ranges):
        got = ai.pairs(whole_p, ai.BernsteinPart(_piece(q, lo, hi)))
        if got is None:
            raise ValueError(_REFUSED)
        hits += [Intersection(f.s, lo + f.t * (hi - lo), f.kind) for f in got]
    out: list[Intersection] = []
    for h in sorted(hits, key=lambda h: h.kind != "coincident"):  # the stretches' ends first
        if not any(abs(h.s - o.s) <= SAME_ROOT and abs(h.t - o.t) <= SAME_ROOT for o in out):
            out.append(h)
    return sorted(out)


_REFUSED = (
    "the curves share a stretch, and the certified search gave up on the rest of them: "
    "rational curves report isolated intersections only there"
)


def _monotone_pieces(curve: RationalBezierCurve) -> list[tuple[float, float, np.ndarray]]:
    """[0, 1] cut in halves until on every piece C' keeps a direction (then the piece cannot
    meet itself): (lo, hi, homogeneous rows) each."""
    todo = [(0.0, 1.0, _float_rows(curve))]
    done = []
    while todo:
        lo, hi, rows = todo.pop()
        if rk.monotone(rk.derivative_numerator(rows)):
            done.append((lo, hi, rows))
            continue
        if hi - lo < 2.0**-16:
            raise ValueError(
                f"self_intersections: C'(t) vanishes or nearly so near t = {lo:.6g} (a cusp); "
                "such curves are not supported"
            )
        left, right = rk.split_halves(rows[None])
        mid = (lo + hi) / 2
        todo += [(lo, mid, left[0]), (mid, hi, right[0])]
    return sorted(done, key=lambda piece: piece[0])


def self_intersections(curve: RationalBezierCurve) -> list[Intersection]:
    """The float answer (_float_self_intersections), or for an exact planar curve in doubt the
    exact one (hazmat.intersect_self_exact on X(s) W(t) − X(t) W(s) divided by s − t, within
    its degree budget): where the float answer has a "tangent" hit or a crossing whose
    tangents' sine is below EXACT_CHECK_SINE (near-double crossings merged), or where it
    refuses a curve with a cusp (C' vanishing: an exact cusp is no crossing, a loop next to it
    is one)."""
    _check_dimension(curve)
    if curve.degree < 2:
        return []
    try:
        hits, gave_up = _float_self_intersections(curve)
    except ValueError:
        exact = _self_decided_exactly(curve)
        if exact is None:
            raise
        return exact
    size = _size(curve)
    if gave_up or any(
        h.kind == "tangent"
        or _sine(curve, curve, h.s, h.t) < EXACT_CHECK_SINE
        or _float_error(curve, h, size) > SELF_PLACED
        for h in hits
    ):
        exact = _self_decided_exactly(curve)
        if exact is not None:
            return exact
    return hits


def _float_error(curve: RationalBezierCurve, h: Intersection, size: float) -> float:
    """How far rounding can move a self-crossing found in floats, in parameter (exact input
    past SELF_PLACED is decided exactly): the points round by about n eps of the size
    (SELF_ROUNDING per degree, hazmat.intersect), and the root moves by that
    over the smallest singular value of the Jacobian [C'(s) | -C'(t)]. On a small loop next
    to a cusp both speeds and the angle between them are small: the cubic (0,0), (a,1),
    (1-a,1), (1,0) with a = 1 + 8/3 10^-8 crosses itself at s = 0.4999, where this is 2e-9
    (and the float search was 3.6e-10 off)."""
    jac = np.stack([curve.derivative(h.s), -curve.derivative(h.t)], axis=1)
    smallest = float(np.linalg.svd(jac, compute_uv=False)[-1])
    rounding = SELF_ROUNDING * curve.degree * size
    return rounding / smallest if smallest > 0.0 else math.inf


def _self_decided_exactly(curve: RationalBezierCurve) -> list[Intersection] | None:
    rows, weights = curve._exact_points, curve._exact_weights
    if rows is None or weights is None or curve.dimension != 2:
        return None
    got = se.self_decided(rows, 2, weights=weights)
    if got is None:
        return None
    return [Intersection(s, t, "tangent" if flat else "transversal") for s, t, flat in got]


def _float_self_intersections(curve: RationalBezierCurve) -> tuple[list[Intersection], bool]:
    """The self-crossings found in floats, and whether the certified search gave up (then
    they come from Newton starts, _fallback_self_intersections)."""
    found = ai.self_pairs(ai.BernsteinPart(_float_rows(curve)))
    if found is not None:
        return [Intersection(f.s, f.t, f.kind) for f in found], False
    return _fallback_self_intersections(curve), True


def _fallback_self_intersections(curve: RationalBezierCurve) -> list[Intersection]:
    pieces = _monotone_pieces(curve)
    size = _size(curve)
    starts = []
    for i, (alo, ahi, arows) in enumerate(pieces):
        for blo, bhi, brows in pieces[i + 1 :]:
            local = rk.overlap_starts(arows, brows, size)
            if local.size:
                starts.append(
                    np.column_stack(
                        [alo + local[:, 0] * (ahi - alo), blo + local[:, 1] * (bhi - blo)]
                    )
                )
    if not starts:
        return []

    def apart(s: np.ndarray, t: np.ndarray) -> np.ndarray:
        out: np.ndarray = np.abs(s - t) > math.sqrt(SAME_ROOT)
        return out

    hits = _collect(curve, curve, np.vstack(starts), size, apart)
    pairs = sorted({(min(h.s, h.t), max(h.s, h.t)) for h in hits})
    merged: list[tuple[float, float]] = []
    for a, b in pairs:
        if not any(abs(a - x) <= SAME_ROOT and abs(b - y) <= SAME_ROOT for x, y in merged):
            merged.append((a, b))
    return [Intersection(a, b, _kind(curve, curve, a, b)) for a, b in merged]
