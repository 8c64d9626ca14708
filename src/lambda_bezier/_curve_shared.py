"""What every curve class shares beyond its evaluation (`ControlPointCurve`, the base of the
polynomial, rational, atom and C-Bézier curves): degree and dimension from the control
points, curvature and torsion from `derivative`. The geometry of curves on a domain of their
own parameter is _domain_geometry's.

The mixin names, as a Protocol on ``self``, what it reads of the curve, so one method serves
every class that mixes it in (the mixin pattern of mypy's documentation).
"""

from __future__ import annotations

from typing import Protocol

import numpy as np

from . import _validate as val
from ._validate import ParamLike


class _Differentiable(Protocol):
    @property
    def dimension(self) -> int: ...

    def derivative(self, t: ParamLike, k: int = 1, *, extrapolate: bool = False) -> np.ndarray: ...

    def _curvature(self, t: ParamLike, extrapolate: bool = False) -> np.ndarray: ...

    def _speed_floor(self, t: ParamLike, extrapolate: bool) -> tuple[np.ndarray, float]: ...


# c in the rounding bound c (n + 1) eps Σ |b_i'(t)| |P_i| of a computed C'(t) (b_i' as each
# class evaluates it: over its atoms for atom and C-Bézier curves). At stops of random cubics
# (P0 = P1 or P2 = P3, 50 each) of every class the computed |C'| measured at most 0.66
# (n + 1) eps Σ |b_i'| |P_i| (rational), 0.44 (Bézier), 0.16 (trig atoms): 32 leaves a margin
# of ~50, and a regular turn, |C'| above ~1e-13 of its points' size, keeps its curvature
ROUNDING_FACTOR = 32.0


def point_sizes(points: np.ndarray, s: float) -> np.ndarray:
    """An upper bound of each |P_i| / s that does not overflow where |P_i|² would:
    sqrt(d) times the largest coordinate."""
    sizes: np.ndarray = np.abs(points / s).max(axis=-1) * np.sqrt(points.shape[-1])
    return sizes


def speed_floor(basis_derivative: np.ndarray, points: np.ndarray) -> tuple[np.ndarray, float]:
    """(the rounding bound c (n + 1) eps Σ_i |b_i'(t)| |P_i| of a computed C'(t), per row of
    `basis_derivative` ((m, n+1) values b_i'(t)), in units of s; s): s is the power of two
    near the points' size, so the bound neither overflows nor underflows. A row whose b_i'
    are not finite (far outside the domain) gives a NaN bound: undefined there."""
    s = val.power_of_two_scale(points)
    eps = np.finfo(float).eps
    with np.errstate(over="ignore", invalid="ignore"):
        total = np.abs(basis_derivative) @ point_sizes(points, s)
    bound: np.ndarray = ROUNDING_FACTOR * points.shape[0] * eps * total
    return bound, s


def check_curvature_dimension(dimension: int) -> None:
    """A ValueError unless the curve is planar or spatial (curvature is defined there)."""
    if dimension not in (2, 3):
        raise ValueError(
            f"curvature is defined here for planar and space curves (dimension 2 or 3), "
            f"this curve has dimension {dimension}"
        )


class ControlPointCurve:
    """degree and dimension from the control points `points` ((n + 1, d)), and curvature,
    _curvature and torsion from `derivative`."""

    points: np.ndarray

    @property
    def degree(self) -> int:
        """The degree n (the curve has n + 1 control points)."""
        return int(self.points.shape[0]) - 1

    @property
    def dimension(self) -> int:
        """The number d of coordinates of a point."""
        return int(self.points.shape[1])

    @property
    def domain(self) -> tuple[float, float]:
        """The parameter interval: (0.0, 1.0) for a curve in Bézier form (polynomial or
        rational). A trigonometric or C-Bézier family's curve has its own, e.g. (0, pi/2)."""
        return (0.0, 1.0)

    def curvature(
        self: _Differentiable, t: ParamLike, *, extrapolate: bool = False
    ) -> np.ndarray | float:
        """Signed curvature in 2D, unsigned in 3D; a ValueError naming t where the first
        derivative is 0 within its rounding (undefined there: a cusp, or a curve that stops)."""
        kappa = val.defined_curvature(self._curvature(t, extrapolate), t)
        return kappa[()] if np.ndim(kappa) == 0 else kappa

    def _curvature(self: _Differentiable, t: ParamLike, extrapolate: bool = False) -> np.ndarray:
        """The curvature as an array, NaN where the first derivative is 0 within the rounding
        of its evaluation (`_speed_floor`; for plots and joint reports)."""
        from .hazmat import rational_kernels as rk

        check_curvature_dimension(self.dimension)
        d1 = self.derivative(t, 1, extrapolate=extrapolate)
        d2 = self.derivative(t, 2, extrapolate=extrapolate)
        floor, s = self._speed_floor(t, extrapolate)
        kappa = rk.curvature_from_derivatives(d1, d2)
        out: np.ndarray = np.where(val.stopped(d1, floor, s), np.nan, kappa)
        return out

    def _basis_derivative(self, t: ParamLike, extrapolate: bool) -> tuple[np.ndarray, np.ndarray]:
        """(b_i'(t), (m, n+1) for t's m values, and the points (n+1, d) they weigh) for the
        rounding bound of C'(t); each class that uses `_speed_floor` supplies it."""
        raise NotImplementedError

    def _speed_floor(self, t: ParamLike, extrapolate: bool) -> tuple[np.ndarray, float]:
        """The rounding bound of the computed |C'(t)| (one per t) in units of s, and s."""
        b1, points = self._basis_derivative(t, extrapolate)
        return speed_floor(np.atleast_2d(b1), points)

    def torsion(
        self: _Differentiable, t: ParamLike, *, extrapolate: bool = False
    ) -> np.ndarray | float:
        """Signed torsion of a 3D curve; ValueError where undefined (2D, or p' x p'' = 0)."""
        from .geometry import torsion

        return torsion(self, t, extrapolate=extrapolate)  # type: ignore[arg-type]
