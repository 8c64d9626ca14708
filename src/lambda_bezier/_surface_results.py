"""Result types of the surfaces' queries, in a module of their own: a frozen dataclass costs
about 1% of numpy's own import to create (its methods are compiled from source when the class
is made), so `surfaces` and `surface_joins` import this on the first call that returns one,
and naming every public name of lambda_bezier does not pay for them (issue #29)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class SurfaceClosestPoint:
    """The nearest point of a surface to q: parameters, point, distance and a certified lower
    bound of the distance (see `Surface.closest_point`); arrays over a batch of queries."""

    u: float | np.ndarray
    v: float | np.ndarray
    point: np.ndarray
    distance: float | np.ndarray
    lower_bound: float | np.ndarray


@dataclass(frozen=True)
class BoundaryReport:
    """The boundary between patch `first` and the next patch in direction `side`."""

    first: tuple[int, int]
    side: str
    continuity: str  # "none", "C0", "G1", "C1" or "C2"
