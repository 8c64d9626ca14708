"""Energy-optimal shape parameter (000, section 3), exact or vectorised over many polygons.

E_k(λ) = ∫_0^1 |p^(k)(t)|² dt is a convex quadratic in λ whose coefficients are quadratic
forms in the control points; the forms are derived in derive/energy.py and read here from
generated/energy.py.
"""

from __future__ import annotations

import math
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
from .hazmat import batch_numpy, kernels
from .hazmat.kernels import chunk_ranges
from .parameter_optimum import (
    OptimalParameters,
    _exact_value,
    _optimal_atoms,
    _optimal_indexed,
    _optimal_several,
    _own_optimum,
    atom_energy_form,
)

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


def _non_finite_error(arr: np.ndarray, single: bool, first: int = 0) -> ValueError:
    """The first non-finite coordinate of `arr`, polygons numbered from `first`."""
    bad = np.argwhere(~np.isfinite(arr))[0]
    where = f"polygon {first + bad[0]}, " if not single else ""
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


def _unscale(
    values: _V, exponents: np.ndarray | None, single: bool, what: str, first: int = 0
) -> _V:
    """values · 2^exponents (the polygons' scaling undone), refused where that overflows
    (polygons numbered from `first`)."""
    if exponents is None:
        return values
    with np.errstate(over="ignore"):
        out: _V = np.ldexp(values, exponents)
    if not np.isfinite(out).all():
        where = "" if single else f" (polygon {first + int(np.argmin(np.isfinite(out)))})"
        raise ValueError(
            f"{what}: beyond the float range for these control points{where}; pass exact "
            "ints/Fractions (computed exactly) or scale the points down (λ* does not change)"
        )
    return out


def _float_coefficients(
    points: PointsLike, k: int, family: object
) -> tuple[tuple[np.ndarray, np.ndarray, np.ndarray], np.ndarray, np.ndarray | None, bool]:
    """((a0, a1, a2) arrays over the batch, a bound on a2's rounding error, the exponents of
    the polygons computed scaled (None when none was), single?), chunk by chunk."""
    arr, single = _as_polygons(points, family)
    m = arr.shape[0]
    out = np.empty((4, m))
    exponents: np.ndarray | None = None
    for lo, hi in _chunks(arr, k, family):
        (a0, a1, a2), rounding, shifts = _chunk_coefficients(arr[lo:hi], k, family, single, lo)
        out[0, lo:hi], out[1, lo:hi], out[2, lo:hi], out[3, lo:hi] = a0, a1, a2, rounding
        if shifts is not None:
            if exponents is None:
                exponents = np.zeros(m, dtype=int)
            exponents[lo:hi] = shifts
    return (out[0], out[1], out[2]), out[3], exponents, single


def _chunks(arr: np.ndarray, k: int, family: object) -> list[tuple[int, int]]:
    """Chunks of polygons whose products (rows × chunk) stay in cache."""
    m, size, dim = arr.shape
    return chunk_ranges(m, _factored_forms(family, size - 1, k, dim)[0].shape[1])


def _chunk_coefficients(
    arr: np.ndarray, k: int, family: object, single: bool, first: int
) -> tuple[tuple[np.ndarray, np.ndarray, np.ndarray], np.ndarray, np.ndarray | None]:
    """_float_coefficients on one chunk of polygons (the first is polygon `first`).

    E_k(λ) = ‖Lᵀ H (Q − λW)‖² summed over coordinates (L the Cholesky factor of the Gram
    matrix, H the k-fold hodograph), so one matrix product per chunk gives Lᵀ H Q and Lᵀ H W
    for every polygon, and three row-wise dot products give the coefficients.
    """
    (a0, a1, a2), rounding = _coefficients_of(arr, k, family)
    exponents: np.ndarray | None = None
    # coordinates near the float limits overflow (or underflow) in the quadratic forms: those
    # polygons are redone scaled by a power of two, E_k(λ) scaling by its square (exactly)
    redo = ~(np.isfinite(a0) & np.isfinite(a2)) | (a2 <= rounding)
    if redo.any():
        sub = arr[redo]
        if not np.isfinite(sub).all():  # NaN/inf in the input propagate into these
            raise _non_finite_error(arr, single, first)
        big = np.abs(sub).reshape(len(sub), -1).max(axis=1)
        shift = np.where(big > 0, np.frexp(big)[1] - 1, 0)
        (b0, b1, b2), r2 = _coefficients_of(np.ldexp(sub, -shift[:, None, None]), k, family)
        a0[redo], a1[redo], a2[redo], rounding[redo] = b0, b1, b2, r2
        exponents = np.zeros(arr.shape[0], dtype=int)
        exponents[redo] = 2 * shift
    return (a0, a1, a2), rounding, exponents


def _coefficients_of(
    arr: np.ndarray, k: int, family: object
) -> tuple[tuple[np.ndarray, np.ndarray, np.ndarray], np.ndarray]:
    m, size, dim = arr.shape
    compiled = kernels.batch_compiled()
    if compiled is not None:  # one pass per polygon (hazmat/batch_compiled.py)
        compact, rows, a2_weight = _compact_forms(family, size - 1, k)
        out = np.empty((4, m))
        compiled.energy_coefficients(
            np.ascontiguousarray(arr), compact, rows, 1e-12 * a2_weight, out
        )
        return (out[0], out[1], out[2]), out[3]
    factor, rows, a2_weight = _factored_forms(family, size - 1, k, dim)
    flat_t = arr.reshape(m, size * dim).T  # a view: column j is (P_0x, P_0y, P_1x, …) of j
    # NaN, infinity and overflow are read off the results (_chunk_coefficients), not warned
    with val.overflow_allowed():
        # wide product (rows × m): BLAS is slow on the tall-skinny one. One product, on
        # OpenBLAS's threads: cut into blocks under its thread threshold it measured 10-13 ms
        # against 6-8 ms on a quiet machine (faster only on a loaded one)
        z = factor.T @ flat_t
        zf, zg = z[:rows], z[rows:]
        a0 = np.einsum("ij,ij->j", zf, zf)
        a1 = np.einsum("ij,ij->j", zf, zg)
        a1 *= 2
        a2 = np.einsum("ij,ij->j", zg, zg)
        rounding = np.einsum("ij,ij->j", flat_t, flat_t)
        rounding *= 1e-12 * a2_weight
    return (a0, a1, a2), rounding


@cache
def _factors(family: object, n: int, k: int) -> tuple[np.ndarray, np.ndarray, float]:
    """((LᵀH M_0ᵀ)ᵀ, (LᵀH M_1ᵀ)ᵀ, Σ|A2|), each (n+1, rows), from the generated Bernstein,
    hodograph and Gram tables (the same data the exact forms were derived from). With
    Q = M_0ᵀD and W = −M_1ᵀD: Q − λW = (M_0ᵀ + λM_1ᵀ)D."""
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
    weight = float(np.abs(_float_forms(family, n, k)[2]).sum())
    return (lower.T @ h @ m0.T).T, (lower.T @ h @ m1.T).T, weight


@cache
def _factored_forms(family: object, n: int, k: int, dim: int) -> tuple[np.ndarray, int, float]:
    """([kron(F, I) | kron(G, I)], rows, Σ|A2|) for the flattened layout, F and G from
    `_factors`."""
    f, g, weight = _factors(family, n, k)
    eye = np.eye(dim)
    f_part = np.kron(f, eye)
    g_part = np.kron(g, eye)
    factor = np.asfortranarray(np.hstack([f_part, g_part]))  # factor.T is C-contiguous
    factor.setflags(write=False)
    return factor, f_part.shape[1], weight


@cache
def _compact_forms(family: object, n: int, k: int) -> tuple[np.ndarray, int, float]:
    """([F | G], rows, Σ|A2|): `_factors` side by side, for the compiled kernel."""
    f, g, weight = _factors(family, n, k)
    compact = np.ascontiguousarray(np.hstack([f, g]))
    compact.setflags(write=False)
    return compact, f.shape[1], weight


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
        of one parameter from `load_family` (a trigonometric, hyperbolic or mixed one too: its
        minimiser is exact in ℚ(π) or ℚ(e^W), one polygon per call).
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
    atom = getattr(family, "atom_data", None)
    if atom is not None:  # a trigonometric, hyperbolic or mixed family of one parameter
        return _optimal_lambda_atoms(points, _check_order(k), atom, val.flag(clamp, "clamp"))
    own = getattr(family, "energy_minimum", None)
    if own is not None:  # a family that answers for itself (certified over its range)
        k = _check_order(k)
        found = _own_optimum(own(points, k), k, family)
        return _own_optimal_lambda(found, family, val.flag(clamp, "clamp"))
    data = _family_data(family)
    k = _check_order(k)
    clamp = val.flag(clamp, "clamp")
    rows = val.exact_rows(points)
    result: tuple[Any, ...]
    if rows is not None:
        a0, a1, a2 = energy_coefficients(rows, k, family)
        if a2 == 0:
            raise ValueError(_no_effect_message(k))
        lam, best, ok, ok_best, energy, unconstrained_energy = _optimum((a0, a1, a2), clamp, data)
        result = (lam, best, bool(ok), bool(ok_best), energy, unconstrained_energy)
    else:
        result = _float_optimum(points, k, family, clamp, data)
    lam, best, ok, ok_best, energy, unconstrained_energy = result
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


def _own_optimal_lambda(r: OptimalParameters, family: Any, clamp: bool) -> OptimalLambda:
    """optimal_lambda from a family's own certified optimum over its range: E_k is not a
    quadratic in its parameter, so there is no unconstrained minimiser apart from it (the
    same value is reported as `unconstrained`, with or without `clamp`)."""
    (x,) = r.values.values()
    attained = "not attained" not in r.boundary
    return OptimalLambda(
        lam=x,
        unconstrained=x,
        admissible=attained,
        unconstrained_admissible=attained,
        energy=r.energy,
        unconstrained_energy=r.energy,
        k=r.k,
        family=r.family,
        range_text=str(family.range_text),
        clamped=clamp,
    )


def _optimal_lambda_atoms(points: PointsLike, k: int, atom: Any, clamp: bool) -> OptimalLambda:
    """optimal_lambda of a one-parameter atom family: E_k = S00 + 2 S01 λ + S11 λ² with
    entries in ℚ[π] or ℚ[e^W] (parameter_optimum.atom_energy_form), solved as 000's quadratic
    in that field: exact (ConstantFraction) for exact points, floats otherwise."""
    if len(atom.NAMES) != 1:
        raise TypeError(
            f"optimal_lambda takes a family of one parameter; {atom.FAMILY!r} has "
            f"{', '.join(atom.NAMES)}: use optimal_parameters(points, k, family=...)"
        )
    if np.ndim(val.real_array(points, "points")) == 3:
        raise ValueError(
            f"points: a batch of polygons is solved for polynomial families; call "
            f"optimal_lambda once per polygon for {atom.FAMILY!r}"
        )
    form = atom_energy_form(points, k, atom)
    if isinstance(form, OptimalParameters):  # E_k no quadratic in λ: no closed minimiser
        raise ValueError(
            f"optimal_lambda: {atom.FAMILY!r} is not affine in {atom.NAMES[0]}, so E_{k} is "
            "no quadratic in it; optimal_parameters gives its certified minimum over the range"
        )
    (s00, s01), (_, s11) = form[0]
    if s11 == 0:
        raise ValueError(_no_effect_message(k))
    lo, hi, lo_closed, hi_closed, text = atom.RANGES[atom.NAMES[0]]
    data = _RangeData((lo, hi), (lo_closed, hi_closed))
    got = _optimum((s00, 2 * s01, s11), clamp, data)
    out: Any = _exact_value if form[1] else float
    lam, best, ok, ok_best, energy, unconstrained_energy = got
    return OptimalLambda(
        lam=out(lam),
        unconstrained=out(best),
        admissible=bool(ok),
        unconstrained_admissible=bool(ok_best),
        energy=out(energy),
        unconstrained_energy=out(unconstrained_energy),
        k=k,
        family=atom.FAMILY,
        range_text=text,
        clamped=clamp,
    )


class _RangeData:
    """The two range attributes _optimum reads of a family's tables. (A plain class: a
    dataclass costs a quarter of a millisecond of every program's import, issue #29.)"""

    __slots__ = ("LAMBDA_CLOSED", "LAMBDA_RANGE")

    def __init__(self, lambda_range: tuple[Any, Any], closed: tuple[bool, bool]) -> None:
        self.LAMBDA_RANGE = lambda_range
        self.LAMBDA_CLOSED = closed


def _optimum(coefficients: tuple[Any, Any, Any], clamp: bool, data: Any) -> tuple[Any, ...]:
    """(λ, λ*, λ admissible, λ* admissible, E_k(λ), E_k(λ*)) from E_k's coefficients, in
    their arithmetic: Fractions (exact), or arrays over a chunk of polygons. (Any: mypy
    would check every pairing of the union, a Fraction with an array, which never meets.)"""
    a0, a1, a2 = coefficients
    lo, hi = data.LAMBDA_RANGE
    lo_closed, hi_closed = data.LAMBDA_CLOSED
    best = -a1 / (2 * a2)
    if not clamp:
        lam = best
    elif not isinstance(best, (np.ndarray, float)):  # exact: a Fraction, or one in ℚ(π)
        lam = min(max(best, Fraction(lo)), Fraction(hi))
    else:  # float bounds: a user family's range is in Fractions (an object array otherwise)
        lam = np.clip(best, float(lo), float(hi))

    def inside(x: Any) -> Any:
        above = x >= lo if lo_closed else x > lo
        below = x <= hi if hi_closed else x < hi
        return above & below

    def energy_at(x: Any) -> Any:
        return a0 + a1 * x + a2 * x * x

    unconstrained_energy = energy_at(best)
    ok_best = inside(best)
    if lam is best:  # unclamped: one evaluation
        return lam, best, ok_best, ok_best, unconstrained_energy, unconstrained_energy
    return lam, best, inside(lam), ok_best, energy_at(lam), unconstrained_energy


def _float_optimum(
    points: PointsLike, k: int, family: object, clamp: bool, data: Any
) -> tuple[Any, ...]:
    """_optimum for float polygons, chunk by chunk: nothing but the results grows with the
    batch (issue #29: 10⁷ polygons in bounded memory), and each chunk's passes run in cache.
    One polygon gives floats and bools, a batch arrays (unclamped, λ and λ* are one array,
    and so are their energies and admissibility)."""
    arr, single = _as_polygons(points, family)
    m = arr.shape[0]
    best, ok_best, energy_best = np.empty(m), np.empty(m, dtype=bool), np.empty(m)
    lam, ok, energy = (
        (np.empty(m), np.empty(m, dtype=bool), np.empty(m))
        if clamp
        else (
            best,
            ok_best,
            energy_best,
        )
    )
    result = (lam, best, ok, ok_best, energy, energy_best)
    compiled = kernels.batch_compiled()
    chunks = _chunks(arr, k, family)
    if compiled is not None:  # one compiled pass
        form, rows, a2_weight = _compact_forms(family, arr.shape[1] - 1, k)
        kernel = compiled.energy_optimum
    else:  # numpy, chunk by chunk, a test per chunk (hazmat/batch_numpy.py)
        form, rows, a2_weight = _factored_forms(family, arr.shape[1] - 1, k, arr.shape[2])
        kernel = batch_numpy.energy_optimum
    bounds = _admissible_bounds(data)
    start = 0
    while start < m:  # only the chunks the pass declines are redone by the careful path
        stop = start + kernel(
            arr[start:], form, rows, 1e-12 * a2_weight, bounds, clamp, best[start:],
            ok_best[start:], energy_best[start:], lam[start:], ok[start:], energy[start:]
        )  # fmt: skip
        if stop == m:
            break
        lo, hi = next(c for c in chunks if c[0] <= stop < c[1])
        _float_optimum_chunk(arr, lo, hi, k, family, clamp, data, single, result)
        start = hi
    if single:
        return (
            float(lam[0]),
            float(best[0]),
            bool(ok[0]),
            bool(ok_best[0]),
            float(energy[0]),
            float(energy_best[0]),
        )
    return result


def _admissible_bounds(data: Any) -> np.ndarray:
    """(clip low, clip high, least admissible, greatest admissible) as floats, for the
    compiled optimum: the clip bounds are `_optimum`'s float(lo), float(hi); the admissible
    ones are the least and greatest floats inside the family's exact range (an open or
    closed end, an int or a Fraction), so closed float comparisons decide exactly what
    `_optimum`'s comparisons with the exact ends decide."""
    lo, hi = data.LAMBDA_RANGE
    lo_closed, hi_closed = data.LAMBDA_CLOSED

    def inner(end: Any, closed: bool, up: float) -> float:
        near = float(end)
        if math.isinf(near):
            return near
        exact, end_q = Fraction(near), Fraction(end)
        inside = (exact - end_q) * up > 0 or (closed and exact == end_q)
        return near if inside else float(np.nextafter(near, up * math.inf))

    return np.array([float(lo), float(hi), inner(lo, lo_closed, 1.0), inner(hi, hi_closed, -1.0)])


def _float_optimum_chunk(
    arr: np.ndarray,
    lo: int,
    hi: int,
    k: int,
    family: object,
    clamp: bool,
    data: Any,
    single: bool,
    result: tuple[np.ndarray, ...],
) -> None:
    """Polygons lo .. hi-1 of `_float_optimum` by the careful path, written into result
    (λ, λ*, λ admissible, λ* admissible, E_k(λ), E_k(λ*)): the numpy fallback, and where the
    compiled pass declines (rescaling near the float limits, the error naming a polygon)."""
    lam, best, ok, ok_best, energy, energy_best = result
    coefficients, rounding, exponents = _chunk_coefficients(arr[lo:hi], k, family, single, lo)
    degenerate = coefficients[2] <= rounding
    if degenerate.any():
        where = "" if single else f" (polygon {lo + int(np.argmax(degenerate))})"
        raise ValueError(_no_effect_message(k) + where)
    got = _optimum(coefficients, clamp, data)
    e_lam, e_best = got[4], got[5]
    if exponents is not None:  # the polygons that were computed scaled
        e_best = _unscale(e_best, exponents, single, f"E_{k}", lo)
        e_lam = e_best if got[4] is got[5] else _unscale(e_lam, exponents, single, f"E_{k}", lo)
    best[lo:hi], ok_best[lo:hi], energy_best[lo:hi] = got[1], got[3], e_best
    if clamp:
        lam[lo:hi], ok[lo:hi], energy[lo:hi] = got[0], got[2], e_lam


def optimal_parameters(
    points: PointsLike, k: int, family: object = "same_degree"
) -> OptimalParameters:
    r"""Every shape parameter of `family`, by its own name, minimising the energy
    :math:`E_k` of one control polygon over the family's (closed) parameter box.

    :math:`E_k` is a convex quadratic in the parameter of a family whose basis is affine in
    it, so the free optimum is exact (Fractions for exact points); when it lies outside the
    box the minimum is at the nearer end, and `boundary` says so. For a family whose basis is
    not affine in its parameters, the minimum over the closed box is certified by exact
    Bernstein branch and bound: `energy` is E_k at `values` exactly, and `lower_bound` is a
    proven lower bound over the box within 1e-12 (relative) of it. An indexed family
    (``lam(i)``) returns the parameters of the points' degree as one tuple, ``result["lam"]``.

    Examples
    --------
    >>> r = optimal_parameters([(0, 6), (0, 2), (5, 2), (7, 0), (2, 0), (6, 8)], k=2)
    >>> r["lam"], r.free_inside, r.boundary
    (Fraction(-2, 1), False, 'lam = -2 (lower end, excluded: not attained)')
    """
    if hasattr(family, "by_degree"):  # an indexed family (lam(i)): its degree's parameters
        return _optimal_indexed(points, _check_order(k), family)
    own = getattr(family, "energy_minimum", None)
    if own is not None:  # a family that answers for itself (certified over its range)
        k = _check_order(k)
        return _own_optimum(own(points, k), k, family)
    atom = getattr(family, "atom_data", None)
    if atom is not None:
        return _optimal_atoms(points, _check_order(k), atom)
    several = getattr(family, "several", None)
    if several is not None:
        return _optimal_several(points, _check_order(k), family, several)
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


def _no_effect_message(k: int) -> str:
    return (
        f"λ has no effect on E_{k} for this control polygon (DᵀYD = 0: the λ-dependent part of "
        f"the curve has a vanishing {ENERGY_NAMES[k]} term), so no optimal λ exists"
    )
