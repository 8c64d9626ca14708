"""A classical Bézier curve written in a λ-family: ``Curve.from_bezier`` (curves.py) calls
``from_bezier`` here.

Which degree. A family curve of degree m at λ is Σ V_i b_i(t; λ), i = 0..m, a polynomial curve
of degree m + offset (offset 0 for same_degree, 2 for bernstein_like). Its control points
solve Mᵀ V = P, where M (m+1 × m+offset+1) holds the basis in the Bernstein basis of degree
m + offset and P are the Bézier points, elevated to that degree. We return the curve of the
**smallest** family degree m whose basis at λ spans the given curve:

* same_degree: where the basis is independent it spans all polynomials of degree m, so
  m = max(N, 3) for a Bézier curve of degree N (a quadratic or a line is elevated first);
* bernstein_like: the degree-m basis spans only an (m+1)-dimensional subspace of the degree
  m + 2 polynomials, and for λ ≠ 0 not even all quadratics (at λ = 1/2 the only polynomials
  of degree <= 2 it contains are the constants, so not even a line segment is such a curve).
  A Bézier curve of degree N is tried in degree m = max(N - 2, 2), then m + 1, ... until
  Mᵀ V = P is consistent (exactly, for exact input): it is a Bernstein-like curve only when its
  points satisfy those conditions, e.g. when it came from ``BernsteinLikeCurve.to_bezier``. At
  λ = 0 (Bernstein) every Bézier curve converts, in degree m = N.

At a singular parameter (``singular_parameters``) M has dependent rows: the control points
are not unique and the conversion is refused with the exact λ named.
"""

from __future__ import annotations

from fractions import Fraction
from typing import TYPE_CHECKING

import numpy as np

from . import _validate as val
from .properties import is_singular, singular_parameters

if TYPE_CHECKING:
    from .curves import BezierCurve, Curve

RELATIVE_TOLERANCE = 1e-9  # float input: residual of the least-squares fit, relative


def _solve_exact(a: list[list[Fraction]], b: list[list[Fraction]]) -> list[list[Fraction]] | None:
    """x with a x = b (a: rows × cols, full column rank), or None when inconsistent."""
    rows, cols = len(a), len(a[0])
    aug = [list(a[r]) + list(b[r]) for r in range(rows)]
    piv_row = 0
    for c in range(cols):
        p = next((r for r in range(piv_row, rows) if aug[r][c] != 0), None)
        if p is None:
            raise ArithmeticError("rank deficient")
        aug[piv_row], aug[p] = aug[p], aug[piv_row]
        inv = 1 / aug[piv_row][c]
        aug[piv_row] = [v * inv for v in aug[piv_row]]
        for r in range(rows):
            if r != piv_row and aug[r][c] != 0:
                f = aug[r][c]
                aug[r] = [v - f * w for v, w in zip(aug[r], aug[piv_row], strict=True)]
        piv_row += 1
    if any(v != 0 for r in range(piv_row, rows) for v in aug[r][cols:]):
        return None
    return [aug[r][cols:] for r in range(cols)]


def from_bezier(
    cls: type[Curve], bezier: BezierCurve, lam: Fraction | float | None = None
) -> Curve:
    from .curves import FAMILIES, BezierCurve, _combine_exact, _tables

    if not isinstance(bezier, BezierCurve):
        raise TypeError(f"bezier must be a BezierCurve, not {type(bezier).__name__}")
    if cls is BezierCurve:
        if lam is not None:
            raise ValueError("lam: a classical Bézier curve takes no shape parameter")
        return BezierCurve(bezier.control_points())
    if lam is None:
        raise ValueError(f"lam: a {cls.family} curve needs a shape parameter")
    lam = val.as_lambda(lam, cls._data, check_range=True)
    offset = cls._data_offset()
    exact = bezier.is_exact and not isinstance(lam, float)
    n_bez = bezier.degree
    degrees = tuple(cls._data.DEGREES)
    start = max(n_bez - offset, degrees[0])
    for m in range(start, degrees[-1] + 1):
        key = cls.family if FAMILIES.get(cls.family) is cls else cls  # a name, or the class
        if is_singular(key, m, lam):
            roots = [
                str(r) if isinstance(r, Fraction) else float(r) for r in singular_parameters(key, m)
            ]
            raise ValueError(
                f"lam: the degree-{m} {cls.family} basis is linearly dependent at λ = {lam} "
                f"(singular_parameters({cls.family!r}, {m}) = {roots}): the control points "
                "of a curve are not unique there"
            )
        target = bezier
        while target.degree < m + offset:
            target = target.elevate()
        if exact:
            mats = _tables(cls._data, "bernstein")[m]
            basis = _combine_exact(mats, Fraction(lam))  # (m+1) × (m+offset+1)
            a = [list(col) for col in zip(*basis, strict=True)]  # Mᵀ
            assert target._exact_points is not None  # exact: so are its elevations
            b = [list(row) for row in target._exact_points]
            try:
                sol = _solve_exact(a, b)
            except ArithmeticError:
                raise ValueError(
                    f"lam: the degree-{m} {cls.family} basis is linearly dependent at λ = {lam}"
                ) from None
            if sol is not None:
                return cls([tuple(row) for row in sol], lam)
            continue
        probe = cls(np.zeros((m + 1, bezier.dimension)), lam, check_range=False)
        a_f = probe.basis_bernstein_matrix().T
        b_f = target.points
        sol_f, *_ = np.linalg.lstsq(a_f, b_f, rcond=None)
        residual = np.linalg.norm(a_f @ sol_f - b_f)
        if residual <= RELATIVE_TOLERANCE * max(1.0, float(np.linalg.norm(b_f))):
            return cls(sol_f, lam)
    raise ValueError(
        f"bezier: this degree-{n_bez} Bézier curve is no {cls.family} curve of degree "
        f"{start}..{degrees[-1]} at λ = {lam} (the basis does not span it; see "
        "lambda_bezier.conversion)"
    )
