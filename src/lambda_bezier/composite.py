"""Composite curves: segments joined end to end, evaluated on one global parameter, with the
continuity actually achieved at every joint measured numerically, and the shape adjustment of
001, section 3.3 (change one segment's λ, re-solve the joints so their continuity is kept).

Parametrisation: a composite of N polynomial segments lives on u ∈ [0, N]; segment i covers
[i, i + 1] with local parameter t = u − i (u = i itself belongs to segment i, u = N to the
last). A segment of a trigonometric, hyperbolic or mixed family (`AtomCurve`) keeps its own
domain [lo, hi] (e.g. [0, π/2]): it covers an interval of u of length hi − lo, on which its
own t = lo + (u − start); the composite's domain is then [0, Σ lengths] (floats). Either way
derivatives are taken with respect to u, so they equal the segments' own t-derivatives (the
derivatives lambda_bezier.join matches), and a C_k joint makes the composite k times
continuously differentiable in u there.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from . import _validate as val
from ._lazy import deferred
from ._validate import ParamLike, PointsLike
from .atom_family import AtomCurve
from .curves import Curve, elsewhere
from .joins import Joint, join

if TYPE_CHECKING:
    from types import ModuleType

    from . import geometry as _geometry
    from .hazmat.intersect import Intersection
else:

    def _load_geometry() -> ModuleType:
        from . import geometry

        return geometry

    _geometry = deferred(_load_geometry)  # imported when a geometry method is first called

NAMES = ("C0", "C1", "C2", "G1", "G2")
Segment = Curve | AtomCurve  # a polynomial curve on [0, 1], or one of an atom family


def _own_domain(seg: object) -> bool:
    """Whether a segment keeps its own domain: an AtomCurve, or a curve whose family has its
    parameter in the domain (it gives `end_derivatives`: a C-Bézier curve on [0, alpha])."""
    return isinstance(seg, AtomCurve) or (
        not isinstance(seg, Curve) and hasattr(seg, "end_derivatives")
    )


@dataclass(frozen=True)
class JointReport:
    r"""The continuity measured at the joint between segment `index` and `index + 1`
    (global parameter u = breaks[index + 1]), from evaluate/derivative/curvature of the segments
    :math:`C_1` (the left one) and :math:`C_2` (the right one).

    Attributes
    ----------
    index : int
        The left segment's index.
    u : int or float
        The joint's global parameter, the composite's ``breaks[index + 1]``: index + 1 when
        every segment before it is polynomial (each covers a unit of u), else the sum of the
        domains' lengths (π/2 for a segment on [0, π/2]).
    position_gap : float
        :math:`\lVert C_1(1) - C_2(0) \rVert`.
    first_derivative_gap, second_derivative_gap : float
        :math:`\lVert C_1^{(k)}(1) - C_2^{(k)}(0) \rVert` for k = 1, 2.
    speed_ratio : float
        :math:`\lVert C_1'(1) \rVert / \lVert C_2'(0) \rVert` (the α of a G joint; 1 for a
        C joint).
    tangent_angle : float
        Angle between :math:`C_1'(1)` and :math:`C_2'(0)`, in radians (NaN if one vanishes).
    curvature : tuple of float
        :math:`(\kappa_1(1), \kappa_2(0))`, signed in 2D.
    curvature_gap : float
        :math:`\lvert \kappa_1(1) - \kappa_2(0) \rvert`.
    binormal_angle : float or None
        3D only (None in 2D, where the sign of κ carries the orientation): angle between
        :math:`C_1' \times C_1''` at 1 and :math:`C_2' \times C_2''` at 0 (NaN where a
        curvature vanishes).
    achieved : frozenset of str
        The names among C0, C1, C2, G1, G2 that hold within the tolerance.
    built_with : Joint or None
        The Joint the composite holds for this joint (None if it was not built by join and
        is never re-solved).
    tol : float
        The tolerance the names in `achieved` were decided with (relative to the size of the
        control points and of the derivatives compared).
    """

    index: int
    u: int | float
    position_gap: float
    first_derivative_gap: float
    second_derivative_gap: float
    speed_ratio: float
    tangent_angle: float
    curvature: tuple[float, float]
    curvature_gap: float
    binormal_angle: float | None
    achieved: frozenset[str]
    built_with: Joint | None
    tol: float

    def holds(self, name: str) -> bool:
        if name not in NAMES:
            raise ValueError(f"continuity must be one of {', '.join(map(repr, NAMES))}")
        return name in self.achieved

    @property
    def kept(self) -> bool | None:
        """Whether the continuity the joint was built with holds (None if not built)."""
        return None if self.built_with is None else self.holds(self.built_with.continuity)


def _scaled(a: np.ndarray, by: float | None = None) -> np.ndarray:
    """a divided by its largest |entry| (or by `by`): norms and products of vectors near the
    ends of the float range then neither overflow nor underflow."""
    m = float(np.max(np.abs(a))) if by is None else by
    return a / m if m > 0 and math.isfinite(m) else a


def _norm(a: np.ndarray) -> float:
    """|a| without overflow in the squares (a Python float: inf where |a| itself is)."""
    m = float(np.max(np.abs(a))) if a.size else 0.0
    if m == 0 or not math.isfinite(m):
        return m
    return m * float(np.linalg.norm(a / m))


def _gap(a: np.ndarray, b: np.ndarray) -> float:
    """|a - b| without overflow in the difference or the squares."""
    common = max(float(np.max(np.abs(a))), float(np.max(np.abs(b))))
    if common == 0 or not math.isfinite(common):
        return common
    return common * _norm(a / common - b / common)


def _angle(a: np.ndarray, b: np.ndarray) -> float:
    """Angle between two vectors, accurate near 0 (atan2 of |a×b| and a·b)."""
    a, b = _scaled(a), _scaled(b)
    na, nb = np.linalg.norm(a), np.linalg.norm(b)
    if na == 0 or nb == 0:
        return math.nan
    cross = np.cross(a, b) if a.size == 3 else a[0] * b[1] - a[1] * b[0]
    return float(math.atan2(float(np.linalg.norm(cross)), float(np.dot(a, b))))


def _relative_gap(a: np.ndarray, b: np.ndarray) -> float:
    scale = max(_norm(a), _norm(b))
    gap = _gap(a, b)
    return 0.0 if gap == 0 else gap / scale


def measure(
    left: Segment,
    right: Segment,
    *,
    index: int = 0,
    joint: Joint | None = None,
    tol: float = 1e-9,
    u: float | None = None,
) -> JointReport:
    """The JointReport for `right` following `left` (see JointReport); `u` is the joint's
    global parameter (default index + 1, where every segment before it covers a unit)."""
    tol = val.tolerance(tol)
    end, start = _span(left)[1], _span(right)[0]  # each segment's own t (an AtomCurve's domain)
    p1, p2 = left.evaluate(end), right.evaluate(start)
    d1, e1 = left.derivative(end, 1), right.derivative(start, 1)
    d2, e2 = left.derivative(end, 2), right.derivative(start, 2)
    # NaN where a segment's speed vanishes at the joint: the report says "undefined"
    k1, k2 = float(left._curvature(end)), float(right._curvature(start))
    size = max(1.0, float(np.abs(left.points).max()), float(np.abs(right.points).max()))
    gap = _gap(p1, p2)
    angle = _angle(d1, e1)
    speed2 = _norm(e1)
    ratio = _norm(d1) / speed2 if speed2 else math.nan
    binormal = None
    if left.dimension == 3:
        binormal = _angle(np.cross(d1, d2), np.cross(e1, e2))
    achieved = set()
    if gap <= tol * size:
        achieved.add("C0")
        if _relative_gap(d1, e1) <= tol and _norm(d1) > 0:
            achieved.add("C1")
            if _relative_gap(d2, e2) <= tol:
                achieved.add("C2")
        if angle <= tol:  # NaN (a vanishing tangent) compares False
            achieved.add("G1")
            kscale = max(abs(k1), abs(k2), 1.0 / size)
            same_kappa = abs(k1 - k2) <= tol * kscale
            flat = max(abs(k1), abs(k2)) <= tol * kscale  # both (numerically) straight
            same_binormal = binormal is None or flat or binormal <= tol
            if same_kappa and same_binormal:
                achieved.add("G2")
    return JointReport(
        index=index,
        u=index + 1 if u is None else u,
        position_gap=gap,
        first_derivative_gap=_gap(d1, e1),
        second_derivative_gap=_gap(d2, e2),
        speed_ratio=ratio,
        tangent_angle=angle,
        curvature=(k1, k2),
        curvature_gap=abs(k1 - k2),
        binormal_angle=binormal,
        achieved=frozenset(achieved),
        built_with=joint,
        tol=tol,
    )


def _span(seg: Segment) -> tuple[float, float]:
    """The interval of the segment's own t: [0, 1], or an AtomCurve's or C-Bézier curve's
    domain (every curve gives its `domain`)."""
    lo, hi = seg.domain
    return (float(lo), float(hi))


def _no_atom(seg: Segment, index: int) -> Curve:
    """The segment, refused when it is an AtomCurve (several parameters, not one λ) or a
    C-Bézier curve (its parameter is its domain's length)."""
    if _own_domain(seg) and not isinstance(seg, AtomCurve):
        raise ValueError(
            f"segment {index} is a curve of the {seg.family} family: its parameter is in the "
            "domain, not a lam; make the segment anew with its family's curve(...)"
        )
    if isinstance(seg, AtomCurve):
        raise ValueError(
            f"segment {index} is a curve of the {seg.family} family: it has parameters "
            f"{', '.join(seg.parameter_values)}, not one lam; make the segment anew with "
            "its family's curve(...) and build the composite from it"
        )
    return seg


def _rejoin(
    left: Segment,
    right: Segment,
    joint: Joint,
    lam: Fraction | float | None = None,
    *,
    check_range: bool = False,
) -> Segment:
    """`right` with its leading control points re-solved against `left` (same family,
    degree, λ (an AtomCurve: its parameters) unless given, and the same trailing points)."""
    keep = right.control_points()[joint.order + 1 :]
    rest = keep if keep else np.zeros((0, right.dimension))
    if isinstance(right, AtomCurve) or _own_domain(right):  # its parameters by name
        return join(  # an AtomCurve (made by _atom_joins) or a C-Bézier curve
            left,  # type: ignore[arg-type]  # join hands atom curves to _atom_joins
            joint.continuity,
            right.degree,
            None,
            joint.alpha,
            joint.d,
            rest=rest,
            family=right.family_object,  # type: ignore[union-attr]
            check_range=check_range,
            params=right.atom_parameter_values(),  # type: ignore[union-attr]
        )
    return join(
        left,  # type: ignore[arg-type]  # join hands atom curves to _atom_joins
        joint.continuity,
        right.degree,
        right.lam if lam is None else lam,
        joint.alpha,
        joint.d,
        rest=rest,
        family=type(right),  # its class: a built-in family or one from load_family
        check_range=check_range,
    )


def _once(hits: list[Intersection], near_s: float, near_t: float) -> list[Intersection]:
    """The hits sorted by (s, t), those within near_s in s and near_t in t of one already
    kept dropped (a hit at a joint, found by the segments on both sides of it)."""
    kept: list[Intersection] = []
    for h in sorted(hits, key=lambda h: (h.s, h.t)):
        if not any(abs(h.s - k.s) <= near_s and abs(h.t - k.t) <= near_t for k in kept):
            kept.append(h)
    return kept


class CompositeCurve:
    """Segments joined end to end on the global parameter u ∈ [0, N] (segment i on
    [i, i + 1], local t = u − i; see the module docstring).

    Build one with `CompositeCurve([first])` and `.join(...)` (which records how each joint
    was built), or from existing segments with `joints` giving each joint's Joint (or its
    continuity name, or None for a joint that is only measured, never re-solved).

    >>> from lambda_bezier import CompositeCurve, SameDegreeCurve
    >>> first = SameDegreeCurve([(0, 0), (1, 2), (3, 2), (4, 0)], lam=0)
    >>> comp = CompositeCurve([first]).join("G2", 4, lam=0, alpha=2, rest=[(6, -3), (8, 0)])
    >>> [r.achieved >= {"G2"} for r in comp.report()]
    [True]
    >>> comp.with_lambda(0, -1).report()[0].holds("G2")     # re-solves the joint
    True
    >>> comp.with_lambda(0, -1, resolve=False).report()[0].holds("G2")
    False
    """

    def __init__(
        self,
        segments: Sequence[Segment] | Segment,
        joints: Sequence[Joint | str | None] | None = None,
    ) -> None:
        one = isinstance(segments, Curve | AtomCurve) or _own_domain(segments)
        segs: tuple[Segment, ...] = (
            (segments,) if one else tuple(segments)  # type: ignore[assignment, arg-type]
        )
        if not segs:
            raise ValueError("a composite curve needs at least one segment")
        for idx, seg in enumerate(segs):
            if not isinstance(seg, Curve | AtomCurve) and not _own_domain(seg):
                told = elsewhere(seg)
                if told is not None:
                    raise TypeError(f"segment {idx}: {told}")
                raise ValueError(
                    f"segment {idx} is not a lambda_bezier curve: {type(seg).__name__}"
                )
            if seg.dimension != segs[0].dimension:
                raise ValueError(
                    f"segment {idx} has dimension {seg.dimension}, segment 0 has dimension "
                    f"{segs[0].dimension}"
                )
        if joints is None:
            specs: tuple[Joint | None, ...] = (None,) * (len(segs) - 1)
        else:
            given = tuple(joints)
            if len(given) != len(segs) - 1:
                raise ValueError(
                    f"joints must have one entry per joint ({len(segs) - 1}), got {len(given)}"
                )
            specs = tuple(s if s is None or isinstance(s, Joint) else Joint(s) for s in given)
        self.segments: tuple[Segment, ...] = segs
        self.joints: tuple[Joint | None, ...] = specs
        # where each segment starts in u, and its own domain (polynomial segments: [i, i + 1])
        self._atoms = any(_own_domain(seg) for seg in segs)
        spans = [_span(seg) for seg in segs]
        self._own = np.array(spans, dtype=float).reshape(len(segs), 2)
        lengths = self._own[:, 1] - self._own[:, 0]
        self._starts = np.concatenate([[0.0], np.cumsum(lengths)])  # (N + 1,)

    def __len__(self) -> int:
        return len(self.segments)

    def __repr__(self) -> str:
        kinds = ", ".join("-" if j is None else j.continuity for j in self.joints)
        return f"CompositeCurve({len(self)} segments, joints=[{kinds}])"

    @property
    def dimension(self) -> int:
        return self.segments[0].dimension

    @property
    def domain(self) -> tuple[float, float]:
        """(0, N) for polynomial segments; (0, Σ lengths of the segments' own domains) when
        an AtomCurve takes part (floats: π/2 is rounded)."""
        if not self._atoms:
            return (0, len(self.segments))
        return (0.0, float(self._starts[-1]))

    @property
    def breaks(self) -> tuple[float, ...]:
        """The u at which each segment starts, and the end of the last (N + 1 values)."""
        return tuple(float(x) for x in self._starts)

    # ------------------------------------------------------------------ building
    def join(
        self,
        continuity: str,
        degree: int,
        lam: Fraction | float | None = None,
        alpha: Fraction | float = 1,
        d: Fraction | float = 0,
        rest: PointsLike = (),
        family: object = None,
        *,
        check_range: bool = True,
        params: dict[str, Fraction | float] | None = None,
        **named: Fraction | float,
    ) -> CompositeCurve:
        """A new composite with one more segment, built by lambda_bezier.join from the last
        segment (same arguments: `params` or keywords give the parameters of a family in
        several, e.g. a trigonometric one); the joint is recorded so with_lambda can re-solve
        it."""
        spec = Joint(continuity, alpha, d)
        nxt: Segment = join(
            self.segments[-1],  # type: ignore[arg-type]  # join hands atom curves on
            spec.continuity,
            degree,
            lam,
            spec.alpha,
            spec.d,
            rest,
            family,
            check_range=check_range,
            params=params,
            **named,
        )
        return CompositeCurve([*self.segments, nxt], [*self.joints, spec])

    def with_lambda(
        self,
        index: int,
        lam: Fraction | float,
        *,
        resolve: bool = True,
        check_range: bool = True,
        keep_points: bool = False,
    ) -> CompositeCurve:
        """A new composite with segment `index` given shape parameter `lam` (001, section
        3.3). With resolve=True (default) the joint into that segment and every joint after
        it are re-solved in order, each with the continuity, α and d it was built with, by
        moving the re-solved segments' leading control points (the caller's trailing points
        stay); joints without a recorded Joint are left as they are. With resolve=False only
        λ changes: a G1 joint survives that (λ scales the end tangents, never turns them),
        C1, C2 and G2 joints in general do not; report() shows which.

        keep_points=True is 001's eq. (17) adjustment: every control point stays, and the
        neighbours' shape parameters follow the changed one through every C1 joint reached
        (in both directions; each new λ solves (end factor)·(last edge) = (start factor)·(first
        edge), exactly for exact input). A G1 joint needs no change and ends the chain, as
        does a joint without a recorded Joint; a C2 or G2 joint cannot be kept by λ alone and
        is refused. A λ a joint needs outside its family's range is refused, naming the joint
        and the value."""
        index = val.integer(index, "index")
        resolve = val.flag(resolve, "resolve")
        keep_points = val.flag(keep_points, "keep_points")
        if keep_points:
            return _follow_c1(self, index, lam, check_range=check_range)
        if not 0 <= index < len(self.segments):
            raise ValueError(
                f"index {index} is out of range: the composite has {len(self.segments)} segments"
            )
        old = _no_atom(self.segments[index], index)
        if not type(old)._has_lambda:
            raise ValueError(f"segment {index} is a classical Bézier curve: it has no lam")
        segs = list(self.segments)
        val.as_lambda(lam, old._data, check_range=check_range)  # the message names the range
        segs[index] = type(old)(old.control_points(), lam, check_range=check_range)
        if resolve:
            start = index - 1 if index > 0 else index
            for j in range(start, len(segs) - 1):
                spec = self.joints[j]
                if spec is None:
                    continue
                try:
                    segs[j + 1] = _rejoin(segs[j], segs[j + 1], spec)
                except ValueError as exc:
                    raise ValueError(
                        f"cannot keep joint {j} ({spec.continuity}) after setting segment "
                        f"{index}'s lam to {lam}: {exc}"
                    ) from None
        return CompositeCurve(segs, self.joints)

    # ------------------------------------------------------------------ evaluation
    def _locate(
        self, u: ParamLike, extrapolate: bool
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, bool]:
        """(u, segment index, the segment's own t, scalar?)."""
        # the checks of a curve's t (types, finiteness), then the composite's own interval
        arr, scalar = val.as_parameters(u, extrapolate=True, name="u")
        extrapolate = val.flag(extrapolate, "extrapolate")
        count = len(self.segments)
        top = self._starts[-1]
        slack = 4 * np.spacing(max(float(top), 1.0)) if self._atoms else 0.0
        if not extrapolate and arr.size and (arr.min() < -slack or arr.max() > top + slack):
            bad = arr[(arr < -slack) | (arr > top + slack)][0]
            where = (
                f"[0, {count}] (segment i covers [i, i + 1])"
                if not self._atoms
                else f"[0, {float(top)!r}] (segment i covers [breaks[i], breaks[i + 1]])"
            )
            raise ValueError(
                f"u = {bad} is outside {where}; pass extrapolate=True to evaluate there"
            )
        if not self._atoms:
            idx = np.clip(np.floor(arr).astype(int), 0, count - 1)
            return arr, idx, arr - idx, scalar
        idx = np.clip(np.searchsorted(self._starts, arr, side="right") - 1, 0, count - 1)
        lo, hi = self._own[idx, 0], self._own[idx, 1]
        t = lo + (arr - self._starts[idx])
        if not extrapolate:  # rounding of the breaks must not push t out of the domain
            t = np.clip(t, lo, hi)
        return arr, idx, t, scalar

    def derivative(self, u: ParamLike, k: int = 1, *, extrapolate: bool = False) -> np.ndarray:
        """d^k/du^k of the composite: shape (d,) for a scalar u, (len(u), d) for an array."""
        k = val.as_order(k)
        arr, idx, t, scalar = self._locate(u, extrapolate)
        out = np.zeros((arr.size, self.dimension))
        for s in np.unique(idx):
            mask = idx == s
            out[mask] = self.segments[s].derivative(t[mask], k, extrapolate=extrapolate)
        return out[0] if scalar else out

    def evaluate(self, u: ParamLike, *, extrapolate: bool = False) -> np.ndarray:
        return self.derivative(u, 0, extrapolate=extrapolate)

    def curvature(self, u: ParamLike, *, extrapolate: bool = False) -> np.ndarray | float:
        """Signed in 2D, unsigned in 3D (as the segments' curvature); a ValueError naming u
        where the curve's first derivative vanishes (undefined there)."""
        arr, idx, t, scalar = self._locate(u, extrapolate)
        out = np.zeros(arr.size)
        for s in np.unique(idx):
            mask = idx == s
            out[mask] = self.segments[s]._curvature(t[mask], extrapolate=extrapolate)
        val.defined_curvature(out, arr, "u")
        return out[0] if scalar else out

    # ------------------------------------------------------------------ geometry
    # polynomial segments: geometry.py; with an AtomCurve, segment by segment through each
    # segment's own geometry in its own t (the rational form or _atom_geometry), u = start + t − lo
    def arc_length(self, u0: Fraction | float = 0, u1: Fraction | float | None = None) -> float:
        """∫ ‖C'(u)‖ du from u0 to u1 (0 <= u0 <= u1 <= the domain's end, default the whole
        composite)."""
        if not self._atoms:
            return _geometry.arc_length(self, u0, u1)
        top = float(self._starts[-1])
        a = self._u(u0, "u0")
        b = top if u1 is None else self._u(u1, "u1")
        if a > b:
            raise ValueError(f"arc_length needs u0 <= u1, got u0={u0}, u1={u1}")
        parts = []
        for i, seg in enumerate(self.segments):
            start, (lo, hi) = float(self._starts[i]), self._own[i]
            x, y = max(a - start + lo, lo), min(b - start + lo, hi)
            if x < y:
                parts.append(seg.arc_length(x, y))
        return math.fsum(parts)

    def parameter_at_length(self, s: npt.ArrayLike) -> np.ndarray | float:
        """The u at which the arc length from u = 0 equals s (a number or an array)."""
        if not self._atoms:
            return _geometry.parameter_at_length(self, s)
        arr, scalar = _geometry.length_queries(s)
        lengths = np.array([seg.arc_length() for seg in self.segments])
        arr = _geometry.lengths_within(arr, math.fsum(lengths))
        cum = np.concatenate([[0.0], np.cumsum(lengths)])
        idx = np.clip(np.searchsorted(cum, arr, side="right") - 1, 0, len(self.segments) - 1)
        out = np.zeros(arr.size)
        for i in np.unique(idx):
            mask = idx == i
            local = np.clip(arr[mask] - cum[i], 0.0, lengths[i])
            lo = self._own[i, 0]
            own = self.segments[i].parameter_at_length(local) if lengths[i] else lo
            out[mask] = self._starts[i] + (np.asarray(own, dtype=float) - lo)
        return float(out[0]) if scalar else out

    def bounding_box(self) -> tuple[np.ndarray, np.ndarray]:
        """(lo, hi): the tight axis-aligned box of all segments."""
        if not self._atoms:
            return _geometry.bounding_box(self)
        boxes = [seg.bounding_box() for seg in self.segments]
        return np.min([b[0] for b in boxes], axis=0), np.max([b[1] for b in boxes], axis=0)

    def closest_point(self, q: npt.ArrayLike) -> _geometry.ClosestPoint:
        """The global nearest point to q, (d,) or a batch (m, d): `t` (the u), `point`,
        `distance`."""
        if not self._atoms:
            return _geometry.closest_point(self, q)
        best_u: np.ndarray | None = None
        for i, seg in enumerate(self.segments):
            found = seg.closest_point(q)
            u = self._starts[i] + (np.asarray(found.t, dtype=float) - self._own[i, 0])
            dist = np.asarray(found.distance, dtype=float)
            pt = np.asarray(found.point, dtype=float)
            if best_u is None:
                best_u, best_pt, best_d = u, pt, dist
                continue
            better = dist < best_d  # a tie (a joint) keeps the earlier segment
            best_u = np.where(better, u, best_u)
            best_pt = np.where(better[..., None], pt, best_pt)
            best_d = np.where(better, dist, best_d)
        assert best_u is not None
        if best_u.ndim == 0:
            return _geometry.ClosestPoint(float(best_u), best_pt, float(best_d))
        return _geometry.ClosestPoint(best_u, best_pt, best_d)

    def torsion(self, u: ParamLike, *, extrapolate: bool = False) -> np.ndarray | float:
        """Signed torsion in u of a 3D composite (see Curve.torsion)."""
        return _geometry.torsion(self, u, extrapolate=extrapolate)

    # ------------------------------------------------------------------ intersections
    intersects_curves = True  # a curve's intersect hands a composite here, s and t swapped

    def _global_u(self, index: int, t: float) -> float:
        """Segment `index`'s own t as the composite's u."""
        return float(self._starts[index] + (t - self._own[index, 0]))

    def intersect(self, other: object) -> list[Intersection]:
        """Every intersection with a curve of any class or another composite, as
        Intersection(s, t, kind) sorted by s: self(s) = other(t), s in this composite's u
        (t in the other's own parameter, its u when it is a composite). Through each pair of
        segments' own intersect; a hit at a joint, found as the end of one segment and the
        start of the next, is reported once (hits within 1e-9 of the domains' lengths in
        both parameters are one). A stretch shared across a joint is reported per pair of
        segments, so its end pairs at that joint are listed too."""
        from .hazmat.intersect import Intersection

        theirs: list[tuple[Any, CompositeCurve | None, int]]
        if isinstance(other, CompositeCurve):
            theirs = [(seg, other, j) for j, seg in enumerate(other.segments)]
            span_b = float(other._starts[-1])
        elif (
            isinstance(other, Curve | AtomCurve)
            or _own_domain(other)
            or (getattr(type(other), "intersects_curves", False))
        ):
            theirs = [(other, None, 0)]
            span_b = float(other.domain[1]) - float(other.domain[0])  # type: ignore[attr-defined]
        else:
            raise TypeError(f"other must be a curve or a composite, got {type(other).__name__}")
        if other.dimension != self.dimension:  # type: ignore[attr-defined]
            raise ValueError(
                f"the curves have different dimensions ({self.dimension} and {other.dimension})"  # type: ignore[attr-defined]
            )
        hits: list[Intersection] = []
        for i, seg in enumerate(self.segments):
            for piece, owner, j in theirs:
                for h in seg.intersect(piece):
                    t = float(h.t) if owner is None else owner._global_u(j, float(h.t))
                    hits.append(Intersection(self._global_u(i, float(h.s)), t, h.kind))
        return _once(hits, 1e-9 * float(self._starts[-1]), 1e-9 * span_b)

    def self_intersections(self) -> list[Intersection]:
        """Every pair s < t of u with C(s) = C(t), as Intersection(s, t, kind) sorted by s:
        each segment's own, and those of every pair of segments (by their intersect), the
        joint where one segment ends and the next begins excepted (a closed composite's
        start and end meet: that pair is reported, as a closed curve's (0, 1) is)."""
        from .hazmat.intersect import Intersection

        hits: list[Intersection] = []
        near = 1e-9 * float(self._starts[-1])
        for i, seg in enumerate(self.segments):
            for h in seg.self_intersections():
                hits.append(Intersection(self._global_u(i, h.s), self._global_u(i, h.t), h.kind))
            for j in range(i + 1, len(self.segments)):
                joint = float(self._starts[j]) if j == i + 1 else None
                for h in seg.intersect(self.segments[j]):  # type: ignore[arg-type]
                    s, t = self._global_u(i, float(h.s)), self._global_u(j, float(h.t))
                    if joint is not None and abs(s - joint) <= near and abs(t - joint) <= near:
                        continue  # the joint itself
                    hits.append(Intersection(s, t, h.kind))
        return _once(hits, near, near)

    def locate(self, point: PointsLike) -> float | None:
        """The u with C(u) = point (within 1e-10 of the segment's size), or None; a point
        at a joint is located once. A ValueError when several u give the point."""
        found: list[float] = []
        for i, seg in enumerate(self.segments):
            t = seg.locate(point)
            if t is not None:
                u = self._global_u(i, float(t))
                if not any(abs(u - v) <= 1e-9 * float(self._starts[-1]) for v in found):
                    found.append(u)
        if len(found) > 1:
            raise ValueError(f"the point is on the composite at several parameters: {found}")
        return found[0] if found else None

    def _u(self, value: object, name: str) -> float:
        x = float(val.real_number(value, name))
        top = float(self._starts[-1])
        if not -1e-15 <= x <= top + 1e-15 * max(top, 1.0):
            raise ValueError(f"{name} = {value} is outside [0, {top!r}]")
        return min(max(x, 0.0), top)

    # ------------------------------------------------------------------ continuity
    def report(self, tol: float = 1e-9) -> tuple[JointReport, ...]:
        """One JointReport per joint (relative tolerance `tol`; see JointReport)."""
        tol = val.tolerance(tol)
        # the joint's u is where the next segment starts (index + 1 only for unit domains)
        return tuple(
            measure(
                self.segments[j],
                self.segments[j + 1],
                index=j,
                joint=self.joints[j],
                tol=tol,
                u=float(self._starts[j + 1]) if self._atoms else None,
            )
            for j in range(len(self.segments) - 1)
        )


# --------------------------------------------------------------------------- eq. (17) of 001


def _end_velocity(curve: Curve, end: int) -> tuple[Fraction | float, ...]:
    """p'(end) for end 0 or 1: exact (Fractions) for an exact curve, else floats."""
    bez = curve.to_bezier()
    pts: Sequence[Sequence[Fraction | float]] = bez.control_points()
    size = bez.degree
    a, b = (pts[0], pts[1]) if end == 0 else (pts[-2], pts[-1])
    return tuple(size * (q - p) for p, q in zip(a, b, strict=True))


def _velocity_in_lam(
    curve: Curve, end: int, *, exact: bool
) -> tuple[tuple[Fraction | float, ...], tuple[Fraction | float, ...]]:
    """(A, S) with p'(end; λ) = A + λ S: every basis of the project is affine in λ."""
    lam0, lam1 = (0, 1) if exact else (0.0, 1.0)
    pts = curve.control_points()
    at0 = _end_velocity(type(curve)(pts, lam0, check_range=False), end)
    at1 = _end_velocity(type(curve)(pts, lam1, check_range=False), end)
    return at0, tuple(b - a for a, b in zip(at0, at1, strict=True))


def _solve_lam(
    target: Sequence[Fraction | float], seg: Curve, end: int, joint: int, exact: bool
) -> Fraction | float:
    """The λ of `seg` (points fixed) whose end velocity equals `target`."""
    a, slope = _velocity_in_lam(seg, end, exact=exact)
    ss = sum(v * v for v in slope)
    if ss == 0:
        raise ValueError(f"joint {joint}: λ does not change the segment's end tangent")
    lam = sum((t - v) * w for t, v, w in zip(target, a, slope, strict=True)) / ss
    miss = [t - (v + lam * w) for t, v, w in zip(target, a, slope, strict=True)]
    scale = max(1.0, max(abs(float(t)) for t in target))
    if any(m != 0 for m in miss) if exact else max(abs(float(m)) for m in miss) > 1e-9 * scale:
        raise ValueError(
            f"joint {joint}: no λ keeps it C1 with the control points fixed (the edges at the "
            "joint are not parallel)"
        )
    return lam


def _follow_c1(
    comp: CompositeCurve, index: int, lam: Fraction | float, *, check_range: bool
) -> CompositeCurve:
    if isinstance(index, bool) or not isinstance(index, int | np.integer):
        raise ValueError(f"index must be an integer, got {index!r}")
    if not 0 <= index < len(comp.segments):
        raise ValueError(
            f"index {index} is out of range: the composite has {len(comp.segments)} segments"
        )
    segs = list(comp.segments)
    old = _no_atom(segs[index], index)
    if not type(old)._has_lambda:
        raise ValueError(f"segment {index} is a classical Bézier curve: it has no lam")
    segs[index] = type(old)(old.control_points(), lam, check_range=check_range)
    # forward (joint j between j and j + 1: segment j + 1 follows) and backward
    for direction in (1, -1):
        j = index if direction == 1 else index - 1
        while 0 <= j < len(segs) - 1:
            spec = comp.joints[j]
            if spec is None or spec.continuity in ("C0", "G1"):
                break  # nothing to keep (G1: λ scales the tangents, never turns them)
            if spec.continuity != "C1":
                raise ValueError(
                    f"joint {j} is {spec.continuity}: with the control points fixed a change of "
                    "λ cannot keep it (001, section 3.3); use keep_points=False to re-solve "
                    "its leading points"
                )
            fixed, moving = (segs[j], segs[j + 1]) if direction == 1 else (segs[j + 1], segs[j])
            fixed = _no_atom(fixed, j if direction == 1 else j + 1)
            moving = _no_atom(moving, j + 1 if direction == 1 else j)
            if not type(moving)._has_lambda:
                raise ValueError(f"joint {j}: its other segment is a classical Bézier curve")
            exact = fixed.is_exact and moving.is_exact
            target = _end_velocity(fixed, 1 if direction == 1 else 0)
            new = _solve_lam(target, moving, 0 if direction == 1 else 1, j, exact)
            moved = j + 1 if direction == 1 else j
            try:
                val.as_lambda(new, moving._data, check_range=check_range)
            except ValueError:
                raise ValueError(
                    f"joint {j}: keeping it C1 needs λ = {new} for segment {moved}, outside the "
                    f"{moving.family} range {moving._data.LAMBDA_RANGE_TEXT}"
                ) from None
            segs[moved] = type(moving)(moving.control_points(), new, check_range=check_range)
            j += direction
    return CompositeCurve(segs, comp.joints)
