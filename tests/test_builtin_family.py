"""builtin_family: the built-in families as family objects with ``curve`` and ``surface``,
taken by every function exactly as their names are."""

from fractions import Fraction

import numpy as np
import pytest

import lambda_bezier as lb

POLY = [(0, 0), (1, 2), (3, 2), (4, 0)]
NET = [[(i, j, (i * j) % 3) for j in range(4)] for i in range(4)]


@pytest.mark.parametrize("name", ["same_degree", "bernstein_like"])
def test_curve_and_surface_are_the_classes_own(name):
    fam = lb.builtin_family(name)
    cls = lb.FAMILIES[name]
    lam = Fraction(1, 3)
    curve = fam.curve(POLY, lam=lam)
    assert type(curve) is cls and curve.lam == lam
    assert fam.curve(POLY, params={"lam": lam}).control_points() == curve.control_points()
    surf = fam.surface(NET, lam, Fraction(-1, 2))
    assert type(surf).__name__ == {"same_degree": "SameDegreeSurface"}.get(
        name, "BernsteinLikeSurface"
    )
    # the surface's iso-curve at v = 0 is the family's curve on the first column of the net
    column = [row[0] for row in NET]
    np.testing.assert_allclose(
        surf.evaluate(0.3, 0.0), fam.curve(column, lam=lam).evaluate(0.3), rtol=0, atol=1e-14
    )


def test_bezier_takes_no_parameter():
    fam = lb.builtin_family("bezier")
    assert fam.parameters == ()
    assert type(fam.curve(POLY)) is lb.BezierCurve
    assert type(fam.surface(NET)) is lb.BezierSurface
    with pytest.raises(TypeError, match="no shape parameter"):
        fam.curve(POLY, lam=1)


def test_every_function_takes_it_as_its_name():
    fam = lb.builtin_family("same_degree")
    assert fam == "same_degree" and hash(fam) == hash("same_degree")
    assert lb.optimal_lambda(POLY, 2, family=fam).lam == lb.optimal_lambda(POLY, 2).lam
    assert lb.optimal_parameters(POLY, 2, family=fam)["lam"] == Fraction(-2, 7)
    np.testing.assert_array_equal(
        lb.evaluate_many([POLY], [0.25, 0.5], lam=0, family=fam),
        lb.evaluate_many([POLY], [0.25, 0.5], lam=0, family="same_degree"),
    )
    assert repr(fam) == "BuiltinFamily('same_degree', lam in (-2, 1])"


def test_bad_names_and_parameters_are_named():
    with pytest.raises(ValueError, match="'nope' is not a built-in family"):
        lb.builtin_family("nope")
    with pytest.raises(TypeError, match="name must be"):
        lb.builtin_family(3)
    fam = lb.builtin_family("same_degree")
    with pytest.raises(TypeError, match="parameter is 'lam': got mu"):
        fam.curve(POLY, mu=1)
    with pytest.raises(ValueError, match="outside the same_degree range"):
        fam.curve(POLY, lam=5)
    # load_family on a built-in's name points here
    with pytest.raises(ValueError, match=r"builtin_family\(.same_degree.\)"):
        lb.load_family("same_degree")
