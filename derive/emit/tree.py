"""generated/ as a tree of files: read it, diff it against a derivation, replace it atomically.

Imports neither SymPy nor FLINT (`lambda-bezier derive --check` on a cached derivation uses
only this module and emit/cache.py).
"""

from __future__ import annotations

import difflib
from collections.abc import Mapping
from pathlib import Path


def _is_ours(path: Path) -> bool:
    return "__pycache__" not in path.parts and path.suffix != ".pyc"


def read_tree(directory: Path) -> dict[str, str]:
    if not directory.is_dir():
        return {}
    return {
        p.relative_to(directory).as_posix(): p.read_text(encoding="utf-8")
        for p in sorted(directory.rglob("*"))
        if p.is_file() and _is_ours(p.relative_to(directory))
    }


def diff_tree(wanted: Mapping[str, str], directory: Path, label: str) -> list[str]:
    """Unified diffs (one string per drifted file): differing, missing or extra files."""
    have = read_tree(directory)
    out = []
    for name in sorted(set(wanted) | set(have)):
        old, new = have.get(name), wanted.get(name)
        if old == new:
            continue
        text = "".join(
            difflib.unified_diff(
                (old or "").splitlines(keepends=True),
                (new or "").splitlines(keepends=True),
                fromfile=f"{label}/{name}" + ("" if old is not None else " (missing)"),
                tofile=f"{label}/{name} (derived)" + ("" if new is not None else " (extra file)"),
            )
        )
        out.append(text or f"--- {label}/{name}\n+++ {label}/{name} (derived)\n")
    return out


def write_tree(files: Mapping[str, str], directory: Path, say=None) -> None:
    """Replace `directory` by exactly `files`, atomically (written and flushed in a sibling
    directory, swapped in with one rename exchange), serialised by a lock, after cleaning up
    what an interrupted earlier run left: see lambda_bezier._generated_dir."""
    from lambda_bezier._generated_dir import replace_tree

    replace_tree(files, Path(directory), *(() if say is None else (say,)))
