"""The public boundary's input checks: one place that every entry point goes through.

Each check names the argument and the problem in a ValueError (never a traceback from deep in
numpy, never a silent wrong number): the type (numbers only: booleans, text and complex values
are refused rather than coerced), the shape, finiteness, and magnitude (an int or a Fraction
too large for a float is refused by name instead of raising OverflowError later). A new public
function gets all of this by calling `real_number`, `real_array`, `as_points`, `as_parameters`,
`flag`, `integer`, `choice` or `tolerance` on its arguments.
"""

from __future__ import annotations

import math
import numbers
import sys
from collections.abc import Sequence
from decimal import Decimal
from fractions import Fraction
from typing import TYPE_CHECKING, TypeGuard

import numpy as np
import numpy.typing as npt

if TYPE_CHECKING:
    from ._lazy import TableSource

ExactRows = tuple[tuple[Fraction, ...], ...]
# What the public entry points accept (each is checked here): numbers and arrays of them, the
# exact ones (ints, Fractions) kept exact where a function offers exact results.
ParamLike = npt.ArrayLike | Fraction | Sequence[Fraction | float]
PointsLike = npt.ArrayLike | Sequence[Sequence[Fraction | float]]

FLOAT_MAX = sys.float_info.max


def is_exact_scalar(x: object) -> TypeGuard[numbers.Rational]:
    # np.integer counts: numpy registers it as a numbers.Integral
    return isinstance(x, numbers.Rational | np.integer) and not isinstance(x, bool | np.bool_)


def describe(x: object) -> str:
    """repr(x), shortened when it is huge (a 400-digit integer is summarised, not printed)."""
    text = str(x) if isinstance(x, numbers.Number) and not isinstance(x, bool) else repr(x)
    if len(text) <= 60:
        return text
    return f"{text[:24]}…{text[-8:]} ({len(text)} characters)"


def to_float(q: Fraction, name: str) -> float:
    """An exact value as a float, or a ValueError naming `name` when it is beyond the range."""
    try:
        return float(q)
    except OverflowError:
        raise ValueError(
            f"{name} = {describe(q)} is too large for a float (magnitude above {FLOAT_MAX:.4g})"
        ) from None


def real_number(
    x: object, name: str, *, keep_exact: bool = True, float_range: bool = True
) -> Fraction | float:
    """One real number: a Fraction for exact input (int, Fraction, numpy integer) when
    `keep_exact`, otherwise a finite float. Booleans, text, complex and non-numbers are refused;
    with `float_range` an exact value must also fit in a float."""
    if isinstance(x, bool | np.bool_):
        raise ValueError(f"{name} must be a real number, got the boolean {x!r}")
    if isinstance(x, str | bytes):
        raise ValueError(
            f"{name} must be a real number, got the text {describe(x)} (pass 0.5 or Fraction(1, 2))"
        )
    if isinstance(x, complex | np.complexfloating):
        raise ValueError(f"{name} must be a real number, got the complex number {x!r}")
    if is_exact_scalar(x):
        q = Fraction(int(x)) if isinstance(x, np.integer) else Fraction(x)
        if float_range or not keep_exact:
            value = to_float(q, name)
        return q if keep_exact else value
    if isinstance(x, numbers.Real | np.floating | Decimal):
        value = float(x)
        if not math.isfinite(value):
            if isinstance(x, Decimal) and x.is_finite():
                raise ValueError(f"{name} = {x} is too large for a float")
            raise ValueError(f"{name} must be finite, got {value}")
        return value
    raise ValueError(f"{name} must be a real number, got {describe(x)} ({type(x).__name__})")


def real_array(x: object, name: str) -> np.ndarray:
    """`x` as a float array of any shape (no copy for a float64 ndarray). Text, booleans,
    complex values, ragged nesting and non-numbers are refused by name; exact values beyond
    the float range too. NaN/inf pass: finiteness is the caller's check (it knows the index
    to report)."""
    if isinstance(x, str | bytes):
        raise ValueError(f"{name} must be numbers, got the text {describe(x)}")
    if isinstance(x, np.ndarray):
        arr = x
    else:
        try:
            arr = np.asarray(x)
        except (ValueError, TypeError) as exc:
            raise ValueError(
                f"{name} must be a regular array of numbers (equal-length rows): {exc}"
            ) from None
    kind = arr.dtype.kind
    if kind in "iuf" and _bools_inside(x):  # numpy casts [True, 2] to [1, 2] silently
        raise ValueError(f"{name} must be numbers, got booleans")
    if kind == "f":
        return arr.astype(float, copy=False)
    if kind in "iu":
        return arr.astype(float)
    if kind == "c":
        raise ValueError(f"{name} must be real numbers, got complex values (dtype {arr.dtype})")
    if kind == "b":
        raise ValueError(f"{name} must be numbers, got booleans")
    if kind in "USa":
        raise ValueError(f"{name} must be numbers, got text (dtype {arr.dtype})")
    if kind == "O":
        out = np.empty(arr.shape, dtype=float)
        flat = out.reshape(-1)
        for i, v in enumerate(arr.flat):
            index = tuple(int(j) for j in np.unravel_index(i, arr.shape))
            where = name if arr.ndim == 0 else f"{name} at index {index}"
            flat[i] = real_number(v, where, keep_exact=False)
        return out
    raise ValueError(f"{name} must be numbers, got an array of dtype {arr.dtype}")


def _bools_inside(x: object, depth: int = 0) -> bool:
    """Whether a (nested) list or tuple holds a boolean, at C speed per level."""
    if not isinstance(x, list | tuple) or depth > 4:
        return False
    types = set(map(type, x))
    if bool in types or np.bool_ in types:
        return True
    if list in types or tuple in types:
        return any(_bools_inside(v, depth + 1) for v in x)
    return False


def flag(x: object, name: str) -> bool:
    """A True/False option (a string such as "no" would otherwise read as True)."""
    if not isinstance(x, bool | np.bool_):
        raise ValueError(f"{name} must be True or False, got {describe(x)}")
    return bool(x)


def integer(x: object, name: str) -> int:
    if isinstance(x, bool | np.bool_) or not isinstance(x, numbers.Integral | np.integer):
        raise ValueError(f"{name} must be an integer, got {describe(x)}")
    return int(x)


def choice(x: object, name: str, choices: Sequence[object]) -> str:
    """One of the names in `choices` (a list, unhashable values included, gets the message)."""
    if isinstance(x, str) and x in choices:
        return x
    raise ValueError(f"unknown {name} {describe(x)}: choose one of {', '.join(map(repr, choices))}")


def tolerance(tol: object, name: str = "tol") -> float:
    value = float(real_number(tol, name, keep_exact=False))
    if value < 0:
        raise ValueError(f"{name} must be >= 0, got {tol}")
    return value


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
    elif isinstance(points, str | bytes):
        return None
    else:
        try:
            rows = [list(r) for r in points]  # type: ignore[attr-defined]
        except TypeError:
            return None
    try:
        if not all(is_exact_scalar(v) for row in rows for v in row):
            return None
    except TypeError:  # a row that is not a sequence, or a deeper nesting (a batch)
        return None
    return tuple(
        tuple(Fraction(int(v)) if isinstance(v, np.integer) else Fraction(v) for v in row)
        for row in rows
    )


def check_point_shape(shape: tuple[int, ...], *, family: str, degrees: tuple[int, ...]) -> None:
    """(n+1, d) with d >= 1 and n in `degrees`."""
    if len(shape) != 2 or shape[1] < 1:
        raise ValueError(
            f"control points must have shape (n+1, d) with d >= 1, got shape {tuple(shape)}"
        )
    degree = shape[0] - 1
    lo, hi = degrees[0], degrees[-1]
    if degree < lo:
        raise ValueError(
            f"a {family} curve needs at least {lo + 1} control points (degree >= {lo}), "
            f"got {shape[0]}"
        )
    if degree > hi:
        raise ValueError(
            f"degree {degree} is not supported for {family}: generated data covers degrees "
            f"{lo}..{hi}"
        )


def exact_shape(rows: ExactRows, *, family: str, degrees: tuple[int, ...]) -> None:
    """check_point_shape for exact rows (any magnitude: they are never made floats)."""
    widths = {len(r) for r in rows}
    if len(widths) > 1:
        raise ValueError("control points must all have the same number of coordinates")
    check_point_shape((len(rows), widths.pop() if widths else 0), family=family, degrees=degrees)


# float arrays up to this many coordinates take as_points' short way (Python's loops over a
# list beat numpy's per-call cost there; past it numpy's reductions are cheaper)
_SMALL = 64


_F64 = np.dtype(np.float64)
# points whose Euclidean norm lies in here have their largest |coordinate| within 2^±100 (the
# norm is at most sqrt(_SMALL) = 8 times it where it is computed): an ordinary size, which
# no power-of-two scaling touches (power_of_two_scale: 2^±900; the intersection's
# normalisation: 2^±128)
_ORDINARY = (2.0**-100, 2.0**100)


def small_points(
    points: object, *, family: str, degrees: tuple[int, ...]
) -> tuple[np.ndarray, bool] | None:
    """as_points' short way, for a small float64 array (the common case; issue #29: a curve
    built to be intersected costs more than the intersection otherwise): (a read-only copy,
    whether its size is ordinary); None for any other input, or one that needs as_points'
    general way to say what is wrong. The norm (one call) is finite only when every
    coordinate is (an inf or a NaN survives it); a norm that overflows although every
    coordinate is finite takes the general way, which says which. The curve classes use
    `ordinary` for their power-of-two scale and the intersection's kernels, which would
    each read the points again."""
    if not (type(points) is np.ndarray and points.dtype is _F64 and points.ndim == 2):
        return None
    rows, width = points.shape
    if rows * width > _SMALL:
        return None
    if not (width >= 1 and degrees[0] <= rows - 1 <= degrees[-1]):
        check_point_shape(points.shape, family=family, degrees=degrees)  # raises: says why
    small = points.copy()
    norm = math.hypot(*small.ravel().tolist())
    if not math.isfinite(norm):
        return None
    small.setflags(write=False)
    return small, _ORDINARY[0] <= norm <= _ORDINARY[1]


def ordinary(points: np.ndarray) -> bool:
    """Whether finite points have an ordinary size (see _ORDINARY): False where unsure."""
    if points.size > _SMALL:
        return False
    return _ORDINARY[0] <= math.hypot(*points.ravel().tolist()) <= _ORDINARY[1]


def as_points(points: object, *, family: str, degrees: tuple[int, ...]) -> np.ndarray:
    """(n+1, d) float array (a read-only copy), d >= 1, n in `degrees`, all finite."""
    small = small_points(points, family=family, degrees=degrees)
    if small is not None:
        return small[0]
    # C order (a Fortran-ordered input stays Fortran-ordered otherwise): the compiled
    # intersection kernels take a curve's own points as they are, compiled for C order
    arr = np.array(real_array(points, "control points"), dtype=float, order="C")
    check_point_shape(arr.shape, family=family, degrees=degrees)
    bad = ~np.isfinite(arr)
    if bad.any():
        row, col = map(int, np.argwhere(bad)[0])
        raise ValueError(f"control point {row} has a non-finite coordinate ({arr[row, col]})")
    arr.setflags(write=False)
    return arr


def in_range(value: Fraction | float, family: TableSource) -> bool:
    lo, hi = family.LAMBDA_RANGE
    lo_closed, hi_closed = family.LAMBDA_CLOSED
    below = value < lo or (value == lo and not lo_closed)
    above = value > hi or (value == hi and not hi_closed)
    return not (below or above)


def as_lambda(
    lam: object, family: TableSource, *, check_range: bool, name: str = "lam"
) -> Fraction | float:
    """λ as a Fraction (exact input) or a float; inside the family's range unless told not.
    `name`: the parameter's name in the family's own words (messages)."""
    check_range = flag(check_range, "check_range")
    value = real_number(lam, name)
    if check_range and not in_range(value, family):
        raise ValueError(
            f"{name} = {describe(lam) if not isinstance(lam, float) else lam} is outside the "
            f"{family.FAMILY} range {family.LAMBDA_RANGE_TEXT}; pass check_range=False to use "
            "it anyway"
        )
    return value


def parameter_range(t: object, name: str = "t") -> tuple[np.ndarray, bool, float, float]:
    """Parameter values as a 1-D float array, whether the input was a scalar, and the array's
    least and greatest values (0.0, 0.0 when empty): checked finite, so a caller with its own
    domain needs no second pass over the array."""
    arr = real_array(t, name)
    if arr.ndim > 1:
        raise ValueError(f"{name} must be a number or a 1-D array, got shape {arr.shape}")
    scalar = arr.ndim == 0
    arr = np.atleast_1d(arr)
    lo = hi = 0.0
    if arr.size:
        # min and max propagate NaN and expose ±inf: two reductions check everything
        lo, hi = float(arr.min()), float(arr.max())
        if not (math.isfinite(lo) and math.isfinite(hi)):
            raise ValueError(f"{name} contains NaN or infinity")
    return arr, scalar, lo, hi


def as_parameters(t: object, *, extrapolate: bool, name: str = "t") -> tuple[np.ndarray, bool]:
    """Parameter values as a 1-D float array, and whether the input was a scalar."""
    extrapolate = flag(extrapolate, "extrapolate")
    arr, scalar, lo, hi = parameter_range(t, name)
    if arr.size and not extrapolate and (lo < 0.0 or hi > 1.0):
        bad = lo if lo < 0.0 else hi
        raise ValueError(
            f"{name} = {bad} is outside [0, 1]; pass extrapolate=True to evaluate there"
        )
    return arr, scalar


def as_order(k: object, name: str = "k") -> int:
    if isinstance(k, bool | np.bool_) or not isinstance(k, numbers.Integral) or int(k) < 0:
        raise ValueError(
            f"derivative order {name} must be a non-negative integer, got {describe(k)}"
        )
    return int(k)


def finite_result(out: np.ndarray, what: str) -> np.ndarray:
    """`out`, or a ValueError when finite input gave an overflow (coordinates near 1e308)."""
    if not np.isfinite(out).all():
        raise ValueError(
            f"{what} overflows the float range (magnitude above {FLOAT_MAX:.4g}) for these "
            "control points; scale them down (or use exact ints/Fractions where offered)"
        )
    return out


def defined_curvature(kappa: np.ndarray, t: object, name: str = "t") -> np.ndarray:
    """`kappa`, or a ValueError naming the first parameter where it is NaN: p' = 0 there, so
    the curvature is undefined (a cusp, or a curve that stops), never returned as NaN."""
    bad = np.isnan(kappa)
    if bad.any():
        at = np.asarray(t, dtype=object).ravel()[int(np.argmax(np.ravel(bad)))]
        raise ValueError(
            f"the curvature is undefined at {name} = {at}: the first derivative vanishes "
            "there (a cusp, or a curve that stops)"
        )
    return kappa


def stopped(d1: np.ndarray, floor: np.ndarray, s: float) -> np.ndarray:
    """Where |C'(t)| (rows of d1) is within the rounding `floor` (one per row, in units of s)
    of 0: a stop or a cusp, where curvature, torsion and the unit tangent are undefined."""
    with np.errstate(over="ignore", invalid="ignore"):
        speed = np.linalg.norm(np.asarray(d1, dtype=float) / s, axis=-1)
    out: np.ndarray = ~(speed > np.reshape(floor, np.shape(speed)))
    return out


def check_moving(d1: np.ndarray, floor: np.ndarray, s: float, t: object, what: str) -> None:
    """A ValueError naming the first t where C'(t) is 0 within its rounding (`stopped`):
    `what` is undefined there (a cusp, or a curve that stops)."""
    bad = np.atleast_1d(stopped(d1, floor, s))
    if bad.any():
        at = np.asarray(t, dtype=object).ravel()[int(np.argmax(bad.ravel()))]
        raise ValueError(
            f"{what} is undefined at t = {at}: the first derivative vanishes there (within "
            "its rounding: a cusp, or a curve that stops)"
        )


def power_of_two_scale(points: np.ndarray) -> float:
    """1.0 for ordinary coordinates; for magnitudes beyond 2^±900 the power of two that brings
    them near 1, so products with basis coefficients (up to ~1e20) neither overflow nor
    underflow. Dividing by a power of two is exact."""
    if points.size <= _SMALL:  # as in as_points: a list's max beats numpy's per-call cost
        flat = points.ravel().tolist()
        return scale_for_magnitude(max(max(flat), -min(flat)) if flat else 0.0)
    return scale_for_magnitude(float(np.abs(points).max()))


def scale_for_magnitude(big: float) -> float:
    """power_of_two_scale for a known largest magnitude."""
    if big == 0.0 or not math.isfinite(big):
        return 1.0
    exponent = math.frexp(big)[1]
    return 1.0 if -900 <= exponent <= 900 else math.ldexp(1.0, exponent - 1)


def overflow_allowed() -> np.errstate:
    """numpy's overflow warnings off for a computation whose result `finite_result` checks:
    the ValueError is the report, not a RuntimeWarning beside an inf."""
    return np.errstate(over="ignore", invalid="ignore")


def as_point(point: object, dimension: int, name: str = "point") -> np.ndarray:
    """One point as a (d,) float array matching the curve's dimension, all finite. Text,
    booleans, complex values and exact values beyond the float range are refused by name
    (real_array), as for control points: np.array(..., dtype=float) took (True, False) as
    (1, 0) and raised a bare OverflowError on an int past 1.8e308."""
    if isinstance(point, str | bytes):
        raise ValueError(f"{name} must be a sequence of {dimension} numbers, got {point!r}")
    try:
        arr = np.array(real_array(point, name), dtype=float)
    except ValueError as exc:
        if "must be a regular array" in str(exc) or "must be a real number" in str(exc):
            raise ValueError(
                f"{name} must be a sequence of {dimension} numbers, got {describe(point)}"
            ) from None
        raise
    if arr.shape != (dimension,):
        raise ValueError(f"{name} must have shape ({dimension},), got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} has a non-finite coordinate: {arr.tolist()}")
    return arr
