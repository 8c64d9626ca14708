"""Self-intersections of a classical Bézier curve (`self_intersections`): the pairs s < t with
p(s) = p(t), by the two-curve engine of hazmat/intersect.py on the curve against itself, with
what only one curve has: loops that are cusps within rounding (`_cusp_loop`), the polish of
float hits on the divided differences (hazmat/intersect_self_polish.py), the exact decision
for exact input in doubt (hazmat/intersect_self_exact.py) and stretches a curve retraces
(hazmat/intersect_refold.py)."""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np

from . import intersect_fold as fold
from . import intersect_refold as refold
from . import intersect_self_exact as _self_exact
from . import intersect_self_polish as _self_polish
from . import intersect_subdivide as sub
from .intersect import (
    BOX_SLACK,
    CUSP_LOOP,
    EXACT_CHECK_SINE,
    SELF_PLACED,
    SELF_ROUNDING,
    TANGENT_SINE,
    Intersection,
    Prepared,
    _add,
    _common_line,
    _dedupe,
    _dedupe_isolated,
    _sine,
    _solve_from,
    intersect,
    normalised,
)
from .intersect_locate import ON_CURVE, SAME_ROOT, _starts


def _cusp_loop(p: Prepared, hit: Intersection) -> bool:
    """Near a cusp p(s) - p(t) vanishes to third order for s close to t: a "loop" whose
    points all lie within rounding of each other (CUSP_LOOP) is that, not a crossing."""
    loop = np.array([p.at(u) for u in np.linspace(hit.s, hit.t, 9)])
    return bool(np.ptp(loop, axis=0).max() <= CUSP_LOOP * p.degree * p.scale)


def self_intersections(p: Prepared) -> list[Intersection]:
    """Pairs s < t with p(s) = p(t), sorted by s."""
    if p.dim < 2:
        raise ValueError("self-intersections need dimension >= 2")
    p = normalised(p, p)[0]
    found: list[Intersection] = []
    if p.degree < 2 or p.is_point:
        return found
    line = _common_line(p.pts, ON_CURVE * p.scale)
    if line is not None:  # on a line: none if it runs one way, stretches if it turns back
        stretches = fold.folded_stretches([p.exact_row(k) for k in range(p.degree + 1)])
        return [Intersection(s, t, "coincident") for s, t in stretches]
    iso = sub.isolate(p.pts[None], None, np.array([BOX_SLACK * p.degree * p.scale]))
    # near_diagonal: a hit or unresolved pieces dropped as a cusp, which a tiny loop (a
    # crossing) looks like in floats; for exact input that is decided exactly below
    near_diagonal = False
    for s, t in zip(iso.root_s.tolist(), iso.root_t.tolist(), strict=True):
        hit = _solve_from(p, p, s, t, found, isolated=True)
        if hit is not None and (abs(hit.s - hit.t) < 1e-7 or _cusp_loop(p, hit)):
            near_diagonal = True
            continue
        if hit is None:
            continue
        if hit.s > hit.t:
            hit = Intersection(hit.t, hit.s, hit.kind)
        if not _dedupe_isolated(found, hit):
            found.append(hit)
    # unresolved pieces on the diagonal are not one-to-one even at width 2^-DEPTH: a cusp
    # (p' = 0), where p(s) - p(t) vanishes to third order, not a crossing
    starts = []
    for s, t in _starts(iso.left_s0, iso.left_t0, iso.left_width):
        if abs(s - t) > 1e-7:
            starts.append((s, t))
        else:
            near_diagonal = True
    for s, t in starts:
        hit = _solve_from(p, p, s, t, found)
        if hit is not None and (abs(hit.s - hit.t) < 1e-7 or _cusp_loop(p, hit)):
            near_diagonal = True
            hit = None
        if hit is None:
            # Newton on p(s) - p(t) falls onto the diagonal s = t from a start next to a
            # small loop (a = 1 + 8/3 10^-9.1875 in the tiny-loop tests); on the divided
            # difference the diagonal is no root, and the loop's crossing is reached
            hit = _loop_from(p, s, t)
            if hit is None:
                continue
        if hit.s > hit.t:
            hit = Intersection(hit.t, hit.s, hit.kind)
        if not _dedupe(found, hit):
            _add(found, hit, p, p)
    found = _polished_self(p, found)
    exact = _self_decided_exactly(p, found, near_diagonal)
    if exact is not None:
        return exact
    if any(h.kind == "tangent" for h in found):
        # touching itself, or turning back along itself (P = Q(g), g not monotone): a shared
        # stretch is reported by its end pairs (intersect_refold), as intersect reports one
        rows = [[Fraction(x) for x in row] for row in (p._given_rows or p.pts.tolist())]
        shared = refold.refolded(rows, _rows_intersect)
        if shared is not None:
            # the pieces' crossings with each other are there; a crossing within one piece
            # (a loop of its own) is one the subdivision found, "transversal", kept unless
            # it lies on a shared stretch
            hits, boxes = shared
            out = [Intersection(s, t, kind) for s, t, kind in hits]
            for h in found:
                on_stretch = any(
                    s0 - SAME_ROOT <= h.s <= s1 + SAME_ROOT
                    and t0 - SAME_ROOT <= h.t <= t1 + SAME_ROOT
                    for s0, s1, t0, t1 in boxes
                )
                if h.kind == "transversal" and not on_stretch and not _dedupe(out, h):
                    out.append(h)
            return sorted(out)
    return sorted(found)


def _polished_self(p: Prepared, found: list[Intersection]) -> list[Intersection]:
    """Each crossing refined on the divided difference (p(s) - p(t)) / (s - t)
    (intersect_self_polish), which places one on a small loop to the rounding of the points
    where Newton on p(s) - p(t) is off by up to the loop's width; its kind by the sine rule
    (TANGENT_SINE) there. Float input only, and only where rounding can move the hit by
    more than SELF_PLACED (_self_misplaced): exact input's hits are refined on exact
    residuals, and decided exactly where in doubt. Where that Newton does not settle (a
    self-tangency's divided difference has a singular Jacobian) the hit stays as it was."""
    out: list[Intersection] = []
    for h in found:
        got = None
        if p._given_rows is None and h.kind != "coincident" and _self_misplaced(p, h):
            got = _self_polish.polished(p.h1, p.h2, h.s, h.t)
        if got is not None:
            kind = "tangent" if _sine(p, p, *got) < TANGENT_SINE else "transversal"
            h = Intersection(got[0], got[1], kind)
        if not _dedupe(out, h):
            out.append(h)
    return out


def _loop_from(p: Prepared, s: float, t: float) -> Intersection | None:
    """The self-crossing Newton on the divided difference reaches from the start (s, t)
    (intersect_self_polish), if it is one: the points meet (within ON_CURVE of the size)
    and the loop between them is not a cusp's rounding (_cusp_loop)."""
    got = _self_polish.polished(p.h1, p.h2, min(s, t), max(s, t))
    if got is None:
        return None
    gap = float(np.linalg.norm(p.at(got[0]) - p.at(got[1])))
    if gap > ON_CURVE * p.scale:
        return None
    kind = "tangent" if _sine(p, p, *got) < TANGENT_SINE else "transversal"
    hit = Intersection(got[0], got[1], kind)
    return None if _cusp_loop(p, hit) else hit


def _self_misplaced(p: Prepared, h: Intersection) -> bool:
    """Rounding of the points (SELF_ROUNDING per degree of the size) can move the float
    root of p(s) = p(t) by more than SELF_PLACED: that over the smallest singular value of
    the Jacobian [p'(s) | -p'(t)]. Small next to a cusp, where both speeds and the angle
    between them are small. That value is |p'(s)| |p'(t)| sine / (the largest), within a
    factor sqrt(2) of the lower bound taken here (the largest below the columns' root sum
    of squares): no SVD per hit (it added a tenth to self_intersections of random curves)."""
    u, v = p.at(h.s, 1), p.at(h.t, 1)
    nu, nv = float(np.linalg.norm(u)), float(np.linalg.norm(v))
    smallest = nu * nv * _sine(p, p, h.s, h.t) / max(math.hypot(nu, nv), 1e-300)
    return bool(SELF_ROUNDING * p.degree * p.scale > SELF_PLACED * smallest)


def _self_decided_exactly(
    p: Prepared, found: list[Intersection], near_diagonal: bool
) -> list[Intersection] | None:
    """The exact answer (intersect_self_exact) for an exact planar curve whose float answer
    is in doubt: a "tangent" hit, a crossing whose tangents' sine is below EXACT_CHECK_SINE
    (two crossings closer than the float path separates come back as one such, or as one
    "tangent"), or a hit or unresolved pieces dropped next to the diagonal (a cusp, or a
    loop too small for floats); None otherwise, or where the exact isolation declines."""
    if p._given_rows is None or p.dim != 2:
        return None
    doubt = near_diagonal or any(
        h.kind == "tangent"
        or (h.kind == "transversal" and _sine(p, p, h.s, h.t) < EXACT_CHECK_SINE)
        for h in found
    )
    if not doubt:
        return None
    got = _self_exact.self_decided(p._given_rows, p.dim)
    if got is None:
        return None
    return [Intersection(s, t, "tangent" if flat else "transversal") for s, t, flat in got]


def _prepared_rows(rows: list[list[Fraction]]) -> Prepared:
    return Prepared(np.array([[float(x) for x in row] for row in rows]), tuple(map(tuple, rows)))


def _rows_intersect(
    a: list[list[Fraction]], b: list[list[Fraction]]
) -> list[tuple[float, float, str]]:
    return [(h.s, h.t, h.kind) for h in intersect(_prepared_rows(a), _prepared_rows(b))]
