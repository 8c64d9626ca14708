"""optimal_lambda's batch pass without numba (issue #29): the interface of
`batch_compiled.energy_optimum`, in numpy, chunk by chunk.

Per chunk of polygons: one matrix product Z = Fᵀ P (BLAS), three row-wise dot products of
Z (the coefficients a₀, a₁, a₂), then λ* = −a₁/(2a₂), the admissibility and the energies,
each numpy call writing into a working buffer reused across chunks or straight into the
results. What the careful path (energy._float_optimum_chunk) spent on every polygon — the
squared norm of every polygon (a pass over the input), the seven passes of its
finite-and-rounding test, the temporaries of the optimum — is replaced by a test per
chunk: the sums of a₀ and a₂ are finite and the least a₂ exceeds a bound on every polygon's
rounding bound in the chunk (from the chunk's largest |coordinate|, two reductions over
the chunk, read from the cache the product just filled). A chunk that fails the test is
left to the careful path, which rescales its polygons or names the one it refuses; so the
decisions are the careful path's, polygon by polygon, and so are the numbers (the same
product in the careful path's layout, a column per polygon, the same dot products along its
rows and operations in the same order: bit for bit on the same BLAS, tested).
"""

from __future__ import annotations

import numpy as np

from .kernels import chunk_ranges, cpu_count, on_threads

# Threads for the pass: None for one per CPU this process may run on, 1 for none. Each
# takes a slab of whole chunks (numpy's passes and BLAS release the GIL).
THREADS: int | None = None
_MIN_SLAB = 1 << 14  # polygons a thread's slab at least gets: below, one thread


def _threads() -> int:
    return THREADS or cpu_count()


def energy_optimum(
    points: np.ndarray,
    factor: np.ndarray,
    rows: int,
    rounding_weight: float,
    bounds: np.ndarray,
    clamp: bool,
    best: np.ndarray,
    ok_best: np.ndarray,
    energy_best: np.ndarray,
    lam: np.ndarray,
    ok: np.ndarray,
    energy: np.ndarray,
) -> int:
    """`batch_compiled.energy_optimum` in numpy: the same results for every polygon of
    points (m, n+1, d) up to the returned index, the start of the first chunk (of
    `kernels.chunk_ranges(m, factor.shape[1])`, energy._chunks' cut) it leaves to the
    careful path, or m. `factor` is energy._factored_forms' Kronecker form (size·d,
    2·rows); `rounding_weight` multiplies a polygon's squared norm into its rounding bound
    on a₂ (1e-12 Σ|A2|).

    The chunks are shared between threads (THREADS), each a slab of whole chunks."""
    m = points.shape[0]
    chunks = chunk_ranges(m, factor.shape[1])
    workers = min(_threads(), len(chunks), max(1, m // _MIN_SLAB))
    args = (factor, rows, rounding_weight, bounds, clamp)
    results = (best, ok_best, energy_best, lam, ok, energy)
    if workers <= 1:
        return _slab(points, chunks, 0, len(chunks), args, results)
    return min(
        on_threads(lambda a, b: _slab(points, chunks, a, b, args, results), len(chunks), workers)
    )


def _slab(
    points: np.ndarray,
    chunks: list[tuple[int, int]],
    first: int,
    last: int,
    args: tuple[np.ndarray, int, float, np.ndarray, bool],
    results: tuple[np.ndarray, ...],
) -> int:
    """energy_optimum on chunks[first:last]: the start of the first chunk declined, or m.
    Each product is cut into blocks under OpenBLAS's threshold for threads (2^18
    multiply-adds): a thread of ours then starts no threads of BLAS's (on a loaded machine
    BLAS's waiting threads measured 5x slower), and a polygon's numbers do not depend on
    the number of threads."""
    factor, rows, rounding_weight, bounds, clamp = args
    best, ok_best, energy_best, lam, ok, energy = results
    m, size, dim = points.shape
    width = size * dim
    step = chunks[0][1] - chunks[0][0] if chunks else 0
    cols = max(1, (1 << 18) // factor.size)
    # a column per polygon (the careful path's layout, energy._coefficients_of): the wide
    # product Fᵀ Pᵀ, and row-wise dot products that run along contiguous rows of it, took
    # 2.0 ms of CPU per 10^5 quintics against 3.1 ms for the tall P F with dot products over
    # rows of 8 (one thread, OPENBLAS_NUM_THREADS=1; issue #29)
    factor_t = factor.T  # C-contiguous (energy._factored_forms)
    z = np.empty((factor.shape[1], step))
    coeffs = np.empty((3, step))  # a0, a1, a2
    work = np.empty((2, step))
    okwork = np.empty(step, dtype=bool)
    clip_lo, clip_hi, least, greatest = (float(b) for b in bounds)
    # a bound on Σ fl(x²) over a polygon's width coordinates, each at most fl(M²): 2·width·M²
    # exceeds it whatever the order and rounding of the sum (every rounding is monotone)
    spread = 2.0 * width
    for lo, hi in chunks[first:last]:
        c = hi - lo
        part = points[lo:hi]
        flat = part.reshape(c, width)  # a view: row j is polygon lo + j
        zc = z[:, :c]
        a0, a1, a2 = coeffs[0, :c], coeffs[1, :c], coeffs[2, :c]
        with np.errstate(all="ignore"):  # decided by the chunk's test below
            for a in range(0, c, cols):
                np.matmul(factor_t, flat[a : a + cols].T, out=zc[:, a : a + cols])
            zf, zg = zc[:rows], zc[rows:]
            np.einsum("ij,ij->j", zf, zf, out=a0)
            np.einsum("ij,ij->j", zf, zg, out=a1)
            a1 *= 2
            np.einsum("ij,ij->j", zg, zg, out=a2)
            top = max(float(part.max()), -float(part.min()))
            bound = (spread * (top * top)) * rounding_weight
            if not (
                np.isfinite(float(np.add.reduce(a0)) + float(np.add.reduce(a2)))
                and float(a2.min()) > bound
            ):
                return lo
            _optimum_into(a0, a1, a2, best[lo:hi], ok_best[lo:hi], energy_best[lo:hi],
                          least, greatest, work[:, :c], okwork[:c], None)  # fmt: skip
            if clamp:
                _optimum_into(a0, a1, a2, lam[lo:hi], ok[lo:hi], energy[lo:hi],
                              least, greatest, work[:, :c], okwork[:c],
                              (best[lo:hi], clip_lo, clip_hi))  # fmt: skip
    return int(m)


def _optimum_into(
    a0: np.ndarray,
    a1: np.ndarray,
    a2: np.ndarray,
    x: np.ndarray,
    inside: np.ndarray,
    energy: np.ndarray,
    least: float,
    greatest: float,
    work: np.ndarray,
    okwork: np.ndarray,
    clip: tuple[np.ndarray, float, float] | None,
) -> None:
    """x = −a₁/(2a₂) (or, with `clip` = (λ*, low, high), λ* clipped), inside = least ≤ x ≤
    greatest, energy = a₀ + a₁x + a₂x·x: energy._optimum's operations in its order, written
    into the results."""
    if clip is None:  # a₁/(−2a₂): −a₁/(2a₂) bit for bit (rounding is symmetric), a pass less
        np.multiply(a2, -2.0, out=work[0])
        np.divide(a1, work[0], out=x)
    else:
        np.clip(clip[0], clip[1], clip[2], out=x)
    np.greater_equal(x, least, out=inside)
    np.less_equal(x, greatest, out=okwork)
    inside &= okwork
    np.multiply(a1, x, out=work[0])
    work[0] += a0
    np.multiply(a2, x, out=work[1])
    work[1] *= x
    np.add(work[0], work[1], out=energy)
