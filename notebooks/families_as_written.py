# ---
# jupyter:
#   jupytext:
#     formats: py:percent
#     text_representation:
#       extension: .py
#       format_name: percent
#   kernelspec:
#     display_name: Python 3
#     language: python
#     name: python3
# ---

# %% [markdown]
# # Families as the field writes them: two parameters, sin and cos, and α as the domain
#
# Most papers on shape-parameter bases use several parameters and trigonometric functions. Two
# such families, both defined only by a file of basis functions (the axiom; everything below is
# derived from it by `lambda-bezier derive --family` and served by the runtime):
#
# - `han_trig_cubic`: the cubic trigonometric basis of Han, Ma and Huang on [0, π/2], with one
#   parameter per end, λ and μ in [−2, 1] (shipped with the package: `lambda_bezier.examples`);
# - `c_bezier_cubic`: the C-Bézier cubic of Zhang on [0, α], where the parameter α is the
#   length of the domain and sits inside sin and cos (also shipped: `lambda_bezier.examples`).
#
# The control polygon is **our own choice** (the papers print none for these bases).

# %%
import math
import os
from fractions import Fraction
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import lambda_bezier as lb
from lambda_bezier import examples

FIGURES = Path(os.environ.get("LAMBDA_BEZIER_FIGURES", Path.cwd() / "figures"))
FIGURES.mkdir(parents=True, exist_ok=True)

POLYGON = [(0, 0), (1, 3), (4, 3), (5, 0)]


def draw(ax, curve, label, samples=200, **style):
    lo, hi = (float(x) for x in curve.domain)
    xy = curve.evaluate(np.linspace(lo, hi, samples))
    ax.plot(xy[:, 0], xy[:, 1], label=label, **style)


def polygon(ax):
    p = np.array(POLYGON, dtype=float)
    ax.plot(p[:, 0], p[:, 1], "o--", color="0.6", lw=1)


# %% [markdown]
# ## Two parameters, one per end
#
# λ shapes the curve near P₀ and μ near P₃: the end tangents are (2 + λ)(P₁ − P₀) and
# (2 + μ)(P₃ − P₂), so a larger parameter pulls its end of the curve towards the polygon.

# %%
trig = lb.load_family(examples.path("han_trig_cubic.toml"))
print(trig)
fig, axes = plt.subplots(1, 2, figsize=(11, 4))
for lam in (-2, -1, 0, 1):
    draw(axes[0], trig.curve(POLYGON, lam=lam, mu=0), f"λ = {lam}, μ = 0")
for mu in (-2, -1, 0, 1):
    draw(axes[1], trig.curve(POLYGON, lam=0, mu=mu), f"λ = 0, μ = {mu}")
for ax in axes:
    polygon(ax)
    ax.set_aspect("equal")
    ax.legend(fontsize=8)
fig.savefig(FIGURES / "trig_two_parameters.png", dpi=80)

# the end tangents the derivation gives, at λ = 1, μ = -1 (t runs over [0, pi/2])
c = trig.curve(POLYGON, lam=1, mu=-1)
start, end = c.derivative(0.0), c.derivative(math.pi / 2)
print("r'(0) =", start, " r'(pi/2) =", end)
assert np.allclose(start, 3 * np.subtract(POLYGON[1], POLYGON[0]))
assert np.allclose(end, 1 * np.subtract(POLYGON[3], POLYGON[2]))

# %% [markdown]
# ## The energy-optimal (λ, μ), exactly
#
# The strain energy ∫ |r″|² dt of a curve of this family is a quadratic in (λ, μ) whose
# coefficients lie in ℚ(π); its minimum over the box is given exactly, with π in it.

# %%
best = lb.optimal_parameters(POLYGON, 2, family=trig)
print("lam =", best["lam"])
print("mu  =", best["mu"])
lam, mu = float(best["lam"]), float(best["mu"])
# the polygon is symmetric, so the two parameters agree
assert abs(lam - mu) < 1e-15 and -2 < lam < 1


def strain(lam_: float, mu_: float) -> float:
    """∫ |r''|² dt by Gauss-Legendre (64 nodes): an independent value of the energy."""
    x, w = np.polynomial.legendre.leggauss(64)
    t = (x + 1) * math.pi / 4
    d = trig.curve(POLYGON, lam=lam_, mu=mu_).derivative(t, 2)
    return float(np.sum(w * np.sum(d * d, axis=1)) * math.pi / 4)


# no neighbour on a small grid around the optimum has a lower energy
around = [strain(lam + a, mu + b) for a in (-0.01, 0, 0.01) for b in (-0.01, 0, 0.01)]
assert min(around) == strain(lam, mu)
print("energy at the optimum:", strain(lam, mu), " at lam = mu = 0:", strain(0, 0))
print("the optimum's energy, exactly:", best.energy)
assert abs(float(best.energy) - strain(lam, mu)) < 1e-9

# %% [markdown]
# ## An exact rational form
#
# With sin and cos written through the half-angle substitution, a curve of this family is a
# rational Bézier curve of degree 6 in a new parameter: exact weights and control points, the
# form CAD systems read (`lambda_bezier.export` writes it as a STEP or DXF rational curve).

# %%
c = trig.curve(POLYGON, lam=Fraction(1, 2), mu=Fraction(-1, 2))
rational = c.to_rational_bezier()
print(rational)
print("weights:", rational.control_weights())
assert rational.control_weights()[0] == 1 and rational.is_exact
s = np.linspace(0, 1, 9)
assert np.allclose(rational.evaluate(s), c.evaluate(c.t_of_s(s)))

# %% [markdown]
# ## C-Bézier: the parameter is the length of the domain
#
# The C-Bézier cubic is spanned by {1, t, sin t, cos t} on [0, α], α in (0, π]. As α → 0 it
# tends to the cubic Bézier curve of the same polygon; a larger α draws the curve away from the
# polygon's middle.

# %%
cbez = lb.load_family(examples.path("c_bezier_cubic.toml"))
print(cbez)
fig, ax = plt.subplots(figsize=(6, 4))
draw(ax, lb.BezierCurve(POLYGON), "cubic Bézier", color="k", lw=2.5, alpha=0.3)
heights = {}
for alpha in (0.2, 1.0, 2.0, math.pi):
    curve = cbez.curve(POLYGON, alpha=alpha)
    draw(ax, curve, f"α = {alpha:.3g}")
    heights[alpha] = float(curve.evaluate(alpha / 2)[1])
polygon(ax)
ax.set_aspect("equal")
ax.legend(fontsize=8)
fig.savefig(FIGURES / "c_bezier_alpha.png", dpi=80)
print("height at the middle:", {round(a, 3): round(h, 4) for a, h in heights.items()})
# the middle lowers as alpha grows, from near the Bezier curve's 9/4; by symmetry it is
# 3 (b_1 + b_2)(alpha/2) = 3 (1 - 2 b_3(alpha/2)) with b_3(t) = (t - sin t)/(alpha - sin alpha),
# Zhang's end function, evaluated here independently of the family file
for alpha, h in heights.items():
    b3 = (alpha / 2 - math.sin(alpha / 2)) / (alpha - math.sin(alpha))
    assert abs(h - 3 * (1 - 2 * b3)) < 1e-13
values = list(heights.values())
assert all(a > b for a, b in zip(values, values[1:], strict=False)) and abs(values[0] - 2.25) < 2e-3

# %% [markdown]
# Near α = 0 the basis is a quotient of terms that all vanish like α³; the derivation writes
# it as an exact series in α (its first term is the Bernstein cubic), so a curve at α = 10⁻⁶ is
# evaluated to rounding and is the Bézier curve to O(α²):

# %%
tiny = cbez.curve(POLYGON, alpha=1e-6)
u = np.linspace(0, 1, 11)
gap = np.max(np.abs(tiny.evaluate(u * 1e-6) - lb.BezierCurve(POLYGON).evaluate(u)))
print("largest distance to the Bezier curve at alpha = 1e-6:", gap)
assert gap < 1e-10

# %% [markdown]
# The certified energy-optimal α of this polygon (a one-parameter minimum over (0, π], with a
# certified lower bound on the energy over the whole range):

# %%
best_alpha = lb.optimal_parameters(POLYGON, 2, family=cbez)
print(best_alpha["alpha"], best_alpha.boundary, best_alpha.method)
assert best_alpha.method == "certified"
