"""generated/joins.py: the closed-form join weights (derive/formulas/joins.py solves them),
printed as functions and checked by executing the printed module against per-degree end
derivatives of the basis polynomials."""

from __future__ import annotations

from fractions import Fraction
from functools import cache
from math import factorial, perm

import flint

from ..algebra import bernstein as _bernstein
from ..algebra import to_fraction
from ..families.registry import REFERENCE, derivation
from ..formulas.joins import (
    CONTINUITIES,
    DEGREES,
    FAMILIES,
    HAS_LAMBDA,
    ORDER,
    SAMPLES,
    endpoint_forms,
    joins,
    pivots,
)
from . import printing as _emit

SCRIPT = "emit/joins.py"
OUTPUT = "joins.py"


# --------------------------------------------------------------------------- checks


@cache
def _per_degree_table(family: str, degree: int) -> dict[tuple[str, int, int], tuple]:
    """Per-degree endpoint derivatives of the basis polynomials, as coefficient lists in λ
    (lowest power first), read off the polynomials' own terms: p^(r)(0) = r! [t^r] p and
    p^(r)(1) = Σ_e e!/(e-r)! [t^e] p. Independent of the closed forms."""
    if family == REFERENCE:
        # the axiom in polynomial arithmetic, as the Bernstein tables have it (computed once)
        polys = [_bernstein.bernstein_poly(degree, ii) for ii in range(degree + 1)]
    else:
        polys = list(derivation(family).basis_polys(degree))
    out: dict = {}
    for idx, p in enumerate(polys):
        for (e, power), c in p.terms():
            c = to_fraction(c)
            for r in range(3):
                keys = [("end", r, idx, perm(e, r))]
                if e == r:
                    keys.append(("start", r, idx, factorial(r)))
                for end, rr, ii, factor in keys:
                    if factor:
                        coeffs = out.setdefault((end, rr, ii), [Fraction(0)] * (power + 1))
                        coeffs.extend([Fraction(0)] * (power + 1 - len(coeffs)))
                        coeffs[power] += factor * c
    return {key: tuple(v) for key, v in out.items() if any(v)}


def _horner(coeffs: tuple, x) -> Fraction:
    """Σ_p coeffs[p] x^p (x None: no shape parameter, only coeffs[0])."""
    acc = Fraction(0)
    for c in reversed(coeffs):
        acc = acc * (0 if x is None else x) + c
    return acc


def second_degrees(family: str, continuity: str) -> tuple[int, ...]:
    """Degrees of the second curve a join into `family` can have: enough control points for
    the solved ones (a family whose second end derivative involves P_{3,2} starts at n >= 3
    (checked in solve), so P_{3,2} always exists)."""
    return tuple(deg for deg in DEGREES[family] if deg >= ORDER[continuity])


def _first_points(degree: int) -> list[Fraction]:
    """Generic exact coordinates (one coordinate suffices: everything is linear)."""
    return [Fraction(3 * ii * ii - 7 * ii + 5, ii + 2) for ii in range(degree + 1)]


def _second_points(degree: int) -> list[Fraction]:
    return [Fraction(ii * ii + 2, 3 * ii + 1) for ii in range(degree + 1)]


def _corner(degree: int, degrees: tuple[int, ...]) -> bool:
    """The grid of the per-degree check: a pair is checked when either degree is one of the
    two lowest, the middle or the highest of its range (so every degree of each range meets
    the corner degrees of the other)."""
    return degree in (degrees[0], degrees[1], degrees[len(degrees) // 2], degrees[-1])


_ZERO = flint.fmpq(0)


def _q(v: int | Fraction | flint.fmpq) -> flint.fmpq:
    """An exact rational as FLINT's fmpq."""
    if type(v) is flint.fmpq:
        return v
    return flint.fmpq(v) if type(v) is int else flint.fmpq(v.numerator, v.denominator)


def _check_per_degree(namespace: dict, table: dict) -> int:
    """The emitted functions against the per-degree tables, on a grid of degree pairs (every
    degree of one range against the corner degrees of the other, see _corner), at one of
    SAMPLES per pair (alternating): C1'(1) etc. are computed from the basis polynomials'
    own coefficients and the points the emitted weights produce.

    The C1 (G1) weights are, entry for entry, the first two rows of the C2 (G2) weights
    (asserted), so checking C2 and G2 on every pair covers them; C1 and G1 are executed on
    the pairs C2 cannot have (m = 1 for a Bézier second curve) and on the diagonal n = m."""
    for (first, second, cont), weights in table.items():
        if cont in ("C1", "G1"):
            full = table[(first, second, cont.replace("1", "2"))]
            if any(
                _emit.expression(w) != _emit.expression(full[key]) for key, w in weights.items()
            ):
                raise AssertionError(f"{cont} {first} -> {second} differs from its order-2 form")

    # Both sides of the comparison are exact in FLINT's fmpq, several times faster than
    # Fraction (issue #29): ours (the points, the end derivatives, the sums the emitted
    # weights produce), and the emitted functions, which run as printed with their F (the
    # runtime's Fraction) bound to fmpq and fmpq arguments. The text is the same and both
    # number types are exact fields, so every weight is the one the runtime computes; a
    # float slipping into the printed text would raise here (fmpq refuses floats).
    namespace["F"] = flint.fmpq  # the globals the printed functions were executed in

    @cache
    def first_end(family, degree, sample):
        lam_ = SAMPLES[sample][0] if HAS_LAMBDA[family] else None
        pts = _first_points(degree)
        out = [Fraction(0)] * 3
        for (e, r, ii), c in _per_degree_table(family, degree).items():
            if e == "end":
                out[r] += _horner(c, lam_) * pts[ii]
        return [_q(v) for v in out]

    @cache
    def second_start(family, degree, sample):
        lam_ = SAMPLES[sample][1] if HAS_LAMBDA[family] else None
        return [
            (r, ii, _q(_horner(c, lam_)))
            for (e, r, ii), c in _per_degree_table(family, degree).items()
            if e == "start"
        ]

    @cache
    def points(degree, which):
        return [_q(v) for v in (_first_points if which == 1 else _second_points)(degree)]

    checks = 0
    for (first, second, cont), (fn, args) in namespace["JOINS"].items():
        order, geometric = ORDER[cont], cont.startswith("G")
        pivot_fn, pivot_args = namespace["PIVOTS"][second]
        for n_ in DEGREES[first]:
            pts1 = points(n_, 1)
            for m_ in second_degrees(second, cont):
                if order == 1 and m_ >= 2 and m_ != n_:
                    continue  # covered by the order-2 form (see above)
                if not (_corner(n_, DEGREES[first]) or _corner(m_, second_degrees(second, cont))):
                    continue
                sample = (n_ + m_) % len(SAMPLES)
                l1, l2, a, dd = SAMPLES[sample]
                if not geometric:
                    a, dd = Fraction(1), Fraction(0)
                values = {"n": n_, "m": m_, "lam1": _q(l1), "lam2": _q(l2)}
                values |= {"alpha": _q(a), "d": _q(dd)}
                piv = pivot_fn(*(values[x] for x in pivot_args))
                if any(piv[f"P{r}"] == 0 for r in range(1, order + 1)):
                    continue  # no join there; the runtime refuses it
                weights = fn(*(values[x] for x in args))
                pts2 = list(points(m_, 2))
                for row in range(order + 1):
                    total = _ZERO
                    for (r, src, j), w in weights.items():
                        if r != row or w == 0:
                            continue
                        w = _q(w)
                        if src == "first":
                            if j > n_:
                                raise AssertionError(f"{cont} {first}->{second}: P_(n-{j}), n={n_}")
                            total += w * pts1[n_ - j]
                        else:
                            total += w * pts2[j]
                    pts2[row] = total
                d1 = first_end(first, n_, sample)
                d2 = [_ZERO] * 3
                for r, ii, c in second_start(second, m_, sample):
                    d2[r] += c * pts2[ii]
                qa, qd = _q(a), _q(dd)
                ok = d2[0] == d1[0] and qa * d2[1] == d1[1]
                if order == 2:
                    ok = ok and qa * qa * d2[2] + qd * d2[1] == d1[2]
                if not ok:
                    raise AssertionError(f"{cont} {first} (n={n_}) -> {second} (m={m_}) fails")
                checks += 1
    return checks


def shared_inputs() -> None:
    """Derive (into their caches) what the joins share with the families' own groups: the
    closed end forms and the basis polynomials of every degree (emit/workers.py derives them
    once, before the joins go to a second process)."""
    for family in FAMILIES:
        endpoint_forms(family)
        if family != REFERENCE:
            for degree in DEGREES[family]:
                derivation(family).basis_polys(degree)


# --------------------------------------------------------------------------- emission


def _arguments(first: str, second: str, continuity: str) -> tuple[str, ...]:
    args = ["n", "m"]
    if HAS_LAMBDA[first]:
        args.append("lam1")
    if HAS_LAMBDA[second]:
        args.append("lam2")
    if continuity.startswith("G"):
        args.append("alpha")
    if continuity == "G2":
        args.append("d")
    return tuple(args)


def function_name(first: str, second: str, continuity: str) -> str:
    return f"{continuity.lower()}_{first}_to_{second}"


CONDITION_TEXT = {
    "C1": "C1(1) = C2(0), C1'(1) = C2'(0)",
    "C2": "C1(1) = C2(0), C1'(1) = C2'(0), C1''(1) = C2''(0)",
    "G1": "C1(1) = C2(0), C1'(1) = α C2'(0)",
    "G2": "C1(1) = C2(0), C1'(1) = α C2'(0), C1''(1) = α² C2''(0) + d C2'(0)",
}


def _join_function(first: str, second: str, cont: str, weights) -> str:
    known = sorted({j for _, src, j in weights if src == "second"})
    given = (
        f" P_{{{ORDER[cont]},2}} is solved with "
        + ", ".join(f"P_{{{j},2}}" for j in known)
        + " given."
        if known
        else ""
    )
    doc = (
        f"{cont}: {first} curve C1 (degree n) then {second} curve C2 (degree m); "
        f"{CONDITION_TEXT[cont]}.{given}"
    )
    body = (
        "return {\n"
        + "".join(
            f"    {_emit.literal(key)}: {_emit.expression(weights[key])},\n"
            for key in sorted(weights)
        )
        + "}"
    )
    return _emit.function(
        function_name(first, second, cont), _arguments(first, second, cont), doc, body
    )


def _pivot_function(family: str) -> tuple[str, tuple[str, ...]]:
    args = ("m", "lam2") if HAS_LAMBDA[family] else ("m",)
    s11, s22 = pivots(family)
    body = f"return {{\n    'P1': {_emit.expression(s11)},\n    'P2': {_emit.expression(s22)},\n}}"
    doc = (
        f"Pivots of a join into a {family} curve of degree m: 'P1' the coefficient of "
        "P_{1,2} in C2'(0), 'P2' that of P_{2,2} in C2''(0). P_{1,2} (P_{2,2}) cannot be "
        "solved for where 'P1' ('P2') vanishes."
    )
    return _emit.function(f"pivots_{family}", args, doc, body), args


# {four_points}: the sentence on families whose second end derivative involves P_{3,2} (_module_doc)
MODULE_DOC = """Joining two curves: leading control points of the second curve for C1, C2, G1, G2.

First curve C1: degree n, shape lam1, points P_{i,1}; second curve C2: degree m, shape lam2,
points P_{j,2}. G joins in 001's convention: C1'(1) = alpha C2'(0) (alpha > 0) and
C1''(1) = alpha**2 C2''(0) + d C2'(0) (d free); C joins are alpha = 1, d = 0.

JOINS[(first, second, continuity)] = (function, argument names). The function returns
{(row, source, j): weight} with P_{row,2} = sum of weight * X over its entries, where
X = P_{n-j,1} (source 'first') or X = P_{j,2} (source 'second', only j = 3). Rows 0..1 are
solved for C1/G1, rows 0..2 for C2/G2.{four_points} Pass ints/Fractions for exact weights. \
Denominators: powers of alpha and
PIVOTS[second] (a join is impossible where a needed pivot vanishes).
"""


def _module_doc() -> str:
    """MODULE_DOC naming the families whose second end derivative involves four points."""
    four = [f for f in FAMILIES if ("start", 2, 3) in endpoint_forms(f)]
    text = ""
    if four:
        names = " and ".join(four)
        text = (
            f" A {names} curve's second derivative at an end\n"
            f"involves four control points, so for a {names} second curve P_{{2,2}} is solved "
            "with\n"
            "P_{3,2} given."
        )
    return MODULE_DOC.replace("{four_points}", text)


def _checked_ranges() -> dict:
    return {
        (a, b, c): (
            (DEGREES[a][0], DEGREES[a][-1]),
            (second_degrees(b, c)[0], second_degrees(b, c)[-1]),
        )
        for a in FAMILIES
        for b in FAMILIES
        for c in CONTINUITIES
    }


def render() -> str:
    table = joins()
    parts = [
        _emit.banner(SCRIPT, _module_doc()),
        "",
        f"FAMILIES = {_emit.literal(FAMILIES)}",
        f"CONTINUITIES = {_emit.literal(CONTINUITIES)}",
        "# Number of derivatives each continuity matches (rows 0..ORDER are solved).",
        f"ORDER = {_emit.literal(ORDER)}",
        "# CHECKED[(first, second, continuity)] = ((n_lo, n_hi), (m_lo, m_hi)): derive checked the",
        "# emitted function exactly against the per-degree basis polynomials, every degree pair.",
        "CHECKED = " + _emit.literal(_checked_ranges()),
        "",
    ]
    pivot_args = {}
    for fam in FAMILIES:
        text, args = _pivot_function(fam)
        pivot_args[fam] = args
        parts += ["", text]
    parts += [
        "",
        "# The pivots printed, for error messages.",
        "PIVOT_TEXT = {\n"
        + "".join(
            f"    {fam!r}: {{'P1': {_emit.expression(pivots(fam)[0])!r}, "
            f"'P2': {_emit.expression(pivots(fam)[1])!r}}},\n"
            for fam in FAMILIES
        )
        + "}",
        "PIVOTS = {\n"
        + "".join(
            f"    {fam!r}: (pivots_{fam}, {_emit.literal(pivot_args[fam])}),\n" for fam in FAMILIES
        )
        + "}",
        "",
    ]
    keys = sorted(table)
    for key in keys:
        parts += ["", _join_function(*key, table[key])]
    parts += [
        "",
        "JOINS = {\n"
        + "".join(
            f"    {_emit.literal(key)}: "
            f"({function_name(*key)}, {_emit.literal(_arguments(*key))}),\n"
            for key in keys
        )
        + "}",
        "",
    ]
    text = "\n".join(parts)
    namespace: dict = {}
    exec(compile(text, f"generated/{OUTPUT}", "exec"), namespace)  # our own printed module
    _check_per_degree(namespace, table)
    return text
