"""Tangencies of exact planar curves decided exactly (issue #29): intersect_exact proves a
touching point (certified, tangent) where Krawczyk cannot (the Jacobian is singular there) and
drops a box with no common point; intersect on exact input with a tangent hit answers from it,
so a near-tangency with no real contact is not reported and near-double crossings are split.
References from SymPy (its own resultants, real roots and square roots), computed here."""

from __future__ import annotations

from fractions import Fraction as F

import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

import lambda_bezier as lb
from lambda_bezier.hazmat import exact_poly as xp

S = sp.Symbol("s")
HALF = F(1, 2)
ARCH = lb.BezierCurve([(0, 0), (HALF, 1), (1, 0)])  # y = 2 s (1 − s), peak 1/2 at s = 1/2


def bezier_of(x_poly, y_poly) -> lb.BezierCurve:
    """The Bézier curve (x(s), y(s)) for s in [0, 1] of polynomials in S with rational
    coefficients: control points b_i = Σ_{k ≤ i} C(i, k) / C(n, k) a_k from the power
    coefficients a_k (SymPy, exact)."""
    px, py = sp.Poly(x_poly, S), sp.Poly(y_poly, S)
    n = max(px.degree(), py.degree())
    coeffs = [[p.coeff_monomial(S**k) for k in range(n + 1)] for p in (px, py)]
    rows = [
        tuple(
            F(str(sum(sp.binomial(i, k) / sp.binomial(n, k) * a[k] for k in range(i + 1))))
            for a in coeffs
        )
        for i in range(n + 1)
    ]
    return lb.BezierCurve(rows)


def sympy_roots(a: lb.BezierCurve, b: lb.BezierCurve) -> list[sp.Expr]:
    """The distinct s in [0, 1] of the common points of a and b, for the curves here, which
    all have x = s (so a(s) = b(t) means t = s): SymPy's real roots of y_a(s) − y_b(s)."""
    ya, yb = sp_curve(a, S)[1], sp_curve(b, S)[1]
    diff = sp.Poly(sp.expand(ya - yb), S)
    assert sp.expand(sp_curve(a, S)[0] - S) == 0 and sp.expand(sp_curve(b, S)[0] - S) == 0
    return sorted({r for r in diff.real_roots() if 0 <= r <= 1}, key=lambda r: float(r))


def sp_curve(curve: lb.BezierCurve, x: sp.Symbol) -> list[sp.Expr]:
    rows = curve.control_points()
    n = len(rows) - 1
    return [
        sum(
            sp.binomial(n, i) * x**i * (1 - x) ** (n - i) * sp.Rational(str(r[c]))
            for i, r in enumerate(rows)
        )
        for c in range(2)
    ]


def line(y) -> lb.BezierCurve:
    return lb.BezierCurve([(0, y), (1, y)])


# ------------------------------------------------------------------------------ exact_poly
def test_sign_at_root_matches_sympy():
    """The sign of p at the root √2/2 of 2x² − 1 in (0, 1): SymPy's exact sign."""
    square = [F(-1), F(0), F(2)]
    (box,) = xp.real_roots(square, F(0), F(1))
    root = sp.sqrt(2) / 2
    for p in (
        [F(-1), F(0), F(2)],
        [F(0), F(1)],
        [F(-7, 10), F(1)],
        [F(-71, 100), F(1)],
        [F(1), F(-2), F(0), F(1)],
        [F(0), F(0), F(1), F(-1)],
    ):
        want = sp.sign(sp.nsimplify(sum(c * root**k for k, c in enumerate(p))).simplify())
        assert xp.sign_at_root(p, square, box) == int(want), p


def test_first_subresultant_gives_the_common_root():
    """f = (y − x)² − 1 and g = y² − x² − 3 meet at (1, 2) and (−1, −2): at those roots of
    Res_y(f, g) (SymPy's), −a0(x0)/a1(x0) is the common root of f(x0, y) and g(x0, y), SymPy's
    gcd of the two; either way round (the same with x and y exchanged)."""
    x, y = sp.symbols("x y")
    f_sp, g_sp = (y - x) ** 2 - 1, y**2 - x**2 - 3

    def as_dict(e):
        return {k: F(str(v)) for k, v in sp.Poly(e, x, y).as_dict().items()}

    for var, (known, other) in ((1, (x, y)), (0, (y, x))):
        a1, a0 = xp.first_subresultant(as_dict(f_sp), as_dict(g_sp), var)
        roots = sp.Poly(sp.resultant(f_sp, g_sp, other), known).real_roots()
        assert sorted(roots) == [-1, 1] if var == 1 else sorted(roots) == [-2, 2]
        for r in roots:
            common = sp.Poly(sp.gcd(f_sp.subs(known, r), g_sp.subs(known, r)), other)
            assert common.degree() == 1
            want = -common.nth(0) / common.nth(1)
            got = -xp.evaluate(a0, F(int(r))) / xp.evaluate(a1, F(int(r)))
            assert got == F(str(want))


# ------------------------------------------------------------------------------ exact
def test_an_irrational_tangency_is_certified():
    """x = s, y = (s² − 1/2)² touches y = 0 at s = √2/2 (a double root): one certified,
    tangent box holding √2/2 (exactly: lo² ≤ 1/2 ≤ hi²), where Krawczyk alone left it
    uncertified; intersect reports it once, at SymPy's √2/2 rounded."""
    quartic = bezier_of(S, (S**2 - sp.Rational(1, 2)) ** 2)
    want = sympy_roots(quartic, line(0))
    assert want == [sp.sqrt(2) / 2]
    (box,) = lb.intersect_exact(quartic, line(0))
    assert box.certified and box.tangent
    assert box.s[0] ** 2 <= HALF <= box.s[1] ** 2 and box.s[1] - box.s[0] <= F(1, 2**59)
    (hit,) = quartic.intersect(line(0))
    assert hit.kind == "tangent" and abs(hit.s - float(sp.N(want[0], 30))) <= 1e-15


@pytest.mark.parametrize("gap", [F(1, 10**13), F(1, 10**15), F(1, 10**20), F(1, 10**40)])
def test_a_near_tangency_without_contact_is_not_reported(gap):
    """The arch against y = 1/2 + gap: no common point (SymPy: no real root), though the gap
    is within the float tolerance (64 ε of the size) for gap ≤ 1e-15, where intersect used to
    report a tangency at s = 1/2."""
    assert sympy_roots(ARCH, line(HALF + gap)) == []
    assert lb.intersect_exact(ARCH, line(HALF + gap)) == []
    assert ARCH.intersect(line(HALF + gap)) == []
    assert line(HALF + gap).intersect(ARCH) == []


@pytest.mark.parametrize("gap", [F(1, 2**50), F(1, 2**60)])
def test_a_dyadic_near_tangency_is_decided_on_every_path(gap):
    """Fractions whose floats are exact (powers of two) take the compiled kernels with numba;
    their tangent hit is decided exactly too: above the arch no common point, below it two
    crossings (SymPy), by intersect and by intersect_many."""
    above, below = line(HALF + gap), line(HALF - gap)
    assert sympy_roots(ARCH, above) == [] and len(sympy_roots(ARCH, below)) == 2
    assert ARCH.intersect(above) == [] and lb.intersect_many([ARCH], [above]) == [[]]
    got = ARCH.intersect(below)
    assert [h.kind for h in got] == ["transversal", "transversal"]
    assert lb.intersect_many([ARCH], [below]) == [got]


@pytest.mark.parametrize("gap", [F(1, 10**15), F(1, 10**20), F(1, 10**30)])
def test_near_double_crossings_are_split(gap):
    """The arch against y = 1/2 − gap: two transversal crossings at s = 1/2 ± √(gap/2) (SymPy),
    reported as two where intersect used to report one tangency; t = s on this line."""
    want = sympy_roots(ARCH, line(HALF - gap))
    assert len(want) == 2
    got = ARCH.intersect(line(HALF - gap))
    assert [h.kind for h in got] == ["transversal", "transversal"]
    for h, r in zip(got, want, strict=True):
        assert abs(h.s - float(sp.N(r, 30))) <= 1e-16 and abs(h.t - h.s) <= 1e-16
    boxes = lb.intersect_exact(ARCH, line(HALF - gap))
    assert [(b.certified, b.tangent) for b in boxes] == [(True, False), (True, False)]


def test_two_curves_touching_at_an_irrational_point():
    """The quartic against its mirror image in y = 0 (x = s, y = −(s² − 1/2)²): they touch
    at s = t = √2/2 (certified, tangent); the mirror moved down by 1e-20 does not meet it."""
    quartic = bezier_of(S, (S**2 - sp.Rational(1, 2)) ** 2)
    mirror = bezier_of(S, -((S**2 - sp.Rational(1, 2)) ** 2))
    assert sympy_roots(quartic, mirror) == [sp.sqrt(2) / 2]
    (box,) = lb.intersect_exact(quartic, mirror)
    assert box.certified and box.tangent
    (hit,) = quartic.intersect(mirror)
    assert hit.kind == "tangent"
    assert abs(hit.s - float(sp.N(sp.sqrt(2) / 2, 30))) <= 1e-15 and abs(hit.t - hit.s) <= 1e-15
    lower = bezier_of(S, -((S**2 - sp.Rational(1, 2)) ** 2) - sp.Rational(1, 10**20))
    assert sympy_roots(quartic, lower) == []
    assert lb.intersect_exact(quartic, lower) == []
    # intersect decides two quartics exactly with python-flint (ie.FLINT, a product of the
    # degrees to 36); past the standard library's budget (ie.PURE, 9) the float answer stands
    assert quartic.intersect(lower) == []


def test_two_quartics_are_past_the_standard_librarys_budget(monkeypatch):
    """Without python-flint (intersect_exact.algebra() is PURE), the quartic against its
    mirror moved down by 1e-20 keeps the float answer (a tangent hit), no contact being
    exact (SymPy, above)."""
    from lambda_bezier.hazmat import intersect_exact as ie

    monkeypatch.setattr(ie, "algebra", lambda: ie.PURE)
    quartic = bezier_of(S, (S**2 - sp.Rational(1, 2)) ** 2)
    lower = bezier_of(S, -((S**2 - sp.Rational(1, 2)) ** 2) - sp.Rational(1, 10**20))
    assert [h.kind for h in quartic.intersect(lower)] == ["tangent"]


def test_a_curve_and_its_mirror_moved_apart_within_the_float_tolerance():
    """Two quadratics within intersect's budget: the arch and its mirror in y = 1/2 touch at
    (1/2, 1/2); the mirror moved up by 1e-20 meets the arch nowhere (SymPy), though within
    the float tolerance."""
    arch = bezier_of(S, 2 * S * (1 - S))
    for lift, want in ((0, [sp.Rational(1, 2)]), (sp.Rational(1, 10**20), [])):
        mirror = bezier_of(S, 1 - 2 * S * (1 - S) + lift)
        assert sympy_roots(arch, mirror) == want
        got = arch.intersect(mirror)
        assert [(h.s, h.t, h.kind) for h in got] == [(0.5, 0.5, "tangent")] * len(want)


@settings(max_examples=10, derandomize=True, deadline=None)
@given(
    st.fractions(F(1, 8), F(7, 8), max_denominator=64),
    st.fractions(F(1, 4), F(4), max_denominator=16),
    st.sampled_from([0, 1, -1]),
    st.integers(12, 30),
)
def test_parabolas_against_lines_near_their_vertex(vertex, curvature, side, digits):
    """y = c (s − v)² against y = side · 10^-digits: touching (side 0), two crossings (side
    1) or none (side −1), as SymPy says, each reported once with the right kind."""
    curve = bezier_of(S, sp.Rational(str(curvature)) * (S - sp.Rational(str(vertex))) ** 2)
    level = F(side, 10**digits)
    want = sympy_roots(curve, line(level))
    got = curve.intersect(line(level))
    assert len(got) == len(want) == (1 if side == 0 else 1 + side)
    kinds = {0: ["tangent"], 1: ["transversal", "transversal"], -1: []}[side]
    assert [h.kind for h in got] == kinds
    for h, r in zip(got, want, strict=True):
        assert abs(h.s - float(sp.N(r, 30))) <= 1e-15
