"""Closed forms in n of families in several parameters over a range of degrees and of indexed
families (issue #30; derive/families/closed_n.py, derive/formulas/joins_closed_n.py).

The forms and weights are read from the committed documents and checked against independent
numerics: Han, Ma and Huang's piecewise basis (Hu-Bo-Qin eq. (1), written out in
tests/test_indexed_families.py) evaluated with mpmath, its end derivatives by finite
differences, at degrees inside the range and far beyond it (where only the derivation for a
general n speaks for them), and the joined curves' conditions checked the same way. Inside
the range, the runtime's joins by the closed-form weights equal the per-degree solve exactly.
"""

from __future__ import annotations

import json
import random
from fractions import Fraction
from pathlib import Path

import mpmath
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st
from test_indexed_families import assert_documents_current, file_to_paper, paper_basis

import lambda_bezier as lb
from lambda_bezier import _derived_joins

DATA = Path(__file__).parent / "data" / "families"
DOCS = {
    name: json.loads((DATA / f"{name}.derived.json").read_text(encoding="utf-8"))
    for name in ("q_bezier", "two_end_bezier")
}
N = sp.Symbol("n")


def _values(name: str, n: int, rng: random.Random) -> list[Fraction]:
    """The file's parameter per index 1..n (two_end_bezier: lam at 1, mu at n, 0 between)."""
    if name == "q_bezier":
        return [Fraction(rng.randint(-9, 9), rng.randint(1, 7)) for _ in range(n)]
    lam, mu = (Fraction(rng.randint(-9, 9), rng.randint(1, 7)) for _ in range(2))
    return [lam, *([Fraction(0)] * (n - 2)), mu]


def _symbol_values(name: str, n: int, lam: list[Fraction], side: str = "") -> dict[str, Fraction]:
    """The document's symbols at degree n: lam(k), lam(n-k) (indexed) or lam, mu."""
    if name == "two_end_bezier":
        return {f"lam{side}": lam[0], f"mu{side}": lam[-1]}
    out = {}  # an index outside 1..n reads as 0 (lam(3) at n = 2)
    out.update({f"lam({k}){side}": Fraction(0) for k in range(n + 1, 9)})
    out.update({f"lam(n-{k}){side}": Fraction(0) for k in range(n, 9)})
    for k in range(1, n + 1):
        out[f"lam({k}){side}"] = lam[k - 1]
        out[(f"lam(n){side}" if k == n else f"lam(n-{n - k}){side}")] = lam[k - 1]
    return out


def _direct(n: int, lam: list[Fraction]):
    """b_0..b_n at t by the paper's piecewise formula (the file's parameters per index
    converted to the paper's l_i), with mpmath numbers."""
    ell = file_to_paper(n, [mpmath.mpf(v.numerator) / v.denominator for v in lam])
    return lambda t: paper_basis(n, ell, t)


def _form(text: str, values: dict[str, Fraction]) -> Fraction:
    """A document's formula (in n, m, alpha, d and the symbols of `values`) at these values:
    the names with parentheses (lam(n-1)) become plain ones before SymPy reads the text."""
    safe = {}
    for k, name in enumerate(sorted(values, key=len, reverse=True)):
        text = text.replace(name, f"v{k}_")
        safe[f"v{k}_"] = values[name]
    expr = sp.sympify(text, locals={x: sp.Symbol(x) for x in safe})
    got = expr.subs(
        {sp.Symbol(x): sp.Rational(v.numerator, v.denominator) for x, v in safe.items()}
    )
    return Fraction(int(got.p), int(got.q))


@pytest.mark.parametrize("name", sorted(DOCS))
@pytest.mark.parametrize("n", [2, 3, 4, 5, 6, 9, 13])
def test_end_forms_match_finite_differences(name, n):
    """d^r b_j(0) and d^r b_(n-j)(1), r = 0..3, by mpmath finite differences of the paper's
    basis, equal the document's closed forms at every n >= valid_from[r], inside and beyond
    the range of degrees."""
    closed = DOCS[name]["closed_n"]
    rng = random.Random(n * 31 + len(name))
    lam = _values(name, n, rng)
    mpmath.mp.dps = 40  # before _direct converts lam: another test may have left it lower
    basis = _direct(n, lam)
    values = _symbol_values(name, n, lam)
    checked = 0
    for key, text in closed["forms"].items():
        end, r, j = key.split(",")
        r, j = int(r), int(j)
        if n < closed["valid_from"][str(r)] or j > n:
            continue
        idx, at = (j, 0) if end == "start" else (n - j, 1)
        fd = mpmath.diff(lambda t, idx=idx: basis(t)[idx], at, r)
        want = _form(text, {**values, "n": Fraction(n)})
        assert abs(fd - mpmath.mpf(want.numerator) / want.denominator) < 1e-25, (key, n)
        checked += 1
    assert checked >= 6
    # every end derivative the forms leave out is 0 (the forms are complete)
    for end, at in (("start", 0), ("end", 1)):
        for r in range(4):
            if n < closed["valid_from"][str(r)]:
                continue
            for idx in range(n + 1):
                j = idx if end == "start" else n - idx
                if f"{end},{r},{j}" not in closed["forms"]:
                    assert abs(mpmath.diff(lambda t, idx=idx: basis(t)[idx], at, r)) < 1e-25


def test_valid_from_is_the_least_degree():
    """Below valid_from[r] (inside the range) some end derivative of order <= r differs from
    its closed form: the bound is where the forms stop holding, not a guess. (q_bezier's
    forms hold from its lowest degree on, where the test above checks them.)"""
    assert set(DOCS["q_bezier"]["closed_n"]["valid_from"].values()) == {2}
    name = "two_end_bezier"
    closed = DOCS[name]["closed_n"]
    low = DOCS[name]["degrees"][0]
    mpmath.mp.dps = 40
    seen = 0
    for r in range(4):
        n = closed["valid_from"][str(r)] - 1
        if n < low:
            continue
        lam = _values(name, n, random.Random(5))
        basis, values = _direct(n, lam), {**_symbol_values(name, n, lam), "n": Fraction(n)}
        gaps = []
        for key, text in closed["forms"].items():
            end, rr, j = key.split(",")
            if int(rr) > r or int(j) > n:
                continue
            idx, at = (int(j), 0) if end == "start" else (n - int(j), 1)
            fd = mpmath.diff(lambda t, idx=idx, f=basis: f(t)[idx], at, int(rr))
            want = _form(text, values)
            gaps.append(abs(fd - mpmath.mpf(want.numerator) / want.denominator))
        assert max(gaps) > 1e-6, (r, n)
        seen += 1
    assert seen == 2  # orders 2 and 3


def _ends(basis, points, at: int, orders: int) -> list[list[mpmath.mpf]]:
    """p^(r)(at), r = 0..orders, of sum P_i b_i by finite differences."""
    out = []
    for r in range(orders + 1):
        out.append(
            [
                mpmath.diff(
                    lambda t, c=c: sum(p[c] * b for p, b in zip(points, basis(t), strict=True)),
                    at,
                    r,
                )
                for c in range(2)
            ]
        )
    return out


JOIN_CASES = [("C1", 1, 1, 0), ("G1", 1, Fraction(3, 2), 0), ("C2", 2, 1, 0)]
JOIN_CASES.append(("G2", 2, Fraction(2, 3), Fraction(-1, 2)))


@pytest.mark.parametrize("name", sorted(DOCS))
@pytest.mark.parametrize(("cont", "order", "alpha", "d"), JOIN_CASES)
@pytest.mark.parametrize(("n", "m"), [(3, 5), (11, 9), (7, 14)])
def test_closed_weights_join_by_finite_differences(name, cont, order, alpha, d, n, m):
    """The document's weights in n and m, at degrees inside and far beyond the range, give a
    second curve whose end derivatives (finite differences of the paper's basis) meet the
    first curve's as the continuity says."""
    table = DOCS[name]["joins"]
    rng = random.Random(n * 100 + m)
    lam1, lam2 = _values(name, n, rng), _values(name, m, rng)
    values = {
        **_symbol_values(name, n, lam1, "1"),
        **_symbol_values(name, m, lam2, "2"),
        "n": n,
        "m": m,
        "alpha": alpha,
        "d": d,
    }
    weights = _derived_joins.lookup(table, f"{name}>{name}", cont, values)
    assert weights is not None
    p1 = [(Fraction(rng.randint(-9, 9)), Fraction(rng.randint(-9, 9))) for _ in range(n + 1)]
    p2 = [None] * (m + 1)
    for k in range(order + 1, m + 1):
        p2[k] = (Fraction(rng.randint(-9, 9)), Fraction(rng.randint(-9, 9)))
    for r in range(order + 1):
        p2[r] = tuple(
            sum(
                (w * (p1[n - k][c] if src == "first" else p2[k][c]))
                for (row, src, k), w in weights.items()
                if row == r
            )
            for c in range(2)
        )
    mpmath.mp.dps = 40
    e1 = _ends(_direct(n, lam1), p1, 1, order)
    s2 = _ends(_direct(m, lam2), p2, 0, order)
    a, dd = mpmath.mpf(alpha.numerator) / alpha.denominator, mpmath.mpf(d.numerator) / d.denominator
    for c in range(2):
        assert abs(e1[0][c] - s2[0][c]) < 1e-20
        assert abs(e1[1][c] - a * s2[1][c]) < 1e-20
        if order == 2:
            assert abs(e1[2][c] - (a**2 * s2[2][c] + dd * s2[1][c])) < 1e-18


def _spy(monkeypatch) -> list:
    used: list = []
    real = _derived_joins.lookup
    monkeypatch.setattr(_derived_joins, "lookup", lambda *a: used.append(a[2]) or real(*a))
    return used


@pytest.mark.parametrize(("cont", "order", "alpha", "d"), JOIN_CASES)
@pytest.mark.parametrize(("n", "m"), [(2, 2), (3, 7), (8, 4), (5, 5)])
def test_runtime_joins_use_the_closed_weights_where_they_hold(
    cont, order, alpha, d, n, m, monkeypatch
):
    """two_end_bezier (one document over degrees 2..8): lb.join takes the weights in closed
    form in n, m where valid_from says they hold at both degrees, and they give exactly the
    per-degree solve's points; below valid_from (C2/G2 into or out of degree 2) the runtime
    solves per degree."""
    fam = lb.load_family(DATA / "two_end_bezier.toml")
    rng = random.Random(n * 10 + m)
    pts = [(rng.randint(-9, 9), rng.randint(-9, 9)) for _ in range(n + 1)]
    first = fam.curve(pts, lam=Fraction(1, 3), mu=Fraction(-1, 2))
    rest = [(rng.randint(-9, 9), rng.randint(-9, 9)) for _ in range(m - order)]
    kw = {"alpha": alpha, "d": d} if cont.startswith("G") else {}
    if m < order:
        return
    used = _spy(monkeypatch)
    got = lb.join(first, cont, m, family=fam, lam=Fraction(-1, 4), mu=1, rest=rest, **kw)
    holds = min(n, m) >= DOCS["two_end_bezier"]["joins"]["valid_from"][str(order)]
    assert used == ([cont] if holds else [])
    monkeypatch.setattr(_derived_joins, "lookup", lambda *a: None)
    want = lb.join(first, cont, m, family=fam, lam=Fraction(-1, 4), mu=1, rest=rest, **kw)
    assert got.points.tolist() == want.points.tolist()


def _definition(tmp_path: Path, name: str, body: str):
    from derive.families.definition import read_definition

    path = tmp_path / f"{name}.toml"
    path.write_text(f'schema_version = 2\n[family]\nname = "{name}"\n{body}')
    return read_definition(path)


def test_a_basis_outside_the_derivation_keeps_a_reason(tmp_path):
    """Closed forms in n need one formula in i and n whose order of vanishing at each end is
    i + c (n - i + c): a basis without one is left per degree, with the reason in the
    document."""
    from derive.emit.closed_n import section

    common = (
        'parameters = ["lam", "mu"]\nrange = { lam = "[0, 1]", mu = "[0, 1]" }\ndegrees = "2..6"\n'
    )
    # b_i carries t**(n - i) first: its order at t = 0 is not i + c
    flipped = _definition(
        tmp_path,
        "flipped",
        common + 'basis = "binomial(n, i)*t**(n - i)*(1 - t)**i*(1 + lam*mu*0)"\n',
    )
    closed, joins_table = section(flipped)
    assert "order" in closed["reason"] and "reason" in joins_table
    good = _definition(
        tmp_path,
        "good",
        common + 'basis = "binomial(n, i)*t**i*(1 - t)**(n - i)'
        '*(1 + (lam*binomial(0, i - 1) - lam*binomial(0, i))*0)"\n',
    )
    closed, _ = section(good)
    assert closed["valid_from"] == {"0": 2, "1": 2, "2": 2, "3": 2}
    assert closed["forms"]["start,1,0"] == "-n"


def test_a_claim_true_on_the_range_but_not_for_general_n_is_caught():
    """An end tangent plus (n - 2)(n - 3)(n - 4)(n - 5)(P(1) - P(0)) holds at every degree
    2..5 of q_bezier, and the per-degree check passes it; the closed forms in n do not."""
    records_mod = pytest.importorskip("derive.verify.records")
    report_mod = pytest.importorskip("derive.verify.report")
    files = [DATA / "q_bezier.toml", DATA / "q_bezier_4.toml", DATA / "q_bezier.records.toml"]
    rec = next(r for r in records_mod.load_paths(files) if r["id"] == "qb.ends_n")
    rec["equations"] = [
        {
            "lhs": "Subs(Derivative(p(t), t), t, 0)",
            "rhs": "(n + lam(1) + (n - 2)*(n - 3)*(n - 4)*(n - 5))*(P(1) - P(0))",
        }
    ]
    res = report_mod.check_record(rec)
    assert res.verdict == "mismatch"
    assert all("for general n" in d for d in res.outcome.diffs)
    rec["equations"][0]["rhs"] = "(n + lam(1))*(P(1) - P(0))"
    assert report_mod.check_record(rec).verdict == "match"


@pytest.mark.parametrize("seed", ["0", "4242"])
@pytest.mark.parametrize("name", ["two_end_bezier", "q_bezier"])
def test_documents_are_current_under_two_hash_seeds(name, seed):
    # one family and seed per test: each is a derivation in its own process, which
    # pytest-xdist spreads over the workers (the four in one test took 570 s at load ~17)
    assert_documents_current(DATA / f"{name}.toml", seeds=(seed,))


def test_a_join_record_at_a_degree_outside_the_range_is_refused():
    records_mod = pytest.importorskip("derive.verify.records")
    report_mod = pytest.importorskip("derive.verify.report")
    files = [DATA / "two_end_bezier.toml", DATA / "two_end_bezier.records.toml"]
    rec = next(r for r in records_mod.load_paths(files) if r["id"] == "te.join_c1_at_3")
    rec["n"] = 9
    res = report_mod.check_record(rec)
    assert res.error is not None and "key n" in str(res.error)


@settings(max_examples=4, deadline=None)
@given(
    a=st.integers(1, 2),
    b=st.integers(0, 1),
    c=st.fractions(min_value=-3, max_value=3, max_denominator=5).filter(lambda x: x != 0),
    n=st.integers(2, 12),
)
def test_random_families_against_a_direct_derivation(a, b, c, n):
    """Random two-parameter families over degrees 2..6 (Bernstein plus a telescoping term in
    lam at index a and mu at index n - b, so the functions sum to 1): the closed forms in n at
    a random degree, inside or beyond the range, equal the end derivatives of the formula
    expanded directly by SymPy at that degree (no derive code)."""
    from derive.algebra import n as n_sym
    from derive.families.closed_n import closed_forms
    from derive.families.definition import definition_from_table

    ell = f"(lam*binomial(0, {{k}} - {a}) + mu*binomial(0, n - {{k}} - {b}))"
    text = (
        f"t**i*(1 - t)**(n - i)*(binomial(n, i) + ({c})*({ell.format(k='i')}*(1 - t)"
        f" - {ell.format(k='(i + 1)')}*t))"
    )
    table = {
        "name": "random_two",
        "parameters": ["lam", "mu"],
        "range": {"lam": "[-1, 1]", "mu": "[-1, 1]"},
        "degrees": "2..6",
        "degree_offset": 1,
        "basis": text,
    }
    closed = closed_forms(definition_from_table(table))
    assert not isinstance(closed, str), closed
    t, lam, mu = sp.symbols("t lam mu")

    def paper_binomial(x, y):
        x, y = int(x), int(y)
        return sp.Integer(0) if not 0 <= y <= x else sp.binomial(x, y)

    for r in range(4):
        if n < closed.valid_from[r]:
            continue
        for i in range(n + 1):
            ell_i = [
                lam * paper_binomial(0, k - a) + mu * paper_binomial(0, n - k - b)
                for k in (i, i + 1)
            ]
            bi = (
                t**i
                * (1 - t) ** (n - i)
                * (
                    sp.binomial(n, i)
                    + sp.Rational(c.numerator, c.denominator) * (ell_i[0] * (1 - t) - ell_i[1] * t)
                )
            )
            d = sp.diff(bi, t, r)
            for key, at in ((("start", r, i)), 0), ((("end", r, n - i)), 1):
                want = sp.expand(d.subs(t, at))
                got = sp.expand(closed.forms.get(key, sp.Integer(0)).xreplace({n_sym: n}))
                assert sp.expand(got - want) == 0, (key, n, got, want)
