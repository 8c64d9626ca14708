"""Non-polynomial families (issue #30) in the runtime: format-4 documents, their curves,
the exact rational form, energies in ℚ(π) / ℚ(e), geometry, evaluate_many.

The documents in tests/data/families/ are written by a scratch script until derive writes
format 4 (see the README there). Every reference here is independent of the runtime: the
definitions' formulas typed in as numpy/mpmath functions, mpmath's numerical derivatives and
quadrature, exact Fractions at rational points of tan(t/2)."""

from __future__ import annotations

import json
import math
from fractions import Fraction as F
from pathlib import Path

import mpmath
import numpy as np
import pytest
from han_surface_reference import han as han_basis

import lambda_bezier as lb
from lambda_bezier.family import FamilyFileError
from lambda_bezier.hazmat import atoms as ak
from lambda_bezier.hazmat.constants import ConstantFraction

DATA = Path(__file__).parent / "data" / "families"
HAN = DATA / "han_trig_cubic.toml"
HYP = DATA / "hyp_cubic.toml"
AT = DATA / "at_cubic.toml"
PTS = [(0, 0), (1, 3), (3, -1), (4, 1)]


# the definitions, typed in again (mpmath functions of t and the parameters); Han's basis is
# the one the surface tests share
def han(t, lam, mu):
    return [han_basis(i, t, lam, mu) for i in range(4)]


def hyp(t, lam, mu):
    ch, sh = mpmath.cosh(t), mpmath.sinh(t)
    return [
        (ch - sh) ** 2,
        1 - (ch - sh) ** 2 - mu * sh**2 - lam * (ch - 1),
        mu * sh**2,
        lam * (ch - 1),
    ]


def at(t, lam):
    s, c = mpmath.sin(t), mpmath.cos(t)
    return [1 - s, (s + c - 1) / 2 + lam * (t - s), (s + c - 1) / 2 - lam * (t - s), 1 - c]


CASES = [
    (HAN, han, {"lam": F(1, 2), "mu": F(-3, 2)}, (0, math.pi / 2)),
    (HYP, hyp, {"lam": F(1, 3), "mu": F(3, 4)}, (0, 1)),
    (AT, at, {"lam": F(2, 5)}, (0, math.pi / 2)),
]


def direct(basis, params, points, t, k=0):
    """C^(k)(t) from the typed-in definition (mpmath's numerical derivative for k > 0)."""
    pts = [[mpmath.mpf(F(v).numerator) / F(v).denominator for v in p] for p in points]
    vals = [float(v) for v in params.values()]

    def coord(x, c):
        b = basis(x, *vals)
        return sum(bi * p[c] for bi, p in zip(b, pts, strict=True))

    return np.array(
        [
            [
                float(mpmath.diff(lambda x, c=c: coord(x, c), tv, k) if k else coord(tv, c))
                for c in (0, 1)
            ]
            for tv in t
        ]
    )


@pytest.fixture(scope="module")
def families():
    return {p: lb.load_family(p) for p in (HAN, HYP, AT)}


# ------------------------------------------------------------------------------ reading
def test_loads_the_three_spaces(families):
    assert families[HAN].space == "trigonometric"
    assert families[HYP].space == "hyperbolic"
    assert families[AT].space == "mixed-trigonometric"
    assert families[HAN].parameters == ("lam", "mu")
    assert families[HAN].domain == (0.0, math.pi / 2)
    assert "t in [0, pi/2]" in repr(families[HAN])


def _doc():
    return json.loads((DATA / "han_trig_cubic.derived.json").read_text())


def _load_mutated(tmp_path, mutate):
    doc = _doc()
    mutate(doc)
    (tmp_path / "han_trig_cubic.toml").write_text(HAN.read_text())
    (tmp_path / "han_trig_cubic.derived.json").write_text(json.dumps(doc))
    return lb.load_family(tmp_path / "han_trig_cubic.toml")


@pytest.mark.parametrize(
    ("mutate", "message"),
    [
        (lambda d: d["atoms"]["3"].__setitem__(1, "__import__('os')"), "is not an atom"),
        (lambda d: d["atoms"]["3"].__setitem__(1, "cos(t)+1"), "is not an atom"),
        (lambda d: d["atoms"]["3"].__setitem__(1, "exp(t)"), "is not an atom"),
        (lambda d: d["atoms"]["3"].__setitem__(1, "cosh(1*t)"), "not of the trigonometric space"),
        (lambda d: d["atoms"]["3"].__setitem__(1, "t^2"), "only in the mixed spaces"),
        (lambda d: d["atoms"]["3"].__setitem__(1, "sin(1*t)"), "listed twice"),
        (lambda d: d.__setitem__("space", "elliptic"), "space"),
        (lambda d: d.pop("atoms"), "'atoms' is missing"),
        (lambda d: d["coefficients"]["3"]["0,0"][0].__setitem__(0, "1.5"), "not an exact number"),
        (lambda d: d["coefficients"]["3"]["0,0"].pop(), "expected a 4 x 7 matrix"),
        (
            lambda d: d["coefficients"]["3"].__setitem__("0,0,1", d["coefficients"]["3"]["0,0"]),
            "monomial",
        ),
        (lambda d: d["rational"]["weights"]["3"].__setitem__(0, "-1"), "must be positive"),
        (lambda d: d["rational"].__setitem__("substitution", "tan(t)"), "substitution"),
        (lambda d: d["rational"].__setitem__("scale", "2"), "not [0, 1]"),
        (lambda d: d["domain"].__setitem__("hi", "0"), "not below"),
        (lambda d: d["domain"].__setitem__("unit", "e"), "unit"),
        (lambda d: d["energy"]["3,1"].__setitem__("constant", "os.system"), "constant"),
        (lambda d: d["energy"]["3,1"]["gram"]["0,0|0,0"][0].__setitem__(0, [["1", "x"]]), "pair"),
        (lambda d: d["energy"]["3,1"]["gram"]["0,0|0,0"][0].__setitem__(0, "pi"), "exact number"),
        (lambda d: d["endpoints"]["3"].__setitem__("middle,0,0", {}), "start|end"),
        (lambda d: d["parameters"][0].__setitem__("name", "Lam; rm"), "parameter name"),
        (lambda d: d.__setitem__("degrees", [3, "3"]), "degrees"),
    ],
)
def test_bad_documents_are_refused_by_key(tmp_path, mutate, message):
    with pytest.raises(FamilyFileError, match=message.replace("[", r"\[").replace("(", r"\(")):
        _load_mutated(tmp_path, mutate)


def test_extra_keys_are_tolerated(tmp_path):
    def extra(d):
        d["something_new"] = {"x": 1}
        d["rational"]["note"] = "hello"

    fam = _load_mutated(tmp_path, extra)
    assert fam.curve(PTS, lam=0, mu=0).evaluate(0.3).shape == (2,)


def test_atom_grammar():
    assert ak.parse_atom("sin(1/2*pi*t)") == ak.Atom("sin", 0, F(1, 2), True)
    assert ak.parse_atom("cos(t)") == ak.Atom("cos", 0, F(1), False)
    assert ak.parse_atom("t^3") == ak.Atom("t", 3, F(0), False)
    assert ak.parse_atom("cosh(3*t)").omega == 3
    for bad in ("sin(0*t)", "sin(-1*t)", "t^0", "sin(2*x)", "sin(2*t) ", "1.0", "tan(t)", ""):
        with pytest.raises(ValueError, match="is not an atom"):
            ak.parse_atom(bad)


# ------------------------------------------------------------------------------ curves
@pytest.mark.parametrize(("path", "basis", "params", "domain"), CASES)
def test_evaluate_and_derivatives_match_the_definition(families, path, basis, params, domain):
    curve = families[path].curve(PTS, params=params)
    t = np.linspace(*domain, 9)
    for k in range(4):
        got = curve.derivative(t, k) if k else curve.evaluate(t)
        want = direct(basis, params, PTS, t, k)
        assert np.abs(got - want).max() <= (1e-13 if k == 0 else 1e-9) * (1 + np.abs(want).max())


@pytest.mark.parametrize(("path", "basis", "params", "domain"), CASES)
def test_basis_sums_to_one(families, path, basis, params, domain):
    curve = families[path].curve(PTS, params=params)
    b = curve.basis(np.linspace(*domain, 11))
    assert np.abs(b.sum(axis=1) - 1).max() < 1e-14


def test_parameters_are_the_familys_t(families):
    curve = families[HAN].curve(PTS, lam=0, mu=0)
    assert np.allclose(curve.evaluate(math.pi / 2), PTS[-1], atol=1e-14)
    with pytest.raises(ValueError, match=r"outside the han_trig_cubic domain \[0, pi/2\]"):
        curve.evaluate(1.6)
    curve.evaluate(1.6, extrapolate=True)
    with pytest.raises(ValueError, match="outside the han_trig_cubic range"):
        families[HAN].curve(PTS, lam=2, mu=0)
    with pytest.raises(TypeError, match="mu"):
        families[HAN].curve(PTS, lam=0)


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
def test_parameters_checked_once_refuse_non_finite(families, bad):
    """One pair of min/max reductions (val.parameter_range) checks finiteness and the domain:
    a NaN or infinity anywhere in the array is named, with or without extrapolate; the
    smallest and largest values are what the domain check reports."""
    curve = families[HAN].curve(PTS, lam=0.5, mu=-1)
    t = np.linspace(0.0, 1.5, 9)
    t[4] = bad
    for extrapolate in (False, True):
        with pytest.raises(ValueError, match="t contains NaN or infinity"):
            curve.evaluate(t, extrapolate=extrapolate)
    t[4] = -0.25
    with pytest.raises(ValueError, match=r"t = -0\.25 is outside the han_trig_cubic domain"):
        curve.derivative(t, 1)
    t[4] = 1.75
    with pytest.raises(ValueError, match=r"t = 1\.75 is outside the han_trig_cubic domain"):
        curve.evaluate(t)
    assert curve.evaluate(np.empty(0)).shape == (0, 2)


def test_half_angle_kernel_equals_the_recurrences(families):
    curve = families[HAN].curve(np.random.default_rng(3).normal(size=(4, 2)), lam=-1.5, mu=0.7)
    t = np.random.default_rng(4).random(1000) * math.pi / 2
    sh = curve.shape
    for k in range(3):
        coeffs = curve._coefficients(k)
        fast = ak.evaluate_half_angle(
            ak.half_angle_coefficients(coeffs, sh.harmonics),
            t - curve._mid,
            sh.omega0,
            sh.harmonics,
        )
        slow = ak.evaluate(coeffs, t - curve._mid, sh.omega0, sh.powers, sh.harmonics, False)
        assert np.abs(fast - slow).max() < 1e-13 * (1 + np.abs(slow).max())


@pytest.mark.parametrize("size", [0, 1, 8191, 8193, 20001])
def test_half_angle_kernel_over_blocks_with_its_centre(families, size):
    """The powers-and-matrix-product form (issue #30, without numba) over several blocks and
    a short last one, τ taken about `centre` inside the kernel: within a few ulps of the
    recurrences, ends of the domain included."""
    curve = families[HAN].curve(np.random.default_rng(5).normal(size=(4, 2)), lam=0.5, mu=-1)
    t = np.random.default_rng(6).random(size) * math.pi / 2
    t[: min(size, 2)] = [0.0, math.pi / 2][: min(size, 2)]
    sh = curve.shape
    for k in range(3):
        coeffs = curve._coefficients(k)
        table = ak.half_angle_coefficients(coeffs, sh.harmonics)
        fast = ak.evaluate_half_angle(table, t, sh.omega0, sh.harmonics, curve._mid)
        slow = ak.evaluate(coeffs, t - curve._mid, sh.omega0, sh.powers, sh.harmonics, False)
        assert fast.shape == slow.shape == (2, size)
        assert np.abs(fast - slow).max(initial=0.0) < 8 * 2.0**-52 * (
            1 + np.abs(slow).max(initial=0.0)
        )


def test_to_bezier_points_to_the_rational_form(families):
    with pytest.raises(NotImplementedError, match="to_rational_bezier"):
        families[HAN].curve(PTS, lam=0, mu=0).to_bezier()
    with pytest.raises(NotImplementedError, match="no rational form"):
        families[AT].curve(PTS, lam=0).to_bezier()
    with pytest.raises(NotImplementedError, match="in floats"):
        families[HYP].curve(PTS, lam=0, mu=0).to_bezier()
    # a hyperbolic curve's rational form is in floats (tests/test_trig_hyperbolic_rational.py)
    assert not families[HYP].curve(PTS, lam=0, mu=0).to_rational_bezier().is_exact


# ------------------------------------------------------------------------------ rational form
def test_rational_form_equals_the_curve(families):
    rng = np.random.default_rng(7)
    for _ in range(5):
        lam, mu = rng.uniform(-2, 1, 2)
        curve = families[HAN].curve(rng.normal(size=(4, 2)), lam=lam, mu=mu)
        rat = curve.to_rational_bezier()
        t = np.linspace(0, math.pi / 2, 201)
        assert np.abs(rat.evaluate(curve.s_of_t(t)) - curve.evaluate(t)).max() < 1e-14 * 4
        assert np.allclose(curve.t_of_s(curve.s_of_t(t)), t, atol=1e-15, rtol=0)


def test_rational_form_is_exact_at_rational_s(families):
    lam, mu = F(1, 2), F(-3, 2)
    curve = families[HAN].curve(PTS, lam=lam, mu=mu)
    rat = curve.to_rational_bezier()
    assert rat.is_exact and all(isinstance(w, F) for w in rat.control_weights())
    for s in (F(0), F(1, 3), F(1, 2), F(5, 7), F(1)):
        sin, cos = 2 * s / (1 + s * s), (1 - s * s) / (1 + s * s)  # t = 2 atan(s)
        b = [
            (1 - sin) ** 2 * (1 - lam * sin),
            sin * (1 - sin) * (2 + lam - lam * sin),
            cos * (1 - cos) * (2 + mu - mu * cos),
            (1 - cos) ** 2 * (1 - mu * cos),
        ]
        want = tuple(sum(bi * p[c] for bi, p in zip(b, PTS, strict=True)) for c in (0, 1))
        assert rat.exact_derivative(s, 0) == want


# ------------------------------------------------------------------------------ energies
def _quad_energy(basis, params, points, k, domain):
    mpmath.mp.dps = 30
    pts = [[mpmath.mpf(v) for v in p] for p in points]
    vals = [mpmath.mpf(F(v).numerator) / F(v).denominator for v in params.values()]

    def speed2(x):
        total = 0
        for c in range(2):
            total += (
                mpmath.diff(
                    lambda y, c=c: sum(b * p[c] for b, p in zip(basis(y, *vals), pts, strict=True)),
                    x,
                    k,
                )
                ** 2
            )
        return total

    lo, hi = domain
    return float(mpmath.quad(speed2, [lo, (lo + hi) / 2, hi]))


@pytest.mark.parametrize(("path", "basis", "params", "domain"), CASES)
@pytest.mark.parametrize("k", [1, 2, 3])
def test_energy_against_quadrature(families, path, basis, params, domain, k):
    curve = families[path].curve(PTS, params=params)
    exact = curve.energy(k)
    assert isinstance(exact, ConstantFraction | F)
    dom = (mpmath.pi / 2) if domain[1] != 1 else mpmath.mpf(1)
    want = _quad_energy(basis, params, PTS, k, (0, dom))
    assert float(exact) == pytest.approx(want, rel=1e-12)
    floaty = families[path].curve(
        np.array(PTS, float), params={n: float(v) for n, v in params.items()}
    )
    assert isinstance(floaty.energy(k), float)
    assert floaty.energy(k) == pytest.approx(want, rel=1e-12)


def test_energy_in_q_pi_is_exact(families):
    e = families[HAN].curve(PTS, lam=0, mu=0).energy(1)
    assert isinstance(e, ConstantFraction) and e.constant == "pi"
    assert e.denominator == (F(1),) and len(e.numerator) == 2  # a + b·π


@pytest.mark.parametrize(("path", "basis", "params", "domain"), CASES)
@pytest.mark.parametrize("k", [1, 2])
def test_optimal_parameters_are_the_box_minimum(families, path, basis, params, domain, k):
    fam = families[path]
    res = lb.optimal_parameters(PTS, k, family=fam)
    names = fam.parameters
    # exact: every value is a Fraction or a ConstantFraction, energy too
    assert all(isinstance(v, F | ConstantFraction) for v in res.values.values())
    best = float(res.energy)
    assert best == pytest.approx(
        float(
            fam.curve(
                PTS,
                params=res.values_float
                if hasattr(res, "values_float")
                else {n: float(v) for n, v in res.values.items()},
                check_range=False,
            ).energy(k)
        ),
        rel=1e-12,
    )
    # no point of a grid over the box is lower
    rng = np.random.default_rng(11)
    for _ in range(60):
        trial = {
            n: float(fam.atom_data.RANGES[n][0])
            + rng.random() * float(fam.atom_data.RANGES[n][1] - fam.atom_data.RANGES[n][0])
            for n in names
        }
        assert fam.curve(PTS, params=trial).energy(k) >= best * (1 - 1e-12)
    if res.free_inside:  # a free minimum: the quadrature energy's gradient vanishes there
        h = 1e-5
        for n in names:
            up = {m: float(v) + (h if m == n else 0) for m, v in res.values.items()}
            dn = {m: float(v) - (h if m == n else 0) for m, v in res.values.items()}
            g = (
                _quad_energy(basis, up, PTS, k, (0, mpmath.pi / 2 if domain[1] != 1 else 1))
                - _quad_energy(basis, dn, PTS, k, (0, mpmath.pi / 2 if domain[1] != 1 else 1))
            ) / (2 * h)
            assert abs(g) < 1e-6 * (1 + best)
    else:
        assert res.boundary


def test_optimal_parameters_float_points(families):
    res = lb.optimal_parameters(np.array(PTS, float), 2, family=families[HAN])
    assert all(isinstance(v, float) for v in res.values.values())
    exact = lb.optimal_parameters(PTS, 2, family=families[HAN])
    for n in ("lam", "mu"):
        assert res[n] == pytest.approx(float(exact[n]), rel=1e-12)


def test_constant_fraction_arithmetic():
    pi = ConstantFraction((F(0), F(1)))
    assert float(pi) == math.pi
    assert pi > F(22, 7) - F(1, 100) and pi < F(22, 7)
    x = (pi + 1) / (pi - 3)
    assert float(x) == pytest.approx(float((mpmath.pi + 1) / (mpmath.pi - 3)), rel=1e-15)
    assert x * (pi - 3) == pi + 1
    assert x - x == 0
    e = ConstantFraction.from_laurent({1: F(1)}, "exp(1)")
    assert float(e) == math.e and float(1 / e) == pytest.approx(1 / math.e, rel=1e-16)
    with pytest.raises(ValueError, match="cannot combine"):
        _ = pi + e


# ------------------------------------------------------------------------------ geometry
def _dense(curve, count=200001):
    lo, hi = curve.domain
    t = np.linspace(lo, hi, count)
    return t, curve.evaluate(t)


@pytest.mark.parametrize(("path", "basis", "params", "domain"), CASES)
def test_arc_length(families, path, basis, params, domain):
    curve = families[path].curve(PTS, params=params)
    mpmath.mp.dps = 20
    vals = [float(v) for v in params.values()]

    def speed(x):
        return mpmath.sqrt(
            sum(
                mpmath.diff(
                    lambda y, c=c: sum(b * p[c] for b, p in zip(basis(y, *vals), PTS, strict=True)),
                    x,
                )
                ** 2
                for c in (0, 1)
            )
        )

    hi = mpmath.pi / 2 if domain[1] != 1 else mpmath.mpf(1)
    want = float(mpmath.quad(speed, mpmath.linspace(0, hi, 5)))
    assert curve.arc_length() == pytest.approx(want, rel=1e-10)
    half = curve.arc_length(0, float(hi) / 2)
    t = curve.parameter_at_length(half)
    assert t == pytest.approx(float(hi) / 2, rel=1e-9)


@pytest.mark.parametrize(("path", "basis", "params", "domain"), CASES)
def test_box_and_closest_point(families, path, basis, params, domain):
    curve = families[path].curve(PTS, params=params)
    t, pts = _dense(curve)
    lo, hi = curve.bounding_box()
    assert np.all(lo <= pts.min(axis=0) + 1e-12) and np.all(hi >= pts.max(axis=0) - 1e-12)
    assert np.allclose(lo, pts.min(axis=0), atol=1e-8) and np.allclose(
        hi, pts.max(axis=0), atol=1e-8
    )
    for q in ([2.0, 3.0], [0.5, -1.0], [5.0, 0.0]):
        found = curve.closest_point(q)
        dmin = np.linalg.norm(pts - q, axis=1).min()
        assert found.distance <= dmin + 1e-12
        assert domain[0] <= found.t <= domain[1] + 1e-15
        assert np.allclose(curve.evaluate(found.t), found.point)
    on = curve.evaluate(0.7)
    assert curve.locate(on) == pytest.approx(0.7, abs=1e-9)
    assert curve.locate([50.0, 50.0]) is None


@pytest.mark.parametrize(("path", "basis", "params", "domain"), CASES)
def test_intersections_with_a_line_and_between_families(families, path, basis, params, domain):
    curve = families[path].curve(PTS, params=params)
    line = lb.BezierCurve([(0.0, 0.4), (4.0, 0.6)])
    hits = curve.intersect(line)
    # the reference: sign changes of the signed distance to the line along a dense sampling
    t, pts = _dense(curve, 20001)
    side = (pts[:, 1] - 0.4) * 4.0 - (pts[:, 0] - 0.0) * 0.2
    assert len(hits) == int(np.sum(np.sign(side[:-1]) != np.sign(side[1:])))
    for h in hits:
        assert np.linalg.norm(curve.evaluate(h.s) - line.evaluate(h.t)) < 1e-12
    other = families[HAN].curve([(0, 1), (2, -2), (3, 4), (4, -1)], lam=0, mu=0)
    for h in curve.intersect(other):
        assert np.linalg.norm(curve.evaluate(h.s) - other.evaluate(h.t)) < 1e-11


def test_split_by_the_rational_form(families):
    curve = families[HAN].curve(PTS, lam=F(1, 2), mu=-1)
    left, right = curve.split(0.6)
    assert np.allclose(left.evaluate(1.0), curve.evaluate(0.6), atol=1e-14)
    assert np.allclose(right.evaluate(0.0), curve.evaluate(0.6), atol=1e-14)
    assert np.allclose(right.evaluate(1.0), PTS[-1], atol=1e-14)
    with pytest.raises(NotImplementedError, match="no rational form"):
        families[AT].curve(PTS, lam=0).split(0.5)


# ------------------------------------------------------------------------------ batches
@pytest.mark.parametrize("path", [HAN, HYP, AT])
def test_evaluate_many(families, path):
    fam = families[path]
    rng = np.random.default_rng(5)
    pts = rng.normal(size=(6, 4, 2))
    params = {
        n: float(fam.atom_data.RANGES[n][0]) / 2 + float(fam.atom_data.RANGES[n][1]) / 2
        for n in fam.parameters
    }
    t = np.linspace(*fam.domain, 13)
    for k in (0, 1, 3):
        got = lb.evaluate_many(pts, t, fam, params=params, k=k)
        want = np.array([fam.curve(p, params=params).derivative(t, k) for p in pts])
        assert np.abs(got - want).max() < 1e-12
    with pytest.raises(ValueError, match="outside"):
        lb.evaluate_many(pts, [0.0, 5.0], fam, params=params)


# ------------------------------------------------------------------------------ joins
def _ends_match(first, second, order, alpha=1, d=0):
    """C1^(r)(end) against α-scaled C2^(r)(start), each in its own parameter."""
    end = first.domain[1] if hasattr(first, "domain") else 1.0
    start = second.domain[0] if hasattr(second, "domain") else 0.0
    c1 = [np.asarray(first.derivative(end, r), float) for r in range(order + 1)]
    c2 = [np.asarray(second.derivative(start, r), float) for r in range(order + 1)]
    want = [c2[0], alpha * c2[1]]
    if order == 2:
        want.append(alpha**2 * c2[2] + d * c2[1])
    scale = 1 + max(np.abs(v).max() for v in c1)
    return all(np.abs(a - b).max() < 1e-12 * scale for a, b in zip(c1, want, strict=False))


@pytest.mark.parametrize("continuity", ["C1", "C2", "G1", "G2"])
def test_joins_trig_to_any_family_and_back(families, continuity):
    order = 1 if continuity in ("C1", "G1") else 2
    alpha, d = (F(3, 2), F(1, 3)) if continuity.startswith("G") else (1, 0)
    kw = (
        {"alpha": alpha, "d": d}
        if continuity == "G2"
        else {"alpha": alpha}
        if continuity == "G1"
        else {}
    )
    trig = families[HAN].curve(PTS, lam=F(1, 2), mu=-1)
    rest4 = [(7, 1), (8, 0), (9, 2)][: 4 - order]
    for target, params in (
        ("bezier", {}),
        ("same_degree", {"lam": F(1, 2)}),
        (lb.load_family(DATA / "per_leg_cubic.toml"), {"s0": F(1, 3), "s1": 0, "s2": F(1, 2)}),
        (families[HAN], {"lam": 0, "mu": F(1, 2)}),
        (families[HYP], {"lam": F(1, 5), "mu": F(1, 2)}),
        (families[AT], {"lam": F(1, 5)}),
    ):
        degree = 4 if target in ("bezier", "same_degree") else 3
        if target is families[AT] and order == 2:
            # b_1 and b_2 of at_cubic agree to second order at t = 0 (lam (t - sin t) ~ t³/6):
            # C''(0) cannot fix P_1 and P_2 apart
            with pytest.raises(ValueError, match="cannot solve"):
                lb.join(trig, continuity, degree, family=target, rest=rest4[:1], **params, **kw)
            continue
        nxt = lb.join(
            trig, continuity, degree, family=target, rest=rest4[: degree - order], **params, **kw
        )
        assert _ends_match(trig, nxt, order, float(alpha), float(d)), target
    # into a trigonometric segment from a polynomial one: exact (the start values are rational)
    poly = lb.BezierCurve([(0, 0), (1, 1), (2, 0), (3, 1)])
    nxt = lb.join(
        poly, continuity, 3, family=families[HAN], lam=0, mu=F(1, 2), rest=rest4[: 3 - order], **kw
    )
    assert nxt.is_exact and all(isinstance(v, F) for p in nxt.control_points() for v in p)
    assert _ends_match(poly, nxt, order, float(alpha), float(d))


def test_join_errors(families):
    trig = families[HAN].curve(PTS, lam=0, mu=0)
    with pytest.raises(ValueError, match="rest must hold the 2 control points"):
        lb.join(trig, "C1", 3, lam=0, mu=0, rest=[(1, 1)])
    with pytest.raises(TypeError, match="mu"):
        lb.join(trig, "C1", 3, lam=0, rest=[(1, 1), (2, 2)])
    with pytest.raises(ValueError, match="outside the han_trig_cubic range"):
        lb.join(trig, "C1", 3, lam=5, mu=0, rest=[(1, 1), (2, 2)])


# ------------------------------------------------------------------------------ JSON, export
@pytest.mark.parametrize("path", [HAN, HYP, AT])
def test_json_round_trip(families, path):
    from lambda_bezier import export

    fam = families[path]
    params = {n: F(1, 3) for n in fam.parameters}
    curve = fam.curve(PTS, params=params)
    back = export.from_json(export.to_json(curve), family=fam)
    assert type(back) is type(curve) and back.is_exact
    assert back.control_points() == curve.control_points()
    assert back.parameter_values == curve.parameter_values
    floaty = fam.curve(np.array(PTS, float) / 3, params={n: 0.3 for n in fam.parameters})
    back = export.from_json(export.to_json(floaty), family=path)  # the definition file
    assert not back.is_exact and back.atom_parameter_values() == {n: 0.3 for n in fam.parameters}
    t = np.linspace(*fam.domain, 7)
    assert np.array_equal(back.evaluate(t), floaty.evaluate(t))
    doc = json.loads(export.to_json(curve))
    doc["parameters"] = {"lam": "1/3"} if len(fam.parameters) > 1 else {"nu": "0"}
    with pytest.raises(TypeError):
        export.from_json(json.dumps(doc), family=fam)


def _spline_matches(spline, curve, tol):
    """The B-spline against the curve at the same points: u ∈ [0, pieces] ↔ t."""
    lo, hi = curve.domain
    if spline.weights is not None:  # the rational form (a hyperbolic curve's: in floats)
        s = np.linspace(0, 1, 41)
        got = np.array([spline.evaluate(float(x)) for x in s])
        want = curve.evaluate(curve.t_of_s(s))
    else:
        u_end = float(spline.knots[-1])
        u = np.linspace(0, u_end, 81)
        got = np.array([spline.evaluate(float(x)) for x in u])
        want = curve.evaluate(lo + (hi - lo) * u / u_end)
    return np.abs(got - want).max() <= tol


@pytest.mark.parametrize("path", [HAN, HYP, AT])
def test_export_through_the_rational_form_or_pieces(families, path, tmp_path):
    from lambda_bezier import export

    fam = families[path]
    curve = fam.curve(PTS, params={n: F(1, 3) for n in fam.parameters})
    spline = export.to_bspline(curve)
    if path == HAN:  # exact: the rational form, a NURBS of degree 6
        assert spline.exact and spline.weights is not None and spline.degree == 6
        assert _spline_matches(spline, curve, 1e-14 * 4)
    elif path == HYP:  # its rational form in floats: one NURBS span of degree 4
        assert not spline.exact and spline.weights is not None and spline.degree == 4
        assert _spline_matches(spline, curve, 1e-14 * 4)
    else:  # numerically: polynomial pieces within 1e-13 of the size
        assert spline.weights is None and spline.degree <= 10
        assert _spline_matches(spline, curve, 1e-13 * 4 * 2)
    ezdxf = pytest.importorskip("ezdxf")
    file = export.to_dxf(curve, tmp_path / "c.dxf")
    (entity,) = ezdxf.readfile(file).modelspace().query("SPLINE")
    assert entity.construction_tool().degree == spline.degree
    pytest.importorskip("OCP")
    assert export.to_step(curve, tmp_path / "c.step").is_file()
