"""Energy-optimal parameters of families with several parameters, over their box.

What `lambda_bezier.optimal_parameters` answers for a family that is not one of the
one-parameter kind: a family affine in its parameters jointly (E_k a quadratic in them: the
exact minimum over the closed box, face by face), a trigonometric, hyperbolic or mixed
family (the same, with entries in ℚ(π) or ℚ(e^W)), an indexed family (lam(i): the
parameters of the points' degree as one tuple), and a family not affine in its parameters
(the certified minimum of _optimal_box). The order k is checked by the caller (energy.py).
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import numpy as np

from . import _validate as val
from ._validate import PointsLike


@dataclass(frozen=True)
class OptimalParameters:
    """The parameters minimising E_k over the family's parameter box, by name, as returned
    by `optimal_parameters`: ``result["mu"]`` for a family whose parameter is ``mu``.

    Attributes
    ----------
    values : dict
        {parameter name: value}, every parameter of the family.
    energy : Fraction or float
        E_k there.
    free : dict
        The minimiser over all real parameters (the free optimum).
    free_inside : bool
        Whether the free optimum lies in the parameter box (then `values` is it).
    boundary : str
        Empty when the free optimum is the answer; otherwise where on the box's boundary the
        minimum lies, e.g. ``"mu = 1 (upper end)"``.
    k : int
        The energy order.
    family : str
        The family name.
    lower_bound : Fraction or float or None
        For a family not affine in its parameters: a proven lower bound of E_k over the box,
        within 1e-12 (relative) of `energy`, which is E_k at `values` exactly; None otherwise.
    method : str
        ``"exact"`` (the free optimum, or a face's, solved exactly), or ``"certified"``: a
        branch and bound proved `lower_bound`. For a family whose parameter is the length of
        the domain (C-Bézier), `energy` is then E_k at `values` to about 2^-200, not exact.
    """

    values: dict[str, Fraction | float]
    energy: Fraction | float
    free: dict[str, Fraction | float]
    free_inside: bool
    boundary: str
    k: int
    family: str
    # a proven lower bound of E_k over the box when the minimum was found by certified branch
    # and bound (a basis not affine in the parameters); None when it is exact
    lower_bound: Fraction | float | None = None
    method: str = "exact"

    def __getitem__(self, name: str) -> Fraction | float:
        if name not in self.values:
            raise KeyError(
                f"{name!r} is not a parameter of {self.family!r} "
                f"(its parameters: {', '.join(self.values)})"
            )
        return self.values[name]


def _own_optimum(got: dict[str, Any], k: int, family: Any) -> OptimalParameters:
    """OptimalParameters from a family's own certified minimum over its range (a family
    whose parameter is the length of the domain: CBezierFamily.energy_minimum)."""
    return OptimalParameters(
        values=dict(got["values"]),
        energy=got["energy"],
        free={},
        free_inside=False,
        boundary=got["boundary"],
        k=k,
        family=str(family.name),
        lower_bound=got["lower_bound"],
        method=got["method"],
    )


def _solve(a: list[list[Fraction]], b: list[Fraction]) -> list[Fraction] | None:
    """a x = b by exact elimination; None when a is singular."""
    size = len(b)
    m = [[*row, rhs] for row, rhs in zip(a, b, strict=True)]
    for col in range(size):
        piv = next((r for r in range(col, size) if m[r][col] != 0), None)
        if piv is None:
            return None
        m[col], m[piv] = m[piv], m[col]
        for r in range(size):
            if r != col and m[r][col] != 0:
                f = m[r][col] / m[col][col]
                m[r] = [x - f * y for x, y in zip(m[r], m[col], strict=True)]
    return [m[r][size] / m[r][r] for r in range(size)]


def _exact_polygon(points: PointsLike, data: Any) -> tuple[list[tuple[Fraction, ...]], bool]:
    """The control points as exact rows (floats at their exact binary values), checked
    against the family's degrees and for one width, and whether they were given exactly."""
    given = val.exact_rows(points)
    if given is None:
        arr = np.asarray(val.as_points(points, family=data.FAMILY, degrees=data.DEGREES))
        return [tuple(Fraction(float(v)) for v in row) for row in arr], False
    val.exact_shape(given, family=data.FAMILY, degrees=data.DEGREES)
    return [tuple(Fraction(v) for v in row) for row in given], True


def _optimal_several(points: PointsLike, k: int, family: Any, several: Any) -> OptimalParameters:
    """E_k = w^T S w with w = (1, x_1..x_J) for a family affine in its parameters jointly
    (S from the derived Gram matrices, exact); its minimum over the closed box is the least
    of the free minima on the box's faces (each a linear system) that lie in the face:
    every face is tried, 3^J of them."""
    names = several.NAMES
    if several.ENERGY_REASON is not None and not several.MONOMIAL_GRAM:
        raise ValueError(f"optimal_parameters: {several.ENERGY_REASON}")
    rows, exact = _exact_polygon(points, several)
    n = len(rows) - 1
    if (n, k) not in several.GRAM and (n, k) not in several.MONOMIAL_GRAM:
        raise ValueError(
            f"points: {n + 1} control points: no derived E_{k} of {several.FAMILY} for degree "
            f"{n} (degrees {several.DEGREES[0]}..{several.DEGREES[-1]}; k = 1, 2, 3)"
        )
    if several.ENERGY_REASON is not None:  # not affine: E_k a polynomial, certified minimum
        return _certified_several(rows, n, k, several, exact)
    size = len(names) + 1
    s_mat = [[Fraction(0)] * size for _ in range(size)]
    for (a, b), gram in several.GRAM[(n, k)].items():
        total = Fraction(0)
        for dim in range(len(rows[0])):
            for i, row in enumerate(gram):
                pi = rows[i][dim]
                if pi == 0:
                    continue
                total += pi * sum((g * rows[j][dim] for j, g in enumerate(row)), Fraction(0))
        s_mat[a][b] = s_mat[b][a] = total

    return _box_minimum(s_mat, names, several.RANGES, exact, k, several.FAMILY)


def _optimal_atoms(points: PointsLike, k: int, data: Any) -> OptimalParameters:
    """optimal_parameters for a trigonometric, hyperbolic or mixed family (atom_family):
    E_k = Σ over monomial pairs params^(m1+m2) P^T G P with entries in ℚ[π] or ℚ[e^W], a
    quadratic in the parameters when each monomial has degree <= 1 (the family is affine in
    them): then the box minimum is exact, in ℚ(π) (ConstantFraction) for exact points."""
    form = atom_energy_form(points, k, data)
    if isinstance(form, OptimalParameters):
        return form
    s_mat, exact = form
    return _box_minimum(s_mat, data.NAMES, data.RANGES, exact, k, data.FAMILY)


def atom_energy_form(
    points: PointsLike, k: int, data: Any
) -> tuple[list[list[Any]], bool] | OptimalParameters:
    """(S, exact): E_k = w^T S w, w = (1, x_1..x_J), of one polygon of an atom family affine
    in its parameters (entries in ℚ[π] or ℚ[e^W]); for a family not affine in them, the
    certified box minimum instead (E_k is then no quadratic)."""
    names = data.NAMES
    if data.ENERGY_REASON is not None and not data.GRAM:
        raise ValueError(f"optimal_parameters: {data.ENERGY_REASON}")
    rows, exact = _exact_polygon(points, data)
    n = len(rows) - 1
    if (n, k) not in data.GRAM:
        raise ValueError(
            f"points: {n + 1} control points: no derived E_{k} of {data.FAMILY} for degree {n}"
        )
    size = len(names) + 1
    if any(sum(m) > 1 for pair in data.GRAM[(n, k)] for m in pair):
        # not affine in the parameters: E_k is no quadratic, its minimum is certified
        return _certified_several(rows, n, k, data, exact, atoms=True)

    def index(mono: tuple[int, ...]) -> int:
        return 0 if sum(mono) == 0 else 1 + mono.index(1)

    s_mat: list[list[Any]] = [[Fraction(0)] * size for _ in range(size)]
    for (m1, m2), gram in data.GRAM[(n, k)].items():
        a, b = index(m1), index(m2)
        total: Any = Fraction(0)
        for dim in range(len(rows[0])):
            for i, row in enumerate(gram):
                pi = rows[i][dim]
                if pi == 0:
                    continue
                for j, g in enumerate(row):
                    if rows[j][dim] and g:
                        total = total + pi * rows[j][dim] * g
        # E = Σ_(a,b) w_a w_b S[a][b] over ordered pairs: S symmetric, the cross term halved
        s_mat[a][b] = s_mat[a][b] + total / 2
        s_mat[b][a] = s_mat[b][a] + total / 2
    return s_mat, exact


def _box_minimum(
    s_mat: list[list[Any]],
    names: tuple[str, ...],
    ranges: dict[str, tuple[Any, ...]],
    exact: bool,
    k: int,
    family: str,
) -> OptimalParameters:
    """The minimum of w^T S w, w = (1, x_1..x_J), over the closed box of `ranges` (the
    least of the free minima of the box's faces that lie in their face). The entries of S
    may be Fractions or exact numbers of a field containing them (hazmat.constants'
    ConstantFraction: energies in ℚ(π)); comparisons are exact either way."""
    import itertools

    size = len(names) + 1

    def energy_at(x: list[Any]) -> Any:
        w = [Fraction(1), *x]
        return sum(
            (w[a] * w[b] * s_mat[a][b] for a in range(size) for b in range(size)), Fraction(0)
        )

    def face_minimum(state: tuple[int, ...]) -> list[Any] | None:
        # state[j]: 0 free, 1 at lo, 2 at hi
        x: list[Any] = [
            None if st == 0 else ranges[name][st - 1] for name, st in zip(names, state, strict=True)
        ]
        free = [j for j, v in enumerate(x) if v is None]
        a = [[s_mat[1 + r][1 + c] for c in free] for r in free]
        b = [
            -(
                s_mat[0][1 + r]
                + sum(
                    (s_mat[1 + r][1 + j] * v for j, v in enumerate(x) if v is not None), Fraction(0)
                )
            )
            for r in free
        ]
        sol = _solve(a, b) if free else []
        if sol is None:
            return None
        for j, v in zip(free, sol, strict=True):
            x[j] = v
        return [v for v in x if v is not None]

    free_opt = face_minimum((0,) * len(names))
    best: tuple[Any, list[Any], tuple[int, ...]] | None = None
    for state in itertools.product((0, 1, 2), repeat=len(names)):
        x = face_minimum(state)
        if x is None:
            continue
        if not all(
            ranges[name][0] <= v <= ranges[name][1] for name, v in zip(names, x, strict=True)
        ):
            continue
        e = energy_at(x)
        if best is None or e < best[0]:
            best = (e, x, state)
    if best is None:  # pragma: no cover - every vertex of the box is a face of dimension 0
        raise AssertionError("no face of the box has a minimum")
    energy, x, state = best
    inside = free_opt is not None and all(
        ranges[name][0] <= v <= ranges[name][1] for name, v in zip(names, free_opt, strict=True)
    )
    boundary = []
    for name, v, st in zip(names, x, state, strict=True):
        lo, hi, lo_closed, hi_closed, _ = ranges[name]
        if st == 0 and lo < v < hi:
            continue
        end = "lower" if v == lo else "upper"
        closed = lo_closed if v == lo else hi_closed
        if st != 0 or v in (lo, hi):
            boundary.append(
                f"{name} = {v} ({end} end{'' if closed else ', excluded: not attained'})"
            )
    out: Any = _exact_value if exact else float
    return OptimalParameters(
        values={name: out(v) for name, v in zip(names, x, strict=True)},
        energy=out(energy),
        free={}
        if free_opt is None
        else {name: out(v) for name, v in zip(names, free_opt, strict=True)},
        free_inside=inside,
        boundary="" if inside else "; ".join(boundary),
        k=k,
        family=family,
    )


def _certified_several(
    rows: list[tuple[Fraction, ...]], n: int, k: int, several: Any, exact: bool, atoms: bool = False
) -> OptimalParameters:
    """The certified minimum of E_k over the box of a family not affine in its parameters
    (_optimal_box; `atoms`: a trigonometric, hyperbolic or mixed family, energies in ℚ(π) or
    ℚ(e^W)). No free optimum is computed: `free` is empty and `free_inside` False."""
    from ._optimal_box import certified_atom_minimum, certified_minimum

    got = (certified_atom_minimum if atoms else certified_minimum)(rows, n, k, several)
    if not got["certified"]:  # pragma: no cover - the budget is far above the test families'
        raise ValueError(
            f"optimal_parameters: the minimum of E_{k} over the box was not certified within "
            f"the budget (best {float(got['value'])}, proven lower bound {float(got['lower'])})"
        )
    out: Any = _exact_value if exact else float
    where = []
    for name, v in zip(several.NAMES, got["point"], strict=True):
        lo, hi, lo_closed, hi_closed, _ = several.RANGES[name]
        if v in (lo, hi):
            closed = lo_closed if v == lo else hi_closed
            end = "lower" if v == lo else "upper"
            where.append(f"{name} = {v} ({end} end{'' if closed else ', excluded: not attained'})")
    return OptimalParameters(
        values={name: out(v) for name, v in zip(several.NAMES, got["point"], strict=True)},
        energy=out(got["value"]),
        free={},
        free_inside=False,
        boundary="; ".join(where),
        k=k,
        family=several.FAMILY,
        lower_bound=out(got["lower"]),
        method="certified",
    )


def _optimal_indexed(points: PointsLike, k: int, family: Any) -> OptimalParameters:
    """The several-parameter optimum of the degree the points give, with the parameters
    lam_a .. lam_b of that degree returned as one tuple under the family's own name."""
    rows = val.as_points(points, family=family.name, degrees=family.degrees)
    fam = family.at_degree(len(rows) - 1)
    r = _optimal_several(points, k, fam, fam.several)
    name = family.index_name
    free: dict[str, Any] = {name: tuple(r.free.values())} if r.free else {}
    return OptimalParameters(
        values={name: tuple(r.values.values())},  # type: ignore[dict-item]
        energy=r.energy,
        free=free,
        free_inside=r.free_inside,
        boundary=r.boundary,
        k=r.k,
        family=r.family,
    )


def _exact_value(v: Any) -> Any:
    """A Fraction, or an exact number of ℚ(π) that is rational, as the Fraction it is."""
    if getattr(v, "is_rational", False):
        return v.numerator[0] if v.numerator else Fraction(0)
    return v
