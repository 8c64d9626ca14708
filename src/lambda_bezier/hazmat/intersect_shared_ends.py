"""A pair's shared end points, for intersect's certificate (hazmat/intersect_certify.py, and
compiled by certify_compiled.py) and the numpy subdivision (intersect_subdivide.py): which
corners of the parameter square are exact common end points with tangents clearly apart
(`shared_corners`), and which of them a pair of pieces holds (`corner_held`). Pure scalar
code on arrays, importing nothing of the engine (its three users import it)."""

from __future__ import annotations

import math

import numpy as np


def shared_corners(a: np.ndarray, b: np.ndarray, shared_sine: float) -> int:
    """The corners (i, k) of the parameter square where end i of a (0 at s = 0, 1 at s = 1)
    is end k of b exactly, as a mask (bit 2 i + k); -1 where at one of them the end tangents
    are not clearly apart (a sine of their angle at most shared_sine, or an end that stops):
    the careful path tells tangencies there.

    Halving keeps an end point exactly (the end piece's first or last control point), so the
    pieces holding a shared point are never dropped (both boxes and both fat lines hold it).
    The shared point is a common point known exactly: where a pair of pieces holding it is
    isolated (disjoint hodograph cones: at most one common point on the pair), it is that
    pair's only one, and the certificate records it as it is, with no Newton."""
    n1, n2, dim = a.shape[0] - 1, b.shape[0] - 1, a.shape[1]
    mask = 0
    for i in range(2):
        ra = n1 if i else 0
        for k in range(2):
            rb = n2 if k else 0
            equal = True
            for j in range(dim):
                if a[ra, j] != b[rb, j]:
                    equal = False
            if not equal:
                continue
            # the end tangents: the hodograph's end control points, as _refine measures them
            nu = nv = dot = 0.0
            for j in range(dim):
                da = n1 * (a[n1, j] - a[n1 - 1, j] if i else a[1, j] - a[0, j])
                db = n2 * (b[n2, j] - b[n2 - 1, j] if k else b[1, j] - b[0, j])
                nu += da * da
                nv += db * db
                dot += da * db
            if not nu * nv > 0.0:
                return -1
            sine = math.sqrt(max(nu * nv - dot * dot, 0.0)) / math.sqrt(nu * nv)
            if not sine > shared_sine:
                return -1
            mask |= 1 << (2 * i + k)
    return mask


def corner_held(corners: int, ka: int, kb: int, lev: int) -> int:
    """The shared corner (bit index 2 i + k) the pair of pieces (ka, kb) at level lev holds,
    -1 where it holds none, -2 where it holds more than one."""
    last = (1 << lev) - 1
    held = -1
    for i in range(2):
        if ka != (last if i else 0):
            continue
        for k in range(2):
            if kb != (last if k else 0) or not (corners >> (2 * i + k)) & 1:
                continue
            held = 2 * i + k if held == -1 else -2
    return held
