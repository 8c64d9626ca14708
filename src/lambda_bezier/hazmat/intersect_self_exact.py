"""Exact, certified isolation of the self-crossings of a planar curve with rational control points.

A curve p crosses itself where p(s) = p(t) with s ≠ t. Every coordinate of p(s) − p(t) has the
factor s − t, whose zeros (the whole diagonal) are not crossings; divided out exactly, the
divided differences

    G_c(s, t) = (p_c(s) − p_c(t)) / (s − t),     c = x, y,

are polynomials symmetric in s and t with G_c(s, s) = p_c'(s), and the self-crossings are
exactly the common zeros of G_x, G_y with s ≠ t (on the diagonal they vanish together only at
a cusp, p'(s) = 0, which is not a crossing). The zeros are isolated on the engine of two
curves (intersect_exact.isolate_system, in its symmetric mode: one resultant in one variable,
its real roots in [0, 1] isolated exactly, the i-th paired with the j-th for i < j only, each
box proved to hold exactly one zero by Krawczyk's test in rational interval arithmetic, or
decided algebraically where Krawczyk cannot contract). At a zero with s ≠ t the Jacobian of G
is that of p(s) − p(t) divided by s − t (the other term carries p(s) − p(t) = 0 as a factor),
so it is singular exactly where the two branches are tangent: a self-tangency comes out once,
``tangent``. Rational curves (Fraction weights) use X_c(s) W(t) − X_c(t) W(s), X_c the
homogeneous coordinates: it vanishes exactly where p(s) = p(t) (W > 0) and carries the same
factor s − t.
"""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction

from . import exact_poly as xp
from . import intersect_exact as ie

# The curve's degree up to which self_intersections decides exactly, by algebra. The divided
# differences have degree n − 1 in each variable (one resultant of degree (n − 1)², symmetric),
# and cost less than two curves of degree n − 1: measured (process time, load average 6-8 on
# 2 cores) on rotated curves with a self-tangency and with two crossings 1e-9 apart, FLINT
# 0.05-0.1 s at degree 6-8 (0.26 s at 10), the standard library 0.04-0.3 s at degree 6 (0.9 s
# at 8); random integer curves of degree 3-8 (transversal crossings) 1-21 ms with FLINT, up to
# 0.09 s at degree 5 without.
SELF_DEGREE = {"exact_flint": 8, "exact_poly": 6}
# The same for rational curves (weights), whose divided differences have degree n in each
# variable: random integer curves with weights 1-5, FLINT 1-46 ms up to degree 6 (0.17 s at
# 7); the standard library 0.14 s at degree 4, 0.3-0.5 s at 5 but over 40 s on a weighted
# quintic with two crossings (the same load).
SELF_DEGREE_RATIONAL = {"exact_flint": 6, "exact_poly": 4}


def divided_by_diagonal(h: xp.Bivariate) -> xp.Bivariate:
    """h(s, t) / (s − t), exactly; h must vanish on the diagonal (ValueError otherwise).
    Synthetic division in s with coefficients polynomials in t: with h = Σ h_i(t) s^i,
    the quotient's q_(n−1) = h_n and q_(i−1) = h_i + t q_i; the remainder h_0 + t q_0 is 0."""
    if not h:
        return {}
    n = max(i for i, _ in h)
    rows: list[dict[int, Fraction]] = [{} for _ in range(n + 1)]
    for (i, j), c in h.items():
        rows[i][j] = c
    out: xp.Bivariate = {}
    carry: dict[int, Fraction] = {}  # q_i, as {power of t: coefficient}
    for i in range(n, 0, -1):
        q = dict(rows[i])
        for j, c in carry.items():  # + t q_i
            q[j + 1] = q.get(j + 1, Fraction(0)) + c
        q = {j: c for j, c in q.items() if c}
        for j, c in q.items():
            out[(i - 1, j)] = c
        carry = q
    remainder = dict(rows[0])
    for j, c in carry.items():
        remainder[j + 1] = remainder.get(j + 1, Fraction(0)) + c
    if any(remainder.values()):
        raise ValueError("h does not vanish on the diagonal s = t")
    return out


def divided_differences(
    rows: Sequence[Sequence[Fraction]], weights: Sequence[Fraction] | None = None
) -> tuple[xp.Bivariate, xp.Bivariate]:
    """(G_x, G_y) of the module's docstring for the planar Bézier curve with control points
    rows (and positive weights, for a rational curve)."""
    if weights is None:
        weights = [Fraction(1)] * len(rows)
    w = ie.power_coefficients([(Fraction(x),) for x in weights], 0)
    out = []
    for axis in (0, 1):
        x = ie.power_coefficients(
            [(Fraction(r[axis]) * Fraction(c),) for r, c in zip(rows, weights, strict=True)], 0
        )
        h: xp.Bivariate = {}
        for i, a in enumerate(x):  # X(s) W(t) − X(t) W(s)
            for j, b in enumerate(w):
                if a and b:
                    h[(i, j)] = h.get((i, j), Fraction(0)) + a * b
                    h[(j, i)] = h.get((j, i), Fraction(0)) - a * b
        out.append(divided_by_diagonal({k: v for k, v in h.items() if v}))
    return out[0], out[1]


def isolate_self(
    rows: Sequence[Sequence[Fraction]],
    narrow: Fraction | None = None,
    alg: ie.Algebra | None = None,
    weights: Sequence[Fraction] | None = None,
) -> list[ie.ExactCrossing]:
    """The self-crossings s < t of the planar curve with exact control points rows (and
    weights), as boxes of Fractions sorted by s (intersect_exact.isolate_system); with
    `narrow`, each box refined to that width. ValueError when the curve has no finite set of
    self-crossings (it runs back along itself: the resultant vanishes identically; or a
    coordinate's divided difference vanishes identically: the curve lies on a line)."""
    gx, gy = divided_differences(rows, weights)
    if not gx or not gy:
        raise ValueError("a coordinate is constant: the curve lies on a line")
    return ie.isolate_system(gx, gy, narrow, alg, symmetric=True)


def self_exact_answer(
    rows: Sequence[Sequence[Fraction]],
    alg: ie.Algebra | None = None,
    weights: Sequence[Fraction] | None = None,
) -> list[tuple[float, float, bool]] | None:
    """Every self-crossing as (s, t, tangent): each box of isolate_self refined to
    intersect_exact.NARROW and rounded at its middle; None when a box is left undecided or
    there is no finite set of self-crossings (the float answer stands then)."""
    try:
        boxes = isolate_self(rows, ie.NARROW, alg, weights)
    except ValueError:
        return None
    if not all(c.certified for c in boxes):
        return None
    return [(float((c.s[0] + c.s[1]) / 2), float((c.t[0] + c.t[1]) / 2), c.tangent) for c in boxes]


def self_decided(
    rows: Sequence[Sequence[Fraction]] | None,
    dim: int,
    alg: ie.Algebra | None = None,
    weights: Sequence[Fraction] | None = None,
) -> list[tuple[float, float, bool]] | None:
    """self_intersections' answer decided exactly (self_exact_answer) for exact planar input,
    or None (the float answer stands): float input, not planar, a box left undecided, no
    finite set of self-crossings, or a system past the algebra's budget. The divided
    differences have degree n − 1 each (n the curve's degree): up to SELF_DEGREE[alg.name]
    for polynomial curves, SELF_DEGREE_RATIONAL[alg.name] for rational ones."""
    alg = alg or ie.algebra()
    if rows is None or dim != 2:
        return None
    budget = SELF_DEGREE if weights is None else SELF_DEGREE_RATIONAL
    if len(rows) - 1 > budget[alg.name]:
        return None
    return self_exact_answer(rows, alg, weights)
