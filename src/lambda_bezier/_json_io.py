"""JSON documents of curves and composites (lambda_bezier.export's to_json, from_json and
family_definition; the format is described in that module's docstring), and the shape
helpers the exporters share: which segments a shape has, whether it is a rational curve.
"""

from __future__ import annotations

import json
import math
import re
from fractions import Fraction
from pathlib import Path
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from collections.abc import Sequence

    from .atom_family import AtomCurve
    from .composite import CompositeCurve
    from .curves import Curve
    from .family import Family, IndexedFamily
    from .rational import RationalBezierCurve

    Shape = Curve | CompositeCurve | RationalBezierCurve  # what the exporters take

FORMAT_VERSION = 1


def _rational(obj: object) -> RationalBezierCurve | None:
    """obj when it is a rational Bézier curve (exported as one rational span)."""
    from .rational import RationalBezierCurve

    return obj if isinstance(obj, RationalBezierCurve) else None


def _segments(obj: object) -> tuple[Curve, ...]:
    from .atom_family import AtomCurve
    from .composite import CompositeCurve
    from .curves import Curve

    if isinstance(obj, CompositeCurve):
        return obj.segments  # type: ignore[return-value]  # AtomCurves have what JSON reads
    if isinstance(obj, Curve | AtomCurve) or hasattr(obj, "end_derivatives"):
        return (obj,)  # type: ignore[return-value]  # an AtomCurve has what JSON reads
    # a surface has its own writers (duck-typed: surfaces is imported only by those who use it)
    surface = hasattr(obj, "curve_at_u") and hasattr(obj, "to_bezier")
    hint = (
        "; a surface is written by lambda_bezier.surface_export (surface_to_json, "
        "to_step_surface, to_mesh_file)"
        if surface
        else ""
    )
    raise TypeError(
        "expected a lambda_bezier curve, RationalBezierCurve or CompositeCurve, got "
        f"{type(obj).__name__}{hint}"
    )


def _number_out(x: Fraction | float) -> str | float:
    if isinstance(x, Fraction):
        return str(x)
    return float(x)


def _number_in(x: object, where: str) -> Fraction | float:
    from .hazmat.numbers import parse_number

    if isinstance(x, bool) or not isinstance(x, str | int | float):
        raise ValueError(f"{where}: expected a number or a string 'p/q', got {x!r}")
    if isinstance(x, str):
        try:
            return parse_number(x)
        except ValueError as exc:
            raise ValueError(f"{where}: {exc}") from None
    if isinstance(x, int):
        return Fraction(x)
    if not math.isfinite(x):
        raise ValueError(f"{where}: {x} is not finite")
    return x


def _own_family(curve: Curve) -> Family | None:
    """The Family of a curve of a family defined by data (None for a built-in family)."""
    family: Family | None = getattr(type(curve), "family_object", None)
    if family is None:  # a curve of a family in several parameters, at fixed values
        family = getattr(type(curve), "several_family", None)
    return family


def _parameters_out(curve: Curve) -> dict[str, Any] | None:
    """{name: value} of a curve of a family in several parameters; an indexed family's
    (lam(i)) as {name: [value per index]}; None for every other curve."""
    values = getattr(type(curve), "parameter_values", None)
    if not isinstance(values, dict):
        return None
    indexed = getattr(_own_family(curve), "indexed_family", None)
    if indexed is not None:
        return {indexed.index_name: [_number_out(v) for v in values.values()]}
    return {name: _number_out(v) for name, v in values.items()}


def _definitions(curves: Sequence[Curve]) -> dict[str, Any]:
    """{name: {definition_digest, definition}} of the own families among `curves` (a curve
    whose family is not its class's, a C-Bézier curve, names it itself)."""
    out = class_definitions([type(c) for c in curves])
    for c in curves:
        family = getattr(c, "family_object", None)
        if getattr(type(c), "family_object", None) is None and hasattr(family, "digest"):
            entry = {"definition_digest": family.digest, "definition": family.table}  # type: ignore[union-attr]
            if out.setdefault(family.name, entry) != entry:  # type: ignore[union-attr]
                raise ValueError(
                    f"two different definitions of the family {family.name!r} in one document"  # type: ignore[union-attr]
                )
    return out


def class_definitions(classes: Sequence[type[Curve]]) -> dict[str, Any]:
    """{name: {definition_digest, definition}} of the own families among curve classes (a
    surface's two directions embed theirs as a curve's family does)."""
    out: dict[str, Any] = {}
    for cls in classes:
        family: Family | None = getattr(cls, "family_object", None)
        if family is None:
            continue
        entry = {"definition_digest": family.digest, "definition": family.table}
        if out.setdefault(family.name, entry) != entry:
            raise ValueError(
                f"two different definitions of the family {family.name!r} in one document"
            )
    return out


def _curve_dict(curve: Curve | AtomCurve | RationalBezierCurve) -> dict[str, Any]:  # JSON values
    out: dict[str, Any] = {
        "family": curve.family,
        "lambda": None if curve.lam is None else _number_out(curve.lam),
        "points": [[_number_out(v) for v in row] for row in curve.control_points()],
    }
    atom_values = getattr(curve, "atom_parameter_values", None)
    if atom_values is not None:  # a trigonometric/hyperbolic/mixed family: every parameter
        out["parameters"] = {name: _number_out(v) for name, v in atom_values().items()}
    else:
        params = _parameters_out(curve) if _rational(curve) is None else None  # type: ignore[arg-type]
        if params is not None:
            out["parameters"] = params
    rational = _rational(curve)
    if rational is not None:
        out["weights"] = [_number_out(w) for w in rational.control_weights()]
    return out


def to_json(obj: Shape, *, indent: int | None = 2) -> str:
    """The JSON form of a curve or composite (see the module docstring): exact numbers as
    strings, floats as JSON numbers; from_json reads it back exactly."""
    from .composite import CompositeCurve

    doc: dict[str, Any]
    definitions = {} if _rational(obj) is not None else _definitions(_segments(obj))
    if isinstance(obj, CompositeCurve):
        joints = [
            None
            if j is None
            else {"continuity": j.continuity, "alpha": _number_out(j.alpha), "d": _number_out(j.d)}
            for j in obj.joints
        ]
        doc = {
            "lambda_bezier": FORMAT_VERSION,
            "kind": "composite",
            "segments": [_curve_dict(s) for s in obj.segments],
            "joints": joints,
        }
    else:
        doc = {"lambda_bezier": FORMAT_VERSION, "kind": "curve", **_curve_dict(obj)}
    if definitions:
        doc["definitions"] = definitions
    text = json.dumps(doc, indent=indent, ensure_ascii=False)
    if indent is None:
        return text
    # one line per point (the numbers hold no spaces, brackets or braces)
    return re.sub(r"\[\s+([^\[\]{}]*?)\s+\]", lambda m: "[" + " ".join(m[1].split()) + "]", text)


def _curve_from(
    data: object,
    where: str,
    check_range: bool,
    own: dict[str, type[Curve]],
    rational: bool = False,
) -> Curve | RationalBezierCurve:
    """A curve from its JSON object: a built-in family, one of `own` (the document's own
    families), or a rational one only where `rational` (composites hold polynomial curves)."""
    from .curves import FAMILIES
    from .rational import RationalBezierCurve

    if not isinstance(data, dict):
        raise ValueError(f"{where}: expected an object with family, lambda and points")
    family = data.get("family")
    names = sorted(FAMILIES) + ([RationalBezierCurve.family] if rational else [])
    if not isinstance(family, str) or (family not in names and family not in own):
        raise ValueError(
            f"{where}.family must be one of {names} or a family of your own "
            f"passed as family= (from the shell: --family FILE), got {family!r}"
        )
    points = data.get("points")
    if not isinstance(points, list) or not all(isinstance(r, list) for r in points):
        raise ValueError(f"{where}.points must be a list of [x, y] or [x, y, z] lists")
    rows = [
        [_number_in(v, f"{where}.points[{i}][{c}]") for c, v in enumerate(row)]
        for i, row in enumerate(points)
    ]
    # one arithmetic per curve: exact only when every coordinate is
    if not all(isinstance(v, Fraction) for row in rows for v in row):
        rows = [[float(v) for v in row] for row in rows]
    if family == RationalBezierCurve.family:
        weights = data.get("weights")
        if not isinstance(weights, list):
            raise ValueError(f"{where}.weights must be a list of numbers, one per point")
        if data.get("lambda") is not None:
            raise ValueError(f"{where}.lambda must be null for a {family} curve")
        ws = [_number_in(w, f"{where}.weights[{i}]") for i, w in enumerate(weights)]
        if not all(isinstance(w, Fraction) for w in ws):
            ws = [float(w) for w in ws]
        return RationalBezierCurve(rows, ws)
    cls = own[family] if family in own else FAMILIES[family]
    lam = data.get("lambda")
    atom_family = getattr(getattr(cls, "family_object", None), "atom_data", None)
    if hasattr(getattr(cls, "family_object", None), "start_coefficients"):  # C-Bézier
        if lam is not None:
            raise ValueError(f"{where}.lambda must be null for a {family} curve (use parameters)")
        given = data.get("parameters")
        own_fam: Any = cls.family_object  # type: ignore[attr-defined]
        if not isinstance(given, dict) or set(given) != {own_fam.parameter}:
            raise ValueError(
                f"{where}.parameters must be an object {{{own_fam.parameter!r}: value}} for "
                f"{family}"
            )
        value = _number_in(given[own_fam.parameter], f"{where}.parameters")
        return own_fam.curve(rows, **{own_fam.parameter: value})  # type: ignore[no-any-return]
    if atom_family is not None:  # a trigonometric, hyperbolic or mixed family: parameters
        if lam is not None:
            raise ValueError(f"{where}.lambda must be null for a {family} curve (use parameters)")
        given = data.get("parameters")
        if not isinstance(given, dict):
            raise ValueError(f"{where}.parameters must be an object {{name: value}} for {family}")
        values = {str(k): _number_in(v, f"{where}.parameters[{k!r}]") for k, v in given.items()}
        fam: Any = cls.family_object  # type: ignore[attr-defined]
        return fam.curve(rows, params=values, check_range=check_range)  # type: ignore[no-any-return]
    if "parameters" in data and family in own:
        return _several_curve_from(data["parameters"], rows, cls, where, check_range)
    if not cls._has_lambda:  # the classical Bézier curve
        if lam is not None:
            raise ValueError(f"{where}.lambda must be null for a {family} curve")
        return cls(rows)
    if lam is None:
        raise ValueError(f"{where}.lambda is required for a {family} curve")
    return cls(rows, _number_in(lam, f"{where}.lambda"), check_range=check_range)


def _several_curve_from(
    given: object, rows: list[Any], cls: type[Curve], where: str, check_range: bool
) -> Curve:
    """A curve of a family in several parameters (or an indexed one) from its parameters."""
    fam = getattr(cls, "family_object", None)
    target: Any = getattr(fam, "indexed_family", None) or fam
    if target is None or not isinstance(given, dict):
        raise ValueError(f"{where}.parameters must be an object {{name: value}}")
    values: dict[str, Any] = {}
    for name, v in given.items():
        if isinstance(v, list):
            values[name] = [
                _number_in(x, f"{where}.parameters.{name}[{i}]") for i, x in enumerate(v)
            ]
        else:
            values[name] = _number_in(v, f"{where}.parameters.{name}")
    try:
        curve: Curve = target.curve(rows, params=values, check_range=check_range)
    except (TypeError, ValueError) as exc:  # the message names the parameter
        raise ValueError(f"{where}.parameters: {exc}") from None
    return curve


def _segment_from(
    data: object, where: str, check_range: bool, own: dict[str, type[Curve]]
) -> Curve | AtomCurve:
    from .atom_family import AtomCurve
    from .curves import Curve

    curve: object = _curve_from(data, where, check_range, own)
    # _curve_from offers no rational curve here; a family of atoms gives an AtomCurve
    assert isinstance(curve, Curve | AtomCurve) or hasattr(curve, "end_derivatives")
    return curve  # type: ignore[return-value]  # a C-Bézier curve has what JSON reads


def parse_json(text: str | bytes | bytearray) -> Any:
    """json.loads with every failure of untrusted text a ValueError: a syntax error, an
    integer past Python's digit limit, and nesting deeper than the recursion limit (a
    RecursionError from the decoder otherwise)."""
    try:
        return json.loads(text)
    except RecursionError:
        raise ValueError("not valid JSON: nested too deeply") from None
    except (TypeError, ValueError) as exc:  # json.JSONDecodeError is a ValueError
        raise ValueError(f"not valid JSON: {exc}") from None


def _load_document(text: str) -> dict[str, Any]:
    doc = parse_json(text)
    if not isinstance(doc, dict) or doc.get("lambda_bezier") != FORMAT_VERSION:
        raise ValueError(
            f'not a lambda-bezier JSON document: expected "lambda_bezier": {FORMAT_VERSION}'
        )
    return doc


def _embedded(doc: dict[str, Any]) -> dict[str, tuple[str, dict[str, Any]]]:
    """{name: (digest, table)} of the definitions a document embeds, each checked against
    its own fingerprint."""
    from .family import definition_digest

    definitions = doc.get("definitions", {})
    if not isinstance(definitions, dict):
        raise ValueError("definitions must be an object {name: {definition_digest, definition}}")
    out = {}
    for name, entry in definitions.items():
        where = f"definitions[{name!r}]"
        if not isinstance(entry, dict) or not isinstance(entry.get("definition"), dict):
            raise ValueError(f"{where}: expected an object with definition_digest and definition")
        table, digest = entry["definition"], entry.get("definition_digest")
        if table.get("name") != name:
            raise ValueError(f"{where}.definition names the family {table.get('name')!r}")
        if digest != definition_digest(table):
            raise ValueError(
                f"{where}: the definition does not match its definition_digest (edited?)"
            )
        out[name] = (digest, table)
    return out


def _given_families(
    family: object, embedded: dict[str, tuple[str, dict[str, Any]]]
) -> dict[str, Family | IndexedFamily]:
    """The families passed as family=, by name: Family objects, definition files (their
    derived document beside them) or derived documents (with the embedded definition)."""
    from .family import Family, IndexedFamily, family_from_definition, load_family

    if family is None:
        return {}
    items = list(family) if isinstance(family, list | tuple) else [family]
    out: dict[str, Family | IndexedFamily] = {}
    for item in items:
        fam: Any
        if isinstance(item, Family | IndexedFamily) or hasattr(item, "start_coefficients"):
            fam = item  # a CBezierFamily has name, digest and curve_class too
        elif isinstance(item, str | Path):
            path = Path(item)
            if path.name.endswith(".derived.json"):
                name = path.name[: -len(".derived.json")]
                if name not in embedded:
                    raise ValueError(
                        f"family={str(item)!r}: the document embeds no definition of {name!r} "
                        "(pass the definition file instead)"
                    )
                fam = family_from_definition(embedded[name][1], path)
            else:
                fam = load_family(path)
        else:
            raise TypeError(
                "family must be a Family (lambda_bezier.load_family), a definition file, its "
                f"derived document, or a list of them; got {type(item).__name__}"
            )
        out[fam.name] = fam
    return out


def _own_classes(
    doc: dict[str, Any], family: object, names: set[Any] | None = None
) -> dict[str, type[Curve]]:
    """The curve classes of the document's own families (those of its segments, or `names`),
    each checked against the fingerprint the document records; a family neither given nor
    built in is refused, saying how to load it."""
    from .curves import FAMILIES

    embedded = _embedded(doc)
    given = _given_families(family, embedded)
    from .rational import RationalBezierCurve

    if names is None:
        segs = doc.get("segments") if doc.get("kind") == "composite" else [doc]
        names = (
            {s["family"] for s in segs if isinstance(s, dict) and isinstance(s.get("family"), str)}
            if isinstance(segs, list)
            else set()
        )
    known = {*FAMILIES, RationalBezierCurve.family}  # _curve_from decides where each may stand
    out: dict[str, type[Curve]] = {}
    for name in sorted(n for n in names if isinstance(n, str) and n not in known):
        digest = embedded[name][0] if name in embedded else None
        if name not in given and digest is None:
            raise ValueError(
                f"family must be one of {sorted(FAMILIES)} or a family of your own passed as "
                f"family= (its definition file or Family; from the shell, --family FILE), "
                f"got {name!r}"
            )
        if name not in given:
            assert digest is not None  # the case without one is refused above
            raise ValueError(
                f"the family {name!r} is not built in: the document embeds its definition "
                f"(fingerprint {digest[:12]}): pass family={name}.derived.json (its derived "
                "document) or the family's definition file or Family; from the shell, --family "
                f"FILE. Without either, write the definition out with `lambda-bezier export "
                f"--format family INPUT.json {name}.toml` and run `lambda-bezier derive "
                f"--family {name}.toml`"
            )
        fam = given[name]
        if digest is not None and fam.digest != digest:
            origin = fam.definition if fam.definition is not None else "the given family"
            raise ValueError(
                f"{origin} defines another version of the family {name!r} (fingerprint "
                f"{fam.digest[:12]}) than the one this document was written with ({digest[:12]})"
            )
        out[name] = fam.curve_class
    return out


def family_definition(text: str, name: str | None = None) -> str:
    """The definition of an own family a JSON form embeds, as the text of a TOML family file
    (for `lambda-bezier derive --family`). `name` may be omitted when there is one."""
    from .family import definition_toml

    embedded = _embedded(_load_document(text))
    if not embedded:
        raise ValueError("the document embeds no family definition (only built-in families)")
    if name is None:
        if len(embedded) > 1:
            raise ValueError(f"name must be one of {sorted(embedded)}")
        name = next(iter(embedded))
    if name not in embedded:
        raise ValueError(f"name must be one of {sorted(embedded)}, got {name!r}")
    return definition_toml(embedded[name][1])


def from_json(text: str, *, check_range: bool = True, family: object = None) -> Shape:
    """A curve or CompositeCurve from its JSON form (see the module docstring).

    `family` names the families of the user's own the document uses: a Family from
    `load_family`, a definition file, its derived document, or a list of them. A built-in
    family needs nothing."""
    from .composite import CompositeCurve
    from .joins import Joint

    doc = _load_document(text)
    kind = doc.get("kind")
    if kind == "surface":  # before _own_classes, which reads a curve's "family" (a str)
        raise ValueError(
            "a surface document: read it with lambda_bezier.surface_export.surface_from_json"
        )
    own = _own_classes(doc, family)
    if kind == "curve":
        return _curve_from(doc, "curve", check_range, own, rational=True)
    if kind != "composite":
        raise ValueError(f'"kind" must be "curve" or "composite", got {kind!r}')
    segs = doc.get("segments")
    if not isinstance(segs, list) or not segs:
        raise ValueError("composite.segments must be a non-empty list")
    curves = [_segment_from(s, f"segments[{i}]", check_range, own) for i, s in enumerate(segs)]
    joints_in = doc.get("joints", [None] * (len(curves) - 1))
    if not isinstance(joints_in, list):
        raise ValueError("composite.joints must be a list (null for a joint not built by join)")
    joints: list[Joint | None] = []
    for i, j in enumerate(joints_in):
        if j is None:
            joints.append(None)
            continue
        if not isinstance(j, dict) or "continuity" not in j:
            raise ValueError(f"joints[{i}] must be null or an object with continuity, alpha, d")
        joints.append(
            Joint(
                j["continuity"],
                _number_in(j.get("alpha", "1"), f"joints[{i}].alpha"),
                _number_in(j.get("d", "0"), f"joints[{i}].d"),
            )
        )
    return CompositeCurve(curves, joints)


# Their documented home is lambda_bezier.export (docs, pickles and introspection name it)
for _public in (to_json, from_json, family_definition):
    _public.__module__ = "lambda_bezier.export"
