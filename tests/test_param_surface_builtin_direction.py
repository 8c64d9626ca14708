"""A surface of a polynomial family from load_family (several parameters) across a built-in
family, by name, BuiltinFamily or class, in either order: `fam.surface(net, ...,
family_v="same_degree")` and `family_surface(net, ("bezier", fam), ...)` once raised an
AttributeError from inside the constructor (a built-in direction was resolved to its curve
class only across an atom family). Checked against each direction's own curves (the tensor
product of the two curves' bases, written out here), the exact Bézier form on a dense grid,
and a JSON round trip."""

from __future__ import annotations

from fractions import Fraction as F

import numpy as np
import pytest

import lambda_bezier as lb
from lambda_bezier import examples
from lambda_bezier import surface_export as se
from lambda_bezier.param_surfaces import ParamSurface, family_surface

TWO = lb.load_family(examples.path("two_shape_cubic.toml"))
NET = [[(i, j, F((i * j) % 3, 2) - F(i, 4)) for j in range(4)] for i in range(4)]
PARAMS = {"lam": F(-1, 2), "mu": F(1, 3)}
BUILTINS = [
    ("same_degree", {"lam": F(1, 3)}),
    ("bernstein_like", {"lam": F(1, 2)}),
    ("bezier", {}),
]


def _basis(curve_of, t: np.ndarray) -> np.ndarray:
    """(len(t), 4): the direction's basis functions, the curve whose control points are the
    unit vectors of R⁴ evaluated at t."""
    return np.asarray(curve_of(np.eye(4).tolist()).evaluate(t))


def _surfaces(name: str, given: dict):
    """The pair both ways: (TWO in u, the built-in in v) and (the built-in in u, TWO in v),
    built by name, as a BuiltinFamily and through Family.surface."""
    lam = given.get("lam")
    out = [
        ("u", TWO.surface(NET, params_u=PARAMS, family_v=name, lam_v=lam)),
        ("u", family_surface(NET, (TWO, lb.builtin_family(name)), params_u=PARAMS, lam_v=lam)),
        ("v", family_surface(NET, (name, TWO), lam_u=lam, params_v=PARAMS)),
    ]
    return out


@pytest.mark.parametrize(("name", "given"), BUILTINS)
def test_a_several_parameter_family_across_a_builtin_one(name, given):
    two_curve = lambda pts: TWO.curve(pts, params=PARAMS)  # noqa: E731
    builtin = lb.builtin_family(name)
    lam = given.get("lam")
    other_curve = lambda pts: builtin.curve(pts, lam) if lam is not None else builtin.curve(pts)  # noqa: E731
    net = np.array(NET, dtype=float)
    t = np.linspace(0, 1, 21)
    for where, s in _surfaces(name, given):
        assert isinstance(s, ParamSurface)
        assert s.family == (
            ("two_shape_cubic", name) if where == "u" else (name, "two_shape_cubic")
        )
        assert s.is_exact
        bu = _basis(two_curve if where == "u" else other_curve, t)
        bv = _basis(other_curve if where == "u" else two_curve, t)
        want = np.einsum("ki,ijd,lj->kld", bu, net, bv)
        assert np.allclose(s.evaluate_grid(t, t), want, rtol=0, atol=1e-13)
        # certified box and closest point (the exact Bézier form) against a dense grid
        dense = s.to_bezier().evaluate_grid(np.linspace(0, 1, 201), np.linspace(0, 1, 201))
        dense = dense.reshape(-1, 3)
        lo, hi = s.bounding_box()
        assert (lo <= dense.min(axis=0) + 1e-12).all() and (dense.max(axis=0) <= hi + 1e-12).all()
        q = np.array([1.2, 2.1, 1.5])
        cp = s.closest_point(q)
        assert cp.lower_bound <= cp.distance <= np.linalg.norm(dense - q, axis=1).min() + 1e-12
        # JSON: exact both ways, the built-in direction by its name
        back = se.surface_from_json(se.surface_to_json(s), family=TWO)
        assert back.family == s.family and back.parameters() == s.parameters()
        assert back.control_net() == s.control_net()


def test_bad_parameters_of_the_builtin_direction_are_named():
    with pytest.raises(TypeError, match="params_v: the same_degree direction needs"):
        TWO.surface(NET, params_u=PARAMS, family_v="same_degree")
    with pytest.raises(TypeError, match="params_v: the bezier direction takes"):
        TWO.surface(NET, params_u=PARAMS, family_v="bezier", lam_v=1)
    with pytest.raises(ValueError, match="unknown family 'nope'"):
        TWO.surface(NET, params_u=PARAMS, family_v="nope", lam_v=0)
