"""The fixed-cost certificate of edge and corner minima (hazmat.surface_certify.edge_minimum,
for the nets certified_minimum declines): never wrong against the exact method, on both
engines, and certifying most edge minima of random nets."""

from __future__ import annotations

from fractions import Fraction
from importlib.util import find_spec

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import lambda_bezier as lb
from lambda_bezier.hazmat.surface_certify import certified_minimum, edge_minimum
from lambda_bezier.surface_energies import _float, minimise_polynomial

BOX = (-2.0, 1.0, -2.0, 1.0)
KEYS = [(a, b) for a in range(3) for b in range(3)]


def engines():
    yield "numpy", lambda c: edge_minimum(*(np.array([v]) for v in c), *BOX, 1e-12)
    if find_spec("numba") is not None:
        from lambda_bezier.hazmat import surface_batch_compiled as sbc

        yield "numba", lambda c: sbc._edge_minimum(*c, *BOX, 1e-12)


ENGINES = dict(engines())


def exact_minimum(coeffs):
    e = {k: Fraction(c) for k, c in zip(KEYS, coeffs, strict=True) if c}
    x, y, kind = minimise_polynomial(e, (Fraction(-2), Fraction(1)), (Fraction(-2), Fraction(1)))
    return _float(x), _float(y), kind


# convex-ish energies whose linear terms push the minimiser towards or past the box's edges;
# the λ_u λ_v terms may spoil convexity (the certificate must then decline, never be wrong)
coefficients = st.tuples(
    st.integers(-60, 60),  # e00
    st.integers(-40, 40),  # e01
    st.integers(1, 9),  # e02
    st.integers(-40, 40),  # e10
    st.integers(-4, 4),  # e11
    st.integers(-2, 2),  # e12
    st.integers(1, 9),  # e20
    st.integers(-2, 2),  # e21
    st.integers(-1, 1),  # e22
).map(lambda c: [float(v) / 8 for v in c])


@pytest.mark.parametrize("engine", list(ENGINES))
@settings(max_examples=60, deadline=None)
@given(c=coefficients)
def test_a_certified_edge_minimum_is_the_exact_one(engine, c):
    x, y, value, delta, ok = (np.asarray(v).ravel()[0] for v in ENGINES[engine](c))
    if not ok:
        return
    ex, ey, kind = exact_minimum(c)
    assert kind in ("edge", "corner")
    assert delta <= 1e-12
    assert abs(x - ex) <= delta + 1e-15 and abs(y - ey) <= delta + 1e-15
    assert value == pytest.approx(
        sum(ci * ex**a * ey**b for ci, (a, b) in zip(c, KEYS, strict=True)), rel=1e-12, abs=1e-12
    )


def test_the_engines_agree_and_edge_minima_are_mostly_certified():
    """On coefficients whose exact minimum is on an edge or a corner, both engines give the
    same answers bit for bit, and most are certified (the rest take the careful path)."""
    rng = np.random.default_rng(11)
    raw = rng.integers(
        [-60, -40, 1, -40, -4, -2, 1, -2, -1], [61, 41, 10, 41, 5, 3, 10, 3, 2], size=(300, 9)
    )
    hits = total = 0
    for row in raw / 8:
        c = [float(v) for v in row]
        _, _, _, _, interior = certified_minimum(*(np.array([v]) for v in c), *BOX, 1e-12)
        ex, ey, kind = exact_minimum(c)
        if kind == "interior" or interior[0]:
            continue
        answers = [tuple(float(np.asarray(v).ravel()[0]) for v in f(c)) for f in ENGINES.values()]
        assert all(a == answers[0] for a in answers)
        total += 1
        if answers[0][4]:
            hits += 1
            assert abs(answers[0][0] - ex) <= 1e-12 and abs(answers[0][1] - ey) <= 1e-12
    assert total > 50 and hits > total // 2


def test_edge_certified_nets_report_their_edge_or_corner_in_a_batch():
    """A batch's edge-certified answers carry the exact method's `where` and parameters."""
    nets = np.random.default_rng(3).normal(size=(3000, 4, 4, 3))
    nets[..., 0] += np.arange(4)[:, None]
    nets[..., 1] += np.arange(4)[None, :]
    res = lb.optimal_parameters(nets, "thin_plate")
    off = np.flatnonzero(res["where"] != "interior")
    assert off.size > res["careful_fallbacks"]
    for i in off[:10]:
        exact_net = [[[Fraction(float(v)) for v in p] for p in row] for row in nets[i]]
        one = lb.optimal_parameters(exact_net, "thin_plate")
        assert res["where"][i] == one["where"]
        assert abs(res["lam_u"][i] - one["lam_u_float"]) <= 1e-12
        assert abs(res["lam_v"][i] - one["lam_v_float"]) <= 1e-12


@pytest.mark.skipif(find_spec("numba") is None, reason="numba is not installed: compiled only")
def test_the_compiled_early_stop_is_edge_minimum_bit_for_bit():
    """surface_batch_compiled._edge_first_at (the four edges in turn, stopping at the first
    certified) against the compiled edge_minimum (all four, then the first certified), on
    coefficients certified on each of the four edges and on none."""
    from lambda_bezier.hazmat import surface_batch_compiled as sbc

    rng = np.random.default_rng(5)
    raw = rng.integers(
        [-60, -40, 1, -40, -4, -2, 1, -2, -1], [61, 41, 10, 41, 5, 3, 10, 3, 2], size=(400, 9)
    )
    acc = np.ascontiguousarray((raw / 8).T)
    seen = set()
    for k in range(acc.shape[1]):
        want = sbc._edge_minimum(*acc[:, k], *BOX, 1e-12)
        radius = sbc.sc.RADIUS * max(BOX[1] - BOX[0], BOX[3] - BOX[2])  # edge_minimum's band
        got = sbc._edge_first_at(acc, k, *BOX, 1e-12, radius)
        assert bool(got[4]) == bool(want[4])
        if want[4]:
            assert [float(v) for v in got[:4]] == [float(v) for v in want[:4]]
            x, y = float(want[0]), float(want[1])
            seen.add("x=lo" if x == BOX[0] else "x=hi" if x == BOX[1] else "y=" + str(y))
        else:
            seen.add("none")
    assert {"x=lo", "x=hi", "none"} <= seen and len(seen) >= 5  # every edge took its turn
