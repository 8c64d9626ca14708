"""Exact power <-> Bernstein conversion and evaluation of a polynomial in several variables
(dense arrays of Fractions): the two operations box_bernstein's branch and bound and
box_convex's floor both build on (a module of their own, so that neither imports the other
both ways).
"""

from __future__ import annotations

from fractions import Fraction
from math import comb

import numpy as np

Box = list[tuple[Fraction, Fraction]]


def _axis_matrix(degree: int, lo: Fraction, hi: Fraction) -> np.ndarray:
    """Power coefficients in x -> Bernstein coefficients on [lo, hi] (x = lo + (hi - lo) u)."""
    h = hi - lo
    shift = np.empty((degree + 1, degree + 1), dtype=object)
    to_bern = np.empty((degree + 1, degree + 1), dtype=object)
    for j in range(degree + 1):
        for k in range(degree + 1):
            shift[j, k] = Fraction(comb(k, j)) * lo ** (k - j) * h**j if k >= j else Fraction(0)
            to_bern[k, j] = Fraction(comb(k, j), comb(degree, j)) if j <= k else Fraction(0)
    out: np.ndarray = to_bern.dot(shift)
    return out


def bernstein(power: np.ndarray, box: Box) -> np.ndarray:
    """The tensor-product Bernstein coefficients of a polynomial over a box."""
    out = power
    for axis, (lo, hi) in enumerate(box):
        mat = _axis_matrix(power.shape[axis] - 1, lo, hi)
        out = np.moveaxis(np.tensordot(mat, out, axes=([1], [axis])), 0, axis)
    return out


def value(power: np.ndarray, point: tuple[Fraction, ...]) -> Fraction:
    """The polynomial at an exact point (Horner along each axis, the last first)."""
    out: object = power
    for x in reversed(point):
        arr = np.asarray(out, dtype=object)
        acc = arr[..., -1]
        for k in range(arr.shape[-1] - 2, -1, -1):
            acc = acc * x + arr[..., k]
        out = acc
    return Fraction(out.item() if isinstance(out, np.ndarray) else out)  # type: ignore[arg-type]


def float_value(power: np.ndarray, point: tuple[float, ...] | np.ndarray) -> float:
    """`value` in floats (a screen before the exact evaluation, and the float Newton steps)."""
    out = power
    for x in reversed(point):
        acc = out[..., -1]
        for k in range(out.shape[-1] - 2, -1, -1):
            acc = acc * x + out[..., k]
        out = acc
    return float(out)
