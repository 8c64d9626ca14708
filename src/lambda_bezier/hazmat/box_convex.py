"""The neighbourhood of a minimum, for box_bernstein's branch and bound: a float polish of a
candidate point, and an exact lower bound of the polynomial over a small box about it.

Why: Bernstein bounds over a box of width h are loose by about C h² (C the size of the
second derivatives), while the polynomial rises from its minimiser by about μ d²/2 at
distance d (μ the least curvature). Near an interior minimum a box can only be dropped once
h is below the tolerance's square root, and every box within d < h sqrt(C/μ) of the
minimiser stays open: with six variables that outran the 20,000-box budget (q_bezier
surfaces, two directions of three parameters). One box about the minimiser on which the
Hessian is bounded below, H >= diag(m), removes that whole neighbourhood at once: there
E(y) >= E(x) + ∇E(x)·(y − x) + Σ m_i (y_i − x_i)² / 2, whose minimum over the box is
separable and exact.

Everything certified here is exact (Fractions); the polish is floats and only proposes a
point (its exact value is the caller's to compute).
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np

from .box_forms import bernstein, float_value, value

Box = list[tuple[Fraction, Fraction]]


def derivative(power: np.ndarray, axis: int) -> np.ndarray:
    """d/dx_axis of a dense power-coefficient array (same dtype; one degree less there, at
    least a constant)."""
    n = power.shape[axis]
    if n == 1:
        return np.zeros_like(power)
    shape = [1] * power.ndim
    shape[axis] = n - 1
    factors = np.arange(1, n).reshape(shape)
    if power.dtype == object:
        factors = factors.astype(object)
    out: np.ndarray = np.take(power, range(1, n), axis=axis) * factors
    return out


def polish(floats: np.ndarray, box: Box, point: tuple[float, ...], steps: int = 12) -> np.ndarray:
    """A float local minimiser over the box near `point`: projected Newton steps (variables
    at an end of their range whose gradient pushes outward are held there; a step that does
    not lower the float value is halved). Only a proposal: nothing here is certified."""
    count = floats.ndim
    lo = np.array([float(a) for a, _ in box])
    hi = np.array([float(b) for _, b in box])
    grads = [derivative(floats, j) for j in range(count)]
    hess = [[derivative(grads[i], j) for j in range(count)] for i in range(count)]
    x: np.ndarray = np.clip(np.array(point, dtype=float), lo, hi)
    fx = float_value(floats, x)
    for _ in range(steps):
        g = np.array([float_value(grads[i], x) for i in range(count)])
        held = ((x <= lo) & (g > 0)) | ((x >= hi) & (g < 0))
        free = np.flatnonzero(~held)
        if free.size == 0:
            break
        h = np.array([[float_value(hess[i][j], x) for j in free] for i in free])
        try:
            step = np.linalg.solve(h, g[free])
        except np.linalg.LinAlgError:
            break
        if not np.all(np.isfinite(step)) or np.any(np.linalg.eigvalsh(h) <= 0):
            step = g[free] / max(float(np.abs(np.diag(h)).max()), 1e-300)  # a gradient step
        t = 1.0
        for _ in range(30):
            y = x.copy()
            y[free] = np.clip(x[free] - t * step, lo[free], hi[free])
            fy = float_value(floats, y)
            if fy <= fx:
                break
            t /= 2
        else:
            break
        if np.array_equal(y, x):
            break
        x, fx = y, fy
    return x


def _bernstein_range(power: np.ndarray, box: Box) -> tuple[Fraction, Fraction]:
    coeffs = bernstein(power, box)
    return Fraction(min(coeffs.flat)), Fraction(max(coeffs.flat))


def _least(g: Fraction, m: Fraction, a: Fraction, b: Fraction) -> Fraction:
    """min of g t + m t² / 2 over t in [a, b] (any sign of m: the vertex, or an end)."""
    ends = [g * t + m * t * t / 2 for t in (a, b)]
    if m > 0 and a <= -g / m <= b:
        ends.append(-g * g / (2 * m))
    return min(ends)


def _semidefinite(mat: list[list[Fraction]]) -> bool:
    """Whether a symmetric exact matrix is positive definite: LDLᵀ with every pivot > 0."""
    a = [row[:] for row in mat]
    size = len(a)
    for k in range(size):
        if a[k][k] <= 0:
            return False
        for i in range(k + 1, size):
            f = a[i][k] / a[k][k]
            if f:
                for j in range(k + 1, size):
                    a[i][j] -= f * a[k][j]
    return True


def _spectral_bound(
    centre: list[list[Fraction]], radius: list[list[Fraction]], scale: list[Fraction]
) -> list[Fraction] | None:
    """Diagonal lower bounds m_i (H >= diag(m)) of every H with |H − centre| <= radius
    entrywise, from the scaled centre's least eigenvalue: with D = diag(scale), D C D − σ I
    certified positive definite (exact LDLᵀ, σ a little below the float eigenvalue) and
    ρ = max_i Σ_j w_i w_j R_ij (which bounds ||D (H − C) D||₂), D H D >= (σ − ρ) I, so
    H >= (σ − ρ) D^-2. None when the float eigenvalue is not finite or the check fails."""
    size = len(centre)
    scaled = [[scale[i] * centre[i][j] * scale[j] for j in range(size)] for i in range(size)]
    least = np.linalg.eigvalsh(np.array(scaled, dtype=float))
    if not np.all(np.isfinite(least)):
        return None
    sigma = Fraction(float(least[0] - 1e-9 * max(1.0, float(np.abs(least).max()))))
    shifted = [
        [x - (sigma if i == j else 0) for j, x in enumerate(row)] for i, row in enumerate(scaled)
    ]
    if not _semidefinite(shifted):
        return None
    rho = max(
        sum((scale[i] * scale[j] * radius[i][j] for j in range(size)), Fraction(0))
        for i in range(size)
    )
    return [(sigma - rho) / (w * w) for w in scale]


def quadratic_floor(
    power: np.ndarray, region: Box, point: tuple[Fraction, ...], scale: list[Fraction]
) -> Fraction:
    """A lower bound of the polynomial over `region` (a box holding `point`).

    Exact Bernstein ranges of every second derivative over the region give a diagonal
    lower bound H >= diag(m) of the Hessian over the region (m_i of any sign), so by
    Taylor's theorem with the integral remainder E(y) >= E(x) + Σ_i (g_i t_i + m_i t_i² / 2),
    t = y − x, minimised coordinate by coordinate over the region. Two such m, the larger
    floor taken (weights w_i = `scale`[i], about 1/sqrt(H_ii), so that badly scaled
    variables do not spoil either):

    - weighted diagonal dominance: m_i = lo(H_ii) − Σ_(j≠i) max|H_ij| w_j / w_i;
    - the scaled centre matrix's least eigenvalue less the ranges' spread (_spectral_bound),
      for Hessians with strongly coupled variables, where dominance fails.

    Tight where the region is strictly convex about a critical point (every m_i > 0,
    g ≈ 0), and where a variable at an end of its range has a gradient pushing outward
    (g_i t_i dominates whatever the sign of m_i)."""
    count = power.ndim
    grads = [derivative(power, j) for j in range(count)]
    lows = [[Fraction(0)] * count for _ in range(count)]
    highs = [[Fraction(0)] * count for _ in range(count)]
    for i in range(count):
        for j in range(i, count):
            lo, hi = _bernstein_range(derivative(grads[i], j), region)
            lows[i][j] = lows[j][i] = lo
            highs[i][j] = highs[j][i] = hi
    dominance = [
        lows[i][i]
        - sum(
            (
                max(abs(lows[i][j]), abs(highs[i][j])) * scale[j] / scale[i]
                for j in range(count)
                if j != i
            ),
            Fraction(0),
        )
        for i in range(count)
    ]
    centre = [[(lows[i][j] + highs[i][j]) / 2 for j in range(count)] for i in range(count)]
    radius = [[(highs[i][j] - lows[i][j]) / 2 for j in range(count)] for i in range(count)]
    spectral = _spectral_bound(centre, radius, scale)
    here = value(power, point)
    slopes = [value(g, point) for g in grads]
    best: Fraction | None = None
    for m in (dominance, spectral):
        if m is None:
            continue
        floor = here
        for i in range(count):
            a, b = region[i][0] - point[i], region[i][1] - point[i]
            floor += _least(slopes[i], m[i], a, b)
        best = floor if best is None else max(best, floor)
    assert best is not None
    return best


def weights(floats: np.ndarray, point: np.ndarray) -> list[Fraction]:
    """Positive rational weights about 1/sqrt(H_ii) at `point` (1 where H_ii is not
    positive): convex_floor's scaling."""
    out = []
    for i in range(floats.ndim):
        h = float_value(derivative(derivative(floats, i), i), point)
        out.append(Fraction(1.0 / np.sqrt(h)) if h > 0 and np.isfinite(h) else Fraction(1))
    return out


def local_floor(
    power: np.ndarray, floats: np.ndarray, box: Box, point: tuple[Fraction, ...], need: Fraction
) -> tuple[Box, Fraction] | None:
    """(region, floor): the widest box about `point` inside `box` (half-widths 2^-k of the
    box's sides, k = 2, 4, 8, ..., 20) whose quadratic_floor is at least `need`; None when
    none is (no strict local minimum there, or too flat)."""
    scale = weights(floats, np.array([float(x) for x in point]))
    for k in (2, 4, 8, 12, 16, 20):
        region: Box = []
        for (lo, hi), x in zip(box, point, strict=True):
            r = (hi - lo) / 2**k
            region.append((max(lo, x - r), min(hi, x + r)))
        got = quadratic_floor(power, region, point, scale)
        if got >= need:
            return region, got
    return None
