"""The certificate at a T-junction: an end point of one curve in the interior of the other
(issue #29, round 21).

intersect_certify answers such a pair when the root there is the only one next to an end,
the tangents are clearly apart, and the careful path's own location of that end point on the
other curve finds it once, next to the certified root, which merges into it. Its answers
must be the careful path's (run here in Python, alone), bit for bit, on both engines; the
pairs it must not answer (a tangency at the end point, two end hits) are declined.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
from conftest import careful_path as careful
from exact_curves import exact_point

from lambda_bezier.hazmat import intersect as engine
from lambda_bezier.hazmat import intersect_certify as cert
from lambda_bezier.hazmat import intersect_subdivide as sub
from lambda_bezier.hazmat.intersect_shared_ends import end_crossing, end_merged

pytestmark = pytest.mark.usefixtures("intersect_engine")


def certified(a: np.ndarray, b: np.ndarray):
    return cert.certify_one(a, b, engine.BOX_SLACK, engine.ROOT_RESIDUAL, engine.SETTLE)


def on(curve: np.ndarray, x: float) -> np.ndarray:
    """curve(x), rounded once from its exact value."""
    rows = [[Fraction(v) for v in row] for row in curve.tolist()]
    return np.array([float(v) for v in exact_point(rows, Fraction(x))])


def t_junctions() -> list[tuple[np.ndarray, np.ndarray]]:
    """Random curves of degrees 1-4, an end of one put on the other (its point at a dyadic
    or random parameter, rounded), in both orders; some in 3-d."""
    rng = np.random.default_rng(2021)
    pairs = []
    for k in range(40):
        n, m = rng.integers(1, 5, 2)
        dim = 3 if k % 8 == 7 else 2
        a, b = rng.uniform(-1, 1, (n + 1, dim)), rng.uniform(-1, 1, (m + 1, dim))
        x = float(rng.choice([0.5, 0.25, 0.375, rng.uniform(0.05, 0.95)]))
        a[-1 if k % 3 else 0] = on(b, x)
        pairs.append((a, b) if k % 2 else (b, a))
    return pairs


def test_the_rules():
    margin = cert.END_MARGIN
    assert end_crossing(0.5, 0.5, margin) == -1
    assert end_crossing(0.0, 0.5, margin) == 0
    assert end_crossing(1.0 + 1e-12, 0.5, margin) == 1
    assert end_crossing(0.5, 1e-12, margin) == 2
    assert end_crossing(0.5, 1.0, margin) == 3
    assert end_crossing(1.0, 0.0, margin) == -2  # a corner: the shared end points' rule
    assert end_crossing(1.2, 0.5, margin) == -2  # beyond the end
    same = cert.SAME
    assert end_merged(1.0, 0.3, 1.0, 0.3, same)
    assert end_merged(1.0 - same / 16, 0.3 + same / 16, 1.0, 0.3, same)
    assert end_merged(1.0 + 1e-12, 0.3 + same / 16, 1.0, 0.3, same)  # clamped to the end
    assert not end_merged(1.0 - same / 4, 0.3, 1.0, 0.3, same)
    assert not end_merged(1.0, 0.3 + same / 4, 1.0, 0.3, same)


def test_certified_t_junctions_are_the_careful_answers():
    answered = 0
    for a, b in t_junctions():
        slow = careful(a, b)
        got = certified(a, b)
        if got is None:
            continue
        answered += 1
        assert list(zip(*got, strict=True)) == [(h.s, h.t) for h in slow]
        assert all(h.kind == "transversal" for h in slow)
        assert sum((h.s in (0.0, 1.0)) != (h.t in (0.0, 1.0)) for h in slow) == 1
    # most of them are answered (the feature itself: before it, none was)
    assert answered >= 30


def test_a_tangent_end_and_two_end_hits_are_declined():
    parabola = np.array([[0.0, 0.0], [0.5, 1.0], [1.0, 0.0]])
    # a segment ending on the vertex along the tangent there: the careful path's tangency
    along = np.array([[-1.0, 0.5], [0.5, 0.5]])
    assert certified(along, parabola) is None
    assert [h.kind for h in careful(along, parabola)] == ["tangent"]
    # a segment ending on the parabola at a small angle (sine ~ 1e-5): the careful path's
    slope = np.array([[-1.0, 0.5 - 1.5e-5], [0.5, 0.5]])
    assert certified(slope, parabola) is None
    # both ends of a segment on the parabola: two end hits, the careful path's
    chord = np.array([on(parabola, 0.25), on(parabola, 0.75)])
    assert certified(chord, parabola) is None
    assert len(careful(chord, parabola)) == 2


def test_the_compiled_half_matrices_are_the_subdivisions():
    # made inside the compiled certificate for a T-junction's location: the same floats
    certify_compiled = pytest.importorskip("lambda_bezier.hazmat.certify_compiled")
    for degree in range(1, 25):
        left, right = certify_compiled.half_matrices(degree)
        want = sub.half_matrices(degree)
        assert np.array_equal(left, want[0]) and np.array_equal(right, want[1])


@pytest.mark.xfail(
    strict=True,
    reason="known, not fixed in round 21: the certificate drops pieces farther apart than its "
    "slack (64 eps x degree x scale) while the careful path accepts an end point within the "
    "rounding of evaluating the other curve there (intersect_locate._rounding_at, up to ~3x "
    "that slack): an end point in between is a hit for the careful path, none for the "
    "certificate (the code before round 21 certified the same empty answer)",
)
def test_an_end_point_within_the_careful_paths_tolerance_is_its_hit():
    a = np.array([[0.0, 3.5e-14], [0.5, 1.0]])  # a(0) 3.5e-14 above the segment b
    b = np.array([[-1.0, 0.0], [1.0, 0.0]])
    assert [(h.s, h.t) for h in careful(a, b)] == [(0.0, 0.5)]
    got = certified(a, b)
    assert got is None or list(zip(*got, strict=True)) == [(0.0, 0.5)]
