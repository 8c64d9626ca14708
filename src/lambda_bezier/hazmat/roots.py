"""Real roots in [0, 1] of polynomials given by Taylor coefficients about t = 1/2.

About 1/2 the monomials are as well conditioned on [0, 1] as the Bernstein basis. Roots come
from the eigenvalues of a companion matrix (batched over rows), accepted generously (near-real,
slightly outside [0, 1]: a spurious candidate only costs its caller one evaluation) and
polished by guarded Newton steps. Nothing starts from a guess.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

IMAG_TOL = 1e-4  # eigenvalues with a larger imaginary part (in u = t - 1/2) are not roots
EDGE_TOL = 1e-6  # eigenvalues this far outside [0, 1] are still tried (then clipped)


def significant(coeffs: np.ndarray) -> np.ndarray:
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


def candidate_roots(c: np.ndarray) -> np.ndarray:
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
    ok = (np.abs(roots.imag) <= IMAG_TOL) & (np.abs(real) <= 0.5 + EDGE_TOL)
    return np.where(ok, np.clip(real, -0.5, 0.5) + 0.5, np.nan)


def newton(
    t: np.ndarray,
    f: Callable[[np.ndarray], np.ndarray],
    fprime: Callable[[np.ndarray], np.ndarray],
    steps: int = 4,
) -> np.ndarray:
    """A few guarded Newton steps on every finite candidate (kept inside [0, 1])."""
    return newton_pair(t, lambda tt: (f(tt), fprime(tt)), steps)


def newton_pair(
    t: np.ndarray,
    f_and_fprime: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]],
    steps: int = 4,
) -> np.ndarray:
    """`newton` with f and f' from one call (which can share their evaluations)."""
    for _ in range(steps):
        good = np.isfinite(t)
        tt = np.where(good, t, 0.5)
        value, slope = f_and_fprime(tt)
        with np.errstate(divide="ignore", invalid="ignore"):
            step = value / slope
        t = np.where(good & np.isfinite(step), np.clip(tt - step, 0.0, 1.0), t)
    return t
