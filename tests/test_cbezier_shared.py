"""C-Bezier curves in the shared functions (issue #30): join from and into them (C1, C2, G1,
G2), CompositeCurve and its report, evaluate_many, the JSON round trip with the definition's
fingerprint.

The joint conditions are checked against an independent evaluation: the C-Bezier curve's
derivatives from the functions written in the definition file (derive's grammar, SymPy's
derivative, mpmath at 30 digits), the polynomial curves' from their Bezier control points
(exact differences), never from the runtime's atom evaluation.
"""

from __future__ import annotations

import json
from fractions import Fraction
from pathlib import Path

import mpmath as mp
import numpy as np
import pytest
import sympy as sp
import tomllib
from conftest import family_file

import lambda_bezier as lb
from derive.families import cbezier as cb
from lambda_bezier import examples, export

DATA = Path(__file__).parent / "data" / "families"
P = [[0.0, 0.0], [1.0, 2.0], [3.0, 2.5], [4.0, 0.5]]


@pytest.fixture(scope="module")
def family():
    return lb.load_family(examples.path("c_bezier_cubic.toml"))


@pytest.fixture(scope="module")
def written():
    """d^r/dt^r b_i(t; alpha) from the file's own formulas, r = 0..2, in mpmath."""
    table = tomllib.loads((examples.path("c_bezier_cubic.toml")).read_text())["family"]
    defn = cb.read_table(table)
    return [
        [sp.lambdify((cb.T, cb.A), sp.diff(f, cb.T, r), modules="mpmath") for f in defn.written()]
        for r in range(3)
    ]


def _cb_derivative(written, curve, t, r):
    a = mp.mpf(curve.alpha)
    pts = curve.control_points()
    return np.array(
        [
            float(sum(f(mp.mpf(t), a) * p[d] for f, p in zip(written[r], pts, strict=True)))
            for d in range(curve.dimension)
        ]
    )


def _bezier_derivative(points, t, r):
    """The r-th derivative of the Bezier curve of `points` at t in {0, 1} (differences)."""
    pts = np.array(points, dtype=float)
    for _ in range(r):
        pts = (len(pts) - 1) * np.diff(pts, axis=0)
    return pts[0] if t == 0 else pts[-1]


def _check(d1, d2, continuity, a, d):
    (p1, v1, w1), (p2, v2, w2) = d1, d2
    scale = 1 + max(np.abs(np.concatenate([v1, w1])).max(), 1)
    assert np.allclose(p1, p2, atol=1e-12 * scale, rtol=0)
    assert np.allclose(v1, a * v2, atol=1e-11 * scale, rtol=0)
    if continuity in ("C2", "G2"):
        assert np.allclose(w1, a * a * w2 + d * v2, atol=1e-10 * scale, rtol=0)


CASES = [("C1", 1, 0), ("C2", 1, 0), ("G1", 2, 0), ("G2", Fraction(3, 2), Fraction(1, 2))]


@pytest.mark.parametrize(("continuity", "a", "d"), CASES)
def test_join_c_bezier_to_c_bezier(family, written, continuity, a, d):
    first = family.curve(P, alpha=2.0)
    rest = [[9.0, 1.0], [10.0, 3.0]][: 3 - int(continuity[1])]
    nxt = lb.join(first, continuity, 3, params={"alpha": 1.25}, rest=rest, alpha=a, d=d)
    assert nxt.alpha == 1.25 and nxt.family == "c_bezier_cubic"
    ends = [_cb_derivative(written, first, 2.0, r) for r in range(3)]
    starts = [_cb_derivative(written, nxt, 0.0, r) for r in range(3)]
    _check(ends, starts, continuity, float(a), float(d))
    assert np.allclose(nxt.control_points()[-len(rest) :], rest)
    report = lb.CompositeCurve([first, nxt], [lb.Joint(continuity, a, d)]).report()
    assert continuity in report[0].achieved


@pytest.mark.parametrize(("continuity", "a", "d"), CASES)
def test_join_from_and_into_polynomial_families(family, written, continuity, a, d):
    """A Bezier curve into a C-Bezier segment, and that segment into a Bezier curve."""
    bez = lb.BezierCurve([(0, 0), (1, 2), (3, 2), (4, 0)])
    order = int(continuity[1])
    into = lb.join(
        bez,
        continuity,
        3,
        family=family,
        params={"alpha": 2.5},
        rest=[[9, 1], [10, 3]][: 3 - order],
        alpha=a,
        d=d,
    )
    ends = [_bezier_derivative(bez.control_points(), 1, r) for r in range(3)]
    starts = [_cb_derivative(written, into, 0.0, r) for r in range(3)]
    _check(ends, starts, continuity, float(a), float(d))
    out = lb.join(
        into,
        continuity,
        4,
        family="bezier",
        rest=[[12, 1], [13, 0], [14, 2]][: 4 - order],
        alpha=a,
        d=d,
    )
    ends = [_cb_derivative(written, into, 2.5, r) for r in range(3)]
    starts = [_bezier_derivative(out.control_points(), 0, r) for r in range(3)]
    _check(ends, starts, continuity, float(a), float(d))


def test_join_refusals(family):
    first = family.curve(P, alpha=2.0)
    with pytest.raises(ValueError, match="needs its parameter"):
        lb.join(first, "C1", 3, rest=[[9, 1], [10, 3]])
    with pytest.raises(ValueError, match="outside the family's range"):
        lb.join(first, "C1", 3, params={"alpha": 4}, rest=[[9, 1], [10, 3]])
    with pytest.raises(TypeError, match="'mu' is not a parameter"):
        lb.join(first, "C1", 3, params={"mu": 1}, rest=[[9, 1], [10, 3]])
    with pytest.raises(ValueError, match="degree 4 is not supported"):
        lb.join(first, "C1", 4, params={"alpha": 1.0}, rest=[[9, 1], [10, 3], [1, 1]])


def test_composite_of_c_bezier_and_polynomial_segments(family, written):
    first = family.curve(P, alpha=2.0)
    comp = lb.CompositeCurve([first]).join(
        "G2", 3, params={"alpha": 1.5}, rest=[[9, 1]], alpha=2, d=0.5
    )
    comp = comp.join("C2", 3, family="bezier", rest=[[12, 1]])
    assert comp.breaks == (0.0, 2.0, 3.5, 4.5)  # each C-Bezier segment covers its own [0, alpha]
    assert [r.achieved >= {"G2"} for r in comp.report()] == [True, True]
    assert "C2" in comp.report()[1].achieved
    u = np.array([0.3, 2.7, 4.1])
    want = np.array(
        [
            _cb_derivative(written, comp.segments[0], 0.3, 0),
            _cb_derivative(written, comp.segments[1], 0.7, 0),
            comp.segments[2].evaluate(0.6),
        ]
    )
    assert np.allclose(comp.evaluate(u), want, atol=1e-12)
    with pytest.raises(ValueError, match="its parameter is in the domain"):
        comp.with_lambda(0, 0.5)


def test_evaluate_many(family, written):
    rng = np.random.default_rng(3)
    pts = rng.normal(size=(4, 4, 2))
    t = np.linspace(0.0, 1.75, 6)
    for k in (0, 2):
        got = lb.evaluate_many(pts, t, family, params={"alpha": 1.75}, k=k)
        assert got.shape == (4, 6, 2)
        for m in (0, 3):
            curve = family.curve(pts[m], alpha=1.75)
            want = np.array([_cb_derivative(written, curve, x, k) for x in t])
            assert np.allclose(got[m], want, atol=1e-12 * (1 + np.abs(want).max()))
    assert lb.evaluate_many(pts, 0.5, family, lam=1.75).shape == (4, 2)
    with pytest.raises(ValueError, match="outside the curve's domain"):
        lb.evaluate_many(pts, 2.0, family, params={"alpha": 1.75})
    with pytest.raises(ValueError, match="needs its parameter"):
        lb.evaluate_many(pts, 0.5, family)


def test_json_round_trip_with_fingerprint(family):
    first = family.curve(P, alpha=2.0)
    comp = lb.CompositeCurve([first]).join("C2", 3, params={"alpha": 1.5}, rest=[[9, 1]])
    for shape in (first, comp):
        text = export.to_json(shape)
        doc = json.loads(text)
        assert doc["definitions"]["c_bezier_cubic"]["definition_digest"] == family.digest
        back = export.from_json(text, family=family)
        u = np.linspace(*shape.domain, 9)
        assert np.array_equal(back.evaluate(u), shape.evaluate(u))
        assert export.from_json(text, family=examples.path("c_bezier_cubic.toml")).evaluate(
            0.5
        ) == pytest.approx(shape.evaluate(0.5))
    with pytest.raises(ValueError, match="not built in"):
        export.from_json(export.to_json(first))
    other = lb.load_family(DATA / "c_bezier_cubic_unit.toml")
    doc = json.loads(export.to_json(first))
    doc["definitions"]["c_bezier_cubic"]["definition"]["title"] = "edited"
    with pytest.raises(ValueError, match="does not match its definition_digest"):
        export.from_json(json.dumps(doc), family=family)
    doc = json.loads(export.to_json(other.curve(P, alpha=1.0)))
    doc["parameters"] = {"alpha": 5}
    with pytest.raises(ValueError, match="outside the family's range"):
        export.from_json(json.dumps(doc), family=other)


TRIG_INTERPOLATING = """[family]
name = "trig_interpolating"
title = "Interpolating trigonometric basis sin(alpha - t)/sin(alpha), sin(t)/sin(alpha)"
parameter = "alpha"
range = "(0, 3]"
domain = "[0, alpha]"
degrees = "1"
functions = ["sin(alpha - t)/sin(alpha)", "sin(t)/sin(alpha)"]
"""


@pytest.mark.parametrize("name", ["hyp_interpolating", "trig_interpolating"])
def test_rational_form_against_the_formula(tmp_path, name):
    """A family without powers of t is a rational Bezier curve (degree 2 here, float
    weights): against the written formula in mpmath at the form's own parameter map."""
    from lambda_bezier.cli import main

    if name == "trig_interpolating":
        path = tmp_path / f"{name}.toml"
        path.write_text(TRIG_INTERPOLATING)
        assert main(["derive", "--family", str(path)]) == 0
        f = [lambda t, a: mp.sin(a - t) / mp.sin(a), lambda t, a: mp.sin(t) / mp.sin(a)]
    else:
        path = family_file(name)
        f = [lambda t, a: mp.sinh(a - t) / mp.sinh(a), lambda t, a: mp.sinh(t) / mp.sinh(a)]
    fam = lb.load_family(path)
    pts = [[0.0, 0.0], [3.0, 1.0]]
    for alpha in (0.4, 2.5):
        curve = fam.curve(pts, alpha=alpha)
        r = curve.to_rational_bezier()
        assert r.degree == 2 and r.control_weights()[0] == 1.0
        s = np.linspace(0, 1, 11)
        t = curve.t_of_s(s)
        assert t[0] == pytest.approx(0, abs=1e-15) and t[-1] == pytest.approx(alpha, rel=1e-15)
        assert np.allclose(curve.s_of_t(t), s, atol=1e-15)
        a = mp.mpf(alpha)
        want = np.array(
            [
                [
                    float(sum(g(mp.mpf(x), a) * p[d] for g, p in zip(f, pts, strict=True)))
                    for d in range(2)
                ]
                for x in t
            ]
        )
        assert np.allclose(r.evaluate(s), want, atol=1e-14, rtol=0)


def test_no_rational_form_with_powers_of_t(family):
    with pytest.raises(ValueError, match="no rational Bézier form: its space has t"):
        family.curve(P, alpha=1.0).to_rational_bezier()


def test_length_location_and_torsion_against_the_written_formulas(family, written):
    """arc_length / parameter_at_length / locate / torsion of a C-Bezier curve (and of a
    composite holding one) against mpmath quadrature of the speed from the file's formulas."""
    c = family.curve(P, alpha=2.0)
    speed = lambda t: mp.sqrt(sum(x * x for x in _cb_derivative(written, c, t, 1)))  # noqa: E731
    with mp.workdps(20):
        whole = float(mp.quad(speed, [0, 0.5, 1, 1.5, 2]))
        part = float(mp.quad(speed, [0.25, 1, 1.5]))
    assert c.arc_length() == pytest.approx(whole, rel=1e-12)
    assert c.arc_length(0.25, 1.5) == pytest.approx(part, rel=1e-12)
    t = c.parameter_at_length(part)
    assert c.arc_length(0, t) == pytest.approx(part, rel=1e-12)
    comp = lb.CompositeCurve([c]).join("C1", 3, rest=[(7, 1), (8, 0)], family="bezier")
    assert comp.breaks[1] == 2.0  # the C-Bezier segment covers its own [0, alpha]
    assert comp.arc_length(0, 2) == pytest.approx(whole, rel=1e-12)
    assert c.locate(c.evaluate(0.7)) == pytest.approx(0.7, abs=1e-9)
    assert c.locate((10.0, 10.0)) is None
    with pytest.raises(ValueError, match="t1 = 3"):
        c.arc_length(0, 3)
    with pytest.raises(ValueError, match="torsion"):
        c.torsion(0.5)  # a planar curve
    space = family.curve([(0, 0, 0), (1, 2, 1), (3, 2, -1), (4, 0, 2)], alpha=2.0)
    d1, d2 = (np.array(space.derivative(1.0, k)) for k in (1, 2))
    d3 = np.array(space.derivative(1.0, 3))
    cross = np.cross(d1, d2)
    assert space.torsion(1.0) == pytest.approx(float(cross @ d3 / (cross @ cross)), rel=1e-9)


def test_curvature_outside_two_and_three_dimensions_is_refused_by_name(family):
    """A 4D C-Bezier curve: curvature and the joint reports' _curvature raise the shared
    ValueError naming the dimension (numpy's cross product used to fail inside)."""
    four = family.curve([(0, 0, 0, 0), (1, 2, 1, 0), (3, 2, -1, 1), (4, 0, 2, 1)], alpha=2.0)
    for method in (four.curvature, four._curvature):
        with pytest.raises(ValueError, match="dimension 2 or 3.*dimension 4"):
            method(0.5)


def test_planar_curvature_is_signed_as_for_every_other_curve(family, written):
    """In 2D the curvature carries the turning direction (x'y'' - y'x'') / |r'|^3, checked
    against the file's own formulas in mpmath; reversing the control points flips it."""
    points = [(0, 0), (1, 2), (3, 2), (4, 0)]
    alpha = 2.0
    curve = family.curve(points, alpha=alpha)
    for t in (0.3, 1.0, 1.7):
        d1 = [sum(written[1][i](t, alpha) * p[c] for i, p in enumerate(points)) for c in (0, 1)]
        d2 = [sum(written[2][i](t, alpha) * p[c] for i, p in enumerate(points)) for c in (0, 1)]
        expected = (d1[0] * d2[1] - d1[1] * d2[0]) / (d1[0] ** 2 + d1[1] ** 2) ** 1.5
        assert expected < 0  # this arch turns clockwise
        assert curve.curvature(t) == pytest.approx(float(expected), rel=1e-9)
    backwards = family.curve(points[::-1], alpha=alpha)
    assert backwards.curvature(alpha - 1.0) == pytest.approx(-curve.curvature(1.0), rel=1e-9)
