"""End values and derivatives in closed form in n for families in several parameters over a
range of degrees and for indexed families (issue #30).

A one-parameter family gets its end forms by fitting a polynomial in n through the degrees of
its range (engine.py). Here the forms are *derived* for a general n from the ``basis`` formula
itself, and the derivation is the proof:

1. Vanishing orders. The basis formula b(i, n, t) is read as a product and sum of factors, and
   a lower bound of its order of vanishing at t = 0 is computed for a symbolic i: it must be
   i + c0 (t**i (1 - t)**(n - i) ... gives i). Then b_i^(r)(0) = 0 for r <= 3 and every
   i > 3 - c0, at every degree. The same at t = 1, where the bound must be n - i + c1.
2. The ends. For each remaining index, i = j (start) or i = n - j (end) with j a number, the
   formula is a function of t, n and the parameters. Binomials are decided with the papers'
   convention for every n from a bound on (binomial(n - 1, 2) is a polynomial in n for
   n >= 1; binomial(0, n - 2) is 0 for n >= 3); an indexed parameter lam(k) becomes an
   index-relative symbol, ``lam(2)`` near the start or ``lam(n-1)`` near the end, or 0 where
   the index lies outside the family's indices for every n from a bound on. The r-th
   derivative at the end is then exact symbolic differentiation in t, with n a symbol.
   Every bound met on the way is recorded: the forms hold for every n >= ``proven_from``.
3. Small degrees. Below ``proven_from``, each degree from the start of the range is checked
   one by one against its own basis (the per-degree expansion); ``valid_from[r]`` is the
   least degree from which the forms of orders 0..r hold at every degree.
4. A fit, as the one-parameter engine does it (a polynomial in n per parameter monomial
   through all but the last two of at least five degrees from ``proven_from`` on, the last
   two held out), must give the derived forms exactly.

A family defined by a seed and a recursion, or by a list of functions, has no formula in n:
it is left per degree, with a reason.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache
from math import comb, factorial

import sympy as sp

from ..algebra import n as _n
from .definition import _I, _N, _T, ENDPOINT_ORDERS, Definition, DefinitionError, _expand
from .engine import basis_polys
from .indexed import _parse_indexed

_BIN = sp.Function("Bin")  # binomials kept apart while i is substituted (no auto-evaluation)


class NoProof(Exception):
    """The basis formula is outside what the derivation in general n decides."""


@dataclass(frozen=True)
class ClosedForms:
    """End values and derivatives d^r b_j (start, at t = 0) and d^r b_(n-j) (end, at 1), as
    polynomials in n and the parameter symbols (index-relative for an indexed family)."""

    forms: dict  # {(end, r, j): expr}
    symbols: tuple[sp.Symbol, ...]  # the parameter symbols the forms may use, in order
    proven_from: int  # the symbolic derivation holds for every n >= this
    valid_from: tuple[int, ...]  # [r]: orders 0..r hold at every n >= this
    checked: tuple[int, ...]  # the degrees checked one by one


def relative_name(base: str, k: int, from_end: bool) -> str:
    """The document's name of an index-relative parameter: lam(2), lam(n), lam(n-1)."""
    if not from_end:
        return f"{base}({k})"
    return f"{base}(n)" if k == 0 else f"{base}(n-{k})"


class _General:
    """The basis at one index i = j or n - j, with n a symbol, and the bounds on n met."""

    def __init__(self, defn: Definition):
        self.defn = defn
        self.spec = defn.indexed
        self.bounds: list[int] = [1]
        self.used: set[str] = set()

    def formula(self) -> sp.Expr:
        if self.defn.basis_text is None:
            raise NoProof(
                "the basis is given by a seed and a recursion or a list of functions, not by "
                "one formula in i and n"
            )
        if self.spec is not None:
            expr = _parse_indexed(self.defn.basis_text, self.spec.name)
        else:
            expr = self.defn.basis
        return expr.replace(sp.binomial, lambda a, b: _BIN(a, b))

    def _affine(self, e: sp.Expr, what: str) -> tuple[int, int]:
        """(a, c) with e = a n + c, integers."""
        p = sp.Poly(sp.expand(e), _N) if e.free_symbols <= {_N} else None
        if p is None or p.degree() > 1 or not all(x.is_Integer for x in p.all_coeffs()):
            raise NoProof(f"{what} {e} is not an integer multiple of n plus an integer")
        coeffs = p.all_coeffs()
        return (int(coeffs[0]), int(coeffs[1])) if p.degree() == 1 else (0, int(coeffs[-1]))

    def _binomial(self, a: sp.Expr, b: sp.Expr) -> sp.Expr:
        (na, ca), (nb, cb) = self._affine(a, "binomial top"), self._affine(b, "binomial bottom")
        if na == nb == 0:
            return sp.Integer(comb(ca, cb) if 0 <= cb <= ca else 0)
        if nb == 0:  # binomial(n + c, k)
            if cb < 0:
                return sp.Integer(0)
            if na != 1:
                raise NoProof(f"binomial({a}, {b})")
            self.bounds.append(-ca)  # a >= 0: the falling factorial is the paper's value
            return sp.expand(sp.ff(_N + ca, cb) / factorial(cb))
        if na == 0:  # binomial(A, n + c) = 0 once n + c > A
            if nb != 1:
                raise NoProof(f"binomial({a}, {b})")
            self.bounds.append(ca - cb + 1)
            return sp.Integer(0)
        if na == nb == 1:  # binomial(n + c1, n + c2) = binomial(n + c1, c1 - c2) for n + c2 >= 0
            k = ca - cb
            if k < 0:
                return sp.Integer(0)
            self.bounds.append(-cb)
            return sp.expand(sp.ff(_N + ca, k) / factorial(k))
        raise NoProof(f"binomial({a}, {b})")

    def _parameter(self, index: sp.Expr) -> sp.Expr:
        spec = self.spec
        assert spec is not None
        a, c = self._affine(index, f"the index of {spec.name}")
        if a == 0:
            if c < spec.first:
                return sp.Integer(0)
            self.bounds.append(c + spec.last_offset)
            name = relative_name(spec.name, c, False)
        elif a == 1:
            if -c < spec.last_offset:
                return sp.Integer(0)
            self.bounds.append(spec.first - c)
            name = relative_name(spec.name, -c, True)
        else:
            raise NoProof(f"{spec.name}({index})")
        self.used.add(name)
        return sp.Symbol(name)

    def at(self, expr: sp.Expr, index: sp.Expr) -> sp.Expr:
        e = expr.xreplace({_I: index})
        if self.spec is not None:
            e = e.replace(
                lambda x: isinstance(x, sp.core.function.AppliedUndef) and x.func != _BIN,
                lambda x: self._parameter(x.args[0]),
            )
        e = e.replace(_BIN, self._binomial)
        for p in e.atoms(sp.Pow):  # symbolic exponents: nonnegative from a bound on
            if p.exp.has(_N):
                a, c = self._affine(p.exp, "an exponent")
                if a != 1:
                    raise NoProof(f"the exponent {p.exp}")
                self.bounds.append(-c)
        return e

    def derivative(self, e: sp.Expr, r: int, at: int) -> sp.Expr:
        value = sp.expand(sp.diff(e, _T, r).subs(_T, at))
        if value.has(_T) or value.has(sp.zoo, sp.nan, sp.oo) or not value.is_polynomial(_N):
            raise NoProof(f"the derivative {r} at t = {at} is {value}, not a polynomial in n")
        for p in value.atoms(sp.Pow):
            if p.exp.has(_N):
                raise NoProof(f"the derivative {r} at t = {at} keeps {p}")
        return value


def _order(e: sp.Expr) -> sp.Expr:
    """A lower bound of the order of vanishing of e at t = 0, affine in i and n."""
    if not e.has(_T):
        return sp.Integer(0)
    if e == _T:
        return sp.Integer(1)
    if e.is_Pow:
        base, ex = e.args
        if ex.has(_T):
            raise NoProof(f"{e}: t in an exponent")
        if base == _T:
            return ex
        at0 = base.subs(_T, 0)
        if at0.is_Number and at0 != 0:
            return sp.Integer(0)
        if ex.is_Integer and ex >= 0:
            return _order(base) * ex
        raise NoProof(f"{e}: a power that may vanish at the end")
    if e.is_Mul:
        return sp.Add(*(_order(a) for a in e.args))
    if e.is_Add:
        orders = [_order(a) for a in e.args]
        low = orders[0]
        for o in orders[1:]:
            gap = sp.expand(o - low)
            if not gap.is_Integer:
                raise NoProof(f"{e}: terms vanish to orders {low} and {o}")
            low = o if gap < 0 else low
        return low
    raise NoProof(f"{e}: not a product or sum of powers")


def _offset(order: sp.Expr, lead: sp.Expr, where: str) -> int:
    c = sp.expand(order - lead)
    if not c.is_Integer:
        raise NoProof(f"the basis vanishes to order {order} at t = {where}, not {lead} + c")
    return int(c)


def _derive(defn: Definition) -> tuple[dict, int, tuple[str, ...]]:
    g = _General(defn)
    expr = g.formula()
    c0 = _offset(_order(expr), _I, "0")
    c1 = _offset(_order(expr.xreplace({_T: 1 - _T})), _N - _I, "1")
    forms = {}
    for end, c, at in (("start", c0, 0), ("end", c1, 1)):
        last = ENDPOINT_ORDERS - c  # b_i^(r) vanishes at this end for every i beyond it
        for j in range(max(last, -1) + 1):
            e = g.at(expr, sp.Integer(j) if end == "start" else _N - j)
            for r in range(ENDPOINT_ORDERS + 1):
                value = g.derivative(e, r, at)
                if value != 0:
                    forms[(end, r, j)] = value
                    g.bounds.append(j)  # b_j (b_(n-j)) exists
    return forms, max(g.bounds), tuple(sorted(g.used))


def _per_degree(defn: Definition, degree: int) -> dict:
    """The end values of the degree's own basis, in the forms' symbols."""
    if defn.indexed is None:
        polys = basis_polys(defn, degree)
        rename: tuple[dict, dict] = ({}, {})
    else:

        def fail(key: str, message: str) -> DefinitionError:
            return DefinitionError(f"[family] {defn.name}, key {key}: {message}")

        at = _expand(defn, degree, fail)
        polys = basis_polys(at, degree)
        spec = defn.indexed
        idx = spec.indices(degree)
        rename = tuple(  # type: ignore[assignment]
            {
                sp.Symbol(spec.symbol_name(k)): sp.Symbol(
                    relative_name(spec.name, degree - k if side else k, bool(side))
                )
                for k in idx
            }
            for side in (0, 1)
        )
    out = {}
    for i, p in enumerate(polys):
        q = p.as_expr()
        for r in range(ENDPOINT_ORDERS + 1):
            for end, at_, j, ren in (("start", 0, i, rename[0]), ("end", 1, degree - i, rename[1])):
                v = sp.expand(q.subs(_T, at_).xreplace(ren))
                if v != 0:
                    out[(end, r, j)] = v
            q = sp.diff(q, _T)
    return out


def _absent(defn: Definition, symbols: tuple[sp.Symbol, ...], degree: int) -> dict:
    """{symbol: 0} for the index-relative symbols with no index at this degree (lam(3) at
    n = 2 reads as 0, the papers' convention)."""
    spec = defn.indexed
    if spec is None:
        return {}
    out = {}
    for s in symbols:
        inner = s.name[len(spec.name) + 1 : -1]
        k = degree - int(inner[2:] or 0) if inner.startswith("n") else int(inner)
        if k not in spec.indices(degree):
            out[s] = sp.Integer(0)
    return out


def _agree(forms: dict, table: dict, degree: int, order: int, absent: dict) -> bool:
    """The forms at n = degree are the degree's own end values (an entry of an index beyond
    the degree must vanish)."""
    keys = {k for k in (*forms, *table) if k[1] <= order}
    return all(
        sp.expand(forms.get(k, sp.Integer(0)).subs(_n, degree).xreplace(absent) - table.get(k, 0))
        == 0
        for k in keys
    )


def _fit(defn: Definition, forms: dict, start: int, symbols: tuple[sp.Symbol, ...]) -> None:
    """The one-parameter engine's fit (all degrees but the last two, the last two held out),
    per parameter monomial, from the per-degree values at n = start, start + 1, ...: it must
    give the derived forms."""
    gens = (_n, *symbols)
    width = max((sp.Poly(v, *gens).degree(_n) for v in forms.values()), default=0)
    degrees = list(range(start, start + max(5, width + 3)))
    tables = [_per_degree(defn, deg) for deg in degrees]
    for key in sorted({k for t in tables for k in t} | set(forms)):
        got = sp.Integer(0)
        # a basis its parameters never enter has no symbols: one dummy generator, degree 0
        plain = symbols or (sp.Dummy("one"),)
        polys = [sp.Poly(t.get(key, sp.Integer(0)), *plain) for t in tables]
        for mono in sorted({m for p in polys for m in p.monoms()}):
            ys = [p.coeff_monomial(mono) for p in polys]
            fit = sp.interpolate(list(zip(degrees[:-2], ys[:-2], strict=True)), _n)
            if any(fit.subs(_n, x) != y for x, y in zip(degrees[-2:], ys[-2:], strict=True)):
                raise AssertionError(f"{defn.name}: the fit of {key} misses the held-out degrees")
            got += fit * sp.Mul(*(s**e for s, e in zip(plain, mono, strict=True)))
        if sp.expand(got - forms.get(key, sp.Integer(0))) != 0:
            raise AssertionError(f"{defn.name}: the fit of {key} is not the derived form")


def closed_forms(defn: Definition) -> ClosedForms | str:
    """The end forms in closed form in n, derived for a general n and checked below the bound
    of the derivation; a reason (str) where there are none."""
    return _closed_forms(defn)


@cache
def _closed_forms(defn: Definition) -> ClosedForms | str:
    if not defn.several or defn.elementary:
        return "closed forms in n of a one-parameter family are the engine's (engine.py)"
    if len(defn.degrees) == 1:
        return "a family of one order (its document has the weights at that order)"
    try:
        derived, proven, used = _derive(defn)
    except NoProof as exc:
        return f"no closed forms in n: {exc}"
    forms = {key: v.xreplace({_N: _n}) for key, v in derived.items()}  # the solve's n
    symbols = tuple(sp.Symbol(x) for x in used) if defn.indexed is not None else defn.symbols
    low = defn.degrees.start
    checked = tuple(range(low, max(defn.degrees.stop, proven)))
    valid = []
    try:  # degrees below the range or up to proven_from may not be the family's degrees
        tables = {deg: _per_degree(defn, deg) for deg in checked}
    except DefinitionError as exc:
        return f"no closed forms in n: a degree the check needs is not defined ({exc})"
    for r in range(ENDPOINT_ORDERS + 1):
        bad = [
            deg
            for deg in checked
            if not _agree(forms, tables[deg], deg, r, _absent(defn, symbols, deg))
        ]
        if any(deg >= proven for deg in bad):
            raise AssertionError(f"{defn.name}: the derived forms fail at n = {bad[-1]}")
        valid.append(max(bad) + 1 if bad else low)
    try:
        _fit(defn, forms, max(valid[-1], proven), symbols)  # every symbol has its index there
    except DefinitionError as exc:
        return f"no closed forms in n: a degree the fit needs is not defined ({exc})"
    return ClosedForms(forms, symbols, proven, tuple(valid), checked)
