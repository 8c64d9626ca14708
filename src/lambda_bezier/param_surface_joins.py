"""`join_surface` across the boundary of a surface of several-parameter, indexed or
trigonometric/hyperbolic/mixed families (param_surfaces, atom_surfaces).

As for one-parameter families (surface_joins), when the next patch keeps the family, degree
and parameters along the boundary, every condition holds for all v exactly when each column
of the net joins as a curve does; the columns are joined with the curves' `join`, which
solves these families' joins per degree (the end derivatives of the derived documents, in
each family's own t). G1 has one constant α: A_u(end, v) = α B_u(start, v). The new patch
is a surface of the same kind, with the new family's parameters by name across the boundary
(default: the patch's own) and the patch's along it.

``conditions="derived"`` reads the join's weights once from the derived document of either
family across the boundary (its ``joins`` table, derive/formulas/joins_several.py, read by
_derived_joins: the weights are data, never evaluated) and applies the same weights to every
column; a pair the document does not hold is a ValueError naming it (conditions="solve" then
joins each column with `join`, which takes the document's weights where it has them and
otherwise solves the join per degree). The tests check the two against each other and against
the per-degree solve.
"""

from __future__ import annotations

from typing import Any, NamedTuple

import numpy as np

from . import _atom_joins
from . import _poly_direction as pd
from . import _validate as val
from ._join_options import JoinOptions
from .joins import join
from .param_surfaces import family_surface
from .surfaces import _exact_net


class Sides(NamedTuple):
    """Both patches' families across a boundary, resolved once for every side: the given
    patch's family and parameters across and along it, the new patch's (default: the given
    patch's across), and the new family as it builds a curve of `degree` (an indexed family
    at that degree with one value per index)."""

    across: Any
    across_params: dict[str, Any]
    along: Any
    along_params: dict[str, Any]
    new_family: Any
    new_params: dict[str, Any]
    target: Any
    target_params: dict[str, Any]


def resolve_sides(patch: Any, axis: int, family: Any, params: Any, degree: int) -> Sides:
    """The families of a join across direction `axis` of a patch whose parameters go by
    name (the sides u1/v1 here and u0/v0 in surface_sides alike)."""
    across = patch.family_u if axis == 0 else patch.family_v
    across_params = patch.params_u if axis == 0 else patch.params_v
    along = patch.family_v if axis == 0 else patch.family_u
    along_params = patch.params_v if axis == 0 else patch.params_u
    new_family = across if family is None else pd.by_name_family(family)
    if params is not None and not isinstance(params, dict):
        raise TypeError(f"params must be a dict {{name: value}}, not {type(params).__name__}")
    new_params = dict(across_params if params is None else params)
    target, target_params = new_family, new_params
    if hasattr(new_family, "index_name"):  # one value per index of the new degree
        target = new_family.at_degree(degree)
        target_params = new_family.index_values(degree, new_params.get(new_family.index_name))
    return Sides(
        across,
        dict(across_params),
        along,
        dict(along_params),
        new_family,
        new_params,
        target,
        target_params,
    )


def _join_param_surface(patch: Any, axis: int, continuity: str, opts: JoinOptions) -> Any:
    """The next patch across `patch`'s boundary at the end of direction `axis` (0: u)."""
    degree, rest, alpha, check_range = opts.degree, opts.rest, opts.alpha, opts.check_range
    family, params, conditions = opts.family, opts.params, opts.conditions
    side = resolve_sides(patch, axis, family, params, degree)
    across, across_params = side.across, side.across_params
    along, along_params = side.along, side.along_params
    new_family, new_params = side.new_family, side.new_params
    target, target_params = side.target, side.target_params
    count = patch.net.shape[1 - axis]
    rows: Any = patch.control_net()
    columns = [[rows[i][j] for i in range(len(rows))] for j in range(count)] if axis == 0 else rows
    rest_cols: list[Any] = [()] * count
    if np.size(np.asarray(val.real_array(rest, "rest"), dtype=float)):
        arr = np.asarray(val.real_array(rest, "rest"), dtype=float)
        if arr.ndim != 3 or (arr.shape[1] if axis == 0 else arr.shape[0]) != count:
            raise ValueError(
                f"rest must be a grid of rows of {count} points along the boundary, got shape "
                f"{arr.shape}"
            )
        exact = _exact_net(rest)
        given: Any = exact if exact is not None else arr.tolist()
        rest_cols = (
            [[given[i][j] for i in range(len(given))] for j in range(count)]
            if axis == 0
            else [list(r) for r in given]
        )
    new_columns: list[Any] = []
    net: Any
    g1 = str(continuity).upper() == "G1"
    weights = None
    if conditions == "derived":
        first = pd.direction_curve(across, columns[0], across_params)
        second = _second_side(target, target_params, degree, check_range)
        weights = _atom_joins.derived_weights(
            _atom_joins.join_side(first, 1, first.degree), second, continuity, alpha if g1 else 1, 0
        )
        if weights is None:
            raise ValueError(
                f'conditions="derived": the derived documents of {pd.family_name(across)} and '
                f"{pd.family_name(new_family)} hold no {continuity} join "
                f"{pd.family_name(across)}>{pd.family_name(new_family)} at degrees "
                f'{first.degree} and {degree} (use conditions="solve")'
            )
    order = 2 if continuity == "C2" else 1
    for j in range(count):
        curve = pd.direction_curve(across, columns[j], across_params)
        if weights is not None:
            given = list(rest_cols[j])
            if len(given) != degree - order:
                raise ValueError(
                    f"rest must hold {degree - order} rows after the {order + 1} solved ones "
                    f"(degree {degree}, {continuity}), got {len(given)}"
                )
            exact_given = val.exact_rows(given) if given else ()
            new_columns.append(_atom_joins._apply(weights, curve, given, exact_given, order))
            continue
        builtin = pd.is_class(target)  # a built-in class takes its λ positionally
        nxt = join(
            curve,
            continuity,
            degree,
            next(iter(target_params.values()), None) if builtin else None,
            alpha=alpha if str(continuity).upper() == "G1" else 1,
            rest=rest_cols[j],
            family=target,
            params=None if builtin else target_params,
            check_range=check_range,
        )
        new_columns.append(list(nxt.control_points()))
    if axis == 0:
        net = [[new_columns[j][i] for j in range(count)] for i in range(len(new_columns[0]))]
        pair, pu, pv = (new_family, along), new_params, along_params
    else:
        net = new_columns
        pair, pu, pv = (along, new_family), along_params, new_params
    return family_surface(net, pair, params_u=pu, params_v=pv, check_range=False)


def _second_side(target: Any, values: Any, degree: int, check_range: bool) -> Any:
    """The new patch's side of a join as _atom_joins.derived_weights names it, as `join`
    builds it: an atom family with its values (exact where given exactly), a polynomial family
    in several parameters at its fixed values, a one-parameter family with its λ."""
    if pd.is_class(target):  # a built-in class across an atom family
        return _atom_joins.join_side(target, 2, degree, next(iter(values.values()), None))
    if getattr(target, "atom_data", None) is not None:
        given = target.parameter_values(None, values, {})
        exact = target.exact_values(given, check_range)
        shown = {
            k: (x if val.is_exact_scalar(given[k]) else float(x))
            for k, x in zip(target.parameters, exact, strict=True)
        }
        return _atom_joins.join_side(target, 2, degree, shown)
    if getattr(target, "several", None) is not None:
        cls = target._fixed_class(target.parameter_values(None, values, {}), check_range)
        return _atom_joins.join_side(cls, 2, degree)
    lam = next(iter(target.parameter_values(None, values, {}).values()))
    return _atom_joins.join_side(target.curve_class, 2, degree, lam)
