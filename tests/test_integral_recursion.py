"""Bases defined by integral recursions (Chen and Wang 2003): the grammar's integral
operators, the polynomial engine (Bernstein from {1 - t, t}), the C-Bezier engine (every
degree from the order-2 trigonometric seed; degree 3 equal to c_bezier_cubic.toml, which
tests/test_cbezier_family.py solved from end conditions), the bad definitions, and the
shipped example end to end.

The references are independent of the engines: the classical Bernstein formula; SymPy's
integrate applied to the definition in this file (for the C-Bezier degrees 2 and 3); mpmath
evaluation of those integrals against the runtime's floats.
"""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

import mpmath as mp
import numpy as np
import pytest
import sympy as sp
import tomllib
from conftest import family_file

from derive.families import cbezier as cb
from derive.families import cbezier_recursion as R
from derive.families import engine
from derive.families.definition import DefinitionError, definition_from_table
from derive.formulas import cbezier as F
from derive.grammar import SYMBOLS, ParseError, parse_formula
from lambda_bezier import examples, load_family
from lambda_bezier.export import from_json, to_json

CHEN_WANG = (
    "kronecker(i, 0) + integral(normalized(b(i - 1, n - 1, t)) - normalized(b(i, n - 1, t)))"
)
t = sp.Symbol("t")


def _table(name: str) -> dict:
    return tomllib.loads(family_file(name).read_text())["family"]


@pytest.fixture(scope="module")
def orders() -> tuple[cb.CDefinition, ...]:
    return R.read_orders(_table("c_bezier_orders"))


# --------------------------------------------------------------------------- the grammar


def test_the_operators_parse_only_in_a_recursion():
    e = parse_formula(CHEN_WANG, SYMBOLS, {"b": sp.Function("b")}, operators=True)
    assert e.has(sp.KroneckerDelta) and "integral" in str(e)
    with pytest.raises(ParseError, match="unknown name 'integral'"):
        parse_formula("integral(t)", SYMBOLS, {})
    with pytest.raises(ParseError, match="nested deeper than 4"):
        parse_formula("integral(" * 5 + "t" + ")" * 5, SYMBOLS, {}, operators=True)
    with pytest.raises(ParseError, match="integers"):
        parse_formula("kronecker(t, 0)", SYMBOLS, {}, operators=True)
    with pytest.raises(ParseError, match="one function of t"):
        parse_formula("total(t, t)", SYMBOLS, {}, operators=True)


# --------------------------------------------------------------------------- polynomial engine


def _poly_table(**over) -> dict:
    table = {
        "name": "integral_bernstein",
        "parameter": "lam",
        "range": "[0, 1]",
        "degrees": "1..12",
        "seed": ["1 - t", "t"],
        "recursion": CHEN_WANG,
    }
    return {**table, **over}


def test_bernstein_from_the_integral_recursion_exactly():
    defn = definition_from_table(_poly_table())
    for n in range(2, 13):
        got = [p.as_expr() for p in engine.basis_polys(defn, n)]
        want = [sp.binomial(n, i) * t**i * (1 - t) ** (n - i) for i in range(n + 1)]
        assert [sp.expand(g - w) for g, w in zip(got, want, strict=True)] == [0] * (n + 1), n
    assert "partition of unity, every degree" in engine.check(defn)


LAMBDA_SEED = [
    "(1 - t)**2 + lam*t*(1 - t)*(1 - 2*t)",
    "2*t*(1 - t)",
    "t**2 - lam*t*(1 - t)*(1 - 2*t)",
]


def test_a_lambda_family_against_sympy_integrate():
    """Degree 3 from a seed whose totals do not depend on lam (1/3 each): the engine against
    the recursion computed here by SymPy's integrate, and the Bernstein cubic at lam = 0."""
    table = _poly_table(
        name="integral_lambda",
        range="[-1, 0]",
        degrees="2..3",
        degree_offset=1,
        bernstein_at="0",
        seed=LAMBDA_SEED,
    )
    defn = definition_from_table(table)
    lam, s = sp.Symbol("lam"), sp.Symbol("s")
    seed = [parse_formula(x, {"t": t, "lam": lam}, {}) for x in LAMBDA_SEED]

    def norm(f):
        return f / sp.integrate(f, (t, 0, 1))

    seed_ext = [sp.Integer(0), *seed, sp.Integer(0)]
    want = [
        int(i == 0)
        + sp.integrate((norm(seed_ext[i]) - norm(seed_ext[i + 1])).subs(t, s), (s, 0, t))
        if (seed_ext[i], seed_ext[i + 1]) != (0, 0)
        else 0
        for i in range(4)
    ]
    # normalized(0) is 0: the first and last terms have one side only
    want[0] = 1 + sp.integrate(-norm(seed[0]).subs(t, s), (s, 0, t))
    want[3] = sp.integrate(norm(seed[2]).subs(t, s), (s, 0, t))
    got = [p.as_expr() for p in engine.basis_polys(defn, 3)]
    assert [sp.simplify(g - w) for g, w in zip(got, want, strict=True)] == [0] * 4
    engine.check(defn)  # partition of unity; Bernstein at lam = 0


def test_a_total_that_leaves_the_polynomials_is_named():
    """A seed whose totals depend on lam makes the next degree rational in lam: the
    polynomial engine refuses it by name (its tables are polynomials in the parameter)."""
    defn = definition_from_table(
        _poly_table(
            name="integral_lambda",
            range="[-1, 0]",
            degrees="2..4",
            degree_offset=1,
            seed=LAMBDA_SEED,
        )
    )
    with pytest.raises(DefinitionError, match=r"b\(0, 4, t\) is not a polynomial"):
        engine.basis_polys(defn, 4)


@pytest.mark.parametrize(
    ("over", "match"),
    [
        (
            {
                "range": "[0, 1]",
                "degrees": "2..3",
                "seed": ["(1 - t)*(1 - lam*t)", "2*lam*t*(1 - t)", "t*(1 - lam*(1 - t))"],
            },
            r"recursion: normalized\(b\(1, 2, t\)\) at n = 3: the total lam/3 is 0 at "
            r"lam = 0, inside the range",
        ),
        ({"recursion": "integral(1/(1 + t))"}, "not a polynomial in t, so its integral"),
        ({"recursion": "integral(" * 5 + "b(i, n - 1, t)" + ")" * 5}, "key recursion: .*nested"),
        ({"recursion": "kronecker(i, 0) + total(b(i, n - 1, t) - b(i, n - 1, t))"}, "is 0"),
    ],
)
def test_bad_polynomial_recursions_name_the_key(over, match):
    with pytest.raises(DefinitionError, match=match):
        defn = definition_from_table(_poly_table(**over))
        for n in defn.degrees:
            engine.basis_polys(defn, n)


# --------------------------------------------------------------------------- C-Bezier engine


def _difference_is_zero(f: cb.Elem, g: cb.Elem) -> bool:
    diff = dict(f)
    for atom, v in g.items():
        cb.add_into(diff, atom, -v)
    return all(cb.is_zero(v, False) for v in diff.values())


def test_degree_3_is_the_c_bezier_cubic_exactly(orders):
    cubic = cb.read_table(_table("c_bezier_cubic"))
    (three,) = [o for o in orders if o.degree == 3]
    assert all(_difference_is_zero(f, g) for f, g in zip(three.elems(), cubic.elems(), strict=True))


def _sympy_orders(top: int) -> list[list[sp.Expr]]:
    """The recursion computed here from the definition: SymPy's integrate on the written
    functions (no atoms, no reduction)."""
    a, s = sp.Symbol("alpha", positive=True), sp.Symbol("s")
    basis = [sp.sin(a - t) / sp.sin(a), sp.sin(t) / sp.sin(a)]
    out = []
    for n in range(2, top + 1):
        norm = [f / sp.integrate(f, (t, 0, a)) for f in basis]
        ext = [sp.Integer(0), *norm, sp.Integer(0)]
        basis = [
            int(i == 0) + sp.integrate((ext[i] - ext[i + 1]).subs(t, s), (s, 0, t))
            for i in range(n + 1)
        ]
        out.append(basis)
    return out


def test_degrees_2_and_3_against_sympy_integrate(orders):
    a = sp.Symbol("alpha", positive=True)
    ref = _sympy_orders(3)
    for defn, want in zip(orders[:2], ref, strict=True):
        assert defn.degree == len(want) - 1
        for elem, w in zip(defn.elems(), want, strict=True):
            got = cb.as_function(elem, False)
            for av, tv in ((sp.Rational(1, 3), sp.Rational(1, 7)), (sp.Rational(5, 2), 2)):
                x = sp.N(got.subs({cb.A: av, cb.T: tv}), 40)
                y = sp.N(w.subs({a: av, t: tv}), 40)
                assert abs(x - y) < sp.Float(10) ** -30


def test_every_degree_passes_the_engines_checks(orders):
    for defn in orders:
        assert F.partition_of_unity(defn), defn.degree
        assert F.bernstein_end_conditions(defn), defn.degree
        assert F.symmetric(defn), defn.degree


def test_degrees_5_and_6_derive_and_keep_the_identities():
    """The recursion to degree 6 (what the shipped document does not reach, README of the
    guide): the space, and partition of unity and the Bernstein end values checked in mpmath
    at 80 digits on the exact elements written out (the exact decisions of formulas/ take a
    minute on these coefficients; at alpha = 1/3 the atoms cancel 25 digits at degree 6)."""
    table = {**_table("c_bezier_orders"), "degrees": "5..6"}
    five, six = R.read_orders(table)
    assert (five.degree, six.degree) == (5, 6)
    assert {a for f in six.functions for a, _ in f} == {("pow", k) for k in range(5)} | {
        ("cos", 1),
        ("sin", 1),
    }  # span{1, t, .., t^4, sin t, cos t}
    with mp.workdps(80):  # mpmath's global precision is the other tests' too
        for defn in (five, six):
            funcs = [
                sp.lambdify((cb.T, cb.A), cb.as_function(e, False), modules="mpmath")
                for e in defn.elems()
            ]
            for alpha in (mp.mpf(1) / 3, mp.mpf(2), mp.mpf(3)):
                for tv in (mp.mpf(0), alpha / 7, alpha / 2, alpha):
                    assert abs(sum(f(tv, alpha) for f in funcs) - 1) < mp.mpf(10) ** -25
                ends = [(f(0, alpha), f(alpha, alpha)) for f in funcs]
                n = defn.degree
                want = [(int(i == 0), int(i == n)) for i in range(n + 1)]
                assert all(
                    abs(x - wx) < mp.mpf(10) ** -25 and abs(y - wy) < mp.mpf(10) ** -25
                    for (x, y), (wx, wy) in zip(ends, want, strict=True)
                )


@pytest.mark.parametrize(
    ("over", "match"),
    [
        (
            {"range": "(0, pi]"},
            r"normalized\(b\(1, 2, t\)\) at n = 3: the total .* tends to 0 at alpha = pi",
        ),
        (
            {"recursion": "integral(b(i, n - 1, t)*b(i - 1, n - 1, t))"},
            "a product of two functions of t",
        ),
        ({"recursion": "integral(" * 5 + "b(i, n - 1, t)" + ")" * 5}, "key recursion: .*nested"),
        ({"recursion": "b(i, n - 2, t)"}, "reads the degree below"),
        ({"seed": ["1", "2", "3", "4", "5"]}, "key seed"),
        ({"domain": "[0, 1]", "seed": ["sin(alpha*(1 - t))", "sin(alpha*t)"]}, "key domain"),
        (
            {"recursion": "kronecker(i, 0) + integral(b(i, n - 1, t)/total(sin(t) - sin(t)))"},
            "is 0",
        ),
    ],
)
def test_bad_c_bezier_recursions_name_the_key(over, match):
    from derive.formulas.cbezier_nonnegative import nonvanishing

    table = {**_table("c_bezier_orders"), "degrees": "2..3", **over}
    with pytest.raises(DefinitionError, match=match):
        R.read_orders(table, "", nonvanishing)


# --------------------------------------------------------------------------- end to end


@pytest.fixture(scope="module")
def family_dir(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("orders")
    for suffix in (".toml", ".derived.json"):
        shutil.copy(examples.path(f"c_bezier_orders{suffix}"), out)
    return out


def test_the_shipped_document_is_the_derivation(family_dir):
    run = subprocess.run(
        [
            sys.executable,
            "-m",
            "lambda_bezier",
            "derive",
            "--family",
            "c_bezier_orders.toml",
            "--check",
        ],
        cwd=family_dir,
        capture_output=True,
        text=True,
        check=False,
    )
    assert run.returncode == 0, run.stdout + run.stderr
    doc = json.loads((family_dir / "c_bezier_orders.derived.json").read_text())
    assert doc["degrees"] == [2, 3]
    for sub in doc["orders"].values():
        v = sub["verdicts"]
        assert v["partition_of_unity"] and v["bernstein_end_conditions"] and v["symmetric"]
    assert doc["orders"]["3"]["verdicts"]["nonnegative"]["verdict"] is True
    # degree 2's middle function is 0 at alpha = pi, on the closed box the certificate works
    # on: sampled positive, not certified there (a true zero, not a budget)
    two = doc["orders"]["2"]["verdicts"]["nonnegative"]
    assert two["verdict"] == "not certified" and "positive ball" in two["sampled"]
    assert "alpha = 3.14159" in two["reason"]


def test_curves_of_every_degree_against_mpmath(family_dir):
    fam = load_family(family_dir / "c_bezier_orders.toml")
    a = sp.Symbol("alpha", positive=True)
    ref = _sympy_orders(3)
    with mp.workdps(30):  # mpmath's global precision is the other tests' too
        alpha = 2.0
        for n, basis in zip((2, 3), ref, strict=True):
            pts = np.arange(2 * (n + 1), dtype=float).reshape(n + 1, 2) ** 1.5
            c = fam.curve(pts, alpha=alpha)
            funcs = [sp.lambdify((t, a), f, modules="mpmath") for f in basis]
            dfuncs = [sp.lambdify((t, a), sp.diff(f, t), modules="mpmath") for f in basis]
            for tv in (0.0, 0.3, 1.1, alpha):
                want = sum(
                    float(f(mp.mpf(tv), mp.mpf(alpha))) * p for f, p in zip(funcs, pts, strict=True)
                )
                dwant = sum(
                    float(f(mp.mpf(tv), mp.mpf(alpha))) * p
                    for f, p in zip(dfuncs, pts, strict=True)
                )
                np.testing.assert_allclose(c.evaluate(tv), want, rtol=1e-10, atol=1e-10)
                np.testing.assert_allclose(c.derivative(tv), dwant, rtol=1e-9, atol=1e-9)
            left, right = c.split(0.7)
            np.testing.assert_allclose(left.evaluate(0.7), c.evaluate(0.7), atol=1e-9)
            end = right.evaluate(right.domain[1])
            np.testing.assert_allclose(end, c.evaluate(alpha), atol=1e-9)
            back = from_json(to_json(c), family=family_dir / "c_bezier_orders.toml")
            np.testing.assert_allclose(back.evaluate(1.0), c.evaluate(1.0), atol=1e-12)
        with pytest.raises(ValueError, match="degrees 2..3"):
            fam.curve(np.zeros((7, 2)), alpha=1.0)
