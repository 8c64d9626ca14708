"""∫ |p'(t)| dt for a polynomial curve p, given by its Taylor coefficients about t = 1/2
(d, N+1): the engine behind geometry.arc_length and parameter_at_length.

The rule. [a, b] is cut in equal pieces. On each piece two rules are compared, the m-point
Gauss–Lobatto rule (exact to degree 2m − 3) and its Kronrod extension (2m − 1 points, the
same and m − 1 more, exact to degree 3m − 3), and the piece keeps the latter's value (a
Gauss value rule as far above the test would need about m + 8 points of its own). A level
is accepted when the differences of its pieces and of those accepted before add up to at
most rtol · total; otherwise the pieces whose difference is within their share (by width)
of that are accepted and the others are refined.

Why the estimate holds. The speed is analytic away from the complex zeros of
q = |p'|² = Σ_c p'_c², which come in conjugate pairs x ± iy (y = 0: a cusp, p' = 0). On a
piece whose Bernstein ellipse of parameter ρ avoids them, the errors fall like ρ^-(degree),
so the value's is smaller than the test rule's by about ρ^-m = ρ^-16 and the difference
is an honest estimate of the test rule's error and a very safe one of the value's. (The
gap matters: with a 20-point Gauss value, degree 39 against 29, the two rules were both
off by 4e-12 in the same direction on a random curve, at ρ ≈ 1.6, and the length by
2e-12.) It can fail where that does not hold, near a zero with y small against the piece
(the speed is then |t − x| up to a smooth factor, errors decay only algebraically and two
rules can agree by chance):
- a kink in a Gauss rule's end gap is invisible to any pair of Gauss rules (all nodes on
  one side of it, both integrate the same smooth branch exactly): measured, two in a
  thousand random kinks in a piece fooled a 12/24-point Gauss pair, by up to 1e-8 of the
  total. The test rule is therefore Lobatto's, whose nodes include both ends;
- elsewhere the two errors cross by chance: measured, a few kinks in 10^5 at the first
  two levels' widths, where the errors are 1e-7..1e-9 of the total, but a few in a hundred
  at the widths where they come near the tolerance (seen: 1.6e-12 where 1e-12 was due). So
  after the first two levels (the second cuts each rejected piece of the first in _SPLIT)
  nothing is refined blindly: the zeros of q are computed (companion eigenvalues, once)
  and the rejected pieces are cut at their real parts and graded geometrically towards
  them, so that every piece keeps a distance from every zero of at least its own width
  (ρ >= 4.2), where the two rules' difference is a safe estimate.

Hidden dips. Near a near-double zero of p' (p' ≈ (t − x)² G + small terms, all coordinates
at once) the speed is about (t − x)² |G|, analytic, but for a dip of width r about the
zeros of q there (r ≈ 1e-4 for p'(x) ≈ 1e-8 |G|); when no node falls in it, both rules
integrate the smooth branch alike and miss about |G| r³ (measured: 1.2e-12 of the length).
Then the nodes next to x have a speed of at most about 2 |G| δ², δ <= half the widest gap
between nodes, so a piece whose least speed at its nodes exceeds 2 |G| (2δ)² (B for |G|,
a bound on |p‴|/2 over [0, 1], _hidden_weights) hides none; one that does not, at the
first two levels, is partitioned like a rejected piece if a zero of q lies by it. (About
one random quintic in 1500 has so low a speed, and then the zeros are computed once.)

Rounding. p' is evaluated with an absolute error of a few ulps of C = Σ |p' coefficient| ·
2^-k (its size on [0, 1]); where the speed is much smaller than C over all of [a, b] (a short
interval around a cusp) that, not rtol, bounds the accuracy, and the rule accepts a
difference within it instead of refining for ever.

Cost. A near-cusp is what makes a piece fail, and about one random quintic in five has one
near enough, so the refinement must be cheap too. On [0, 1] (most calls) the nodes of the
first level, and of the refinement of each of its pieces, are fixed, and so are the
matrices of powers there: such a level is one matrix product and a few ufuncs, and numpy's
cost per call is most of what a call costs.
"""

from __future__ import annotations

import math
from functools import cache

import numpy as np

from . import kernels

_ORDER = 16  # m: the Lobatto test rule's points (both ends among them); 2m − 1 in all
_PIECES = 24  # equal pieces of the first level
_SPLIT = 16  # a rejected first-level piece is cut in this many
_SNAP = 1e-9  # zeros of q nearer the real axis than this count as real (double: a cusp)
_NOISE = 32 * np.finfo(float).eps  # rounding of a speed value, relative to C
_MAX_PIECES = 4096  # a level with more pieces than this is accepted as it stands


@cache
def _pair() -> tuple[np.ndarray, np.ndarray]:
    """Nodes (2m − 1,) on [0, 1]: the m-point Gauss–Lobatto rule's, then the m − 1 of its
    Kronrod extension; and weights (2m − 1, 2): column 0 gives (Lobatto − Lobatto–Kronrod),
    column 1 the Lobatto–Kronrod value (exact to degree 3m − 3, against 2m − 3).

    The extension's nodes are the zeros of the polynomial E of degree m − 1 orthogonal to
    all of lower degree with the weight ω(x) = (1 − x²) P'_{m−1}(x) of the Lobatto nodes
    (Kronrod's condition); the weights then make the 2m − 1 nodes' rule interpolatory. For
    m = 4 this is Gander and Gautschi's 7-point rule (tests/test_arclength.py)."""
    legendre = np.polynomial.legendre
    derivative = legendre.Legendre.basis(_ORDER - 1).deriv()
    lobatto = np.concatenate([[-1.0], np.sort(derivative.roots().real), [1.0]])
    w_lobatto = 2.0 / (_ORDER * (_ORDER - 1) * legendre.legval(lobatto, np.eye(_ORDER)[-1]) ** 2)
    x, w = legendre.leggauss(3 * _ORDER)  # exact for ω P_j P_k, j, k < m
    basis = legendre.legvander(x, _ORDER - 1)
    gram = (basis * (w * (1 - x * x) * derivative(x))[:, None]).T @ basis
    e = np.zeros(_ORDER)
    e[-1] = 1.0
    e[:-1] = np.linalg.solve(gram[:-1, :-1], -gram[:-1, -1])
    kronrod = np.sort(legendre.legroots(e).real)
    nodes = np.concatenate([lobatto, kronrod])
    moments = np.zeros(nodes.size)
    moments[0] = 2.0
    w_value = np.linalg.solve(legendre.legvander(nodes, nodes.size - 1).T, moments)
    weights = np.zeros((nodes.size, 2))
    weights[:, 0] = -w_value / 2
    weights[:_ORDER, 0] += w_lobatto / 2
    weights[:, 1] = w_value / 2
    nodes = (nodes + 1) / 2
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


@cache
def _unit_levels(
    size: int,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The fixed levels on [0, 1] for p with `size` Taylor coefficients: the derivative
    powers (size, K·(2m−1)) at the first level's nodes (p's coefficients times them are p'
    there), the weights scaled to its width 1/K and K ones (to add up the pieces' sums with
    .dot, cheaper than .sum(axis=0)); then the derivative powers (K, size, S·(2m−1)) at the
    nodes of the S parts of each first-level piece, and the weights scaled to 1/(K·S)."""
    nodes, weights = _pair()
    first = ((np.arange(_PIECES)[:, None] + nodes) / _PIECES).ravel()
    parts = (np.arange(_SPLIT)[:, None] + nodes).ravel() / _SPLIT
    second = (np.arange(_PIECES)[:, None] + parts) / _PIECES
    out = (
        _derivative_powers(first - 0.5, size),
        weights / _PIECES,
        np.ones(_PIECES),
        np.stack([_derivative_powers(row - 0.5, size) for row in second]),
        weights / (_PIECES * _SPLIT),
    )
    for arr in out:
        arr.setflags(write=False)
    return out


def scaled(coeffs: np.ndarray) -> tuple[np.ndarray, float]:
    """(coeffs / f, f), f a power of two such that the squares of p' neither overflow nor
    underflow (1.0 for ordinary coordinates; lengths scale by f)."""
    out, factor, _ = _scaled(coeffs)
    return out, factor


def _scaled(coeffs: np.ndarray) -> tuple[np.ndarray, float, float]:
    """scaled's (coeffs / f, f), and the largest |coefficient| of p/f but its constant term."""
    # (not the constant term: a far translation does not matter); a Python max over these
    # few numbers is cheaper than numpy's
    terms = coeffs.ravel().tolist()
    del terms[:: coeffs.shape[1]]
    peak = max(map(abs, terms), default=0.0)
    if peak == 0.0 or 2.0**-400 <= peak <= 2.0**400:
        return coeffs, 1.0, peak
    factor = math.ldexp(1.0, math.frexp(peak)[1])
    return coeffs / factor, factor, peak / factor


@cache
def _hidden_weights(size: int) -> tuple[float, np.ndarray]:
    """For p with `size` Taylor coefficients about 1/2: (h, w) with w · |coefficients| summed
    over the coordinates a bound B on |p‴|/2 over [0, 1] (the term of degree e: e(e−1)(e−2)/2
    · 2^-(e−3)), and h such that a piece of width W whose least speed at the nodes exceeds
    h · W² · B hides no near-double zero of p' between them (the module's note on hidden
    dips): h = 2 (2g)², g the widest gap between nodes, relative to the width, halved."""
    nodes, _ = _pair()
    gap = float(np.diff(np.sort(nodes)).max()) / 2
    e = np.arange(size, dtype=float)
    w = np.where(e >= 3, e * (e - 1) * (e - 2) / 2 * 0.5 ** np.maximum(e - 3, 0), 0.0)
    w.setflags(write=False)
    return 8 * gap * gap, w


def _hidden_bound(coeffs: np.ndarray) -> float:
    """B of _hidden_weights for these coefficients (the sum over coordinates)."""
    factor, w = _hidden_weights(coeffs.shape[1])
    return factor * float(np.abs(coeffs).dot(w).sum())


def _norms(values: np.ndarray) -> np.ndarray:
    """|p'| from p' values (d, n) or (P, d, n), overwriting them: (n,) or (P, n). (p' itself,
    not |p'|² as one polynomial: that would save a ufunc or two, but its rounding, about
    1e-16 of C² (C the size of p' on [0, 1]), swamps the speed near a zero of p' of order
    k over a width of about 1e-16^(1/2k); measured 1.7e-10 of the length at a flat end with
    p' ~ (1 − t)³.)"""
    np.multiply(values, values, out=values)
    if values.ndim == 2:
        total = values[0]
        for c in range(1, values.shape[0]):  # d − 1 additions beat a reduction over d
            total += values[c]
    else:
        total = values.sum(axis=1)
    out: np.ndarray = np.sqrt(total, out=total)
    return out


def speeds(coeffs: np.ndarray, t: np.ndarray) -> np.ndarray:
    """|p'(t)| at every t (any shape), for coefficients from `scaled`."""
    powers = _derivative_powers(t.ravel() - 0.5, coeffs.shape[1])
    return _norms(np.dot(coeffs, powers)).reshape(t.shape)


def _sums(coeffs: np.ndarray, left: np.ndarray, width: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(P, 2): (test − value, value) on each [left_i, left_i + width_i]; and (P,) the least
    speed at each piece's nodes."""
    nodes, weights = _pair()
    speed = speeds(coeffs, left[:, None] + width[:, None] * nodes)
    sums: np.ndarray = np.dot(speed, weights) * width[:, None]
    return sums, speed.min(axis=1)


def partial(coeffs: np.ndarray, start: np.ndarray, end: np.ndarray) -> np.ndarray:
    """The value rule for ∫|p'| over each [start_i, end_i] (vectorised), for coefficients
    from `scaled`."""
    nodes, weights = _pair()
    width = end - start
    speed = speeds(coeffs, start[:, None] + width[:, None] * nodes)
    out: np.ndarray = np.dot(speed, weights[:, 1]) * width
    return out


def unit_integral(coeffs: np.ndarray, rtol: float) -> float:
    """∫_0^1 |p'| to a relative accuracy rtol (coefficients of any size). The first level
    and the refinement of its rejected pieces use the fixed nodes; what still fails goes
    on in _finish. (Every product here stays single-threaded in OpenBLAS, which is what
    makes these products cheap: a plane curve's p' as one complex matrix-vector product,
    x + iy, with |p'| from np.abs, measured 2 us faster on an idle machine, but OpenBLAS
    runs a complex product of 4096 entries or more on two threads, which with the other
    core busy doubled its time and once stretched a benchmark run of 100 curves to 0.8 s;
    cut into single-threaded blocks it was no faster than this.)"""
    first, weights, ones, second, second_weights = _unit_levels(coeffs.shape[1])
    unit = _hidden_unit(coeffs.shape[1])
    compiled = kernels.compiled()
    factor, code = 1.0, 1
    if compiled is not None:  # the level and the decisions below in one compiled call
        size = np.empty((_PIECES, 2))
        code, spent, total, least, peak = compiled.unit_first_level(
            coeffs, first, weights, _PIECES, rtol, unit, size
        )
        if code == 0:  # most curves: decided at once (the same tests as below)
            return float(total)
    if code == 1:  # numpy, or coefficients to scale first
        coeffs, factor, peak = _scaled(coeffs)
        if compiled is not None:  # (kernels_compiled.first_level: the same level)
            spent, total, least = compiled.first_level(coeffs, first, weights, _PIECES, size)
        else:
            # (the .dot method: a little cheaper than np.dot, which is cheaper than @, on
            # operands this small)
            speed = _norms(coeffs.dot(first))
            sums = speed.reshape(_PIECES, -1).dot(weights)
            size = np.abs(sums)
            spent, total = ones.dot(size).tolist()
            least = speed.min()
    # a cheap bound on _hidden_bound (the coordinates' count times the largest coefficient)
    hidden = unit * float(coeffs.shape[0]) * peak
    if not total > 0.0:  # a constant curve
        return 0.0
    if least <= hidden / _PIECES**2:  # a near-double zero of p' may hide: the full rule
        return factor * _from_start(coeffs, 0.0, 1.0, rtol, None)
    if spent <= rtol * total:  # most curves: accepted at once
        return float(factor * total)
    bad = (size[:, 0] > rtol * total / _PIECES).nonzero()[0]
    for rejected, value in size[bad].tolist():
        spent -= rejected
        total -= value
    if compiled is not None:  # the same steps in one compiled call (kernels_compiled)
        sums = np.empty((bad.size * _SPLIT, 2))
        low = np.empty(bad.size * _SPLIT)
        new_spent, new_total, least = compiled.second_level(
            coeffs, second, second_weights, bad, sums, low
        )
    else:
        # one piece as a rule, or two (a near-cusp by a joint): a product each (cheaper
        # than one batched product of a fancy-indexed stack)
        if bad.size == 1:
            values = coeffs.dot(second[bad[0]])
        else:
            values = np.concatenate([coeffs.dot(second[k]) for k in bad], axis=-1)
        speed = _norms(values)
        least = speed.min()
        sums = speed.reshape(bad.size * _SPLIT, -1).dot(second_weights)
        new_spent, new_total = np.abs(sums).sum(axis=0).tolist()
        low = speed.reshape(bad.size * _SPLIT, -1).min(axis=1)
    if least <= hidden / (_PIECES * _SPLIT) ** 2:
        return factor * _from_start(coeffs, 0.0, 1.0, rtol, None)
    if spent + new_spent <= rtol * (total + new_total):
        return float(factor * (total + new_total))
    width = 1.0 / (_PIECES * _SPLIT)
    left = ((bad[:, None] * _SPLIT + np.arange(_SPLIT)) * width).ravel()
    widths = np.full(left.size, width)
    level = (left, widths, sums, low)
    return factor * _finish(coeffs, 0.0, 1.0, rtol, level, total, spent, None)


@cache
def _hidden_unit(size: int) -> float:
    """_hidden_weights' h times the sum of its w: h · B <= (coordinates) · (largest
    |coefficient|) · this."""
    factor, w = _hidden_weights(size)
    return factor * float(w.sum())


def _from_start(
    coeffs: np.ndarray,
    a: float,
    b: float,
    rtol: float,
    parts: list[tuple[np.ndarray, np.ndarray]] | None,
) -> float:
    """The adaptive rule on [a, b] from its first level (coefficients from `scaled`)."""
    width = np.full(_PIECES, (b - a) / _PIECES)
    left = a + width * np.arange(_PIECES)
    sums, low = _sums(coeffs, left, width)
    return _finish(coeffs, a, b, rtol, (left, width, sums, low), 0.0, 0.0, parts)


def integral(coeffs: np.ndarray, a: float, b: float, rtol: float) -> float:
    """∫_a^b |p'| to a relative accuracy rtol (coefficients of any size)."""
    coeffs, factor = scaled(coeffs)
    return factor * _from_start(coeffs, a, b, rtol, None)


def table(coeffs: np.ndarray, rtol: float) -> tuple[np.ndarray, np.ndarray]:
    """The accepted pieces of [0, 1]: sorted edges (K+1,) and cumulative lengths (K+1,)
    (coefficients of any size)."""
    coeffs, factor = scaled(coeffs)
    parts: list[tuple[np.ndarray, np.ndarray]] = []
    total = _from_start(coeffs, 0.0, 1.0, rtol, parts)
    lefts = np.concatenate([p[0] for p in parts])
    values = np.concatenate([p[1] for p in parts])
    order = np.argsort(lefts, kind="stable")
    edges = np.append(lefts[order], 1.0)  # the accepted pieces tile [0, 1]
    cum = np.concatenate([[0.0], np.cumsum(values[order])])
    cum[-1] = total
    return edges, cum * factor


def _finish(
    coeffs: np.ndarray,
    a: float,
    b: float,
    rtol: float,
    level: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray],
    accepted: float,
    spent: float,
    parts: list[tuple[np.ndarray, np.ndarray]] | None,
) -> float:
    """The adaptive rule from a level of pieces (left ends, widths, sums, least speeds at
    their nodes), given the value and the error estimate of the pieces accepted before it:
    rejected pieces of the first level are cut in _SPLIT, then the rejected ones once by
    the zeros of q (_partition), then halved while they fail. Before that partition, a
    piece that passes but may hide a near-double zero of p' (its least speed within
    _hidden_bound · width²) is partitioned too if a zero of q lies in it or by it
    (_hiding). Returns the total; `parts` (if given) collects the accepted pieces' left
    ends and values."""
    left, width, sums, low = level
    span = b - a
    stage = 0 if width[0] * _PIECES >= span * (1 - 1e-9) else 1  # (first-level pieces: 0)
    # C, the size of p' on [0, 1] (Σ |e · coeffs[:, e]| 2^-(e−1)), and from it the rounding
    # of a difference of the rules per unit width (see the module's note on rounding)
    e = np.arange(1.0, coeffs.shape[1])
    noise = _NOISE * float((np.abs(coeffs[:, 1:]) * (e * 0.5 ** (e - 1))).sum())
    hidden = _hidden_bound(coeffs)
    zeros: list[complex] | None = None
    while True:
        # a difference within rounding is accepted only from pieces the zeros of q have cut
        # (stage 2 on), where it cannot be truncation; before that it could be (a curve
        # with coefficients large against its length has a large rounding allowance)
        allowance = noise if stage >= 2 else 0.0
        size = np.abs(sums)
        level_spent, level_total = size.sum(axis=0).tolist()
        total = accepted + level_total
        if left.size > _MAX_PIECES or not total > 0:
            if parts is not None:
                parts.append((left, sums[:, 1]))
            return float(total)
        if spent + level_spent <= max(rtol * total, allowance * span):
            passed = np.ones(left.size, dtype=bool)
        else:
            passed = size[:, 0] <= np.maximum(rtol * total / span, allowance) * width
        hiding = np.zeros(left.size, dtype=bool)
        if stage < 2:  # (later pieces come from _partition, which leaves none hiding)
            suspect = passed & (low <= hidden * width * width)
            if suspect.any():
                if zeros is None:
                    zeros = _zeros(coeffs)
                hiding[suspect] = _hiding(zeros, left[suspect], width[suspect])
        ok = passed & ~hiding
        if ok.all():
            if parts is not None:
                parts.append((left, sums[:, 1]))
            return float(total)
        accepted += float(size[ok, 1].sum())
        spent += float(size[ok, 0].sum())
        if parts is not None:
            parts.append((left[ok], sums[ok, 1]))
        failed = ~passed
        hide_left, hide_width = left[hiding], width[hiding]
        left, width = left[failed], width[failed]
        if stage == 0:  # as the fixed second level: wide pieces are cut in _SPLIT, blindly
            width = np.repeat(width / _SPLIT, _SPLIT)
            left = (left[:, None] + width.reshape(-1, _SPLIT) * np.arange(_SPLIT)).ravel()
        elif stage == 1:
            left, width = np.append(left, hide_left), np.append(width, hide_width)
            hide_left = hide_width = left[:0]
            left, width = _partition(coeffs, left, width)
        else:
            left = np.concatenate([left, left + width / 2])
            width = np.concatenate([width, width]) / 2
        if hide_left.size:
            hide_left, hide_width = _partition(coeffs, hide_left, hide_width)
            left, width = np.append(left, hide_left), np.append(width, hide_width)
        stage += 1
        sums, low = _sums(coeffs, left, width)


def _hiding(zeros: list[complex], left: np.ndarray, width: np.ndarray) -> np.ndarray:
    """Which pieces [left_i, left_i + width_i] have a zero x + iy of q nearer than half
    their width (one with y < _SNAP, a double real zero: strictly inside), where a near-
    double zero of p' may hide between the nodes; _partition leaves none such."""
    out = np.zeros(left.size, dtype=bool)
    right = left + width
    for z in zeros:
        x, y = z.real, abs(z.imag)
        if y < _SNAP:
            out |= (left < x) & (x < right)
        else:
            outside = np.maximum(np.maximum(left - x, x - right), 0.0)
            out |= np.hypot(outside, y) < width / 2
    return out


def _zeros(coeffs: np.ndarray) -> list[complex]:
    """The zeros t of q = |p'|² with Im t >= 0 (the others are their conjugates):
    eigenvalues of the companion matrix of q's Taylor coefficients. In the plane, q = P·P̄
    for P = p'_x + i p'_y, and P's zeros (with the conjugates of those below the axis) are
    those of q: a near-double zero of p' is a double zero of P but a fourfold one of q, and
    is computed from P to about 1e-8, against 1e-4 from q."""
    if coeffs.shape[0] == 2:
        power = np.arange(coeffs.shape[1])
        slope = ((coeffs[0] + 1j * coeffs[1]) * power)[1:].tolist()
        while slope and slope[-1] == 0:
            slope.pop()
        if len(slope) < 2:
            return []
        roots = np.polynomial.polynomial.polyroots(slope).tolist()
        return [complex(u.real + 0.5, abs(u.imag)) for u in roots]
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
