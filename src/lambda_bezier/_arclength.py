"""∫ |p'(t)| dt for a polynomial curve p, given by its Taylor coefficients about t = 1/2
(d, N+1): the engine behind geometry.arc_length and parameter_at_length.

The rule. [a, b] is cut in equal pieces. On each piece two rules are compared, the m-point
Gauss–Lobatto rule (exact to degree 2m − 3) and the g-point Gauss–Legendre rule (to degree
2g − 1, higher), and the piece keeps the latter's value. A level is accepted when the
differences of its pieces and of those accepted before add up to at most rtol · total;
otherwise the pieces whose difference is within their share (by width) of that are
accepted and the others are refined.

Why the estimate holds. The speed is analytic away from the complex zeros of
q = |p'|² = Σ_c p'_c², which come in conjugate pairs x ± iy (y = 0: a cusp, p' = 0). On a
piece whose Bernstein ellipse of parameter ρ avoids them, the errors fall like ρ^-(degree):
where the test rule's is within the tolerance (ρ >= 2.6 or so), the value's is smaller by
ρ^-(2g − 2m + 2), below 1e-4, so the difference is an honest estimate of the test rule's
error and a very safe one of the value's. It can fail where that does not hold, near a
zero with y small against the piece (the speed is then |t − x| up to a smooth factor,
errors decay only algebraically and two rules can agree by chance):
- a kink in a Gauss rule's end gap is invisible to any pair of Gauss rules (all nodes on
  one side of it, both integrate the same smooth branch exactly): measured, two in a
  thousand random kinks in a piece fooled a 12/24-point Gauss pair, by up to 1e-8 of the
  total. The test rule is therefore Lobatto's, whose nodes include both ends;
- elsewhere the two errors cross by chance: measured, a few kinks in 10^5 at the first
  two levels' widths, where the errors are 1e-7..1e-9 of the total, but a few in a hundred
  at the widths where they come near the tolerance (seen: 1.6e-12 where 1e-12 was due). So
  after the first two levels (the second cuts each rejected piece of the first in _SPLIT)
  nothing is refined blindly: the zeros of q are computed
  (companion eigenvalues, once) and the rejected pieces are cut at their real parts and
  graded geometrically towards them, so that every piece keeps a distance from every zero
  of at least its own width (ρ >= 4.2), where the two rules' difference is a safe estimate.

Rounding. p' is evaluated with an absolute error of a few ulps of C = Σ |p' coefficient| ·
2^-k (its size on [0, 1]); where the speed is much smaller than C over all of [a, b] (a short
interval around a cusp) that, not rtol, bounds the accuracy, and the rule accepts a
difference within it instead of refining for ever.

Cost. A near-cusp is what makes a piece fail, and about one random quintic in four has one
near enough, so the refinement must be cheap too. On [0, 1] (most calls) the nodes of the
first level, and of the refinement of each of its pieces, are fixed, and so are the
matrices of powers there: such a level is one matrix product and a few ufuncs, and numpy's
cost per call is most of what a call costs.
"""

from __future__ import annotations

import math
from functools import cache

import numpy as np

_ORDER = 16  # m: the Lobatto test rule's points (both ends among them)
_VALUE = 20  # g: the Gauss rule's points, whose sums are the values
_PIECES = 24  # equal pieces of the first level
_SPLIT = 16  # a rejected first-level piece is cut in this many
_SNAP = 1e-9  # zeros of q nearer the real axis than this count as real (double: a cusp)
_NOISE = 32 * np.finfo(float).eps  # rounding of a speed value, relative to C
_SQUARED_UP_TO = 8  # the fixed levels evaluate |p'|² as one polynomial up to this degree of p
_MAX_PIECES = 4096  # a level with more pieces than this is accepted as it stands


@cache
def _pair() -> tuple[np.ndarray, np.ndarray]:
    """Nodes (m + g,) on [0, 1], the m-point Lobatto rule's then the g-point Gauss rule's,
    and weights (m + g, 2): column 0 gives (Lobatto − Gauss), column 1 the Gauss value."""
    legendre = np.polynomial.legendre.Legendre.basis(_ORDER - 1)
    inner = np.sort(legendre.deriv().roots().real)
    lobatto = np.concatenate([[-1.0], inner, [1.0]])
    w_lobatto = 2.0 / (_ORDER * (_ORDER - 1) * legendre(lobatto) ** 2)
    gauss, w_gauss = np.polynomial.legendre.leggauss(_VALUE)
    nodes = (np.concatenate([lobatto, gauss]) + 1) / 2
    weights = np.zeros((_ORDER + _VALUE, 2))
    weights[:_ORDER, 0] = w_lobatto / 2
    weights[_ORDER:, 0] = -w_gauss / 2
    weights[_ORDER:, 1] = w_gauss / 2
    nodes.setflags(write=False)
    weights.setflags(write=False)
    return nodes, weights


def _derivative_powers(u: np.ndarray, size: int) -> np.ndarray:
    """(size, len(u)) rows e · u^(e−1) (row 0 zero): coefficients (d, size) of p about 1/2
    times this are p' at t = u + 1/2."""
    out = np.empty((size, u.size))
    out[0] = 0.0
    if size > 1:
        out[1] = 1.0
    if size > 2:
        out[2] = u
    for e in range(3, size):  # (numpy's cumprod along this axis is several times slower)
        np.multiply(out[e - 1], u, out=out[e])
    if size > 2:
        out[2:] *= np.arange(2.0, size)[:, None]
    return out


@cache
def _square_map(size: int) -> np.ndarray:
    """(2·size − 3, size²): q = this @ (C^T C).ravel() for C the (d, size) Taylor
    coefficients of p, since q_k = Σ_{i+j=k+2} i·j Σ_c C[c, i] C[c, j] (p' is Σ i C_i u^(i−1))."""
    out = np.zeros((2 * size - 3, size * size))
    for i in range(1, size):
        for j in range(1, size):
            out[i + j - 2, i * size + j] = i * j
    out.setflags(write=False)
    return out


def _powers(u: np.ndarray, size: int) -> np.ndarray:
    """(size, len(u)) rows u^e."""
    out = np.empty((size, u.size))
    out[0] = 1.0
    if size > 1:
        out[1] = u
    for e in range(2, size):
        np.multiply(out[e - 1], u, out=out[e])
    return out


@cache
def _unit_levels(
    size: int,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The fixed levels on [0, 1] for p with `size` Taylor coefficients: at the first
    level's nodes the matrix that takes the operand (q's coefficients up to degree
    _SQUARED_UP_TO, else p's: rows of powers (t − 1/2)^e, or e (t − 1/2)^(e−1)) to values,
    the weights scaled to its width 1/K and K ones (to add up the pieces' sums with np.dot,
    cheaper than .sum(axis=0)); then the same matrix (K, ·, S·(m+g)) at the nodes of the S
    parts of each first-level piece, and the weights scaled to 1/(K·S)."""
    nodes, weights = _pair()
    first = ((np.arange(_PIECES)[:, None] + nodes) / _PIECES).ravel()
    parts = (np.arange(_SPLIT)[:, None] + nodes).ravel() / _SPLIT
    second = (np.arange(_PIECES)[:, None] + parts) / _PIECES
    if size <= _SQUARED_UP_TO + 1:
        terms = 2 * size - 3
        matrix = _powers
    else:
        terms = size
        matrix = _derivative_powers
    out = (
        matrix(first - 0.5, terms),
        weights / _PIECES,
        np.ones(_PIECES),
        np.stack([matrix(row - 0.5, terms) for row in second]),
        weights / (_PIECES * _SPLIT),
    )
    for arr in out:
        arr.setflags(write=False)
    return out


def _norms(values: np.ndarray) -> np.ndarray:
    """|p'| from p' values (…, d, n), overwriting them: (…, n)."""
    np.multiply(values, values, out=values)
    total = values[..., 0, :]
    for c in range(1, values.shape[-2]):  # d − 1 additions beat a reduction over d
        total += values[..., c, :]
    out: np.ndarray = np.sqrt(total, out=total)
    return out


def speeds(coeffs: np.ndarray, t: np.ndarray) -> np.ndarray:
    """|p'(t)| at every t (any shape)."""
    powers = _derivative_powers(t.ravel() - 0.5, coeffs.shape[1])
    return _norms(np.dot(coeffs, powers)).reshape(t.shape)


def _sums(coeffs: np.ndarray, left: np.ndarray, width: np.ndarray) -> np.ndarray:
    """(P, 2): (Lobatto − Gauss, Gauss) on each [left_i, left_i + width_i]."""
    nodes, weights = _pair()
    speed = speeds(coeffs, left[:, None] + width[:, None] * nodes)
    sums: np.ndarray = np.dot(speed, weights) * width[:, None]
    return sums


def partial(coeffs: np.ndarray, start: np.ndarray, end: np.ndarray) -> np.ndarray:
    """The Gauss rule for ∫|p'| over each [start_i, end_i] (vectorised)."""
    nodes, weights = _pair()
    width = end - start
    speed = speeds(coeffs, start[:, None] + width[:, None] * nodes[_ORDER:])
    out: np.ndarray = np.dot(speed, weights[_ORDER:, 1]) * width
    return out


def unit_integral(coeffs: np.ndarray, rtol: float) -> float:
    """∫_0^1 |p'| to a relative accuracy rtol. The first level and the refinement of its
    rejected pieces use the fixed nodes; what still fails goes on in _finish. Up to degree
    _SQUARED_UP_TO of p, |p'|² is evaluated there as the one polynomial q (one product and
    two ufuncs instead of one product and d + 1 ufuncs, and this is most of the work): its
    rounding, about C² ulps instead of C·|p'| (C the size of p' on [0, 1]), is harmless at
    such degrees where these levels accept a piece (away from zeros of q). (Measured on
    random curves of degree 9..14, still within 1e-13, but C grows fast with the degree;
    past _SQUARED_UP_TO these levels evaluate p' itself.)"""
    size = coeffs.shape[1]
    first, weights, ones, second, second_weights = _unit_levels(size)
    squared = size <= _SQUARED_UP_TO + 1
    # (the .dot method: a little cheaper than np.dot, which is cheaper than @, on operands
    # this small; np.abs before np.sqrt: q < 0 only by rounding, where it is 0 within it,
    # and half the cost of np.maximum with 0)
    if squared:
        operand = _square_map(size).dot(coeffs.T.dot(coeffs).ravel())  # q
        values = operand.dot(first)
        np.abs(values, out=values)
        np.sqrt(values, out=values)
    else:
        operand = coeffs
        values = _norms(coeffs.dot(first))
    sums = values.reshape(_PIECES, -1).dot(weights)
    size = np.abs(sums)
    spent, total = ones.dot(size).tolist()
    if spent <= rtol * total or not total > 0.0:  # most curves: accepted at once
        return float(total)  # (0: a constant curve)
    bad = (size[:, 0] > rtol * total / _PIECES).nonzero()[0]
    for rejected, value in size[bad].tolist():
        spent -= rejected
        total -= value
    # one piece as a rule, or two (a near-cusp by a joint): one product for all
    values = operand.dot(second[bad[0]]) if bad.size == 1 else operand @ second[bad]
    if squared:
        np.abs(values, out=values)
        np.sqrt(values, out=values)
    else:
        values = _norms(values)
    sums = values.reshape(bad.size * _SPLIT, -1).dot(second_weights)
    size = np.abs(sums)
    new_spent, new_total = size.sum(axis=0).tolist()
    if spent + new_spent <= rtol * (total + new_total):
        return float(total + new_total)
    width = 1.0 / (_PIECES * _SPLIT)
    left = ((bad[:, None] * _SPLIT + np.arange(_SPLIT)) * width).ravel()
    widths = np.full(left.size, width)
    return _finish(coeffs, 0.0, 1.0, rtol, left, widths, sums, total, spent, None)


def integral(coeffs: np.ndarray, a: float, b: float, rtol: float) -> float:
    """∫_a^b |p'| to a relative accuracy rtol."""
    width = np.full(_PIECES, (b - a) / _PIECES)
    left = a + width * np.arange(_PIECES)
    sums = _sums(coeffs, left, width)
    return _finish(coeffs, a, b, rtol, left, width, sums, 0.0, 0.0, None)


def table(coeffs: np.ndarray, rtol: float) -> tuple[np.ndarray, np.ndarray]:
    """The accepted pieces of [0, 1]: sorted edges (K+1,) and cumulative lengths (K+1,)."""
    width = np.full(_PIECES, 1.0 / _PIECES)
    left = width * np.arange(_PIECES)
    sums = _sums(coeffs, left, width)
    parts: list[tuple[np.ndarray, np.ndarray]] = []
    total = _finish(coeffs, 0.0, 1.0, rtol, left, width, sums, 0.0, 0.0, parts)
    lefts = np.concatenate([p[0] for p in parts])
    values = np.concatenate([p[1] for p in parts])
    order = np.argsort(lefts, kind="stable")
    edges = np.append(lefts[order], 1.0)  # the accepted pieces tile [0, 1]
    cum = np.concatenate([[0.0], np.cumsum(values[order])])
    cum[-1] = total
    return edges, cum


def _finish(
    coeffs: np.ndarray,
    a: float,
    b: float,
    rtol: float,
    left: np.ndarray,
    width: np.ndarray,
    sums: np.ndarray,
    accepted: float,
    spent: float,
    parts: list[tuple[np.ndarray, np.ndarray]] | None,
) -> float:
    """The adaptive rule from a level of pieces [left_i, left_i + width_i] with their sums,
    given the value and the error estimate of the pieces accepted before it: rejected
    pieces of the first level are cut in _SPLIT, then the rejected ones once by the zeros
    of q (_partition), then halved while they fail. Returns the total; `parts` (if given)
    collects the accepted pieces' left ends and values."""
    span = b - a
    stage = 0 if width[0] * _PIECES >= span * (1 - 1e-9) else 1  # (first-level pieces: 0)
    # C, the size of p' on [0, 1] (Σ |e · coeffs[:, e]| 2^-(e−1)), and from it the rounding
    # of a difference of the rules per unit width (see the module's note on rounding)
    e = np.arange(1.0, coeffs.shape[1])
    noise = _NOISE * float((np.abs(coeffs[:, 1:]) * (e * 0.5 ** (e - 1))).sum())
    while True:
        size = np.abs(sums)
        level_spent, level_total = size.sum(axis=0).tolist()
        total = accepted + level_total
        if (
            spent + level_spent <= max(rtol * total, noise * span)
            or left.size > _MAX_PIECES
            or not total > 0
        ):
            if parts is not None:
                parts.append((left, sums[:, 1]))
            return float(total)
        ok = size[:, 0] <= np.maximum(rtol * total / span, noise) * width
        accepted += float(size[ok, 1].sum())
        spent += float(size[ok, 0].sum())
        if parts is not None:
            parts.append((left[ok], sums[ok, 1]))
        left, width = left[~ok], width[~ok]
        if stage == 0:  # as the fixed second level: wide pieces are cut in _SPLIT, blindly
            width = np.repeat(width / _SPLIT, _SPLIT)
            left = (left[:, None] + width.reshape(-1, _SPLIT) * np.arange(_SPLIT)).ravel()
        elif stage == 1:
            left, width = _partition(coeffs, left, width)
        else:
            left = np.concatenate([left, left + width / 2])
            width = np.concatenate([width, width]) / 2
        stage += 1
        sums = _sums(coeffs, left, width)


def _zeros(coeffs: np.ndarray) -> list[complex]:
    """The zeros t of q = |p'|² with Im t >= 0 (the others are their conjugates):
    eigenvalues of the companion matrix of q's Taylor coefficients."""
    q = np.dot(_square_map(coeffs.shape[1]), np.dot(coeffs.T, coeffs).ravel()).tolist()
    while q and q[-1] == 0.0:
        q.pop()
    degree = len(q) - 1
    if degree < 1:
        return []
    companion = np.eye(degree, k=-1)
    companion[0] = q[-2::-1]
    companion[0] /= -q[-1]
    return [u + 0.5 for u in np.linalg.eigvals(companion).tolist() if u.imag >= 0]


def _partition(
    coeffs: np.ndarray, left: np.ndarray, width: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """The pieces [left_i, left_i + width_i] (disjoint, in any order) cut so that every
    part lies at least its own width away from every zero x + iy of q: at x, and at
    x ± y·2^k (k = 0, 1, …), the geometric grading that keeps a part next to x as wide as y
    and the others as wide as their distance to x. A zero with y < _SNAP counts as a double
    real zero (p' = 0, a cusp: the speed is |t − x| times a smooth factor, analytic on
    either side of x): a cut at x alone. (The error of taking such a y as 0 is about
    y² log(1/y) of the speed's scale; and a double zero is computed only to about 1e-8, as
    x ± iy or x ± y, which the same rule handles. Zeros farther than the widest piece from
    all of them cut nothing, and parts farther from x than that need no cut.)"""
    right = left + width
    lo, hi, widest = float(left.min()), float(right.max()), float(width.max())
    cuts = left.tolist() + right.tolist()
    for z in _zeros(coeffs):
        x, y = z.real, abs(z.imag)
        if y >= widest or not lo - widest < x < hi + widest:
            continue
        cuts.append(x)
        if y >= _SNAP:
            for k in range(math.ceil(math.log2(widest / y)) + 1):
                cuts += [x - y * 2.0**k, x + y * 2.0**k]
    points = np.array(sorted(set(cuts)))
    # the parts: consecutive points whose midpoint lies in one of the pieces (inside as
    # many left ends as right ends plus one)
    mid = (points[:-1] + points[1:]) / 2
    keep = np.searchsorted(np.sort(left), mid) > np.searchsorted(np.sort(right), mid)
    return points[:-1][keep], np.diff(points)[keep]
