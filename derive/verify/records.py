"""Records files: read, validate and resolve before anything in them is evaluated.

A records file (derive/published/*.toml, or a user's own) is untrusted input. Loading it is a
pipeline of checks, each failing with a ``RecordsError`` that names the file, the record and
the key:

1. size, then TOML syntax (``tomllib``; the error names the line);
2. the JSON Schema of the records format (``jsonschema``): every key known, every value of its
   type, the schema version supported;
3. ids unique, every ``claim`` a known kind for its family, every cross-reference (``uses``,
   ``numerator``, ``denominator``, ``formula``) to a record of the same run;
4. every formula read by the records grammar (derive/grammar/formula.py), so a syntax error, an
   unknown name or a limit is reported here and not halfway through a run.

The format itself is documented in derive/published/README.md ("The records format").
"""

from __future__ import annotations

import sys
from collections.abc import Iterable, Iterator
from pathlib import Path

from sympy import preorder_traversal

from ..families import cbezier
from ..families.definition import (
    REFERENCE,
    DefinitionError,
    definition_from_table,
    rename_parameter,
)
from ..grammar import Interval, ParseError
from ..grammar.messages import schema_message
from .expr_parse import fn_name
from .expr_parse import parse as parse_formula  # cached: the checkers reuse each parse
from .registry import (
    FAMILIES,
    SEVERAL_FAMILIES,
    claim_kind,
    kind_problem,
    register_cbezier_family,
    register_defined_family,
    register_elementary_family,
    register_several_family,
)

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.10
    import tomli as tomllib

SCHEMA_VERSIONS = (1, 2)
MAX_FILE_BYTES = 2_000_000
MAX_RECORDS = 5_000


class RecordsError(ValueError):
    """A records file that cannot be read or validated (the message names file, record, key)."""


# --------------------------------------------------------------------------- the schema

_STR = {"type": "string"}
_INT = {"type": "integer"}
_STRS = {"type": "array", "items": _STR}
_POINTS = {"type": "array", "items": _STRS}  # [["x", "y"], ...] exact numbers as strings
_LEVELS = {"type": "array", "items": _POINTS}
_MATRIX = {"type": "array", "items": {"type": "array", "items": _INT}}
_NAMED_STRS = {"type": "object", "additionalProperties": _STR}


def _table(properties: dict, required: Iterable[str] = ()) -> dict:
    return {
        "type": "object",
        "properties": properties,
        "required": list(required),
        "additionalProperties": False,
    }


_EQUATION = _table(
    {"lhs": _STR, "rhs": _STR, "given": _NAMED_STRS, "where": _NAMED_STRS}, ["lhs", "rhs"]
)
_CASE = _table({"index": _STR, "value": _STR, "condition": _STR}, ["index", "value"])
_CURVE_SPEC = _table(
    {"curve": _STR, "degree": _STR, "shape": _STR, "points": _STR},
    ["curve", "degree", "shape", "points"],
)
_RATIO = _table(
    {"point": _STR, "start": _STR, "end": _STR, "ratio": {**_STRS, "minItems": 2, "maxItems": 2}},
    ["point", "start", "end", "ratio"],
)
_SMALL_DEGREE = {"type": "integer", "minimum": 0, "maximum": 12}
# one printed weight of a surface join: P2(row, j) = Σ weight · P1(n - k, j) (source "first")
_WEIGHT = _table(
    {"row": _INT, "source": {"enum": ["first", "second"]}, "k": _INT, "weight": _STR},
    ["row", "source", "k", "weight"],
)
_STEP = _table(
    {
        "parameter": _STR,
        "parameter_printed": _STR,
        "keep": {"enum": ["left", "right"]},
        "control_points": _POINTS,
        "levels": _LEVELS,
        "printed_sequence": _POINTS,
        "result": _POINTS,
    }
)

_BOUND = r"\s*[-+]?\d{1,30}(/\d{1,30})?\s*"  # an end of a parameter_range: an exact number

# The payload keys a record (and an erratum, which replaces them) may carry.
PAYLOAD = {
    "equations": {"type": "array", "items": _EQUATION},
    "conventions": {"type": "array", "items": _EQUATION},
    "convention": {"type": "array", "items": _EQUATION},
    "conventions_text": _STR,
    "cases": {"type": "array", "items": _CASE},
    "function": _STR,
    "index": _STR,
    "at": _STR,
    "order": {"type": "integer", "minimum": 0, "maximum": 20},
    "first": _CURVE_SPEC,
    "second": _CURVE_SPEC,
    "constants": _STR,
    "uses": _STRS,
    "ratios": {"type": "array", "items": _RATIO},
    "row": _STRS,
    "matrix": _MATRIX,
    "points": _STRS,
    "argmax": _STR,
    "degree": {"type": "integer", "minimum": 0, "maximum": 64},
    "parameter": _STR,
    "control_points": _POINTS,
    "levels": _LEVELS,
    "left": _POINTS,
    "right": _POINTS,
    "t1": _STR,
    "t2": _STR,
    "result": _POINTS,
    "step1": _STEP,
    "step2": _STEP,
    "conclusions": _NAMED_STRS,
    "name": {"enum": ["X", "Y"]},
    "scale": _STR,
    "formula": _STR,
    "numerator": _STR,
    "denominator": _STR,
    "vector": _STRS,
    "printed_form": _STR,
    "lambda": _STR,
    # property claims (derive/verify/checks_properties.py) and worked examples checked against
    # a range
    "parameter_range": {
        "type": "string",
        "pattern": rf"^\s*[\(\[]{_BOUND},{_BOUND}[\)\]]\s*$",
        # what a user is told instead of the pattern (grammar/messages.py)
        "description": 'an interval with exact ends in brackets, such as "(-2, 1]" or '
        '"[-1, 1/2)" (ASCII digits: integers or fractions p/q)',
    },
    "min_degree": {"type": "integer", "minimum": 0, "maximum": 64},
    "shape": _STR,
    "claimed_degree": _STR,
    "count": _STR,
    "counted": _STR,
    "continuity": {"enum": ["C0", "C1", "C2", "G1", "G2"]},
    "expression": _STR,
    "sign": {"enum": ["positive", "nonnegative", "nonzero"]},
    # surface claims (derive/verify/checks_surfaces.py)
    "degrees": {"type": "array", "items": _SMALL_DEGREE, "minItems": 2, "maxItems": 2},
    "family_v": {"type": "string", "pattern": r"^[a-z][a-z0-9_]*$"},
    "second_family": {"type": "string", "pattern": r"^[a-z][a-z0-9_]*$"},
    "lam_u": _STR,
    "lam_v": _STR,
    # ... of a family in several parameters (checks_surfaces_several.py), in its own names
    "parameters_u": _NAMED_STRS,
    "parameters_v": _NAMED_STRS,
    "uv": {**_STRS, "minItems": 2, "maxItems": 2},
    "values": _POINTS,
    "sums_to_one": {"type": "boolean"},
    "side": {"enum": ["u=0", "u=1", "v=0", "v=1"]},
    "line": {"type": "string", "pattern": r"^(row|column) (\d{1,2}|m|n)$"},
    "corners": {
        "type": "array",
        "items": {"type": "array", "items": _INT, "minItems": 4, "maxItems": 4},
    },
    "weights": {"type": "array", "items": _WEIGHT},
    "energy": {"enum": ["membrane", "thin_plate"]},
    "term": {"type": "array", "items": _INT, "minItems": 2, "maxItems": 2},
    # claims about a family in several parameters (derive/verify/checks_several.py)
    "swap": _NAMED_STRS,
    "parameters": _NAMED_STRS,
    "gram": {"type": "array", "items": _STRS},
    # trigonometric, hyperbolic and mixed families (derive/verify/checks_elementary.py)
    "substitution": {"enum": ["tan(t/2)", "tanh(t/2)"]},
    "rational_weights": _STRS,
    "rational_numerators": {"type": "array", "items": _STRS},
    "nonnegative": {"type": "boolean"},
    "independent": {"type": "boolean"},
    "box": _NAMED_STRS,
    # join weights of such families (derive/verify/checks_joins_several.py)
    "pair": {"type": "string", "pattern": r"^[a-z][a-z0-9_]*>[a-z][a-z0-9_]*$"},
    "join_weights": _NAMED_STRS,
}

_RECORD = _table(
    {
        "id": {"type": "string", "minLength": 1, "maxLength": 200},
        "claim": {
            "type": "string",
            "pattern": r"^([a-z][a-z0-9_]*\.)?[a-z][a-z0-9_]*$",
            "description": 'a claim kind, such as "endpoint_curve" or '
            '"my_family.endpoint_curve" (lower-case letters, digits and _)',
        },
        "source": _STR,
        "location": _STR,
        "note": _STR,
        "variable": _STR,
        "family": {
            "type": "string",
            "pattern": r"^[a-z][a-z0-9_]*$",
            "description": 'a family name, such as "my_family" (lower-case letters, digits and _)',
        },
        "point_function": _STR,
        "domain": _STR,
        "ambiguous": _STR,
        "expect": {"enum": ["match", "mismatch", "caveat", "pending"]},
        "n": {"type": "integer", "minimum": 0, "maximum": 64},
        "k": {"type": "integer", "minimum": 0, "maximum": 20},
        "erratum": {
            "type": "object",
            "properties": {
                "origin": _STR,
                "explanation": {"type": "string", "minLength": 1},
                **PAYLOAD,
            },
            "required": ["explanation"],
            "additionalProperties": False,
        },
        **PAYLOAD,
    },
    ["id", "claim"],
)

SCHEMA = {
    "$schema": "https://json-schema.org/draft/2020-12/schema",
    "title": "lambda-bezier records file",
    "type": "object",
    "properties": {
        "schema_version": {"enum": list(SCHEMA_VERSIONS)},
        "source": _STR,
        "title": _STR,
        # the default family of the records: a name, or the definition of a family of the
        # user's own (a [family] table, validated by derive/families/engine.py)
        "family": {
            "oneOf": [{"type": "string", "pattern": r"^[a-z][a-z0-9_]*$"}, {"type": "object"}]
        },
        "variable": _STR,
        "point_function": _STR,
        "record": {"type": "array", "items": _RECORD, "maxItems": MAX_RECORDS},
    },
    "required": ["schema_version", "record"],
    "additionalProperties": False,
}

# String values that are free text or names, never formulas.
TEXT_KEYS = frozenset(
    {
        "id",
        "claim",
        "source",
        "location",
        "note",
        "variable",
        "family",
        "point_function",
        "domain",
        "ambiguous",
        "expect",
        "conventions_text",
        "condition",
        "constants",
        "uses",
        "formula",
        "numerator",
        "denominator",
        "name",
        "keep",
        "curve",
        "printed_form",
        "parameter_printed",
        "origin",
        "explanation",
        "parameter_range",
        "continuity",
        "sign",
        "family_v",
        "second_family",
        "side",
        "line",
        "energy",
        "substitution",
    }
)


# --------------------------------------------------------------------------- loading


def _where(path: Path, rec: dict | None, key: str = "") -> str:
    out = str(path)
    if rec is not None:
        out += f": record {rec.get('id', '?')!r}"
    if key:
        out += f", key {key}"
    return out


def _key_path(parts: Iterable) -> str:
    out = ""
    for p in parts:
        out += f"[{p}]" if isinstance(p, int) else (f".{p}" if out else str(p))
    return out


def _toml(path: Path) -> dict:
    """The TOML of a file, within the size limit, every failure a RecordsError naming it."""
    try:
        size = path.stat().st_size
        if size > MAX_FILE_BYTES:
            raise RecordsError(f"{path}: {size} bytes, more than the {MAX_FILE_BYTES} allowed")
        text = path.read_bytes().decode("utf-8")
    except FileNotFoundError:
        raise RecordsError(f"{path}: no such file") from None
    except IsADirectoryError:
        raise RecordsError(f"{path}: is a directory, not a records file") from None
    except UnicodeDecodeError as exc:
        raise RecordsError(f"{path}: not UTF-8 text ({exc.reason} at byte {exc.start})") from None
    except OSError as exc:
        raise RecordsError(f"{path}: cannot be read ({exc.strerror})") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise RecordsError(f"{path}: not valid TOML: {exc}") from None
    except RecursionError:  # the decoder recurses on nested arrays and tables
        raise RecordsError(f"{path}: not valid TOML: nested too deeply") from None
    return data


def is_family_file(data: dict) -> bool:
    """A family definition in a file of its own: a [family] table and no records."""
    return isinstance(data.get("family"), dict) and "record" not in data


def read_file(path: Path, data: dict | None = None) -> dict:
    """The TOML of one records file, validated against SCHEMA."""
    import jsonschema

    data = _toml(path) if data is None else data
    validator = jsonschema.Draft202012Validator(SCHEMA)
    errors = sorted(validator.iter_errors(data), key=lambda e: list(map(str, e.absolute_path)))
    if errors:
        err = min(errors, key=lambda e: len(e.absolute_path) * -1)  # the deepest is the clearest
        parts = list(err.absolute_path)
        rec = None
        if len(parts) >= 2 and parts[0] == "record" and isinstance(parts[1], int):
            rec = data["record"][parts[1]] if isinstance(data["record"][parts[1]], dict) else {}
            parts = parts[2:]
        more = f" (and {len(errors) - 1} more problems)" if len(errors) > 1 else ""
        raise RecordsError(f"{_where(path, rec, _key_path(parts))}: {schema_message(err)}{more}")
    return data


def load_file(path: Path, data: dict | None = None) -> list[dict]:
    """The records of one file, each with its family, file, source and variable filled in."""
    data = read_file(path, data)
    if isinstance(data.get("family"), dict):
        data["family"] = _define_family(path, data["family"], data.get("point_function"))
    out = []
    for rec in data["record"]:
        rec = dict(rec)
        claim = rec["claim"]
        if "." in claim:
            family = claim.split(".", 1)[0]
            if rec.get("family", family) != family:
                raise RecordsError(
                    f"{_where(path, rec, 'claim')}: claim {claim!r} names family {family!r} but "
                    f"the record's family is {rec['family']!r}"
                )
        else:
            family = rec.get("family") or data.get("family")
            if not family:
                raise RecordsError(
                    f"{_where(path, rec, 'claim')}: claim {claim!r} names no family; write "
                    "<family>.<kind> or set `family` in the file"
                )
        problem = kind_problem(family, claim_kind(claim))
        if problem:
            raise RecordsError(f"{_where(path, rec, 'claim')}: {problem}")
        rec["family"] = family
        rec["claim"] = f"{family}.{claim_kind(claim)}"
        rec.setdefault("source", data.get("source", path.name))
        rec.setdefault("file", str(path))
        rec.setdefault("expect", "match")
        for key in ("variable", "point_function"):
            if key not in rec and key in data:
                rec[key] = data[key]
        if family in SEVERAL_FAMILIES:  # formulas in its own names: read by checks_several
            out.append(rec)
            continue
        if "n" in rec and rec["n"] not in FAMILIES[family].degrees and family != REFERENCE:
            raise RecordsError(
                f"{_where(path, rec, 'n')}: degree {rec['n']} is outside the {family} range "
                f"{FAMILIES[family].degrees.start}..{FAMILIES[family].degrees.stop - 1}"
            )
        degrees = FAMILIES[family].degrees if family in FAMILIES else range(0)
        if "min_degree" in rec and family != REFERENCE and rec["min_degree"] >= degrees.stop > 0:
            raise RecordsError(
                f"{_where(path, rec, 'min_degree')}: no degree of the {family} range "
                f"{degrees.start}..{degrees.stop - 1} is >= {rec['min_degree']}"
            )
        if "parameter_range" in rec:
            try:
                Interval.parse(rec["parameter_range"])
            except ValueError as exc:
                raise RecordsError(f"{_where(path, rec, 'parameter_range')}: {exc}") from None
        fam = FAMILIES.get(family)
        parameter = getattr(fam, "parameter", "lam")
        _parse_formulas(path, rec, parameter)
        _check_point_names(path, rec, parameter)
        _check_join_curves(path, rec, parameter)
        out.append(rec)
    return out


def _check_join_curves(path: Path, rec: dict, parameter: str = "lam") -> None:
    """A join record's `degree` and `shape` of each curve are symbols (n, m; lam1, lam2): the
    vertex formulas are checked symbolically in them and at every degree pair and parameter
    sample, which a number in their place cannot be (a degree "3" or shape "1/2" ended in an
    internal error of the compiled weights)."""
    seen: dict = {}
    for piece in ("first", "second"):
        spec = rec.get(piece)
        if not isinstance(spec, dict):
            continue
        for key in ("degree", "shape"):
            text = spec.get(key)
            if not isinstance(text, str):
                continue
            value = parse_formula(rename_parameter(text, parameter, lam_too=True))
            if not value.is_Symbol:
                raise RecordsError(
                    f"{_where(path, rec, f'{piece}.{key}')}: {text!r} must be a symbol "
                    f"({'n or m' if key == 'degree' else 'lam1 or lam2'}), not a number or a "
                    "formula: a join is checked for every degree and parameter"
                )
            if value in seen:
                raise RecordsError(
                    f"{_where(path, rec, f'{piece}.{key}')}: {text!r} is also "
                    f"{seen[value]}: the two curves need symbols of their own"
                )
            seen[value] = f"{'first' if piece == 'second' else 'second'}.{key}"


def _define_family(path: Path, table: dict, points: str | None) -> str:
    """Derive the family a records file defines and make it known to this run's checkers."""
    try:
        if cbezier.is_frequency_family(table):  # C-Bezier: checks_cbezier.py, exact in Q(A, S, C)
            cdefn = cbezier.read_table(table, str(path))
            register_cbezier_family(cdefn)
            return cdefn.name
        defn = definition_from_table(table, str(path))
        if defn.elementary:  # sin, cos, ...: checks_several.py's kinds, in exact atoms
            register_elementary_family(defn)
        elif defn.several:  # its records: checks_several.py's claim kinds
            register_several_family(defn)
        else:
            register_defined_family(defn, points)
    except DefinitionError as exc:
        raise RecordsError(
            str(exc) if str(exc).startswith(str(path)) else f"{path}: {exc}"
        ) from None
    return defn.name


def _strings(value, key: str) -> Iterator[tuple[str, str]]:
    """(key path, string) for every formula string inside a record value."""
    if isinstance(value, str):
        yield key, value
    elif isinstance(value, list):
        for pos, item in enumerate(value):
            yield from _strings(item, f"{key}[{pos}]")
    elif isinstance(value, dict):
        for name, item in value.items():
            if name not in TEXT_KEYS:
                yield from _strings(item, f"{key}.{name}")


def _formula_texts(rec: dict) -> Iterator[tuple[str, str]]:
    """(key path, formula text) for every formula of a record."""
    for name, value in rec.items():
        if name in TEXT_KEYS or name == "file":
            continue
        if name == "points" and isinstance(value, str):
            continue
        for key, text in _strings(value, name):
            if key.endswith(".points") or key.endswith(".curve"):
                continue  # names of the functions of a join's curves
            yield key, text


def renamed_record(rec: dict, parameter: str) -> dict:
    """The record with its formulas in the checkers' names: a family's own parameter name
    read as `lam` (token by token; the report shows the record as written)."""
    if parameter == "lam":
        return rec

    def walk(value, key: str):
        if isinstance(value, str):
            return rename_parameter(value, parameter, lam_too=True)
        if isinstance(value, list):
            return [walk(item, key) for item in value]
        if isinstance(value, dict):
            return {
                k: (v if k in TEXT_KEYS or k in ("points", "curve") else walk(v, k))
                for k, v in value.items()
            }
        return value

    return {
        name: value
        if name in TEXT_KEYS or name == "file" or (name == "points" and isinstance(value, str))
        else walk(value, name)
        for name, value in rec.items()
    }


_POINT_CALL_NAMES = ("P", "V")  # the grammar's control-point functions of one curve


def _parse_formulas(path: Path, rec: dict, parameter: str = "lam") -> None:
    for name, value in rec.items():
        if name in TEXT_KEYS or name == "file":
            continue
        if name == "points" and isinstance(value, str):
            continue
        for key, text in _strings(value, name):
            parts = [text]
            if key.endswith(".index") or ".where." in key or key == "counted":
                if text == "otherwise":
                    continue
                if ".." in text:
                    parts = text.split("..", 1)
            elif key.endswith(".points") or key.endswith(".curve"):
                continue  # names of the functions of a join's curves
            for part in parts:
                try:
                    parse_formula(rename_parameter(part, parameter, lam_too=True))
                except ParseError as exc:
                    hint = (
                        f" (the {rec['family']} family's shape parameter is {parameter})"
                        if parameter != "lam" and "unknown name" in str(exc)
                        else ""
                    )
                    raise RecordsError(f"{_where(path, rec, key)}: {exc}{hint}") from None


# The names a record may give control points: one-argument applications P(i), V(i). One rule
# for every pass (the symbolic closed-form comparison and the per-degree realiser would read a
# foreign name differently: as the points, or as an unknown function), so a name that is not
# the family's is refused here, before either runs.
POINT_NAMES = ("P", "V")


def _check_point_names(path: Path, rec: dict, parameter: str = "lam") -> None:
    points = rec.get("point_function") or FAMILIES[rec["family"]].points
    allowed = {points}
    for piece in ("first", "second"):  # a join record names its curves' points itself
        if isinstance(rec.get(piece), dict) and isinstance(rec[piece].get("points"), str):
            allowed.add(rec[piece]["points"])
    # the formulas the checkers realise (an energy_lambda_nk `vector` is the paper's D = (P_0
    # … P_n) whatever the family calls its points, and is compared with exactly that)
    for name in ("equations", "conventions", "convention", "cases"):
        for key, text in _strings(rec.get(name) or [], name):
            if key.endswith(".index") or ".where." in key or ".given." in key:
                continue  # index ranges and values, no points
            for app in preorder_traversal(
                parse_formula(rename_parameter(text, parameter, lam_too=True))
            ):
                found = fn_name(app)
                if found in POINT_NAMES and found not in allowed and len(app.args) == 1:
                    raise RecordsError(
                        f"{_where(path, rec, key)}: {app} names control points {found!r}, but "
                        f"the {rec['family']} family's control points are {points!r} here; "
                        f"set point_function = {found!r} in the file or the record to call "
                        f"them {found}"
                    )


def load_paths(paths: Iterable[Path]) -> list[dict]:
    """The records of several files, ids unique across them and cross-references resolved."""
    records: list[dict] = []
    texts = [(Path(path), _toml(Path(path))) for path in paths]
    # family definitions in files of their own first: a records file names them by `family`
    for path, data in texts:
        if is_family_file(data):
            _define_family(path, data["family"], None)
    for path, data in texts:
        if not is_family_file(data):
            records += load_file(path, data)
    seen: dict[str, str] = {}
    for rec in records:
        if rec["id"] in seen:
            raise RecordsError(
                f"{rec['file']}: record {rec['id']!r}, key id: duplicate id "
                f"(also in {seen[rec['id']]})"
            )
        seen[rec["id"]] = rec["file"]
    for rec in records:
        refs = [("uses", u) for u in rec.get("uses", [])] + [
            (key, rec[key]) for key in ("numerator", "denominator", "formula") if key in rec
        ]
        for key, rid in refs:
            if rid not in seen:
                raise RecordsError(
                    f"{rec['file']}: record {rec['id']!r}, key {key}: no record {rid!r} in this run"
                )
    return records
