"""A classical Bézier curve written in a λ-family: ``Curve.from_bezier`` and
``from_bezier`` here are one function (it lives in _curve_base.py, below the curve classes).

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

from ._curve_base import RELATIVE_TOLERANCE as RELATIVE_TOLERANCE
from ._curve_base import from_bezier as from_bezier

__all__ = ["RELATIVE_TOLERANCE", "from_bezier"]
