"""Issue #29 "Then fast": intersect_many's batch (every pair of float Bézier curves of one
dimension in one compiled call) and Curve.intersect's way round the Prepared form (float
Bézier points handed to the kernels as they are) give the answers of the reference path,
hazmat.intersect.intersect on the curves' Prepared forms, bit for bit, on both engines
(conftest.intersect_engine); pairs the batch cannot take (exact input, sizes that need
scaling, other classes, points) go the reference way with the same answers and errors."""

from __future__ import annotations

import json
import pickle
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest

import lambda_bezier as lb
from lambda_bezier.hazmat import intersect as engine
from lambda_bezier.hazmat import intersect_pairs

pytestmark = pytest.mark.usefixtures("intersect_engine")

DATA = Path(__file__).parent / "data" / "bezier"


def _fixture_pairs() -> list[tuple[np.ndarray, np.ndarray]]:
    curves = json.loads((DATA / "curves.json").read_text())
    cases = json.loads((DATA / "curve_intersections.json").read_text())

    def number(v) -> float:
        if isinstance(v, int):
            return float(v)
        if "x" in v:
            return float.fromhex(v)
        return float(Fraction(v))

    def nodes(curve_id: str) -> np.ndarray:
        cols = curves[curve_id]["control_points"]
        return np.array([[number(v) for v in row] for row in cols]).T.copy()

    return [(nodes(c["curve1"]), nodes(c["curve2"])) for c in cases]


def _random_pairs(count: int, seed: int) -> list[tuple[np.ndarray, np.ndarray]]:
    rng = np.random.default_rng(seed)
    out = []
    for k in range(count):
        dim = 3 if k % 7 == 6 else 2
        a = rng.uniform(-1, 1, (int(rng.integers(2, 6)), dim))
        b = rng.uniform(-1, 1, (int(rng.integers(2, 6)), dim))
        if k % 5 == 4:  # the reflection of a in its tangent line at the middle: a tangency
            mid = lb.BezierCurve(a).evaluate(0.5)
            tangent = lb.BezierCurve(a).derivative(0.5)
            u = tangent / np.linalg.norm(tangent)
            rel = a - mid
            b = mid + 2 * np.outer(rel @ u, u) - rel if dim == 2 else b
        out.append((a, b))
    return out


def _bits(hits) -> list[tuple[str, str, str]]:
    return [(float(h.s).hex(), float(h.t).hex(), h.kind) for h in hits]


def _reference(a: lb.BezierCurve, b: lb.BezierCurve) -> list[tuple[str, str, str]]:
    """The path every curve took before: the Prepared forms through hazmat.intersect."""
    return _bits(engine.intersect(a._prepared, b._prepared))


PAIRS = _fixture_pairs() + _random_pairs(60, 2911)


def test_intersect_without_prepared_is_the_reference_bit_for_bit():
    for p, q in PAIRS:
        got = lb.BezierCurve(p).intersect(lb.BezierCurve(q))
        assert _bits(got) == _reference(lb.BezierCurve(p), lb.BezierCurve(q))


def test_intersect_many_pairs_is_intersect_bit_for_bit():
    a = [lb.BezierCurve(p) for p, _ in PAIRS]
    b = [lb.BezierCurve(q) for _, q in PAIRS]
    got = lb.intersect_many(a, b)
    assert [_bits(h) for h in got] == [_reference(x, y) for x, y in zip(a, b, strict=True)]


def test_intersect_many_all_is_intersect_bit_for_bit():
    # a curve repeated (one slot in the batch) and one given twice; 2-d and 3-d pairs in one
    # batch (one call each) are the pairs test's
    picks = [(p, q) for p, q in PAIRS[:8] + PAIRS[-10:] if p.shape[1] == q.shape[1] == 2]
    a = [lb.BezierCurve(p) for p, _ in picks] + [lb.BezierCurve(picks[0][0])]
    b = [lb.BezierCurve(q) for _, q in picks[::3]] + [lb.BezierCurve(picks[0][0])]
    a.append(b[0])
    got = lb.intersect_many(a, b, mode="all")
    for i, x in enumerate(a):
        for j, y in enumerate(b):
            assert _bits(got[i][j]) == _reference(x, y)


def test_the_batch_is_one_compiled_call(intersect_engine, monkeypatch):
    if intersect_engine != "numba":
        assert not intersect_pairs.in_use()
        return
    kernel = intersect_pairs._compiled()
    calls = []
    real = kernel.pairs

    def counted(*args):
        calls.append(len(args[2]))
        return real(*args)

    monkeypatch.setattr(kernel, "pairs", counted)
    a = [lb.BezierCurve(p) for p, _ in PAIRS[:51]]
    b = [lb.BezierCurve(q) for _, q in PAIRS[:51]]
    lb.intersect_many(a, b)
    assert calls == [51]


def test_pairs_the_batch_cannot_take_go_the_reference_way():
    arch = np.array([[0.0, 0.0], [1.0, 2.0], [2.0, 0.0]])
    line = np.array([[0.0, 0.5], [2.0, 0.5]])
    on_line = (np.array([[0.0, 0.0], [2.0, 0.0]]), np.array([[1.0, 0.0], [3.0, 0.0]]))
    firsts = [
        lb.BezierCurve(arch),
        lb.BezierCurve([[Fraction(0), Fraction(0)], [Fraction(1), Fraction(2)], [2, 0]]),
        lb.BezierCurve(arch * 2.0**300),  # beyond the ordinary size: normalised first
        lb.BezierCurve(arch * 2.0**-300),
        lb.BezierCurve(on_line[0]),  # one line: the compiled careful path declines
        pickle.loads(pickle.dumps(lb.BezierCurve(arch))),  # writeable points
        lb.BezierCurve(np.asfortranarray(np.vstack([arch] * 11))),  # past the short way
    ]
    seconds = [
        lb.BezierCurve(line),
        lb.BezierCurve(line),
        lb.BezierCurve(line * 2.0**300),
        lb.BezierCurve(line * 2.0**-300),
        lb.BezierCurve(on_line[1]),
        lb.BezierCurve(line),
        lb.BezierCurve(line),
    ]
    got = lb.intersect_many(firsts, seconds)
    for x, y, hits in zip(firsts, seconds, got, strict=True):
        assert _bits(hits) == _reference(x, y) == _bits(x.intersect(y))
    assert [h.kind for h in got[4]] == ["coincident", "coincident"]


def test_the_same_errors_in_the_batch():
    point = lb.BezierCurve(np.array([[1.0, 1.0], [1.0, 1.0]]))
    line = lb.BezierCurve(np.array([[0.0, 0.0], [2.0, 2.0]]))
    with pytest.raises(ValueError, match="single point") as one:
        point.intersect(line)
    with pytest.raises(ValueError, match="single point") as many:
        lb.intersect_many([line, point], [line, line])
    assert str(one.value) == str(many.value)
    flat = lb.BezierCurve(np.array([[0.0, 0.0, 0.0], [1.0, 1.0, 1.0]]))
    with pytest.raises(ValueError, match="dimensions 2 and 3"):
        lb.intersect_many([line], [flat])
