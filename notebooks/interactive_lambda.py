# ---
# jupyter:
#   execution:
#     timeout: 30
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
# # Exploring λ interactively
#
# Sliders for the shape parameter λ, the energy order k (1 stretch, 2 strain, 3 jerk) and the
# family redraw three panels: the curve with its control polygon (beside the classical Bézier
# curve on the same polygon and the curve at the E_k-optimal λ), its curvature against t, and
# E_k(λ) over the family's range with the chosen λ and the optimum marked.
#
# The sliders need a running kernel (Jupyter Lab or Notebook, with `pip install
# ".[notebooks]"`). The first drawing below is a plain function call, so the notebook also
# runs top to bottom without a browser (the tests run it that way, and the documentation
# shows that picture).

# %%
import os
from pathlib import Path

import ipywidgets as widgets
import matplotlib.pyplot as plt
import numpy as np
from IPython.display import display

import lambda_bezier as lb
from lambda_bezier.energy import ENERGY_NAMES
from lambda_bezier.plot import plot_curvature, plot_curve

FIGURES = Path(os.environ.get("LAMBDA_BEZIER_FIGURES", Path.cwd() / "figures"))
FIGURES.mkdir(parents=True, exist_ok=True)

# Our own polygon (degree 4, used for Fig. 4 in same_degree_energy.py): both λ families
# take it, and the E_1, E_2 and E_3 optima all lie inside their ranges.
POINTS = [(1, 2), (2, 2), (7, 6), (9, 4), (10, 4)]
# The λ-range of each family, as the library states it; the slider stays inside the open end.
RANGES = {"same_degree": (-2.0, 1.0), "bernstein_like": (-1.0, 1.0)}
STEP = 0.01

# %% [markdown]
# ## The drawing
#
# `draw(family, lam, k)` does all the work; the widgets below only call it. E_k(λ) is an exact
# quadratic in λ (`energy_coefficients`), so the right-hand panel is that parabola, not a
# sampled integral; the optimum comes from `optimal_lambda(..., clamp=True)`.


# %%
def draw(family="same_degree", lam=0.5, k=2, save_as=None):
    """Curve, control polygon, curvature and E_k(λ) for one choice of family, λ and k."""
    fig, (ax_curve, ax_kappa, ax_energy) = plt.subplots(1, 3, figsize=(15, 4.5))
    bezier = lb.BezierCurve(POINTS)
    plot_curve(bezier, ax_curve, polygon=False, color="0.6", linewidth=1, label="Bézier")
    plot_curvature(bezier, ax_kappa, color="0.6", linewidth=1, label="Bézier")
    if family == "bezier":
        curve = bezier
        plot_curve(curve, ax_curve, color="C0", label="Bézier (no λ)")
        ax_energy.text(0.5, 0.5, "the classical Bézier curve\nhas no shape parameter",
                       ha="center", va="center", transform=ax_energy.transAxes)  # fmt: skip
        ax_energy.set_axis_off()
        summary = f"bezier: E_{k} = {float(curve.energy(k)):.4f}"
    else:
        curve = lb.FAMILIES[family](POINTS, lam)
        best = lb.optimal_lambda(POINTS, k, family, clamp=True)
        optimal = lb.FAMILIES[family](POINTS, best.lam, check_range=False)
        plot_curve(curve, ax_curve, color="C0", label=f"λ = {lam:.2f}")
        plot_curve(optimal, ax_curve, polygon=False, color="C3", linestyle="--",
                   label=f"E{k}-optimal λ = {float(best.lam):.3f}")  # fmt: skip
        plot_curvature(curve, ax_kappa, color="C0", label=f"λ = {lam:.2f}")
        plot_curvature(optimal, ax_kappa, color="C3", linestyle="--", label="E-optimal")
        a0, a1, a2 = (float(a) for a in lb.energy_coefficients(POINTS, k, family))
        lo, hi = RANGES[family]
        grid = np.linspace(lo, hi, 200)
        ax_energy.plot(grid, a0 + a1 * grid + a2 * grid**2, color="k", linewidth=1)
        ax_energy.plot([lam], [a0 + a1 * lam + a2 * lam**2], "o", color="C0", label="chosen λ")
        ax_energy.plot([float(best.lam)], [float(best.energy)], "s", color="C3", label="optimum")
        ax_energy.set_xlabel("λ")
        ax_energy.set_ylabel(f"E{k}(λ)")
        ax_energy.set_title(f"E{k} ({ENERGY_NAMES[k]}) over {best.range_text}")
        ax_energy.legend(fontsize=8)
        summary = (
            f"{family}: E_{k}(λ = {lam:.2f}) = {float(curve.energy(k)):.4f}; "
            f"optimum λ* = {best.lam} ≈ {float(best.lam):.4f}, E_{k}(λ*) = {float(best.energy):.4f}"
        )
    ax_curve.set_title(f"{family}, degree {curve.degree}")
    ax_curve.legend(fontsize=8)
    ax_kappa.set_title("curvature")
    ax_kappa.legend(fontsize=8)
    fig.tight_layout()
    if save_as:
        fig.savefig(FIGURES / save_as, dpi=80)
    print(summary)
    plt.show()
    return curve


# %% [markdown]
# ## One drawing, without widgets
#
# The same-degree curve at λ = 1/2 against its strain-optimal (E₂) curve.

# %%
curve = draw("same_degree", 0.5, 2, save_as="interactive_lambda.png")
best = lb.optimal_lambda(POINTS, 2, "same_degree", clamp=True)
# the optimum is a minimum: no λ on a fine grid over the range gives a smaller strain energy
grid = np.linspace(RANGES["same_degree"][0] + STEP, 1.0, 300)
assert all(lb.SameDegreeCurve(POINTS, lam).energy(2) >= float(best.energy) - 1e-9 for lam in grid)

# %% [markdown]
# ## The sliders
#
# Changing the family moves the λ slider's bounds to that family's range (the Bézier family
# has no λ, so the slider is disabled there).

# %%
family_widget = widgets.Dropdown(
    options=["same_degree", "bernstein_like", "bezier"], value="same_degree", description="family"
)
lam_widget = widgets.FloatSlider(
    value=0.5, min=RANGES["same_degree"][0] + STEP, max=1.0, step=STEP, description="λ"
)
k_widget = widgets.IntSlider(value=2, min=1, max=3, description="energy k")


def follow_family(change):
    """Keep λ inside the new family's range (an open end is kept one step away)."""
    if change["new"] == "bezier":
        lam_widget.disabled = True
        return
    lam_widget.disabled = False
    lo, hi = RANGES[change["new"]]
    lam_widget.min = lo + STEP if change["new"] == "same_degree" else lo
    lam_widget.max = hi


family_widget.observe(follow_family, names="value")
controls = widgets.interactive(
    draw, family=family_widget, lam=lam_widget, k=k_widget, save_as=widgets.fixed(None)
)
display(controls)

# %% [markdown]
# Outside a kernel nothing reacts to a mouse, but the widgets still work as objects: setting
# the family redraws through `draw` (its return value is the curve drawn) and moves the λ
# slider's bounds.

# %%
for family, bounds in [("bernstein_like", (-1.0, 1.0)), ("bezier", None), ("same_degree", None)]:
    controls.result = None
    family_widget.value = family
    assert isinstance(controls.result, lb.FAMILIES[family]), f"drawing {family} failed"
    assert lam_widget.disabled == (family == "bezier")
    if bounds:
        assert (lam_widget.min, lam_widget.max) == bounds
k_widget.value = 3
assert controls.result.family == "same_degree" and controls.result.lam == lam_widget.value
