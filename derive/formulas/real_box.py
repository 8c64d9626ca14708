"""Exact real algebra on a box of parameters (issue #30): the cases the Bernstein branch and
bound of box.py cannot settle, because a polynomial *touches* zero in the box (a double root)
or vanishes on a set of lower dimension.

**Sample points of the complement of a hypersurface** (`open_cell_samples`). For D(x_1..x_k)
not identically zero, a rational point in every connected component of B° minus {D = 0}
(B the box): a cylindrical decomposition by recursive projection. With B the product of D's
distinct factors that involve x_k, the projection is the product of the factors free of x_k,
lc_xk(B), disc_xk(B) and B at the two faces x_k = lo, hi (factors that are x_k - lo or
x_k - hi themselves only lie on the box's boundary and are dropped). Over a connected open
cell of the projection's complement B(x', .) has a constant number of simple roots, none at
the faces, moving continuously; so the sectors between them are connected, and a rational
point between consecutive roots above a sample of each cell meets every component.

**Non-negativity** of P(u, x) on [a, b] x B (`nonnegative_poly`). Only the odd-multiplicity
factors Q of P decide its sign. Off the zero set of D = lc_u(Q) disc_u(Q) Q(a, x) Q(b, x), a
proper algebraic subset of B, Q(., x) has simple roots only, none at a or b; so on each cell
of B° minus {D = 0} either Q(., x) changes sign in (a, b) for every x of the cell or it has no
root in [a, b] for every x. One sample per cell, each an exact univariate question (root
isolation), decides Q >= 0 on the dense set, hence on [a, b] x B by continuity. This is the
"touching set is where the discriminant vanishes" argument made exact.

**A point of {f = 0} in the closed box** (`hypersurface_point`, f irreducible): either the
zero set meets a face (recursion with x_j set to the face's end), or it has a compact
component inside the open box, on which x_j attains its least value at a point where f and
every df/dx_i, i != j, vanish (a smooth point by Lagrange, or a singular one); when that
system has finitely many solutions they are found exactly. `ideal_point` does the same for
several polynomials: exact when the Groebner basis is {1}, finite or principal; otherwise a
point found on a face, or at a critical point of a coordinate on the zero set (the Jacobian's
minors of the codimension added; finitely many solutions), counts, and "no point" is proved
only by the Bernstein bound of the sum of squares > 0 on the box (a component of lower
dimension can escape the critical points); else Undecided, naming the dimension.

Points are tuples of SymPy numbers (rationals, radicals or CRootOf), compared exactly.
"""

from __future__ import annotations

from collections.abc import Callable
from fractions import Fraction
from typing import Any

import sympy as sp

from . import box as bern

MAX_DEGREE = 60  # of a projection polynomial in one variable, before the search gives up


class Undecided(ValueError):
    """The exact method would exceed its limits; the message says where."""


Box = list[tuple[Fraction, Fraction]]


def _q(x: Fraction) -> sp.Rational:
    return sp.Rational(x.numerator, x.denominator)


def _frac(x: sp.Rational) -> Fraction:
    return Fraction(int(x.p), int(x.q))


# --------------------------------------------------------------------------- one variable


def root_intervals(p: sp.Poly, lo: Fraction, hi: Fraction) -> list[tuple[Fraction, Fraction]]:
    """Disjoint sorted isolating intervals (exact (r, r) for a rational root) of the real
    roots of p in [lo, hi]; none straddles lo or hi."""
    if p.is_zero:
        raise ValueError("p is zero")
    if p.degree() <= 0:
        return []
    eps = Fraction(1, 10**6)
    for _ in range(60):
        out = []
        for (a, b), _ in p.sqf_part().intervals(eps=_q(eps)):
            a, b = Fraction(str(a)), Fraction(str(b))
            if b < lo or a > hi:
                continue
            if (a < lo < b and p.eval(_q(lo))) or (a < hi < b and p.eval(_q(hi))):
                break  # refine: the interval straddles an end that is not a root
            out.append((max(a, lo), min(b, hi)))
        else:
            return sorted(out)
        eps /= 1000
    raise Undecided("a root too close to an end of an interval")  # pragma: no cover


def gap_points(p: sp.Poly, lo: Fraction, hi: Fraction) -> list[Fraction]:
    """A rational point strictly inside every gap of (lo, hi) between p's real roots."""
    if p.degree() <= 0:
        return [(lo + hi) / 2]
    ivs = root_intervals(p, lo, hi)
    lefts = [lo] + [b for _, b in ivs]
    rights = [a for a, _ in ivs] + [hi]
    out = []
    for left, right in zip(lefts, rights, strict=True):
        if left < right:
            out.append((left + right) / 2)
        elif left == right and lo < left < hi and p.eval(_q(left)):
            out.append(left)  # two isolating intervals that share an end
    return out


def negative_at(p: sp.Poly, lo: Fraction, hi: Fraction) -> Fraction | None:
    """A rational point of [lo, hi] where p < 0, or None when p >= 0 there (exact: p keeps
    its sign between consecutive roots)."""
    if p.is_zero:
        return None
    for x in [lo, hi, *gap_points(p, lo, hi)]:
        if p.eval(_q(x)) < 0:
            return x
    return None


# --------------------------------------------------------------------------- cells


def _factors(poly: sp.Poly) -> list[sp.Poly]:
    return [f for f, _ in poly.factor_list()[1] if not f.is_ground]


def _face_factor(f: sp.Poly, x: sp.Symbol, lo: Fraction, hi: Fraction) -> bool:
    """f is c (x - lo) or c (x - hi): its zeros are on the box's boundary only."""
    if f.total_degree() != 1 or f.degree(x) != 1:
        return False
    root = sp.solve(f.as_expr(), x)[0]
    return root in (_q(lo), _q(hi))


def open_cell_samples(d: sp.Poly, box: Box) -> list[tuple[Fraction, ...]]:
    """A rational point in every connected component of the open box minus {d = 0}."""
    gens = d.gens
    if not gens or d.is_ground:
        if not gens:
            return [()]
        return _product_of_midpoints(box)
    x, (lo, hi) = gens[-1], box[-1]
    rest = gens[:-1]
    involved, free = [], []
    for f in _factors(d):
        (involved if f.degree(x) > 0 else free).append(f)
    involved = [f for f in involved if not _face_factor(f, x, lo, hi)]
    big = sp.Poly(sp.Mul(*[f.as_expr() for f in involved]), *gens)
    if big.degree(x) > MAX_DEGREE:
        raise Undecided(f"a projection polynomial of degree {big.degree(x)} in {x}")
    if not rest:
        return [(v,) for v in gap_points(sp.Poly(big.as_expr(), x), lo, hi)]
    proj = sp.Integer(1)
    for f in free:
        proj *= f.as_expr()
    if big.degree(x) > 0:
        in_x = sp.Poly(big.as_expr(), x)
        proj *= in_x.LC() * sp.discriminant(in_x.as_expr(), x)
        proj *= big.as_expr().subs(x, _q(lo)) * big.as_expr().subs(x, _q(hi))
    base = open_cell_samples(sp.Poly(sp.expand(proj), *rest), box[:-1])
    out = []
    for s in base:
        at = dict(zip(rest, [_q(v) for v in s], strict=True))
        line = sp.Poly(big.as_expr().xreplace(at), x)
        out.extend((*s, v) for v in gap_points(line, lo, hi))
    return out


def _product_of_midpoints(box: Box) -> list[tuple[Fraction, ...]]:
    return [tuple((lo + hi) / 2 for lo, hi in box)]


# --------------------------------------------------------------------------- non-negativity


def nonnegative_poly(p: sp.Poly, box: Box) -> dict:
    """p(u, x_1..x_k) >= 0 on box = [a, b] x [x ranges] (p's gens in that order)?
    {"holds": True} or {"holds": False, "point": rational point with p < 0}; raises
    Undecided beyond the limits (module docstring)."""
    u, xs = p.gens[0], p.gens[1:]
    (a, b), xbox = box[0], box[1:]
    const, factors = p.factor_list()
    odd = sp.Rational(const)  # the content: a rational, never truncated
    for f, mult in factors:
        if mult % 2 == 0:
            continue
        if f.degree(u) == f.total_degree() == 1 and _face_factor(f, u, a, b):
            odd *= sp.sign(f.as_expr().subs(u, _q((a + b) / 2)))  # of one sign on [a, b]
            continue
        odd *= f.as_expr()
    odd_poly = sp.Poly(odd, *p.gens)
    if odd_poly.is_ground:
        if odd_poly.LC() >= 0:
            return {"holds": True}
        return {"holds": False, "point": _negative_point_of(p, box, _midpoint(box))}
    if odd_poly.degree(u) == 0:
        d = odd_poly
    else:
        in_u = sp.Poly(odd, u)
        d_expr = in_u.LC() * sp.discriminant(odd, u)
        d_expr *= odd.subs(u, _q(a)) * odd.subs(u, _q(b))
        d = sp.Poly(sp.expand(d_expr), *p.gens)
    d = sp.Poly(d.as_expr(), *xs) if xs else d
    samples = open_cell_samples(d, xbox) if xs else [()]
    for s in samples:
        at = dict(zip(xs, [_q(v) for v in s], strict=True))
        line = sp.Poly(odd_poly.as_expr().xreplace(at), u)
        v = negative_at(line, a, b)
        if v is not None:
            return {"holds": False, "point": _negative_point_of(p, box, (v, *s))}
    return {"holds": True}


def _midpoint(box: Box) -> tuple[Fraction, ...]:
    return tuple((lo + hi) / 2 for lo, hi in box)


def _negative_point_of(p: sp.Poly, box: Box, point: tuple[Fraction, ...]) -> tuple:
    """A point where p itself is < 0, near `point`, where its odd part is: the even factors
    vanish on a thinner set, so a step towards the box's centre (halved until it works) or
    along u leaves it."""
    centre = _midpoint(box)
    for k in range(80):
        step = Fraction(1, 2**k) if k else Fraction(0)
        for q in (
            tuple(x + (c - x) * step for x, c in zip(point, centre, strict=True)),
            (point[0] + (centre[0] - point[0]) * step, *point[1:]),
        ):
            if p.eval(tuple(_q(v) for v in q)) < 0:
                return q
    raise Undecided("no point where the function itself is negative")  # pragma: no cover


# --------------------------------------------------------------------------- zeros in a box


def inside(v: Any, lo: Fraction, hi: Fraction) -> bool:
    """A real algebraic number in [lo, hi], compared exactly."""
    return bool(v.is_real) and bool(v >= _q(lo)) and bool(v <= _q(hi))


def dimension(basis: list[sp.Poly], gens: tuple) -> int:
    """Krull dimension of the ideal the polynomials generate: from a graded Groebner basis,
    the largest set of variables that no leading monomial lives on alone."""
    graded = sp.groebner([f.as_expr() for f in basis], *gens, order="grevlex")
    if list(graded.exprs) == [1]:
        return -1
    leads = [sp.Poly(f, *gens).monoms(order="grevlex")[0] for f in graded.exprs]
    best = 0
    k = len(gens)
    for mask in range(1 << k):
        chosen = {i for i in range(k) if mask >> i & 1}
        if len(chosen) <= best:
            continue
        if all(any(e and i not in chosen for i, e in enumerate(m)) for m in leads):
            best = len(chosen)
    return best


Accept = Callable[[tuple], bool]


class _Search:
    """The points a caller accepts (a box with open ends excludes some of its faces), and
    whether a zero was met that it did not accept (then no "none" can be claimed)."""

    def __init__(self, accept: Accept | None):
        self.accept = accept or (lambda _p: True)
        self.rejected: list[tuple] = []

    def take(self, points: list[tuple]) -> tuple | None:
        for point in points:
            if self.accept(point):
                return point
            self.rejected.append(point)
        return None

    def none(self) -> None:
        if self.rejected:
            raise Undecided(
                f"the only zeros found ({', '.join(map(str, self.rejected[:2]))}) lie on an "
                "excluded end of a range; whether others lie inside is not decided"
            )


def _finite_points(exprs: list, gens: tuple, box: Box) -> list[tuple]:
    found = sp.solve_poly_system(exprs, *gens) or []
    return [
        tuple(sol)
        for sol in found
        if all(inside(v, lo, hi) for v, (lo, hi) in zip(sol, box, strict=True))
    ]


def _on_face(point: tuple, j: int, end: Fraction) -> tuple:
    return (*point[:j], _q(end), *point[j:])


def hypersurface_point(f: sp.Poly, box: Box, accept: Accept | None = None) -> tuple | None:
    """A point of the closed box where the irreducible polynomial f vanishes (one `accept`
    takes), or None when there is none (module docstring); raises Undecided."""
    search = _Search(accept)
    point = _hypersurface(f, box, search)
    if point is None:
        search.none()
    return point


def _hypersurface(f: sp.Poly, box: Box, search: _Search) -> tuple | None:
    gens = f.gens
    if f.is_zero:
        return search.take([_midpoint_sp(box)])
    if f.is_ground:
        return None
    if len(gens) == 1:
        roots = [r for r in sp.real_roots(f) if inside(r, *box[0])]
        return search.take([(r,) for r in roots])
    on_face = _face_point(f, box, search)
    if on_face is not None:
        return on_face
    for j in range(len(gens)):
        crit = [f.as_expr()] + [f.diff(g).as_expr() for i, g in enumerate(gens) if i != j]
        basis = sp.groebner(crit, *gens, order="grevlex")
        if list(basis.exprs) == [1]:
            return None
        if basis.is_zero_dimensional:
            return search.take(_finite_points(list(basis.exprs), gens, box))
    raise Undecided(
        f"the critical points of every coordinate on {f.as_expr()} = 0 are not finitely many"
    )


def _midpoint_sp(box: Box) -> tuple:
    return tuple(_q(v) for v in _midpoint(box))


def _face_point(f: sp.Poly, box: Box, search: _Search) -> tuple | None:
    """A point of {f = 0} on the box's boundary that the search accepts, or None."""
    gens = f.gens
    for j, (lo, hi) in enumerate(box):
        others = gens[:j] + gens[j + 1 :]
        sub = box[:j] + box[j + 1 :]
        for end in (lo, hi):
            on = sp.Poly(f.as_expr().subs(gens[j], _q(end)), *others)
            inner = _Search(lambda p, j=j, end=end: search.accept(_on_face(p, j, end)))
            if on.is_zero:
                point = inner.take([_midpoint_sp(sub)])
            else:
                point = None
                for g in _factors(on):
                    point = _hypersurface(g, sub, inner)
                    if point is not None:
                        break
            search.rejected += [_on_face(p, j, end) for p in inner.rejected]
            if point is not None:
                return _on_face(point, j, end)
    return None


def _critical_point(polys: list[sp.Poly], box: Box, search: _Search) -> tuple | None:
    """A common zero inside the box where x_j is critical on the zero set: the ideal with
    the c x c minors of its Jacobian without column j added (c its codimension), when that
    has finitely many solutions. Finds the least x_j of a compact component of the top
    dimension; a component of lower dimension can escape it, so None proves nothing."""
    import itertools

    gens = polys[0].gens
    codim = len(gens) - dimension(polys, gens)
    jac = [[p.diff(g) for g in gens] for p in polys]
    for j in range(len(gens)):
        cols = [i for i in range(len(gens)) if i != j]
        minors = []
        for rows in itertools.combinations(range(len(polys)), codim):
            for sub in itertools.combinations(cols, codim):
                mat = sp.Matrix([[jac[r][c].as_expr() for c in sub] for r in rows])
                minors.append(sp.expand(mat.det(method="berkowitz")))
        basis = sp.groebner([p.as_expr() for p in polys] + minors, *gens, order="grevlex")
        if list(basis.exprs) != [1] and basis.is_zero_dimensional:
            point = search.take(_finite_points(list(basis.exprs), gens, box))
            if point is not None:
                return point
    return None


def ideal_point(polys: list[sp.Poly], box: Box, accept: Accept | None = None) -> tuple | None:
    """A point of the closed box where every polynomial vanishes (one `accept` takes), or
    None when there is none; raises Undecided (module docstring)."""
    search = _Search(accept)
    point = _ideal(polys, box, search)
    if point is None:
        search.none()
    return point


def _ideal(polys: list[sp.Poly], box: Box, search: _Search) -> tuple | None:
    gens = polys[0].gens
    basis = sp.groebner([p.as_expr() for p in polys], *gens, order="grevlex")
    exprs = list(basis.exprs)
    if exprs == [1]:
        return None
    if basis.is_zero_dimensional:
        return search.take(_finite_points(exprs, gens, box))
    if len(exprs) == 1:
        for f in _factors(sp.Poly(exprs[0], *gens)):
            point = _hypersurface(f, box, search)
            if point is not None:
                return point
        return None
    polys = [sp.Poly(e, *gens) for e in exprs]
    for j, (lo, hi) in enumerate(box):  # a point on a face, exact, when there is one
        others = gens[:j] + gens[j + 1 :]
        sub = box[:j] + box[j + 1 :]
        for end in (lo, hi):
            on = [sp.Poly(p.as_expr().subs(gens[j], _q(end)), *others) for p in polys]
            on = [p for p in on if not p.is_zero]
            inner = _Search(lambda p, j=j, end=end: search.accept(_on_face(p, j, end)))
            try:
                point = _ideal(on, sub, inner) if on else inner.take([_midpoint_sp(sub)])
            except Undecided:
                continue
            if point is not None:
                return _on_face(point, j, end)
    point = _critical_point(polys, box, search)
    if point is not None:
        return point
    total = sp.Poly(sp.Add(*[p.as_expr() ** 2 for p in polys]), *gens)
    try:
        got = bern.sign_over_box(total, box, strict=True)
    except bern.TooLarge as exc:
        raise Undecided(f"{exc}") from exc
    if got["holds"] is True:
        return None
    raise Undecided(
        f"the common zeros of {exprs} (dimension {dimension(polys, gens)}) do not meet the "
        "box's faces, and their sum of squares is not proved > 0 inside it"
    )
