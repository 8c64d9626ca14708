"""Issues #30 and #32, third acceptance pass: what a new user met beyond the first two passes
(tests/test_acceptance_30.py, test_acceptance_30b*.py). Each test failed on the code before
its fix; every reference is computed here, from formulas written in this file (mpmath,
SymPy), never from the derived documents or the runtime's basis.

- A hyperbolic C-Bézier family on a wide box (0, 40]: its float atom form cancels at large
  alpha (terms near e^alpha / 4 for basis values in [0, 1]); a curve there was silently wrong
  by 2 (P_0 came out as (0.95, 2)). Now refused by name, and right where accepted.
- STEP, DXF, SVG and B-spline export of a C-Bézier curve (and of a composite holding one)
  stopped with AttributeError ('CBezierCurve' object has no attribute 'to_bezier'), from the
  Python API and from `lambda-bezier export`. Now certified polynomial pieces, as for a mixed
  family's curves.
- A join from an exact trigonometric curve into a family of one's own (a polynomial family in
  two parameters) came out in floats, its first point an ulp off the curve's end, although
  sin and cos are 0 or 1 at the end of [0, pi/2]. Now exact.
- `derive --family` named the file in most refusals, not in all (partition of unity, a
  polynomial basis on [0, pi], `inf` in a range); `load_family` of a derived document (JSON)
  said "not valid TOML: Invalid statement".
"""

from __future__ import annotations

import math
from fractions import Fraction
from pathlib import Path

import mpmath as mp
import numpy as np
import pytest
import sympy as sp

import lambda_bezier as lb
from lambda_bezier import cli, examples, export
from lambda_bezier.joins import Joint, leading_weights

DATA = Path(__file__).parent / "data" / "families"
POLYGON = [(0, 0), (1, 2), (3, 2), (4, 0)]


# ---- the C-Bézier cubics, written here from their definitions ------------------------------


def _c_bezier(t, a, sin, cos):
    """Zhang's C-Bézier cubic on [0, a] (sin, cos) or its hyperbolic analogue (sinh, cosh),
    the functions with the Bernstein end conditions, in the form the papers print."""
    hyperbolic = sin is mp.sinh or sin is math.sinh
    if hyperbolic:
        d = sin(a) - a
        e = 2 * cos(a) - 2 - a * sin(a)
        k = cos(a) - 1
        first = sin(a - t) - a + t
        last = sin(t) - t
        return [
            first / d,
            k * (k * first - d * (cos(a - t) - 1)) / (d * e),
            k * (k * last - d * (cos(t) - 1)) / (d * e),
            last / d,
        ]
    d = a - sin(a)
    e = a * sin(a) + 2 * cos(a) - 2
    k = 1 - cos(a)
    first = a - t - sin(a - t)
    last = t - sin(t)
    return [
        first / d,
        k * (k * first - d * (1 - cos(a - t))) / (d * e),
        k * (k * last - d * (1 - cos(t))) / (d * e),
        last / d,
    ]


def _point(t, a, functions):
    b = _c_bezier(t, a, *functions)
    return [sum(bi * p[k] for bi, p in zip(b, POLYGON, strict=True)) for k in range(2)]


def test_a_wide_hyperbolic_c_bezier_curve_is_right_or_refused_by_name():
    fam = lb.load_family(DATA / "hc_bezier_wide.toml")
    mp.mp.dps = 60
    try:
        accepted = []
        for alpha in (4.0, 10.0, 20.0, 30.0, 40.0):
            try:
                curve = fam.curve(POLYGON, alpha=alpha)
            except ValueError as exc:
                assert f"alpha = {alpha}" in str(exc) and "floats" in str(exc)
                continue
            accepted.append(alpha)
            for t in np.linspace(0.0, alpha, 9):
                want = _point(mp.mpf(t), mp.mpf(alpha), (mp.sinh, mp.cosh))
                got = curve.evaluate(t)
                assert max(abs(float(g - w)) for g, w in zip(got, want, strict=True)) < 1e-6
        # refusing everything would pass the loop: the box's low end is accepted
        assert 4.0 in accepted and 10.0 in accepted
        # at alpha = 40 the float atom form is wrong by about 2 (the old answer for P_0)
        assert 40.0 not in accepted
    finally:
        mp.mp.dps = 15


# ---- export of C-Bézier curves ------------------------------------------------------------


def _distance_to_reference(points: np.ndarray, alpha: float) -> float:
    """The largest distance of `points` from the C-Bézier cubic at alpha (closest parameter:
    the nearest of a dense sample, then a golden-section search about it)."""
    trig = (math.sin, math.cos)
    ts = np.linspace(0.0, alpha, 4001)
    dense = np.array([_point(t, alpha, trig) for t in ts])
    h = ts[1] - ts[0]
    worst = 0.0
    for x in points:
        j = int(np.argmin(((dense - x) ** 2).sum(axis=1)))
        lo, hi = max(ts[j] - h, 0.0), min(ts[j] + h, alpha)
        g = (math.sqrt(5) - 1) / 2
        for _ in range(80):
            m1, m2 = hi - g * (hi - lo), lo + g * (hi - lo)
            d1 = math.dist(x, _point(m1, alpha, trig))
            d2 = math.dist(x, _point(m2, alpha, trig))
            lo, hi = (lo, m2) if d1 < d2 else (m1, hi)
        worst = max(worst, math.dist(x, _point((lo + hi) / 2, alpha, trig)))
    return worst


def test_a_c_bezier_curve_exports_within_its_tolerance(tmp_path):
    fam = lb.load_family(examples.path("c_bezier_cubic.toml"))
    curve = fam.curve(POLYGON, alpha=2.0)
    tolerance = 1e-9
    spline = export.to_bspline(curve, tolerance=tolerance)
    u = np.linspace(0.0, float(spline.knots[-1]), 121)
    samples = np.array([[float(v) for v in spline.point(x)] for x in u])
    assert np.allclose(samples[0], POLYGON[0], atol=tolerance)
    assert np.allclose(samples[-1], POLYGON[-1], atol=tolerance)
    # 1e-12 over the tolerance: the reference's own rounding and the search's
    assert _distance_to_reference(samples, 2.0) <= tolerance + 1e-12
    step = export.to_step(curve, tmp_path / "c.step")
    assert "B_SPLINE_CURVE_WITH_KNOTS" in step.read_text()
    assert export.to_dxf(curve, tmp_path / "c.dxf").stat().st_size > 0
    svg = export.to_svg(curve, tolerance=1e-6)
    assert svg.count(" C ") + svg.count(' d="M') >= 2
    with pytest.raises(NotImplementedError, match="not a polynomial curve"):
        curve.to_bezier()


def test_a_composite_with_a_c_bezier_segment_exports(tmp_path):
    fam = lb.load_family(examples.path("c_bezier_cubic.toml"))
    curve = fam.curve(POLYGON, alpha=2.0)
    nxt = lb.join(curve, "C1", 3, family="bezier", rest=[(8, 1), (9, 0)])
    spline = export.to_bspline(lb.CompositeCurve([curve, nxt]))
    first = np.array([float(v) for v in spline.point(spline.knots[0])])
    last = np.array([float(v) for v in spline.point(spline.knots[-1])])
    assert np.allclose(first, POLYGON[0], atol=1e-12) and np.allclose(last, (9, 0), atol=1e-12)
    # the joint (4, 0) lies on the spline: one B-spline through both segments
    u = np.linspace(0.0, float(spline.knots[-1]), 2001)
    pts = np.array([[float(v) for v in spline.point(x)] for x in u])
    assert np.min(np.hypot(pts[:, 0] - 4, pts[:, 1])) < 1e-3


def test_cli_exports_a_c_bezier_curve(tmp_path, capsys):
    fam = lb.load_family(examples.path("c_bezier_cubic.toml"))
    source = tmp_path / "curve.json"
    source.write_text(export.to_json(fam.curve(POLYGON, alpha=2.0)))
    family = str(examples.path("c_bezier_cubic.toml"))
    for fmt in ("step", "dxf"):
        target = tmp_path / f"curve.{fmt}"
        argv = ["export", "--format", fmt, "--family", family, str(source), str(target)]
        assert cli.main(argv) == 0, capsys.readouterr().err
        assert target.stat().st_size > 0
    target = tmp_path / "curve.svg"
    argv = ["export", "--format", "svg", "--tolerance", "1e-6", "--family", family]
    assert cli.main([*argv, str(source), str(target)]) == 0, capsys.readouterr().err
    assert target.read_text().startswith("<?xml")


# ---- joins from an exact trigonometric curve ----------------------------------------------


def _han_trig(t, lam, mu):
    s, c = sp.sin(t), sp.cos(t)
    return [
        (1 - s) ** 2 * (1 - lam * s),
        s * (1 - s) * (2 + lam - lam * s),
        c * (1 - c) * (2 + mu - mu * c),
        (1 - c) ** 2 * (1 - mu * c),
    ]


def _two_shape(t, lam, mu):
    return [
        (1 - lam * t) * (1 - t) ** 3,
        t * (1 - t) ** 2 * (3 + lam * (1 - t)),
        t**2 * (1 - t) * (3 + mu * t),
        (1 - mu + mu * t) * t**3,
    ]


@pytest.mark.parametrize("continuity", ["C1", "C2", "G2"])
def test_a_join_from_an_exact_trigonometric_curve_into_an_own_family_is_exact(continuity):
    trig = lb.load_family(examples.path("han_trig_cubic.toml"))
    two = lb.load_family(examples.path("two_shape_cubic.toml"))
    lam1, mu1 = Fraction(1, 2), Fraction(-1)
    lam2, mu2 = Fraction(0), Fraction(1, 2)
    alpha, d = (Fraction(2), Fraction(1, 3)) if continuity == "G2" else (1, 0)
    order = 1 if continuity == "C1" else 2
    rest = [(9, 1), (10, 0)][order - 1 :]
    curve = trig.curve(POLYGON, lam=lam1, mu=mu1)
    got = lb.join(curve, continuity, 3, family=two, lam=lam2, mu=mu2, rest=rest, alpha=alpha, d=d)
    assert all(isinstance(v, Fraction) for row in got.control_points() for v in row)
    # SymPy from the two definitions: C2(0) = C1(pi/2), C1' = alpha C2', C1'' = alpha^2 C2'' + d C2'
    t = sp.Symbol("t")
    first = [sp.Matrix(p) for p in POLYGON]
    b1 = _han_trig(t, sp.Rational(lam1), sp.Rational(mu1))
    c1 = sum((b * p for b, p in zip(b1, first, strict=True)), sp.zeros(2, 1))
    unknown = [sp.Matrix(sp.symbols(f"x{j} y{j}")) for j in range(order + 1)]
    second = unknown + [sp.Matrix(p) for p in rest]
    b2 = _two_shape(t, sp.Rational(lam2), sp.Rational(mu2))
    c2 = sum((b * p for b, p in zip(b2, second, strict=True)), sp.zeros(2, 1))
    end = [sp.simplify(c1.diff(t, r).subs(t, sp.pi / 2)) for r in range(order + 1)]
    start = [c2.diff(t, r).subs(t, 0) for r in range(order + 1)]
    a, dd = sp.Rational(alpha), sp.Rational(d)
    equations = [end[0] - start[0], end[1] - a * start[1]]
    if order == 2:
        equations.append(end[2] - a**2 * start[2] - dd * start[1])
    unknowns = [s for m in unknown for s in m]
    solution = sp.solve([e for m in equations for e in m], unknowns, dict=True)[0]
    want = [tuple(Fraction(str(solution[s])) for s in m) for m in unknown]
    assert list(got.control_points()[: order + 1]) == want
    assert list(got.control_points()[order + 1 :]) == [tuple(map(Fraction, p)) for p in rest]


# ---- refusals that name the file ----------------------------------------------------------

_HEAD = '[family]\nname = "{name}"\n'
_ILL = {
    "not_unity": (
        'parameters = ["lam", "mu"]\nrange = { lam = "[-2, 1]", mu = "[-2, 1]" }\n'
        'degrees = "1"\nfunctions = ["1 - t + lam*t", "t"]\n',
        "no partition of unity",
    ),
    "inf_range": (
        'parameter = "lam"\nrange = "[0, inf]"\ndegrees = "1"\nfunctions = ["1 - t", "t"]\n',
        "unknown name 'inf'",
    ),
    "poly_on_pi": (
        'parameter = "lam"\nrange = "[0, 1]"\ndomain = "[0, pi]"\ndegrees = "1"\n'
        'functions = ["1 - t/pi", "t/pi"]\n',
        "a polynomial basis is derived on [0, 1] only",
    ),
}


@pytest.mark.parametrize("name", sorted(_ILL))
def test_derive_names_the_file_in_every_refusal(tmp_path, capsys, name):
    body, problem = _ILL[name]
    path = tmp_path / f"{name}.toml"
    path.write_text(_HEAD.format(name=name) + body)
    assert cli.main(["derive", "--family", str(path), "--out", str(tmp_path), "-q"]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"lambda-bezier derive: {path}: ") and problem in err
    assert "Traceback" not in err
    assert not (tmp_path / f"{name}.derived.json").exists()


def test_a_derived_document_given_as_the_family_says_what_to_pass(tmp_path, capsys):
    derived = examples.path("nouri_saeidian.derived.json")
    with pytest.raises(ValueError, match="not a family definition") as caught:
        lb.load_family(derived)
    assert str(derived) in str(caught.value) and "TOML" in str(caught.value)
    argv = ["optimal-lambda", "--family", str(derived), "0,0", "1,2", "3,2", "4,0"]
    assert cli.main(argv) == 2
    assert "not a family definition" in capsys.readouterr().err


# ---- a C-Bézier family's own parameter name (#32: its names are its own) -----------------


def test_a_c_bezier_curve_takes_its_parameter_by_its_own_name_only():
    # c_bezier_h.toml: the C-Bézier cubic with its parameter called h. `alpha=` (the name of
    # curve()'s own argument) was accepted for it, and `params={"h": ...}` refused
    own = lb.load_family(DATA / "c_bezier_h.toml")
    by_name = own.curve(POLYGON, h=2.0)
    assert repr(by_name) == "CBezierCurve(c_bezier_h, h=2.0, dimension=2)"
    by_params = own.curve(POLYGON, params={"h": 2.0})
    assert np.array_equal(by_params.evaluate(1.0), by_name.evaluate(1.0))
    want = _point(1.0, 2.0, (math.sin, math.cos))
    assert np.allclose(by_name.evaluate(1.0), want, rtol=0, atol=1e-14)
    with pytest.raises(TypeError, match="'alpha' is not a parameter of 'c_bezier_h'"):
        own.curve(POLYGON, alpha=2.0)
    with pytest.raises(TypeError, match="once"):
        own.curve(POLYGON, h=2.0, params={"h": 2.0})


# ---- one-parameter functions given an indexed or a C-Bézier family ------------------------


C1 = Joint("C1", 1, 0)


@pytest.mark.parametrize(
    "call",
    [
        lambda q: lb.energy_matrices(3, 2, family=q),
        lambda q: lb.energy_coefficients(POLYGON, 2, family=q),
        lambda q: lb.optimal_lambda(POLYGON, 2, family=q),
        lambda q: leading_weights(lb.BezierCurve([(0, 0), (1, 1), (2, 0)]), C1, q, 3, [0, 0, 0]),
    ],
    ids=["energy_matrices", "energy_coefficients", "optimal_lambda", "leading_weights"],
)
def test_an_indexed_family_in_a_one_parameter_function_is_a_type_error(call):
    # these read the indexed family's lowest degree's tables: an AttributeError ('SeveralData'
    # object has no attribute 'ENERGY' / 'POWER'), or "degree 3 is not supported for
    # q_bezier: generated data covers degrees 2..2" for a family of degrees 2..5
    q = lb.load_family(DATA / "q_bezier.toml")
    with pytest.raises(TypeError, match=r"'q_bezier' has one parameter per index \(lam\(i\)\)"):
        call(q)


def test_a_c_bezier_family_surface_is_refused_naming_what_takes_it():
    from lambda_bezier.param_surfaces import family_surface

    fam = lb.load_family(examples.path("c_bezier_cubic.toml"))
    net = [[(i, j, (i * j) % 3) for j in range(4)] for i in range(4)]
    # was AttributeError: 'CBezierFamily' object has no attribute 'parameter_values'
    with pytest.raises(TypeError, match="'c_bezier_cubic' has its parameter alpha in the domain"):
        family_surface(net, fam, params_u={"alpha": 1}, params_v={"alpha": 1})


# ---- a hyperbolic family with fast decaying atoms -----------------------------------------


def _fast_decay(t, lam, k=0):
    """b_0 = e^(-40 t), b_2 = lam (e^(-20 t) - e^(-40 t)), b_1 = 1 - b_0 - b_2: the k-th
    derivatives, in mpmath."""
    e40 = (-40) ** k * mp.exp(-40 * t)
    e20 = (-20) ** k * mp.exp(-20 * t)
    b2 = lam * (e20 - e40)
    return [e40, (1 if k == 0 else 0) - e40 - b2, b2]


def test_a_fast_decaying_hyperbolic_curve_against_its_definition():
    # e^(-40 t) over cosh(40 t), sinh(40 t), centred about t = 1/2 in floats: C(0) came out
    # as (2.5, 1) instead of P_0 = (0, 0), C(1) 29 off; its arc length then never ended
    fam = lb.load_family(DATA / "hyp_fast_decay.toml")
    points = [(0, 0), (1, 2), (4, 0)]
    curve = fam.curve(points, lam=Fraction(1, 2))
    lam = mp.mpf(1) / 2
    mp.mp.dps = 40
    try:
        for k in (0, 1, 2):
            scale = 40.0**k
            for t in (0.0, 0.01, 0.1, 0.5, 0.9, 1.0):
                b = _fast_decay(mp.mpf(t), lam, k)
                want = [sum(bi * p[c] for bi, p in zip(b, points, strict=True)) for c in range(2)]
                got = curve.derivative(t, k) if k else curve.evaluate(t)
                assert (
                    max(abs(float(g - w)) for g, w in zip(got, want, strict=True)) < 1e-13 * scale
                )

        def speed(t):
            b = _fast_decay(t, lam, 1)
            return mp.hypot(
                *(sum(bi * p[c] for bi, p in zip(b, points, strict=True)) for c in (0, 1))
            )

        length = mp.quad(speed, [0, 0.01, 0.05, 0.1, 0.3, 1])
        assert abs(curve.arc_length() - length) <= 1e-12 * length
    finally:
        mp.mp.dps = 15
    assert np.allclose(curve.derivative(0.0), [70, 60], rtol=1e-14, atol=0)  # 30 P_1 + 10 P_2
