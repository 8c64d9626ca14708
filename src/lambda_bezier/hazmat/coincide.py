"""Shared stretches of two rational curves, from their homogeneous rows (a polynomial curve is
the rational curve with weights 1), under any parameterisation: decided exactly when both
curves' rows are exact (Fractions), to the rounding of evaluation otherwise.

Two curves share a stretch when (a) their images lie on one algebraic curve and (b) their
parameter ranges overlap along it.

(a) The image of a rational curve p of degree n_p is irreducible, of degree at most n_p. So it
    lies on q's curve (the Zariski closure of q's image) as soon as more than n_p n_q distinct
    points of it do (Bezout; in 3D after a projection that keeps two distinct curves distinct).
    A point x is on q's curve exactly when the d polynomials A_c(t) − x_c w(t) (A = w q, the
    homogeneous rows) have a common root t, complex or at infinity: their gcd over Q is not
    constant, or they all drop degree (the root t = ∞). Exact rows: decided in Fractions
    (`exact_same_curve`). Float rows: the polynomial path's rule (hazmat.intersect._runs_along:
    n_p n_q + 1 points of p's arc located on q's arc, in order, each within `tol`).
(b) A stretch's ends are ends of p or of q, located on the other curve (exact rows: the real
    roots in [0, 1] of that gcd, isolated by Sturm sequences, exact_poly). Two end pairs bound
    a shared stretch when points of p's arc between them are located on q's arc between them,
    in the same order, and the same the other way round (two arcs of one curve with the same
    ends either agree or run round different ways, and a fold back would break the order).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from fractions import Fraction
from typing import NamedTuple

import numpy as np

from . import exact_poly as xp
from . import rational_kernels as rk
from .intersect_exact import power_coefficients

SAME = 1e-9  # two located end parameters closer than this are one end
ROOT_WIDTH = Fraction(1, 1 << 60)  # exact locations are refined to this width, then rounded
ExactRows = Sequence[Sequence[Fraction]]


class Stretch(NamedTuple):
    """p over [s0, s1] and q between t0 and t1 (t0 > t1 when q runs the other way) are one
    arc: p(s0) = q(t0), p(s1) = q(t1)."""

    s0: float
    s1: float
    t0: float
    t1: float


class Side(NamedTuple):
    """One curve as the decision uses it: its point at a parameter, and every parameter in
    [lo, hi] where it passes through a given point of the other curve."""

    point: Callable[[float], object]
    locate: Callable[[object, float, float], list[float]]
    degree: int


# ------------------------------------------------------------------------------- exact rows
def exact_point(rows: ExactRows, s: Fraction) -> tuple[Fraction, ...]:
    """The curve's point at s, exactly (de Casteljau on the homogeneous rows)."""
    work = [list(r) for r in rows]
    for k in range(len(work) - 1, 0, -1):
        work = [
            [(1 - s) * a + s * b for a, b in zip(work[i], work[i + 1], strict=True)]
            for i in range(k)
        ]
    *num, w = work[0]
    return tuple(c / w for c in num)


def _common_factor(rows: ExactRows, point: Sequence[Fraction]) -> tuple[xp.Poly, bool]:
    """(gcd over Q of A_c(t) − x_c w(t), c = 1..d; whether they all drop degree)."""
    d = len(rows[0]) - 1
    n = len(rows) - 1
    w = power_coefficients(rows, d)
    g: xp.Poly = []
    at_infinity = True
    for c in range(d):
        f = [a - point[c] * b for a, b in zip(power_coefficients(rows, c), w, strict=True)]
        at_infinity &= f[n] == 0
        g = xp.gcd(g, f)
    return g, at_infinity


def on_curve(rows: ExactRows, point: Sequence[Fraction]) -> bool:
    """Whether the point lies on the algebraic curve of the rows (complex t or t = ∞ too)."""
    g, at_infinity = _common_factor(rows, point)
    return len(g) != 1 or at_infinity


def exact_locate(rows: ExactRows, point: Sequence[Fraction], lo: float, hi: float) -> list[float]:
    """Every t in [lo, hi] with curve(t) = point, exactly isolated (then rounded)."""
    g, _ = _common_factor(rows, point)
    if len(g) <= 1:
        return [] if g else [lo]  # a constant curve at the point: every t (degenerate)
    out = []
    for root in xp.real_roots(g, Fraction(lo), Fraction(hi)):
        if isinstance(root, tuple):
            root = xp.refine(xp.squarefree(g), root, ROOT_WIDTH)
        out.append(float(root) if isinstance(root, Fraction) else float(sum(root) / 2))
    return out


def exact_same_curve(p: ExactRows, q: ExactRows) -> bool:
    """Whether p's image lies on q's algebraic curve: n_p n_q + 1 distinct points of p on it."""
    need = (len(p) - 1) * (len(q) - 1) + 1
    seen: set[tuple[Fraction, ...]] = set()
    count = 2 * need + 2
    for k in range(4 * count + 1):
        # the points of [0, 1] at k / count first, then in between (distinct points needed)
        s = Fraction(k, count) if k <= count else Fraction(2 * (k - count) - 1, 6 * count)
        x = exact_point(p, s)
        if x in seen:
            continue
        if not on_curve(q, x):
            return False
        seen.add(x)
        if len(seen) >= need:
            return True
    return False


def exact_side(rows: ExactRows) -> Side:
    def point(s: float) -> object:
        return exact_point(rows, Fraction(s))

    def locate(x: object, lo: float, hi: float) -> list[float]:
        return exact_locate(rows, x, lo, hi)  # type: ignore[arg-type]

    return Side(point, locate, len(rows) - 1)


# ------------------------------------------------------------------------------- float rows
def _eval(rows: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    h, dh = rk.homogeneous_derivatives(rows, t, 1)
    c = h[:, :-1] / h[:, -1:]
    dc = (dh[:, :-1] - c * dh[:, -1:]) / h[:, -1:]
    return c, dc


def float_side(rows: np.ndarray, tol: float) -> Side:
    """Location to within tol: the critical points of |A − x w|² in [0, 1] (roots of
    (A − x w) · (A − x w)′), polished by Newton on the projection, kept within tol of x."""

    def point(s: float) -> object:
        return _eval(rows, np.array([s]))[0][0]

    def locate(x: object, lo: float, hi: float) -> list[float]:
        xv = np.asarray(x, dtype=float)
        diff = rows[:, :-1] - xv[None, :] * rows[:, -1:]
        g = rk.product(diff, rk.hodograph(diff)).sum(axis=-1)
        t = np.concatenate([[0.0, 1.0], rk.roots_in_unit(rk.bernstein_to_centred(g))])
        for _ in range(6):
            c, dc = _eval(rows, t)
            with np.errstate(divide="ignore", invalid="ignore"):
                step = ((c - xv) * dc).sum(-1) / (dc * dc).sum(-1)
            t = np.where(np.isfinite(step), np.clip(t - step, 0.0, 1.0), t)
        c, _ = _eval(rows, t)
        near = np.sort(t[(np.linalg.norm(c - xv, axis=-1) <= tol) & (t >= lo) & (t <= hi)])
        out: list[float] = []
        for v in near.tolist():
            if not out or v - out[-1] > SAME:
                out.append(v)
        return out

    return Side(point, locate, rows.shape[0] - 1)


# ------------------------------------------------------------------------------- stretches
def _runs_along(p: Side, q: Side, a: Stretch, count: int) -> bool:
    """count points of p's arc [a.s0, a.s1] lie on q's arc between a.t0 and a.t1, each at
    exactly one t, in the same order (hazmat.intersect._runs_along's rule)."""
    lo, hi = min(a.t0, a.t1) - SAME, max(a.t0, a.t1) + SAME
    located = []
    for k in range(count):
        u = (k + 0.5) / count
        on_q = q.locate(p.point(a.s0 + u * (a.s1 - a.s0)), lo, hi)
        if len(on_q) != 1:
            return False
        located.append(on_q[0])
    return bool(np.all(np.diff(located) * np.sign(a.t1 - a.t0) > 0))


def stretches(p: Side, q: Side, count: int) -> list[Stretch]:
    """The stretches p and q share, each from its two end pairs, sorted by s0 (s0 < s1).
    count: points located each way on every candidate arc (3 once (a) is decided exactly,
    else n_p n_q + 1)."""
    ends: list[tuple[float, float]] = []
    for s_end in (0.0, 1.0):
        ends += [(s_end, t) for t in q.locate(p.point(s_end), 0.0, 1.0)]
    for t_end in (0.0, 1.0):
        ends += [(s, t_end) for s in p.locate(q.point(t_end), 0.0, 1.0)]
    unique: list[tuple[float, float]] = []
    for e in sorted(ends):
        for k, u in enumerate(unique):
            if abs(e[0] - u[0]) < SAME and abs(e[1] - u[1]) < SAME:
                # one end found from both curves: keep each parameter where it is an end
                unique[k] = (
                    e[0] if e[0] in (0.0, 1.0) else u[0],
                    e[1] if e[1] in (0.0, 1.0) else u[1],
                )
                break
        else:
            unique.append(e)
    out: list[Stretch] = []
    for i, a in enumerate(unique):
        for b in unique[i + 1 :]:
            if abs(a[0] - b[0]) < SAME or abs(a[1] - b[1]) < SAME:
                continue
            cand = Stretch(a[0], b[0], a[1], b[1])
            back = (
                Stretch(a[1], b[1], a[0], b[0]) if a[1] < b[1] else Stretch(b[1], a[1], b[0], a[0])
            )
            if _runs_along(p, q, cand, count) and _runs_along(q, p, back, count):
                out.append(cand)
    return sorted(out)
