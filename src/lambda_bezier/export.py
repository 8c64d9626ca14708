"""Exact export of curves and composites: one B-spline, STEP, DXF, SVG and a JSON form.

Every λ-curve is exactly a polynomial curve (`to_bezier()`), so a curve or a composite is
exactly one clamped B-spline on the composite's own parameter u ∈ [0, N]: the Bernstein
pieces, elevated to a common degree p, with the knot at joint u = j repeated p − k times
where the joint is C^k in u, k the continuity that actually holds there (in Fractions when the
curve is exact, otherwise within `tol`). `to_bspline` then checks that the B-spline it built
reproduces every piece (p + 1 values per piece: exact equality for exact input) and falls
back to full multiplicity, which is always exact, if not. G1/G2 joints with α ≠ 1 are not C1
in u, so their knots stay at multiplicity p.

A RationalBezierCurve (lambda_bezier.rational) is one rational B-spline (a NURBS with a
single Bézier span, its weights kept): STEP, DXF and JSON hold it exactly (STEP and DXF in
floats); SVG paths have no rational segments, so it becomes polynomial cubics within a given
tolerance (a certified bound, see hazmat.rational_kernels.cubics) unless its weights are all equal.

STEP (through OCCT's Python binding, OCP) and DXF (through ezdxf) need the optional extra
`cad`: pip install "lambda-bezier[cad]". They store the B-spline in floats (the exact
Fractions rounded once). A STEP file carries each of them with 17 significant digits, which
reads back as the same double (OCCT's own writer prints 12 decimals in [0.1, 1000) and 13
significant digits elsewhere: `_write_step` sends the model with its own number format).

JSON form (`to_json` / `from_json`), version 1; every exact number (int or Fraction) is a
string "p/q" or "n", a float is a JSON number (shortest repr, so it round-trips exactly)::

    {"lambda_bezier": 1, "kind": "curve",
     "family": "same_degree" | "bernstein_like" | "bezier",
     "lambda": "1/2" | 0.5 | null,                 (null for "bezier")
     "points": [["0", "0"], ["1", "2"], ...]}      (2 or 3 coordinates each)

    {"lambda_bezier": 1, "kind": "curve", "family": "rational_bezier", "lambda": null,
     "points": [...], "weights": ["1", "1/2", ...]}   (one positive weight per point)

    {"lambda_bezier": 1, "kind": "composite",
     "segments": [{"family": ..., "lambda": ..., "points": ...}, ...],
     "joints": [null | {"continuity": "C1" | "C2" | "G1" | "G2",
                        "alpha": "2", "d": "1"}, ...]}   (one per joint, as built)

A curve of a family of the user's own (`lambda_bezier.load_family`) is written under its name,
and the document then also holds that family's definition and fingerprint::

     "definitions": {"nouri_saeidian": {"definition_digest": "<sha256>",
                                        "definition": {<the [family] table>}}}

Reading it back needs the family's derived tables, which `from_json(text, family=...)` takes
as a Family, a definition file (its derived document beside it) or the derived document itself
(then no definition file is needed: the embedded definition is used); each must carry the
fingerprint the document records. From the shell: `lambda-bezier export --family FILE`;
`lambda-bezier export --format family INPUT.json NAME.toml` writes an embedded definition out.
"""

from __future__ import annotations

import importlib
import math
from bisect import bisect_right
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path
from types import ModuleType
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from . import _validate as val

# JSON lives in _json_io (below this module); its public functions are this module's
from ._json_io import FORMAT_VERSION as FORMAT_VERSION
from ._json_io import _number_in as _number_in
from ._json_io import _number_out as _number_out
from ._json_io import _rational, _segments
from ._json_io import family_definition as family_definition
from ._json_io import from_json as from_json
from ._json_io import to_json as to_json
from .hazmat import kernels as alg
from .hazmat.kernels import Row, Rows, Scalar

if TYPE_CHECKING:
    from collections.abc import Sequence

    from .composite import CompositeCurve
    from .curves import Curve
    from .rational import RationalBezierCurve

    Shape = Curve | CompositeCurve | RationalBezierCurve  # what the exporters take

CAD_HINT = 'pip install "lambda-bezier[cad]"'
# The highest degree whose SPLINE ezdxf's own construction_tool() reads back and evaluates:
# its accelerated B-spline basis (ezdxf/acc/bspline.pyx, Basis.__cinit__) refuses an order
# >= MAX_SPLINE_ORDER = 12 (ezdxf/acc/constants.h, ezdxf 1.4.5) with "invalid order", so
# order 11, degree 10. (A degree-11 file was written before and could not be evaluated.)
DXF_MAX_DEGREE = 10


def _optional(module: str, package: str, feature: str) -> ModuleType:
    """Import an optional dependency, or say which extra provides it."""
    try:
        return importlib.import_module(module)
    except ImportError:
        raise ImportError(f"{feature} needs the optional package {package}: {CAD_HINT}") from None


# ---------------------------------------------------------------------- B-spline
@dataclass(frozen=True)
class BSpline:
    """A clamped B-spline: `degree` p, the full knot vector `knots` (first and last values
    repeated p + 1 times) and `control_points` (len(knots) − p − 1 rows), in Fractions when
    `exact`. Its parameter is the composite's u ∈ [0, N] (a curve: t ∈ [0, 1]). `weights`
    (one per control point) make it a rational B-spline (NURBS); None: polynomial."""

    degree: int
    knots: tuple[Scalar, ...]
    control_points: Rows
    exact: bool
    weights: tuple[Scalar, ...] | None = None

    @property
    def dimension(self) -> int:
        return len(self.control_points[0])

    def breakpoints(self) -> tuple[list[Scalar], list[int]]:
        """The distinct knot values and their multiplicities."""
        values: list[Scalar] = []
        mults: list[int] = []
        for k in self.knots:
            if values and k == values[-1]:
                mults[-1] += 1
            else:
                values.append(k)
                mults.append(1)
        return values, mults

    def point(self, u: Scalar) -> Row:
        """C(u) by the B-spline basis (de Boor / Cox): exact for a Fraction u and an exact
        spline, floats otherwise."""
        p, knots = self.degree, self.knots
        span = _span(knots, p, len(self.control_points) - 1, u)
        basis = _basis(knots, p, span, u)
        rows = self.control_points[span - p : span + 1]
        if self.weights is not None:  # Σ b_i w_i P_i / Σ b_i w_i
            basis = [b * w for b, w in zip(basis, self.weights[span - p : span + 1], strict=True)]
            total = sum(basis[1:], basis[0])
            basis = [b / total for b in basis]
        return tuple(
            sum((b * row[c] for b, row in zip(basis, rows, strict=True)), 0 * basis[0])
            for c in range(self.dimension)
        )

    def evaluate(self, u: npt.ArrayLike) -> np.ndarray:
        """Float values at a number or an array of u: (d,) or (len(u), d)."""
        arr = np.atleast_1d(np.asarray(u, dtype=float))
        knots = [float(k) for k in self.knots]
        if arr.size and not (knots[0] <= arr.min() and arr.max() <= knots[-1]):
            raise ValueError(f"u must lie in [{knots[0]}, {knots[-1]}] (the knot range)")
        pts = [tuple(float(v) for v in row) for row in self.control_points]
        weights = None if self.weights is None else tuple(float(w) for w in self.weights)
        flt = BSpline(self.degree, tuple(knots), tuple(pts), False, weights)
        out = np.array([flt.point(float(x)) for x in arr])
        values: np.ndarray = out[0] if np.ndim(u) == 0 else out
        return values


def _span(knots: Sequence[Scalar], p: int, n: int, u: Scalar) -> int:
    """The knot span index i with knots[i] <= u < knots[i+1] (the last one at the end)."""
    return min(max(bisect_right(knots, u) - 1, p), n)


def _basis(knots: Sequence[Scalar], p: int, i: int, u: Scalar) -> list[Scalar]:
    """The p + 1 nonzero B-spline basis functions on span i at u (Cox–de Boor, in the
    arithmetic of the inputs)."""
    values: list[Scalar] = [u * 0 + 1]
    left: list[Scalar] = [0] * (p + 1)
    right: list[Scalar] = [0] * (p + 1)
    for j in range(1, p + 1):
        left[j] = u - knots[i + 1 - j]
        right[j] = knots[i + j] - u
        saved: Scalar = 0 * values[0]
        for r in range(j):
            temp = values[r] / (right[r + 1] + left[j - r])
            values[r] = saved + right[r + 1] * temp
            saved = left[j - r] * temp
        values.append(saved)
    return values


def _pieces(segs: Sequence[Curve]) -> tuple[int, list[Rows], bool]:
    """The segments' Bézier control points at one common degree, exact when all are."""
    beziers = [seg.to_bezier() for seg in segs]
    degree = max(b.degree for b in beziers)
    exact = all(b.is_exact for b in beziers)
    rows: list[Rows] = []
    for b in beziers:
        if not exact and b.is_exact:
            from .curves import BezierCurve

            b = BezierCurve(b.points)  # one arithmetic for the whole spline
        while b.degree < degree:
            b = b.elevate()
        rows.append(b.control_points())
    return degree, rows, exact


def _differences(rows: Rows, order: int, at_end: bool) -> Row:
    """Δ^order of the last (at_end) or first order + 1 control points."""
    pts = [list(r) for r in (rows[len(rows) - order - 1 :] if at_end else rows[: order + 1])]
    for _ in range(order):
        pairs = zip(pts[:-1], pts[1:], strict=True)
        pts = [[b - a for a, b in zip(p, q, strict=True)] for p, q in pairs]
    return tuple(pts[0])


def _joint_order(left: Rows, right: Rows, degree: int, exact: bool, tol: float, size: float) -> int:
    """The largest k <= degree with C^k at the joint (−1 if not even C0): the m-th
    derivatives there are p!/(p−m)! Δ^m of the end points, so compare Δ^m."""
    k = -1
    for m in range(degree + 1):
        a = _differences(left, m, True)
        b = _differences(right, m, False)
        if exact:
            same = a == b
        else:
            gap = math.dist(a, b)
            scale = size if m == 0 else max(math.hypot(*a), math.hypot(*b))
            same = gap <= tol * scale
        if not same:
            break
        k = m
    return k


def _solve(
    matrix: list[list[Scalar]], rhs: list[list[Scalar]], exact: bool
) -> Sequence[Sequence[Scalar]]:
    """matrix @ X = rhs. The collocation matrix at the Greville sites is totally positive
    and banded, so Gaussian elimination needs no pivoting and stays inside the band."""
    if not exact:
        sol = np.linalg.solve(np.array(matrix, dtype=float), np.array(rhs, dtype=float))
        floats: list[list[float]] = sol.tolist()
        return floats
    n = len(matrix)
    a = [row[:] for row in matrix]
    b = [row[:] for row in rhs]
    for i in range(n):
        if a[i][i] == 0:
            raise ZeroDivisionError("zero pivot")
        cols = [c for c in range(i, n) if a[i][c] != 0]
        for r in range(i + 1, n):
            if a[r][i] == 0:
                continue
            f = a[r][i] / a[i][i]
            for c in cols:
                a[r][c] -= f * a[i][c]
            b[r] = [x - f * y for x, y in zip(b[r], b[i], strict=True)]
    x: list[list[Scalar]] = [[] for _ in range(n)]
    for i in range(n - 1, -1, -1):
        acc = list(b[i])
        for c in range(i + 1, n):
            if a[i][c] != 0:
                acc = [v - a[i][c] * w for v, w in zip(acc, x[c], strict=True)]
        x[i] = [v / a[i][i] for v in acc]
    return x


def _piece_value(rows: Rows, t: Scalar) -> Row:
    return alg.de_casteljau_triangle(rows, t)[-1][0]


def _assemble(
    degree: int, rows: list[Rows], mults: list[int], exact: bool, tol: float, size: float
) -> BSpline | None:
    """The B-spline with these interior multiplicities reproducing the pieces, or None."""
    p, count = degree, len(rows)
    one = Fraction(1) if exact else 1.0
    knots: list[Scalar] = [0 * one] * (p + 1)
    for j, m in enumerate(mults):
        knots += [(j + 1) * one] * m
    knots += [count * one] * (p + 1)
    n = len(knots) - p - 1
    if all(m == p for m in mults):  # the Bézier points themselves, joints shared
        shared = list(rows[0])
        for piece in rows[1:]:
            shared += list(piece[1:])
        return BSpline(p, tuple(knots), tuple(map(tuple, shared)), exact)
    greville = [sum(knots[i + 1 : i + p + 1], 0 * one) / p for i in range(n)]
    matrix: list[list[Scalar]] = []
    rhs: list[list[Scalar]] = []
    for xi in greville:
        span = _span(knots, p, n - 1, xi)
        row: list[Scalar] = [0 * one] * n
        row[span - p : span + 1] = _basis(knots, p, span, xi)
        matrix.append(row)
        at = min(int(math.floor(xi)), count - 1)  # the piece holding xi
        rhs.append(list(_piece_value(rows[at], xi - at)))
    try:
        ctrl = _solve(matrix, rhs, exact)
    except (ZeroDivisionError, np.linalg.LinAlgError):
        return None
    spline = BSpline(p, tuple(knots), tuple(tuple(r) for r in ctrl), exact)
    # a degree-p polynomial is fixed by p + 1 values: compare them on every piece
    for j, piece in enumerate(rows):
        for s in range(p + 1):
            t = Fraction(s + 1, p + 2) if exact else (s + 1) / (p + 2)
            ours = spline.point(j + t)
            want = _piece_value(piece, t)
            if exact and tuple(ours) != tuple(want):
                return None
            if not exact and math.dist(ours, want) > tol * size:
                return None
    return spline


def _exportable(obj: Any, tolerance: float | None = None) -> Any:
    """A curve of a trigonometric, hyperbolic or mixed family (atom_family) as what the
    writers take: its exact rational form where it has one (tan(t/2): a NURBS equal to the
    curve), a hyperbolic curve's rational form in floats (tanh(t/2), within about 1e-15 of
    its size); otherwise its approximation by polynomial Bézier pieces of degree 9, one
    CompositeCurve, each piece within 1e-13 of the curve's size where rounding allows
    (_atom_geometry.pieces, checked on a grid of 37 points per piece). A composite with such
    segments: each of them by its polynomial pieces, in one polynomial CompositeCurve (so the
    B-spline's parameter runs over the pieces, one unit each, not over the composite's u).
    Anything else unchanged.

    The pieces of a curve without a rational form are within `tolerance` (a distance in the
    curve's units; default DEFAULT_DEVIATION times its size) of it at every t, certified
    (_atom_geometry.certified_pieces). A C-Bézier curve (cbezier_family: its space depends
    on its alpha) is always written by these certified pieces."""
    from .composite import CompositeCurve

    if isinstance(obj, CompositeCurve) and any(_over_atoms(s) for s in obj.segments):
        # one polynomial B-spline: every AtomCurve segment by its polynomial pieces (a NURBS
        # segment and polynomial ones share no exact common form); the joints are measured
        # on the pieces as on any composite, so the knots say what continuity they keep
        return CompositeCurve(
            [
                p
                for seg in obj.segments
                for p in (_pieces_of(seg, tolerance) if _over_atoms(seg) else [seg])
            ]
        )
    if not _over_atoms(obj):
        return obj
    if not _by_certified_pieces(obj):  # an exact rational form; hyperbolic: in floats
        return obj.to_rational_bezier()
    return CompositeCurve(_pieces_of(obj, tolerance))


def _over_atoms(curve: Any) -> bool:
    """Whether `curve` is a sum of atoms (1, t^k, cos, sin, cosh, sinh) with no polynomial
    form: a curve of a trigonometric, hyperbolic or mixed family, or a C-Bézier curve."""
    from .atom_family import AtomCurve
    from .cbezier_family import CBezierCurve

    return isinstance(curve, AtomCurve | CBezierCurve)


def _by_certified_pieces(curve: Any) -> bool:
    """Whether a curve over atoms is written by certified polynomial pieces: a mixed one (no
    rational form) and every C-Bézier curve (the float rational form some of these have is
    not certified, and none has an exact one for a general alpha)."""
    from .cbezier_family import CBezierCurve

    if isinstance(curve, CBezierCurve):
        return True
    return not curve.has_rational_form and curve.data.SPACE != "hyperbolic"


def _has_mixed(obj: Any) -> bool:
    """Whether obj is, or has a segment that is, a curve written by certified pieces."""
    segs = getattr(obj, "segments", [obj])
    return any(_over_atoms(c) and _by_certified_pieces(c) for c in segs)


DEFAULT_DEVIATION = 1e-10  # relative to the curve's size: the export's default tolerance


def _pieces_of(curve: Any, tolerance: float | None = None) -> list[Any]:
    """An AtomCurve's polynomial Bézier pieces of degree EXPORT_DEGREE: those of
    _atom_geometry.pieces when it has a rational form (a composite's segment), else within
    `tolerance` of it, certified (_atom_geometry.certified_pieces)."""
    from . import _atom_geometry as ag

    if not _by_certified_pieces(curve):
        return [piece for _, _, piece in ag.pieces(curve, ag.EXPORT_DEGREE)]
    if tolerance is None:
        tolerance = DEFAULT_DEVIATION * max(float(np.abs(curve.points).max()), 1e-300)
    found, _ = ag.certified_pieces(curve, tolerance, ag.EXPORT_DEGREE)
    return [piece for _, _, piece in found]


def to_bspline(obj: Shape, *, tol: float = 1e-9, tolerance: float | None = None) -> BSpline:
    """One clamped B-spline equal to the curve or composite (on t ∈ [0, 1] or u ∈ [0, N]):
    the Bernstein pieces at a common degree p, the knot at each joint repeated p − k times
    where the joint is C^k in u (exactly, for exact input; within the relative tolerance
    `tol` otherwise). Exact (Fractions) when every segment is exact. A composite with a
    gap at a joint raises ValueError. A RationalBezierCurve is one rational span with its
    weights; a curve of a trigonometric family is its exact rational form, of a family
    without one its approximation by polynomial pieces within `tolerance` (a distance;
    default 1e-10 of its size), certified (`_exportable`)."""
    obj = _exportable(obj, _tolerance(tolerance))
    rational = _rational(obj)
    if rational is not None:
        n = rational.degree
        exact = rational.is_exact
        zero, one = (Fraction(0), Fraction(1)) if exact else (0.0, 1.0)
        points = rational.control_points()
        weights = rational.control_weights()
        return BSpline(n, (zero,) * (n + 1) + (one,) * (n + 1), points, exact, weights)
    segs = _segments(obj)
    degree, rows, exact = _pieces(segs)
    size = max(1.0, max(abs(float(v)) for piece in rows for row in piece for v in row))
    mults: list[int] = []
    for j in range(len(rows) - 1):
        k = _joint_order(rows[j], rows[j + 1], degree, exact, tol, size)
        if k < 0:
            gap = math.dist(map(float, rows[j][-1]), map(float, rows[j + 1][0]))
            raise ValueError(
                f"the composite is not continuous at joint {j} (u = {j + 1}): the segments "
                f"are {gap:.3g} apart; one B-spline needs connected segments"
            )
        mults.append(max(degree - k, 0))
    spline = _assemble(degree, rows, mults, exact, tol, size)
    if spline is None:  # never expected: full multiplicity is the pieces themselves
        spline = _assemble(degree, rows, [degree] * len(mults), exact, tol, size)
    assert spline is not None
    return spline


# ---------------------------------------------------------------------- STEP (OCCT)
def _in_space(spline: BSpline, what: str) -> None:
    """STEP and DXF hold points in space: a 2D curve is written in the plane z = 0, a 3D one
    as it is; any other dimension refused by name (a 4D curve lost its fourth coordinate, a
    1D one failed unpacking a point)."""
    dim = len(spline.control_points[0])
    if dim not in (2, 3):
        raise ValueError(
            f"{what} holds curves in the plane (written at z = 0) or in space; this curve is {dim}D"
        )


def _quiet_occt(message_module: ModuleType) -> None:
    """OCCT's default messenger prints every transfer to stdout; keep only failures."""
    gravity = message_module.Message_Gravity.Message_Fail
    for printer in message_module.Message.DefaultMessenger_s().Printers():
        printer.SetTraceLevel(gravity)


def _write_step(writer: Any, target: Path) -> Path:
    """Write the model of an OCCT STEPControl_Writer that has its transfer done to `target`,
    every real with 17 significant digits, so that each double reads back unchanged.

    (STEPControl_Writer.Write formats reals with the Interface_FloatWriter(12) of
    StepData_StepWriter, "%14.12f" for 0.1 <= |x| < 1000 and "%14.12E" elsewhere, trailing
    zeros cut: 1/3 becomes 0.333333333333, and no Interface_Static parameter changes that.
    The same writer, made here, takes another format: "%.16E" always has the point and the
    exponent an ISO 10303-21 real may have; SetFormat's reset drops the fixed-point range and
    the zero suppression, which scans only a number's first 16 characters.)"""
    from OCP.StepData import StepData_StepWriter

    model = writer.Model()
    out = StepData_StepWriter(model)
    out.FloatWriter().SetFormat("%.16E", True)
    out.SendModel(model.Protocol(), False)
    text = "".join(out.Line(i).ToCString() + "\n" for i in range(1, out.NbLines() + 1))
    try:
        target.write_text(text, encoding="utf-8")
    except OSError as exc:
        raise OSError(f"could not write the STEP file {target}: {exc.strerror or exc}") from exc
    return target


def to_step(obj: Shape, path: str | Path, *, tolerance: float | None = None) -> Path:
    """Write the curve or composite as one B-spline edge (B_SPLINE_CURVE_WITH_KNOTS) to a
    STEP file through OCCT (OCP); 2D curves lie in the plane z = 0 (other dimensions than 2
    and 3 are refused). Every number is written
    with 17 significant digits: the file holds the B-spline's floats (`to_bspline`, exact
    Fractions rounded once) exactly, and OCCT reads back the same doubles. A curve of a
    mixed family (no rational form) is written as polynomial pieces within `tolerance` of it
    (a distance in its units; default 1e-10 of its size), a certified bound."""
    feature = "to_step"
    _optional("OCP", "cadquery-ocp-novtk (OCP)", feature)
    from OCP import Message
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge
    from OCP.collections import Array1_double, Array1_gp_Pnt, Array1_int
    from OCP.Geom import Geom_BSplineCurve
    from OCP.gp import gp_Pnt
    from OCP.IFSelect import IFSelect_ReturnStatus
    from OCP.STEPControl import STEPControl_StepModelType, STEPControl_Writer

    spline = to_bspline(obj, tolerance=tolerance)
    _in_space(spline, "a STEP file")
    _quiet_occt(Message)
    values, mults = spline.breakpoints()
    poles = Array1_gp_Pnt(1, len(spline.control_points))
    for i, row in enumerate(spline.control_points, start=1):
        x, y, *z = (float(v) for v in row)
        poles.SetValue(i, gp_Pnt(x, y, z[0] if z else 0.0))
    knots = Array1_double(1, len(values))
    multiplicities = Array1_int(1, len(values))
    for i, (v, m) in enumerate(zip(values, mults, strict=True), start=1):
        knots.SetValue(i, float(v))
        multiplicities.SetValue(i, m)
    if spline.weights is None:
        curve = Geom_BSplineCurve(poles, knots, multiplicities, spline.degree)
    else:  # a rational B-spline: OCCT writes it as a rational B_SPLINE_CURVE_WITH_KNOTS
        weights = Array1_double(1, len(spline.weights))
        for i, w in enumerate(spline.weights, start=1):
            weights.SetValue(i, float(w))
        curve = Geom_BSplineCurve(poles, weights, knots, multiplicities, spline.degree)
    edge = BRepBuilderAPI_MakeEdge(curve).Edge()
    writer = STEPControl_Writer()
    done = IFSelect_ReturnStatus.IFSelect_RetDone
    if writer.Transfer(edge, STEPControl_StepModelType.STEPControl_AsIs) != done:
        raise RuntimeError("OCCT could not transfer the B-spline edge to STEP")
    return _write_step(writer, Path(path))


# ---------------------------------------------------------------------- DXF (ezdxf)
def to_dxf(obj: Shape, path: str | Path, *, tolerance: float | None = None) -> Path:
    """Write the curve or composite as one DXF SPLINE entity (DXF R2010) through ezdxf;
    2D curves lie in the plane z = 0 (other dimensions than 2 and 3 are refused). Degrees up
    to 10: ezdxf's own construction_tool()
    evaluates no higher (order 12 and above is refused by its B-spline basis). `tolerance`:
    as for to_step."""
    ezdxf = _optional("ezdxf", "ezdxf", "to_dxf")
    spline = to_bspline(obj, tolerance=tolerance)
    _in_space(spline, "a DXF SPLINE")
    if spline.degree > DXF_MAX_DEGREE:
        raise ValueError(
            f"a DXF SPLINE is written for degrees up to {DXF_MAX_DEGREE} (the highest ezdxf reads "
            "back and evaluates: its B-spline basis refuses order 12 and above); this curve "
            f"is a polynomial of degree {spline.degree}: export it with to_step instead"
        )
    doc = ezdxf.new("R2010")
    points = [tuple(float(v) for v in row) for row in spline.control_points]
    knots = [float(k) for k in spline.knots]
    if spline.weights is None:
        doc.modelspace().add_open_spline(points, degree=spline.degree, knots=knots)
    else:
        weights = [float(w) for w in spline.weights]
        doc.modelspace().add_rational_spline(points, weights, degree=spline.degree, knots=knots)
    target = Path(path)
    try:  # as to_step: the path named, not ezdxf's own traceback
        doc.saveas(target)
    except OSError as exc:
        raise OSError(f"could not write the DXF file {target}: {exc.strerror or exc}") from exc
    return target


# ---------------------------------------------------------------------- SVG
def _hermite_cubic(rows: np.ndarray) -> np.ndarray:
    """The cubic with the piece's end points and end derivatives."""
    p = rows.shape[0] - 1
    q1 = rows[0] + p / 3 * (rows[1] - rows[0])
    q2 = rows[-1] - p / 3 * (rows[-1] - rows[-2])
    return np.array([rows[0], q1, q2, rows[-1]])


def _elevated(rows: np.ndarray, degree: int) -> np.ndarray:
    """Bézier points elevated to `degree` (P*_i = i/(n+1) P_{i-1} + (1 − i/(n+1)) P_i)."""
    while rows.shape[0] - 1 < degree:
        n = rows.shape[0] - 1
        i = np.arange(1, n + 1)[:, None] / (n + 1)
        mid = i * rows[:-1] + (1 - i) * rows[1:]
        rows = np.vstack([rows[:1], mid, rows[-1:]])
    return rows


def _cubics(rows: np.ndarray, tolerance: float, depth: int = 0) -> list[np.ndarray]:
    """Cubics within `tolerance` of the Bézier piece `rows` (degree > 3): the Hermite cubic
    when the Bernstein coefficients of the difference (a bound on the distance at every t,
    by the convex hull property) are small enough, else both halves."""
    cubic = _hermite_cubic(rows)
    bound = np.linalg.norm(rows - _elevated(cubic, rows.shape[0] - 1), axis=1).max()
    scale = np.abs(rows).max()
    if bound + 64 * np.finfo(float).eps * scale <= tolerance:
        return [cubic]
    if depth >= 40:
        raise ValueError(f"cannot approximate within tolerance={tolerance} (too small)")
    left, right = alg.split_rows(rows.tolist(), 0.5)
    return _cubics(np.array(left), tolerance, depth + 1) + _cubics(
        np.array(right), tolerance, depth + 1
    )


def _num(x: float) -> str:
    return repr(float(x)) if x != 0 else "0"


def _tolerance(tolerance: object) -> float | None:
    """None, or the caller's tolerance as a positive finite distance; a ValueError naming
    the argument otherwise (a bool, a text, NaN, or a negative number as given, before any
    share of it is taken)."""
    if tolerance is None:
        return None
    value = float(val.real_number(tolerance, "tolerance", keep_exact=False))
    if value <= 0:
        raise ValueError(f"tolerance must be a positive distance, got {tolerance!r}")
    return value


def to_svg(obj: Shape, *, tolerance: float | None = None, stroke_width: float | None = None) -> str:
    """An SVG document with one path for a 2D curve or composite, in the curve's own
    coordinates (the group flips y so that y points up on screen). Pieces of degree <= 3 are
    exact (L, Q, C commands; coordinates as shortest float repr). Higher-degree pieces need
    `tolerance`: they become cubics within that distance of the curve at every parameter
    (checked on the Bernstein form of the difference), else ValueError. A rational curve
    whose weights differ always needs `tolerance` (SVG has no rational segments)."""
    tolerance = _tolerance(tolerance)
    if tolerance is not None and _has_mixed(obj):
        # half the tolerance to the polynomial pieces (certified), half to their cubics
        tolerance = float(tolerance) / 2
    obj = _exportable(obj, tolerance)
    rational = _rational(obj)
    if rational is not None:
        if rational.dimension != 2:
            raise ValueError(f"SVG paths are 2D; this curve is {rational.dimension}D")
        if len(set(rational.control_weights())) == 1:
            obj = rational.to_bezier()  # a polynomial curve after all: exact up to cubics
        else:
            return _rational_svg(rational, tolerance, stroke_width)
    segs = _segments(obj)
    if segs[0].dimension != 2:
        raise ValueError(f"SVG paths are 2D; this curve is {segs[0].dimension}D")
    if tolerance is not None:
        tolerance = float(tolerance)
        if not math.isfinite(tolerance) or tolerance <= 0:
            raise ValueError(f"tolerance must be a positive distance, got {tolerance}")
    commands: list[str] = []
    previous: np.ndarray | None = None
    for i, seg in enumerate(segs):
        rows = np.array(seg.to_bezier().points, dtype=float)
        degree = rows.shape[0] - 1
        if previous is None or not np.array_equal(rows[0], previous):
            commands.append(f"M {_num(rows[0][0])} {_num(rows[0][1])}")
        if degree <= 3:
            pieces = [rows]
        elif tolerance is None:
            raise ValueError(
                f"segment {i} is a polynomial of degree {degree}; SVG paths hold cubics at "
                "most: pass tolerance= (a distance in the curve's units; --tolerance on the "
                "command line) to approximate it"
            )
        else:
            pieces = _cubics(rows, tolerance)
        for piece in pieces:
            letter = {1: "L", 2: "Q", 3: "C"}[piece.shape[0] - 1]
            coords = " ".join(f"{_num(x)} {_num(y)}" for x, y in piece[1:])
            commands.append(f"{letter} {coords}")
        previous = rows[-1]
    return _svg_document(commands, _svg_box(obj), stroke_width)


def _svg_document(
    commands: list[str], box: tuple[np.ndarray, np.ndarray], stroke_width: float | None
) -> str:
    lo, hi = box
    span = max(hi[0] - lo[0], hi[1] - lo[1], 1e-12)
    pad = 0.02 * span
    width = stroke_width if stroke_width is not None else span / 200
    view = (lo[0] - pad, -hi[1] - pad, hi[0] - lo[0] + 2 * pad, hi[1] - lo[1] + 2 * pad)
    return (
        '<?xml version="1.0" encoding="UTF-8"?>\n'
        f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="{" ".join(map(_num, view))}">\n'
        '  <g transform="scale(1 -1)">\n'
        f'    <path d="{" ".join(commands)}" fill="none" stroke="black" '
        f'stroke-width="{_num(width)}"/>\n'
        "  </g>\n"
        "</svg>\n"
    )


def _rational_svg(
    curve: RationalBezierCurve, tolerance: float | None, stroke_width: float | None
) -> str:
    from .hazmat import rational_kernels as rk

    if tolerance is None:
        raise ValueError(
            "a rational curve (weights not all equal) has no exact SVG path: pass tolerance= "
            "(a distance in the curve's units) to approximate it by cubics within it"
        )
    tolerance = float(tolerance)
    if not math.isfinite(tolerance) or tolerance <= 0:
        raise ValueError(f"tolerance must be a positive distance, got {tolerance}")
    rows = np.array(curve.to_homogeneous().points, dtype=float)
    # the error bounds square coordinates: near 2^600 they overflowed and no tolerance was
    # met; the cubics are found for the curve divided by a power of two (exact), then scaled
    top = float(np.abs(rows[:, :-1]).max())
    shift = math.frexp(top)[1] if top > 0 else 0
    rows[:, :-1] = np.ldexp(rows[:, :-1], -shift)
    found = rk.cubics(rows / rows[:, -1].max(), math.ldexp(tolerance, -shift))
    pieces = [np.ldexp(piece, shift) for piece in found]
    commands = [f"M {_num(pieces[0][0][0])} {_num(pieces[0][0][1])}"]
    for piece in pieces:
        commands.append("C " + " ".join(f"{_num(x)} {_num(y)}" for x, y in piece[1:]))
    return _svg_document(commands, curve.bounding_box(), stroke_width)


def _svg_box(obj: Shape) -> tuple[np.ndarray, np.ndarray]:
    from .geometry import bounding_box

    return bounding_box(obj)  # type: ignore[arg-type]
