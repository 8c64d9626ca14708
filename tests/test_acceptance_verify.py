"""An independent acceptance audit of `lambda-bezier verify` (issues 5, 17 and 20): what a
researcher who brings a records file of their own finds.

Each test is a defect the audit found, with its exact expected answer computed here
independently (SymPy from 000's eq. (1), never derive's code):

- a property claim about one degree (`n = 3`) was decided over every degree of the family's
  range, so a true claim got `mismatch` (with counterexamples from other degrees);
- a formula with a symbolic exponent tower (`t**n**n**n`) hung verify for hours: the
  symbolic comparison evaluated it at its sample point n = 17 before any limit applied;
- a formula that adds a number to a control point failed with an internal type name.
"""

from __future__ import annotations

import io
import json
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest
import sympy as sp
from conftest import ROOT

from lambda_bezier import _verify_runner

pytestmark = pytest.mark.skipif(
    not (ROOT / "derive" / "verify" / "report.py").is_file(),
    reason="needs the source checkout (derive/)",
)

T, LAM = sp.symbols("t lam")


def paper_binomial(n: int, k: int) -> int:
    return int(sp.binomial(n, k)) if 0 <= k <= n else 0


def same_degree_basis(n: int) -> list[sp.Expr]:
    """000's eq. (1), typed from the paper's definition (the axiom), nothing else."""
    out = []
    for i in range(n + 1):
        bracket = (
            paper_binomial(n - 3, i - 3) * (1 - T) ** 2
            - paper_binomial(n - 2, i - 1) * (1 - T) * T
            + paper_binomial(n - 3, i) * T**2
        )
        e = (
            paper_binomial(n, i) * (1 - T) ** (n - i) * T**i
            + (1 - LAM) * (1 - T) ** (n - i - 1) * T ** (i - 1) * bracket
        )
        out.append(sp.expand(sp.cancel(e)))
    return out


def determinant(n: int) -> sp.Expr:
    """det of the power-basis coefficients of the degree-n basis, a polynomial in λ."""
    basis = same_degree_basis(n)
    rows = [[sp.Poly(f, T).coeff_monomial(T**j) for j in range(n + 1)] for f in basis]
    return sp.factor(sp.Matrix(rows).det())


def run_json(tmp_path: Path, text: str) -> tuple[int, dict]:
    path = tmp_path / "mine.toml"
    path.write_text(textwrap.dedent(text), encoding="utf-8")
    out = io.StringIO()
    code = _verify_runner.run(fmt="json", root=ROOT, paths=[path], out=out, progress=False)
    return code, {r["id"]: r for r in json.loads(out.getvalue())["records"]}


# --------------------------------------------------------------------------- `n` fixes the degree


def test_a_property_claim_about_one_degree_is_decided_at_that_degree(tmp_path):
    # independently: at n = 3 the determinant is c·(λ + 2)² (root -2 only, outside (-2, 1]);
    # at n = 5 it vanishes at λ = -3/2, where b_2 = b_3
    d3 = determinant(3)
    assert sp.Poly(d3, LAM).real_roots() == [-2, -2]
    assert sp.Poly(determinant(5), LAM).eval(sp.Rational(-3, 2)) == 0
    b5 = same_degree_basis(5)
    assert sp.expand((b5[2] - b5[3]).subs(LAM, sp.Rational(-3, 2))) == 0

    code, by_id = run_json(
        tmp_path,
        """
        schema_version = 2
        family = "same_degree"

        [[record]]
        id = "mine.n3.open"
        claim = "basis_linearly_independent"
        parameter_range = "(-2, 1]"
        n = 3

        [[record]]
        id = "mine.n3.closed"
        claim = "basis_linearly_independent"
        parameter_range = "[-2, 1]"
        n = 3
        expect = "mismatch"
        [record.erratum]
        origin = "paper"
        explanation = "at lam = -2 the function b_1^3 = (2 + lam) t (1 - t)^2 vanishes"
        parameter_range = "(-2, 1]"

        [[record]]
        id = "mine.n4.nonneg"
        claim = "basis_nonnegative"
        parameter_range = "(-2, 1]"
        n = 4

        [[record]]
        id = "mine.n5.at_root"
        claim = "basis_linearly_independent"
        parameter_range = "[-3/2, -3/2]"
        n = 5
        expect = "mismatch"
        [record.erratum]
        origin = "paper"
        explanation = "b_2^5 = b_3^5 at lam = -3/2"
        parameter_range = "[-1, 1]"
        """,
    )
    assert code == 0
    assert by_id["mine.n3.open"]["verdict"] == "match"
    assert by_id["mine.n3.open"]["checked"] == ["degrees 3..3, every λ in (-2, 1] (exact)"]
    # the counterexample is the one at degree 3, and no other degree is looked at
    assert by_id["mine.n3.closed"]["verdict"] == "mismatch"
    assert by_id["mine.n3.closed"]["diff"] == [
        "degree 3: the basis is linearly dependent at λ = -2 (det = (lam + 2)**2/9): (1)·b_1 = 0"
    ]
    assert by_id["mine.n4.nonneg"]["verdict"] == "match"
    assert by_id["mine.n5.at_root"]["verdict"] == "mismatch"
    (line,) = by_id["mine.n5.at_root"]["diff"]
    assert line.startswith("degree 5: the basis is linearly dependent at λ = -3/2")
    assert line.endswith("(-1)·b_2 + (1)·b_3 = 0")


def test_a_degree_outside_the_range_or_below_min_degree_is_a_clear_error(tmp_path):
    code, by_id = run_json(
        tmp_path,
        """
        schema_version = 2
        family = "same_degree"

        [[record]]
        id = "mine.below"
        claim = "basis_nonnegative"
        n = 3
        min_degree = 5
        """,
    )
    assert code == 1
    assert by_id["mine.below"]["verdict"] == "error"
    assert by_id["mine.below"]["problems"] == [
        "checker error: ValueError: n = 3 is not a degree of the same_degree range from "
        "min_degree 5 on"
    ]


# --------------------------------------------------------------------------- limits, symbolically


def test_an_exponent_tower_in_the_degree_ends_in_a_limit_error_not_a_hang(tmp_path):
    # t**n**n**n: at n = 3 the exponent is 3**27 = 7625597484987, past the limit of 1000; the
    # symbolic comparison used to compute 17**(17**17) at its sample point first (hours)
    path = tmp_path / "tower.toml"
    path.write_text(
        textwrap.dedent(
            """
            schema_version = 2
            family = "same_degree"

            [[record]]
            id = "mine.tower"
            claim = "endpoint_curve"
            equations = [ { lhs = "p(0)", rhs = "V(0)*t**n**n**n" } ]

            [[record]]
            id = "mine.factorial_tower"
            claim = "endpoint_curve"
            equations = [ { lhs = "p(0)", rhs = "V(0)*(1 + t*factorial(n**n))" } ]
            """
        ),
        encoding="utf-8",
    )
    proc = subprocess.run(
        [sys.executable, "-m", "lambda_bezier", "verify", "--format", "json", str(path)],
        capture_output=True,
        text=True,
        timeout=90,
        cwd=ROOT,
    )
    assert proc.returncode == 1, proc.stderr
    by_id = {r["id"]: r for r in json.loads(proc.stdout)["records"]}
    assert by_id["mine.tower"]["problems"] == [
        "checker error: LimitError: an exponent 7625597484987 larger than 1000"
    ]
    assert by_id["mine.factorial_tower"]["problems"] == [
        # n = 3 first: 3**3 = 27 is fine, and the first degree past the limit is named
        "checker error: LimitError: factorial(3125) (at most 1000)"
    ]


def test_adding_a_number_to_a_point_is_named_in_words(tmp_path):
    code, by_id = run_json(
        tmp_path,
        """
        schema_version = 2
        family = "same_degree"

        [[record]]
        id = "mine.mixed"
        claim = "endpoint_curve"
        equations = [ { lhs = "p(0)", rhs = "V(0) + 1" } ]
        """,
    )
    assert code == 1
    (problem,) = by_id["mine.mixed"]["problems"]
    assert problem.startswith("checker error: TypeError: a formula adds ")
    assert "a number" in problem and "a combination of control points" in problem
    assert problem.endswith("which cannot be added")


def test_the_json_report_names_the_record_of_every_problem(tmp_path):
    # the text report says "FAIL mine.false: ..."; the JSON summary list said only the problem
    path = tmp_path / "mine.toml"
    path.write_text(
        textwrap.dedent(
            """
            schema_version = 2
            family = "same_degree"

            [[record]]
            id = "mine.false"
            claim = "basis_nonnegative"
            parameter_range = "(-2, 101/100]"
            n = 3
            """
        ),
        encoding="utf-8",
    )
    out = io.StringIO()
    code = _verify_runner.run(fmt="json", root=ROOT, paths=[path], out=out, progress=False)
    data = json.loads(out.getvalue())
    assert code == 1
    assert data["problems"] == [
        "mine.false: NEW DISCREPANCY: expected match, the derivation disagrees"
    ]
    # and the counterexample is exact: b_0^3 = (1 - λt)(1 - t)^2 at λ = 101/100, t = 201/202
    b0 = same_degree_basis(3)[0]
    value = b0.subs({LAM: sp.Rational(101, 100), T: sp.Rational(201, 202)})
    assert value == sp.Rational(-1, 8160800)
    (record,) = data["records"]
    assert record["diff"] == ["degree 3: b_0(t = 201/202) = -1/8160800 < 0 at λ = 101/100"]


# --------------------------------------------------------------------------- join records


def c1_join(n: str, lam1: str) -> str:
    """A same_degree C1 join record, the first curve's degree and shape as given."""
    rhs = (
        f"(1 + ({n} - 1 + {lam1})/(m - 1 + lam2))*P1({n})"
        f" - ({n} - 1 + {lam1})/(m - 1 + lam2)*P1({n} - 1)"
    )
    return C1_JOIN.format(n=n, lam1=lam1, rhs=rhs)


C1_JOIN = """
schema_version = 2

[[record]]
id = "mine.c1"
claim = "same_degree.c1_join"
first = {{ curve = "p1", degree = "{n}", shape = "{lam1}", points = "P1" }}
second = {{ curve = "p2", degree = "m", shape = "lam2", points = "P2" }}
convention = [
  {{ lhs = "p1(1)", rhs = "p2(0)" }},
  {{ lhs = "Subs(Derivative(p1(t), t), t, 1)", rhs = "Subs(Derivative(p2(t), t), t, 0)" }},
]
equations = [
  {{ lhs = "P2(0)", rhs = "P1({n})" }},
  {{ lhs = "P2(1)", rhs = "{rhs}" }},
]
"""


def test_a_join_of_same_degree_curves_is_checked_like_001s(tmp_path):
    # p'(1) = (n - 1 + λ)(V_n - V_{n-1}) and p'(0) = (n - 1 + λ)(V_1 - V_0) (000's eq. (9),
    # re-derived from eq. (1) here): C1 gives P2(1) as below for every n, m, λ1, λ2
    for n in (3, 4, 5):
        b = same_degree_basis(n)
        assert sp.expand(sp.diff(b[n], T).subs(T, 1) - (n - 1 + LAM)) == 0
        assert sp.expand(sp.diff(b[n - 1], T).subs(T, 1) + (n - 1 + LAM)) == 0
    code, by_id = run_json(tmp_path, c1_join("n", "lam1"))
    assert code == 0
    assert by_id["mine.c1"]["verdict"] == "match"


@pytest.mark.parametrize(
    ("n", "lam1", "key", "text"),
    [("3", "lam1", "first.degree", "'3'"), ("n", "1/2", "first.shape", "'1/2'")],
)
def test_a_join_curve_with_a_number_for_its_degree_or_shape_is_refused_by_name(
    tmp_path, capsys, n, lam1, key, text
):
    # it ended in "SyntaxError: invalid syntax (<lambdifygenerated-1>, line 1)"
    path = tmp_path / "mine.toml"
    path.write_text(c1_join(n, lam1), encoding="utf-8")
    out = io.StringIO()
    code = _verify_runner.run(fmt="json", root=ROOT, paths=[path], out=out, progress=False)
    assert code == 2
    assert f"record 'mine.c1', key {key}: {text} must be a symbol" in capsys.readouterr().err


# --------------------------------------------------------------------------- messages


@pytest.mark.parametrize(
    ("key", "value", "wanted"),
    [
        # a minus sign pasted from a paper (U+2212), and an infinite end
        ("parameter_range", "(−2, 1]", "an interval with exact ends in brackets"),
        ("parameter_range", "(-oo, 1]", "an interval with exact ends in brackets"),
        ("claim", "Basis Symmetric", "a claim kind, such as"),
    ],
)
def test_a_value_of_the_wrong_form_is_told_the_form_wanted_not_a_regex(
    tmp_path, capsys, key, value, wanted
):
    path = tmp_path / "mine.toml"
    claim = "" if key == "claim" else 'claim = "basis_nonnegative"\n'
    path.write_text(
        'schema_version = 2\nfamily = "same_degree"\n[[record]]\nid = "mine.x"\n'
        f"{claim}{key} = {json.dumps(value, ensure_ascii=False)}\n",
        encoding="utf-8",
    )
    code = _verify_runner.run(fmt="json", root=ROOT, paths=[path], out=io.StringIO())
    err = capsys.readouterr().err
    assert code == 2
    assert f"record 'mine.x', key {key}: {value!r} is not {wanted}" in err
    assert "\\\\s" not in err and "^" not in err


def test_a_min_degree_past_the_family_range_is_a_validation_error(tmp_path, capsys):
    # exit 2 and the key, like `n` outside the range (it was a checker error, exit 1)
    path = tmp_path / "mine.toml"
    path.write_text(
        'schema_version = 2\nfamily = "same_degree"\n[[record]]\nid = "mine.x"\n'
        'claim = "basis_symmetric"\nmin_degree = 40\n',
        encoding="utf-8",
    )
    code = _verify_runner.run(fmt="json", root=ROOT, paths=[path], out=io.StringIO())
    assert code == 2
    assert (
        "record 'mine.x', key min_degree: no degree of the same_degree range 3..12 is >= 40"
        in capsys.readouterr().err
    )


def test_an_equation_that_no_degree_of_the_range_can_evaluate_says_why(tmp_path):
    # b(i, n + 20, t) exists at no degree of 3..12: nothing is compared, so no verdict; the
    # message was an internal "AssertionError: ... was checked for no instance"
    code, by_id = run_json(
        tmp_path,
        """
        schema_version = 2
        family = "same_degree"

        [[record]]
        id = "mine.recursion"
        claim = "recursion"
        equations = [
          { lhs = "b(i, n, t)", rhs = "(1 - t)*b(i, n + 20, t) + t*b(i - 1, n - 1, t)" },
        ]
        """,
    )
    assert code == 1
    assert by_id["mine.recursion"]["verdict"] == "error"
    (problem,) = by_id["mine.recursion"]["problems"]
    assert problem.startswith(
        "checker error: ValueError: equation 1 could be checked at no degree or index: every "
        "case left a term undefined (e.g. same_degree degree "
    )
    assert problem.endswith(" outside 3..12)")


def test_the_coverage_in_json_is_json():
    # `--coverage --format json` printed the text report
    out = io.StringIO()
    code = _verify_runner.run(coverage=True, root=ROOT, fmt="json", out=out, progress=False)
    assert code == 0
    data = json.loads(out.getvalue())
    items = data["items"]
    assert data["summary"]["items"] == len(items)
    assert data["summary"]["with_records"] == sum(1 for it in items if it["records"])
    assert all(bool(it["records"]) != bool(it["reason"]) for it in items)
    (prop5,) = [it for it in items if any(r["id"] == "000.prop5" for r in it["records"])]
    assert prop5["records"] == [{"id": "000.prop5", "verdict": "mismatch"}]
    assert prop5["document"] == "000_10ca634d356c575d.txt"


def test_a_surface_degree_outside_the_family_names_its_degrees_as_the_definition_does(tmp_path):
    """The message gave Python's range(3, 13) for the degrees 3..12."""
    code, by_id = run_json(
        tmp_path,
        """
        schema_version = 2
        family = "same_degree"

        [[record]]
        id = "mine.surface"
        claim = "surface_boundary"
        degrees = [2, 3]
        side = "u=1"
        line = "row m"
        """,
    )
    text = json.dumps(by_id["mine.surface"])
    assert "degree 2 is outside the same_degree degrees 3..12" in text
    assert "range(" not in text
