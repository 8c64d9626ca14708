"""Joins with the derived conditions, and the continuity report, of surfaces of
several-parameter, indexed and trigonometric/hyperbolic/mixed families (param_surface_joins,
param_surface_report): against the per-degree numeric solve of the curve joins, against the
cross derivatives evaluated on each side, and against finite differences."""

from __future__ import annotations

import math
from fractions import Fraction as F

import numpy as np
import pytest
from conftest import surface_families

import lambda_bezier as lb
from lambda_bezier import _atom_joins, examples
from lambda_bezier import param_surface_report as pr
from lambda_bezier.atom_surfaces import AtomSurface

TRIG, TWO, QB, HYP, MIXED = surface_families()

NET = [[(i, j, F((i * j) % 3, 2) - F(i, 4)) for j in range(4)] for i in range(4)]


def params(fam, sign=1):
    """(params_u, params_v, new) inside each family's box."""
    if fam is QB:
        return {"lam": [1, F(1, 2), -1]}, {"lam": [0, F(1, 3), 0]}, {"lam": [0, 0, 0]}
    if fam is MIXED:
        return {"lam": F(1, 4)}, {"lam": F(1, 5)}, {"lam": F(1, 2)}
    pu = {k: F(i + 1, 4) for i, k in enumerate(fam.parameters)}
    pv = {k: -sign * F(i + 1, 3) for i, k in enumerate(fam.parameters)}
    return pu, pv, {k: 0 for k in fam.parameters}


def rest_rows(rows, axis):
    grid = [[(5 + k, j, F(j, 3)) for j in range(4)] for k in range(rows)]
    return grid if axis == 0 else [list(r) for r in zip(*grid, strict=True)]


# ---------------------------------------------------------------------- derived joins
@pytest.mark.parametrize("fam", [TRIG, TWO, QB, HYP])
@pytest.mark.parametrize(("continuity", "rows"), [("C1", 2), ("G1", 2), ("C2", 1)])
@pytest.mark.parametrize("side", ["u", "v"])
def test_derived_join_is_the_per_degree_solve(fam, continuity, rows, side, monkeypatch):
    pu, pv, new = params(fam)
    a = fam.surface(NET, params_u=pu, params_v=pv)
    alpha = F(1, 2) if continuity == "G1" else 1
    rest = rest_rows(rows, 0 if side == "u" else 1)
    derived = lb.join_surface(
        a, side, continuity, 3, rest=rest, alpha=alpha, params=new, conditions="derived"
    )
    # the per-degree numeric solve: the curves' join with the documents' weights switched off
    monkeypatch.setattr(_atom_joins, "derived_weights", lambda *args: None)
    solved = lb.join_surface(a, side, continuity, 3, rest=rest, alpha=alpha, params=new)
    assert type(derived) is type(solved) is type(a)
    assert np.allclose(derived.net, solved.net, rtol=1e-12, atol=1e-12)
    if fam is TRIG:  # the document's weights are in ℚ, and so are the end derivatives at
        # pi/2 (sin and cos are 0 or 1 there): the per-degree solve is exact too, the same net
        assert derived.is_exact and solved.is_exact
        assert derived.control_net() == solved.control_net()
    elif not isinstance(a, AtomSurface):  # polynomial families: both exact, the same
        assert derived.is_exact and derived.control_net() == solved.control_net()
    # and the derived path reads the document: without its weights it refuses
    with pytest.raises(ValueError, match='hold no .* join .*conditions="solve"'):
        lb.join_surface(
            a, side, continuity, 3, rest=rest, alpha=alpha, params=new, conditions="derived"
        )


def test_derived_join_meets_the_cross_derivatives():
    """The derived C2 patch of a trigonometric surface, by finite differences across."""
    pu, pv, new = params(TRIG)
    a = TRIG.surface(NET, params_u=pu, params_v=pv)
    b = lb.join_surface(a, "u", "C2", 3, rest=rest_rows(1, 0), params=new, conditions="derived")
    vs = np.linspace(0, math.pi / 2, 5)
    h = 1e-4
    end = math.pi / 2
    for k, (fa, fb) in enumerate(
        (
            (a.evaluate(np.full(5, end), vs), b.evaluate(np.zeros(5), vs)),
            (
                (a.evaluate(np.full(5, end), vs) - a.evaluate(np.full(5, end - h), vs)) / h,
                (b.evaluate(np.full(5, h), vs) - b.evaluate(np.zeros(5), vs)) / h,
            ),
        )
    ):
        assert np.allclose(fa, fb, atol=1e-3 if k else 1e-13)


def test_derived_join_refusals_name_the_problem():
    pu, pv, new = params(TRIG)
    a = TRIG.surface(NET, params_u=pu, params_v=pv)
    with pytest.raises(ValueError, match="conditions"):
        lb.join_surface(a, "u", "C1", 3, rest=rest_rows(2, 0), params=new, conditions="guess")
    with pytest.raises(ValueError, match="rest must hold 2 rows"):
        lb.join_surface(a, "u", "C1", 3, rest=rest_rows(1, 0), params=new, conditions="derived")


# ---------------------------------------------------------------------- the report
@pytest.mark.parametrize("fam", [TRIG, HYP, MIXED])
def test_exact_end_weights_are_the_basis_at_the_ends(fam):
    """The exact b_i^(r) at the domain's ends (rational where the atoms' values are) against
    the float basis evaluated there."""
    pu, pv, _ = params(fam)
    a = fam.surface(NET, params_u=pu, params_v=pv)
    for axis in (0, 1):
        probe = a._probes[axis]
        for at_end in (True, False):
            got = pr._end_weights(a, axis, at_end, 3)
            t = probe.domain[1] if at_end else probe.domain[0]
            for r in range(4):
                want = probe.basis(t, r)
                assert np.allclose(np.array(got[r], dtype=float), want, atol=1e-12), (r, at_end)
    if fam is TRIG:  # [0, π/2]: every atom is rational at both ends
        assert all(isinstance(w, F) for row in pr._end_weights(a, 0, True, 3) for w in row)


@pytest.mark.parametrize("fam", [TRIG, HYP, MIXED, TWO, QB])
@pytest.mark.parametrize(("continuity", "rows"), [("C1", 2), ("G1", 2), ("C2", 1)])
def test_report_finds_the_continuity_of_a_join(fam, continuity, rows):
    pu, pv, new = params(fam)
    a = fam.surface(NET, params_u=pu, params_v=pv)
    alpha = F(1, 2) if continuity == "G1" else 1
    b = lb.join_surface(a, "u", continuity, 3, rest=rest_rows(rows, 0), alpha=alpha, params=new)
    c = lb.join_surface(a, "v", continuity, 3, rest=rest_rows(rows, 1), alpha=alpha, params=new)
    assert [r.continuity for r in lb.CompositeSurface([[a], [b]]).report()] == [continuity]
    assert [r.continuity for r in lb.CompositeSurface([[a, c]]).report()] == [continuity]


@pytest.mark.parametrize("fam", [TRIG, HYP, MIXED])
def test_report_sees_a_broken_join(fam):
    """Moving B's net along a direction that keeps the cross derivatives of orders < r and
    changes order r (a null vector of b_i^(s)(start), s < r, from the float basis) breaks the
    join at order r exactly."""
    pu, pv, new = params(fam)
    a = fam.surface(NET, params_u=pu, params_v=pv)
    b = lb.join_surface(a, "u", "C2", 3, rest=rest_rows(1, 0), params=new)
    rows = np.array(b.control_net(), dtype=float)
    start = b.domain_u[0]
    w = np.array([b._probes[0].basis(start, r) for r in range(3)])
    for r, want in enumerate(("none", "C0", "C1")):
        null = np.linalg.svd(w[:r])[2][r:] if r else np.eye(4)
        x = null[int(np.argmax(np.abs(null @ w[r])))]
        moved = rows.copy()
        moved[:, 1, 2] += 1e-6 * x / np.abs(x).max()
        other = fam.surface(moved, params_u=new, params_v=pv)
        assert lb.CompositeSurface([[a], [other]]).report()[0].continuity == want, r
    # other parameters along the boundary: the sampled comparison sees the mismatch
    other = fam.surface(rows, params_u=new, params_v=params(fam, sign=-1)[0])
    assert lb.CompositeSurface([[a], [other]]).report()[0].continuity == "none"


def test_report_is_exact_for_exact_trigonometric_patches():
    """A change of 1e-30 in B's third row: only exact end derivatives see it (b_2 of Han's
    basis starts as t², so only the second cross derivative moves)."""
    pu, pv, new = params(TRIG)
    a = TRIG.surface(NET, params_u=pu, params_v=pv)
    b = lb.join_surface(a, "u", "C2", 3, rest=rest_rows(1, 0), params=new)
    assert b.is_exact
    rows = [[list(p) for p in row] for row in b.control_net()]
    rows[2][1][2] += F(1, 10**30)
    other = TRIG.surface(rows, params_u=new, params_v=pv)
    assert lb.CompositeSurface([[a], [other]]).report()[0].continuity == "C1"
    floats = TRIG.surface(np.array(rows, dtype=float), params_u=new, params_v=pv)
    assert lb.CompositeSurface([[a], [floats]]).report()[0].continuity == "C2"


def test_report_compares_other_families_along_by_sampling():
    """A trigonometric patch next to a surface with the same values along the boundary but
    another family there: equal functions, told apart from unequal ones by sampling."""
    pu, pv, new = params(TRIG)
    a = TRIG.surface(NET, params_u=pu, params_v=pv)
    b = lb.join_surface(a, "u", "C1", 3, rest=rest_rows(2, 0), params=new)
    same = TRIG.surface(b.control_net(), params_u=new, params_v=pv)
    assert lb.CompositeSurface([[a], [same]]).report()[0].continuity == "C1"
    assert not pr._same_along(a, HYP.surface(NET, params_u=pu, params_v=pu), 0)


def test_composite_evaluates_each_patch_on_its_domain():
    pu, pv, new = params(TRIG)
    a = TRIG.surface(NET, params_u=pu, params_v=pv)
    b = lb.join_surface(a, "u", "C1", 3, rest=rest_rows(2, 0), params=new)
    comp = lb.CompositeSurface([[a], [b]])
    assert np.allclose(comp.evaluate(0.5, 0.5), a.evaluate(math.pi / 4, math.pi / 4))
    assert np.allclose(comp.evaluate(1.25, 1.0), b.evaluate(math.pi / 8, math.pi / 2))


def test_derived_join_into_another_family_names_the_missing_pair():
    """two_shape_cubic's document holds its joins with the built-in families and itself, not
    with nouri_saeidian: "derived" refuses, naming the pair; "solve" joins per degree."""
    nouri = lb.load_family(examples.path("nouri_saeidian.toml"))
    a = TWO.surface(NET, params_u={"lam": 0, "mu": 0}, params_v={"lam": 0, "mu": 0})
    new = {"sigma": F(1, 2)}
    with pytest.raises(ValueError, match="two_shape_cubic>nouri_saeidian at degrees 3 and 3"):
        lb.join_surface(
            a, "u", "C1", 3, rest=rest_rows(2, 0), family=nouri, params=new, conditions="derived"
        )
    b = lb.join_surface(a, "u", "C1", 3, rest=rest_rows(2, 0), family=nouri, params=new)
    assert b.family == ("nouri_saeidian", "two_shape_cubic")
    assert [r.continuity for r in lb.CompositeSurface([[a], [b]]).report()] == ["C1"]
