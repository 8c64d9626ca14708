"""Non-negativity over the parameter box of bases with no polynomial substitution (issue #30):
the mixed algebraic-trigonometric and algebraic-hyperbolic spaces, and bases not affine in
their parameters, decided by a certified branch and bound in ball arithmetic.

Every b_i is an exact element (derive/algebra/atoms.py): rational coefficients on atoms
params^m t^k e^(h w t) cos|sin(m w t). On a box (an interval of t times an interval of each
parameter) it is enclosed in FLINT's arb ball arithmetic (rigorous: every operation rounds
outwards; pi and e^W are balls too), by the natural extension term by term and by the mean
value form b(mid) + b'(box) (t − mid), whichever is tighter. A box is settled when

- the lower bound of b on it is > 0; or
- it touches an end of the domain where b vanishes to order r for every parameter value (the
  derivatives of orders < r at the end are exactly zero as elements: decided exactly, pi and
  e^W being transcendental) and ±b^(r) > 0 on it (+ at the low end, (−1)^r at the high end):
  then b(end ± s) = s^r/r! · b^(r)(ξ) ≥ 0 by Taylor's theorem;

and it is a counterexample when b at its middle point (rational t and parameters) has an
upper bound < 0. Any other box is halved (t, or the widest parameter). For a basis affine in
the parameters jointly, b at fixed t is least at a vertex of the box (an open end by
continuity), so only the vertices are searched; otherwise the whole box is.

The verdict: {"nonnegative": True}, or {"nonnegative": False, "counterexample": {...}} with a
rational point (t, parameters inside their ranges) where b_i < 0 is proved. Where the search
stalls (a zero of b inside the domain, where no enclosure is > 0), touching_points.py looks
for rational touching points of even order with b >= 0 proved around them, and it searches
again. Otherwise a reason (then touching.py decides a trigonometric or hyperbolic basis
exactly; a mixed one touching zero at an irrational point, or with an end order that changes
with the parameters, keeps it).
"""

from __future__ import annotations

import itertools
from fractions import Fraction

import flint

from ..algebra import atoms as A
from ..families.definition import Definition
from ..families.spaces import Space
from .touching_points import certified_touches

PREC = 128  # bits of the balls
MAX_BOXES = 20_000  # boxes examined per function before the search gives up (undecided)
MAX_ORDER = 8  # end orders looked for


def _q(x: Fraction) -> flint.arb:
    return flint.arb(flint.fmpq(x.numerator, x.denominator))


def _ball(lo: Fraction, hi: Fraction) -> flint.arb:
    mid = (lo + hi) / 2
    return _q(mid) + flint.arb(0, _q((hi - lo) / 2))


class _Frame:
    """The frame's numbers as balls: the unit of t (pi or 1), the base rate, the constant."""

    def __init__(self, frame: A.Frame):
        pi = flint.arb.pi()
        self.unit = pi if frame.dom_pi else flint.arb(1)
        self.rate = _q(frame.rate) * (pi if frame.rate_pi else 1)
        self.const = pi if frame.exp_unit is None else _q(frame.exp_unit).exp()
        self.frame = frame


def _enclose(elem: A.Elem, fr: _Frame, t: flint.arb, params: tuple[flint.arb, ...]) -> flint.arb:
    """The natural interval extension of the element on t (a ball in the family's t) and
    balls of the parameters."""
    total = flint.arb(0)
    for (mono, c, k, h, m, kind), v in elem.items():
        term = _q(v)
        for p, e in zip(params, mono, strict=True):
            if e:
                term *= p**e
        if c:
            term *= fr.const**c
        if k:
            term *= t**k
        if h:
            term *= (h * fr.rate * t).exp()
        if m:
            term *= (m * fr.rate * t).cos() if kind == A.COS else (m * fr.rate * t).sin()
        total += term
    return total


def _lower(b: A.Elem, db: A.Elem, fr: _Frame, box: tuple, params: tuple) -> flint.arb:
    """An enclosure of b on the box: natural, intersected with the mean value form in t."""
    (lo, hi), ps = box[0], params
    t = _ball(lo, hi) * fr.unit
    mid = _q((lo + hi) / 2) * fr.unit
    natural = _enclose(b, fr, t, ps)
    mean = _enclose(b, fr, mid, ps) + _enclose(db, fr, t, ps) * (t - mid)
    try:
        return natural.intersection(mean)
    except ValueError:  # pragma: no cover - both contain the true range
        return natural


def _end_order(b: A.Elem, frame: A.Frame, end: Fraction) -> tuple[int, A.Elem] | None:
    """(r, b^(r)): b^(j)(end) is identically zero (in the parameters) for j < r and not for
    j = r; None when b vanishes there to more than MAX_ORDER (or is zero)."""
    d = b
    for r in range(MAX_ORDER + 1):
        if A.value(d, frame, end):
            return r, d
        d = A.diff(d, frame)
    return None


def _decide_one(
    b: A.Elem, space: Space, fr: _Frame, start: list[tuple[Fraction, Fraction]], defn: Definition
) -> tuple[str, tuple | None]:
    """("ok" | "negative" | "undecided", the negative point)."""
    if not b:  # identically zero (a vertex where the function vanishes)
        return "ok", None
    frame = space.frame
    db = A.diff(b, frame)
    ends = {}
    for end, sign in ((frame.lo, 1), (frame.hi, -1)):
        found = _end_order(b, frame, end)
        if found is not None and found[0] > 0:
            r, dr = found
            ends[end] = (A.scale(dr, sign**r), A.diff(A.scale(dr, sign**r), frame))
    queue = [[(frame.lo, frame.hi), *start]]
    seen, touches, tried = 0, [], False
    while queue:
        box = queue.pop()
        seen += 1
        if seen > MAX_BOXES:
            return "undecided", None
        if seen > MAX_BOXES // 10 and not tried:
            # stalled: look for rational touching points (touching.py) and search again
            tried = True
            stalled = [(x + y) / 2 for (x, y), *_ in [box, *queue]]
            touches = certified_touches(
                b,
                frame,
                lambda e, de, bx: _lower(e, de, fr, bx, tuple(_ball(x, y) for x, y in bx[1:])),
                start,
                stalled,
                frame.lo,
                frame.hi,
            )
            if touches:
                queue, seen = [[(frame.lo, frame.hi), *start]], 0
                continue
        lo, hi = box[0]
        if any(a <= lo and hi <= c for a, c in touches):
            continue  # b >= 0 proved on that interval around a touching point
        ps = tuple(_ball(x, y) for x, y in box[1:])
        if _lower(b, db, fr, box, ps) > 0:
            continue
        settled = False
        for end, touch in ((frame.lo, lo == frame.lo), (frame.hi, hi == frame.hi)):
            if touch and end in ends and _lower(*ends[end], fr, box, ps) > 0:
                settled = True
        if settled:
            continue
        point = tuple((x + y) / 2 for x, y in box)
        at = _enclose(b, fr, _q(point[0]) * fr.unit, tuple(_q(p) for p in point[1:]))
        if at < 0:
            return "negative", point
        widths = [
            (y - x) / max(q.hi - q.lo, Fraction(1, 10**9))
            for (x, y), q in zip(box[1:], defn.params, strict=True)
        ]
        t_width = (hi - lo) / (frame.hi - frame.lo)
        axis = 0
        if widths and max(widths) > t_width:
            axis = 1 + widths.index(max(widths))
        x, y = box[axis]
        m = (x + y) / 2
        for half in ((x, m), (m, y)):
            nxt = list(box)
            nxt[axis] = half
            queue.append(nxt)
    return "ok", None


def _inside_ranges(point: tuple, defn: Definition, b: A.Elem, fr: _Frame) -> tuple:
    """The negative point moved off any open end of a parameter's range, still negative."""
    values = list(point[1:])
    for j, q in enumerate(defn.params):
        bad = (values[j] == q.lo and not q.lo_closed) or (values[j] == q.hi and not q.hi_closed)
        if not bad:
            continue
        inward = 1 if values[j] == q.lo else -1
        for k in range(4, 80):
            trial = list(values)
            trial[j] = values[j] + inward * (q.hi - q.lo) / 2**k
            at = _enclose(b, fr, _q(point[0]) * fr.unit, tuple(_q(p) for p in trial))
            if at < 0:
                values = trial
                break
    return (point[0], *values)


def nonnegative_elementary(defn: Definition, space: Space) -> dict:
    """Every b_i >= 0 on the domain for every parameter value of the box? (module docstring)"""
    old = flint.ctx.prec
    flint.ctx.prec = PREC
    try:
        fr = _Frame(space.frame)
        affine = all(sum(key[0]) <= 1 for elem in space.functions for key in elem)
        if affine:  # the least value at fixed t is at a vertex: search the vertices only
            starts = [
                (vertex, [(v, v) for v in vertex])
                for vertex in itertools.product(*[(q.lo, q.hi) for q in defn.params])
            ]
        else:
            starts = [(None, [(q.lo, q.hi) for q in defn.params])]
        undecided = []
        for idx, b in enumerate(space.functions):
            for vertex, start in starts:
                fixed = b if vertex is None else A.at_parameters(b, vertex)
                verdict, point = _decide_one(fixed, space, fr, start, defn)
                if verdict == "negative":
                    assert point is not None
                    point = _inside_ranges(point, defn, b, fr)
                    where = f"{point[0]}*pi" if space.frame.dom_pi else str(point[0])
                    at = _enclose(b, fr, _q(point[0]) * fr.unit, tuple(_q(p) for p in point[1:]))
                    return {
                        "nonnegative": False,
                        "counterexample": {
                            "n": len(space.functions) - 1,
                            "i": idx,
                            "t": where,
                            **{q.name: str(v) for q, v in zip(defn.params, point[1:], strict=True)},
                            "value_upper_bound": f"{float(at.upper()):.6e}",
                        },
                    }
                if verdict == "undecided":
                    undecided.append(idx)
        if undecided:
            return {
                "reason": f"b_{sorted(set(undecided))[0]}: no sign proved in {MAX_BOXES} boxes "
                "(a zero inside the domain, or an end order that changes with the parameters)"
            }
        return {"nonnegative": True}
    finally:
        flint.ctx.prec = old
