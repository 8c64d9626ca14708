r"""Certified extremes of tensor-product surfaces over centred atoms: the bounding box and the
closest point of S(u, v) = Σ_i Σ_j b_i(u) b_j(v) P_ij, each direction's basis functions b_i
given as a curve over centred atoms (`atom_bounds.AtomCurveData` with one "coordinate" per
basis function), for the mixed (algebraic-trigonometric/hyperbolic) families that have no
rational form.

**Enclosures.** On a cell [u0, u1] × [v0, v1], atom_bounds encloses every b_i^(a) on [u0, u1]
and b_j^(b) on [v0, v1] (Taylor form, widened for rounding); S^(a, b) is then enclosed by
interval arithmetic, Σ_ij P_ij [b_i^(a)] [b_j^(b)], every product and sum widened by its
rounding. That enclosure is first order (it forgets that Σ b_i = 1), so the bound used for a
scalar f (a coordinate, or D = |S − q|²) is the better of it and the second-order form

    f(c + δ) ≤ f(c) + |f_u(c)| h_u + |f_v(c)| h_v + (M_uu h_u² + 2 M_uv h_u h_v + M_vv h_v²)/2,

(Taylor with Lagrange's remainder in two variables), f and ∇f enclosed at the centre c and
M_ab ≥ sup |f_ab| over the cell, with D_uu = 2 (S_u·S_u + (S − q)·S_uu) and so on.

**Faces.** The domain is the union of its interior, its four open edges and its four
corners. The global maximum p of f lies in the relative interior of one of them, where the
derivatives of f along that face's free directions vanish. So the branch and bound runs on
cells of every face together (an edge's cells have width 0 across it): a cell is dropped when
a free direction's derivative has one sign on it (p is not in it), or when its bound is within
the slack of the best value found (f ≤ that bound there); otherwise it is halved in its free
directions and its centre becomes a candidate. The corners are candidates.

**What is returned** is the best value found (attained, at a point returned with it) and the
certified bound: the largest bound of a cell dropped by its value, so the true extreme lies
between the two, and they differ by at most the slack (`SurfaceData.slack`, a few hundred ulps
of the surface's size; for the closest point, that slack carried into D). Cells narrower than
NARROW that are still open are settled by their bound (still certified, but maybe looser than
the slack; `Stats.narrow` counts them, 0 in every answer the tests check).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from .atom_bounds import AtomCurveData, Stats, _products, _squares, _sum

START = 8  # cells per direction of the first level
NARROW = 2.0**-40  # a cell this narrow (relative to the domain) in every free direction is settled
MAX_ROUNDS = 120
MAX_OPEN = 1 << 15
NEWTON_STEPS = 12
_U = 2.0**-53

Pair = tuple[np.ndarray, np.ndarray]


def _times_net(lo: np.ndarray, hi: np.ndarray, net: np.ndarray) -> Pair:
    """Σ_ij P_ij [lo_ij, hi_ij]: (n+1, q+1, m) intervals and net (n+1, q+1, d) -> (d, m)."""
    p = net[:, :, :, None]
    a, b = lo[:, :, None, :] * p, hi[:, :, None, :] * p
    low, high = np.minimum(a, b), np.maximum(a, b)
    pad = 2 * _U * np.maximum(np.abs(low), np.abs(high))
    low, high = low - pad, high + pad
    rows = net.shape[0] * net.shape[1]
    return _sum(low.reshape(rows, *low.shape[2:]), high.reshape(rows, *high.shape[2:]))


@dataclass
class SurfaceData:
    """A surface over centred atoms: each direction's basis as an AtomCurveData (coordinates
    = basis functions) on its centred domain [lo, hi], and the net (n+1, q+1, d) in floats."""

    basis_u: AtomCurveData
    basis_v: AtomCurveData
    domain_u: tuple[float, float]
    domain_v: tuple[float, float]
    net: np.ndarray

    def values(self, a: int, b: int, u: np.ndarray, v: np.ndarray) -> np.ndarray:
        """(m, d): S^(a, b) at paired centred parameters, in floats."""
        bu, bv = self.basis_u.values(a, u), self.basis_v.values(b, v)
        out: np.ndarray = np.einsum("im,ijd,jm->md", bu, self.net, bv, optimize=True)
        return out

    def enclose(
        self, a: int, b: int, u0: np.ndarray, u1: np.ndarray, v0: np.ndarray, v1: np.ndarray
    ) -> Pair:
        """(lower, upper), each (d, m): bounds of S^(a, b) on the cells [u0, u1] × [v0, v1]."""
        ulo, uhi = self.basis_u.enclose(a, u0, u1)
        vlo, vhi = self.basis_v.enclose(b, v0, v1)
        plo, phi = _products(ulo[:, None, :], uhi[:, None, :], vlo[None, :, :], vhi[None, :, :])
        return _times_net(plo, phi, self.net)

    def slack(self) -> np.ndarray:
        """(d,): the value tests' slack per coordinate: twice the rounding allowance of a
        value (each direction's, relative to Σ|terms|) times a bound of |S| on the domain."""
        lo, hi = self.enclose(0, 0, *_whole(self.domain_u), *_whole(self.domain_v))
        top = np.maximum(np.abs(lo), np.abs(hi))[:, 0]
        reach = np.array([max(map(abs, self.domain_u)), max(map(abs, self.domain_v))])
        allow = self.basis_u._allowance(reach[:1])[0] + self.basis_v._allowance(reach[1:])[0]
        out: np.ndarray = 4 * top * allow + 1e-300
        return out


def _whole(dom: tuple[float, float]) -> tuple[np.ndarray, np.ndarray]:
    return np.array([dom[0]]), np.array([dom[1]])


@dataclass
class _Cells:
    u0: np.ndarray
    u1: np.ndarray
    v0: np.ndarray
    v1: np.ndarray

    @property
    def free_u(self) -> np.ndarray:
        out: np.ndarray = self.u1 > self.u0
        return out

    @property
    def free_v(self) -> np.ndarray:
        out: np.ndarray = self.v1 > self.v0
        return out

    def take(self, keep: np.ndarray) -> _Cells:
        return _Cells(self.u0[keep], self.u1[keep], self.v0[keep], self.v1[keep])

    def centres(self) -> tuple[np.ndarray, np.ndarray]:
        return 0.5 * (self.u0 + self.u1), 0.5 * (self.v0 + self.v1)

    def halves(self) -> _Cells:
        """Every cell cut in two in each free direction (four, two or one pieces)."""
        uc, vc = self.centres()
        parts = []
        for ua, ub in ((self.u0, uc), (uc, self.u1)):
            for va, vb in ((self.v0, vc), (vc, self.v1)):
                parts.append((ua, ub, va, vb))
        pieces = [np.concatenate(x) for x in zip(*parts, strict=True)]
        cells = _Cells(*pieces)
        # a direction that is not free gives two equal pieces: keep one
        n = self.u0.size
        dup_u = np.tile(~self.free_u, 4) & (np.repeat(np.arange(4), n) // 2 == 1)
        dup_v = np.tile(~self.free_v, 4) & (np.repeat(np.arange(4), n) % 2 == 1)
        return cells.take(~(dup_u | dup_v))


def _initial_cells(data: SurfaceData) -> tuple[_Cells, np.ndarray, np.ndarray]:
    """The cells of the interior and of the four edges, and the corners (u, v)."""
    (ua, ub), (va, vb) = data.domain_u, data.domain_v
    us, vs = np.linspace(ua, ub, START + 1), np.linspace(va, vb, START + 1)
    gu0, gv0 = np.meshgrid(us[:-1], vs[:-1], indexing="ij")
    gu1, gv1 = np.meshgrid(us[1:], vs[1:], indexing="ij")
    k = np.ones(START)
    u0 = np.concatenate([gu0.ravel(), ua * k, ub * k, us[:-1], us[:-1]])
    u1 = np.concatenate([gu1.ravel(), ua * k, ub * k, us[1:], us[1:]])
    v0 = np.concatenate([gv0.ravel(), vs[:-1], vs[:-1], va * k, vb * k])
    v1 = np.concatenate([gv1.ravel(), vs[1:], vs[1:], va * k, vb * k])
    return _Cells(u0, u1, v0, v1), np.array([ua, ua, ub, ub]), np.array([va, vb, va, vb])


@dataclass
class _Scalar:
    """A scalar's bounds on cells: (lower, upper) of f over each cell, of f_u and f_v over
    each cell, and the second-order form's (lower, upper)."""

    lo: np.ndarray
    hi: np.ndarray
    du: Pair
    dv: Pair


def _second_order(
    cells: _Cells, at: Pair, grad_u: Pair, grad_v: Pair, huu: Pair, huv: Pair, hvv: Pair
) -> Pair:
    """The second-order form's (lower, upper) of f on the cells from enclosures of f, f_u,
    f_v at the centres and of the Hessian over the cells."""
    hu = 0.5 * (cells.u1 - cells.u0) * (1 + 4 * _U)
    hv = 0.5 * (cells.v1 - cells.v0) * (1 + 4 * _U)

    def mag(p: Pair) -> np.ndarray:
        out: np.ndarray = np.maximum(np.abs(p[0]), np.abs(p[1]))
        return out

    spread = mag(grad_u) * hu + mag(grad_v) * hv
    spread = spread + 0.5 * (mag(huu) * hu * hu + 2 * mag(huv) * hu * hv + mag(hvv) * hv * hv)
    spread = spread * (1 + 16 * _U)
    lo, hi = at[0] - spread, at[1] + spread
    pad = 8 * _U * (np.abs(lo) + np.abs(hi))
    return lo - pad, hi + pad


def _coordinate(data: SurfaceData, cells: _Cells, c: int) -> _Scalar:
    args = (cells.u0, cells.u1, cells.v0, cells.v1)
    uc, vc = cells.centres()
    mid = (uc, uc, vc, vc)
    lo, hi = data.enclose(0, 0, *args)
    du, dv = data.enclose(1, 0, *args), data.enclose(0, 1, *args)
    at = data.enclose(0, 0, *mid)
    gu, gv = data.enclose(1, 0, *mid), data.enclose(0, 1, *mid)
    hs = [data.enclose(a, b, *args) for a, b in ((2, 0), (1, 1), (0, 2))]
    pick = [(p[0][c], p[1][c]) for p in (at, gu, gv, *hs)]
    slo, shi = _second_order(cells, *pick)  # type: ignore[arg-type]
    return _Scalar(
        np.maximum(lo[c], slo), np.minimum(hi[c], shi), (du[0][c], du[1][c]), (dv[0][c], dv[1][c])
    )


def _dot(a: Pair, b: Pair) -> Pair:
    return _sum(*_products(a[0], a[1], b[0], b[1]))


def _distance(data: SurfaceData, cells: _Cells, q: np.ndarray) -> _Scalar:
    """Bounds of D = |S − q|² (and of D_u / 2, D_v / 2) on the cells."""
    args = (cells.u0, cells.u1, cells.v0, cells.v1)
    uc, vc = cells.centres()
    mid = (uc, uc, vc, vc)

    def shifted(p: Pair) -> Pair:
        return p[0] - q[:, None], p[1] - q[:, None]

    r = shifted(data.enclose(0, 0, *args))
    su, sv = data.enclose(1, 0, *args), data.enclose(0, 1, *args)
    suu, suv, svv = (data.enclose(a, b, *args) for a, b in ((2, 0), (1, 1), (0, 2)))
    rc = shifted(data.enclose(0, 0, *mid))
    suc, svc = data.enclose(1, 0, *mid), data.enclose(0, 1, *mid)

    def twice(p: Pair) -> Pair:
        return 2 * p[0], 2 * p[1]

    def plus(a: Pair, b: Pair) -> Pair:
        lo, hi = a[0] + b[0], a[1] + b[1]
        pad = 4 * _U * (np.abs(lo) + np.abs(hi))
        return lo - pad, hi + pad

    huu = twice(plus(_sum(*_squares(*su)), _dot(r, suu)))
    huv = twice(plus(_dot(su, sv), _dot(r, suv)))
    hvv = twice(plus(_sum(*_squares(*sv)), _dot(r, svv)))
    at = _sum(*_squares(*rc))
    slo, shi = _second_order(cells, at, twice(_dot(rc, suc)), twice(_dot(rc, svc)), huu, huv, hvv)
    lo, hi = _sum(*_squares(*r))
    return _Scalar(np.maximum(lo, slo), np.minimum(hi, shi), _dot(r, su), _dot(r, sv))


def _one_signed(cells: _Cells, s: _Scalar) -> np.ndarray:
    """Cells on which a free direction's derivative of f keeps one sign."""
    out: np.ndarray = (cells.free_u & ((s.du[0] > 0) | (s.du[1] < 0))) | (
        cells.free_v & ((s.dv[0] > 0) | (s.dv[1] < 0))
    )
    return out


def _minimise(
    data: SurfaceData,
    bounds: Callable[[_Cells], _Scalar],
    value: Callable[[np.ndarray, np.ndarray], np.ndarray],
    slack: Callable[[float], float],
    polish: Callable[[float, float], tuple[float, float]] | None,
    stats: Stats,
) -> tuple[float, float, float, float]:
    """(u, v, best, lower): the least value of f found (at centred (u, v)) and the certified
    lower bound of f over the domain. `bounds` gives f's bounds on cells, `value` f at
    points, `slack(best)` the value test's slack."""
    cells, cu, cv = _initial_cells(data)
    cand_u, cand_v = [cu], [cv]
    cand_f = [value(cu, cv)]
    # the corners (faces of dimension 0) are candidates, and their enclosures bound f there
    lower = float(bounds(_Cells(cu, cu, cv, cv)).lo.min())
    width = max(data.domain_u[1] - data.domain_u[0], data.domain_v[1] - data.domain_v[0])
    rounds = 0
    while cells.u0.size:
        rounds += 1
        stats.rounds += 1
        stats.intervals += cells.u0.size
        allf = np.concatenate(cand_f)
        k = int(np.argmin(allf))
        best = float(allf[k])
        if polish is not None:
            pu, pv = polish(float(np.concatenate(cand_u)[k]), float(np.concatenate(cand_v)[k]))
            cand_u.append(np.array([pu]))
            cand_v.append(np.array([pv]))
            cand_f.append(value(cand_u[-1], cand_v[-1]))
            best = min(best, float(cand_f[-1][0]))
        s = bounds(cells)
        settled = s.lo >= best - slack(best)
        if settled.any():
            lower = min(lower, float(s.lo[settled].min()))
        keep = ~(settled | _one_signed(cells, s))
        cells, low = cells.take(keep), s.lo[keep]
        narrow = np.maximum(cells.u1 - cells.u0, cells.v1 - cells.v0) <= NARROW * width
        if rounds >= MAX_ROUNDS or cells.u0.size > MAX_OPEN:
            narrow = np.ones_like(narrow)
        if narrow.any():
            stats.narrow += int(narrow.sum())
            lower = min(lower, float(low[narrow].min()))
            cells = cells.take(~narrow)
        uc, vc = cells.centres()
        cand_u.append(uc)
        cand_v.append(vc)
        cand_f.append(value(uc, vc))
        cells = cells.halves()
    allf = np.concatenate(cand_f)
    k = int(np.argmin(allf))
    best = float(allf[k])
    return float(np.concatenate(cand_u)[k]), float(np.concatenate(cand_v)[k]), best, min(lower, best)


def coordinate_extremes(
    data: SurfaceData, stats: Stats | None = None
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(inner min, inner max, outer min, outer max), each (d,): for every coordinate the
    least and greatest values attained (at points of the surface) and certified bounds of
    it over the domain, within `SurfaceData.slack` of them."""
    stats = stats if stats is not None else Stats()
    slacks = data.slack()
    dim = data.net.shape[2]
    out = np.empty((4, dim))
    for c in range(dim):
        for sign, inner, outer in ((1.0, 0, 2), (-1.0, 1, 3)):

            def bounds(cells: _Cells, c: int = c, sign: float = sign) -> _Scalar:
                s = _coordinate(data, cells, c)
                if sign > 0:
                    return s
                return _Scalar(-s.hi, -s.lo, s.du, s.dv)

            def value(u: np.ndarray, v: np.ndarray, c: int = c, sign: float = sign) -> np.ndarray:
                out: np.ndarray = sign * data.values(0, 0, u, v)[:, c]
                return out

            slack = float(slacks[c])
            *_, best, lower = _minimise(data, bounds, value, lambda _b: slack, None, stats)
            out[inner, c], out[outer, c] = sign * best, sign * lower
    return out[0], out[1], out[2], out[3]


def closest(
    data: SurfaceData, q: np.ndarray, stats: Stats | None = None
) -> tuple[float, float, float, float]:
    """(u, v, squared distance, certified lower bound of it): the point of the surface
    (centred parameters) nearest q, the global minimum of |S − q|² within the slack of the
    coordinates' rounding carried into D, refined by Newton from the best point found."""
    stats = stats if stats is not None else Stats()
    tol = float(data.slack().max())
    dim = q.size
    (ua, ub), (va, vb) = data.domain_u, data.domain_v

    def value(u: np.ndarray, v: np.ndarray) -> np.ndarray:
        out: np.ndarray = np.square(data.values(0, 0, u, v) - q).sum(axis=1)
        return out

    def slack(best: float) -> float:
        return dim * (2 * np.sqrt(max(best, 0.0)) * tol + tol * tol) + 16 * dim * _U * best

    def polish(u: float, v: float) -> tuple[float, float]:
        """Newton on ∇D = 0 from (u, v), kept in the domain."""
        for _ in range(NEWTON_STEPS):
            x, y = np.array([u]), np.array([v])
            r = data.values(0, 0, x, y)[0] - q
            su, sv = data.values(1, 0, x, y)[0], data.values(0, 1, x, y)[0]
            suu, suv, svv = (data.values(a, b, x, y)[0] for a, b in ((2, 0), (1, 1), (0, 2)))
            g = np.array([r @ su, r @ sv])
            h = np.array(
                [[su @ su + r @ suu, su @ sv + r @ suv], [su @ sv + r @ suv, sv @ sv + r @ svv]]
            )
            if not np.isfinite(h).all() or abs(np.linalg.det(h)) < 1e-300:
                break
            step = np.linalg.solve(h, g)
            nu, nv = min(max(u - step[0], ua), ub), min(max(v - step[1], va), vb)
            if nu == u and nv == v:
                break
            u, v = nu, nv
        return u, v

    return _minimise(data, lambda cells: _distance(data, cells, q), value, slack, polish, stats)
