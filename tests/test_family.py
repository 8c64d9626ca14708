"""A family from its definition: derive --family, load_family, and the whole toolkit for it.

The published family used here is neither of ours: Nouri and Saeidian's enhanced basis
(arXiv:2405.07086, src/lambda_bezier/examples/nouri_saeidian.toml). Its derived artifacts are
checked against independent numerics written from the paper's construction (direct
evaluation, finite differences, quadrature energies, numeric minimisation), and the built-in
families, defined as data in derive/families/*.toml, must come out of the same engine exactly
as derive/families/same_degree.py and derive/families/bernstein_like.py derive them by hand.
"""

from __future__ import annotations

import importlib
import json
import os
import shutil
import subprocess
import sys
from fractions import Fraction
from math import comb
from pathlib import Path

import numpy as np
import pytest
from conftest import ROOT

from lambda_bezier import _derive_runner

pytestmark = pytest.mark.skipif(
    not (ROOT / "derive" / "families" / "engine.py").is_file(), reason="needs the source checkout"
)

NS_FILE = ROOT / "src" / "lambda_bezier" / "examples" / "nouri_saeidian.toml"


def _derive_module(name: str):
    return importlib.import_module(f"{_derive_runner.load_derive(ROOT).__name__}.{name}")


@pytest.fixture(scope="module")
def definition():
    """Reading and validating a definition (derive/families/definition.py)."""
    return _derive_module("families.definition")


@pytest.fixture(scope="module")
def engine():
    """The engine: one definition to its bases, tables and end forms."""
    return _derive_module("families.engine")


@pytest.fixture(scope="module")
def document():
    """The derived family document (derive/emit/document.py)."""
    return _derive_module("emit.document")


@pytest.fixture(scope="module")
def ns_doc(definition, document):
    return document.derive(definition.read_definition(NS_FILE))


def ns_basis(n: int, sigma: float, t: np.ndarray) -> np.ndarray:
    """T_{n,i}(t), i = 0..n, straight from the paper's construction (rows: i)."""
    t = np.asarray(t, dtype=float)
    phi = 3 * t**2 - 2 * t**3
    out = np.array([sigma * comb(n, i) * t**i * (1 - t) ** (n - i) for i in range(n + 1)])
    out[0] += (1 - sigma) * (1 - phi)
    out[n] += (1 - sigma) * phi
    return out


def _fr(x: str) -> float:
    return float(Fraction(x))


# --------------------------------------------------------------------------- the engine


def test_builtin_families_as_data_match_their_hand_derivations(definition, engine, document):
    derive = _derive_runner.load_derive(ROOT)
    modules = {
        name: importlib.import_module(f"{derive.__name__}.{package}.{name}")
        for package, name in (
            ("families", "same_degree"),
            ("families", "bernstein_like"),
            ("formulas", "energy"),
        )
    }
    import reference
    import sympy as sp
    from lambda_bezier._generated import bernstein_like as g_bl
    from lambda_bezier._generated import same_degree as g_sd

    t_sym, lam_sym = sp.Symbol("t"), sp.Symbol("lam")

    for name, generated in (("same_degree", g_sd), ("bernstein_like", g_bl)):
        defn = definition.builtin_definition(name)
        engine.check(defn)
        hand = modules[name]
        doc = document.derive(defn, with_joins=False)
        ts = np.linspace(0, 1, 7)
        for deg in defn.degrees:
            # the engine's polynomials against tests/reference.py's independent evaluation of
            # the papers' definitions (000's eq. (1); 001's seed and recursion)
            for lam_ in (-0.75, 0.5):
                got = np.array(
                    [
                        [float(p.eval({t_sym: x, lam_sym: lam_})) for x in ts]
                        for p in engine.basis_polys(defn, deg)
                    ]
                )
                if name == "same_degree":
                    want = np.array(
                        [
                            [reference.same_degree_definition(deg, i, x, lam_) for x in ts]
                            for i in range(deg + 1)
                        ]
                    )
                else:
                    want = np.array(reference.bernstein_like_recursion(deg, ts, lam_))
                assert np.allclose(got, want, atol=1e-12), (name, deg)
            for kind, table in (("power", generated.POWER), ("bernstein", generated.BERNSTEIN)):
                got = tuple(
                    tuple(tuple(Fraction(v) for v in row) for row in mat)
                    for mat in doc[kind][str(deg)]
                )
                want = tuple(
                    tuple(tuple(Fraction(v) for v in row) for row in m) for m in table[deg]
                )
                assert got == want, (name, kind, deg)
            for k in (1, 2, 3):
                entry = doc["energy"][f"{deg},{k}"]
                forms = modules["energy"].energy_forms(name, deg, k)
                for part in ("ff", "fg", "gg"):
                    scale, u = forms[part]
                    assert Fraction(entry[part][0]) == scale
                    assert tuple(tuple(r) for r in entry[part][1]) == u
        # closed forms in n, interpolated by the engine, equal the ones derived symbolically
        # from 000's three-term form and 001's explicit form
        closed = engine.closed_endpoint_forms(defn)
        form = (
            hand.endpoint_closed_forms(hand.three_term_form())
            if name == "same_degree"
            else hand.endpoint_closed_forms(hand.explicit_factor())
        )
        for key, value in form.items():
            assert sp.expand(closed[key] - value) == 0, (name, key)


def test_published_family_basis_against_its_construction(ns_doc):
    assert ns_doc["family"] == "nouri_saeidian"
    ts = np.linspace(0, 1, 17)
    for n in (3, 6, 12):
        power = ns_doc["power"][str(n)]  # [p][i][e]: coefficient of sigma^p t^e
        for sigma in (0.0, 0.3, 1.0):
            got = np.array(
                [
                    [
                        sum(
                            _fr(power[p][i][e]) * sigma**p * t**e
                            for p in range(len(power))
                            for e in range(n + 1)
                        )
                        for t in ts
                    ]
                    for i in range(n + 1)
                ]
            )
            assert np.allclose(got, ns_basis(n, sigma, ts), atol=1e-12)


def test_published_family_end_derivatives_by_finite_differences(ns_doc):
    """The derived end derivatives (start: d^r/dt^r of T_{n,i} at 0) against one-sided finite
    differences of the paper's construction."""
    h = 1e-5
    for n in (3, 7):
        table = ns_doc["endpoints"][str(n)]
        for sigma in (0.25, 0.9):
            vals = ns_basis(n, sigma, np.array([0.0, h, 2 * h, 3 * h]))
            d1 = (-3 * vals[:, 0] + 4 * vals[:, 1] - vals[:, 2]) / (2 * h)
            d2 = (2 * vals[:, 0] - 5 * vals[:, 1] + 4 * vals[:, 2] - vals[:, 3]) / h**2
            for r, approx, tol in ((1, d1, 1e-6), (2, d2, 1e-3)):
                for i in range(n + 1):
                    coeffs = table.get(f"start,{r},{i}", ["0"])
                    derived = sum(_fr(c) * sigma**p for p, c in enumerate(coeffs))
                    assert abs(derived - approx[i]) < tol * max(1, abs(derived)), (n, sigma, r, i)


def test_published_family_energy_matrices_by_quadrature(ns_doc):
    """E_k(σ) = s_ff DᵀU_ffD − 2σ s_fg DᵀXD + σ² s_gg DᵀYD against Gauss–Legendre quadrature of
    |p⁽ᵏ⁾|² computed from the construction (differentiated numerically as a polynomial)."""
    rng = np.random.default_rng(3)
    x, w = np.polynomial.legendre.leggauss(40)
    ts, ws = (x + 1) / 2, w / 2
    for n in (3, 5):
        pts = rng.normal(size=(n + 1, 2))
        for k in (1, 2, 3):
            entry = ns_doc["energy"][f"{n},{k}"]
            for sigma in (0.2, 0.7):
                # fit p exactly as a polynomial of degree n on Chebyshev nodes, differentiate
                nodes = np.cos(np.pi * (np.arange(n + 1) + 0.5) / (n + 1)) / 2 + 0.5
                curve = ns_basis(n, sigma, nodes).T @ pts
                coef = np.polynomial.polynomial.polyfit(nodes, curve, n)
                deriv = np.polynomial.polynomial.polyder(coef, k)
                vals = np.polynomial.polynomial.polyval(ts, deriv)  # (d, len)
                quad = float(np.sum(ws * np.sum(vals**2, axis=0)))

                ff, fg, gg = (
                    float(Fraction(entry[part][0]))
                    * float(np.einsum("id,ij,jd->", pts, np.array(entry[part][1], float), pts))
                    for part in ("ff", "fg", "gg")
                )
                derived = ff - 2 * sigma * fg + sigma**2 * gg
                assert abs(derived - quad) <= 1e-8 * max(1.0, abs(quad)), (n, k, sigma)


def test_published_family_closed_forms_say_why_they_are_missing(ns_doc):
    """Its second end derivative involves P_n at t = 0 (phi''(0) = 6): no fixed stencil, so
    the end values and tangents are in closed form in n and the second derivatives are not;
    C1/G1 joins get closed-form weights, C2/G2 are derived per degree, and the document says
    so for every pair."""
    assert ns_doc["endpoint_closed_orders"] == 1
    closed = ns_doc["endpoint_closed_forms"]
    assert closed["start,1,0"] == "-lam*n" and closed["start,1,1"] == "lam*n"
    assert not any(key.split(",")[1] in ("2", "3") for key in closed)
    pairs = ns_doc["joins"]
    assert len(pairs) == 7  # after and before each built-in family, and itself
    for entry in pairs.values():
        assert "C2/G2" in entry["reason"] and "per degree" in entry["reason"]
        assert {key.split(",")[0] for key in entry["weights"]} == {"C1", "G1"}
    # C1 of two such curves: P_{1,2} = P_n + (λ1 n / (λ2 m)) (P_n - P_{n-1})
    assert pairs["nouri_saeidian>nouri_saeidian"]["weights"]["C1,1,first,1"] == ("-lam1*n/(lam2*m)")
    assert ns_doc["checked"][1] == "partition of unity, every degree"


ILL_DEFINED = {
    "not a polynomial": (
        {"basis": "binomial(n, i)*t**(i - 2)*(1 - t)**(n - i)"},
        "is not a polynomial",
    ),
    "no partition of unity": (
        {"basis": "binomial(n, i)*t**i*(1 - t)**(n - i)*(1 + lam)"},
        "no partition of unity",
    ),
    "empty range": ({"range": "(1, 1]"}, "is empty"),
    "reversed range": ({"range": "[2, 1]"}, "is empty"),
    "unknown symbol": (
        {"basis": "binomial(n, i)*t**i*(1 - t)**(n - i) + 0*x"},
        "unknown name 'x'",
    ),
    "unknown name": ({"basis": "tan(t)"}, "unknown name 'tan'"),
    # sin, cos, ... are known since issue #30, in an explicit `functions` list only
    "sin in a closed formula": ({"basis": "sin(t)"}, "belong in an explicit `functions` list"),
    "not Bernstein there": (
        {
            "bernstein_at": "0",
            "basis": "lam*binomial(n, i)*t**i*(1 - t)**(n - i)"
            " + (1 - lam)*(binomial(0, i)*(1 - t) + binomial(0, n - i)*t)",
        },
        "not the Bernstein function",
    ),
    "wrong offset": ({"degree_offset": 1}, "basis: at n = 2 the basis functions have degree 2"),
    "too few degrees for a basis": (
        {"basis": None, "degrees": "1", "bernstein_at": None, "functions": ["1", "0"]},
        "functions: at n = 1 the basis functions have degree 0 in t, not n + degree_offset = 1: "
        "2 functions of degree 0 cannot be linearly independent",
    ),
    "built-in name": ({"name": "same_degree"}, "is a built-in family"),
    "bad degrees": ({"degrees": "0..40"}, "degrees must satisfy"),
    "missing key": ({"basis": None}, "defined by `basis`"),
    "unknown key": ({"colour": "red"}, "Additional properties"),
    "parameter taken": ({"parameter": "t"}, "is taken by the formula language"),
    "hostile basis": ({"basis": "__import__('os').system('true')"}, "not allowed"),
    "seed of the wrong size": (
        {"basis": None, "seed": ["1 - t", "t"], "recursion": "(1 - t)*b(i, n - 1, t)"},
        "the seed is the basis of the lowest degree 2: 3 functions",
    ),
    "recursion two degrees down": (
        {
            "basis": None,
            "seed": ["(1 - t)**2", "2*t*(1 - t)", "t**2"],
            "recursion": "(1 - t)*b(i, n - 2, t) + t*b(i - 1, n - 1, t)",
        },
        "a recursion reads the degree below",
    ),
    "basis and recursion": (
        {"seed": ["(1 - t)**2", "2*t*(1 - t)", "t**2"], "recursion": "b(i, n - 1, t)"},
        "one of these",
    ),
    "function in a closed formula": ({"basis": "b(i, n, t)"}, "unknown name 'b'"),
}

GOOD = {
    "name": "tiny",
    "parameter": "lam",
    "range": "[-1, 1]",
    "degrees": "2..6",
    "bernstein_at": "1",
    "degree_offset": 0,
    "basis": "binomial(n, i)*t**i*(1 - t)**(n - i)",
}


@pytest.mark.parametrize("case", list(ILL_DEFINED))
def test_ill_defined_families_get_their_message(definition, engine, case):
    change, needle = ILL_DEFINED[case]
    table = {**GOOD, "basis": "binomial(n, i)*t**i*(1 - t)**(n - i)*(lam + (1 - lam))"}
    table.update(change)
    table = {k: v for k, v in table.items() if v is not None}
    with pytest.raises(definition.DefinitionError) as info:
        defn = definition.definition_from_table(table, "fam.toml")
        engine.check(defn)
    assert needle in str(info.value), str(info.value)


def test_parameter_of_its_own_name(definition, engine):
    table = dict(GOOD, parameter="mu", basis="binomial(n, i)*t**i*(1 - t)**(n - i)*(mu + 1 - mu)")
    defn = definition.definition_from_table(table)
    assert engine.check(defn)[0].startswith("polynomials")
    assert definition.rename_parameter("mu*mu2 + mu", "mu") == "lam*mu2 + lam"


# --------------------------------------------------------------------------- the command


def _derive_family(path: Path, *extra: str, seed: str = "0") -> subprocess.CompletedProcess:
    env = dict(os.environ, PYTHONHASHSEED=seed)
    return subprocess.run(
        [sys.executable, "-m", "lambda_bezier", "derive", "--family", str(path), *extra],
        capture_output=True,
        text=True,
        cwd=ROOT,
        env=env,
        timeout=300,
    )


def test_derive_family_command_is_deterministic_and_checks(tmp_path):
    fam = tmp_path / "tiny.toml"
    fam.write_text(
        "[family]\n" + "".join(f"{k} = {json.dumps(v)}\n" for k, v in GOOD.items()),
        encoding="utf-8",
    )
    first = _derive_family(fam, seed="1")
    assert first.returncode == 0, first.stderr
    out = tmp_path / "tiny.derived.json"
    text = out.read_text(encoding="utf-8")
    assert text.lstrip().startswith('{\n "generated_by": "lambda-bezier derive --family')
    other = tmp_path / "other"
    other.mkdir()
    second = _derive_family(fam, "--out", str(other), seed="12345")
    assert second.returncode == 0, second.stderr
    assert (other / "tiny.derived.json").read_text(encoding="utf-8") == text
    assert _derive_family(fam, "--check").returncode == 0
    # a changed definition: --check names the drift and the command, load_family refuses
    fam.write_text(fam.read_text(encoding="utf-8").replace('"2..6"', '"2..7"'), encoding="utf-8")
    drift = _derive_family(fam, "--check")
    assert drift.returncode == 1 and "+++" in drift.stdout and "derive --family" in drift.stderr
    import lambda_bezier as lb

    with pytest.raises(ValueError, match="another version of the definition.*derive --family"):
        lb.load_family(fam)
    out.unlink()
    with pytest.raises(ValueError, match="has not been derived.*derive --family"):
        lb.load_family(fam)
    bad = tmp_path / "bad.toml"
    bad.write_text('[family]\nname = "bad"\n', encoding="utf-8")
    res = _derive_family(bad)
    assert res.returncode == 2 and "required property" in res.stderr
    assert "Traceback" not in res.stderr


def test_load_family_needs_no_sympy(tmp_path):
    fam = tmp_path / "nouri_saeidian.toml"
    shutil.copy(NS_FILE, fam)
    assert _derive_family(fam).returncode == 0
    code = (
        "import sys, lambda_bezier as lb; "
        f"fam = lb.load_family({str(fam)!r}); "
        "c = fam.curve([(0, 0), (1, 2), (3, 2), (4, 0)], lam=0.5); "
        "print(c.evaluate(0.5).tolist(), 'sympy' in sys.modules)"
    )
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT)
    assert res.returncode == 0, res.stderr
    assert res.stdout.strip().endswith("False")


# --------------------------------------------------------------------------- the runtime


@pytest.fixture(scope="module")
def ns_family():
    import lambda_bezier as lb

    return lb.load_family(NS_FILE)


def test_committed_derivation_is_current():
    """The committed nouri_saeidian.derived.json is what derive gives now (golden file)."""
    res = _derive_family(NS_FILE, "--check")
    assert res.returncode == 0, res.stdout[-3000:] + res.stderr


def test_family_curve_against_the_construction(ns_family):
    rng = np.random.default_rng(11)
    ts = np.linspace(0, 1, 33)
    h = 1e-6
    for n in (3, 5, 9):
        for dim in (2, 3):
            pts = rng.normal(size=(n + 1, dim))
            for sigma in (0.0, 0.35, 1.0):
                c = ns_family.curve(pts, sigma)
                want = ns_basis(n, sigma, ts).T @ pts
                assert np.allclose(c.evaluate(ts), want, atol=1e-12)
                assert np.allclose(c.basis(ts), ns_basis(n, sigma, ts).T, atol=1e-12)
                fd = (ns_basis(n, sigma, ts[1:-1] + h) - ns_basis(n, sigma, ts[1:-1] - h)).T
                assert np.allclose(c.derivative(ts[1:-1]), fd @ pts / (2 * h), atol=1e-6)
                assert np.allclose(c.to_bezier().evaluate(ts), want, atol=1e-12)
    exact = ns_family.curve([(0, 0), (1, 2), (3, 2), (4, 0)], Fraction(1, 2))
    assert exact.to_bezier().control_points()[1] == (Fraction(1, 2), Fraction(1))


def _quad_energy(curve, k: int) -> float:
    x, w = np.polynomial.legendre.leggauss(30)
    vals = curve.derivative((x + 1) / 2, k)
    return float(np.sum(w / 2 * np.sum(vals**2, axis=1)))


def test_family_energy_and_optimal_lambda_by_quadrature(ns_family):
    from scipy.optimize import minimize_scalar

    import lambda_bezier as lb

    rng = np.random.default_rng(5)
    for n in (3, 4, 6):
        pts = rng.normal(size=(n + 1, 2))
        for k in (1, 2, 3):
            c = ns_family.curve(pts, 0.6)
            assert abs(c.energy(k) - _quad_energy(c, k)) <= 1e-9 * max(1, _quad_energy(c, k))
            best = minimize_scalar(
                lambda s, k=k, pts=pts: _quad_energy(ns_family.curve(pts, s, check_range=False), k),
                bounds=(-5, 5),
                method="bounded",
                options={"xatol": 1e-11},
            )
            r = lb.optimal_lambda(pts, k, family=ns_family)
            assert abs(r.unconstrained - best.x) < 1e-6, (n, k)
            assert r.family == "nouri_saeidian" and r.range_text == "[0, 1]"
    # exact in, exact out
    r = lb.optimal_lambda([(0, 0), (1, 2), (3, 2), (4, 0)], 2, family=ns_family)
    assert isinstance(r.lam, Fraction)
    scale, x, y = lb.energy_matrices(3, 1, family=ns_family)
    assert isinstance(scale, Fraction) and len(x) == 4


def test_family_batch_clamped_optimal_lambda_is_a_float_array(ns_family):
    """A batch clamped to a loaded family's range (Fraction ends) stays float64: np.clip with
    the Fraction ends made an object array holding Fractions (found by mypy)."""
    import lambda_bezier as lb

    pts = np.random.default_rng(1).normal(size=(40, 4, 2)) * 5
    free = lb.optimal_lambda(pts, 2, family=ns_family)
    r = lb.optimal_lambda(pts, 2, family=ns_family, clamp=True)
    assert r.lam.dtype == np.float64 and r.energy.dtype == np.float64
    assert np.array_equal(r.lam, np.clip(free.unconstrained, 0.0, 1.0))
    assert ((free.unconstrained < 0) | (free.unconstrained > 1)).any()  # some were clamped


def _check_joint(first, second, cont: str, alpha=1.0, d=0.0) -> None:
    a1, b1 = first.derivative(1.0, 1), first.derivative(1.0, 2)
    a2, b2 = second.derivative(0.0, 1), second.derivative(0.0, 2)
    scale = max(1.0, float(np.abs(a1).max()), float(np.abs(b1).max()))
    assert np.allclose(first.evaluate(1.0), second.evaluate(0.0), atol=1e-9 * scale)
    assert np.allclose(a1, alpha * a2, atol=1e-9 * scale)
    if cont in ("C2", "G2"):
        assert np.allclose(b1, alpha**2 * b2 + d * a2, atol=1e-8 * scale)


@pytest.mark.parametrize("other", ["bezier", "same_degree", "bernstein_like", "self"])
@pytest.mark.parametrize("cont", ["C1", "C2", "G1", "G2"])
def test_joins_into_and_out_of_the_family(ns_family, other, cont):
    import lambda_bezier as lb

    rng = np.random.default_rng(len(other) + len(cont))
    alpha, d = (1.0, 0.0) if cont[0] == "C" else (1.7, 0.4 if cont == "G2" else 0.0)
    target = ns_family if other == "self" else other
    lam_other = {"bezier": None, "same_degree": 0.3, "bernstein_like": -0.4, "self": 0.8}[other]
    for n, m in ((3, 4), (5, 3)):
        first = ns_family.curve(rng.normal(size=(n + 1, 2)), 0.6)
        order = 2 if cont in ("C2", "G2") else 1
        rest = rng.normal(size=(m - order, 2))
        kw = {} if lam_other is None else {"lam": lam_other}
        second = lb.join(first, cont, m, alpha=alpha, d=d, rest=rest, family=target, **kw)
        _check_joint(first, second, cont, alpha, d)
        # and out of a built-in curve into the family
        if other != "self":
            cls = lb.FAMILIES[other]
            pts = rng.normal(size=(n + 1, 2))
            start = cls(pts) if lam_other is None else cls(pts, lam_other)
            back = lb.join(start, cont, m, lam=0.7, alpha=alpha, d=d, rest=rest, family=ns_family)
            _check_joint(start, back, cont, alpha, d)


def test_exact_join_and_composite_with_the_family(ns_family):
    import lambda_bezier as lb

    first = ns_family.curve([(0, 0), (1, 2), (3, 2), (4, 0)], Fraction(1, 2))
    nxt = lb.join(first, "C2", 4, lam=Fraction(3, 4), rest=[(9, 1), (10, 0)])
    assert all(isinstance(v, Fraction) for p in nxt.control_points() for v in p)
    assert nxt.control_points()[0] == (4, 0)
    comp = (
        lb.CompositeCurve([first])
        .join("C2", 4, Fraction(3, 4), rest=[(9, 1), (10, 0)])
        .join("G2", 3, 0.5, alpha=2, d=1, rest=[(14, 3)], family="same_degree")
    )
    assert [sorted(r.achieved) for r in comp.report()] == [
        ["C0", "C1", "C2", "G1", "G2"],
        ["C0", "G1", "G2"],
    ]
    assert [r.kept for r in comp.with_lambda(1, Fraction(1, 5)).report()] == [True, True]
    pts = np.array([[(0, 0), (1, 2), (3, 2), (4, 0)]] * 3, dtype=float)
    many = lb.evaluate_many(pts, [0.0, 0.5, 1.0], ns_family, lam=[0.0, 0.5, 1.0])
    for j, s in enumerate((0.0, 0.5, 1.0)):
        assert np.allclose(many[j], ns_family.curve(pts[0], s).evaluate([0.0, 0.5, 1.0]))


def test_join_into_a_line_segment_names_the_pivot(ns_family):
    """At sigma = 0 the family's curve is the segment P_0 P_m, whose end derivative ignores
    P_1: a C1 join into it cannot be solved, and the message says which point and why."""
    import lambda_bezier as lb

    first = lb.BezierCurve([(0, 0), (1, 1), (2, 0)])
    with pytest.raises(ValueError, match=r"cannot solve C1 for P_\{1,2\}.*nouri_saeidian"):
        lb.join(first, "C1", 3, lam=0.0, rest=[(5, 5), (6, 0)], family=ns_family)


def test_generic_join_engine_equals_the_closed_forms():
    """The per-degree solve the runtime uses for families defined by data gives exactly the
    closed-form vertex formulas derived for the built-in families (exact arithmetic)."""
    import itertools

    import lambda_bezier as lb
    from lambda_bezier import _join_engine, joins

    for f1, f2 in itertools.product(lb.FAMILIES, lb.FAMILIES):
        for cont in ("C1", "C2", "G1", "G2"):
            for n, m in ((3, 3), (4, 7), (6, 4)):
                cls1 = lb.FAMILIES[f1]
                pts = [(i, (i * i) % 5) for i in range(n + 1)]
                first = cls1(pts) if f1 == "bezier" else cls1(pts, Fraction(1, 3))
                lam2 = None if f2 == "bezier" else Fraction(-2, 5)
                spec = joins.Joint(
                    cont,
                    Fraction(3, 2) if cont[0] == "G" else 1,
                    Fraction(-7, 4) if cont == "G2" else 0,
                )
                want = joins.leading_weights(first, spec, f2, m, lam2)
                want = {k: v for k, v in want.items() if v != 0 and k[0] <= spec.order}
                got = _join_engine.weights(
                    first, spec.order, spec.alpha, spec.d, lb.FAMILIES[f2], m, lam2, cont
                )
                assert got == want, (f1, f2, cont, n, m)


def test_singular_parameters_of_a_family_defined_by_data(definition, ns_family):
    """The engine runs the same exact procedure as for the built-in families: a copy of
    same_degree under another name has exactly its singular parameters, and the published
    family is singular at sigma = 0 (the inner functions vanish: the curve is the segment)."""
    import dataclasses

    import lambda_bezier as lb

    copy = dataclasses.replace(definition.builtin_definition("same_degree"), name="sd_copy")
    table = _derive_module("formulas.family").singular_artifacts(copy)
    for n in (3, 5, 6, 9):
        want = lb.singular_parameters("same_degree", n)
        got = table[str(n)]
        assert len(got) == len(want)
        for g, w in zip(got, want, strict=True):
            if isinstance(g, str):
                assert Fraction(g) == w
            else:
                assert (Fraction(g[0][0]), Fraction(g[0][1])) == (w.lo, w.hi)
    assert lb.singular_parameters(ns_family, 4) == (Fraction(0),)
    bez = lb.BezierCurve([(0, 0), (1, 2), (3, 2), (4, 0)])
    c = ns_family.from_bezier(bez, Fraction(1, 2))
    assert c.to_bezier().control_points() == bez.control_points()
    with pytest.raises(ValueError, match="^sigma: .*linearly dependent at sigma = 0"):
        ns_family.from_bezier(bez, 0)


# A family whose end tangent involves three control points (P_0, P_1, P_2): the case
# of a first end derivative with three points. Bernstein plus a shape term that sums to zero
# over i and vanishes at both ends.
WIDE_STENCIL = """
[family]
name = "wide_stencil"
title = "Bernstein plus a shape term whose end tangent involves P_2"
parameter = "mu"
range = "[-1/2, 1/2]"
degrees = "4..12"
bernstein_at = "0"
degree_offset = 0
basis = "{basis}"
""".format(
    basis="binomial(n, i)*(1 - t)**(n - i)*t**i"
    " + mu*t*(1 - t)**(n - 1)*(binomial(0, i - 2) - binomial(0, i - 1))"
    " + mu*t**(n - 1)*(1 - t)*(binomial(0, n - i - 2) - binomial(0, n - i - 1))"
)


def _weight_at(text: str, values: dict) -> Fraction:
    import sympy as sp  # the test's own reading of the derived document (our output)

    value = sp.sympify(text).subs({sp.Symbol(k): sp.Rational(str(v)) for k, v in values.items()})
    return Fraction(int(value.p), int(value.q))


def test_three_point_stencil_joins_in_closed_form(tmp_path, definition, document):
    """Closed-form C1/C2/G1/G2 weights for a family whose first end derivative involves three
    points (so P_{2,2} is given in C1/G1 and solved together with P_{1,2} in C2/G2), equal to
    the runtime's per-degree solve at exact values, into and out of the built-in families."""
    import lambda_bezier as lb
    from lambda_bezier import _join_engine

    path = tmp_path / "wide.toml"
    path.write_text(WIDE_STENCIL)
    defn = definition.read_definition(path)
    (tmp_path / "wide_stencil.derived.json").write_text(document.render(defn))
    doc = json.loads((tmp_path / "wide_stencil.derived.json").read_text())
    # orders 0..2 in closed form; the third derivative at 0 picks up the far term at n = 4 only
    assert doc["endpoint_closed_orders"] == 2
    assert doc["endpoint_closed_forms"]["start,1,2"] == "lam"  # p'(0) involves P_2
    fam = lb.load_family(path)
    classes = {**lb.FAMILIES, "wide_stencil": fam.curve_class}
    lams = {"bezier": None, "same_degree": Fraction(1, 3), "bernstein_like": Fraction(-2, 5)}
    lams["wide_stencil"] = Fraction(1, 4)
    for other in ("bezier", "same_degree", "bernstein_like", "wide_stencil"):
        for first, second in (("wide_stencil", other), (other, "wide_stencil")):
            entry = doc["joins"][f"{first}>{second}"]
            assert "reason" not in entry, entry
            for cont in ("C1", "C2", "G1", "G2"):
                n, m = 5, 6
                alpha = Fraction(3, 2) if cont[0] == "G" else Fraction(1)
                d = Fraction(-7, 4) if cont == "G2" else Fraction(0)
                pts = [(i, (i * i) % 5) for i in range(n + 1)]
                cls1 = classes[first]
                curve = cls1(pts) if lams[first] is None else cls1(pts, lams[first])
                order = 2 if cont[1] == "2" else 1
                want = _join_engine.weights(
                    curve, order, alpha, d, classes[second], m, lams[second], cont
                )
                values = {"n": n, "m": m, "alpha": alpha, "d": d}
                values.update({"lam1": lams[first] or 0, "lam2": lams[second] or 0})
                got = {}
                for key, text in entry["weights"].items():
                    c, row, src, j = key.split(",")
                    if c == cont:
                        got[(int(row), src, int(j))] = _weight_at(text, values)
                assert got == {k: v for k, v in want.items() if v != 0}, (first, second, cont)
