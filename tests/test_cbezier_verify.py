"""verify: records about C-Bezier families (derive/verify/checks_cbezier.py, issue #30).

The records file tests/data/families/c_bezier_cubic.records.toml states partition of unity, the
end values and derivatives (orders 0..2) at t = 0 and t = alpha, the end conditions of the curve
and the symmetry, with right-hand sides computed by SymPy from the family file's formulas, and
the Gram matrix of E_1 (checked here against mpmath quadrature of the written functions),
non-negativity, independence, G1 and C1 join weights (checked here against the curves' end
derivatives by mpmath), an end derivative in half angles and E_1 of a polygon (checked here
against mpmath quadrature of |p'|^2); five records are deliberate misprints. Each verdict
must agree with its expectation, and changing a single term of a matching record must flip it
(a verdict cannot be fixed in advance). The same claims are checked on the family written on
[0, 1] (sin(alpha*t)) and on a hyperbolic family that is not a partition of unity.
"""

from __future__ import annotations

import copy
import re
from pathlib import Path

import pytest
from conftest import family_file

from lambda_bezier import examples

DATA = Path(__file__).parent / "data" / "families"
FAMILY = examples.path("c_bezier_cubic.toml")
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
        "cb.energy_matrix_e1": "match",
        "cb.energy_matrix_e1_misprint": "mismatch",
        "cb.energy_e1": "match",
        "cb.energy_e1_misprint": "mismatch",
        "cb.nonnegative": "match",
        "cb.nonnegative_wide_misprint": "mismatch",
        "cb.independence": "match",
        "cb.join_g1": "match",
        "cb.join_c1_misprint": "mismatch",
        "cb.half_angle": "match",
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
claim = "several_optimum"
location = "x"
k = 1
control_points = [["0", "0"], ["1", "2"], ["3", "3"], ["4", "0"]]
parameters = { alpha = "1" }
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
        ('{ lhs = "b(0, n, 0)", rhs = "cos(alpha/9)" }', "fractions of alpha up to alpha/8"),
        ('{ lhs = "b(0, n, 0)", rhs = "cos(t/2)" }', "not an integer multiple of t"),
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


# --------------------------------------------------------------------------- energies, joins

mp = pytest.importorskip("mpmath")
mp.mp.dps = 40


def _defn():
    import tomllib

    from derive.families import cbezier as cb

    return cb.read_table(tomllib.loads(FAMILY.read_text())["family"])


def _written_derivatives(defn, order: int):
    """b_i^(order)(t; alpha) from the file's written formulas (SymPy diff, mpmath numbers)."""
    import sympy as sp

    from derive.families import cbezier as cb

    return [
        sp.lambdify((cb.T, cb.A), sp.diff(f, cb.T, order), modules="mpmath") for f in defn.written()
    ]


def _own_derivatives(defn, order: int):
    """As `_written_derivatives`, in the family's own parameter: the file's texts read by the
    grammar as they stand (u on [0, 1] for a family written there, no change of variable)."""
    import sympy as sp

    from derive.families import cbezier as cb
    from derive.grammar import parse_formula

    out = []
    for text in defn.functions_texts:
        f = parse_formula(
            text,
            {"t": cb.T, defn.parameter: cb.A},
            {},
            elementary=True,
            frequency=(defn.parameter,),
        )
        out.append(sp.lambdify((cb.T, cb.A), sp.diff(f, cb.T, order), modules="mpmath"))
    return out


@pytest.mark.parametrize("alpha", ["0.7", "2.9"])
def test_the_printed_gram_matrix_against_quadrature(records, alpha):
    """Each printed entry (read by the records grammar, evaluated by mpmath) is the integral
    of b_i' b_j' over [0, alpha] by mpmath quadrature: the record is right independently of
    derive, so the verdict "match" is the derivation agreeing with an independent number."""
    import sympy as sp

    from derive.grammar import parse_formula

    rec = _by_id(records, "cb.energy_matrix_e1")
    a = mp.mpf(alpha)
    ders = _written_derivatives(_defn(), 1)
    sym = sp.Symbol("alpha")
    for r, row in enumerate(rec["gram"]):
        for c, text in enumerate(row):
            expr = parse_formula(text, {"alpha": sym}, {}, elementary=True, frequency=("alpha",))
            printed = sp.lambdify(sym, expr, modules="mpmath")(a)
            want = mp.quad(lambda t, r=r, c=c: ders[r](t, a) * ders[c](t, a), [0, a])
            assert abs(printed - want) < mp.mpf(10) ** -25 * (1 + abs(want)), (r, c)


def _defn_of(path: Path):
    import tomllib

    from derive.families import cbezier as cb

    return cb.read_table(tomllib.loads(path.read_text())["family"])


def _assert_joint(first, second, continuity):
    """derive's weights, evaluated in floats of mpmath, put into a curve of `second` after one
    of `first`: the joint conditions hold for the curves built from the written formulas
    (mpmath derivatives, each in its own parameter: t, or u for a family on [0, 1])."""
    import random

    import sympy as sp

    from derive.formulas import cbezier_joins as J

    n, m = first.degree, second.degree
    weights = J.weights(first, continuity, second)
    rnd = random.Random(7)
    a1, a2, g, d = mp.mpf("1.3"), mp.mpf("2.4"), mp.mpf("0.8"), mp.mpf("0.35")
    p1 = [mp.mpf(rnd.uniform(-2, 2)) for _ in range(n + 1)]  # one coordinate suffices
    p2 = [mp.mpf(rnd.uniform(-2, 2)) for _ in range(m + 1)]
    sin1, cos1 = (mp.sinh, mp.cosh) if first.hyperbolic else (mp.sin, mp.cos)
    sin2, cos2 = (mp.sinh, mp.cosh) if second.hyperbolic else (mp.sin, mp.cos)
    env = {J.A1: a1, J.S1: sin1(a1), J.C1: cos1(a1), J.A2: a2, J.S2: sin2(a2)}
    env.update({J.C2: cos2(a2), J.G_ALPHA: g, J.G_D: d})
    rows = J.ORDER[continuity] + 1
    for row in range(rows):
        value = mp.mpf(0)
        for key, w in weights.items():
            r, src, k = key.split(",")
            if int(r) == row:
                x = p1[n - int(k)] if src == "first" else p2[int(k)]
                value += sp.lambdify(list(env), w, modules="mpmath")(*env.values()) * x
        p2[row] = value
    ders1 = [_own_derivatives(first, r) for r in range(3)]
    ders2 = [_own_derivatives(second, r) for r in range(3)]
    end = 1 if first.form == "unit" else a1

    def end1(r):
        return sum(ders1[r][j](end, a1) * p1[j] for j in range(n + 1))

    def start2(r):
        return sum(ders2[r][j](0, a2) * p2[j] for j in range(m + 1))

    tol = mp.mpf(10) ** -20
    assert abs(end1(0) - start2(0)) < tol
    if continuity.startswith("C"):
        for r in range(1, rows):
            assert abs(end1(r) - start2(r)) < tol * (1 + abs(end1(r)))
    else:
        assert abs(end1(1) - g * start2(1)) < tol * (1 + abs(end1(1)))
        if continuity == "G2":
            assert abs(end1(2) - g**2 * start2(2) - d * start2(1)) < tol * (1 + abs(end1(2)))


@pytest.mark.parametrize("continuity", ["C1", "C2", "G1", "G2"])
def test_join_weights_make_the_joint(continuity):
    _assert_joint(_defn(), _defn(), continuity)


@pytest.mark.parametrize(
    ("first", "second", "continuity"),
    [
        ("c_bezier_cubic", "hc_bezier_cubic", "C2"),
        ("hc_bezier_cubic", "c_bezier_cubic", "G2"),
        ("c_bezier_cubic", "c_bezier_cubic_unit", "C2"),
        ("c_bezier_cubic_unit", "hyp_interpolating", "G1"),
    ],
)
def test_join_weights_across_families_make_the_joint(first, second, continuity):
    """Joins between two different C-Bezier families: trigonometric into hyperbolic and back,
    [0, alpha] into [0, 1], and a cubic into a degree-1 family."""
    _assert_joint(_defn_of(family_file(first)), _defn_of(family_file(second)), continuity)


_CROSS = """
[[record]]
id = "x.c1"
claim = "several_join"
location = "x"
pair = "PAIR"
continuity = "C1"
join_weights = { "0,first,0" = "1", "1,first,0" = "1 + RATIO", "1,first,1" = "-RATIO" }
"""
# P2_1 = P1_3 + c(alpha1)/h(alpha2) (P1_3 - P1_2): the end slopes of b_3 at alpha1 and of b_1
# at 0, c(x) = (1 - cos x)/(x - sin x), h(x) = (cosh x - 1)/(sinh x - x), written by hand
_C1 = "(1 - cos(alpha1))/(alpha1 - sin(alpha1))"
_H2 = "(cosh(alpha2) - 1)/(sinh(alpha2) - alpha2)"


def _cross(tmp_path, body: str):
    path = tmp_path / "r.toml"
    path.write_text('schema_version = 2\nsource = "t"\nfamily = "c_bezier_cubic"\n' + body)
    recs = records_mod.load_paths([FAMILY, DATA / "hc_bezier_cubic.toml", path])
    return report_mod.check_record(recs[0])


def test_a_join_with_another_family_is_decided(tmp_path):
    pair = "c_bezier_cubic>hc_bezier_cubic"
    right = _CROSS.replace("PAIR", pair).replace("RATIO", f"({_C1})/({_H2})")
    assert _cross(tmp_path, right).outcome.verdict == "match"
    inverted = _CROSS.replace("PAIR", pair).replace("RATIO", f"({_H2})/({_C1})")
    assert _cross(tmp_path, inverted).outcome.verdict == "mismatch"
    # h of the first curve's parameter: cosh(alpha1) is outside the trigonometric side's field
    swapped = _CROSS.replace("PAIR", pair).replace("RATIO", f"({_C1})/({_H2.replace('2', '1')})")
    res = _cross(tmp_path, swapped)
    assert res.error is not None and re.search(
        r"(sinh|cosh)\(alpha1\) is not in the field of alpha1", str(res.error)
    )
    halved = _CROSS.replace("PAIR", pair).replace("RATIO", f"({_C1})/(2*{_H2})")
    assert _cross(tmp_path, halved).outcome.verdict == "mismatch"


@pytest.mark.parametrize(
    ("pair", "message"),
    [
        ("c_bezier_cubic>bernstein", "'bernstein': joins of 'c_bezier_cubic' are decided with"),
        ("hc_bezier_cubic>hc_bezier_cubic", "with 'c_bezier_cubic' on one side"),
    ],
)
def test_a_join_with_a_family_not_decided_is_refused(tmp_path, pair, message):
    res = _cross(tmp_path, _CROSS.replace("PAIR", pair).replace("RATIO", "1"))
    assert res.error is not None and message in str(res.error), res.error


def test_box_claims_flip_and_refuse(tmp_path):
    body = """
[[record]]
id = "dep"
claim = "several_independence"
location = "x"
independent = false
[[record]]
id = "neg"
claim = "several_nonnegative"
location = "x"
nonnegative = false
"""
    got = _run(tmp_path, FAMILY, body)
    assert got == {"dep": "mismatch", "neg": "mismatch"}
    bad = body.replace("nonnegative = false", 'nonnegative = true\nbox = { beta = "(0, 1]" }')
    path = tmp_path / "r.toml"
    path.write_text('schema_version = 2\nsource = "t"\nfamily = "c_bezier_cubic"\n' + bad)
    res = report_mod.check_record(records_mod.load_paths([FAMILY, path])[1])
    assert res.error is not None and "key box" in str(res.error)


def test_half_angle_claim_flips(records):
    rec = _by_id(records, "cb.half_angle")
    rec["equations"][0]["rhs"] = rec["equations"][0]["rhs"].replace(
        "2*sin(alpha/2)*", "sin(alpha/2)*"
    )
    assert _check(rec) == "mismatch"


# --------------------------------------------------------------------------- energies of points


@pytest.mark.parametrize("alpha", ["0.4", "2.9"])
def test_the_printed_energy_against_quadrature(records, alpha):
    """cb.energy_e1's expression (read by the records grammar, evaluated by mpmath) is
    int_0^alpha |p'(t)|^2 dt by mpmath quadrature of the file's written functions, so its
    "match" is the derivation agreeing with an independent number; the misprint is not."""
    import sympy as sp

    from derive.grammar import parse_formula

    a = mp.mpf(alpha)
    ders = _written_derivatives(_defn(), 1)
    sym = sp.Symbol("alpha")

    def printed(rid: str):
        text = _by_id(records, rid)["expression"]
        expr = parse_formula(text, {"alpha": sym}, {}, elementary=True, frequency=("alpha",))
        return sp.lambdify(sym, expr, modules="mpmath")(a)

    pts = _by_id(records, "cb.energy_e1")["control_points"]
    coords = [[mp.mpf(v) for v in row] for row in pts]

    def speed2(t):
        return sum(
            sum(ders[j](t, a) * coords[j][dim] for j in range(len(coords))) ** 2
            for dim in range(len(coords[0]))
        )

    want = mp.quad(speed2, [0, a])
    assert abs(printed("cb.energy_e1") - want) < mp.mpf(10) ** -25 * (1 + abs(want))
    assert abs(printed("cb.energy_e1_misprint") - want) > mp.mpf(10) ** -3


def test_an_energy_flips_and_its_erratum_matches(records):
    rec = _by_id(records, "cb.energy_e1")
    rec["control_points"][3][1] = "2"  # y scaled by 2: E_1 gains 3 G33
    assert _check(rec) == "mismatch"
    rec = _by_id(records, "cb.energy_e1_misprint")
    rec["expression"] = rec["erratum"]["expression"]
    assert _check(rec) == "match"


def test_energies_on_the_unit_interval_and_hyperbolic(tmp_path):
    # u = t/alpha: E_1 in u is alpha times E_1 in t (u-derivatives carry alpha, du = dt/alpha)
    energy = "(1 - cos(alpha))/(alpha - sin(alpha))"
    body = """
[[record]]
id = "u.energy"
claim = "several_energy"
location = "x"
k = 1
control_points = [["1"], ["0"], ["0"], ["1"]]
expression = "alpha*ENERGY"
[[record]]
id = "u.energy_in_t"
claim = "several_energy"
location = "x"
k = 1
control_points = [["1"], ["0"], ["0"], ["1"]]
expression = "ENERGY"
"""
    got = _run(tmp_path, DATA / "c_bezier_cubic_unit.toml", body.replace("ENERGY", energy))
    assert got == {"u.energy": "match", "u.energy_in_t": "mismatch"}
    # int_0^alpha cosh(t)^2 dt / sinh(alpha)^2, written by hand
    body = """
[[record]]
id = "h.energy"
claim = "several_energy"
location = "x"
k = 1
control_points = [["0"], ["1"]]
expression = "(alpha/2 + sinh(2*alpha)/4)/sinh(alpha)**2"
[[record]]
id = "h.energy_sign"
claim = "several_energy"
location = "x"
k = 1
control_points = [["0"], ["1"]]
expression = "(alpha/2 - sinh(2*alpha)/4)/sinh(alpha)**2"
"""
    got = _run(tmp_path, DATA / "hyp_interpolating.toml", body)
    assert got == {"h.energy": "match", "h.energy_sign": "mismatch"}


@pytest.mark.parametrize(
    ("extra", "message"),
    [
        (
            'k = 1\ncontrol_points = [["0"], ["1"], ["2"], ["3"]]\nparameters = { alpha = "1" }\n'
            'expression = "1"',
            "key parameters: E_1 of 'c_bezier_cubic' is claimed as a function",
        ),
        ('k = 1\ncontrol_points = [["0"], ["1"], ["2"]]\nexpression = "1"', "4 points"),
        ('k = 4\ncontrol_points = [["0"], ["1"], ["2"], ["3"]]\nexpression = "1"', "key k"),
        ('k = 1\ncontrol_points = [["0"], ["1"], ["2"], ["3"]]', "key expression"),
        ('k = 1\ncontrol_points = [["0"], ["1"], ["2"], ["3"]]\nexpression = "t"', "depends on t"),
        (
            'k = 1\ncontrol_points = [["0"], ["x"], ["2"], ["3"]]\nexpression = "1"',
            "control_points",
        ),
    ],
)
def test_bad_energy_records_are_record_errors(tmp_path, extra, message):
    body = '\n[[record]]\nid = "e"\nclaim = "several_energy"\nlocation = "x"\n' + extra + "\n"
    path = tmp_path / "r.toml"
    path.write_text('schema_version = 2\nsource = "t"\nfamily = "c_bezier_cubic"\n' + body)
    (rec,) = records_mod.load_paths([FAMILY, path])
    res = report_mod.check_record(rec)
    assert res.error is not None and message in str(res.error), res.error
