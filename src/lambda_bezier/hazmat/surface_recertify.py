"""hazmat.surface_certify's two fixed-cost certificates (interior, and edge or corner) with
one test sharpened, in numpy, for the sets of coefficients the compiled fixed-cost stage
declined: every "this quadratic exceeds `slack` on [a, b]" is decided by the quadratic's
least value there (its ends, and q0 − q1²/(4 q2) where q2 > 0 and the vertex is in [a, b])
instead of its three Bernstein coefficients there, which are lower bounds of it only.

Why: the interior certificate needs E_xx / 2 = A(y) > 0 on the whole side (and E_yy / 2 =
F(x) the same); for a trigonometric family such as at_cubic A dips well below its end values
inside [−1, 1], and its middle Bernstein coefficient falls below zero while A stays positive.
On the 10,000 at_cubic benchmark nets the fixed-cost stage declines 1,533; this pass
certifies 1,161 of those (372 left), at numpy's speed.

Soundness: q's least value on [a, b] is at an end or at the vertex v = −q1/(2 q2) (q2 > 0,
v in [a, b]); q0 − q1²/(4 q2) is q's least value over every real t, so using it whenever
the float vertex lies in a slightly widened [a, b] only makes the test stricter. Where v is
in [a, b], |∂m/∂q0| = 1, |∂m/∂q1| = |v| and |∂m/∂q2| = v², so m's error from its
coefficients' errors is the error of q's value at a point of [a, b], the same the Bernstein
coefficients (and the ends) carry; the callers' `slack` covers it, as before.

surface_certify itself is left as it is: the compiled kernel inlines its source and records
its hash (hazmat/surface_batch_compiled.py), so this module runs surface_certify's own
functions under a namespace where `_quadratic_positive` is the sharper test (the compiled
kernel's `_recompiled` rebinds `_where` the same way).
"""

from __future__ import annotations

import types
from collections.abc import Callable
from typing import Any

import numpy as np

from . import surface_certify as sc

F = Any  # an array of floats
WIDEN = 2.0**-30  # the vertex counts as inside [a, b] within this times the interval's reach


def _quadratic_positive(q0: F, q1: F, q2: F, a: F, b: F, slack: F) -> F:
    """q0 + q1 t + q2 t² > slack on [a, b], by its least value there (see the module's doc)."""
    at_a = sc._at(q0, q1, q2, a)
    at_b = sc._at(q0, q1, q2, b)
    cup = q2 > 0
    safe = np.where(cup, q2, 1.0)
    vertex = -q1 / (2 * safe)
    reach = WIDEN * (np.abs(a) + np.abs(b) + (b - a))
    inside = cup & (vertex >= a - reach) & (vertex <= b + reach)
    least = np.where(inside, q0 - q1 * q1 / (4 * safe), np.inf)
    return (at_a > slack) & (at_b > slack) & (least > slack)


def _rebound() -> dict[str, Callable[..., Any]]:
    """surface_certify's certificates with `_quadratic_positive` the sharper test: the same
    code objects under a copy of its namespace (their calls to each other bound there)."""
    space: dict[str, Any] = dict(vars(sc))
    space["_quadratic_positive"] = _quadratic_positive
    for name in ("_side_clear", "_direction", "certified_minimum", "_edge", "edge_minimum"):
        fn = getattr(sc, name)
        space[name] = types.FunctionType(fn.__code__, space, name, fn.__defaults__)
    return {name: space[name] for name in ("certified_minimum", "edge_minimum")}


_SHARP = _rebound()


def recertified_minimum(
    c: list[np.ndarray], box: np.ndarray, tol: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(x, y, energy, certified, on_edge) as surface_fixed_cost.fixed_cost_minimum's, for the
    nine coefficient arrays c[3a + b] of x^a y^b, with the sharper test: the interior
    certificate, then the edge and corner one on what it declines."""
    interior, edge = _SHARP["certified_minimum"], _SHARP["edge_minimum"]
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        bx, by, bval, _, ok = interior(*c, box[0], box[1], box[2], box[3], tol)
        bx, by, bval = np.array(bx, float), np.array(by, float), np.array(bval, float)
        ok = np.array(ok, bool)
        on_edge = np.zeros(ok.shape, bool)
        undecided = np.flatnonzero(~ok)
        if undecided.size:
            d = [v[undecided] for v in c]
            ex, ey, ev, _, eok = edge(*d, box[0], box[1], box[2], box[3], tol)
            done = undecided[eok]
            bx[done], by[done], bval[done] = ex[eok], ey[eok], ev[eok]
            ok[done] = on_edge[done] = True
    return bx, by, bval, ok, on_edge
