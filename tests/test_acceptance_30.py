"""Issue #30 tried as a new user would, from the issue's text alone: the failures found that way,
each with an independent reference (mpmath quadrature, direct evaluation) or the refusal the
issue asks for (a ValueError/TypeError naming the argument, the key and the term)."""

from __future__ import annotations

import math
from fractions import Fraction
from pathlib import Path

import mpmath as mp
import pytest
from definition_checks import TWO_PARAMETER_TRIG, assert_refused

import lambda_bezier as lb
from derive.emit.document import derive as derive_document
from derive.families.definition import DefinitionError, definition_from_table
from lambda_bezier import cli, examples

# A one-parameter quadratic trigonometric family on [0, pi/2], written by a new user
ONE_TRIG = """\
[family]
name = "{name}"
title = "one-parameter quadratic trigonometric basis"
parameter = "lam"
range = "{range}"
domain = "[0, pi/2]"
degrees = "2"
functions = [
  "(1 - sin(t))*(1 - lam*sin(t))",
  "1 - (1 - sin(t))*(1 - lam*sin(t)) - (1 - cos(t))*(1 - lam*cos(t))",
  "(1 - cos(t))*(1 - lam*cos(t))",
]
"""
POINTS = [(0, 0), (1, 3), (4, 0)]


def _family(tmp_path: Path, name: str, lam_range: str) -> lb.Family:
    path = tmp_path / f"{name}.toml"
    path.write_text(ONE_TRIG.format(name=name, range=lam_range), encoding="utf-8")
    assert cli.main(["derive", "--family", str(path)]) == 0
    return lb.load_family(path)


def _energy(lam: mp.mpf, k: int) -> mp.mpf:
    """E_k of the POINTS curve by mpmath quadrature. The basis as written, by hand in
    harmonics (s² = (1 - cos 2t)/2, c² = (1 + cos 2t)/2):
    b_0 = 1 + lam/2 - (1 + lam) sin t - (lam/2) cos 2t, b_2 the same with cos t and
    + (lam/2) cos 2t, b_1 = 1 - b_0 - b_2; so d^k is exact (a shift by k pi/2 per harmonic)."""
    shift = k * mp.pi / 2

    def basis(t: mp.mpf) -> tuple[mp.mpf, mp.mpf, mp.mpf]:
        sin_k, cos_k = mp.sin(t + shift), mp.cos(t + shift)
        cos2_k = 2**k * mp.cos(2 * t + shift)
        b0 = -(1 + lam) * sin_k - lam / 2 * cos2_k
        b2 = -(1 + lam) * cos_k + lam / 2 * cos2_k
        return b0, -b0 - b2, b2

    def integrand(t: mp.mpf) -> mp.mpf:
        b = basis(t)
        return sum(sum(b[i] * POINTS[i][d] for i in range(3)) ** 2 for d in range(2))

    return mp.quad(integrand, [0, mp.pi / 4, mp.pi / 2])


def test_the_hand_written_harmonics_are_the_basis():
    # guards _energy's algebra: at k = 0 its harmonics must give the functions as written
    # (the constant 1 + lam/2 dropped by every derivative is checked here)
    with mp.workdps(40):
        lam, t = mp.mpf(1) / 3, mp.mpf("0.7")
        s, c = mp.sin(t), mp.cos(t)
        b0 = 1 + lam / 2 - (1 + lam) * s - lam / 2 * mp.cos(2 * t)
        b2 = 1 + lam / 2 - (1 + lam) * c + lam / 2 * mp.cos(2 * t)
        assert abs(b0 - (1 - s) * (1 - lam * s)) < mp.mpf(10) ** -35
        assert abs(b2 - (1 - c) * (1 - lam * c)) < mp.mpf(10) ** -35


@pytest.fixture(scope="module")
def trig_one(tmp_path_factory):
    return _family(tmp_path_factory.mktemp("trig_one"), "trig_one", "[-1, 1]")


@pytest.mark.parametrize("k", [1, 2, 3])
def test_optimal_lambda_of_a_one_parameter_trigonometric_family(trig_one, k):
    # "optimal_lambda keeps working for one-parameter families": it raised TypeError for a
    # trigonometric one. E_k is a quadratic in lam: its vertex from three mpmath energies.
    fam = trig_one
    with mp.workdps(40):  # never the global precision: other tests' finite differences use it
        e = [_energy(mp.mpf(x), k) for x in (-1, 0, 1)]
        a2, a1 = (e[2] + e[0]) / 2 - e[1], (e[2] - e[0]) / 2
        vertex = -a1 / (2 * a2)
        vertex_energy = e[1] + a1 * vertex + a2 * vertex**2
    got = lb.optimal_lambda(POINTS, k, family=fam)
    assert abs(float(got.lam) - float(vertex)) < 1e-12
    assert abs(float(got.energy) - float(vertex_energy)) < 1e-10
    assert got.unconstrained_admissible == (-1 <= vertex <= 1)
    floats = lb.optimal_lambda([(0.0, 0.0), (1.0, 3.0), (4.0, 0.0)], k, family=fam)
    assert isinstance(floats.lam, float) and abs(floats.lam - float(vertex)) < 1e-12
    both = lb.optimal_parameters(POINTS, k, family=fam)
    assert both["lam"] == got.lam and both.energy == got.energy


def test_optimal_lambda_clamped_to_an_open_end(tmp_path):
    # the free optimum (-7/23 for k = 2, exact: the basis is symmetric) lies left of (0, 1/2]:
    # clamped to the excluded end 0, as for polynomial families, with E_2 there exact
    fam = _family(tmp_path, "trig_narrow", "(0, 1/2]")
    free = lb.optimal_lambda(POINTS, 2, family=fam)
    assert free.lam == free.unconstrained == Fraction(-7, 23) and not free.admissible
    got = lb.optimal_lambda(POINTS, 2, family=fam, clamp=True)
    assert got.lam == 0 and not got.admissible and got.unconstrained == Fraction(-7, 23)
    with mp.workdps(40):
        at_end, at_free = _energy(mp.mpf(0), 2), _energy(mp.mpf(-7) / 23, 2)
    assert abs(float(got.energy) - float(at_end)) < 1e-12
    assert abs(float(got.unconstrained_energy) - float(at_free)) < 1e-12
    assert got.energy == fam.curve(POINTS, lam=0, check_range=False).energy(2)


def test_optimal_lambda_refuses_several_parameters_and_batches(trig_one):
    fam = trig_one
    with pytest.raises(ValueError, match="points: a batch of polygons"):
        lb.optimal_lambda([POINTS, POINTS], 2, family=fam)
    two = lb.load_family(examples.path("han_trig_cubic.toml"))
    with pytest.raises(TypeError, match="one parameter; 'han_trig_cubic' has lam, mu"):
        lb.optimal_lambda([(0, 0), (1, 2), (3, 2), (4, 0)], 2, family=two)


@pytest.fixture(scope="module")
def trig_curve():
    fam = lb.load_family(examples.path("han_trig_cubic.toml"))
    return fam.curve([(0, 0), (1, 2), (3, 2), (4, 0)], lam=Fraction(1, 2), mu=-1)


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
def test_parameter_maps_refuse_non_finite_values(trig_curve, bad):
    # s_of_t and t_of_s answered NaN for NaN and inf
    with pytest.raises(ValueError, match="t contains NaN or infinity"):
        trig_curve.s_of_t(bad)
    with pytest.raises(ValueError, match="s contains NaN or infinity"):
        trig_curve.t_of_s([0.5, bad])


def test_parameter_maps_refuse_values_off_their_interval(trig_curve):
    # t_of_s(2) answered 2 atan(2), a t outside [0, pi/2]; the hyperbolic inverse has poles
    with pytest.raises(ValueError, match=r"s = 2.0 is outside \[0, 1\]"):
        trig_curve.t_of_s(2)
    with pytest.raises(ValueError, match=r"t = -0.5 is outside \[0, pi/2\]"):
        trig_curve.s_of_t([0.1, -0.5])
    # the ends themselves, and rounding just past them, stay accepted
    assert trig_curve.s_of_t(math.pi / 2) == pytest.approx(1.0, abs=1e-15)
    assert trig_curve.t_of_s([0.0, 0.5, 1.0]) == pytest.approx(
        [0.0, 2 * math.atan(0.5), math.pi / 2], abs=1e-15
    )


@pytest.mark.parametrize("t", [0.0, math.pi / 2])
def test_split_at_an_end_of_the_domain_is_refused(trig_curve, t):
    # split(pi/2) gave a degenerate piece (tan(pi/4) rounds below 1); RationalBezierCurve
    # refuses split(1) the same way
    with pytest.raises(ValueError, match=r"split needs t inside the domain \[0, pi/2\]"):
        trig_curve.split(t)


@pytest.mark.parametrize(
    ("term", "needle"),
    [
        ("tan(t)", "key functions[0]: unknown name 'tan'"),
        ("sin(t)**2 + foo", "key functions[0]: unknown name 'foo'"),
    ],
)
def test_a_term_outside_the_grammar_is_named_before_the_domain(term, needle):
    # with domain [0, pi/2] and no other function in sin, cos, ..., a function that did not
    # parse was blamed on the domain ("a polynomial basis is derived on [0, 1] only"), and
    # the term went unnamed
    table = {**TWO_PARAMETER_TRIG, "functions": [term, f"1 - ({term}) - t**2", "t**2"]}
    assert_refused(table, [needle], derive=False)


def test_an_indexed_trigonometric_basis_is_refused_with_the_reason():
    table = {
        "name": "idx_trig",
        "parameters": ["lam(i)"],
        "range": {"lam": "[-1, 1]"},
        "domain": "[0, pi/2]",
        "degrees": "2",
        "functions": ["cos(t)**2*(1 - lam(0))", "lam(0)*cos(t)**2", "sin(t)**2"],
    }
    with pytest.raises(DefinitionError) as info:
        definition_from_table(table, "fam.toml")
    assert "key functions[0]: unknown name 'cos'" in str(info.value)
    assert "an indexed family (lam(i)) is polynomial in this version" in str(info.value)


def test_an_indexed_family_its_parameters_never_enter_derives():
    # the closed-form fit called sp.Poly with no generators: a SymPy traceback
    table = {
        "name": "idx_unused",
        "parameters": ["lam(i)"],
        "range": {"lam": "[-1, 1]"},
        "degrees": "2..3",
        "basis": "binomial(n, i)*t**i*(1 - t)**(n - i)",
    }
    doc = derive_document(definition_from_table(table))
    closed = doc["closed_n"]["forms"]
    assert closed["start,1,0"] == "-n" and closed["end,1,0"] == "n"


@pytest.mark.parametrize("continuity", ["C1", "C2", "G1", "G2"])
def test_join_from_a_trigonometric_curve_into_an_indexed_family(trig_curve, continuity):
    # "joins between any two families with their own parameters": into q_bezier (lam(i)) the
    # values are one per index, as from a polynomial curve; the atom path passed the list on
    # as one number ("lam_1 must be a real number, got [1, 0, -1]")
    q = lb.load_family(Path(__file__).parent / "data" / "families" / "q_bezier.toml")
    order = int(continuity[1])
    rest = [(10, 1), (11, 0)][: 3 - order]
    alpha = {"alpha": Fraction(2)} if continuity[0] == "G" else {}
    nxt = lb.join(trig_curve, continuity, 3, family=q, lam=[1, 0, -1], rest=rest, **alpha)
    assert repr(nxt) == "QBezierCurve(degree=3, dimension=2, lam_1=1, lam_2=0, lam_3=-1)"
    end = math.pi / 2
    scale = 2.0 if continuity[0] == "G" else 1.0
    assert nxt.evaluate(0.0) == pytest.approx(trig_curve.evaluate(end), abs=1e-13)
    assert trig_curve.derivative(end, 1) == pytest.approx(scale * nxt.derivative(0.0, 1), abs=1e-12)
    if order == 2:
        a1, a2 = trig_curve.derivative(end, 1), trig_curve.derivative(end, 2)
        b1, b2 = nxt.derivative(0.0, 1), nxt.derivative(0.0, 2)
        if continuity == "C2":
            assert a2 == pytest.approx(b2, abs=1e-12)
        else:  # G2: the same curvature
            k1 = (a1[0] * a2[1] - a1[1] * a2[0]) / math.hypot(*a1) ** 3
            k2 = (b1[0] * b2[1] - b1[1] * b2[0]) / math.hypot(*b1) ** 3
            assert k1 == pytest.approx(k2, abs=1e-12)


@pytest.mark.parametrize("scale", [1e308, 1e-300])
def test_rational_geometry_near_the_ends_of_the_float_range(scale):
    # the scale factor of _rational_geometry._unit was 2^1024 for coordinates near 1e308:
    # OverflowError ("math range error") from arc_length, bounding_box and closest_point.
    # Reference: the same curve at scale 1, whose length and box scale exactly.
    unit = lb.RationalBezierCurve([(0, 0), (1, 1), (0, 1)], [1, 0.5, 1])
    big = lb.RationalBezierCurve([(0, 0), (scale, scale), (0, scale)], [1, 0.5, 1])
    assert big.arc_length() / scale == pytest.approx(unit.arc_length(), rel=1e-12)
    lo, hi = big.bounding_box()
    assert (lo / scale).tolist() == [0.0, 0.0]
    assert (hi / scale).tolist() == pytest.approx(unit.bounding_box()[1].tolist(), rel=1e-12)
    assert big.closest_point([scale, 0]).t == pytest.approx(unit.closest_point([1, 0]).t)


def test_a_rational_arc_length_beyond_the_floats_is_refused():
    big = lb.RationalBezierCurve([(0, 0), (1.7e308, 1.7e308), (0, 1.7e308)], [1, 0.5, 1])
    with pytest.raises(ValueError, match="the arc length overflows the float range"):
        big.arc_length()
    assert math.isfinite(big.arc_length(0, 0.5))


@pytest.mark.parametrize(
    ("args", "needle"), [((3,), "path must be"), (("x.toml", 5), "derived must be")]
)
def test_load_family_names_a_path_that_is_no_path(args, needle):
    # load_family(3) raised pathlib's "expected str, bytes or os.PathLike object, not int"
    with pytest.raises(TypeError, match=f"{needle} a file path \\(str or Path\\), got int"):
        lb.load_family(*args)


def test_a_curve_energy_order_given_as_text_is_named():
    # a polygon with k = "2": the order of E_k, not a surface energy's name
    with pytest.raises(TypeError, match=r"energy: a control polygon .* as an int, got '2'"):
        lb.optimal_parameters([(0, 0), (1, 2), (3, 1), (4, 0)], "2")
    with pytest.raises(ValueError, match="unknown energy 'bad'"):  # a net: the names offered
        lb.optimal_parameters([[(0, 0, 0), (1, 0, 0)], [(0, 1, 0), (1, 1, 1)]], "bad")
