"""Families whose parameter is the length of the domain or sits inside sin/cos (issue #30):
C-Bezier curves on [0, alpha] (Zhang 1996) and their hyperbolic analogue.

A definition is a ``[family]`` table with one parameter (``parameter = "alpha"``) whose
``domain`` is ``"[0, alpha]"`` with functions in t, sin(t), cos(t) (or sinh, cosh), or
``"[0, 1]"`` with functions in sin(alpha*t), cos(alpha*t); in both, the coefficients may be
rational functions of alpha, sin(alpha), cos(alpha) (sinh, cosh for the hyperbolic space). The
grammar (derive/grammar/formula.py, ``frequency``) admits alpha inside an argument only as
a*t + b*alpha + c*alpha*t with rationals; this module admits integer a, b, c only.

Both forms are read into one exact representation in the family's space on [0, alpha] (the
form on [0, 1] through t = alpha*u): a function is a dict {atom: coefficient}, the atoms
t^k (k <= MAX_POWER), cos(m t), sin(m t) (cosh, sinh) with 1 <= m <= MAX_HARMONIC, and each
coefficient a rational function of the symbols A = alpha, S = sin(alpha), C = cos(alpha) (or
sinh, cosh) taken modulo S^2 + C^2 = 1 (C^2 - S^2 = 1).

Why (A, S, C) modulo the circle and not the half angle w = tan(alpha/2): the box of a C-Bezier
family is (0, pi], and w is infinite at pi; S and C are bounded everywhere. The reduction
S^2 -> 1 - C^2 (S^2 -> C^2 - 1) is a Groebner basis of a prime ideal, and alpha, cos(alpha) are
algebraically independent functions while sin(alpha) is not in C(alpha, cos(alpha)), so a
numerator reduced to degree <= 1 in S is zero as a function of alpha exactly when it is zero
as a polynomial: every identity below (partition of unity, end conditions, symmetry) is
decided by `reduce` and a comparison with 0.
"""

from __future__ import annotations

import dataclasses
import re
from dataclasses import dataclass
from fractions import Fraction
from functools import cache

import sympy as sp

from ..grammar import ParseError, parse_formula
from ..grammar.messages import schema_message
from .definition import SCHEMA, DefinitionError, digest

A, S, C = sp.symbols("alpha_ s_ c_")  # alpha, sin(alpha) or sinh(alpha), cos or cosh
T = sp.Symbol("t")
MAX_HARMONIC = 8
MAX_POWER = 8
COS, SIN, POW = "cos", "sin", "pow"
Atom = tuple[str, int]  # ("pow", k) for t^k (k = 0 is 1), ("cos", m), ("sin", m)
Elem = dict[Atom, sp.Expr]

_TRIG = (sp.sin, sp.cos)
_HYP = (sp.sinh, sp.cosh)


@dataclass(frozen=True)
class CDefinition:
    """A family with its parameter in the domain or inside sin/cos, read and converted."""

    name: str
    title: str
    parameter: str
    range_text: str
    lo: sp.Expr  # exact ends of the parameter box (rationals or rational multiples of pi)
    hi: sp.Expr
    lo_closed: bool
    hi_closed: bool
    form: str  # "domain": t on [0, alpha]; "unit": u on [0, 1], t = alpha*u
    hyperbolic: bool
    functions_texts: tuple[str, ...]
    functions: tuple[tuple[tuple[Atom, sp.Expr], ...], ...]  # exact, in t on [0, alpha]
    digest: str
    domain_text: str
    # a degree derived by an integral recursion (cbezier_recursion.py): its functions written
    # out as SymPy expressions in t and A (the texts would be parsed again otherwise)
    written_exprs: tuple[sp.Expr, ...] | None = None

    @property
    def degree(self) -> int:
        return len(self.functions) - 1

    @property
    def space(self) -> str:
        return "hyperbolic" if self.hyperbolic else "trigonometric"

    def elems(self) -> list[Elem]:
        return [dict(f) for f in self.functions]

    def written(self) -> list[sp.Expr]:
        """The functions as written (parsed again by the grammar), in t on [0, alpha] with
        alpha as A: the natural form for ball enclosures (it cancels less than the atoms)."""
        if self.written_exprs is not None:
            return list(self.written_exprs)
        alpha = sp.Symbol(self.parameter)
        out = []
        for text in self.functions_texts:
            e = parse_formula(
                text,
                {"t": T, self.parameter: alpha},
                {},
                elementary=True,
                frequency=(self.parameter,),
            )
            if self.form == "unit":
                e = e.subs(T, T / alpha)
            out.append(e.subs(alpha, A))
        return out


# --------------------------------------------------------------------------- exact numbers


def reduce(expr: sp.Expr, hyperbolic: bool) -> sp.Expr:
    """The normal form of a rational function of (A, S, C) modulo the circle (hyperbola):
    numerator and denominator reduced to degree <= 1 in S, common factors cancelled."""
    num, den = sp.fraction(sp.cancel(sp.together(expr)))
    square = C**2 - 1 if hyperbolic else 1 - C**2
    num, den = (_reduce_poly(x, square) for x in (num, den))
    if den == 0:
        raise ZeroDivisionError("a denominator that vanishes identically")
    return sp.cancel(num / den) if num != 0 else sp.Integer(0)


def _reduce_poly(p: sp.Expr, square: sp.Expr) -> sp.Expr:
    poly = sp.Poly(sp.expand(p), S)
    out = sp.Integer(0)
    for (e,), coeff in poly.terms():
        out += coeff * square ** (e // 2) * S ** (e % 2)
    return sp.expand(out)


def is_zero(expr: sp.Expr, hyperbolic: bool) -> bool:
    """expr == 0 as a function: its numerator over a common denominator (not cancelled: the
    gcd of large rational functions is the slow part of `reduce`) reduced modulo the circle."""
    num, den = sp.fraction(sp.together(expr))
    square = C**2 - 1 if hyperbolic else 1 - C**2
    if _reduce_poly(den, square) == 0:
        raise ZeroDivisionError("a denominator that vanishes identically")
    return _reduce_poly(num, square) == 0


@cache
def _chebyshev(m: int) -> tuple[sp.Expr, sp.Expr]:
    """(cos(m alpha), sin(m alpha)) as polynomials in C, S (the same for cosh, sinh)."""
    return sp.expand(sp.chebyshevt(m, C)), sp.expand(S * sp.chebyshevu(m - 1, C)) if m else 0


def angle(m: int, hyperbolic: bool) -> tuple[sp.Expr, sp.Expr]:
    """cos(m alpha), sin(m alpha) (cosh, sinh) for an integer m of either sign."""
    c, s = _chebyshev(abs(m))
    return c, (s if m >= 0 else -s)


# --------------------------------------------------------------------------- elements


def add_into(out: Elem, atom: Atom, value: sp.Expr) -> None:
    out[atom] = out.get(atom, sp.Integer(0)) + value


def normal(e: Elem, hyperbolic: bool) -> Elem:
    out = {}
    for atom in sorted(e):
        v = reduce(e[atom], hyperbolic)
        if v != 0:
            out[atom] = v
    return out


def derivative(e: Elem, hyperbolic: bool, order: int = 1) -> Elem:
    for _ in range(order):
        out: Elem = {}
        for (kind, m), v in e.items():
            if kind == POW:
                if m:
                    add_into(out, (POW, m - 1), m * v)
            elif kind == COS:
                add_into(out, (SIN, m), (m if hyperbolic else -m) * v)
            else:
                add_into(out, (COS, m), m * v)
        e = out
    return e


def value_at(e: Elem, end: str, hyperbolic: bool) -> sp.Expr:
    """The value at t = 0 or t = alpha ("lo", "hi"), reduced."""
    total = sp.Integer(0)
    for (kind, m), v in e.items():
        if end == "lo":
            total += v if (kind == POW and m == 0) or kind == COS else 0
        elif kind == POW:
            total += v * A**m
        else:
            c, s = angle(m, hyperbolic)
            total += v * (c if kind == COS else s)
    return reduce(total, hyperbolic)


def reflect(e: Elem, hyperbolic: bool) -> Elem:
    """The function t -> f(alpha - t) in the same atoms."""
    out: Elem = {}
    for (kind, m), v in e.items():
        if kind == POW:
            for j in range(m + 1):
                add_into(out, (POW, j), v * sp.binomial(m, j) * A ** (m - j) * (-1) ** j)
            continue
        c, s = angle(m, hyperbolic)
        # cos(m(a - t)) = cos(ma) cos(mt) + sin(ma) sin(mt); sin(m(a - t)) = sin(ma) cos(mt)
        # - cos(ma) sin(mt); cosh(m(a - t)) = cosh cosh - sinh sinh; sinh = sinh cosh - cosh sinh
        if kind == COS:
            add_into(out, (COS, m), v * c)
            add_into(out, (SIN, m), v * (-s if hyperbolic else s))
        else:
            add_into(out, (COS, m), v * s)
            add_into(out, (SIN, m), -v * c)
    return out


def as_function(e: Elem, hyperbolic: bool, base: int = 1) -> sp.Expr:
    """The element as a SymPy function of t and alpha (for checks against independent
    numerics: the atoms and the coefficients written out, S and C as sin/cos of alpha, or of
    alpha/base for a claim's field, `to_atoms`)."""
    cos, sin = (sp.cosh, sp.sinh) if hyperbolic else (sp.cos, sp.sin)
    out = sp.Integer(0)
    for (kind, m), v in e.items():
        atom = T**m if kind == POW else (cos if kind == COS else sin)(m * T)
        out += v * atom
    return out.subs({S: sin(A / base), C: cos(A / base)})


# --------------------------------------------------------------------------- reading


def _names(table: dict) -> list[str]:
    if "parameters" in table and isinstance(table["parameters"], list):
        return [str(x) for x in table["parameters"]]
    return [str(table["parameter"])] if isinstance(table.get("parameter"), str) else []


def is_frequency_family(table: object) -> bool:
    """Does this [family] table put its parameter in the domain or inside sin/cos/sinh/cosh?
    (Then this module reads it; every other table goes to definition.py.)"""
    if not isinstance(table, dict):
        return False
    names = _names(table)
    domain = table.get("domain")
    if isinstance(domain, str) and any(re.search(rf"\b{re.escape(p)}\b", domain) for p in names):
        return True
    functions = table.get("functions", table.get("seed"))
    if not isinstance(functions, list):
        return False
    calls = re.compile(r"\b(sin|cos|sinh|cosh|exp)\s*\(([^()]*)\)")
    for text in functions:
        if not isinstance(text, str):
            continue
        for match in calls.finditer(text):
            if any(re.search(rf"\b{re.escape(p)}\b", match.group(2)) for p in names):
                return True
    return False


_RANGE = re.compile(r"^\s*([\[(])([^,\[\]()]+),([^,\[\]()]+)([\])])\s*$")


def _end(text: str, key: str, fail) -> sp.Expr:
    try:
        e = parse_formula(text, {}, {}, elementary=True)
    except ParseError as exc:
        raise fail(key, str(exc)) from None
    unit = e / sp.pi if e.has(sp.pi) else e
    if not unit.is_Rational:
        raise fail(key, f"{text!r} is neither an exact rational nor a rational times pi")
    return e


def parse_range(rng: str, key: str, fail) -> tuple[sp.Expr, sp.Expr, bool, bool]:
    """(lo, hi, lo closed, hi closed) of an interval of the parameter such as "(0, pi]": the
    ends exact rationals or rational multiples of pi, the box in alpha > 0; fail(key, message)
    otherwise."""
    m = _RANGE.match(rng)
    if not m:
        raise fail(key, f'{rng!r} is not an interval such as "(0, pi]"')
    lo, hi = _end(m.group(2).strip(), key, fail), _end(m.group(3).strip(), key, fail)
    lo_closed, hi_closed = m.group(1) == "[", m.group(4) == "]"
    if not lo < hi:
        raise fail(key, f"the interval {rng} is empty")
    if lo < 0 or (lo == 0 and lo_closed):
        raise fail(
            key,
            f"{rng}: the parameter is the length of the domain (or a frequency): the box lies "
            "in alpha > 0 (write an open end, such as (0, pi])",
        )
    return lo, hi, lo_closed, hi_closed


def with_range(defn: CDefinition, rng: str, key: str, fail) -> CDefinition:
    """The definition over another box of its parameter (a record's `box`)."""
    lo, hi, lo_closed, hi_closed = parse_range(rng, key, fail)
    return dataclasses.replace(
        defn, range_text=rng.strip(), lo=lo, hi=hi, lo_closed=lo_closed, hi_closed=hi_closed
    )


def read_table(table: dict, where: str = "") -> CDefinition:
    """Validate and convert a table that `is_frequency_family`; DefinitionError naming the
    key (and the term) otherwise."""
    import jsonschema

    prefix = f"{where}: [family]" if where else "[family]"

    def fail(key: str, message: str) -> DefinitionError:
        return DefinitionError(f"{prefix}, key {key}: {message}")

    errors = list(jsonschema.Draft202012Validator(SCHEMA).iter_errors(table))
    if errors:
        err = errors[0]
        key = ".".join(map(str, err.absolute_path)) or "(table)"
        raise DefinitionError(f"{prefix}, key {key}: {schema_message(err)}")
    for key in ("basis", "seed", "recursion", "bernstein_at", "degree_offset"):
        if key in table:
            raise fail(
                key,
                "a family whose parameter is the length of the domain or sits inside sin/cos "
                "is defined by an explicit `functions` list (and no `" + key + "`)",
            )
    if "functions" not in table:
        raise fail("functions", "required: b_0 .. b_n as formulas in t and the parameter")
    if "parameters" in table and len(table["parameters"]) != 1:
        raise fail(
            "parameters",
            "a family whose parameter is the length of the domain or sits inside sin/cos has "
            f"one parameter, got {len(table['parameters'])}",
        )
    if ("parameter" in table) == ("parameters" in table):
        raise fail("parameter", 'name the parameter with `parameter = "alpha"`')
    (name,) = _names(table)
    if name in ("t", "pi", "sin", "cos", "sinh", "cosh", "exp"):
        raise fail("parameter", f"{name!r} is taken by the formula language")
    rng = table["range"]
    if isinstance(rng, dict):
        if set(rng) != {name}:
            raise fail("range", f"an interval for the parameter {name!r} only")
        rng = rng[name]
    lo, hi, lo_closed, hi_closed = parse_range(rng, "range", fail)
    degree_text = table["degrees"].strip()
    if not degree_text.isdigit():
        raise fail("degrees", 'an explicit list of functions is one order: degrees = "n"')
    degree = int(degree_text)
    if len(table["functions"]) != degree + 1:
        raise fail(
            "functions",
            f"the basis of degree {degree} has {degree + 1} functions, "
            f"got {len(table['functions'])}",
        )
    dom = table.get("domain", "[0, 1]").strip()
    dm = _RANGE.match(dom)
    if not dm or dm.group(1) != "[" or dm.group(4) != "]" or dm.group(2).strip() != "0":
        raise fail("domain", f'{dom!r}: "[0, {name}]" or "[0, 1]" (with sin({name}*t))')
    end = dm.group(3).strip()
    if end == name:
        form = "domain"
    elif end == "1":
        form = "unit"
    else:
        words = re.findall(r"[A-Za-z_][A-Za-z0-9_]*", end)
        stray = [w for w in words if w not in (name, "pi")]
        if stray:
            raise fail("domain", f"{dom!r}: {stray[0]!r} is not the family's parameter ({name})")
        raise fail("domain", f'{dom!r}: "[0, {name}]" or "[0, 1]" (with sin({name}*t))')
    alpha = sp.Symbol(name)
    functions = []
    kinds: set[str] = set()
    for idx, text in enumerate(table["functions"]):
        key = f"functions[{idx}]"
        try:
            expr = parse_formula(
                text, {"t": T, name: alpha}, {}, elementary=True, frequency=(name,)
            )
        except ParseError as exc:
            raise fail(key, str(exc)) from None
        extra = sorted(s.name for s in expr.free_symbols if s not in (T, alpha))
        if extra:
            raise fail(key, f"unknown symbol {extra[0]!r} (a formula in t and {name})")
        elem, kind = to_atoms(expr, alpha, form, lambda msg, key=key: fail(key, msg))
        kinds |= kind
        functions.append(elem)
    if kinds == {"trig", "hyp"}:
        raise fail("functions", "trigonometric and hyperbolic functions together")
    hyperbolic = kinds == {"hyp"}
    if not any(k != (POW, 0) and k[0] != POW for f in functions for k in f) and form == "unit":
        raise fail("functions", f"no sin({name}*t) or cos({name}*t): a polynomial basis")
    return CDefinition(
        name=table["name"],
        title=table.get("title", ""),
        parameter=name,
        range_text=rng.strip(),
        lo=lo,
        hi=hi,
        lo_closed=lo_closed,
        hi_closed=hi_closed,
        form=form,
        hyperbolic=hyperbolic,
        functions_texts=tuple(table["functions"]),
        functions=tuple(tuple(sorted(normal(f, hyperbolic).items())) for f in functions),
        digest=digest(table),
        domain_text=dom,
    )


def angle_base(expr: sp.Expr, alpha: sp.Symbol, form: str) -> int:
    """L, the least common denominator of the multiples of alpha inside sin/cos/sinh/cosh of
    expr (1 when they are integers): a claim with cos(alpha/2) is decided in
    Q(alpha, sin(alpha/L), cos(alpha/L)), which holds the family's field through
    sin(alpha) = sin(L theta), cos(alpha) = cos(L theta) (`angle`)."""
    base = 1
    for call in expr.atoms(*_TRIG, *_HYP):
        arg = sp.expand(call.args[0])
        if form == "unit":
            arg = sp.expand(arg.subs(T, T / alpha))
        b = arg.coeff(alpha, 1).subs(T, 0) if arg.has(alpha) else sp.Integer(0)
        if b.is_Rational:
            base = int(sp.ilcm(base, int(b.q)))
    return base


def to_atoms(
    expr: sp.Expr, alpha: sp.Symbol, form: str, fail, base: int = 1
) -> tuple[Elem, set[str]]:
    """The parsed function in atoms of t on [0, alpha] with coefficients in (A, S, C); with
    base L > 1 (a record's claim, `angle_base`), S and C stand for sin(alpha/L), cos(alpha/L)
    and an argument's multiple of alpha may be any multiple of 1/L."""
    kinds: set[str] = set()
    E = sp.Symbol("E_")  # e^(i t) (trigonometric) or e^t (hyperbolic)

    def split(arg: sp.Expr) -> tuple[int, int]:
        """arg = a*t + b*alpha in the family's [0, alpha] t: (a, L*b), integers."""
        arg = sp.expand(arg)  # alpha*(1 - t) is alpha - alpha*t: its rate is read below
        if form == "unit":  # u on [0, 1]: alpha*u is the t of [0, alpha]
            if arg.has(T) and not sp.expand(arg.coeff(T)).has(alpha):
                raise fail(f"{arg}: on [0, 1] the rate of t is a multiple of {alpha}")
            arg = sp.expand(arg.subs(T, T / alpha))
        poly = sp.Poly(arg, T, alpha)
        a, b = poly.coeff_monomial(T), poly.coeff_monomial(alpha) * base
        if set(poly.monoms()) - {(1, 0), (0, 1)} or not (a.is_Integer and b.is_Integer):
            raise fail(
                f"the argument {arg} is not an integer multiple of t (of {alpha}*t on [0, 1]) "
                f"plus an integer multiple of {alpha}"
                + (f" or of {alpha}/{base}" if base > 1 else "")
            )
        if abs(a) > MAX_HARMONIC or abs(b) > MAX_HARMONIC * base:
            raise fail(f"the argument {arg}: a multiple larger than {MAX_HARMONIC}")
        return int(a), int(b)

    def rewrite(call: sp.Expr) -> sp.Expr:
        a, b = split(call.args[0])
        trig = isinstance(call, _TRIG)
        kinds.add("trig" if trig else "hyp")
        cb, sb = angle(b, not trig)  # cos(b alpha), sin(b alpha) in C, S
        z = E**a
        if trig:
            ca, sa = (z + 1 / z) / 2, (z - 1 / z) / (2 * sp.I)
            # cos(x + y) = cos x cos y - sin x sin y; sin(x + y) = sin x cos y + cos x sin y
            return ca * cb - sa * sb if isinstance(call, sp.cos) else sa * cb + ca * sb
        ca, sa = (z + 1 / z) / 2, (z - 1 / z) / 2
        return ca * cb + sa * sb if isinstance(call, sp.cosh) else sa * cb + ca * sb

    calls = sorted(expr.atoms(*_TRIG, *_HYP, sp.exp), key=str)
    for call in calls:
        if isinstance(call, sp.exp):
            raise fail(f"{call}: write exp through sinh and cosh in this kind of family")
    body = expr.xreplace({call: rewrite(call) for call in calls})
    if form == "unit":
        body = body.subs(T, T / alpha)
    body = body.subs(alpha, A)
    if body.has(sp.pi):
        raise fail("pi enters only the range")
    num, den = sp.fraction(sp.together(body))
    den_terms = sp.Poly(den, E).terms() if den.has(E) else [((0,), den)]
    if den.has(T) or len(den_terms) != 1:
        raise fail("a division by a function of t")
    (top,), den = den_terms[0]  # den = E^top * (a function of alpha)
    out: Elem = {}
    poly = sp.Poly(sp.expand(num), T, E)
    for (k, e), coeff in poly.terms():
        coeff = coeff / den
        m = e - top
        if k and m:
            raise fail(f"t**{k} times a trigonometric or hyperbolic function is not decided here")
        if k > MAX_POWER:
            raise fail(f"the power t**{k} is larger than {MAX_POWER}")
        if m == 0:
            add_into(out, (POW, k), coeff)
        elif abs(m) > MAX_HARMONIC:
            raise fail(f"a harmonic {abs(m)} larger than {MAX_HARMONIC}")
        elif "trig" in kinds:  # c e^(imt) = c cos(mt) + i c sin(mt)
            add_into(out, (COS, abs(m)), coeff)
            add_into(out, (SIN, abs(m)), sp.I * coeff * (1 if m > 0 else -1))
        else:  # c e^(mt) = c cosh(mt) + c sinh(mt)
            add_into(out, (COS, abs(m)), coeff)
            add_into(out, (SIN, abs(m)), coeff * (1 if m > 0 else -1))
    elem: Elem = {}
    for atom, v in out.items():
        v = sp.expand(v)  # the i of e^(imt) and e^(-imt) cancels: a real coefficient
        if v.has(sp.I):
            raise fail("a coefficient that is not real")  # pragma: no cover - real input
        elem[atom] = v
    return elem, kinds


def fraction_of(x: sp.Expr) -> Fraction:
    return Fraction(int(x.p), int(x.q))
