"""lambda-bezier benchmarks: every figure is a ratio against a reference timed in the same run.

    python benchmarks/run.py            # full run (a few minutes), markdown table on stdout
    python benchmarks/run.py --quick    # smaller sizes, for a smoke test

Needs the benchmark extra: pip install ".[bench]" (the `bezier` package is the reference for
evaluation; SymPy for the derivation benchmarks). Times are the best of several repeats.

The groups live beside this file, one module per subject (bench_curves, bench_intersection,
bench_surfaces, bench_derive); their clocks and the rows they record are in timing.py.
"""

from __future__ import annotations

import argparse
import datetime
import json
import math
import platform
import sys
from pathlib import Path

import numpy as np
from bench_curves import (
    bench_arc_length,
    bench_batch_evaluation,
    bench_evaluation,
    bench_optimal_lambda,
    bench_rational_evaluation,
    bench_trig_evaluation,
)
from bench_derive import bench_derive, bench_import, bench_verify
from bench_intersection import bench_closest, bench_compile, bench_exact, bench_intersection
from bench_surfaces import (
    bench_param_surfaces,
    bench_several_batch,
    bench_surface_bounds,
    bench_surfaces,
)
from timing import ROWS


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="smaller sizes (smoke test)")
    parser.add_argument("--json", type=Path, help="also write the rows as JSON here")
    groups = (
        "evaluation",
        "rational",
        "trig",
        "batch",
        "lambda",
        "geometry",
        "intersection",
        "exact",
        "closest",
        "compile",
        "surfaces",
        "param_surfaces",
        "several_batch",
        "surface_bounds",
        "derive",
        "verify",
        "import",
    )
    parser.add_argument(
        "--only",
        help=f"comma-separated subset of {', '.join(groups)} (default: all)",
        default=",".join(groups),
    )
    args = parser.parse_args()
    only = set(args.only.split(","))
    if only - set(groups):
        parser.error(f"unknown benchmark group(s): {', '.join(sorted(only - set(groups)))}")
    import bezier
    import sympy

    size, m_batch, m_lambda = (10**5, 10**4, 10**4) if args.quick else (10**6, 10**5, 10**5)
    m_memory = 10**6 if args.quick else 10**7  # issue #29: 1e7 curves in bounded memory
    runs = {
        "evaluation": lambda: bench_evaluation(size),
        "rational": lambda: bench_rational_evaluation(size),
        "trig": lambda: bench_trig_evaluation(size),
        "batch": lambda: bench_batch_evaluation(m_batch, m_memory),
        "lambda": lambda: bench_optimal_lambda(m_lambda, m_memory),
        "geometry": lambda: bench_arc_length(20 if args.quick else 100),
        "intersection": bench_intersection,
        "exact": bench_exact,
        "closest": lambda: bench_closest(1000 if args.quick else 10_000),
        "compile": bench_compile,
        "surfaces": lambda: bench_surfaces(
            300 if args.quick else 1000, 1000 if args.quick else 10_000, 10_000
        ),
        "param_surfaces": lambda: bench_param_surfaces(1000 if args.quick else 10_000),
        "several_batch": lambda: bench_several_batch(
            1000 if args.quick else 10_000, 10 if args.quick else 40
        ),
        "surface_bounds": lambda: bench_surface_bounds(100 if args.quick else 1000),
        "derive": bench_derive,
        "verify": bench_verify,
        "import": bench_import,
    }
    for name in groups:
        if name in only:
            print(f"{name} ...", file=sys.stderr)
            runs[name]()

    import os

    machine = (
        f"{platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}, "
        f"numpy {np.__version__}, bezier {bezier.__version__}, sympy {sympy.__version__}, "
        f"{datetime.date.today().isoformat()}"
    )
    print(f"Machine: {machine}\n")

    def _met(r: dict) -> str:  # a row with no target (shown for scale) meets nothing
        return "-" if r["target"] == "-" else ("yes" if r["met"] else "no")

    print("| benchmark | ours | reference | ratio | target | met |")
    print("|---|---:|---|---:|---|---|")
    for r in ROWS:
        ref_ms = r["reference_s"] * 1e3
        ref_time = "" if math.isnan(ref_ms) else f" ({ref_ms:.1f} ms)"  # a memory row: none
        print(
            f"| {r['benchmark']} | {r['ours_s'] * 1e3:.1f} ms | {r['reference']}{ref_time} | "
            f"{r['shown']} | {r['target']} | {_met(r)} |"
        )
    if args.json:
        args.json.write_text(json.dumps({"machine": machine, "rows": ROWS}, indent=2))


if __name__ == "__main__":
    main()
