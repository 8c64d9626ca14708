"""Random valid definitions in several parameters (bases that sum to one by construction)
and random broken ones: derive either succeeds or says what is wrong (DefinitionError), and
what it derives evaluates in the runtime as the formulas do. Never a traceback."""

from __future__ import annotations

import importlib
import json
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

from lambda_bezier import _derive_runner
from lambda_bezier.family import Family, SeveralData

ROOT = Path(__file__).resolve().parent.parent
pytestmark = pytest.mark.skipif(
    not (ROOT / "derive" / "families" / "engine.py").is_file(), reason="needs the source checkout"
)


def _derive(name: str):
    return importlib.import_module(f"{_derive_runner.load_derive(ROOT).__name__}.{name}")


def _term(draw, names):
    coef = draw(st.integers(-3, 3))
    te = draw(st.integers(0, 3))
    mono = "*".join(f"{x}**{draw(st.integers(0, 1))}" for x in names)
    return f"({coef})*t**{te}*{mono}"


@st.composite
def tables(draw):
    names = draw(st.sampled_from([["lam", "mu"], ["mu", "nu", "rho"]]))
    n = draw(st.integers(1, 3))
    funcs = [
        " + ".join(_term(draw, names) for _ in range(draw(st.integers(1, 3)))) for _ in range(n)
    ]
    funcs[0] += f" + t**{n + 3}"  # the stated degree n + degree_offset is reached
    last = "1 - (" + ") - (".join(funcs) + ")"
    table = {
        "name": "random_family",
        "parameters": names,
        "range": {x: draw(st.sampled_from(["[-1, 1]", "[0, 1/2]", "(0, 2]"])) for x in names},
        "degrees": str(n),
        "degree_offset": 3,
        "functions": [*funcs, last],
    }
    broken = draw(st.sampled_from([None, "sum", "symbol", "offset", "text"]))
    if broken == "sum":
        table["functions"][-1] += " + t"
    elif broken == "symbol":
        table["functions"][0] += " + zeta"
    elif broken == "offset":
        table["degree_offset"] = 0
    elif broken == "text":
        table["functions"][0] += " +* ("
    return table


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(tables())
@example(  # found by hypothesis: basis functions without a root in [0, 1]
    {
        "name": "random_family",
        "parameters": ["lam", "mu"],
        "range": {"lam": "[-1, 1]", "mu": "[-1, 1]"},
        "degrees": "1",
        "degree_offset": 3,
        "functions": ["(1)*t**0*lam**0*mu**0 + t**4", "1 - ((1)*t**0*lam**0*mu**0 + t**4)"],
    }
)
def test_random_several_parameter_definitions(table):
    definition, document = _derive("families.definition"), _derive("emit.document")
    try:
        defn = definition.definition_from_table(table, "random.toml")
        doc = json.loads(json.dumps(document.derive(defn)))
    except definition.DefinitionError as exc:
        assert "[family]" in str(exc)
        return
    data = SeveralData(doc, "random.derived.json")
    fam = Family(data, Path("random.toml"), "", data.NAMES[0], several=data)
    n = int(table["degrees"])
    values = {
        x: Fraction(1, 3) if "(" not in table["range"][x] else Fraction(1) for x in data.NAMES
    }
    pts = [(i, (i * i) % 3) for i in range(n + 1)]
    c = fam.curve(pts, params=values)
    # the curve at t = 2/5 against the basis formulas of the document, exactly
    t = Fraction(2, 5)
    env = {"t": t, **values}
    import sympy as sp  # the test's own reading of our output

    want = [
        sum(
            sp.Rational(
                str(sp.sympify(f).subs({sp.Symbol(k): sp.Rational(str(v)) for k, v in env.items()}))
            )
            * p[d]
            for f, p in zip(doc["basis"][str(n)], pts, strict=True)
        )
        for d in range(2)
    ]
    np.testing.assert_allclose(c.evaluate(float(t)), [float(w) for w in want], atol=1e-12)
