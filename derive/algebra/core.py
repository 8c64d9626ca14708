"""Exact polynomial algebra shared by the derive modules.

A basis function is held as a SymPy ``Poly`` in (t, lam) over QQ. From it we read its power
coefficients and, by solving against the Bernstein polynomials of the target degree, its
Bernstein coefficients; both split by powers of λ so that the runtime can assemble
``M(λ) = M_0 + λ M_1 + …`` with numpy.
"""

from __future__ import annotations

from fractions import Fraction
from math import comb, factorial

import flint
import sympy as sp
from sympy.printing.pycode import PythonCodePrinter

from .ratfunc import from_expr

t, lam = sp.symbols("t lam")
# Symbols of the general-n closed forms: integers, so SymPy may simplify binomials.
n, m, i, j, k = sp.symbols("n m i j k", integer=True, nonnegative=True)

Matrix = tuple[tuple[Fraction, ...], ...]


def to_fraction(x: object) -> Fraction:
    """An exact SymPy/Python rational as a Fraction; anything inexact is a derivation bug."""
    if isinstance(x, bool):
        raise TypeError("bool is not a coefficient")
    if isinstance(x, int | Fraction):
        return Fraction(x)
    if isinstance(x, sp.Rational):
        return Fraction(int(x.p), int(x.q))
    raise TypeError(f"not an exact rational: {x!r} ({type(x).__name__})")


def poly(expr: sp.Expr) -> sp.Poly:
    """A polynomial in (t, lam); a rational expression must cancel to one."""
    try:
        return sp.Poly(expr, t, lam, domain="QQ")
    except (
        sp.PolynomialError
    ):  # negative powers that only cancel after putting over one denominator
        pass
    expr = sp.cancel(sp.sympify(expr, strict=True))
    num, den = sp.fraction(expr)
    p = sp.Poly(num, t, lam, domain="QQ")
    d = sp.Poly(den, t, lam, domain="QQ")
    q, r = p.div(d)
    if not r.is_zero:
        raise ArithmeticError(f"{expr} is not a polynomial in t and lam")
    return q


def to_flint(mat) -> flint.fmpq_mat:
    """A matrix of exact rationals (int, Fraction or SymPy Rational entries) as FLINT's
    fmpq_mat, for products in C."""
    return flint.fmpq_mat([[_fmpq(v) for v in row] for row in mat])


def from_flint(mat: flint.fmpq_mat) -> Matrix:
    return tuple(tuple(Fraction(int(v.p), int(v.q)) for v in row) for row in mat.table())


def _fmpq(v) -> flint.fmpq:
    if isinstance(v, int):
        return flint.fmpq(v)
    v = v if isinstance(v, Fraction) else Fraction(v)
    return flint.fmpq(v.numerator, v.denominator)


def matmul(a, b) -> Matrix:
    """Exact product of rational matrices (FLINT's fmpq_mat: the product never normalises a
    Fraction; each entry is converted back once)."""
    return from_flint(to_flint(a) * to_flint(b))


def transpose(a) -> Matrix:
    return tuple(zip(*a, strict=True))


def lambda_degree(polys: list[sp.Poly]) -> int:
    return max(p.degree(lam) for p in polys)


def power_matrices(polys: list[sp.Poly], degree: int) -> tuple[Matrix, ...]:
    """M_p[i][e] = coefficient of lam^p t^e in basis function i, for p = 0..deg_λ."""
    size = degree + 1
    mats = [[[Fraction(0)] * size for _ in polys] for _ in range(lambda_degree(polys) + 1)]
    for row, pp in enumerate(polys):
        for (e, p), c in pp.terms():
            if e >= size:
                raise ArithmeticError(f"basis function {row} has degree {e} > {degree}")
            mats[p][row][e] = to_fraction(c)
    return tuple(tuple(tuple(r) for r in mat) for mat in mats)


LAMBDA_SAMPLES = (0, 1)  # two values of λ decide equality of expressions linear in λ


def linear_in_lambda(expr: sp.Expr) -> bool:
    """Whether `expr` is a rational function of degree <= 1 in λ with no λ in its
    denominator (in lowest terms)."""
    expr = sp.sympify(expr)
    others = sorted(expr.free_symbols - {lam}, key=str)
    try:  # FLINT's cancellation, where the expression is a rational function at all
        value = from_expr(expr, (lam, *others))
    except ValueError:  # binomials, factorials of symbols: SymPy's own
        num, den = sp.fraction(sp.together(expr))
        return not den.has(lam) and sp.degree(num, lam) <= 1
    return value.den.degrees()[0] == 0 and (value.num.is_zero() or value.num.degrees()[0] <= 1)


class _ExactCodePrinter(PythonCodePrinter):
    """Python code in which a rational constant is a Fraction (the default printer writes
    1/3, a float)."""

    def _print_Rational(self, expr):
        return f"Fraction({expr.p}, {expr.q})"

    def _print_Half(self, expr):
        return self._print_Rational(expr)

    def _print_binomial(self, expr):  # the papers' binomial: zero outside 0 <= k <= n
        return f"binomial({self._print(expr.args[0])}, {self._print(expr.args[1])})"


def exact_function(expr: sp.Expr, args, number: type = Fraction):
    """`expr` as a Python function of exact numbers, computed in `number`s (an int argument
    would turn n**-1 into a float): Fraction, or flint.fmpq, which is several times faster
    where the function is evaluated thousands of times."""
    convert = _fmpq if number is flint.fmpq else number  # fmpq() refuses a Fraction
    fn = sp.lambdify(
        args,
        expr,
        modules=[{"binomial": _binomial, "factorial": _factorial, "Fraction": number}, "math"],
        printer=_ExactCodePrinter(
            {"fully_qualified_modules": False, "inline": True, "allow_unknown_functions": True}
        ),
    )
    return lambda *values: fn(*(convert(v) for v in values))


def _binomial(a, b):
    if a.denominator != 1 or b.denominator != 1:  # int() would truncate silently
        raise ValueError(f"binomial({a}, {b}) of a non-integer")
    a, b = int(a), int(b)
    return comb(a, b) if 0 <= b <= a else 0


def _factorial(a):
    if a.denominator != 1 or a < 0:  # math.factorial refuses a Fraction, even a whole one
        raise ValueError(f"factorial({a}) of a non-integer or a negative number")
    return factorial(int(a))


def endpoint_values(polys, orders: int) -> dict[tuple[str, int, int], tuple[Fraction, ...]]:
    """Per-degree derivatives d^r b_i/dt^r at t=0 and t=1 (nonzero ones), at each λ of
    LAMBDA_SAMPLES. The basis functions are linear in λ, so these samples determine them."""
    if any(p.degree(lam) > 1 for p in polys):
        raise AssertionError("basis functions are expected to be linear in λ")
    out = {}
    for idx, p in enumerate(polys):
        d = p
        for r in range(orders + 1):
            for end, at in (("start", 0), ("end", 1)):
                val = d.eval(t, at)
                if not val.is_zero:
                    out[(end, r, idx)] = tuple(to_fraction(val.eval(x)) for x in LAMBDA_SAMPLES)
            d = d.diff(t)
    return out


def check_endpoint_closed_forms(closed: dict, polys_by_degree: dict, orders: int) -> None:
    """Each closed form {("start"|"end", r, idx): expr in n, λ} equals the derivative of the
    per-degree expansion for every degree given, and no nonzero entry is missing."""
    for key, expr in closed.items():
        if not linear_in_lambda(expr):
            raise AssertionError(f"endpoint closed form {key} is not linear in λ")
    fns = {key: exact_function(expr, (n, lam)) for key, expr in closed.items()}
    zero = tuple(Fraction(0) for _ in LAMBDA_SAMPLES)
    for deg, polys in polys_by_degree.items():
        table = endpoint_values(polys, orders)
        by_key = {(e, r, ii if e == "start" else deg - ii): v for (e, r, ii), v in table.items()}
        for key in set(by_key) | set(fns):
            got = (
                tuple(Fraction(fns[key](Fraction(deg), Fraction(x))) for x in LAMBDA_SAMPLES)
                if key in fns
                else zero
            )
            if got != by_key.get(key, zero):
                raise AssertionError(f"endpoint closed form {key} wrong at n={deg}")


def bernstein_terms(expr: sp.Expr, degree: sp.Expr) -> dict[sp.Expr, sp.Expr]:
    """Read a sum of terms c · t^a (1-t)^b with a + b = degree as Σ coeff_a B_a^degree.

    Works with symbolic exponents: products are distributed without expanding the powers,
    exponents are combined, and each coefficient is divided by C(degree, a) and simplified.
    Returns {a: coefficient of B_a^degree}.
    """
    s = sp.Dummy("s")  # stands for 1 - t, so that distributing never expands it
    expr = sp.expand(expr.subs(1 - t, s), power_exp=False, power_base=False, log=False)
    out: dict[sp.Expr, sp.Expr] = {}
    for term in sp.Add.make_args(expr):
        coeff, rest = term.as_independent(t, s)
        powers = dict(sp.powsimp(rest).as_powers_dict())
        a = powers.pop(t, sp.Integer(0))
        b = powers.pop(s, sp.Integer(0))
        # exponents are polynomials in n and i, so expanding decides (simplify would import
        # sympy.physics on first use)
        if any(e != 0 for e in powers.values()) or sp.expand(a + b - degree) != 0:
            raise ArithmeticError(f"term {term} is not a multiple of a degree-{degree} Bernstein")
        out[a] = out.get(a, 0) + coeff / sp.binomial(degree, a)
    return {a: sp.factor(sp.combsimp(c)) for a, c in out.items()}


CENTRE = Fraction(1, 2)


def centred_row(row: tuple[Fraction, ...], centre: Fraction = CENTRE) -> tuple[Fraction, ...]:
    """Taylor coefficients about `centre`: Σ a_q t^q = Σ c_e (t - centre)^e, exactly.
    (Horner on these is as accurate as de Casteljau on [0, 1]; at 0 it is not.)"""
    # p(s + centre) by FLINT's exact composition: the binomial sums in Fractions were a
    # tenth of `derive --check` (issue #29)
    size = len(row)
    shifted = flint.fmpq_poly([_fmpq(c) for c in row])(flint.fmpq_poly([_fmpq(centre), 1]))
    coeffs = [Fraction(int(c.p), int(c.q)) for c in shifted.coeffs()]
    return tuple(coeffs + [Fraction(0)] * (size - len(coeffs)))


def centred_matrices(mats: tuple[Matrix, ...]) -> tuple[Matrix, ...]:
    return tuple(tuple(centred_row(row) for row in mat) for mat in mats)
