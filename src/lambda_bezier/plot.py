"""Plotting helpers (optional extra: pip install "lambda-bezier[plot]").

Each function draws on a matplotlib Axes (a new one when none is given) and returns it.
Composite curves only need ``segments`` and ``evaluate``-capable segments, so any object
with a ``segments`` attribute of curves works.
"""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction
from typing import TYPE_CHECKING, Any

import numpy as np

try:
    import matplotlib.pyplot as plt
except ImportError as exc:  # pragma: no cover - exercised only without the extra
    raise ImportError(
        "lambda_bezier.plot needs matplotlib: pip install 'lambda-bezier[plot]'"
    ) from exc

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.typing import ColorType

    from .atom_family import AtomCurve
    from .composite import CompositeCurve
    from .curves import Curve

SAMPLES = 400


def _axes(ax: Axes | None) -> Axes:
    if ax is None:
        new: Axes
        _, new = plt.subplots()
        return new
    return ax


def plot_curve(
    curve: Curve | AtomCurve,
    ax: Axes | None = None,
    *,
    polygon: bool = True,
    samples: int = SAMPLES,
    label: str | None = None,
    color: ColorType | None = None,
    polygon_style: dict[str, Any] | None = None,
    **line_kwargs: Any,  # matplotlib's Line2D properties
) -> Axes:
    """The curve (2D, or the xy projection of a 3D curve) with its control polygon."""
    ax = _axes(ax)
    lo, hi = getattr(curve, "domain", (0.0, 1.0))  # an AtomCurve: its family's domain of t
    t = np.linspace(lo, hi, samples)
    xy = curve.evaluate(t)
    (line,) = ax.plot(xy[:, 0], xy[:, 1], label=label, color=color, **line_kwargs)
    if polygon:
        style: dict[str, Any] = {  # matplotlib's Line2D properties
            "color": line.get_color(),
            "linestyle": ":",
            "marker": "o",
            "markersize": 3,
            "linewidth": 0.8,
            "alpha": 0.7,
        }
        style.update(polygon_style or {})
        pts = curve.points
        ax.plot(pts[:, 0], pts[:, 1], **style)
    ax.set_aspect("equal", adjustable="datalim")
    return ax


def plot_curvature(
    curve: Curve,
    ax: Axes | None = None,
    *,
    samples: int = SAMPLES,
    label: str | None = None,
    **line_kwargs: Any,  # matplotlib's Line2D properties
) -> Axes:
    """Curvature against t (signed in 2D)."""
    ax = _axes(ax)
    t = np.linspace(0.0, 1.0, samples)
    ax.plot(t, curve._curvature(t), label=label, **line_kwargs)  # gaps where undefined
    ax.set_xlabel("t")
    ax.set_ylabel("curvature")
    return ax


def plot_composite(
    composite: CompositeCurve,
    ax: Axes | None = None,
    *,
    polygon: bool = True,
    samples: int = SAMPLES,
    joints: bool = True,
    **line_kwargs: Any,  # matplotlib's Line2D properties
) -> Axes:
    """Every segment of a composite curve, with its joints marked."""
    ax = _axes(ax)
    for idx, seg in enumerate(composite.segments):
        plot_curve(
            seg,
            ax,
            polygon=polygon,
            samples=samples,
            label=line_kwargs.pop("label", None) if idx == 0 else None,
            **line_kwargs,
        )
    if joints:
        ends = composite.evaluate(np.array(composite.breaks[1:-1]))
        if len(ends):
            ax.plot(ends[:, 0], ends[:, 1], "ks", markersize=5, label="joints")
    return ax


def plot_de_casteljau(
    points: np.ndarray | Sequence[Sequence[Fraction | float]],
    t: float,
    ax: Axes | None = None,
    *,
    colors: Sequence[ColorType] | None = None,
) -> Axes:
    """The de Casteljau construction of p(t): every level of intermediate points."""
    from .hazmat.kernels import de_casteljau_triangle

    ax = _axes(ax)
    rows = de_casteljau_triangle([tuple(map(float, p)) for p in points], float(t))
    colors = colors or plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for level, row in enumerate(rows):
        arr = np.array(row)
        color = colors[level % len(colors)]
        ax.plot(
            arr[:, 0],
            arr[:, 1],
            "-o",
            color=color,
            markersize=4,
            linewidth=0.8,
            label=f"level {level}",
        )
    ax.set_aspect("equal", adjustable="datalim")
    return ax
