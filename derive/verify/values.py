"""The values of the realiser beside scalars: ``Form`` (a polynomial in the control points,
linear for a point, quadratic for a dot product), ``Wedge`` (a cross product of two point
combinations), ``Rad`` (a scalar times powers of Euclidean lengths), ``Ratio`` (a quotient of
two Forms) and ``DotSum`` (a lazy dot product), with their arithmetic.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

from .scalar import (
    Sc,
    Undefined,
    _is_zero,
    _nz,
    as_int,
)

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


def trivially_zero(v) -> bool:
    """Zero without a computation (models return an exact 0 for a vanishing function)."""
    if isinstance(v, (Form, Wedge)):
        return not v.terms
    if isinstance(v, Rad):
        return trivially_zero(v.coef)
    if isinstance(v, Sc):
        return v.is_zero()
    return not isinstance(v, (Ratio, DotSum)) and v == 0


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
    raise TypeError(f"a formula adds {_kind(a)} and {_kind(b)}, which cannot be added")


# what a value is, in a user's words (an error names the terms a records formula mixes)
_KINDS = {
    "Sc": "a number",
    "Form": "a combination of control points",
    "Wedge": "a cross product of points",
    "DotSum": "a dot product of points",
    "Rad": "a square root",
    "Ratio": "a quotient",
}


def _kind(value) -> str:
    return _KINDS.get(type(value).__name__, type(value).__name__)


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
