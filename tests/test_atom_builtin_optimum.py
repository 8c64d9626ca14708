"""optimal_parameters with a trigonometric, hyperbolic or mixed family in one direction and a
built-in family (named, or its curve class) in the other, in either order, and with a
several-parameter or indexed polynomial family beside a built-in name, against an independent
reference: the energy by Gauss–Legendre quadrature of the surface's second derivatives (not
the energy matrices), its biquadratic form in (λ_u, λ_v) interpolated from a 3 x 3 grid and
checked at other points, then a dense grid over the box and an mpmath polish (40 digits) of
the interior critical point and of each edge's exact minimum."""

from __future__ import annotations

import itertools
from fractions import Fraction as F

import mpmath
import numpy as np
import pytest
from conftest import ROOT, surface_families

import lambda_bezier as lb
from lambda_bezier.param_surface_energy import _direction
from lambda_bezier.param_surfaces import family_surface

TRIG, TWO, QB, HYP, MIXED = surface_families()
DATA = ROOT / "tests" / "data" / "families"
AT = lb.load_family(DATA / "at_cubic.toml")
HAN_QUAD = lb.load_family(DATA / "lit_han_quad_trig.toml")
NODES, WEIGHTS = np.polynomial.legendre.leggauss(24)


def net(m: int, n: int) -> list:
    return [
        [(i, j, F((i * j + i) % 3, 2) - F(i * i, 5)) for j in range(n + 1)] for i in range(m + 1)
    ]


def named(fam: object) -> object:
    return lb.curves.family_class(fam) if isinstance(fam, str) else fam


def surface(grid: list, pair: tuple, x: object, y: object) -> lb.Surface:
    """The surface of `pair` at λ_u = x, λ_v = y (None: a direction without a parameter)."""
    kw: dict = {}
    for fam, value, d in ((pair[0], x, "u"), (pair[1], y, "v")):
        if value is None:
            continue
        if isinstance(fam, str | type):  # a built-in family by name or curve class
            kw[f"lam_{d}"] = value
        else:
            kw[f"params_{d}"] = {fam.parameters[0]: value}
    return family_surface(grid, pair, **kw, check_range=False)  # an open end's limit too


def quadrature_energy(s: lb.Surface, energy: str) -> float:
    """∫∫ over the patch's own domain, Gauss–Legendre in each direction."""
    (a, b), (c, d) = (getattr(s, "domain_u", (0, 1)), getattr(s, "domain_v", (0, 1)))
    u = (float(b) - float(a)) / 2 * NODES + (float(a) + float(b)) / 2
    v = (float(d) - float(c)) / 2 * NODES + (float(c) + float(d)) / 2
    uu, vv = np.meshgrid(u, v, indexing="ij")
    w = np.outer(WEIGHTS, WEIGHTS) * (float(b) - float(a)) * (float(d) - float(c)) / 4
    terms = {"membrane": [(1, 1, 0), (1, 0, 1)], "thin_plate": [(1, 2, 0), (2, 1, 1), (1, 0, 2)]}
    terms = terms[energy]
    total = np.zeros_like(w)
    for k, du, dv in terms:
        total += k * np.sum(np.asarray(s.derivative(uu, vv, du, dv)) ** 2, axis=-1)
    return float(np.sum(w * total))


def box(fam: object, degree: int) -> tuple[float, float] | None:
    d = _direction(named(fam), degree)
    if not d.names:
        return None
    lo, hi, *_ = d.ranges[d.names[0]]
    return float(lo), float(hi)


def reference_minimum(grid: list, pair: tuple, energy: str) -> tuple[float, tuple]:
    """(min, point) of the energy over the closed box, from the quadrature."""
    m, n = len(grid) - 1, len(grid[0]) - 1
    boxes = [box(pair[0], m), box(pair[1], n)]
    axes = [
        b[0] + (b[1] - b[0]) * np.array([0.05, 0.5, 0.95]) if b else np.array([np.nan])
        for b in boxes
    ]
    deg = [2 if b else 0 for b in boxes]

    def e(x: float, y: float) -> float:
        xx = None if np.isnan(x) else F(x)
        yy = None if np.isnan(y) else F(y)
        return quadrature_energy(surface(grid, pair, xx, yy), energy)

    # E = sum c_ab x^a y^b (a <= deg[0], b <= deg[1]): interpolated on the 3 x 3 grid
    pts = list(itertools.product(axes[0], axes[1]))
    mons = [(a, b) for a in range(deg[0] + 1) for b in range(deg[1] + 1)]

    def row(x: float, y: float) -> list[float]:
        return [(1 if a == 0 else x**a) * (1 if b == 0 else y**b) for a, b in mons]

    coef = np.linalg.solve(np.array([row(x, y) for x, y in pts]), [e(x, y) for x, y in pts])
    fit = dict(zip(mons, coef, strict=True))
    # the form holds elsewhere (the families are affine in their parameter)
    for t in (0.31, 0.77):
        x = boxes[0][0] + t * (boxes[0][1] - boxes[0][0]) if boxes[0] else np.nan
        y = boxes[1][0] + (1 - t) * (boxes[1][1] - boxes[1][0]) if boxes[1] else np.nan
        assert abs(np.dot(row(x, y), coef) - e(x, y)) <= 1e-11 * abs(e(x, y))

    mpmath.mp.dps = 40

    def E(x: object, y: object) -> object:  # noqa: N802
        return sum(
            mpmath.mpf(c) * (1 if a == 0 else x**a) * (1 if b == 0 else y**b)
            for (a, b), c in fit.items()
        )

    lo = [b[0] if b else 0.0 for b in boxes]
    hi = [b[1] if b else 0.0 for b in boxes]
    xs, ys = np.linspace(lo[0], hi[0], 201), np.linspace(lo[1], hi[1], 201)
    cands = [(mpmath.mpf(x), mpmath.mpf(y)) for x in (lo[0], hi[0]) for y in (lo[1], hi[1])]
    for axis in (0, 1):  # each edge: E is quadratic in the free parameter there
        if not boxes[axis]:
            continue
        for fixed in (lo[1 - axis], hi[1 - axis]) if boxes[1 - axis] else (0.0,):

            def along(t: object, axis: int = axis, fixed: float = fixed) -> object:
                return E(t, mpmath.mpf(fixed)) if axis == 0 else E(mpmath.mpf(fixed), t)

            c0, c1, c2 = (along(mpmath.mpf(t)) for t in (0, 1, -1))
            a2, a1 = (c1 + c2) / 2 - c0, (c1 - c2) / 2
            if a2 > 0:
                t = -a1 / (2 * a2)
                if lo[axis] <= t <= hi[axis]:
                    cands.append((t, mpmath.mpf(fixed)) if axis == 0 else (mpmath.mpf(fixed), t))
    if boxes[0] and boxes[1]:  # the interior: the dense grid's best, polished by Newton
        xx, yy = np.meshgrid(xs, ys, indexing="ij")
        vals = sum(c * xx**a * yy**b for (a, b), c in fit.items())
        i, j = np.unravel_index(np.argmin(vals), vals.shape)
        try:
            x, y = mpmath.findroot(
                [
                    lambda x, y: mpmath.diff(E, (x, y), (1, 0)),
                    lambda x, y: mpmath.diff(E, (x, y), (0, 1)),
                ],
                (mpmath.mpf(xs[i]), mpmath.mpf(ys[j])),
            )
            if lo[0] <= x <= hi[0] and lo[1] <= y <= hi[1]:
                cands.append((x, y))
        except (ValueError, ZeroDivisionError):
            pass  # no interior critical point near the grid's best: a boundary minimum
    best = min(cands, key=lambda p: E(*p))
    middle = E(mpmath.mpf((lo[0] + hi[0]) / 2), mpmath.mpf((lo[1] + hi[1]) / 2))
    return float(E(*best)), float(middle)


PAIRS = [
    ((AT, "same_degree"), (3, 3)),
    (("bernstein_like", AT), (3, 3)),
    ((MIXED, "same_degree"), (3, 3)),
    (("same_degree", HAN_QUAD), (3, 2)),
    ((AT, lb.BernsteinLikeCurve), (3, 3)),
    (("bezier", AT), (3, 3)),
]


@pytest.mark.parametrize("energy", ["thin_plate", "membrane"])
@pytest.mark.parametrize(("pair", "shape"), PAIRS, ids=lambda p: str(p)[:40])
def test_the_minimum_is_the_dense_grid_and_mpmath_one(pair, shape, energy):
    grid = net(*shape)
    got = lb.optimal_parameters(grid, energy, family=pair)
    assert got.certified
    ref, scale = reference_minimum(grid, pair, energy)
    value = float(got.energy)
    # relative to the energy's size over the box (at_pi_cubic's thin-plate infimum is 0, at
    # its excluded end λ_u = 1, where the basis degenerates)
    assert abs(value - ref) <= 1e-10 * scale, (value, ref, got)
    assert float(got.lower_bound) <= ref + 1e-10 * scale
    assert value - float(got.lower_bound) <= 1e-12 * scale
    # the energy at the answer's parameters, by quadrature, is the answer's energy
    values = list(got.parameters.values())
    xs: list = [None, None]
    it = iter(values)
    for k, f in enumerate(pair):
        if box(f, shape[k]) is not None:
            xs[k] = F(next(it))
    attained = quadrature_energy(surface(grid, pair, *xs), energy)
    assert abs(attained - value) <= 1e-10 * scale
    # float input: the same minimum within the certificate
    fl = lb.optimal_parameters(np.array(grid, dtype=float), energy, family=pair)
    assert abs(float(fl.energy) - value) <= 1e-11 * scale


@pytest.mark.parametrize(("pair", "shape"), PAIRS[:4], ids=lambda p: str(p)[:40])
def test_a_batch_agrees_with_one_net_at_a_time(pair, shape):
    base = np.array(net(*shape), dtype=float)
    nets = np.stack([base, base * [1, 1, 2], base + [0, 0, 0.25] * base[..., :1] ** 2])
    got = lb.optimal_parameters(nets, "thin_plate", family=pair)
    for k in range(len(nets)):
        one = lb.optimal_parameters(nets[k], "thin_plate", family=pair)
        assert abs(got.energy[k] - float(one.energy)) <= 1e-11 * float(one.energy)


@pytest.mark.parametrize(
    "pair", [(TWO, "same_degree"), ("bernstein_like", TWO), (QB, "same_degree"), (TRIG, "bezier")]
)
def test_several_parameters_beside_a_builtin_name(pair):
    """A family with several (or indexed) parameters beside a built-in name: certified, and
    no sampled point of the box does better than the proven lower bound."""
    grid = net(3, 3)
    got = lb.optimal_parameters(grid, "membrane", family=pair)
    assert got.certified
    rng = np.random.default_rng(7)
    boxes = []
    for fam, deg in zip(pair, (3, 3), strict=True):
        d = _direction(named(fam), deg)
        boxes.append([(float(d.ranges[x][0]), float(d.ranges[x][1])) for x in d.names])
    for _ in range(8):
        given = []
        for b in boxes:
            vals = [F(float(rng.uniform(lo, hi))).limit_denominator(64) for lo, hi in b]
            given.append(vals)
        kw: dict = {}
        for fam, vals, d in zip(pair, given, "uv", strict=True):
            if isinstance(fam, str):
                if vals:
                    kw[f"lam_{d}"] = vals[0]
            elif hasattr(fam, "index_name"):
                kw[f"params_{d}"] = {fam.index_name: vals}
            else:
                kw[f"params_{d}"] = dict(zip(fam.parameters, vals, strict=True))
        s = family_surface(grid, pair, **kw)
        assert quadrature_energy(s, "membrane") >= float(got.lower_bound) * (1 - 1e-12)


def test_a_batch_with_two_parameters_or_none_in_a_direction_is_each_nets_minimum():
    """Such batches were refused (the fixed-cost certificate is for two variables); they now
    take the vectorised search and certificate (hazmat.box_batch), which takes both nets of
    both pairs, against each net's one-net certified minimum (param_surface_optimum)."""
    nets = np.zeros((2, 4, 4, 3))
    nets[:] = np.array(net(3, 3), dtype=float)
    nets[1, 1, 2] += (0.5, -0.25, 1.0)
    for pair in ((TWO, "same_degree"), ("bezier", AT)):
        got = lb.optimal_parameters(nets, "thin_plate", family=pair)
        assert got.careful_fallbacks == 0
        for i in range(2):
            one = lb.optimal_parameters(nets[i], "thin_plate", family=pair)
            best, lower = float(one.energy), float(one.lower_bound)
            assert lower - 1e-12 * best <= got.energy[i] <= best + 1e-12 * best
