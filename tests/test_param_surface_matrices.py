"""Surface energy matrices of several-parameter and trigonometric/hyperbolic/mixed families, and
the exact energy of a trigonometric x hyperbolic surface (issue #31).

lb.surface_energy_matrices builds them by the Kronecker identity from each direction's curve
Gram matrices (param_surface_energy). The references here are independent of it:
- the tensor-product basis integrated directly, exactly, with SymPy from the family's own
  formula text (a polynomial family in two parameters), entry by entry and monomial by
  monomial;
- mpmath quadrature over the surface's domain at 40 digits of the energy integrand itself
  (|S_u|² + |S_v|², |S_uu|² + 2|S_uv|² + |S_vv|²), the surface built from the families'
  functions written out in SymPy and differentiated there.
"""

from __future__ import annotations

import sys
from fractions import Fraction as F
from pathlib import Path

import pytest

import lambda_bezier as lb
from lambda_bezier import examples
from lambda_bezier.hazmat.constants import ConstantFraction, ConstantSum

sp = pytest.importorskip("sympy")
mpmath = pytest.importorskip("mpmath")
from mpmath.calculus.quadrature import GaussLegendre  # noqa: E402

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

DATA = Path(__file__).parent / "data" / "families"
TWO_END = DATA / "two_end_bezier.toml"
TRIG = Path(examples.path("han_trig_cubic.toml"))
HYP = DATA / "hyp_cubic.toml"
ENERGIES = {"membrane": ((1, 0, 1), (0, 1, 1)), "thin_plate": ((2, 0, 1), (1, 1, 2), (0, 2, 1))}
t = sp.Symbol("t")


def _functions(path: Path, degree: int, params: dict) -> tuple[list, tuple]:
    """The family's basis functions at `degree` and `params` as SymPy expressions in t, read
    from its definition text by SymPy itself (trusted test data), and its domain."""
    fam = tomllib.loads(path.read_text())["family"]
    names = {name: sp.Symbol(name) for name in params}
    subs = {names[k]: sp.Rational(str(v)) for k, v in params.items()}
    local = {"t": t, **names}
    if "functions" in fam:
        funcs = [sp.sympify(f, locals=local).subs(subs) for f in fam["functions"]]
        lo, hi = (sp.sympify(x) for x in fam.get("domain", "[0, 1]").strip("[]").split(","))
        return funcs, (lo, hi)
    i, n = sp.symbols("i n", integer=True)
    local |= {"i": i, "n": n}
    expr = sp.sympify(fam["basis"], locals=local)
    funcs = [expr.subs({n: degree, i: k}).subs(subs) for k in range(degree + 1)]
    return [sp.expand(sp.expand_func(f)) for f in funcs], (sp.Integer(0), sp.Integer(1))


def _quadrature_energy(energy: str, net, fu, fv) -> mpmath.mpf:
    """∫∫ of the energy integrand over the product of the domains at 40 digits: a tensor
    Gauss-Legendre rule on the integrand's values at the nodes (each basis function and its
    derivatives evaluated there from SymPy's own derivative), run at 24 and at 48 nodes a
    direction; the two must agree to 1e-32 (the functions are entire: the rule converges
    faster than geometrically), so the reference certifies itself."""
    (bu, (ulo, uhi)), (bv, (vlo, vhi)) = fu, fv
    dim = len(net[0][0])
    rows = [
        [[mpmath.mpf(sp.Rational(str(x)).p) / sp.Rational(str(x)).q for x in p] for p in row]
        for row in net
    ]
    results = []
    with mpmath.workdps(40):
        rule = GaussLegendre(mpmath.mp)
        calls = [
            [[sp.lambdify(t, sp.diff(b, t, k), "mpmath") for b in basis] for k in range(3)]
            for basis in (bu, bv)
        ]
        for degree in (4, 5):
            du, dv = (
                [
                    (w, [[f(x) for f in fk] for fk in fns])
                    for x, w in rule.get_nodes(
                        mpmath.mpf(sp.N(lo, 50)), mpmath.mpf(sp.N(hi, 50)), degree, mpmath.mp.prec
                    )
                ]
                for fns, lo, hi in ((calls[0], ulo, uhi), (calls[1], vlo, vhi))
            )
            total = mpmath.mpf(0)
            for wv, fv_k in dv:
                # Σ_j P_ij c_j^(kv)(v) per row i, coordinate c and order kv at this node
                inner = {
                    kv: [
                        [
                            mpmath.fsum(rows[i][j][c] * fv_k[kv][j] for j in range(len(bv)))
                            for c in range(dim)
                        ]
                        for i in range(len(bu))
                    ]
                    for kv in {kv for _, kv, _ in ENERGIES[energy]}
                }
                for wu, fu_k in du:
                    point = mpmath.mpf(0)
                    for ku, kv, weight in ENERGIES[energy]:
                        for c in range(dim):
                            d = mpmath.fsum(fu_k[ku][i] * inner[kv][i][c] for i in range(len(bu)))
                            point += weight * d * d
                    total += wu * wv * point
            results.append(total)
        assert abs(results[0] - results[1]) <= mpmath.mpf(10) ** -32 * max(1, abs(results[1]))
    return results[1]


def _close(exact, reference) -> None:
    with mpmath.workdps(40):
        if isinstance(exact, ConstantSum):
            lo, hi = exact.enclosure(160)
            value = (
                mpmath.mpf(lo.numerator) / lo.denominator
                + mpmath.mpf(hi.numerator) / hi.denominator
            ) / 2
        elif isinstance(exact, ConstantFraction):
            value = mpmath.mpf(sp.N(_sympy(exact), 45))
        else:
            value = mpmath.mpf(exact.numerator) / exact.denominator
        assert abs(value - reference) <= mpmath.mpf(10) ** -30 * max(1, abs(reference)), (
            value,
            reference,
        )


def _sympy(x: ConstantFraction):
    c = sp.pi if x.constant == "pi" else sp.exp(sp.Rational(x.constant[4:-1]))
    num = sum(sp.Rational(q.numerator, q.denominator) * c**e for e, q in enumerate(x.numerator))
    den = sum(sp.Rational(q.numerator, q.denominator) * c**e for e, q in enumerate(x.denominator))
    return num / den


NET = [[(F(i), F(j), F((3 * i * j + i) % 5, 2)) for j in range(4)] for i in range(4)]


# ---------------------------------------------------------------------- direct integration
def test_a_two_parameter_family_equals_the_direct_integration():
    """two_end_bezier (lam, mu) at degrees (3, 3): every monomial's matrix equals the
    tensor-product basis B_ij(u, v) = b_i(u) b_j(v), with the four parameters symbolic,
    differentiated and integrated over the unit square by SymPy, entry by entry."""
    fam = lb.load_family(TWO_END)
    mats = lb.surface_energy_matrices((3, 3), "membrane", fam)
    assert mats.names == ("lam_u", "mu_u", "lam_v", "mu_v") and mats.constants == ()
    text = tomllib.loads(TWO_END.read_text())["family"]["basis"]
    i, n = sp.symbols("i n", integer=True)
    lam, mu, lu, mu_u, lv, mu_v, u, v = sp.symbols("lam mu lam_u mu_u lam_v mu_v u v")
    expr = sp.sympify(text, locals={"i": i, "n": n, "lam": lam, "mu": mu, "t": t})
    curve = [sp.expand(sp.expand_func(expr.subs({n: 3, i: k}))) for k in range(4)]
    bu = [c.subs({t: u, lam: lu, mu: mu_u}) for c in curve]
    bv = [c.subs({t: v, lam: lv, mu: mu_v}) for c in curve]
    gens = (lu, mu_u, lv, mu_v)
    basis = [sp.Poly(a * b, u, v, *gens) for a in bu for b in bv]  # over QQ: fast products
    parts = {
        (ku, kv): [b.diff((u, ku), (v, kv)) for b in basis] for ku, kv, _ in ENERGIES["membrane"]
    }
    seen = set()
    for r in range(16):
        for c in range(r, 16):
            total: dict = {}
            for ku, kv, w in ENERGIES["membrane"]:
                prod = parts[(ku, kv)][r] * parts[(ku, kv)][c]
                for (pu, pv, *key), coef in prod.terms():  # ∫∫ u^pu v^pv = 1/((pu+1)(pv+1))
                    value = F(str(coef)) * w / ((pu + 1) * (pv + 1))
                    total[tuple(key)] = total.get(tuple(key), F(0)) + value
            for key, value in total.items():
                if value:
                    seen.add(key)
                    assert mats.full[key][r][c] == value, (key, r, c)
    assert seen == set(mats.full)
    for key, (scale, upper) in mats.terms.items():  # scale · U is the full matrix
        assert all(
            scale * upper[r][c] == mats.full[key][r][c] * (1 if r == c else 2)
            for r in range(16)
            for c in range(r, 16)
        )
        assert all(isinstance(x, int) for row in upper for x in row)


# ---------------------------------------------------------------------- quadrature
CASES = {
    "two_end_bezier": (
        (TWO_END, {"lam": F(1, 2), "mu": F(-1)}),
        (TWO_END, {"lam": 0, "mu": F(1, 3)}),
    ),
    "trig": ((TRIG, {"lam": F(1), "mu": F(-1, 2)}), (TRIG, {"lam": F(-2), "mu": F(1, 3)})),
    "hyp": ((HYP, {"lam": F(1, 2), "mu": F(1, 3)}), (HYP, {"lam": F(1), "mu": F(0)})),
    "trig_x_hyp": ((TRIG, {"lam": F(1), "mu": F(-1, 2)}), (HYP, {"lam": F(1, 2), "mu": F(1, 3)})),
    "hyp_x_two_end": ((HYP, {"lam": F(1, 4), "mu": F(1)}), (TWO_END, {"lam": F(1), "mu": F(-2)})),
}


@pytest.mark.parametrize("energy", ["membrane", "thin_plate"])
@pytest.mark.parametrize("case", sorted(CASES))
def test_matrices_and_energy_against_quadrature(case, energy):
    (pu, params_u), (pv, params_v) = CASES[case]
    fam_u, fam_v = lb.load_family(pu), lb.load_family(pv)
    mats = lb.surface_energy_matrices((3, 3), energy, (fam_u, fam_v))
    reference = _quadrature_energy(
        energy, NET, _functions(pu, 3, params_u), _functions(pv, 3, params_v)
    )
    point = tuple(params_u[x] for x in ("lam", "mu")) + tuple(params_v[x] for x in ("lam", "mu"))
    _close(mats.at(NET, tuple(F(x) for x in point)), reference)
    surf = fam_u.surface(NET, params_u=params_u, params_v=params_v, family_v=fam_v)
    got = lb.surface_energy(surf, energy)
    expected_type = {
        "trig_x_hyp": ConstantSum,
        "trig": ConstantFraction,
        "hyp": ConstantFraction,
        "hyp_x_two_end": ConstantFraction,
    }.get(case, F)
    assert isinstance(got, expected_type)
    _close(got, reference)


def test_the_honest_form_of_an_atom_family():
    """With π the entries lie in ℚ[π, 1/π]: one integer matrix with a scale per power of π
    and parameter monomial, and at least two powers occur (no single integer scale)."""
    mats = lb.surface_energy_matrices((3, 3), "thin_plate", lb.load_family(TRIG))
    assert mats.constants == ("pi",)
    powers = {key[-1] for key in mats.terms}
    assert len(powers) >= 2
    for key, (scale, upper) in mats.terms.items():
        assert isinstance(scale, F) and all(isinstance(x, int) for row in upper for x in row)
        size = len(upper)
        assert all(
            scale * upper[r][c] == mats.full[key][r][c] * (1 if r == c else 2)
            for r in range(size)
            for c in range(r, size)
        )


def test_trig_x_hyp_energy_is_exact_with_a_certified_enclosure():
    fam_u, fam_v = lb.load_family(TRIG), lb.load_family(HYP)
    (_, pu), (_, pv) = CASES["trig_x_hyp"]
    surf = fam_u.surface(NET, params_u=pu, params_v=pv, family_v=fam_v)
    got = lb.surface_energy(surf, "membrane")
    assert got.constants == ("pi", "exp(1)")
    lo, hi = got.enclosure(200)
    assert lo <= hi and hi - lo < F(1, 10**50)
    closed = got.to_sympy()
    assert closed.has(sp.pi) and closed.has(sp.E)
    assert abs(sp.N(closed, 50) - sp.Rational(lo.numerator, lo.denominator)) < sp.Rational(
        1, 10**40
    )
    assert float(got) == pytest.approx(float(sp.N(closed, 30)), rel=1e-15)
    floaty = fam_u.surface(
        [[tuple(float(x) for x in p) for p in row] for row in NET],
        params_u=pu,
        params_v=pv,
        family_v=fam_v,
    )
    assert isinstance(lb.surface_energy(floaty, "membrane"), float)


def test_bad_degrees_and_energy_are_named():
    fam = lb.load_family(TRIG)
    with pytest.raises(ValueError, match=r"degrees = \(4, 3\).*direction u"):
        lb.surface_energy_matrices((4, 3), "membrane", fam)
    with pytest.raises(ValueError, match="energy"):
        lb.surface_energy_matrices((3, 3), "bending", fam)
    with pytest.raises(ValueError, match="degrees must be a pair"):
        lb.surface_energy_matrices(3, "membrane", fam)
    mats = lb.surface_energy_matrices((3, 3), "membrane", fam)
    with pytest.raises(ValueError, match="net must have 4 x 4 points"):
        mats.polynomial(NET[:3])


def test_an_indexed_family_names_each_parameter():
    """q_bezier, lam(1..n) in each direction: one name per index and direction, and the
    matrices at a point give the energy surface_energy computes by its own accumulation."""
    fam = lb.load_family(DATA / "q_bezier.toml")
    mats = lb.surface_energy_matrices((3, 2), "thin_plate", fam)
    assert mats.names == ("lam_1_u", "lam_2_u", "lam_3_u", "lam_1_v", "lam_2_v")
    net = [[(F(i), F(j), F((i * j) % 3)) for j in range(3)] for i in range(4)]
    lam_u, lam_v = (F(1, 2), F(0), F(-1, 3)), (F(1), F(1, 2))
    surf = fam.surface(net, params_u={"lam": lam_u}, params_v={"lam": lam_v})
    assert mats.at(net, (*lam_u, *lam_v)) == lb.surface_energy(surf, "thin_plate")
