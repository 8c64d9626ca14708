"""The formula grammar of records files and family definitions: text in, SymPy out, nothing run.

A records file or a family definition is untrusted input, so its formulas are read by this
module's own tokenizer and recursive-descent parser, never by ``eval``, ``exec``, ``sympify``
or ``parse_expr``. The language is a small subset of Python's expression syntax, with Python's
precedence so that a formula reads the way it looks:

    relation := bitor [("<" | "<=" | ">" | ">=") bitor]      (no chains)
    bitor    := bitand ("|" bitand)*                           (relations only)
    bitand   := arith ("&" arith)*                             (relations only)
    arith    := term (("+" | "-") term)*
    term     := factor (("*" | "/") factor)*
    factor   := ("+" | "-") factor | power
    power    := atom ["**" factor]                             (right-associative)
    atom     := NUMBER | SYMBOL | FUNCTION "(" args ")" | "(" relation ")" | "(" tuple ")"

Numbers are ASCII decimal literals, exact: ``3``, ``1/2`` (a quotient of integers is a
rational), ``0.25`` (read as 1/4, never a float). Names are looked up in fixed tables:
symbols (``t``, ``n``, ``lam``, ...), undefined functions (``b``, ``B``, ``P``, ``p``, ...) and
the built-in forms ``Sum(expr, (i, lo, hi))``, ``Integral(expr, (t, lo, hi))``,
``Derivative(expr, t)``, ``Derivative(expr, t, 2)``, ``Derivative(expr, (t, k))``,
``Subs(expr, t, value)``, ``binomial(a, b)`` and ``factorial(a)``. Anything else (another
name, an attribute, a subscript, a string, a keyword argument, a lambda, a comprehension, a
character outside the language) is refused with a ``ParseError`` naming the text and the
column.

Limits keep a hostile formula from hanging or crashing the checker: the text's length, the
nesting depth, the size of integer literals, and constant exponents (``t**10**10`` and
``2**2**40`` are refused while they are parsed, before anything is computed). The evaluator
applies the same exponent limit to exponents that become concrete only later (``t**n``), and
bounds summation ranges and derivative orders (derive/verify/realiser.py).

Binomials follow the papers: ``binomial(a, b)`` with integer literals is C_a^b, zero unless
0 <= b <= a (SymPy's own ``binomial`` differs for negative arguments).
"""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from fractions import Fraction
from math import comb

import sympy as sp

from .messages import clip

# --------------------------------------------------------------------------- limits

MAX_TEXT = 10_000  # characters in one formula
MAX_DEPTH = 60  # nesting of parentheses, calls and unary signs
MAX_DIGITS = 400  # digits in one number literal
MAX_EXPONENT = 1_000  # |e| of a constant integer exponent, here and in the evaluator
MAX_CONSTANT_BITS = 100_000  # size of a number computed while parsing (a power of literals)
MAX_FACTORIAL = 1_000  # factorial(a) of a literal a
MAX_ARGS = 16  # arguments of one call


class ParseError(ValueError):
    """A formula outside the grammar or its limits (the message names the text and where)."""


# --------------------------------------------------------------------------- the tables

SYMBOL_NAMES = (
    "t u x c tstar n m i j k l r lam lam1 lam2 alpha beta d C omega".split()  # noqa: SIM905
)
FUNCTION_NAMES = (
    "b B A f a p p1 p2 P P1 P2 V V1 V2 Vl Ql Q W F G E y kappa bk Delta dot cross norm".split()  # noqa: SIM905
)
SYMBOLS: dict[str, sp.Symbol] = {name: sp.Symbol(name) for name in SYMBOL_NAMES}
FUNCTIONS: dict[str, sp.FunctionClass] = {name: sp.Function(name) for name in FUNCTION_NAMES}
BUILTINS = ("Sum", "Integral", "Derivative", "Subs", "binomial", "factorial")
# the elementary functions of family definitions (issue #30), only with `elementary=True`:
# each applied to a rational multiple of t or of pi*t, and the constant `pi`
ELEMENTARY: dict[str, sp.FunctionClass] = {
    "sin": sp.sin,
    "cos": sp.cos,
    "sinh": sp.sinh,
    "cosh": sp.cosh,
    "exp": sp.exp,
}
MAX_FREQUENCY = 1_000  # numerator and denominator of the rate w in sin(w*t)
# the integral operators of a family's `recursion` (bases defined by integral recursions,
# Chen and Wang 2003), only with `operators=True`; each takes one function of t:
#   integral(f)   = the integral of f from the domain's start to t (f's t is the variable)
#   total(f)      = the integral of f over the whole domain (a number: a function of the
#                   parameters only)
#   normalized(f) = f / total(f), and 0 when f is the zero function (b(i, n, t) outside
#                   0..n: the convention that makes delta * b vanish there)
#   kronecker(a, b) = 1 when the integers a and b are equal, else 0 (the [i = 0] term)
OPERATORS: dict[str, sp.FunctionClass] = {
    name: sp.Function(name) for name in ("integral", "total", "normalized")
}
MAX_OPERATOR_NESTING = 4  # integral(integral(...)) nested deeper than this is refused


# --------------------------------------------------------------------------- tokens

_TOKEN = re.compile(
    r"(?P<space>[ \t\r\n]+)"
    r"|(?P<number>[0-9]+(?:\.[0-9]*)?|\.[0-9]+)"
    r"|(?P<name>[A-Za-z_][A-Za-z0-9_]*)"
    r"|(?P<op>\*\*|<=|>=|[-+*/()<>,&|])",
    re.ASCII,
)


@dataclass(frozen=True)
class Token:
    kind: str  # "number" | "name" | "op" | "end"
    text: str
    pos: int


def tokenize(text: str) -> list[Token]:
    out: list[Token] = []
    pos = 0
    while pos < len(text):
        m = _TOKEN.match(text, pos)
        if m is None:
            ch = text[pos]
            what = {
                "'": "a string",
                '"': "a string",
                ".": "an attribute access",
                "[": "a subscript",
                "=": "'=' (a keyword argument or an assignment)",
                "^": "'^' (write powers as **)",
                "!": "'!' (write factorial(n))",
            }.get(ch, f"the character {ch!r}")
            raise ParseError(f"{what} is not allowed in a formula: {_at(text, pos)}")
        kind = m.lastgroup or ""
        if kind != "space":
            out.append(Token(kind, m.group(), pos))
        pos = m.end()
    out.append(Token("end", "", len(text)))
    return out


_SHOWN = 120  # characters of a formula an error message quotes around the column


def _at(text: str, pos: int) -> str:
    # A 10,000-character formula is legal: quote the stretch around the fault, not all of it.
    if len(text) <= _SHOWN:
        return f"{text!r} at column {pos + 1}"
    lo = max(0, min(pos - _SHOWN // 2, len(text) - _SHOWN))
    piece = text[lo : lo + _SHOWN]
    before = "..." if lo > 0 else ""
    after = "..." if lo + _SHOWN < len(text) else ""
    return f"{before}{piece!r}{after} at column {pos + 1} of {len(text)}"


# --------------------------------------------------------------------------- values


def _is_bool(e: object) -> bool:
    return isinstance(e, sp.logic.boolalg.Boolean) and not isinstance(e, sp.Expr)


class _Tuple:
    """A parenthesised tuple: legal only as an argument of Sum, Integral, Derivative."""

    def __init__(self, items: list):
        self.items = items


def paper_binomial_expr(a: sp.Expr, b: sp.Expr) -> sp.Expr:
    """binomial(a, b) with the papers' convention where both are integers, else symbolic."""
    if a.is_Integer and b.is_Integer:
        return sp.Integer(comb(int(a), int(b)) if 0 <= int(b) <= int(a) else 0)
    return sp.binomial(a, b)


# --------------------------------------------------------------------------- the parser


class _Parser:
    def __init__(
        self,
        text: str,
        symbols: Mapping[str, sp.Symbol],
        functions: Mapping,
        elementary: bool = False,
        frequency: frozenset[sp.Symbol] = frozenset(),
        operators: bool = False,
    ):
        self.operators = operators
        self.operator_depth = 0
        self.elementary = elementary
        self.frequency = frequency
        self.text = text
        self.tokens = tokenize(text)
        self.pos = 0
        self.depth = 0
        self.symbols = symbols
        self.functions = functions

    # ---- helpers
    @property
    def tok(self) -> Token:
        return self.tokens[self.pos]

    def error(self, message: str, tok: Token | None = None) -> ParseError:
        tok = tok or self.tok
        return ParseError(f"{clip(message)}: {_at(self.text, tok.pos)}")

    def accept(self, *ops: str) -> Token | None:
        tok = self.tok
        if tok.kind == "op" and tok.text in ops:
            self.pos += 1
            return tok
        return None

    def expect(self, op: str) -> Token:
        tok = self.accept(op)
        if tok is None:
            found = "the end of the text" if self.tok.kind == "end" else repr(self.tok.text)
            raise self.error(f"expected {op!r}, found {found}")
        return tok

    def enter(self) -> None:
        self.depth += 1
        if self.depth > MAX_DEPTH:
            raise self.error(f"nesting deeper than {MAX_DEPTH} levels")

    # ---- grammar
    def parse(self) -> sp.Basic:
        e = self.relation()
        if self.tok.kind != "end":
            raise self.error(f"unexpected {self.tok.text!r}")
        if isinstance(e, _Tuple):
            raise self.error(
                "a tuple is allowed only as an argument of Sum, Integral or Derivative"
            )
        return e

    def relation(self):
        left = self.bitor()
        tok = self.accept("<", "<=", ">", ">=")
        if tok is None:
            return left
        right = self.bitor()
        if self.tok.kind == "op" and self.tok.text in ("<", "<=", ">", ">="):
            raise self.error("chained comparisons are not allowed; join them with &")
        for side in (left, right):
            self._arith_operand(side, tok)
        ops = {"<": sp.Lt, "<=": sp.Le, ">": sp.Gt, ">=": sp.Ge}
        return ops[tok.text](left, right)

    def bitor(self):
        left = self.bitand()
        while tok := self.accept("|"):
            right = self.bitand()
            left = sp.Or(self._bool_operand(left, tok), self._bool_operand(right, tok))
        return left

    def bitand(self):
        left = self.arith()
        while tok := self.accept("&"):
            right = self.arith()
            left = sp.And(self._bool_operand(left, tok), self._bool_operand(right, tok))
        return left

    def arith(self):
        left = self.term()
        while tok := self.accept("+", "-"):
            right = self.term()
            a, b = self._arith_operand(left, tok), self._arith_operand(right, tok)
            left = a + b if tok.text == "+" else a - b
        return left

    def term(self):
        left = self.factor()
        while tok := self.accept("*", "/"):
            right = self.factor()
            a, b = self._arith_operand(left, tok), self._arith_operand(right, tok)
            if tok.text == "/":
                if b == 0:
                    raise self.error("division by zero", tok)
                left = a / b
            else:
                left = a * b
        return left

    def factor(self):
        tok = self.accept("+", "-")
        if tok is None:
            return self.power()
        self.enter()
        operand = self._arith_operand(self.factor(), tok)
        self.depth -= 1
        return -operand if tok.text == "-" else operand

    def power(self):
        base = self.atom()
        tok = self.accept("**")
        if tok is None:
            return base
        self.enter()
        exponent = self.factor()
        self.depth -= 1
        base, exponent = self._arith_operand(base, tok), self._arith_operand(exponent, tok)
        if exponent.is_number:
            if not exponent.is_Integer:
                raise self.error(f"the exponent {exponent} is not an integer", tok)
            if abs(int(exponent)) > MAX_EXPONENT:
                raise self.error(f"the exponent {exponent} is larger than {MAX_EXPONENT}", tok)
            if base.is_number:
                if base == 0 and exponent < 0:
                    raise self.error("division by zero", tok)
                size = max(int(sp.numer(base)).bit_length(), int(sp.denom(base)).bit_length())
                if size * abs(int(exponent)) > MAX_CONSTANT_BITS:
                    raise self.error(f"the power {base}**{exponent} is too large to compute", tok)
        return base**exponent

    def atom(self):
        tok = self.tok
        if tok.kind == "number":
            self.pos += 1
            return self.number(tok)
        if tok.kind == "name":
            self.pos += 1
            return self.name(tok)
        if self.accept("("):
            self.enter()
            items = [self.relation()]
            while self.accept(","):
                items.append(self.relation())
            self.expect(")")
            self.depth -= 1
            if len(items) == 1:
                if isinstance(items[0], _Tuple):
                    raise self.error("nested tuples are not allowed", tok)
                return items[0]
            return _Tuple(items)
        if tok.kind == "end":
            raise self.error("the formula ends too early")
        raise self.error(f"unexpected {tok.text!r}")

    def number(self, tok: Token) -> sp.Rational:
        digits = tok.text.replace(".", "")
        if len(digits) > MAX_DIGITS:
            raise self.error(f"a number with more than {MAX_DIGITS} digits", tok)
        value = Fraction(tok.text)
        return sp.Rational(value.numerator, value.denominator)

    def name(self, tok: Token):
        name = tok.text
        called = self.tok.kind == "op" and self.tok.text == "("
        if name in self.symbols:
            if called:
                raise self.error(f"{name!r} is a symbol, not a function", tok)
            return self.symbols[name]
        if self.elementary and name == "pi":
            if called:
                raise self.error("'pi' is a constant, not a function", tok)
            return sp.pi
        if self.elementary and name in ELEMENTARY:
            if not called:
                raise self.error(f"{name!r} is a function and must be called", tok)
            self.pos += 1
            self.enter()
            args = self.arguments()
            self.depth -= 1
            return self.elementary_call(name, args, tok)
        if self.operators and (name in OPERATORS or name == "kronecker"):
            if not called:
                raise self.error(f"{name!r} is an operator and must be called", tok)
            self.pos += 1
            self.enter()
            nested = name in OPERATORS
            if nested:
                self.operator_depth += 1
                if self.operator_depth > MAX_OPERATOR_NESTING:
                    raise self.error(
                        f"integral operators nested deeper than {MAX_OPERATOR_NESTING} levels",
                        tok,
                    )
            args = self.arguments()
            self.operator_depth -= nested
            self.depth -= 1
            return self.operator_call(name, args, tok)
        if name in self.functions or name in BUILTINS:
            if not called:
                raise self.error(f"{name!r} is a function and must be called", tok)
            self.pos += 1
            self.enter()
            args = self.arguments()
            self.depth -= 1
            if name in BUILTINS:
                return self.builtin(name, args, tok)
            for a in args:
                if isinstance(a, _Tuple) or _is_bool(a):
                    raise self.error(f"an argument of {name} must be an expression", tok)
            return self.functions[name](*args)
        raise self.error(f"unknown name {name!r} (see the symbol and function table)", tok)

    def arguments(self) -> list:
        args: list = []
        if self.accept(")"):
            return args
        while True:
            args.append(self.relation())
            if len(args) > MAX_ARGS:
                raise self.error(f"more than {MAX_ARGS} arguments")
            if self.accept(")"):
                return args
            self.expect(",")

    def elementary_call(self, name: str, args: list, tok: Token):
        """sin, cos, sinh, cosh, exp of w*t with w a nonzero rational or a rational times pi:
        anything else (sin(t**2), sin(lam*t), sin(t + 1)) is refused here, by name."""
        if len(args) != 1 or isinstance(args[0], _Tuple) or _is_bool(args[0]):
            raise self.error(f"{name} takes one argument, a rational multiple of t", tok)
        arg = args[0]
        t = self.symbols.get("t")
        if self.frequency and arg.free_symbols & self.frequency:
            return self.frequency_call(name, arg, t, tok)
        rate = sp.expand(arg / t) if t is not None and arg.has(t) else None
        unit = rate / sp.pi if rate is not None and rate.has(sp.pi) else rate
        if unit is None or not unit.is_Rational or unit == 0:
            raise self.error(
                f"{name}({arg}): the argument must be a rational multiple of t or of pi*t "
                f"(such as {name}(2*t), {name}(t/3), {name}(pi*t/2))",
                tok,
            )
        if max(abs(int(unit.p)), int(unit.q)) > MAX_FREQUENCY:
            raise self.error(
                f"{name}({arg}): a rate larger than {MAX_FREQUENCY} in numerator or denominator",
                tok,
            )
        return ELEMENTARY[name](arg)

    def frequency_call(self, name: str, arg: sp.Expr, t: sp.Symbol | None, tok: Token):
        """sin(a*t + b*alpha + c*alpha*t) with rationals a, b, c and alpha a parameter allowed
        inside arguments (`frequency`: C-Bezier families on [0, alpha] or with sin(alpha*t))."""
        (alpha,) = sorted(arg.free_symbols & self.frequency, key=str)[:1]
        poly = None
        if arg.free_symbols <= {alpha} | ({t} if t is not None else set()):
            try:
                poly = sp.Poly(arg, *([alpha, t] if t is not None else [alpha]))
            except sp.PolynomialError:
                poly = None
        allowed = {(1, 0), (0, 1), (1, 1)} if t is not None else {(1,)}
        if (
            poly is None
            or len(arg.free_symbols & self.frequency) > 1
            or not set(poly.monoms()) <= allowed
            or not all(c.is_Rational for c in poly.coeffs())
        ):
            raise self.error(
                f"{name}({arg}): an argument with the parameter {alpha} is a*t + b*{alpha} + "
                f"c*{alpha}*t with rationals a, b, c (such as {name}({alpha} - t), "
                f"{name}({alpha}*t), {name}({alpha}))",
                tok,
            )
        for c in poly.coeffs():
            if max(abs(int(c.p)), int(c.q)) > MAX_FREQUENCY:
                raise self.error(
                    f"{name}({arg}): a rate larger than {MAX_FREQUENCY} in numerator or "
                    "denominator",
                    tok,
                )
        return ELEMENTARY[name](arg)

    def operator_call(self, name: str, args: list, tok: Token):
        """integral(f), total(f), normalized(f): one function of t; kronecker(a, b): two
        integer expressions (in i, n)."""
        count = 2 if name == "kronecker" else 1
        if len(args) != count or any(isinstance(a, _Tuple) or _is_bool(a) for a in args):
            what = "two integer expressions" if count == 2 else "one function of t"
            raise self.error(f"{name} takes {what}, got {len(args)} argument(s)", tok)
        if name == "kronecker":
            t = self.symbols.get("t")
            for a in args:
                if t is not None and a.has(t):
                    raise self.error(
                        f"kronecker({args[0]}, {args[1]}): its arguments are "
                        "integers (in i and n), not functions of t",
                        tok,
                    )
            return sp.KroneckerDelta(*args)
        return OPERATORS[name](args[0])

    # ---- the built-in forms
    def builtin(self, name: str, args: list, tok: Token):
        handler: Callable = getattr(self, f"_b_{name}")
        return handler(args, tok)

    def _plain(self, args: list, tok: Token, name: str, count: int | tuple[int, ...]) -> list:
        counts = (count,) if isinstance(count, int) else count
        if len(args) not in counts:
            want = " or ".join(str(c) for c in counts)
            raise self.error(f"{name} takes {want} arguments, got {len(args)}", tok)
        return args

    def _limit(self, item, tok: Token, name: str, size: int) -> tuple:
        if not isinstance(item, _Tuple) or len(item.items) != size:
            raise self.error(f"{name} needs a limit tuple of {size} entries", tok)
        var, *rest = item.items
        if not isinstance(var, sp.Symbol):
            raise self.error(f"{name}'s variable must be a symbol", tok)
        for r in rest:
            self._arith_operand(r, tok)
        return (var, *rest)

    def _with_limits(self, form, example: str, args: list, tok: Token):
        """Sum(expr, (i, lo, hi), ...) and Integral(expr, (t, lo, hi), ...)."""
        name = form.__name__
        if len(args) < 2:
            raise self.error(f"{name} takes an expression and at least one {example}", tok)
        body = self._arith_operand(args[0], tok)
        return form(body, *(self._limit(a, tok, name, 3) for a in args[1:]))

    def _b_Sum(self, args: list, tok: Token):
        return self._with_limits(sp.Sum, "(i, lo, hi)", args, tok)

    def _b_Integral(self, args: list, tok: Token):
        return self._with_limits(sp.Integral, "(t, lo, hi)", args, tok)

    def _b_Derivative(self, args: list, tok: Token):
        if len(args) < 2:
            raise self.error("Derivative takes an expression and a variable", tok)
        body = self._arith_operand(args[0], tok)
        rest: list = []
        for a in args[1:]:
            if isinstance(a, _Tuple):
                var, order = self._limit(a, tok, "Derivative", 2)
                rest.append((var, self._order(order, tok)))
            elif isinstance(a, sp.Symbol):
                rest.append(a)
            elif a.is_Integer and rest:
                rest.append(self._order(a, tok))
            else:
                raise self.error("Derivative's variables must be symbols or (t, order)", tok)
        return sp.Derivative(body, *rest)

    def _order(self, order, tok: Token):
        if order.is_number and (not order.is_Integer or not 0 <= order <= MAX_EXPONENT):
            raise self.error(f"a derivative order must be an integer in 0..{MAX_EXPONENT}", tok)
        return order

    def _b_Subs(self, args: list, tok: Token):
        body, var, value = self._plain(args, tok, "Subs", 3)
        if not isinstance(var, sp.Symbol):
            raise self.error("Subs's second argument must be a symbol", tok)
        return sp.Subs(self._arith_operand(body, tok), var, self._arith_operand(value, tok))

    def _b_binomial(self, args: list, tok: Token):
        a, b = (self._arith_operand(x, tok) for x in self._plain(args, tok, "binomial", 2))
        for x in (a, b):
            if x.is_number and (not x.is_Integer or abs(int(x)) > MAX_EXPONENT * 10):
                raise self.error(f"binomial's arguments must be integers (got {x})", tok)
        return paper_binomial_expr(a, b)

    def _b_factorial(self, args: list, tok: Token):
        (a,) = (self._arith_operand(x, tok) for x in self._plain(args, tok, "factorial", 1))
        if a.is_number and (not a.is_Integer or not 0 <= a <= MAX_FACTORIAL):
            raise self.error(f"factorial needs an integer in 0..{MAX_FACTORIAL} (got {a})", tok)
        return sp.factorial(a)

    # ---- operand checks
    def _arith_operand(self, e, tok: Token):
        if isinstance(e, _Tuple):
            raise self.error(f"a tuple cannot be an operand of {tok.text!r}", tok)
        if _is_bool(e):
            raise self.error(f"a condition cannot be an operand of {tok.text!r}", tok)
        return e

    def _bool_operand(self, e, tok: Token):
        if not _is_bool(e):
            raise self.error(f"{tok.text!r} joins conditions (such as (x >= 0)), not values", tok)
        return e


def parse_formula(
    text: object,
    symbols: Mapping[str, sp.Symbol] | None = None,
    functions: Mapping | None = None,
    *,
    elementary: bool = False,
    frequency: tuple[str, ...] = (),
    operators: bool = False,
) -> sp.Basic:
    """A formula of the records grammar as a SymPy object; ParseError for anything else.

    `symbols` and `functions` replace the default tables (a family definition adds its own
    parameter symbol, for instance). `elementary`: also `pi` and sin, cos, sinh, cosh, exp
    of a rational multiple of t or of pi*t (family definitions, issue #30). `frequency`: the
    names (in `symbols`) of parameters that may also stand in those arguments, as
    a*t + b*alpha + c*alpha*t with rationals a, b, c (C-Bezier families). `operators`: also
    integral(f), total(f), normalized(f) and kronecker(a, b) (a family's `recursion`, see
    OPERATORS), nested at most MAX_OPERATOR_NESTING deep."""
    if not isinstance(text, str):
        raise ParseError(f"a formula must be a string, got {type(text).__name__}")
    if len(text) > MAX_TEXT:
        raise ParseError(f"a formula longer than {MAX_TEXT} characters ({len(text)})")
    if not text.strip():
        raise ParseError("an empty formula")
    table = SYMBOLS if symbols is None else symbols
    parser = _Parser(
        text,
        table,
        FUNCTIONS if functions is None else functions,
        elementary,
        frozenset(table[name] for name in frequency),
        operators,
    )
    try:
        return parser.parse()
    except RecursionError:  # pragma: no cover - MAX_DEPTH keeps the recursion far from this
        raise ParseError(f"a formula nested too deeply: {text[:60]!r}...") from None
