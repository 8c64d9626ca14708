r"""Rational Bézier curves: :math:`C(t) = \sum_i w_i P_i B_{i,n}(t) / \sum_i w_i B_{i,n}(t)`.

A rational curve is the central projection of its homogeneous form, the polynomial curve
H(t) = Σ (w_i P_i, w_i) B_{i,n}(t) one dimension up (`to_homogeneous`), and that is how it is
computed: H is a `BezierCurve` (its fast Horner evaluation, exact subdivision and elevation),
values are H's first d coordinates divided by the last, and the derivatives follow from H's by
the quotient rule (Leibniz on A = w C; see _rational_kernels). The weights must be positive:
then w(t) > 0 on [0, 1], there is no pole, every piece lies in the convex hull of its
control points, and subdividing keeps the weights positive.

Exact in, exact out: with int/Fraction points and weights, `split`, `segment`, `elevate`,
`reparameterize`, `hodograph`, `to_homogeneous` and `exact_derivative` are Fractions.

Möbius reparameterisation. The weights w_i ρ^i (ρ > 0) give the same curve with the
parameter s, where the original's is t = ρ s / ((1 − s) + ρ s) (`reparameterize`); together
with the reversal s ↦ 1 − s these are all the Möbius maps of [0, 1] onto itself. ρ =
(w_0 / w_n)^(1/n) after dividing by w_0 gives the standard form w_0 = w_n = 1 (`normalized`).

Trigonometric and hyperbolic families (the bridge to issue #30's families). On t ∈ [0, π/2],
u = tan(t/2) runs over [0, 1] and cos t = (1 − u²)/(1 + u²), sin t = 2u/(1 + u²): a basis of
trigonometric polynomials of degree m in (cos t, sin t) becomes rational functions of u of
degree 2m over the common denominator (1 + u²)^m, so the family's curve is a rational Bézier
curve of degree 2m in u whose homogeneous form is found by expanding each b_i(t(u)) (1 + u²)^m
in the Bernstein basis of degree 2m; the weights are the Bernstein coefficients of
(1 + u²)^m, which are positive. On [0, α] one takes u = tan(t/2) / tan(α/2) (then
(1 + tan²(α/2) u²)^m is the denominator). A hyperbolic family on [0, a] goes the same way
through u = tanh(t/2) / tanh(a/2), with cosh t = (1 + v²)/(1 − v²) and sinh t = 2v/(1 − v²),
v = tanh(t/2); the denominator (1 − v²)^m is positive on the interval. The family's own
parameter is then t = 2 arctan(u tan(α/2)) (or 2 artanh(u tanh(a/2))); a reparameterisation
by a Möbius map of [0, 1] (`reparameterize`) brings the result to the standard form without
changing the curve.
"""

from __future__ import annotations

import math
import sys
from fractions import Fraction
from typing import TYPE_CHECKING, NoReturn

import numpy as np
import numpy.typing as npt

from . import _validate as val
from ._curve_base import _swapped_intersect
from ._curve_shared import ROUNDING_FACTOR, ControlPointCurve, point_sizes
from ._validate import ParamLike, PointsLike
from .curves import BezierCurve, Curve
from .hazmat import intersect_kind as _kind
from .hazmat import kernels as alg
from .hazmat import rational_kernels as rk
from .hazmat.intersect_prepared import NORMAL_EXPONENT

if TYPE_CHECKING:
    from sympy import Poly

    from .geometry import ClosestPoint
    from .hazmat.intersect import Intersection

WIDE_WEIGHTS = 2.0**10  # a larger ratio of the weights is evaluated by de Casteljau
RTOL = 1e-12  # the relative accuracy arc_length and parameter_at_length aim for
ON_CURVE = 1e-10  # relative distance below which locate counts a point as on the curve
SAME_ROOT = 1e-7  # intersection parameters closer than this are one intersection
TANGENT_SINE = 1e-5  # below this sine of the angle between tangents an intersection is tangent

Rows = tuple[tuple[Fraction, ...], ...] | tuple[tuple[float, ...], ...]
WeightsLike = npt.ArrayLike | tuple[Fraction | float, ...] | list[Fraction | float]


def _not_for_rational(what: str, why: str) -> NoReturn:
    raise NotImplementedError(f"{what} is not available for a rational Bézier curve: {why}")


def _as_weights(weights: object, count: int) -> tuple[np.ndarray, tuple[Fraction, ...] | None]:
    arr = val.real_array(weights, "weights")
    if arr.ndim != 1 or arr.size != count:
        raise ValueError(
            f"weights must be one number per control point ({count}), got shape {arr.shape}"
        )
    if not np.isfinite(arr).all():
        raise ValueError(f"weights must be finite, got {arr.tolist()}")
    if not (arr > 0).all():
        i = int(np.argmax(~(arr > 0)))
        raise ValueError(
            f"weights must be positive, got weights[{i}] = {arr[i]} (a zero or negative weight "
            "can put a pole in the curve and voids the convex hull property)"
        )
    exact = val.exact_rows([weights])
    arr = np.array(arr, dtype=float)
    arr.setflags(write=False)
    return arr, None if exact is None else exact[0]


def _exact_scalar(t: object, name: str) -> Fraction:
    if not val.is_exact_scalar(t):
        raise ValueError(f"{name} must be an int or a Fraction for an exact result, got {t!r}")
    return Fraction(int(t)) if isinstance(t, np.integer) else Fraction(t)


def _normalised(
    a: RationalBezierCurve, b: RationalBezierCurve
) -> tuple[RationalBezierCurve, RationalBezierCurve]:
    """a and b divided by one power of two (the same parameters) when their size is beyond
    2^±NORMAL_EXPONENT: at 2^-700 a crossing with a line was lost and the other called
    "tangent", at 2^1000 the search overflowed."""
    top = max(math.frexp(float(np.abs(c.points).max(initial=0.0)))[1] for c in (a, b))
    if -NORMAL_EXPONENT <= top <= NORMAL_EXPONENT:
        return a, b
    return a._divided(top), (a._divided(top) if b is a else b._divided(top))


class RationalBezierCurve(ControlPointCurve):
    r"""A rational Bézier curve :math:`C(t) = \sum_i w_i P_i B_{i,n}(t) / \sum_i w_i
    B_{i,n}(t)` on t ∈ [0, 1], any degree n >= 0, any dimension d >= 1, positive weights.
    All weights equal: the classical Bézier curve, exactly."""

    # Curve.intersect(this) asks this class's intersect, with s and t exchanged
    intersects_curves = True

    family = "rational_bezier"
    lam = None  # no shape parameter
    parameter_name = "lam"  # the name BezierCurve shows for its (absent) parameter

    def __init__(self, points: PointsLike, weights: WeightsLike) -> None:
        self.points = val.as_points(points, family="rational Bézier", degrees=(0, sys.maxsize))
        self._exact_points = val.exact_rows(points)
        self.weights, self._exact_weights = _as_weights(weights, self.points.shape[0])
        if self.is_exact:
            assert self._exact_points is not None and self._exact_weights is not None
            rows = tuple(
                (*(w * v for v in row), w)
                for row, w in zip(self._exact_points, self._exact_weights, strict=True)
            )
            self._homogeneous = BezierCurve(rows)
        else:
            with val.overflow_allowed():
                hom = rk.to_homogeneous(self.points, self.weights)
            self._homogeneous = BezierCurve(val.finite_result(hom, "the homogeneous points"))
        # all weights equal: the curve is the polynomial one, evaluated as such (same floats)
        self._polynomial = (
            BezierCurve(self.control_points()) if np.all(self.weights == self.weights[0]) else None
        )

    # ------------------------------------------------------------------ description
    @property
    def is_exact(self) -> bool:
        """True when the control points and the weights are all ints/Fractions."""
        return self._exact_points is not None and self._exact_weights is not None

    @property
    def polynomial_degree(self) -> int:
        _not_for_rational(
            "polynomial_degree", "C(t) is a quotient of two polynomials of degree n (`degree`)"
        )

    def __repr__(self) -> str:
        return f"RationalBezierCurve(degree={self.degree}, dimension={self.dimension})"

    def control_points(self) -> tuple[tuple[Fraction, ...], ...] | tuple[tuple[float, ...], ...]:
        """The control points as given: Fractions if exact, floats otherwise."""
        if self._exact_points is not None:
            return self._exact_points
        return tuple(tuple(float(v) for v in row) for row in self.points)

    def control_weights(self) -> tuple[Fraction, ...] | tuple[float, ...]:
        """The weights as given: Fractions if exact, floats otherwise."""
        if self._exact_weights is not None:
            return self._exact_weights
        return tuple(float(w) for w in self.weights)

    # ------------------------------------------------------------------ homogeneous form
    def to_homogeneous(self) -> BezierCurve:
        """The polynomial curve H(t) = Σ (w_i P_i, w_i) B_i(t) in dimension d + 1, whose
        projection (the first d coordinates over the last) is this curve."""
        return self._homogeneous

    @classmethod
    def from_homogeneous(cls, curve: BezierCurve | PointsLike) -> RationalBezierCurve:
        """The rational curve whose homogeneous form is `curve` (a BezierCurve or its
        control points, rows (w_i P_i, w_i)); the last coordinates must be positive."""
        hom = curve if isinstance(curve, BezierCurve) else BezierCurve(curve)
        if hom.dimension < 2:
            raise ValueError(
                "a homogeneous form needs at least 2 coordinates (the point, then the weight)"
            )
        return cls._from_rows(hom.control_points())

    @classmethod
    def _from_rows(cls, rows: Rows) -> RationalBezierCurve:
        weights: list[Fraction | float] = [r[-1] for r in rows]
        if not all(w > 0 for w in weights):
            raise ValueError(
                f"the weights (last homogeneous coordinates) must be positive, got {weights}"
            )
        points = [[v / w for v in r[:-1]] for r, w in zip(rows, weights, strict=True)]  # type: ignore[operator]
        return RationalBezierCurve(points, weights)

    @classmethod
    def from_bezier(cls, bezier: Curve) -> RationalBezierCurve:
        """The curve of any family (its exact Bézier form) with all weights 1."""
        if not isinstance(bezier, Curve):
            raise TypeError(f"bezier must be a lambda_bezier curve, got {type(bezier).__name__}")
        bez = bezier.to_bezier()
        return cls(bez.control_points(), [1] * (bez.degree + 1))

    def to_bezier(self) -> BezierCurve:
        """The classical Bézier curve with the same points, when all weights are equal (the
        curve is then polynomial); a ValueError otherwise."""
        if self._polynomial is None:
            raise ValueError(
                "this rational curve is not a polynomial curve (its weights differ): it has no "
                "classical Bézier form"
            )
        return self._polynomial

    # ------------------------------------------------------------------ evaluation
    def evaluate(self, t: ParamLike, *, extrapolate: bool = False) -> np.ndarray:
        """C(t): shape (d,) for a scalar t, (len(t), d) for an array."""
        if self._polynomial is not None:
            return self._polynomial.evaluate(t, extrapolate=extrapolate)
        coeffs = self._centred_coefficients()
        if coeffs is not None and not val.flag(extrapolate, "extrapolate"):
            # on [0, 1] w(t) >= the smallest weight > 0: no pole, and no overflow (the rows
            # are scaled to size 1, see _centred_coefficients)
            tt, scalar = val.as_parameters(t, extrapolate=False)
            h = alg.centred_horner(coeffs, tt).T  # (d+1, len(t)), coordinate-major, ours
            np.divide(h[:-1], h[-1], out=h[:-1])  # in place: no new (d, len(t)) array
            out: np.ndarray = h[:-1].T
            return out[0] if scalar else out
        if self._wide_weights and not extrapolate:  # de Casteljau: w(t) to full accuracy
            # in the form (1 - t) a + t b (rk.de_casteljau): a + t (b - a) is not relatively
            # accurate near t = 1 when the weights there are tiny (a hyperbolic curve's float
            # form, weights 1 .. 7e-17, was 3e-8 off near its end); the rows scaled by a power
            # of two, which the projection does not see
            tt, scalar = val.as_parameters(t, extrapolate=False)
            hom = self._homogeneous
            h = rk.de_casteljau(hom.points / hom._scale, tt)
            h = h[0] if scalar else h
        else:
            h = self._homogeneous.evaluate(t, extrapolate=extrapolate)
        with val.overflow_allowed(), np.errstate(divide="ignore"):
            projected = rk.project(h)
        return self._checked(projected, t, "C(t)")

    @property
    def _wide_weights(self) -> bool:
        """Whether the weights span more than WIDE_WEIGHTS: the monomial (Horner) form of w(t)
        then cancels badly near an end (a term of size max w gives a value of size min w),
        and evaluation goes by de Casteljau, whose positive combinations keep w(t)'s
        relative accuracy."""
        return float(self.weights.max()) > WIDE_WEIGHTS * float(self.weights.min())

    def _centred_coefficients(self) -> np.ndarray | None:
        """(d+1, n+1): the homogeneous form's Taylor coefficients about t = 1/2 (computed in
        Fractions from the exact or float rows, rounded once), for rows scaled by a power of
        two to size about 1 (the projection does not see a common factor); filled on first
        use. None past degree 14, where monomials lose accuracy (de Casteljau then), or
        where the weights span too many binades for the scaled rows."""
        cached: np.ndarray | None = self.__dict__.get("_centred")
        if cached is None and "_centred" not in self.__dict__:
            rows = self._homogeneous.points
            big = float(np.abs(rows).max())
            if self.degree <= 14 and not self._wide_weights:
                scale = 2.0 ** -np.frexp(big)[1]
                exact = np.array(
                    [[Fraction(float(v) * scale) for v in row] for row in rows], dtype=object
                )
                if self.is_exact:  # from the exact rows: one rounding in all
                    exact = np.array(self._homogeneous.control_points(), dtype=object) * Fraction(
                        scale
                    )
                cached = np.array(rk.bernstein_to_centred(exact).T, dtype=float, order="C")
                cached.setflags(write=False)
            self.__dict__["_centred"] = cached
        return cached

    def _checked(self, out: np.ndarray, t: ParamLike, what: str) -> np.ndarray:
        if not np.isfinite(out).all():  # w(t) = 0 can only happen outside [0, 1]
            raise ValueError(
                f"{what} is not finite at some t (a pole of the curve, where w(t) = 0 outside "
                "[0, 1], or an overflow of the float range)"
            )
        return out

    def derivative(self, t: ParamLike, k: int = 1, *, extrapolate: bool = False) -> np.ndarray:
        """The k-th derivative C^(k)(t), any k >= 0 (floats; `exact_derivative` gives
        Fractions): (d,) for a scalar t, (len(t), d) for an array."""
        order = val.as_order(k)
        if self._polynomial is not None:
            return self._polynomial.derivative(t, order, extrapolate=extrapolate)
        tt, scalar = val.as_parameters(t, extrapolate=extrapolate)
        with val.overflow_allowed(), np.errstate(divide="ignore"):
            if self._wide_weights and not extrapolate:
                h = rk.homogeneous_derivatives(self._homogeneous.points, tt, order)
            else:
                h = [
                    self._homogeneous.derivative(tt, j, extrapolate=extrapolate)
                    for j in range(order + 1)
                ]
            out = rk.quotient_derivatives(h)[order]
        out = self._checked(out, t, "the derivative" if order else "C(t)")
        return out[0] if scalar else out

    def _speed_floor(self, t: ParamLike, extrapolate: bool) -> tuple[np.ndarray, float]:
        """The rounding bound of the computed |C'(t)| per t, in units of s, and s. By the
        quotient rule C' = (A' − w' C) / w with A = Σ w_i P_i B_i: c (n+1) eps times
        Σ |B_i'(t)| |w_i| (|P_i| + |C(t)|) / |w(t)| (ControlPointCurve._speed_floor)."""
        if self._polynomial is not None:
            return self._polynomial._speed_floor(t, extrapolate)
        tt, _ = val.as_parameters(t, extrapolate=extrapolate)
        n = self.degree
        b = rk.de_casteljau(np.eye(n + 1), tt)
        b1 = rk.de_casteljau(rk.hodograph(np.eye(n + 1)), tt) if n else np.zeros_like(b)
        w = np.abs(self.weights.astype(float))
        scale = val.power_of_two_scale(self.points)
        with val.overflow_allowed(), np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            point = np.atleast_2d(self.derivative(t, 0, extrapolate=extrapolate))
            here = point_sizes(point, scale)
            sizes = point_sizes(self.points, scale)
            weigh = np.abs(b1) * w  # (m, n+1)
            top = weigh @ sizes + weigh.sum(axis=1) * here
            wt = np.abs(b @ self.weights.astype(float))
            floor: np.ndarray = ROUNDING_FACTOR * (n + 1) * np.finfo(float).eps * top / wt
        return floor, scale

    def exact_derivative(self, t: Fraction | int, k: int = 0) -> tuple[Fraction, ...]:
        """C^(k)(t) in Fractions, for an exact curve and an exact t (k = 0: the point)."""
        order = val.as_order(k)
        if not self.is_exact:
            raise ValueError("exact_derivative needs exact control points and weights")
        tq = _exact_scalar(t, "t")
        rows = np.array(self._homogeneous.control_points(), dtype=object)
        h = []
        for _ in range(order + 1):
            h.append(rk.split_at(rows, tq)[0][-1][None, :])
            rows = rk.hodograph(rows)
        if h[0][0, -1] == 0:
            raise ValueError(f"the curve has a pole at t = {tq} (w(t) = 0)")
        return tuple(rk.quotient_derivatives(h)[order][0].tolist())

    def de_casteljau(self, t: ParamLike, *, extrapolate: bool = False) -> np.ndarray:
        """C(t) by de Casteljau's algorithm on the homogeneous points (a second evaluator)."""
        if extrapolate:
            h = self._homogeneous.de_casteljau(t, extrapolate=True)
        else:  # the form (1 - t) a + t b, relatively accurate at both ends (see evaluate)
            tt, scalar = val.as_parameters(t, extrapolate=False)
            hom = self._homogeneous
            h = rk.de_casteljau(hom.points / hom._scale, tt)
            h = h[0] if scalar else h
        with val.overflow_allowed(), np.errstate(divide="ignore"):
            return self._checked(rk.project(h), t, "C(t)")

    def basis(self, t: ParamLike, *, extrapolate: bool = False) -> np.ndarray:
        """The rational basis R_i(t) = w_i B_i(t) / Σ_j w_j B_j(t): (n+1,) or (len(t), n+1)."""
        tt, scalar = val.as_parameters(t, extrapolate=extrapolate)
        bern = rk.de_casteljau(np.eye(self.degree + 1), tt) * self.weights
        with np.errstate(divide="ignore", invalid="ignore"):
            out = bern / bern.sum(axis=1, keepdims=True)
        out = self._checked(out, t, "the basis")
        return out[0] if scalar else out

    # ------------------------------------------------------------------ subdivision
    def split(self, t: Fraction | float) -> tuple[RationalBezierCurve, RationalBezierCurve]:
        """The pieces over [0, t] and [t, 1] (exact for an exact curve and t)."""
        left, right = self._homogeneous.split(t)
        return self._from_rows(left.control_points()), self._from_rows(right.control_points())

    def segment(
        self, t1: Fraction | float, t2: Fraction | float, *, extrapolate: bool = False
    ) -> RationalBezierCurve:
        """The piece between C(t1) and C(t2), 0 <= t1 < t2 <= 1, reparametrised to [0, 1]
        (with extrapolate=True any t1 < t2 where the weights of the piece stay positive)."""
        piece = self._homogeneous.segment(t1, t2, extrapolate=extrapolate)
        return self._from_rows(piece.control_points())

    def elevate(self) -> RationalBezierCurve:
        """The same curve with one degree more (the homogeneous form elevated)."""
        return self._from_rows(self._homogeneous.elevate().control_points())

    def reverse(self) -> RationalBezierCurve:
        """The same curve traversed backwards: parameter 1 − t."""
        return RationalBezierCurve(self.control_points()[::-1], self.control_weights()[::-1])

    def reparameterize(self, rho: Fraction | float) -> RationalBezierCurve:
        """The same curve with weights w_i ρ^i (ρ > 0): its parameter s corresponds to this
        curve's t = ρ s / ((1 − s) + ρ s) (the Möbius maps of [0, 1] that fix both ends).
        Exact for an exact curve and ρ."""
        value = val.real_number(rho, "rho")
        if not value > 0:
            raise ValueError(f"rho must be positive, got {rho}")
        if self.is_exact and isinstance(value, Fraction):
            weights = rk.reweight(np.array(self.control_weights(), dtype=object), value)
            return RationalBezierCurve(self.control_points(), tuple(weights.tolist()))
        with np.errstate(over="ignore"):
            try:
                weights = rk.reweight(self.weights, float(value))
            except OverflowError:
                weights = np.array([np.inf])
        if not np.isfinite(weights).all() or not (weights > 0).all():
            raise ValueError(
                f"rho = {rho}: the weights w_i rho^i leave the float range for degree {self.degree}"
            )
        return RationalBezierCurve(self.points, weights)

    def normalized(self) -> tuple[RationalBezierCurve, Fraction | float]:
        """(curve, ρ): the same curve in standard form, w_0 = w_n = 1, and the ρ of the
        reparameterisation that gives it (its s maps to this curve's t = ρ s / ((1 − s) +
        ρ s)). Exact when the curve is exact and (w_0 / w_n)^(1/n) is rational."""
        n = self.degree
        if n == 0:
            one = Fraction(1) if self.is_exact else 1.0
            return RationalBezierCurve(self.control_points(), [one]), one
        exact = self._exact_weights
        if exact is not None:
            ratio = exact[0] / exact[-1]
            num, den = _integer_root(ratio.numerator, n), _integer_root(ratio.denominator, n)
            if num and den:
                rho = Fraction(num, den)
                scaled = tuple(w / exact[0] * rho**i for i, w in enumerate(exact))
                return RationalBezierCurve(self.control_points(), scaled), rho
        # in logarithms: w_i ρ^i / w_0 stays in range where ρ^i or w_i / w_0 alone would not
        logs = np.log(self.weights)
        log_rho = (logs[0] - logs[-1]) / n
        scaled_floats = np.exp(logs - logs[0] + log_rho * np.arange(n + 1))
        scaled_floats[0] = scaled_floats[-1] = 1.0  # 1 up to rounding: make them 1
        if not np.isfinite(scaled_floats).all() or not (scaled_floats > 0).all():
            raise ValueError("normalized: the standard-form weights leave the float range")
        return RationalBezierCurve(self.points, scaled_floats), float(np.exp(log_rho))

    def hodograph(self) -> RationalBezierCurve:
        """C'(t) as a rational Bézier curve of degree 2n: C' = (A' w − A w') / w², whose
        denominator w² has positive Bernstein coefficients (exact for an exact curve)."""
        if self.degree < 1:
            raise ValueError("a degree-0 curve (a point) has no hodograph: its derivative is 0")
        rows = self._rows_array()
        num = rk.elevate(rk.derivative_numerator(rows), 1)
        den = rk.product(rows[:, -1:], rows[:, -1:])[:, 0]
        if rows.dtype == object:
            pts = [[v / w for v in row] for row, w in zip(num.tolist(), den.tolist(), strict=True)]
            return RationalBezierCurve(pts, den.tolist())
        return RationalBezierCurve(num / den[:, None], den)

    def _rows_array(self) -> np.ndarray:
        """Homogeneous rows as an object array of Fractions (exact curve) or floats."""
        if self.is_exact:
            return np.array(self._homogeneous.control_points(), dtype=object)
        return np.array(self._homogeneous.points, dtype=float)

    # ------------------------------------------------------------------ geometry
    def arc_length(self, t0: Fraction | float = 0, t1: Fraction | float = 1) -> float:
        """∫ ‖C'(t)‖ dt from t0 to t1 (0 <= t0 <= t1 <= 1), to a relative accuracy of 1e-12."""
        from . import _rational_geometry as rg

        return rg.arc_length(self, t0, t1)

    def parameter_at_length(self, s: npt.ArrayLike) -> np.ndarray | float:
        """The t at which the arc length from 0 equals s (a number or an array)."""
        from . import _rational_geometry as rg

        return rg.parameter_at_length(self, s)

    def bounding_box(self) -> tuple[np.ndarray, np.ndarray]:
        """(lo, hi): the tight axis-aligned box, from the ends and every root in [0, 1] of
        each coordinate's derivative numerator A_c' w − A_c w'."""
        from . import _rational_geometry as rg

        return rg.bounding_box(self)

    def closest_point(self, q: npt.ArrayLike) -> ClosestPoint:
        """The global nearest point to q, (d,) or a batch (m, d): `t`, `point`,
        `distance`; certified by the Bernstein form of ‖A − q w‖² − D² w² (see
        _rational_geometry)."""
        from . import _rational_geometry as rg

        return rg.closest_point(self, q)

    def locate(self, point: PointsLike) -> float | None:
        """The t with C(t) = point (within 1e-10 of the curve's size), or None when the point
        is not on the curve. A ValueError when several t give the point (a self-crossing) or
        the curve is a single point, as on the polynomial classes."""
        found = self._locate_all(point)
        if len(found) > 1:
            raise ValueError(f"the point is on the curve at several parameters: {found}")
        return found[0] if found else None

    def _locate_all(self, point: PointsLike) -> list[float]:
        """Every t with C(t) = point (within 1e-10 of the curve's size), the closest point's
        t first: [] off the curve."""
        from . import _rational_geometry as rg

        arr = val.as_point(point, self.dimension)
        if not np.ptp(self.points, axis=0).any():
            raise ValueError("the curve is a single point: every t gives it")
        found = self.closest_point(arr)
        size = max(float(np.abs(self.points).max()), float(np.ptp(self.points, axis=0).max()))
        tol = ON_CURVE * max(size, 1e-300)
        if not float(found.distance) <= tol:
            return []
        best = float(found.t)
        others = [t for t in rg.on_curve_parameters(self, arr, tol) if abs(t - best) >= 1e-9]
        return sorted([best, *others])

    def intersect(self, other: RationalBezierCurve | Curve) -> list[Intersection]:
        """Every isolated intersection with another rational or polynomial curve, as
        Intersection(s, t, kind) sorted by s: self(s) = other(t), kind "transversal" or
        "tangent". Curves sharing a stretch raise ValueError."""
        from . import _rational_geometry as rg

        if isinstance(other, Curve):
            other = RationalBezierCurve.from_bezier(other)
        if not isinstance(other, RationalBezierCurve):
            swapped = _swapped_intersect(other, self)  # a trigonometric/hyperbolic/mixed curve
            if swapped is None:
                raise TypeError(f"other must be a curve, got {type(other).__name__}")
            return swapped
        if other.dimension != self.dimension:
            raise ValueError(
                f"the curves have different dimensions ({self.dimension} and {other.dimension})"
            )
        for name, c in (("the first", self), ("the second", other)):
            if not np.ptp(c.points, axis=0).any():  # as the polynomial classes refuse it
                raise ValueError(f"{name} curve is a single point: use locate() on the other")
        p, q = _normalised(self, other)
        size = max(float(np.abs(c.points).max()) for c in (p, q))
        bound = 64 * float(np.finfo(float).eps) * max(p.degree, q.degree, 1) * size
        hits = _kind.at_ends(
            rg.intersect(p, q), p.evaluate, q.evaluate, ((0.0, 1.0), (0.0, 1.0)), bound
        )
        return _kind.one_sided(hits, p.points, q.points, size, (p.weights, q.weights), TANGENT_SINE)

    def self_intersections(self) -> list[Intersection]:
        """Every pair s < t with C(s) = C(t), as Intersection(s, t, kind), sorted by s."""
        from . import _rational_geometry as rg

        if not np.ptp(self.points, axis=0).any():
            return []  # a single point, as on the polynomial classes (it never leaves it)
        return rg.self_intersections(_normalised(self, self)[0])

    def _divided(self, shift: int) -> RationalBezierCurve:
        """The same curve, its control points divided by 2^shift (exactly), same weights."""
        if self.is_exact:
            assert self._exact_points is not None
            factor = Fraction(2) ** -shift
            exact = [[x * factor for x in row] for row in self._exact_points]
            return RationalBezierCurve(exact, self._exact_weights or self.weights)
        return RationalBezierCurve(np.ldexp(self.points, -shift), self.weights)

    def implicitize(self) -> Poly:
        """The algebraic curve f(x, y) = 0 containing this planar curve, as an exact
        sympy.Poly in x and y with coprime integer coefficients (SymPy is imported here):
        the resultant in t of X(t) − x w(t) and Y(t) − y w(t). Needs an exact curve."""
        if self.dimension != 2:
            raise ValueError(f"implicitize needs a planar curve, got dimension {self.dimension}")
        if not self.is_exact:
            raise ValueError("implicitize needs exact control points and weights")
        from .hazmat.implicit import implicitize

        rows = self._homogeneous._exact_points
        assert rows is not None  # checked above: the curve is exact
        return implicitize(rows, homogeneous=True)

    # ------------------------------------------------------------------ not applicable
    def energy(self, k: int) -> NoReturn:
        _not_for_rational(
            "energy",
            "∫|C^(k)|² of a rational curve is not a polynomial in the control points (in "
            "general it has logarithms and arctangents); integrate |derivative(t, k)|² "
            "numerically if you need it",
        )

    def reduce(self) -> NoReturn:
        _not_for_rational(
            "reduce", "least squares on control points bounds no distance between rational curves"
        )

    def full_reduce(self, tol: float = 1e-12) -> NoReturn:
        _not_for_rational(
            "full_reduce",
            "use to_homogeneous().full_reduce() and from_homogeneous for an exact reduction",
        )

    def basis_power_matrix(self) -> NoReturn:
        _not_for_rational("basis_power_matrix", "the rational basis functions are not polynomials")

    def basis_bernstein_matrix(self, exact: bool = False) -> NoReturn:
        _not_for_rational(
            "basis_bernstein_matrix", "the rational basis functions are not polynomials"
        )


def _integer_root(value: int, n: int) -> int:
    """The integer r >= 1 with r^n = value, or 0 when there is none (Newton's method on
    integers, from an upper bound)."""
    if value <= 0:
        return 0
    r = 1 << -(-value.bit_length() // n)
    while True:
        s = ((n - 1) * r + value // r ** (n - 1)) // n
        if s >= r:
            break
        r = s
    return r if r**n == value else 0
