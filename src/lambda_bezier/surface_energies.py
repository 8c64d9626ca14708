"""Surface energies and the energy-optimal (λ_u, λ_v).

The membrane energy ∫∫ |S_u|² + |S_v|² and the thin-plate energy ∫∫ |S_uu|² + 2|S_uv|² + |S_vv|²
over the unit square are quadratic forms in the control net. With the curves' Gram-type
matrices A^k(λ) = B(λ) Hᵀ G H B(λ)ᵀ (B the family's basis in the Bernstein basis, H the
hodograph matrices down k degrees, G the Bernstein Gram matrix of generated/energy.py), the
form of ∫∫ |∂^(a+b) S / ∂u^a ∂v^b|² is the Kronecker product A^a_u(λ_u) ⊗ A^b_v(λ_v) on the
row-major vector of the net. Its entries are polynomials in (λ_u, λ_v): the coefficient of
λ_u^a λ_v^b is returned by `surface_energy_matrices` as an integer matrix with a scale. For a
built-in family in both directions at the degrees derive emits (generated/surface_energy.py,
derived by integrating the tensor-product basis itself) the emitted matrices are read; other
degrees and families are built here by the Kronecker products.

For a given net the energy is a polynomial E(λ_u, λ_v) of degree 2 in each parameter (for
families affine in λ). `optimal_parameters` minimises it over the parameter box: exactly for
exact input (critical points by resultants and Sturm isolation, then the edges and corners),
or vectorised over a batch of float nets (surface_optimum).
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from fractions import Fraction
from functools import cache
from math import lcm
from typing import Any

import numpy as np

from . import _validate as val
from ._lazy import generated
from ._singular import IsolatedRoot
from .curves import Curve, Matrix, family_class
from .hazmat import exact_poly as xp
from .hazmat.forms import hodograph_matrix
from .surfaces import NetLike, Surface, _as_family_pair, _check_degree, basis_to_bernstein_split

# the energy is a quadratic form in the net with entries up to about 1e4 (degrees <= 12):
# coordinates below this keep every coefficient far inside the float range (the batch optima
# of surface_optimum and param_surface_optimum refuse nets past it)
MAX_COORDINATE = 1e140


def check_net_values(nets: np.ndarray) -> None:
    """A ValueError for a batch of float nets holding NaN or infinity, or coordinates above
    MAX_COORDINATE (where the energy overflows a float)."""
    if not np.isfinite(nets).all():
        raise ValueError("the nets contain NaN or infinity")
    if np.abs(nets).max() > MAX_COORDINATE:
        raise ValueError(
            f"the nets have coordinates above {MAX_COORDINATE:.0e}, where the energy overflows "
            "a float; scale them down (the optimal parameters do not depend on the scale)"
        )


def moved_to_origin(nets: np.ndarray, fast: Any = None) -> np.ndarray:
    """The nets moved so that each far from the origin starts there; for an energy that
    depends on the net's differences alone (E(P + c) = E(P)), which the caller decides. The
    float coefficients are sums of Gram products P_i · P_j: for a net far from the origin
    (CAD coordinates about 1e3 or 1e6) they cancel, and a batch's λ came out 1e-10 to 1e-4
    off (tests/test_acceptance_31d.py); each difference is rounded relative to itself.
    A net is moved when its first point is more than 4 times as far from the origin as its
    farthest corner is from it (at most 16 times the rounding of a net about the origin
    otherwise). Only the corners are read: in one compiled pass with numba (`fast`, the
    hazmat.surface_batch_compiled module; 0.01 ms for 10,000 bicubic nets), else column by
    column (numpy's reductions over a short last axis cost ten times more; this way 0.19 ms,
    2.6 read passes). Moving every net, a new array, doubled the time of a batch of 10,000
    bicubic nets about the origin."""
    first = nets[:, 0, 0, :]
    if fast is not None and nets.dtype == np.float64:
        far = fast.far_from_origin(nets, 4.0)
    else:
        size, reach = np.zeros(nets.shape[0]), np.zeros(nets.shape[0])
        for c in range(nets.shape[3]):
            np.maximum(size, np.abs(first[:, c]), out=size)
            for i, j in ((0, -1), (-1, 0), (-1, -1)):
                np.maximum(reach, np.abs(nets[:, i, j, c] - first[:, c]), out=reach)
        far = size > 4 * reach
    if not far.any():
        return nets
    check_net_values(nets)  # the limits hold for the nets as given, moved or not
    moved: np.ndarray = nets - np.where(far[:, None], first, 0.0)[:, None, None, :]
    return moved


_energy = generated("energy")
_surface_energy = generated("surface_energy")

# (a, b, weight): the energy is Σ weight ∫∫ |∂^(a+b) S / ∂u^a ∂v^b|²
ENERGIES: dict[str, tuple[tuple[int, int, int], ...]] = {
    "membrane": ((1, 0, 1), (0, 1, 1)),
    "thin_plate": ((2, 0, 1), (1, 1, 2), (0, 2, 1)),
}
Algebraic = Fraction | IsolatedRoot


# ---------------------------------------------------------------------- the matrices
def _gram(degree: int) -> list[list[Fraction]]:
    """∫ B_a B_b over [0, 1] for the Bernstein basis of `degree`, full and exact."""
    if degree not in _energy.GRAM:
        raise ValueError(
            f"no generated Gram matrix for degree {degree} (they cover degrees "
            f"{min(_energy.GRAM)}..{max(_energy.GRAM)})"
        )
    scale, upper = _energy.GRAM[degree]
    size = degree + 1
    return [
        [
            Fraction(scale)
            * (upper[min(a, b)][max(a, b)] if a == b else Fraction(upper[min(a, b)][max(a, b)], 2))
            for b in range(size)
        ]
        for a in range(size)
    ]


def _matmul(a: Any, b: Any) -> list[list[Fraction]]:
    cols = list(zip(*b, strict=True))
    return [
        [sum((x * y for x, y in zip(row, col, strict=True)), Fraction(0)) for col in cols]
        for row in a
    ]


@cache
def hodograph_gram(big: int, k: int) -> list[list[Fraction]]:
    """Hᵀ G H: ∫ p^(k) q^(k) over [0, 1] = aᵀ (Hᵀ G H) b for the degree-`big` Bernstein
    coefficients a, b of p, q (H the hodograph matrices down k degrees); zero when k > big."""
    if k > big:
        return [[Fraction(0)] * (big + 1) for _ in range(big + 1)]
    h: list[list[Fraction]] = [
        [Fraction(int(r == c)) for c in range(big + 1)] for r in range(big + 1)
    ]
    for d in range(big, big - k, -1):
        h = _matmul(hodograph_matrix(d), h)
    return _matmul(_matmul(list(zip(*h, strict=True)), _gram(big - k)), h)


@cache
def direction_forms(cls: Any, degree: int, k: int) -> tuple[Matrix, ...]:
    """(A_0, A_1, …): ∫ |p^(k)|² = Dᵀ (Σ_a λ^a A_a) D summed over coordinates, for the
    family's degree-`degree` curve with control points D; exact, symmetric."""
    split = basis_to_bernstein_split(cls, degree)
    big = len(split[0][0]) - 1
    if k > big:
        zero = tuple(tuple(Fraction(0) for _ in range(degree + 1)) for _ in range(degree + 1))
        return (zero,)
    inner = hodograph_gram(big, k)
    out: list[list[list[Fraction]]] = []
    for p, bp in enumerate(split):
        left = _matmul(bp, inner)
        for q, bq in enumerate(split):
            term = _matmul(left, list(zip(*bq, strict=True)))
            while len(out) <= p + q:
                out.append([[Fraction(0)] * (degree + 1) for _ in range(degree + 1)])
            acc = out[p + q]
            for r in range(degree + 1):
                for c in range(degree + 1):
                    acc[r][c] += term[r][c]
    while len(out) > 1 and not any(any(row) for row in out[-1]):
        out.pop()
    return tuple(tuple(tuple(row) for row in mat) for mat in out)


IntegerForms = tuple[tuple[Any, int, tuple[tuple[int, int, int], ...]], ...]


def integer_forms(full: Mapping[Any, tuple[tuple[Fraction, ...], ...]]) -> IntegerForms:
    """((key, denominator, ((r, c, w), ..)), ..): each matrix Q_key folded onto r <= c (it is
    used as vec(P)ᵀ Q vec(P)) as integers w over one denominator per key; the one keyed
    accumulation of both surface energy modules (keyed_quadratic)."""
    out = []
    for key, mat in full.items():
        size = len(mat)
        folded = {
            (r, c): mat[r][c] + (mat[c][r] if c != r else 0)
            for r in range(size)
            for c in range(r, size)
        }
        denominator = lcm(1, *(q.denominator for q in folded.values()))
        entries = tuple((r, c, int(q * denominator)) for (r, c), q in folded.items() if q)
        out.append((key, denominator, entries))
    return tuple(out)


def keyed_quadratic(forms: IntegerForms, vec: list[tuple[Fraction, ...]]) -> dict[Any, Fraction]:
    """{key: vec(P)ᵀ Q_key vec(P)} for an exact net read row by row, summed over coordinates:
    the net over its common denominator in integers, its Gram products P_r · P_c once, then
    one integer sum and one division per key (no Fraction arithmetic per entry)."""
    scale = lcm(1, *(x.denominator for p in vec for x in p))
    ints = [[int(x * scale) for x in p] for p in vec]
    size = len(ints)
    gram = [
        [sum(a * b for a, b in zip(ints[r], ints[c], strict=True)) for c in range(size)]
        for r in range(size)
    ]
    return {
        key: Fraction(sum(w * gram[r][c] for r, c, w in entries), denominator * scale * scale)
        for key, denominator, entries in forms
    }


@dataclass(frozen=True, eq=False)  # hashed by identity: one object per (families, degrees)
class SurfaceEnergyMatrices:
    """The energy as Σ_{a,b} λ_u^a λ_v^b vec(P)ᵀ Q_ab vec(P), summed over coordinates, with
    vec(P) the net read row by row (P_00, P_01, …, P_0n, P_10, …).

    ``terms[(a, b)] = (scale, U)``: U upper-triangular integers in the curves' convention,
    vec(P)ᵀ Q_ab vec(P) = scale · Σ_{r <= c} U[r][c] P_r · P_c.
    """

    energy: str
    degrees: tuple[int, int]
    terms: dict[tuple[int, int], tuple[Fraction, tuple[tuple[int, ...], ...]]]
    full: dict[tuple[int, int], tuple[tuple[Fraction, ...], ...]] = field(repr=False)

    def polynomial(self, net: NetLike) -> dict[tuple[int, int], Fraction | float]:
        """{(a, b): e_ab} with E(λ_u, λ_v) = Σ e_ab λ_u^a λ_v^b for one net (exact for an
        exact net)."""
        exact = _exact_vector(net, self.degrees)
        if exact is not None:
            return dict(keyed_quadratic(_forms(self), exact))
        flat = _float_vectors(net, self.degrees)[None]
        coeffs = _float_polynomial(self, flat)
        return {key: float(v[0]) for key, v in coeffs.items()}


def _integer_form(
    mat: tuple[tuple[Fraction, ...], ...],
) -> tuple[Fraction, tuple[tuple[int, ...], ...]]:
    size = len(mat)
    upper = [
        [mat[r][c] * (1 if r == c else 2) if c >= r else Fraction(0) for c in range(size)]
        for r in range(size)
    ]
    den = lcm(*(v.denominator for row in upper for v in row))
    ints = [[int(v * den) for v in row] for row in upper]
    from math import gcd

    g = 0
    for row in ints:
        for v in row:
            g = gcd(g, v)
    g = g or 1
    # the sign rule of the curves' X and Y (and of generated/surface_energy.py): the first
    # nonzero diagonal entry positive, else the first nonzero entry
    entries = [v for row in ints for v in row if v]
    lead = next((ints[r][r] for r in range(size) if ints[r][r]), entries[0] if entries else 1)
    g = -g if lead < 0 else g
    return Fraction(g, den), tuple(tuple(v // g for v in row) for row in ints)


def _emitted_matrices(
    u_cls: Any, v_cls: Any, m: int, n: int, energy: str
) -> SurfaceEnergyMatrices | None:
    """The matrices derive emitted (generated/surface_energy.py) for a built-in family in both
    directions at small degrees, or None (then they are built by Kronecker products)."""
    name = u_cls.family
    if v_cls is not u_cls or name not in _surface_energy.SURFACE_ENERGY:
        return None  # mixed directions, or a family defined at run time
    if family_class(name) is not u_cls:
        return None  # a family defined at run time under a built-in name
    table = _surface_energy.SURFACE_ENERGY[name].get((m, n, energy))
    if table is None:
        return None
    size = (m + 1) * (n + 1)
    full = {
        key: tuple(
            tuple(
                Fraction(scale) * Fraction(upper[min(r, c)][max(r, c)], 1 if r == c else 2)
                for c in range(size)
            )
            for r in range(size)
        )
        for key, (scale, upper) in sorted(table.items())
    }
    terms = {key: (Fraction(scale), upper) for key, (scale, upper) in sorted(table.items())}
    return SurfaceEnergyMatrices(energy, (m, n), terms, full)


@cache
def _cached_matrices(u_cls: Any, v_cls: Any, m: int, n: int, energy: str) -> SurfaceEnergyMatrices:
    return _emitted_matrices(u_cls, v_cls, m, n, energy) or kronecker_matrices(
        u_cls, v_cls, m, n, energy
    )


@cache
def kronecker_matrices(
    u_cls: Any, v_cls: Any, m: int, n: int, energy: str
) -> SurfaceEnergyMatrices:
    """The matrices as Kronecker products of the curves' forms A^a_u ⊗ A^b_v (any families and
    degrees; tests check them against the emitted ones)."""
    full: dict[tuple[int, int], list[list[Fraction]]] = {}
    size = (m + 1) * (n + 1)
    for ku, kv, weight in ENERGIES[energy]:
        au, av = direction_forms(u_cls, m, ku), direction_forms(v_cls, n, kv)
        for a, ma in enumerate(au):
            for b, mb in enumerate(av):
                acc = full.setdefault((a, b), [[Fraction(0)] * size for _ in range(size)])
                for i in range(m + 1):
                    for k in range(m + 1):
                        w = weight * ma[i][k]
                        if not w:
                            continue
                        for j in range(n + 1):
                            row = acc[i * (n + 1) + j]
                            for l_ in range(n + 1):
                                if mb[j][l_]:
                                    row[k * (n + 1) + l_] += w * mb[j][l_]
    frozen = {
        key: tuple(tuple(r) for r in mat)
        for key, mat in sorted(full.items())
        if any(any(r) for r in mat)
    }
    return SurfaceEnergyMatrices(
        energy, (m, n), {key: _integer_form(mat) for key, mat in frozen.items()}, frozen
    )


def _param_families(family: object) -> bool:
    """Whether `family` (or either of a pair) is one for param_surface_energy and its
    certified optimum rather than this module: several or indexed parameters, or a
    trigonometric, hyperbolic or mixed basis. Here, below both, so that the public entry
    points (surface_optimum) decide without importing that engine (issue #29: import time)."""
    pair = family if isinstance(family, tuple | list) else (family,)
    return any(
        hasattr(f, "atom_data") or hasattr(f, "index_name") or getattr(f, "several", None)
        for f in pair
    )


def surface_energy_matrices(
    degrees: tuple[int, int], energy: str = "thin_plate", family: object = "same_degree"
) -> SurfaceEnergyMatrices:
    """The exact quadratic forms of a surface energy for nets of (m+1) x (n+1) points.

    >>> mats = surface_energy_matrices((3, 3), "membrane")
    >>> sorted(mats.terms)[:3]
    [(0, 0), (0, 1), (0, 2)]
    """
    energy = val.choice(energy, "energy", tuple(ENERGIES))
    if not isinstance(degrees, tuple | list) or len(degrees) != 2:
        raise ValueError(f"degrees must be a pair (m, n), got {val.describe(degrees)}")
    m, n = (val.integer(d, "degrees") for d in degrees)
    u_cls, v_cls = _as_family_pair(family)
    try:
        _check_degree(u_cls, m, "u")
        _check_degree(v_cls, n, "v")
    except ValueError as exc:  # the check speaks of a net; here the degrees were given
        raise ValueError(f"degrees = ({m}, {n}): {str(exc).removeprefix('net, ')}") from None
    classes: tuple[Any, Any] = (u_cls, v_cls)  # hashable: classes hash by identity
    return _cached_matrices(*classes, m, n, energy)


def surface_energy(surf: Surface, energy: str = "thin_plate") -> Fraction | float:
    """The energy of a surface (exact for an exact surface)."""
    if not isinstance(surf, Surface):
        raise TypeError(f"surf must be a lambda_bezier surface, got {type(surf).__name__}")
    if not hasattr(surf, "_u_cls"):  # an AtomSurface: param_surface_energy (lb.surface_energy)
        raise TypeError(
            "surf: the energy of a surface of trigonometric, hyperbolic or mixed families is "
            "lambda_bezier.surface_energy (param_surface_energy.surface_energy)"
        )
    mats = surface_energy_matrices(surf.degrees, energy, (surf._u_cls, surf._v_cls))
    poly = mats.polynomial(surf._exact if surf._exact is not None and surf.is_exact else surf.net)
    lu = Fraction(0) if surf.lam_u is None else surf.lam_u
    lv = Fraction(0) if surf.lam_v is None else surf.lam_v
    total = sum(
        (c * lu**a * lv**b for (a, b), c in poly.items()), Fraction(0) if surf.is_exact else 0.0
    )
    return total


# ---------------------------------------------------------------------- net vectors
def _exact_vector(net: object, degrees: tuple[int, int]) -> list[tuple[Fraction, ...]] | None:
    from .surfaces import _as_net, _exact_net

    arr = _as_net(net)
    if arr.shape[:2] != (degrees[0] + 1, degrees[1] + 1):
        raise ValueError(
            f"net has {arr.shape[0]} x {arr.shape[1]} points, the matrices are for "
            f"{degrees[0] + 1} x {degrees[1] + 1}"
        )
    exact = _exact_net(net)
    if exact is None or len(exact[0][0]) != arr.shape[2]:
        return None
    return [p for row in exact for p in row]


def _float_vectors(net: object, degrees: tuple[int, int]) -> np.ndarray:
    from .surfaces import _as_net

    arr = _as_net(net)
    if arr.shape[:2] != (degrees[0] + 1, degrees[1] + 1):
        raise ValueError(
            f"net has {arr.shape[0]} x {arr.shape[1]} points, the matrices are for "
            f"{degrees[0] + 1} x {degrees[1] + 1}"
        )
    return arr.reshape(-1, arr.shape[2])


@cache
def _forms(mats: SurfaceEnergyMatrices) -> IntegerForms:
    return integer_forms(mats.full)


@cache
def _float_full(mats: SurfaceEnergyMatrices) -> dict[tuple[int, int], np.ndarray]:
    return {key: np.array(mat, dtype=float) for key, mat in mats.full.items()}


def _float_polynomial(
    mats: SurfaceEnergyMatrices, flat: np.ndarray
) -> dict[tuple[int, int], np.ndarray]:
    """{(a, b): e_ab over the batch} for nets flattened to (batch, (m+1)(n+1), d)."""
    out = {}
    for key, q in _float_full(mats).items():
        qp = np.matmul(q, flat)  # (batch, size, d)
        out[key] = np.einsum("brd,brd->b", flat, qp)
    return out


# ---------------------------------------------------------------------- the optimum
@dataclass(frozen=True)
class SurfaceOptimalParameters(Mapping[str, Any]):
    """The energy-optimal (λ_u, λ_v); read by name: ``result["lam_u"]``, ``result["lam_v"]``.

    For exact input ``lam_u``/``lam_v`` are Fractions or IsolatedRoot (an irrational algebraic
    number: its integer polynomial and an isolating interval), ``lam_u_float``/``lam_v_float``
    their floats, ``energy`` the minimum (a Fraction when both are rational, else a float) and
    ``where`` "interior", "edge" or "corner". For a batch every field is an array (but
    ``lam_u``/``lam_v`` of a direction without a shape parameter, None as for one net).
    ``admissible`` is False where the minimum over the closed box sits on an excluded end of a
    family's range (λ = −2 for same_degree); ``free_u``/``free_v`` mark a parameter the energy
    does not depend on (then the family's Bézier value is returned).
    """

    lam_u: Any
    lam_v: Any
    lam_u_float: Any
    lam_v_float: Any
    energy: Any
    where: Any
    admissible: Any
    free_u: Any = False
    free_v: Any = False
    exact_fallbacks: int = 0
    careful_fallbacks: int = 0  # a batch: nets the fixed-cost certificate declined

    def __getitem__(self, key: str) -> Any:
        key = self._aliases().get(key, key)
        if key not in self.__dataclass_fields__:
            raise KeyError(key)
        return getattr(self, key)

    def __iter__(self) -> Iterator[str]:
        return iter(self.__dataclass_fields__)

    def __len__(self) -> int:
        return len(self.__dataclass_fields__)

    def named(self, u_name: str, v_name: str) -> SurfaceOptimalParameters:
        """This result also read by each direction's own parameter name: r["sigma_u"] is
        r["lam_u"] for a family whose parameter is sigma (as its surfaces' keywords and repr
        name it); the keys listed stay lam_u, lam_v."""
        object.__setattr__(self, "_names", (u_name, v_name))
        return self

    def _aliases(self) -> dict[str, str]:
        u_name, v_name = getattr(self, "_names", ("lam", "lam"))
        out = {}
        for name, d in ((u_name, "u"), (v_name, "v")):
            if name != "lam":
                out[f"{name}_{d}"], out[f"{name}_{d}_float"] = f"lam_{d}", f"lam_{d}_float"
        return out


def _box(cls: type[Curve]) -> tuple[Fraction, Fraction, tuple[bool, bool]] | None:
    if not cls._has_lambda:
        return None
    lo, hi = cls._data.LAMBDA_RANGE
    lo_closed, hi_closed = cls._data.LAMBDA_CLOSED
    return Fraction(lo), Fraction(hi), (bool(lo_closed), bool(hi_closed))


def _default(cls: type[Curve], box: tuple[Fraction, Fraction, Any]) -> Fraction:
    at = getattr(cls._data, "BERNSTEIN_LAMBDA", None)
    if at is not None and box[0] <= at <= box[1]:
        return Fraction(at)
    return (box[0] + box[1]) / 2


Point = tuple[Fraction | tuple[Fraction, Fraction], Fraction | tuple[Fraction, Fraction]]


def _interval(r: Fraction | tuple[Fraction, Fraction]) -> tuple[Fraction, Fraction]:
    return (r, r) if isinstance(r, Fraction) else r


def _roots(
    p: list[Fraction], lo: Fraction, hi: Fraction
) -> list[Fraction | tuple[Fraction, Fraction]]:
    """The roots of p in the open interval (lo, hi) (none for the zero polynomial: handled by
    the caller as a free parameter)."""
    p = xp.trim(p)
    if not p:
        return []
    return [r for r in xp.real_roots(p, lo, hi) if not (isinstance(r, Fraction) and r in (lo, hi))]


def _refine_all(
    poly: list[Fraction], r: Fraction | tuple[Fraction, Fraction], width: Fraction
) -> Fraction | tuple[Fraction, Fraction]:
    if isinstance(r, Fraction):
        return r
    return xp.refine(xp.squarefree(poly), r, width)


def minimise_polynomial(
    e: dict[tuple[int, int], Fraction],
    box_x: tuple[Fraction, Fraction],
    box_y: tuple[Fraction, Fraction],
) -> tuple[Algebraic, Algebraic, str]:
    """The global minimiser of Σ e_ab x^a y^b over the closed box, exactly."""
    (xlo, xhi), (ylo, yhi) = box_x, box_y
    cands: list[tuple[Any, Any, list[Fraction] | None, list[Fraction] | None, str]] = []
    for x0 in (xlo, xhi):
        for y0 in (ylo, yhi):
            cands.append((x0, y0, None, None, "corner"))
    fx, fy = xp.partial(e, 0), xp.partial(e, 1)
    for x0 in (xlo, xhi):
        g = xp.substitute(fy, 0, x0)
        for r in _roots(g, ylo, yhi):
            cands.append((x0, r, None, g, "edge"))
    for y0 in (ylo, yhi):
        g = xp.substitute(fx, 1, y0)
        for r in _roots(g, xlo, xhi):
            cands.append((r, y0, g, None, "edge"))
    fx = {k: c for k, c in fx.items() if c}
    fy = {k: c for k, c in fy.items() if c}
    if fx and fy:
        ry = xp.resultant(fx, fy, 0)
        rx = xp.resultant(fx, fy, 1)
        systems = [(fx, fy, rx, ry)] if ry and rx else _isolated_parts(e, fx, fy)
        for gx, gy, rx, ry in systems:
            ys, xs = _roots(ry, ylo, yhi), _roots(rx, xlo, xhi)
            for xr in xs:
                for yr in ys:
                    if _pair(gx, gy, rx, ry, xr, yr) is not None:
                        cands.append((xr, yr, rx, ry, "interior"))
    return _least(e, cands)


def _isolated_parts(
    e: xp.Bivariate, fx: xp.Bivariate, fy: xp.Bivariate
) -> list[tuple[xp.Bivariate, xp.Bivariate, list[Fraction], list[Fraction]]]:
    """Where E_x and E_y share a factor, the critical points form curves as well as isolated
    points (a net zero but for one inner point does it). E is constant along a curve of
    critical points, and for E of degree <= 2 in x every such curve in the box reaches its
    boundary: E_x = c(y)·p(x, y) with p primitive and of degree <= 1 in x, so a common factor
    is p (whose zeros are a graph x(y)) or a factor h(y) of c (lines y = y0). There both
    partials vanish, so the corners and the edges' critical points, which are candidates
    already, attain every value the curves take. What remains is the isolated critical
    points: the common zeros of p and E_y when p does not divide E_y, and of c/h and E_y.
    Returns those systems (f, g, res_y(f, g), res_x(f, g)), each with nonzero resultants."""
    if max(a for a, _ in e) > 2:
        raise ValueError(
            "the energy's critical points form a curve for this net (the derivatives share "
            "a factor); optimal_parameters cannot isolate them"
        )

    def column(f: xp.Bivariate, a: int) -> list[Fraction]:  # the coefficient of x^a, in y
        top = max((j for _, j in f), default=0)
        return xp.trim([f.get((a, j), Fraction(0)) for j in range(top + 1)])

    def bivariate(polys: dict[int, list[Fraction]]) -> xp.Bivariate:
        return {(a, j): c for a, p in polys.items() for j, c in enumerate(p) if c}

    alpha, beta = column(fx, 1), column(fx, 0)
    content = xp.gcd(alpha, beta) if alpha else beta
    systems = []
    if alpha:  # p = E_x / c, of degree 1 in x
        p = bivariate({1: xp._divide(alpha, content), 0: xp._divide(beta, content)})
        ry = xp.resultant(p, fy, 0)
        if ry:  # p does not divide E_y: isolated common zeros only
            systems.append((p, fy, xp.resultant(p, fy, 1), ry))
    fy_content: list[Fraction] = []
    for a in range(1 + max(a for a, _ in fy)):
        fy_content = xp.gcd(fy_content, column(fy, a)) if fy_content else column(fy, a)
    lines = xp.gcd(content, fy_content) if fy_content else content
    rest = xp._divide(content, lines) if len(lines) > 1 else content
    if len(rest) > 1:  # lines y = y0 of E_x's content on which E_y is not identically 0
        c = bivariate({0: rest})
        systems.append((c, fy, xp.resultant(c, fy, 1), rest))
    return [sys_ for sys_ in systems if sys_[2] and sys_[3]]


def _pair(
    fx: xp.Bivariate, fy: xp.Bivariate, rx: list[Fraction], ry: list[Fraction], xr: Any, yr: Any
) -> tuple[Any, Any] | None:
    """(xr, yr) refined, when ∇E may vanish there: interval evaluation excludes the pairs that
    are not common roots; a pair is kept once its intervals are 2^-120 wide and still enclose
    a zero of both derivatives."""
    width = Fraction(1, 2**8)
    while True:
        xr, yr = _refine_all(rx, xr, width), _refine_all(ry, yr, width)
        ix, iy = _interval(xr), _interval(yr)
        for f in (fx, fy):
            lo, hi = xp.interval_evaluate2(f, ix, iy)
            if lo > 0 or hi < 0:
                return None
        if width < Fraction(1, 2**120):
            return xr, yr
        width /= 2**16


def _least(e: xp.Bivariate, cands: list[Any]) -> tuple[Algebraic, Algebraic, str]:
    """The candidate of least energy, its parameters given by their isolating intervals as
    found (refined copies decide the comparison)."""
    width = Fraction(1, 2**20)
    work = list(cands)
    while True:
        encl = []
        for i, (x, y, px, py, where) in enumerate(work):
            if px is not None:
                x = _refine_all(px, x, width)
            if py is not None:
                y = _refine_all(py, y, width)
            work[i] = (x, y, px, py, where)
            encl.append(xp.interval_evaluate2(e, _interval(x), _interval(y)))
        best = min(range(len(work)), key=lambda i: encl[i][1])
        rivals = [i for i in range(len(work)) if i != best and encl[i][0] < encl[best][1]]
        if not rivals or width < Fraction(1, 2**200):
            x, y, px, py, where = cands[best]
            # a refined end met the root exactly: that root is rational
            rx, ry = work[best][0], work[best][1]
            x = rx if isinstance(rx, Fraction) else x
            y = ry if isinstance(ry, Fraction) else y
            return _algebraic(x, px), _algebraic(y, py), where
        width /= 2**20


def _algebraic(r: Any, poly: list[Fraction] | None) -> Algebraic:
    """The root of `poly` in the isolating interval r, as a Fraction when it is rational:
    IsolatedRoot promises an irrational number (an edge's quadratic has a rational vertex)."""
    if isinstance(r, Fraction):
        return r
    assert poly is not None
    factor = xp.squarefree(poly)
    coefficients = xp.integer_coefficients(factor)
    if len(coefficients) == 2:
        return Fraction(-coefficients[0], coefficients[1])
    # a rational root p/q with q <= 2^64 is the only fraction of such a denominator within
    # 2^-129 of any point 2^-140 from it (two of them differ by at least 2^-128), so the
    # best approximation of the narrowed interval's middle finds it; an exact zero proves it
    narrow = xp.refine(factor, r, Fraction(1, 2**140))
    if isinstance(narrow, Fraction):
        return narrow
    guess = ((narrow[0] + narrow[1]) / 2).limit_denominator(2**64)
    if r[0] < guess < r[1] and xp.evaluate(factor, guess) == 0:
        return guess
    return IsolatedRoot(r[0], r[1], coefficients)


def _float(x: Algebraic) -> float:
    return float(x)


def _exact_optimum(
    e: dict[tuple[int, int], Fraction],
    u_box: Any,
    v_box: Any,
    u_cls: type[Curve],
    v_cls: type[Curve],
) -> SurfaceOptimalParameters:
    free_u = u_box is None or not any(a for (a, _), c in e.items() if c)
    free_v = v_box is None or not any(b for (_, b), c in e.items() if c)
    pin_u = None if u_box is None else _default(u_cls, u_box)
    pin_v = None if v_box is None else _default(v_cls, v_box)
    bx = (
        (pin_u, pin_u)
        if free_u and pin_u is not None
        else ((Fraction(0), Fraction(0)) if u_box is None else (u_box[0], u_box[1]))
    )
    by = (
        (pin_v, pin_v)
        if free_v and pin_v is not None
        else ((Fraction(0), Fraction(0)) if v_box is None else (v_box[0], v_box[1]))
    )
    x, y, where = minimise_polynomial(e, bx, by)
    energy: Fraction | float
    if isinstance(x, Fraction) and isinstance(y, Fraction):
        energy = xp.evaluate2(e, x, y)
    else:
        energy = sum(float(c) * float(x) ** a * float(y) ** b for (a, b), c in e.items())
    admissible = all(
        box is None
        or free
        or not ((val_ == box[0] and not box[2][0]) or (val_ == box[1] and not box[2][1]))
        for box, val_, free in ((u_box, x, free_u), (v_box, y, free_v))
    )
    return SurfaceOptimalParameters(
        None if u_box is None else x,
        None if v_box is None else y,
        None if u_box is None else float(x),
        None if v_box is None else float(y),
        energy,
        where,
        admissible,
        free_u,
        free_v,
    )
