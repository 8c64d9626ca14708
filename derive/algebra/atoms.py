"""Exact exponential polynomials: sums of parameter monomials times atoms
t^k e^(h w t) cos(m w t) or sin(m w t), with rational coefficients (issue #30).

SymPy's trigonometric simplification is slow and is not a decision procedure, so the
trigonometric and hyperbolic families are computed here by exact linear algebra on atoms:
products by the product-to-sum rules, derivatives and integrals over the domain in closed
form, with Fractions only. An element is a dict

    {(monomial, c, k, h, m, kind): coefficient}

meaning  sum coefficient * params^monomial * C^c * t^k * e^(h w t) * (cos | sin)(m w t),

where w is the frame's base rate (a rational, times pi when `rate_pi`), h and m are integers
(m >= 0; kind 0 is cos, 1 is sin; cos(0) is the constant 1 and sin(0) never occurs), and C
is the frame's transcendental constant: pi for a trigonometric space, e^W for a hyperbolic
one. A family's own basis has c = 0 everywhere (rational coefficients on atoms); derivatives
(factors w), integrals (1/w, values of t^k at ends in pi) and end values (e^(h w x)) bring in
powers of C. Since pi and e^W are transcendental, two elements are equal as functions exactly
when their dicts are equal: partition of unity and symmetry are dict comparisons.

A definition with a parameter inside sin/cos, or a domain [0, alpha] with a parameter alpha
(C-Bezier), would give the frame a symbolic rate or end: the atoms stay, and `Frame` is the
one place that would change (docs/guide/architecture.md).
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from fractions import Fraction
from functools import cache
from math import comb

Mono = tuple[int, ...]
Key = tuple[Mono, int, int, int, int, int]  # (monomial, c, k, h, m, kind)
Elem = dict[Key, Fraction]
Number = dict[tuple[Mono, int], Fraction]  # {(monomial, c): coefficient}: values, integrals

COS, SIN = 0, 1
MAX_TERMS = 50_000  # terms of one element: a definition that expands past this is refused


class AtomError(ValueError):
    """An operation outside the representable space (the caller names the definition key)."""


@dataclass(frozen=True)
class Frame:
    """The base rate w = rate * (pi if rate_pi), the domain [lo, hi] * (pi if dom_pi), and
    for hyperbolic spaces the exponent W of the constant C = e^W (None: C = pi)."""

    rate: Fraction
    rate_pi: bool
    lo: Fraction
    hi: Fraction
    dom_pi: bool
    exp_unit: Fraction | None
    nparams: int

    @property
    def zero_mono(self) -> Mono:
        return (0,) * self.nparams


# --------------------------------------------------------------------------- construction


def add_into(out: Elem, key: Key, value: Fraction) -> None:
    got = out.get(key, Fraction(0)) + value
    if got:
        out[key] = got
    else:
        out.pop(key, None)
    if len(out) > MAX_TERMS:
        raise AtomError(f"more than {MAX_TERMS} terms after expansion")


def constant(frame: Frame, value: Fraction | int = 1) -> Elem:
    return {(frame.zero_mono, 0, 0, 0, 0, COS): Fraction(value)} if value else {}


def atom(frame: Frame, k: int = 0, h: int = 0, m: int = 0, kind: int = COS) -> Elem:
    out: Elem = {}
    _put(out, frame.zero_mono, 0, k, h, m, kind, Fraction(1))
    return out


def parameter(frame: Frame, index: int) -> Elem:
    mono = tuple(int(j == index) for j in range(frame.nparams))
    return {(mono, 0, 0, 0, 0, COS): Fraction(1)}


def _put(out: Elem, mono: Mono, c: int, k: int, h: int, m: int, kind: int, v: Fraction) -> None:
    """Add v * atom, the atom normalised: m >= 0 (sin(-x) = -sin x), sin(0) = 0."""
    if m < 0:
        m = -m
        if kind == SIN:
            v = -v
    if m == 0 and kind == SIN:
        return
    add_into(out, (mono, c, k, h, m, kind), v)


def add(a: Elem, b: Elem, scale: Fraction | int = 1) -> Elem:
    out = dict(a)
    for key, v in b.items():
        add_into(out, key, v * scale)
    return out


def scale(a: Elem, factor: Fraction | int) -> Elem:
    return {key: v * factor for key, v in a.items()} if factor else {}


def mul(a: Elem, b: Elem) -> Elem:
    """The product, by the product-to-sum rules (cos x cos y = (cos(x-y) + cos(x+y))/2, ...)."""
    out: Elem = {}
    half = Fraction(1, 2)
    for (m1, c1, k1, h1, w1, s1), v1 in a.items():
        for (m2, c2, k2, h2, w2, s2), v2 in b.items():
            mono = tuple(x + y for x, y in zip(m1, m2, strict=True))
            c, k, h, v = c1 + c2, k1 + k2, h1 + h2, v1 * v2
            if w1 == 0 or w2 == 0:  # a cos(0) factor is 1
                _put(out, mono, c, k, h, w1 + w2, s1 if w2 == 0 else s2, v)
                continue
            if s1 == COS and s2 == COS:
                terms = ((w1 - w2, COS, half), (w1 + w2, COS, half))
            elif s1 == SIN and s2 == SIN:
                terms = ((w1 - w2, COS, half), (w1 + w2, COS, -half))
            elif s1 == SIN:
                terms = ((w1 + w2, SIN, half), (w1 - w2, SIN, half))
            else:
                terms = ((w1 + w2, SIN, half), (w1 - w2, SIN, -half))
            for w, kind, f in terms:
                _put(out, mono, c, k, h, w, kind, v * f)
    return out


def power(a: Elem, exponent: int, frame: Frame) -> Elem:
    out, base = constant(frame), a
    while exponent:
        if exponent & 1:
            out = mul(out, base)
        exponent >>= 1
        if exponent:
            base = mul(base, base)
    return out


# --------------------------------------------------------------------------- calculus


def diff(a: Elem, frame: Frame, order: int = 1) -> Elem:
    """d^order/dt^order: d(t^k E) = k t^(k-1) E + t^k E', E' = w (h E -+ m E~)."""
    for _ in range(order):
        out: Elem = {}
        dc = 1 if frame.rate_pi else 0
        for (mono, c, k, h, m, kind), v in a.items():
            if k:
                _put(out, mono, c, k - 1, h, m, kind, v * k)
            if h:
                _put(out, mono, c + dc, k, h, m, kind, v * h * frame.rate)
            if m:
                sign = -1 if kind == COS else 1
                _put(out, mono, c + dc, k, h, m, 1 - kind, v * sign * m * frame.rate)
        a = out
    return a


@cache
def _primitive(frame: Frame, k: int, h: int, m: int, kind: int) -> tuple:
    """An antiderivative of t^k e^(h w t) cos|sin(m w t), as ((c, k, h, m, kind, coef), ...):
    by parts, int t^k E = t^k F - k int t^(k-1) F with F' = E."""
    if h == 0 and m == 0:
        return ((0, k + 1, 0, 0, COS, Fraction(1, k + 1)),)
    if h and m:
        raise AtomError("no closed form kept for the integral of e^(ht) times cos|sin(mt)")
    dc = -1 if frame.rate_pi else 0
    if h:
        first = [(dc, 0, h, 0, COS, 1 / (h * frame.rate))]
    elif kind == COS:
        first = [(dc, 0, 0, m, SIN, 1 / (m * frame.rate))]
    else:
        first = [(dc, 0, 0, m, COS, -1 / (m * frame.rate))]
    out: dict[tuple, Fraction] = {}
    for c, _, hh, mm, kk, f in first:
        out[(c, k, hh, mm, kk)] = out.get((c, k, hh, mm, kk), Fraction(0)) + f
        if k:
            for c2, k2, h2, m2, s2, f2 in _primitive(frame, k - 1, hh, mm, kk):
                key = (c + c2, k2, h2, m2, s2)
                out[key] = out.get(key, Fraction(0)) - k * f * f2
    return tuple((*key, v) for key, v in sorted(out.items()) if v)


def phase(frame: Frame, m: int, x: Fraction) -> tuple[Fraction, Fraction]:
    """(cos, sin) of m * w * x * U (U = pi for a domain in pi): exact rationals, since the
    frame is built so that every such phase is a multiple of pi/2 (else AtomError)."""
    if m == 0 or x == 0:
        return Fraction(1), Fraction(0)
    if int(frame.rate_pi) + int(frame.dom_pi) != 1:
        square = "*pi**2" if frame.dom_pi else ""
        raise AtomError(f"cos({m * frame.rate * x}{square}) is not rational")
    quarter = 2 * m * frame.rate * x  # the phase in units of pi/2
    if quarter.denominator != 1:
        raise AtomError(f"the phase {m * frame.rate * x}*pi is not a multiple of pi/2")
    q = int(quarter) % 4
    return (Fraction((1, 0, -1, 0)[q]), Fraction((0, 1, 0, -1)[q]))


def exp_power(frame: Frame, h: int, x: Fraction) -> int:
    """e^(h w x) as a power of C = e^W (an integer, by the frame's construction)."""
    if h == 0 or x == 0:
        return 0
    assert frame.exp_unit is not None and not frame.rate_pi and not frame.dom_pi
    ratio = h * frame.rate * x / frame.exp_unit
    if ratio.denominator != 1:
        raise AtomError(f"e^({h * frame.rate * x}) is not a power of e^({frame.exp_unit})")
    return int(ratio)


def _term_value(frame: Frame, x: Fraction, c: int, k: int, h: int, m: int, kind: int):
    """(factor, c) of one atom at t = x * U."""
    cos_, sin_ = phase(frame, m, x)
    trig = cos_ if kind == COS else sin_
    if not trig or (k and not x):
        return Fraction(0), 0
    return x**k * trig, c + k * int(frame.dom_pi) + exp_power(frame, h, x)


def value(a: Elem, frame: Frame, x: Fraction) -> Number:
    """The element at t = x * U, exact: {(monomial, power of C): rational}."""
    out: Number = {}
    for (mono, c, k, h, m, kind), v in a.items():
        f, cc = _term_value(frame, x, c, k, h, m, kind)
        if f:
            _acc(out, (mono, cc), v * f)
    return out


def integral(a: Elem, frame: Frame) -> Number:
    """int over [lo, hi] * U of the element, dt, exact."""
    out: Number = {}
    for (mono, c, k, h, m, kind), v in a.items():
        for c2, k2, h2, m2, s2, f in _primitive(frame, k, h, m, kind):
            for x, sign in ((frame.hi, 1), (frame.lo, -1)):
                g, cc = _term_value(frame, x, c + c2, k2, h2, m2, s2)
                if g:
                    _acc(out, (mono, cc), sign * v * f * g)
    return out


def _acc(out: Number, key: tuple[Mono, int], v: Fraction) -> None:
    got = out.get(key, Fraction(0)) + v
    if got:
        out[key] = got
    else:
        out.pop(key, None)


def reflect(a: Elem, frame: Frame) -> Elem:
    """The element at lo + hi - t (the mirror of the domain), exact."""
    mid = frame.lo + frame.hi
    out: Elem = {}
    for (mono, c, k, h, m, kind), v in a.items():
        cos_, sin_ = phase(frame, m, mid)
        ce = c + exp_power(frame, h, mid)
        for j in range(k + 1):  # (mid - t)^k
            f = v * comb(k, j) * mid ** (k - j) * (-1) ** j
            if not f:
                continue
            cj = ce + (k - j) * int(frame.dom_pi)
            if m == 0:
                _put(out, mono, cj, j, -h, 0, COS, f)
            elif kind == COS:  # cos(a - x) = cos a cos x + sin a sin x
                _put(out, mono, cj, j, -h, m, COS, f * cos_)
                _put(out, mono, cj, j, -h, m, SIN, f * sin_)
            else:  # sin(a - x) = sin a cos x - cos a sin x
                _put(out, mono, cj, j, -h, m, COS, f * sin_)
                _put(out, mono, cj, j, -h, m, SIN, -f * cos_)
    return out


def substitute_parameters(a: Elem, perm: Iterable[int], signs: Iterable[int]) -> Elem:
    """x_j -> signs[j] * x_perm[j]: each monomial's exponents move and pick up the signs."""
    perm, signs = tuple(perm), tuple(signs)
    out: Elem = {}
    for (mono, *rest), v in a.items():
        new = [0] * len(mono)
        sign = 1
        for j, e in enumerate(mono):
            new[perm[j]] += e
            if signs[j] < 0 and e % 2:
                sign = -sign
        add_into(out, (tuple(new), *rest), v * sign)  # type: ignore[arg-type]
    return out


def at_parameters(a: Elem, point: tuple[Fraction, ...]) -> Elem:
    """The element with every parameter set to a rational value."""
    zero = (0,) * len(point)
    out: Elem = {}
    for (mono, *rest), v in a.items():
        f = v
        for x, e in zip(point, mono, strict=True):
            f *= x**e
        add_into(out, (zero, *rest), f)  # type: ignore[arg-type]
    return out


def monomials(elems: Iterable[Elem]) -> list[Mono]:
    return sorted({key[0] for a in elems for key in a})


def part(a: Elem, mono: Mono) -> Elem:
    """The coefficient of one parameter monomial (as an element with the zero monomial)."""
    zero = (0,) * len(mono)
    return {(zero, *key[1:]): v for key, v in a.items() if key[0] == mono}  # type: ignore[misc]
