"""Join weights from the derived documents of several-parameter, indexed and atom families
(issue #30): the runtime's derived weights agree with the per-degree solve on random points
and parameters, and the joined curves meet their conditions by finite differences."""

from __future__ import annotations

from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import lambda_bezier as lb
from lambda_bezier import _derived_joins

DATA = Path(__file__).parent / "data" / "families"
FAMILIES = {
    name: lb.load_family(DATA / f"{name}.toml")
    for name in ("han_trig_cubic", "hyp_two_shape_cubic", "at_pi_cubic", "per_leg_cubic")
}
FAMILIES["q_bezier"] = lb.load_family(DATA / "q_bezier.toml").at_degree(3)  # type: ignore[union-attr]
CONTINUITIES = ("C1", "C2", "G1", "G2")


def _inside(fam: object, draw: st.DataObject) -> dict[str, Fraction]:
    """Parameter values strictly inside the family's box (exact)."""
    data = getattr(fam, "atom_data", None) or fam.several  # type: ignore[attr-defined]
    out = {}
    for name in fam.parameters:  # type: ignore[attr-defined]
        lo, hi = data.RANGES[name][:2]
        k = draw.draw(st.integers(1, 9), label=name)
        out[name] = lo + (hi - lo) * Fraction(k, 10)
    return out


def _ends(curve: object, at_end: bool, h: float = 1e-4) -> tuple[np.ndarray, ...]:
    """(C, C', C'') at the end (or start) of the curve's domain, by one-sided differences
    of order 2 from evaluate() alone."""
    lo, hi = getattr(curve, "domain", (0.0, 1.0))
    s = -1.0 if at_end else 1.0
    x0 = hi if at_end else lo
    f = [np.asarray(curve.evaluate(x0 + s * k * h), dtype=float) for k in range(4)]  # type: ignore[attr-defined]
    d1 = s * (-3 * f[0] + 4 * f[1] - f[2]) / (2 * h)
    d2 = (2 * f[0] - 5 * f[1] + 4 * f[2] - f[3]) / h**2
    return f[0], d1, d2


def _curvature(d1: np.ndarray, d2: np.ndarray) -> float:
    cross = d1[0] * d2[1] - d1[1] * d2[0]
    return float(cross / np.linalg.norm(d1) ** 3)


def _join_both(curve, cont, degree, family, params, rest, monkeypatch, **kw):
    """The join by the derived weights (checked to be used) and by the per-degree solve."""
    used = []
    real = _derived_joins.lookup

    def spy(*args):
        got = real(*args)
        used.append(got is not None)
        return got

    with monkeypatch.context() as mp:
        mp.setattr(_derived_joins, "lookup", spy)
        derived = lb.join(curve, cont, degree, family=family, rest=rest, params=params, **kw)
    with monkeypatch.context() as mp:
        mp.setattr(_derived_joins, "lookup", lambda *a: None)
        solved = lb.join(curve, cont, degree, family=family, rest=rest, params=params, **kw)
    assert any(used), "the derived weights were not used"
    return derived, solved


def _extra(cont: str) -> dict:
    return {
        "G1": {"alpha": Fraction(3, 2)},
        "G2": {"alpha": Fraction(2, 3), "d": Fraction(-1, 2)},
    }.get(cont, {})


@pytest.mark.parametrize("name", sorted(FAMILIES))
@pytest.mark.parametrize("cont", CONTINUITIES)
@settings(
    max_examples=4, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture]
)
@given(draw=st.data())
def test_derived_weights_agree_with_the_solve(name, cont, draw, monkeypatch):
    fam = FAMILIES[name]
    pts = draw.draw(
        st.lists(st.tuples(st.integers(-9, 9), st.integers(-9, 9)), min_size=4, max_size=4),
        label="points",
    )
    first = fam.curve(pts, params=_inside(fam, draw))
    order = 1 if cont in ("C1", "G1") else 2
    rest = [(7, 1), (8, -2), (9, 0)][: 3 - order]
    try:
        derived, solved = _join_both(
            first, cont, 3, fam, _inside(fam, draw), rest, monkeypatch, **_extra(cont)
        )
    except ValueError as exc:  # a degenerate end or singular stencil: both paths must say so
        assert "cannot" in str(exc) or "degenerate" in str(exc)
        return
    scale = 1 + np.abs(solved.points).max()
    assert np.abs(derived.points - solved.points).max() <= 1e-9 * scale
    # the built-in families on the other side, in both directions
    for other, lam in (("bernstein_like", Fraction(1, 3)), ("same_degree", Fraction(1, 2))):
        rest4 = [(7, 1), (8, -2), (9, 0)][: 4 - order]
        into = lb.join(first, cont, 4, lam=lam, family=other, rest=rest4, **_extra(cont))
        with monkeypatch.context() as mp:
            mp.setattr(_derived_joins, "lookup", lambda *a: None)
            ref = lb.join(first, cont, 4, lam=lam, family=other, rest=rest4, **_extra(cont))
        assert np.abs(into.points - ref.points).max() <= 1e-9 * (1 + np.abs(ref.points).max())
        back, back_ref = _join_both(
            into, cont, 3, fam, _inside(fam, draw), rest, monkeypatch, **_extra(cont)
        )
        assert np.abs(back.points - back_ref.points).max() <= 1e-9 * (
            1 + np.abs(back_ref.points).max()
        )


@pytest.mark.parametrize("name", ["han_trig_cubic", "hyp_two_shape_cubic", "at_pi_cubic"])
@pytest.mark.parametrize("cont", CONTINUITIES)
def test_joined_curves_meet_by_finite_differences(name, cont, monkeypatch):
    fam = FAMILIES[name]
    box = fam.atom_data.RANGES
    mid = {x: (box[x][0] + box[x][1]) / 2 + Fraction(1, 7) for x in fam.parameters}
    first = fam.curve([(0, 0), (1, 2), (3, 3), (4, 1)], params=mid)
    order = 1 if cont in ("C1", "G1") else 2
    rest = [(7, 1), (8, -2), (9, 0)][: 3 - order]
    nxt, _ = _join_both(first, cont, 3, fam, mid, rest, monkeypatch, **_extra(cont))
    p1, d1, dd1 = _ends(first, True)
    p2, d2, dd2 = _ends(nxt, False)
    size = 1 + np.abs(d1).max()
    assert np.abs(p1 - p2).max() < 1e-12 * size
    if cont == "C1" or cont == "C2":
        assert np.abs(d1 - d2).max() < 1e-5 * size
    tangent = np.abs(d1 / np.linalg.norm(d1) - d2 / np.linalg.norm(d2)).max()
    assert tangent < 1e-6
    if cont == "G1":
        assert abs(np.linalg.norm(d1) / np.linalg.norm(d2) - 1.5) < 1e-5
    if order == 2:
        k1, k2 = _curvature(d1, dd1), _curvature(d2, dd2)
        assert abs(k1 - k2) < 1e-4 * (1 + abs(k1))
    if cont == "C2":
        assert np.abs(dd1 - dd2).max() < 1e-3 * (1 + np.abs(dd1).max())


def test_a_wrong_weight_is_caught(monkeypatch):
    """The finite-difference check fails when one weight of the table is changed (the
    test above can fail)."""
    fam = FAMILIES["han_trig_cubic"]
    table = fam.atom_data.JOINS
    key = "han_trig_cubic>han_trig_cubic"
    entry = dict(table["pairs"][key])
    c1 = dict(entry["C1"])
    num, den = c1["1,first,0"].split(" / ")
    c1["1,first,0"] = f"{num} 1@{','.join('0' * len(table['variables']))} / {den}"
    entry["C1"] = c1
    broken = {**table, "pairs": {**table["pairs"], key: entry}}
    monkeypatch.setattr(fam.atom_data, "JOINS", broken)
    first = fam.curve([(0, 0), (1, 2), (3, 3), (4, 1)], lam=Fraction(1, 3), mu=0)
    nxt = lb.join(first, "C1", 3, family=fam, lam=0, mu=0, rest=[(7, 1), (8, -2)])
    _, d1, _ = _ends(first, True)
    _, d2, _ = _ends(nxt, False)
    assert np.abs(d1 - d2).max() > 1e-3


def test_bad_weight_text_is_refused():
    table = {"variables": ["n"], "pairs": {"a>b": {"C1": {"0,first,0": "1@x / 1@0"}}}}
    with pytest.raises(ValueError, match="not a term"):
        _derived_joins.lookup(table, "a>b", "C1", {"n": 3})
    table["pairs"]["a>b"]["C1"] = {"0,first,0": "1@1 / -3@0 3@1"}
    with pytest.raises(ValueError, match="vanishing denominator"):
        _derived_joins.lookup(table, "a>b", "C1", {"n": 1})


def test_an_indexed_family_joins_itself_at_another_degree(monkeypatch):
    """Each degree's table of q_bezier holds that degree with itself only; a join from degree
    3 into degree 4 takes the document's weights in closed form in n and m (index-relative
    symbols lam(n)1, lam(1)2, ...), exactly the per-degree solve's, and it is C1."""
    fam = lb.load_family(DATA / "q_bezier.toml")
    first = fam.curve([(0, 0), (1, 2), (3, 3), (4, 1)], lam=[Fraction(1, 2), 0, Fraction(-1, 3)])
    used = []
    real = _derived_joins.lookup
    monkeypatch.setattr(_derived_joins, "lookup", lambda *a: used.append((a[1], a[2])) or real(*a))
    four = fam.at_degree(4)
    values = dict(zip(four.parameters, [Fraction(1, 4), 0, 0, Fraction(1, 5)], strict=True))
    rest = [(7, 1), (8, -2), (9, 0)]
    nxt = lb.join(first, "C1", 4, family=four, params=values, rest=rest)
    assert used == [("q_bezier>q_bezier", "C1")]
    monkeypatch.setattr(_derived_joins, "lookup", lambda *a: None)
    solved = lb.join(first, "C1", 4, family=four, params=values, rest=rest)
    assert nxt.points.tolist() == solved.points.tolist()
    assert [float(v) for v in nxt.derivative(0.0)] == pytest.approx(
        [float(v) for v in first.derivative(1.0)], abs=1e-12
    )
