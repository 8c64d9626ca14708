"""Linear independence over the parameter box of a trigonometric, hyperbolic or mixed family
(issue #30), exactly: the atom coefficient matrix M(x) (atom_family.coefficient_tables) has
full row rank at x unless every maximal minor vanishes there.

One minor first: the columns of a basis of the row space at the box's centre; when that minor
has no zero in the box, the family is independent everywhere. Otherwise candidates: the zeros
in the box of the minors so far (a point on each hypersurface of the minors' gcd, the common
zeros of the cofactors: all of them when finitely many, else a point on them), located
exactly by derive/formulas/real_box.py for any number of parameters. At a candidate the
exact rank decides (in Q, or in the number field of an algebraic point, SymPy's
AlgebraicField): full, and the minor of its pivot columns, nonzero there, joins the list;
not full, and the candidate is a point where the rank drops (reported exactly, and as
floats when irrational). Done when every candidate is such a point. When the minors are
few, all of them decide at once: no nonzero minor (dependent everywhere), the real roots of
their gcd (one parameter), or their common zeros in the box (several).
"""

from __future__ import annotations

import itertools
from fractions import Fraction

import sympy as sp

from ..families.definition import Definition
from ..families.spaces import Space
from . import real_box
from .atom_family import coefficient_tables

MAX_MINORS = 5_000  # maximal minors tried for linear independence


def independence(defn: Definition, space: Space) -> dict:
    """Linear independence of b_0..b_n over the parameter box: the atom coefficient matrix
    M(x) has full row rank unless every maximal minor vanishes. Decided exactly: no nonzero
    minor (dependent everywhere); one parameter, the real roots of the gcd of the minors in
    the range; several, a Groebner basis of the minors ({1}: nowhere; finitely many common
    zeros: those in the box). {"independent": bool, "singular": [points]} or a reason."""
    _, tables = coefficient_tables(space)
    syms = defn.symbols
    rows = len(space.functions)
    width = len(next(iter(tables.values()))[0])
    from sympy.polys.matrices import DomainMatrix

    ring = sp.QQ[syms]  # exact polynomials in the parameters
    entries = [[ring.zero for _ in range(width)] for _ in range(rows)]
    for mono, table in tables.items():
        term = ring.from_sympy(sp.Mul(*[s**e for s, e in zip(syms, mono, strict=True)]))
        for i in range(rows):
            for j in range(width):
                if table[i][j]:
                    v = table[i][j]
                    entries[i][j] += ring.convert(sp.Rational(v.numerator, v.denominator)) * term
    if width < rows:
        return {"independent": False, "everywhere": True, "why": "fewer atoms than functions"}
    # one minor first: the columns of a basis of the row space at a point inside the box (its
    # minor is nonzero there); the rank can drop only where it vanishes, so when it has no
    # zero in the box the family is independent over the whole box, with no other minor
    pivots = _pivot_columns(tables, defn)
    if pivots is not None:
        sub = DomainMatrix([[row[j] for j in pivots] for row in entries], (rows, rows), ring)
        first = sp.Poly(ring.to_sympy(sub.det()), *syms, domain="QQ")
        if first.is_ground or _no_zero_in_closed_box(first, defn):
            return {"independent": True, "singular": []}
        refined = _refine(first, tables, entries, ring, defn)
        if isinstance(refined, dict):
            return refined
        why = refined
    else:
        why = "the rank is not full at the box's centre"
    combos = list(itertools.combinations(range(width), rows))
    if len(combos) > MAX_MINORS:
        return {
            "reason": f"{len(combos)} maximal minors (over {MAX_MINORS}: their common zeros are "
            f"not computed), and the search one minor at a time stopped: {why}"
        }
    minors = []
    for cols in combos:
        sub = DomainMatrix([[row[j] for j in cols] for row in entries], (rows, rows), ring)
        d = sub.det()
        if d:
            minors.append(sp.Poly(ring.to_sympy(d), *syms, domain="QQ"))
    if not minors:
        mid = {q.name: str((q.lo + q.hi) / 2) for q in defn.params}
        return {"independent": False, "everywhere": True, "at": mid}
    if any(p.is_ground for p in minors):
        return {"independent": True, "singular": []}
    if len(syms) == 1:
        g = minors[0]
        for p in minors[1:]:
            g = g.gcd(p)
        roots = []
        q = defn.params[0]
        for factor, _ in g.factor_list()[1]:
            if factor.degree() == 1:
                c1, c0 = factor.all_coeffs()
                r = Fraction(int(sp.numer(-c0 / c1)), int(sp.denom(-c0 / c1)))
                if _inside(r, q):
                    roots.append(str(r))
            else:
                for (a, b), _ in factor.intervals(eps=sp.Rational(1, 10**12)):
                    a, b = Fraction(str(a)), Fraction(str(b))
                    if _inside(a, q) and _inside(b, q):
                        roots.append([[str(a), str(b)], [int(c) for c in factor.all_coeffs()]])
        return {"independent": not roots, "singular": sorted(roots, key=str)}
    try:
        found = _common_zeros(minors, defn, every=True)
    except real_box.Undecided as exc:
        return {"reason": f"the rank may drop where every maximal minor vanishes: {exc}"}
    points = [_box_point(defn, p) for p in found]
    return {"independent": not points, "singular": points}


def _pivot_columns(tables: dict, defn: Definition, point: tuple | None = None):
    """Columns of the atom matrix at a point (the box's centre by default; exact, FLINT)
    that span its row space, or None when the rank is not full there."""
    import flint

    if point is None:
        point = tuple((q.lo + q.hi) / 2 for q in defn.params)
    rows = len(next(iter(tables.values())))
    width = len(next(iter(tables.values()))[0])
    mat = flint.fmpq_mat(rows, width)
    for mono, table in tables.items():
        weight = Fraction(1)
        for x, e in zip(point, mono, strict=True):
            weight *= x**e
        for i in range(rows):
            for j in range(width):
                if table[i][j]:
                    v = table[i][j] * weight
                    mat[i, j] += flint.fmpq(v.numerator, v.denominator)
    echelon, rank = mat.rref()
    if rank < rows:
        return None
    cols = []
    for i in range(rows):
        cols.append(next(j for j in range(width) if echelon[i, j] != 0))
    return tuple(cols)


def _inside_real(v: sp.Expr, q) -> bool:
    """A real algebraic number in the parameter's interval (exact comparisons)."""
    lo, hi = (
        sp.Rational(q.lo.numerator, q.lo.denominator),
        sp.Rational(q.hi.numerator, q.hi.denominator),
    )
    above = bool(v >= lo) if q.lo_closed else bool(v > lo)
    below = bool(v <= hi) if q.hi_closed else bool(v < hi)
    return above and below


def _box_point(defn: Definition, values: tuple) -> dict:
    """An exact point by parameter name; an irrational coordinate also as a float."""
    out = {}
    for v, q in zip(values, defn.params, strict=True):
        out[q.name] = str(v)
        if not v.is_Rational:
            out[f"{q.name}_float"] = f"{float(sp.N(v, 30)):.17g}"
    return out


def _refine(first, tables, entries, ring, defn: Definition, rounds: int = 40) -> dict | str:
    """The points of the box where the rank drops, from few minors: the candidates are the
    zeros in the box of the minors so far (a point on each curve of zeros, the finitely many
    other common zeros); at a rational candidate the exact rank decides: full, and the minor
    of its pivot columns (nonzero there) joins the list; not full, and it is a point where
    the rank drops. Done when every candidate is such a point (one parameter: that is every
    such point). A reason when the candidates cannot be located (real_box.Undecided)."""
    from sympy.polys.matrices import DomainMatrix

    syms = defn.symbols
    rows = len(entries)
    minors, singular = [first], {}
    for _ in range(rounds):
        try:
            candidates = _common_zeros(minors, defn, every=False)
        except real_box.Undecided as exc:
            return f"where the minors vanish together: {exc}"
        grew = False
        for point in candidates:
            if point in singular:
                continue
            pivots = _pivots_at(tables, defn, point)
            if pivots is None:
                singular[point] = True
                continue
            sub = DomainMatrix([[row[j] for j in pivots] for row in entries], (rows, rows), ring)
            minors.append(sp.Poly(ring.to_sympy(sub.det()), *syms, domain="QQ"))
            grew = True
        if not grew:
            points = sorted(singular, key=lambda p: tuple(float(v) for v in p))
            if len(syms) == 1:
                return {"independent": not points, "singular": [str(p[0]) for p in points]}
            return {"independent": not points, "singular": [_box_point(defn, p) for p in points]}
    return f"no end after {rounds} rounds of candidates"


def _inside(x: Fraction, q) -> bool:
    above = x >= q.lo if q.lo_closed else x > q.lo
    below = x <= q.hi if q.hi_closed else x < q.hi
    return above and below


def _closed(defn: Definition) -> list[tuple[Fraction, Fraction]]:
    return [(q.lo, q.hi) for q in defn.params]


def _in_ranges(defn: Definition):
    return lambda point: all(_inside_real(v, q) for v, q in zip(point, defn.params, strict=True))


def _no_zero_in_closed_box(poly: sp.Poly, defn: Definition) -> bool:
    """True when the polynomial provably has no zero in the closed parameter box."""
    try:
        return all(
            real_box.hypersurface_point(f, _closed(defn)) is None for f, _ in poly.factor_list()[1]
        )
    except real_box.Undecided:
        return False


def _common_zeros(minors: list, defn: Definition, *, every: bool) -> list[tuple]:
    """Points of the box (open ends excluded) where every minor of the list vanishes: each
    real zero (one parameter); a point on each hypersurface of their gcd, and the cofactors'
    common zeros, all of them when finitely many (`every`, or always) else one. Raises
    real_box.Undecided."""
    syms = defn.symbols
    g = minors[0]
    for p in minors[1:]:
        g = g.gcd(p)
    if len(syms) == 1:
        q = defn.params[0]
        return sorted(
            {(r,) for f, _ in g.factor_list()[1] for r in sp.real_roots(f) if _inside_real(r, q)},
            key=lambda p: float(p[0]),
        )
    box, accept = _closed(defn), _in_ranges(defn)
    points = []
    for factor, _ in g.factor_list()[1]:  # V(g h_1, g h_2, ...) = V(g) | V(h_1, h_2, ...)
        if not factor.is_ground:
            point = real_box.hypersurface_point(factor, box, accept)
            if point is not None:
                points.append(point)
    rest = [p.exquo(g) for p in minors]
    if any(p.is_ground for p in rest):
        return points
    basis = sp.groebner([p.as_expr() for p in rest], *syms, order="grevlex")
    if list(basis.exprs) == [1]:
        return points
    if basis.is_zero_dimensional:
        return points + [
            p for p in real_box._finite_points(list(basis.exprs), syms, box) if accept(p)
        ]
    point = real_box.ideal_point(rest, box, accept)
    return points + ([point] if point is not None else [])


def _pivots_at(tables: dict, defn: Definition, point: tuple) -> tuple | None:
    """The pivot columns of the atom matrix at an exact point: over Q (FLINT) when it is
    rational, else over the number field its coordinates generate; None when the rank is
    not full there."""
    if all(v.is_Rational for v in point):
        return _pivot_columns(tables, defn, tuple(Fraction(int(v.p), int(v.q)) for v in point))
    from sympy.polys.matrices import DomainMatrix

    field = sp.QQ.algebraic_field(*[v for v in point if not v.is_Rational])
    coords = [field.from_sympy(v) for v in point]
    rows = len(next(iter(tables.values())))
    width = len(next(iter(tables.values()))[0])
    mat = [[field.zero for _ in range(width)] for _ in range(rows)]
    for mono, table in tables.items():
        weight = field.one
        for x, e in zip(coords, mono, strict=True):
            weight *= x**e
        for i in range(rows):
            for j in range(width):
                if table[i][j]:
                    v = table[i][j]
                    mat[i][j] += field.from_sympy(sp.Rational(v.numerator, v.denominator)) * weight
    _, pivots = DomainMatrix(mat, (rows, width), field).rref()
    return tuple(pivots) if len(pivots) == rows else None
