"""The fixed-cost stage of the batch optimum for many declined nets (an atom family's, where
the interior certificate declines about one net in eleven), compiled with numba (the `fast`
extra): hazmat.surface_batch_compiled's `optimise_batch`, with each edge of its edge
certificate screened before its pieces are tried.

`surface_certify._edge` certifies an edge minimum when its cheap conditions hold (the edge's
quadratic is convex enough, its vertex is within `tol`, A > 0 along the edge, the gradient
pushes into the box on the band about the vertex) AND its 2 x EDGE_PIECES pieces are cleared,
which is most of its work. `_edge_may` computes those cheap conditions the same way, and an
edge is tried only where they hold: as `_edge`'s answer is their conjunction with the pieces'
tests, a screened-out edge is one `_edge` declines, and the answers are the same bit for bit
(tests/test_surface_edge_screen.py checks both on random and on benchmark nets). Were the
screen ever stricter than `_edge`'s conditions, an edge it skips would only leave its net
declined, to the careful path: never a wrong answer.

Measured on the at_cubic benchmark's 10,000 thin plate nets (901 declined by the interior
certificate; load 8, CPU time, best of 21): the edge pass 0.77 ms unscreened, 0.19 ms
screened, of a stage of 1.3 ms. The edge pass runs scalar (each net stops at its first
certified edge), the interior certificate and the coefficients are `optimise_batch`'s.

Imported only by lambda_bezier.param_surface_optimum, when numba is installed and not
disabled.
"""

from __future__ import annotations

from typing import Any

import numba
import numpy as np

from . import surface_batch_compiled as sbc
from . import surface_certify as sc
from . import surface_coefficients_ir as emitted

# inlined from surface_certify like surface_batch_compiled's kernels: cached only where its
# recorded hash of surface_certify's source holds (else compiled afresh, never stale code)
_JIT: dict[str, Any] = {"cache": sbc._JIT["cache"], "error_model": "numpy"}
_at, _slope, _clip = sbc._CERTIFY["_at"], sbc._CERTIFY["_slope"], sbc._CERTIFY["_clip"]
_quadratic_positive, _edge = sbc._CERTIFY["_quadratic_positive"], sbc._CERTIFY["_edge"]
_largest, _certified_at = sbc._CERTIFY["_largest"], sbc._certified_at
ROUND, GRADIENT_ROUND, RADIUS = sc.ROUND, sc.GRADIENT_ROUND, sc.RADIUS


@numba.njit(inline="always", error_model="numpy")
def _edge_may(
    a0: float,
    a1: float,
    a2: float,
    b0: float,
    b1: float,
    b2: float,
    c1: float,
    c2: float,
    s0: float,
    inward: float,
    lo: float,
    hi: float,
    r: float,
    emax: float,
    tol: float,
) -> bool:
    """surface_certify._edge's conditions before its pieces, on its arguments (less c0, which
    only they use), computed by the same steps: False where `_edge` declines the edge."""
    m = max(1.0, abs(lo), abs(hi))
    reach = emax * (1 + abs(s0) + s0 * s0)
    slack = ROUND * reach * (1 + m + m * m)
    q1 = _at(c1, b1, a1, s0)
    q2 = _at(c2, b2, a2, s0)
    err = GRADIENT_ROUND * reach
    if not q2 > err:  # _edge's `cup`
        return False
    vertex = -q1 / (2 * q2)
    t = _clip(vertex, lo, hi)
    delta = err * (1 + 2 * abs(vertex)) / (2 * (q2 - err)) + GRADIENT_ROUND * abs(vertex)
    if not delta <= tol:
        return False
    g0 = inward * _slope(b0, a0, s0)
    g1 = inward * _slope(b1, a1, s0)
    g2 = inward * _slope(b2, a2, s0)
    if not _quadratic_positive(a0, a1, a2, lo, hi, slack):
        return False
    return bool(_quadratic_positive(g0, g1, g2, max(t - r, lo), min(t + r, hi), slack))


@numba.njit(**_JIT)
def _edges(acc: np.ndarray, n: int, box: np.ndarray, tol: float, out: np.ndarray) -> None:
    """surface_batch_compiled._certify_chunk's second loop (edge_minimum on the nets the
    interior certificate declined, status 2.0 where an edge certifies, its four edges in
    edge_minimum's order, stopping at the first certified), each edge screened by
    `_edge_may` first."""
    xlo, xhi, ylo, yhi = box[0], box[1], box[2], box[3]
    r = RADIUS * max(xhi - xlo, yhi - ylo)
    for k in range(n):
        if out[4, k] != 0.0:
            continue
        e00, e01, e02, e10, e11, e12 = (
            acc[0, k],
            acc[1, k],
            acc[2, k],
            acc[3, k],
            acc[4, k],
            acc[5, k],
        )
        e20, e21, e22 = acc[6, k], acc[7, k], acc[8, k]
        emax = _largest(e00, e01, e02, e10, e11, e12, e20, e21, e22)
        for side in range(4):
            # x = xlo, xhi: E = A(y) x² + B(y) x + C(y); y = ylo, yhi: E = F(x) y² + G(x) y + H(x)
            if side < 2:
                s0, lo, hi = (xlo if side == 0 else xhi), ylo, yhi
                a0, a1, a2, b0, b1, b2, c0, c1, c2 = e20, e21, e22, e10, e11, e12, e00, e01, e02
            else:
                s0, lo, hi = (ylo if side == 2 else yhi), xlo, xhi
                a0, a1, a2, b0, b1, b2, c0, c1, c2 = e02, e12, e22, e01, e11, e21, e00, e10, e20
            inward = 1.0 if side % 2 == 0 else -1.0
            if not _edge_may(a0, a1, a2, b0, b1, b2, c1, c2, s0, inward, lo, hi, r, emax, tol):
                continue
            t, v, d, ok = _edge(
                a0, a1, a2, b0, b1, b2, c0, c1, c2, s0, inward, lo, hi, r, emax, tol
            )
            if ok:
                out[0, k], out[1, k] = (s0, t) if side < 2 else (t, s0)
                out[2, k], out[3, k], out[4, k] = v, d, 2.0
                break


@numba.njit(**_JIT)
def _interior(acc: np.ndarray, n: int, box: np.ndarray, tol: float, out: np.ndarray) -> None:
    """surface_batch_compiled._certify_chunk's first loop (certified_minimum on every net,
    branch-free, so it vectorises): status 1.0 certified, 0.0 declined."""
    xlo, xhi, ylo, yhi = box[0], box[1], box[2], box[3]
    for k in range(n):
        x, y, e, d, ok = _certified_at(acc, k, xlo, xhi, ylo, yhi, tol)
        out[0, k] = x
        out[1, k] = y
        out[2, k] = e
        out[3, k] = d
        out[4, k] = 1.0 if ok else 0.0


def optimise_batch(
    flat: np.ndarray, dim: int, w: tuple[np.ndarray, ...], box: np.ndarray, tol: float, limit: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, bool]:
    """surface_batch_compiled.optimise_batch's answers, bit for bit (the same arguments),
    with the edge pass screened; where the emitted coefficients do not apply (a batch under
    its EMITTED_MIN_NETS, weights over its MAX_OPERATIONS, no code built here), that function
    itself."""
    count = flat.shape[0]
    fits = count >= sbc.EMITTED_MIN_NETS and emitted.operations(w, dim) <= emitted.MAX_OPERATIONS
    fn = emitted.kernel(w, dim, flat.shape[1]) if fits else None
    if fn is None:
        return sbc.optimise_batch(flat, dim, w, box, tol, limit, use_emitted=False)
    out = np.empty((5, count))
    span = count if count <= sbc.ONE_PASS else sbc.SPAN
    acc = np.empty((9, span))
    answers = out if span == count else np.empty((5, span))  # one span: no copy
    valid = True
    for start in range(0, count, span):
        stop = min(count, start + span)
        valid &= emitted.coefficients(fn, flat, start, stop, acc, limit)
        _interior(acc, stop - start, box, tol, answers)
        _edges(acc, stop - start, box, tol, answers)
        if answers is not out:
            out[:, start:stop] = answers[:, : stop - start]
    return out[0], out[1], out[2], out[3], out[4], valid
