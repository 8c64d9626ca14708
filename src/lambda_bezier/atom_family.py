r"""Families beyond polynomials (issue #30): trigonometric, hyperbolic and mixed bases.

`load_family` reads a derived document of ``"format": 4`` here (`AtomData`): the basis
functions of each degree as exact rational combinations of *atoms* (``1``, ``t^K``,
``cos(W*t)``, ``sin(W*t)``, ``cosh(W*t)``, ``sinh(W*t)``), per monomial of the shape
parameters, on the family's own domain of t (e.g. [0, π/2]); the exact rational Bézier form
where there is one (u = tan(t/2) for trigonometric families), and the energies with entries
in ℚ[π] or ℚ[e^W] (`hazmat.constants`). Every key is checked; the atom strings go through a
strict regular expression (`hazmat.atoms.parse_atom`), nothing is evaluated.

`AtomCurve` is a curve of such a family at fixed parameter values, with the curve API; its
parameter is always the family's own t on its domain. Evaluation and derivatives of any
order are exact differentiation of the atoms then the kernels of `hazmat.atoms`, or, for long
arrays with numba, a certified piecewise polynomial of them (`hazmat.atom_pieces`); the geometry
(split, arc length, boxes, closest points, intersections) goes through the exact
`to_rational_bezier()` when the family has a rational form, with the parameters mapped back
to t (t = lo + 2·atan(scale·s) for tan(t/2)), and numerically otherwise (_atom_geometry).
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import TYPE_CHECKING, Any, NoReturn

import numpy as np
import numpy.typing as npt

from . import _validate as val
from ._atom_document import AtomData, Exact, RationalForm
from ._domain_geometry import DomainGeometry
from ._family_document import combine, monomial_value
from ._validate import ParamLike, PointsLike
from .hazmat import atom_pieces as ap
from .hazmat import atoms as ak
from .rational import RationalBezierCurve

if TYPE_CHECKING:
    pass


def _not_available(what: str, why: str) -> NoReturn:
    raise NotImplementedError(f"{what} is not available for this curve: {why}")


def _centred_basis(basis: Any, shape: Any, mid: float, name: str) -> np.ndarray:
    """(A, n+1): the exact basis (rows over the document's atoms) over the centred atoms
    about t = mid, in floats. A hyperbolic pair a cosh x + b sinh x (x = j w0 t) is
    p e^x + q e^-x with p = (a + b)/2, q = (a - b)/2 taken exactly, and about mid it is
    (p e^phi) e^(j w0 tau) + (q e^-phi) e^(-j w0 tau), phi = j w0 mid: each product rounded
    once. The float centring matrix (cosh phi, sinh phi) cancelled instead: exp(-40 t) on
    [0, 1], written cosh(40 t) - sinh(40 t), came out 2.5 off at t = 0."""
    out: np.ndarray = shape.centring.T @ np.array(basis, dtype=float).T
    if not shape.hyperbolic:
        return out
    first = 1 + shape.powers
    for j in range(1, shape.harmonics + 1):
        phi = j * shape.omega0 * mid
        if abs(phi) > 700:
            raise ValueError(
                f"the {name} family's atom e^({j * shape.omega0:g} t) at the middle of its "
                "domain is past the float range: its curves cannot be evaluated in floats"
            )
        grow, decay = math.exp(phi), math.exp(-phi)
        for i, row in enumerate(basis):
            a = b = Fraction(0)
            for c, atom in zip(row, shape.atoms, strict=True):
                w = float(atom.omega) * (math.pi if atom.pi else 1.0)
                if atom.kind in ("cosh", "sinh") and round(w / shape.omega0) == j:
                    a, b = (a + c, b) if atom.kind == "cosh" else (a, b + c)
            big, small = float((a + b) / 2) * grow, float((a - b) / 2) * decay
            out[first + 2 * (j - 1), i] = big + small
            out[first + 2 * (j - 1) + 1, i] = big - small
    return out


class AtomCurve(DomainGeometry):
    """A curve Σ P_i b_i(t; parameters) of a trigonometric, hyperbolic or mixed family, t on
    the family's domain (e.g. [0, π/2]). Made by ``Family.curve``; exact control points and
    parameter values (ints, Fractions) keep `to_rational_bezier` and `energy` exact."""

    # Curve.intersect(this) asks this class's intersect, with s and t exchanged
    intersects_curves = True

    _has_lambda = False
    lam = None

    def __init__(
        self,
        family: Any,
        points: PointsLike,
        values: tuple[Fraction, ...],
        exact_parameters: bool = True,
    ):
        data: AtomData = family.atom_data
        self.family_object = family
        self.data = data
        self.family = data.FAMILY
        self.points = val.as_points(points, family=data.FAMILY, degrees=data.DEGREES)
        self._exact_points = val.exact_rows(points)
        self._exact_parameters = exact_parameters  # given as ints/Fractions (not floats)
        self.values = values
        self.parameter_values = dict(zip(data.NAMES, values, strict=True))
        n = self.degree
        self.shape = data.SHAPES[n]
        basis = combine(data.COEFFICIENTS[n], values)  # (n+1, atoms), exact
        self.basis_coefficients = basis
        self._basis_float = np.array(basis, dtype=float)
        # the curve over the document's atoms, then over the centred atoms (floats)
        scale = val.power_of_two_scale(self.points)
        lo, hi = data.DOMAIN
        self._mid = 0.5 * (lo + hi)
        self._centred_basis = _centred_basis(basis, self.shape, self._mid, data.FAMILY)
        with val.overflow_allowed():
            self._centred = self._centre(self.points / scale)
        self._scale = scale
        self._orders: dict[int, np.ndarray] = {0: self._centred}
        self._half_angle = (
            data.SPACE == "trigonometric" and self.shape.omega0 * (hi - lo) * 0.5 <= math.pi / 2
        )
        self._tables: dict[int, np.ndarray] = {}
        self._pieces: dict[int, ap.PieceTable | None] = {}

    def _centre(self, rows: np.ndarray) -> np.ndarray:
        """Coefficients over the centred atoms of the curves with control points `rows`
        ((n+1, d)): the hyperbolic ones through `_centred_basis`, the others through the
        centring matrix after the points (that order's rounding is what the tests pin)."""
        if self.shape.hyperbolic:
            out: np.ndarray = self._centred_basis @ rows
            return out
        out = self.shape.centring.T @ (self._basis_float.T @ rows)
        return out

    # ------------------------------------------------------------------ description
    @property
    def domain(self) -> tuple[float, float]:
        """The family's interval of t (floats; `data.DOMAIN_TEXT` exactly)."""
        return self.data.DOMAIN

    @property
    def is_exact(self) -> bool:
        """Exact control points and parameter values (ints and Fractions)."""
        return self._exact_points is not None and self._exact_parameters

    def __repr__(self) -> str:
        shown = ", ".join(f"{k}={v}" for k, v in self.parameter_values.items())
        return (
            f"{type(self).__name__}({self.family}, degree={self.degree}, "
            f"dimension={self.dimension}, {shown}, t in {self.data.DOMAIN_TEXT})"
        )

    def control_points(self) -> tuple[tuple[Fraction, ...], ...] | tuple[tuple[float, ...], ...]:
        if self._exact_points is not None:
            return self._exact_points
        return tuple(tuple(float(v) for v in row) for row in self.points)

    def atom_parameter_values(self) -> dict[str, Fraction | float]:
        """The parameter values as given: Fractions if given exactly, floats otherwise (what
        the JSON form writes)."""
        if self._exact_parameters:
            return dict(self.parameter_values)
        return {k: float(v) for k, v in self.parameter_values.items()}

    # ------------------------------------------------------------------ evaluation
    def _parameters(self, t: ParamLike, extrapolate: bool) -> tuple[np.ndarray, bool]:
        extrapolate = val.flag(extrapolate, "extrapolate")
        tt, scalar, small, big = val.parameter_range(t)
        lo, hi = self.data.DOMAIN
        if not extrapolate and tt.size:
            # the domain's ends are rounded (π/2): allow them to a few ulps
            slack = 4 * np.spacing(max(abs(lo), abs(hi), 1.0))
            if small < lo - slack or big > hi + slack:
                bad = small if small < lo - slack else big
                raise ValueError(
                    f"t = {bad} is outside the {self.family} domain {self.data.DOMAIN_TEXT}; "
                    "pass extrapolate=True to evaluate there"
                )
        return tt, scalar

    def _coefficients(self, order: int) -> np.ndarray:
        if order not in self._orders:
            d = self.shape.derivative
            out = self._orders[max(k for k in self._orders if k < order)]
            for _ in range(order - max(k for k in self._orders if k < order)):
                out = d @ out
            self._orders[order] = out
        return self._orders[order]

    def _piece_table(self, order: int) -> ap.PieceTable | None:
        """The certified piecewise polynomial of the order-th derivative (hazmat.atom_pieces),
        built on first use; None where none is certified."""
        if order not in self._pieces:
            sh = self.shape
            lo, hi = self.data.DOMAIN
            curve = ap.CentredCurve(
                self._coefficients(order),
                lo,
                hi,
                self._mid,
                sh.omega0,
                sh.powers,
                sh.harmonics,
                sh.hyperbolic,
            )
            self._pieces[order] = ap.build(curve, sh.derivative)
        return self._pieces[order]

    def _values(self, tt: np.ndarray, order: int, inside: bool) -> np.ndarray:
        """(d, len(tt)): the order-th derivative (points scaled back). With the compiled
        kernel, arrays of at least ap.PIECES_FROM parameters inside the domain go through
        the certified piecewise form. Without it the atoms are faster: in numpy the piecewise
        form measured 4-7x a polynomial cubic's evaluation (one gather per coefficient and
        parameter), a trigonometric curve's half-angle form 1.7-2.1x (issue #30, README
        "Benchmarks")."""
        fast = inside and tt.size >= ap.PIECES_FROM and ap.compiled() is not None
        pieces = self._piece_table(order) if fast else None
        if pieces is not None:
            out = ap.evaluate(pieces, tt)
            if self._scale == 1.0:
                return out  # ap.build bounds the values far below overflow
            with val.overflow_allowed():
                out = out * self._scale
            return val.finite_result(out, "the curve" if order == 0 else f"derivative {order}")
        coeffs = self._coefficients(order)
        sh = self.shape
        with val.overflow_allowed():
            if inside and self._half_angle:
                if order not in self._tables:
                    self._tables[order] = ak.half_angle_coefficients(coeffs, sh.harmonics)
                table = self._tables[order]
                out = ak.evaluate_half_angle(table, tt, sh.omega0, sh.harmonics, self._mid)
            else:
                tau = tt - self._mid
                out = ak.evaluate(coeffs, tau, sh.omega0, sh.powers, sh.harmonics, sh.hyperbolic)
            if self._scale != 1.0:
                out = out * self._scale
        if inside and self._half_angle and self._scale == 1.0:
            return out  # |u| <= 1, denominator >= 1, coordinates below 2^900: no overflow
        return val.finite_result(out, "the curve" if order == 0 else f"derivative {order}")

    def evaluate(self, t: ParamLike, *, extrapolate: bool = False) -> np.ndarray:
        """C(t): (d,) for a scalar t, (len(t), d) for an array; t in the family's domain."""
        tt, scalar = self._parameters(t, extrapolate)
        out = self._values(tt, 0, not extrapolate).T
        return out[0] if scalar else out

    def derivative(self, t: ParamLike, k: int = 1, *, extrapolate: bool = False) -> np.ndarray:
        """d^k C / dt^k (in the family's t), any k >= 0, by exact differentiation of the atoms."""
        order = val.as_order(k)
        tt, scalar = self._parameters(t, extrapolate)
        out = self._values(tt, order, not extrapolate).T
        return out[0] if scalar else out

    def basis(self, t: ParamLike, order: int = 0, *, extrapolate: bool = False) -> np.ndarray:
        """b_i^(order)(t) at the curve's parameter values: (n+1,) or (len(t), n+1) (the
        tensor-product surfaces of atom_surfaces evaluate through it)."""
        order = val.as_order(order)
        tt, scalar = self._parameters(t, extrapolate)
        sh = self.shape
        coeffs = self._centred_basis  # (A, n+1)
        for _ in range(order):
            coeffs = sh.derivative @ coeffs
        out = ak.evaluate(coeffs, tt - self._mid, sh.omega0, sh.powers, sh.harmonics, sh.hyperbolic)
        return out.T[0] if scalar else out.T

    def _basis_derivative(self, t: ParamLike, extrapolate: bool) -> tuple[np.ndarray, np.ndarray]:
        """(Σ_a |c_ai'| |atom_a(t)|, the control points): the rounding of C'(t), evaluated
        over the atoms, is relative to the atoms' terms, not to b_i'(t) (which cancel: at a
        stop P0 = P1 the computed C'(0) is ~1e-16, not 0) (_speed_floor)."""
        tt, _ = self._parameters(t, extrapolate)
        sh = self.shape
        coeffs = sh.derivative @ self._centred_basis  # (A, n+1)
        tau = np.atleast_1d(tt) - self._mid
        atoms = ak.evaluate(
            np.eye(coeffs.shape[0]), tau, sh.omega0, sh.powers, sh.harmonics, sh.hyperbolic
        )
        return (np.abs(coeffs).T @ np.abs(atoms)).T, self.points

    def tangent(self, t: ParamLike, *, extrapolate: bool = False) -> np.ndarray:
        """The unit tangent C'/‖C'‖; ValueError where C'(t) = 0 (within its rounding)."""
        d1 = self.derivative(t, 1, extrapolate=extrapolate)
        floor, s = self._speed_floor(t, extrapolate)
        if val.stopped(d1, floor, s).any():
            raise ValueError("the tangent is undefined where C'(t) = 0 (a cusp, or a stop)")
        norm = np.linalg.norm(d1, axis=-1, keepdims=True)
        out: np.ndarray = d1 / norm
        return out

    def normal(self, t: ParamLike, *, extrapolate: bool = False) -> np.ndarray:
        """The unit normal of a planar curve: the tangent turned by +90°."""
        if self.dimension != 2:
            raise ValueError(f"normal is defined for planar curves, got dimension {self.dimension}")
        tan = self.tangent(t, extrapolate=extrapolate)
        return np.stack([-tan[..., 1], tan[..., 0]], axis=-1)

    # ------------------------------------------------------------------ the rational form
    @property
    def has_rational_form(self) -> bool:
        return self.degree in self.data.RATIONAL

    def to_rational_bezier(self) -> RationalBezierCurve:
        """The exact rational Bézier curve of this curve (Fractions in, Fractions out), in
        s = tan(t/2)/scale (hyperbolic: tanh); `t_of_s` and `s_of_t` map the parameters.

        A hyperbolic family has no exact form (its scale tanh(ω(hi − lo)/2) is irrational):
        then the form is in **floats** (weights and points), within about 1e-15 of the
        curve's size (tested to 1e-14), through u = tanh(ω0 (t − lo)/2) = scale · s, ω0 the
        base frequency (`_float_rational`)."""
        cached: RationalBezierCurve | None = self.__dict__.get("_rational")
        if cached is not None:
            return cached
        form = self.data.RATIONAL.get(self.degree)
        if form is None:
            if self.data.SPACE == "hyperbolic":
                return self._float_rational()[0]
            raise ValueError(
                f"the {self.family} family has no exact rational Bézier form: "
                f"{self.data.RATIONAL_REASON}"
            )
        num = combine(form.numerators, self.values)  # (n+1, deg+1)
        if self._exact_points is not None:
            pts = self._exact_points
            rows = [
                (
                    *(
                        sum((num[i][j] * p[c] for i, p in enumerate(pts)), Fraction(0))
                        for c in range(self.dimension)
                    ),
                    form.weights[j],
                )
                for j in range(len(form.weights))
            ]
            curve = RationalBezierCurve._from_rows(tuple(rows))
        else:
            numf = np.array(num, dtype=float)
            w = np.array(form.weights, dtype=float)
            pts_f = (numf.T @ self.points) / w[:, None]
            curve = RationalBezierCurve(pts_f, w)
        self.__dict__["_rational"] = curve
        return curve

    def _float_rational(self) -> tuple[RationalBezierCurve, RationalForm]:
        """A hyperbolic curve as a rational Bézier curve in floats: the basis written exactly
        over e^(kx), x = ω0 (t − lo), |k| <= K, then e^(kx) (1 − u²)^K in Bernstein form
        (hazmat.atoms.exponential_bernstein); the weights are those of (1 − u²)^K."""
        cached: tuple[RationalBezierCurve, RationalForm] | None = self.__dict__.get("_float_form")
        if cached is not None:
            return cached
        sh = self.shape
        waves = [a for a in sh.atoms if a.kind in ("cosh", "sinh")]
        base = ak.base_frequency([a.omega for a in waves]) if waves else Fraction(1)
        big = sh.harmonics
        # exact coefficients over e^(k ω0 t), k = -K..K
        on_exp = [[Fraction(0)] * (2 * big + 1) for _ in self.basis_coefficients]
        for a, atom in enumerate(sh.atoms):
            k = int(atom.omega / base) if atom in waves else 0
            sign = -1 if atom.kind == "sinh" else 1
            for i, row in enumerate(self.basis_coefficients):
                if atom.kind == "1":
                    on_exp[i][big] += row[a]
                else:
                    on_exp[i][big + k] += row[a] / 2
                    on_exp[i][big - k] += sign * row[a] / 2
        lo, hi = self.data.DOMAIN
        w0 = float(base)
        shift = np.exp(w0 * lo * np.arange(-big, big + 1))  # e^(k ω0 t) = e^(k ω0 lo) e^(kx)
        scale = math.tanh(0.5 * w0 * (hi - lo))
        table = ak.exponential_bernstein(big, scale)  # (2K+1 exponents, 2K+1 Bernstein)
        mix = (np.array(on_exp, dtype=float) * shift) @ table  # (n+1, 2K+1)
        weights = table[big]
        with val.overflow_allowed():
            points = (mix.T @ (self.points / self._scale)) / weights[:, None] * self._scale
        points = val.finite_result(points, "the rational form's control points")
        curve = RationalBezierCurve(points, weights)
        form = RationalForm(True, base, Fraction(scale), lo, tuple(), {})
        self.__dict__["_float_form"] = (curve, form)
        return curve, form

    def s_of_t(self, t: npt.ArrayLike) -> np.ndarray | float:
        """The rational form's parameter s at the family's t."""
        form = self._form("s_of_t")
        lo, hi = self.data.DOMAIN
        x = self._within(t, "t", lo, hi, self.data.DOMAIN_TEXT)
        s = form.s_of_t(x)
        if form.weights:  # the exact form
            return s
        # the float form's scale is tanh(hi) rounded: the domain's end may map to 1 + 1 ulp
        snapped = np.where((s > 1.0) & (s <= 1.0 + 1e-15), 1.0, s)
        return float(snapped) if np.ndim(snapped) == 0 else snapped

    def t_of_s(self, s: npt.ArrayLike) -> np.ndarray | float:
        """The family's t at the rational form's parameter s."""
        form = self._form("t_of_s")
        return form.t_of_s(self._within(s, "s", 0.0, 1.0, "[0, 1]"))

    @staticmethod
    def _within(x: npt.ArrayLike, name: str, lo: float, hi: float, text: str) -> Any:
        """Finite values within [lo, hi] (to 1e-12 of its width), a float for a scalar: the
        maps are monotone on the domain only, and tanh's inverse has poles just beyond."""
        arr, scalar, least, most = val.parameter_range(x, name)
        slack = 1e-12 * (hi - lo)
        if arr.size and (least < lo - slack or most > hi + slack):
            bad = least if least < lo - slack else most
            raise ValueError(f"{name} = {bad} is outside {text}")
        return float(arr[0]) if scalar else arr

    def _form(self, what: str) -> RationalForm:
        form = self.data.RATIONAL.get(self.degree)
        if form is None and self.data.SPACE == "hyperbolic":
            return self._float_rational()[1]
        if form is None:
            raise ValueError(f"{what}: the {self.family} family has no rational form")
        return form

    def to_bezier(self) -> NoReturn:
        _not_available(
            "to_bezier",
            f"a {self.data.SPACE} curve is not a polynomial curve"
            + (
                "; use to_rational_bezier() for its exact rational Bézier form"
                if self.has_rational_form
                else "; use to_rational_bezier() for its rational Bézier form in floats"
                if self.data.SPACE == "hyperbolic"
                else f" and has no rational form ({self.data.RATIONAL_REASON})"
            ),
        )

    # ------------------------------------------------------------------ energy
    def energy(self, k: int) -> Exact | float:
        r"""E_k = ∫ ‖C^(k)(t)‖² dt over the family's domain, from the document's Gram
        matrices: exact (a Fraction or a `ConstantFraction` in π or e^W) for exact points and
        parameters, a float otherwise."""
        from .hazmat.constants import ConstantFraction

        if isinstance(k, bool) or not isinstance(k, int | np.integer) or k < 1:
            raise ValueError(f"k must be a positive integer (the derivative order), got {k!r}")
        gram = self.data.GRAM.get((self.degree, int(k)))
        if gram is None:
            reason = self.data.ENERGY_REASON or "not in the derived document"
            raise ValueError(f"E_{k} of {self.family} at degree {self.degree}: {reason}")
        rows = self._exact_points
        exact = self.is_exact
        pts = (
            rows
            if rows is not None
            else [tuple(Fraction(float(v)) for v in r) for r in self.points]
        )
        total: Exact = Fraction(0)
        for (m1, m2), mat in gram.items():
            w = monomial_value(self.values, tuple(a + b for a, b in zip(m1, m2, strict=True)))
            if not w:
                continue
            for dim in range(self.dimension):
                for i, row in enumerate(mat):
                    pi = pts[i][dim]
                    if pi:
                        for j, g in enumerate(row):
                            if g and pts[j][dim]:
                                total = total + w * pi * pts[j][dim] * g
        if not exact:
            return float(total)
        if isinstance(total, ConstantFraction) and total.is_rational:
            return total.numerator[0] if total.numerator else Fraction(0)
        return total

    # ------------------------------------------------------------------ geometry
    def _rational_or_none(self, *, floats: bool = True) -> RationalBezierCurve | None:
        """The rational form the geometry goes through: the exact one, or with `floats` a
        hyperbolic curve's float form (measured: closest points 3x faster than the numeric
        route, boxes as fast with the ends exact; arc length stays numeric, 3x faster)."""
        if self.has_rational_form:
            return self.to_rational_bezier()
        if floats and self.data.SPACE == "hyperbolic":
            return self._float_rational()[0]
        return None

    def _domain_point(self, t: object, name: str) -> float:
        x = float(val.real_number(t, name))
        lo, hi = self.data.DOMAIN
        if not lo - 1e-15 <= x <= hi + 1e-15:
            raise ValueError(f"{name} = {t} is outside the domain {self.data.DOMAIN_TEXT}")
        return min(max(x, lo), hi)

    def split(self, t: Fraction | float) -> tuple[RationalBezierCurve, RationalBezierCurve]:
        """The pieces over [lo, t] and [t, hi] as rational Bézier curves, each in its own
        parameter on [0, 1] (the rational form split at s(t), in floats: s(t) = tan(t/2) is
        irrational at most t)."""
        x = self._domain_point(t, "t")
        if not self.data.DOMAIN[0] < x < self.data.DOMAIN[1]:
            raise ValueError(f"split needs t inside the domain {self.data.DOMAIN_TEXT}, got {t}")
        rat = self._rational_or_none()
        if rat is None:
            _not_available("split", f"it has no rational form ({self.data.RATIONAL_REASON})")
        # (a hyperbolic curve: its rational form in floats)
        s = self.s_of_t(x)
        return rat.split(float(s))


def evaluate_many(
    atom_family: Any,
    points: npt.ArrayLike,
    t: npt.ArrayLike,
    k: int,
    values: tuple[Fraction, ...],
    extrapolate: bool,
) -> np.ndarray:
    """batch.evaluate_many for a family of this module: m curves of one degree and one set
    of parameter values, (m, T, d): every curve's coefficients over the centred atoms in one
    product, the atoms evaluated once on the shared grid, one more product."""
    data: AtomData = atom_family.atom_data
    arr = val.real_array(points, "control points")
    if arr.ndim != 3:
        raise ValueError(f"control points must have shape (m, n+1, d), got shape {arr.shape}")
    m, size, dim = arr.shape
    val.check_point_shape((size, dim), family=data.FAMILY, degrees=data.DEGREES)
    if not np.isfinite(arr).all():
        idx = np.argwhere(~np.isfinite(arr))[0]
        raise ValueError(f"curve {idx[0]}, control point {idx[1]} has a non-finite coordinate")
    order = val.as_order(k)
    probe = AtomCurve(atom_family, arr[0], values, False)  # checks t against the domain too
    tt, scalar = probe._parameters(t, extrapolate)
    sh = probe.shape
    scale = val.power_of_two_scale(arr)
    with val.overflow_allowed():
        pt = np.ascontiguousarray(arr.transpose(1, 0, 2)).reshape(size, m * dim) / scale
        coeffs = probe._centre(pt)  # (A, m·d)
        for _ in range(order):
            coeffs = sh.derivative @ coeffs
        out = ak.evaluate(
            coeffs, tt - probe._mid, sh.omega0, sh.powers, sh.harmonics, sh.hyperbolic
        )
        out = (out.T.reshape(tt.size, m, dim).transpose(1, 0, 2)) * scale
    val.finite_result(out, "p(t)" if order == 0 else f"the derivative of order {order}")
    result: np.ndarray = out[:, 0] if scalar else out
    return result
