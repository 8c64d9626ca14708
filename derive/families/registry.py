"""The registry of built-in families: derive/families/*.toml, each a [family] definition and
a [builtin] table saying how the project ships it (order, curve class, derivation module,
the verify module of the paper's own claims). Every layer above reads this one list.
"""

from __future__ import annotations

import importlib
import sys
from dataclasses import dataclass
from functools import cache

from ..algebra import bernstein as _bernstein
from ..grammar.messages import schema_message
from .definition import (
    _NAME,
    FAMILY_DEFINITIONS,
    REFERENCE,
    Definition,
    DefinitionError,
    read_definition,
)
from .engine import GenericDerivation


@dataclass(frozen=True)
class Builtin:
    """A family the project ships: its definition (the [family] table of
    derive/families/<name>.toml) and how it is shipped (the file's [builtin] table)."""

    definition: Definition
    order: int  # position in generated/ and in reports
    points: str  # the control points' name in the paper's records
    curve_class: str  # the runtime's class name for its curves
    # derive/families/<derivation>.py: the paper's own closed forms and the emitted module;
    # without one the engine derives and emits the family from its definition alone
    # (GenericDerivation)
    derivation: str | None = None
    # the degree symbols of the first and second curve of the paper's join records that do not
    # name their curves (000's eq. 17 says p1 has degree m, 001's eq. 12 says n)
    join_degrees: tuple[str, str] = ("n", "m")
    # derive/verify/<checks>.py: checkers of claims only this paper makes (verify imports it)
    checks: str | None = None

    @property
    def name(self) -> str:
        return self.definition.name

    def module(self):
        """The derivation module (derive/families/<derivation>.py, imported by the name the
        [builtin] table gives), or the engine's own derivation of the family when its paper
        prints no closed form of its own."""
        if self.derivation is None:
            return _generic_derivation(self.definition)
        return importlib.import_module(f"{__package__}.{self.derivation}")


@cache
def _generic_derivation(defn: Definition) -> GenericDerivation:
    return GenericDerivation(defn)


_BUILTIN_SCHEMA = {
    "type": "object",
    "properties": {
        "order": {"type": "integer", "minimum": 0},
        "derivation": {"type": "string", "pattern": _NAME},
        "points": {"type": "string", "pattern": r"^[A-Za-z]$"},
        "curve_class": {"type": "string", "pattern": r"^[A-Z][A-Za-z0-9]*Curve$"},
        "join_degrees": {
            "type": "array",
            "items": {"enum": ["n", "m"]},
            "minItems": 2,
            "maxItems": 2,
            "uniqueItems": True,
        },
        "checks": {"type": "string", "pattern": _NAME},
    },
    "required": ["order", "points", "curve_class"],
    "additionalProperties": False,
}


@cache
def builtin_families() -> tuple[Builtin, ...]:
    """Every family in derive/families/, in their `order`: the one list of built-in families
    the derivations, the emitter and verify iterate over (no shared module names one)."""
    import jsonschema

    if sys.version_info >= (3, 11):
        import tomllib
    else:  # pragma: no cover - Python 3.10
        import tomli as tomllib

    out = []
    for path in sorted(FAMILY_DEFINITIONS.glob("*.toml")):
        info = tomllib.loads(path.read_text(encoding="utf-8")).get("builtin")
        errors = list(jsonschema.Draft202012Validator(_BUILTIN_SCHEMA).iter_errors(info))
        if errors:
            raise DefinitionError(f"{path}: [builtin]: {schema_message(errors[0])}")
        defn = read_definition(path, builtin=True)
        if path.stem != defn.name:
            raise DefinitionError(f"{path}: the file must be named after the family {defn.name}")
        if "join_degrees" in info:
            info["join_degrees"] = tuple(info["join_degrees"])
        out.append(Builtin(defn, **info))
    out.sort(key=lambda b: b.order)
    if len({b.order for b in out}) != len(out):
        raise DefinitionError(f"{FAMILY_DEFINITIONS}: two built-in families share an order")
    return tuple(out)


def builtin(name: str) -> Builtin:
    for fam in builtin_families():
        if fam.name == name:
            return fam
    raise KeyError(name)


def derivation(name: str):
    """The derive module of a built-in family, or the reference basis (derive/algebra/bernstein.py):
    each has DEGREES and closed_end_forms() (the end values and derivatives in closed form)."""
    if name == REFERENCE:
        return _REFERENCE_DERIVATION
    return builtin(name).module()


def builtin_names() -> tuple[str, ...]:
    """The reference basis, then the built-in families in order."""
    return (REFERENCE, *(b.name for b in builtin_families()))


def reference_degrees() -> range:
    """The degrees of the reference Bernstein basis: every built-in curve converts to a Bézier
    curve of degree n + offset, up to the largest."""
    return range(
        1, max(b.definition.degrees.stop - 1 + b.definition.offset for b in builtin_families()) + 1
    )


class _ReferenceDerivation:
    """The reference basis as a derivation (DEGREES, closed_end_forms, and the rest of
    derive/algebra/bernstein.py): its degrees come from the built-in families."""

    @property
    def DEGREES(self) -> range:  # noqa: N802 - the derivation modules' constant
        return reference_degrees()

    def __getattr__(self, name: str):
        return getattr(_bernstein, name)


_REFERENCE_DERIVATION = _ReferenceDerivation()
