"""Certified non-negativity of C-Bezier bases over the whole (t, alpha) box (issue #30,
derive/formulas/cbezier_nonnegative.py).

Checked against independent numerics (mpmath at 40 digits of the functions as the file
writes them): the series model with its remainder bound against the exact quotient at random
points, the certified boxes against dense sampling (below the sampling grid of the
derivation, too), a counterexample of a perturbed basis that the derivation's sampling grid
misses, and a box past the interval where the basis is non-negative never certified.
"""

from __future__ import annotations

from fractions import Fraction
from pathlib import Path

import flint
import mpmath as mp
import pytest
import sympy as sp
import tomllib
from conftest import family_file

from derive.families import cbezier as cb
from derive.formulas import cbezier as F
from derive.formulas import cbezier_nonnegative as N

DATA = Path(__file__).parent / "data" / "families"
mp.mp.dps = 40


def _table(name: str) -> dict:
    return tomllib.loads(family_file(name).read_text())["family"]


def _written(defn: cb.CDefinition, i: int):
    return sp.lambdify((cb.T, cb.A), defn.written()[i], modules="mpmath")


@pytest.mark.parametrize("name", ["c_bezier_cubic", "c_bezier_cubic_unit", "hc_bezier_cubic"])
def test_the_paper_boxes_are_certified(name):
    defn = cb.read_table(_table(name))
    got = N.certify(defn, F.zero_order)
    assert got["verdict"] is True and got["method"].startswith("certified")
    assert F.nonnegative(defn)["verdict"] is True
    # dense sampling, down to alpha = 1e-3 (below the derivation's grid) and at the top end
    fs = [_written(defn, i) for i in range(defn.degree + 1)]
    for a in (mp.mpf("0.001"), mp.mpf("0.05"), mp.mpf(1), mp.mpf(2), mp.pi):
        for u in mp.linspace(mp.mpf("0.005"), mp.mpf("0.995"), 41):
            assert all(f(a * u, a) > 0 for f in fs), (name, a, u)


@pytest.mark.parametrize("i", [0, 1, 2, 3])
def test_the_series_model_and_its_bound_against_mpmath(i):
    """Q_i = N_i / (alpha^e u^z0 (1-u)^z1) from the exact series, at points: the exact value
    (mpmath, the written functions times the common denominator) lies within rho."""
    defn = cb.read_table(_table("c_bezier_cubic"))
    nums, den = N._numerators(defn.elems()[i])
    z0, z1 = F.zero_order(defn, i, "lo"), F.zero_order(defn, i, "hi")
    top = Fraction(3927, 1250)
    with flint.ctx.workprec(N.PREC):
        dmodel, e = N._model({(cb.POW, 0): den}, 0, 0, 72, None, False, top)
        model, _ = N._model(nums, z0, z1, 72, e, False, top)
        den_f = sp.lambdify(cb.A, den.subs({cb.S: sp.sin(cb.A), cb.C: sp.cos(cb.A)}), "mpmath")
        f = _written(defn, i)
        for text_a, text_u in [("0.3", "0.1"), ("1.5", "0.5"), ("3.1", "0.9"), ("2.2", "0.02")]:
            a, u = mp.mpf(text_a), mp.mpf(text_u)
            want = f(a * u, a) * den_f(a) / (a**e * u**z0 * (1 - u) ** z1)
            ball = model.value(flint.arb(text_a), flint.arb(text_u))
            rho = float(model.rho(flint.arb(text_a)).upper())
            got = mp.mpf(ball.mid().str(45, radius=False))
            assert abs(got - want) <= rho + mp.mpf(10) ** -30 * (1 + abs(want))
            assert rho < 1e-15


def test_a_perturbed_basis_has_a_certified_counterexample():
    """b_3 - b_2/64 is negative for small u (b_3 ~ u^3, b_2 ~ u^2): inside the first cell of
    the sampling grid (u < 1/32), so only the certificate finds it."""
    table = _table("c_bezier_cubic")
    fs = list(table["functions"])
    fs[3] = f"{fs[3]} - ({fs[2]})/64"
    defn = cb.read_table({**table, "name": "perturbed", "functions": fs})
    got = N.certify(defn, F.zero_order)
    assert got["verdict"] is False
    cex = got["counterexample"]
    assert cex["i"] == 3
    # checked again, independently, at 40 digits
    assert _written(defn, 3)(mp.mpf(cex["t_float"]), mp.mpf(cex["alpha_float"])) < 0


def test_a_box_past_two_pi_is_never_certified():
    table = {**_table("c_bezier_cubic"), "range": "(0, 3*pi]"}
    got = N.certify(cb.read_table(table), F.zero_order)
    assert got["verdict"] is not True and ("reason" in got or "counterexample" in got)
