"""Ill-defined trigonometric, hyperbolic and mixed definitions are refused with a message that
names the key and the term (issue #30), and random valid ones derive without a traceback."""

from __future__ import annotations

import json
from fractions import Fraction
from math import comb

import pytest
from definition_checks import assert_refused
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from derive.emit.document import derive as derive_document
from derive.families.definition import DefinitionError, definition_from_table

HAN = [
    "(1 - sin(t))**2 * (1 - lam*sin(t))",
    "sin(t)*(1 - sin(t))*(2 + lam - lam*sin(t))",
    "cos(t)*(1 - cos(t))*(2 + lam - lam*cos(t))",
    "(1 - cos(t))**2 * (1 - lam*cos(t))",
]
GOOD = {
    "name": "trig_fam",
    "parameters": ["lam"],
    "range": {"lam": "[-2, 1]"},
    "domain": "[0, pi/2]",
    "degrees": "3",
    "functions": HAN,
}


def _swap(k: int, text: str) -> list[str]:
    return [text if j == k else f for j, f in enumerate(HAN)]


ILL_DEFINED = {
    "no partition of unity": (
        {"functions": ["1 - sin(t)", "sin(t)", "cos(t)", "1 - cos(t)"]},
        "key functions: no partition of unity: the functions sum to 2",
    ),
    "wrong count": ({"functions": HAN[:3]}, "the basis of degree 3 has 4 functions, got 3"),
    "t times sin": (
        {"functions": _swap(0, "t*sin(t)")},
        "key functions[0]: t*sin(1*t) is not in a space this version decides",
    ),
    "exp times sin": (
        {"functions": _swap(1, "exp(t)*sin(t)")},
        "trigonometric and hyperbolic functions together",
    ),
    "two units": ({"functions": _swap(1, "sin(pi*t)")}, "no common period"),
    "ends not rational": (
        {"domain": "[0, pi/3]"},
        "key domain: [0, pi/3] with the base rate 1: the values at the ends are not rational",
    ),
    "domain in t without pi": ({"domain": "[0, 1]"}, "key domain: [0, 1] with the base rate"),
    "domain not closed": ({"domain": "(0, pi/2]"}, "key domain: '(0, pi/2]' is not a closed"),
    "domain units mixed": ({"domain": "[1, pi]"}, "both ends are rationals or both"),
    "domain empty": ({"domain": "[pi/2, 0]"}, "the interval [pi/2, 0] is empty"),
    "domain not a number": ({"domain": "[0, e]"}, "key domain: unknown name 'e'"),
    "polynomial off [0, 1]": (
        {"functions": ["(1 - t)**3", "3*t*(1 - t)**2", "3*t**2*(1 - t)", "t**3"]},
        "a polynomial basis is derived on [0, 1] only",
    ),
    "rate not rational": (
        {"functions": _swap(0, "sin(pi*pi*t)")},
        "the argument must be a rational multiple of t or of pi*t",
    ),
    "parameter inside sin": (
        {"functions": _swap(0, "sin(lam*t)")},
        "sin(lam*t): the argument must be a rational multiple of t",
    ),
    "sin of t squared": ({"functions": _swap(0, "sin(t**2)")}, "sin(t**2): the argument"),
    "tan": ({"functions": _swap(0, "tan(t)")}, "key functions[0]: unknown name 'tan'"),
    "pi as a coefficient": ({"functions": _swap(0, "pi*sin(t)")}, "pi enters only in an argument"),
    "division by cos": ({"functions": _swap(0, "1/cos(t)")}, "a division by a function of t"),
    "huge power": ({"functions": _swap(0, "sin(t)**500")}, "a power of a function of t above 64"),
    "huge rate": ({"functions": _swap(0, "sin(2000*t)")}, "a rate larger than 1000"),
    "bernstein_at": ({"bernstein_at": "0"}, "key bernstein_at: not used by a trigonometric"),
    "hyperbolic on pi": (
        {"functions": ["exp(-t)", "1 - exp(-t)"], "degrees": "1"},
        "key domain: [0, pi/2]: a hyperbolic basis has a rational domain",
    ),
}


@pytest.mark.parametrize("case", list(ILL_DEFINED))
def test_ill_defined_trigonometric_definitions(case):
    change, needle = ILL_DEFINED[case]
    assert_refused({**GOOD, **change}, [needle])


def test_good_table_derives():
    doc = derive_document(definition_from_table(GOOD))
    assert doc["format"] == 4 and doc["symmetry"]["swap"] == ["lam"]


# --------------------------------------------------------------------------- random definitions

# Bernstein polynomials in a variable x(t) that runs over [0, 1] on the domain, then a random
# zero-sum perturbation lam * c_i * g(t): a partition of unity for every lam
SPACES = {
    "trig": ("[0, pi/2]", "sin(t)**2", ["sin(2*t)", "cos(t)", "cos(t)**3", "sin(t)*cos(3*t)"]),
    "trig-pi": ("[0, 1]", "(1 - cos(pi*t/2))", ["sin(pi*t/2)", "cos(pi*t)", "sin(pi*t)**2"]),
    "trig-wide": ("[-3*pi/2, 3*pi/2]", "(1 + sin(t/3))/2", ["cos(t/3)", "sin(2*t/3)"]),
    "hyp": ("[0, 1]", "(1 - exp(-t))", ["sinh(t)", "cosh(2*t)", "exp(t/2)"]),
    "hyp-shift": ("[-1, 2]", "(1 - exp(-t))", ["sinh(t)**2", "cosh(t/2)"]),
    "mixed": ("[0, pi/2]", "sin(t)", ["t", "t**2", "cos(t)"]),
    "mixed-hyp": ("[0, 1]", "t", ["sinh(t)", "t**3", "exp(-t)"]),
}


@st.composite
def definitions(draw):
    kind = draw(st.sampled_from(sorted(SPACES)))
    domain, x, extras = SPACES[kind]
    n = draw(st.integers(1, 3))
    coeffs = draw(st.lists(st.integers(-3, 3), min_size=n, max_size=n))
    coeffs.append(-sum(coeffs))
    g = draw(st.sampled_from(extras))
    lo = draw(st.sampled_from(["-1", "0", "1/2"]))
    funcs = []
    for i in range(n + 1):
        base = f"{Fraction(__import__('math').comb(n, i))}*({x})**{i}*(1 - ({x}))**{n - i}"
        funcs.append(f"{base} + lam*({coeffs[i]})*({g})")
    return {
        "name": "random_fam",
        "parameters": ["lam"],
        "range": {"lam": f"[{lo}, 1]"},
        "domain": domain,
        "degrees": str(n),
        "functions": funcs,
    }


@settings(
    max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow], derandomize=True
)
@given(definitions())
def test_random_valid_definitions_derive(table):
    try:
        doc = derive_document(definition_from_table(table))
    except DefinitionError as exc:  # a clear refusal is allowed, a traceback is not
        assert str(exc).startswith("[family]"), str(exc)
        return
    text = json.dumps(doc)
    assert doc["format"] == 4 and "NaN" not in text
    assert doc["checked"][1].startswith("partition of unity")


def test_independence_of_a_larger_family_is_decided():
    """n = 6 (15 atoms, 5005 maximal minors): decided from a few pivot minors, and the
    verdict agrees with singular values of the functions sampled at points of the box."""
    import mpmath as mp

    n = 6
    x = "sin(t)**2"
    funcs = [f"{comb(n, i)}*({x})**{i}*(1 - {x})**{n - i}" for i in range(n + 1)]
    funcs[0] += " + lam*cos(t)*(1 - sin(t))"
    funcs[1] += " - lam*cos(t)*(1 - sin(t))"
    funcs[-1] += " + mu*sin(t)*(1 - cos(t))"
    funcs[-2] += " - mu*sin(t)*(1 - cos(t))"
    table = {
        "name": "wide",
        "parameters": ["lam", "mu"],
        "range": {"lam": "[0, 1]", "mu": "[0, 1]"},
        "domain": "[0, pi/2]",
        "degrees": str(n),
        "functions": funcs,
    }
    doc = derive_document(definition_from_table(table))
    assert doc["linear_independence"] == {"independent": True, "singular": []}
    s, c = mp.sin, mp.cos
    for lam, mu in ((0, 0), (1, 1), (0.3, 0.8), (1, 0)):
        rows = []
        for i in range(n + 1):
            row = []
            for t in mp.linspace(0.01, mp.pi / 2 - 0.01, 2 * n + 4):
                v = comb(n, i) * s(t) ** (2 * i) * (1 - s(t) ** 2) ** (n - i)
                v += {0: lam, 1: -lam}.get(i, 0) * c(t) * (1 - s(t))
                v += {n: mu, n - 1: -mu}.get(i, 0) * s(t) * (1 - c(t))
                row.append(v)
            rows.append(row)
        assert min(mp.svd_r(mp.matrix(rows), compute_uv=False)) > 1e-12


def test_verify_checks_records_about_a_trigonometric_family():
    """verify used to refuse these families; it now checks their records (issue #30,
    derive/verify/checks_elementary.py; the records themselves: test_elementary_verify.py)."""
    import subprocess
    import sys
    from pathlib import Path

    root = Path(__file__).parents[1]
    got = subprocess.run(
        [
            sys.executable,
            "-m",
            "lambda_bezier",
            "verify",
            "tests/data/families/at_pi_cubic.toml",
            "tests/data/families/at_pi_cubic.records.toml",
        ],
        cwd=root,
        capture_output=True,
        text=True,
    )
    assert got.returncode == 0, got.stdout + got.stderr
    assert "6 match" in got.stdout, got.stdout
