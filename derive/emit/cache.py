"""A content-addressed cache of `render_all`: generated/'s text, keyed by everything it is a
function of.

`lambda-bezier derive [--check]` re-derives every formula and runs every check inside the
derivation (general-n forms against each degree, the joins re-proved, the surface matrices
against their Kronecker form). That work depends only on

- the bytes of every file of the derive package (the formulas, the family definitions),
- the bytes of the runtime modules derive reads definitions with (lambda_bezier's sources),
- the versions of Python, SymPy, mpmath and python-flint, and SymPy's ground types,

so its result is stored under the SHA-256 of exactly those inputs. A later run with the same
inputs reads the text back instead of deriving it again: every check it stands for passed on
those same inputs, since a failed check raises and nothing is stored. Change one byte of
derive/ or one library version and the key changes. `--no-cache` (or
LAMBDA_BEZIER_DERIVE_CACHE=off) derives afresh. The cache lives in
$LAMBDA_BEZIER_CACHE_DIR, else $XDG_CACHE_HOME/lambda-bezier, else ~/.cache/lambda-bezier;
an entry that does not read back whole (truncated, edited) is ignored and derived again.

This module imports neither SymPy nor FLINT: a cache hit pays for neither import.
"""

from __future__ import annotations

import hashlib
import json
import os
import sys
import tempfile
from importlib import metadata
from pathlib import Path

FORMAT = 1  # bump when the entry layout changes
_LIBRARIES = ("sympy", "mpmath", "python-flint")


def enabled() -> bool:
    """False when LAMBDA_BEZIER_DERIVE_CACHE is off, 0, no or false."""
    return os.environ.get("LAMBDA_BEZIER_DERIVE_CACHE", "").strip().lower() not in (
        "off",
        "0",
        "no",
        "false",
    )


def directory() -> Path:
    explicit = os.environ.get("LAMBDA_BEZIER_CACHE_DIR")
    if explicit:
        return Path(explicit) / "derive"
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "lambda-bezier" / "derive"


def _version(dist: str) -> str:
    try:
        return metadata.version(dist)
    except metadata.PackageNotFoundError:
        return "absent"


# not inputs: bytecode, and (in an installed wheel, where derive and generated/ sit inside
# lambda_bezier) the generated files a --check compares against
_SKIPPED = {"__pycache__", "_generated", "_derive"}


def _tree(root: Path, label: str, digest: hashlib._Hash) -> None:
    """Every file under `root` (but _SKIPPED), in a fixed order, by relative path."""
    files = sorted(
        p
        for p in root.rglob("*")
        if p.is_file()
        and not _SKIPPED.intersection(p.relative_to(root).parts)
        and p.suffix not in (".pyc", ".pyo")
    )
    for path in files:
        rel = path.relative_to(root).as_posix()
        data = path.read_bytes()
        digest.update(f"{label}/{rel}\0{len(data)}\0".encode())
        digest.update(data)


def key(derive_dir: Path, runtime_dir: Path) -> str:
    """The SHA-256 of the derivation's inputs (see the module docstring)."""
    digest = hashlib.sha256(f"lambda-bezier derive cache {FORMAT}\0".encode())
    environment = {
        "python": sys.version,
        "implementation": sys.implementation.name,
        **{dist: _version(dist) for dist in _LIBRARIES},
        # SymPy picks FLINT ground types when python-flint is installed, unless told otherwise
        "SYMPY_GROUND_TYPES": os.environ.get("SYMPY_GROUND_TYPES", ""),
    }
    digest.update(json.dumps(environment, sort_keys=True).encode())
    _tree(derive_dir, "derive", digest)
    _tree(runtime_dir, "lambda_bezier", digest)
    return digest.hexdigest()


def load(entry_key: str) -> dict[str, str] | None:
    """The files stored under `entry_key`, or None (absent, unreadable, or not whole)."""
    path = directory() / f"{entry_key}.json"
    try:
        entry = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    if not isinstance(entry, dict) or entry.get("key") != entry_key:
        return None
    files = entry.get("files")
    if not isinstance(files, dict) or not all(
        isinstance(k, str) and isinstance(v, str) for k, v in files.items()
    ):
        return None
    if entry.get("sha256") != _files_digest(files):
        return None
    return files


def store(entry_key: str, files: dict[str, str]) -> None:
    """Store `files` under `entry_key` (atomically); a cache that cannot be written is skipped:
    it only saves time."""
    target = directory()
    entry = {"key": entry_key, "sha256": _files_digest(files), "files": files}
    try:
        target.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=target, prefix=".tmp-", suffix=".json")
        try:
            with os.fdopen(fd, "w", encoding="utf-8") as out:
                json.dump(entry, out, sort_keys=True)
            os.replace(tmp, target / f"{entry_key}.json")
        except BaseException:
            Path(tmp).unlink(missing_ok=True)
            raise
    except OSError:
        return


def _files_digest(files: dict[str, str]) -> str:
    digest = hashlib.sha256()
    for name in sorted(files):
        text = files[name].encode()
        digest.update(f"{name}\0{len(text)}\0".encode())
        digest.update(text)
    return digest.hexdigest()
