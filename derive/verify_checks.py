"""Claim checkers: each published record compared with OUR derivation.

The derived side always comes from the derive modules (each family's ``basis_polys`` and
``closed_end_forms``, ``bernstein.bernstein_basis``, ``original_basis``, ``endpoint_weights``,
the Bernstein/power matrices, and ``energy``); nothing printed is re-typed here. A paper's
own closed forms (000's three-term form, 001's explicit form) are checked by the module its
family's definition names under ``checks`` (derive/verify_same_degree.py, ...).

Every undefined function of the expression language has a *model*: the derived object it names
(``b`` the family's basis polynomials, ``p`` the curve Σ b_i P_i, ``bk`` de Casteljau points,
``Q``/``W`` the λ-free parts of the curve's Bernstein control points, ``F``/``G`` the λ-free
parts of p^(k), ``A`` = (b - B)/(1 - λ), ``kappa`` the curvature |p' × p''|/|p'|^3, ...). An
equation ``lhs = rhs`` is then checked for every degree of the family's range and every index
(``per-degree``), and, where derive has a general-n closed form, symbolically in n (and i, k).

Registry: ``CHECKERS[kind] = [Checker(function, requires, family), ...]``; a checker with a
family is that family's own (a paper's closed form no generic rule gives), registered by the
module its derive/families/<name>.toml names under ``checks``. ``requires`` names derive modules a
checker needs (REQUIREMENTS lists the functions each must provide); while one is missing the
record's verdict is ``pending`` with the reason. The energy checkers use ``derive/energy.py``
(issue 3), the join checkers ``derive/joins.py`` (issue 4); a new claim kind plugs in as one
function registered with ``@checker(kind, requires=...)``.

Per-degree ranges: the family's degrees (derive's DEGREES); indices 0..n unless
``index_ranges`` or an equation's ``where`` says otherwise; an instance whose evaluation leaves
the definitions (a degree outside the range, a negative order) is skipped, and an equation
checked for no instance is an error. Join formulas, which involve two degrees, are checked
symbolically in n, m and, per degree, for every degree of each curve against the smallest and
the largest of the other (and equal degrees), at exact sample values of λ1, λ2, α, d.
"""

from __future__ import annotations

import importlib
import itertools
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from fractions import Fraction
from functools import cache, lru_cache
from math import comb

import flint
import sympy as sp
from sympy.core.function import AppliedUndef
from sympy.solvers.inequalities import reduce_rational_inequalities

from . import _algebra
from . import bernstein as bz
from .family_engine import REFERENCE, builtin_families
from .verify_expr import (
    DEGREE_SYMBOLS,
    GEN,
    INDEX_SYMBOLS,
    POINT_LIKE,
    SYMBOLS,
    Form,
    Ratio,
    Realiser,
    Sc,
    Undefined,
    _is_zero,
    _NotRational,
    _proportional_pairs,
    as_fraction,
    as_int,
    as_sympy,
    compare,
    cross,
    delta_model,
    equal,
    fast_factor,
    fn_name,
    norm,
    parse,
    show,
    symbolic_delta,
    v_add,
    v_apply,
    v_div,
    v_is_zero,
    v_mul,
    v_neg,
)

S = SYMBOLS
T, LAM = S["t"], S["lam"]
ST, SLAM = Sc(GEN[T]), Sc(GEN[LAM])


def is_param(x, sym) -> bool:
    """x is exactly the parameter `sym` (so no substitution is needed)."""
    return isinstance(x, Sc) and x.c is None and x.den == 1 and x.pden is None and x.num == GEN[sym]


# --------------------------------------------------------------------------- outcomes


class Pending(Exception):
    """A derivation this record needs does not exist yet."""


@dataclass
class Outcome:
    verdict: str  # "match" | "mismatch" | "pending"
    diffs: list[str] = field(default_factory=list)
    checked: list[str] = field(default_factory=list)  # what was compared, for the report


@dataclass
class Checker:
    fn: Callable[[dict, Context], Outcome]
    requires: tuple[str, ...] = ()
    family: str | None = None  # only this family's records (its paper's own form), else any
    fits: Callable[[dict], bool] | None = None  # the records it checks, by their payload


CHECKERS: dict[str, list[Checker]] = {}  # kind -> its checkers, in registration order

# Missing derivations: module -> (functions that must exist, what to say while missing).
REQUIREMENTS = {
    "energy": (
        ("energy_forms", "published_form", "optimal_lambda_exact"),
        "needs the energy derivation derive/energy.py (energy_forms, published_form, "
        "optimal_lambda_exact; issue 3)",
    ),
    "joins": (
        ("solve",),
        "needs the join derivation derive/joins.py (C1/C2/G1/G2 vertex formulas; issue 4)",
    ),
}


def checker(
    *kinds: str,
    requires: tuple[str, ...] = (),
    family: str | None = None,
    fits: Callable[[dict], bool] | None = None,
    only: str | None = None,
):
    """Register fn for each claim kind. `family`: fn checks that family's records only (the
    other families' records of the kind go to the shared checkers); `fits`: which records of
    the kind it takes; `only`: the kind exists for `family` alone, with this reason."""

    def register(fn):
        for kind in kinds:
            if "." in kind:
                raise AssertionError(f"{kind}: a checker is registered for a bare kind")
            entry = Checker(fn, requires, family, fits)
            CHECKERS.setdefault(kind, []).append(entry)
            if only is not None:
                assert family is not None, "a kind for one family names it"
                KIND_FAMILIES[kind] = ((family,), only)
        return fn

    return register


def derive_module(name: str):
    """The sibling derive module `name` (derive/<name>.py), or None when it does not exist."""
    try:
        return importlib.import_module(f"{__package__}.{name}")
    except ModuleNotFoundError as exc:
        if exc.name and exc.name.endswith(f".{name}"):
            return None
        raise


def missing_requirement(requires: tuple[str, ...]) -> str | None:
    for name in requires:
        funcs, reason = REQUIREMENTS[name]
        module = derive_module(name)
        if module is None or any(not hasattr(module, f) for f in funcs):
            return reason
    return None


def claim_kind(claim: str) -> str:
    """`<family>.endpoint_d1` -> `endpoint_d1` (a kind is family-independent)."""
    return claim.split(".", 1)[1] if "." in claim else claim


# Kinds whose derivation exists for some families only, with the reason a user is told;
# LAMBDA stands for every family with a shape parameter (every family but the reference
# Bernstein basis). A family's own kinds are added by its checks module (checker(only=...)).
LAMBDA = "*"
_LAMBDA_FAMILIES = (LAMBDA,)
KIND_FAMILIES: dict[str, tuple[tuple[str, ...], str]] = {
    **{
        kind: (_LAMBDA_FAMILIES, "it is about the λ-basis b(i, n, t), which bezier does not have")
        for kind in ("basis_general", "basis_explicit", "basis_list", "basis_in_bernstein")
    },
    **{
        kind: (_LAMBDA_FAMILIES, "the classical Bézier curve has no shape parameter to optimise")
        for kind in (
            "energy_definition",
            "energy_functional",
            "energy_lambda",
            "energy_lambda_nk",
            "energy_matrix",
            "energy_example",
            "energy_split",
            "energy_qw",
            "energy_derivative",
        )
    },
}


def kinds() -> dict[str, tuple[str, ...]]:
    """Every claim kind with the families it is defined for."""
    out = {}
    for claim in CHECKERS:
        kind = claim_kind(claim)
        out[kind] = _allowed(kind)
    return dict(sorted(out.items()))


def _allowed(kind: str) -> tuple[str, ...]:
    allowed = KIND_FAMILIES.get(kind, ((), ""))[0]
    if not allowed:
        return tuple(FAMILIES)
    if LAMBDA in allowed:
        return tuple(f for f in FAMILIES if f != REFERENCE)
    return allowed


def kind_problem(family: str, kind: str) -> str | None:
    """Why `family.kind` cannot be checked (None when it can)."""
    if family not in FAMILIES:
        return (
            f"unknown family {family!r} (known: {', '.join(FAMILIES)}; a family defined in a "
            "file of its own is given to verify with the records: "
            "`lambda-bezier verify FAMILY.toml RECORDS.toml`)"
        )
    if kind not in kinds():
        return f"unknown claim kind {kind!r} (see the records format for the list)"
    reason = KIND_FAMILIES.get(kind, ((), ""))[1]
    allowed = _allowed(kind)
    if family not in allowed:
        return f"claim kind {kind!r} is defined for {', '.join(allowed)} only: {reason}"
    return None


def resolve_checker(record: dict) -> Checker:
    """The checker of a record's claim: its own family's where one is registered and takes the
    record, else the first shared one for that kind that does (an endpoint kind by its payload:
    cases or equations), else the per-degree check of an explicit form of the basis."""
    claim, family = record["claim"], record["family"]
    kind = claim_kind(claim)
    problem = kind_problem(family, kind)
    if problem:
        raise KeyError(problem)
    candidates = [c for c in CHECKERS.get(kind, []) if _fits(c, record)]
    for wanted in (family, None):
        for entry in candidates:
            if entry.family == wanted:
                return entry
    # an explicit form of another family's basis: every degree and index, per degree
    return next(c for c in CHECKERS["basis_general"] if c.family is None)


def _fits(entry: Checker, record: dict) -> bool:
    """Endpoint kinds come as `cases` (per index) or as `equations` (of the curve); joins
    with or without a stated convention."""
    if entry.fits is not None:
        return entry.fits(record)
    if entry.fn.__name__ == "check_cases":
        return "cases" in record
    if entry.fn.__name__ == "check_endpoint_equations":
        return "equations" in record
    # a join states its continuity condition (001's convention); one without it is a paper's
    # own condition (000's Prop. 9, registered with its family)
    if entry.fn.__name__ == "check_join":
        return "convention" in record
    return True


def run_checker(record: dict) -> Outcome:
    entry = resolve_checker(record)
    reason = missing_requirement(entry.requires)
    if reason is not None:
        return Outcome("pending", [reason])
    try:
        return entry.fn(record, Context.of(record))
    except Pending as exc:
        return Outcome("pending", [str(exc)])


# --------------------------------------------------------------------------- families


@dataclass(frozen=True)
class Family:
    name: str
    degrees: range
    points: str  # name of the control-point function in this paper's records
    basis_polys: Callable[[int], list] | None = None  # per degree, Polys in t, lam
    offset: int = 0  # the basis polynomials have degree n + offset
    closed: Callable[[], dict] | None = None  # closed end forms {(end, r, idx): expr in n, lam}
    # degree symbols of p1, p2 in a join record that does not name its curves (the paper's)
    join_degrees: tuple[str, str] = ("n", "m")
    closed_order: int = 2  # closed end forms exist for derivative orders 0..closed_order


def _builtin_family(b) -> Family:
    module = b.module()
    return Family(
        b.name,
        module.DEGREES,
        b.points,
        lambda degree: list(module.basis_polys(degree)),
        b.definition.offset,
        module.closed_end_forms,
        b.join_degrees,
    )


# The built-in families (derive/families/*.toml, in order), then the reference Bernstein basis
# (002's notes: no shape parameter, no b(i, n, t); its control points are b_i).
FAMILIES = {b.name: _builtin_family(b) for b in builtin_families()}
FAMILIES[REFERENCE] = Family(REFERENCE, bz.DEGREES, "b")


def register_family(family: Family) -> None:
    """A family defined by data (derive/family_engine.py) joins the built-in ones for this run:
    its records are checked with the same checkers (the derivations it has: no closed form of
    its own where the engine found none)."""
    FAMILIES[family.name] = family
    for fn in (_basis_sc, closed_forms, _bernstein_mats):
        fn.cache_clear()


@cache
def _bernstein_sc(degree: int, index: int) -> Sc:
    return Sc.of(comb(degree, index)) * ST**index * (1 - ST) ** (degree - index)


@cache
def _basis_sc(family: str, degree: int, index: int) -> Sc:
    """The derived basis polynomial (a Poly in t, lam) as a scalar of the evaluator."""
    polys = FAMILIES[family].basis_polys(degree)  # type: ignore[misc]
    return Sc.from_qq_poly(polys[index])


def family_basis(family: str, degree: int, index: int, x=None, shape=None) -> Sc:
    """The derived basis function at x (default t) with shape `shape` (default lam); zero
    outside 0..degree, Undefined for a degree outside the derived range."""
    x = ST if x is None else Sc.of(x)
    if family == REFERENCE:
        if degree < 0:
            raise Undefined(f"Bernstein degree {degree}")
        if not 0 <= index <= degree:
            return Sc.of(0)
        if is_param(x, T):
            return _bernstein_sc(degree, index)
        return Sc.of(comb(degree, index)) * x**index * (1 - x) ** (degree - index)
    if degree not in FAMILIES[family].degrees:
        raise Undefined(f"{family} degree {degree} outside {FAMILIES[family].degrees}")
    if not 0 <= index <= degree:
        return Sc.of(0)
    e = _basis_sc(family, degree, index)
    if shape is not None and not is_param(shape, LAM):
        e = e.subs(LAM, shape)
    if not is_param(x, T):
        e = e.subs(T, x)
    return e


@cache
def closed_forms(family: str) -> dict:
    """{(end, r, idx): value} in the derive symbols: derivative of order r of basis function idx
    (start) or n - idx (end) at t = 0 / t = 1; absent keys are zero."""
    closed = FAMILIES[family].closed
    forms = None if closed is None else closed()
    if forms is None:
        raise KeyError(f"{family} has no closed end forms")
    return forms


def has_closed_forms(family: str, order: int = 0) -> bool:
    """The family has its end derivatives of order `order` (and below) in closed form in n."""
    try:
        closed_forms(family)
    except KeyError:
        return False
    return order <= FAMILIES[family].closed_order


@cache
def bezier_weights():
    return bz.endpoint_weights()


def bezier_closed(end: str, r: int, idx) -> sp.Expr:
    w_start, w_end = bezier_weights()
    if not 0 <= idx <= r:
        return sp.Integer(0)
    w = w_start if end == "start" else w_end
    return w.subs({_algebra.k: r, _algebra.i: idx})


# derive's symbols carry integer assumptions: the parsed ones are mapped onto them
TO_DERIVE = {
    S["n"]: _algebra.n,
    S["m"]: _algebra.m,
    S["i"]: _algebra.i,
    S["j"]: _algebra.j,
    S["k"]: _algebra.k,
}


def to_derive(e):
    return e.xreplace(TO_DERIVE)


def symbolic_zero(e) -> bool:
    e = to_derive(as_sympy(e))
    if e == 0:
        return True
    try:  # a rational function (the common case): exact ring arithmetic decides
        return not as_fraction(e)[0]
    except (_NotRational, Undefined):
        pass
    if _nonzero_at_sample(e):  # a proof that it is not identically zero, without simplify
        return False
    e = sp.combsimp(sp.expand_func(e))
    if e == 0:
        return True
    try:  # a rational function: exact ring arithmetic decides
        return not as_fraction(e)[0]
    except _NotRational:
        return sp.simplify(e) == 0


# A generic point (degrees above orders above indices, parameters at unrelated rationals) at
# which symbolic_zero evaluates an expression exactly before trying to simplify it.
_SAMPLE_POINT = {
    **{
        _algebra.n: sp.Integer(17),
        _algebra.m: sp.Integer(13),
        _algebra.k: sp.Integer(7),
        _algebra.j: sp.Integer(4),
        _algebra.i: sp.Integer(3),
        S["l"]: sp.Integer(6),
        S["r"]: sp.Integer(5),
    },
    **{
        S[name]: sp.Rational(p, q)
        for name, p, q in (
            ("t", 2, 7),
            ("u", 3, 11),
            ("x", 5, 13),
            ("c", 7, 17),
            ("tstar", 4, 19),
            ("lam", 3, 23),
            ("lam1", 5, 29),
            ("lam2", -7, 31),
            ("alpha", 9, 37),
            ("beta", 11, 41),
            ("d", -13, 43),
            ("C", 15, 47),
            ("omega", 17, 53),
        )
    },
}


def _nonzero_at_sample(e) -> bool:
    """True when e has a finite nonzero exact value at _SAMPLE_POINT (other integer symbols,
    such as summation indices, at 2): then it is not identically zero. False says nothing."""
    values = {}
    for sym in e.free_symbols:
        if sym in _SAMPLE_POINT:
            values[sym] = _SAMPLE_POINT[sym]
        elif sym.is_integer:
            values[sym] = sp.Integer(2)
        else:
            return False
    value = e.xreplace(values)
    return bool(value.is_Rational) and value != 0


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
    from .verify_expr import dot

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
def _bernstein_mats(family: str, n: int):
    fam = FAMILIES[family]
    return _algebra.bernstein_matrices(list(fam.basis_polys(n)), n + fam.offset)  # type: ignore[misc]


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
    for env in instances(record, ctx, (lhs, rhs), eq):
        try:
            left = real(lhs, env)
            right = real(rhs, env)
        except Undefined:
            tally.skipped += 1
            continue
        # the degree a record fixes (`n = 3`) locates an instance whose env is otherwise empty
        where = env or ({S["n"]: sp.Integer(record["n"])} if "n" in record else {})
        if tally.failures:  # details only for the first failing case
            tally.add(where, ["differs"] if not equal(right, left) else [])
            continue
        diffs = compare(right, left)
        diffs = [d.replace("printed", names[1]).replace("derived", names[0]) for d in diffs]
        tally.add(where, diffs)
    if tally.total == 0:
        raise AssertionError(f"{record['id']}: {label} was checked for no instance")
    tally_out.append(tally)


def equations_outcome(record, ctx, equations, real=None, extra_lines=()) -> Outcome:
    real = real or ctx.realiser()
    tallies: list[Tally] = []
    for pos, eq in enumerate(equations):
        check_equation(record, ctx, eq, real, f"equation {pos + 1}", tallies)
    diffs = list(extra_lines) + [line for t in tallies for line in t.lines()]
    checked = [f"{t.label.split(' `')[0]}: {t.total} cases" for t in tallies]
    return Outcome("mismatch" if diffs else "match", diffs, checked)


# --------------------------------------------------------------------------- generic claims


@checker(
    "basis_general",
    "recursion",
    "basis_list",
    "basis_in_bernstein",
    "curve_definition",
    "energy_split",
    "energy_qw",
    "energy_derivative",
    "join_setup",
    "original_curve",
    "original_basis",
    "original_basis_list",
    "original_to_bernstein",
    "bernstein_definition",
    "bernstein_list",
    "partition_of_unity",
    "symmetry",
    "bernstein_derivative",
    "degree_elevation",
    "subdivision_identity",
    "integral",
    "power_to_bernstein",
    "bernstein_to_power",
    "endpoint_interpolation",
    "decasteljau",
    "decasteljau_intermediate",
    "hodograph",
    "end_curvature",
    "derivative_decasteljau",
    "derivative_decasteljau_example",
    "subdivision",
)
def check_equations(record: dict, ctx: Context, extra_lines=()) -> Outcome:
    """Every printed equality, for every degree of the range and every index, with the models
    (`extra_lines`: a family checker's own findings, e.g. a symbolic comparison)."""
    eqs = list(record["equations"]) + list(record.get("conventions") or [])
    return equations_outcome(record, ctx, eqs, extra_lines=extra_lines)


def _orig(e) -> str:
    return str(e.xreplace({v: k for k, v in TO_DERIVE.items()}))


def _from_derive(e):
    return e.xreplace({v: k for k, v in TO_DERIVE.items()})


# --------------------------------------------------------------------------- endpoint cases


def _index_bounds(text: str):
    if text == "otherwise":
        return None
    if ".." in text:
        lo, hi = text.split("..")
        return parse(lo), parse(hi)
    e = parse(text)
    return e, e


def _generic_le(a, b) -> bool:
    """a <= b for every large n (a, b linear in n)."""
    d = sp.expand(b - a)
    c = d.coeff(S["n"])
    return c > 0 or (c == 0 and d.subs(S["n"], 0) >= 0)


@checker("endpoint_values", "endpoint_d1", "endpoint_d2")
def check_cases(record: dict, ctx: Context) -> Outcome:
    """By-index results (eqs. 8-11 of 000/001, B(0), B(1) of 002): every printed case against
    the derived closed forms symbolically, and every index 0..n of every degree against the
    derived derivative, including indices the printed cases do not cover."""
    func = parse(record["function"])
    var = S[record.get("variable", "t")]
    at = parse(record["at"])
    order = int(record["order"])
    end = "start" if at == 0 else "end"
    cases = [(_index_bounds(c["index"]), parse(c["value"]), c) for c in record["cases"]]
    fam = ctx.family.name if fn_name(func) == "b" else REFERENCE
    diffs = symbolic_cases(fam, end, order, cases)
    real = ctx.realiser()
    tally = Tally("per-degree")
    n = S["n"]
    for deg in ctx.family.degrees:
        env0 = {n: sp.Integer(deg)}
        covered: dict = {}
        for bounds, value, case in cases:
            if bounds is None:
                continue
            lo = as_int(real(bounds[0], env0))
            hi = as_int(real(bounds[1], env0))
            for ii in range(max(lo, 0), min(hi, deg) + 1):
                covered.setdefault(ii, []).append((value, case))
        rest = [(v, c) for b, v, c in cases if b is None]
        for ii in range(deg + 1):
            env = {**env0, S[record["index"]]: sp.Integer(ii)}
            val = real(func, env)
            want = val.diff(var, order).subs(var, Sc.of(at))
            hits = covered.get(ii) or rest
            row = []
            if not hits:
                row.append(f"index {ii} is not covered by any printed case (derived {show(want)})")
            if len(hits) > 1:
                first, *others = (real(v, env) for v, _ in hits)
                if any(not _is_zero(first - other) for other in others):
                    values = {show(first), *map(show, others)}
                    row.append(
                        f"index {ii} is covered by cases with different values {sorted(values)}"
                    )
            for v, c in hits[:1]:
                got = real(v, env)
                if not _is_zero(got - want):
                    row.append(f"case `{c['index']}`: printed {show(got)}, derived {show(want)}")
            tally.add(env, row)
    diffs += tally.lines()
    checked = [
        "symbolic: cases vs derived closed forms"
        if fam == REFERENCE or has_closed_forms(fam, order)
        else f"symbolic: none ({fam} has no closed end forms in n of order {order})",
        f"per-degree: {tally.total} cases",
    ]
    return Outcome("mismatch" if diffs else "match", diffs, checked)


def symbolic_cases(family: str, end: str, order: int, cases) -> list[str]:
    n = S["n"]
    if family == REFERENCE:
        keys = {(end, order, idx): bezier_closed(end, order, idx) for idx in range(order + 1)}
    elif not has_closed_forms(family, order):
        return []  # a family without general-n end forms: checked per degree only
    else:
        keys = {key: v for key, v in closed_forms(family).items() if key[:2] == (end, order)}
    keys = {k: v for k, v in keys.items() if v != 0}

    def index_of(idx):
        return sp.Integer(idx) if end == "start" else n - idx

    def covers(bounds, index) -> bool:
        lo, hi = bounds
        return _generic_le(lo, index) and _generic_le(index, hi)

    diffs = []
    explicit = [(b, v, c) for b, v, c in cases if b is not None]
    other = [(b, v, c) for b, v, c in cases if b is None]
    for key, derived in sorted(keys.items(), key=str):
        index = index_of(key[2])
        hits = [(v, c) for b, v, c in explicit if covers(b, index)] or [(v, c) for _, v, c in other]
        if not hits:
            diffs.append(f"symbolic: index {index} (derived {sp.factor(derived)}) is not covered")
            continue
        for v, c in hits:
            if not symbolic_zero(v - _from_any(derived)):
                diffs.append(
                    f"symbolic: case `{c['index']}`: printed {v}, derived "
                    f"{sp.factor(sp.combsimp(derived))}"
                )
    # explicit single-index cases whose derived value is zero
    for b, v, c in explicit:
        if b[0] != b[1]:
            continue
        index = b[0]
        offset = sp.expand(index if end == "start" else n - index)
        if not offset.is_Integer:
            continue
        if (end, order, int(offset)) not in keys and not symbolic_zero(v):
            diffs.append(f"symbolic: case `{c['index']}`: printed {v}, derived 0")
    return diffs


def _from_any(e):
    return _from_derive(e)


# --------------------------------------------------------------------------- endpoint curves


def _endpoint_lhs(lhs):
    """(end, order) of p(0), p(1), Subs(Derivative(p(t), (t, r)), t, 0/1); else None."""
    if fn_name(lhs) == "p" and lhs.args[0] in (0, 1):
        return ("start" if lhs.args[0] == 0 else "end"), sp.Integer(0)
    if isinstance(lhs, sp.Subs) and isinstance(lhs.expr, sp.Derivative):
        d = lhs.expr
        if fn_name(d.expr) == "p" and len(d.variable_count) == 1:
            point = lhs.point[0]
            return ("start" if point == 0 else "end"), d.variable_count[0][1]
    return None


def symbolic_endpoint(family: str, eq: dict) -> list[str]:
    """p^(r)(0) / p^(r)(1) printed as a combination of control points vs the closed forms."""
    lhs, rhs = parse(eq["lhs"]), parse(eq["rhs"])
    which = _endpoint_lhs(lhs)
    if which is None or (family != REFERENCE and not has_closed_forms(family)):
        return []  # not an end value, or a family checked per degree only
    end, order = which
    n = S["n"]
    rhs = symbolic_delta(rhs)
    if not order.is_Integer or rhs.has(sp.Sum):
        return symbolic_endpoint_sum(family, end, order, lhs, rhs, eq)
    order = int(order)
    if family != REFERENCE and not has_closed_forms(family, order):
        return []  # this order has no general-n form: checked per degree only
    pts = {a for a in sp.preorder_traversal(rhs) if fn_name(a) in ("P", "V", "b")}
    coeffs = sp.collect(sp.expand(rhs), list(pts), evaluate=False) if pts else {}
    printed = {}
    for p_app, c in coeffs.items():
        if p_app == 1:
            if c != 0:
                return [f"symbolic: `{eq['lhs']}`: printed has a term {c} without a point"]
            continue
        off = sp.expand(p_app.args[0] if end == "start" else n - p_app.args[0])
        printed[int(off)] = printed.get(int(off), 0) + c
    derived = {}
    for idx in range(order + 2):
        if family == REFERENCE:
            v = bezier_closed(end, order, idx)
        else:
            v = closed_forms(family).get((end, order, idx), 0)
        if v != 0:
            derived[idx] = _from_derive(v)
    diffs = []
    for idx in sorted(set(printed) | set(derived)):
        a, b = (
            as_sympy(printed.get(idx, 0)),
            as_sympy(derived.get(idx, 0)),
        )
        if not symbolic_zero(a - b):
            name = f"{idx}" if end == "start" else f"n - {idx}" if idx else "n"
            diffs.append(
                f"symbolic: `{eq['lhs']}`: coefficient of point {name}: printed "
                f"{sp.factor(a)}, derived {sp.factor(sp.combsimp(b))}"
            )
    return diffs


def symbolic_endpoint_sum(family, end, order, lhs, rhs, eq) -> list[str]:
    """A printed C·Σ_{v=lo}^{hi} c(v)·point(e(v)) with a symbolic order, against the Bézier
    weights: reindexed by s (point s at t=0, point n - s at t=1)."""
    if family != REFERENCE:
        return []
    n = S["n"]
    sums = [a for a in sp.preorder_traversal(rhs) if isinstance(a, sp.Sum)]
    if len(sums) != 1:
        return []
    s_ = sums[0]
    outer = sp.Mul(*[a for a in sp.Mul.make_args(rhs) if a != s_])
    if outer.has(sp.Sum) or any(fn_name(a) for a in sp.preorder_traversal(outer)):
        return []
    (v, lo, hi), body = s_.limits[0], s_.function
    pts = [a for a in sp.preorder_traversal(body) if fn_name(a) == "b"]
    if len(pts) != 1:
        return []
    pt = pts[0]
    coeff = body / pt
    s = sp.Symbol("s", integer=True, nonnegative=True)
    index = pt.args[0]
    target = s if end == "start" else n - s
    vs = _solve_linear(index, target, v)
    if vs is None:
        return []
    c_s = (outer * coeff).subs(v, vs)
    ends = [_solve_linear(vs, lo, s), _solve_linear(vs, hi, s)]
    if None in ends:
        return []
    bounds = sorted((sp.expand(e) for e in ends), key=str)
    w_start, w_end = bezier_weights()
    w = (w_start if end == "start" else w_end).subs(_algebra.i, s)
    w = _from_derive(w).subs(S["k"], order)
    diffs = []
    if set(bounds) != {sp.Integer(0), order}:
        diffs.append(
            f"symbolic: `{eq['lhs']}`: summation covers points {bounds}, derived 0..{order}"
        )
    if not symbolic_zero(to_derive(c_s - w)):
        name = "s" if end == "start" else "n - s"
        diffs.append(
            f"symbolic: `{eq['lhs']}`: weight of point {name}: printed {c_s}, "
            f"derived {sp.factor(w)}"
        )
    return diffs


@checker("endpoint_curve", "endpoint_d1", "endpoint_d2", "endpoint_dk", "endpoint_dr_delta")
def check_endpoint_equations(record: dict, ctx: Context) -> Outcome:
    """End points and end derivatives of the curve: symbolically against the closed forms
    (eq. 4 of 001; the Bernstein endpoint weights for 002) and per degree."""
    extra = []
    for eq in record["equations"]:
        extra += symbolic_endpoint(ctx.family.name, eq)
    out = equations_outcome(record, ctx, record["equations"], extra_lines=extra)
    fam = ctx.family.name
    out.checked.insert(
        0,
        "symbolic: vs derived endpoint closed forms"
        if fam == REFERENCE or has_closed_forms(fam)
        else f"symbolic: none ({fam} has no closed end forms in n)",
    )
    return out


# --------------------------------------------------------------------------- geometric ratio


# --------------------------------------------------------------------------- cubic matrix


@checker("cubic_matrix")
def check_cubic_matrix(record: dict, ctx: Context) -> Outcome:
    n = int(record["n"])
    row = [parse(x) for x in record["row"]]
    pts = [parse(x) for x in record["points"]]
    mat = record["matrix"]
    real = ctx.realiser()
    env = {S["n"]: sp.Integer(n)}
    printed = sp.Integer(0)
    for r, rv in enumerate(row):
        for c, pv in enumerate(pts):
            printed = v_add(printed, v_mul(real(rv, env) * mat[r][c], real(pv, env)))
    derived = real(parse("p(t)"), env)
    diffs = compare(printed, derived)
    if (
        diffs
        and all(row[e] == T**e for e in range(n + 1))
        and all(pts[c] == sp.Function("b")(c) for c in range(n + 1))
    ):
        power = _algebra.bernstein_power_matrix(n)  # power[j][e]: coefficient of t^e in B_j
        diffs = [
            f"entry [{e}][{j}] (t^{e}, b{j}): printed {mat[e][j]}, derived {power[j][e]}"
            for e in range(n + 1)
            for j in range(n + 1)
            if Fraction(mat[e][j]) != power[j][e]
        ]
    return Outcome("mismatch" if diffs else "match", diffs, ["p(t) = row·M·points vs Σ b_j B_j"])


# --------------------------------------------------------------------------- Bernstein maximum


@checker("bernstein_maximum")
def check_maximum(record: dict, ctx: Context) -> Outcome:
    func = parse(record["function"])
    arg = parse(record["argmax"])
    var = S[record.get("variable", "u")]
    real = ctx.realiser()
    tally = Tally("per-degree")
    for deg in ctx.family.degrees:
        for ii in range(deg + 1):
            env = {S["n"]: sp.Integer(deg), S["i"]: sp.Integer(ii)}
            value = real(func, env)
            a = sp.Rational(str(real(arg, env).ground()))
            f = value.univariate(var)
            if f is not None:  # exact in FLINT when every critical point is rational
                f = flint.fmpq_poly([flint.fmpq(c.numerator, c.denominator) for c in f])
                roots = _rational_roots(f.derivative())
            if f is None or roots is None:
                f = sp.Poly(value.to_expr(), var)
                roots = f.diff(var).real_roots()
            cands = {sp.Integer(0), sp.Integer(1)} | {r for r in roots if 0 <= r <= 1}
            at_value = {c: _poly_at(f, c) for c in cands}
            best = max(at_value.values())
            row = []
            if not (0 <= a <= 1) or _poly_at(f, a) != best:
                at = sorted(c for c in cands if at_value[c] == best)
                row.append(f"printed maximum at {a}, derived at {', '.join(map(str, at))}")
            tally.add(env, row)
    return Outcome(
        "mismatch" if tally.failures else "match",
        tally.lines(),
        [f"per-degree: {tally.total} cases"],
    )


def _rational_roots(poly) -> list[sp.Rational] | None:
    """The real roots of an fmpq_poly when all of them are rational (FLINT factors it), else
    None."""
    if poly.degree() < 1:
        return []
    roots = []
    for factor, _ in poly.factor()[1]:
        if factor.degree() != 1:
            return None
        b, a = factor.coeffs()
        root = -flint.fmpq(b) / a
        roots.append(sp.Rational(int(root.p), int(root.q)))
    return roots


def _poly_at(f, x):
    if isinstance(f, sp.Poly):
        return f.eval(x)
    y = f(flint.fmpq(int(x.p), int(x.q)))
    return sp.Rational(int(y.p), int(y.q))


# --------------------------------------------------------------------------- worked examples


def _frac(s) -> Fraction:
    e = parse(str(s))
    if not e.is_Rational:
        raise ValueError(f"{s!r} is not an exact number")
    return Fraction(int(e.p), int(e.q))


def _pts(rows) -> list[tuple[Fraction, ...]]:
    return [tuple(_frac(x) for x in row) for row in rows]


def _pt_str(p) -> str:
    return "(" + ", ".join(str(x) for x in p) + ")"


def decasteljau_levels(points, t) -> list[list[tuple]]:
    """The de Casteljau triangle (the notes' recursion (*)), exactly."""
    rows = [list(points)]
    while len(rows[-1]) > 1:
        prev = rows[-1]
        rows.append(
            [
                tuple((1 - t) * a + t * b for a, b in zip(p, q, strict=True))
                for p, q in zip(prev, prev[1:], strict=False)
            ]
        )
    return rows


def reparametrised(points, a, b) -> list[tuple]:
    """Control points of the piece u -> p(a + (b - a) u), from the power form of
    p(a + (b-a)u) and derive's power→Bernstein matrix (independent of de Casteljau)."""
    n = len(points) - 1
    u = sp.Symbol("u")
    conv = _algebra.power_to_bernstein_matrix(n)
    out_coords = []
    for c in range(len(points[0])):
        expr = sum(
            sp.Rational(points[i][c].numerator, points[i][c].denominator)
            * bz.bernstein_basis(
                n,
                i,
                sp.Rational(a.numerator, a.denominator)
                + sp.Rational((b - a).numerator, (b - a).denominator) * u,
            )
            for i in range(n + 1)
        )
        coeffs = sp.Poly(sp.expand(expr), u).all_coeffs()[::-1]
        coeffs += [0] * (n + 1 - len(coeffs))
        power = [Fraction(int(sp.Rational(x).p), int(sp.Rational(x).q)) for x in coeffs]
        out_coords.append([sum(power[e] * conv[e][j] for e in range(n + 1)) for j in range(n + 1)])
    return [tuple(col[j] for col in out_coords) for j in range(n + 1)]


def _compare_points(label, printed, derived) -> list[str]:
    if len(printed) != len(derived):
        return [f"{label}: printed {len(printed)} points, derived {len(derived)}"]
    return [
        f"{label}[{j}]: printed {_pt_str(p)}, derived {_pt_str(d)}"
        for j, (p, d) in enumerate(zip(printed, derived, strict=True))
        if p != d
    ]


def _compare_levels(label, printed_levels, points, t) -> list[str]:
    derived = decasteljau_levels(points, t)
    out = []
    if len(printed_levels) != len(derived):
        out.append(f"{label}: printed {len(printed_levels)} levels, derived {len(derived)}")
    for k, (p, d) in enumerate(zip(printed_levels, derived, strict=False)):
        out += _compare_points(f"{label}[{k}]", _pts(p), d)
    return out


@checker("subdivision_example")
def check_subdivision_example(record: dict, ctx: Context) -> Outcome:
    pts = _pts(record["control_points"])
    t = _frac(record["parameter"])
    diffs = []
    if len(pts) != int(record["degree"]) + 1:
        diffs.append(f"degree {record['degree']} but {len(pts)} control points")
    diffs += _compare_levels("levels", record["levels"], pts, t)
    diffs += _compare_points("left", _pts(record["left"]), reparametrised(pts, Fraction(0), t))
    diffs += _compare_points("right", _pts(record["right"]), reparametrised(pts, t, Fraction(1)))
    checked = ["levels vs de Casteljau", "pieces vs reparametrisation p(t* u), p(t* + (1-t*)u)"]
    return Outcome("mismatch" if diffs else "match", diffs, checked)


@checker("segment_example")
def check_segment_example(record: dict, ctx: Context) -> Outcome:
    pts = _pts(record["control_points"])
    t1, t2 = _frac(record["t1"]), _frac(record["t2"])
    diffs = []
    current = pts
    lo, hi = Fraction(0), Fraction(1)  # the original parameter interval of `current`
    for name in ("step1", "step2"):
        step = record[name]
        par = _frac(step["parameter"])
        if "parameter_printed" in step and _frac(step["parameter_printed"]) != par:
            diffs.append(f"{name}.parameter_printed {step['parameter_printed']} != {par}")
        diffs += _compare_points(f"{name}.control_points", _pts(step["control_points"]), current)
        diffs += _compare_levels(f"{name}.levels", step["levels"], current, par)
        flat = sorted(p for level in _pts_levels(step["levels"]) for p in level)
        if sorted(_pts(step["printed_sequence"])) != flat:
            diffs.append(f"{name}.printed_sequence is not the points of {name}.levels")
        # the split point in the original parameter, and the piece kept
        split = lo + (hi - lo) * par
        piece = (lo, split) if step["keep"] == "left" else (split, hi)
        derived = reparametrised(pts, *piece)
        diffs += _compare_points(f"{name}.result", _pts(step["result"]), derived)
        current, (lo, hi) = derived, piece
    if (lo, hi) != (t1, t2):
        diffs.append(f"the two steps keep [{lo}, {hi}], not [t1, t2] = [{t1}, {t2}]")
    diffs += _compare_points("result", _pts(record["result"]), reparametrised(pts, t1, t2))
    checked = ["each step's levels vs de Casteljau", "pieces vs reparametrisation"]
    return Outcome("mismatch" if diffs else "match", diffs, checked)


def _pts_levels(levels):
    return [_pts(level) for level in levels]


# --------------------------------------------------------------------------- convexity example


@checker("convexity_example")
def check_convexity(record: dict, ctx: Context) -> Outcome:
    """Quartic with a free ω: x(t), y(x), y''(x) against the derived curve; the conclusions
    against the ω-sets where the derived y'' keeps its sign / changes sign twice on [0, 1]
    (`convex`, `two_inflections`: equal sets, the printed pair being a dichotomy) and where the
    control polygon is not convex but the curve is (`concave_polygon_convex_curve`: printed as
    an example range, so it must lie inside the derived set)."""
    omega, x = S["omega"], S["x"]
    coords = [[parse(str(c)) for c in row] for row in record["control_points"]]
    n = int(record["degree"])
    if len(coords) != n + 1:
        return Outcome("mismatch", [f"degree {n} but {len(coords)} control points"])
    comp = [sum(coords[i][c] * bz.bernstein_basis(n, i, T) for i in range(n + 1)) for c in (0, 1)]
    xt, yt = (sp.expand(c) for c in comp)
    derived = {
        "x": xt,
        "y": sp.expand(yt.subs(T, x)),
        "y2": sp.expand(sp.diff(yt, T, 2).subs(T, x)),
    }
    diffs = []
    if sp.expand(xt - T) != 0:
        diffs.append(f"x(t) is {xt}, not t: y cannot be written as a function of x = t")
    real = Realiser({"y": lambda a, env: Sc.of(derived["y"].subs(x, a[0].to_expr()))})
    for pos, eq in enumerate(record["equations"]):
        lhs, rhs = parse(eq["lhs"]), parse(eq["rhs"])
        want = xt if lhs == x else real(lhs, {}).to_expr()
        got = real(rhs, {}).to_expr()
        if not _is_zero(got - want):
            diffs.append(
                f"equation {pos + 1} `{eq['lhs']} = …`: printed {sp.factor(got)}, derived "
                f"{sp.factor(want)} (difference {sp.factor(got - want)})"
            )
    y2 = derived["y2"]
    convex_set = _omega_set(lambda w: _sign_changes(y2.subs(omega, w), x) == 0, [y2], x, omega)
    two_set = _omega_set(lambda w: _sign_changes(y2.subs(omega, w), x) == 2, [y2], x, omega)
    turns = _turns(coords)
    poly_convex = _omega_set(
        lambda w: (
            all(c.subs(omega, w) >= 0 for c in turns) or all(c.subs(omega, w) <= 0 for c in turns)
        ),
        turns,
        None,
        omega,
    )
    concave_convex = sp.Intersection(sp.Complement(sp.S.Reals, poly_convex), convex_set)
    concl = record.get("conclusions", {})
    for key, want, mode in (
        ("convex", convex_set, "equal"),
        ("two_inflections", two_set, "equal"),
        ("concave_polygon_convex_curve", concave_convex, "subset"),
    ):
        if key not in concl:
            continue
        got = _condition_set(concl[key])
        ok = got == want if mode == "equal" else got.is_subset(want)
        if not ok:
            rel = "is" if mode == "equal" else "lies inside"
            diffs.append(f"conclusion {key}: printed omega in {got}, derived set {rel} {want}")
    checked = ["x, y, y'' vs the derived quartic", "conclusions vs derived ω-sets"]
    return Outcome("mismatch" if diffs else "match", diffs, checked)


@lru_cache(maxsize=64)
def _condition_set(text: str):
    """A printed condition on ω as a set (the record and its erratum share conclusions)."""
    return _as_set(parse(text))


def _as_set(cond):
    """cond.as_set(), with each polynomial inequality in one variable solved as a rational
    inequality: Relational.as_set first asks whether the relation is periodic, which calls
    simplify, whose first use imports sympy.physics (half a second of a worker)."""
    if isinstance(cond, sp.And):
        return sp.Intersection(*(_as_set(a) for a in cond.args))
    if isinstance(cond, sp.Or):
        return sp.Union(*(_as_set(a) for a in cond.args))
    if isinstance(cond, sp.Not):
        return sp.Complement(sp.S.Reals, _as_set(cond.args[0]))
    if isinstance(cond, sp.core.relational.Relational) and len(cond.free_symbols) == 1:
        (var,) = cond.free_symbols
        if all(side.is_polynomial(var) for side in cond.args):
            return reduce_rational_inequalities([[cond]], var, relational=False)
    return cond.as_set()


def _turns(coords):
    out = []
    for a, b, c in zip(coords, coords[1:], coords[2:], strict=False):
        e1 = (b[0] - a[0], b[1] - a[1])
        e2 = (c[0] - b[0], c[1] - b[1])
        out.append(sp.expand(e1[0] * e2[1] - e1[1] * e2[0]))
    return out


def _sign_changes(poly_expr, x) -> int:
    p = sp.Poly(sp.expand(poly_expr), x)
    if p.is_zero:
        return 0
    changes = 0
    for factor, mult in p.sqf_list()[1]:
        if mult % 2:
            changes += sum(1 for r in factor.real_roots() if 0 < r < 1)
    return changes


def _omega_set(pred, exprs, x, omega):
    """The set of ω where pred holds, from exact samples between the critical values."""
    crit = set()
    for e in exprs:
        e = sp.expand(e)
        polys = [e] if x is None else [e.subs(x, 0), e.subs(x, 1), sp.discriminant(e, x)]
        if x is not None:
            polys.append(sp.Poly(e, x).LC())
        for p in polys:
            p = sp.Poly(p, omega)
            if p.degree() > 0:
                crit |= {r for r in p.real_roots()}
    crit = sorted(crit)
    pieces = []
    if not crit:
        return sp.S.Reals if pred(sp.Integer(0)) else sp.S.EmptySet
    bounds = [-sp.oo, *crit, sp.oo]
    for a, b in zip(bounds, bounds[1:], strict=False):
        mid = a + 1 if b == sp.oo else b - 1 if a == -sp.oo else (a + b) / 2
        if pred(mid):
            pieces.append(sp.Interval.open(a, b))
    pieces += [sp.FiniteSet(c) for c in crit if pred(c)]
    return sp.Union(*pieces) if pieces else sp.S.EmptySet


# --------------------------------------------------------------------------- energy (issue 3)


def _energy():
    return derive_module("energy")


def quad_form(matrix, points="P") -> Form:
    """Dᵀ M D = Σ_{a,b} M[a][b] P_a·P_b, read as printed (README: not symmetrised)."""
    terms: dict = {}
    for a, row in enumerate(matrix):
        for b, v in enumerate(row):
            if v:
                key = tuple(sorted(((points, a), (points, b))))
                terms[key] = terms.get(key, Sc.of(0)) + Sc.of(Fraction(str(v)))
    return Form(terms)


def _energy_degree(family: str, n: int) -> int:
    if n not in FAMILIES[family].degrees:
        raise Undefined(f"{family} degree {n} outside {FAMILIES[family].degrees}")
    return n


@cache
def _published(family: str, n: int, k: int):
    c, X, Y = _energy().published_form(family, _energy_degree(family, n), k)
    return Fraction(c), X, Y


@cache
def _energy_forms(family: str, n: int, k: int):
    return _energy().energy_forms(family, _energy_degree(family, n), k)


@cache
def _energy_quad(family: str, n: int, k: int, points: str) -> Form:
    """E_k(λ) = ∫f·f - 2λ∫f·g + λ²∫g·g from energy_forms(), as a quadratic form in the points."""
    forms = _energy_forms(family, n, k)
    out = Sc.of(0)
    for key, weight in (("ff", Sc.of(1)), ("fg", SLAM * -2), ("gg", SLAM**2)):
        scale, U = forms[key]
        out = v_add(out, v_mul(weight * Sc.of(Fraction(scale)), quad_form(U, points)))
    return out


def energy_model(ctx: Context):
    def E(a, env):
        e = _energy_quad(ctx.family.name, ctx.degree(env), _int(a[0]), ctx.family.points)
        if len(a) > 1 and not is_param(a[1], LAM):
            e = v_apply(e, lambda s: s.subs(LAM, a[1]))
        return e

    return E


def lambda_star(family: str, n: int, k: int, points: str) -> Ratio:
    c, X, Y = _published(family, n, k)
    return Ratio(v_mul(Sc.of(Fraction(c)), quad_form(X, points)), quad_form(Y, points))


@checker(
    "energy_definition",
    "energy_functional",
    "energy_lambda",
    requires=("energy",),
)
def check_energy_equations(record: dict, ctx: Context) -> Outcome:
    """E_k, its quadratic form in λ and the stationary λ, for every n and k = 1, 2, 3, with
    E(k[, λ]) from energy_forms(): a left side `lam` is the derived minimiser
    c·DᵀXD/DᵀYD of published_form(), and `dE/dλ = 0` is checked at that minimiser."""
    real = ctx.realiser({"E": energy_model(ctx)})
    tallies: list[Tally] = []
    for pos, eq in enumerate(record["equations"]):
        lhs, rhs = parse(eq["lhs"]), parse(eq["rhs"])
        label = f"equation {pos + 1} `{eq['lhs']} = …`"
        if lhs == LAM or (rhs == 0 and lhs.has(sp.Derivative) and LAM in lhs.free_symbols):
            tally = Tally(label)
            for env in instances(record, ctx, (lhs, rhs, parse("p(t)")), eq):
                n, k = int(env[S["n"]]), int(env[S["k"]])
                try:
                    star = lambda_star(ctx.family.name, n, k, ctx.family.points)
                except ZeroDivisionError as exc:  # Y = 0: E_k does not depend on λ
                    tally.add(env, [f"{exc}: no λ minimises E_{k}"])
                    continue
                if lhs == LAM:
                    diffs = compare(real(rhs, env), star)
                else:  # a + λ b = 0 at λ = num/den  <=>  a·den + b·num = 0
                    val = real(lhs, env)
                    a = v_apply(val, lambda s: s.subs(LAM, 0))
                    b = v_apply(val, lambda s: s.diff(LAM))
                    # a + λ b = 0 at λ = num/den: b = μ·den and a = -μ·num suffices (cheap);
                    # otherwise a·den + b·num = 0 as a quartic form decides
                    ok = _proportional_pairs(
                        Ratio(v_neg(a), b), Ratio(star.num, star.den)
                    ) or v_is_zero(v_add(v_mul(a, star.den), v_mul(b, star.num)))
                    diffs = [] if ok else ["dE/dλ does not vanish at the derived minimiser"]
                tally.add(env, diffs)
            tallies.append(tally)
        else:
            check_equation(record, ctx, eq, real, f"equation {pos + 1}", tallies)
    diffs = [line for t in tallies for line in t.lines()]
    checked = [f"{t.label.split(' `')[0]}: {t.total} cases" for t in tallies]
    return Outcome("mismatch" if diffs else "match", diffs, checked)


def _records_by_id(record):
    from .verify import records_by_id

    return records_by_id()


def _normalised(matrix):
    """(q, primitive matrix with first nonzero diagonal entry positive), matrix = q·primitive."""
    from math import gcd

    flat = [int(v) for row in matrix for v in row]
    g = 0
    for v in flat:
        g = gcd(g, v)
    if g == 0:
        return Fraction(0), matrix
    diag = [int(matrix[a][a]) for a in range(len(matrix)) if int(matrix[a][a])]
    sign = -1 if diag and diag[0] < 0 else 1
    return Fraction(sign * g), tuple(tuple(int(v) // (sign * g) for v in row) for row in matrix)


@checker("energy_matrix", requires=("energy",))
def check_energy_matrix(record: dict, ctx: Context) -> Outcome:
    """A printed X_n^k or Y_n^k, entry by entry, against published_form()."""
    n, k, family = int(record["n"]), int(record["k"]), ctx.family.name
    # X and Y straight from the forms: they exist even where Y = 0 (E_k does not depend on λ,
    # e.g. E_3 of a quadratic basis), where published_form() has no scale c = s_fg / s_gg
    forms = _energy_forms(family, n, k)
    derived = forms["fg" if record["name"] == "X" else "gg"][1]
    printed = record["matrix"]
    diffs = []
    if len(printed) != n + 1 or any(len(row) != n + 1 for row in printed):
        return Outcome("mismatch", [f"printed shape is not {n + 1}×{n + 1}"])
    for a in range(n + 1):
        for b in range(n + 1):
            if int(printed[a][b]) != int(derived[a][b]):
                diffs.append(f"entry [{a}][{b}]: printed {printed[a][b]}, derived {derived[a][b]}")
    if diffs:
        q, prim = _normalised(printed)
        if prim == tuple(tuple(int(v) for v in row) for row in derived):
            diffs = [f"printed matrix = {q} × derived (entries otherwise proportional)"]
    scale = _frac(record["scale"])
    checked = [f"entries vs published_form({family!r}, {n}, {k})"]
    return Outcome("mismatch" if diffs else "match", diffs, checked + [f"scale {scale}"])


@checker("energy_lambda_nk", requires=("energy",))
def check_energy_formula(record: dict, ctx: Context) -> Outcome:
    """λ = scale·DᵀXD/DᵀYD with the printed scale and matrices, against the derived minimiser
    c·DᵀX'D/DᵀY'D (equal as rational functions of the control points)."""
    n, k = int(record["n"]), int(record["k"])
    by_id = _records_by_id(record)
    Xp = by_id[record["numerator"]]["matrix"]
    Yp = by_id[record["denominator"]]["matrix"]
    scale = _frac(record["scale"])
    pts = [parse(p) for p in record["vector"]]
    if pts != [sp.Function("P")(a) for a in range(n + 1)]:
        return Outcome("mismatch", [f"vector {record['vector']} is not P(0)..P({n})"])
    printed = Ratio(v_mul(Sc.of(Fraction(scale)), quad_form(Xp)), quad_form(Yp))
    try:
        c, X, Y = _published(ctx.family.name, n, k)
    except ZeroDivisionError as exc:  # Y = 0: E_k does not depend on λ
        return Outcome("mismatch", [f"{exc}: no λ minimises E_{k}"])
    diffs = compare(printed, lambda_star(ctx.family.name, n, k, "P"))
    if diffs:
        qx, px = _normalised(Xp)
        qy, py = _normalised(Yp)
        diffs = []
        implied = scale * qx / qy if qy else None
        if implied is not None and implied != c:
            diffs.append(
                f"scale: printed {scale} (implied {implied} for primitive matrices), derived {c}"
            )
        for name, prim, der in (("X", px, X), ("Y", py, Y)):
            bad = [
                f"{name}[{a}][{b}]: printed {prim[a][b]}, derived {der[a][b]}"
                for a in range(n + 1)
                for b in range(n + 1)
                if int(prim[a][b]) != int(der[a][b])
            ]
            diffs += bad
    return Outcome("mismatch" if diffs else "match", diffs, [f"λ vs published_form({n}, {k})"])


@checker("energy_example", requires=("energy",))
def check_energy_example(record: dict, ctx: Context) -> Outcome:
    pts = _pts(record["control_points"])
    n, k = int(record["n"]), int(record["k"])
    diffs = []
    if len(pts) != n + 1:
        diffs.append(f"{len(pts)} control points for degree {n}")
    derived = Fraction(_energy().optimal_lambda_exact(pts, k, family=ctx.family.name))
    printed = _frac(record["lambda"])
    if printed != derived:
        diffs.append(f"λ: printed {printed}, derived {derived}")
    checked = [f"λ vs optimal_lambda_exact(points, k={k})"]
    if not diffs:
        caveat = _range_caveat(record, ctx, pts, k, derived)
        if caveat:
            return Outcome("caveat", caveat, [*checked, "λ against the stated parameter range"])
    return Outcome("mismatch" if diffs else "match", diffs, checked)


def _range_caveat(record: dict, ctx: Context, pts, k: int, lam: Fraction) -> list[str]:
    """Why an exactly right λ* is still not the answer the example states: it lies outside
    the paper's parameter range, where E_k (a quadratic in λ) has no minimiser at all."""
    from . import properties

    family = ctx.family.name
    text = record.get("parameter_range")
    iv = properties.Interval.parse(text) if text else properties.FAMILY_RANGES[family]
    if iv.contains(lam):
        return []
    forms = _energy().energy_forms(family, len(pts) - 1, k)
    scale, gg = forms["gg"]
    leading = scale * _energy()._quadratic(gg, pts)  # E_k(λ) = ... + leading·λ², exactly
    side = iv.lo if lam <= iv.lo else iv.hi
    closed = (not iv.lo_open) if side == iv.lo else (not iv.hi_open)
    lines = [
        f"λ* = {lam} (≈ {float(lam):.6g}) is the exact minimiser of E_{k}, but it lies outside "
        f"the stated range {iv}",
        f"E_{k}(λ) = E_{k}(λ*) + {leading}·(λ - λ*)² is convex, so on {iv} it is smallest at "
        f"the end λ = {side}"
        + (
            ""
            if closed
            else f", which the range excludes: E_{k} has NO minimum on {iv} "
            f"(its infimum is approached as λ → {side})"
        ),
    ]
    bad = properties.nonnegative(family, len(pts) - 1, properties.Interval(lam, lam))
    if bad is not None:
        lines.append(f"at λ* the basis is not non-negative ({bad.text}): no convex-hull property")
    return lines


# --------------------------------------------------------------------------- joins (issue 4)

JOIN_CONTINUITY = {"g1_join": "G1", "c1_join": "C1", "c2_join": "C2", "g2_join": "G2"}


def _diff_text(a, b) -> str:
    """printed vs derived; when both are long, their (factored) difference instead."""
    fa, fb = fast_factor(a), fast_factor(b)
    if len(str(fa)) + len(str(fb)) <= 240:
        return f"printed {_orig(fa)}, derived {_orig(fb)}"
    return f"printed - derived = {_orig(fast_factor(a - b))}"


def _join_specs(record: dict, ctx: Context):
    """(first, second) as (curve, degree symbol, shape symbol, points name); 000 names its
    first curve's degree m and the second's n (eq. 17), 001 the other way round (eq. 12)."""
    if record.get("first") and record.get("second"):
        return tuple(
            (sp_["curve"], parse(sp_["degree"]), parse(sp_["shape"]), sp_["points"])
            for sp_ in (record["first"], record["second"])
        )
    pts, degs = ctx.family.points, ctx.family.join_degrees
    return tuple((f"p{w}", S[degs[w - 1]], S[f"lam{w}"], f"{pts}{w}") for w in (1, 2))


def _printed_rows(record: dict, second_points: str) -> dict[int, sp.Expr]:
    """{r: printed right side of P_{r,2}}, with the rows of `uses` records and every reference
    to an earlier row of the second curve resolved."""
    rows: dict[int, sp.Expr] = {}
    sources = [records_by_id_safe(u) for u in record.get("uses", [])] + [record]
    for rec in sources:
        for eq in rec.get("equations", []):
            lhs = parse(eq["lhs"])
            if fn_name(lhs) == second_points and lhs.args[0].is_Integer:
                rows[int(lhs.args[0])] = parse(eq["rhs"])
    fn = sp.Function(second_points)
    for _ in range(3):
        for r in list(rows):
            rows[r] = rows[r].xreplace({fn(q): rows[q] for q in rows if q != r})
    return rows


def records_by_id_safe(rid: str) -> dict:
    by_id = _records_by_id(None)
    if rid not in by_id:
        raise KeyError(f"record {rid} (named in `uses`) does not exist")
    return by_id[rid]


@cache
def _join_rows(family: str, order: int):
    return derive_module("joins").solve(family, family, order)


def _join_derived(family: str, continuity: str) -> list[dict]:
    """Derived weights of P_{r,2}: {("first", j) | ("second", 3): Expr in the derive symbols}."""
    out = []
    order = 1 if continuity in ("C1", "G1") else 2
    for row in _join_rows(family, order):
        d = {}
        for key, w in row.items():
            e = w.as_expr()
            if continuity in ("C1", "C2"):  # C = G at α = 1, d = 0
                e = e.xreplace({S["alpha"]: 1, S["d"]: 0})
            d[key] = e
        out.append(d)
    return out


@lru_cache(maxsize=1024)
def _coefficient(rhs, point):
    """∂rhs/∂point: the weight of a control point in a formula linear in the points (used by
    the symbolic and the per-degree join checks of the same rows). Taken with respect to a
    Dummy in the point's place, which is what SymPy does for a function argument, directly."""
    d = sp.Dummy()
    return sp.diff(rhs.xreplace({point: d}), d).xreplace({d: point})


@lru_cache(maxsize=1024)
def _compiled(exprs: tuple, syms: tuple):
    """exact_function, once per formula (a printed record and its erratum share most rows)."""
    return _algebra.exact_function(list(exprs), syms, number=flint.fmpq)


def linear_in_points(rhs, syms: tuple):
    """rhs = Σ w·P(idx) with weights and indices rational functions of `syms`, compiled to a
    function of their values that returns what the realiser would (a Form), or None when rhs
    is not of that shape. The printed vertex formulas are evaluated at ~100 degree pairs and
    samples per record, and Fraction arithmetic is far cheaper than walking the expression."""
    pts = sorted({a for a in sp.preorder_traversal(rhs) if isinstance(a, AppliedUndef)}, key=str)
    if not pts or any(fn_name(p) not in POINT_LIKE or len(p.args) != 1 for p in pts):
        return None
    weights = [_coefficient(rhs, p) for p in pts]
    exprs = [*weights, *(p.args[0] for p in pts)]
    if rhs.xreplace(dict.fromkeys(pts, 0)) != 0 or any(
        e.has(*pts) or not e.free_symbols <= set(syms) for e in exprs
    ):
        return None
    fn = _compiled(tuple(exprs), tuple(syms))
    names = [fn_name(p) for p in pts]

    def realise(values) -> Form:
        try:
            out = fn(*values)
        except ZeroDivisionError:
            raise Undefined("division by zero") from None
        terms: dict = {}
        for name, w, idx in zip(names, out[: len(pts)], out[len(pts) :], strict=True):
            key = ((name, as_int(idx)),)
            terms[key] = terms.get(key, Sc.of(0)) + Sc.of(w)
        return Form(terms)

    return realise


def _weights(rhs, first_pts: str, second_pts: str, n_first) -> tuple[dict, sp.Expr]:
    """Printed weights keyed like derive/joins.py: ("first", j) for P_{n-j,1}."""
    pts = {a for a in sp.preorder_traversal(rhs) if fn_name(a) in (first_pts, second_pts)}
    out: dict = {}
    for pt in pts:
        c = _coefficient(rhs, pt)
        if fn_name(pt) == first_pts:
            key = ("first", sp.expand(n_first - pt.args[0]))
        else:
            key = ("second", pt.args[0])
        out[key] = out.get(key, 0) + c
    rest = rhs.xreplace({pt: 0 for pt in pts})
    return out, rest


def join_symbolic(record, ctx, rows, specs, continuity) -> tuple[list[str], dict]:
    (_, n1, l1, pts1), (_, n2, l2, pts2) = specs
    to_j = {n1: _algebra.n, n2: _algebra.m, l1: S["lam1"], l2: S["lam2"]}
    derived = _join_derived(ctx.family.name, continuity)
    diffs = []
    for r, rhs in sorted(rows.items()):
        printed, rest = _weights(rhs, pts1, pts2, n1)
        if rest != 0:
            diffs.append(f"symbolic: P_{r},2 has a term {rest} without a control point")
        want = derived[r]
        keys = {(s_, int(j)) for s_, j in printed if as_sympy(j).is_Integer} | set(want)
        for key in sorted(keys):
            a = printed.get((key[0], sp.Integer(key[1])), 0)
            a = as_sympy(a).xreplace(to_j)
            b = want.get(key, sp.Integer(0))
            if not _is_zero(a - b):
                name = f"{pts1}({n1} - {key[1]})" if key[0] == "first" else f"{pts2}({key[1]})"
                diffs.append(f"symbolic: {pts2}({r}): weight of {name}: " + _diff_text(a, b))
    return diffs, derived


def _degree_pairs(ctx: Context):
    """Every degree of the range for each curve, against the smallest and the largest of the
    other (and the diagonal)."""
    degs = list(ctx.family.degrees)
    ends = (degs[0], degs[-1])
    return sorted({(a, b) for a in degs for b in degs if a == b or a in ends or b in ends})


def _substitute(value, sub: dict):
    if not isinstance(value, Form):
        return value
    out = Sc.of(0)
    for key, c in value.terms.items():
        if len(key) == 1 and key[0] in sub:
            out = v_add(out, v_mul(c, sub[key[0]]))
        else:
            out = v_add(out, Form({key: c}))
    return out


# Exact parameter values for the per-degree join checks (inside both λ ranges, α ≠ 1, d ≠ 0):
# the weights are compared for general n, m, λ1, λ2, α, d symbolically; per degree pair the
# printed conditions are evaluated exactly at these values, as derive/joins.py checks its own.
JOIN_SAMPLES = (
    {
        "lam1": Fraction(1, 3),
        "lam2": Fraction(-2, 5),
        "alpha": Fraction(3, 2),
        "d": Fraction(-7, 4),
    },
    {"lam1": Fraction(-5, 7), "lam2": Fraction(4, 9), "alpha": Fraction(2, 5), "d": Fraction(5, 3)},
)


def join_per_degree(record, ctx, rows, specs, conventions, label="convention") -> Tally:
    """The printed conditions hold, per degree pair (and at JOIN_SAMPLES), for the curves
    built from the derived basis polynomials with the printed vertex formulas substituted."""
    (_, n1, l1, _), (_, n2, l2, pts2) = specs
    tally = Tally(f"per-degree {label}")
    env_syms = (n1, n2, l1, l2, S["alpha"], S["d"])
    compiled = {r: linear_in_points(rhs, env_syms) for r, rhs in rows.items()}
    real = ctx.realiser()
    for (a, b), sample in itertools.product(_degree_pairs(ctx), JOIN_SAMPLES):
        real.reset()  # the pieces' models read the λ samples, which memo keys do not hold
        values = (a, b, sample["lam1"], sample["lam2"], sample["alpha"], sample["d"])
        env = dict(zip(env_syms, values, strict=True))
        try:
            sub = {
                (pts2, r): real(rhs, env) if compiled[r] is None else compiled[r](values)
                for r, rhs in rows.items()
            }
        except Undefined:
            continue
        row = []
        for eq in conventions:
            left = _substitute(real(parse(eq["lhs"]), env), sub)
            right = _substitute(real(parse(eq["rhs"]), env), sub)
            if not equal(left, right):
                if tally.failures or row:  # details for the first failure only
                    row.append("differs")
                    continue
                row += [
                    f"`{eq['lhs']} = {eq['rhs']}`: "
                    + d.replace("printed", "right side").replace("derived", "left side")
                    for d in compare(right, left)[:1]
                ]
        tally.add(env, row)
    return tally


@checker(
    "c1_join",
    "c2_join",
    "g1_join",
    "g2_join",
    requires=("joins",),
)
def check_join(record: dict, ctx: Context) -> Outcome:
    """Vertex formulas of 001's C1/C2/G1/G2 theorems: each weight against derive/joins.py's
    solve() symbolically in n, m, λ1, λ2 (α, d), and, per degree pair, the printed continuity
    conditions with the printed vertices substituted."""
    continuity = JOIN_CONTINUITY[claim_kind(record["claim"])]
    specs = _join_specs(record, ctx)
    rows = _printed_rows(record, specs[1][3])
    family = ctx.family.name
    symbolic = family == REFERENCE or has_closed_forms(family, 2 if continuity[1] == "2" else 1)
    diffs = join_symbolic(record, ctx, rows, specs, continuity)[0] if symbolic else []
    tally = join_per_degree(record, ctx, rows, specs, record.get("convention", []))
    diffs += tally.lines()
    checked = [
        "symbolic: weights vs joins.solve()"
        if symbolic
        else f"symbolic: none ({family} has no closed end forms in n)",
        f"per-degree conditions: {tally.total} pairs",
    ]
    return Outcome("mismatch" if diffs else "match", diffs, checked)


def _solve_linear(lhs, rhs, x):
    """The x with lhs = rhs when lhs - rhs is linear in x, else None. (By hand: sp.solve
    imports sympy.physics on first use, half a second of a verify worker.)"""
    diff = sp.expand(lhs - rhs)
    slope = diff.coeff(x, 1)
    if slope == 0 or sp.expand(diff - slope * x).has(x):
        return None
    return sp.cancel(-(diff - slope * x) / slope)


# The property kinds (basis_nonnegative, basis_linearly_independent, ...) register themselves,
# and so do the kinds of a paper about one family (the `checks` module of its definition).
from . import verify_properties  # noqa: E402, F401

for _builtin in builtin_families():
    if _builtin.checks:
        importlib.import_module(f"{__package__}.{_builtin.checks}")
