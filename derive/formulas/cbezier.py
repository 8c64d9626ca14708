"""The decisions of a family whose parameter is the length of the domain or sits inside sin/cos
(derive/families/cbezier.py): exact where they can be, certified in arb balls where not.

* partition of unity, end values and derivatives (orders 0..3 at t = 0 and t = alpha), the
  symmetry t <-> alpha - t (b_i(t) = b_(n-i)(alpha - t)) and linear independence (the rank of
  the coefficient matrix over the atoms) are identities in Q(alpha, S, C) modulo the circle,
  decided by `cbezier.reduce`;
* the singular points of the box: zeros of a denominator at an end of the box (alpha -> 0,
  where alpha - sin(alpha) vanishes) decided exactly, inside the box certified absent by arb;
* non-negativity over the box: sampled on a grid of (alpha, t = alpha*u) in point balls (a
  negative ball is a certified counterexample), then certified over the whole closed box by
  formulas/cbezier_nonnegative.py (exact series in alpha about 0, the end zeros divided out,
  a majorant tail bound, an arb branch and bound); "not certified" with its reason when that
  does not settle the sign;
* energies E_k = int_0^alpha |r^(k)(t)|^2 dt as Gram matrices of exact closed forms in
  (alpha, S, C).
"""

from __future__ import annotations

from functools import cache

import flint
import sympy as sp

from ..families import cbezier as cb
from ..families.cbezier import A, C, CDefinition, Elem, S, T
from .arb_enclose import enclose

ENERGY_ORDERS = (1, 2, 3)
ORDERS = 3


# --------------------------------------------------------------------------- printing


def show(expr: sp.Expr, defn: CDefinition) -> str:
    """An exact coefficient in the family's own names: alpha, sin(alpha), cos(alpha)."""
    alpha = sp.Symbol(defn.parameter)
    sin, cos = (sp.sinh, sp.cosh) if defn.hyperbolic else (sp.sin, sp.cos)
    return str(sp.factor(expr).subs({S: sin(alpha), C: cos(alpha), A: alpha}))


def ratfn(expr: sp.Expr) -> dict:
    """A rational function of (A, S, C) as data the runtime evaluates without SymPy:
    numerator and denominator as [[exponents of A, S, C], "p/q"] terms."""
    num, den = sp.fraction(sp.cancel(sp.together(expr)))

    def terms(p: sp.Expr) -> list:
        poly = sp.Poly(sp.expand(p), A, S, C)
        return [[list(mono), str(coeff)] for mono, coeff in sorted(poly.terms())]

    return {"num": terms(num), "den": terms(den)}


# --------------------------------------------------------------------------- identities


def partition_of_unity(defn: CDefinition) -> bool:
    total: Elem = {}
    for f in defn.elems():
        for atom, v in f.items():
            cb.add_into(total, atom, v)
    cb.add_into(total, (cb.POW, 0), sp.Integer(-1))
    return all(cb.is_zero(v, defn.hyperbolic) for v in total.values())


@cache
def end_table(defn: CDefinition) -> tuple[tuple[tuple[sp.Expr, ...], tuple[sp.Expr, ...]], ...]:
    """[i] -> (values at t = 0 of b_i^(0..3), values at t = alpha), exact."""
    out = []
    for f in defn.elems():
        lo, hi = [], []
        for order in range(ORDERS + 1):
            d = cb.derivative(f, defn.hyperbolic, order)
            lo.append(cb.value_at(d, "lo", defn.hyperbolic))
            hi.append(cb.value_at(d, "hi", defn.hyperbolic))
        out.append((tuple(lo), tuple(hi)))
    return tuple(out)


def zero_order(defn: CDefinition, i: int, end: str) -> int:
    """The order of b_i's zero at t = 0 ("lo") or t = alpha ("hi"), from the exact end
    derivatives (orders 0..n); n + 1 when all of them vanish."""
    f = defn.elems()[i]
    for order in range(defn.degree + 1):
        d = cb.derivative(f, defn.hyperbolic, order)
        if cb.value_at(d, end, defn.hyperbolic) != 0:
            return order
    return defn.degree + 1


def bernstein_end_conditions(defn: CDefinition) -> bool:
    """b_i has a zero of order exactly i at t = 0 and n - i at t = alpha (the Bernstein end
    conditions that make the control polygon tangent at the ends)."""
    n = defn.degree
    return all(
        zero_order(defn, i, "lo") == i and zero_order(defn, i, "hi") == n - i for i in range(n + 1)
    )


def symmetric(defn: CDefinition) -> bool:
    """b_i(t) = b_(n-i)(alpha - t) for every i, exactly."""
    fs = defn.elems()
    n = defn.degree
    for i, f in enumerate(fs):
        diff = cb.reflect(f, defn.hyperbolic)
        for atom, v in fs[n - i].items():
            cb.add_into(diff, atom, -v)
        if not all(cb.is_zero(v, defn.hyperbolic) for v in diff.values()):
            return False
    return True


def coefficient_matrix(defn: CDefinition) -> tuple[list, sp.Matrix]:
    atoms = sorted({atom for f in defn.functions for atom, _ in f})
    rows = [[dict(f).get(a, sp.Integer(0)) for a in atoms] for f in defn.functions]
    return atoms, sp.Matrix(rows)


def rank(defn: CDefinition) -> tuple[int, sp.Expr | None]:
    """The rank of the coefficient matrix over Q(alpha, S, C) (exact pivots, zero tests by
    `reduce`), and with n + 1 atoms its determinant (reduced)."""
    atoms, m = coefficient_matrix(defn)
    rows = [list(m.row(r)) for r in range(m.rows)]
    r = 0
    for col in range(len(atoms)):
        pivot = next(
            (k for k in range(r, len(rows)) if not cb.is_zero(rows[k][col], defn.hyperbolic)),
            None,
        )
        if pivot is None:
            continue
        rows[r], rows[pivot] = rows[pivot], rows[r]
        for k in range(r + 1, len(rows)):
            factor = rows[k][col] / rows[r][col]
            rows[k] = [
                cb.reduce(x - factor * y, defn.hyperbolic)
                for x, y in zip(rows[k], rows[r], strict=True)
            ]
        r += 1
    det = None
    if m.rows == m.cols:
        det = cb.reduce(m.det(method="berkowitz"), defn.hyperbolic)
    return r, det


# --------------------------------------------------------------------------- arb


def _arb(x: sp.Expr) -> flint.arb:
    if x == sp.pi:
        return flint.arb.pi()
    q = x / sp.pi if x.has(sp.pi) else x
    v = flint.arb(flint.fmpq(int(q.p), int(q.q)))
    return v * flint.arb.pi() if x.has(sp.pi) else v


PREC = 128  # bits of the balls: the coefficients cancel like alpha^3 near alpha = 0


def _env(alpha: flint.arb, hyperbolic: bool) -> dict:
    return {
        A: alpha,
        S: alpha.sinh() if hyperbolic else alpha.sin(),
        C: alpha.cosh() if hyperbolic else alpha.cos(),
    }


def _ball(lo: flint.arb, hi: flint.arb) -> flint.arb:
    return (lo + hi) / 2 + flint.arb(0, 1) * ((hi - lo) / 2)


# --------------------------------------------------------------------------- singular points


def denominators(defn: CDefinition) -> list[sp.Expr]:
    """The distinct irreducible factors (in A, S, C) of the coefficients' denominators."""
    found: set[sp.Expr] = set()
    for f in defn.functions:
        for _, v in f:
            den = sp.fraction(sp.cancel(v))[1]
            for factor, _mult in sp.factor_list(den)[1]:
                if factor.free_symbols:
                    found.add(sp.expand(factor))
    return sorted(found, key=sp.default_sort_key)


def singular_points(defn: CDefinition) -> list[dict]:
    """Where a denominator vanishes on the closure of the box: exactly at the ends (alpha = 0
    is the limit of a C-Bezier box, with the leading term of the series there), certified
    absent inside by arb bisection on [SCAN_FLOOR, hi] (a box open at 0: (0, SCAN_FLOOR) is
    not scanned), or reported as an interval that could not be cleared."""
    with flint.ctx.workprec(PREC):
        return _singular_points(defn)


def _singular_points(defn: CDefinition) -> list[dict]:
    out = []
    ends = [(defn.lo, "lo"), (defn.hi, "hi")]
    for factor in denominators(defn):
        name = show(factor, defn)
        for x, which in ends:
            sc = (sp.sinh(x), sp.cosh(x)) if defn.hyperbolic else (sp.sin(x), sp.cos(x))
            value = sp.nsimplify(sp.expand(factor.subs({A: x, S: sc[0], C: sc[1]})))
            if value == 0:
                closed = defn.lo_closed if which == "lo" else defn.hi_closed
                row = {
                    "at": str(x),
                    "denominator": name,
                    "where": "an end of the box, "
                    + ("inside it" if closed else "excluded (open); the limit is singular"),
                }
                if x == 0:
                    row["leading_term"] = series_at_zero(factor, defn)
                out.append(row)
        for lo, hi in _uncleared(factor, defn):
            out.append({"at": f"[{lo}, {hi}]", "denominator": name, "where": "inside, not cleared"})
    return out


SCAN_FLOOR = sp.Rational(1, 8)  # the interior scan of a box open at 0 starts here


def d_alpha(expr: sp.Expr, hyperbolic: bool) -> sp.Expr:
    """d/d alpha of a function of (A, S, C): S' = C, C' = -S (C' = S for cosh)."""
    return sp.diff(expr, A) + C * sp.diff(expr, S) + (S if hyperbolic else -S) * sp.diff(expr, C)


def scan_start(defn: CDefinition) -> sp.Expr:
    return defn.lo if defn.lo != 0 else SCAN_FLOOR


def _uncleared(factor: sp.Expr, defn: CDefinition) -> list[tuple[float, float]]:
    """Intervals of the box where the mean-value enclosure f(m) + f'(X)(X - m) of the factor
    still contains 0 after bisection (from SCAN_FLOOR when the box is open at 0)."""
    hyp = defn.hyperbolic
    slope = d_alpha(factor, hyp)
    start = _arb(scan_start(defn))
    stack = [(start, _arb(defn.hi), 0)]
    left: list[tuple[float, float]] = []
    budget = 20_000
    while stack and len(left) < 5:
        a, b, depth = stack.pop()
        budget -= 1
        if budget < 0:
            left.append((float(a.mid()), float(b.mid())))
            break
        box = _ball(a, b)
        mid = flint.arb(box.mid())
        v = enclose(factor, _env(mid, hyp)) + enclose(slope, _env(box, hyp)) * (box - mid)
        if not v.contains(0):
            continue
        if depth > 50:
            left.append((float(a.mid()), float(b.mid())))
            continue
        stack += [(a, mid, depth + 1), (mid, b, depth + 1)]
    return left


def series_at_zero(factor: sp.Expr, defn: CDefinition) -> str:
    """The leading term of the factor's Taylor series at alpha = 0 (exact)."""
    alpha = sp.Symbol(defn.parameter, positive=True)
    sin, cos = (sp.sinh, sp.cosh) if defn.hyperbolic else (sp.sin, sp.cos)
    f = factor.subs({S: sin(alpha), C: cos(alpha), A: alpha})
    return str(sp.series(f, alpha, 0, 12).removeO().as_ordered_terms()[-1])


# --------------------------------------------------------------------------- non-negativity


def nonnegative(defn: CDefinition) -> dict:
    """Non-negativity over the box: a grid of GRID x GRID points (alpha, u), t = alpha*u, each
    value a point ball at PREC bits (a negative ball is a certified counterexample), then the
    certificate of formulas/cbezier_nonnegative.py over the closed box. Point balls of the
    written form alone certify nothing over a box: near alpha = 0 numerator and denominator
    cancel like alpha^3, which the certificate removes by dividing the exact series."""
    from .cbezier_nonnegative import certify

    with flint.ctx.workprec(PREC):
        sampled = _nonnegative(defn)
    if sampled["verdict"] is False:
        return sampled
    got = certify(defn, zero_order)
    if got["verdict"] is False:
        return got
    if got["verdict"] is True:
        return got
    return {**sampled, "reason": got["reason"]}


GRID = 32


def _nonnegative(defn: CDefinition) -> dict:
    n = defn.degree
    a_lo = defn.lo if defn.lo_closed else defn.lo + (defn.hi - defn.lo) / (4 * GRID)
    lo, hi = _arb(a_lo), _arb(defn.hi)
    fs = defn.written()
    worst = None
    for ka in range(GRID + 1):
        alpha = lo + (hi - lo) * flint.arb(flint.fmpq(ka, GRID))
        for ku in range(1, GRID):
            u = flint.arb(flint.fmpq(ku, GRID))
            for i in range(n + 1):
                value = enclose(fs[i], {A: alpha, T: alpha * u})
                if value < 0:
                    exact_alpha = a_lo + (defn.hi - a_lo) * sp.Rational(ka, GRID)
                    return {
                        "verdict": False,
                        "counterexample": {
                            "i": i,
                            defn.parameter: str(exact_alpha),
                            "t": str(exact_alpha * sp.Rational(ku, GRID)),  # t = u * alpha
                            "alpha_float": float(alpha.mid()),
                            "t_float": float((alpha * u).mid()),
                            "value": float(value.mid()),
                        },
                        "method": f"a point ball at {PREC} bits (certified negative)",
                    }
                if worst is None or value.mid() < worst:
                    worst = value.mid()
    return {
        "verdict": "not certified",
        "sampled": f"{(GRID + 1) * (GRID - 1)} points (alpha, u) of [{a_lo}, {defn.hi}] x "
        f"(0, 1), every value a positive ball",
        "method": "sampling only: the certificate did not settle the sign",
    }


# --------------------------------------------------------------------------- energies


@cache
def _atom_integral(kind: str, m: int, hyperbolic: bool) -> sp.Expr:
    """int_0^alpha of t^m (kind "pow"), cos(m t), sin(m t) (cosh, sinh), in (A, S, C)."""
    if kind == cb.POW:
        return A ** (m + 1) / (m + 1)
    c, s = cb.angle(m, hyperbolic)
    if kind == cb.COS:  # sin(m a)/m; sinh(m a)/m
        return s / m
    return (c - 1) / m if hyperbolic else (1 - c) / m


def _product(a: tuple[str, int], b: tuple[str, int], hyperbolic: bool) -> list:
    """The product of two atoms as [(coefficient, atom)] (product-to-sum rules)."""
    (ka, ma), (kb, mb) = a, b
    if ka == cb.POW and kb == cb.POW:
        return [(1, (cb.POW, ma + mb))]
    if ka == cb.POW or kb == cb.POW:
        (_, k), other = (a, b) if ka == cb.POW else (b, a)
        if k:
            raise ValueError("t^k times sin/cos is outside the energies decided here")
        return [(1, other)]
    half = sp.Rational(1, 2)
    sgn = 1 if hyperbolic else -1

    def atom(kind: str, m: int) -> list:
        if m == 0:
            return [(1, (cb.POW, 0))] if kind == cb.COS else []
        if m < 0:
            return [((-1 if kind == cb.SIN else 1), (kind, -m))]
        return [(1, (kind, m))]

    out = []

    def put(coef, kind, m):
        out.extend((coef * c, at) for c, at in atom(kind, m))

    if ka == cb.COS and kb == cb.COS:  # cos cos = (cos(a-b) + cos(a+b))/2; cosh likewise
        put(half, cb.COS, ma - mb)
        put(half, cb.COS, ma + mb)
    elif ka == cb.SIN and kb == cb.SIN:  # sin sin = (cos(a-b) - cos(a+b))/2; sinh: (ch+ - ch-)/2
        put(-sgn * half, cb.COS, ma - mb)
        put(sgn * half, cb.COS, ma + mb)
    else:  # sin a cos b = (sin(a+b) + sin(a-b))/2 (sinh likewise)
        (ms, mc) = (ma, mb) if ka == cb.SIN else (mb, ma)
        put(half, cb.SIN, ms + mc)
        put(half, cb.SIN, ms - mc)
    return out


@cache
def gram(defn: CDefinition, k: int) -> list[list[sp.Expr]]:
    """G[i][j] = int_0^alpha b_i^(k) b_j^(k) dt, exact in (A, S, C)."""
    hyp = defn.hyperbolic
    ders = [cb.derivative(f, hyp, k) for f in defn.elems()]
    n = defn.degree
    out = [[sp.Integer(0)] * (n + 1) for _ in range(n + 1)]
    for i in range(n + 1):
        for j in range(i, n + 1):
            total = sp.Integer(0)
            for a, va in ders[i].items():
                for b, vb in ders[j].items():
                    for coef, atom in _product(a, b, hyp):
                        total += coef * va * vb * _atom_integral(*atom, hyp)
            out[i][j] = out[j][i] = cb.reduce(total, hyp)
    return out
