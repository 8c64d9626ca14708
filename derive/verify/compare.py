"""Comparing a printed value with the derived one (exactly, with the diff a report shows),
and lazy dot products: integrals of dot products of polynomial curves in t, reduced to
quadratic forms in the control points without expanding every term.
"""

from __future__ import annotations

from fractions import Fraction
from functools import cache, lru_cache
from math import gcd

import flint
import sympy as sp

from ..grammar import SYMBOLS
from .scalar import (
    _GPOS,
    _NVARS,
    PARAMS,
    ZERO,
    Sc,
    _degree,
    _integral_between,
    _is_zero,
    _lcm,
    _nz,
    _poly,
    simplify_scalar,
)
from .values import (
    DotSum,
    Form,
    Rad,
    Ratio,
    Wedge,
    is_scalar,
    trivially_zero,
    v_add,
    v_mul,
    v_neg,
)

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
