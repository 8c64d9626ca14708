"""Non-polynomial families (issue #30), continued: the command line, self-intersections,
fuzzing of the derived document, random atom spaces, and the polynomial-only functions'
messages (test_trig_runtime.py holds the helpers and the core tests)."""

from __future__ import annotations

import json
import math
from fractions import Fraction as F

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from test_trig_runtime import AT, DATA, HAN, HYP, PTS, _doc

import lambda_bezier as lb
from lambda_bezier.family import FamilyFileError
from lambda_bezier.hazmat import atoms as ak


@pytest.fixture(scope="module")
def families():
    return {p: lb.load_family(p) for p in (HAN, HYP, AT)}


# ------------------------------------------------------------------------------ command line
def test_cli_optimal_parameters(capsys):
    from lambda_bezier.cli import main

    points = ["0,0", "1,3", "3,-1", "4,1"]
    assert main(["optimal-lambda", "--json", "--family", str(HAN), *points]) == 0
    report = json.loads(capsys.readouterr().out)
    want = lb.optimal_parameters(PTS, 2, family=lb.load_family(HAN))
    assert report["parameters"] == {n: str(v) for n, v in want.values.items()}
    assert report["parameters_decimal"]["mu"] == float(want["mu"])
    assert "pi" in report["energy"] and report["free_inside"] is True
    assert main(["optimal-lambda", "-k", "1", "--family", str(HYP), *points]) == 0
    assert "lam = 0 (lower end)" in capsys.readouterr().out


def test_cli_export_reads_the_family(tmp_path, capsys):
    from lambda_bezier import export
    from lambda_bezier.cli import main

    fam = lb.load_family(HAN)
    src = tmp_path / "c.json"
    src.write_text(export.to_json(fam.curve(PTS, lam=0, mu=F(1, 2))))
    pytest.importorskip("ezdxf")
    out = tmp_path / "c.dxf"
    assert main(["export", "--format", "dxf", "--family", str(HAN), str(src), str(out)]) == 0
    assert out.is_file()


def test_the_shipped_example_is_the_test_family():
    """The own-family guide loads examples/han_trig_cubic.*, the tests tests/data's copy:
    both are regenerated together (tests/data/families/README.md)."""
    from lambda_bezier import examples

    for name in ("han_trig_cubic.toml", "han_trig_cubic.derived.json"):
        assert examples.path(name).read_bytes() == (DATA / name).read_bytes()


def _polyline_crossings(pts):
    """Parameter index pairs (i < j - 1) where the polyline's segments i and j cross."""
    a, b = pts[:-1], pts[1:]
    d = b - a
    den = d[:, None, 0] * d[None, :, 1] - d[:, None, 1] * d[None, :, 0]
    w = a[None, :, :] - a[:, None, :]
    with np.errstate(divide="ignore", invalid="ignore"):
        u = (w[..., 0] * d[None, :, 1] - w[..., 1] * d[None, :, 0]) / den
        v = (w[..., 0] * d[:, None, 1] - w[..., 1] * d[:, None, 0]) / den
    i, j = np.nonzero((u >= 0) & (u < 1) & (v >= 0) & (v < 1))
    keep = j > i + 1
    return list(zip(i[keep], j[keep], strict=True))


# (points, parameters) with one loop each (found by a polyline search), and without
LOOPS = {
    HAN: ([(0, 0), (20, 10), (-16, 10), (4, 0)], {"lam": 1, "mu": 1}),
    HYP: (
        [(-2.304, 0.268), (-3.661, -0.508), (-2.762, 0.364), (2.976, -1.603)],
        {"lam": 0.15, "mu": 0.94},
    ),
    AT: ([(2.022, -3.168), (-2.689, -0.333), (0.865, -8.834), (0.211, 0.693)], {"lam": -0.95}),
}


@pytest.mark.parametrize("path", [HAN, HYP, AT])
def test_self_intersections_against_a_polyline(families, path):
    fam = families[path]
    rng = np.random.default_rng(21)
    cases = [LOOPS[path]]
    for _ in range(3):
        params = {
            n: float(fam.atom_data.RANGES[n][0])
            + rng.random() * float(fam.atom_data.RANGES[n][1] - fam.atom_data.RANGES[n][0])
            for n in fam.parameters
        }
        cases.append((rng.normal(size=(4, 2)) * 3, params))
    loops = 0
    for pts, params in cases:
        curve = fam.curve(pts, params=params)
        t = np.linspace(*curve.domain, 1201)
        want = _polyline_crossings(curve.evaluate(t))
        got = curve.self_intersections()
        assert len(got) == len(want), (got, want)
        loops += len(got)
        for x, (i, j) in zip(got, want, strict=True):
            assert np.linalg.norm(curve.evaluate(x.s) - curve.evaluate(x.t)) < 1e-10
            assert t[i] - 1e-2 <= x.s <= t[i + 1] + 1e-2 and t[j] - 1e-2 <= x.t <= t[j + 1] + 1e-2
    assert loops >= 1


# ------------------------------------------------------------------------------ hypothesis


def _leaves(node, path=()):
    if isinstance(node, dict):
        for k, v in node.items():
            yield from _leaves(v, (*path, k))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            yield from _leaves(v, (*path, i))
    yield path


JUNK = st.one_of(
    st.none(),
    st.booleans(),
    st.integers(-(10**6), 10**6),
    st.floats(allow_nan=True, allow_infinity=True),
    st.text(max_size=12),
    st.sampled_from(["1/0", "0/0", "-", "sin(t)", "cos(0*t)", "t^0", "[", "exp(0)", "pi"]),
    st.lists(st.integers(), max_size=3),
    st.dictionaries(st.text(max_size=4), st.integers(), max_size=2),
)


@settings(max_examples=150, deadline=None)
@given(data=st.data())
def test_a_mangled_document_is_refused_by_name_never_a_traceback(tmp_path_factory, data):
    doc = _doc()
    paths = list(_leaves(doc))
    path = data.draw(st.sampled_from(paths[:-1]))  # the last one is the root
    parent = doc
    for key in path[:-1]:
        parent = parent[key]
    if data.draw(st.booleans()) and isinstance(parent, dict):
        del parent[path[-1]]
    else:
        parent[path[-1]] = data.draw(JUNK)
    tmp = tmp_path_factory.mktemp("mangled")
    (tmp / "han_trig_cubic.toml").write_text(HAN.read_text())
    (tmp / "han_trig_cubic.derived.json").write_text(json.dumps(doc))
    try:
        fam = lb.load_family(tmp / "han_trig_cubic.toml")
    except FamilyFileError:
        return
    # accepted (an ignored or harmless change): it must still work
    curve = fam.curve(PTS, lam=0, mu=0, check_range=False)  # a range may have changed
    assert np.isfinite(curve.evaluate(np.linspace(*fam.domain, 5))).all()


@st.composite
def _trig_sums(draw):
    """A random curve of a trigonometric/hyperbolic/mixed space: atoms with rational (or
    π-rational) frequencies and random coefficients, as a one-parameter format-4 document."""
    hyper = draw(st.booleans())
    mixed = draw(st.booleans())
    base = F(draw(st.integers(1, 3)), draw(st.integers(1, 3)))
    use_pi = (not hyper) and draw(st.booleans())
    harmonics = sorted(set(draw(st.lists(st.integers(1, 4), min_size=1, max_size=3))))
    kinds = ("cosh", "sinh") if hyper else ("cos", "sin")
    atoms = ["1"] + (["t^1", "t^2"] if mixed else [])
    for j in harmonics:
        w = base * j
        text = f"{w}*pi" if use_pi else f"{w}"
        atoms += [f"{kinds[0]}({text}*t)", f"{kinds[1]}({text}*t)"]
    coeffs = [
        [str(F(draw(st.integers(-9, 9)), draw(st.integers(1, 5)))) for _ in atoms] for _ in range(4)
    ]
    space = ("mixed-" if mixed else "") + ("hyperbolic" if hyper else "trigonometric")
    hi = draw(st.sampled_from(["1", "1/2", "2"]))
    return atoms, coeffs, space, hi


def _atom_value(atom, t):
    a = ak.parse_atom(atom)
    if a.kind == "1":
        return np.ones_like(t)
    if a.kind == "t":
        return t**a.power
    w = float(a.omega) * (math.pi if a.pi else 1.0)
    return {"cos": np.cos, "sin": np.sin, "cosh": np.cosh, "sinh": np.sinh}[a.kind](w * t)


@settings(max_examples=60, deadline=None)
@given(case=_trig_sums())
def test_random_spaces_evaluate_as_the_sum_of_their_atoms(tmp_path_factory, case):
    atoms, coeffs, space, hi = case
    doc = {
        "format": 4,
        "family": "random_atoms",
        "space": space,
        "parameters": [{"name": "lam", "range": {"lo": "0", "hi": "1", "text": "[0, 1]"}}],
        "domain": {"lo": "0", "hi": hi, "unit": "1"},
        "degrees": [3, 3],
        "atoms": {"3": atoms},
        "coefficients": {"3": {"0": coeffs}},
        "rational": {"reason": "random"},
        "energy": {"reason": "random"},
    }
    from lambda_bezier._atom_document import AtomData
    from lambda_bezier.family import AtomFamily

    fam = AtomFamily(AtomData(doc, "random"), None, "random", {"name": "random_atoms"})
    pts = np.array(PTS, float)
    curve = fam.curve(pts, lam=0)
    t = np.linspace(0, float(F(hi)), 23)
    c = np.array([[float(F(x)) for x in row] for row in coeffs])
    values = np.array([_atom_value(a, t) for a in atoms])  # (A, T)
    want = (c @ values).T @ pts
    got = curve.evaluate(t)
    assert np.abs(got - want).max() <= 1e-12 * (1 + np.abs(want).max())
    h = 1e-6 * float(F(hi))
    inner = t[1:-1]
    fd = (curve.evaluate(inner + h) - curve.evaluate(inner - h)) / (2 * h)
    assert np.abs(curve.derivative(inner) - fd).max() <= 1e-6 * (1 + np.abs(fd).max())


def test_polynomial_only_functions_say_so(families):
    fam = families[AT]
    # optimal_lambda keeps working for a family of one parameter (issue #30): the same
    # minimiser as optimal_parameters, exact in Q(pi); tests/test_acceptance_30.py checks it
    # against mpmath
    one = lb.optimal_lambda(PTS, 2, family=fam, clamp=True)
    assert one.lam == lb.optimal_parameters(PTS, 2, family=fam)["lam"]
    with pytest.raises(TypeError, match="not polynomial"):
        lb.energy_coefficients(PTS, 2, family=fam)
    with pytest.raises(ValueError, match="it has parameters lam, not one lam"):
        lb.CompositeCurve([fam.curve(PTS, lam=0)]).with_lambda(0, 1)
    # surfaces of such families exist now (atom_surfaces; tests/test_param_surfaces.py)
    assert type(fam.surface([[(0, 0, 0)] * 4] * 4, 0, 0)).__name__ == "AtomSurface"
    with pytest.raises(ValueError, match="k must be a positive integer"):
        fam.curve(PTS, lam=0).energy(2.5)
