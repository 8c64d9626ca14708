"""The runtime stays thin: importing it must not import SymPy."""

import subprocess
import sys


def test_import_does_not_import_sympy():
    code = "import sys, lambda_bezier; print('sympy' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_public_api():
    import lambda_bezier as lb

    assert set(lb.FAMILIES) == {"bezier", "same_degree", "bernstein_like"}
    assert lb.__version__
