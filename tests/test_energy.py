"""Energy forms and optimal λ against quadrature and numeric minimisation."""

from __future__ import annotations

import importlib.metadata
import json
import os
import subprocess
import sys
from fractions import Fraction

import numpy as np
import pytest
from conftest import make_curve
from hypothesis import given
from hypothesis import strategies as st
from reference import FAMILIES
from scipy.optimize import minimize_scalar

import lambda_bezier as lb
from lambda_bezier.cli import main
from lambda_bezier.hazmat.numbers import parse_number, parse_point

LAMBDA_FAMILIES = ["same_degree", "bernstein_like"]
EXAMPLE = [(0, 6), (0, 2), (5, 2), (7, 0), (2, 0), (6, 8)]  # 000, section 4.2


def quadrature_energy(curve, k: int) -> float:
    """∫_0^1 |p^(k)|² by Gauss–Legendre, exact for these polynomial degrees."""
    x, w = np.polynomial.legendre.leggauss(curve.polynomial_degree + 2)
    t = (x + 1) / 2
    d = curve.derivative(t, k)
    return float(np.sum(w / 2 * np.sum(d * d, axis=1)))


@st.composite
def polygons(draw, family: str, max_degree: int = 8):
    fam = FAMILIES[family]
    n = draw(st.integers(max(fam.degrees[0], 3), max_degree))
    d = draw(st.sampled_from((2, 3)))
    coord = st.integers(-20, 20).map(lambda v: v / 2)
    pts = draw(st.lists(st.lists(coord, min_size=d, max_size=d), min_size=n + 1, max_size=n + 1))
    return np.array(pts, dtype=float)


@pytest.mark.parametrize("family", LAMBDA_FAMILIES)
@given(data=st.data())
def test_quadratic_form_matches_quadrature(family, data):
    pts = data.draw(polygons(family))
    k = data.draw(st.sampled_from((1, 2, 3)))
    lam = data.draw(st.floats(*FAMILIES[family].lam_range))
    a0, a1, a2 = lb.energy_coefficients(pts, k, family)
    curve = make_curve(FAMILIES[family], pts, lam)
    want = quadrature_energy(curve, k)
    scale = 1 + abs(want) + abs(a0)
    assert abs((a0 + a1 * lam + a2 * lam**2) - want) <= 1e-9 * scale
    assert abs(curve.energy(k) - want) <= 1e-9 * scale


@pytest.mark.parametrize("name", list(FAMILIES))
def test_curve_energy_every_order(name):
    fam = FAMILIES[name]
    rng = np.random.default_rng(11)
    for n in fam.degrees[:6]:
        curve = make_curve(fam, rng.normal(size=(n + 1, 3)), None if name == "bezier" else 0.25)
        for k in range(curve.polynomial_degree + 2):
            want = quadrature_energy(curve, k)
            assert abs(curve.energy(k) - want) <= 1e-9 * (1 + want)


@pytest.mark.parametrize("family", LAMBDA_FAMILIES)
@given(data=st.data())
def test_optimal_lambda_matches_numeric_minimisation(family, data):
    pts = data.draw(polygons(family, max_degree=7))
    k = data.draw(st.sampled_from((1, 2, 3)))
    try:
        result = lb.optimal_lambda(pts, k, family)
    except ValueError as exc:
        assert "no effect" in str(exc)
        a2 = lb.energy_coefficients(pts, k, family)[2]
        assert a2 <= 1e-9 * (1 + np.abs(pts).max() ** 2)
        return

    def energy(lam: float) -> float:
        curve = lb.FAMILIES[family](pts, lam, check_range=False)
        return quadrature_energy(curve, k)

    found = minimize_scalar(energy, bracket=(-1.0, 1.0), tol=1e-12)
    e_best = energy(result.lam)
    # the minimiser of a convex quadratic: no numeric search does better
    assert e_best <= found.fun + 1e-9 * (1 + abs(found.fun))
    assert abs(result.energy - e_best) <= 1e-8 * (1 + e_best)
    curvature = lb.energy_coefficients(pts, k, family)[2]
    assert abs(result.lam - found.x) <= 1e-4 * (1 + abs(found.x)) or curvature < 1e-6


def test_paper_example_exact():
    """000, section 4.2: λ = -690/319 for the strain energy, outside (-2, 1]."""
    result = lb.optimal_lambda(EXAMPLE, 2)
    assert result.lam == Fraction(-690, 319) and isinstance(result.lam, Fraction)
    assert result.admissible is False and result.unconstrained_admissible is False
    clamped = lb.optimal_lambda(EXAMPLE, 2, clamp=True)
    assert clamped.lam == -2 and clamped.unconstrained == Fraction(-690, 319)
    assert clamped.admissible is False  # -2 itself is excluded from (-2, 1]
    assert clamped.energy > clamped.unconstrained_energy
    curve = lb.SameDegreeCurve(EXAMPLE, result.lam, check_range=False)
    assert curve.energy(2) == result.energy  # two exact routes agree


def test_clamp_inside_range_changes_nothing():
    pts = [(0, 0), (1, 2), (3, 3), (4, 0)]
    free, clamped = lb.optimal_lambda(pts, 2), lb.optimal_lambda(pts, 2, clamp=True)
    if free.admissible:
        assert free.lam == clamped.lam
    clamped_bl = lb.optimal_lambda(EXAMPLE, 1, "bernstein_like", clamp=True)
    assert -1 <= clamped_bl.lam <= 1 and clamped_bl.admissible


@pytest.mark.parametrize("family", LAMBDA_FAMILIES)
def test_batch_equals_single_and_exact_equals_float(family):
    rng = np.random.default_rng(5)
    batch = rng.integers(-9, 10, size=(50, 6, 2))
    for k in (1, 2, 3):
        result = lb.optimal_lambda(batch.astype(float), k, family, clamp=True)
        assert result.lam.shape == (50,)
        for idx in (0, 17, 49):
            single = lb.optimal_lambda(batch[idx].astype(float), k, family, clamp=True)
            exact = lb.optimal_lambda(
                [tuple(map(int, p)) for p in batch[idx]], k, family, clamp=True
            )
            assert isinstance(exact.unconstrained, Fraction)
            np.testing.assert_allclose(result.unconstrained[idx], single.unconstrained, rtol=1e-12)
            np.testing.assert_allclose(single.unconstrained, float(exact.unconstrained), rtol=1e-12)
            assert result.admissible[idx] == single.admissible == exact.admissible


def test_energy_matrices_api():
    scale, x, y = lb.energy_matrices(5, 2)
    assert isinstance(scale, Fraction)
    assert all(isinstance(v, int) for row in x + y for v in row)
    assert all(x[r][c] == 0 for r in range(6) for c in range(r))  # upper triangular
    # λ* = scale·DᵀXD/DᵀYD reproduces optimal_lambda
    d = np.array(EXAMPLE, dtype=object)

    def form(u):
        return sum(
            u[r][c] * (Fraction(int(d[r][0]) * int(d[c][0]) + int(d[r][1]) * int(d[c][1])))
            for r in range(6)
            for c in range(r, 6)
        )

    assert scale * form(x) / form(y) == Fraction(-690, 319)
    with pytest.raises(ValueError, match="degree 13"):
        lb.energy_matrices(13, 2)


@pytest.mark.parametrize(
    ("points", "kwargs", "message"),
    [
        ([(1, 1)] * 4, {"k": 2}, "no effect"),
        ([(0, 0), (1, float("nan")), (2, 0), (3, 1)], {"k": 2}, "non-finite"),
        (np.zeros((4, 0)), {"k": 2}, "shape"),  # d >= 1: energies hold in any dimension
        ([(0, 0)] * 3, {"k": 2}, "at least 4"),
        (EXAMPLE, {"k": 4}, "1, 2 or 3"),
        (EXAMPLE, {"k": 2, "family": "bezier"}, "unknown family"),
        (np.zeros((3, 2, 2, 2)), {"k": 2}, "shape"),
        (np.stack([np.array(EXAMPLE, float), np.ones((6, 2))]), {"k": 2}, r"no effect.*polygon 1"),
    ],
)
def test_bad_input(points, kwargs, message):
    with pytest.raises(ValueError, match=message):
        lb.optimal_lambda(points, **kwargs)


# ---------------------------------------------------------------------------- CLI


def test_cli_text(capsys):
    assert (
        main(
            [
                "optimal-lambda",
                "--family",
                "same_degree",
                "--energy",
                "2",
                "0,6",
                "0,2",
                "5,2",
                "7,0",
                "2,0",
                "6,8",
            ]
        )
        == 0
    )
    out = capsys.readouterr().out
    assert "-690/319" in out and "-2.16300940439" in out and "no: outside (-2, 1]" in out


def test_cli_json(capsys):
    assert (
        main(["optimal-lambda", "--json", "--clamp", "0,6", "0,2", "5,2", "7,0", "2,0", "6,8"]) == 0
    )
    report = json.loads(capsys.readouterr().out)
    assert report["lambda"] == "-690/319" and report["admissible"] is False
    assert report["clamped_lambda"] == "-2"
    assert Fraction(report["energy"]) == lb.optimal_lambda(EXAMPLE, 2).energy


def test_console_script_flushes_its_output_and_keeps_the_exit_code():
    """The console script ends with os._exit (no interpreter teardown): what it printed into
    a pipe, which is block-buffered, must still arrive, with main()'s exit code."""
    points = ["0,6", "0,2", "5,2", "7,0", "2,0", "6,8"]
    run = [sys.executable, "-m", "lambda_bezier", "optimal-lambda"]
    env = {k: v for k, v in os.environ.items() if k != "PYTHONUNBUFFERED"}  # buffer the pipe
    kw = {"capture_output": True, "text": True, "timeout": 120, "env": env}
    ok = subprocess.run([*run, "--json", *points], **kw)
    assert ok.returncode == 0, ok.stderr
    assert json.loads(ok.stdout)["lambda"] == "-690/319"
    bad = subprocess.run([*run, *points[:3], "1e5,0"], **kw)
    assert bad.returncode == 2 and "not a number: '1e5'" in bad.stderr
    script = importlib.metadata.entry_points(group="console_scripts", name="lambda-bezier")
    assert [ep.value for ep in script] == ["lambda_bezier.cli:console_main"]


@pytest.mark.parametrize(
    "bad", ["__import__('os')", "1e5", "0x10", "1/0", "2**3", "1,2,3,4", "nan"]
)
def test_cli_rejects_malformed_numbers(capsys, bad):
    assert main(["optimal-lambda", "0,6", "0,2", "5,2", bad if "," in bad else f"{bad},0"]) == 2
    assert "error" in capsys.readouterr().err


@given(st.fractions(max_denominator=10**6))
def test_parse_number_round_trip(q):
    assert parse_number(str(q)) == q


def test_parse_forms():
    assert parse_number("-0.25") == Fraction(-1, 4)
    assert parse_number(".5") == Fraction(1, 2)
    assert parse_number("+3") == 3
    assert parse_point("1/2,0.25,3") == (Fraction(1, 2), Fraction(1, 4), 3)
    for bad in ("", "1/", "/2", "1/2/3", "1.5/2", "inf", " 1 2", "1_000"):
        with pytest.raises(ValueError):
            parse_number(bad)
