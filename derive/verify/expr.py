"""Expressions of the published records: parsing with a fixed table, and exact evaluation.

Parsing. Formulas of records files (the built-in ones and a user's, which are untrusted) are read
by the records grammar of derive/grammar.py: our own tokenizer and parser over a FIXED table of
symbols and undefined functions, with limits on length, depth and exponents; nothing in a file is
ever evaluated as code.

Evaluation ("realising"). A parsed expression is evaluated for concrete degrees and indices by
a recursive walk with an environment {symbol: int}: the undefined functions are replaced by
*models* supplied by the checker (the derived basis functions, the curve, de Casteljau points,
...), sums are expanded, derivatives, substitutions and integrals are carried out. Control points
stay symbolic. Values are

* a SymPy expression (a scalar, rational in the parameters t, u, lam, ...),
* ``Form``: a polynomial in the control points (linear for a point, quadratic for a dot product)
  with scalar coefficients, keyed by sorted tuples of points ``("V", 3)``,
* ``Wedge``: an antisymmetric bilinear form (a cross product of two point combinations),
* ``Rad``: a scalar times a product of powers of Euclidean lengths (``norm``),
* ``Ratio``: a quotient of two Forms.

Binomial convention. The papers use C_n^k = 0 unless 0 <= k <= n (including a negative n).
SymPy's ``binomial`` does not (``binomial(-2, 1) == -2``), so a concrete binomial is always
evaluated by ``paper_binomial``; the walk substitutes values itself (never ``subs`` on the
whole expression) so that SymPy cannot evaluate a binomial with its own convention first.
A product whose function factor is zero (e.g. ``B(-1, n, t)``) is zero without evaluating its
other factors, so a coefficient 0/0 beside a vanishing basis function is never formed.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from fractions import Fraction
from functools import cache, lru_cache
from math import comb, factorial, gcd

import flint
import sympy as sp
from sympy.core.function import AppliedUndef

from .grammar import MAX_EXPONENT, MAX_FACTORIAL, SYMBOLS, parse_formula
from .grammar import ParseError as ParseError  # re-exported: callers catch it from here

INDEX_SYMBOLS = tuple(SYMBOLS[s] for s in ["i", "j", "k", "l", "r"])
DEGREE_SYMBOLS = (SYMBOLS["n"], SYMBOLS["m"])
# Functions whose first argument is a control-point index (shifted by the difference operator).
POINT_LIKE = frozenset(["b", "bk", "a", "P", "P1", "P2", "V", "V1", "V2", "Vl", "Ql", "Q", "W"])
# Summation ranges a formula may ask for (a hostile Sum(..., (i, 0, 10**9)) is refused).
MAX_SUM_TERMS = 10_000


def as_sympy(x: object) -> sp.Basic:
    """A number or a SymPy object as SymPy; a string is refused (sympify would evaluate it)."""
    if isinstance(x, str):
        raise TypeError("a string reaches SymPy only through parse_formula")
    return sp.sympify(x, strict=True)


@cache
def parse(text: str) -> sp.Expr:
    """A printed expression, read by the records grammar (derive/grammar.py): our own parser
    over a fixed table of symbols and functions, nothing evaluated."""
    return parse_formula(text)


def parse_relation(text: str):
    """A boolean condition (convexity conclusions): relations joined by & and |."""
    return parse(text)


def fn_name(expr) -> str | None:
    return expr.func.__name__ if isinstance(expr, AppliedUndef) else None


# --------------------------------------------------------------------------- binomials


def paper_binomial(a: int, b: int) -> int:
    """C_a^b with the papers' convention: 0 unless 0 <= b <= a."""
    return comb(a, b) if 0 <= b <= a else 0


def as_int(x) -> int:
    """A concrete integer (index, degree, order) from an evaluated value."""
    if isinstance(x, int):
        return x
    if isinstance(x, (Fraction, flint.fmpq)) and x.denominator == 1:
        return int(x)
    if isinstance(x, Sc):
        c = x.c
        if type(c) is int:
            return c
        if c is not None and c.denominator == 1:
            return int(c.numerator)
        raise TypeError(f"{x.to_expr()} is not a concrete integer")
    x = as_sympy(x)
    if not x.is_Integer:
        raise TypeError(f"{x} is not a concrete integer")
    return int(x)


# --------------------------------------------------------------------------- values


class LimitError(ValueError):
    """A formula asks for more than the evaluator allows (an exponent, a sum, an order)."""


class Undefined(Exception):
    """The expression refers to something outside its definition (a negative degree, a degree
    outside the family's range, ...): that instance is not checked."""


# Scalars are exact rational functions of the parameters: num / (den · pden) with num, pden in
# the integer polynomial ring ZZ[PARAMS] and den a positive integer (integer coefficients are
# much faster than rational ones); a plain number is an int or an fmpq (the fast path). The
# ring is FLINT's fmpz_mpoly (python-flint): the checks are millions of small polynomial
# operations, and there it is 5-30x faster than SymPy's pure-Python PolyElement.
PARAMS = tuple(s for s in SYMBOLS.values() if s not in (*INDEX_SYMBOLS, *DEGREE_SYMBOLS))
_CTX = flint.fmpz_mpoly_ctx.get(tuple(str(s) for s in PARAMS), "lex")
GEN = dict(zip(PARAMS, _CTX.gens(), strict=True))
_GPOS = {sym: pos for pos, sym in enumerate(PARAMS)}
_GEN_SYMBOL = {str(g): sym for sym, g in GEN.items()}
_ONE = _CTX.constant(1)
_NVARS = len(PARAMS)


def _poly(terms: dict):
    """The ring element Σ coeff·x^monom of {monom tuple: int}."""
    return _CTX.from_dict(terms)


def _is_constant(poly) -> bool:
    # len() (the number of terms) first: fmpz_mpoly.is_constant() costs a microsecond
    return len(poly) == 0 or (len(poly) == 1 and poly.is_constant())


def _degree(poly, pos: int) -> int:
    """Degree in generator `pos` (-1 for the zero polynomial)."""
    return int(poly.degrees()[pos])


def poly_expr(poly, symbols=PARAMS) -> sp.Expr:
    """An fmpz_mpoly (generators `symbols`, default the parameters) as a SymPy expression."""
    return sp.Add(
        *(
            sp.Integer(int(c))
            * sp.Mul(*(g ** int(e) for g, e in zip(symbols, m, strict=True) if e))
            for m, c in poly.terms()
        )
    )


def _lcm(a: int, b: int) -> int:
    return a // gcd(a, b) * b


_fmpq = flint.fmpq


def _q(p: int, q: int):
    """p/q as an int when exact (ints are cheapest), else FLINT's fmpq (ten times faster than
    a Fraction; it never leaves Sc: ground() gives a Fraction)."""
    return p // q if p % q == 0 else _fmpq(p, q)


def _inv(c):
    if isinstance(c, int):
        return _fmpq(1, c) if c not in (1, -1) else c
    return 1 / c


class Sc:
    """An exact scalar: the number `c` (an int, or an fmpq) when it is constant, else
    num / (den · pden)."""

    __slots__ = ("c", "num", "den", "pden")

    @staticmethod
    def const(c) -> Sc:
        out = object.__new__(Sc)
        out.c, out.num, out.den, out.pden = c, None, 1, None
        return out

    def __init__(self, num=None, den: int = 1, pden=None, c=None):
        if c is not None:
            self.c, self.num, self.den, self.pden = c, None, 1, None
            return
        if pden is not None:
            if not pden:
                raise Undefined("division by zero")
            if _is_constant(pden):
                den, pden = den * int(pden.leading_coefficient()), None
        if den < 0:
            num, den = -num, -den
        if pden is None and _is_constant(num):
            self.c, self.num, self.den, self.pden = (
                _q(int(num.leading_coefficient()) if num else 0, den),
                None,
                1,
                None,
            )
            return
        if den > 1:
            g = gcd(int(num.content()), den)
            if g > 1:
                num, den = num / g, den // g
        self.c, self.num, self.den, self.pden = None, num, den, pden

    # ---- construction and conversion

    @staticmethod
    def of(x) -> Sc:
        if isinstance(x, Sc):
            return x
        if isinstance(x, int):
            return Sc.const(x)
        if isinstance(x, Fraction):
            return Sc.const(_q(x.numerator, x.denominator))
        if isinstance(x, _fmpq):
            return Sc.const(x)
        x = as_sympy(x)
        if x.is_Rational:
            return Sc.const(_q(int(x.p), int(x.q)))
        if x.is_Symbol:
            return Sc(GEN[x])
        if x.is_Add:
            out = Sc.const(0)
            for a in x.args:
                out = out + Sc.of(a)
            return out
        if x.is_Mul:
            out = Sc.const(1)
            for a in x.args:
                out = out * Sc.of(a)
            return out
        if x.is_Pow and x.exp.is_Integer:
            return Sc.of(x.base) ** int(x.exp)
        raise TypeError(f"not a rational function of the parameters: {x}")

    @staticmethod
    def from_qq_poly(poly: sp.Poly) -> Sc:
        """A SymPy Poly with rational coefficients, in (some of) the parameters."""
        pos = [_GPOS[g] for g in poly.gens]
        den = 1
        for coeff in poly.coeffs():
            den = _lcm(den, int(sp.Rational(coeff).q))
        terms = {}
        for monom, coeff in poly.terms():
            e = [0] * _NVARS
            for p, x in zip(pos, monom, strict=True):
                e[p] = x
            q = sp.Rational(coeff)
            terms[tuple(e)] = int(q.p) * (den // int(q.q))
        return Sc(_poly(terms), den)

    def parts(self):
        """(num, den, pden) with num a ring element."""
        if self.c is not None:
            return _CTX.constant(int(self.c.numerator)), int(self.c.denominator), None
        return self.num, self.den, self.pden

    def to_expr(self) -> sp.Expr:
        if self.c is not None:
            return sp.Rational(int(self.c.numerator), int(self.c.denominator))
        den = sp.Integer(self.den) * (poly_expr(self.pden) if self.pden is not None else 1)
        return poly_expr(self.num) / den

    def generator(self) -> sp.Symbol | None:
        """The parameter symbol when this scalar is exactly that parameter, else None."""
        if self.c is not None or self.den != 1 or self.pden is not None:
            return None
        return _GEN_SYMBOL.get(str(self.num))

    def ground(self) -> Fraction | None:
        if self.c is None:
            return None
        return Fraction(int(self.c.numerator), int(self.c.denominator))

    def univariate(self, sym) -> list[Fraction] | None:
        """Coefficients (lowest power first) when this is a polynomial in `sym` alone, else
        None."""
        if self.c is not None:
            return [self.ground()]
        if self.pden is not None:
            return None
        pos = _GPOS[sym]
        coeffs: dict = {}
        for monom, c in self.num.terms():
            if any(e for p, e in enumerate(monom) if p != pos):
                return None
            coeffs[int(monom[pos])] = Fraction(int(c), self.den)
        return [coeffs.get(e, Fraction(0)) for e in range(max(coeffs) + 1)]

    def is_zero(self) -> bool:
        return self.c == 0 if self.c is not None else not self.num

    # ---- arithmetic

    def __add__(self, o):
        if type(o) is not Sc:
            o = Sc.of(o)
        c, oc = self.c, o.c
        if c is not None:
            if oc is not None:
                return Sc.const(c + oc)
            return o if c == 0 else o._plus_number(c)
        if oc is not None:
            return self if oc == 0 else self._plus_number(oc)
        a, da, pa = self.num, self.den, self.pden
        b, db, pb = o.num, o.den, o.pden
        # each FLINT operation costs about a microsecond however small the polynomial, so
        # the common cases (equal denominators) take the fewest
        if pa is None and pb is None:
            if da == db:
                return Sc(a + b, da)
            L = _lcm(da, db)
            return Sc(a * (L // da) + b * (L // db), L)
        if pa is not None and pb is not None and pa == pb:
            if da == db:
                return Sc(a + b, da, pa)
            L = _lcm(da, db)
            return Sc(a * (L // da) + b * (L // db), L, pa)
        pa1 = pa if pa is not None else _ONE
        pb1 = pb if pb is not None else _ONE
        return Sc((a * pb1) * db + (b * pa1) * da, da * db, pa1 * pb1)

    def _plus_number(self, c) -> Sc:
        """self + c for a nonzero number c (self not constant):
        num/(den·pden) + p/q = (num·q + p·den·pden) / (den·q·pden)."""
        p, q = (c, 1) if type(c) is int else (int(c.numerator), int(c.denominator))
        num, den, pden = self.num, self.den, self.pden
        shift = p * den
        if q != 1:
            num, den = num * q, den * q
        return Sc(num + shift if pden is None else num + pden * shift, den, pden)

    __radd__ = __add__

    def __neg__(self):
        if self.c is not None:
            return Sc.const(-self.c)
        return Sc(-self.num, self.den, self.pden)

    def __sub__(self, o):
        if type(o) is not Sc:
            o = Sc.of(o)
        if o.c is not None:
            return self + Sc.const(-o.c)
        if self.c is None and self.pden is None and o.pden is None and self.den == o.den:
            return Sc(self.num - o.num, self.den)
        return self + (-o)

    def __rsub__(self, o):
        return Sc.of(o) - self

    def __mul__(self, o):
        if type(o) is not Sc:
            o = Sc.of(o)
        c, oc = self.c, o.c
        if c is not None and oc is not None:
            return Sc.const(c * oc)
        if c is not None or oc is not None:
            k, p = (c, o) if c is not None else (oc, self)
            if k == 0:
                return ZERO
            if k == 1:
                return p
            return Sc(p.num * k.numerator, p.den * int(k.denominator), p.pden)
        if self.pden is None and o.pden is None:
            pden = None
        else:
            pden = (self.pden or _ONE) * (o.pden or _ONE)
        return Sc(self.num * o.num, self.den * o.den, pden)

    __rmul__ = __mul__

    def __truediv__(self, o):
        o = o if isinstance(o, Sc) else Sc.of(o)
        if o.is_zero():
            raise Undefined("division by zero")
        if o.c is not None:
            return self * Sc.const(_inv(o.c))
        a, da, pa = self.parts()
        b, db, pb = o.parts()
        num = a * db * (pb if pb is not None else _ONE)
        return Sc(num, da, (pa if pa is not None else _ONE) * b)

    def __rtruediv__(self, o):
        return Sc.of(o) / self

    def __pow__(self, k):
        k = int(k)
        if self.c is not None:
            if k < 0:
                if self.c == 0:
                    raise Undefined("zero to a negative power")
                return Sc.const(_inv(self.c ** (-k)))
            return Sc.const(self.c**k)
        if k >= 0:
            return Sc(self.num**k, self.den**k, None if self.pden is None else self.pden**k)
        return Sc.const(1) / self ** (-k)

    def __eq__(self, o):
        try:
            return (self - Sc.of(o)).is_zero()
        except (TypeError, sp.SympifyError):
            return NotImplemented

    __hash__ = None  # type: ignore[assignment]

    # ---- calculus in one parameter

    def diff(self, sym, count: int = 1) -> Sc:
        if self.c is not None:
            return self if count == 0 else Sc.const(0)
        g = _GPOS[sym]
        out = self
        for _ in range(count):
            if out.c is not None:
                return Sc.const(0)
            if out.pden is None or _degree(out.pden, g) <= 0:
                out = Sc(out.num.derivative(g), out.den, out.pden)
            else:
                n_, p_ = out.num, out.pden
                out = Sc(n_.derivative(g) * p_ - n_ * p_.derivative(g), out.den, p_**2)
        return out

    def subs(self, sym, value) -> Sc:
        if self.c is not None:
            return self
        value = value if isinstance(value, Sc) else Sc.of(value)
        num = _compose(self.num, _GPOS[sym], value)
        out = num * Sc.const(_q(1, self.den))
        if self.pden is not None:
            out = out / _compose(self.pden, _GPOS[sym], value)
        return out

    def integrate(self, sym, lo, hi) -> Sc:
        if self.c is not None:
            return self * (Sc.of(hi) - Sc.of(lo))
        pos = _GPOS[sym]
        if self.pden is not None and _degree(self.pden, pos) > 0:
            raise TypeError("cannot integrate a rational function")
        lo_c, hi_c = Sc.of(lo).c, Sc.of(hi).c
        if type(lo_c) is int and type(hi_c) is int:  # the common case: one FLINT call per end
            value, scale = _integral_between(self.num, pos, lo_c, hi_c)
            return Sc(value, self.den * scale, self.pden)
        scale, anti = self.num.integral(pos)  # anti' = scale·num
        anti = Sc(anti, self.den * int(scale), self.pden)
        return anti.subs(sym, hi) - anti.subs(sym, lo)


def _integral_between(poly, pos: int, lo: int, hi: int) -> tuple:
    """(value, scale) with ∫_lo^hi poly d(generator pos) = value / scale, for an integer
    polynomial of any FLINT context whose generators start with PARAMS."""
    scale, anti = poly.integral(pos)  # anti' = scale·poly, anti = 0 where the generator is 0
    name = str(PARAMS[pos])
    top = anti.subs({name: hi})
    return (top - anti.subs({name: lo}) if lo else top), int(scale)


ZERO = Sc.const(0)
ONE = Sc.const(1)


def _compose(poly, pos: int, value: Sc) -> Sc:
    """poly (a ring element) with generator `pos` replaced by value."""
    top = _degree(poly, pos)
    if top <= 0:
        return Sc(poly)
    if value.c is not None:
        p, q = int(value.c.numerator), int(value.c.denominator)
        if q == 1:
            return Sc(poly.subs({PARAMS[pos].name: p}))
        terms: dict = {}
        for monom, coeff in poly.terms():
            e = list(map(int, monom))
            k = e[pos]
            e[pos] = 0
            key = tuple(e)
            terms[key] = terms.get(key, 0) + int(coeff) * p**k * q ** (top - k)
        return Sc(_poly(terms), q**top)
    # poly(v/w)·w^top = Σ_k c_k·v^k·w^(top-k), c_k the coefficient of x_pos^k
    v, dv, pv = value.parts()
    w = _CTX.constant(dv) * (pv if pv is not None else _ONE)  # value = v / w
    by_power: dict = {}
    for monom, coeff in poly.terms():
        e = list(map(int, monom))
        k = e[pos]
        e[pos] = 0
        by_power.setdefault(k, {})[tuple(e)] = int(coeff)
    vpow = [_ONE]
    wpow = [_ONE]
    for _ in range(top):
        vpow.append(vpow[-1] * v)
        wpow.append(wpow[-1] * w)
    out = _CTX.constant(0)
    for k, terms_k in by_power.items():
        out += _poly(terms_k) * vpow[k] * wpow[top - k]
    return Sc(out, 1, wpow[top])


def _is_zero(expr) -> bool:
    """Exactly zero as a rational function of its symbols."""
    if isinstance(expr, Sc):
        return expr.is_zero()
    if isinstance(expr, (int, Fraction)):
        return expr == 0
    expr = as_sympy(expr)
    if expr.is_Number:
        return expr == 0
    try:  # fast path: exact rational-function arithmetic in a polynomial ring
        return not as_fraction(expr)[0]
    except _NotRational:
        return sp.cancel(expr) == 0


def _nz(expr) -> bool:
    return not _is_zero(expr)


def trivially_zero(v) -> bool:
    """Zero without a computation (models return an exact 0 for a vanishing function)."""
    if isinstance(v, (Form, Wedge)):
        return not v.terms
    if isinstance(v, Rad):
        return trivially_zero(v.coef)
    if isinstance(v, Sc):
        return v.is_zero()
    return not isinstance(v, (Ratio, DotSum)) and v == 0


class _NotRational(Exception):
    pass


@lru_cache(maxsize=64)
def _int_ctx(nvars: int):
    """FLINT's Z[x0, ..., x(nvars-1)] in lex order."""
    return flint.fmpz_mpoly_ctx.get(tuple(f"x{k}" for k in range(nvars)), "lex")


def as_fraction(expr) -> tuple:
    """(numerator, denominator, symbols) of a rational expression: integer polynomials
    (FLINT fmpz_mpoly, not cancelled) in `symbols`, its free symbols sorted by name (a Dummy
    when it has none), computed bottom-up with ring arithmetic, which is much faster than
    expanding the SymPy expression."""
    symbols = tuple(sorted(expr.free_symbols, key=str)) or (sp.Dummy("z"),)
    ctx = _int_ctx(len(symbols))
    index = dict(zip(symbols, ctx.gens(), strict=True))
    num, den = _frac(expr, ctx, index)
    return num, den, symbols


def _frac(e, ctx, index):
    if e.is_Rational:
        return ctx.constant(int(e.p)), ctx.constant(int(e.q))
    if e.is_Symbol:
        if e not in index:
            raise _NotRational(e)
        return index[e], ctx.constant(1)
    if e.is_Add:
        num, den = ctx.constant(0), ctx.constant(1)
        for a in e.args:
            n2, d2 = _frac(a, ctx, index)
            if d2 == den:
                num = num + n2
            else:
                num, den = num * d2 + n2 * den, den * d2
        return num, den
    if e.is_Mul:
        num, den = ctx.constant(1), ctx.constant(1)
        for a in e.args:
            n2, d2 = _frac(a, ctx, index)
            num, den = num * n2, den * d2
        return num, den
    if e.is_Pow and e.exp.is_Integer:
        num, den = _frac(e.base, ctx, index)
        k = int(e.exp)
        if k >= 0:
            return num**k, den**k
        if not num:
            raise Undefined("zero to a negative power")
        return den ** (-k), num ** (-k)
    raise _NotRational(e)


def cancelled(num, den) -> tuple:
    """num / den in lowest terms (integer polynomials)."""
    common = num.gcd(den)
    return num / common, den / common


def fast_factor(expr) -> sp.Expr:
    """A rational expression cancelled and factored with ring arithmetic (sp.cancel on large
    nested expressions is slow)."""
    expr = as_sympy(expr)
    if expr.is_Number:
        return expr
    try:
        num, den, symbols = as_fraction(expr)
    except _NotRational:
        return sp.factor(sp.cancel(expr))
    num, den = cancelled(num, den)
    return _flint_factored(num, symbols) / _flint_factored(den, symbols)


def _flint_factored(poly, symbols=PARAMS) -> sp.Expr:
    """An fmpz_mpoly as content·Π f^k, factored by FLINT (SymPy's multivariate factoring is
    what made the long mismatch messages slow). The form is SymPy's: each f primitive with a
    positive leading coefficient in lex order of `symbols`."""
    content, factors = poly.factor()
    return sp.Integer(int(content)) * sp.Mul(*(poly_expr(f, symbols) ** int(k) for f, k in factors))


def simplify_scalar(expr):
    if isinstance(expr, Sc):
        g = expr.ground()
        if g is not None:
            return sp.Rational(g.numerator, g.denominator)
        num, den = expr.num, expr.pden
        if den is not None:
            num, den = cancelled(num, den)
        out = _flint_factored(num) / sp.Integer(expr.den)
        return out / _flint_factored(den) if den is not None else out
    expr = as_sympy(expr)
    if expr.is_Number:
        return expr
    return sp.factor(sp.cancel(sp.together(expr)))


Key = tuple  # sorted tuple of point keys ("V", 3)


@dataclass
class Form:
    """Polynomial in control points: {sorted tuple of (name, index): scalar coefficient}."""

    terms: dict = field(default_factory=dict)

    @staticmethod
    def point(name: str, index: int) -> Form:
        return Form({((name, index),): Sc.of(1)})

    def scaled(self, s) -> Form:
        if type(s) is Sc and s.c == 1:  # values are never mutated, so sharing is safe
            return self
        return Form({k: v * s for k, v in self.terms.items()})

    def map(self, fn: Callable) -> Form:
        return Form({k: fn(v) for k, v in self.terms.items()})

    def degree(self) -> int:
        return max((len(k) for k in self.terms), default=0)


@dataclass
class Wedge:
    """Antisymmetric bilinear form a × b on point combinations: {(p, q) with p < q: coeff}."""

    terms: dict = field(default_factory=dict)


@dataclass
class Rad:
    """coef × Π |w|^e over canonical (primitive) point combinations w."""

    coef: object
    factors: tuple  # sorted ((canon, exponent), ...)


@dataclass
class Ratio:
    num: object
    den: object


@dataclass
class DotSum:
    """Σ coef·(a·b): dot products of point combinations whose coefficients are polynomials
    in the curve parameter, kept unexpanded. Integrals are exact quadratures and equalities
    are checked at more nodes than the degree in the parameter (both exact for polynomials)."""

    terms: list  # [(Sc coef, Form a, Form b)]


def _merge(a: dict, b: dict) -> dict:
    out = dict(a)
    for k, v in b.items():
        out[k] = out[k] + v if k in out else v
    return out


def is_scalar(v) -> bool:
    return not isinstance(v, (Form, Wedge, Rad, Ratio, DotSum))


def v_add(a, b):
    if type(a) is Sc and type(b) is Sc:
        return a + b
    if is_scalar(a) and is_scalar(b):
        return Sc.of(a) + Sc.of(b)
    if trivially_zero(a):
        return b
    if trivially_zero(b):
        return a
    if isinstance(a, Form) and isinstance(b, Form):
        return Form(_merge(a.terms, b.terms))
    if isinstance(a, Wedge) and isinstance(b, Wedge):
        return Wedge(_merge(a.terms, b.terms))
    if isinstance(a, DotSum) and isinstance(b, DotSum):
        return DotSum(a.terms + b.terms)
    if isinstance(a, Rad) and isinstance(b, Rad) and a.factors == b.factors:
        return Rad(a.coef + b.coef, a.factors)
    if isinstance(a, Ratio) or isinstance(b, Ratio):
        ra = a if isinstance(a, Ratio) else Ratio(a, Sc.of(1))
        rb = b if isinstance(b, Ratio) else Ratio(b, Sc.of(1))
        return Ratio(v_add(v_mul(ra.num, rb.den), v_mul(rb.num, ra.den)), v_mul(ra.den, rb.den))
    raise TypeError(f"cannot add {type(a).__name__} and {type(b).__name__}")


def v_neg(a):
    return v_mul(Sc.of(-1), a)


def v_mul(a, b):
    if type(a) is Sc:
        if type(b) is Sc:
            return a * b
        if a.c == 1 and not is_scalar(b):  # values are never mutated: share b
            return b
    if is_scalar(a) and is_scalar(b):
        return Sc.of(a) * Sc.of(b)
    if is_scalar(b) and not is_scalar(a):
        a, b = b, a
    if is_scalar(a):
        a = Sc.of(a)
        if isinstance(b, Form):
            return b.scaled(a)
        if isinstance(b, Wedge):
            return Wedge({k: v * a for k, v in b.terms.items()})
        if isinstance(b, Rad):
            return Rad(a * b.coef, b.factors)
        if isinstance(b, Ratio):
            return Ratio(v_mul(a, b.num), b.den)
        if isinstance(b, DotSum):
            return DotSum([(a * c, x, y) for c, x, y in b.terms])
    if isinstance(a, Form) and isinstance(b, Form):
        out: dict = {}
        for ka, va in a.terms.items():
            for kb, vb in b.terms.items():
                key = tuple(sorted(ka + kb))
                out[key] = out[key] + va * vb if key in out else va * vb
        return Form(out)
    if isinstance(a, Rad) and isinstance(b, Rad):
        exps = dict(a.factors)
        for c, e in b.factors:
            exps[c] = exps.get(c, 0) + e
        return Rad(a.coef * b.coef, tuple(sorted((c, e) for c, e in exps.items() if e)))
    if isinstance(a, Ratio) or isinstance(b, Ratio):
        ra = a if isinstance(a, Ratio) else Ratio(a, Sc.of(1))
        rb = b if isinstance(b, Ratio) else Ratio(b, Sc.of(1))
        return Ratio(v_mul(ra.num, rb.num), v_mul(ra.den, rb.den))
    raise TypeError(f"cannot multiply {type(a).__name__} and {type(b).__name__}")


def v_pow(a, e):
    e = as_int(e)
    if is_scalar(a):
        return Sc.of(a) ** e
    if isinstance(a, Rad):
        if e < 0 and not _nz(a.coef):
            raise Undefined("division by a zero length")
        return Rad(a.coef**e, tuple((c, x * e) for c, x in a.factors))
    if e < 0:
        return Ratio(Sc.of(1), v_pow(a, -e))
    out = Sc.of(1)
    for _ in range(e):
        out = v_mul(out, a)
    return out


def v_div(a, b):
    if is_scalar(b):
        if _is_zero(b):
            raise Undefined("division by zero")
        return v_mul(Sc.of(1) / Sc.of(b), a) if not is_scalar(a) else Sc.of(a) / Sc.of(b)
    if isinstance(b, Rad):
        return v_mul(a, v_pow(b, -1))
    return Ratio(a, b) if not isinstance(a, Ratio) else Ratio(a.num, v_mul(a.den, b))


def v_apply(v, fn: Callable):
    """Apply a scalar map (diff, subs, integrate) to every coefficient."""
    if is_scalar(v):
        return fn(v)
    if isinstance(v, Form):
        return v.map(fn)
    if isinstance(v, Wedge):
        return Wedge({k: fn(x) for k, x in v.terms.items()})
    raise TypeError(f"cannot apply a parameter operation to {type(v).__name__}")


def v_is_zero(v) -> bool:
    if isinstance(v, DotSum):
        return not compare(v, Sc.of(0))
    if is_scalar(v):
        return _is_zero(v)
    if isinstance(v, (Form, Wedge)):
        return all(_is_zero(x) for x in v.terms.values())
    if isinstance(v, Rad):
        return _is_zero(v.coef)
    return v_is_zero(v.num)


def dot(a, b):
    if isinstance(a, Form) and isinstance(b, Form):
        # commuting point symbols make a·b a faithful symmetric bilinear form; the product is
        # formed lazily (see DotSum)
        return DotSum([(Sc.of(1), a, b)])
    if (is_scalar(a) and _is_zero(a)) or (is_scalar(b) and _is_zero(b)):
        return Sc.of(0)
    raise TypeError("dot needs two point combinations")


def cross(a, b):
    if (is_scalar(a) and _is_zero(a)) or (is_scalar(b) and _is_zero(b)):
        return Wedge({})
    if not (isinstance(a, Form) and isinstance(b, Form)):
        raise TypeError("cross needs two point combinations")
    out: dict = {}
    for (ka,), va in a.terms.items():
        for (kb,), vb in b.terms.items():
            if ka == kb:
                continue
            key, sign = ((ka, kb), 1) if ka < kb else ((kb, ka), -1)
            out[key] = out.get(key, Sc.of(0)) + va * vb * sign
    return Wedge(out)


def norm(v):
    """|v| as a Rad: v = c·w with w primitive (first coefficient 1), |v| = |c|·|w|."""
    items = v.terms.items() if isinstance(v, (Form, Wedge)) else None
    if items is None:
        if is_scalar(v) and _is_zero(v):
            return Sc.of(0)
        raise TypeError("norm needs a point combination")
    items = sorted((k, Sc.of(x).ground()) for k, x in items if _nz(x))
    if not items:
        return Sc.of(0)
    if any(x is None for _, x in items):
        raise TypeError("norm of a combination with non-numeric coefficients")
    lead = items[0][1]
    canon = (type(v).__name__, tuple((k, x / lead) for k, x in items))
    return Rad(Sc.of(abs(lead)), ((canon, 1),))


# --------------------------------------------------------------------------- evaluation


Model = Callable[..., object]


@dataclass
class Realiser:
    """Evaluates parsed expressions with `models` for the undefined functions.

    models[name](args, env) receives the evaluated arguments (SymPy objects; integers for
    indices and degrees) and returns a value. `raw_models` receive the unevaluated arguments.

    Each (sub)expression is compiled once into a closure of the environment: an expression is
    evaluated for hundreds of environments (degrees, indices, sample values), and dispatching
    on SymPy node types and hashing SymPy nodes per node and environment cost more than the
    arithmetic. Equal subexpressions share one closure, and with it one memo.
    """

    models: Mapping[str, Model]
    raw_models: Mapping[str, Model] = field(default_factory=dict)
    # jets[name](order, x, env): the order-th t-derivative of the model name(t) at the
    # constant x, or None; lets Subs(Derivative(p(t), (t, r)), t, x) skip the polynomial in t
    jets: Mapping[str, Callable] = field(default_factory=dict)

    compiled: dict = field(default_factory=dict)
    memos: list = field(default_factory=list)

    def reset(self) -> None:
        """Forget every memoised value (for models that read values the memo keys do not
        contain, such as a shape sample) but keep the compiled closures."""
        for memo in self.memos:
            memo.clear()

    def __call__(self, expr, env: Mapping) -> object:
        """env: {symbol: integer} (degrees, indices), or an exact number for a parameter."""
        return self.walk(expr, {k: _env_value(v) for k, v in env.items()})

    def walk(self, e, env):
        return self._fn(e)(env)

    def _fn(self, e) -> Callable:
        """The closure of e, compiled on first use."""
        fn = self.compiled.get(e)
        if fn is None:
            fn = self.compiled[e] = self._compile(e)
        return fn

    def _compile(self, e) -> Callable:
        kind = _kind(e)
        if kind == "num":
            if not isinstance(e, (int, Fraction)) and not e.is_Rational:

                def inexact(env):
                    raise TypeError(f"inexact number {e}")

                return inexact
            value = _number(e)
            return lambda env: value
        if kind == "sym":
            gen = Sc(GEN[e]) if e in GEN else None

            def symbol(env):
                v = env.get(e)
                if v is not None:
                    return Sc.const(v) if type(v) is int else Sc.of(v)
                if gen is None:
                    raise TypeError(f"free symbol {e} has no value")
                return gen

            return symbol
        inner = self._compile_node(e)
        if kind != "memo":
            return inner
        # models may depend on the degrees and k without printing them (p(t) on n)
        keys = _free(e) + _IMPLICIT
        memo: dict = {}
        self.memos.append(memo)

        def memoised(env):
            key = tuple([env.get(s) for s in keys])
            hit = memo.get(key)
            if hit is None:
                hit = memo[key] = inner(env)
            return hit

        return memoised

    def _compile_node(self, e) -> Callable:  # noqa: C901 - a dispatch over node types
        if isinstance(e, AppliedUndef):
            return self._compile_function(e)
        if e.is_Add:
            terms = [self._fn(a) for a in e.args]

            def add(env):
                out = ZERO
                for f in terms:
                    out = v_add(out, f(env))
                return out

            return add
        if e.is_Mul:
            # functions first: a vanishing basis function makes the product zero before its
            # coefficient (possibly 0/0 by the binomial convention) is looked at
            first, rest = (tuple(self._fn(a) for a in part) for part in _mul_split(e))

            def mul(env):
                out = ONE
                for f in first:
                    val = f(env)
                    if trivially_zero(val):
                        return ZERO
                    out = v_mul(out, val)
                for f in rest:
                    out = v_mul(out, f(env))
                return out

            return mul
        if e.is_Pow:
            base_fn, exp_fn = self._fn(e.base), self._fn(e.exp)

            def power(env):
                base = base_fn(env)
                ex = as_int(exp_fn(env))
                if abs(ex) > MAX_EXPONENT:
                    raise LimitError(f"an exponent {ex} larger than {MAX_EXPONENT}")
                if is_scalar(base) and trivially_zero(base) and ex < 0:
                    raise Undefined("division by zero")
                return v_pow(base, ex)

            return power
        if isinstance(e, sp.binomial):
            top_fn, bottom_fn = (self._fn(x) for x in e.args)

            def binom(env):
                top, bottom = as_int(top_fn(env)), as_int(bottom_fn(env))
                if max(abs(top), abs(bottom)) > MAX_FACTORIAL:
                    raise LimitError(f"binomial({top}, {bottom}) (at most {MAX_FACTORIAL})")
                return Sc.const(paper_binomial(top, bottom))

            return binom
        if isinstance(e, sp.factorial):
            arg_fn = self._fn(e.args[0])

            def fact(env):
                a = as_int(arg_fn(env))
                if a < 0:
                    raise Undefined(f"factorial({a})")
                if a > MAX_FACTORIAL:
                    raise LimitError(f"factorial({a}) (at most {MAX_FACTORIAL})")
                return Sc.const(factorial(a))

            return fact
        if isinstance(e, sp.Sum):
            return self._compile_sum(e.function, list(e.limits))
        if isinstance(e, sp.Derivative):
            expr_fn = self._fn(e.expr)
            counts = [(var, self._fn(count)) for var, count in e.variable_count]

            def derivative(env):
                val = expr_fn(env)
                for var, count_fn in counts:
                    cnt = as_int(count_fn(env))
                    if cnt < 0:
                        raise Undefined(f"derivative of order {cnt}")
                    if cnt > MAX_EXPONENT:
                        raise LimitError(f"a derivative of order {cnt} (at most {MAX_EXPONENT})")
                    val = v_apply(val, lambda s, var=var, cnt=cnt: s.diff(var, cnt))
                return val

            return derivative
        if isinstance(e, sp.Subs):
            return self._compile_subs(e)
        if isinstance(e, sp.Integral):
            return self._compile_integral(e)

        def unknown(env):
            raise TypeError(f"cannot evaluate {e!r}")

        return unknown

    def _compile_function(self, e) -> Callable:
        name = e.func.__name__
        if name in self.raw_models:
            raw, args = self.raw_models[name], e.args
            return lambda env: raw(args, env, self)
        model = self.models.get(name)
        if model is None:

            def missing(env):
                raise KeyError(f"no model for {name}")

            return missing
        arg_fns = [self._fn(a) for a in e.args]
        return lambda env: model([f(env) for f in arg_fns], env)

    def _compile_sum(self, body, limits) -> Callable:
        if not limits:
            return self._fn(body)
        (var, lo, hi), rest = limits[0], limits[1:]
        lo_fn, hi_fn, inner = self._fn(lo), self._fn(hi), self._compile_sum(body, rest)

        def total(env):
            lo, hi = as_int(lo_fn(env)), as_int(hi_fn(env))
            if hi - lo >= MAX_SUM_TERMS:
                raise LimitError(f"a sum over {var} = {lo}..{hi} (at most {MAX_SUM_TERMS} terms)")
            out = ZERO
            for val in range(lo, hi + 1):  # empty when hi < lo
                out = v_add(out, inner({**env, var: val}))
            return out

        return total

    def _compile_subs(self, e) -> Callable:
        jet = self._compile_jet(e) if self.jets else None
        expr_fn = self._fn(e.expr)
        points = [(var, self._fn(point)) for var, point in zip(e.variables, e.point, strict=True)]

        def substitute(env):
            if jet is not None:
                val = jet(env)
                if val is not None:
                    return val
            val = expr_fn(env)
            for var, point_fn in points:
                pt = point_fn(env)
                val = v_apply(val, lambda s, var=var, pt=pt: s.subs(var, pt))
            return val

        return substitute

    def _compile_jet(self, e) -> Callable | None:
        """Subs(f(t), t, x) or Subs(Derivative(f(t), (t, r)), t, x) through jets[f]: a closure
        giving the value or None (when t has a value), or None when the form does not fit."""
        if len(e.variables) != 1:
            return None
        var, inner, order_fn = e.variables[0], e.expr, None
        if isinstance(inner, sp.Derivative):
            if len(inner.variable_count) != 1 or inner.variable_count[0][0] != var:
                return None
            order_fn = self._fn(inner.variable_count[0][1])
            inner = inner.expr
        if not isinstance(inner, AppliedUndef) or inner.args != (var,):
            return None
        jet = self.jets.get(inner.func.__name__)
        if jet is None:
            return None
        point_fn = self._fn(e.point[0])

        def at_point(env):
            if var in env:
                return None
            order = 0
            if order_fn is not None:
                order = as_int(order_fn(env))
                if order < 0:
                    raise Undefined(f"derivative of order {order}")
            x = point_fn(env)
            return jet(order, x, env) if isinstance(x, Sc) and x.c is not None else None

        return at_point

    def _compile_integral(self, e) -> Callable:
        fn = self._fn(e.function)
        limits = [(lim[0], self._fn(lim[1]), self._fn(lim[2])) for lim in e.limits]

        def integral(env):
            val = fn(env)
            if isinstance(val, DotSum) and len(limits) == 1:
                var, lo_fn, hi_fn = limits[0]
                return dotsum_integral(val, var, lo_fn(env), hi_fn(env))
            for var, lo_fn, hi_fn in limits:
                lo, hi = lo_fn(env), hi_fn(env)
                val = v_apply(val, lambda s, var=var, lo=lo, hi=hi: s.integrate(var, lo, hi))
            return val

        return integral


_IMPLICIT = (SYMBOLS["n"], SYMBOLS["m"], SYMBOLS["k"])


def _number(e) -> Sc:
    if isinstance(e, (int, Fraction)):
        return Sc.of(e)
    return Sc.const(_q(int(e.p), int(e.q)))


_KINDS: dict = {}


def _kind(e) -> str:
    t = type(e)
    k = _KINDS.get(t)
    if k is None:
        if issubclass(t, (int, Fraction)) or (issubclass(t, sp.Basic) and e.is_Number):
            k = "num"
        elif issubclass(t, sp.Symbol):
            k = "sym"
        elif issubclass(t, (AppliedUndef, sp.Derivative, sp.Subs, sp.Integral, sp.Sum)):
            k = "memo"
        else:
            k = "other"
        _KINDS[t] = k
    return k


@lru_cache(maxsize=8192)
def _mul_split(e) -> tuple:
    first = tuple(a for a in e.args if _has_function(a))
    return first, tuple(a for a in e.args if not _has_function(a))


def _env_value(v):
    if isinstance(v, (int, Fraction)):
        return v
    v = sp.Rational(v)
    return int(v) if v.q == 1 else Fraction(int(v.p), int(v.q))


@lru_cache(maxsize=8192)
def _free(e) -> tuple:
    return tuple(sorted(e.free_symbols, key=str))


@lru_cache(maxsize=8192)
def _has_function(e) -> bool:
    return any(isinstance(a, AppliedUndef) for a in sp.preorder_traversal(e))


def delta_model(args, env, realiser: Realiser):
    """Δ^r X = Σ_q (-1)^(r-q) C(r,q) X[shift q]; the shift adds q to the first argument of every
    control-point-like function in X (README: `Delta`)."""
    r = as_int(realiser.walk(args[0], env))
    if r < 0:
        raise Undefined(f"difference of order {r}")
    out = Sc.of(0)
    for q in range(r + 1):
        coeff = Sc.of((-1) ** (r - q) * comb(r, q))
        out = v_add(out, v_mul(coeff, realiser.walk(shift_points(args[1], q), env)))
    return out


@lru_cache(maxsize=4096)
def shift_points(expr, q):
    def is_point(e):
        name = fn_name(e)
        return name in POINT_LIKE and not (name == "b" and len(e.args) != 1)

    return expr.replace(is_point, lambda e: e.func(e.args[0] + q, *e.args[1:]))


def symbolic_delta(expr):
    """Expand every Delta(r, X) with a symbolic order into an explicit Sum (for the general-n
    checks)."""

    def is_delta(e):
        return fn_name(e) == "Delta"

    def expand(e):
        r, body = e.args
        q = sp.Dummy("q", integer=True, nonnegative=True)
        return sp.Sum(
            (-1) ** (r - q) * sp.binomial(r, q) * shift_points(body, q), (q, sp.Integer(0), r)
        )

    return expr.replace(is_delta, expand)


# --------------------------------------------------------------------------- comparison


def _proportional_pairs(a: Ratio, b: Ratio) -> bool:
    """a.num/a.den == b.num/b.den because a = μ·b termwise (numerator and denominator)."""
    if not all(isinstance(v, Form) for v in (a.num, a.den, b.num, b.den)):
        return False
    keys = [k for k, v in b.den.terms.items() if not v.is_zero()]
    if not keys:
        return False
    mu = a.den.terms.get(keys[0], Sc.of(0)) / b.den.terms[keys[0]]
    for x, y in ((a.num, b.num), (a.den, b.den)):
        for k in set(x.terms) | set(y.terms):
            if not (x.terms.get(k, Sc.of(0)) - mu * y.terms.get(k, Sc.of(0))).is_zero():
                return False
    return True


def show(x) -> str:
    if is_scalar(x):
        return str(simplify_scalar(x))
    if isinstance(x, Form):
        return " + ".join(f"({show(v)})*{key_str(k)}" for k, v in sorted(x.terms.items())) or "0"
    return repr(x)


def key_str(key) -> str:
    return "*".join(f"{name}({idx})" for name, idx in key)


def equal(a, b) -> bool:
    """a == b exactly (no diff text)."""
    if is_scalar(a) and is_scalar(b):
        return (Sc.of(a) - Sc.of(b)).is_zero()
    if isinstance(a, Form) and isinstance(b, Form):
        return all(
            (a.terms.get(k, ZERO) - b.terms.get(k, ZERO)).is_zero()
            for k in set(a.terms) | set(b.terms)
        )
    return not compare(a, b)


def compare(printed, derived) -> list[str]:
    """Differences between two values, smallest first: [] when they are equal."""
    if isinstance(printed, DotSum) or isinstance(derived, DotSum):
        return _compare_dotsums(printed, derived)
    if is_scalar(printed) and is_scalar(derived):
        if _is_zero(printed - derived):
            return []
        return [f"printed {show(printed)}, derived {show(derived)}"]
    if isinstance(printed, Ratio) or isinstance(derived, Ratio):
        rp = printed if isinstance(printed, Ratio) else Ratio(printed, sp.Integer(1))
        rd = derived if isinstance(derived, Ratio) else Ratio(derived, sp.Integer(1))
        if _proportional_pairs(rp, rd) or v_is_zero(
            v_add(v_mul(rp.num, rd.den), v_neg(v_mul(rd.num, rp.den)))
        ):
            return []
        return ["the quotients differ (cross products unequal)"]
    if isinstance(printed, Rad) or isinstance(derived, Rad):
        if v_is_zero(printed) and v_is_zero(derived):
            return []
        if isinstance(printed, Rad) and isinstance(derived, Rad):
            if printed.factors != derived.factors:
                return ["printed and derived involve different lengths |...|"]
            if _is_zero(printed.coef - derived.coef):
                return []
            return [
                f"factor in front of the lengths: printed {show(printed.coef)}, "
                f"derived {show(derived.coef)}"
            ]
        return ["one side is zero, the other is not"]
    fp = printed if not is_scalar(printed) else Form({(): printed} if _nz(printed) else {})
    fd = derived if not is_scalar(derived) else Form({(): derived} if _nz(derived) else {})
    if type(fp) is not type(fd):
        if v_is_zero(fp) and v_is_zero(fd):
            return []
        return [f"printed {type(fp).__name__}, derived {type(fd).__name__}"]
    out = []
    for key in sorted(set(fp.terms) | set(fd.terms)):
        a, b = fp.terms.get(key, ZERO), fd.terms.get(key, ZERO)
        if len(out) >= 3:
            break
        if not _is_zero(a - b):
            name = key_str(key) if key and isinstance(key[0], tuple) else str(key)
            out.append(f"coefficient of {name or '1'}: printed {show(a)}, derived {show(b)}")
    return out


# --------------------------------------------------------------------------- lazy dot products

T_SYM = SYMBOLS["t"]


def _t_degree(v, var) -> int:
    g = _GPOS[var]
    if isinstance(v, Sc):
        if v.c is not None:
            return 0
        if v.pden is not None and _degree(v.pden, g) > 0:
            raise TypeError("a rational function of the integration variable")
        return max(_degree(v.num, g), 0)
    if isinstance(v, Form):
        return max((_t_degree(c, var) for c in v.terms.values()), default=0)
    if isinstance(v, DotSum):
        return max(
            (_t_degree(c, var) + _t_degree(a, var) + _t_degree(b, var) for c, a, b in v.terms),
            default=0,
        )
    return 0


def _at(v, var, x):
    """v with the parameter var set to the number x (a DotSum becomes a quadratic Form)."""
    if isinstance(v, DotSum):
        out = Sc.of(0)
        for c, a, b in v.terms:
            out = v_add(out, v_mul(c.subs(var, x), v_mul(_at(a, var, x), _at(b, var, x))))
        return out
    if isinstance(v, Form):
        return Form({k: c.subs(var, x) for k, c in v.terms.items()})
    return Sc.of(v).subs(var, x) if is_scalar(v) else v


@cache
def newton_cotes(npts: int) -> tuple[tuple[Fraction, Fraction], ...]:
    """(node, weight) on [0, 1], npts equally spaced nodes: Σ w f(x) = ∫_0^1 f exactly for every
    polynomial f of degree < npts (weights solve the moment equations exactly)."""
    if npts == 1:
        return ((Fraction(1, 2), Fraction(1)),)
    nodes = [Fraction(r, npts - 1) for r in range(npts)]
    # solve Σ_r w_r x_r^p = 1/(p+1), p = 0..npts-1 (Vandermonde, exact Gaussian elimination)
    rows = [[x**p for x in nodes] + [Fraction(1, p + 1)] for p in range(npts)]
    for col in range(npts):
        piv = next(r for r in range(col, npts) if rows[r][col] != 0)
        rows[col], rows[piv] = rows[piv], rows[col]
        inv = 1 / rows[col][col]
        rows[col] = [v * inv for v in rows[col]]
        for r in range(npts):
            if r != col and rows[r][col] != 0:
                f = rows[r][col]
                rows[r] = [a - f * b for a, b in zip(rows[r], rows[col], strict=True)]
    return tuple((x, rows[r][npts]) for r, x in enumerate(nodes))


class _Slow(Exception):
    """The fast kernel does not apply (a parameter other than t and lam)."""


_T_POS = PARAMS.index(SYMBOLS["t"])
_L_POS = PARAMS.index(SYMBOLS["lam"])


def _tl_terms(c: Sc) -> tuple:
    """c as (((a, b, int), ...), den) meaning Σ coef·t^a·lam^b / den; _Slow otherwise."""
    if c.c is not None:
        return (((0, 0, int(c.c.numerator)),), int(c.c.denominator))
    if c.pden is not None:
        raise _Slow
    out = []
    for monom, coeff in c.num.terms():
        if any(e for pos, e in enumerate(monom) if pos not in (_T_POS, _L_POS)):
            raise _Slow
        out.append((int(monom[_T_POS]), int(monom[_L_POS]), int(coeff)))
    return tuple(out), c.den


class _Point:
    """t = xn/xd, lam = y (an integer), with the powers used by the kernel as integers:
    a polynomial of degree <= A in t is evaluated as an integer over xd^A."""

    def __init__(self, x: Fraction, y: int, big_a: int, big_b: int):
        xn, xd = x.numerator, x.denominator
        self.tp = [xn**a * xd ** (big_a - a) for a in range(big_a + 1)]
        self.lp = [y**b for b in range(big_b + 1)]
        self.scale = xd**big_a

    def value(self, poly) -> tuple[int, int]:
        terms, den = poly
        tp, lp = self.tp, self.lp
        return sum(c * tp[a] * lp[b] for a, b, c in terms), den * self.scale


def _lam_degree(poly) -> int:
    return max((b for _, b, _ in poly[0]), default=0)


def _t_deg(poly) -> int:
    return max((a for a, _, _ in poly[0]), default=0)


def _int_vector(values: list) -> tuple:
    """[(num, den)] -> (ints, common denominator)."""
    den = 1
    for _, d in values:
        den = den * d // gcd(den, d)
    return [v * (den // d) for v, d in values], den


_ZERO = ((), 1)


class _Kernel:
    """A DotSum (or a quadratic Form) evaluated at numbers for t and lam: integer matrices."""

    def __init__(self, value, keys: list):
        self.keys = keys
        self.index = {k: pos for pos, k in enumerate(keys)}
        self.parts = []  # ("dot", coef, a per key, b per key) or ("quad", {key: poly})
        if isinstance(value, DotSum):
            for c, a, b in value.terms:
                self.parts.append(("dot", _tl_terms(c), self._vec(a), self._vec(b)))
        elif isinstance(value, Form):
            if any(len(k) != 2 for k in value.terms):
                raise _Slow
            self.parts.append(("quad", {k: _tl_terms(c) for k, c in value.terms.items()}))
        elif not (is_scalar(value) and trivially_zero(value)):
            raise _Slow

    def _vec(self, form) -> list:
        if not isinstance(form, Form) or any(len(k) != 1 for k in form.terms):
            raise _Slow
        out = [_ZERO] * len(self.keys)
        for (key,), c in form.terms.items():
            out[self.index[key]] = _tl_terms(c)
        return out

    def degrees(self) -> tuple[int, int]:
        dt = dl = 0
        for part in self.parts:
            if part[0] == "dot":
                _, c, a, b = part
                dt = max(dt, _t_deg(c) + max(map(_t_deg, a)) + max(map(_t_deg, b)))
                dl = max(dl, _lam_degree(c) + max(map(_lam_degree, a)) + max(map(_lam_degree, b)))
            else:
                for poly in part[1].values():
                    dt, dl = max(dt, _t_deg(poly)), max(dl, _lam_degree(poly))
        return dt, dl

    def matrix(self, pt: _Point) -> tuple[dict, int]:
        """(integer upper-triangular coefficient matrix {(i, j): entry, i <= j}, denominator)
        at the point."""
        acc: dict = {}
        den = 1

        def add(entries: dict, entries_den: int) -> None:
            nonlocal acc, den
            new_den = den * entries_den // gcd(den, entries_den)
            scale, escale = new_den // den, new_den // entries_den
            if scale != 1:
                acc = {ij: v * scale for ij, v in acc.items()}
            for ij, v in entries.items():
                acc[ij] = acc.get(ij, 0) + v * escale
            den = new_den

        for part in self.parts:
            entries: dict = {}
            if part[0] == "dot":
                _, c, a, b = part
                cn, cd = pt.value(c)
                if cn == 0:
                    continue
                va, da = _int_vector([pt.value(p) for p in a])
                vb, db = _int_vector([pt.value(p) for p in b])
                for i, x in enumerate(va):
                    for j, y in enumerate(vb):
                        if x and y:  # P_i·P_j = P_j·P_i: both land on the upper triangle
                            ij = (i, j) if i <= j else (j, i)
                            entries[ij] = entries.get(ij, 0) + cn * x * y
                add(entries, da * db * cd)
            else:
                ints, d = _int_vector([pt.value(p) for p in part[1].values()])
                for (k1, k2), v in zip(part[1], ints, strict=True):
                    ij = tuple(sorted((self.index[k1], self.index[k2])))
                    entries[ij] = entries.get(ij, 0) + v
                add(entries, d)
        return acc, den


def _keys_of(*values) -> list:
    keys = set()
    for v in values:
        if isinstance(v, DotSum):
            for _, a, b in v.terms:
                keys |= {k[0] for k in a.terms} | {k[0] for k in b.terms}
        elif isinstance(v, Form):
            keys |= {p for k in v.terms for p in k}
    return sorted(keys)


def quadratic_terms(v) -> dict:
    """A DotSum, a quadratic Form or zero as {(p, q), p <= q: coefficient of p·q}, the dot
    products expanded with P_i·P_j = P_j·P_i; TypeError for anything else."""
    if is_scalar(v) and trivially_zero(v):
        return {}
    if isinstance(v, Form):
        if any(len(k) != 2 for k in v.terms):
            raise TypeError("not a quadratic form in the points")
        return dict(v.terms)
    if not isinstance(v, DotSum):
        raise TypeError(f"not a quadratic form: {type(v).__name__}")
    out: dict = {}
    for c, a, b in v.terms:
        if not (isinstance(a, Form) and isinstance(b, Form)):
            raise TypeError("dot needs two point combinations")
        for ka, ca in a.terms.items():
            cca = c * ca
            for kb, cb in b.terms.items():
                if len(ka) != 1 or len(kb) != 1:
                    raise TypeError("dot needs two point combinations")
                key = ka + kb if ka <= kb else kb + ka
                val = cca * cb
                out[key] = out[key] + val if key in out else val
    return out


# A quadratic form in the points as one FLINT polynomial: each point key gets a generator next
# to the parameters (P_i·P_j = P_j·P_i, so commuting generators are faithful). Products,
# integrals and equality are then one call each instead of one per pair of points.


class _NotPolynomial(Exception):
    """A coefficient is a rational function of the parameters, or a term is not quadratic."""


@lru_cache(maxsize=64)
def _point_ctx(count: int):
    """(context, parameter generators, point generators) for `count` point keys."""
    names = (*(str(s) for s in PARAMS), *(f"_x{q}" for q in range(count)))
    ctx = flint.fmpz_mpoly_ctx.get(names, "lex")
    gens = ctx.gens()
    return ctx, gens[:_NVARS], gens[_NVARS:]


def _embedded(c: Sc, ctx, params) -> tuple:
    """c as (integer polynomial in ctx, positive integer denominator)."""
    if c.c is not None:
        return ctx.constant(int(c.c.numerator)), int(c.c.denominator)
    if c.pden is not None:
        raise _NotPolynomial
    return c.num.compose(*params, ctx=ctx), c.den


def _over_common_denominator(parts: list, ctx) -> tuple:
    den = 1
    for _, d in parts:
        den = _lcm(den, d)
    out = ctx.constant(0)
    for p, d in parts:
        out += p * (den // d)
    return out, den


def _quadratic_poly(v, keys: list) -> tuple:
    """A DotSum, a quadratic Form or zero as (integer polynomial, denominator) in
    _point_ctx(len(keys)); _NotPolynomial when it is not a polynomial in the parameters."""
    ctx, params, xs = _point_ctx(len(keys))
    index = {key: q for q, key in enumerate(keys)}
    seen: dict = {}  # id -> (form, polynomial): F·F, F·G, G·G embed each form once

    def linear(form):
        hit = seen.get(id(form))
        if hit is not None and hit[0] is form:
            return hit[1]
        seen[id(form)] = (form, out := _linear(form))
        return out

    def _linear(form):
        parts = []
        for key, c in form.terms.items():
            if len(key) != 1:
                raise _NotPolynomial
            p, d = _embedded(c, ctx, params)
            parts.append((p * xs[index[key[0]]], d))
        return _over_common_denominator(parts, ctx)

    parts = []
    if isinstance(v, DotSum):
        for c, a, b in v.terms:
            if not (isinstance(a, Form) and isinstance(b, Form)):
                raise _NotPolynomial
            (pc, dc), (pa, da), (pb, db) = _embedded(c, ctx, params), linear(a), linear(b)
            parts.append((pc * pa * pb, dc * da * db))
    elif isinstance(v, Form):
        for key, c in v.terms.items():
            if len(key) != 2:
                raise _NotPolynomial
            p, d = _embedded(c, ctx, params)
            parts.append((p * xs[index[key[0]]] * xs[index[key[1]]], d))
    elif not (is_scalar(v) and trivially_zero(v)):
        raise _NotPolynomial
    return _over_common_denominator(parts, ctx)


def _quadratic_form(poly, den: int, keys: list) -> Form:
    """The Form {(p, q), p <= q: coefficient of p·q} of a polynomial of _quadratic_poly."""
    by_key: dict = {}
    for monom, coeff in poly.terms():
        pos = [q for q, e in enumerate(monom[_NVARS:]) for _ in range(int(e))]
        if len(pos) != 2:
            raise AssertionError("not a quadratic form in the points")
        key = (keys[pos[0]], keys[pos[1]])  # keys are sorted, so p <= q
        by_key.setdefault(key, {})[tuple(int(e) for e in monom[:_NVARS])] = int(coeff)
    return Form({key: Sc(_poly(by_key[key]), den) for key in sorted(by_key)})


def dotsum_integral(v: DotSum, var, lo, hi) -> Form:
    """∫_lo^hi of a DotSum, exact: as one polynomial (see _quadratic_poly) between integer
    bounds, else coefficient by coefficient."""
    lo_f, hi_f = Sc.of(lo).ground(), Sc.of(hi).ground()
    if lo_f is None or hi_f is None:
        raise TypeError("integration bounds must be numbers")
    if lo_f.denominator == 1 and hi_f.denominator == 1:
        keys = _keys_of(v)
        try:
            poly, den = _quadratic_poly(v, keys)
        except _NotPolynomial:
            pass
        else:
            value, scale = _integral_between(poly, _GPOS[var], int(lo_f), int(hi_f))
            return _quadratic_form(value, den * scale, keys)
    out = {}
    for key, c in sorted(quadratic_terms(v).items()):
        val = c.integrate(var, lo_f, hi_f)
        if not val.is_zero():
            out[key] = val
    return Form(out)


def _compare_dotsums(a, b) -> list[str]:
    """Equal as quadratic forms in the points with coefficients exact in the parameters; when
    they differ, the first point of a grid in (t, lam) where they do (a grid with more nodes
    than the degrees), for a diff a reader can check by hand."""
    if not all(isinstance(v, (DotSum, Form)) or is_scalar(v) for v in (a, b)):
        return ["printed and derived are of different kinds"]
    keys = _keys_of(a, b)
    try:
        (pa, da), (pb, db) = _quadratic_poly(a, keys), _quadratic_poly(b, keys)
    except _NotPolynomial:
        try:
            qa, qb = quadratic_terms(a), quadratic_terms(b)
        except TypeError:
            pass
        else:
            if all((qa.get(k, ZERO) - qb.get(k, ZERO)).is_zero() for k in qa.keys() | qb.keys()):
                return []
    else:
        if pa * db == pb * da:
            return []
    try:
        ka, kb = _Kernel(a, keys), _Kernel(b, keys)
        (ta, la), (tb, lb) = ka.degrees(), kb.degrees()
        dt, dl = max(ta, tb), max(la, lb)
        for x in range(dt + 1):
            for y in range(dl + 1):
                pt = _Point(Fraction(x), y, dt, dl)
                ma, da = ka.matrix(pt)
                mb, db = kb.matrix(pt)
                differing = sorted(
                    ij for ij in ma.keys() | mb.keys() if ma.get(ij, 0) * db != mb.get(ij, 0) * da
                )
                if differing:
                    diff = [
                        f"coefficient of {keys[i][0]}({keys[i][1]})*{keys[j][0]}({keys[j][1]}): "
                        f"printed {Fraction(ma.get((i, j), 0), da)}, "
                        f"derived {Fraction(mb.get((i, j), 0), db)}"
                        for i, j in differing
                    ]
                    return [f"at t = {x}, lam = {y}: " + "; ".join(diff[:2])]
        return []
    except _Slow:
        pass
    deg = max(_t_degree(a, T_SYM), _t_degree(b, T_SYM))
    for x, _ in newton_cotes(deg + 1):
        diffs = compare(_at(a, T_SYM, Sc.of(x)), _at(b, T_SYM, Sc.of(x)))
        if diffs:
            return [f"at t = {x}: " + d for d in diffs]
    return []
