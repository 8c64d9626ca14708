"""Energy-optimal shape parameter (000, section 3), exact or vectorised over many polygons.

E_k(λ) = ∫_0^1 |p^(k)(t)|² dt is a convex quadratic in λ whose coefficients are quadratic
forms in the control points; the forms are derived in derive/energy.py and read here from
generated/energy.py.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from functools import cache
from typing import TYPE_CHECKING, Any, TypeVar

import numpy as np

if TYPE_CHECKING:
    from ._lazy import TableSource

from . import _validate as val
from ._lazy import generated
from ._validate import PointsLike
from .curves import FAMILIES, Curve, family_class

_energy = generated("energy")

ENERGY_NAMES = {1: "stretch", 2: "strain", 3: "jerk"}
# the built-in families with a shape parameter (all but the reference, BezierCurve)
LAMBDA_FAMILIES = tuple(name for name, cls in FAMILIES.items() if cls._has_lambda)

# one quadratic form: (scale s, upper-triangular integer matrix U); E_k's three are ff, fg, gg
_V = TypeVar("_V", np.ndarray, float)  # one value or an array of them, kept as given
UpperInts = tuple[tuple[int, ...], ...]
Form = tuple[Fraction | int, UpperInts]
# (a0, a1, a2) of E_k(λ) = a0 + a1 λ + a2 λ²: exact, float, or arrays over a batch
Coefficients = (
    tuple[Fraction, Fraction, Fraction]
    | tuple[float, float, float]
    | tuple[np.ndarray, np.ndarray, np.ndarray]
)


@dataclass(frozen=True)
class OptimalLambda:
    """The λ minimising E_k for one polygon (scalars) or a batch (arrays of length m),
    as returned by `optimal_lambda`.

    Attributes
    ----------
    lam : Fraction, float or numpy.ndarray
        The answer: the unconstrained minimiser, or with clamp=True the minimiser over the
        closed range (exact since E_k is a convex quadratic in λ).
    unconstrained : Fraction, float or numpy.ndarray
        The minimiser over all real λ.
    admissible : bool or numpy.ndarray
        Whether `lam` lies in the family's range (False for an unconstrained optimum outside
        it, and for a clamped one that sits on an excluded end such as λ = −2).
    unconstrained_admissible : bool or numpy.ndarray
        Whether `unconstrained` lies in the family's range.
    energy, unconstrained_energy : Fraction, float or numpy.ndarray
        E_k at `lam` and at `unconstrained`.
    k : int
        The energy order.
    family : str
        The family name.
    range_text : str
        The family's λ-range as text, e.g. ``"(-2, 1]"``.
    clamped : bool
        Whether the answer was clamped to the range (``clamp=True``).
    """

    lam: Fraction | float | np.ndarray
    unconstrained: Fraction | float | np.ndarray
    admissible: bool | np.ndarray
    unconstrained_admissible: bool | np.ndarray
    energy: Fraction | float | np.ndarray
    unconstrained_energy: Fraction | float | np.ndarray
    k: int
    family: str
    range_text: str
    clamped: bool


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
    """

    values: dict[str, Fraction | float]
    energy: Fraction | float
    free: dict[str, Fraction | float]
    free_inside: bool
    boundary: str
    k: int
    family: str

    def __getitem__(self, name: str) -> Fraction | float:
        if name not in self.values:
            raise KeyError(
                f"{name!r} is not a parameter of {self.family!r} "
                f"(its parameters: {', '.join(self.values)})"
            )
        return self.values[name]


def _family_cls(family: object) -> type[Curve]:
    """A family with a shape parameter: a built-in name, or a family from load_family."""
    if isinstance(family, str):
        return FAMILIES[val.choice(family, "family", LAMBDA_FAMILIES)]
    cls = family_class(family)
    if not cls._has_lambda:
        raise ValueError(f"the {cls.family} family has no shape parameter to optimise")
    return cls


def _family_data(family: object) -> TableSource:
    return _family_cls(family)._data


def _name(family: object) -> str:
    return family if isinstance(family, str) else _family_cls(family).family


def _energy_table(family: object) -> dict[tuple[int, int], tuple[Form, ...]]:
    """{(n, k): ((s_ff, U_ff), (s_fg, X), (s_gg, Y))} of the family (generated, or derived)."""
    if isinstance(family, str):
        table: dict[tuple[int, int], tuple[Form, ...]] = _energy.ENERGY[family]
        return table
    data = _family_data(family)
    if not data.ENERGY:
        raise ValueError(f"no energy forms for the {data.FAMILY} family: {data.ENERGY_REASON}")
    forms: dict[tuple[int, int], tuple[Form, ...]] = data.ENERGY
    return forms


def _check_order(k: object) -> int:
    if (
        isinstance(k, bool | np.bool_)
        or not isinstance(k, int | np.integer)
        or k not in _energy.ORDERS
    ):
        raise ValueError(
            f"energy order k must be 1, 2 or 3 (stretch, strain, jerk), got {val.describe(k)}"
        )
    return int(k)


def energy_matrices(
    n: int, k: int, family: object = "same_degree"
) -> tuple[Fraction, UpperInts, UpperInts]:
    r"""The matrices of the optimal λ in the paper's normalisation (000, eq. 20).

    .. math:: \lambda^\ast = c \, \frac{D^\mathsf{T} X D}{D^\mathsf{T} Y D},
              \qquad D = (P_0, \dots, P_n)^\mathsf{T},

    a product :math:`D^\mathsf{T} U D = \sum_{i \le j} U_{ij} \, P_i \cdot P_j`
    summing over the coordinates.

    Parameters
    ----------
    n : int
        The degree (n + 1 control points), within the family's range.
    k : int
        The energy order: 1 stretch, 2 strain, 3 jerk.
    family : str or Family
        ``"same_degree"``, ``"bernstein_like"``, or a family from `load_family`.

    Returns
    -------
    tuple
        ``(c, X, Y)``: the scale c as a Fraction, and :math:`X_n^k`, :math:`Y_n^k` as
        upper-triangular tuples of tuples of ints.

    Raises
    ------
    ValueError
        For a degree outside the family's range, or when E_k does not depend on λ at that
        degree (:math:`Y_n^k = 0`), and for bad input.

    Examples
    --------
    >>> scale, X, Y = energy_matrices(3, 1)
    >>> scale, X[0], Y[0]
    (Fraction(-1, 2), (5, -13, -7, 10), (2, -4, -1, 1))
    """
    data = _family_data(family)
    k = _check_order(k)
    n = val.integer(n, "degree n")
    if (n, k) not in _energy_table(family):
        raise ValueError(
            f"degree {n} is not supported for {_name(family)}: "
            f"degrees {data.DEGREES[0]}..{data.DEGREES[-1]}"
        )
    _, (s_fg, x), (s_gg, y) = _energy_table(family)[(n, k)]
    if s_gg == 0:  # Y_n^k = 0 (e.g. E_3 of a quadratic basis, which vanishes identically)
        raise ValueError(
            f"λ has no effect on E_{k} for {_name(family)} of degree {n} (Y = 0: E_{k} does not "
            "depend on λ for any control polygon), so eq. 20 has no optimal λ"
        )
    return Fraction(s_fg) / Fraction(s_gg), x, y


@cache
def _float_forms(family: object, n: int, k: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(A0, A1, A2), symmetric, with E_k(λ) = Σ_coords Dᵀ(A0 + λA1 + λ²A2)D."""
    (s_ff, u_ff), (s_fg, x), (s_gg, y) = _energy_table(family)[(n, k)]

    def sym(scale: Fraction | int, u: UpperInts) -> np.ndarray:
        a = np.array(u, dtype=float) * float(scale)
        symmetric: np.ndarray = (a + a.T) / 2
        return symmetric

    out = (sym(s_ff, u_ff), -2 * sym(s_fg, x), sym(s_gg, y))
    for a in out:
        a.setflags(write=False)
    return out


def _exact_coefficients(
    family: object, n: int, k: int, rows: val.ExactRows
) -> tuple[Fraction, Fraction, Fraction]:
    def form(scale: Fraction | int, u: UpperInts) -> Fraction:
        total = Fraction(0)
        for r in range(n + 1):
            for c in range(r, n + 1):
                if u[r][c]:
                    total += u[r][c] * sum(
                        (a * b for a, b in zip(rows[r], rows[c], strict=True)), Fraction(0)
                    )
        return Fraction(scale) * total

    (s_ff, u_ff), (s_fg, x), (s_gg, y) = _energy_table(family)[(n, k)]
    return form(s_ff, u_ff), -2 * form(s_fg, x), form(s_gg, y)


def _as_polygons(points: PointsLike, family: object) -> tuple[np.ndarray, bool]:
    """(m, n+1, d) float array and whether the input was a single polygon."""
    data = _family_data(family)
    arr = val.real_array(points, "control points")
    if arr.ndim == 2:
        single = True
        arr = arr[None]
    elif arr.ndim == 3:
        single = False
    else:
        raise ValueError(
            f"control points must have shape (n+1, d) or (m, n+1, d), got shape {arr.shape}"
        )
    # shape and degree checks on the first polygon; finiteness is read off the results
    val.check_point_shape(arr.shape[1:], family=_name(family), degrees=tuple(data.DEGREES))
    return np.ascontiguousarray(arr), single


def _non_finite_error(arr: np.ndarray, single: bool) -> ValueError:
    bad = np.argwhere(~np.isfinite(arr))[0]
    where = f"polygon {bad[0]}, " if not single else ""
    return ValueError(f"{where}control point {bad[-2]} has a non-finite coordinate")


def energy_coefficients(points: PointsLike, k: int, family: object = "same_degree") -> Coefficients:
    r"""The coefficients of the energy as a quadratic in λ,
    :math:`E_k(\lambda) = \int_0^1 \lVert p^{(k)}(t; \lambda) \rVert^2 dt
    = a_0 + a_1 \lambda + a_2 \lambda^2`.

    Parameters
    ----------
    points : array_like
        One control polygon, shape (n+1, d), or a batch, shape (m, n+1, d).
    k : int
        The energy order: 1 stretch, 2 strain, 3 jerk.
    family : str or Family
        ``"same_degree"``, ``"bernstein_like"``, or a family from `load_family`.

    Returns
    -------
    tuple
        ``(a0, a1, a2)``: exact Fractions for a single polygon whose coordinates are all ints
        or Fractions; floats for other single polygons; arrays of length m for a batch
        (computed in floating point, vectorised over m).
    """
    k = _check_order(k)
    data = _family_data(family)
    rows = val.exact_rows(points)
    if rows is not None:  # exact: any magnitude, nothing is made a float
        val.exact_shape(rows, family=_name(family), degrees=tuple(data.DEGREES))
        return _exact_coefficients(family, len(rows) - 1, k, rows)
    coeffs, _, exponents, single = _float_coefficients(points, k, family)
    a0, a1, a2 = (_unscale(c, exponents, single, "the energy coefficients") for c in coeffs)
    return (a0[0], a1[0], a2[0]) if single else (a0, a1, a2)


def _unscale(values: _V, exponents: np.ndarray | None, single: bool, what: str) -> _V:
    """values · 2^exponents (the polygons' scaling undone), refused where that overflows."""
    if exponents is None:
        return values
    with np.errstate(over="ignore"):
        out: _V = np.ldexp(values, exponents)
    if not np.isfinite(out).all():
        where = "" if single else f" (polygon {int(np.argmin(np.isfinite(out)))})"
        raise ValueError(
            f"{what}: beyond the float range for these control points{where}; pass exact "
            "ints/Fractions (computed exactly) or scale the points down (λ* does not change)"
        )
    return out


def _float_coefficients(
    points: PointsLike, k: int, family: object
) -> tuple[tuple[np.ndarray, np.ndarray, np.ndarray], np.ndarray, np.ndarray | None, bool]:
    """((a0, a1, a2) arrays over the batch, a bound on a2's rounding error, single?).

    E_k(λ) = ‖Lᵀ H (Q − λW)‖² summed over coordinates (L the Cholesky factor of the Gram
    matrix, H the k-fold hodograph), so one matrix product per batch gives Lᵀ H Q and Lᵀ H W
    for every polygon, and three row-wise dot products give the coefficients.
    """
    arr, single = _as_polygons(points, family)
    (a0, a1, a2), rounding = _coefficients_of(arr, k, family)
    exponents: np.ndarray | None = None
    # coordinates near the float limits overflow (or underflow) in the quadratic forms: those
    # polygons are redone scaled by a power of two, E_k(λ) scaling by its square (exactly)
    redo = ~(np.isfinite(a0) & np.isfinite(a2)) | (a2 <= rounding)
    if redo.any():
        sub = arr[redo]
        if not np.isfinite(sub).all():  # NaN/inf in the input propagate into these
            raise _non_finite_error(arr, single)
        big = np.abs(sub).reshape(len(sub), -1).max(axis=1)
        shift = np.where(big > 0, np.frexp(big)[1] - 1, 0)
        (b0, b1, b2), r2 = _coefficients_of(np.ldexp(sub, -shift[:, None, None]), k, family)
        a0[redo], a1[redo], a2[redo], rounding[redo] = b0, b1, b2, r2
        exponents = np.zeros(arr.shape[0], dtype=int)
        exponents[redo] = 2 * shift
    return (a0, a1, a2), rounding, exponents, single


def _coefficients_of(
    arr: np.ndarray, k: int, family: object
) -> tuple[tuple[np.ndarray, np.ndarray, np.ndarray], np.ndarray]:
    m, size, dim = arr.shape
    factor, rows, a2_weight = _factored_forms(family, size - 1, k, dim)
    flat_t = arr.reshape(m, size * dim).T  # a view: column j is (P_0x, P_0y, P_1x, …) of j
    z = factor.T @ flat_t  # wide product (rows × m): BLAS is slow on the tall-skinny one
    zf, zg = z[:rows], z[rows:]
    a0 = np.einsum("ij,ij->j", zf, zf)
    a1 = 2 * np.einsum("ij,ij->j", zf, zg)
    a2 = np.einsum("ij,ij->j", zg, zg)
    norm2 = np.einsum("ij,ij->j", flat_t, flat_t)
    return (a0, a1, a2), 1e-12 * a2_weight * norm2


@cache
def _factored_forms(family: object, n: int, k: int, dim: int) -> tuple[np.ndarray, int, float]:
    """([kron((LᵀH M_0ᵀ)ᵀ, I) | kron((LᵀH M_1ᵀ)ᵀ, I)], rows, Σ|A2|) for the flattened layout,
    from the generated Bernstein, hodograph and Gram tables (the same data the exact forms
    were derived from). With Q = M_0ᵀD and W = −M_1ᵀD: Q − λW = (M_0ᵀ + λM_1ᵀ)D."""
    from .curves import _bernstein, _float_matrix, _tables

    big = n + _family_cls(family)._data_offset()
    h = np.eye(big + 1)
    for d in range(big, big - k, -1):
        h = np.array(_bernstein.HODOGRAPH[d], dtype=float) @ h
    scale, upper = _energy.GRAM[big - k]
    g = np.array(upper, dtype=float) * float(scale)
    g = (g + g.T) / 2  # the off-diagonal entries were stored doubled
    lower = np.linalg.cholesky(g)
    m0 = _float_matrix(_family_data(family), "bernstein", n, 0)
    m1 = _float_matrix(_family_data(family), "bernstein", n, 1)
    assert len(_tables(_family_data(family), "bernstein")[n]) == 2, (
        "E_k is quadratic in λ for these bases"
    )
    eye = np.eye(dim)
    f_part = np.kron((lower.T @ h @ m0.T).T, eye)
    g_part = np.kron((lower.T @ h @ m1.T).T, eye)
    factor = np.asfortranarray(np.hstack([f_part, g_part]))  # factor.T is C-contiguous
    factor.setflags(write=False)
    return factor, f_part.shape[1], float(np.abs(_float_forms(family, n, k)[2]).sum())


def optimal_lambda(
    points: PointsLike, k: int, family: object = "same_degree", clamp: bool = False
) -> OptimalLambda:
    r"""The λ minimising the energy
    :math:`E_k(\lambda) = \int_0^1 \lVert p^{(k)}(t; \lambda) \rVert^2 dt` (000, section 3).

    :math:`E_k` is a convex quadratic in λ, so the minimiser is
    :math:`\lambda^\ast = -a_1 / (2 a_2)` (see `energy_coefficients`), and over a closed
    range the clamped value.

    Parameters
    ----------
    points : array_like
        Control points, shape (n+1, d), or a batch of polygons, shape (m, n+1, d), solved in
        one vectorised call. Exact (Fractions) when every coordinate is an int or a Fraction.
    k : int
        The energy order: 1 stretch, 2 strain, 3 jerk.
    family : str or Family
        ``"same_degree"`` (range (−2, 1]), ``"bernstein_like"`` (range [−1, 1]), or a family
        from `load_family`.
    clamp : bool
        Return the minimiser over the family's closed range instead of over all real λ
        (the unconstrained one is still reported).

    Returns
    -------
    OptimalLambda
        The minimiser, whether it is admissible, and the energy there.

    Raises
    ------
    ValueError
        When λ has no effect on the energy of a polygon (:math:`D^\mathsf{T} Y D = 0`), or
        for bad input.

    Examples
    --------
    >>> r = optimal_lambda([(0, 6), (0, 2), (5, 2), (7, 0), (2, 0), (6, 8)], k=2)
    >>> r.lam, r.admissible
    (Fraction(-690, 319), False)
    >>> optimal_lambda([(0, 6), (0, 2), (5, 2), (7, 0), (2, 0), (6, 8)], k=2, clamp=True).lam
    Fraction(-2, 1)
    """
    data = _family_data(family)
    k = _check_order(k)
    clamp = val.flag(clamp, "clamp")
    rows = val.exact_rows(points)
    exact = rows is not None
    # Fractions on the exact path, floats (or arrays over a batch) otherwise: the arithmetic
    # below is shared, and mypy would check every pairing of a union (a Fraction with an
    # array), which never meets at run time
    a0: Any
    a1: Any
    a2: Any
    exponents: np.ndarray | None = None
    if rows is not None:
        a0, a1, a2 = energy_coefficients(rows, k, family)
    else:
        (a0, a1, a2), rounding, exponents, single = _float_coefficients(points, k, family)
    lo, hi = data.LAMBDA_RANGE
    lo_closed, hi_closed = data.LAMBDA_CLOSED
    if exact:
        if a2 == 0:
            raise ValueError(_no_effect_message(k))
        best = -a1 / (2 * a2)
        lam = min(max(best, Fraction(lo)), Fraction(hi)) if clamp else best
    else:
        degenerate = a2 <= rounding
        if degenerate.any():
            where = "" if single else f" (polygon {int(np.argmax(degenerate))})"
            raise ValueError(_no_effect_message(k) + where)
        if single:
            a0, a1, a2 = a0[0], a1[0], a2[0]
        best = -a1 / (2 * a2)
        # float bounds: a user family's range is in Fractions, which would make an object array
        lam = np.clip(best, float(lo), float(hi)) if clamp else best

    def inside(x: Any) -> bool | np.ndarray:
        ok: bool | np.ndarray = ((x > lo) | ((x == lo) & lo_closed)) & (
            (x < hi) | ((x == hi) & hi_closed)
        )
        return ok

    energy = a0 + a1 * lam + a2 * lam * lam
    unconstrained_energy = a0 + a1 * best + a2 * best * best
    if exponents is not None:  # the polygons that were computed scaled (see above)
        energy, unconstrained_energy = (
            _unscale(e, exponents if not single else exponents[0], single, f"E_{k}")
            for e in (energy, unconstrained_energy)
        )
    ok, ok_best = inside(lam), inside(best)
    if exact or np.ndim(best) == 0:
        ok, ok_best = bool(ok), bool(ok_best)
    if not exact and np.ndim(best) == 0:
        best, lam, energy, unconstrained_energy = (
            float(x) for x in (best, lam, energy, unconstrained_energy)
        )
    return OptimalLambda(
        lam=lam,
        unconstrained=best,
        admissible=ok,
        unconstrained_admissible=ok_best,
        energy=energy,
        unconstrained_energy=unconstrained_energy,
        k=k,
        family=_name(family),
        range_text=data.LAMBDA_RANGE_TEXT,
        clamped=clamp,
    )


def optimal_parameters(
    points: PointsLike, k: int, family: object = "same_degree"
) -> OptimalParameters:
    r"""Every shape parameter of `family`, by its own name, minimising the energy
    :math:`E_k` of one control polygon over the family's (closed) parameter box.

    :math:`E_k` is a convex quadratic in the parameter of a family whose basis is affine in
    it, so the free optimum is exact (Fractions for exact points); when it lies outside the
    box the minimum is at the nearer end, and `boundary` says so.

    Examples
    --------
    >>> r = optimal_parameters([(0, 6), (0, 2), (5, 2), (7, 0), (2, 0), (6, 8)], k=2)
    >>> r["lam"], r.free_inside, r.boundary
    (Fraction(-2, 1), False, 'lam = -2 (lower end, excluded: not attained)')
    """
    atom = getattr(family, "atom_data", None)
    if atom is not None:
        return _optimal_atoms(points, k, atom)
    several = getattr(family, "several", None)
    if several is not None:
        return _optimal_several(points, k, family, several)
    one = optimal_lambda(points, k, family, clamp=True)
    if isinstance(one.lam, np.ndarray):  # pragma: no cover - a polygon batch
        raise ValueError("points: optimal_parameters takes one control polygon")
    name = _family_cls(family).parameter_name
    data = _family_data(family)
    lo, hi = data.LAMBDA_RANGE
    boundary = ""
    if one.lam != one.unconstrained:
        lower = one.lam == lo
        end = "lower" if lower else "upper"
        closed = data.LAMBDA_CLOSED[0 if lower else 1]
        # an open end is the infimum over the range, not attained in it
        boundary = f"{name} = {one.lam} ({end} end{'' if closed else ', excluded: not attained'})"
    return OptimalParameters(
        values={name: one.lam},
        energy=one.energy,  # type: ignore[arg-type]
        free={name: one.unconstrained},  # type: ignore[dict-item]
        free_inside=bool(one.unconstrained_admissible),
        boundary=boundary,
        k=one.k,
        family=one.family,
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


def _optimal_several(points: PointsLike, k: int, family: Any, several: Any) -> OptimalParameters:
    """E_k = w^T S w with w = (1, x_1..x_J) for a family affine in its parameters jointly
    (S from the derived Gram matrices, exact); its minimum over the closed box is the least
    of the free minima on the box's faces (each a linear system) that lie in the face:
    every face is tried, 3^J of them."""
    k = _check_order(k)
    names = several.NAMES
    if several.ENERGY_REASON is not None:
        raise ValueError(f"optimal_parameters: {several.ENERGY_REASON}")
    given = val.exact_rows(points)
    exact = given is not None
    rows: list[tuple[Fraction, ...]]
    if given is None:
        arr = np.asarray(val.as_points(points, family=several.FAMILY, degrees=several.DEGREES))
        rows = [tuple(Fraction(float(v)) for v in row) for row in arr]
    else:
        rows = [tuple(Fraction(v) for v in row) for row in given]
    n = len(rows) - 1
    if (n, k) not in several.GRAM:
        raise ValueError(
            f"points: {n + 1} control points: no derived E_{k} of {several.FAMILY} for degree "
            f"{n} (degrees {several.DEGREES[0]}..{several.DEGREES[-1]}; k = 1, 2, 3)"
        )
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
    k = _check_order(k)
    names = data.NAMES
    if data.ENERGY_REASON is not None and not data.GRAM:
        raise ValueError(f"optimal_parameters: {data.ENERGY_REASON}")
    given = val.exact_rows(points)
    exact = given is not None
    rows: list[tuple[Fraction, ...]]
    if given is None:
        arr = np.asarray(val.as_points(points, family=data.FAMILY, degrees=data.DEGREES))
        rows = [tuple(Fraction(float(v)) for v in row) for row in arr]
    else:
        val.exact_shape(given, family=data.FAMILY, degrees=data.DEGREES)
        rows = [tuple(Fraction(v) for v in row) for row in given]
    n = len(rows) - 1
    if (n, k) not in data.GRAM:
        raise ValueError(
            f"points: {n + 1} control points: no derived E_{k} of {data.FAMILY} for degree {n}"
        )
    size = len(names) + 1

    def index(mono: tuple[int, ...]) -> int:
        if sum(mono) == 0:
            return 0
        if sum(mono) == 1:
            return 1 + mono.index(1)
        raise ValueError(
            f"optimal_parameters: {data.FAMILY} is not affine in its parameters (a term "
            f"{mono} of degree {sum(mono)}): its energy is not a quadratic in them, and this "
            "version minimises only quadratics exactly"
        )

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
    return _box_minimum(s_mat, names, data.RANGES, exact, k, data.FAMILY)


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


def _exact_value(v: Any) -> Any:
    """A Fraction, or an exact number of ℚ(π) that is rational, as the Fraction it is."""
    if getattr(v, "is_rational", False):
        return v.numerator[0] if v.numerator else Fraction(0)
    return v


def _no_effect_message(k: int) -> str:
    return (
        f"λ has no effect on E_{k} for this control polygon (DᵀYD = 0: the λ-dependent part of "
        f"the curve has a vanishing {ENERGY_NAMES[k]} term), so no optimal λ exists"
    )
