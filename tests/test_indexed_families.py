"""Indexed shape parameters (lam(i)) and the decisions over a whole box of parameters (#30).

The literature family is Han, Ma and Huang's generalized Bernstein basis with n shape
parameters. Its definition is taken as Hu, Bo and Qin restate it (J. Inequal. Appl.
2017:115, eq. (1)). Its files are tests/data/families/q_bezier.toml (every degree, signs
after the middle flipped) and q_bezier_4.toml (n = 4, as printed). The family is checked
against that piecewise construction, which is written out again below and evaluated
directly, independently of derive: mpmath for values and finite differences, and mpmath
quadrature for energies. The decisions over the box are checked at their counterexample
points by independent exact arithmetic, and the certified minimum against a grid.
"""

from __future__ import annotations

import json
import random
from fractions import Fraction
from math import comb
from pathlib import Path

import mpmath
import numpy as np
import pytest
import sympy as sp
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import lambda_bezier as lb
from lambda_bezier import examples
from lambda_bezier.export import from_json, to_json

DATA = Path(__file__).parent / "data" / "families"
Q_FILE = DATA / "q_bezier.toml"
Q4_FILE = DATA / "q_bezier_4.toml"
PRODUCT_FILE = DATA / "product_shape_cubic.toml"


@pytest.fixture(scope="module")
def q():
    return lb.load_family(Q_FILE)


def paper_basis(n: int, lam: list, t):
    """Hu-Bo-Qin eq. (1) (Han-Ma-Huang's basis) with l_1..l_n = lam[0..n-1], as printed:
    m = n/2 (even n) or (n + 1)/2 (odd n)."""
    m = n // 2 if n % 2 == 0 else (n + 1) // 2
    ell = [None, *lam]
    out = [(1 - t) ** n * (1 - ell[1] * t)]
    for i in range(1, n):
        base = t**i * (1 - t) ** (n - i)
        if i < m:
            out.append(base * (comb(n, i) + ell[i] - ell[i] * t - ell[i + 1] * t))
        elif i == m:
            out.append(base * (comb(n, i) + ell[i] - ell[i] * t + ell[i + 1] * t))
        else:
            out.append(base * (comb(n, i) - ell[i] + ell[i] * t + ell[i + 1] * t))
    out.append(t**n * (1 - ell[n] + ell[n] * t))
    return out


def paper_ranges(n: int) -> list[tuple[int, int]]:
    m = n // 2 if n % 2 == 0 else (n + 1) // 2
    return [
        (-comb(n, i), comb(n, i - 1)) if i <= m else (-comb(n, i - 1), comb(n, i))
        for i in range(1, n + 1)
    ]


def file_to_paper(n: int, lam: list) -> list:
    """q_bezier.toml's lam(i) -> the paper's l_i (the sign flips after the middle)."""
    m = n // 2 if n % 2 == 0 else (n + 1) // 2
    return [v if i <= m else -v for i, v in enumerate(lam, start=1)]


def basis_values(fam, n: int, lam: list, t: float) -> np.ndarray:
    """b_0..b_n of the family at t, read off curves whose points are unit vectors."""
    eye = np.eye(n + 1)
    return fam.curve(eye, lam=lam, check_range=False).evaluate(t)


def random_box_point(rng: random.Random, ranges) -> list[Fraction]:
    return [Fraction(rng.randint(4 * lo, 4 * hi), 4) for lo, hi in ranges]


# --------------------------------------------------------------------------- the definition


def test_q_bezier_is_the_papers_basis_at_every_degree(q):
    rng = random.Random(30)
    assert q.degrees == (2, 3, 4, 5)
    for n in q.degrees:
        ranges = paper_ranges(n)
        # the file's ranges are the paper's, mirrored after the middle
        got = [q.at_degree(n).several.RANGES[f"lam_{i}"][:2] for i in range(1, n + 1)]
        flipped = [
            (lo, hi)
            for lo, hi in (
                r if i <= (n + 1) // 2 else (-r[1], -r[0]) for i, r in enumerate(ranges, start=1)
            )
        ]
        assert got == [(Fraction(lo), Fraction(hi)) for lo, hi in flipped]
        for _ in range(6):
            lam = random_box_point(rng, flipped)
            t = rng.random()
            want = [
                float(v)
                for v in paper_basis(
                    n,
                    [mpmath.mpf(x.numerator) / x.denominator for x in file_to_paper(n, lam)],
                    mpmath.mpf(t),
                )
            ]
            assert np.allclose(basis_values(q, n, lam, t), want, rtol=0, atol=1e-12)


def test_q_bezier_4_as_printed():
    q4 = lb.load_family(Q4_FILE)
    rng = random.Random(4)
    ranges = paper_ranges(4)
    got = [q4.at_degree(4).several.RANGES[f"lam_{i}"][:2] for i in range(1, 5)]
    assert got == [(Fraction(lo), Fraction(hi)) for lo, hi in ranges]
    for _ in range(8):
        lam = random_box_point(rng, ranges)
        t = rng.random()
        want = [
            float(v)
            for v in paper_basis(
                4, [mpmath.mpf(x.numerator) / x.denominator for x in lam], mpmath.mpf(t)
            )
        ]
        assert np.allclose(basis_values(q4, 4, lam, t), want, rtol=0, atol=1e-12)


def test_derived_symmetry_of_the_printed_basis_is_the_papers():
    doc = json.loads((DATA / "q_bezier_4.derived.json").read_text())["by_degree"]["4"]
    assert doc["symmetry"]["swap"] == ["lam_4", "lam_3", "lam_2", "lam_1"]
    # the same by direct evaluation: b_i(t; l) = b_{n-i}(1 - t; reversed l)
    lam = [mpmath.mpf(x) for x in ("-1.5", "2", "0.25", "-3")]
    t = mpmath.mpf("0.3")
    left = paper_basis(4, lam, t)
    right = paper_basis(4, lam[::-1], 1 - t)[::-1]
    assert all(abs(a - b) < 1e-13 for a, b in zip(left, right, strict=True))


@mpmath.workdps(40)
def test_end_derivatives_against_finite_differences(q):
    """The derived end data (first derivative at t = 0) against the paper's basis,
    differentiated numerically by mpmath."""
    n = 5
    lam = [Fraction(1, 2), Fraction(-3), Fraction(2), Fraction(-1, 4), Fraction(3)]
    pts = [(0, 0), (1, 3), (2, -1), (4, 2), (5, 5), (7, 1)]
    c = q.curve(pts, lam=lam)
    ell = [mpmath.mpf(x.numerator) / x.denominator for x in file_to_paper(n, lam)]
    for order in (1, 2):
        for at in (0, 1):
            want = [
                mpmath.diff(
                    lambda s, d=d: sum(
                        p[d] * b for p, b in zip(pts, paper_basis(n, ell, s), strict=True)
                    ),
                    at,
                    order,
                )
                for d in (0, 1)
            ]
            got = c.derivative(float(at), order)
            assert np.allclose(got, [float(w) for w in want], rtol=1e-12, atol=1e-10)


@mpmath.workdps(30)
def test_energy_against_mpmath_quadrature(q):
    n = 4
    lam = [Fraction(-2), Fraction(3), Fraction(-1), Fraction(1, 2)]
    pts = [(0, 0), (1, 2), (3, 3), (4, 0), (6, 1)]
    c = q.curve(pts, lam=lam)
    ell = [mpmath.mpf(x.numerator) / x.denominator for x in file_to_paper(n, lam)]
    for k in (1, 2, 3):

        def integrand(s, k=k):
            total = 0
            for d in (0, 1):
                total += (
                    mpmath.diff(
                        lambda u, d=d: sum(
                            p[d] * b for p, b in zip(pts, paper_basis(n, ell, u), strict=True)
                        ),
                        s,
                        k,
                    )
                    ** 2
                )
            return total

        want = mpmath.quad(integrand, [0, 0.5, 1])
        assert abs(float(c.energy(k)) - float(want)) <= 1e-9 * max(1.0, float(want))


def test_two_shape_cubic_is_the_paper_cubic_with_the_middle_parameter_zero(q):
    """examples/two_shape_cubic.toml: Han-Ma-Huang's cubic at l_2 = 0 (lam = l_1, mu = l_3;
    in q_bezier.toml's signs lam(3) = -l_3)."""
    two = lb.load_family(examples.path("two_shape_cubic.toml"))
    pts = [(0, 0), (1, 2), (3, 2), (4, 0)]
    for lam, mu in ((Fraction(1, 2), Fraction(-2)), (Fraction(-3), Fraction(1)), (0, 0)):
        a = two.curve(pts, lam=lam, mu=mu)
        b = q.curve(pts, lam=[lam, 0, -mu])
        for t in (0.0, 0.2, 0.5, 0.9, 1.0):
            assert np.allclose(a.evaluate(t), b.evaluate(t), rtol=0, atol=1e-13)
        assert a.energy(2) == b.energy(2)


# --------------------------------------------------------------------------- box decisions


def _coefficient_rank(polys: list, t: sp.Symbol) -> int:
    mat = sp.Matrix(
        [[sp.Poly(p, t).coeff_monomial(t**c) for c in range(len(polys) + 1)] for p in polys]
    )
    return mat.rank()


def test_linear_independence_counterexamples_are_singular():
    """Every reported counterexample, rechecked by the rank of the paper basis' coefficient
    matrix (SymPy, exact), and its closed box is where the paper allows the parameters."""
    t = sp.Symbol("t")
    doc = json.loads((DATA / "q_bezier.derived.json").read_text())
    for key, sub in doc["by_degree"].items():
        n = int(key)
        verdict = sub["singular_parameters"]
        assert verdict["independent"] is False, verdict
        point = verdict["counterexample"]
        lam = [sp.Rational(point[f"lam_{i}"]) for i in range(1, n + 1)]
        ell = file_to_paper(n, lam)
        assert all(lo <= v <= hi for v, (lo, hi) in zip(ell, paper_ranges(n), strict=True))
        polys = [sp.expand(b) for b in paper_basis(n, ell, t)]
        assert _coefficient_rank(polys, t) < n + 1
    # and at a generic point inside, the same basis is independent
    polys = [sp.expand(b) for b in paper_basis(3, [sp.Rational(1, 2), 1, -1], t)]
    assert _coefficient_rank(polys, t) == 4


def test_two_shape_cubic_corner_is_singular():
    doc = json.loads(examples.path("two_shape_cubic.derived.json").read_text())
    assert doc["singular_parameters"]["counterexample"] == {
        "n": 3,
        "where": "every maximal minor = 0",
        "lam": "-3",
        "mu": "-3",
    }
    two = lb.load_family(examples.path("two_shape_cubic.toml"))
    # b1 = b2 there: the curves of two polygons that differ only in P1 - P2 coincide
    a = two.curve([(0, 0), (1, 0), (0, 0), (0, 0)], lam=-3, mu=-3)
    b = two.curve([(0, 0), (0, 0), (1, 0), (0, 0)], lam=-3, mu=-3)
    ts = np.linspace(0, 1, 11)
    assert np.allclose(a.evaluate(ts), b.evaluate(ts), atol=1e-15)


def test_independence_proved_for_the_per_leg_family():
    doc = json.loads((DATA / "per_leg_cubic.derived.json").read_text())
    assert doc["singular_parameters"]["independent"] is True
    # consistent with a sample: full rank of the coefficient matrix at random box points
    fam = lb.load_family(DATA / "per_leg_cubic.toml")
    rng = random.Random(1)
    for _ in range(20):
        s = {f"s{j}": Fraction(rng.randint(-8, 8), 8) for j in range(3)}
        eye = np.eye(4)
        c = fam.curve(eye, params=s)
        ts = np.linspace(0.05, 0.95, 9)
        assert np.linalg.matrix_rank(c.evaluate(ts)) == 4


def _product_definition(tmp_path: Path, lam_range: str) -> Path:
    text = PRODUCT_FILE.read_text().replace('lam = "[-1, 0]"', f'lam = "{lam_range}"')
    text = text.replace('name = "product_shape_cubic"', 'name = "product_wide"')
    path = tmp_path / "product_wide.toml"
    path.write_text(text)
    return path


def test_nonnegativity_not_affine_certified_and_counterexample(tmp_path):
    from derive.emit import document
    from derive.families.definition import read_definition

    doc = json.loads((DATA / "product_shape_cubic.derived.json").read_text())
    assert doc["nonnegative_over_box"]["nonnegative"] is True
    assert "branch and bound" in doc["nonnegative_over_box"]["method"]
    wide = document.derive(read_definition(_product_definition(tmp_path, "[-1, 1]")))
    verdict = wide["nonnegative_over_box"]
    assert verdict["nonnegative"] is False
    ce = verdict["counterexample"]
    # recomputed from the functions as written in the file, exactly
    t, lam, mu = (sp.Rational(ce[x]) for x in ("t", "lam", "mu"))
    c = lam + mu**2
    b3 = t**3 * (1 - c * (1 - t))
    assert ce["i"] == 3 and b3 < 0 and sp.Rational(ce["value"]) == b3
    assert -1 <= lam <= 1 and -1 <= mu <= 1 and 0 <= t <= 1


def _energy_polynomial(pts, k: int):
    """E_k(lam, mu) of product_shape_cubic, from the functions typed here, exactly."""
    t, lam, mu = sp.symbols("t lam mu")
    a, c = lam * mu, lam + mu**2
    basis = [
        (1 - t) ** 3 * (1 - a * t),
        t * (1 - t) ** 2 * (3 + a * (1 - t)),
        t**2 * (1 - t) * (3 + c * t),
        t**3 * (1 - c * (1 - t)),
    ]
    curve = [sum(p[d] * b for p, b in zip(pts, basis, strict=True)) for d in (0, 1)]
    e = sum(sp.integrate(sp.expand(sp.diff(x, t, k) ** 2), (t, 0, 1)) for x in curve)
    return sp.lambdify((lam, mu), e, "numpy"), sp.Lambda((lam, mu), e)


@pytest.mark.parametrize(
    "pts",
    [
        [(0, 0), (1, 2), (3, 2), (4, 0)],
        [(0, 0), (1, 3), (3, -2), (4, 1)],
        [(0, 0), (-2, 5), (6, 5), (4, 0)],
    ],
)
def test_certified_minimum_not_affine(pts):
    fam = lb.load_family(PRODUCT_FILE)
    r = lb.optimal_parameters(pts, 2, family=fam)
    numeric, exact = _energy_polynomial(pts, 2)
    # the energy reported is E_2 at the reported point, exactly
    assert exact(r["lam"], r["mu"]) == r.energy
    assert r.lower_bound <= r.energy <= r.lower_bound + Fraction(1, 10**12) * max(1, r.energy)
    # no point of a fine grid beats the proven lower bound
    lam, mu = np.meshgrid(np.linspace(-1, 0, 201), np.linspace(-1, 1, 401))
    grid = numeric(lam, mu)
    assert grid.min() >= float(r.lower_bound) - 1e-9 * max(1.0, abs(grid.min()))
    assert float(r.energy) <= grid.min() + 1e-9 * max(1.0, abs(grid.min()))


# --------------------------------------------------------------------------- the runtime


def test_indexed_curve_and_optimum(q):
    pts = [(0, 0), (1, 2), (3, 2), (4, 0), (5, 3)]
    r = lb.optimal_parameters(pts, 2, family=q)
    assert isinstance(r["lam"], tuple) and len(r["lam"]) == 4
    c = q.curve(pts, lam=r["lam"])
    assert c.energy(2) == r.energy
    # no box corner or random box point does better
    rng = random.Random(2)
    ranges = [q.at_degree(4).several.RANGES[f"lam_{i}"][:2] for i in range(1, 5)]
    for _ in range(30):
        lam = [Fraction(rng.randint(8 * int(lo), 8 * int(hi)), 8) for lo, hi in ranges]
        assert q.curve(pts, lam=lam).energy(2) >= r.energy


def test_indexed_bad_input(q):
    pts = [(0, 0), (1, 2), (3, 2), (4, 0)]
    with pytest.raises(ValueError, match="lam: degree 3 has 3 parameters"):
        q.curve(pts, lam=[1, 2])
    with pytest.raises(TypeError, match="lam must be a sequence"):
        q.curve(pts, lam=1)
    with pytest.raises(TypeError, match="'mu' is not a parameter"):
        q.curve(pts, mu=[1, 2, 3])
    with pytest.raises(TypeError, match="needs its shape parameters lam"):
        q.curve(pts)
    with pytest.raises(ValueError, match="outside"):
        q.curve(pts, lam=[5, 0, 0])
    with pytest.raises(ValueError, match="degree 8 is not supported for q_bezier"):
        q.curve([(0, 0)] * 9, lam=[0] * 8)


def test_json_round_trip_several_and_indexed(q):
    pts = [(0, 0), (1, 2), (3, 2), (4, 0)]
    two = lb.load_family(examples.path("two_shape_cubic.toml"))
    for fam, curve in (
        (two, two.curve(pts, lam=Fraction(1, 2), mu=-1)),
        (q, q.curve(pts, lam=[1, Fraction(1, 2), -1])),
    ):
        text = to_json(curve)
        back = from_json(text, family=fam)
        assert type(back).parameter_values == type(curve).parameter_values
        assert [tuple(p) for p in back.control_points()] == [
            tuple(p) for p in curve.control_points()
        ]
        assert np.array_equal(
            back.evaluate(np.linspace(0, 1, 7)), curve.evaluate(np.linspace(0, 1, 7))
        )
    doc = json.loads(to_json(q.curve(pts, lam=[1, Fraction(1, 2), -1])))
    assert doc["parameters"] == {"lam": ["1", "1/2", "-1"]}
    doc["parameters"]["lam"] = ["1", "1/2"]
    with pytest.raises(ValueError, match="parameters: .*3 parameters"):
        from_json(json.dumps(doc), family=q)


def test_cli_optimal_lambda_takes_several_and_indexed(capsys):
    from lambda_bezier.cli import main

    assert (
        main(
            [
                "optimal-lambda",
                "--json",
                "--family",
                str(Q_FILE),
                "-k",
                "2",
                "0,0",
                "1,2",
                "3,2",
                "4,0",
            ]
        )
        == 0
    )
    out = json.loads(capsys.readouterr().out)
    r = lb.optimal_parameters([(0, 0), (1, 2), (3, 2), (4, 0)], 2, family=lb.load_family(Q_FILE))
    assert out["parameters"] == {"lam": [str(v) for v in r["lam"]]}
    assert main(["optimal-lambda", "--family", str(PRODUCT_FILE), "0,0", "1,2", "3,2", "4,0"]) == 0
    assert "proven bound" in capsys.readouterr().out


# --------------------------------------------------------------------------- bad definitions

GOOD = {
    "name": "idx",
    "parameters": ["lam(i)"],
    "indices": {"lam": "1..n"},
    "range": {"lam": "[-1, 1]"},
    "degrees": "2..3",
    "degree_offset": 1,
    "basis": "t**i*(1 - t)**(n - i)*(binomial(n, i) + lam(i)*(1 - t) - lam(i + 1)*t)",
}


@pytest.mark.parametrize(
    ("change", "message"),
    [
        ({"parameters": ["lam(i)", "mu(i)"]}, "key parameters: an indexed family has exactly one"),
        ({"parameters": ["t(i)"]}, "'t' is taken"),
        ({"indices": {"lam": "1..m"}}, "key indices.lam: '1..m' is not an index range"),
        ({"indices": {"lam": "2..n-1"}, "degrees": "2"}, "fewer than two indices at n = 2"),
        ({"range": {"mu": "[0, 1]"}}, "key range: an indexed family gives `range`"),
        ({"range": {"lam": "[1, -1]"}}, "the interval of lam\\(1\\) is empty"),
        ({"range": {"lam": "[-binomial(n, i), t]"}}, "key range.lam"),
        ({"basis": "lam(t)*t**i"}, "an index is a formula in i and n"),
        ({"basis": "mu(i)*t**i"}, "unknown name|the only call"),
        ({"basis": "lam(i/2)*t**i + binomial(n, i)*t**i*(1 - t)**(n - i)"}, "is not an integer"),
        ({"seed": ["1", "t"], "recursion": "b(i, n - 1, t)"}, "an indexed family is defined by"),
        ({"degrees": "2..12"}, "degrees satisfy"),
        ({"basis": "binomial(n, i)*t**i*(1 - t)**(n - i) + lam(i)*t"}, "partition of unity"),
    ],
)
def test_bad_indexed_definitions_refused(change, message):
    from derive.emit import document
    from derive.families.definition import DefinitionError, definition_from_table

    table = {**GOOD, **change}
    if "seed" in change:
        table.pop("basis")
    with pytest.raises(DefinitionError, match=message):
        document.derive(definition_from_table(table, "test"))


def test_good_indexed_definition_derives():
    from derive.emit import document
    from derive.families.definition import definition_from_table

    doc = document.derive(definition_from_table(dict(GOOD), "test"))
    assert sorted(doc["by_degree"]) == ["2", "3"]
    assert doc["indexed"]["symbols"]["3"] == ["lam_1", "lam_2", "lam_3"]


def test_evaluate_many_indexed(q):
    pts = np.array([[(0, 0), (1, 2), (3, 2), (4, 0)], [(0, 1), (2, 2), (3, 0), (5, 1)]], float)
    lam = [1, Fraction(1, 2), -1]
    got = lb.evaluate_many(pts, [0.0, 0.3, 1.0], q, params={"lam": lam})
    for row, p in zip(got, pts, strict=True):
        assert np.allclose(row, q.curve(p, lam=lam).evaluate(np.array([0.0, 0.3, 1.0])))
    with pytest.raises(TypeError, match="takes one sequence"):
        lb.evaluate_many(pts, [0.5], q, params={"mu": lam})
    assert np.array_equal(lb.evaluate_many(pts, [0.0, 0.3, 1.0], q, lam=lam), got)


def test_box_bernstein_kernel_directly():
    from lambda_bezier.hazmat import box_bernstein as bb

    def dense(coeffs):  # {(i, j): c} -> object array
        shape = tuple(max(k[a] for k in coeffs) + 1 for a in range(2))
        out = np.empty(shape, dtype=object)
        out.fill(Fraction(0))
        for k, c in coeffs.items():
            out[k] = Fraction(c)
        return out

    one = Fraction(1)
    unit = [(Fraction(0), one), (-one, one)]
    # (x - 1/2)^2 + y^2: >= 0 proved, not > 0 (zero at the centre, exactly)
    p = dense({(2, 0): 1, (1, 0): -1, (0, 0): Fraction(1, 4), (0, 2): 1})
    assert bb.sign_search(p, unit, strict=False, budget=100) == {"holds": True}
    found = bb.sign_search(p, unit, strict=True, budget=100)
    assert found["holds"] is False and found["value"] == 0
    # x^2 + y^2 - 1/2 changes sign: a zero is found; x + 2 has none
    q2 = dense({(2, 0): 1, (0, 2): 1, (0, 0): Fraction(-1, 2)})
    assert bb.zero_search(q2, unit, 100)["zero"] is True
    assert bb.zero_search(dense({(1, 0): 1, (0, 0): 2}), unit, 100) == {"zero": False}
    # min of (x - 1/3)^2 + y^2 + 1 is 1 at (1/3, 0): certified within 1e-12
    r = dense({(2, 0): 1, (1, 0): Fraction(-2, 3), (0, 0): Fraction(10, 9), (0, 2): 1})
    got = bb.minimum(r, unit, Fraction(1, 10**12), 10_000)
    assert got["certified"] and got["lower"] <= 1 <= got["value"] <= 1 + Fraction(1, 10**12)


@st.composite
def indexed_tables(draw):
    """Random indexed definitions whose functions sum to one by construction: the Bernstein
    basis plus c (lam(i) psi_i - lam(i + 1) psi_(i+1)), psi_j = t^j (1 - t)^(n - j + 1)
    (a telescoping sum, lam(0) = lam(n + 1) = 0), sometimes broken."""
    c = draw(st.sampled_from(["1", "-2", "1/3"]))
    first = draw(st.integers(0, 1))
    lo = draw(st.integers(2, 3))
    table = {
        "name": "random_indexed",
        "parameters": ["lam(i)"],
        "indices": {"lam": f"{first}..n"},
        "range": {"lam": draw(st.sampled_from(["[-1, 1]", "[-binomial(n, i), 1]", "(0, i]"]))},
        "degrees": f"{lo}..{lo + draw(st.integers(0, 1))}",
        "degree_offset": 1,
        "basis": f"binomial(n, i)*t**i*(1 - t)**(n - i) + ({c})*(lam(i)*t**i*(1 - t)**(n - i + 1)"
        " - lam(i + 1)*t**(i + 1)*(1 - t)**(n - i))",
    }
    broken = draw(st.sampled_from([None, None, "sum", "index", "range", "name"]))
    if broken == "sum":
        table["basis"] += " + lam(i)*t"
    elif broken == "index":
        table["basis"] += " + 0*lam(t)"
    elif broken == "range":
        table["range"] = {"lam": "[i, -i]"}
    elif broken == "name":
        table["parameters"] = ["b(i)"]
    return table


@settings(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(indexed_tables())
def test_random_indexed_definitions(table):
    """derive either succeeds or names the key (DefinitionError); what it derives evaluates
    in the runtime as the formula does. Never a traceback."""
    from derive.emit import document
    from derive.families.definition import DefinitionError, definition_from_table

    try:
        defn = definition_from_table(table, "random.toml")
        doc = json.loads(json.dumps(document.derive(defn)))
    except DefinitionError as exc:
        assert "[family]" in str(exc)
        return
    from lambda_bezier.family import IndexedFamily

    fam = IndexedFamily(doc, None, "", table, "random.derived.json")
    n = fam.degrees[0]
    names = fam.at_degree(n).parameters
    lam = [Fraction(1, 2)] * len(names)
    t = 0.4
    # the basis formula, evaluated directly at this degree (lam(k) = 0 outside the indices)
    first = int(table["indices"]["lam"][0])
    value = dict(zip(range(first, n + 1), lam, strict=True))
    c = Fraction(sp.Rational(table["basis"].split("+ (")[1].split(")")[0]))

    def b(i):
        psi = lambda j: t**j * (1 - t) ** (n - j + 1)  # noqa: E731
        return comb(n, i) * t**i * (1 - t) ** (n - i) + float(c) * (
            float(value.get(i, 0)) * psi(i) - float(value.get(i + 1, 0)) * psi(i + 1)
        )

    want = [b(i) for i in range(n + 1)]
    got = fam.curve(np.eye(n + 1), lam=lam, check_range=False).evaluate(t)
    np.testing.assert_allclose(got, want, atol=1e-12)


def assert_documents_current(*paths: Path, seeds: tuple[str, ...] = ("0", "4242")) -> None:
    """`derive --check --family` passes for each definition under two hash seeds: the
    committed documents are what derive gives now, byte for byte (sets and dicts never order
    the output). A test may ask for one seed at a time (pytest-xdist then spreads them)."""
    import os
    import subprocess
    import sys

    for seed in seeds:
        for path in paths:
            res = subprocess.run(
                [sys.executable, "-m", "lambda_bezier", "derive", "-q", "--check", "--family",
                 str(path)],
                env={**os.environ, "PYTHONHASHSEED": seed},
                capture_output=True,
                text=True,
                check=False,
            )  # fmt: skip
            assert res.returncode == 0, (seed, path.name, res.stdout[-2000:], res.stderr[-2000:])


@pytest.mark.parametrize("seed", ["0", "4242"])
@pytest.mark.parametrize("name", ["q_bezier_4", "product_shape_cubic"])
def test_derived_documents_are_current_under_any_hash_seed(name, seed):
    """The committed documents of the test families are current under two hash seeds (one
    family and seed per test: each is a derivation in its own process)."""
    assert_documents_current(DATA / f"{name}.toml", seeds=(seed,))
