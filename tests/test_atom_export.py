"""Export of mixed (algebraic-trigonometric) curves, which have no rational form (issue #30):
polynomial pieces within a tolerance the user chooses, the bound certified
(hazmat.atom_deviation), checked against dense mpmath sampling of the curve and of the pieces
(their float control points exactly)."""

from __future__ import annotations

import math

import mpmath as mp
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from test_atom_certified_geometry import mp_curve

from lambda_bezier import _atom_geometry as ag
from lambda_bezier import export

mp.mp.dps = 40


def mp_bezier(rows, u):
    n = len(rows) - 1
    u = mp.mpf(u)
    return [
        mp.fsum(
            mp.binomial(n, i) * u**i * (1 - u) ** (n - i) * mp.mpf(float(rows[i][c]))
            for i in range(n + 1)
        )
        for c in range(len(rows[0]))
    ]


def mp_worst(curve, found, per_piece: int = 40) -> mp.mpf:
    """The largest distance, at per_piece + 1 points of every piece, between the piece and the
    curve (both in mpmath; t = a + u (b − a) with a, b the floats)."""
    worst = mp.mpf(0)
    for a, b, piece in found:
        rows = np.asarray(piece.points, dtype=float)
        for k in range(per_piece + 1):
            u = mp.mpf(k) / per_piece
            t = mp.mpf(a) + u * (mp.mpf(b) - mp.mpf(a))
            c, p = mp_curve(curve, t), mp_bezier(rows, u)
            worst = max(worst, mp.sqrt(mp.fsum((x - y) ** 2 for x, y in zip(c, p, strict=True))))
    return worst


POINTS = st.lists(st.floats(-4, 4, allow_nan=False), min_size=8, max_size=8).map(
    lambda r: np.array(r).reshape(4, 2)
)


@settings(max_examples=8)
@given(POINTS, st.floats(0, 0.99), st.sampled_from([1e-3, 1e-7, 1e-11]), st.booleans())
def test_certified_bound_holds_against_mpmath(at_family, at_pi_family, pts, lam, rel, pi):
    fam = at_pi_family if pi else at_family
    curve = fam.curve(pts, lam=lam)
    size = max(float(np.abs(pts).max()), 1e-3)
    tol = rel * size
    found, bound = ag.certified_pieces(curve, tol)
    assert bound <= tol
    lo, hi = curve.domain
    assert found[0][0] == lo and found[-1][1] == hi
    assert all(x[1] == y[0] for x, y in zip(found[:-1], found[1:], strict=True))
    assert mp_worst(curve, found, 12) <= bound


def test_tolerance_decides_the_pieces(at_family):
    curve = at_family.curve([(0, 0), (1, 3), (3, -2), (4, 1)], lam=0.3)
    counts = []
    for tol in (1e-2, 1e-6, 1e-12):
        found, bound = ag.certified_pieces(curve, tol)
        assert bound <= tol
        assert mp_worst(curve, found, 30) <= bound
        counts.append(len(found))
    assert counts[0] <= counts[1] <= counts[2] and counts[0] < counts[2]
    for bad in (0.0, -1.0, math.nan, math.inf):
        with pytest.raises(ValueError, match="tolerance"):
            ag.certified_pieces(curve, bad)
    with pytest.raises(ValueError, match="tolerance"):
        ag.certified_pieces(curve, 1e-17)


def test_bspline_and_files_keep_the_tolerance(at_family, tmp_path):
    curve = at_family.curve([(0, 0), (1, 3), (3, -2), (4, 1)], lam=0.3)
    tol = 1e-6
    spline = export.to_bspline(curve, tolerance=tol)
    found, bound = ag.certified_pieces(curve, tol)
    assert len(spline.breakpoints()[0]) - 1 == len(found)
    for j, (a, b, _) in enumerate(found):
        for u in np.linspace(0, 1, 9):
            got = np.array(spline.point(j + u), dtype=float)
            assert np.linalg.norm(got - curve.evaluate(a + (b - a) * u)) <= tol
    pytest.importorskip("ezdxf")
    export.to_dxf(curve, tmp_path / "c.dxf", tolerance=tol)
    assert (tmp_path / "c.dxf").stat().st_size > 0
    svg = export.to_svg(curve, tolerance=1e-4)
    assert svg.count(" C ") + svg.count("C ") >= 1


def test_default_tolerance_is_relative(at_family):
    curve = at_family.curve(np.array([(0, 0), (1, 3), (3, -2), (4, 1)]) * 1000.0, lam=0.3)
    spline = export.to_bspline(curve)
    found, _ = ag.certified_pieces(curve, export.DEFAULT_DEVIATION * 4000.0)
    assert len(spline.breakpoints()[0]) - 1 == len(found)
