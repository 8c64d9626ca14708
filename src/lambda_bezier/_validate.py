"""Input checks with messages that name the problem (never a traceback from deep in numpy)."""

from __future__ import annotations

import math
import numbers
from fractions import Fraction
from types import ModuleType

import numpy as np

ExactRows = tuple[tuple[Fraction, ...], ...]


def is_exact_scalar(x: object) -> bool:
    return isinstance(x, numbers.Rational | np.integer) and not isinstance(x, bool | np.bool_)


def exact_rows(points: object) -> ExactRows | None:
    """The control points as Fractions when every coordinate is an int or a Fraction."""
    if isinstance(points, np.ndarray):
        if points.ndim != 2:
            return None
        if points.dtype.kind in "iu":
            return tuple(tuple(Fraction(int(v)) for v in row) for row in points.tolist())
        if points.dtype.kind != "O":
            return None
        rows = points.tolist()
    else:
        try:
            rows = [list(r) for r in points]  # type: ignore[union-attr]
        except TypeError:
            return None
    try:
        if not all(is_exact_scalar(v) for row in rows for v in row):
            return None
    except TypeError:  # a row that is not a sequence, or a deeper nesting (a batch)
        return None
        return None
    return tuple(
        tuple(Fraction(int(v)) if isinstance(v, np.integer) else Fraction(v) for v in row)
        for row in rows
    )


def as_points(points: object, *, family: str, degrees: tuple[int, ...]) -> np.ndarray:
    """(n+1, d) float array, d >= 1, n in `degrees`, all finite."""
    try:
        arr = np.array(points, dtype=float)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"control points must be an (n+1, d) array of numbers: {exc}") from None
    if arr.ndim != 2 or arr.shape[1] < 1:
        raise ValueError(
            f"control points must have shape (n+1, d) with d >= 1, got shape {arr.shape}"
        )
    degree = arr.shape[0] - 1
    lo, hi = degrees[0], degrees[-1]
    if degree < lo:
        raise ValueError(
            f"a {family} curve needs at least {lo + 1} control points (degree >= {lo}), "
            f"got {arr.shape[0]}"
        )
    if degree > hi:
        raise ValueError(
            f"degree {degree} is not supported for {family}: generated data covers degrees "
            f"{lo}..{hi}"
        )
    bad = ~np.isfinite(arr)
    if bad.any():
        row, col = map(int, np.argwhere(bad)[0])
        raise ValueError(f"control point {row} has a non-finite coordinate ({arr[row, col]})")
    arr.setflags(write=False)
    return arr


def as_lambda(lam: object, family: ModuleType, *, check_range: bool) -> Fraction | float:
    """λ as a Fraction (exact input) or a float; inside the family's range unless told not."""
    if isinstance(lam, bool | np.bool_) or not isinstance(lam, numbers.Real | np.floating):
        raise ValueError(f"lam must be a real number, got {lam!r}")
    value: Fraction | float
    if is_exact_scalar(lam):
        value = Fraction(int(lam)) if isinstance(lam, np.integer) else Fraction(lam)  # type: ignore[arg-type]
    else:
        value = float(lam)  # type: ignore[arg-type]
        if not math.isfinite(value):
            raise ValueError(f"lam must be finite, got {value}")
    if check_range:
        lo, hi = family.LAMBDA_RANGE
        lo_closed, hi_closed = family.LAMBDA_CLOSED
        below = value < lo or (value == lo and not lo_closed)
        above = value > hi or (value == hi and not hi_closed)
        if below or above:
            raise ValueError(
                f"lam = {lam} is outside the {family.FAMILY} range {family.LAMBDA_RANGE_TEXT}; "
                "pass check_range=False to use it anyway"
            )
    return value


def as_parameters(t: object, *, extrapolate: bool) -> tuple[np.ndarray, bool]:
    """Parameter values as a 1-D float array, and whether the input was a scalar."""
    try:
        arr = np.asarray(t, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"t must be a number or a 1-D array of numbers, got {t!r}") from None
    if arr.ndim > 1:
        raise ValueError(f"t must be a number or a 1-D array, got shape {arr.shape}")
    scalar = arr.ndim == 0
    arr = np.atleast_1d(arr)
    if arr.size:
        # min and max propagate NaN and expose ±inf: two reductions check everything
        lo, hi = float(arr.min()), float(arr.max())
        if not (math.isfinite(lo) and math.isfinite(hi)):
            raise ValueError("t contains NaN or infinity")
        if not extrapolate and (lo < 0.0 or hi > 1.0):
            bad = lo if lo < 0.0 else hi
            raise ValueError(
                f"t = {bad} is outside [0, 1]; pass extrapolate=True to evaluate there"
            )
    return arr, scalar


def as_order(k: object) -> int:
    if isinstance(k, bool) or not isinstance(k, numbers.Integral) or int(k) < 0:  # type: ignore[call-overload]
        raise ValueError(f"derivative order k must be a non-negative integer, got {k!r}")
    return int(k)  # type: ignore[call-overload]


def as_point(point: object, dimension: int) -> np.ndarray:
    """One point as a (d,) float array matching the curve's dimension, all finite."""
    try:
        arr = np.array(point, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(
            f"point must be a sequence of {dimension} numbers, got {point!r}"
        ) from None
    if arr.shape != (dimension,):
        raise ValueError(f"point must have shape ({dimension},), got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"point has a non-finite coordinate: {arr.tolist()}")
    return arr
