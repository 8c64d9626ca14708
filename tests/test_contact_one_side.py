"""Issue #29 "then fast", round 20: contacts that the straight separating axes of
hazmat.intersect_contact cannot confine, confined without halving to the flat pieces.

- curves on ONE side of their common tangent (a circle inside another): a parabola between
  them (its curvature the mean of theirs) parts them away from the contact. Sound: where the
  certificate holds, every crossing of the pair lies within R of the contact, checked against
  the exact crossings of two parabolas y = c1 (x - x0)^2 and y = c2 (x - x0)^2 + h; and it
  holds at true one-sided tangencies (else that check could pass by never holding); a pair
  holding a second crossing 1e-4 to 0.1 away from a one-sided tangency is never confined;
- a smooth join (the pieces' end points meet, tangents parallel, curvatures equal: Newton's
  Jacobian is singular) is confined at its corner; a corner where the curves cross is not
  (the cones isolate it);
- intersect's answers are the subdivision's to the flat pieces (contact cells switched off)
  on such pairs, and the compiled twin takes the same decisions.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from conftest import assert_same_isolated as same
from conftest import on_both_subdivision_paths as both
from hypothesis import given, settings
from hypothesis import strategies as st
from test_contact_cell import (
    SLACK,
    assert_same_answer,
    parabola,
    piece,
    with_and_without_cells,
)
from test_parity import CASES, control_rows

import lambda_bezier as lb
from lambda_bezier.hazmat import intersect as engine
from lambda_bezier.hazmat import intersect_contact as contact
from lambda_bezier.hazmat import intersect_subdivide as sub


def graph(c: float, x0: float, h: float) -> np.ndarray:
    """y = c (x - x0)^2 + h over x = -1/2 + 2 t, t in [0, 1], as a quadratic Bézier curve
    (exact for dyadic c, x0, h)."""
    xs = (-0.5, 0.5, 1.5)
    y0 = c * (xs[0] - x0) ** 2 + h
    y1 = y0 + 2 * c * (xs[0] - x0) * (xs[1] - xs[0])  # the tangent at t = 0 through (x1, y1)
    y2 = c * (xs[2] - x0) ** 2 + h
    return np.array([[xs[0], y0], [xs[1], y1], [xs[2], y2]])


@settings(max_examples=80, deadline=None, derandomize=True)
@given(
    curvatures=st.sampled_from([(4.0, 1.0), (1.0, 4.0), (2.0, 1.0), (16.0, 4.0), (-1.0, -4.0)]),
    u0=st.integers(1, 63).map(lambda k: k / 64),
    h=st.sampled_from([0.0, 1e-16, 1e-14, 1e-13, 1e-12, 1e-10, -1e-13, -1e-10]),
    level=st.integers(0, 10),
)
def test_a_one_sided_contact_confined_has_its_crossings_in_the_cell(curvatures, u0, h, level):
    c1, c2 = curvatures
    a, b = parabola(c1, u0), graph(c2, u0, h)
    ka = min(int(u0 * 2**level), 2**level - 1)
    kb = min(int((u0 + 0.5) / 2 * 2**level), 2**level - 1)
    found, cell_a, cell_b = contact.contact_cell(
        piece(a, level, ka), piece(b, level, kb), ka, kb, level, contact.DEEP, SLACK
    )
    radius = 0.5**contact.RADIUS
    if h == 0.0 and level >= 4:
        # an exact tangency, both curves on one side of the tangent, curvatures apart:
        # confined (a straight separating axis cannot do it; the parabola between does).
        # On wider pieces Newton from their middles may miss the contact in its 8 steps
        assert found
    if not found:
        return
    if h / (c1 - c2) > 0.0:  # crossings at x0 -+ sqrt(h / (c1 - c2)): both within R
        for u in (u0 - math.sqrt(h / (c1 - c2)), u0 + math.sqrt(h / (c1 - c2))):
            if ka * 0.5**level <= u <= (ka + 1) * 0.5**level:
                assert abs(u - u0) <= radius
    cell = 0.5**contact.DEEP
    assert abs((cell_a + 0.5) * cell - u0) <= 0.5**level * 1e-9 + cell
    assert abs((cell_b + 0.5) * cell - (u0 + 0.5) / 2) <= 0.5**level * 1e-9 + cell


def test_one_sided_crossings_farther_apart_than_the_cell_are_not_confined():
    # y = 4 (x - 1/2)^2 against y = (x - 1/2)^2 + h: crossings 2 sqrt(h / 3) apart
    a = parabola(4.0, 0.5)
    for h in (1e-10, 1e-8, 1e-6, 1e-4):
        b = graph(1.0, 0.5, h)
        for level in range(0, 12):
            half = 2 ** (level - 1) if level else 0
            for ka in {max(half - 1, 0), half}:
                kb = half
                got = contact.contact_cell(
                    piece(a, level, ka), piece(b, level, kb), ka, kb, level, contact.DEEP, SLACK
                )
                assert not got[0], (h, level, ka, kb)


def cubic_graph(c: float, k: float, x0: float) -> np.ndarray:
    """y = c (x - x0)^2 + k (x - x0)^3 over x = -1/2 + 2 t as a cubic Bézier curve (its
    control points solved from four samples: the curve tested is these floats)."""
    ts = np.array([0.0, 1 / 3, 2 / 3, 1.0])
    xs = -0.5 + 2 * ts
    basis = np.array([[math.comb(3, j) * t**j * (1 - t) ** (3 - j) for j in range(4)] for t in ts])
    ys = np.linalg.solve(basis, c * (xs - x0) ** 2 + k * (xs - x0) ** 3)
    return np.column_stack([-0.5 + 2 * np.arange(4) / 3, ys])


@settings(max_examples=80, deadline=None, derandomize=True)
@given(
    curvatures=st.sampled_from([(4.0, 1.0), (1.0, 4.0), (2.0, 1.0), (-1.0, -4.0)]),
    u0=st.integers(8, 56).map(lambda k: k / 64),
    away=st.sampled_from([1e-4, 1e-3, 1e-2, 0.1, -1e-4, -1e-3, -0.1]),
    level=st.integers(2, 14),
)
def test_a_one_sided_contact_with_another_crossing_in_the_pair_is_not_confined(
    curvatures, u0, away, level
):
    """The parabola y = c1 (x - x0)^2 against y = c2 (x - x0)^2 + k (x - x0)^3: tangent at
    x0 (both on one side), crossing again at x0 + away (k = (c1 - c2) / away). A pair of
    pieces holding that crossing, farther than R from the contact, must not be confined."""
    c1, c2 = curvatures
    a, b = parabola(c1, u0), cubic_graph(c2, (c1 - c2) / away, u0)
    # the second crossing of these very floats: a root of the difference along x (b's x is
    # linear in t, so both curves are graphs of polynomials in x)
    xs = np.linspace(-0.5, 1.5, 9)
    tb = (xs + 0.5) / 2
    yb = sum(math.comb(3, j) * tb**j * (1 - tb) ** (3 - j) * b[j, 1] for j in range(4))
    difference = np.polynomial.Polynomial.fit(xs, c1 * (xs - u0) ** 2 - yb, 3).convert()
    roots = difference.roots()
    x2 = float(roots[np.argmin(np.abs(roots - (u0 + away)))].real)
    assert abs(x2 - (u0 + away)) < 1e-6 * max(1.0, abs(away) * 1e3)
    ka = min(int(u0 * 2**level), 2**level - 1)
    kb = min(int((u0 + 0.5) / 2 * 2**level), 2**level - 1)
    width = 0.5**level
    inside_a = ka * width <= x2 <= (ka + 1) * width
    inside_b = kb * width <= (x2 + 0.5) / 2 <= (kb + 1) * width
    found, _, _ = contact.contact_cell(
        piece(a, level, ka), piece(b, level, kb), ka, kb, level, contact.DEEP, SLACK
    )
    if inside_a and inside_b:
        assert not found


def split(points: np.ndarray, at: float) -> tuple[np.ndarray, np.ndarray]:
    """The two parts of a curve cut at `at` (de Casteljau): a smooth join of equal
    curvatures at their common end point."""
    left, right = np.empty_like(points), np.empty_like(points)
    contact._part(points, 0.0, at, np.empty_like(points), left)
    contact._part(points, at, 1.0, np.empty_like(points), right)
    return left, right


@pytest.mark.parametrize("level", [2, 5, 8])
def test_a_smooth_join_is_confined_at_its_corner_and_a_crossing_corner_is_not(level):
    cubic = np.array([[0.0, 0.0], [1.0, 2.0], [3.0, -1.0], [4.0, 1.0]])
    left, right = split(cubic, 0.5)
    last = 2**level - 1
    slack = 64 * float(np.finfo(float).eps) * 3 * 4
    found, cell_a, cell_b = contact.contact_cell(
        piece(left, level, last), piece(right, level, 0), last, 0, level, contact.DEEP, slack
    )
    assert found
    assert (cell_a, cell_b) == (2**contact.DEEP - 1, 0)  # the corner's cell
    # the same corner where the second curve turns away (a transversal join): not a contact
    bent = right.copy()
    bent[1:] = bent[0] + (bent[1:] - bent[0]) @ np.array([[0.0, 1.0], [-1.0, 0.0]])
    found, _, _ = contact.contact_cell(
        piece(left, level, last), piece(bent, level, 0), last, 0, level, contact.DEEP, slack
    )
    assert not found


def fixture_pair(case_id: int) -> tuple[list, list]:
    """A case of the bezier package's fixtures as two lists of float control points (the
    benchmark's input)."""
    (case,) = (c for c in CASES if c["id"] == case_id)
    return tuple(
        [[float(x) for x in point] for point in control_rows(case[k])] for k in ("curve1", "curve2")
    )


def _scaled_and_split_pairs() -> list[tuple[list, list]]:
    rng = np.random.default_rng(2029)
    pairs = []
    for degree in (2, 3, 4):
        for at in (0.3, 0.5, 0.71):
            pts = rng.integers(-8, 9, size=(degree + 1, 2)).astype(float)
            left, right = split(pts, at)
            pairs += [(left, right), (left, right[::-1].copy()), (right, left)]
            work = np.empty_like(pts)
            point = np.empty_like(pts)
            contact._part(pts, at, 1.0, work, point)  # point[0]: the curve at `at`
            for scale in (0.5, 0.75, 2.0):  # a copy scaled about a point on it: one side
                pairs.append((pts, (pts - point[0]) * scale + point[0]))
    return [(a.tolist(), b.tolist()) for a, b in pairs]


PAIRS = [fixture_pair(k) for k in (11, 14, 33, 34, 35, 43, 44, 46, 47)]
PAIRS += _scaled_and_split_pairs()
PAIRS += [  # one-sided parabolas: touching, and crossing twice near the vertex
    (parabola(4.0, 0.5).tolist(), graph(1.0, 0.5, h).tolist()) for h in (0.0, 1e-12, 1e-6)
]


@pytest.mark.parametrize("pair", range(len(PAIRS)))
def test_answers_are_the_subdivisions_to_the_flat_pieces(pair, no_contact_cells):
    got, want = with_and_without_cells(*PAIRS[pair], no_contact_cells)
    assert_same_answer(got, want)


@pytest.mark.parametrize("pair", range(len(PAIRS)))
def test_both_loops_leave_the_same_cells_and_intersect_agrees(pair):
    pytest.importorskip("numba", reason="numba is not installed: no twin")
    a, b = (np.array(x, dtype=float)[None] for x in PAIRS[pair])
    p, q = lb.BezierCurve(a[0])._prepared, lb.BezierCurve(b[0])._prepared
    slow, fast = both(lambda: sub.isolate(a, b, np.array([engine._slack(p, q)])))
    same(slow, fast)
    curve_a, curve_b = lb.BezierCurve(a[0]), lb.BezierCurve(b[0])
    slow_hits, fast_hits = both(lambda: curve_a.intersect(curve_b))
    assert_same_answer(fast_hits, slow_hits)
