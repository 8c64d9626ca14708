r"""Certified extremes of tensor-product surfaces over centred atoms: the bounding box and the
closest point of S(u, v) = Σ_i Σ_j b_i(u) b_j(v) P_ij, each direction's basis functions b_i
given as a curve over centred atoms (`atom_bounds.AtomCurveData` with one "coordinate" per
basis function), for the mixed (algebraic-trigonometric/hyperbolic) families that have no
rational form. A polynomial direction across a mixed one is an atom direction of the same
kind, its basis over 1, τ, …, τ^N and no harmonics (`bernstein_direction`), so every
enclosure below serves both pairs. (Measured against the Bernstein hull of the polynomial
basis on a cell: the Taylor enclosures are 12–17% wider at cell width 1/8, under 2% from
1/64 on, and the searches take as many cells as with two atom directions.)

**Enclosures.** On a cell [u0, u1] × [v0, v1], atom_bounds encloses every b_i^(a) on [u0, u1]
and b_j^(b) on [v0, v1] (Taylor form, widened for rounding); S^(a, b) is then enclosed by
interval arithmetic, Σ_ij P_ij [b_i^(a)] [b_j^(b)], every product and sum widened by its
rounding. That enclosure is first order with a constant that ignores cancellation (Σ b_i = 1,
say), so the bound used for a scalar f (a coordinate, or D = |S − q|²) is the better of it and
the second-order form (Taylor with Lagrange's remainder in two variables)

    f(c + δ) ∈ f(c) ± (|f_u(c)| h_u + |f_v(c)| h_v + (M_uu h_u² + 2 M_uv h_u h_v + M_vv h_v²)/2),

f and ∇f enclosed at the centre c (an interval of rounding width only) and M_ab ≥ sup |f_ab|
over the cell, with D_uu = 2 (S_u·S_u + (S − q)·S_uu) and so on. Its width is the centre's
rounding radius plus terms that shrink with the cell, each charged to the direction it comes
from (`_Scalar.share_u`, `share_v`). The bounds M of S's second derivatives are the better
of interval arithmetic and the surface written over products of atoms, S^(a, b) = Σ_kl G_kl
α_k(u) β_l(v) with |S^(a, b)| ≤ Σ_kl |G_kl| sup|α_k| sup|β_l| (`SurfaceData.second_sup`, G
computed in floats and widened by its rounding): where S does not depend on v, G's
v-derivative is rounding only, which interval arithmetic on the bases cannot see (it forgets
Σ_j b_j'' = 0). S_u and S_v over a cell are the better of interval arithmetic and the mean
value form about the centre, S_u(c) ± (M_uu h_u + M_uv h_v).

**Faces.** The domain is the union of its interior, its four open edges and its four
corners; the global minimum p of f lies in the relative interior of one of them, where the
derivatives of f along that face's free directions vanish. So the branch and bound runs on the
cells of every face together (an edge's cells have width 0 across it), and the corners are
candidates. A cell is

- **dropped** when a free direction's derivative has one sign on it (p is not in it), or when
  its lower bound is at least the best value found (f there is no better);
- **settled** when its enclosure is narrower than the tolerance (a *width* test: the cell's
  lower bound is then within the tolerance of a value f takes in it, its centre, which becomes
  a candidate), or when its lower bound is within the tolerance of the best value found (a
  *value* test: nothing in it is better by more than the tolerance; this ends the search on a
  curve of minima no cell can be narrow on, such as the level curve S = q of a surface in one
  dimension, where |S − q|² has width ~ |∇S|² h² on a cell of size h);
- otherwise **halved**, in the free directions whose share of the enclosure's width is at
  least a third of the larger share (a direction in which f is flat, e.g. a coordinate that
  depends on u only, is not cut, so a line of minima costs a few cells, not millions).

**What is returned** is the best value found (attained, at a point returned with it) and the
certified lower bound: the least of the settled cells' lower bounds and of the enclosure of f
at the best point, so the true minimum lies between the two, and they differ by at most the
tolerance (or the enclosure's rounding radius at a point, a few hundred ulps of the surface's
size, if that is larger: `SurfaceData.floor`). A coordinate whose net is constant, in a
basis that sums to one exactly (`SurfaceData.unity`), is that constant, exactly. Should the
search exceed MAX_ROUNDS or MAX_OPEN open cells, the open cells are settled by their lower
bounds: still certified, maybe looser than the tolerance; `Stats.narrow` counts them (0 in
every answer the tests check). Several searches (a box's 2d ones: each coordinate, each sign;
a batch of closest-point queries) run as one, their cells side by side (`_Cells.group`).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from functools import cache
from math import comb

import numpy as np

from .atom_bounds import AtomCurveData, Stats, _products, _squares, _sum

START = 8  # cells per direction of the first level
MAX_ROUNDS = 160
MAX_OPEN = 1 << 15
NEWTON_STEPS = 12
SHARE = 1.0 / 3.0  # a direction is cut when its share of the width is this much of the larger
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


def _bilinear(a: np.ndarray, tensor: np.ndarray, b: np.ndarray) -> np.ndarray:
    """(d, m): Σ_kl a_km T_kld b_lm for a (K, m), T (K, L, d), b (L, m) (two BLAS products;
    einsum's path search costs more than the sums at these sizes)."""
    inner = np.tensordot(tensor, b, axes=(1, 0))  # (K, d, m)
    out: np.ndarray = (inner * a[:, None, :]).sum(axis=0)
    return out


@cache
def _centred_bernstein(degree: int) -> tuple[tuple[Fraction, ...], ...]:
    """M (N+1, N+1), exact: B_k^N(1/2 + τ) = Σ_p M_kp τ^p, from C(N, k) (1/2 + τ)^k
    (1/2 − τ)^(N−k) multiplied out."""
    half = Fraction(1, 2)
    rows = []
    for k in range(degree + 1):
        poly = [Fraction(comb(degree, k))]
        for factor in [(half, Fraction(1))] * k + [(half, Fraction(-1))] * (degree - k):
            nxt = [Fraction(0)] * (len(poly) + 1)
            for p, c in enumerate(poly):
                nxt[p] += c * factor[0]
                nxt[p + 1] += c * factor[1]
            poly = nxt
        rows.append(tuple(poly))
    return tuple(rows)


def bernstein_direction(
    bernstein: Sequence[Sequence[Fraction | float]],
) -> tuple[AtomCurveData, bool]:
    """A polynomial direction on [0, 1] as an atom direction: basis function b_i = Σ_k B_ik
    B_k^N(t) (`bernstein` (n+1) × (N+1), Fractions or floats) over the centred atoms 1, τ, …,
    τ^N, τ = t − 1/2 (no harmonics), so that a mixed family across a polynomial one is
    enclosed by the same tensor enclosures as two atom directions: the polynomials of degree
    N are the algebraic part of the atom space. The coefficients are computed exactly (each
    float entry as the rational it is) and rounded once; also returned is whether the basis
    sums to one exactly (Σ_i B_ik = 1 for every k, in exact arithmetic on the entries)."""
    rows = [[Fraction(x) for x in row] for row in bernstein]
    degree = len(rows[0]) - 1
    m = _centred_bernstein(degree)
    coefficients = np.array(
        [
            [float(sum((row[k] * m[k][p] for k in range(degree + 1)), Fraction(0))) for row in rows]
            for p in range(degree + 1)
        ]
    )
    unity = all(sum(col) == 1 for col in zip(*rows, strict=True))
    return AtomCurveData(coefficients, 1.0, degree, 0, False), unity


@dataclass
class SurfaceData:
    """A surface over centred atoms: each direction's basis as an AtomCurveData (coordinates
    = basis functions) on its centred domain [lo, hi], the net (n+1, q+1, d) in floats, and
    whether each direction's basis sums to one exactly (then a coordinate with a constant net
    is that constant)."""

    basis_u: AtomCurveData
    basis_v: AtomCurveData
    domain_u: tuple[float, float]
    domain_v: tuple[float, float]
    net: np.ndarray
    unity: bool = False
    _tensors: dict[tuple[int, int], np.ndarray] = field(default_factory=dict)

    def values(self, a: int, b: int, u: np.ndarray, v: np.ndarray) -> np.ndarray:
        """(m, d): S^(a, b) at paired centred parameters, in floats."""
        bu, bv = self.basis_u.values(a, u), self.basis_v.values(b, v)
        return _bilinear(bu, self.net, bv).T

    def enclose(
        self, a: int, b: int, u0: np.ndarray, u1: np.ndarray, v0: np.ndarray, v1: np.ndarray
    ) -> Pair:
        """(lower, upper), each (d, m): bounds of S^(a, b) on the cells [u0, u1] × [v0, v1]."""
        ulo, uhi = self.basis_u.enclose(a, u0, u1)
        vlo, vhi = self.basis_v.enclose(b, v0, v1)
        plo, phi = _products(ulo[:, None, :], uhi[:, None, :], vlo[None, :, :], vhi[None, :, :])
        return _times_net(plo, phi, self.net)

    def _tensor(self, a: int, b: int) -> np.ndarray:
        """(A_u, A_v, d): bounds of |coefficients| of S^(a, b) over the atom products
        α_k(u) β_l(v), the float contraction Σ_ij B^(a)_ki P_ij B^(b)_lj plus its rounding."""
        key = (a, b)
        if key not in self._tensors:
            bu, bv = self.basis_u.order(a), self.basis_v.order(b)
            exact = np.einsum("ki,ijd,lj->kld", bu, self.net, bv, optimize=True)
            spread = np.einsum("ki,ijd,lj->kld", np.abs(bu), np.abs(self.net), np.abs(bv))
            terms = self.net.shape[0] + self.net.shape[1] + 4
            self._tensors[key] = np.abs(exact) + spread * (4 * terms * _U) + 1e-300
        return self._tensors[key]

    def second_sup(self, cells: _Cells) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Bounds of |S_uu|, |S_uv|, |S_vv| over the cells, each (d, m), from the atom
        tensor: Σ_kl |G_kl| sup|α_k| sup|β_l|. Crude but blind to no cancellation inside a
        direction: where S does not depend on v, G's v-derivative is rounding only."""
        ru = np.maximum(np.abs(cells.u0), np.abs(cells.u1))
        rv = np.maximum(np.abs(cells.v0), np.abs(cells.v1))
        au, av = self.basis_u._sup_atoms(ru), self.basis_v._sup_atoms(rv)
        out = []
        for a, b in ((2, 0), (1, 1), (0, 2)):
            top = _bilinear(au, self._tensor(a, b), av)
            out.append(top * (1 + 64 * _U))
        return out[0], out[1], out[2]

    def size(self) -> float:
        """The net's size, max |P_ij|: the unit of the tolerances."""
        return float(np.abs(self.net).max()) if self.net.size else 0.0

    def floor(self) -> np.ndarray:
        """(d,): the widest enclosure of a coordinate at a single point (its rounding radius,
        twice), over the corners and the centre: below this no width test can pass."""
        (ua, ub), (va, vb) = self.domain_u, self.domain_v
        u = np.array([ua, ua, ub, ub, 0.5 * (ua + ub)])
        v = np.array([va, vb, va, vb, 0.5 * (va + vb)])
        lo, hi = self.enclose(0, 0, u, u, v, v)
        out: np.ndarray = (hi - lo).max(axis=1)
        return out

    def constant(self, c: int) -> float | None:
        """The coordinate's value if it is exactly constant (a constant net, a basis that sums
        to one in each direction), else None."""
        col = self.net[:, :, c]
        if self.unity and col.size and (col == col.flat[0]).all():
            return float(col.flat[0])
        return None


@dataclass
class _Cells:
    """Cells [u0, u1] × [v0, v1], each of one search (`group`: a query, or a coordinate and
    a sign): several searches run as one, their cells side by side."""

    u0: np.ndarray
    u1: np.ndarray
    v0: np.ndarray
    v1: np.ndarray
    group: np.ndarray

    @property
    def free_u(self) -> np.ndarray:
        out: np.ndarray = self.u1 > self.u0
        return out

    @property
    def free_v(self) -> np.ndarray:
        out: np.ndarray = self.v1 > self.v0
        return out

    def take(self, keep: np.ndarray) -> _Cells:
        return _Cells(self.u0[keep], self.u1[keep], self.v0[keep], self.v1[keep], self.group[keep])

    def centres(self) -> tuple[np.ndarray, np.ndarray]:
        return 0.5 * (self.u0 + self.u1), 0.5 * (self.v0 + self.v1)

    def halves(self, cut_u: np.ndarray, cut_v: np.ndarray) -> _Cells:
        """Every cell cut in two in each direction marked (four, two or one pieces)."""
        uc, vc = self.centres()
        # the first piece of each direction: [u0, uc] if cut, else the whole [u0, u1]
        u_first = (self.u0, np.where(cut_u, uc, self.u1))
        v_first = (self.v0, np.where(cut_v, vc, self.v1))
        parts = [
            (u_first, v_first, np.ones_like(cut_u)),
            ((uc, self.u1), v_first, cut_u),
            (u_first, (vc, self.v1), cut_v),
            ((uc, self.u1), (vc, self.v1), cut_u & cut_v),
        ]
        pieces = [(uu[0][k], uu[1][k], vv[0][k], vv[1][k], self.group[k]) for uu, vv, k in parts]
        u0, u1, v0, v1, group = (np.concatenate(col) for col in zip(*pieces, strict=True))
        return _Cells(u0, u1, v0, v1, group)


def _initial_cells(data: SurfaceData, groups: int) -> tuple[_Cells, _Cells]:
    """The cells of the interior and of the four edges, and the corners (as cells of width
    0), for each of `groups` searches."""
    (ua, ub), (va, vb) = data.domain_u, data.domain_v
    us, vs = np.linspace(ua, ub, START + 1), np.linspace(va, vb, START + 1)
    gu0, gv0 = np.meshgrid(us[:-1], vs[:-1], indexing="ij")
    gu1, gv1 = np.meshgrid(us[1:], vs[1:], indexing="ij")
    k = np.ones(START)
    u0 = np.concatenate([gu0.ravel(), ua * k, ub * k, us[:-1], us[:-1]])
    u1 = np.concatenate([gu1.ravel(), ua * k, ub * k, us[1:], us[1:]])
    v0 = np.concatenate([gv0.ravel(), vs[:-1], vs[:-1], va * k, vb * k])
    v1 = np.concatenate([gv1.ravel(), vs[1:], vs[1:], va * k, vb * k])
    cu, cv = np.array([ua, ua, ub, ub]), np.array([va, vb, va, vb])

    def each(a: np.ndarray, b: np.ndarray, c: np.ndarray, d: np.ndarray) -> _Cells:
        group = np.repeat(np.arange(groups), a.size)
        a, b, c, d = (np.tile(x, groups) for x in (a, b, c, d))
        return _Cells(a, b, c, d, group)

    return each(u0, u1, v0, v1), each(cu, cu, cv, cv)


@dataclass
class _Scalar:
    """A scalar's bounds on cells: (lower, upper) of f over each cell, of f_u and f_v over
    each cell, and the shares of the second-order form's width due to u and to v."""

    lo: np.ndarray
    hi: np.ndarray
    du: Pair
    dv: Pair
    share_u: np.ndarray
    share_v: np.ndarray

    def negated(self) -> _Scalar:
        return _Scalar(-self.hi, -self.lo, self.du, self.dv, self.share_u, self.share_v)


def _mag(p: Pair) -> np.ndarray:
    out: np.ndarray = np.maximum(np.abs(p[0]), np.abs(p[1]))
    return out


def _meet(a: Pair, b: Pair) -> Pair:
    """The intersection of two enclosures of the same quantity."""
    return np.maximum(a[0], b[0]), np.minimum(a[1], b[1])


def _around(centre: Pair, radius: np.ndarray) -> Pair:
    lo, hi = centre[0] - radius, centre[1] + radius
    pad = 4 * _U * (np.abs(lo) + np.abs(hi))
    return lo - pad, hi + pad


@dataclass
class _Parts:
    """Enclosures of S and its partial derivatives on cells, each (d, m): S, S_u, S_v over
    the cells; at the centres; and S_uu, S_uv, S_vv over the cells with their magnitudes."""

    half_u: np.ndarray
    half_v: np.ndarray
    s: Pair
    su: Pair
    sv: Pair
    at: Pair
    at_u: Pair
    at_v: Pair
    second: tuple[Pair, Pair, Pair]
    sups: tuple[np.ndarray, np.ndarray, np.ndarray]


def _parts(data: SurfaceData, cells: _Cells) -> _Parts:
    """Every enclosure the bounds need. The second derivatives are the better of interval
    arithmetic on the bases and the atom-tensor bound (`SurfaceData.second_sup`, which sees a
    direction S does not depend on), and S_u, S_v over a cell the better of interval arithmetic
    and the mean-value form about the centre."""
    args = (cells.u0, cells.u1, cells.v0, cells.v1)
    uc, vc = cells.centres()
    mid = (uc, uc, vc, vc)
    hu = 0.5 * (cells.u1 - cells.u0) * (1 + 4 * _U)
    hv = 0.5 * (cells.v1 - cells.v0) * (1 + 4 * _U)
    at, at_u, at_v = (data.enclose(a, b, *mid) for a, b in ((0, 0), (1, 0), (0, 1)))
    tensor = data.second_sup(cells)
    second = []
    sups = []
    for (a, b), top in zip(((2, 0), (1, 1), (0, 2)), tensor, strict=True):
        box = _meet(data.enclose(a, b, *args), (-top, top))
        second.append(box)
        sups.append(_mag(box))
    muu, muv, mvv = sups
    su = _meet(data.enclose(1, 0, *args), _around(at_u, (muu * hu + muv * hv) * (1 + 8 * _U)))
    sv = _meet(data.enclose(0, 1, *args), _around(at_v, (muv * hu + mvv * hv) * (1 + 8 * _U)))
    s_cells = data.enclose(0, 0, *args)
    return _Parts(
        hu, hv, s_cells, su, sv, at, at_u, at_v, (second[0], second[1], second[2]), (muu, muv, mvv)
    )


def _second_order(
    parts: _Parts,
    at: Pair,
    grad_u: Pair,
    grad_v: Pair,
    muu: np.ndarray,
    muv: np.ndarray,
    mvv: np.ndarray,
    first: Pair,
    du: Pair,
    dv: Pair,
) -> _Scalar:
    """f's bounds on the cells: the better of the first-order enclosure `first` and the
    second-order form from enclosures of f, f_u, f_v at the centres and bounds of |f_uu|,
    |f_uv|, |f_vv| over the cells."""
    hu, hv = parts.half_u, parts.half_v
    cross = 0.5 * muv * hu * hv
    share_u = (_mag(grad_u) * hu + 0.5 * muu * hu * hu + cross) * (1 + 16 * _U)
    share_v = (_mag(grad_v) * hv + 0.5 * mvv * hv * hv + cross) * (1 + 16 * _U)
    spread = (share_u + share_v) * (1 + 4 * _U)
    lo, hi = at[0] - spread, at[1] + spread
    pad = 8 * _U * (np.abs(lo) + np.abs(hi))
    lo, hi = np.maximum(first[0], lo - pad), np.minimum(first[1], hi + pad)
    return _Scalar(lo, hi, du, dv, share_u, share_v)


def _row(p: Pair, c: np.ndarray) -> Pair:
    """Coordinate c[m] of every cell m."""
    cols = np.arange(c.size)
    return p[0][c, cols], p[1][c, cols]


def _coordinate(parts: _Parts, c: np.ndarray) -> _Scalar:
    """Bounds of coordinate c[m] on cell m."""
    cols = np.arange(c.size)
    muu, muv, mvv = (m[c, cols] for m in parts.sups)
    return _second_order(
        parts,
        _row(parts.at, c),
        _row(parts.at_u, c),
        _row(parts.at_v, c),
        muu,
        muv,
        mvv,
        _row(parts.s, c),
        _row(parts.su, c),
        _row(parts.sv, c),
    )


def _dot(a: Pair, b: Pair) -> Pair:
    return _sum(*_products(a[0], a[1], b[0], b[1]))


def _plus(a: Pair, b: Pair) -> Pair:
    lo, hi = a[0] + b[0], a[1] + b[1]
    pad = 4 * _U * (np.abs(lo) + np.abs(hi))
    return lo - pad, hi + pad


def _twice(p: Pair) -> Pair:
    return 2 * p[0], 2 * p[1]


def _distance(parts: _Parts, q: np.ndarray) -> _Scalar:
    """Bounds of D = |S − q_m|² (and of D_u / 2, D_v / 2) on the cells m, q (d, m)."""

    def shifted(p: Pair) -> Pair:
        return p[0] - q, p[1] - q

    r, rc = shifted(parts.s), shifted(parts.at)
    su, sv = parts.su, parts.sv
    suu, suv, svv = parts.second
    huu = _twice(_plus(_sum(*_squares(*su)), _dot(r, suu)))
    huv = _twice(_plus(_dot(su, sv), _dot(r, suv)))
    hvv = _twice(_plus(_sum(*_squares(*sv)), _dot(r, svv)))
    return _second_order(
        parts,
        _sum(*_squares(*rc)),
        _twice(_dot(rc, parts.at_u)),
        _twice(_dot(rc, parts.at_v)),
        _mag(huu),
        _mag(huv),
        _mag(hvv),
        _sum(*_squares(*r)),
        _dot(r, su),
        _dot(r, sv),
    )


def _one_signed(cells: _Cells, s: _Scalar) -> np.ndarray:
    """Cells on which a free direction's derivative of f keeps one sign."""
    out: np.ndarray = (cells.free_u & ((s.du[0] > 0) | (s.du[1] < 0))) | (
        cells.free_v & ((s.dv[0] > 0) | (s.dv[1] < 0))
    )
    return out


def _cuts(cells: _Cells, s: _Scalar) -> tuple[np.ndarray, np.ndarray]:
    """The directions to cut: free ones whose share of the width is at least SHARE of the
    larger share (both free directions when neither share is positive)."""
    top = np.maximum(s.share_u, s.share_v)
    cut_u = cells.free_u & (s.share_u >= SHARE * top)
    cut_v = cells.free_v & (s.share_v >= SHARE * top)
    neither = ~(cut_u | cut_v)
    return cut_u | (neither & cells.free_u), cut_v | (neither & cells.free_v)


Polish = Callable[[np.ndarray, np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]]


def _best_of_groups(
    groups: np.ndarray,
    f: np.ndarray,
    best: np.ndarray,
    at_u: np.ndarray,
    at_v: np.ndarray,
    u: np.ndarray,
    v: np.ndarray,
) -> np.ndarray:
    """Takes every candidate (u, v, value f, of search `groups`) better than its search's best
    into (best, at_u, at_v), in place; returns the searches improved (a mask)."""
    order = np.lexsort((f, groups))
    first = np.ones(order.size, dtype=bool)
    first[1:] = groups[order][1:] != groups[order][:-1]
    pick = order[first]
    g = groups[pick]
    better = f[pick] < best[g]
    g, pick = g[better], pick[better]
    best[g], at_u[g], at_v[g] = f[pick], u[pick], v[pick]
    improved = np.zeros(best.size, dtype=bool)
    improved[g] = True
    return improved


def _minimise(
    data: SurfaceData,
    groups: int,
    bounds: Callable[[_Cells], _Scalar],
    value: Callable[[np.ndarray, np.ndarray, np.ndarray], np.ndarray],
    tolerance: Callable[[np.ndarray], np.ndarray],
    polish: Polish | None,
    stats: Stats,
    enough: Callable[[np.ndarray], np.ndarray] | None = None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(u, v, best, lower), each (groups,): for each search g the least value of f_g found
    (at centred (u, v)) and the certified lower bound of f_g over the domain, within
    tolerance(best)_g of best (see the module's docstring). `bounds` gives f's bounds on
    cells (each of its search), `value(u, v, g)` f_g at points; `enough(best)` the least
    lower bound that settles a cell by the value test (default best − tolerance(best))."""
    cells, corners = _initial_cells(data, groups)
    best = np.full(groups, np.inf)
    at_u, at_v = np.zeros(groups), np.zeros(groups)
    cf = value(corners.u0, corners.v0, corners.group)
    _best_of_groups(corners.group, cf, best, at_u, at_v, corners.u0, corners.v0)
    # the corners (faces of dimension 0) are candidates, bounded by their enclosures
    lower = np.full(groups, np.inf)
    np.minimum.at(lower, corners.group, bounds(corners).lo)
    fresh = np.ones(groups, dtype=bool)  # searches whose best point is not yet polished
    rounds = 0
    while cells.u0.size:
        rounds += 1
        stats.rounds += 1
        stats.intervals += cells.u0.size
        if polish is not None and fresh.any():
            g = np.flatnonzero(fresh)
            pu, pv = polish(at_u[g], at_v[g], g)
            _best_of_groups(g, value(pu, pv, g), best, at_u, at_v, pu, pv)
            fresh[:] = False
        s = bounds(cells)
        # settled: the enclosure is narrow (its centre is within tol of its bound), or its
        # lower bound is within tol of the best value found (nothing in it is better by more
        # than tol: a level curve of D = 0 in one dimension, where no cell is ever narrow)
        allowed = tolerance(best)
        floor = best - allowed if enough is None else enough(best)
        settled = ((s.hi - s.lo) <= allowed[cells.group]) | (s.lo >= floor[cells.group])
        if rounds >= MAX_ROUNDS or cells.u0.size > MAX_OPEN:
            stats.narrow += int((~settled).sum())
            settled = np.ones_like(settled)
        dropped = (s.lo >= best[cells.group]) | _one_signed(cells, s)
        settled &= ~dropped
        np.minimum.at(lower, cells.group[settled], s.lo[settled])
        # every centre not dropped is a candidate (a settled cell's is within tol of its bound)
        live = ~dropped
        uc, vc = cells.centres()
        uc, vc, gc = uc[live], vc[live], cells.group[live]
        fresh |= _best_of_groups(gc, value(uc, vc, gc), best, at_u, at_v, uc, vc)
        keep = ~(settled | dropped)
        cut_u, cut_v = _cuts(cells, s)
        cells = cells.take(keep).halves(cut_u[keep], cut_v[keep])
    # the best points' own enclosures bound the dropped cells (their bounds were >= best)
    idx = np.arange(groups)
    at = bounds(_Cells(at_u, at_u, at_v, at_v, idx))
    return at_u, at_v, best, np.minimum(np.minimum(lower, best), at.lo)


def coordinate_extremes(
    data: SurfaceData, tol: float = 1e-12, stats: Stats | None = None
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(inner min, inner max, outer min, outer max), each (d,): for every coordinate the
    least and greatest values attained (at points of the surface, in floats) and certified
    bounds of it over the domain, within max(tol × the net's size, `SurfaceData.floor`) of
    the true extremes. The 2d searches (coordinate c, sign ±: search 2c or 2c + 1, of sign ×
    x_c) run as one."""
    stats = stats if stats is not None else Stats()
    dim = data.net.shape[2]
    fixed = [data.constant(c) for c in range(dim)]
    free = np.array([c for c in range(dim) if fixed[c] is None], dtype=int)
    allowed = np.maximum(tol * data.size(), data.floor())
    coord = np.repeat(free, 2)  # search -> coordinate
    sign = np.tile([1.0, -1.0], free.size)  # search -> sign

    def bounds(cells: _Cells) -> _Scalar:
        f = _coordinate(_parts(data, cells), coord[cells.group])
        neg = sign[cells.group] < 0
        return _Scalar(
            np.where(neg, -f.hi, f.lo),
            np.where(neg, -f.lo, f.hi),
            f.du,
            f.dv,
            f.share_u,
            f.share_v,
        )

    def value(u: np.ndarray, v: np.ndarray, g: np.ndarray) -> np.ndarray:
        out: np.ndarray = sign[g] * data.values(0, 0, u, v)[np.arange(g.size), coord[g]]
        return out

    def tolerance(_best: np.ndarray) -> np.ndarray:
        out: np.ndarray = allowed[coord]
        return out

    out = np.empty((4, dim))
    if free.size:
        *_, best, lower = _minimise(data, 2 * free.size, bounds, value, tolerance, None, stats)
        out[0, free], out[2, free] = best[0::2], lower[0::2]
        out[1, free], out[3, free] = -best[1::2], -lower[1::2]
    for c in range(dim):
        if fixed[c] is not None:
            out[:, c] = fixed[c]
    return out[0], out[1], out[2], out[3]


NEWTON_PARTIALS = ((1, 0), (0, 1), (2, 0), (1, 1), (0, 2))  # distance_newton_step's order


def distance_newton_step(
    r: np.ndarray,
    su: np.ndarray,
    sv: np.ndarray,
    suu: np.ndarray,
    suv: np.ndarray,
    svv: np.ndarray,
) -> tuple[np.ndarray, np.ndarray]:
    """The Newton step (du, dv) on the gradient of |S − q|² / 2, from the residual
    r = S − q and the partials of S at k points (each (k, d)); 0 where the Hessian is
    singular or not finite."""
    gu, gv = (r * su).sum(1), (r * sv).sum(1)
    huu = (su * su + r * suu).sum(1)
    huv = (su * sv + r * suv).sum(1)
    hvv = (sv * sv + r * svv).sum(1)
    det = huu * hvv - huv * huv
    ok = np.isfinite(det) & (np.abs(det) > 1e-300)
    safe = np.where(ok, det, 1.0)
    du = np.where(ok, (hvv * gu - huv * gv) / safe, 0.0)
    dv = np.where(ok, (huu * gv - huv * gu) / safe, 0.0)
    return du, dv


def closest(
    data: SurfaceData, q: np.ndarray, tol: float = 1e-12, stats: Stats | None = None
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(u, v, squared distance, certified lower bound of it), each (k,): for each query q_k
    of q (k, d), the point of the surface (centred parameters) nearest q_k, the distance
    within max(tol × size, the floor) of the certified lower bound's, size being the net's
    plus |q_k|'s (as for polynomial surfaces), refined by Newton from the best point found.
    The k searches run as one."""
    stats = stats if stats is not None else Stats()
    q = np.atleast_2d(q)
    size = data.size() + np.abs(q).max(axis=1, initial=0.0)
    gap = np.maximum(tol * size, float(data.floor().max()))
    (ua, ub), (va, vb) = data.domain_u, data.domain_v

    def value(u: np.ndarray, v: np.ndarray, g: np.ndarray) -> np.ndarray:
        out: np.ndarray = np.square(data.values(0, 0, u, v) - q[g]).sum(axis=1)
        return out

    def tolerance(best: np.ndarray) -> np.ndarray:
        # a squared distance within this of best is a distance within gap of sqrt(best)
        out: np.ndarray = 2 * np.sqrt(np.maximum(best, 0.0)) * gap + gap * gap
        return out

    def enough(best: np.ndarray) -> np.ndarray:
        # a cell whose squared distance is at least (|q − S(best point)| − gap)², rounded
        # up, holds no point nearer by more than gap; any cell does, once that is <= gap
        near = np.sqrt(np.maximum(best, 0.0)) - gap
        out: np.ndarray = np.where(near > 0, np.square(near) * (1 + 8 * _U), -np.inf)
        return out

    def polish(u: np.ndarray, v: np.ndarray, g: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Newton on ∇D = 0 from (u, v), kept in the domain (a singular step stops)."""
        for _ in range(NEWTON_STEPS):
            partials = (data.values(a, b, u, v) for a, b in NEWTON_PARTIALS)
            du, dv = distance_newton_step(data.values(0, 0, u, v) - q[g], *partials)
            nu, nv = np.clip(u - du, ua, ub), np.clip(v - dv, va, vb)
            if np.array_equal(nu, u) and np.array_equal(nv, v):
                break
            u, v = nu, nv
        return u, v

    def bounds(cells: _Cells) -> _Scalar:
        return _distance(_parts(data, cells), q[cells.group].T)

    return _minimise(data, q.shape[0], bounds, value, tolerance, polish, stats, enough)
