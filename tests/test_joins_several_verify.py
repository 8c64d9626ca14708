"""verify's claim kind several_join (derive/verify/checks_joins_several.py): a records
file states a join weight of a family in several parameters, indexed, or with atoms, and
gets an exact verdict; one changed symbol flips it (issue #30)."""

from __future__ import annotations

import copy
from pathlib import Path

import pytest

DATA = Path(__file__).parent / "data" / "families"
records_mod = pytest.importorskip("derive.verify.records")
report_mod = pytest.importorskip("derive.verify.report")

RECORDS = """
schema_version = 2
source = "test"
family = "{family}"

[[record]]
id = "join"
claim = "several_join"
location = "test"
pair = "{pair}"
continuity = "{continuity}"
{extra}join_weights = {weights}
"""


def _check(tmp_path, family: str, pair: str, continuity: str, weights: str, extra: str = ""):
    text = RECORDS.format(
        family=family, pair=pair, continuity=continuity, weights=weights, extra=extra
    )
    path = tmp_path / f"{family}.records.toml"
    path.write_text(text)
    (rec,) = [
        r for r in records_mod.load_paths([DATA / f"{family}.toml", path]) if r["id"] == "join"
    ]
    return report_mod.check_record(copy.deepcopy(rec))


@pytest.mark.parametrize(
    ("family", "pair", "continuity", "right", "wrong", "extra"),
    [
        # per_leg_cubic (degree_offset 1): p'(1) = (3 - s2)(P3 - P2)
        (
            "per_leg_cubic",
            "per_leg_cubic>bezier",
            "G1",
            '{ "1,first,1" = "-(3 - s21)/(alpha*m)" }',
            '{ "1,first,1" = "-(3 + s21)/(alpha*m)" }',
            "",
        ),
        # q_bezier at n = 3: p'(0) = (3 + lam_1)(P1 - P0), after a Bezier curve of degree n
        (
            "q_bezier",
            "bezier>q_bezier",
            "C1",
            '{ "1,first,1" = "-n/(3 + lam_12)" }',
            '{ "1,first,1" = "-n/(3 + lam_22)" }',
            "n = 3\n",
        ),
        # at_pi_cubic: its start and end derivatives carry pi (sin(pi t/2)); the given P2_2
        # enters the C1 solve of P2_1
        (
            "at_pi_cubic",
            "at_pi_cubic>at_pi_cubic",
            "C1",
            '{ "0,first,0" = "1", "1,second,2" = "-2/(pi - 2)" }',
            '{ "0,first,0" = "1", "1,second,2" = "-2/(pi - 3)" }',
            "",
        ),
    ],
)
def test_a_join_weight_gets_a_verdict_and_one_change_flips_it(
    tmp_path, family, pair, continuity, right, wrong, extra
):
    good = _check(tmp_path, family, pair, continuity, right, extra)
    assert good.verdict == "match", (good.outcome, good.error)
    bad = _check(tmp_path, family, pair, continuity, wrong, extra)
    assert bad.verdict == "mismatch", (bad.outcome, bad.error)
    assert "derived" in bad.outcome.diffs[0]


def test_a_pair_without_the_family_is_a_mismatch_with_the_reason(tmp_path):
    res = _check(tmp_path, "per_leg_cubic", "bezier>same_degree", "C1", '{ "0,first,0" = "1" }')
    assert res.verdict == "mismatch"
    assert "not a pair of per_leg_cubic" in res.outcome.diffs[0]


def test_an_unreadable_weight_is_refused_naming_the_key(tmp_path):
    res = _check(tmp_path, "per_leg_cubic", "per_leg_cubic>bezier", "C1", '{ "1,first,1" = "m**" }')
    assert res.verdict != "match"
    assert "join_weights.1,first,1" in str(res.error or res.outcome)
