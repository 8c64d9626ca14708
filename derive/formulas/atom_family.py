"""What is decided for a trigonometric, hyperbolic or mixed family (issue #30), exactly, from
its space (derive/families/spaces.py): the atom coefficient tables, linear independence over
the parameter box, end values and derivatives, symmetry with a parameter swap, energies as
Gram matrices with entries in Q[C, 1/C] (C = pi or e^W), the rational Bezier form through
tan(t/2), and non-negativity over the parameter box.

Everything is exact linear algebra on atoms (derive/algebra/atoms.py); SymPy is used for
polynomials in the parameters and in the half-angle variable only.
"""

from __future__ import annotations

import itertools
from fractions import Fraction
from math import comb

import sympy as sp

from ..algebra import atoms as A
from ..families.definition import ENDPOINT_ORDERS, ENERGY_ORDERS, Definition, DefinitionError
from ..families.engine import _negative_point
from ..families.spaces import Space, space_of

MAX_MINORS = 5_000  # maximal minors tried for linear independence


# --------------------------------------------------------------------------- exact numbers


def mono_key(mono: A.Mono) -> str:
    return ",".join(map(str, mono))


def exact(values: dict[int, Fraction]) -> str | list:
    """An exact number of the format-4 document: "p/q", or [["coefficient", exponent], ...]
    (sum of coefficient * C^exponent) where the constant enters."""
    items = sorted((c, v) for c, v in values.items() if v)
    if not items:
        return "0"
    if [c for c, _ in items] == [0]:
        return str(items[0][1])
    return [[str(v), c] for c, v in items]


def by_monomial(number: A.Number) -> dict[str, str | list]:
    """{monomial key: exact number} of a value that is a polynomial in the parameters."""
    grouped: dict[A.Mono, dict[int, Fraction]] = {}
    for (mono, c), v in number.items():
        grouped.setdefault(mono, {})[c] = v
    return {mono_key(m): exact(grouped[m]) for m in sorted(grouped)}


def show_number(values: dict[int, Fraction], constant: str) -> str:
    terms = [f"{v}*{constant}**{c}" if c else str(v) for c, v in sorted(values.items()) if v]
    return " + ".join(terms) or "0"


# --------------------------------------------------------------------------- atoms and tables


def _rate_text(space: Space, m: int) -> str:
    w = m * space.frame.rate
    return f"{w}*pi" if space.frame.rate_pi else str(w)


def atom_columns(space: Space) -> list[tuple[str, dict]]:
    """[(atom text, {key of algebra/atoms: weight})]: the columns of the coefficient table.
    Hyperbolic atoms are cosh(m w t) = (e^(mwt) + e^(-mwt))/2 and sinh; the table's
    coefficient of cosh is a_m + a_-m, of sinh a_m - a_-m (a_h: the coefficient of e^(hwt))."""
    keys = {key[2:] for elem in space.functions for key in elem}
    cols: list[tuple[str, dict]] = [("1", {(0, 0, 0, A.COS): Fraction(1)})]
    for k in sorted({k for k, h, m, _ in keys if k}):
        cols.append((f"t^{k}", {(k, 0, 0, A.COS): Fraction(1)}))
    for m in sorted({m for _, _, m, _ in keys if m}):
        w = _rate_text(space, m)
        cols.append((f"cos({w}*t)", {(0, 0, m, A.COS): Fraction(1)}))
        cols.append((f"sin({w}*t)", {(0, 0, m, A.SIN): Fraction(1)}))
    for h in sorted({abs(h) for _, h, _, _ in keys if h}):
        w = _rate_text(space, h)
        cols.append((f"cosh({w}*t)", {(0, h, 0, A.COS): Fraction(1), (0, -h, 0, A.COS): 1}))
        cols.append((f"sinh({w}*t)", {(0, h, 0, A.COS): Fraction(1), (0, -h, 0, A.COS): -1}))
    return cols


def coefficient_tables(space: Space) -> tuple[list[str], dict[A.Mono, list[list[Fraction]]]]:
    """The atoms and, per parameter monomial, the (n+1) x atoms matrix of rationals with
    b_i = sum_m params^m sum_a C[m][i][a] atom_a."""
    cols = atom_columns(space)
    out: dict[A.Mono, list[list[Fraction]]] = {}
    for mono in A.monomials(space.functions):
        rows = []
        for elem in space.functions:
            coeff = {key[2:]: v for key, v in A.part(elem, mono).items()}
            row = []
            for text, picks in cols:
                if text.startswith(("cosh", "sinh")):
                    (plus, _), (minus, sign) = picks.items()
                    row.append(coeff.get(plus, Fraction(0)) + sign * coeff.get(minus, Fraction(0)))
                else:
                    ((key, _),) = picks.items()
                    row.append(coeff.get(key, Fraction(0)))
            rows.append(row)
        out[mono] = rows
    # the table reproduces the functions (a check of the hyperbolic change of atoms)
    for i, elem in enumerate(space.functions):
        back: A.Elem = {}
        for mono, rows in out.items():
            for (text, picks), v in zip(cols, rows[i], strict=True):
                if not v:
                    continue
                for (k, h, m, kind), wgt in picks.items():
                    wgt = Fraction(wgt) / 2 if text.startswith(("cosh", "sinh")) else wgt
                    A.add_into(back, (mono, 0, k, h, m, kind), v * wgt)
        assert back == elem, f"the atom table does not reproduce b_{i}"
    return [text for text, _ in cols], out


def check_partition(defn: Definition, space: Space) -> None:
    total: A.Elem = {}
    for elem in space.functions:
        total = A.add(total, elem)
    if total != A.constant(space.frame):
        shown = show_elem(total, defn, space)
        raise DefinitionError(
            f"[family], key functions: no partition of unity: the functions sum to {shown}"
        )


def show_elem(elem: A.Elem, defn: Definition, space: Space) -> str:
    """An element as readable text (messages only)."""
    terms = []
    for (mono, c, k, h, m, kind), v in sorted(elem.items()):
        parts = [str(v)]
        names = zip(defn.parameters, mono, strict=True)
        parts += [f"{x}**{e}" if e > 1 else x for x, e in names if e]
        if c:
            parts.append(f"{space.constant}**{c}")
        if k:
            parts.append(f"t**{k}" if k > 1 else "t")
        if h:
            parts.append(f"exp({_rate_text(space, h)}*t)")
        if m:
            parts.append(f"{'cos' if kind == A.COS else 'sin'}({_rate_text(space, m)}*t)")
        terms.append("*".join(parts))
    return " + ".join(terms) or "0"


# --------------------------------------------------------------------------- end values


def end_values(space: Space) -> dict[tuple[str, int, int], A.Number]:
    """{("start", r, j): d^r b_j at lo, ("end", r, j): d^r b_(n-j) at hi}, r = 0..3, exact
    (polynomials in the parameters with coefficients in Q[C, 1/C])."""
    n = len(space.functions) - 1
    frame = space.frame
    out: dict[tuple[str, int, int], A.Number] = {}
    for i, elem in enumerate(space.functions):
        d = elem
        for r in range(ENDPOINT_ORDERS + 1):
            out[("start", r, i)] = A.value(d, frame, frame.lo)
            out[("end", r, n - i)] = A.value(d, frame, frame.hi)
            d = A.diff(d, frame)
    return out


def endpoints(space: Space) -> dict[str, dict]:
    """end_values() for the document: {"start,r,j" | "end,r,j": value by monomial}."""
    row = {f"{e},{r},{j}": by_monomial(v) for (e, r, j), v in end_values(space).items()}
    return dict(sorted(row.items(), key=lambda kv: _endpoint_order(kv[0])))


def _endpoint_order(key: str) -> tuple:
    end, r, j = key.split(",")
    return (int(r), int(j), end != "start")


# --------------------------------------------------------------------------- symmetry


def symmetry(defn: Definition, space: Space) -> tuple[str, ...] | None:
    """The parameter substitution s with b_i(lo + hi - t; s(x)) = b_(n-i)(t; x): the identity,
    a transposition, the reversal of the parameters, or any of these with signs flipped
    (the candidates of derive/families/engine.py's polynomial symmetry)."""
    count = len(defn.parameters)
    perms = [tuple(range(count))]
    for a in range(count):
        for b in range(a + 1, count):
            perm = list(range(count))
            perm[a], perm[b] = b, a
            perms.append(tuple(perm))
    if count > 2:
        perms.append(tuple(reversed(range(count))))
    signs = list(itertools.product((1, -1), repeat=count)) if count <= 4 else [(1,) * count]
    mirrored = [A.reflect(elem, space.frame) for elem in space.functions]
    target = list(reversed(space.functions))
    for perm in perms:
        for sign in signs:
            if all(
                A.substitute_parameters(m, perm, sign) == q
                for m, q in zip(mirrored, target, strict=True)
            ):
                names = defn.parameters
                return tuple(("-" if sign[k] < 0 else "") + names[perm[k]] for k in range(count))
    return None


# --------------------------------------------------------------------------- energies


def energies(space: Space) -> dict[str, dict]:
    """{"n,k": {"constant": C, "gram": {"m1|m2": G}}} with G[i][j] = int_lo^hi of the k-th
    derivatives of the m1-part of b_i and the m2-part of b_j, exact; E_k = sum over every
    ordered pair of monomials params^(m1 + m2) P^T G P. k = 0 too: the Gram matrix of the
    functions themselves, which the surface energies' Kronecker products need (issue #31)."""
    n = len(space.functions) - 1
    monos = A.monomials(space.functions)
    frame = space.frame
    out: dict[str, dict] = {}
    for k in (0, *ENERGY_ORDERS):
        ders = {m: [A.diff(A.part(b, m), frame, k) for b in space.functions] for m in monos}
        gram: dict[tuple[A.Mono, A.Mono], list[list]] = {}
        for a, m1 in enumerate(monos):
            for m2 in monos[a:]:
                mat = [[_inner(p, q, frame) for q in ders[m2]] for p in ders[m1]]
                gram[(m1, m2)] = mat
                gram[(m2, m1)] = [list(col) for col in zip(*mat, strict=True)]
        out[f"{n},{k}"] = {
            "constant": space.constant,
            "gram": {
                f"{mono_key(m1)}|{mono_key(m2)}": [[exact(v) for v in row] for row in mat]
                for (m1, m2), mat in sorted(gram.items())
            },
        }
    return out


def _inner(p: A.Elem, q: A.Elem, frame: A.Frame) -> dict[int, Fraction]:
    got = A.integral(A.mul(p, q), frame)
    return {c: v for (_, c), v in got.items()}


# --------------------------------------------------------------------------- half angles


def _half_angle(m: int) -> tuple[list[int], list[int]]:
    """cos(m psi), sin(m psi) = Re, Im of (1 + i u)^(2m) / (1 + u^2)^m with u = tan(psi/2):
    the numerators' coefficients, constant first."""
    re_, im_ = [0] * (2 * m + 1), [0] * (2 * m + 1)
    for j in range(2 * m + 1):
        c = comb(2 * m, j)
        if j % 4 == 0:
            re_[j] = c
        elif j % 4 == 1:
            im_[j] = c
        elif j % 4 == 2:
            re_[j] = -c
        else:
            im_[j] = -c
    return re_, im_


def _poly_mul(a: list, b: list) -> list:
    out = [Fraction(0)] * (len(a) + len(b) - 1)
    for i, x in enumerate(a):
        if x:
            for j, y in enumerate(b):
                out[i + j] += x * y
    return out


def half_angle_numerator(elem: A.Elem, frame: A.Frame, start: Fraction, top: int) -> list:
    """N(u) with elem(t) = N(u) / (1 + u^2)^top, u = tan(psi/2), psi = w (t - start): the
    element a trigonometric polynomial (no t^k) with every multiple m <= top, parameters set
    or kept per monomial by the caller (the zero monomial is read)."""
    out = [Fraction(0)] * (2 * top + 1)
    one_plus = [Fraction(1), Fraction(0), Fraction(1)]
    for (_, c, k, h, m, kind), v in elem.items():
        assert not (c or k or h), "a trigonometric polynomial"
        cos_a, sin_a = A.phase(frame, m, start)  # cos(m psi + m phi0), phi0 = w * start
        re_, im_ = _half_angle(m)
        # cos(x + a) = cos x cos a - sin x sin a;  sin(x + a) = sin x cos a + cos x sin a
        if kind == A.COS:
            num = [cos_a * x - sin_a * y for x, y in zip(re_, im_, strict=True)]
        else:
            num = [cos_a * y + sin_a * x for x, y in zip(re_, im_, strict=True)]
        pad = [Fraction(1)]
        for _ in range(top - m):
            pad = _poly_mul(pad, one_plus)
        for j, x in enumerate(_poly_mul(num, pad)):
            out[j] += v * x
    return out


def power_to_bernstein(coeffs: list[Fraction]) -> list[Fraction]:
    """Bernstein coefficients on [0, 1] of a polynomial given by power coefficients:
    b_j = sum_(i <= j) C(j, i) / C(N, i) a_i."""
    big = len(coeffs) - 1
    return [
        sum((Fraction(comb(j, i), comb(big, i)) * coeffs[i] for i in range(j + 1)), Fraction(0))
        for j in range(big + 1)
    ]


def _top_multiple(space: Space) -> int:
    return max((key[4] for elem in space.functions for key in elem), default=0)


def rational_form(space: Space) -> dict:
    """The exact rational Bezier form through s = tan((t - lo)/2) / scale, or a reason."""
    frame = space.frame
    if space.name != "trigonometric":
        why = {
            "hyperbolic": f"tanh((hi - lo)/2) = tanh({(frame.hi - frame.lo) * frame.rate}/2) "
            "is not rational (e^x is transcendental for a rational x != 0): no exact "
            "rational Bezier form with rational weights",
            "mixed-trigonometric": "t is not a rational function of tan(t/2): a mixed "
            "algebraic-trigonometric basis has no rational Bezier form",
            "mixed-hyperbolic": "t is not a rational function of tanh(t/2): a mixed "
            "algebraic-hyperbolic basis has no rational Bezier form",
        }[space.name]
        return {"reason": why}
    if frame.rate_pi or frame.rate.denominator != 1 or not frame.dom_pi:
        return {
            "reason": f"the rates are multiples of {_rate_text(space, 1)}, not integers, on a "
            "domain in pi: cos and sin of them are not rational functions of tan(t/2)"
        }
    if frame.hi - frame.lo != Fraction(1, 2) or frame.rate != 1:
        return {
            "reason": f"the scale tan((hi - lo)/2) = tan({(frame.hi - frame.lo) * frame.rate}"
            "*pi/2) is not rational (tan at a rational multiple of pi is rational only at "
            "multiples of pi/4): the form needs a domain of length pi/2"
        }
    n = len(space.functions) - 1
    top = _top_multiple(space)
    weights = power_to_bernstein(
        [Fraction(comb(top, j // 2)) if j % 2 == 0 else Fraction(0) for j in range(2 * top + 1)]
    )
    numerators = {}
    for mono in A.monomials(space.functions):
        numerators[mono_key(mono)] = [
            [
                str(x)
                for x in power_to_bernstein(
                    half_angle_numerator(A.part(b, mono), frame, frame.lo, top)
                )
            ]
            for b in space.functions
        ]
    assert all(w > 0 for w in weights)
    return {
        "substitution": "tan(t/2)",
        "scale": "1",
        "t_offset": str(frame.lo),
        "degree": {str(n): 2 * top},
        "weights": {str(n): [str(w) for w in weights]},
        "numerators": {str(n): numerators},
    }


# --------------------------------------------------------------------------- non-negativity


def nonnegative_is_certified(space: Space) -> bool:
    """Whether non-negativity over the box is decided by the certified branch and bound of
    atom_nonnegative.py (arb balls) rather than exactly: a mixed space has no polynomial
    substitution, and a basis not affine in its parameters has no vertex argument."""
    return space.name.startswith("mixed") or any(
        sum(key[0]) > 1 for elem in space.functions for key in elem
    )


def nonnegative_over_box(defn: Definition, space: Space) -> dict:
    """Every b_i >= 0 on the domain for every parameter value of the box? For a basis affine
    in the parameters jointly the least value at fixed t is at a vertex of the box (an open
    end by continuity); at a vertex a trigonometric b_i on each quarter period
    [x0, x0 + pi/(2w)] of the domain is N(u)/(1 + u^2)^M with u = tan(w (t - x0)/2) in
    [0, 1], so the question is polynomial non-negativity of N on [0, 1] (decided exactly by
    derive/families/engine.py's root isolation)."""
    if nonnegative_is_certified(space):
        from .atom_nonnegative import nonnegative_elementary

        return nonnegative_elementary(defn, space)
    if space.name == "hyperbolic":
        return _nonnegative_hyperbolic(defn, space)
    frame = space.frame
    quarters = 2 * frame.rate * (frame.hi - frame.lo)  # the domain in quarter periods
    assert quarters.denominator == 1
    step = (frame.hi - frame.lo) / int(quarters)
    top = _top_multiple(space)
    u = sp.Symbol("u")
    corners = [(q.lo, q.hi) for q in defn.params]
    for vertex in itertools.product(*corners):
        for idx, b in enumerate(space.functions):
            fixed = A.at_parameters(b, vertex)
            for piece in range(int(quarters)):
                x0 = frame.lo + piece * step
                num = half_angle_numerator(fixed, frame, x0, top)
                poly = sp.Poly(
                    list(reversed([sp.Rational(x.numerator, x.denominator) for x in num])), u
                )
                at = _negative_point(poly)
                if at is None:
                    continue
                where = f"{x0}*pi" if frame.dom_pi else str(x0)
                rate = _rate_text(space, 1)
                value = Fraction(int(sp.numer(poly.eval(at))), int(sp.denom(poly.eval(at))))
                value /= (1 + Fraction(int(at.p), int(at.q)) ** 2) ** top
                return {
                    "nonnegative": False,
                    "counterexample": {
                        "n": len(space.functions) - 1,
                        "i": idx,
                        "t": f"{where} + 2*atan({at})/({rate})",
                        **{q.name: str(v) for q, v in zip(defn.params, vertex, strict=True)},
                        "value": str(value),
                    },
                }
    return {"nonnegative": True}


def _exp_enclosure(x: Fraction) -> tuple[Fraction, Fraction]:
    """Rationals lo <= e^x <= hi (mpmath's interval arithmetic, rigorous; exact for x = 0)."""
    if x == 0:
        return Fraction(1), Fraction(1)
    import mpmath

    with mpmath.workprec(256):
        box = mpmath.iv.exp(mpmath.iv.mpf(x.numerator) / x.denominator)
        ends = []
        for end in (box.a, box.b):
            man, exp_ = mpmath.mpf(end).man_exp
            ends.append(Fraction(int(man)) * Fraction(2) ** int(exp_))
    return ends[0], ends[1]


def _nonnegative_hyperbolic(defn: Definition, space: Space) -> dict:
    """At a vertex b = sum_h a_h e^(h w t) = z^(-H) P(z) with z = e^(w t) in [e^(w lo), e^(w hi)]:
    P >= 0 there is decided from the real roots of P (exact isolation) and rational
    enclosures of the transcendental ends (refined until no root interval meets them; an
    algebraic root never equals e^x for a rational x != 0)."""
    frame = space.frame
    z = sp.Symbol("z")
    encl = [_exp_enclosure(frame.rate * x) for x in (frame.lo, frame.hi)]
    corners = [(q.lo, q.hi) for q in defn.params]
    for vertex in itertools.product(*corners):
        for idx, b in enumerate(space.functions):
            fixed = A.at_parameters(b, vertex)
            top = max((abs(key[3]) for key in fixed), default=0)
            coeffs = {key[3] + top: v for key, v in fixed.items()}
            poly = sp.Poly(
                {(e,): sp.Rational(v.numerator, v.denominator) for e, v in coeffs.items()}, z
            )
            at = _negative_inside(poly, encl)
            if at is not None:
                return {
                    "nonnegative": False,
                    "counterexample": {
                        "n": len(space.functions) - 1,
                        "i": idx,
                        "t": f"log({at})" + ("" if frame.rate == 1 else f"/{frame.rate}"),
                        **{q.name: str(v) for q, v in zip(defn.params, vertex, strict=True)},
                        "value_sign": "negative",
                    },
                }
    return {"nonnegative": True}


def _negative_inside(poly: sp.Poly, encl: list[tuple[Fraction, Fraction]]) -> Fraction | None:
    """A rational z in [a, b] with poly(z) < 0, or None; a in encl[0], b in encl[1]."""
    if poly.is_zero:
        return None
    (a_lo, a_hi), (b_lo, b_hi) = encl
    eps = Fraction(1, 10**6)
    for _ in range(40):
        ivs = sorted(
            (Fraction(str(x)), Fraction(str(y)))
            for (x, y), _ in poly.sqf_part().intervals(
                inf=sp.Rational(str(a_lo)), sup=sp.Rational(str(b_hi)), eps=sp.Rational(str(eps))
            )
        )
        meets = any(
            lo_ <= hi and hi_ >= lo and not (lo_ == hi_ == lo == hi)
            for lo_, hi_ in ivs
            for lo, hi in encl
            if lo != hi
        )
        if not meets:
            break
        eps /= 10**6
    else:  # pragma: no cover - roots are algebraic, the ends transcendental
        raise DefinitionError("non-negativity: a root too close to an end of the domain")
    inner = [(x, y) for x, y in ivs if y >= a_lo and x <= b_hi]
    points = [a_hi, b_lo]  # beside the ends: no root between them and the ends
    for (_, y), (u, _) in zip(inner, inner[1:], strict=False):
        points.append((y + u) / 2)
    points += [x for x, y in inner] + [y for x, y in inner]
    for x in sorted(set(points)):
        if a_hi <= x <= b_lo and poly.eval(sp.Rational(x.numerator, x.denominator)) < 0:
            return x
    return None


# --------------------------------------------------------------------------- independence


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
        if first.is_ground or _no_zero_in_box(first, defn):
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
    names = defn.parameters
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
    g = minors[0]
    for p in minors[1:]:
        g = g.gcd(p)
    points: list[dict] = []
    if not g.is_ground:  # V(g h_1, g h_2, ...) = V(g) | V(h_1, h_2, ...)
        for factor, _ in g.factor_list()[1]:
            point = _point_on(factor, defn)
            if point == "undecided":
                return {
                    "reason": f"the rank drops on {factor.as_expr()} = 0; whether that meets "
                    "the box is decided for two parameters only"
                }
            if point is not None:
                points.append({"on": f"{factor.as_expr()} = 0", **_box_point(defn, point)})
        minors = [p.exquo(g) for p in minors]
    basis = sp.groebner([p.as_expr() for p in minors], *syms, order="grevlex")
    if list(basis.exprs) != [1]:
        if not basis.is_zero_dimensional:
            return {
                "reason": f"the rank drops on the variety of {list(basis.exprs)}; whether it "
                "meets the box is not decided by this version"
            }
        for sol in sp.solve_poly_system(list(basis.exprs), *syms) or []:
            if all(v.is_real for v in sol) and all(
                _inside_real(v, q) for v, q in zip(sol, defn.params, strict=True)
            ):
                points.append({name: str(v) for name, v in zip(names, sol, strict=True)})
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


def _no_zero_in_box(poly: sp.Poly, defn: Definition) -> bool:
    """True when the polynomial provably has no zero in the parameter box (one parameter:
    no real root in the range; two: none on an edge and none at a critical point inside)."""
    if len(defn.params) == 1:
        q = defn.params[0]
        return not any(
            _inside_real(r, q) for f, _ in poly.factor_list()[1] for r in sp.real_roots(f)
        )
    if len(defn.params) == 2:
        return all(_point_on(f, defn) is None for f, _ in poly.factor_list()[1])
    return False


def _inside_real(v: sp.Expr, q) -> bool:
    """A real algebraic number in the parameter's interval (exact comparisons)."""
    lo, hi = (
        sp.Rational(q.lo.numerator, q.lo.denominator),
        sp.Rational(q.hi.numerator, q.hi.denominator),
    )
    above = bool(v >= lo) if q.lo_closed else bool(v > lo)
    below = bool(v <= hi) if q.hi_closed else bool(v < hi)
    return above and below


def _point_on(factor: sp.Poly, defn: Definition) -> dict | None | str:
    """A point of the box where the factor vanishes (exact or an algebraic number as text),
    None when there is none, "undecided" beyond two parameters. Two parameters: a zero on an
    edge of the box, or else a closed component inside it, which has a point where the
    derivative in the first parameter vanishes too (finitely many, solved exactly)."""
    syms, params = defn.symbols, defn.params
    if len(syms) != 2:
        return "undecided"
    for j in range(2):
        for end in (params[j].lo, params[j].hi):
            other = 1 - j
            edge = sp.Poly(
                factor.as_expr().subs(syms[j], sp.Rational(end.numerator, end.denominator)),
                syms[other],
            )
            if edge.is_zero:
                v = (params[other].lo + params[other].hi) / 2
                return _values({j: end, other: v})
            if not _inside(end, params[j]):
                continue
            for root in sp.real_roots(edge):
                if _inside_real(root, params[other]):
                    return _values({j: end, other: root})
    crit = sp.groebner([factor.as_expr(), factor.diff(syms[0]).as_expr()], *syms)
    if list(crit.exprs) == [1]:
        return None
    if not crit.is_zero_dimensional:
        return "undecided"
    for sol in sp.solve_poly_system(list(crit.exprs), *syms) or []:
        if all(v.is_real for v in sol) and all(
            _inside_real(v, q) for v, q in zip(sol, params, strict=True)
        ):
            return tuple(sol)
    return None


def _values(values: dict) -> tuple:
    return tuple(
        sp.Rational(v.numerator, v.denominator) if isinstance(v, Fraction) else v
        for _, v in sorted(values.items())
    )


def _box_point(defn: Definition, values: tuple) -> dict:
    return {q.name: str(v) for v, q in zip(values, defn.params, strict=True)}


def _refine(first, tables, entries, ring, defn: Definition, rounds: int = 40) -> dict | str:
    """The points of the box where the rank drops, from few minors: the candidates are the
    zeros in the box of the minors so far (a point on each curve of zeros, the finitely many
    other common zeros); at a rational candidate the exact rank decides: full, and the minor
    of its pivot columns (nonzero there) joins the list; not full, and it is a point where
    the rank drops. Done when every candidate is such a point (one parameter: that is every
    such point). None (not decided this way) at an irrational candidate or beyond two
    parameters."""
    from sympy.polys.matrices import DomainMatrix

    syms = defn.symbols
    rows = len(entries)
    minors, singular = [first], {}
    for _ in range(rounds):
        candidates = _candidates(minors, defn)
        if candidates is None:
            return (
                "more than two parameters: the zeros of a minor in the box are not located"
                if len(syms) > 2
                else "the minors' common zeros are neither finitely many nor curves"
            )
        grew = False
        for point in candidates:
            if point in singular:
                continue
            if not all(v.is_Rational for v in point):
                return (
                    f"a point where the rank may drop is irrational ({point}): the exact rank "
                    "there (over an algebraic field) is not computed"
                )
            exact = tuple(Fraction(int(v.p), int(v.q)) for v in point)
            pivots = _pivot_columns(tables, defn, exact)
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


def _candidates(minors: list, defn: Definition) -> list[tuple] | None:
    """Points of the box where every minor of the list vanishes: each real zero (one
    parameter), or a point on each curve of common zeros and the isolated ones (two)."""
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
    if len(syms) != 2:
        return None
    points = []
    if not g.is_ground:
        for factor, _ in g.factor_list()[1]:
            point = _point_on(factor, defn)
            if point == "undecided":
                return None
            if point is not None:
                points.append(point)
    rest = [p.exquo(g) for p in minors]
    if any(p.is_ground for p in rest):
        return points
    basis = sp.groebner([p.as_expr() for p in rest], *syms, order="grevlex")
    if list(basis.exprs) == [1]:
        return points
    if not basis.is_zero_dimensional:
        return None
    for sol in sp.solve_poly_system(list(basis.exprs), *syms) or []:
        if all(v.is_real for v in sol) and all(
            _inside_real(v, q) for v, q in zip(sol, defn.params, strict=True)
        ):
            points.append(tuple(sol))
    return points


def _inside(x: Fraction, q) -> bool:
    above = x >= q.lo if q.lo_closed else x > q.lo
    below = x <= q.hi if q.hi_closed else x < q.hi
    return above and below


__all__ = ["space_of"]
