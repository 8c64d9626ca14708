"""Tensor-product surfaces S(u, v) = Σ_i Σ_j P_ij b_i(u; λ_u) b_j(v; λ_v) for every family.

A surface has a net of (m+1) × (n+1) control points in any dimension d >= 1, a family and a
shape parameter in each direction (``family`` may be one family or a pair (u, v)). Every
quantity goes through the exact Bézier net of degrees (M, N) (M = m, or m + 2 for
bernstein_like): ``to_bezier`` is exact for exact input, and the numeric kernels
(hazmat.surface_kernels) work on that net alone.

>>> from fractions import Fraction
>>> from lambda_bezier import SameDegreeSurface
>>> net = [[(i, j, (i * j) % 2) for j in range(4)] for i in range(4)]
>>> s = SameDegreeSurface(net, Fraction(1, 2), Fraction(-1, 2))
>>> s.evaluate(0.5, 0.5).round(6).tolist()
[1.5, 1.5, 0.25]
>>> s.to_bezier().control_net()[1][1]
(Fraction(5, 6), Fraction(1, 2), Fraction(5, 12))
"""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction
from functools import cached_property
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from . import _surface_curvature as _curv
from . import _surface_shapes as _shapes
from . import _validate as val
from ._validate import ParamLike
from .curves import BezierCurve, Curve, Matrix, _identity, _tables, family_class
from .hazmat import surface_kernels as ker

if TYPE_CHECKING:
    from ._surface_results import SurfaceClosestPoint


def __getattr__(name: str) -> Any:
    # SurfaceClosestPoint lives in _surface_results, imported on the first closest_point
    # (issue #29: import time); still reachable here, where it was defined until round 18
    if name == "SurfaceClosestPoint":
        from ._surface_results import SurfaceClosestPoint

        return SurfaceClosestPoint
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


ExactNet = ker.ExactNet
NetLike = npt.ArrayLike | Sequence[Sequence[Sequence[Fraction | float]]]


# ---------------------------------------------------------------------- the table adapter
def basis_to_bernstein_split(cls: type[Curve], degree: int) -> tuple[Matrix, ...]:
    """(M_0, M_1, …): the family's degree-`degree` basis in the Bernstein basis of degree N,
    split by powers of λ (row i of Σ_p λ^p M_p holds basis function i). The only place the
    surfaces read the families' generated tables: re-point it when the tables move."""
    if not cls._has_lambda:
        if degree in cls._data.DEGREES:
            return _tables(cls._data, "bernstein")[degree]
        return (_identity(degree + 1),)
    return _tables(cls._data, "bernstein")[degree]


def combine(split: tuple[Matrix, ...], lam: Fraction | float | None) -> Matrix | np.ndarray:
    """Σ_p λ^p M_p: Fractions for an exact λ (or none), floats for a float λ."""
    if lam is None or not isinstance(lam, float):
        x = Fraction(0) if lam is None else lam
        rows, cols = len(split[0]), len(split[0][0])
        return tuple(
            tuple(
                sum((Fraction(m[r][c]) * x**p for p, m in enumerate(split)), Fraction(0))
                for c in range(cols)
            )
            for r in range(rows)
        )
    out = np.zeros((len(split[0]), len(split[0][0])))
    for p, m in enumerate(split):
        out += lam**p * np.array(m, dtype=float)
    return out


# ---------------------------------------------------------------------- validation
def _as_family_pair(family: object) -> tuple[type[Curve], type[Curve]]:
    if isinstance(family, tuple | list):
        if len(family) != 2:
            raise ValueError(f"family must be one family or a pair (u, v), got {len(family)} items")
        return family_class(family[0]), family_class(family[1])
    cls = family_class(family)
    return cls, cls


def _exact_net(net: object) -> ExactNet | None:
    """The net as Fractions when every coordinate is an int or a Fraction, else None (an
    integer array is exact, as for curves; a 2-D grid of numbers is a net of points in d = 1)."""
    if isinstance(net, np.ndarray):
        if net.dtype.kind in "iu":
            net = net.tolist()
        elif net.dtype != object:
            return None
    if not isinstance(net, Sequence | np.ndarray):
        return None
    rows = []
    for row in net:
        exact = val.exact_rows(row)
        if exact is None and _is_numbers(row):
            exact = val.exact_rows([(x,) for x in row])
        if exact is None:
            return None
        rows.append(exact)
    return tuple(rows)


def _is_numbers(row: object) -> bool:
    """A row given as plain numbers (a scalar field's row), not as points."""
    if isinstance(row, str | bytes) or not isinstance(row, Sequence | np.ndarray):
        return False
    return all(val.is_exact_scalar(x) for x in row)


def _as_net(net: object) -> np.ndarray:
    arr = val.real_array(net, "net")
    arr = np.array(arr, dtype=float)
    if arr.ndim == 2:  # a scalar field: d = 1
        arr = arr[:, :, None]
    if arr.ndim != 3 or arr.shape[0] < 1 or arr.shape[1] < 1 or arr.shape[2] < 1:
        raise ValueError(
            "net must be an (m+1) x (n+1) grid of control points of dimension d >= 1, got "
            f"shape {np.shape(arr)}"
        )
    bad = ~np.isfinite(arr)
    if bad.any():
        i, j, _ = map(int, np.argwhere(bad)[0])
        raise ValueError(f"control point ({i}, {j}) of the net has a non-finite coordinate")
    arr.setflags(write=False)
    return arr


def _check_degree(cls: type[Curve], degree: int, direction: str) -> None:
    degrees = (0, 10**9) if cls._any_degree else tuple(cls._data.DEGREES)
    try:
        val.check_point_shape((degree + 1, 1), family=cls.family, degrees=degrees)
    except ValueError as exc:
        raise ValueError(f"net, direction {direction}: {exc}") from None


def _lam(cls: type[Curve], lam: object, name: str, check_range: bool) -> Fraction | float | None:
    if not cls._has_lambda:
        if lam is not None:
            raise ValueError(f"{name}: the classical Bézier direction takes no shape parameter")
        return None
    if lam is None:
        raise ValueError(f"{name}: a {cls.family} direction needs a shape parameter")
    try:
        return val.as_lambda(lam, cls._data, check_range=check_range)
    except (TypeError, ValueError) as exc:
        raise type(exc)(f"{name}: {exc}") from None


def _parameter_pair(u: object, v: object, extrapolate: bool) -> tuple[np.ndarray, np.ndarray, bool]:
    uu, su = val.as_parameters(u, extrapolate=extrapolate, name="u")
    vv, sv = val.as_parameters(v, extrapolate=extrapolate, name="v")
    return paired(uu, su, vv, sv)


def paired(
    uu: np.ndarray, su: bool, vv: np.ndarray, sv: bool
) -> tuple[np.ndarray, np.ndarray, bool]:
    """(u, v, both single): a single u (su) or v (sv) repeated against the other's array;
    two arrays must have one length."""
    if su and not sv:
        uu = np.full(vv.shape, uu[0])
    elif sv and not su:
        vv = np.full(uu.shape, vv[0])
    elif uu.shape != vv.shape:
        raise ValueError(f"u and v must have the same length, got {uu.size} and {vv.size}")
    return uu, vv, su and sv


def no_queries(q: np.ndarray, dimension: int) -> SurfaceClosestPoint:
    """The answer to an empty batch of queries (0, d): empty arrays, the points (0, d), as
    numpy and the curves give; a batch of another width is named."""
    from ._surface_results import SurfaceClosestPoint

    if q.shape[1] != dimension:
        raise ValueError(
            f"q: a batch of queries must have shape (k, {dimension}), got shape {q.shape}"
        )
    empty = np.empty(0)
    return SurfaceClosestPoint(
        empty, empty.copy(), np.empty((0, dimension)), empty.copy(), empty.copy()
    )


class Surface:
    """A tensor-product surface of any family (one, or one per direction).

    ``Surface(net, lam_u, lam_v, family="same_degree")``; a family from `load_family`, a
    built-in family's name or a curve class, or a pair (family_u, family_v). A direction of
    the classical Bézier family takes no parameter (pass None).
    """

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        _shapes.wrap_overrides(cls)  # an overridden derivative takes meshgrids too

    def __init__(
        self,
        net: NetLike,
        lam_u: Fraction | float | None = None,
        lam_v: Fraction | float | None = None,
        *,
        family: object,
        check_range: bool = True,
    ) -> None:
        self._u_cls, self._v_cls = _as_family_pair(family)
        self.net = _as_net(net)
        self._exact = _exact_net(net)
        if (
            self._exact is not None
            and self.net.ndim == 3
            and len(self._exact[0][0]) != self.net.shape[2]
        ):
            self._exact = None  # not a net of points (the shape check above names it)
        check_range = val.flag(check_range, "check_range")
        _check_degree(self._u_cls, self.net.shape[0] - 1, "u")
        _check_degree(self._v_cls, self.net.shape[1] - 1, "v")
        self.lam_u = _lam(self._u_cls, lam_u, "lam_u", check_range)
        self.lam_v = _lam(self._v_cls, lam_v, "lam_v", check_range)

    # ------------------------------------------------------------------ description
    @property
    def family(self) -> str | tuple[str, str]:
        fu, fv = self._u_cls.family, self._v_cls.family
        return fu if fu == fv else (fu, fv)

    @property
    def degrees(self) -> tuple[int, int]:
        """(m, n): the net has (m+1) x (n+1) control points."""
        return int(self.net.shape[0]) - 1, int(self.net.shape[1]) - 1

    @property
    def dimension(self) -> int:
        return int(self.net.shape[2])

    @property
    def is_exact(self) -> bool:
        return (
            self._exact is not None
            and not isinstance(self.lam_u, float)
            and not isinstance(self.lam_v, float)
        )

    def control_net(self) -> ExactNet | tuple[tuple[tuple[float, ...], ...], ...]:
        """The control net as given: Fractions if exact, floats otherwise."""
        if self._exact is not None:
            return self._exact
        return tuple(tuple(tuple(map(float, p)) for p in row) for row in self.net)

    def __repr__(self) -> str:
        m, n = self.degrees
        lams = "".join(
            f", {cls.parameter_name}_{d}={lam}"
            for d, cls, lam in (("u", self._u_cls, self.lam_u), ("v", self._v_cls, self.lam_v))
            if lam is not None
        )
        # the generic class names its families (one, or u x v), as AtomSurface does: the
        # built-in classes' names say it
        fu, fv = self._u_cls.family, self._v_cls.family
        which = "" if type(self) is not Surface else (f"{fu}, " if fu == fv else f"{fu} x {fv}, ")
        return f"{type(self).__name__}({which}degrees=({m}, {n}), dimension={self.dimension}{lams})"

    # ------------------------------------------------------------------ Bézier form
    def _bernstein(self, axis: int) -> Matrix | np.ndarray:
        cls, lam = (self._u_cls, self.lam_u) if axis == 0 else (self._v_cls, self.lam_v)
        return combine(basis_to_bernstein_split(cls, self.degrees[axis]), lam)

    def to_bezier(self) -> BezierSurface:
        """The same surface as a tensor-product Bézier surface of degrees (M, N); exact
        (Fraction control points) when the surface is exact."""
        bu, bv = self._bernstein(0), self._bernstein(1)
        if self.is_exact:
            assert self._exact is not None
            return BezierSurface(ker.exact_transform(bu, self._exact, bv))  # type: ignore[arg-type]
        with val.overflow_allowed():
            net = np.einsum(
                "ia,ijd,jb->abd",
                np.asarray(bu, dtype=float),
                self.net,
                np.asarray(bv, dtype=float),
                optimize=True,
            )
        return BezierSurface(val.finite_result(net, "the Bézier control net"))

    @cached_property
    def _bezier_net(self) -> np.ndarray:
        net = self.to_bezier().net
        return net

    @cached_property
    def _coefficients(self) -> np.ndarray:
        with val.overflow_allowed():
            out = ker.centred_coefficients(self._bezier_net)
        out = val.finite_result(out, "the surface's coefficients")
        out.setflags(write=False)
        return out

    def _derivative_coefficients(self, du: int, dv: int) -> np.ndarray:
        cache = self.__dict__.setdefault("_derivative_cache", {})
        key = (du, dv)
        if key not in cache:
            coeffs = ker.differentiate(self._coefficients, du, dv)
            coeffs.setflags(write=False)
            cache[key] = coeffs
        out: np.ndarray = cache[key]
        return out

    # ------------------------------------------------------------------ evaluation
    def evaluate(self, u: ParamLike, v: ParamLike, *, extrapolate: bool = False) -> np.ndarray:
        """S(u, v) at paired parameters: (d,) for scalars, (k, d) for arrays of length k (a
        scalar pairs with every entry of the other); u, v of any shapes that broadcast
        together (a meshgrid): their shape + (d,)."""
        return self.derivative(u, v, 0, 0, extrapolate=extrapolate)

    @_shapes.grid_shaped
    def derivative(
        self, u: ParamLike, v: ParamLike, du: int = 1, dv: int = 0, *, extrapolate: bool = False
    ) -> np.ndarray:
        """The partial derivative ∂^(du+dv) S / ∂u^du ∂v^dv at paired parameters."""
        du, dv = val.as_order(du, "du"), val.as_order(dv, "dv")
        uu, vv, scalar = _parameter_pair(u, v, extrapolate)
        with val.overflow_allowed():
            out = ker.evaluate_points(self._derivative_coefficients(du, dv), uu, vv)
        val.finite_result(out, "the surface value")
        return out[0] if scalar else out

    def evaluate_grid(
        self, us: ParamLike, vs: ParamLike, du: int = 0, dv: int = 0, *, extrapolate: bool = False
    ) -> np.ndarray:
        """S (or a partial derivative) on the grid us × vs: (len(us), len(vs), d)."""
        du, dv = val.as_order(du, "du"), val.as_order(dv, "dv")
        uu, _ = val.as_parameters(us, extrapolate=extrapolate, name="us")
        vv, _ = val.as_parameters(vs, extrapolate=extrapolate, name="vs")
        coeffs = self._derivative_coefficients(du, dv)
        with val.overflow_allowed():
            out = ker.evaluate_grid(coeffs, uu, vv)
        # |value| <= Σ|A_ij| on the unit square: the output is checked only when that bound
        # (or extrapolation) allows an overflow, so the common case costs no extra pass
        if extrapolate or not float(np.abs(coeffs).sum()) <= 1e300:
            val.finite_result(out, "the surface value")
        return out

    # ------------------------------------------------------------------ differential geometry
    def _pair(self, u: ParamLike, v: ParamLike) -> tuple[np.ndarray, np.ndarray, bool]:
        """Paired parameter arrays on the surface's domain (atom_surfaces: the families' t)."""
        return _parameter_pair(u, v, False)

    def _partial(self, uu: np.ndarray, vv: np.ndarray, du: int, dv: int) -> np.ndarray:
        """(k, d): ∂^(du+dv) S at paired parameter arrays (no checks; the caller's)."""
        out: np.ndarray = ker.evaluate_points(self._derivative_coefficients(du, dv), uu, vv)
        return out

    def _partial_magnitude(self, uu: np.ndarray, vv: np.ndarray, du: int, dv: int) -> np.ndarray:
        """(k,): the sum of the absolute terms that `_partial` adds up (its largest coordinate),
        so that its rounding error is a small multiple of eps times this."""
        coeffs = np.abs(self._derivative_coefficients(du, dv))
        with val.overflow_allowed():
            terms = ker.evaluate_points(coeffs, 0.5 + np.abs(uu - 0.5), 0.5 + np.abs(vv - 0.5))
        out: np.ndarray = terms.max(axis=-1)
        return out

    def _frame(self, u: ParamLike, v: ParamLike) -> tuple[np.ndarray, ...]:
        if self.dimension != 3:
            raise ValueError(
                f"normals and curvatures are defined here for surfaces in 3D, this one has "
                f"dimension {self.dimension}"
            )
        uu, vv, scalar = self._pair(u, v)
        with val.overflow_allowed():
            su, sv = self._partial(uu, vv, 1, 0), self._partial(uu, vv, 0, 1)
        val.finite_result(su, "S_u")
        val.finite_result(sv, "S_v")
        # one scale per point for every derivative (the largest first-derivative entry): the
        # products below neither overflow for a huge net nor underflow for a tiny one, and
        # the unit normal does not depend on it (curvatures rescale by it, see curvatures)
        scale = np.maximum(np.abs(su).max(axis=-1), np.abs(sv).max(axis=-1))
        safe = np.where(scale > 0, scale, 1.0)[:, None]
        su, sv = su / safe, sv / safe
        cross = np.cross(su, sv)
        size = np.linalg.norm(cross, axis=-1)
        len_u, len_v = np.linalg.norm(su, axis=-1), np.linalg.norm(sv, axis=-1)
        # a partial that is zero in exact arithmetic (a collapsed edge) comes out as rounding
        # noise, about eps times the terms summed; the cross product of noise is a normal in
        # an arbitrary direction, so the normal counts as undefined unless |S_u x S_v| clears
        # the rounding of both partials by far (the direction is then good to about 1e-7)
        with val.overflow_allowed():
            mag_u = self._partial_magnitude(uu, vv, 1, 0) / safe[:, 0]
            mag_v = self._partial_magnitude(uu, vv, 0, 1) / safe[:, 0]
        noise = 1e-9 * (mag_u * len_v + len_u * mag_v)
        bad = ~(size > 1e-14 * len_u * len_v) | ~(size > noise) | (scale == 0)
        if bad.any():
            k = int(np.argmax(bad))
            raise ValueError(
                f"the normal is undefined at (u, v) = ({uu[k]}, {vv[k]}): S_u x S_v vanishes "
                "there, or is within the rounding of S_u and S_v (a degenerate point of the "
                "surface, such as a collapsed edge)"
            )
        # the normal's rounding error (radians, to first order): the partials' own rounding
        # (ROUNDING times their magnitudes) turns the cross product by at most this much
        turn = _curv.ROUNDING * (mag_u * len_v + len_u * mag_v) / size
        return uu, vv, su, sv, cross / size[:, None], np.array(scalar), safe, size, turn

    @_shapes.grid_shaped
    def normal(self, u: ParamLike, v: ParamLike) -> np.ndarray:
        """The unit normal S_u × S_v / ‖S_u × S_v‖ (3D); a ValueError where it vanishes."""
        *_, n, scalar, _, _, _ = self._frame(u, v)
        return n[0] if scalar else n

    @_shapes.grid_shaped
    def curvatures(self, u: ParamLike, v: ParamLike) -> tuple[np.ndarray, np.ndarray]:
        """(K, H): Gaussian and mean curvature (H's sign follows the normal S_u x S_v); a
        ValueError where the normal is undefined."""
        uu, vv, su, sv, n, scalar, c, size, turn = self._frame(u, v)
        pairs = ((2, 0), (1, 1), (0, 2))
        with val.overflow_allowed():
            second = [self._partial(uu, vv, a, b) / c for a, b in pairs]
            mags = [self._partial_magnitude(uu, vv, a, b) / c[:, 0] for a, b in pairs]
        suu, suv, svv = (val.finite_result(x, "a second derivative") for x in second)
        # every derivative divided by the same c: K = K_scaled / c², H = H_scaled / c
        gauss, mean = _curv.shape_operator(su, sv, n, size, (suu, suv, svv), mags, turn, uu, vv)
        with val.overflow_allowed(), np.errstate(divide="ignore"):
            gauss = gauss / c[:, 0] / c[:, 0]  # c² could underflow
            mean = mean / c[:, 0]
        if not (np.isfinite(gauss).all() and np.isfinite(mean).all()):
            raise ValueError(
                "the curvature is beyond the float range here (a net this small curves more "
                "than 1.8e308); scale the net up"
            )
        if scalar:
            return gauss[0], mean[0]
        return gauss, mean

    def gaussian_curvature(self, u: ParamLike, v: ParamLike) -> np.ndarray:
        return self.curvatures(u, v)[0]

    def mean_curvature(self, u: ParamLike, v: ParamLike) -> np.ndarray:
        return self.curvatures(u, v)[1]

    # ------------------------------------------------------------------ isoparametric curves
    def _basis_values(self, axis: int, t: object) -> tuple[Any, ...]:
        name = "u" if axis == 0 else "v"
        x: Fraction | float
        if val.is_exact_scalar(t):
            x = Fraction(int(t.numerator), int(t.denominator))
            if not 0 <= x <= 1:
                raise ValueError(f"{name} = {x} is outside [0, 1]")
        else:
            tt, scalar = val.as_parameters(t, extrapolate=False, name=name)
            if not scalar:
                raise ValueError(f"{name} must be a single number")
            x = float(tt[0])
        bern = self._bernstein(axis)
        big = (len(bern[0]) if isinstance(bern, tuple) else bern.shape[1]) - 1
        values = ker.bernstein_values(big, x)
        rows = bern if isinstance(bern, tuple) else bern.tolist()
        return tuple(sum((r[k] * values[k] for k in range(big + 1)), 0 * x) for r in rows)

    def _contract(self, axis: int, weights: Any, exact: bool) -> Any:
        """The control points of an iso-parameter curve: the net's rows along `axis` combined
        with the basis values `weights` (exact rows where `exact`, else a float array)."""
        if not exact:
            w = np.array([float(x) for x in weights])
            return np.tensordot(w, self.net, axes=([0], [axis]))
        assert self._exact is not None
        net: ExactNet = self._exact if axis == 0 else tuple(zip(*self._exact, strict=True))
        return [
            tuple(
                sum((w * net[i][j][c] for i, w in enumerate(weights)), Fraction(0))
                for c in range(self.dimension)
            )
            for j in range(self.net.shape[1 - axis])
        ]

    def _iso_curve(self, axis: int, t: object) -> Curve:
        weights = self._basis_values(axis, t)
        exact = self.is_exact and all(isinstance(w, Fraction) for w in weights)
        cls, lam = (self._v_cls, self.lam_v) if axis == 0 else (self._u_cls, self.lam_u)
        pts = self._contract(axis, weights, exact)
        if cls._has_lambda:
            return cls(pts, lam, check_range=False)
        return cls(pts)

    def curve_at_u(self, u: Fraction | float) -> Curve:
        """The isoparametric curve v ↦ S(u, v), a curve of the v family at λ_v (exact for
        exact input and an exact u)."""
        return self._iso_curve(0, u)

    def curve_at_v(self, v: Fraction | float) -> Curve:
        """The isoparametric curve u ↦ S(u, v), a curve of the u family at λ_u."""
        return self._iso_curve(1, v)

    # ------------------------------------------------------------------ subdivision
    def split_u(self, u: Fraction | float) -> tuple[BezierSurface, BezierSurface]:
        """The pieces over [0, u] and [u, 1] in u, each reparametrised to [0, 1], as Bézier
        surfaces (a piece of a λ-surface is in general not one of the same λ)."""
        return self.to_bezier()._split(u, 0)

    def split_v(self, v: Fraction | float) -> tuple[BezierSurface, BezierSurface]:
        """split_u in the v direction."""
        return self.to_bezier()._split(v, 1)

    # ------------------------------------------------------------------ global queries
    def bounding_box(self, tol: float = 1e-12) -> tuple[np.ndarray, np.ndarray]:
        """(lo, hi): the axis-aligned box of the surface over the unit square, each bound the
        attained extreme within `tol` times the net's size (branch and bound on the Bézier net;
        the result contains the surface)."""
        tol = val.tolerance(tol)
        net = self._bezier_net
        size = float(np.abs(net).max()) or 1.0
        lo, hi = np.empty(self.dimension), np.empty(self.dimension)
        for c in range(self.dimension):
            for sign, out in ((1.0, lo), (-1.0, hi)):
                scalar = sign * net[:, :, c]
                coeffs = sign * self._coefficients[:, :, c : c + 1]
                grad = (ker.differentiate(coeffs, 1, 0), ker.differentiate(coeffs, 0, 1))
                hess = (
                    ker.differentiate(coeffs, 2, 0),
                    ker.differentiate(coeffs, 1, 1),
                    ker.differentiate(coeffs, 0, 2),
                )
                value = _scalar_value(coeffs)
                polish = _newton_polish(grad, hess)
                _, _, _, bound = ker.minimise_scalar_net(scalar, value, polish, tol * size)
                out[c] = sign * bound
        return lo, hi

    def closest_point(self, q: npt.ArrayLike, tol: float = 1e-12) -> SurfaceClosestPoint:
        """The global nearest point of the surface (over the unit square) to q, certified: the
        squared distance's Bézier net bounds it from below on every patch of a branch and
        bound, which stops when the best attained distance is within `tol` times the net's
        size (seen from q: the largest coordinate of P_ij − q) of the bound
        (``lower_bound``). Within about 1e-7 of the net's size from the surface, float
        rounding of the squared distance limits that gap to about sqrt(256 eps) times the
        size; ``lower_bound`` always says what was certified.
        q is one point (d,) or a batch (k, d) (then every field is an array over the batch)."""
        from ._surface_results import SurfaceClosestPoint

        tol = val.tolerance(tol)
        arr = np.asarray(val.real_array(q, "q"), dtype=float)
        if arr.ndim == 2:
            if arr.shape[0] == 0:
                return no_queries(arr, self.dimension)
            rows = [val.as_point(row, self.dimension, "q") for row in arr]
            found = [self._closest(row, tol) for row in rows]
            return SurfaceClosestPoint(
                *(
                    np.array([getattr(r, f) for r in found])
                    for f in ("u", "v", "point", "distance", "lower_bound")
                )
            )
        return self._closest(val.as_point(q, self.dimension, "q"), tol)

    def _closest(self, q: object, tol: float) -> SurfaceClosestPoint:
        from ._surface_results import SurfaceClosestPoint

        point = val.as_point(q, self.dimension, "q")
        # the search works in coordinates centred on q: its tolerance, the rounding floor of
        # the squared distance and the values it attains then scale with the net seen from q,
        # not with how far both are from the origin (a unit patch at 1e6 came back 2% of its
        # size off, tests/test_acceptance_31d.py)
        net = self._bezier_net - point
        size = float(np.abs(net).max()) or 1.0
        shifted = ker.centred_coefficients(net)
        f_net = sum(
            ker.bernstein_product(net[:, :, c], net[:, :, c]) for c in range(self.dimension)
        )
        coeffs = ker.centred_coefficients(np.asarray(f_net)[:, :, None])
        grad = (ker.differentiate(coeffs, 1, 0), ker.differentiate(coeffs, 0, 1))
        hess = (
            ker.differentiate(coeffs, 2, 0),
            ker.differentiate(coeffs, 1, 1),
            ker.differentiate(coeffs, 0, 2),
        )

        def value(u: np.ndarray, v: np.ndarray) -> np.ndarray:
            diff = ker.evaluate_points(shifted, u, v)
            out: np.ndarray = (diff * diff).sum(axis=1)
            return out

        polish = _newton_polish(grad, hess)
        floor = 256 * np.finfo(float).eps * size * size  # see _distance_gap

        u, v, best, lower = ker.minimise_scalar_net(
            np.asarray(f_net), value, polish, _distance_gap(tol * size, floor)
        )
        at = ker.evaluate_points(self._coefficients, np.array([u]), np.array([v]))[0]
        # the net's least coefficient is rounded too: at a corner, where it is the attained
        # value itself, it can come out an ulp above it; a lower bound lowered stays one
        lower = min(max(lower, 0.0), best)
        return SurfaceClosestPoint(u, v, at, float(np.sqrt(best)), float(np.sqrt(lower)))

    # ------------------------------------------------------------------ degree elevation
    def elevate_u(self) -> BezierSurface:
        """The Bézier form with one degree more in u (the same surface)."""
        return self.to_bezier().elevate_u()

    def elevate_v(self) -> BezierSurface:
        """The Bézier form with one degree more in v (the same surface)."""
        return self.to_bezier().elevate_v()


def _distance_gap(reach: float, floor: float) -> Any:
    """The squared-distance gap at which the closest point's search stops: the distance
    gap sqrt(best) - sqrt(lower) <= reach needs a squared gap of reach·(sqrt(best) +
    sqrt(lower)) >= reach·sqrt(best); float rounding of the squared distance's net (about
    eps·size²) sets `floor` under it. Once sqrt(best) <= reach every bound will do (a
    distance is >= 0): without that, a query on a level curve of a scalar field (d = 1, the
    minimum 0 along a curve) ran to the patch budget, about 2.5 s a query."""

    def gap(best: float) -> float:
        root = float(np.sqrt(max(best, 0.0)))
        return np.inf if root <= reach else max(reach * root, floor)

    return gap


def _scalar_value(coeffs: np.ndarray) -> Any:
    def value(u: np.ndarray, v: np.ndarray) -> np.ndarray:
        out: np.ndarray = ker.evaluate_points(coeffs, u, v)[:, 0]
        return out

    return value


def _newton_polish(grad: tuple[np.ndarray, ...], hess: tuple[np.ndarray, ...]) -> Any:
    """Newton on ∇f = 0 from (u, v), kept in the unit square (a few steps; the branch and
    bound only uses the values it reaches, so a poor step costs nothing but time)."""

    # the five scalar tensors side by side (zero-padded to one shape): one evaluation a step
    parts = (*grad, *hess)
    shape = (max(p.shape[0] for p in parts), max(p.shape[1] for p in parts))
    stacked = np.zeros((*shape, len(parts)))
    for k, part in enumerate(parts):
        stacked[: part.shape[0], : part.shape[1], k] = part[:, :, 0]

    def polish(u: float, v: float) -> tuple[float, float]:
        for _ in range(8):
            uu, vv = np.array([u]), np.array([v])
            gx, gy, hxx, hxy, hyy = map(float, ker.evaluate_points(stacked, uu, vv)[0])
            det = hxx * hyy - hxy * hxy
            if not det or not np.isfinite(det):
                break
            nu = u - (hyy * gx - hxy * gy) / det
            nv = v - (hxx * gy - hxy * gx) / det
            nu, nv = min(max(nu, 0.0), 1.0), min(max(nv, 0.0), 1.0)
            if nu == u and nv == v:
                break
            u, v = nu, nv
        return u, v

    return polish


class BezierSurface(Surface):
    r"""A tensor-product Bézier surface :math:`\sum_i \sum_j P_{ij} B_i^m(u) B_j^n(v)`."""

    def __init__(self, net: NetLike) -> None:
        super().__init__(net, family=BezierCurve)

    def to_bezier(self) -> BezierSurface:
        """The surface itself (surfaces are immutable)."""
        return self

    @cached_property
    def _bezier_net(self) -> np.ndarray:
        return self.net

    def _rows(self) -> Any:
        return self._exact if self._exact is not None else self.net.tolist()

    def _split(self, t: object, axis: int) -> tuple[BezierSurface, BezierSurface]:
        name = "u" if axis == 0 else "v"
        x: Fraction | float
        if val.is_exact_scalar(t) and self._exact is not None:
            x = Fraction(int(t.numerator), int(t.denominator))
            rows = self._exact
        else:
            tt, scalar = val.as_parameters(t, extrapolate=False, name=name)
            if not scalar:
                raise ValueError(f"{name} must be a single number")
            x, rows = float(tt[0]), self.net.tolist()
        if not 0 < x < 1:
            raise ValueError(f"splitting needs 0 < {name} < 1, got {x}")
        left, right = ker.split_net(rows, x, axis)
        return BezierSurface(left), BezierSurface(right)

    def _elevate(self, axis: int) -> BezierSurface:
        from .hazmat.forms import elevation_matrix

        size = self.degrees[axis]
        weights = elevation_matrix(size)  # (size + 2, size + 1)
        ident = _identity(self.degrees[1 - axis] + 1)
        left, right = (
            (tuple(zip(*weights, strict=True)), ident)
            if axis == 0
            else (ident, tuple(zip(*weights, strict=True)))
        )
        if self._exact is not None:
            return BezierSurface(ker.exact_transform(left, self._exact, right))
        net = np.einsum(
            "ia,ijd,jb->abd", np.array(left, dtype=float), self.net, np.array(right, dtype=float)
        )
        return BezierSurface(net)

    def elevate_u(self) -> BezierSurface:
        return self._elevate(0)

    def elevate_v(self) -> BezierSurface:
        return self._elevate(1)


def surface(
    net: NetLike,
    lam_u: Fraction | float | None = None,
    lam_v: Fraction | float | None = None,
    *,
    family: object = "same_degree",
    check_range: bool = True,
) -> Surface:
    """A surface of `family` (a name, a family from load_family, or a pair (u, v))."""
    return Surface(net, lam_u, lam_v, family=family, check_range=check_range)
