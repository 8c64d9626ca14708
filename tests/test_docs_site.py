"""The documentation site (docs/): its examples run as written, and the API reference lists
every public name. Building the site itself (sphinx-build -W, which executes the notebooks)
is a CI step, not a test: see .ci/run."""

from __future__ import annotations

import doctest
import importlib
import re

import pytest
from conftest import ROOT

import lambda_bezier

DOCS = ROOT / "docs"
PAGES = sorted(DOCS.rglob("*.md")) if DOCS.is_dir() else []
PAGES = [p for p in PAGES if "_build" not in p.parts]
FLAGS = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE


@pytest.mark.skipif(not PAGES, reason="needs the checkout's docs/")
@pytest.mark.parametrize("page", PAGES, ids=[str(p.relative_to(DOCS)) for p in PAGES])
def test_page_examples(page):
    result = doctest.testfile(str(page), module_relative=False, optionflags=FLAGS)
    assert result.failed == 0


@pytest.mark.skipif(not PAGES, reason="needs the checkout's docs/")
def test_the_guide_has_examples():
    """The pages with `>>>` examples are the ones the doctests above run (a page whose
    examples were all lost, e.g. by a broken fence, would pass them vacuously)."""
    with_examples = {p.relative_to(DOCS).as_posix() for p in PAGES if ">>> " in p.read_text()}
    assert {
        "getting-started.md",
        "guide/families.md",
        "guide/energy.md",
        "guide/joins.md",
        "guide/verify.md",
        "guide/surfaces.md",
        "guide/rational.md",
    } <= with_examples


# the modules behind lambda_bezier.__all__, whose docstrings the API reference renders
MODULES = sorted({f"lambda_bezier.{m}" for m in lambda_bezier._EXPORTS.values()})


@pytest.mark.parametrize("module", MODULES)
def test_docstring_examples(module):
    result = doctest.testmod(importlib.import_module(module), optionflags=FLAGS)
    assert result.failed == 0


@pytest.mark.skipif(not (DOCS / "api.rst").is_file(), reason="needs the checkout's docs/")
def test_api_reference_lists_every_public_name():
    api = (DOCS / "api.rst").read_text()
    listed = set(re.findall(r"^   (\w+)$", api, re.M)) | set(
        re.findall(r"^\.\. data:: (\w+)$", api, re.M)
    )
    assert set(lambda_bezier.__all__) <= listed, set(lambda_bezier.__all__) - listed


@pytest.mark.skipif(not (DOCS / "tutorials").is_dir(), reason="needs the checkout's docs/")
def test_every_notebook_is_a_tutorial():
    """docs/tutorials/ links every notebook (so the site executes and shows it) and its index
    lists each one."""
    notebooks = {p.name for p in (ROOT / "notebooks").glob("*.py")}
    linked = {p.name for p in (DOCS / "tutorials").glob("*.py")}
    assert linked == notebooks
    for name in linked:
        assert (DOCS / "tutorials" / name).resolve() == (ROOT / "notebooks" / name).resolve()
    index = (DOCS / "tutorials" / "index.md").read_text()
    assert {f"{name[:-3]}" for name in notebooks} <= set(index.split())
