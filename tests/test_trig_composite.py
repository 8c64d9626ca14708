"""Composites with segments of trigonometric, hyperbolic and mixed families (issue #30):
each segment keeps its own domain of t, the composite's u runs over the segments' domains end
to end, derivatives in u are the segments' own t-derivatives. Checked against direct
evaluation of the segments, finite differences (mpmath) and the joints lb.join builds."""

from __future__ import annotations

import math
from fractions import Fraction as F
from pathlib import Path

import numpy as np
import pytest

import lambda_bezier as lb
from lambda_bezier import export
from lambda_bezier.atom_family import AtomCurve

DATA = Path(__file__).parent / "data" / "families"
PTS = [(0, 0), (1, 3), (3, -1), (4, 1)]


@pytest.fixture(scope="module")
def fams():
    return {
        name: lb.load_family(DATA / f"{name}.toml")
        for name in ("han_trig_cubic", "hyp_cubic", "at_cubic")
    }


def _chain(fams):
    """trig --C2--> polynomial --C1--> hyperbolic --G1--> mixed --C1--> polynomial."""
    trig = fams["han_trig_cubic"].curve(PTS, lam=F(1, 2), mu=-1)
    comp = lb.CompositeCurve([trig])
    comp = comp.join("C2", 4, lam=F(1, 3), family="same_degree", rest=[(8, 0), (9, 2)])
    comp = comp.join(
        "C1", 3, family=fams["hyp_cubic"], lam=F(1, 5), mu=F(1, 2), rest=[(12, 1), (13, 3)]
    )
    comp = comp.join(
        "G1", 3, alpha=F(3, 2), family=fams["at_cubic"], lam=F(1, 5), rest=[(15, 0), (16, 2)]
    )
    return comp.join("C1", 3, family="bezier", rest=[(18, 1), (19, 0)])


def test_parametrisation_and_direct_evaluation(fams):
    comp = _chain(fams)
    assert [isinstance(s, AtomCurve) for s in comp.segments] == [True, False, True, True, False]
    lengths = [math.pi / 2, 1, 1, math.pi / 2, 1]
    assert comp.breaks == pytest.approx(np.concatenate([[0], np.cumsum(lengths)]), abs=1e-15)
    assert comp.domain == (0.0, comp.breaks[-1])
    rng = np.random.default_rng(3)
    for i, seg in enumerate(comp.segments):
        lo, hi = seg.domain if isinstance(seg, AtomCurve) else (0.0, 1.0)
        t = np.sort(rng.uniform(lo, hi, 7))
        u = comp.breaks[i] + (t - lo)
        for k in range(4):
            got = comp.derivative(u, k)
            want = seg.derivative(t, k)
            assert np.allclose(got, want, rtol=1e-12, atol=1e-12 * (1 + np.abs(want).max())), (i, k)
    # scalar u, both ends of the domain
    assert np.allclose(comp.evaluate(0.0), comp.segments[0].evaluate(0.0))
    assert np.allclose(comp.evaluate(comp.domain[1]), comp.segments[-1].evaluate(1.0))
    with pytest.raises(ValueError, match="outside"):
        comp.evaluate(comp.domain[1] + 1e-6)
    assert comp.evaluate(comp.domain[1] + 0.5, extrapolate=True).shape == (2,)


def test_derivatives_in_u_against_finite_differences(fams):
    comp = _chain(fams)
    h = 1e-4
    for u0 in (0.3, 2.1, 3.0, 4.2, 5.9, comp.domain[1] - 0.2):
        p = comp.evaluate(np.array([u0 - h, u0, u0 + h]))
        first, second = (p[2] - p[0]) / (2 * h), (p[2] - 2 * p[1] + p[0]) / h**2
        for k, fd in ((1, first), (2, second)):
            got = comp.derivative(u0, k)
            assert np.allclose(got, fd, rtol=1e-5, atol=1e-5 * (1 + np.abs(got).max())), (u0, k)


def test_report_at_joints(fams):
    comp = _chain(fams)
    rep = comp.report()
    assert [r.kept for r in rep] == [True] * 4
    assert {"C0", "C1", "C2", "G1", "G2"} <= rep[0].achieved  # C2 implies G2
    assert {"C1", "G1"} <= rep[1].achieved and "C2" not in rep[1].achieved
    assert "G1" in rep[2].achieved and "C1" not in rep[2].achieved
    assert rep[2].speed_ratio == pytest.approx(1.5, rel=1e-12)
    assert "C1" in rep[3].achieved
    # a trigonometric segment with a C1 joint in its own t is not C1 in a rescaled parameter:
    # the report measures in u = own t, so changing a segment's points breaks it visibly
    bad = lb.CompositeCurve([comp.segments[0], lb.BezierCurve([(4, 1), (5, 5), (6, 0)])])
    assert "G1" not in bad.report()[0].achieved


def test_resolve_through_atom_segments(fams):
    comp = _chain(fams)
    moved = comp.with_lambda(1, F(-1, 2))  # the same_degree segment; re-solves joints 0..3
    assert all(r.kept for r in moved.report())
    assert moved.segments[2].parameter_values == comp.segments[2].parameter_values
    with pytest.raises(ValueError, match="segment 0 is a curve of the han_trig_cubic family"):
        comp.with_lambda(0, 0)


def test_geometry_against_the_segments(fams):
    comp = _chain(fams)
    total = comp.arc_length()
    assert total == pytest.approx(math.fsum(s.arc_length() for s in comp.segments), rel=1e-12)
    u = np.linspace(0, comp.domain[1], 4001)
    speed = np.linalg.norm(comp.derivative(u, 1), axis=1)
    fine = 0
    for i in range(len(comp.segments)):  # Simpson per segment (the speed is smooth inside)
        # the right end just inside: u = breaks[i + 1] belongs to the next segment (joint 2
        # is G1 with alpha = 3/2, the speed jumps there)
        uu = np.linspace(comp.breaks[i], np.nextafter(comp.breaks[i + 1], 0), 2001)
        sp = np.linalg.norm(comp.derivative(uu, 1), axis=1)
        fine += (uu[1] - uu[0]) / 3 * (sp[0] + sp[-1] + 4 * sp[1:-1:2].sum() + 2 * sp[2:-1:2].sum())
    assert total == pytest.approx(fine, rel=1e-9)
    assert speed.min() > 0
    half = comp.parameter_at_length(total / 2)
    assert comp.arc_length(0, half) == pytest.approx(total / 2, rel=1e-10)
    assert comp.arc_length(1.0, 4.0) == pytest.approx(
        comp.arc_length(0, 4.0) - comp.arc_length(0, 1.0), rel=1e-10
    )
    lo, hi = comp.bounding_box()
    pts = comp.evaluate(u)
    assert (pts >= lo - 1e-9).all() and (pts <= hi + 1e-9).all()
    assert np.allclose(lo, pts.min(axis=0), atol=1e-6) and np.allclose(
        hi, pts.max(axis=0), atol=1e-6
    )
    q = comp.evaluate(3.7) + np.array([0.0, 1e-3])
    found = comp.closest_point(q)
    assert np.allclose(comp.evaluate(found.t), found.point, atol=1e-9)
    assert found.distance <= np.linalg.norm(pts - q, axis=1).min() + 1e-12
    batch = comp.closest_point(np.stack([q, comp.evaluate(0.5)]))
    assert batch.t.shape == (2,) and batch.t[1] == pytest.approx(0.5, abs=1e-7)


def test_json_round_trip_and_export(fams, tmp_path):
    comp = _chain(fams)
    text = export.to_json(comp)
    back = export.from_json(text, family=list(fams.values()))
    assert isinstance(back.segments[0], AtomCurve) and back.segments[0].is_exact
    u = np.linspace(0, comp.domain[1], 50)
    assert np.array_equal(back.evaluate(u), comp.evaluate(u))
    assert [j.continuity for j in back.joints] == ["C2", "C1", "G1", "C1"]
    spline = export.to_bspline(comp)
    # the spline runs over the polynomial pieces; compare the traced point sets
    knots = spline.knots
    s = np.linspace(float(knots[0]), float(knots[-1]), 3001)
    traced = np.array([np.asarray(spline.point(x), float) for x in s])
    exact = comp.evaluate(np.linspace(0, comp.domain[1], 3001))
    far = max(np.min(np.linalg.norm(traced - p, axis=1)) for p in exact[::30])
    assert far < 5e-2  # the grid of the spline's own parameter, not the same points
    ends = [np.asarray(spline.point(float(knots[-1])), float), comp.evaluate(comp.domain[1])]
    assert np.allclose(*ends, atol=1e-12)


def test_refusals(fams):
    with pytest.raises(ValueError, match="not a lambda_bezier curve"):
        lb.CompositeCurve([object()])
    trig3 = fams["han_trig_cubic"].curve([(0, 0, 0), (1, 1, 1), (2, 0, 1), (3, 1, 0)], lam=0, mu=0)
    with pytest.raises(ValueError, match="dimension"):
        lb.CompositeCurve([fams["han_trig_cubic"].curve(PTS, lam=0, mu=0), trig3])
