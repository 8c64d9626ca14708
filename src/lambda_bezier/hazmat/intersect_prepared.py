"""A classical Bézier curve as the intersection solvers use it (intersect, and the careful
path's exact arithmetic): float control points, their exact values as integers over one
denominator, and the first two hodographs, built on first use."""

from __future__ import annotations

import functools
import math
from collections.abc import Sequence
from fractions import Fraction

import numpy as np

from . import forms
from . import kernels as alg

NORMAL_EXPONENT = 128  # pairs whose largest coordinate is beyond 2^±this are scaled near 1

_SMALL = 64  # control point arrays up to this many coordinates: _extent over Python lists


class Prepared:
    """A classical Bézier curve as the solvers use it: float and exact control points and
    the first two hodographs of each."""

    def __init__(self, points: np.ndarray, rows: tuple[tuple[Fraction, ...], ...] | None) -> None:
        self.pts = np.ascontiguousarray(points, dtype=float)
        self._given_rows = rows
        self.degree = self.pts.shape[0] - 1
        self.dim = self.pts.shape[1]
        # the largest |coordinate|'s binary exponent: intersect.normalised brings a pair
        # outside 2^±128 near 1 (its tests multiply four coordinates: 1e-100 underflowed)
        flat = self.pts.ravel().tolist() if self.pts.size <= _SMALL else None
        big = max(max(flat), -min(flat)) if flat else float(np.abs(self.pts).max(initial=0.0))
        self.exponent = math.frexp(big)[1] if big else 0
        if rows is None:  # floats given: set here, not read through cached_property's lock
            self.__dict__["floats_exact"] = True

    def scaled(self, shift: int) -> Prepared:
        """The same curve divided by 2^shift, exactly (its rows as Fractions when given)."""
        rows = self._given_rows
        if rows is not None:
            factor = Fraction(2) ** -shift
            rows = tuple(tuple(Fraction(x) * factor for x in row) for row in rows)
            # rounded from the exact rows: the floats of exact points near 2^-1074 are
            # subnormal (a few bits, or 0), and scaling them up would keep only those bits
            return Prepared(np.array([[float(x) for x in row] for row in rows]), rows)
        return Prepared(np.ldexp(self.pts, -shift), rows)

    @functools.cached_property
    def _extent(self) -> tuple[float, float]:
        """(largest extent of the control points along an axis, largest |coordinate|). On a
        few points Python's min and max over lists cost a fraction of numpy's per-call cost
        (issue #29: these are read for every pair intersect_many or the careful path takes);
        the same float operations, so the same values."""
        if self.pts.size <= _SMALL:
            columns = list(zip(*self.pts.tolist(), strict=True))
            return (
                max(max(c) - min(c) for c in columns),
                max(max(max(c), -min(c)) for c in columns),
            )
        return float(np.ptp(self.pts, axis=0).max()), float(np.abs(self.pts).max())

    @property
    def _span(self) -> float:
        return self._extent[0]

    @property
    def is_point(self) -> bool:
        """Every t gives the same point."""
        return self._span == 0.0

    @functools.cached_property
    def scale(self) -> float:
        """The control points' extent or largest coordinate, whichever is larger."""
        return float(max(self._span, self._extent[1], 1e-300))

    @functools.cached_property
    def _integer_rows(self) -> list[tuple[list[list[int]], int]]:
        """Exact values as integer numerators over one denominator per curve: p, p', p''.
        Each float or Fraction is an exact ratio of integers (as_integer_ratio: no Fraction
        objects, which cost most of this setup when built for every float). Built on first
        use: the certified fast path (intersect_certify) needs none of it."""
        source: Sequence[Sequence[Fraction | int | float]] = (
            self._given_rows if self._given_rows is not None else self.pts.tolist()
        )
        ratios = [[_ratio(v) for v in row] for row in source]
        den = math.lcm(*(d for row in ratios for _, d in row))
        ints = [[n * (den // d) for n, d in row] for row in ratios]
        h1 = _integer_hodograph(ints)
        h2 = _integer_hodograph(h1)
        return [(ints, den), (h1, den), (h2, den)]

    @functools.cached_property
    def h1(self) -> np.ndarray:
        ints, den = self._integer_rows[1]
        return np.array([[x / den for x in row] for row in ints])  # int / int rounds once

    @functools.cached_property
    def h2(self) -> np.ndarray:
        ints, den = self._integer_rows[2]
        return np.array([[x / den for x in row] for row in ints])

    @functools.cached_property
    def floats_exact(self) -> bool:
        """The float control points are the curve exactly (floats given, or Fractions that
        are all doubles): the fast path's float arithmetic then sees the true curve."""
        if self._given_rows is None:
            return True
        return all(
            Fraction(x) == v
            for row, given in zip(self.pts.tolist(), self._given_rows, strict=True)
            for x, v in zip(row, given, strict=True)
        )

    def exact_row(self, k: int) -> Sequence[Fraction | int | float]:
        """Control point k exactly: the given Fractions, or the floats (exact as they are)."""
        if self._given_rows is not None:
            return self._given_rows[k]
        row: list[float] = self.pts[k].tolist()
        return row

    @functools.cached_property
    def size(self) -> float:
        """The size of the curve itself (its points' extent and distance from the origin,
        from 129 samples), which tolerances on distances to it are relative to."""
        samples = alg.de_casteljau_steps(self.pts, np.linspace(0.0, 1.0, 129), self.degree)[:, 0]
        return float(max(np.ptp(samples, axis=0).max(), np.abs(samples).max(), 1e-300))

    def at(self, s: float, which: int = 0) -> np.ndarray:
        work = (self.pts, self.h1, self.h2)[which]
        while work.shape[0] > 1:
            work = work[:-1] + s * (work[1:] - work[:-1])
        point: np.ndarray = work[0]
        return point

    def at_with_tangent(self, s: float) -> tuple[np.ndarray, np.ndarray]:
        """p(s) and p'(s) from one de Casteljau pass (p' = n (b_1 - b_0) of its last level)."""
        work = self.pts
        if work.shape[0] == 1:
            return work[0], np.zeros(self.dim)
        while work.shape[0] > 2:
            work = work[:-1] + s * (work[1:] - work[:-1])
        a, b = work[0], work[1]
        return a + s * (b - a), self.degree * (b - a)

    def normal_offset(self, point: np.ndarray, s: float) -> float:
        """|point − p(s)| without its part along p'(s): how far point is off the curve near
        p(s), blind to where along the curve it sits (another curve's parameter can run
        ahead of this one's by far more than the curves are apart)."""
        at, tangent = self.at_with_tangent(s)
        r = point - at
        size = float(tangent @ tangent)
        if size > 0.0:
            r = r - (float(r @ tangent) / size) * tangent
        return float(np.linalg.norm(r))

    def exact_at(self, s: float, which: int = 0) -> tuple[list[int], int]:
        """p(s) (which = 0), p'(s) or p''(s) exactly, for a float s: integer numerators and
        one denominator. de Casteljau on integers (control points over their common
        denominator, s = m / 2^e): Python's int arithmetic is exact and much faster than
        Fractions, and int / int rounds correctly when a float is finally wanted."""
        ints, den = self._integer_rows[which]
        m, power_of_two = float(s).as_integer_ratio()
        work = ints
        for _ in range(len(ints) - 1):  # (1 - s) a + s b, scaled by 2^e
            work = [
                [(power_of_two - m) * a + m * b for a, b in zip(p, q, strict=True)]
                for p, q in zip(work[:-1], work[1:], strict=True)
            ]
        return work[0], den * power_of_two ** (len(ints) - 1)


def _exact_difference(a: tuple[list[int], int], b: tuple[list[int], int]) -> np.ndarray:
    """a - b for exact values (numerators, denominator), correctly rounded to floats."""
    (na, da), (nb, db) = a, b
    return np.array([(x * db - y * da) / (da * db) for x, y in zip(na, nb, strict=True)])


def _integer_point(point: Sequence[Fraction | int | float]) -> tuple[list[int], int]:
    ratios = [_ratio(v) for v in point]
    den = math.lcm(*(d for _, d in ratios))
    return [n * (den // d) for n, d in ratios], den


def _ratio(v: Fraction | int | float) -> tuple[int, int]:
    """(numerator, denominator) of an int, float or Fraction, exactly."""
    if isinstance(v, Fraction):
        return v.numerator, v.denominator
    if isinstance(v, int):
        return v, 1
    return float(v).as_integer_ratio()


@functools.cache
def _hodograph_weights(degree: int) -> tuple[tuple[tuple[int, int], ...], ...]:
    """The hodograph matrix's nonzero entries, row by row: (column, integer weight)."""
    return tuple(
        tuple((k, int(w)) for k, w in enumerate(row) if w) for row in forms.hodograph_matrix(degree)
    )


def _integer_hodograph(ints: list[list[int]]) -> list[list[int]]:
    """The hodograph's numerators (same denominator), from the hodograph matrix, whose
    entries are integers (n times 0 or ±1)."""
    return [
        [sum(w * ints[k][c] for k, w in row) for c in range(len(ints[0]))]
        for row in _hodograph_weights(len(ints) - 1)
    ]
