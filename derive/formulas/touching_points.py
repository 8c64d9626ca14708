"""Rational touching points of an atom basis (issue #30), for the branch and bound of
atom_nonnegative.py, which cannot settle a box around a zero of b (no enclosure of b there is
> 0). Candidates t0 come from where the search stalls (the middles of the boxes it could not
settle, as rationals of small denominator); at a candidate, b^(j)(t0) is checked to be
exactly zero as an element (every parameter value) for j < r, r even, and an arb enclosure of
b^(r) on T x box is > 0, T an interval around t0. Then b >= 0 on T x box by Taylor's theorem
(b = (t - t0)^r / r! b^(r)(xi)): t0 is a double (or higher even order) root, the only zero of
b in T, and the search settles every box inside T.
"""

from __future__ import annotations

from fractions import Fraction

from ..algebra import atoms as A

MAX_TOUCH_ORDER = 6  # the even orders looked for at a touching point
DENOMINATORS = (2, 3, 4, 5, 6, 8, 10, 12, 16, 20, 24, 32, 64, 100, 128, 1000)


def _order_at(b: A.Elem, frame: A.Frame, t0: Fraction) -> tuple[int, A.Elem] | None:
    """(r, b^(r)) with b^(j)(t0) exactly zero for every parameter value for j < r, or None
    (not a zero of b, or an exact value out of reach at t0)."""
    d = b
    try:
        for r in range(MAX_TOUCH_ORDER + 1):
            if A.value(d, frame, t0):
                return (r, d) if r else None
            d = A.diff(d, frame)
    except A.AtomError:  # cos(m w t0) not rational: no exact test there
        return None
    return None


def candidates(stalled: list[Fraction], lo: Fraction, hi: Fraction) -> list[Fraction]:
    """Rationals of small denominator near the middles of the boxes the search stalled on."""
    out: list[Fraction] = []
    for mid in stalled:
        for den in DENOMINATORS:
            t0 = mid.limit_denominator(den)
            if lo < t0 < hi and t0 not in out and abs(t0 - mid) <= (hi - lo) / 64:
                out.append(t0)
    return out


def certified_touches(b, frame, lower, start, stalled, lo, hi):
    """Intervals [t0 - r, t0 + r] (family units) on which b >= 0 is proved for every
    parameter of the start box (module docstring); `lower(elem, d_elem, box)` is the
    caller's enclosure of an element on a box."""
    found = []
    for t0 in candidates(stalled, lo, hi):
        got = _order_at(b, frame, t0)
        if got is None or got[0] % 2:
            continue
        r, dr = got
        ddr = A.diff(dr, frame)
        for k in range(6, 40):
            rad = (hi - lo) / 2**k
            t_box = (max(lo, t0 - rad), min(hi, t0 + rad))
            if lower(dr, ddr, [t_box, *start]) > 0:
                found.append(t_box)
                break
    return found
