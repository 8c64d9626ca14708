"""Implicitization of planar classical Bézier curves with exact control points.

The algebraic curve f(x, y) = 0 containing p(t) = (x(t), y(t)) is the resultant in t of
x(t) - x and y(t) - y (Sederberg's method; the `bezier` package computes the same). It is a
power of the implicit equation when the parametrisation runs over the curve several times,
so the square-free part is taken; the result is made primitive over the integers with its
first coefficient positive (terms ordered by total degree, then x-degree). SymPy is
imported here, when the method is called, never by `import lambda_bezier`.
"""

from __future__ import annotations

from fractions import Fraction
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import sympy


def implicitize(rows: tuple[tuple[Fraction, ...], ...], homogeneous: bool = False) -> sympy.Poly:
    """The implicit polynomial of a planar curve as a sympy.Poly in x, y over the integers.
    With homogeneous=True the rows are (w X, w Y, w) of a rational curve: the resultant is
    then that of X(t) - x w(t) and Y(t) - y w(t)."""
    try:
        import sympy
    except ImportError:  # SymPy comes with the derive extra, not with the runtime
        raise ImportError("implicitize needs SymPy: pip install 'lambda-bezier[derive]'") from None

    t, x, y = sympy.symbols("t x y")
    n = len(rows) - 1
    bern = [sympy.binomial(n, i) * t**i * (1 - t) ** (n - i) for i in range(n + 1)]
    xt = sympy.Poly(sum(sympy.Rational(r[0]) * b for r, b in zip(rows, bern, strict=True)), t)
    yt = sympy.Poly(sum(sympy.Rational(r[1]) * b for r, b in zip(rows, bern, strict=True)), t)
    if xt.degree() <= 0 and yt.degree() <= 0:
        raise ValueError("implicitize: the curve is a single point, not a curve")
    wt = sympy.Integer(1)
    if homogeneous:
        wt = sum(sympy.Rational(r[2]) * b for r, b in zip(rows, bern, strict=True))
    px = sympy.Poly(xt.as_expr() - x * wt, t, x, y)
    py = sympy.Poly(yt.as_expr() - y * wt, t, x, y)
    res = sympy.resultant(px.as_expr(), py.as_expr(), t)
    poly = sympy.Poly(sympy.sqf_part(sympy.Poly(res, x, y)), x, y)
    _, poly = poly.clear_denoms(convert=True)
    poly = poly.primitive()[1]
    first = min(poly.monoms(), key=lambda m: (m[0] + m[1], m[0]))
    if poly.coeff_monomial(x ** first[0] * y ** first[1]) < 0:
        poly = -poly
    return poly
