"""The layout is a contract (issue 27): derive/ has no import cycle, function-level imports
included; no hand-written module is over 800 lines; `lint-imports` keeps the layers contracts
of pyproject.toml's [tool.importlinter]. Each check has a companion showing it can fail.
"""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest
from conftest import ROOT
from import_graph import describe, edges_of, strongly_connected

grimp = pytest.importorskip("grimp")

pytestmark = pytest.mark.skipif(
    not (ROOT / "derive" / "__init__.py").is_file(), reason="needs the source checkout"
)

MAX_LINES = 800
# Hand-written Python: derive/, the runtime, the tests and their helpers (generated/ is emitted).
HAND_WRITTEN = ("derive", "src", "tests")


def _derive_graph() -> grimp.ImportGraph:
    sys.path.insert(0, str(ROOT))
    try:
        # grimp reads every import statement, those inside functions included
        return grimp.build_graph("derive", cache_dir=None)
    finally:
        sys.path.remove(str(ROOT))


def test_derive_has_no_import_cycle():
    graph = _derive_graph()
    assert len(graph.modules) > 20  # the graph is derive's, not an empty one
    cycles = strongly_connected(edges_of(graph))
    assert not cycles, "import cycles in derive/:\n" + "\n\n".join(
        describe(graph, c) for c in cycles
    )


def test_the_cycle_check_sees_a_cycle():
    graph = grimp.ImportGraph()
    for module in ("pkg", "pkg.a", "pkg.b", "pkg.c", "pkg.d"):
        graph.add_module(module)
    graph.add_import(importer="pkg.a", imported="pkg.b", line_number=1, line_contents="import b")
    graph.add_import(importer="pkg.b", imported="pkg.c", line_number=3, line_contents="import c")
    graph.add_import(importer="pkg.c", imported="pkg.a", line_number=7, line_contents="import a")
    graph.add_import(importer="pkg.d", imported="pkg.a", line_number=1, line_contents="import a")
    assert strongly_connected(edges_of(graph)) == [["pkg.a", "pkg.b", "pkg.c"]]
    assert "pkg.c -> pkg.a (line 7: import a)" in describe(graph, ["pkg.a", "pkg.b", "pkg.c"])
    graph.remove_import(importer="pkg.c", imported="pkg.a")
    assert strongly_connected(edges_of(graph)) == []


def test_a_function_level_import_counts():
    # the cycle the layout removed was held together by imports inside functions: grimp
    # must see those
    graph = _derive_graph()
    assert "derive.emit.generated" in graph.find_modules_directly_imported_by("derive")


def _long_modules(roots: list[Path]) -> list[str]:
    out = []
    for root in roots:
        for path in sorted(root.rglob("*.py")):
            count = len(path.read_text(encoding="utf-8").splitlines())
            if count > MAX_LINES:
                out.append(f"{path}: {count} lines")
    return out


def test_no_hand_written_module_over_800_lines():
    roots = [ROOT / name for name in HAND_WRITTEN]
    assert sum(1 for root in roots for _ in root.rglob("*.py")) > 50
    long = _long_modules(roots)
    assert not long, f"modules over {MAX_LINES} lines (split them):\n" + "\n".join(long)


def test_the_length_check_sees_a_long_module(tmp_path):
    (tmp_path / "short.py").write_text("x = 1\n" * MAX_LINES)
    (tmp_path / "long.py").write_text("x = 1\n" * (MAX_LINES + 1))
    assert _long_modules([tmp_path]) == [f"{tmp_path / 'long.py'}: {MAX_LINES + 1} lines"]


def _lint_imports(cwd: Path, *args: str) -> subprocess.CompletedProcess:
    # src/ first: the contracts are about the checkout's runtime (an installed copy of the
    # package also holds derive, as lambda_bezier._derive)
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(cwd / "src"), str(cwd)]))
    return subprocess.run(
        ["lint-imports", "--no-cache", *args],
        cwd=cwd,
        env=env,
        capture_output=True,
        text=True,
        timeout=600,
    )


def test_lint_imports_keeps_every_contract():
    result = _lint_imports(ROOT)
    assert result.returncode == 0, result.stdout + result.stderr
    for contract in (
        "derive: emit | verify > formulas > families > algebra | grammar KEPT",
        "lambda_bezier never imports sympy, flint or derive at import time KEPT",
    ):
        assert contract in result.stdout, result.stdout
    assert "0 broken" in result.stdout


def test_importing_every_runtime_module_leaves_sympy_flint_and_derive_out():
    # the forbidden contract ignores two call-time imports of SymPy; this says that importing
    # the runtime, every module of it, still loads none of them
    code = textwrap.dedent(
        """\
        import importlib, pkgutil, sys
        import lambda_bezier
        skip = ("lambda_bezier._derive", "lambda_bezier._generated", "lambda_bezier.__main__")
        def walk(path, prefix):  # pkgutil.walk_packages would import the skipped packages
            for m in pkgutil.iter_modules(path, prefix):
                if m.name.startswith(skip):
                    continue
                yield m.name
                if m.ispkg:
                    yield from walk(importlib.import_module(m.name).__path__, m.name + ".")
        names = list(walk(lambda_bezier.__path__, "lambda_bezier."))
        for name in names:
            importlib.import_module(name)
        loaded = sorted(m for m in sys.modules if m.split(".")[0] in ("sympy", "flint", "derive")
                        or m.startswith("_lambda_bezier_checkout_derive"))
        print(len(names), loaded[:5])
        """
    )
    result = subprocess.run(
        [sys.executable, "-c", code],
        capture_output=True,
        text=True,
        timeout=600,
        cwd=ROOT / "tests",
    )
    assert result.returncode == 0, result.stderr
    count, loaded = result.stdout.split(" ", 1)
    assert int(count) > 20 and loaded.strip() == "[]", result.stdout


def test_lint_imports_sees_an_upward_import(tmp_path):
    # a copy of the contract on a two-layer package: an import from the lower layer into the
    # upper one breaks it
    pkg = tmp_path / "toy"
    for layer in ("top", "bottom"):
        (pkg / layer).mkdir(parents=True)
        (pkg / layer / "__init__.py").write_text("")
    (pkg / "__init__.py").write_text("")
    (pkg / "top" / "a.py").write_text("from ..bottom import b\n")
    (pkg / "bottom" / "b.py").write_text("def f():\n    from ..top import a  # upward\n")
    (tmp_path / ".importlinter").write_text(
        textwrap.dedent(
            """\
            [importlinter]
            root_package = toy

            [importlinter:contract:toy-layers]
            name = toy layers
            type = layers
            containers = toy
            layers =
                top
                bottom
            """
        )
    )
    result = _lint_imports(tmp_path)
    assert result.returncode != 0
    assert "BROKEN" in result.stdout and "toy.bottom.b -> toy.top.a" in result.stdout
