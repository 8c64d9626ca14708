"""Generated expansions against the basis definitions, and the basis properties."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import make_curve
from hypothesis import given
from hypothesis import strategies as st
from lambda_bezier._generated import bernstein_like, same_degree
from reference import FAMILIES, bernstein

T = np.linspace(0, 1, 41)


def _unit_curve(fam, n, lam):
    """Any curve of degree n gives the basis; use the unit-simplex-like points."""
    pts = np.zeros((n + 1, 2))
    pts[:, 0] = np.arange(n + 1)
    return make_curve(fam, pts, lam)


@pytest.mark.parametrize("name", list(FAMILIES))
@given(data=st.data())
def test_basis_matches_definition(name, data):
    fam = FAMILIES[name]
    n = data.draw(st.sampled_from(fam.degrees))
    lam = None if name == "bezier" else data.draw(st.floats(*fam.lam_range))
    t = np.array(data.draw(st.lists(st.floats(0, 1), min_size=1, max_size=8)))
    got = _unit_curve(fam, n, lam).basis(t)
    np.testing.assert_allclose(got, fam.basis(n, t, lam), atol=1e-9)


def test_every_degree_and_index(family):
    """Exhaustive over the supported degrees, at a few λ, including the range ends."""
    lams = [None] if family.name == "bezier" else [*family.lam_range, 0.3, -0.7]
    for n in family.degrees:
        for lam in lams:
            got = _unit_curve(family, n, lam).basis(T)
            np.testing.assert_allclose(
                got, family.basis(n, T, lam), atol=1e-9, err_msg=f"n={n} lam={lam}"
            )


def test_partition_of_unity_symmetry_nonnegativity(family):
    lams = [None] if family.name == "bezier" else np.linspace(*family.lam_range, 7)
    for n in family.degrees:
        for lam in lams:
            b = _unit_curve(family, n, lam).basis(T)
            np.testing.assert_allclose(b.sum(axis=1), 1.0, atol=1e-10)
            mirrored = _unit_curve(family, n, lam).basis(1 - T)
            np.testing.assert_allclose(mirrored, b[:, ::-1], atol=1e-10)
            assert (b >= -1e-12).all(), f"negative basis value at n={n}, lam={lam}"


@pytest.mark.parametrize("name", ["same_degree", "bernstein_like"])
def test_reduces_to_bernstein(name):
    fam = FAMILIES[name]
    for n in fam.degrees:
        b = _unit_curve(fam, n, fam.bernstein_lambda).basis(T)
        # λ at the Bernstein value: degree n basis; bernstein_like is then of degree n exactly
        want = np.stack([bernstein(n, i, T) for i in range(n + 1)], axis=-1)
        np.testing.assert_allclose(b, want, atol=1e-10)


def test_range_is_where_nonnegativity_holds():
    """Just outside each family's range some basis function goes negative, which is why
    the range is checked (check_range=False lets a researcher look anyway)."""
    import lambda_bezier as lb

    pts = [(0, 0), (1, 0), (2, 0), (3, 0)]
    below = lb.SameDegreeCurve(pts, -2.2, check_range=False).basis(T)
    assert below.min() < 0
    outside = lb.BernsteinLikeCurve(pts, 1.5, check_range=False).basis(T)
    assert outside.min() < 0


@pytest.mark.parametrize(
    "module", [same_degree, bernstein_like], ids=["same_degree", "bernstein_like"]
)
def test_bernstein_and_power_tables_agree(module):
    """BERNSTEIN and POWER describe the same polynomials (exact, Fractions)."""
    from lambda_bezier._generated import bernstein as bz

    for n in module.DEGREES:
        big = n + module.DEGREE_OFFSET
        for p, (pm, bm) in enumerate(zip(module.POWER[n], module.BERNSTEIN[n], strict=True)):
            for i in range(n + 1):
                via_bernstein = [
                    sum(bm[i][j] * bz.POWER[big][j][e] for j in range(big + 1))
                    for e in range(big + 1)
                ]
                assert via_bernstein == list(pm[i]), (n, p, i)


def test_general_forms_match_per_degree_tables():
    """The general-n closed forms emitted by derive against the per-degree tables."""
    for n in same_degree.DEGREES:
        for lam in (0, 1, -1):
            for i in range(n + 1):
                alpha, beta, gamma = same_degree.three_term_bernstein(n, i, lam)
                row = [
                    same_degree.BERNSTEIN[n][0][i][j] + lam * same_degree.BERNSTEIN[n][1][i][j]
                    for j in range(n + 1)
                ]
                want = [0] * (n + 1)
                want[i] = beta
                if i > 0:
                    want[i - 1] = alpha
                if i < n:
                    want[i + 1] = gamma
                assert row == want, (n, i, lam)
    for n in bernstein_like.DEGREES:
        for lam in (0, 1, -1):
            for i in range(n + 1):
                c = bernstein_like.explicit_factor(n, i, lam)
                # (c0 + c1 t + c2 t^2) C(n,i) t^i (1-t)^(n-i) at a few rational t, exactly
                for tt in (0.25, 0.5, 0.75):
                    want = (c[0] + c[1] * tt + c[2] * tt**2) * bernstein(n, i, tt)
                    got = FAMILIES["bernstein_like"].basis(n, tt, lam)[0, i]
                    assert abs(float(want) - got) < 1e-12
