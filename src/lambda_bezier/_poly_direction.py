r"""One polynomial direction of a surface whose other direction is a trigonometric, hyperbolic
or mixed family (issues #30, #31: a surface with its own family in each direction).

A polynomial family at fixed parameter values is a curve class (the built-in classes, a
Family's `curve_class` at λ, a several-parameter family's `_fixed_class`, an indexed family's
at one degree): `direction_class` is the one place that resolves a direction's family and
parameters to that class, for `ParamSurface` and for `PolyProbe`.

`PolyProbe` gives that direction the interface `AtomSurface` reads from an atom direction's
identity curve: the basis functions and their derivatives at t (the identity curve's values:
row i of its control points is the unit vector e_i, so its values are the b_i), the domain
[0, 1], and the **rational form**: the family's basis in the Bernstein basis of degree N,
b_i = Σ_k B_ik B_k^N(t), is a rational Bézier form with every weight 1 (Σ_i B_ik = 1 because
the basis sums to one) and s = t, exact for exact parameters. So a trigonometric direction
across a polynomial one is exactly a tensor-product rational Bézier surface, and the box,
closest point, split and STEP export of `AtomSurface` go through it unchanged.
"""

from __future__ import annotations

from fractions import Fraction
from itertools import pairwise
from typing import Any, TypeGuard

import numpy as np
import numpy.typing as npt

from . import _validate as val
from ._validate import ParamLike
from .curves import Curve, _identity, family_class
from .surfaces import _lam, basis_to_bernstein_split, combine


def is_atom(family: object) -> bool:
    return hasattr(family, "atom_data")


def is_indexed(family: object) -> bool:
    return hasattr(family, "index_name") and hasattr(family, "at_degree")


def is_class(family: object) -> TypeGuard[type[Curve]]:
    """Whether a direction's family is a built-in curve class (not a family object)."""
    return isinstance(family, type) and issubclass(family, Curve)


def polynomial_family(family: object) -> Any:
    """A direction's polynomial family as the surfaces keep it: a family from load_family
    as given, a built-in family's name (or curve class) as its curve class."""
    if isinstance(family, str) or is_class(family):
        return family_class(family)
    return family


def by_name_family(family: object) -> Any:
    """The new patch's family where parameters go by name: a built-in name as its curve class,
    a curve class or a family from load_family as given; anything else a TypeError."""
    fam = polynomial_family(family)
    if is_class(fam) or hasattr(fam, "curve"):
        return fam
    raise TypeError(
        "family must be a built-in family's name, a curve class or a family from "
        f"lambda_bezier.load_family, got {type(family).__name__}"
    )


def family_name(family: Any) -> str:
    """The name of a direction's family (a Family's `name`, a curve class's `family`)."""
    return str(family.family if is_class(family) else family.name)


def family_degrees(family: Any) -> tuple[int, ...] | None:
    """The degrees a direction's family has (None: any degree, the classical Bézier)."""
    if is_class(family):
        return None if family._any_degree else tuple(family._data.DEGREES)
    return tuple(family.degrees)


def builtin_given(cls: type[Curve], lam: object, params: object) -> dict[str, object]:
    """{name: value} of a built-in class's direction: its one λ (`lam` or ``params={"lam":
    ..}``), none for the classical Bézier (TypeError naming the parameter)."""
    given = dict(params) if isinstance(params, dict) else {}
    if params is not None and not isinstance(params, dict):
        raise TypeError(f"params must be a dict {{name: value}}, not {type(params).__name__}")
    name = cls.parameter_name if cls._has_lambda else None
    unknown = sorted(set(given) - ({name, "lam"} if name else set()))
    if unknown:
        shown = f"its parameter: {name}" if name else "the classical Bézier takes none"
        raise TypeError(f"{unknown[0]!r} is not a parameter of {cls.family!r} ({shown})")
    values = list(given.values())
    if lam is not None:
        values.append(lam)
    if name is None:
        if values:
            raise TypeError(f"the {cls.family} direction takes no shape parameter")
        return {}
    if len(values) != 1:
        raise TypeError(f"the {cls.family} direction needs its {name}, once")
    return {name: values[0]}


def direction_class(
    family: Any, given: dict[str, object], degree: int, check_range: bool
) -> tuple[type[Curve], Fraction | float | None]:
    """(curve class, λ) of a polynomial direction of `degree` at its parameters: the class
    of the family at those values (λ None) or, for a one-parameter family, its class and λ."""
    if is_class(family):
        lam = next(iter(given.values()), None)
        return family, _lam(family, lam, family.parameter_name, check_range)
    if is_indexed(family):
        at = family.at_degree(degree)
        values = family.index_values(degree, given[family.index_name])
        return at._fixed_class(values, check_range), None
    if family.several is not None:
        return family._fixed_class(given, check_range), None
    lam = next(iter(given.values()))
    return family.curve_class, _lam(family.curve_class, lam, family.parameter, check_range)


class _PolyData:
    DOMAIN_TEXT = "[0, 1]"
    SPACE = "polynomial"


class _UnitForm:
    """The polynomial basis as a rational Bézier form: (control points, weights 1)."""

    def __init__(self, points: Any, exact: bool) -> None:
        self._points = points
        self._weights = tuple(Fraction(1) if exact else 1.0 for _ in points)

    def control_points(self) -> Any:
        return self._points

    def control_weights(self) -> Any:
        return self._weights


class PolyProbe:
    """A polynomial direction of an `AtomSurface`: the identity curve of its class at its
    parameters, read as an atom direction's probe (see the module's doc)."""

    data = _PolyData()
    domain = (0.0, 1.0)
    has_rational_form = True

    def __init__(
        self, family: Any, given: dict[str, object], degree: int, check_range: bool
    ) -> None:
        self.cls, self.lam = direction_class(family, given, degree, check_range)
        self.family = family_name(family)
        self.degree = degree
        rows = _identity(degree + 1)
        self.curve = self.cls(rows, self.lam) if self.cls._has_lambda else self.cls(rows)
        self.exact = not isinstance(self.lam, float)

    def make_curve(self, points: Any) -> Curve:
        """A curve of this direction's family at its parameters on `points`."""
        if self.cls._has_lambda:
            return self.cls(points, self.lam, check_range=False)
        return self.cls(points)

    def basis(self, t: ParamLike, order: int = 0, *, extrapolate: bool = True) -> np.ndarray:
        """(len(t), degree + 1): the k-th derivatives b_i^(k)(t)."""
        if order == 0:
            out: np.ndarray = self.curve.evaluate(t, extrapolate=extrapolate)
        else:
            out = self.curve.derivative(t, order, extrapolate=extrapolate)
        return out

    def bernstein(self) -> Any:
        """B (degree + 1) x (N + 1): b_i = Σ_k B_ik B_k^N (Fractions when exact)."""
        return combine(basis_to_bernstein_split(self.cls, self.degree), self.lam)

    def to_rational_bezier(self) -> _UnitForm:
        b = self.bernstein()
        if self.exact:
            return _UnitForm(tuple(zip(*b, strict=True)), True)
        arr = np.asarray(b, dtype=float)
        return _UnitForm(tuple(tuple(map(float, col)) for col in arr.T), False)

    def s_of_t(self, t: npt.ArrayLike) -> Any:
        return t

    def t_of_s(self, s: npt.ArrayLike) -> Any:
        return s

    def end_derivatives(self, order: int, at_end: bool) -> list[list[Any]]:
        """w[r][i] = b_i^(r) at t = 1 (at_end) or 0, r = 0..order: exact Fractions for exact
        parameters (the r-th hodograph's Bernstein coefficient at that end), else floats."""
        b: Any = self.bernstein()
        rows = [list(r) for r in b] if self.exact else np.asarray(b, dtype=float).tolist()
        zero: Any = Fraction(0) if self.exact else 0.0
        big = len(rows[0]) - 1
        out = []
        for r in range(order + 1):
            out.append([(row[-1] if at_end else row[0]) if row else zero for row in rows])
            rows = [[(big - r) * (x - y) for y, x in pairwise(row)] for row in rows]
        return out

    def crude_sup(self, order: int) -> np.ndarray:
        """A bound of sup |b_i^(order)| over [0, 1] per i: the largest |coefficient| of the
        order-th hodograph's Bernstein form (the convex hull property)."""
        b = np.asarray(self.bernstein(), dtype=float)  # (n + 1, N + 1)
        big = b.shape[1] - 1
        if order > big:
            return np.zeros(b.shape[0])
        coeffs = b
        for j in range(order):
            coeffs = (big - j) * np.diff(coeffs, axis=1)
        return np.asarray(np.abs(coeffs).max(axis=1))


def checked_degree(family: Any, degree: int, name: str) -> None:
    """ValueError naming the direction when `family` has no basis of `degree`."""
    degrees = family_degrees(family)
    if degrees is not None and degree not in degrees:
        raise ValueError(
            f"net, direction {name}: {degree + 1} control points make degree {degree}; the "
            f"family {family_name(family)!r} has degrees {degrees[0]}..{degrees[-1]}"
        )


def exact_value(x: object) -> bool:
    if isinstance(x, list | tuple):
        return all(val.is_exact_scalar(y) for y in x)
    return val.is_exact_scalar(x)


def shown(x: object) -> Fraction | float:
    """A parameter value as a surface reports it: exact as a Fraction, else a float."""
    got = val.real_number(x, "parameter")
    return got if val.is_exact_scalar(x) else float(got)


def direction_curve(family: Any, points: Any, given: dict[str, object]) -> Any:
    """The curve of a direction's family at its parameters on `points` (a column of a
    surface's net): `fam.curve` for a family from load_family; a built-in class with its λ."""
    if is_class(family):
        lam: Any = next(iter(given.values()), None)
        return family(points, lam, check_range=False) if family._has_lambda else family(points)
    return family.curve(points, params=given, check_range=False)
