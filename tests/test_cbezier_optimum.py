"""The certified least E_k(alpha) of a C-Bezier family (issue #30, optimal_parameters and
optimal_lambda), against an independent computation: the energy of the curve written in the
definition file (its functions parsed by derive's grammar, differentiated by SymPy, the
curve evaluated directly in mpmath at 30 digits), integrated by mpmath's quadrature on a
grid of alpha and refined by golden section. Nothing of the derived document or of the
runtime's Taylor models enters the reference.
"""

from __future__ import annotations

import math
from fractions import Fraction
from pathlib import Path

import mpmath as mp
import pytest
import sympy as sp
import tomllib
from conftest import family_file

import lambda_bezier as lb
from derive.families import cbezier as cb
from lambda_bezier import examples

DATA = Path(__file__).parent / "data" / "families"
P = [[0.0, 0.0], [1.0, 2.0], [3.0, 2.5], [4.0, 0.5]]


def _reference(name: str, points, k: int):
    """E_k(alpha) by quadrature of |p^(k)|^2 over the family's own parameter."""
    table = tomllib.loads((family_file(name)).read_text())["family"]
    defn = cb.read_table(table)
    x = sp.Symbol("x")
    unit = table["domain"] == "[0, 1]"
    fs = []
    for expr in defn.written():  # in t on [0, alpha] (the grammar's parse of the file)
        # the family's own parameter: t on [0, alpha], or u = t/alpha on [0, 1]
        own = expr.subs(cb.T, cb.A * x) if unit else expr.subs(cb.T, x)
        fs.append(sp.lambdify((x, cb.A), sp.diff(own, x, k), modules="mpmath"))

    def energy(alpha):
        a = mp.mpf(alpha)
        end = 1 if unit else a

        def speed2(s):
            d = [sum(f(s, a) * p[j] for f, p in zip(fs, points, strict=True)) for j in range(2)]
            return d[0] ** 2 + d[1] ** 2

        return mp.quad(speed2, [0, end / 2, end])

    return energy


def _dense_minimum(energy, lo: float, hi: float, count: int = 12):
    grid = [lo + (hi - lo) * i / count for i in range(count + 1)]
    values = [energy(a) for a in grid]
    best = min(range(len(grid)), key=lambda i: values[i])
    if best in (0, count):
        return grid[best], values[best]
    a, b = mp.mpf(grid[best - 1]), mp.mpf(grid[best + 1])
    ratio = (mp.sqrt(5) - 1) / 2
    x1, x2 = b - ratio * (b - a), a + ratio * (b - a)
    f1, f2 = energy(x1), energy(x2)
    for _ in range(45):  # golden section to |b - a| ~ 1e-10 (E_k is flat there: 1e-20)
        if f1 <= f2:
            b, x2, f2 = x2, x1, f1
            x1 = b - ratio * (b - a)
            f1 = energy(x1)
        else:
            a, x1, f1 = x1, x2, f2
            x2 = a + ratio * (b - a)
            f2 = energy(x2)
    return float((a + b) / 2), energy((a + b) / 2)


@pytest.mark.parametrize(
    ("name", "k", "where"),
    [
        ("c_bezier_cubic", 2, "upper"),  # alpha = pi
        ("c_bezier_cubic_unit", 2, "interior"),
        ("hc_bezier_cubic", 1, "upper"),  # alpha = 4
    ],
)
def test_certified_minimum_against_quadrature(name, k, where):
    mp.mp.dps = 30
    fam = lb.load_family(family_file(name))
    got = lb.optimal_parameters(P, k, family=fam)
    assert got.method == "certified" and got.lower_bound is not None
    alpha = got["alpha"]
    energy = _reference(name, P, k)
    # the energy reported is E_k at the point reported, and the bound is below it by <= 1e-12
    assert abs(float(energy(alpha)) - got.energy) <= 1e-13 * got.energy
    assert 0 <= got.energy - float(got.lower_bound) <= 1e-12 * got.energy
    hi = fam.hi
    best_alpha, best = _dense_minimum(energy, 0.25, hi)
    # nothing found by the dense search is below the proven lower bound
    assert float(best) >= float(got.lower_bound) - 1e-14 * float(best)
    assert abs(float(best) - got.energy) <= 2e-12 * got.energy
    if where == "upper":
        assert got.boundary.endswith("(upper end)") and alpha == pytest.approx(hi, abs=1e-15)
    else:
        assert got.boundary == "" and alpha == pytest.approx(best_alpha, abs=1e-5)
    one = lb.optimal_lambda(P, k, family=fam)  # the same answer, as optimal_lambda's type
    assert one.lam == alpha and one.energy == got.energy and one.admissible


def test_the_infimum_at_the_open_end_is_the_bezier_limit():
    """On [0, 1] (E_3 in u), this polygon's least E_3 is the limit alpha -> 0, where the
    C-Bezier cubic becomes the Bezier cubic: E_3 = 36 |P3 - 3 P2 + 3 P1 - P0|^2 = 180,
    exactly, not attained (0 is outside the range)."""
    mp.mp.dps = 30
    fam = lb.load_family(DATA / "c_bezier_cubic_unit.toml")
    got = lb.optimal_parameters(P, 3, family=fam)
    assert got["alpha"] == 0.0 and "not attained" in got.boundary
    assert got.energy == 180.0
    assert 0 <= 180 - got.lower_bound <= Fraction(180, 10**12)
    energy = _reference("c_bezier_cubic_unit", P, 3)
    for a in (0.05, 0.5, 2.0, math.pi):
        assert energy(a) > 180
    assert not lb.optimal_lambda(P, 3, family=fam).admissible


def test_refusals():
    fam = lb.load_family(examples.path("c_bezier_cubic.toml"))
    with pytest.raises(ValueError, match="k must be 1, 2 or 3"):
        lb.optimal_parameters(P, 4, family=fam)
    with pytest.raises(ValueError, match="points"):
        lb.optimal_parameters(P[:3], 2, family=fam)


def test_a_range_holding_a_singular_point_is_refused(tmp_path):
    """Past 2*pi the C-Bezier cubic's denominators vanish inside the range: no minimum, and
    the refusal is immediate (the derived verdicts name the point)."""
    from lambda_bezier.cli import main

    text = (examples.path("c_bezier_cubic.toml")).read_text()
    text = text.replace('range = "(0, pi]"', 'range = "(0, 3*pi]"')
    text = text.replace('name = "c_bezier_cubic"', 'name = "c_bezier_wide"')
    path = tmp_path / "c_bezier_wide.toml"
    path.write_text(text)
    assert main(["derive", "--family", str(path)]) == 0
    fam = lb.load_family(path)
    with pytest.raises(ValueError, match=r"holds a singular point of the family \(alpha = "):
        lb.optimal_parameters(P, 2, family=fam)


def test_cli_optimal_lambda_says_certified(capsys):
    import json

    from lambda_bezier.cli import main

    args = ["optimal-lambda", "--family", str(examples.path("c_bezier_cubic.toml")), "-k", "2"]
    pts = ["0,0", "1,2", "3,2.5", "4,0.5"]
    assert main([*args, *pts]) == 0
    out = capsys.readouterr().out
    assert "optimal alpha   pi  ≈ 3.141592653589793" in out  # the range's end, exactly
    assert "on the boundary alpha = pi (upper end)" in out and "method          certified" in out
    assert main([*args, "--json", *pts]) == 0
    report = json.loads(capsys.readouterr().out)
    assert report["method"] == "certified" and report["boundary"] == "alpha = pi (upper end)"
    assert Fraction(report["lower_bound"]) <= Fraction(report["energy"])
