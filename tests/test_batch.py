"""evaluate_many against single-curve evaluation."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import make_curve
from reference import FAMILIES

import lambda_bezier as lb


@pytest.mark.parametrize("name", list(FAMILIES))
@pytest.mark.parametrize("k", [0, 1, 2, 9])
def test_batch_matches_single(name, k):
    fam = FAMILIES[name]
    rng = np.random.default_rng(k)
    n, m = fam.degrees[0] + 2, 7
    pts = rng.normal(size=(m, n + 1, 3))
    t = np.linspace(0, 1, 13)
    lams = None if name == "bezier" else rng.uniform(*fam.lam_range, size=m)
    got = lb.evaluate_many(pts, t, name, lams, k=k)
    assert got.shape == (m, t.size, 3)
    for idx in range(m):
        curve = make_curve(fam, pts[idx], None if lams is None else lams[idx])
        np.testing.assert_allclose(got[idx], curve.derivative(t, k), atol=1e-10 * (1 + k) ** 6)
    if name != "bezier":
        same = lb.evaluate_many(pts, 0.25, name, 0.5)
        assert same.shape == (m, 3)
        np.testing.assert_allclose(same[2], make_curve(fam, pts[2], 0.5).evaluate(0.25))


@pytest.mark.parametrize(
    ("args", "kwargs", "message"),
    [
        ((np.zeros((2, 4, 2)), [0.5], "same_degree"), {}, "needs a shape parameter"),
        ((np.zeros((2, 4, 2)), [0.5], "bezier", 0.5), {}, "no shape parameter"),
        ((np.zeros((2, 4, 2)), [0.5], "same_degree", [0.5, -3.0]), {}, r"curve 1.*\(-2, 1\]"),
        ((np.zeros((2, 4, 2)), [0.5], "same_degree", [0.5, 0.5, 0.5]), {}, "array of 2"),
        ((np.zeros((4, 2)), [0.5], "bezier"), {}, r"\(m, n\+1, d\)"),
        ((np.full((2, 4, 2), np.nan), [0.5], "bezier"), {}, "non-finite"),
        ((np.zeros((2, 4, 2)), [1.5], "bezier"), {}, "outside"),
        ((np.zeros((2, 4, 2)), [0.5], "spline"), {}, "unknown family"),
        ((np.zeros((2, 2, 2)), [0.5], "same_degree", 0.5), {}, "at least 4"),
    ],
)
def test_batch_bad_input(args, kwargs, message):
    with pytest.raises(ValueError, match=message):
        lb.evaluate_many(*args, **kwargs)
