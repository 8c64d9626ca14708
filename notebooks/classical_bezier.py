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
# # Classical Bézier curves: de Casteljau, subdivision, convexity
#
# The worked examples of the lecture notes *Chapter 4: Bézier curves and surfaces*
# (`002_b1311022d66a73a0.txt`), reproduced exactly (Fractions) with `BezierCurve`.

# %%
import os
from fractions import Fraction as F
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import lambda_bezier as lb
from lambda_bezier.plot import plot_curvature, plot_curve, plot_de_casteljau

FIGURES = Path(os.environ.get("LAMBDA_BEZIER_FIGURES", Path.cwd() / "figures"))
FIGURES.mkdir(parents=True, exist_ok=True)


def show(points):
    return ", ".join("(" + ", ".join(str(v) for v in p) + ")" for p in points)


# %% [markdown]
# ## de Casteljau's construction of p(1/3)
#
# The notes' example: P₀ = (0,0), P₁ = (1,3), P₂ = (2,1), P₃ = (3,3), t = 1/3. Each level of
# intermediate points divides the previous legs in the ratio t : (1 − t).

# %%
P = [(0, 0), (1, 3), (2, 1), (3, 3)]
cubic = lb.BezierCurve(P)
left, right = cubic.split(F(1, 3))
print("first half :", show(left.control_points()))
print("second half:", show(right.control_points()))
assert left.control_points()[-1] == (1, F(5, 3))  # the notes' p(1/3) = (1, 5/3)

fig, ax = plt.subplots(figsize=(6, 5))
plot_curve(cubic, ax, polygon=False, color="0.5", label="p(t)")
plot_de_casteljau(P, F(1, 3), ax)
ax.legend(fontsize=8)
ax.set_title("de Casteljau at t = 1/3")
fig.savefig(FIGURES / "bezier_de_casteljau.png", dpi=80)
plt.show()

# %% [markdown]
# ## Subdivision between t₁ = 1/4 and t₂ = 3/4
#
# The notes' second example: b = (−9,0), (−3,6), (3,6), (9,0). Scheme 1 splits at 3/4, then
# splits the left piece at (1/4)/(3/4) = 1/3 and keeps the right part; the result is the
# piece of the curve between P(1/4) and P(3/4), reparametrised to [0, 1].

# %%
arch = lb.BezierCurve([(-9, 0), (-3, 6), (3, 6), (9, 0)])
piece = arch.segment(F(1, 4), F(3, 4))
print("segment [1/4, 3/4]:", show(piece.control_points()))
u = np.linspace(0, 1, 7)
assert np.allclose(piece.evaluate(u), arch.evaluate(0.25 + 0.5 * u))

fig, ax = plt.subplots(figsize=(7, 3.5))
plot_curve(arch, ax, label="whole curve", color="0.5")
plot_curve(piece, ax, label="piece [1/4, 3/4]", color="C3", linewidth=2.5)
ax.legend(fontsize=8)
fig.savefig(FIGURES / "bezier_segment.png", dpi=80)
plt.show()

# %% [markdown]
# ## The convexity example
#
# A quartic with b₀ = (0,0), b₁ = (1/4,1/4), b₂ = (1/2,ω), b₃ = (3/4,1/4), b₄ = (1,0). Its
# x(t) = t, so y is a function of x; the notes say the curve is convex for 0 ≤ ω ≤ 1/2 and has
# two inflection points otherwise — even though for 0 < ω < 1/4 the control polygon is not
# convex. We check it on the curve's own second derivative (computed from the generated
# hodograph), not on the notes' printed y″.

# %%
fig, axes = plt.subplots(1, 2, figsize=(11, 4))
for omega in (F(-1, 4), F(0), F(1, 8), F(1, 4), F(1, 2), F(3, 4)):
    quartic = lb.BezierCurve(
        [(0, 0), (F(1, 4), F(1, 4)), (F(1, 2), omega), (F(3, 4), F(1, 4)), (1, 0)]
    )
    x = np.linspace(0, 1, 401)
    y2 = quartic.derivative(x, 2)[:, 1]  # x(t) = t, so d²y/dx² = y''(t)
    convex = bool(np.all(y2 <= 1e-12) or np.all(y2 >= -1e-12))
    print(f"ω = {omega}: convex = {convex}")
    assert convex == (0 <= omega <= F(1, 2))
    plot_curve(quartic, axes[0], polygon=omega == F(1, 8), label=f"ω = {omega}")
    axes[1].plot(x, y2, label=f"ω = {omega}")
axes[0].legend(fontsize=7)
axes[1].axhline(0, color="k", linewidth=0.5)
axes[1].set_xlabel("x")
axes[1].set_ylabel("y''")
fig.savefig(FIGURES / "bezier_convexity.png", dpi=80)
plt.show()

# %% [markdown]
# ## Curvature at the ends
#
# The end curvature of the notes, k(0) = ((n−1)/n)|Δb₀ × Δb₁|/|Δb₀|³, from the library's
# derivatives.

# %%
fig, ax = plt.subplots(figsize=(5, 3))
plot_curvature(cubic, ax)
print("curvature at t = 0 and 1:", cubic.curvature([0.0, 1.0]))
fig.savefig(FIGURES / "bezier_curvature.png", dpi=80)
plt.show()
