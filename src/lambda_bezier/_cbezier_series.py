"""The basis of a C-Bézier family near alpha = 0, from its derived document's exact series
(``small_alpha``, derive/formulas/cbezier_series.py): b_i(alpha u; alpha) = sum_k alpha^k
p_ik(u), with the p_ik polynomials in u = t/alpha. Below the document's threshold the float
coefficients over the atoms cancel like alpha^-3, so lambda_bezier.cbezier_family evaluates
this series there instead.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np

_EPS = 2.0**-53


class SmallAlpha:
    """The basis below `below` as series in alpha: table[i, k, j] is the u^j coefficient
    of p_ik (zeros where the document has none)."""

    def __init__(self, below: float, rows: list[list[tuple[int, np.ndarray]]]):
        self.below = below
        top = max((k for row in rows for k, _ in row), default=0)
        width = max((len(c) for row in rows for _, c in row), default=1)
        self.table = np.zeros((len(rows), top + 1, width))
        for i, row in enumerate(rows):
            for k, c in row:
                self.table[i, k, : len(c)] += c
        self.sizes = np.abs(self.table).sum(axis=2)  # (n+1, K+1): sum_j |p_ikj|

    def coefficients(self, x: float) -> tuple[np.ndarray, float]:
        """((n+1, D+1) coefficients over u^j at alpha = x, normwise relative error bound):
        the orders k whose alpha^k sum_j |p_ikj| is below 2^-64 for every i are left out."""
        powers = x ** np.arange(self.table.shape[1], dtype=float)
        mags = self.sizes * powers  # (n+1, K+1)
        keep = mags.max(axis=0) >= 2.0**-64
        keep[0] = True
        top = int(np.flatnonzero(keep)[-1])
        out = np.einsum("ikj,k->ij", self.table[:, : top + 1], powers[: top + 1])
        used = max((j for j in range(out.shape[1]) if np.any(out[:, j] != 0)), default=0)
        norm = np.abs(out).sum(axis=1)
        size = mags[:, : top + 1].sum(axis=1)
        rel = float(np.max((top + 3) * _EPS * size / np.maximum(norm, np.finfo(float).tiny)))
        return out[:, : used + 1], rel + 2.0**-60


def small_alpha_of(raw: object, where: str, size: int) -> SmallAlpha | None:
    """The document's ``small_alpha`` entry (None: absent), checked: a ValueError naming
    ``small_alpha`` for anything else (the document is data, read with limits)."""
    if raw is None:
        return None
    if (
        not isinstance(raw, dict)
        or not isinstance(raw.get("below_float"), float)
        or not isinstance(raw.get("series"), list)
        or len(raw["series"]) != size
    ):
        raise ValueError(f"{where}: small_alpha is {{'below_float': x, 'series': [...]}}")
    rows = []
    for row in raw["series"]:
        if not isinstance(row, list) or len(row) > 256:
            raise ValueError(f"{where}: small_alpha: a series is a list of [k, [...]]")
        out = []
        for item in row:
            if (
                not isinstance(item, list)
                or len(item) != 2
                or not isinstance(item[0], int)
                or not 0 <= item[0] <= 256
                or not isinstance(item[1], list)
                or not 0 < len(item[1]) <= 260
                or not all(isinstance(v, str) and len(v) < 200 for v in item[1])
            ):
                raise ValueError(f"{where}: small_alpha: a term is [k, ['p/q', ...]]")
            try:
                coeffs = np.array([float(Fraction(v)) for v in item[1]])
            except (ValueError, ZeroDivisionError, OverflowError):
                raise ValueError(f"{where}: small_alpha: not a list of rationals") from None
            out.append((item[0], coeffs))
        rows.append(out)
    return SmallAlpha(raw["below_float"], rows)
