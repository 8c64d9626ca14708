"""The certificate at an end point the two curves share exactly (issue #29, round 20).

intersect_certify answers such a pair when the end tangents there are clearly apart and the
pair of pieces holding the shared corner is isolated: the shared point is then recorded as it
is, with no Newton. Its answers must be the careful path's (run here in Python, alone), bit
for bit, on both engines, and the pairs it must not answer (a smooth join, where the careful
path calls the shared point a tangency) are declined.
"""

from __future__ import annotations

import numpy as np
import pytest
from conftest import careful_path as careful

import lambda_bezier as lb
from lambda_bezier.hazmat import intersect as engine
from lambda_bezier.hazmat import intersect_certify as cert

pytestmark = pytest.mark.usefixtures("intersect_engine")


def glued_pairs() -> list[tuple[np.ndarray, np.ndarray]]:
    """Random curves of degrees 1-4 whose ends meet exactly, in each orientation; some meet
    at both ends, some are in 3-d."""
    rng = np.random.default_rng(2020)
    pairs = []
    for k in range(48):
        n, m = rng.integers(1, 5, 2)
        dim = 3 if k % 8 == 7 else 2
        a, b = rng.uniform(-1, 1, (n + 1, dim)), rng.uniform(-1, 1, (m + 1, dim))
        i, j = rng.integers(0, 2, 2)
        b[-1 if j else 0] = a[-1 if i else 0]
        if k % 6 == 5:
            b[0 if j else -1] = a[0 if i else -1]
        pairs.append((a, b))
    return pairs


def test_the_knobs_are_the_careful_paths():
    # the neighbourhood is the careful path's merge radius; the least sine far above its
    # tangent sine, so that both call the shared point a crossing
    assert cert.SHARED_NEAR == engine.MERGE_RADIUS
    assert cert.SHARED_SINE >= 100 * engine.TANGENT_SINE


def test_certified_shared_ends_are_the_careful_answers():
    answered = 0
    for a, b in glued_pairs():
        slow = careful(a, b)
        got = cert.certify_one(a, b, engine.BOX_SLACK, engine.ROOT_RESIDUAL, engine.SETTLE)
        if got is None:
            continue
        answered += 1
        assert list(zip(*got, strict=True)) == [(h.s, h.t) for h in slow]
        assert all(h.kind == "transversal" for h in slow)
        assert any(h.s in (0.0, 1.0) and h.t in (0.0, 1.0) for h in slow)
    # most of them are answered (the feature itself: before it, none was)
    assert answered >= 30


def test_a_smooth_join_is_declined():
    """The two halves of a split curve meet with parallel tangents: a tangency for the
    careful path, never a certified crossing."""
    rng = np.random.default_rng(7)
    for degree in (2, 3, 4):
        curve = lb.BezierCurve(rng.uniform(-1, 1, (degree + 1, 2)))
        left, right = curve.split(0.5)
        a = np.array(left.control_points(), dtype=float)
        b = np.array(right.control_points(), dtype=float)
        for x, y in ((a, b), (b, a), (a[::-1].copy(), b), (a, b[::-1].copy())):
            assert (
                cert.certify_one(x, y, engine.BOX_SLACK, engine.ROOT_RESIDUAL, engine.SETTLE)
                is None
            )
            assert any(h.kind == "tangent" for h in careful(x, y))
