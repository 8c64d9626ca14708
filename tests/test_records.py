"""`lambda-bezier verify PATH`: a user's records files, validated and read by our own grammar.

The user file src/lambda_bezier/examples/user_paper.toml holds true and misprinted
records about each built-in family; its verdicts are asserted here, and the true values it
states are recomputed with independent numerics (the runtime, finite differences,
quadrature). Hostile and malformed files must end in a clear error (exit 2) naming file,
record and key, and nothing in a file is ever run.
"""

from __future__ import annotations

import contextlib
import importlib
import io
import json
import re
import subprocess
import sys
import textwrap
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
import sympy as sp
from conftest import ROOT
from hypothesis import given
from hypothesis import strategies as st

import lambda_bezier as lb
from lambda_bezier import _derive_runner, _verify_runner

pytestmark = pytest.mark.skipif(
    not (ROOT / "derive" / "verify" / "report.py").is_file(),
    reason="needs the source checkout (derive/)",
)

USER_FILE = ROOT / "src" / "lambda_bezier" / "examples" / "user_paper.toml"
FORMAT_DOC = ROOT / "derive" / "published" / "README.md"


@pytest.fixture(scope="module")
def derive():
    return _derive_runner.load_derive(ROOT)


@pytest.fixture(scope="module")
def grammar(derive):
    return importlib.import_module(f"{derive.__name__}.grammar")


def run_verify(*argv: str, cwd: Path | None = None) -> tuple[int, str, str]:
    """The command as a user runs it, in a fresh process."""
    proc = subprocess.run(
        [sys.executable, "-m", "lambda_bezier", "verify", *argv],
        capture_output=True,
        text=True,
        timeout=120,
        cwd=cwd or ROOT,
    )
    return proc.returncode, proc.stdout, proc.stderr


def run_in_process(paths: list[Path], **kw) -> tuple[int, str]:
    out = io.StringIO()
    code = _verify_runner.run(fmt="json", root=ROOT, paths=paths, out=out, progress=False, **kw)
    return code, out.getvalue()


# --------------------------------------------------------------------------- a user's paper


@pytest.fixture(scope="module")
def user_report():
    code, text = run_in_process([USER_FILE])
    return code, {r["id"]: r for r in json.loads(text)["records"]}


EXPECTED = {
    "survey.sd.endpoints": "match",
    "survey.sd.d1_misprint": "mismatch",
    "survey.bl.d1_cases": "match",
    "survey.bz.d1_cases": "match",
    "survey.bl.X_3^2": "match",
    "survey.bl.Y_3^2": "mismatch",
    "survey.bl.lambda_3^2": "mismatch",
    "survey.bl.Y_3^2.corrected": "match",
    "survey.bl.example": "match",
    "survey.sd.c1": "match",
    "survey.sd.c1_misprint": "mismatch",
    "survey.sd.recursion": "match",
    "survey.bl.explicit_general": "mismatch",
    "survey.sd.list3": "match",
    "survey.bl.recursion": "match",
    "survey.bz.symmetry": "match",
    "survey.sd.X_4^2": "match",
    "survey.sd.Y_4^2": "match",
    "survey.sd.lambda_4^2": "match",
    "survey.sd.example": "match",
    "survey.bl.g1": "match",
    "survey.bz.c1": "match",
    "survey.sd.g1": "match",
}


def test_user_file_verdicts(user_report):
    code, by_id = user_report
    assert code == 0
    assert {rid: r["verdict"] for rid, r in by_id.items()} == EXPECTED
    for rid, r in by_id.items():
        if r["verdict"] == "mismatch":
            assert r["erratum"]["verdict"] == "match", rid
    # the smallest useful diff names what differs
    assert "entry [2][3]: printed -57, derived -75" in by_id["survey.bl.Y_3^2"]["diff"]
    sd = " ".join(by_id["survey.sd.d1_misprint"]["diff"])
    assert "printed -lam - n, derived -lam - n + 1" in sd and "n=3" in sd
    # a kind checked for one built-in family is checked for the others: symbolic and per degree
    assert any("symbolic" in c for c in by_id["survey.sd.endpoints"]["checked"])


def test_user_file_misprint_flips_its_verdict(tmp_path):
    text = USER_FILE.read_text(encoding="utf-8").replace('lambda = "-84/163"', 'lambda = "-84/161"')
    path = tmp_path / "changed.toml"
    path.write_text(text, encoding="utf-8")
    code, out = run_in_process([path], only=["survey.bl.example"])
    (rec,) = json.loads(out)["records"]
    assert (code, rec["verdict"]) == (1, "mismatch")
    assert "printed -12/23, derived -84/163" in rec["diff"][0]  # -84/161, reduced
    assert "NEW DISCREPANCY" in rec["problems"][0]


def test_user_file_true_values_by_independent_numerics():
    """What the user file states as true, recomputed without derive/."""
    rng = np.random.default_rng(7)
    h = 1e-6
    for n in (3, 5, 8):
        for lam in (-1.5, 0.25, 1.0):
            pts = rng.normal(size=(n + 1, 2))
            c = lb.SameDegreeCurve(pts, lam=lam)
            # survey.sd.endpoints: p'(0) = (n - 1 + λ)(V1 - V0)
            assert np.allclose(c.derivative(0.0), (n - 1 + lam) * (pts[1] - pts[0]))
            assert np.allclose(c.derivative(1.0), (n - 1 + lam) * (pts[n] - pts[n - 1]))
    for n in (2, 4, 7):
        for lam in (-1.0, 0.5):
            # survey.bl.d1_cases: b_0'(0) = -(n + 2λ), b_1'(0) = n + 2λ, others 0 (forward FD)
            c = lb.BernsteinLikeCurve(np.zeros((n + 1, 2)), lam=lam)
            d = (c.basis(h) - c.basis(0.0)) / h
            want = np.zeros(n + 1)
            want[0], want[1] = -(n + 2 * lam), n + 2 * lam
            assert np.allclose(d, want, atol=1e-4)
    # survey.bl.example: the E2-optimal λ of a cubic bernstein_like curve, by quadrature and a
    # one-dimensional minimisation (independent of the energy derivation)
    from scipy.integrate import quad
    from scipy.optimize import minimize_scalar

    pts = np.array([(0, 0), (1, 3), (3, 3), (4, 0)], dtype=float)

    def energy(lam):
        c = lb.BernsteinLikeCurve(pts, lam=lam, check_range=False)
        return quad(lambda t: float(np.sum(c.derivative(t, k=2) ** 2)), 0, 1, epsabs=1e-12)[0]

    best = minimize_scalar(energy, bounds=(-3, 3), method="bounded", options={"xatol": 1e-10})
    assert abs(best.x - (-84 / 163)) < 1e-6
    # survey.sd.example: the same for a quartic same_degree curve
    pts = np.array([(0, 0), (1, 2), (2, 3), (4, 2), (5, 0)], dtype=float)

    def energy_sd(lam):
        c = lb.SameDegreeCurve(pts, lam=lam, check_range=False)
        return quad(lambda t: float(np.sum(c.derivative(t, k=2) ** 2)), 0, 1, epsabs=1e-12)[0]

    best = minimize_scalar(energy_sd, bounds=(-3, 3), method="bounded", options={"xatol": 1e-10})
    assert abs(best.x - (-3 / 5)) < 1e-6
    # survey.bl.g1 and survey.bz.c1: the runtime's joins (solved from derive/formulas/joins.py,
    # compared here with the user's formulas at a few parameter values)
    for alpha in (0.5, 2.0):
        first = lb.BernsteinLikeCurve(rng.normal(size=(4, 2)), lam=0.4)
        second = lb.join(first, "G1", 5, lam=-0.3, alpha=alpha, rest=[(0, 1)] * 4)
        p1 = np.array(first.control_points(), dtype=float)
        want = p1[3] + (3 + 0.8) / (alpha * (5 - 0.6)) * (p1[3] - p1[2])
        assert np.allclose(np.array(second.control_points(), dtype=float)[1], want)
    first = lb.BezierCurve(rng.normal(size=(4, 2)))
    second = lb.join(first, "C1", 2, rest=[(1, 1)], family="bezier")
    p1 = np.array(first.control_points(), dtype=float)
    assert np.allclose(
        np.array(second.control_points(), dtype=float)[1], p1[3] + 3 / 2 * (p1[3] - p1[2])
    )
    # survey.sd.c1: the C1 vertex of the runtime's join is the user's formula
    first = lb.SameDegreeCurve(rng.normal(size=(5, 2)), lam=0.3)
    second = lb.join(first, "C1", 3, lam=-0.5, rest=[(1, 1), (2, 0)], family="same_degree")
    p1 = np.array(first.control_points(), dtype=float)
    n, m, lam1, lam2 = 4, 3, 0.3, -0.5
    want = p1[n] + (n - 1 + lam1) / (m - 1 + lam2) * (p1[n] - p1[n - 1])
    assert np.allclose(np.array(second.control_points(), dtype=float)[1], want)


def test_command_line_user_file_and_json():
    code, out, err = run_verify(str(USER_FILE), "--format", "json", "--only", "survey.bz.d1")
    assert code == 0, err
    data = json.loads(out)
    assert [(r["id"], r["verdict"]) for r in data["records"]] == [("survey.bz.d1_cases", "match")]


def test_expect_defaults_to_match_and_strict(tmp_path):
    path = tmp_path / "p.toml"
    path.write_text(
        textwrap.dedent(
            """
            schema_version = 2
            family = "bezier"
            [[record]]
            id = "p.d1"
            claim = "endpoint_d1"
            function = "B(i, n, t)"
            index = "i"
            at = "0"
            order = 1
            cases = [{ index = "0", value = "-n" }, { index = "otherwise", value = "0" }]
            """
        ),
        encoding="utf-8",
    )
    code, out = run_in_process([path])
    (rec,) = json.loads(out)["records"]
    assert (code, rec["expect"], rec["verdict"]) == (1, "match", "mismatch")
    assert "index 1" in " ".join(rec["diff"]) or "i=1" in " ".join(rec["diff"])


def test_format_document_example_runs(tmp_path):
    """The complete example of the records format document is a file that verifies."""
    doc = FORMAT_DOC.read_text(encoding="utf-8")
    blocks = re.findall(r"```toml\n(.*?)```", doc, flags=re.S)
    example = [b for b in blocks if b.lstrip().startswith("# my_paper.toml")]
    assert example, "the format document has lost its complete example"
    path = tmp_path / "my_paper.toml"
    path.write_text(example[0], encoding="utf-8")
    code, out = run_in_process([path])
    data = json.loads(out)
    assert code == 0, data["problems"]
    verdicts = {r["id"]: r["verdict"] for r in data["records"]}
    assert "mismatch" in verdicts.values() and "match" in verdicts.values()
    # every claim kind of the document's table is one the verifier knows, for its families
    checks = importlib.import_module(_derive_runner.load_derive(ROOT).__name__ + ".verify.registry")
    table = doc[doc.index("## Claim kinds") : doc.index("**Reading Dᵀ M D.**")]
    documented = set(re.findall(r"^\| `([a-z_0-9]+)` \|", table, flags=re.M))
    assert documented == set(checks.kinds())


# --------------------------------------------------------------------------- bad files

GOOD_RECORD = """
[[record]]
id = "x.1"
claim = "same_degree.recursion"
equations = [{ lhs = "b(i, n, t)", rhs = "(1 - t)*b(i, n - 1, t) + t*b(i - 1, n - 1, t)" }]
"""

BAD_FILES = {
    "unknown top key": ("schema_version = 2\ncolour = 1\n" + GOOD_RECORD, ["colour"]),
    "unknown record key": (
        "schema_version = 2\n" + GOOD_RECORD + 'colour = "red"\n',
        ["'x.1'", "colour"],
    ),
    "wrong type": (
        "schema_version = 2\n" + GOOD_RECORD + 'n = "3"\n',
        ["'x.1'", "key n", "not of type 'integer'"],
    ),
    "bad version": ("schema_version = 9\n" + GOOD_RECORD, ["schema_version", "9"]),
    "duplicate id": ("schema_version = 2\n" + GOOD_RECORD + GOOD_RECORD, ["'x.1'", "duplicate"]),
    "unknown claim": (
        "schema_version = 2\n" + GOOD_RECORD.replace("recursion", "recursoin"),
        ["'x.1'", "key claim", "unknown claim kind 'recursoin'"],
    ),
    "unknown family": (
        "schema_version = 2\n" + GOOD_RECORD.replace("same_degree.", "my_family."),
        ["'x.1'", "key claim", "unknown family 'my_family'"],
    ),
    "kind not for family": (
        "schema_version = 2\n"
        + GOOD_RECORD.replace("same_degree.recursion", "bezier.energy_lambda"),
        ["'x.1'", "energy_lambda", "bezier"],
    ),
    "no family": (
        "schema_version = 2\n" + GOOD_RECORD.replace("same_degree.", ""),
        ["'x.1'", "names no family"],
    ),
    "dangling reference": (
        "schema_version = 2\n" + GOOD_RECORD + 'uses = ["x.0"]\n',
        ["'x.1'", "key uses", "'x.0'"],
    ),
    "bad formula": (
        "schema_version = 2\n" + GOOD_RECORD.replace("(1 - t)*b", "(1 - t)*)b"),
        ["'x.1'", "equations[0].rhs", "unexpected ')'", "column 9"],
    ),
    "unknown name": (
        "schema_version = 2\n" + GOOD_RECORD.replace("(1 - t)", "(1 - zeta)"),
        ["'x.1'", "equations[0].rhs", "unknown name 'zeta'"],
    ),
    "toml syntax": ("schema_version = 2\n[[record]\n", ["not valid TOML", "line 2"]),
    "degree outside range": (
        "schema_version = 2\n" + GOOD_RECORD + "n = 40\n",
        ["'x.1'", "key n", "outside the same_degree range"],
    ),
}


@pytest.mark.parametrize("case", list(BAD_FILES))
def test_bad_file_is_a_clear_error(tmp_path, case):
    text, needles = BAD_FILES[case]
    path = tmp_path / "bad.toml"
    path.write_text(text, encoding="utf-8")
    out, err = io.StringIO(), io.StringIO()
    old = sys.stderr
    sys.stderr = err
    try:
        code = _verify_runner.run(root=ROOT, paths=[path], out=out, progress=False)
    finally:
        sys.stderr = old
    message = err.getvalue()
    assert code == 2, message
    assert str(path) in message and "Traceback" not in message
    for needle in needles:
        assert needle in message, (needle, message)


def test_unreadable_files_are_clear_errors(tmp_path):
    (tmp_path / "latin1.toml").write_bytes(b"schema_version = 2\n# caf\xe9\n")
    for path, needle in (
        (tmp_path / "missing.toml", "no such file"),
        (tmp_path, "is a directory"),
        (tmp_path / "latin1.toml", "not UTF-8"),
    ):
        code, _, err = run_verify(str(path))
        assert code == 2 and needle in err and "Traceback" not in err, err


def test_wrong_root_is_a_clear_error(tmp_path):
    code, _, err = run_verify(str(USER_FILE), "--root", str(tmp_path))
    assert code == 2 and "not a lambda-bezier source checkout" in err and "Traceback" not in err


# --------------------------------------------------------------------------- hostile files


HOSTILE = [
    "__import__('os').system('touch {marker}')",
    "b(i, n, t).__class__.__init__.__globals__",
    'exec(\'open("{marker}", "w")\')',
    "lambda: open('{marker}', 'w')",
    "[open('{marker}', 'w') for _ in (1,)]",
    "Sum(1, (i, 0, 10))(x=open('{marker}', 'w'))",
    "t**10**10",
    "2**2**40",
    "factorial(10**6)",
    "(" * 500 + "t" + ")" * 500,
    "t" + "+t" * 20_000,
]


def _hostile_file(tmp_path, formula: str):
    path = tmp_path / "hostile.toml"
    path.write_text(
        'schema_version = 2\nfamily = "same_degree"\n[[record]]\nid = "h"\n'
        'claim = "recursion"\n'
        f'equations = [{{ lhs = "b(i, n, t)", rhs = {json.dumps(formula)} }}]\n',
        encoding="utf-8",
    )
    return path


@pytest.mark.parametrize("formula", HOSTILE, ids=range(len(HOSTILE)))
def test_hostile_formula_runs_nothing_and_ends_quickly(tmp_path, formula):
    marker = tmp_path / "PWNED"
    path = _hostile_file(tmp_path, formula.replace("{marker}", str(marker)))
    code, out, err = run_verify(str(path))
    assert not marker.exists()
    assert code == 2 and "record 'h'" in err and "Traceback" not in err, err


@pytest.mark.parametrize("formula", HOSTILE[-5:], ids=range(5))
def test_hostile_formula_message_quotes_a_readable_stretch(tmp_path, formula):
    # The refusal names the fault, but quotes at most a few hundred characters of a formula
    # that may be 40,000 long (or of a number that may have 2,500 digits).
    code, out, err = run_verify(str(_hostile_file(tmp_path, formula)))
    assert code == 2 and "record 'h'" in err
    assert max(len(line) for line in err.splitlines()) < 800, err[:2000]


def test_long_family_formula_is_refused_with_a_short_quote(tmp_path):
    from derive.families.definition import DefinitionError, definition_from_table

    table = {"name": "f", "parameters": ["lam"], "basis": "t" + "+t" * 20_000}
    with pytest.raises(DefinitionError) as info:
        definition_from_table(table)
    message = str(info.value)
    assert "key basis" in message and "too long" in message and "elided" in message
    assert len(message) < 600


def test_hostile_sum_range_is_refused_while_evaluating(tmp_path):
    path = tmp_path / "sum.toml"
    path.write_text(
        'schema_version = 2\nfamily = "same_degree"\n[[record]]\nid = "s"\nclaim = "recursion"\n'
        'equations = [{ lhs = "b(i, n, t)", rhs = "Sum(t, (j, 0, 10**9))" }]\n',
        encoding="utf-8",
    )
    code, out, err = run_verify(str(path))
    assert code == 1 and "a sum over j = 0..1000000000" in out


def test_a_derive_beside_the_file_is_never_run(tmp_path):
    """verify PATH uses the installed (or the current checkout's) derivation, never derive/
    found beside PATH."""
    fake = tmp_path / "paper"
    (fake / "derive").mkdir(parents=True)
    marker = tmp_path / "RAN"
    (fake / "derive" / "__init__.py").write_text(f"open({str(marker)!r}, 'w')\n")
    (fake / "pyproject.toml").write_text('[project]\nname = "lambda-bezier"\n')
    target = fake / "mine.toml"
    target.write_text(USER_FILE.read_text(encoding="utf-8"), encoding="utf-8")
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    code, out, err = run_verify(str(target), "--only", "survey.bz", cwd=elsewhere)
    assert code == 0, err
    assert not marker.exists()


# --------------------------------------------------------------------------- the grammar


def test_grammar_reads_every_builtin_formula_like_sympy(grammar, derive):
    """Every formula of the built-in records gives the object SymPy itself builds from the same
    operations (the table shadows SymPy's C, E, Q, S, beta)."""
    e = grammar.parse_formula("C*E(2) + Q(1) + beta")
    assert {s.name for s in e.free_symbols} == {"C", "beta"}
    t, n, i = (grammar.SYMBOLS[s] for s in "tni")
    b = grammar.FUNCTIONS["b"]
    assert (
        grammar.parse_formula("-(1 - t)**(n - i)*b(i, n, t)/2")
        == -((1 - t) ** (n - i)) * b(i, n, t) / 2
    )
    assert grammar.parse_formula("2**-1") == sp.Rational(1, 2)
    assert grammar.parse_formula("-2**2") == -4  # Python's precedence
    assert grammar.parse_formula("0.25") == sp.Rational(1, 4)  # exact, never a float
    assert grammar.parse_formula("binomial(-1, -1)") == 0  # the papers' convention
    cond = grammar.parse_formula("(omega >= 0) & (omega <= 1/2)")
    assert isinstance(cond, sp.And)


@pytest.mark.parametrize(
    "text, needle",
    [
        ("t +", "ends too early"),
        ("t t", "unexpected 't'"),
        ("sin(t)", "unknown name 'sin'"),
        ("b", "must be called"),
        ("t(1)", "is a symbol"),
        ("t < n < 1", "chained"),
        ("t & n", "joins conditions"),
        ("(t, n)", "tuple"),
        ("t / 0", "division by zero"),
        ("t ** (1/2)", "not an integer"),
        ("1" * 500, "digits"),
        ("t^2", "write powers as **"),
        ("'t'", "a string"),
        ("ｔ", "not allowed"),
        ("１", "not allowed"),
        ("", "empty"),
        ("Sum(t, i)", "limit tuple"),
        ("Subs(t, 1, 2)", "symbol"),
    ],
)
def test_grammar_errors_name_the_problem(grammar, text, needle):
    with pytest.raises(grammar.ParseError) as info:
        grammar.parse_formula(text)
    assert needle in str(info.value)


_ATOMS = st.sampled_from(["t", "n", "i", "lam", "alpha", "1", "2", "3", "1/2", "-1"])


@st.composite
def formulas(draw, depth=3):
    if depth == 0 or draw(st.booleans()):
        return draw(_ATOMS)
    kind = draw(st.sampled_from(["+", "-", "*", "/", "**", "call", "b", "binomial", "neg"]))
    a, b = draw(formulas(depth=depth - 1)), draw(formulas(depth=depth - 1))
    if kind == "**":
        return f"({a})**{draw(st.integers(0, 4))}"
    if kind == "/":
        return f"({a})/({draw(st.sampled_from(['t', '2', 'n + 1', '1 - lam']))})"
    if kind == "call":
        return f"P({a})"
    if kind == "b":
        return f"b({a}, {b}, t)"
    if kind == "binomial":
        return f"binomial(n, {draw(st.sampled_from(['i', 'i - 1', '2']))})"
    if kind == "neg":
        return f"-({a})"
    return f"({a}) {kind} ({b})"


@given(formulas())
def test_grammar_round_trips_printed_expressions(grammar, text):
    """Parsing the printed form of a parsed expression gives the same expression (the same
    rational function of the symbols and function values; SymPy's printer does not promise
    the same tree, e.g. -(n + t)/t comes back as (-n - t)/t)."""
    e = grammar.parse_formula(text)
    again = grammar.parse_formula(str(e))
    assert again == e or sp.cancel(again - e) == 0


@given(st.text(max_size=80))
def test_grammar_random_text_raises_only_its_own_error(grammar, text):
    with contextlib.suppress(grammar.ParseError):
        grammar.parse_formula(text)


@given(st.text(alphabet="tnilam0123456789+-*/()., <>=&|_bBP", max_size=60))
def test_grammar_near_valid_text_raises_only_its_own_error(grammar, text):
    with contextlib.suppress(grammar.ParseError):
        grammar.parse_formula(text)


def test_grammar_module_never_calls_an_evaluator():
    import ast

    # what reads untrusted text: the grammar, records files and family definitions
    for name in (
        "grammar/formula.py",
        "grammar/interval.py",
        "verify/records.py",
        "families/definition.py",
    ):
        tree = ast.parse((ROOT / "derive" / name).read_text(encoding="utf-8"))
        calls = [node.func for node in ast.walk(tree) if isinstance(node, ast.Call)]
        names = {f.id for f in calls if isinstance(f, ast.Name)}
        attrs = {f.attr for f in calls if isinstance(f, ast.Attribute)}
        assert not names & {"eval", "exec", "compile", "__import__", "sympify", "parse_expr"}
        assert not attrs & {"sympify", "parse_expr", "S", "eval"}, name


def test_exact_numbers_stay_exact(grammar):
    assert grammar.parse_formula("-690/319") == sp.Rational(-690, 319)
    assert Fraction(str(grammar.parse_formula("0.125"))) == Fraction(1, 8)


def test_a_dying_worker_names_its_record(monkeypatch):
    """A worker that dies (as FLINT aborting on a huge exponent once made it) is reported with
    the record it was checking, not as an anonymous failure."""
    import os

    verify = importlib.import_module(_derive_runner.load_derive(ROOT).__name__ + ".verify.report")
    records = verify.load_records([USER_FILE])
    real = verify.check_record

    def dying(record):
        if record["id"] == "survey.bz.d1_cases":
            os._exit(7)
        return real(record)

    monkeypatch.setattr(verify, "check_record", dying)
    with pytest.raises(RuntimeError, match="survey.bz.d1_cases"):
        verify.verify(records, jobs=2)


def test_family_in_a_file_of_its_own(tmp_path):
    """A [family] table alone in a file defines the family for the run; the records file
    names it, and the two files may come in either order. Without the family file, the error
    says how to give it."""
    ns = (ROOT / "src" / "lambda_bezier" / "examples" / "nouri_saeidian.toml").read_text()
    family = tmp_path / "my_family.toml"
    family.write_text(ns[ns.index("[family]") : ns.index("[[record]]")])
    records = tmp_path / "my_records.toml"
    records.write_text(
        textwrap.dedent(
            """
            schema_version = 2
            source = "a paper about the family"
            family = "nouri_saeidian"

            [[record]]
            id = "own.tangent"
            claim = "endpoint_curve"
            location = "the end tangent"
            equations = [{ lhs = "Subs(Derivative(p(t), t), t, 0)", rhs = "n*lam*(P(1) - P(0))" }]

            [[record]]
            id = "own.wrong"
            claim = "nouri_saeidian.endpoint_curve"
            location = "a wrong end tangent"
            expect = "mismatch"
            equations = [{ lhs = "Subs(Derivative(p(t), t), t, 0)", rhs = "n*(P(1) - P(0))" }]
            [record.erratum]
            origin = "paper"
            explanation = "the factor lam is missing"
            equations = [
              { lhs = "Subs(Derivative(p(t), t), t, 0)", rhs = "n*lam*(P(1) - P(0))" },
            ]
            """
        )
    )
    for paths in ([family, records], [records, family]):
        code, text = run_in_process(paths)
        assert code == 0, text
        verdicts = {r["id"]: r["verdict"] for r in json.loads(text)["records"]}
        assert verdicts == {"own.tangent": "match", "own.wrong": "mismatch"}
    code, out, err = run_verify(str(records))
    assert code == 2
    assert "unknown family 'nouri_saeidian'" in err
    assert "lambda-bezier verify FAMILY.toml RECORDS.toml" in err
