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

from ..grammar import (
    BUILTINS,
    ELEMENTARY,
    FUNCTIONS,
    OPERATORS,
    SYMBOLS,
    Interval,
    ParseError,
    parse_formula,
    tokenize,
)
from ..grammar.messages import schema_message
from . import indexed

# version of the derived JSON document (2: with singular_parameters; 3: several parameters,
# tables by parameter monomials; a one-parameter document is laid out as in 2)
FORMAT = 3
MAX_DEGREE = 20
MAX_OFFSET = 6
MAX_PARAMETERS = 8
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
_PARAM_NAME = {"type": "string", "pattern": r"^[A-Za-z][A-Za-z0-9_]{0,19}$"}
_INTERVAL = {"type": "string", "maxLength": 200}
SCHEMA = {
    "type": "object",
    "properties": {
        "name": {"type": "string", "pattern": _NAME},
        "title": {"type": "string", "maxLength": 500},
        "parameter": _PARAM_NAME,
        # several shape parameters (issue #30); `parameter` is the one-parameter form
        "parameters": {
            "type": "array",
            "items": _PARAM_NAME,
            "minItems": 1,
            "maxItems": MAX_PARAMETERS,
            "uniqueItems": True,
        },
        # an interval, or a table {parameter: interval} (required with several parameters)
        "range": {
            "oneOf": [_INTERVAL, {"type": "object", "additionalProperties": _INTERVAL}],
        },
        "domain": _INTERVAL,  # the interval of t
        "degrees": {"type": "string", "maxLength": 20},
        "bernstein_at": {
            "oneOf": [_INTERVAL, {"type": "object", "additionalProperties": _INTERVAL}],
        },
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
        # or the functions b_0 .. b_n of a single order, each a formula in t and the parameters
        "functions": {
            "type": "array",
            "items": {"type": "string", "maxLength": 10_000},
            "minItems": 2,
            "maxItems": MAX_DEGREE + 1,
        },
        "source": {"type": "string"},
        "note": {"type": "string"},
    },
    "required": ["name", "range", "degrees"],
    "additionalProperties": False,
}

# basis formulas are in i, n, t and the parameter, which is read as the symbol `lam` (the
# engine's internal name); what the user reads shows the family's own name (Definition.show)
_I, _N = SYMBOLS["i"], SYMBOLS["n"]
_T, _LAM = SYMBOLS["t"], SYMBOLS["lam"]


@dataclass(frozen=True)
class Parameter:
    """One shape parameter: its name and its admissible interval."""

    name: str
    range_text: str
    lo: Fraction
    hi: Fraction
    lo_closed: bool
    hi_closed: bool
    bernstein_at: Fraction | None


@dataclass(frozen=True)
class Definition:
    name: str
    title: str
    parameter: str  # the first (with one parameter: the) parameter's name
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
    recursion_text: str | None  # b(i, n, t) from the degree below, or
    digest: str  # of the [family] table: a derived file names the definition it came from
    # every parameter with its interval (one for a `parameter = ...` table)
    params: tuple[Parameter, ...] = ()
    functions_texts: tuple[str, ...] | None = None  # b_0 .. b_n of the single order
    # an indexed parameter lam(i) (derive/families/indexed.py: `expand` gives each degree's
    # family in plain parameters); None for every other family
    indexed: object | None = None
    # issue #30: functions with sin, cos, sinh, cosh, exp (derive/families/spaces.py), and the
    # interval of t, value = lo * unit .. hi * unit with unit "1" or "pi"
    elementary: bool = False
    domain_lo: Fraction = Fraction(0)
    domain_hi: Fraction = Fraction(1)
    domain_unit: str = "1"
    domain_text: str = "[0, 1]"

    @property
    def parameters(self) -> tuple[str, ...]:
        return tuple(p.name for p in self.params) or (self.parameter,)

    @property
    def several(self) -> bool:
        return len(self.parameters) > 1 or self.indexed is not None

    @property
    def symbols(self) -> tuple[sp.Symbol, ...]:
        """The engine's symbols of the parameters: `lam` for a one-parameter family (the
        formula tables' name), the family's own names for several."""
        if not self.several:
            return (_LAM,)
        return tuple(sp.Symbol(name) for name in self.parameters)

    @property
    def domain(self) -> Interval:
        return Interval(Fraction(0), Fraction(1))

    def at_degree(self, degree: int) -> Definition:
        """An indexed family's degree-n family, in the plain parameters name_a .. name_b of
        that degree (derive/families/indexed.py); any other family is itself."""
        if self.indexed is None:
            return self
        return _at_degree(self, degree)

    def show(self, expr: sp.Basic) -> str:
        """An expression as the user reads it: in the family's own parameter names."""
        if self.parameter == "lam" or self.several:
            return str(expr)
        return str(expr.xreplace({_LAM: sp.Symbol(self.parameter)}))

    @property
    def basis(self) -> sp.Expr:
        assert self.basis_text is not None, "a family defined by a recursion"
        return _parse_basis(self.basis_text, self.parameters)

    @property
    def seed(self) -> tuple[sp.Expr, ...]:
        assert self.seed_texts is not None
        return tuple(_parse_basis(text, self.parameters) for text in self.seed_texts)

    @property
    def recursion(self) -> sp.Expr:
        assert self.recursion_text is not None
        return _parse_basis(self.recursion_text, self.parameters, recursive=True)

    @property
    def functions(self) -> tuple[sp.Expr, ...]:
        assert self.functions_texts is not None
        return tuple(_parse_basis(text, self.parameters) for text in self.functions_texts)


def digest(table: dict) -> str:
    """A stable fingerprint of a [family] table: the runtime's, so that load_family can tell
    whether a derived document came from this very definition."""
    from lambda_bezier._family_file import definition_digest

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
def _parse_basis(text: str, parameters: tuple[str, ...], recursive: bool = False) -> sp.Expr:
    # one parameter's own name maps to the engine's symbol `lam`, several keep their names: a
    # parse error quotes the user's text
    symbols = {"i": _I, "n": _N, "t": _T}
    if len(parameters) == 1:
        symbols[parameters[0]] = _LAM
    else:
        symbols.update({name: sp.Symbol(name) for name in parameters})
    functions = {"b": FUNCTIONS["b"]} if recursive else {}
    return parse_formula(text, symbols, functions, elementary=True, operators=recursive)


def is_operator(call: sp.Basic) -> bool:
    """integral(f), total(f), normalized(f) of a recursion (derive/grammar, OPERATORS)."""
    return isinstance(call, sp.core.function.AppliedUndef) and call.func in OPERATORS.values()


def _is_elementary(expr: sp.Basic) -> bool:
    return expr.has(sp.pi, *ELEMENTARY.values())


def _domain(text: str, fail, parameters: tuple[str, ...] = ()) -> tuple[Fraction, Fraction, str]:
    """`[lo, hi]`: exact rationals, or rational multiples of pi (both ends in one unit)."""
    m = _RANGE.match(text)
    if not m or m.group(1) != "[" or m.group(4) != "]":
        raise fail("domain", f'{text!r} is not a closed interval such as "[0, 1]" or "[0, pi/2]"')
    ends, units = [], set()
    for part in (m.group(2).strip(), m.group(3).strip()):
        named = [p for p in parameters if re.search(rf"\b{re.escape(p)}\b", part)]
        if named:  # C-Bezier curves on [0, alpha]: the issue's design must say what is missing
            raise fail(
                "domain",
                f"{text!r}: the end {part!r} names the shape parameter {named[0]!r}; a domain "
                "whose length is a parameter (C-Bezier curves on [0, alpha]) is not supported "
                "in this version: the ends are exact numbers, rationals or rational multiples "
                "of pi",
            )
        try:
            e = parse_formula(part, {}, {}, elementary=True)
        except ParseError as exc:
            raise fail("domain", str(exc)) from None
        unit = e / sp.pi if e.has(sp.pi) else e
        if not unit.is_Rational:
            raise fail("domain", f"{part!r} is neither an exact rational nor a rational times pi")
        if unit != 0:
            units.add("pi" if e.has(sp.pi) else "1")
        ends.append(Fraction(int(unit.p), int(unit.q)))
    if len(units) > 1:
        raise fail(
            "domain", f"{text!r}: both ends are rationals or both are rational multiples of pi"
        )
    if ends[0] >= ends[1]:
        raise fail("domain", f"the interval {text} is empty")
    return ends[0], ends[1], units.pop() if units else "1"


def _number(text: str, key: str) -> Fraction:
    try:
        e = parse_formula(text, {}, {})
    except ParseError as exc:
        raise DefinitionError(f"key {key}: {exc}") from None
    if not e.is_Rational:
        raise DefinitionError(f"key {key}: {text!r} is not an exact number")
    return Fraction(int(e.p), int(e.q))


_RANGE = re.compile(r"^\s*([\[(])([^,\[\]()]+),([^,\[\]()]+)([\])])\s*$")


def _interval(text: str, key: str, fail) -> tuple[Fraction, Fraction, bool, bool]:
    m = _RANGE.match(text)
    if not m:
        raise fail(key, f'{text!r} is not an interval such as "(-2, 1]"')
    lo, hi = (_number(x.strip(), key) for x in (m.group(2), m.group(3)))
    lo_closed, hi_closed = m.group(1) == "[", m.group(4) == "]"
    if lo > hi or (lo == hi and not (lo_closed and hi_closed)):
        raise fail(key, f"the interval {text} is empty")
    return lo, hi, lo_closed, hi_closed


def _per_parameter(table: dict, key: str, names: list[str], fail) -> dict[str, str]:
    """A key that is a plain string (one parameter) or a table {parameter: text}."""
    value = table[key]
    if isinstance(value, str):
        if len(names) != 1:
            raise fail(
                key,
                f"with several parameters ({', '.join(names)}), `{key}` is a table "
                f'{{ {names[0]} = "..." , ... }}',
            )
        return {names[0]: value}
    unknown = sorted(set(value) - set(names))
    if unknown:
        raise fail(f"{key}.{unknown[0]}", f"{unknown[0]!r} is not a parameter ({', '.join(names)})")
    return dict(value)


def _parameter_names(table: dict, fail) -> list[str]:
    if ("parameter" in table) == ("parameters" in table):
        raise fail(
            "parameters" if "parameters" in table else "parameter",
            'a family names its shape parameter with `parameter = "lam"` or its '
            'parameters with `parameters = ["lam", "mu"]`, one of the two',
        )
    names = [table["parameter"]] if "parameter" in table else list(table["parameters"])
    taken = (*SYMBOLS, *FUNCTIONS, *BUILTINS, *ELEMENTARY, "pi")
    key = "parameter" if "parameter" in table else "parameters"
    for name in names:
        if name in taken and name != "lam":
            raise fail(key, f"{name!r} is taken by the formula language")
    return names


def definition_from_table(table: object, where: str = "", *, builtin: bool = False) -> Definition:
    """Validate a [family] table (JSON Schema, then the meaning of each key). `builtin`: one
    of derive/families/*.toml, the built-in families as data, may use a built-in name."""
    import jsonschema

    prefix = f"{where}: [family]" if where else "[family]"
    if indexed.is_indexed(table):
        assert isinstance(table, dict)
        return _indexed_definition(table, prefix, builtin)
    errors = list(jsonschema.Draft202012Validator(SCHEMA).iter_errors(table))
    if errors:
        err = errors[0]
        key = ".".join(map(str, err.absolute_path)) or "(table)"
        raise DefinitionError(f"{prefix}, key {key}: {schema_message(err)}")
    assert isinstance(table, dict)

    def fail(key: str, message: str) -> DefinitionError:
        return DefinitionError(f"{prefix}, key {key}: {message}")

    given = [key for key in ("basis", "seed", "recursion", "functions") if key in table]
    if given not in (["basis"], ["seed", "recursion"], ["functions"]):
        raise fail(
            "basis"
            if "basis" in given or not given
            else ("recursion" if "seed" in given else "seed"),
            "a family is defined by `basis` (a closed formula in i, n, t and the parameters), "
            "by `seed` and `recursion`, or by `functions` (b_0 .. b_n of one order), one of "
            f"these; this table has {given or 'neither'}",
        )

    if not builtin and table["name"] in _builtin_file_names():
        raise fail("name", f"{table['name']!r} is a built-in family; choose another name")
    names = _parameter_names(table, fail)
    ranges = _per_parameter(table, "range", names, fail)
    missing = [name for name in names if name not in ranges]
    if missing:
        raise fail("range", f"no interval for the parameter {missing[0]!r}")
    ats = _per_parameter(table, "bernstein_at", names, fail) if "bernstein_at" in table else {}
    if ats and len(ats) != len(names):
        raise fail(
            "bernstein_at",
            "the Bernstein basis is at a value of every parameter: "
            f"{', '.join(x for x in names if x not in ats)} missing",
        )
    params = []
    for name in names:
        key = "range" if len(names) == 1 else f"range.{name}"
        lo, hi, lo_closed, hi_closed = _interval(ranges[name], key, fail)
        at = None
        if name in ats:
            at_key = "bernstein_at" if len(names) == 1 else f"bernstein_at.{name}"
            at = _number(ats[name], at_key)
            inside = (lo < at or (lo_closed and lo == at)) and (at < hi or (hi_closed and at == hi))
            if not inside:
                raise fail(at_key, f"{at} is outside the range {ranges[name].strip()} of {name}")
        params.append(Parameter(name, ranges[name].strip(), lo, hi, lo_closed, hi_closed, at))
    dom_lo, dom_hi, dom_unit = (
        _domain(table["domain"], fail, tuple(names))
        if "domain" in table
        else (Fraction(0), Fraction(1), "1")
    )
    elementary = "functions" in table and any(
        _is_elementary(_parse_basis(text, tuple(names)))
        for text in table["functions"]
        if _parses(text, tuple(names))
    )
    dlo, dhi = indexed.degree_range(table, fail, MAX_DEGREE, "3..12")
    formulas = (
        [("basis", table["basis"], False)]
        if "basis" in table
        else [(f"functions[{k}]", text, False) for k, text in enumerate(table["functions"])]
        if "functions" in table
        else [(f"seed[{k}]", text, False) for k, text in enumerate(table["seed"])]
        + [("recursion", table["recursion"], True)]
    )
    for key, text, recursive in formulas:
        _check_formula(fail, key, text, tuple(names), recursive)
    # after the formulas: a term outside the grammar is named before the domain it voids
    if not elementary and (dom_lo, dom_hi, dom_unit) != (0, 1, "1"):
        raise fail(
            "domain",
            f"{table['domain']!r}: a polynomial basis is derived on [0, 1] only (a basis "
            "with sin, cos, sinh, cosh or exp may have a domain of its own)",
        )
    if elementary and "bernstein_at" in table:
        raise fail(
            "bernstein_at",
            "not used by a trigonometric or hyperbolic basis: the reduction to the Bernstein "
            "polynomials is decided for polynomial bases only (leave the key out)",
        )
    if elementary and "degree_offset" in table:
        raise fail(
            "degree_offset", "not used by a trigonometric or hyperbolic basis (leave it out)"
        )
    if "seed" in table and len(table["seed"]) != dlo + 1:
        raise fail(
            "seed",
            f"the seed is the basis of the lowest degree {dlo}: {dlo + 1} functions, "
            f"got {len(table['seed'])}",
        )
    first = params[0]
    return Definition(
        name=table["name"],
        title=table.get("title", ""),
        parameter=first.name,
        range_text=first.range_text,
        lo=first.lo,
        hi=first.hi,
        lo_closed=first.lo_closed,
        hi_closed=first.hi_closed,
        degrees=range(dlo, dhi + 1),
        bernstein_at=first.bernstein_at,
        points=table.get("points", "P"),
        offset=int(table.get("degree_offset", 0)),
        basis_text=table.get("basis"),
        seed_texts=tuple(table["seed"]) if "seed" in table else None,
        recursion_text=table.get("recursion"),
        digest=digest(table),
        params=tuple(params),
        functions_texts=tuple(table["functions"]) if "functions" in table else None,
        elementary=elementary,
        domain_lo=dom_lo,
        domain_hi=dom_hi,
        domain_unit=dom_unit,
        domain_text=table.get("domain", "[0, 1]").strip(),
    )


def _indexed_definition(table: dict, prefix: str, builtin: bool) -> Definition:
    def fail(key: str, message: str) -> DefinitionError:
        return DefinitionError(f"{prefix}, key {key}: {message}")

    taken = () if builtin else _builtin_file_names()
    spec, dlo, dhi = indexed.read_indexed(table, fail, SCHEMA, taken)
    defn = Definition(
        name=table["name"],
        title=table.get("title", ""),
        parameter=spec.name,
        range_text=spec.range_text,
        lo=Fraction(0),
        hi=Fraction(0),
        lo_closed=True,
        hi_closed=True,
        degrees=range(dlo, dhi + 1),
        bernstein_at=None,
        points=table.get("points", "P"),
        offset=int(table.get("degree_offset", 0)),
        basis_text=table.get("basis"),
        seed_texts=None,
        recursion_text=None,
        digest=digest(table),
        functions_texts=tuple(table["functions"]) if "functions" in table else None,
        indexed=spec,
    )
    for deg in defn.degrees:  # every degree's ranges and functions, errors naming the key
        _expand(defn, deg, fail)
    return defn


@cache
def _at_degree(defn: Definition, degree: int) -> Definition:
    def fail(key: str, message: str) -> DefinitionError:
        return DefinitionError(f"[family] {defn.name}, key {key}: {message}")

    if degree not in defn.degrees:
        raise DefinitionError(f"{defn.name}: no degree {degree} (degrees {defn.degrees})")
    return _expand(defn, degree, fail)


def _expand(defn: Definition, degree: int, fail) -> Definition:
    from dataclasses import replace

    spec = defn.indexed
    assert isinstance(spec, indexed.Indexed)
    raw, texts = indexed.degree_parts(spec, defn.basis_text, defn.functions_texts, degree, fail)
    params = tuple(Parameter(*row) for row in raw)
    first = params[0]
    return replace(
        defn,
        parameter=first.name,
        range_text=first.range_text,
        lo=first.lo,
        hi=first.hi,
        lo_closed=first.lo_closed,
        hi_closed=first.hi_closed,
        degrees=range(degree, degree + 1),
        bernstein_at=first.bernstein_at,
        basis_text=None,
        functions_texts=texts,
        params=params,
        indexed=None,
    )


def _check_formula(fail, key: str, text: str, names: tuple[str, ...], recursive: bool) -> None:
    shown = " and ".join([", ".join(("i", "n", "t", *names[:-1])), names[-1]])
    try:
        expr = _parse_basis(text, names, recursive)
    except ParseError as exc:
        hint = f" (a basis is a formula in {shown})"
        raise fail(key, str(exc) + (hint if "unknown name" in str(exc) else "")) from None
    own = {_LAM} if len(names) == 1 else {sp.Symbol(x) for x in names}
    extra = sorted(s.name for s in expr.free_symbols if s not in {_I, _N, _T} | own)
    if extra:
        raise fail(key, f"unknown symbol {extra[0]!r} (the basis is a formula in {shown})")
    if _is_elementary(expr) and not key.startswith("functions"):
        raise fail(
            key,
            "pi, sin, cos, sinh, cosh and exp belong in an explicit `functions` list (a "
            "trigonometric or hyperbolic basis of one order)",
        )
    if expr.has(sp.Sum, sp.Integral, sp.Subs, sp.Derivative):
        raise fail(key, "a basis is a closed formula: no sums, integrals or derivatives")
    if not recursive and expr.atoms(sp.core.function.AppliedUndef):
        raise fail(key, "a closed formula calls no functions (b(...) belongs in `recursion`)")
    for call in expr.atoms(sp.core.function.AppliedUndef):
        if is_operator(call):
            continue
        if len(call.args) != 3 or call.args[2] != _T:
            raise fail(key, f"{call} must be b(index, degree, t)")


def _parses(text: str, names: tuple[str, ...]) -> bool:
    try:
        _parse_basis(text, names)
    except ParseError:
        return False  # reported with its key by _check_formula
    return True


def read_definition(path: Path, *, builtin: bool = False) -> Definition:
    """The [family] table of a file (a family file, or a records file that defines one), read
    by the runtime's reader (the same table lambda_bezier.load_family fingerprints)."""
    from lambda_bezier._family_file import FamilyFileError, read_family_table

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
