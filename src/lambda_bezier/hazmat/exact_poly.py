"""Exact polynomial algebra over the rationals, standard library only.

Univariate polynomials are lists of Fractions, lowest degree first; bivariate ones are dicts
{(i, j): coefficient of x^i y^j}. Real roots are isolated by Sturm sequences into intervals
with rational ends; resultants are computed by evaluation at integer points and interpolation
(exact, no SymPy or FLINT needed). Bound for ``lambda_bezier.hazmat`` with the surface kernels.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from fractions import Fraction

Poly = list[Fraction]
Bivariate = dict[tuple[int, int], Fraction]


def trim(p: Sequence[Fraction]) -> Poly:
    out = [Fraction(c) for c in p]
    while out and out[-1] == 0:
        out.pop()
    return out


def evaluate(p: Sequence[Fraction], x: Fraction) -> Fraction:
    """p(x), exactly. With integer coefficients (what exact_flint's polynomials have) in
    integers: d^k p(n/d) = Σ c_i n^i d^(k−i) by Horner, one Fraction at the end, instead of a
    gcd after every step."""
    if not isinstance(x, Fraction | int) or not all(
        isinstance(c, int) or c.denominator == 1 for c in p
    ):
        acc = Fraction(0)
        for c in reversed(p):
            acc = acc * x + c
        return acc
    x = Fraction(x)
    num, den = x.numerator, x.denominator
    total, scale = 0, 1
    for c in reversed(p):
        total = total * num + int(c) * scale
        scale *= den
    return Fraction(total, scale // den) if p else Fraction(0)


def derivative(p: Sequence[Fraction]) -> Poly:
    return trim([k * p[k] for k in range(1, len(p))])


def multiply(a: Sequence[Fraction], b: Sequence[Fraction]) -> Poly:
    if not a or not b:
        return []
    out = [Fraction(0)] * (len(a) + len(b) - 1)
    for i, x in enumerate(a):
        if x:
            for j, y in enumerate(b):
                out[i + j] += x * y
    return trim(out)


def _rem(a: Poly, b: Poly) -> Poly:
    a = list(a)
    while len(a) >= len(b):
        if a[-1] == 0:
            a.pop()
            continue
        f = a[-1] / b[-1]
        shift = len(a) - len(b)
        for k, c in enumerate(b):
            a[shift + k] -= f * c
        a.pop()
    return trim(a)


def _divide(a: Poly, b: Poly) -> Poly:
    a = list(a)
    q = [Fraction(0)] * max(len(a) - len(b) + 1, 1)
    while len(a) >= len(b) and a:
        f = a[-1] / b[-1]
        shift = len(a) - len(b)
        q[shift] = f
        for k, c in enumerate(b):
            a[shift + k] -= f * c
        a.pop()
    return trim(q)


def gcd(a: Poly, b: Poly) -> Poly:
    a, b = trim(a), trim(b)
    while b:
        a, b = b, _rem(a, b)
    return [c / a[-1] for c in a] if a else a


def squarefree(p: Poly) -> Poly:
    g = gcd(p, derivative(p))
    return _divide(trim(p), g) if len(g) > 1 else trim(p)


def sturm_sequence(p: Poly) -> list[Poly]:
    seq = [trim(p), derivative(p)]
    while seq[-1]:
        r = _rem(seq[-2], seq[-1])
        seq.append([-c for c in r])
    return seq[:-1]


def _sign_changes(seq: list[Poly], x: Fraction) -> int:
    signs = [s for s in ((evaluate(p, x) > 0) - (evaluate(p, x) < 0) for p in seq) if s]
    return sum(1 for a, b in zip(signs, signs[1:], strict=False) if a != b)


def real_roots(
    p: Sequence[Fraction], lo: Fraction, hi: Fraction
) -> list[Fraction | tuple[Fraction, Fraction]]:
    """The distinct real roots of p in [lo, hi], increasing: a Fraction for a rational root
    met exactly, else (a, b), an open interval with rational ends holding exactly one root."""
    q = squarefree(trim(p))
    if len(q) <= 1:
        if not q:
            raise ValueError("the zero polynomial has every number as a root")
        return []
    seq = sturm_sequence(q)
    out: list[Fraction | tuple[Fraction, Fraction]] = []
    if evaluate(q, lo) == 0:
        out.append(lo)
    stack = [(lo, hi)]
    found: list[Fraction | tuple[Fraction, Fraction]] = []
    while stack:
        a, b = stack.pop()
        count = _sign_changes(seq, a) - _sign_changes(seq, b)  # roots in (a, b]
        if count == 0:
            continue
        if count == 1 and evaluate(q, b) == 0:
            found.append(b)
            continue
        if count == 1 and evaluate(q, a) != 0:  # both ends are not roots: refine can bisect
            found.append((a, b))
            continue
        mid = (a + b) / 2
        stack += [(a, mid), (mid, b)]
    out += found
    return sorted(out, key=lambda r: r if isinstance(r, Fraction) else r[0])


def refine(
    p: Sequence[Fraction], interval: tuple[Fraction, Fraction], width: Fraction
) -> Fraction | tuple[Fraction, Fraction]:
    """Bisect an isolating interval of a square-free factor's root down to `width` (or hit it)."""
    a, b = interval
    fa = evaluate(p, a)
    while b - a > width:
        mid = (a + b) / 2
        fm = evaluate(p, mid)
        if fm == 0:
            return mid
        if (fm > 0) == (fa > 0):
            a, fa = mid, fm
        else:
            b = mid
    return (a, b)


def integer_coefficients(p: Sequence[Fraction]) -> tuple[int, ...]:
    """p scaled to coprime integers with a positive leading coefficient."""
    from math import gcd as igcd
    from math import lcm

    p = trim(p)
    den = lcm(*(c.denominator for c in p)) if p else 1
    ints = [int(c * den) for c in p]
    g = 0
    for c in ints:
        g = igcd(g, c)
    g = g or 1
    if ints and ints[-1] < 0:
        g = -g
    return tuple(c // g for c in ints)


# ---------------------------------------------------------------------- bivariate
def partial(f: Bivariate, var: int) -> Bivariate:
    out: Bivariate = {}
    for (i, j), c in f.items():
        k = (i, j)[var]
        if k and c:
            key = (i - 1, j) if var == 0 else (i, j - 1)
            out[key] = out.get(key, Fraction(0)) + k * c
    return out


def substitute(f: Bivariate, var: int, value: Fraction) -> Poly:
    """f with x (var 0) or y (var 1) fixed: a polynomial in the other variable."""
    size = 1 + max((key[1 - var] for key in f), default=0)
    out = [Fraction(0)] * size
    for key, c in f.items():
        out[key[1 - var]] += c * value ** key[var]
    return trim(out)


def evaluate2(f: Bivariate, x: Fraction, y: Fraction) -> Fraction:
    return sum((c * x**i * y**j for (i, j), c in f.items()), Fraction(0))


def _determinant(rows: list[list[Fraction]]) -> Fraction:
    a = [list(r) for r in rows]
    n = len(a)
    det = Fraction(1)
    for c in range(n):
        p = next((r for r in range(c, n) if a[r][c] != 0), None)
        if p is None:
            return Fraction(0)
        if p != c:
            a[c], a[p] = a[p], a[c]
            det = -det
        det *= a[c][c]
        for r in range(c + 1, n):
            if a[r][c]:
                f = a[r][c] / a[c][c]
                a[r] = [v - f * w for v, w in zip(a[r], a[c], strict=True)]
    return det


def _sylvester(p: Poly, q: Poly) -> Fraction:
    """Res(p, q) for the given formal degrees len(p) - 1, len(q) - 1."""
    m, n = len(p) - 1, len(q) - 1
    size = m + n
    if size == 0:
        return Fraction(1)
    rows = []
    for k in range(n):
        row = [Fraction(0)] * size
        for i, c in enumerate(reversed(p)):
            row[k + i] = c
        rows.append(row)
    for k in range(m):
        row = [Fraction(0)] * size
        for i, c in enumerate(reversed(q)):
            row[k + i] = c
        rows.append(row)
    return _determinant(rows)


def resultant(f: Bivariate, g: Bivariate, var: int) -> Poly:
    """Res_var(f, g) as a polynomial in the other variable, eliminating x (var 0) or y (var 1).

    The formal degrees in `var` are those of f and g as a whole; the resultant is a polynomial
    of degree at most deg_var(f)·deg_other(g) + deg_var(g)·deg_other(f), found by evaluating
    the Sylvester determinant at that many + 1 integer points and interpolating.
    """
    other = 1 - var
    df = max((k[var] for k in f if f[k]), default=0)
    dg = max((k[var] for k in g if g[k]), default=0)
    ef = max((k[other] for k in f if f[k]), default=0)
    eg = max((k[other] for k in g if g[k]), default=0)
    bound = df * eg + dg * ef
    xs = [Fraction(k) for k in range(bound + 1)]
    ys = []
    for x0 in xs:
        fp = _in_var(f, var, other, x0, df)
        gp = _in_var(g, var, other, x0, dg)
        ys.append(_sylvester(fp, gp))
    return _interpolate(xs, ys)


def first_subresultant(
    f: Bivariate,
    g: Bivariate,
    var: int,
    determinant: Callable[[list[list[Fraction]]], Fraction] | None = None,
    interpolate: Callable[[list[Fraction], list[Fraction]], Poly] | None = None,
) -> tuple[Poly, Poly] | None:
    """The first subresultant of f and g in `var`, S_1 = a1 · var + a0, as (a1, a0):
    polynomials in the other variable. Where Res_var(f, g) vanishes at x0, f and g have
    constant leading coefficients in `var` and a1(x0) ≠ 0, S_1(x0, ·) is their gcd, so their
    only common root is var = −a0(x0)/a1(x0) (real when x0 is); with leading coefficients in
    `var` that depend on the other variable, the same holds where one of them does not vanish
    at x0 (the caller checks it). When one of them does not involve `var` (a vertical or
    horizontal line: then Res = f^dg, so it vanishes at x0) and the other is linear in it,
    that linear one is the gcd at x0. None when a degree in `var` is 0 and the other's is not
    1 (no such form). Found like
    `resultant`: the minors of the Sylvester matrix at integer points, interpolated (their
    determinants by `determinant`, Gaussian elimination in Fractions by default; the
    interpolation by `interpolate`, Newton's divided differences by default)."""
    other = 1 - var
    df = max((k[var] for k in f if f[k]), default=0)
    dg = max((k[var] for k in g if g[k]), default=0)
    if (df == 0 or dg == 0) and df + dg != 1:
        return None
    if df == 1 or dg == 1:  # a linear one is its own S_1 (up to a constant)
        h = f if df == 1 else g
        return (
            substitute_row(h, var, 1),
            substitute_row(h, var, 0),
        )
    ef = max((k[other] for k in f if f[k]), default=0)
    eg = max((k[other] for k in g if g[k]), default=0)
    bound = df * eg + dg * ef
    xs = [Fraction(k) for k in range(bound + 1)]
    a1s, a0s = [], []
    for x0 in xs:
        minors = _subresultant_one(
            _in_var(f, var, other, x0, df),
            _in_var(g, var, other, x0, dg),
            determinant or _determinant,
        )
        a1s.append(minors[0])
        a0s.append(minors[1])
    through = interpolate or _interpolate
    return through(xs, a1s), through(xs, a0s)


def substitute_row(f: Bivariate, var: int, power: int) -> Poly:
    """The coefficient of var^power in f, a polynomial in the other variable."""
    other = 1 - var
    size = 1 + max((k[other] for k in f), default=0)
    out = [Fraction(0)] * size
    for key, c in f.items():
        if key[var] == power:
            out[key[other]] += c
    return trim(out)


def _subresultant_one(
    p: Poly, q: Poly, determinant: Callable[[list[list[Fraction]]], Fraction]
) -> tuple[Fraction, Fraction]:
    """(a1, a0) of S_1(p, q) for the formal degrees m = len(p) − 1, n = len(q) − 1 ≥ 2: the
    (m + n − 2)-row matrix of n − 1 shifted rows of p and m − 1 of q, its first m + n − 3
    columns with the column of x^1, then with that of x^0."""
    m, n = len(p) - 1, len(q) - 1
    width = m + n - 1
    rows = []
    for k in range(n - 1):
        row = [Fraction(0)] * width
        for i, c in enumerate(reversed(p)):
            row[k + i] = c
        rows.append(row)
    for k in range(m - 1):
        row = [Fraction(0)] * width
        for i, c in enumerate(reversed(q)):
            row[k + i] = c
        rows.append(row)
    head = width - 2  # columns of x^(m+n-2) ... x^2
    return (
        determinant([r[:head] + [r[head]] for r in rows]),
        determinant([r[:head] + [r[head + 1]] for r in rows]),
    )


def sign_at_root(p: Poly, square_free: Poly, interval: tuple[Fraction, Fraction]) -> int:
    """The sign (−1, 0, 1) of p at the one root of the square-free polynomial `square_free` in
    `interval` (a rational point (r, r), or an open interval with non-root ends, as
    real_roots and refine give them): 0 exactly when p and square_free share a root there
    (their gcd over Q has one in the interval: Sturm on the gcd, usually of low degree), else
    the sign of an enclosure of p over the interval, halved about the root until the
    enclosure excludes 0 (it must: p does not vanish at the root)."""
    lo, hi = interval
    p = trim(p)
    if not p:
        return 0
    if lo == hi:
        v = evaluate(p, lo)
        return (v > 0) - (v < 0)
    common = gcd(p, square_free)
    if len(common) > 1 and real_roots(common, lo, hi):
        return 0
    return sign_off_root(p, square_free, interval)


def sign_off_root(p: Poly, square_free: Poly, interval: tuple[Fraction, Fraction]) -> int:
    """The sign of p at the one root of `square_free` in the open `interval` (non-root
    ends), p known not to vanish there: an enclosure of p over the interval, halved about
    the root until it excludes 0."""
    lo, hi = interval
    while True:
        low, high = _enclose(p, lo, hi)
        if low > 0 or high < 0:
            return 1 if low > 0 else -1
        got = refine(square_free, (lo, hi), (hi - lo) / 2)
        if isinstance(got, Fraction):  # met the root exactly
            v = evaluate(p, got)
            return (v > 0) - (v < 0)
        lo, hi = got


def _enclose(p: Poly, lo: Fraction, hi: Fraction) -> tuple[Fraction, Fraction]:
    """An enclosure of p over [lo, hi]: the mean-value form p(m) ± |p′|·r about the middle,
    |p′| bounded by its coefficients' magnitudes at max(|lo|, |hi|)."""
    mid, rad = (lo + hi) / 2, (hi - lo) / 2
    big = max(abs(lo), abs(hi))
    slope = Fraction(0)
    for c in reversed(derivative(p)):
        slope = slope * big + abs(c)
    centre = evaluate(p, mid)
    return centre - slope * rad, centre + slope * rad


def _in_var(f: Bivariate, var: int, other: int, value: Fraction, degree: int) -> Poly:
    out = [Fraction(0)] * (degree + 1)
    for key, c in f.items():
        out[key[var]] += c * value ** key[other]
    return out


def _interpolate(xs: list[Fraction], ys: list[Fraction]) -> Poly:
    """The polynomial of degree < len(xs) through the points (Newton's divided differences)."""
    n = len(xs)
    coef = list(ys)
    for j in range(1, n):
        for i in range(n - 1, j - 1, -1):
            coef[i] = (coef[i] - coef[i - 1]) / (xs[i] - xs[i - j])
    out: Poly = [Fraction(0)]
    for i in range(n - 1, -1, -1):  # Horner on the Newton form
        out = [Fraction(0)] + out
        for k in range(len(out) - 1):
            out[k] -= xs[i] * out[k + 1]
        out[0] += coef[i]
    return trim(out)


# ---------------------------------------------------------------------- intervals
Interval = tuple[Fraction, Fraction]


def interval_evaluate2(f: Bivariate, x: Interval, y: Interval) -> Interval:
    """An enclosure of f over the box x × y (monomial-wise interval arithmetic)."""
    lo = hi = Fraction(0)
    for (i, j), c in f.items():
        a, b = _power(x, i)
        e, g = _power(y, j)
        prods = (a * e, a * g, b * e, b * g)
        m0, m1 = min(prods) * c, max(prods) * c
        lo += min(m0, m1)
        hi += max(m0, m1)
    return lo, hi


def _power(x: Interval, k: int) -> Interval:
    a, b = x
    if k == 0:
        return Fraction(1), Fraction(1)
    ends = (a**k, b**k)
    if k % 2 == 0 and a < 0 < b:
        return Fraction(0), max(ends)
    return min(ends), max(ends)
