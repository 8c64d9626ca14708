"""join_surface on all four sides of a patch (surface_sides), for built-in, data-defined,
several-parameter, indexed, trigonometric, hyperbolic and mixed families, and CompositeSurface
grids joined on every side, against finite differences of `evaluate` (the patches' own
parameters): the cross derivatives across each boundary, and the continuity the report
names, read off the differences independently of the report's exact Bézier-form test."""

from __future__ import annotations

from fractions import Fraction as F

import numpy as np
import pytest
from conftest import surface_families
from hypothesis import given, settings
from hypothesis import strategies as st

import lambda_bezier as lb
from lambda_bezier.atom_surfaces import AtomSurface

TRIG, TWO, QB, HYP, MIXED = surface_families()
NET = [[(i, j, F((i * j) % 3, 2) - F(i, 4)) for j in range(4)] for i in range(4)]
ORDER = {"C1": 1, "G1": 1, "C2": 2}


def domain(s: lb.Surface, axis: int) -> tuple[float, float]:
    if isinstance(s, AtomSurface):
        lo, hi = s.domain_u if axis == 0 else s.domain_v
        return float(lo), float(hi)
    return 0.0, 1.0


def fd_cross(s: lb.Surface, axis: int, at_end: bool, along: np.ndarray, r: int) -> np.ndarray:
    """∂^r S/∂(across)^r on the boundary, one-sided finite differences of `evaluate` inside
    the patch (second-order stencils; the step scaled to the domain)."""
    lo, hi = domain(s, axis)
    h = (hi - lo) * (1e-4 if r == 1 else 2e-3)
    x0, sign = (hi, -1.0) if at_end else (lo, 1.0)

    def at(k: int) -> np.ndarray:
        x = np.full_like(along, x0 + sign * k * h)
        return np.asarray(s.evaluate(x, along) if axis == 0 else s.evaluate(along, x))

    if r == 0:
        return at(0)
    if r == 1:  # (-3 f0 + 4 f1 - f2) / 2h, with the direction of the step
        return sign * (-3 * at(0) + 4 * at(1) - at(2)) / (2 * h)
    return (2 * at(0) - 5 * at(1) + 4 * at(2) - at(3)) / h**2


def along_points(s: lb.Surface, axis: int) -> np.ndarray:
    lo, hi = domain(s, 1 - axis)
    return np.linspace(lo, hi, 5)


def fd_continuity(a: lb.Surface, b: lb.Surface, axis: int) -> str:
    """The continuity across a's end / b's start in direction `axis`, from differences."""
    va, vb = along_points(a, axis), along_points(b, axis)
    size = max(1.0, float(np.abs(a.net).max()), float(np.abs(b.net).max()))
    if not np.allclose(fd_cross(a, axis, True, va, 0), fd_cross(b, axis, False, vb, 0), atol=1e-9):
        return "none"
    da, db = fd_cross(a, axis, True, va, 1), fd_cross(b, axis, False, vb, 1)
    if not np.allclose(da, db, atol=1e-5 * size):
        ratio = np.sum(da * db) / np.sum(db * db)  # one α with da = α db
        if ratio > 0 and np.allclose(da, ratio * db, atol=1e-5 * size):
            return "G1"
        return "C0"
    dda, ddb = fd_cross(a, axis, True, va, 2), fd_cross(b, axis, False, vb, 2)
    return "C2" if np.allclose(dda, ddb, atol=2e-3 * size) else "C1"


def assert_second_jumps(a: lb.Surface, b: lb.Surface, axis: int) -> None:
    """A C1 (not C2) boundary: the second cross derivatives differ well beyond the
    differences' error, so fd_continuity's C1/C2 decision is not a matter of tolerance."""
    va, vb = along_points(a, axis), along_points(b, axis)
    jump = np.abs(fd_cross(a, axis, True, va, 2) - fd_cross(b, axis, False, vb, 2)).max()
    assert jump > 0.05


# the patch to join onto, and the new patch's parameters (join_surface's keywords)
def patch_cases():
    yield "same_degree", lb.SameDegreeSurface(NET, F(1, 2), -1), {"lam": F(1, 3)}
    yield "bernstein_like", lb.BernsteinLikeSurface(NET, 1, F(1, 2)), {}
    yield "bezier", lb.BezierSurface(NET), {}
    yield "sd>bl", lb.SameDegreeSurface(NET, 1, 0), {"family": "bernstein_like", "lam": F(-1, 2)}
    pu = {"lam": F(1, 2), "mu": -1}
    yield "trig", TRIG.surface(NET, params_u=pu, params_v={"lam": 0, "mu": F(1, 3)}), {}
    two_u, two_v = {"lam": F(1, 4), "mu": F(1, 2)}, {"lam": 0, "mu": -F(1, 3)}
    yield "two", TWO.surface(NET, params_u=two_u, params_v=two_v), {}
    yield "hyp", HYP.surface(NET, params_u=two_u, params_v=two_v), {}
    one = {k: F(1, 2) for k in MIXED.parameters}
    yield "mixed", MIXED.surface(NET, params_u=one, params_v=one), {}
    qb = {"lam": [1, F(1, 2), -1]}
    yield "indexed", QB.surface(NET, params_u=qb, params_v={"lam": [0, F(1, 3), 0]}), {}
    yield "trig x sd", TRIG.surface(NET, params_u=pu, lam_v=F(1, 3), family_v="same_degree"), {}
    # into another family across the boundary, parameters by name where it takes them
    sd = lb.SameDegreeSurface(NET, F(1, 2), 0)
    yield "sd>trig", sd, {"family": TRIG, "params": {"lam": 0, "mu": 0}}
    yield "sd>indexed", sd, {"family": QB, "params": {"lam": [0, F(1, 2), 0]}}
    trig = TRIG.surface(NET, params_u=pu, params_v={"lam": 0, "mu": F(1, 3)})
    yield "trig>sd", trig, {"family": "same_degree", "params": {"lam": F(1, 3)}}
    yield "trig>two", trig, {"family": TWO, "params": {"lam": 0, "mu": F(1, 2)}}


CASES = list(patch_cases())


def rest_for(a: lb.Surface, side: str, rows: int) -> list:
    """`rows` rows of the new patch beyond the solved ones, in its own increasing parameter
    (the far row first on the sides u0 and v0)."""
    count = a.net.shape[1 if side[0] == "u" else 0]
    far = [6 + k for k in range(rows)]
    if side.endswith("0"):
        far = [-x for x in reversed(far)]
    if side[0] == "u":
        return [[(x, j, F(j * x, 7)) for j in range(count)] for x in far]
    return [[(i, x, F(i * x, 7)) for x in far] for i in range(count)]


def grid(a: lb.Surface, b: lb.Surface, side: str) -> list[list[lb.Surface]]:
    return {"u0": [[b], [a]], "u1": [[a], [b]], "v0": [[b, a]], "v1": [[a, b]]}[side]


@pytest.mark.parametrize("side", ["u0", "v0", "u1", "v1"])
@pytest.mark.parametrize("continuity", ["C1", "G1", "C2"])
@pytest.mark.parametrize(("name", "patch", "new"), CASES, ids=[c[0] for c in CASES])
def test_join_on_every_side_against_finite_differences(side, continuity, name, patch, new):
    alpha = F(3, 2) if continuity == "G1" else 1
    rows = 3 - ORDER[continuity]
    b = lb.join_surface(
        patch, side, continuity, rest=rest_for(patch, side, rows), alpha=alpha, **new
    )
    (first, second), axis = ([b, patch] if side.endswith("0") else [patch, b]), int(side[0] == "v")
    # the cross derivatives by differences: given = α^r · new on every side
    va, vb = along_points(first, axis), along_points(second, axis)
    for r in range(ORDER[continuity] + 1):
        da, db = fd_cross(first, axis, True, va, r), fd_cross(second, axis, False, vb, r)
        given, made = (db, da) if side.endswith("0") else (da, db)
        tol = (1e-9, 1e-5, 2e-3)[r] * max(1.0, float(np.abs(given).max()))
        assert np.allclose(given, float(alpha) ** r * made, atol=tol), (r, given, made)
    # and the report names what the differences show
    report = lb.CompositeSurface(grid(patch, b, side)).report()
    assert [x.continuity for x in report] == [continuity]
    assert fd_continuity(first, second, axis) == continuity
    if continuity == "C1":
        assert_second_jumps(first, second, axis)
    exact = name in ("same_degree", "bernstein_like", "bezier", "sd>bl", "two", "indexed")
    exact = exact or name == "sd>indexed"
    if exact and side.endswith("0"):  # exact in, exact out
        assert all(isinstance(c, F) for row in b.control_net() for p in row for c in p)


def test_the_new_patch_keeps_the_family_along_the_boundary_and_its_degree_from_rest():
    a = lb.SameDegreeSurface(NET, F(1, 2), -1)
    b = lb.join_surface(a, "v0", "C1", rest=rest_for(a, "v0", 3))
    assert b.net.shape == (4, 5, 3)  # degree 1 + 3 rows across v, A's 4 points along it
    assert (b.lam_u, b.lam_v) == (F(1, 2), -1)  # λ along it A's, across it A's by default
    c = lb.join_surface(a, "u=0", "C2", 4, F(1, 3), rest=rest_for(a, "u0", 2))
    assert c.net.shape == (5, 4, 3) and c.lam_u == F(1, 3)


def test_grids_joined_on_every_side_report_what_differences_show():
    """A 3x3 grid grown from its middle patch on all four sides, then its corners joined
    onto the edge patches: the report of every interior boundary equals the continuity read
    off finite differences (corner patches meet their second neighbour with no continuity
    asked for, so the grid holds several verdicts)."""
    mid = lb.SameDegreeSurface(NET, F(1, 2), F(1, 4))
    up = lb.join_surface(mid, "u1", "C2", rest=rest_for(mid, "u1", 1))
    down = lb.join_surface(mid, "u0", "G1", alpha=2, rest=rest_for(mid, "u0", 2))
    left = lb.join_surface(mid, "v0", "C1", rest=rest_for(mid, "v0", 2))
    right = lb.join_surface(mid, "v1", "C2", rest=rest_for(mid, "v1", 1))
    corners = {
        (0, 0): lb.join_surface(down, "v0", "C1", rest=rest_for(down, "v0", 2)),
        (0, 2): lb.join_surface(down, "v1", "G1", alpha=F(1, 2), rest=rest_for(down, "v1", 2)),
        (2, 0): lb.join_surface(up, "v0", "C2", rest=rest_for(up, "v0", 1)),
        (2, 2): lb.join_surface(right, "u1", "C1", rest=rest_for(right, "u1", 2)),
    }
    patches = [
        [corners[0, 0], down, corners[0, 2]],
        [left, mid, right],
        [corners[2, 0], up, corners[2, 2]],
    ]
    comp = lb.CompositeSurface(patches, tol=1e-9)
    got = {(r.first, r.side): r.continuity for r in comp.report()}
    assert len(got) == 12
    for (r, c), side in got:
        a = patches[r][c]
        b = patches[r + 1][c] if side == "u" else patches[r][c + 1]
        assert got[(r, c), side] == fd_continuity(a, b, 0 if side == "u" else 1), (r, c, side)
    # the boundaries joined on purpose
    assert got[(0, 1), "u"] == "G1" and got[(1, 1), "u"] == "C2"
    assert got[(1, 0), "v"] == "C1" and got[(1, 1), "v"] == "C2"
    assert got[(0, 0), "v"] == "C1" and got[(0, 1), "v"] == "G1"
    assert got[(2, 0), "v"] == "C2" and got[(1, 2), "u"] == "C1"
    # global evaluation lands on the right patch
    assert np.allclose(comp.evaluate(0.5, 2.5), corners[0, 2].evaluate(0.5, 0.5))


def test_a_split_grid_is_c2_where_the_pieces_have_equal_widths():
    """Split at u = 1/2 and v = 1/3: across u the pieces are C2; across v the first piece
    spans 1/3 and the second 2/3 of v, so each piece's own v runs at a different speed and
    the boundary is G1 (α = 1/2), as the differences show too."""
    s = lb.SameDegreeSurface(NET, F(1, 2), 1)
    low, high = s.split_u(F(1, 2))
    quads = [list(low.split_v(F(1, 3))), list(high.split_v(F(1, 3)))]
    report = lb.CompositeSurface(quads).report()
    assert [r.continuity for r in report] == ["C2", "G1", "C2", "G1"]
    for r in report:
        (i, j), axis = r.first, 0 if r.side == "u" else 1
        b = quads[i + 1][j] if axis == 0 else quads[i][j + 1]
        assert fd_continuity(quads[i][j], b, axis) == r.continuity


@pytest.mark.parametrize(
    ("call", "match"),
    [
        (lambda a: lb.join_surface(a, "w", "C1", 3), "side must name one of .*'u0'.*'v=0'"),
        (lambda a: lb.join_surface(a, 0, "C1", 3), "side must name"),
        (
            lambda a: lb.join_surface(a, "u0", "C1", 3, rest=[[(0, 0, 0)] * 3] * 2),
            "rest must have 4",
        ),
        (lambda a: lb.join_surface(a, "u0", "C1", 3, rest=[[(0, 0, 0)] * 4]), "rest must hold 2"),
        (lambda a: lb.join_surface(a, "v0", "G1", alpha=0), "alpha must be > 0"),
        (lambda a: lb.join_surface(a, "v0", "G1", alpha="x"), "alpha"),
        (lambda a: lb.join_surface(a, "u0", "C1", mu=(1, 1)), "mu .* needs continuity G1"),
        (lambda a: lb.join_surface(a, "v0", "G1", mu=(1, -2)), "mu.* must be positive"),
        (lambda a: lb.join_surface(a, "u0", "C1", conditions="derived"), "derived document"),
        (lambda a: lb.join_surface(a, "u0", "C1", conditions="guess"), "conditions"),
        (lambda a: lb.join_surface(a, "u0", "C1", 3, float("nan")), "lam"),
        (lambda a: lb.join_surface(a, "u0", "C1", "3"), "degree"),
        (lambda a: lb.join_surface(a, "u0", "C1", 30), "degree 30"),
        (lambda a: lb.join_surface(a, "u0", "C3"), "continuity"),
        (lambda a: lb.join_surface(a, "u0", "C1", family=42, lam=0), "family must be"),
        (lambda a: lb.join_surface(a, "u0", "C1", family="nope", lam=0), "unknown family 'nope'"),
        (lambda a: lb.join_surface(a, "v1", "C1", family=TRIG, lam=0), "lam: .* params="),
        (
            lambda a: lb.join_surface(a, "u0", "C1", family=TRIG, params=[0]),
            "params must be a dict",
        ),
        (
            lambda a: lb.join_surface(a, "u0", "C1", rest=[[(0, 0, float("inf"))] * 4] * 2),
            "rest",
        ),
    ],
)
def test_bad_input_is_named(call, match):
    a = lb.SameDegreeSurface(NET, 1, 0)
    with pytest.raises((ValueError, TypeError), match=match):
        call(a)


# ---------------------------------------------------------------------- exact, drawn nets
FAMILIES = {
    "same_degree": (lb.SameDegreeSurface, [F(-3, 2), F(0), F(1, 2), F(1)]),
    "bernstein_like": (lb.BernsteinLikeSurface, [F(-1), F(-1, 3), F(0), F(1)]),
}
coordinate = st.fractions(min_value=-4, max_value=4, max_denominator=6)


@st.composite
def exact_cases(draw):
    name = draw(st.sampled_from(sorted(FAMILIES)))
    cls, lams = FAMILIES[name]
    low = 3 if name == "same_degree" else 2  # the families' lowest degrees
    m, n = draw(st.integers(low, 4)), draw(st.integers(low, 4))
    net = [[(F(i), F(j), draw(coordinate)) for j in range(n + 1)] for i in range(m + 1)]
    side = draw(st.sampled_from(["u0", "v0"]))
    continuity = draw(st.sampled_from(["C1", "G1", "C2"]))
    order = ORDER[continuity]
    rows = draw(st.integers(max(1, low - order), 2))
    if side == "u0":  # rows of n + 1 points, the far one first
        rest = [
            [(F(-4 - rows + k), F(j), draw(coordinate)) for j in range(n + 1)] for k in range(rows)
        ]
    else:  # m + 1 lines of `rows` points across v
        rest = [
            [(F(i), F(-4 - rows + k), draw(coordinate)) for k in range(rows)] for i in range(m + 1)
        ]
    alpha = draw(st.sampled_from([F(1, 3), F(2), F(5, 4)])) if continuity == "G1" else 1
    lam = draw(st.sampled_from(lams))
    return (
        cls(net, draw(st.sampled_from(lams)), draw(st.sampled_from(lams))),
        side,
        continuity,
        order,
        rest,
        alpha,
        lam,
    )


@settings(max_examples=40, deadline=None)
@given(exact_cases())
def test_exact_joins_before_meet_their_conditions_exactly(case):
    """Exact patches, drawn: across u = 0 or v = 0 the new patch's Bézier form meets the
    given one's to the order asked, exactly (the report compares Fractions), and the
    cross derivatives of the two Bézier forms there are α^r apart, in Fractions."""
    a, side, continuity, order, rest, alpha, lam = case
    try:
        b = lb.join_surface(a, side, continuity, None, lam, rest=rest, alpha=alpha)
    except ValueError as exc:  # only where B's end or A's start has no tangent
        assert "cannot meet the conditions" in str(exc)
        degree = order + (len(rest) if side == "u0" else len(rest[0]))
        cls = lb.curves.family_class(a.family[0] if isinstance(a.family, tuple) else a.family)
        polygon = [(0, 0), (1, 2), (3, 1), (4, 5), (2, 2), (7, 1)]
        own = a.lam_u if side == "u0" else a.lam_v
        given = a.degrees[0 if side == "u0" else 1]
        ends = [
            cls(polygon[: degree + 1], lam).derivative(1.0, 1),
            cls(polygon[: given + 1], own).derivative(0.0, 1),
        ]
        assert any(np.allclose(e, 0) for e in ends), ends
        return
    assert b.is_exact
    grid = [[b], [a]] if side == "u0" else [[b, a]]
    assert [r.continuity for r in lb.CompositeSurface(grid).report()] == [continuity]
    axis = 0 if side == "u0" else 1
    from lambda_bezier.surface_joins import _boundary_derivatives, _elevate_to

    da = _boundary_derivatives(a, axis, False, order)
    db = _boundary_derivatives(b, axis, True, order)
    for r in range(order + 1):
        size = max(len(da[r]), len(db[r])) - 1
        x, y = _elevate_to(da[r], size), _elevate_to(db[r], size)
        assert all(isinstance(c, F) for p in x for c in p)
        assert [tuple(c for c in p) for p in x] == [tuple(alpha**r * c for c in p) for p in y]
