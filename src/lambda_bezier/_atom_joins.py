"""Joins where a trigonometric, hyperbolic or mixed family takes part (issue #30).

`joins.join` hands over here when the first curve or the new segment's family is one of
atom_family's. The conditions are joins.py's, with every derivative taken in each curve's
own parameter (a trigonometric curve's t on [0, π/2], a polynomial curve's t on [0, 1]):

    C2(start) = C1(end),  C1'(end) = α C2'(start),  C1''(end) = α² C2''(start) + d C2'(start)

(α = 1, d = 0 for C joins). The new segment's start derivatives are linear in its control
points: s[r][j] is the coefficient of P_j in C2^(r)(start) (the r-th derivative of b_j at the
start of the domain: from the atoms, exactly when the domain starts at 0 and no frequency is a
multiple of π; from the power tables for a polynomial family). The first curve's end
derivatives are vectors: exact for an exact polynomial curve and for an exact curve of an atom
family where every atom's derivatives at the end of its domain are rational (a trigonometric
family: W·hi is a multiple of π/2 there), floats otherwise (e^hi, a power of π). P_{0..R,2} then
solve an (R+1) x (R+1) system, the given points P_{R+1..m,2} on its right-hand side.
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any

import numpy as np

from . import _derived_joins, _join_engine
from . import _validate as val
from ._validate import PointsLike
from .atom_family import AtomCurve
from .curves import FAMILIES, Curve, family_class
from .hazmat import atoms as ak

Number = Fraction | float


def involved(curve: object, family: object) -> bool:
    """Whether the first curve or the target family is a family of atoms, or one whose
    curves give their end derivatives and whose start coefficients are numeric (a family
    with its parameter in the domain: `end_derivatives`, `start_coefficients`)."""
    return (
        isinstance(curve, AtomCurve)
        or getattr(family, "atom_data", None) is not None
        or hasattr(curve, "end_derivatives")
        or hasattr(family, "start_coefficients")
    )


# family name, variables, joins table of its degree, that table valid, joins table in closed
# form in n (several parameters over a range of degrees, indexed families) or None
Side = tuple[str, dict[str, Any], Any, bool, Any]


def join_side(thing: Any, side: int, degree: int, values: Any = None) -> Side:
    """One curve of a join as the derived weights name it: a curve (side 1) or the new
    segment's family or class (side 2) with its parameter `values` (a dict by name)."""
    letter = "n" if side == 1 else "m"
    if hasattr(thing, "end_derivatives") or hasattr(thing, "start_coefficients"):
        return str(thing.family if side == 1 else thing.name), {letter: degree}, None, False, None
    if isinstance(thing, AtomCurve) or getattr(thing, "atom_data", None) is not None:
        fam = thing.family_object if isinstance(thing, AtomCurve) else thing
        data = fam.atom_data
        given = thing.atom_parameter_values() if isinstance(thing, AtomCurve) else values
        names = tuple(data.NAMES)
        got = _derived_joins.side_values(side, names, tuple(given[x] for x in names))
        return data.FAMILY, {letter: degree, **got}, data.JOINS, degree in data.DEGREES, None
    cls = thing if isinstance(thing, type) else type(thing)
    several = getattr(cls, "several_family", None)
    if several is not None:
        given = cls.parameter_values  # type: ignore[attr-defined]
        names = tuple(several.parameters)
        got = _derived_joins.side_values(side, names, tuple(given[x] for x in names))
        table = several.several.JOINS
        indexed = getattr(several, "indexed_family", None)
        closed = table if _derived_joins.is_closed(table) else None
        if indexed is not None and _derived_joins.is_closed(indexed.JOINS):
            closed = indexed.JOINS
            base = indexed.index_name
            got.update(_derived_joins.relative_values(side, base, degree, names, given))
        ok = tuple(several.degrees) == (degree,)
        return several.name, {letter: degree, **got}, table, ok, closed
    lam = thing.lam if not isinstance(thing, type) else values
    # a one-parameter family defined by data: its document's weights (surface_joins, the
    # column-wise curve joins in closed form in n, m) hold at every degree; built-ins: none
    table = getattr(cls._data, "SURFACE_JOINS", None) if hasattr(cls, "_data") else None
    closed = table if isinstance(table, dict) and "pairs" in table else None
    return str(getattr(cls, "family", "")), {letter: degree, f"lam{side}": lam}, None, True, closed


def derived_weights(
    first: Side, second: Side, continuity: str, alpha: Number, d: Number
) -> dict[tuple[int, str, int], Number] | None:
    """The join's weights from the derived document of either side's family, or None."""
    pair = f"{first[0]}>{second[0]}"
    values = {**first[1], **second[1], "alpha": alpha, "d": d}
    # an indexed family at two degrees: its per-degree tables hold each degree with itself
    two_degrees = first[0] == second[0] and first[1]["n"] != second[1]["m"]
    for table in (first[2], second[2]):
        if two_degrees or table is None or not (first[3] and second[3]):
            continue
        found = _derived_joins.lookup(table, pair, continuity, values)
        if found is not None:
            return found
    # weights in closed form in n and m, where they hold at both curves' degrees
    for owner in (first, second):
        table = owner[4]
        if table is None:
            continue
        mine = [side[1][letter] for side, letter in ((first, "n"), (second, "m"))]
        mine = [deg for deg, side in zip(mine, (first, second), strict=True) if side[0] == owner[0]]
        if all(_derived_joins.holds_at(table, continuity, deg) for deg in mine):
            found = _derived_joins.lookup(table, pair, continuity, values)
            if found is not None:
                return found
    return None


def _atom_start(
    family: Any, values: tuple[Fraction, ...], degree: int, orders: int
) -> list[list[Number]]:
    """s[r][j] = b_j^(r)(lo) of an atom family at `values` (exact where the atoms' values at
    lo are rational: lo = 0 and no frequency a multiple of π)."""
    from ._family_document import combine

    data = family.atom_data
    shape = data.SHAPES[degree]
    basis = combine(data.COEFFICIENTS[degree], values)  # (m+1, atoms)
    lo_exact = data.DOMAIN_EXACT[0]
    exact = lo_exact == 0 and not any(a.pi for a in shape.atoms)
    rows: list[list[Number]] = []
    for r in range(orders + 1):
        if exact:
            at = [_atom_at_zero(a, r) for a in shape.atoms]
            rows.append(
                [sum((c * v for c, v in zip(b, at, strict=True)), Fraction(0)) for b in basis]
            )
        else:
            lo = data.DOMAIN[0]
            at_f = [_atom_float(a, r, lo) for a in shape.atoms]
            rows.append(
                [float(sum(float(c) * v for c, v in zip(b, at_f, strict=True))) for b in basis]
            )
    return rows


def _atom_at_zero(atom: ak.Atom, r: int) -> Fraction:
    if atom.kind == "1":
        return Fraction(1 if r == 0 else 0)
    if atom.kind == "t":
        return Fraction(math.factorial(r)) if r == atom.power else Fraction(0)
    w = atom.omega**r
    cycle = {
        "cos": (1, 0, -1, 0),
        "sin": (0, 1, 0, -1),
        "cosh": (1, 0, 1, 0),
        "sinh": (0, 1, 0, 1),
    }[atom.kind]
    return Fraction(w * cycle[r % 4])


def _atom_float(atom: Any, r: int, x: float) -> float:
    if atom.kind == "1":
        return 1.0 if r == 0 else 0.0
    if atom.kind == "t":
        k = atom.power
        return 0.0 if r > k else math.factorial(k) / math.factorial(k - r) * x ** (k - r)
    w = float(atom.omega) * (math.pi if atom.pi else 1.0)
    phase = w * x
    if atom.kind in ("cos", "sin"):
        shift = r * math.pi / 2 - (math.pi / 2 if atom.kind == "sin" else 0.0)
        return w**r * math.cos(phase + shift)
    even = math.cosh(phase) if atom.kind == "cosh" else math.sinh(phase)
    odd = math.sinh(phase) if atom.kind == "cosh" else math.cosh(phase)
    return w**r * (even if r % 2 == 0 else odd)


def _atom_at_end(atom: ak.Atom, r: int, hi: Fraction, unit: str) -> Fraction | None:
    """The r-th derivative of `atom` at the domain's end hi (times pi when `unit` is "pi"),
    exactly when it is rational, else None. A trigonometric atom at an end where its phase is
    a multiple of pi/2 (the domain rule of a trigonometric family) is 0 or +-W^r, rational
    when W has no factor pi; t^k at a rational end; cosh and sinh only at 0."""
    on_pi = unit == "pi"
    if atom.kind == "1":
        return Fraction(1 if r == 0 else 0)
    if atom.kind == "t":
        k = atom.power
        if r > k or k == r:
            return Fraction(0 if r > k else math.factorial(k))
        if on_pi and hi != 0:
            return None  # a power of pi
        return Fraction(math.factorial(k), math.factorial(k - r)) * hi ** (k - r)
    if hi == 0:
        return _atom_at_zero(atom, r) if not atom.pi or r == 0 else None
    if atom.kind in ("cosh", "sinh") or atom.pi == on_pi or (atom.pi and r > 0):
        return None  # e^x, a phase that is no multiple of pi/2, or a factor pi^r
    quarters = 2 * atom.omega * hi  # the phase W hi in quarter turns
    if quarters.denominator != 1:
        return None
    cycle = {"cos": (1, 0, -1, 0), "sin": (0, 1, 0, -1)}[atom.kind]
    return Fraction(atom.omega**r * cycle[(int(quarters) + r) % 4])


def _exact_end_derivatives(curve: AtomCurve, orders: int) -> list[list[Number]] | None:
    """C^(r)(end) as Fractions, r = 0..orders, for an exact curve whose atoms' derivatives
    at the end of its domain are rational (a trigonometric family on [0, pi/2]: there
    sin and cos are 0 or +-1), else None."""
    from ._family_document import combine

    if not curve.is_exact:
        return None
    data = curve.family_object.atom_data
    _, hi, unit = data.DOMAIN_EXACT
    given = curve.atom_parameter_values()
    values = tuple(Fraction(given[x]) for x in data.NAMES)
    basis = combine(data.COEFFICIENTS[curve.degree], values)
    points: Any = curve.control_points()  # Fractions: the curve is exact
    out: list[list[Number]] = []
    for r in range(orders + 1):
        found = [_atom_at_end(a, r, hi, unit) for a in data.SHAPES[curve.degree].atoms]
        at = [v for v in found if v is not None]
        if len(at) < len(found):
            return None
        weights = [sum((c * v for c, v in zip(b, at, strict=True)), Fraction(0)) for b in basis]
        out.append(
            [
                sum((w * Fraction(p[k]) for w, p in zip(weights, points, strict=True)), Fraction(0))
                for k in range(curve.dimension)
            ]
        )
    return out


def _end_derivatives(curve: Any, orders: int) -> list[list[Number]]:
    """C1^(r)(end) as vectors, r = 0..orders: exact for an exact curve whose end derivatives
    are rational (a polynomial curve; an atom curve by _exact_end_derivatives)."""
    if isinstance(curve, AtomCurve):
        exact = _exact_end_derivatives(curve, orders)
        if exact is not None:
            return exact
        hi = curve.domain[1]
        return [[float(v) for v in curve.derivative(hi, r)] for r in range(orders + 1)]
    if hasattr(curve, "end_derivatives"):
        got: list[list[Number]] = curve.end_derivatives(orders)
        return got
    e = _join_engine.end_coefficients(curve, orders)  # coefficient of P_{n-j} in C^(r)(1)
    pts = curve.control_points()
    n = curve.degree
    out: list[list[Number]] = []
    for r in range(orders + 1):
        acc: list[Number] = [Fraction(0) if curve.is_exact else 0.0] * curve.dimension
        for j, w in enumerate(e[r]):
            if w:
                acc = [a + w * p for a, p in zip(acc, pts[n - j], strict=True)]
        out.append(acc if curve.is_exact else [float(a) for a in acc])
    return out


def join(
    curve: Any,
    continuity: str,
    order: int,
    alpha: Number,
    d: Number,
    degree: int,
    lam: object,
    rest: PointsLike,
    family: object,
    check_range: bool,
    params: object,
    named: dict[str, object],
) -> Any:
    """joins.join for the cases `involved` names (see the module docstring)."""
    if not isinstance(curve, AtomCurve | Curve) and not hasattr(curve, "end_derivatives"):
        raise ValueError(f"curve must be a lambda_bezier curve, got {type(curve).__name__}")
    target: Any = family
    if family is None:
        target = type(curve) if isinstance(curve, Curve) else curve.family_object
    degree = val.integer(degree, "degree")
    exact_inputs = not any(isinstance(x, float) for x in (alpha, d))
    # the new segment's start coefficients and its constructor
    if getattr(target, "atom_data", None) is not None:
        names = target.parameters
        if lam is not None and "lam" in names:
            named, lam = {**named, "lam": lam}, None
        values = target.parameter_values(lam, params, named)
        exact_inputs = exact_inputs and all(val.is_exact_scalar(v) for v in values.values())
        exact_values = target.exact_values(values, check_range)
        degrees = target.degrees
        if degree not in degrees:
            raise ValueError(
                f"degree {degree} is not supported for {target.name}: degrees "
                f"{degrees[0]}..{degrees[-1]}"
            )
        start = _atom_start(target, exact_values, degree, order)
        given_values = {
            k: (v if exact_inputs else float(v)) for k, v in zip(names, exact_values, strict=True)
        }
        second_side = join_side(target, 2, degree, given_values)

        def make(points: PointsLike) -> Any:
            return target.curve(points, params=values, check_range=check_range)
    elif hasattr(target, "start_coefficients"):  # numeric start derivatives (C-Bézier)
        value = target.parameter_value(lam, params, named)
        exact_inputs = False
        if degree != target.degree:
            raise ValueError(
                f"degree {degree} is not supported for {target.name}: degree {target.degree}"
            )
        start = target.start_coefficients(value, order)
        second_side = join_side(target, 2, degree)

        def make(points: PointsLike) -> Any:
            return target.curve(points, **{target.parameter: value})
    else:
        if getattr(target, "several", None) is not None:  # polynomial, several parameters
            if lam is not None and "lam" in target.parameters:
                named, lam = {**named, "lam": lam}, None
            values = target.parameter_values(lam, params, named)
            exact_inputs = exact_inputs and all(val.is_exact_scalar(v) for v in values.values())
            target = target._fixed_class(values, check_range)
            lam, params, named = None, None, {}
        if params is not None or named:
            raise TypeError("params and named parameters are for families of several parameters")
        cls: type[Curve] = (
            FAMILIES[val.choice(target, "family", tuple(FAMILIES))]
            if isinstance(target, str)
            else target
            if isinstance(target, type)
            else family_class(target)
        )
        if cls._has_lambda:
            if lam is None:
                raise ValueError(f"a {cls.family} segment needs a shape parameter lam")
            lam = val.as_lambda(lam, cls._data, check_range=check_range, name=cls.parameter_name)
        elif lam is not None:
            raise ValueError("a classical Bézier segment takes no shape parameter lam")
        degrees = tuple(cls._data.DEGREES)
        if not degrees[0] <= degree <= degrees[-1] and cls._has_lambda:
            raise ValueError(f"degree {degree} is not supported for {cls.family}")
        exact_inputs = exact_inputs and not isinstance(lam, float)
        start = _join_engine.start_coefficients(cls, degree, lam, order)
        second_side = join_side(cls, 2, degree, lam)

        def make(points: PointsLike) -> Any:
            return cls(points, lam, check_range=check_range) if cls._has_lambda else cls(points)

    if degree < order:
        raise ValueError(f"a {continuity} join needs the new curve of degree >= {order}")
    rest_any: Any = rest
    given_rows: list[Any] = (
        rest_any.tolist() if isinstance(rest_any, np.ndarray) else [list(r) for r in rest_any]
    )
    if len(given_rows) != degree - order:
        raise ValueError(
            f"rest must hold the {degree - order} control points after P_{{{order},2}} "
            f"(degree {degree}, {continuity}), got {len(given_rows)}"
        )
    given_exact = val.exact_rows(given_rows) if given_rows else ()
    ends = _end_derivatives(curve, order)
    exact = (
        exact_inputs
        and given_exact is not None
        and all(isinstance(v, Fraction) for row in ends for v in row)
        and all(isinstance(v, Fraction) for row in start for v in row)
    )
    dim = curve.dimension
    given: list[list[Number]] = (
        [list(r) for r in given_exact]  # type: ignore[union-attr]
        if exact
        else [
            [float(v) for v in r]
            for r in val.as_points(given_rows, family="rest", degrees=(0, 10**6))
        ]
        if given_rows
        else []
    )
    if given and len(given[0]) != dim:
        raise ValueError(f"rest: points of dimension {len(given[0])}, the curve has {dim}")
    derived = derived_weights(join_side(curve, 1, curve.degree), second_side, continuity, alpha, d)
    if derived is not None:  # the document's exact weights (derive/formulas/joins_several.py)
        return make(_apply(derived, curve, given_rows, given_exact, order))
    one: Number = Fraction(1) if exact else 1.0
    a_, d_ = (Fraction(alpha), Fraction(d)) if exact else (float(alpha), float(d))
    targets: list[list[Number]] = [list(ends[0])]
    if order >= 1:
        targets.append([v * one / a_ for v in ends[1]])
    if order >= 2:
        targets.append([(v - d_ * t1) / a_**2 for v, t1 in zip(ends[2], targets[1], strict=True)])
    for r in range(order + 1):
        for j in range(order + 1, degree + 1):
            if start[r][j]:
                targets[r] = [
                    t - start[r][j] * g
                    for t, g in zip(targets[r], given[j - order - 1], strict=True)
                ]
    matrix = [[start[r][c] for c in range(order + 1)] for r in range(order + 1)]
    if exact:
        solved = _solve_exact(matrix, targets, continuity)
    else:
        m = np.array(matrix, dtype=float)
        # rows scaled to 1 first: the r-th derivatives grow like h^-r on a short segment
        # (a C-Bézier curve at alpha = 1e-6), which is no singularity
        rows = np.abs(m).max(axis=1)
        if not np.all(rows > 0) or abs(np.linalg.det(m / rows[:, None])) <= 1e-12:
            raise ValueError(_singular(continuity))
        rhs = np.array(targets, dtype=float) / rows[:, None]
        solved = np.linalg.solve(m / rows[:, None], rhs).tolist()
    return make([*solved, *given])


def _singular(continuity: str) -> str:
    return (
        f"cannot solve {continuity}: the new segment's start derivatives do not determine its "
        "leading control points at these parameters (choose another degree or parameters)"
    )


def _solve_exact(
    matrix: list[list[Number]], targets: list[list[Number]], continuity: str
) -> list[list[Number]]:
    size = len(matrix)
    rows = [[*matrix[r], *targets[r]] for r in range(size)]
    for col in range(size):
        piv = next((r for r in range(col, size) if rows[r][col] != 0), None)
        if piv is None:
            raise ValueError(_singular(continuity))
        rows[col], rows[piv] = rows[piv], rows[col]
        for r in range(size):
            if r != col and rows[r][col] != 0:
                f = rows[r][col] / rows[col][col]
                rows[r] = [x - f * y for x, y in zip(rows[r], rows[col], strict=True)]
    return [[v / rows[r][r] for v in rows[r][size:]] for r in range(size)]


def _apply(
    weights: dict[tuple[int, str, int], Number],
    curve: Any,
    given_rows: list[Any],
    given_exact: Any,
    order: int,
) -> list[list[Number]]:
    """P_{0..order,2} from the weights, then the given points (exact where all of it is)."""
    exact = (
        curve.is_exact
        and given_exact is not None
        and all(isinstance(w, Fraction) for w in weights.values())
    )
    first: Any = curve.control_points() if exact else curve.points.tolist()
    given: Any = [list(r) for r in given_exact] if exact and given_rows else given_rows
    given = [[v if exact else float(v) for v in r] for r in given]
    n = curve.degree
    zero: Number = Fraction(0) if exact else 0.0
    lead = []
    for row in range(order + 1):
        acc = [zero] * curve.dimension
        for (r, src, j), w in weights.items():
            if r == row:
                p = first[n - j] if src == "first" else given[j - order - 1]
                acc = [a + (w if exact else float(w)) * v for a, v in zip(acc, p, strict=True)]
        lead.append(acc)
    return [*lead, *given]
