"""The geometry of a curve in its own parameter t on a domain (atom and C-Bézier curves):
arc length, boxes, closest points, location and intersections, through the exact rational
form where the curve has one (its parameter s mapped back to t) and the certified atom
machinery (_atom_geometry) otherwise.

`DomainGeometry` names, as a Protocol on ``self``, what it reads of the curve (the mixin
pattern of mypy's documentation).
"""

from __future__ import annotations

from fractions import Fraction
from typing import TYPE_CHECKING, Any, Protocol

import numpy as np
import numpy.typing as npt

from ._curve_shared import ControlPointCurve
from ._validate import PointsLike

if TYPE_CHECKING:
    from .geometry import ClosestPoint
    from .hazmat.intersect import Intersection
    from .rational import RationalBezierCurve


class _OnDomain(Protocol):
    @property
    def domain(self) -> tuple[float, float]: ...

    def _domain_point(self, t: object, name: str) -> float: ...

    def _rational_or_none(self, *, floats: bool = True) -> RationalBezierCurve | None: ...

    def s_of_t(self, t: float) -> np.ndarray | float: ...

    def t_of_s(self, s: np.ndarray | float) -> np.ndarray | float: ...


class DomainGeometry(ControlPointCurve):
    """Arc length, boxes, closest points, location and intersections of a curve in its own
    parameter t on `domain`: through `_rational_or_none()` (the rational form, its parameter
    s mapped back by `t_of_s`) when the curve has one, numerically (_atom_geometry) otherwise.
    A class supplies `domain`, `_domain_point` (a checked t) and, with a rational form,
    `_rational_or_none`, `s_of_t` and `t_of_s`."""

    def _rational_or_none(self, *, floats: bool = True) -> RationalBezierCurve | None:
        """The rational form the geometry goes through; here none (numeric geometry)."""
        return None

    def arc_length(
        self: _OnDomain, t0: Fraction | float | None = None, t1: Fraction | float | None = None
    ) -> float:
        """∫ ‖C'(t)‖ dt from t0 to t1 (default: the whole domain), relative accuracy 1e-12."""
        lo, hi = self.domain
        a = lo if t0 is None else self._domain_point(t0, "t0")
        b = hi if t1 is None else self._domain_point(t1, "t1")
        if a > b:
            raise ValueError(f"t0 = {t0} must not exceed t1 = {t1}")
        rat = self._rational_or_none(floats=False)
        if rat is not None:
            return rat.arc_length(self.s_of_t(a), self.s_of_t(b))  # type: ignore[arg-type]
        from . import _atom_geometry as ag

        return ag.arc_length(self, a, b)  # type: ignore[arg-type]

    def parameter_at_length(self: _OnDomain, s: npt.ArrayLike) -> np.ndarray | float:
        """The t at which the arc length from the domain's start equals s."""
        rat = self._rational_or_none(floats=False)
        if rat is not None:
            return self.t_of_s(rat.parameter_at_length(s))
        from . import _atom_geometry as ag

        return ag.parameter_at_length(self, s)  # type: ignore[arg-type]

    def bounding_box(self: _OnDomain) -> tuple[np.ndarray, np.ndarray]:
        """(lo, hi): the tight axis-aligned box of the curve over its domain."""
        rat = self._rational_or_none()
        if rat is not None:
            return rat.bounding_box()
        from . import _atom_geometry as ag

        return ag.bounding_box(self)  # type: ignore[arg-type]

    def closest_point(self: _OnDomain, q: npt.ArrayLike) -> ClosestPoint:
        """The nearest point to q ((d,) or a batch (m, d)); `t` in the curve's own t."""
        rat = self._rational_or_none()
        if rat is not None:
            from .geometry import ClosestPoint

            found = rat.closest_point(q)
            return ClosestPoint(self.t_of_s(found.t), found.point, found.distance)
        from . import _atom_geometry as ag

        return ag.closest_point(self, q)  # type: ignore[arg-type]

    def locate(self: _OnDomain, point: PointsLike) -> float | None:
        """The t with C(t) = point (within 1e-10 of the curve's size), or None."""
        rat = self._rational_or_none()
        if rat is not None:
            found = [float(self.t_of_s(s)) for s in rat._locate_all(point)]
            if len(found) > 1:
                raise ValueError(f"the point is on the curve at several parameters: {found}")
            return found[0] if found else None
        from . import _atom_geometry as ag

        return ag.locate(self, point)  # type: ignore[arg-type]

    def intersect(self, other: object) -> list[Intersection]:
        """Every isolated intersection with another curve, Intersection(s, t, kind) sorted by
        s: self(s) = other(t), each parameter in its own curve's t."""
        from . import _atom_geometry as ag
        from ._curve_base import Curve, _swapped_intersect
        from .rational import RationalBezierCurve

        if not isinstance(other, Curve | RationalBezierCurve | DomainGeometry):
            swapped = _swapped_intersect(other, self)  # a composite: its answer, s and t swapped
            if swapped is not None:
                return swapped
        return ag.intersect(self, other)  # type: ignore[arg-type]

    def segment(self, t1: Fraction | float, t2: Fraction | float) -> object:
        """The piece between C(t1) and C(t2), t1 < t2 in the domain, in the form `split`
        gives: the rational form's segment between s(t1) and s(t2) (a RationalBezierCurve on
        [0, 1]) where the curve has one; otherwise `split` twice (a C-Bézier family: a curve
        of the family again, the space being invariant under shifts of t)."""
        on: _OnDomain = self  # type: ignore[assignment]
        lo, hi = on.domain
        a, b = on._domain_point(t1, "t1"), on._domain_point(t2, "t2")
        if not a < b:
            raise ValueError(f"segment needs t1 < t2, got t1={t1}, t2={t2}")
        rat = self._rational_or_none()
        if rat is not None:
            return rat.segment(float(on.s_of_t(a)), float(on.s_of_t(b)))
        split: Any = self.split  # type: ignore[attr-defined]  # the class's own split
        piece: Any = self if b >= hi else split(b)[0]
        if a <= lo:
            return piece
        p_lo, p_hi = piece.domain  # [lo, b] of this curve, in the piece's own parameter
        return piece.split(p_lo + (a - lo) * (p_hi - p_lo) / (b - lo))[1]

    def self_intersections(self: _OnDomain) -> list[Intersection]:
        """Every pair s < t with C(s) = C(t), both in the curve's own t."""
        rat = self._rational_or_none()
        if rat is None:
            from . import _atom_geometry as ag

            return ag.self_intersections(self)  # type: ignore[arg-type]
        from .hazmat.intersect import Intersection

        return [
            Intersection(float(self.t_of_s(x.s)), float(self.t_of_s(x.t)), x.kind)
            for x in rat.self_intersections()
        ]
