"""The context of one record's check (its family, the models of the undefined functions)
and the per-degree loop every equation checker shares.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, field, replace
from functools import cache, lru_cache

import sympy as sp

from ..algebra import bernstein as bz
from ..families.registry import REFERENCE
from .checks_core import (
    LAM,
    SLAM,
    ST,
    Outcome,
    S,
    T,
    claim_kind,
    is_param,
)
from .claim_families import (
    FAMILIES,
    Family,
    _bernstein_mats,
    family_basis,
)
from .compare import (
    compare,
    equal,
)
from .expr_parse import (
    DEGREE_SYMBOLS,
    INDEX_SYMBOLS,
    as_sympy,
    fn_name,
    parse,
)
from .realiser import (
    Realiser,
    delta_model,
)
from .scalar import (
    GEN,
    Sc,
    Undefined,
    as_int,
)
from .values import (
    Form,
    cross,
    dot,
    norm,
    v_add,
    v_apply,
    v_div,
    v_mul,
    v_neg,
)

# --------------------------------------------------------------------------- context, models


_int = as_int


@lru_cache(maxsize=64)
def _piece_text(points: str, degree: str, shape: str) -> tuple:
    """(points, degree symbol name, shape) of one curve of a join record, parsed once (the
    per-degree join check asks for it hundreds of times)."""
    return points, str(parse(degree)), parse(shape)


@dataclass
class Context:
    record: dict
    family: Family

    @staticmethod
    def of(record: dict) -> Context:
        family = FAMILIES[record["family"]]
        if record.get("point_function"):  # a records file may name its control points
            family = replace(family, points=record["point_function"])
        return Context(record, family)

    # ---- models

    def realiser(self, extra: dict | None = None) -> Realiser:
        fam = self.family
        pts = fam.points
        models: dict = {
            "B": lambda a, env: family_basis(REFERENCE, _int(a[1]), _int(a[0]), a[2]),
            "b": self._b_model,
            "f": self._f_model,
            "a": self._a_model,
            "p": lambda a, env: self.curve(env, a[0]),
            "p1": lambda a, env: self.piece(1, env, a[0]),
            "p2": lambda a, env: self.piece(2, env, a[0]),
            "A": self._a_split_model,
            "Q": lambda a, env: self.qw(env, _int(a[0]))[0],
            "W": lambda a, env: self.qw(env, _int(a[0]))[1],
            "F": lambda a, env: self.fg(env, a[0])[0],
            "G": lambda a, env: self.fg(env, a[0])[1],
            "bk": lambda a, env: self.casteljau(
                "b", self.casteljau_param(), _int(a[0]), _int(a[1])
            ),
            "Vl": lambda a, env: self.casteljau("V", T, _int(a[0]), _int(a[1])),
            "Ql": lambda a, env: self.cubic_points(env, _int(a[0]), _int(a[1])),
            "kappa": lambda a, env: self.curvature(env, a[0]),
            "dot": lambda a, env: _dot(a[0], a[1]),
            "cross": lambda a, env: cross(a[0], a[1]),
            "norm": lambda a, env: norm(a[0]),
        }
        for name in ("P", "V", "P1", "P2", "V1", "V2"):
            models[name] = lambda a, env, name=name: Form.point(name, _int(a[0]))
        if pts == "b":
            models["b"] = lambda a, env: (
                Form.point("b", _int(a[0])) if len(a) == 1 else self._b_model(a, env)
            )
        extra = extra or {}
        models.update(extra)
        jets = {
            "p": lambda order, x, env: self.curve_jet(env, order, x),
            "p1": lambda order, x, env: self.piece_jet(1, order, x, env),
            "p2": lambda order, x, env: self.piece_jet(2, order, x, env),
        }
        # a checker's own model for p, p1 or p2 is not the curve the jets know
        jets = {k: v for k, v in jets.items() if k not in extra}
        return Realiser(models, {"Delta": delta_model}, jets)

    def _b_model(self, a, env):
        if len(a) == 1:
            return Form.point("b", _int(a[0]))
        fam = self.family.name
        if fam == REFERENCE:
            raise TypeError("b(i, n, t) is not defined for the Bézier notes")
        shape = a[3] if len(a) == 4 else None
        return family_basis(fam, _int(a[1]), _int(a[0]), a[2], shape)

    def _f_model(self, a, env):
        i, deg = _int(a[0]), _int(a[1])
        if deg < 0 or not 0 <= i <= deg:
            raise Undefined(f"f({i}, {deg})")
        return _original(deg, i).subs(T, a[2])

    def _a_model(self, a, env):
        """Relative vectors of Bézier's original form: b_0 = a_0, b_j = b_{j-1} + a_j."""
        i = _int(a[0])
        if i < 0:
            raise Undefined(f"a({i})")
        if i == 0:
            return Form.point("b", 0)
        return v_add(Form.point("b", i), v_neg(Form.point("b", i - 1)))

    def _a_split_model(self, a, env):
        """A_i^n with b_i^n = B_i^n + (1 - λ) A_i^n."""
        i, deg = _int(a[0]), _int(a[1])
        b = family_basis(self.family.name, deg, i)
        B = family_basis(REFERENCE, deg, i)
        diff = b - B
        if diff.is_zero():
            return Sc.of(0)
        quo, rem = divmod(diff.num, (1 - SLAM).num)
        if rem or diff.pden is not None:
            raise AssertionError("b - B is not divisible by 1 - lam")
        return Sc(quo, diff.den).subs(T, a[2])

    def degree(self, env, sym="n") -> int:
        n = env.get(S[sym])
        if n is None:
            if sym == "n" and "n" in self.record:
                return int(self.record["n"])
            raise TypeError(f"degree {sym} is not fixed")
        return _int(n)

    def curve(self, env, x, points=None, deg_sym="n", shape=None) -> Form:
        if isinstance(x, Sc) and x.c is not None:
            hit = self.curve_jet(env, 0, x, points, deg_sym, shape)
            if hit is not None:
                return hit
        n = self.degree(env, deg_sym)
        points = points or self.family.points
        skey = _shape_key(shape)
        if skey is _UNSHARED:
            c = v_apply(_curve(self.family.name, n, points), lambda s: s.subs(LAM, shape))
        else:
            c = _curve_at_shape(self.family.name, n, points, skey)
        if not is_param(x, T):
            c = v_apply(c, lambda s: s.subs(T, x))
        return c

    def curve_jet(self, env, order: int, x: Sc, points=None, deg_sym="n", shape=None):
        """The order-th t-derivative of the curve at the number x (shared by every record of
        the run), or None for a shape that is an expression."""
        skey = _shape_key(shape)
        if skey is _UNSHARED:
            return None
        n = self.degree(env, deg_sym)
        return _curve_jet(self.family.name, n, points or self.family.points, skey, order, x.c)

    def _piece_spec(self, which: int, env):
        """(points, degree symbol, shape) of curve `which` of a join record."""
        first = self.record.get("first")
        second = self.record.get("second")
        if first and second:
            spec = first if which == 1 else second
            spec = _piece_text(spec["points"], spec["degree"], spec["shape"])
        else:  # the paper's convention (000 eq. 17: p1 degree m; 001 eq. 12: C_1 degree n)
            pts, deg = self.family.points, self.family.join_degrees[which - 1]
            spec = (f"{pts}{which}", deg, S[f"lam{which}"])
        shape = env[spec[2]] if spec[2] in env else spec[2]  # a sample value, or symbolic
        return spec[0], spec[1], Sc.of(shape)

    def _subdivision(self) -> bool:
        """p1, p2 of 002 are the two pieces of a subdivision at t*, unless the record is a join
        (which names its two curves in `first` and `second`)."""
        return self.family.name == REFERENCE and not self.record.get("first")

    def piece(self, which: int, env, x) -> Form:
        if self._subdivision():  # the two pieces of a subdivision at t*
            ts = Sc(GEN[S["tstar"]])
            arg = ts * x if which == 1 else 1 - (1 - ts) * (1 - x)
            return self.curve(env, arg)
        return self.curve(env, x, *self._piece_spec(which, env))

    def piece_jet(self, which: int, order: int, x: Sc, env):
        if self._subdivision():
            return None  # a piece of a subdivision is the curve at a composed parameter
        return self.curve_jet(env, order, x, *self._piece_spec(which, env))

    def casteljau_param(self):
        return parse(self.record["at"]) if self.record.get("at") else T

    def casteljau(self, name, s, j, k) -> Form:
        if j < 0 or k < 0:
            raise Undefined(f"{name}_{j}^{k}")
        return _casteljau(name, s, j, k)

    def cubic_points(self, env, i, level) -> Form:
        """Q_i^l of Prop. 8: l = n-2 the cubic Bézier points of the cubic λ-curve on
        V_0^{n-3}..V_3^{n-3} (from the derived cubic Bernstein matrix), then de Casteljau."""
        n = self.degree(env)
        if level < n - 2:
            raise Undefined(f"Q^{level} below n - 2")
        if level == n - 2:
            if not 0 <= i <= 3:
                raise Undefined(f"Q_{i}^(n-2)")
            mats = _bernstein_mats(self.family.name, 3)
            out = sp.Integer(0)
            for q in range(4):
                coeff = sum((SLAM**p * mats[p][q][i] for p in range(len(mats))), Sc.of(0))
                out = v_add(out, v_mul(coeff, self.casteljau("V", T, q, n - 3)))
            return out
        left = self.cubic_points(env, i, level - 1)
        right = self.cubic_points(env, i + 1, level - 1)
        return v_add(v_mul(1 - ST, left), v_mul(ST, right))

    def qw(self, env, i) -> tuple[Form, Form]:
        """Q_i, W_i: the curve's Bernstein control points are Q_i - λ W_i with Q, W λ-free."""
        n = self.degree(env)
        if not 0 <= i <= n:
            raise Undefined(f"Q_{i}, W_{i} for n = {n}")
        return _qw(self.family.name, n, self.family.points)[i]

    def fg(self, env, x) -> tuple[Form, Form]:
        """f, g of eq. 19: p^(k) = f - λ g with f, g λ-free, so f = p^(k)|λ=0, g = -∂p^(k)/∂λ."""
        k = _int(env[S["k"]])
        f, g = _fg(self.family.name, self.degree(env), k, self.family.points)
        if not is_param(x, T):
            f, g = (v_apply(v, lambda s: s.subs(T, x)) for v in (f, g))
        return f, g

    def curvature(self, env, s):
        c = self.curve(env, ST)
        d1 = v_apply(c, lambda e: e.diff(T).subs(T, s))
        d2 = v_apply(c, lambda e: e.diff(T, 2).subs(T, s))
        return v_div(norm(cross(d1, d2)), v_mul(norm(d1), v_mul(norm(d1), norm(d1))))


@cache
def _fg(family: str, n: int, k: int, points: str) -> tuple[Form, Form]:
    pk = v_apply(_curve(family, n, points), lambda s: s.diff(T, k))
    return v_apply(pk, lambda s: s.subs(LAM, 0)), v_apply(pk, lambda s: -s.diff(LAM))


def _dot(a, b):
    return dot(a, b)


@cache
def _original(deg: int, i: int) -> Sc:
    return Sc.from_qq_poly(bz.original_basis(deg, i, bz.X))


@cache
def _curve(family: str, n: int, points: str) -> Form:
    terms = {}
    for i in range(n + 1):
        terms[((points, i),)] = family_basis(family, n, i)
    return Form(terms)


_UNSHARED = object()


def _shape_key(shape):
    """A hashable key for a curve's shape: None for λ itself, a number, another parameter's
    symbol, or _UNSHARED for an expression."""
    if shape is None or is_param(shape, LAM):
        return None
    if shape.c is not None:
        return shape.c
    symbol = shape.generator()
    return _UNSHARED if symbol is None else symbol


@cache
def _curve_at_shape(family: str, n: int, points: str, shape) -> Form:
    """The curve with λ replaced by `shape` (a key of _shape_key)."""
    c = _curve(family, n, points)
    if shape is None:
        return c
    value = Sc(GEN[shape]) if isinstance(shape, sp.Symbol) else Sc.of(shape)
    return v_apply(c, lambda s: s.subs(LAM, value))


@cache
def _curve_jet(family: str, n: int, points: str, shape, order: int, x) -> Form:
    """d^order/dt^order of the curve of degree n at t = x, λ replaced by `shape`."""
    c = _curve_at_shape(family, n, points, shape)
    if order:
        c = v_apply(c, lambda s: s.diff(T, order))
    return v_apply(c, lambda s: s.subs(T, Sc.of(x)))


@cache
def _casteljau(name, s, j, k) -> Form:
    if k == 0:
        return Form.point(name, j)
    ss = Sc(GEN[s])
    left, right = _casteljau(name, s, j, k - 1), _casteljau(name, s, j + 1, k - 1)
    return v_add(v_mul(1 - ss, left), v_mul(ss, right))


@cache
def _qw(family: str, n: int, points: str) -> tuple[tuple[Form, Form], ...]:
    mats = _bernstein_mats(family, n)
    if len(mats) > 2:
        raise AssertionError("Bernstein control points are not linear in λ")
    out = []
    for i in range(n + 1):
        q = Form({((points, v),): Sc.of(mats[0][v][i]) for v in range(n + 1)})
        w = Form(
            {((points, v),): Sc.of(-mats[1][v][i] if len(mats) > 1 else 0) for v in range(n + 1)}
        )
        out.append((q, w))
    return tuple(out)


# --------------------------------------------------------------------------- per-degree loop


def index_ranges(record: dict) -> dict:
    """Quantifier ranges of the free index symbols, as (lo, hi) expressions in n (README: the
    printed domains; the default is 0..n)."""
    kind = claim_kind(record["claim"])
    if kind.startswith("energy"):
        return {S["k"]: (1, 3)}
    if kind == "geometric_step":
        return {S["l"]: (0, S["n"] + 1), S["i"]: (0, S["n"] + 1)}
    if kind == "original_to_bernstein":  # printed: j = 1, 2, ..., n
        return {S["j"]: (1, S["n"])}
    return {}


def _where(eq: dict) -> dict:
    out = {}
    for name, spec in (eq.get("where") or {}).items():
        lo, hi = spec.split("..")
        out[S[name]] = (parse(lo), parse(hi))
    return out


def instances(record: dict, ctx: Context, exprs, eq: dict | None = None):
    """Every environment {n (, m), index: value} the equation is checked for."""
    eq = eq or {}
    free = set().union(*(e.free_symbols for e in exprs))
    given = {S[k]: parse(v) for k, v in (eq.get("given") or {}).items()}
    deg_syms = [d for d in DEGREE_SYMBOLS if d in free or (d == S["n"] and _needs_n(exprs))]
    if not deg_syms and "n" not in record and free & set(INDEX_SYMBOLS):
        # indices range over 0..n without n itself appearing: the largest degree covers the
        # ranges of all smaller ones
        deg_syms = [S["n"]]
        given.setdefault(S["n"], sp.Integer(max(ctx.family.degrees)))
    deg_lists = []
    for d in deg_syms:
        if d in given:
            deg_lists.append([int(given[d])])
        elif d == S["n"] and "n" in record:
            deg_lists.append([int(record["n"])])
        else:
            deg_lists.append(list(ctx.family.degrees))
    if S["k"] not in free and any(
        fn_name(a) in ("F", "G") for e in exprs for a in sp.preorder_traversal(e)
    ):
        free.add(S["k"])  # f, g of eq. 19 depend on the derivative order k
    idx_syms = [s for s in INDEX_SYMBOLS if s in free]
    ranges = {**index_ranges(record), **_where(eq)}
    for degs in itertools.product(*deg_lists):
        env = {d: sp.Integer(v) for d, v in zip(deg_syms, degs, strict=True)}
        n_val = env.get(S["n"], sp.Integer(record.get("n", 0)))
        lists = []
        for s in idx_syms:
            if s in given:
                lists.append([int(given[s])])
                continue
            lo, hi = ranges.get(s, (0, S["n"]))
            lo = int(as_sympy(lo).subs(S["n"], n_val))
            hi = int(as_sympy(hi).subs(S["n"], n_val))
            lists.append(range(lo, hi + 1))
        for idx in itertools.product(*lists):
            yield {**env, **{s: sp.Integer(v) for s, v in zip(idx_syms, idx, strict=True)}}


def _needs_n(exprs) -> bool:
    """p(t), F, G, Q, W, Ql, kappa depend on the degree n without printing it."""
    implicit = {"p", "F", "G", "Q", "W", "Ql", "kappa", "E", "p1", "p2"}
    return any(fn_name(a) in implicit for e in exprs for a in sp.preorder_traversal(e))


def env_str(env: dict) -> str:
    return ", ".join(f"{k}={v}" for k, v in sorted(env.items(), key=lambda kv: str(kv[0])))


@dataclass
class Tally:
    """Failures of one comparison over its instances, summarised into one diff line."""

    label: str
    total: int = 0
    skipped: int = 0
    failures: list = field(default_factory=list)

    def add(self, env, diffs):
        self.total += 1
        if diffs:
            self.failures.append((env, diffs))

    def lines(self) -> list[str]:
        if not self.failures:
            return []
        env, diffs = self.failures[0]
        # an equation with no free degree or index (b(0, 3, t) = …) is checked once, as printed
        where = env_str(env) or "the printed values"
        more = ""
        if len(self.failures) > 1:
            listed = "; ".join(env_str(e) for e, _ in self.failures[1:5])
            extra = len(self.failures) - 5
            more = f" (fails in {len(self.failures)} of {self.total} cases; also {listed}"
            more += f"; +{extra} more)" if extra > 0 else ")"
        return [f"{self.label}: at {where}: " + "; ".join(diffs[:3]) + more]


def atomic(e) -> bool:
    """A left side naming one derived object (so it is 'derived' and the right 'printed')."""
    if fn_name(e) is not None or e.is_Symbol:
        return True
    if isinstance(e, (sp.Subs, sp.Derivative, sp.Integral)):
        return atomic(e.args[0])
    return False


def check_equation(record, ctx, eq, real: Realiser, label: str, tally_out: list) -> None:
    lhs, rhs = parse(eq["lhs"]), parse(eq["rhs"])
    tally = Tally(
        f"{label} `{eq['lhs']} = {eq['rhs']}`"
        if len(eq["rhs"]) < 90
        else f"{label} `{eq['lhs']} = …`"
    )
    names = ("derived", "printed") if atomic(lhs) else ("left", "right")
    why = ""  # the last reason an instance could not be evaluated
    for env in instances(record, ctx, (lhs, rhs), eq):
        try:
            left = real(lhs, env)
            right = real(rhs, env)
        except Undefined as exc:
            tally.skipped += 1
            why = str(exc)
            continue
        # the degree a record fixes (`n = 3`) locates an instance whose env is otherwise empty
        where = env or ({S["n"]: sp.Integer(record["n"])} if "n" in record else {})
        if tally.failures:  # details only for the first failing case
            tally.add(where, ["differs"] if not equal(right, left) else [])
            continue
        diffs = compare(right, left)
        diffs = [d.replace("printed", names[1]).replace("derived", names[0]) for d in diffs]
        tally.add(where, diffs)
    if tally.total == 0:  # nothing compared: never a verdict
        raise ValueError(
            f"{label} could be checked at no degree or index: every case left a term undefined"
            + (f" (e.g. {why})" if why else "")
        )
    tally_out.append(tally)


def equations_outcome(record, ctx, equations, real=None, extra_lines=()) -> Outcome:
    real = real or ctx.realiser()
    tallies: list[Tally] = []
    for pos, eq in enumerate(equations):
        check_equation(record, ctx, eq, real, f"equation {pos + 1}", tallies)
    diffs = list(extra_lines) + [line for t in tallies for line in t.lines()]
    checked = [f"{t.label.split(' `')[0]}: {t.total} cases" for t in tallies]
    return Outcome("mismatch" if diffs else "match", diffs, checked)


def _solve_linear(lhs, rhs, x):
    """The x with lhs = rhs when lhs - rhs is linear in x, else None. (By hand: sp.solve
    imports sympy.physics on first use, half a second of a verify worker.)"""
    diff = sp.expand(lhs - rhs)
    slope = diff.coeff(x, 1)
    if slope == 0 or sp.expand(diff - slope * x).has(x):
        return None
    return sp.cancel(-(diff - slope * x) / slope)
