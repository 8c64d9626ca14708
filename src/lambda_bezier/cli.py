"""The `lambda-bezier` command line."""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Iterator
from fractions import Fraction
from pathlib import Path
from typing import TYPE_CHECKING, Any, SupportsFloat, cast

if TYPE_CHECKING:
    from .energy import OptimalLambda


def _energy_order(text: str) -> int:
    """--energy: an ASCII integer (argparse's int() would take '２' or '1_0')."""
    from .hazmat.numbers import parse_int

    try:
        return parse_int(text)
    except ValueError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


class _ShapeFamilies:
    """optimal-lambda's --family choices, the built-in shape-parameter families in order
    (generated/__init__.py), read only when the option is checked or help is printed: the
    parser is built for every command, and `lambda-bezier derive` must run where generated/
    is missing."""

    def names(self) -> list[str]:
        from ._lazy import builtin_families

        return list(builtin_families())

    def __contains__(self, name: object) -> bool:
        return name in self.names()

    def __iter__(self) -> Iterator[str]:
        return iter(self.names())


def build_parser() -> argparse.ArgumentParser:
    from . import __version__

    parser = argparse.ArgumentParser(
        prog="lambda-bezier",
        description="Derive, check and use Bézier curves with a shape parameter λ.",
    )
    parser.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
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
    derive.add_argument(
        "--no-cache",
        action="store_true",
        help="derive afresh even when these exact sources and libraries were derived before "
        "(the content-addressed cache; LAMBDA_BEZIER_DERIVE_CACHE=off does the same)",
    )
    derive.add_argument(
        "--family",
        type=Path,
        metavar="FILE",
        help="derive the family a [family] table in FILE defines (into FILE's directory)",
    )
    derive.add_argument(
        "--out", type=Path, metavar="DIR", help="with --family: write the derived file into DIR"
    )

    opt = sub.add_parser(
        "optimal-lambda",
        help="the λ minimising a curve energy for given control points",
        description="The λ minimising E_k = ∫|p^(k)|² dt (k = 1 stretch, 2 strain, 3 jerk) for "
        "the given control points, exactly. Points are x,y or x,y,z with integer, decimal or "
        "p/q coordinates (ASCII digits; negative ones as typed, e.g. -1,2), e.g.: "
        "lambda-bezier optimal-lambda --energy 2 0,6 0,2 5,2 7,0 2,0 6,8",
    )
    opt.add_argument("points", nargs="+", metavar="POINT", help="control point x,y or x,y,z")
    opt.add_argument(
        "--family",
        metavar="NAME|FILE",
        # the built-in names are not listed here: the parser is built for every command, and
        # `lambda-bezier derive` must run where generated/ is missing
        help="curve family: a built-in shape-parameter family's name (default: the first "
        "built-in one) or a family file of your own, derived with `lambda-bezier derive "
        "--family FILE`",
    )
    opt.add_argument(
        "--energy",
        "-k",
        type=_energy_order,
        default=2,
        choices=[1, 2, 3],
        help="energy order k (default: 2, strain)",
    )
    opt.add_argument(
        "--clamp", action="store_true", help="also give the minimiser over the family's λ range"
    )
    opt.add_argument("--json", action="store_true", help="machine-readable output")

    exp = sub.add_parser(
        "export",
        help="write a curve or composite (lambda-bezier JSON) as STEP, DXF, SVG or JSON",
        description="Read a curve or composite in the JSON form of lambda_bezier.export and "
        "write it as one exact B-spline (STEP through OCCT, DXF SPLINE through ezdxf; both "
        'need pip install "lambda-bezier[cad]"), an SVG path, or normalised JSON.',
    )
    exp.add_argument(
        "--format",
        required=True,
        choices=["step", "dxf", "svg", "json", "family"],
        help="family: write the definition of the own family INPUT.json embeds as a TOML "
        "family file (for `lambda-bezier derive --family`)",
    )
    exp.add_argument(
        "--family",
        action="append",
        type=Path,
        metavar="FILE",
        help="a family of your own that INPUT.json uses: its definition file (derived with "
        "`lambda-bezier derive --family FILE`) or its NAME.derived.json; repeatable. Default: "
        "a NAME.derived.json beside INPUT.json",
    )
    exp.add_argument(
        "--tolerance",
        type=float,
        default=None,
        help="SVG only: approximate pieces of degree > 3 by cubics within this distance",
    )
    exp.add_argument("input", type=Path, metavar="INPUT.json")
    exp.add_argument("output", type=Path, metavar="OUTPUT")

    ex = sub.add_parser(
        "example",
        help="copy the example family or records files shipped with the package into DIR",
        description="Copy the example files shipped with lambda-bezier into DIR, to use them "
        "anywhere: `family` (nouri_saeidian.toml, a family of your own with records about it, "
        "and its derived document), `records` (user_paper.toml, records about the built-in "
        "families); `list` prints every example file's installed path.",
    )
    ex.add_argument("kind", choices=["family", "records", "list"])
    ex.add_argument("directory", type=Path, nargs="?", metavar="DIR", help="(not for list)")

    from ._verify_runner import add_arguments

    add_arguments(
        sub.add_parser(
            "verify",
            help="check every published formula and matrix against the derivation",
            description="Compare every formula the papers print (derive/published/*.toml) "
            "with our derivation; one line per record: id, source, verdict and, for a "
            "mismatch, the smallest diff. Exit 1 when a verdict differs from its recorded "
            "expectation (or, with --strict, on any mismatch).",
        )
    )
    return parser


def console_main() -> None:
    """The `lambda-bezier` console script (and `python -m lambda_bezier`): main(), then the
    process ends without tearing the interpreter down.

    Freeing SymPy's modules and caches at a normal exit takes 0.2-0.3 s on our 2-core VM,
    about a twentieth of a whole `verify`, with no file or child process left to clean up:
    the output is flushed here, files are written atomically before main() returns, and the
    verify workers are joined. mypy ends its command the same way. An exception, SystemExit
    included (argparse errors), takes the ordinary exit path.
    """
    try:
        code = main()
        sys.stdout.flush()
    except BrokenPipeError:  # the reader left (`... | head`): no traceback, as a shell tool
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        os._exit(1)
    sys.stderr.flush()
    os._exit(code)


def _negative_points_as_positionals(argv: list[str]) -> list[str]:
    """argparse takes a word starting with '-' for an option unless it is a plain negative
    number: '-1,2' would be an unknown option. Negative coordinates are the commonest there
    are, so after `optimal-lambda` such a word gets a leading space, which argparse reads as a
    positional and the number grammar strips."""
    from .hazmat.numbers import NEGATIVE

    if "optimal-lambda" not in argv:
        return argv
    start = argv.index("optimal-lambda") + 1
    return argv[:start] + [" " + a if NEGATIVE.fullmatch(a) else a for a in argv[start:]]


def main(argv: list[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    args = build_parser().parse_args(_negative_points_as_positionals(argv))
    if args.command == "derive" and args.family is not None:
        from ._family_runner import run as run_family

        return run_family(args.family, args.out, check=args.check, quiet=args.quiet)
    if args.command == "derive":
        from ._derive_runner import find_checkout, run

        root = args.root.resolve() if args.root else None
        if root is not None and find_checkout(root) != root:  # as verify --root: exit 2
            print(
                f"lambda-bezier derive: --root {args.root} is not a lambda-bezier source "
                "checkout (a directory with derive/ and this project's pyproject.toml)",
                file=sys.stderr,
            )
            return 2
        return run(check=args.check, root=root, quiet=args.quiet, cache=not args.no_cache)
    if args.command == "optimal-lambda":
        return _optimal_lambda(args)
    if args.command == "export":
        return _export(args)
    if args.command == "example":
        return _example(args)
    if args.command == "verify":
        from ._verify_runner import run_from_args

        return run_from_args(args)
    raise AssertionError(args.command)  # argparse enforces the choices


def _export(args: argparse.Namespace) -> int:
    from . import export

    try:
        if args.tolerance is not None and args.format != "svg":
            raise ValueError("--tolerance applies to --format svg only")
        text = args.input.read_text(encoding="utf-8")
        if args.format == "family":
            if args.family:
                raise ValueError("--family does not apply to --format family")
            args.output.write_text(export.family_definition(text), encoding="utf-8")
            return 0
        obj = export.from_json(text, family=args.family or _derived_beside(args.input, text))
        if args.format == "json":
            args.output.write_text(export.to_json(obj) + "\n", encoding="utf-8")
        elif args.format == "svg":
            args.output.write_text(export.to_svg(obj, tolerance=args.tolerance), encoding="utf-8")
        else:
            getattr(export, f"to_{args.format}")(obj, args.output)
    except (OSError, ValueError, ImportError) as exc:
        print(f"lambda-bezier export: error: {exc}", file=sys.stderr)
        return 2
    return 0


def _example(args: argparse.Namespace) -> int:
    from . import examples

    try:
        if args.kind == "list":
            if args.directory is not None:
                raise ValueError("`example list` takes no DIR")
            for name in examples.names():
                print(examples.path(name))
            return 0
        if args.directory is None:
            raise ValueError(f"`example {args.kind}` needs a DIR to copy into")
        for path in examples.copy(args.kind, args.directory):
            print(path)
    except (OSError, ValueError) as exc:
        print(f"lambda-bezier example: error: {exc}", file=sys.stderr)
        return 2
    return 0


def _derived_beside(path: Path, text: str) -> list[Path]:
    """The derived documents beside a JSON form of the own families it embeds."""
    import json

    try:
        definitions = json.loads(text).get("definitions", {})
    except (ValueError, AttributeError, RecursionError):
        return []  # from_json says what is wrong
    if not isinstance(definitions, dict):
        return []
    beside = [path.parent / f"{name}.derived.json" for name in definitions if isinstance(name, str)]
    return [p for p in beside if p.is_file()]


def _family_argument(text: str | None) -> object:
    """--family of optimal-lambda: a built-in family's name, or a family file of the user's
    own (a Family from load_family)."""
    names = _ShapeFamilies().names()
    if text is None:
        return names[0]
    if text in names:
        return text
    if "/" in text or "\\" in text or text.endswith(".toml") or Path(text).is_file():
        from .family import load_family

        return load_family(text)
    raise ValueError(f"--family must be one of {', '.join(names)} or a family file, got {text!r}")


def _optimal_lambda(args: argparse.Namespace) -> int:
    from .energy import optimal_lambda
    from .hazmat.numbers import parse_point

    try:
        points = [parse_point(p.lstrip(" ")) for p in args.points]
        if len({len(p) for p in points}) != 1:
            raise ValueError("all points must have the same dimension (2 or 3 coordinates)")
        family = _family_argument(args.family)
        if (
            getattr(family, "atom_data", None) is not None
            or getattr(family, "several", None) is not None
            or hasattr(family, "by_degree")
            or hasattr(family, "energy_minimum")
        ):
            # several (or indexed) parameters, a trigonometric/hyperbolic/mixed family, or
            # one with its parameter in the domain (C-Bézier: certified): every parameter by
            # name over the box (optimal_parameters; --clamp is implied)
            return _optimal_parameters(args, points, family)
        result = optimal_lambda(points, args.energy, family, clamp=args.clamp)
    except ValueError as exc:
        print(f"lambda-bezier optimal-lambda: error: {exc}", file=sys.stderr)
        return 2
    # An exact result has a few times the digits of its input (a 4000-digit coordinate gives
    # a λ of about 16000), past Python's 4300-digit guard on int/str conversion, a guard
    # against untrusted text and not our own results (each input number is held within it).
    limit = sys.get_int_max_str_digits()
    sys.set_int_max_str_digits(0)
    try:
        return _print_optimal_lambda(args, family, result)
    finally:
        sys.set_int_max_str_digits(limit)


def _print_optimal_lambda(args: argparse.Namespace, family: object, result: OptimalLambda) -> int:
    import json

    from .energy import ENERGY_NAMES

    k = args.energy
    family_name = family if isinstance(family, str) else getattr(family, "name", str(family))
    report = {
        "family": family_name,
        "range": result.range_text,
        "energy_order": k,
        "energy_name": ENERGY_NAMES[k],
        "lambda": str(result.unconstrained),
        "lambda_decimal": _float_or_none(result.unconstrained),
        "energy": str(result.unconstrained_energy),
        "energy_decimal": _float_or_none(result.unconstrained_energy),
        "admissible": bool(result.unconstrained_admissible),
    }
    if args.clamp:
        report |= {
            "clamped_lambda": str(result.lam),
            "clamped_lambda_decimal": _float_or_none(result.lam),
            "clamped_energy": str(result.energy),
            "clamped_energy_decimal": _float_or_none(result.energy),
            "clamped_admissible": bool(result.admissible),
        }
    if args.json:
        print(json.dumps(report, indent=2, ensure_ascii=False))
        return 0

    def both(key: str) -> str:
        return f"{report[key]}  ≈ {_decimal(cast(Fraction, exact[key]))}"

    # the points were parsed to Fractions, so every value of the result is an exact Fraction
    exact = {
        "lambda": result.unconstrained,
        "energy": result.unconstrained_energy,
        "clamped_lambda": result.lam,
        "clamped_energy": result.energy,
    }

    verdict = "yes" if report["admissible"] else f"no: outside {result.range_text}"
    lines = [
        f"family          {family_name}  (λ ∈ {result.range_text})",
        f"energy          E_{k} ({ENERGY_NAMES[k]})",
        f"optimal λ       {both('lambda')}",
        f"E_{k} at λ        {both('energy')}",
        f"admissible      {verdict}",
    ]
    if args.clamp:
        note = "" if report["clamped_admissible"] else "  (an excluded end of the range)"
        lines += [
            f"clamped λ       {both('clamped_lambda')}{note}",
            f"E_{k} at clamped  {both('clamped_energy')}",
        ]
    print("\n".join(lines))
    return 0


def _optimal_parameters(args: argparse.Namespace, points: list[Any], family: Any) -> int:
    """optimal-lambda for a family file in several (or indexed) parameters, or of atoms
    (trigonometric, hyperbolic, mixed): every parameter by name over the closed box
    (lambda_bezier.optimal_parameters), exact (a Fraction, or a ConstantFraction in π or
    e^W) and as a decimal; --clamp changes nothing, the box is always respected."""
    import json

    from .energy import ENERGY_NAMES, optimal_parameters

    r = optimal_parameters(points, args.energy, family=family)
    k = args.energy

    at_end = _attained_end(family, r)

    def text(v: Any, name: str = "") -> Any:
        if name in at_end:  # the range's end as written ("pi"), not its float
            return at_end[name]
        return [str(x) for x in v] if isinstance(v, tuple) else str(v)

    def decimal(v: Any) -> Any:
        return [_float_or_none(x) for x in v] if isinstance(v, tuple) else _float_or_none(v)

    range_text = getattr(family, "range_text", "every parameter over its closed range")
    report = {
        "family": family.name,
        "range": range_text,
        "energy_order": k,
        "energy_name": ENERGY_NAMES[k],
        "parameters": {name: text(v, name) for name, v in r.values.items()},
        "parameters_decimal": {name: decimal(v) for name, v in r.values.items()},
        "energy": str(r.energy),
        "energy_decimal": _float_or_none(r.energy),
        "free_inside": r.free_inside,
        "boundary": r.boundary,
        "lower_bound": None if r.lower_bound is None else str(r.lower_bound),
        "method": r.method,
    }
    if args.json:
        print(json.dumps(report, indent=2, ensure_ascii=False))
        return 0
    lines = [
        f"family          {family.name}  ({range_text})",
        f"energy          E_{k} ({ENERGY_NAMES[k]})",
    ]
    for name, value in r.values.items():
        lines.append(f"optimal {name:<8}{text(value, name)}  ≈ {decimal(value)}")
    lines.append(f"E_{k} there      {r.energy}  ≈ {float(r.energy):.12g}")
    lines.append(
        "where           "
        + (
            "the free minimum, inside the box"
            if r.free_inside
            else f"on the boundary {r.boundary}"
            if r.boundary
            else "inside the range"
        )
    )
    if r.lower_bound is not None:
        lines.append(f"proven bound    E_{k} >= {float(r.lower_bound):.12g} on the box")
    if r.method != "exact":
        lines.append(f"method          {r.method}: the least E_{k} is within 1e-12 of E_{k} there")
    print("\n".join(lines))
    return 0


def _attained_end(family: Any, r: Any) -> dict[str, str]:
    """{name: the end as the family writes it} when a certified optimum over a C-Bézier
    family's range lies on a closed end ("alpha = pi (upper end)"): its exact value, where
    `values` holds the float (a curve of the family takes a float alpha)."""
    ends = getattr(family, "range_ends", None)
    if ends is None or r.method != "certified" or len(r.values) != 1:
        return {}
    name = next(iter(r.values))
    closed = (getattr(family, "lo_closed", False), getattr(family, "hi_closed", False))
    for end, is_closed, side in zip(ends, closed, ("lower", "upper"), strict=True):
        if is_closed and r.boundary == f"{name} = {end} ({side} end)":
            return {name: str(end)}
    return {}


def _float_or_none(q: SupportsFloat) -> float | None:
    """The JSON *_decimal fields: the nearest float, or null for an exact value beyond the
    float range (the exact value is in the field without _decimal)."""
    try:
        value = float(q)
    except OverflowError:
        return None
    return value if value != 0 or q == 0 else None


def _decimal(q: Fraction) -> str:
    """12 significant digits of an exact value, at any magnitude (a 400-digit coordinate
    gives an energy far beyond the float range; it still prints)."""
    from decimal import Decimal, localcontext

    value = _float_or_none(q)
    if value is not None:
        return f"{value:.12g}"
    with localcontext() as ctx:
        ctx.prec = 12
        d = Decimal(q.numerator) / Decimal(q.denominator)
    return format(d.normalize(), "g")


if __name__ == "__main__":
    raise SystemExit(main())
