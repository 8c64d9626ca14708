r"""Certified extremes of curves over centred atoms (hazmat.atoms): rigorous enclosures of a
coordinate and its derivatives on intervals of τ, and the branch and bound built on them for
tight boxes and closest points.

A curve here is (A, d) coefficients over the centred atoms 1, τ, …, τ^K, cos(jωτ), sin(jωτ)
(or cosh, sinh), j = 1..J. Differentiation is a matrix (`atoms.derivative_matrix`), so the
k-th derivative is the same kind of sum with the coefficients D^k C.

**Enclosure** of f = f^(k) on [c − h, c + h] (Taylor's theorem with Lagrange's remainder):

    f(c + s) ∈ Σ_{j<N} f^(j)(c) s^j / j! + [−1, 1] · M h^N / N!,   M = sup |f^(N)| on the interval,

with M bounded term by term: Σ_a |g_a| · sup|atom_a|, g = D^(k+N) C, where sup|τ^p| is
max(|lo|, |hi|)^p, sup|cos|, |sin| ≤ 1 and sup|cosh|, |sinh| ≤ cosh(jω max|τ|). The
polynomial part is bounded by f(c) ± Σ_{j≥1} |f^(j)(c)| h^j / j!. Every float that enters is
widened by an allowance for its rounding: the atoms at c are computed directly (np.cos(jωc),
not the Chebyshev recurrence, so each has an error of a few ulps plus the rounding of its
argument, ≤ u·jω|c|), a dot product of A terms adds A ulps of Σ|terms| (`_allowance`). So the
enclosure holds for the curve as its float coefficients define it, assuming numpy's sin, cos
and exp are within 4 ulps (they are within 1 to 4 ulps on every platform numpy supports).

**Box** (`coordinate_extremes`): for each coordinate, intervals are dropped when the
enclosure of x lies within the extremes found so far, or when x' has one sign on it (x is
monotone: its extremes there are at the ends, which are candidates), or when x'' has one
sign (x' is monotone: at most one critical point, found by bisection on x'); every other
interval is halved. What is returned is the best of the candidates: no point of the curve
lies beyond it by more than `AtomCurveData.tolerance` (twice the enclosures' rounding
allowance, a few hundred ulps of the coordinate's size), the slack of the value test that lets
flat stretches end the search.

**Closest point** (`closest`): the same on D(τ) = |C(τ) − q|², with interval products for
D ≥ Σ_c min (x_c − q_c)², D' = 2 (C − q)·C' and D'' = 2 (|C'|² + (C − q)·C''), and the
second-order bound D ≥ D(c) − |D'(c)| h − sup|D''| h²/2 (which ends the search where D is
flat, e.g. along a circle about q). The squared distance returned is within the tolerance
carried into D of the global minimum.

Intervals narrower than NARROW (relative to the domain) that are still open are settled by
their middle; `Stats.narrow` counts them (0 in every certified answer the tests check).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from math import factorial
from typing import Any

import numpy as np

from . import atoms as ak

ORDER = 3  # N: Taylor terms at the centre before the remainder
START = 16  # intervals of the first level
NARROW = 2.0**-44  # an open interval this narrow (relative to the domain) is settled by its middle
MAX_ROUNDS = 200
MAX_OPEN = 1 << 17  # open intervals beyond this are settled by their middles (counted)
_U = 2.0**-53


@dataclass
class Stats:
    """How a branch and bound went: intervals examined, rounds, intervals settled by their
    middle only (not certified there)."""

    intervals: int = 0
    rounds: int = 0
    narrow: int = 0


@dataclass
class AtomCurveData:
    """A curve over centred atoms: `coefficients` (A, d), the space (ω, K, J, hyperbolic);
    derivatives' coefficients are made on demand."""

    coefficients: np.ndarray
    omega0: float
    powers: int
    harmonics: int
    hyperbolic: bool
    _orders: list[np.ndarray] = field(default_factory=list)

    def __post_init__(self) -> None:
        self._orders = [np.asarray(self.coefficients, dtype=float)]
        self._d = ak.derivative_matrix(self.omega0, self.powers, self.harmonics, self.hyperbolic)

    @property
    def size(self) -> int:
        return 1 + self.powers + 2 * self.harmonics

    def order(self, k: int) -> np.ndarray:
        while len(self._orders) <= k:
            self._orders.append(self._d @ self._orders[-1])
        return self._orders[k]

    def values(self, k: int, tau: np.ndarray) -> np.ndarray:
        """(d, len(tau)): the k-th derivative at τ (the fast evaluation of hazmat.atoms)."""
        return ak.evaluate(
            self.order(k), tau, self.omega0, self.powers, self.harmonics, self.hyperbolic
        )

    # ------------------------------------------------------------------ enclosures
    def _direct_atoms(self, tau: np.ndarray) -> np.ndarray:
        """(A, m): the atoms at τ, each computed on its own (no recurrence)."""
        out = np.empty((self.size, tau.size))
        out[0] = 1.0
        for p in range(1, self.powers + 1):
            out[p] = tau**p
        base = 1 + self.powers
        for j in range(1, self.harmonics + 1):
            x = (j * self.omega0) * tau
            c = base + 2 * (j - 1)
            if self.hyperbolic:
                out[c], out[c + 1] = np.cosh(x), np.sinh(x)
            else:
                out[c], out[c + 1] = np.cos(x), np.sin(x)
        return out

    def _sup_atoms(self, reach: np.ndarray) -> np.ndarray:
        """(A, m): upper bounds of |atom| on intervals with max |τ| = reach."""
        out = np.ones((self.size, reach.size))
        for p in range(1, self.powers + 1):
            out[p] = reach**p * (1 + 4 * p * _U)
        if self.hyperbolic:
            base = 1 + self.powers
            for j in range(1, self.harmonics + 1):
                c = base + 2 * (j - 1)
                out[c] = out[c + 1] = np.cosh((j * self.omega0) * reach) * (1 + 8 * _U) + 1e-300
        return out

    def _allowance(self, tau: np.ndarray) -> np.ndarray:
        """(m,): the relative rounding allowance of a value at τ, per unit of Σ|terms|."""
        spread = self.harmonics * self.omega0 * np.abs(tau)
        out: np.ndarray = 4 * _U * (self.size + self.powers + 8 + spread)
        return out

    def tolerance(self, lo: float, hi: float) -> np.ndarray:
        """(d,): twice the largest rounding allowance of a value of each coordinate on
        [lo, hi], the slack of the branch and bound's value tests (a few hundred ulps of
        the coordinate's size): intervals whose enclosure lies within it of the best value
        are settled, so flat stretches (a constant coordinate, a circle about the query)
        end the search instead of halving forever."""
        reach = np.array([max(abs(lo), abs(hi))])
        top = (np.abs(self.order(0)).T @ self._sup_atoms(reach))[:, 0]
        out: np.ndarray = 2 * top * self._allowance(reach)[0] + 1e-300
        return out

    def enclose(self, k: int, lo: np.ndarray, hi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(lower, upper), each (d, m): bounds of the k-th derivative on [lo_i, hi_i]."""
        c = 0.5 * (lo + hi)
        h = 0.5 * (hi - lo) * (1 + 2 * _U)
        h = np.maximum(h, np.maximum(hi - c, c - lo))
        atoms = self._direct_atoms(c)
        mag = np.abs(atoms)
        allow = self._allowance(c)
        centre = self.order(k).T @ atoms  # (d, m)
        radius = (np.abs(self.order(k)).T @ mag) * allow
        for j in range(1, ORDER):
            g = self.order(k + j)
            term = np.abs(g.T @ atoms) + (np.abs(g).T @ mag) * allow
            radius = radius + term * (h**j / factorial(j))
        reach = np.maximum(np.abs(lo), np.abs(hi))
        top = np.abs(self.order(k + ORDER)).T @ self._sup_atoms(reach)
        radius = radius + top * (h**ORDER / factorial(ORDER))
        radius = radius * (1 + 16 * _U) + 1e-300
        return centre - radius, centre + radius


# ---------------------------------------------------------------------- the box
def _root_in(f: object, a: float, b: float, fa: float) -> float:
    """A zero of a monotone function with a sign change on [a, b] (bisection to the last bit)."""
    for _ in range(200):
        m = 0.5 * (a + b)
        if m in (a, b):
            break
        fm = f(m)  # type: ignore[operator]
        if fm == 0:
            return m
        if (fm > 0) == (fa > 0):
            a, fa = m, fm
        else:
            b = m
    return 0.5 * (a + b)


def coordinate_extremes(
    curve: AtomCurveData, lo: float, hi: float, stats: Stats | None = None
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(min, max, τ of min, τ of max), each (d,): the certified extremes of every coordinate
    over τ ∈ [lo, hi]."""
    stats = stats if stats is not None else Stats()
    dim = curve.coefficients.shape[1]
    width = hi - lo
    ends = np.array([lo, hi])
    v = curve.values(0, ends)
    slacks = curve.tolerance(lo, hi)
    out = []
    for c in range(dim):
        slack = float(slacks[c])
        cand_t = [lo, hi]
        cand_v = [float(v[c, 0]), float(v[c, 1])]
        edges = np.linspace(lo, hi, START + 1)
        a, b = edges[:-1], edges[1:]
        grid = curve.values(0, np.concatenate([a, [hi]]))[c]
        cand_t += list(a)
        cand_v += list(grid[:-1])
        rounds = 0
        while a.size:
            rounds += 1
            stats.rounds += 1
            stats.intervals += a.size
            top, bottom = max(cand_v), min(cand_v)
            vlo, vhi = curve.enclose(0, a, b)
            inside = (vhi[c] <= top + slack) & (vlo[c] >= bottom - slack)
            dlo, dhi = curve.enclose(1, a, b)
            monotone = ((dlo[c] > 0) | (dhi[c] < 0)) & ~inside
            slo, shi = curve.enclose(2, a, b)
            bent = ((slo[c] > 0) | (shi[c] < 0)) & ~monotone & ~inside
            # x' monotone: at most one critical point, found by bisection on x'
            for x, y in zip(a[bent], b[bent], strict=True):

                def slope(t: float, c: int = c) -> float:
                    return float(curve.values(1, np.array([t]))[c, 0])

                fa, fb = slope(x), slope(y)
                if fa != 0 and fb != 0 and (fa > 0) != (fb > 0):
                    r = _root_in(slope, x, y, fa)
                    cand_t.append(r)
                    cand_v.append(float(curve.values(0, np.array([r]))[c, 0]))
            # the ends of a monotone or bent interval are candidates (its other extremes)
            ended = monotone | bent
            if ended.any():
                pts = np.concatenate([a[ended], b[ended]])
                cand_t += list(pts)
                cand_v += list(curve.values(0, pts)[c])
            keep = ~(inside | ended)
            a, b = a[keep], b[keep]
            # (called at once, inside this round: the lambda sees this c)
            a, b = _settle_and_halve(
                a,
                b,
                width,
                rounds,
                stats,
                lambda t: curve.values(0, t)[c],  # noqa: B023
                cand_t,
                cand_v,
            )
        arr = np.array(cand_v)
        i, j = int(np.argmin(arr)), int(np.argmax(arr))
        out.append((arr[i], arr[j], cand_t[i], cand_t[j]))
    mins, maxs, tmins, tmaxs = (np.array(col, dtype=float) for col in zip(*out, strict=True))
    return mins, maxs, tmins, tmaxs


def _settle_and_halve(
    a: np.ndarray,
    b: np.ndarray,
    width: float,
    rounds: int,
    stats: Stats,
    value: Callable[[np.ndarray], np.ndarray],
    cand_t: list[Any],
    cand_v: list[Any],
) -> tuple[np.ndarray, np.ndarray]:
    """One round's end for the open intervals [a, b] of a branch and bound: those narrower
    than NARROW * width (all of them past MAX_ROUNDS or MAX_OPEN) are settled by their middle
    (not certified: counted in stats.narrow), the others halved; every middle becomes a
    candidate (cand_t, cand_v, with `value` at it). Returns the halves."""
    done = (b - a) <= NARROW * width
    if rounds >= MAX_ROUNDS or a.size > MAX_OPEN:
        done = np.ones_like(done)
    if done.any():
        mids = 0.5 * (a[done] + b[done])
        stats.narrow += int(done.sum())
        cand_t += list(mids)
        cand_v += list(value(mids))
        a, b = a[~done], b[~done]
    mid = 0.5 * (a + b)
    if mid.size:
        cand_t += list(mid)
        cand_v += list(value(mid))
    return np.concatenate([a, mid]), np.concatenate([mid, b])


# ---------------------------------------------------------------------- closest points
def _products(
    alo: np.ndarray, ahi: np.ndarray, blo: np.ndarray, bhi: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Interval products, elementwise, widened by their rounding."""
    p = np.stack([alo * blo, alo * bhi, ahi * blo, ahi * bhi])
    low, high = p.min(axis=0), p.max(axis=0)
    pad = 4 * _U * np.maximum(np.abs(low), np.abs(high))
    return low - pad, high + pad


def _squares(alo: np.ndarray, ahi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    low = np.where((alo <= 0) & (ahi >= 0), 0.0, np.minimum(alo * alo, ahi * ahi))
    high = np.maximum(alo * alo, ahi * ahi)
    return low * (1 - 4 * _U), high * (1 + 4 * _U)


def _sum(lo: np.ndarray, hi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    s_lo, s_hi = lo.sum(axis=0), hi.sum(axis=0)
    pad = 2 * lo.shape[0] * _U * (np.abs(lo).sum(axis=0) + np.abs(hi).sum(axis=0))
    return s_lo - pad, s_hi + pad


def _distance2(curve: AtomCurveData, q: np.ndarray, tau: np.ndarray) -> np.ndarray:
    return np.square(curve.values(0, tau) - q[:, None]).sum(axis=0)  # type: ignore[no-any-return]


def _dslope(curve: AtomCurveData, q: np.ndarray, t: float) -> float:
    x = np.array([t])
    return float((curve.values(0, x)[:, 0] - q) @ curve.values(1, x)[:, 0])


def closest(
    curve: AtomCurveData, q: np.ndarray, lo: float, hi: float, stats: Stats | None = None
) -> tuple[float, float]:
    """(τ, squared distance) of the point of the curve over [lo, hi] nearest q (d,): the
    certified global minimum of |C(τ) − q|²."""
    stats = stats if stats is not None else Stats()
    width = hi - lo
    tol = float(curve.tolerance(lo, hi).max())
    dim = q.size
    edges = np.linspace(lo, hi, START + 1)
    cand_t = list(edges)
    cand_v = list(_distance2(curve, q, edges))
    a, b = edges[:-1], edges[1:]
    rounds = 0
    while a.size:
        rounds += 1
        stats.rounds += 1
        stats.intervals += a.size
        best = min(cand_v)
        xlo, xhi = curve.enclose(0, a, b)
        xlo, xhi = xlo - q[:, None], xhi - q[:, None]
        plo, phi = curve.enclose(1, a, b)
        slo, shi = curve.enclose(2, a, b)
        g_lo, g_hi = _sum(*_products(xlo, xhi, plo, phi))  # D'/2 on the interval
        sq_lo, sq_hi = _sum(*_squares(plo, phi))
        cr_lo, cr_hi = _sum(*_products(xlo, xhi, slo, shi))
        bend = np.maximum(np.abs(sq_lo + cr_lo), np.abs(sq_hi + cr_hi))  # sup |D''/2|
        # D >= min of the squares of the enclosures, and (second order, for flat D) D >= D(c)
        # - |D'(c)| h - sup|D''| h^2 / 2, with D(c), D'(c) enclosed at the point c itself
        mid = 0.5 * (a + b)
        h = 0.5 * (b - a) * (1 + 4 * _U)
        clo, chi = curve.enclose(0, mid, mid)
        clo, chi = clo - q[:, None], chi - q[:, None]
        dlo, dhi = curve.enclose(1, mid, mid)
        at_lo, _ = _sum(*_squares(clo, chi))
        gc_lo, gc_hi = _sum(*_products(clo, chi, dlo, dhi))
        taylor = at_lo - 2 * np.maximum(np.abs(gc_lo), np.abs(gc_hi)) * h - bend * h * h
        taylor = taylor - 8 * _U * np.abs(taylor)
        d2lo = np.maximum(_sum(*_squares(xlo, xhi))[0], taylor)
        # the slack: the rounding allowance of a coordinate carried into D, and D's own
        far = d2lo >= best - dim * (2 * np.sqrt(best) * tol + tol * tol) - 16 * dim * _U * best
        monotone = ((g_lo > 0) | (g_hi < 0)) & ~far
        convex = (sq_lo + cr_lo > 0) & ~far & ~monotone
        if monotone.any():
            pts = np.where(g_lo[monotone] > 0, a[monotone], b[monotone])
            cand_t += list(pts)
            cand_v += list(_distance2(curve, q, pts))
        for x, y in zip(a[convex], b[convex], strict=True):
            fa, fb = _dslope(curve, q, x), _dslope(curve, q, y)
            if fa < 0 < fb:
                r = _root_in(lambda t: _dslope(curve, q, t), x, y, fa)
            else:
                r = x if fa >= 0 else y
            cand_t.append(r)
            cand_v.append(float(_distance2(curve, q, np.array([r]))[0]))
        keep = ~(far | monotone | convex)
        a, b = a[keep], b[keep]
        a, b = _settle_and_halve(
            a, b, width, rounds, stats, lambda t: _distance2(curve, q, t), cand_t, cand_v
        )
    k = int(np.argmin(cand_v))
    return float(cand_t[k]), float(cand_v[k])
