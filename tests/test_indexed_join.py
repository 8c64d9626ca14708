"""lb.join into, and out of, a family with one shape parameter per index (IndexedFamily,
``lam(i)``): the new segment's degree picks the family of that degree, and the values come
as one sequence. Before, family=<IndexedFamily> gave "degree 3 is not supported for q_bezier:
degrees 2..2", its lowest degree, though fam.at_degree(3) joins fine."""

from __future__ import annotations

from fractions import Fraction as F
from pathlib import Path

import numpy as np
import pytest

import lambda_bezier as lb

Q_FILE = Path(__file__).parent / "data" / "families" / "q_bezier.toml"
FIRST = [(0, 0), (1, 2), (3, 2), (4, 0)]
REST = [(9, 1), (10, 0), (12, 3)]


@pytest.fixture(scope="module")
def q():
    return lb.load_family(Q_FILE)


def _values(degree: int) -> list[F]:
    return [F(k, 7) - F(1, 3) for k in range(1, degree + 1)]


def _assert_joint(first, second, continuity: str, alpha=1, d=0) -> None:
    """C2(0) = C1(1), C1'(1) = α C2'(0) and, for order 2, C1''(1) = α² C2''(0) + d C2'(0)."""
    alpha, d = float(alpha), float(d)
    scale = 1 + np.abs(np.asarray(first.points, dtype=float)).max()
    np.testing.assert_allclose(second.evaluate(0), first.evaluate(1), atol=1e-12 * scale)
    d1, d2 = first.derivative(1, 1), second.derivative(0, 1)
    np.testing.assert_allclose(d1, alpha * d2, atol=1e-10 * scale)
    if continuity.endswith("2"):
        want = alpha**2 * second.derivative(0, 2) + d * d2
        np.testing.assert_allclose(first.derivative(1, 2), want, atol=1e-9 * scale)


@pytest.mark.parametrize("degree", [3, 4, 5])
@pytest.mark.parametrize("continuity", ["C1", "C2", "G1", "G2"])
def test_join_into_an_indexed_family_at_any_of_its_degrees(q, degree, continuity):
    first = lb.BezierCurve(FIRST)
    alpha = F(3, 2) if continuity.startswith("G") else 1
    d = F(-1, 4) if continuity == "G2" else 0
    order = int(continuity[1])
    rest = [(9 + k, (-1) ** k * k) for k in range(degree - order)]
    nxt = lb.join(first, continuity, degree, [*_values(degree)], alpha, d, rest, family=q)
    assert nxt.degree == degree
    assert type(nxt) is q.at_degree(degree).curve_class or nxt.family == q.name
    _assert_joint(first, nxt, continuity, alpha, d)
    # the same segment as joining into that degree's own family by its plain parameters
    fam = q.at_degree(degree)
    params = dict(zip(fam.parameters, _values(degree), strict=True))
    same = lb.join(first, continuity, degree, None, alpha, d, rest, fam, params=params)
    assert nxt.control_points() == same.control_points()
    assert all(isinstance(v, F) for p in nxt.control_points() for v in p)  # exact stays exact


def test_the_values_by_name_or_in_params(q):
    first = lb.BezierCurve(FIRST)
    by_lam = lb.join(first, "C2", 4, family=q, lam=_values(4), rest=REST[:2])
    by_params = lb.join(first, "C2", 4, family=q, params={"lam": _values(4)}, rest=REST[:2])
    assert by_lam.control_points() == by_params.control_points()


def test_continuing_an_indexed_curve_at_another_degree(q):
    first = q.curve(FIRST, lam=_values(3))
    nxt = lb.join(first, "C2", 5, lam=_values(5), rest=REST)
    assert nxt.degree == 5
    _assert_joint(first, nxt, "C2")
    comp = lb.CompositeCurve([first]).join("G1", 4, _values(4), 2, rest=REST, family=q)
    _assert_joint(first, comp.segments[-1], "G1", alpha=2)


@pytest.mark.parametrize(
    "kwargs, error, message",
    [
        ({"degree": 7, "lam": [1] * 7}, ValueError, r"degree 7 is not supported for q_bezier: "),
        ({"degree": 3}, ValueError, r"needs its shape parameters lam=\[\.\.\.\]"),
        ({"degree": 3, "lam": [1, 2]}, ValueError, r"degree 3 has 3 parameters"),
        ({"degree": 3, "lam": 0.5}, TypeError, r"lam must be a sequence of 3 numbers"),
        ({"degree": 3, "mu": [1, 2, 3]}, TypeError, r"'mu' is not a parameter of 'q_bezier'"),
        (
            {"degree": 3, "lam": [1, 2, 3], "params": {"lam": [1, 2, 3]}},
            TypeError,
            r"lam is given twice",
        ),
        ({"degree": "3", "lam": [1, 2, 3]}, ValueError, r"degree must be an integer"),
    ],
)
def test_bad_input_is_named(q, kwargs, error, message):
    first = lb.BezierCurve(FIRST)
    degree = kwargs.pop("degree")
    with pytest.raises(error, match=message):
        lb.join(first, "C1", degree, family=q, rest=REST[:2], **kwargs)
