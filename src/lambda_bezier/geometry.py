"""Geometry of curves and composites: arc length and its inverse, tight bounding boxes,
closest points and torsion.

Every curve of every family is a polynomial curve (`to_bezier()`), so each question reduces
to one on polynomials. We take the Taylor coefficients about t = 1/2 of that Bézier form
(computed in Fractions and rounded once when the curve is exact): about 1/2 the monomials are
as well conditioned on [0, 1] as the Bernstein basis, which matters for the root finding.

- Arc length: adaptive Gauss–Legendre on the speed |p'(t)|, every interval of a level in one
  vectorised evaluation; an interval is accepted when the rule on it and the sum of the rule
  on its halves agree to the share of the tolerance its width gets (the halves' sum is kept).
- Extremes and closest points: all real roots in [0, 1] of a polynomial (a derivative
  component, or (p − q)·p'), from the eigenvalues of its companion matrix (batched over query
  points), accepted generously (near-real, slightly outside [0, 1]: a spurious candidate only
  costs one evaluation, since the answer is the best of all candidates and the ends) and
  polished by Newton steps. Nothing starts from a guess.

A CompositeCurve is handled segment by segment on its global parameter u ∈ [0, N].
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from fractions import Fraction
from functools import cache
from typing import TYPE_CHECKING, Literal, cast, overload

import numpy as np
import numpy.typing as npt

from . import _algorithms as alg
from ._lazy import generated

if TYPE_CHECKING:
    from ._validate import ParamLike
    from .composite import CompositeCurve
    from .curves import Curve

_bernstein = generated("bernstein")

RTOL = 1e-12  # the relative accuracy arc_length and parameter_at_length aim for
_GL_ORDER = 20  # Gauss–Legendre points per interval
_FIRST_PIECES = 24  # equal intervals the adaptive rule starts from (most curves end there)
_SPLIT = 4  # a rejected interval is cut in this many (fewer levels near a near-cusp)
_MAX_LEVELS = 60  # bisection depth: widths down to 2^-60 of the range
_IMAG_TOL = 1e-4  # eigenvalues with a larger imaginary part (in u = t - 1/2) are not roots
_EDGE_TOL = 1e-6  # eigenvalues this far outside [0, 1] are still tried (then clipped)


# ---------------------------------------------------------------------- polynomial data
class _Poly:
    """p and its derivatives as Taylor coefficients about 1/2, (d, N+1) each (on demand)."""

    def __init__(self, base: np.ndarray) -> None:
        self._coeffs = {0: base}

    def __getitem__(self, k: int) -> np.ndarray:
        out = self._coeffs.get(k)
        if out is None:
            out = self._coeffs[k] = alg.differentiate_coefficients(self._coeffs[0], k)
        return out


def _centred_coefficients(curve: Curve) -> np.ndarray:
    """(d, N+1) Taylor coefficients about t = 1/2 of the curve's Bézier form, computed in
    Fractions and rounded once when the curve is exact. A float curve already holds them
    (Curve._derivative_coeffs[0], from the same generated centred matrices)."""
    if not curve._tabulated:  # a classical curve of degree 0 or past the tables
        raise ValueError(
            f"this uses the generated Taylor tables, which cover degrees "
            f"{_bernstein.DEGREES[0]}..{_bernstein.DEGREES[-1]}; the curve has degree "
            f"{curve.degree}"
        )
    if not curve.is_exact:
        return np.ascontiguousarray(curve._derivative_coeffs[0], dtype=float)
    bez = curve.to_bezier()
    rows = bez._exact_points
    assert rows is not None  # an exact curve has an exact Bézier form
    cols = tuple(zip(*_bernstein.CENTRED[bez.degree], strict=True))  # row i: B_i about 1/2
    exact = alg.exact_matmul(cols, rows)  # (N+1, d)
    return np.array([[float(v) for v in row] for row in exact]).T.copy()


def _poly(curve: Curve) -> _Poly:
    cached: _Poly | None = curve.__dict__.get("_geometry_poly")
    if cached is None:
        cached = curve.__dict__["_geometry_poly"] = _Poly(_centred_coefficients(curve))
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
@cache
def _gauss_legendre(order: int) -> tuple[np.ndarray, np.ndarray]:
    nodes, weights = np.polynomial.legendre.leggauss(order)
    return (nodes + 1) / 2, weights / 2  # on [0, 1]


@cache
def _pattern() -> np.ndarray:
    """(3, order) nodes on [0, 1]: the rule on the interval, on its left and right half."""
    x, _ = _gauss_legendre(_GL_ORDER)
    return np.stack([x, x / 2, 0.5 + x / 2])


@cache
def _unit_powers(pieces: int, size: int) -> np.ndarray:
    """(size, nodes): (t − 1/2)^e at the level-0 nodes of [0, 1] cut into `pieces`, so the
    derivative there is one matrix product (the common case: the whole curve)."""
    left = np.arange(pieces)[:, None, None] / pieces
    t = (left + _pattern() / pieces).ravel()
    out = np.ascontiguousarray(((t[:, None] - 0.5) ** np.arange(size)).T)
    out.setflags(write=False)
    return out


def _unit_speeds(d1: np.ndarray, pieces: int) -> np.ndarray:
    """(pieces, 3) Gauss–Legendre sums (unscaled) of the speed over the level-0 intervals of
    [0, 1] and their halves; few array operations, since this is most calls' whole work."""
    values = d1 @ _unit_powers(pieces, d1.shape[1])  # (d, nodes)
    speed = np.sqrt(np.einsum("ij,ij->j", values, values))
    sums: np.ndarray = speed.reshape(3 * pieces, _GL_ORDER) @ _gauss_legendre(_GL_ORDER)[1]
    return sums.reshape(pieces, 3)


def _rule(d1: np.ndarray, left: np.ndarray, right: np.ndarray) -> np.ndarray:
    """Gauss–Legendre of the speed over each [left_i, right_i] (vectorised)."""
    x, w = _gauss_legendre(_GL_ORDER)
    width = right - left
    t = left[:, None] + width[:, None] * x
    speed = np.sqrt(np.square(_eval(d1, t)).sum(axis=1)).reshape(t.shape)
    out: np.ndarray = (speed @ w) * width
    return out


def _level(
    d1: np.ndarray, left: np.ndarray, right: np.ndarray, unit: bool
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The rule on each interval and on each of its halves, in one evaluation."""
    width = right - left
    if unit:  # left, right = k/K, (k+1)/K
        sums = _unit_speeds(d1, left.size) * width[:, None]
    else:
        values = _eval(d1, left[:, None, None] + width[:, None, None] * _pattern())
        speed = np.sqrt(np.square(values).sum(axis=1)).reshape(left.size, 3, _GL_ORDER)
        sums = (speed @ _gauss_legendre(_GL_ORDER)[1]) * width[:, None]
    return sums[:, 0], sums[:, 1] / 2, sums[:, 2] / 2


@overload
def _adaptive(
    d1: np.ndarray, a: float, b: float, rtol: float, *, table: Literal[False] = False
) -> float: ...
@overload
def _adaptive(
    d1: np.ndarray, a: float, b: float, rtol: float, *, table: Literal[True]
) -> tuple[np.ndarray, np.ndarray]: ...
def _adaptive(
    d1: np.ndarray, a: float, b: float, rtol: float, *, table: bool = False
) -> float | tuple[np.ndarray, np.ndarray]:
    """∫_a^b |p'| to a relative accuracy rtol: an interval is accepted when the rule on it
    and the sum over its halves agree to its share (by width) of rtol · total (the halves'
    sum is kept, far more accurate than that test asks); a rejected one is cut in _SPLIT.
    With table=True: the accepted half-intervals' sorted edges (K+1,) and integrals (K,)."""
    pieces = _FIRST_PIECES
    left = a + (b - a) * np.arange(pieces) / pieces
    right = np.append(left[1:], b)
    unit = a == 0.0 and b == 1.0
    done_left: list[np.ndarray] = []
    done_values: list[np.ndarray] = []
    accepted_total = 0.0
    for level in range(_MAX_LEVELS):
        whole, first, second = _level(d1, left, right, unit and level == 0)
        both = first + second
        total = accepted_total + float(both.sum())
        ok = np.abs(whole - both) <= (rtol * max(total, 0.0) / (b - a)) * (right - left)
        if level == _MAX_LEVELS - 1 or total == 0.0:
            ok[:] = True
        every = bool(ok.all())
        if not table and every and not done_values:  # the common case: accepted at once
            return math.fsum(both)
        if every or ok.any():
            accepted_total += float(both[ok].sum())
            done_left.append(left[ok])
            done_values.append(np.stack([first[ok], second[ok]], axis=1).ravel())
        if every:
            break
        keep = ~ok
        width = (right[keep] - left[keep])[:, None] / _SPLIT
        left = (left[keep][:, None] + width * np.arange(_SPLIT)).ravel()
        right = np.append(left[1:], 0.0)
        right[_SPLIT - 1 :: _SPLIT] = left[_SPLIT - 1 :: _SPLIT] + width[:, 0]
    values = np.concatenate(done_values)
    if not table:
        return math.fsum(values)
    starts = np.concatenate(done_left)
    order = np.argsort(starts, kind="stable")
    lo = starts[order]
    pairs = values.reshape(-1, 2)[order]
    mids = (lo + np.append(lo[1:], b)) / 2  # the accepted intervals tile [a, b]
    edges = np.append(np.stack([lo, mids], axis=1).ravel(), b)
    return edges, pairs.ravel()


def _curve_arc_length(curve: Curve, t0: float, t1: float) -> float:
    if t0 == t1:
        return 0.0
    d1 = _poly(curve)[1]
    if t0 == 0.0 and t1 == 1.0:  # most calls: the whole curve, accepted at the first level
        sums = _unit_speeds(d1, _FIRST_PIECES)
        both = (sums[:, 1] + sums[:, 2]) / 2
        total = math.fsum(both)
        # _adaptive's test with every piece's share rtol · total / K, both sides times K
        if np.abs(sums[:, 0] - both).max() <= RTOL * total:
            return total / _FIRST_PIECES
    return _adaptive(d1, t0, t1, RTOL)


def arc_length(
    obj: Curve | CompositeCurve, start: Fraction | float = 0, end: Fraction | float | None = None
) -> float:
    """∫ |p'| from `start` to `end` (a curve: 0 <= start <= end <= 1; a composite:
    0 <= start <= end <= N in its global u), to a relative accuracy of 1e-12."""
    segs = _segments(obj)
    hi = len(segs)  # 1 for a curve, N for a composite
    a = _parameter(start, "t0", hi)
    b = _parameter(hi if end is None else end, "t1", hi)
    if a > b:
        raise ValueError(f"arc_length needs t0 <= t1, got t0={start}, t1={end}")
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
        edges, values = _adaptive(_poly(curve)[1], 0.0, 1.0, RTOL, table=True)
        cum = np.concatenate([[0.0], np.cumsum(values)])
        cum[-1] = math.fsum(values)
        cached = (edges, cum)
        curve.__dict__["_geometry_lengths"] = cached
    return cached


def _curve_parameter_at_length(curve: Curve, s: np.ndarray) -> np.ndarray:
    """t with L(0, t) = s for lengths 0 <= s <= L (vectorised safeguarded Newton inside the
    accepted interval holding s, where L(t) = cumulative + Gauss–Legendre up to t)."""
    d1 = _poly(curve)[1]
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
        f = base + _rule(d1, start, t) - s
        done = np.abs(f) <= goal
        if done.all():
            break
        lo = np.where(f < 0, t, lo)
        hi = np.where(f > 0, t, hi)
        speed = np.sqrt(np.square(_eval(d1, t)).sum(axis=1))
        with np.errstate(divide="ignore", invalid="ignore"):
            step = t - f / speed
        inside = np.isfinite(step) & (step > lo) & (step < hi)
        nxt = np.where(inside, step, (lo + hi) / 2)
        nxt = np.where(done, t, nxt)
        if np.array_equal(nxt, t):
            break
        t = nxt
    return t


def parameter_at_length(obj: Curve | CompositeCurve, s: npt.ArrayLike) -> np.ndarray | float:
    """The parameter (t for a curve, u for a composite) at which the arc length from the
    start equals s, for a number or an array of lengths in [0, total length]."""
    try:
        arr = np.asarray(s, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"s must be a number or a 1-D array of numbers, got {s!r}") from None
    if arr.ndim > 1:
        raise ValueError(f"s must be a number or a 1-D array, got shape {arr.shape}")
    scalar = arr.ndim == 0
    arr = np.atleast_1d(arr)
    if not np.isfinite(arr).all():
        raise ValueError("s contains NaN or infinity")
    segs = _segments(obj)
    lengths = np.array([_length_table(seg)[1][-1] for seg in segs])
    total = math.fsum(lengths)
    if total == 0:
        raise ValueError("the curve has zero length: no parameter belongs to a given length")
    slack = 4 * RTOL * total
    if arr.size and (arr.min() < -slack or arr.max() > total + slack):
        bad = arr[(arr < -slack) | (arr > total + slack)][0]
        raise ValueError(f"s = {bad} is outside [0, {total!r}] (the total arc length)")
    arr = np.clip(arr, 0.0, total)
    cum = np.concatenate([[0.0], np.cumsum(lengths)])
    idx = np.clip(np.searchsorted(cum, arr, side="right") - 1, 0, len(segs) - 1)
    out = np.zeros(arr.size)
    for i in np.unique(idx):
        mask = idx == i
        local = np.clip(arr[mask] - cum[i], 0.0, lengths[i])
        out[mask] = i + (_curve_parameter_at_length(segs[i], local) if lengths[i] else 0.0)
    return float(out[0]) if scalar else out


# ---------------------------------------------------------------------- real roots
def _significant(coeffs: np.ndarray) -> np.ndarray:
    """Drop leading (highest-power) coefficients whose term is below 1e-13 of the largest on
    |u| <= 1/2: rounding noise (a degree-elevated float curve's top coefficient is zero up
    to it) would make the companion matrix's other entries huge. The candidates found
    without such a term are polished and judged on the full polynomial, so what it can move
    is a flat spot's value by about 1e-13 of the curve's size."""
    c = np.atleast_2d(coeffs)
    size = np.abs(c) * 0.5 ** np.arange(c.shape[-1])
    scale = size.max()
    if scale == 0:
        return c[..., :1]
    keep = np.nonzero((size > 1e-13 * scale).any(axis=0))[0]
    return c[..., : keep[-1] + 1]


def _candidate_roots(c: np.ndarray) -> np.ndarray:
    """Candidate roots t in [0, 1] of each polynomial Σ_e c[j, e] (t - 1/2)^e (rows share
    their degree, its leading coefficient nonzero): (m, degree) with NaN where none."""
    m, size = c.shape
    degree = size - 1
    if degree < 1:
        return np.full((m, 0), np.nan)
    comp = np.zeros((m, degree, degree))
    if degree > 1:
        comp[:, np.arange(1, degree), np.arange(degree - 1)] = 1.0
    comp[:, :, -1] = -c[:, :-1] / c[:, -1:]
    roots = np.linalg.eigvals(comp)
    real = roots.real
    ok = (np.abs(roots.imag) <= _IMAG_TOL) & (np.abs(real) <= 0.5 + _EDGE_TOL)
    return np.where(ok, np.clip(real, -0.5, 0.5) + 0.5, np.nan)


def _newton(
    t: np.ndarray,
    f: Callable[[np.ndarray], np.ndarray],
    fprime: Callable[[np.ndarray], np.ndarray],
    steps: int = 4,
) -> np.ndarray:
    """A few guarded Newton steps on every finite candidate (kept inside [0, 1])."""
    for _ in range(steps):
        good = np.isfinite(t)
        tt = np.where(good, t, 0.5)
        with np.errstate(divide="ignore", invalid="ignore"):
            step = f(tt) / fprime(tt)
        t = np.where(good & np.isfinite(step), np.clip(tt - step, 0.0, 1.0), t)
    return t


# ---------------------------------------------------------------------- bounding box
def _curve_box(curve: Curve) -> tuple[np.ndarray, np.ndarray]:
    poly = _poly(curve)
    candidates = []
    for axis in range(curve.dimension):
        c1 = _significant(poly[1][axis])
        c2 = poly[2][axis : axis + 1]
        if c1.shape[-1] < 2 or not c1.any():
            continue
        roots = _candidate_roots(c1)[0]
        roots = roots[np.isfinite(roots)]

        def slope(t: np.ndarray, a: int = axis) -> np.ndarray:
            return _eval(poly[1][a : a + 1], t)[:, 0]

        def bend(t: np.ndarray, c: np.ndarray = c2) -> np.ndarray:
            return _eval(c, t)[:, 0]

        polished = _newton(
            roots.copy(),
            slope,
            bend,
        )
        candidates += [roots, polished]
    t = np.concatenate([np.empty(0), *candidates])
    # a root within 1e-12 of an end adds nothing to the end itself (the coordinate is flat
    # there), and the ends are the Bézier form's first and last control points, exactly
    t = t[(t > 1e-12) & (t < 1 - 1e-12)]
    bez = curve.to_bezier().points
    values = np.vstack([bez[[0, -1]], _eval(poly[0], t)])
    return values.min(axis=0), values.max(axis=0)


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
    try:
        arr = np.asarray(q, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"q must be a point or an (m, d) array of points, got {q!r}") from None
    if arr.ndim not in (1, 2) or arr.shape[-1] != dimension:
        raise ValueError(
            f"q must have shape ({dimension},) or (m, {dimension}) for this {dimension}D curve, "
            f"got shape {arr.shape}"
        )
    if not np.isfinite(arr).all():
        raise ValueError("q contains NaN or infinity")
    return np.atleast_2d(arr), arr.ndim == 1


def _curve_closest(curve: Curve, q: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Parameters, points and squared distances of the nearest points to each row of q."""
    poly = _poly(curve)
    p = _significant(poly[0])  # (d, N'+1) with the true leading term
    m, dim = q.shape
    size = p.shape[1]
    cands = [np.zeros((m, 1)), np.ones((m, 1))]
    if size >= 2:
        dp = alg.differentiate_coefficients(p, 1)  # (d, N')
        # g(u) = (p(u) - q) · p'(u) = Σ_c p_c p'_c − Σ_c q_c p'_c: degree 2N' − 1
        fixed = sum(np.convolve(p[c], dp[c]) for c in range(dim))
        g = np.tile(fixed, (m, 1))
        g[:, : size - 1] -= q @ dp
        roots = _candidate_roots(g)
        d2 = alg.differentiate_coefficients(p, 2)

        def gval(t: np.ndarray) -> np.ndarray:
            shape = t.shape
            pts = _eval(p, t).reshape(*shape, dim)
            der = _eval(dp, t).reshape(*shape, dim)
            g: np.ndarray = ((pts - q[:, None, :]) * der).sum(-1)
            return g

        def gprime(t: np.ndarray) -> np.ndarray:
            shape = t.shape
            pts = _eval(p, t).reshape(*shape, dim)
            der = _eval(dp, t).reshape(*shape, dim)
            sec = _eval(d2, t).reshape(*shape, dim)
            dg: np.ndarray = (der * der).sum(-1) + ((pts - q[:, None, :]) * sec).sum(-1)
            return dg

        polished = _newton(roots.copy(), gval, gprime)
        cands += [np.nan_to_num(roots, nan=0.0), np.nan_to_num(polished, nan=0.0)]
    t = np.concatenate(cands, axis=1)
    pts = _eval(poly[0], t).reshape(*t.shape, dim)
    dist2 = np.square(pts - q[:, None, :]).sum(-1)
    best = np.argmin(dist2, axis=1)
    rows = np.arange(m)
    return t[rows, best], pts[rows, best], dist2[rows, best]


def closest_point(obj: Curve | CompositeCurve, q: npt.ArrayLike) -> ClosestPoint:
    """The global minimum of |p(t) − q| over the curve (u over a composite): the best of both
    ends and every critical point, i.e. every root of (p − q)·p' in [0, 1]. q is one point
    (d,) or a batch (m, d)."""
    segs = _segments(obj)
    queries, single = _queries(q, segs[0].dimension)
    best_t, best_pt, best_d2 = _curve_closest(segs[0], queries)
    for i, seg in enumerate(segs[1:], start=1):
        t, pt, d2 = _curve_closest(seg, queries)
        better = d2 < best_d2  # a tie (a joint) keeps the earlier segment
        best_t = np.where(better, t + i, best_t)
        best_pt = np.where(better[:, None], pt, best_pt)
        best_d2 = np.where(better, d2, best_d2)
    dist = np.sqrt(best_d2)
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
    tau = torsion_from_derivatives(d1, d2, d3, t)
    return float(tau) if np.ndim(tau) == 0 else tau
