"""Joining surface patches along a common boundary, and grids of patches.

When the next patch B continues A across A's boundary u = 1 and has A's family, degree and λ
in v, both sides of every condition are combinations of the same v-basis functions, so the
conditions hold for every v exactly when they hold for the coefficient of each basis
function: column j of B's net (the u-curve through B's points P_{·,j}) must join column j of
A's net as a curve does. `join_surface` therefore solves the rows of B next to the boundary
column by column with the curves' `join` (its generated vertex formulas, any ordered pair of
families); G1 there has one constant α along the boundary (A_u(1, v) = α B_u(0, v)).

G1 with a factor varying along the boundary, B_u(0, v) = μ(v) A_u(1, v) with a linear
μ(v) = μ0 + μ1 v > 0 (``mu=(μ0, μ1)``), needs one degree more along the boundary: μ(v) A_u(1, v)
has degree N + 1 where A's Bézier form has degree N in v. The new patch is therefore classical
Bézier of degree N + 1 along the boundary (A's boundary degree-elevated), and its rows next to
the boundary are solved column by column from the target value and cross derivative at each
of its N + 2 Bernstein coefficients (the product μ·A_u in Bernstein form). A linear α(v) in
A_u(1, v) = α(v) B_u(0, v) is not offered: B_u = A_u / α(v) is not a polynomial.

A family defined by data carries the same conditions in its derived document
(``surface_joins``: the column-wise weights in closed form, proved by derive on the family's
own basis); ``join_surface(..., conditions="derived")`` applies those instead of solving, and
the tests check that the two agree.

`CompositeSurface` holds a grid of patches and reports, for every interior boundary, the
continuity achieved, found exactly on the Bézier forms (Fractions for exact patches); its G1
is the general one, tangent planes that agree along the boundary (B_u = μ A_u + ν A_v with
μ > 0, _tangent_planes), of which join_surface's constant and linear factors are cases; where a
patch of trigonometric, hyperbolic or mixed families takes part, in the families' own
parameters (param_surface_report). Each patch lives on its own domain (the unit square, or
its families' domains), and `evaluate` maps the global parameters onto it.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace
from fractions import Fraction
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from . import _validate as val
from ._lazy import deferred
from .builtin_surfaces import most_specific
from .curves import BezierCurve, family_class
from .hazmat.forms import elevation_matrix, hodograph_matrix
from .joins import join
from .surfaces import BezierSurface, Surface, _exact_net

if TYPE_CHECKING:
    from types import ModuleType

    from . import param_surface_joins, param_surface_report, surface_sides
    from ._join_options import JoinOptions
    from ._surface_results import BoundaryReport
else:

    def _load_sides() -> ModuleType:
        from . import surface_sides

        return surface_sides

    def _load_report() -> ModuleType:
        from . import param_surface_report

        return param_surface_report

    def _load_param_joins() -> ModuleType:
        from . import param_surface_joins

        return param_surface_joins

    # imported on a join's first use, then bound: they bring the atom surfaces' engine
    # (atom_surfaces, hazmat.atom_surface_bounds), which naming CompositeSurface or
    # join_surface does not need (`import lambda_bezier`'s time, issue #29)
    surface_sides = deferred(_load_sides)
    param_surface_report = deferred(_load_report)
    param_surface_joins = deferred(_load_param_joins)

SURFACE_CONTINUITIES = ("C1", "G1", "C2")
CONDITIONS = ("solve", "derived")
ORDER = {"C1": 1, "G1": 1, "C2": 2}


def _transpose(rows: Any) -> Any:
    return [[rows[i][j] for i in range(len(rows))] for j in range(len(rows[0]))]


def _columns(surf: Surface, axis: int) -> list[Any]:
    """The u-curves' control points (axis 0) or v-curves' (axis 1), exact when possible."""
    rows: Any = surf.control_net()
    return _transpose(rows) if axis == 0 else [list(r) for r in rows]


def join_surface(
    patch: Surface,
    side: str,
    continuity: str,
    degree: int | None = None,
    lam: Fraction | float | None = None,
    rest: npt.ArrayLike | Sequence[Any] = (),
    *,
    alpha: Fraction | float = 1,
    mu: tuple[Fraction | float, Fraction | float] | None = None,
    family: object = None,
    check_range: bool = True,
    conditions: str = "solve",
    params: dict[str, Any] | None = None,
) -> Surface:
    """The next patch across one of `patch`'s four boundaries.

    `side` is "u1" (also "u", "u=1"): across u = 1, the new patch B starting there
    (B(0, v) = A(1, v)); "u0" ("u=0"): across u = 0, B ending there (B(1, v) = A(0, v), B
    before A in u); "v1" ("v", "v=1") and "v0" ("v=0") the same in v (surface_sides).
    The new patch has `degree` and `lam` (and `family`, default the patch's) across the
    boundary, and the patch's family, degree and λ along it. Its rows of control points next to
    the boundary are solved for `continuity` ("C1", "G1" with a constant `alpha` > 0, "C2");
    `rest` gives its other rows, in its own order (after the solved ones across u = 1, before
    them across u = 0): an array (k, n+1, d) for a side in u ((m+1, k, d) in v). G1 means
    that the given patch's cross derivative is `alpha` times the new patch's, on every side.
    `degree` defaults to the solved rows plus the rows of `rest` (without `rest`, the patch's
    own degree across the boundary) and `lam` to the patch's own λ across it. Exact input
    gives an exact patch.

    ``mu=(μ0, μ1)`` (G1 only, instead of `alpha`) asks for B_u(0, v) = (μ0 + μ1 v) A_u(1, v),
    a factor varying along the boundary (positive on [0, 1]); on u0, B_u(1, v) = μ(v) A_u(0, v)
    (v0 likewise). The new patch is then classical
    Bézier along the boundary, of one degree more than `patch`'s Bézier form there (N + 1),
    and `rest` has N + 2 points along the boundary.

    A patch of several-parameter, indexed or atom families (param_surfaces) takes the new
    patch's parameters by name, ``params={...}`` (default: the patch's own), and its
    boundary is the end of its domain (param_surface_joins); with ``conditions="derived"``
    the join weights come from those families' derived documents (their ``joins`` table).

    ``conditions="derived"`` takes the conditions from the derived document of a family
    defined by data (one of the two across the boundary; its ``surface_joins``) instead of
    solving the curve joins per column; the result is the same.

    >>> from lambda_bezier import SameDegreeSurface
    >>> from lambda_bezier.surface_joins import join_surface
    >>> a = SameDegreeSurface([[(i, j, i * j) for j in range(4)] for i in range(4)], 1, 0)
    >>> b = join_surface(a, "u", "C1", 3, 1, rest=[[(5, j, 0) for j in range(4)]] * 2)
    >>> b.control_net()[1][2]
    (Fraction(4, 1), Fraction(2, 1), Fraction(8, 1))
    >>> c = join_surface(a, "u0", "C1", rest=[[(-5, j, 0) for j in range(4)]] * 2)
    >>> c.control_net()[2][2], c.degrees
    ((Fraction(-1, 1), Fraction(2, 1), Fraction(-2, 1)), (3, 3))
    """
    axis, at_end = surface_sides.parse_side(side)
    continuity = val.choice(
        continuity.upper() if isinstance(continuity, str) else continuity,
        "continuity",
        SURFACE_CONTINUITIES,
    )
    if not isinstance(patch, Surface):
        raise TypeError(f"patch must be a lambda_bezier surface, got {type(patch).__name__}")
    degree = _default_degree(patch, axis, continuity, degree, rest)
    if not hasattr(patch, "family_u") and surface_sides.takes_names(family):
        if lam is not None or mu is not None:
            raise ValueError(
                "lam: the new patch's family takes its parameters by name: give params={...}"
            )
        patch = surface_sides.ByName(patch)  # type: ignore[assignment]
    if lam is None and family is None and not hasattr(patch, "family_u"):
        lam = patch.lam_u if axis == 0 else patch.lam_v  # the patch's own, as its family

    def options() -> JoinOptions:  # the choices as they stand once checked, for every side
        from ._join_options import JoinOptions  # on call: a frozen dataclass costs import time

        assert degree is not None  # _default_degree's
        return JoinOptions(degree, lam, rest, alpha, mu, family, params, check_range, conditions)

    if not at_end:
        conditions = val.choice(conditions, "conditions", CONDITIONS)
        if mu is not None:
            if hasattr(patch, "family_u"):
                raise ValueError(
                    "patch: a surface of several-parameter, indexed or atom families is joined "
                    "with a constant alpha; give the new parameters as params={...} (not mu)"
                )
            _check_varying(continuity, conditions, alpha)
            return _join_varying_before(patch, axis, options())
        if params is not None and not hasattr(patch, "family_u"):
            raise ValueError("params is for patches of several-parameter or atom families")
        if hasattr(patch, "family_u") and lam is not None:
            raise ValueError(
                "lam: a surface of several-parameter, indexed or atom families takes the new "
                "patch's parameters as params={...}"
            )
        return surface_sides.join_before(patch, axis, continuity, options())
    if hasattr(patch, "family_u"):  # ParamSurface, AtomSurface: parameters by name
        if mu is not None or lam is not None:
            raise ValueError(
                "patch: a surface of several-parameter, indexed or atom families is joined "
                "with a constant alpha; give the new parameters as params={...} (not lam or mu)"
            )
        conditions = val.choice(conditions, "conditions", CONDITIONS)
        degree = val.integer(degree, "degree")
        return param_surface_joins._join_param_surface(  # type: ignore[no-any-return]
            patch, axis, continuity, options()
        )
    if params is not None:
        raise ValueError("params is for patches of several-parameter or atom families")
    if isinstance(alpha, tuple | list):
        raise ValueError(
            "alpha is one constant (A_u(1, v) = alpha B_u(0, v)); a factor varying along the "
            "boundary is mu=(mu0, mu1): B_u(0, v) = (mu0 + mu1 v) A_u(1, v) (a linear alpha(v) "
            "would make B_u = A_u / alpha(v), not a polynomial)"
        )
    conditions = val.choice(conditions, "conditions", CONDITIONS)
    if mu is not None:
        _check_varying(continuity, conditions, alpha)
        return _join_varying(patch, axis, options())
    across_cls = patch._u_cls if axis == 0 else patch._v_cls
    along_cls = patch._v_cls if axis == 0 else patch._u_cls
    across_lam = patch.lam_u if axis == 0 else patch.lam_v
    along_lam = patch.lam_v if axis == 0 else patch.lam_u
    new_family = across_cls if family is None else family
    count = patch.net.shape[1 - axis]
    given = np.size(np.asarray(val.real_array(rest, "rest"), dtype=float)) > 0
    rest_arr = np.asarray(val.real_array(rest, "rest"), dtype=float) if given else None
    exact_rest = _exact_net(rest) if given else ()
    if rest_arr is not None:
        if rest_arr.ndim != 3:
            raise ValueError(
                "rest must be a grid of control points (rows, points, d), got shape "
                f"{rest_arr.shape}"
            )
        want = count
        got = rest_arr.shape[1] if axis == 0 else rest_arr.shape[0]
        if got != want:
            raise ValueError(f"rest must have {want} points along the boundary, got {got}")
    columns = _columns(patch, axis)
    rest_cols: list[Any] = [()] * count
    if rest_arr is not None:
        rest_rows: Any = exact_rest if exact_rest is not None else rest_arr.tolist()
        rest_cols = _transpose(rest_rows) if axis == 0 else [list(r) for r in rest_rows]
    if conditions == "derived":
        new_cls = family_class(new_family)
        weights = surface_sides.derived_weights(
            across_cls,
            new_cls,
            continuity,
            len(columns[0]) - 1,
            degree,
            (across_lam, lam, alpha if continuity == "G1" else 1),
        )
        order = ORDER[continuity]
        if any(len(col) != degree - order for col in rest_cols):
            raise ValueError(
                f"rest must hold {degree - order} rows after the {order + 1} solved ones "
                f"(degree {degree}), got {len(rest_cols[0])}"
            )
        new_columns = [
            _apply_weights(weights, columns[j], list(rest_cols[j]), order) for j in range(count)
        ]
        net: Any = _transpose(new_columns) if axis == 0 else new_columns
        fam = (new_cls, along_cls) if axis == 0 else (along_cls, new_cls)
        lams = (lam, along_lam) if axis == 0 else (along_lam, lam)
        if not new_cls._has_lambda:
            lams = (None, along_lam) if axis == 0 else (along_lam, None)
        return most_specific(net, lams[0], lams[1], classes=fam, check_range=check_range)
    new_columns = []
    for j in range(count):
        curve = (
            across_cls(columns[j], across_lam, check_range=False)
            if across_cls._has_lambda
            else across_cls(columns[j])
        )
        nxt = join(
            curve,
            continuity,
            degree,
            lam,
            alpha=alpha if continuity == "G1" else 1,
            rest=rest_cols[j],
            family=new_family,
            check_range=check_range,
        )
        new_columns.append(list(nxt.control_points()))
    net = _transpose(new_columns) if axis == 0 else new_columns
    fam = (type(nxt), along_cls) if axis == 0 else (along_cls, type(nxt))
    lams = (nxt.lam, along_lam) if axis == 0 else (along_lam, nxt.lam)
    return most_specific(net, lams[0], lams[1], classes=fam, check_range=False)


def _default_degree(
    patch: Surface, axis: int, continuity: str, degree: object, rest: object
) -> int:
    """`degree`, or by default the solved rows plus the rows of `rest` (so that a call with
    `rest` need not count them), or the patch's own degree across the boundary."""
    if degree is not None:
        return val.integer(degree, "degree")
    arr = np.asarray(val.real_array(rest, "rest"), dtype=float)
    if arr.size and arr.ndim == 3:
        return ORDER[continuity] + int(arr.shape[axis])
    return int(patch.net.shape[axis]) - 1


def _apply_weights(weights: Any, first: list[Any], rest: list[Any], order: int) -> list[Any]:
    """One column of the new patch: rows 0..order by the weights, then `rest`."""
    n = len(first) - 1
    dim = len(first[0])
    rows = []
    for r in range(order + 1):
        acc: list[Any] = [0 * first[0][0]] * dim
        for (row, src, k), w in weights.items():
            if row != r:
                continue
            x = first[n - k] if src == "first" else rest[k - order - 1]
            acc = [a + w * c for a, c in zip(acc, x, strict=True)]
        rows.append(tuple(acc))
    return rows + [tuple(p) for p in rest]


def _check_varying(continuity: str, conditions: str, alpha: object) -> None:
    if conditions != "solve":
        raise ValueError('mu (a varying G1 factor) is solved: use conditions="solve"')
    if continuity != "G1":
        raise ValueError(f"mu (a varying G1 factor) needs continuity G1, got {continuity}")
    if alpha != 1:
        raise ValueError("give either alpha (a constant G1 factor) or mu, not both")


def _varying_target(
    patch: Surface, axis: int, at_end: bool, mu: object
) -> tuple[list[Any], list[Any]]:
    """(value, target): A's boundary (at the end of direction `axis`, or its start) and
    μ(v) times A's cross derivative there, both in Bernstein form of degree N + 1 along it
    (N: A's Bézier degree there)."""
    mu0, mu1 = _factor(mu)
    lines = _rows_across(patch.to_bezier().control_net(), axis)  # N + 1 Bézier lines across
    big_n = len(lines) - 1
    big_m = len(lines[0]) - 1
    if at_end:  # A(1, v) and A_u(1, v) = M (P_M - P_{M-1}) on each line
        ends = [line[-1] for line in lines]
        slopes = [
            tuple(big_m * (x - y) for x, y in zip(line[-1], line[-2], strict=True))
            for line in lines
        ]
    else:  # A(0, v) and A_u(0, v) = M (P_1 - P_0)
        ends = [line[0] for line in lines]
        slopes = [
            tuple(big_m * (x - y) for x, y in zip(line[1], line[0], strict=True)) for line in lines
        ]
    value = _elevate_to(ends, big_n + 1)
    f0, f1 = mu0, mu0 + mu1  # μ in Bernstein degree 1
    dim = len(ends[0])
    zero = 0 * ends[0][0]
    target = []  # (μ A_u)_k = ((N+1-k) f0 s_k + k f1 s_{k-1}) / (N+1)
    for k in range(big_n + 2):
        target.append(
            tuple(
                (
                    (big_n + 1 - k) * f0 * (slopes[k][c] if k <= big_n else zero)
                    + k * f1 * (slopes[k - 1][c] if k >= 1 else zero)
                )
                / (big_n + 1)
                for c in range(dim)
            )
        )
    return value, target


def _join_varying_before(patch: Surface, axis: int, opts: JoinOptions) -> Surface:
    """G1 across u = 0 (or v = 0) with B_u(1, v) = μ(v) A_u(0, v): the Bézier patch of
    degree 1 across with B's boundary values and cross derivative as its own (the lines from
    value_k to value_k + target_k), joined before with C1 (surface_sides.join_before): B ends
    at A(0, v) with that derivative, classical Bézier of degree N + 1 along the boundary."""
    value, target = _varying_target(patch, axis, False, opts.mu)
    ramp = [
        value,
        [
            tuple(x + y for x, y in zip(p, d, strict=True))
            for p, d in zip(value, target, strict=True)
        ],
    ]
    net = ramp if axis == 0 else _transpose(ramp)
    across = patch._u_cls if axis == 0 else patch._v_cls
    try:
        family = across if opts.family is None else opts.family
        ramp_opts = replace(opts, alpha=1, mu=None, family=family, params=None, conditions="solve")
        return surface_sides.join_before(BezierSurface(net), axis, "C1", ramp_opts)
    except ValueError as exc:
        if "points along the boundary" in str(exc):
            count = len(value)
            raise ValueError(
                f"rest must be a grid of control points with {count} points along the boundary "
                f"(N + 2 = {count}: the patch's Bézier degree {count - 2} there, plus one for mu)"
            ) from None
        raise


def _factor(mu: object) -> tuple[Fraction | float, Fraction | float]:
    if not isinstance(mu, tuple | list) or len(mu) != 2:
        raise ValueError(f"mu must be a pair (mu0, mu1) for mu(v) = mu0 + mu1 v, got {mu!r}")
    mu0 = val.real_number(mu[0], "mu[0]")
    mu1 = val.real_number(mu[1], "mu[1]")
    if not (mu0 > 0 and mu0 + mu1 > 0):
        raise ValueError(
            f"mu(v) = {mu0} + {mu1} v must be positive on [0, 1] (mu0 > 0 and mu0 + mu1 > 0)"
        )
    return mu0, mu1


def _rows_across(rows: Any, axis: int) -> list[Any]:
    """The lines of a net across the boundary (each one curve in the across direction)."""
    return _transpose(rows) if axis == 0 else [list(r) for r in rows]


def _join_varying(patch: Surface, axis: int, opts: JoinOptions) -> Surface:
    """G1 with B_u(0, v) = μ(v) A_u(1, v), μ linear (see the module's docstring)."""
    degree, lam, rest, mu = opts.degree, opts.lam, opts.rest, opts.mu
    family, check_range = opts.family, opts.check_range
    across_cls = patch._u_cls if axis == 0 else patch._v_cls
    value, target = _varying_target(patch, axis, True, mu)
    big_n = len(value) - 2
    count = big_n + 2
    given = np.size(np.asarray(val.real_array(rest, "rest"), dtype=float)) > 0
    rest_cols: list[Any] = [()] * count
    if given:
        rest_arr = np.asarray(val.real_array(rest, "rest"), dtype=float)
        got = rest_arr.shape[1] if rest_arr.ndim == 3 and axis == 0 else None
        if rest_arr.ndim == 3 and axis == 1:
            got = rest_arr.shape[0]
        if got != count:
            raise ValueError(
                f"rest must be a grid of control points with {count} points along the boundary "
                f"(N + 2 = {count}: the patch's Bézier degree {big_n} there, plus one for mu), "
                f"got shape {rest_arr.shape}"
            )
        exact_rest = _exact_net(rest)
        rest_rows: Any = exact_rest if exact_rest is not None else rest_arr.tolist()
        rest_cols = _rows_across(rest_rows, axis)
    new_family = across_cls if family is None else family
    new_columns = []
    for k in range(count):
        # the line through value_k - target_k and value_k: it ends at value_k with slope target_k
        start = tuple(x - y for x, y in zip(value[k], target[k], strict=True))
        nxt = join(
            BezierCurve([start, value[k]]),
            "C1",
            degree,
            lam,
            rest=rest_cols[k],
            family=new_family,
            check_range=check_range,
        )
        new_columns.append(list(nxt.control_points()))
    net: Any = _transpose(new_columns) if axis == 0 else new_columns
    fam = (type(nxt), BezierCurve) if axis == 0 else (BezierCurve, type(nxt))
    lams = (nxt.lam, None) if axis == 0 else (None, nxt.lam)
    if not type(nxt)._has_lambda:
        return BezierSurface(net)
    return Surface(net, lams[0], lams[1], family=fam, check_range=False)


# ---------------------------------------------------------------------- grids of patches
def _boundary_derivatives(surf: Surface, axis: int, at_end: bool, order: int) -> list[Any]:
    """The Bézier control points (along the boundary) of ∂^r S/∂(across)^r on the boundary
    (across = 1 if at_end else 0), r = 0..order, in the net's arithmetic."""
    bez = surf.to_bezier()
    rows: Any = bez.control_net()
    lines = _transpose(rows) if axis == 0 else [list(r) for r in rows]  # lines across
    out = []
    for r in range(order + 1):
        coeffs = []
        for line in lines:
            pts = list(line)
            for d in range(len(pts) - 1, len(pts) - 1 - r, -1):
                if d < 1:
                    pts = [tuple(0 * c for c in pts[0])]
                    break
                pts = _apply(hodograph_matrix(d), pts)
            coeffs.append(pts[-1] if at_end else pts[0])
        out.append(coeffs)
    return out


def _apply(weights: Any, points: list[Any]) -> list[Any]:
    """weights @ points, in the points' arithmetic (Fractions stay exact)."""
    dim = len(points[0])
    return [
        tuple(
            sum((w * p[c] for w, p in zip(row, points, strict=True)), 0 * points[0][c])
            for c in range(dim)
        )
        for row in weights
    ]


def _elevate_to(points: list[Any], degree: int) -> list[Any]:
    while len(points) - 1 < degree:
        points = _apply(elevation_matrix(len(points) - 1), points)
    return points


def _same(a: list[Any], b: list[Any], tol: float) -> bool:
    size = max(len(a), len(b)) - 1
    a, b = _elevate_to(a, size), _elevate_to(b, size)
    return all(
        abs(x - y) <= tol for p, q in zip(a, b, strict=True) for x, y in zip(p, q, strict=True)
    )


def _proportional(a: list[Any], b: list[Any], tol: float) -> bool:
    """a = α b with one α > 0."""
    size = max(len(a), len(b)) - 1
    return param_surface_report.proportional(_elevate_to(a, size), _elevate_to(b, size), tol)


def _linear_factor(a: list[Any], b: list[Any], tol: float) -> bool:
    """b = μ a with μ(v) linear and positive on [0, 1] (a G1 join with a varying factor): with
    a of Bernstein degree p and b of degree p + 1, b_0 = μ(0) a_0 and b_{p+1} = μ(1) a_p give
    μ, and every coefficient of μ·a is checked."""
    p = max(len(a) - 1, len(b) - 2)
    a, b = _elevate_to(a, p), _elevate_to(b, p + 1)
    ends = []
    for src, dst in ((a[0], b[0]), (a[-1], b[-1])):
        k = max(range(len(src)), key=lambda i: abs(src[i]))
        if not src[k]:
            return False
        ends.append(dst[k] / src[k])
    f0, f1 = ends
    if not (f0 > 0 and f1 > 0):
        return False
    zero = 0 * a[0][0]
    for k, q in enumerate(b):
        for c, x in enumerate(q):
            left = a[k][c] if k <= p else zero
            right = a[k - 1][c] if k >= 1 else zero
            if abs(x - ((p + 1 - k) * f0 * left + k * f1 * right) / (p + 1)) > tol:
                return False
    return True


def __getattr__(name: str) -> Any:
    # BoundaryReport lives in _surface_results, imported on the first report() (issue #29:
    # import time); still reachable here, where it was defined until round 18
    if name == "BoundaryReport":
        from ._surface_results import BoundaryReport

        return BoundaryReport
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


class CompositeSurface:
    """A grid of patches: patches[r][c] meets patches[r + 1][c] along its boundary u = 1 and
    patches[r][c + 1] along v = 1 (each patch on its own domain: the unit square, or its
    families' domains for a patch of trigonometric, hyperbolic or mixed families)."""

    def __init__(self, patches: Sequence[Sequence[Surface]], *, tol: float = 1e-12) -> None:
        try:  # a surface, or a row of them, is not iterable
            grid = [list(row) for row in patches]
        except TypeError:
            raise TypeError(
                "patches must be a grid of surfaces, a list of rows: [[patch]] for one patch, "
                "[[a], [b]] for b across a's boundary u = 1, [[a, b]] across v = 1"
            ) from None
        if not grid or not grid[0] or any(len(row) != len(grid[0]) for row in grid):
            raise ValueError("patches must be a non-empty rectangular grid (a list of equal rows)")
        for row in grid:
            for p in row:
                if not isinstance(p, Surface):
                    raise TypeError(
                        f"patches: every patch must be a lambda_bezier surface, got "
                        f"{type(p).__name__}"
                    )
        if len({p.dimension for row in grid for p in row}) != 1:
            raise ValueError("patches: all patches must have the same dimension")
        self.patches = grid
        self.tol = val.tolerance(tol)

    def report(self) -> list[BoundaryReport]:
        """The continuity achieved at every interior boundary (exact patches: exactly)."""
        from ._surface_results import BoundaryReport  # on first use: import time (#29)

        out = []
        rows, cols = len(self.patches), len(self.patches[0])
        for r in range(rows):
            for c in range(cols):
                for side, (r2, c2) in (("u", (r + 1, c)), ("v", (r, c + 1))):
                    if r2 < rows and c2 < cols:
                        out.append(
                            BoundaryReport(
                                (r, c),
                                side,
                                self._continuity(
                                    self.patches[r][c],
                                    self.patches[r2][c2],
                                    0 if side == "u" else 1,
                                ),
                            )
                        )
        return out

    def _continuity(self, a: Surface, b: Surface, axis: int) -> str:
        if param_surface_report.is_atom_patch(a) or param_surface_report.is_atom_patch(b):
            return param_surface_report.continuity(a, b, axis, self.tol)  # no Bézier form
        exact = a.is_exact and b.is_exact
        size = max(
            float(np.abs(a.to_bezier().net).max()), float(np.abs(b.to_bezier().net).max()), 1.0
        )
        tol = 0.0 if exact else self.tol * size
        da = _boundary_derivatives(a, axis, True, 2)
        db = _boundary_derivatives(b, axis, False, 2)
        if not _same(da[0], db[0], tol):
            return "none"
        if not _same(da[1], db[1], tol * 10):
            if (
                _proportional(da[1], db[1], tol * 10)
                or _linear_factor(da[1], db[1], tol * 10)  # B_u = μ A_u, B after A
                or _linear_factor(db[1], da[1], tol * 10)  # A_u = μ B_u, B before A (u0, v0)
                or self._tangent_planes_agree(a, b, axis, da, db, tol * 10)
            ):
                return "G1"
            return "C0"
        return "C2" if _same(da[2], db[2], tol * 100) else "C1"

    @staticmethod
    def _tangent_planes_agree(
        a: Surface, b: Surface, axis: int, da: list[Any], db: list[Any], eps: float
    ) -> bool:
        """G1 in general: B_u = μ A_u + ν A_v with μ(v) > 0 along the boundary (the tangent
        planes agree, B on the far side), μ and ν any functions of v; exact for exact
        patches (_tangent_planes.span_exact), else at sample points."""
        from ._tangent_planes import span_exact  # on call: import time (#29)

        if eps == 0:
            n = len(da[0]) - 1
            tangent = _apply(hodograph_matrix(n), da[0]) if n else [tuple(0 * x for x in da[0][0])]
            return span_exact(da[1], tangent, db[1])
        return bool(param_surface_report.g1_sampled(a, b, axis, eps))

    def evaluate(self, u: float, v: float) -> np.ndarray:
        """S at global parameters u in [0, rows], v in [0, cols]."""
        rows, cols = len(self.patches), len(self.patches[0])
        uu = val.real_number(u, "u")
        vv = val.real_number(v, "v")
        if not (0 <= uu <= rows and 0 <= vv <= cols):
            raise ValueError(f"(u, v) = ({uu}, {vv}) is outside [0, {rows}] x [0, {cols}]")
        r, c = min(int(uu), rows - 1), min(int(vv), cols - 1)
        patch = self.patches[r][c]
        return patch.evaluate(*param_surface_report.local(patch, float(uu) - r, float(vv) - c))
