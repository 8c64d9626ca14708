"""Acceptance of issue #29's "Correct first" list, each case with its exact answer (sympy-free:
Fractions, mpmath at 50 digits), on the families that can draw the same curve, and hypothesis
over the same shape (a crossing pair about 1e-3 apart) on every built-in family."""

from __future__ import annotations

from fractions import Fraction as F
from itertools import pairwise
from math import comb

import mpmath as mp
import numpy as np
import pytest
from hypothesis import example, given
from hypothesis import strategies as st

import lambda_bezier as lb
from lambda_bezier.conversion import from_bezier

# the same polynomial curve drawn in each family that spans it (bernstein_like of degree n
# lives in degree n + 1 but does not span degree n: the hypothesis test below covers it)
SPANNING = [("bezier", None), ("same_degree", F(1, 2)), ("same_degree", F(-1))]


def _in_family(bz: lb.BezierCurve, family: str, lam: F | None) -> lb.Curve:
    if family == "bezier":
        return bz
    return from_bezier(lb.FAMILIES[family], bz, lam)


def _power_to_bezier(coeffs: list[tuple[F, F]]) -> lb.BezierCurve:
    """The degree-n Bézier curve of Σ a_k s^k (b_j = Σ_k C(j,k)/C(n,k) a_k), exactly."""
    n = len(coeffs) - 1
    pts = [
        tuple(sum(F(comb(j, k), comb(n, k)) * coeffs[k][c] for k in range(j + 1)) for c in range(2))
        for j in range(n + 1)
    ]
    return lb.BezierCurve(pts)


def _polymul(a: list[F], b: list[F]) -> list[F]:
    out = [F(0)] * (len(a) + len(b) - 1)
    for i, x in enumerate(a):
        for j, y in enumerate(b):
            out[i + j] += x * y
    return out


def _compose(p: list[F], inner: list[F]) -> list[F]:
    """p(inner(s)) as power coefficients."""
    out, power = [F(0)], [F(1)]
    for c in p:
        out = [
            (out[i] if i < len(out) else 0) + (c * power[i] if i < len(power) else 0)
            for i in range(max(len(out), len(power)))
        ]
        power = _polymul(power, inner)
    return out


def _assert_hits(got, want, tol=1e-9):
    assert len(got) == len(want), ([(g.s, g.t, g.kind) for g in got], want)
    for g, (s, t) in zip(got, want, strict=True):
        assert abs(g.s - s) < tol and abs(g.t - t) < tol, (g, s, t)


@pytest.mark.parametrize(("family", "lam"), SPANNING)
def test_parabola_and_line_cross_twice_1e3_apart(family, lam):
    par = lb.BezierCurve([(-1, F(121, 100)), (0, F(-99, 100)), (1, F(81, 100))])
    line = lb.BezierCurve([(-1, F(1, 10**6)), (1, F(1, 10**6))])
    if family != "bezier":
        par = _in_family(par.elevate(), family, lam)  # same_degree needs degree >= 3
    # y(s) - 1e-6 = 4 s^2 - 4.4 s + 1.21 - 1e-6 = 4 (s - 0.5495)(s - 0.5505), x = 2s - 1
    _assert_hits(par.intersect(line), [(0.5495, 0.5495), (0.5505, 0.5505)], tol=1e-15)


def _chebyshev(n: int) -> list[F]:
    t = [[F(1)], [F(0), F(1)]]
    for _ in range(2, n + 1):
        a = [F(0)] + [2 * c for c in t[-1]]
        b = t[-2] + [F(0)] * (len(a) - len(t[-2]))
        t.append([x - y for x, y in zip(a, b, strict=True)])
    return t[n]


@pytest.mark.parametrize(("family", "lam"), SPANNING)
def test_chebyshev_12_against_a_line_under_its_peaks(family, lam):
    """(x, T12(x)) on x = 2s - 1 against y = 1 - 1e-6: two crossings at each of the five
    inner peaks and one near each end, at x = cos((2kπ ± acos(1 - 1e-6)) / 12)."""
    y = _compose(_chebyshev(12), [F(-1), F(2)])
    x = [F(-1), F(2)] + [F(0)] * 11
    curve = _in_family(_power_to_bezier(list(zip(x, y, strict=True))), family, lam)
    line = lb.BezierCurve([(-1, 1 - F(1, 10**6)), (1, 1 - F(1, 10**6))])
    mp.mp.dps = 50
    c = mp.acos(1 - mp.mpf(1) / 10**6)
    xs = sorted(
        {float(mp.cos((2 * k * mp.pi + sign * c) / 12)) for k in range(7) for sign in (1, -1)}
    )
    want = [((v + 1) / 2, (v + 1) / 2) for v in xs if -1 < v < 1]
    assert len(want) == 12
    _assert_hits(curve.intersect(line), want)


@pytest.mark.parametrize(
    ("ra", "rb"), [(F(1, 2), F(51, 100)), (F(3, 10), F(61, 200)), (F(7, 10), F(141, 200))]
)
@pytest.mark.parametrize(("family", "lam"), SPANNING)
def test_two_self_crossings_0_005_apart(family, lam, ra, rb):
    """(t², t (t² - a²)(t² - b²)) on t = 2s - 1 crosses itself at t = ±a and t = ±b."""
    curve = _in_family(two_self_crossings(ra, rb), family, lam)
    want = sorted([(float((1 - r) / 2), float((1 + r) / 2)) for r in (ra, rb)])
    _assert_hits(curve.self_intersections(), want)


def two_self_crossings(ra: F, rb: F) -> lb.BezierCurve:
    """The quintic (t², t (t² − a²)(t² − b²)) on t = 2s − 1, exactly: it crosses itself at
    t = ±a and t = ±b, i.e. at s = (1 ∓ a)/2 and (1 ∓ b)/2 (also the rational case of
    tests/test_acceptance_29_classes.py, under a Möbius map)."""
    t = [F(-1), F(2)]
    x = _compose([F(0), F(0), F(1)], t)
    y = _compose([F(0), ra**2 * rb**2, F(0), -(ra**2 + rb**2), F(0), F(1)], t)
    x += [F(0)] * (len(y) - len(x))
    return _power_to_bezier(list(zip(x, y, strict=True)))


def _de_casteljau(pts, t):
    while len(pts) > 1:
        pts = [
            tuple((1 - t) * a + t * b for a, b in zip(p, q, strict=True)) for p, q in pairwise(pts)
        ]
    return pts[0]


@pytest.mark.parametrize("seed", range(6))
@pytest.mark.parametrize(("family", "lam"), SPANNING)
def test_a_curve_touches_its_mirror_in_its_tangent_once(family, lam, seed):
    rng = np.random.default_rng(seed)
    pts = [(F(int(rng.integers(-9, 10)), 4), F(int(rng.integers(-9, 10)), 4)) for _ in range(4)]
    s0 = F(int(rng.integers(1, 9)), 10)
    p0 = _de_casteljau(pts, s0)
    dx, dy = _de_casteljau(
        [tuple(3 * (b - a) for a, b in zip(p, q, strict=True)) for p, q in pairwise(pts)], s0
    )
    size = dx * dx + dy * dy
    assert size
    r = ((dx * dx - dy * dy) / size, 2 * dx * dy / size, (dy * dy - dx * dx) / size)
    mirror = [
        (
            p0[0] + r[0] * (x - p0[0]) + r[1] * (y - p0[1]),
            p0[1] + r[1] * (x - p0[0]) + r[2] * (y - p0[1]),
        )
        for x, y in pts
    ]
    a = _in_family(lb.BezierCurve(pts), family, lam)
    b = _in_family(lb.BezierCurve(mirror), family, lam)
    touching = [
        h for h in a.intersect(b) if abs(h.s - float(s0)) < 1e-6 or abs(h.t - float(s0)) < 1e-6
    ]
    assert len(touching) == 1, touching
    assert touching[0].kind == "tangent"
    assert abs(touching[0].s - float(s0)) < 1e-7 and abs(touching[0].t - float(s0)) < 1e-7


@pytest.mark.parametrize("seed", range(4))
@pytest.mark.parametrize(("family", "lam"), SPANNING)
def test_a_curve_and_its_reparameterisation_are_coincident(family, lam, seed):
    """P(s) = Q(s²): the same image under a non-affine change of parameter."""
    rng = np.random.default_rng(seed)
    qp = [(F(int(rng.integers(-9, 10))), F(int(rng.integers(-9, 10)))) for _ in range(4)]
    power = [
        tuple(
            sum(comb(3, k) * comb(k, i) * (-1) ** (k - i) * qp[i][c] for i in range(k + 1))
            for c in range(2)
        )
        for k in range(4)
    ]
    p_coeffs = [power[k // 2] if k % 2 == 0 else (F(0), F(0)) for k in range(7)]
    p = _in_family(_power_to_bezier(p_coeffs), family, lam)
    q = _in_family(lb.BezierCurve(qp), family, lam)
    got = p.intersect(q)
    assert [h.kind for h in got] == ["coincident", "coincident"]
    _assert_hits(got, [(0.0, 0.0), (1.0, 1.0)], tol=1e-12)


def _power(bernstein: list[F]) -> list[F]:
    n = len(bernstein) - 1
    out = [
        sum(F(comb(n, k) * comb(k, i) * (-1) ** (k - i)) * bernstein[i] for i in range(k + 1))
        for k in range(n + 1)
    ]
    while len(out) > 1 and out[-1] == 0:
        out.pop()
    return out


def _real_roots(p: list[F], lo: float, hi: float) -> list[mp.mpf]:
    mp.mp.dps = 50
    roots = mp.polyroots(
        [mp.mpf(c.numerator) / c.denominator for c in reversed(p)], maxsteps=400, extraprec=400
    )
    return sorted(
        mp.re(r) for r in roots if abs(mp.im(r)) < mp.mpf(10) ** -25 and lo <= mp.re(r) <= hi
    )


@given(
    family=st.sampled_from(["bezier", "same_degree", "bernstein_like"]),
    lam_tenths=st.integers(-9, 9),
    heights=st.lists(st.integers(-20, 20), min_size=4, max_size=6),
)
@example(family="bernstein_like", lam_tenths=3, heights=[10, -12, -12, 10])
@example(family="same_degree", lam_tenths=-9, heights=[5, -20, 7, -3, 12])
def test_a_crossing_pair_1e3_apart_on_every_family(family, lam_tenths, heights):
    """The graph (x(s), y(s)) against the line y = min + 1e-7 through a local minimum: two
    crossings about 1e-3 apart, against mpmath's roots of y(s) - level."""
    cls = lb.FAMILIES[family]
    n = len(heights) - 1
    pts = [(F(i, n), F(h, 10)) for i, h in enumerate(heights)]
    curve = cls(pts) if family == "bezier" else cls(pts, F(lam_tenths, 10))
    bz = curve.to_bezier() if family != "bezier" else curve
    py = _power([p[1] for p in bz.control_points()])
    dy = [k * py[k] for k in range(1, len(py))]
    if len(dy) < 2:
        return
    minima = [
        s for s in _real_roots(dy, 0.05, 0.95)
        if sum(k * (k - 1) * py[k] * F(str(s)) ** (k - 2) for k in range(2, len(py))) > F(1, 2)
    ]  # fmt: skip
    if not minima:
        return
    s0 = minima[0]
    level = F(
        mp.nstr(sum(mp.mpf(c.numerator) / c.denominator * s0**k for k, c in enumerate(py)), 40)
    ) + F(1, 10**7)
    px = _power([p[0] for p in bz.control_points()])
    xs = [p[0] for p in bz.control_points()]
    x_lo, x_hi = min(xs) - 1, max(xs) + 1
    line = lb.BezierCurve([(x_lo, level), (x_hi, level)])
    want_s = _real_roots([py[0] - level, *py[1:]], 0, 1)
    want = [
        (
            float(s),
            float(
                (sum(mp.mpf(c.numerator) / c.denominator * s**k for k, c in enumerate(px)) - x_lo)
                / (x_hi - x_lo)
            ),
        )
        for s in want_s
    ]
    _assert_hits(curve.intersect(line), want)


def test_the_merge_tolerance_is_documented():
    from pathlib import Path

    text = (Path(__file__).resolve().parents[1] / "docs" / "guide" / "geometry.md").read_text()
    assert "merged into one only when the curves stay within 64 ε per degree" in text
