"""The curve classes of the built-in families that have code or documentation of their own.

`curves.FAMILIES` lists every built-in family of generated/__init__.py; it takes a family's
class from here when this module defines one under the class name generated/ gives, and
otherwise makes a plain `Curve` subclass from the generated module alone. So a family needs a
class here only for what no table gives: an evaluator its paper describes (000's Prop. 8, below)
or the documentation of a public class. Nothing else in the runtime names a family.

This module imports only modules that do not read `curves.FAMILIES` (that would import this
module half-way through: an import cycle).
"""

from __future__ import annotations

from fractions import Fraction
from typing import cast

import numpy as np

from . import _validate as val
from ._curve_base import Curve, Matrix, _combine_exact, _float_matrix, _tables
from ._lazy import generated
from ._validate import ParamLike
from .hazmat import kernels as alg


class SameDegreeCurve(Curve):
    r"""λ-Bézier curve of the same-degree family (000):
    :math:`p(t) = \sum_{i=0}^n V_i \, b_i^n(t; \lambda)`, :math:`\lambda \in (-2, 1]`,
    degree n ≥ 3; λ = 1 is the Bézier curve."""

    family = "same_degree"
    _data = generated("same_degree")

    def evaluate_geometric(self, t: ParamLike, *, extrapolate: bool = False) -> np.ndarray:
        """Prop. 8 of 000: n-3 de Casteljau steps down to a cubic, the cubic λ-Bernstein
        control points Q (eq. 16, from the generated cubic Bernstein matrix), then de
        Casteljau on the cubic Bézier curve. An independent second evaluator."""
        tt, scalar = val.as_parameters(t, extrapolate=extrapolate)
        m3 = np.array(_float_matrix(self._data, "bernstein", 3, 0))
        assert self.lam is not None  # a same_degree curve always has one (__init__)
        lam = float(self.lam)
        m3 = m3 + lam * _float_matrix(self._data, "bernstein", 3, 1)
        with val.overflow_allowed():  # on the scaled points; checked below where it matters
            unit = self.points / self._scale
            cubic = alg.de_casteljau_steps(unit, tt, self.degree - 3)  # (len t, 4, d)
            q = np.einsum("ij,tid->tjd", m3, cubic)
            out = alg.de_casteljau_steps(q, tt, 3)[:, 0] * self._scale
        if self._scale != 1.0 or extrapolate:
            val.finite_result(out, "p(t)")
        return out[0] if scalar else out

    def geometric_levels(self, t: Fraction | float) -> list[tuple[alg.Row, ...]]:
        """Every point of Prop. 8's construction at one t, level by level: V^0 … V^(n-3)
        (de Casteljau, eq. 14), then Q^(n-2) (eq. 16, from the generated cubic Bernstein
        matrix), Q^(n-1), Q^n and Q^(n+1) = p(t) (eq. 15). Exact for exact points, λ and t."""
        exact = self.is_exact and val.is_exact_scalar(t)
        if exact:
            t = Fraction(t)
            if not 0 <= t <= 1:
                raise ValueError(f"t = {t} is outside [0, 1] (geometric_levels evaluates there)")
            assert self._exact_points is not None and self.lam is not None  # is_exact
            rows: alg.Rows = self._exact_points
            m3: alg.Rows = _combine_exact(_tables(self._data, "bernstein")[3], Fraction(self.lam))
        else:
            tt, _ = val.as_parameters(t, extrapolate=False)
            if tt.size != 1:
                raise ValueError("geometric_levels takes a single t")
            t = float(tt[0])
            rows = tuple(tuple(float(v) for v in row) for row in self.points)
            cubic_curve = self.__class__(np.zeros((4, 2)), self.lam, check_range=False)
            m3 = tuple(tuple(float(v) for v in row) for row in cubic_curve.basis_bernstein_matrix())
        tri = alg.de_casteljau_triangle(rows, t)[: self.degree - 2]
        cubic = tri[-1]
        q = (
            # exact: Fractions throughout (exact points, λ and t)
            alg.exact_matmul(tuple(zip(*m3, strict=True)), cast(Matrix, tuple(cubic)))
            if exact
            else tuple(
                tuple(sum(m3[i][j] * cubic[i][c] for i in range(4)) for c in range(len(cubic[0])))
                for j in range(4)
            )
        )
        return [tuple(level) for level in tri] + [
            tuple(level) for level in alg.de_casteljau_triangle(q, t)
        ]


class BernsteinLikeCurve(Curve):
    r"""λ-Bézier curve of the Bernstein-like family (001):
    :math:`p(t) = \sum_{i=0}^n P_i \, b_{i,n}(t; \lambda)`, :math:`\lambda \in [-1, 1]`;
    a degree-n curve is a polynomial of degree n + 2, and λ = 0 is the Bézier curve."""

    family = "bernstein_like"
    _data = generated("bernstein_like")
