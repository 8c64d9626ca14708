"""Joining segments: the next curve whose leading control points make the joint C1, C2, G1
or G2 (001, Theorems 2-5; 000, Prop. 9), for any ordered pair of families.

The vertex formulas are derived in derive/joins.py from the endpoint derivatives of the
bases and read here from generated/joins.py; nothing is typed in from the papers. With the
first curve C1 of degree n (shape λ1) and the new curve C2 of degree m (shape λ2):

    C1:  C2(0) = C1(1),  C2'(0) = C1'(1)
    C2:  C1 and C2''(0) = C1''(1)
    G1:  C2(0) = C1(1),  C1'(1) = α C2'(0)                      (α > 0)
    G2:  G1 and C1''(1) = α² C2''(0) + d C2'(0)                 (d free)

G1 keeps the unit tangent; G2 also the curvature and (in 3D) the binormal direction. The
join solves P_{0,2}, P_{1,2} (and P_{2,2} for order 2); the caller gives the remaining
control points. A same_degree curve's second derivative at t = 0 involves P_{0..3}, so for a
same_degree C2/G2 target P_{2,2} is solved with P_{3,2} given: there `rest` starts at P_{3,2}
and that point enters the solve.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction
from types import ModuleType
from typing import Any, TypeVar, cast

import numpy as np

from . import _validate as val
from ._lazy import generated
from ._validate import PointsLike
from .curves import FAMILIES, Curve, _tables, elsewhere, family_class

_bernstein = generated("bernstein")
_joins = generated("joins")
_Solved = TypeVar("_Solved")  # what a generated join formula returns


def _order(continuity: str) -> int:
    """Derivatives matched at the joint (1 or 2), as emitted by derive/joins.py."""
    order: int = _joins.ORDER[continuity]
    return order


@dataclass(frozen=True)
class Joint:
    """How a joint was built: the continuity and, for G joints, α and d (001's convention
    C1'(1) = α C2'(0), C1''(1) = α² C2''(0) + d C2'(0))."""

    continuity: str
    alpha: Fraction | float = Fraction(1)
    d: Fraction | float = Fraction(0)

    def __post_init__(self) -> None:
        cont = continuity_name(self.continuity)
        alpha, d = _check_alpha_d(cont, self.alpha, self.d)
        object.__setattr__(self, "continuity", cont)
        object.__setattr__(self, "alpha", alpha)
        object.__setattr__(self, "d", d)

    @property
    def order(self) -> int:
        """How many derivatives the joint matches (1 or 2): P_{0..order,2} are solved."""
        return _order(self.continuity)


def continuity_name(name: object) -> str:
    if isinstance(name, str) and name.strip().upper() in _joins.CONTINUITIES:
        return name.strip().upper()
    raise ValueError(
        f"continuity must be one of {', '.join(map(repr, _joins.CONTINUITIES))}, got {name!r}"
    )


def _real(x: object, name: str) -> Fraction | float:
    """An exact input as a Fraction (any magnitude), anything else as a finite float."""
    return val.real_number(x, name, float_range=False)


def _check_alpha_d(cont: str, alpha: object, d: object) -> tuple[Fraction | float, ...]:
    a, dd = _real(alpha, "alpha"), _real(d, "d")
    if cont.startswith("C"):
        if a != 1 or dd != 0:
            raise ValueError(
                f"alpha and d belong to G1/G2 joins; a {cont} joint has alpha = 1 and d = 0 "
                f"(got alpha = {alpha}, d = {d})"
            )
    elif a <= 0:
        raise ValueError(
            f"alpha must be > 0 (C1'(1) = alpha C2'(0): the tangents point the same way), "
            f"got alpha = {alpha}"
        )
    elif cont == "G1" and dd != 0:
        raise ValueError(f"d only enters G2 joins (C1''(1) = α² C2''(0) + d C2'(0)), got d = {d}")
    return a, dd


def _family_class(family: object) -> type[Curve]:
    """A built-in family's name, a family from lambda_bezier.load_family, or a curve class."""
    if isinstance(family, str):
        return FAMILIES[val.choice(family, "family", tuple(FAMILIES))]
    return family_class(family)


def _closed_forms(first: type[Curve], second: type[Curve], continuity: str) -> bool:
    """Whether generated/joins.py has this join in closed form: both families built in, and
    the pair emitted (otherwise the join is solved per degree, as for families from
    load_family)."""
    return (
        all(FAMILIES.get(cls.family) is cls for cls in (first, second))
        and (first.family, second.family, continuity) in _joins.JOINS
        and second.family in _joins.PIVOTS
    )


def _end_factor(curve: Curve) -> Fraction | float:
    """The coefficient of P_n in C1'(1) (= −that of P_{n−1}), from the generated end data."""
    if not curve._has_lambda:  # the reference, BezierCurve: generated/bernstein.py
        weight: Fraction | float = _bernstein.endpoint_weight_end(curve.degree, 1, 0)
        return weight
    lam = curve.lam
    # a built-in family (leading_weights checked): its generated module has endpoint_end
    data = cast("ModuleType | generated", curve._data)
    factor: Fraction | float = data.endpoint_end(curve.degree, lam)[(1, 0)]
    return factor


def _is_zero(x: Fraction | float, scale: float = 1.0) -> bool:
    if isinstance(x, Fraction):
        return x == 0
    return abs(float(x)) <= 1e-12 * scale


def leading_weights(
    curve: Curve, joint: Joint, family: object, degree: int, lam: Fraction | float | None
) -> dict[tuple[int, str, int], Fraction | float]:
    """{(row, source, j): weight}: P_{row,2} = Σ weight · X, X = P_{n−j} of `curve` (source
    "first") or a given P_{j,2} of the new curve (source "second"). Raises ValueError where
    the join does not exist (degenerate end of `curve`, vanishing pivot for this m and λ2).

    Built-in families use the closed forms derived in derive/joins.py; a family from
    load_family (on either side) is solved per degree from the power tables."""
    cls = _family_class(family)
    if not _closed_forms(type(curve), cls, joint.continuity):
        return _generic_weights(curve, joint, cls, degree, lam)
    family = cls.family
    n, m = curve.degree, degree
    order = joint.order
    pts = curve.points
    # relative to the curve's size (it was at least 1: every tangent of a curve of size
    # 2^-600 counted as zero, and its join was refused as degenerate)
    scale = float(np.abs(pts).max()) or 1.0
    tail = np.asarray(curve.control_points()[-1], dtype=object) - np.asarray(
        curve.control_points()[-2], dtype=object
    )
    if all(_is_zero(v, scale) for v in tail):
        raise ValueError(
            f"the first curve's end is degenerate: P_{n} = P_{n - 1}, so C1'(1) = 0 and there "
            "is no tangent to continue"
        )
    factor = _end_factor(curve)
    if _is_zero(factor, n * n):
        raise ValueError(
            f"the first curve's end is degenerate: C1'(1) = {factor}·(P_{n} − P_{n - 1}) = 0 for "
            f"a {curve.family} curve of degree {n} with lam = {curve.lam}"
        )
    pivot_fn, pivot_args = _joins.PIVOTS[family]
    values = {"n": n, "m": m, "lam1": curve.lam, "lam2": lam, "alpha": joint.alpha, "d": joint.d}
    pivots: dict[str, Fraction | float] = _solve_step(pivot_fn, pivot_args, values, joint)
    for r in range(1, order + 1):
        if _is_zero(pivots[f"P{r}"], m * m):
            text = _joins.PIVOT_TEXT[family][f"P{r}"]
            lam_text = "" if lam is None else f" with lam = {lam}"
            raise ValueError(
                f"cannot solve {joint.continuity} for P_{{{r},2}}: its coefficient in "
                f"C2{chr(39) * r}(0), {text}, vanishes for a {family} curve of degree m = {m}"
                f"{lam_text} (C2{chr(39) * r}(0) does not depend on P_{{{r},2}} there); choose "
                "another degree or lam"
            )
    fn, args = _joins.JOINS[(curve.family, family, joint.continuity)]
    return _solve_step(fn, args, values, joint)


def _generic_weights(
    curve: Curve, joint: Joint, cls: type[Curve], degree: int, lam: Fraction | float | None
) -> dict[tuple[int, str, int], Fraction | float]:
    from . import _join_engine  # only families from load_family need the per-degree solve

    e1 = _join_engine.end_coefficients(curve, 1)[1]  # weights of P_{n-j} in C1'(1)
    pts = curve.control_points()
    tangent = [
        sum(e1[j] * pts[curve.degree - j][c] for j in range(len(e1)))
        for c in range(curve.dimension)
    ]
    scale = float(np.abs(curve.points).max()) or 1.0  # relative to the size, as above
    if all(_is_zero(v, scale * curve.degree**2) for v in tangent):
        raise ValueError(
            f"the first curve's end is degenerate: C1'(1) = 0 for this {curve.family} curve "
            f"of degree {curve.degree} with lam = {curve.lam}, so there is no tangent to continue"
        )
    from . import _atom_joins, _derived_joins  # a family's document may hold the weights

    first = _atom_joins.join_side(curve, 1, curve.degree)
    second = _atom_joins.join_side(cls, 2, degree, lam)
    try:
        derived = _atom_joins.derived_weights(first, second, joint.continuity, joint.alpha, joint.d)
    except _derived_joins.SingularWeight:  # the closed form's pole: the solve decides, naming
        derived = None  # the point it cannot determine where the join does not exist
    if derived is not None:
        return derived
    try:
        return _join_engine.weights(
            curve, joint.order, joint.alpha, joint.d, cls, degree, lam, joint.continuity
        )
    except (ZeroDivisionError, OverflowError):
        raise ValueError(_too_extreme(joint)) from None


def _solve_step(
    fn: Callable[..., _Solved],
    args: Sequence[str],
    values: Mapping[str, object],
    joint: Joint,
) -> _Solved:
    """fn(*args) from generated/joins.py; in floating point an extreme α or d (the formulas
    divide by α and α²) overflows or divides by an underflowed zero: named here."""
    try:
        return fn(*(values[a] for a in args))
    except (ZeroDivisionError, OverflowError):
        raise ValueError(_too_extreme(joint)) from None


def _too_extreme(joint: Joint) -> str:
    return (
        f"alpha = {val.describe(joint.alpha)}, d = {val.describe(joint.d)} are too extreme for "
        "floating point: the solved points grow like 1/alpha and 1/alpha² (and d/alpha²) and "
        "overflow the float range, or alpha² underflows to zero; use moderate values, or exact "
        "ints/Fractions for every input"
    )


def _own_parameter(
    cls: type[Curve], lam: object, params: object, named: Mapping[str, object]
) -> Any:
    """The new segment's parameter given as `lam`, in `params` or by its own name."""
    name = cls.parameter_name
    given: list[tuple[str, object]] = [] if lam is None else [("lam", lam)]
    if params is not None:
        if not isinstance(params, dict):
            raise TypeError(f"params must be a dict {{name: value}}, not {type(params).__name__}")
        given += [(f"params[{k!r}]", v) for k, v in params.items() if k == name]
        wrong = [k for k in params if k != name]
        if wrong:
            raise TypeError(
                f"params: {wrong[0]!r} is not a parameter of the {cls.family} family "
                f"(its parameter: {name})"
            )
    for key, v in named.items():
        if key != name:
            raise TypeError(
                f"join() got an unexpected keyword argument {key!r} (the {cls.family} "
                f"family's parameter is {name})"
            )
        given.append((f"{key}=", v))
    if len(given) > 1:
        raise TypeError(
            f"the parameter {name} is given twice ({given[0][0]} and {given[1][0]}); give it once"
        )
    return given[0][1] if given else None


def _indexed_target(
    curve: Curve,
    family: object,
    degree: int,
    lam: Fraction | float | None,
    params: dict[str, Fraction | float] | None,
    named: dict[str, Fraction | float],
) -> tuple[object, Any, Any, dict[str, Any]]:
    """(family, lam, params, named) for the rest of join. A family with one parameter per
    index (IndexedFamily, ``lam(i)``) is one Family per degree: the new segment's is the one
    of `degree`, its values one sequence (``lam=[...]``, ``params={"lam": [...]}`` or the
    family's own name) spread over that degree's lam_a..lam_b. Other families pass through."""
    from .family import IndexedFamily

    indexed = family
    if family is None:  # continuing a curve of an indexed family: the family, not its degree
        indexed = getattr(getattr(type(curve), "several_family", None), "indexed_family", None)
    if not isinstance(indexed, IndexedFamily):
        return family, lam, params, named
    name, fam_name = indexed.index_name, indexed.name
    own = f"its parameter: {name}, one value per index"
    supplied: list[tuple[str, Any]] = [*(params or {}).items(), *named.items()]
    if lam is not None:
        if name != "lam":
            raise TypeError(f"lam is not a parameter of {fam_name!r} ({own})")
        supplied.append(("lam", lam))
    given: dict[str, Any] = {}
    for key, v in supplied:
        if key in given:
            raise TypeError(f"{key} is given twice; give it once")
        given[key] = v
    unknown = sorted(set(given) - {name})
    if unknown:
        raise TypeError(f"{unknown[0]!r} is not a parameter of {fam_name!r} ({own})")
    degree = val.integer(degree, "degree")
    if degree not in indexed.degrees:
        raise ValueError(
            f"degree {degree} is not supported for {fam_name}: degrees "
            f"{', '.join(map(str, indexed.degrees))} (one family per degree, {name}(i) per index)"
        )
    if name not in given:
        raise ValueError(
            f"a {fam_name} segment of degree {degree} needs its shape parameters "
            f"{name}=[...], one per index ({', '.join(indexed.at_degree(degree).parameters)})"
        )
    values = indexed.index_values(degree, given[name])
    return indexed.at_degree(degree), None, values, {}


def join(
    curve: Curve,
    continuity: str,
    degree: int,
    lam: Fraction | float | None = None,
    alpha: Fraction | float = 1,
    d: Fraction | float = 0,
    rest: PointsLike = (),
    family: object = None,
    *,
    check_range: bool = True,
    params: dict[str, Fraction | float] | None = None,
    **named: Fraction | float,
) -> Curve:
    r"""The next segment after `curve`: a curve of `family` (default: `curve`'s own) and
    `degree` whose leading control points make the joint `continuity` ("C1", "C2", "G1",
    "G2"), followed by the control points `rest`.

    P_{0,2} and P_{1,2} are solved (and P_{2,2} for C2/G2); `rest` holds the others:
    P_{2..m} for C1/G1, P_{3..m} for C2/G2. For a same_degree C2/G2 target the first point of
    `rest`, P_{3,2}, enters the solve of P_{2,2} (a same_degree second derivative at an end
    involves four control points). G joins use 001's convention C1'(1) = α C2'(0),
    C1''(1) = α² C2''(0) + d C2'(0) with α > 0 and d free; C joins have α = 1, d = 0.
    Exact inputs (ints/Fractions for the points, λs, α, d and `rest`) give exact points.

    Parameters
    ----------
    curve : Curve
        The segment to continue (any family).
    continuity : str
        ``"C1"``, ``"C2"``, ``"G1"`` or ``"G2"``.
    degree : int
        The new segment's degree m.
    lam : number, optional
        The new segment's λ (required unless its family is ``"bezier"``).
    alpha, d : number
        The G-joint constants α > 0 and d (:math:`C_1'(1) = \alpha C_2'(0)`,
        :math:`C_1''(1) = \alpha^2 C_2''(0) + d \, C_2'(0)`); C joints take 1 and 0.
    rest : array_like
        The control points after the solved ones.
    family : str or Family, optional
        The new segment's family; default that of `curve`. A family with one parameter per
        index (``lam(i)``, an IndexedFamily) takes its values as one sequence, one per index
        of `degree`: ``lam=[...]`` or ``params={"lam": [...]}``.
    check_range : bool
        Refuse a λ outside the new family's range.
    params, **named : optional
        The new segment's shape parameter by its family's own name (``mu=...`` or
        ``params={"mu": ...}`` for a family defined with ``parameter = "mu"``), instead of
        `lam`.

    Returns
    -------
    Curve
        The new segment, of the class of `family`.

    Examples
    --------
    >>> from lambda_bezier import BernsteinLikeCurve, join
    >>> c = BernsteinLikeCurve([(0, 0), (1, 2), (3, 2), (4, 0)], lam=1)
    >>> nxt = join(c, "C2", 3, lam=0, rest=[(9, 1)])
    >>> [tuple(map(str, p)) for p in nxt.control_points()[:3]]
    [('4', '0'), ('17/3', '-10/3'), ('8', '-40/3')]
    """
    from . import _atom_joins

    if _atom_joins.involved(curve, family):  # a trigonometric, hyperbolic or mixed family
        spec = Joint(continuity, alpha, d)
        # into an indexed family (lam(i)): its Family of `degree`, the values spread by index
        family, lam, params, named = _indexed_target(curve, family, degree, lam, params, named)
        return _atom_joins.join(  # type: ignore[no-any-return]
            curve,
            spec.continuity,
            spec.order,
            spec.alpha,
            spec.d,
            degree,
            lam,
            rest,
            family,
            val.flag(check_range, "check_range"),
            params,
            dict(named),
        )
    if not isinstance(curve, Curve):
        told = elsewhere(curve)
        if told is not None:
            raise TypeError(f"curve: {told}")
        raise ValueError(
            "curve must be a lambda_bezier curve (one of "
            f"{', '.join(cls.__name__ for cls in FAMILIES.values())}, or a curve of a family "
            f"from lambda_bezier.load_family), got {type(curve).__name__}"
        )
    spec = Joint(continuity, alpha, d)
    family, lam, params, named = _indexed_target(curve, family, degree, lam, params, named)
    # a family in several parameters: the new segment's class is the family at its values
    target = family if family is not None else getattr(type(curve), "several_family", None)
    cls: type[Curve]
    if getattr(target, "several", None) is not None:
        if lam is not None and "lam" in target.parameters:  # type: ignore[union-attr]
            named, lam = {**named, "lam": lam}, None  # join's own `lam` is this parameter
        values = target.parameter_values(lam, params, named)  # type: ignore[union-attr]
        cls = target._fixed_class(values, check_range)  # type: ignore[union-attr]
        lam, params, named = None, None, {}
    else:
        cls = type(curve) if family is None else _family_class(family)
    fam = cls.family
    data = cls._data
    degrees = tuple(data.DEGREES)
    degree = val.integer(degree, "degree")
    if not degrees[0] <= degree <= degrees[-1]:
        raise ValueError(
            f"degree {degree} is not supported for {fam}: degrees {degrees[0]}..{degrees[-1]}"
        )
    if degree < spec.order:
        raise ValueError(
            f"a {spec.continuity} join solves P_{{0,2}}..P_{{{spec.order},2}}: the new curve "
            f"needs degree >= {spec.order}, got {degree}"
        )
    if cls._has_lambda:
        lam = _own_parameter(cls, lam, params, named)
    name = cls.parameter_name
    if cls._has_lambda:
        if lam is None:
            raise ValueError(f"a {fam} segment needs a shape parameter {name}")
        lam = val.as_lambda(lam, data, check_range=check_range, name=name)
    elif lam is not None:
        raise ValueError("a classical Bézier segment takes no shape parameter lam")
    rest_rows = _rest(rest, curve, spec, cls, degree)
    weights = leading_weights(curve, spec, cls, degree, lam)
    exact = (
        curve.is_exact
        and not isinstance(lam, float)
        and not isinstance(spec.alpha, float)
        and not isinstance(spec.d, float)
        and rest_rows[1] is not None
    )
    if exact:
        first = curve._exact_points  # what control_points() gives for an exact curve
        given = rest_rows[1]
        assert first is not None and given is not None  # exact: checked above
        lead = []
        for row in range(spec.order + 1):
            acc: list[Fraction | float] = [Fraction(0)] * curve.dimension
            for (r, src, j), w in weights.items():
                if r != row or w == 0:
                    continue
                p = first[curve.degree - j] if src == "first" else given[j - spec.order - 1]
                acc = [a + w * v for a, v in zip(acc, p, strict=True)]
            lead.append(tuple(acc))
        points: PointsLike = [*lead, *given]
    else:
        first_f = curve.points
        given_f = rest_rows[0]
        lead_f = np.zeros((spec.order + 1, curve.dimension))
        for (r, src, j), w in weights.items():
            if r > spec.order or w == 0:
                continue
            p = first_f[curve.degree - j] if src == "first" else given_f[j - spec.order - 1]
            try:
                lead_f[r] += float(w) * p
            except OverflowError:  # an exact weight beyond the float range
                lead_f[r] = np.inf
        if not np.isfinite(lead_f).all():
            raise ValueError(_too_extreme(spec))
        points = np.vstack([lead_f, given_f])
    if cls._has_lambda:
        return cls(points, lam, check_range=check_range)
    return cls(points)


def _entering_given_points(cls: type[Curve], degree: int, order: int) -> str:
    """Which given points P_{j,2} (j > order) enter the solve, and of which solved points: a
    given point enters where the start derivatives p^(r)(0), r <= order, involve it (at some
    λ), read off the power tables (the t^r coefficient of basis function j). "" for none."""
    mats = _tables(cls._data, "power")[degree]
    lowest: dict[int, int] = {}
    for j in range(order + 1, degree + 1):
        rows = [r for r in range(order + 1) if any(m[j][r] != 0 for m in mats)]
        if rows:
            lowest[j] = rows[0]
    if not lowest:
        return ""
    given = ", ".join(f"P_{{{j},2}}" for j in lowest)
    first = min(lowest.values())
    solved = f"P_{{{first},2}}" if first == order else f"P_{{{first},2}}..P_{{{order},2}}"
    verb = "enters" if len(lowest) == 1 else "enter"
    return f"; {given} {verb} the solve of {solved}"


def _rest(
    rest: PointsLike, curve: Curve, spec: Joint, cls: type[Curve], degree: int
) -> tuple[np.ndarray, val.ExactRows | None]:
    """(float array (k, d), exact rows or None) for the caller's remaining control points."""
    family = cls.family
    want = degree - spec.order
    first_index = spec.order + 1
    which = (
        "no further points"
        if want == 0
        else f"P_{{{first_index},2}}..P_{{{degree},2}}"
        if want > 1
        else f"P_{{{degree},2}}"
    )
    arr = np.array(val.real_array(rest, "rest"), dtype=float)
    if arr.size == 0:
        arr = arr.reshape(0, curve.dimension)
    if arr.ndim != 2:
        raise ValueError(f"rest must be a (k, d) array of points, got shape {arr.shape}")
    if arr.shape[1] != curve.dimension:
        raise ValueError(
            f"rest has points of dimension {arr.shape[1]} but the first curve has dimension "
            f"{curve.dimension}"
        )
    if arr.shape[0] != want:
        note = _entering_given_points(cls, degree, spec.order)
        raise ValueError(
            f"a {spec.continuity} join into a {family} curve of degree {degree} solves "
            f"P_{{0,2}}..P_{{{spec.order},2}}; rest must hold the other {want} point(s) "
            f"({which}{note}), got {arr.shape[0]}"
        )
    if not np.isfinite(arr).all():
        raise ValueError("rest contains NaN or infinity")
    exact = () if want == 0 else val.exact_rows(rest)
    return arr, exact
