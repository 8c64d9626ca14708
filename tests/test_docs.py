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
