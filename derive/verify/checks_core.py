"""Claim checkers: each published record compared with OUR derivation.

The derived side always comes from the derive modules (each family's ``basis_polys`` and
``closed_end_forms``, ``bernstein.bernstein_basis``, ``original_basis``, ``endpoint_weights``,
the Bernstein/power matrices, and ``energy``); nothing printed is re-typed here. A paper's
own closed forms (000's three-term form, 001's explicit form) are checked by the module its
family's definition names under ``checks`` (derive/verify/checks_same_degree.py, ...).

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
record's verdict is ``pending`` with the reason. The energy checkers use
``derive/formulas/energy.py`` (issue 3), the join checkers ``derive/formulas/joins.py`` (issue
4); a new claim kind plugs in as one function registered with ``@checker(kind, requires=...)``.

Per-degree ranges: the family's degrees (derive's DEGREES); indices 0..n unless
``index_ranges`` or an equation's ``where`` says otherwise; an instance whose evaluation leaves
the definitions (a degree outside the range, a negative order) is skipped, and an equation
checked for no instance is an error. Join formulas, which involve two degrees, are checked
symbolically in n, m and, per degree, for every degree of each curve against the smallest and
the largest of the other (and equal degrees), at exact sample values of λ1, λ2, α, d.

This module holds the outcomes and the registry of checkers by claim kind; the families the
checkers know are in claim_families.py, the evaluation context in context.py, the checkers
in checks_*.py (one module per group of claim kinds), and registry.py imports them all.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from dataclasses import dataclass, field

from ..grammar import SYMBOLS
from .scalar import (
    GEN,
    Sc,
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
    # (record, context.Context) -> Outcome; the context sits above this registry
    fn: Callable[..., Outcome]
    requires: tuple[str, ...] = ()
    family: str | None = None  # only this family's records (its paper's own form), else any
    fits: Callable[[dict], bool] | None = None  # the records it checks, by their payload


CHECKERS: dict[str, list[Checker]] = {}  # kind -> its checkers, in registration order

# Missing derivations: module -> (functions that must exist, what to say while missing).
REQUIREMENTS = {
    "energy": (
        ("energy_forms", "published_form", "optimal_lambda_exact"),
        "needs the energy derivation derive/formulas/energy.py (energy_forms, published_form, "
        "optimal_lambda_exact; issue 3)",
    ),
    "joins": (
        ("solve",),
        "needs the join derivation derive/formulas/joins.py (C1/C2/G1/G2 vertex formulas; issue 4)",
    ),
    "surface_energy": (
        ("tensor_basis", "surface_forms"),
        "needs the surface derivation derive/formulas/surface_energy.py (issue 31)",
    ),
    "surface_joins": (
        ("conditions", "check_pair"),
        "needs the surface join derivation derive/formulas/surface_joins.py (issue 31)",
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


_FORMULAS = __package__.rsplit(".", 1)[0] + ".formulas"


def derive_module(name: str):
    """The formulas module `name` (derive/formulas/<name>.py), or None when it does not exist
    (imported by name: a claim kind may be registered before its derivation is written)."""
    try:
        return importlib.import_module(f"{_FORMULAS}.{name}")
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
