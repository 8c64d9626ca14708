"""A polynomial B-spline within a tolerance of a surface that has no exact B-spline form: a
surface of a mixed algebraic-trigonometric (or -hyperbolic) family, whose basis has no
rational Bézier form (t is not a rational function of tan(t/2)).

The spline is the piecewise bicubic Hermite interpolant on a uniform grid of cells of the
families' own (u, v): on every cell it matches S, S_u, S_v and S_uv at the four corners (the
surface's own derivatives, not differences), so neighbouring cells share their boundary
curves and cross derivatives and the whole is C1. Each cell's Bézier net follows from the
corner data (P_1 = S + h S_u / 3 and so on), and the nets side by side are the poles of a
B-spline of degree 3 with every interior knot of multiplicity 3, whose parameters are the
families' t themselves (knots from the domain's ends), so the spline at (u, v) approximates
S(u, v).

The deviation is measured, not proved: the spline is compared with the surface at 5 x 5
points inside every cell (its corners are exact), and the grid doubles in both directions
until that maximum is within the tolerance. Hermite interpolation errs by O(h^4) times the
fourth derivatives, so the samples inside each cell see the error's shape; the measured
maximum is reported (`deviation`) with the samples it was taken on.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.lib.stride_tricks import sliding_window_view

from . import _validate as val
from .surfaces import Surface

MAX_CELLS = 256  # per direction: 3 * 256 + 1 poles each way at most (about 1e-11 here)
CHECKS = 5  # samples per cell and direction for the measured deviation


@dataclass(frozen=True)
class HermiteSpline:
    """A bicubic B-spline: poles (3 N_u + 1, 3 N_v + 1, d), the knot values in the families'
    own u and v (each interior knot of multiplicity 3, the ends of multiplicity 4), and the
    largest deviation from the surface measured on `samples` points per cell and direction."""

    poles: np.ndarray
    knots_u: np.ndarray
    knots_v: np.ndarray
    deviation: float
    samples: int

    @property
    def cells(self) -> tuple[int, int]:
        return len(self.knots_u) - 1, len(self.knots_v) - 1

    def evaluate(self, u: float, v: float) -> np.ndarray:
        """The spline at one (u, v) of the domain (each cell's Bézier net by de Casteljau)."""
        pu, su = _cell(self.knots_u, float(u))
        pv, sv = _cell(self.knots_v, float(v))
        net = self.poles[3 * pu : 3 * pu + 4, 3 * pv : 3 * pv + 4]
        return np.asarray(_bernstein3(su) @ np.tensordot(net, _bernstein3(sv), axes=([1], [0])))


def _cell(knots: np.ndarray, x: float) -> tuple[int, float]:
    k = int(np.clip(np.searchsorted(knots, x, side="right") - 1, 0, len(knots) - 2))
    return k, (x - knots[k]) / (knots[k + 1] - knots[k])


def _bernstein3(s: Any) -> np.ndarray:
    s = np.asarray(s, dtype=float)
    r = 1 - s
    return np.stack([r**3, 3 * r * r * s, 3 * r * s * s, s**3], axis=-1)


def _offsets(nodes: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For Bézier index r = 0..3N along one direction: its grid node and its step from it
    (r = 3i: node i; 3i + 1: node i, + h_i / 3; 3i + 2: node i + 1, - h_i / 3)."""
    h = np.diff(nodes)
    n = len(h)
    r = np.arange(3 * n + 1)
    node = (r + 1) // 3
    step = np.zeros(3 * n + 1)
    step[1::3] = h / 3
    step[2::3] = -h / 3
    return node, step


def _poles(surf: Surface, us: np.ndarray, vs: np.ndarray) -> np.ndarray:
    """The bicubic Hermite interpolant's Bézier nets side by side, (3N + 1, 3M + 1, d): the
    point at (r, c) is S + a S_u + b S_v + a b S_uv at its node, a and b its steps."""
    (iu, a), (iv, b) = _offsets(us), _offsets(vs)
    out = np.zeros((len(iu), len(iv), surf.dimension))
    for du in (0, 1):
        for dv in (0, 1):
            values = np.asarray(surf.evaluate_grid(us, vs, du, dv))[np.ix_(iu, iv)]
            out += (a[:, None, None] ** du) * (b[None, :, None] ** dv) * values
    return out


def hermite_bspline(surf: Surface, tolerance: float) -> HermiteSpline:
    """The bicubic Hermite B-spline of `surf` over its domain, its grid doubled until the
    deviation measured inside every cell is within `tolerance` (see the module's doc)."""
    if not isinstance(surf, Surface):
        raise TypeError(f"surf must be a lambda_bezier surface, got {type(surf).__name__}")
    tol = val.tolerance(tolerance, "tolerance")
    if tol <= 0:
        raise ValueError("tolerance must be > 0: the spline approximates the surface")
    (u0, u1) = getattr(surf, "domain_u", (0.0, 1.0))
    (v0, v1) = getattr(surf, "domain_v", (0.0, 1.0))
    inner = (np.arange(CHECKS) + 0.5) / CHECKS
    cells = 4
    while True:
        us, vs = np.linspace(u0, u1, cells + 1), np.linspace(v0, v1, cells + 1)
        poles = _poles(surf, us, vs)
        su = (us[:-1, None] + np.diff(us)[:, None] * inner).ravel()
        sv = (vs[:-1, None] + np.diff(vs)[:, None] * inner).ravel()
        want = np.asarray(surf.evaluate_grid(su, sv))
        basis = _bernstein3(inner)  # (CHECKS, 4), the same in every cell
        nets = sliding_window_view(poles, (4, 4), axis=(0, 1))[::3, ::3]  # (N, N, d, 4, 4)
        got = np.einsum("pk,ijdkl,ql->ipjqd", basis, nets, basis, optimize=True)
        got = got.reshape(cells * CHECKS, cells * CHECKS, -1)
        deviation = float(np.linalg.norm(got - want, axis=-1).max())
        if not math.isfinite(deviation):
            raise ValueError("the surface's values are not finite on its domain")
        if deviation <= tol:
            return HermiteSpline(poles, us, vs, deviation, CHECKS)
        if cells >= MAX_CELLS:
            raise ValueError(
                f"tolerance {tol}: {cells} x {cells} bicubic cells still deviate by "
                f"{deviation:.3g}; choose a larger tolerance"
            )
        cells *= 2


def occt_bspline(spline: HermiteSpline) -> Any:
    """The spline as an OCCT Geom_BSplineSurface (3D; 2D poles at z = 0)."""
    from OCP.collections import Array1_double, Array1_int, Array2_gp_Pnt
    from OCP.Geom import Geom_BSplineSurface
    from OCP.gp import gp_Pnt

    rows, cols, dim = spline.poles.shape
    if dim not in (2, 3):
        raise ValueError(f"OCCT surfaces live in 3D: this surface has dimension {dim}")
    poles = Array2_gp_Pnt(1, rows, 1, cols)
    for i in range(rows):
        for j in range(cols):
            x, y, *z = (float(c) for c in spline.poles[i, j])
            poles.SetValue(i + 1, j + 1, gp_Pnt(x, y, z[0] if z else 0.0))

    def knots(values: np.ndarray) -> tuple[Any, Any]:
        ks, ms = Array1_double(1, len(values)), Array1_int(1, len(values))
        for k, x in enumerate(values, start=1):
            ks.SetValue(k, float(x))
            ms.SetValue(k, 4 if k in (1, len(values)) else 3)
        return ks, ms

    (uk, um), (vk, vm) = knots(spline.knots_u), knots(spline.knots_v)
    return Geom_BSplineSurface(poles, uk, vk, um, vm, 3, 3)
