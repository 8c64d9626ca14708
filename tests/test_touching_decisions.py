"""The cases of independence and non-negativity over the parameter box that were left
undecided before (issue #30), decided now by derive/formulas/real_box.py, touching.py and
atom_independence.py: a function that touches zero inside its domain (polynomial,
trigonometric not affine in its parameter, mixed), and a rank that drops at an irrational
point of a box of three parameters. Each family is defined only by its file in
tests/data/families/; each verdict is checked against independent numerics (mpmath) or exact
SymPy, and the reasons the old searches gave are gone from every committed document."""

from __future__ import annotations

import json
from fractions import Fraction
from pathlib import Path

import mpmath as mp
import pytest
import sympy as sp

from derive.emit.document import derive as derive_document
from derive.families.definition import read_definition
from derive.families.engine import basis_polys
from derive.formulas import box, real_box
from derive.formulas.several_box import _odd_part

ROOT = Path(__file__).resolve().parent.parent
DATA = ROOT / "tests" / "data" / "families"
EXAMPLES = ROOT / "src" / "lambda_bezier" / "examples"
mp.mp.dps = 40
F = Fraction
t, lam, mu = sp.symbols("t lam mu")


def _doc(name: str) -> dict:
    return json.loads((DATA / f"{name}.derived.json").read_text(encoding="utf-8"))


# --------------------------------------------------------------------------- the documents


def _verdicts(doc: dict) -> list:
    return [doc.get("nonnegative_over_box"), doc.get("singular_parameters")] + [
        doc.get("linear_independence")
    ]


@pytest.mark.parametrize(
    "path", sorted([*DATA.glob("*.derived.json"), *EXAMPLES.glob("*.derived.json")])
)
def test_no_document_is_left_undecided(path):
    """No committed family document carries a reason for independence or non-negativity."""
    doc = json.loads(path.read_text(encoding="utf-8"))
    for verdict in _verdicts(doc):
        assert not (isinstance(verdict, dict) and "reason" in verdict), (path.name, verdict)
        if isinstance(verdict, dict):
            assert verdict.get("nonnegative", True) is not None
            assert verdict.get("independent", True) is not None


@pytest.mark.parametrize(
    "name",
    [
        "touch_two_shape_quadratic",
        "touch_trig_quadratic",
        "touch_mixed_quadratic",
        "three_shape_trig_quadratic",
        "line_three_trig_quadratic",
        "touch_hyp_quadratic",
        "touch_point_quadratic",
    ],
)
def test_committed_documents_of_the_new_families_are_current(name):
    # one derivation per test, so that pytest-xdist spreads the seven over the workers
    derived = derive_document(read_definition(DATA / f"{name}.toml"))
    assert json.loads(json.dumps(derived)) == _doc(name), name


# --------------------------------------------------------------------------- polynomial, touching


def _touch_two(tv, lv, mv):
    """touch_two_shape_quadratic.toml's functions, written out again."""
    g = (3 * tv - 1) ** 2 - lv * mv
    return [(1 - tv) * (1 - tv * g / 8), tv * (1 - tv) * g / 4, tv * (1 - (1 - tv) * g / 8)]


def test_polynomial_touching_zero_is_decided_exactly():
    """b_1 = t (1 - t) ((3t - 1)^2 - lam mu) / 4 touches 0 at t = 1/3 on the faces lam = 0 and
    mu = 0: the Bernstein search cannot settle it, the cells off the discriminant can."""
    defn = read_definition(DATA / "touch_two_shape_quadratic.toml")
    b1 = basis_polys(defn, 2)[1]
    odd, _ = _odd_part(b1)
    t_box = [(F(0), F(1)), (F(-1), F(0)), (F(0), F(1))]
    assert box.sign_over_box(odd, t_box, strict=False)["holds"] is None  # the old stop
    verdict = _doc("touch_two_shape_quadratic")["nonnegative_over_box"]
    assert verdict["nonnegative"] is True
    assert "discriminant" in verdict["method"]
    assert b1.eval((sp.Rational(1, 3), 0, sp.Rational(1, 2))) == 0  # it does touch zero
    for lv in mp.linspace(-1, 0, 7):
        for mv in mp.linspace(0, 1, 7):
            for tv in mp.linspace(0, 1, 61):
                assert min(_touch_two(tv, lv, mv)) > -(mp.mpf(10) ** -30)


def test_polynomial_touching_widened_gives_an_exact_counterexample(tmp_path):
    """With mu down to -1/10, lam mu > 0 somewhere and b_1 < 0 near t = 1/3."""
    text = (DATA / "touch_two_shape_quadratic.toml").read_text(encoding="utf-8")
    path = tmp_path / "w.toml"
    path.write_text(text.replace('mu = "[0, 1]"', 'mu = "[-1/10, 1]"'), encoding="utf-8")
    cx = derive_document(read_definition(path))["nonnegative_over_box"]["counterexample"]
    values = _touch_two(
        *(
            mp.mpf(Fraction(cx[k]).numerator) / Fraction(cx[k]).denominator
            for k in ("t", "lam", "mu")
        )
    )
    assert values[cx["i"]] < 0


def test_polynomial_rank_drops_at_a_touching_point():
    """touch_point_quadratic: c = (lam - 1/3)^2 + (mu - 1/3)^2 touches zero at one point of
    the box. Both verdicts were reasons before; now the point is exact, SymPy confirms the
    rank drops there (b_1 = 0), and mpmath that every function is >= 0."""
    doc = _doc("touch_point_quadratic")
    cx = doc["singular_parameters"]["counterexample"]
    assert (cx["lam"], cx["mu"]) == ("1/3", "1/3")
    defn = read_definition(DATA / "touch_point_quadratic.toml")
    polys = basis_polys(defn, 2)
    at = {lam: sp.Rational(1, 3), mu: sp.Rational(1, 3)}
    rows = [sp.Poly(p.as_expr().xreplace(at), t).all_coeffs() for p in polys]
    width = max(len(r) for r in rows)
    mat = sp.Matrix([[0] * (width - len(r)) + r for r in rows])
    assert mat.rank() < 3
    assert doc["nonnegative_over_box"]["nonnegative"] is True
    for lv in mp.linspace(0, 1, 7):
        for mv in mp.linspace(0, 1, 7):
            c = (lv - mp.mpf(1) / 3) ** 2 + (mv - mp.mpf(1) / 3) ** 2
            for tv in mp.linspace(0, 1, 41):
                values = [(1 - tv) * (1 - tv * c), 2 * tv * (1 - tv) * c, tv * (1 - (1 - tv) * c)]
                assert min(values) >= 0


@pytest.mark.parametrize(
    ("expr", "ranges", "holds"),
    [
        ((3 * t - 1) ** 2 - lam * mu, [(-1, 0), (0, 1)], True),
        ((3 * t - 1 - lam) ** 2 + (lam - mu) ** 2, [(0, 1), (-1, 1)], True),  # inner curve
        ((3 * t - 1 - lam) ** 2 + (lam - mu) ** 2 - mu**4 / 100, [(0, 1), (-1, 1)], False),
        ((3 * t - 1) ** 2 + lam * mu, [(-1, 0), (0, 1)], False),
        (t * (1 - t) * ((2 * t - 1) ** 2 - lam**2 * mu), [(-1, 1), (-1, 0)], True),
    ],
)
def test_nonnegative_poly_against_sympy(expr, ranges, holds):
    """The verdict, and a counterexample where SymPy evaluates the polynomial < 0 exactly."""
    poly = sp.Poly(expr, t, lam, mu)
    got = real_box.nonnegative_poly(poly, [(F(0), F(1)), *[(F(a), F(b)) for a, b in ranges]])
    assert got["holds"] is holds
    if not holds:
        point = got["point"]
        assert 0 <= point[0] <= 1
        assert all(F(a) <= v <= F(b) for v, (a, b) in zip(point[1:], ranges, strict=True))
        assert expr.subs(dict(zip((t, lam, mu), map(sp.Rational, point), strict=True))) < 0


# --------------------------------------------------------------------------- trigonometric


def _touch_trig(tv, lv):
    q = (mp.sin(tv) - lv * mp.cos(tv)) ** 2
    return [(1 - q / 8) * (1 - mp.sin(tv)), q / 8, (1 - q / 8) * mp.sin(tv)]


def test_trigonometric_touching_curve_is_decided_exactly():
    verdict = _doc("touch_trig_quadratic")["nonnegative_over_box"]
    assert verdict["nonnegative"] is True
    assert "half-angle" in verdict["method"]
    for lv in mp.linspace(mp.mpf(1) / 2, 1, 9):
        assert _touch_trig(mp.atan(lv), lv)[1] < mp.mpf(10) ** -35  # the touching point
        for tv in mp.linspace(0, mp.pi / 2, 81):
            assert min(_touch_trig(tv, lv)) > -(mp.mpf(10) ** -30)


def test_trigonometric_touching_widened_gives_a_counterexample(tmp_path):
    """b_0 = (1 - q/8)(1 - sin t) < 0 once q > 8: lam up to 4 (q(pi/2... 0) = lam^2 = 16)."""
    text = (DATA / "touch_trig_quadratic.toml").read_text(encoding="utf-8")
    path = tmp_path / "w.toml"
    path.write_text(text.replace('range = "[1/2, 1]"', 'range = "[1/2, 4]"'), encoding="utf-8")
    verdict = derive_document(read_definition(path))["nonnegative_over_box"]
    cx = verdict["counterexample"]
    assert verdict["nonnegative"] is False
    tv = _time(cx["t"])
    assert min(_touch_trig(tv, _mpq(cx["lam"]))) < 0


def _mpq(text: str):
    q = Fraction(text)
    return mp.mpf(q.numerator) / q.denominator


def _time(text: str):
    """'x0*pi + 2*atan(u)/(1)' or a rational multiple of pi (the document's forms)."""
    if "atan" in text:
        head, rest = text.split(" + 2*atan(")
        u, rate = rest.split(")/(")
        return _time(head) + 2 * mp.atan(_mpq(u)) / _mpq(rate.rstrip(")"))
    return mp.pi * _mpq(text[: -len("*pi")]) if text.endswith("*pi") else _mpq(text)


# --------------------------------------------------------------------------- hyperbolic


def _touch_hyp(tv, lv):
    q = (mp.sinh(tv) - lv * mp.cosh(tv)) ** 2 / 8
    return [(1 - q) * mp.exp(-tv), q, (1 - q) * (1 - mp.exp(-tv))]


def test_hyperbolic_touching_curve_is_decided_exactly():
    verdict = _doc("touch_hyp_quadratic")["nonnegative_over_box"]
    assert verdict["nonnegative"] is True
    assert "e^(w t)" in verdict["method"]
    for lv in mp.linspace(mp.mpf(1) / 4, mp.mpf(1) / 2, 9):
        assert _touch_hyp(mp.atanh(lv), lv)[1] < mp.mpf(10) ** -35  # the touching point
        for tv in mp.linspace(0, 1, 81):
            assert min(_touch_hyp(tv, lv)) > -(mp.mpf(10) ** -30)


def test_hyperbolic_touching_widened_gives_a_counterexample(tmp_path):
    """lam up to 3: q = (sinh t - lam cosh t)^2/8 > 1 somewhere, and b_0 < 0 there (found by
    the ball search or the exact form, whichever ends first)."""
    text = (DATA / "touch_hyp_quadratic.toml").read_text(encoding="utf-8")
    path = tmp_path / "w.toml"
    path.write_text(text.replace('range = "[1/4, 1/2]"', 'range = "[1/4, 3]"'), encoding="utf-8")
    cx = derive_document(read_definition(path))["nonnegative_over_box"]["counterexample"]
    text = cx["t"]
    tv = mp.log(_mpq(text[len("log(") : -1])) if text.startswith("log(") else _mpq(text)
    assert 0 <= tv <= 1
    assert _touch_hyp(tv, _mpq(cx["lam"]))[cx["i"]] < 0


# --------------------------------------------------------------------------- mixed


def _touch_mixed(tv, lv):
    q = lv * (1 - mp.cos(4 * mp.pi * tv)) / 10
    return [1 - tv - q, 2 * q, tv - q]


def test_mixed_touching_point_is_certified():
    """b_1 = lam (1 - cos 4 pi t)/5 has a double zero at t = 1/2 for every lam: certified."""
    assert _doc("touch_mixed_quadratic")["nonnegative_over_box"] == {"nonnegative": True}
    for lv in mp.linspace(mp.mpf(1) / 100, 1, 9):
        assert _touch_mixed(mp.mpf(1) / 2, lv)[1] == 0
        for tv in mp.linspace(0, 1, 201):
            assert min(_touch_mixed(tv, lv)) > -(mp.mpf(10) ** -30)


def test_mixed_touching_widened_is_not_certified_wrongly(tmp_path):
    """With lam up to 3, b_0 = 1 - t - q < 0 near t = 1/4 (q = 3/5 there): a counterexample,
    not a certificate around the touching point at t = 1/2."""
    text = (DATA / "touch_mixed_quadratic.toml").read_text(encoding="utf-8")
    path = tmp_path / "w.toml"
    path.write_text(text.replace('range = "(0, 1]"', 'range = "(0, 3]"'), encoding="utf-8")
    verdict = derive_document(read_definition(path))["nonnegative_over_box"]
    cx = verdict["counterexample"]
    assert min(_touch_mixed(_mpq(cx["t"]), _mpq(cx["lam"]))) < 0


# --------------------------------------------------------------------------- independence


def _three(tv, lv, mv, nv):
    s, c = mp.sin(tv), mp.cos(tv)
    b0 = 1 - s + (mv**2 - 3) * (c - 1)
    b1 = (lv + nv) * (s + c - 1)
    return [b0, b1, 1 - b0 - b1]


def _gram_det(functions, lv, mv, nv):
    """det of the Gram matrix of the three `functions(t, lam, mu, nu)` on [0, pi/2] by mpmath
    quadrature (the matrix is symmetric: each product is integrated once)."""
    gram = mp.matrix(3, 3)
    for i in range(3):
        for j in range(i, 3):
            gram[i, j] = gram[j, i] = mp.quad(
                lambda x, i=i, j=j: functions(x, lv, mv, nv)[i] * functions(x, lv, mv, nv)[j],
                [0, mp.pi / 2],
            )
    return mp.det(gram)


def test_three_parameters_irrational_singular_point():
    verdict = _doc("three_shape_trig_quadratic")["linear_independence"]
    assert verdict["independent"] is False
    (point,) = verdict["singular"]
    assert sp.sympify(point["mu"]) == sp.sqrt(2)  # our own output, a plain number
    assert abs(float(point["mu_float"]) - 2**0.5) < 1e-15
    lv, nv = _mpq(point["lam"]), _mpq(point["nu"])
    assert abs(_gram_det(_three, lv, mp.sqrt(2), nv)) < mp.mpf(10) ** -30
    assert abs(_gram_det(_three, lv, mp.sqrt(2) + mp.mpf(1) / 10, nv)) > mp.mpf(10) ** -6


def _line(tv, lv, mv, nv):
    b1 = (lv - mv) * (1 - mp.cos(tv)) + (mv - nv) * mp.sin(2 * tv)
    return [1 - mp.sin(tv) - b1 / 2, b1, mp.sin(tv) - b1 / 2]


def test_three_parameters_dependent_on_a_line():
    """The rank drops on the segment lam = mu = nu (a curve: neither points nor a surface);
    the point reported lies on it, where mpmath's Gram determinant vanishes, and off it the
    determinant does not."""
    verdict = _doc("line_three_trig_quadratic")["linear_independence"]
    assert verdict["independent"] is False
    (point,) = verdict["singular"]
    lv, mv, nv = (Fraction(point[k]) for k in ("lam", "mu", "nu"))
    assert lv == mv == nv and F(1, 2) <= nv <= 1

    half, three_quarters = mp.mpf(1) / 2, mp.mpf(3) / 4
    on_line = (mp.mpf(v.numerator) / v.denominator for v in (lv, mv, nv))
    assert abs(_gram_det(_line, *on_line)) < 1e-30
    assert abs(_gram_det(_line, half, half, three_quarters)) > 1e-8  # lam = mu only
    assert abs(_gram_det(_line, three_quarters, half, half)) > 1e-8  # mu = nu only


def test_three_parameters_independent_box(tmp_path):
    """mu in [3/2, 2] misses sqrt(2): independent over the whole box."""
    text = (DATA / "three_shape_trig_quadratic.toml").read_text(encoding="utf-8")
    path = tmp_path / "w.toml"
    path.write_text(text.replace('mu = "[1, 2]"', 'mu = "[3/2, 2]"'), encoding="utf-8")
    verdict = derive_document(read_definition(path))["linear_independence"]
    assert verdict == {"independent": True, "singular": []}
    for mv in mp.linspace(mp.mpf(3) / 2, 2, 5):
        assert abs(_gram_det(_three, 0, mv, 1)) > mp.mpf(10) ** -6


def test_half_open_range_without_the_zero(tmp_path):
    """mu in [1/2, 1), which misses sqrt(2): independent."""
    text = (DATA / "three_shape_trig_quadratic.toml").read_text(encoding="utf-8")
    path = tmp_path / "w.toml"
    path.write_text(text.replace('mu = "[1, 2]"', 'mu = "[1/2, 1)"'), encoding="utf-8")
    verdict = derive_document(read_definition(path))["linear_independence"]
    assert verdict["independent"] is True


# --------------------------------------------------------------------------- points in a box

x, y, z = sp.symbols("x y z")


def _exactly_zero(expr, point) -> bool:
    value = expr.subs(dict(zip((x, y, z), point, strict=True)))
    return sp.minimal_polynomial(sp.nsimplify(value) if value.is_Rational else value, x) == x


@pytest.mark.parametrize(
    ("polys", "box", "found"),
    [
        ([x**2 + y**2 + z**2 - 1], [(F(1, 4), 1), (F(1, 4), 1), (-1, 1)], True),
        ([x**2 + y**2 + z**2 - 1], [(F(3, 4), 1), (F(3, 4), 1), (-1, 1)], False),
        ([(x - F(1, 2)) ** 2 + (y - F(1, 3)) ** 2 + z**2], [(0, 1), (0, 1), (-1, 1)], True),
        ([x * y * z - 5], [(0, 1), (0, 1), (-1, 1)], False),
        # a circle strictly inside the box, touching no face: found at a critical point
        (
            [(x - F(1, 2)) ** 2 + (y - F(1, 2)) ** 2 + z**2 - F(1, 16), x - y],
            [(0, 1), (0, 1), (-1, 1)],
            True,
        ),
        (
            [(x - F(1, 2)) ** 2 + (y - F(1, 2)) ** 2 + z**2 - F(1, 16), x - y],
            [(0, F(1, 4)), (0, 1), (-1, 1)],
            False,
        ),
    ],
)
def test_ideal_point_exact(polys, box, found):
    cube = [(F(a), F(b)) for a, b in box]
    point = real_box.ideal_point([sp.Poly(p, x, y, z) for p in polys], cube)
    assert (point is not None) is found
    if found:
        assert all(_exactly_zero(p, point) for p in polys)
        assert all(lo <= float(v) <= hi for v, (lo, hi) in zip(point, cube, strict=True))
    else:  # independently: mpmath finds no near-zero on a grid
        grid = mp.linspace(0, 1, 9)
        for a in grid:
            for b in grid:
                for c in grid:
                    p = [lo + (hi - lo) * s for (lo, hi), s in zip(cube, (a, b, c), strict=True)]
                    vals = [abs(sp.lambdify((x, y, z), q, "mpmath")(*p)) for q in polys]
                    assert max(vals) > 1e-6


def test_zero_only_on_an_excluded_end_is_not_claimed():
    """x^2 + y^2 = 2 meets [0, 1]^2 only at (1, 1); with x < 1 excluded no point is
    accepted, and none is claimed absent either."""
    f = sp.Poly(x**2 + y**2 - 2, x, y)
    cube = [(F(0), F(1)), (F(0), F(1))]
    assert real_box.hypersurface_point(f, cube) == (1, 1)
    with pytest.raises(real_box.Undecided, match="excluded end"):
        real_box.hypersurface_point(f, cube, accept=lambda p: p[0] < 1)
