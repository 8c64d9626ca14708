"""The fixed-cost certified minimum of E(x, y) = Σ e_ab x^a y^b (a, b <= 2) over a box, for
arrays of coefficient sets, in numpy: the interior certificate
(surface_certify.certified_minimum) and, on what it declines, the edge and corner one
(surface_certify.edge_minimum), in the order the compiled kernel
(surface_batch_compiled.optimise) runs them. Both batch optima's numpy engines call this.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from .surface_certify import certified_minimum, edge_minimum


def fixed_cost_minimum(
    c: Sequence[np.ndarray], box: np.ndarray, tol: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(x, y, energy, certified, on_edge) for the nine coefficient arrays c[3a + b] of
    x^a y^b and box = (xlo, xhi, ylo, yhi); certified False where both certificates decline,
    on_edge True where the edge one certified."""
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        bx, by, bval, _, ok = certified_minimum(
            c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7], c[8],
            box[0], box[1], box[2], box[3], tol,
        )  # fmt: skip
        bx, by, bval = np.array(bx, float), np.array(by, float), np.array(bval, float)
        ok = np.array(ok, bool)
        on_edge = np.zeros(ok.shape, bool)
        undecided = np.flatnonzero(~ok)
        if undecided.size:  # the declined sets' edge and corner minima
            d = [v[undecided] for v in c]
            ex, ey, eval_, _, eok = edge_minimum(
                d[0], d[1], d[2], d[3], d[4], d[5], d[6], d[7], d[8],
                box[0], box[1], box[2], box[3], tol,
            )  # fmt: skip
            done = undecided[eok]
            bx[done], by[done], bval[done] = ex[eok], ey[eok], eval_[eok]
            ok[done] = on_edge[done] = True
    return bx, by, bval, ok, on_edge
