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
from ..families.engine import _negative_point, symmetry_candidates
from ..families.spaces import Space, space_of

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
    mirrored = [A.reflect(elem, space.frame) for elem in space.functions]
    target = list(reversed(space.functions))
    for perm, sign in symmetry_candidates(count):
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
                return negative_at_log(defn, space, idx, at, vertex)
    return {"nonnegative": True}


def negative_at_log(
    defn: Definition, space: Space, idx: int, z: object, values: tuple | list
) -> dict:
    """The verdict that b_idx of a hyperbolic space is negative at t = log(z)/w with the
    parameters at `values` (z a rational or algebraic number, as a string)."""
    rate = space.frame.rate
    return {
        "nonnegative": False,
        "counterexample": {
            "n": len(space.functions) - 1,
            "i": idx,
            "t": f"log({z})" + ("" if rate == 1 else f"/{rate}"),
            **{q.name: str(v) for q, v in zip(defn.params, values, strict=True)},
            "value_sign": "negative",
        },
    }


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


# Linear independence over the parameter box: atom_independence.py (it uses the tables above).


__all__ = ["space_of"]
