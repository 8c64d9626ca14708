"""join and CompositeCurve: the continuity of every join checked numerically from the curves'
own evaluate / derivative / curvature (never from the vertex formulas), exact joins checked
exactly through the Bézier hodographs, and the errors."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st

import lambda_bezier as lb

CONTINUITIES = ("C1", "C2", "G1", "G2")
LOW = {"bezier": 2, "same_degree": 3, "bernstein_like": 2}
# λ ranges for sampling: the admissible ranges, kept off the ends where a low degree makes
# an end derivative coefficient vanish (same_degree n = 3: C'(0) ∝ λ + 2 → 0 as λ → −2;
# bernstein_like n = 2: C'(0) ∝ 2 + 2λ = 0 at λ = −1, C''(0) free of P_2 at λ = 1), which
# makes the joins ill-conditioned near there (and impossible exactly there: see the errors).
LAMS = {"same_degree": (-1.8, 1.0), "bernstein_like": (-0.9, 0.9)}
ORDER = {"C1": 1, "C2": 2, "G1": 1, "G2": 2}


def make(family, points, lam):
    cls = lb.FAMILIES[family]
    return cls(points) if family == "bezier" else cls(points, lam)


@st.composite
def coordinates(draw, rows: int, dim: int):
    coord = st.floats(-10, 10, allow_nan=False, allow_infinity=False)
    pts = draw(st.lists(st.lists(coord, min_size=dim, max_size=dim), min_size=rows, max_size=rows))
    return np.array(pts, dtype=float)


def well_conditioned(curve, ratio: float = 0.05) -> bool:
    """The end tangent C'(1) is not tiny next to the control points (else every derivative at
    the end loses its digits to cancellation and no tolerance is meaningful)."""
    speed = np.linalg.norm(curve.derivative(1.0))
    return bool(speed >= ratio * (1 + np.abs(curve.points).max()))


@st.composite
def segments(draw, family: str | None = None, dim: int | None = None):
    family = family or draw(st.sampled_from(sorted(lb.FAMILIES)))
    dim = dim or draw(st.sampled_from((2, 3)))
    n = draw(st.integers(LOW[family], 8))
    pts = draw(coordinates(n + 1, dim))
    lam = None if family == "bezier" else draw(st.floats(*LAMS[family]))
    curve = make(family, pts, lam)
    assume(well_conditioned(curve))
    return curve


@st.composite
def join_specs(draw, continuity: str | None = None):
    """(continuity, alpha, d)."""
    cont = continuity or draw(st.sampled_from(CONTINUITIES))
    if cont.startswith("C"):
        return cont, 1, 0
    alpha = draw(st.floats(0.2, 5))
    d = draw(st.floats(-5, 5)) if cont == "G2" else 0
    return cont, alpha, d


@st.composite
def next_segment(draw, curve, cont, alpha, d):
    family = draw(st.sampled_from(sorted(lb.FAMILIES)))
    m = draw(st.integers(LOW[family], 8))
    lam = None if family == "bezier" else draw(st.floats(*LAMS[family]))
    rest = draw(coordinates(m - ORDER[cont], curve.dimension))
    return lb.join(curve, cont, m, lam, alpha, d, rest, family=family)


# --------------------------------------------------------------------------- independent checks


def _ends(left, right):
    return (
        [left.derivative(1.0, k) for k in range(3)],
        [right.derivative(0.0, k) for k in range(3)],
    )


def assert_joint(left, right, cont, alpha=1.0, rtol=1e-8):
    """The continuity `cont` at the joint, from the segments' own derivatives and curvature."""
    (p, d1, d2), (q, e1, e2) = _ends(left, right)
    size = 1 + max(np.abs(left.points).max(), np.abs(right.points).max())
    np.testing.assert_allclose(q, p, atol=rtol * size)
    vscale = 1 + max(np.linalg.norm(d1), np.linalg.norm(e1))
    if cont.startswith("C"):
        np.testing.assert_allclose(e1, d1, atol=rtol * vscale)
        if cont == "C2":
            ascale = 1 + max(np.linalg.norm(d2), np.linalg.norm(e2))
            np.testing.assert_allclose(e2, d2, atol=rtol * ascale)
        return
    # G: the same unit tangent (and the speed ratio alpha of the convention)
    u1, u2 = d1 / np.linalg.norm(d1), e1 / np.linalg.norm(e1)
    np.testing.assert_allclose(u2, u1, atol=rtol * 10)
    assert np.linalg.norm(d1) / np.linalg.norm(e1) == pytest.approx(alpha, rel=rtol * 10)
    if cont == "G2":
        k1, k2 = float(left.curvature(1.0)), float(right.curvature(0.0))
        kscale = 1 / size + max(abs(k1), abs(k2))
        assert abs(k1 - k2) <= rtol * 10 * kscale, (k1, k2)
        if left.dimension == 3:
            b1, b2 = np.cross(d1, d2), np.cross(e1, e2)
            n1, n2 = np.linalg.norm(b1), np.linalg.norm(b2)
            if min(n1, n2) > 1e-6 * np.linalg.norm(d1) * (1 + np.linalg.norm(d2)):
                np.testing.assert_allclose(b2 / n2, b1 / n1, atol=rtol * 1e3)


# --------------------------------------------------------------------------- join


@given(data=st.data())
def test_join_makes_the_joint(data):
    cont, alpha, d = data.draw(join_specs())
    first = data.draw(segments())
    second = data.draw(next_segment(first, cont, alpha, d))
    assert_joint(first, second, cont, alpha)
    report = lb.CompositeCurve([first, second], [lb.Joint(cont, alpha, d)]).report(tol=1e-7)[0]
    assert report.kept and report.holds("G1")


@pytest.mark.parametrize("family", sorted(lb.FAMILIES))
@pytest.mark.parametrize("cont", CONTINUITIES)
def test_join_keeps_rest_and_family(family, cont):
    first = lb.SameDegreeCurve([(0, 0), (1, 2), (3, 2), (4, 0)], lam=0.5)
    m = 5
    rest = np.arange(2 * (m - ORDER[cont]), dtype=float).reshape(-1, 2) + 10
    lam = None if family == "bezier" else 0.25
    nxt = lb.join(
        first,
        cont,
        m,
        lam,
        *((2, 0.5) if cont == "G2" else (2, 0) if cont == "G1" else ()),
        rest=rest,
        family=family,
    )
    assert nxt.family == family and nxt.degree == m and nxt.lam == lam
    np.testing.assert_array_equal(nxt.points[ORDER[cont] + 1 :], rest)
    np.testing.assert_array_equal(nxt.points[0], first.points[-1])
    same = lb.join(
        first,
        cont,
        4,
        0,
        *((2, 0.5) if cont == "G2" else (2, 0) if cont == "G1" else ()),
        rest=rest[1:],
    )
    assert type(same) is lb.SameDegreeCurve


def test_join_default_family_is_the_curves():
    first = lb.BezierCurve([(0, 0), (1, 1), (2, 0)])
    nxt = lb.join(first, "C1", 2, rest=[(5, 5)])
    assert type(nxt) is lb.BezierCurve
    assert_joint(first, nxt, "C1")


def test_same_degree_target_uses_given_p3():
    """For a same_degree C2/G2 target P_{2,2} depends on P_{3,2}: moving it moves P_{2,2}."""
    first = lb.BernsteinLikeCurve([(0, 0), (1, 2), (3, 2), (4, 0)], lam=0.5)
    a = lb.join(first, "C2", 4, 0.3, rest=[(8, 0), (9, 2)], family="same_degree")
    b = lb.join(first, "C2", 4, 0.3, rest=[(8, 5), (9, 2)], family="same_degree")
    assert not np.allclose(a.points[2], b.points[2])
    np.testing.assert_allclose(a.points[:2], b.points[:2])
    assert_joint(first, a, "C2")
    assert_joint(first, b, "C2")
    # at λ = 1 the family is Bernstein: P_{3,2} drops out of C2''(0)
    c = lb.join(first, "C2", 4, 1, rest=[(8, 0), (9, 2)], family="same_degree")
    e = lb.join(first, "C2", 4, 1, rest=[(8, 5), (9, 2)], family="same_degree")
    np.testing.assert_allclose(c.points[2], e.points[2])


def test_exact_join_is_exact():
    """Exact inputs give exact control points, and the conditions hold exactly (checked with
    the exact Bézier hodographs of both curves)."""
    alpha, d = Fraction(3, 2), Fraction(-1, 3)
    first = lb.SameDegreeCurve(
        [(0, 0, 1), (1, 2, 0), (3, 2, 2), (4, 0, 1), (6, 1, 0)], Fraction(1, 3)
    )
    rest = [(9, 1, 2), (10, 4, 1), (12, 0, 0)]
    for family, lam in (
        ("bernstein_like", Fraction(-1, 2)),
        ("same_degree", Fraction(2, 5)),
        ("bezier", None),
    ):
        nxt = lb.join(first, "G2", 5, lam, alpha, d, rest, family=family)
        assert nxt.is_exact and all(
            isinstance(v, Fraction) for p in nxt.control_points() for v in p
        )

        def ends(curve, at_end):
            h = curve.to_bezier()
            out = []
            for _ in range(3):
                pts = h.control_points()
                out.append(np.array(pts[-1] if at_end else pts[0], dtype=object))
                if h.degree >= 2:
                    h = h.hodograph()
                else:  # a line's derivative is constant
                    pts = h.control_points()
                    h = lb.BezierCurve(
                        [tuple(h.degree * (b - a) for a, b in zip(pts[0], pts[1], strict=True))] * 2
                    )
            return out

        p, d1, d2 = ends(first, True)
        q, e1, e2 = ends(nxt, False)
        assert list(q) == list(p)
        assert list(alpha * e1) == list(d1)
        assert list(alpha**2 * e2 + d * e1) == list(d2)
        floats = lb.join(
            lb.SameDegreeCurve(first.points, 1 / 3),
            "G2",
            5,
            None if lam is None else float(lam),
            1.5,
            -1 / 3,
            np.array(rest, float),
            family=family,
        )
        np.testing.assert_allclose(
            floats.points, np.array(nxt.control_points(), float), rtol=1e-12, atol=1e-12
        )


def test_paper_figure_convention_g1_same_degree():
    """000 Prop. 9's G1 join is the G1 join here with α = 1/β: P_{1,2} − P_{0,2} is a positive
    multiple of P_{n,1} − P_{n−1,1}."""
    first = lb.SameDegreeCurve([(0, 0), (1, 2), (3, 2), (4, 0)], lam=-1)
    nxt = lb.join(first, "G1", 3, 0.5, alpha=2, rest=[(7, -1), (8, 0)])
    step, tangent = nxt.points[1] - nxt.points[0], first.points[-1] - first.points[-2]
    ratio = step / tangent
    assert ratio[0] == pytest.approx(ratio[1]) and ratio[0] > 0


# --------------------------------------------------------------------------- composite


@st.composite
def composites(draw, cont: str):
    dim = draw(st.sampled_from((2, 3)))
    comp = lb.CompositeCurve([draw(segments(dim=dim))])
    for _ in range(draw(st.integers(1, 3))):
        _, alpha, d = draw(join_specs(cont))
        family = draw(st.sampled_from(sorted(lb.FAMILIES)))
        m = draw(st.integers(LOW[family], 8))
        lam = None if family == "bezier" else draw(st.floats(*LAMS[family]))
        rest = draw(coordinates(m - ORDER[cont], dim))
        comp = comp.join(cont, m, lam, alpha, d, rest, family=family)
        assume(well_conditioned(comp.segments[-1]))
    return comp


@pytest.mark.parametrize("cont", ["C2", "G2", "C1", "G1"])
@given(data=st.data())
def test_composite_keeps_continuity_after_lambda_change(cont, data):
    comp = data.draw(composites(cont))
    for j, (left, right) in enumerate(zip(comp.segments, comp.segments[1:], strict=False)):
        assert_joint(left, right, cont, comp.joints[j].alpha)
    choices = [i for i, s in enumerate(comp.segments) if s.family != "bezier"]
    assume(choices)
    index = data.draw(st.sampled_from(choices))
    seg = comp.segments[index]
    lam = data.draw(st.floats(*LAMS[seg.family]))
    new = comp.with_lambda(index, lam)
    assume(all(well_conditioned(seg, 0.01) for seg in new.segments[:-1]))
    assert new.segments[index].lam == lam
    assert new.segments[:index] == comp.segments[:index]  # the same objects: untouched
    for j, (left, right) in enumerate(zip(new.segments, new.segments[1:], strict=False)):
        # the re-solved points can grow through several joins: a looser, relative tolerance
        assert_joint(left, right, cont, comp.joints[j].alpha, rtol=1e-6)
    for s_old, s_new in zip(comp.segments, new.segments, strict=True):
        np.testing.assert_array_equal(
            s_new.points[ORDER[cont] + 1 :], s_old.points[ORDER[cont] + 1 :]
        )


def test_lambda_change_without_resolve_section_3_3():
    """001, section 3.3: a G1 composite survives a λ change with its control points fixed,
    C1, C2 and G2 ones do not (they need the re-solve)."""
    first = lb.BernsteinLikeCurve([(0, 0), (1, 2), (3, 3), (5, 2)], lam=0)
    for cont, extra in (("G1", (2, 0)), ("C1", ()), ("C2", ()), ("G2", (2, 1))):
        comp = lb.CompositeCurve([first]).join(
            cont, 4, 0.5, *extra, rest=[(9, 0), (10, 1), (12, 3)][ORDER[cont] - 1 :]
        )
        assert comp.report()[0].kept
        moved = comp.with_lambda(1, -0.5, resolve=False)
        assert moved.report()[0].kept is (cont == "G1")
        assert moved.report()[0].holds("G1")
        assert comp.with_lambda(1, -0.5).report()[0].kept
        assert comp.with_lambda(0, 0.7).report()[0].kept


def test_composite_parametrisation_and_report():
    a = lb.BezierCurve([(0, 0), (1, 1), (2, 0)])
    comp = lb.CompositeCurve([a]).join("C2", 3, 0.5, rest=[(5, 1)], family="same_degree")
    comp = comp.join("G1", 2, -0.5, alpha=3, rest=[(9, 9)], family="bernstein_like")
    assert len(comp) == 3 and comp.domain == (0, 3)
    u = np.array([0, 0.25, 1, 1.5, 2, 2.75, 3])
    seg_of = [0, 0, 1, 1, 2, 2, 2]
    local = [0, 0.25, 0, 0.5, 0, 0.75, 1]
    want = np.array([comp.segments[s].evaluate(t) for s, t in zip(seg_of, local, strict=True)])
    np.testing.assert_allclose(comp.evaluate(u), want)
    np.testing.assert_allclose(comp.evaluate(1.5), want[3])
    np.testing.assert_allclose(comp.derivative(u, 2)[3], comp.segments[1].derivative(0.5, 2))
    np.testing.assert_allclose(comp.curvature(u)[5], comp.segments[2].curvature(0.75))
    # C2 at u = 1: left and right limits of the composite's derivatives agree
    for k in (0, 1, 2):
        left = comp.derivative(1 - 1e-7, k)
        np.testing.assert_allclose(left, comp.derivative(1.0, k), atol=1e-4 * (1 + abs(left).max()))
    r1, r2 = comp.report()
    assert r1.achieved == {"C0", "C1", "C2", "G1", "G2"} and r1.built_with == lb.Joint("C2")
    assert r2.holds("G1") and not r2.holds("C1") and r2.speed_ratio == pytest.approx(3)
    assert r1.binormal_angle is None and r2.u == 2
    with pytest.raises(ValueError, match=r"outside \[0, 3\]"):
        comp.evaluate(3.5)
    assert comp.evaluate(3.5, extrapolate=True).shape == (2,)
    assert "CompositeCurve(3 segments" in repr(comp)


def test_report_measures_a_kink_and_3d_binormal():
    a = lb.BezierCurve([(0, 0, 0), (1, 0, 0), (2, 1, 0)])
    b = lb.BezierCurve([(2, 1, 0), (3, 1, 0), (4, 1, 1)])  # turns 45°: C0 only
    r = lb.CompositeCurve([a, b]).report()[0]
    assert r.achieved == {"C0"} and r.tangent_angle == pytest.approx(np.pi / 4)
    assert r.kept is None and r.binormal_angle is not None
    c = lb.join(a, "G2", 3, alpha=2, d=1, rest=[(5, 0, 3)])
    r = lb.CompositeCurve([a, c], ["G2"]).report()[0]
    assert r.holds("G2") and r.binormal_angle < 1e-9
    assert not r.holds("C1")


# --------------------------------------------------------------------------- errors


@pytest.fixture
def cubic():
    return lb.BernsteinLikeCurve([(0, 0), (1, 2), (3, 2), (4, 0)], lam=0.5)


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"continuity": "C3"}, r"continuity must be one of 'C1', 'C2', 'G1', 'G2', got 'C3'"),
        ({"continuity": 2}, r"continuity must be one of"),
        ({"continuity": "G1", "alpha": 0}, r"alpha must be > 0"),
        ({"continuity": "G2", "alpha": -1.5}, r"alpha must be > 0"),
        ({"continuity": "G2", "alpha": float("nan")}, r"alpha must be finite"),
        ({"continuity": "C1", "alpha": 2}, r"alpha and d belong to G1/G2 joins"),
        ({"continuity": "G1", "alpha": 2, "d": 1}, r"d only enters G2"),
        ({"family": "nurbs"}, r"unknown family 'nurbs'"),
        ({"degree": 13}, r"degree 13 is not supported for bernstein_like"),
        ({"degree": 2.5}, r"degree must be an integer"),
        ({"lam": None}, r"needs a shape parameter lam"),
        ({"lam": 2}, r"outside the bernstein_like range \[-1, 1\]"),
        ({"family": "bezier"}, r"classical Bézier segment takes no shape parameter"),
        ({"rest": [(1, 2, 3), (4, 5, 6)]}, r"dimension 3 but the first curve has dimension 2"),
        (
            {"rest": [(1, 2)]},
            r"rest must hold the other 2 point\(s\) \(P_\{2,2\}..P_\{3,2\}\), got 1",
        ),
        ({"rest": [(1, float("inf")), (2, 2)]}, r"NaN or infinity"),
    ],
)
def test_bad_input(cubic, kwargs, message):
    args = {"continuity": "C1", "degree": 3, "lam": 0, "alpha": 1, "d": 0, "rest": [(5, 0), (6, 1)]}
    args.update(kwargs)
    with pytest.raises(ValueError, match=message):
        lb.join(cubic, **args)


def test_same_degree_rest_message_names_p3(cubic):
    with pytest.raises(ValueError, match=r"P_\{3,2\} enters the solve of P_\{2,2\}"):
        lb.join(cubic, "C2", 4, 0, rest=[(5, 0)], family="same_degree")


def test_degenerate_end():
    bad = lb.SameDegreeCurve([(0, 0), (1, 2), (4, 0), (4, 0)], lam=0.5)
    with pytest.raises(ValueError, match=r"degenerate: P_3 = P_2, so C1'\(1\) = 0"):
        lb.join(bad, "G1", 3, 0, alpha=1, rest=[(5, 0), (6, 1)])
    exact = lb.BezierCurve([(0, 0), (Fraction(1, 3), 1), (Fraction(1, 3), 1)])
    with pytest.raises(ValueError, match="degenerate"):
        lb.join(exact, "C1", 2, rest=[(5, 0)])
    # C1'(1) = (n - 1 + λ)(P_n - P_{n-1}) vanishes at λ = 1 - n (outside the range, on purpose)
    zero = lb.SameDegreeCurve([(0, 0), (1, 2), (3, 2), (4, 0)], lam=-2, check_range=False)
    with pytest.raises(
        ValueError, match=r"C1'\(1\) = 0.*same_degree curve of degree 3 with lam = -2"
    ):
        lb.join(zero, "C1", 3, 0, rest=[(5, 0), (6, 1)])


def test_vanishing_pivot_is_named(cubic):
    """A quadratic bernstein_like curve with λ = 1 is t⁴ at its start: C2''(0) does not
    involve P_{2,2}, so no C2/G2 join can end there; C1/G1 can."""
    with pytest.raises(
        ValueError,
        match=r"cannot solve C2 for P_\{2,2\}: its coefficient in C2''\(0\), "
        r"4\*lam2\*m - 10\*lam2 \+ m\*\*2 - m, vanishes for a bernstein_like curve of degree "
        r"m = 2 with lam = 1",
    ):
        lb.join(cubic, "C2", 2, 1, rest=[])
    with pytest.raises(ValueError, match=r"P_\{2,2\}"):
        lb.join(cubic, "G2", 2, Fraction(1), alpha=2, d=1, rest=[])
    ok = lb.join(cubic, "C1", 2, 1, rest=[(7, 7)])
    assert_joint(cubic, ok, "C1")
    # same_degree m = 3 at λ = −2 (excluded from the range): C2'(0) has coefficient λ + m − 1 = 0
    with pytest.raises(ValueError, match=r"P_\{1,2\}: its coefficient in C2'\(0\), lam2 \+ m - 1"):
        lb.join(cubic, "C1", 3, -2, rest=[(5, 0), (6, 1)], family="same_degree", check_range=False)


def test_quadratic_bernstein_like_at_lambda_minus_one_has_no_end_tangent():
    """Inside the range: b_{0,2} and b_{1,2} have C'(0) coefficient 2 + 2λ = 0 at λ = −1, so a
    quadratic bernstein_like curve with λ = −1 can neither start nor end a G1/C1 join."""
    quad = lb.BernsteinLikeCurve([(0, 0), (1, 2), (3, 0)], lam=-1)
    assert np.linalg.norm(quad.derivative(1.0)) == pytest.approx(0, abs=1e-12)
    with pytest.raises(ValueError, match=r"C1'\(1\) = 0.*bernstein_like curve of degree 2"):
        lb.join(quad, "G1", 3, 0, alpha=1, rest=[(5, 0), (6, 1)])
    cubic = lb.BernsteinLikeCurve([(0, 0), (1, 2), (3, 2), (4, 0)], lam=0)
    with pytest.raises(ValueError, match=r"P_\{1,2\}: its coefficient in C2'\(0\), 2\*lam2 \+ m"):
        lb.join(cubic, "C1", 2, -1, rest=[(7, 7)])


def test_bezier_c2_target_needs_degree_two(cubic):
    with pytest.raises(ValueError, match=r"needs degree >= 2, got 1"):
        lb.join(cubic, "C2", 1, rest=[], family="bezier")
    line = lb.join(cubic, "C1", 1, family="bezier")
    assert line.degree == 1
    assert_joint(cubic, line, "C1")


def test_composite_errors(cubic):
    with pytest.raises(ValueError, match="at least one segment"):
        lb.CompositeCurve([])
    with pytest.raises(ValueError, match="segment 1 has dimension 3, segment 0 has dimension 2"):
        lb.CompositeCurve([cubic, lb.BezierCurve([(4, 0, 0), (5, 0, 0)])])
    with pytest.raises(ValueError, match="segment 1 is not a lambda_bezier curve"):
        lb.CompositeCurve([cubic, [(4, 0), (5, 0)]])
    with pytest.raises(ValueError, match=r"one entry per joint \(1\), got 2"):
        lb.CompositeCurve([cubic, cubic], ["C1", "C1"])
    with pytest.raises(ValueError, match="continuity must be one of"):
        lb.CompositeCurve([cubic, cubic], ["smooth"])
    comp = lb.CompositeCurve([lb.BezierCurve([(0, 0), (1, 1), (4, 0)])]).join(
        "C1", 3, 0, rest=[(5, 5), (6, 0)], family="bernstein_like"
    )
    with pytest.raises(ValueError, match="segment 0 is a classical Bézier curve"):
        comp.with_lambda(0, 0.5)
    with pytest.raises(ValueError, match="index 2 is out of range"):
        comp.with_lambda(2, 0.5)
    with pytest.raises(ValueError, match=r"outside the bernstein_like range"):
        comp.with_lambda(1, 3)
    with pytest.raises(ValueError, match="curve must be a lambda_bezier curve"):
        lb.join([(0, 0), (1, 1)], "C1", 2, rest=[(1, 1)])
