"""The half-angle evaluation of trigonometric curves without numba on threads (issue #29,
hazmat/atoms.evaluate_half_angle): whole blocks per thread, so bit for bit the one-thread
answer at any number of threads, and within a few ulps of the recurrences."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import lambda_bezier as lb
from lambda_bezier.hazmat import atoms as ak
from lambda_bezier.hazmat import kernels

FAMILIES = Path(__file__).parent / "data" / "families"


@pytest.mark.parametrize("threads", [2, 3, 5])
@pytest.mark.parametrize("size", [8192 * 5 + 17, 8192 * 9])
def test_threads_give_the_one_thread_answer(threads, size, monkeypatch):
    monkeypatch.setattr(kernels, "USE_COMPILED", False)
    monkeypatch.setattr(ak, "_HALF_ANGLE_PER_THREAD", 1)
    curve = lb.load_family(FAMILIES / "han_trig_cubic.toml").curve(
        np.random.default_rng(5).normal(size=(4, 2)), lam=0.5, mu=-1
    )
    t = np.random.default_rng(6).random(size) * math.pi / 2
    t[:2] = [0.0, math.pi / 2]
    sh = curve.shape
    values = []
    for k in range(2):
        coeffs = curve._coefficients(k)
        table = ak.half_angle_coefficients(coeffs, sh.harmonics)
        monkeypatch.setattr(ak, "HALF_ANGLE_THREADS", 1)
        one = ak.evaluate_half_angle(table, t, sh.omega0, sh.harmonics, curve._mid)
        monkeypatch.setattr(ak, "HALF_ANGLE_THREADS", threads)
        many = ak.evaluate_half_angle(table, t, sh.omega0, sh.harmonics, curve._mid)
        np.testing.assert_array_equal(many, one)
        slow = ak.evaluate(coeffs, t - curve._mid, sh.omega0, sh.powers, sh.harmonics, False)
        assert np.abs(many - slow).max() < 8 * 2.0**-52 * (1 + np.abs(slow).max())
        values.append(many)
    # and through the curve: the public evaluate takes this path without numba
    np.testing.assert_array_equal(curve.evaluate(t), values[0].T)
