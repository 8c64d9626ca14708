"""The README's and the package's examples run as written."""

import doctest

import pytest
from conftest import ROOT

import lambda_bezier


@pytest.mark.skipif(not (ROOT / "README.md").is_file(), reason="needs the checkout")
def test_readme_examples():
    result = doctest.testfile(
        str(ROOT / "README.md"), module_relative=False, optionflags=doctest.NORMALIZE_WHITESPACE
    )
    assert result.attempted > 10 and result.failed == 0


def test_package_docstring():
    result = doctest.testmod(lambda_bezier)
    assert result.attempted > 0 and result.failed == 0


def _modules_with_examples() -> list[str]:
    from pathlib import Path

    package = Path(lambda_bezier.__file__).parent
    names = []
    for path in sorted(package.rglob("*.py")):
        top = path.name == "__init__.py" and path.parent == package
        if not top and ">>>" in path.read_text(encoding="utf-8"):
            rel = path.relative_to(package).with_suffix("")
            parts = [p for p in rel.parts if p != "__init__"]
            names.append(".".join(["lambda_bezier", *parts]))
    return names


@pytest.mark.parametrize("module", _modules_with_examples())
def test_module_docstring_examples(module):
    """Every example in a module's docstrings runs as written (the package's own docstring is
    the test above)."""
    import importlib

    result = doctest.testmod(
        importlib.import_module(module),
        optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE,
    )
    assert result.attempted > 0 and result.failed == 0


@pytest.mark.skipif(not (ROOT / ".ci" / "run").is_file(), reason="needs the checkout")
def test_ci_runs_exactly_the_readme_set_up_commands():
    import re

    setup = (ROOT / "README.md").read_text().split("## Set up", 1)[1].split("\n## ", 1)[0]
    commands = re.findall(r"```bash\n(.*?)\n```", setup, re.S)
    assert len(commands) == 2, "the README keeps exactly two set-up commands"
    ci = (ROOT / ".ci" / "run").read_text()
    for command in commands:
        venv, activate, rest = command.split(" && ", 2)
        assert venv.startswith("python3 -m venv") and activate.startswith(". ")
        assert rest in ci, f"CI does not run the README's `{rest}`"


def test_public_names_resolve_lazily():
    """`import lambda_bezier` imports neither numpy nor SymPy (the command line starts without
    them); each public name imports its module on first access, and the runtime never needs
    SymPy."""
    import subprocess
    import sys

    script = (
        "import sys, lambda_bezier as lb\n"
        "print(sorted(m for m in ('numpy', 'sympy') if m in sys.modules))\n"
        "values = [getattr(lb, name) for name in lb.__all__]\n"
        "print(sorted(m for m in ('numpy', 'sympy') if m in sys.modules))\n"
    )
    out = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, check=True
    ).stdout.split("\n")
    assert out[:2] == ["[]", "['numpy']"]
    assert set(lambda_bezier.__all__) == set(lambda_bezier._EXPORTS)
    assert set(lambda_bezier.__all__) <= set(dir(lambda_bezier))
    # dir() shows the public API, not what __init__ imports for its own use
    public = {name for name in dir(lambda_bezier) if not name.startswith("_")}
    assert public == set(lambda_bezier.__all__)
    with pytest.raises(AttributeError, match="no attribute 'nothing'"):
        lambda_bezier.nothing  # noqa: B018
