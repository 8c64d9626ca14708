"""The four sides of a patch for `join_surface`, and joins on the sides u = 0 and v = 0.

A side names the boundary the new patch meets: "u1" (also "u", "u=1") is the patch's
boundary u = 1, "u0" ("u=0") its boundary u = 0, and "v1" ("v", "v=1") and "v0" ("v=0") the
same in v. The new patch is oriented so that the grid reads in increasing parameters: across
u = 1 it starts where the patch ends (B(0, v) = A(1, v)); across u = 0 it ends where the
patch starts (B(1, v) = A(0, v)), so that B comes before A in u, as in a `CompositeSurface`
[[B], [A]].

Across u = 0 the unknowns are the new patch's last rows, next to the boundary. The conditions
say that A continues B as the curves' `join` continues a curve, column by column: A's rows
P_0..P_R (R = 1 for C1/G1, 2 for C2) are `join`'s solved points of a curve B's column, the
rest of A's column given. `join` is linear in the points it is given, so one call on a probe
reads its weights: B's column the unit vectors e_0..e_m and A's later points e_{m+1}.. in a
space of that many coordinates; the solved points' coordinates are then the weights of each
point (exact for exact parameters). Every family pair `join` supports (built-in, defined by
data, several-parameter, indexed, trigonometric, hyperbolic, mixed) is thereby supported on
these sides too, in each family's own t. The weights of B's last R + 1 points form a square
system; it is solved per column, B's other points (`rest`) on the right-hand side.

G1 keeps one convention on every side: the given patch's cross derivative is α times the new
patch's (A_u(1, v) = α B_u(0, v) across u = 1, A_u(0, v) = α B_u(1, v) across u = 0), so α > 1
gives the new patch a shorter cross tangent on either side.
"""

from __future__ import annotations

from collections.abc import Callable
from fractions import Fraction
from typing import Any

import numpy as np

from . import _atom_joins, _derived_joins
from . import _poly_direction as pd
from . import _validate as val
from ._join_options import JoinOptions
from .builtin_surfaces import most_specific
from .curves import Curve, family_class
from .joins import join
from .param_surface_joins import _second_side, resolve_sides
from .param_surfaces import family_surface
from .surfaces import Surface, _exact_net

Number = Fraction | float

#: the side names join_surface accepts: name -> (axis, at the end of that direction)
SIDE_NAMES: dict[str, tuple[int, bool]] = {
    "u": (0, True),
    "u1": (0, True),
    "u=1": (0, True),
    "u0": (0, False),
    "u=0": (0, False),
    "v": (1, True),
    "v1": (1, True),
    "v=1": (1, True),
    "v0": (1, False),
    "v=0": (1, False),
}


def parse_side(side: object) -> tuple[int, bool]:
    """(axis, at_end) of a side name: axis 0 for u, 1 for v; at_end for u = 1 or v = 1."""
    if isinstance(side, str):
        key = side.strip().lower().replace(" ", "")
        if key in SIDE_NAMES:
            return SIDE_NAMES[key]
    raise ValueError(
        f"side must name one of the patch's four boundaries: 'u1' (or 'u', 'u=1'), 'u0' (or "
        f"'u=0'), 'v1' (or 'v', 'v=1'), 'v0' (or 'v=0'); got {side!r}"
    )


def inverse_alpha(alpha: object) -> Number:
    """1/α for `join` (its convention is C1'(end) = α C2'(start), the earlier curve first)."""
    a = val.real_number(alpha, "alpha")
    if not a > 0:
        raise ValueError(f"alpha must be > 0 (a G1 join keeps the direction), got {a}")
    return Fraction(1) / a if isinstance(a, Fraction) else 1.0 / float(a)


def probe_weights(
    make_new: Callable[[list[list[int]]], Curve],
    new_degree: int,
    given_degree: int,
    order: int,
    join_given: Callable[[Curve, list[list[int]]], Curve],
) -> list[list[Number]]:
    """L[r][i]: the weight of point i in the given curve's solved point P_r when it joins a
    new curve (points 0..m, then the given curve's points P_{R+1}.. as i = m+1..)."""
    size = new_degree + 1 + given_degree - order
    unit = [[1 if c == i else 0 for c in range(size)] for i in range(size)]
    probe = make_new(unit[: new_degree + 1])
    try:
        solved = join_given(probe, unit[new_degree + 1 :]).control_points()
    except ValueError as exc:  # say which curve is which in join's words
        raise ValueError(
            "the new patch B before the given patch A cannot meet the conditions (B's lines "
            "across the boundary are join's first curve, of degree "
            f"{new_degree}; A's its second): {exc}"
        ) from None
    return [list(p) for p in solved[: order + 1]]


def weights_from_document(
    found: dict[tuple[int, str, int], Any], new_degree: int, given_degree: int, order: int
) -> list[list[Number]]:
    """probe_weights' L[r][i] read from a derived document's join weights {(row, src, k): w}
    with the new curve first: src "first" k is its point m - k (i = m - k), src "rest" k the
    given curve's own point k (i = m + 1 + k - R - 1)."""
    size = new_degree + 1 + given_degree - order
    out: list[list[Number]] = [[Fraction(0)] * size for _ in range(order + 1)]
    for (r, src, k), w in found.items():
        i = new_degree - k if src == "first" else new_degree + k - order
        out[r][i] = out[r][i] + w
    return out


def _solve(matrix: list[list[Number]], rhs: list[list[Number]]) -> list[list[Number]]:
    """X with matrix X = rhs (rows of X are points), Gauss–Jordan in the entries' arithmetic;
    ValueError when the matrix is singular."""
    size = len(matrix)
    a = [list(row) for row in matrix]
    b = [list(row) for row in rhs]
    scale = max((abs(float(x)) for row in a for x in row), default=1.0) or 1.0
    for col in range(size):
        pivot = max(range(col, size), key=lambda r: abs(float(a[r][col])))
        x = a[pivot][col]
        if (x == 0) if isinstance(x, Fraction) else abs(float(x)) <= 1e-13 * scale:
            raise ValueError(
                "the new patch's rows next to the boundary are not determined: its end "
                f"derivatives there do not involve row {col} of them independently (choose "
                "another degree or parameter)"
            )
        a[col], a[pivot] = a[pivot], a[col]
        b[col], b[pivot] = b[pivot], b[col]
        for r in range(size):
            if r != col and a[r][col] != 0:
                f = a[r][col] / a[col][col]
                a[r] = [p - f * q for p, q in zip(a[r], a[col], strict=True)]
                b[r] = [p - f * q for p, q in zip(b[r], b[col], strict=True)]
    return [[v / a[r][r] for v in b[r]] for r in range(size)]


def solve_before(
    weights: list[list[Number]],
    given_line: list[Any],
    new_given: list[Any],
    new_degree: int,
    order: int,
) -> list[Any]:
    """The new curve's points 0..m (its given first points `new_given`, the last R + 1
    solved) such that `given_line` continues it with the `weights` of probe_weights."""
    m = new_degree
    first_unknown = m - order
    if len(new_given) != first_unknown:
        raise ValueError(
            f"rest must hold {first_unknown} rows before the {order + 1} solved ones (the new "
            f"patch's degree {m} across the boundary), got {len(new_given)}"
        )
    dim = len(given_line[0])
    rhs: list[list[Any]] = []
    for r in range(order + 1):
        acc = list(given_line[r])
        for i in range(first_unknown):
            w = weights[r][i]
            if w != 0:
                acc = [a - w * p for a, p in zip(acc, new_given[i], strict=True)]
        for k, point in enumerate(given_line[order + 1 :]):
            w = weights[r][m + 1 + k]
            if w != 0:
                acc = [a - w * p for a, p in zip(acc, point, strict=True)]
        rhs.append(acc)
    square = [[weights[r][first_unknown + j] for j in range(order + 1)] for r in range(order + 1)]
    solved = _solve(square, rhs)
    assert all(len(p) == dim for p in solved)
    return [tuple(p) for p in new_given] + [tuple(p) for p in solved]


def rest_lines(rest: Any, axis: int, count: int) -> tuple[list[Any], int | None]:
    """`rest` (rows across the boundary, each of `count` points along it) as lines across the
    boundary (one per point along it), exact where given exactly, and its number of rows
    across (None when not given)."""
    arr = np.asarray(val.real_array(rest, "rest"), dtype=float)
    if arr.size == 0:
        return [[] for _ in range(count)], None
    if arr.ndim != 3:
        raise ValueError(
            f"rest must be a grid of control points (rows, points, d), got shape {arr.shape}"
        )
    along = arr.shape[1] if axis == 0 else arr.shape[0]
    if along != count:
        raise ValueError(f"rest must have {count} points along the boundary, got {along}")
    if not np.isfinite(arr).all():
        raise ValueError("rest contains NaN or infinity")
    exact = _exact_net(rest)
    rows: Any = exact if exact is not None else arr.tolist()
    if axis == 0:
        lines = [[rows[i][j] for i in range(len(rows))] for j in range(count)]
    else:
        lines = [list(r) for r in rows]
    return lines, arr.shape[0] if axis == 0 else arr.shape[1]


def _lines(rows: Any, axis: int) -> list[Any]:
    """The lines of a net across the boundary (axis 0: the u-curves, one per column)."""
    if axis == 0:
        return [[rows[i][j] for i in range(len(rows))] for j in range(len(rows[0]))]
    return [list(r) for r in rows]


def _net(lines: list[Any], axis: int) -> list[Any]:
    if axis == 0:
        return [[lines[j][i] for j in range(len(lines))] for i in range(len(lines[0]))]
    return lines


def join_before(patch: Surface, axis: int, continuity: str, opts: JoinOptions) -> Surface:
    """The patch B across `patch`'s boundary u = 0 (axis 0) or v = 0: B(1, v) = A(0, v) and
    the cross derivatives per `continuity` (see the module's docstring); with
    ``conditions="derived"`` the weights come from a derived document instead of the probe."""
    degree, lam, rest, alpha = opts.degree, opts.lam, opts.rest, opts.alpha
    family, check_range, conditions = opts.family, opts.check_range, opts.conditions
    order = 2 if continuity == "C2" else 1
    step = inverse_alpha(alpha) if continuity == "G1" else 1
    count = patch.net.shape[1 - axis]
    given_lines = _lines(patch.control_net(), axis)
    n = len(given_lines[0]) - 1
    new_given, _ = rest_lines(rest, axis, count)
    if hasattr(patch, "family_u"):  # several-parameter, indexed or atom families, by name
        return _before_by_name(
            patch, axis, continuity, opts, step, given_lines, new_given, n, order
        )
    across_cls = patch._u_cls if axis == 0 else patch._v_cls
    along_cls = patch._v_cls if axis == 0 else patch._u_cls
    across_lam = patch.lam_u if axis == 0 else patch.lam_v
    along_lam = patch.lam_v if axis == 0 else patch.lam_u
    new_cls = across_cls if family is None else family_class(family)
    if new_cls._has_lambda:
        if lam is None:
            raise ValueError(f"a {new_cls.family} patch needs a shape parameter lam")
        new_lam = val.as_lambda(lam, new_cls._data, check_range=check_range)
    elif lam is not None:
        raise ValueError("lam: a classical Bézier direction takes no shape parameter")
    else:
        new_lam = None
    _check_new_degree(new_cls, degree)

    def make_new(points: list[list[int]]) -> Curve:
        return (
            new_cls(points, new_lam, check_range=False) if new_cls._has_lambda else new_cls(points)
        )

    def join_given(probe: Curve, later: list[list[int]]) -> Curve:
        return join(
            probe,
            continuity,
            n,
            across_lam,
            alpha=step,
            rest=later or (),
            family=across_cls,
            check_range=False,
        )

    if conditions == "derived":  # B's curve is the document's first, A's its second
        found = derived_weights(
            new_cls, across_cls, continuity, degree, n, (new_lam, across_lam, step)
        )
        weights = weights_from_document(found, degree, n, order)
    else:
        weights = probe_weights(make_new, degree, n, order, join_given)
    lines = [
        solve_before(weights, given_lines[j], new_given[j], degree, order) for j in range(count)
    ]
    net = _net(lines, axis)
    fam = (new_cls, along_cls) if axis == 0 else (along_cls, new_cls)
    lams = (new_lam, along_lam) if axis == 0 else (along_lam, new_lam)
    return most_specific(net, lams[0], lams[1], classes=fam, check_range=False)


def _check_new_degree(cls: type[Curve], degree: int) -> None:
    degrees = pd.family_degrees(cls)
    if degrees is not None and degree not in degrees:
        raise ValueError(
            f"degree {degree} is not supported for {cls.family}: degrees "
            f"{degrees[0]}..{degrees[-1]}"
        )


def _before_by_name(
    patch: Any,
    axis: int,
    continuity: str,
    opts: JoinOptions,
    step: Any,
    given_lines: list[Any],
    new_given: list[Any],
    n: int,
    order: int,
) -> Surface:
    """join_before for a patch whose directions take their parameters by name."""
    degree, family, params = opts.degree, opts.family, opts.params
    check_range, conditions = opts.check_range, opts.conditions
    side = resolve_sides(patch, axis, family, params, degree)  # as on the sides u1, v1
    across, across_params = side.across, side.across_params
    along, along_params = side.along, side.along_params
    new_family, new_params = side.new_family, side.new_params
    target, target_params = side.target, side.target_params
    given_target, given_values = across, dict(across_params)
    if hasattr(across, "index_name"):
        given_target = across.at_degree(n)
        given_values = across.index_values(n, across_params.get(across.index_name))
    builtin_given = pd.is_class(given_target)

    def make_new(points: list[list[int]]) -> Curve:
        if pd.is_class(target):
            lam: Any = next(iter(target_params.values()), None)
            if target._has_lambda:
                return target(points, lam, check_range=check_range)
            return target(points)
        return target.curve(points, params=target_params, check_range=check_range)  # type: ignore[no-any-return]

    def join_given(probe: Curve, later: list[list[int]]) -> Curve:
        return join(
            probe,
            continuity,
            n,
            next(iter(given_values.values()), None) if builtin_given else None,
            alpha=step,
            rest=later or (),
            family=given_target,
            params=None if builtin_given else given_values,
            check_range=False,
        )

    if conditions == "derived":  # B's curve is the document's first, A's its second
        first = _atom_joins.join_side(make_new([[0]] * (degree + 1)), 1, degree)
        second = _second_side(given_target, given_values, n, check_range)
        found = _atom_joins.derived_weights(first, second, continuity, step, 0)
        if found is None:
            raise ValueError(
                f'conditions="derived": the derived documents of {pd.family_name(new_family)} '
                f"and {pd.family_name(across)} hold no {continuity} join "
                f"{pd.family_name(new_family)}>{pd.family_name(across)} at degrees {degree} "
                f"and {n} (the new patch B comes first across u = 0 or v = 0; use "
                'conditions="solve")'
            )
        weights = weights_from_document(found, degree, n, order)
    else:
        weights = probe_weights(make_new, degree, n, order, join_given)
    lines = [
        solve_before(weights, given_lines[j], new_given[j], degree, order)
        for j in range(len(given_lines))
    ]
    net = _net(lines, axis)
    if axis == 0:
        pair, pu, pv = (new_family, along), new_params, along_params
    else:
        pair, pu, pv = (along, new_family), along_params, new_params
    return family_surface(net, pair, params_u=pu, params_v=pv, check_range=False)


def derived_weights(
    first: type[Curve], second: type[Curve], continuity: str, n: int, m: int, values: Any
) -> dict[tuple[int, str, int], Any]:
    """{(row, src, k): weight} of the derived document of a family defined by data, at the
    degrees n (across the patch) and m (the new patch) and (λ1, λ2, α); exact for exact
    values. The weights are polynomial data (no expression is parsed)."""
    key = f"{first.family}>{second.family}"
    docs = [getattr(cls._data, "SURFACE_JOINS", None) for cls in (first, second) if cls is not None]
    table = next((d for d in docs if isinstance(d, dict)), None)
    if table is None:
        raise ValueError(
            f'conditions="derived" reads the derived document of a family defined by data; '
            f"{first.family} and {second.family} have none with surface joins (use "
            f'conditions="solve", or re-derive the family with `lambda-bezier derive --family`)'
        )
    if "pairs" not in table:
        raise ValueError(f"no derived surface conditions for {key}: {table.get('reason')}")
    entry = table["pairs"].get(key, {})
    if continuity not in entry:
        reason = entry.get("reason", "the pair is not in the document")
        raise ValueError(f"no derived {continuity} conditions for {key}: {reason}")
    lam1, lam2, alpha = (Fraction(0) if x is None else x for x in values)
    point = {"n": n, "m": m, "lam1": lam1, "lam2": lam2, "alpha": alpha}
    found = _derived_joins.lookup(table, key, continuity, point)
    assert found is not None  # the pair and continuity are in the table (checked above)
    return found


def takes_names(family: object) -> bool:
    """Whether `family` is a family whose parameters go by name (several, indexed, atom)."""
    return any(getattr(family, a, None) is not None for a in ("several", "index_name", "atom_data"))


class ByName:
    """A surface of built-in (one-parameter) families seen as one whose directions take their
    parameters by name, for a join into a family that does ({"lam": λ}, none for Bézier)."""

    def __init__(self, patch: Surface) -> None:
        self.net = patch.net
        self._patch = patch
        self.family_u, self.family_v = patch._u_cls, patch._v_cls
        self.params_u = {} if patch.lam_u is None else {patch._u_cls.parameter_name: patch.lam_u}
        self.params_v = {} if patch.lam_v is None else {patch._v_cls.parameter_name: patch.lam_v}

    def control_net(self) -> Any:
        return self._patch.control_net()
