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


CONSTANT_BITS = 64  # the width of the rational interval around π or e^W


def _laurent(entry: Any) -> dict[int, Fraction]:
    """An exact number (a Fraction, or a ConstantFraction whose denominator is a power of
    its constant, as every Gram entry is) as {exponent: coefficient}."""
    if isinstance(entry, Fraction | int):
        return {0: Fraction(entry)} if entry else {}
    den = entry.denominator
    shift = len(den) - 1
    if any(den[:-1]) or den[-1] != 1:  # pragma: no cover - parse_exact writes c^-m only
        raise ValueError("optimal_parameters: an energy entry is not a Laurent polynomial")
    return {e - shift: v for e, v in enumerate(entry.numerator) if v}


def certified_atom_minimum(
    rows: list[tuple[Fraction, ...]], n: int, k: int, data: Any
) -> dict[str, Any]:
    """The certified minimum of E_k over the box of a trigonometric, hyperbolic or mixed
    family not affine in its parameters (atom_family's AtomData): E_k = Σ_e c^e E_e(x), c = π
    or e^W, E_e rational polynomials. The constant is bounded by a rational interval
    (hazmat.constants.constant_bounds) and its positive and negative powers become two more
    variables p ∈ [lo, hi], r ∈ [1/hi, 1/lo] of the box: the branch and bound of the
    rational polynomial in (x, p, r) gives a proven lower bound of E_k over the parameter box
    (the true (π, 1/π) lies in the box), and the exact E_k at its point x is the value.
    {"point" (x), "value" (exact, ℚ(c)), "lower", "certified"}."""
    from .hazmat.constants import ConstantFraction, constant_bounds

    names = data.NAMES
    grams = data.GRAM[(n, k)]
    terms: dict[tuple[int, ...], Fraction] = {}  # (x exponents..., p exponent, r exponent)
    constant = "pi"
    for (a, b), gram in grams.items():
        for row_i, row in enumerate(gram):
            for col_j, g in enumerate(row):
                if not g:
                    continue
                if isinstance(g, ConstantFraction):
                    constant = g.constant
                dot = sum(
                    (rows[row_i][d] * rows[col_j][d] for d in range(len(rows[0]))), Fraction(0)
                )
                if not dot:
                    continue
                for e, v in _laurent(g).items():
                    key = (*(x + y for x, y in zip(a, b, strict=True)), max(e, 0), max(-e, 0))
                    terms[key] = terms.get(key, Fraction(0)) + dot * v
    degree = [max((key[j] for key in terms), default=0) for j in range(len(names) + 2)]
    power = np.empty(tuple(d + 1 for d in degree), dtype=object)
    power.fill(Fraction(0))
    for key, v in terms.items():
        power[key] += v
    lo, hi = constant_bounds(constant, CONSTANT_BITS)
    box = [(data.RANGES[x][0], data.RANGES[x][1]) for x in names] + [(lo, hi), (1 / hi, 1 / lo)]
    got = box_bernstein.minimum(power, box, TOLERANCE, BUDGET)
    point = tuple(got["point"][: len(names)])
    value: Any = Fraction(0)
    for (a, b), gram in grams.items():
        w = Fraction(1)
        for x, e in zip(point, (p + q for p, q in zip(a, b, strict=True)), strict=True):
            w *= x**e
        if not w:
            continue
        for row_i, row in enumerate(gram):
            for col_j, g in enumerate(row):
                dot = sum(
                    (rows[row_i][d] * rows[col_j][d] for d in range(len(rows[0]))), Fraction(0)
                )
                if g and dot:
                    value = value + w * dot * g
    lower = got["lower"]
    gap = value - lower
    certified = got["certified"] and not (TOLERANCE * max(1, abs(float(value))) < gap)
    return {"point": point, "value": value, "lower": lower, "certified": certified}
