"""A pair's whole compiled intersection in one call, and many pairs in one call (numba).

Each pair runs the certificate (certify_compiled.certify_one) and, where it declines, the
careful path compiled (settle_compiled.settle), exactly as intersect_certify's two wrappers
run them one after the other from Python: the same kernels on the same argument types (so
numba reuses their compiled code: read-only curve rows, the knobs as tuples, each degree's
half matrices as writeable C arrays), so the answers are the same bit for bit. What this
saves is the Python between and around them (issue #29): per pair one call instead of two,
and for a batch one call for every pair (`pairs`) instead of one or two a pair.

The half matrices of every degree a call needs come in one flat table (`halves`: left then
right, row-major, at `offsets[degree]`), reshaped here without a copy. The knobs come as one
float row (`constants`: intersect_pairs.packed), made back into the tuples the kernels take
here: numba types a tuple of 26 numbers on every call, ~0.3 us of a small pair's ~5 us.

Imported only by intersect_pairs, and only when numba is installed and not disabled; numba
compiles on first use and caches the machine code next to this file (its cache does not see
a change in certify_compiled or settle_compiled: clear __pycache__ after editing those).
"""

from __future__ import annotations

import numba
import numpy as np

from .certify_compiled import Settings, certify_one
from .pieces_compiled import JIT as _JIT
from .refine_compiled import Knobs
from .settle_compiled import settle

_TRANSVERSAL = 1.0  # refine_compiled.TRANSVERSAL: a certified crossing's kind code


@numba.njit(**_JIT)
def _halves(table: np.ndarray, offsets: np.ndarray, degree: int) -> tuple[np.ndarray, np.ndarray]:
    start, size = offsets[degree], (degree + 1) * (degree + 1)
    left = table[start : start + size].reshape((degree + 1, degree + 1))
    right = table[start + size : start + 2 * size].reshape((degree + 1, degree + 1))
    return left, right


@numba.njit(**_JIT)
def _settings(c: np.ndarray) -> Settings:
    """certify_compiled.Settings from constants[0:11] (its first three are counts)."""
    return (int(c[0]), int(c[1]), int(c[2]), c[3], c[4], c[5], c[6], c[7], c[8], c[9], c[10])


@numba.njit(**_JIT)
def _knobs(c: np.ndarray) -> Knobs:
    """refine_compiled.Knobs from constants[11:26] (its 11th to 13th are counts)."""
    return (
        c[11],
        c[12],
        c[13],
        c[14],
        c[15],
        c[16],
        c[17],
        c[18],
        c[19],
        c[20],
        int(c[21]),
        int(c[22]),
        int(c[23]),
        c[24],
        c[25],
    )


@numba.njit(**_JIT)
def _one(
    a: np.ndarray,
    b: np.ndarray,
    constants: np.ndarray,
    careful: bool,
    table: np.ndarray,
    offsets: np.ndarray,
) -> tuple[int, np.ndarray]:
    box_slack, root_residual = constants[26], constants[27]
    knobs = _knobs(constants)
    count, roots = certify_one(a, b, box_slack, root_residual, _settings(constants), knobs)
    if count >= 0:
        hits = np.empty((count, 3))
        for k in range(count):
            hits[k, 0], hits[k, 1], hits[k, 2] = roots[0, k], roots[1, k], _TRANSVERSAL
        return count, hits
    if not careful:
        return -1, np.empty((0, 3))
    count, hits = settle(
        a,
        b,
        knobs,
        _halves(table, offsets, a.shape[0] - 1),
        _halves(table, offsets, b.shape[0] - 1),
    )
    return count, hits


@numba.njit(**_JIT)
def pair(
    a: np.ndarray,
    b: np.ndarray,
    constants: np.ndarray,
    careful: bool,
    table: np.ndarray,
    offsets: np.ndarray,
) -> tuple[int, np.ndarray]:
    """One pair of float curves (n+1, d), (m+1, d) that are the curves exactly, d >= 2:
    (count, hits) with hits (count, 3) rows (s, t, kind code) in the careful path's order,
    count -1 where the certificate declines and (careful False, or) the careful path
    declines too."""
    count, hits = _one(a, b, constants, careful, table, offsets)
    return count, hits


@numba.njit(**_JIT)
def pairs(
    points: np.ndarray,
    starts: np.ndarray,
    first: np.ndarray,
    second: np.ndarray,
    constants: np.ndarray,
    careful: bool,
    table: np.ndarray,
    offsets: np.ndarray,
) -> tuple[np.ndarray, np.ndarray]:
    """Many pairs in one call: curve c is points[starts[c] : starts[c + 1]] (every curve of
    one dimension), pair k is curve first[k] against curve second[k]. (counts, hits): pair
    k's count as `pair` gives it (-1: declined), its hits the next max(count, 0) rows of
    hits, pair after pair."""
    counts = np.empty(first.shape[0], dtype=np.int64)
    out = np.empty((4 * first.shape[0] + 16, 3))
    used = 0
    for k in range(first.shape[0]):
        i, j = first[k], second[k]
        a = points[starts[i] : starts[i + 1]]
        b = points[starts[j] : starts[j + 1]]
        count, hits = _one(a, b, constants, careful, table, offsets)
        counts[k] = count
        if count > 0:
            if used + count > out.shape[0]:
                grown = np.empty((max(2 * out.shape[0], used + count), 3))
                grown[:used] = out[:used]
                out = grown
            out[used : used + count] = hits[:count]
            used += count
    return counts, out[:used]
