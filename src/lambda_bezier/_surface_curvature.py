"""Gaussian and mean curvature of a surface from its partial derivatives at paired points,
with a bound of their rounding: `Surface.curvatures` refuses a point where rounding decides
them, as `Surface._frame` refuses a normal within the rounding of S_u and S_v."""

from __future__ import annotations

import numpy as np

from . import _validate as val

# the relative rounding of a derivative evaluated from its Taylor coefficients, per unit of
# the sum of its absolute terms (`_partial_magnitude`): a few ulps times the degree, generously
ROUNDING = 1e-15


def _length(x: np.ndarray) -> np.ndarray:
    out: np.ndarray = np.linalg.norm(x, axis=-1)
    return out


def shape_operator(
    su: np.ndarray,
    sv: np.ndarray,
    n: np.ndarray,
    size: np.ndarray,
    second: tuple[np.ndarray, ...],
    mags: list[np.ndarray],
    turn: np.ndarray,
    uu: np.ndarray,
    vv: np.ndarray,
) -> tuple[np.ndarray, np.ndarray]:
    """(K, H) in the scaled units of `Surface._frame`, refused where rounding decides them.

    The shape operator W in the orthonormal tangent frame e1 = S_u / |S_u|, e2 = n x e1:
    with w = S_v - c S_u (c = <S_u, S_v> / |S_u|², so w = b e2, b = |S_u x S_v| / |S_u|),
    W11 = <S_uu, n> / |S_u|², W12 = <S_uv - c S_uu, n> / (|S_u| b) and
    W22 = <S_vv - 2c S_uv + c² S_uu, n> / b², the second derivative along w. K = det W,
    H = tr W / 2 (the classical (LN - M²) / (EG - F²), whose EG - F² cancels to 0 in floats
    where S_u and S_v are nearly parallel: a curvature wrong by 10% at an angle of 1e-7).

    Each entry's error is bounded by the rounding of the second partials it combines
    (ROUNDING times their magnitudes), plus its vector's length times the normal's turn,
    plus, in W22, the rounding of c; the principal curvatures move by at most the Frobenius
    norm rho of those bounds. Where S_u and S_v are nearly parallel, b is tiny and rho
    large: the second partials, each rounded on its own, no longer resolve the bending
    along w. At a collapsed edge b is small too, but there S_vv and its rounding shrink
    with it. The curvatures are returned when rho is within 1e-6 of the larger principal
    curvature, or of 1 (the partials, scaled to entries at most 1, measure the patch: a
    curvature of 1 is a radius of about its size), so that planes and flat parts pass."""
    suu, suv, svv = second
    mag_uu, mag_uv, mag_vv = mags
    with val.overflow_allowed(), np.errstate(divide="ignore"):
        e = (su * su).sum(-1)
        len_u, len_v = np.sqrt(e), np.linalg.norm(sv, axis=-1)
        c = (su * sv).sum(-1) / e
        b = size / len_u
        across = suv - c[:, None] * suu
        along_w = svv - 2 * c[:, None] * suv + (c * c)[:, None] * suu
        w11 = (suu * n).sum(-1) / e
        w12 = (across * n).sum(-1) / (len_u * b)
        w22 = (along_w * n).sum(-1) / (b * b)
        gauss, mean = w11 * w22 - w12 * w12, 0.5 * (w11 + w22)
        ac = np.abs(c)
        slant = ROUNDING * len_v / b  # c's rounding, as an angle of w off e2
        d11 = (ROUNDING * mag_uu + _length(suu) * turn) / e
        d12 = (ROUNDING * (mag_uv + ac * mag_uu) + _length(across) * turn) / (len_u * b)
        d22 = (
            (ROUNDING * (mag_vv + 2 * ac * mag_uv + c * c * mag_uu) + _length(along_w) * turn)
            / (b * b)
            + 2 * slant * np.abs(w12)
            + slant * slant * np.abs(w11)
        )
        rho = np.sqrt(d11 * d11 + 2 * d12 * d12 + d22 * d22)
        kmax = np.abs(mean) + np.sqrt(np.abs(mean * mean - gauss))
        bad = ~(rho <= 1e-6 * np.maximum(kmax, 1.0))
    if bad.any():
        k = int(np.argmax(bad))
        raise ValueError(
            f"the curvature is undefined within rounding at (u, v) = ({uu[k]}, {vv[k]}): S_u "
            "and S_v are so nearly parallel there that the rounding of the second "
            "derivatives decides it (a degenerate point of the parametrisation)"
        )
    return gauss, mean
