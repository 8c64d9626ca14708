"""The fixed-cost certified minimum of E(x, y) = Σ e_ab x^a y^b (a, b <= 2) over a box, for
arrays of coefficient sets, in numpy: the interior certificate
(surface_certify.certified_minimum) and, on what it declines, the edge and corner one
(surface_certify.edge_minimum), then on what both decline the retries
(surface_certify.retry_minimum, then retry_edges: edge_band_minimum at narrower bands), in
the order the compiled kernel (surface_batch_compiled.optimise) runs them. Both batch
optima's numpy engines call this.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from .surface_certify import (
    EDGE_BANDS,
    RADIUS,
    certified_minimum,
    edge_band_minimum,
    edge_minimum,
    retry_minimum,
)


def fixed_cost_minimum(
    c: Sequence[np.ndarray], box: np.ndarray, tol: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(x, y, energy, certified, on_edge) for the nine coefficient arrays c[3a + b] of
    x^a y^b and box = (xlo, xhi, ylo, yhi); certified False where both certificates decline,
    on_edge True where the edge one certified."""
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        bx, by, bval, _, ok = certified_minimum(
            c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7], c[8],
            box[0], box[1], box[2], box[3], tol,
        )  # fmt: skip
        bx, by, bval = np.array(bx, float), np.array(by, float), np.array(bval, float)
        ok = np.array(ok, bool)
        on_edge = np.zeros(ok.shape, bool)
        undecided = np.flatnonzero(~ok)
        if undecided.size:  # the declined sets' edge and corner minima
            d = [v[undecided] for v in c]
            ex, ey, eval_, _, eok = edge_minimum(
                d[0], d[1], d[2], d[3], d[4], d[5], d[6], d[7], d[8],
                box[0], box[1], box[2], box[3], tol,
            )  # fmt: skip
            done = undecided[eok]
            bx[done], by[done], bval[done] = ex[eok], ey[eok], eval_[eok]
            ok[done] = on_edge[done] = True
        for retry, edge in ((_retry_interior, False), (retry_edges, True)):
            undecided = np.flatnonzero(~ok)
            if not undecided.size:
                break
            d = [v[undecided] for v in c]
            rx, ry, rval, _, rok = retry(d, box, tol)
            rok = np.array(rok, bool)
            done = undecided[rok]
            bx[done], by[done], bval[done] = rx[rok], ry[rok], rval[rok]
            ok[done] = True
            on_edge[done] = edge
    return bx, by, bval, ok, on_edge


def retry_edges(
    c: Sequence[np.ndarray], box: np.ndarray, tol: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(x, y, energy, δ, certified): edge_band_minimum at the band half-widths RADIUS · box
    / 2, / 4, ..., / 2^EDGE_BANDS, the first that certifies (each is a certificate on its
    own; the compiled kernel tries them in turn, net by net). An edge minimum near which
    E_s(edge, t) turns to point out of the box fails the band test at RADIUS and passes at
    a narrower one (at_cubic's benchmark nets: all 32 such). Every band in one call, the
    coefficient sets repeated once a band (numpy's per-call cost, not the arithmetic, is
    what a loop over bands would multiply)."""
    count = c[0].shape[0]
    radius = RADIUS * max(box[1] - box[0], box[3] - box[2])
    radii = radius * 0.5 ** np.arange(1, EDGE_BANDS + 1)  # exact: halving, as the kernel does
    t = [np.tile(v, EDGE_BANDS) for v in c]
    got = edge_band_minimum(
        t[0], t[1], t[2], t[3], t[4], t[5], t[6], t[7], t[8],
        box[0], box[1], box[2], box[3], tol, np.repeat(radii, count),
    )  # fmt: skip
    x, y, energy, delta, ok = (np.reshape(v, (EDGE_BANDS, count)) for v in got)
    pick = (np.argmax(ok, axis=0), np.arange(count))  # the first band that certifies
    certified = np.asarray(ok.any(axis=0))
    return x[pick], y[pick], energy[pick], delta[pick], certified


def _retry_interior(
    c: Sequence[np.ndarray], box: np.ndarray, tol: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """surface_certify.retry_minimum on the coefficient sets c (a list of nine arrays)."""
    return retry_minimum(
        c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7], c[8],
        box[0], box[1], box[2], box[3], tol,
    )  # fmt: skip
