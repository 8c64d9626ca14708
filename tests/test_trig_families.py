"""Trigonometric, hyperbolic and mixed families (issue #30): the format-4 documents that
`lambda-bezier derive --family` writes for tests/data/families/{han_trig_cubic,
hyp_two_shape_cubic, at_pi_cubic}.toml, checked against each family's own construction by
independent numerics (mpmath: direct evaluation, numerical derivatives, quadrature, singular
values), never against derive's own arithmetic."""

from __future__ import annotations

import json
import os
import random
import re
import subprocess
import sys
from pathlib import Path

import mpmath as mp
import pytest

from derive.emit.document import derive as derive_document
from derive.emit.document import render
from derive.families.definition import read_definition

DATA = Path(__file__).parent / "data" / "families"


@pytest.fixture(autouse=True)
def _precision():
    """40 digits in this module's tests only (mpmath's precision is global)."""
    with mp.workdps(40):
        yield


# --------------------------------------------------------------------------- the constructions


def _han(lam, mu):
    s, c = mp.sin, mp.cos
    return [
        lambda t: (1 - s(t)) ** 2 * (1 - lam * s(t)),
        lambda t: s(t) * (1 - s(t)) * (2 + lam - lam * s(t)),
        lambda t: c(t) * (1 - c(t)) * (2 + mu - mu * c(t)),
        lambda t: (1 - c(t)) ** 2 * (1 - mu * c(t)),
    ]


def _hyp(lam, mu):
    def x(t):
        return 1 - mp.exp(-t)

    return [
        lambda t: (1 - lam * x(t)) * (1 - x(t)) ** 3,
        lambda t: x(t) * (1 - x(t)) ** 2 * (3 + lam * (1 - x(t))),
        lambda t: x(t) ** 2 * (1 - x(t)) * (3 + mu * x(t)),
        lambda t: (1 - mu + mu * x(t)) * x(t) ** 3,
    ]


def _at_pi(lam):
    def b1(t):
        return (1 - lam) * (mp.sin(mp.pi * t / 2) - t)

    def b2(t):
        return (1 - lam) * (mp.cos(mp.pi * t / 2) - 1 + t)

    return [lambda t: 1 - t - b1(t), b1, b2, lambda t: t - b2(t)]


CONSTRUCTIONS = {
    "han_trig_cubic": (lambda p: _han(*p), lambda: (mp.mpf(0), mp.pi / 2)),
    "hyp_two_shape_cubic": (lambda p: _hyp(*p), lambda: (mp.mpf(0), mp.mpf(1))),
    "at_pi_cubic": (lambda p: _at_pi(*p), lambda: (mp.mpf(0), mp.mpf(1))),
}
FAMILIES = sorted(CONSTRUCTIONS)


def _family(name: str):
    """The construction and the domain, at the working precision of the test."""
    build, domain = CONSTRUCTIONS[name]
    return build, domain()


# --------------------------------------------------------------------------- reading a document


def _doc(name: str) -> dict:
    return json.loads((DATA / f"{name}.derived.json").read_text(encoding="utf-8"))


def _constant(text: str):
    if text == "pi":
        return mp.pi
    m = re.fullmatch(r"exp\((.+)\)", text)
    assert m, text
    return mp.exp(mp.mpf(mp.fraction(*map(int, (m.group(1) + "/1").split("/")[:2]))))


def _number(value, const):
    if isinstance(value, str):
        num, _, den = value.partition("/")
        return mp.mpf(int(num)) / int(den or 1)
    return mp.fsum(_number(c, const) * const**e for c, e in value)


def _atom(text: str):
    if text == "1":
        return lambda t: mp.mpf(1)
    if text.startswith("t^"):
        k = int(text[2:])
        return lambda t: t**k
    m = re.fullmatch(r"(cos|sin|cosh|sinh)\(([0-9/]+)(\*pi)?\*t\)", text)
    assert m, text
    num, _, den = m.group(2).partition("/")
    w = mp.mpf(int(num)) / int(den or 1) * (mp.pi if m.group(3) else 1)
    f = getattr(mp, m.group(1))
    return lambda t: f(w * t)


def _monomial(key: str, params) -> mp.mpf:
    out = mp.mpf(1)
    for x, e in zip(params, map(int, key.split(",")), strict=True):
        out *= mp.mpf(x) ** e
    return out


def _doc_basis(doc: dict, params):
    (n,) = doc["atoms"]
    atoms = [_atom(a) for a in doc["atoms"][n]]
    table = doc["coefficients"][n]

    def b(i, t):
        return mp.fsum(
            _monomial(mono, params) * _number(c, None) * atom(t)
            for mono, rows in table.items()
            for c, atom in zip(rows[i], atoms, strict=True)
            if c != "0"
        )

    return b


def _points(doc: dict, count: int = 3, seed: int = 0) -> list[tuple]:
    """Parameter points of the box: its corners and random rationals inside."""
    rng = random.Random(seed)
    out = []
    ranges = [
        (mp.mpf(_number(q["range"]["lo"], None)), mp.mpf(_number(q["range"]["hi"], None)))
        for q in doc["parameters"]
    ]
    for _ in range(count):
        out.append(tuple(lo + (hi - lo) * mp.mpf(rng.randint(1, 99)) / 100 for lo, hi in ranges))
    return out


# --------------------------------------------------------------------------- the tests


@pytest.mark.parametrize("name", FAMILIES)
def test_document_is_the_derivation(name):
    defn = read_definition(DATA / f"{name}.toml")
    assert (DATA / f"{name}.derived.json").read_text(encoding="utf-8") == render(defn)
    assert _doc(name)["format"] == 4


@pytest.mark.parametrize("name", FAMILIES)
def test_atom_table_is_the_construction(name):
    doc = _doc(name)
    build, (lo, hi) = _family(name)
    for params in _points(doc):
        direct, table = build(params), _doc_basis(doc, params)
        for t in mp.linspace(lo, hi, 7):
            for i, f in enumerate(direct):
                assert abs(table(i, t) - f(t)) < mp.mpf(10) ** -30
            assert abs(mp.fsum(f(t) for f in direct) - 1) < mp.mpf(10) ** -30


@pytest.mark.parametrize("name", FAMILIES)
def test_end_derivatives_match_numerical_derivatives(name):
    doc = _doc(name)
    build, (lo, hi) = _family(name)
    (n,) = doc["atoms"]
    const = _constant(doc["endpoints"]["constant"])
    for params in _points(doc, 2):
        direct = build(params)
        for key, value in doc["endpoints"][n].items():
            end, r, j = key.split(",")
            idx = int(j) if end == "start" else int(n) - int(j)
            at = lo if end == "start" else hi
            exact = mp.fsum(_monomial(m, params) * _number(v, const) for m, v in value.items())
            numeric = mp.diff(direct[idx], at, int(r))
            assert abs(exact - numeric) < mp.mpf(10) ** -20 * (1 + abs(numeric)), key


@pytest.mark.parametrize("name", FAMILIES)
def test_energies_match_quadrature(name):
    doc = _doc(name)
    build, (lo, hi) = _family(name)
    (n,) = doc["atoms"]
    rng = random.Random(1)
    control = [[mp.mpf(rng.randint(-9, 9)) for _ in range(2)] for _ in range(int(n) + 1)]
    (params,) = _points(doc, 1, seed=2)
    direct = build(params)
    with mp.workdps(25):
        for k in (1, 2, 3):
            entry = doc["energy"][f"{n},{k}"]
            const = _constant(entry["constant"])
            exact = mp.mpf(0)
            for pair, gram in entry["gram"].items():
                m1, m2 = pair.split("|")
                w = _monomial(m1, params) * _monomial(m2, params)
                for i, row in enumerate(gram):
                    for j, v in enumerate(row):
                        dot = sum(control[i][d] * control[j][d] for d in range(2))
                        exact += w * _number(v, const) * dot

            def speed2(t, k=k):
                ders = [mp.diff(f, t, k) for f in direct]
                return sum(
                    mp.fsum(control[i][d] * ders[i] for i in range(len(direct))) ** 2
                    for d in range(2)
                )

            numeric = mp.quad(speed2, [lo, (lo + hi) / 2, hi])
            assert abs(exact - numeric) < mp.mpf(10) ** -12 * abs(numeric), k


def test_han_rational_form_is_the_basis():
    doc = _doc("han_trig_cubic")
    rational = doc["rational"]
    assert rational["substitution"] == "tan(t/2)" and rational["scale"] == "1"
    weights = [_number(w, None) for w in rational["weights"]["3"]]
    big = rational["degree"]["3"]
    assert all(w > 0 for w in weights)
    for params in _points(doc):
        direct = _han(*params)
        for s in mp.linspace(0, 1, 9):
            bern = [mp.binomial(big, j) * s**j * (1 - s) ** (big - j) for j in range(big + 1)]
            den = mp.fsum(w * b for w, b in zip(weights, bern, strict=True))
            t = 2 * mp.atan(s)
            for i, f in enumerate(direct):
                num = mp.fsum(
                    _monomial(mono, params) * _number(c, None) * b
                    for mono, rows in rational["numerators"]["3"].items()
                    for c, b in zip(rows[i], bern, strict=True)
                )
                assert abs(num / den - f(t)) < mp.mpf(10) ** -30


@pytest.mark.parametrize("name", FAMILIES)
def test_symmetry_as_documented(name):
    doc = _doc(name)
    build, (lo, hi) = _family(name)
    names = [q["name"] for q in doc["parameters"]]
    swap = doc["symmetry"]
    if name == "hyp_two_shape_cubic":  # x = 1 - e^(-t) has no mirror on [0, 1]
        assert swap is None
        (params,) = _points(doc, 1)
        assert abs(build(params)[0](mp.mpf(1) / 3) - build(params)[3](hi - mp.mpf(1) / 3)) > 0.01
        return
    for params in _points(doc):
        value = dict(zip(names, params, strict=True))
        swapped = [-value[s[1:]] if s.startswith("-") else value[s] for s in swap["swap"]]
        direct, mirrored = build(params), build(swapped)
        for t in mp.linspace(lo, hi, 5):
            for i in range(len(direct)):
                assert abs(direct[i](t) - mirrored[len(direct) - 1 - i](lo + hi - t)) < 1e-30


@pytest.mark.parametrize("name", FAMILIES)
def test_nonnegativity_and_independence_agree_with_sampling(name):
    doc = _doc(name)
    build, (lo, hi) = _family(name)
    ranges = [(q["range"]["lo"], q["range"]["hi"]) for q in doc["parameters"]]
    corners = [
        tuple(_number(c[j], None) for c, j in zip(ranges, js, strict=True))
        for js in ([0] * len(ranges), [1] * len(ranges), [0, 1][: len(ranges)])
    ]
    verdict = doc["nonnegative_over_box"]
    if verdict.get("nonnegative"):
        for params in corners + _points(doc, 4, seed=3):
            for f in build(params):
                assert min(f(t) for t in mp.linspace(lo, hi, 41)) > -(mp.mpf(10) ** -30)
    # independence: singular values of the functions sampled at 12 points (no atom table)
    ts = mp.linspace(lo, hi, 12)
    singular = doc["linear_independence"]["singular"]
    assert doc["linear_independence"]["independent"] is (not singular)
    for params in _points(doc, 3, seed=4):
        sample = mp.matrix([[f(t) for t in ts] for f in build(params)])
        assert min(mp.svd_r(sample, compute_uv=False)) > mp.mpf(10) ** -8
    for point in singular:
        values = (
            [point[q["name"]] for q in doc["parameters"]] if isinstance(point, dict) else [point]
        )
        params = [_number(v, None) for v in values]
        sample = mp.matrix([[f(t) for t in ts] for f in build(params)])
        assert min(mp.svd_r(sample, compute_uv=False)) < mp.mpf(10) ** -30


def test_expected_verdicts():
    """What the three documents decide (each verdict also sampled above)."""
    han, hyp, at = (_doc(n) for n in ("han_trig_cubic", "hyp_two_shape_cubic", "at_pi_cubic"))
    assert (han["space"], hyp["space"], at["space"]) == (
        "trigonometric",
        "hyperbolic",
        "mixed-trigonometric",
    )
    assert han["symmetry"]["swap"] == ["mu", "lam"] and at["symmetry"]["swap"] == ["lam"]
    assert han["nonnegative_over_box"] == {"nonnegative": True}
    assert hyp["nonnegative_over_box"] == {"nonnegative": True}
    assert at["nonnegative_over_box"] == {"nonnegative": True}  # atom_nonnegative
    assert han["linear_independence"] == {"independent": True, "singular": []}
    # at lam = mu = -3 the hyperbolic basis is dependent; at_pi's lam = 1 is outside [0, 1)
    assert hyp["linear_independence"]["singular"] == [{"lam": "-3", "mu": "-3"}]
    assert at["linear_independence"] == {"independent": True, "singular": []}
    assert "reason" in hyp["rational"] and "reason" in at["rational"]
    assert han["energy"]["3,1"]["constant"] == "pi"
    assert hyp["energy"]["3,1"]["constant"] == "exp(1)"


def test_negative_counterexamples_are_negative(tmp_path):
    for name, old, new in (
        ("han_trig_cubic", 'lam = "[-2, 1]"', 'lam = "[-2, 3]"'),
        ("hyp_two_shape_cubic", 'lam = "[-3, 1]"', 'lam = "[-4, 1]"'),
    ):
        text = (DATA / f"{name}.toml").read_text(encoding="utf-8").replace(old, new)
        path = tmp_path / f"{name}.toml"
        path.write_text(text.replace(f'name = "{name}"', 'name = "widened"'), encoding="utf-8")
        doc = derive_document(read_definition(path))
        verdict = doc["nonnegative_over_box"]
        assert verdict["nonnegative"] is False, verdict
        cx = verdict["counterexample"]
        params = [_number(cx[q["name"]], None) for q in doc["parameters"]]
        m = re.fullmatch(r"(.*)\*pi \+ 2\*atan\((.*)\)/\((.*)\)", cx["t"]) or re.fullmatch(
            r"log\((.*)\)", cx["t"]
        )
        assert m, cx["t"]
        if name == "han_trig_cubic":
            t = _number(m.group(1), None) * mp.pi + 2 * mp.atan(_number(m.group(2), None))
            value = _han(*params)[cx["i"]](t)
            assert abs(value - _number(cx["value"], None)) < 1e-30
        else:
            t = mp.log(_number(m.group(1), None))
            value = _hyp(*params)[cx["i"]](t)
        assert value < 0


def test_byte_identical_under_any_hash_seed(tmp_path):
    for seed in ("0", "4242"):
        env = {**os.environ, "PYTHONHASHSEED": seed}
        got = subprocess.run(
            [
                sys.executable,
                "-m",
                "lambda_bezier",
                "derive",
                "--family",
                str(DATA / "han_trig_cubic.toml"),
                "--check",
                "-q",
            ],
            env=env,
            capture_output=True,
            text=True,
            cwd=Path(__file__).parents[1],
        )
        assert got.returncode == 0, got.stdout + got.stderr
