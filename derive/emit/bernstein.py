"""generated/bernstein.py: the classical Bézier data of derive/algebra/bernstein.py, for the
reference basis's degrees (the built-in families' registry gives them)."""

from __future__ import annotations

from ..algebra import (
    bernstein_power_matrix,
    centred_matrices,
    check_endpoint_weights,
    elevation_matrix,
    endpoint_weights,
    hodograph_matrix,
    original_power_matrix,
    power_to_bernstein_matrix,
)
from ..families.registry import reference_degrees
from . import printing as _emit

SCRIPT = "emit/bernstein.py"
OUTPUT = "bernstein.py"


def render() -> str:
    start, end = endpoint_weights()
    check_endpoint_weights(start, end, reference_degrees())
    degrees = tuple(reference_degrees())
    parts = [
        _emit.banner(
            SCRIPT, "Classical Bézier data, derived from B_{j,N}(t) = C(N,j) t^j (1-t)^(N-j)."
        ),
        _emit.EXACT_HELPERS,
        "",
        f"DEGREES = {_emit.literal(degrees)}",
        "",
        "# POWER[N][j][e]: coefficient of t^e in B_{j,N}.",
        "POWER = " + _emit.literal({d: bernstein_power_matrix(d) for d in degrees}),
        "",
        "# CENTRED[N][j][e]: coefficient of (t - 1/2)^e in B_{j,N}.",
        "CENTRED = "
        + _emit.literal({d: centred_matrices((bernstein_power_matrix(d),))[0] for d in degrees}),
        "",
        "# TO_BERNSTEIN[N][e][j]: coefficient of B_{j,N} in t^e.",
        "TO_BERNSTEIN = " + _emit.literal({d: power_to_bernstein_matrix(d) for d in degrees}),
        "",
        "# HODOGRAPH[N][j][i]: weight of P_i in control point j of p'(t) (degree N - 1).",
        "HODOGRAPH = " + _emit.literal({d: hodograph_matrix(d) for d in degrees}),
        "",
        "# ELEVATION[N][j][i]: weight of P_i in control point j of p(t) written in degree N + 1.",
        "ELEVATION = " + _emit.literal({d: elevation_matrix(d) for d in degrees}),
        "",
        "# ORIGINAL_POWER[N][i][e]: coefficient of t^e in Bézier's f_i = sum_{j>=i} B_{j,N}.",
        "ORIGINAL_POWER = " + _emit.literal({d: original_power_matrix(d) for d in degrees}),
        "",
        "",
        _emit.function(
            "endpoint_weight_start",
            ["n", "k", "i"],
            "Weight of P_i (0 <= i <= k) in p^(k)(0) of a degree-n Bézier curve.",
            f"return {_emit.expression(start)}",
        ),
        "",
        _emit.function(
            "endpoint_weight_end",
            ["n", "k", "i"],
            "Weight of P_{n-i} (0 <= i <= k) in p^(k)(1) of a degree-n Bézier curve.",
            f"return {_emit.expression(end)}",
        ),
    ]
    return "\n".join(parts)
