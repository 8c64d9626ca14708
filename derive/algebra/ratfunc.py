"""Exact rational functions in t and the shape parameters, on FLINT's multivariate
polynomials (fmpq_mpoly), for the family engine's evaluation of a definition per degree.

SymPy's sparse field Q(t, λ) does the same arithmetic, but cancels every intermediate result
with a gcd in Python; a basis definition of degree 12 is a few thousand such operations per
degree (issue #29: it was a fifth of `derive --check`). Here a value is a numerator and a
denominator in FLINT's C arithmetic. Denominators only arise from negative powers (t^(i-1) at
i = 0, say), so a denominator that is a number is folded into the numerator at once and a
gcd is only taken when one is not.
"""

from __future__ import annotations

from fractions import Fraction
from functools import cache
from math import gcd, lcm
from typing import TYPE_CHECKING

import flint
import sympy as sp

if TYPE_CHECKING:
    from sympy.polys.fields import FracElement, FracField


@cache
def context(count: int) -> flint.fmpq_mpoly_ctx:
    """Polynomials in `count` variables (t first, then the parameters), lexicographic."""
    return flint.fmpq_mpoly_ctx.get(tuple(f"x{k}" for k in range(count)), "lex")


class RationalFunction:
    """num / den over Q, both fmpq_mpoly of one context; den is 1 unless it has a variable,
    and num / den is in lowest terms (a common factor is cancelled when it forms)."""

    __slots__ = ("num", "den")

    def __init__(self, num: flint.fmpq_mpoly, den: flint.fmpq_mpoly | None = None):
        ctx = num.context()
        if den is None or den.is_one():
            self.num, self.den = num, ctx.from_dict({(0,) * ctx.nvars(): 1})
            return
        if den.is_zero():
            raise ZeroDivisionError("a rational function with denominator 0")
        if den.is_constant():
            self.num, self.den = (
                num / den.leading_coefficient(),
                ctx.from_dict({(0,) * ctx.nvars(): 1}),
            )
            return
        g = num.gcd(den)
        if not g.is_one():
            num, den = num / g, den / g
        lead = den.leading_coefficient()  # a unique representative: den with leading term 1
        self.num, self.den = num / lead, den / lead
        if self.den.is_constant():  # the gcd took every variable out
            self.den = ctx.from_dict({(0,) * ctx.nvars(): 1})

    @classmethod
    def constant(cls, count: int, value: int | Fraction) -> RationalFunction:
        ctx = context(count)
        value = Fraction(value)
        return cls(ctx.from_dict({(0,) * count: flint.fmpq(value.numerator, value.denominator)}))

    @classmethod
    def variable(cls, count: int, index: int) -> RationalFunction:
        return cls(context(count).gens()[index])

    @property
    def is_polynomial(self) -> bool:
        return self.den.is_constant()

    def is_zero(self) -> bool:
        return bool(self.num.is_zero())

    def constant_value(self) -> Fraction | None:
        """The value when this is a number, else None."""
        if not (self.num.is_constant() and self.den.is_constant()):
            return None
        if self.num.is_zero():
            return Fraction(0)
        q = self.num.leading_coefficient()
        return Fraction(int(q.p), int(q.q))

    def _coerce(self, other: object) -> RationalFunction:
        if isinstance(other, RationalFunction):
            return other
        if isinstance(other, int | Fraction):
            return RationalFunction.constant(self.num.context().nvars(), other)
        raise TypeError(f"cannot combine a rational function with {type(other).__name__}")

    def __eq__(self, other: object) -> bool:
        if isinstance(other, int | Fraction):
            return self.constant_value() == other
        if not isinstance(other, RationalFunction):
            return NotImplemented
        return bool(self.num == other.num and self.den == other.den)

    def __ne__(self, other: object) -> bool:
        equal = self.__eq__(other)
        return equal if equal is NotImplemented else not equal

    __hash__ = None  # type: ignore[assignment]  # mutable-looking, compared by value

    def __neg__(self) -> RationalFunction:
        out = object.__new__(RationalFunction)
        out.num, out.den = -self.num, self.den
        return out

    def __sub__(self, other: RationalFunction | int | Fraction) -> RationalFunction:
        return self + (-self._coerce(other))

    def __rsub__(self, other: int | Fraction) -> RationalFunction:
        return self._coerce(other) + (-self)

    def __radd__(self, other: int | Fraction) -> RationalFunction:
        return self._coerce(other) + self

    def __rmul__(self, other: int | Fraction) -> RationalFunction:
        return self._coerce(other) * self

    def __truediv__(self, other: RationalFunction | int | Fraction) -> RationalFunction:
        other = self._coerce(other)
        if other.num.is_zero():
            raise ZeroDivisionError("division by the zero rational function")
        return RationalFunction(self.num * other.den, self.den * other.num)

    def __rtruediv__(self, other: int | Fraction) -> RationalFunction:
        return self._coerce(other) / self

    def __add__(self, other: RationalFunction | int | Fraction) -> RationalFunction:
        other = self._coerce(other)
        if self.den.is_one() and other.den.is_one():
            return RationalFunction(self.num + other.num)
        return RationalFunction(self.num * other.den + other.num * self.den, self.den * other.den)

    def __mul__(self, other: RationalFunction | int | Fraction) -> RationalFunction:
        other = self._coerce(other)
        if self.den.is_one() and other.den.is_one():
            return RationalFunction(self.num * other.num)
        return RationalFunction(self.num * other.num, self.den * other.den)

    def __pow__(self, exponent: int) -> RationalFunction:
        if exponent >= 0:
            if self.den.is_one():
                return RationalFunction(self.num**exponent)
            return RationalFunction(self.num**exponent, self.den**exponent)
        if self.num.is_zero():
            raise ZeroDivisionError("0 to a negative power")
        return RationalFunction(self.den ** (-exponent), self.num ** (-exponent))

    def terms(self) -> dict[tuple[int, ...], Fraction]:
        """{exponent tuple: coefficient} of a polynomial (the denominator is 1)."""
        if not self.is_polynomial:
            raise ArithmeticError("not a polynomial")
        return {
            tuple(int(e) for e in m): Fraction(int(c.p), int(c.q))
            for m, c in zip(self.num.monoms(), self.num.coeffs(), strict=True)
        }

    def as_pair(self) -> tuple[dict[tuple[int, ...], Fraction], dict[tuple[int, ...], Fraction]]:
        """(numerator, denominator) as {exponent tuple: coefficient}, for printing."""

        def terms(p: flint.fmpq_mpoly) -> dict[tuple[int, ...], Fraction]:
            return {
                tuple(int(e) for e in m): Fraction(int(c.p), int(c.q))
                for m, c in zip(p.monoms(), p.coeffs(), strict=True)
            }

        return terms(self.num), terms(self.den)


def from_expr(expr: sp.Expr, symbols: tuple[sp.Symbol, ...]) -> RationalFunction:
    """A SymPy rational expression in `symbols` (sums, products, integer powers, rational
    numbers) as a RationalFunction in those variables, in that order."""
    count = len(symbols)
    index = {s: k for k, s in enumerate(symbols)}

    def walk(e: sp.Expr) -> RationalFunction:
        if e.is_Rational:
            return RationalFunction.constant(count, Fraction(int(e.p), int(e.q)))
        if e.is_Symbol:
            if e not in index:
                raise ValueError(f"{e} is not one of the variables {symbols}")
            return RationalFunction.variable(count, index[e])
        if e.is_Add:
            out = walk(e.args[0])
            for a in e.args[1:]:
                out = out + walk(a)
            return out
        if e.is_Mul:
            out = walk(e.args[0])
            for a in e.args[1:]:
                out = out * walk(a)
            return out
        if e.is_Pow and e.exp.is_Integer:
            return walk(e.base) ** int(e.exp)
        raise ValueError(f"{e} is not a rational function of {symbols}")

    return walk(sp.sympify(expr))


def to_sympy_field(value: RationalFunction, field: FracField) -> FracElement:
    """`value` as an element of SymPy's field over QQ with the same variables in the same
    order, in the form SymPy's own arithmetic leaves it (numerator and denominator with
    integer coefficients and no common factor, not even a number, the denominator's leading
    term positive in lex order), so that whatever prints it prints the same text."""
    num, den = value.as_pair()
    if not num:
        return field.zero
    # value.den is monic, so scaling both by the least common denominator leaves integer
    # polynomials with no common factor (some coefficient keeps each prime of the scale) and
    # a positive leading term: SymPy's form already
    scale = lcm(*(c.denominator for c in (*num.values(), *den.values())))
    inum = {m: int(c * scale) for m, c in num.items()}
    iden = {m: int(c * scale) for m, c in den.items()}
    if iden[max(iden)] <= 0 or gcd(*inum.values(), *iden.values()) != 1:
        raise AssertionError(f"not in lowest terms with a monic denominator: {value.as_pair()}")
    ring = field.ring
    qq = ring.domain
    numer = ring.from_dict({m: qq(c) for m, c in inum.items()})
    denom = ring.from_dict({m: qq(c) for m, c in iden.items()})
    return field.zero.raw_new(numer, denom)


@cache
def _integer_context(count: int) -> flint.fmpz_mpoly_ctx:
    return flint.fmpz_mpoly_ctx.get(tuple(f"x{k}" for k in range(count)), "lex")


def factored(terms: dict[tuple[int, ...], Fraction], symbols: tuple[sp.Symbol, ...]) -> sp.Expr:
    """The polynomial Σ c·x^m over Q in `symbols` as content · Π f^k, factored by FLINT, in
    the form SymPy's factor_list gives it (each f primitive with integer coefficients and a
    positive leading term in lex order of `symbols`, the rational content in front): the
    same expression, so the same printed text, at a fraction of the time."""
    terms = {m: c for m, c in terms.items() if c}
    if not terms:
        return sp.Integer(0)
    scale = lcm(*(c.denominator for c in terms.values()))
    ctx = _integer_context(len(symbols))
    poly = ctx.from_dict({m: int(c * scale) for m, c in terms.items()})
    content, factors = poly.factor()
    const = sp.Rational(int(content), scale)
    parts = []
    for f, k in factors:
        fterms = dict(zip((tuple(int(e) for e in m) for m in f.monoms()), f.coeffs(), strict=True))
        if int(fterms[max(fterms)]) < 0:  # FLINT's unit may differ from SymPy's: make it +
            fterms = {m: -c for m, c in fterms.items()}
            const = const * (-1) ** int(k)
        expr = sp.Add(
            *(
                sp.Integer(int(c)) * sp.Mul(*(g**e for g, e in zip(symbols, m, strict=True)))
                for m, c in fterms.items()
            )
        )
        parts.append(expr ** int(k))
    return sp.Mul(const, *parts)
