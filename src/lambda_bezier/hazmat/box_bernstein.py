"""Exact Bernstein bounds of a polynomial in several variables over a box.

A polynomial is a dense array of exact power coefficients (``power[e_1, ..., e_m]`` is the
coefficient of x_1^e_1 ... x_m^e_m, Fractions in an object array); a box is a list of
(lo, hi) pairs of Fractions. Over a box the polynomial is a combination of tensor-product
Bernstein polynomials, which are >= 0 and sum to 1: the least Bernstein coefficient is a
lower bound of the polynomial on the box, and the coefficients at the corners are its values
there. Boxes are split in two along the widest side (branch and bound). Everything is exact
(Fractions): a bound here is a proof, not an estimate.

Used by derive (non-negativity and linear independence over a box of shape parameters) and
by lambda_bezier.energy (the certified global minimum of E_k over the box).
"""

from __future__ import annotations

import itertools
import math
from fractions import Fraction
from math import comb
from typing import Any

import numpy as np

from . import box_convex
from .box_forms import bernstein, float_value, value

Box = list[tuple[Fraction, Fraction]]


def samples(box: Box) -> list[tuple[Fraction, ...]]:
    """The corners of a box and its centre."""
    return [*itertools.product(*box), tuple((lo + hi) / 2 for lo, hi in box)]


def sample_values(
    power: np.ndarray, box: Box, coeffs: np.ndarray
) -> list[tuple[Fraction, tuple[Fraction, ...]]]:
    """(value, point) at each of `samples(box)`, in that order. A corner's value is the
    Bernstein coefficient at that corner (`coeffs`, over `box`), exactly: only the centre is
    evaluated (with 5 parameters, 32 exact evaluations a box were most of derive's time)."""
    corners = itertools.product(*[((0, lo), (-1, hi)) for lo, hi in box])
    out = [(Fraction(coeffs[tuple(i for i, _ in c)]), tuple(x for _, x in c)) for c in corners]
    centre = tuple((lo + hi) / 2 for lo, hi in box)
    return [*out, (value(power, centre), centre)]


def split(box: Box) -> tuple[Box, Box]:
    """The two halves of a box across its widest side (the first of equal ones)."""
    axis = max(range(len(box)), key=lambda j: (box[j][1] - box[j][0], -j))
    lo, hi = box[axis]
    mid = (lo + hi) / 2
    left, right = list(box), list(box)
    left[axis], right[axis] = (lo, mid), (mid, hi)
    return left, right


def sign_search(power: np.ndarray, box: Box, *, strict: bool, budget: int) -> dict[str, Any]:
    """Whether the polynomial is >= 0 (strict: > 0) on the closed box: {"holds": True} (every
    sub-box's coefficients are >= 0, resp. > 0), {"holds": False, "point", "value"} at an
    exact point where it fails, or {"holds": None, "boxes": budget} when undecided."""
    boxes = [box]
    for _ in range(budget):
        if not boxes:
            return {"holds": True}
        current = boxes.pop()
        coeffs = bernstein(power, current)
        least = min(coeffs.flat)
        if least > 0 or (least == 0 and not strict):
            continue
        for v, p in sample_values(power, current, coeffs):
            if v < 0 or (strict and v == 0):
                return {"holds": False, "point": p, "value": v}
        boxes.extend(split(current))
    return {"holds": True} if not boxes else {"holds": None, "boxes": budget}


def zero_search(power: np.ndarray, box: Box, budget: int) -> dict[str, Any]:
    """Whether the polynomial vanishes on the closed box: {"zero": False} (on every sub-box
    the coefficients have one strict sign), {"zero": True, "point"} at an exact point,
    {"zero": True, "negative", "positive"} two exact points of opposite signs (a zero on the
    segment between them), or {"zero": None, "boxes": budget}."""
    boxes = [box]
    for _ in range(budget):
        if not boxes:
            return {"zero": False}
        current = boxes.pop()
        coeffs = bernstein(power, current)
        if min(coeffs.flat) > 0 or max(coeffs.flat) < 0:
            continue
        values = sample_values(power, current, coeffs)
        for v, p in values:
            if v == 0:
                return {"zero": True, "point": p}
        pos = [p for v, p in values if v > 0]
        neg = [p for v, p in values if v < 0]
        if pos and neg:
            return {"zero": True, "negative": neg[0], "positive": pos[0]}
        boxes.extend(split(current))
    return {"zero": False} if not boxes else {"zero": None, "boxes": budget}


def minimum(
    power: np.ndarray,
    box: Box,
    tolerance: Fraction,
    budget: int,
    *,
    start: list[tuple[Fraction, ...]] | None = None,
) -> dict[str, Any]:
    """The global minimum of the polynomial over the closed box, certified: {"point",
    "value", "lower"} with value - lower <= tolerance * max(1, |value|), value the exact
    polynomial value at the exact point and lower a proven lower bound over the whole box
    (the least Bernstein coefficient over the sub-boxes still open). "certified" False when
    the budget ran out first (lower is still a proven bound).

    Every box's corners and centre are tried as candidates. With `start` (candidate points
    found otherwise, e.g. by a float search) only those and each box's centre are, and a
    box's coefficients come from its parent's by integer de Casteljau halving
    (`_minimum_by_halving`): the 2^J corners and the Bernstein change of basis from the
    power form cost far more when J is 4 or more (surface energies)."""
    if start is not None:
        return _minimum_by_halving(power, box, tolerance, budget, start)
    best_v: Fraction | None = None
    best_p: tuple[Fraction, ...] | None = None

    def consider(p: tuple[Fraction, ...]) -> None:
        nonlocal best_v, best_p
        v = value(power, p)
        if best_v is None or v < best_v:
            best_v, best_p = v, p

    # open boxes with their lower bounds; the one with the least bound is split first
    open_boxes = [(min(bernstein(power, box).flat), box)]
    for p in samples(box):
        consider(p)
    for _ in range(budget):
        open_boxes.sort(key=lambda item: item[0])
        lower = open_boxes[0][0]
        assert best_v is not None
        if best_v - lower <= tolerance * max(Fraction(1), abs(best_v)):
            return {"point": best_p, "value": best_v, "lower": lower, "certified": True}
        _, current = open_boxes.pop(0)
        for half in split(current):
            for p in samples(half):
                consider(p)
            bound = min(bernstein(power, half).flat)
            if bound <= best_v:
                open_boxes.append((bound, half))
        if not open_boxes:
            return {"point": best_p, "value": best_v, "lower": best_v, "certified": True}
    open_boxes.sort(key=lambda item: item[0])
    return {"point": best_p, "value": best_v, "lower": open_boxes[0][0], "certified": False}


def _halve(coeffs: np.ndarray, axis: int) -> tuple[np.ndarray, np.ndarray]:
    """The integer Bernstein coefficients of the two halves along `axis`, both times 2^n
    (n the degree there): left_k = 2^(n-k) Σ_j C(k, j) c_j, right_k = 2^k Σ_j C(n-k, j)
    c_(k+j); no division, so Python integers stay exact and fast."""
    c = np.moveaxis(coeffs, axis, 0)
    n = c.shape[0] - 1
    left = np.empty_like(c)
    right = np.empty_like(c)
    for k in range(n + 1):
        acc_l = sum((comb(k, j) * c[j] for j in range(k + 1)), np.zeros_like(c[0]))
        acc_r = sum((comb(n - k, j) * c[k + j] for j in range(n - k + 1)), np.zeros_like(c[0]))
        left[k] = acc_l * 2 ** (n - k)
        right[k] = acc_r * 2**k
    return np.moveaxis(left, 0, axis), np.moveaxis(right, 0, axis)


def _inside(inner: Box, outer: Box) -> bool:
    return all(a >= c and b <= d for (a, b), (c, d) in zip(inner, outer, strict=True))


def _minimum_by_halving(
    power: np.ndarray,
    box: Box,
    tolerance: Fraction,
    budget: int,
    start: list[tuple[Fraction, ...]],
) -> dict[str, Any]:
    """`minimum` from candidate points: the Bernstein coefficients over the whole box once,
    as integers over one denominator, then each box's from its parent's (`_halve`); a box's
    bound is its least coefficient over denominator · 2^s."""
    import heapq

    first = bernstein(power, box)
    den = 1
    for x in first.flat:
        den = den * Fraction(x).denominator // math.gcd(den, Fraction(x).denominator)
    ints = np.empty(first.shape, dtype=object)
    for idx, x in np.ndenumerate(first):
        ints[idx] = int(Fraction(x) * den)
    best_v: Fraction | None = None
    best_p: tuple[Fraction, ...] | None = None
    floats = np.array(power.tolist(), dtype=float)
    best_f = np.inf

    def consider(p: tuple[Fraction, ...]) -> None:
        # a centre is evaluated exactly only when its float value could beat the best by
        # more than rounding: most cannot, and the exact value dominated the cost
        nonlocal best_v, best_p, best_f
        if best_v is not None:
            approx = float_value(floats, tuple(float(x) for x in p))
            if not approx < best_f - 1e-14 * max(1.0, abs(best_f)):
                return
        v = value(power, p)
        if best_v is None or v < best_v:
            best_v, best_p, best_f = v, p, float(v)

    for p in [*start, *samples(box)]:
        consider(p)
    # the best start polished in floats, and a box about it with a quadratic floor (box_convex):
    # without them the boxes about an interior minimum must shrink to the tolerance's square
    # root, and with six variables millions stay open (q_bezier surfaces)
    assert best_p is not None
    polished = box_convex.polish(floats, box, tuple(float(x) for x in best_p))
    consider(tuple(min(max(Fraction(x), a), b) for x, (a, b) in zip(polished, box, strict=True)))
    assert best_v is not None
    need = best_v - tolerance * max(Fraction(1), abs(best_v))
    local = box_convex.local_floor(power, floats, box, best_p, need)
    tie = itertools.count()
    heap = [(Fraction(min(ints.flat), den), next(tie), box, ints, 0)]
    floor: Fraction | None = None  # the least bound of the boxes dropped as within tolerance
    for _ in range(budget):
        assert best_v is not None
        allowed = tolerance * max(Fraction(1), abs(best_v))
        lower = heap[0][0] if heap else best_v
        if floor is not None:
            lower = min(lower, floor)
        if best_v - lower <= allowed:
            return {"point": best_p, "value": best_v, "lower": lower, "certified": True}
        bound, _, current, coeffs, shift = heapq.heappop(heap)
        if bound > best_v - allowed:
            floor = bound if floor is None else min(floor, bound)
            continue
        axis = max(range(len(current)), key=lambda j: (current[j][1] - current[j][0], -j))
        lo, hi = current[axis]
        mid = (lo + hi) / 2
        halves = _halve(coeffs, axis)
        step = shift + coeffs.shape[axis] - 1
        for (a, b), part in zip(((lo, mid), (mid, hi)), halves, strict=True):
            sub = list(current)
            sub[axis] = (a, b)
            if local is not None and _inside(sub, local[0]):  # bounded by the convex floor
                floor = local[1] if floor is None else min(floor, local[1])
                continue
            consider(tuple((x + y) / 2 for x, y in sub))
            lb = Fraction(min(part.flat), den * 2**step)
            heapq.heappush(heap, (lb, next(tie), sub, part, step))
    assert best_v is not None
    lower = heap[0][0] if heap else best_v
    if floor is not None:
        lower = min(lower, floor)
    return {"point": best_p, "value": best_v, "lower": lower, "certified": False}
