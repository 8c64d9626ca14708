"""Issue #30, second acceptance pass (continued from test_acceptance_30b.py): the command line
and verify on the literature families of tests/data/families/lit_*.toml, ill-formed
definitions (each refused naming its key and term), random valid definitions (hypothesis),
and a definition edited and derived again in one process."""

from __future__ import annotations

import json
from fractions import Fraction
from pathlib import Path

import pytest
from conftest import examples_per_profile
from definition_checks import TWO_PARAMETER_TRIG, assert_refused
from hypothesis import given, settings
from hypothesis import strategies as st

import lambda_bezier as lb
from derive.emit.document import derive as derive_document
from derive.families.definition import DefinitionError, definition_from_table
from lambda_bezier import cli

DATA = Path(__file__).parent / "data" / "families"


# ---- the command line, verify -----------------------------------------------------------


def test_cli_optimal_parameters_by_name(capsys):
    path = DATA / "lit_han_trig2.toml"
    points = ["0,0", "-2,3", "3,2", "4,0"]
    assert (
        cli.main(["optimal-lambda", "--family", str(path), "--energy", "1", "--json", *points]) == 0
    )
    out = json.loads(capsys.readouterr().out)
    got = lb.optimal_parameters([(0, 0), (-2, 3), (3, 2), (4, 0)], 1, family=lb.load_family(path))
    assert out["parameters"] == {"lam": str(got["lam"]), "mu": str(got["mu"])}
    assert out["parameters_decimal"] == {
        "lam": -2.0,
        "mu": pytest.approx(float(got["mu"]), abs=1e-15),
    }
    assert out["free_inside"] is False and out["boundary"] == "lam = -2 (lower end)"
    # the text form names both parameters and the face
    assert cli.main(["optimal-lambda", "--family", str(path), "--energy", "1", *points]) == 0
    text = capsys.readouterr().out
    assert "optimal lam" in text and "optimal mu" in text and "lam = -2 (lower end)" in text


def test_cli_derive_check_of_every_literature_family(tmp_path):
    # the committed documents are what derive --family writes from the files alone
    for name in ("lit_han_quad_trig", "lit_hyp_quad", "lit_yan_liang"):
        assert cli.main(["derive", "--family", str(DATA / f"{name}.toml"), "--check"]) == 0


def test_verify_finds_the_misprints_in_a_records_file_of_a_literature_family():
    records = pytest.importorskip("derive.verify.records")
    report = pytest.importorskip("derive.verify.report")
    loaded = records.load_paths(
        [DATA / "lit_han_quad_trig.toml", DATA / "lit_han_quad_trig.records.toml"]
    )
    results = {rec["id"]: report.check_record(rec) for rec in loaded}
    assert len(results) == 8
    wrong = {rid for rid, r in results.items() if r.verdict == "mismatch"}
    assert wrong == {"hq.ends_misprint", "hq.independent_misprint", "hq.energy2_misprint"}
    for rid, res in results.items():
        assert res.problems() == [], (rid, res.outcome)
        if rid in wrong:
            assert res.erratum.verdict == "match", rid
        else:
            assert res.verdict == "match", rid
    assert "-1" in results["hq.independent_misprint"].outcome.diffs[0]


# ---- ill-formed definitions -------------------------------------------------------------

_TABLE = TWO_PARAMETER_TRIG


def _with_first(term: str) -> list[str]:
    return [term, f"1 - ({term}) - (1 - cos(t))**2", "(1 - cos(t))**2"]


@pytest.mark.parametrize(
    ("change", "needles"),
    [
        # the literature's classic error: as many functions as the degree
        ({"degrees": "3"}, ["key functions", "degree 3 has 4 functions, got 3"]),
        ({"functions": _TABLE["functions"][:2]}, ["key functions", "has 3 functions, got 2"]),
        ({"functions": _with_first("tan(t)")}, ["key functions[0]", "unknown name 'tan'"]),
        (
            {"functions": _with_first("sin(t)**1000")},
            ["key functions[0]", "sin(t)**1000", "above 64"],
        ),
        ({"functions": _with_first("sin(10**9*t)")}, ["key functions[0]", "rate larger than 1000"]),
        (
            {"functions": _with_first("sin(t*t)")},
            ["key functions[0]", "sin(t**2)", "rational multiple"],
        ),
        ({"functions": _with_first("sin(pi*pi*t)")}, ["key functions[0]", "rational multiple"]),
        ({"functions": _with_first("sin(lam*t)")}, ["key functions[0]", "sin(lam*t)"]),
        (
            {"functions": _with_first("sin(t)**lam")},
            ["key functions[0]", "sin(t)**lam", "exponent"],
        ),
        ({"functions": _with_first("t**mu")}, ["key functions[0]", "t**mu", "exponent"]),
        ({"functions": _with_first("exp(t)*sin(t)")}, ["key functions[0]", "together"]),
        ({"functions": _with_first("pi*sin(t)")}, ["key functions[0]", "pi enters only"]),
        ({"degrees": "40", "functions": ["1"] + ["0"] * 40}, ["key"]),
        ({"degrees": "3..80"}, ["key degrees", "20"]),
        ({"domain": "[0, alpha]"}, ["key domain", "unknown name 'alpha'"]),
        # C-Bezier on [0, alpha], alpha a parameter: what the definition lacks, said plainly
        (
            {
                "parameters": ["lam", "mu", "w"],
                "range": {"lam": "[-1, 1]", "mu": "[-1, 1]", "w": "[1/2, 3]"},
                "domain": "[0, w]",
            },
            ["key domain", "shape parameter 'w'", "C-Bezier", "not supported"],
        ),
        ({"domain": "[0, pi/3]"}, ["key domain", "pi/2"]),
        ({"functions": ["sin(t)", "cos(t)", "1"]}, ["key functions", "no partition of unity"]),
    ],
)
def test_an_ill_formed_definition_is_refused_naming_key_and_term(change, needles):
    assert_refused({**_TABLE, **change}, needles)


# ---- hypothesis: random valid definitions -------------------------------------------------

_ATOMS = {
    "polynomial": ("[0, 1]", ["t", "(1 - t)"]),
    "trigonometric": ("[0, pi/2]", ["sin(t)", "cos(t)", "(1 - sin(t))", "(1 - cos(t))"]),
    "hyperbolic": ("[0, 1]", ["exp(-t)", "(1 - exp(-t))", "sinh(t)"]),
    "mixed": ("[0, 1]", ["t", "(1 - t)", "sin(pi*t/2)", "(1 - cos(pi*t/2))"]),
}


@st.composite
def _definitions(draw):
    space = draw(st.sampled_from(sorted(_ATOMS)))
    domain, atoms = _ATOMS[space]
    n = draw(st.integers(1, 3))
    terms = []
    for _ in range(n):
        factors = draw(st.lists(st.sampled_from(atoms), min_size=1, max_size=2))
        coef = draw(st.sampled_from([-2, -1, 1, 2, Fraction(1, 2)]))
        shape = draw(st.sampled_from(["", "*lam", "*(1 - lam)"]))
        terms.append(f"{coef}*{'*'.join(factors)}{shape}")
    functions = [f"1 - ({' + '.join(terms)})", *terms]
    return {
        "name": "random_fam",
        "parameter": "lam",
        "range": "[0, 1]",
        **({} if space == "polynomial" else {"domain": domain}),
        "degrees": str(n),
        "functions": functions,
        **({"degree_offset": 2} if space == "polynomial" else {}),
    }


@settings(max_examples=examples_per_profile(8, 150), deadline=None)
@given(_definitions())
def test_random_valid_definitions_derive_or_are_refused_clearly(table):
    # a basis summing to one by construction; it may be dependent or of another degree than
    # stated, which must be a DefinitionError naming a key, never a traceback
    try:
        doc = derive_document(definition_from_table(table, "fam.toml"))
    except DefinitionError as err:
        assert "[family]" in str(err), str(err)
        return
    assert (
        doc["family"] == "random_fam"
        or doc.get("name") == "random_fam"
        or "random_fam" in json.dumps(doc)[:2000]
    )


def _user_family(coefficient: str) -> dict:
    # b_1 = c(lam) t vanishes, and the basis is dependent, exactly where c(lam) = 0
    return {
        "name": "edited_fam",
        "parameter": "lam",
        "range": "[0, 1]",
        "degrees": "2",
        "functions": [f"1 - ({coefficient})*t - t**2", f"({coefficient})*t", "t**2"],
    }


def test_a_definition_edited_and_derived_again_in_one_process():
    # the one-parameter properties were cached by the family's name: after deriving the first
    # version (singular at 1/2), the edited one (singular at 1/3) was reported singular at
    # 1/2, and a random definition after another was "dependent for every lam"
    first = derive_document(definition_from_table(_user_family("2*lam - 1"), "fam.toml"))
    second = derive_document(definition_from_table(_user_family("3*lam - 1"), "fam.toml"))
    assert first["singular_parameters"] == {"2": ["1/2"]}
    assert second["singular_parameters"] == {"2": ["1/3"]}


@pytest.mark.parametrize("at", ["5", "-2"])
def test_bernstein_at_lies_in_the_parameter_range(at):
    """`bernstein_at` names a value of the parameter: outside its range it was accepted (and
    checked there), an open end is outside too."""
    table = {
        "name": "end_shape_at",
        "parameter": "lam",
        "range": "(-2, 1]",
        "bernstein_at": at,
        "degrees": "3..4",
        "degree_offset": 1,
        "basis": "t**i*(1 - t)**(n - i)*(binomial(n, i) + lam*(binomial(0, i - 1) - "
        "binomial(0, n - i))*(1 - t) - lam*(binomial(0, i) - binomial(0, n - i - 1))*t)",
    }
    assert_refused(table, ["key bernstein_at", f"{at} is outside the range (-2, 1]"], derive=False)
