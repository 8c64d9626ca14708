"""The `lambda-bezier` command line."""

from __future__ import annotations

import argparse
from pathlib import Path


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="lambda-bezier",
        description="Derive, check and use Bézier curves with a shape parameter λ.",
    )
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    derive = sub.add_parser(
        "derive",
        help="regenerate generated/ from the SymPy derivations in derive/",
        description="Regenerate generated/ from derive/ (atomically), or with --check compare "
        "the derivation with the committed files and show a unified diff of any drift.",
    )
    derive.add_argument(
        "--check",
        action="store_true",
        help="write nothing; exit 1 with a diff if generated/ differs from the derivation",
    )
    derive.add_argument(
        "--root",
        type=Path,
        default=None,
        help="the source checkout (default: the one containing the current directory)",
    )
    derive.add_argument("-q", "--quiet", action="store_true", help="no progress messages")
    return parser


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    if args.command == "derive":
        from ._derive_runner import run

        root = args.root.resolve() if args.root else None
        return run(check=args.check, root=root, quiet=args.quiet)
    raise AssertionError(args.command)  # argparse enforces the choices


if __name__ == "__main__":
    raise SystemExit(main())
