"""Many curves of one family and degree at once: no Python loop over curves or parameters."""

from __future__ import annotations

import sys
from typing import Any

import numpy as np
import numpy.typing as npt

from . import _validate as val
from .curves import FAMILIES, Curve, _float_matrix, _tables, family_class
from .hazmat import kernels as alg
from .hazmat.kernels import chunk_ranges, differentiate_coefficients


def _lambdas(lam: npt.ArrayLike, cls: type[Curve], m: int, check_range: bool) -> np.ndarray:
    data, family = cls._data, cls.family
    arr = val.real_array(lam, "lam")
    if arr.ndim > 1 or (arr.ndim == 1 and arr.size != m):
        raise ValueError(f"lam must be a number or an array of {m} numbers, got shape {arr.shape}")
    arr = np.broadcast_to(arr, (m,))
    if not np.isfinite(arr).all():
        raise ValueError("lam contains NaN or infinity")
    if check_range:
        lo, hi = data.LAMBDA_RANGE
        lo_closed, hi_closed = data.LAMBDA_CLOSED
        ok = ((arr > lo) | ((arr == lo) & lo_closed)) & ((arr < hi) | ((arr == hi) & hi_closed))
        if not ok.all():
            idx = int(np.argmin(ok))
            raise ValueError(
                f"lam = {arr[idx]} (curve {idx}) is outside the {family} range "
                f"{data.LAMBDA_RANGE_TEXT}; pass check_range=False to use it anyway"
            )
    return arr


def _named(lam: object, named_params: dict[str, object]) -> dict[str, object]:
    """Keyword parameters in the family's own names, with `lam` among them when given."""
    if lam is None:
        return dict(named_params)
    if "lam" in named_params:  # unreachable through the signature; kept for callers' dicts
        raise TypeError("lam is given twice; give it once")
    return {"lam": lam, **named_params}


def _merged(
    params: dict[str, Any] | None, named_params: dict[str, object]
) -> dict[str, Any] | None:
    """`params` with the keyword parameters added (TypeError for one given both ways)."""
    if not named_params:
        return params
    both = sorted(set(params or {}) & set(named_params))
    if both:
        raise TypeError(f"{', '.join(both)} given twice (params and keyword); give it once")
    return {**(params or {}), **named_params}


def evaluate_many(
    points: npt.ArrayLike,
    t: npt.ArrayLike,
    family: object = "bezier",
    lam: npt.ArrayLike | None = None,
    *,
    k: int = 0,
    check_range: bool = True,
    extrapolate: bool = False,
    params: dict[str, float] | None = None,
    out: np.ndarray | None = None,
    **named_params: object,
) -> np.ndarray:
    r"""The k-th derivative :math:`p^{(k)}(t)` of m curves of one family and degree at once.

    Parameters
    ----------
    points : array_like
        Control points of shape (m, n+1, d).
    t : array_like
        Parameter values, shape (T,), in [0, 1] unless `extrapolate` (a trigonometric,
        hyperbolic or mixed family: in its own domain of t, e.g. [0, π/2]).
    family : str
        ``"bezier"``, ``"same_degree"`` or ``"bernstein_like"``.
    lam : float or array_like, optional
        One λ for every curve, or one per curve (shape (m,)); not for ``"bezier"``.
    k : int
        The derivative order (0: the points of the curves).
    check_range : bool
        Refuse a λ outside the family's range.
    extrapolate : bool
        Allow t outside [0, 1].
    params : dict, optional
        A family in several parameters (from `load_family`): one value per parameter,
        ``{"lam": ..., "mu": ...}``, shared by every curve; an indexed family (``lam(i)``)
        takes ``{"lam": [one value per index]}`` (or ``lam=[...]``).
    **named_params
        The same parameters as keywords in the family's own names (``lam=..., mu=...``), as
        ``fam.curve`` takes them.
    out : numpy.ndarray, optional
        An array to write the result into and return, as numpy's ``out=``: float64,
        C-contiguous, writeable, of the result's shape (m, T, d) ((m, d) for a scalar t),
        and not overlapping `points` or `t`. Reusing one buffer across calls saves
        allocating (and the operating system zeroing) a fresh result each time.

    Returns
    -------
    numpy.ndarray
        Shape (m, T, d) (`out` when given).

    Examples
    --------
    >>> import numpy as np
    >>> pts = np.array([[(0, 0), (1, 2), (3, 2), (4, 0)]] * 2, dtype=float)
    >>> evaluate_many(pts, [0.0, 0.5], "same_degree", lam=[1.0, 0.5])[:, 1]
    array([[2.  , 1.5 ],
           [2.  , 1.25]])
    """
    if getattr(family, "atom_data", None) is not None:  # trigonometric, hyperbolic, mixed
        from .atom_family import evaluate_many as atom_evaluate_many

        named = _named(lam, named_params)
        given = family.parameter_values(None, params, named)  # type: ignore[attr-defined]
        exact = family.exact_values(given, val.flag(check_range, "check_range"))  # type: ignore[attr-defined]
        values = atom_evaluate_many(family, points, t, k, exact, extrapolate)
        return values if out is None else _into(out, values, points, t)
    own = getattr(family, "evaluate_curves", None)
    if own is not None:  # a family with its parameter in the domain (C-Bézier): its own
        params = _merged(params, named_params)
        values = own(points, t, k, lam, params, val.flag(extrapolate, "extrapolate"))
        return values if out is None else _into(out, values, points, t)
    if hasattr(family, "by_degree"):  # an indexed family (lam(i)): its degree's own Family
        shape = np.shape(val.real_array(points, "control points"))
        if len(shape) != 3:
            raise ValueError(f"control points must have shape (m, n+1, d), got shape {shape}")
        name = family.index_name  # type: ignore[attr-defined]
        params = _merged(params, named_params)
        named_params = {}
        given = dict(params or {}) if lam is None else {name: lam, **(params or {})}
        if set(given) != {name}:
            raise TypeError(f"params: {family.name!r} takes one sequence, {name}=[...]")  # type: ignore[attr-defined]
        params = family.index_values(shape[1] - 1, given[name])  # type: ignore[attr-defined]
        family, lam = family.at_degree(shape[1] - 1), None  # type: ignore[attr-defined]
    if getattr(family, "several", None) is not None:
        named = _named(lam, named_params)  # a parameter may be called lam
        given = family.parameter_values(None, params, named)  # type: ignore[attr-defined]
        family = family._fixed_class(given, val.flag(check_range, "check_range"))  # type: ignore[attr-defined]
        lam = None
    elif params is not None:
        raise TypeError("params: only a family in several parameters takes params (use lam)")
    elif named_params:
        raise TypeError(
            f"{', '.join(sorted(named_params))}: a family of one parameter takes it as lam="
        )
    # a built-in family's name, or a family from lambda_bezier.load_family
    cls = (
        FAMILIES[val.choice(family, "family", tuple(FAMILIES))]
        if isinstance(family, str)
        else family_class(family)
    )
    family = cls.family
    check_range = val.flag(check_range, "check_range")
    arr = val.real_array(points, "control points")
    if arr.ndim != 3:
        raise ValueError(f"control points must have shape (m, n+1, d), got shape {arr.shape}")
    m, size, dim = arr.shape
    # the classical curve takes any degree (as BezierCurve does); past its tables (and at
    # degree 0) it is evaluated by de Casteljau below
    degrees = (0, sys.maxsize) if cls._any_degree else tuple(cls._data.DEGREES)
    val.check_point_shape((size, dim), family=family, degrees=degrees)
    k = val.as_order(k)
    tt, scalar = val.as_parameters(t, extrapolate=extrapolate)
    n = size - 1
    if n not in cls._data.DEGREES:
        if lam is not None:
            raise ValueError("a classical Bézier curve takes no shape parameter")
        values = _de_casteljau_many(arr, tt, k, scalar)
        return values if out is None else _into(out, values, points, arr, t)
    mats = _tables(cls._data, "centred")[n]
    if not cls._has_lambda:
        if lam is not None:
            raise ValueError("a classical Bézier curve takes no shape parameter")
        lams = np.zeros(())  # unused: one table, no λ (not one zero per curve: memory)
    else:
        if lam is None:
            raise ValueError(f"a {family} curve needs a shape parameter lam")
        lams = _lambdas(lam, cls, m, check_range)
    tables = [_float_matrix(cls._data, "centred", n, p).T for p in range(len(mats))]
    result = None if out is None else _checked_out(out, (m, tt.size, dim), scalar, points, arr, t)
    values = np.empty((m, tt.size, dim)) if result is None else result
    check_needed = extrapolate or not check_range  # else nothing can overflow
    if lams.ndim == 1 and m and (lams == lams[0]).all():
        lams = lams[0, ...]  # one λ for every curve (0-d): folded into the products' matrix
    _products_threaded(arr, tables, lams, tt, k, check_needed, values)
    if out is not None:
        return out
    return values[:, 0] if scalar else values


# Threads for evaluate_many's products: None for one per CPU this process may run on
# (os.sched_getaffinity), 1 for none. Each thread takes a slab of whole curves and runs
# _products_many on it (BLAS, numpy's passes and numba's magnitude test all release the GIL),
# so the page faults of a fresh result (the operating system zeroing its pages) are taken by
# the thread that writes them, and the arithmetic is split. Slabs are cut between the chunks
# of curves _products_many takes in one thread, so every BLAS call sees the same rows and the
# answers do not depend on the number of threads (BLAS's order of sums does depend on the
# rows it is given: one row takes its vector path).
THREADS: int | None = None
_MIN_SLAB = 1 << 20  # result elements a thread's slab at least gets: below, one thread


def _curve_chunks(m: int, per_curve: int) -> list[tuple[int, int]]:
    """_products_many's chunks of curves (a quarter of CHUNK_ELEMENTS each: at 10^5 quintics
    about 18 of them, so that slabs of whole chunks share the work between threads within a
    chunk, while a chunk's fixed cost stays small)."""
    return chunk_ranges(m, 4 * per_curve)


def _products_threaded(
    arr: np.ndarray,
    tables: list[np.ndarray],
    lams: np.ndarray,
    tt: np.ndarray,
    k: int,
    check_needed: bool,
    values: np.ndarray,
) -> None:
    """_products_many over slabs of curves, one per thread (THREADS). An error is the one
    the first failing slab raises, as the slabs run in order one thread after another."""
    m, size, dim = arr.shape
    chunks = _curve_chunks(m, size * dim)  # _products_many's chunks of curves
    workers = min(THREADS or alg.cpu_count(), values.size // _MIN_SLAB, len(chunks))
    if workers <= 1:
        _products_many(arr, tables, lams, tt, k, check_needed, values)
        return
    first = [lo for lo, _ in chunks] + [m]  # chunk j's first curve; m past the last

    def slab(a: int, b: int) -> None:
        lo, hi = first[a], first[b]
        part = lams[lo:hi] if lams.ndim else lams
        _products_many(arr[lo:hi], tables, part, tt, k, check_needed, values[lo:hi], lo)

    alg.on_threads(slab, len(chunks), workers)


def _products_many(
    arr: np.ndarray,
    tables: list[np.ndarray],
    lams: np.ndarray,
    tt: np.ndarray,
    k: int,
    check_needed: bool,
    values: np.ndarray,
    first: int = 0,
) -> None:
    """evaluate_many on the tables, into `values` (m, T, d), C-contiguous: each block of
    values is one matrix product written by BLAS straight into its place.

    Row j of values, flattened to T·d numbers, is c_j K: c_j the curve's coefficients of the
    k-th derivative in the centred monomials, flattened to (N+1-k)·d numbers, and K the
    monomials (t - 1/2)^e of the block's parameters, Kronecker with the d × d identity, so
    that the product's rows come out in the result's (T, d) order. With one table (the
    classical curve) or one λ for every curve, the tables fold into K as well: the product
    is then of the control points themselves, c_j never formed. The products are cut into
    blocks of fewer than 2^18 multiply-adds: working memory bounded at any m or T, and
    below OpenBLAS's threshold for threads (2^18 there), which on a loaded machine measured
    slower, not faster (up to 10x). Issue #29: this replaced a compiled Horner loop per
    curve (numba), which took more CPU time in the same runs (README, benchmark notes).

    `lams` holds one λ per curve (shape (m,)), or one λ for all (0-d, folded into K);
    `first` is the index of arr's first curve in the caller's batch (named in errors)."""
    m, size, dim = arr.shape
    total = tt.size
    # per table p, the map from a curve's flattened points to its flattened coefficients of
    # p^(k): kron(D_p, I_d), D_p (n+1, N+1-k) (at least one zero column past the degree)
    maps = [np.kron(differentiate_coefficients(tab.T, k), np.eye(dim)) for tab in tables]
    width = maps[0].shape[1]
    per_lam = lams.ndim == 1
    if not per_lam:
        folded = sum((maps[p] * float(lams) ** p for p in range(1, len(maps))), maps[0])
    inner = width if per_lam else size * dim
    # parameters per block: the block of K (inner × span·d numbers) stays in the L2 cache
    span = max(1, min(total, (alg.CHUNK_ELEMENTS // 4) // (inner * dim)))
    flat = values.reshape(m, total * dim)
    what = "p(t)" if k == 0 else f"the derivative of order {k}"
    compiled = alg.batch_compiled()  # numba's one-pass test of the curves' magnitudes
    for s0 in range(0, total, span):
        s1 = min(s0 + span, total)
        u = tt[s0:s1] - 0.5
        powers = np.empty((width // dim, s1 - s0))
        powers[0] = 1.0
        for e in range(1, width // dim):
            np.multiply(powers[e - 1], u, out=powers[e])
        basis = np.kron(powers, np.eye(dim)).reshape(width, (s1 - s0) * dim)
        product = basis if per_lam else folded @ basis
        # chunks of curves for the checks and the coefficients (a NumPy call has a fixed
        # cost: per product block it would be most of the time), each cut into the blocks
        # of the products
        for lo, hi in _curve_chunks(m, size * dim):
            # a curve with coordinates beyond 2^±900 is computed on its points scaled by a
            # power of two (exact), then scaled back, so a representable p(t) is not lost to
            # an overflow or underflow in the coefficients (each curve by its own magnitude)
            scales = (
                None
                if compiled is not None and compiled.odd_curves(arr[lo:hi]) == 0
                else _curve_scales(arr[lo:hi], first + lo)
            )
            part = arr[lo:hi].reshape(hi - lo, size * dim)  # a copy only if arr is strided
            if scales is not None:
                part = part / scales[:, None]
            block = flat[lo:hi, s0 * dim : s1 * dim]
            with val.overflow_allowed():
                if per_lam:
                    coeffs = part @ maps[0]
                    for p in range(1, len(maps)):
                        coeffs += (part @ maps[p]) * (lams[lo:hi] ** p)[:, None]
                    part = coeffs
                for a, b in chunk_ranges(hi - lo, product.size):
                    np.matmul(part[a:b], product, out=block[a:b])
                if scales is not None:
                    block *= scales[:, None]
            if scales is not None or check_needed:
                val.finite_result(block, what)


def _checked_out(
    out: object, shape: tuple[int, int, int], scalar: bool, *inputs: npt.ArrayLike
) -> np.ndarray:
    """`out` as the (m, T, d) array to write (a view of the (m, d) one for a scalar t), or
    a TypeError/ValueError naming what is wrong with it: numpy's `out=` rules, checked
    before anything is computed."""
    want = (shape[0], shape[2]) if scalar else shape
    if not isinstance(out, np.ndarray):
        raise TypeError(f"out must be a numpy array, got {type(out).__name__}")
    if out.dtype != np.float64:
        raise TypeError(f"out must have dtype float64, got {out.dtype}")
    if out.shape != want:
        raise ValueError(f"out must have the result's shape {want}, got shape {out.shape}")
    if not out.flags.c_contiguous:
        raise ValueError("out must be C-contiguous")
    if not out.flags.writeable:
        raise ValueError("out is read-only")
    if any(np.may_share_memory(out, x) for x in inputs):
        raise ValueError("out must not overlap the control points or t")
    return out.reshape(shape)


def _into(out: object, values: np.ndarray, *inputs: npt.ArrayLike) -> np.ndarray:
    """`values` (computed by a path that allocates its own result) copied into the
    checked `out`."""
    scalar = values.ndim == 2
    shape = (values.shape[0], 1, values.shape[1]) if scalar else values.shape
    target = _checked_out(out, shape, scalar, *inputs)
    target[...] = values.reshape(shape)
    return out  # type: ignore[return-value]


_ODD_HIGH, _ODD_LOW = 2.0**900, 2.0**-900  # _curve_scales' fast test (its exponents: 900)


def _curve_scales(part: np.ndarray, first: int) -> np.ndarray | None:
    """None when every curve of the chunk (the first is curve `first`) has ordinary
    coordinates, else the power of two per curve (1 for ordinary ones) that brings a curve
    with magnitudes beyond 2^±900 near 1 (`_validate.scale_for_magnitude`'s rule, per
    curve). A NaN or infinity is refused, named by its curve."""
    if part.size:
        # the common case first, in passes over the whole chunk (a maximum per curve of a
        # few coordinates is several times slower): every coordinate finite and below
        # 2^900, and none in (0, 2^-900), so that no curve's largest one is there either
        mag = np.abs(part)
        top = mag.max()
        if top < _ODD_HIGH and np.count_nonzero(mag) == np.count_nonzero(mag >= _ODD_LOW):
            return None
    big = np.abs(part).max(axis=(1, 2)) if part.shape[1] * part.shape[2] else np.zeros(0)
    if not np.isfinite(big).all():  # NaN propagates into the maximum
        idx = np.argwhere(~np.isfinite(part))[0]
        raise ValueError(
            f"curve {first + idx[0]}, control point {idx[1]} has a non-finite coordinate"
        )
    exponent = np.frexp(big)[1]
    odd = ((exponent > 900) | (exponent < -900)) & (big > 0)
    if not odd.any():
        return None
    return np.where(odd, np.ldexp(1.0, exponent - 1), 1.0)


def _de_casteljau_many(arr: np.ndarray, tt: np.ndarray, k: int, scalar: bool) -> np.ndarray:
    """evaluate_many for classical curves past the generated tables (and degree 0): de
    Casteljau on the k-th hodograph of every curve at once (the centred monomials are
    ill-conditioned at high degree; de Casteljau is not), chunk by chunk of curves. No
    overflow scaling is needed: every step is a convex combination, and the differences of
    the hodograph are formed on points scaled by a power of two."""
    m, size, dim = arr.shape
    n = size - 1
    out = np.empty((tt.size, m * dim))
    # the de Casteljau triangle holds (T, n+1, c·d) elements at its widest
    for lo, hi in chunk_ranges(m, tt.size * size * dim):
        part = arr[lo:hi]
        scales = _curve_scales(part, lo)
        work = part / scales[:, None, None] if scales is not None else part
        for order in range(k):  # p^(r+1) has the points (n - r)(P_{i+1} - P_i) of p^(r)
            if work.shape[1] == 1:
                work = np.zeros_like(work)
                break
            work = (n - order) * (work[:, 1:] - work[:, :-1])
        pts = np.ascontiguousarray(work.transpose(1, 0, 2)).reshape(work.shape[1], -1)
        block = out[:, lo * dim : hi * dim]
        with val.overflow_allowed():
            block[...] = alg.de_casteljau_steps(pts, tt, pts.shape[0] - 1)[:, 0]  # (T, c·d)
            if scales is not None:
                block *= np.repeat(scales, dim)
        val.finite_result(block, "p(t)" if k == 0 else f"the derivative of order {k}")
    values: np.ndarray = out.reshape(tt.size, m, dim).transpose(1, 0, 2)
    return values[:, 0] if scalar else values
