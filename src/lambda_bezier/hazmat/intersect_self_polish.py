"""Self-crossings polished on the divided difference G(s, t) = (p(s) − p(t)) / (s − t), in floats.

Newton on p(s) − p(t) = 0 cannot place a crossing on a small loop: near a cusp both the
difference and its Jacobian carry the factor s − t, so rounding of the points (about n ε of
the size) moves the root by n ε / (|s − t| σ), σ the smallest singular value of the Jacobian
of G. The cubic (0,0), (a,1), (1−a,1), (1,0) with a = 1 + 8/3·10^-12 crosses itself at
s = 1/2 ∓ 1e-6; Newton on the difference stops 4e-7 off. G itself is a polynomial whose
value rounds to about n ε of the size whatever s − t is: by the blossom of the hodograph
h = p′ (degree m = n − 1),

    G(s, t) = (1/n) Σ_{k=0}^{m} h[s^k, t^(m−k)],

(for p = x^n: Σ s^k t^(n−1−k)), and its derivative in s, from ∂h[u]/∂u_i = h′[u without u_i] / m,

    ∂G/∂s (s, t) = (1/(n m)) Σ_{k=1}^{m} k h′[s^(k−1), t^(m−k)],    ∂G/∂t (s, t) = ∂G/∂s (t, s),

with h′ the second hodograph. Every blossom of one call is one de Casteljau run over a batch
(one row of arguments per term).
"""

from __future__ import annotations

import numpy as np

POLISH_STEPS = 12  # Newton converges quadratically; more steps than this means it does not
# a step this small (in parameter) before the steps stop contracting: Newton has converged
# (from there quadratic convergence reaches the last bits in one more step)
SETTLED = 1e-8


def _blossoms(rows: np.ndarray, args: np.ndarray) -> np.ndarray:
    """(b, d): the blossom of the Bézier control points rows (m + 1, d) at each row of args
    (b, m)."""
    m = rows.shape[0] - 1
    work = np.broadcast_to(rows, (args.shape[0], *rows.shape)).copy()
    for j in range(m):
        u = args[:, j, None, None]
        work = (1.0 - u) * work[:, :-1] + u * work[:, 1:]
    out: np.ndarray = work[:, 0]
    return out


def _args(m: int, s: float, t: float, first: int) -> np.ndarray:
    """Rows [s]*k + [t]*(m − k) for k = first .. first + rows − 1 (m arguments each)."""
    ks = np.arange(first, m + 1)
    cols = np.arange(m)
    return np.where(cols[None, :] < ks[:, None], s, t)


def divided_difference(h1: np.ndarray, s: float, t: float) -> np.ndarray:
    """G(s, t) of the module's docstring, h1 the hodograph's control points (n, d)."""
    n = h1.shape[0]
    out: np.ndarray = _blossoms(h1, _args(n - 1, s, t, 0)).sum(axis=0) / n
    return out


def _d_ds(h2: np.ndarray, n: int, s: float, t: float) -> np.ndarray:
    m = n - 1
    if m == 0:
        return np.zeros(h2.shape[1])
    ks = np.arange(1, m + 1, dtype=float)
    # rows [s]*(k−1) + [t]*(m−k): m − 1 arguments each, k = 1 .. m
    b = _blossoms(h2, _args(m - 1, s, t, 0))
    out: np.ndarray = (ks[:, None] * b).sum(axis=0) / (n * m)
    return out


def polished(h1: np.ndarray, h2: np.ndarray, s: float, t: float) -> tuple[float, float] | None:
    """(s, t) refined by Newton on G = 0 (least squares past the plane), or None when Newton
    does not settle inside 0 <= s < t <= 1 (the float answer stands then)."""
    n = h1.shape[0]
    if n < 2 or not 0.0 <= s < t <= 1.0:
        return None
    last = np.inf
    for _ in range(POLISH_STEPS):
        g = divided_difference(h1, s, t)
        jac = np.stack([_d_ds(h2, n, s, t), _d_ds(h2, n, t, s)], axis=1)
        step, *_ = np.linalg.lstsq(jac, -g, rcond=None)
        if not np.isfinite(step).all():
            return None
        size = float(np.abs(step).max())
        if size >= last:  # no longer contracting: at the last bits, or not converging
            return (s, t) if last <= SETTLED else None
        s, t = s + float(step[0]), t + float(step[1])
        if not 0.0 <= s < t <= 1.0:
            return None
        if size == 0.0:
            return s, t
        last = size
    return None
