r"""Energy-optimal parameters of surfaces of several-parameter, indexed and
trigonometric/hyperbolic/mixed families: one net, and batches of nets.

**One net: certified, not a closed form.** For a given net the energy is a polynomial in
every parameter of both directions (param_surface_energy.energy_polynomial), with
coefficients in ℚ, or in ℚ[c, 1/c] for an atom family (c = π or e^W). One-parameter
polynomial families get the exact minimum (surface_optimum: the resultants of E_x and E_y,
exact real-root isolation). Here there is none, and the result says so (``method``
"certified"): a family with two or more parameters in a direction makes the interior critical
points the solutions of four or more polynomial equations (eliminating a direction's
parameters, which enter E quadratically, leaves two rational equations of high degree in the
other's, and every face of the box another such system), which the runtime cannot solve
exactly; an atom family with one parameter per direction has coefficients in ℚ(π) or ℚ(e^W),
so the resultants' roots are not algebraic over ℚ and the runtime has no exact arithmetic for
them. The minimum is then param_surface_energy's certified one: a rational point, its exact
energy, and a proven lower bound within 1e-12 (relative).

**A batch** of float nets, shape (k, m+1, n+1, d), with one parameter in each direction: the
energy's nine coefficients e_ab (x^a y^b, a, b <= 2) of every net at once, as weights on the
nets' Gram products P_ij · P_kl (each direction's Gram matrices in floats, the constant c at
its float, in Kronecker products); then the fixed-cost certificate of one-parameter surfaces.
With numba both run in the one-parameter surfaces' compiled kernel
(hazmat.surface_batch_compiled.optimise_batch, which takes any such weights: for large
batches the coefficients from straight-line code emitted for these weights,
hazmat.surface_coefficients_ir), else in numpy (one batched matrix product, then
hazmat.surface_certify.certified_minimum on arrays; LAMBDA_BEZIER_NO_NUMBA=1 selects it, and
the tests run both). The certificate (local strong convexity and a global clearing of the
rest of the box) puts the minimiser within 1e-12 of the answer, for the float coefficients;
where it declines, its fixed-cost edge certificate (surface_certify.edge_minimum) certifies
most minima on an edge or at a corner (``boundary`` then names the ends, as for one net).
Both decide a quadratic's positivity on an interval by its least value there (at_cubic's
E is only weakly convex across its box, and the quadratic's Bernstein coefficients, used
before, declined 1,533 of the 10,000 benchmark nets, not 372: see surface_certify's doc).
What both decline takes their retries, at a fixed cost too (surface_certify.retry_minimum:
a searched start, the sides cleared piece by piece or from a face; retry_edges: narrower
bands), which certify all 306 of at_cubic's benchmark nets the first two declined. What
they all decline takes the vectorised careful path below (_careful_batch), and what that
declines the one-net path.

The careful path, and the whole batch with two or more parameters in a direction (or none in
one; the fixed-cost certificate is for two variables): every net's coefficients at every
monomial of the parameters are computed at once (_monomial_weights, the same Kronecker
weights), a vectorised float search (a grid, then one-parameter sweeps: float_search) finds
each net's start, and hazmat.box_batch certifies all nets at once from there (local strong
convexity about a polished point, with its faces held where the gradient pushes outward and
its R cut at the faces, and a Bernstein clearing of the rest of the box, every net's
sub-boxes as rows of arrays): the minimiser within 1e-12 of the answer, for the float
coefficients. The nets it declines (two minima of nearly equal energy, a Hessian not
certified positive) take the one-net certified path started at its point, and are counted in
``careful_fallbacks``: that count is the number of nets solved one by one.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from fractions import Fraction
from functools import cache
from types import ModuleType
from typing import Any

import numpy as np

from . import _poly_direction as pd
from . import _validate as val
from .hazmat import box_batch
from .hazmat import surface_kernels as ker
from .hazmat.constants import constant_bounds
from .hazmat.surface_fixed_cost import fixed_cost_minimum
from .hazmat.surface_weights import pair_weights, plain_weights
from .param_surface_energy import (
    Direction,
    SurfaceParameterOptimum,
    _direction,
    _family_pair,
    _grams,
    named_point,
)
from .param_surface_energy import optimal_parameters as certified_parameters
from .surface_energies import ENERGIES, MAX_COORDINATE, check_net_values, moved_to_origin
from .surfaces import NetLike

CERTIFIED_TOLERANCE = 1e-12  # the batch certificate: the minimiser within this of its answer


def _directions(shape: tuple[int, ...], fu: Any, fv: Any) -> tuple[Direction, Direction]:
    m, n = int(shape[0]) - 1, int(shape[1]) - 1
    for fam, deg, name in ((fu, m, "u"), (fv, n, "v")):
        pd.checked_degree(fam, deg, name)
    return _direction(fu, m), _direction(fv, n)


def _builtin_named(family: Any) -> Any:
    """A pair with a built-in family named (or given as its curve class) in one direction:
    that direction as its curve class, beside any family from load_family (atom, several
    parameters or indexed) in the other, as `fam.surface(..., family_v="same_degree")`
    takes it."""
    if not isinstance(family, tuple | list) or len(family) != 2:
        return family
    if isinstance(family[0], str) and isinstance(family[1], str):
        return family  # two built-in names: surface_optimum's exact path, not this module
    return tuple(pd.polynomial_family(f) if isinstance(f, str) else f for f in family)


def _end_labels(points: np.ndarray, du: Direction, dv: Direction) -> np.ndarray:
    """The boundary note of every row of `points` (every parameter, u's then v's), as the
    one-net result says it: a coordinate equal to the float of an end of its range is that
    end exactly. The note depends only on which ends a row is at (a code in base 3), so
    named_point runs once per such pattern: for at most LABEL_TABLE patterns once per pair of
    families and degrees (_label_table, then one gather: 561 edge nets of at_cubic's
    benchmark batch, 0.12 ms before, when every call named its patterns again), else once
    per pattern present."""
    ranges = [du.ranges[x] for x in du.names] + [dv.ranges[x] for x in dv.names]
    code = np.zeros(points.shape[0], dtype=np.int64)
    for j, r in enumerate(ranges):
        at = np.where(points[:, j] == float(r[0]), 1, np.where(points[:, j] == float(r[1]), 2, 0))
        code += at * 3**j
    if 3 ** len(ranges) <= LABEL_TABLE:
        table = _label_table(du.family, du.degree, dv.family, dv.degree)
        labels: np.ndarray = table[code]
        return labels
    out = np.empty(points.shape[0], dtype=object)
    out[:] = ""
    for key in np.unique(code[code > 0]):
        out[code == key] = _pattern_label(du, dv, int(key))
    return out


LABEL_TABLE = 81  # _end_labels: up to this many patterns (four parameters) named at once


def _pattern_label(du: Direction, dv: Direction, key: int) -> str:
    """The boundary note of the pattern `key` (base 3, parameter j's digit: 0 inside, 1 at
    its lower end, 2 at its upper end)."""
    ranges = [du.ranges[x] for x in du.names] + [dv.ranges[x] for x in dv.names]
    digits = [(key // 3**j) % 3 for j in range(len(ranges))]
    point = tuple(
        Fraction(r[0]) if k == 1 else Fraction(r[1]) if k == 2 else 0.0
        for k, r in zip(digits, ranges, strict=True)
    )
    label: str = named_point(du, dv, point, exact=False)[1]
    return label


@cache
def _label_table(family_u: Any, m: int, family_v: Any, n: int) -> np.ndarray:
    """Every pattern's boundary note (_pattern_label), indexed by its code; "" for 0."""
    du, dv = _direction(family_u, m), _direction(family_v, n)
    size = 3 ** (len(du.names) + len(dv.names))
    table = np.empty(size, dtype=object)
    table[0] = ""
    for key in range(1, size):
        table[key] = _pattern_label(du, dv, key)
    table.setflags(write=False)
    return table


def _box(d: Direction) -> tuple[Fraction, Fraction]:
    lo, hi, *_ = d.ranges[d.names[0]]
    return Fraction(lo), Fraction(hi)


def optimal_parameters(
    net: NetLike, energy: str, family: Any
) -> SurfaceParameterOptimum | SurfaceParameterBatch:
    """The energy-optimal parameters of one net (certified) or of a batch of nets; see the
    module's doc."""
    energy = val.choice(energy, "energy", tuple(ENERGIES))
    fu, fv = _family_pair(_builtin_named(family))
    arr = np.asarray(val.real_array(net, "net"), dtype=float)
    if arr.ndim == 4:
        return optimal_parameters_batch(arr, energy, (fu, fv))
    out: SurfaceParameterOptimum = certified_parameters(net, energy, (fu, fv))
    return out


# ---------------------------------------------------------------------- batches
@dataclass(frozen=True)
class SurfaceParameterBatch(Mapping[str, Any]):
    """The optimal parameters of a batch of nets, by name (``r["lam_u"]``: an array of
    length k), ``energy`` at them (floats), ``boundary`` per net (the parameters at an end of
    their range, as the one-net result says it; "" inside), and how many nets the vectorised
    certificates declined (``careful_fallbacks``, solved one by one)."""

    parameters: dict[str, np.ndarray]
    energy: np.ndarray
    boundary: np.ndarray
    careful_fallbacks: int

    def __getitem__(self, key: str) -> Any:
        if key in self.parameters:
            return self.parameters[key]
        if key in ("energy", "boundary", "careful_fallbacks"):
            return getattr(self, key)
        raise KeyError(f"{key!r}: the parameters are {', '.join(self.parameters)}")

    def __iter__(self) -> Iterator[str]:
        return iter((*self.parameters, "energy", "boundary", "careful_fallbacks"))

    def __len__(self) -> int:
        return len(self.parameters) + 3


def _float_grams(d: Direction, k: int) -> dict[int, np.ndarray]:
    """{s: G} with G = Σ_{a+b=s} G_(a,b) in floats: the order-k Gram matrix at x^s of a
    direction of one parameter (the constant at its float)."""
    return {key[0]: mat for key, mat in _float_grams_by_monomial(d, k).items()}


def _float_grams_by_monomial(d: Direction, k: int) -> dict[tuple[int, ...], np.ndarray]:
    """{e: G} with G = Σ_{a+b=e} G_(a,b) in floats: the order-k Gram matrix at the monomial
    x^e of a direction's parameters (the constant at its float)."""
    c = 1.0
    if d.constant is not None:
        lo, hi = constant_bounds(d.constant, 64)
        c = float((lo + hi) / 2)
    out: dict[tuple[int, ...], np.ndarray] = {}
    for (a, b), mat in d.grams(k).items():
        key = tuple(x + y for x, y in zip(a, b, strict=True))
        dense = np.array([[sum(float(v) * c**e for e, v in g.items()) for g in row] for row in mat])
        out[key] = out.get(key, 0.0) + dense
    return out


def energy_weights(du: Direction, dv: Direction, energy: str) -> dict[tuple[int, int], np.ndarray]:
    """{(a, b): K} with e_ab = Σ K[ij, kl] P_ij · P_kl: the weight of x^a y^b on the Gram
    products of a net read row by row, Σ_terms weight · G^(a)_u ⊗ G^(b)_v (floats; computed
    once per pair of families and degrees)."""
    return _energy_weights(du.family, du.degree, dv.family, dv.degree, energy)


@cache
def _energy_weights(
    family_u: Any, m: int, family_v: Any, n: int, energy: str
) -> dict[tuple[int, int], np.ndarray]:
    du, dv = _direction(family_u, m), _direction(family_v, n)
    out: dict[tuple[int, int], np.ndarray] = {}
    for ku, kv, weight in ENERGIES[energy]:
        gu, gv = _float_grams(du, ku), _float_grams(dv, kv)
        for a, mat_u in gu.items():
            for b, mat_v in gv.items():
                out[(a, b)] = out.get((a, b), 0.0) + float(weight) * np.kron(mat_u, mat_v)
    return out


@cache
def _batch_weights(family_u: Any, m: int, family_v: Any, n: int, energy: str) -> Any:
    """energy_weights in the compiled kernels' form (hazmat.surface_weights.plain_weights),
    once per pair of families, degrees and energy: optimise_batch finds its emitted code by
    the weights' identity (no 12 kB key hashed per call)."""
    weights = _energy_weights(family_u, m, family_v, n, energy)
    size = next(iter(weights.values())).shape[0]
    forms = {3 * a + b: w for (a, b), w in weights.items()}
    return plain_weights(*pair_weights(forms, size))


def energy_coefficients(nets: np.ndarray, du: Direction, dv: Direction, energy: str) -> Any:
    """{(a, b): e_ab over the batch}: the energy of every net as Σ e_ab x^a y^b (floats): the
    nets' Gram products P_ij · P_kl (one batched matrix product) against each weight."""
    weights = energy_weights(du, dv, energy)
    count = nets.shape[0]
    flat = nets.reshape(count, -1, nets.shape[-1])
    with np.errstate(over="ignore", invalid="ignore"):
        gram = np.matmul(flat, flat.transpose(0, 2, 1)).reshape(count, -1)
        keys = sorted(weights)
        stacked = np.stack([weights[key].ravel() for key in keys], axis=1)
        values = gram @ stacked
    return {key: values[:, i] for i, key in enumerate(keys)}


def _batch_compiled() -> ModuleType | None:
    """hazmat.surface_batch_compiled (numba; the switch of hazmat.surface_kernels), or None."""
    if not ker.USE_COMPILED:
        return None
    from .hazmat import surface_batch_compiled

    return surface_batch_compiled


def fixed_cost(
    nets: np.ndarray, du: Direction, dv: Direction, energy: str
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(x, y, energy, certified, on_edge) of every net by the fixed-cost certificate and, where
    that declines, its edge_minimum and their retries (compiled with the coefficients when
    numba is there, else numpy); certified False where all decline, on_edge True where an
    edge one certified."""
    return _fixed_cost(nets, du, dv, energy)[:5]


def _fixed_cost(
    nets: np.ndarray, du: Direction, dv: Direction, energy: str
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, bool | None]:
    """fixed_cost's answers and whether every coordinate was finite and within
    MAX_COORDINATE (the compiled kernel notes it as it reads the nets; None where nothing
    read them: the caller checks)."""
    count = nets.shape[0]
    (xlo, xhi), (ylo, yhi) = _box(du), _box(dv)
    weights = energy_weights(du, dv, energy)
    box = np.array([float(xlo), float(xhi), float(ylo), float(yhi)])
    fast = _batch_compiled()
    if max(max(a, b) for a, b in weights) > 2:  # not affine: the certificate is for degree 2
        bx, by, bval, ok = np.zeros(count), np.zeros(count), np.zeros(count), np.zeros(count, bool)
        return bx, by, bval, ok, np.zeros(count, bool), None
    if fast is not None:  # the one-parameter surfaces' compiled kernel, on these weights
        flat = np.ascontiguousarray(nets.reshape(count, -1), dtype=float)
        bx, by, bval, _, status, valid = fast.optimise_batch(
            flat,
            nets.shape[-1],
            _batch_weights(du.family, du.degree, dv.family, dv.degree, energy),
            box,
            CERTIFIED_TOLERANCE,
            MAX_COORDINATE,
        )
        return bx, by, bval, status > 0.5, status > 1.5, bool(valid)
    coeffs = energy_coefficients(nets, du, dv, energy)
    zero = np.zeros(count)
    c = [coeffs.get((a, b), zero) for a in range(3) for b in range(3)]
    return (*fixed_cost_minimum(c, box, CERTIFIED_TOLERANCE), None)


@cache
def _differences_only(fu: Any, du: int, fv: Any, dv: int, energy: str) -> bool:
    """Whether the energy depends on the net's differences alone (E(P + c) = E(P)): every
    Gram matrix of a derivative it takes, in each direction, has zero row sums exactly (each
    term of ENERGIES differentiates at least one direction). True where each direction's
    basis sums to a constant for every parameter value; decided once per families, degrees
    and energy."""
    orders = {a for a, _, _ in ENERGIES[energy]} | {b for _, b, _ in ENERGIES[energy]}
    for family, degree in ((fu, du), (fv, dv)):
        for k in sorted(orders - {0}):
            for mat in _grams(family, degree, k).values():
                for row in mat:
                    total: dict[int, Fraction] = {}
                    for entry in row:
                        for power, c in entry.items():
                            total[power] = total.get(power, Fraction(0)) + c
                    if any(total.values()):
                        return False
    return True


def optimal_parameters_batch(nets: np.ndarray, energy: str, family: Any) -> SurfaceParameterBatch:
    """optimal_parameters for (k, m+1, n+1, d) float nets; see the module's doc."""
    energy = val.choice(energy, "energy", tuple(ENERGIES))
    fu, fv = _family_pair(family)
    if nets.ndim != 4 or nets.shape[0] == 0:
        raise ValueError(f"a batch of nets must have shape (k, m+1, n+1, d), got {nets.shape}")
    du, dv = _directions(nets.shape[1:], fu, fv)
    if len(du.names) != 1 or len(dv.names) != 1:
        check_net_values(nets)
        if not du.names and not dv.names:
            raise ValueError("net: neither direction has a shape parameter: nothing to optimise")
        return _several_batch(nets, energy, (fu, fv), du, dv)
    count = nets.shape[0]
    given, fast = nets, _batch_compiled()
    if fast is None:
        check_net_values(nets)
    if _differences_only(du.family, du.degree, dv.family, dv.degree, energy):
        nets = moved_to_origin(nets, fast)  # far nets: the floats cancel less
    bx, by, bval, ok, on_edge, valid = _fixed_cost(nets, du, dv, energy)
    if not valid:  # the compiled kernel's reading of the nets (0.17 ms saved), or no reading
        check_net_values(given)  # raises the error that fits
        check_net_values(nets)  # a moved net spanning more than MAX_COORDINATE
    boundary = np.empty(count, dtype=object)
    boundary[:] = ""
    edge = np.flatnonzero(on_edge)  # certified on an edge or at a corner: name the ends
    boundary[edge] = _end_labels(np.stack([bx[edge], by[edge]], axis=1), du, dv)
    declined = np.flatnonzero(~ok)
    fallbacks = 0
    if declined.size:  # the vectorised certificate, then the one-net path for what it declines
        rest = _careful_batch(nets[declined], energy, (fu, fv), du, dv)
        bx[declined], by[declined] = rest.values[:, 0], rest.values[:, 1]
        bval[declined], boundary[declined] = rest.energy, rest.boundary
        fallbacks = rest.fallbacks
    values = {f"{du.names[0]}_u": bx, f"{dv.names[0]}_v": by}
    return SurfaceParameterBatch(values, bval, boundary, fallbacks)


@dataclass(frozen=True)
class _Careful:
    """_careful_batch's answer: every parameter (u's then v's) as the columns of `values`,
    the energy, the boundary note, and how many nets took the one-net path."""

    values: np.ndarray
    energy: np.ndarray
    boundary: np.ndarray
    fallbacks: int


def _careful_batch(
    nets: np.ndarray, energy: str, family: tuple[Any, Any], du: Direction, dv: Direction
) -> _Careful:
    """The certified minima of a batch of nets by the vectorised careful path, for any
    number of parameters a direction: every net's coefficient at every monomial of the
    parameters at once (one batched product with _monomial_weights), a vectorised float
    search (float_search), the vectorised certificate (hazmat.box_batch: local strong
    convexity about the polished point, a face held where the gradient pushes outward, and a
    Bernstein clearing of the rest of the box), and the nets it declines certified one by one
    by the one-net path started at its point (counted in ``fallbacks``). A parameter ending
    on an end of its range is that end exactly, named as the one-net path names it."""
    count = nets.shape[0]
    exponents, weights = _monomial_weights(du.family, du.degree, dv.family, dv.degree, energy)
    flat = nets.reshape(count, -1, nets.shape[-1])
    with np.errstate(over="ignore", invalid="ignore"):
        gram = np.matmul(flat, flat.transpose(0, 2, 1)).reshape(count, -1)
        # in blocks of rows under OpenBLAS's threshold for threads (as float_search's): at
        # 372 at_cubic nets, (372, 256) @ (256, 9) took 11 ms wall and 3.2 ms CPU on its
        # threads at load 6, against about 0.1 ms on one
        coeffs = np.empty((count, weights.shape[1]))
        rows = max(1, 2**18 // max(1, weights.size))
        for a in range(0, count, rows):
            np.matmul(gram[a : a + rows], weights, out=coeffs[a : a + rows])
    ranges = [du.ranges[x] for x in du.names] + [dv.ranges[x] for x in dv.names]
    lo = np.array([float(r[0]) for r in ranges])
    hi = np.array([float(r[1]) for r in ranges])
    starts = float_search(coeffs, exponents, lo, hi)
    bx, bval, _, ok = box_batch.certified_minimum(  # bx: polished, a better one-net start
        coeffs, exponents, lo, hi, starts, CERTIFIED_TOLERANCE
    )
    values = bx.copy()
    boundary = _end_labels(bx, du, dv)  # ends named exactly, as one net's are
    for i in np.flatnonzero(~ok):
        try:
            one = certified_parameters(nets[i], energy, family, start=tuple(bx[i]))
        except ValueError as exc:  # the budget ran out: say which net
            raise ValueError(f"net {i} of the batch: {exc}") from None
        values[i] = [x for v in one.parameters.values() for x in np.ravel(v)]
        bval[i], boundary[i] = float(one.energy), one.boundary
    # E is an integral of squares: a float value below 0 is rounding (an infimum of 0 at
    # a degenerate end, as at_pi_cubic's at lam = 1), and 0 is nearer the truth
    return _Careful(values, np.maximum(bval, 0.0), boundary, int(np.count_nonzero(~ok)))


# ---------------------------------------------------------------------- several parameters
@cache
def _monomial_weights(
    family_u: Any, m: int, family_v: Any, n: int, energy: str
) -> tuple[np.ndarray, np.ndarray]:
    """(exponents, weights): the energy's monomials x^e in every parameter (u's then v's) as
    rows of `exponents` (K, P), and their weights on the Gram products P_ij · P_kl of a net
    read row by row as the columns of `weights` (N², K): Σ_terms weight · G_u ⊗ G_v per pair
    of each direction's monomials (floats, the constants at their floats; computed once per
    pair of families and degrees)."""
    du, dv = _direction(family_u, m), _direction(family_v, n)
    acc: dict[tuple[int, ...], np.ndarray] = {}
    for ku, kv, weight in ENERGIES[energy]:
        gu, gv = _float_grams_by_monomial(du, ku), _float_grams_by_monomial(dv, kv)
        for a, mat_u in gu.items():
            for b, mat_v in gv.items():
                key = (*a, *b)
                acc[key] = acc.get(key, 0.0) + float(weight) * np.kron(mat_u, mat_v)
    keys = sorted(acc)
    exponents = np.array(keys, dtype=np.int64).reshape(len(keys), len(du.names) + len(dv.names))
    return exponents, np.stack([acc[key].ravel() for key in keys], axis=1)


def _monomials(points: np.ndarray, exponents: np.ndarray) -> np.ndarray:
    """x^e for every point (rows of `points`, (G, P)) and exponent row: (G, K)."""
    out = np.ones((points.shape[0], exponents.shape[0]))
    for j in range(exponents.shape[1]):
        out *= points[:, j : j + 1] ** exponents[None, :, j]
    return out


def float_search(
    coeffs: np.ndarray, exponents: np.ndarray, lo: np.ndarray, hi: np.ndarray, sweeps: int = 8
) -> np.ndarray:
    """A float minimiser of Σ_K coeffs[:, K] x^exponents[K] over the box [lo, hi] for every
    row of `coeffs` at once: the best point of a grid, then `sweeps` rounds of exact
    minimisation in one parameter at a time, clipped to the box (E is quadratic in each
    parameter of an affine family; a parameter of higher degree keeps its grid value). Where
    a parameter is quadratic (the last such), the grid is over the others only, about
    4096^((P-1)/P) points, with that parameter minimised exactly at each (its quadratic's
    vertex clipped to its range, or an end): for two parameters, 64 values of one and the
    exact best of the other, where a 64 × 64 grid took 64 times the work. Only a start for
    the certified path: nothing here is certified."""
    count, dims = coeffs.shape[0], exponents.shape[1]
    side = max(3, int(round(4096 ** (1 / dims))))
    quadratic = [j for j in range(dims) if exponents[:, j].max() <= 2]
    along = quadratic[-1] if quadratic else None  # minimised exactly at each grid point
    gridded = [j for j in range(dims) if j != along]
    axes = [np.linspace(lo[j], hi[j], side) for j in gridded]
    mesh = np.meshgrid(*axes, indexing="ij") if axes else []
    grid = np.zeros((int(np.prod([side] * len(gridded))), dims))
    for j, g in zip(gridded, mesh, strict=True):
        grid[:, j] = g.ravel()
    if along is None:
        powers = [(np.ones(exponents.shape[0], bool), _monomials(grid, exponents))]
    else:  # the monomials of the other parameters, by the power of this one
        rest = exponents.copy()
        rest[:, along] = 0
        mono = _monomials(grid, rest)
        powers = [(exponents[:, along] == e, mono) for e in range(3)]
    points = np.empty((count, dims))
    # blocks of products under 2^18 multiply-adds: OpenBLAS's threshold for threads, which
    # on a loaded machine measured 13-30x slower than one thread here
    width = sum(int(mask.sum()) for mask, _ in powers) * grid.shape[0]
    block = max(1, 2**18 // max(1, width))
    for first in range(0, count, block):
        part = coeffs[first : first + block]
        terms = [part[:, mask] @ mono[:, mask].T for mask, mono in powers]
        if along is None:
            best = np.argmin(terms[0], axis=1)
            points[first : first + block] = grid[best]
            continue
        a0, a1, a2 = terms
        lo_j, hi_j = lo[along], hi[along]
        with np.errstate(divide="ignore", invalid="ignore"):
            vertex = np.where(a2 > 0, -a1 / (2 * a2), lo_j)
        vertex = np.clip(np.nan_to_num(vertex, nan=lo_j), lo_j, hi_j)
        ends = (np.full(a0.shape, lo_j), np.full(a0.shape, hi_j), vertex)
        values = np.stack([a0 + (a1 + a2 * t) * t for t in ends])
        pick = np.argmin(values, axis=0)
        t = np.choose(pick, ends)
        best = np.argmin(np.take_along_axis(values, pick[None], 0)[0], axis=1)
        rows = np.arange(part.shape[0])
        chosen = grid[best]
        chosen[:, along] = t[rows, best]
        points[first : first + block] = chosen
    for _ in range(sweeps):
        for j in range(dims):
            if exponents[:, j].max() > 2:
                continue
            others = np.ones_like(coeffs)
            for i in range(dims):
                if i != j:
                    others *= points[:, i : i + 1] ** exponents[None, :, i]
            terms = coeffs * others
            a0, a1, a2 = (terms[:, exponents[:, j] == e].sum(axis=1) for e in range(3))
            with np.errstate(divide="ignore", invalid="ignore"):
                vertex = np.where(a2 > 0, -a1 / (2 * a2), lo[j])
            cands = np.stack([np.full(count, lo[j]), np.full(count, hi[j]), vertex], axis=1)
            cands = np.clip(np.nan_to_num(cands, nan=lo[j]), lo[j], hi[j])
            q = a0[:, None] + a1[:, None] * cands + a2[:, None] * cands**2
            points[:, j] = cands[np.arange(count), np.argmin(q, axis=1)]
    return points


def _several_batch(
    nets: np.ndarray, energy: str, family: tuple[Any, Any], du: Direction, dv: Direction
) -> SurfaceParameterBatch:
    """A batch with two or more parameters in a direction (or none in one): every net by
    _careful_batch (the fixed-cost certificate is for two variables)."""
    rest = _careful_batch(nets, energy, family, du, dv)
    arrays: dict[str, np.ndarray] = {}
    k = 0
    for d, suffix in ((du, "u"), (dv, "v")):
        width = len(d.names)
        if d.indexed is not None:  # one name, every net's values as a row
            arrays[f"{d.indexed}_{suffix}"] = rest.values[:, k : k + width]
        else:
            for j, x in enumerate(d.names):
                arrays[f"{x}_{suffix}"] = rest.values[:, k + j]
        k += width
    return SurfaceParameterBatch(arrays, rest.energy, rest.boundary, rest.fallbacks)
