"""The certified global minimum of E_k over the parameter box, for a family whose basis is
not affine in its parameters (issue #30 item 3).

E_k(x) = sum over monomial pairs (a, b) of x^(a + b) tr(P^T G_ab P), with the Gram matrices
G_ab from the derived document (derive/formulas/energy_several.py). For given control points
this is a polynomial in the parameters with exact rational coefficients. Its minimum over
the closed box is found by exact Bernstein branch and bound (hazmat.box_bernstein.minimum).
The point returned has an exact energy value, and a proven lower bound over the whole box
lies within TOLERANCE of it (relative to max(1, |E|)).
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

import numpy as np

from .hazmat import box_bernstein

TOLERANCE = Fraction(1, 10**12)
BUDGET = 20_000  # boxes split before giving up (the result then says it is not certified)


def energy_polynomial(rows: list[tuple[Fraction, ...]], n: int, k: int, several: Any) -> np.ndarray:
    """The dense power coefficients of E_k in the parameters, exact."""
    grams = several.MONOMIAL_GRAM[(n, k)]
    count = len(several.NAMES)
    degree = [0] * count
    for a, b in grams:
        for j in range(count):
            degree[j] = max(degree[j], a[j] + b[j])
    power = np.empty(tuple(d + 1 for d in degree), dtype=object)
    power.fill(Fraction(0))
    for (a, b), gram in grams.items():
        total = Fraction(0)
        for dim in range(len(rows[0])):
            for i, row in enumerate(gram):
                pi = rows[i][dim]
                if pi:
                    total += pi * sum((g * rows[j][dim] for j, g in enumerate(row)), Fraction(0))
        if a != b:
            total *= 2  # the pair (b, a) is not stored
        power[tuple(x + y for x, y in zip(a, b, strict=True))] += total
    return power


def certified_minimum(
    rows: list[tuple[Fraction, ...]], n: int, k: int, several: Any
) -> dict[str, Any]:
    """{"point", "value", "lower", "certified"} over the closed box of several.RANGES."""
    power = energy_polynomial(rows, n, k, several)
    box = [(several.RANGES[x][0], several.RANGES[x][1]) for x in several.NAMES]
    return box_bernstein.minimum(power, box, TOLERANCE, BUDGET)
