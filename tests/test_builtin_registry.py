"""The built-in families are data (issue 19): derive/ names no family in shared code, and a new
built-in family is one file in derive/families/ — derive emits it, joins and energies cover
it, verify checks its records — with no edit to any shared module."""

from __future__ import annotations

import ast
import importlib
import io
import json
import shutil
import subprocess
import sys
import textwrap
import tokenize
from fractions import Fraction
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DERIVE = ROOT / "derive"

pytest.importorskip("sympy")


def _builtin_tables() -> dict[str, dict]:
    import tomllib

    return {
        path.stem: tomllib.loads(path.read_text(encoding="utf-8"))
        for path in sorted((DERIVE / "families").glob("*.toml"))
    }


def _code_tokens(path: Path) -> list[tuple[int, str]]:
    """(line, text) of every token but comments and docstrings."""
    source = path.read_text(encoding="utf-8")
    docstrings = set()
    for node in ast.walk(ast.parse(source)):
        body = getattr(node, "body", None)
        if isinstance(body, list) and body:
            first = body[0]
            if (
                isinstance(first, ast.Expr)
                and isinstance(first.value, ast.Constant)
                and isinstance(first.value.value, str)
            ):
                docstrings.add(first.lineno)
    out = []
    for tok in tokenize.generate_tokens(io.StringIO(source).readline):
        if tok.type == tokenize.COMMENT:
            continue
        if tok.type == tokenize.STRING and tok.start[0] in docstrings:
            continue
        out.append((tok.start[0], tok.string))
    return out


def test_shared_derive_modules_name_no_builtin_family():
    tables = _builtin_tables()
    names = set(tables)
    assert {"same_degree", "bernstein_like"} <= names  # the check below is about something
    own = set()  # a family's own modules may name it: its derivation and its paper's checks
    for table in tables.values():
        own |= {table["builtin"].get(k) for k in ("derivation", "checks")} - {None}
    found = []
    for path in sorted(DERIVE.rglob("*.py")):
        if path.stem in own:
            continue
        for line, text in _code_tokens(path):
            if any(name in text for name in names):
                found.append(f"{path.name}:{line}: {text}")
    assert not found, "shared derive modules name a built-in family:\n" + "\n".join(found)


def test_the_scan_sees_a_family_name_in_code(tmp_path):
    # the scan above must be able to fail: a planted name in code is seen, one in a comment
    # or a docstring is not
    planted = tmp_path / "m.py"
    planted.write_text('"""same_degree here is prose."""\n# same_degree\nX = "same_degree"\n')
    assert [text for _, text in _code_tokens(planted) if "same_degree" in text] == ['"same_degree"']


def test_registry_follows_the_definition_files():
    from lambda_bezier import _derive_runner

    derive = _derive_runner.load_derive(ROOT)
    registry = importlib.import_module(f"{derive.__name__}.families.registry")
    order = [b.name for b in registry.builtin_families()]
    tables = _builtin_tables()
    assert order == sorted(tables, key=lambda name: tables[name]["builtin"]["order"])
    assert registry.builtin_names() == (registry.REFERENCE, *order)
    assert derive.groups()[1 : 1 + len(order)] == tuple(order)
    init = (ROOT / "generated" / "__init__.py").read_text(encoding="utf-8")
    namespace: dict = {}
    exec(compile(init, "generated/__init__.py", "exec"), namespace)  # noqa: S102
    assert list(namespace["FAMILIES"]) == order


NEW_FAMILY = "copy_family"


@pytest.fixture(scope="module")
def checkout_with_new_family(tmp_path_factory) -> Path:
    """A copy of derive/ with one more built-in family, 000's eq. (1) under another name and
    with no derivation module of its own: only derive/families/copy_family.toml is added."""
    root = tmp_path_factory.mktemp("checkout")
    shutil.copytree(DERIVE, root / "derive", ignore=shutil.ignore_patterns("__pycache__"))
    text = (DERIVE / "families" / "same_degree.toml").read_text(encoding="utf-8")
    lines = [
        line
        for line in text.replace('name = "same_degree"', f'name = "{NEW_FAMILY}"')
        .replace("SameDegreeCurve", "CopyFamilyCurve")
        .splitlines()
        if not line.startswith(("derivation =", "checks =", "order ="))
    ]
    lines.append("order = 9")
    (root / "derive" / "families" / f"{NEW_FAMILY}.toml").write_text("\n".join(lines) + "\n")
    end_1, start_2 = "Subs(Derivative(p1(t), t), t, 1)", "Subs(Derivative(p2(t), t), t, 0)"
    records = root / "records.toml"
    records.write_text(
        textwrap.dedent(
            f"""
            schema_version = 2
            source = "test"
            family = "{NEW_FAMILY}"
            point_function = "V"

            [[record]]
            id = "copy.ends"
            claim = "endpoint_curve"
            location = "end values and first derivatives"
            equations = [
              {{ lhs = "p(0)", rhs = "V(0)" }},
              {{ lhs = "Subs(Derivative(p(t), t), t, 0)", rhs = "(n - 1 + lam)*(V(1) - V(0))" }},
            ]

            [[record]]
            id = "copy.misprint"
            claim = "endpoint_curve"
            location = "a wrong first derivative"
            expect = "mismatch"
            equations = [
              {{ lhs = "Subs(Derivative(p(t), t), t, 0)", rhs = "n*(V(1) - V(0))" }},
            ]

            [[record]]
            id = "copy.c1"
            claim = "c1_join"
            location = "C1 join of two such curves"
            first = {{ curve = "p1", degree = "n", shape = "lam1", points = "V1" }}
            second = {{ curve = "p2", degree = "m", shape = "lam2", points = "V2" }}
            convention = [
              {{ lhs = "p1(1)", rhs = "p2(0)" }},
              {{ lhs = "{end_1}", rhs = "{start_2}" }},
            ]
            equations = [
              {{ lhs = "V2(0)", rhs = "V1(n)" }},
              {{ lhs = "V2(1)", rhs = "V1(n) + (n-1+lam1)/(m-1+lam2)*(V1(n) - V1(n-1))" }},
            ]
            """
        )
    )
    script = textwrap.dedent(
        """
        import json, sys
        import derive
        from derive.verify import report as verify
        files = derive.render_all()
        out = sys.argv[1]
        json.dump(files, open(out + "/files.json", "w"))
        records = verify.load_records([__import__("pathlib").Path(out) / "records.toml"])
        results = {r["id"]: verify.check_record(r) for r in records}
        verdicts = {k: [v.verdict, v.error] for k, v in results.items()}
        json.dump(verdicts, open(out + "/verdicts.json", "w"))
        """
    )
    subprocess.run(
        [sys.executable, "-c", script, str(root)],
        cwd=root,
        env={"PYTHONPATH": str(root), "PATH": "/usr/bin:/bin"},
        check=True,
        timeout=300,
    )
    return root


def _module(text: str, name: str, exact_helpers: str) -> dict:
    """Execute an emitted module's text (its relative import of _exact resolved by hand)."""
    namespace: dict = {}
    exec(compile(exact_helpers, "_exact", "exec"), namespace)  # noqa: S102 - our own output
    body = text.replace("from ._exact import binomial, factorial, falling_factorial\n", "")
    exec(compile(body, name, "exec"), namespace)  # noqa: S102
    return namespace


def test_new_builtin_family_is_emitted_from_its_definition(checkout_with_new_family):
    files = json.loads((checkout_with_new_family / "files.json").read_text())
    assert f"{NEW_FAMILY}.py" in files
    init = _module(files["__init__.py"], "init", files["_exact.py"])
    assert list(init["FAMILIES"]) == ["same_degree", "bernstein_like", NEW_FAMILY]
    assert init["FAMILIES"][NEW_FAMILY] == "CopyFamilyCurve"
    new = _module(files[f"{NEW_FAMILY}.py"], NEW_FAMILY, files["_exact.py"])
    old = _module(files["same_degree.py"], "same_degree", files["_exact.py"])
    assert new["FAMILY"] == NEW_FAMILY
    for key in ("DEGREES", "DEGREE_OFFSET", "LAMBDA_RANGE", "POWER", "CENTRED", "BERNSTEIN"):
        assert new[key] == old[key], key
    # the end forms: fitted in n by the engine, 000's from its three-term form; equal
    for n in (3, 4, 7, 12):
        for lam in (Fraction(-3, 2), Fraction(1, 3), Fraction(1)):
            for fn in ("endpoint_start", "endpoint_end"):
                assert new[fn](n, lam) == old[fn](n, lam), (fn, n, lam)
    # the committed generated/ is what this checkout emits for the built-in families
    for name in ("same_degree.py", "bernstein_like.py", "bernstein.py"):
        assert files[name] == (ROOT / "generated" / name).read_text(encoding="utf-8"), name


def test_new_builtin_family_joins_energies_and_properties(checkout_with_new_family):
    files = json.loads((checkout_with_new_family / "files.json").read_text())
    helpers = files["_exact.py"]
    joins = _module(files["joins.py"], "joins", helpers)
    for other in ("bezier", "same_degree", "bernstein_like", NEW_FAMILY):
        for cont in ("C1", "C2", "G1", "G2"):
            for pair in ((NEW_FAMILY, other), (other, NEW_FAMILY)):
                assert (*pair, cont) in joins["JOINS"], (pair, cont)
    # the copy joins exactly as the family it copies
    lam1, lam2, alpha, d = Fraction(1, 3), Fraction(-1, 2), Fraction(3, 2), Fraction(2, 7)
    for cont, extra in (("C1", ()), ("C2", ()), ("G1", (alpha,)), ("G2", (alpha, d))):
        fn_new, args_new = joins["JOINS"][(NEW_FAMILY, "bernstein_like", cont)]
        fn_old, args_old = joins["JOINS"][("same_degree", "bernstein_like", cont)]
        assert args_new == args_old
        assert fn_new(5, 4, lam1, lam2, *extra) == fn_old(5, 4, lam1, lam2, *extra)
    energy = _module(files["energy.py"], "energy", helpers)
    assert energy["ENERGY"][NEW_FAMILY] == energy["ENERGY"]["same_degree"]
    properties = _module(files["properties.py"], "properties", helpers)
    assert properties["SINGULAR"][NEW_FAMILY] == properties["SINGULAR"]["same_degree"]


def test_new_builtin_family_records_are_verified(checkout_with_new_family):
    verdicts = json.loads((checkout_with_new_family / "verdicts.json").read_text())
    assert verdicts == {
        "copy.ends": ["match", None],
        "copy.misprint": ["mismatch", None],
        "copy.c1": ["match", None],
    }
