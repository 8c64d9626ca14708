"""The certified piecewise form of trigonometric, hyperbolic and mixed curves (issue #30,
hazmat.atom_pieces): with numba, AtomCurve.evaluate and derivative of arrays of at least
atom_pieces.PIECES_FROM parameters in the domain go through it; without, the atoms.

References are independent of the runtime: the definitions typed in as mpmath functions
(test_trig_runtime), mpmath's derivatives, and mpmath's own sin/cos/sinh/cosh at 40 digits
for the remainder bound. The curve runs with the compiled kernel switched on and off, and the
numpy evaluation of the pieces is checked on the same tables."""

from __future__ import annotations

import math
from fractions import Fraction as F

import mpmath
import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from test_trig_runtime import AT, HAN, HYP, at, han, hyp

import lambda_bezier as lb
from lambda_bezier.hazmat import atom_pieces as ap
from lambda_bezier.hazmat import atoms as ak
from lambda_bezier.hazmat import kernels

DATA = HAN.parent


def at_pi(t, lam):
    s, c = mpmath.sin(mpmath.pi * t / 2), mpmath.cos(mpmath.pi * t / 2)
    return [
        1 - t - (1 - lam) * (s - t),
        (1 - lam) * (s - t),
        (1 - lam) * (c - 1 + t),
        t - (1 - lam) * (c - 1 + t),
    ]


def hyp_shift(t, lam):
    e = mpmath.cosh(2 * t) - mpmath.sinh(2 * t)
    return [e, 1 - e - lam * mpmath.sinh(t) ** 2, lam * mpmath.sinh(t) ** 2]


# (file, typed-in basis, parameters, degree): one curve of every space the runtime reads
CASES = {
    "trigonometric": (HAN, han, {"lam": F(1, 2), "mu": F(-3, 2)}, 3),
    "hyperbolic": (HYP, hyp, {"lam": F(1, 3), "mu": F(3, 4)}, 3),
    "hyperbolic-shifted": (DATA / "hyp_shift_quadratic.toml", hyp_shift, {"lam": F(2, 3)}, 2),
    "mixed": (AT, at, {"lam": F(2, 5)}, 3),
    "mixed-pi": (DATA / "at_pi_cubic.toml", at_pi, {"lam": F(1, 4)}, 3),
}


@pytest.fixture(params=["numba", "numpy"])
def compiled(request, monkeypatch):
    monkeypatch.setattr(kernels, "USE_COMPILED", request.param == "numba")
    return request.param == "numba"


@pytest.fixture(scope="module")
def curves():
    out = {}
    for name, (path, basis, params, n) in CASES.items():
        fam = lb.load_family(path)
        pts = np.random.default_rng(len(name)).normal(size=(n + 1, 2)) * 3
        out[name] = (fam.curve(pts, **params), basis, params, pts)
    return out


def _reference(basis, params, pts, t, k=0):
    """C^(k)(t) at 40 digits from the typed-in definition, at the float t exactly."""
    vals = [mpmath.mpf(v.numerator) / v.denominator for v in params.values()]
    rows = [[mpmath.mpf(float(v)) for v in p] for p in pts]

    def coord(x, c):
        return mpmath.fsum(b * p[c] for b, p in zip(basis(x, *vals), rows, strict=True))

    with mpmath.workdps(40):
        return np.array(
            [
                [
                    float(mpmath.diff(lambda x, c=c: coord(x, c), mpmath.mpf(x), k))
                    if k
                    else float(coord(mpmath.mpf(x), c))
                    for c in range(pts.shape[1])
                ]
                for x in t
            ]
        )


def _parameters(curve, order, count, seed):
    """At least PIECES_FROM parameters: random ones, every piece boundary, the domain's ends
    and their neighbouring floats inside."""
    lo, hi = curve.domain
    pieces = curve._piece_table(order)
    assert pieces is not None, "a certified piecewise form exists for this curve"
    bounds = lo + np.arange(pieces.pieces + 1) * pieces.width
    rng = np.random.default_rng(seed)
    t = np.concatenate(
        [
            rng.uniform(lo, hi, count),
            np.clip(bounds, lo, hi),
            [lo, hi, np.nextafter(lo, hi), np.nextafter(hi, lo)],
        ]
    )
    t = np.resize(t, max(t.size, ap.PIECES_FROM))  # repeats keep the size above the switch
    return t, pieces


@pytest.mark.parametrize("name", list(CASES))
def test_values_match_mpmath_within_a_few_ulps(name, curves, compiled):
    curve, basis, params, pts = curves[name]
    t, pieces = _parameters(curve, 0, 600, 1)
    want = _reference(basis, params, pts, t)
    scale = np.abs(want).max()
    # the curve (pieces with numba, atoms without), and the numpy path on the same pieces
    for got in (curve.evaluate(t), ap.evaluate_pieces(pieces, t).T):
        err = np.abs(got - want).max() / np.spacing(scale)
        assert err <= 8, f"{name}: {err} ulps of the coordinate scale {scale}"
    assert pieces.bound <= pieces.tolerance <= scale * 2.0**-53


@pytest.mark.parametrize("name", list(CASES))
@pytest.mark.parametrize("k", [1, 2])
def test_derivatives_match_mpmath(name, k, curves, compiled):
    curve, basis, params, pts = curves[name]
    t, _ = _parameters(curve, k, 40, 2)
    pick = np.r_[0 : 40 + 12, -4:0]  # random ones, the first boundaries, the ends
    want = _reference(basis, params, pts, t[pick], k)
    for got in (curve.derivative(t, k), ap.evaluate_pieces(curve._piece_table(k), t).T):
        err = np.abs(got[pick] - want).max() / np.spacing(np.abs(want).max())
        assert err <= 16, f"{name}, derivative {k}: {err} ulps"


@pytest.mark.parametrize("name", list(CASES))
def test_pieces_and_atoms_agree(name, curves, compiled):
    """The long-array path (pieces, with numba) and the short-array path (atoms) give the
    same curve."""
    curve, *_ = curves[name]
    lo, hi = curve.domain
    t = np.linspace(lo, hi, 3 * ap.PIECES_FROM)
    whole = curve.evaluate(t)
    parts = np.concatenate([curve.evaluate(t[i : i + 100]) for i in range(0, t.size, 100)])
    assert np.abs(whole - parts).max() <= 16 * np.spacing(np.abs(parts).max())


def test_extrapolation_keeps_the_atoms(curves):
    curve, basis, params, pts = curves["trigonometric"]
    lo, hi = curve.domain
    t = np.linspace(lo - 0.5, hi + 0.5, ap.PIECES_FROM + 1)
    got = curve.evaluate(t, extrapolate=True)
    want = _reference(basis, params, pts, t[::64])
    assert np.abs(got[::64] - want).max() <= 8 * np.spacing(np.abs(want).max())


def test_large_coordinates_scale_back(compiled):
    fam = lb.load_family(HAN)
    pts = np.array([(0, 0), (1, 3), (3, -1), (4, 1)], dtype=float)
    small = fam.curve(pts, lam=0.5, mu=-1.0)
    big = fam.curve(pts * 2.0**950, lam=0.5, mu=-1.0)
    t = np.linspace(0, math.pi / 2, ap.PIECES_FROM)
    assert np.array_equal(big.evaluate(t), small.evaluate(t) * 2.0**950)


# ------------------------------------------------------------------------------ the kernels
@given(
    st.integers(1, 3),
    st.integers(0, 9),
    st.integers(1, 400),
    st.floats(-3, 3),
    st.floats(1e-3, 10),
    st.integers(0, 2**32 - 1),
)
def test_kernel_and_numpy_agree_bit_for_bit(dim, degree, count, lo, span, seed):
    rng = np.random.default_rng(seed)
    pieces = ap.PieceTable(
        lo,
        span / count,
        count / span,
        lo + (np.arange(count) + 0.5) * (span / count),
        rng.normal(size=(dim, degree + 1, count)),
        math.nan,
        math.nan,
    )
    t = rng.uniform(lo, lo + span, 700)
    t[:2] = (lo, lo + span)
    t[2] = np.nextafter(lo, -math.inf)  # a few ulps outside: clamped to the end pieces
    fast = ap.compiled()
    if fast is None:
        pytest.skip("numba is not installed")
    out = np.empty((dim, t.size))
    fast.evaluate_pieces(t, pieces.lo, pieces.inv_width, pieces.centres, pieces.table, out)
    assert np.array_equal(out, ap.evaluate_pieces(pieces, t))


def _taylor_error(f, centre, degree, h, samples=41):
    """max |f − T_degree| on [centre − h, centre + h] at 40 digits, f an mpmath function."""
    with mpmath.workdps(40):
        c = mpmath.mpf(centre)
        coeffs = mpmath.taylor(f, c, degree)
        worst = mpmath.mpf(0)
        for x in mpmath.linspace(c - h, c + h, samples):
            worst = max(worst, abs(f(x) - mpmath.polyval(coeffs[::-1], x - c)))
        return float(worst)


@pytest.mark.parametrize("hyperbolic", [False, True])
@pytest.mark.parametrize("degree", [3, 5, 8])
def test_remainder_bound_holds_and_is_tight(hyperbolic, degree):
    """One coordinate 0.3 + 0.2 τ² + 0.7 τ^(degree + 2) + (a cos 3ωτ + b sin 3ωτ) (or cosh,
    sinh): the bound is above the true Taylor error on every piece tried, and within a small
    factor of it (so it is not vacuous)."""
    omega0, powers, harmonics = 1.5, degree + 2, 3
    coeffs = np.zeros((1 + powers + 2 * harmonics, 1))
    coeffs[0], coeffs[2], coeffs[powers] = 0.3, 0.2, 0.7
    a, b = -1.25, 0.5
    coeffs[1 + powers + 4], coeffs[1 + powers + 5] = a, b
    wave = (mpmath.cosh, mpmath.sinh) if hyperbolic else (mpmath.cos, mpmath.sin)

    def f(x):
        nu = 3 * mpmath.mpf(omega0)
        return 0.3 + 0.2 * x**2 + 0.7 * x**powers + a * wave[0](nu * x) + b * wave[1](nu * x)

    amp = ap.amplitudes(
        ap.CentredCurve(coeffs, -0.6, 0.6, 0.0, omega0, powers, harmonics, hyperbolic)
    )
    radius = 0.6
    for h in (0.01, 0.05, 0.1):
        bound = float(ap.remainder_bound(amp, degree, h, radius)[0])
        worst = max(_taylor_error(f, c, degree, h) for c in (-radius + h, 0.0, 0.2, radius - h))
        assert worst <= bound <= 40 * worst, (h, worst, bound)


def test_polynomial_parts_up_to_the_degree_cost_nothing():
    coeffs = np.zeros((1 + 4, 2))
    coeffs[:, 0] = (1, 2, 3, 4, 5)
    amp = ap.amplitudes(ap.CentredCurve(coeffs, 0.0, 1.0, 0.5, 1.0, 4, 0, False))
    assert (ap.remainder_bound(amp, 4, 0.5, 1.0) == 0).all()
    assert ap.remainder_bound(amp, 3, 0.5, 1.0)[0] == pytest.approx(5 * 0.5**4, rel=1e-8)


def test_choice_reaches_the_tolerance_and_is_minimal():
    fam = lb.load_family(HAN)
    curve = fam.curve([(0, 0), (1, 3), (3, -1), (4, 1)], lam=F(1, 2), mu=-1)
    sh = curve.shape
    lo, hi = curve.domain
    coeffs = curve._coefficients(0)
    centred = ap.CentredCurve(
        coeffs, lo, hi, curve._mid, sh.omega0, sh.powers, sh.harmonics, sh.hyperbolic
    )
    degree, count, bound, tol = ap.choose_pieces(centred)
    assert bound <= tol
    amp = ap.amplitudes(centred)
    wider = 0.5 * (hi - lo) / (count - 1)
    assert float(ap.remainder_bound(amp, degree, wider, hi - lo).max()) > tol  # one fewer fails
    assert count * 2 * (degree + 1) * 8 <= ap.TABLE_BYTES


def test_no_certified_form_falls_back_to_the_atoms():
    """A frequency no table of MAX_PIECES pieces reaches: no piecewise form, and evaluation
    stays right (through the atoms)."""
    coeffs = np.zeros((3, 1))
    coeffs[1] = 1.0  # cos(ω τ)
    fast = ap.CentredCurve(coeffs, 0.0, 1.0, 0.5, 1e6, 0, 1, False)
    assert ap.choose_pieces(fast) is None
    assert ap.build(fast, np.zeros((3, 3))) is None
    coeffs[1] = math.inf
    assert ap.choose_pieces(ap.CentredCurve(coeffs, 0.0, 1.0, 0.5, 1.0, 0, 1, False)) is None


def test_hazmat_table_against_atom_evaluation():
    """Each piece's Taylor polynomial, at its centre and its ends, is the atoms' value."""
    omega0, powers, harmonics = 2.0, 2, 2
    rng = np.random.default_rng(7)
    coeffs = rng.normal(size=(1 + powers + 2 * harmonics, 2))
    d = ak.derivative_matrix(omega0, powers, harmonics, True)
    pieces = ap.build(ap.CentredCurve(coeffs, -0.5, 1.5, 0.5, omega0, powers, harmonics, True), d)
    assert pieces is not None
    t = np.concatenate([pieces.centres, pieces.centres - pieces.width / 2, [1.5]])
    want = ak.evaluate(coeffs, t - 0.5, omega0, powers, harmonics, True)
    got = ap.evaluate_pieces(pieces, t)
    assert np.abs(got - want).max() <= 8 * np.spacing(np.abs(want).max())


def test_long_arrays_take_the_pieces_only_with_the_kernel(monkeypatch):
    fam = lb.load_family(HAN)
    t = np.linspace(0, math.pi / 2, ap.PIECES_FROM)
    for on in (True, False):
        monkeypatch.setattr(kernels, "USE_COMPILED", on)
        if on and ap.compiled() is None:
            continue
        curve = fam.curve([(0, 0), (1, 3), (3, -1), (4, 1)], lam=F(1, 2), mu=-1)
        curve.evaluate(t[:-1])  # one short of the switch: the atoms
        assert curve._pieces == {}
        got = curve.evaluate(t)
        assert (0 in curve._pieces) == on
        if on:
            assert np.array_equal(got, ap.evaluate_pieces(curve._pieces[0], t).T)
