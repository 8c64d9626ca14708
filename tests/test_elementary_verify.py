"""verify: records about trigonometric, hyperbolic and mixed families
(derive/verify/checks_elementary.py, through checks_several.py's claim kinds).

Each records file under tests/data/families/*.records.toml of such a family must agree with
its expectations: the deliberate misprints are caught by the derivation (exact atoms), their
errata match. Changing one number in a matching record flips its verdict, so no verdict is
fixed in advance. Record payloads are read by derive's grammar; a formula outside it, or
outside the family's space, is refused with the key named.
"""

from __future__ import annotations

import copy
from pathlib import Path

import pytest

DATA = Path(__file__).parent / "data" / "families"
NAMES = ("han_trig_cubic", "hyp_two_shape_cubic", "at_pi_cubic")

records_mod = pytest.importorskip("derive.verify.records")
report_mod = pytest.importorskip("derive.verify.report")


@pytest.fixture(scope="module")
def records():
    paths = [DATA / f"{name}.toml" for name in NAMES]
    paths += [DATA / f"{name}.records.toml" for name in NAMES]
    return records_mod.load_paths(paths)


@pytest.fixture(scope="module")
def results(records):
    return {rec["id"]: report_mod.check_record(rec) for rec in records}


def _record(records, rid: str) -> dict:
    return copy.deepcopy(next(r for r in records if r["id"] == rid))


def test_every_record_agrees_with_its_expectation(results):
    assert len(results) == 31
    for rid, res in results.items():
        assert res.problems() == [], (rid, res.outcome, res.error)
        assert res.verdict in ("match", "mismatch"), (rid, res.outcome)
    misprints = {
        "han.ends_misprint",
        "han.nonnegative_misprint",
        "hyp.energy1_misprint",
        "han.join_c1_misprint",
    }
    assert {rid for rid, r in results.items() if r.verdict == "mismatch"} == misprints
    for rid in misprints:
        assert results[rid].erratum.verdict == "match", rid


def test_the_misprinted_tangent_is_caught_with_its_gap(results):
    diff = results["han.ends_misprint"].outcome.diffs[0]
    assert "fails at n = 3" in diff and "lam*P_1" in diff and "lam*P_0" in diff
    counter = results["han.nonnegative_misprint"].outcome.diffs[0]
    assert "'lam': '2'" in counter and "'i': 0" in counter


@pytest.mark.parametrize(
    ("rid", "path", "old", "new"),
    [
        ("han.basis", ("equations", 1, "rhs"), "(2 + lam", "(3 + lam"),
        ("han.ends", ("equations", 3, "rhs"), "(2 + mu)", "(2 + lam)"),
        ("han.ends", ("equations", 1, "lhs"), "p(pi/2)", "p(0)"),
        ("han.ends2", ("equations", 0, "rhs"), "4*(1 + lam)", "4*(1 + mu)"),
        ("han.special_zero", ("equations", 1, "rhs"), "2*sin", "3*sin"),
        ("han.symmetry", ("swap", "lam"), "mu", "lam"),
        ("han.gram1", ("gram", 2, 1), "10/3", "11/3"),
        ("han.gram1", ("gram", 0, 0), "5*pi/4", "5*pi/3"),
        ("han.energy2", ("expression",), "7901*pi/128", "7901*pi/127"),
        ("han.optimum2", ("parameters", "mu"), "-759731", "-659731"),
        ("han.rational", ("rational_weights", 3), "8/5", "7/5"),
        ("han.rational", ("rational_numerators", 2, 4), "4*mu/15", "4*lam/15"),
        ("hyp.ends", ("equations", 1, "rhs"), "(3 + lam)", "(2 + lam)"),
        ("hyp.ends", ("equations", 2, "rhs"), "-4*lam*e**(-4)", "-4*lam*e**(-3)"),
        ("hyp.basis_cosh", ("equations", 0, "rhs"), "sinh(4*t)", "sinh(3*t)"),
        ("hyp.energy1", ("expression",), "552*e**(-7)/7", "552*e**(-7)/5"),
        ("at.ends", ("equations", 2, "rhs"), "pi**2/4", "pi**2/2"),
        ("at.ends", ("equations", 1, "rhs"), "P(3)*lam", "P(3)*lam*pi"),
        ("at.mirror", ("equations", 0, "rhs"), "b(2, n, 1 - t)", "b(2, n, t)"),
        ("at.gram2_entries", ("expression",), "pi**4/128", "pi**3/128"),
        ("han.join_g1", ("join_weights", "1,first,1"), "-(2 + mu1)", "-(3 + mu1)"),
        ("han.join_g1", ("join_weights", "1,first,0"), "alpha*(2 + lam2)", "(2 + lam2)"),
        ("hyp.join_c1_bezier", ("join_weights", "0,first,3"), "e**4", "e**3"),
        ("hyp.join_c1_bezier", ("join_weights", "0,first,2"), "3*e", "2*e"),
    ],
)
def test_one_changed_number_flips_the_verdict(records, rid, path, old, new):
    rec = _record(records, rid)
    holder = rec
    for key in path[:-1]:
        holder = holder[key]
    assert old in holder[path[-1]]
    holder[path[-1]] = holder[path[-1]].replace(old, new, 1)
    res = report_mod.check_record(rec)
    assert res.verdict == "mismatch", (res.outcome, res.error)


@pytest.mark.parametrize(
    ("rid", "key", "value"),
    [
        ("han.nonnegative", "box", {"lam": "[-2, 1]", "mu": "[-5/2, 1]"}),
        ("han.independent", "independent", False),
        ("hyp.nonnegative_wide", "box", {"lam": "[-3, 1]"}),
        ("hyp.dependent_corner", "independent", True),
        ("at.independent", "box", {"lam": "[0, 1]"}),
    ],
)
def test_a_changed_decision_flips_the_verdict(records, rid, key, value):
    rec = _record(records, rid)
    rec[key] = value
    res = report_mod.check_record(rec)
    assert res.verdict == "mismatch", (res.outcome, res.error)


def test_a_rational_form_where_none_exists_is_a_mismatch(records):
    rec = _record(records, "at.unity")
    rec.update(claim="at_pi_cubic.several_rational", rational_weights=["1", "1"])
    del rec["equations"]
    res = report_mod.check_record(rec)
    assert res.verdict == "mismatch"
    assert "no exact rational Bezier form" in res.outcome.diffs[0]


def test_non_negativity_of_a_mixed_family_is_decided(records):
    """Decided by derive/formulas/atom_nonnegative.py (it was pending before): at_pi_cubic is
    non-negative on its box, so the claim matches and its negation is a mismatch."""
    for claimed, verdict in ((True, "match"), (False, "mismatch")):
        rec = _record(records, "at.independent")
        rec.update(claim="at_pi_cubic.several_nonnegative", nonnegative=claimed)
        del rec["independent"]
        res = report_mod.check_record(rec)
        assert res.outcome.verdict == verdict
        if verdict == "match":  # the report says how it was decided: not exactly, certified
            assert any("certified" in line for line in res.outcome.checked), res.outcome.checked
            assert not any(line.endswith(": exact") for line in res.outcome.checked)


@pytest.mark.parametrize(
    ("rid", "text", "message"),
    [
        ("han.basis", "sin(lam*t)", "rational multiple of t"),
        ("han.basis", "sinh(t)", "not in the trigonometric space"),
        ("han.basis", "sin(t/3)", "not a multiple of the base rate"),
        ("han.basis", "exec(t)", "unknown name"),
        ("han.basis", "b(0, n, t**2)", "is read at t"),
        ("han.basis", "1/sin(t)", "division"),
        ("han.ends", "p(pi/7)", "multiple of pi/2"),
        ("han.ends", "p(1)", "not a rational multiple of pi"),
        ("hyp.basis_cosh", "pi*t", "pi in a claim"),
        ("hyp.basis_cosh", "e**(1/2)", "not an integer"),
        ("at.unity", "e", "unknown name"),
    ],
)
def test_a_formula_outside_the_family_is_refused_with_its_key(records, rid, text, message):
    rec = _record(records, rid)
    rec["equations"] = [{"lhs": text, "rhs": "1"}]
    res = report_mod.check_record(rec)
    assert res.verdict == "error" or res.error, (res.outcome, res.error)
    assert message in str(res.error), res.error
    assert "key equations[0].lhs" in str(res.error), res.error


def test_kinds_for_elementary_families_only_refuse_a_polynomial_family(tmp_path):
    paths = [DATA / "q_bezier_4.toml"]
    body = (
        'schema_version = 2\nfamily = "q_bezier_4"\n[[record]]\nid = "x"\n'
        'claim = "several_nonnegative"\nnonnegative = true\n'
    )
    (tmp_path / "r.records.toml").write_text(body)
    recs = records_mod.load_paths([*paths, tmp_path / "r.records.toml"])
    res = report_mod.check_record(recs[0])
    assert "is polynomial" in str(res.error)


@pytest.mark.parametrize(
    ("change", "message"),
    [
        ({"control_points": [["0", "0"], ["1"], ["3", "3"], ["4", "0"]]}, "same number"),
        ({"control_points": [["0", "0"], ["1", "2"], ["3", "3"]]}, "4 points"),
        ({"control_points": [["pi", "0"], ["1", "2"], ["3", "3"], ["4", "0"]]}, "unknown name"),
        ({"k": 5}, "key k"),
        ({"parameters": {"lam": "1/2"}}, "no value of mu"),
        ({"parameters": {"lam": "1/2", "mu": "-1", "nu": "0"}}, "not a parameter"),
        ({"parameters": {"lam": "pi", "mu": "-1"}}, "unknown name"),
    ],
)
def test_a_bad_energy_payload_is_refused_with_its_key(records, change, message):
    rec = _record(records, "han.energy2")
    rec.update(change)
    res = report_mod.check_record(rec)
    assert message in str(res.error), (res.outcome, res.error)
