r"""The curves taking part in hazmat.atom_intersect's branch and bound, and the interval
arithmetic it runs on.

Every curve taking part is a `Part`: its parameter interval, point values and derivatives, and
*enclosures* of the curve and of its first derivative over many parameter intervals at once
(rigorous, every rounding included):

- `AtomPart`: the Taylor-form enclosures of hazmat.atom_bounds, in τ = t − mid, coordinates
  divided by a power-of-two scale (so they are exact);
- `BernsteinPart`: a polynomial or rational Bézier curve with positive weights, through its
  homogeneous control rows (w_i P_i, w_i). On [a, b] the rows of the restriction are the
  blossoms H[a^(n−i) b^i], and the curve there lies in the convex hull of their projections
  (the weights stay positive); the derivative is (A' w − A w') / w² in interval arithmetic
  with A', w' from the hodograph's rows, restricted the same way. The blossoms' rounding
  (n de Casteljau steps, each a few ulps of the rows' size) is added.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np

from . import atom_bounds as ab

_U = 2.0**-53

Bounds = tuple[np.ndarray, np.ndarray]


class Part(Protocol):
    """A curve as the branch and bound sees it: parameter interval [lo, hi], and for arrays
    of parameters (intervals [a, b]) values (d, m) and enclosures (lower, upper), each (d, m),
    of the curve (k = 0) and its derivative (k = 1)."""

    lo: float
    hi: float

    @property
    def size(self) -> float: ...  # read only: a field, or BernsteinPart's computed property

    def values(self, k: int, x: np.ndarray) -> np.ndarray: ...

    def enclose(self, k: int, a: np.ndarray, b: np.ndarray) -> Bounds: ...


@dataclass
class AtomPart:
    """A curve over centred atoms: parameter τ ∈ [lo, hi], coordinates `data` × `scale`
    (a power of two)."""

    data: ab.AtomCurveData
    lo: float
    hi: float
    scale: float

    @property
    def size(self) -> float:
        return float(self.scale * np.abs(self.data.coefficients).sum(axis=0).max()) or 1e-300

    def values(self, k: int, x: np.ndarray) -> np.ndarray:
        return self.data.values(k, np.asarray(x, dtype=float)) * self.scale

    def enclose(self, k: int, a: np.ndarray, b: np.ndarray) -> Bounds:
        low, high = self.data.enclose(k, a, b)
        return low * self.scale, high * self.scale


def _blossoms(rows: np.ndarray, a: np.ndarray, b: np.ndarray, absolute: bool = False) -> np.ndarray:
    """(m, n+1, e): the Bernstein rows of the polynomial with rows (n+1, e) restricted to
    [a_j, b_j]: row i is the blossom at (a^(n−i), b^i), by de Casteljau steps (absolute:
    with the factors |1 − x| and |x|, a bound on the magnitudes met on the way)."""
    n = rows.shape[0] - 1
    out = np.empty((a.size, n + 1, rows.shape[1]))
    for i in range(n + 1):
        arr = np.broadcast_to(rows, (a.size, *rows.shape))
        for step in range(n):
            x = (b if step < i else a)[:, None, None]
            if absolute:
                arr = np.abs(1 - x) * arr[:, :-1] + np.abs(x) * arr[:, 1:]
            else:
                arr = (1 - x) * arr[:, :-1] + x * arr[:, 1:]
        out[:, i] = arr[:, 0]
    return out


def _point(rows: np.ndarray, x: np.ndarray) -> np.ndarray:
    """(m, e): the rows' polynomial at each x (de Casteljau; _blossoms' first row at a = b =
    x, the same arithmetic, without the n other blossoms)."""
    arr = np.broadcast_to(rows, (x.size, *rows.shape))
    for _ in range(rows.shape[0] - 1):
        arr = (1 - x)[:, None, None] * arr[:, :-1] + x[:, None, None] * arr[:, 1:]
    out: np.ndarray = arr[:, 0]
    return out


@dataclass
class BernsteinPart:
    """A polynomial or rational Bézier curve on [0, 1] by its homogeneous rows (n+1, d+1),
    (w_i P_i, w_i) with w_i > 0 (a polynomial curve: w_i = 1)."""

    rows: np.ndarray
    lo: float = 0.0
    hi: float = 1.0

    def __post_init__(self) -> None:
        self.rows = np.asarray(self.rows, dtype=float)
        n = self.rows.shape[0] - 1
        self._hodograph = n * np.diff(self.rows, axis=0) if n else np.zeros((1, self.rows.shape[1]))
        self._magnitude = np.abs(self.rows)
        # the hodograph's magnitude with its own rounding (one difference, one product by n:
        # within 4 ulps of n (|r_i| + |r_(i+1)|)) added, element by element
        ends = self._magnitude[:-1] + self._magnitude[1:] if n else self._magnitude * 0
        self._hodo_error = 4 * _U * max(n, 1) * ends
        self._hodo_magnitude = np.abs(self._hodograph) + self._hodo_error

    @property
    def size(self) -> float:
        pts = self.rows[:, :-1] / self.rows[:, -1:]
        return float(np.abs(pts).max()) or 1e-300

    def values(self, k: int, x: np.ndarray) -> np.ndarray:
        x = np.asarray(x, dtype=float)
        h = _point(self.rows, x)  # (m, e)
        if k == 0:
            value: np.ndarray = (h[:, :-1] / h[:, -1:]).T
            return value
        dh = _point(self._hodograph, x)
        w = h[:, -1:]
        out: np.ndarray = ((dh[:, :-1] * w - h[:, :-1] * dh[:, -1:]) / (w * w)).T
        return out

    @staticmethod
    def _pad(magnitude: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        """(m, n+1, e): the blossoms' rounding, absolute, element by element: each de
        Casteljau step (1 − x) u + x v rounds by a few ulps of |1 − x| |u| + |x| |v|, so n
        steps stay within 6 (n + 1) ulps of the blossoms of the rows' magnitudes (taken with
        |1 − x| and |x|). Relative to each blossom, not to the largest row: with weights
        spanning 5e5, the ends' rows are 2e-6 of the largest, and a pad from the largest row
        blurred their projections by 5e-9 of the curve's size, so the search gave up."""
        n = magnitude.shape[0] - 1
        out: np.ndarray = 6 * (n + 1) * _U * _blossoms(magnitude, a, b, absolute=True) + 1e-300
        return out

    def _homogeneous(self, a: np.ndarray, b: np.ndarray) -> tuple[Bounds, Bounds, Bounds, Bounds]:
        """Intervals (lower, upper) of A (d, m), w (1, m), A' and w' on [a, b]."""
        sub = _blossoms(self.rows, a, b)
        pad = self._pad(self._magnitude, a, b)
        n1 = self.rows.shape[0]
        dsub = _blossoms(self._hodograph, a, b)
        # plus the hodograph rows' own rounding, carried through the (linear) steps
        carried = _blossoms(self._hodo_error, a, b, absolute=True) * (1 + 8 * _U * n1)
        dpad = self._pad(self._hodo_magnitude, a, b) + carried
        lo, hi = (sub - pad).min(axis=1).T, (sub + pad).max(axis=1).T
        dlo, dhi = (dsub - dpad).min(axis=1).T, (dsub + dpad).max(axis=1).T
        return (lo[:-1], hi[:-1]), (lo[-1:], hi[-1:]), (dlo[:-1], dhi[:-1]), (dlo[-1:], dhi[-1:])

    def enclose(self, k: int, a: np.ndarray, b: np.ndarray) -> Bounds:
        sub = _blossoms(self.rows, a, b)  # (m, n+1, e)
        pad = self._pad(self._magnitude, a, b)
        w = sub[:, :, -1]
        wmin = (w - pad[:, :, -1]).min(axis=1)
        bad = wmin <= 0  # weights not proven positive: no enclosure
        d = self.rows.shape[1] - 1
        if k == 0:
            # the hull of the projections A_i / w_i, each A_i ± pad over w_i ∓ pad
            num = sub[:, :, :-1]
            wl, wh = (w - pad[:, :, -1])[:, :, None], (w + pad[:, :, -1])[:, :, None]
            nl, nh = num - pad[:, :, :-1], num + pad[:, :, :-1]
            with np.errstate(divide="ignore", invalid="ignore"):
                cand = np.stack([nl / wl, nl / wh, nh / wl, nh / wh])
            low = cand.min(axis=(0, 2)).T
            high = cand.max(axis=(0, 2)).T
            low = low - 4 * _U * np.abs(low)
            high = high + 4 * _U * np.abs(high)
        else:
            (al, ah), (wl_, wh_), (dal, dah), (dwl, dwh) = self._homogeneous(a, b)
            wl_ = np.maximum(wl_, 0.0)
            n1 = _mul(dal, dah, wl_, wh_)
            n2 = _mul(al, ah, dwl, dwh)
            num_lo, num_hi = _add(n1[0], n1[1], -n2[1], -n2[0])
            den_lo, den_hi = _mul(wl_, wh_, wl_, wh_)
            with np.errstate(divide="ignore", invalid="ignore"):
                low, high = _div_positive(num_lo, num_hi, den_lo, den_hi)
        low = np.where(bad[None, :], -np.inf, low)
        high = np.where(bad[None, :], np.inf, high)
        return low.reshape(d, -1), high.reshape(d, -1)


# ---------------------------------------------------------------------- interval arithmetic
def _widen(low: np.ndarray, high: np.ndarray) -> Bounds:
    pad = 4 * _U * np.maximum(np.abs(low), np.abs(high)) + 1e-300
    return low - pad, high + pad


def _add(alo: np.ndarray, ahi: np.ndarray, blo: np.ndarray, bhi: np.ndarray) -> Bounds:
    return _widen(alo + blo, ahi + bhi)


def _mul(alo: np.ndarray, ahi: np.ndarray, blo: np.ndarray, bhi: np.ndarray) -> Bounds:
    with np.errstate(invalid="ignore"):
        p = np.stack(np.broadcast_arrays(alo * blo, alo * bhi, ahi * blo, ahi * bhi))
    p = np.where(np.isnan(p), np.inf, p)
    return _widen(p.min(axis=0), p.max(axis=0))


def _div_positive(alo: np.ndarray, ahi: np.ndarray, blo: np.ndarray, bhi: np.ndarray) -> Bounds:
    """[a] / [b] for b > 0 (b's lower end 0 gives an unbounded quotient)."""
    p = np.stack(np.broadcast_arrays(alo / blo, alo / bhi, ahi / blo, ahi / bhi))
    p = np.where(np.isnan(p), np.inf, p)
    low, high = p.min(axis=0), p.max(axis=0)
    low = np.where(blo > 0, low, -np.inf)
    high = np.where(blo > 0, high, np.inf)
    return _widen(low, high)


def _mag(lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    out: np.ndarray = np.maximum(np.abs(lo), np.abs(hi))
    return out


def _dot(n: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> Bounds:
    """n (d, m) · [lo, hi] (d, m), elementwise per column, as an interval (m,)."""
    a, b = n * lo, n * hi
    low, high = np.minimum(a, b).sum(axis=0), np.maximum(a, b).sum(axis=0)
    pad = 2 * n.shape[0] * _U * (np.abs(a) + np.abs(b)).sum(axis=0) + 1e-300
    return low - pad, high + pad
