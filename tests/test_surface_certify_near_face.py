"""The interior certificate near a face (hazmat.surface_certify.certified_minimum): R's
half-width shrinks to NEAR_FACE of the point's distance to the nearest face, so minima within
RADIUS of a face are certified too. Checked on adversarial energies against the exact global
minimiser over the box (surface_energies.minimise_polynomial: resultants and exact real-root
isolation on the float coefficients' exact rational values), in both engines: a certified
answer must be within its δ <= tol of that minimiser, whatever the distance to the face
(inside, on the face, one ulp outside, far outside), and minima a little inside a face must
now be certified."""

from __future__ import annotations

from fractions import Fraction
from functools import cache
from importlib.util import find_spec

import numpy as np
import pytest

from lambda_bezier.hazmat import surface_certify as sc
from lambda_bezier.surface_energies import minimise_polynomial

BOX = (-2.0, 1.0, -2.0, 1.0)
TOL = 1e-12
R0 = sc.RADIUS * 3.0  # R's half-width away from the faces, for this box


def _engines():
    yield "numpy"
    if find_spec("numba") is not None:
        yield "numba"


def certify(engine, e):
    """certified_minimum's (x, y, δ, certified) for the coefficients e[(a, b)] (the compiled
    engine: its cached kernel's certificate stage, status 1.0 for this certificate)."""
    c = [float(e.get((a, b), 0.0)) for a in range(3) for b in range(3)]
    if engine == "numba":
        from lambda_bezier.hazmat import surface_batch_compiled as sbc

        out = np.empty((5, 1))
        sbc._certify_chunk(np.array(c).reshape(9, 1), 1, np.array(BOX), TOL, out)
        return out[0, 0], out[1, 0], out[3, 0], bool(out[4, 0] == 1.0)
    x, y, _, delta, ok = sc.certified_minimum(*(np.array([v]) for v in c), *BOX, TOL)
    return float(x[0]), float(y[0]), float(delta[0]), bool(ok[0])


def exact_minimiser(e):
    """The global minimiser over the closed box of Σ e_ab x^a y^b, e's floats taken exactly."""
    poly = {k: Fraction(v) for k, v in e.items() if v}
    lo, hi = Fraction(BOX[0]), Fraction(BOX[1])
    x, y, _ = minimise_polynomial(poly, (lo, hi), (lo, hi))
    return float(x), float(y)


def expand(terms, sx, sy):
    """Σ c X^a Y^b with X = x − sx, Y = y − sy, as float coefficients of x^a y^b (the
    expansion in Fractions, each coefficient rounded once)."""
    binom = ((1,), (1, 1), (1, 2, 1))
    out: dict[tuple[int, int], Fraction] = {}
    for (a, b), c in terms.items():
        for i in range(a + 1):
            for j in range(b + 1):
                coeff = Fraction(c) * binom[a][i] * binom[b][j]
                coeff *= Fraction(-sx) ** (a - i) * Fraction(-sy) ** (b - j)
                out[i, j] = out.get((i, j), Fraction(0)) + coeff
    return {k: float(v) for k, v in out.items()}


def check(engine, e):
    """A certified answer is within its δ of the exact minimiser; returns whether certified."""
    x, y, delta, ok = certify(engine, e)
    if ok:
        ex, ey = exact_minimiser(e)
        assert delta <= TOL
        # δ bounds the distance to the exact minimiser; its conversion to float adds half an ulp
        assert abs(x - ex) <= delta + 2.0**-52 * abs(ex), (x, ex, delta)
        assert abs(y - ey) <= delta + 2.0**-52 * abs(ey), (y, ey, delta)
    return ok


# distances of the critical point from the face (negative: outside the box, where the box's
# minimum is on the face and an interior answer would be wrong)
DISTANCES = [0.9 * R0, 0.3 * R0, 1e-3, 1e-6, 1e-9, 1e-13, 2.0**-52, 0.0, -(2.0**-52), -1e-9]


@pytest.mark.parametrize("engine", list(_engines()))
@pytest.mark.parametrize("face", ["xlo", "xhi", "ylo", "yhi", "corner"])
def test_convex_minima_near_a_face_are_certified_only_where_right(engine, face):
    certified = []
    for d in DISTANCES:
        sx = sy = -0.4  # the critical point (X, Y) = (0, 0): away from every face...
        if face in ("xlo", "corner"):
            sx = BOX[0] + d  # ...but this one
        if face == "xhi":
            sx = BOX[1] - d
        if face in ("ylo", "corner"):
            sy = BOX[2] + d
        if face == "yhi":
            sy = BOX[3] - d
        # a convex quadratic with a cross term, about (sx, sy), plus a small λ_u λ_v part
        terms = {(2, 0): 1.5, (0, 2): 0.75, (1, 1): 0.5, (0, 0): 2.0, (2, 2): 0.01}
        certified.append(check(engine, expand(terms, sx, sy)))
    # inside by 1e-3 (1/3000 of the box) or more: certified now (the fixed RADIUS declined
    # all but the first; nearer, the global clearing's Bernstein test declines, 3e-4 to 1e-4
    # here); on the face or outside: never by the interior certificate
    assert certified[:3] == [True] * 3
    assert certified[-3:] == [False] * 3


@pytest.mark.parametrize("engine", list(_engines()))
@pytest.mark.parametrize("c1, c2", [(0.05, 0.05), (-0.05, -0.05), (0.05, -0.1), (0.0, 0.0)])
@pytest.mark.parametrize("d", [1e-4, 1e-8])
def test_two_basins_with_one_near_a_face_are_never_certified_wrong(engine, c1, c2, d):
    # (XY − 1)² + (X² + Y²) / 2 + c1 X + c2 Y, two basins about ±(0.707, 0.707) in (X, Y),
    # placed so that the (−, −) basin's minimiser is about d inside the corner (xlo, ylo):
    # where the start falls into the worse basin the certificate must decline
    shift = 0.5**0.5
    terms = {(2, 2): 1.0, (1, 1): -2.0, (0, 0): 1.0, (2, 0): 0.5, (0, 2): 0.5}
    terms |= {(1, 0): c1, (0, 1): c2}
    check(engine, expand(terms, BOX[0] + d + shift, BOX[2] + d + shift))


@pytest.mark.parametrize("engine", list(_engines()))
def test_a_concave_direction_near_a_face_is_declined(engine):
    # E = −(x − xlo − 1e-3)² + (y + 0.5)²: the x-critical point is a maximum 1e-3 inside the
    # face; the box's minimum is at x = xhi, the far face
    e = expand({(2, 0): -1.0, (0, 2): 1.0}, BOX[0] + 1e-3, -0.5)
    assert not check(engine, e)


def benchmark_nets(count):
    """The surfaces benchmark's batch (benchmarks/bench_surfaces.py): its first `count` nets."""
    rng = np.random.default_rng(4)
    rng.normal(size=(4, 4, 3))  # the grid row's surface, drawn first
    nets = rng.normal(size=(count, 4, 4, 3))
    nets[..., 0] += np.arange(4)[:, None]
    nets[..., 1] += np.arange(4)[None, :]
    return nets


NEAR_FACE_NETS = (271, 333, 938)  # of the benchmark's batch: interior minima near a face


@cache
def exact_answers():
    """The exact optimum of each of those nets read as exact binary fractions (the one-net
    path: resultants and exact real-root isolation), once for both engines."""
    import lambda_bezier as lb

    out = []
    for net in benchmark_nets(max(NEAR_FACE_NETS) + 1)[list(NEAR_FACE_NETS)]:
        exact_net = [[[Fraction(float(c)) for c in p] for p in row] for row in net]
        one = lb.optimal_parameters(exact_net, "thin_plate")
        out.append((one["where"], one["lam_u_float"], one["lam_v_float"]))
    return out


@pytest.mark.parametrize("engine", list(_engines()))
def test_the_benchmark_nets_near_a_face_take_the_fixed_cost_path(engine, monkeypatch):
    """Three nets of the benchmark's batch with interior minima 0.002-0.045 from a face,
    which the fixed RADIUS sent to the careful path: now certified, each within 1e-12 of the
    exact optimum."""
    import lambda_bezier as lb
    from lambda_bezier.hazmat import surface_kernels

    monkeypatch.setattr(surface_kernels, "USE_COMPILED", engine == "numba")
    nets = benchmark_nets(max(NEAR_FACE_NETS) + 1)[list(NEAR_FACE_NETS)]
    res = lb.optimal_parameters(nets, "thin_plate")
    assert res["careful_fallbacks"] == 0
    for i, (where, u, v) in enumerate(exact_answers()):
        assert where == res["where"][i] == "interior"
        assert abs(u - res["lam_u"][i]) <= 1e-12 and abs(v - res["lam_v"][i]) <= 1e-12
        gap = min(abs(t - end) for t in (u, v) for end in (BOX[0], BOX[1]))
        assert gap < R0  # the fixed R would not have fitted in the box
