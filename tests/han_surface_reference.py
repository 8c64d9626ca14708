"""What the trigonometric-surface tests (tests/test_param_surfaces.py, across a trigonometric
family; tests/test_mixed_surfaces.py, across a polynomial one) share: the net, the u
direction's parameters, and Han, Ma and Huang's cubic trigonometric basis (2009) written out
from the paper in mpmath, independent of the runtime's derivation."""

from __future__ import annotations

from fractions import Fraction as F

import mpmath

NET = [[(i, j, F((i * j) % 3, 2) - F(i, 4)) for j in range(4)] for i in range(4)]
PU = {"lam": F(1, 2), "mu": -1}  # the u direction's (lam, mu) of han_trig_cubic


def mp(x: object) -> mpmath.mpf:
    """An exact number (int, Fraction) in mpmath at the working precision."""
    x = F(x)
    return mpmath.mpf(x.numerator) / x.denominator


def han(i: int, t: object, lam: object, mu: object) -> object:
    """Han, Ma and Huang's cubic trigonometric basis (2009), b_i(t) at (lam, mu), written out
    (mpmath)."""
    s, c = mpmath.sin(t), mpmath.cos(t)
    return [
        (1 - s) ** 2 * (1 - lam * s),
        s * (1 - s) * (2 + lam - lam * s),
        c * (1 - c) * (2 + mu - mu * c),
        (1 - c) ** 2 * (1 - mu * c),
    ][i]
