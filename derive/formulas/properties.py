"""Exact decisions of the basis properties the papers state, over a whole parameter interval.

Every basis function b_i of degree n is held by its Bernstein coefficients in degree
N = n + offset, each a polynomial in λ with rational coefficients (FLINT's ``fmpq_poly``):
b_i(t, λ) = Σ_j c_ij(λ) B_j^N(t). The properties are then statements about these polynomials,
decided for EVERY λ of an interval (open or closed ends), never at sampled values of λ:

* partition of unity, symmetry, end-point interpolation, reduction to Bernstein: identities
  between the polynomials c_ij(λ) (compared coefficient by coefficient);
* linear independence: the rank of C(λ) = (c_ij(λ)). Its determinant (square C) or the Gram
  determinant det(C Cᵀ) (= Σ of squared maximal minors by Cauchy–Binet, so its real zeros are
  exactly the λ where the rank drops) is interpolated exactly from FLINT determinants at
  integer λ, factored over Z and its real roots in the interval isolated with rational ends;
* non-negativity: c_ij(λ) ≥ 0 on the interval is sufficient. Where it fails, b_i is decided
  exactly: b_i is affine in λ for every family of the project, so for each t its minimum over
  the interval is at an end of the closure, and b_i ≥ 0 on the interval iff the two
  polynomials b_i(t, lo), b_i(t, hi) are ≥ 0 on [0, 1] (decided by exact real-root isolation
  in t). A failure comes with an exact counterexample (λ inside the interval, t, value).

Also emitted: ``singular_parameters`` (generated/properties.py), the λ inside each family's
range where its degree-n basis is linearly dependent.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from functools import cache
from math import comb

import flint
import sympy as sp

from ..algebra import bernstein_matrices
from ..families.registry import REFERENCE, builtin_families
from ..grammar import Interval

_X = sp.Symbol("x")


# The built-in families (derive/families/*.toml, in order) and the reference Bernstein basis.
FAMILY_RANGES = {
    b.name: Interval(
        b.definition.lo, b.definition.hi, not b.definition.lo_closed, not b.definition.hi_closed
    )
    for b in builtin_families()
}
BUILTIN_RANGES = dict(FAMILY_RANGES)  # what generated/properties.py holds
OFFSETS = {b.name: b.definition.offset for b in builtin_families()} | {REFERENCE: 0}
FAMILY_DEGREES = {b.name: b.module().DEGREES for b in builtin_families()} | {
    REFERENCE: range(1, 13)
}
_BASES = {b.name: b.module().basis_polys for b in builtin_families()}


def register(name: str, basis_polys, offset: int, degrees: range, interval: Interval) -> None:
    """A family defined by data (derive/families/engine.py) gets the same property procedures."""
    _BASES[name] = basis_polys
    OFFSETS[name] = offset
    FAMILY_DEGREES[name] = degrees
    FAMILY_RANGES[name] = interval
    # every cache here is keyed by the family's name: a definition registered again under
    # the same name (edited and derived again in one process) must not get the old answers
    coefficients.cache_clear()
    independence_polynomial.cache_clear()
    singular_roots.cache_clear()


# --------------------------------------------------------------------------- coefficients


def _q(v) -> flint.fmpq:
    v = Fraction(v)
    return flint.fmpq(v.numerator, v.denominator)


def _frac(v: flint.fmpq) -> Fraction:
    return Fraction(int(v.p), int(v.q))


@cache
def coefficients(family: str, n: int) -> tuple[tuple[flint.fmpq_poly, ...], ...]:
    """c[i][j](λ): coefficient of B_j^{n+offset} in basis function i of degree n."""
    if family == REFERENCE:
        return tuple(
            tuple(flint.fmpq_poly([1 if i == j else 0]) for j in range(n + 1)) for i in range(n + 1)
        )
    polys = _BASES[family](n)
    mats = bernstein_matrices(list(polys), n + OFFSETS[family])
    rows, cols = len(mats[0]), len(mats[0][0])
    return tuple(
        tuple(flint.fmpq_poly([_q(mats[p][i][j]) for p in range(len(mats))]) for j in range(cols))
        for i in range(rows)
    )


def _at(p: flint.fmpq_poly, x: Fraction) -> Fraction:
    return _frac(p(_q(x)))


def _basis_in_t(family: str, n: int, i: int, lam: Fraction | None) -> flint.fmpq_poly:
    """b_i(t, lam) as a polynomial in t (power basis), exactly."""
    row = coefficients(family, n)[i]
    N = len(row) - 1
    out = flint.fmpq_poly([])
    t = flint.fmpq_poly([0, 1])
    for j, c in enumerate(row):
        cj = _q(_at(c, lam)) if lam is not None else c(0)
        if cj != 0:
            out += cj * comb(N, j) * t**j * (1 - t) ** (N - j)
    return out


# --------------------------------------------------------------------------- real roots


@dataclass(frozen=True)
class Root:
    """A real root: exact (lo == hi) or the only root of `factor` in the open (lo, hi)."""

    lo: Fraction
    hi: Fraction
    factor: tuple[int, ...]  # integer coefficients, lowest degree first

    @property
    def exact(self) -> Fraction | None:
        return self.lo if self.lo == self.hi else None

    def __str__(self) -> str:
        if self.exact is not None:
            return str(self.exact)
        poly = sp.Poly(list(reversed(self.factor)), sp.Symbol("lam"))
        a, b = poly.refine_root(self.lo, self.hi, eps=Fraction(1, 10**12))
        approx = float((a + b) / 2)
        return f"the root of {poly.as_expr()} in ({self.lo}, {self.hi}) (≈ {approx:.9g})"

    def as_data(self):
        return self.exact if self.exact is not None else (self.lo, self.hi)


def _refined(poly: sp.Poly, lo, hi, eps) -> tuple[Fraction, Fraction]:
    a, b = poly.refine_root(lo, hi, eps=eps)
    return Fraction(int(a.p), int(a.q)), Fraction(int(b.p), int(b.q))


def real_roots(p: flint.fmpq_poly, iv: Interval | None = None) -> list[Root]:
    """The distinct real roots of p (nonzero) inside iv (all when None), sorted, with disjoint
    isolating intervals that do not contain an end of iv unless the root is that end."""
    if p.is_zero():
        raise ValueError("the zero polynomial has every number as a root")
    _, factors = p.numer().factor()
    roots: list[tuple[Root, sp.Poly]] = []
    for f, _mult in factors:
        coeffs = tuple(int(c) for c in f.coeffs())
        if f.degree() == 1:
            r = Fraction(-coeffs[0], coeffs[1])
            roots.append((Root(r, r, coeffs), None))
            continue
        poly = sp.Poly(list(reversed(coeffs)), _X, domain="ZZ")
        for (a, b), _ in poly.intervals():
            lo, hi = Fraction(int(a.p), int(a.q)), Fraction(int(b.p), int(b.q))
            roots.append((Root(lo, hi, coeffs), poly))
    # refine until no interval holds an end of iv and the intervals are pairwise disjoint
    changed = True
    while changed:
        changed = False
        ends = [] if iv is None else [iv.lo, iv.hi]
        for k, (r, poly) in enumerate(roots):
            if r.exact is None and any(r.lo <= e <= r.hi for e in ends):
                lo, hi = _refined(poly, r.lo, r.hi, (r.hi - r.lo) / 4)
                roots[k] = (Root(lo, hi, r.factor), poly)
                changed = True
        roots.sort(key=lambda rp: (rp[0].lo, rp[0].hi))
        for k in range(len(roots) - 1):
            r1, r2 = roots[k][0], roots[k + 1][0]
            if r2.lo <= r1.hi:
                for idx, (r, poly) in ((k, roots[k]), (k + 1, roots[k + 1])):
                    if r.exact is None:
                        lo, hi = _refined(poly, r.lo, r.hi, (r.hi - r.lo) / 4)
                        roots[idx] = (Root(lo, hi, r.factor), poly)
                changed = True
                break
    out = [r for r, _ in roots]
    if iv is not None:
        out = [r for r in out if iv.contains(r.lo if r.exact is not None else (r.lo + r.hi) / 2)]
    return out


def negative_point(p: flint.fmpq_poly, iv: Interval) -> Fraction | None:
    """A rational x in iv with p(x) < 0, or None when p >= 0 on all of iv (exact)."""
    if p.is_zero():
        return None
    if iv.lo == iv.hi:
        return iv.lo if _at(p, iv.lo) < 0 else None
    if p.degree() <= 0:
        return None if p(0) >= 0 else (iv.lo if not iv.lo_open else (iv.lo + iv.hi) / 2)
    roots = real_roots(p, iv)
    samples = [] if iv.lo_open else [iv.lo]
    samples += [] if iv.hi_open else [iv.hi]
    # one point in every open cell between consecutive roots (and the ends of iv)
    cuts = [iv.lo] + [x for r in roots for x in (r.lo, r.hi)] + [iv.hi]
    for a, b in zip(cuts[::2], cuts[1::2], strict=True):
        if a < b:
            samples.append((a + b) / 2)
    for x in samples:
        if iv.contains(x) and _at(p, x) < 0:
            return x
    return None


# --------------------------------------------------------------------------- properties


@dataclass
class Finding:
    """What goes wrong, at which degree (and parameter, index, t)."""

    degree: int
    text: str
    data: dict


def _lam_text(lam) -> str:
    return f"λ = {lam}"


def partition_of_unity(family: str, n: int) -> Finding | None:
    c = coefficients(family, n)
    for j in range(len(c[0])):
        total = sum((row[j] for row in c), flint.fmpq_poly([]))
        if total != 1:
            lam = next(x for x in map(Fraction, range(-2, 3)) if _at(total, x) != 1)
            s = _basis_sum_at(family, n, lam)
            return Finding(
                n,
                f"degree {n}: Σ b_i = {s} at {_lam_text(lam)} (coefficient of B_{j} is "
                f"{total.str(var='lam')}, not 1)",
                {"lam": lam},
            )
    return None


def _basis_sum_at(family, n, lam) -> str:
    total = sum((_basis_in_t(family, n, i, lam) for i in range(n + 1)), flint.fmpq_poly([]))
    return total.str(var="t")


def symmetry(family: str, n: int) -> Finding | None:
    c = coefficients(family, n)
    N = len(c[0]) - 1
    for i in range(n + 1):
        for j in range(N + 1):
            if c[i][j] != c[n - i][N - j]:
                return Finding(
                    n,
                    f"degree {n}: b_{i}(1 - t) ≠ b_{n - i}(t): coefficient of B_{N - j}: "
                    f"{c[i][j].str(var='lam')} vs {c[n - i][N - j].str(var='lam')}",
                    {"index": i},
                )
    return None


def endpoint_interpolation(family: str, n: int) -> Finding | None:
    c = coefficients(family, n)
    N = len(c[0]) - 1
    for i in range(n + 1):
        for end, j, want in (("0", 0, int(i == 0)), ("1", N, int(i == n))):
            if c[i][j] != want:
                return Finding(
                    n,
                    f"degree {n}: b_{i}({end}) = {c[i][j].str(var='lam')}, not {want}",
                    {"index": i},
                )
    return None


def reduces_to_bernstein(family: str, n: int, lam: Fraction) -> Finding | None:
    c = coefficients(family, n)
    N = len(c[0]) - 1
    for i in range(n + 1):
        for j in range(N + 1):
            # B_i^n elevated to degree N: C(n, i) C(N - n, j - i) / C(N, j)
            want = (
                Fraction(comb(n, i) * comb(N - n, j - i), comb(N, j)) if 0 <= j - i <= N - n else 0
            )
            if _at(c[i][j], lam) != want:
                got = _basis_in_t(family, n, i, lam).str(var="t")
                text = f"degree {n}: at {_lam_text(lam)}, b_{i} = {got}, not B_{i}^{n}"
                return Finding(n, text, {"index": i})
    return None


def degree_in_t(family: str, n: int) -> int:
    """The largest t-degree of a degree-n basis function (for generic λ)."""
    return max(_basis_in_t_generic(family, n, i) for i in range(n + 1))


def _basis_in_t_generic(family, n, i) -> int:
    # generic λ: the degree is reached for all but finitely many λ; two values decide it
    return max(_basis_in_t(family, n, i, lam).degree() for lam in (Fraction(1, 3), Fraction(2, 7)))


def nonnegative(family: str, n: int, iv: Interval | None) -> Finding | None:
    """Every degree-n basis function >= 0 for all t in [0, 1] and λ in iv (exact)."""
    c = coefficients(family, n)
    unit = Interval(Fraction(0), Fraction(1))
    for i, row in enumerate(c):
        if iv is None:
            p = _basis_in_t(family, n, i, None)
            x = negative_point(p, unit)
            if x is not None:
                return Finding(n, f"degree {n}: b_{i}({x}) = {_at(p, x)} < 0", {"index": i, "t": x})
            continue
        if all(negative_point(cij, iv) is None for cij in row):
            continue  # non-negative Bernstein coefficients: sufficient
        if max(cij.degree() for cij in row) > 1:
            raise NotImplementedError("non-negativity is decided for bases affine in λ only")
        # affine in λ: the minimum over λ is at an end of the closure of iv
        for end in (iv.lo, iv.hi):
            p = _basis_in_t(family, n, i, end)
            x = negative_point(p, unit)
            if x is None:
                continue
            # g(λ) = b_i(x, λ) is affine with g(end) < 0: step from the middle towards the end
            # until inside iv and negative (it converges to g(end) < 0, so this ends)
            lam, step = end, 0
            while not iv.contains(lam) or _at(_basis_in_t(family, n, i, lam), x) >= 0:
                step += 1
                lam = end + ((iv.lo + iv.hi) / 2 - end) / 2**step
            value = _at(_basis_in_t(family, n, i, lam), x)
            return Finding(
                n,
                f"degree {n}: b_{i}(t = {x}) = {value} < 0 at {_lam_text(lam)}"
                + (f" (and at the end λ = {end} of the range)" if lam != end else ""),
                {"index": i, "t": x, "lam": lam, "value": value},
            )
    return None


def _interpolate(xs: list[int], ys: list[flint.fmpq]) -> flint.fmpq_poly:
    """The polynomial through (xs, ys), exactly (Newton's divided differences)."""
    coef = list(ys)
    size = len(xs)
    for level in range(1, size):
        for k in range(size - 1, level - 1, -1):
            coef[k] = (coef[k] - coef[k - 1]) / (xs[k] - xs[k - level])
    out = flint.fmpq_poly([coef[-1]])
    for k in range(size - 2, -1, -1):
        out = out * flint.fmpq_poly([-xs[k], 1]) + coef[k]
    return out


def _matrix_at(c, lam: Fraction) -> flint.fmpq_mat:
    x = _q(lam)
    return flint.fmpq_mat([[cij(x) for cij in row] for row in c])


@cache
def independence_polynomial(family: str, n: int) -> flint.fmpq_poly:
    """det C(λ) for a square C, else det(C Cᵀ): zero exactly where the rank drops."""
    c = coefficients(family, n)
    square = len(c) == len(c[0])
    lam_deg = max(cij.degree() for row in c for cij in row)
    bound = max(lam_deg, 0) * len(c) * (1 if square else 2)
    xs = list(range(bound + 1))
    ys = []
    for x in xs:
        m = _matrix_at(c, Fraction(x))
        ys.append(m.det() if square else (m * m.transpose()).det())
    return _interpolate(xs, ys)


@cache
def singular_roots(family: str, n: int, iv: Interval | None) -> tuple[Root, ...]:
    poly = independence_polynomial(family, n)
    if poly.is_zero():
        raise ArithmeticError(f"the degree-{n} {family} basis is dependent for every λ")
    if poly.degree() <= 0:
        return ()
    return tuple(real_roots(poly, iv))


def null_combination(family: str, n: int, lam: Fraction) -> list[Fraction]:
    """Integer coefficients k_i, not all zero, with Σ k_i b_i = 0 at the rational `lam`."""
    c = coefficients(family, n)
    mat = sp.Matrix([[sp.Rational(_at(cij, lam)) for cij in row] for row in c])
    null = mat.T.nullspace()
    if not null:
        raise ArithmeticError(f"degree {n} is independent at λ = {lam}")
    vec = null[0]
    den = sp.ilcm(*[sp.fraction(v)[1] for v in vec])
    vec = [v * den for v in vec]
    g = sp.igcd(*[int(v) for v in vec])
    return [Fraction(int(v) // g) for v in vec]


def linear_independence(family: str, n: int, iv: Interval | None) -> Finding | None:
    if independence_polynomial(family, n).is_zero():
        lam = iv.hi if iv is not None and not iv.hi_open else Fraction(0)
        if iv is not None and not iv.contains(lam):
            lam = (iv.lo + iv.hi) / 2
        k = null_combination(family, n, lam)
        combo = " + ".join(f"({v})·b_{i}" for i, v in enumerate(k) if v)
        return Finding(
            n,
            f"degree {n}: the basis is linearly dependent for EVERY λ (e.g. λ = {lam}: "
            f"{combo} = 0)",
            {"roots": "all"},
        )
    roots = singular_roots(family, n, iv)
    if not roots:
        return None
    r = roots[0]
    poly = independence_polynomial(family, n)
    what = "det" if len(coefficients(family, n)) == len(coefficients(family, n)[0]) else "Gram det"
    factor = sp.factor(sp.Poly(list(reversed(poly.coeffs())), sp.Symbol("lam")).as_expr())
    text = f"degree {n}: the basis is linearly dependent at λ = {r} ({what} = {factor})"
    if r.exact is not None:
        k = null_combination(family, n, r.exact)
        combo = " + ".join(f"({v})·b_{i}" for i, v in enumerate(k) if v)
        text += f": {combo} = 0"
    more = [str(x) for x in roots[1:]]
    if more:
        text += f"; also at λ = {', '.join(more)}"
    return Finding(n, text, {"roots": [x.as_data() for x in roots]})


# --------------------------------------------------------------------------- emitted


def singular_table() -> dict[str, dict[int, tuple]]:
    """{family: {n: (root, ...)}}: an exact root as a Fraction, an irrational one as
    ((lo, hi), (c_0, ..., c_k)): the isolating interval and the integer coefficients (lowest
    degree first) of the irreducible factor it is the only root of in (lo, hi)."""
    out: dict[str, dict[int, tuple]] = {}
    for family, iv in BUILTIN_RANGES.items():
        out[family] = {}
        for deg in FAMILY_DEGREES[family]:
            out[family][deg] = tuple(
                r.exact if r.exact is not None else ((r.lo, r.hi), r.factor)
                for r in singular_roots(family, deg, iv)
            )
    return out
