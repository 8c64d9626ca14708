r"""The certified global minimum of E_k(α) over the parameter range of a C-Bézier family
(issue #30): a family whose parameter is the length of the domain, or sits inside sin/cos.

For a given polygon P, E_k(α) = Σ_ij (P_i · P_j) G_ij(α), and each Gram entry of the derived
document is N(α, sin α, cos α) / D(α, sin α, cos α) (sinh, cosh for the hyperbolic space)
with rational coefficients. Entries with the same denominator are summed first, so E_k is a
short sum Σ_g N_g / D_g with exact rational numerators (the points are read as the exact
binary rationals their floats are).

Enclosures are Taylor models in h = α − c on a box |h| <= r: a polynomial of degree K in h
whose coefficients are rational intervals (rounded outwards to 2^-BITS when they grow), and
a remainder |h|^(K+1) · [−R, R]. sin(c + h) = sin c cos h + cos c sin h with sin c, cos c
enclosed by their Taylor series and Lagrange's bound, cos h and sin h by their Taylor
polynomials with the remainder |h|^(K+1)/(K+1)! (times cosh r for cosh and sinh). Products
move the terms past K into the remainder; 1/D is the geometric series of D's variable part
over its constant, with the tail bounded (it needs that part < 1/2 of the constant: else the
box is split). At α → 0, where the denominators vanish (α − sin α ~ α³/6), the box (0, r]
is expanded about 0 itself, where sin 0 and cos 0 are exact: the Taylor coefficients are
exact rationals, so the orders of vanishing of N_g and D_g are read exactly, h^m is divided
out of both, and E_k = h^e F(h) with F a Taylor model: E_k ≥ r^e min F on (0, r] when e < 0
and min F > 0 (E_k → ∞ at the open end), E_k → F(0) when e = 0 (then the infimum may be that
limit, not attained).

Branch and bound splits the box of least lower bound; a lower bound uses the model's
quadratic part exactly, and each box proposes the minimiser of its quadratic part as a
candidate point, where E_k is enclosed (a model with r = 0). It stops when the least value
found is within TOLERANCE (relative to max(1, E)) of the least lower bound over every box:
the minimum is certified, not exact (E_k at the point is an enclosure of width ~2^-200).
"""

from __future__ import annotations

import heapq
import math
import re
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

BITS = 256
TOLERANCE = Fraction(1, 10**12)
BUDGET = 4000  # boxes split before the search says it is not certified
ORDER = 6  # Taylor order on a box away from 0
ORDER_AT_ZERO = 22  # about 0: past the denominators' orders of vanishing (alpha**14 at most)
Interval = tuple[int, int]  # [lo, hi] / 2^BITS
Poly = dict[tuple[int, int, int], Fraction]
SCALE = 1 << BITS
_Z: Interval = (0, 0)
_NONE = -(1 << 2000)  # a lower bound that proves nothing


def _floor(x: Fraction) -> int:
    return (x.numerator << BITS) // x.denominator


def _ceil(x: Fraction) -> int:
    return -((-x.numerator << BITS) // x.denominator)


def _point(x: Fraction) -> Interval:
    return (_floor(x), _ceil(x))


def _mulf(a: int, b: int) -> int:  # floor(a b / S)
    return (a * b) >> BITS


def _mulc(a: int, b: int) -> int:  # ceil(a b / S)
    return -((-a * b) >> BITS)


def _imul(a: Interval, b: Interval) -> Interval:
    if a[0] == a[1] and b[0] == b[1]:
        p = a[0] * b[0]
        return (p >> BITS, -((-p) >> BITS))
    ps = (a[0] * b[0], a[0] * b[1], a[1] * b[0], a[1] * b[1])
    return (min(ps) >> BITS, -((-max(ps)) >> BITS))


def _mag(a: Interval) -> int:
    return max(-a[0], a[1])


class Model:
    """f(h) ∈ Σ_j c_j h^j + |h|^(K+1) [−rem, rem] for |h| <= r: the coefficients are
    intervals of integers over 2^BITS, rounded outwards, and rem, r are upper bounds."""

    __slots__ = ("c", "rem", "rp")

    def __init__(self, c: list[Interval], rem: int, rp: list[int]) -> None:
        self.c, self.rem, self.rp = c, rem, rp  # rp[j] >= r^j (scaled), j = 0..2K+2

    @staticmethod
    def powers(r: int, order: int) -> list[int]:
        out = [SCALE]
        for _ in range(2 * order + 2):
            out.append(_mulc(out[-1], r))
        return out

    @property
    def order(self) -> int:
        return len(self.c) - 1

    def constant(self, x: Interval) -> Model:
        return Model([x] + [_Z] * self.order, 0, self.rp)

    def bound(self) -> int:
        """max |polynomial part| over |h| <= r."""
        rp = self.rp
        return sum(_mulc(_mag(a), rp[j]) for j, a in enumerate(self.c))

    def add(self, other: Model) -> Model:
        c = [(a[0] + b[0], a[1] + b[1]) for a, b in zip(self.c, other.c, strict=True)]
        return Model(c, self.rem + other.rem, self.rp)

    def scale(self, q: Interval) -> Model:
        return Model([_imul(a, q) for a in self.c], _mulc(self.rem, _mag(q)), self.rp)

    def mul(self, other: Model) -> Model:
        k, rp = self.order, self.rp
        lo = [0] * (2 * k + 1)
        hi = [0] * (2 * k + 1)
        for i, a in enumerate(self.c):
            if a == _Z:
                continue
            for j, b in enumerate(other.c):
                if b == _Z:
                    continue
                p = _imul(a, b)
                lo[i + j] += p[0]
                hi[i + j] += p[1]
        rem = 0
        for j in range(k + 1, 2 * k + 1):  # h^j = h^(k+1) h^(j-k-1), |h| <= r
            rem += _mulc(max(-lo[j], hi[j]), rp[j - k - 1])
        if self.rem:
            rem += _mulc(self.rem, other.bound())
        if other.rem:
            rem += _mulc(other.rem, self.bound()) + _mulc(_mulc(self.rem, other.rem), rp[k + 1])
        return Model(list(zip(lo[: k + 1], hi[: k + 1], strict=True)), rem, rp)

    def enclosure(self) -> Interval:
        """The range over |h| <= r."""
        rest = self.bound() - _mag(self.c[0]) + _mulc(self.rem, self.rp[self.order + 1])
        return (self.c[0][0] - rest, self.c[0][1] + rest)

    def reciprocal(self) -> Model | None:
        """1/f, or None when the constant term does not dominate (the box is too wide)."""
        d0 = self.c[0]
        if d0[0] <= 0 <= d0[1]:
            return None
        inv = ((SCALE * SCALE) // d0[1], -((-SCALE * SCALE) // d0[0]))
        u = Model([_Z, *self.c[1:]], self.rem, self.rp).scale(inv)
        k, rp = self.order, self.rp
        # |u(h)| <= |h| beta1 for |h| <= r (u has no constant term)
        beta1 = sum(_mulc(_mag(a), rp[j]) for j, a in enumerate(u.c[1:])) + _mulc(u.rem, rp[k])
        beta = _mulc(beta1, rp[1])
        if 2 * beta > SCALE:
            return None
        one = self.constant((SCALE, SCALE))
        neg_u = u.scale((-SCALE, -SCALE))
        s = one
        for _ in range(k):  # 1 - u + u^2 - ... (k + 1 terms), Horner's rule
            s = one.add(neg_u.mul(s))
        # the tail Σ_{i>k} |u|^i <= |h|^(k+1) beta1^(k+1) / (1 - beta), times |1/d0|
        tail = Fraction(_mag(inv), SCALE) * Fraction(beta1, SCALE) ** (k + 1)
        tail /= 1 - Fraction(beta, SCALE)
        out = s.scale(inv)
        return Model(out.c, out.rem + _ceil(tail), self.rp)

    def truncate(self, order: int) -> Model:
        """The same function as a model of a lower order."""
        k, rp = self.order, self.rp
        rem = _mulc(self.rem, rp[k - order])
        for j in range(order + 1, k + 1):
            rem += _mulc(_mag(self.c[j]), rp[j - order - 1])
        return Model(self.c[: order + 1], rem, rp)

    def shifted(self, m: int) -> Model:
        """f / h^m for a model whose first m coefficients are proven 0 (their intervals,
        rounded, are dropped)."""
        return Model(self.c[m:], self.rem, self.rp)

    def times_h(self) -> Model:
        """h f, of the same order."""
        k, rp = self.order, self.rp
        top = self.c[k]
        rem = _mag(top) + _mulc(self.rem, rp[1])
        return Model([_Z, *self.c[:k]], rem, rp)


# --------------------------------------------------------------------------- sin and cos


def _exp_bound(x: Fraction) -> Fraction:
    """A rational upper bound of e^|x| (e < 3)."""
    return Fraction(3) ** (math.floor(abs(x)) + 1)


def trig_at(c: Fraction, hyperbolic: bool) -> tuple[Interval, Interval]:
    """Enclosures of (sin c, cos c), or (sinh c, cosh c), by the Taylor series and
    Lagrange's remainder |c|^M/M! (times e^|c| for the hyperbolic ones)."""
    if c == 0:
        return _Z, (SCALE, SCALE)
    s, co = Fraction(0), Fraction(0)
    term = Fraction(1)  # c^m / m!, rounded once its denominator is past 2^BITS
    m = 0
    limit = Fraction(1, 1 << (BITS + 16))
    while True:
        if m % 2 == 0:
            co += term if hyperbolic or m % 4 == 0 else -term
        else:
            s += term if hyperbolic or m % 4 == 1 else -term
        m += 1
        term = term * c / m
        if term.denominator > SCALE:
            term = Fraction(_floor(term), SCALE)
        if m > 2 * abs(c) + 2 and abs(term) < limit:
            break
    # each rounded term is off by < 2^-BITS, carried into the later terms with factors whose
    # products are below e^|c|; the Lagrange remainder is |c|^m/m! (times e^|c|)
    grow = _exp_bound(c)
    err = Fraction(m + 2, SCALE) * grow + (abs(term) + Fraction(m + 2, SCALE) * grow) * grow
    return (_floor(s - err), _ceil(s + err)), (_floor(co - err), _ceil(co + err))


def _series(kind: str, rp: list[int], order: int, r: Fraction, hyperbolic: bool) -> Model:
    """cos h or sin h (cosh, sinh) as a model of `order` on |h| <= r."""
    c: list[Interval] = []
    for j in range(order + 1):
        if (kind == "cos") == (j % 2 == 0):
            v = Fraction(1, math.factorial(j))
            if not hyperbolic and (j // 2) % 2 == 1:
                v = -v
            c.append(_point(v))
        else:
            c.append(_Z)
    rem = Fraction(1, math.factorial(order + 1)) * (_exp_bound(r) if hyperbolic else 1)
    return Model(c, _ceil(rem), rp)


def exact_series(poly: Poly, order: int, hyperbolic: bool) -> list[Fraction]:
    """The Taylor coefficients at α = 0 of N(α, sin α, cos α), exactly (sin 0 = 0, cos 0 = 1)."""
    sin = [Fraction(0)] * (order + 1)
    cos = [Fraction(0)] * (order + 1)
    for j in range(order + 1):
        v = Fraction(1, math.factorial(j))
        sign = 1 if hyperbolic or (j // 2) % 2 == 0 else -1
        (cos if j % 2 == 0 else sin)[j] = sign * v
    alpha = [Fraction(0), Fraction(1)] + [Fraction(0)] * (order - 1)

    def mul(a: list[Fraction], b: list[Fraction]) -> list[Fraction]:
        out = [Fraction(0)] * (order + 1)
        for i, x in enumerate(a):
            if x:
                for j in range(order + 1 - i):
                    if b[j]:
                        out[i + j] += x * b[j]
        return out

    one = [Fraction(1)] + [Fraction(0)] * order
    cache: dict[tuple[int, int], list[Fraction]] = {}

    def power(which: int, k: int) -> list[Fraction]:
        if (which, k) not in cache:
            base = (alpha, sin, cos)[which]
            cache[(which, k)] = one if k == 0 else mul(power(which, k - 1), base)
        return cache[(which, k)]

    total = [Fraction(0)] * (order + 1)
    for (i, j, k), v in poly.items():
        term = mul(mul(power(0, i), power(1, j)), power(2, k))
        total = [t + v * x for t, x in zip(total, term, strict=True)]
    return total


# --------------------------------------------------------------------------- the energy


@dataclass
class Energy:
    """E_k(α) = α^extra Σ_g N_g(α, S, C) / D_g(α, S, C) for one polygon."""

    groups: tuple[tuple[Poly, Poly], ...]
    hyperbolic: bool
    extra: int  # 2k - 1 for a family on [0, 1] (E in u = t/alpha), else 0
    orders_at_zero: list[tuple[int, int]] | None = None  # exact orders of vanishing of N_g, D_g


def energy_of(
    entries: list[list[tuple[Poly, Poly]]],
    rows: list[tuple[Fraction, ...]],
    hyperbolic: bool,
    extra: int,
) -> Energy:
    """Σ_ij (P_i · P_j) N_ij / D_ij grouped by denominator (`entries` holds, per Gram entry,
    (num, den) as {(i, j, k): Fraction}, the exponents of α, S, C)."""
    groups: dict[tuple[tuple[tuple[int, int, int], Fraction], ...], Poly] = {}
    dens: dict[tuple[tuple[tuple[int, int, int], Fraction], ...], Poly] = {}
    for i, row in enumerate(entries):
        for j, (num, den) in enumerate(row):
            w = sum((a * b for a, b in zip(rows[i], rows[j], strict=True)), Fraction(0))
            if not w or not num:
                continue
            key = tuple(sorted(den.items()))
            acc = groups.setdefault(key, {})
            dens[key] = den
            for mono, v in num.items():
                acc[mono] = acc.get(mono, Fraction(0)) + w * v
    out = []
    for key, num in groups.items():
        kept = {m: v for m, v in num.items() if v}
        if kept:
            out.append((kept, dens[key]))
    return Energy(tuple(out), hyperbolic, extra)


def _alpha_model(c: Fraction, rp: list[int], order: int) -> Model:
    return Model([_point(c), (SCALE, SCALE)] + [_Z] * (order - 1), 0, rp)


def _monomials(
    e: Energy, c: Fraction, r: Fraction, order: int
) -> dict[tuple[int, int, int], Model]:
    rp = Model.powers(_ceil(r), order)
    sc, cc = trig_at(c, e.hyperbolic)
    cos_h = _series("cos", rp, order, r, e.hyperbolic)
    sin_h = _series("sin", rp, order, r, e.hyperbolic)
    if e.hyperbolic:  # sinh(c+h) = sinh c cosh h + cosh c sinh h; cosh likewise
        s_m = cos_h.scale(sc).add(sin_h.scale(cc))
        c_m = cos_h.scale(cc).add(sin_h.scale(sc))
    else:  # sin(c+h) = sin c cos h + cos c sin h; cos(c+h) = cos c cos h - sin c sin h
        s_m = cos_h.scale(sc).add(sin_h.scale(cc))
        c_m = cos_h.scale(cc).add(sin_h.scale((-sc[1], -sc[0])))
    a_m = _alpha_model(c, rp, order)
    one = a_m.constant((SCALE, SCALE))
    needed = {m for g in e.groups for part in g for m in part}
    cache: dict[tuple[int, int], Model] = {}

    def power(which: int, k: int) -> Model:
        if (which, k) not in cache:
            base = (a_m, s_m, c_m)[which]
            cache[(which, k)] = one if k == 0 else power(which, k - 1).mul(base)
        return cache[(which, k)]

    out = {}
    for i, j, k in needed:
        term = power(0, i)
        if j:
            term = term.mul(power(1, j))
        if k:
            term = term.mul(power(2, k))
        out[(i, j, k)] = term
    return out


def _combine(poly: Poly, monos: dict[tuple[int, int, int], Model]) -> Model:
    first = next(iter(monos.values()))
    total = first.constant(_Z)
    for m, v in poly.items():
        total = total.add(monos[m].scale(_point(v)))
    return total


def model_at(e: Energy, c: Fraction, r: Fraction, order: int = ORDER) -> Model | None:
    """E_k on |α - c| <= r (c > r >= 0: away from 0), or None when a denominator's constant
    part does not dominate there."""
    monos = _monomials(e, c, r, order)
    total: Model | None = None
    for num, den in e.groups:
        inv = _combine(den, monos).reciprocal()
        if inv is None:
            return None
        part = _combine(num, monos).mul(inv)
        total = part if total is None else total.add(part)
    if total is None:
        return None
    for _ in range(e.extra):
        total = total.mul(_alpha_model(c, total.rp, order))
    return total


def value_at(e: Energy, x: Fraction) -> Interval | None:
    """An enclosure of E_k(x)."""
    m = model_at(e, x, Fraction(0), 1)
    return None if m is None else m.enclosure()


@dataclass(frozen=True)
class AtZero:
    """E_k = h^power F(h) on (0, r]."""

    power: int
    f: Model


def _first_nonzero(series: list[Fraction]) -> int | None:
    return next((j for j, v in enumerate(series) if v), None)


def model_at_zero(e: Energy, r: Fraction) -> AtZero | None:
    """E_k on (0, r] about α = 0, with the orders of vanishing read exactly."""
    order = ORDER_AT_ZERO
    if e.orders_at_zero is None:
        orders = []
        for num, den in e.groups:
            vn = _first_nonzero(exact_series(num, order, e.hyperbolic))
            vd = _first_nonzero(exact_series(den, order, e.hyperbolic))
            if vn is None or vd is None or order - max(vn, vd) < 2:
                return None  # pragma: no cover - a vanishing past ORDER_AT_ZERO
            orders.append((vn, vd))
        e.orders_at_zero = orders
    monos = _monomials(e, Fraction(0), r, order)
    parts = []
    for (num, den), (vn, vd) in zip(e.groups, e.orders_at_zero, strict=True):
        low = order - max(vn, vd)
        n_s = _combine(num, monos).shifted(vn).truncate(low)
        d_s = _combine(den, monos).shifted(vd).truncate(low)
        inv = d_s.reciprocal()
        if inv is None:
            return None
        parts.append((vn - vd + e.extra, n_s.mul(inv)))
    low = min(p.order for _, p in parts)
    least = min(v for v, _ in parts)
    total: Model | None = None
    for v, p in parts:
        p = p.truncate(low)
        for _ in range(v - least):
            p = p.times_h()
        total = p if total is None else total.add(p)
    assert total is not None
    return AtZero(least, total)


# --------------------------------------------------------------------------- the search


_PI = re.compile(r"^\s*(?:(\d+)\s*\*\s*)?pi(?:\s*/\s*(\d+))?\s*$")


def end_bounds(text: str) -> tuple[Fraction, Fraction]:
    """Rationals lo <= x <= hi around an end of the range written as a rational or as
    a rational multiple of pi (p*pi/q)."""
    from .hazmat.constants import constant_bounds

    match = _PI.match(text)
    if match is None:
        x = Fraction(text)
        return x, x
    p = Fraction(int(match.group(1) or 1), int(match.group(2) or 1))
    lo, hi = constant_bounds("pi", 96)
    return _dyadic(lo * p, 100, -1), _dyadic(hi * p, 100, 1)


def _dyadic(x: Fraction, bits: int = 64, direction: int = 0) -> Fraction:
    scaled = x * (1 << bits)
    n = (
        math.floor(scaled)
        if direction < 0
        else math.ceil(scaled)
        if direction > 0
        else round(scaled)
    )
    return Fraction(n, 1 << bits)


def _quadratic_lower(m: Model, r: Fraction) -> tuple[int, Fraction]:
    """(a lower bound of m over |h| <= r using its quadratic part exactly, the h where that
    quadratic part is least)."""
    rp = m.rp
    c0 = m.c[0][0]
    e1 = m.c[1] if m.order >= 1 else _Z
    e2 = m.c[2] if m.order >= 2 else _Z
    mid1 = Fraction(e1[0] + e1[1], 2 * SCALE)
    rad1 = (e1[1] - e1[0] + 1) // 2 + 1
    q = Fraction(e2[0], SCALE)
    if q > 0:
        h = min(max(-mid1 / (2 * q), -r), r)
        quad = _floor(mid1 * h + q * h * h)
    else:
        h = -r if mid1 > 0 else r
        quad = _floor(-abs(mid1) * r + q * r * r)
    rest = sum(_mulc(_mag(a), rp[j + 3]) for j, a in enumerate(m.c[3:]))
    rest += _mulc(m.rem, rp[m.order + 1]) + _mulc(rad1, rp[1])
    return c0 + quad - rest, h


def _range_on(m: Model, a: Fraction, b: Fraction) -> tuple[Fraction, Fraction]:
    """The range of m over h in [a, b] (0 <= a < b, |h| <= the model's r), by Horner's rule
    in interval arithmetic, with the remainder |h|^(K+1) rem <= b^(K+1) rem."""
    lo, hi = Fraction(0), Fraction(0)
    for c in reversed(m.c):
        ps = (lo * a, lo * b, hi * a, hi * b)
        lo, hi = _dyadic(min(ps), BITS, -1), _dyadic(max(ps), BITS, 1)
        lo, hi = lo + Fraction(c[0], SCALE), hi + Fraction(c[1], SCALE)
    tail = Fraction(m.rem, SCALE) * b ** (m.order + 1)
    return lo - tail, hi + tail


@dataclass
class _Box:
    a: Fraction
    b: Fraction
    lower: int
    kind: str = "regular"  # or "zero" (0, b], "near": bounded by the expansion about 0


def certified_minimum(
    e: Energy, lo_text: str, hi_text: str, lo_closed: bool, hi_closed: bool
) -> dict[str, Any]:
    """The least E_k over the range: {"point" (a Fraction inside the range, or the open end
    0 when the infimum is the limit there), "value" (an enclosure (lo, hi) of E_k there,
    Fractions), "lower" (a proven lower bound of E_k over the range), "certified", "limit"
    (the point is an open end: the infimum, not attained), "boxes"}."""
    lo_cov, lo_in = end_bounds(lo_text)
    hi_in, hi_cov = end_bounds(hi_text)
    lo_open_point = lo_cov == lo_in and not lo_closed  # a rational open end: not attained
    hi_open_point = hi_cov == hi_in and not hi_closed
    best: list[Any] = [None, None, None, False]  # upper value, point, enclosure, limit

    def offer(x: Fraction) -> None:
        x = min(max(x, lo_in), hi_in)
        y = _dyadic(x)  # a short rational inside (an end stays as it is)
        x = y if lo_in < x < hi_in and lo_in <= y <= hi_in else x
        if x <= 0:
            return
        got = value_at(e, x)
        if got is not None and (best[0] is None or got[1] < best[0]):
            limit = (x == lo_in and lo_open_point) or (x == hi_in and hi_open_point)
            best[:] = [got[1], x, got, limit]

    heap: list[tuple[int, int, _Box]] = []
    count = [0]

    def push(box: _Box) -> None:
        count[0] += 1
        heapq.heappush(heap, (box.lower, count[0], box))

    def regular(a: Fraction, b: Fraction) -> None:
        c, r = (a + b) / 2, (b - a) / 2
        m = model_at(e, c, r)
        if m is None:
            push(_Box(a, b, _NONE))  # split until the denominators dominate
            return
        lower, h = _quadratic_lower(m, r)
        offer(c + h)
        push(_Box(a, b, lower))

    def near_zero(a: Fraction, b: Fraction) -> None:
        """(a, b] with 0 <= a < b, from the expansion about 0 at radius b: E = h^power F(h),
        F's range over h in [a, b] by Horner's rule in interval arithmetic."""
        z = model_at_zero(e, b)
        if z is None:
            push(_Box(a, b, _NONE, "zero" if a == 0 else "regular"))
            return
        f_lo, _ = _range_on(z.f, a, b)
        if z.power < 0:
            lower = _floor(f_lo * b**z.power) if f_lo > 0 else _NONE
        elif z.power == 0:
            lower = _floor(f_lo)
        else:
            lower = _floor(min(f_lo * a**z.power, f_lo * b**z.power))
        if a == 0 and z.power == 0:  # the limit at the open end 0: the infimum if least
            limit = z.f.c[0]
            if best[0] is None or limit[1] < best[0]:
                best[:] = [limit[1], Fraction(0), limit, True]
        if a > 0:
            offer((a + b) / 2)
        push(_Box(a, b, lower, "zero" if a == 0 else "near"))

    start = lo_cov
    if lo_cov <= 0:
        r0 = min(Fraction(1, 4), _dyadic(hi_cov / 8))
        near_zero(Fraction(0), r0)
        start = r0
    else:
        offer(lo_in)
    offer(hi_in)
    pieces = 8
    for i in range(pieces):
        regular(start + (hi_cov - start) * i / pieces, start + (hi_cov - start) * (i + 1) / pieces)
    splits = 0
    certified = False
    while heap:
        lower = heap[0][0]
        size = max(Fraction(1), abs(Fraction(best[0] or 0, SCALE)))
        if best[0] is not None and best[0] - lower <= _floor(TOLERANCE * size):
            certified = True
            break
        if splits >= BUDGET:
            break
        _, _, box = heapq.heappop(heap)
        splits += 1
        if box.b - box.a < Fraction(1, 1 << 80):
            push(box)
            break
        if box.kind != "regular":
            half = _dyadic((box.a + box.b) / 2, 80)
            near_zero(box.a, half)
            near_zero(half, box.b)
        else:
            mid = _dyadic((box.a + box.b) / 2, 80)
            regular(box.a, mid)
            regular(mid, box.b)
    low = heap[0][0] if heap else best[0]
    value = best[2]
    return {
        "point": best[1],
        "value": None if value is None else (Fraction(value[0], SCALE), Fraction(value[1], SCALE)),
        "lower": Fraction(low, SCALE),
        "certified": certified,
        "limit": best[3],
        "boxes": splits,
    }
