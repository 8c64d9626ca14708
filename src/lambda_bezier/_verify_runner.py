"""`lambda-bezier verify`: every published formula and matrix checked against the derivation.

The engine lives in derive/verify/report.py (it needs SymPy, imported only when the command runs);
this module parses the options, shows progress on a terminal, renders the report (or, with
--coverage, the papers' inventory from derive/verify/coverage.py) and keeps ERRATA.md current in a
checkout.
"""

from __future__ import annotations

import argparse
import copy
import importlib
import os
import sys
import tempfile
import time
from pathlib import Path
from typing import TextIO

from ._derive_runner import find_checkout, load_derive

FORMATS = ("text", "json", "markdown")


EXIT_CODES = """exit codes:
  0  every verdict is as its record expects (a record without `expect` expects match)
  1  some verdict differs from its expectation (or, with --strict, is not match), an
     erratum does not verify, a checker failed, or ERRATA.md is stale (with --coverage:
     also an item naming a missing record, or a built-in record in no item)
  2  a records file cannot be read or validated, or the options are wrong

Records files are read by a grammar of our own (nothing in them is run as code) and
checked with the derivation installed with lambda-bezier, or the checkout's derive/ when
run inside a checkout of this project (or --root), never code found beside PATH.
The records format: derive/published/README.md."""


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.formatter_class = argparse.RawDescriptionHelpFormatter
    parser.epilog = EXIT_CODES
    parser.add_argument(
        "paths",
        nargs="*",
        type=Path,
        metavar="PATH",
        help="records files (TOML) to check; default: the built-in records of the three papers",
    )
    parser.add_argument(
        "--format", choices=FORMATS, default="text", help="report format (default: text)"
    )
    parser.add_argument(
        "--strict",
        action="store_true",
        help="also fail on any mismatch or pending record, expected or not",
    )
    parser.add_argument(
        "--errata",
        action="store_true",
        help="(re)write ERRATA.md at the checkout root from the recorded errata",
    )
    parser.add_argument(
        "--coverage",
        action="store_true",
        help="print, per document and section, every item of the three papers with its "
        "records and verdicts or the reason it has none (built-in records only)",
    )
    parser.add_argument(
        "--only",
        action="append",
        default=[],
        metavar="TEXT",
        help="check only records whose id contains TEXT (repeatable)",
    )
    parser.add_argument(
        "--root",
        type=Path,
        default=None,
        help="the source checkout (default: the one containing the current directory)",
    )


def run_from_args(args: argparse.Namespace) -> int:
    root = args.root.resolve() if args.root else None
    return run(
        fmt=args.format,
        strict=args.strict,
        errata=args.errata,
        root=root,
        only=args.only,
        paths=args.paths,
        coverage=args.coverage,
    )


class Progress:
    """A one-line counter on stderr, shown only on a terminal and only after a moment."""

    def __init__(self, enabled: bool, delay: float = 0.5):
        self.enabled = enabled
        self.delay = delay
        self.start = time.monotonic()
        self.shown = False

    def __call__(self, done: int, total: int, current: str) -> None:
        """`done` of `total` records checked, `current` the last one finished."""
        if not self.enabled:
            return
        if done >= total:
            if self.shown:
                sys.stderr.write("\r\033[K")
                sys.stderr.flush()
            return
        if time.monotonic() - self.start < self.delay:
            return
        self.shown = True
        last = f" (last: {current})" if current else ""
        sys.stderr.write(f"\r\033[Kverify: {done}/{total} records checked{last}")
        sys.stderr.flush()


def _write_atomically(path: Path, text: str) -> None:
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "w", encoding="utf-8", newline="\n") as fh:
            fh.write(text)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def run(
    fmt: str = "text",
    strict: bool = False,
    errata: bool = False,
    root: Path | None = None,
    only: list[str] | None = None,
    out: TextIO | None = None,
    progress: bool | None = None,
    paths: list[Path] | None = None,
    coverage: bool = False,
) -> int:
    # the reported time is the command's: SymPy's import and the derivation of a records
    # file's own family (when loading it) took most of a short run, and verify() times
    # only the checking (a 2.8 s run printed "(0.0 s)")
    started = time.perf_counter()
    out = out or sys.stdout
    if root is not None and find_checkout(root) != root:
        print(
            f"lambda-bezier verify: --root {root} is not a lambda-bezier source checkout "
            "(a directory with derive/ and this project's pyproject.toml)",
            file=sys.stderr,
        )
        return 2
    if errata and paths:
        print(
            "lambda-bezier verify: --errata rewrites ERRATA.md from the built-in records; "
            "it takes no PATH",
            file=sys.stderr,
        )
        return 2
    if coverage and (paths or only or errata):
        print(
            "lambda-bezier verify: --coverage reports on the built-in records; it takes no "
            "PATH, --only or --errata",
            file=sys.stderr,
        )
        return 2
    checkout = root if root is not None else find_checkout(Path.cwd())
    if errata and checkout is None:
        raise SystemExit(
            "lambda-bezier verify --errata writes ERRATA.md into a source checkout: run it "
            "inside the checkout or pass --root PATH"
        )
    derive = load_derive(checkout)  # exits with an install hint when SymPy is missing
    verify = importlib.import_module(f"{derive.__name__}.verify.report")
    if not paths:
        published = checkout / "derive" / "published" if checkout else verify.PUBLISHED
        paths = sorted(published.glob("*.toml"))
        builtin = True
    else:
        builtin = False
    try:
        every = verify.load_records(paths)
    except verify.RecordsError as exc:
        print(f"lambda-bezier verify: {exc}", file=sys.stderr)
        return 2
    records = every
    if only:
        records = [r for r in every if any(text in r["id"] for text in only)]
        if not records:
            print(f"lambda-bezier verify: no record id contains {only}", file=sys.stderr)
            return 2
    if progress is None:
        progress = out is sys.stdout and sys.stdout.isatty() and sys.stderr.isatty()
    try:
        report = copy.copy(verify.verify(records, progress=Progress(progress), index=every))
    except RuntimeError as exc:  # a worker process died (the message names its record)
        print(f"lambda-bezier verify: {exc}", file=sys.stderr)
        return 1
    report.extra_problems = list(report.extra_problems)
    report.seconds = time.perf_counter() - started
    errata_path = checkout / verify.ERRATA_FILE if checkout is not None and builtin else None
    if errata_path is not None and not only:
        text = verify.render_errata(report)
        if errata:
            _write_atomically(errata_path, text)
            print(f"wrote {errata_path}", file=sys.stderr)
        elif not errata_path.is_file() or errata_path.read_text(encoding="utf-8") != text:
            report.extra_problems.append(
                f"{verify.ERRATA_FILE} is stale: run `{verify.ERRATA_COMMAND}` and commit it"
            )
    if coverage:
        cov = importlib.import_module(f"{derive.__name__}.verify.coverage")
        items = cov.load()
        verdicts = {r.id: r.verdict for r in report.results}
        report.extra_problems += cov.problems(items, verdicts)
        if fmt == "json":
            out.write(cov.render_json(items, verdicts))
        else:
            out.write(cov.render(items, verdicts, markdown=fmt == "markdown"))
    else:
        out.write(verify.RENDERERS[fmt](report))
    out.flush()
    problems = report.problems()
    if problems:
        print(
            f"lambda-bezier verify: {len(problems)} problem(s), listed at the end of the report "
            "(a verdict that differs from its recorded expectation, an erratum that does not "
            "verify, or a stale ERRATA.md)",
            file=sys.stderr,
        )
        return 1
    if report.failed(strict=strict):
        print(
            "lambda-bezier verify --strict: some records do not match (all expected)",
            file=sys.stderr,
        )
        return 1
    return 0
