"""Property claims, caveats, singular parameters and from_bezier, against independent numerics.

Every verdict the exact procedures of derive/formulas/properties.py reach about the papers is
re-computed here in floats from the basis *definitions* (tests/reference.py), never from
generated/ or derive/.
"""

from __future__ import annotations

import importlib
from fractions import Fraction

import numpy as np
import pytest
from conftest import ROOT
from hypothesis import given
from hypothesis import strategies as st
from reference import FAMILIES, C

import lambda_bezier as lb
from lambda_bezier import _derive_runner

T = np.linspace(0.0, 1.0, 201)
NODES, WEIGHTS = np.polynomial.legendre.leggauss(24)


@pytest.fixture(scope="module")
def pr():
    return importlib.import_module(
        _derive_runner.load_derive(ROOT).__name__ + ".formulas.properties"
    )


def ref_basis(family: str, n: int, t, lam) -> np.ndarray:
    return FAMILIES[family].basis(n, t, lam)


def sample_matrix(family: str, n: int, lam: float) -> np.ndarray:
    """(n+1) × len(T): the basis functions sampled; rank < n + 1 iff they are dependent."""
    return ref_basis(family, n, T, lam).T


def relative_smallest_singular_value(family: str, n: int, lam: float) -> float:
    s = np.linalg.svd(sample_matrix(family, n, lam), compute_uv=False)
    return s[-1] / s[0]


def derivative(f, t: float, order: int = 1, h: float = 1e-4) -> float:
    """Central/one-sided finite differences, enough for the O(1) values compared here."""
    if order == 1:
        return (
            (f(t + h) - f(t - h)) / (2 * h)
            if 0 < t < 1
            else (
                (-3 * f(t) + 4 * f(t + h) - f(t + 2 * h)) / (2 * h)
                if t == 0
                else (3 * f(t) - 4 * f(t - h) + f(t - 2 * h)) / (2 * h)
            )
        )
    s = 1 if t == 0 else -1
    return (2 * f(t) - 5 * f(t + s * h) + 4 * f(t + 2 * s * h) - f(t + 3 * s * h)) / h**2


# --------------------------------------------------------------------------- singular parameters


def test_degree5_same_degree_basis_is_dependent_at_minus_three_halves():
    """000 Prop. 5 is false: at λ = -3/2 the degree-5 functions b_2 and b_3 coincide."""
    b = ref_basis("same_degree", 5, T, -1.5)
    assert np.max(np.abs(b[:, 2] - b[:, 3])) < 1e-14
    assert lb.singular_parameters("same_degree", 5) == (Fraction(-3, 2),)


@pytest.mark.parametrize("n", range(3, 13))
def test_singular_parameters_are_where_the_sampled_basis_loses_rank(n):
    roots = lb.singular_parameters("same_degree", n)
    for root in roots:
        lam = float(root)
        assert -2 < lam <= 1
        assert relative_smallest_singular_value("same_degree", n, lam) < 1e-9
        for step in (-0.02, 0.02):
            if -2 < lam + step <= 1:
                assert relative_smallest_singular_value("same_degree", n, lam + step) > 1e-7
    # no root missed: det of the square sample matrix at n + 1 nodes changes sign exactly at
    # the listed (simple) roots, on a fine grid of the range
    nodes = 0.5 - 0.5 * np.cos(np.pi * (np.arange(n + 1) + 0.5) / (n + 1))
    grid = np.linspace(-1.9999, 1.0, 6000)
    # (all 6000 matrices at once, lam as a column: the same elementwise arithmetic and the
    # same LU per matrix, bit for bit the one-at-a-time loop's determinants, 1/50 the time)
    dets = np.linalg.det(ref_basis("same_degree", n, nodes, grid[:, None]))
    assert dets.shape == grid.shape
    changes = int(np.sum(np.sign(dets[1:]) != np.sign(dets[:-1])))
    assert changes == len(roots)


@pytest.mark.parametrize("n", [2, 3, 5, 8, 12])
def test_bernstein_like_and_bezier_have_no_singular_parameter(n):
    assert lb.singular_parameters("bernstein_like", n) == ()
    assert lb.singular_parameters("bezier", n) == ()
    worst = min(
        relative_smallest_singular_value("bernstein_like", n, x) for x in np.linspace(-1, 1, 41)
    )
    assert worst > 1e-9


def test_isolated_roots_are_roots():
    for n in range(6, 13):
        for root in lb.singular_parameters("same_degree", n):
            assert isinstance(root, lb.IsolatedRoot)
            x = float(root)
            assert float(root.lo) < x < float(root.hi)
            value = sum(c * x**j for j, c in enumerate(root.coefficients))
            scale = sum(abs(c) * abs(x) ** j for j, c in enumerate(root.coefficients))
            assert abs(value) < 1e-12 * scale
            assert root.polynomial(root.lo) * root.polynomial(root.hi) < 0


def test_singular_parameters_refuse_bad_input():
    with pytest.raises(ValueError, match="family"):
        lb.singular_parameters("cubic", 3)
    with pytest.raises(ValueError, match="unknown family 3"):  # not a name nor a family
        lb.singular_parameters(3, 3)
    with pytest.raises(ValueError, match="n: degree 2"):
        lb.singular_parameters("same_degree", 2)
    with pytest.raises(TypeError, match="n must be"):
        lb.singular_parameters("same_degree", 3.0)


# --------------------------------------------------------------------------- other properties


@pytest.mark.parametrize("family", ["same_degree", "bernstein_like"])
def test_stated_properties_hold_numerically(family):
    fam = FAMILIES[family]
    lo, hi = fam.lam_range
    for n in fam.degrees:
        for lam in np.linspace(lo, hi, 13):
            b = ref_basis(family, n, T, lam)
            assert b.min() > -1e-12  # non-negative
            assert np.allclose(b.sum(axis=1), 1.0, atol=1e-12)  # partition of unity
            mirrored = ref_basis(family, n, 1 - T, lam)[:, ::-1]
            assert np.allclose(b, mirrored, atol=1e-12)  # symmetry
        bern = np.stack([C(n, i) * T**i * (1 - T) ** (n - i) for i in range(n + 1)], axis=1)
        assert np.allclose(ref_basis(family, n, T, fam.bernstein_lambda), bern, atol=1e-12)


def test_nonnegativity_counterexample_outside_the_range_is_real(pr):
    """Widen the ranges: the exact procedure names a (λ, t) where b_i < 0; the definition
    evaluated in floats agrees on the value."""
    for family, iv, n in (
        ("same_degree", pr.Interval(Fraction(-3), Fraction(1)), 3),
        ("same_degree", pr.Interval(Fraction(-2), Fraction(2), lo_open=True), 6),
        ("bernstein_like", pr.Interval(Fraction(-2), Fraction(1)), 3),
        ("bernstein_like", pr.Interval(Fraction(-1), Fraction(3)), 2),
    ):
        found = pr.nonnegative(family, n, iv)
        assert found is not None, (family, iv)
        lam, t, value = found.data["lam"], found.data["t"], found.data["value"]
        assert iv.contains(lam) and 0 <= t <= 1 and value < 0
        ref = ref_basis(family, n, [float(t)], float(lam))[0, found.data["index"]]
        assert ref == pytest.approx(float(value), rel=1e-9, abs=1e-12)


def test_nonnegativity_needs_more_than_bernstein_coefficients(pr):
    """p = B_0^2 - B_1^2/16 + B_2^2 = 1 - 9t/4 + 9t²/4 has a negative Bernstein coefficient but
    is >= 7/16 on [0, 1]; the exact decision in t says so, and finds p - 1/2 < 0 at some t."""
    fmpq, fmpq_poly = pr.flint.fmpq, pr.flint.fmpq_poly
    p = fmpq_poly([4, -9, 9]) / 4
    unit = pr.Interval(Fraction(0), Fraction(1))
    assert pr.negative_point(p, unit) is None
    q = p - fmpq(1, 2)
    x = pr.negative_point(q, unit)
    assert x is not None and 0 <= x <= 1 and 1 - 2.25 * x + 2.25 * x * x - 0.5 < 0


@given(st.lists(st.integers(-30, 30), min_size=2, max_size=7))
def test_real_roots_agree_with_numpy(pr, coeffs):
    p = pr.flint.fmpq_poly(coeffs)
    if p.degree() < 1:
        return
    roots = pr.real_roots(p)
    approx = sorted(
        r.real for r in np.roots(list(reversed(coeffs))) if abs(r.imag) < 1e-7 * (1 + abs(r))
    )
    distinct = []
    for r in approx:
        if not distinct or abs(r - distinct[-1]) > 1e-5:
            distinct.append(r)
    assert len(roots) == len(distinct)
    for root, r in zip(roots, distinct, strict=True):
        lo, hi = float(root.lo), float(root.hi)
        assert lo - 1e-6 <= r <= hi + 1e-6


def test_interval_parse(pr):
    iv = pr.Interval.parse("(-2, 1]")
    assert (iv.lo, iv.hi, iv.lo_open, iv.hi_open) == (-2, 1, True, False)
    assert not iv.contains(Fraction(-2)) and iv.contains(Fraction(1))
    for bad in ("-2, 1", "(1, -2]", "(1, 1]", "[a, 1]"):
        with pytest.raises(ValueError, match="parameter range"):
            pr.Interval.parse(bad)


def test_identity_checkers_fail_on_a_basis_without_the_property(pr, monkeypatch):
    """The partition, symmetry, end-point and independence procedures can fail: fed a broken
    basis (Bernstein with b_0 doubled and b_1 = b_2 at λ = 1/2) they say where."""
    fmpq_poly = pr.flint.fmpq_poly

    def broken(family, n):
        rows = [[fmpq_poly([int(i == j)]) for j in range(n + 1)] for i in range(n + 1)]
        rows[0][0] = fmpq_poly([2])
        rows[2][2] = fmpq_poly([-1, 2])  # b_2 = (2λ - 1) B_2: zero at λ = 1/2
        if n == 4:  # b_4 = b_3: dependent for every λ
            rows[4] = rows[3]
        return tuple(tuple(r) for r in rows)

    monkeypatch.setattr(pr, "coefficients", broken)
    assert "Σ b_i" in pr.partition_of_unity("x", 3).text
    assert "b_0(1 - t)" in pr.symmetry("x", 3).text
    assert "b_0(0) = 2" in pr.endpoint_interpolation("x", 3).text
    pr.independence_polynomial.cache_clear()
    pr.singular_roots.cache_clear()
    found = pr.linear_independence("x", 3, pr.Interval(Fraction(0), Fraction(1)))
    pr.independence_polynomial.cache_clear()
    pr.singular_roots.cache_clear()
    assert found is not None and found.data["roots"] == [Fraction(1, 2)]
    assert "(1)·b_2 = 0" in found.text
    always = pr.linear_independence("x", 4, pr.Interval(Fraction(0), Fraction(1)))
    pr.independence_polynomial.cache_clear()
    assert always is not None and "EVERY λ" in always.text


# --------------------------------------------------------------------------- findings, numerically


def test_example_4_2_optimum_lies_outside_the_range():
    """000 section 4.2: E_2(λ) by quadrature of the definition is a convex quadratic whose
    minimiser is -690/319 < -2, so on (-2, 1] it decreases towards the excluded end."""
    pts = np.array([(0, 6), (0, 2), (5, 2), (7, 0), (2, 0), (6, 8)], dtype=float)
    x = (NODES + 1) / 2

    def energy(lam):
        # p is a quintic: fit it exactly through 12 nodes of the definition, differentiate twice
        nodes = np.linspace(0, 1, 12)
        p = ref_basis("same_degree", 5, nodes, lam) @ pts
        polys = [np.polynomial.Polynomial.fit(nodes, p[:, c], 5).convert() for c in range(2)]
        second = np.stack([q.deriv(2)(x) for q in polys], axis=1)
        return float(np.sum(WEIGHTS / 2 * np.sum(second**2, axis=1)))

    e = [energy(v) for v in (-3.0, 0.0, 1.0)]
    quad = np.polyfit([-3.0, 0.0, 1.0], e, 2)
    assert quad[0] == pytest.approx(5104 / 7, rel=1e-8)
    assert -quad[1] / (2 * quad[0]) == pytest.approx(-690 / 319, rel=1e-9)
    assert energy(-1.999) < energy(-1.9) < energy(0.0)


def test_bernstein_like_tangent_vanishes_at_degree_2_lambda_minus_1():
    """001 section 3.3: n + 2λ = 0 at n = 2, λ = -1: C'(0) = 0 whatever the points."""
    f = lambda t: ref_basis("bernstein_like", 2, [t], -1.0)[0]  # noqa: E731
    pts = np.array([(0.0, 0.0), (1.0, 3.0), (4.0, 1.0)])
    velocity = np.array([derivative(lambda s, c=c: f(s) @ pts[:, c], 0.0) for c in range(2)])
    assert np.max(np.abs(velocity)) < 1e-6


def test_bernstein_like_second_derivative_weight_vanishes_at_degree_2_lambda_1():
    """001 eq. (19): the C''(0) weight of P_{2,2} is 0 at m = 2, λ2 = 1: P_{2,2} is free."""
    f = lambda t: ref_basis("bernstein_like", 2, [t], 1.0)[0, 2]  # noqa: E731
    assert abs(derivative(f, 0.0, order=2, h=1e-3)) < 1e-4


def test_printed_proof_lines_of_prop_7_at_t_1_are_wrong():
    """000 proof of Prop. 7: the printed b'_{n-1}(1) line gives -nλ, the printed b'_n(1)
    line gives n, while the derivatives of the definition are ∓(n - 1 + λ)."""
    for n in (3, 5, 8):
        for lam in (-1.5, 0.5):
            b = lambda t, n=n, lam=lam: ref_basis("same_degree", n, [t], lam)[0]  # noqa: E731
            d_prev = derivative(lambda t, b=b, n=n: b(t)[n - 1], 1.0, h=1e-5)
            d_last = derivative(lambda t, b=b, n=n: b(t)[n], 1.0, h=1e-5)
            assert d_prev == pytest.approx(-(n - 1 + lam), abs=1e-6)
            assert d_last == pytest.approx(n - 1 + lam, abs=1e-6)
            printed_prev = ((C(n - 1, n - 1) - C(n - 2, n - 2)) + lam) / C(n - 1, n - 1) * -n
            printed_last = C(n - 3, n) * (1 - lam) / C(n - 1, n - 1) * -n + n
            assert abs(printed_prev - d_prev) > 0.5 and abs(printed_last - d_last) > 0.5


def test_printed_partition_proof_sum_is_not_one():
    """000 proof of Prop. 3 with Σ_{i=1}^{k} b_{i-1}^k: equals 1 - t·b_k^k, not 1."""
    k, lam = 4, 0.25
    b = ref_basis("same_degree", k, T, lam)
    printed = (1 - T) * b.sum(axis=1) + T * b[:, :k].sum(axis=1)
    assert np.max(np.abs(printed - 1)) > 0.1
    assert np.allclose(printed, 1 - T * b[:, k])


def test_hodograph_has_n_control_points():
    """002: the first hodograph of a degree-n curve has n control points, not n - 1."""
    for n in (2, 3, 6):
        curve = lb.BezierCurve(np.random.default_rng(n).normal(size=(n + 1, 2)))
        assert len(curve.hodograph().control_points()) == n


# --------------------------------------------------------------------------- from_bezier


exact_coord = st.fractions(min_value=-10, max_value=10, max_denominator=12)


@given(
    st.integers(3, 7),
    st.lists(st.tuples(exact_coord, exact_coord), min_size=8, max_size=8),
    st.sampled_from([Fraction(1), Fraction(1, 2), Fraction(-1), Fraction(-19, 10)]),
)
def test_same_degree_from_bezier_round_trip_exact(n, pts, lam):
    bez = lb.BezierCurve(pts[: n + 1])
    if lam in lb.singular_parameters("same_degree", n):
        return
    curve = lb.SameDegreeCurve.from_bezier(bez, lam)
    assert curve.degree == n and curve.is_exact
    assert curve.to_bezier().control_points() == bez.control_points()
    # the definition at a few t agrees with the Bézier curve
    tt = np.array([0.1, 0.5, 0.8])
    want = np.stack([C(n, i) * tt**i * (1 - tt) ** (n - i) for i in range(n + 1)], 1) @ np.array(
        bez.points
    )
    got = ref_basis("same_degree", n, tt, float(lam)) @ np.array(curve.points)
    assert np.allclose(got, want, atol=1e-9)


def test_from_bezier_float_and_low_degree():
    bez = lb.BezierCurve([(0.0, 0.0), (1.0, 2.0), (3.0, 0.0)])  # a quadratic
    curve = lb.SameDegreeCurve.from_bezier(bez, 0.25)
    assert curve.degree == 3
    assert np.allclose(curve.evaluate(T), bez.evaluate(T), atol=1e-12)


def test_from_bezier_refuses_a_singular_parameter():
    bez = lb.BezierCurve([(i, i * i % 5) for i in range(6)])
    with pytest.raises(ValueError, match=r"linearly dependent at λ = -3/2"):
        lb.SameDegreeCurve.from_bezier(bez, Fraction(-3, 2))


def test_bernstein_like_from_bezier():
    src = lb.BernsteinLikeCurve([(0, 0), (1, 2), (3, 3), (5, 1)], Fraction(1, 2))
    back = lb.BernsteinLikeCurve.from_bezier(src.to_bezier(), Fraction(1, 2))
    assert back.control_points() == src.control_points()
    generic = lb.BezierCurve([(0, 0), (1, 2), (3, 3), (4, 1), (5, 0)])
    assert lb.BernsteinLikeCurve.from_bezier(generic, 0).degree == 4  # λ = 0: Bernstein
    with pytest.raises(ValueError, match="bezier: this degree-4 Bézier curve is no"):
        lb.BernsteinLikeCurve.from_bezier(generic, Fraction(1, 2))


def test_from_bezier_refuses_bad_input():
    bez = lb.BezierCurve([(0, 0), (1, 2), (3, 3), (4, 1)])
    with pytest.raises(TypeError, match="bezier must be a BezierCurve"):
        lb.SameDegreeCurve.from_bezier([(0, 0), (1, 1)], 1)
    with pytest.raises(ValueError, match="lam"):
        lb.SameDegreeCurve.from_bezier(bez, None)
    with pytest.raises(ValueError, match="lam"):
        lb.SameDegreeCurve.from_bezier(bez, 5)
    with pytest.raises(ValueError, match="lam"):
        lb.BezierCurve.from_bezier(bez, 1)
    assert lb.BezierCurve.from_bezier(bez).control_points() == bez.control_points()


# --------------------------------------------------------------------------- with_lambda (eq. 17)


def _ref_velocity(seg, end: int) -> np.ndarray:
    """p'(end) of a segment from the definition (reference basis, finite differences)."""
    fam, pts = seg.family, np.array(seg.control_points(), dtype=float)
    lam = float(seg.lam)
    return np.array(
        [
            derivative(lambda t, c=c: (ref_basis(fam, seg.degree, [t], lam) @ pts[:, c])[0], end)
            for c in range(pts.shape[1])
        ]
    )


def _chain():
    first = lb.BernsteinLikeCurve([(0, 0), (1, 2), (3, 3), (4, 1)], Fraction(1, 2))
    return (
        lb.CompositeCurve([first])
        .join("C1", 4, Fraction(0), rest=[(7, -2), (8, 0), (9, 3)])
        .join("C1", 3, Fraction(1, 4), rest=[(12, 5), (13, 1)])
        .join("G1", 3, Fraction(0), alpha=2, rest=[(16, 2), (18, 0)])
    )


def test_with_lambda_keep_points_follows_every_c1_joint():
    comp = _chain()
    new = comp.with_lambda(1, Fraction(1, 2), keep_points=True)
    # (3 + 2λ0)·e = (4 + 2·1/2)·e and (4 + 1)·e = (3 + 2λ2)·(8/7)e: λ0 = 1, λ2 = 11/16
    assert [s.lam for s in new.segments] == [1, Fraction(1, 2), Fraction(11, 16), 0]
    for old, seg in zip(comp.segments, new.segments, strict=True):
        assert seg.control_points() == old.control_points()
    for j in (0, 1):  # C1 by the definition, independently of the runtime's derivative
        left, right = new.segments[j], new.segments[j + 1]
        assert np.allclose(_ref_velocity(left, 1), _ref_velocity(right, 0), atol=1e-5)
    assert new.report()[2].holds("G1")  # the G1 joint needed no change and ends the chain


def test_with_lambda_keep_points_same_degree():
    first = lb.SameDegreeCurve([(0, 0), (1, 2), (3, 3), (4, 1)], Fraction(0))
    comp = lb.CompositeCurve([first]).join("C1", 3, Fraction(1, 2), rest=[(8, 0), (9, 2)])
    new = comp.with_lambda(0, Fraction(-1, 2), keep_points=True)
    # (2 + λ0)·e = (2 + λ1)·f: 2·e = 5/2·f, then 3/2·e = (2 + λ1)·(4/5)e gives λ1 = -1/8
    assert new.segments[1].lam == Fraction(-1, 8)
    assert np.allclose(
        _ref_velocity(new.segments[0], 1), _ref_velocity(new.segments[1], 0), atol=1e-5
    )


def test_with_lambda_keep_points_refusals():
    comp = _chain()
    first = lb.SameDegreeCurve([(0, 0), (1, 2), (3, 3), (4, 1)], Fraction(0))
    sd = lb.CompositeCurve([first]).join("C1", 3, Fraction(1, 2), rest=[(8, 0), (9, 2)])
    with pytest.raises(ValueError, match=r"needs λ = 9/8 for segment 1, outside the same_degree"):
        sd.with_lambda(0, Fraction(1, 2), keep_points=True)
    with pytest.raises(ValueError, match=r"joint 0: keeping it C1 needs λ = -3/2 for segment 1"):
        comp.with_lambda(0, Fraction(-1), keep_points=True)
    c2 = lb.CompositeCurve([comp.segments[0]]).join("C2", 4, Fraction(0), rest=[(8, 2), (9, 0)])
    with pytest.raises(ValueError, match="joint 0 is C2"):
        c2.with_lambda(1, Fraction(1, 2), keep_points=True)
    with pytest.raises(ValueError, match="index 9 is out of range"):
        comp.with_lambda(9, 0, keep_points=True)


def test_nonnegativity_and_hull_fail_on_a_negative_basis(pr, monkeypatch):
    """A basis with b_1 = -B_1 (and b_0 = B_0 + 2B_1 so that it still sums to one): the
    exact procedure finds b_1 < 0, and the convex-hull claim fails with it."""
    fmpq_poly = pr.flint.fmpq_poly

    def negative(family, n):
        rows = [[fmpq_poly([int(i == j)]) for j in range(n + 1)] for i in range(n + 1)]
        rows[1][1] = fmpq_poly([-1])
        rows[0][1] = fmpq_poly([2])
        return tuple(tuple(r) for r in rows)

    monkeypatch.setattr(pr, "coefficients", negative)
    found = pr.nonnegative("x", 3, None)
    assert found is not None and found.data["index"] == 1
    t = float(found.data["t"])
    assert 0 <= t <= 1 and -3 * t * (1 - t) ** 2 < 0
    assert pr.partition_of_unity("x", 3) is None


def test_property_records_refuse_malformed_values(tmp_path):
    from lambda_bezier import _verify_runner

    bad = tmp_path / "bad.toml"
    bad.write_text(
        'schema_version = 2\nfamily = "same_degree"\n'
        '[[record]]\nid = "x.deg"\nclaim = "basis_degree"\nclaimed_degree = "m + 1"\n'
        '[[record]]\nid = "x.shape"\nclaim = "basis_reduces_to_bernstein"\nshape = "lam"\n'
        '[[record]]\nid = "x.sign"\nclaim = "sign_on_range"\nexpression = "alpha + lam"\n',
        encoding="utf-8",
    )
    import io

    out = io.StringIO()
    assert _verify_runner.run(paths=[bad], root=ROOT, out=out, progress=False) == 1
    text = out.getvalue()
    assert "may use n only" in text and "must be an exact number" in text
    assert "n or m and lam only, not alpha" in text
    bad.write_text(
        'schema_version = 2\nfamily = "same_degree"\n[[record]]\nid = "x.r"\n'
        'claim = "basis_nonnegative"\nparameter_range = "(1, -2]"\n',
        encoding="utf-8",
    )
    assert _verify_runner.run(paths=[bad], root=ROOT, out=io.StringIO(), progress=False) == 2


def test_an_isolated_root_shows_its_value():
    """repr(IsolatedRoot) ends with the value it isolates (its interval may span the whole
    range): the degree-6 same_degree root, 9λ² + 67λ + 74 = 0, by the quadratic formula."""
    import math

    import lambda_bezier as lb

    (root,) = lb.singular_parameters("same_degree", 6)
    want = (-67 + math.sqrt(67**2 - 4 * 9 * 74)) / 18
    assert root.coefficients == (74, 67, 9)
    assert abs(float(root) - want) <= 1e-15
    assert repr(root).endswith(f"≈ {float(root)!r})")
