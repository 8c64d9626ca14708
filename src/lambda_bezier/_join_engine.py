"""Joins between any two families, per degree, from the families' power tables.

derive/joins.py derives the vertex formulas of the built-in families in closed form; a family
defined by data may have no closed form (its end derivatives can involve control points far
from the end), so the runtime solves the joint conditions for the degrees and parameters at
hand. The end coefficients come from the generated power tables (the coefficient of P_j in
p^(r)(0) is r! times the t^r coefficient of b_j, in p^(r)(1) the sum of e!/(e-r)! times the
t^e coefficients), so nothing assumes that an end derivative involves only the nearest
points: the solve is a small dense linear system, exact for exact input.

With the first curve C1 (degree n) and the new curve C2 (degree m), the unknowns are
P_{0..R,2} (R = 1 for C1/G1, 2 for C2/G2) and the conditions are 001's:

    C2(0) = C1(1),   α C2'(0) = C1'(1),   α² C2''(0) + d C2'(0) = C1''(1)

(α = 1, d = 0 for C joins). The result has the form join() consumes: {(row, source, j):
weight} with P_{row,2} = Σ weight · X, X = P_{n-j,1} (source "first") or the given P_{j,2}
(source "second", j > R).
"""

from __future__ import annotations

from fractions import Fraction
from math import factorial

from .curves import Curve, _tables

Number = Fraction | float


def _combined_power(
    cls: type[Curve], degree: int, lam: Fraction | float | None
) -> list[list[Number]]:
    """Power coefficients [i][e] of the degree-`degree` basis of `cls` at λ = lam."""
    mats = _tables(cls._data, "power")[degree]
    exact = lam is None or isinstance(lam, Fraction)
    x = Fraction(0) if lam is None else lam
    rows, cols = len(mats[0]), len(mats[0][0])
    out: list[list[Number]] = []
    for i in range(rows):
        row: list[Number] = []
        for e in range(cols):
            v = (
                sum((Fraction(m[i][e]) * x**p for p, m in enumerate(mats)), Fraction(0))
                if exact
                else sum(float(m[i][e]) * float(x) ** p for p, m in enumerate(mats))
            )
            row.append(v)
        out.append(row)
    return out


def end_coefficients(curve: Curve, orders: int) -> list[list[Number]]:
    """e[r][j]: the coefficient of P_{n-j} in p^(r)(1), r = 0..orders."""
    power = _combined_power(type(curve), curve.degree, curve.lam)
    n = curve.degree
    out: list[list[Number]] = []
    for r in range(orders + 1):
        row: list[Number] = []
        for j in range(n + 1):
            coeffs = power[n - j]
            row.append(
                sum(
                    (coeffs[e] * (factorial(e) // factorial(e - r)) for e in range(r, len(coeffs))),
                    coeffs[0] * 0,
                )
            )
        out.append(row)
    return out


def start_coefficients(
    cls: type[Curve], degree: int, lam: Fraction | float | None, orders: int
) -> list[list[Number]]:
    """s[r][j]: the coefficient of P_j in p^(r)(0), r = 0..orders."""
    power = _combined_power(cls, degree, lam)
    return [
        [
            (power[j][r] * factorial(r) if r < len(power[j]) else power[j][0] * 0)
            for j in range(degree + 1)
        ]
        for r in range(orders + 1)
    ]


def _is_zero(x: Number, scale: float) -> bool:
    return x == 0 if isinstance(x, Fraction) else abs(x) <= 1e-12 * scale


def weights(
    curve: Curve,
    order: int,
    alpha: Number,
    d: Number,
    cls: type[Curve],
    degree: int,
    lam: Fraction | float | None,
    continuity: str,
) -> dict[tuple[int, str, int], Number]:
    """P_{row,2} as combinations of the first curve's points and the given P_{j,2}."""
    exact = all(x is None or isinstance(x, Fraction) for x in (curve.lam, lam, alpha, d))
    one = Fraction(1) if exact else 1.0
    e = end_coefficients(curve, order)
    s = start_coefficients(cls, degree, lam, order)
    n = curve.degree
    # right-hand sides T_r as {("first", j): weight}
    targets: list[dict[tuple[str, int], Number]] = []
    for r in range(order + 1):
        t = {("first", j): e[r][j] for j in range(n + 1) if e[r][j] != 0}
        if r == 1:
            t = {k: v * one / alpha for k, v in t.items()}
        if r == 2:
            t = {k: v * one / alpha**2 for k, v in t.items()}
            for k, v in targets[1].items():  # - d C2'(0) / α² with C2'(0) = T_1
                t[k] = t.get(k, 0 * one) - d * v / alpha**2
        targets.append(t)
    # move the given points P_{j,2}, j > order, to the right-hand side
    for r in range(order + 1):
        for j in range(order + 1, degree + 1):
            if s[r][j] != 0:
                targets[r][("second", j)] = targets[r].get(("second", j), 0 * one) - s[r][j]
    # Gaussian elimination on the (order+1)² system s[r][0..order] x = targets[r]
    a = [[s[r][c] for c in range(order + 1)] for r in range(order + 1)]
    b = [dict(t) for t in targets]
    scale = max((abs(float(v)) for row in a for v in row), default=1.0) or 1.0
    size = order + 1
    for col in range(size):
        pivot = max(range(col, size), key=lambda r: abs(float(a[r][col])))
        if _is_zero(a[pivot][col], scale):
            lam_text = "" if lam is None else f" with lam = {lam}"
            raise ValueError(
                f"cannot solve {continuity} for P_{{{col},2}}: the conditions on "
                f"C2(0)..C2{chr(39) * order}(0) do not determine it for a {cls.family} curve "
                f"of degree m = {degree}{lam_text} (its coefficients vanish there); choose "
                "another degree or lam"
            )
        a[col], a[pivot] = a[pivot], a[col]
        b[col], b[pivot] = b[pivot], b[col]
        for r in range(size):
            if r == col or a[r][col] == 0:
                continue
            f = a[r][col] / a[col][col]
            a[r] = [x - f * y for x, y in zip(a[r], a[col], strict=True)]
            for k, v in b[col].items():
                b[r][k] = b[r].get(k, 0 * one) - f * v
    out: dict[tuple[int, str, int], Number] = {}
    for row in range(size):
        for (src, j), v in b[row].items():
            w = v / a[row][row]
            if w != 0:
                out[(row, src, j)] = w
    return out
