"""A family in two shape parameters (lambda_bezier/examples/two_shape_cubic.toml), checked
against its definition by independent numerics: direct evaluation of the formulas, finite
differences, mpmath quadrature, and a grid over the parameter box."""

from __future__ import annotations

import importlib
import itertools
import json
from fractions import Fraction
from pathlib import Path

import mpmath
import numpy as np
import pytest

import lambda_bezier as lb
from lambda_bezier import _derive_runner

ROOT = Path(__file__).resolve().parent.parent
FILE = ROOT / "src" / "lambda_bezier" / "examples" / "two_shape_cubic.toml"
pytestmark = pytest.mark.skipif(
    not (ROOT / "derive" / "families" / "engine.py").is_file(), reason="needs the source checkout"
)
PTS = [(0, 0), (1, 2), (3, 2), (4, 0)]


def _derive(name: str):
    return importlib.import_module(f"{_derive_runner.load_derive(ROOT).__name__}.{name}")


def basis(t, lam, mu):
    """The four functions as the file's comment states them (Han, Ma, Huang's form)."""
    return [
        (1 - lam * t) * (1 - t) ** 3,
        t * (1 - t) ** 2 * (3 + lam * (1 - t)),
        t**2 * (1 - t) * (3 + mu * t),
        (1 - mu + mu * t) * t**3,
    ]


def _mp(x):
    x = Fraction(x)
    return mpmath.mpf(x.numerator) / x.denominator


def point(t, lam, mu, pts=PTS):
    b = basis(t, lam, mu)
    return [sum(bi * p[d] for bi, p in zip(b, pts, strict=True)) for d in range(len(pts[0]))]


@pytest.fixture(scope="module")
def fam():
    return lb.load_family(FILE)


def test_committed_derivation_is_current():
    defn = _derive("families.definition").read_definition(FILE)
    assert _derive("emit.document").render(defn) == FILE.with_name(
        "two_shape_cubic.derived.json"
    ).read_text(encoding="utf-8")


def test_document_decisions():
    doc = json.loads(FILE.with_name("two_shape_cubic.derived.json").read_text())
    assert doc["format"] == 3
    assert [q["name"] for q in doc["parameters"]] == ["lam", "mu"]
    assert "partition of unity, every degree" in doc["checked"]
    assert doc["symmetry"]["swap"] == ["mu", "lam"]  # b_i(t; lam, mu) = b_{3-i}(1 - t; mu, lam)
    assert sorted(doc["power"]["3"]) == ["0,0", "0,1", "1,0"]  # affine: no lam*mu term


@pytest.mark.parametrize(("lam", "mu"), [(0, 0), (Fraction(1, 2), -1), (-3, 1), (1, -3)])
def test_curve_against_the_formula(fam, lam, mu):
    c = fam.curve(PTS, lam=lam, mu=mu)
    ts = np.linspace(0, 1, 13)
    want = np.array([point(float(t), float(lam), float(mu)) for t in ts])
    np.testing.assert_allclose(c.evaluate(ts), want, atol=1e-13)
    assert "lam=" in repr(c) and "mu=" in repr(c)
    # the same through params= and positional-free keywords
    same = fam.curve(PTS, params={"lam": lam, "mu": mu})
    np.testing.assert_array_equal(same.evaluate(ts), c.evaluate(ts))
    # end derivatives 1..3 by finite differences of the formula (mpmath, 30 digits)
    mpmath.mp.dps = 30
    for end in (0, 1):
        for r in (1, 2, 3):
            got = c.derivative(float(end), r)
            for d in range(2):
                f = lambda x, d=d: point(x, _mp(lam), _mp(mu))[d]  # noqa: E731
                want_d = mpmath.diff(f, end, r)
                assert abs(float(want_d) - got[d]) < 1e-9, (end, r, d)


def test_energy_by_quadrature_and_optimum_over_the_box(fam):
    mpmath.mp.dps = 30
    pts = [(0, 0), (1, 5), (3, -4), (4, 0)]
    for lam, mu in [(Fraction(1, 3), Fraction(-2)), (Fraction(-3), Fraction(1))]:
        c = fam.curve(pts, lam=lam, mu=mu)

        def integrand(x, lam=lam, mu=mu):
            f = lambda y, d: point(y, _mp(lam), _mp(mu), pts)[d]  # noqa: E731
            return sum(mpmath.diff(lambda y, d=d: f(y, d), x, 2) ** 2 for d in range(2))

        want = mpmath.quad(integrand, [0, 1])
        assert abs(float(c.energy(2)) - float(want)) < 1e-9 * float(want)
    r = lb.optimal_parameters(pts, 2, family=fam)
    grid = [Fraction(k, 8) - 3 for k in range(33)]
    sampled = min(fam.curve(pts, lam=a, mu=b).energy(2) for a, b in itertools.product(grid, grid))
    assert r.energy <= sampled
    assert fam.curve(pts, lam=r["lam"], mu=r["mu"]).energy(2) == r.energy
    # outside the box: a polygon whose free optimum is far out, the minimum on a face
    far = [(0, 0), (0, 30), (4, 30), (4, 0)]
    r = lb.optimal_parameters(far, 1, family=fam)
    if not r.free_inside:
        assert r.boundary and any(r[x] in (-3, 1) for x in ("lam", "mu"))
    sampled = min(fam.curve(far, lam=a, mu=b).energy(1) for a, b in itertools.product(grid, grid))
    assert r.energy <= sampled
    # exact control points are checked as floats are: one width, a degree the family has
    # (a ragged polygon once gave an optimum computed on its first coordinates)
    with pytest.raises(ValueError, match="same number of coordinates"):
        lb.optimal_parameters([(0, 0), (1, 2, 3), (3, 2), (4, 0)], 2, family=fam)
    with pytest.raises(ValueError, match="at least 4 control points"):
        lb.optimal_parameters([(0, 0), (1, 2)], 2, family=fam)


def test_several_parameter_errors(fam):
    with pytest.raises(TypeError, match="needs its shape parameter mu"):
        fam.curve(PTS, lam=0)
    with pytest.raises(TypeError, match="has 2 parameters: name them"):
        fam.curve(PTS, 0)
    with pytest.raises(ValueError, match=r"^mu = 2 is outside"):
        fam.curve(PTS, lam=0, mu=2)


@pytest.mark.parametrize(
    ("change", "needle"),
    [
        ({"range": "[-3, 1]"}, "`range` is a table"),
        ({"range": {"lam": "[-3, 1]"}}, "no interval for the parameter 'mu'"),
        ({"range": {"lam": "[-3, 1]", "mu": "[-3, 1]", "nu": "[0, 1]"}}, "'nu' is not a parameter"),
        ({"parameter": "lam"}, "one of the two"),
        ({"parameters": ["lam", "t"]}, "'t' is taken"),
        ({"degrees": "3..5"}, "one order"),
        ({"functions": ["1 - t", "t"]}, "has 4 functions, got 2"),
        ({"domain": "[0, pi/2]"}, "key domain"),
        ({"bernstein_at": {"lam": "0"}}, "mu missing"),
        ({"bernstein_at": {"lam": "0", "mu": "1"}}, "bernstein_at: at lam = 0, mu = 1"),
        (
            {
                "functions": [
                    "(1 - lam*t)*(1 - t)**3",
                    "t*(1-t)**2*(3 + lam)",
                    "t**2*(1-t)*(3 + mu*t)",
                    "(1 - mu + mu*t)*t**3",
                ]
            },
            "no partition of unity",
        ),
        ({"functions": ["(1 - nu*t)*(1 - t)**3", "0", "0", "0"]}, "unknown name 'nu'"),
    ],
)
def test_ill_defined_several_parameter_families(change, needle):
    import tomllib

    definition, engine = _derive("families.definition"), _derive("families.engine")
    table = tomllib.loads(FILE.read_text())["family"]
    table.update(change)
    with pytest.raises(definition.DefinitionError) as info:
        engine.check(definition.definition_from_table(table, "fam.toml"))
    assert needle in str(info.value), str(info.value)


@pytest.mark.parametrize("cont", ["C1", "C2", "G1", "G2"])
def test_joins_into_out_of_and_within_the_family(fam, cont):
    """The runtime's per-degree solve, checked on the curves' own derivatives at the joint
    (exact: the end derivatives are compared as exact Bézier differences)."""
    alpha = Fraction(3, 2) if cont[0] == "G" else Fraction(1)
    d = Fraction(1, 5) if cont == "G2" else Fraction(0)
    order = 1 if cont[1] == "1" else 2
    first = fam.curve(PTS, lam=Fraction(1, 2), mu=-1)
    cases = [
        (first, {"lam": Fraction(-1, 3), "mu": Fraction(1, 4)}, None, 3),
        (first, {"lam": Fraction(1, 3)}, "bernstein_like", 4),
        (lb.SameDegreeCurve([(0, 0), (1, 3), (2, 1), (4, 0)], lam=Fraction(1, 2)), {}, fam, 3),
    ]
    for c, kwargs, family, m in cases:
        if family is fam:
            kwargs = {"lam": Fraction(-1), "mu": Fraction(1, 2)}
        rest = [(9 + j, (-1) ** j) for j in range(m - order)]
        nxt = lb.join(c, cont, m, alpha=alpha, d=d, rest=rest, family=family, **kwargs)
        ends = [np.array(c.derivative(1.0, r)) for r in range(3)]
        starts = [np.array(nxt.derivative(0.0, r)) for r in range(3)]
        np.testing.assert_allclose(starts[0], ends[0], atol=1e-12)
        np.testing.assert_allclose(float(alpha) * starts[1], ends[1], atol=1e-9)
        if order == 2:
            want = float(alpha) ** 2 * starts[2] + float(d) * starts[1]
            np.testing.assert_allclose(want, ends[2], atol=1e-9)


def test_evaluate_many_matches_the_curves(fam):
    rng = np.random.default_rng(7)
    pts = rng.normal(size=(6, 4, 3))
    ts = np.linspace(0, 1, 9)
    got = lb.evaluate_many(pts, ts, fam, params={"lam": 0.5, "mu": -1.0}, k=1)
    for i in range(6):
        want = fam.curve(pts[i], lam=0.5, mu=-1.0).derivative(ts)
        np.testing.assert_allclose(got[i], want, atol=1e-12)
    with pytest.raises(TypeError, match="needs its shape parameter mu"):
        lb.evaluate_many(pts, ts, fam, params={"lam": 0.5})
    # the parameters as keywords in the family's own names, as fam.curve takes them
    keywords = lb.evaluate_many(pts, ts, fam, lam=0.5, mu=-1.0, k=1)
    assert np.array_equal(keywords, got)
    assert np.array_equal(lb.evaluate_many(pts, ts, fam, params={"lam": 0.5}, mu=-1.0, k=1), got)
    with pytest.raises(TypeError, match="mu (is )?given twice"):
        lb.evaluate_many(pts, ts, fam, params={"lam": 0.5, "mu": 1.0}, mu=-1.0)
    with pytest.raises(TypeError, match="nu"):
        lb.evaluate_many(pts, ts, fam, lam=0.5, mu=-1.0, nu=2.0)
    with pytest.raises(TypeError, match="mu: a family of one parameter takes it as lam="):
        lb.evaluate_many(pts, ts, "same_degree", mu=0.5)


# --------------------------------------------------------------------------- one per leg

LEGS = ROOT / "tests" / "data" / "families" / "per_leg_cubic.toml"


def leg_basis(t, s0, s1, s2):
    """The file's construction: b_i -= s_i psi_i, b_{i+1} += s_i psi_i."""
    b = [(1 - t) ** 3, 3 * t * (1 - t) ** 2, 3 * t**2 * (1 - t), t**3]
    for i, s in enumerate((s0, s1, s2)):
        psi = t ** (i + 1) * (1 - t) ** (3 - i)
        b[i] -= s * psi
        b[i + 1] += s * psi
    return b


def test_per_leg_family_derived_and_evaluated():
    doc_path = LEGS.with_name("per_leg_cubic.derived.json")
    defn = _derive("families.definition").read_definition(LEGS)
    assert _derive("emit.document").render(defn) == doc_path.read_text(encoding="utf-8")
    doc = json.loads(doc_path.read_text())
    assert doc["symmetry"]["swap"] == ["-s2", "-s1", "-s0"]
    fam = lb.load_family(LEGS)
    two = lb.load_family(FILE)
    s = (Fraction(1, 2), Fraction(-1, 4), Fraction(1, 3))
    c = fam.curve(PTS, s0=s[0], s1=s[1], s2=s[2])
    ts = np.linspace(0, 1, 11)
    want = np.array(
        [
            [
                sum(b * p[d] for b, p in zip(leg_basis(t, *map(float, s)), PTS, strict=True))
                for d in (0, 1)
            ]
            for t in ts
        ]
    )
    np.testing.assert_allclose(c.evaluate(ts), want, atol=1e-13)
    # at s1 = 0, s2 = -mu: the two-parameter cubic with lam = s0, exactly
    a = fam.curve(PTS, s0=Fraction(1, 2), s1=0, s2=Fraction(1, 3))
    b = two.curve(PTS, lam=Fraction(1, 2), mu=Fraction(-1, 3))
    assert a.to_bezier().control_points() == b.to_bezier().control_points()


def test_per_leg_optimum_over_the_box():
    fam = lb.load_family(LEGS)
    pts = [(0, 0), (1, 5), (3, -4), (4, 0)]
    r = lb.optimal_parameters(pts, 2, family=fam)
    assert not r.free_inside and "s0 = -1 (lower end)" in r.boundary
    grid = [Fraction(k, 4) - 1 for k in range(9)]
    sampled = min(
        fam.curve(pts, s0=a, s1=b, s2=c).energy(2)
        for a, b, c in itertools.product(grid, grid, grid)
    )
    assert r.energy <= sampled
    assert fam.curve(pts, params=dict(r.values)).energy(2) == r.energy


def test_verify_takes_the_family_and_refuses_one_parameter_kinds_clearly(tmp_path):
    """verify reads a family in several parameters (its records: the several_* kinds of
    tests/test_several_verify.py); a one-parameter claim kind about it is refused by name."""
    records = _derive("verify.records")
    assert records.load_paths([FILE]) == []  # the family file alone: defined, no records
    bad = tmp_path / "r.toml"
    bad.write_text(
        'schema_version = 2\nfamily = "two_shape_cubic"\n[[record]]\nid = "x"\n'
        'claim = "endpoint_d1"\nequations = [{ lhs = "p(0)", rhs = "P(0)" }]\n'
    )
    with pytest.raises(records.RecordsError, match="'two_shape_cubic' has several"):
        records.load_paths([FILE, bad])


def test_one_parameter_entry_points_refuse_clearly(fam):
    for call in (
        lambda: lb.optimal_lambda(PTS, 2, family=fam),
        lambda: lb.singular_parameters(fam, 3),
    ):
        with pytest.raises(TypeError, match="several parameters"):
            call()


def test_nonnegativity_over_the_box_exact_or_a_counterexample():
    import tomllib

    definition, engine = _derive("families.definition"), _derive("families.engine")
    table = tomllib.loads(FILE.read_text())["family"]
    assert engine.nonnegative_over_box(definition.definition_from_table(table)) == {
        "nonnegative": True
    }
    # the claim on a grid of the box, by the formulas
    grid = np.linspace(-3, 1, 9)
    ts = np.linspace(0, 1, 101)
    assert min(min(basis(ts, a, b)[i].min() for i in range(4)) for a in grid for b in grid) >= 0
    wide = dict(table, range={"lam": "[-4, 1]", "mu": "[-3, 1]"})
    got = engine.nonnegative_over_box(definition.definition_from_table(wide))
    assert got["nonnegative"] is False
    ce = got["counterexample"]
    value = basis(Fraction(ce["t"]), Fraction(ce["lam"]), Fraction(ce["mu"]))[ce["i"]]
    assert value < 0 and value == Fraction(ce["value"])
