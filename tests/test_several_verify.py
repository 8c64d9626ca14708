"""verify: records about families in several shape parameters (derive/verify/checks_several.py).

The literature records (tests/data/families/q_bezier.records.toml) must each agree with their
expectation: misprints are caught by the derivation and their errata match. The tests also
change a single number in a matching record and check that the verdict flips, so a verdict
cannot be fixed in advance. Records about the plain two-parameter family are checked the
same way.
"""

from __future__ import annotations

import copy
from pathlib import Path

import pytest

from lambda_bezier import examples

DATA = Path(__file__).parent / "data" / "families"
FILES = [DATA / "q_bezier.toml", DATA / "q_bezier_4.toml", DATA / "q_bezier.records.toml"]

records_mod = pytest.importorskip("derive.verify.records")
report_mod = pytest.importorskip("derive.verify.report")


@pytest.fixture(scope="module")
def records():
    return records_mod.load_paths(FILES)


@pytest.fixture(scope="module")
def results(records):
    return {rec["id"]: report_mod.check_record(rec) for rec in records}


def test_every_record_agrees_with_its_expectation(results):
    assert len(results) == 18
    for rid, res in results.items():
        assert res.problems() == [], (rid, res.outcome, res.error)
    assert {rid for rid, r in results.items() if r.verdict == "mismatch"} == {
        "qb4.d1_misprint",
        "qb.optimum_bernstein",
        "qb.ends_n_misprint",
    }
    # the closed forms in n catch the misprint for a general n too
    assert any("for general n" in d for d in results["qb.ends_n_misprint"].outcome.diffs)
    assert results["qb.ends_n_misprint"].erratum.verdict == "match"
    assert "fails at n = 4" in results["qb4.d1_misprint"].outcome.diffs[0]
    assert results["qb4.d1_misprint"].erratum.verdict == "match"


@pytest.mark.parametrize(
    ("rid", "path", "old", "new"),
    [
        ("qb4.basis", ("equations", 2, "rhs"), "lam(3)*t)", "lam(2)*t)"),
        ("qb4.ends", ("equations", 3, "rhs"), "(n + lam(n))", "(n - lam(n))"),
        ("qb.ends", ("equations", 2, "rhs"), "2*lam(2)", "3*lam(2)"),
        ("qb.symmetry", ("swap", "lam(k)"), "-lam(", "lam("),
        ("qb.gram2", ("gram", 1, 1), "4/3", "5/3"),
        ("qb4.energy", ("expression",), "13168/35", "13169/35"),
        ("qb.optimum", ("parameters", "lam(3)"), "5/4", "1"),
        # closed forms in n (derive/verify/checks_closed_n.py): one symbol changed
        ("qb.ends_n", ("equations", 1, "rhs"), "2*lam(n - 1)", "2*lam(n - 2)"),
        ("qb.join_c1_n", ("join_weights", "1,first,1"), "lam1(n)", "lam1(n - 1)"),
        ("qb.join_g1_n", ("join_weights", "1,first,0"), "lam2(1)", "lam2(2)"),
        ("qb.join_c2_n", ("join_weights", "2,first,2"), "lam2(2)", "lam2(1)"),
        ("qb.join_g1_bezier_n", ("join_weights", "1,first,1"), "alpha*m", "alpha*n"),
    ],
)
def test_one_changed_number_flips_the_verdict(records, rid, path, old, new):
    rec = copy.deepcopy(next(r for r in records if r["id"] == rid))
    holder = rec
    for key in path[:-1]:
        holder = holder[key]
    assert old in holder[path[-1]]
    holder[path[-1]] = holder[path[-1]].replace(old, new, 1)
    res = report_mod.check_record(rec)
    assert res.verdict == "mismatch", (res.outcome, res.error)


def _records_file(tmp_path: Path, body: str) -> Path:
    path = tmp_path / "two.records.toml"
    path.write_text('schema_version = 2\nfamily = "two_shape_cubic"\n' + body)
    return path


def _check(tmp_path: Path, body: str):
    paths = [examples.path("two_shape_cubic.toml"), _records_file(tmp_path, body)]
    return [report_mod.check_record(r) for r in records_mod.load_paths(paths)]


def test_plain_two_parameter_records(tmp_path):
    body = """
[[record]]
id = "two.swap"
claim = "several_symmetry"
swap = { lam = "mu", mu = "lam" }

[[record]]
id = "two.ends"
claim = "several_end_conditions"
equations = [
  { lhs = "Subs(Derivative(p(t), t), t, 0)", rhs = "(3 + lam)*(P(1) - P(0))" },
  { lhs = "Subs(Derivative(p(t), t), t, 1)", rhs = "(3 + mu)*(P(3) - P(2))" },
]

[[record]]
id = "two.bad_swap"
claim = "several_symmetry"
swap = { lam = "-mu", mu = "-lam" }
"""
    got = {r.id: r.verdict for r in _check(tmp_path, body)}
    assert got == {"two.swap": "match", "two.ends": "match", "two.bad_swap": "mismatch"}


def test_one_parameter_kinds_refused_for_several(tmp_path):
    body = """
[[record]]
id = "two.basis"
claim = "basis_general"
equations = [{ lhs = "b(0, n, t)", rhs = "(1 - lam*t)*(1 - t)**3" }]
"""
    with pytest.raises(records_mod.RecordsError, match="has several: its claim kinds are"):
        _check(tmp_path, body)


def test_several_kinds_refused_for_one_parameter_families(tmp_path):
    path = tmp_path / "r.toml"
    path.write_text(
        'schema_version = 2\n[[record]]\nid = "x"\nclaim = "same_degree.several_basis"\n'
        'equations = [{ lhs = "b(0, n, t)", rhs = "1" }]\n'
    )
    with pytest.raises(records_mod.RecordsError, match="families in several parameters"):
        records_mod.load_paths([path])


@pytest.mark.parametrize(
    ("body", "message"),
    [
        ('claim = "several_symmetry"\nswap = { nu = "lam" }', "not a parameter"),
        ('claim = "several_symmetry"\nswap = { lam = "mu" }', "no image of mu"),
        ('claim = "several_energy"\nk = 2\ncontrol_points = [["0", "0"]]', "outside"),
        (
            'claim = "several_basis"\nequations = [{ lhs = "b(0, n, t)", rhs = "nu" }]',
            "unknown name",
        ),
    ],
)
def test_bad_several_records_are_errors_naming_the_key(tmp_path, body, message):
    (res,) = _check(tmp_path, f'[[record]]\nid = "bad"\n{body}\n')
    assert res.verdict == "error" and message in res.error


def test_a_wrong_optimum_names_the_certified_minimum(records):
    """A printed minimiser moved off the optimum: the report gives E_k there, the certified
    minimum over the box and where it lies (λ_3 = 5/4, as printed before the change)."""
    rec = copy.deepcopy(next(r for r in records if r["id"] == "qb.optimum"))
    rec["parameters"]["lam(3)"] = "1"
    res = report_mod.check_record(rec)
    assert res.verdict == "mismatch"
    assert res.outcome.diffs[0].startswith("E_2 at the printed parameters is 219 ≈ 219; ")
    assert "certified minimum over the box is 216 at" in res.outcome.diffs[0]
    assert "lam_3 = 5/4" in res.outcome.diffs[0]
