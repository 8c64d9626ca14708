"""`lambda-bezier derive --family FILE [--out DIR] [--check]`: a user's family, derived.

The derivation (derive/families/engine.py) needs SymPy, imported only when the command runs.
The result is one JSON document written beside FILE (or into DIR) as `<name>.derived.json`,
atomically; `--check` compares instead and prints a unified diff when it drifted. Nothing is
written into an installed package (the shipped examples included): the command says to copy
the file out (`lambda-bezier example family DIR`) or to pass --out.
"""

from __future__ import annotations

import difflib
import importlib
import json
import os
import sys
import sysconfig
import tempfile
from pathlib import Path

from ._derive_runner import find_checkout, load_derive


def _say(quiet: bool, message: str) -> None:
    if not quiet:
        print(message, file=sys.stderr, flush=True)


def _write_atomically(path: Path, text: str) -> None:
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "w", encoding="utf-8", newline="\n") as fh:
            fh.write(text)
        os.chmod(tmp, 0o644)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def _installed_location(target: Path) -> Path | None:
    """The installed-package directory (this package, or site-packages) that would hold
    `target`, or None: derive --family without --out never writes into an installation
    (a source checkout, where an editable install's files live, is not one)."""
    import lambda_bezier

    roots = [Path(lambda_bezier.__file__).parent] + [
        Path(sysconfig.get_paths()[key]) for key in ("purelib", "platlib")
    ]
    where = target.resolve().parent
    if find_checkout(where) is not None:  # a source checkout (an editable install's files)
        return None
    for root in roots:
        if where == root.resolve() or root.resolve() in where.parents:
            return root
    return None


def run(path: Path, out_dir: Path | None, check: bool, quiet: bool = False) -> int:
    derive = load_derive(find_checkout(Path.cwd()))  # exits with a hint without SymPy
    definition = importlib.import_module(f"{derive.__name__}.families.definition")
    document = importlib.import_module(f"{derive.__name__}.emit.document")
    if out_dir is not None and not out_dir.is_dir():
        print(f"lambda-bezier derive: --out {out_dir} is not a directory", file=sys.stderr)
        return 2
    try:
        from ._family_file import FamilyFileError, read_family_table

        try:
            table = read_family_table(path)
        except FamilyFileError as exc:
            raise definition.DefinitionError(str(exc)) from None
        frequency = importlib.import_module(f"{derive.__name__}.families.cbezier")
        if frequency.is_frequency_family(table):  # C-Bezier on [0, alpha] (issue #30)
            document = importlib.import_module(f"{derive.__name__}.emit.cbezier_document")
            defn = document.read(table, str(path))
        else:
            defn = definition.read_definition(path)
        _say(quiet, f"deriving family {defn.name!r} from {path} ...")
        text = document.render(defn)
        if frequency.is_frequency_family(table):
            _say(quiet, document.summary(json.loads(text)))
    except definition.DefinitionError as exc:
        text = str(exc)
        if not text.startswith(f"{path}:"):  # every refusal names the file it is about
            text = f"{path}: {text}"
        print(f"lambda-bezier derive: {text}", file=sys.stderr)
        return 2
    target = document.derived_path(path, defn.name, out_dir)
    installed = _installed_location(target) if out_dir is None else None
    if installed is not None and not check:
        print(
            f"lambda-bezier derive: {path} is inside the installed package ({installed}); "
            f"nothing is written there. Copy it out first (`lambda-bezier example family DIR` "
            f"for the shipped example) or pass --out DIR",
            file=sys.stderr,
        )
        return 2
    if check:
        old = target.read_text(encoding="utf-8") if target.is_file() else ""
        if old == text:
            _say(quiet, f"{target} matches the derivation.")
            return 0
        diff = difflib.unified_diff(
            old.splitlines(keepends=True),
            text.splitlines(keepends=True),
            f"{target} (on disk)",
            f"{target} (derived)",
        )
        sys.stdout.writelines(diff)
        print(
            f"{target} differs from the derivation of {path}; run "
            f"`lambda-bezier derive --family {path}` to refresh it",
            file=sys.stderr,
        )
        return 1
    try:
        _write_atomically(target, text)
    except OSError as exc:
        print(f"lambda-bezier derive: cannot write {target}: {exc.strerror}", file=sys.stderr)
        return 2
    _say(quiet, f"wrote {target}")
    return 0
