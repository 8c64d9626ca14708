"""Surfaces out and back in: STEP (a B-spline surface, through OCCT's OCP), a triangle mesh
with a guaranteed deviation (OBJ, STL or PLY, written by trimesh) and JSON (exact numbers as
strings, read back exactly).
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path
from typing import Any

import numpy as np

from . import _poly_direction as pd
from . import _validate as val
from . import surface_approx
from ._json_io import _own_classes, class_definitions, parse_json
from .builtin_surfaces import most_specific
from .export import (
    FORMAT_VERSION,
    _number_in,
    _number_out,
    _optional,
    _quiet_occt,
    _write_step,
)
from .surfaces import Surface

# ---------------------------------------------------------------------- STEP (OCCT)


def occt_bezier_surface(surf: Surface) -> Any:
    """The surface's Bézier form as an OCCT Geom_BezierSurface (3D; 2D nets at z = 0)."""
    _optional("OCP", "cadquery-ocp-novtk (OCP)", "occt_bezier_surface")
    from OCP.collections import Array2_gp_Pnt
    from OCP.Geom import Geom_BezierSurface
    from OCP.gp import gp_Pnt

    net = surf.to_bezier().net
    if net.shape[2] not in (2, 3):
        raise ValueError(f"OCCT surfaces live in 3D: this surface has dimension {net.shape[2]}")
    if net.shape[0] > 26 or net.shape[1] > 26:  # Geom_BezierSurface::MaxDegree() is 25
        raise ValueError("OCCT's Bézier surfaces have degree at most 25 in each direction")
    poles = Array2_gp_Pnt(1, net.shape[0], 1, net.shape[1])
    for i in range(net.shape[0]):
        for j in range(net.shape[1]):
            x, y, *z = (float(c) for c in net[i, j])
            poles.SetValue(i + 1, j + 1, gp_Pnt(x, y, z[0] if z else 0.0))
    return Geom_BezierSurface(poles)


def occt_rational_surface(rat: Any) -> Any:
    """A RationalBezierSurface (atom_surfaces) as an OCCT rational Geom_BSplineSurface: one
    span with clamped knots on [0, 1]², its weights kept (3D; 2D nets at z = 0)."""
    from OCP.collections import Array1_double, Array1_int, Array2_double, Array2_gp_Pnt
    from OCP.Geom import Geom_BSplineSurface
    from OCP.gp import gp_Pnt

    h = rat.homogeneous.net
    rows, cols, dim = h.shape
    if dim - 1 not in (2, 3):
        raise ValueError(f"OCCT surfaces live in 3D: this surface has dimension {dim - 1}")
    poles = Array2_gp_Pnt(1, rows, 1, cols)
    weights = Array2_double(1, rows, 1, cols)
    for i in range(rows):
        for j in range(cols):
            w = float(h[i, j, -1])
            x, y, *z = (float(c) / w for c in h[i, j, :-1])
            poles.SetValue(i + 1, j + 1, gp_Pnt(x, y, z[0] if z else 0.0))
            weights.SetValue(i + 1, j + 1, w)

    def knots(degree: int) -> tuple[Any, Any]:
        values, mults = Array1_double(1, 2), Array1_int(1, 2)
        for k, v in enumerate((0.0, 1.0), start=1):
            values.SetValue(k, v)
            mults.SetValue(k, degree + 1)
        return values, mults

    (uk, um), (vk, vm) = knots(rows - 1), knots(cols - 1)
    return Geom_BSplineSurface(poles, weights, uk, vk, um, vm, rows - 1, cols - 1)


def to_step_surface(surf: Surface, path: str | Path, *, tolerance: float | None = None) -> Path:
    """Write the surface as one face on a B-spline surface (B_SPLINE_SURFACE_WITH_KNOTS, its
    Bézier form with clamped knots) to a STEP file through OCCT, every number with 17
    significant digits (the doubles read back unchanged). A surface of trigonometric or
    hyperbolic families is written as its rational form (a rational B-spline surface, one
    span, whose parameters are the rational form's s_u, s_v ∈ [0, 1], not the families' t).

    A surface of a mixed algebraic-trigonometric or -hyperbolic family has no rational form:
    it is written as a bicubic B-spline within `tolerance` of it (surface_approx: the Hermite
    interpolant on a grid of cells, its deviation measured inside every cell; default
    1e-6 times the net's largest coordinate, at least 1e-6), whose parameters are the
    families' own u and v. `tolerance` is not used for the exact forms."""
    _optional("OCP", "cadquery-ocp-novtk (OCP)", "to_step_surface")
    from OCP import Message
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
    from OCP.GeomConvert import GeomConvert
    from OCP.IFSelect import IFSelect_ReturnStatus
    from OCP.STEPControl import STEPControl_StepModelType, STEPControl_Writer

    if not isinstance(surf, Surface):
        raise TypeError(f"surf must be a lambda_bezier surface, got {type(surf).__name__}")
    _quiet_occt(Message)
    if tolerance is not None:
        tolerance = val.tolerance(tolerance, "tolerance")
    if hasattr(surf, "_has_form") and not surf._has_form():  # a mixed family: approximated
        size = max(1.0, float(np.abs(surf.net).max()))
        spline = surface_approx.occt_bspline(
            surface_approx.hermite_bspline(surf, 1e-6 * size if tolerance is None else tolerance)
        )
    elif hasattr(surf, "to_rational_bezier"):  # an AtomSurface: its rational form, (s_u, s_v)
        spline = occt_rational_surface(surf.to_rational_bezier())
    else:
        spline = GeomConvert.SurfaceToBSplineSurface_s(occt_bezier_surface(surf))
    face = BRepBuilderAPI_MakeFace(spline, 1e-9).Face()
    writer = STEPControl_Writer()
    done = IFSelect_ReturnStatus.IFSelect_RetDone
    if writer.Transfer(face, STEPControl_StepModelType.STEPControl_AsIs) != done:
        raise RuntimeError("OCCT could not transfer the B-spline face to STEP")
    return _write_step(writer, Path(path))


# ---------------------------------------------------------------------- triangle mesh
@dataclass(frozen=True)
class SurfaceMesh:
    """Vertices (k, 3), their parameters (k, 2), triangles (t, 3) of vertex indices, and a
    bound on the distance from any point of a triangle to the surface point of the same
    (linearly interpolated) parameters."""

    vertices: np.ndarray
    parameters: np.ndarray
    faces: np.ndarray
    deviation_bound: float


def _hull_bound(coeffs_net: np.ndarray) -> float:
    """max |control point|: bounds the polynomial on the unit square (convex hull)."""
    return float(np.linalg.norm(coeffs_net, axis=-1).max()) if coeffs_net.size else 0.0


def _derivative_net(net: np.ndarray, du: int, dv: int) -> np.ndarray:
    """The Bézier net of ∂^(du+dv) S / ∂u^du ∂v^dv (forward differences times the degrees)."""
    out = net
    for axis, k in ((0, du), (1, dv)):
        for _ in range(k):
            degree = out.shape[axis] - 1
            if degree == 0:
                return np.zeros((1, 1, net.shape[2]))
            out = degree * np.diff(out, axis=axis)
    return out


def mesh(surf: Surface, tolerance: float) -> SurfaceMesh:
    """A uniform triangulation whose triangles deviate from the surface by at most
    `tolerance`: on a right triangle of legs h_u, h_v linear interpolation errs by at most
    (M_uu h_u² + 2 M_uv h_u h_v + M_vv h_v²) / 8, with M the bounds of the second derivatives
    from their Bézier nets (see `_cell_size`)."""
    tol = val.tolerance(tolerance, "tolerance")
    if not isinstance(surf, Surface):
        raise TypeError(f"surf must be a lambda_bezier surface, got {type(surf).__name__}")
    if surf.dimension not in (2, 3):
        raise ValueError(
            f"a triangle mesh needs a surface in 2D or 3D, got dimension {surf.dimension}"
        )
    (u0, u1), (v0, v1) = (0.0, 1.0), (0.0, 1.0)
    if hasattr(surf, "derivative_bounds"):  # an AtomSurface: bounds from its atoms, its domain
        muu, muv, mvv = surf.derivative_bounds()
        (u0, u1), (v0, v1) = surf.domain_u, surf.domain_v  # type: ignore[attr-defined]
    else:
        net = surf.to_bezier().net
        muu, muv, mvv = (
            _hull_bound(_derivative_net(net, a, b)) for a, b in ((2, 0), (1, 1), (0, 2))
        )
    span_u, span_v = u1 - u0, v1 - v0
    if tol == 0 and (muu or muv or mvv):
        raise ValueError(
            "tolerance must be > 0 for a curved surface (only a flat one meshes exactly)"
        )
    hu, hv = _cell_size(muu, muv, mvv, tol, span_u, span_v)
    if span_u / hu * (span_v / hv) > 25_000_000:
        raise ValueError(
            f"tolerance {tol} needs about {span_u / hu:.3g} x {span_v / hv:.3g} cells (at most "
            "25,000,000); choose a larger tolerance"
        )
    nu, nv = max(1, math.ceil(span_u / hu)), max(1, math.ceil(span_v / hv))
    us, vs = np.linspace(u0, u1, nu + 1), np.linspace(v0, v1, nv + 1)
    pts = surf.evaluate_grid(us, vs).reshape(-1, surf.dimension)
    if surf.dimension == 2:
        pts = np.column_stack([pts, np.zeros(len(pts))])
    idx = np.arange((nu + 1) * (nv + 1)).reshape(nu + 1, nv + 1)
    a, b = idx[:-1, :-1].ravel(), idx[1:, :-1].ravel()
    c, d = idx[1:, 1:].ravel(), idx[:-1, 1:].ravel()
    faces = np.concatenate([np.stack([a, b, c], 1), np.stack([a, c, d], 1)])
    h1, h2 = span_u / nu, span_v / nv
    bound = (muu * h1 * h1 + 2 * muv * h1 * h2 + mvv * h2 * h2) / 8
    params = np.stack(np.meshgrid(us, vs, indexing="ij"), axis=-1).reshape(-1, 2)
    return SurfaceMesh(pts, params, faces, bound)


def _cell_size(
    muu: float, muv: float, mvv: float, tol: float, span_u: float, span_v: float
) -> tuple[float, float]:
    """The legs (h_u, h_v) of the largest cells whose triangles stay within `tol`.

    At a point x of a triangle with vertices x_i and barycentric weights λ_i (Σ λ_i x_i = x),
    Taylor's theorem from x to each vertex gives S(x) − Σ λ_i S(x_i) = −½ Σ λ_i D²S(ξ_i)[w_i, w_i],
    w_i = x_i − x, so the error is at most ½ Σ λ_i (M_uu w_iu² + 2 M_uv |w_iu w_iv| + M_vv w_iv²).
    Σ λ_i w_iu² is the variance of the vertices' u under the weights λ, at most h_u²/4 on a
    triangle whose vertices' u span h_u (likewise v), and Σ λ_i |w_iu w_iv| is at most the
    root of the two variances' product (Cauchy-Schwarz): the error is at most
    (M_uu h_u² + 2 M_uv h_u h_v + M_vv h_v²) / 8, as for linear interpolation on a segment.
    The fewest cells for that bound = tol have M_uu h_u² = M_vv h_v² (the product h_u h_v
    fixed, the sum of the two squares least)."""
    budget = 8 * tol * (1 - 1e-9)  # the bound stays below tol after its own rounding
    if muu and mvv:
        k2 = budget / (2 + 2 * muv / math.sqrt(muu * mvv))
        hu, hv = math.sqrt(k2 / muu), math.sqrt(k2 / mvv)
        if hu > span_u:  # one direction needs no cut: give the other all the budget
            hu = span_u
            hv = _leg(mvv, 2 * muv * hu, budget - muu * hu * hu)
        elif hv > span_v:
            hv = span_v
            hu = _leg(muu, 2 * muv * hv, budget - mvv * hv * hv)
    elif muu:  # straight in v: v needs cuts only for the twist
        hv = span_v
        hu = _leg(muu, 2 * muv * hv, budget)
    elif mvv:
        hu = span_u
        hv = _leg(mvv, 2 * muv * hu, budget)
    elif muv:  # a bilinear twist: h_u h_v = 4 tol / M_uv, square cells of the domain's shape
        scale = math.sqrt(budget / (2 * muv * span_u * span_v))
        hu, hv = span_u * scale, span_v * scale
    else:
        return span_u, span_v
    return min(hu, span_u), min(hv, span_v)


def _leg(square: float, linear: float, budget: float) -> float:
    """The positive h with square·h² + linear·h = budget (budget > 0)."""
    if not square:
        return budget / linear if linear else math.inf
    return 2 * budget / (linear + math.sqrt(linear * linear + 4 * square * budget))


def to_mesh_file(surf: Surface, path: str | Path, tolerance: float) -> Path:
    """Write `mesh(surf, tolerance)` to an OBJ, STL or PLY file (by the suffix) with trimesh."""
    target = Path(path)
    kind = target.suffix.lower().lstrip(".")
    if kind not in ("obj", "stl", "ply"):
        raise ValueError(f"path must end in .obj, .stl or .ply, got {target.name!r}")
    trimesh = _optional("trimesh", "trimesh", "to_mesh_file")
    m = mesh(surf, tolerance)
    tri = trimesh.Trimesh(vertices=m.vertices, faces=m.faces, process=False)
    tri.export(str(target), file_type=kind)
    return target


# ---------------------------------------------------------------------- JSON
def surface_to_json(surf: Surface, *, indent: int | None = 2) -> str:
    """The JSON form of a surface: exact numbers as strings; a direction of a family of your
    own embeds its definition (``definitions``, as the curves' JSON does), so that
    surface_from_json can check the family it is given against it."""
    if not isinstance(surf, Surface):
        raise TypeError(f"surf must be a lambda_bezier surface, got {type(surf).__name__}")
    if hasattr(surf, "family_u"):  # several, indexed or atom families: parameters by name
        return _param_surface_json(surf, indent)
    doc: dict[str, Any] = {
        "lambda_bezier": FORMAT_VERSION,
        "kind": "surface",
        "family": [surf._u_cls.family, surf._v_cls.family],
        "lambda": [None if x is None else _number_out(x) for x in (surf.lam_u, surf.lam_v)],
        "net": [[[_number_out(c) for c in p] for p in row] for row in surf.control_net()],
    }
    definitions = class_definitions([surf._u_cls, surf._v_cls])
    if definitions:
        doc["definitions"] = definitions
    return json.dumps(doc, indent=indent, ensure_ascii=False)


def _param_surface_json(surf: Any, indent: int | None) -> str:
    """A surface of param_surfaces: ``"parameters": [{name: value}, {name: value}]`` (an
    indexed family's as {name: [value per index]}) instead of ``"lambda"``."""

    def values(given: dict[str, Any]) -> dict[str, Any]:
        return {
            k: [_number_out(x) for x in v] if isinstance(v, list | tuple) else _number_out(v)
            for k, v in given.items()
        }

    doc: dict[str, Any] = {
        "lambda_bezier": FORMAT_VERSION,
        "kind": "surface",
        "family": [pd.family_name(surf.family_u), pd.family_name(surf.family_v)],
        "parameters": [values(surf.params_u), values(surf.params_v)],
        "net": [[[_number_out(c) for c in p] for p in row] for row in surf.control_net()],
    }
    fams = (surf.family_u, surf.family_v)  # a built-in direction across an atom one: a class
    definitions = class_definitions([f if pd.is_class(f) else f.curve_class for f in fams])
    if definitions:
        doc["definitions"] = definitions
    return json.dumps(doc, indent=indent, ensure_ascii=False)


def _param_surface_from(
    doc: dict[str, Any], classes: dict[str, Any], rows: Any, check_range: bool
) -> Surface:
    from .param_surfaces import family_surface

    params = doc["parameters"]
    if not (
        isinstance(params, list) and len(params) == 2 and all(isinstance(p, dict) for p in params)
    ):
        raise ValueError("surface.parameters must be a pair of tables {name: value}")
    fams = []
    for name in doc["family"]:
        fam = getattr(classes[name], "family_object", None)
        fams.append(classes[name] if fam is None else getattr(fam, "indexed_family", fam))

    def value(v: object, where: str) -> Any:
        if isinstance(v, list):
            return [_number_in(x, where) for x in v]
        return _number_in(v, where)

    given = [{k: value(v, f"surface.parameters.{k}") for k, v in p.items()} for p in params]
    return family_surface(
        rows, tuple(fams), params_u=given[0], params_v=given[1], check_range=check_range
    )


def surface_from_json(text: str, *, family: object = None, check_range: bool = True) -> Surface:
    """A surface from its JSON form. A direction of a family of your own needs that family:
    `family` is its Family (load_family), definition file or derived document (or a list of
    them), checked against the definition the document embeds; without it the error says
    how to get it (`lambda-bezier export --format family` writes the embedded definition)."""
    from .curves import FAMILIES

    if not isinstance(text, str | bytes | bytearray):
        raise TypeError(f"text must be a JSON string, got {type(text).__name__}")
    doc = parse_json(text)
    if (
        not isinstance(doc, dict)
        or doc.get("lambda_bezier") != FORMAT_VERSION
        or doc.get("kind") != "surface"
    ):
        raise ValueError(
            f'not a lambda-bezier surface document: expected "lambda_bezier": '
            f'{FORMAT_VERSION} and "kind": "surface"'
        )
    fams, lams, net = doc.get("family"), doc.get("lambda"), doc.get("net")
    if not (isinstance(fams, list) and len(fams) == 2 and all(isinstance(f, str) for f in fams)):
        raise ValueError(f"surface.family must be a pair of family names, got {fams!r}")
    try:
        own = _own_classes(doc, family, set(fams))
    except ValueError as exc:
        raise ValueError(f"surface.family: {exc}") from None
    classes = {**FAMILIES, **own}
    if not all(f in classes for f in fams):
        raise ValueError(
            f"surface.family must be a pair of names from {sorted(FAMILIES)} or families "
            f"passed as family=, got {fams!r}"
        )
    if "parameters" not in doc and not (isinstance(lams, list) and len(lams) == 2):
        raise ValueError("surface.lambda must be a pair (null for a Bézier direction)")
    if not (
        isinstance(net, list)
        and net
        and all(isinstance(r, list) and all(isinstance(p, list) for p in r) for r in net)
    ):
        raise ValueError("surface.net must be a list of rows of points")
    rows = [
        [[_number_in(c, f"net[{i}][{j}][{k}]") for k, c in enumerate(p)] for j, p in enumerate(r)]
        for i, r in enumerate(net)
    ]
    if not all(isinstance(c, Fraction) for r in rows for p in r for c in p):
        rows = [[[float(c) for c in p] for p in r] for r in rows]
    if "parameters" in doc:
        return _param_surface_from(doc, classes, rows, check_range)
    lu, lv = (None if x is None else _number_in(x, "surface.lambda") for x in lams)  # type: ignore[union-attr]
    return most_specific(
        rows, lu, lv, classes=(classes[fams[0]], classes[fams[1]]), check_range=check_range
    )


def bezier_net_bounds(surf: Surface) -> tuple[float, float, float]:
    """(M_uu, M_uv, M_vv): the second-derivative bounds the mesh uses (for tests and docs)."""
    net = surf.to_bezier().net
    return tuple(_hull_bound(_derivative_net(net, a, b)) for a, b in ((2, 0), (1, 1), (0, 2)))  # type: ignore[return-value]


__all__ = [
    "SurfaceMesh",
    "mesh",
    "occt_bezier_surface",
    "occt_rational_surface",
    "surface_from_json",
    "surface_to_json",
    "to_mesh_file",
    "to_step_surface",
]
