"""A family's own names (issue #32 item 3): its parameter and control-point names are what
keyword arguments, repr, derive's messages and records formulas use."""

from __future__ import annotations

import importlib
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest

import lambda_bezier as lb
from lambda_bezier import _derive_runner

ROOT = Path(__file__).resolve().parent.parent
pytestmark = pytest.mark.skipif(
    not (ROOT / "derive" / "families" / "engine.py").is_file(), reason="needs the source checkout"
)

# Bernstein plus a shape term that sums to zero over i and vanishes at both ends: the
# parameter is `mu` and the records write the control points V.
MU_FAMILY = """
[family]
name = "mu_tilt"
title = "Bernstein plus mu times a zero-sum shape term"
parameter = "mu"
points = "V"
range = "[-1/2, 1/2]"
degrees = "3..8"
bernstein_at = "0"
degree_offset = 0
basis = "{basis}"
""".format(
    basis="binomial(n, i)*(1 - t)**(n - i)*t**i"
    " + mu*t*(1 - t)**(n - 1)*(binomial(0, i - 1) - binomial(0, i - 2))"
)

PTS = [(0, 0), (1, 2), (3, 2), (4, 0)]


def _derive(name: str):
    return importlib.import_module(f"{_derive_runner.load_derive(ROOT).__name__}.{name}")


@pytest.fixture(scope="module")
def mu_file(tmp_path_factory) -> Path:
    directory = tmp_path_factory.mktemp("mu")
    path = directory / "mu_tilt.toml"
    path.write_text(MU_FAMILY)
    definition, document = _derive("families.definition"), _derive("emit.document")
    defn = definition.read_definition(path)
    (directory / "mu_tilt.derived.json").write_text(document.render(defn))
    return path


def _basis(n: int, mu: float, t: float) -> np.ndarray:
    """The definition's formula, evaluated directly."""
    from math import comb

    b = np.array([comb(n, i) * (1 - t) ** (n - i) * t**i for i in range(n + 1)])
    b[1] += mu * t * (1 - t) ** (n - 1)
    b[2] -= mu * t * (1 - t) ** (n - 1)
    return b


def test_keyword_params_and_repr_use_the_family_name(mu_file):
    fam = lb.load_family(mu_file)
    assert repr(fam) == "Family('mu_tilt', degrees 3..8, mu in [-1/2, 1/2])"
    by_name = fam.curve(PTS, mu=Fraction(1, 4))
    assert repr(by_name) == "MuTiltCurve(degree=3, dimension=2, mu=1/4)"
    same = [
        fam.curve(PTS, params={"mu": Fraction(1, 4)}),
        fam.curve(PTS, lam=Fraction(1, 4)),  # one parameter: lam= keeps working
        fam.curve(PTS, Fraction(1, 4)),
    ]
    for c in same:
        assert c.control_points() == by_name.control_points() and c.lam == by_name.lam
    want = np.asarray(PTS, float).T @ _basis(3, 0.25, 0.3)
    np.testing.assert_allclose(by_name.evaluate(0.3), want, rtol=1e-14)
    bez = by_name.to_bezier()
    back = fam.from_bezier(bez, mu=Fraction(1, 4))
    assert back.control_points() == by_name.control_points()


@pytest.mark.parametrize(
    ("kwargs", "needle"),
    [
        ({"sigma": 1}, "'sigma' is not a parameter of 'mu_tilt' (its parameters: mu"),
        ({}, "needs its shape parameter mu"),
        ({"mu": 0, "lam": 0}, "mu is given twice"),
        ({"params": {"nu": 0}}, "params: 'nu' is not a parameter"),
        ({"params": [0]}, "params must be a dict"),
    ],
)
def test_wrong_names_are_type_errors_naming_them(mu_file, kwargs, needle):
    fam = lb.load_family(mu_file)
    with pytest.raises(TypeError) as info:
        fam.curve(PTS, **kwargs)
    assert needle in str(info.value)


def test_range_and_join_messages_and_keywords(mu_file):
    fam = lb.load_family(mu_file)
    with pytest.raises(ValueError, match=r"^mu = 1 is outside the mu_tilt range \[-1/2, 1/2\]"):
        fam.curve(PTS, mu=1)
    c = fam.curve(PTS, mu=Fraction(1, 4))
    a = lb.join(c, "C2", 4, mu=Fraction(-1, 3), rest=[(9, 1), (10, 0)])
    b = lb.join(c, "C2", 4, lam=Fraction(-1, 3), rest=[(9, 1), (10, 0)])
    assert a.control_points() == b.control_points() and "mu=-1/3" in repr(a)
    # the join is C2: compare derivatives at the joint
    for k in (0, 1, 2):
        np.testing.assert_allclose(c.derivative(1.0, k), a.derivative(0.0, k), atol=1e-9)
    with pytest.raises(TypeError, match="family's parameter is mu"):
        lb.join(c, "C1", 4, sigma=0, rest=[(9, 1), (10, 0), (11, 1)])
    with pytest.raises(TypeError, match="given twice"):
        lb.join(c, "C1", 4, lam=0, mu=0, rest=[(9, 1), (10, 0), (11, 1)])


def test_optimal_parameters_by_name(mu_file):
    fam = lb.load_family(mu_file)
    pts = [(0, 0), (1, 3), (2, -1), (4, 0)]
    r = lb.optimal_parameters(pts, 2, family=fam)
    one = lb.optimal_lambda(pts, 2, family=fam, clamp=True)
    assert r["mu"] == one.lam and set(r.values) == {"mu"}
    with pytest.raises(KeyError, match="its parameters: mu"):
        r["lam"]
    # the minimum over the box, checked by sampling E_2 on a grid of the box
    grid = [Fraction(k, 40) - Fraction(1, 2) for k in range(41)]
    energies = [fam.curve(pts, mu=m).energy(2) for m in grid]
    assert r.energy <= min(energies)
    assert (r.boundary == "") == r.free_inside


def test_derive_messages_use_the_family_name():
    definition, engine = _derive("families.definition"), _derive("families.engine")
    table = {
        "name": "mu_broken",
        "parameter": "mu",
        "range": "[0, 1]",
        "degrees": "3..5",
        "degree_offset": 1,
        "basis": "binomial(n, i)*(1 - t)**(n - i)*t**i*(1 + mu*t)",
    }
    defn = definition.definition_from_table(table)
    with pytest.raises(definition.DefinitionError) as info:
        engine.check(defn)
    assert "mu*t + 1" in str(info.value) and "lam" not in str(info.value)
    bad = dict(table, basis="binomial(n, i)*(1 - t)**(n - i)*t**i*(lam + 1 - lam)")
    with pytest.raises(definition.DefinitionError) as info:
        definition.definition_from_table(bad)
    assert "unknown name 'lam'" in str(info.value) and "and mu" in str(info.value)
    with pytest.raises(definition.DefinitionError, match="key points"):
        definition.definition_from_table(dict(table, points="Q"))
    with pytest.raises(definition.DefinitionError, match="taken by the formula language"):
        definition.definition_from_table(dict(table, parameter="P"))


RECORDS = """
schema_version = 2
source = "test"
family = "mu_tilt"

[[record]]
id = "mu.ends"
claim = "endpoint_curve"
equations = [
  {{ lhs = "p(0)", rhs = "{p0}" }},
  {{ lhs = "Subs(Derivative(p(t), t), t, 0)", rhs = "n*(V(1) - V(0)) + mu*(V(1) - V(2))" }},
]
"""


def _verify(paths):
    records = _derive("verify.records").load_paths(paths)
    return _derive("verify.report").verify(records, jobs=1)


def test_records_use_the_family_names(mu_file, tmp_path):
    path = tmp_path / "recs.toml"
    path.write_text(RECORDS.format(p0="V(0)"))
    report = _verify([mu_file, path])
    assert [r.verdict for r in report.results] == ["match"], report.results
    # a misprint: the mismatch speaks of mu, never of lam
    path.write_text(RECORDS.format(p0="V(0) + mu*V(1)"))
    (res,) = _verify([mu_file, path]).results
    assert res.verdict == "mismatch"
    text = " ".join(res.outcome.diffs)
    assert "mu" in text and "lam" not in text and "λ" not in text, text
    # another control-point name: refused at load, naming point_function
    path.write_text(RECORDS.format(p0="P(0)"))
    records = _derive("verify.records")
    with pytest.raises(records.RecordsError, match="point_function"):
        records.load_paths([mu_file, path])
    # an unknown parameter name says what the family's is
    path.write_text(RECORDS.format(p0="V(0) + 0*nu"))
    with pytest.raises(records.RecordsError, match="shape parameter is mu"):
        records.load_paths([mu_file, path])


def test_old_documents_load_or_name_the_command(tmp_path):
    """Format 2 (one parameter, the same layout) still loads; another format is refused with
    the command that re-derives it."""
    import json

    src = ROOT / "src" / "lambda_bezier" / "examples"
    (tmp_path / "nouri_saeidian.toml").write_text((src / "nouri_saeidian.toml").read_text())
    doc = json.loads((src / "nouri_saeidian.derived.json").read_text())
    assert doc["format"] == 3
    for fmt, ok in ((2, True), (1, False)):
        (tmp_path / "nouri_saeidian.derived.json").write_text(json.dumps(dict(doc, format=fmt)))
        if ok:
            fam = lb.load_family(tmp_path / "nouri_saeidian.toml")
            assert fam.curve(PTS, sigma=Fraction(1, 2)).evaluate(0.5).tolist() == [2.0, 0.75]
        else:
            with pytest.raises(lb.family.FamilyFileError, match="run `lambda-bezier derive"):
                lb.load_family(tmp_path / "nouri_saeidian.toml")
