"""The energy weights of the compiled batch optimum in the basis where the λ-part is sparse
(hazmat.surface_weights): the change of basis is exact and does what it claims, the weights
give the energy's coefficients, and every nonzero weight is in its block's powers."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from lambda_bezier.hazmat.surface_weights import BLOCK, _inverse, batch_weights, lambda_pivots
from lambda_bezier.surface_energies import surface_energy_matrices
from lambda_bezier.surface_optimum import _batch_weights
from lambda_bezier.surfaces import _as_family_pair, basis_to_bernstein_split

CASES = [
    ("same_degree", (3, 3), "thin_plate"),
    ("same_degree", (3, 4), "membrane"),
    ("bernstein_like", (3, 3), "thin_plate"),
    (("same_degree", "bezier"), (4, 3), "thin_plate"),
    (("bezier", "bernstein_like"), (3, 5), "membrane"),
    ("bezier", (3, 3), "thin_plate"),
]


def weights_for(family, degrees, energy, dim):
    u_cls, v_cls = _as_family_pair(family)
    mats = surface_energy_matrices(degrees, energy, (u_cls, v_cls))
    return mats, _batch_weights(mats, u_cls, v_cls, dim)


def contract(w, flat):
    """The kernel's contraction in numpy: the change of basis in order, then Σ_p w_p g_p."""
    z = flat.copy()
    for t, s, c in zip(w.mix_target, w.mix_source, w.mix_weight, strict=True):
        z[:, t] += c * z[:, s]
    dim = flat.shape[1] // (max(max(w.pair_i), max(w.pair_j)) + 1)
    pts = z.reshape(len(z), -1, dim)
    gram = np.einsum("kpc,kpc->kp", pts[:, w.pair_i], pts[:, w.pair_j])
    return gram @ w.weights  # (k, 9), column 3a + b


@pytest.mark.parametrize(("family", "degrees", "energy"), CASES)
def test_lambda_part_lives_on_the_pivot_rows_exactly(family, degrees, energy):
    """M⁻ᵀ C_1 (the basis's λ-part in the changed points) is zero off the pivot rows, and
    M⁻¹ is M's inverse, in exact arithmetic."""
    for cls, deg in zip(_as_family_pair(family), degrees, strict=True):
        split = basis_to_bernstein_split(cls, deg)
        if len(split) < 2:
            assert lambda_pivots(None, deg + 1) == []
            continue
        c1, size = split[1], deg + 1
        pivots = lambda_pivots(c1, size)
        m = [[Fraction(int(r == c)) for c in range(size)] for r in range(size)]
        for p, row in pivots:
            m[p] = row
        inv = _inverse(pivots, size)
        for r in range(size):
            for c in range(size):
                prod = sum((m[r][k] * inv[k][c] for k in range(size)), Fraction(0))
                assert prod == int(r == c)
        rows = {p for p, _ in pivots}
        for r in set(range(size)) - rows:
            for c in range(len(c1[0])):
                assert sum((inv[k][r] * c1[k][c] for k in range(size)), Fraction(0)) == 0
        assert 0 < len(pivots) < size


@given(seed=st.integers(0, 2**32 - 1), case=st.sampled_from(CASES), dim=st.sampled_from([1, 3]))
def test_weights_give_the_energy_coefficients(seed, case, dim):
    family, degrees, energy = case
    mats, w = weights_for(family, degrees, energy, dim)
    rng = np.random.default_rng(seed)
    nets = rng.normal(size=(5, degrees[0] + 1, degrees[1] + 1, dim)) * rng.uniform(0.1, 10)
    got = contract(w, nets.reshape(5, -1))
    for k in range(5):
        want = mats.polynomial([[[Fraction(x) for x in p] for p in row] for row in nets[k]])
        size = sum(abs(float(v)) for v in want.values()) + 1e-300
        for a in range(3):
            for b in range(3):
                exact = float(want.get((a, b), 0))
                assert abs(got[k, 3 * a + b] - exact) <= 1e-13 * size, (a, b)


@pytest.mark.parametrize(("family", "degrees", "energy"), CASES)
def test_every_nonzero_weight_is_in_its_blocks_powers(family, degrees, energy):
    _, w = weights_for(family, degrees, energy, 3)
    for p in range(len(w.pair_i)):
        q = p // BLOCK
        powers = set(w.block_powers[w.block_start[q] : w.block_start[q + 1]].tolist())
        assert set(np.flatnonzero(w.weights[p]).tolist()) <= powers
    assert (np.diff(w.block_start) >= 1).all()
    assert len(w.block_start) - 1 == -(-len(w.pair_i) // BLOCK)


def test_the_000_bicubic_thin_plate_is_sparse_in_the_changed_basis():
    """536 nonzero weights against 9 x 136 in the net's own basis (the reason for the basis)."""
    _, w = weights_for("same_degree", (3, 3), "thin_plate", 3)
    assert np.count_nonzero(w.weights) == 536
    assert len(w.block_powers) < 9 * len(w.block_start) // 2
    identity = batch_weights(
        surface_energy_matrices((3, 3), "thin_plate").full, None, None, (4, 4), 3
    )
    assert np.count_nonzero(identity.weights) == 9 * 136 and identity.mix_target.size == 0
