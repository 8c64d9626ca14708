"""Surface claims about families in several parameters and atom families (issue #31):
`lambda-bezier verify FAMILY.toml RECORDS.toml` decides the surface kinds for a polynomial
two-parameter family (two_end_bezier), an indexed one (lit_per_leg, lam(i)), a trigonometric
one (han_trig_cubic, entries in Q[pi]) and hyperbolic ones (hyp_two_shape_cubic,
hyp_square_quadratic, entries in Q[e, 1/e]).

Each records file holds true claims and deliberate misprints. The true values were computed
with SymPy on the families' functions directly; here a few of them are recomputed once more
by mpmath quadrature and evaluation of the functions (not through derive), and verify must find
exactly the misprints, with errata that verify.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

mpmath = pytest.importorskip("mpmath")
records_mod = pytest.importorskip("derive.verify.records")
report_mod = pytest.importorskip("derive.verify.report")

DATA = Path(__file__).parent / "data" / "families"
ROOT = Path(__file__).parent.parent
FAMILIES = (
    "two_end_bezier",
    "lit_per_leg",
    "han_trig_cubic",
    "hyp_two_shape_cubic",
    "hyp_square_quadratic",
)
MISPRINTS = {
    "teb.s.corners_misprint",
    "teb.s.thin_plate_misprint",
    "htc.s.boundary_misprint",
    "htc.s.thin_plate_misprint",
    "hts.s.boundary_misprint",
    "hts.s.corners_misprint",
    "hsq.s.thin_plate_misprint",
    "plg.s.values_misprint",
    "teb.s.g1_misprint",
}


def _paths(family: str) -> list[Path]:
    return [DATA / f"{family}.toml", DATA / f"{family}.surfaces.records.toml"]


@pytest.fixture(scope="module")
def cli_report() -> dict:
    """One `lambda-bezier verify --format json` run over the four families and their records."""
    argv = [str(p) for family in FAMILIES for p in _paths(family)]
    res = subprocess.run(
        [sys.executable, "-m", "lambda_bezier", "verify", "--format", "json", *argv],
        capture_output=True,
        text=True,
        cwd=ROOT,
        timeout=300,
    )
    assert res.returncode == 0, res.stderr[-2000:]
    return json.loads(res.stdout)


@pytest.fixture(scope="module")
def records() -> dict[str, dict]:
    out = {}
    for family in FAMILIES:
        out |= {r["id"]: r for r in records_mod.load_paths(_paths(family))}
    return out


# ---------------------------------------------------------------------- verify's verdicts
def test_verify_finds_exactly_the_misprints(cli_report):
    verdicts = {r["id"]: r["verdict"] for r in cli_report["records"]}
    assert {rid for rid, v in verdicts.items() if v == "mismatch"} == MISPRINTS
    assert {rid for rid, v in verdicts.items() if v == "match"} == set(verdicts) - MISPRINTS
    assert len(verdicts) == 30
    for r in cli_report["records"]:
        if r["id"] in MISPRINTS:
            assert r["erratum"]["verdict"] == "match", r["id"]
    assert cli_report["summary"]["error"] == 0


def test_each_kind_is_decided_exactly_for_each_family_kind(cli_report):
    """Every kind ran for a polynomial, a trigonometric and a hyperbolic family, exactly."""
    by_id = {r["id"]: r for r in cli_report["records"]}
    assert "exact" in by_id["teb.s.membrane"]["checked"][0]
    assert "direct integration" in by_id["teb.s.membrane"]["checked"][0]
    assert "Q[pi, 1/pi]" in by_id["htc.s.membrane"]["checked"][0]
    assert "every parameter" in by_id["htc.s.corners"]["checked"][0]
    assert "Q[e, 1/e]" in by_id["hsq.s.membrane"]["checked"][0]
    assert "Q[e, 1/e]" in by_id["hts.s.values"]["checked"][0]
    kinds = {r["claim"].split(".")[1] for r in cli_report["records"]}
    assert kinds == {
        "surface_basis",
        "surface_boundary",
        "surface_corners",
        "surface_energy_matrix",
        "surface_continuity",
    }
    assert "re-proved exactly" in by_id["teb.s.c2"]["checked"][0]
    assert "linearity in the columns" in by_id["htc.s.g1"]["checked"][0]


def test_the_misprints_are_named(cli_report):
    diffs = {r["id"]: r["diff"] for r in cli_report["records"]}
    assert diffs["teb.s.thin_plate_misprint"] == [
        "Q[0][1]: printed 55/28, derived -55/28",
        "Q[1][0]: printed 55/28, derived -55/28",
    ]
    assert len(diffs["htc.s.thin_plate_misprint"]) == 1
    assert diffs["htc.s.thin_plate_misprint"][0].startswith("Q[0][0]: printed -729079*pi/960")
    assert diffs["hts.s.corners_misprint"][0].startswith(
        "S(1, 0): printed P_30, derived weights at [(0, 0), (1, 0), (2, 0), (3, 0)]"
    )


# ---------------------------------------------------------------------- a changed term flips
@pytest.mark.parametrize(
    ("rid", "row", "col", "extra"),
    [
        ("teb.s.membrane", 4, 7, " + lam_u*mu_v*(lam_v + 1)/1000"),  # zero only where it vanishes
        ("htc.s.membrane", 5, 5, " + pi**2/10**9"),
        ("hsq.s.membrane", 2, 6, " + e**(-9)"),
    ],
)
def test_a_changed_term_flips_an_energy_record(records, rid, row, col, extra):
    rec = dict(records[rid])
    assert report_mod.check_record(rec).verdict == "match"
    rec["gram"] = [list(r) for r in rec["gram"]]
    rec["gram"][row][col] += extra
    res = report_mod.check_record(rec)
    assert res.verdict == "mismatch"
    assert [d.split(":")[0] for d in res.outcome.diffs] == [f"Q[{row}][{col}]"]


def test_a_changed_basis_value_flips(records):
    rec = dict(records["hts.s.values"])
    rec["values"] = [list(r) for r in rec["values"]]
    rec["values"][3][3] += " + e**(-8)"
    res = report_mod.check_record(rec)
    assert res.verdict == "mismatch"
    assert res.outcome.diffs[0].startswith("B_33(1, 1): printed")


# ---------------------------------------------------------------------- independent values
def _han_functions(lam, mu):
    """han_trig_cubic.toml's functions and their t-derivatives (SymPy diff of the formulas as
    printed there, not derive's basis), as mpmath callables."""
    sp = pytest.importorskip("sympy")
    t = sp.Symbol("t")
    s, c = sp.sin(t), sp.cos(t)
    funcs = [
        (1 - s) ** 2 * (1 - lam * s),
        s * (1 - s) * (2 + lam - lam * s),
        c * (1 - c) * (2 + mu - mu * c),
        (1 - c) ** 2 * (1 - mu * c),
    ]
    return [(sp.lambdify(t, f, "mpmath"), sp.lambdify(t, sp.diff(f, t), "mpmath")) for f in funcs]


def _value(text: str, constant: str) -> mpmath.mpf:
    """A printed number in pi or e, read by the records grammar (no eval), at mpmath precision."""
    from derive.grammar import parse_formula

    e = parse_formula(text, {"e": __import__("sympy").Symbol("e")}, {}, elementary=True)
    sp = __import__("sympy")
    value = sp.pi if constant == "pi" else sp.E
    return mpmath.mpf(sp.N(e.xreplace({sp.Symbol("e"): sp.E, sp.pi: value}), 30))


def test_trig_membrane_entries_are_the_double_integrals(records):
    """Two entries of htc.s.membrane as ∫∫ over [0, pi/2]^2 of ∇B_r · ∇B_c by mpmath
    (Gauss-Legendre in two dimensions, not separated into curve integrals)."""
    sp = pytest.importorskip("sympy")
    rec = records["htc.s.membrane"]
    along_u = _han_functions(sp.Integer(0), sp.Integer(1))
    along_v = _han_functions(sp.Integer(-1), sp.Rational(1, 2))
    mpmath.mp.dps = 20
    try:
        for r, c in ((0, 0), (5, 10)):
            (i, j), (k, l_) = divmod(r, 4), divmod(c, 4)

            def f(u, v, i=i, j=j, k=k, l_=l_):
                (bi, di), (bj, dj) = along_u[i], along_v[j]
                (bk, dk), (bl, dl) = along_u[k], along_v[l_]
                return di(u) * bj(v) * dk(u) * bl(v) + bi(u) * dj(v) * bk(u) * dl(v)

            got = mpmath.quad(f, [0, mpmath.pi / 2], [0, mpmath.pi / 2], method="gauss-legendre")
            assert abs(got - _value(rec["gram"][r][c], "pi")) < mpmath.mpf(10) ** -15, (r, c)
    finally:
        mpmath.mp.dps = 15


def test_hyperbolic_values_are_the_functions(records):
    """hts.s.values: b_i(1; 0, -1) b_j(1; 1, -3) evaluated by mpmath from the functions."""
    rec = records["hts.s.values"]
    mpmath.mp.dps = 30

    def b(i, t, lam, mu):
        x = 1 - mpmath.exp(-t)
        return [
            (1 - lam * x) * mpmath.exp(-3 * t),
            x * mpmath.exp(-2 * t) * (3 + lam * mpmath.exp(-t)),
            x**2 * mpmath.exp(-t) * (3 + mu * x),
            (1 - mu + mu * x) * x**3,
        ][i]

    try:
        for i in range(4):
            for j in range(4):
                want = b(i, 1, 0, -1) * b(j, 1, 1, -3)
                got = _value(rec["values"][i][j], "e")
                assert abs(got - want) < mpmath.mpf(10) ** -25, (i, j)
    finally:
        mpmath.mp.dps = 15


# ---------------------------------------------------------------------- refusals
def _one_record(tmp_path: Path, family_file: str, body: str) -> list[Path]:
    family = family_file.removesuffix(".toml")
    rec = tmp_path / "r.toml"
    rec.write_text(
        f'schema_version = 2\nsource = "t"\nfamily = "{family}"\n\n[[record]]\nid = "x"\n'
        f'location = "x"\n{body}\n'
    )
    return [DATA / family_file, rec]


def test_the_true_c2_weights_solve_the_end_conditions(records):
    """teb.s.c2 from two_end_bezier.toml's formula at n = 3: patch 2's first three rows solved
    from p1^(r)(1) = p2^(r)(0), r = 0, 1, 2, with SymPy (not derive's join solve)."""
    sp = pytest.importorskip("sympy")
    t, lam1, mu1, lam2, mu2 = sp.symbols("t lam1 mu1 lam2 mu2")

    def b(i, lam, mu):
        def one(k):
            return int(k == 0)

        return (
            t**i
            * (1 - t) ** (3 - i)
            * (
                sp.binomial(3, i)
                + (lam * one(i - 1) + mu * one(3 - i)) * (1 - t)
                - (lam * one(i) + mu * one(3 - i - 1)) * t
            )
        )

    p, q = sp.symbols("p0:4"), sp.symbols("q0:4")
    s1 = sum(b(i, lam1, mu1) * p[i] for i in range(4))
    s2 = sum(b(i, lam2, mu2) * q[i] for i in range(4))
    eqs = [sp.diff(s1, t, r).subs(t, 1) - sp.diff(s2, t, r).subs(t, 0) for r in range(3)]
    (sol,) = sp.solve(eqs, q[:3], dict=True)
    names = {"lam1": lam1, "mu1": mu1, "lam2": lam2, "mu2": mu2}
    printed = {
        (w["row"], w["k"]): sp.sympify(w["weight"], locals=names)
        for w in records["teb.s.c2"]["weights"]
    }
    for row in range(3):
        expr = sp.expand(sol[q[row]])
        for k in range(4):
            want = sp.cancel(expr.coeff(p[3 - k]))
            assert sp.cancel(printed.get((row, k), 0) - want) == 0, (row, k)


def test_indexed_values_are_the_formula(records):
    """plg.s.values from lit_per_leg.toml's basis formula, lam(k) = 0 outside 0..n-1 (SymPy
    on the formula as printed there, not derive's basis)."""
    sp = pytest.importorskip("sympy")
    rec = records["plg.s.values"]

    def basis(n, lams, x):
        lam = [sp.Rational(v) for v in lams]
        at = lambda k: lam[k] if 0 <= k <= n - 1 else 0  # noqa: E731
        return [
            sp.binomial(n, i) * x**i * (1 - x) ** (n - i)
            + at(i) * x ** (i + 1) * (1 - x) ** (n - i)
            - at(i - 1) * x**i * (1 - x) ** (n - i + 1)
            for i in range(n + 1)
        ]

    bu = basis(2, ["1/2", "-1"], sp.Rational(1, 3))
    bv = basis(3, ["0", "1", "1/4"], sp.Rational(1, 2))
    assert [[str(a * c) for c in bv] for a in bu] == rec["values"]


def test_an_indexed_parameter_outside_the_degree_is_named(records):
    rec = dict(records["plg.s.values"])
    rec["parameters_u"] = {**rec["parameters_u"], "lam(2)": "1"}  # degree 2 has lam(0), lam(1)
    res = report_mod.check_record(rec)
    assert "key parameters_u.lam(2): not a parameter at degree 2" in res.error


@pytest.mark.parametrize(
    ("change", "message"),
    [
        ({"gram": "__import__('os')"}, "key gram[0][0]"),
        ({"parameters_u": {"nu": "1"}}, "key parameters_u.nu: not a parameter"),
        ({"parameters_u": {"lam": "1", "mu": "pi"}}, "key parameters_u.mu"),
        ({"degrees": [9, 2]}, "key degrees: 9 is outside"),
    ],
)
def test_bad_energy_records_name_the_key(tmp_path, change, message):
    """A formula is read by the records grammar, never evaluated; a wrong key is named."""
    zeros = "[" + ", ".join(["[" + ", ".join(['"0"'] * 9) + "]"] * 9) + "]"
    paths = _one_record(
        tmp_path,
        "two_end_bezier.toml",
        f'claim = "surface_energy_matrix"\ndegrees = [2, 2]\nenergy = "membrane"\ngram = {zeros}',
    )
    (rec,) = records_mod.load_paths(paths)
    for key, value in change.items():
        if key == "gram":
            rec["gram"] = [list(row) for row in rec["gram"]]
            rec["gram"][0][0] = value
        else:
            rec[key] = value
    res = report_mod.check_record(rec)
    assert res.verdict == "error" or res.error is not None, res
    assert message in res.error, res.error
