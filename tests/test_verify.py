"""`lambda-bezier verify`: verdicts are computed at run time from the derivation; altering one
printed number flips a record's verdict; every erratum's corrected form matches; the exit code
follows the recorded expectations; ERRATA.md is current."""

from __future__ import annotations

import copy
import difflib
import importlib
import io
import json
import re
import shutil
import types
from fractions import Fraction

import pytest
from conftest import ROOT
from hypothesis import given
from hypothesis import strategies as st

from lambda_bezier import _derive_runner, _verify_runner

pytestmark = pytest.mark.skipif(
    not (ROOT / "derive" / "verify" / "report.py").is_file(),
    reason="needs the source checkout (derive/)",
)


@pytest.fixture(scope="module")
def verify():
    derive = _derive_runner.load_derive(ROOT)
    return importlib.import_module(f"{derive.__name__}.verify.report")


def _verify_modules(verify, *names: str) -> types.SimpleNamespace:
    """The public and private names of several derive/verify modules, as one namespace (the
    tests below reach into a group of modules that used to be one)."""
    package = verify.__name__.rsplit(".", 1)[0]
    out: dict = {}
    for name in names:
        module = importlib.import_module(f"{package}.{name}")
        out.update({k: v for k, v in vars(module).items() if not k.startswith("__")})
    return types.SimpleNamespace(**out)


@pytest.fixture(scope="module")
def expr_mod(verify):
    """The expression model: parsing, scalars, values, the realiser, comparison."""
    return _verify_modules(verify, "expr_parse", "scalar", "values", "realiser", "compare")


@pytest.fixture(scope="module")
def records(verify):
    return verify.load_records()


@pytest.fixture(scope="module")
def report(verify, records):
    """The one full verification run of this module."""
    return verify.verify(records)


_RECORDS = (
    importlib.import_module(
        _derive_runner.load_derive(ROOT).__name__ + ".verify.report"
    ).load_records()
    if (ROOT / "derive" / "verify" / "report.py").is_file()
    else []
)
RECORD_IDS = [r["id"] for r in _RECORDS]


# --------------------------------------------------------------------------- the run


def test_every_verdict_is_its_expectation(report):
    problems = report.problems()
    assert not problems, "\n".join(f"{rid}: {p}" for rid, p in problems)
    assert report.counts()["error"] == 0


def test_every_mismatch_has_a_verified_erratum(report):
    for r in report.results:
        if r.verdict == "mismatch":
            assert r.record.get("erratum"), r.id
            assert r.erratum is not None and r.erratum.verdict == "match", r.id
            assert r.outcome.diffs, f"{r.id}: a mismatch without a diff"


def test_pending_records_say_what_is_missing(report):
    for r in report.results:
        if r.verdict == "pending":
            assert any("derive/" in d for d in r.outcome.diffs), r.id


def test_errata_document_is_current(verify, report):
    want = verify.render_errata(report)
    path = ROOT / verify.ERRATA_FILE
    have = path.read_text(encoding="utf-8") if path.is_file() else ""
    if have != want:
        diff = "".join(
            difflib.unified_diff(
                have.splitlines(True), want.splitlines(True), "ERRATA.md", "ERRATA.md (derived)"
            )
        )
        pytest.fail(f"ERRATA.md is stale; run `{verify.ERRATA_COMMAND}`:\n{diff}")


# --------------------------------------------------------------------------- flips

_NUMBER = re.compile(r"(?<![A-Za-z_0-9.])\d+(?![0-9])")


def _bump(text: str) -> str:
    """The first integer literal of an expression (not part of a name like lam1) plus one;
    without one, twice the expression."""
    m = _NUMBER.search(text)
    if m is None:
        return f"2*({text})"
    return text[: m.start()] + str(int(m.group()) + 1) + text[m.end() :]


def _bump_point(rows):
    rows = copy.deepcopy(rows)
    rows[-1][0] = _bump(str(rows[-1][0]))
    return rows


def mutate(record: dict) -> tuple[dict, str]:
    """The record with one printed number changed (and a description of the change)."""
    rec = copy.deepcopy(record)
    for key in ("shape", "claimed_degree", "count", "continuity"):
        if key in rec:  # property and word claims: the one printed value
            rec[key] = _bump(rec[key])
            return rec, f"{key} -> {rec[key]}"
    if "expression" in rec and claim_kind(rec) == "formula_domain":
        rec["min_degree"] = rec.get("min_degree", 0) + 1  # a caveat: past the degenerate degree
        return rec, f"min_degree -> {rec['min_degree']}"
    if "parameter_range" in rec and "lambda" not in rec:  # one unit wider at both ends
        lo, hi = (Fraction(x) for x in re.findall(r"-?\d+(?:/\d+)?", rec["parameter_range"]))
        rec["parameter_range"] = f"[{lo - 1}, {hi + 1}]"
        return rec, f"parameter_range -> {rec['parameter_range']}"
    if "matrix" in rec:
        rec["matrix"][0][0] = int(rec["matrix"][0][0]) + 1
        return rec, "matrix[0][0] + 1"
    if "equations" in rec:
        eqs = rec["equations"]
        pos = next((k for k, e in enumerate(eqs) if _NUMBER.search(e["rhs"])), 0)
        eqs[pos]["rhs"] = _bump(eqs[pos]["rhs"])
        return rec, f"equation {pos + 1} rhs -> {eqs[pos]['rhs']}"
    if "cases" in rec:
        rec["cases"][0]["value"] = _bump(rec["cases"][0]["value"])
        return rec, f"case 1 value -> {rec['cases'][0]['value']}"
    if "ratios" in rec:
        rec["ratios"][0]["ratio"][0] = _bump(rec["ratios"][0]["ratio"][0])
        return rec, "ratio"
    if "numerator" in rec:  # energy formula: the printed scale
        rec["scale"] = _bump(rec["scale"])
        return rec, f"scale -> {rec['scale']}"
    if "lambda" in rec:
        rec["lambda"] = _bump(rec["lambda"])
        return rec, f"lambda -> {rec['lambda']}"
    if "left" in rec:
        rec["left"] = _bump_point(rec["left"])
        return rec, "last left point"
    if "result" in rec:
        rec["result"] = _bump_point(rec["result"])
        return rec, "last result point"
    if "argmax" in rec:
        rec["argmax"] = _bump(rec["argmax"])
        return rec, f"argmax -> {rec['argmax']}"
    raise AssertionError(f"no mutation for {record['id']}")


def claim_kind(record: dict) -> str:
    return record["claim"].split(".", 1)[1]


# Property claims that print no number: true for every λ whatever range one states (identities
# between the Bernstein coefficients, or a basis independent for every real λ). That their
# checkers do fail on a basis without the property is tested in tests/test_claims.py.
NO_NUMBER = {
    "basis_partition_of_unity",
    "basis_symmetric",
    "basis_endpoint_interpolation",
}
INDEPENDENT_FOR_EVERY_LAMBDA = {"001.eq2.independent", "002.bernstein.independent"}
# The classical Bernstein basis has no parameter whose range a record could state.
NO_PARAMETER = {"002.bernstein.nonnegative", "002.curve.convex_hull"}


def _has_no_number(record: dict) -> bool:
    kind = record["claim"].split(".", 1)[1]
    # a surface basis summing to one (002's affine-invariance remark) prints no number either;
    # its checker failing on a wrong basis is tested in tests/test_surface_derive.py
    unity_only = kind == "surface_basis" and "values" not in record
    return (
        kind in NO_NUMBER
        or unity_only
        or record["id"] in INDEPENDENT_FOR_EVERY_LAMBDA | NO_PARAMETER
    )


WITHOUT_NUMBER = [r["id"] for r in _RECORDS if _has_no_number(r)]


def test_records_without_a_printed_number_match(report):
    """These state a property with no number a misprint could change; that their checkers
    fail on a basis without the property is tested in tests/test_claims.py."""
    by_id = {r.id: r for r in report.results}
    assert WITHOUT_NUMBER and all(by_id[rid].verdict == "match" for rid in WITHOUT_NUMBER)


@pytest.mark.parametrize("rid", [rid for rid in RECORD_IDS if rid not in WITHOUT_NUMBER])
def test_one_changed_number_flips_the_verdict(verify, report, rid):
    result = next(r for r in report.results if r.id == rid)
    record = result.record
    if result.verdict == "pending":
        assert record["expect"] == "pending"
        pytest.skip(f"{rid} is pending: {result.outcome.diffs[0]}")
    if result.verdict == "mismatch":
        fixed = verify.corrected(record)
        assert verify.check_record(fixed).verdict == "match", f"{rid}: erratum does not match"
        record = fixed
    else:
        assert result.verdict in ("match", "caveat")
    mutated, how = mutate(record)
    res = verify.check_record(mutated)
    assert res.error is None, f"{rid} ({how}): {res.error}"
    domain_caveat = result.verdict == "caveat" and claim_kind(record) == "formula_domain"
    flipped = "match" if domain_caveat else "mismatch"
    assert res.verdict == flipped, f"{rid}: changing {how} did not flip the verdict"
    assert res.outcome.diffs or flipped == "match"


# --------------------------------------------------------------------------- engine details


def test_paper_binomial_convention(expr_mod):
    C = expr_mod.paper_binomial
    assert C(5, 2) == 10 and C(3, 0) == 1 and C(3, 3) == 1
    assert C(3, -1) == 0 and C(3, 4) == 0 and C(-1, -1) == 0 and C(-2, 1) == 0


@pytest.fixture(scope="module")
def checks_mod(verify):
    """The checkers' shared machinery: registry, families, context, the examples' helpers."""
    return _verify_modules(verify, "checks_core", "claim_families", "context", "checks_examples")


def test_corner_positive_needs_one_sign_and_the_same_sign(verify, expr_mod):
    import sympy as sp

    # 000's G1 condition (Prop. 9) is checked by the same_degree family's own checks module
    own = _verify_modules(verify, "checks_same_degree")
    S = expr_mod.SYMBOLS
    l1, l2, C = S["lam1"], S["lam2"], S["C"]
    positive = own._corner_positive
    assert positive((l2 + 2) / (l1 + 2), [l1, l2])  # zeros only at λ = -2, excluded
    assert positive(C * (l1 + 3) / (C * l2 + 3 * C), [l1, l2])  # C cancels
    assert not positive(-(l2 + 2) / (l1 + 2), [l1, l2])  # one sign, but negative
    assert not positive((l2 + 2) / (-l1 - 2), [l1, l2])
    assert not positive((l2 - sp.Rational(1, 2)) / (l1 + 3), [l1, l2])  # changes sign
    assert not positive(l1**2 + 1, [l1, l2])  # not multilinear: not decided by corners
    assert not positive(C * (l1 + 3), [l1, l2])  # depends on C


def test_symbolic_zero_without_simplify(checks_mod, expr_mod):
    import sympy as sp

    S = expr_mod.SYMBOLS
    n, k = S["n"], S["k"]
    same = sp.factorial(n) / sp.factorial(n - k) - sp.ff(n, k)
    assert checks_mod.symbolic_zero(same)
    # the generic-point value proves a difference nonzero (a printed sign misprint)
    sign = (-1) ** k * sp.binomial(n, k) - sp.binomial(n, k)
    assert checks_mod._nonzero_at_sample(checks_mod.to_derive(sign))
    assert not checks_mod.symbolic_zero(sign)
    assert not checks_mod._nonzero_at_sample(checks_mod.to_derive(same))


def test_linear_solve_and_condition_sets(checks_mod, expr_mod):
    import sympy as sp

    S = expr_mod.SYMBOLS
    x, n = S["x"], S["n"]
    assert checks_mod._solve_linear(n - 2 * x, 4, x) == n / 2 - 2
    assert checks_mod._solve_linear(x**2, 1, x) is None
    assert checks_mod._solve_linear(n, 1, x) is None
    got = checks_mod._condition_set("(omega < 0) | (omega > 1/2)")
    want = sp.Union(sp.Interval.open(-sp.oo, 0), sp.Interval.open(sp.Rational(1, 2), sp.oo))
    assert got == want
    assert checks_mod._condition_set("(omega > 0) & (omega**2 < 1/4)") == sp.Interval.open(
        0, sp.Rational(1, 2)
    )


def _form(expr_mod, rows):
    """A Form Σ c·P(j) from rows [(j, {(t power, lam power): integer})], over a denominator."""
    E, S = expr_mod, expr_mod.SYMBOLS
    t, lam = E.GEN[S["t"]], E.GEN[S["lam"]]
    out = {}
    for j, coeffs, den in rows:
        poly = sum((c * t**a * lam**b for (a, b), c in coeffs.items()), E._CTX.constant(0))
        out[(("P", j),)] = E.Sc(poly, den)
    return E.Form(out)


_POLY = st.dictionaries(
    st.tuples(st.integers(0, 4), st.integers(0, 2)), st.integers(-9, 9), min_size=1, max_size=4
)
_ROWS = st.lists(
    st.tuples(st.integers(0, 5), _POLY, st.integers(1, 6)),
    min_size=1,
    max_size=4,
    unique_by=lambda row: row[0],
)


@given(a=_ROWS, b=_ROWS, c=_POLY)
def test_quadratic_form_as_one_polynomial_matches_pair_by_pair(expr_mod, a, b, c):
    """The one-polynomial path (point keys as commuting generators) gives the coefficients of
    the pair-by-pair expansion, and its integral over [0, 1] is the exact Newton-Cotes
    quadrature of the form evaluated at nodes."""
    E, t = expr_mod, expr_mod.SYMBOLS["t"]
    [coef] = _form(E, [(0, c, 1)]).terms.values()
    v = E.DotSum([(coef, _form(E, a), _form(E, b)), (E.Sc.of(-3), _form(E, b), _form(E, b))])
    keys = E._keys_of(v)
    one_poly = E._quadratic_form(*E._quadratic_poly(v, keys), keys)
    assert E.equal(one_poly, E.Form(E.quadratic_terms(v)))
    integral = E.dotsum_integral(v, t, 0, 1)
    degree = E._t_degree(v, t)
    quadrature = E.Sc.of(0)
    for x, w in E.newton_cotes(degree + 1):
        quadrature = E.v_add(quadrature, E.v_mul(E.Sc.of(w), E._at(v, t, E.Sc.of(x))))
    assert E.equal(integral, quadrature)
    # the whole-interval integral of one coefficient, by the two routes of Sc.integrate
    half = Fraction(1, 2)
    for value in one_poly.terms.values():
        split = value.integrate(t, 0, half) + value.integrate(t, half, 1)
        assert (value.integrate(t, 0, 1) - split).is_zero()
    # one changed coefficient is seen
    seven = _form(E, [(7, {(1, 0): 1}, 1)])  # t·P(7), no P(7) in v
    changed = E.DotSum([*v.terms, (E.Sc.of(1), seven, seven)])
    assert E._compare_dotsums(v, v) == []
    assert E._compare_dotsums(v, changed) != []


def test_parser_rejects_names_outside_the_table(expr_mod):
    with pytest.raises(expr_mod.ParseError):
        expr_mod.parse("b(i, n, t) + zeta")
    with pytest.raises(expr_mod.ParseError):
        expr_mod.parse("sin(t)")
    with pytest.raises(expr_mod.ParseError):
        expr_mod.parse("H(i)")
    # the table shadows SymPy's own C, E, Q, S, beta
    e = expr_mod.parse("C*E(2) + Q(1) + beta")
    assert {s.name for s in e.free_symbols} == {"C", "beta"}


def test_misprint_diff_names_what_differs(report):
    by_id = {r.id: r for r in report.results}
    eq7 = " ".join(by_id["000.eq7"].outcome.diffs)
    assert "left side" in eq7 and "B(i, n, t)" in eq7 and "B(i + 1, n, t)" in eq7
    assert "not covered" in " ".join(by_id["001.eq11"].outcome.diffs)
    assert "n=1" in by_id["002.curve.endpoint_dk.t1"].outcome.diffs[-1]


def test_energy_checks_are_pending_without_energy(verify, records, monkeypatch):
    checks = _verify_modules(verify, "checks_core")
    monkeypatch.setitem(
        checks.REQUIREMENTS,
        "energy",
        (("no_such_function",), "needs derive/formulas/energy.py (test)"),
    )
    rec = next(r for r in records if r["id"] == "000.X_3^1")
    res = verify.check_record(rec)
    assert res.verdict == "pending" and "derive/formulas/energy.py" in res.outcome.diffs[0]


# --------------------------------------------------------------------------- CLI


def _run(**kw):
    out = io.StringIO()
    rc = _verify_runner.run(out=out, progress=False, root=ROOT, **kw)
    return rc, out.getvalue()


def test_cli_text_json_markdown():
    rc, text = _run(only=["000.eq3", "001.eq11"])
    assert rc == 0
    lines = text.splitlines()
    assert lines[0].split()[:3] == ["000.eq3", "000_10ca634d356c575d.txt", "match"]
    assert any(line.split()[:3][-1] == "mismatch" for line in lines if "001.eq11" in line)
    assert "not covered" in text and "erratum" in text
    rc, js = _run(fmt="json", only=["001.eq11"])
    data = json.loads(js)
    assert rc == 0 and data["records"][0]["verdict"] == "mismatch"
    assert data["records"][0]["erratum"]["verdict"] == "match"
    rc, md = _run(fmt="markdown", only=["001.eq11"])
    assert md.startswith("| id | source | verdict | diff |")


def test_cli_strict_fails_on_expected_mismatch():
    assert _run(only=["000.eq3"], strict=True)[0] == 0
    assert _run(only=["001.eq11"], strict=True)[0] == 1


@pytest.fixture
def checkout_copy(tmp_path):
    for item in ("pyproject.toml", "derive", "generated", "ERRATA.md"):
        src = ROOT / item
        if src.is_dir():
            shutil.copytree(src, tmp_path / item, ignore=shutil.ignore_patterns("__pycache__"))
        elif src.is_file():
            shutil.copy(src, tmp_path / item)
    return tmp_path


def _edit(path, old, new):
    text = path.read_text(encoding="utf-8")
    assert old in text
    path.write_text(text.replace(old, new, 1), encoding="utf-8")


def test_cli_fails_on_a_new_discrepancy(checkout_copy, capsys):
    """A changed printed coefficient (expected to match) fails the run with a clear message."""
    toml = checkout_copy / "derive" / "published" / "000_same_degree.toml"
    _edit(toml, '"(2 + lam)*t*(1 - t)**2"', '"(3 + lam)*t*(1 - t)**2"')
    out = io.StringIO()
    rc = _verify_runner.run(out=out, progress=False, root=checkout_copy, only=["000.eq3"])
    assert rc == 1
    assert "NEW DISCREPANCY" in out.getvalue()
    assert "expectation" in capsys.readouterr().err


def test_cli_fails_when_a_misprint_matches(checkout_copy):
    toml = checkout_copy / "derive" / "published" / "002_bezier_notes.toml"
    _edit(toml, "3*bk(1, n - 3) + bk(0, n - 3))", "3*bk(1, n - 3) - bk(0, n - 3))")
    _edit(toml, "3*bk(1, 0) + bk(0, 0))", "3*bk(1, 0) - bk(0, 0))")
    out = io.StringIO()
    rc = _verify_runner.run(
        out=out, progress=False, root=checkout_copy, only=["derivative_decasteljau.examples"]
    )
    assert rc == 1 and "now MATCHES" in out.getvalue()


def test_cli_flags_a_stale_errata_file(checkout_copy, verify, report, monkeypatch, capsys):
    """A stale ERRATA.md fails the run with the command to fix it; --errata rewrites it.
    (The module's verification run is reused: the engine is not what is tested here.)"""
    monkeypatch.setattr(verify, "verify", lambda *a, **k: report)
    (checkout_copy / "ERRATA.md").write_text("stale\n", encoding="utf-8")
    out = io.StringIO()
    assert _verify_runner.run(out=out, progress=False, root=checkout_copy) == 1
    assert "ERRATA.md is stale" in out.getvalue() and "--errata" in out.getvalue()
    assert (
        _verify_runner.run(out=io.StringIO(), progress=False, root=checkout_copy, errata=True) == 0
    )
    assert (checkout_copy / "ERRATA.md").read_text(encoding="utf-8") == (
        ROOT / "ERRATA.md"
    ).read_text(encoding="utf-8")
    capsys.readouterr()


def test_progress_only_on_a_terminal(capsys):
    p = _verify_runner.Progress(enabled=False)
    p(0, 10, "x")
    p(10, 10, "")
    assert capsys.readouterr().err == ""
    p = _verify_runner.Progress(enabled=True, delay=0)
    p(0, 2, "")
    p(1, 2, "000.eq1")
    p(2, 2, "")
    err = capsys.readouterr().err
    assert "verify: 1/2 records checked (last: 000.eq1)" in err


def test_parallel_run_keeps_record_order_and_verdicts(verify, records):
    """Two workers taking records from both ends give the serial run's results, in order."""
    picked = [
        r for r in records if r["claim"].endswith(("endpoint_values", "endpoint_d1", "_list"))
    ]
    assert {r["family"] for r in picked} >= {"same_degree", "bernstein_like", "bezier"}
    serial = verify.verify(picked, index=records, jobs=1)
    parallel = verify.verify(picked, index=records, jobs=2)
    assert [r.id for r in parallel.results] == [r["id"] for r in picked]
    assert [(r.verdict, r.outcome.diffs) for r in parallel.results] == [
        (r.verdict, r.outcome.diffs) for r in serial.results
    ]


def test_a_dead_worker_is_an_error_not_a_hang(verify, records, monkeypatch):
    import os

    monkeypatch.setattr(verify, "check_record", lambda record: os._exit(3))
    with pytest.raises(RuntimeError, match="exited early"):
        verify._parallel(records[:6], 2, lambda idx, res: None)


def test_exact_functions_in_fmpq_and_fraction_agree(verify):
    """The join weights are evaluated in FLINT's fmpq (verify) and in Fraction (derive): the
    same values, the papers' binomial convention in both, and a binomial of a non-integer is
    an error rather than a truncation."""
    from fractions import Fraction

    import flint
    import sympy as sp

    package = verify.__name__.rsplit(".", 1)[0]
    algebra = importlib.import_module(package.rsplit(".", 1)[0] + ".algebra")
    n, lam = sp.symbols("n lam")
    expr = sp.binomial(n, 2) * (1 - lam) / (n + 1) - sp.Rational(1, 3)
    slow = algebra.exact_function(expr, (n, lam))
    fast = algebra.exact_function(expr, (n, lam), number=flint.fmpq)
    for deg in range(-2, 9):
        for x in (Fraction(-2, 5), 0, Fraction(7, 3)):
            if deg == -1:
                with pytest.raises(ZeroDivisionError):
                    fast(deg, x)
                continue
            want = Fraction(slow(deg, x))
            got = fast(deg, x)
            assert Fraction(int(got.p), int(got.q)) == want
    assert slow(1, 0) == Fraction(-1, 3)  # C(1, 2) = 0
    for fn in (slow, fast):
        with pytest.raises(ValueError, match="non-integer"):
            fn(Fraction(5, 2), 0)


def test_coverage_names_every_record_and_the_readme_table_is_current(verify, report):
    """The coverage inventory names only existing records and every built-in record; the
    README's table is exactly `lambda-bezier verify --coverage --format markdown`."""
    coverage = _verify_modules(verify, "coverage")
    items = coverage.load()
    verdicts = {r.id: r.verdict for r in report.results}
    assert coverage.problems(items, verdicts) == []
    assert all(it.records or it.reason for it in items)
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    start = readme.index("<!-- coverage:start -->\n") + len("<!-- coverage:start -->\n")
    table = readme[start : readme.index("<!-- coverage:end -->")]
    assert table == coverage.render(items, verdicts, markdown=True), (
        "README coverage table is stale: paste `lambda-bezier verify --coverage --format "
        "markdown` between its markers"
    )


def test_coverage_run_exits_cleanly(capsys):
    code = _verify_runner.run(coverage=True, root=ROOT, progress=False, fmt="text")
    out = capsys.readouterr().out
    assert code == 0
    assert "items in 3 documents" in out and "000.prop5 (mismatch)" in out
    assert _verify_runner.run(coverage=True, root=ROOT, only=["000"], progress=False) == 2
