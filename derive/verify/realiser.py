"""Evaluation ("realising"). A parsed expression is evaluated for concrete degrees and indices by
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

This module holds the walk (``Realiser``) and the comparison of printed and derived values.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from fractions import Fraction
from functools import lru_cache
from math import comb, factorial

import sympy as sp
from sympy.core.function import AppliedUndef

from ..grammar import MAX_EXPONENT, MAX_FACTORIAL, SYMBOLS
from .compare import (
    dotsum_integral,
)
from .expr_parse import (
    MAX_SUM_TERMS,
    POINT_LIKE,
    fn_name,
    paper_binomial,
)
from .scalar import (
    GEN,
    ONE,
    ZERO,
    LimitError,
    Sc,
    Undefined,
    _q,
    as_int,
)
from .values import (
    DotSum,
    is_scalar,
    trivially_zero,
    v_add,
    v_apply,
    v_mul,
    v_pow,
)

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
