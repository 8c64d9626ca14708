"""Acceptance audit of issues #21 (CAD-ready curves) and #23 (parity with the `bezier`
package: every algorithm for every family), round 21, on the curve classes added after
those issues were resolved: what a new user tried and did not get.

- #23 asks `segment(t0, t1)` (and the peer's subdivide and hodograph) "for every family, by
  way of the exact Bézier form": the shape-parameter families (built-in, a user's, several
  parameters, one per index) had none, nor the trigonometric, hyperbolic and C-Bézier ones.
- the guide says every curve class takes every other in `intersect`; a CompositeCurve had
  no intersect, and a curve given one raised TypeError.
- `lambda-bezier optimal-lambda` printed a C-Bézier optimum on the end α = π of the range
  as the float 3.141592653589793.
- `to_dxf` into a missing directory ended in ezdxf's own FileNotFoundError traceback, where
  `to_step` names the file it could not write.

Every expected answer is computed here independently: the basis definition (000's eq. 1)
in Fractions, the C-Bézier space's invariance under shifts of t, hand-solved crossings, and
mpmath quadrature of the energy.
"""

from __future__ import annotations

import json
import math
import re
from fractions import Fraction as F

import mpmath
import numpy as np
import pytest

import lambda_bezier as lb
from lambda_bezier import examples
from lambda_bezier.hazmat.intersect import Intersection
from tests.conftest import family_file
from tests.exact_curves import exact_point
from tests.reference import C, bernstein_like_recursion

ARCH = [(0, 0), (1, 2), (3, 2), (4, 0)]


def _same_degree_point(rows, lam: F, t: F) -> tuple[F, ...]:
    """000's eq. (1) in Fractions: C(n,i) s^(n-i) t^i + (1 - λ)(C(n-3,i-3) s^(n-i+1) t^(i-1)
    - C(n-2,i-1) s^(n-i) t^i + C(n-3,i) s^(n-i-1) t^(i+1)), s = 1 - t, summed with the
    points (the powers only where the binomial in front is nonzero)."""
    n, s = len(rows) - 1, 1 - t
    out = [F(0)] * len(rows[0])
    for i, row in enumerate(rows):
        b = C(n, i) * s ** (n - i) * t**i
        for coeff, ps, pt in (
            (C(n - 3, i - 3), n - i + 1, i - 1),
            (-C(n - 2, i - 1), n - i, i),
            (C(n - 3, i), n - i - 1, i + 1),
        ):
            if coeff:
                b += (1 - lam) * coeff * s**ps * t**pt
        out = [o + b * x for o, x in zip(out, row, strict=True)]
    return tuple(out)


# ---------------------------------------------------------------- #23: pieces of every family
def test_segment_split_hodograph_of_a_same_degree_curve_are_exact():
    lam = F(1, 2)
    curve = lb.SameDegreeCurve(ARCH, lam=lam)
    piece = curve.segment(F(1, 4), F(3, 4))
    rows = piece.control_points()
    assert all(isinstance(x, F) for row in rows for x in row)
    # a cubic is fixed by four points: the piece at u is the curve at 1/4 + u/2, exactly
    for u in (F(0), F(1, 3), F(2, 3), F(1)):
        assert exact_point(rows, u) == _same_degree_point(ARCH, lam, F(1, 4) + u / 2)
    left, right = curve.split(F(2, 5))
    for u in (F(0), F(1, 3), F(2, 3), F(1)):
        assert exact_point(left.control_points(), u) == _same_degree_point(ARCH, lam, u * 2 / 5)
        assert exact_point(right.control_points(), u) == _same_degree_point(
            ARCH, lam, F(2, 5) + u * 3 / 5
        )
    # extrapolated, as the peer's specialize: t in [-1/2, 3/2]
    wide = curve.segment(F(-1, 2), F(3, 2), extrapolate=True)
    assert exact_point(wide.control_points(), F(1, 4)) == _same_degree_point(ARCH, lam, F(0))
    # the hodograph: p'(t) against the definition's central difference (h = 1e-6)
    hod = curve.hodograph().control_points()
    for t in (F(1, 5), F(7, 10)):
        h = F(1, 10**6)
        diff = [
            (a - b) / (2 * h)
            for a, b in zip(
                _same_degree_point(ARCH, lam, t + h),
                _same_degree_point(ARCH, lam, t - h),
                strict=True,
            )
        ]
        assert max(abs(float(a - b)) for a, b in zip(exact_point(hod, t), diff, strict=True)) < 1e-9


def test_segment_of_a_bernstein_like_curve_against_its_recursion():
    lam = 0.3
    curve = lb.BernsteinLikeCurve(ARCH, lam=lam)
    piece = curve.segment(0.2, 0.9)
    u = np.linspace(0, 1, 7)
    basis = np.array(bernstein_like_recursion(3, 0.2 + 0.7 * u, lam)).T  # (7, 4)
    np.testing.assert_allclose(piece.evaluate(u), basis @ np.array(ARCH, float), atol=1e-14)


@pytest.mark.parametrize(
    "name, make",
    [
        ("nouri_saeidian", lambda fam: fam.curve(ARCH, F(1, 2))),
        ("two_shape_cubic", lambda fam: fam.curve(ARCH, lam=F(1, 2), mu=F(-1))),
        ("q_bezier", lambda fam: fam.curve(ARCH, [F(1, 2), F(1, 3), F(1, 4)])),
    ],
)
def test_segment_of_a_users_family_curve_is_its_exact_piece(name, make):
    try:
        path = examples.path(f"{name}.toml")
    except ValueError:  # not shipped: the test data
        path = family_file(name)
    curve = make(lb.load_family(path))
    piece = curve.segment(F(1, 5), F(4, 5))
    assert all(isinstance(x, F) for row in piece.control_points() for x in row)
    u = np.linspace(0, 1, 9)
    np.testing.assert_allclose(piece.evaluate(u), curve.evaluate(0.2 + 0.6 * u), atol=1e-14)
    left, right = curve.split(F(1, 2))
    np.testing.assert_allclose(left.evaluate(u), curve.evaluate(u / 2), atol=1e-14)
    np.testing.assert_allclose(right.evaluate(u), curve.evaluate(0.5 + u / 2), atol=1e-14)


def test_segment_of_trigonometric_and_hyperbolic_curves_is_the_rational_piece():
    trig = lb.load_family(examples.path("han_trig_cubic.toml"))
    hyp = lb.load_family(family_file("hyp_cubic"))
    for curve, (a, b) in (
        (trig.curve(ARCH, lam=F(1, 2), mu=-1), (math.pi / 8, math.pi / 3)),
        (hyp.curve(ARCH, lam=F(1, 2), mu=F(1, 3)), (0.2, 0.7)),
    ):
        piece = curve.segment(a, b)
        assert isinstance(piece, lb.RationalBezierCurve)
        np.testing.assert_allclose(piece.evaluate(0.0), curve.evaluate(a), atol=1e-14)
        np.testing.assert_allclose(piece.evaluate(1.0), curve.evaluate(b), atol=1e-14)
        # every point of the piece is on the curve, at a t between a and b, in order
        found = [curve.closest_point(piece.evaluate(u)) for u in np.linspace(0, 1, 9)]
        assert max(f.distance for f in found) < 1e-13
        ts = [f.t for f in found]
        assert ts == sorted(ts) and a - 1e-12 <= ts[0] and ts[-1] <= b + 1e-12
        with pytest.raises(ValueError, match="t1 < t2"):
            curve.segment(b, a)


def test_segment_of_a_c_bezier_curve_is_the_shifted_curve_of_its_family():
    fam = lb.load_family(examples.path("c_bezier_cubic.toml"))
    curve = fam.curve([[0, 0], [1, 2], [3, 2.5], [4, 0.5]], alpha=2.0)
    piece = curve.segment(0.4, 1.5)
    # the space span{1, t, sin t, cos t} is invariant under shifts of t: the piece is the
    # family's curve with alpha = 1.1 and piece(x) = curve(0.4 + x)
    assert type(piece) is type(curve) and piece.domain == pytest.approx((0.0, 1.1), abs=1e-15)
    x = np.linspace(0, 1.1, 9)
    np.testing.assert_allclose(piece.evaluate(x), curve.evaluate(0.4 + x), atol=1e-13)
    whole = curve.segment(0.0, 2.0)
    np.testing.assert_allclose(whole.evaluate(x), curve.evaluate(x), atol=1e-13)
    # the family written on u in [0, 1]: the piece's own u runs over [0, 1] too
    unit = lb.load_family(family_file("c_bezier_cubic_unit"))
    curve = unit.curve([[0, 0], [1, 2], [3, 2.5], [4, 0.5]], alpha=2.0)
    piece = curve.segment(0.2, 0.7)
    assert piece.alpha == pytest.approx(1.0, abs=1e-15) and piece.domain == (0.0, 1.0)
    u = np.linspace(0, 1, 9)
    np.testing.assert_allclose(piece.evaluate(u), curve.evaluate(0.2 + 0.5 * u), atol=1e-13)


# ---------------------------------------------------------------- composites take intersect
def test_a_composite_intersects_any_curve_and_a_joint_is_reported_once():
    first = lb.BezierCurve(ARCH)
    comp = lb.CompositeCurve([first]).join("C1", 3, rest=[(9, 1), (10, 0)])
    line = lb.BezierCurve([(0, F(1, 2)), (10, F(1, 2))])
    # the first segment's y is 6 s (1 - s) = 1/2 at s = (1 ∓ sqrt(2/3)) / 2, x = ...; the
    # second's y = 3 t (1 - t)(3 t - 2) stays below 1/2 (its maximum, at t ≈ 0.85, is 0.21)
    want_s = [(1 - math.sqrt(2 / 3)) / 2, (1 + math.sqrt(2 / 3)) / 2]
    hits = comp.intersect(line)
    assert [h.kind for h in hits] == ["transversal"] * 2
    np.testing.assert_allclose([h.s for h in hits], want_s, atol=1e-15)
    x = [3 * s * (1 - s) ** 2 + 9 * s**2 * (1 - s) + 4 * s**3 for s in want_s]
    np.testing.assert_allclose([h.t for h in hits], [v / 10 for v in x], atol=1e-15)
    # asked the other way round (any class), and through intersect_many: s and t swapped
    swapped = [Intersection(h.t, h.s, h.kind) for h in hits]
    assert line.intersect(comp) == swapped
    assert lb.intersect_many([line], [comp]) == [swapped]
    # a rational curve (a quarter circle of radius 4) on either side, meeting the composite
    # where both curves are
    arc = lb.RationalBezierCurve([(4, 0), (4, 4), (0, 4)], [1, 1, 2])
    round_hits = comp.intersect(arc)
    assert round_hits and arc.intersect(comp) == [
        Intersection(h.t, h.s, h.kind) for h in round_hits
    ]
    for h in round_hits:
        np.testing.assert_allclose(comp.evaluate(h.s), arc.evaluate(h.t), atol=1e-12)
        assert abs(np.hypot(*comp.evaluate(h.s)) - 4) < 1e-12
    # a vertical line through the joint u = 1 at (1, 1) of a folded polyline: one hit, there
    bent = lb.CompositeCurve([lb.BezierCurve([(0, 0), (1, 1)]), lb.BezierCurve([(1, 1), (2, 0)])])
    assert bent.intersect(lb.BezierCurve([(1, 0), (1, 2)])) == [
        Intersection(1.0, 0.5, "transversal")
    ]
    # two composites meeting at both joints: once, in both composites' u
    down = lb.CompositeCurve([lb.BezierCurve([(1, 2), (1, 1)]), lb.BezierCurve([(1, 1), (1, 0)])])
    assert bent.intersect(down) == [Intersection(1.0, 1.0, "transversal")]


def test_a_composite_crosses_itself_and_locates_a_point_in_its_u():
    def polyline(*corners):
        return lb.CompositeCurve(
            [lb.BezierCurve([a, b]) for a, b in zip(corners, corners[1:], strict=False)]
        )

    # a Z: the first and last segments cross at (1, 1), halfway along each; the joints
    # (where a segment ends and the next begins) are no crossings
    zed = polyline((0, 0), (2, 2), (2, 0), (0, 2))
    assert zed.self_intersections() == [Intersection(0.5, 2.5, "transversal")]
    with pytest.raises(ValueError, match="several parameters"):
        zed.locate((1, 1))
    assert zed.locate((2, 1)) == 1.5 and zed.locate((2, 2)) == 1.0 and zed.locate((3, 3)) is None
    # a closed square: its start meets its end, as a closed curve's (0, 1)
    square = polyline((0, 0), (1, 0), (1, 1), (0, 1), (0, 0))
    assert square.self_intersections() == [Intersection(0.0, 4.0, "transversal")]
    # a C1 composite (a smooth joint, tangent there) with a loop in its first segment
    loop = lb.BezierCurve([(0, 0), (3, 3), (-3, 3), (1, -1)])
    comp = lb.CompositeCurve([loop]).join("C1", 3, rest=[(5, 0), (6, 0)])
    assert comp.self_intersections() == loop.self_intersections()


def test_a_composite_of_trigonometric_segments_reports_its_own_u():
    trig = lb.load_family(examples.path("han_trig_cubic.toml"))
    first = trig.curve(ARCH, lam=F(1, 2), mu=-1)
    comp = lb.CompositeCurve(
        [first, lb.join(first, "C1", 3, lam=F(1, 2), mu=-1, rest=[(9, 1), (10, 0)])]
    )
    line = lb.BezierCurve([(0, F(1, 2)), (10, F(1, 2))])
    hits = comp.intersect(line)
    pieces = [
        (start + h.s, h.t)
        for start, seg in zip((0.0, math.pi / 2), comp.segments, strict=True)
        for h in seg.intersect(line)
    ]
    got = [x for h in hits for x in (h.s, h.t)]  # flat: approx takes no nested tuples
    assert got == pytest.approx([x for pair in pieces for x in pair], abs=1e-15)
    for h in hits:  # each hit is where the composite meets the line
        np.testing.assert_allclose(comp.evaluate(h.s), line.evaluate(h.t), atol=1e-13)
    # the first segment against the composite: the stretch they share, by its end pairs (the
    # second segment's start, the same point, once)
    half = math.pi / 2
    assert first.intersect(comp) == [
        Intersection(0.0, 0.0, "coincident"),
        Intersection(half, half, "coincident"),
    ]


# ---------------------------------------------------------------- the CLI's exact C-Bézier end
def _energy_1(curve, alpha: float) -> float:
    """E_1 = ∫_0^α |p'(t)|² dt by mpmath quadrature (the curve's own derivative)."""
    return float(mpmath.quad(lambda t: float(np.sum(curve.derivative(float(t)) ** 2)), [0, alpha]))


def test_cli_prints_a_c_bezier_optimum_at_pi_as_pi(capsys, monkeypatch):
    from lambda_bezier import cli, energy

    # the certified search (~1.5 s of CPU) once for the two outputs
    search, found = energy.optimal_parameters, []

    def once(*args, **kwargs):
        if not found:
            found.append(search(*args, **kwargs))
        return found[0]

    monkeypatch.setattr(energy, "optimal_parameters", once)

    path = str(examples.path("c_bezier_cubic.toml"))
    points = ["0,0", "1,2", "3,2", "4,0"]
    assert cli.main(["optimal-lambda", "--family", path, "--energy", "1", "--json", *points]) == 0
    report = json.loads(capsys.readouterr().out)
    assert report["parameters"] == {"alpha": "pi"}
    assert report["parameters_decimal"] == {"alpha": math.pi}
    assert cli.main(["optimal-lambda", "--family", path, "--energy", "1", *points]) == 0
    assert "optimal alpha   pi  ≈ 3.141592653589793" in capsys.readouterr().out
    # independently: E_1 falls towards the end alpha = pi of the range (0, pi]
    fam = lb.load_family(path)
    energies = [_energy_1(fam.curve(ARCH, alpha=a), a) for a in (1.0, 2.0, 3.0, math.pi)]
    assert energies == sorted(energies, reverse=True)
    assert energies[-1] == pytest.approx(report["energy_decimal"], rel=1e-12)


# ---------------------------------------------------------------- a file that cannot be written
def test_dxf_into_a_missing_directory_names_the_file(tmp_path):
    pytest.importorskip("ezdxf")
    from lambda_bezier import export

    target = tmp_path / "missing" / "curve.dxf"
    with pytest.raises(OSError, match="could not write the DXF file .*curve.dxf"):
        export.to_dxf(lb.BezierCurve(ARCH), target)


@pytest.mark.parametrize("dim", [1, 4])
def test_step_and_dxf_refuse_a_curve_outside_the_plane_and_space(tmp_path, dim):
    # a 4D curve was written to STEP without its fourth coordinate; a 1D one, and DXF of
    # either, ended in an unpacking error or ezdxf's "invalid argument count"
    pytest.importorskip("OCP")
    pytest.importorskip("ezdxf")
    from lambda_bezier import export

    curve = lb.BezierCurve([[i + j for j in range(dim)] for i in range(4)])
    for write, suffix, what in ((export.to_step, "step", "STEP"), (export.to_dxf, "dxf", "DXF")):
        target = tmp_path / f"curve.{suffix}"
        with pytest.raises(ValueError, match=f"a {what} .* this curve is {dim}D"):
            write(curve, target)
        assert not target.exists()


def test_cli_output_into_a_closed_pipe_ends_without_a_traceback():
    # `lambda-bezier optimal-lambda ... | head -1` printed a BrokenPipeError traceback: here
    # the reader is gone before the command writes
    import os
    import subprocess
    import sys

    read_end, write_end = os.pipe()
    os.close(read_end)
    try:
        run = subprocess.run(
            [sys.executable, "-m", "lambda_bezier", "optimal-lambda", "0,0", "1,2", "3,2", "4,0"],
            stdout=write_end,
            stderr=subprocess.PIPE,
            text=True,
            check=False,
        )
    finally:
        os.close(write_end)
    assert run.returncode == 1 and "Traceback" not in run.stderr, run.stderr


@pytest.mark.parametrize(
    "bad, says",
    [
        (True, "got the boolean True"),  # was taken as a tolerance of 1
        ("a", "got the text 'a'"),  # was "could not convert string to float: 'a'"
        (1j, "got the complex number 1j"),
        (-1, "positive distance, got -1"),  # a mixed curve's message said -0.5, its half
    ],
)
def test_export_tolerance_is_checked_as_given(bad, says):
    from lambda_bezier import export

    mixed = lb.load_family(family_file("at_cubic")).curve(ARCH, lam=F(1, 2))
    for curve in (mixed, lb.BezierCurve([(0, 0), (1, 2), (2, 0), (3, 1), (4, 0)])):
        for write in (export.to_svg, export.to_bspline):
            with pytest.raises(ValueError, match=f"tolerance must be a .*{re.escape(says)}"):
                write(curve, tolerance=bad)


@pytest.mark.parametrize("exponent", [600, -600, 1000, -1000])
def test_arc_length_of_curves_without_a_polynomial_form_at_huge_and_tiny_sizes(exponent):
    # the numeric route (C-Bézier, mixed and hyperbolic curves) squared the speed past the
    # float range: 2^600 never returned (inf speeds halved to depth 40 on every branch),
    # 2^-600 gave the length 0. Scaling by a power of two scales the length exactly.
    scale = 2.0**exponent
    made = [
        (lb.load_family(examples.path("c_bezier_cubic.toml")), {"alpha": 2.0}),
        (lb.load_family(family_file("at_cubic")), {"lam": F(1, 2)}),
        (lb.load_family(family_file("hyp_cubic")), {"lam": F(1, 2), "mu": F(1, 3)}),
    ]
    for fam, params in made:
        unit = fam.curve(ARCH, **params)
        lo, hi = unit.domain
        want = float(
            mpmath.quad(
                lambda t, c=unit: float(np.linalg.norm(c.derivative(float(t)))),
                np.linspace(lo, hi, 9).tolist(),
            )
        )
        big = fam.curve([(x * scale, y * scale) for x, y in ARCH], **params)
        assert big.arc_length() / scale == pytest.approx(want, rel=1e-12)
        half = big.parameter_at_length(big.arc_length() / 2)
        assert big.arc_length(lo, half) / scale == pytest.approx(want / 2, rel=1e-12)


@pytest.mark.parametrize("exponent", [600, -600])
def test_svg_of_a_rational_curve_at_huge_and_tiny_sizes_is_the_scaled_path(exponent):
    # the cubics' error bound squared coordinates near 2^600 past the float range: "cannot
    # approximate within tolerance=4.1e+174 (too small)" for a tolerance 1e-6 of the size
    from lambda_bezier import export

    scale = 2.0**exponent
    weights = [1, 2, 3, 1]
    small = export.to_svg(lb.RationalBezierCurve(ARCH, weights), tolerance=1e-6)
    big = export.to_svg(
        lb.RationalBezierCurve([(x * scale, y * scale) for x, y in ARCH], weights),
        tolerance=1e-6 * scale,
    )

    def numbers(svg):
        return [float(v) for v in re.findall(r"-?\d[\d.e+-]*", re.search(r' d="([^"]+)"', svg)[1])]

    assert [v * scale for v in numbers(small)] == numbers(big)


@pytest.mark.parametrize("exponent", [-600, -40])
def test_a_small_curve_is_joined_not_refused_as_degenerate(exponent):
    # the degenerate-end test compared the end tangent with 1e-12 of max(1, size): every
    # curve below size 1e-12 "had no tangent to continue". The C1 join of the arch is
    # P_0 = (4, 0), P_1 = 2 P_3 - P_2 = (5, -2), scaled
    scale = 2.0**exponent
    small = [(x * scale, y * scale) for x, y in ARCH]
    rest = [(9 * scale, scale), (10 * scale, 0.0)]
    for curve, kw in (
        (lb.BezierCurve(small), {}),
        (lb.SameDegreeCurve(small, lam=0.5), {"lam": 0.5}),
    ):
        nxt = lb.join(curve, "C1", 3, rest=rest, **kw)
        assert nxt.control_points()[:2] == ((4 * scale, 0.0), (5 * scale, -2 * scale))
    comp = lb.CompositeCurve([lb.BezierCurve(small)]).join("C1", 3, rest=rest)
    assert comp.report()[0].holds("C1")
