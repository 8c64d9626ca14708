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

_HAZMAT = "lambda_bezier.hazmat"


def _intersections() -> None:
    import lambda_bezier as lb

    a = lb.BezierCurve([(0, 0), (1, 2), (2, -1), (3, 1)])
    b = lb.BezierCurve([(0, 1), (1, -1), (2, 2), (3, 0)])
    a.intersect(b)  # the certificate (certify_compiled) and the subdivision
    lb.intersect_many([a], [b])
    # the certificate on its own, as the certificate tests call it (writable arrays: a type
    # of their own, compiled apart from the one-call pair kernel's read-only rows)
    import numpy as np

    from lambda_bezier.hazmat import intersect as engine
    from lambda_bezier.hazmat import intersect_certify as cert

    rows = [np.array(c.points, dtype=float) for c in (a, b)]
    cert.certify_one(*rows, engine.BOX_SLACK, engine.ROOT_RESIDUAL, engine.SETTLE)


def _careful_path() -> None:
    import lambda_bezier as lb

    # a tangency, which the certificate declines: the careful path compiled (settle_compiled
    # and refine_compiled, about 45 s of CPU on a fresh cache). A pair that only looked
    # careful once reached the certificate alone, and each worker compiled the careful path
    # itself: the check makes the warm-up fail (conftest warns) if this pair stops reaching it
    arch = lb.BezierCurve([(0, 0), (1, 2), (2, 0)])
    hits = arch.intersect(lb.BezierCurve([(0, 1), (2, 1)]))
    if [h.kind for h in hits] != ["tangent"] or f"{_HAZMAT}.settle_compiled" not in sys.modules:
        raise RuntimeError(f"the tangent pair did not reach the compiled careful path: {hits}")


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


# each part with its CPU seconds in a fresh cache, imports included (measured at load 2-5),
# longest first: warm() deals them out so that the processes get about the same share
# (two processes: 47 and 51)
PARTS = ((_careful_path, 47), (_batches, 27), (_intersections, 12), (_self_and_closest, 12))


def warm(index: int, count: int) -> None:
    """Runs this process's share of the parts: process `index` of `count`, each part given
    in turn to the process with the least CPU so far."""
    loads = [0] * count
    for part, seconds in PARTS:
        k = loads.index(min(loads))
        loads[k] += seconds
        if k == index:
            part()


if __name__ == "__main__":
    warm(int(sys.argv[1]), int(sys.argv[2]))
