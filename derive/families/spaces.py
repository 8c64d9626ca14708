"""The space of a basis with sin, cos, sinh, cosh or exp, decided exactly (issue #30).

A definition's functions (parsed by the grammar, so every sin/cos/... has a rational multiple
of t or of pi*t as its argument) are read into exact exponential polynomials
(derive/algebra/atoms.py) over one frame: the base rate w (the greatest common divisor of the
rates, all in one unit), the domain and the transcendental constant. The space is then:

* ``trigonometric``: polynomials in sin(w t), cos(w t) (atoms 1, cos(m w t), sin(m w t));
* ``hyperbolic``: polynomials in sinh(w t), cosh(w t), e^(+-w t) (atoms 1, cosh, sinh);
* ``mixed-trigonometric`` / ``mixed-hyperbolic``: those atoms and 1, t, ..., t^k.

Anything else is refused with a DefinitionError naming the key and the term: a product of
t with a trigonometric or hyperbolic atom, trigonometric and hyperbolic functions together,
rates in different units (sin(t) with sin(pi*t)), pi outside an argument, a division by a
function of t. The domain must make every end value rational or a power of the constant:
for a trigonometric space w*lo and w*hi are multiples of pi/2 (so [0, pi/2] with sin(t), or
[0, 1] with sin(pi*t/2)); a C-Bezier family on [0, alpha] with a general alpha would need a
symbolic end in the frame and is not built.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from functools import cache
from math import gcd

import sympy as sp

from ..algebra import atoms as A
from .definition import _T, Definition, DefinitionError

TRIG = (sp.sin, sp.cos)
HYP = (sp.sinh, sp.cosh, sp.exp)
MAX_HARMONIC = 64  # the largest multiple m of the base rate in a basis function


@dataclass(frozen=True)
class Space:
    name: str  # trigonometric | hyperbolic | mixed-trigonometric | mixed-hyperbolic
    frame: A.Frame
    functions: tuple[A.Elem, ...]  # b_0 .. b_n, exact
    constant: str  # "pi" or "exp(W)": what C stands for in exact numbers

    @property
    def trigonometric(self) -> bool:
        return self.name.endswith("trigonometric")


def _fraction(x: sp.Rational) -> Fraction:
    return Fraction(int(x.p), int(x.q))


def _rate(call: sp.Basic) -> tuple[Fraction, bool]:
    """(rational, in pi) of the argument of sin/cos/...: the grammar made it rate * t."""
    r = sp.expand(call.args[0] / _T)
    unit = r.has(sp.pi)
    return _fraction(r / sp.pi if unit else r), unit


def _gcd(values: list[Fraction]) -> Fraction:
    num = 0
    den = 1
    for v in values:
        den = den * v.denominator // gcd(den, v.denominator)
    for v in values:
        num = gcd(num, abs(v.numerator) * (den // v.denominator))
    return Fraction(num, den)


@cache
def space_of(defn: Definition) -> Space:
    """The exact space of the definition's functions, or a DefinitionError naming why not."""
    prefix = "[family]"

    def fail(key: str, message: str) -> DefinitionError:
        return DefinitionError(f"{prefix}, key {key}: {message}")

    exprs = defn.functions
    trig: list[tuple[str, sp.Basic]] = []
    hyp: list[tuple[str, sp.Basic]] = []
    for idx, e in enumerate(exprs):
        key = f"functions[{idx}]"
        trig += [(key, c) for c in sorted(e.atoms(*TRIG), key=str)]
        hyp += [(key, c) for c in sorted(e.atoms(*HYP), key=str)]
    if trig and hyp:
        raise fail(
            hyp[0][0],
            f"{hyp[0][1]} with {trig[0][1]} ({trig[0][0]}): trigonometric and hyperbolic "
            "functions together are not in a space this version decides",
        )
    calls = trig or hyp
    units = {_rate(c)[1] for _, c in calls}
    if len(units) > 1:
        key, c = next((k, c) for k, c in calls if _rate(c)[1])
        raise fail(
            key,
            f"{c}: rates in pi and rational rates together (sin(t) with sin(pi*t)) have no "
            "common period; use one unit",
        )
    rate_pi = units.pop() if units else False
    if hyp and rate_pi:
        raise fail(hyp[0][0], f"{hyp[0][1]}: a hyperbolic rate is rational (no pi)")
    dom_pi = defn.domain_unit == "pi"
    if hyp and dom_pi:
        raise fail("domain", f"{defn.domain_text}: a hyperbolic basis has a rational domain")
    rate = _gcd([_rate(c)[0] for _, c in calls]) if calls else Fraction(1)
    lo, hi = defn.domain_lo, defn.domain_hi
    exp_unit = None
    if hyp:
        exp_unit = _gcd([x * rate for x in (lo, hi) if x])
    frame = A.Frame(rate, rate_pi, lo, hi, dom_pi, exp_unit, len(defn.parameters))
    if trig:
        for x in (lo, hi):
            try:
                A.phase(frame, 1, x)
            except A.AtomError:
                w = f"{rate}{'*pi' if rate_pi else ''}"
                raise fail(
                    "domain",
                    f"{defn.domain_text} with the base rate {w}: the values at the ends are "
                    f"not rational (cos({w}*{x}{'*pi' if dom_pi else ''}) is not); this "
                    "version needs the base rate times each end to be a multiple of pi/2 "
                    "(such as [0, pi/2] with sin(t), or [0, 1] with sin(pi*t/2))",
                ) from None
    elif not hyp and (lo, hi, dom_pi) != (0, 1, False):
        raise fail("domain", f"{defn.domain_text}: a polynomial basis is derived on [0, 1] only")

    functions = []
    symbols = {s: j for j, s in enumerate(defn.symbols)}
    for idx, e in enumerate(exprs):
        key = f"functions[{idx}]"
        try:
            elem = _convert(e, frame, symbols, rate)
        except A.AtomError as exc:
            raise fail(key, str(exc)) from None
        for _mono, c, k, h, m, kind in elem:
            if c:
                raise fail(key, "pi enters only in an argument (sin(pi*t)) or the domain")
            if k and (h or m):
                raise fail(
                    key,
                    f"{_show(k, h, m, kind, frame)} is not in a space this version decides "
                    "(t^k times a trigonometric or hyperbolic function)",
                )
            if max(abs(h), m, k) > MAX_HARMONIC:
                raise fail(
                    key,
                    f"a harmonic {max(abs(h), m)} times the base rate or a power t^{k} (at "
                    f"most {MAX_HARMONIC})",
                )
        functions.append(elem)
    algebraic = any(key[2] for elem in functions for key in elem)
    name = ("trigonometric" if trig else "hyperbolic") if calls else "polynomial"
    if algebraic and calls:
        name = f"mixed-{name}"
    constant = "pi" if not hyp else f"exp({exp_unit})"
    return Space(name, frame, tuple(functions), constant)


def _show(k: int, h: int, m: int, kind: int, frame: A.Frame) -> str:
    pi = "*pi" if frame.rate_pi else ""
    parts = [f"t**{k}" if k > 1 else "t"] if k else []
    if h:
        parts.append(f"exp({h * frame.rate}{pi}*t)")
    if m:
        parts.append(f"{'cos' if kind == A.COS else 'sin'}({m * frame.rate}{pi}*t)")
    return "*".join(parts)


def _convert(e: sp.Basic, frame: A.Frame, symbols: dict, rate: Fraction) -> A.Elem:
    """A parsed function as an exact element over the frame (AtomError: not representable)."""
    if e == _T:
        return A.atom(frame, k=1)
    if e in symbols:
        return A.parameter(frame, symbols[e])
    if e.is_Rational:
        return A.constant(frame, _fraction(e))
    if e == sp.pi:
        zero = frame.zero_mono
        return {(zero, 1, 0, 0, 0, A.COS): Fraction(1)}
    if e.is_Add:
        out: A.Elem = {}
        for a in e.args:
            out = A.add(out, _convert(a, frame, symbols, rate))
        return out
    if e.is_Mul:
        out = A.constant(frame)
        for a in e.args:
            out = A.mul(out, _convert(a, frame, symbols, rate))
        return out
    if e.is_Pow:
        if not e.exp.is_Integer:
            raise A.AtomError(f"{e}: the exponent is not an integer")
        if e.exp < 0:
            if not e.base.is_Rational:
                raise A.AtomError(f"{e}: a division by a function of t or of a parameter")
            return A.constant(frame, _fraction(e))
        if e.exp > MAX_HARMONIC and e.base.has(_T):
            raise A.AtomError(f"{e}: a power of a function of t above {MAX_HARMONIC}")
        return A.power(_convert(e.base, frame, symbols, rate), int(e.exp), frame)
    if isinstance(e, TRIG + HYP):
        r, _ = _rate(e)
        mult = r / rate
        assert mult.denominator == 1, "the base rate divides every rate"
        m = int(mult)
        if isinstance(e, sp.cos):
            return A.atom(frame, m=m)
        if isinstance(e, sp.sin):
            return A.scale(A.atom(frame, m=abs(m), kind=A.SIN), 1 if m > 0 else -1)
        if isinstance(e, sp.exp):
            return A.atom(frame, h=m)
        half = Fraction(1, 2)
        sign = 1 if isinstance(e, sp.cosh) else -1
        return A.add(A.scale(A.atom(frame, h=m), half), A.atom(frame, h=-m), sign * half)
    raise A.AtomError(f"{e} is not a sum of products of t, the parameters and sin/cos/... ")
