"""generated/properties.py: the singular parameters of every built-in family
(derive/formulas/properties.py derives them)."""

from __future__ import annotations

from ..formulas.properties import singular_table
from . import printing as _emit

SCRIPT = "emit/properties.py"
OUTPUT = "properties.py"


def render() -> str:
    table = singular_table()
    parts = [
        _emit.banner(SCRIPT, "Exact basis properties derived from the definitions."),
        "# SINGULAR[family][n]: the λ inside the family's range where its degree-n basis is",
        "# linearly dependent (the determinant of its Bernstein coefficients, or their Gram",
        "# determinant, vanishes there): an exact F, or ((lo, hi), (c_0, ..., c_k)) for an",
        "# irrational root, the only root in (lo, hi) of the integer polynomial Σ c_j λ^j.",
        "SINGULAR = " + _emit.literal(table),
        "",
    ]
    return "\n".join(parts)
