"""Issue #29 "then fast": a tangency's pair of pieces is confined to a small cell around its
point of contact (hazmat.intersect_contact) instead of being subdivided to the flat pieces.

- the certificate is sound: where it holds, every common point of the pair lies within
  R = 2^-RADIUS of the contact, checked against the exact crossings of a parabola and a line
  (x = u, y = c (u - u0)^2 against y = h: crossings at u0 -+ sqrt(h / c));
- it holds at true tangencies (else the test above could pass by never holding);
- the answers of intersect are the subdivision's to the flat pieces (contact cells switched
  off) on tangencies: the fixtures' and curves reflected in their own tangent lines, with the
  same kinds, crossings to the last bit and tangencies to the parity tests' 32 ulps;
- its compiled twin (the same source compiled with numba) takes the same decisions, and both
  subdivision loops leave the same cells.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from conftest import assert_same_isolated as same
from conftest import careful_path as careful
from conftest import on_both_subdivision_paths as both
from hypothesis import given, settings
from hypothesis import strategies as st

import lambda_bezier as lb
from lambda_bezier.hazmat import intersect as engine
from lambda_bezier.hazmat import intersect_contact as contact
from lambda_bezier.hazmat import intersect_subdivide as sub

SLACK = 128 * float(np.finfo(float).eps)  # the careful path's for quadratics of size ~1


def piece(points: np.ndarray, level: int, k: int) -> np.ndarray:
    """The control points of the k-th piece of width 2^-level."""
    out = np.empty_like(points)
    width = 0.5**level
    contact._part(points, k * width, (k + 1) * width, np.empty_like(points), out)
    return out


def parabola(c: float, u0: float) -> np.ndarray:
    """x = u, y = c (u - u0)^2 as a quadratic Bézier curve (its control points exact for
    dyadic u0 and c)."""
    return np.array([[0.0, c * u0 * u0], [0.5, -c * u0 * (1 - u0)], [1.0, c * (1 - u0) ** 2]])


@settings(max_examples=60, deadline=None, derandomize=True)
@given(
    c=st.sampled_from([0.25, 1.0, 4.0, 16.0]),
    u0=st.integers(1, 63).map(lambda k: k / 64),
    h=st.sampled_from([0.0, 1e-16, 1e-14, 1e-13, 4e-13, 1e-12, 1e-11, 1e-9, -1e-12, -1e-9]),
    level=st.integers(0, 8),
)
def test_a_confined_pair_has_its_crossings_in_the_cell(c, u0, h, level):
    a = parabola(c, u0)
    b = np.array([[-0.5, h], [1.5, h]])  # the line y = h over x in [-0.5, 1.5], t = (x + 0.5) / 2
    ka = min(int(u0 * 2**level), 2**level - 1)
    kb = min(int((u0 + 0.5) / 2 * 2**level), 2**level - 1)
    found, cell_a, cell_b = contact.contact_cell(
        piece(a, level, ka), piece(b, level, kb), ka, kb, level, contact.DEEP, SLACK
    )
    radius = 0.5**contact.RADIUS
    if h == 0.0 and c * radius**2 > 8 * SLACK:
        # an exact tangency, its curves on the two sides of the common tangent, curved enough
        # to leave the slack within R (flatter ones are halved to the flat pieces as before)
        assert found
    if not found:
        return
    cell = 0.5**contact.DEEP
    if h > 0.0:  # two crossings, at u0 -+ sqrt(h / c): both within R of the contact
        for u in (u0 - math.sqrt(h / c), u0 + math.sqrt(h / c)):
            if ka * 0.5**level <= u <= (ka + 1) * 0.5**level:
                assert abs(u - u0) <= radius
    # the cell holds the contact (or lies next to it, at the pair's edge)
    assert abs((cell_a + 0.5) * cell - u0) <= 0.5**level * 1e-9 + cell
    assert abs((cell_b + 0.5) * cell - (u0 + 0.5) / 2) <= 0.5**level * 1e-9 + cell


def test_crossings_farther_apart_than_the_cell_are_not_confined():
    # y = (u - 1/2)^2 against y = h: crossings 2 sqrt(h) apart. Beyond R (and the slack), the
    # parts beside the contact cross the line: no pair of pieces is confined
    a = parabola(1.0, 0.5)
    for h in (1e-10, 1e-8, 1e-6, 1e-4):
        b = np.array([[-0.5, h], [1.5, h]])
        for level in range(0, 12):
            k = 2 ** (level - 1) if level else 0
            for ka in {max(k - 1, 0), k}:
                kb = max(0, min(2 ** (level - 1) if level else 0, 2**level - 1))
                got = contact.contact_cell(
                    piece(a, level, ka), piece(b, level, kb), ka, kb, level, contact.DEEP, SLACK
                )
                assert not got[0], (h, level, ka, kb)


def assert_same_answer(got, want) -> None:
    assert [h.kind for h in got] == [h.kind for h in want], (got, want)
    for x, y in zip(got, want, strict=True):
        tol = 0.0 if x.kind == "transversal" else 32 * np.spacing(1.0)
        assert abs(x.s - y.s) <= tol and abs(x.t - y.t) <= tol, (got, want)


def reflected(rng: np.random.Generator, degree: int, at: float) -> tuple[np.ndarray, np.ndarray]:
    """A random curve and its reflection in its own tangent line at `at` (tangent there, the
    two on the two sides of the common tangent where the curve is convex)."""
    pts = rng.integers(-8, 9, size=(degree + 1, 2)).astype(float)
    work = pts.copy()
    for level in range(degree):
        if level == degree - 1:
            tangent = work[1] - work[0]
        work = work[:-1] + at * (work[1:] - work[:-1])
    point = work[0]
    unit = tangent / np.linalg.norm(tangent)
    rel = pts - point
    mirrored = 2 * (rel @ unit)[:, None] * unit - rel + point
    return pts, mirrored


TANGENT_PAIRS = [
    ([(0.0, 0.0), (0.5, 1.0), (1.0, 0.0)], [(0.0, 1.0), (0.5, 0.0), (1.0, 1.0)]),
    ([(0.0, 0.0), (4.5, 9.0), (9.0, 0.0)], [(3.0, 4.5), (8.0, 4.5)]),
    ([(-1.0, 1.0), (0.0, -1.0), (1.0, 1.0)], [(-1.0, 0.0), (1.0, 0.0)]),
    ([(0.5, 0.125), (1.25, -0.25), (2.0, 0.5)], [(0.5, -0.125), (1.0, 0.125), (1.5, -0.125)]),
    ([(0.0, 0.0), (-0.5, 1.5), (1.0, 1.0)], [(-1.0, 1.0), (0.5, 0.5), (0.0, 2.0)]),
    ([(-0.5, -3.0), (0.5, 5.0), (1.5, -3.0)], [(4.0, -4.125), (-1.5, 1.375), (1.0, 0.875)]),
    ([(0.0, 0.0), (0.375, 0.75), (0.75, 0.375)], [(0.25, 0.625), (0.625, 0.25), (1.0, 1.0)]),
    # a tangency and two crossings; near-double crossings 1e-3 apart (two, not one contact)
    ([(0.0, 0.0), (1.0, 3.0), (2.0, -3.0), (3.0, 0.0)], [(0.0, 0.75), (3.0, 0.75)]),
    ([(-1.0, 1.21), (0.0, -0.99), (1.0, 0.81)], [(-1.0, 1e-6), (1.0, 1e-6)]),
    ([(-1.0, 1.21), (0.0, -0.99), (1.0, 0.81)], [(-1.0, 1e-12), (1.0, 1e-12)]),
]
_rng = np.random.default_rng(1929)
TANGENT_PAIRS += [
    tuple(x.tolist() for x in reflected(_rng, degree, at))
    for degree in (2, 3, 4)
    for at in (0.3, 0.5, 0.71)
]


def with_and_without_cells(a, b, switch) -> tuple[list, list]:
    """careful(a, b) on the numpy loop with the contact cells (`switch(True)`) and halved to
    the flat pieces (`switch(False)`): (got, want)."""
    saved = sub.USE_COMPILED
    sub.USE_COMPILED = False  # the numpy loop reads the switch per call
    try:
        switch(False)
        want = careful(a, b)
        switch(True)
        got = careful(a, b)
    finally:
        sub.USE_COMPILED = saved
    return got, want


@pytest.mark.parametrize("pair", range(len(TANGENT_PAIRS)))
def test_answers_are_the_subdivisions_to_the_flat_pieces(pair, no_contact_cells):
    a, b = TANGENT_PAIRS[pair]
    got, want = with_and_without_cells(a, b, no_contact_cells)
    assert_same_answer(got, want)
    if b == [(-1.0, 1e-6), (1.0, 1e-6)]:  # the near-double crossing: still two
        assert [h.kind for h in got] == ["transversal", "transversal"]


def test_a_tangent_subdivision_stops_early():
    """The arches touching at their tops: four cells of width 2^-32 at level 2, instead of
    the flat pieces of width 2^-23 (~180 pairs of pieces halved on the way down)."""
    a = np.array([[[0.0, 0.0], [0.5, 1.0], [1.0, 0.0]]])
    b = np.array([[[0.0, 1.0], [0.5, 0.0], [1.0, 1.0]]])
    saved = sub.USE_COMPILED
    sub.USE_COMPILED = False
    try:
        iso = sub.isolate(a, b, np.array([SLACK]))
    finally:
        sub.USE_COMPILED = saved
    assert iso.left_width.tolist() == [0.5**contact.DEEP] * 4
    assert set(iso.left_s0.tolist()) <= {0.5, 0.5 - 0.5**contact.DEEP}


@pytest.mark.parametrize("pair", range(len(TANGENT_PAIRS)))
def test_both_loops_leave_the_same_cells(pair):
    pytest.importorskip("numba", reason="numba is not installed: no twin")
    a, b = (np.array(x, dtype=float)[None] for x in TANGENT_PAIRS[pair])
    p, q = lb.BezierCurve(a[0])._prepared, lb.BezierCurve(b[0])._prepared
    slow, fast = both(lambda: sub.isolate(a, b, np.array([engine._slack(p, q)])))
    same(slow, fast)


@settings(max_examples=40, deadline=None, derandomize=True)
@given(
    degrees=st.tuples(st.integers(1, 4), st.integers(1, 4)),
    seed=st.integers(0, 2**32 - 1),
    level=st.integers(0, 12),
)
def test_the_compiled_twin_takes_the_same_decisions(degrees, seed, level):
    pytest.importorskip("numba", reason="numba is not installed: no twin")
    from lambda_bezier.hazmat import intersect_compiled

    rng = np.random.default_rng(seed)
    a, b = reflected(rng, max(degrees), rng.uniform(0.1, 0.9))
    if degrees[1] < degrees[0]:
        b = rng.normal(size=(degrees[1] + 1, 2))
    k = int(rng.integers(0, 2**level))
    pa, pb = piece(a, level, k), piece(b, level, k)
    for slack in (1e-13, 1e-9):
        want = contact.contact_cell(pa, pb, k, k, level, contact.DEEP, slack)
        got = intersect_compiled.contact_cell(pa, pb, k, k, level, contact.DEEP, slack)
        assert tuple(got) == tuple(want)
