"""generated/surface_energy.py: the membrane and thin-plate energy matrices of tensor-product
surfaces, one family in both directions (derive/formulas/surface_energy.py derives them by
integrating the tensor-product basis and checks them against the curves' Gram matrices)."""

from __future__ import annotations

from ..formulas.surface_energy import ENERGIES, SURFACE_DEGREES, emitted
from . import printing as _emit

SCRIPT = "emit/surface_energy.py"
OUTPUT = "surface_energy.py"


def render() -> str:
    return "\n".join(
        [
            _emit.banner(
                SCRIPT,
                "Surface energy matrices (membrane, thin plate) of tensor-product surfaces.",
            ),
            "",
            f"ENERGIES = {_emit.literal(tuple(ENERGIES))}",
            f"DEGREES = {_emit.literal(tuple(SURFACE_DEGREES))}",
            "",
            "# SURFACE_ENERGY[family][(m, n, energy)] = {(a, b): (s, U)}: for a net P of",
            "# (m+1) x (n+1) points of `family` in both directions, read row by row into",
            "# vec(P) = (P_00, P_01, …, P_0n, P_10, …), the energy is",
            "#     E(λ_u, λ_v) = Σ_(a,b) λ_u^a λ_v^b · s · Σ_{r<=c} U[r][c] vec(P)_r · vec(P)_c",
            "# (U upper-triangular primitive integers, off-diagonal entries doubled; the",
            "# classical Bézier family has only (0, 0)).",
            "SURFACE_ENERGY = " + _emit.literal(emitted()),
            "",
        ]
    )
