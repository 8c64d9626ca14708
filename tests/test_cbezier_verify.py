"""verify: records about C-Bezier families (derive/verify/checks_cbezier.py, issue #30).

The records file tests/data/families/c_bezier_cubic.records.toml states partition of unity, the
end values and derivatives (orders 0..2) at t = 0 and t = alpha, the end conditions of the curve
and the symmetry, with right-hand sides computed by SymPy from the family file's formulas; one
record is a deliberate misprint. Each verdict must agree with its expectation, and changing a
single term of a matching record must flip it (a verdict cannot be fixed in advance). The same
claims are checked on the family written on [0, 1] (sin(alpha*t)) and on a hyperbolic family
that is not a partition of unity.
"""

from __future__ import annotations

import copy
import re
from pathlib import Path

import pytest

DATA = Path(__file__).parent / "data" / "families"
FAMILY = DATA / "c_bezier_cubic.toml"
RECORDS = DATA / "c_bezier_cubic.records.toml"

records_mod = pytest.importorskip("derive.verify.records")
report_mod = pytest.importorskip("derive.verify.report")


@pytest.fixture(scope="module")
def records():
    return records_mod.load_paths([FAMILY, RECORDS])


@pytest.fixture(scope="module")
def results(records):
    return {rec["id"]: report_mod.check_record(rec) for rec in records}


def test_each_record_has_its_verdict(results):
    verdicts = {rid: r.verdict for rid, r in results.items()}
    assert verdicts == {
        "cb.unity": "match",
        "cb.values": "match",
        "cb.first_derivatives": "match",
        "cb.second_derivatives_start": "match",
        "cb.second_derivatives_end_misprint": "mismatch",
        "cb.second_derivatives_end": "match",
        "cb.ends": "match",
        "cb.symmetry": "match",
        "cb.symmetry_equation": "match",
    }
    for rid, res in results.items():
        assert res.problems() == [], (rid, res.outcome, res.error)


def _check(rec: dict) -> str:
    return report_mod.check_record(rec).outcome.verdict


def _by_id(records, rid: str) -> dict:
    return copy.deepcopy(next(r for r in records if r["id"] == rid))


def test_one_changed_term_flips_a_match(records):
    rec = _by_id(records, "cb.first_derivatives")
    eq = rec["equations"][3]  # b_2'(alpha) = (cos(alpha) - 1)/(alpha - sin(alpha))
    assert _check(rec) == "match"
    eq["rhs"] = eq["rhs"].replace("cos(alpha) - 1", "cos(alpha) - 2")
    assert _check(rec) == "mismatch"
    rec = _by_id(records, "cb.ends")
    rec["equations"][3]["rhs"] = rec["equations"][3]["rhs"].replace("P(2)", "P(1)")
    assert _check(rec) == "mismatch"


def test_the_misprint_corrected_matches(records):
    rec = _by_id(records, "cb.second_derivatives_end_misprint")
    rec["equations"] = rec["erratum"]["equations"]
    assert _check(rec) == "match"


def _run(tmp_path, family: Path, body: str) -> dict:
    path = tmp_path / "r.toml"
    path.write_text(
        'schema_version = 2\nsource = "test"\nfamily = "' + _name(family) + '"\n' + body
    )
    recs = records_mod.load_paths([family, path])
    return {r["id"]: report_mod.check_record(r).outcome.verdict for r in recs}


def _name(family: Path) -> str:
    import tomllib

    return tomllib.loads(family.read_text())["family"]["name"]


def test_a_family_written_on_the_unit_interval(tmp_path):
    # u = t/alpha: every t-derivative gains a factor alpha (computed by hand from cb.ends)
    body = """
[[record]]
id = "u.unity"
claim = "several_basis"
location = "x"
equations = [{ lhs = "b(0, n, t) + b(1, n, t) + b(2, n, t) + b(3, n, t)", rhs = "1" }]
[[record]]
id = "u.tangent"
claim = "several_end_conditions"
location = "x"
equations = [{ lhs = "Subs(Derivative(p(t), t), t, 0)", rhs = "alpha*TANGENT" }]
[[record]]
id = "u.tangent_without_alpha"
claim = "several_end_conditions"
location = "x"
equations = [{ lhs = "Subs(Derivative(p(t), t), t, 0)", rhs = "TANGENT" }]
[[record]]
id = "u.symmetry"
claim = "several_symmetry"
location = "x"
[[record]]
id = "u.symmetry_equation"
claim = "several_basis"
location = "x"
equations = [{ lhs = "b(i, n, t)", rhs = "b(n - i, n, 1 - t)" }]
"""
    tangent = "(1 - cos(alpha))/(alpha - sin(alpha))*(P(1) - P(0))"
    got = _run(tmp_path, DATA / "c_bezier_cubic_unit.toml", body.replace("TANGENT", tangent))
    assert got == {
        "u.unity": "match",
        "u.tangent": "match",
        "u.tangent_without_alpha": "mismatch",
        "u.symmetry": "match",
        "u.symmetry_equation": "match",
    }


def test_a_hyperbolic_family_that_is_not_a_partition_of_unity(tmp_path):
    # sinh(alpha - t)/sinh(alpha) + sinh(t)/sinh(alpha) is 1 only at the ends
    body = """
[[record]]
id = "h.unity"
claim = "several_basis"
location = "x"
equations = [{ lhs = "b(0, n, t) + b(1, n, t)", rhs = "1" }]
[[record]]
id = "h.slope"
claim = "several_basis"
location = "x"
equations = [{ lhs = "Subs(Derivative(b(1, n, t), t), t, 0)", rhs = "1/sinh(alpha)" }]
[[record]]
id = "h.symmetry"
claim = "several_symmetry"
location = "x"
"""
    got = _run(tmp_path, DATA / "hyp_interpolating.toml", body)
    assert got == {"h.unity": "mismatch", "h.slope": "match", "h.symmetry": "match"}


def test_other_claim_kinds_are_refused_by_name(tmp_path):
    body = """
[[record]]
id = "e"
claim = "several_energy"
location = "x"
k = 1
control_points = [["0", "0"], ["1", "2"], ["3", "3"], ["4", "0"]]
parameters = { alpha = "1" }
expression = "1"
"""
    with pytest.raises(records_mod.RecordsError, match="several_basis, several_end_conditions"):
        _run(tmp_path, FAMILY, body)


def test_a_mixed_claim_is_a_record_error(tmp_path):
    body = """
[[record]]
id = "m"
claim = "several_basis"
location = "x"
equations = [{ lhs = "b(0, n, 0)", rhs = "cosh(alpha) - sinh(alpha)" }]
"""
    path = tmp_path / "r.toml"
    path.write_text('schema_version = 2\nsource = "t"\nfamily = "c_bezier_cubic"\n' + body)
    (rec,) = records_mod.load_paths([FAMILY, path])
    res = report_mod.check_record(rec)
    assert res.error is not None and "not in its field" in str(res.error)


@pytest.mark.parametrize(
    ("equation", "message"),
    [
        ('{ lhs = "p(0)", rhs = "P(7)" }', r"P\(7\) at n = 3: no such control point"),
        ('{ lhs = "b(0, n, t**2)", rhs = "0" }', "the argument t\\*\\*2 is not an integer"),
        ('{ lhs = "b(0, n, 0)", rhs = "cos(alpha/2)" }', "the argument alpha/2 is not"),
    ],
)
def test_bad_claims_are_record_errors_naming_the_term(tmp_path, equation, message):
    body = (
        '[[record]]\nid = "bad"\nclaim = "several_basis"\nlocation = "x"\n'
        f"equations = [{equation}]\n"
    )
    path = tmp_path / "r.toml"
    path.write_text('schema_version = 2\nsource = "t"\nfamily = "c_bezier_cubic"\n' + body)
    (rec,) = records_mod.load_paths([FAMILY, path])
    res = report_mod.check_record(rec)
    assert res.error is not None
    assert re.search(message, str(res.error)), res.error
