"""Independent numeric references: the basis *definitions* evaluated directly in floats.

Nothing here reads generated/; the tests compare generated data and the runtime with these.
"""

from __future__ import annotations

from dataclasses import dataclass
from math import comb

import numpy as np


def C(a: int, b: int) -> int:
    """Binomial coefficient with the papers' convention: 0 outside 0 <= b <= a."""
    return comb(a, b) if 0 <= b <= a else 0


def bernstein(n: int, i: int, t):
    t = np.asarray(t, dtype=float)
    return C(n, i) * t**i * (1 - t) ** (n - i)


def same_degree_definition(n: int, i: int, t, lam: float):
    """Eq. (1) of 000, with the t^(i-1) and (1-t)^(n-i-1) factors multiplied in only where
    the binomial in front is nonzero (they are then non-negative powers)."""
    t = np.asarray(t, dtype=float)
    s = 1 - t
    value = C(n, i) * s ** (n - i) * t**i
    for coeff, ps, pt in (
        (C(n - 3, i - 3), n - i + 1, i - 1),
        (-C(n - 2, i - 1), n - i, i),
        (C(n - 3, i), n - i - 1, i + 1),
    ):
        if coeff:
            value = value + (1 - lam) * coeff * s**ps * t**pt
    return value


def bernstein_like_recursion(n: int, t, lam: float):
    """All b_{i,n}, i = 0..n, from the seed (eq. 1 of 001) and the recursion (eq. 2)."""
    t = np.asarray(t, dtype=float)
    b = [
        (1 - 2 * lam * t + lam * t**2) * (1 - t) ** 2,
        2 * t * (1 - t) * (1 + lam - lam * t + lam * t**2),
        (1 - lam + lam * t**2) * t**2,
    ]
    for deg in range(3, n + 1):
        zero = np.zeros_like(t)
        b = [
            (1 - t) * (b[i] if i < deg else zero) + t * (b[i - 1] if i >= 1 else zero)
            for i in range(deg + 1)
        ]
    return b


@dataclass(frozen=True)
class Family:
    name: str
    degrees: tuple[int, ...]
    lam_range: tuple[float, float]  # closed interval used for sampling (open end nudged in)
    bernstein_lambda: float | None
    offset: int

    def basis(self, n: int, t, lam: float | None) -> np.ndarray:
        """(len(t), n+1) basis values from the definition."""
        t = np.atleast_1d(np.asarray(t, dtype=float))
        if self.name == "bezier":
            cols = [bernstein(n, i, t) for i in range(n + 1)]
        elif self.name == "same_degree":
            cols = [same_degree_definition(n, i, t, lam) for i in range(n + 1)]
        else:
            cols = bernstein_like_recursion(n, t, lam)
        return np.stack(cols, axis=-1)


FAMILIES = {
    "bezier": Family("bezier", tuple(range(1, 15)), (0.0, 0.0), None, 0),
    "same_degree": Family("same_degree", tuple(range(3, 13)), (-1.999, 1.0), 1.0, 0),
    "bernstein_like": Family("bernstein_like", tuple(range(2, 13)), (-1.0, 1.0), 0.0, 2),
}
