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
from dataclasses import dataclass
from fractions import Fraction
from functools import cache

import numpy as np

from . import _algorithms as alg
from ._lazy import generated

_bernstein = generated("bernstein")

RTOL = 1e-12  # the relative accuracy arc_length and parameter_at_length aim for
_GL_ORDER = 12  # Gauss–Legendre points per interval
_MAX_LEVELS = 60  # bisection depth: widths down to 2^-60 of the range
_IMAG_TOL = 1e-4  # eigenvalues with a larger imaginary part (in u = t - 1/2) are not roots
_EDGE_TOL = 1e-6  # eigenvalues this far outside [0, 1] are still tried (then clipped)


# ---------------------------------------------------------------------- polynomial data
@dataclass(frozen=True)
class _Poly:
    """p and its first three derivatives, as Taylor coefficients about 1/2, (d, N+1) each."""

    coeffs: tuple[np.ndarray, ...]


def _centred_coefficients(curve) -> np.ndarray:
    """(d, N+1) Taylor coefficients about t = 1/2 of the curve's Bézier form; computed in
    Fractions and rounded once when the curve is exact."""
    bez = curve.to_bezier()
    matrix = _bernstein.CENTRED[bez.degree]  # row i: B_i about 1/2
    if bez.is_exact:
        rows = bez.control_points()
        cols = tuple(zip(*matrix, strict=True))
        exact = alg.exact_matmul(cols, rows)  # (N+1, d)
        return np.array([[float(v) for v in row] for row in exact]).T.copy()
    return (np.array(matrix, dtype=float).T @ bez.points).T.copy()


def _poly(curve) -> _Poly:
    cached = curve.__dict__.get("_geometry_poly")
    if cached is None:
        base = _centred_coefficients(curve)
        derivs = [base] + [alg.differentiate_coefficients(base, k) for k in (1, 2, 3)]
        cached = _Poly(tuple(derivs))
        curve.__dict__["_geometry_poly"] = cached
    return cached


def _eval(coeffs: np.ndarray, t: np.ndarray) -> np.ndarray:
    """(len(t), d) values of the polynomial with centred coefficients (d, N+1)."""
    return alg.centred_horner(coeffs, np.ascontiguousarray(t, dtype=float).ravel())


def _segments(obj) -> tuple:
    segs = getattr(obj, "segments", None)
    return (obj,) if segs is None else tuple(segs)


def _parameter(value, name: str, hi: int) -> float:
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


def _rule(d1: np.ndarray, left: np.ndarray, right: np.ndarray) -> np.ndarray:
    """Gauss–Legendre of the speed over each [left_i, right_i] (vectorised)."""
    x, w = _gauss_legendre(_GL_ORDER)
    width = right - left
    t = left[:, None] + width[:, None] * x
    speed = np.sqrt(np.square(_eval(d1, t)).sum(axis=1)).reshape(t.shape)
    return (speed @ w) * width


def _adaptive(d1: np.ndarray, a: float, b: float, rtol: float):
    """Accepted sub-intervals of [a, b] (sorted edges, (K+1,)) and the speed's integral over
    each (K,), to a relative accuracy rtol of the total."""
    left = a + (b - a) * np.arange(4) / 4
    right = np.append(left[1:], b)
    done_edges: list[np.ndarray] = []
    done_values: list[np.ndarray] = []
    accepted_total = 0.0
    for level in range(_MAX_LEVELS):
        mid = (left + right) / 2
        whole = _rule(d1, left, right)
        halves = _rule(d1, np.concatenate([left, mid]), np.concatenate([mid, right]))
        first, second = halves[: left.size], halves[left.size :]
        both = first + second
        total = accepted_total + float(both.sum())
        share = rtol * max(total, 0.0) * (right - left) / (b - a)
        ok = np.abs(whole - both) <= share
        if level == _MAX_LEVELS - 1 or total == 0.0:
            ok[:] = True
        if ok.any():
            accepted_total += float(both[ok].sum())
            done_edges.append(np.stack([left[ok], mid[ok]], axis=1).ravel())
            done_values.append(np.stack([first[ok], second[ok]], axis=1).ravel())
        if ok.all():
            break
        keep = ~ok
        left = np.concatenate([left[keep], mid[keep]])
        right = np.concatenate([mid[keep], right[keep]])
    starts = np.concatenate(done_edges)
    values = np.concatenate(done_values)
    order = np.argsort(starts, kind="stable")
    edges = np.append(starts[order], b)
    return edges, values[order]


def _curve_arc_length(curve, t0: float, t1: float) -> float:
    if t0 == t1:
        return 0.0
    _, values = _adaptive(_poly(curve).coeffs[1], t0, t1, RTOL)
    return math.fsum(values)


def arc_length(obj, start=0, end=None) -> float:
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


def _length_table(curve):
    """The accepted partition of [0, 1] with cumulative lengths (cached on the curve)."""
    cached = curve.__dict__.get("_geometry_lengths")
    if cached is None:
        edges, values = _adaptive(_poly(curve).coeffs[1], 0.0, 1.0, RTOL)
        cum = np.concatenate([[0.0], np.cumsum(values)])
        cum[-1] = math.fsum(values)
        cached = (edges, cum)
        curve.__dict__["_geometry_lengths"] = cached
    return cached


def _curve_parameter_at_length(curve, s: np.ndarray) -> np.ndarray:
    """t with L(0, t) = s for lengths 0 <= s <= L (vectorised safeguarded Newton inside the
    accepted interval holding s, where L(t) = cumulative + Gauss–Legendre up to t)."""
    d1 = _poly(curve).coeffs[1]
    edges, cum = _length_table(curve)
    k = np.clip(np.searchsorted(cum, s, side="right") - 1, 0, edges.size - 2)
    base, lo, hi = cum[k], edges[k].copy(), edges[k + 1].copy()
    span = cum[k + 1] - base
    with np.errstate(divide="ignore", invalid="ignore"):
        frac = np.where(span > 0, (s - base) / span, 0.0)
    t = lo + np.clip(frac, 0, 1) * (hi - lo)
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


def parameter_at_length(obj, s):
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
    """Drop leading (highest-power) coefficients whose term is below rounding on |u| <= 1/2."""
    c = np.atleast_2d(coeffs)
    size = np.abs(c) * 0.5 ** np.arange(c.shape[-1])
    scale = size.max()
    if scale == 0:
        return c[..., :1]
    keep = np.nonzero((size > 1e-15 * scale).any(axis=0))[0]
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


def _newton(t: np.ndarray, f, fprime, steps: int = 4) -> np.ndarray:
    """A few guarded Newton steps on every finite candidate (kept inside [0, 1])."""
    for _ in range(steps):
        good = np.isfinite(t)
        tt = np.where(good, t, 0.5)
        with np.errstate(divide="ignore", invalid="ignore"):
            step = f(tt) / fprime(tt)
        t = np.where(good & np.isfinite(step), np.clip(tt - step, 0.0, 1.0), t)
    return t


# ---------------------------------------------------------------------- bounding box
def _curve_box(curve) -> tuple[np.ndarray, np.ndarray]:
    poly = _poly(curve)
    candidates = [np.array([0.0, 1.0])]
    for axis in range(curve.dimension):
        c1 = _significant(poly.coeffs[1][axis])
        c2 = poly.coeffs[2][axis : axis + 1]
        if c1.shape[-1] < 2 or not c1.any():
            continue
        roots = _candidate_roots(c1)[0]
        roots = roots[np.isfinite(roots)]
        polished = _newton(
            roots.copy(),
            lambda t, a=axis: _eval(poly.coeffs[1][a : a + 1], t)[:, 0],
            lambda t, c=c2: _eval(c, t)[:, 0],
        )
        candidates += [roots, polished]
    t = np.concatenate(candidates)
    values = _eval(poly.coeffs[0], t)
    return values.min(axis=0), values.max(axis=0)


def bounding_box(obj) -> tuple[np.ndarray, np.ndarray]:
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


def _queries(q, dimension: int) -> tuple[np.ndarray, bool]:
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


def _curve_closest(curve, q: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Parameters, points and squared distances of the nearest points to each row of q."""
    poly = _poly(curve)
    p = _significant(poly.coeffs[0])  # (d, N'+1) with the true leading term
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

        def gval(t):
            shape = t.shape
            pts = _eval(p, t).reshape(*shape, dim)
            der = _eval(dp, t).reshape(*shape, dim)
            return ((pts - q[:, None, :]) * der).sum(-1)

        def gprime(t):
            shape = t.shape
            pts = _eval(p, t).reshape(*shape, dim)
            der = _eval(dp, t).reshape(*shape, dim)
            sec = _eval(d2, t).reshape(*shape, dim)
            return (der * der).sum(-1) + ((pts - q[:, None, :]) * sec).sum(-1)

        polished = _newton(roots.copy(), gval, gprime)
        cands += [np.nan_to_num(roots, nan=0.0), np.nan_to_num(polished, nan=0.0)]
    t = np.concatenate(cands, axis=1)
    pts = _eval(poly.coeffs[0], t).reshape(*t.shape, dim)
    dist2 = np.square(pts - q[:, None, :]).sum(-1)
    best = np.argmin(dist2, axis=1)
    rows = np.arange(m)
    return t[rows, best], pts[rows, best], dist2[rows, best]


def closest_point(obj, q) -> ClosestPoint:
    """The global minimum of |p(t) − q| over the curve (u over a composite): the best of both
    ends and every critical point, i.e. every root of (p − q)·p' in [0, 1]. q is one point
    (d,) or a batch (m, d)."""
    segs = _segments(obj)
    queries, single = _queries(q, segs[0].dimension)
    best_t = best_d2 = best_pt = None
    for i, seg in enumerate(segs):
        t, pt, d2 = _curve_closest(seg, queries)
        if best_t is None:
            best_t, best_pt, best_d2 = t + i, pt, d2
            continue
        better = d2 < best_d2
        best_t = np.where(better, t + i, best_t)
        best_pt = np.where(better[:, None], pt, best_pt)
        best_d2 = np.where(better, d2, best_d2)
    assert best_t is not None and best_pt is not None and best_d2 is not None
    dist = np.sqrt(best_d2)
    if single:
        return ClosestPoint(float(best_t[0]), best_pt[0], float(dist[0]))
    return ClosestPoint(best_t, best_pt, dist)


# ---------------------------------------------------------------------- torsion
def torsion_from_derivatives(d1: np.ndarray, d2: np.ndarray, d3: np.ndarray, where):
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
    return (cross * d3).sum(-1) / norm2


def torsion(obj, t, *, extrapolate: bool = False):
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
