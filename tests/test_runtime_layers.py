"""The runtime's layers (issue #27): no import circle in lambda_bezier, hazmat self-contained,
and import-linter's contracts (pyproject.toml) kept. Imports inside functions count;
imports under `if TYPE_CHECKING:` (annotations only) do not."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import grimp
from import_graph import describe, edges_of, strongly_connected

ROOT = Path(__file__).resolve().parents[1]
# generated/ and derive/ are installed inside the package (lambda_bezier._generated, ._derive
# in a non-editable install): they are not the runtime, and derive has contracts of its own
NOT_RUNTIME = ("lambda_bezier._generated", "lambda_bezier._derive")


def _graph(package: str) -> grimp.ImportGraph:
    return grimp.build_graph(package, exclude_type_checking_imports=True, cache_dir=None)


def test_no_import_cycle_in_the_runtime():
    graph = _graph("lambda_bezier")
    found = strongly_connected(edges_of(graph, NOT_RUNTIME))
    assert not found, "import cycles in lambda_bezier:\n" + "\n\n".join(
        describe(graph, c) for c in found
    )


def test_a_cycle_through_a_function_level_import_is_found(tmp_path, monkeypatch):
    pkg = tmp_path / "cyclepkg"
    pkg.mkdir()
    (pkg / "__init__.py").write_text("")
    (pkg / "low.py").write_text(
        textwrap.dedent(
            """
            def helper():
                from . import high  # the upward import a lazy dispatch hides
                return high
            """
        )
    )
    (pkg / "high.py").write_text("from . import low, typing_only\n")
    # an annotation-only import back up closes no circle
    (pkg / "typing_only.py").write_text(
        "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from . import high\n"
    )
    monkeypatch.syspath_prepend(str(tmp_path))
    graph = _graph("cyclepkg")
    assert strongly_connected(edges_of(graph)) == [["cyclepkg.high", "cyclepkg.low"]]
    assert "cyclepkg.low -> cyclepkg.high (line 3" in describe(
        graph, ["cyclepkg.high", "cyclepkg.low"]
    )


def test_hazmat_imports_nothing_else_from_lambda_bezier():
    graph = _graph("lambda_bezier")
    hazmat = "lambda_bezier.hazmat"
    modules = {m for m in graph.modules if m == hazmat or m.startswith(hazmat + ".")}
    assert {f"{hazmat}.{name}" for name in ("kernels", "arclength", "intersect")} <= modules
    outside = sorted(
        f"{m} -> {i}"
        for m in modules
        for i in graph.find_modules_directly_imported_by(m)
        if i.startswith("lambda_bezier") and i not in modules
    )
    assert not outside, outside


def test_hazmat_all_names_its_modules():
    import lambda_bezier.hazmat as hazmat

    here = Path(hazmat.__file__).parent
    assert sorted(hazmat.__all__) == sorted(p.stem for p in here.glob("[!_]*.py"))


def test_import_linter_contracts_are_kept():
    env = dict(os.environ)
    # the source tree, whether the package is installed editable or not
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(ROOT / "src"), env.get("PYTHONPATH")]))
    # lint-imports, run by this interpreter (the console script may be another environment's)
    code = "from importlinter.cli import lint_imports_command; lint_imports_command()"
    out = subprocess.run(
        [sys.executable, "-c", code, "--no-cache"],
        cwd=ROOT,
        env=env,
        capture_output=True,
        text=True,
    )
    assert out.returncode == 0, out.stdout + out.stderr
    assert "0 broken" in out.stdout


def test_pickles_made_before_the_layers_load():
    """Pickles name a class by module and name: the classes that moved (Curve, BezierCurve to
    _curve_base, IsolatedRoot to _singular) still pickle and unpickle under their documented
    modules."""
    import base64
    import json
    import pickle
    from fractions import Fraction as F

    import numpy as np

    import lambda_bezier as lb
    from lambda_bezier.geometry import ClosestPoint

    data = json.loads((ROOT / "tests" / "data" / "old_pickles.json").read_text())
    old = {k: pickle.loads(base64.b64decode(v)) for k, v in data["pickles"].items()}
    a = lb.SameDegreeCurve([(0, 0), (1, 2), (3, 2), (4, 0)], lam=F(1, 2))
    want = {
        "bezier_exact": lb.BezierCurve([(0, 0), (1, 2), (3, 2), (4, 0)]),
        "bezier_float": lb.BezierCurve([(0.0, 0.5), (1.5, 2.0), (3.0, -1.0)]),
        "same_degree": a,
        "bernstein_like": lb.BernsteinLikeCurve([(0, 0), (1, 2), (3, 2), (4, 0)], lam=F(-1, 3)),
    }
    for name, curve in want.items():
        got = old[name]
        assert type(got) is type(curve), name
        assert got.control_points() == curve.control_points() and got.lam == curve.lam, name
        assert np.array_equal(got.evaluate([0.25, 0.5]), curve.evaluate([0.25, 0.5])), name
        assert pickle.loads(pickle.dumps(curve)).control_points() == curve.control_points()
    assert old["isolated_root"] == lb.IsolatedRoot(F(1), F(2), (-2, 0, 1))
    assert abs(float(old["isolated_root"]) - 2**0.5) < 1e-15
    point = old["closest_point"]
    assert type(point) is ClosestPoint and (point.t, point.distance) == (0.5, 1.5)
    composite = old["composite"]
    assert type(composite) is lb.CompositeCurve and len(composite.segments) == 2
    assert composite.segments[1].control_points()[-1] == (10, 3)
    # new pickles name the documented modules, not the private ones the classes live in
    assert b"lambda_bezier.curves" in pickle.dumps(want["bezier_exact"])
    assert b"_curve_base" not in pickle.dumps(want["bezier_exact"])
    assert b"lambda_bezier.properties" in pickle.dumps(lb.IsolatedRoot(F(1), F(2), (-2, 0, 1)))
