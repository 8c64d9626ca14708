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
# # Bernstein-like λ-Bézier curves: petals, joins and shape adjustment
#
# Reproduces the figures of *Continuity conditions for λ-Bézier curves of degree n*
# (`001_33da2b0fa8491127.txt`) with `BernsteinLikeCurve`, `join` and `CompositeCurve`. The
# paper does not print its control points; **all control points here are our own**. The
# continuity at every joint is measured from the curves (positions, derivatives, tangents,
# curvatures), not read off the formulas.

# %%
import os
from fractions import Fraction as F
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import lambda_bezier as lb
from lambda_bezier.composite import measure
from lambda_bezier.plot import plot_composite, plot_curve

FIGURES = Path(os.environ.get("LAMBDA_BEZIER_FIGURES", Path.cwd() / "figures"))
FIGURES.mkdir(parents=True, exist_ok=True)
STYLES = {1: "-", 0: "--", -1: "-."}  # the paper's solid, dashed, dash-dotted for λ = 1, 0, -1


def reversed_curve(curve):
    """The same curve traversed backwards: both bases are symmetric, b_i(1-t) = b_{n-i}(t)."""
    return type(curve)(curve.control_points()[::-1], curve.lam)


def print_report(name, composite):
    for r in composite.report():
        print(
            f"{name} joint {r.index}: built {r.built_with.continuity if r.built_with else '-'}, "
            f"achieved {sorted(r.achieved)}, tangent angle {r.tangent_angle:.1e}"
        )


# %% [markdown]
# ## Fig. 1: petals drawn with cubic and quartic λ-curves, λ = 1, 0, −1
#
# Each petal is one closed control polygon (first point = last point at the centre); λ = 0 is
# the classical Bézier curve, λ = 1 pulls the curve towards the polygon, λ = −1 away from it.

# %%
fig, axes = plt.subplots(1, 2, figsize=(11, 5.5))
petal3 = np.array([(0, 0), (1.0, 2.2), (2.2, 1.0), (0, 0)])
petal4 = np.array([(0, 0), (0.3, 2.0), (1.6, 2.4), (2.0, 0.3), (0, 0)])
for ax, petal in zip(axes, (petal3, petal4), strict=True):
    for k in range(6):
        angle = k * np.pi / 3
        rot = np.array([[np.cos(angle), -np.sin(angle)], [np.sin(angle), np.cos(angle)]])
        pts = petal @ rot.T
        for lam, style in STYLES.items():
            curve = lb.BernsteinLikeCurve(pts, lam)
            plot_curve(
                curve,
                ax,
                polygon=(lam == 0),
                color=f"C{k}",
                linestyle=style,
                polygon_style={"color": "0.6"},
            )
    ax.set_title(f"degree {len(petal) - 1}: λ = 1 (solid), 0 (dashed), −1 (dash-dot)")
fig.savefig(FIGURES / "bernstein_like_petals_fig1.png", dpi=80)
plt.show()

# %% [markdown]
# ## Fig. 2: a closed C¹ "apple" of two quartic and two cubic segments
#
# The top quartic is given; the right cubic is joined C¹ to it; the left cubic is joined C¹
# to the *reversed* top curve (and reversed back), so it ends C¹ into the top's start; the
# bottom quartic takes its leading points from a C¹ join to the right cubic and its trailing
# points from a C¹ join to the reversed left cubic. All four joints, including the closing
# one, are then measured.

# %%
LAM = {"top": F(1, 2), "right": F(0), "bottom": F(1, 2), "left": F(0)}
top = lb.BernsteinLikeCurve(
    [(-1, F(5, 2)), (F(-1, 2), F(7, 2)), (0, F(3, 2)), (F(1, 2), F(7, 2)), (1, F(5, 2))],
    LAM["top"],
)
right = lb.join(top, "C1", 3, LAM["right"], rest=[(F(13, 5), F(-17, 5)), (F(6, 5), F(-33, 10))])
left = reversed_curve(
    lb.join(
        reversed_curve(top),
        "C1",
        3,
        LAM["left"],
        rest=[(F(-13, 5), F(-17, 5)), (F(-6, 5), F(-33, 10))],
    )
)
lead = lb.join(right, "C1", 4, LAM["bottom"], rest=[(0, F(-18, 5)), (0, 0), (0, 0)])
tail = lb.join(reversed_curve(left), "C1", 4, LAM["bottom"], rest=[(0, F(-18, 5)), (0, 0), (0, 0)])
bottom_pts = [*lead.control_points()[:3], tail.control_points()[1], tail.control_points()[0]]
bottom = lb.BernsteinLikeCurve(bottom_pts, LAM["bottom"])
apple = lb.CompositeCurve([top, right, bottom, left], ["C1", "C1", "C1"])
closing = measure(left, top, index=3)
print_report("apple", apple)
print(f"apple closing joint: achieved {sorted(closing.achieved)}")
assert all(r.holds("C1") for r in apple.report()) and closing.holds("C1")

fig, ax = plt.subplots(figsize=(5.5, 6))
for seg, color in zip(apple.segments, ("C3", "C0", "C3", "C0"), strict=True):
    plot_curve(seg, ax, color=color)
ax.set_title("C¹ apple: quartics red, cubics blue")
fig.savefig(FIGURES / "bernstein_like_apple_fig2.png", dpi=80)
plt.show()

# %% [markdown]
# ## Figs. 3–5: C², G¹ and G² composites
#
# Fig. 3: a cubic and a quartic joined C². Fig. 4: cubic, quartic and quintic joined G¹
# (α = 2 and α = 1/2). Fig. 5: a cubic and a quintic joined G² (α = 3/2, d = 1).

# %%
cubic = lb.BernsteinLikeCurve([(0, 0), (1, 2), (3, 3), (4, 1)], F(1, 2))
c2 = lb.CompositeCurve([cubic]).join("C2", 4, F(-1, 2), rest=[(8, 2), (9, 0)])
g1 = (
    lb.CompositeCurve([cubic])
    .join("G1", 4, F(0), alpha=2, rest=[(6, -2), (8, 0), (9, 2)])
    .join("G1", 5, F(1), alpha=F(1, 2), rest=[(11, 5), (13, 4), (14, 1), (16, 2)])
)
g2 = lb.CompositeCurve([cubic]).join(
    "G2", 5, F(-1), alpha=F(3, 2), d=1, rest=[(7, 0), (9, 3), (11, 1)]
)
for name, comp in (("C2", c2), ("G1", g1), ("G2", g2)):
    print_report(name, comp)
    assert all(r.kept for r in comp.report())

fig, axes = plt.subplots(1, 3, figsize=(16, 4.5))
for ax, (name, comp) in zip(axes, (("C²", c2), ("G¹", g1), ("G²", g2)), strict=True):
    plot_composite(comp, ax)
    ax.set_title(f"{name} joins (Fig. {3 + ['C²', 'G¹', 'G²'].index(name)})")
fig.savefig(FIGURES / "bernstein_like_joins_fig3_5.png", dpi=80)
plt.show()

# %% [markdown]
# ## Figs. 6–9: shape adjustment
#
# * **C¹ (Fig. 6).** With the control points fixed, changing one segment's λ breaks C¹ unless
#   the neighbours' λ change too (the paper's eq. 17): only global adjustment.
#   `with_lambda(0, λ, keep_points=True)` changes the top's λ and lets the right, bottom and
#   left λ follow through the C¹ joints (exactly: the end derivative is affine in λ); the
#   closing joint (left to top) is then measured.
# * **G¹ (Fig. 7).** λ scales end tangents but never turns them, so changing one λ with the
#   points fixed keeps G¹: local adjustment (`with_lambda(..., resolve=False)`).
# * **C², G² (Figs. 8, 9).** λ alone breaks them; changing λ *and* re-solving the joint's
#   leading points (the starred points) keeps them (`with_lambda(...)`, the default).


# %%
fig, axes = plt.subplots(1, 4, figsize=(20, 5))
ax = axes[0]
for seg in apple.segments:
    plot_curve(seg, ax, polygon=False, color="k")
for new_top, style in ((F(1), "--"), (F(-1, 2), "-.")):
    adjusted = apple.with_lambda(0, new_top, keep_points=True)
    t2, r2, b2, l2 = adjusted.segments
    ok = all(r.holds("C1") for r in adjusted.report()) and measure(l2, t2).holds("C1")
    print(
        f"Fig. 6: top λ = {new_top}: right λ = {r2.lam}, bottom λ = {b2.lam}, "
        f"left λ = {l2.lam}, C1 everywhere (closing joint too): {ok}"
    )
    assert ok and all(
        s.control_points() == o.control_points()
        for s, o in zip(adjusted.segments, apple.segments, strict=True)
    )
    for seg in adjusted.segments:
        plot_curve(seg, ax, polygon=False, color="C3", linestyle=style)
ax.set_title("Fig. 6: C¹ apple, global adjustment")

ax = axes[1]
plot_composite(g1, ax, color="k")
for lam, style in ((F(-1), "--"), (F(1), "-.")):
    changed = g1.with_lambda(1, lam, resolve=False)
    assert all(r.holds("G1") for r in changed.report())
    plot_composite(changed, ax, polygon=False, joints=False, color="C3", linestyle=style)
ax.set_title("Fig. 7: G¹, one λ changed, points fixed")

for ax, comp, name, idx in ((axes[2], c2, "C²", 1), (axes[3], g2, "G²", 1)):
    plot_composite(comp, ax, color="k")
    for lam, style in ((F(1), "--"), (F(1, 2) if name == "G²" else F(-1), "-.")):
        fixed_points = comp.with_lambda(idx, lam, resolve=False)
        resolved = comp.with_lambda(idx, lam)
        print(
            f"{name}: λ → {lam}: points fixed keeps {name}: "
            f"{fixed_points.report()[0].kept}; re-solved: {resolved.report()[0].kept}"
        )
        assert resolved.report()[0].kept
        plot_composite(resolved, ax, polygon=False, joints=False, color="C3", linestyle=style)
        moved = np.array(resolved.segments[idx].control_points()[:3], float)
        ax.plot(moved[:, 0], moved[:, 1], "*", color="C3", markersize=10)
    ax.set_title(f"Fig. {8 if name == 'C²' else 9}: {name}, λ and starred points changed")
fig.tight_layout()
fig.savefig(FIGURES / "bernstein_like_adjustment_fig6_9.png", dpi=80)
plt.show()
