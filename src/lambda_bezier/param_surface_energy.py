r"""Surface energies and energy-optimal parameters of surfaces of several-parameter, indexed
and trigonometric/hyperbolic/mixed families (param_surfaces, atom_surfaces).

Each direction's curve Gram matrices per pair of parameter monomials,
G^k_(a,b)[i][l] = ∫ (b_i^(a))^(k) (b_l^(b))^(k) over the family's domain (b^(a) the part of
the basis at the monomial x^a), give the energy's quadratic form as Kronecker products, as
for one-parameter families (surface_energies):

    ∫∫ |∂_u^p ∂_v^q S|² = Σ_(a,b) Σ_(c,d) x_u^(a+b) x_v^(c+d) Σ_ijkl G^p_u,(a,b)[i][k]
                           G^q_v,(c,d)[j][l] P_ij · P_kl.

The membrane energy is the (1, 0) and (0, 1) terms, the thin-plate energy (2, 0), 2·(1, 1)
and (0, 2). A polynomial family's Gram matrices are computed here, exactly, from its
Bernstein tables (Bᵀ Hᵀ G H B, surface_energies.hodograph_gram); an atom family's are the
derived document's (``energy`` "n,k", k = 0..3, entries in ℚ[π, 1/π] or Laurent in e^W).

For a given net the energy is therefore a polynomial in all the parameters of both
directions whose coefficients lie in ℚ[c, 1/c] (c = π or e^W). It is quadratic in each
direction's parameters for affine families and quartic jointly, never a quadratic in all of
them, so its minimum over the parameter box is found by the exact Bernstein branch and bound
the curves' several-parameter optimum uses (`hazmat.box_bernstein.minimum`, with
`_optimal_box`'s tolerance and budget), started from the best point of a float grid, with c
replaced by a rational ĉ within 2^-64 of it and the difference bounded over the box
(`_rational_power`): the point is exact, its energy exact (a Fraction or a
ConstantFraction), and ``lower_bound`` a proven lower bound over the whole box within 1e-12
(relative) of it. A trigonometric direction across a hyperbolic one has both π and e^W: both
are replaced by rationals and bounded the same way, the energy at the point is a ConstantSum
(never compared exactly), and the 1e-12 certificate is decided on its enclosure.
Never exact in closed form: the minimiser is in general irrational (a point of
ℚ(π)-algebraic coordinates), so a rational point within the certificate is given.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from fractions import Fraction
from functools import cache
from typing import Any

import numpy as np

from . import _poly_direction as pd
from . import _validate as val
from . import surface_energies
from ._optimal_box import BUDGET, CONSTANT_BITS, TOLERANCE, _laurent
from .hazmat import box_bernstein
from .hazmat.constants import ConstantSum
from .surface_energies import ENERGIES, _matmul, _param_families, hodograph_gram
from .surfaces import NetLike, _as_net, _exact_net, basis_to_bernstein_split

Laurent = dict[int, Fraction]
Mono = tuple[int, ...]


# ---------------------------------------------------------------------- one direction
@dataclass(frozen=True, eq=False)
class Direction:
    """One direction of a surface: the family at one degree, its parameter names (in the
    result: ``name_u``), their boxes, and its Gram matrices per monomial pair and order."""

    family: Any
    degree: int
    names: tuple[str, ...]
    ranges: dict[str, tuple[Fraction, Fraction, bool, bool, str]]
    constant: str | None
    indexed: str | None  # the indexed family's own name: its values come back as one tuple

    def grams(self, k: int) -> dict[tuple[Mono, Mono], tuple[tuple[Laurent, ...], ...]]:
        return _grams(self.family, self.degree, k)


def _direction(family: Any, degree: int) -> Direction:
    """The Direction of a family from load_family at one degree."""
    if hasattr(family, "index_name"):
        at = family.at_degree(degree)
        d = _direction(at, degree)
        return Direction(at, degree, d.names, d.ranges, None, family.index_name)
    if hasattr(family, "atom_data"):
        data = family.atom_data
        entries = (g for grams in data.GRAM.values() for m in grams.values() for r in m for g in r)
        constant = next((g.constant for g in entries if hasattr(g, "constant")), None)
        return Direction(family, degree, data.NAMES, dict(data.RANGES), constant, None)
    if pd.is_class(family):  # a built-in class across an atom family (_poly_direction)
        if not family._has_lambda:
            return Direction(family, degree, (), {}, None, None)
        data = family._data
        lo, hi = data.LAMBDA_RANGE
        rng = (Fraction(lo), Fraction(hi), *data.LAMBDA_CLOSED, data.LAMBDA_RANGE_TEXT)
        return Direction(
            family, degree, (family.parameter_name,), {family.parameter_name: rng}, None, None
        )
    if family.several is not None:
        sev = family.several
        return Direction(family, degree, sev.NAMES, dict(sev.RANGES), None, None)
    data = family.data
    lo, hi = data.LAMBDA_RANGE
    closed = data.LAMBDA_CLOSED
    rng = (lo, hi, closed[0], closed[1], data.LAMBDA_RANGE_TEXT)
    return Direction(family, degree, (family.parameter,), {family.parameter: rng}, None, None)


@cache
def _grams(
    family: Any, degree: int, k: int
) -> dict[tuple[Mono, Mono], tuple[tuple[Laurent, ...], ...]]:
    """{(a, b): G} with G[i][l] = ∫ (part a of b_i)^(k) (part b of b_l)^(k), as Laurent
    dicts {exponent of the constant: Fraction} (exponent 0 only for polynomial families)."""
    if hasattr(family, "atom_data"):
        data = family.atom_data
        if (degree, k) not in data.GRAM:
            raise ValueError(
                f"family: the derived document of {family.name!r} has no Gram matrix of order "
                f"{k} at degree {degree}; re-derive it (lambda-bezier derive --family FILE) "
                "with this version, which writes order 0 for surfaces"
            )
        return {
            pair: tuple(tuple(_laurent(g) for g in row) for row in mat)
            for pair, mat in data.GRAM[(degree, k)].items()
        }
    if pd.is_class(family):  # a built-in class: its tables split by powers of λ
        split = basis_to_bernstein_split(family, degree)
        by_mono = {((p,) if family._has_lambda else ()): m for p, m in enumerate(split)}
    elif family.several is not None:
        by_mono = family.several.TABLES["bernstein"][degree]
    else:
        split = family.data.BERNSTEIN[degree]
        by_mono = {(p,): m for p, m in enumerate(split)}
    big = len(next(iter(by_mono.values()))[0]) - 1
    inner = hodograph_gram(big, k)
    out: dict[tuple[Mono, Mono], tuple[tuple[Laurent, ...], ...]] = {}
    for a, ba in by_mono.items():
        left = _matmul(ba, inner)
        for b, bb in by_mono.items():
            mat = _matmul(left, list(zip(*bb, strict=True)))
            out[(a, b)] = tuple(tuple({0: x} if x else {} for x in row) for row in mat)
    return out


# ---------------------------------------------------------------------- the energy polynomial
def energy_polynomial(
    rows: Any, du: Direction, dv: Direction, energy: str
) -> tuple[dict[tuple[int, ...], Fraction], str | None]:
    """The energy of the exact net `rows` ((m+1) x (n+1) points of Fractions) as a sparse
    polynomial {(u exponents.., v exponents.., c exponent, 1/c exponent): coefficient} in the
    parameters of both directions (and the constant c of an atom family, named second)."""
    constants = {c for c in (du.constant, dv.constant) if c}
    if len(constants) > 1:
        raise ValueError(
            "family: the two directions' energies involve different constants "
            f"({' and '.join(sorted(constants))}); their surface energy is not available"
        )
    dim = len(rows[0][0])
    m, n = len(rows) - 1, len(rows[0]) - 1
    out: dict[tuple[int, ...], Fraction] = {}
    for ku, kv, weight in ENERGIES[energy]:
        gu, gv = du.grams(ku), dv.grams(kv)
        for (c, d), mat_v in gv.items():
            # R[i][k] = Σ_coord Σ_jl G_v[j][l] P_ij · P_kl, per exponent of the constant
            r_mat: list[list[Laurent]] = [[{} for _ in range(m + 1)] for _ in range(m + 1)]
            for i in range(m + 1):
                for k in range(m + 1):
                    acc = r_mat[i][k]
                    for j in range(n + 1):
                        for l_ in range(n + 1):
                            g = mat_v[j][l_]
                            if not g:
                                continue
                            dot = sum(
                                (rows[i][j][x] * rows[k][l_][x] for x in range(dim)), Fraction(0)
                            )
                            if dot:
                                for e, v in g.items():
                                    acc[e] = acc.get(e, Fraction(0)) + v * dot
            for (a, b), mat_u in gu.items():
                total: Laurent = {}
                for i in range(m + 1):
                    for k in range(m + 1):
                        g, r = mat_u[i][k], r_mat[i][k]
                        for e1, v1 in g.items():
                            for e2, v2 in r.items():
                                total[e1 + e2] = total.get(e1 + e2, Fraction(0)) + v1 * v2
                mono = (
                    *(x + y for x, y in zip(a, b, strict=True)),
                    *(x + y for x, y in zip(c, d, strict=True)),
                )
                for e, v in total.items():
                    if v:
                        key = (*mono, max(e, 0), max(-e, 0))
                        out[key] = out.get(key, Fraction(0)) + weight * v
    return {key: v for key, v in out.items() if v}, next(iter(constants), None)


def _value(
    poly: dict[tuple[int, ...], Fraction], point: tuple[Fraction, ...], constant: str | None
) -> Any:
    """The polynomial at exact parameter values, exactly (a ConstantFraction with a constant)."""
    from .hazmat.constants import ConstantFraction

    by_power: dict[int, Fraction] = {}
    for key, v in poly.items():
        w = v
        for x, e in zip(point, key[:-2], strict=True):
            w *= x**e
        e = key[-2] - key[-1]
        by_power[e] = by_power.get(e, Fraction(0)) + w
    if constant is None or all(e == 0 or not v for e, v in by_power.items()):
        return by_power.get(0, Fraction(0))
    return ConstantFraction.from_laurent({e: v for e, v in by_power.items() if v}, constant)


def _exact_rows(net: NetLike) -> tuple[Any, bool]:
    grid = _as_net(net)
    exact = _exact_net(net)
    if exact is None or len(exact[0][0]) != grid.shape[2]:
        rows = tuple(tuple(tuple(Fraction(float(c)) for c in p) for p in row) for row in grid)
        return rows, False
    return exact, True


def surface_energy(surf: Any, energy: str = "thin_plate") -> Any:
    """The membrane or thin-plate energy of any surface over its domain (lb.surface_energy):
    exact (a Fraction, or a ConstantFraction in π or e^W for an AtomSurface) for an exact
    surface, else a float. A trigonometric direction across a hyperbolic one gives a
    ConstantSum in π and e^W (exact terms, a certified enclosure; never compared). A surface of
    one-parameter or built-in families goes to surface_energies.surface_energy."""
    if not hasattr(surf, "family_u"):
        return surface_energies.surface_energy(surf, energy)
    energy = val.choice(energy, "energy", tuple(ENERGIES))
    m, n = surf.degrees
    du, dv = _direction(surf.family_u, m), _direction(surf.family_v, n)
    rows, exact = _exact_rows(surf.net if surf._exact is None else surf._exact)
    point = (*_flat(du, surf.params_u), *_flat(dv, surf.params_v))
    if du.constant and dv.constant and du.constant != dv.constant:
        mats = _param_matrices(surf.family_u, surf.family_v, m, n, energy)
        got: Any = mats.at(rows, point)
    else:
        poly, constant = energy_polynomial(rows, du, dv, energy)
        got = _value(poly, point, constant)
    return got if exact and surf.is_exact else float(got)


# ---------------------------------------------------------------------- the matrices
@dataclass(frozen=True, eq=False)
class ParamSurfaceEnergyMatrices:
    """The energy of a net of (m+1) x (n+1) points as Σ_key x^key · vec(P)ᵀ Q_key vec(P),
    summed over coordinates, vec(P) the net read row by row (P_00, P_01, …, P_0n, P_10, …).

    A key is the exponents of the parameters `names` (u's then v's, ``lam_u``, ``mu_u``, …,
    ``lam_v``), then the exponents, of any sign, of the `constants` (none for polynomial
    families; ``pi`` or ``exp(W)`` for trigonometric or hyperbolic ones; both for a
    trigonometric direction across a hyperbolic one). ``terms[key] = (scale, U)``: U
    upper-triangular primitive integers with off-diagonal entries doubled, the curves' X and
    Y convention, so vec(P)ᵀ Q_key vec(P) = scale · Σ_{r<=c} U[r][c] P_r · P_c. For a
    polynomial family each monomial's matrix is one integer matrix with a scale; with a
    constant, an entry lies in ℚ[c, 1/c] and has no single integer scale: Q is a Laurent
    polynomial in c whose coefficients are such matrices, one per power.
    """

    energy: str
    degrees: tuple[int, int]
    names: tuple[str, ...]
    constants: tuple[str, ...]
    terms: dict[tuple[int, ...], tuple[Fraction, tuple[tuple[int, ...], ...]]]
    full: dict[tuple[int, ...], tuple[tuple[Fraction, ...], ...]] = field(repr=False)

    def polynomial(self, net: NetLike) -> dict[tuple[int, ...], Fraction | float]:
        """{key: e_key}: the energy of one net as Σ e_key x^key (exact for an exact net)."""
        rows, exact = _exact_rows(net)
        m, n = self.degrees
        if len(rows) != m + 1 or any(len(row) != n + 1 for row in rows):
            raise ValueError(f"net must have {m + 1} x {n + 1} points, got {len(rows)} rows")
        found = surface_energies.keyed_quadratic(_forms(self), [p for row in rows for p in row])
        return {key: v if exact else float(v) for key, v in found.items()}

    def at(self, rows: Any, point: tuple[Fraction, ...]) -> Any:
        """The energy of the exact net `rows` at exact parameter values `point` (in the order
        of `names`): a Fraction, a ConstantFraction (one constant) or a ConstantSum (two)."""
        count = len(self.names)
        by_power: dict[tuple[int, ...], Fraction] = {}
        for key, v in self.polynomial(rows).items():
            w = Fraction(v)
            for x, e in zip(point, key[:count], strict=True):
                w *= x**e
            power = key[count:]
            by_power[power] = by_power.get(power, Fraction(0)) + w
        if len(self.constants) == 2:
            return ConstantSum({(a, b): q for (a, b), q in by_power.items()}, self.constants)
        if self.constants:
            return _value({(e, 0): q for (e,), q in by_power.items()}, (), self.constants[0])
        return by_power.get((), Fraction(0))


@cache
def _param_matrices(
    family_u: Any, family_v: Any, m: int, n: int, energy: str
) -> ParamSurfaceEnergyMatrices:
    """Q_key as Σ_terms weight · G^{k_u}_u ⊗ G^{k_v}_v over the pairs of parameter monomials
    of each direction's curve Gram matrices (the Kronecker identity of the module's doc)."""
    du, dv = _direction(family_u, m), _direction(family_v, n)
    constants = tuple(dict.fromkeys(c for c in (du.constant, dv.constant) if c))
    slot_u = constants.index(du.constant) if du.constant else None
    slot_v = constants.index(dv.constant) if dv.constant else None
    size = (m + 1) * (n + 1)
    acc: dict[tuple[int, ...], list[list[Fraction]]] = {}
    for ku, kv, weight in ENERGIES[energy]:
        gu, gv = du.grams(ku), dv.grams(kv)
        for (a, b), mat_u in gu.items():
            for (c, d), mat_v in gv.items():
                mono = (
                    *(x + y for x, y in zip(a, b, strict=True)),
                    *(x + y for x, y in zip(c, d, strict=True)),
                )
                for i in range(m + 1):
                    for k in range(m + 1):
                        for e1, x1 in mat_u[i][k].items():
                            for j in range(n + 1):
                                for l_ in range(n + 1):
                                    for e2, x2 in mat_v[j][l_].items():
                                        power = [0] * len(constants)
                                        if slot_u is not None:
                                            power[slot_u] += e1
                                        if slot_v is not None:
                                            power[slot_v] += e2
                                        key = (*mono, *power)
                                        if key not in acc:
                                            acc[key] = [[Fraction(0)] * size for _ in range(size)]
                                        acc[key][i * (n + 1) + j][k * (n + 1) + l_] += (
                                            weight * x1 * x2
                                        )
    full = {
        key: tuple(tuple(row) for row in mat)
        for key, mat in sorted(acc.items())
        if any(any(row) for row in mat)
    }
    names = tuple(f"{x}_u" for x in du.names) + tuple(f"{x}_v" for x in dv.names)
    terms = {key: surface_energies._integer_form(mat) for key, mat in full.items()}
    return ParamSurfaceEnergyMatrices(energy, (m, n), names, constants, terms, full)


def surface_energy_matrices(
    degrees: tuple[int, int], energy: str = "thin_plate", family: object = "same_degree"
) -> Any:
    """The exact quadratic forms of a surface energy for nets of (m+1) x (n+1) points
    (lb.surface_energy_matrices): ParamSurfaceEnergyMatrices for several-parameter, indexed
    and trigonometric/hyperbolic/mixed families (one, or a pair (u, v)); the one-parameter and
    built-in families' SurfaceEnergyMatrices (surface_energies) otherwise."""
    if not _param_families(family):
        return surface_energies.surface_energy_matrices(degrees, energy, family)
    energy = val.choice(energy, "energy", tuple(ENERGIES))
    if not isinstance(degrees, tuple | list) or len(degrees) != 2:
        raise ValueError(f"degrees must be a pair (m, n), got {val.describe(degrees)}")
    m, n = (val.integer(d, "degrees") for d in degrees)
    fu, fv = _family_pair(family)
    try:
        for fam, deg, name in ((fu, m, "u"), (fv, n, "v")):
            pd.checked_degree(fam, deg, name)
    except ValueError as exc:  # the check speaks of a net; here the degrees were given
        raise ValueError(f"degrees = ({m}, {n}): {str(exc).removeprefix('net, ')}") from None
    return _param_matrices(fu, fv, m, n, energy)


def _flat(d: Direction, given: dict[str, Any]) -> tuple[Fraction, ...]:
    """The values of one direction in the order of d.names, as exact Fractions."""
    if d.indexed is not None:
        seq = given[d.indexed]
        return tuple(Fraction(val.real_number(x, d.indexed)) for x in seq)
    return tuple(Fraction(val.real_number(given[x], x)) for x in d.names)


# ---------------------------------------------------------------------- the optimum
def _rational_power(
    poly: dict[tuple[int, ...], Fraction], constants: tuple[str, ...], box: list[Any]
) -> tuple[np.ndarray, Fraction]:
    """(power, slack): the dense power coefficients in the parameters of the energy
    `poly` ({(parameter exponents.., exponent of each of `constants`, of any sign): q}) with
    each constant c replaced by a rational ĉ within 2^-64 of it (the midpoint of
    hazmat.constants.constant_bounds), and a proven bound `slack` of |E(x; c) − E(x; ĉ)| over
    the box. A product of powers of constants > 0 is monotone in each, so its distance from
    the product at ĉ is greatest at a corner of the constants' enclosure box; two constants
    (π across e^W) are bounded the same way as one, and never compared. A lower bound of the
    rational polynomial minus `slack` bounds the true energy: this keeps the constants out of
    the branch and bound, whose cost grows with the number of variables."""
    from .hazmat.constants import constant_bounds

    count = len(box)
    bounds = [constant_bounds(c, CONSTANT_BITS) for c in constants]
    hats = [(lo + hi) / 2 for lo, hi in bounds]
    size = [max(abs(a), abs(b)) for a, b in box]
    degree = [max((key[j] for key in poly), default=0) for j in range(count)]
    power = np.empty(tuple(d + 1 for d in degree), dtype=object)
    power.fill(Fraction(0))
    slack = Fraction(0)
    for key, v in poly.items():
        exps = key[count:]
        at_hat = Fraction(1)
        for c_hat, e in zip(hats, exps, strict=True):
            at_hat *= c_hat**e
        power[key[:count]] += v * at_hat
        if any(exps):
            reach = Fraction(1)
            for x, a in zip(size, key[:count], strict=True):
                reach *= x**a
            corners = [Fraction(1)]
            for (lo, hi), e in zip(bounds, exps, strict=True):
                corners = [w * c**e for w in corners for c in (lo, hi)]
            slack += abs(v) * max(abs(w - at_hat) for w in corners) * reach
    return power, slack


def _upper_gap(value: Any, lower: Fraction) -> tuple[float, float]:
    """(an upper bound of value − lower, a lower bound of |value|) as floats rounded outwards
    enough for the 1e-12 test; a ConstantSum (π across e^W) through its enclosure, since
    such sums are never compared exactly."""
    if isinstance(value, ConstantSum):
        lo, hi = value.enclosure(CONSTANT_BITS * 2)
        return float(hi - lower), float(min(abs(lo), abs(hi)) if lo * hi > 0 else 0)
    return float(value - lower), abs(float(value))


def _grid_start(power: np.ndarray, box: list[Any]) -> tuple[Fraction, ...]:
    """The best point of a float grid over the box (about 20,000 points): the branch and
    bound's first candidate, so that it prunes from the start."""
    count = len(box)
    side = max(3, int(round(20_000 ** (1 / count))))
    axes = [np.linspace(float(a), float(b), side) for a, b in box]
    mesh = np.meshgrid(*axes, indexing="ij")
    flat = [g.ravel() for g in mesh]
    coeffs = np.array(power.tolist(), dtype=float)
    total = np.zeros(flat[0].shape)
    for idx in zip(*np.nonzero(coeffs), strict=True):
        term = np.full(flat[0].shape, coeffs[idx])
        for x, e in zip(flat, idx, strict=True):
            if e:
                term = term * x**e
        total += term
    k = int(np.argmin(total))
    return tuple(Fraction(float(axis[k])) for axis in flat)


@dataclass(frozen=True)
class SurfaceParameterOptimum(Mapping[str, Any]):
    """The energy-optimal parameters of both directions by name: ``r["lam_u"]``,
    ``r["mu_v"]`` (an indexed family's as one tuple, ``r["lam_u"]``); ``energy`` exact at
    that point, ``lower_bound`` a proven lower bound of the energy over the whole box within
    1e-12 (relative) of it; ``boundary`` names the parameters at an end of their range."""

    parameters: dict[str, Any]
    energy: Any
    lower_bound: Any
    boundary: str
    certified: bool
    method: str = "certified"  # or "exact": the closed form (param_surface_optimum)

    def __getitem__(self, key: str) -> Any:
        if key in self.parameters:
            return self.parameters[key]
        if key in _FIELDS:
            return getattr(self, key)
        raise KeyError(f"{key!r}: the parameters are {', '.join(self.parameters)}")

    def __iter__(self) -> Iterator[str]:
        return iter((*self.parameters, *_FIELDS))

    def __len__(self) -> int:
        return len(self.parameters) + len(_FIELDS)


_FIELDS = ("energy", "lower_bound", "boundary", "certified", "method")


def _family_pair(family: Any) -> tuple[Any, Any]:
    """(u family, v family) of `family`: one family from load_family, or a pair of them."""
    fu, fv = family if isinstance(family, tuple | list) else (family, family)
    if pd.is_atom(fu) or pd.is_atom(fv):  # a built-in polynomial direction may be named
        fu, fv = pd.polynomial_family(fu), pd.polynomial_family(fv)
    for f in (fu, fv):
        if pd.is_class(f):
            continue
        if not hasattr(f, "degrees") or not hasattr(f, "parameters"):
            raise TypeError(
                "family: a family from load_family is needed in each direction, got "
                f"{type(f).__name__}"
            )
    return fu, fv


def optimal_parameters(
    net: NetLike, energy: str, family: Any, *, start: tuple[float, ...] | None = None
) -> SurfaceParameterOptimum:
    """The certified global minimum of the surface energy over both directions' parameter
    boxes (`family` one family from load_family or a pair); see the module's doc. `start`
    (a point of every parameter, u's then v's, found otherwise: a batch's vectorised float
    search) replaces the float grid's first candidate; it only speeds the pruning, the
    certificate is the same."""
    energy = val.choice(energy, "energy", tuple(ENERGIES))
    fu, fv = _family_pair(family)
    if np.ndim(val.real_array(net, "net")) == 4:
        raise ValueError(
            "net: a batch of nets is solved vectorised for one-parameter families only; "
            "call optimal_parameters once per net for this family"
        )
    grid = _as_net(net)
    m, n = int(grid.shape[0]) - 1, int(grid.shape[1]) - 1
    for fam, deg, name in ((fu, m, "u"), (fv, n, "v")):
        pd.checked_degree(fam, deg, name)
    du, dv = _direction(fu, m), _direction(fv, n)
    rows, exact = _exact_rows(net)
    count = len(du.names) + len(dv.names)
    poly, constants, value_at = _energy_in_parameters(rows, du, dv, energy)
    ranges = [du.ranges[x] for x in du.names] + [dv.ranges[x] for x in dv.names]
    box = [(r[0], r[1]) for r in ranges]
    power, slack = _rational_power(poly, constants, box)
    first = (
        _grid_start(power, box)
        if start is None
        else tuple(
            min(max(Fraction(float(x)), lo), hi) for x, (lo, hi) in zip(start, box, strict=True)
        )
    )
    got = box_bernstein.minimum(power, box, TOLERANCE, BUDGET, start=[first])
    point = tuple(got["point"][:count])
    value = value_at(point)
    lower = got["lower"] - slack
    gap, size = _upper_gap(value, lower)
    certified = got["certified"] and not (TOLERANCE * max(1.0, size) < gap)
    if not certified:
        raise ValueError(
            f"optimal_parameters: the minimum of the {energy} energy over the box was not "
            f"certified within the budget (best {float(value)}, lower bound {float(lower)})"
        )
    energy_out = value if exact else float(value)
    lower_out = lower if exact else float(lower)
    values, where = named_point(du, dv, point, exact)
    return SurfaceParameterOptimum(values, energy_out, lower_out, where, certified)


def _energy_in_parameters(
    rows: Any, du: Direction, dv: Direction, energy: str
) -> tuple[dict[tuple[int, ...], Fraction], tuple[str, ...], Any]:
    """(poly, constants, value_at): the energy of the exact net `rows` as {(parameter
    exponents.., exponent of each constant): q}, the constants it involves (none, one, or π
    and e^W for a trigonometric direction across a hyperbolic one), and the exact energy at
    a rational point (a Fraction, ConstantFraction or ConstantSum).

    The one keyed accumulation of both surface energy modules
    (surface_energies.keyed_quadratic): the matrices Q_key of surface_energy_matrices (each
    direction's Gram matrices per monomial in Kronecker products, built once per pair of
    families and degrees) as integers over one denominator per key, against the net's Gram
    products in integers."""
    mats = _param_matrices(du.family, dv.family, du.degree, dv.degree, energy)
    names, constants = mats.names, mats.constants
    found = surface_energies.keyed_quadratic(_forms(mats), [p for row in rows for p in row])
    poly = {key: q for key, q in found.items() if q}
    count = len(names)

    def value_at(point: tuple[Fraction, ...]) -> Any:
        by_power: dict[tuple[int, ...], Fraction] = {}
        for key, q in poly.items():
            w = q
            for x, e in zip(point, key[:count], strict=True):
                if e:
                    w *= x**e
            by_power[key[count:]] = by_power.get(key[count:], Fraction(0)) + w
        if len(constants) == 2:
            return ConstantSum({(a, b): q for (a, b), q in by_power.items()}, constants)
        if constants:
            return _value({(e, 0): q for (e,), q in by_power.items()}, (), constants[0])
        return by_power.get((), Fraction(0))

    return poly, constants, value_at


@cache
def _forms(mats: ParamSurfaceEnergyMatrices) -> surface_energies.IntegerForms:
    return surface_energies.integer_forms(mats.full)


def named_point(
    du: Direction, dv: Direction, point: tuple[Any, ...], exact: bool
) -> tuple[dict[str, Any], str]:
    """({name_u: value, ...}, boundary note) of a point of both directions' parameters, in
    the order of du.names then dv.names (floats unless `exact`; an indexed family's values
    as one tuple)."""
    out: Any = (lambda x: x) if exact else float
    values: dict[str, Any] = {}
    where = []
    k = 0
    for d, suffix in ((du, "u"), (dv, "v")):
        vals = point[k : k + len(d.names)]
        for x, v in zip(d.names, vals, strict=True):
            lo_, hi_, lo_closed, hi_closed, _ = d.ranges[x]
            if isinstance(v, Fraction) and v in (lo_, hi_):
                end = "lower" if v == lo_ else "upper"
                closed = lo_closed if v == lo_ else hi_closed
                note = "" if closed else ", excluded: not attained"
                where.append(f"{x}_{suffix} = {v} ({end} end{note})")
        if d.indexed is not None:
            values[f"{d.indexed}_{suffix}"] = tuple(out(v) for v in vals)
        else:
            values.update({f"{x}_{suffix}": out(v) for x, v in zip(d.names, vals, strict=True)})
        k += len(d.names)
    return values, "; ".join(where)
