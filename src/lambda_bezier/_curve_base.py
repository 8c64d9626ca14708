"""The curve base classes: Curve, shared by every family, and BezierCurve, the classical
Bézier curve (both documented as lambda_bezier.curves', which re-exports them and assembles
the families above them).

Every family is a polynomial curve p(t) = Σ_i P_i b_i(t; λ) whose basis functions are given,
per degree, as exact matrices in generated/ (power and Bernstein coefficients, split by powers
of λ). The base class turns those matrices into the curve's power coefficients once, and all
evaluation is Horner's rule vectorised over t.

BezierCurve, the classical Bézier curve (no λ, ``_has_lambda = False``), is the reference
every curve converts to (``to_bezier``). The shape-parameter families are those generated/
lists; `FAMILIES` gives their classes (see builtin_curves for the ones with code of their own).
"""

from __future__ import annotations

import re
import sys
from fractions import Fraction
from functools import cache
from typing import TYPE_CHECKING, ClassVar, Literal, overload

import numpy as np
import numpy.typing as npt

from . import _singular
from . import _validate as val
from ._curve_shared import ControlPointCurve, check_curvature_dimension, speed_floor
from ._lazy import TableSource, deferred, generated
from ._validate import ParamLike, PointsLike
from .hazmat import forms
from .hazmat import kernels as alg

if TYPE_CHECKING:
    from types import ModuleType

    from sympy import Poly

    from . import geometry as _geometry
    from .hazmat import intersect as _intersect
    from .hazmat import intersect_self as _intersect_self
    from .hazmat import reduce as _reduce
else:

    def _load_geometry() -> ModuleType:
        from . import geometry

        return geometry

    def _load_intersect() -> ModuleType:
        from .hazmat import intersect

        return intersect

    def _load_intersect_self() -> ModuleType:
        from .hazmat import intersect_self

        return intersect_self

    def _load_reduce() -> ModuleType:
        from .hazmat import reduce

        return reduce

    # imported when a method first needs them, then bound (`import lambda_bezier` stays light)
    _geometry = deferred(_load_geometry)
    _intersect = deferred(_load_intersect)
    _intersect_self = deferred(_load_intersect_self)
    _reduce = deferred(_load_reduce)

_bernstein = generated("bernstein")

Matrix = tuple[tuple[Fraction, ...], ...]


@cache
def _float_matrix(data: object, kind: str, degree: int, power: int) -> np.ndarray:
    mats = _tables(data, kind)[degree]
    arr = np.array(mats[power], dtype=float)
    arr.setflags(write=False)
    return arr


@cache
def _float_hodograph(degree: int) -> np.ndarray:
    # degree 0: one zero row, the derivative of a constant (reached past the degree)
    return np.array(forms.hodograph_matrix(degree), dtype=float)


def _combine_exact(mats: tuple[Matrix, ...], lam: Fraction) -> Matrix:
    """Σ_p λ^p M_p in Fractions."""
    rows, cols = len(mats[0]), len(mats[0][0])
    return tuple(
        tuple(
            sum((Fraction(m[r][c]) * lam**p for p, m in enumerate(mats)), Fraction(0))
            for c in range(cols)
        )
        for r in range(rows)
    )


def _identity(size: int) -> Matrix:
    return tuple(tuple(Fraction(int(r == c)) for c in range(size)) for r in range(size))


@cache
def _tables(data: object, kind: str) -> dict[int, tuple[Matrix, ...]]:
    """kind ("power", "centred", "bernstein") -> degree -> tuple of λ-power matrices of the
    family whose tables `data` holds (a generated module, or a user family's FamilyData);
    the Bernstein basis has no λ (one matrix each)."""
    if data is _bernstein:
        if kind == "bernstein":
            return {d: (_identity(d + 1),) for d in _bernstein.DEGREES}
        return {d: (m,) for d, m in getattr(_bernstein, kind.upper()).items()}
    tables: dict[int, tuple[Matrix, ...]] = getattr(data, kind.upper())
    return tables


def _swapped_words(text: str) -> str:
    """A refusal of other.intersect(curve) said of curve.intersect(other): "the first" and
    "the second" curve exchanged, and the two dimensions of a mismatch."""
    for said, meant in (
        ("the first curve", "the second curve"),
        ("the second curve", "the first curve"),
    ):
        if text.startswith(said):
            return meant + text[len(said) :]
    dims = re.fullmatch(r"the curves have different dimensions \((\d+) and (\d+)\)", text)
    if dims:
        return f"the curves have different dimensions ({dims[2]} and {dims[1]})"
    return text


def _swapped_intersect(other: object, curve: object) -> list[_intersect.Intersection] | None:
    """curve(s) = other(t) when `other` is a curve class of a higher layer whose own
    intersect takes polynomial curves (rational Bézier, trigonometric/hyperbolic/mixed: they
    set ``intersects_curves``): asked the other way round, the same answer with s and t
    exchanged. None for anything else."""
    if not getattr(type(other), "intersects_curves", False):
        return None
    try:
        found = other.intersect(curve)  # type: ignore[attr-defined]
    except ValueError as err:  # its words are about the pair the other way round
        raise ValueError(_swapped_words(str(err))) from None
    return sorted(
        (_intersect.Intersection(h.t, h.s, h.kind) for h in found), key=lambda h: (h.s, h.t)
    )


class Curve(ControlPointCurve):
    """Behaviour shared by every family (the role numpy.polynomial's ABCPolyBase plays).

    Subclasses set ``family`` (a name), ``_data`` (the generated module) and whether they
    take a shape parameter.
    """

    family: ClassVar[str]
    _data: ClassVar[TableSource]
    _has_lambda: ClassVar[bool] = True
    # the shape parameter's name where the user reads it (repr, messages): a family defined
    # by data names its own (``parameter = "mu"``); the attribute stays ``lam``
    parameter_name: ClassVar[str] = "lam"
    _any_degree: ClassVar[bool] = False  # True: degrees past the generated tables are allowed
    # the control points' size is ordinary (_validate._ORDINARY: no power-of-two scaling
    # anywhere); set in __init__, False on an instance that bypassed it
    _ordinary: bool = False
    # the control points are the curve's classical Bézier points (to_bezier() is self)
    _bezier_form: ClassVar[bool] = False

    def __init__(
        self, points: PointsLike, lam: Fraction | float | None = None, *, check_range: bool = True
    ) -> None:
        degrees = (0, sys.maxsize) if self._any_degree else tuple(self._data.DEGREES)
        small = val.small_points(points, family=self.family, degrees=degrees)
        if small is not None:  # a small float array: no exact rows, its size read once
            self.points, self._ordinary = small
            self._exact_points: val.ExactRows | None = None
        else:
            self.points = val.as_points(points, family=self.family, degrees=degrees)
            self._exact_points = val.exact_rows(points)
            self._ordinary = val.ordinary(self.points)
        if self._has_lambda:
            if lam is None:
                raise ValueError(
                    f"a {self.family} curve needs a shape parameter {self.parameter_name}"
                )
            self.lam: Fraction | float | None = val.as_lambda(
                lam, self._data, check_range=check_range, name=self.parameter_name
            )
        else:
            if lam is not None:
                raise ValueError("a classical Bézier curve takes no shape parameter")
            self.lam = None
        # Coordinates near the float limit (or near its bottom) would overflow (underflow) in
        # the basis products although p(t) is representable: the coefficients are then kept
        # for the points scaled by a power of two (exact), and evaluation scales back.
        self._scale = 1.0 if self._ordinary else val.power_of_two_scale(self.points)
        # k -> Taylor coefficients of p^(k) about t = 1/2, coordinate-major (d, N+1 - k): what
        # evaluation uses at the tabulated degrees; filled on demand (_centred), so that a
        # curve built only to be intersected or located does not pay for them (issue #29)
        self._derivative_coeffs: dict[int, np.ndarray] = {}
        self._hodographs: list[np.ndarray] = []  # Bézier points of p, p', …, for energies

    # ------------------------------------------------------------------ description
    @property
    def polynomial_degree(self) -> int:
        """The degree of p(t) as a polynomial: n, or n + 2 for bernstein_like."""
        return self.degree + self._data_offset()

    @property
    def _tabulated(self) -> bool:
        """Whether generated/ has this degree's matrices (else de Casteljau evaluates)."""
        return self.degree in self._data.DEGREES

    @property
    def is_exact(self) -> bool:
        """True when control points and λ are all ints/Fractions (exact conversions)."""
        return self._exact_points is not None and not isinstance(self.lam, float)

    def __repr__(self) -> str:
        lam = "" if self.lam is None else f", {self.parameter_name}={self.lam}"
        return f"{type(self).__name__}(degree={self.degree}, dimension={self.dimension}{lam})"

    @classmethod
    def _data_offset(cls) -> int:
        return int(getattr(cls._data, "DEGREE_OFFSET", 0))

    # ------------------------------------------------------------------ basis matrices
    def _matrices(self, kind: str) -> tuple[Matrix, ...]:
        if not self._tabulated and self._any_degree:  # the classical basis: computed
            return (forms.basis_matrix(kind, self.degree),)
        if not self._tabulated:
            raise ValueError(
                f"no generated basis matrices for degree {self.degree} (they cover degrees "
                f"{self._data.DEGREES[0]}..{self._data.DEGREES[-1]})"
            )
        return _tables(self._data, kind)[self.degree]

    def _combined(self, kind: str) -> np.ndarray:
        mats = self._matrices(kind)
        if not self._tabulated:  # a classical curve past the tables: no λ, one matrix
            return np.array(mats[0], dtype=float)
        out = np.array(_float_matrix(self._data, kind, self.degree, 0))
        lam = 0.0 if self.lam is None else float(self.lam)
        for p in range(1, len(mats)):
            out += lam**p * _float_matrix(self._data, kind, self.degree, p)
        return out

    def basis_power_matrix(self) -> np.ndarray:
        """(n+1, N+1): row i holds the power coefficients of basis function i at this λ."""
        return self._combined("power")

    @overload
    def basis_bernstein_matrix(self, exact: Literal[False] = False) -> np.ndarray: ...
    @overload
    def basis_bernstein_matrix(self, exact: Literal[True]) -> Matrix: ...
    @overload
    def basis_bernstein_matrix(self, exact: bool) -> np.ndarray | Matrix: ...
    def basis_bernstein_matrix(self, exact: bool = False) -> np.ndarray | Matrix:
        """(n+1, N+1): row i holds basis function i in the Bernstein basis of degree N.
        With exact=True (needs an exact λ) a tuple of tuples of Fractions."""
        if not val.flag(exact, "exact"):
            return self._combined("bernstein")
        lam = Fraction(0) if self.lam is None else self.lam
        if isinstance(lam, float):
            raise ValueError("an exact basis matrix needs an exact lam (int or Fraction)")
        return _combine_exact(self._matrices("bernstein"), lam)

    # ------------------------------------------------------------------ evaluation
    def evaluate(self, t: ParamLike, *, extrapolate: bool = False) -> np.ndarray:
        """p(t): shape (d,) for a scalar t, (len(t), d) for an array."""
        return self.derivative(t, 0, extrapolate=extrapolate)

    def derivative(self, t: ParamLike, k: int = 1, *, extrapolate: bool = False) -> np.ndarray:
        """The k-th derivative p^(k)(t) (zero beyond the polynomial degree)."""
        if self._scale == 1.0 and not extrapolate:  # cannot overflow: see __init__
            return self._unit_derivative(t, k, extrapolate)
        with val.overflow_allowed():
            out = self._unit_derivative(t, k, extrapolate) * self._scale
        return val.finite_result(out, "p(t)" if k == 0 else f"the derivative of order {k}")

    def _unit_derivative(self, t: ParamLike, k: object, extrapolate: bool) -> np.ndarray:
        """p^(k)(t) of the curve scaled by 1/self._scale."""
        order = val.as_order(k)
        tt, scalar = val.as_parameters(t, extrapolate=extrapolate)
        if not self._tabulated:  # de Casteljau on the k-th hodograph stays accurate
            ctrl = self._hodograph_points(order)
            if self._scale != 1.0:
                ctrl = ctrl / self._scale
            out = alg.de_casteljau_steps(ctrl, tt, ctrl.shape[0] - 1)[:, 0]
            return out[0] if scalar else out
        coeffs = self._derivative_coeffs.get(order)
        if coeffs is None and order == 0:
            coeffs = self._centred()
        elif coeffs is None:
            coeffs = alg.differentiate_coefficients(self._centred(), order)
            coeffs.setflags(write=False)
            self._derivative_coeffs[order] = coeffs
        out = alg.centred_horner(coeffs, tt)
        return out[0] if scalar else out

    def _centred(self) -> np.ndarray:
        """The Taylor coefficients of p about t = 1/2 (d, N+1), for the points divided by
        self._scale, from the generated centred matrices (tabulated degrees only)."""
        centred = self._derivative_coeffs.get(0)
        if centred is None:
            unit = self.points if self._scale == 1.0 else self.points / self._scale
            centred = np.ascontiguousarray((self._combined("centred").T @ unit).T)
            centred.setflags(write=False)
            self._derivative_coeffs[0] = centred
        return centred

    def _hodograph_points(self, k: int) -> np.ndarray:
        """Bézier control points of p^(k), from the generated hodograph matrices."""
        if not self._hodographs:
            ctrl = self.basis_bernstein_matrix().T @ self.points
            ctrl.setflags(write=False)
            self._hodographs.append(ctrl)
        while len(self._hodographs) <= k:
            prev = self._hodographs[-1]
            nxt = _float_hodograph(prev.shape[0] - 1) @ prev
            nxt.setflags(write=False)
            self._hodographs.append(nxt)
        return self._hodographs[k]

    def basis(self, t: ParamLike, *, extrapolate: bool = False) -> np.ndarray:
        """Basis function values: (n+1,) for a scalar t, (len(t), n+1) for an array."""
        tt, scalar = val.as_parameters(t, extrapolate=extrapolate)
        if not self._tabulated:  # the Bernstein polynomials, by de Casteljau on unit points
            out = alg.de_casteljau_steps(np.eye(self.degree + 1), tt, self.degree)[:, 0]
        else:
            out = alg.centred_horner(self._combined("centred"), tt)
        return out[0] if scalar else out

    def _speed_floor(self, t: ParamLike, extrapolate: bool) -> tuple[np.ndarray, float]:
        """The rounding bound of the computed |p'(t)|, per t, in units of s, and s: relative
        to Σ |B_j'(t)| |Q_j| over the Bernstein basis and the Bézier control points Q (which
        de Casteljau on the hodograph weighs; ControlPointCurve._speed_floor)."""
        tt, _ = val.as_parameters(t, extrapolate=extrapolate)
        bezier = self._hodograph_points(0)  # cached, of the polynomial degree N (>= n)
        if self._scale != 1.0:
            bezier = self.basis_bernstein_matrix().T @ (self.points / self._scale)
        n = bezier.shape[0] - 1
        if n == 0:
            return np.zeros(tt.shape), 1.0
        with np.errstate(over="ignore", invalid="ignore"):  # far outside: NaN, undefined
            b1 = alg.de_casteljau_steps(_float_hodograph(n), tt, n - 1)[:, 0]
        floor, s = speed_floor(b1, bezier)
        return floor, s * self._scale

    def _curvature(self, t: ParamLike, extrapolate: bool = False) -> np.ndarray:
        """The curvature as an array, NaN where p'(t) = 0 within its rounding (for plots and
        joint reports)."""
        check_curvature_dimension(self.dimension)
        with val.overflow_allowed():  # κ(s·p) = κ(p)/s: computed unscaled, scaled back below
            d1 = self._unit_derivative(t, 1, extrapolate)
            d2 = self._unit_derivative(t, 2, extrapolate)
        if extrapolate:
            val.finite_result(d1, "the curvature")
            val.finite_result(d2, "the curvature")
        # per point, d1 and d2 divided by a power of two c near their size: κ = κ_c / c
        # without |p'|³ or p'×p'' overflowing (or underflowing) on the way
        floor, s = self._speed_floor(t, extrapolate)
        moving = ~val.stopped(d1, floor, s / self._scale)
        size = np.maximum(np.abs(d1).max(axis=-1), np.abs(d2).max(axis=-1))
        c = np.ldexp(1.0, np.frexp(np.where(size > 0, size, 1.0))[1])
        d1, d2 = d1 / c[..., None], d2 / c[..., None]
        if self.dimension == 2:
            cross = d1[..., 0] * d2[..., 1] - d1[..., 1] * d2[..., 0]
        else:
            cross = np.linalg.norm(np.cross(d1, d2), axis=-1)
        speed = np.linalg.norm(d1, axis=-1)
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            # divided one speed at a time: speed**3 underflows where |p'| << |p''| (near a
            # cusp) although κ itself is finite
            kappa = np.where(moving, cross / speed / speed / speed, np.nan) / c / self._scale
        if np.isinf(kappa).any():  # a curve of size ~1e-310
            raise ValueError("the curvature overflows the float range for these control points")
        return np.asarray(kappa)

    def energy(self, k: int) -> Fraction | float:
        r"""The energy :math:`E_k = \int_0^1 \lVert p^{(k)}(t) \rVert^2 \, dt`.

        k = 1, 2, 3 are the stretch, strain and jerk energies (any k >= 0 works). Computed from
        the Bézier form and the generated Bernstein Gram matrices: a Fraction when the curve is
        exact, a float otherwise.
        """
        from ._generated.energy import GRAM

        k = val.as_order(k)
        big = self.polynomial_degree
        if k > big:
            return Fraction(0) if self.is_exact else 0.0
        # past the generated Gram matrices: the same form, computed (hazmat.forms.gram_form)
        scale, upper = GRAM[big - k] if big - k in GRAM else forms.gram_form(big - k)
        if self.is_exact:
            h = self.to_bezier()._exact_points
            assert h is not None  # an exact curve has an exact Bézier form
            for d in range(big, big - k, -1):
                h = alg.exact_matmul(forms.hodograph_matrix(d), h)
            size = len(h)
            total = sum(
                (
                    upper[r][c] * sum((a * b for a, b in zip(h[r], h[c], strict=True)), Fraction(0))
                    for r in range(size)
                    for c in range(r, size)
                ),
                Fraction(0),
            )
            return Fraction(scale) * total
        g = np.array(upper, dtype=float) * float(scale)
        with val.overflow_allowed():
            ctrl = self._hodograph_points(k)
            energy = np.einsum("id,ij,jd->", ctrl, (g + g.T) / 2, ctrl)
        return float(val.finite_result(energy, f"E_{k}"))

    # ------------------------------------------------------------------ geometry (geometry.py)
    def arc_length(self, t0: Fraction | float = 0, t1: Fraction | float = 1) -> float:
        """∫ ‖p'(t)‖ dt from t0 to t1 (0 <= t0 <= t1 <= 1), to a relative accuracy of 1e-12."""
        return _geometry.arc_length(self, t0, t1)

    def parameter_at_length(self, s: npt.ArrayLike) -> np.ndarray | float:
        """The t at which the arc length from 0 equals s (a number or an array)."""
        return _geometry.parameter_at_length(self, s)

    def bounding_box(self) -> tuple[np.ndarray, np.ndarray]:
        """(lo, hi): the tight axis-aligned box, from the exact extremes of each coordinate."""
        return _geometry.bounding_box(self)

    def closest_point(self, q: npt.ArrayLike) -> _geometry.ClosestPoint:
        """The global nearest point to q, (d,) or a batch (m, d): `t`, `point`, `distance`."""
        return _geometry.closest_point(self, q)

    # ------------------------------------------------------------------ conversion
    @classmethod
    def from_bezier(cls, bezier: BezierCurve, lam: Fraction | float | None = None) -> Curve:
        """The curve of this family, at shape `lam`, that traces `bezier` exactly (Fractions
        for exact input), in the smallest degree whose basis spans it; refused at a singular
        parameter. See lambda_bezier.conversion for which degree that is."""
        return from_bezier(cls, bezier, lam)

    def to_bezier(self) -> BezierCurve:
        """The same curve as a classical Bézier curve of degree N (n, or n + 2).
        Exact (Fraction control points) when the curve is exact."""
        if self.is_exact:
            assert self._exact_points is not None
            weights = tuple(zip(*self.basis_bernstein_matrix(exact=True), strict=True))
            return BezierCurve(alg.exact_matmul(weights, self._exact_points))
        with val.overflow_allowed():
            ctrl = self.basis_bernstein_matrix().T @ self.points
        return BezierCurve(val.finite_result(ctrl, "the Bézier control points"))

    def control_points(self) -> tuple[tuple[Fraction, ...], ...] | tuple[tuple[float, ...], ...]:
        """The control points as given: Fractions if exact, floats otherwise."""
        if self._exact_points is not None:
            return self._exact_points
        return tuple(tuple(float(v) for v in row) for row in self.points)

    # ------------------------------------------------------------------ intersection, location
    # All of these work on the exact Bézier form (to_bezier keeps the parameter t), see
    # _intersect.py for the method; parameters are in this curve's own t.
    @property
    def _prepared(self) -> _intersect.Prepared:
        # kept in the instance dict by hand: functools.cached_property takes a lock on every
        # read in Python 3.11, a share of a small intersection's whole cost (issue #29)
        prepared: _intersect.Prepared | None = self.__dict__.get("_prepared_cache")
        if prepared is None:
            bez = self.to_bezier()
            prepared = _intersect.Prepared(bez.points, bez._exact_points)
            self.__dict__["_prepared_cache"] = prepared
        return prepared

    def intersect(self, other: Curve) -> list[_intersect.Intersection]:
        """Every intersection with another curve (any family), as Intersection(s, t, kind)
        sorted by s: self(s) = other(t). kind is "transversal", "tangent" or "coincident";
        a shared stretch is reported by its two end pairs, both "coincident". A rational or
        trigonometric/hyperbolic/mixed `other` answers through its own intersect."""
        if not isinstance(other, Curve):
            swapped = _swapped_intersect(other, self)
            if swapped is None:
                raise TypeError(f"other must be a curve, got {type(other).__name__}")
            return swapped
        if (
            self._bezier_form
            and other._bezier_form
            and self._exact_points is None
            and other._exact_points is None
            and self._ordinary
            and other._ordinary
        ):
            # float Bézier points are the curves exactly: the compiled kernels take them as
            # they are, no Prepared built (issue #29: a share of a small pair's whole time)
            found = _intersect.float_pair(self.points, other.points)
            if found is not None:
                return found
        return _intersect.intersect(self._prepared, other._prepared)

    def self_intersections(self) -> list[_intersect.Intersection]:
        """Every pair s < t with p(s) = p(t), as Intersection(s, t, kind), sorted by s."""
        return _intersect_self.self_intersections(self._prepared)

    def locate(self, point: PointsLike) -> float | None:
        """The t with p(t) = point (within 1e-10 of the curve's size), or None when the point
        is not on the curve. A ValueError when several t give the point (a self-crossing)."""
        arr = val.as_point(point, self.dimension)
        exact = val.exact_rows([point])
        found = _intersect.locate_point(self._prepared, arr, None if exact is None else exact[0])
        if len(found) > 1:
            raise ValueError(f"the point is on the curve at several parameters: {found}")
        return found[0] if found else None

    def implicitize(self) -> Poly:
        """The algebraic curve f(x, y) = 0 containing this planar curve, as an exact
        sympy.Poly in x and y with coprime integer coefficients (SymPy is imported here).
        Float control points (and a float lam) are taken at their exact binary values
        (``Fraction(x)`` is exact), so the result is the implicit form of exactly the curve
        the floats describe."""
        if self.dimension != 2:
            raise ValueError(f"implicitize needs a planar curve, got dimension {self.dimension}")
        from .hazmat.implicit import implicitize

        curve = self
        if not self.is_exact:  # every float is a binary rational: the same curve, exactly
            exact = [[Fraction(float(x)) for x in row] for row in self.points]
            cls = type(self)
            curve = (
                cls(exact, Fraction(float(self.lam)), check_range=False)
                if self.lam is not None
                else cls(exact)
            )
        rows = curve.to_bezier()._exact_points
        assert rows is not None  # checked above: the curve is exact
        return implicitize(rows)

    # ------------------------------------------------------------------ pieces (issue #23)
    # By way of the exact Bézier form, which keeps the parameter: a piece of a curve of a
    # shape-parameter family is a polynomial curve, in general not one of the family at the
    # same parameter, so these return classical Bézier curves (BezierCurve overrides them).
    def split(self, t: Fraction | float) -> tuple[BezierCurve, BezierCurve]:
        """The pieces over [0, t] and [t, 1] as classical Bézier curves (``to_bezier()``
        split at t; exact for exact points and t)."""
        return self.to_bezier().split(t)

    def segment(
        self, t1: Fraction | float, t2: Fraction | float, *, extrapolate: bool = False
    ) -> BezierCurve:
        """The piece between p(t1) and p(t2) as a classical Bézier curve on [0, 1]
        (``to_bezier().segment``: 0 <= t1 < t2 <= 1, or any t1 < t2 with extrapolate=True)."""
        return self.to_bezier().segment(t1, t2, extrapolate=extrapolate)

    def hodograph(self) -> BezierCurve:
        """The derivative curve p'(t) as a classical Bézier curve (``to_bezier().hodograph()``,
        of degree N - 1 for the Bézier form's degree N)."""
        return self.to_bezier().hodograph()


class BezierCurve(Curve):
    r"""A classical Bézier curve :math:`p(t) = \sum_{i=0}^n P_i B_{i,n}(t)` with the
    Bernstein basis :math:`B_{i,n}(t) = \binom{n}{i} t^i (1-t)^{n-i}` (lecture notes 002)."""

    family = "bezier"
    _data = _bernstein
    _has_lambda = False
    _any_degree = True  # any degree >= 0: de Casteljau past the generated tables
    _bezier_form = True

    def __init__(self, points: PointsLike) -> None:
        super().__init__(points)

    @overload
    def basis_bernstein_matrix(self, exact: Literal[False] = False) -> np.ndarray: ...
    @overload
    def basis_bernstein_matrix(self, exact: Literal[True]) -> Matrix: ...
    @overload
    def basis_bernstein_matrix(self, exact: bool) -> np.ndarray | Matrix: ...
    def basis_bernstein_matrix(self, exact: bool = False) -> np.ndarray | Matrix:
        if self._tabulated:
            return super().basis_bernstein_matrix(exact)
        return _identity(self.degree + 1) if exact else np.eye(self.degree + 1)

    def to_bezier(self) -> BezierCurve:
        """The curve itself (it is one already; curves are immutable)."""
        return self

    def _rows(self) -> tuple[tuple[Fraction, ...], ...] | tuple[tuple[float, ...], ...]:
        return self.control_points()

    def de_casteljau(self, t: ParamLike, *, extrapolate: bool = False) -> np.ndarray:
        """p(t) by de Casteljau's algorithm (a second evaluator, vectorised over t)."""
        tt, scalar = val.as_parameters(t, extrapolate=extrapolate)
        with val.overflow_allowed():
            out = alg.de_casteljau_steps(self.points / self._scale, tt, self.degree)[:, 0]
            out = out * self._scale
        if self._scale != 1.0 or extrapolate:
            val.finite_result(out, "p(t)")
        return out[0] if scalar else out

    def _exact_t(
        self, t: Fraction | float, name: str = "t", extrapolate: bool = False
    ) -> Fraction | float:
        if val.is_exact_scalar(t):
            return Fraction(t)
        tt, _ = val.as_parameters(t, extrapolate=extrapolate, name=name)
        if tt.size != 1:
            raise ValueError(f"{name} must be a single number")
        return float(tt[0])

    def split(self, t: Fraction | float) -> tuple[BezierCurve, BezierCurve]:
        """The pieces over [0, t] and [t, 1] (exact for exact points and t)."""
        t = self._exact_t(t)
        if not 0 < t < 1:
            raise ValueError(f"split needs 0 < t < 1, got {t}")
        rows = self._rows() if isinstance(t, Fraction) else self.points.tolist()
        left, right = alg.split_rows(rows, t)
        return BezierCurve(left), BezierCurve(right)

    def segment(
        self, t1: Fraction | float, t2: Fraction | float, *, extrapolate: bool = False
    ) -> BezierCurve:
        """The piece between p(t1) and p(t2), 0 <= t1 < t2 <= 1, reparametrised to [0, 1]
        (the lecture notes' scheme 1: split at t2, then at t1/t2 of the left piece). With
        extrapolate=True any t1 < t2 (the polynomial continued past [0, 1], by blossoming)."""
        t1 = self._exact_t(t1, "t1", extrapolate)
        t2 = self._exact_t(t2, "t2", extrapolate)
        if extrapolate and not t1 < t2:
            raise ValueError(f"segment needs t1 < t2, got t1={t1}, t2={t2}")
        if not extrapolate and not 0 <= t1 < t2 <= 1:
            raise ValueError(
                f"segment needs 0 <= t1 < t2 <= 1, got t1={t1}, t2={t2}; pass extrapolate=True "
                "for a piece of the curve continued past [0, 1]"
            )
        exact = isinstance(t1, Fraction) and isinstance(t2, Fraction)
        rows = self._rows() if exact else self.points.tolist()
        if extrapolate:
            return BezierCurve(forms.segment_rows(rows, t1, t2))
        if t2 != 1:
            rows, _ = alg.split_rows(rows, t2)
        if t1 != 0:
            _, rows = alg.split_rows(rows, t1 / t2)
        return BezierCurve(rows)

    def elevate(self) -> BezierCurve:
        """The same curve with one degree more (generated elevation matrix)."""
        return self._apply(forms.elevation_matrix(self.degree))

    def hodograph(self) -> BezierCurve:
        """The derivative curve p'(t) as a Bézier curve of degree n - 1 (degree 0, a
        constant, for a line segment)."""
        if self.degree < 1:
            raise ValueError("a degree-0 curve (a point) has no hodograph: its derivative is 0")
        return self._apply(forms.hodograph_matrix(self.degree))

    def reduce(self) -> tuple[BezierCurve, float]:
        """The curve of one degree less whose elevation is closest to this one (least
        squares on the control points), and the error: the largest distance between this
        curve's control points and the elevated reduction's, which bounds ‖p(t) − r(t)‖
        on [0, 1]. Exact, with error 0, when the curve is an exact degree elevation."""
        red = _reduce.reduce(self.points, self._exact_points)
        return BezierCurve(red.points), red.error

    def full_reduce(self, tol: float = 1e-12) -> tuple[BezierCurve, float]:
        """Reduce as long as the curve is a degree elevation (exactly for exact points,
        else while the summed error stays within tol times the control points' size);
        returns the lowest-degree curve and the error bound."""
        red = _reduce.full_reduce(self.points, self._exact_points, tol)
        return BezierCurve(red.points), red.error

    def _apply(self, weights: Matrix) -> BezierCurve:
        if self._exact_points is not None:
            return BezierCurve(alg.exact_matmul(weights, self._exact_points))
        with val.overflow_allowed():
            ctrl = np.array(weights, dtype=float) @ self.points
        return BezierCurve(val.finite_result(ctrl, "the control points"))


# ---------------------------------------------------------------------- conversion
# (lambda_bezier.conversion documents which degree; the method and that module share this)
RELATIVE_TOLERANCE = 1e-9  # float input: residual of the least-squares fit, relative


def from_bezier(
    cls: type[Curve], bezier: BezierCurve, lam: Fraction | float | None = None
) -> Curve:
    if not isinstance(bezier, BezierCurve):
        raise TypeError(f"bezier must be a BezierCurve, not {type(bezier).__name__}")
    if cls is BezierCurve:
        if lam is not None:
            raise ValueError("lam: a classical Bézier curve takes no shape parameter")
        return BezierCurve(bezier.control_points())
    name = cls.parameter_name
    shown = "λ" if name == "lam" else name  # the papers' letter for the built-in families
    if lam is None:
        raise ValueError(f"{name}: a {cls.family} curve needs a shape parameter")
    lam = val.as_lambda(lam, cls._data, check_range=True, name=name)
    offset = cls._data_offset()
    exact = bezier.is_exact and not isinstance(lam, float)
    n_bez = bezier.degree
    degrees = tuple(cls._data.DEGREES)
    start = max(n_bez - offset, degrees[0])
    for m in range(start, degrees[-1] + 1):
        singular = _singular.roots(cls.family, cls._data, m)
        if _singular.is_root(singular, lam):
            roots = [str(r) if isinstance(r, Fraction) else float(r) for r in singular]
            raise ValueError(
                f"{name}: the degree-{m} {cls.family} basis is linearly dependent at "
                f"{shown} = {lam} "
                f"(singular_parameters({cls.family!r}, {m}) = {roots}): the control points "
                "of a curve are not unique there"
            )
        target = bezier
        while target.degree < m + offset:
            target = target.elevate()
        if exact:
            mats = _tables(cls._data, "bernstein")[m]
            basis = _combine_exact(mats, Fraction(lam))  # (m+1) × (m+offset+1)
            a = [list(col) for col in zip(*basis, strict=True)]  # Mᵀ
            assert target._exact_points is not None  # exact: so are its elevations
            b = [list(row) for row in target._exact_points]
            try:
                sol = alg.solve_exact(a, b)
            except ArithmeticError:
                raise ValueError(
                    f"{name}: the degree-{m} {cls.family} basis is linearly dependent at "
                    f"{shown} = {lam}"
                ) from None
            if sol is not None:
                return cls([tuple(row) for row in sol], lam)
            continue
        probe = cls(np.zeros((m + 1, bezier.dimension)), lam, check_range=False)
        a_f = probe.basis_bernstein_matrix().T
        b_f = target.points
        sol_f, *_ = np.linalg.lstsq(a_f, b_f, rcond=None)
        residual = np.linalg.norm(a_f @ sol_f - b_f)
        if residual <= RELATIVE_TOLERANCE * max(1.0, float(np.linalg.norm(b_f))):
            return cls(sol_f, lam)
    raise ValueError(
        f"bezier: this degree-{n_bez} Bézier curve is no {cls.family} curve of degree "
        f"{start}..{degrees[-1]} at {shown} = {lam} (the basis does not span it; see "
        "lambda_bezier.conversion)"
    )


# documented, and pickled, as lambda_bezier.curves' (which re-exports them)
Curve.__module__ = BezierCurve.__module__ = "lambda_bezier.curves"
