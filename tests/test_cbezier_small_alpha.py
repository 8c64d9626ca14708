"""C-Bézier curves at small alpha (the removable end alpha -> 0 of the range).

Over the atoms (1, t, cos t, sin t) the float coefficients cancel like alpha^-3 and worse, so
below the document's threshold the runtime evaluates the basis from its exact series in alpha
(derive/formulas/cbezier_series.py). Checked here against independent numerics: the functions
as the definition file writes them, differentiated by SymPy and evaluated in mpmath with
enough digits for their own cancellation (40 plus 10 per decade of alpha below 1); the limit
alpha -> 0 against the Bézier curve; energies against Gauss-Legendre quadrature in mpmath;
joins, split, geometry and batches at small alpha.
"""

from __future__ import annotations

import json
import math
from fractions import Fraction
from functools import cache
from math import comb
from pathlib import Path

import mpmath as mp
import numpy as np
import pytest
import sympy as sp
import tomllib
from conftest import family_file

import lambda_bezier as lb
from derive.families import cbezier as cb
from lambda_bezier import examples, export

DATA = Path(__file__).parent / "data" / "families"
P = [[0.0, 0.0], [1.0, 3.0], [4.0, 3.0], [5.0, 0.0]]
NAMES = ["c_bezier_cubic", "c_bezier_cubic_unit", "hc_bezier_cubic"]
ALPHAS = [1e-8, 1e-6, 1e-4, 1e-2, 0.1, 0.5, 1.0, 1.4999, 1.5, 2.0, 3.0]
U = [0.0, 0.05, 0.2, 1 / 3, 0.5, 0.7, 0.9, 0.999, 1.0]


@cache
def _family(name: str):
    return lb.load_family(str(family_file(name)))


@cache
def _reference(name: str):
    """(d^r/dt^r b_i for r = 0..2) as mpmath functions of (t, alpha), from the file's
    written formulas (t on [0, alpha], alpha as cb.A), and whether the family is in u."""
    table = tomllib.loads((family_file(name)).read_text())["family"]
    defn = cb.read_table(table)
    fns = [
        [sp.lambdify((cb.T, cb.A), sp.diff(f, cb.T, r), modules="mpmath") for f in defn.written()]
        for r in range(3)
    ]
    return fns, defn.form == "unit"


def _digits(alpha: float) -> int:
    return 40 + 10 * max(0, math.ceil(-math.log10(alpha)))


def _want(name: str, points, alpha: float, u: float, order: int) -> list:
    """The curve's derivative of `order` in its own parameter at u (of [0, 1]), mpmath."""
    fns, unit = _reference(name)
    a = mp.mpf(alpha)
    t = a * mp.mpf(u)
    rate = a**order if unit else 1  # d/du = alpha d/dt
    return [
        sum(fns[order][i](t, a) * points[i][d] for i in range(len(points))) * rate
        for d in range(len(points[0]))
    ]


@pytest.mark.parametrize("name", NAMES)
def test_evaluate_derivatives_and_curvature_against_mpmath(name):
    """Relative to the largest value of each quantity over the curve, at every alpha from
    1e-8 to the top of the range. Below the series' threshold 3/2: p, p', p'' within 5e-15,
    the curvature within 1e-14 (measured worst 2.1e-15 and 2.3e-15). Above it, the atom
    form: 2e-14 and 5e-14 (measured worst 1.1e-15 for the trigonometric cubic, 8.4e-15 and
    1.1e-14 for the hyperbolic one at alpha = 1.5). Before the series: 1e-7 at alpha = 0.1,
    and a refusal below about 0.1."""
    fam = _family(name)
    unit = fam.form == "unit"
    for alpha in [*ALPHAS, fam.hi]:
        tol, tol_k = (5e-15, 1e-14) if alpha < 1.5 else (2e-14, 5e-14)
        c = fam.curve(P, alpha=alpha)
        own = np.array(U) if unit else alpha * np.array(U)
        with mp.workdps(_digits(alpha)):
            want = [[_want(name, P, alpha, u, r) for u in U] for r in range(3)]
            kappa = [
                (x1 * y2 - y1 * x2) / mp.power(x1 * x1 + y1 * y1, 1.5)
                for (x1, y1), (x2, y2) in zip(want[1], want[2], strict=True)
            ]
        for r in range(3):
            got = c.derivative(own, r)
            ref = np.array([[float(v) for v in row] for row in want[r]])
            err = np.abs(got - ref).max() / np.abs(ref).max()
            assert err < tol, (name, alpha, r, err)
        got_k = c.curvature(own)
        ref_k = np.array([float(k) for k in kappa])
        err = np.abs(got_k - ref_k).max() / np.abs(ref_k).max()
        assert err < tol_k, (name, alpha, "curvature", err)


@pytest.mark.parametrize("name", NAMES)
def test_the_limit_is_the_bezier_cubic(name):
    """The series' first term is the Bernstein cubic exactly (the document), and a curve at
    alpha = 1e-6 is the Bézier curve of its control points up to O(alpha^2) in value and in
    the derivatives in u."""
    fam = _family(name)
    doc = json.loads((family_file(name, ".derived.json")).read_text())
    first = [dict(row)[0] for row in doc["small_alpha"]["series"]]
    for i, coeffs in enumerate(first):
        bern = [Fraction(0)] * 4  # B_i^3(u) = C(3, i) u^i (1 - u)^(3 - i), expanded here
        for j in range(4 - i):
            bern[i + j] = Fraction(comb(3, i) * comb(3 - i, j) * (-1) ** j)
        assert [Fraction(v) for v in coeffs] == bern, (i, coeffs)
    alpha = 1e-6
    c = fam.curve(P, alpha=alpha)
    bez = lb.BezierCurve(P)
    u = np.linspace(0, 1, 11)
    scale = 1.0 if fam.form == "unit" else alpha
    for r in range(4):
        got = c.derivative(u * scale, r) * scale**r
        want = bez.derivative(u, r) if r else bez.evaluate(u)
        assert np.abs(got - want).max() < 1e-10 * max(1.0, np.abs(want).max()), r


@pytest.mark.parametrize("name", ["c_bezier_cubic", "hc_bezier_cubic"])
def test_energy_at_small_alpha_against_mpmath_quadrature(name):
    """E_k by the curve (64-point Gauss-Legendre in floats) against a 24-point rule in
    mpmath on the written functions (exact to far below 1e-30 for this analytic integrand
    on so short an interval)."""
    fam = _family(name)
    nodes, weights = np.polynomial.legendre.leggauss(24)
    for alpha in (1e-4, 0.05, 0.7):
        c = fam.curve(P, alpha=alpha)
        for k in (1, 2):
            with mp.workdps(_digits(alpha)):
                total = mp.mpf(0)
                for x, w in zip(nodes, weights, strict=True):
                    d = _want(name, P, alpha, (1 + float(x)) / 2, k)
                    total += w * (d[0] ** 2 + d[1] ** 2)
                want = float(total * alpha / 2)
            assert abs(c.energy(k) - want) < 1e-13 * want, (alpha, k, c.energy(k), want)


@pytest.mark.parametrize("alpha", [1e-3, 1e-6])
@pytest.mark.parametrize("name", ["c_bezier_cubic", "c_bezier_cubic_unit"])
def test_join_into_a_small_alpha_segment(name, alpha):
    """A C2 join from a curve at alpha = 2 into one at a small alpha: the new segment's
    start derivatives (mpmath, written functions, at its float control points) equal the
    first curve's end ones, to the rounding the float points allow: |b_i^(r)(0)| grows like
    alpha^-r, so a point rounded by 2^-53 |P| moves the r-th derivative by that much. (At
    1e-6 the join engine's singularity test, on the unscaled rows, refused this before.)"""
    fam = _family(name)
    first = fam.curve(P, alpha=2.0)
    nxt = lb.join(first, "C2", 3, params={"alpha": alpha}, rest=[[9.0, 1.0]])
    pts = np.asarray(nxt.points).tolist()
    ends = first.end_derivatives(2)
    fns, unit = _reference(name)
    size = float(np.abs(pts).max())
    with mp.workdps(_digits(alpha)):
        for r in range(3):
            want = [float(v) for v in _want(name, pts, alpha, 0.0, r)]
            rate = alpha**r if unit else 1
            weight = float(sum(abs(f(mp.mpf(0), mp.mpf(alpha))) for f in fns[r]) * rate)
            tol = 4 * np.finfo(float).eps * (size * weight + np.abs(ends[r]).max())
            assert np.abs(np.array(want) - ends[r]).max() <= tol, (r, want, ends[r], tol)


def test_split_geometry_and_batches_at_small_alpha():
    fam = _family("c_bezier_cubic")
    alpha = 1e-4
    c = fam.curve(P, alpha=alpha)
    left, right = c.split(0.3e-4)
    assert left.alpha == pytest.approx(0.3e-4) and right.alpha == pytest.approx(0.7e-4)
    for s in np.linspace(0, 0.3e-4, 5):
        assert np.allclose(left.evaluate(s), c.evaluate(s), rtol=0, atol=1e-13)
    for s in np.linspace(0, 0.7e-4, 5):
        assert np.allclose(right.evaluate(s), c.evaluate(0.3e-4 + s), rtol=0, atol=1e-13)
    grid = c.evaluate(np.linspace(0, alpha, 20001))
    lo, hi = c.bounding_box()
    assert np.all(grid >= lo - 1e-12) and np.all(grid <= hi + 1e-12)
    assert np.allclose(lo, grid.min(axis=0), atol=1e-8)
    assert np.allclose(hi, grid.max(axis=0), atol=1e-8)
    q = np.array([2.0, 3.0])
    found = c.closest_point(q)
    assert found.distance <= np.linalg.norm(grid - q, axis=1).min() + 1e-12
    many = np.array([P, np.array(P) * 2.0])
    t = np.linspace(0, alpha, 7)
    got = lb.evaluate_many(many, t, fam, params={"alpha": alpha})
    assert np.allclose(got[1], fam.curve(many[1], alpha=alpha).evaluate(t), rtol=1e-15)
    d2 = lb.evaluate_many(many, t, fam, k=2, params={"alpha": alpha})
    assert np.allclose(d2[0], c.derivative(t, 2), rtol=1e-14)
    comp = lb.CompositeCurve([c]).join("C2", 3, params={"alpha": 1e-6}, rest=[[7.0, 1.0]])
    for shape in (c, comp):
        back = export.from_json(export.to_json(shape), family=fam)
        u = np.linspace(*shape.domain, 9)
        assert np.array_equal(back.evaluate(u), shape.evaluate(u))


def test_the_old_refusals_are_gone_and_the_floor_is_clear():
    fam = _family("c_bezier_cubic")
    for alpha in (0.01, 1e-3, 1e-4, 1e-8, 1e-50):
        fam.curve(P, alpha=alpha).evaluate(alpha / 3)
    with pytest.raises(ValueError, match=r"alpha = 1e-300 is too small .* underflows"):
        fam.curve(P, alpha=1e-300)
    unit = _family("c_bezier_cubic_unit")  # in u on [0, 1] nothing underflows
    got = unit.curve(P, alpha=1e-300).evaluate(0.5)
    assert np.allclose(got, lb.BezierCurve(P).evaluate(0.5), rtol=1e-15)


@pytest.mark.parametrize(
    "change",
    [
        lambda sa: sa.update(series="x"),
        lambda sa: sa.update(below_float="3/2"),
        lambda sa: sa["series"].pop(),
        lambda sa: sa["series"][0].append([300, ["1"]]),
        lambda sa: sa["series"][0].append([2, ["1/0"]]),
        lambda sa: sa["series"][0].append([2, ["x" * 300]]),
        lambda sa: sa["series"][0].append([2, [1.5]]),
    ],
)
def test_a_malformed_series_is_refused_by_name(change):
    from lambda_bezier.cbezier_family import CBezierError, CBezierFamily

    doc = json.loads((examples.path("c_bezier_cubic.derived.json")).read_text())
    change(doc["small_alpha"])
    with pytest.raises(CBezierError, match="small_alpha"):
        CBezierFamily(doc, "c.json", "t", {})


@pytest.mark.parametrize("name", ["c_bezier_cubic", "hc_bezier_cubic", "c_bezier_cubic_unit"])
def test_energy_matrix_at_small_alpha(name):
    """fam.energy_matrix below the threshold (the float Gram entries cancel there: refused
    before) against a 16-point Gauss-Legendre rule in mpmath on the written functions (the
    integrands are entire; at alpha <= 1.2 the rule's error is far below 1e-20), in t on
    [0, alpha] whatever the form; and P^T G P is the curve's energy."""
    fam = _family(name)
    nodes, weights = np.polynomial.legendre.leggauss(16)
    for alpha in (1e-3, 1.2):
        for k in (1, 3):
            got = fam.energy_matrix(alpha, k)
            with mp.workdps(_digits(alpha)):
                a = mp.mpf(alpha)
                vals = [
                    [fns_k(a * (1 + mp.mpf(float(x))) / 2, a) for fns_k in _derivatives(name, k)]
                    for x in nodes
                ]
                want = np.array(
                    [
                        [
                            float(
                                sum(w * v[i] * v[j] for w, v in zip(weights, vals, strict=True))
                                * a
                                / 2
                            )
                            for j in range(4)
                        ]
                        for i in range(4)
                    ]
                )
            assert np.abs(got - want).max() <= 1e-13 * np.abs(want).max(), (alpha, k)
    c = fam.curve(P, alpha=0.3)
    pts = np.array(P)
    gram = fam.energy_matrix(0.3, 2)
    rate = 0.3**3 if fam.form == "unit" else 1.0  # E_k in u is alpha^(2k-1) E_k in t
    assert c.energy(2) == pytest.approx(rate * np.einsum("ij,id,jd->", gram, pts, pts), rel=1e-13)


@cache
def _derivatives(name: str, k: int):
    table = tomllib.loads((family_file(name)).read_text())["family"]
    defn = cb.read_table(table)
    return [
        sp.lambdify((cb.T, cb.A), sp.diff(f, cb.T, k), modules="mpmath") for f in defn.written()
    ]
