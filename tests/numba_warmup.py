"""Fills numba's on-disk cache with the runtime's kernels before pytest-xdist starts its
workers (conftest.py's `pytest_configure`), in as many processes as there are workers.

Why: a fresh install (CI's `pip install ".[test]"`) has no cache, and each xdist worker would
compile every kernel it meets on its own, the two workers mostly at the same time: 30 s of CPU
for the intersection kernels alone. Compiled once here, split over the processes, the workers
load them from the cache instead. A kernel this misses is compiled by the worker that meets it,
as before: the warm-up changes no result, only when the compiling happens.

Each part is one public call per compiled path, with the argument types the tests use
(float64 arrays; 2-D and 3-D curves share one signature)."""

from __future__ import annotations

import sys


def _intersections() -> None:
    import lambda_bezier as lb

    a = lb.BezierCurve([(0, 0), (1, 2), (2, -1), (3, 1)])
    b = lb.BezierCurve([(0, 1), (1, -1), (2, 2), (3, 0)])
    a.intersect(b)  # the certificate (certify_compiled) and the subdivision
    lb.intersect_many([a], [b])
    tangent = lb.BezierCurve([(0, 1), (1.5, -0.5), (3, 1)])
    lb.BezierCurve([(0, 0), (1.5, 2), (3, 0)]).intersect(tangent)  # the careful path (settle)


def _self_and_closest() -> None:
    import lambda_bezier as lb

    loop = lb.BezierCurve([(0, 0), (3, 2), (0, 2), (3, 0)])
    loop.self_intersections()
    loop.closest_point((1, 1))
    loop.arc_length()


def _batches() -> None:
    import numpy as np

    import lambda_bezier as lb
    from lambda_bezier import examples

    pts = np.random.default_rng(0).normal(size=(50, 4, 2))
    for family in ("same_degree", "bernstein_like"):
        lb.optimal_lambda(pts, 2, family)
        lb.evaluate_many(pts, np.linspace(0, 1, 9), family, lam=np.full(50, 0.5))
    nets = np.random.default_rng(1).normal(size=(20, 4, 4, 3))
    lb.optimal_parameters(nets, "thin_plate", "same_degree")
    s = lb.Surface(nets[0], 0.25, -0.75, family=("same_degree", "bernstein_like"))
    s.evaluate_grid(np.linspace(0, 1, 5), np.linspace(0, 1, 4))
    han = lb.load_family(examples.path("han_trig_cubic.toml"))  # atom_pieces_compiled
    curve = han.curve(np.array([(0, 0), (1, 3), (3, -1), (4, 1)], dtype=float), lam=0.5, mu=-1.0)
    curve.evaluate(np.linspace(0, 1.5, 2000))


# CPU seconds of each part in a fresh cache, imports included (measured at load ~17): 25, 40,
# 24; in this order two processes get about the same share (index::count: 49 and 40)
PARTS = (_intersections, _batches, _self_and_closest)


def warm(index: int, count: int) -> None:
    """Runs the parts index, index + count, ...: part of the warm-up in one of `count`
    processes."""
    for part in PARTS[index::count]:
        part()


if __name__ == "__main__":
    warm(int(sys.argv[1]), int(sys.argv[2]))
