"""The benchmarks' clocks and their table: best-of and interleaved timings, fresh processes,
and the rows every group records (`record`, `record_memory`)."""

from __future__ import annotations

import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def best_of(fn, repeat: int = 5) -> float:
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def interleaved(fns: dict[str, object], rounds: int = 5) -> dict[str, float]:
    """Best time of each function, the functions taking turns round by round: on a shared
    machine a burst of load then hits both sides of a ratio alike, not one of them."""
    best = {name: float("inf") for name in fns}
    for _ in range(rounds):
        for name, fn in fns.items():
            t0 = time.perf_counter()
            fn()  # type: ignore[operator]
            best[name] = min(best[name], time.perf_counter() - t0)
    return best


def peak_memory(fn) -> tuple[float, object]:
    """(peak bytes numpy and Python allocated during fn(), its result), by tracemalloc (numpy
    reports its buffers to it); what existed before the call does not count."""
    import tracemalloc

    tracemalloc.start()
    try:
        tracemalloc.reset_peak()
        result = fn()
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    return float(peak), result


def fresh_process(code: str, repeat: int = 1) -> float:
    """Best wall time of `python -c code` in new processes."""
    return _best_wall([sys.executable, "-c", code], repeat)


def command(*args: str, repeat: int = 1, env: dict[str, str] | None = None) -> float:
    """Best wall time of `lambda-bezier args` as a user runs it (the console script's entry
    point, output to /dev/null)."""
    return _best_wall([sys.executable, "-m", "lambda_bezier", *args], repeat, env)


def _best_wall(argv: list[str], repeat: int, env: dict[str, str] | None = None) -> float:
    import os

    full = None if env is None else {**os.environ, **env}
    return best_of(
        lambda: subprocess.run(argv, check=True, cwd=ROOT, stdout=subprocess.DEVNULL, env=full),
        repeat,
    )


def timed_in_fresh_process(code: str) -> float:
    """`code` prints the seconds of its own timed section; run it in a new process."""
    out = subprocess.run(
        [sys.executable, "-c", code], check=True, cwd=ROOT, capture_output=True, text=True
    )
    return float(out.stdout.strip().splitlines()[-1])


ROWS: list[dict] = []


def record(name: str, ours: float, ref_name: str, ref: float, target: str, ok: bool) -> None:
    """ratio = ours / reference (time); for "faster" targets the speed-up ref / ours is shown."""
    shown = f"{ref / ours:.1f}x faster" if "faster" in target else f"{ours / ref:.2f}x"
    ROWS.append(
        {
            "benchmark": name,
            "ours_s": ours,
            "reference": ref_name,
            "reference_s": ref,
            "ratio": ours / ref,
            "shown": shown,
            "target": target,
            "met": ok,
        }
    )
    print(
        f"  {name}: {ours * 1e3:.1f} ms vs {ref_name} {ref * 1e3:.1f} ms "
        f"-> {shown} (target {target}: {'met' if ok else 'NOT met'})",
        file=sys.stderr,
        flush=True,
    )


def record_memory(name: str, seconds: float, extra: float, limit: float) -> None:
    """A memory row: `extra` bytes allocated beyond the results at the peak, against `limit`
    (the ratio column is extra / limit)."""
    ROWS.append(
        {
            "benchmark": name,
            "ours_s": seconds,
            "reference": f"a bound of {limit / 1e6:.0f} MB beyond the results",
            "reference_s": float("nan"),
            "ratio": extra / limit,
            "shown": f"{extra / 1e6:.1f} MB extra",
            "target": f"<= {limit / 1e6:.0f} MB",
            "met": extra <= limit,
        }
    )
    print(
        f"  {name}: {seconds:.2f} s, {extra / 1e6:.1f} MB beyond the results "
        f"(target <= {limit / 1e6:.0f} MB: {'met' if extra <= limit else 'NOT met'})",
        file=sys.stderr,
        flush=True,
    )


def interleaved_clocks(
    fns: dict[str, object], rounds: int
) -> tuple[dict[str, float], dict[str, float]]:
    """`interleaved` with the CPU time too: (best wall time, best CPU time of the process, all
    its threads summed) of each function, the functions taking turns round by round."""
    wall = {name: float("inf") for name in fns}
    cpu = dict(wall)
    for _ in range(rounds):
        for name, fn in fns.items():
            c0, t0 = time.process_time(), time.perf_counter()
            fn()  # type: ignore[operator]
            wall[name] = min(wall[name], time.perf_counter() - t0)
            cpu[name] = min(cpu[name], time.process_time() - c0)
    return wall, cpu
