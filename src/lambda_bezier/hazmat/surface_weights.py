"""The surface energy as weights of Gram products in a basis where the λ-dependence is sparse:
what the compiled batch optimum (hazmat.surface_batch_compiled) contracts each net with.

E(λ_u, λ_v) = Σ_ab λ_u^a λ_v^b vec(P)ᵀ Q_ab vec(P). A family's basis is b(t; λ) = C_0 B(t) +
λ C_1 B(t) (B the Bernstein basis); the λ-part lives in the column space of C_1, of rank r
(2 for the 000 cubic, 3 for 001's). In the control points Z = M P, with M the identity whose
rows at r pivots are a reduced echelon basis of that column space, the λ-part of the basis is
carried by the r pivot rows alone: a power λ_u^a, a >= 1, then only weighs pairs of points
with a u-pivot index (and the same in v). In this basis the bicubic thin-plate energy of the
000 family has 536 nonzero weights against 9 x 136 = 1224 in the net's own; the Gram products
cost the same (136 pairs, d multiply-adds each), the change of basis about 100 multiply-adds.

Everything here is exact (Fractions) until the weights are rounded once to floats; M is
unimodular (determinant 1) and M⁻¹ = 2I − M, so Q'_ab = M⁻ᵀ Q_ab M⁻¹ is exact too.
"""

from __future__ import annotations

from collections.abc import Mapping
from fractions import Fraction
from typing import Any, NamedTuple

import numpy as np

Exact = tuple[tuple[Fraction, ...], ...]
BLOCK = 4  # pairs per accumulator update in the compiled kernel


class BatchWeights(NamedTuple):
    """The energy in the basis Z = (M_u ⊗ M_v) vec(P), ready for the compiled kernel.

    pair_i, pair_j: the pairs (i <= j) of points of Z with a nonzero weight, sorted so that
    each block of BLOCK pairs shares its powers; weights[p, 3a + b]: pair p's weight of
    λ_u^a λ_v^b (the off-diagonal ones doubled); block_start, block_powers: block q updates
    the powers block_powers[block_start[q]:block_start[q + 1]] only; mix_target,
    mix_source, mix_weight: the change of basis on a net's coordinates (row r·d + c of point
    r), applied in order: row[target] += weight · row[source]."""

    pair_i: np.ndarray
    pair_j: np.ndarray
    weights: np.ndarray
    block_start: np.ndarray
    block_powers: np.ndarray
    mix_target: np.ndarray
    mix_source: np.ndarray
    mix_weight: np.ndarray


def lambda_pivots(lam_part: Exact | None, size: int) -> list[tuple[int, list[Fraction]]]:
    """The non-identity rows of M for one direction: (pivot, row) with the rows a reduced
    echelon basis of the column space of the basis's λ-part C_1 (size x N), each 1 at its
    pivot and 0 at the others. None (a family without λ): M is the identity."""
    if lam_part is None:
        return []
    rows = [[Fraction(lam_part[i][c]) for i in range(size)] for c in range(len(lam_part[0]))]
    pivots: list[int] = []
    rank = 0
    for col in range(size):
        found = next((i for i in range(rank, len(rows)) if rows[i][col] != 0), None)
        if found is None:
            continue
        rows[rank], rows[found] = rows[found], rows[rank]
        lead = rows[rank][col]
        rows[rank] = [x / lead for x in rows[rank]]
        for i, row in enumerate(rows):
            if i != rank and row[col] != 0:
                f = row[col]
                rows[i] = [x - f * y for x, y in zip(row, rows[rank], strict=True)]
        pivots.append(col)
        rank += 1
    return [(p, rows[s]) for s, p in enumerate(pivots)]


def _inverse(pivots: list[tuple[int, list[Fraction]]], size: int) -> list[list[Fraction]]:
    """M⁻¹ = 2I − M: M − I maps the non-pivot coordinates into the pivot ones only, so
    (M − I)² = 0."""
    inv = [[Fraction(int(r == c)) for c in range(size)] for r in range(size)]
    for p, row in pivots:
        for c in range(size):
            if c != p:
                inv[p][c] = -row[c]
    return inv


def batch_weights(
    full: dict[tuple[int, int], Exact],
    u_lam: Exact | None,
    v_lam: Exact | None,
    shape: tuple[int, int],
    dim: int,
) -> BatchWeights:
    """The weights of the energy matrices `full` (Q_ab over vec(P), points row by row) for
    nets of `shape` (m+1, n+1) points in `dim` coordinates, with u_lam, v_lam each direction's
    C_1 (None for a direction without λ)."""
    m1, n1 = shape
    size = m1 * n1
    pu, pv = lambda_pivots(u_lam, m1), lambda_pivots(v_lam, n1)
    iu, iv = _inverse(pu, m1), _inverse(pv, n1)
    # Kinv = M_u⁻¹ ⊗ M_v⁻¹ as sparse columns: vec(P)_r = Σ_s Kinv[r][s] vec(Z)_s
    cols: list[list[tuple[int, Fraction]]] = [[] for _ in range(size)]
    for i in range(m1):
        for k in range(m1):
            if iu[i][k]:
                for j in range(n1):
                    for l_ in range(n1):
                        if iv[j][l_]:
                            cols[k * n1 + l_].append((i * n1 + j, iu[i][k] * iv[j][l_]))
    transformed: dict[int, list[list[Fraction]]] = {}
    for (a, b), form in full.items():
        # Q' = Kinvᵀ Q Kinv, one column of Kinv at a time
        qk = [[sum((form[r][t] * w for t, w in cols[s]), Fraction(0)) for s in range(size)]
              for r in range(size)]  # fmt: skip
        transformed[3 * a + b] = [
            [sum((w * qk[t][s] for t, w in cols[r]), Fraction(0)) for s in range(size)]
            for r in range(size)
        ]
    entries = _entries(*pair_weights(transformed, size))
    mix: list[tuple[int, int, Fraction]] = []
    for p, row in pu:  # Z = M_u P first (rows), then Z M_vᵀ (columns)
        for k in range(m1):
            if k != p and row[k]:
                mix += [((p * n1 + j) * dim + c, (k * n1 + j) * dim + c, row[k])
                        for j in range(n1) for c in range(dim)]  # fmt: skip
    for p, row in pv:
        for k in range(n1):
            if k != p and row[k]:
                mix += [((i * n1 + p) * dim + c, (i * n1 + k) * dim + c, row[k])
                        for i in range(m1) for c in range(dim)]  # fmt: skip
    return _blocked(entries, mix)


def pair_weights(forms: Mapping[int, Any], size: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The energy's forms {3a + b: Q_ab} (size x size, Fractions or floats, read at i <= j)
    as weights of the Gram products P_i · P_j: (pair_i, pair_j, W) with W[p, 3a + b] the
    weight of λ_u^a λ_v^b on pair p (off the diagonal doubled: both orders), each rounded to a
    float once; the pairs whose weights are all 0 dropped. The one place both batch optima
    (exact matrices in surface_optimum, float ones in param_surface_optimum) build them."""
    rows_i, rows_j = np.triu_indices(size)
    twice = np.where(rows_i == rows_j, 1.0, 2.0)
    w = np.zeros((rows_i.size, 9))
    for t, mat in forms.items():
        w[:, t] = twice * np.array([float(mat[i][j]) for i, j in zip(rows_i, rows_j, strict=True)])
    keep = w.any(axis=1)
    ints: Any = np.int64
    return rows_i[keep].astype(ints), rows_j[keep].astype(ints), np.ascontiguousarray(w[keep])


def _entries(
    pair_i: np.ndarray, pair_j: np.ndarray, weights: np.ndarray
) -> list[tuple[tuple[int, ...], int, int, np.ndarray]]:
    return [
        (tuple(int(t) for t in np.flatnonzero(w)), int(i), int(j), np.asarray(w, dtype=float))
        for i, j, w in zip(pair_i, pair_j, weights, strict=True)
        if w.any()
    ]


def plain_weights(pair_i: np.ndarray, pair_j: np.ndarray, weights: np.ndarray) -> BatchWeights:
    """BatchWeights of Gram products in the net's own basis (no change of basis): pairs
    (pair_i[p], pair_j[p]) with weights[p, 3a + b] the weight of λ_u^a λ_v^b, for energies
    whose λ-part has no sparse basis here (param_surface_optimum's atom families)."""
    return _blocked(_entries(pair_i, pair_j, weights), [])


def _blocked(
    entries: list[tuple[tuple[int, ...], int, int, np.ndarray]],
    mix: list[tuple[int, int, Fraction]],
) -> BatchWeights:
    """The kernel's layout of (powers, i, j, weights) pairs and a change of basis `mix`."""
    # pairs with the same powers side by side: most blocks then update only their own powers
    entries = sorted(entries, key=lambda e: (-len(e[0]), e[0], e[1], e[2]))
    block_start, block_powers = [0], []
    for start in range(0, len(entries), BLOCK):
        union = sorted({t for e in entries[start : start + BLOCK] for t in e[0]})
        block_powers.extend(union)
        block_start.append(len(block_powers))
    ints: Any = np.int64
    return BatchWeights(
        np.array([e[1] for e in entries], dtype=ints),
        np.array([e[2] for e in entries], dtype=ints),
        np.array([e[3] for e in entries]).reshape(-1, 9),
        np.array(block_start, dtype=ints),
        np.array(block_powers, dtype=ints),
        np.array([t for t, _, _ in mix], dtype=ints),
        np.array([s for _, s, _ in mix], dtype=ints),
        np.array([float(w) for _, _, w in mix]),
    )
