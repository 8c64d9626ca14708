"""The families verify knows: the built-in ones (from derive/families' registry) and those a
records file defines (registered for the run), with their derived bases and closed forms.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import cache
from math import comb

import sympy as sp

from .. import algebra as _algebra
from ..algebra import bernstein as bz
from ..families.cbezier import CDefinition
from ..families.registry import REFERENCE, builtin_families, reference_degrees
from ..grammar import MAX_EXPONENT, MAX_FACTORIAL
from .checks_core import (
    CHECKERS,
    KIND_FAMILIES,
    LAM,
    LAMBDA,
    ST,
    Checker,
    S,
    T,
    claim_kind,
    is_param,
)
from .expr_parse import (
    as_sympy,
)
from .scalar import (
    Sc,
    Undefined,
    _NotRational,
    as_fraction,
)

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
    # a family defined by data names its parameter and its control points itself (#32 item 3):
    # records write them; the checkers read the parameter as `lam`
    parameter: str = "lam"
    defined_by_data: bool = False


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
FAMILIES[REFERENCE] = Family(REFERENCE, reference_degrees(), "b")


# Families in several shape parameters (plain or indexed) that a records file defines, by name:
# their Definition. Their records use the claim kinds of checks_several.py only.
SEVERAL_FAMILIES: dict[str, object] = {}


def register_family(family: Family) -> None:
    """A family defined by data (derive/families/engine.py) joins the built-in ones for this run:
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
        degrees = FAMILIES[family].degrees
        raise Undefined(f"{family} degree {degree} outside {degrees.start}..{degrees.stop - 1}")
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
    value = _bounded_xreplace(e, values)
    return value is not None and bool(value.is_Rational) and value != 0


def _bounded_xreplace(e, values):
    """e.xreplace(values), or None where that would compute a power, factorial or binomial of
    numbers past the evaluator's limits: a user's `t**n**n**n` becomes 17**(17**17) at the
    sample point, which SymPy would compute (for hours) before anything else is looked at."""
    if e in values:
        return values[e]
    if not e.args:
        return e
    args = []
    for a in e.args:
        v = _bounded_xreplace(a, values)
        if v is None:
            return None
        args.append(v)
    if e.is_Pow:
        base, ex = args
        if base.is_number and ex.is_Integer and abs(int(ex)) > MAX_EXPONENT:
            return None
    elif isinstance(e, (sp.factorial, sp.binomial)) and any(
        a.is_Integer and abs(int(a)) > MAX_FACTORIAL for a in args
    ):
        return None
    return e.func(*args)


_SEVERAL = ("(families in several parameters)",)
# the claim kinds of a C-Bezier family (checks_cbezier.py, reached through checks_several.py)
# The surface kinds decided for a family in several parameters (plain or indexed), polynomial
# or trigonometric / hyperbolic (checks_surfaces_several.py).
SEVERAL_SURFACE_KINDS = (
    "surface_basis",
    "surface_boundary",
    "surface_corners",
    "surface_energy_matrix",
    "surface_continuity",
)

CBEZIER_KINDS = (
    "several_basis",
    "several_end_conditions",
    "several_symmetry",
    "several_energy_matrix",
    "several_energy",
    "several_nonnegative",
    "several_independence",
    "several_join",
)  # checks_several.py's kinds' families


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
    if isinstance(SEVERAL_FAMILIES.get(family), CDefinition):
        if kind not in CBEZIER_KINDS:
            return (
                f"claim kind {kind!r} is not decided for {family!r} (its parameter is the "
                "length of the domain or sits inside sin/cos); its claim kinds are "
                f"{', '.join(CBEZIER_KINDS)}"
            )
        return None
    if family in SEVERAL_FAMILIES:
        several = sorted(k for k, (fams, _) in KIND_FAMILIES.items() if fams == _SEVERAL)
        if kind in SEVERAL_SURFACE_KINDS:  # checks_surfaces_several.py
            return None
        if kind not in several:
            return (
                f"claim kind {kind!r} is about a family with one shape parameter; {family!r} "
                f"has several: its claim kinds are {', '.join(several)}"
            )
        return None
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


@cache
def _bernstein_mats(family: str, n: int):
    fam = FAMILIES[family]
    return _algebra.bernstein_matrices(list(fam.basis_polys(n)), n + fam.offset)  # type: ignore[misc]
