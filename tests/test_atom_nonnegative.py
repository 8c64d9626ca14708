"""Non-negativity over the parameter box of mixed (algebraic-trigonometric) bases and of
bases not affine in their parameters (issue #30): derive/formulas/atom_nonnegative.py's
certified branch and bound, its verdicts in the documents, each counterexample re-evaluated
by mpmath from the definition's own formulas, and agreement with the exact deciders where
those apply (trigonometric and hyperbolic bases affine in their parameters)."""

from __future__ import annotations

import json
from fractions import Fraction
from pathlib import Path

import mpmath as mp
import pytest

from derive.emit.document import derive as derive_document
from derive.families.definition import read_definition
from derive.families.spaces import space_of
from derive.formulas import atom_family as F
from derive.formulas.atom_nonnegative import nonnegative_elementary

DATA = Path(__file__).parent / "data" / "families"
mp.mp.dps = 40


def _at_pi(lam, t):
    """at_pi_cubic.toml's functions, written out again (x = pi t / 2)."""
    s, c = mp.sin(mp.pi * t / 2), mp.cos(mp.pi * t / 2)
    b1 = (1 - lam) * (s - t)
    b2 = (1 - lam) * (c - 1 + t)
    return [1 - t - b1, b1, b2, t - b2]


def _at(lam, t):
    """at_cubic.toml's functions."""
    s, c = mp.sin(t), mp.cos(t)
    inner = (s + c - 1) / 2
    return [1 - s, inner + lam * (t - s), inner - lam * (t - s), 1 - c]


def _square(lam, t):
    """trig_square_quadratic.toml's functions (lam squared)."""
    s, c = mp.sin(t), mp.cos(t)
    return [1 - s - lam**2 * s * c, s + c - 1 + (lam**2 + lam) * s * c, 1 - c - lam * s * c]


def _t(text: str):
    return mp.pi * _mpq(text[: -len("*pi")]) if text.endswith("*pi") else _mpq(text)


def _mpq(text: str):
    q = Fraction(text)
    return mp.mpf(q.numerator) / q.denominator


def _doc(name: str) -> dict:
    return json.loads((DATA / f"{name}.derived.json").read_text(encoding="utf-8"))


def test_mixed_nonnegative_family():
    """at_pi_cubic is non-negative for lam in [0, 1) (its file says why); mpmath agrees on a
    grid of parameters and t, end zeros included."""
    assert _doc("at_pi_cubic")["nonnegative_over_box"] == {"nonnegative": True}
    for lam in mp.linspace(0, 1, 9):
        for t in mp.linspace(0, 1, 81):
            assert min(_at_pi(lam, t)) > -(mp.mpf(10) ** -30)


def test_mixed_counterexample_is_negative():
    verdict = _doc("at_cubic")["nonnegative_over_box"]
    assert verdict["nonnegative"] is False
    cx = verdict["counterexample"]
    value = _at(_mpq(cx["lam"]), _t(cx["t"]))[cx["i"]]
    assert value < 0
    assert value <= float(cx["value_upper_bound"]) * (1 - 1e-6)


def test_widened_range_gives_a_counterexample_inside_it(tmp_path):
    """at_pi_cubic with lam down to -1: b_0 = 1 + t - 2 sin(pi t/2) < 0 near t = 0.8; the
    point reported lies inside the widened, half-open range."""
    text = (DATA / "at_pi_cubic.toml").read_text(encoding="utf-8")
    path = tmp_path / "w.toml"
    path.write_text(text.replace('lam = "[0, 1)"', 'lam = "[-1, 1)"'), encoding="utf-8")
    verdict = derive_document(read_definition(path))["nonnegative_over_box"]
    cx = verdict["counterexample"]
    lam = Fraction(cx["lam"])
    assert -1 <= lam < 1
    assert _at_pi(_mpq(cx["lam"]), _t(cx["t"]))[cx["i"]] < 0


def test_open_end_counterexample_moves_inside(tmp_path):
    """A negative vertex on an open end of the range is moved inwards (still negative)."""
    text = (DATA / "at_pi_cubic.toml").read_text(encoding="utf-8")
    path = tmp_path / "w.toml"
    path.write_text(text.replace('lam = "[0, 1)"', 'lam = "(-1, 1)"'), encoding="utf-8")
    cx = derive_document(read_definition(path))["nonnegative_over_box"]["counterexample"]
    lam = Fraction(cx["lam"])
    assert -1 < lam < 1
    assert _at_pi(_mpq(cx["lam"]), _t(cx["t"]))[cx["i"]] < 0


def test_not_affine_counterexample():
    verdict = _doc("trig_square_quadratic")["nonnegative_over_box"]
    cx = verdict["counterexample"]
    assert -1 <= Fraction(cx["lam"]) <= 1
    assert _square(_mpq(cx["lam"]), _t(cx["t"]))[cx["i"]] < 0
    assert _doc("hyp_square_quadratic")["nonnegative_over_box"]["nonnegative"] is False


@pytest.mark.parametrize(
    "name", ["han_trig_cubic", "hyp_two_shape_cubic", "hyp_cubic", "hyp_shift_quadratic"]
)
def test_branch_and_bound_agrees_with_the_exact_deciders(name):
    defn = read_definition(DATA / f"{name}.toml")
    space = space_of(defn)
    exact = F.nonnegative_over_box(defn, space)
    certified = nonnegative_elementary(defn, space)
    assert exact["nonnegative"] is certified["nonnegative"]
