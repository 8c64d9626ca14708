"""The certified-box check shared by the atom-surface tests (tests/test_atom_surface_bounds.py,
two atom directions, and tests/test_mixed_poly_surface_bounds.py, an atom direction across a
polynomial one). Each file keeps its own mpmath reference of the surface; this module only
compares the box against the extremes that reference finds."""

from __future__ import annotations

from collections.abc import Callable

import mpmath as mp
import numpy as np

from lambda_bezier.hazmat import atom_bounds as ab
from lambda_bezier.hazmat import atom_surface_bounds as asb

TOL = 1e-12  # the public methods' default tolerance (times the net's size)

# extreme(c, sign, values): the least value of sign × coordinate c over the domain, by the
# test file's own mpmath reference, seeded from `values` (sign × coordinate c on the grid)
Extreme = Callable[[int, int, np.ndarray], mp.mpf]


def check_box(s, grid: np.ndarray, extreme: Extreme, relative: float | None = None) -> None:
    """The public bounding_box is the search's outer box; each bound holds the attained
    extreme and is within max(TOL × size, the rounding floor) of it (and, given `relative`,
    within that fraction of the extreme's size); the inner box lies inside the outer one.
    `grid` is the surface evaluated on the reference's grid, shape (rows, columns, d)."""
    data = s._surface_data()
    stats = ab.Stats()
    inner_lo, inner_hi, lo, hi = asb.coordinate_extremes(data, TOL, stats)
    assert stats.narrow == 0
    box = s.bounding_box()
    assert np.array_equal(np.array(box), np.array([lo, hi]))
    assert np.isfinite(box).all()
    size = data.size()
    allowed = max(TOL * size, float(data.floor().max()))
    tiny = 1e-14 * max(size, 1e-300)  # the float basis coefficients against the exact basis
    for c in range(s.dimension):
        for sign, bound in ((1, lo[c]), (-1, hi[c])):
            best = sign * extreme(c, sign, sign * grid[:, :, c])
            assert sign * (float(best) - bound) >= -tiny  # the box holds the attained extreme
            assert sign * (float(best) - bound) <= allowed + tiny  # and is within tol of it
            if relative is not None:
                assert abs(float(best) - bound) <= relative * max(abs(float(best)), size)
    assert (lo <= inner_lo).all() and (inner_hi <= hi).all()
