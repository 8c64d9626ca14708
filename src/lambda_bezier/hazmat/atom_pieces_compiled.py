"""The piecewise evaluation of `atom_pieces` compiled with numba (the `fast` extra).

Blocks of parameters: the pieces and the offsets t − centre of a block first, then for every
coordinate Horner's rule along the block, each pass gathering one coefficient per parameter
from one contiguous row of the table (the loops vectorise, gathers included). The arithmetic
is `atom_pieces.evaluate_pieces`' in the same order, without fused multiply-adds (numba does
not contract them without fastmath), so the two agree bit for bit; tests/test_atom_pieces.py
runs both.

Imported only through `atom_pieces.compiled()` (numba compiles on first use and caches the
machine code next to this file).
"""

from __future__ import annotations

from typing import Any

import numba
import numpy as np

_JIT: dict[str, Any] = {"cache": True, "error_model": "numpy", "nogil": True}
_BLOCK = 512  # parameters per block: pieces, offsets and the block's output stay in L1


@numba.njit(**_JIT)
def evaluate_pieces(
    t: np.ndarray,
    lo: float,
    inv_width: float,
    centres: np.ndarray,
    table: np.ndarray,
    out: np.ndarray,
) -> None:
    """out[c, i] = Σ_e table[c, e, k] (t[i] − centres[k])^e, k = int((t[i] − lo)·inv_width)
    clamped to [0, m − 1]."""
    dim, size, m = table.shape
    piece = np.empty(_BLOCK, np.int64)
    offset = np.empty(_BLOCK)
    for start in range(0, t.size, _BLOCK):
        count = min(_BLOCK, t.size - start)
        for j in range(count):
            x = t[start + j]
            k = int((x - lo) * inv_width)
            k = min(max(k, 0), m - 1)
            piece[j] = k
            offset[j] = x - centres[k]
        for c in range(dim):
            acc = out[c, start : start + count]
            row = table[c, size - 1]
            for j in range(count):
                acc[j] = row[piece[j]]
            for e in range(size - 2, -1, -1):
                row = table[c, e]
                for j in range(count):
                    acc[j] = acc[j] * offset[j] + row[piece[j]]
