"""A family from its definition: derive --family, load_family, and the whole toolkit for it.

The published family used here is neither of ours: Nouri and Saeidian's enhanced basis
(arXiv:2405.07086, tests/data/families/nouri_saeidian.toml). Its derived artifacts are
checked against independent numerics written from the paper's construction (direct
evaluation, finite differences, quadrature energies, numeric minimisation), and the built-in
families, defined as data in derive/families/*.toml, must come out of the same engine exactly
as derive/same_degree.py and derive/bernstein_like.py derive them by hand.
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
    not (ROOT / "derive" / "family_engine.py").is_file(), reason="needs the source checkout"
)

NS_FILE = ROOT / "tests" / "data" / "families" / "nouri_saeidian.toml"


@pytest.fixture(scope="module")
def engine():
    derive = _derive_runner.load_derive(ROOT)
    return importlib.import_module(f"{derive.__name__}.family_engine")


@pytest.fixture(scope="module")
def ns_doc(engine):
    return engine.derive(engine.read_definition(NS_FILE))


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


def test_builtin_families_as_data_match_their_hand_derivations(engine):
    derive = _derive_runner.load_derive(ROOT)
    modules = {
        name: importlib.import_module(f"{derive.__name__}.{name}")
        for name in ("same_degree", "bernstein_like", "energy")
    }
    from lambda_bezier._generated import bernstein_like as g_bl
    from lambda_bezier._generated import same_degree as g_sd

    for name, generated in (("same_degree", g_sd), ("bernstein_like", g_bl)):
        defn = engine.builtin_definition(name)
        engine.check(defn)
        hand = modules[name]
        doc = engine.derive(defn, with_joins=False)
        for deg in defn.degrees:
            assert engine.basis_polys(defn, deg) == list(hand.basis_polys(deg)), (name, deg)
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
        # closed forms in n, interpolated by the engine, equal the hand-derived ones
        closed = engine.closed_endpoint_forms(defn)
        form = (
            hand.endpoint_closed_forms(hand.three_term_form())
            if name == "same_degree"
            else hand.endpoint_closed_forms(hand.explicit_factor())
        )
        import sympy as sp

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
    """Its second end derivative involves P_n at t = 0 (phi''(0) = 6): no fixed stencil, so no
    closed form in n; the joins are then derived per degree, and the document says so."""
    assert ns_doc["endpoint_closed_forms"] is None
    assert "per degree" in ns_doc["joins"]["reason"]
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
    "unknown name": ({"basis": "sin(t)"}, "unknown name 'sin'"),
    "not Bernstein there": (
        {
            "bernstein_at": "0",
            "basis": "lam*binomial(n, i)*t**i*(1 - t)**(n - i)"
            " + (1 - lam)*(binomial(0, i)*(1 - t) + binomial(0, n - i)*t)",
        },
        "not the Bernstein function",
    ),
    "wrong offset": ({"degree_offset": 1}, "not n + degree_offset"),
    "built-in name": ({"name": "same_degree"}, "is a built-in family"),
    "bad degrees": ({"degrees": "0..40"}, "degrees must satisfy"),
    "missing key": ({"basis": None}, "'basis' is a required property"),
    "unknown key": ({"colour": "red"}, "Additional properties"),
    "parameter taken": ({"parameter": "t"}, "is taken by the formula language"),
    "hostile basis": ({"basis": "__import__('os').system('true')"}, "not allowed"),
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
def test_ill_defined_families_get_their_message(engine, case):
    change, needle = ILL_DEFINED[case]
    table = {**GOOD, "basis": "binomial(n, i)*t**i*(1 - t)**(n - i)*(lam + (1 - lam))"}
    table.update(change)
    table = {k: v for k, v in table.items() if v is not None}
    with pytest.raises(engine.DefinitionError) as info:
        defn = engine.definition_from_table(table, "fam.toml")
        engine.check(defn)
    assert needle in str(info.value), str(info.value)


def test_parameter_of_its_own_name(engine):
    table = dict(GOOD, parameter="mu", basis="binomial(n, i)*t**i*(1 - t)**(n - i)*(mu + 1 - mu)")
    defn = engine.definition_from_table(table)
    assert engine.check(defn)[0].startswith("polynomials")
    assert engine.rename_parameter("mu*mu2 + mu", "mu") == "lam*mu2 + lam"


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
