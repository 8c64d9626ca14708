"""The sides u = 0 and v = 0 of join_surface with a G1 factor varying along the boundary
(mu) and with the conditions read from derived documents (conditions="derived"), issue #31.

References: the cross derivatives of both patches at the boundary by the surfaces' own
derivative and by central finite differences of evaluate (mu); the per-degree solve on the
same side (derived: the curves' join, the documents' weights switched off for atom and
several-parameter families) and CompositeSurface.report.
"""

from __future__ import annotations

from fractions import Fraction as F

import numpy as np
import pytest
from conftest import surface_families
from test_param_surface_composites import NET as PNET
from test_param_surface_composites import params, rest_rows
from test_surfaces_more import own_family

import lambda_bezier as lb
from lambda_bezier import _atom_joins

TRIG, TWO, QB, HYP, _ = surface_families()
NET = [[(i, j, (i * j) % 2) for j in range(4)] for i in range(4)]
VS = np.linspace(0, 1, 9)


def _cross(s, axis: int, at: float, w: float, h: float = 1e-6) -> np.ndarray:
    """∂S/∂(across) at the boundary by a one-sided second-order difference (inside the
    square: a patch is defined on [0, 1]² only)."""
    sign = -1 if at == 1.0 else 1

    def point(t):
        return s.evaluate(t, w) if axis == 0 else s.evaluate(w, t)

    f0, f1, f2 = point(at), point(at + sign * h), point(at + 2 * sign * h)
    return sign * (-3 * f0 + 4 * f1 - f2) / (2 * h)


@pytest.mark.parametrize("side", ["u0", "v0"])
@pytest.mark.parametrize("mu", [(F(1, 2), 1), (2, F(-3, 2))])
def test_mu_on_the_start_sides_meets_the_varying_factor(side, mu):
    a = lb.SameDegreeSurface(NET, F(1, 2), F(-1, 2))
    axis = 0 if side == "u0" else 1
    rows = [[(-4 - k, j, j % 2) for j in range(5)] for k in range(2)]
    rest = rows if axis == 0 else [list(r) for r in zip(*rows, strict=True)]
    b = lb.join_surface(a, side, "G1", 3, F(1, 3), rest=rest, mu=mu)
    assert b.is_exact
    assert b.degrees == ((3, 4) if axis == 0 else (4, 3))  # Bézier of degree N + 1 along
    factor = [float(mu[0]) + float(mu[1]) * v for v in VS]
    for v, f in zip(VS, factor, strict=True):
        du = (1, 0) if axis == 0 else (0, 1)
        at_b = (1.0, v) if axis == 0 else (v, 1.0)
        at_a = (0.0, v) if axis == 0 else (v, 0.0)
        assert np.allclose(b.evaluate(*at_b), a.evaluate(*at_a), atol=1e-13)
        got, want = b.derivative(*at_b, *du), f * a.derivative(*at_a, *du)
        assert np.allclose(got, want, atol=1e-12)
        # the same by finite differences of the two surfaces' values
        fd_b, fd_a = _cross(b, axis, 1.0, v), _cross(a, axis, 0.0, v)
        assert np.allclose(fd_b, f * fd_a, atol=1e-6)
    grid = [[b], [a]] if axis == 0 else [[b, a]]
    assert [r.continuity for r in lb.CompositeSurface(grid).report()] == ["G1"]


def test_mu_on_the_start_side_names_the_rest_it_needs():
    a = lb.SameDegreeSurface(NET, F(1, 2), F(-1, 2))
    with pytest.raises(ValueError, match=r"5 points along the boundary .*plus one for mu"):
        lb.join_surface(a, "u0", "G1", 3, rest=[[(0, j, 0) for j in range(4)]] * 2, mu=(1, 1))
    p = TRIG.surface(PNET, params_u={"lam": 0, "mu": 0}, params_v={"lam": 0, "mu": 0})
    with pytest.raises(ValueError, match="constant alpha"):
        lb.join_surface(p, "v0", "G1", 3, mu=(1, 1))


@pytest.mark.parametrize("continuity", ["C1", "G1"])  # the document has no closed-form C2
@pytest.mark.parametrize("side", ["u0", "v0"])
@pytest.mark.parametrize("pair", ["own>own", "own>same_degree", "bernstein_like>own"])
def test_derived_on_the_start_sides_is_the_solved_join(continuity, side, pair):
    """B before A: the document of B's family (or A's) holds B>A; the weights, read once,
    give A's first rows from B's last, and B's are solved from them."""
    fam = own_family()
    new, given = (fam if x == "own" else x for x in pair.split(">"))
    lams = {"same_degree": F(1, 3), "bernstein_like": F(-1, 2)}
    lam_new = F(3, 4) if new is fam else lams[new]
    lam_given = F(1, 3) if given is fam else lams[given]
    axis = 0 if side == "u0" else 1
    net = [[(i, j, (i * j + j * j) % 5 - F(i, 3)) for j in range(4)] for i in range(5)]
    if axis == 1:
        net = [list(r) for r in zip(*net, strict=True)]
    family = (given, "same_degree") if axis == 0 else ("same_degree", given)
    lam_u, lam_v = (lam_given, F(-1, 2)) if axis == 0 else (F(-1, 2), lam_given)
    a = lb.Surface(net, lam_u, lam_v, family=family)
    order = 2 if continuity == "C2" else 1
    rows = [[(-6 - k, j, k) for j in range(4)] for k in range(4 - order)]
    rest = rows if axis == 0 else [list(r) for r in zip(*rows, strict=True)]
    kw = dict(rest=rest, family=new, alpha=F(3, 2) if continuity == "G1" else 1)
    solved = lb.join_surface(a, side, continuity, 4, lam_new, **kw)
    derived = lb.join_surface(a, side, continuity, 4, lam_new, conditions="derived", **kw)
    assert derived.is_exact and derived.control_net() == solved.control_net()
    grid = [[derived], [a]] if axis == 0 else [[derived, a]]
    assert lb.CompositeSurface(grid).report()[0].continuity in (continuity, "C1", "C2")


@pytest.mark.parametrize("fam", [TRIG, TWO, QB, HYP])
@pytest.mark.parametrize(("continuity", "rows"), [("C1", 2), ("G1", 2), ("C2", 1)])
@pytest.mark.parametrize("side", ["u0", "v0"])
def test_derived_by_name_on_the_start_sides_is_the_per_degree_solve(
    fam, continuity, rows, side, monkeypatch
):
    pu, pv, new = params(fam)
    a = fam.surface(PNET, params_u=pu, params_v=pv)
    alpha = F(1, 2) if continuity == "G1" else 1
    rest = rest_rows(rows, 0 if side == "u0" else 1)
    derived = lb.join_surface(
        a, side, continuity, 3, rest=rest, alpha=alpha, params=new, conditions="derived"
    )
    grid = [[derived], [a]] if side == "u0" else [[derived, a]]
    assert lb.CompositeSurface(grid).report()[0].continuity in (continuity, "C1", "C2")
    monkeypatch.setattr(_atom_joins, "derived_weights", lambda *args: None)
    solved = lb.join_surface(a, side, continuity, 3, rest=rest, alpha=alpha, params=new)
    assert type(derived) is type(solved) is type(a)
    assert np.allclose(derived.net, solved.net, rtol=1e-11, atol=1e-11)
    with pytest.raises(ValueError, match='hold no .* join .*conditions="solve"'):
        lb.join_surface(
            a, side, continuity, 3, rest=rest, alpha=alpha, params=new, conditions="derived"
        )
