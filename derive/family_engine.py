"""A shape-parameter family from its definition: one engine for any basis.

A family is data: a ``[family]`` table (in a file of its own or at the top of a records file)
whose ``basis`` is a formula of the records grammar in i, n, t and the shape parameter. From
that definition alone this module derives what a built-in family gets:

* per degree n: the basis polynomials (negative powers that cancel are allowed; anything that
  is not a polynomial of degree <= n + degree_offset in t after cancellation is an error), the
  checks (partition of unity, reduction to Bernstein at ``bernstein_at``), the power, Bernstein
  and centred (Taylor about 1/2) tables split by powers of the parameter;
* the values and derivatives (orders 0..3) of every basis function at both ends, per degree,
  and in closed form in n where one polynomial in n reproduces every degree of the range;
* the energy quadratic forms and the paper-style integer matrices X_n^k, Y_n^k with their
  scale (k = 1, 2, 3), where the basis is linear in the parameter (else E_k is not quadratic);
* the C1, C2, G1, G2 join weights after and before itself and every built-in family, in
  closed form in n, m where the end stencils allow derive/joins.py's solve; the runtime joins
  any two families by a per-degree solve from the power tables (lambda_bezier/joins.py).

Everything is exact (SymPy/FLINT rationals); the result is one JSON document (data, never
code: a derived file is read by ``lambda_bezier.load_family`` without running anything).
"""

from __future__ import annotations

import json
import re
import sys
from dataclasses import dataclass
from fractions import Fraction
from functools import cache
from math import comb
from pathlib import Path

import sympy as sp

from ._algebra import expansion_tables, lam, lambda_degree, t
from .grammar import FUNCTIONS, MAX_EXPONENT, SYMBOLS, ParseError, parse_formula, tokenize

FORMAT = 2  # version of the derived JSON document (2: with singular_parameters)
MAX_DEGREE = 20
MAX_OFFSET = 6
# The classical Bernstein basis (derive/bernstein.py) is every family's reference (to_bezier,
# bernstein_at), not a family defined by data; the built-in families are derive/families/*.toml.
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

# basis formulas are in i, n, t and the parameter (renamed to `lam` while reading)
_BASIS_SYMBOLS = {name: SYMBOLS[name] for name in ("i", "n", "t", "lam")}
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
    offset: int
    basis_text: str | None  # the closed formula, or
    seed_texts: tuple[str, ...] | None  # the lowest degree's functions, and
    recursion_text: str | None  # b(i, n, t) from the degree below
    digest: str  # of the [family] table: a derived file names the definition it came from

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


def rename_parameter(text: str, parameter: str) -> str:
    """The formula with the parameter's name replaced by `lam`, token by token (a name is
    a whole token, so `mu` in `mu2` is left alone)."""
    if parameter == "lam":
        return text
    out, last = [], 0
    for tok in tokenize(text):
        if tok.kind == "name" and tok.text == parameter:
            out += [text[last : tok.pos], "lam"]
            last = tok.pos + len(tok.text)
        elif tok.kind == "name" and tok.text == "lam":
            raise ParseError(f"`lam` is not this family's parameter ({parameter!r}): {text!r}")
    return "".join(out) + text[last:]


@cache
def _parse_basis(text: str, parameter: str, recursive: bool = False) -> sp.Expr:
    functions = {"b": FUNCTIONS["b"]} if recursive else {}
    return parse_formula(rename_parameter(text, parameter), _BASIS_SYMBOLS, functions)


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

    if not builtin and table["name"] in builtin_names():
        raise fail("name", f"{table['name']!r} is a built-in family; choose another name")
    if table["parameter"] in SYMBOLS and table["parameter"] != "lam":
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


# --------------------------------------------------------------------------- the basis


def _instantiate(e: sp.Basic, env: dict, ring, lookup=None) -> object:
    """e with n and i replaced by integers, evaluated in the field Q(t, lam): binomials with
    the papers' convention, powers bounded; b(i', n', t) of a recursion through lookup."""
    if isinstance(e, sp.core.function.AppliedUndef):
        if lookup is None:
            raise DefinitionError(f"cannot evaluate {e} in a closed formula")
        idx, deg = (_integer(_instantiate(x, env, ring), "index of b") for x in e.args[:2])
        return lookup(idx, deg)
    if e.is_Symbol:
        if e in env:
            return ring(env[e])
        return ring(e)
    if e.is_Rational:
        return ring(e)
    if isinstance(e, sp.binomial):
        a, b = (_integer(_instantiate(x, env, ring), "binomial") for x in e.args)
        return ring(comb(a, b) if 0 <= b <= a else 0)
    if isinstance(e, sp.factorial):
        a = _integer(_instantiate(e.args[0], env, ring), "factorial")
        if not 0 <= a <= 1000:
            raise DefinitionError(f"factorial({a}) in the basis")
        return ring(sp.factorial(a))
    if e.is_Add:
        out = ring(0)
        for a in e.args:
            out += _instantiate(a, env, ring, lookup)
        return out
    if e.is_Mul:
        out = ring(1)
        for a in e.args:
            out *= _instantiate(a, env, ring, lookup)
        return out
    if e.is_Pow:
        base = _instantiate(e.base, env, ring, lookup)
        ex = _integer(_instantiate(e.exp, env, ring), "exponent")
        if abs(ex) > MAX_EXPONENT:
            raise DefinitionError(f"an exponent {ex} in the basis")
        if ex < 0:
            if base == 0:
                raise DefinitionError("the basis divides by zero")
            return 1 / base**-ex
        return base**ex
    raise DefinitionError(f"cannot evaluate {e} in a basis definition")


def _integer(x, what: str) -> int:
    if x.denom != 1 or not x.numer.is_ground:
        raise DefinitionError(f"the {what} {x.as_expr()} is not an integer once n and i are set")
    value = sp.Rational(x.numer.LC if x.numer else 0)
    if not value.is_Integer:
        raise DefinitionError(f"the {what} {value} is not an integer")
    return int(value)


@cache
def _field():
    return sp.polys.fields.field([_T, _LAM], sp.QQ)[0]


def basis_polys(defn: Definition, degree: int) -> list[sp.Poly]:
    return list(_basis_polys(defn, degree))


@cache
def _basis_values(defn: Definition, degree: int) -> tuple:
    """The degree-`degree` functions as elements of Q(t, lam): the closed formula per index,
    or the seed at the lowest degree and the recursion above it."""
    field = _field()
    if defn.basis_text is not None:
        basis = defn.basis
        return tuple(_instantiate(basis, {_N: degree, _I: idx}, field) for idx in range(degree + 1))
    if degree == defn.degrees.start:
        return tuple(_instantiate(f, {_N: degree}, field) for f in defn.seed)
    below = _basis_values(defn, degree - 1)

    def lookup(idx: int, deg: int):
        if deg != degree - 1:
            raise DefinitionError(
                f"[family] recursion: b({idx}, {deg}, t) at n = {degree}; a recursion reads "
                "the degree below, b(., n - 1, t)"
            )
        return below[idx] if 0 <= idx <= deg else field(0)

    rec = defn.recursion
    return tuple(
        _instantiate(rec, {_N: degree, _I: idx}, field, lookup) for idx in range(degree + 1)
    )


@cache
def _basis_polys(defn: Definition, degree: int) -> tuple[sp.Poly, ...]:
    big = degree + defn.offset
    out = []
    for idx, value in enumerate(_basis_values(defn, degree)):
        if not value.denom.is_ground:
            raise DefinitionError(
                f"[family] basis: b({idx}, {degree}, t) is not a polynomial: "
                f"{sp.factor(value.as_expr())} (a negative power that does not cancel)"
            )
        numer = value.numer.quo_ground(value.denom.LC)  # the denominator is a number
        p = sp.Poly.from_dict(dict(numer), t, lam, domain="QQ")  # same t, lam symbols
        if p.degree(t) > big:
            raise DefinitionError(
                f"[family] basis: b({idx}, {degree}, t) has degree {p.degree(t)} in t, more "
                f"than n + degree_offset = {big}"
            )
        out.append(p)
    return tuple(out)


def check(defn: Definition) -> list[str]:
    """The definition's own claims, for every degree: what was checked (raises on failure)."""
    done = []
    one = sp.Poly(1, t, lam, domain="QQ")
    for deg in defn.degrees:
        polys = basis_polys(defn, deg)
        big = deg + defn.offset
        total = sum(polys[1:], polys[0])
        if total != one:
            raise DefinitionError(
                f"[family] basis: no partition of unity at n = {deg}: the functions sum to "
                f"{sp.factor(total.as_expr())}"
            )
        if defn.bernstein_at is not None:
            x = sp.Rational(defn.bernstein_at.numerator, defn.bernstein_at.denominator)
            for idx, p in enumerate(polys):
                want = sp.Poly(comb(deg, idx) * t**idx * (1 - t) ** (deg - idx), t, domain="QQ")
                got = sp.Poly(p.eval(lam, x).as_expr(), t, domain="QQ")
                if got != want:
                    raise DefinitionError(
                        f"[family] bernstein_at: at {defn.parameter} = {x}, b({idx}, {deg}, t) "
                        f"= {sp.factor(got.as_expr())}, not the Bernstein function "
                        f"{sp.factor(want.as_expr())}"
                    )
        generic = max(p.degree(t) for p in polys)
        if generic != big:
            raise DefinitionError(
                f"[family] degree_offset: at n = {deg} the basis functions have degree "
                f"{generic} in t, not n + degree_offset = {big}"
            )
    done.append(
        f"polynomials of degree n + {defn.offset}, n = {defn.degrees.start}.."
        f"{defn.degrees.stop - 1}"
    )
    done.append("partition of unity, every degree")
    if defn.bernstein_at is not None:
        done.append(f"Bernstein basis at {defn.parameter} = {defn.bernstein_at}, every degree")
    return done


# --------------------------------------------------------------------------- artifacts


def _lam_coeffs(p: sp.Poly) -> list[str]:
    """A polynomial in lam as its coefficients, constant first, exact strings."""
    return [str(c) for c in reversed(p.all_coeffs())]


def endpoint_table(defn: Definition) -> dict[str, dict[str, list[str]]]:
    """{n: {"start,r,j" | "end,r,j": lam-coefficients}}: d^r/dt^r of b_j (start, at t = 0)
    and of b_{n-j} (end, at t = 1)."""
    return _endpoint_table(defn)


@cache
def _endpoint_table(defn: Definition) -> dict[str, dict[str, list[str]]]:
    out = {}
    for deg in defn.degrees:
        row = {}
        for idx, p in enumerate(basis_polys(defn, deg)):
            d = p
            for r in range(ENDPOINT_ORDERS + 1):
                for end, at, j in (("start", 0, idx), ("end", 1, deg - idx)):
                    value = d.eval(t, at)  # a Poly in lam
                    if not value.is_zero:
                        row[f"{end},{r},{j}"] = _lam_coeffs(value)
                d = d.diff(t)
        out[str(deg)] = dict(sorted(row.items()))
    return out


def closed_endpoint_forms(defn: Definition) -> dict[tuple[str, int, int], sp.Expr] | None:
    """Closed forms in n of the end values/derivatives of orders 0..closed_endpoint_order():
    for each entry, the polynomial in n (of degree at most #degrees - 3) through the values at
    all degrees but the last two that also gives those two. An order is in closed form only
    when every entry of it and of the orders below has such a polynomial (a family whose
    second derivative at 0 involves P_n, say, has its values and first derivatives in closed
    form and its second per degree). None when not even the end values are (or the range has
    fewer than five degrees): then the family is checked per degree only."""
    forms, order = _closed_endpoint_forms(defn)
    return forms if order >= 0 else None


def closed_endpoint_order(defn: Definition) -> int:
    """The highest order r such that the end derivatives of orders 0..r are in closed form in
    n (-1: none)."""
    return _closed_endpoint_forms(defn)[1]


@cache
def _closed_endpoint_forms(defn: Definition) -> tuple[dict[tuple[str, int, int], sp.Expr], int]:
    table = endpoint_table(defn)
    keys = sorted({k for row in table.values() for k in row})
    nn = _algebra_n()
    out = {}
    degrees = list(defn.degrees)
    if len(degrees) < 5:
        return {}, -1
    failed = ENDPOINT_ORDERS + 1  # the lowest order with an entry that has no closed form
    for key in keys:
        end, r, j = key.split(",")
        pts = [(deg, table[str(deg)].get(key, ["0"])) for deg in degrees if int(j) <= deg]
        form = sp.Integer(0) if len(pts) >= 5 else None
        width = max(len(c) for _, c in pts)
        for p in range(width if form is not None else 0):
            xs = [sp.Integer(deg) for deg, _ in pts]
            ys = [sp.Rational(c[p]) if p < len(c) else sp.Integer(0) for _, c in pts]
            poly = sp.interpolate(list(zip(xs[:-2], ys[:-2], strict=True)), nn)
            if any(poly.subs(nn, x) != y for x, y in zip(xs[-2:], ys[-2:], strict=True)):
                form = None
                break
            form += sp.expand(poly) * lam**p
        if form is None:
            failed = min(failed, int(r))
        elif form != 0:
            out[(end, int(r), int(j))] = sp.factor(form)
    return {key: v for key, v in out.items() if key[1] < failed}, failed - 1


def _algebra_n():
    from ._algebra import n

    return n


def energy_artifacts(defn: Definition) -> dict:
    """{"n,k": {"ff": [scale, U], "fg": [...], "gg": [...]}} and the published (c, X, Y), or a
    reason when the basis is not linear in the parameter."""
    from . import energy

    out: dict = {}
    for deg in defn.degrees:
        polys = basis_polys(defn, deg)
        if lambda_degree(polys) == 0:
            return {"reason": f"the basis does not depend on {defn.parameter}: nothing to optimise"}
        if lambda_degree(polys) > 1:
            return {
                "reason": f"the basis is of degree {lambda_degree(polys)} in "
                f"{defn.parameter} at n = {deg}: E_k is not a quadratic in it"
            }
        for k in ENERGY_ORDERS:
            forms = energy.forms_from_polys(polys, deg + defn.offset, k)
            entry = {key: [str(s), [list(r) for r in u]] for key, (s, u) in forms.items()}
            (s_fg, x), (s_gg, y) = forms["fg"], forms["gg"]
            if s_gg != 0:
                entry["published"] = [str(s_fg / s_gg), [list(r) for r in x], [list(r) for r in y]]
            out[f"{deg},{k}"] = entry
    return out


def join_artifacts(defn: Definition, closed: dict) -> dict:
    """Closed-form join weights (derive/joins.py's solve) of the family after and before
    itself and every built-in family, each checked per degree pair; a pair whose stencil the
    closed-form solve does not cover is named with the reason (the runtime still joins it,
    per degree)."""
    from . import joins

    out: dict = {}
    order = closed_endpoint_order(defn)
    with joins.extra_family(defn.name, closed, tuple(defn.degrees), True, order):
        for other in (*builtin_names(), defn.name):
            for first, second in ((defn.name, other), (other, defn.name)):
                if (first, second) == (defn.name, defn.name) and f"{first}>{second}" in out:
                    continue
                solved, reasons = {}, []
                for k in (1, 2):
                    if k > order:
                        reasons.append(
                            f"{'C2/G2' if k == 2 else 'C1/G1'}: the end derivatives of order "
                            f"{k} have no closed form in n (the runtime joins per degree)"
                        )
                        continue
                    try:
                        solved[k] = joins.solve(first, second, k)
                    except (AssertionError, KeyError, ZeroDivisionError) as exc:
                        reasons.append(f"{'C2/G2' if k == 2 else 'C1/G1'}: no closed form: {exc}")
                weights = {}
                for cont in CONTINUITIES:
                    if joins.ORDER[cont] not in solved:
                        continue
                    for r, combo in enumerate(solved[joins.ORDER[cont]]):
                        for (src, j), w in sorted(combo.items()):
                            e = w.as_expr()
                            if cont in ("C1", "C2"):
                                e = e.xreplace({joins.alpha: 1, joins.d: 0})
                            e = sp.factor(e)
                            if e != 0:
                                weights[f"{cont},{r},{src},{j}"] = str(e)
                entry: dict = {"weights": weights} if solved else {}
                if reasons:
                    entry["reason"] = "; ".join(reasons)
                out[f"{first}>{second}"] = entry
    return out


# --------------------------------------------------------------------------- the document


def _matrices(mats) -> list:
    return [[[str(Fraction(v)) for v in row] for row in mat] for mat in mats]


def derive(defn: Definition, *, with_joins: bool = True) -> dict:
    """Every artifact of the family, as one JSON-able document (exact numbers as strings)."""
    checked = check(defn)
    tables = expansion_tables(lambda deg: basis_polys(defn, deg), tuple(defn.degrees), defn.offset)
    closed = closed_endpoint_forms(defn)
    doc = {
        "generated_by": "lambda-bezier derive --family -- DO NOT EDIT; regenerate with "
        "`lambda-bezier derive --family FILE`",
        "format": FORMAT,
        "definition_sha256": defn.digest,
        "family": defn.name,
        "title": defn.title,
        "parameter": defn.parameter,
        "range": {
            "text": defn.range_text,
            "lo": str(defn.lo),
            "hi": str(defn.hi),
            "closed": [defn.lo_closed, defn.hi_closed],
        },
        "degrees": [defn.degrees.start, defn.degrees.stop - 1],
        "degree_offset": defn.offset,
        "bernstein_at": None if defn.bernstein_at is None else str(defn.bernstein_at),
        "checked": checked,
        "basis": {
            str(deg): [str(p.as_expr()) for p in basis_polys(defn, deg)] for deg in defn.degrees
        },
        "power": {str(k): _matrices(v) for k, v in tables["power"].items()},
        "bernstein": {str(k): _matrices(v) for k, v in tables["bernstein"].items()},
        "centred": {str(k): _matrices(v) for k, v in tables["centred"].items()},
        "endpoints": endpoint_table(defn),
        "endpoint_closed_orders": closed_endpoint_order(defn),
        "endpoint_closed_forms": None
        if closed is None
        else {f"{e},{r},{j}": str(v) for (e, r, j), v in sorted(closed.items())},
        "energy": energy_artifacts(defn),
        "singular_parameters": singular_artifacts(defn),
    }
    if with_joins:
        doc["joins"] = (
            {"reason": "no closed end forms in n: the runtime joins per degree"}
            if closed is None
            else join_artifacts(defn, closed)
        )
    return doc


def render(defn: Definition) -> str:
    """The derived document as deterministic text (sorted keys, fixed separators)."""
    # keys in the order derive() builds them (every loop there runs over sorted keys), so the
    # banner comes first; the text does not depend on PYTHONHASHSEED
    return json.dumps(derive(defn), indent=1, ensure_ascii=False) + "\n"


def _register_properties(defn: Definition) -> None:
    from . import properties

    interval = properties.Interval(defn.lo, defn.hi, not defn.lo_closed, not defn.hi_closed)
    properties.register(
        defn.name, lambda degree: basis_polys(defn, degree), defn.offset, defn.degrees, interval
    )


def singular_artifacts(defn: Definition) -> dict[str, list]:
    """{n: [root, ...]}: the parameters inside the range where the degree-n basis is linearly
    dependent (derive/properties.py: the determinant of the Bernstein coefficients, exact root
    isolation); a root is an exact "p/q" or [[lo, hi], [c_0, ..., c_k]] around an irrational
    root of the integer polynomial Σ c_j λ^j."""
    from . import properties

    _register_properties(defn)
    iv = properties.FAMILY_RANGES[defn.name]
    out = {}
    for deg in defn.degrees:
        out[str(deg)] = [
            str(r.exact)
            if r.exact is not None
            else [[str(r.lo), str(r.hi)], [int(c) for c in r.factor]]
            for r in properties.singular_roots(defn.name, deg, iv)
        ]
    return out


class _EnergyBasis:
    """What derive/energy.py reads of a family module, for a family defined by data."""

    def __init__(self, defn: Definition):
        self.defn = defn
        self.DEGREE_OFFSET = defn.offset
        self.DEGREES = defn.degrees

    def basis_polys(self, degree: int) -> list[sp.Poly]:
        return basis_polys(self.defn, degree)


def register(defn: Definition, points: str = "P") -> None:
    """Make the family known to verify for this process: its records are checked by the same
    checkers as a built-in family's (per degree always; symbolically in n where the engine
    found closed end forms; energies where the basis is linear in the parameter)."""
    from . import energy, joins, verify_checks

    check(defn)
    closed = closed_endpoint_forms(defn)
    verify_checks.register_family(
        verify_checks.Family(
            defn.name,
            defn.degrees,
            points,
            lambda degree: basis_polys(defn, degree),
            defn.offset,
            lambda: closed,
            closed_order=closed_endpoint_order(defn),
        )
    )
    energy.EXTRA[defn.name] = _EnergyBasis(defn)
    _register_properties(defn)
    if closed is not None:
        joins.register(defn.name, closed, tuple(defn.degrees), True, closed_endpoint_order(defn))


FAMILY_DEFINITIONS = Path(__file__).resolve().parent / "families"


@dataclass(frozen=True)
class Builtin:
    """A family the project ships: its definition (the [family] table of
    derive/families/<name>.toml) and how it is shipped (the file's [builtin] table)."""

    definition: Definition
    order: int  # position in generated/ and in reports
    points: str  # the control points' name in the paper's records
    curve_class: str  # the runtime's class name for its curves
    # derive/<derivation>.py: the paper's own closed forms and the emitted module; without one
    # the engine derives and emits the family from its definition alone (GenericDerivation)
    derivation: str | None = None
    # the degree symbols of the first and second curve of the paper's join records that do not
    # name their curves (000's eq. 17 says p1 has degree m, 001's eq. 12 says n)
    join_degrees: tuple[str, str] = ("n", "m")
    checks: str | None = None  # derive/<checks>.py: checkers of claims only this paper makes

    @property
    def name(self) -> str:
        return self.definition.name

    def module(self):
        """The derivation module (imported on demand: it imports this engine), or the engine's
        own derivation of the family when its paper prints no closed form of its own."""
        if self.derivation is None:
            return _generic_derivation(self.definition)
        import importlib

        return importlib.import_module(f"{__package__}.{self.derivation}")


class GenericDerivation:
    """What a derivation module provides (DEGREES, DEGREE_OFFSET, basis_polys,
    closed_end_forms, OUTPUT, render), for a built-in family from its definition alone: the
    emitted module has the tables and the end forms in closed form in n (fitted, then checked
    against every degree of the range), and no general form of a paper's own."""

    SCRIPT = "family_engine.py"

    def __init__(self, defn: Definition):
        self.DEFINITION = defn
        self.DEGREES = defn.degrees
        self.DEGREE_OFFSET = defn.offset
        self.OUTPUT = f"{defn.name}.py"

    def basis_polys(self, degree: int) -> list[sp.Poly]:
        return basis_polys(self.DEFINITION, degree)

    def closed_end_forms(self) -> dict[tuple[str, int, int], sp.Expr]:
        closed = closed_endpoint_forms(self.DEFINITION)
        if closed is None:
            raise DefinitionError(
                f"{self.DEFINITION.name}: a built-in family needs its end values and "
                "derivatives in closed form in n (the joins are emitted in n, m); this "
                "definition has none, so give it a derivation module or keep it a user family"
            )
        return {key: v for key, v in closed.items() if key[1] <= 2}

    def render(self) -> str:
        from . import _emit
        from ._algebra import check_endpoint_closed_forms

        defn = self.DEFINITION
        check(defn)
        closed = self.closed_end_forms()
        check_endpoint_closed_forms(closed, {d: self.basis_polys(d) for d in defn.degrees}, 2)
        return _emit.family_module(
            script=self.SCRIPT,
            doc=f"{defn.title or defn.name}: derived from its definition alone.",
            definition=defn,
            **expansion_tables(self.basis_polys, tuple(defn.degrees), defn.offset),
            general_forms=[],
            endpoint=closed,
        )


@cache
def _generic_derivation(defn: Definition) -> GenericDerivation:
    return GenericDerivation(defn)


_BUILTIN_SCHEMA = {
    "type": "object",
    "properties": {
        "order": {"type": "integer", "minimum": 0},
        "derivation": {"type": "string", "pattern": _NAME},
        "points": {"type": "string", "pattern": r"^[A-Za-z]$"},
        "curve_class": {"type": "string", "pattern": r"^[A-Z][A-Za-z0-9]*Curve$"},
        "join_degrees": {
            "type": "array",
            "items": {"enum": ["n", "m"]},
            "minItems": 2,
            "maxItems": 2,
            "uniqueItems": True,
        },
        "checks": {"type": "string", "pattern": _NAME},
    },
    "required": ["order", "points", "curve_class"],
    "additionalProperties": False,
}


@cache
def builtin_families() -> tuple[Builtin, ...]:
    """Every family in derive/families/, in their `order`: the one list of built-in families
    the derivations, the emitter and verify iterate over (no shared module names one)."""
    import jsonschema

    if sys.version_info >= (3, 11):
        import tomllib
    else:  # pragma: no cover - Python 3.10
        import tomli as tomllib

    out = []
    for path in sorted(FAMILY_DEFINITIONS.glob("*.toml")):
        info = tomllib.loads(path.read_text(encoding="utf-8")).get("builtin")
        errors = list(jsonschema.Draft202012Validator(_BUILTIN_SCHEMA).iter_errors(info))
        if errors:
            raise DefinitionError(f"{path}: [builtin]: {errors[0].message}")
        defn = read_definition(path, builtin=True)
        if path.stem != defn.name:
            raise DefinitionError(f"{path}: the file must be named after the family {defn.name}")
        if "join_degrees" in info:
            info["join_degrees"] = tuple(info["join_degrees"])
        out.append(Builtin(defn, **info))
    out.sort(key=lambda b: b.order)
    if len({b.order for b in out}) != len(out):
        raise DefinitionError(f"{FAMILY_DEFINITIONS}: two built-in families share an order")
    return tuple(out)


def builtin(name: str) -> Builtin:
    for fam in builtin_families():
        if fam.name == name:
            return fam
    raise KeyError(name)


def derivation(name: str):
    """The derive module of a built-in family, or derive/bernstein.py for the reference basis:
    each has DEGREES and closed_end_forms() (the end values and derivatives in closed form)."""
    if name == REFERENCE:
        from . import bernstein

        return bernstein
    return builtin(name).module()


def builtin_names() -> tuple[str, ...]:
    """The reference basis, then the built-in families in order."""
    return (REFERENCE, *(b.name for b in builtin_families()))


def builtin_definition(name: str) -> Definition:
    """A built-in family's definition as data (derive/families/<name>.toml)."""
    return read_definition(FAMILY_DEFINITIONS / f"{name}.toml", builtin=True)


def derived_path(definition_file: Path, name: str, out_dir: Path | None = None) -> Path:
    return (out_dir or Path(definition_file).resolve().parent) / f"{name}.derived.json"
