"""Kernels for rational Bézier curves: pure functions on homogeneous control arrays.

A rational Bézier curve C(t) = Σ w_i P_i B_i(t) / Σ w_i B_i(t) is the central projection of
the polynomial curve H(t) = Σ (w_i P_i, w_i) B_i(t) in one dimension more (its homogeneous
form, rows (w_i P_i, w_i)). Everything here works on such rows, or on Bernstein coefficient
arrays, with numpy and the standard library only (no curve class): the runtime's rational
curve class (lambda_bezier.rational) holds the curve, these hold the algorithms.

Most functions work in the arithmetic of their input: numpy object arrays of Fractions stay
exact, float arrays stay float (the quotient rule, Bernstein products and conversions).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from fractions import Fraction
from functools import cache

import numpy as np
import numpy.typing as npt

# ---------------------------------------------------------------------- homogeneous form


def to_homogeneous(points: np.ndarray, weights: np.ndarray) -> np.ndarray:
    """(n+1, d) points and (n+1,) weights -> (n+1, d+1) rows (w_i P_i, w_i)."""
    return np.concatenate([points * weights[:, None], weights[:, None]], axis=1)


def from_homogeneous(rows: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(n+1, d+1) rows (w_i P_i, w_i) -> points (n+1, d) and weights (n+1,)."""
    weights = rows[:, -1]
    return rows[:, :-1] / weights[:, None], weights


def project(values: np.ndarray) -> np.ndarray:
    """(…, d+1) homogeneous values -> (…, d): the last coordinate divided out."""
    out: np.ndarray = values[..., :-1] / values[..., -1:]
    return out


def quotient_derivatives(h: Sequence[np.ndarray]) -> list[np.ndarray]:
    """C, C', …, C^(k) from H, H', …, H^(k) (each (m, d+1), last column the weight w):
    Leibniz's rule on A = w C gives A^(j) = Σ_i binom(j, i) w^(i) C^(j-i), so
    C^(j) = (A^(j) − Σ_{i>=1} binom(j, i) w^(i) C^(j-i)) / w. Object arrays of Fractions
    stay exact."""
    w = h[0][:, -1:]
    out: list[np.ndarray] = []
    for j, hj in enumerate(h):
        acc = hj[:, :-1]
        for i in range(1, j + 1):
            acc = acc - math.comb(j, i) * h[i][:, -1:] * out[j - i]
        out.append(acc / w)
    return out


def curvature_from_derivatives(d1: np.ndarray, d2: np.ndarray) -> np.ndarray:
    """Signed curvature (2D) or unsigned (3D) row-wise from C', C''; NaN where C' = 0. Each
    row is scaled by a power of two near its size first: |C'|³ then neither overflows nor
    underflows where κ itself is finite."""
    size = np.maximum(np.abs(d1).max(axis=-1), np.abs(d2).max(axis=-1))
    c = np.ldexp(1.0, np.frexp(np.where(size > 0, size, 1.0))[1])
    d1, d2 = d1 / c[..., None], d2 / c[..., None]
    if d1.shape[-1] == 2:
        cross = d1[..., 0] * d2[..., 1] - d1[..., 1] * d2[..., 0]
    else:
        cross = np.linalg.norm(np.cross(d1, d2), axis=-1)
    speed = np.linalg.norm(d1, axis=-1)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        kappa: np.ndarray = np.where(speed > 0, cross / speed / speed / speed, np.nan) / c
    return kappa


# ---------------------------------------------------------------------- Bernstein algebra
def de_casteljau(rows: np.ndarray, t: np.ndarray) -> np.ndarray:
    """Σ rows_i B_i(t) at every t: rows (n+1, …) -> (len(t), …) (floats). In the form
    (1 − t) a + t b, whose rounding is relative to the positive combination at both ends
    (a + t (b − a) is not near t = 1 when |a| >> |b|): w(t) keeps its relative accuracy."""
    tt = t.reshape(-1, *([1] * rows.ndim))
    ss = 1 - tt
    work = np.broadcast_to(rows, (t.size, *rows.shape))
    for _ in range(rows.shape[0] - 1):
        work = ss * work[:, :-1] + tt * work[:, 1:]
    out: np.ndarray = work[:, 0]
    return out


def homogeneous_derivatives(rows: np.ndarray, t: np.ndarray, order: int) -> list[np.ndarray]:
    """H, H', …, H^(order) at every t, (len(t), d+1) each, by de Casteljau on the
    hodographs (floats)."""
    out = []
    for _ in range(order + 1):
        out.append(de_casteljau(rows, t))
        rows = hodograph(rows)
    return out


def split_halves(pieces: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Subdivide a stack of Bernstein coefficient arrays (K, n+1, …) at t = 1/2."""
    left = [pieces[:, 0]]
    right = [pieces[:, -1]]
    work = pieces
    while work.shape[1] > 1:
        work = (work[:, :-1] + work[:, 1:]) / 2
        left.append(work[:, 0])
        right.append(work[:, -1])
    return np.stack(left, axis=1), np.stack(right[::-1], axis=1)


def split_at(rows: np.ndarray, t: object) -> tuple[np.ndarray, np.ndarray]:
    """Subdivide Bernstein coefficients (n+1, …) at one t, in the arithmetic of the inputs
    (an object array of Fractions and a Fraction t stay exact)."""
    left = [rows[0]]
    right = [rows[-1]]
    work = rows
    while work.shape[0] > 1:
        work = work[:-1] + t * (work[1:] - work[:-1])
        left.append(work[0])
        right.append(work[-1])
    return np.stack(left), np.stack(right[::-1])


def hodograph(rows: np.ndarray) -> np.ndarray:
    """Bernstein coefficients (n, …) of the derivative of Σ rows_i B_{i,n}; a zero row for
    n = 0."""
    n = rows.shape[0] - 1
    if n == 0:
        out: np.ndarray = rows * 0
        return out
    diff: np.ndarray = (rows[1:] - rows[:-1]) * n
    return diff


def elevate(rows: np.ndarray, times: int = 1) -> np.ndarray:
    """Degree elevation of Bernstein coefficients (n+1, …) by `times` degrees."""
    for _ in range(times):
        n = rows.shape[0] - 1
        top = n + 1
        mid = [
            rows[i - 1] * Fraction(i, top) + rows[i] * Fraction(top - i, top)
            if rows.dtype == object
            else rows[i - 1] * (i / top) + rows[i] * ((top - i) / top)
            for i in range(1, top)
        ]
        rows = np.stack([rows[0], *mid, rows[-1]])
    return rows


def product(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Bernstein coefficients of the product of Σ a_i B_{i,m} and Σ b_j B_{j,n}, degree
    m + n: c_k = Σ_{i+j=k} binom(m,i) binom(n,j) / binom(m+n,k) a_i b_j. The trailing axes
    broadcast (a (m+1, d) times a scalar polynomial b (n+1, 1), say)."""
    m, n = a.shape[0] - 1, b.shape[0] - 1
    exact = a.dtype == object or b.dtype == object
    terms: list[np.ndarray] = []
    for k in range(m + n + 1):
        acc: np.ndarray | None = None
        for i in range(max(0, k - n), min(m, k) + 1):
            num, den = math.comb(m, i) * math.comb(n, k - i), math.comb(m + n, k)
            coef: Fraction | float = Fraction(num, den) if exact else num / den
            term = a[i] * b[k - i] * coef
            acc = term if acc is None else acc + term
        assert acc is not None
        terms.append(acc)
    return np.stack(terms)


def derivative_numerator(rows: np.ndarray) -> np.ndarray:
    """Bernstein coefficients (2n, d) of N = A' w − A w' (degree 2n − 1), for homogeneous rows
    (n+1, d+1) = (A, w): C' = N / w². (Its top coefficient is zero: the true degree is at
    most 2n − 2; it is kept so that the degree is regular.)"""
    a, w = rows[:, :-1], rows[:, -1:]
    if rows.shape[0] == 1:
        out: np.ndarray = np.zeros((1, a.shape[1]), dtype=rows.dtype) * a[:1]
        return out
    diff: np.ndarray = product(hodograph(a), w) - product(a, hodograph(w))
    return diff


@cache
def _centred_basis(n: int) -> np.ndarray:
    """(n+1, n+1) Fractions: row i holds B_{i,n}(1/2 + u) as coefficients of u^0..u^n."""
    half = Fraction(1, 2)
    rows = []
    for i in range(n + 1):
        poly = [Fraction(math.comb(n, i))]
        for factor in [(half, Fraction(1))] * i + [(half, Fraction(-1))] * (n - i):
            nxt = [Fraction(0)] * (len(poly) + 1)
            for e, c in enumerate(poly):
                nxt[e] += c * factor[0]
                nxt[e + 1] += c * factor[1]
            poly = nxt
        rows.append(poly)
    return np.array(rows, dtype=object)


def bernstein_to_centred(coeffs: np.ndarray) -> np.ndarray:
    """(n+1, …) Bernstein coefficients -> (n+1, …) coefficients of (t − 1/2)^e (exact for an
    object array of Fractions, rounded once at the end for floats)."""
    basis = _centred_basis(coeffs.shape[0] - 1)
    if coeffs.dtype == object:
        out: np.ndarray = np.tensordot(basis.T, coeffs, axes=1)
        return out
    return np.tensordot(basis.astype(float).T, coeffs, axes=1)


# ---------------------------------------------------------------------- real roots
IMAG_TOL = 1e-4  # eigenvalues with a larger imaginary part (in u = t − 1/2) are not roots
EDGE_TOL = 1e-6  # eigenvalues this far outside [0, 1] are still tried (then clipped)


def _horner(c: np.ndarray, t: np.ndarray) -> np.ndarray:
    u = t - 0.5
    acc = np.full(t.shape, c[-1], dtype=float)
    for e in range(c.size - 2, -1, -1):
        acc = acc * u + c[e]
    return acc


def roots_in_unit(centred: np.ndarray) -> np.ndarray:
    """Candidate real roots in [0, 1] of Σ c_e (t − 1/2)^e (floats): companion eigenvalues
    of the polynomial without leading terms below 1e-13 of the largest term on |u| <= 1/2
    (rounding noise there would make the companion matrix's entries huge), accepted
    generously (a spurious candidate only costs an evaluation where they are used) and
    polished by Newton steps on the full polynomial."""
    c = np.asarray(centred, dtype=float)
    size = np.abs(c) * 0.5 ** np.arange(c.size)
    if not np.isfinite(size).all() or size.max(initial=0.0) == 0.0:
        return np.empty(0)
    keep = np.nonzero(size > 1e-13 * size.max())[0][-1]
    trimmed = c[: keep + 1]
    if trimmed.size < 2:
        return np.empty(0)
    roots = np.roots(trimmed[::-1])
    ok = (np.abs(roots.imag) <= IMAG_TOL) & (np.abs(roots.real) <= 0.5 + EDGE_TOL)
    t: np.ndarray = np.clip(roots.real[ok], -0.5, 0.5) + 0.5
    dc = c[1:] * np.arange(1, c.size)
    for _ in range(4):
        with np.errstate(divide="ignore", invalid="ignore"):
            step = _horner(c, t) / _horner(dc, t) if dc.size else np.zeros_like(t)
        t = np.where(np.isfinite(step), np.clip(t - step, 0.0, 1.0), t)
    return np.concatenate([np.clip(roots.real[ok], -0.5, 0.5) + 0.5, t])


def negative_intervals(coeffs: np.ndarray, floor: float, depth: int = 40) -> list[float]:
    """Midpoints of small intervals of [0, 1] where the scalar polynomial with Bernstein
    coefficients `coeffs` may be below `floor`: the pieces whose smallest Bernstein
    coefficient stays below it after subdivision to width 2^-depth (by the convex hull
    property the polynomial is >= floor on every other piece). An empty list certifies
    p(t) >= floor on all of [0, 1]."""
    pieces = np.asarray(coeffs, dtype=float)[None, :]
    lefts = np.zeros(1)
    width = 1.0
    for _ in range(depth):
        bad = pieces.min(axis=1) < floor
        pieces, lefts = pieces[bad], lefts[bad]
        if not pieces.size:
            return []
        # a piece whose values at both ends and middle are already below the floor holds a
        # point that is: stop subdividing it (enough to return a witness)
        width /= 2
        a, b = split_halves(pieces[:, :, None])
        pieces = np.concatenate([a[:, :, 0], b[:, :, 0]])
        lefts = np.concatenate([lefts, lefts + width])
        if pieces.shape[0] > 4096:  # keep the lowest ones: a witness is all that is needed
            order = np.argsort(pieces.min(axis=1))[:4096]
            pieces, lefts = pieces[order], lefts[order]
    bad = pieces.min(axis=1) < floor
    return [float(x) for x in lefts[bad] + width / 2]


# ---------------------------------------------------------------------- Möbius maps of [0, 1]
def reweight(weights: np.ndarray, rho: Fraction | float) -> np.ndarray:
    """Weights w_i ρ^i (ρ > 0): the same curve, reparameterised by the Möbius map
    t = ρ s / ((1 − s) + ρ s) of [0, 1] onto itself (see mobius)."""
    return np.array([w * rho**i for i, w in enumerate(weights)], dtype=weights.dtype)


def mobius(rho: float, s: np.ndarray) -> np.ndarray:
    """t = ρ s / ((1 − s) + ρ s): the parameter of the original curve at parameter s of the
    curve reweighted by ρ. Its inverse is mobius(1/ρ, ·)."""
    out: np.ndarray = rho * s / ((1 - s) + rho * s)
    return out


# ---------------------------------------------------------------------- quadrature
_GAUSS = 16  # points of the Gauss–Legendre rule on each piece
_MAX_PIECES = 20000  # pieces of one level beyond which adaptive_table gives up


@cache
def _gauss() -> tuple[np.ndarray, np.ndarray]:
    x, w = np.polynomial.legendre.leggauss(_GAUSS)
    return (x + 1) / 2, w / 2  # on [0, 1]


def gauss_pieces(
    f: Callable[[np.ndarray], np.ndarray], lo: np.ndarray, hi: np.ndarray
) -> np.ndarray:
    """The Gauss rule for ∫ f over each [lo_k, hi_k] (one vectorised call of f)."""
    x, w = _gauss()
    width = hi - lo
    values = f((lo[:, None] + width[:, None] * x).ravel()).reshape(lo.size, _GAUSS)
    out: np.ndarray = values @ w * width
    return out


def adaptive_table(
    f: Callable[[np.ndarray], np.ndarray], rtol: float, breaks: npt.ArrayLike = ()
) -> tuple[np.ndarray, np.ndarray]:
    """∫_0^1 f for a smooth non-negative f, adaptively: each piece's Gauss value is compared
    with the sum over its halves, and pieces are accepted (with the halves' sum, far more
    accurate than the difference that tested it) while their differences fit in the error
    budget rtol · total (see below). `breaks` are points where pieces must end (kinks of f).
    Returns the accepted partition's edges (K+1,) and cumulative integrals (K+1,)."""
    edges = np.unique(np.concatenate([np.linspace(0.0, 1.0, 17), np.asarray(breaks, float)]))
    edges = edges[(edges >= 0) & (edges <= 1)]
    # breaks within rounding of each other (a double root found twice) are one
    edges = edges[np.concatenate([[True], np.diff(edges) > 1e-12])]
    edges[-1] = 1.0
    lo, hi = edges[:-1], edges[1:]
    accepted_lo: list[np.ndarray] = []
    accepted_hi: list[np.ndarray] = []
    accepted_val: list[np.ndarray] = []
    whole = gauss_pieces(f, lo, hi)
    peak = 0.0  # the largest mean of f over a piece so far: f's size
    spent = 0.0  # the error estimates of the accepted pieces
    for _ in range(60):
        mid = (lo + hi) / 2
        left, right = gauss_pieces(f, lo, mid), gauss_pieces(f, mid, hi)
        halves = left + right
        total = sum(float(v.sum()) for v in accepted_val) + float(halves.sum())
        err = np.abs(halves - whole)
        # the error budget left, rtol · total less what accepted pieces spent: all pieces
        # are accepted when their errors fit in it; otherwise those with the smallest
        # errors, up to half of it, and the rest are halved
        budget = rtol * max(total, 1e-300) - spent
        if float(err.sum()) <= budget:
            ok = np.ones(err.size, dtype=bool)
        else:
            order = np.argsort(err)
            ok = np.zeros(err.size, dtype=bool)
            ok[order[np.cumsum(err[order]) <= budget / 2]] = True
        # or within the rounding of the values themselves: f is computed with an absolute
        # error of a few ulps of its largest size (a quotient-rule derivative cancels where
        # the speed is small against it), which no refinement removes
        peak = max(peak, float((np.abs(halves) / (hi - lo)).max()))
        ok |= err <= 1e3 * np.finfo(float).eps * peak * (hi - lo)
        # pieces too narrow to refine in floats are accepted as they stand
        ok |= (hi - lo) < 1e-14
        spent += float(err[ok].sum())
        for side_lo, side_hi, val in ((lo, mid, left), (mid, hi, right)):
            accepted_lo.append(side_lo[ok])
            accepted_hi.append(side_hi[ok])
            accepted_val.append(val[ok])
        if ok.all():
            break
        bad = ~ok
        if 2 * int(bad.sum()) > _MAX_PIECES:
            raise ArithmeticError(
                f"the adaptive quadrature needs more than {_MAX_PIECES} pieces (f spikes "
                "sharply, e.g. weights of very different size)"
            )
        lo = np.concatenate([lo[bad], mid[bad]])
        hi = np.concatenate([mid[bad], hi[bad]])
        whole = np.concatenate([left[bad], right[bad]])
    else:
        raise ArithmeticError("arc length: the adaptive quadrature did not converge")
    los = np.concatenate(accepted_lo)
    his = np.concatenate(accepted_hi)
    vals = np.concatenate(accepted_val)
    order = np.lexsort((his, los))  # a zero-width piece before the piece it starts
    out_edges = np.append(los[order], 1.0)
    cum = np.concatenate([[0.0], np.cumsum(vals[order])])
    return out_edges, cum


# ---------------------------------------------------------------------- SVG approximation
def hermite_cubic(rows: np.ndarray, d: int) -> np.ndarray:
    """The polynomial cubic (4, d) with the rational piece's end points and end
    derivatives (C'(0) = n w_1/w_0 (P_1 − P_0), C'(1) = n w_{n-1}/w_n (P_n − P_{n-1}))."""
    pts, w = project(rows), rows[:, -1]
    n = rows.shape[0] - 1
    d0 = n * w[1] / w[0] * (pts[1] - pts[0])
    d1 = n * w[-2] / w[-1] * (pts[-1] - pts[-2])
    return np.array([pts[0], pts[0] + d0 / 3, pts[-1] - d1 / 3, pts[-1]])


def cubic_error_bound(rows: np.ndarray, cubic: np.ndarray) -> float:
    """A bound on max_t |C(t) − Q(t)| for the rational piece (homogeneous rows, positive
    weights) and the polynomial cubic Q: C − Q = (A − Q w) / w, and on [0, 1]
    |A − Q w| <= the largest norm of its Bernstein coefficients while w >= its smallest
    Bernstein coefficient (convex hull property)."""
    a, w = rows[:, :-1], rows[:, -1:]
    diff = elevate(a, 3) - product(cubic, w)
    return float(np.linalg.norm(diff, axis=1).max() / w.min())


def cubics(rows: np.ndarray, tolerance: float, depth: int = 0) -> list[np.ndarray]:
    """Polynomial cubics within `tolerance` of the rational piece at every parameter (by
    cubic_error_bound), halving where the Hermite cubic is not close enough."""
    cubic = hermite_cubic(rows, rows.shape[1] - 1)
    scale = float(np.abs(project(rows)).max())
    if cubic_error_bound(rows, cubic) + 64 * np.finfo(float).eps * scale <= tolerance:
        return [cubic]
    if depth >= 40:
        raise ValueError(f"cannot approximate within tolerance={tolerance} (too small)")
    left, right = split_halves(rows[None])
    return cubics(left[0], tolerance, depth + 1) + cubics(right[0], tolerance, depth + 1)


# ---------------------------------------------------------------------- intersection
def _boxes(pieces: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Axis-aligned boxes (P, d) of stacked homogeneous pieces (P, n+1, d+1): with positive
    weights each piece lies in the convex hull of its projected control points."""
    pts = project(pieces)
    return pts.min(axis=1), pts.max(axis=1)


def overlap_starts(
    ha: np.ndarray, hb: np.ndarray, size: float, *, stop: float = 1e-4, max_pairs: int = 20000
) -> np.ndarray:
    """Starting points (s, t) for Newton, (k, 2): the midpoints of the pairs of subdivided
    pieces of the two curves (homogeneous rows, positive weights) whose boxes still overlap
    once every box is below stop · size (or after 40 halvings). A pair of pieces whose boxes
    are apart cannot intersect (convex hull property), so no intersection is missed. More
    than `max_pairs` pairs means the curves share a stretch: ValueError."""
    pa, pb = ha[None], hb[None]
    lo = np.zeros((1, 2))
    slack = 1e-9 * size
    wa = wb = 1.0  # the pieces' parameter widths on each curve
    for _ in range(80):
        alo, ahi = _boxes(pa)
        blo, bhi = _boxes(pb)
        keep = np.all((alo <= bhi + slack) & (blo <= ahi + slack), axis=1)
        pa, pb, lo = pa[keep], pb[keep], lo[keep]
        if not keep.any():
            return np.empty((0, 2))
        # a side whose boxes are small already (or a point) is not cut further
        cut_a = float((ahi - alo)[keep].max()) > stop * size and wa > 2.0**-40
        cut_b = float((bhi - blo)[keep].max()) > stop * size and wb > 2.0**-40
        if not (cut_a or cut_b):
            break
        if pa.shape[0] * (1 + cut_a) * (1 + cut_b) > max_pairs:
            raise ValueError(
                "the curves appear to share a stretch (coincident pieces): rational curves "
                "report isolated intersections only"
            )
        if cut_a:
            a0, a1 = split_halves(pa)
            wa /= 2
            pb = np.concatenate([pb, pb])
            pa = np.concatenate([a0, a1])
            lo = np.concatenate([lo, lo + [wa, 0.0]])
        if cut_b:
            b0, b1 = split_halves(pb)
            wb /= 2
            pa = np.concatenate([pa, pa])
            pb = np.concatenate([b0, b1])
            lo = np.concatenate([lo, lo + [0.0, wb]])
    starts: np.ndarray = lo + [wa / 2, wb / 2]
    return starts


def monotone(numerator: np.ndarray) -> bool:
    """Whether every Bernstein coefficient of a curve's derivative numerator N (k, d) has a
    positive dot product with their mean direction: then C' never reverses along it and the
    piece cannot meet itself."""
    mean = numerator.mean(axis=0)
    if not np.any(mean):
        return False
    return bool(np.all(numerator @ mean > 0))
