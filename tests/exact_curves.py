"""Exact reference computations on Bézier control points in Fractions, shared by the tests:
the Bernstein sum at a parameter, the hodograph, a rational curve's point and tangent, and a
curve reflected in its own tangent line (the tangency fixtures of issue #29).

Independent of the library: nothing here calls lambda_bezier."""

from __future__ import annotations

import math
from fractions import Fraction


def exact_point(rows, t: Fraction) -> tuple[Fraction, ...]:
    """Independent evaluation: Σ C(n,i) t^i (1-t)^(n-i) P_i in Fractions, every coordinate."""
    n = len(rows) - 1
    weights = [math.comb(n, i) * t**i * (1 - t) ** (n - i) for i in range(n + 1)]
    return tuple(
        sum((w * r[c] for w, r in zip(weights, rows, strict=True)), Fraction(0))
        for c in range(len(rows[0]))
    )


def hodograph(rows) -> list[tuple[Fraction, ...]]:
    """The control points of the derivative: n (P_{i+1} - P_i)."""
    n = len(rows) - 1
    return [
        tuple(n * (b - a) for a, b in zip(r0, r1, strict=True))
        for r0, r1 in zip(rows, rows[1:], strict=False)
    ]


def point_and_tangent(rows, weights, t0: Fraction):
    """The rational curve's point at t0 and a tangent vector there (h[-1]^2 times the
    derivative, from the homogeneous form; zero at a cusp or on a point curve). Unit weights
    give the polynomial curve's point and its derivative."""
    hom = [(*(x * w for x in row), w) for row, w in zip(rows, weights, strict=True)]
    h, dh = exact_point(hom, t0), exact_point(hodograph(hom), t0)
    point = tuple(x / h[-1] for x in h[:-1])
    return point, tuple(dx * h[-1] - x * dh[-1] for x, dx in zip(h[:-1], dh[:-1], strict=True))


def reflect_line(point, d, offset: Fraction = Fraction(0)):
    """The affine map reflecting the plane in the line through `point` along `d`, then moving
    by `offset` along the normal (-d_y, d_x); applied to control points, it maps a curve
    touching that line at `point` to a curve touching it there too."""
    dd = d[0] ** 2 + d[1] ** 2

    def reflect(v):
        w = (v[0] - point[0], v[1] - point[1])
        along = (w[0] * d[0] + w[1] * d[1]) / dd
        return (
            point[0] + 2 * along * d[0] - w[0] - offset * d[1],
            point[1] + 2 * along * d[1] - w[1] + offset * d[0],
        )

    return reflect
