"""C-Bezier families on [0, alpha] (issue #30): a parameter in the domain or inside sin/cos.

Every decision is checked against independent numerics (mpmath at 40 digits): the sum of the
basis, end derivatives by mpmath.diff, energies by quadrature, the counterexample of a box
reaching past 2*pi; the definition file's functions against the solution of the end
conditions; the runtime against mpmath evaluation of the written functions.
"""

from __future__ import annotations

import math
import shutil
from pathlib import Path

import mpmath as mp
import numpy as np
import pytest
import sympy as sp
import tomllib
from conftest import family_file
from hypothesis import example, given, settings
from hypothesis import strategies as st

from derive.families import cbezier as cb
from derive.families.definition import DefinitionError
from derive.formulas import cbezier as F
from lambda_bezier import examples

DATA = Path(__file__).parent / "data" / "families"
mp.mp.dps = 40


def _table(name: str) -> dict:
    return tomllib.loads(family_file(name).read_text())["family"]


@pytest.fixture(scope="module")
def cubic() -> cb.CDefinition:
    return cb.read_table(_table("c_bezier_cubic"))


@pytest.fixture(scope="module")
def hyperbolic() -> cb.CDefinition:
    return cb.read_table(_table("hc_bezier_cubic"))


def _mp_function(defn: cb.CDefinition, i: int):
    """b_i(t; alpha) in mpmath, from the exact element written out (independent of the
    reduction and of the runtime)."""
    expr = cb.as_function(defn.elems()[i], defn.hyperbolic)
    return sp.lambdify((cb.T, cb.A), expr, modules="mpmath")


def _mp_written(defn: cb.CDefinition, i: int):
    """b_i as the file writes it (the grammar's parse, t on [0, alpha])."""
    return sp.lambdify((cb.T, cb.A), defn.written()[i], modules="mpmath")


# --------------------------------------------------------------------------- the definition


def _solve_end_conditions(hyp: bool) -> list[dict]:
    """The cubic basis of span{1, t, sin t, cos t} (sinh, cosh) with the Bernstein end
    conditions, solved here from the conditions (not read from a paper)."""
    atoms = [(cb.POW, 0), (cb.POW, 1), (cb.COS, 1), (cb.SIN, 1)]
    x = sp.symbols("x0:4")

    def solve(conds):
        e = dict(zip(atoms, x, strict=True))
        eqs = []
        for end, order, val in conds:
            d = cb.derivative(e, hyp, order)
            total = 0
            for (kind, m), v in d.items():
                if end == "lo":
                    total += v if (kind == cb.POW and m == 0) or kind == cb.COS else 0
                else:
                    c, s = cb.angle(m, hyp)
                    total += v * (cb.A**m if kind == cb.POW else c if kind == cb.COS else s)
            eqs.append(total - val)
        sol = sp.solve(eqs, x, dict=True)[0]
        return {a: sol[xi] for a, xi in zip(atoms, x, strict=True)}

    b0 = solve([("lo", 0, 1), ("hi", 0, 0), ("hi", 1, 0), ("hi", 2, 0)])
    b3 = solve([("hi", 0, 1), ("lo", 0, 0), ("lo", 1, 0), ("lo", 2, 0)])
    d0 = cb.value_at(cb.derivative(b0, hyp), "lo", hyp)
    d3 = cb.value_at(cb.derivative(b3, hyp), "hi", hyp)
    b1 = solve([("lo", 0, 0), ("hi", 0, 0), ("hi", 1, 0), ("lo", 1, -d0)])
    b2 = solve([("hi", 0, 0), ("lo", 0, 0), ("lo", 1, 0), ("hi", 1, -d3)])
    return [b0, b1, b2, b3]


@pytest.mark.parametrize("name", ["c_bezier_cubic", "c_bezier_cubic_unit", "hc_bezier_cubic"])
def test_the_file_is_the_solution(name):
    defn = cb.read_table(_table(name))
    solved = _solve_end_conditions(defn.hyperbolic)
    for f, g in zip(defn.elems(), solved, strict=True):
        for atom in set(f) | set(g):
            diff = f.get(atom, 0) - g.get(atom, 0)
            assert cb.is_zero(diff, defn.hyperbolic), (name, atom)


def test_the_two_forms_are_one_basis(cubic):
    unit = cb.read_table(_table("c_bezier_cubic_unit"))
    assert unit.form == "unit" and cubic.form == "domain"
    assert [dict(f) for f in unit.functions] == [dict(f) for f in cubic.functions]


def test_reduce_decides_the_circle():
    # sin^2 + cos^2 - 1 is zero; sin - sqrt-free expressions that are not zero are not
    assert cb.is_zero(cb.S**2 + cb.C**2 - 1, False)
    assert cb.is_zero(cb.C**2 - cb.S**2 - 1, True)
    assert not cb.is_zero(cb.S + cb.C - 1, False)
    assert not cb.is_zero(cb.A - cb.S, False)


# --------------------------------------------------------------------------- decisions


def test_exact_identities(cubic, hyperbolic):
    for defn in (cubic, hyperbolic):
        assert F.partition_of_unity(defn)
        assert F.symmetric(defn)
        assert F.bernstein_end_conditions(defn)


def test_interpolating_basis_is_not_a_partition():
    defn = cb.read_table(_table("hyp_interpolating"))
    assert not F.partition_of_unity(defn)
    assert F.symmetric(defn)
    assert F.rank(defn)[0] == 2
    ends = F.end_table(defn)
    assert ends[0][0][0] == 1 and ends[0][1][0] == 0 and ends[1][1][0] == 1


def test_a_broken_basis_is_caught(cubic):
    """The deciders can fail: a basis with b_3 doubled is neither a partition nor symmetric,
    and its ends are not Bernstein's when b_1 is replaced."""
    table = dict(_table("c_bezier_cubic"))
    funcs = list(table["functions"])
    funcs[3] = f"2*({funcs[3]})"
    broken = cb.read_table({**table, "functions": funcs})
    assert not F.partition_of_unity(broken)
    assert not F.symmetric(broken)
    funcs = list(table["functions"])
    funcs[1] = "sin(t)/sin(alpha)"
    assert not F.bernstein_end_conditions(cb.read_table({**table, "functions": funcs}))


@pytest.mark.parametrize("alpha", ["1/3", "1", "2.5", "pi"])
def test_sum_ends_and_symmetry_against_mpmath(cubic, alpha):
    a = mp.mpf(mp.pi) if alpha == "pi" else mp.mpf(sp.Rational(alpha))
    fs = [_mp_written(cubic, i) for i in range(4)]
    for t in (a / 7, a / 2, a * 5 / 6):
        assert abs(sum(f(t, a) for f in fs) - 1) < mp.mpf(10) ** -30
        for i in range(4):
            assert abs(fs[i](t, a) - fs[3 - i](a - t, a)) < mp.mpf(10) ** -30
    ends = F.end_table(cubic)
    sym = sp.Symbol("alpha")
    for i in range(4):
        for order in range(4):
            for end, x in ((0, mp.mpf(0)), (1, a)):
                got = mp.diff(lambda t, i=i: fs[i](t, a), x, order)
                exact = ends[i][end][order].subs({cb.S: sp.sin(sym), cb.C: sp.cos(sym)})
                exact_alpha = sp.pi if alpha == "pi" else sp.Rational(alpha)
                want = sp.N(exact.subs(cb.A, sym).subs(sym, exact_alpha), 45)
                assert abs(got - mp.mpf(str(want))) < mp.mpf(10) ** -20, (i, order, end)


@pytest.mark.parametrize("k", [1, 2, 3])
def test_energies_against_quadrature(cubic, k):
    g = F.gram(cubic, k)
    fs = [_mp_written(cubic, i) for i in range(4)]
    a = mp.mpf(2) / 3 + 1
    for i, j in ((0, 0), (0, 3), (1, 2), (2, 2)):
        want = mp.quad(
            lambda t, i=i, j=j: (
                mp.diff(lambda x: fs[i](x, a), t, k) * mp.diff(lambda x: fs[j](x, a), t, k)
            ),
            [0, a],
        )
        got = sp.N(
            g[i][j].subs(
                {
                    cb.A: sp.Rational(5, 3),
                    cb.S: sp.sin(sp.Rational(5, 3)),
                    cb.C: sp.cos(sp.Rational(5, 3)),
                }
            ),
            40,
        )
        assert abs(mp.mpf(str(got)) - want) < mp.mpf(10) ** -15 * (1 + abs(want)), (i, j)


def test_singular_point_is_named(cubic):
    rows = F.singular_points(cubic)
    assert rows and all(r["at"] == "0" for r in rows)
    assert {r["leading_term"] for r in rows} >= {"alpha**3/6"}
    assert any(r["denominator"] == "alpha - sin(alpha)" for r in rows)


def test_a_box_past_two_pi_has_a_counterexample():
    table = {**_table("c_bezier_cubic"), "name": "c_bezier_wide", "range": "(0, 3*pi]"}
    defn = cb.read_table(table)
    got = F.nonnegative(defn)
    assert got["verdict"] is False
    cex = got["counterexample"]
    f = _mp_written(defn, cex["i"])
    # the counterexample checked again, independently, at 40 digits
    assert f(mp.mpf(cex["t_float"]), mp.mpf(cex["alpha_float"])) < 0
    inside = [r for r in F.singular_points(defn) if r["where"].startswith("inside")]
    assert inside and any(
        abs(float(r["at"].strip("[]").split(",")[0]) - 2 * math.pi) < 1e-6 for r in inside
    )


def test_the_paper_box_is_certified_positive(cubic):
    got = F.nonnegative(cubic)
    assert got["verdict"] is True and got["method"].startswith("certified")
    fs = [_mp_written(cubic, i) for i in range(4)]
    for a in (mp.mpf("0.01"), mp.mpf("0.2"), mp.pi):  # below the sampled grid too
        for u in np.linspace(0.01, 0.99, 25):
            assert all(f(a * mp.mpf(u), a) > 0 for f in fs)


# --------------------------------------------------------------------------- refusals


@pytest.mark.parametrize(
    ("change", "key", "words"),
    [
        ({"domain": "[0, beta]"}, "domain", "'beta' is not the family's parameter"),
        ({"functions": ["sin(alpha*t**2)", "1", "1", "1"]}, "functions[0]", "alpha*t**2"),
        ({"functions": ["t**2000", "1", "1", "1"]}, "functions[0]", "2000"),
        ({"functions": ["sin(alpha/2 - t)", "1", "1", "1"]}, "functions[0]", "integer multiple"),
        ({"functions": ["t*sin(t)", "1", "1", "1"]}, "functions[0]", "t**1 times"),
        ({"functions": ["sin(t)/sin(t + alpha)", "1", "1", "1"]}, "functions[0]", "division"),
        ({"range": "[0, pi]"}, "range", "alpha > 0"),
        ({"range": "(0, e]"}, "range", "unknown name"),
        ({"functions": ["1", "1", "1"]}, "functions", "has 4 functions"),
        ({"functions": ["sin(t) + cosh(t)", "1", "1", "1"]}, "functions", "together"),
        ({"bernstein_at": "1"}, "bernstein_at", "explicit `functions`"),
    ],
)
def test_bad_definitions_are_refused_by_key(change, key, words):
    table = {**_table("c_bezier_cubic"), **change}
    with pytest.raises(DefinitionError) as err:
        cb.read_table(table)
    assert f"key {key}:" in str(err.value) and words in str(err.value), str(err.value)


def test_a_parameter_in_the_domain_is_recognised():
    assert cb.is_frequency_family(_table("c_bezier_cubic"))
    assert cb.is_frequency_family(_table("c_bezier_cubic_unit"))
    assert not cb.is_frequency_family(_table("lit_han_quad_trig"))


# --------------------------------------------------------------------------- the runtime


@pytest.fixture(scope="module")
def family():
    import lambda_bezier as lb

    return lb.load_family(examples.path("c_bezier_cubic.toml"))


P = [[0.0, 0.0], [1.0, 2.0], [3.0, 2.5], [4.0, 0.5]]


@settings(max_examples=25, deadline=None)
@given(alpha=st.floats(0.3, math.pi), u=st.floats(0, 1))
@example(alpha=math.pi, u=0.5)
@example(alpha=0.3, u=0.999)
def test_runtime_evaluation_against_mpmath(family, cubic, alpha, u):
    c = family.curve(P, alpha=alpha)
    t = alpha * u
    a = mp.mpf(alpha)
    fs = [_mp_written(cubic, i) for i in range(4)]
    for order in (0, 1, 2):
        want = [
            sum(mp.diff(lambda x, i=i: fs[i](x, a), mp.mpf(t), order) * P[i][d] for i in range(4))
            for d in range(2)
        ]
        got = c.derivative(t, order)
        tol = 1e-9 * (1 + float(max(abs(w) for w in want)))
        assert np.allclose(got, [float(w) for w in want], rtol=0, atol=tol), (order, got, want)


def test_runtime_energy_split_and_geometry(family, cubic):
    c = family.curve(P, alpha=2.0)
    fs = [_mp_written(cubic, i) for i in range(4)]
    a = mp.mpf(2)

    def speed2(t):
        d = [
            sum(mp.diff(lambda x, i=i: fs[i](x, a), t, 2) * P[i][k] for i in range(4))
            for k in range(2)
        ]
        return d[0] ** 2 + d[1] ** 2

    assert abs(c.energy(2) - float(mp.quad(speed2, [0, a]))) < 1e-9 * c.energy(2)
    left, right = c.split(0.7)
    assert left.alpha == pytest.approx(0.7) and right.alpha == pytest.approx(1.3)
    for s in (0.0, 0.3, 0.7):
        assert np.allclose(left.evaluate(s), c.evaluate(s), atol=1e-12)
    for s in (0.0, 0.6, 1.3):
        assert np.allclose(right.evaluate(s), c.evaluate(0.7 + s), atol=1e-12)
    q = np.array([2.0, 3.0])
    found = c.closest_point(q)
    grid = c.evaluate(np.linspace(0, 2.0, 20001))
    assert found.distance <= np.linalg.norm(grid - q, axis=1).min() + 1e-12
    lo, hi = c.bounding_box()
    assert np.all(grid >= lo - 1e-12) and np.all(grid <= hi + 1e-12)


def test_runtime_refusals(family):
    with pytest.raises(ValueError, match="alpha = 4 is outside"):
        family.curve(P, alpha=4)
    with pytest.raises(ValueError, match="alpha = 0 is outside"):
        family.curve(P, alpha=0)
    # alpha -> 0 is removable: small alpha is evaluated from the series (and checked against
    # mpmath in tests/test_cbezier_small_alpha.py); only past the float range is it refused
    family.curve(P, alpha=1e-5)
    with pytest.raises(ValueError, match="alpha = 1e-300 is too small"):
        family.curve(P, alpha=1e-300)
    with pytest.raises(TypeError, match="alpha must be a real number"):
        family.curve(P, alpha="1")


def test_optimal_alpha_is_the_least_energy(family):
    """fam.optimal_alpha is the certified optimum as a dict (tests/test_cbezier_optimum.py
    checks it against quadrature); here against the runtime's own energy on a grid."""
    got = family.optimal_alpha(P, 1)
    grid = [family.energy(P, x, 1) for x in np.linspace(0.5, math.pi, 400)]
    assert got["energy"] <= min(grid) + 1e-12
    assert got["where"] == "upper end" and got["alpha"] == math.pi
    assert got["energy"] - float(got["lower_bound"]) <= 1e-12 * got["energy"]


def test_derive_cli_prints_verdicts(tmp_path, capsys):
    from lambda_bezier.cli import main

    shutil.copy(DATA / "hyp_interpolating.toml", tmp_path)
    assert main(["derive", "--family", str(tmp_path / "hyp_interpolating.toml")]) == 0
    err = capsys.readouterr().err
    assert "partition of unity: False (exact)" in err
    assert "alpha = 0 (sinh(alpha) = 0" in err
    assert main(["derive", "--check", "--family", str(DATA / "hyp_interpolating.toml")]) == 0


def test_shared_functions_say_where_the_family_api_is(family):
    """A shared function that takes polynomial families only names such a family and points
    to the functions that take it (before: 'unknown family' for a family load_family had just
    returned). optimal_parameters, join, CompositeCurve, evaluate_many and to_json take it
    (tests/test_cbezier_optimum.py, tests/test_cbezier_shared.py)."""
    import lambda_bezier as lb

    with pytest.raises(TypeError) as info:
        lb.energy_coefficients(P, 2, family=family)
    text = str(info.value)
    assert "'c_bezier_cubic' has its parameter alpha in the domain" in text
    assert "optimal_parameters" in text and "fam.curve(points, alpha=...)" in text
