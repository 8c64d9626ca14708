"""Issue #30, second acceptance pass: families from the literature, each defined only by a file
in tests/data/families/lit_*.toml, checked against its paper's construction written out here
in mpmath (direct evaluation, mpmath.diff for end derivatives and joins, mpmath.quad for the
energies, a dense grid and an exact polish for the optimum). None of the references reads the
derived documents or the runtime's basis.

The families (written from the papers' constructions, not from the project's other files):
- lit_han_trig2: Han, Ma, Huang (2009), cubic trigonometric, (lam, mu) in [-2, 1]^2;
  lit_han_trig2_wide the same functions on [-3, 1] x [-2, 2], where non-negativity fails;
- lit_han_quad_trig: Han (2002), quadratic trigonometric, one lam in [-1, 1] (b_1 = 0 at -1);
- lit_hyp_quad: a hyperbolic quadratic written in sinh and cosh (x = 1 - cosh t + sinh t);
- lit_at_two: algebraic-trigonometric {1, t, sin(pi t/2), cos(pi t/2)}, one parameter per end;
- lit_yan_liang: a quartic for four control points with one parameter per end (Yan-Liang style);
- lit_per_leg: one parameter per leg of the control polygon, lam(i), degrees 2..3.
"""

from __future__ import annotations

import itertools
import json
import math
from collections.abc import Callable, Sequence
from fractions import Fraction
from pathlib import Path

import mpmath as mp
import numpy as np
import pytest

import lambda_bezier as lb

DATA = Path(__file__).parent / "data" / "families"


class _HalfPi:
    """pi/2 at the working precision of the moment (a module constant would be 15 digits)."""

    def __rsub__(self, other):
        return mp.pi / 2 - other

    def __truediv__(self, other):
        return mp.pi / 2 / other

    def __float__(self):
        return math.pi / 2

    def mp(self):
        return mp.pi / 2


HALF_PI = _HalfPi()


def _hi(hi) -> mp.mpf:
    return hi.mp() if isinstance(hi, _HalfPi) else mp.mpf(hi)


def _han_trig2(t, lam, mu):
    s, c = mp.sin(t), mp.cos(t)
    return [
        (1 - s) ** 2 * (1 - lam * s),
        s * (1 - s) * (2 + lam * (1 - s)),
        c * (1 - c) * (2 + mu * (1 - c)),
        (1 - c) ** 2 * (1 - mu * c),
    ]


def _han_quad(t, lam):
    s, c = mp.sin(t), mp.cos(t)
    return [(1 - s) * (1 - lam * s), (1 + lam) * (s + c - 1), (1 - c) * (1 - lam * c)]


def _hyp_quad(t, lam):
    x = 1 - mp.exp(-t)
    b0 = (1 - x) ** 2 * (1 - lam * x)
    b2 = x**2 * (1 - lam * (1 - x))
    return [b0, 1 - b0 - b2, b2]


def _at_two(t, lam, mu):
    s, c = mp.sin(mp.pi * t / 2), mp.cos(mp.pi * t / 2)
    return [
        1 - t - (1 - lam) * (s - t),
        (1 - lam) * (s - t),
        (1 - mu) * (c - 1 + t),
        t - (1 - mu) * (c - 1 + t),
    ]


def _yan_liang(t, lam, mu):
    return [
        (1 - t) ** 3 * (1 - lam * t),
        t * (1 - t) ** 2 * (3 + lam * (1 - t)),
        t**2 * (1 - t) * (3 + mu * t),
        t**3 * (1 - mu + mu * t),
    ]


def _per_leg(t, *lams):
    n = len(lams)
    lam = dict(enumerate(lams))
    return [
        math.comb(n, i) * t**i * (1 - t) ** (n - i)
        + lam.get(i, 0) * t ** (i + 1) * (1 - t) ** (n - i)
        - lam.get(i - 1, 0) * t**i * (1 - t) ** (n - i + 1)
        for i in range(n + 1)
    ]


# name: (reference basis, domain end, parameter names, box, symmetry swap (a map of values)
# or None, whether it is affine in its parameters)
FAMILIES: dict[str, tuple] = {
    "lit_han_trig2": (_han_trig2, HALF_PI, ("lam", "mu"), ((-2, 1), (-2, 1)), lambda p: p[::-1]),
    "lit_han_quad_trig": (_han_quad, HALF_PI, ("lam",), ((-1, 1),), lambda p: p),
    "lit_hyp_quad": (_hyp_quad, 1, ("lam",), ((-1, 1),), None),
    "lit_at_two": (_at_two, 1, ("lam", "mu"), ((0, 1), (0, 1)), lambda p: p[::-1]),
    "lit_yan_liang": (_yan_liang, 1, ("lam", "mu"), ((-3, 1), (-3, 1)), lambda p: p[::-1]),
}
# the indexed family at degree 3, its three parameters one name each for the references
PER_LEG_3 = (_per_leg, 1, ("lam_0", "lam_1", "lam_2"), ((-1, 1),) * 3, None)
POINTS = {
    2: [(0, 0), (Fraction(3, 2), 3), (4, 0)],
    3: [(0, 0), (1, 3), (3, Fraction(5, 2)), (4, 0)],
}


@pytest.fixture(scope="module")
def fams() -> dict[str, object]:
    return {name: lb.load_family(DATA / f"{name}.toml") for name in [*FAMILIES, "lit_per_leg"]}


def _curve_ref(basis: Callable, points: Sequence, params: Sequence) -> Callable:
    def at(t):
        b = basis(t, *params)
        return [mp.fsum(b[i] * _mpf(points[i][d]) for i in range(len(b))) for d in range(2)]

    return at


def _mpf(x) -> mp.mpf:
    if isinstance(x, Fraction):
        return mp.mpf(x.numerator) / x.denominator
    return mp.mpf(x)


def _sample_params(box, count: int) -> list[tuple[Fraction, ...]]:
    grid = [
        [Fraction(lo), Fraction(hi), Fraction(lo + hi, 2), lo + Fraction(hi - lo, 7)]
        for lo, hi in box
    ]
    return list(itertools.islice(itertools.product(*grid), count))


# ---- the document's decisions against the construction ------------------------------------


def _number(value, constant: mp.mpf) -> mp.mpf:
    # a document's exact number: a rational string, or [[coefficient, exponent], ...] meaning
    # the sum of coefficient * C^exponent (C = pi, or e^W for a hyperbolic family)
    if isinstance(value, str):
        return _mpf(Fraction(value))
    return mp.fsum(_mpf(Fraction(c)) * constant**e for c, e in value)


def _constant(text: str) -> mp.mpf:
    return (
        mp.pi
        if text == "pi"
        else mp.exp(_mpf(Fraction(text.removeprefix("exp(").removesuffix(")"))))
    )


def _poly(monomials: dict, params, constant: mp.mpf) -> mp.mpf:
    total = mp.mpf(0)
    for key, value in monomials.items():
        term = _number(value, constant)
        for x, e in zip(params, map(int, key.split(",")), strict=True):
            term *= _mpf(x) ** e
        total += term
    return total


@pytest.mark.parametrize("name", list(FAMILIES))
def test_end_values_and_derivatives_in_closed_form(name):
    # every entry of `endpoints` (d^r b_i at the start, d^r b_(n-j) at the end, r = 0..3, as a
    # polynomial in the parameters) against mpmath.diff of the construction at sampled values
    basis, hi, names, box, _, *_ = FAMILIES[name]
    doc = json.loads((DATA / f"{name}.derived.json").read_text())
    ends = doc["endpoints"]
    (n_text,) = [key for key in ends if key.isdigit()]
    table, n = ends[n_text], int(n_text)
    seen, samples = 0, _sample_params(box, 6)
    with mp.workdps(40):
        constant = _constant(ends.get("constant", "pi"))
        for params in samples:
            vals = [_mpf(p) for p in params]
            for r in range(4):
                for j in range(n + 1):
                    start = mp.diff(lambda t, j=j, v=vals: basis(t, *v)[j], 0, r)
                    end = mp.diff(lambda t, j=j, v=vals: basis(t, *v)[n - j], _hi(hi), r)
                    for key, ref in ((f"start,{r},{j}", start), (f"end,{r},{j}", end)):
                        assert (
                            abs(_poly(table.get(key, {}), params, constant) - ref)
                            < mp.mpf(10) ** -25
                        ), (key, params)
                        seen += 1
    assert seen == len(samples) * 4 * (n + 1) * 2


@pytest.mark.parametrize("name", list(FAMILIES))
def test_symmetry_decision(name):
    basis, hi, names, box, swap = FAMILIES[name][:5]
    doc = json.loads((DATA / f"{name}.derived.json").read_text())
    with mp.workdps(30):
        n = len(basis(mp.mpf(0), *[0] * len(names))) - 1
        for params in _sample_params(box, 5):
            vals = [_mpf(p) for p in params]
            for t in (mp.mpf("0.1"), mp.mpf("0.77")):
                b, mirrored = basis(t, *vals), basis(_hi(hi) - t, *(swap(vals) if swap else vals))
                ok = all(abs(b[i] - mirrored[n - i]) < mp.mpf(10) ** -25 for i in range(n + 1))
                assert ok == (swap is not None)
    if swap is None:
        assert doc["symmetry"] is None
    else:
        expected = list(swap(list(names)))
        assert doc["symmetry"]["swap"] == expected


def _rank_drop(basis, params, n: int) -> mp.mpf:
    # the least singular value of the functions' values at n + 3 points of [0, 1] (inside
    # every domain here): zero exactly when they are linearly dependent there
    ts = [mp.mpf(k + 1) / (n + 4) for k in range(n + 3)]
    values = mp.matrix([[mp.mpf(v) for v in basis(t, *params)] for t in ts])
    return min(mp.svd_r(values, compute_uv=False))


@pytest.mark.parametrize(
    ("name", "singular"),
    [
        ("lit_han_trig2", []),
        ("lit_han_quad_trig", ["-1"]),  # b_1 = (1 + lam)(sin t + cos t - 1) = 0
        ("lit_hyp_quad", []),
    ],
)
def test_independence_of_one_order(name, singular):
    basis, _, names, box, *_ = FAMILIES[name]
    doc = json.loads((DATA / f"{name}.derived.json").read_text())
    assert doc["linear_independence"]["singular"] == singular
    assert doc["linear_independence"]["independent"] == (not singular)
    with mp.workdps(30):
        n = len(basis(mp.mpf(0), *[0] * len(names))) - 1
        for x in singular:
            assert _rank_drop(basis, [_mpf(Fraction(x))], n) < mp.mpf(10) ** -25
        for params in _sample_params(box, 6):
            if [str(p) for p in params] != singular:
                assert _rank_drop(basis, [_mpf(p) for p in params], n) > mp.mpf(10) ** -8


def test_independence_fails_on_two_edges_of_the_at_box():
    # lam = 1 gives b_1 = 0 and mu = 1 gives b_2 = 0: the document names a point of each line
    doc = json.loads((DATA / "lit_at_two.derived.json").read_text())
    points = doc["linear_independence"]["singular"]
    assert not doc["linear_independence"]["independent"]
    on = {("lam" if Fraction(p["lam"]) == 1 else "mu") for p in points}
    assert on == {"lam", "mu"}
    with mp.workdps(30):
        for p in points:
            assert (
                _rank_drop(_at_two, [_mpf(Fraction(p["lam"])), _mpf(Fraction(p["mu"]))], 3)
                < mp.mpf(10) ** -25
            )
        assert _rank_drop(_at_two, [mp.mpf("0.5"), mp.mpf("0.25")], 3) > mp.mpf(10) ** -8


def test_independence_of_the_quartic_fails_at_one_corner():
    doc = json.loads((DATA / "lit_yan_liang.derived.json").read_text())
    assert doc["singular_parameters"]["counterexample"]["lam"] == "-3"
    assert doc["singular_parameters"]["counterexample"]["mu"] == "-3"
    with mp.workdps(30):  # b_1 = b_2 = 3 t^2 (1 - t)^2 there
        assert _rank_drop(_yan_liang, [-3, -3], 3) < mp.mpf(10) ** -25
        assert _rank_drop(_yan_liang, [-3, -2], 3) > mp.mpf(10) ** -8


@pytest.mark.parametrize("name", list(FAMILIES))
def test_nonnegative_on_the_papers_box(name):
    # evidence for the exact decision: no negative value on a dense grid of box x domain
    basis, hi, names, box, *_ = FAMILIES[name]
    doc = json.loads((DATA / f"{name}.derived.json").read_text())
    assert doc["nonnegative_over_box"]["nonnegative"] is True
    grids = [np.linspace(lo, h, 9) for lo, h in box]
    ts = np.linspace(0, float(hi), 41)
    least = min(
        float(min(basis(mp.mpf(t), *map(mp.mpf, p)))) for p in itertools.product(*grids) for t in ts
    )
    assert least > -1e-12


def test_nonnegativity_fails_on_part_of_a_wider_box():
    # lam in [-3, 1], mu in [-2, 2]: b_1 = s (1 - s)(2 + lam (1 - s)) < 0 for lam < -2 and
    # small s; the counterexample point is checked by the construction
    doc = json.loads((DATA / "lit_han_trig2_wide.derived.json").read_text())
    cex = doc["nonnegative_over_box"]["counterexample"]
    assert doc["nonnegative_over_box"]["nonnegative"] is False
    lam, mu = Fraction(cex["lam"]), Fraction(cex["mu"])
    assert -3 <= lam <= 1 and -2 <= mu <= 2
    tan_half = Fraction(cex["t"].split("atan(")[1].split(")")[0])
    with mp.workdps(40):
        t = 2 * mp.atan(_mpf(tan_half))
        value = _han_trig2(t, _mpf(lam), _mpf(mu))[cex["i"]]
        assert value < 0
        assert abs(value - _mpf(Fraction(cex["value"]))) < mp.mpf(10) ** -30


# ---- energies, optimum ------------------------------------------------------------------


def _energy_ref(basis, hi, points, params, k: int) -> mp.mpf:
    vals = [_mpf(p) for p in params]
    curve = _curve_ref(basis, points, vals)

    def integrand(t):
        return mp.fsum(mp.diff(lambda x, d=d: curve(x)[d], t, k) ** 2 for d in range(2))

    return mp.quad(integrand, [0, _hi(hi) / 2, _hi(hi)])


@pytest.mark.parametrize("name", list(FAMILIES))
@pytest.mark.parametrize("k", [1, 2, 3])
def test_energy_is_exact(fams, name, k):
    basis, hi, names, box, *_ = FAMILIES[name]
    fam = fams[name]
    n = len(basis(mp.mpf(0), *[0] * len(names))) - 1
    params = _sample_params(box, 5)[-1]
    curve = fam.curve(POINTS[n], **dict(zip(names, params, strict=True)))
    with mp.workdps(30):
        ref = _energy_ref(basis, hi, POINTS[n], params, k)
    got = curve.energy(k)
    assert abs(float(got) - float(ref)) <= 1e-12 * float(ref)


def _quadratic_energy(basis, hi, points, names, k: int):
    # E_k is a quadratic in the parameters (the basis is affine in them): fitted exactly
    # through mpmath energies at 1 + J + J(J+1)/2 points
    j = len(names)
    nodes = [tuple([0] * j)]
    nodes += [tuple(int(a == b) for b in range(j)) for a in range(j)]
    nodes += [
        tuple(int(b in (a, c)) + int(a == c == b) for b in range(j))
        for a in range(j)
        for c in range(a, j)
    ]
    monos = [()] + [(a,) for a in range(j)] + [(a, c) for a in range(j) for c in range(a, j)]
    rows = [[mp.fprod(mp.mpf(x[i]) for i in m) for m in monos] for x in nodes]
    rhs = [_energy_ref(basis, hi, points, x, k) for x in nodes]
    coef = mp.lu_solve(mp.matrix(rows), mp.matrix(rhs))
    return lambda x: mp.fsum(coef[i] * mp.fprod(x[a] for a in m) for i, m in enumerate(monos))


@pytest.mark.parametrize(
    ("name", "points", "k", "inside"),
    [
        ("lit_han_trig2", [(0, 0), (1, 5), (3, -4), (4, 0)], 2, True),
        ("lit_han_trig2", [(0, 0), (0, 3), (4, 3), (4, 0)], 1, False),  # a corner
        ("lit_han_trig2", [(0, 0), (-2, 3), (3, 2), (4, 0)], 1, False),  # the face lam = -2
        ("lit_han_trig2", [(0, 0), (-2, 3), (3, 2), (4, 0)], 3, False),  # the face mu = 1
        ("lit_yan_liang", [(0, 0), (1, 5), (3, -4), (4, 0)], 2, True),
        ("lit_yan_liang", [(0, 0), (-2, 3), (6, 3), (4, 0)], 2, False),  # the singular corner
        ("lit_yan_liang", [(0, 0), (1, 4), (5, 1), (4, 0)], 2, False),  # the face mu = -3
        ("lit_han_quad_trig", [(0, 0), (2, 3), (4, 0)], 2, True),
        ("lit_at_two", [(0, 0), (1, 2), (3, 2), (4, 0)], 2, True),  # the segment, E_2 = 0
        ("lit_hyp_quad", [(0, 0), (2, 3), (4, 0)], 2, None),
        ("lit_hyp_quad", [(0, 0), (2, 8), (4, 0)], 3, False),
        ("lit_per_leg", [(0, 0), (1, 3), (3, 3), (4, 0)], 2, None),
        ("lit_per_leg", [(0, 0), (-3, 4), (7, 4), (4, 0)], 1, None),
    ],
)
def test_optimal_parameters_against_a_dense_grid(fams, name, points, k, inside):
    basis, hi, names, box, *_ = FAMILIES.get(name) or PER_LEG_3
    steps = 80 if len(names) <= 2 else 16
    with mp.workdps(30):
        energy = _quadratic_energy(basis, hi, points, names, k)
        # the dense grid, then coordinate descent (each step the exact clamped 1D vertex)
        grids = [[lo + (h - lo) * mp.mpf(i) / steps for i in range(steps + 1)] for lo, h in box]
        best = min(itertools.product(*grids), key=energy)
        polished = list(best)
        for _ in range(60):  # coordinate descent: each 1D step is the exact clamped vertex
            for a, (lo, h) in enumerate(box):
                e0, ep, em = energy(polished), None, None
                step = mp.mpf(1) / 1000
                ep = energy([x + step * (i == a) for i, x in enumerate(polished)])
                em = energy([x - step * (i == a) for i, x in enumerate(polished)])
                curv = (ep + em - 2 * e0) / step**2
                slope = (ep - em) / (2 * step)
                polished[a] = min(max(polished[a] - slope / curv, lo), h)
        ref_energy = energy(polished)
        # the free optimum: the quadratic's gradient and Hessian by exact central differences
        j, h = len(names), mp.mpf(1)
        unit = [[h * (a == b) for b in range(j)] for a in range(j)]
        zero = [mp.mpf(0)] * j
        grad = [(energy(unit[a]) - energy([-x for x in unit[a]])) / 2 for a in range(j)]
        hess = mp.matrix(j, j)
        for a in range(j):
            for b in range(j):
                plus = [x + y for x, y in zip(unit[a], unit[b], strict=True)]
                hess[a, b] = (
                    energy(plus) - energy(unit[a]) - energy(unit[b]) + energy(zero)
                    if a != b
                    else energy(unit[a]) + energy([-x for x in unit[a]]) - 2 * energy(zero)
                )
        free = mp.lu_solve(hess, -mp.matrix(grad))
        free_inside = all(lo - 1e-12 <= free[a] <= h_ + 1e-12 for a, (lo, h_) in enumerate(box))
    got = lb.optimal_parameters(points, k, family=fams[name])
    if name == "lit_per_leg":  # one value per index, by the indexed name
        assert set(got.values) == {"lam"}
        got_point = [float(x) for x in got["lam"]]
    else:
        assert set(got.values) == set(names)
        got_point = [float(got[x]) for x in names]
    assert float(got.energy) == pytest.approx(float(ref_energy), rel=1e-10)
    assert got_point == pytest.approx([float(x) for x in polished], abs=1e-7)
    assert got.free_inside == free_inside
    if inside is not None:
        assert got.free_inside == inside
    if not free_inside:  # the boundary names the parameters held at an end, and only them
        on_face = {
            x
            for x, v, (lo, h) in zip(names, polished, box, strict=True)
            if abs(v - lo) < 1e-9 or abs(v - h) < 1e-9
        }
        assert {x for x in names if f"{x} = " in got.boundary} == on_face, got.boundary


# ---- rational form, evaluation, curves by keyword -------------------------------------------


@pytest.mark.parametrize(
    ("name", "params"),
    [("lit_han_trig2", (Fraction(1, 2), -1)), ("lit_han_quad_trig", (Fraction(-1, 3),))],
)
def test_rational_bezier_is_exact(fams, name, params):
    basis, hi, names, *_ = FAMILIES[name]
    n = len(params) + 1 if name == "lit_han_trig2" else 2
    points = POINTS[n]
    curve = fams[name].curve(points, params=dict(zip(names, params, strict=True)))
    rat = curve.to_rational_bezier()
    weights = rat.control_weights()
    ctrl = rat.control_points()
    assert all(isinstance(w, Fraction) for w in weights)
    m = len(weights) - 1
    for s in (Fraction(0), Fraction(1, 3), Fraction(5, 7), Fraction(1)):
        bern = [math.comb(m, i) * s**i * (1 - s) ** (m - i) for i in range(m + 1)]
        den = sum(w * b for w, b in zip(weights, bern, strict=True))
        exact = [
            sum(w * b * p[d] for w, b, p in zip(weights, bern, ctrl, strict=True)) / den
            for d in range(2)
        ]
        with mp.workdps(40):
            ref = _curve_ref(basis, points, [_mpf(p) for p in params])
            t = 2 * mp.atan(_mpf(s))
            for d in range(2):
                assert abs(_mpf(exact[d]) - ref(t)[d]) < mp.mpf(10) ** -35
    # geometry reports the family's own t
    t0 = 0.7
    assert curve.closest_point(curve.evaluate(t0)).t == pytest.approx(t0, abs=1e-9)
    first, _ = curve.split(t0)
    assert first.evaluate(1.0) == pytest.approx(curve.evaluate(t0), abs=1e-12)


def test_hyperbolic_rational_form_in_floats(fams):
    curve = fams["lit_hyp_quad"].curve(POINTS[2], lam=Fraction(1, 2))
    rat = curve.to_rational_bezier()
    ref = _curve_ref(_hyp_quad, POINTS[2], [mp.mpf(1) / 2])
    for t in (0.0, 0.3, 0.9, 1.0):
        s = float(curve.s_of_t(t))
        assert rat.evaluate(s) == pytest.approx([float(x) for x in ref(mp.mpf(t))], abs=1e-13)
    assert curve.closest_point(curve.evaluate(0.4)).t == pytest.approx(0.4, abs=1e-9)


@pytest.mark.parametrize("name", [*FAMILIES, "lit_per_leg"])
def test_curve_by_keyword_params_and_evaluate_many(fams, name):
    if name == "lit_per_leg":
        basis, hi, names, params = _per_leg, 1, ("lam",), ([Fraction(1, 2), Fraction(-1, 3), 1],)
        points, ref_params = POINTS[3], params[0]
    else:
        basis, hi, names, box, *_ = FAMILIES[name]
        params = _sample_params(box, 4)[-1]
        ref_params = params
        points = POINTS[len(basis(mp.mpf(0), *[0] * len(names))) - 1]
    fam = fams[name]
    by_name = fam.curve(points, **dict(zip(names, params, strict=True)))
    by_dict = fam.curve(points, params=dict(zip(names, params, strict=True)))
    ts = np.linspace(0, float(hi), 2001)
    assert np.array_equal(by_name.evaluate(ts), by_dict.evaluate(ts))
    many = lb.evaluate_many([points, points], ts, fam, params=dict(zip(names, params, strict=True)))
    ref = _curve_ref(basis, points, [_mpf(Fraction(p)) for p in ref_params])
    expected = np.array([[float(v) for v in ref(mp.mpf(t))] for t in ts[::50]])
    assert many.shape == (2, len(ts), 2)
    assert np.allclose(many[0, ::50], expected, atol=1e-13, rtol=0)
    assert np.allclose(by_name.evaluate(ts[::50]), expected, atol=1e-13, rtol=0)


# ---- joins, composites ------------------------------------------------------------------

SECOND = {  # family: (degree, parameters by name)
    "lit_han_trig2": (3, {"lam": Fraction(1, 2), "mu": -1}),
    "lit_han_quad_trig": (2, {"lam": Fraction(-1, 2)}),
    "lit_hyp_quad": (2, {"lam": Fraction(1, 3)}),
    "lit_at_two": (3, {"lam": Fraction(1, 4), "mu": Fraction(1, 2)}),
    "lit_yan_liang": (3, {"lam": Fraction(-1, 2), "mu": 1}),
    "lit_per_leg": (3, {"lam": [Fraction(1, 2), 0, Fraction(-1, 4)]}),
    "bezier": (3, {}),
    "bernstein_like": (3, {"lam": Fraction(1, 4)}),
}


def _reference(name: str, points, params: dict) -> tuple[Callable, mp.mpf] | None:
    # the construction's curve and its domain end, None for a built-in family
    if name == "lit_per_leg":
        lams = [_mpf(Fraction(x)) for x in params["lam"]]
        return _curve_ref(_per_leg, points, lams), mp.mpf(1)
    if name not in FAMILIES:
        return None
    basis, hi, names, *_ = FAMILIES[name]
    return _curve_ref(basis, points, [_mpf(Fraction(params[x])) for x in names]), _hi(hi)


def _ends(curve, ref, at_end: bool) -> list[np.ndarray]:
    # the curve's position and first two derivatives at an end: by mpmath.diff of the
    # construction, or the runtime's own for a built-in family
    if ref is None:
        t = 1.0 if at_end else 0.0
        return [np.asarray(curve.evaluate(t))] + [
            np.asarray(curve.derivative(t, r)) for r in (1, 2)
        ]
    at, hi = ref
    x = hi if at_end else mp.mpf(0)
    return [
        np.array([float(mp.diff(lambda s, d=d: at(s)[d], x, r)) for d in range(2)])
        for r in range(3)
    ]


@pytest.mark.parametrize("continuity", ["C1", "C2", "G1", "G2"])
@pytest.mark.parametrize("second", list(SECOND))
@pytest.mark.parametrize(
    "first", ["lit_han_trig2", "lit_hyp_quad", "lit_yan_liang", "lit_per_leg", "bernstein_like"]
)
def test_joins_with_every_family_by_finite_differences(fams, first, second, continuity):
    all_fams = {**fams, "bezier": "bezier", "bernstein_like": "bernstein_like"}
    n1, p1 = SECOND[first]
    points1 = POINTS[n1] if n1 in POINTS else POINTS[3]
    c1 = (
        lb.BernsteinLikeCurve(points1, p1["lam"])
        if first == "bernstein_like"
        else all_fams[first].curve(points1, params=p1)
    )
    n2, p2 = SECOND[second]
    order = int(continuity[1])
    rest = [(10 + i, (-1) ** i) for i in range(n2 - order)]
    g = {"G1": {"alpha": Fraction(3, 2)}, "G2": {"alpha": Fraction(3, 2), "d": Fraction(1, 2)}}.get(
        continuity, {}
    )
    c2 = lb.join(c1, continuity, n2, family=all_fams[second], rest=rest, **g, **p2)
    with mp.workdps(30):
        a = _ends(c1, _reference(first, c1.control_points(), p1), True)
        b = _ends(c2, _reference(second, c2.control_points(), p2), False)
    alpha, d = float(g.get("alpha", 1)), float(g.get("d", 0))
    scale = max(1.0, *(float(np.abs(v).max()) for v in a))
    assert np.allclose(a[0], b[0], atol=1e-10 * scale, rtol=0)
    assert np.allclose(a[1], alpha * b[1], atol=1e-9 * scale, rtol=0)
    if order == 2:
        assert np.allclose(a[2], alpha**2 * b[2] + d * b[1], atol=1e-8 * scale, rtol=0)


def test_a_composite_of_literature_families(fams):
    comp = lb.CompositeCurve(fams["lit_han_trig2"].curve(POINTS[3], lam=Fraction(1, 2), mu=-1))
    comp = comp.join(
        "C2", 3, family=fams["lit_yan_liang"], lam=Fraction(-1, 2), mu=1, rest=[(9, 2)]
    )
    comp = comp.join(
        "G1",
        3,
        family=fams["lit_per_leg"],
        lam=[Fraction(1, 2), 0, 0],
        alpha=2,
        rest=[(12, 0), (13, 1)],
    )
    comp = comp.join("C1", 2, family=fams["lit_han_quad_trig"], lam=Fraction(1, 3), rest=[(15, 0)])
    breaks = [float(x) for x in comp.breaks]
    assert breaks == pytest.approx([0, math.pi / 2, math.pi / 2 + 1, math.pi / 2 + 2, math.pi + 2])
    report = comp.report()
    assert [r.built_with.continuity for r in report] == ["C2", "G1", "C1"]
    assert all(r.built_with.continuity in r.achieved for r in report)
    # the joint's u is where the next segment starts: u = index + 1 was reported (1, 2, 3)
    # though the first segment covers [0, pi/2]
    assert [r.u for r in report] == pytest.approx(breaks[1:-1])
    for r in report:
        right = comp.segments[r.index + 1]
        start = right.domain[0] if hasattr(right, "domain") else 0.0
        assert comp.evaluate(r.u) == pytest.approx(right.evaluate(start), abs=1e-12)
    # continuity of position at every break, evaluated through the composite
    for u in breaks[1:-1]:
        assert comp.evaluate(u - 1e-9) == pytest.approx(comp.evaluate(u + 1e-9), abs=1e-7)
    # the last segment is the construction's, in its own t = u - start
    seg = comp.segments[-1]
    ref = _curve_ref(_han_quad, seg.control_points(), [mp.mpf(1) / 3])
    u = breaks[-2] + 0.4
    assert comp.evaluate(u) == pytest.approx([float(v) for v in ref(mp.mpf(0.4))], abs=1e-12)


def test_the_per_leg_family_per_degree_against_its_construction(fams):
    # symmetry lam(k) -> -lam(n-1-k), non-negativity and independence over [-1, 1]^n, each
    # decided per degree in the document, against the construction
    doc = json.loads((DATA / "lit_per_leg.derived.json").read_text())
    with mp.workdps(30):
        for n in (2, 3):
            per = doc["by_degree"][str(n)]
            assert per["symmetry"]["swap"] == [f"-lam_{n - 1 - k}" for k in range(n)]
            assert per["nonnegative_over_box"]["nonnegative"] is True
            assert per["singular_parameters"]["independent"] is True
            for lams in itertools.product(*[[-1, Fraction(1, 3), 1]] * n):
                vals = [_mpf(Fraction(x)) for x in lams]
                assert _rank_drop(_per_leg, vals, n) > mp.mpf(10) ** -8
                for t in (mp.mpf("0.2"), mp.mpf("0.9")):
                    b = _per_leg(t, *vals)
                    mirror = _per_leg(1 - t, *[-v for v in vals[::-1]])
                    assert all(abs(b[i] - mirror[n - i]) < mp.mpf(10) ** -25 for i in range(n + 1))
                    assert min(b) >= 0
    # the one-parameter property table is not an indexed family's: said so, not a KeyError
    # (degree 2) or "degree 3 is outside the range 2..2"
    with pytest.raises(TypeError, match=r"one parameter per index \(lam\(i\)\).*by_degree"):
        lb.singular_parameters(fams["lit_per_leg"], 3)
