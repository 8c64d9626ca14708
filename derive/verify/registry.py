"""The registry verify reads itself: every checker module, the paper-specific checkers each
built-in family's definition names (derive/families/<name>.toml, ``[builtin] checks``), and
the families a records file defines. Importing this module registers every claim kind.

Nothing below verify knows verify: the families layer only names the checks module, and
verify imports it here.
"""

from __future__ import annotations

import importlib

from ..families.cbezier import CDefinition
from ..families.definition import Definition
from ..families.engine import basis_polys, check, closed_endpoint_forms, closed_endpoint_order
from ..families.registry import builtin_families
from ..families.spaces import space_of
from ..formulas.atom_family import check_partition
from ..formulas.family import register_formulas

# The shared checkers register their claim kinds on import (one module per group of kinds).
from . import (  # noqa: F401 - imported for their registrations
    checks_energy,
    checks_equations,
    checks_examples,
    checks_joins,
    checks_joins_several,
    checks_properties,
    checks_several,
    checks_surfaces,
    checks_surfaces_several,
)
from .checks_core import CHECKERS, Outcome, Pending, claim_kind, missing_requirement
from .claim_families import (
    FAMILIES,
    SEVERAL_FAMILIES,
    Family,
    kind_problem,
    kinds,
    register_family,
    resolve_checker,
)
from .context import Context

__all__ = [
    "CHECKERS",
    "FAMILIES",
    "Outcome",
    "claim_kind",
    "kind_problem",
    "kinds",
    "register_cbezier_family",
    "register_defined_family",
    "register_elementary_family",
    "register_several_family",
    "run_checker",
]

# A paper's own claims: the module its family's definition names (checks = "checks_<name>").
for _builtin in builtin_families():
    if _builtin.checks:
        importlib.import_module(f"{__package__}.{_builtin.checks}")


def run_checker(record: dict) -> Outcome:
    entry = resolve_checker(record)
    reason = missing_requirement(entry.requires)
    if reason is not None:
        return Outcome("pending", [reason])
    try:
        if record["family"] in SEVERAL_FAMILIES:  # no one-parameter context: checks_several
            return entry.fn(record, None)
        return entry.fn(record, Context.of(record))
    except Pending as exc:
        return Outcome("pending", [str(exc)])


def register_defined_family(defn: Definition, points: str | None = None) -> None:
    """Make a family a records file defines known to verify for this process: its records are
    checked by the same checkers as a built-in family's (per degree always; symbolically in n
    where the engine found closed end forms; energies where the basis is linear in the
    parameter), and the formula tables know it (derive/formulas/family.py)."""
    check(defn)
    closed = closed_endpoint_forms(defn)
    register_family(
        Family(
            defn.name,
            defn.degrees,
            points or defn.points,
            lambda degree: basis_polys(defn, degree),
            defn.offset,
            lambda: closed,
            closed_order=closed_endpoint_order(defn),
            parameter=defn.parameter,
            defined_by_data=True,
        )
    )
    register_formulas(defn)


def register_several_family(defn: Definition) -> None:
    """A family in several parameters (plain or indexed) that a records file defines: its
    records are checked by checks_several.py's claim kinds (each definition checked first)."""
    for degree in defn.degrees:
        check(defn.at_degree(degree))
    SEVERAL_FAMILIES[defn.name] = defn


def register_cbezier_family(defn: CDefinition) -> None:
    """A family whose parameter is the length of the domain or sits inside sin/cos (C-Bezier)
    that a records file defines: read and converted by cbezier.read_table (a DefinitionError
    names the key); its records use checks_several.py's basis, end-condition and symmetry
    kinds, decided exactly in Q(alpha, sin alpha, cos alpha) by checks_cbezier.py."""
    SEVERAL_FAMILIES[defn.name] = defn


def register_elementary_family(defn: Definition) -> None:
    """A trigonometric, hyperbolic or mixed family that a records file defines: its space and
    partition of unity are decided first (a DefinitionError names the key), then its records
    are checked by checks_several.py's claim kinds in exact atoms (checks_elementary.py)."""
    check_partition(defn, space_of(defn))
    SEVERAL_FAMILIES[defn.name] = defn
