"""Parameters of any shape for a surface's pointwise methods (evaluate, derivative, normal,
curvatures): u and v that broadcast together (a meshgrid, a column against a row) are
evaluated flat and the result takes their shape, S(U, V) of shape U.shape + (d,).

The pointwise kernels take scalars or 1-D arrays of equal length; this layer is the one
place that flattens and reshapes, so every surface class (surfaces, atom_surfaces) gets it
from `Surface` without its own code."""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import Any, TypeVar

import numpy as np

Method = TypeVar("Method", bound=Callable[..., Any])


def _shape(x: object) -> tuple[int, ...] | None:
    """x's array shape, or None when numpy cannot read it as an array (the pointwise path's
    own checks then name the problem)."""
    if isinstance(x, np.ndarray):  # no object copy of a large float array
        return tuple(x.shape)
    try:
        return tuple(np.shape(np.asarray(x, dtype=object)))
    except (TypeError, ValueError):
        return None


def grid_shaped(method: Method) -> Method:
    """Wrap a method (self, u, v, ...) whose result is (k, ...) for 1-D u, v of length k (or a
    tuple of such results): u, v of two or more dimensions are broadcast, flattened, and the
    result reshaped to the broadcast shape + the trailing axes."""
    if getattr(method, "_grid_shaped", False):
        return method

    @functools.wraps(method)
    def shaped(self: Any, u: Any, v: Any, *args: Any, **kwargs: Any) -> Any:
        su, sv = _shape(u), _shape(v)
        if su is None or sv is None or max(len(su), len(sv)) < 2:
            return method(self, u, v, *args, **kwargs)
        try:
            shape = np.broadcast_shapes(su, sv)
        except ValueError:
            raise ValueError(
                f"u and v must broadcast together (as in a meshgrid), got shapes {su} and {sv}"
            ) from None
        uu = np.broadcast_to(np.asarray(u), shape).ravel()
        vv = np.broadcast_to(np.asarray(v), shape).ravel()
        out = method(self, uu, vv, *args, **kwargs)
        if isinstance(out, tuple):
            return tuple(np.asarray(x).reshape(shape + np.shape(x)[1:]) for x in out)
        return np.asarray(out).reshape(shape + np.shape(out)[1:])

    shaped._grid_shaped = True  # type: ignore[attr-defined]
    return shaped  # type: ignore[return-value]


# the methods that take paired (u, v); a subclass that overrides one (atom_surfaces'
# derivative) is wrapped again by Surface.__init_subclass__
POINTWISE = ("derivative", "normal", "curvatures")


def wrap_overrides(cls: type) -> None:
    for name in POINTWISE:
        if name in cls.__dict__:
            setattr(cls, name, grid_shaped(cls.__dict__[name]))
