"""Plotting surfaces (optional extra: pip install "lambda-bezier[plot]").

``plot_surface`` draws a 3D surface on a matplotlib 3D Axes (a new one when none is given),
optionally with its control net and coloured by Gaussian or mean curvature, and returns it.
"""

from __future__ import annotations

import contextlib
from typing import TYPE_CHECKING, Any

import numpy as np

from . import _validate as val

try:
    import matplotlib.pyplot as plt
    from matplotlib import cm, colors
except ImportError as exc:  # pragma: no cover - exercised only without the extra
    raise ImportError(
        "lambda_bezier.surface_plot needs matplotlib: pip install 'lambda-bezier[plot]'"
    ) from exc

if TYPE_CHECKING:
    from matplotlib.axes import Axes

    from .surfaces import Surface

COLOURINGS = ("gaussian", "mean", "none")
MAX_SAMPLES = 2000  # per direction: 4 million points, far past what a plot resolves


def plot_surface(
    surf: Surface,
    ax: Axes | None = None,
    *,
    net: bool = True,
    curvature: str = "gaussian",
    samples: int = 40,
    cmap: str = "coolwarm",
    **surface_kwargs: Any,  # matplotlib's plot_surface properties
) -> Axes:
    """The surface over a samples x samples grid, coloured by its Gaussian or mean curvature
    (a colour map centred on zero; "none" for one colour), with its control net."""
    from .surfaces import Surface

    if not isinstance(surf, Surface):
        raise TypeError(f"surf must be a lambda_bezier surface, got {type(surf).__name__}")
    if surf.dimension != 3:
        raise ValueError(
            f"plot_surface draws surfaces in 3D, this one has dimension {surf.dimension}"
        )
    curvature = val.choice(curvature, "curvature", COLOURINGS)
    samples = val.integer(samples, "samples")
    if not 2 <= samples <= MAX_SAMPLES:
        raise ValueError(f"samples must be from 2 to {MAX_SAMPLES}, got {samples}")
    net = val.flag(net, "net")
    if not isinstance(cmap, str | colors.Colormap):
        raise TypeError(f"cmap must be a colour map or its name, got {type(cmap).__name__}")
    try:
        plt.get_cmap(cmap)
    except ValueError:
        raise ValueError(f"cmap {cmap!r} is not a matplotlib colour map") from None
    if ax is None:
        ax = plt.figure().add_subplot(projection="3d")
    elif not hasattr(ax, "plot_surface"):
        raise TypeError(
            f"ax must be a matplotlib 3D Axes (add_subplot(projection='3d')), got "
            f"{type(ax).__name__}"
        )
    # an AtomSurface (atom_surfaces) lives on its families' domains, every other on [0, 1]²
    (u0, u1), (v0, v1) = getattr(surf, "domain_u", (0.0, 1.0)), getattr(surf, "domain_v", (0, 1))
    tu, tv = np.linspace(u0, u1, samples), np.linspace(v0, v1, samples)
    pts = surf.evaluate_grid(tu, tv)
    kwargs: dict[str, Any] = {"linewidth": 0, "antialiased": True, "alpha": 0.9}
    if curvature != "none":
        uu, vv = np.meshgrid(tu, tv, indexing="ij")
        values = _curvature_values(surf, uu, vv, curvature == "gaussian")
        # the colour of a quad is that of its first corner: centre the map on zero
        top = float(np.nanmax(np.abs(values))) if np.isfinite(values).any() else 0.0
        norm = colors.Normalize(-(top or 1.0), top or 1.0)
        colour_map = plt.get_cmap(cmap).with_extremes(bad="0.6")
        kwargs["facecolors"] = colour_map(norm(np.ma.masked_invalid(values)))
        mappable = cm.ScalarMappable(norm=norm, cmap=cmap)
        mappable.set_array(values)
        ax.figure.colorbar(mappable, ax=ax, shrink=0.6, label=f"{curvature} curvature")
    kwargs.update(surface_kwargs)
    surface_ax: Any = ax  # a 3D Axes (mpl_toolkits.mplot3d), which the stubs do not type
    surface_ax.plot_surface(pts[..., 0], pts[..., 1], pts[..., 2], **kwargs)
    if net:
        p = surf.net
        style: dict[str, Any] = {"color": "0.3", "linewidth": 0.7, "marker": "o", "markersize": 2.5}
        for i in range(p.shape[0]):
            surface_ax.plot(p[i, :, 0], p[i, :, 1], p[i, :, 2], **style)
        for j in range(p.shape[1]):
            surface_ax.plot(p[:, j, 0], p[:, j, 1], p[:, j, 2], **style)
    return ax


def _curvature_values(surf: Surface, uu: np.ndarray, vv: np.ndarray, gaussian: bool) -> np.ndarray:
    """K or H on the grid; NaN (drawn grey) at the points where the normal is undefined (a
    collapsed edge, S_u parallel to S_v), which `curvatures` refuses with a ValueError."""
    pick = 0 if gaussian else 1
    try:
        out: np.ndarray = np.asarray(surf.curvatures(uu, vv)[pick], dtype=float)
        return out
    except ValueError:
        values = np.full(uu.shape, np.nan)
        for idx in np.ndindex(uu.shape):
            with contextlib.suppress(ValueError):  # undefined here: left NaN
                values[idx] = float(surf.curvatures(uu[idx], vv[idx])[pick])
        return values
