"""Exact B-splines, and every exported file read back by the library that consumes it:
OCCT reads the STEP file, ezdxf the DXF file, svgpathtools the SVG; JSON round-trips."""

from __future__ import annotations

import json
import math
import subprocess
import sys
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

import lambda_bezier as lb
from lambda_bezier import export
from lambda_bezier.cli import main


def bernstein_value(rows, t):
    """Σ P_i C(n,i) t^i (1-t)^(n-i) in the arithmetic of the inputs (independent of the
    library's de Casteljau)."""
    n = len(rows) - 1
    return tuple(
        sum(math.comb(n, i) * t**i * (1 - t) ** (n - i) * rows[i][c] for i in range(n + 1))
        for c in range(len(rows[0]))
    )


def composite(dim=2, exact=True):
    pts = (
        [(0, 0), (1, 2), (3, 2), (4, 0)]
        if dim == 2
        else [(0, 0, 0), (1, 2, 1), (3, 2, -1), (4, 0, 2)]
    )
    rest1 = [(9, -1), (10, 1)] if dim == 2 else [(9, -1, 1), (10, 1, 0)]
    rest2 = [(14, 3)] if dim == 2 else [(14, 3, 2)]
    rest3 = [(15, 5), (17, 4)] if dim == 2 else [(15, 5, 1), (17, 4, 0)]
    half = Fraction(1, 2) if exact else 0.5
    if not exact:
        pts = np.array(pts, float)
    first = lb.BernsteinLikeCurve(pts, lam=half)
    return (
        lb.CompositeCurve([first])
        .join("C2", 4, 0, rest=rest1)
        .join("G2", 3, -half, alpha=2, d=1, rest=rest2, family="same_degree")
        .join("C1", 3, rest=rest3, family="bezier")
    )


OBJECTS = {
    "same_degree": lb.SameDegreeCurve([(0, 0), (1, 2), (3, 2), (4, 0)], lam=Fraction(1, 2)),
    "bernstein_like-3d": lb.BernsteinLikeCurve(
        [(0, 0, 0), (1, 2, 1), (3, 2, -1), (4, 0, 2), (5, 1, 1)], lam=Fraction(-1, 3)
    ),
    "bezier": lb.BezierCurve([(0, 0), (1, 3), (2, 1), (3, 3)]),
    "composite-2d": composite(2),
    "composite-3d": composite(3),
    "composite-float": composite(2, exact=False),
}


def domain(obj):
    return len(obj.segments) if isinstance(obj, lb.CompositeCurve) else 1


# ---------------------------------------------------------------------- B-spline
@pytest.mark.parametrize("name", OBJECTS)
def test_bspline_reproduces_the_curve(name):
    obj = OBJECTS[name]
    spline = export.to_bspline(obj)
    p = spline.degree
    assert len(spline.knots) == len(spline.control_points) + p + 1
    assert spline.knots[: p + 1] == (0,) * (p + 1)
    u = np.linspace(0, domain(obj), 97)
    np.testing.assert_allclose(spline.evaluate(u), obj.evaluate(u), atol=1e-12)
    if spline.exact:  # equal as rational functions: exact values at rational u
        segs = obj.segments if isinstance(obj, lb.CompositeCurve) else (obj,)
        for j, seg in enumerate(segs):
            rows = seg.to_bezier().control_points()
            for t in (Fraction(1, 3), Fraction(5, 7), Fraction(1)):
                assert spline.point(j + t) == bernstein_value(rows, t)


def test_knot_multiplicities_follow_the_achieved_continuity():
    comp = composite(2)
    spline = export.to_bspline(comp)
    p = spline.degree
    assert p == 6  # the quartic bernstein_like segment... and the first: n + 2 = 5; C2 seg 4
    values, mults = spline.breakpoints()
    assert values == [0, 1, 2, 3, 4]
    # C2 (built, and measured by report()), G2 with α = 2 (only C0 in u), C1
    achieved = [r.achieved for r in comp.report()]
    assert "C2" in achieved[0] and "C1" not in achieved[1] and "C1" in achieved[2]
    assert mults == [p + 1, p - 2, p, p - 1, p + 1]


def test_a_split_curve_is_one_polynomial_piece():
    # halves of one curve, each on a unit interval of u: the same polynomial in u, C^∞
    b = lb.BezierCurve([(0, 0), (1, 3), (2, 1), (3, 3), (5, 0), (6, 2)])
    left, right = b.split(Fraction(1, 2))
    spline = export.to_bspline(lb.CompositeCurve([left, right]))
    assert spline.breakpoints() == ([0, 2], [6, 6])
    assert spline.control_points == b.control_points()


def random_joined_composite(data):
    """An exact composite of three segments of random families, joined C1/C2/G1/G2."""
    coord = st.integers(-9, 9)
    families = st.sampled_from(["bezier", "same_degree", "bernstein_like"])

    def curve_args(fam, count):
        pts = data.draw(st.lists(st.tuples(coord, coord), min_size=count, max_size=count))
        lam = None if fam == "bezier" else Fraction(data.draw(st.integers(-2, 2)), 4)
        return pts, lam

    fam = data.draw(families)
    pts, lam = curve_args(fam, data.draw(st.integers(4, 6)))
    first = lb.FAMILIES[fam](pts) if lam is None else lb.FAMILIES[fam](pts, lam)
    comp, built = lb.CompositeCurve([first]), []
    for _ in range(2):
        cont = data.draw(st.sampled_from(["C1", "C2", "G1", "G2"]))
        fam2, m = data.draw(families), data.draw(st.integers(4, 5))
        rest, lam2 = curve_args(fam2, m - (1 if cont[1] == "1" else 2))
        alpha = Fraction(data.draw(st.integers(1, 3))) if cont[0] == "G" else 1
        comp = comp.join(cont, m, lam2, alpha=alpha, rest=rest, family=fam2)
        built.append(cont)
    return comp, built


@settings(max_examples=20, deadline=None)
@given(data=st.data())
def test_bspline_of_random_joined_composites(data):
    """The B-spline equals every piece exactly, and each joint's knot multiplicity is at
    most p − k for the k its construction guarantees (C1, C2; a G joint may happen to be
    C1 in u, when α = 1)."""
    try:
        comp, built = random_joined_composite(data)
    except ValueError:  # a degenerate end or a vanishing pivot: join says which
        assume(False)
    spline = export.to_bspline(comp)
    p = spline.degree
    for j, seg in enumerate(comp.segments):
        rows = seg.to_bezier().control_points()
        for t in (Fraction(1, 5), Fraction(2, 3)):
            assert spline.point(j + t) == bernstein_value(rows, t)
    _, mults = spline.breakpoints()
    for cont, mult in zip(built, mults[1:-1], strict=True):
        assert mult <= p - {"C1": 1, "C2": 2}.get(cont, 0)


def test_bspline_refuses_a_gap():
    a = lb.BezierCurve([(0, 0), (1, 1)])
    b = lb.BezierCurve([(2, 1), (3, 0)])
    with pytest.raises(ValueError, match="not continuous at joint 0"):
        export.to_bspline(lb.CompositeCurve([a, b]))
    with pytest.raises(TypeError, match="lambda_bezier curve"):
        export.to_bspline([(0, 0), (1, 1)])


# ---------------------------------------------------------------------- JSON
@pytest.mark.parametrize("name", OBJECTS)
def test_json_round_trips_exactly(name):
    obj = OBJECTS[name]
    text = export.to_json(obj)
    back = export.from_json(text)
    assert type(back) is type(obj)
    assert export.to_json(back) == text
    segs = (obj.segments, back.segments) if isinstance(obj, lb.CompositeCurve) else ([obj], [back])
    for a, b in zip(*segs, strict=True):
        assert a.family == b.family and a.control_points() == b.control_points()
        assert a.lam == b.lam and type(a.lam) is type(b.lam)
    if isinstance(obj, lb.CompositeCurve):
        assert back.joints == obj.joints
    doc = json.loads(text)
    assert doc["lambda_bezier"] == 1


def test_json_form_is_as_documented():
    doc = json.loads(export.to_json(OBJECTS["composite-2d"]))
    assert doc["kind"] == "composite"
    assert doc["segments"][0] == {
        "family": "bernstein_like",
        "lambda": "1/2",
        "points": [["0", "0"], ["1", "2"], ["3", "2"], ["4", "0"]],
    }
    assert doc["joints"][1] == {"continuity": "G2", "alpha": "2", "d": "1"}
    float_doc = json.loads(export.to_json(OBJECTS["composite-float"]))
    assert float_doc["segments"][0]["lambda"] == 0.5


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("{", "not valid JSON"),
        ('{"kind": "curve"}', "not a lambda-bezier JSON document"),
        ('{"lambda_bezier": 1, "kind": "blob"}', '"kind" must be'),
        ('{"lambda_bezier": 1, "kind": "curve", "family": "nurbs"}', "family must be one of"),
        (
            '{"lambda_bezier": 1, "kind": "curve", "family": "bezier", "lambda": null,'
            ' "points": [["0", "x"], ["1", "1"]]}',
            r"points\[0\]\[1\]: not a number",
        ),
        (
            '{"lambda_bezier": 1, "kind": "curve", "family": "same_degree", "lambda": "-3",'
            ' "points": [["0", "0"], ["1", "1"], ["2", "0"], ["3", "1"]]}',
            "outside the same_degree range",
        ),
    ],
)
def test_from_json_errors(text, message):
    with pytest.raises(ValueError, match=message):
        export.from_json(text)


# ---------------------------------------------------------------------- SVG
def svg_paths(text, tmp_path):
    from svgpathtools import svg2paths

    file = tmp_path / "curve.svg"
    file.write_text(text)
    paths, _ = svg2paths(str(file))
    assert len(paths) == 1
    return paths[0]


def test_svg_is_exact_for_cubics(tmp_path):
    b = lb.BezierCurve([(0, 0), (1, 3), (2, 1), (3, 3)])
    q = lb.BezierCurve([(3, 3), (4, 5), (6, 3)])
    line = lb.BezierCurve([(6, 3), (7, 0)])
    sd = lb.SameDegreeCurve([(7, 0), (8, 1), (9, -1), (10, 0)], lam=Fraction(1, 3))
    comp = lb.CompositeCurve([b, q, line, sd])
    path = svg_paths(export.to_svg(comp), tmp_path)
    assert [type(s).__name__ for s in path] == [
        "CubicBezier",
        "QuadraticBezier",
        "Line",
        "CubicBezier",
    ]
    for j, seg in enumerate(path):
        for t in np.linspace(0, 1, 11):
            z = seg.point(t)
            want = comp.evaluate(j + t)
            assert abs(z.real - want[0]) <= 1e-13 and abs(z.imag - want[1]) <= 1e-13


@pytest.mark.parametrize("tolerance", [1e-2, 1e-5])
def test_svg_approximates_high_degree_within_the_tolerance(tmp_path, tolerance):
    comp = OBJECTS["composite-2d"]  # quintic, sextic pieces
    with pytest.raises(ValueError, match="pass tolerance="):
        export.to_svg(comp)
    path = svg_paths(export.to_svg(comp, tolerance=tolerance), tmp_path)
    assert all(type(s).__name__ in ("CubicBezier", "Line") for s in path)
    # every point of the path lies within the tolerance of the curve, and back
    ts = np.linspace(0, 1, 41)
    path_pts = np.array([[z.real, z.imag] for s in path for z in (s.point(t) for t in ts)])
    assert comp.closest_point(path_pts).distance.max() <= tolerance
    for x, y in comp.evaluate(np.linspace(0, len(comp), 61)):
        (nearest, _, _), _ = path.radialrange(complex(x, y))  # svgpathtools' own minimiser
        assert nearest <= tolerance * (1 + 1e-9)
    assert len(path) > 4


def test_svg_errors():
    with pytest.raises(ValueError, match="SVG paths are 2D"):
        export.to_svg(OBJECTS["composite-3d"])
    with pytest.raises(ValueError, match="positive distance"):
        export.to_svg(OBJECTS["bezier"], tolerance=-1)


# ---------------------------------------------------------------------- DXF
@pytest.mark.parametrize("name", OBJECTS)
def test_dxf_read_back_by_ezdxf(name, tmp_path):
    import ezdxf

    obj = OBJECTS[name]
    file = export.to_dxf(obj, tmp_path / "curve.dxf")
    doc = ezdxf.readfile(file)
    splines = list(doc.modelspace().query("SPLINE"))
    assert len(splines) == 1
    tool = splines[0].construction_tool()
    spline = export.to_bspline(obj)
    assert tool.degree == spline.degree
    u = np.linspace(0, domain(obj), 41)
    got = np.array([tuple(tool.point(x)) for x in u])[:, : obj.dimension]
    np.testing.assert_allclose(got, obj.evaluate(u), atol=1e-12)


def test_dxf_refuses_degrees_autocad_cannot_read(tmp_path):
    pts = [(i, (-1) ** i) for i in range(11)]
    with pytest.raises(ValueError, match="up to 10"):
        export.to_dxf(lb.BernsteinLikeCurve(pts, lam=0), tmp_path / "x.dxf")  # degree 12


# ---------------------------------------------------------------------- STEP
def occt_curves(path):
    from OCP.BRep import BRep_Tool
    from OCP.IFSelect import IFSelect_ReturnStatus
    from OCP.STEPControl import STEPControl_Reader
    from OCP.TopAbs import TopAbs_ShapeEnum
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS

    reader = STEPControl_Reader()
    assert reader.ReadFile(str(path)) == IFSelect_ReturnStatus.IFSelect_RetDone
    reader.TransferRoots()
    explorer = TopExp_Explorer(reader.OneShape(), TopAbs_ShapeEnum.TopAbs_EDGE)
    out = []
    while explorer.More():
        out.append(BRep_Tool.Curve_s(TopoDS.Edge(explorer.Current()), 0.0, 1.0))
        explorer.Next()
    return out


@pytest.mark.parametrize("name", OBJECTS)
def test_step_read_back_by_occt(name, tmp_path):
    obj = OBJECTS[name]
    file = export.to_step(obj, tmp_path / "curve.step")
    assert "B_SPLINE_CURVE_WITH_KNOTS" in file.read_text()
    (curve,) = occt_curves(file)
    assert curve.DynamicType().Name() == "Geom_BSplineCurve"
    spline = export.to_bspline(obj)
    assert curve.Degree() == spline.degree and curve.NbPoles() == len(spline.control_points)
    assert (curve.FirstParameter(), curve.LastParameter()) == (0, domain(obj))
    for u in np.linspace(0, domain(obj), 41):
        p = curve.Value(float(u))
        got = np.array([p.X(), p.Y(), p.Z()])
        want = obj.evaluate(u)
        np.testing.assert_allclose(got[: obj.dimension], want, atol=1e-12)
        if obj.dimension == 2:
            assert got[2] == 0


def test_step_holds_every_double_exactly(tmp_path):
    # OCCT's own writer prints 12 decimals (1/3 -> 0.333333333333) or 13 significant
    # digits; to_step writes 17, so each pole and knot reads back as the same double, at
    # every magnitude and sign, subnormal and zero included
    pts = [
        (Fraction(1, 3), -Fraction(2, 7)),
        (12345.678901234567, 1e-5),
        (-0.1, 2.0**-1074),
        (1e300, -(2.0**-60)),
        (0.0, -0.0),
    ]
    obj = lb.CompositeCurve([lb.BezierCurve(pts), lb.BezierCurve([pts[-1], (1.5, 7 / 9)])])
    spline = export.to_bspline(obj)
    (curve,) = occt_curves(export.to_step(obj, tmp_path / "exact.step"))
    poles = [curve.Pole(i) for i in range(1, curve.NbPoles() + 1)]
    assert [(p.X(), p.Y(), p.Z()) for p in poles] == [
        (float(x), float(y), 0.0) for x, y in spline.control_points
    ]
    knots = [curve.Knot(i) for i in range(1, curve.NbKnots() + 1)]
    assert knots == [float(v) for v in spline.breakpoints()[0]]


def test_missing_cad_packages_name_the_extra(tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "ezdxf", None)  # import ezdxf now raises ImportError
    monkeypatch.setitem(sys.modules, "OCP", None)
    with pytest.raises(ImportError, match=r'pip install "lambda-bezier\[cad\]"'):
        export.to_dxf(OBJECTS["bezier"], tmp_path / "x.dxf")
    with pytest.raises(ImportError, match=r'pip install "lambda-bezier\[cad\]"'):
        export.to_step(OBJECTS["bezier"], tmp_path / "x.step")


def test_export_module_imports_no_cad_package():
    code = (
        "import sys, lambda_bezier.export, lambda_bezier.geometry\n"
        "print(sorted(m for m in ('OCP', 'ezdxf', 'svgpathtools', 'scipy', 'sympy')"
        " if m in sys.modules))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


# ---------------------------------------------------------------------- command line
@pytest.mark.parametrize("fmt", ["json", "svg", "dxf", "step"])
def test_cli_export(fmt, tmp_path, capsys):
    source = tmp_path / "in.json"
    source.write_text(export.to_json(OBJECTS["composite-2d"]))
    target = tmp_path / f"out.{fmt}"
    args = ["export", "--format", fmt, str(source), str(target)]
    if fmt == "svg":
        args += ["--tolerance", "1e-4"]
    assert main(args) == 0
    text = target.read_text()
    if fmt == "json":
        assert text.strip() == source.read_text().strip()
    elif fmt == "svg":
        assert "<path d=" in text
    elif fmt == "step":
        assert len(occt_curves(target)) == 1
    else:
        import ezdxf

        assert len(list(ezdxf.readfile(target).modelspace().query("SPLINE"))) == 1


def test_cli_export_errors(tmp_path, capsys):
    source = tmp_path / "in.json"
    source.write_text('{"lambda_bezier": 1, "kind": "curve", "family": "nurbs"}')
    assert main(["export", "--format", "json", str(source), str(tmp_path / "o.json")]) == 2
    assert "family must be one of" in capsys.readouterr().err
    source.write_text(export.to_json(OBJECTS["composite-2d"]))
    assert main(["export", "--format", "svg", str(source), str(tmp_path / "o.svg")]) == 2
    assert "pass tolerance=" in capsys.readouterr().err
    assert main(["export", "--format", "json", str(tmp_path / "nope.json"), "o"]) == 2
    assert "nope.json" in capsys.readouterr().err
    assert main(["export", "--format", "dxf", "--tolerance", "1", str(source), "o"]) == 2
    assert "--format svg only" in capsys.readouterr().err
