"""The certified energy-optimal parameters of a trigonometric direction across a hyperbolic
one (issue #31): optimal_parameters(net, energy, family=(trig, hyp)).

The energy lies in ℚ[π, 1/π, e, 1/e] and is never compared exactly; the result is certified
from rational enclosures of both constants. The references here are independent of the
runtime's energy polynomial and Gram matrices:
- mpmath Gauss-Legendre quadrature at 40 digits of the energy integrand at the returned
  point (test_param_surface_matrices._quadrature_energy, the families' functions written out
  in SymPy from their definition text and differentiated there);
- a dense float grid over the whole four-parameter box, each grid point's energy by a float
  Gauss-Legendre rule on the basis functions lambdified from the same SymPy text (the rule's
  sums taken one direction at a time): no grid
  value may fall below the certified lower bound, and none below the returned energy by more
  than the rounding of the rule.
"""

from __future__ import annotations

import sys
from fractions import Fraction as F
from pathlib import Path

import numpy as np
import pytest

import lambda_bezier as lb
from lambda_bezier import examples
from lambda_bezier.hazmat.constants import ConstantSum

sp = pytest.importorskip("sympy")
mpmath = pytest.importorskip("mpmath")
from test_param_surface_matrices import _functions, _quadrature_energy  # noqa: E402

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

TRIG = Path(examples.path("han_trig_cubic.toml"))
HYP = Path(__file__).parent / "data" / "families" / "hyp_cubic.toml"
NETS = {
    "exact": [[(F(i), F(j), F((3 * i * j + i) % 5, 2)) for j in range(4)] for i in range(4)],
    "float": np.random.default_rng(31).normal(size=(4, 4, 3)).round(6).tolist(),
}
ORDERS = {"membrane": ((1, 0, 1), (0, 1, 1)), "thin_plate": ((2, 0, 1), (1, 1, 2), (0, 2, 1))}
t = sp.Symbol("t")


def _lambdified(path: Path):
    """The family's basis and its first two derivatives as numpy functions of (t, lam, mu),
    its domain as floats, and its parameter box (from the definition text, by SymPy)."""
    fam = tomllib.loads(path.read_text())["family"]
    lam, mu = sp.symbols("lam mu")
    funcs = [sp.sympify(f, locals={"t": t, "lam": lam, "mu": mu}) for f in fam["functions"]]
    lo, hi = (float(sp.sympify(x)) for x in fam.get("domain", "[0, 1]").strip("[]").split(","))
    calls = [
        [sp.lambdify((t, lam, mu), sp.diff(f, t, k), "numpy") for f in funcs] for k in range(3)
    ]
    box = {k: tuple(float(x) for x in v.strip("[]").split(",")) for k, v in fam["range"].items()}
    return calls, (lo, hi), (box["lam"], box["mu"])


def _grid_energies(
    net, energy: str, side: int, paths: tuple[Path, Path] = (TRIG, HYP)
) -> tuple[np.ndarray, list[np.ndarray]]:
    """The energy at every point of a side^4 grid over the box, by a 32-node float
    Gauss-Legendre rule a direction: (values of shape (side,)*4, the grid axes)."""
    nodes, weights = np.polynomial.legendre.leggauss(32)
    pts = np.asarray(net, dtype=float)
    per_dir = []
    axes = []
    for path in paths:
        calls, (lo, hi), ((llo, lhi), (mlo, mhi)) = _lambdified(path)
        x = (hi - lo) / 2 * nodes + (hi + lo) / 2
        w = (hi - lo) / 2 * weights
        lams, mus = np.linspace(llo, lhi, side), np.linspace(mlo, mhi, side)
        axes += [lams, mus]
        L, M, X = np.meshgrid(lams, mus, x, indexing="ij")
        # vals[k][i]: derivative k of basis function i, shape (side, side, nodes)
        vals = np.array(
            [[np.broadcast_to(f(X, L, M), X.shape) for f in fk] for fk in calls], dtype=float
        )
        per_dir.append((vals, w))
    (vu, wu), (vv, wv) = per_dir
    total = np.zeros((side,) * 4)  # (lam_u, mu_u, lam_v, mu_v)
    for ku, kv, weight in ORDERS[energy]:
        # the double integral of |Σ_ij P_ij bu_i^(ku)(x) bv_j^(kv)(y)|² by the tensor rule,
        # summed over the nodes one direction at a time: Gu[a,b,i,k] = Σ_x w bu_i bu_k
        gu = np.einsum("iabx,kabx,x->abik", vu[ku], vu[ku], wu)
        gv = np.einsum("jcdy,lcdy,y->cdjl", vv[kv], vv[kv], wv)
        dots = np.einsum("ijz,klz->ijkl", pts, pts)
        total += weight * np.einsum("abik,ijkl,cdjl->abcd", gu, dots, gv, optimize=True)
    return total, axes


@pytest.mark.parametrize(("kind", "energy"), [("exact", "membrane"), ("float", "thin_plate")])
def test_trig_across_hyp_is_certified_against_quadrature_and_a_dense_grid(kind, energy):
    fam_u, fam_v = lb.load_family(TRIG), lb.load_family(HYP)
    net = NETS[kind]
    res = lb.optimal_parameters(net, energy, family=(fam_u, fam_v))
    assert res.method == "certified" and res.certified
    assert sorted(res.parameters) == ["lam_u", "lam_v", "mu_u", "mu_v"]
    if kind == "exact":
        assert isinstance(res.energy, ConstantSum) and res.energy.constants == ("pi", "exp(1)")
        lo, hi = res.energy.enclosure(200)
        assert isinstance(res.lower_bound, F)
        assert hi - res.lower_bound <= F(1, 10**12) * lo  # certified to 1e-12 (relative)
        value = float(res.energy)
    else:
        assert isinstance(res.energy, float) and isinstance(res.lower_bound, float)
        value = res.energy
        assert value - res.lower_bound <= 1e-12 * value * (1 + 1e-9)
    # the energy at the returned point, by quadrature of the integrand (40 digits)
    pu = {"lam": F(res["lam_u"]), "mu": F(res["mu_u"])}
    pv = {"lam": F(res["lam_v"]), "mu": F(res["mu_v"])}
    exact_net = [[tuple(F(x) for x in p) for p in row] for row in net]
    reference = _quadrature_energy(
        energy, exact_net, _functions(TRIG, 3, pu), _functions(HYP, 3, pv)
    )
    assert abs(value - float(reference)) <= 1e-13 * float(reference)
    # no point of a dense grid over the box beats the certified lower bound
    grid, axes = _grid_energies(net, energy, 17)
    rounding = 1e-11 * float(grid.max())  # the float rule's rounding on these sums
    assert grid.min() >= float(res.lower_bound) - rounding
    assert value <= grid.min() + rounding
    # and the returned point is in the box
    for x, axis in zip((res["lam_u"], res["mu_u"], res["lam_v"], res["mu_v"]), axes, strict=True):
        assert axis[0] <= float(x) <= axis[-1]


def test_the_grid_reference_is_the_runtime_energy_at_a_point():
    """The grid's float rule against the exact energy of a surface at one parameter point
    (so that the grid check above measures the right function)."""
    fam_u, fam_v = lb.load_family(TRIG), lb.load_family(HYP)
    net = NETS["exact"]
    grid, axes = _grid_energies(net, "thin_plate", 3)
    pu = {"lam": F(int(axes[0][1] * 2), 2), "mu": F(int(axes[1][2]))}
    pv = {"lam": F(axes[2][0]).limit_denominator(8), "mu": F(axes[3][1]).limit_denominator(8)}
    surf = fam_u.surface(net, params_u=pu, params_v=pv, family_v=fam_v)
    exact = float(lb.surface_energy(surf, "thin_plate"))
    assert grid[1, 2, 0, 1] == pytest.approx(exact, rel=1e-12)
