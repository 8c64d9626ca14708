"""`lambda-bezier derive [--check]`: regenerate generated/ from derive/, or compare.

SymPy is imported here only when the command runs, never by `import lambda_bezier`.
"""

from __future__ import annotations

import hashlib
import importlib
import importlib.util
import sys
from collections.abc import Callable
from importlib import metadata
from pathlib import Path
from types import ModuleType

HINT = "hint: run `lambda-bezier derive` in the checkout to refresh generated/"


def find_checkout(start: Path) -> Path | None:
    """The lambda-bezier source checkout containing `start`, if any."""
    for d in (start, *start.parents):
        pyproject = d / "pyproject.toml"
        if (
            (d / "derive" / "__init__.py").is_file()
            and pyproject.is_file()
            and 'name = "lambda-bezier"' in pyproject.read_text(encoding="utf-8")
        ):
            return d
    return None


def load_derive(root: Path | None) -> ModuleType:
    """The checkout's derive/ package when there is a checkout (so edits to derive/ take effect
    without reinstalling), else the copy installed with the wheel."""
    # found, not imported: a derivation read back from the cache (derive/emit/cache.py)
    # never pays for importing SymPy
    if importlib.util.find_spec("sympy") is None:
        raise SystemExit("lambda-bezier derive needs SymPy: pip install 'lambda-bezier[derive]'")
    if root is None:
        return importlib.import_module("lambda_bezier._derive")
    # one module name per checkout, so two roots in one process never share a package
    digest = hashlib.sha1(str(root.resolve()).encode()).hexdigest()[:12]
    name = f"_lambda_bezier_checkout_derive_{digest}"
    if name in sys.modules:
        return sys.modules[name]
    init = root / "derive" / "__init__.py"
    spec = importlib.util.spec_from_file_location(
        name, init, submodule_search_locations=[str(init.parent)]
    )
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    spec.loader.exec_module(module)
    return module


def installed_generated_dir() -> Path:
    # the submodule by its full name: mypy, which does not see generated/ (it is installed
    # under this name by the package-dir mapping), then skips it instead of reading the
    # package's __getattr__
    import lambda_bezier._generated as _generated

    return Path(_generated.__file__).parent


def run(check: bool, root: Path | None, quiet: bool = False, cache: bool = True) -> int:
    checkout = root if root is not None else find_checkout(Path.cwd())
    if checkout is None and not check:
        print(
            "lambda-bezier derive writes into a source checkout's generated/: run it inside "
            "the checkout or pass --root PATH (use --check to compare an installed copy)",
            file=sys.stderr,
        )
        return 2
    derive = load_derive(checkout)  # exits with an install hint when SymPy is missing
    target = checkout / "generated" if checkout else installed_generated_dir()
    say: Callable[[str], None] = (
        (lambda msg: None) if quiet else (lambda msg: print(msg, file=sys.stderr, flush=True))
    )
    sympy_version = _sympy_version()
    if sympy_version != derive.SYMPY_VERSION:
        say(
            f"warning: generated/ is printed with SymPy {derive.SYMPY_VERSION}, "
            f"this is SymPy {sympy_version}; output may differ"
        )
    files = _render(derive, cache, say)
    emit = importlib.import_module(f"{derive.__name__}.emit.tree")
    if check:
        label = "generated" if checkout else str(target)
        missing = _recover_before_check(target, say)
        if missing:
            print(missing, file=sys.stderr)
            return 1
        diffs = emit.diff_tree(files, target, label)
        if diffs:
            sys.stdout.write("".join(diffs))
            print(f"{len(diffs)} generated file(s) differ from the derivation.", file=sys.stderr)
            print(HINT, file=sys.stderr)
            return 1
        say(f"generated/ matches the derivation ({len(files)} files).")
        return 0
    assert checkout is not None
    try:
        emit.write_tree(files, target, say)
    except OSError as exc:
        where = exc.filename or target
        print(
            f"lambda-bezier derive: error: cannot write {target}: {exc.strerror or exc} "
            f"({where}); {target} was left as it was",
            file=sys.stderr,
        )
        return 1
    say(f"wrote {len(files)} files to {target}")
    return 0


def _sympy_version() -> str:
    try:
        return metadata.version("sympy")
    except metadata.PackageNotFoundError:  # a SymPy without installed metadata
        import sympy

        return str(sympy.__version__)


def _render(derive: ModuleType, use_cache: bool, say: Callable[[str], None]) -> dict[str, str]:
    """derive.render_all(), or its text read back from the content-addressed cache when the
    same sources and libraries were derived before (derive/emit/cache.py)."""
    derive_file: str | None = getattr(derive, "__file__", None)
    cache = importlib.import_module(f"{derive.__name__}.emit.cache") if derive_file else None
    key = None
    if cache is not None and derive_file is not None and use_cache and cache.enabled():
        key = cache.key(Path(derive_file).parent, Path(__file__).parent)
        files: dict[str, str] | None = cache.load(key)
        if files is not None:
            say(
                f"derived before from the same sources and libraries (cache {key[:12]}); "
                "--no-cache derives again"
            )
            return files
    files = derive.render_all(progress=lambda name: say(f"deriving {name} ..."))
    if cache is not None and key is not None:
        cache.store(key, files)
    return files


def _recover_before_check(target: Path, say: Callable[[str], None]) -> str | None:
    """--check compares against generated/: first undo an interrupted derive (a lone backup
    put back, debris removed), then name a directory that is still missing instead of listing
    every file as differing. Returns the error message, or None."""
    from ._generated_dir import backup_path, locked, recover

    try:
        with locked(target, say, required=False):
            for msg in recover(target):
                say(msg)
    except OSError as exc:
        return f"lambda-bezier derive --check: error: cannot recover {target}: {exc}"
    if not target.is_dir():
        return (
            f"lambda-bezier derive --check: error: {target} does not exist (no "
            f"{backup_path(target).name} to restore it from either); {HINT[6:]}"
        )
    return None
