"""Surfaces, issue 31's remaining items: G1 joins with a factor varying along the boundary,
JSON of a user family's surface, and the derived continuity conditions of a user family
against the runtime's join_surface."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

import lambda_bezier as lb

F = Fraction


def patch():
    return lb.SameDegreeSurface(
        [[(i, j, (i * j) % 3 - F(j, 2)) for j in range(4)] for i in range(4)], F(1, 2), F(1, 3)
    )


@pytest.mark.parametrize("side", ["u", "v"])
@pytest.mark.parametrize("mu", [(F(1, 2), F(1)), (F(3), F(-2)), (2, 0)])
def test_g1_with_a_linear_factor(side, mu):
    a = patch()
    big_n = a.to_bezier().degrees[1 if side == "u" else 0]
    count = big_n + 2
    if side == "u":
        rest = [[(5 + k, F(j, 2), 0) for j in range(count)] for k in range(2)]
    else:
        rest = [[(i, 5 + k, 1) for k in range(2)] for i in range(count)]
    b = lb.join_surface(a, side, "G1", 3, F(-1, 2), rest=rest, mu=mu)
    assert b.is_exact
    t = np.linspace(0, 1, 9)
    one, zero = np.ones(9), np.zeros(9)
    factor = (float(mu[0]) + float(mu[1]) * t)[:, None]
    if side == "u":
        pairs = [
            (a.evaluate(one, t), b.evaluate(zero, t)),
            (a.derivative(one, t, 1, 0), b.derivative(zero, t, 1, 0) / factor),
        ]
    else:
        pairs = [
            (a.evaluate(t, one), b.evaluate(t, zero)),
            (a.derivative(t, one, 0, 1), b.derivative(t, zero, 0, 1) / factor),
        ]
    for left, right in pairs:
        np.testing.assert_allclose(left, right, atol=1e-12)
    grid = [[a], [b]] if side == "u" else [[a, b]]
    assert [r.continuity for r in lb.CompositeSurface(grid).report()] == ["G1"]
    # the degrees along the boundary: one more than a's Bézier form there
    assert b.degrees[1 if side == "u" else 0] == big_n + 1


def test_g1_varying_factor_errors_are_named():
    a = patch()
    rest = [[(5, j, 0) for j in range(6)]] * 2
    with pytest.raises(ValueError, match="mu=\\(mu0, mu1\\)"):
        lb.join_surface(a, "u", "G1", 3, 0, rest=rest, alpha=(1, 2))
    with pytest.raises(ValueError, match="positive on \\[0, 1\\]"):
        lb.join_surface(a, "u", "G1", 3, 0, rest=rest, mu=(1, -2))
    with pytest.raises(ValueError, match="needs continuity G1"):
        lb.join_surface(a, "u", "C1", 3, 0, rest=rest, mu=(1, 1))
    with pytest.raises(ValueError, match="5 points along the boundary"):
        lb.join_surface(a, "u", "G1", 3, 0, rest=[[(5, j, 0) for j in range(4)]] * 2, mu=(1, 1))
    # a patch joined with a constant factor is not mistaken for a varying one, and a kink is
    b = lb.join_surface(a, "u", "G1", 3, 0, rest=[[(5, j, 0) for j in range(4)]] * 2, alpha=2)
    assert lb.CompositeSurface([[a], [b]]).report()[0].continuity == "G1"
    kinked = [list(row) for row in b.control_net()]
    kinked[1][0] = tuple(c + 1 for c in kinked[1][0])
    bad = lb.Surface(kinked, b.lam_u, b.lam_v, family=b.family)
    assert lb.CompositeSurface([[a], [bad]]).report()[0].continuity == "C0"


# ---------------------------------------------------------------------- JSON, own families
def own_family():
    from lambda_bezier import examples

    return lb.load_family(examples.path("nouri_saeidian.toml"))


def test_json_round_trip_of_a_user_family_surface():
    from lambda_bezier import examples
    from lambda_bezier.surface_export import surface_from_json, surface_to_json

    fam = own_family()
    net = [[(i, F(j, 3), (i * j) % 2) for j in range(4)] for i in range(5)]
    s = lb.Surface(net, F(1, 2), F(1, 4), family=(fam, "same_degree"))
    text = surface_to_json(s)
    assert '"definitions"' in text and "nouri_saeidian" in text
    back = surface_from_json(text, family=fam)
    assert back.control_net() == s.control_net() and (back.lam_u, back.lam_v) == (F(1, 2), F(1, 4))
    assert back.family == ("nouri_saeidian", "same_degree") and back.is_exact
    assert back.evaluate(0.3, 0.7).tolist() == s.evaluate(0.3, 0.7).tolist()
    # the definition file works as family= too; without a family the error says what to pass
    again = surface_from_json(text, family=examples.path("nouri_saeidian.toml"))
    assert again.control_net() == s.control_net()
    with pytest.raises(ValueError, match="embeds its definition"):
        surface_from_json(text)
    # ... and the embedded definition can be written out as a family file
    from lambda_bezier.export import family_definition

    assert 'name = "nouri_saeidian"' in family_definition(text)
    # a document written with another definition under the same name is refused
    import json

    from lambda_bezier.family import definition_digest

    doc = json.loads(text)
    entry = doc["definitions"]["nouri_saeidian"]
    entry["definition"]["title"] = "edited"
    entry["definition_digest"] = definition_digest(entry["definition"])
    with pytest.raises(ValueError, match="another version"):
        surface_from_json(json.dumps(doc), family=fam)


# ---------------------------------------------------------------------- derived conditions
@pytest.mark.parametrize("continuity", ["C1", "G1"])
@pytest.mark.parametrize("side", ["u", "v"])
@pytest.mark.parametrize("pair", ["own>own", "own>same_degree", "bernstein_like>own", "bezier>own"])
def test_derived_surface_conditions_match_the_solved_join(continuity, side, pair):
    fam = own_family()
    first, second = (fam if x == "own" else x for x in pair.split(">"))
    lams = {"same_degree": F(1, 3), "bernstein_like": F(-1, 2), "bezier": None}
    lam1 = F(1, 3) if first is fam else lams[first]
    lam2 = F(3, 4) if second is fam else lams[second]
    degree = {"bernstein_like": 3, "bezier": 3, "same_degree": 4}.get(first, 4)
    net = [[(i, j, (i * j + j * j) % 5 - F(i, 3)) for j in range(4)] for i in range(degree + 1)]
    if side == "v":
        net = [list(r) for r in zip(*net, strict=True)]
    family = (first, "same_degree") if side == "u" else ("same_degree", first)
    lam_u, lam_v = (lam1, F(-1, 2)) if side == "u" else (F(-1, 2), lam1)
    a = lb.Surface(net, lam_u, lam_v, family=family)
    new_degree = 4
    if side == "u":
        rest = [[(6 + k, j, k) for j in range(4)] for k in range(new_degree - 1)]
    else:
        rest = [[(i, 6 + k, k) for k in range(new_degree - 1)] for i in range(4)]
    kw = dict(rest=rest, family=second, alpha=F(3, 2) if continuity == "G1" else 1)
    solved = lb.join_surface(a, side, continuity, new_degree, lam2, **kw)
    derived = lb.join_surface(a, side, continuity, new_degree, lam2, conditions="derived", **kw)
    assert derived.is_exact and derived.control_net() == solved.control_net()
    assert derived.family == solved.family and (derived.lam_u, derived.lam_v) == (
        solved.lam_u,
        solved.lam_v,
    )
    report = lb.CompositeSurface([[a], [derived]] if side == "u" else [[a, derived]]).report()
    assert report[0].continuity in (continuity, "C1", "C2")


def test_derived_surface_conditions_say_what_is_missing():
    fam = own_family()
    a = lb.Surface([[(i, j, 0) for j in range(4)] for i in range(4)], F(1, 2), F(1, 3), family=fam)
    rest = [[(5, j, 0) for j in range(4)]]
    with pytest.raises(ValueError, match="no derived C2 conditions.*order 2"):
        lb.join_surface(a, "u", "C2", 3, F(1, 2), rest=rest, conditions="derived")
    b = lb.SameDegreeSurface([[(i, j, 0) for j in range(4)] for i in range(4)], 0, 0)
    with pytest.raises(ValueError, match='conditions="solve"'):
        lb.join_surface(b, "u", "C1", 3, 0, rest=rest * 2, conditions="derived")
    with pytest.raises(ValueError, match="conditions"):
        lb.join_surface(b, "u", "C1", 3, 0, rest=rest * 2, conditions="guess")


def test_derive_proves_each_user_family_condition_and_rejects_a_wrong_one(monkeypatch):
    import importlib

    from conftest import ROOT

    from lambda_bezier import _derive_runner, examples

    if not (ROOT / "derive" / "formulas" / "surface_joins.py").is_file():
        pytest.skip("needs the source checkout (derive/)")
    pkg = _derive_runner.load_derive(ROOT).__name__
    sj = importlib.import_module(f"{pkg}.formulas.surface_joins")
    family = importlib.import_module(f"{pkg}.formulas.family")
    definition = importlib.import_module(f"{pkg}.families.definition")
    engine = importlib.import_module(f"{pkg}.families.engine")
    defn = definition.read_definition(examples.path("nouri_saeidian.toml"))
    closed = engine.closed_endpoint_forms(defn)
    doc = family.surface_join_artifacts(defn, closed)
    shipped = own_family().curve_class._data.SURFACE_JOINS
    assert doc == shipped  # the shipped document holds what derive gives now
    # a changed weight fails the column-wise proof on the family's own basis
    original = sj._check_weights

    def corrupt(first, second, continuity, basis, weights):
        bad = dict(weights)
        key = next(k for k in sorted(bad) if k[0] == 1)
        bad[key] = bad[key] + 1
        original(first, second, continuity, basis, bad)

    monkeypatch.setattr(sj, "_check_weights", corrupt)
    with pytest.raises(AssertionError, match="do not match"):
        family.surface_join_artifacts(defn, closed)


# ---------------------------------------------------------------------- robustness
def test_closest_point_along_a_curve_of_minima_is_certified_and_quick():
    import math

    # a cylinder patch (radius 1 about the z axis) and a point on the axis: every point of the
    # surface at z = 0.5 is nearest; a scalar field (d = 1) and a value on a level line
    angles = np.linspace(0, 1.2, 4)
    cyl = lb.BezierSurface([[(math.cos(a), math.sin(a), z) for a in angles] for z in (0, 1)])
    plane = lb.BezierSurface([[(i + j,) for j in range(3)] for i in range(3)])
    for surf, q in ((cyl, [0, 0, 0.5]), (plane, [1.0])):
        cp = surf.closest_point(q)
        us, vs = np.meshgrid(np.linspace(0, 1, 201), np.linspace(0, 1, 201), indexing="ij")
        dense = np.linalg.norm(surf.evaluate(us.ravel(), vs.ravel()) - np.asarray(q), axis=1)
        assert cp.lower_bound <= cp.distance <= dense.min() + 1e-12
        np.testing.assert_allclose(np.linalg.norm(cp.point - np.asarray(q)), cp.distance)
        assert cp.distance - cp.lower_bound <= 1e-6  # certified, if more loosely than tol


def test_normals_and_curvatures_of_huge_and_tiny_nets():
    base = [[(i, j, (i - 1) * (j - 1)) for j in range(3)] for i in range(3)]
    ref = lb.BezierSurface(base)
    k0, h0 = ref.curvatures(0.3, 0.6)
    for scale in (1e-200, 1e-100, 1e100, 1e250):
        s = lb.BezierSurface(np.array(base, dtype=float) * scale)
        np.testing.assert_allclose(s.normal(0.3, 0.6), ref.normal(0.3, 0.6), rtol=1e-13)
        if scale >= 1e-100:
            k, h = s.curvatures(0.3, 0.6)
            np.testing.assert_allclose(h * scale, h0, rtol=1e-12)
            if scale < 1e150:  # beyond, K (about 1/scale²) is below the smallest float
                np.testing.assert_allclose(k * scale * scale, k0, rtol=1e-12)
            else:
                assert k == 0
    flat_tiny = lb.BezierSurface(
        [[(i * 1e-300, j * 1e-300, 0) for j in range(3)] for i in range(3)]
    )
    assert [float(x) for x in flat_tiny.curvatures(0.5, 0.5)] == [0.0, 0.0]
    with pytest.raises(ValueError, match="beyond the float range"):
        lb.BezierSurface(np.array(base, dtype=float) * 1e-200).curvatures(0.3, 0.6)


def test_bad_magnitudes_and_tolerances_are_named():
    from lambda_bezier.surface_export import mesh

    nets = np.random.default_rng(1).normal(size=(2, 4, 4, 3)) * 1e200
    with pytest.raises(ValueError, match="scale them down"):
        lb.optimal_parameters(nets, "membrane")
    s = patch()
    with pytest.raises(ValueError, match="tolerance must be > 0"):
        mesh(s, 0)
    with pytest.raises(ValueError, match="cells"):
        mesh(s, 1e-300)
    flat = lb.BezierSurface([[(i, j, 0) for j in range(3)] for i in range(3)])
    assert mesh(flat, 0).deviation_bound == 0
