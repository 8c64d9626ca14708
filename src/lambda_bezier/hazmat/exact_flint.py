"""The costly steps of intersect_exact's exact algebra on python-flint (optional, imported on
call): resultants of bivariate polynomials (fmpz_mpoly), gcds and square-free parts over Z
(fmpz_poly) and real-root isolation (FLINT's certified complex root isolation, whose real roots
come as real intervals, each holding exactly one root), with the same contracts as the
standard-library versions in exact_poly, which stay the fallback when python-flint is not
installed. Why: Euclid and Sturm over Q in Fractions swell the coefficients (two quintics:
110 s in exact_poly; 0.1 s here, see intersect_exact.DECIDE_DEGREE). Results are polynomials
of Fractions again, so everything downstream is the same exact arithmetic either way.

Resultants and subresultants here are those of f and g scaled to integer coefficients by
positive constants: they differ from exact_poly's by a positive constant factor, which changes
no root and no sign that intersect_exact reads.
"""

from __future__ import annotations

from fractions import Fraction
from math import lcm
from types import ModuleType
from typing import Any

from . import exact_poly as xp

_FLINT: list[ModuleType | None] = []  # memo of the import: [] not tried, [None] not installed


def available() -> bool:
    return _flint() is not None


def _flint() -> ModuleType | None:
    if not _FLINT:
        try:
            import flint
        except ImportError:
            _FLINT.append(None)
        else:
            _FLINT.append(flint)
    return _FLINT[0]


def _module() -> Any:
    flint = _flint()
    if flint is None:
        raise RuntimeError("python-flint is not installed (pip install 'lambda-bezier[exact]')")
    return flint


def _integer_poly(p: xp.Poly) -> Any:
    """p (Fractions) times the positive lcm of its denominators, as an fmpz_poly."""
    p = xp.trim(p)
    den = lcm(*(c.denominator for c in p)) if p else 1
    return _module().fmpz_poly([int(c * den) for c in p])


def _fractions(p: Any) -> xp.Poly:
    return [Fraction(int(c)) for c in p.coeffs()]


def _integer_bivariate(f: xp.Bivariate) -> dict[tuple[int, int], int]:
    den = lcm(*(c.denominator for c in f.values())) if f else 1
    return {k: int(c * den) for k, c in f.items() if c}


def resultant(f: xp.Bivariate, g: xp.Bivariate, var: int) -> xp.Poly:
    """Res_var(f, g) up to a positive constant (see the module's docstring), a polynomial in
    the other variable, by fmpz_mpoly.resultant."""
    flint = _module()
    ctx = flint.fmpz_mpoly_ctx.get(("x", "y"), "lex")
    fz, gz = (ctx.from_dict(_integer_bivariate(h)) for h in (f, g))
    res = fz.resultant(gz, ("x", "y")[var]).to_dict()
    other = 1 - var
    size = 1 + max((k[other] for k in res), default=-1)
    out = [Fraction(0)] * size
    for key, c in res.items():
        out[key[other]] += int(c)
    return xp.trim(out)


def multiply(a: xp.Poly, b: xp.Poly) -> xp.Poly:
    """a · b, exactly (fmpq_poly)."""
    flint = _module()
    product = _rational_poly(flint, a) * _rational_poly(flint, b)
    return xp.trim([Fraction(int(c.p), int(c.q)) for c in product.coeffs()])


def _rational_poly(flint: Any, p: xp.Poly) -> Any:
    return flint.fmpq_poly([flint.fmpq(c.numerator, c.denominator) for c in p])


def gcd(a: xp.Poly, b: xp.Poly) -> xp.Poly:
    """The monic gcd over Q, as exact_poly.gcd (from the primitive gcd over Z)."""
    a, b = xp.trim(a), xp.trim(b)
    if not a or not b:
        got = a or b
        return [c / got[-1] for c in got] if got else got
    common = _fractions(_integer_poly(a).gcd(_integer_poly(b)))
    return [c / common[-1] for c in common]


def squarefree(p: xp.Poly) -> xp.Poly:
    """p divided by gcd(p, p') (a constant multiple of exact_poly.squarefree's answer)."""
    return _fractions(_squarefree_z(_integer_poly(p)))


def _squarefree_z(pz: Any) -> Any:
    if pz.degree() < 1:
        return pz
    common = pz.gcd(pz.derivative())
    return pz if common.degree() < 1 else pz // common


def real_roots(
    p: xp.Poly, lo: Fraction, hi: Fraction
) -> list[Fraction | tuple[Fraction, Fraction]]:
    """exact_poly.real_roots' contract: the distinct real roots of p in [lo, hi], increasing,
    a Fraction for a rational root met exactly, else an open interval (a, b) with rational ends
    that are not roots, holding exactly one root, where p's square-free part changes sign.

    FLINT isolates every complex root of the square-free part in disjoint balls, the real
    ones as real intervals [m - r, m + r] (exact dyadic ends), each holding exactly one root
    (arb_fmpz_poly_complex_roots); such an interval is cut at lo or hi by the sign of the
    polynomial there, exactly."""
    pz = _integer_poly(p)
    if pz.is_zero():
        raise ValueError("the zero polynomial has every number as a root")
    q = _squarefree_z(pz)
    if q.degree() < 1:
        return []
    qf = _fractions(q)
    out: list[Fraction | tuple[Fraction, Fraction]] = []
    for root, _ in q.complex_roots():
        if not root.imag.is_zero():
            continue
        mid, rad = (_dyadic(x) for x in (root.real.mid(), root.real.rad()))
        got = _clipped(qf, mid - rad, mid + rad, lo, hi)
        if got is not None:
            out.append(got)
    return sorted(out, key=lambda r: r if isinstance(r, Fraction) else r[0])


def _dyadic(x: Any) -> Fraction:
    man, exp = x.man_exp()
    man, exp = int(man), int(exp)
    return Fraction(man * 2**exp) if exp >= 0 else Fraction(man, 2**-exp)


def _sign(p: xp.Poly, x: Fraction) -> int:
    v = xp.evaluate(p, x)
    return (v > 0) - (v < 0)


def _clipped(
    q: xp.Poly, a: Fraction, b: Fraction, lo: Fraction, hi: Fraction
) -> Fraction | tuple[Fraction, Fraction] | None:
    """The one root of q in [a, b] as real_roots gives it, if it lies in [lo, hi]."""
    if b < lo or a > hi:
        return None
    for end in (a, b):
        if _sign(q, end) == 0:  # the root itself
            return end if lo <= end <= hi else None
    if a < lo:  # the root is in (a, b): in (lo, b) exactly when q changes sign there
        if _sign(q, lo) == 0:
            return lo
        if _sign(q, lo) == _sign(q, b):
            return None
        a = lo
    if b > hi:
        if _sign(q, hi) == 0:
            return hi
        if _sign(q, hi) == _sign(q, a):
            return None
        b = hi
    return (a, b)


def sign_at_root(p: xp.Poly, square_free: xp.Poly, interval: tuple[Fraction, Fraction]) -> int:
    """exact_poly.sign_at_root with its gcd and the gcd's root isolation done here."""
    lo, hi = interval
    p = xp.trim(p)
    if not p:
        return 0
    if lo == hi:
        return _sign(p, lo)
    common = gcd(p, square_free)
    if len(common) > 1 and real_roots(common, lo, hi):
        return 0
    return xp.sign_off_root(p, square_free, interval)


def first_subresultant(
    f: xp.Bivariate, g: xp.Bivariate, var: int
) -> tuple[xp.Poly, xp.Poly] | None:
    """exact_poly.first_subresultant of f and g scaled to integers (a positive constant times
    its (a1, a0), see the module's docstring), its minors taken by fmpz_mat.det."""
    flint = _module()
    scaled = [{k: Fraction(c) for k, c in _integer_bivariate(h).items()} for h in (f, g)]

    def determinant(rows: list[list[Fraction]]) -> Fraction:
        return Fraction(int(flint.fmpz_mat([[int(v) for v in row] for row in rows]).det()))

    def interpolate(xs: list[Fraction], ys: list[Fraction]) -> xp.Poly:
        # the Vandermonde system at the integer points, solved exactly (fmpq_mat)
        size = len(xs)
        vandermonde = flint.fmpq_mat(size, size, [int(x) ** k for x in xs for k in range(size)])
        column = flint.fmpq_mat(size, 1, [flint.fmpq(y.numerator, y.denominator) for y in ys])
        solved = vandermonde.solve(column)
        return xp.trim([Fraction(int(solved[k, 0].p), int(solved[k, 0].q)) for k in range(size)])

    return xp.first_subresultant(scaled[0], scaled[1], var, determinant, interpolate)
