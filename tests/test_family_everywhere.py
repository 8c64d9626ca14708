"""Issue 32: a family of the user's own works wherever a built-in family's name does.

Every public function and method of the package with a parameter named `family`, and every
subcommand of `lambda-bezier` with a `--family` option, is found by introspection; each must
have a call here with a loaded family (and, from the command line, with a family file), checked
against an independent result. A new one fails `test_every_family_parameter_is_covered` until
a call is added.
"""

from __future__ import annotations

import argparse
import importlib
import inspect
import json
import math
import pkgutil
from fractions import Fraction

import numpy as np
import pytest

import lambda_bezier as lb
from lambda_bezier import examples
from lambda_bezier.cli import build_parser, main
from lambda_bezier.family import definition_digest

NS_FILE = examples.path("nouri_saeidian.toml")
POINTS = [(0, 0), (1, 2), (3, 2), (4, 0)]


@pytest.fixture(scope="module")
def fam():
    return lb.load_family(NS_FILE)


def _public_callables_with_family():
    """'module.function' and 'module.Class.method' of every public callable whose signature
    has a parameter named `family` (private modules and names skipped; the derive copy
    installed as lambda_bezier._derive is not the runtime)."""
    found = set()
    for info in pkgutil.walk_packages(lb.__path__, "lambda_bezier."):
        if any(part.startswith("_") for part in info.name.split(".")[1:]):
            continue
        module = importlib.import_module(info.name)
        for name, obj in vars(module).items():
            if name.startswith("_") or getattr(obj, "__module__", None) != module.__name__:
                continue
            members = [(name, obj)]
            if inspect.isclass(obj):
                members = [
                    (f"{name}.{m}", f)
                    for m, f in vars(obj).items()
                    if not m.startswith("_") and callable(f)
                ]
            for qual, f in members:
                try:
                    params = inspect.signature(f).parameters
                except (TypeError, ValueError):
                    continue
                if "family" in params:
                    found.add(f"{info.name.split('.', 1)[1]}.{qual}")
    return found


def _own_curve(fam):
    return fam.curve(POINTS, lam=Fraction(1, 2))


def _call_optimal_lambda(fam):
    r = lb.optimal_lambda(POINTS, 2, family=fam)
    # independent: the minimiser of E_2(λ) = ∫|p''|² from the curve's own exact energy
    e = [fam.curve(POINTS, lam=Fraction(x, 7)).energy(2) for x in (3, 4, 5)]
    assert e[1] < e[0] and e[1] < e[2] and r.lam == Fraction(4, 7)


def _call_curve_optimal_parameters(fam):
    r = lb.optimal_parameters(POINTS, 2, family=fam)
    # by the family's own name; the minimiser of the curve's own exact E_2 (as above)
    e = [fam.curve(POINTS, sigma=Fraction(x, 7)).energy(2) for x in (3, 4, 5)]
    assert e[1] < e[0] and e[1] < e[2] and r["sigma"] == Fraction(4, 7)


def _call_energy_coefficients(fam):
    c = lb.energy_coefficients(POINTS, 2, family=fam)
    # E_2(λ) = a + bλ + cλ² against the curve's own energy at three λ
    for lam in (Fraction(0), Fraction(1, 3), Fraction(1)):
        coeffs = [Fraction(x) for x in c] if not hasattr(c, "c0") else [c.c0, c.c1, c.c2]
        value = sum(a * lam**i for i, a in enumerate(coeffs))
        assert value == fam.curve(POINTS, lam=lam).energy(2)


def _call_energy_matrices(fam):
    scale, x, y = lb.energy_matrices(3, 2, family=fam)
    assert len(x) == len(y) == 4 and all(len(row) == 4 for row in (*x, *y)) and scale != 0
    assert all(isinstance(v, int) for row in (*x, *y) for v in row)
    assert (scale, x, y) != lb.energy_matrices(3, 2), "the family's own, not same_degree's"


def _call_join(fam):
    first = lb.BezierCurve([(0, 0), (1, 1), (2, 0)])
    nxt = lb.join(first, "C1", 3, lam=Fraction(1, 2), rest=[(5, 5), (6, 0)], family=fam)
    assert type(nxt) is fam.curve_class
    assert np.allclose(first.derivative(1.0), nxt.derivative(0.0))


def _call_composite_join(fam):
    comp = lb.CompositeCurve([lb.BezierCurve([(0, 0), (1, 1), (2, 0)])]).join(
        "C1", 3, Fraction(1, 2), rest=[(5, 5), (6, 0)], family=fam
    )
    assert type(comp.segments[1]) is fam.curve_class and comp.report()[0].kept


def _call_evaluate_many(fam):
    pts = np.array([POINTS] * 2, dtype=float)
    ts = np.linspace(0, 1, 7)
    got = lb.evaluate_many(pts, ts, fam, lam=[0.5, 0.25])
    want = [fam.curve(POINTS, lam=lam).evaluate(ts) for lam in (0.5, 0.25)]
    assert np.allclose(got, want, rtol=0, atol=1e-12)


def _call_singular_parameters(fam):
    assert lb.singular_parameters(fam, 3) == (Fraction(0),)


def _call_is_singular(fam):
    from lambda_bezier.properties import is_singular

    assert is_singular(fam, 3, 0) and not is_singular(fam, 3, Fraction(1, 2))


def _call_family_class(fam):
    from lambda_bezier.curves import family_class

    assert family_class(fam) is fam.curve_class


def _call_from_json(fam):
    from lambda_bezier.export import from_json, to_json

    c = _own_curve(fam)
    back = from_json(to_json(c), family=fam)
    assert type(back) is fam.curve_class and back.lam == c.lam
    assert back.control_points() == c.control_points()


def _call_surface_from_json(fam):
    from lambda_bezier.surface_export import surface_from_json, surface_to_json
    from lambda_bezier.surfaces import surface

    s = surface(NET, Fraction(1, 2), Fraction(1, 3), family=fam)
    back = surface_from_json(surface_to_json(s), family=fam)
    assert back.control_net() == s.control_net() and (back.lam_u, back.lam_v) == (s.lam_u, s.lam_v)
    assert back.family == s.family


def _call_leading_weights(fam):
    from lambda_bezier.joins import Joint, leading_weights

    first = lb.BezierCurve([(0, 0), (1, 1), (2, 0)])
    w = leading_weights(first, Joint("C1", 1, 0), fam, 3, Fraction(1, 2))
    nxt = lb.join(first, "C1", 3, lam=Fraction(1, 2), rest=[(5, 5), (6, 0)], family=fam)
    # P_{1,2} = Σ weight · X, X a point of the first curve (P_{n-j}) or a given one (P_{j,2})
    given = {j: nxt.control_points()[j] for j in range(4)}
    row1 = [
        sum(
            Fraction(wt) * (first.control_points()[2 - j][c] if src == "first" else given[j][c])
            for (row, src, j), wt in w.items()
            if row == 1
        )
        for c in range(2)
    ]
    assert tuple(row1) == nxt.control_points()[1]


# surfaces (issue #31): a net of the loaded family in both directions
NET = [[(i, j, (i * j) % 3) for j in range(4)] for i in range(4)]


def _nested(fam, net, lam_u, lam_v, u, v):
    """S(u, v) independently: the curves of the columns at u, then the curve through them."""
    cols = [fam.curve([row[j] for row in net], lam=lam_u).evaluate(u) for j in range(len(net[0]))]
    return fam.curve([tuple(c) for c in cols], lam=lam_v).evaluate(v)


def _call_surface(fam):
    from lambda_bezier.surfaces import surface

    s = surface(NET, Fraction(1, 2), Fraction(1, 3), family=fam)
    for u, v in ((0.2, 0.7), (0.9, 0.1)):
        want = _nested(fam, NET, Fraction(1, 2), Fraction(1, 3), u, v)
        assert np.allclose(s.evaluate(u, v), want)


def _gauss_energy(s, energy):
    """∫∫ |S_u|² + |S_v|² (membrane) on an 8 × 8 Gauss grid: exact for these degrees."""
    x, w = np.polynomial.legendre.leggauss(8)
    x, w = (x + 1) / 2, w / 2
    uu, vv = (a.ravel() for a in np.meshgrid(x, x, indexing="ij"))
    ww = np.outer(w, w).ravel()
    su, sv = s.derivative(uu, vv, 1, 0), s.derivative(uu, vv, 0, 1)
    return float(ww @ ((su**2).sum(-1) + (sv**2).sum(-1)))


def _call_surface_energy_matrices(fam):
    from lambda_bezier.surfaces import surface

    mats = lb.surface_energy_matrices((3, 3), "membrane", family=fam)
    poly = mats.polynomial(NET)
    lu, lv = Fraction(1, 2), Fraction(1, 3)
    value = sum(c * lu**a * lv**b for (a, b), c in poly.items())
    assert math.isclose(
        float(value), _gauss_energy(surface(NET, lu, lv, family=fam), "membrane"), rel_tol=1e-12
    )


def _call_join_surface(fam):
    from lambda_bezier.surfaces import surface

    a = surface(NET, Fraction(1, 2), Fraction(1, 3), family=fam)
    rest = [[(6, j, 0) for j in range(4)]] * 2
    b = lb.join_surface(a, "u", "C1", 3, Fraction(1, 2), rest=rest, family=fam)
    for v in (0.25, 0.5):  # C1 across u = 1
        assert np.allclose(a.evaluate(1.0, v), b.evaluate(0.0, v))
        assert np.allclose(a.derivative(1.0, v, 1, 0), b.derivative(0.0, v, 1, 0))


def _call_join_before(fam):
    from lambda_bezier._join_options import JoinOptions
    from lambda_bezier.surface_sides import join_before
    from lambda_bezier.surfaces import surface

    a = surface(NET, Fraction(1, 2), Fraction(1, 3), family=fam)
    rest = [[(-6, j, 0) for j in range(4)]] * 2
    b = join_before(a, 0, "C1", JoinOptions(3, Fraction(1, 2), rest, 1, None, fam))
    for v in (0.25, 0.5):  # C1 across u = 0: b ends where a starts
        assert np.allclose(b.evaluate(1.0, v), a.evaluate(0.0, v))
        assert np.allclose(b.derivative(1.0, v, 1, 0), a.derivative(0.0, v, 1, 0))


def _call_resolve_sides(fam):
    from lambda_bezier import _poly_direction as pd
    from lambda_bezier.param_surface_joins import resolve_sides
    from lambda_bezier.surface_sides import ByName
    from lambda_bezier.surfaces import surface

    a = ByName(surface(NET, Fraction(1, 2), Fraction(1, 3), family=fam))
    got = resolve_sides(a, 0, fam, {"sigma": Fraction(1, 4)}, 3)  # as join_surface resolves
    assert pd.family_name(got.new_family) == pd.family_name(got.across) == fam.name
    assert got.new_params == {"sigma": Fraction(1, 4)}
    assert got.across_params == {"sigma": Fraction(1, 2)}
    assert got.along_params == {"sigma": Fraction(1, 3)}


def _call_optimal_parameters_batch(fam):
    from lambda_bezier.surface_optimum import optimal_parameters_batch

    nets = np.array([NET, [[(i, j, (i + j) % 2) for j in range(4)] for i in range(4)]], float)
    got = optimal_parameters_batch(nets, "membrane", fam)
    for k in range(2):  # each against the exact solve of the same net
        exact = [[tuple(map(Fraction, p)) for p in row] for row in nets[k].tolist()]
        one = lb.optimal_parameters(exact, "membrane", family=fam)
        assert math.isclose(float(got["lam_u"][k]), one["lam_u_float"], abs_tol=1e-9)
        assert math.isclose(float(got["lam_v"][k]), one["lam_v_float"], abs_tol=1e-9)


def _call_optimal_parameters(fam):
    from lambda_bezier.surface_energies import surface_energy
    from lambda_bezier.surfaces import surface

    r = lb.optimal_parameters(NET, "membrane", family=fam)
    best = surface_energy(surface(NET, r["lam_u_float"], r["lam_v_float"], family=fam), "membrane")
    for du, dv in ((0.01, 0), (-0.01, 0), (0, 0.01), (0, -0.01)):  # no better neighbour inside
        lu, lv = r["lam_u_float"] + du, r["lam_v_float"] + dv
        if 0 <= lu <= 1 and 0 <= lv <= 1:  # sigma's range [0, 1]
            other = surface(NET, lu, lv, family=fam)
            assert surface_energy(other, "membrane") >= best - 1e-12


def _call_family_surface(fam):
    from lambda_bezier.param_surfaces import family_surface
    from lambda_bezier.surfaces import surface

    s = family_surface(NET, fam, params_u={"sigma": Fraction(1, 2)}, params_v={"sigma": 0})
    plain = surface(NET, Fraction(1, 2), 0, family=fam)
    assert s.parameters() == {"sigma_u": Fraction(1, 2), "sigma_v": 0}
    assert s.to_bezier().control_net() == plain.to_bezier().control_net()


def _call_param_optimal_parameters(fam):
    from lambda_bezier.param_surface_energy import optimal_parameters

    r = optimal_parameters(NET, "membrane", fam)  # the certified branch and bound
    one = lb.optimal_parameters(NET, "membrane", family=fam)  # exact: resultants, Sturm
    assert math.isclose(float(r["sigma_u"]), one["lam_u_float"], abs_tol=1e-5)
    assert math.isclose(float(r["sigma_v"]), one["lam_v_float"], abs_tol=1e-5)
    # the exact minimum as a float is rounded to nearest, and the certified bounds about it
    # are within 1e-30 of each other (box_convex's floor): one unit in the last place each way
    e = float(one["energy"])
    assert r.lower_bound - math.ulp(e) <= e <= r.energy + math.ulp(e)
    assert r.energy - r.lower_bound <= 1e-12 * max(1, r.energy)


def _call_param_surface_optimum(fam):
    from lambda_bezier.param_surface_optimum import optimal_parameters

    r = optimal_parameters(NET, "membrane", fam)  # one net: the certified path, by name
    one = lb.optimal_parameters(NET, "membrane", family=fam)  # exact: resultants, Sturm
    assert r.method == "certified"
    assert math.isclose(float(r["sigma_u"]), one["lam_u_float"], abs_tol=1e-5)


def _call_param_surface_batch(fam):
    from lambda_bezier.param_surface_optimum import optimal_parameters_batch

    nets = np.random.default_rng(2).normal(size=(6, 4, 4, 2))
    r = optimal_parameters_batch(nets, "membrane", fam)  # the fixed-cost certificate
    exact = lb.optimal_parameters(nets, "membrane", family=fam)  # the one-parameter batch
    assert np.allclose(r["sigma_u"], exact["lam_u"], atol=1e-5)
    assert np.allclose(r.energy, exact["energy"], rtol=1e-10)


# parameters named `family` that name something else
NOT_A_FAMILY = {
    "curves.data_curve_class": "the new class's family name, not one to look up",
    "surface_sides.takes_names": "asks what kind of family it is given; uses none",
}

CALLS = {
    "joins.leading_weights": _call_leading_weights,
    "energy.optimal_lambda": _call_optimal_lambda,
    "energy.optimal_parameters": _call_curve_optimal_parameters,
    "energy.energy_coefficients": _call_energy_coefficients,
    "energy.energy_matrices": _call_energy_matrices,
    "joins.join": _call_join,
    "composite.CompositeCurve.join": _call_composite_join,
    "batch.evaluate_many": _call_evaluate_many,
    "properties.singular_parameters": _call_singular_parameters,
    "properties.is_singular": _call_is_singular,
    "curves.family_class": _call_family_class,
    "export.from_json": _call_from_json,
    "surfaces.surface": _call_surface,
    "surface_export.surface_from_json": _call_surface_from_json,
    "surface_energies.surface_energy_matrices": _call_surface_energy_matrices,
    "surface_joins.join_surface": _call_join_surface,
    "param_surface_joins.resolve_sides": _call_resolve_sides,
    "surface_optimum.optimal_parameters": _call_optimal_parameters,
    "surface_optimum.optimal_parameters_batch": _call_optimal_parameters_batch,
    "surface_optimum.surface_energy_matrices": _call_surface_energy_matrices,  # lb.'s
    "param_surfaces.family_surface": _call_family_surface,
    "param_surface_energy.optimal_parameters": _call_param_optimal_parameters,
    "param_surface_energy.surface_energy_matrices": _call_surface_energy_matrices,
    "param_surface_optimum.optimal_parameters": _call_param_surface_optimum,
    "param_surface_optimum.optimal_parameters_batch": _call_param_surface_batch,
}


def test_every_family_parameter_is_covered():
    found = _public_callables_with_family()
    assert found, "introspection found nothing: the walk is broken"
    found -= set(NOT_A_FAMILY)
    assert found == set(CALLS), (
        f"without a call here: {sorted(found - set(CALLS))}; gone: {sorted(set(CALLS) - found)}"
    )


@pytest.mark.parametrize("name", sorted(CALLS))
def test_accepts_a_loaded_family(name, fam):
    CALLS[name](fam)


def test_join_before_takes_a_loaded_family_in_its_options(fam):
    """surface_sides.join_before takes the family inside its JoinOptions, not as a `family`
    parameter, so the walk above does not list it: called here instead."""
    _call_join_before(fam)


# ------------------------------------------------------------------------- the command line


def _subcommands_with_family():
    parser = build_parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    return {
        name
        for name, p in sub.choices.items()
        if any("--family" in a.option_strings for a in p._actions)
    }


def _cli_derive(tmp_path, capsys):
    # a copy of the example (derive --family writes nothing into the installed package)
    files = examples.copy("family", tmp_path)
    (tmp_path / "nouri_saeidian.derived.json").unlink()
    assert main(["derive", "-q", "--family", str(files[0])]) == 0
    written = (tmp_path / "nouri_saeidian.derived.json").read_text()
    assert written == examples.path("nouri_saeidian.derived.json").read_text()
    assert main(["derive", "-q", "--family", str(files[0]), "--check"]) == 0


def _cli_optimal_lambda(tmp_path, capsys):
    assert (
        main(["optimal-lambda", "--json", "--family", str(NS_FILE), "0,0", "1,2", "3,2", "4,0"])
        == 0
    )
    report = json.loads(capsys.readouterr().out)
    assert report["family"] == "nouri_saeidian" and report["lambda"] == "4/7"
    assert report["range"] == "[0, 1]"


def _cli_export(tmp_path, capsys):
    from lambda_bezier.export import from_json, to_json

    fam = lb.load_family(NS_FILE)
    c = _own_curve(fam)
    src = tmp_path / "curve.json"
    src.write_text(to_json(c))
    out = tmp_path / "out.json"
    assert main(["export", "--format", "json", "--family", str(NS_FILE), str(src), str(out)]) == 0
    assert from_json(out.read_text(), family=fam).control_points() == c.control_points()
    # without the family: refused, saying how
    assert main(["export", "--format", "json", str(src), str(out)]) == 2
    err = capsys.readouterr().err
    assert "'nouri_saeidian' is not built in" in err and "--family FILE" in err
    # the embedded definition written out is the definition (same fingerprint)
    toml = tmp_path / "ns.toml"
    assert main(["export", "--format", "family", str(src), str(toml)]) == 0
    from lambda_bezier.family import definition_digest, read_family_table

    assert definition_digest(read_family_table(toml)) == fam.digest


CLI = {"derive": _cli_derive, "optimal-lambda": _cli_optimal_lambda, "export": _cli_export}


def test_every_family_option_is_covered():
    assert _subcommands_with_family() == set(CLI)


@pytest.mark.parametrize("command", sorted(CLI))
def test_cli_accepts_a_family_file(command, tmp_path, capsys):
    CLI[command](tmp_path, capsys)


# ------------------------------------------------------------------- the JSON form, in detail


def test_json_composite_of_own_and_built_in_families_round_trips_exactly(fam, tmp_path):
    from lambda_bezier.export import from_json, to_json

    comp = lb.CompositeCurve([_own_curve(fam)]).join(
        "C1", 3, Fraction(1, 4), rest=[(7, 1), (8, 0)], family="bernstein_like"
    )
    text = to_json(comp)
    doc = json.loads(text)
    assert set(doc["definitions"]) == {"nouri_saeidian"}
    assert doc["definitions"]["nouri_saeidian"]["definition_digest"] == fam.digest
    # the derived document alone, copied away from any definition file
    derived = tmp_path / "nouri_saeidian.derived.json"
    derived.write_text(examples.path("nouri_saeidian.derived.json").read_text())
    for given in (fam, NS_FILE, derived, [derived]):
        back = from_json(text, family=given)
        assert [s.control_points() for s in back.segments] == [
            s.control_points() for s in comp.segments
        ]
        assert [s.lam for s in back.segments] == [s.lam for s in comp.segments]
        assert to_json(back) == text


def test_json_refuses_another_version_of_the_family(fam, tmp_path):
    from lambda_bezier.export import from_json, to_json

    text = to_json(_own_curve(fam))
    other = tmp_path / "nouri_saeidian.toml"
    other.write_text(NS_FILE.read_text().replace('degrees = "3..12"', 'degrees = "3..11"'))
    with pytest.raises(ValueError, match="another version of the family 'nouri_saeidian'"):
        from_json(
            text, family=lb.Family(fam.data, other, "", "sigma", dict(fam.table, degrees="3..11"))
        )
    # an edited embedded definition no longer matches its own fingerprint
    doc = json.loads(text)
    doc["definitions"]["nouri_saeidian"]["definition"]["range"] = "[0, 2]"
    with pytest.raises(ValueError, match=r"does not match its definition_digest"):
        from_json(json.dumps(doc), family=fam)
    # a derived document of another definition
    with pytest.raises(ValueError, match="derived from another version"):
        from_json(
            json.dumps(
                {
                    **json.loads(text),
                    "definitions": {
                        "nouri_saeidian": {
                            "definition": dict(fam.table, title="x"),
                            "definition_digest": definition_digest(dict(fam.table, title="x")),
                        }
                    },
                }
            ),
            family=examples.path("nouri_saeidian.derived.json"),
        )
    with pytest.raises(TypeError, match="family must be a Family"):
        from_json(text, family=3)


def test_embedded_definition_written_out_is_a_family_file(fam):
    from lambda_bezier.export import family_definition, to_json
    from lambda_bezier.family import definition_toml

    text = family_definition(to_json(_own_curve(fam)))
    import tomllib

    assert tomllib.loads(text)["family"] == fam.table
    hostile = dict(fam.table, title='quote " backslash \\ newline \n del \x7f tab \t é')
    assert tomllib.loads(definition_toml(hostile))["family"] == hostile
    with pytest.raises(ValueError, match="embeds no family definition"):
        family_definition(to_json(lb.BezierCurve([(0, 0), (1, 1)])))


# ------------------------------------------------------------------------------- the examples


def test_examples_copy_and_refuse_to_overwrite(tmp_path):
    copied = examples.copy("records", tmp_path)
    assert [p.name for p in copied] == ["user_paper.toml"]
    assert copied[0].read_text() == examples.path("user_paper.toml").read_text()
    with pytest.raises(ValueError, match="not overwritten"):
        examples.copy("records", tmp_path)
    with pytest.raises(ValueError, match="kind must be one of family, records"):
        examples.copy("figures", tmp_path)
    with pytest.raises(ValueError, match="name must be one of"):
        examples.path("../family.py")
    assert main(["example", "list"]) == 0


def test_derive_family_refuses_to_write_into_an_installation(tmp_path, monkeypatch):
    from lambda_bezier import _family_runner

    site = tmp_path / "site-packages"
    (site / "pkg").mkdir(parents=True)
    monkeypatch.setattr(
        _family_runner.sysconfig, "get_paths", lambda: {"purelib": str(site), "platlib": str(site)}
    )
    assert _family_runner._installed_location(site / "pkg" / "x.derived.json") == site
    assert _family_runner._installed_location(tmp_path / "x.derived.json") is None
