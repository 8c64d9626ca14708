"""The batch optimum of (λ_u, λ_v), compiled with numba (the `fast` extra): one pass over the
nets in cache-sized chunks, each chunk transposed once (net index last, so every later loop
runs over contiguous lanes and vectorises), its energy coefficients from the Gram products,
then hazmat.surface_certify's fixed-cost certified minimum, compiled from the same source.

The coefficients: e_ab = Σ_p W[p, 3a + b] g_p over the pairs p = (i, j), i <= j, of control
points, g_p = P_i · P_j, in the basis of hazmat.surface_weights, where each direction's
λ-part touches only a few points: each net's chunk lanes are changed to that basis first
(48 multiply-adds a bicubic net), and each block of four pairs is added only into the powers
it has (536 weights for the 000 bicubic thin plate, against 9 x 136 in the net's own basis).
The Kronecker route (contract the net with the per-direction forms first, P ↦ A_u P A_v^T)
costs more at these sizes: each of the nine λ-powers needs its own pair of small products
(about 3,600 multiply-adds a net for the thin plate energy, 2,400 through orthonormal
features).

Then, per net, surface_certify.certified_minimum (vectorised over the chunk) and, for the
nets it declines, surface_certify.edge_minimum.

Validation rides along: the transposition notes any coordinate that is not finite or is above
`limit`, and the caller raises the same errors as the numpy path.

`optimise_batch` is the entry for large batches: the coefficients come from straight-line
vector code emitted for the energy's weights (hazmat.surface_coefficients_ir: about 4x faster
than `_coefficients_chunk` with its transposition, but built once per energy, net shape and
dimension in about 0.4 s), then the same `_certify_chunk`. `optimise` stays the entry for
small batches and for weights too many for the emitted code.
"""

from __future__ import annotations

import hashlib
import types
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numba
import numpy as np

from . import surface_certify as sc
from . import surface_coefficients_ir as emitted

# numba's cache of a kernel is keyed to the file that defines it, here, yet the kernels inline
# surface_certify's code: its source's hash is recorded below, so that editing it means
# editing this file too (tests/test_surfaces_certify.py checks the two agree). Where they
# differ anyway (an edit without the tests), the kernels compile afresh, uncached, rather
# than load code of the old certificate.
CERTIFY_SHA256 = "57b1e97cf88bc2e99ede8bcb2a8efc3c61578c81ca22986adbdbf0b3e4deada6"


def certify_source_sha256() -> str:
    return hashlib.sha256(Path(sc.__file__).read_bytes()).hexdigest()


_JIT: dict[str, Any] = {
    "cache": certify_source_sha256() == CERTIFY_SHA256,
    "error_model": "numpy",
    "fastmath": False,
}
CHUNK = 64  # nets per chunk: the transposed chunk (s·d x CHUNK floats) stays in L1


@numba.njit(cache=True, error_model="numpy")
def far_from_origin(nets: np.ndarray, ratio: float) -> np.ndarray:
    """For (k, m+1, n+1, d) nets: whether each net's first point is more than `ratio` times as
    far from the origin (max norm) as the farthest of its other corners is from it (NaN is
    not screened here: the caller's checks refuse it). One pass over the corners
    (numpy's column-by-column version took 2.6 read passes of a bicubic batch)."""
    k, m1, n1, d = nets.shape
    out = np.zeros(k, np.bool_)
    for i in range(k):
        size = 0.0
        reach = 0.0
        for c in range(d):
            f = nets[i, 0, 0, c]
            size = max(size, abs(f))
            reach = max(reach, abs(nets[i, 0, n1 - 1, c] - f))
            reach = max(reach, abs(nets[i, m1 - 1, 0, c] - f))
            reach = max(reach, abs(nets[i, m1 - 1, n1 - 1, c] - f))
        out[i] = size > ratio * reach
    return out


@numba.njit(inline="always", error_model="numpy")
def _select(c: bool, a: float, b: float) -> float:
    return a if c else b


@numba.njit(inline="always", error_model="numpy")
def _none_scalar(c: bool) -> bool:
    return not c


@numba.njit(inline="always", error_model="numpy")
def _every_scalar(c: bool) -> bool:
    return c


def _recompiled(names: tuple[str, ...]) -> dict[str, Callable[..., Any]]:
    """surface_certify's functions compiled for scalars: the same code objects with `_where`
    bound to a scalar selection, `_none` to a scalar `not` and `_every` to the scalar itself
    (and their calls to each other bound to the compiled ones)."""
    space: dict[str, Any] = dict(vars(sc))
    space["_where"] = _select
    space["_none"] = _none_scalar
    space["_every"] = _every_scalar
    out: dict[str, Callable[..., Any]] = {}
    for name in names:  # callees first
        fn = getattr(sc, name)
        copy = types.FunctionType(fn.__code__, space, name, fn.__defaults__)
        copy.__qualname__ = f"surface_batch_compiled.{name}"
        # inlined into the cached kernels below (numba inlines at its own IR level, so the
        # loops over nets see straight-line code)
        out[name] = space[name] = numba.njit(inline="always", error_model="numpy")(copy)
    return out


_CERTIFY = _recompiled(
    (
        "_clip",
        "_at",
        "_slope",
        "_step",
        "_sweep",
        "_newton",
        "_quartic_positive",
        "_quadratic_positive",
        "_discriminant",
        "_side_clear",
        "_largest",
        "_direction",
        "_local_bounds",
        "certified_minimum",
        "_edge",
        "edge_band_minimum",
        "edge_minimum",
        "_grows_from",
        "_side_clear_pieces",
        "_search_start",
        "retry_minimum",
    )
)


def _lane(
    acc: np.ndarray, k: int, xlo: float, xhi: float, ylo: float, yhi: float, tol: float
) -> Any:
    """`_target` (certified_minimum or edge_minimum, bound by _on_lane) on net k's nine
    energy coefficients acc[0..8, k] and the box."""
    return _target(  # type: ignore[name-defined]  # noqa: F821  (bound by _on_lane)
        acc[0, k],
        acc[1, k],
        acc[2, k],
        acc[3, k],
        acc[4, k],
        acc[5, k],
        acc[6, k],
        acc[7, k],
        acc[8, k],
        xlo,
        xhi,
        ylo,
        yhi,
        tol,
    )


def _on_lane(target: Callable[..., Any], name: str) -> Callable[..., Any]:
    """_lane with `_target` bound to a compiled certificate (the same code object, its own
    globals, as _recompiled does): one spelled-out call for both certificates."""
    copy = types.FunctionType(_lane.__code__, {"_target": target}, name)
    copy.__qualname__ = f"surface_batch_compiled.{name}"
    fn: Callable[..., Any] = numba.njit(inline="always", error_model="numpy")(copy)
    return fn


_certified_minimum, _edge_minimum = _CERTIFY["certified_minimum"], _CERTIFY["edge_minimum"]
_certified_at = _on_lane(_certified_minimum, "_certified_at")
_edge_at = _on_lane(_edge_minimum, "_edge_at")
_retry_at = _on_lane(_CERTIFY["retry_minimum"], "_retry_at")
_edge, _largest = _CERTIFY["_edge"], _CERTIFY["_largest"]


@numba.njit(inline="always", error_model="numpy")
def _edge_first_at(
    acc: np.ndarray,
    k: int,
    xlo: float,
    xhi: float,
    ylo: float,
    yhi: float,
    tol: float,
    r: float,
) -> Any:
    """edge_band_minimum (edge_minimum at r = RADIUS · box) on net k's coefficients (as
    _edge_at), its four edges tried in its order and the rest skipped after the first it
    certifies: that one is its answer, so the result is the same bit for bit
    (tests/test_surfaces_edge_certify.py checks it), at a third less work on the declined
    nets of a typical batch (most certify on their first or third edge). The edges'
    arguments are edge_band_minimum's."""
    e00, e01, e02, e10, e11, e12 = acc[0, k], acc[1, k], acc[2, k], acc[3, k], acc[4, k], acc[5, k]
    e20, e21, e22 = acc[6, k], acc[7, k], acc[8, k]
    emax = _largest(e00, e01, e02, e10, e11, e12, e20, e21, e22)
    zero = 0.0 * e00
    t, v, d, ok = _edge(
        e20, e21, e22, e10, e11, e12, e00, e01, e02, xlo, 1.0, ylo, yhi, r, emax, tol
    )
    x, y = xlo + zero, t
    if not ok:
        t, v, d, ok = _edge(
            e20, e21, e22, e10, e11, e12, e00, e01, e02, xhi, -1.0, ylo, yhi, r, emax, tol
        )
        x, y = xhi + zero, t
    if not ok:
        t, v, d, ok = _edge(
            e02, e12, e22, e01, e11, e21, e00, e10, e20, ylo, 1.0, xlo, xhi, r, emax, tol
        )
        x, y = t, ylo + zero
    if not ok:
        t, v, d, ok = _edge(
            e02, e12, e22, e01, e11, e21, e00, e10, e20, yhi, -1.0, xlo, xhi, r, emax, tol
        )
        x, y = t, yhi + zero
    return x, y, v, d, ok


@numba.njit(**_JIT)
def _certify_chunk(acc: np.ndarray, n: int, box: np.ndarray, tol: float, out: np.ndarray) -> None:
    """certified_minimum for the chunk's n nets into out[:, :n] (x, y, energy, δ, status:
    1.0 certified, 0.0 declined): one output array, indexed by the loop variable alone, and
    no branches, so the loop vectorises (measured: five output arrays, or an offset index,
    kept it scalar, 3-4x slower). Then edge_minimum for the declined nets alone (about 1 in
    60; scalar, so _edge_first_at's early stop), status 2.0 where it certifies an edge or
    corner minimum, and on what that declines retry_minimum (status 1.0) and retry_edges
    (its bands in turn, each by _edge_first_at; status 2.0), as surface_fixed_cost runs them."""
    xlo, xhi, ylo, yhi = box[0], box[1], box[2], box[3]
    for k in range(n):
        x, y, e, d, ok = _certified_at(acc, k, xlo, xhi, ylo, yhi, tol)
        out[0, k] = x
        out[1, k] = y
        out[2, k] = e
        out[3, k] = d
        out[4, k] = 1.0 if ok else 0.0
    radius = sc.RADIUS * max(xhi - xlo, yhi - ylo)
    for k in range(n):
        if out[4, k] == 0.0:
            x, y, e, d, ok = _edge_first_at(acc, k, xlo, xhi, ylo, yhi, tol, radius)
            status = 2.0
            if not ok:  # the retries (surface_certify.retry_minimum, then retry_edges)
                x, y, e, d, ok = _retry_at(acc, k, xlo, xhi, ylo, yhi, tol)
                status = 1.0
                r = radius
                for _ in range(sc.EDGE_BANDS):
                    if ok:
                        break
                    r = 0.5 * r
                    x, y, e, d, ok = _edge_first_at(acc, k, xlo, xhi, ylo, yhi, tol, r)
                    status = 2.0
            if ok:
                out[0, k] = x
                out[1, k] = y
                out[2, k] = e
                out[3, k] = d
                out[4, k] = status


@numba.njit(**_JIT)
def _transpose_chunk(flat: np.ndarray, start: int, n: int, limit: float, lanes: np.ndarray) -> bool:
    """lanes[r, k] = flat[start + k, r]; whether every value was finite and <= limit."""
    valid = True
    for k in range(n):
        row = flat[start + k]
        for r in range(row.shape[0]):
            v = row[r]
            valid &= abs(v) <= limit  # False for NaN too
            lanes[r, k] = v
    return valid


@numba.njit(cache=_JIT["cache"], error_model="numpy", fastmath={"contract"})
def _coefficients_chunk(
    lanes: np.ndarray,
    dim: int,
    w: tuple[np.ndarray, ...],
    gram: np.ndarray,
    acc: np.ndarray,
) -> None:
    """acc[t, k] = Σ_p weights[p, t] g_p(k) for the chunk's nets (lanes k), in the basis of
    hazmat.surface_weights (w: its BatchWeights): first the change of basis on the lanes,
    then the Gram products of BLOCK pairs at a time, each block added into the powers it has
    (the updates' loads and stores bound the loop, so a power a block lacks is skipped).
    Every loop runs over the lanes alone, so each vectorises. Multiply-adds may fuse
    (fastmath "contract" only: one rounding instead of two, no reassociation)."""
    pair_i, pair_j, weights, block_start, block_powers, mix_t, mix_s, mix_w = w
    width = lanes.shape[1]
    n_pairs = pair_i.shape[0]
    for r in range(mix_t.shape[0]):
        t, s, c = mix_t[r], mix_s[r], mix_w[r]
        for k in range(width):
            lanes[t, k] += c * lanes[s, k]
    acc[:, :] = 0.0
    last = n_pairs - 1
    for q in range(0, n_pairs, 4):
        for s in range(4):
            p = min(q + s, last)
            a, b = pair_i[p] * dim, pair_j[p] * dim
            if q + s > last:  # past the last pair: a zero product (weights unused)
                for k in range(width):
                    gram[s, k] = 0.0
                continue
            for k in range(width):
                gram[s, k] = lanes[a, k] * lanes[b, k]
            for c in range(1, dim):
                for k in range(width):
                    gram[s, k] += lanes[a + c, k] * lanes[b + c, k]
        block = q // 4
        for u in range(block_start[block], block_start[block + 1]):
            t = block_powers[u]
            w0 = weights[q, t]
            w1 = weights[min(q + 1, last), t]
            w2 = weights[min(q + 2, last), t]
            w3 = weights[min(q + 3, last), t]
            for k in range(width):
                acc[t, k] += w0 * gram[0, k] + w1 * gram[1, k] + w2 * gram[2, k] + w3 * gram[3, k]


@numba.njit(**_JIT)
def optimise(
    flat: np.ndarray,
    dim: int,
    w: tuple[np.ndarray, ...],
    box: np.ndarray,
    tol: float,
    limit: float,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, bool]:
    """For nets flat (k, s·d) (control point i's coordinates at i·d .. i·d + d − 1) and the
    energy Σ_p weights[p, 3a + b] g_p x^a y^b in the basis of w (hazmat.surface_weights'
    BatchWeights, g_p the Gram products of the changed net): per net (x, y, energy, δ, status)
    of surface_certify.certified_minimum over box = (xlo, xhi, ylo, yhi), or of its
    edge_minimum where that declines (status 1.0: an interior minimum certified, 2.0: an edge
    or corner minimum certified, 0.0: declined), and whether every coordinate was finite and
    <= limit."""
    count, width = flat.shape
    out = np.empty((5, count))
    lanes = np.zeros((width, CHUNK))
    acc = np.empty((9, CHUNK))
    gram = np.empty((4, CHUNK))
    answers = np.empty((5, CHUNK))
    valid = True
    for start in range(0, count, CHUNK):
        n = min(CHUNK, count - start)
        valid &= _transpose_chunk(flat, start, n, limit, lanes)
        _coefficients_chunk(lanes, dim, w, gram, acc)
        _certify_chunk(acc, n, box, tol, answers)
        for row in range(5):
            for k in range(n):
                out[row, start + k] = answers[row, k]
    return out[0], out[1], out[2], out[3], out[4], valid


# optimise_batch: batches smaller than this take `optimise` (the emitted code's first build,
# about 0.3 s, pays off only over many nets). Up to ONE_PASS nets run as one span, the
# certificate writing straight into the result (measured on 10,000 bicubic nets: 0.577 ms
# against 0.598 ms in spans of 2,048 with a copy of the answers); larger batches in spans of
# SPAN nets (the coefficients, 9 x SPAN floats, in the core's L2: on 50,000 nets, spans of
# 2,048 to 16,384 measured alike, 3.6-3.8 ms)
EMITTED_MIN_NETS = 1024
ONE_PASS = 16384
SPAN = 4096


def optimise_batch(
    flat: np.ndarray,
    dim: int,
    w: tuple[np.ndarray, ...],
    box: np.ndarray,
    tol: float,
    limit: float,
    *,
    use_emitted: bool | None = None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, bool]:
    """`optimise`'s answers (the same arguments, flat C-contiguous float64), with the
    coefficients from hazmat.surface_coefficients_ir when `use_emitted` (None: for batches of
    at least EMITTED_MIN_NETS nets whose weights are within its MAX_OPERATIONS) and that
    module can build its code here; otherwise `optimise` itself."""
    count = flat.shape[0]
    if use_emitted is None:
        use_emitted = (
            count >= EMITTED_MIN_NETS and emitted.operations(w, dim) <= emitted.MAX_OPERATIONS
        )
    fn = emitted.kernel(w, dim, flat.shape[1]) if use_emitted else None
    if fn is None:
        return optimise(flat, dim, w, box, tol, limit)  # type: ignore[no-any-return]
    out = np.empty((5, count))
    span = count if count <= ONE_PASS else SPAN
    acc = np.empty((9, span))
    answers = out if span == count else np.empty((5, span))  # one span: no copy
    valid = True
    for start in range(0, count, span):
        stop = min(count, start + span)
        valid &= emitted.coefficients(fn, flat, start, stop, acc, limit)
        _certify_chunk(acc, stop - start, box, tol, answers)
        if answers is not out:
            out[:, start:stop] = answers[:, : stop - start]
    return out[0], out[1], out[2], out[3], out[4], valid
