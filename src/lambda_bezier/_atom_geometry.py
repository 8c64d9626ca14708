"""Geometry of curves of non-polynomial families (atom_family.AtomCurve), numerically.

Curves with an exact rational form do their geometry on it (atom_family); this module serves
the others (hyperbolic families on a domain where tanh is irrational, mixed
algebraic-trigonometric families) and intersections between any two curves.

The accuracy promises are those of the polynomial and rational curves, reached differently:
- `arc_length`: adaptive Gauss-Legendre on the exact speed |C'(t)|, relative 1e-12;
- `bounding_box` and `closest_point`: certified, by branch and bound in t on rigorous Taylor
  enclosures of the coordinates and their derivatives (hazmat.atom_bounds): an interval is
  dropped only when its enclosure proves it holds nothing better, or when a derivative of one
  sign leaves at most one candidate in it, found by bisection to the last bit of t. So no
  extreme is missed however narrow (a spike between the points of any fixed grid is found),
  up to the enclosures' rounding allowance (a few ulps of the curve's size);
- `intersect` and `self_intersections` of a curve without a rational form, in 2D and 3D:
  certified, by the branch and bound of hazmat.atom_intersect (every crossing found, proven
  single by Krawczyk's test or reported once per unresolved cluster as a tangency). Curves
  that share a stretch (the search gives up) and curves with a rational form: the curve is
  approximated piece by piece by polynomial Bézier curves (Chebyshev interpolation of degree
  `DEGREE`, pieces halved until the approximation is within 1e-13 of the curve's size at a
  check grid), those are intersected by the polynomial code, and every candidate is
  polished by Newton's method on the exact curves;
- export (`certified_pieces`): pieces within a chosen tolerance, the bound certified by
  hazmat.atom_deviation.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from . import _validate as val
from .curves import BezierCurve, Curve
from .geometry import ClosestPoint, length_queries
from .hazmat import atom_bounds as ab
from .hazmat import atom_intersect as ai
from .hazmat import intersect_kind as _kind
from .hazmat import intersect_locate as _intersect
from .hazmat.intersect import Intersection
from .hazmat.intersect_prepared import NORMAL_EXPONENT
from .rational import RationalBezierCurve

if TYPE_CHECKING:
    from .atom_family import AtomCurve

# the degree of the polynomial pieces approximating a curve: low enough that the Bernstein
# collocation at Chebyshev points is well conditioned (the pieces then reach 1e-13 of the
# size instead of stalling on amplified rounding), and a DXF SPLINE holds it (degree <= 10)
DEGREE = 9
EXPORT_DEGREE = DEGREE
APPROX_TOL = 1e-13  # relative to the curve's size
MAX_PIECES = 512
SAME = 1e-9  # parameters closer than this (relative to the domain) are one intersection
END_ULPS = 4  # a parameter this many ulps (of the domain) from an end is at the end
MERGE_RADIUS = 1e-3  # intersect.MERGE_RADIUS, relative to the domain: _merged_contacts
EPS = float(np.finfo(float).eps)


def _size(curve: AtomCurve) -> float:
    pts = curve.points
    return max(float(np.abs(pts).max()), float(np.ptp(pts, axis=0).max()), 1e-300)


def _nodes(a: float, b: float, count: int) -> np.ndarray:
    k = np.arange(count)
    x = -np.cos(np.pi * (k + 0.5) / count)  # Chebyshev points of the first kind, increasing
    return a + (b - a) * (x + 1) / 2


def _bernstein_collocation(u: np.ndarray, n: int) -> np.ndarray:
    from math import comb

    i = np.arange(n + 1)
    binom = np.array([comb(n, j) for j in i], dtype=float)
    return binom * u[:, None] ** i * (1 - u[:, None]) ** (n - i)


def pieces(curve: AtomCurve, degree: int = DEGREE) -> list[tuple[float, float, BezierCurve]]:
    """(a, b, B): polynomial Bézier curves B(u) of `degree`, u ∈ [0, 1] ↔ t = a + u (b − a),
    each within APPROX_TOL · size of the curve (checked on a grid of 4 · degree + 1 points
    per piece; pieces are halved until it holds, up to MAX_PIECES)."""
    cache: dict[int, list[tuple[float, float, BezierCurve]]] = curve.__dict__.setdefault(
        "_pieces", {}
    )
    if degree in cache:
        return cache[degree]
    lo, hi = curve.domain
    tol = APPROX_TOL * _size(curve)
    u_nodes = _nodes(0.0, 1.0, degree + 1)
    colloc = np.linalg.inv(_bernstein_collocation(u_nodes, degree))
    u_check = np.linspace(0.0, 1.0, 4 * degree + 1)
    check = _bernstein_collocation(u_check, degree)
    count = 4
    best: tuple[float, list[tuple[float, float, BezierCurve]]] | None = None
    while True:
        edges = np.linspace(lo, hi, count + 1)
        edges[-1] = hi
        out: list[tuple[float, float, BezierCurve]] = []
        worst = 0.0
        for a, b in zip(edges[:-1], edges[1:], strict=True):
            ctrl = colloc @ curve.evaluate(a + (b - a) * u_nodes, extrapolate=True)
            err = np.abs(check @ ctrl - curve.evaluate(a + (b - a) * u_check, extrapolate=True))
            worst = max(worst, float(err.max()))
            out.append((float(a), float(b), BezierCurve(ctrl)))
        if best is not None and worst > best[0] / 4:
            break  # rounding, not the approximation, dominates: halving gains nothing more
        best = (worst, out)
        if worst <= tol or count >= MAX_PIECES:
            break
        count *= 2
    assert best is not None
    curve.__dict__.setdefault("_approximation_error", {})[degree] = best[0]
    cache[degree] = best[1]
    return best[1]


# ---------------------------------------------------------------------- arc length
_GL = np.polynomial.legendre.leggauss(20)
_GL2 = np.polynomial.legendre.leggauss(30)


def _speed(d: np.ndarray) -> np.ndarray:
    """‖d‖ along the last axis, the squares taken after dividing by a power of two near the
    largest entry (exact): coordinates near 2^±600 squared past the float range, so the
    speed was inf (the adaptive rule then halved to depth 40 on every branch) or 0 (a
    curve of size 2^-600 had length 0)."""
    top = float(np.max(np.abs(d))) if d.size else 0.0
    if top == 0 or not math.isfinite(top):
        return np.asarray(np.linalg.norm(d, axis=-1))
    shift = math.frexp(top)[1]
    return np.asarray(np.ldexp(np.linalg.norm(np.ldexp(d, -shift), axis=-1), shift))


def _gauss(curve: AtomCurve, a: float, b: float, rule: tuple[np.ndarray, np.ndarray]) -> float:
    x, w = rule
    t = a + (b - a) * (x + 1) / 2
    speed = _speed(curve.derivative(t, 1, extrapolate=True))
    return float((b - a) / 2 * (w @ speed))


def _adaptive(curve: AtomCurve, a: float, b: float, tol: float, depth: int = 0) -> float:
    coarse = _gauss(curve, a, b, _GL)
    fine = _gauss(curve, a, b, _GL2)
    if abs(fine - coarse) <= tol or depth >= 40 or b - a <= 1e-15 * max(1.0, abs(a)):
        return fine
    m = 0.5 * (a + b)
    return _adaptive(curve, a, m, tol / 2, depth + 1) + _adaptive(curve, m, b, tol / 2, depth + 1)


def arc_length(curve: AtomCurve, a: float, b: float) -> float:
    if a == b:
        return 0.0
    spans = [(max(pa, a), min(pb, b)) for pa, pb, _ in pieces(curve)]
    spans = [(lo, hi) for lo, hi in spans if lo < hi]
    roughs = [_gauss(curve, lo, hi, _GL) for lo, hi in spans]
    # each piece to 1e-13 of itself, or of its share of the whole: a piece far shorter than
    # the rest (the tail of exp(-40 t), 1e-10 long) cannot reach 1e-13 of its own length
    # through the rounding of its speed, and halving it to depth 40 never ended
    share = sum(abs(r) for r in roughs) / max(len(spans), 1)
    total = 0.0
    for (lo, hi), rough in zip(spans, roughs, strict=True):
        total += _adaptive(curve, lo, hi, 1e-13 * max(abs(rough), share, 1e-300))
    return total


def parameter_at_length(curve: AtomCurve, s: npt.ArrayLike) -> np.ndarray | float:
    flat, scalar = length_queries(s)
    lo, hi = curve.domain
    total = arc_length(curve, lo, hi)
    if flat.size and (flat.min() < 0 or flat.max() > total * (1 + 1e-12)):
        raise ValueError(f"s must lie in [0, {total}] (the curve's length), got {flat}")
    edges = [lo] + [p[1] for p in pieces(curve)]
    cum = np.cumsum(
        [0.0] + [arc_length(curve, x, y) for x, y in zip(edges[:-1], edges[1:], strict=True)]
    )
    out = np.empty_like(flat)
    for idx, target in enumerate(flat):
        k = int(min(np.searchsorted(cum, target, side="right") - 1, len(edges) - 2))
        a, b = edges[k], edges[k + 1]
        base = cum[k]
        x = a + (b - a) * (target - base) / max(cum[k + 1] - base, 1e-300)
        for _ in range(60):  # safeguarded Newton on L(x) = target
            f = base + arc_length(curve, a, x) - target
            speed = float(_speed(curve.derivative(x, 1, extrapolate=True)))
            step = f / speed if speed > 0 else 0.0
            new = min(max(x - step, edges[k]), edges[k + 1])
            if abs(new - x) <= 1e-15 * max(1.0, abs(x)):
                x = new
                break
            x = new
        out[idx] = x
    return float(out[0]) if scalar else out


# ---------------------------------------------------------------------- boxes
def _bounds_data(curve: AtomCurve) -> ab.AtomCurveData:
    """The curve over its centred atoms (coefficients divided by the curve's power-of-two
    scale), for the certified kernels of hazmat.atom_bounds."""
    cached: ab.AtomCurveData | None = curve.__dict__.get("_bounds_data")
    if cached is None:
        sh = curve.shape
        cached = ab.AtomCurveData(curve._centred, sh.omega0, sh.powers, sh.harmonics, sh.hyperbolic)
        curve.__dict__["_bounds_data"] = cached
    return cached


def bounding_box(curve: AtomCurve) -> tuple[np.ndarray, np.ndarray]:
    """The certified tight box (hazmat.atom_bounds.coordinate_extremes), in t."""
    lo, hi = curve.domain
    data = _bounds_data(curve)
    mins, maxs, _, _ = ab.coordinate_extremes(data, lo - curve._mid, hi - curve._mid)
    ends = curve.evaluate(np.array([lo, hi]))
    with val.overflow_allowed():
        mins, maxs = mins * curve._scale, maxs * curve._scale
    return np.minimum(mins, ends.min(axis=0)), np.maximum(maxs, ends.max(axis=0))


# ---------------------------------------------------------------------- closest points
def closest_point(curve: AtomCurve, q: npt.ArrayLike) -> ClosestPoint:
    """The certified global minimum of |C(t) − q| (hazmat.atom_bounds.closest) per query."""
    from .geometry import _queries

    queries, single = _queries(q, curve.dimension)
    lo, hi = curve.domain
    data = _bounds_data(curve)
    ts = np.empty(len(queries))
    for k, qq in enumerate(queries):
        unit_q = qq / curve._scale
        # |C − q|² passes the float range for a query past 2^512 (the sum of squares from
        # 2^511), and underflows for a curve and query below 2^-500 (at 2^-700 a point on
        # the curve was not located): curve and query scaled together by a power of two
        # (exact, the same minimiser) when either is beyond 2^±256, the query then at most
        # 2^256 and the curve's coefficients normal floats
        big_q = float(np.abs(unit_q).max())
        own = math.frexp(float(np.abs(curve._centred).max()))[1]
        q_exp = math.frexp(big_q)[1] if big_q else own
        shift = max(own, q_exp - 256) if q_exp > 256 or not -256 <= own <= 256 else 0
        if shift:
            sh = curve.shape
            scaled = ab.AtomCurveData(
                np.ldexp(curve._centred, -shift), sh.omega0, sh.powers, sh.harmonics, sh.hyperbolic
            )
            tau, _ = ab.closest(scaled, np.ldexp(unit_q, -shift), lo - curve._mid, hi - curve._mid)
        else:
            tau, _ = ab.closest(data, unit_q, lo - curve._mid, hi - curve._mid)
        ts[k] = min(max(tau + curve._mid, lo), hi)
    points = curve.evaluate(ts)
    # the difference (and its square) can pass the float range for a query far away (from
    # 1e154 on the norm came back inf): the norm is taken at a power-of-two scale, exactly
    with val.overflow_allowed():
        pre = 0 if np.isfinite(points - queries).all() else 2
        diff = np.ldexp(points, -pre) - np.ldexp(queries, -pre)
        big = float(np.abs(diff).max()) if diff.size else 0.0
        shift = math.frexp(big)[1] if big > 0.0 else 0
        dists = np.ldexp(np.linalg.norm(np.ldexp(diff, -shift), axis=1), shift + pre)
    if single:
        return ClosestPoint(float(ts[0]), points[0], float(dists[0]))
    return ClosestPoint(ts, points, dists)


def locate(curve: AtomCurve, point: object) -> float | None:
    """The closest point's t when within 1e-10 of the size; a ValueError when the point is
    on the curve at several t (a self-crossing) or the curve is a single point, as on the
    polynomial classes: the other t are those located on the polynomial pieces (each
    within APPROX_TOL of the curve) whose curve point is within the tolerance too."""
    arr = val.as_point(point, curve.dimension)
    if not np.ptp(np.asarray(curve.points, float), axis=0).any():
        raise ValueError("the curve is a single point: every t gives it")
    found = closest_point(curve, arr)
    tol = 1e-10 * _size(curve)
    if not float(found.distance) <= tol:
        return None
    best = float(found.t)
    others: list[float] = []
    for a, b, piece in pieces(curve):
        for u in _intersect.locate_point(piece._prepared, arr, None):
            t = a + (b - a) * u
            near = [best, *others]
            if min(abs(t - x) for x in near) >= 1e-9 and (
                float(np.linalg.norm(curve.evaluate(t) - arr)) <= tol
            ):
                others.append(t)
    if others:
        several = sorted([best, *others])
        raise ValueError(f"the point is on the curve at several parameters: {several}")
    return best


# ---------------------------------------------------------------------- intersections
def _as_parts(curve: Any) -> list[tuple[Any, Any]]:
    """[(polynomial or rational curve, its parameter -> the caller's t)]."""
    if _is_atom(curve):
        if curve.has_rational_form:
            return [(curve.to_rational_bezier(), curve.t_of_s)]
        return [(b, lambda u, a=a, w=bb - a: a + w * np.asarray(u)) for a, bb, b in pieces(curve)]
    if isinstance(curve, Curve | RationalBezierCurve):
        return [(curve, lambda u: u)]
    raise TypeError(f"other must be a curve, got {type(curve).__name__}")


def _pair(p: Any, q: Any) -> list[Intersection]:
    if isinstance(p, RationalBezierCurve):
        return p.intersect(q)
    if isinstance(q, RationalBezierCurve):
        return [Intersection(x.t, x.s, x.kind) for x in q.intersect(p)]
    return p.intersect(q)  # type: ignore[no-any-return]


def _polish(p: Any, q: Any, s: float, t: float) -> tuple[float, float]:
    """Newton's method on p(s) − q(t) = 0 (least squares in 3D), on the exact curves."""

    def ev(c: Any, x: float, k: int) -> np.ndarray:
        return np.asarray(
            c.derivative(x, k, extrapolate=True) if k else c.evaluate(x, extrapolate=True)
        )

    def system(s: float, t: float) -> tuple[np.ndarray, np.ndarray]:
        f = ev(p, s, 0) - ev(q, t, 0)
        return f, np.stack([ev(p, s, 1), -ev(q, t, 1)], axis=1)

    for _ in range(30):
        f, jac = system(s, t)
        step, *_ = np.linalg.lstsq(jac, -f, rcond=None)
        if not np.isfinite(step).all():
            break
        s, t = s + float(step[0]), t + float(step[1])
        if abs(step).max() <= 1e-15:
            break
    return ai.onto_domains(system, s, t, (*_dom(p), *_dom(q)))


def _is_atom(c: object) -> bool:
    # an AtomCurve (atom_family sits above this module: no import of it here)
    return hasattr(c, "has_rational_form") and hasattr(c, "shape")


def _dom(c: Any) -> tuple[float, float]:
    return c.domain if _is_atom(c) else (0.0, 1.0)


def _part(c: Any) -> tuple[Any, float]:
    """(hazmat.atom_intersect part, the offset from its parameter to the curve's t)."""
    if _is_atom(c):
        lo, hi = c.domain
        return ai.AtomPart(_bounds_data(c), lo - c._mid, hi - c._mid, c._scale), c._mid
    if isinstance(c, RationalBezierCurve):
        rows = np.asarray(c.to_homogeneous().points, dtype=float)
    else:
        pts = np.asarray(c.to_bezier().points, dtype=float)
        rows = np.hstack([pts, np.ones((pts.shape[0], 1))])
    return ai.BernsteinPart(rows), 0.0


def _normalised_parts(*parts: Any) -> tuple[Any, ...]:
    """The certified search's parts divided by one power of two (the same parameters) when
    their size is beyond 2^±NORMAL_EXPONENT (as hazmat.intersect.normalised): at 2^-700 a
    trigonometric curve's crossing with a line was lost and the other called "tangent", at
    2^1000 the search overflowed."""
    top = max(math.frexp(part.size)[1] for part in parts)
    if -NORMAL_EXPONENT <= top <= NORMAL_EXPONENT:
        return parts
    out: list[Any] = []
    for part in parts:
        if isinstance(part, ai.AtomPart):
            out.append(ai.AtomPart(part.data, part.lo, part.hi, math.ldexp(part.scale, -top)))
        else:
            rows = part.rows.copy()
            rows[:, :-1] = np.ldexp(rows[:, :-1], -top)  # the coordinates, not the weights
            out.append(ai.BernsteinPart(rows, part.lo, part.hi))
    return tuple(out)


def intersect(p: AtomCurve, q: Any) -> list[Intersection]:
    if not isinstance(q, Curve | RationalBezierCurve) and not _is_atom(q):
        raise TypeError(f"other must be a curve, got {type(q).__name__}")
    if q.dimension != p.dimension:
        raise ValueError(f"the curves have different dimensions ({p.dimension} and {q.dimension})")
    for name, c in (("the first", p), ("the second", q)):
        pts = np.asarray(c.points if hasattr(c, "points") else c.to_bezier().points, float)
        if not np.ptp(pts, axis=0).any():
            raise ValueError(f"{name} curve is a single point: use locate() on the other")
    # the certified search on the atoms' enclosures first, also where a rational form exists:
    # Newton from the rational pieces' starts merged crossings 3.6e-4 apart (issue #29), and
    # the search on the rational form's blossoms costs about 10x this one
    if p.dimension in (2, 3):
        (pp, ps), (qq, qs) = _part(p), _part(q)
        pp, qq = _normalised_parts(pp, qq)
        certified = ai.pairs(pp, qq)
        if certified is not None:
            hits = [Intersection(f.s + ps, f.t + qs, f.kind) for f in certified]
            # float hits merged by the polynomial rule; not the exact answer, which parts
            # crossings 3e-7 apart whose curves stay closer than that rule's gap
            return _at_ends(p, q, _decided_exactly(p, q, _merged_contacts(p, q, hits)))
    return _at_ends(p, q, _merged_contacts(p, q, _pieces_intersect(p, q)))


def _exact_form(c: Any) -> tuple[RationalBezierCurve, Any, Any] | None:
    """(the exact rational Bézier form, its s -> the curve's t, t -> s), or None where the
    curve has none (floats, a mixed or hyperbolic family)."""
    if _is_atom(c):
        if not (c.has_rational_form and c.is_exact):
            return None
        form = c.to_rational_bezier()
        return (form, c.t_of_s, c.s_of_t) if form.is_exact else None
    if not c.is_exact:
        return None
    form = c if isinstance(c, RationalBezierCurve) else RationalBezierCurve.from_bezier(c)
    return form, float, float


def _decided_exactly(p: Any, q: Any, hits: list[Intersection]) -> list[Intersection]:
    """hits, or where both curves have exact rational forms (exact trigonometric curves,
    exact polynomial and rational ones) and the search reports a "tangent" hit or a crossing
    at a small angle, the exact isolation's answer on those forms (_rational_geometry's, in
    its degree budget), mapped back to t: a cluster of two crossings 3e-7 apart (a line
    1e-13 above a trigonometric curve's minimum) came back as one "tangent" hit."""
    if p.dimension != 2 or not hits:
        return hits
    form_p, form_q = _exact_form(p), _exact_form(q)
    if form_p is None or form_q is None:
        return hits
    from . import _rational_geometry as rg

    (fp, p_t, p_s), (fq, q_t, q_s) = form_p, form_q
    in_s = [Intersection(float(p_s(h.s)), float(q_s(h.t)), h.kind) for h in hits]
    got = rg._decided_exactly(fp, fq, in_s)
    if got is in_s:
        return hits
    return [Intersection(float(p_t(h.s)), float(q_t(h.t)), h.kind) for h in got]


def _at_ends(p: Any, q: Any, hits: list[Intersection]) -> list[Intersection]:
    """hits with a parameter within a few ulps of its domain's end at that end exactly: the
    search and the shift from its parameter to t round (two pieces of a spline met at their
    join at t = 1.1e-16, a curve against its reversal at 0.9999999999999999)."""
    (a, b), (c, d) = _dom(p), _dom(q)
    hits = [h._replace(s=_snapped(h.s, a, b), t=_snapped(h.t, c, d)) for h in hits]
    # every length below at the size's power of two (exactly): curves at 2^1000 overflowed
    shift = _size_exponent(p, q)
    bound = 64 * EPS * max(_any_degree(p), _any_degree(q), 1) * _any_size(p, q, shift)
    hits = _kind.at_ends(
        hits,
        lambda x: np.ldexp(np.asarray(p.evaluate(x), float), -shift),
        lambda x: np.ldexp(np.asarray(q.evaluate(x), float), -shift),
        ((a, b), (c, d)),
        bound,
    )
    return [_one_sided(p, q, h, shift) for h in hits]


def _size_exponent(p: Any, q: Any) -> int:
    return max(math.frexp(_any_size(c))[1] for c in (p, q))


def _merged_contacts(p: Any, q: Any, hits: list[Intersection]) -> list[Intersection]:
    """hits, two closer than MERGE_RADIUS in both parameters taken as one when the curves stay
    within the meeting rounding (64 ε per degree of the size) of each other all the way
    between them: the polynomial classes' rule (intersect._add). A C-Bézier curve leaving a
    line tangentially with zero speed stays within 1e-16 of it for 6e-6 of its domain, and
    its rounding crossed the line there, a second "transversal" hit (issue #29 round 21).
    The hit at a domain end, else the first, stays."""
    if len(hits) < 2:
        return hits
    (a, b), (c, d) = _dom(p), _dom(q)
    shift = _size_exponent(p, q)  # lengths at the size's power of two (2^1000 overflowed)
    bound = 64 * EPS * max(_any_degree(p), _any_degree(q), 1) * _any_size(p, q, shift)
    out: list[Intersection] = []
    for h in hits:
        old = out[-1] if out else None
        if (
            old is not None
            and "coincident" not in (old.kind, h.kind)
            and abs(h.s - old.s) < MERGE_RADIUS * (b - a)
            and abs(h.t - old.t) < MERGE_RADIUS * (d - c)
        ):
            u = np.linspace(0.0, 1.0, 9)
            ps = np.ldexp(np.asarray(p.evaluate(old.s + u * (h.s - old.s)), float), -shift)
            qt = np.ldexp(np.asarray(q.evaluate(old.t + u * (h.t - old.t)), float), -shift)
            tangent = np.ldexp(
                np.asarray(q.derivative(old.t + u * (h.t - old.t), 1), float), -shift
            )
            r = ps - qt
            norms = np.einsum("ij,ij->i", tangent, tangent)
            along = np.where(
                norms > 0, np.einsum("ij,ij->i", r, tangent) / np.where(norms > 0, norms, 1), 0
            )
            gap = float(np.linalg.norm(r - along[:, None] * tangent, axis=1).max())
            if gap <= bound:
                if _near_end(h.s, a, b) or _near_end(h.t, c, d):
                    out[-1] = h
                continue
        out.append(h)
    return out


def _near_end(x: float, lo: float, hi: float) -> bool:
    return min(abs(x - lo), abs(x - hi)) <= _kind.STOPPED_END * (hi - lo)


def _one_sided(p: Any, q: Any, h: Intersection, shift: int) -> Intersection:
    """h's kind where a curve stops (zero speed: a repeated end control point, a cusp) from
    the one-sided tangent, its first derivative that does not vanish (intersect_kind, the
    polynomial classes' rule); the search took the rounding of a zero derivative for a
    direction."""
    if h.kind == "coincident":
        return h
    dirs = []
    stopped = False
    for c, x in ((p, h.s), (q, h.t)):
        lo, hi = _dom(c)
        n = max(_any_degree(c), 1)
        small = 64 * EPS * n * _any_size(c, None, shift)
        v = None
        for k in range(1, n + 2):
            d = np.ldexp(np.asarray(c.derivative(x, k), float), -shift) * (hi - lo) ** k
            if float(np.linalg.norm(d)) > small * 2**k:
                v = d
                break
            stopped = True
        dirs.append(v)
    if not stopped or dirs[0] is None or dirs[1] is None:
        return h
    return h._replace(
        kind="tangent" if _kind.sine(dirs[0], dirs[1]) <= ai.TANGENT_SINE else "transversal"
    )


def _any_size(c: Any, other: Any = None, shift: int = 0) -> float:
    """The larger of the curves' largest coordinate and extent, times 2^-shift."""
    out = 0.0
    for curve in (c,) if other is None else (c, other):
        pts = np.ldexp(np.asarray(curve.points, float), -shift)
        out = max(out, float(np.abs(pts).max()), float(np.ptp(pts, axis=0).max()))
    return out


def _any_degree(c: Any) -> int:
    return int(np.asarray(c.points).shape[0]) - 1


def _snapped(x: float, lo: float, hi: float) -> float:
    tol = END_ULPS * math.ulp(max(abs(lo), abs(hi), hi - lo))
    return lo if abs(x - lo) <= tol else hi if abs(x - hi) <= tol else x


def _pieces_intersect(p: AtomCurve, q: Any) -> list[Intersection]:
    """Through polynomial pieces (curves that share a stretch, or with a rational form). A
    stretch shared piece by piece (the polynomial or rational path's "coincident" end pairs)
    is joined with its neighbours into one, and hits inside it are dropped."""
    found: list[tuple[float, float, str]] = []
    stretches: list[tuple[float, float, float, float]] = []
    for pc, pmap in _as_parts(p):
        for qc, qmap in _as_parts(q):
            got = _pair(pc, qc)
            ends = [x for x in got if x.kind == "coincident"]
            for a, b in zip(ends[::2], ends[1::2], strict=True):
                stretches.append(
                    (float(pmap(a.s)), float(pmap(b.s)), float(qmap(a.t)), float(qmap(b.t)))
                )
            for x in got:
                if x.kind != "coincident":
                    found.append((*_polish(p, q, float(pmap(x.s)), float(qmap(x.t))), x.kind))
    width = max(_dom(p)[1] - _dom(p)[0], _dom(q)[1] - _dom(q)[0], 1e-300)
    joined = _joined(stretches, SAME * width)
    for s0, s1, t0, t1 in joined:
        found += [(s0, t0, "coincident"), (s1, t1, "coincident")]
    found.sort()
    out: list[Intersection] = []
    for s, t, kind in found:
        if out and abs(s - out[-1].s) <= SAME * width and abs(t - out[-1].t) <= SAME * width:
            continue  # the same point found in two neighbouring pieces
        if kind != "coincident" and _within(joined, s, t, SAME * width):
            continue
        out.append(Intersection(s, t, kind))
    return out


def _joined(
    stretches: list[tuple[float, float, float, float]], tol: float
) -> list[tuple[float, float, float, float]]:
    """Stretches (s0 < s1, t0, t1) chained where one ends where the next begins (both
    parameters within tol): neighbouring pieces of one shared stretch."""
    out: list[tuple[float, float, float, float]] = []
    for s0, s1, t0, t1 in sorted(stretches):
        if out and abs(s0 - out[-1][1]) <= tol and abs(t0 - out[-1][3]) <= tol:
            out[-1] = (out[-1][0], s1, out[-1][2], t1)
        else:
            out.append((s0, s1, t0, t1))
    return out


def _within(
    stretches: list[tuple[float, float, float, float]], s: float, t: float, tol: float
) -> bool:
    return any(
        s0 - tol <= s <= s1 + tol and min(t0, t1) - tol <= t <= max(t0, t1) + tol
        for s0, s1, t0, t1 in stretches
    )


def _boxes_meet(p: BezierCurve, q: BezierCurve) -> bool:
    """Whether the control polygons' boxes overlap (else the pieces cannot meet)."""
    lo_p, hi_p = p.points.min(axis=0), p.points.max(axis=0)
    lo_q, hi_q = q.points.min(axis=0), q.points.max(axis=0)
    return bool(np.all(lo_p <= hi_q) and np.all(lo_q <= hi_p))


def self_intersections(curve: AtomCurve) -> list[Intersection]:
    """Pairs s < t with C(s) = C(t): certified (hazmat.atom_intersect.self_pairs) in 2D and
    3D, else (a curve running over itself) from the polynomial pieces."""
    if curve.dimension in (2, 3):
        part, shift = _part(curve)
        (part,) = _normalised_parts(part)
        certified = ai.self_pairs(part)
        if certified is not None:
            hits = [Intersection(f.s + shift, f.t + shift, f.kind) for f in certified]
            return _at_ends(curve, curve, hits)
    return _at_ends(curve, curve, _pieces_self_intersections(curve))


def _pieces_self_intersections(curve: AtomCurve) -> list[Intersection]:
    """Pairs s < t with C(s) = C(t), from the polynomial pieces (every pair of pieces, and
    each piece with itself), polished by Newton's method on the exact curve."""
    parts = pieces(curve)
    width = max(curve.domain[1] - curve.domain[0], 1e-300)
    found: list[tuple[float, float, str]] = []
    for i, (a, b, p) in enumerate(parts):
        for x in p.self_intersections():
            found.append((a + (b - a) * x.s, a + (b - a) * x.t, x.kind))
        for c, e, q in parts[i + 1 :]:
            if not _boxes_meet(p, q):
                continue
            for x in p.intersect(q):
                s, t = a + (b - a) * x.s, c + (e - c) * x.t
                if abs(s - t) <= SAME * width:  # the shared end of neighbouring pieces
                    continue
                found.append((s, t, x.kind))
    out: list[Intersection] = []
    for s, t, kind in sorted(found):
        if kind != "coincident":
            s, t = _polish(curve, curve, s, t)
        s, t = min(s, t), max(s, t)
        if t - s <= SAME * width:
            continue
        if out and abs(s - out[-1].s) <= SAME * width and abs(t - out[-1].t) <= SAME * width:
            continue
        out.append(Intersection(s, t, kind))
    return out


# ---------------------------------------------------------------------- export
def certified_pieces(
    curve: AtomCurve, tolerance: float, degree: int = EXPORT_DEGREE
) -> tuple[list[tuple[float, float, BezierCurve]], float]:
    """(pieces, bound): polynomial Bézier pieces (a, b, B) of `degree` (B(u), u ∈ [0, 1] ↔
    t = a + u (b − a)) whose distance from the curve is at most `bound` <= `tolerance` at
    every t, certified (hazmat.atom_deviation): interpolation at Chebyshev points on four
    pieces, each halved until its certified bound is within the tolerance. ValueError when
    a tolerance below what rounding allows (about 1e-13 of the size) is asked for."""
    from fractions import Fraction

    from .hazmat import atom_deviation as adv

    tol = float(tolerance)
    if not np.isfinite(tol) or tol <= 0:
        raise ValueError(f"tolerance must be a positive distance, got {tolerance}")
    data = _bounds_data(curve)
    mid = Fraction(curve._mid)
    scale = float(curve._scale)
    u_nodes = _nodes(0.0, 1.0, degree + 1)
    colloc = np.linalg.inv(_bernstein_collocation(u_nodes, degree))
    lo, hi = curve.domain
    edges = np.linspace(lo, hi, 5)
    edges[0], edges[-1] = lo, hi
    todo = []
    for x, y in zip(edges[:-1], edges[1:], strict=True):
        ctrl = colloc @ curve.evaluate(x + (y - x) * u_nodes, extrapolate=True)
        todo.append((float(x), float(y), BezierCurve(ctrl)))
    out: list[tuple[float, float, BezierCurve]] = []
    worst = 0.0
    while todo:
        a, b, piece = todo.pop()
        rows = np.asarray(piece.points, dtype=float) / scale
        tau_a, tau_b = Fraction(a) - mid, Fraction(b) - mid
        bound = adv.deviation(data, rows, tau_a, tau_b, tol / scale) * scale
        if bound <= tol:
            out.append((a, b, piece))
            worst = max(worst, bound)
            continue
        if b - a <= 1e-6 * (curve.domain[1] - curve.domain[0]):
            raise ValueError(
                f"tolerance={tol} is below what the pieces reach here (certified {bound:.3g} "
                f"on a piece of width {b - a:.3g}): ask for at least about 1e-12 of the size"
            )
        m = 0.5 * (a + b)
        for x, y in ((m, b), (a, m)):
            ctrl = colloc @ curve.evaluate(x + (y - x) * u_nodes, extrapolate=True)
            todo.append((x, y, BezierCurve(ctrl)))
    out.sort(key=lambda p: p[0])
    return out, worst
