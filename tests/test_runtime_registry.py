"""The runtime names no built-in shape-parameter family (issue 19): it takes them from the list
generated/ carries, so a family added to generated/ works everywhere with no edit of the runtime.

Two checks: the shared runtime modules hold no family name in their code (docstrings and
comments may name them, and so may the documented defaults of public functions); and a
family that exists only in a copy of generated/ (a copy of bernstein_like's module under
another name, with the entries derive would emit for it) is a full member of the runtime in
an installed copy of the package.
"""

from __future__ import annotations

import ast
import inspect
import os
import re
import shutil
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

import lambda_bezier as lb
from lambda_bezier import curves, energy
from lambda_bezier._lazy import builtin_families

ROOT = Path(__file__).resolve().parents[1]
SRC = ROOT / "src" / "lambda_bezier"
# modules that may name the built-in families: the public export list, and the one module
# holding the classes of families with code of their own
FAMILY_SPECIFIC = {"__init__.py", "builtin_curves.py", "builtin_surfaces.py"}
FAMILY_NAME = re.compile(r"same_?degree|bernstein_?like", re.IGNORECASE)


def family_names_in_code(source: str) -> list[tuple[int, str]]:
    """(line, text) of every identifier or string of the code that names a built-in family;
    not counted: docstrings and other bare string statements, comments (not in the AST), and
    the defaults of public functions (documented API, e.g. optimal_lambda's family)."""
    tree = ast.parse(source)
    documentation: set[int] = set()
    for node in ast.walk(tree):
        if (
            isinstance(node, ast.Expr)
            and isinstance(node.value, ast.Constant)
            and isinstance(node.value.value, str)
        ):
            documentation.add(id(node.value))
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef) and not node.name.startswith(
            "_"
        ):
            for default in [*node.args.defaults, *node.args.kw_defaults]:
                if isinstance(default, ast.Constant):
                    documentation.add(id(default))
    hits = []
    for node in ast.walk(tree):
        if id(node) in documentation:
            continue
        texts: list[str | None] = []
        if isinstance(node, ast.Constant) and isinstance(node.value, str):
            texts = [node.value]
        elif isinstance(node, ast.Name):
            texts = [node.id]
        elif isinstance(node, ast.Attribute):
            texts = [node.attr]
        elif isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef):
            texts = [node.name]
        elif isinstance(node, ast.arg | ast.keyword):
            texts = [node.arg]
        elif isinstance(node, ast.alias):
            texts = [node.name, node.asname]
        elif isinstance(node, ast.ImportFrom):
            texts = [node.module]
        hits += [(node.lineno, t) for t in texts if t and FAMILY_NAME.search(t)]
    return sorted(hits)


@pytest.mark.parametrize(
    ("code", "named"),
    [
        ('x = "same_degree"', True),
        ('if fam == "bernstein_like":\n    pass', True),
        ('msg = f"{n} same_degree"', True),
        ("class SameDegreeThing:\n    pass", True),
        ("from .curves import BernsteinLikeCurve", True),
        ("from . import same_degree", True),
        ('def _f(family="same_degree"):\n    pass', True),  # a private default is code
        ("def f(bernstein_like=1):\n    pass", True),
        ('"""A docstring naming same_degree."""\n# and a comment: bernstein_like\nx = 1', False),
        ('def f(family="same_degree"):\n    """Doc: bernstein_like."""', False),
        ('x = "bezier"', False),  # the reference basis is not a shape-parameter family
    ],
)
def test_the_checker_sees_family_names_in_code_only(code, named):
    assert bool(family_names_in_code(code)) == named


def test_shared_runtime_modules_name_no_family():
    shared = sorted(p for p in SRC.glob("*.py") if p.name not in FAMILY_SPECIFIC)
    assert len(shared) > 20  # the glob found the runtime
    found = {
        p.name: hits
        for p in shared
        if (hits := family_names_in_code(p.read_text(encoding="utf-8")))
    }
    assert not found, f"family names in shared runtime code: {found}"


def test_families_come_from_generated():
    listed = builtin_families()
    assert list(curves.FAMILIES) == [lb.BezierCurve.family, *listed]
    for name, class_name in listed.items():
        cls = curves.FAMILIES[name]
        assert cls.__name__ == class_name and cls.family == name and cls._has_lambda
        assert getattr(curves, class_name) is cls is getattr(lb, class_name)
        assert name == cls._data.FAMILY  # the generated module is the family's
    assert not lb.BezierCurve._has_lambda  # the reference: the one class without λ
    assert tuple(listed) == energy.LAMBDA_FAMILIES
    assert lb.FAMILIES is curves.FAMILIES
    with pytest.raises(AttributeError):
        lb.NoSuchCurve  # noqa: B018
    with pytest.raises(AttributeError):
        curves.NoSuchCurve  # noqa: B018


def test_cli_default_family_is_the_api_default():
    from lambda_bezier.cli import _ShapeFamilies

    default = inspect.signature(lb.optimal_lambda).parameters["family"].default
    assert _ShapeFamilies().names()[0] == default
    assert list(_ShapeFamilies()) == list(energy.LAMBDA_FAMILIES)


# --------------------------------------------------------------------------- a new family

# Appended to the copies of generated/'s modules: the entries derive would emit for two more
# families, both copies of bernstein_like. mirror_like gets closed-form joins as the built-in
# families do; plain_like gets none (its joins are solved per degree).
_EXTRA = {
    "__init__.py": """
        FAMILIES['mirror_like'] = 'MirrorLikeCurve'
        FAMILIES['plain_like'] = 'PlainLikeCurve'
    """,
    "energy.py": """
        ENERGY['mirror_like'] = ENERGY['plain_like'] = ENERGY['bernstein_like']
    """,
    "properties.py": """
        SINGULAR['mirror_like'] = SINGULAR['plain_like'] = SINGULAR['bernstein_like']
    """,
    "joins.py": """
        import itertools as _it

        for (_a, _b, _c), _v in list(JOINS.items()):
            for _x, _y in _it.product(*(
                (f, 'mirror_like') if f == 'bernstein_like' else (f,) for f in (_a, _b)
            )):
                JOINS.setdefault((_x, _y, _c), _v)
        PIVOTS['mirror_like'] = PIVOTS['bernstein_like']
        PIVOT_TEXT['mirror_like'] = PIVOT_TEXT['bernstein_like']
        FAMILIES = (*FAMILIES, 'mirror_like')
    """,
}

_CHECKS = r"""
import io
import pickle
import sys
from contextlib import redirect_stdout
from fractions import Fraction as F

sys.meta_path[:] = [f for f in sys.meta_path if "editable" not in repr(f).lower()]

import numpy as np

import lambda_bezier as lb
from lambda_bezier import _join_engine, curves, energy, export
from lambda_bezier.cli import main

SITE = sys.argv[1]
assert lb.__file__.startswith(SITE), lb.__file__
new = ("mirror_like", "plain_like")
assert list(lb.FAMILIES) == ["bezier", "same_degree", "bernstein_like", *new], list(lb.FAMILIES)
assert energy.LAMBDA_FAMILIES == ("same_degree", "bernstein_like", *new)
Mirror, Plain, BL = lb.MirrorLikeCurve, curves.PlainLikeCurve, lb.BernsteinLikeCurve
assert lb.FAMILIES["mirror_like"] is Mirror and lb.FAMILIES["plain_like"] is Plain
assert issubclass(Mirror, lb.Curve) and Mirror.family == "mirror_like"
assert Mirror._data.FAMILY == "mirror_like" and Mirror._data.__file__.startswith(SITE)

pts = [(0, 0), (1, 2), (3, 2), (4, 0), (6, 1)]
lam = F(1, 3)
ref = BL(pts, lam)
ts = np.linspace(0, 1, 11)
for cls in (Mirror, Plain):
    c = cls(pts, lam)
    assert repr(c) == f"{cls.__name__}(degree=4, dimension=2, lam=1/3)"
    assert c.to_bezier().control_points() == ref.to_bezier().control_points()
    for k in range(4):
        assert np.array_equal(c.derivative(ts, k), ref.derivative(ts, k))
    assert np.array_equal(c.basis(ts), ref.basis(ts))
    assert np.array_equal(c.curvature(ts), ref.curvature(ts))
    assert c.energy(2) == ref.energy(2) and c.polynomial_degree == 6
    back = pickle.loads(pickle.dumps(c))
    assert type(back) is cls and back.control_points() == c.control_points()
    assert cls.from_bezier(ref.to_bezier(), lam).control_points() == ref.control_points()
    loaded = export.from_json(export.to_json(c))
    assert type(loaded) is cls and loaded.control_points() == c.control_points()

    fam = cls.family
    for k in (1, 2, 3):
        assert lb.energy_matrices(4, k, fam) == lb.energy_matrices(4, k, "bernstein_like")
        got = lb.optimal_lambda(pts, k, family=fam, clamp=True)
        want = lb.optimal_lambda(pts, k, family="bernstein_like", clamp=True)
        assert (got.lam, got.energy, got.family) == (want.lam, want.energy, fam)
    batch = np.array([pts, pts[::-1]], dtype=float)
    got = lb.optimal_lambda(batch, 2, family=fam).lam
    assert np.array_equal(got, lb.optimal_lambda(batch, 2, family="bernstein_like").lam)
    many = lb.evaluate_many(batch, ts, fam, lam=[0.5, -0.25], k=1)
    want = lb.evaluate_many(batch, ts, "bernstein_like", lam=[0.5, -0.25], k=1)
    assert np.array_equal(many, want)
    for n in cls._data.DEGREES:
        assert lb.singular_parameters(fam, n) == lb.singular_parameters("bernstein_like", n)

    solved_per_degree = []
    original = _join_engine.weights
    _join_engine.weights = lambda *a, **kw: solved_per_degree.append(1) or original(*a, **kw)
    joins = [  # (into the new family, out of it, within it), each against bernstein_like's
        (ref, "C2", 4, F(1, 2), 1, 0, [(9, 1), (10, 3)], fam, "bernstein_like"),
        (c, "G2", 5, F(-1, 2), 2, 1, [(9, 1), (10, 3), (12, 0)], "same_degree", "same_degree"),
        (c, "G1", 3, F(1, 4), F(1, 2), 0, [(9, 1), (10, 3)], fam, "bernstein_like"),
        (c, "C1", 3, None, 1, 0, [(9, 1), (10, 3)], "bezier", "bezier"),
    ]
    for first, cont, m, lam2, alpha, d, rest, into, into_ref in joins:
        got = lb.join(first, cont, m, lam=lam2, alpha=alpha, d=d, rest=rest, family=into)
        first_ref = ref if first is c else first
        want = lb.join(first_ref, cont, m, lam=lam2, alpha=alpha, d=d, rest=rest, family=into_ref)
        assert type(got) is lb.FAMILIES[into] and got.control_points() == want.control_points()
    _join_engine.weights = original
    # closed forms where generated/joins.py has them (mirror_like), else the per-degree solve
    assert len(solved_per_degree) == (0 if cls is Mirror else len(joins)), solved_per_degree
    comp = lb.CompositeCurve(c).join("G2", 4, lam=F(1, 2), alpha=2, d=1, rest=[(9, 1), (10, 3)])
    assert np.array_equal(comp.evaluate(0.5), c.evaluate(0.5))
    moved = comp.with_lambda(0, F(-1, 2))  # the G2 joint re-solved, across the new family
    assert type(moved.segments[1]) is cls and moved.report()[0].kept

    out = io.StringIO()
    argv = ["optimal-lambda", "--json", "--family", fam, *[f"{x},{y}" for x, y in pts]]
    with redirect_stdout(out):
        assert main(argv) == 0
    assert f'"family": "{fam}"' in out.getvalue()

c = Mirror(pts, lam)
try:
    lb.join(c, "C2", 4, lam=lam, rest=[(9, 1)], family="mirror_like")
except ValueError as exc:  # bernstein_like's second end derivative involves P_0..P_2 only
    assert "rest must hold the other 2 point(s) (P_{3,2}..P_{4,2}), got 1" in str(exc), exc
else:
    raise AssertionError("a join with too few points was accepted")
print("ok")
"""


def test_a_family_added_to_generated_needs_no_runtime_edit(tmp_path):
    site = tmp_path / "site"
    package = site / "lambda_bezier"
    shutil.copytree(SRC, package, ignore=shutil.ignore_patterns("__pycache__"))
    gen = package / "_generated"
    shutil.copytree(ROOT / "generated", gen, ignore=shutil.ignore_patterns("__pycache__"))
    source = (gen / "bernstein_like.py").read_text(encoding="utf-8")
    assert source.count("FAMILY = 'bernstein_like'\n") == 1
    for name in ("mirror_like", "plain_like"):
        text = source.replace("FAMILY = 'bernstein_like'\n", f"FAMILY = '{name}'\n")
        (gen / f"{name}.py").write_text(text, encoding="utf-8")
    for module, extra in _EXTRA.items():
        with open(gen / module, "a", encoding="utf-8") as fh:
            fh.write("\n" + textwrap.dedent(extra))
    script = tmp_path / "checks.py"
    script.write_text(_CHECKS, encoding="utf-8")
    env = {**os.environ, "PYTHONPATH": str(site)}
    proc = subprocess.run(
        [sys.executable, str(script), str(site)],
        capture_output=True,
        text=True,
        env=env,
        timeout=300,
        cwd=tmp_path,
    )
    assert proc.returncode == 0, proc.stderr[-4000:]
    assert proc.stdout.strip().endswith("ok")
