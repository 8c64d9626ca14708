"""Issue #29, the numpy fallback's speed work (round 18): what it relies on for unchanged answers.

- Rows of isolate_points are subdivided independently, so one call for many points gives each
  point exactly what a call of its own gives (split_rows), which lets intersect locate the end
  points of a whole group of pairs in one call.
- The per-level helpers, rewritten with fewer numpy calls, compute bit for bit what their plain
  spelling (np.linalg.norm, np.diff, np.clip, ndarray reductions, one call per side) computes.
"""

from __future__ import annotations

import numpy as np
import pytest

from lambda_bezier.hazmat import intersect_subdivide as sub


@pytest.fixture
def numpy_loop(monkeypatch):
    monkeypatch.setattr(sub, "USE_COMPILED", False)


def on_curve(curves: np.ndarray, t: np.ndarray) -> np.ndarray:
    work = curves.copy()
    while work.shape[1] > 1:
        work = work[:, :-1] + t[:, None, None] * (work[:, 1:] - work[:, :-1])
    return work[:, 0]


def as_bytes(iso: sub.Isolated) -> list[bytes]:
    return [np.asarray(x, dtype=float).tobytes() for x in iso]


@pytest.mark.parametrize("degree", [1, 2, 3, 5])
def test_one_call_for_many_points_is_each_points_own_call(numpy_loop, degree):
    rng = np.random.default_rng(degree)
    curves = rng.normal(size=(24, degree + 1, 2))
    # points on the curves, at their ends, and off them; one curve is a line through a point
    t = np.concatenate([rng.uniform(0, 1, 12), np.zeros(4), np.ones(4)])
    points = np.concatenate([on_curve(curves[:20], t), rng.normal(size=(4, 2))])
    slack = np.full(24, 1e-13)
    together = sub.split_rows(sub.isolate_points(curves, points, slack), 24)
    found = 0
    for g in range(24):
        alone = sub.isolate_points(curves[g : g + 1], points[g : g + 1], slack[g : g + 1])
        alone = alone._replace(root_pair=alone.root_pair + g, left_pair=alone.left_pair + g)
        assert as_bytes(together[g]) == as_bytes(alone), g
        found += alone.root_pair.size + alone.left_pair.size
    assert found >= 20  # every point on a curve is found: the comparison is not of empties


def test_split_rows_of_pairs_keeps_each_rows_order(numpy_loop):
    # two pairs that touch (pieces left at the depth) and two that cross several times
    touching = np.array(
        [[[0.0, 0.0], [0.5, 1.0], [1.0, 0.0]], [[0.0, 1.0], [0.5, 0.0], [1.0, 1.0]]]
    )
    rng = np.random.default_rng(3)
    a = np.concatenate([touching[:1], rng.normal(size=(2, 3, 2)), touching[:1]])
    b = np.concatenate([touching[1:] - [0.0, 0.5], rng.normal(size=(2, 3, 2)), touching[1:]])
    slack = np.full(4, 1e-14)
    together = sub.split_rows(sub.isolate(a, b, slack), 4)
    for g in range(4):
        alone = sub.isolate(a[g : g + 1], b[g : g + 1], slack[g : g + 1])
        alone = alone._replace(root_pair=alone.root_pair + g, left_pair=alone.left_pair + g)
        assert as_bytes(together[g]) == as_bytes(alone), g
    assert together[3].left_pair.size > 0  # the tangency leaves pieces: order matters there


# the plain spellings, as the helpers were written before round 18
def plain_fat_line_apart(a, b, slack):
    chord = b[:, -1] - b[:, 0]
    length = np.hypot(chord[:, 0], chord[:, 1])
    ok = length > 0
    normal = np.stack([-chord[:, 1], chord[:, 0]], axis=1) / np.where(ok, length, 1.0)[:, None]
    base = b[:, :1]
    db = np.einsum("kid,kd->ki", b - base, normal)
    da = np.einsum("kid,kd->ki", a - base, normal)
    apart = (da.min(axis=1) > db.max(axis=1) + slack) | (da.max(axis=1) < db.min(axis=1) - slack)
    return apart & ok


def plain_thickness(pieces):
    chord = pieces[:, -1] - pieces[:, 0]
    length = np.linalg.norm(chord, axis=1)
    unit = chord / np.where(length > 0, length, 1.0)[:, None]
    rel = pieces - pieces[:, :1]
    along = np.einsum("kid,kd->ki", rel, unit)
    off = np.linalg.norm(rel - along[..., None] * unit[:, None], axis=2).max(axis=1)
    return np.where(length > 0, off, np.inf)


def plain_runs_forward(pieces):
    chord = pieces[:, -1] - pieces[:, 0]
    along = np.einsum("kid,kd->ki", np.diff(pieces, axis=1), chord)
    return np.all(along >= 0, axis=1) & np.any(chord != 0, axis=1)


def plain_cones(pieces, slack):
    h = np.diff(pieces, axis=1)
    norm = np.linalg.norm(h, axis=2)
    good = np.all(norm > 2 * sub.BLUR * slack[:, None], axis=1)
    unit = h / np.where(norm > 0, norm, 1.0)[..., None]
    axis = unit.sum(axis=1)
    axis_norm = np.linalg.norm(axis, axis=1)
    good &= axis_norm > 0
    axis = axis / np.where(axis_norm > 0, axis_norm, 1.0)[:, None]
    cos = np.einsum("kid,kd->ki", unit, axis).min(axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        blur = np.arcsin(np.clip(2 * sub.BLUR * slack[:, None] / norm, 0.0, 1.0)).max(axis=1)
    half = np.where(good & (cos > 0), np.arccos(np.clip(cos, -1.0, 1.0)) + blur, np.pi)
    return axis, half


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("degree", [1, 2, 3, 6])
def test_helpers_are_bit_identical_to_their_plain_spelling(degree, dim):
    rng = np.random.default_rng(10 * degree + dim)
    pieces = rng.normal(size=(40, degree + 1, dim)) * 10.0 ** rng.uniform(-9, 3, size=(40, 1, 1))
    pieces[:4, -1] = pieces[:4, 0]  # closed: no chord
    pieces[4:8] = pieces[4:8, :1]  # a point: every hodograph point zero
    pieces[8:12] = np.linspace(0, 1, degree + 1)[None, :, None] * pieces[8:12, -1:]  # straight
    others = rng.normal(size=(40, degree + 1, dim))
    slack = np.where(rng.uniform(size=40) < 0.5, 0.0, 1e-12)
    with np.errstate(all="ignore"):
        for new, old in [
            (sub._thickness(pieces), plain_thickness(pieces)),
            (sub._runs_forward(pieces), plain_runs_forward(pieces)),
            (sub._cones(pieces, slack)[0], plain_cones(pieces, slack)[0]),
            (sub._cones(pieces, slack)[1], plain_cones(pieces, slack)[1]),
        ]:
            assert new.tobytes() == old.tobytes()
        if dim == 2:
            new = sub._fat_line_apart(others, pieces, slack)
            assert new.tobytes() == plain_fat_line_apart(others, pieces, slack).tobytes()
            assert new.any() and not new.all()  # both outcomes occur
