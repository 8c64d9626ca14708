"""Exact scalars of the realiser: ``Sc``, a rational function in the parameters (t, u, lam,
...) held as FLINT multivariate polynomials over a common denominator, and the helpers that
cancel, factor and simplify them.
"""

from __future__ import annotations

from fractions import Fraction
from functools import lru_cache
from math import gcd

import flint
import sympy as sp

from ..grammar import SYMBOLS
from .expr_parse import (
    DEGREE_SYMBOLS,
    INDEX_SYMBOLS,
    as_sympy,
)

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
