"""The built-in families (bezier, same_degree, bernstein_like) as family objects, with the
methods a family from `load_family` has: ``fam = builtin_family("same_degree")``, then
``fam.curve(points, lam=...)`` and ``fam.surface(net, lam_u, lam_v)``.

The object *is* the family's name (a `str` subclass, equal to and hashed as the name), so
every function that takes a family (``optimal_lambda``, ``join``, ``evaluate_many``,
``Surface``, ``optimal_parameters``...) takes it exactly as it takes the name, on the same
fast paths of the generated tables.

Examples
--------
>>> import lambda_bezier as lb
>>> fam = lb.builtin_family("same_degree")
>>> fam
BuiltinFamily('same_degree', lam in (-2, 1])
>>> fam.curve([(0, 0), (1, 2), (3, 2), (4, 0)], lam=0).evaluate(0.5)
array([2., 1.])
>>> net = [[(i, j, (i * j) % 3) for j in range(4)] for i in range(4)]
>>> surf = fam.surface(net, 0, 0.5)
>>> type(surf).__name__, surf.evaluate(0.5, 0.5).shape
('SameDegreeSurface', (3,))
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

from .builtin_surfaces import most_specific
from .curves import FAMILIES, Curve, family_class
from .surfaces import NetLike, Surface


class BuiltinFamily(str):
    """A built-in family as a family object (see the module): the name, with methods."""

    __slots__ = ()

    def __new__(cls, name: str) -> BuiltinFamily:
        family_class(name)  # a built-in name, or the ValueError naming the choices
        return super().__new__(cls, name)

    @property
    def name(self) -> str:
        return str(self)

    @property
    def curve_class(self) -> type[Curve]:
        """The built-in curve class (SameDegreeCurve, BernsteinLikeCurve, BezierCurve)."""
        return family_class(str(self))

    @property
    def parameters(self) -> tuple[str, ...]:
        """The shape parameter's name, or () for the classical Bézier family."""
        cls = self.curve_class
        return (cls.parameter_name,) if cls._has_lambda else ()

    @property
    def range_text(self) -> str:
        """The parameter's range as its paper states it ('' without a parameter)."""
        return str(self.curve_class._data.LAMBDA_RANGE_TEXT) if self.parameters else ""

    def _value(self, value: object, named: dict[str, Any], params: dict[str, Any] | None) -> Any:
        given = dict(params or {}) | named
        if value is not None:
            given.setdefault("value", value)
        if not self.parameters:
            if given:
                raise TypeError(f"the {self.name} family has no shape parameter: got {given}")
            return None
        (name,) = self.parameters
        unknown = set(given) - {name, "value", "lam"}
        if unknown:
            raise TypeError(
                f"the {self.name} family's parameter is {name!r}: got {', '.join(sorted(unknown))}"
            )
        values = [v for v in given.values()]
        if len(values) != 1:
            raise TypeError(f"give the {self.name} family's parameter {name!r} once")
        return values[0]

    def curve(
        self,
        points: Any,
        value: Fraction | float | None = None,
        *,
        params: dict[str, Fraction | float] | None = None,
        check_range: bool = True,
        **named: Fraction | float,
    ) -> Curve:
        """The family's curve on `points`: the parameter positionally, by name
        (``lam=``), or as ``params={"lam": ...}``; none for the Bézier family."""
        lam = self._value(value, named, params)
        if not self.parameters:
            return self.curve_class(points)
        return self.curve_class(points, lam, check_range=check_range)

    def surface(
        self,
        net: NetLike,
        lam_u: Fraction | float | None = None,
        lam_v: Fraction | float | None = None,
        *,
        check_range: bool = True,
    ) -> Surface:
        """The tensor-product surface of this family on a net of (m+1) x (n+1) points, with
        its own parameter in each direction (none for the Bézier family)."""
        cls = self.curve_class
        return most_specific(net, lam_u, lam_v, classes=(cls, cls), check_range=check_range)

    def __repr__(self) -> str:
        shown = f", {self.parameters[0]} in {self.range_text}" if self.parameters else ""
        return f"BuiltinFamily({self.name!r}{shown})"


def builtin_family(name: str) -> BuiltinFamily:
    """The built-in family `name` ('bezier', 'same_degree' or 'bernstein_like') as a family
    object with ``curve`` and ``surface``; a ValueError naming the choices otherwise."""
    if not isinstance(name, str):
        raise TypeError(f"name must be a built-in family's name (a str), got {name!r}")
    if name not in FAMILIES:
        raise ValueError(
            f"name: {name!r} is not a built-in family: choose one of "
            f"{', '.join(map(repr, FAMILIES))} (a family defined in a file: load_family)"
        )
    return BuiltinFamily(name)
