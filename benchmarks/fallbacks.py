"""Issue #29's numpy fallbacks against their previous code, interleaved in one process (best of
25 rounds, wall and CPU time), with the benchmark rows' references:

    python benchmarks/fallbacks.py lambda   # batch optimal_lambda without numba, 10^5 quintics
    python benchmarks/fallbacks.py trig     # han_trig_cubic without numba, 10^6 t

lambda: "previous" declines every chunk to the careful path (energy._float_optimum_chunk on
each chunk: the fallback before hazmat/batch_numpy.py); "one thread" is the new pass with
batch_numpy.THREADS = 1. trig: "one thread" is atoms.HALF_ANGLE_THREADS = 1 (the code before
the threads). Ratios are to one read pass (lambda) or to BezierCurve.evaluate of a cubic
(trig), as in benchmarks/run.py. Set OPENBLAS_NUM_THREADS=1 to take BLAS's threads out of
the previous lambda code's CPU time.
"""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path

import numpy as np

import lambda_bezier as lb
from lambda_bezier.hazmat import atoms, batch_numpy, kernels


def rounds(fns: dict, clock, count: int = 25) -> dict[str, float]:
    best = dict.fromkeys(fns, float("inf"))
    for _ in range(count):
        for name, fn in fns.items():
            start = clock()
            fn()
            best[name] = min(best[name], clock() - start)
    return best


def with_setting(module, name: str, value, fn):
    def run():
        saved = getattr(module, name)
        setattr(module, name, value)
        try:
            return fn()
        finally:
            setattr(module, name, saved)

    return run


def lambda_fns() -> tuple[dict, str]:
    pts = np.random.default_rng(3).normal(size=(100_000, 6, 2))
    new = lambda: lb.optimal_lambda(pts, 2)  # noqa: E731
    return {
        "new": new,
        "one thread": with_setting(batch_numpy, "THREADS", 1, new),
        "previous": with_setting(batch_numpy, "energy_optimum", lambda *args: 0, new),
        "read": lambda: pts.sum(),
    }, "read"


def trig_fns() -> tuple[dict, str]:
    data = Path(__file__).resolve().parents[1] / "tests/data/families"
    t = np.random.default_rng(0).random(10**6)
    pts = np.random.default_rng(3).normal(size=(4, 2))
    curve = lb.load_family(data / "han_trig_cubic.toml").curve(pts, lam=0.5, mu=-1.0)
    lo, hi = curve.domain
    tt = lo + t * (hi - lo)
    cubic = lb.BezierCurve(np.random.default_rng(3).normal(size=(4, 2)))
    new = lambda: curve.evaluate(tt)  # noqa: E731
    return {
        "new": new,
        "one thread": with_setting(atoms, "HALF_ANGLE_THREADS", 1, new),
        "cubic": lambda: cubic.evaluate(t),
    }, "cubic"


def main() -> None:
    kernels.USE_COMPILED = False
    fns, ref = {"lambda": lambda_fns, "trig": trig_fns}[sys.argv[1]]()
    for fn in fns.values():
        fn()
    for clock in (time.perf_counter, time.process_time):
        best = rounds(fns, clock)
        shown = ", ".join(
            f"{name} {value * 1e3:.2f} ms ({value / best[ref]:.2f}x)"
            for name, value in best.items()
        )
        print(f"{clock.__name__}: {shown}; load {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
