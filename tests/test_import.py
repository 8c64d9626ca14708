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


def test_public_names_leave_the_engines_unimported():
    # every public name resolved, as benchmarks/run.py's import row does: the geometry,
    # intersection and atom-surface engines and the thread pool's module are imported on
    # first use, not by naming a class (issue #29: import time)
    code = (
        "import sys, lambda_bezier as lb; [getattr(lb, n) for n in lb.__all__]; "
        "print(' '.join(sorted(sys.modules)))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    loaded = set(out.stdout.split())
    assert "lambda_bezier.surface_joins" in loaded  # the names were resolved
    engines = {
        "lambda_bezier.geometry",
        "lambda_bezier._atom_geometry",
        "lambda_bezier.hazmat.atom_intersect",
        "lambda_bezier.hazmat.atom_surface_bounds",
        "lambda_bezier.atom_surfaces",
        "concurrent.futures",
        "numpy.polynomial",
        # the polynomial intersection engine (intersect_many and intersect_exact name it on
        # first call) and the several-parameter surface optimum's certified engine
        "lambda_bezier.hazmat.intersect",
        "lambda_bezier.hazmat.intersect_exact",
        "lambda_bezier.param_surface_optimum",
        # the several-parameter surface energies (lb.surface_energy names them on the first
        # call that needs them) with what only they use, and the heap of the surfaces'
        # branch and bound (round 18)
        "lambda_bezier.param_surface_energy",
        "lambda_bezier._optimal_box",
        "lambda_bezier._poly_direction",
        "lambda_bezier.hazmat.box_bernstein",
        "heapq",
        "lambda_bezier._surface_results",  # SurfaceClosestPoint, BoundaryReport (round 18)
        "lambda_bezier._join_options",  # a surface join's options, built on the first join
    }
    assert not engines & loaded, sorted(engines & loaded)
