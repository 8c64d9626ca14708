"""Many curves of one family and degree at once: no Python loop over curves or parameters."""

from __future__ import annotations

import sys

import numpy as np
import numpy.typing as npt

from . import _validate as val
from .curves import FAMILIES, Curve, _float_matrix, _tables, family_class
from .hazmat import kernels as alg


def _lambdas(lam: npt.ArrayLike, cls: type[Curve], m: int, check_range: bool) -> np.ndarray:
    data, family = cls._data, cls.family
    arr = val.real_array(lam, "lam")
    if arr.ndim > 1 or (arr.ndim == 1 and arr.size != m):
        raise ValueError(f"lam must be a number or an array of {m} numbers, got shape {arr.shape}")
    arr = np.broadcast_to(arr, (m,))
    if not np.isfinite(arr).all():
        raise ValueError("lam contains NaN or infinity")
    if check_range:
        lo, hi = data.LAMBDA_RANGE
        lo_closed, hi_closed = data.LAMBDA_CLOSED
        ok = ((arr > lo) | ((arr == lo) & lo_closed)) & ((arr < hi) | ((arr == hi) & hi_closed))
        if not ok.all():
            idx = int(np.argmin(ok))
            raise ValueError(
                f"lam = {arr[idx]} (curve {idx}) is outside the {family} range "
                f"{data.LAMBDA_RANGE_TEXT}; pass check_range=False to use it anyway"
            )
    return arr


def evaluate_many(
    points: npt.ArrayLike,
    t: npt.ArrayLike,
    family: object = "bezier",
    lam: npt.ArrayLike | None = None,
    *,
    k: int = 0,
    check_range: bool = True,
    extrapolate: bool = False,
    params: dict[str, float] | None = None,
) -> np.ndarray:
    r"""The k-th derivative :math:`p^{(k)}(t)` of m curves of one family and degree at once.

    Parameters
    ----------
    points : array_like
        Control points of shape (m, n+1, d).
    t : array_like
        Parameter values, shape (T,), in [0, 1] unless `extrapolate` (a trigonometric,
        hyperbolic or mixed family: in its own domain of t, e.g. [0, π/2]).
    family : str
        ``"bezier"``, ``"same_degree"`` or ``"bernstein_like"``.
    lam : float or array_like, optional
        One λ for every curve, or one per curve (shape (m,)); not for ``"bezier"``.
    k : int
        The derivative order (0: the points of the curves).
    check_range : bool
        Refuse a λ outside the family's range.
    extrapolate : bool
        Allow t outside [0, 1].
    params : dict, optional
        A family in several parameters (from `load_family`): one value per parameter,
        ``{"lam": ..., "mu": ...}``, shared by every curve.

    Returns
    -------
    numpy.ndarray
        Shape (m, T, d).

    Examples
    --------
    >>> import numpy as np
    >>> pts = np.array([[(0, 0), (1, 2), (3, 2), (4, 0)]] * 2, dtype=float)
    >>> evaluate_many(pts, [0.0, 0.5], "same_degree", lam=[1.0, 0.5])[:, 1]
    array([[2.  , 1.5 ],
           [2.  , 1.25]])
    """
    if getattr(family, "atom_data", None) is not None:  # trigonometric, hyperbolic, mixed
        from .atom_family import evaluate_many as atom_evaluate_many

        named = {} if lam is None else {"lam": lam}
        given = family.parameter_values(None, params, named)  # type: ignore[attr-defined]
        exact = family.exact_values(given, val.flag(check_range, "check_range"))  # type: ignore[attr-defined]
        return atom_evaluate_many(family, points, t, k, exact, extrapolate)
    if getattr(family, "several", None) is not None:
        named = {} if lam is None else {"lam": lam}  # a parameter may be called lam
        given = family.parameter_values(None, params, named)  # type: ignore[attr-defined]
        family = family._fixed_class(given, val.flag(check_range, "check_range"))  # type: ignore[attr-defined]
        lam = None
    elif params is not None:
        raise TypeError("params: only a family in several parameters takes params (use lam)")
    # a built-in family's name, or a family from lambda_bezier.load_family
    cls = (
        FAMILIES[val.choice(family, "family", tuple(FAMILIES))]
        if isinstance(family, str)
        else family_class(family)
    )
    family = cls.family
    check_range = val.flag(check_range, "check_range")
    arr = val.real_array(points, "control points")
    if arr.ndim != 3:
        raise ValueError(f"control points must have shape (m, n+1, d), got shape {arr.shape}")
    m, size, dim = arr.shape
    # the classical curve takes any degree (as BezierCurve does); past its tables (and at
    # degree 0) it is evaluated by de Casteljau below
    degrees = (0, sys.maxsize) if cls._any_degree else tuple(cls._data.DEGREES)
    val.check_point_shape((size, dim), family=family, degrees=degrees)
    big = float(np.abs(arr).max()) if arr.size else 0.0  # NaN and inf propagate into this
    if not np.isfinite(big):
        idx = np.argwhere(~np.isfinite(arr))[0]
        raise ValueError(f"curve {idx[0]}, control point {idx[1]} has a non-finite coordinate")
    k = val.as_order(k)
    tt, scalar = val.as_parameters(t, extrapolate=extrapolate)
    n = size - 1
    if n not in cls._data.DEGREES:
        if lam is not None:
            raise ValueError("a classical Bézier curve takes no shape parameter")
        return _de_casteljau_many(arr, tt, k, scalar)
    mats = _tables(cls._data, "centred")[n]
    if not cls._has_lambda:
        if lam is not None:
            raise ValueError("a classical Bézier curve takes no shape parameter")
        lams = np.zeros(m)
    else:
        if lam is None:
            raise ValueError(f"a {family} curve needs a shape parameter lam")
        lams = _lambdas(lam, cls, m, check_range)
    # Coefficients of every curve in the centred monomials (t - 1/2)^e, laid out (N+1, m·d)
    # so that both products below are wide matrix products (BLAS is slow on tall-skinny ones).
    # coordinates beyond 2^±900: computed on points scaled by a power of two (exact), then
    # scaled back, so a representable p(t) is not lost to an overflow in the coefficients
    scale = val.scale_for_magnitude(big)
    with val.overflow_allowed():
        pt = np.ascontiguousarray(arr.transpose(1, 0, 2)).reshape(size, m * dim)
        if scale != 1.0:
            pt = pt / scale
        coeffs = _float_matrix(cls._data, "centred", n, 0).T @ pt
        for p in range(1, len(mats)):
            part = _float_matrix(cls._data, "centred", n, p).T @ pt
            coeffs += part * np.repeat(lams**p, dim)
        if k:
            from .hazmat.kernels import differentiate_coefficients

            coeffs = differentiate_coefficients(coeffs.T, k).T
        # Every curve shares the parameter grid: one product with the monomials at the grid.
        u = tt - 0.5
        powers = np.empty((tt.size, coeffs.shape[0]))
        powers[:, 0] = 1.0
        for e in range(1, coeffs.shape[0]):
            np.multiply(powers[:, e - 1], u, out=powers[:, e])
        out = (powers @ coeffs).reshape(tt.size, m, dim).transpose(1, 0, 2)
        if scale != 1.0:
            out = out * scale
    if scale != 1.0 or extrapolate or not check_range:  # otherwise nothing can overflow
        val.finite_result(out, "p(t)" if k == 0 else f"the derivative of order {k}")
    values: np.ndarray = out[:, 0] if scalar else out
    return values


def _de_casteljau_many(arr: np.ndarray, tt: np.ndarray, k: int, scalar: bool) -> np.ndarray:
    """evaluate_many for classical curves past the generated tables (and degree 0): de
    Casteljau on the k-th hodograph of every curve at once (the centred monomials are
    ill-conditioned at high degree; de Casteljau is not). No overflow scaling is needed:
    every step is a convex combination, and the differences of the hodograph are formed on
    points scaled by a power of two."""
    m, size, dim = arr.shape
    n = size - 1
    scale = val.scale_for_magnitude(float(np.abs(arr).max()) if arr.size else 0.0)
    work = arr / scale if scale != 1.0 else arr
    for order in range(k):  # p^(r+1) has the points (n - r)(P_{i+1} - P_i) of p^(r)
        if work.shape[1] == 1:
            work = np.zeros_like(work)
            break
        work = (n - order) * (work[:, 1:] - work[:, :-1])
    pts = np.ascontiguousarray(work.transpose(1, 0, 2)).reshape(work.shape[1], m * dim)
    with val.overflow_allowed():
        out = alg.de_casteljau_steps(pts, tt, pts.shape[0] - 1)[:, 0]  # (T, m·d)
        out = out.reshape(tt.size, m, dim).transpose(1, 0, 2)
        if scale != 1.0:
            out = out * scale
    val.finite_result(out, "p(t)" if k == 0 else f"the derivative of order {k}")
    values: np.ndarray = out[:, 0] if scalar else out
    return values
