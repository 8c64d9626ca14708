"""The groups of generated/ derived on two cores: the joins (the largest group, which needs
only the families' end forms) in a forked second process, every other group here.

Each group's text is a function of derive's sources alone, whichever process prints it, so
the files are the same bytes as a serial run (tests/test_derive.py compares both, and the
committed generated/, under other hash seeds). A failed check in the second process is
raised here, as it would be in a serial run. Serial where there is no fork (Windows, macOS's
default), on one core, or with LAMBDA_BEZIER_DERIVE_JOBS=1 (issue #29).
"""

from __future__ import annotations

import multiprocessing
import os
import pickle
import sys
from collections.abc import Callable, Sequence

# the groups the second process derives: the joins re-prove every weight per degree pair and
# need from the families only their closed end forms and basis polynomials
SECOND = ("joins",)


def jobs() -> int:
    """1 or 2: LAMBDA_BEZIER_DERIVE_JOBS when set, else 2 when two cores are ours and fork
    is available (Linux)."""
    text = os.environ.get("LAMBDA_BEZIER_DERIVE_JOBS", "").strip()
    if text:
        if text not in ("1", "2"):
            raise ValueError(f"LAMBDA_BEZIER_DERIVE_JOBS must be 1 or 2, not {text!r}")
        wanted = int(text)
    else:
        wanted = 2
    if wanted == 1 or not sys.platform.startswith("linux"):
        return 1
    if "fork" not in multiprocessing.get_all_start_methods():
        return 1
    return 2 if len(os.sched_getaffinity(0)) >= 2 else 1


def _second(names: Sequence[str], render: Callable[[str], str], conn) -> None:
    try:
        result: tuple = ("ok", {name: render(name) for name in names})
    except BaseException as exc:  # noqa: BLE001 - every failure goes back to the parent
        try:
            pickle.dumps(exc)
            result = ("error", exc)
        except Exception:  # noqa: BLE001 - an exception that does not pickle: its text
            result = ("error", RuntimeError(f"{type(exc).__name__}: {exc}"))
    conn.send(result)
    conn.close()


def render_groups(
    names: Sequence[str],
    render: Callable[[str], str],
    progress: Callable[[str], object] | None = None,
    shared: Callable[[], object] | None = None,
) -> dict[str, str]:
    """{group: text} of every group in `names`, rendered by `render(group)`. `shared()`
    derives, before the fork, what both processes need (the families' end forms and bases),
    so that neither derives it again."""
    second = [name for name in names if name in SECOND]
    if jobs() == 1 or not second or len(second) == len(names):
        out = {}
        for name in names:
            if progress:
                progress(name)
            out[name] = render(name)
        return out
    if shared is not None:
        shared()
    ctx = multiprocessing.get_context("fork")
    receive, send = ctx.Pipe(duplex=False)
    worker = ctx.Process(target=_second, args=(second, render, send), daemon=True)
    worker.start()
    send.close()
    try:
        out = {}
        for name in names:
            if progress:
                progress(name if name not in SECOND else f"{name} (second process)")
            if name not in SECOND:
                out[name] = render(name)
        try:
            status, value = receive.recv()
        except EOFError:
            worker.join()
            raise RuntimeError(
                f"the process deriving {', '.join(second)} ended without an answer "
                f"(exit code {worker.exitcode})"
            ) from None
        if status == "error":
            raise value
        out.update(value)
    finally:
        receive.close()
        if worker.is_alive():  # a check failed here first (or the answer is in): stop it
            worker.kill()
        worker.join()
    return {name: out[name] for name in names}
