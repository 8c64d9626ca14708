"""Rational Bézier curves exported and read back by the library that consumes each format:
OCCT reads the STEP file, ezdxf the DXF file, svgpathtools the SVG; JSON round-trips exactly."""

from __future__ import annotations

import json
import math
from fractions import Fraction

import numpy as np
import pytest
from test_export import occt_curves, svg_paths

from lambda_bezier import RationalBezierCurve, export
from lambda_bezier.cli import main

CURVES = {
    "circle-exact": RationalBezierCurve([(1, 0), (1, 1), (0, 1)], [1, 1, 2]),
    "circle-float": RationalBezierCurve([(1, 0), (1, 1), (0, 1)], [1, math.sqrt(0.5), 1]),
    "cubic-3d": RationalBezierCurve(
        [(0, 0, 0), (1, 2, 1), (3, 2, -1), (4, 0, 2)], [1, Fraction(5, 2), Fraction(1, 3), 2]
    ),
    "quintic": RationalBezierCurve(
        [(0, 0), (1, 3), (2, -1), (4, 2), (5, 5), (7, 0)], [1, 2, 0.5, 3, 1, 0.25]
    ),
}


@pytest.mark.parametrize("name", CURVES)
def test_bspline_is_the_curve(name):
    curve = CURVES[name]
    spline = export.to_bspline(curve)
    assert spline.weights == curve.control_weights() and spline.exact == curve.is_exact
    for t in (Fraction(0), Fraction(1, 7), Fraction(1, 2), Fraction(1)):
        if curve.is_exact:
            assert spline.point(t) == curve.exact_derivative(t)
        np.testing.assert_allclose(spline.evaluate(float(t)), curve.evaluate(float(t)), atol=1e-14)


@pytest.mark.parametrize("name", CURVES)
def test_step_read_back_by_occt(name, tmp_path):
    pytest.importorskip("OCP")
    curve = CURVES[name]
    file = export.to_step(curve, tmp_path / "curve.step")
    (occ,) = occt_curves(file)
    assert occ.DynamicType().Name() == "Geom_BSplineCurve"
    assert occ.IsRational() and occ.Degree() == curve.degree
    # (the STEP file holds 17 significant digits: each weight's double comes back unchanged)
    assert [occ.Weight(i) for i in range(1, curve.degree + 2)] == [
        float(w) for w in curve.control_weights()
    ]
    poles = [occ.Pole(i) for i in range(1, curve.degree + 2)]
    assert [[p.X(), p.Y(), p.Z()][: curve.dimension] for p in poles] == [
        [float(v) for v in row] for row in curve.control_points()
    ]
    for u in np.linspace(0, 1, 41):
        p = occ.Value(float(u))
        got = np.array([p.X(), p.Y(), p.Z()])
        np.testing.assert_allclose(got[: curve.dimension], curve.evaluate(u), atol=1e-12)


@pytest.mark.parametrize("name", CURVES)
def test_dxf_read_back_by_ezdxf(name, tmp_path):
    ezdxf = pytest.importorskip("ezdxf")
    curve = CURVES[name]
    file = export.to_dxf(curve, tmp_path / "curve.dxf")
    (entity,) = ezdxf.readfile(file).modelspace().query("SPLINE")
    assert list(entity.weights) == pytest.approx([float(w) for w in curve.control_weights()])
    tool = entity.construction_tool()
    assert tool.degree == curve.degree and tool.is_rational
    u = np.linspace(0, 1, 41)
    got = np.array([tuple(tool.point(x)) for x in u])[:, : curve.dimension]
    np.testing.assert_allclose(got, curve.evaluate(u), atol=1e-12)


@pytest.mark.parametrize("name", CURVES)
def test_json_round_trip_is_exact(name):
    curve = CURVES[name]
    text = export.to_json(curve)
    doc = json.loads(text)
    assert doc["family"] == "rational_bezier" and len(doc["weights"]) == curve.degree + 1
    back = export.from_json(text)
    assert isinstance(back, RationalBezierCurve)
    assert back.control_points() == curve.control_points()
    assert back.control_weights() == curve.control_weights()
    assert back.is_exact == curve.is_exact


@pytest.mark.parametrize(
    ("change", "message"),
    [
        ({"weights": None}, "weights must be a list"),
        ({"weights": ["1", "0", "2"]}, "positive"),
        ({"weights": ["1", "x", "2"]}, r"weights\[1\]"),
        ({"weights": ["1", "2"]}, "one number per control point"),
        ({"lambda": "1/2"}, "lambda must be null"),
    ],
)
def test_json_bad_rational(change, message):
    doc = json.loads(export.to_json(CURVES["circle-exact"]))
    doc.update(change)
    with pytest.raises(ValueError, match=message):
        export.from_json(json.dumps(doc))


def test_composites_hold_no_rational_segment():
    seg = json.loads(export.to_json(CURVES["circle-exact"]))
    doc = {"lambda_bezier": 1, "kind": "composite", "segments": [seg], "joints": []}
    with pytest.raises(ValueError, match="family must be one of"):
        export.from_json(json.dumps(doc))


@pytest.mark.parametrize("tolerance", [1e-2, 1e-5])
def test_svg_approximates_within_the_tolerance(tmp_path, tolerance):
    curve = CURVES["quintic"]
    with pytest.raises(ValueError, match="no exact SVG path"):
        export.to_svg(curve)
    path = svg_paths(export.to_svg(curve, tolerance=tolerance), tmp_path)
    assert all(type(s).__name__ == "CubicBezier" for s in path)
    ts = np.linspace(0, 1, 11)
    path_pts = np.array([[z.real, z.imag] for s in path for z in (s.point(t) for t in ts)])
    assert curve.closest_point(path_pts).distance.max() <= tolerance
    for x, y in curve.evaluate(np.linspace(0, 1, 61)):
        (nearest, _, _), _ = path.radialrange(complex(x, y))
        assert nearest <= tolerance * (1 + 1e-9)


def test_svg_of_equal_weights_is_exact(tmp_path):
    curve = RationalBezierCurve([(0, 0), (1, 3), (2, 1), (3, 3)], [2, 2, 2, 2])
    (seg,) = svg_paths(export.to_svg(curve), tmp_path)
    assert type(seg).__name__ == "CubicBezier"
    assert [(z.real, z.imag) for z in seg.bpoints()] == [(0, 0), (1, 3), (2, 1), (3, 3)]
    with pytest.raises(ValueError, match="2D"):
        export.to_svg(CURVES["cubic-3d"], tolerance=1e-3)


def test_cli_exports_a_rational_curve(tmp_path):
    source = tmp_path / "c.json"
    source.write_text(export.to_json(CURVES["circle-exact"]))
    out = tmp_path / "c.svg"
    assert main(["export", "--format", "svg", "--tolerance", "1e-6", str(source), str(out)]) == 0
    assert "<path" in out.read_text()
    assert main(["export", "--format", "svg", str(source), str(out)]) == 2
    again = tmp_path / "again.json"
    assert main(["export", "--format", "json", str(source), str(again)]) == 0
    assert export.from_json(again.read_text()).control_weights() == (1, 1, 2)
