"""Second acceptance pass of issue #31 (surfaces), as a new user meets it, on every kind of
family: the failures found, each against a reference that does not use the surface code (the
families' curves, one per row of the net, then one across them; exact Bézier sums; the
derivation's own records check).

Found and fixed here: evaluation on a meshgrid (2-D parameter arrays) was refused; bad input
to closest_point, CompositeSurface, join_surface (indexed families), surface_from_json,
Family.surface(family_v=...) and optimal_parameters did not name the argument (or raised
Python's own TypeError)."""

from __future__ import annotations

from fractions import Fraction as F
from math import comb
from pathlib import Path

import numpy as np
import pytest
from conftest import ROOT

import lambda_bezier as lb
from lambda_bezier import examples
from lambda_bezier.surface_export import surface_from_json

FAMILIES = ROOT / "tests" / "data" / "families"


def _fam(name: str):
    return lb.load_family(FAMILIES / f"{name}.toml")


def _net(m: int, n: int, d: int, seed: int = 0) -> list[list[tuple[F, ...]]]:
    rng = np.random.default_rng(seed + 10 * m + n)
    a = rng.integers(-5, 6, size=(m + 1, n + 1, d))
    return [[tuple(F(int(x), 3) for x in a[i, j]) for j in range(n + 1)] for i in range(m + 1)]


def _cases():
    """(surface, curve of the u direction from points, curve of the v direction, domains):
    a built-in family object, each built-in class, a mixed pair, user families with one,
    two, per-leg and indexed parameters, trigonometric, hyperbolic, trigonometric across a
    polynomial family; degree 1 in one direction, m != n, d = 1..4."""
    sd = lb.builtin_family("same_degree")
    ns = lb.load_family(examples.path("nouri_saeidian.toml"))
    two = lb.load_family(examples.path("two_shape_cubic.toml"))
    q, trig, hyp = _fam("q_bezier"), _fam("han_trig_cubic"), _fam("hyp_cubic")
    half_pi = (0.0, np.pi / 2)
    unit = (0.0, 1.0)
    pu, pv = {"lam": F(1, 2), "mu": -1}, {"lam": 0, "mu": F(1, 3)}
    return {
        "same_degree object": (
            sd.surface(_net(3, 3, 3), F(1, 2), F(-1, 3)),
            lambda p: lb.SameDegreeCurve(p, F(1, 2)),
            lambda p: lb.SameDegreeCurve(p, F(-1, 3)),
            (unit, unit),
        ),
        "bernstein_like 3x2, d=2": (
            lb.BernsteinLikeSurface(_net(3, 2, 2), F(1, 3), F(1, 5)),
            lambda p: lb.BernsteinLikeCurve(p, F(1, 3)),
            lambda p: lb.BernsteinLikeCurve(p, F(1, 5)),
            (unit, unit),
        ),
        "bezier 1x3, d=1": (
            lb.BezierSurface(_net(1, 3, 1)),
            lb.BezierCurve,
            lb.BezierCurve,
            (unit, unit),
        ),
        "same_degree x bernstein_like 3x4, d=4": (
            lb.Surface(_net(3, 4, 4), F(1, 4), F(1, 3), family=("same_degree", "bernstein_like")),
            lambda p: lb.SameDegreeCurve(p, F(1, 4)),
            lambda p: lb.BernsteinLikeCurve(p, F(1, 3)),
            (unit, unit),
        ),
        "user one-parameter (nouri_saeidian)": (
            ns.surface(_net(3, 4, 3), F(1, 2), F(1, 3)),
            lambda p: ns.curve(p, F(1, 2)),
            lambda p: ns.curve(p, F(1, 3)),
            (unit, unit),
        ),
        "user two-parameter": (
            two.surface(_net(3, 3, 3), params_u=pu, params_v=pv),
            lambda p: two.curve(p, **pu),
            lambda p: two.curve(p, **pv),
            (unit, unit),
        ),
        "indexed (q_bezier) 2x3": (
            q.surface(_net(2, 3, 3), [F(1, 2), 0], [0, F(1, 3), -1]),
            lambda p: q.curve(p, lam=[F(1, 2), 0]),
            lambda p: q.curve(p, lam=[0, F(1, 3), -1]),
            (unit, unit),
        ),
        "trigonometric": (
            trig.surface(_net(3, 3, 3), params_u=pu, params_v=pv),
            lambda p: trig.curve(p, **pu),
            lambda p: trig.curve(p, **pv),
            (half_pi, half_pi),
        ),
        "hyperbolic": (
            hyp.surface(_net(3, 3, 3), params_u={"lam": F(1, 2), "mu": 0}, params_v=pv),
            lambda p: hyp.curve(p, lam=F(1, 2), mu=0),
            lambda p: hyp.curve(p, **pv),
            (unit, unit),
        ),
        "trigonometric x same_degree": (
            trig.surface(_net(3, 3, 3), params_u=pu, lam_v=F(1, 3), family_v="same_degree"),
            lambda p: trig.curve(p, **pu),
            lambda p: lb.SameDegreeCurve(p, F(1, 3)),
            (half_pi, unit),
        ),
    }


CASES = _cases()


def _reference(case, u: float, v: float, du: int = 0, dv: int = 0) -> np.ndarray:
    """∂^du_u ∂^dv_v S(u, v) from the families' curves alone: each row's curve (or its
    derivative) at v gives the control points of a curve across the rows."""
    surf, curve_u, curve_v, _ = case
    net = np.array(surf.control_net(), dtype=float)
    rows = []
    for row in net:
        c = curve_v(row.tolist())
        rows.append(c.derivative(v, dv) if dv else c.evaluate(v))
    across = curve_u(np.array(rows).tolist())
    return np.asarray(across.derivative(u, du) if du else across.evaluate(u), dtype=float)


def _grid(case, nu: int = 4, nv: int = 3) -> tuple[np.ndarray, np.ndarray]:
    (ua, ub), (va, vb) = case[3]
    return np.meshgrid(np.linspace(ua, ub, nu), np.linspace(va, vb, nv), indexing="ij")


# ---------------------------------------------------------------------- meshgrids
@pytest.mark.parametrize("name", list(CASES))
def test_evaluate_on_a_meshgrid(name):
    """Before: evaluate(U, V) with U, V from np.meshgrid raised "u must be a number or a 1-D
    array". Now the result has U's shape + (d,), each point the curves' reference."""
    case = CASES[name]
    surf = case[0]
    uu, vv = _grid(case)
    got = surf.evaluate(uu, vv)
    assert got.shape == (*uu.shape, surf.dimension)
    for i, j in np.ndindex(uu.shape):
        want = _reference(case, uu[i, j], vv[i, j])
        np.testing.assert_allclose(got[i, j], want, atol=1e-12 * (1 + np.abs(want).max()))
    # a column against a row broadcasts to the same grid
    np.testing.assert_array_equal(surf.evaluate(uu[:, :1], vv[:1, :]), got)
    # and evaluate_grid agrees with it
    np.testing.assert_allclose(surf.evaluate_grid(uu[:, 0], vv[0]), got, atol=1e-13)


@pytest.mark.parametrize("name", list(CASES))
@pytest.mark.parametrize("du, dv", [(1, 0), (0, 2), (2, 1), (1, 3), (4, 0)])
def test_derivatives_on_a_meshgrid(name, du, dv):
    case = CASES[name]
    surf = case[0]
    uu, vv = _grid(case, 3, 2)
    got = surf.derivative(uu, vv, du, dv)
    assert got.shape == (*uu.shape, surf.dimension)
    for i, j in np.ndindex(uu.shape):
        want = _reference(case, uu[i, j], vv[i, j], du, dv)
        np.testing.assert_allclose(got[i, j], want, rtol=1e-9, atol=1e-9 * (1 + np.abs(want).max()))


@pytest.mark.parametrize("name", [k for k, c in CASES.items() if c[0].dimension == 3])
def test_normals_and_curvatures_on_a_meshgrid(name):
    """The unit normal and K, H on a meshgrid, against the textbook formulas on the curves'
    reference derivatives (first and second fundamental forms)."""
    case = CASES[name]
    surf = case[0]
    (ua, ub), (va, vb) = case[3]
    uu, vv = np.meshgrid(np.linspace(ua, ub, 5)[1:-1], np.linspace(va, vb, 4)[1:-1], indexing="ij")
    normals = surf.normal(uu, vv)
    gauss, mean = surf.curvatures(uu, vv)
    assert normals.shape == (*uu.shape, 3) and gauss.shape == mean.shape == uu.shape
    for i, j in np.ndindex(uu.shape):
        su, sv, suu, suv, svv = (
            _reference(case, uu[i, j], vv[i, j], a, b)
            for a, b in ((1, 0), (0, 1), (2, 0), (1, 1), (0, 2))
        )
        n = np.cross(su, sv)
        n /= np.linalg.norm(n)
        e, f, g = su @ su, su @ sv, sv @ sv
        l_, m_, n_ = suu @ n, suv @ n, svv @ n
        det = e * g - f * f
        np.testing.assert_allclose(normals[i, j], n, atol=1e-10)
        assert gauss[i, j] == pytest.approx((l_ * n_ - m_ * m_) / det, rel=1e-8, abs=1e-10)
        assert mean[i, j] == pytest.approx((e * n_ - 2 * f * m_ + g * l_) / (2 * det), rel=1e-8)


def test_exact_parameters_on_a_meshgrid():
    """Fractions in nested lists (an object meshgrid) are parameters too."""
    surf = CASES["same_degree object"][0]
    us = [[F(0), F(1, 3)], [F(1, 2), F(1)]]
    vs = [[F(1, 4), F(1, 4)], [F(1), F(0)]]
    got = surf.evaluate(us, vs)
    assert got.shape == (2, 2, 3)
    bez = surf.to_bezier().control_net()
    for i, j in np.ndindex(2, 2):
        u, v = us[i][j], vs[i][j]
        want = [
            sum(
                bez[a][b][c] * comb(3, a) * u**a * (1 - u) ** (3 - a)
                * comb(3, b) * v**b * (1 - v) ** (3 - b)
                for a in range(4)
                for b in range(4)
            )
            for c in range(3)
        ]  # fmt: skip
        np.testing.assert_allclose(got[i, j], [float(w) for w in want], atol=1e-14)


@pytest.mark.parametrize("name", ["same_degree object", "trigonometric"])
def test_meshgrids_that_do_not_broadcast_name_u_and_v(name):
    surf = CASES[name][0]
    with pytest.raises(ValueError, match="u and v must broadcast"):
        surf.evaluate(np.full((2, 3), 0.5), np.full((3, 2), 0.5))
    with pytest.raises(ValueError, match="u and v must broadcast"):
        surf.normal(np.full((2, 3), 0.5), np.full((4,), 0.5))
    with pytest.raises(ValueError, match="v"):  # still checked: outside the domain
        surf.evaluate(np.full((2, 2), 0.5), np.full((2, 2), 7.0))


# ---------------------------------------------------------------------- bad input
@pytest.mark.parametrize(
    "name", ["same_degree object", "indexed (q_bezier) 2x3", "trigonometric", "hyperbolic"]
)
def test_closest_point_names_q(name):
    """Before: "point must have shape (3,)", but the argument is q."""
    surf = CASES[name][0]
    with pytest.raises(ValueError, match=r"^q must have shape \(3,\)"):
        surf.closest_point([1.0, 2.0])
    with pytest.raises(ValueError, match="^q has a non-finite"):
        surf.closest_point([1.0, 2.0, float("nan")])
    with pytest.raises(ValueError, match=r"^q must have shape \(3,\)"):
        surf.closest_point([[1.0, 2.0], [0.0, 0.0]])


def test_composite_surface_names_patches():
    """Before: CompositeSurface(patch) and CompositeSurface([a, b]) raised Python's
    "'SameDegreeSurface' object is not iterable"."""
    a = CASES["same_degree object"][0]
    for bad in (a, [a, a], 3, [3]):
        with pytest.raises(TypeError, match="patches must be a grid of surfaces"):
            lb.CompositeSurface(bad)
    with pytest.raises(TypeError, match="patches: every patch must be a lambda_bezier surface"):
        lb.CompositeSurface([[a, "x"]])
    assert [r.continuity for r in lb.CompositeSurface([[a]]).report()] == []


def test_join_surface_of_an_indexed_family_names_the_degree():
    """Before: join_surface(<q_bezier patch>, "u", "C1", "x") raised Python's "can only
    concatenate str (not "int") to str"."""
    q = CASES["indexed (q_bezier) 2x3"][0]
    rest = [[(9, j, 0) for j in range(4)]]
    with pytest.raises(ValueError, match="degree must be an integer"):
        lb.join_surface(q, "u", "C1", "x", rest=rest)
    with pytest.raises(ValueError, match="degree must be an integer"):
        lb.join_surface(q, "u", "C1", 2.0, rest=rest)
    b = lb.join_surface(q, "u", "C1", 2, rest=rest)  # the good call still works
    assert [r.continuity for r in lb.CompositeSurface([[q], [b]]).report()] == ["C1"]


def test_surface_from_json_names_text():
    with pytest.raises(TypeError, match="text must be a JSON string, got int"):
        surface_from_json(3)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="not valid JSON"):
        surface_from_json("{")


def test_family_v_is_named():
    trig = _fam("han_trig_cubic")
    net = _net(3, 3, 3)
    with pytest.raises(ValueError, match="^family_v: unknown family 'nope'"):
        trig.surface(net, params_u={"lam": 0, "mu": 0}, family_v="nope")


def test_optimal_parameters_of_a_bezier_surface_names_family():
    with pytest.raises(ValueError, match="^family: neither direction"):
        lb.optimal_parameters(_net(3, 3, 3), "membrane", family="bezier")


# ------------------------------------------------------- closest point on the surface
@pytest.mark.parametrize("name", ["trigonometric", "hyperbolic", "trigonometric x same_degree"])
@pytest.mark.parametrize("at", [(0.7, 0.4), (0.05, 0.93), (0.5, 0.0)])
def test_a_point_on_an_atom_surface_is_its_own_closest_point(name, at):
    """Before: the rational form's branch and bound had no Newton polish, so its rounding
    floor on the squared distance (about 1e-13 of the size squared) left a query on the
    surface 2e-7..4e-7 away from itself."""
    surf, *_, domains = CASES[name]
    u, v = (lo + f * (hi - lo) for f, (lo, hi) in zip(at, domains, strict=True))
    q = surf.evaluate(u, v)
    cp = surf.closest_point(q)
    assert cp.distance < 1e-12 * (1 + np.abs(q).max())
    assert cp.lower_bound <= cp.distance


@pytest.mark.parametrize("name", ["trigonometric", "hyperbolic", "trigonometric x same_degree"])
def test_no_parameters_give_empty_results_on_an_atom_surface(name):
    """Before: evaluate([], []) raised numpy's "cannot reshape array of size 0"."""
    surf = CASES[name][0]
    assert surf.evaluate([], []).shape == (0, 3)
    assert surf.derivative([], [], 1, 1).shape == (0, 3)
    assert surf.evaluate(np.zeros((0, 2)), np.zeros((0, 2))).shape == (0, 2, 3)


def test_a_mixed_family_surface_names_q():
    """Before: the two-atom (no rational form) path said "point" for the argument q."""
    at = _fam("at_cubic")
    surf = at.surface(_net(3, 3, 3), F(1, 2), F(-1, 3))
    for bad in ([1.0, 2.0], [[1.0, 2.0]]):
        with pytest.raises(ValueError, match="^q"):
            surf.closest_point(bad)


# ---------------------------------------------------------------------- verify
def _basis_values(lam_u: F, lam_v: F, u: F, v: F) -> list[list[F]]:
    """b_i(u) b_j(v) of bernstein_like degrees (3, 2), from each delta net's exact Bézier form
    summed in Fractions (no derivation code)."""
    out = []
    for i in range(4):
        row = []
        for j in range(3):
            net = [[(F(int((a, b) == (i, j))),) for b in range(3)] for a in range(4)]
            bz = lb.BernsteinLikeSurface(net, lam_u, lam_v).to_bezier().control_net()
            big_m, big_n = len(bz) - 1, len(bz[0]) - 1
            row.append(
                sum(
                    bz[a][b][0]
                    * comb(big_m, a)
                    * u**a
                    * (1 - u) ** (big_m - a)
                    * comb(big_n, b)
                    * v**b
                    * (1 - v) ** (big_n - b)
                    for a in range(big_m + 1)
                    for b in range(big_n + 1)
                )  # fmt: skip
            )
        out.append(row)
    return out


def test_verify_finds_a_misprinted_surface_claim(tmp_path: Path):
    """A records file of our own: the tensor-product basis values (computed here from the
    runtime's exact Bézier form) match; the same with one value misprinted, and a misprinted
    corner, are mismatches naming the entry."""
    import subprocess
    import sys

    vals = _basis_values(F(1, 2), F(-1, 2), F(1, 3), F(1, 4))
    bad = [list(r) for r in vals]
    bad[2][1] += F(1, 100)

    def rows(table: list[list[F]]) -> str:
        return ", ".join("[" + ", ".join(f'"{x}"' for x in r) + "]" for r in table)

    common = 'claim = "surface_basis"\ndegrees = [3, 2]\nlam_u = "1/2"\nlam_v = "-1/2"\n'
    common += 'uv = ["1/3", "1/4"]\n'
    path = tmp_path / "surface_claims.toml"
    path.write_text(
        'schema_version = 2\nsource = "acceptance 31b"\nfamily = "bernstein_like"\n\n'
        f'[[record]]\nid = "b.ok"\n{common}values = [{rows(vals)}]\n\n'
        f'[[record]]\nid = "b.misprint"\n{common}values = [{rows(bad)}]\n\n'
        '[[record]]\nid = "c.misprint"\nclaim = "surface_corners"\ndegrees = [3, 2]\n'
        "corners = [[0, 0, 0, 0], [0, 1, 0, 1]]\n"
    )
    run = subprocess.run(
        [sys.executable, "-m", "lambda_bezier", "verify", "--format", "text", str(path)],
        capture_output=True,
        text=True,
        cwd=ROOT,
        check=False,
    )
    # exit 1: the two misprints are new discrepancies (the records expect a match)
    assert run.returncode == 1, run.stdout + run.stderr
    lines = run.stdout.splitlines()
    failed = sorted(ln.split()[1].rstrip(":") for ln in lines if ln.startswith("FAIL "))
    assert failed == ["b.misprint", "c.misprint"]
    verdict = {ln.split()[0]: ln.split()[-1] for ln in lines if ln.startswith(("b.", "c."))}
    assert verdict == {"b.ok": "match", "b.misprint": "mismatch", "c.misprint": "mismatch"}
    assert f"B_21(1/3, 1/4): printed {bad[2][1]}, derived {vals[2][1]}" in run.stdout
    assert "S(0, 1): printed P_01, derived weights at [(0, 2)]" in run.stdout


# ---------------------------------------------------------------------- plots
# row 0 of the net is one point: the edge u = 0 collapses (the normal is undefined on it)
COLLAPSED = [[(0, 0, 0)] * 4] + [[(i, j, (i * j) % 3) for j in range(4)] for i in range(1, 4)]


@pytest.mark.parametrize(
    "surf",
    [
        lb.SameDegreeSurface(COLLAPSED, F(1, 2), F(-1, 3)),
        lb.BezierSurface(COLLAPSED),
        lb.load_family(examples.path("nouri_saeidian.toml")).surface(COLLAPSED, F(1, 2), 1),
        _fam("han_trig_cubic").surface(
            COLLAPSED, params_u={"lam": F(1, 2), "mu": -1}, params_v={"lam": 0, "mu": 0}
        ),
    ],
    ids=["same_degree", "bezier", "nouri_saeidian", "han_trig_cubic"],
)
@pytest.mark.parametrize("curvature", ["gaussian", "mean"])
def test_curvature_colouring_of_a_surface_with_a_collapsed_edge(surf, curvature):
    """Before: plot_surface(surf) raised "the normal is undefined at (u, v) = (0.0, 0.0)" for
    any surface with one degenerate sample point. Now those points are left uncoloured (NaN,
    drawn grey) and every other point has the surface's own curvature there."""
    matplotlib = pytest.importorskip("matplotlib")
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from lambda_bezier.surface_plot import _curvature_values, plot_surface

    ax = plot_surface(surf, curvature=curvature, samples=12)
    assert ax.collections  # the surface was drawn
    plt.close("all")
    (u0, u1), (v0, v1) = getattr(surf, "domain_u", (0, 1)), getattr(surf, "domain_v", (0, 1))
    uu, vv = np.meshgrid(np.linspace(u0, u1, 12), np.linspace(v0, v1, 12), indexing="ij")
    values = _curvature_values(surf, uu, vv, curvature == "gaussian")
    assert np.isnan(values[0]).all()  # the collapsed edge u = u0
    assert np.isfinite(values[1:]).all()
    pick = 0 if curvature == "gaussian" else 1
    for idx in [(1, 0), (5, 7), (11, 11)]:
        assert values[idx] == surf.curvatures(uu[idx], vv[idx])[pick]


# ------------------------------------------------------- a level curve of a scalar field
@pytest.mark.parametrize("name", ["bezier 1x3, d=1", "trigonometric d=1"])
def test_closest_point_on_a_level_curve_of_a_scalar_field(name):
    """d = 1: a value inside the surface's range is at distance 0 along a whole level curve,
    where no patch of the search ever narrows below the squared distance's rounding floor.
    Before, each such query ran to the patch budget (about 2.5 s); the search now stops once
    the best distance found is within the tolerance (a distance is >= 0). Checked against
    the range from a dense grid: inside it the distance is 0 within tol·size, outside it the
    distance to the nearer end."""
    if name == "trigonometric d=1":
        trig = _fam("han_trig_cubic")
        pv = {"lam": 0, "mu": F(1, 3)}
        surf = trig.surface(_net(3, 3, 1), params_u={"lam": F(1, 2), "mu": -1}, params_v=pv)
        domains = ((0.0, np.pi / 2), (0.0, np.pi / 2))
    else:
        surf, *_, domains = CASES[name]
    (ua, ub), (va, vb) = domains
    grid = surf.evaluate(*np.meshgrid(np.linspace(ua, ub, 401), np.linspace(va, vb, 401)))
    lo, hi = float(grid.min()), float(grid.max())
    size = float(np.abs(surf.net).max())
    for value in np.linspace(lo, hi, 7)[1:-1]:
        cp = surf.closest_point([value])
        assert cp.distance <= 1e-12 * (size + abs(value)) + 1e-15
        assert 0.0 <= cp.lower_bound <= cp.distance
        assert abs(surf.evaluate(cp.u, cp.v)[0] - value) <= 1e-12 * (size + abs(value)) + 1e-15
    far = surf.closest_point([hi + 1.0])
    assert far.distance == pytest.approx(1.0, abs=1e-3)  # the grid's max is within 1e-3
    assert far.lower_bound <= far.distance
