"""generated/energy.py: the energy forms of every built-in family and the Bernstein Gram
matrices (derive/formulas/energy.py derives them)."""

from __future__ import annotations

from ..formulas.energy import FAMILIES, GRAM_DEGREES, ORDERS, energy_forms, gram, upper_form
from . import printing as _emit

SCRIPT = "emit/energy.py"
OUTPUT = "energy.py"


def render() -> str:
    degrees = {name: tuple(module.DEGREES) for name, module in FAMILIES.items()}
    energy = {
        name: {
            (n, k): tuple(energy_forms(name, n, k)[key] for key in ("ff", "fg", "gg"))
            for n in degrees[name]
            for k in ORDERS
        }
        for name in FAMILIES
    }
    grams = {m: upper_form(gram(m)) for m in GRAM_DEGREES}
    return "\n".join(
        [
            _emit.banner(
                SCRIPT,
                "Energy quadratic forms E_k(λ) (000, section 3) for both families, and Bernstein "
                "Gram matrices.",
            ),
            "",
            f"ORDERS = {_emit.literal(ORDERS)}",
            "",
            "# GRAM[m] = (s, U), U upper-triangular: ∫_0^1 B_a^m B_b^m dt = s·U[a][b] for a = b,",
            "# s·U[a][b]/2 for a < b.",
            "GRAM = " + _emit.literal(grams),
            "",
            "# ENERGY[family][(n, k)] = ((s_ff, U_ff), (s_fg, X), (s_gg, Y)): with",
            "# D = (P_0 … P_n)ᵀ and DᵀUD = Σ_coords Σ_{i<=j} U_ij P_i·P_j,",
            "#     E_k(λ) = s_ff·DᵀU_ffD − 2λ·s_fg·DᵀXD + λ²·s_gg·DᵀYD,",
            "#     λ* = (s_fg / s_gg) · DᵀXD / DᵀYD",
            "# (eq. 20; the paper prints c = s_fg / s_gg with X and Y).",
            "ENERGY = " + _emit.literal(energy),
            "",
        ]
    )
