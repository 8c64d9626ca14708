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
# # The same-degree λ-Bézier curve and its energy-optimal λ
#
# Reproduces the figures of *Extension of Bézier curves of the same degree and the parameter
# selection* (`000_10ca634d356c575d.txt`) from the library: the curves whose λ minimises the
# stretch (E₁), strain (E₂) and jerk (E₃) energy beside the classical Bézier curve, with their
# curvature plots (Figs. 3–8), the section 4.2 example, and the geometric evaluation algorithm
# (Fig. 1).
#
# The paper does not print the control points of Figs. 3–8, so **the control points below are
# our own choice**; the comparison it draws (E₁ straightens the legs, E₂ looks smooth, E₃ stays
# close to the Bézier curve) can be checked on them.

# %%
import os
from fractions import Fraction
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import lambda_bezier as lb
from lambda_bezier.plot import plot_curvature, plot_curve

FIGURES = Path(os.environ.get("LAMBDA_BEZIER_FIGURES", Path.cwd() / "figures"))
FIGURES.mkdir(parents=True, exist_ok=True)

# %% [markdown]
# ## Figs. 3–8: E₁-, E₂-, E₃-optimal curves of degree 3, 4, 5 and the Bézier curve
#
# `optimal_lambda(points, k, clamp=True)` returns the exact minimiser over the admissible range
# (−2, 1]; the unconstrained optimum is reported too, so nothing outside the range is hidden.

# %%
# Our own control points (the paper does not print those of Figs. 3-8), chosen so that all
# three optima are admissible, as they are in the paper's figures.
POLYGONS = {
    3: [(2, 7), (4, 0), (6, 4), (10, 4)],
    4: [(1, 2), (2, 2), (7, 6), (9, 4), (10, 4)],
    5: [(2, 2), (4, 2), (7, 2), (7, 4), (8, 4), (9, 4)],
}

for n, pts in POLYGONS.items():
    fig, axes = plt.subplots(2, 4, figsize=(16, 7))
    for col, k in enumerate((1, 2, 3)):
        result = lb.optimal_lambda(pts, k, clamp=True)
        lam = result.lam
        note = "" if result.unconstrained_admissible else f" (clamped from {result.unconstrained})"
        print(
            f"n={n} E_{k}: λ* = {lam} ≈ {float(lam):.6f}{note}, E_{k} = {float(result.energy):.4f}"
        )
        curve = lb.SameDegreeCurve(pts, lam, check_range=False)
        plot_curve(curve, axes[0, col], label=f"E{k}: λ={float(lam):.3f}")
        axes[0, col].set_title(f"degree {n}, E{k}-optimal")
        plot_curvature(curve, axes[1, col])
    bez = lb.BezierCurve(pts)
    plot_curve(bez, axes[0, 3], color="k")
    axes[0, 3].set_title(f"degree {n}, Bézier (λ = 1)")
    plot_curvature(bez, axes[1, 3], color="k")
    fig.tight_layout()
    fig.savefig(FIGURES / f"same_degree_energy_n{n}.png", dpi=80)
    plt.show()

# %% [markdown]
# ## Section 4.2: the published example, λ = −690/319
#
# For (0,6), (0,2), (5,2), (7,0), (2,0), (6,8) the strain-energy optimum is exactly
# −690/319 ≈ −2.163, **outside** the admissible range (−2, 1]: the basis is no longer
# non-negative there. The library says so, and `clamp=True` gives the constrained optimum.

# %%
EXAMPLE = [(0, 6), (0, 2), (5, 2), (7, 0), (2, 0), (6, 8)]
free = lb.optimal_lambda(EXAMPLE, 2)
clamped = lb.optimal_lambda(EXAMPLE, 2, clamp=True)
assert free.lam == Fraction(-690, 319)
print(f"unconstrained λ* = {free.lam} ≈ {float(free.lam):.6f}, admissible: {free.admissible}")
print(f"clamped λ = {clamped.lam}: E2 = {clamped.energy} vs {free.energy} unconstrained")
try:
    lb.SameDegreeCurve(EXAMPLE, free.lam)
except ValueError as exc:
    print("SameDegreeCurve refuses it:", exc)

fig, ax = plt.subplots(figsize=(6, 6))
plot_curve(
    lb.SameDegreeCurve(EXAMPLE, free.lam, check_range=False),
    ax,
    label="λ = −690/319 (outside the range)",
)
plot_curve(
    lb.SameDegreeCurve(EXAMPLE, Fraction(-199, 100)),
    ax,
    polygon=False,
    label="λ = −1.99 (inside, near the clamped optimum)",
    linestyle="--",
)
plot_curve(lb.BezierCurve(EXAMPLE), ax, polygon=False, label="Bézier", color="k", linewidth=0.8)
ax.legend(fontsize=8)
fig.savefig(FIGURES / "same_degree_example_4_2.png", dpi=80)
plt.show()

# %% [markdown]
# ## Fig. 1: the geometric evaluation algorithm (n = 5, t = 2/3, λ = 1/2)
#
# Two de Casteljau steps take the quintic down to a cubic λ-curve (eq. 14); eq. 16 turns its
# control points into those of a cubic Bézier curve (Q, the points dividing the outer legs in
# the ratio (2+λ):(1−λ)); three more de Casteljau steps (eq. 15) give p(2/3). The control
# points are our own; every level is computed exactly.

# %%
FIG1 = [(0, 0), (1, 3), (3, 4), (5, 3), (6, 1), (8, 2)]
curve = lb.SameDegreeCurve(FIG1, Fraction(1, 2))
levels = curve.geometric_levels(Fraction(2, 3))
assert np.allclose(np.array(levels[-1][0], float), curve.evaluate(2 / 3))
print("p(2/3) =", levels[-1][0], "=", curve.evaluate(2 / 3))

fig, ax = plt.subplots(figsize=(7, 5))
plot_curve(curve, ax, polygon=False, color="0.6", label="λ-Bézier curve")
names = ["V⁰ (control points)", "V¹", "V²", "Q (eq. 16)", "Q¹", "Q²", "p(2/3)"]
markers = ["o", "D", "D", "s", "v", "o", "."]
for level, name, marker in zip(levels, names, markers, strict=True):
    arr = np.array(level, dtype=float)
    ax.plot(arr[:, 0], arr[:, 1], marker=marker, linestyle="-", linewidth=0.7, label=name)
ax.legend(fontsize=7)
ax.set_title("Geometric evaluation, n = 5, t = 2/3, λ = 1/2")
fig.savefig(FIGURES / "same_degree_geometric_fig1.png", dpi=80)
plt.show()

# %% [markdown]
# ## Fig. 2: shape adjustment of a closed composite of cubic λ-curves
#
# Three cubic same-degree segments joined G¹ (Prop. 9: V₂₀ = V₁ₘ, V₂₁ = V₂₀ + C(V₁ₘ − V₁,ₘ₋₁)
# with C > 0), the last ending where the first starts. G¹ only asks the end tangents to be
# parallel, and λ scales end tangents without turning them, so changing λ with the control
# points fixed keeps every joint G¹: segments 1 and 3 set to λ = 0 (local change), then all
# segments to λ = −1.5 (global change), as in the paper. Control points of our own.

# %%
loop = lb.CompositeCurve(
    [
        lb.SameDegreeCurve([(0, -3), (3, -3), (5, 0), (3, 3)], 1),
        lb.SameDegreeCurve([(3, 3), (1, 6), (-1, 6), (-3, 3)], 1),
        lb.SameDegreeCurve([(-3, 3), (-5, 0), (-3, -3), (0, -3)], 1),
    ],
    ["G1", "G1"],
)
variants = {
    "λ = 1 (Bézier)": loop,
    "segments 1, 3: λ = 0": loop.with_lambda(0, 0, resolve=False).with_lambda(2, 0, resolve=False),
    "all: λ = −1.5": loop.with_lambda(0, -1.5, resolve=False)
    .with_lambda(1, -1.5, resolve=False)
    .with_lambda(2, -1.5, resolve=False),
}
fig, ax = plt.subplots(figsize=(6, 6))
for (name, comp), style in zip(variants.items(), ("-", ":", "-"), strict=True):
    closing = lb.CompositeCurve([comp.segments[-1], comp.segments[0]]).report()[0]
    kept = all(r.holds("G1") for r in comp.report()) and closing.holds("G1")
    print(f"{name}: G1 at every joint (closing one included): {kept}")
    assert kept
    for seg in comp.segments:
        plot_curve(
            seg,
            ax,
            polygon=name.startswith("λ = 1"),
            linestyle=style,
            color={"-": "k", ":": "k"}[style] if "−1.5" not in name else "C3",
        )
ax.set_title("Fig. 2: closed G¹ composite, λ changed per segment")
fig.savefig(FIGURES / "same_degree_composite_fig2.png", dpi=80)
plt.show()
