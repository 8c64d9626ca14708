"""Indexed shape parameters: one parameter per control point (or per leg), ``lam(i)``.

A family such as Han, Ma and Huang's Q-Bezier basis has a shape parameter per index, so the
number of parameters depends on the degree. Its ``[family]`` table says so with

    parameters = ["lam(i)"]                    # one indexed parameter
    indices = { lam = "1..n" }                 # which indices exist at degree n (default 0..n)
    range = { lam = "[-binomial(n, i), binomial(n, i - 1)]" }   # per index: formulas in n, i
    bernstein_at = { lam = "0" }               # optional, every index
    basis = "... lam(i) ... lam(i + 1) ..."    # or `functions` for a single order

In the basis, ``lam(k)`` names the parameter of index k; an index outside ``indices`` reads
as 0 (the papers' convention lam_0 = lam_{n+1} = 0 at the two ends). Nothing else is new:
at each degree n the family is expanded into a family in the several plain parameters
``lam_a .. lam_b`` of that degree (``expand``), and every decision, table and energy is the
several-parameter one of that expansion. Formulas are read by the records grammar only.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from fractions import Fraction
from functools import cache

import sympy as sp

from ..grammar import BUILTINS, FUNCTIONS, SYMBOLS, ParseError, parse_formula
from ..grammar.formula import paper_binomial_expr
from ..grammar.messages import schema_message

# definition.py imports this module (never the other way round: no import cycle); it builds
# the Definition and its per-degree expansions from what is read here
_I, _N, _T = SYMBOLS["i"], SYMBOLS["n"], SYMBOLS["t"]

_INDEXED_NAME = re.compile(r"^([A-Za-z][A-Za-z0-9]{0,11})\(i\)$")
_ONE_INDEX = re.compile(r"^[A-Za-z][A-Za-z0-9]{0,11}\(([0-9]{1,2})\)$")
_INDICES = re.compile(r"^\s*([0-9])\s*\.\.\s*n\s*(?:-\s*([0-9]))?\s*$")
MAX_INDEXED_DEGREE = 8  # parameters per degree stay within what the box decisions handle


def indexed_schema(schema: dict) -> dict:
    """The [family] schema with `indices`, and a parameter name that carries "(i)"."""
    return {
        **schema,
        "properties": {
            **schema["properties"],
            "parameters": {
                "type": "array",
                "items": {"type": "string", "pattern": _INDEXED_NAME.pattern},
                "minItems": 1,
                "maxItems": 1,
            },
            "indices": {"type": "object", "additionalProperties": {"type": "string"}},
        },
    }


def is_indexed(table: object) -> bool:
    """Whether a [family] table declares an indexed parameter (``name(i)``)."""
    if not isinstance(table, dict):
        return False
    names = table.get("parameters")
    return isinstance(names, list) and any(isinstance(x, str) and x.endswith("(i)") for x in names)


@dataclass(frozen=True)
class Indexed:
    """The indexed parameter of a definition: its base name, the index range a..n-b, and the
    per-index range and Bernstein value as formula texts in n and i."""

    name: str
    first: int
    last_offset: int  # the last index is n - last_offset
    range_text: str
    range_overrides: tuple[tuple[int, str], ...]  # ((k, interval text of name(k)), ...)
    bernstein_text: str | None

    def indices(self, degree: int) -> range:
        return range(self.first, degree - self.last_offset + 1)

    def symbol_name(self, idx: int) -> str:
        return f"{self.name}_{idx}"


_DEGREE = re.compile(r"^\s*([0-9]{1,3})\s*$")
_DEGREE_RANGE = re.compile(r"^\s*([0-9]{1,3})\s*\.\.\s*([0-9]{1,3})\s*$")


def degree_range(
    table: dict, fail, maximum: int, example: str, bound: str = "degrees must satisfy"
) -> tuple[int, int]:
    """(lo, hi) of a [family] table's `degrees` ("n" or "lo..hi", 1 <= lo <= hi <= maximum),
    and an explicit `functions` list checked to be one order of n + 1 functions (for every
    definition: the plain, several-parameter and indexed ones; derive/families/definition.py
    imports this module)."""
    d = _DEGREE_RANGE.match(table["degrees"])
    single = _DEGREE.match(table["degrees"])
    if not d and not single:
        raise fail(
            "degrees",
            f'{table["degrees"]!r} is not a degree or a degree range such as "{example}"',
        )
    dlo, dhi = (int(d.group(1)), int(d.group(2))) if d else (int(single.group(1)),) * 2
    if not 1 <= dlo <= dhi <= maximum:
        raise fail("degrees", f"{bound} 1 <= lo <= hi <= {maximum}")
    if "functions" in table:
        if dlo != dhi:
            raise fail("functions", 'an explicit list of functions is one order: degrees = "n"')
        if len(table["functions"]) != dlo + 1:
            raise fail(
                "functions",
                f"the basis of degree {dlo} has {dlo + 1} functions, got {len(table['functions'])}",
            )
    return dlo, dhi


def read_indexed(table: dict, fail, schema: dict, taken_names: tuple[str, ...]) -> tuple:
    """Validate an indexed [family] table: (the Indexed spec, lowest degree, highest degree).
    definition.py builds the Definition and checks every degree's expansion."""
    import jsonschema

    errors = list(jsonschema.Draft202012Validator(indexed_schema(schema)).iter_errors(table))
    if errors:
        err = errors[0]
        key = ".".join(map(str, err.absolute_path)) or "(table)"
        if key.startswith("parameters"):
            raise fail(
                "parameters",
                "an indexed family has exactly one parameter written name(i), e.g. "
                f'["lam(i)"] ({schema_message(err)})',
            )
        raise fail(key, schema_message(err))
    (written,) = table["parameters"]
    base = _INDEXED_NAME.match(written)
    assert base is not None  # the schema's pattern
    name = base.group(1)
    if name in (*SYMBOLS, *FUNCTIONS, *BUILTINS) and name != "lam":
        raise fail("parameters", f"{name!r} is taken by the formula language")
    for key in ("indices", "range", "bernstein_at"):
        value = table.get(key)
        if value is None:
            continue
        own = {name} | ({k for k in value if _ONE_INDEX.match(k)} if key == "range" else set())
        if not isinstance(value, dict) or name not in value or set(value) - own:
            raise fail(
                key,
                f'an indexed family gives `{key}` as a table {{ {name} = "..." }}'
                + (
                    f' (and "{name}(k)" = "..." for an index k of its own)'
                    if key == "range"
                    else ""
                ),
            )
    _ONE = re.compile(rf"^{name}\(([0-9]{{1,2}})\)$")
    overrides = {
        int(m.group(1)): text.strip()
        for k, text in table["range"].items()
        if (m := _ONE.match(k)) and isinstance(text, str)
    }
    indices = table.get("indices", {name: "0..n"})[name]
    m = _INDICES.match(indices)
    if not m:
        raise fail(f"indices.{name}", f'{indices!r} is not an index range such as "0..n" or "1..n"')
    spec = Indexed(
        name=name,
        first=int(m.group(1)),
        last_offset=int(m.group(2) or 0),
        range_text=table["range"][name].strip(),
        range_overrides=tuple(sorted(overrides.items())),
        bernstein_text=table["bernstein_at"][name] if "bernstein_at" in table else None,
    )
    given = [key for key in ("basis", "seed", "recursion", "functions") if key in table]
    if given not in (["basis"], ["functions"]):
        raise fail(
            "basis",
            "an indexed family is defined by `basis` (a formula in i, n, t and "
            f"{name}(index)) or by `functions` (b_0 .. b_n of one order); this table has "
            f"{given or 'neither'}",
        )
    dlo, dhi = degree_range(
        table, fail, MAX_INDEXED_DEGREE, "3..6", "an indexed family's degrees satisfy"
    )
    for deg in range(dlo, dhi + 1):
        if len(spec.indices(deg)) < 2:
            raise fail(
                f"indices.{name}",
                f"{indices!r} gives fewer than two indices at n = {deg} (a family with one "
                "parameter is written `parameter = ...`)",
            )
    if table["name"] in taken_names:
        raise fail("name", f"{table['name']!r} is a built-in family; choose another name")
    texts = (table["basis"],) if "basis" in table else tuple(table["functions"])
    keys = ("basis",) if "basis" in table else tuple(f"functions[{k}]" for k in range(len(texts)))
    for key, text in zip(keys, texts, strict=True):
        _check_indexed_formula(fail, key, text, name)
    return spec, dlo, dhi


@cache
def _parse_indexed(text: str, name: str) -> sp.Expr:
    return parse_formula(text, {"i": _I, "n": _N, "t": _T}, {name: sp.Function(name)})


def _check_indexed_formula(fail, key: str, text: str, name: str) -> None:
    try:
        expr = _parse_indexed(text, name)
    except ParseError as exc:
        try:  # the term is fine elsewhere: say why not here rather than "unknown name"
            parse_formula(
                text, {"i": _I, "n": _N, "t": _T}, {name: sp.Function(name)}, elementary=True
            )
        except ParseError:
            raise fail(key, f"{exc} (a basis is a formula in i, n, t and {name}(index))") from None
        raise fail(
            key,
            f"{exc}: an indexed family ({name}(i)) is polynomial in this version; pi, sin, cos, "
            'sinh, cosh and exp belong to a family with named parameters (parameters = ["lam", '
            '"mu"]) and a list of functions',
        ) from None
    extra = sorted(s.name for s in expr.free_symbols if s not in {_I, _N, _T})
    if extra:
        raise fail(
            key,
            f"unknown symbol {extra[0]!r} (the basis is a formula in i, n, t and {name}(index))",
        )
    if expr.has(sp.Sum, sp.Integral, sp.Subs, sp.Derivative):
        raise fail(key, "a basis is a closed formula: no sums, integrals or derivatives")
    for call in expr.atoms(sp.core.function.AppliedUndef):
        if call.func.__name__ != name or len(call.args) != 1:
            raise fail(key, f"{call}: the only call in an indexed basis is {name}(index)")
        if call.args[0].free_symbols - {_I, _N}:
            raise fail(key, f"{call}: an index is a formula in i and n")


def _exact(expr: sp.Basic, what: str, fail, key: str) -> Fraction:
    if not expr.is_Rational:
        raise fail(key, f"{what} is {expr}, not an exact number")
    return Fraction(int(expr.p), int(expr.q))


def _split_interval(text: str, fail, key: str) -> tuple[str, str, str, str]:
    """'[a, b)' -> ('[', a, b, ')') with a and b formulas (the comma at depth 0 splits)."""
    s = text.strip()
    if len(s) < 5 or s[0] not in "[(" or s[-1] not in "])":
        raise fail(key, f'{text!r} is not an interval such as "[-binomial(n, i), 1]"')
    body, depth, cut = s[1:-1], 0, []
    for pos, ch in enumerate(body):
        depth += ch == "("
        depth -= ch == ")"
        if ch == "," and depth == 0:
            cut.append(pos)
    if len(cut) != 1:
        raise fail(key, f'{text!r} is not an interval such as "[-binomial(n, i), 1]"')
    return s[0], body[: cut[0]], body[cut[0] + 1 :], s[-1]


def _at(text: str, deg: int, idx: int, fail, key: str) -> Fraction:
    try:
        expr = parse_formula(text, {"i": _I, "n": _N}, {})
    except ParseError as exc:
        raise fail(key, f"{exc} (a formula in n and i)") from None
    value = _evaluate_integers(expr, deg, idx)
    return _exact(value, f"{text.strip()} at n = {deg}, i = {idx}", fail, key)


def _evaluate_integers(expr: sp.Basic, deg: int, idx: int) -> sp.Basic:
    """expr at n = deg, i = idx, binomials with the papers' convention (0 outside 0..n)."""

    value = expr.xreplace({_N: sp.Integer(deg), _I: sp.Integer(idx)})
    return value.replace(sp.binomial, lambda a, b: paper_binomial_expr(a, b))


def degree_parts(
    spec: Indexed,
    basis_text: str | None,
    functions_texts: tuple[str, ...] | None,
    degree: int,
    fail,
) -> tuple[list[tuple], tuple[str, ...]]:
    """At degree n: every parameter (name_k, interval text, lo, hi, lo_closed, hi_closed,
    Bernstein value) and the functions b_0 .. b_n as formula texts in name_k and t."""
    params = []
    overrides = dict(spec.range_overrides)
    for idx in spec.indices(degree):
        key = f"range.{spec.name}" + (f"({idx})" if idx in overrides else "")
        text = overrides.get(idx, spec.range_text)
        opening, lo_text, hi_text, closing = _split_interval(text, fail, key)
        lo, hi = (_at(x, degree, idx, fail, key) for x in (lo_text, hi_text))
        lo_closed, hi_closed = opening == "[", closing == "]"
        if lo > hi or (lo == hi and not (lo_closed and hi_closed)):
            raise fail(key, f"at n = {degree} the interval of {spec.name}({idx}) is empty")
        at = None
        if spec.bernstein_text is not None:
            at = _at(spec.bernstein_text, degree, idx, fail, f"bernstein_at.{spec.name}")
        text = f"{opening}{lo}, {hi}{closing}"
        params.append((spec.symbol_name(idx), text, lo, hi, lo_closed, hi_closed, at))
    symbols = {idx: sp.Symbol(spec.symbol_name(idx)) for idx in spec.indices(degree)}
    texts = (basis_text,) * (degree + 1) if basis_text is not None else functions_texts
    assert texts is not None
    functions = []
    for idx, text in enumerate(texts):
        where = "basis" if basis_text is not None else f"functions[{idx}]"
        expr = _evaluate_integers(_parse_indexed(text, spec.name), degree, idx)

        def param(arg: sp.Basic, where: str = where) -> sp.Basic:
            if not arg.is_Integer:
                raise fail(where, f"the index {arg} of {spec.name} is not an integer")
            return symbols.get(int(arg), sp.Integer(0))  # outside the indices: 0

        expr = expr.replace(
            lambda e: isinstance(e, sp.core.function.AppliedUndef), lambda e: param(e.args[0])
        )
        functions.append(sp.sstr(expr, order="lex"))
    return params, tuple(functions)
