r"""Exact numbers in ℚ(c) for one transcendental constant c (π, or e^W with W rational).

The energies of trigonometric families have entries in ℚ[π] (∫ sin² over [0, π/2] is π/4),
those of hyperbolic families in ℚ[e^W, e^−W]; a family affine in its parameters then has its
energy-optimal parameters in the field ℚ(c): quotients of polynomials in c with rational
coefficients. `ConstantFraction` is such a quotient, kept exact; comparisons are decided
exactly, because c is transcendental (Lindemann): a nonzero polynomial in c is not zero, so
evaluating it on rational intervals around c that shrink (`constant_bounds`, integer
arithmetic: Machin's formula for π, the exponential series for e^W) settles its sign.
"""

from __future__ import annotations

import re
from fractions import Fraction
from functools import lru_cache, total_ordering
from typing import Any, Union

Poly = tuple[Fraction, ...]  # coefficients in ascending powers of c
_CONSTANT = re.compile(r"^(?:pi|exp\((-?[0-9]{1,30}(?:/[0-9]{1,30})?)\))$")
MAX_BITS = 1 << 14  # past this precision a sign is given up (a ValueError, never a guess)


def check_constant(name: object) -> str:
    """The constant's name ("pi" or "exp(W)"), or ValueError."""
    if not isinstance(name, str) or not _CONSTANT.match(name):
        raise ValueError(f"{name!r} is not a constant (pi or exp(W) with W rational)")
    if name == "pi":
        return name
    try:
        w = Fraction(name[4:-1])
    except ZeroDivisionError:
        raise ValueError(f"{name!r}: a zero denominator") from None
    if w == 0:
        raise ValueError(f"{name!r}: exp(0) = 1 is not transcendental")
    return name


def _atan_inverse(x: int, one: int) -> tuple[int, int]:
    """(atan(1/x) * one by the alternating series, the error bound in units): each term
    loses less than two units to the floors, the dropped tail less than one."""
    total, term, k, sign = 0, one // x, 1, 1
    x2 = x * x
    while term:
        total += sign * (term // k)
        term //= x2
        k += 2
        sign = -sign
    return total, k + 2


def _exp_fixed(w: Fraction, bits: int) -> tuple[int, int]:
    """(e^w * 2^bits rounded down termwise, the error bound in units) for 0 <= w <= 1: each
    of the k terms loses less than one unit, and the dropped tail is below one unit."""
    one = 1 << bits
    total, term, k = one, one, 1
    while term:
        term = term * w.numerator // (w.denominator * k)
        total += term
        k += 1
    return total, k + 2


@lru_cache(maxsize=64)
def constant_bounds(name: str, bits: int) -> tuple[Fraction, Fraction]:
    """Rationals lo < c < hi with hi − lo about 2^(−bits) · max(1, c)."""
    guard = bits + 16
    one = 1 << guard
    if name == "pi":
        (a, ea), (b, eb) = _atan_inverse(5, one), _atan_inverse(239, one)
        approx, err = 16 * a - 4 * b, 16 * ea + 4 * eb
        return Fraction(approx - err, one), Fraction(approx + err, one)
    w = Fraction(name[4:-1])
    steps = 0
    small = abs(w)
    while small > 1:  # e^w = (e^(w/2^k))^(2^k)
        small /= 2
        steps += 1
    extra = guard + 2 * steps + int(abs(w)) * 2 + 8
    base, err = _exp_fixed(small, extra)
    lo, hi = Fraction(base - err, 1 << extra), Fraction(base + err, 1 << extra)
    for _ in range(steps):
        lo, hi = lo * lo, hi * hi
        lo = Fraction(lo.numerator * (1 << extra) // lo.denominator, 1 << extra)
        hi = Fraction(-(-hi.numerator * (1 << extra) // hi.denominator), 1 << extra)
    return (lo, hi) if w > 0 else (1 / hi, 1 / lo)


def _trim(p: Poly) -> Poly:
    end = len(p)
    while end and p[end - 1] == 0:
        end -= 1
    return p[:end]


def _add(a: Poly, b: Poly) -> Poly:
    size = max(len(a), len(b))
    return _trim(
        tuple(
            (a[i] if i < len(a) else Fraction(0)) + (b[i] if i < len(b) else Fraction(0))
            for i in range(size)
        )
    )


def _scale(a: Poly, x: Fraction) -> Poly:
    return _trim(tuple(v * x for v in a))


def _mul(a: Poly, b: Poly) -> Poly:
    if not a or not b:
        return ()
    out = [Fraction(0)] * (len(a) + len(b) - 1)
    for i, x in enumerate(a):
        if x:
            for j, y in enumerate(b):
                out[i + j] += x * y
    return _trim(tuple(out))


def _divmod(a: Poly, b: Poly) -> tuple[Poly, Poly]:
    rem = list(a)
    quot = [Fraction(0)] * max(len(a) - len(b) + 1, 1)
    while len(_trim(tuple(rem))) >= len(b):
        rem = list(_trim(tuple(rem)))
        shift = len(rem) - len(b)
        f = rem[-1] / b[-1]
        quot[shift] = f
        for i, y in enumerate(b):
            rem[shift + i] -= f * y
    return _trim(tuple(quot)), _trim(tuple(rem))


def _gcd(a: Poly, b: Poly) -> Poly:
    while b:
        a, b = b, _divmod(a, b)[1]
    return _scale(a, 1 / a[-1]) if a else a


def poly_sign(p: Poly, name: str) -> int:
    """The sign of p(c), decided exactly (c is transcendental)."""
    p = _trim(p)
    if not p:
        return 0
    bits = 64
    while bits <= MAX_BITS:
        lo_c, hi_c = constant_bounds(name, bits)
        lo = hi = Fraction(0)
        for e, coef in enumerate(p):
            if coef == 0:
                continue
            a, b = lo_c**e, hi_c**e
            x, y = sorted((coef * a, coef * b))
            lo, hi = lo + x, hi + y
        if lo > 0:
            return 1
        if hi < 0:
            return -1
        bits *= 4
    raise ValueError(f"the sign of a polynomial in {name} needs more than {MAX_BITS} bits")


Number = Union[int, Fraction, "ConstantFraction"]


@total_ordering
class ConstantFraction:
    """An exact element p(c)/q(c) of ℚ(c), c = π (``constant="pi"``) or e^W
    (``"exp(W)"``); p, q with rational coefficients in ascending powers of c, q monic and
    coprime to p. Arithmetic with ints, Fractions and other ConstantFractions of the same
    constant stays exact; ``float(x)`` is correctly rounded up to a few units in the last
    place; comparisons are exact."""

    __slots__ = ("constant", "denominator", "numerator")

    def __init__(self, numerator: Poly, denominator: Poly = (Fraction(1),), constant: str = "pi"):
        self.constant = check_constant(constant)
        num = _trim(tuple(Fraction(x) for x in numerator))
        den = _trim(tuple(Fraction(x) for x in denominator))
        if not den:
            raise ZeroDivisionError("ConstantFraction with a zero denominator")
        g = _gcd(num, den) if num else den
        if len(g) > 1:
            num, den = _divmod(num, g)[0], _divmod(den, g)[0]
        lead = den[-1]
        if not num:
            den = (Fraction(1),)
        self.numerator: Poly = _scale(num, 1 / lead) if num else ()
        self.denominator: Poly = _scale(den, 1 / lead) if num else (Fraction(1),)

    @classmethod
    def from_laurent(cls, terms: dict[int, Fraction], constant: str) -> ConstantFraction:
        """Σ terms[e] c^e, exponents of any sign."""
        low = min(terms, default=0)
        shift = -low if low < 0 else 0
        size = max(terms, default=0) + shift + 1
        num = [Fraction(0)] * size
        for e, v in terms.items():
            num[e + shift] += v
        den = [Fraction(0)] * shift + [Fraction(1)]
        return cls(tuple(num), tuple(den), constant)

    def _coerce(self, other: object) -> ConstantFraction | None:
        if isinstance(other, ConstantFraction):
            if other.constant != self.constant:
                raise ValueError(
                    f"cannot combine numbers in {self.constant} and in {other.constant}"
                )
            return other
        if isinstance(other, int | Fraction):
            return ConstantFraction((Fraction(other),), (Fraction(1),), self.constant)
        return None

    def __add__(self, other: object) -> ConstantFraction:
        o = self._coerce(other)
        if o is None:
            return NotImplemented
        num = _add(_mul(self.numerator, o.denominator), _mul(o.numerator, self.denominator))
        return ConstantFraction(num, _mul(self.denominator, o.denominator), self.constant)

    __radd__ = __add__

    def __neg__(self) -> ConstantFraction:
        return ConstantFraction(
            _scale(self.numerator, Fraction(-1)), self.denominator, self.constant
        )

    def __sub__(self, other: object) -> ConstantFraction:
        o = self._coerce(other)
        if o is None:
            return NotImplemented
        return self + (-o)

    def __rsub__(self, other: object) -> ConstantFraction:
        o = self._coerce(other)
        if o is None:
            return NotImplemented
        return o + (-self)

    def __mul__(self, other: object) -> ConstantFraction:
        o = self._coerce(other)
        if o is None:
            return NotImplemented
        return ConstantFraction(
            _mul(self.numerator, o.numerator), _mul(self.denominator, o.denominator), self.constant
        )

    __rmul__ = __mul__

    def __truediv__(self, other: object) -> ConstantFraction:
        o = self._coerce(other)
        if o is None:
            return NotImplemented
        if not o.numerator:
            raise ZeroDivisionError("division of a ConstantFraction by zero")
        return ConstantFraction(
            _mul(self.numerator, o.denominator), _mul(self.denominator, o.numerator), self.constant
        )

    def __rtruediv__(self, other: object) -> ConstantFraction:
        o = self._coerce(other)
        if o is None:
            return NotImplemented
        return o / self

    def sign(self) -> int:
        """-1, 0 or 1, exactly."""
        return poly_sign(self.numerator, self.constant) * poly_sign(self.denominator, self.constant)

    def __eq__(self, other: object) -> bool:
        if isinstance(other, float):
            return float(self) == other
        o = self._coerce(other)
        if o is None:
            return NotImplemented
        return (self - o).sign() == 0

    def __lt__(self, other: object) -> bool:
        if isinstance(other, float):
            return float(self) < other
        o = self._coerce(other)
        if o is None:
            return NotImplemented
        return (self - o).sign() < 0

    def __hash__(self) -> int:
        if len(self.numerator) <= 1 and self.denominator == (Fraction(1),):
            return hash(self.numerator[0] if self.numerator else Fraction(0))
        return hash((self.numerator, self.denominator, self.constant))

    def __float__(self) -> float:
        lo, hi = constant_bounds(self.constant, 120)
        c = (lo + hi) / 2

        def value(p: Poly) -> Fraction:
            acc = Fraction(0)
            for v in reversed(p):
                acc = acc * c + v
            return acc

        if not self.numerator:
            return 0.0
        return float(value(self.numerator) / value(self.denominator))

    @property
    def is_rational(self) -> bool:
        return len(self.numerator) <= 1 and self.denominator == (Fraction(1),)

    def __repr__(self) -> str:
        return f"ConstantFraction({self}, ≈ {float(self)!r})"

    def __str__(self) -> str:
        num = _text(self.numerator, self.constant)
        if self.denominator == (Fraction(1),):
            return num
        return f"({num}) / ({_text(self.denominator, self.constant)})"


def _text(p: Poly, name: str) -> str:
    if not p:
        return "0"
    parts = []
    for e, v in enumerate(p):
        if v == 0:
            continue
        power = "" if e == 0 else (name if e == 1 else f"{name}^{e}")
        if not power:
            parts.append(str(v))
        elif v == 1:
            parts.append(power)
        else:
            parts.append(f"{v}*{power}")
    return " + ".join(parts).replace("+ -", "- ")


def parse_exact(value: object, constant: str | None, where: str) -> Fraction | ConstantFraction:
    """An exact number of the format-4 document: "p/q", or [["coefficient", exponent], ...]
    meaning Σ coefficient · constant^exponent. ValueError naming `where` otherwise."""
    if isinstance(value, str):
        if not re.match(r"^-?[0-9]{1,400}(/0*[1-9][0-9]{0,400})?$", value):
            raise ValueError(f"{where}: {value!r} is not an exact number")
        return Fraction(value)
    if not isinstance(value, list) or not value:
        raise ValueError(f"{where}: {value!r} is not an exact number")
    if constant is None:
        raise ValueError(f"{where}: a number in a constant, but the table names no constant")
    terms: dict[int, Fraction] = {}
    for pair in value:
        if (
            not isinstance(pair, list)
            or len(pair) != 2
            or not isinstance(pair[1], int)
            or isinstance(pair[1], bool)
            or abs(pair[1]) > 64
        ):
            raise ValueError(f"{where}: {pair!r} is not a [coefficient, exponent] pair")
        coef = parse_exact(pair[0], None, where)
        assert isinstance(coef, Fraction)
        terms[pair[1]] = terms.get(pair[1], Fraction(0)) + coef
    out = ConstantFraction.from_laurent(terms, constant)
    if out.is_rational:
        return out.numerator[0] if out.numerator else Fraction(0)
    return out


class ConstantSum:
    r"""An exact Σ q · c_1^a · c_2^b (q rational, exponents of any sign) in two constants
    c_1 = π and c_2 = e^W: the energy of a surface whose directions are trigonometric and
    hyperbolic. Kept exact as its terms; whether two such sums are equal is open (the
    algebraic independence of π and e is not known), so they are not ordered. ``float(x)``
    and ``enclosure(bits)`` come from rational enclosures of both constants, interval
    arithmetic throughout: ``enclosure`` returns rationals lo <= x <= hi, a proven bound;
    ``to_sympy()`` gives the closed form in SymPy's pi and exp (SymPy imported on the call)."""

    __slots__ = ("constants", "terms")

    def __init__(self, terms: dict[tuple[int, int], Fraction], constants: tuple[str, str]):
        self.constants = (check_constant(constants[0]), check_constant(constants[1]))
        if self.constants[0] == self.constants[1]:
            raise ValueError(f"two different constants are needed, got {constants!r}")
        self.terms = {
            (int(a), int(b)): Fraction(q) for (a, b), q in sorted(terms.items()) if q != 0
        }

    def enclosure(self, bits: int = 120) -> tuple[Fraction, Fraction]:
        """Rationals lo <= x <= hi, from both constants enclosed to about 2^-bits."""
        boxes = [constant_bounds(c, bits) for c in self.constants]  # both constants are > 0
        lo_sum, hi_sum = Fraction(0), Fraction(0)
        for (a, b), q in self.terms.items():
            lo, hi = Fraction(1), Fraction(1)
            for (c_lo, c_hi), e in zip(boxes, (a, b), strict=True):
                lo *= c_lo**e if e >= 0 else c_hi**e  # c^e increases in c for e >= 0
                hi *= c_hi**e if e >= 0 else c_lo**e
            lo_sum, hi_sum = (
                (lo_sum + q * lo, hi_sum + q * hi)
                if q > 0
                else (
                    lo_sum + q * hi,
                    hi_sum + q * lo,
                )
            )
        return lo_sum, hi_sum

    def __float__(self) -> float:
        bits = 120
        while True:  # widen the precision until the enclosure rounds to one float
            lo, hi = self.enclosure(bits)
            if float(lo) == float(hi) or bits >= MAX_BITS:
                return float((lo + hi) / 2)
            bits *= 2

    def __eq__(self, other: object) -> bool:  # as written: equal terms (never by value)
        if not isinstance(other, ConstantSum):
            return NotImplemented
        return (self.constants, self.terms) == (other.constants, other.terms)

    def __hash__(self) -> int:
        return hash((self.constants, tuple(self.terms.items())))

    def to_sympy(self) -> object:
        import sympy as sp

        def symbol(name: str) -> Any:
            return sp.pi if name == "pi" else sp.exp(sp.Rational(name[4:-1]))

        c1, c2 = (symbol(c) for c in self.constants)
        return sp.Add(
            *(
                sp.Rational(q.numerator, q.denominator) * c1**a * c2**b
                for (a, b), q in self.terms.items()
            )
        )

    def __repr__(self) -> str:
        return f"ConstantSum({self}, ≈ {float(self)!r})"

    def __str__(self) -> str:
        if not self.terms:
            return "0"
        parts = []
        for (a, b), q in self.terms.items():
            powers = [
                name if e == 1 else f"{name}^{e}"
                for name, e in zip(self.constants, (a, b), strict=True)
                if e
            ]
            if not powers:
                parts.append(str(q))
            else:
                head = {Fraction(1): [], Fraction(-1): ["-"]}.get(q, [f"{q}*"])
                parts.append("".join(head) + "*".join(powers))
        return " + ".join(parts).replace("+ -", "- ")
