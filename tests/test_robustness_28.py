"""Issue #28: each robustness item, pinned by a test that fails without its fix."""

from __future__ import annotations

import os
import subprocess
import sys
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from conftest import ROOT

import lambda_bezier as lb

HAS_DERIVE = (ROOT / "derive" / "__init__.py").is_file()
needs_derive = pytest.mark.skipif(not HAS_DERIVE, reason="needs the source checkout")


def _cli(*args: str, cwd: Path = ROOT) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "lambda_bezier", *args],
        capture_output=True,
        text=True,
        cwd=cwd,
        env=dict(os.environ, PYTHONHASHSEED="0"),
        timeout=300,
    )


# --------------------------------------------------------------------------- item 1

# A basis from degree 2 whose λ-part is the quadratic t(1 - t) moved between the end functions:
# its third derivative vanishes, so E_3 does not depend on λ at any degree, and at degree 2 the
# whole of E_3 vanishes identically.
QUADRATIC_FAMILY = """\
[family]
name = "from_two"
title = "a family whose degrees start at 2"
parameter = "lam"
range = "[0, 1]"
degrees = "2..4"
bernstein_at = "0"
degree_offset = 0
basis = "binomial(n, i)*t**i*(1 - t)**(n - i) + lam*(binomial(0, i) - binomial(0, n - i))*t*(1 - t)"
"""

QUADRATIC_RECORDS = """\
schema_version = 2
source = "test"
title = "records about from_two"
family = "from_two"

[[record]]
id = "two.y3"
claim = "energy_matrix"
location = "E_3 at n = 2: Y = 0"
expect = "match"
name = "Y"
k = 3
n = 2
scale = "1"
matrix = [[0, 0, 0], [0, 0, 0], [0, 0, 0]]

[[record]]
id = "two.lambda3"
claim = "energy_lambda_nk"
location = "a lambda* printed for E_3, which does not depend on lambda"
expect = "mismatch"
k = 3
n = 2
scale = "1"
numerator = "two.y3"
denominator = "two.y3"
vector = ["P(0)", "P(1)", "P(2)"]
[record.erratum]
origin = "paper"
explanation = "E_3 does not depend on lambda"
equations = []
"""


@needs_derive
def test_family_from_degree_two_derives_and_flows(derive_beside, tmp_path):
    fam_file = tmp_path / "from_two.toml"
    fam_file.write_text(QUADRATIC_FAMILY, encoding="utf-8")
    derive_beside(fam_file)
    fam = lb.load_family(fam_file)
    pts = [(0, 0), (1, 2), (3, 1)]
    # E_3 ≡ 0 at degree 2: a curve has it, energy_matrices and optimal_lambda say λ has no effect
    assert fam.curve(pts, lam=Fraction(1, 3)).energy(3) == 0
    with pytest.raises(ValueError, match="no effect on E_3.*degree 2"):
        lb.energy_matrices(2, 3, family=fam)
    with pytest.raises(ValueError, match="no effect on E_3"):
        lb.optimal_lambda(pts, 3, family=fam)
    # E_2 depends on λ: the minimiser agrees with the quadratic fitted through three exact energies
    e = [fam.curve(pts, lam=Fraction(x, 2)).energy(2) for x in (0, 1, 2)]
    # E(λ) = a0 + a1 λ + a2 λ² sampled at λ = 0, 1/2, 1
    a2 = 2 * (e[2] - 2 * e[1] + e[0])
    a1 = e[2] - e[0] - a2
    assert lb.optimal_lambda(pts, 2, family=fam).unconstrained == -a1 / (2 * a2)


@needs_derive
def test_verify_handles_an_energy_that_does_not_depend_on_lambda(tmp_path):
    fam_file = tmp_path / "from_two.toml"
    fam_file.write_text(QUADRATIC_FAMILY, encoding="utf-8")
    rec = tmp_path / "records.toml"
    rec.write_text(QUADRATIC_RECORDS, encoding="utf-8")
    res = _cli("verify", str(fam_file), str(rec))
    out = res.stdout + res.stderr
    assert "checker error" not in out and "Traceback" not in out, out
    assert "two.y3" in out and "no λ minimises E_3" in out, out


# --------------------------------------------------------------------------- item 2

FOREIGN_POINTS = """\
schema_version = 2
source = "test"
title = "same_degree records written with P(i)"
family = "same_degree"
{point_function}
[[record]]
id = "sd.ends"
claim = "endpoint_curve"
location = "ends"
equations = [
  {{ lhs = "p(0)", rhs = "P(0)" }},
  {{ lhs = "Subs(Derivative(p(t), t), t, 0)", rhs = "(n - 1 + lam)*(P(1) - P(0))" }},
]
"""


@needs_derive
def test_foreign_control_point_name_is_one_error_naming_point_function(tmp_path):
    rec = tmp_path / "records.toml"
    rec.write_text(FOREIGN_POINTS.format(point_function=""), encoding="utf-8")
    res = _cli("verify", str(rec))
    assert res.returncode == 2, res.stdout + res.stderr
    assert "record 'sd.ends'" in res.stderr and "point_function = 'P'" in res.stderr
    assert "Traceback" not in res.stderr
    # naming them makes both passes (symbolic and per degree) read P as the points: true
    rec.write_text(FOREIGN_POINTS.format(point_function='point_function = "P"'), encoding="utf-8")
    res = _cli("verify", str(rec))
    assert res.returncode == 0, res.stdout + res.stderr
    assert "1 match" in res.stdout


BASIS_LIST = """\
schema_version = 2
source = "test"
title = "a misprinted basis list"

[[record]]
id = "bl.cubic0"
claim = "same_degree.basis_list"
location = "eq. (1)"
expect = "mismatch"
variable = "t"
n = 3
equations = [{ lhs = "b(0, 3, t)", rhs = "(1 - t)**3" }]
[record.erratum]
origin = "paper"
explanation = "b(0, 3, t) has a lam term"
equations = [{ lhs = "b(0, 3, t)", rhs = "(1 - t)**2*(1 - lam*t)" }]
"""


@needs_derive
def test_basis_list_mismatch_has_a_location(tmp_path):
    rec = tmp_path / "records.toml"
    rec.write_text(BASIS_LIST, encoding="utf-8")
    res = _cli("verify", str(rec))
    assert res.returncode == 0, res.stdout + res.stderr
    assert "at n=3: printed" in res.stdout and "at :" not in res.stdout, res.stdout


# --------------------------------------------------------------------------- item 3


def test_optimal_lambda_with_a_4000_digit_coordinate_prints_the_exact_result():
    import json

    big = "1" * 4000
    res = _cli("optimal-lambda", "--json", "0,0", f"1,{big}", "2,1", "3,0")
    assert res.returncode == 0, res.stderr
    got = json.loads(res.stdout)
    limit = sys.get_int_max_str_digits()
    sys.set_int_max_str_digits(0)
    try:
        pts = [(0, 0), (1, int(big)), (2, 1), (3, 0)]
        want = lb.optimal_lambda(pts, 2)
        assert got["lambda"] == str(want.unconstrained)
        assert got["energy"] == str(want.unconstrained_energy)
    finally:
        sys.set_int_max_str_digits(limit)
    # beyond Python's own limit on a number's text: refused, named, exit 2
    res = _cli("optimal-lambda", "0,0", "1," + "1" * 5000, "2,1", "3,0")
    assert res.returncode == 2 and "5000 digits" in res.stderr and "Traceback" not in res.stderr


@pytest.mark.parametrize(
    "args",
    [
        ("derive", "--root", "/nonexistent", "--check"),
        ("derive", "--root", "/nonexistent"),
        ("derive", "--root", "/tmp", "--check"),
        ("derive", "--root", "/tmp"),
        ("derive", "--root", str(ROOT / "pyproject.toml")),
        ("verify", "--root", "/nonexistent"),
        ("verify", "--root", "/tmp"),
        ("verify", "/nonexistent.toml"),
        ("verify", "/tmp"),
        ("derive", "--family", "/nonexistent.toml"),
        ("derive", "--family", "/tmp"),
        (
            "derive",
            "--family",
            str(ROOT / "src/lambda_bezier/examples/nouri_saeidian.toml"),
            "--out",
            "/nonexistent",
        ),
        ("export", "--format", "svg", "/nonexistent.json", "out.svg"),
        ("export", "--format", "svg", "/tmp", "out.svg"),
        ("export", "--format", "svg", "--tolerance", "nan", "/tmp", "out.svg"),
        ("export", "--format", "svg", "--tolerance", "-1", "/tmp", "out.svg"),
        ("export", "--format", "svg", "--tolerance", "abc", "/tmp", "out.svg"),
        ("optimal-lambda", "0,0", "1,1e400", "2,0", "3,1"),
        ("optimal-lambda", "0,0", "1,1/0", "2,0", "3,1"),
        ("optimal-lambda", "--energy", "99999999999999999999", "0,0", "1,1", "2,0", "3,1"),
        ("optimal-lambda", "--energy", "x", "0,0", "1,1", "2,0", "3,1"),
    ],
)
def test_cli_paths_and_numbers_are_named_with_exit_2(args, tmp_path):
    if args[0] == "derive" and not HAS_DERIVE:
        pytest.skip("needs the source checkout")
    res = _cli(*args, cwd=tmp_path if args[0] == "export" else ROOT)
    assert res.returncode == 2, (res.returncode, res.stderr)
    assert "Traceback" not in res.stderr and res.stderr.strip(), res.stderr


# --------------------------------------------------------------------------- item 4


def _exact_bezier(points, t: Fraction) -> list[Fraction]:
    """de Casteljau in Fractions: the independent reference."""
    work = [[Fraction(x) for x in p] for p in points]
    while len(work) > 1:
        work = [
            [(1 - t) * a + t * b for a, b in zip(p, q, strict=True)]
            for p, q in zip(work, work[1:], strict=False)
        ]
    return work[0]


def test_degree_zero_curve_has_zero_length_and_evaluates_in_batches():
    c = lb.BezierCurve([(0, 0)])
    assert c.arc_length() == 0.0 and c.arc_length(0.25, 0.5) == 0.0
    got = lb.evaluate_many(np.array([[(1.0, 2.0)], [(3.0, -1.0)]]), [0.0, 0.5, 1.0])
    assert got.shape == (2, 3, 2)
    assert (got[0] == (1.0, 2.0)).all() and (got[1] == (3.0, -1.0)).all()
    assert (lb.evaluate_many(np.array([[(1.0, 2.0)]]), [0.3], k=1) == 0).all()


def test_centred_expansion_equals_the_generated_tables():
    from lambda_bezier._lazy import generated
    from lambda_bezier.hazmat import forms

    tables = generated("bernstein")
    for degree in tables.DEGREES:
        want = tuple(tuple(Fraction(v) for v in row) for row in tables.CENTRED[degree])
        assert forms.centred_expansion(degree) == want


@pytest.mark.parametrize("degree", [15, 20, 27])
def test_classical_curves_past_the_tables(degree):
    import mpmath as mp

    rng = np.random.default_rng(degree)
    # a monotone polygon: the speed has no zero, so plain quadrature is exact to its precision
    pts = np.cumsum(rng.uniform(0.2, 1.0, size=(degree + 1, 2)), axis=0)
    exact = [[Fraction(float(x)) for x in p] for p in pts]
    c = lb.BezierCurve(pts)
    mp.mp.dps = 30

    def speed(t):
        w = [
            [
                mp.mpf((d := degree * (b - a)).numerator) / d.denominator
                for a, b in zip(p, q, strict=True)
            ]
            for p, q in zip(exact, exact[1:], strict=False)
        ]
        while len(w) > 1:
            w = [
                [(1 - t) * a + t * b for a, b in zip(p, q, strict=True)]
                for p, q in zip(w, w[1:], strict=False)
            ]
        return mp.sqrt(sum(x * x for x in w[0]))

    for t0, t1 in ((0, 1), (0.2, 0.7)):
        ref = mp.quad(speed, [t0, (t0 + t1) / 2, t1])
        assert abs(c.arc_length(t0, t1) - ref) <= 1e-12 * ref
    s = c.arc_length()
    t_half = c.parameter_at_length(s / 2)
    assert abs(c.arc_length(0, t_half) - s / 2) <= 1e-12 * s
    lo, hi = c.bounding_box()
    samples = np.array(
        [[float(v) for v in _exact_bezier(exact, Fraction(k, 64))] for k in range(65)]
    )
    assert (samples >= lo - 1e-12 * abs(lo)).all() and (samples <= hi + 1e-12 * abs(hi)).all()
    q = samples[20] + np.array([0.01, -0.01])
    assert c.closest_point(q).distance <= np.linalg.norm(q - samples[20]) + 1e-12
    many = lb.evaluate_many(pts[None], [0.0, 0.3, 1.0])[0]
    want = [[float(v) for v in _exact_bezier(exact, Fraction(x))] for x in (0, Fraction(3, 10), 1)]
    np.testing.assert_allclose(many, want, rtol=1e-13, atol=0)


@pytest.mark.parametrize("name", ["same_degree", "bernstein_like"])
def test_lambda_families_refuse_degrees_past_their_tables(name):
    cls = lb.FAMILIES[name]
    lo, hi = cls._data.DEGREES[0], cls._data.DEGREES[-1]
    for degree in (lo - 1, hi + 1):
        with pytest.raises(ValueError, match=f"{name}"):
            cls([(k, k % 2) for k in range(degree + 1)], 0.5)
    with pytest.raises(ValueError, match="not supported|at least"):
        lb.evaluate_many(np.zeros((1, hi + 2, 2)), [0.5], name, lam=0.5)


# --------------------------------------------------------------------------- item 5


@pytest.mark.parametrize("name", ["bezier", "same_degree", "bernstein_like"])
def test_implicitize_takes_floats_exactly(name):
    import sympy as sp

    pts = [(0.1, 0.0), (0.7, 1.3), (1.9, -0.2), (2.5, 0.4)]
    cls = lb.FAMILIES[name]
    curve = cls(pts) if name == "bezier" else cls(pts, 0.3)
    f = curve.implicitize()
    # the same curve in Fractions: f vanishes exactly on its points
    exact = [[Fraction(x) for x in p] for p in pts]
    ecurve = cls(exact) if name == "bezier" else cls(exact, Fraction(0.3))
    bez = ecurve.to_bezier().control_points()
    x, y = f.gens
    for t in (Fraction(1, 3), Fraction(5, 7)):
        px, py = _exact_bezier(bez, t)
        assert f.as_expr().subs({x: sp.Rational(px), y: sp.Rational(py)}) == 0
    assert f == ecurve.implicitize()


# --------------------------------------------------------------------------- item 8


@pytest.mark.parametrize("exponent", [600, 1000, 1020, -600, -1000])
def test_closest_point_at_huge_and_tiny_scales(exponent):
    base = np.array([(0, 0), (1, 2), (3, 1), (4, 0)], dtype=float)
    queries = np.array([(2.0, 3.0), (-1.0, 0.5), (4.5, -0.25)])
    want = lb.BezierCurve(base).closest_point(queries)
    s = 2.0**exponent
    got = lb.BezierCurve(base * s).closest_point(queries * s)
    np.testing.assert_allclose(got.t, want.t, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(got.point / s, want.point, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(got.distance / s, want.distance, rtol=1e-12)


# --------------------------------------------------------------------------- item 7


@pytest.mark.parametrize("degree", [10, 11])
def test_dxf_writes_only_what_ezdxf_reads_back_and_evaluates(degree, tmp_path):
    ezdxf = pytest.importorskip("ezdxf")
    from lambda_bezier import export

    pts = [(i, (-1) ** i * (1 + i % 3)) for i in range(degree + 1)]
    curve = lb.BezierCurve(pts)
    target = tmp_path / "x.dxf"
    if degree > export.DXF_MAX_DEGREE:
        with pytest.raises(ValueError, match="up to 10"):
            export.to_dxf(curve, target)
        # the limit is ezdxf's: its construction tool cannot evaluate a degree-11 spline
        from ezdxf.math import BSpline

        spline = export.to_bspline(curve)
        with pytest.raises(ValueError, match="invalid order"):
            BSpline(spline.control_points, order=degree + 1, knots=spline.knots).point(0.5)
        return
    export.to_dxf(curve, target)
    tool = next(iter(ezdxf.readfile(target).modelspace().query("SPLINE"))).construction_tool()
    u = np.linspace(0, 1, 41)
    got = np.array([tuple(tool.point(x)) for x in u])[:, :2]
    np.testing.assert_allclose(got, curve.evaluate(u), atol=1e-12)
