"""A family definition as data: the [family] table, read and validated.

A family is a ``[family]`` table (in a file of its own or at the top of a records file) whose
``basis`` is a formula of the records grammar in i, n, t and the shape parameter, or a
``seed`` and a ``recursion``. Reading checks every key against a schema and every formula
against the grammar; nothing here evaluates a basis (derive/families/engine.py does).
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from fractions import Fraction
from functools import cache
from pathlib import Path

import sympy as sp

from ..grammar import BUILTINS, FUNCTIONS, SYMBOLS, Interval, ParseError, parse_formula, tokenize

FORMAT = 2  # version of the derived JSON document (2: with singular_parameters)
MAX_DEGREE = 20
MAX_OFFSET = 6
# The classical Bernstein basis (derive/algebra/bernstein.py) is every family's reference
# (to_bezier, bernstein_at), not a family defined by data; the built-in families are
# derive/families/*.toml.
REFERENCE = "bezier"
ENDPOINT_ORDERS = 3  # derivatives 0..3 at each end
ENERGY_ORDERS = (1, 2, 3)
CONTINUITIES = ("C1", "C2", "G1", "G2")


class DefinitionError(ValueError):
    """A family definition that cannot be read or does not define a basis (names the key)."""


# --------------------------------------------------------------------------- the definition

_NAME = r"^[a-z][a-z0-9_]{0,39}$"
SCHEMA = {
    "type": "object",
    "properties": {
        "name": {"type": "string", "pattern": _NAME},
        "title": {"type": "string", "maxLength": 500},
        "parameter": {"type": "string", "pattern": r"^[A-Za-z][A-Za-z0-9_]{0,19}$"},
        "range": {"type": "string", "maxLength": 200},
        "degrees": {"type": "string", "maxLength": 20},
        "bernstein_at": {"type": "string", "maxLength": 200},
        # the name records give the control points (P(i) by default; #32 item 3)
        # (the records grammar's point functions: P or V)
        "points": {"enum": ["P", "V"]},
        "degree_offset": {"type": "integer", "minimum": 0, "maximum": MAX_OFFSET},
        "basis": {"type": "string", "maxLength": 10_000},
        # or a recursion from a seed: the functions of the lowest degree, then b(i, n, t) in
        # terms of b(., n - 1, t) (e.g. 001's eqs. (1), (2))
        "seed": {
            "type": "array",
            "items": {"type": "string", "maxLength": 10_000},
            "minItems": 2,
            "maxItems": MAX_DEGREE + 1,
        },
        "recursion": {"type": "string", "maxLength": 10_000},
        "source": {"type": "string"},
        "note": {"type": "string"},
    },
    "required": ["name", "parameter", "range", "degrees", "degree_offset"],
    "additionalProperties": False,
}

# basis formulas are in i, n, t and the parameter, which is read as the symbol `lam` (the
# engine's internal name); what the user reads shows the family's own name (Definition.show)
_I, _N = SYMBOLS["i"], SYMBOLS["n"]
_T, _LAM = SYMBOLS["t"], SYMBOLS["lam"]


@dataclass(frozen=True)
class Definition:
    name: str
    title: str
    parameter: str
    range_text: str
    lo: Fraction
    hi: Fraction
    lo_closed: bool
    hi_closed: bool
    degrees: range
    bernstein_at: Fraction | None
    points: str  # the control points' name in records (P unless the table says `points`)
    offset: int
    basis_text: str | None  # the closed formula, or
    seed_texts: tuple[str, ...] | None  # the lowest degree's functions, and
    recursion_text: str | None  # b(i, n, t) from the degree below
    digest: str  # of the [family] table: a derived file names the definition it came from

    # The interface names the parameters as a tuple and the domain as an interval, so that
    # families with several parameters or another domain (issue #30) fit without a new
    # interface; today every family has one parameter and the domain [0, 1].
    @property
    def parameters(self) -> tuple[str, ...]:
        return (self.parameter,)

    @property
    def domain(self) -> Interval:
        return Interval(Fraction(0), Fraction(1))

    def show(self, expr: sp.Basic) -> str:
        """An expression as the user reads it: in the family's own parameter name."""
        if self.parameter == "lam":
            return str(expr)
        return str(expr.xreplace({_LAM: sp.Symbol(self.parameter)}))

    @property
    def basis(self) -> sp.Expr:
        assert self.basis_text is not None, "a family defined by a recursion"
        return _parse_basis(self.basis_text, self.parameter)

    @property
    def seed(self) -> tuple[sp.Expr, ...]:
        assert self.seed_texts is not None
        return tuple(_parse_basis(text, self.parameter) for text in self.seed_texts)

    @property
    def recursion(self) -> sp.Expr:
        assert self.recursion_text is not None
        return _parse_basis(self.recursion_text, self.parameter, recursive=True)


def digest(table: dict) -> str:
    """A stable fingerprint of a [family] table: the runtime's, so that load_family can tell
    whether a derived document came from this very definition."""
    from lambda_bezier.family import definition_digest

    return definition_digest(table)


def rename_parameter(text: str, parameter: str, *, lam_too: bool = False) -> str:
    """The formula with the parameter's name replaced by `lam`, token by token (a name is
    a whole token, so `mu` in `mu2` is left alone): how verify reads a records formula about
    a family whose parameter has a name of its own. `lam_too`: `lam` may also stand for it
    (records written before families had their own names)."""
    if parameter == "lam":
        return text
    out, last = [], 0
    for tok in tokenize(text):
        if tok.kind == "name" and tok.text == parameter:
            out += [text[last : tok.pos], "lam"]
            last = tok.pos + len(tok.text)
        elif tok.kind == "name" and tok.text == "lam" and not lam_too:
            raise ParseError(f"`lam` is not this family's parameter ({parameter!r}): {text!r}")
    return "".join(out) + text[last:]


@cache
def _parse_basis(text: str, parameter: str, recursive: bool = False) -> sp.Expr:
    # the parameter's own name maps to the engine's symbol: a parse error quotes the user's text
    symbols = {"i": _I, "n": _N, "t": _T, parameter: _LAM}
    functions = {"b": FUNCTIONS["b"]} if recursive else {}
    return parse_formula(text, symbols, functions)


def _number(text: str, key: str) -> Fraction:
    try:
        e = parse_formula(text, {}, {})
    except ParseError as exc:
        raise DefinitionError(f"key {key}: {exc}") from None
    if not e.is_Rational:
        raise DefinitionError(f"key {key}: {text!r} is not an exact number")
    return Fraction(int(e.p), int(e.q))


_RANGE = re.compile(r"^\s*([\[(])([^,\[\]()]+),([^,\[\]()]+)([\])])\s*$")
_DEGREES = re.compile(r"^\s*([0-9]{1,3})\s*\.\.\s*([0-9]{1,3})\s*$")


def definition_from_table(table: object, where: str = "", *, builtin: bool = False) -> Definition:
    """Validate a [family] table (JSON Schema, then the meaning of each key). `builtin`: one
    of derive/families/*.toml, the built-in families as data, may use a built-in name."""
    import jsonschema

    prefix = f"{where}: [family]" if where else "[family]"
    errors = list(jsonschema.Draft202012Validator(SCHEMA).iter_errors(table))
    if errors:
        err = errors[0]
        key = ".".join(map(str, err.absolute_path)) or "(table)"
        raise DefinitionError(f"{prefix}, key {key}: {err.message}")
    assert isinstance(table, dict)

    def fail(key: str, message: str) -> DefinitionError:
        return DefinitionError(f"{prefix}, key {key}: {message}")

    given = [key for key in ("basis", "seed", "recursion") if key in table]
    if given not in (["basis"], ["seed", "recursion"]):
        raise fail(
            "basis"
            if "basis" in given or not given
            else ("recursion" if "seed" in given else "seed"),
            "a family is defined by `basis` (a closed formula in i, n, t and the parameter) or "
            f"by `seed` and `recursion`, one of the two; this table has {given or 'neither'}",
        )

    if not builtin and table["name"] in _builtin_file_names():
        raise fail("name", f"{table['name']!r} is a built-in family; choose another name")
    taken = (*SYMBOLS, *FUNCTIONS, *BUILTINS)
    if table["parameter"] in taken and table["parameter"] != "lam":
        raise fail("parameter", f"{table['parameter']!r} is taken by the formula language")
    m = _RANGE.match(table["range"])
    if not m:
        raise fail("range", f'{table["range"]!r} is not an interval such as "(-2, 1]"')
    lo, hi = (_number(x.strip(), "range") for x in (m.group(2), m.group(3)))
    lo_closed, hi_closed = m.group(1) == "[", m.group(4) == "]"
    if lo > hi or (lo == hi and not (lo_closed and hi_closed)):
        raise fail("range", f"the interval {table['range']} is empty")
    d = _DEGREES.match(table["degrees"])
    if not d:
        raise fail("degrees", f'{table["degrees"]!r} is not a degree range such as "3..12"')
    dlo, dhi = int(d.group(1)), int(d.group(2))
    if not 1 <= dlo <= dhi <= MAX_DEGREE:
        raise fail("degrees", f"degrees must satisfy 1 <= lo <= hi <= {MAX_DEGREE}")
    at = None
    if "bernstein_at" in table:
        at = _number(table["bernstein_at"], "bernstein_at")
    formulas = (
        [("basis", table["basis"], False)]
        if "basis" in table
        else [(f"seed[{k}]", text, False) for k, text in enumerate(table["seed"])]
        + [("recursion", table["recursion"], True)]
    )
    for key, text, recursive in formulas:
        _check_formula(fail, key, text, table["parameter"], recursive)
    if "seed" in table and len(table["seed"]) != dlo + 1:
        raise fail(
            "seed",
            f"the seed is the basis of the lowest degree {dlo}: {dlo + 1} functions, "
            f"got {len(table['seed'])}",
        )
    return Definition(
        name=table["name"],
        title=table.get("title", ""),
        parameter=table["parameter"],
        range_text=table["range"].strip(),
        lo=lo,
        hi=hi,
        lo_closed=lo_closed,
        hi_closed=hi_closed,
        degrees=range(dlo, dhi + 1),
        bernstein_at=at,
        points=table.get("points", "P"),
        offset=int(table["degree_offset"]),
        basis_text=table.get("basis"),
        seed_texts=tuple(table["seed"]) if "seed" in table else None,
        recursion_text=table.get("recursion"),
        digest=digest(table),
    )


def _check_formula(fail, key: str, text: str, parameter: str, recursive: bool) -> None:
    try:
        expr = _parse_basis(text, parameter, recursive)
    except ParseError as exc:
        hint = f" (a basis is a formula in i, n, t and {parameter})"
        raise fail(key, str(exc) + (hint if "unknown name" in str(exc) else "")) from None
    extra = sorted(s.name for s in expr.free_symbols if s not in (_I, _N, _T, _LAM))
    if extra:
        raise fail(
            key,
            f"unknown symbol {extra[0]!r} (the basis is a formula in i, n, t and {parameter})",
        )
    if expr.has(sp.Sum, sp.Integral, sp.Subs, sp.Derivative):
        raise fail(key, "a basis is a closed formula: no sums, integrals or derivatives")
    if not recursive and expr.atoms(sp.core.function.AppliedUndef):
        raise fail(key, "a closed formula calls no functions (b(...) belongs in `recursion`)")
    for call in expr.atoms(sp.core.function.AppliedUndef):
        if len(call.args) != 3 or call.args[2] != _T:
            raise fail(key, f"{call} must be b(index, degree, t)")


def read_definition(path: Path, *, builtin: bool = False) -> Definition:
    """The [family] table of a file (a family file, or a records file that defines one), read
    by the runtime's reader (the same table lambda_bezier.load_family fingerprints)."""
    from lambda_bezier.family import FamilyFileError, read_family_table

    try:
        table = read_family_table(path)
    except FamilyFileError as exc:
        raise DefinitionError(str(exc)) from None
    return definition_from_table(table, str(path), builtin=builtin)


FAMILY_DEFINITIONS = Path(__file__).resolve().parent  # the built-in families' *.toml


def _builtin_file_names() -> tuple[str, ...]:
    """The names a user family may not take: the reference basis and the built-in families
    (registry.py checks that each file is named after its family)."""
    return (REFERENCE, *sorted(path.stem for path in FAMILY_DEFINITIONS.glob("*.toml")))


def builtin_definition(name: str) -> Definition:
    """A built-in family's definition as data (derive/families/<name>.toml)."""
    return read_definition(FAMILY_DEFINITIONS / f"{name}.toml", builtin=True)
