"""Geometry of curves and composites: arc length and its inverse, tight bounding boxes,
closest points and torsion.

Every curve of every family is a polynomial curve (`to_bezier()`), so each question reduces
to one on polynomials. We take the Taylor coefficients about t = 1/2 of that Bézier form
(computed in Fractions and rounded once when the curve is exact): about 1/2 the monomials are
as well conditioned on [0, 1] as the Bernstein basis, which matters for the root finding.

- Arc length (hazmat.arclength): adaptive quadrature of the speed |p'|, a piece accepted when a
  Gauss–Lobatto rule and its Kronrod extension agree to its share of the tolerance, every
  piece of a level in one vectorised evaluation, and pieces kept away from the complex
  zeros of |p'|² (near-cusps) once the first two levels have not sufficed.
- Extremes and closest points (hazmat.extremes, hazmat.roots): all real roots in [0, 1] of a
  polynomial (a derivative component, or (p − q)·p'), from the eigenvalues of its companion
  matrix (batched over query points), accepted generously (near-real, slightly outside [0,
  1]: a spurious candidate only costs one evaluation, since the answer is the best of all
  candidates and the ends) and polished by Newton steps. Nothing starts from a guess.

A CompositeCurve is handled segment by segment on its global parameter u ∈ [0, N].
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from typing import TYPE_CHECKING, cast

import numpy as np
import numpy.typing as npt

from . import _validate as val
from ._lazy import generated
from .hazmat import arclength as _arclength
from .hazmat import extremes, forms
from .hazmat import kernels as alg

if TYPE_CHECKING:
    from ._validate import ParamLike
    from .composite import CompositeCurve
    from .curves import Curve

_bernstein = generated("bernstein")

RTOL = 1e-12  # the relative accuracy arc_length and parameter_at_length aim for


# ---------------------------------------------------------------------- polynomial data
class _Poly:
    """p/scale and its derivatives as Taylor coefficients about 1/2, (d, N+1) each (on
    demand); scale is a power of two (a float curve with huge or tiny coordinates keeps its
    coefficients scaled, see Curve.__init__). `speed`: parameter_at_length's (coeffs,
    scale) with coeffs safe to square (_arclength.scaled), once."""

    def __init__(self, base: np.ndarray, scale: float) -> None:
        self._coeffs = {0: base}
        self.scale = scale
        self.speed: tuple[np.ndarray, float] | None = None

    def __getitem__(self, k: int) -> np.ndarray:
        out = self._coeffs.get(k)
        if out is None:
            out = self._coeffs[k] = alg.differentiate_coefficients(self._coeffs[0], k)
        return out


def _centred_coefficients(curve: Curve) -> tuple[np.ndarray, float]:
    """(coeffs, scale): p = scale · Σ_e coeffs[:, e] (t − 1/2)^e, the (d, N+1) Taylor
    coefficients about t = 1/2 of the curve's Bézier form, computed in Fractions and rounded
    once when the curve is exact (scale 1). A float curve already holds them
    (Curve._centred(), from the same generated centred matrices, filled in
    exactly at the tabulated degrees), for its points divided by Curve._scale."""
    base = curve._centred() if curve._tabulated else None
    if not curve.is_exact:
        if base is None:  # a classical curve of degree 0 or past the tables: the same
            # expansion, computed (hazmat.forms.centred_matrix), for the same scaled points
            unit = curve.points / curve._scale
            base = (np.array(forms.centred_matrix(curve.degree), dtype=float).T @ unit).T
        return base, curve._scale
    bez = curve.to_bezier()
    rows = bez._exact_points
    assert rows is not None  # an exact curve has an exact Bézier form
    cols = tuple(zip(*forms.centred_matrix(bez.degree), strict=True))  # row i: B_i about 1/2
    exact = alg.exact_matmul(cols, rows)  # (N+1, d)
    # exact coordinates near the float limit have coefficients past it (and tiny ones lose
    # their digits in subnormals): divided by a power of two, exactly, as float curves are
    big = max((abs(v) for row in exact for v in row), default=Fraction(0))
    shift = 0
    if big and not Fraction(1, 2**500) <= big <= 2**500:
        shift = big.numerator.bit_length() - big.denominator.bit_length()
        shift = min(max(shift, -1022), 1023)  # the scale itself a (normal) float
    scale = Fraction(2) ** shift
    coeffs = np.array([[float(v / scale) for v in row] for row in exact]).T.copy()
    return coeffs, math.ldexp(1.0, shift)


def _poly(curve: Curve) -> _Poly:
    cached: _Poly | None = curve.__dict__.get("_geometry_poly")
    if cached is None:
        cached = curve.__dict__["_geometry_poly"] = _Poly(*_centred_coefficients(curve))
    return cached


def _eval(coeffs: np.ndarray, t: np.ndarray) -> np.ndarray:
    """(len(t), d) values of the polynomial with centred coefficients (d, N+1)."""
    return alg.centred_horner(coeffs, np.ascontiguousarray(t, dtype=float).ravel())


def _segments(obj: Curve | CompositeCurve) -> tuple[Curve, ...]:
    segs: list[Curve] | None = getattr(obj, "segments", None)
    # no segments: obj is a Curve (a CompositeCurve always has them)
    return (cast("Curve", obj),) if segs is None else tuple(segs)


def _parameter(value: object, name: str, hi: int) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float | Fraction | np.number):
        raise ValueError(f"{name} must be a number, got {value!r}")
    x = float(value)
    if not math.isfinite(x) or not 0 <= x <= hi:
        raise ValueError(f"{name} = {value} is outside [0, {hi}]")
    return x


# ---------------------------------------------------------------------- arc length
def _speed_coefficients(curve: Curve) -> tuple[np.ndarray, float]:
    """(coeffs, scale): p = scale · Σ_e coeffs[:, e] (t − 1/2)^e, coeffs of a size whose
    derivative's squares neither overflow nor underflow (scale a power of two; cached)."""
    poly = _poly(curve)
    if poly.speed is None:
        coeffs, factor = _arclength.scaled(poly[0])
        poly.speed = (coeffs, poly.scale * factor)
    return poly.speed


def _curve_arc_length(curve: Curve, t0: float, t1: float) -> float:
    if t0 == t1:
        return 0.0
    poly = _poly(curve)
    if t0 == 0.0 and t1 == 1.0:  # most calls: the whole curve
        return poly.scale * _arclength.unit_integral(poly[0], RTOL)
    return poly.scale * _arclength.integral(poly[0], t0, t1, RTOL)


def arc_length(
    obj: Curve | CompositeCurve, start: Fraction | float = 0, end: Fraction | float | None = None
) -> float:
    """∫ |p'| from `start` to `end` (a curve: 0 <= start <= end <= 1; a composite:
    0 <= start <= end <= N in its global u), to a relative accuracy of 1e-12. (Not below
    the rounding of p' itself, about 1e-16 of its size on [0, 1] times end − start, which
    matters only where |p'| is far smaller than that all over [start, end]: a short
    interval around a cusp.)"""
    if (  # Curve.arc_length's defaults (ints 0 and 1) on a curve: most calls
        type(start) is int
        and type(end) is int
        and start == 0
        and end == 1
        and getattr(obj, "segments", None) is None
    ):
        poly = _poly(cast("Curve", obj))
        return poly.scale * _arclength.unit_integral(poly[0], RTOL)
    segs = _segments(obj)
    hi = len(segs)  # 1 for a curve, N for a composite
    a = _parameter(start, "t0", hi)
    b = _parameter(hi if end is None else end, "t1", hi)
    if a > b:
        raise ValueError(f"arc_length needs t0 <= t1, got t0={start}, t1={end}")
    if hi == 1:
        return _curve_arc_length(segs[0], a, b)
    total = []
    for i, seg in enumerate(segs):
        lo, up = max(a - i, 0.0), min(b - i, 1.0)
        if lo < up:
            total.append(_curve_arc_length(seg, lo, up))
    return math.fsum(total)


def _length_table(curve: Curve) -> tuple[np.ndarray, np.ndarray]:
    """The accepted partition of [0, 1] with cumulative lengths (cached on the curve)."""
    cached: tuple[np.ndarray, np.ndarray] | None = curve.__dict__.get("_geometry_lengths")
    if cached is None:
        poly = _poly(curve)
        edges, cum = _arclength.table(poly[0], RTOL)
        cached = (edges, cum * poly.scale)
        curve.__dict__["_geometry_lengths"] = cached
    return cached


def _curve_parameter_at_length(curve: Curve, s: np.ndarray) -> np.ndarray:
    """t with L(0, t) = s for lengths 0 <= s <= L (vectorised safeguarded Newton inside the
    accepted piece holding s, where L(t) = cumulative + the Gauss rule up to t: on a part
    of an accepted piece that rule is at least as accurate as on the whole)."""
    coeffs, scale = _speed_coefficients(curve)
    edges, cum = _length_table(curve)
    k = np.clip(np.searchsorted(cum, s, side="right") - 1, 0, edges.size - 2)
    base, lo, hi = cum[k], edges[k].copy(), edges[k + 1].copy()
    span = cum[k + 1] - base
    with np.errstate(divide="ignore", invalid="ignore"):
        frac = np.where(span > 0, (s - base) / span, 0.0)
    t: np.ndarray = lo + np.clip(frac, 0, 1) * (hi - lo)
    start = edges[k]
    goal = RTOL * cum[-1] / 16
    for _ in range(100):
        f = base + scale * _arclength.partial(coeffs, start, t) - s
        done = np.abs(f) <= goal
        if done.all():
            break
        lo = np.where(f < 0, t, lo)
        hi = np.where(f > 0, t, hi)
        speed = scale * _arclength.speeds(coeffs, t)
        with np.errstate(divide="ignore", invalid="ignore"):
            step = t - f / speed
        inside = np.isfinite(step) & (step > lo) & (step < hi)
        nxt = np.where(inside, step, (lo + hi) / 2)
        nxt = np.where(done, t, nxt)
        if np.array_equal(nxt, t):
            break
        t = nxt
    return t


def length_queries(s: npt.ArrayLike) -> tuple[np.ndarray, bool]:
    """(the lengths s as a 1-D float array, whether s was one number), for every curve's
    parameter_at_length: text, booleans and non-numbers are refused by name
    (`_validate.real_array`), so are an array of more than one dimension and NaN/infinity."""
    arr = val.real_array(s, "s")
    if arr.ndim > 1:
        raise ValueError(f"s must be a number or a 1-D array, got shape {arr.shape}")
    if not np.isfinite(arr).all():
        raise ValueError("s contains NaN or infinity")
    return np.atleast_1d(arr), arr.ndim == 0


def lengths_within(arr: np.ndarray, total: float) -> np.ndarray:
    """Arc lengths s checked against [0, total] (rounding slack allowed) and clipped to it;
    ValueError for a curve of zero length or an s outside."""
    if total == 0:
        raise ValueError("the curve has zero length: no parameter belongs to a given length")
    slack = 4 * RTOL * total
    if arr.size and (arr.min() < -slack or arr.max() > total + slack):
        bad = arr[(arr < -slack) | (arr > total + slack)][0]
        raise ValueError(f"s = {bad} is outside [0, {total!r}] (the total arc length)")
    clipped: np.ndarray = np.clip(arr, 0.0, total)
    return clipped


def parameter_at_length(obj: Curve | CompositeCurve, s: npt.ArrayLike) -> np.ndarray | float:
    """The parameter (t for a curve, u for a composite) at which the arc length from the
    start equals s, for a number or an array of lengths in [0, total length]."""
    arr, scalar = length_queries(s)
    segs = _segments(obj)
    lengths = np.array([_length_table(seg)[1][-1] for seg in segs])
    total = math.fsum(lengths)
    arr = lengths_within(arr, total)
    cum = np.concatenate([[0.0], np.cumsum(lengths)])
    idx = np.clip(np.searchsorted(cum, arr, side="right") - 1, 0, len(segs) - 1)
    out = np.zeros(arr.size)
    for i in np.unique(idx):
        mask = idx == i
        local = np.clip(arr[mask] - cum[i], 0.0, lengths[i])
        out[mask] = i + (_curve_parameter_at_length(segs[i], local) if lengths[i] else 0.0)
    return float(out[0]) if scalar else out


# ---------------------------------------------------------------------- real roots
# ---------------------------------------------------------------------- bounding box
def _curve_box(curve: Curve) -> tuple[np.ndarray, np.ndarray]:
    poly = _poly(curve)
    ends = curve.to_bezier().points[[0, -1]]
    # poly holds p / scale (a power of two): the ends go in at that scale and the box comes
    # back out of it (the inner extremes were the scaled curve's, 1e-300 times too small)
    shift = math.frexp(poly.scale)[1] - 1
    with val.overflow_allowed():
        lo, hi = extremes.box(poly[0], poly[1], poly[2], np.ldexp(ends, -shift))
        return np.ldexp(lo, shift), np.ldexp(hi, shift)


def bounding_box(obj: Curve | CompositeCurve) -> tuple[np.ndarray, np.ndarray]:
    """(lo, hi): the tight axis-aligned box, from the curve's values at both ends and at
    every root in [0, 1] of each coordinate's derivative."""
    boxes = [_curve_box(seg) for seg in _segments(obj)]
    lo = np.min([b[0] for b in boxes], axis=0)
    hi = np.max([b[1] for b in boxes], axis=0)
    return lo, hi


# ---------------------------------------------------------------------- closest point
@dataclass(frozen=True)
class ClosestPoint:
    """The point of a curve nearest to a query: parameter `t` (u for a composite), the
    curve `point` there and the `distance`. For a batch of m queries: arrays of shape (m,),
    (m, d) and (m,)."""

    t: float | np.ndarray
    point: np.ndarray
    distance: float | np.ndarray


def _queries(q: npt.ArrayLike, dimension: int) -> tuple[np.ndarray, bool]:
    """q as an (m, d) float array of query points, and whether it was one point (d,)."""
    arr = val.real_array(q, "q")
    if arr.ndim not in (1, 2) or arr.shape[-1] != dimension:
        raise ValueError(
            f"q must have shape ({dimension},) or (m, {dimension}) for this {dimension}D curve, "
            f"got shape {arr.shape}"
        )
    if not np.isfinite(arr).all():
        raise ValueError("q contains NaN or infinity")
    return np.atleast_2d(arr), arr.ndim == 1


def no_queries(dimension: int) -> ClosestPoint:
    """The answer to an empty batch of queries (0, d): empty arrays, as numpy gives."""
    return ClosestPoint(np.empty(0), np.empty((0, dimension)), np.empty(0))


def _curve_closest(curve: Curve, q: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Parameters, points and distances of the nearest points to each row of q."""
    poly = _poly(curve)
    # (p − q)·p′ squares coordinates: at 2^600 that overflows, at 2^-600 it underflows. The
    # coefficients and the queries are divided by one power of two (exact), so that the
    # larger of them is near 1; distances are scaled back at the end. The power is applied
    # as an exponent (ldexp), never as a float factor: 2^1024 (a query at 1e308, or a curve
    # scaled by 2^1023) is not a float, and a factor of inf made a finite point inf. Queries
    # far larger than the curve (2^256 times) take their own power: one power for a whole
    # batch shrank its near queries' distances with the far one's, to 0 past 2^540.
    # in exponents: q / poly.scale itself overflows for a far query to a tiny curve
    offset = math.frexp(poly.scale)[1] - 1  # poly.scale is a power of two: exact
    own = math.frexp(float(np.abs(poly[0]).max()))[1]
    query_big = float(np.abs(q).max())
    if query_big == 0.0 or math.frexp(query_big)[1] - offset <= own + 256:  # every query near
        shift = max(own, math.frexp(query_big)[1] - offset if query_big else own)
        t, pts, dist2 = extremes.closest(np.ldexp(poly[0], -shift), np.ldexp(q, -shift - offset))
        with val.overflow_allowed():
            return t, np.ldexp(pts, shift + offset), np.ldexp(np.sqrt(dist2), shift + offset)
    sizes = np.abs(q).max(axis=1)
    query_exp = np.frexp(sizes)[1] - offset
    far = (sizes > 0) & (query_exp > own + 256)
    shifts = np.where(far, query_exp, own)
    shifts[~far] = max(own, int(query_exp[~far & (sizes > 0)].max(initial=own)))
    t = np.empty(len(q))
    pts = np.empty(q.shape)
    dist = np.empty(len(q))
    for shift in np.unique(shifts).tolist():
        rows = shifts == shift
        t[rows], p_rows, dist2 = extremes.closest(
            np.ldexp(poly[0], -shift), np.ldexp(q[rows], -shift - offset)
        )
        with val.overflow_allowed():
            pts[rows] = np.ldexp(p_rows, shift + offset)
            dist[rows] = np.ldexp(np.sqrt(dist2), shift + offset)
    return t, pts, dist


def closest_point(obj: Curve | CompositeCurve, q: npt.ArrayLike) -> ClosestPoint:
    """The global minimum of |p(t) − q| over the curve (u over a composite): the best of both
    ends and every critical point, i.e. every root of (p − q)·p' in [0, 1]. q is one point
    (d,) or a batch (m, d)."""
    segs = _segments(obj)
    queries, single = _queries(q, segs[0].dimension)
    if not queries.shape[0]:
        return no_queries(segs[0].dimension)
    best_t, best_pt, dist = _curve_closest(segs[0], queries)
    for i, seg in enumerate(segs[1:], start=1):
        t, pt, d = _curve_closest(seg, queries)
        better = d < dist  # a tie (a joint) keeps the earlier segment
        best_t = np.where(better, t + i, best_t)
        best_pt = np.where(better[:, None], pt, best_pt)
        dist = np.where(better, d, dist)
    if single:
        return ClosestPoint(float(best_t[0]), best_pt[0], float(dist[0]))
    return ClosestPoint(best_t, best_pt, dist)


# ---------------------------------------------------------------------- torsion
def torsion_from_derivatives(
    d1: np.ndarray, d2: np.ndarray, d3: np.ndarray, where: object
) -> np.ndarray:
    """(p' × p'') · p''' / |p' × p''|², row-wise; ValueError where p' × p'' vanishes (below
    1e-12 |p'| |p''|: the curve is straight there, or has a cusp)."""
    cross = np.cross(d1, d2)
    norm2 = np.square(cross).sum(-1)
    scale = np.linalg.norm(d1, axis=-1) * np.linalg.norm(d2, axis=-1)
    bad = np.sqrt(norm2) <= 1e-12 * scale
    if bad.any():
        at = np.asarray(where).ravel()[np.argmax(np.atleast_1d(bad))]
        raise ValueError(
            f"torsion is undefined at {at}: p' x p'' = 0 there (the curve is straight "
            "or has a cusp)"
        )
    tau: np.ndarray = (cross * d3).sum(-1) / norm2
    return tau


def torsion(
    obj: Curve | CompositeCurve, t: ParamLike, *, extrapolate: bool = False
) -> np.ndarray | float:
    """Signed torsion of a 3D curve (composite: in u) at t, a number or an array."""
    if obj.dimension != 3:
        raise ValueError(
            f"torsion is defined for 3D curves; this curve is {obj.dimension}D (a plane "
            "curve has no torsion)"
        )
    d1 = obj.derivative(t, 1, extrapolate=extrapolate)
    d2 = obj.derivative(t, 2, extrapolate=extrapolate)
    d3 = obj.derivative(t, 3, extrapolate=extrapolate)
    speed_floor = getattr(obj, "_speed_floor", None)  # a segment class: p' = 0 within its
    if speed_floor is not None:  # rounding is a stop or cusp (CompositeCurve: its segments')
        floor, s = speed_floor(t, extrapolate)
        val.check_moving(d1, floor, s, t, "torsion")
    tau = torsion_from_derivatives(d1, d2, d3, t)
    return float(tau) if np.ndim(tau) == 0 else tau
