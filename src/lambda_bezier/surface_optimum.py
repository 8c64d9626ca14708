"""Energy-optimal (λ_u, λ_v): `optimal_parameters` for one net (exact, through
surface_energies) or for a batch of float nets, vectorised.

A batch first takes the fixed-cost certified minimum (hazmat.surface_certify: start, Newton,
local strong convexity and a global clearing of the rest of the box; compiled with the
coefficients in hazmat.surface_batch_compiled). The nets it declines take its fixed-cost
certificate of edge and corner minima (surface_certify.edge_minimum). Only the nets both
decline (minima near an edge or a corner but not on it, or not convex enough about the
minimum) take the careful path below, counted in ``careful_fallbacks``.

The careful path. For families affine in λ the energy of one net is
E(x, y) = Σ_{a,b<=2} e_ab x^a y^b. Over the box its minimum is at a corner, on an edge (a
quadratic in one variable: closed form), or at an interior critical point: with
E_x = α(y) x + β(y) and E_y = γ(y) x² + δ(y) x + ε(y), the interior ones have y a root of
R(y) = γβ² − δαβ + εα² (the resultant, degree <= 5) and x = −β/α. The roots of R come from
the eigenvalues of its companion matrices, all nets at once, and are polished by Newton on ∇E = 0.

With numba installed (the `fast` extra) the same method runs compiled, one pass per net
(hazmat.surface_compiled: the resultant's roots by its derivative chain instead of
eigenvalues); set LAMBDA_BEZIER_NO_NUMBA=1, or hazmat.surface_kernels.USE_COMPILED = False,
for this numpy version. Both are tested against each other and against the exact method.

Certification: a net's answer is accepted when the winning point is a corner or an edge
minimum (closed forms), or an interior point whose last Newton step is below 1e-13 (quadratic
convergence: the point is within about that of the critical point) with a positive definite
Hessian; and the best energy beats every other candidate at a distinct point by a clear margin;
and no root of R was near the real axis without being on it. Every other net (and every net of
a family with λ² terms) is solved again by the exact method on the floats' exact rational
values; ``exact_fallbacks`` counts them.
"""

from __future__ import annotations

from fractions import Fraction
from functools import cache
from types import ModuleType
from typing import Any, cast

import numpy as np

from . import _validate as val
from .energy import optimal_parameters as curve_optimal_parameters
from .hazmat import surface_kernels as ker
from .hazmat.surface_fixed_cost import fixed_cost_minimum
from .hazmat.surface_kernels import OPTIMUM_STEP_TOLERANCE
from .hazmat.surface_weights import BatchWeights, batch_weights, pair_weights
from .parameter_optimum import OptimalParameters as CurveOptimalParameters
from .surface_energies import (
    ENERGIES,
    MAX_COORDINATE,
    SurfaceEnergyMatrices,
    SurfaceOptimalParameters,
    _box,
    _exact_optimum,
    _float_polynomial,
    _param_families,
    check_net_values,
    moved_to_origin,
)
from .surface_energies import surface_energy as _one_parameter_energy
from .surface_energies import surface_energy_matrices as _one_parameter_matrices
from .surfaces import NetLike, _as_family_pair, _as_net, _exact_net, basis_to_bernstein_split

STEP_TOLERANCE = OPTIMUM_STEP_TOLERANCE
# the fixed-cost path accepts a net when the minimiser is certified within this of its answer
CERTIFIED_TOLERANCE = 1e-12
_WHERE = np.array(["edge", "interior", "corner"], dtype=object)  # the compiled kernel's codes


def _compiled() -> ModuleType | None:
    """The compiled kernels (hazmat.surface_kernels.USE_COMPILED decides), or None."""
    return ker.compiled()


def _batch_compiled() -> ModuleType | None:
    """The compiled fixed-cost batch optimum (the same switch), or None."""
    if not ker.USE_COMPILED:
        return None
    from .hazmat import surface_batch_compiled  # numba compiles (or loads its cache) here

    return surface_batch_compiled


@cache
def _pair_weights(mats: SurfaceEnergyMatrices) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The energy matrices as weights of the Gram products g_ij = P_i · P_j, i <= j:
    (pair_i, pair_j, W) with E = Σ_p W[p, 3a + b] g_p λ_u^a λ_v^b (surface_weights)."""
    size = len(next(iter(mats.full.values())))
    return pair_weights({3 * a + b: q for (a, b), q in mats.full.items()}, size)


@cache
def _batch_weights(mats: SurfaceEnergyMatrices, u_cls: Any, v_cls: Any, dim: int) -> BatchWeights:
    """The energy for the compiled batch kernel, in the basis where each direction's
    λ-part is sparse (hazmat.surface_weights)."""
    m, n = mats.degrees
    u_split, v_split = basis_to_bernstein_split(u_cls, m), basis_to_bernstein_split(v_cls, n)
    return batch_weights(
        mats.full,
        u_split[1] if len(u_split) > 1 else None,
        v_split[1] if len(v_split) > 1 else None,
        (m + 1, n + 1),
        dim,
    )


@cache
def _depends_on_differences(mats: SurfaceEnergyMatrices) -> bool:
    """Whether every Q_ab has zero row sums, so that E(P + c) = E(P) for every point c (each
    direction's basis sums to a constant): decided exactly, once per energy."""
    return all(sum(row) == 0 for q in mats.full.values() for row in q)


def _centred(
    nets: np.ndarray, mats: SurfaceEnergyMatrices, fast: ModuleType | None = None
) -> np.ndarray:
    """The nets moved to the origin where that sharpens their floats (`moved_to_origin`),
    where the energy allows it (it depends on the net's differences alone)."""
    return moved_to_origin(nets, fast) if _depends_on_differences(mats) else nets


@cache
def _batch_setup(
    u_cls: Any, v_cls: Any, degrees: tuple[int, int], energy: str
) -> tuple[SurfaceEnergyMatrices, Any, Any, np.ndarray | None, int]:
    """What a batch needs besides its nets, once per families, degrees and energy (about
    10 µs a call otherwise): the energy matrices, each direction's exact box, the box as
    floats (xlo, xhi, ylo, yhi; None where a direction has no λ) and the highest power of
    λ_u or λ_v in the energy."""
    mats = _one_parameter_matrices(degrees, energy, (u_cls, v_cls))
    u_box, v_box = _box(u_cls), _box(v_cls)
    top = max(max(a, b) for a, b in mats.full)
    if u_box is None or v_box is None:
        return mats, u_box, v_box, None, top
    box = np.array([float(u_box[0]), float(u_box[1]), float(v_box[0]), float(v_box[1])])
    # shared by every call and written by none (writeable all the same: numba would compile
    # its kernels again for a read-only array type)
    return mats, u_box, v_box, box, top


def _polymul(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Products of polynomials over a batch: (k, p) x (k, q) -> (k, p + q - 1), low first."""
    out = np.zeros((a.shape[0], a.shape[1] + b.shape[1] - 1))
    for i in range(a.shape[1]):
        out[:, i : i + b.shape[1]] += a[:, i : i + 1] * b
    return out


def _energy_at(e: np.ndarray, x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """E at (x, y), with e (k, 3, 3) and x, y (k, c)."""
    px = np.stack([np.ones_like(x), x, x * x], axis=-1)
    py = np.stack([np.ones_like(y), y, y * y], axis=-1)
    out: np.ndarray = np.einsum("kca,kab,kcb->kc", px, e, py)
    return out


def _edge_minima(
    c0: np.ndarray, c1: np.ndarray, c2: np.ndarray, lo: float, hi: float
) -> np.ndarray:
    """argmin of c0 + c1 t + c2 t² over [lo, hi] (an end where the quadratic is not convex)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.where(c2 > 0, -c1 / (2 * c2), lo)
    out: np.ndarray = np.clip(np.nan_to_num(t, nan=lo), lo, hi)
    return out


def optimal_parameters_batch(
    nets: np.ndarray, energy: str, family: object
) -> SurfaceOptimalParameters:
    """optimal_parameters for (k, m+1, n+1, d) float nets; arrays of length k in every field.

    Every net first takes the fixed-cost certified minimum (hazmat.surface_certify; compiled
    in hazmat.surface_batch_compiled with the coefficients when numba is there), then the
    nets it declines its edge_minimum; the nets both decline go to `_careful_batch`
    (``careful_fallbacks`` counts them, ``exact_fallbacks`` those of them the exact method
    then solves)."""
    u_cls, v_cls = _as_family_pair(family)
    if nets.ndim != 4 or nets.shape[0] == 0:
        raise ValueError(f"a batch of nets must have shape (k, m+1, n+1, d), got {nets.shape}")
    count, m1, n1, dim = nets.shape
    classes: tuple[Any, Any] = (u_cls, v_cls)  # hashable: classes hash by identity
    mats, u_box, v_box, box, top = _batch_setup(*classes, (m1 - 1, n1 - 1), energy)
    fast = _batch_compiled()
    if box is None or top > 2 or fast is None:
        check_net_values(nets)
    if box is None or top > 2:
        return _all_exact(nets, np.ones(count, bool), None, energy, u_box, v_box, u_cls, v_cls)
    work = _centred(nets, mats, fast)  # the floats' work; the exact fallbacks take `nets` as given
    if fast is not None:
        weights = _batch_weights(mats, *classes, dim)
        flat = np.ascontiguousarray(work.reshape(count, m1 * n1 * dim), dtype=float)
        bx, by, bval, _, status, valid = fast.optimise_batch(
            flat, dim, weights, box, CERTIFIED_TOLERANCE, MAX_COORDINATE
        )
        if not valid:
            check_net_values(nets)  # raises the error that fits
            check_net_values(work)  # a net spanning more than MAX_COORDINATE
        # the status codes straight to indices (no boolean arrays between: 10,000 nets, 8 µs)
        declined, edge = np.flatnonzero(status == 0.0), np.flatnonzero(status == 2.0)
    else:
        check_net_values(work)
        coeffs = _float_polynomial(mats, work.reshape(count, m1 * n1, dim))
        zero = np.zeros(count)  # a power λ_u^a λ_v^b the energy lacks
        c = [coeffs.get((a, b), zero) for a in range(3) for b in range(3)]
        bx, by, bval, ok, on_edge = fixed_cost_minimum(c, box, CERTIFIED_TOLERANCE)
        declined, edge = np.flatnonzero(~ok), np.flatnonzero(on_edge)
    where = np.empty(count, dtype=object)
    where[:] = "interior"  # (np.full of a str into an object array is 6x slower)
    admissible, free_u, free_v = np.ones(count, bool), np.zeros(count, bool), np.zeros(count, bool)
    if edge.size:  # certified on an edge or at a corner (edge_minimum)
        ex, ey = bx[edge], by[edge]
        at_x = (ex == box[0]) | (ex == box[1])
        at_y = (ey == box[2]) | (ey == box[3])
        where[edge] = _WHERE[2 * (at_x & at_y)]  # "corner" or "edge", no str array between
        admissible[edge] = _admissible(ex, u_box) & _admissible(ey, v_box)
    exact = 0
    if declined.size:
        rest = _careful_batch(
            work[declined], energy, mats, u_box, v_box, u_cls, v_cls, nets[declined]
        )
        bx[declined], by[declined], bval[declined] = rest.lam_u, rest.lam_v, rest.energy
        where[declined], admissible[declined] = rest.where, rest.admissible
        free_u[declined], free_v[declined] = rest.free_u, rest.free_v
        exact = rest.exact_fallbacks
    return SurfaceOptimalParameters(
        bx, by, bx, by, bval, where, admissible, free_u, free_v, exact, int(declined.size)
    )


def _careful_batch(
    nets: np.ndarray,
    energy: str,
    mats: SurfaceEnergyMatrices,
    u_box: Any,
    v_box: Any,
    u_cls: Any,
    v_cls: Any,
    exact_nets: np.ndarray | None = None,
) -> SurfaceOptimalParameters:
    """The careful path for nets the fixed-cost certificate declined: every candidate (corners,
    edge minima, the interior critical points from the resultant's roots), with its own
    certificate, and the exact method where that declines too (on `exact_nets`, the nets as
    given, when `nets` were centred)."""
    given = nets if exact_nets is None else exact_nets
    count, m1, n1, dim = nets.shape
    flat = np.ascontiguousarray(nets.reshape(count, m1 * n1, dim))
    compiled = _compiled()
    if compiled is not None:
        box = np.array([float(u_box[0]), float(u_box[1]), float(v_box[0]), float(v_box[1])])
        pair_i, pair_j, weights = _pair_weights(mats)
        bx, by, bval, kind, unsure = compiled.optimise(
            flat, pair_i, pair_j, weights, box, STEP_TOLERANCE
        )
        result = {
            "lam_u": bx,
            "lam_v": by,
            "energy": bval,
            "where": _WHERE[kind],
            "admissible": _admissible(bx, u_box) & _admissible(by, v_box),
        }
        return _all_exact(given, unsure, result, energy, u_box, v_box, u_cls, v_cls)
    coeffs = _float_polynomial(mats, flat)
    e = np.zeros((count, 3, 3))
    for (a, b), c in coeffs.items():
        e[:, a, b] = c
    xlo, xhi = float(u_box[0]), float(u_box[1])
    ylo, yhi = float(v_box[0]), float(v_box[1])
    xs, ys, kinds = [], [], []
    for x0 in (xlo, xhi):  # edges x = x0 (with their corners)
        cb = np.einsum("kab,a->kb", e, np.array([1.0, x0, x0 * x0]))
        edge = _edge_minima(cb[:, 0], cb[:, 1], cb[:, 2], ylo, yhi)
        for y in (np.full(count, ylo), np.full(count, yhi), edge):
            xs.append(np.full(count, x0))
            ys.append(y)
            kinds.append(0)
    for y0 in (ylo, yhi):
        ca = np.einsum("kab,b->ka", e, np.array([1.0, y0, y0 * y0]))
        xs.append(_edge_minima(ca[:, 0], ca[:, 1], ca[:, 2], xlo, xhi))
        ys.append(np.full(count, y0))
        kinds.append(0)
    # interior: the resultant in y, its roots, then x = -β/α and Newton
    alpha = 2 * e[:, 2, :]
    beta = e[:, 1, :]
    gamma = np.stack([e[:, 2, 1], 2 * e[:, 2, 2]], axis=1)
    delta = np.stack([e[:, 1, 1], 2 * e[:, 1, 2]], axis=1)
    eps = np.stack([e[:, 0, 1], 2 * e[:, 0, 2]], axis=1)
    res = (
        _polymul(gamma, _polymul(beta, beta))
        - _polymul(delta, _polymul(alpha, beta))
        + _polymul(eps, _polymul(alpha, alpha))
    )  # (k, 6)
    size = np.abs(res).max(axis=1)
    lead = res[:, 5]
    suspect = ~(np.abs(lead) > 1e-9 * size)
    with np.errstate(divide="ignore", invalid="ignore"):
        monic = res[:, :5] / np.where(suspect, 1.0, lead)[:, None]
    comp = np.zeros((count, 5, 5))
    comp[:, 1:, :-1] = np.eye(4)
    comp[:, :, -1] = -monic
    roots = np.linalg.eigvals(np.nan_to_num(comp))
    imag = np.abs(roots.imag)
    real = roots.real
    scale = 1 + np.abs(real)
    is_real = imag <= 1e-7 * scale
    suspect |= ((imag > 1e-7 * scale) & (imag < 1e-3 * scale)).any(axis=1)
    iy = np.where(is_real, real, np.nan)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        a_y = alpha[:, :1] + alpha[:, 1:2] * iy + alpha[:, 2:3] * iy * iy
        b_y = beta[:, :1] + beta[:, 1:2] * iy + beta[:, 2:3] * iy * iy
        ix = -b_y / a_y
        steps = np.full(ix.shape, np.inf)
        posdef = np.zeros(ix.shape, bool)
        for _ in range(4):
            gx, gy, hxx, hxy, hyy = _derivatives(e, ix, iy)
            det = hxx * hyy - hxy * hxy
            dx = (hyy * gx - hxy * gy) / det
            dy = (hxx * gy - hxy * gx) / det
            ix, iy = ix - dx, iy - dy
            steps = np.maximum(np.abs(dx), np.abs(dy)) / (1 + np.abs(ix) + np.abs(iy))
            posdef = (hxx > 0) & (det > 0)
    inside = (ix > xlo) & (ix < xhi) & (iy > ylo) & (iy < yhi) & np.isfinite(ix) & np.isfinite(iy)
    ix = np.where(inside, ix, xlo)
    iy = np.where(inside, iy, ylo)
    for j in range(5):
        xs.append(ix[:, j])
        ys.append(iy[:, j])
        kinds.append(1)
    cx, cy = np.stack(xs, axis=1), np.stack(ys, axis=1)
    values = _energy_at(e, cx, cy)
    best = np.argmin(values, axis=1)
    rows = np.arange(count)
    bx, by, bval = cx[rows, best], cy[rows, best], values[rows, best]
    interior = best >= len(kinds) - 5
    j = np.clip(best - (len(kinds) - 5), 0, 4)
    good_newton = ~interior | ((steps[rows, j] < STEP_TOLERANCE) & posdef[rows, j])
    # a rival: another candidate within 1e-12 (relative) of the best energy at a distinct point
    far = (np.abs(cx - bx[:, None]) + np.abs(cy - by[:, None])) > 1e-9
    margin = 1e-12 * np.maximum(np.abs(bval), np.abs(e).max(axis=(1, 2)))
    rival = (far & (values <= (bval + margin)[:, None])).any(axis=1)
    uncertain = suspect | ~good_newton | rival
    where = np.where(interior, "interior", "edge").astype(object)
    corner = np.isin(bx, (xlo, xhi)) & np.isin(by, (ylo, yhi))
    where[corner] = "corner"
    result = {
        "lam_u": bx,
        "lam_v": by,
        "energy": bval,
        "where": where,
        "admissible": _admissible(bx, u_box) & _admissible(by, v_box),
    }
    return _all_exact(given, uncertain, result, energy, u_box, v_box, u_cls, v_cls)


def _derivatives(e: np.ndarray, x: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, ...]:
    def c(a: int, b: int) -> np.ndarray:
        return e[:, a, b][:, None]

    px = (np.ones_like(x), x, x * x)
    py = (np.ones_like(y), y, y * y)
    gx = sum(a * c(a, b) * px[a - 1] * py[b] for a in (1, 2) for b in range(3))
    gy = sum(b * c(a, b) * px[a] * py[b - 1] for a in range(3) for b in (1, 2))
    hxx = sum(2 * c(2, b) * py[b] for b in range(3))
    hyy = sum(2 * c(a, 2) * px[a] for a in range(3))
    hxy = sum(a * b * c(a, b) * px[a - 1] * py[b - 1] for a in (1, 2) for b in (1, 2))
    return gx, gy, hxx, hxy, hyy


def _admissible(x: np.ndarray, box: Any) -> np.ndarray:
    """Whether each x is inside the box: not at an open end (a closed box: all True)."""
    lo, hi, closed = box
    out: np.ndarray = np.ones(x.shape, bool)
    if not closed[0]:
        out &= x != float(lo)
    if not closed[1]:
        out &= x != float(hi)
    return out


def _all_exact(
    nets: np.ndarray,
    which: np.ndarray,
    result: dict[str, Any] | None,
    energy: str,
    u_box: Any,
    v_box: Any,
    u_cls: Any,
    v_cls: Any,
) -> SurfaceOptimalParameters:
    """Fill the nets marked `which` from the exact method on their exact rational values."""
    count, m1, n1, _ = nets.shape
    if result is None:
        result = {
            "lam_u": np.zeros(count),
            "lam_v": np.zeros(count),
            "energy": np.zeros(count),
            "where": np.empty(count, object),
            "admissible": np.ones(count, bool),
        }
    free_u, free_v = np.zeros(count, bool), np.zeros(count, bool)
    indices = np.flatnonzero(which)
    if indices.size:
        mats = _one_parameter_matrices((m1 - 1, n1 - 1), energy, (u_cls, v_cls))
    for i in indices:
        exact = tuple(tuple(tuple(Fraction(float(c)) for c in p) for p in row) for row in nets[i])
        poly = {k: Fraction(v) for k, v in mats.polynomial(exact).items()}
        r = _exact_optimum(poly, u_box, v_box, u_cls, v_cls)
        for key in ("lam_u", "lam_v"):
            value = r[key + "_float"]
            if value is not None:
                result[key][i] = value
        result["energy"][i] = float(r["energy"])
        result["where"][i] = r["where"]
        result["admissible"][i] = r["admissible"]
        free_u[i], free_v[i] = r["free_u"], r["free_v"]
    # a direction without a shape parameter (Bézier) has None, as for one net: never NaN
    lam_u = None if u_box is None else result["lam_u"]
    lam_v = None if v_box is None else result["lam_v"]
    return SurfaceOptimalParameters(
        lam_u,
        lam_v,
        lam_u,
        lam_v,
        result["energy"],
        result["where"],
        result["admissible"],
        free_u,
        free_v,
        int(indices.size),
    )


def _is_polygon(points: object) -> bool:
    """Whether `points` reads as one curve's control polygon (n+1, d), not a surface's net."""
    try:
        return np.ndim(np.asarray(points, dtype=object)) == 2
    except ValueError:  # ragged: not a polygon either
        return False


def optimal_parameters(
    net: NetLike,
    energy: str | int = "thin_plate",
    family: object = "same_degree",
    *,
    k: int | None = None,
) -> SurfaceOptimalParameters | CurveOptimalParameters:
    """The energy-optimal shape parameters, by name, over the closed parameter box: of a
    surface, or of a curve.

    A surface: `net` is one net (m+1, n+1, d) and `energy` "thin_plate" or "membrane"; exact
    input gives the exact global minimum; a batch of float nets (k, m+1, n+1, d) is solved
    vectorised (see `optimal_parameters_batch`). The result is read as ``r["lam_u"]``,
    ``r["lam_v"]``.

    A curve: `net` is its control polygon (n+1, d) and `energy` (or ``k=``) the order k of
    the energy E_k (an int); every parameter of `family` comes back by its own name
    (lambda_bezier.energy.optimal_parameters).
    """
    if k is not None or (isinstance(energy, int) and not isinstance(energy, bool)):
        order = energy if k is None else k
        if k is not None and energy != "thin_plate":
            raise TypeError("give the curve energy's order once: as energy or as k")
        return curve_optimal_parameters(net, cast(int, order), family)  # type: ignore[arg-type]
    if isinstance(energy, str) and energy not in ENERGIES and _is_polygon(net):
        raise TypeError(
            f"energy: a control polygon (n+1 points) takes the order k of the curve energy "
            f"E_k as an int, got {energy!r}; a surface's net takes 'thin_plate' or 'membrane'"
        )
    energy = val.choice(energy, "energy", tuple(ENERGIES))
    if isinstance(net, np.ndarray) and net.ndim == 4 and not len(net):  # a batch, no net
        raise ValueError(
            f"net: an empty batch of nets (shape {net.shape}) has no optimum; pass at least one net"
        )
    if _param_families(family):  # several/indexed parameters, trigonometric...: certified
        # the certified engine (box_bernstein, _optimal_box) loads on first use
        from .param_surface_optimum import optimal_parameters as param_optimal_parameters

        return param_optimal_parameters(net, energy, family)  # type: ignore[return-value]
    u_cls, v_cls = _as_family_pair(family)
    u_box, v_box = _box(u_cls), _box(v_cls)
    if u_box is None and v_box is None:
        raise ValueError(
            "family: neither direction of a classical Bézier surface has a shape parameter"
        )
    names = (u_cls.parameter_name, v_cls.parameter_name)
    arr = np.asarray(val.real_array(net, "net"), dtype=float)
    if arr.ndim == 4:
        return optimal_parameters_batch(arr, energy, family).named(*names)
    grid = _as_net(net)
    m, n = grid.shape[0] - 1, grid.shape[1] - 1
    mats = _one_parameter_matrices((m, n), energy, (u_cls, v_cls))
    exact = _exact_net(net)
    if exact is None or len(exact[0][0]) != grid.shape[2]:
        exact = tuple(tuple(tuple(Fraction(float(c)) for c in p) for p in row) for row in grid)
    poly = mats.polynomial(exact)
    polynomial = {k: Fraction(v) for k, v in poly.items()}
    return _exact_optimum(polynomial, u_box, v_box, u_cls, v_cls).named(*names)


# ---------------------------------------------------------------------- the public energies
# lb.surface_energy and lb.surface_energy_matrices: here, where naming them costs nothing more,
# and the several-parameter engine (param_surface_energy, with _optimal_box, _poly_direction and
# box_bernstein) is imported on the first call that needs it (issue #29: import time)


def surface_energy(surf: Any, energy: str = "thin_plate") -> Any:
    """The membrane or thin-plate energy of any surface over its domain: exact (a Fraction,
    or a ConstantFraction in π or e^W for an AtomSurface) for an exact surface, else a float.
    A trigonometric direction across a hyperbolic one gives a ConstantSum in π and e^W (exact
    terms, a certified enclosure; never compared). A surface of one-parameter or built-in
    families goes to surface_energies.surface_energy, every other one to
    param_surface_energy.surface_energy."""
    if not hasattr(surf, "family_u"):
        return _one_parameter_energy(surf, energy)
    from .param_surface_energy import surface_energy as param_surface_energy

    return param_surface_energy(surf, energy)


def surface_energy_matrices(
    degrees: tuple[int, int], energy: str = "thin_plate", family: object = "same_degree"
) -> Any:
    """The exact quadratic forms of a surface energy for nets of (m+1) x (n+1) points:
    ParamSurfaceEnergyMatrices (param_surface_energy) for several-parameter, indexed and
    trigonometric/hyperbolic/mixed families (one, or a pair (u, v)); the one-parameter and
    built-in families' SurfaceEnergyMatrices (surface_energies) otherwise.

    >>> mats = surface_energy_matrices((3, 3), "membrane")
    >>> sorted(mats.terms)[:3]
    [(0, 0), (0, 1), (0, 2)]
    """
    if not _param_families(family):
        return _one_parameter_matrices(degrees, energy, family)
    from .param_surface_energy import surface_energy_matrices as param_matrices

    return param_matrices(degrees, energy, family)
