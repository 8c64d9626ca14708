"""fam.surface takes each direction's parameters as keywords with the direction's suffix
(lam_u=, mu_u=, lam_v=, mu_v=; sigma_u= for a family whose parameter is sigma), the same
surface as params_u / params_v or the positional lam_u, lam_v; anything else is a TypeError
naming the keyword."""

from fractions import Fraction as F

import numpy as np
import pytest

import lambda_bezier as lb
from lambda_bezier import examples

NET = [[(i, j, (i * j) % 3) for j in range(4)] for i in range(4)]
UV = (np.array([0.1, 0.3, 0.7]), np.array([0.2, 0.4, 0.9]))


@pytest.fixture(scope="module")
def two():
    return lb.load_family(examples.path("han_trig_cubic.toml"))  # lam, mu; t in [0, pi/2]


@pytest.fixture(scope="module")
def sigma():
    return lb.load_family(examples.path("nouri_saeidian.toml"))  # one parameter, sigma


def test_suffixed_keywords_are_the_params_dicts(two):
    by_keyword = two.surface(NET, lam_u=F(1, 2), mu_u=0, lam_v=0, mu_v=F(1, 3))
    by_dict = two.surface(
        NET, params_u={"lam": F(1, 2), "mu": 0}, params_v={"lam": 0, "mu": F(1, 3)}
    )
    assert by_keyword.params_u == by_dict.params_u and by_keyword.params_v == by_dict.params_v
    u, v = UV
    assert np.array_equal(by_keyword.evaluate(u, v), by_dict.evaluate(u, v))


def test_a_one_parameter_family_takes_its_own_name(sigma):
    by_name = sigma.surface(NET, sigma_u=F(1, 2), sigma_v=1)
    positional = sigma.surface(NET, F(1, 2), 1)
    u, v = UV
    assert np.array_equal(by_name.evaluate(u, v), positional.evaluate(u, v))
    with pytest.raises(TypeError, match="lam_u is given twice"):
        sigma.surface(NET, F(1, 2), 1, sigma_u=1)


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"nu_u": 1}, "nu_u: 'nu' is not a parameter of 'han_trig_cubic'"),
        ({"mu_w": 1}, "unexpected keyword argument 'mu_w'"),
        ({"mu": 1}, "unexpected keyword argument 'mu'"),
        ({"mu_u": 1, "params_u": {"lam": 0, "mu": 1}}, "mu_u is given twice"),
        ({"lam_u": 1, "mu_u": 0, "params_u": {"lam": 0}}, "lam_u is given twice"),
    ],
)
def test_bad_keywords_are_named(two, kwargs, message):
    with pytest.raises(TypeError, match=message):
        two.surface(NET, **kwargs)
