"""Surface claims about a family a records file defines (issue #31): verify checks the surface
kinds for a one-parameter family of the user's own as for a built-in one.

tests/data/families/end_shape_bezier.records.toml states ten claims about end_shape_bezier.toml;
three are deliberate misprints. The true ones are recomputed here with SymPy from the family's
formula directly (the tensor-product basis expanded and integrated monomial by monomial, the
join rows solved from the end derivatives), not through derive, and verify must find exactly
the misprints.
"""

from __future__ import annotations

from fractions import Fraction
from math import gcd, lcm
from pathlib import Path

import pytest

sp = pytest.importorskip("sympy")
records_mod = pytest.importorskip("derive.verify.records")
report_mod = pytest.importorskip("derive.verify.report")

DATA = Path(__file__).parent / "data" / "families"
FILES = [DATA / "end_shape_bezier.toml", DATA / "end_shape_bezier.records.toml"]
MISPRINTS = {"es.corners_misprint", "es.g1_misprint", "es.membrane_misprint"}
DEGREES = range(3, 6)  # the family's own

u, v, lu, lv = sp.symbols("u v lam_u lam_v")
n, m, lam1, lam2, alpha = sp.symbols("n m lam1 lam2 alpha")


@pytest.fixture(scope="module")
def records() -> dict[str, dict]:
    return {r["id"]: r for r in records_mod.load_paths(FILES)}


@pytest.fixture(scope="module")
def results(records) -> dict[str, object]:
    return {rid: report_mod.check_record(rec) for rid, rec in records.items()}


# ---------------------------------------------------------------------- the reference
def _b(i: int, deg: int, x, lam):
    """The family's formula written out (end_shape_bezier.toml), [k = 0] as 1 or 0."""

    def one(k: int) -> int:
        return int(k == 0)

    return (
        x**i
        * (1 - x) ** (deg - i)
        * (
            sp.binomial(deg, i)
            + lam * (one(i - 1) - one(deg - i)) * (1 - x)
            - lam * (one(i) - one(deg - i - 1)) * x
        )
    )


def _tensor(mu: int, nu: int) -> list:
    return [
        sp.Poly(sp.expand(_b(i, mu, u, lu) * _b(j, nu, v, lv)), u, v, lu, lv)
        for i in range(mu + 1)
        for j in range(nu + 1)
    ]


def _energy_coefficient(mu: int, nu: int, energy: str, a: int, b: int) -> list[list[Fraction]]:
    """The full symmetric coefficient of λ_u^a λ_v^b: ∫∫ over the unit square, monomial by
    monomial (∫∫ u^p v^q = 1/((p+1)(q+1)))."""
    terms = {"membrane": ((1, 0, 1), (0, 1, 1)), "thin_plate": ((2, 0, 1), (1, 1, 2), (0, 2, 1))}
    basis = _tensor(mu, nu)
    size = len(basis)
    out = [[Fraction(0)] * size for _ in range(size)]
    for ku, kv, w in terms[energy]:
        parts = [sp.Poly(sp.diff(p.as_expr(), u, ku, v, kv), u, v, lu, lv) for p in basis]
        for r in range(size):
            for c in range(size):
                total = Fraction(0)
                for (pu, pv, pa, pb), coef in (parts[r] * parts[c]).terms():
                    if (pa, pb) == (a, b):
                        total += Fraction(str(coef)) / ((pu + 1) * (pv + 1))
                out[r][c] += w * total
    return out


def _integer_form(full: list[list[Fraction]]) -> tuple[Fraction, list[list[int]]]:
    size = len(full)
    upper = [
        [full[r][c] * (1 if r == c else 2) if c >= r else Fraction(0) for c in range(size)]
        for r in range(size)
    ]
    den = lcm(*(x.denominator for row in upper for x in row))
    ints = [[int(x * den) for x in row] for row in upper]
    g = 0
    for row in ints:
        for x in row:
            g = gcd(g, x)
    lead = next((ints[r][r] for r in range(size) if ints[r][r]), 1)
    g = -g if lead < 0 else g
    return Fraction(g, den), [[x // g for x in row] for row in ints]


def _join_rows(continuity: str, deg1: int, deg2: int) -> dict:
    """{(row, "first", k): weight} at the degrees deg1, deg2, from the end derivatives."""
    t = sp.Symbol("t")
    order = 2 if continuity == "C2" else 1
    p = sp.symbols(f"p0:{deg1 + 1}")
    q = sp.symbols(f"q0:{deg2 + 1}")
    s1 = sum(_b(i, deg1, t, lam1) * p[i] for i in range(deg1 + 1))
    s2 = sum(_b(i, deg2, t, lam2) * q[i] for i in range(deg2 + 1))
    scale = alpha if continuity == "G1" else 1
    eqs = [
        sp.diff(s1, t, r).subs(t, 1) - scale**r * sp.diff(s2, t, r).subs(t, 0)
        for r in range(order + 1)
    ]
    sol = sp.solve(eqs, q[: order + 1], dict=True)[0]
    out = {}
    for row in range(order + 1):
        expr = sp.expand(sol[q[row]])
        for k in range(deg1 + 1):
            w = sp.cancel(expr.coeff(p[deg1 - k]))
            if w != 0:
                out[(row, "first", k)] = w
    return out


def _printed_weights(rec: dict, deg1: int, deg2: int) -> dict:
    names = {"n": n, "m": m, "lam1": lam1, "lam2": lam2, "alpha": alpha}
    return {
        (w["row"], w["source"], w["k"]): sp.sympify(w["weight"], locals=names).subs(
            {n: deg1, m: deg2}
        )
        for w in rec["weights"]
    }


# ---------------------------------------------------------------------- the true records
def test_the_true_basis_values_are_the_formulas(records):
    rec = records["es.values"]
    mu, nu = rec["degrees"]
    at = {u: sp.Rational(rec["uv"][0]), v: sp.Rational(rec["uv"][1])}
    at |= {lu: sp.Rational(rec["lam_u"]), lv: sp.Rational(rec["lam_v"])}
    basis = _tensor(mu, nu)
    got = [
        [str(basis[i * (nu + 1) + j].as_expr().subs(at)) for j in range(nu + 1)]
        for i in range(mu + 1)
    ]
    assert got == rec["values"]


def test_the_true_energy_matrix_is_the_integral(records):
    rec = records["es.membrane"]
    scale, upper = _integer_form(_energy_coefficient(*rec["degrees"], rec["energy"], *rec["term"]))
    assert (str(scale), upper) == (rec["scale"], rec["matrix"])
    bad = records["es.membrane_misprint"]
    assert (bad["scale"], bad["matrix"]) != (rec["scale"], rec["matrix"])


@pytest.mark.parametrize("rid", ["es.c1", "es.c2"])
def test_the_true_join_weights_solve_the_end_conditions(records, rid):
    rec = records[rid]
    for deg1 in DEGREES:
        for deg2 in DEGREES:
            want = _join_rows(rec["continuity"], deg1, deg2)
            got = _printed_weights(rec, deg1, deg2)
            assert set(got) == set(want), (deg1, deg2)
            for key, w in want.items():
                assert sp.cancel(got[key] - w) == 0, (deg1, deg2, key)


def test_the_g1_misprint_is_false_and_its_erratum_true(records):
    rec = records["es.g1_misprint"]
    want = _join_rows("G1", 3, 4)
    wrong = _printed_weights(rec, 3, 4)
    assert any(sp.cancel(wrong[k] - w) != 0 for k, w in want.items())
    fixed = _printed_weights({"weights": rec["erratum"]["weights"]}, 3, 4)
    assert all(sp.cancel(fixed[k] - w) == 0 for k, w in want.items())


# ---------------------------------------------------------------------- verify's verdicts
def test_verify_finds_exactly_the_misprints(results):
    verdicts = {rid: res.verdict for rid, res in results.items()}
    assert all(res.error is None for res in results.values()), {
        rid: res.error for rid, res in results.items() if res.error
    }
    assert {rid for rid, v in verdicts.items() if v == "mismatch"} == MISPRINTS
    assert {rid for rid, v in verdicts.items() if v == "match"} == set(verdicts) - MISPRINTS
    assert len(verdicts) - len(MISPRINTS) >= 3


def test_the_misprints_are_named_and_their_errata_verify(results):
    assert (
        "S(1, 1): printed P_43, derived weights at [(3, 4)]"
        in results["es.corners_misprint"].outcome.diffs
    )
    g1 = results["es.g1_misprint"].outcome.diffs
    assert any(d.startswith("n = 3, m = 4: row 1, first point 1") for d in g1)
    for rid in MISPRINTS:
        assert results[rid].erratum is not None and results[rid].erratum.verdict == "match", rid


def test_a_family_without_closed_end_forms_is_checked_at_every_degree_pair(results):
    (checked,) = results["es.c2"].outcome.checked
    assert "every degree pair" in checked
    assert all(f"({a}, {b})" in checked for a in DEGREES for b in DEGREES)


def test_a_changed_weight_at_one_degree_pair_only_is_found(records):
    """A C1 weight that is right except at n = 4, m = 5 (a term vanishing elsewhere)."""
    rec = dict(records["es.c1"])
    rec["weights"] = [dict(w) for w in rec["weights"]]
    rec["weights"][2]["weight"] += " + (n - 3)*(n - 5)*(m - 3)*(m - 4)"
    res = report_mod.check_record(rec)
    assert res.verdict == "mismatch"
    assert all(d.startswith("n = 4, m = 5:") for d in res.outcome.diffs), res.outcome.diffs


# ---------------------------------------------------------------------- the derivation
@pytest.mark.parametrize(
    ("first", "second", "continuity"),
    [
        ("same_degree", "same_degree", "C1"),
        ("same_degree", "bernstein_like", "G1"),
        ("bernstein_like", "same_degree", "C2"),
        ("bezier", "same_degree", "C2"),
    ],
)
def test_per_degree_conditions_equal_the_closed_forms(first, second, continuity):
    """The per-degree solve (surface_joins.conditions_at) against the closed forms in n, m of
    the built-in families (joins.py), at two degree pairs each."""
    sj = pytest.importorskip("derive.formulas.surface_joins")
    closed = sj.conditions(first, second, continuity)
    for deg1, deg2 in ((3, 3), (4, 3)):
        at = {sj.curve_joins.n: deg1, sj.curve_joins.m: deg2}
        per = sj.conditions_at(first, second, continuity, deg1, deg2)
        assert set(per) == set(closed)
        for key, w in closed.items():
            assert sp.cancel(w.xreplace(at) - per[key]) == 0, key


def test_a_defined_family_with_closed_end_forms_uses_them():
    """nouri_saeidian (shipped) has closed end forms of order 1: its surface C1 weights in n,
    m equal the per-degree solve from its basis; C2 (no closed second derivatives) is refused
    in n by a KeyError, which sends verify to the per-degree check."""
    from derive.families.definition import read_definition
    from derive.formulas import surface_joins as sj
    from derive.verify.registry import register_defined_family
    from lambda_bezier import examples

    defn = read_definition(Path(examples.path("nouri_saeidian.toml")))
    register_defined_family(defn)
    with pytest.raises(KeyError, match="order 2 not in closed form"):
        sj.conditions(defn.name, defn.name, "C2")
    for continuity in ("C1", "G1"):
        closed = sj.conditions(defn.name, defn.name, continuity)
        sj.check_pair(defn.name, defn.name, continuity)
        at = {sj.curve_joins.n: 4, sj.curve_joins.m: 3}
        per = sj.conditions_at(defn.name, defn.name, continuity, 4, 3)
        assert set(per) == set(closed)
        assert all(sp.cancel(closed[k].xreplace(at) - per[k]) == 0 for k in per)


def test_a_registered_family_is_never_emitted(results):
    """Registering a records file's family (done by the verdicts above) makes it known to the
    surface derivation for the process but leaves the emitted families (generated/) alone."""
    from derive.formulas import surface_energy as se

    assert se.known("end_shape_bezier")
    assert "end_shape_bezier" not in se.FAMILIES
    assert set(se.FAMILIES) == {"bezier", "same_degree", "bernstein_like"}


@pytest.mark.parametrize("continuity", ["C1", "G1", "C2"])
def test_the_per_degree_weights_join_the_tensor_product_patches(results, continuity):
    """conditions_at's weights, applied column by column, make the two patches built from the
    tensor-product basis meet with the continuity along the whole boundary; one weight off and
    the cross-boundary derivatives differ."""
    from derive.formulas import surface_joins as sj

    sj.check_columnwise_at("end_shape_bezier", "end_shape_bezier", continuity, 3, 4)
    weights = sj.conditions_at("end_shape_bezier", "end_shape_bezier", continuity, 3, 4)
    weights[(1, "first", 1)] += 1
    with pytest.raises(AssertionError, match="column-wise"):
        sj._check_weights(
            "end_shape_bezier", "end_shape_bezier", continuity, sj.tensor_basis, weights, (3, 4)
        )


@pytest.mark.parametrize(
    ("change", "message"),
    [
        ({"drop": "lam_u"}, "key lam_u is required with `values`: the basis depends on it"),
        ({"drop": "uv"}, "key uv is required with `values`"),
        ({"uv": ["1/3"]}, "key uv: a list of 2 numbers"),
        ({"uv": ["1/3", "x"]}, "key uv:"),
        ({"values": [["1"]]}, "key values:"),
    ],
)
def test_a_malformed_values_record_is_an_error_naming_its_key(records, change, message):
    """A surface_basis record with printed values: a parameter the basis depends on left out
    was read as 0 (a wrong verdict); a malformed point or table was a "mismatch" with a
    parser's message. Both are the verdict "error" naming the key."""
    rec = {k: v for k, v in records["es.values"].items() if k != change.get("drop")}
    rec |= {k: v for k, v in change.items() if k != "drop"}
    res = report_mod.check_record(rec)
    assert res.verdict == "error", (res.verdict, res.outcome)
    assert message in str(res.error)


def test_a_wrong_printed_value_names_the_point_plainly(records):
    rec = dict(records["es.values"])
    rec["values"] = [list(row) for row in rec["values"]]
    rec["values"][0][0] = "7"
    res = report_mod.check_record(rec)
    assert res.verdict == "mismatch"
    u0, v0 = rec["uv"]
    assert res.outcome.diffs[0].startswith(f"B_00({u0}, {v0}): printed 7, derived ")
