r"""Families whose parameter is the length of the domain or sits inside sin/cos (issue #30):
C-Bézier curves on [0, α] and their hyperbolic analogue, from a ``"format": 5`` document.

The document (derive/emit/cbezier_document.py) holds the basis over the atoms 1, t^k,
cos(m t), sin(m t) (cosh, sinh) of t on [0, α], each coefficient a rational function of
α, sin α, cos α (sinh, cosh) as exponent/rational terms, and the Gram matrices of E_1..E_3 in
the same form. Nothing is evaluated but those sums.

`CBezierFamily.curve(points, alpha=...)` computes the float coefficients once per curve, with
a stated bound on their relative error (`coefficient_error`): each numerator and denominator
is a sum of terms evaluated in floats, so its relative error is at most
(degree + 3) · 2⁻⁵³ · Σ|terms| / |sum| (plus one ulp from sin and cos); near the open end
α → 0 (α − sin α ~ α³/6) that ratio grows like α⁻³, and the atoms' sum cancels as well
(measured for the cubic: 1e-12 relative at α = 0.5, 1e-7 at 0.1). So below the document's
threshold (``small_alpha``, derive/formulas/cbezier_series.py) the basis is taken instead from
its exact series in α about 0, b_i(α u; α) = Σ_k α^k p_ik(u) with polynomials p_ik in
u = t/α: a curve there is a polynomial curve in its own parameter (the removable limit α → 0
is p_i0, for Zhang's cubic the Bernstein cubic), evaluated through the same atom machinery
with powers only. A curve whose atom-form bound exceeds MAX_COEFFICIENT_ERROR (a singular
point other than the series' end) is refused by name instead of returning amplified rounding.

A curve is in the family's own parameter: t on [0, α] (``domain = "[0, alpha]"``) or u on
[0, 1] (``domain = "[0, 1]"`` with sin(alpha*t)). Evaluation, derivatives, curvature and the
energies are direct; the bounding box, closest point and intersections go through the
certified atom machinery (`_atom_geometry`, hazmat.atom_bounds, hazmat.atom_intersect) on
the curve's centred atoms at that α (numeric: these curves have no rational form for a
general α); `split` gives two curves of the same family (its space is invariant under shifts
of t) on [0, t] and [t, α].
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from . import _validate as val
from ._cbezier_series import small_alpha_of
from ._domain_geometry import DomainGeometry
from ._validate import ParamLike, PointsLike
from .hazmat import atoms as ak

if TYPE_CHECKING:
    pass

FORMAT = 5
MAX_COEFFICIENT_ERROR = 1e-6  # relative: past this a curve at that alpha is refused
_EPS = 2.0**-53
Terms = list[tuple[tuple[int, int, int], float]]


class CBezierError(ValueError):
    """A document that is not a well-formed format-5 document."""


def _terms(raw: object, where: str) -> Terms:
    if not isinstance(raw, list):
        raise CBezierError(f"{where}: not a list of terms")
    out: Terms = []
    for item in raw:
        if (
            not isinstance(item, list)
            or len(item) != 2
            or not isinstance(item[0], list)
            or len(item[0]) != 3
            or not all(isinstance(e, int) and 0 <= e <= 64 for e in item[0])
            or not isinstance(item[1], str)
        ):
            raise CBezierError(f"{where}: a term is [[i, j, k], 'p/q']")
        try:
            value = float(Fraction(item[1]))
        except (ValueError, ZeroDivisionError):
            raise CBezierError(f"{where}: {item[1]!r} is not a rational") from None
        out.append(((item[0][0], item[0][1], item[0][2]), value))
    return out


@dataclass(frozen=True)
class RatFn:
    num: Terms
    den: Terms

    def value(self, a: float, s: float, c: float) -> tuple[float, float]:
        """(value, bound on its relative error)."""
        parts = []
        for terms in (self.num, self.den):
            total, size, top = 0.0, 0.0, 0
            vals = [coef * a**i * s**j * c**k for (i, j, k), coef in terms]
            total = math.fsum(vals)
            size = math.fsum(abs(v) for v in vals)
            top = max((i + j + k for (i, j, k), _ in terms), default=0)
            parts.append((total, (top + 3) * _EPS * size))
        (n, en), (d, ed) = parts
        if abs(d) <= ed:
            return math.nan, math.inf
        if n == 0 and en == 0:
            return 0.0, 0.0
        rel = (en / abs(n) if n else math.inf) + ed / abs(d)
        return n / d, rel


def _exact(terms: list[Any]) -> dict[tuple[int, int, int], Fraction]:
    """Terms already checked by _terms, as {(i, j, k): Fraction}."""
    out: dict[tuple[int, int, int], Fraction] = {}
    for (i, j, k), v in terms:
        out[(i, j, k)] = out.get((i, j, k), Fraction(0)) + Fraction(v)
    return out


@dataclass(frozen=True)
class Representation:
    """A basis at one alpha over atoms of the family's own parameter (t on [0, alpha], or u
    on [0, 1]): `own` (n+1, len(layout)), the layout's highest power and harmonic, the
    coefficients as the document or the series gives them (`coefficients` over `atoms`:
    the document's atoms of t, or ("pow", j) of u = t/alpha below the series' threshold), and
    their relative error bound."""

    layout: list[tuple[str, int]]
    own: np.ndarray
    powers: int
    harmonics: int
    coefficients: np.ndarray
    atoms: list[tuple[str, int]]
    error: float


def _ratfn(raw: object, where: str) -> RatFn:
    if not isinstance(raw, dict) or set(raw) != {"num", "den"}:
        raise CBezierError(f"{where}: a coefficient is {{'num': [...], 'den': [...]}}")
    return RatFn(_terms(raw["num"], where), _terms(raw["den"], where))


class _Shape:
    """What hazmat.atom_bounds and _atom_geometry read of a curve's space."""

    def __init__(self, omega0: float, powers: int, harmonics: int, hyperbolic: bool):
        self.omega0, self.powers, self.harmonics = omega0, powers, harmonics
        self.hyperbolic = hyperbolic


class CBezierFamily:
    """A family of ``"format": 5`` (made by `load_family`)."""

    def __init__(self, doc: dict[str, Any], path: str, title: str, table: dict[str, Any]):
        where = path
        try:
            self.family = str(doc["family"])
            self.name = self.family
            self.parameter = str(doc["parameter"])
            rng = doc["range"]
            self.lo, self.hi = float(rng["lo_float"]), float(rng["hi_float"])
            self.lo_closed, self.hi_closed = bool(rng["lo_closed"]), bool(rng["hi_closed"])
            self.range_text = str(rng["text"])
            self.form = str(doc["form"])
            self.space = str(doc["space"])
            self.degree = int(doc["degree"])
            self.atoms = [(str(k), int(m)) for k, m in doc["atoms"]]
            self._coefficients = [
                [_ratfn(x, f"{where}: coefficients") for x in row] for row in doc["coefficients"]
            ]
            self._energies = {
                int(k): [[_ratfn(x, f"{where}: energies") for x in row] for row in mat]
                for k, mat in doc["energies"].items()
            }
            # the same entries exactly, for the certified optimum (_cbezier_optimum)
            self._exact_energies = {
                int(k): [[(_exact(x["num"]), _exact(x["den"])) for x in row] for row in mat]
                for k, mat in doc["energies"].items()
            }
            self.range_ends = (str(rng["lo"]), str(rng["hi"]))
            self.small_alpha = small_alpha_of(doc.get("small_alpha"), where, self.degree + 1)
            self.verdicts = doc["verdicts"]
            self.functions = doc["functions"]
        except (KeyError, TypeError, ValueError) as exc:
            raise CBezierError(f"{where}: not a format-5 document ({exc})") from None
        if self.form not in ("domain", "unit") or self.space not in ("trigonometric", "hyperbolic"):
            raise CBezierError(f"{where}: unknown form or space")
        self.hyperbolic = self.space == "hyperbolic"
        # what the shared functions that take a polynomial or atom family say about this one
        where_param = "domain" if self.form == "domain" else "frequency"
        self.elsewhere = (
            f"has its parameter {self.parameter} in the {where_param} "
            "(C-Bézier): this function takes polynomial families only; optimal_parameters, "
            "optimal_lambda, evaluate_many(..., params={...}), join(..., params={...}), "
            "CompositeCurve and export (JSON, STEP, DXF, SVG) take it; its curves come from "
            f"fam.curve(points, {self.parameter}=...)"
        )
        self.title = title
        self.definition = table
        # what a curve's JSON form embeds, as for every family defined by data (_json_io)
        from ._family_file import definition_digest

        self.table = table
        self.digest = definition_digest(table)
        self.powers = max((m for k, m in self.atoms if k == "pow"), default=0)
        self.harmonics = max((m for k, m in self.atoms if k != "pow"), default=0)

    def __repr__(self) -> str:
        return (
            f"CBezierFamily({self.name}, degree={self.degree}, {self.parameter} in "
            f"{self.range_text}, {self.space})"
        )

    # ------------------------------------------------------------------ the parameter
    def check_alpha(self, alpha: object) -> float:
        name = self.parameter
        if isinstance(alpha, bool) or not isinstance(alpha, int | float | Fraction):
            raise TypeError(f"{name} must be a real number, got {type(alpha).__name__}")
        x = float(alpha)
        if not math.isfinite(x):
            raise ValueError(f"{name} must be finite, got {alpha}")
        below = x < self.lo or (x == self.lo and not self.lo_closed)
        above = x > self.hi or (x == self.hi and not self.hi_closed)
        if below or above:
            raise ValueError(f"{name} = {alpha} is outside the family's range {self.range_text}")
        return x

    def _angles(self, x: float) -> tuple[float, float]:
        return (math.sinh(x), math.cosh(x)) if self.hyperbolic else (math.sin(x), math.cos(x))

    def _matrix(self, rows: list[list[RatFn]], x: float, what: str) -> tuple[np.ndarray, float]:
        s, c = self._angles(x)
        out = np.empty((len(rows), len(rows[0])))
        worst = 0.0
        for i, row in enumerate(rows):
            for j, f in enumerate(row):
                v, rel = f.value(x, s, c)
                out[i, j] = v
                worst = max(worst, rel)
        if not worst <= MAX_COEFFICIENT_ERROR:
            raise ValueError(
                f"{self.parameter} = {x}: the {what} cannot be computed in floats to "
                f"{MAX_COEFFICIENT_ERROR:g} (bound {worst:.3g}); this is near a singular "
                f"point of the family ({self.singular_text()})"
                + (
                    f"; curves there use the exact series below {self.parameter} = "
                    f"{self.small_alpha.below} (fam.representation({x}))"
                    if self.small_alpha is not None and x < self.small_alpha.below
                    else ""
                )
            )
        return out, worst

    def singular_text(self) -> str:
        rows = self.verdicts.get("singular_points", [])
        return "; ".join(f"{self.parameter} = {r['at']}: {r['denominator']} = 0" for r in rows)

    def representation(self, alpha: object) -> Representation:
        """The basis at alpha over atoms of the own parameter: from the document's series
        below its threshold (no cancellation there), else from the atom coefficients."""
        x = self.check_alpha(alpha)
        unit = self.form == "unit"
        series = self.small_alpha
        if series is not None and x < series.below:
            coeffs, err = series.coefficients(x)
            degree = coeffs.shape[1] - 1
            if not unit and x**degree < 1e-290:  # t^k / alpha^k past the float range
                raise ValueError(
                    f"{self.parameter} = {x} is too small for a curve in t on [0, "
                    f"{self.parameter}] in floats (t^{degree} / {self.parameter}^{degree} "
                    f"underflows); its limit {self.parameter} -> 0 is the polynomial curve of "
                    "the series' first term"
                )
            own = coeffs if unit else coeffs / x ** np.arange(degree + 1)
            layout = [("pow", j) for j in range(degree + 1)]
            atoms = [("pow", j) for j in range(degree + 1)]
            return Representation(layout, own, degree, 0, coeffs, atoms, err)
        basis, err = self.basis_coefficients(x)
        rate = x if unit else 1.0  # t = alpha*u on [0, 1]
        layout = [("pow", k) for k in range(self.powers + 1)]
        for m in range(1, self.harmonics + 1):
            layout += [("cos", m), ("sin", m)]
        own = np.zeros((basis.shape[0], len(layout)))
        for j, (kind, m) in enumerate(self.atoms):  # t^k = (alpha u)^k; cos(m t) keeps its own
            factor = rate**m if kind == "pow" else 1.0
            own[:, layout.index((kind, m))] += basis[:, j] * factor
        self._check_cancellation(x, own, layout, 1.0 if unit else x, rate, err)
        return Representation(layout, own, self.powers, self.harmonics, basis, self.atoms, err)

    def _check_cancellation(
        self,
        x: float,
        own: np.ndarray,
        layout: list[tuple[str, int]],
        hi: float,
        rate: float,
        err: float,
    ) -> None:
        """Refuse an alpha where the atom form's sum cancels past MAX_COEFFICIENT_ERROR: `err`
        bounds the coefficients' relative error, but b_i(t) = sum_a c_ia a(t) sums terms of
        size sum_a |c_ia| |a(t)| (|a| <= hi^k, 1, cosh(m rate hi) on [0, hi]). A hyperbolic
        basis on [0, 40] has terms near e^40 / 4: its floats were wrong by 2 (P_0 at (0.95, 2))."""
        sizes = []
        for kind, m in layout:
            if kind == "pow":
                sizes.append(hi**m)
            elif self.hyperbolic:
                sizes.append(math.cosh(min(m * rate * hi, 700.0)))
            else:
                sizes.append(1.0)
        terms = float((np.abs(own) @ np.array(sizes)).max())
        bound = (err + 4 * len(layout) * _EPS) * terms
        if not bound <= MAX_COEFFICIENT_ERROR:
            raise ValueError(
                f"{self.parameter} = {x}: the {self.name} basis cannot be evaluated in floats "
                f"to {MAX_COEFFICIENT_ERROR:g} there: its atoms' terms reach {terms:.3g} for "
                f"values of size 1 (bound {bound:.3g}); a smaller {self.parameter} is needed"
            )

    def basis_coefficients(self, alpha: object) -> tuple[np.ndarray, float]:
        """((n+1, atoms) float coefficients in t on [0, alpha], bound on their relative error)."""
        return self._matrix(self._coefficients, self.check_alpha(alpha), "basis coefficients")

    def energy_matrix(self, alpha: object, k: int) -> np.ndarray:
        """G with E_k = sum_ij G_ij P_i . P_j, in the family's t on [0, alpha]: from the
        document's exact Gram entries in floats, or, below the series' threshold (where
        those cancel), G = alpha^(1-2k) int_0^1 B_i^(k) B_j^(k) du of the series' polynomials
        B_i(u) = b_i(alpha u) by Gauss-Legendre with enough points to be exact for them."""
        if k not in self._energies:
            raise ValueError(f"k must be one of {sorted(self._energies)}, got {k!r}")
        x = self.check_alpha(alpha)
        if self.small_alpha is not None and x < self.small_alpha.below:
            coeffs, _ = self.small_alpha.coefficients(x)  # (n+1, D+1) over u^j
            if coeffs.shape[1] > k:  # (D+1-k, n+1): the k-th derivatives in u
                derived = np.polynomial.polynomial.polyder(coeffs.T, k, axis=0)
            else:
                derived = np.zeros((1, coeffs.shape[0]))
            # degree 2(D-k) <= 2D - 1: exact with D points
            nodes, weights = np.polynomial.legendre.leggauss(max(1, coeffs.shape[1]))
            u = (nodes + 1) / 2
            values = np.polynomial.polynomial.polyval(u, derived)  # (n+1, nodes)
            gram: np.ndarray = (values * weights) @ values.T / 2 * x ** (1 - 2 * k)
            return gram
        return self._matrix(self._energies[k], x, f"E_{k} matrix")[0]

    # ------------------------------------------------------------------ curves
    def curve(
        self, points: PointsLike, value: object = None, /, *, params: object = None, **named: object
    ) -> CBezierCurve:
        """The curve at the parameter, by the family's own name (``alpha=2.0``), as
        ``params={name: value}`` or positionally; another name is a TypeError naming it."""
        if params is not None and not isinstance(params, dict):
            raise TypeError("params must be a dict {name: value}")
        names = [self.parameter] * (value is not None) + [*(params or {}), *named]
        for x in names:
            if x != self.parameter:
                raise TypeError(f"{x!r} is not a parameter of {self.name!r} ({self.parameter})")
        if len(names) != 1:
            raise TypeError(f"curve() takes the parameter {self.parameter}=... once")
        x = value if value is not None else {**(params or {}), **named}[self.parameter]
        return CBezierCurve(self, points, self.check_alpha(x))

    def energy(self, points: PointsLike, alpha: object, k: int) -> float:
        """E_k of the curve at alpha (CBezierCurve.energy)."""
        return self.curve(points, alpha).energy(k)

    def evaluate_curves(
        self,
        points: npt.ArrayLike,
        t: ParamLike,
        k: int,
        lam: object,
        params: object,
        extrapolate: bool,
    ) -> np.ndarray:
        """batch.evaluate_many for this family: m curves (m, n+1, d) at one alpha
        (``params={"alpha": ...}`` or ``lam=...``), the k-th derivative in the family's own
        parameter at every t, (m, T, d): the curves' coefficients over the centred atoms in one
        product, the atoms evaluated once on the shared t."""
        alpha = self.parameter_value(lam, params, {})
        arr = val.real_array(points, "control points")
        if arr.ndim != 3:
            raise ValueError(f"control points must have shape (m, n+1, d), got shape {arr.shape}")
        m, size, dim = arr.shape
        val.check_point_shape((size, dim), family=self.name, degrees=(self.degree,))
        if not np.isfinite(arr).all():
            idx = np.argwhere(~np.isfinite(arr))[0]
            raise ValueError(f"curve {idx[0]}, control point {idx[1]} has a non-finite coordinate")
        order = val.as_order(k)
        probe = CBezierCurve(self, arr[0], alpha)  # its basis at alpha; checks t below
        tau, scalar = probe._tau(t, extrapolate)
        scale = val.power_of_two_scale(arr)
        with val.overflow_allowed():
            pt = np.ascontiguousarray(arr.transpose(1, 0, 2)).reshape(size, m * dim) / scale
            coeffs = probe._centring(probe._own.T @ pt)  # (A, m·d)
            for _ in range(order):
                coeffs = probe._d @ coeffs
            sh = probe.shape
            out = ak.evaluate(coeffs, tau, sh.omega0, sh.powers, sh.harmonics, sh.hyperbolic)
            out = (out.T.reshape(tau.size, m, dim).transpose(1, 0, 2)) * scale
        val.finite_result(out, "p(t)" if order == 0 else f"the derivative of order {order}")
        result: np.ndarray = out[:, 0] if scalar else out
        return result

    @property
    def curve_class(self) -> type[CBezierCurve]:
        """CBezierCurve with this family as its class's `family_object` (what from_json
        builds a curve of this family through)."""
        return type(f"{self.name}Curve", (CBezierCurve,), {"family_object": self})

    def start_coefficients(self, alpha: object, orders: int) -> list[list[float]]:
        """s[r][j] = b_j^(r)(0) in the family's own parameter at alpha, r = 0..orders (what a
        join into this family solves with: _atom_joins)."""
        x = self.check_alpha(alpha)
        rep = self.representation(x)
        rate = x if self.form == "unit" else 1.0  # the own atoms are cos(m rate u), u^k
        cycle = {
            "cos": (1, 0, -1, 0),
            "sin": (0, 1, 0, -1),
            "cosh": (1, 0, 1, 0),
            "sinh": (0, 1, 0, 1),
        }
        rows = []
        for r in range(orders + 1):
            at = []
            for kind, m in rep.layout:  # the r-th derivative of each own atom at 0
                if kind == "pow":
                    at.append(float(math.factorial(m)) if r == m else 0.0)
                else:
                    name = (kind + "h") if self.hyperbolic else kind
                    at.append((m * rate) ** r * cycle[name][r % 4])
            rows.append([float(v) for v in rep.own @ np.array(at)])
        return rows

    def parameter_value(self, lam: object, params: object, named: dict[str, object]) -> float:
        """The new segment's alpha in a join: ``params={"alpha": ...}`` or join's ``lam``
        (join's own ``alpha`` is the G-joint constant)."""
        given: dict[str, object] = {}
        if params is not None:
            if not isinstance(params, dict):
                raise TypeError("params must be a dict {name: value}")
            given.update(params)
        given.update(named)
        if lam is not None:
            if self.parameter in given:
                raise TypeError(f"{self.parameter} is given twice; give it once")
            given[self.parameter] = lam
        unknown = sorted(set(given) - {self.parameter})
        if unknown:
            raise TypeError(f"{unknown[0]!r} is not a parameter of {self.name!r}")
        if self.parameter not in given:
            raise ValueError(
                f"a {self.name} segment needs its parameter: params={{{self.parameter!r}: ...}} "
                "(or lam=...; join's own alpha is the G-joint constant)"
            )
        return self.check_alpha(given[self.parameter])

    def energy_minimum(self, points: PointsLike, k: int) -> dict[str, Any]:
        """The certified least E_k over the range, as {"values", "energy", "boundary",
        "lower_bound", "method"} (what `optimal_parameters` answers for this family): E_k in
        the family's own parameter (t on [0, alpha]; u on [0, 1] for a family written on
        [0, 1], that is alpha**(2k-1) times the energy in t), its
        minimum certified by branch and bound on Taylor models of the document's exact
        Gram entries (`_cbezier_optimum`): `lower_bound` is a proven lower bound over the
        whole range, within 1e-12 (relative to max(1, E)) of `energy`, which is E_k at
        `values` to about 2^-200. Certified, not exact: the entries are in
        Q(alpha, sin alpha, cos alpha)."""
        from . import _cbezier_optimum as opt

        if isinstance(k, bool) or not isinstance(k, int) or k not in self._exact_energies:
            raise ValueError(f"k must be one of {sorted(self._exact_energies)}, got {k!r}")
        pts = val.as_points(points, family=self.name, degrees=(self.degree,))
        given = val.exact_rows(points)
        rows = (
            [tuple(Fraction(v) for v in row) for row in given]
            if given is not None
            else [tuple(Fraction(float(v)) for v in row) for row in pts]
        )
        extra = 2 * k - 1 if self.form == "unit" else 0
        energy = opt.energy_of(self._exact_energies[k], rows, self.hyperbolic, extra)
        if not energy.groups:
            raise ValueError(
                f"{self.parameter} has no effect on E_{k} of this polygon (E_{k} = 0 for every "
                f"{self.parameter}), so no optimal {self.parameter} exists"
            )
        inside = [
            r
            for r in self.verdicts.get("singular_points", [])
            if str(r.get("where", "")).startswith("inside")
        ]
        if inside:  # E_k has a pole there (or is not defined): no minimum over the range
            raise ValueError(
                f"optimal_parameters: the range {self.range_text} of {self.parameter} holds a "
                f"singular point of the family ({self.parameter} = {inside[0]['at']}: "
                f"{inside[0]['denominator']} = 0); choose a range without it"
            )
        lo, hi = self.range_ends
        got = opt.certified_minimum(energy, lo, hi, self.lo_closed, self.hi_closed)
        if not got["certified"]:
            best = float(got["value"][1]) if got["value"] else math.nan
            proven = got["lower"]
            shown = f"{float(proven):.17g}" if abs(proven) < 1e300 else "none"
            raise ValueError(
                f"optimal_parameters: the least E_{k} over {self.parameter} in "
                f"{self.range_text} was not certified within {opt.BUDGET} boxes (best "
                f"{best}, proven lower bound {shown})"
            )
        point, (e_lo, e_hi) = got["point"], got["value"]
        name = self.parameter
        end_lo, end_hi = opt.end_bounds(lo), opt.end_bounds(hi)
        boundary = ""
        if got["limit"] or point <= end_lo[1]:
            boundary = f"{name} = {lo} (lower end" + (
                ", excluded: not attained; the limit there)" if got["limit"] else ")"
            )
        elif point >= end_hi[0]:
            boundary = f"{name} = {hi} (upper end" + (
                ", excluded: not attained; the limit there)" if got["limit"] else ")"
            )
        return {
            "values": {name: float(point)},
            "energy": float((e_lo + e_hi) / 2),
            "boundary": boundary,
            "lower_bound": got["lower"],
            "method": "certified",
        }

    def optimal_alpha(self, points: PointsLike, k: int) -> dict[str, Any]:
        """{parameter: value, "energy", "where", "lower_bound"}: `energy_minimum`
        as a dict ("where" is "interior", "lower end" or "upper end")."""
        r = self.energy_minimum(points, k)
        where = (
            "interior"
            if not r["boundary"]
            else "lower end"
            if "(lower end" in r["boundary"]
            else "upper end"
        )
        return {
            self.parameter: r["values"][self.parameter],
            "energy": r["energy"],
            "where": where,
            "lower_bound": r["lower_bound"],
        }


class CBezierCurve(DomainGeometry):
    """A curve sum P_i b_i(.; alpha) of a CBezierFamily at one alpha, in the family's own
    parameter (t on [0, alpha], or u on [0, 1])."""

    intersects_curves = True
    has_rational_form = False

    @property
    def domain(self) -> tuple[float, float]:
        """(0, alpha), or (0, 1) for a family written on the unit interval."""
        return self._domain

    def __init__(self, family: CBezierFamily, points: PointsLike, alpha: float):
        n = family.degree
        self.family_object = family
        self.family = family.name
        self.alpha = alpha
        self.points = val.as_points(points, family=family.name, degrees=(n,))
        rep = family.representation(alpha)
        self.coefficient_error = rep.error
        # over `basis_atoms`: the document's atoms of t, or powers of u = t/alpha below the
        # series' threshold (CBezierFamily.representation)
        self.basis_coefficients = rep.coefficients
        self.basis_atoms = rep.atoms
        self._own = rep.own  # (n+1, A) over the own parameter's atoms
        self._own_layout = rep.layout
        unit = family.form == "unit"
        self._rate = alpha if unit else 1.0  # u on [0, 1]: t = alpha*u
        self._domain = (0.0, 1.0) if unit else (0.0, alpha)
        self._mid = 0.5 * self._domain[1]
        self.shape = _Shape(self._rate, rep.powers, rep.harmonics, family.hyperbolic)
        self._scale = val.power_of_two_scale(self.points)
        self._centred = self._centring(self._own.T @ (self.points / self._scale))
        self._d = ak.derivative_matrix(self._rate, rep.powers, rep.harmonics, family.hyperbolic)

    def __repr__(self) -> str:
        p = self.family_object.parameter
        return f"CBezierCurve({self.family}, {p}={self.alpha}, dimension={self.dimension})"

    def _layout(self) -> list[tuple[str, int]]:
        return self._own_layout

    def _centring(self, coeffs: np.ndarray) -> np.ndarray:
        """Coefficients over atoms of x to atoms of tau = x - mid."""
        from math import comb

        layout = self._layout()
        index = {atom: j for j, atom in enumerate(layout)}
        mid, w, hyp = self._mid, self._rate, self.family_object.hyperbolic
        out = np.zeros_like(coeffs)
        # the powers first (the layout starts with t^0..t^P in order): t^m = sum_i C(m, i)
        # mid^(m-i) tau^i, one (P+1, P+1) product (the series' curves have P up to ~31)
        top = max((m for kind, m in layout if kind == "pow"), default=-1)
        shift = np.zeros((top + 1, top + 1))
        for m in range(top + 1):
            for i in range(m + 1):
                shift[i, m] = comb(m, i) * mid ** (m - i)
        out[: top + 1] = shift @ coeffs[: top + 1]
        for j, (kind, m) in enumerate(layout):
            row = coeffs[j]
            if kind == "pow":
                continue
            x = m * w * mid
            ca, sa = (math.cosh(x), math.sinh(x)) if hyp else (math.cos(x), math.sin(x))
            ic, isn = index[("cos", m)], index[("sin", m)]
            if kind == "cos":  # cos(a + b) = ca cos b - sa sin b; cosh: ca cosh b + sa sinh b
                out[ic] += ca * row
                out[isn] += (sa if hyp else -sa) * row
            else:  # sin(a + b) = sa cos b + ca sin b (sinh likewise)
                out[ic] += sa * row
                out[isn] += ca * row
        return out

    lam = None  # no λ: its parameter is the domain's (JSON writes it under "parameters")

    def atom_parameter_values(self) -> dict[str, float]:
        """{parameter: alpha}, as the curves of families in several parameters give theirs."""
        return {self.family_object.parameter: self.alpha}

    # ------------------------------------------------------------------ the rational form
    def _rational_map(self) -> tuple[float, float, float]:
        """(kind 0 trig / 1 hyperbolic, a, b) of the map from s in [0, 1] to the centred angle
        theta = rate (x - mid): trig v = tan(theta/2) = a (2s - 1) with a = tan(alpha/4);
        hyperbolic z = e^theta = a + s (b - a)."""
        fam = self.family_object
        if fam.powers > 0:
            raise ValueError(
                f"the {self.family} family has no rational Bézier form: its space has t "
                "(a power of t is not a rational function of tan(t/2) or of e^t)"
            )
        half = self._rate * self.domain[1] / 2  # alpha/2 in both forms
        if fam.hyperbolic:
            return 1.0, math.exp(-half), math.exp(half)
        if not half < math.pi:
            raise ValueError(f"no rational form over an angle of 2*pi or more ({2 * half})")
        return 0.0, math.tan(half / 2), 0.0

    def t_of_s(self, s: ParamLike) -> np.ndarray | float:
        """The family's own parameter at the rational form's s in [0, 1]."""
        kind, a, b = self._rational_map()
        ss = np.asarray(s, dtype=float)
        theta = 2 * np.arctan(a * (2 * ss - 1)) if kind == 0 else np.log(a + ss * (b - a))
        out = self._mid + theta / self._rate
        return float(out) if out.ndim == 0 else out

    def s_of_t(self, t: ParamLike) -> np.ndarray | float:
        """The rational form's s at the family's own parameter t."""
        kind, a, b = self._rational_map()
        theta = self._rate * (np.asarray(t, dtype=float) - self._mid)
        out = (np.tan(theta / 2) / a + 1) / 2 if kind == 0 else (np.exp(theta) - a) / (b - a)
        return float(out) if np.ndim(out) == 0 else out

    def to_rational_bezier(self) -> Any:
        """The curve as a rational Bézier curve in s (`t_of_s`, `s_of_t`), for a family whose
        space has no power of t (1, cos mt, sin mt; or cosh, sinh): of degree 2M (M the
        highest harmonic), through v = tan(theta/2) (theta the angle about the middle of
        the domain) or z = e^theta, affine in s. The curve is N(s)/D(s) with
        D = (1 + v^2)^M or z^M; its weights are D's Bernstein coefficients and its points
        N's over them, from N and D at 2M + 1 Chebyshev points of s: **floats** (alpha's
        sin, cos and exp are irrational in general), not exact."""
        from math import comb

        from .rational import RationalBezierCurve

        kind, a, b = self._rational_map()
        n = 2 * self.family_object.harmonics
        nodes = (1 - np.cos(np.pi * (np.arange(n + 1) + 0.5) / (n + 1))) / 2
        if kind == 0:
            den = (1 + (a * (2 * nodes - 1)) ** 2) ** (n // 2)
        else:
            den = (a + nodes * (b - a)) ** (n // 2)
        values = np.atleast_2d(self.evaluate(np.clip(self.t_of_s(nodes), *self.domain)))
        bern = np.array(
            [[comb(n, i) * x**i * (1 - x) ** (n - i) for i in range(n + 1)] for x in nodes]
        )
        weights = np.linalg.solve(bern, den)
        if not np.all(weights > 0):
            raise ValueError(f"the rational form at {self.alpha} has weights that are not positive")
        numer = np.linalg.solve(bern, values * den[:, None])
        return RationalBezierCurve(numer / weights[:, None], weights / weights[0])

    def to_bezier(self) -> Any:
        """Refused: not a polynomial curve (export writes certified polynomial pieces)."""
        raise NotImplementedError(
            f"to_bezier is not available for this curve: a {self.family} curve is a sum of "
            "atoms (t and sin/cos or sinh/cosh of t), not a polynomial curve; "
            "lambda_bezier.export writes it as certified polynomial pieces"
        )

    def end_derivatives(self, orders: int) -> list[list[float]]:
        """The curve's derivatives of orders 0..orders at the end of its domain (a join from
        this curve: _atom_joins)."""
        hi = self.domain[1]
        return [[float(v) for v in self.derivative(hi, r)] for r in range(orders + 1)]

    # ------------------------------------------------------------------ evaluation
    def _tau(self, t: ParamLike, extrapolate: bool) -> tuple[np.ndarray, bool]:
        tt, scalar, small, big = val.parameter_range(t)
        lo, hi = self.domain
        slack = 4 * np.spacing(max(hi, 1.0))
        if not extrapolate and tt.size and (small < lo - slack or big > hi + slack):
            bad = small if small < lo - slack else big
            raise ValueError(f"t = {bad} is outside the curve's domain [0, {hi}]")
        return tt - self._mid, scalar

    def derivative(self, t: ParamLike, k: int = 1, *, extrapolate: bool = False) -> np.ndarray:
        """The k-th derivative in the family's own parameter."""
        if isinstance(k, bool) or not isinstance(k, int) or not 0 <= k <= 20:
            raise ValueError(f"k must be an integer in 0..20, got {k!r}")
        tau, scalar = self._tau(t, extrapolate)
        coeffs = self._centred
        for _ in range(k):
            coeffs = self._d @ coeffs
        sh = self.shape
        out = ak.evaluate(coeffs, tau, sh.omega0, sh.powers, sh.harmonics, sh.hyperbolic).T
        out = out * self._scale
        return out[0] if scalar else out

    def evaluate(self, t: ParamLike, *, extrapolate: bool = False) -> np.ndarray:
        return self.derivative(t, 0, extrapolate=extrapolate)

    def _basis_derivative(self, t: ParamLike, extrapolate: bool) -> tuple[np.ndarray, np.ndarray]:
        """(Σ_a |c_ai'| |atom_a(t)|, the control points): the rounding of C'(t), evaluated
        over the atoms, is relative to the atoms' terms (_speed_floor; AtomCurve's)."""
        tau, _ = self._tau(t, extrapolate)
        coeffs = self._d @ self._centring(self._own.T)
        sh = self.shape
        eye = np.eye(coeffs.shape[0])
        atoms = ak.evaluate(
            eye, np.atleast_1d(tau), sh.omega0, sh.powers, sh.harmonics, sh.hyperbolic
        )
        # the float basis coefficients carry a relative error up to coefficient_error (1e-14
        # at alpha = 2; below the series' threshold a few ulps): the computed C'(0) at a
        # stop is of that size
        inflate = 1.0 + self.coefficient_error / np.finfo(float).eps
        return inflate * (np.abs(coeffs).T @ np.abs(atoms)).T, self.points

    def control_points(self) -> list[tuple[float, ...]]:
        """The control points as tuples of floats."""
        return [tuple(float(v) for v in row) for row in self.points]

    def energy(self, k: int) -> float:
        """E_k = int |r^(k)|^2 in the family's own parameter (t on [0, alpha], or u on [0, 1]:
        the document's Gram matrices are in t on [0, alpha]), by 64-point Gauss-Legendre
        on the float coefficients (the integrand is smooth, of period 2*pi at most, on an
        interval of length <= the box's end: the rule is exact to rounding there). The exact
        Gram matrices (`CBezierFamily.energy_matrix`) cancel badly in floats away from
        large alpha (bound 1e-2 at alpha = 0.5), so they are not used here."""
        if k not in (1, 2, 3):
            raise ValueError(f"k must be 1, 2 or 3, got {k!r}")
        x, w = np.polynomial.legendre.leggauss(64)
        hi = self.domain[1]
        d = self.derivative(hi * (x + 1) / 2, k)
        return float(np.sum(w * np.sum(d * d, axis=1)) * hi / 2)

    # ------------------------------------------------------------------ geometry
    # (arc length, boxes, closest points, location, intersections: _curve_shared.DomainGeometry,
    # numeric: these curves have no rational form for a general alpha)
    def _domain_point(self, t: object, name: str) -> float:
        x = float(val.real_number(t, name, keep_exact=False))
        lo, hi = self.domain
        if not lo <= x <= hi:
            raise ValueError(f"{name} = {t} is outside the curve's domain [{lo}, {hi}]")
        return x

    def split(self, t: float) -> tuple[CBezierCurve, CBezierCurve]:
        """Two curves of the same family: on [0, t] and [t, end] of the own parameter, with
        alpha_1 = t (alpha*t on [0, 1]) and alpha_2 = alpha - alpha_1 (the space is invariant
        under shifts of t, and the basis spans it when it has as many functions as atoms)."""
        fam = self.family_object
        x = float(t)
        lo, hi = self.domain
        if not lo < x < hi:
            raise ValueError(f"split needs t inside (0, {hi}), got {t}")
        if len(fam.atoms) != fam.degree + 1:
            raise ValueError("split needs a basis of the whole space (as many atoms as functions)")
        cut = x * self._rate if fam.form == "unit" else x
        n = fam.degree
        # the piece's control points from the curve at n + 1 Chebyshev-Lobatto points of the
        # piece (the ends among them): the piece lies in the same space exactly, so this
        # collocation solve is exact up to rounding, whichever form (atoms or series) either
        # side is evaluated in
        share = (1 - np.cos(np.pi * np.arange(n + 1) / n)) / 2
        out = []
        for start, length in ((0.0, cut), (cut, self.alpha - cut)):
            probe = CBezierCurve(fam, np.zeros_like(self.points), length)
            own = share * (probe._domain[1])
            sh = probe.shape
            basis = ak.evaluate(
                probe._centring(probe._own.T),
                own - probe._mid,
                sh.omega0,
                sh.powers,
                sh.harmonics,
                sh.hyperbolic,
            )  # (n+1, nodes)
            values = self.evaluate(np.clip((start + share * length) / self._rate, lo, hi))
            ctrl = np.linalg.solve(basis.T, values)
            out.append(CBezierCurve(fam, ctrl, length))
        return out[0], out[1]
