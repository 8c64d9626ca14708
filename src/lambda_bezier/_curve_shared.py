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

    def curvature(
        self: _Differentiable, t: ParamLike, *, extrapolate: bool = False
    ) -> np.ndarray | float:
        """Signed curvature in 2D, unsigned in 3D; a ValueError naming t where the first
        derivative is 0 (undefined there: a cusp, or a curve that stops)."""
        kappa = val.defined_curvature(self._curvature(t, extrapolate), t)
        return kappa[()] if np.ndim(kappa) == 0 else kappa

    def _curvature(self: _Differentiable, t: ParamLike, extrapolate: bool = False) -> np.ndarray:
        """The curvature as an array, NaN where the first derivative is 0 (for plots and
        joint reports)."""
        from .hazmat import rational_kernels as rk

        check_curvature_dimension(self.dimension)
        d1 = self.derivative(t, 1, extrapolate=extrapolate)
        d2 = self.derivative(t, 2, extrapolate=extrapolate)
        return rk.curvature_from_derivatives(d1, d2)

    def torsion(
        self: _Differentiable, t: ParamLike, *, extrapolate: bool = False
    ) -> np.ndarray | float:
        """Signed torsion of a 3D curve; ValueError where undefined (2D, or p' x p'' = 0)."""
        from .geometry import torsion

        return torsion(self, t, extrapolate=extrapolate)  # type: ignore[arg-type]
