"""Third acceptance pass of issue #31 (surfaces): what tests/test_acceptance_31.py and
tests/test_acceptance_31b.py do not cover, each against a computation that does not use the
code under test (mpmath at 50 digits on the exact Bézier form or on a closed form, exact
Fractions, dense sampling)."""

from __future__ import annotations

import functools
from fractions import Fraction as F

import mpmath as mp
import numpy as np
import pytest

import lambda_bezier as lb

# ------------------------------------------------ curvatures near a degenerate point
# The graph z = (x² + y²) / 2 over x = u + v, y = eps v: a biquadratic Bézier surface whose
# partials S_u = (1, 0, x) and S_v = (1, eps, x + eps² v) are nearly parallel for a small eps,
# while its curvatures are those of the paraboloid, K = 1 / w², H = (1 + w) / (2 w^(3/2)),
# w = 1 + x² + y² (sign: the normal S_u x S_v points up).
_T, _T2 = (F(0), F(1, 2), F(1)), (F(0), F(0), F(1))  # Bernstein coefficients of t, t²


def _sheared_paraboloid(eps: F) -> lb.BezierSurface:
    return lb.BezierSurface(
        [
            [
                (
                    _T[i] + _T[j],
                    eps * _T[j],
                    (_T2[i] + 2 * _T[i] * _T[j] + (1 + eps**2) * _T2[j]) / 2,
                )
                for j in range(3)
            ]
            for i in range(3)
        ]
    )


def _paraboloid_curvatures(eps: F, u: float, v: float) -> tuple[float, float]:
    with mp.workdps(50):
        x = mp.mpf(u) + mp.mpf(v)
        y = mp.mpf(eps.numerator) / eps.denominator * mp.mpf(v)
        w = 1 + x * x + y * y
        return float(1 / w**2), float((1 + w) / (2 * w ** mp.mpf(1.5)))


@pytest.mark.parametrize("k", [1, 2, 3, 4])
def test_curvatures_where_the_partials_are_nearly_parallel(k):
    """Where the curvatures are returned they are the paraboloid's, to 1e-7 (before: K was
    computed with EG - F², which cancels; it was wrong by 4e-4 at eps = 1e-6)."""
    eps = F(1, 10**k)
    K, H = _sheared_paraboloid(eps).curvatures(0.3, 0.4)
    K_ref, H_ref = _paraboloid_curvatures(eps, 0.3, 0.4)
    assert pytest.approx(K_ref, rel=1e-7) == K
    assert pytest.approx(H_ref, rel=1e-7) == H


@pytest.mark.parametrize("k", [6, 7, 8])
def test_curvatures_decided_by_rounding_are_refused(k):
    """Before: eps = 1e-7 gave K = 0.4098 (the true 0.4504, 9% off) without a word, eps = 1e-8
    a ValueError calling the curvature beyond the float range (EG - F² came out 0) and a
    divide-by-zero RuntimeWarning. Now a ValueError naming the point, as for the normal."""
    surf = _sheared_paraboloid(F(1, 10**k))
    surf.normal(0.3, 0.4)  # the normal itself is still defined within rounding
    with pytest.raises(
        ValueError, match=r"curvature is undefined within rounding at \(u, v\) = \(0.3, 0.4\)"
    ):
        surf.curvatures(0.3, 0.4)
    with pytest.raises(ValueError, match="undefined within rounding"):
        surf.curvatures(np.array([0.1, 0.3]), np.array([0.1, 0.4]))


def _bezier_curvatures(surf: lb.Surface, u: float, v: float) -> tuple[mp.mpf, mp.mpf]:
    """K and H of the exact Bézier form, at 50 digits (Bernstein derivatives by mpmath)."""
    net = surf.to_bezier().control_net()
    m, n = len(net) - 1, len(net[0]) - 1
    with mp.workdps(50):
        uu, vv = mp.mpf(u), mp.mpf(v)

        def bern(k: int, deg: int, t: mp.mpf, order: int) -> mp.mpf:
            return mp.diff(lambda x: mp.binomial(deg, k) * x**k * (1 - x) ** (deg - k), t, order)

        bu = {(i, a): bern(i, m, uu, a) for i in range(m + 1) for a in range(3)}
        bv = {(j, b): bern(j, n, vv, b) for j in range(n + 1) for b in range(3)}

        def part(a: int, b: int) -> list[mp.mpf]:
            return [
                mp.fsum(
                    mp.mpf(net[i][j][c].numerator) / net[i][j][c].denominator * bu[i, a] * bv[j, b]
                    for i in range(m + 1)
                    for j in range(n + 1)
                )
                for c in range(3)
            ]

        su, sv, suu, suv, svv = part(1, 0), part(0, 1), part(2, 0), part(1, 1), part(0, 2)
        dot = lambda x, y: mp.fsum(p * q for p, q in zip(x, y, strict=True))  # noqa: E731
        cross = [
            su[1] * sv[2] - su[2] * sv[1],
            su[2] * sv[0] - su[0] * sv[2],
            su[0] * sv[1] - su[1] * sv[0],
        ]
        nrm = [x / mp.sqrt(dot(cross, cross)) for x in cross]
        e, f, g = dot(su, su), dot(su, sv), dot(sv, sv)
        l_, m_, n_ = dot(suu, nrm), dot(suv, nrm), dot(svv, nrm)
        det = e * g - f * f
        return (l_ * n_ - m_ * m_) / det, (e * n_ - 2 * f * m_ + g * l_) / (2 * det)


# row 0 is one point: the edge u = 0 collapses and the curvatures grow like 1/u towards it
_COLLAPSED = [[(0, 0, 0)] * 4] + [[(i, j, (i * j) % 3) for j in range(4)] for i in range(1, 4)]


_COLLAPSED_V = [list(col) for col in zip(*_COLLAPSED, strict=True)]  # the edge v = 0 instead


@pytest.mark.parametrize(
    ("surf", "along_v"),
    [
        (lb.SameDegreeSurface(_COLLAPSED, F(1, 2), F(-1, 3)), False),
        (lb.BernsteinLikeSurface(_COLLAPSED, F(1, 3), F(1, 5)), False),
        (lb.SameDegreeSurface(_COLLAPSED_V, F(-1, 3), F(1, 2)), True),
        (lb.BernsteinLikeSurface(_COLLAPSED_V, F(1, 5), F(1, 3)), True),
    ],
    ids=["same_degree", "bernstein_like", "same_degree_v", "bernstein_like_v"],
)
def test_curvatures_towards_a_collapsed_edge(surf, along_v):
    """Every curvature returned on the way to the collapsed edge (u = 0, or v = 0) is the
    exact form's to 1e-6; at 1e-12 from it the point is refused (the normal, or the
    curvature, undefined within rounding), never a wild float."""
    for k in (2, 4, 6, 8):
        u, v = (0.4, 10.0**-k) if along_v else (10.0**-k, 0.4)
        K, H = surf.curvatures(u, v)
        K_ref, H_ref = _bezier_curvatures(surf, u, v)
        assert float(K_ref) == pytest.approx(K, rel=1e-6)
        assert float(H_ref) == pytest.approx(H, rel=1e-6)
    with pytest.raises(ValueError, match="undefined"):
        surf.curvatures(*((0.4, 1e-12) if along_v else (1e-12, 0.4)))


# ---------------------------------------------------------------- JSON, untrusted text
@pytest.mark.parametrize("depth", [100_000, 5_000])
def test_deeply_nested_json_is_a_value_error(depth):
    """Before: surface_from_json (and the curves' loader) let the decoder's RecursionError
    through, a deep traceback from untrusted text."""
    from lambda_bezier._json_io import _load_document
    from lambda_bezier.surface_export import surface_from_json

    text = "[" * depth + "]" * depth
    for load in (surface_from_json, _load_document):
        with pytest.raises(ValueError, match="nested too deeply"):
            load(text)
    inside = '{"lambda_bezier": 1, "kind": "surface", "net": ' + text + "}"
    with pytest.raises(ValueError, match="nested too deeply"):
        surface_from_json(inside)


def test_deeply_nested_family_files_are_named_errors(tmp_path):
    """A family definition (TOML) or derived document (JSON) nested past the recursion limit:
    before, RecursionError from the decoder; now the FamilyFileError (a ValueError) naming
    the file."""
    deep = tmp_path / "deep.toml"
    deep.write_text("a = " + "[" * 100_000 + "]" * 100_000 + "\n", encoding="utf-8")
    with pytest.raises(ValueError, match="deep.toml: not valid TOML: nested too deeply"):
        lb.load_family(deep)
    from lambda_bezier import examples

    src = examples.path("nouri_saeidian.toml")
    (tmp_path / "nouri_saeidian.toml").write_text(src.read_text(encoding="utf-8"), "utf-8")
    (tmp_path / "nouri_saeidian.derived.json").write_text("[" * 100_000 + "]" * 100_000)
    with pytest.raises(ValueError, match="not a derived family document"):
        lb.load_family(tmp_path / "nouri_saeidian.toml")


def test_deeply_nested_records_file_is_named(tmp_path):
    """`lambda-bezier verify` on a records file nested past the recursion limit: before, a
    RecursionError traceback; now exit 2 with the file named."""
    import subprocess
    import sys

    deep = tmp_path / "deep.records.toml"
    deep.write_text("a = " + "[" * 20_000 + "]" * 20_000 + "\n", encoding="utf-8")
    run = subprocess.run(
        [sys.executable, "-m", "lambda_bezier", "verify", str(deep)],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert "Traceback" not in run.stderr
    assert "deep.records.toml: not valid TOML: nested too deeply" in run.stderr
    assert run.returncode != 0


# ------------------------------------------ an exact reference from the basis definitions
# Polynomials in t as tuples of Fraction coefficients (ascending powers), built from each
# family's definition (000's eq. 1, 001's seed and recursion, Bernstein): nothing from the
# package but the classes under test.
def _pmul(a, b):
    out = [F(0)] * (len(a) + len(b) - 1)
    for i, x in enumerate(a):
        for j, y in enumerate(b):
            out[i + j] += x * y
    return tuple(out)


def _padd(*ps):
    out = [F(0)] * max(len(p) for p in ps)
    for p in ps:
        for i, x in enumerate(p):
            out[i] += x
    return tuple(out)


def _pscale(c, p):
    return tuple(c * x for x in p)


def _ppow(p, k):
    out = (F(1),)
    for _ in range(k):
        out = _pmul(out, p)
    return out


def _pder(p, k=1):
    for _ in range(k):
        p = tuple(i * p[i] for i in range(1, len(p))) or (F(0),)
    return p


def _peval(p, t):
    return sum((c * t**i for i, c in enumerate(p)), F(0))


def _pint(p):  # the integral over [0, 1]
    return sum((c / (i + 1) for i, c in enumerate(p)), F(0))


_TT, _ST = (F(0), F(1)), (F(1), F(-1))  # t and 1 - t


def _binom(a, b):
    from math import comb

    return comb(a, b) if 0 <= b <= a else 0


def _basis(family, n, lam):
    """The degree-n basis of a family as exact polynomials in t, from its definition."""
    lam = F(lam) if lam is not None else None
    if family == "bezier":
        return [
            _pscale(F(_binom(n, i)), _pmul(_ppow(_ST, n - i), _ppow(_TT, i))) for i in range(n + 1)
        ]
    if family == "same_degree":
        out = []
        for i in range(n + 1):
            terms = [_pscale(F(_binom(n, i)), _pmul(_ppow(_ST, n - i), _ppow(_TT, i)))]
            for coeff, ps, pt in (
                (_binom(n - 3, i - 3), n - i + 1, i - 1),
                (-_binom(n - 2, i - 1), n - i, i),
                (_binom(n - 3, i), n - i - 1, i + 1),
            ):
                if coeff:
                    terms.append(_pscale((1 - lam) * coeff, _pmul(_ppow(_ST, ps), _ppow(_TT, pt))))
            out.append(_padd(*terms))
        return out
    if family == "nouri_saeidian":  # its definition file's basis, phi = 3t² - 2t³
        phi = (F(0), F(0), F(3), F(-2))
        out = [
            _pscale(lam * _binom(n, i), _pmul(_ppow(_ST, n - i), _ppow(_TT, i)))
            for i in range(n + 1)
        ]
        out[0] = _padd(out[0], _pscale(1 - lam, _padd((F(1),), _pscale(F(-1), phi))))
        out[n] = _padd(out[n], _pscale(1 - lam, phi))
        return out
    assert family == "bernstein_like"
    one = (F(1),)
    b = [
        _pmul(_padd(one, _pscale(-2 * lam, _TT), _pscale(lam, _ppow(_TT, 2))), _ppow(_ST, 2)),
        _pmul(
            _pscale(F(2), _pmul(_TT, _ST)),
            _padd(one, (lam,), _pscale(-lam, _TT), _pscale(lam, _ppow(_TT, 2))),
        ),
        _pmul(_padd((1 - lam,), _pscale(lam, _ppow(_TT, 2))), _ppow(_TT, 2)),
    ]
    for deg in range(3, n + 1):
        b = [
            _padd(
                _pmul(_ST, b[i]) if i < deg else (F(0),),
                _pmul(_TT, b[i - 1]) if i >= 1 else (F(0),),
            )
            for i in range(deg + 1)
        ]
    return b


def _exact_partial(families, lams, net, u, v, du=0, dv=0):
    """∂^(du+dv) S(u, v) exactly, from the definitions."""
    net = [[tuple(F(x) for x in p) for p in row] for row in net]
    bu = [_peval(_pder(p, du), F(u)) for p in _basis(families[0], len(net) - 1, lams[0])]
    bv = [_peval(_pder(p, dv), F(v)) for p in _basis(families[1], len(net[0]) - 1, lams[1])]
    d = len(net[0][0])
    return tuple(
        sum((bu[i] * bv[j] * net[i][j][c] for i in range(len(bu)) for j in range(len(bv))), F(0))
        for c in range(d)
    )


@functools.cache
def _gram(family, n, lam, order):
    """∫ b_i^(order) b_k^(order) over [0, 1], exactly."""
    basis = [_pder(p, order) for p in _basis(family, n, lam)]
    return [[_pint(_pmul(p, q)) for q in basis] for p in basis]


def _exact_energy(families, lams, net, kind):
    """The membrane or thin-plate energy exactly: each term ∫∫ |∂_u^a ∂_v^b S|² is a sum over
    pairs of control points of products of one-dimensional integrals of the definitions."""
    net = [[tuple(F(x) for x in p) for p in row] for row in net]
    m, n, d = len(net) - 1, len(net[0]) - 1, len(net[0][0])
    terms = ((1, 0, 1), (0, 1, 1)) if kind == "membrane" else ((2, 0, 1), (1, 1, 2), (0, 2, 1))
    total = F(0)
    for a, b, weight in terms:
        gu, gv = _gram(families[0], m, lams[0], a), _gram(families[1], n, lams[1], b)
        for i in range(m + 1):
            for j in range(n + 1):
                for k in range(m + 1):
                    for l_ in range(n + 1):
                        dot = sum((net[i][j][c] * net[k][l_][c] for c in range(d)), F(0))
                        total += weight * gu[i][k] * gv[j][l_] * dot
    return total


_NET_45 = [[(i, j, (i * j) % 3, (i + 2 * j) % 4 - 1) for j in range(5)] for i in range(4)]  # d = 4


@pytest.mark.parametrize(
    ("families", "lams"),
    [
        (("same_degree", "bernstein_like"), (F(1, 2), F(-1, 3))),
        (("bernstein_like", "same_degree"), (F(-1, 1), F(-3, 2))),
        (("bezier", "same_degree"), (None, F(1, 4))),
    ],
)
def test_mixed_families_in_four_dimensions_exactly(families, lams):
    """A 4 x 5 net of points in d = 4, a different family, degree and λ in each direction:
    the iso-curves' control points, the energies and the Bézier form's corner derivatives
    are exactly the definitions'; values and partial derivatives agree to rounding."""
    surf = lb.Surface(_NET_45, *lams, family=families)
    assert surf.degrees == (3, 4) and surf.dimension == 4 and surf.is_exact
    for kind in ("membrane", "thin_plate"):
        assert lb.surface_energy(surf, kind) == _exact_energy(families, lams, _NET_45, kind)
    # v -> S(1/3, v) is a curve of the v family at λ_v whose points are Σ_i b_i(1/3) P_ij
    c = surf.curve_at_u(F(1, 3))
    bu = [_peval(p, F(1, 3)) for p in _basis(families[0], 3, lams[0])]
    expected = [
        tuple(sum((bu[i] * F(_NET_45[i][j][k]) for i in range(4)), F(0)) for k in range(4))
        for j in range(5)
    ]
    assert [tuple(p) for p in c.control_points()] == expected
    assert c.family == families[1] and c.lam == lams[1]
    bz = surf.to_bezier()
    for u, v in ((0, 0), (1, 0), (0, 1), (1, 1)):  # every corner, exactly
        for du, dv in ((0, 0), (1, 0), (0, 1), (1, 1), (2, 0), (0, 2)):
            ref = _exact_partial(families, lams, _NET_45, u, v, du, dv)
            got = _exact_partial(("bezier", "bezier"), (None, None), bz.control_net(), u, v, du, dv)
            assert got == ref
    for u, v, du, dv in (
        (F(1, 3), F(2, 7), 0, 0),
        (F(3, 4), F(1, 5), 1, 2),
        (F(1, 9), F(5, 6), 3, 1),
    ):
        ref = np.array([float(x) for x in _exact_partial(families, lams, _NET_45, u, v, du, dv)])
        got = surf.derivative(float(u), float(v), du, dv)
        np.testing.assert_allclose(got, ref, rtol=1e-11, atol=1e-11 * np.abs(ref).max())


def _families(surf):
    fam = surf.family
    return (fam, fam) if isinstance(fam, str) else fam


@pytest.mark.parametrize("side", ["u1", "u0", "v1", "v0"])
@pytest.mark.parametrize("continuity", ["C1", "G1", "C2"])
def test_join_surface_across_families_on_every_side(side, continuity):
    """A same_degree patch continued by a bernstein_like one of degree 4 across the boundary:
    the cross derivatives along the common boundary agree exactly (from the definitions, at
    rational points of the boundary), G1 with the given α; the new patch is of the built-in
    class when its family runs both ways, and the composite reports the continuity."""
    net = [[(i, j, (i * j) % 3) for j in range(4)] for i in range(4)]
    a = lb.SameDegreeSurface(net, F(1, 2), F(-1, 3))
    solved = 3 if continuity == "C2" else 2
    extra = [[(5 + k, j, (j * k) % 2) for j in range(4)] for k in range(5 - solved)]
    rest = extra if side[0] == "u" else [list(col) for col in zip(*extra, strict=True)]
    alpha = F(2) if continuity == "G1" else F(1)
    kw = {"alpha": alpha} if continuity == "G1" else {}
    b = lb.join_surface(a, side, continuity, 4, F(1, 4), rest=rest, family="bernstein_like", **kw)
    assert b.degrees == ((4, 3) if side[0] == "u" else (3, 4))
    first, second = (a, b) if side[1] == "1" else (b, a)  # first ends where second starts
    fa, fb = _families(first), _families(second)
    la, lb_ = (first.lam_u, first.lam_v), (second.lam_u, second.lam_v)
    na, nb = first.control_net(), second.control_net()
    orders = (0, 1, 2) if continuity == "C2" else (0, 1)
    for t in (F(0), F(1, 3), F(4, 5), F(1)):
        for k in orders:
            if side[0] == "u":
                end = _exact_partial(fa, la, na, 1, t, k, 0)
                start = _exact_partial(fb, lb_, nb, 0, t, k, 0)
            else:
                end = _exact_partial(fa, la, na, t, 1, 0, k)
                start = _exact_partial(fb, lb_, nb, t, 0, 0, k)
            # G1: the given patch's cross derivative is α times the new patch's
            if continuity == "G1" and k == 1:
                given, new = (end, start) if first is a else (start, end)
                assert given == tuple(alpha * x for x in new)
            else:
                assert end == start
    grid = [[first], [second]] if side[0] == "u" else [[first, second]]
    assert [r.continuity for r in lb.CompositeSurface(grid).report()] == [continuity]
    same = lb.join_surface(a, side, continuity, 4, F(1, 4), rest=rest, **kw)
    assert type(same) is lb.SameDegreeSurface  # before: the generic Surface on every side


# ------------------------------------------------------------ energy-optimal parameters
def _energy_poly(family, net, kind):
    """{(a, b): e_ab} with E(λ_u, λ_v) = Σ e_ab λ_u^a λ_v^b, exactly: E is quadratic in each
    parameter for a family affine in λ, so 3 x 3 exact values at λ in {-1, 0, 1} fix it."""
    nodes = (F(-1), F(0), F(1))
    values = {
        (x, y): _exact_energy((family, family), (x, y), net, kind) for x in nodes for y in nodes
    }

    def lagrange(k):  # coefficients of the k-th Lagrange polynomial on the nodes
        others = [nodes[i] for i in range(3) if i != k]
        den = (nodes[k] - others[0]) * (nodes[k] - others[1])
        return (others[0] * others[1] / den, -(others[0] + others[1]) / den, F(1) / den)

    out = {}
    for a in range(3):
        for b in range(3):
            out[a, b] = sum(
                (
                    lagrange(i)[a] * lagrange(j)[b] * values[nodes[i], nodes[j]]
                    for i in range(3)
                    for j in range(3)
                ),
                F(0),
            )
    return out


def _e(poly, x, y):
    return sum((c * x**a * y**b for (a, b), c in poly.items()), 0 * x)


def _reference_minimum(poly, lo, hi):
    """The global minimum over [lo, hi]² of the biquadratic E, independently: the corners,
    each edge's vertex, and the interior critical points found by mpmath Newton (50 digits)
    from the best points of a 21 x 21 grid. Returns (energy, x, y) as mpf."""
    with mp.workdps(50):
        c = {k: mp.mpf(v.numerator) / v.denominator for k, v in poly.items()}
        lo, hi = mp.mpf(lo), mp.mpf(hi)
        cands = [(x, y) for x in (lo, hi) for y in (lo, hi)]
        for fixed in (lo, hi):
            # E(fixed, y) = A y² + B y + C, and E(x, fixed) likewise
            for swap in (False, True):
                coef = [
                    sum(c[(b, a) if swap else (a, b)] * fixed**a for a in range(3))
                    for b in range(3)
                ]
                if coef[2] > 0:
                    t = -coef[1] / (2 * coef[2])
                    if lo <= t <= hi:
                        cands.append((t, fixed) if swap else (fixed, t))

        def grad(x, y):
            gx = sum(a * c[a, b] * x ** (a - 1) * y**b for (a, b) in c if a)
            gy = sum(b * c[a, b] * x**a * y ** (b - 1) for (a, b) in c if b)
            return gx, gy

        def hess(x, y):
            hxx = sum(a * (a - 1) * c[a, b] * x ** (a - 2) * y**b for (a, b) in c if a > 1)
            hyy = sum(b * (b - 1) * c[a, b] * x**a * y ** (b - 2) for (a, b) in c if b > 1)
            hxy = sum(a * b * c[a, b] * x ** (a - 1) * y ** (b - 1) for (a, b) in c if a and b)
            return hxx, hxy, hyy

        ev = lambda x, y: sum(c[a, b] * x**a * y**b for (a, b) in c)  # noqa: E731
        grid = [lo + (hi - lo) * k / 20 for k in range(21)]
        starts = sorted(((ev(x, y), x, y) for x in grid for y in grid), key=lambda r: r[0])[:4]
        for _, x, y in starts:
            for _ in range(60):
                gx, gy = grad(x, y)
                hxx, hxy, hyy = hess(x, y)
                det = hxx * hyy - hxy * hxy
                if det == 0:
                    break
                x, y = x - (hyy * gx - hxy * gy) / det, y - (hxx * gy - hxy * gx) / det
                if not (lo - 1 <= x <= hi + 1 and lo - 1 <= y <= hi + 1):
                    break
            hxx, hxy, hyy = hess(x, y)
            inside = lo <= x <= hi and lo <= y <= hi
            critical = max(map(abs, grad(x, y))) < mp.mpf(10) ** -40 * max(map(abs, c.values()))
            if inside and critical and hxx > 0 and hxx * hyy - hxy * hxy > 0:
                cands.append((x, y))
        return min((ev(x, y), x, y) for x, y in cands)


def test_an_edge_optimum_is_the_exact_vertex_of_its_edge():
    """bernstein_like on a 4 x 5 net: the membrane optimum lies on the edge λ_u = -1; its
    λ_v is the vertex of the edge's quadratic (exact, from the definitions), and no point of
    the box has a lower energy (the independent minimum above)."""
    net = [[(i, j, (i * j) % 3) for j in range(5)] for i in range(4)]
    r = lb.optimal_parameters(net, energy="membrane", family="bernstein_like")
    poly = _energy_poly("bernstein_like", net, "membrane")
    assert r["lam_u"] == -1 and r["where"] == "edge"
    edge = [sum((poly[a, b] * F(-1) ** a for a in range(3)), F(0)) for b in range(3)]
    assert r["lam_v"] == -edge[1] / (2 * edge[2])  # exactly the vertex
    assert (
        r["energy"]
        == _e(poly, F(-1), r["lam_v"])
        == lb.surface_energy(lb.BernsteinLikeSurface(net, r["lam_u"], r["lam_v"]), "membrane")
    )
    best, x, y = _reference_minimum(poly, -1, 1)
    assert abs(float(x) + 1) < 1e-12 and abs(float(y) - r["lam_v_float"]) < 1e-12
    assert float(r["energy"]) == pytest.approx(float(best), rel=1e-14)


def test_an_interior_optimum_solves_the_gradient_equations():
    """same_degree, thin plate, on a 4 x 5 net of points in d = 4: an interior minimum whose
    parameters are algebraic (exact: an integer polynomial with an isolating interval); the
    floats are the independent minimiser's to 1e-12, and each polynomial vanishes there."""
    r = lb.optimal_parameters(_NET_45, "thin_plate", family="same_degree")
    poly = _energy_poly("same_degree", _NET_45, "thin_plate")
    best, x, y = _reference_minimum(poly, -2, 1)
    assert r["where"] == "interior"
    assert abs(r["lam_u_float"] - float(x)) < 1e-12 and abs(r["lam_v_float"] - float(y)) < 1e-12
    for key, value in (("lam_u", x), ("lam_v", y)):
        root = r[key]
        if isinstance(root, F):
            assert abs(float(root) - float(value)) < 1e-15
            continue
        assert root.lo <= float(value) <= root.hi
        with mp.workdps(50):
            p = sum(mp.mpf(c) * value**k for k, c in enumerate(root.coefficients))
            scale = sum(abs(mp.mpf(c)) * abs(value) ** k for k, c in enumerate(root.coefficients))
            assert abs(p) < mp.mpf(10) ** -35 * scale  # a root, to the reference's digits


def test_a_batch_of_float_nets_is_the_independent_minimum():
    """Eight float nets at once (numpy and, when installed, numba): every (λ_u, λ_v) is the
    independent global minimiser of the exact energy of that float net to 1e-10 (the
    certificate promises 1e-12 for the energy's float coefficients)."""
    nets = np.random.default_rng(31).normal(size=(8, 4, 4, 3))
    r = lb.optimal_parameters(nets, "thin_plate", "bernstein_like")
    assert r["lam_u"].shape == (8,)
    for k in range(8):
        # exactly the float net times 2^k (integers: faster Fractions; the same minimiser)
        shift = max(F(float(x)).denominator for x in nets[k].ravel())
        net = [[tuple(int(F(float(x)) * shift) for x in p) for p in row] for row in nets[k]]
        best, x, y = _reference_minimum(_energy_poly("bernstein_like", net, "thin_plate"), -1, 1)
        assert abs(r["lam_u"][k] - float(x)) < 1e-10, k
        assert abs(r["lam_v"][k] - float(y)) < 1e-10, k


def test_a_batch_with_a_bezier_direction_has_no_nan():
    """Bézier across same_degree, a batch: λ_u is None as for one net (before: an array of
    NaN), and each λ_v is the vertex of the exact energy's quadratic in λ_v, clipped to
    [-2, 1] (from the definitions)."""
    nets = np.random.default_rng(7).normal(size=(3, 5, 4, 2))
    r = lb.optimal_parameters(nets, "membrane", ("bezier", "same_degree"))
    assert r["lam_u"] is None and r["lam_u_float"] is None
    assert r["free_u"].all()
    fams = ("bezier", "same_degree")
    for k in range(3):
        net = [[tuple(F(float(x)) for x in p) for p in row] for row in nets[k]]
        e = [_exact_energy(fams, (None, F(y)), net, "membrane") for y in (-1, 0, 1)]
        a, b = (e[2] + e[0]) / 2 - e[1], (e[2] - e[0]) / 2  # E(y) = a y² + b y + e[1]
        vertex = min(max(-b / (2 * a), F(-2)), F(1))
        assert abs(r["lam_v"][k] - float(vertex)) < 1e-12


# ------------------------------------------------------------------------------ plots
@pytest.mark.parametrize(
    ("kwargs", "error", "match"),
    [
        ({"ax": "mean"}, TypeError, "ax must be a matplotlib 3D Axes"),  # before: AttributeError
        ({"samples": 10**6}, ValueError, "samples must be from 2 to"),  # before: MemoryError
        ({"net": "no"}, ValueError, "net must be True or False"),  # before: drew the net
        ({"cmap": "nope"}, ValueError, "cmap 'nope' is not a matplotlib colour map"),
        ({"cmap": 3}, TypeError, "cmap must be a colour map or its name"),
    ],
)
def test_plot_surface_bad_input_names_the_argument(kwargs, error, match):
    pytest.importorskip("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    from lambda_bezier.surface_plot import plot_surface

    surf = lb.SameDegreeSurface([[(i, j, (i * j) % 3) for j in range(4)] for i in range(4)], 0, 0)
    with pytest.raises(error, match=match):
        plot_surface(surf, **kwargs)


# ---------------------------------------------------------------- energy matrices as data
@pytest.mark.parametrize(
    ("degrees", "family", "energy"),
    [
        ((3, 4), "same_degree", "thin_plate"),  # emitted by derive (degrees 1 to 4)
        ((5, 3), "bernstein_like", "membrane"),  # built at run time (Kronecker products)
        ((4, 3), ("same_degree", "bernstein_like"), "thin_plate"),  # a mixed pair
    ],
)
def test_energy_matrices_in_paper_form_are_the_energy(degrees, family, energy):
    """The paper-style terms (coefficient of λ_u^a λ_v^b: scale s and an upper-triangular
    integer matrix U with vec(P)ᵀ Q vec(P) = s Σ_{r<=c} U_rc P_r·P_c, the net read row by
    row) give, at rational (λ_u, λ_v), exactly the energy integrated from the definitions."""
    mats = lb.surface_energy_matrices(degrees, energy, family=family)
    fams = (family, family) if isinstance(family, str) else family
    m, n = degrees
    rng = np.random.default_rng(sum(degrees))
    net = [
        [tuple(int(x) for x in rng.integers(-5, 6, size=2)) for _ in range(n + 1)]
        for _ in range(m + 1)
    ]
    flat = [p for row in net for p in row]
    for lam_u, lam_v in ((F(1, 2), F(-1, 3)), (F(-1), F(1, 7))):
        total = F(0)
        for (a, b), (scale, upper) in mats.terms.items():
            assert all(isinstance(x, int) for row in upper for x in row)
            assert all(upper[r][c] == 0 for r in range(len(upper)) for c in range(r))
            quad = sum(
                upper[r][c] * sum(x * y for x, y in zip(flat[r], flat[c], strict=True))
                for r in range(len(flat))
                for c in range(r, len(flat))
            )
            total += F(scale) * quad * lam_u**a * lam_v**b
        assert total == _exact_energy(fams, (lam_u, lam_v), net, energy)


def test_an_own_family_optimum_by_its_parameter_name():
    """nouri_saeidian (parameter sigma in [0, 1]), one net and a batch: the optimum is the
    independent minimiser of the energy integrated from its definition, and is read as
    r["sigma_u"] too (as its surfaces' keywords and repr name it; before: KeyError)."""
    from lambda_bezier import examples

    ns = lb.load_family(examples.path("nouri_saeidian.toml"))
    net = [[(i, j, (i * j) % 3) for j in range(5)] for i in range(4)]
    surf = ns.surface(net, sigma_u=F(1, 2), sigma_v=F(1, 3))
    assert repr(surf).startswith("Surface(nouri_saeidian, degrees=(3, 4)")
    assert "sigma_u=1/2, sigma_v=1/3" in repr(surf)
    assert lb.surface_energy(surf, "membrane") == _exact_energy(
        ("nouri_saeidian",) * 2, (F(1, 2), F(1, 3)), net, "membrane"
    )
    r = lb.optimal_parameters(net, "membrane", family=ns)
    best, x, y = _reference_minimum(_energy_poly("nouri_saeidian", net, "membrane"), 0, 1)
    assert abs(r["sigma_u_float"] - float(x)) < 1e-12 and abs(r["sigma_v_float"] - float(y)) < 1e-12
    assert r["sigma_u"] is r["lam_u"] and r["sigma_v"] is r["lam_v"]
    assert "sigma_u" not in list(r) and "lam_u" in list(r)
    batch = lb.optimal_parameters(np.array([net, net], dtype=float), "membrane", family=ns)
    np.testing.assert_allclose(batch["sigma_u"], [float(x)] * 2, atol=1e-12)
    with pytest.raises(KeyError):
        r["mu_u"]


@pytest.mark.parametrize(
    ("text", "match"),
    [
        ('{"lambda_bezier": 1, "kind": "curve", "family": [1]}', r"curve.family must be one of"),
        (
            '{"lambda_bezier": 1, "kind": "composite", "segments": [{"family": {"a": 1}}]}',
            r"segments\[0\].family must be one of",
        ),
    ],
)
def test_a_curve_document_with_a_family_not_a_name(text, match):
    """Before: TypeError "unhashable type: 'list'" from deep in the loader."""
    from lambda_bezier.export import from_json

    with pytest.raises(ValueError, match=match):
        from_json(text)


def test_curve_writers_and_reader_point_surfaces_to_their_own():
    """export.to_json / to_step of a surface, and export.from_json of a surface document:
    before, a TypeError saying only "expected a curve" and, reading, "unhashable type:
    'list'"; now each names lambda_bezier.surface_export."""
    from lambda_bezier import export
    from lambda_bezier.surface_export import surface_from_json, surface_to_json

    surf = lb.SameDegreeSurface([[(i, j, i * j) for j in range(4)] for i in range(4)], 0, 0)
    with pytest.raises(TypeError, match="surface is written by lambda_bezier.surface_export"):
        export.to_json(surf)
    text = surface_to_json(surf)
    with pytest.raises(ValueError, match="read it with lambda_bezier.surface_export"):
        export.from_json(text)
    assert surface_from_json(text).control_net() == surf.control_net()
