"""A tangency's pair of pieces confined without subdividing it to the rounding (issue #29).

Near a tangency the subdivision (intersect_subdivide) keeps a few pairs of pieces at every
level, neither dropped nor isolated, until both pieces are flat to the slack (width ~2^-23 for
unit quadratics): ~16 pairs of pieces examined a level, most of a tangent pair's time. Those
flat pieces only give Newton its starts; the tangent refinement does the rest.

`contact_cell` ends that descent early where a certificate holds. On a planar pair of pieces a
(local parameter u) and b (v), Newton on

    a'(u) x b'(v) = 0,    (a(u) - b(v)) . a'(u) = 0

(regular at a tangency whose curvatures differ) finds the point of contact (u*, v*): the
pieces run parallel there and their difference is along the normal n. The pair is confined
to that point when

1. the gap |a(u*) - b(v*)| is within the pieces' rounding (GAP of the slack): the curves
   touch there to the precision of their pieces;
2. cutting a at u* -+ ra and b at v* -+ rb (ra, rb: a radius R in the curves' parameter, one
   of them doubled in length along the tangent) into left, middle and right parts, every pair
   of parts but (middle, middle) is apart by more than twice the slack along n or along the
   tangent e: their control points' projections on that axis lie in disjoint intervals, so by
   the convex hull property the parts have no common point (a separating axis; any axis is
   sound, these are the ones that separate the parts next to a tangency whose curves lie on
   the two sides of the common tangent). One of the two ways of doubling must do it.

Where a straight axis cannot part them (both curves on ONE side of the common tangent, a
circle inside another: the parts beside the contact overlap along both axes), a curved one
may (issue #29 round 20): with signed curvatures ka != kb along n at the contact and
c = (ka + kb) / 2, the parabola f(p) = n . (p - o) - c/2 (e . (p - o))^2 = 0 has a on one
side and b on the other near the contact (f(a) ~ (ka - c) s^2 / 2, f(b) ~ (kb - c) s^2 / 2).
Each piece is cut at its contact and at -+ R of it into four parts; f on a part is a
polynomial of degree 2n, whose range lies within its Bernstein coefficients (made from the
part's control points: B_i B_j = C(n, i) C(n, j) / C(2n, i + j) B_(i+j)); every pair of
parts but the middle ones must have ranges apart by more than both ranges' error bounds
(the pieces' rounding times f's slope there, and the coefficients' own rounding), or be
apart along n or e as above.

The contact comes from Newton; where Newton fails (its Jacobian is singular where the
curvatures agree, as at a smooth join of two curves), a corner of the pair where the
pieces' end points meet within GAP of the slack with parallel tangents (sine below
CORNER_SINE) is taken as the contact instead, and certified the same way (a smooth join's
parts lie apart along the tangent).

Then every common point of the pair lies within R of (u*, v*), and the pair is reported as the
unresolved piece of width R at level `deep` holding the contact (the cell the subdivision
would reach on its way down there): the careful path's tangent refinement starts from its
middle. A contact of equal curvatures away from a corner, one of higher order (an
inflection on the other curve) or two crossings farther apart than the rounding fail a
test, and the pair is halved as before. Only the starts change: the answers are the careful
path's to the tolerance of its tangent refinement (tests/test_contact_cell.py and
tests/test_contact_one_side.py compare them with the subdivision to the flat pieces).

The same source runs in numpy's fallback (plain Python on floats) and compiled
(intersect_compiled wraps it with numba): one sum in one order, so both take the same pairs.
"""

from __future__ import annotations

import math
from typing import Any

CONTACT_LEVEL = 2  # the first level whose halved pairs try the certificate ...
CONTACT_EVERY = 3  # ... and every third level after it (each try costs ~1 us compiled)
RADIUS = 20  # common points are confined to within R = 2^-20 ~ 1e-6 of the contact
DEEP = 32  # the cell reported, of width 2^-32 (the subdivision's depth), holds the contact
STEPS = 8  # Newton steps at most
STEP = 1e-12  # Newton has converged below this step (in the pieces' local parameters)
FAR = 8.0  # ... and is given up beyond this far outside the pieces (its first step can be long)
CONDITION = 1e-6  # ... and its Jacobian's determinant, relative to its terms, at least this
# the gap at the contact, as a share of the slack: the pieces' own rounding (the input's half
# ulp and ~1 ulp per halving, intersect_subdivide.BLUR). Curves apart by more there, or
# crossing twice with more than that between them, are halved as before: the flat pieces'
# several Newton starts then decide (two crossings 2e-7 apart whose curves separate by 1e-14
# between them are one transversal hit there, and stay so)
GAP = 1 / 16
# curvatures closer than this share of their sizes are not parted by the parabola between them
CURVED = 1e-3
# a corner where the pieces' ends meet is a contact when their end tangents' sine is below this
# (intersect.TANGENT_SINE: the careful path refines such a hit as a tangency)
CORNER_SINE = 1e-6
EPS = 2.0**-52


def _rows(count: int, width: int) -> Any:
    """Scratch rows of floats: nested lists here (Python indexes them faster than numpy's
    scalars), an array in the compiled twin (intersect_compiled replaces this function)."""
    return [[0.0] * width for _ in range(count)]


def _blocks(count: int, rows: int, width: int) -> Any:
    """count blocks of scratch rows (_rows)."""
    return [_rows(rows, width) for _ in range(count)]


def _second_order(piece: Any, u: float, work: Any, out: Any) -> None:
    """A planar piece's value, first and second derivative at u (rows 0, 1, 2 of out), by
    de Casteljau in work."""
    n = len(piece) - 1
    for i in range(n + 1):
        for j in range(2):
            work[i][j] = piece[i][j]
    for j in range(2):
        out[1][j] = 0.0
        out[2][j] = 0.0
    for level in range(n):
        if level == n - 2:
            for j in range(2):
                out[2][j] = (n * (n - 1)) * ((work[2][j] - work[1][j]) - (work[1][j] - work[0][j]))
        if level == n - 1:
            for j in range(2):
                out[1][j] = n * (work[1][j] - work[0][j])
        for i in range(n - level):
            for j in range(2):
                work[i][j] = work[i][j] + u * (work[i + 1][j] - work[i][j])
    for j in range(2):
        out[0][j] = work[0][j]


def _part(piece: Any, u0: float, u1: float, work: Any, out: Any) -> None:
    """The control points of piece over [u0, u1] (0 <= u0 < u1 <= 1) into out: de Casteljau
    at u1 (its left part), then at u0 / u1 (the right part of that)."""
    n = len(piece) - 1
    for i in range(n + 1):
        for j in range(2):
            work[i][j] = piece[i][j]
    for level in range(n + 1):  # the left part at u1: the first point of each level
        for j in range(2):
            out[level][j] = work[0][j]
        for i in range(n - level):
            for j in range(2):
                work[i][j] = work[i][j] + u1 * (work[i + 1][j] - work[i][j])
    if u0 <= 0.0:
        return
    x = u0 / u1
    for i in range(n + 1):
        for j in range(2):
            work[i][j] = out[i][j]
    for level in range(n + 1):  # the right part at x: the last point of each level
        for j in range(2):
            out[n - level][j] = work[n - level][j]
        for i in range(n - level):
            for j in range(2):
                work[i][j] = work[i][j] + x * (work[i + 1][j] - work[i][j])


def _interval(
    points: Any, count: int, ox: float, oy: float, x: float, y: float
) -> tuple[float, float]:
    lo, hi = math.inf, -math.inf
    for i in range(count):
        d = (points[i][0] - ox) * x + (points[i][1] - oy) * y
        lo, hi = min(lo, d), max(hi, d)
    return lo, hi


def _apart(p: Any, q: Any, ox: float, oy: float, ex: float, ey: float, gap: float) -> bool:
    """p and q (control points) apart by more than gap along the normal (-ey, ex) or along
    the tangent (ex, ey)."""
    count_p, count_q = len(p), len(q)
    p_lo, p_hi = _interval(p, count_p, ox, oy, -ey, ex)
    q_lo, q_hi = _interval(q, count_q, ox, oy, -ey, ex)
    if p_lo > q_hi + gap or p_hi < q_lo - gap:
        return True
    p_lo, p_hi = _interval(p, count_p, ox, oy, ex, ey)
    q_lo, q_hi = _interval(q, count_q, ox, oy, ex, ey)
    return p_lo > q_hi + gap or p_hi < q_lo - gap


def _confined(
    a: Any,
    b: Any,
    u: float,
    v: float,
    ra: float,
    rb: float,
    ox: float,
    oy: float,
    ex: float,
    ey: float,
    gap: float,
    parts_a: Any,
    parts_b: Any,
    work: Any,
) -> int:
    """Whether every pair of the parts of a ([0, u - ra], [u - ra, u + ra], [u + ra, 1]) and
    of b (likewise with v, rb) but the two middle ones is apart (_apart), empty parts
    skipped: 0 when they are; else 1 where two outer parts are not (the curves on one side
    of the tangent, which other radii do not change), 2 where a middle part is not. Outer
    pairs first (where most failures are), each part made when first needed."""
    cuts_a = (0.0, max(u - ra, 0.0), min(u + ra, 1.0), 1.0)
    cuts_b = (0.0, max(v - rb, 0.0), min(v + rb, 1.0), 1.0)
    made_a, made_b = [False, False, False], [False, False, False]
    for m in range(8):  # (0, 0), (2, 2), (0, 2), (2, 0), then (0, 1), (2, 1), (1, 0), (1, 2)
        if m < 4:
            i, j = (0, 2, 0, 2)[m], (0, 2, 2, 0)[m]
        else:
            i, j = (0, 2, 1, 1)[m - 4], (1, 1, 0, 2)[m - 4]
        if not (cuts_a[i + 1] > cuts_a[i] and cuts_b[j + 1] > cuts_b[j]):
            continue
        if not made_a[i]:
            _part(a, cuts_a[i], cuts_a[i + 1], work, parts_a[i])
            made_a[i] = True
        if not made_b[j]:
            _part(b, cuts_b[j], cuts_b[j + 1], work, parts_b[j])
            made_b[j] = True
        if not _apart(parts_a[i][: len(a)], parts_b[j][: len(b)], ox, oy, ex, ey, gap):
            return 1 if m < 4 else 2
    return 0


def _binomial(n: int, k: int) -> float:
    out = 1.0
    for i in range(k):
        out = out * (n - i) / (i + 1)
    return out


def _curved_range(
    part: Any,
    count: int,
    ox: float,
    oy: float,
    ex: float,
    ey: float,
    c: float,
    sign: float,
    slack: float,
) -> tuple[float, float, float]:
    """The range of f(p) = sign (n . (p - o) - c/2 (e . (p - o))^2) (n = (-ey, ex)) over the
    part (count control points): within its Bernstein coefficients of degree 2 (count - 1),
    those of the polynomial f(part(w)) (the convex hull property), made from the products
    B_i B_j = C(n, i) C(n, j) / C(2n, i + j) B_(i+j) of the part's own coefficients.
    Returned as (lo, hi, err), err bounding the error of both: a control point off by the
    pieces' rounding (slack) moves each coefficient by at most slack (1 + |c| T) (T: the
    largest |e . (p - o)| of the part), and their rounding is below 8 (2n + 2) eps of their
    terms."""
    n = count - 1
    lo, hi = math.inf, -math.inf
    reach_n = reach_t = 0.0
    for i in range(count):
        reach_n = max(reach_n, abs(-(part[i][0] - ox) * ey + (part[i][1] - oy) * ex))
        reach_t = max(reach_t, abs((part[i][0] - ox) * ex + (part[i][1] - oy) * ey))
    for k in range(2 * n + 1):
        total = 0.0
        for i in range(max(0, k - n), min(n, k) + 1):
            j = k - i
            ni = -(part[i][0] - ox) * ey + (part[i][1] - oy) * ex
            ti = (part[i][0] - ox) * ex + (part[i][1] - oy) * ey
            tj = (part[j][0] - ox) * ex + (part[j][1] - oy) * ey
            total += _binomial(n, i) * _binomial(n, j) * (ni - 0.5 * c * ti * tj)
        g = sign * total / _binomial(2 * n, k)
        lo, hi = min(lo, g), max(hi, g)
    rounding = 8.0 * (2 * n + 2) * EPS * (reach_n + abs(c) * reach_t * reach_t)
    return lo, hi, slack * (1.0 + abs(c) * reach_t) + rounding


def _curved_confined(
    a: Any,
    b: Any,
    u: float,
    v: float,
    ra: float,
    rb: float,
    ox: float,
    oy: float,
    ex: float,
    ey: float,
    c: float,
    sign: float,
    slack: float,
    parts_a: Any,
    parts_b: Any,
    work: Any,
) -> bool:
    """Whether every pair of the parts of a ([0, u - ra], [u - ra, u], [u, u + ra],
    [u + ra, 1]) and of b (likewise with v, rb) but the middle ones is apart along the
    parabola f = 0 (_curved_range: a's parts on its positive side, b's on its negative one,
    the middle ones touching it at the contact), by more than both ranges' errors, or
    along the normal or the tangent (_apart)."""
    n1, n2 = len(a), len(b)
    cuts_a = (0.0, min(max(u - ra, 0.0), 1.0), min(max(u, 0.0), 1.0), min(u + ra, 1.0), 1.0)
    cuts_b = (0.0, min(max(v - rb, 0.0), 1.0), min(max(v, 0.0), 1.0), min(v + rb, 1.0), 1.0)
    lo_a, hi_a, err_a = [0.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 0.0]
    lo_b, hi_b, err_b = [0.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 0.0]
    for i in range(4):
        if cuts_a[i + 1] > cuts_a[i]:
            _part(a, cuts_a[i], cuts_a[i + 1], work, parts_a[i])
            lo_a[i], hi_a[i], err_a[i] = _curved_range(
                parts_a[i], n1, ox, oy, ex, ey, c, sign, slack
            )
        if cuts_b[i + 1] > cuts_b[i]:
            _part(b, cuts_b[i], cuts_b[i + 1], work, parts_b[i])
            lo_b[i], hi_b[i], err_b[i] = _curved_range(
                parts_b[i], n2, ox, oy, ex, ey, c, sign, slack
            )
    for i in range(4):
        if not cuts_a[i + 1] > cuts_a[i]:
            continue
        for j in range(4):
            if not cuts_b[j + 1] > cuts_b[j] or (0 < i < 3 and 0 < j < 3):
                continue
            margin = err_a[i] + err_b[j]
            if lo_a[i] > hi_b[j] + margin or hi_a[i] < lo_b[j] - margin:
                continue
            if not _apart(parts_a[i][:n1], parts_b[j][:n2], ox, oy, ex, ey, 2.0 * slack):
                return False
    return True


def _newton_contact(
    a: Any, b: Any, wa: Any, wb: Any, da: Any, db: Any
) -> tuple[bool, float, float]:
    """Newton on the tangency system from the pieces' middles: (True, u*, v*) where it
    converges and its Jacobian there is regular (curvatures that differ)."""
    u = v = 0.5
    for _ in range(STEPS):
        _second_order(a, u, wa, da)
        _second_order(b, v, wb, db)
        a1x, a1y, b1x, b1y = da[1][0], da[1][1], db[1][0], db[1][1]
        ex, ey = da[0][0] - db[0][0], da[0][1] - db[0][1]
        f1 = a1x * b1y - a1y * b1x
        f2 = ex * a1x + ey * a1y
        j11 = da[2][0] * b1y - da[2][1] * b1x
        j12 = a1x * db[2][1] - a1y * db[2][0]
        j21 = (a1x * a1x + a1y * a1y) + (ex * da[2][0] + ey * da[2][1])
        j22 = -(b1x * a1x + b1y * a1y)
        det = j11 * j22 - j12 * j21
        if not (det != 0.0 and math.isfinite(det)):
            return False, 0.0, 0.0
        du = (j12 * f2 - j22 * f1) / det
        dv = (j21 * f1 - j11 * f2) / det
        u, v = u + du, v + dv
        if not (-FAR < u < 1.0 + FAR and -FAR < v < 1.0 + FAR):
            return False, 0.0, 0.0  # no contact of these pieces near
        if abs(du) + abs(dv) < STEP:
            # regular there: curvatures that differ (equal ones, as where two pieces of one
            # curve meet, leave det at rounding level, and the decision to rounding)
            return abs(det) > CONDITION * (abs(j11 * j22) + abs(j12 * j21)), u, v
    return False, 0.0, 0.0


def _corner_contact(a: Any, b: Any, slack: float) -> tuple[bool, float, float]:
    """A corner of the pair where the pieces' end points meet within their rounding (GAP of
    the slack) and their tangents are parallel (sine below CORNER_SINE): where two curves
    join smoothly their contact is known without Newton (whose Jacobian is singular there
    when the curvatures agree). A corner where they cross is left to the cones, which
    isolate it."""
    n1, n2 = len(a), len(b)
    for corner in range(4):
        i = 0 if corner < 2 else n1 - 1
        j = 0 if corner % 2 == 0 else n2 - 1
        gx, gy = a[i][0] - b[j][0], a[i][1] - b[j][1]
        if not math.sqrt(gx * gx + gy * gy) <= GAP * slack:
            continue
        i2 = 1 if corner < 2 else n1 - 2
        j2 = 1 if corner % 2 == 0 else n2 - 2
        ax, ay = a[i2][0] - a[i][0], a[i2][1] - a[i][1]
        bx, by = b[j2][0] - b[j][0], b[j2][1] - b[j][1]
        norms = math.sqrt(ax * ax + ay * ay) * math.sqrt(bx * bx + by * by)
        if norms > 0.0 and abs(ax * by - ay * bx) <= CORNER_SINE * norms:
            return True, (0.0 if corner < 2 else 1.0), (0.0 if corner % 2 == 0 else 1.0)
    return False, 0.0, 0.0


def contact_cell(
    a: Any, b: Any, ka: int, kb: int, level: int, deep: int, slack: float
) -> tuple[bool, int, int]:
    """A planar pair of pieces a, b (the ka-th and kb-th of width 2^-level): (True, the
    indices of the cell of width 2^-deep holding its point of contact) where the certificate
    above confines every common point of the pair to within R = 2^-RADIUS of it; else
    (False, 0, 0). a and b: arrays (n+1, 2), or nested lists (faster in plain Python)."""
    n1, n2 = len(a), len(b)
    wa, wb = _rows(n1, 2), _rows(n2, 2)
    da, db = _rows(3, 2), _rows(3, 2)
    for attempt in range(2):  # the contact by Newton, else a corner where the pieces join
        if attempt == 0:
            found, u, v = _newton_contact(a, b, wa, wb, da, db)
        else:
            found, u, v = _corner_contact(a, b, slack)
        if found and _certified(a, b, u, v, level, slack, wa, wb, da, db):
            # the cell of the contact (or, just past the pair's edge, the pair's cell next
            # to it)
            cells = 2 ** (deep - level)
            at_a = (ka + min(max(u, 0.0), 1.0)) * cells
            at_b = (kb + min(max(v, 0.0), 1.0)) * cells
            cell_a = min(int(math.floor(at_a)), (ka + 1) * cells - 1)
            cell_b = min(int(math.floor(at_b)), (kb + 1) * cells - 1)
            return True, cell_a, cell_b
    return False, 0, 0


def _certified(
    a: Any, b: Any, u: float, v: float, level: int, slack: float, wa: Any, wb: Any, da: Any, db: Any
) -> bool:
    """Whether every common point of the pair lies within R of (u, v): the curves meet
    there within the pieces' rounding, and the parts away from it are apart (_confined,
    else _curved_confined)."""
    n1, n2 = len(a), len(b)
    size = max(n1, n2)
    _second_order(a, u, wa, da)
    _second_order(b, v, wb, db)
    gx, gy = da[0][0] - db[0][0], da[0][1] - db[0][1]
    if not math.sqrt(gx * gx + gy * gy) <= GAP * slack:
        return False  # apart, or crossing twice beyond the pieces' rounding: subdivide
    length_a = math.sqrt(da[1][0] * da[1][0] + da[1][1] * da[1][1])
    length_b = math.sqrt(db[1][0] * db[1][0] + db[1][1] * db[1][1])
    if not (length_a > 0.0 and length_b > 0.0):
        return False
    ex, ey = da[1][0] / length_a, da[1][1] / length_a
    width = 0.5**level
    radius = 0.5**RADIUS / width  # R in a's and b's local parameters
    parts_a, parts_b = _blocks(4, size, 2), _blocks(4, size, 2)
    work = _rows(size, 2)
    ox, oy, gap = da[0][0], da[0][1], 2.0 * slack
    confined = False
    for wider in range(2):  # b's middle part twice as long along the tangent as a's, or a's
        if wider == 0:
            ra, rb = radius, 2.0 * radius * length_a / length_b
        else:
            ra, rb = 2.0 * radius * length_b / length_a, radius
        if not (u - ra < 1.0 and u + ra > 0.0 and v - rb < 1.0 and v + rb > 0.0):
            continue  # the contact is a neighbour's: its pair reports it
        failed = _confined(a, b, u, v, ra, rb, ox, oy, ex, ey, gap, parts_a, parts_b, work)
        if failed == 0:
            confined = True
            break
        if failed == 1:
            break  # two outer parts meet: the other radii would not separate them
    if not confined:
        # both curves on one side of the common tangent: a parabola between them (its
        # curvature the mean of theirs, along the normal) parts them away from the contact
        ra, rb = radius, radius * length_a / length_b
        if not (u - ra < 1.0 and u + ra > 0.0 and v - rb < 1.0 and v + rb > 0.0):
            return False
        curve_a = (-ey * da[2][0] + ex * da[2][1]) / (length_a * length_a)
        curve_b = (-ey * db[2][0] + ex * db[2][1]) / (length_b * length_b)
        if not abs(curve_a - curve_b) > CURVED * (abs(curve_a) + abs(curve_b)):
            return False
        sign = 1.0 if curve_a > curve_b else -1.0
        c = 0.5 * (curve_a + curve_b)
        confined = _curved_confined(
            a, b, u, v, ra, rb, ox, oy, ex, ey, c, sign, slack, parts_a, parts_b, work
        )
    return confined


def tries(level: int) -> bool:
    """Whether pairs halved at this level try contact_cell."""
    return (
        level >= CONTACT_LEVEL and (level - CONTACT_LEVEL) % CONTACT_EVERY == 0 and level < RADIUS
    )
