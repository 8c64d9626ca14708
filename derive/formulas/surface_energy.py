"""Surface energies as quadratic forms in the control net, derived by integrating the
tensor-product basis itself (issue #31).

A tensor-product surface of the families F_u (degree m, shape λ_u) and F_v (degree n,
shape λ_v) is S(u, v) = Σ_{i,j} P_ij b_i(u; λ_u) c_j(v; λ_v). Its two energies over the unit
square are

    membrane    ∫∫ |S_u|² + |S_v|²
    thin plate  ∫∫ |S_uu|² + 2|S_uv|² + |S_vv|²

and each is vec(P)ᵀ Q(λ_u, λ_v) vec(P) summed over coordinates, vec(P) the net read row by
row (P_00, P_01, …, P_0n, P_10, …). Here every entry of Q is obtained directly: the basis
function B_ij(u, v) = b_i(u) c_j(v) is formed as one exact polynomial in (u, v, λ_u, λ_v)
(FLINT's fmpq_mpoly), differentiated, multiplied by its partner and integrated over u and
then v; what remains is a polynomial in (λ_u, λ_v). Q = Σ_{a,b} λ_u^a λ_v^b Q_ab and each Q_ab
is printed as scale · U with U upper-triangular primitive integers (off-diagonal entries
doubled), the curves' X and Y convention (energy.upper_form).

Checked at derivation time (check_kronecker): Q equals the Kronecker-product-and-sum form
built from the curves' own energy forms (energy.energy_forms, energy.stiffness),

    Q = Σ_terms weight · A^{k_u}(λ_u) ⊗ A^{k_v}(λ_v),   A^k(λ) = S_ff − 2λ S_fg + λ² S_gg,

so the two derivations, one without and one with the separation of variables, agree.
"""

from __future__ import annotations

from fractions import Fraction
from functools import cache

import flint
import sympy as sp

from ..algebra import lam, t
from ..algebra.bernstein import bernstein_basis
from ..families.registry import REFERENCE, builtin_families
from .energy import energy_forms, stiffness, upper_form

# (k_u, k_v, weight): the energy is Σ weight ∫∫ |∂^(k_u+k_v) S / ∂u^k_u ∂v^k_v|²
ENERGIES: dict[str, tuple[tuple[int, int, int], ...]] = {
    "membrane": ((1, 0, 1), (0, 1, 1)),
    "thin_plate": ((2, 0, 1), (1, 1, 2), (0, 2, 1)),
}
# The emitted degree range in each direction (intersected with each family's own degrees);
# kept small so that `derive --check` stays fast. Other degrees: the runtime's Kronecker form.
SURFACE_DEGREES = range(1, 4)
FAMILIES: dict[str, object] = {REFERENCE: None} | {b.name: b.module() for b in builtin_families()}
# Families defined by data, registered for this process (register): derived on demand, never
# emitted (emitted() reads FAMILIES only, so a registration cannot change generated/).
DEFINED: dict[str, object] = {}

_CTX = flint.fmpq_mpoly_ctx.get(("u", "v", "lam_u", "lam_v"))
_U, _V = 0, 1  # generator indices of u and v
_ZERO = flint.fmpq(0)

FullMatrix = tuple[tuple[flint.fmpq, ...], ...]  # exact; FLINT for speed


def register(name: str, module) -> None:
    """A family defined by data (formulas/family.py's register_formulas) joins the surface
    derivations for this process: `module` has DEGREES and basis_polys(degree) (Polys in t,
    lam). Re-registering a name clears what was derived for the old definition."""
    DEFINED[name] = module
    for fn in (_curve_basis, tensor_basis, surface_matrices, surface_forms, energy_forms):
        fn.cache_clear()


def known(family: str) -> bool:
    return family in FAMILIES or family in DEFINED


def _module(family: str):
    """The derivation of a family: None for the reference Bernstein basis (REFERENCE)."""
    return FAMILIES[family] if family in FAMILIES else DEFINED[family]


def degrees(family: str) -> tuple[int, ...]:
    """The degrees emitted for `family` in one direction."""
    module = _module(family)
    own = range(1, 15) if module is None else module.DEGREES
    return tuple(d for d in SURFACE_DEGREES if d in own)


@cache
def _curve_basis(family: str, degree: int) -> tuple[dict[tuple[int, int], Fraction], ...]:
    """The family's degree-`degree` basis, each function as {(power of t, power of λ): coef}."""
    module = _module(family)
    if module is None:
        polys = [sp.Poly(bernstein_basis(degree, i), t, lam) for i in range(degree + 1)]
    else:
        polys = list(module.basis_polys(degree))
    return tuple(
        {(int(e[0]), int(e[1])): Fraction(int(c.p), int(c.q)) for e, c in p.terms()} for p in polys
    )


def _direction(basis: dict[tuple[int, int], Fraction], axis: int) -> flint.fmpq_mpoly:
    """One curve basis function as a polynomial in (u, λ_u) (axis 0) or (v, λ_v) (axis 1)."""
    out = {}
    for (pt, pl), coef in basis.items():
        exps = [0, 0, 0, 0]
        exps[axis], exps[2 + axis] = pt, pl
        out[tuple(exps)] = flint.fmpq(coef.numerator, coef.denominator)
    return _CTX.from_dict(out)


@cache
def tensor_basis(family_u: str, family_v: str, m: int, n: int) -> tuple[flint.fmpq_mpoly, ...]:
    """B_ij(u, v; λ_u, λ_v) = b_i(u; λ_u) c_j(v; λ_v), row-major in (i, j)."""
    bu = [_direction(b, _U) for b in _curve_basis(family_u, m)]
    bv = [_direction(c, _V) for c in _curve_basis(family_v, n)]
    return tuple(b * c for b in bu for c in bv)


def _by_parameters(
    p: flint.fmpq_mpoly,
) -> dict[tuple[int, int], dict[tuple[int, int], flint.fmpq]]:
    """p = Σ λ_u^a λ_v^b p_ab(u, v), as {(a, b): {(power of u, power of v): coefficient}}."""
    out: dict[tuple[int, int], dict[tuple[int, int], flint.fmpq]] = {}
    for (eu, ev, pa, pb), coef in p.to_dict().items():  # exponents come as fmpz
        out.setdefault((int(pa), int(pb)), {})[(int(eu), int(ev))] = coef
    return out


def _partial(p: flint.fmpq_mpoly, ku: int, kv: int) -> flint.fmpq_mpoly:
    for _ in range(ku):
        p = p.derivative(_U)
    for _ in range(kv):
        p = p.derivative(_V)
    return p


@cache
def surface_matrices(
    family_u: str, family_v: str, m: int, n: int, energy: str
) -> dict[tuple[int, int], FullMatrix]:
    """{(a, b): Q_ab}, full symmetric and exact, with E = Σ λ_u^a λ_v^b vec(P)ᵀ Q_ab vec(P);
    terms that vanish identically are left out.

    Each ∫∫ ∂B_r ∂B_c over the square is the product's monomials integrated one by one,
    ∫∫ u^i v^j = 1/((i + 1)(j + 1)): with ∂B_r = Σ_μ λ^μ Σ_α c_rμα u^α_u v^α_v, the entry's
    λ^(μ+ν) part is Σ_α,β c_rμα H_αβ c_cνβ, H_αβ = ∫∫ u^(α_u+β_u) v^(α_v+β_v) the moments
    of the square. So every entry at once is a product of exact matrices, Cᵀ_μ H C_ν (issue
    #29: the same numbers as multiplying and integrating each pair, a tenth of the time)."""
    basis = tensor_basis(family_u, family_v, m, n)
    size = len(basis)
    acc: dict[tuple[int, int], flint.fmpq_mat] = {}
    for ku, kv, weight in ENERGIES[energy]:
        parts = [_by_parameters(_partial(b, ku, kv)) for b in basis]
        monos = sorted({mono for part in parts for sub in part.values() for mono in sub})
        if not monos:
            continue
        keys = sorted({key for part in parts for key in part})
        columns = {  # C_μ: one column per basis function, one row per monomial of (u, v)
            key: flint.fmpq_mat(
                [[part.get(key, {}).get(mono, _ZERO) for part in parts] for mono in monos]
            )
            for key in keys
        }
        moments = flint.fmpq_mat(
            [
                [flint.fmpq(weight, (a[0] + b[0] + 1) * (a[1] + b[1] + 1)) for b in monos]
                for a in monos
            ]
        )
        left = {key: columns[key].transpose() * moments for key in keys}
        for mu in keys:
            for nu in keys:
                total = (mu[0] + nu[0], mu[1] + nu[1])
                term = left[mu] * columns[nu]
                acc[total] = acc[total] + term if total in acc else term
    out = {}
    for key, mat in sorted(acc.items()):
        rows = tuple(tuple(mat[r, c] for c in range(size)) for r in range(size))
        if any(any(row) for row in rows):
            out[key] = rows
    return out


@cache
def surface_forms(
    family_u: str, family_v: str, m: int, n: int, energy: str
) -> dict[tuple[int, int], tuple[Fraction, tuple[tuple[int, ...], ...]]]:
    """{(a, b): (scale, U)}: vec(P)ᵀ Q_ab vec(P) = scale · Σ_{r<=c} U[r][c] P_r·P_c, checked
    against the Kronecker form first."""
    full = surface_matrices(family_u, family_v, m, n, energy)
    check_kronecker(family_u, family_v, m, n, energy, full)
    return {key: upper_form(mat) for key, mat in full.items()}


# ---------------------------------------------------------------------- the identity
def full_from_upper(scale: Fraction, upper) -> list[list[Fraction]]:
    """The symmetric matrix of a form printed as scale · U (U upper, off-diagonals doubled)."""
    size = len(upper)
    return [
        [scale * Fraction(upper[min(r, c)][max(r, c)], 1 if r == c else 2) for c in range(size)]
        for r in range(size)
    ]


def curve_form(family: str, degree: int, k: int) -> tuple[list[list[flint.fmpq]], ...]:
    """(A_0, A_1, A_2): ∫|p^(k)|² = Dᵀ(Σ λ^p A_p)D for a curve of `family`, read from the
    curves' derivation (energy.py), not from the surface's."""
    size = degree + 1
    if _module(family) is None:
        if k > degree:
            return ([[_ZERO] * size for _ in range(size)],)
        return (stiffness(degree, k).table(),)
    forms = energy_forms(family, degree, k)
    ff, fg, gg = (
        [
            [flint.fmpq(x.numerator, x.denominator) for x in row]
            for row in full_from_upper(*forms[key])
        ]
        for key in ("ff", "fg", "gg")
    )
    return ff, [[-2 * x for x in row] for row in fg], gg


def kronecker_matrices(
    family_u: str, family_v: str, m: int, n: int, energy: str
) -> dict[tuple[int, int], FullMatrix]:
    """Q_ab as Σ_terms weight · A^{k_u}_a ⊗ A^{k_v}_b from the curves' forms."""
    size = (m + 1) * (n + 1)
    acc: dict[tuple[int, int], list[list[flint.fmpq]]] = {}
    for ku, kv, weight in ENERGIES[energy]:
        for a, au in enumerate(curve_form(family_u, m, ku)):
            for b, av in enumerate(curve_form(family_v, n, kv)):
                if (a, b) not in acc:
                    acc[(a, b)] = [[_ZERO] * size for _ in range(size)]
                mat = acc[(a, b)]
                for i in range(m + 1):
                    for k in range(m + 1):
                        if not au[i][k]:
                            continue
                        w = weight * au[i][k]
                        for j in range(n + 1):
                            row = mat[i * (n + 1) + j]
                            for l_ in range(n + 1):
                                row[k * (n + 1) + l_] += w * av[j][l_]
    return {
        key: tuple(tuple(row) for row in mat)
        for key, mat in sorted(acc.items())
        if any(any(row) for row in mat)
    }


def check_kronecker(family_u, family_v, m, n, energy, full=None) -> None:
    """Raise unless the direct integration equals the Kronecker-product-and-sum form."""
    direct = full if full is not None else surface_matrices(family_u, family_v, m, n, energy)
    kron = kronecker_matrices(family_u, family_v, m, n, energy)
    if direct != kron:
        raise AssertionError(
            f"{energy} energy of a {family_u} x {family_v} surface of degrees ({m}, {n}): the "
            "direct integration and the Kronecker form of the curves' Gram matrices differ"
        )


def emitted() -> dict[str, dict[tuple[int, int, str], dict]]:
    """{family: {(m, n, energy): {(a, b): (scale, U)}}} for one family in both directions."""
    return {
        fam: {
            (m, n, energy): surface_forms(fam, fam, m, n, energy)
            for m in degrees(fam)
            for n in degrees(fam)
            for energy in ENERGIES
        }
        for fam in FAMILIES
    }
