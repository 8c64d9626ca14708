"""A family of the user's own: its definition file and the document `derive` made from it.

``load_family(FILE)`` reads the ``[family]`` table of FILE and the derived document
``<name>.derived.json`` beside it (written by ``lambda-bezier derive --family FILE``), checks
that the document was derived from exactly this definition, and returns a ``Family`` whose
curves have the API of the built-in classes. Nothing here imports SymPy, and nothing in either
file is run: the definition is only fingerprinted, the derived document is data (exact
rationals as strings).

>>> import lambda_bezier as lb
>>> from lambda_bezier import examples
>>> fam = lb.load_family(examples.path("nouri_saeidian.toml"))   # shipped, already derived
>>> fam.curve([(0, 0), (1, 2), (3, 2), (4, 0)], lam=0.5).evaluate(0.5)
array([2.  , 0.75])
"""

from __future__ import annotations

import os
import re
import sys
from collections.abc import Mapping
from fractions import Fraction
from pathlib import Path
from typing import TYPE_CHECKING, Any

from . import curves as _curves
from ._atom_document import AtomData

# re-exported: the document's readers lived here before _family_document
from ._family_document import FamilyData as FamilyData
from ._family_document import FixedData
from ._family_document import SeveralData as SeveralData

# re-exported: they lived here before derive needed them without numpy (issue #29)
from ._family_file import FamilyFileError as FamilyFileError
from ._family_file import definition_digest as definition_digest
from ._family_file import read_family_table as read_family_table
from ._validate import PointsLike
from .atom_family import AtomCurve
from .curves import BezierCurve, Curve, data_curve_class

if TYPE_CHECKING:
    from .surfaces import NetLike, Surface

FORMAT = 3  # the derived document's format this runtime writes and reads
# 2: one parameter, laid out as in 3; 4: non-polynomial families (atom_family)
READS = (2, 3, 4, 5)
MAX_DOCUMENT_BYTES = 50_000_000


def _exact_in_ranges(
    family: str,
    ranges: Mapping[str, tuple[Fraction, Fraction, bool, bool, str]],
    values: Mapping[str, object],
    check_range: bool,
) -> tuple[Fraction, ...]:
    """Parameter values as exact Fractions (a float at its exact binary value), each checked
    against its range (lo, hi, lo closed, hi closed, text) unless `check_range` is False."""
    from . import _validate as val

    out = []
    for name, v in values.items():
        x = val.real_number(v, name)
        lo, hi, lo_closed, hi_closed, text = ranges[name]
        inside = (lo < x or (lo == x and lo_closed)) and (x < hi or (x == hi and hi_closed))
        if check_range and not inside:
            raise ValueError(
                f"{name} = {v} is outside the {family} range {text}; pass "
                "check_range=False to use it anyway"
            )
        out.append(Fraction(x))
    return tuple(out)


class Family:
    """A shape-parameter family defined by data, with the toolkit of the built-in ones:
    ``curve(points, lam)`` gives a curve with the built-in classes' API; ``optimal_lambda``,
    ``join``, ``CompositeCurve`` and ``evaluate_many`` take the family object wherever they
    take a family name."""

    def __init__(
        self,
        data: FamilyData | SeveralData,
        definition: Path | None,
        title: str,
        parameter: str,
        table: dict[str, Any] | None = None,
        several: SeveralData | None = None,
    ):
        self.data = data
        self.several = several  # the tables of a family in several parameters
        self._classes: dict[tuple[Fraction, ...], type[Curve]] = {}
        self.definition = definition  # the definition file, or None (embedded in a JSON form)
        self.title = title
        self.parameter = parameter
        # the [family] table and its fingerprint: what a curve's JSON form names
        self.table: dict[str, Any] = dict(table or {})
        self.digest = definition_digest(self.table)
        camel = "".join(part.capitalize() for part in data.FAMILY.split("_"))
        origin = definition if definition is not None else "an embedded definition"
        doc = f"A curve of the family {data.FAMILY!r} ({title}), from {origin}."
        self.curve_class: type[Curve] = data_curve_class(
            data.FAMILY, f"{camel}Curve", data, doc, __name__, parameter
        )
        # what a curve's JSON form reads the definition from (one class per Family object)
        setattr(self.curve_class, "family_object", self)  # noqa: B010

    @property
    def name(self) -> str:
        return self.data.FAMILY

    @property
    def degrees(self) -> tuple[int, ...]:
        return self.data.DEGREES

    @property
    def range_text(self) -> str:
        if self.several is not None:
            return ", ".join(f"{x} in {r[4]}" for x, r in self.several.RANGES.items())
        return self.data.LAMBDA_RANGE_TEXT  # type: ignore[union-attr]

    @property
    def degree_offset(self) -> int:
        return self.data.DEGREE_OFFSET

    @property
    def parameters(self) -> tuple[str, ...]:
        """The shape parameters' names, in the definition's order."""
        if self.several is not None:
            return self.several.NAMES
        return (self.parameter,)

    def surface(
        self,
        net: NetLike,
        lam_u: Fraction | float | None = None,
        lam_v: Fraction | float | None = None,
        *,
        params_u: dict[str, Any] | None = None,
        params_v: dict[str, Any] | None = None,
        family_v: object = None,
        check_range: bool = True,
        **named: Any,
    ) -> Surface:
        """The tensor-product surface Σ P_ij b_i(u; x_u) b_j(v; x_v) of this family on a net
        of (m+1) x (n+1) control points: ``lam_u, lam_v`` for one parameter, or each
        direction's parameters by name, ``params_u={"lam": .., "mu": ..}`` or as keywords
        with the direction's suffix, ``lam_u=.., mu_u=.., lam_v=.., mu_v=..``; an indexed
        family one sequence per direction; an atom family u, v in its own domain
        (param_surfaces). `family_v`: another family in v (a family from load_family or a
        built-in family's name), e.g. a trigonometric family across a polynomial one; default
        this family."""
        from .param_surfaces import family_surface

        if named:
            params_u, params_v, lam_u, lam_v = self._suffixed_parameters(
                named, family_v, params_u, params_v, lam_u, lam_v
            )
        if isinstance(family_v, str):
            from .curves import family_class

            try:
                family_class(family_v)
            except ValueError as exc:
                raise ValueError(f"family_v: {exc}") from None
        pair: Any = self if family_v is None else (self, family_v)
        if type(self) is Family and self.several is None and params_u is params_v is None:
            from .surfaces import Surface

            if family_v is None or not hasattr(family_v, "atom_data"):
                return Surface(net, lam_u, lam_v, family=pair, check_range=check_range)
        return family_surface(
            net, pair, lam_u, lam_v, params_u=params_u, params_v=params_v, check_range=check_range
        )

    def _suffixed_parameters(
        self,
        named: dict[str, Any],
        family_v: object,
        params_u: dict[str, Any] | None,
        params_v: dict[str, Any] | None,
        lam_u: object,
        lam_v: object,
    ) -> tuple[Any, Any, Any, Any]:
        """surface()'s keywords NAME_u / NAME_v, each a parameter of that direction's family,
        folded into params_u / params_v (several parameters) or lam_u / lam_v (one); a
        TypeError naming the keyword for anything else or for a parameter given twice."""
        by_side: dict[str, dict[str, Any]] = {"u": dict(params_u or {}), "v": dict(params_v or {})}
        for key, value in named.items():
            stem, _, side = key.rpartition("_")
            if side not in ("u", "v") or not stem:
                raise TypeError(
                    f"surface() got an unexpected keyword argument {key!r} (a direction's "
                    "parameter is given as NAME_u or NAME_v, e.g. mu_u=..., or as "
                    "params_u={...})"
                )
            family = self if side == "u" or family_v is None else family_v
            names = tuple(getattr(family, "parameters", None) or ("lam",))
            if stem not in names:
                label = getattr(family, "name", family)
                raise TypeError(
                    f"{key}: {stem!r} is not a parameter of {label!r} (its parameters: "
                    f"{', '.join(names)})"
                )
            if stem in by_side[side]:
                raise TypeError(f"{key} is given twice ({key}= and params_{side}); give it once")
            by_side[side][stem] = value
        one = {
            side: len(tuple(getattr(fam, "parameters", None) or ("lam",))) == 1
            and getattr(fam, "several", None) is None
            for side, fam in (("u", self), ("v", self if family_v is None else family_v))
        }
        lams = {"u": lam_u, "v": lam_v}
        out: dict[str, Any] = {}
        for side in ("u", "v"):
            given = by_side[side]
            if not one[side] and lams[side] is not None and given:
                if "lam" in given:  # lam_u=... binds to the positional lam_u
                    raise TypeError(f"lam_{side} is given twice (lam_{side} and params_{side})")
                given = {"lam": lams[side], **given}  # a parameter named lam, with its fellows
                lams[side] = None
            if one[side] and given and (params_u if side == "u" else params_v) is None:
                if lams[side] is not None:
                    raise TypeError(
                        f"lam_{side} is given twice (lam_{side} and {next(iter(given))}_{side})"
                    )
                lams[side] = next(iter(given.values()))  # a one-parameter family's own name
                out[side] = None
            else:
                out[side] = given or None
        return out["u"], out["v"], lams["u"], lams["v"]

    def parameter_values(
        self,
        value: object = None,
        params: object = None,
        named: Mapping[str, object] | None = None,
    ) -> dict[str, object]:
        """{name: value} for every parameter, from a positional value, a `params` mapping or
        keyword arguments in the family's own names (``lam=`` too, for one parameter).
        TypeError naming the argument for a name the family does not have, a missing or a
        doubly given parameter."""
        names = self.parameters
        given: dict[str, object] = {}
        sources: dict[str, str] = {}

        def put(name: str, v: object, source: str) -> None:
            if name in given:
                raise TypeError(
                    f"{name} is given twice ({sources[name]} and {source}); give it once"
                )
            given[name], sources[name] = v, source

        if params is not None:
            if not isinstance(params, dict):
                raise TypeError(
                    f"params must be a dict {{name: value}}, not {type(params).__name__}"
                )
            for key, v in params.items():
                if key not in names:
                    raise TypeError(
                        f"params: {key!r} is not a parameter of {self.name!r} "
                        f"(its parameters: {', '.join(names)})"
                    )
                put(key, v, "params")
        for given_as, v in (named or {}).items():
            key = given_as
            if key == "lam" and "lam" not in names and len(names) == 1:
                key = names[0]  # `lam=` keeps working for one-parameter families
            elif key not in names:
                raise TypeError(
                    f"{key!r} is not a parameter of {self.name!r} (its parameters: "
                    f"{', '.join(names)}; or pass params={{name: value}})"
                )
            put(key, v, f"{given_as}=")
        if value is not None:
            if len(names) != 1:
                raise TypeError(
                    f"{self.name!r} has {len(names)} parameters: name them "
                    f"({', '.join(f'{x}=...' for x in names)}) or pass params={{...}}"
                )
            put(names[0], value, "the positional argument")
        missing = [x for x in names if x not in given]
        if missing:
            raise TypeError(
                f"a {self.name} curve needs its shape parameter"
                f"{'s' if len(missing) > 1 else ''} {', '.join(missing)} (as {missing[0]}=...)"
            )
        return {x: given[x] for x in names}

    def curve(
        self,
        points: PointsLike,
        value: Fraction | float | None = None,
        *,
        params: dict[str, Fraction | float] | None = None,
        check_range: bool = True,
        **named: Fraction | float,
    ) -> Curve:
        """Σ P_i b_i(t; parameters) with the family's degree-n basis (n + 1 points).

        The parameter by its own name (``fam.curve(points, mu=...)``), by ``params={"mu":
        ...}``, positionally, or as ``lam=`` (one-parameter families)."""
        values = self.parameter_values(value, params, named)
        if self.several is not None:
            return self._fixed_class(values, check_range)(points)
        (lam,) = values.values()
        return self.curve_class(points, lam, check_range=check_range)  # type: ignore[arg-type]

    def _fixed_class(self, values: dict[str, object], check_range: bool) -> type[Curve]:
        """The curve class of this family at these parameter values (exact: a float is
        taken at its exact binary value), cached per values."""

        assert self.several is not None
        key = _exact_in_ranges(self.name, self.several.RANGES, values, check_range)
        if key not in self._classes:
            shown = ", ".join(f"{n}={v}" for n, v in values.items())
            data = FixedData(self.several, key)
            cls = data_curve_class(
                self.name, self.curve_class.__name__, data, self.curve_class.__doc__ or ""
            )
            cls._has_lambda = False
            cls.several_family = self  # type: ignore[attr-defined]  # joins continue in it
            cls.parameter_values = dict(zip(self.parameters, key, strict=True))  # type: ignore[attr-defined]

            def shown_repr(c: Curve, shown: str = shown) -> str:
                return f"{type(c).__name__}(degree={c.degree}, dimension={c.dimension}, {shown})"

            cls.__repr__ = shown_repr  # type: ignore[method-assign]
            self._classes[key] = cls
        return self._classes[key]

    def from_bezier(
        self,
        bezier: BezierCurve,
        value: Fraction | float | None = None,
        *,
        params: dict[str, Fraction | float] | None = None,
        **named: Fraction | float,
    ) -> Curve:
        """A classical Bézier curve written in this family (Curve.from_bezier); the
        parameters as for `curve`."""
        values = self.parameter_values(value, params, named)
        if self.several is not None:
            return self._fixed_class(values, True).from_bezier(bezier)
        (lam,) = values.values()
        return self.curve_class.from_bezier(bezier, lam)  # type: ignore[arg-type]

    def __repr__(self) -> str:
        ranges = self.range_text if self.several else f"{self.parameter} in {self.range_text}"
        return f"Family({self.name!r}, degrees {self.degrees[0]}..{self.degrees[-1]}, {ranges})"


class IndexedFamily:
    """A family with one shape parameter per index, ``lam(i)`` (its number depends on the
    degree): per degree, the Family of that degree's parameters lam_a .. lam_b. A curve takes
    them as one sequence, ``fam.curve(points, lam=[...])``; ``optimal_parameters`` gives
    ``result["lam"]`` as a tuple."""

    def __init__(
        self,
        doc: dict[str, Any],
        definition: Path | None,
        title: str,
        table: dict[str, Any],
        where: str,
    ):
        try:
            self.index_name: str = str(doc["indexed"]["name"])
            by_degree = doc["by_degree"]
            self.by_degree: dict[int, Family] = {}
            for key, sub in by_degree.items():
                several = SeveralData(sub, f"{where}, degree {key}")
                self.by_degree[int(key)] = Family(
                    several, definition, title, several.NAMES[0], table, several
                )
                self.by_degree[int(key)].indexed_family = self  # type: ignore[attr-defined]
        except (KeyError, TypeError, ValueError, AttributeError) as exc:
            if isinstance(exc, FamilyFileError):
                raise
            raise FamilyFileError(f"{where}: not a derived family document ({exc!r})") from None
        if not self.by_degree:
            raise FamilyFileError(f"{where}: no degree")
        self.definition = definition
        self.title = title
        self.table: dict[str, Any] = dict(table)
        self.digest = definition_digest(self.table)
        self.several = None  # one Family per degree: `at_degree`
        # join weights in closed form in n, m (index-relative symbols), read by _derived_joins
        self.JOINS: Any = doc.get("joins")
        # what a curve's JSON form is read with (from_json): the lowest degree's class, whose
        # family_object leads back here through `indexed_family`
        self.curve_class = self.by_degree[min(self.by_degree)].curve_class

    @property
    def name(self) -> str:
        return next(iter(self.by_degree.values())).name

    @property
    def degrees(self) -> tuple[int, ...]:
        return tuple(sorted(self.by_degree))

    @property
    def parameters(self) -> tuple[str, ...]:
        return (self.index_name,)

    def at_degree(self, degree: int) -> Family:
        """The Family of degree n, in the plain parameters lam_a .. lam_b of that degree."""
        if degree not in self.by_degree:
            raise ValueError(
                f"points: {degree + 1} control points make degree {degree}; the family "
                f"{self.name!r} has degrees {self.degrees[0]}..{self.degrees[-1]}"
            )
        return self.by_degree[degree]

    def index_values(self, degree: int, values: object) -> dict[str, object]:
        """{lam_k: value} of degree n from a sequence of one value per index."""
        names = self.at_degree(degree).parameters
        if isinstance(values, str | bytes) or not hasattr(values, "__len__"):
            raise TypeError(
                f"{self.index_name} must be a sequence of {len(names)} numbers (one per index "
                f"of degree {degree}: {', '.join(names)}), not {type(values).__name__}"
            )
        seq = list(values)  # type: ignore[call-overload]
        if len(seq) != len(names):
            raise ValueError(
                f"{self.index_name}: degree {degree} has {len(names)} parameters "
                f"({', '.join(names)}), got {len(seq)} values"
            )
        return dict(zip(names, seq, strict=True))

    def curve(
        self,
        points: PointsLike,
        values: object = None,
        *,
        params: dict[str, object] | None = None,
        check_range: bool = True,
        **named: object,
    ) -> Curve:
        """Σ P_i b_i(t; lam_a..lam_b) of degree n = len(points) - 1: ``lam=[...]`` (the
        family's own name), one value per index of that degree, or ``params={"lam": [...]}``."""
        from . import _validate as val

        given = dict(params or {})
        for key, v in named.items():
            if key != self.index_name:
                raise TypeError(
                    f"{key!r} is not a parameter of {self.name!r} (its parameter: "
                    f"{self.index_name}, one value per index)"
                )
            if key in given:
                raise TypeError(f"{key} is given twice; give it once")
            given[key] = v
        if values is not None:
            if self.index_name in given:
                raise TypeError(f"{self.index_name} is given twice; give it once")
            given[self.index_name] = values
        unknown = sorted(set(given) - {self.index_name})
        if unknown:
            raise TypeError(f"params: {unknown[0]!r} is not a parameter of {self.name!r}")
        if self.index_name not in given:
            raise TypeError(
                f"a {self.name} curve needs its shape parameters {self.index_name}=[...]"
            )
        rows = val.as_points(points, family=self.name, degrees=self.degrees)
        degree = len(rows) - 1
        fam = self.at_degree(degree)
        return fam.curve(
            points,
            params=self.index_values(degree, given[self.index_name]),  # type: ignore[arg-type]
            check_range=check_range,
        )

    # one sequence of values per direction: lam_u=[...] or params_u={"lam": [...]}
    surface = Family.surface

    def __repr__(self) -> str:
        lo, hi = self.degrees[0], self.degrees[-1]
        return f"IndexedFamily({self.name!r}, degrees {lo}..{hi}, {self.index_name}(i) per index)"


class AtomFamily(Family):
    """A family of trigonometric, hyperbolic or mixed basis functions (format-4 document,
    atom_family): ``curve(points, lam=..., mu=...)`` gives an `AtomCurve` whose parameter is
    the family's own t on its domain (`domain_text`, e.g. ``[0, pi/2]``)."""

    def __init__(
        self,
        data: AtomData,
        definition: Path | None,
        title: str,
        table: dict[str, Any] | None = None,
    ):
        self.atom_data = data
        self.data = data  # type: ignore[assignment]
        self.several = None
        self.definition = definition
        self.title = title
        self.parameter = data.NAMES[0]
        self.table = dict(table or {})
        self.digest = definition_digest(self.table)
        camel = "".join(part.capitalize() for part in data.FAMILY.split("_"))
        doc = f"A curve of the family {data.FAMILY!r} ({title}), t in {data.DOMAIN_TEXT}."
        self.atom_curve_class: type[AtomCurve] = type(
            f"{camel}Curve", (AtomCurve,), {"__doc__": doc, "__module__": __name__}
        )
        self.curve_class = self.atom_curve_class  # type: ignore[assignment]
        setattr(self.curve_class, "family_object", self)  # noqa: B010

    @property
    def parameters(self) -> tuple[str, ...]:
        return self.atom_data.NAMES

    @property
    def range_text(self) -> str:
        return ", ".join(f"{x} in {r[4]!s}" for x, r in self.atom_data.RANGES.items())

    @property
    def space(self) -> str:
        """The space of the basis: "trigonometric", "hyperbolic", "mixed-trigonometric" or
        "mixed-hyperbolic"."""
        return self.atom_data.SPACE

    @property
    def domain(self) -> tuple[float, float]:
        """The interval of t (floats; `domain_text` gives it exactly)."""
        return self.atom_data.DOMAIN

    @property
    def domain_text(self) -> str:
        return self.atom_data.DOMAIN_TEXT

    def exact_values(
        self, values: Mapping[str, object], check_range: bool = True
    ) -> tuple[Fraction, ...]:
        """The parameter values as exact Fractions (a float at its exact binary value),
        checked against the ranges."""
        return _exact_in_ranges(self.name, self.atom_data.RANGES, values, check_range)

    def curve(  # type: ignore[override]
        self,
        points: PointsLike,
        value: Fraction | float | None = None,
        *,
        params: dict[str, Fraction | float] | None = None,
        check_range: bool = True,
        **named: Fraction | float,
    ) -> AtomCurve:
        """Σ P_i b_i(t; parameters), t on the family's domain; the parameters by name,
        `params={...}`, or positionally for a one-parameter family."""
        from . import _validate as val

        values = self.parameter_values(value, params, named)
        exact = all(val.is_exact_scalar(v) for v in values.values())
        return self.atom_curve_class(self, points, self.exact_values(values, check_range), exact)

    def from_bezier(self, *args: object, **kwargs: object) -> Curve:
        raise NotImplementedError(
            f"a {self.space} family does not contain the polynomial curves: a Bézier curve "
            "has no exact form in it"
        )

    def __repr__(self) -> str:
        return (
            f"Family({self.name!r}, {self.space}, degrees {self.degrees[0]}..{self.degrees[-1]}, "
            f"t in {self.domain_text}, {self.range_text})"
        )


def definition_toml(table: dict[str, Any]) -> str:
    """The ``[family]`` table as the text of a TOML file (a definition embedded in a curve's
    JSON form, written out for ``lambda-bezier derive --family``). The table's values are
    strings, integers and lists of strings (definition.py's schema); the text is read back
    and compared before it is returned."""
    import json

    if sys.version_info >= (3, 11):
        import tomllib
    else:  # pragma: no cover - Python 3.10
        import tomli as tomllib

    def value(v: object, key: str) -> str:
        if isinstance(v, str):  # a JSON string is a TOML basic string, but for DEL
            return json.dumps(v, ensure_ascii=False).replace("\x7f", "\\u007f")
        if isinstance(v, int) and not isinstance(v, bool):
            return str(v)
        if isinstance(v, list):
            return "[" + ", ".join(value(x, key) for x in v) + "]"
        raise FamilyFileError(f"definition key {key!r}: unexpected value {v!r}")

    lines = ["[family]"]
    for key, v in table.items():
        if not isinstance(key, str) or not re.match(r"^[A-Za-z0-9_-]{1,64}$", key):
            raise FamilyFileError(f"definition key {key!r} is not a plain TOML key")
        lines.append(f"{key} = {value(v, key)}")
    text = "\n".join(lines) + "\n"
    if tomllib.loads(text).get("family") != table:
        raise FamilyFileError("the definition does not survive a TOML round trip")
    return text


def _family_name(table: dict[str, Any], where: str) -> str:
    name = table.get("name")
    if not isinstance(name, str):
        raise FamilyFileError(f"{where}: the [family] table has no name")
    if not re.match(r"^[a-z][a-z0-9_]{0,39}$", name):
        raise FamilyFileError(f"{where}: [family] name {name!r} is not a lowercase identifier")
    return name


def _derived_family(
    table: dict[str, Any], where: str, doc_path: Path, command: str, definition: Path | None
) -> Family | IndexedFamily:
    """The Family of the definition `table` with the tables of the derived document at
    `doc_path`, which must have been derived from exactly this table (its fingerprint)."""
    import json  # imported here: `import lambda_bezier` stays light

    name = _family_name(table, where)
    if not doc_path.is_file():
        raise FamilyFileError(
            f"{where}: the family {name!r} has not been derived ({doc_path} is missing); "
            f"run `{command}`"
        )
    if doc_path.stat().st_size > MAX_DOCUMENT_BYTES:
        raise FamilyFileError(f"{doc_path}: larger than {MAX_DOCUMENT_BYTES} bytes")
    try:
        doc = json.loads(doc_path.read_text(encoding="utf-8"))
    except (OSError, ValueError) as exc:  # UnicodeDecodeError, JSONDecodeError are ValueErrors
        raise FamilyFileError(f"{doc_path}: not a derived family document ({exc})") from None
    except RecursionError:
        raise FamilyFileError(
            f"{doc_path}: not a derived family document (nested too deeply)"
        ) from None
    if not isinstance(doc, dict) or doc.get("format") not in READS:
        raise FamilyFileError(
            f"{doc_path}: derived by another version of lambda-bezier (format "
            f"{doc.get('format') if isinstance(doc, dict) else '?'}, this one reads {FORMAT}); "
            f"run `{command}`"
        )
    if doc.get("definition_sha256") != definition_digest(table) or doc.get("family") != name:
        raise FamilyFileError(
            f"{doc_path} was derived from another version of the definition in {where}; "
            f"run `{command}`"
        )
    title = table.get("title", "")
    title = title if isinstance(title, str) else ""
    if "indexed" in doc:
        return IndexedFamily(doc, definition, title, table, str(doc_path))
    if doc.get("format") == 5 and "orders" in doc:  # C-Bezier of several degrees
        from .cbezier_orders import CBezierOrders

        return CBezierOrders(doc, str(doc_path), title, table)  # type: ignore[return-value]
    if doc.get("format") == 5:  # C-Bezier on [0, alpha] (lambda_bezier.cbezier_family)
        from .cbezier_family import CBezierFamily

        return CBezierFamily(doc, str(doc_path), title, table)  # type: ignore[return-value]
    if doc.get("format") == 4:
        atom = AtomData(doc, str(doc_path))
        return AtomFamily(atom, definition, title, table)
    if "parameters" in doc:
        several = SeveralData(doc, str(doc_path))
        return Family(several, definition, title, several.NAMES[0], table, several)
    return Family(FamilyData(doc, str(doc_path)), definition, title, doc["parameter"], table)


def load_family(path: str | Path, derived: str | Path | None = None) -> Family | IndexedFamily:
    """The family defined in `path` (a TOML file with a ``[family]`` table), with the tables
    of its derived document (default: ``<name>.derived.json`` beside `path`).

    Refuses, naming the command to run, when the derived document is missing or was derived
    from another version of the definition."""
    for value, what in ((path, "path"), (derived, "derived")):
        if value is not None and not isinstance(value, str | os.PathLike):
            raise TypeError(f"{what} must be a file path (str or Path), got {type(value).__name__}")
    if isinstance(path, str) and path in _curves.FAMILIES and not Path(path).exists():
        raise FamilyFileError(
            f"{path}: a built-in family, not a file: lambda_bezier.builtin_family({path!r}) "
            "gives it as a family object (curve, surface)"
        )
    path = Path(path)
    table = read_family_table(path)
    name = _family_name(table, str(path))
    doc_path = (
        Path(derived) if derived is not None else path.resolve().parent / f"{name}.derived.json"
    )
    command = f"lambda-bezier derive --family {path}"
    return _derived_family(table, str(path), doc_path, command, path)


def family_from_definition(table: dict[str, Any], derived: str | Path) -> Family | IndexedFamily:
    """The family a ``[family]`` table defines (e.g. the one a curve's JSON form embeds), with
    the tables of the derived document `derived`, which must have been derived from exactly
    this table. No definition file is needed."""
    if not isinstance(table, dict):
        raise TypeError(f"table must be a [family] table (a dict), got {type(table).__name__}")
    derived = Path(derived)
    name = _family_name(table, "the embedded definition")
    command = (
        f"save the definition as {name}.toml and run `lambda-bezier derive --family {name}.toml`"
    )
    return _derived_family(table, f"the definition of {name!r}", derived, command, None)
