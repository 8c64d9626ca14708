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
# # Tensor-product λ-surfaces: the effect of λ_u and λ_v
#
# Paper 000 ends by naming the extension to surfaces. A surface of a family is
# S(u, v) = Σ P_ij b_i(u; λ_u) b_j(v; λ_v); each parameter acts in its own direction. Below, one
# bicubic net of **our own choice** (the papers print none) as a same-degree surface at several
# (λ_u, λ_v), coloured by Gaussian curvature, then the thin-plate-optimal pair.

# %%
import os
from fractions import Fraction
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import lambda_bezier as lb
from lambda_bezier.surface_plot import plot_surface

FIGURES = Path(os.environ.get("LAMBDA_BEZIER_FIGURES", Path.cwd() / "figures"))
FIGURES.mkdir(parents=True, exist_ok=True)

# a bump over the unit square: the middle four points raised
NET = [[(i, j, 2 if 0 < i < 3 and 0 < j < 3 else 0) for j in range(4)] for i in range(4)]

# %% [markdown]
# ## λ_u and λ_v act separately
#
# At λ = 1 the same-degree basis is the Bernstein basis; a smaller λ gives the inner basis
# functions less weight in that direction, so the bump over the raised inner points flattens
# (the curve's behaviour, row by row).

# %%
PAIRS = [(1, 1), (Fraction(-3, 2), 1), (1, Fraction(-3, 2)), (Fraction(-3, 2), Fraction(-3, 2))]
fig = plt.figure(figsize=(16, 4))
heights = []
for k, (lu, lv) in enumerate(PAIRS):
    s = lb.SameDegreeSurface(NET, lu, lv)
    ax = fig.add_subplot(1, 4, k + 1, projection="3d")
    plot_surface(s, ax, curvature="gaussian", samples=30)
    ax.set_title(f"λ_u = {lu}, λ_v = {lv}")
    heights.append(float(s.evaluate(0.5, 0.5)[2]))
fig.savefig(FIGURES / "surface_lambda.png", dpi=80)
print("height at the centre:", [round(h, 4) for h in heights])
# a smaller λ in either direction lowers the middle; in both, lower still
assert heights[0] > heights[1] > heights[3] and heights[0] > heights[2] > heights[3]
assert abs(heights[1] - heights[2]) < 1e-12  # the net is symmetric under u <-> v

# %% [markdown]
# ## Isoparametric curves are curves of the family
#
# `curve_at_u(u)` is the curve v ↦ S(u, v): a same-degree curve at λ_v, with exact control
# points.

# %%
s = lb.SameDegreeSurface(NET, Fraction(-1, 2), Fraction(1, 2))
iso = s.curve_at_u(Fraction(1, 2))
print(iso, iso.control_points()[1])
t = np.linspace(0, 1, 11)
assert np.allclose(iso.evaluate(t), s.evaluate(0.5, t))

# %% [markdown]
# ## The thin-plate-optimal (λ_u, λ_v)
#
# The thin-plate energy of this net is a polynomial in (λ_u, λ_v) of degree 2 in each; its exact
# global minimum over (−2, 1]² is found by resultants and Sturm isolation.

# %%
best = lb.optimal_parameters(NET, "thin_plate", "same_degree")
print(best["where"], best["lam_u"], best["lam_v"], best.energy)
poly = lb.surface_energy_matrices((3, 3), "thin_plate").polynomial(NET)
xs = np.linspace(-2, 1, 121)
x, y = np.meshgrid(xs, xs, indexing="ij")
energy = sum(float(c) * x**a * y**b for (a, b), c in poly.items())
assert float(best.energy) <= energy.min() + 1e-9
fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.5))
cs = ax1.contourf(x, y, np.log10(energy), 30)
fig.colorbar(cs, ax=ax1, label="log10 thin-plate energy")
ax1.plot(best["lam_u_float"], best["lam_v_float"], "r*", markersize=14)
ax1.set_xlabel("λ_u")
ax1.set_ylabel("λ_v")
ax2.remove()
ax2 = fig.add_subplot(1, 2, 2, projection="3d")
plot_surface(
    lb.SameDegreeSurface(NET, best["lam_u_float"], best["lam_v_float"]), ax2, curvature="mean"
)
ax2.set_title("the thin-plate-optimal surface")
fig.savefig(FIGURES / "surface_optimal.png", dpi=80)
