"""Claims about a family whose parameter is the length of the domain or sits inside sin/cos
(C-Bezier families, derive/families/cbezier.py; issue #30).

A records file defining such a family uses these of checks_several.py's claim kinds, which
hand its records here:

* ``several_basis`` and ``several_end_conditions``: ``equations`` in t, the parameter (alpha),
  ``sin``/``cos`` (``sinh``/``cosh``) of integer multiples of t and alpha, the basis
  ``b(j, n, x)``, the control points ``P(j)`` and the curve ``p(x)``, with ``Derivative`` and
  ``Subs`` (end values and derivatives at t = 0 and t = alpha, partition of unity, a function
  itself). An equation mentioning i is checked at every i = 0..n.
* ``several_symmetry`` (no ``swap``): b_i(t) = b_(n-i)(alpha - t) for every i.
* ``several_energy_matrix`` and ``several_energy`` (``k``, rational ``control_points`` and an
  ``expression`` in alpha: E_k = sum P^T G_k(alpha) P), from derive's exact Gram matrices;
* ``several_nonnegative``, ``several_independence`` and ``several_join`` (below).

Each side is built from the derived functions (the family file's functions converted to exact
atoms by cbezier.read_table) and the difference is converted to the same atoms t^k, cos(m t),
sin(m t) with coefficients in Q(alpha, sin alpha, cos alpha); each coefficient is then reduced
modulo sin^2 + cos^2 = 1 (cosh^2 - sinh^2 = 1) by cbezier.reduce, where zero is decided
exactly (see cbezier's docstring). Record formulas are read by the records grammar
(derive/grammar), never by sympify.
"""

from __future__ import annotations

import sympy as sp

from ..families import cbezier as cb
from ..families.cbezier import CDefinition
from ..formulas import cbezier as F
from ..grammar import SYMBOLS, ParseError, parse_formula
from .checks_core import Outcome
from .checks_elementary import (
    RecordError,
    claimed_flag,
    curve_call,
    flag_mismatch,
    walk_equations,
)
from .checks_elementary import _point_rows as point_rows

_I, _N = SYMBOLS["i"], SYMBOLS["n"]
_FUNCTIONS = {name: sp.Function(name) for name in ("P", "b", "p")}


def _parse(defn: CDefinition, text: str, key: str) -> sp.Basic:
    alpha = sp.Symbol(defn.parameter)
    symbols = {"i": _I, "n": _N, "t": cb.T, defn.parameter: alpha}
    try:
        return parse_formula(
            text, symbols, _FUNCTIONS, elementary=True, frequency=(defn.parameter,)
        )
    except ParseError as exc:
        raise RecordError(f"key {key}: {exc}") from None


def _function(defn: CDefinition, j: int) -> sp.Expr:
    """b_j as a SymPy function of the family's own t and alpha (t on [0, alpha], or u on
    [0, 1] with t = alpha*u for a family written that way)."""
    alpha = sp.Symbol(defn.parameter)
    e = cb.as_function(defn.elems()[j], defn.hyperbolic).xreplace({cb.A: alpha})
    if defn.form == "unit":
        e = e.xreplace({cb.T: alpha * cb.T})
    return e


def _realise(defn: CDefinition, expr: sp.Basic, idx: int | None) -> sp.Expr:
    degree = defn.degree
    env = {_N: sp.Integer(degree)}
    if idx is not None:
        env[_I] = sp.Integer(idx)
    e = expr.xreplace(env)

    def basis(j: int, x: sp.Expr) -> sp.Expr:
        if not 0 <= j <= degree:
            return sp.Integer(0)
        f = _function(defn, j)
        return f if x == cb.T else f.xreplace({cb.T: x})

    def model(call: sp.Basic) -> sp.Basic:
        got = curve_call(call, degree, basis)
        if got is None:
            raise RecordError(f"{call}: not a function of these claims (P, b, p)")
        return got

    e = e.replace(lambda x: isinstance(x, sp.core.function.AppliedUndef), model)
    return e.doit()


def _gap(defn: CDefinition, expr: sp.Expr, what: str) -> tuple[cb.Elem, int]:
    """expr (a function of t, alpha and the points) in exact atoms, reduced: {} when zero;
    and the base L of its field (S, C = sin, cos of alpha/L: a claim with cos(alpha/2) is
    decided in Q(alpha, sin(alpha/2), cos(alpha/2)), cbezier.angle_base)."""
    elem, base = _atoms(defn, expr, what)
    return cb.normal(elem, defn.hyperbolic), base


def _atoms(defn: CDefinition, expr: sp.Expr, what: str) -> tuple[cb.Elem, int]:
    """As `_gap`, the coefficients not reduced (`cb.is_zero` decides them)."""
    alpha = sp.Symbol(defn.parameter)

    def fail(message: str) -> RecordError:
        return RecordError(f"{what}: {message}")

    base = cb.angle_base(expr, alpha, defn.form)
    if base > cb.MAX_HARMONIC:
        raise fail(
            f"a multiple of {alpha}/{base} inside sin or cos: fractions of {alpha} up to "
            f"{alpha}/{cb.MAX_HARMONIC} are decided"
        )

    stray = sorted(
        s.name for s in expr.free_symbols if s not in (cb.T, alpha) and not s.name.startswith("P_")
    )
    if stray:
        raise fail(f"unknown symbol {stray[0]!r}")
    elem, kinds = cb.to_atoms(expr, alpha, defn.form, fail, base)
    if kinds - {"hyp" if defn.hyperbolic else "trig"}:
        raise fail(
            f"{'trigonometric' if defn.hyperbolic else 'hyperbolic'} functions in a claim about "
            f"a {defn.space} family: not in its field"
        )
    return elem, base


def _show(defn: CDefinition, elem: cb.Elem, base: int = 1) -> str:
    alpha = sp.Symbol(defn.parameter)
    e = cb.as_function(elem, defn.hyperbolic, base).xreplace({cb.A: alpha})
    return str(sp.factor(e))


def equations(record: dict, defn: CDefinition) -> Outcome:
    def prepare(number: int, eq: dict) -> tuple[object, bool]:
        lhs = _parse(defn, eq["lhs"], f"equations[{number}].lhs")
        rhs = _parse(defn, eq["rhs"], f"equations[{number}].rhs")
        return (number, lhs, rhs), _I in (lhs.free_symbols | rhs.free_symbols)

    def gap(parsed: object, _degree: int, idx: int | None) -> str | None:
        number, lhs, rhs = parsed  # type: ignore[misc]
        where = f"equations[{number}]" + (f" at i = {idx}" if idx is not None else "")
        diff, base = _gap(defn, _realise(defn, lhs, idx) - _realise(defn, rhs, idx), where)
        return _show(defn, diff, base) if diff else None

    diffs, checked = walk_equations(
        record,
        (defn.degree,),
        prepare,
        gap,
        "for this family; the equation is checked at its degree (and every index i)",
        f"exact in Q({defn.parameter}, {defn.space} of {defn.parameter})",
    )
    return Outcome("mismatch" if diffs else "match", diffs, checked)


def symmetry(record: dict, defn: CDefinition) -> Outcome:
    """b_i(t) = b_(n-i)(alpha - t) for every i (the reflection of [0, alpha]; of [0, 1] for
    a family written on [0, 1]: the same identity in t = alpha*u)."""
    if record.get("swap"):
        raise RecordError(
            f"key swap: {defn.name!r} has no parameter to swap; its symmetry is "
            f"b_i(t) = b_(n-i)({defn.parameter} - t) (leave `swap` out)"
        )
    fs = defn.elems()
    n = defn.degree
    diffs = []
    for i, f in enumerate(fs):
        gap = cb.reflect(fs[n - i], defn.hyperbolic)
        for atom, v in f.items():
            cb.add_into(gap, atom, -v)
        gap = cb.normal(gap, defn.hyperbolic)
        if gap:
            diffs.append(
                f"i = {i}: b_(n-i)({defn.parameter} - t) - b_i(t) = {_show(defn, gap)} "
                "(in t on [0, " + defn.parameter + "])"
            )
            break
    checked = [f"b_i(t) = b_(n-i)({defn.parameter} - t), i = 0..{n}: exact"]
    return Outcome("mismatch" if diffs else "match", diffs, checked)


# --------------------------------------------------------------------------- energies


def _constant(defn: CDefinition, text: str, key: str) -> tuple[sp.Expr, int]:
    """A record's formula in alpha, sin(alpha), cos(alpha) (no t) as an exact (A, S, C)."""
    expr = _realise(defn, _parse(defn, text, key), None)
    elem, base = _atoms(defn, expr, f"key {key}")
    if any(not cb.is_zero(v, defn.hyperbolic) for a, v in elem.items() if a != (cb.POW, 0)):
        raise RecordError(f"key {key}: {text!r} depends on t (a function of the parameter only)")
    return elem.get((cb.POW, 0), sp.Integer(0)), base


def _in_base(value: sp.Expr, base: int, hyperbolic: bool) -> sp.Expr:
    """A number of the family's field Q(alpha, sin alpha, cos alpha) written in the field of
    alpha/base: sin(alpha) = sin(base*theta), cos(alpha) = cos(base*theta) (Chebyshev)."""
    if base == 1:
        return value
    c, s = cb.angle(base, hyperbolic)
    return value.xreplace({cb.S: s, cb.C: c})


def energy_matrix(record: dict, defn: CDefinition) -> Outcome:
    """G_ij = int b_i^(k) b_j^(k) over the family's own parameter (t on [0, alpha]; u on
    [0, 1] for a family written there: alpha^(2k-1) times the integral in t), each entry
    compared with derive's exact Gram matrix (formulas/cbezier.gram) in Q(alpha, S, C)."""
    degree, k, gram = record.get("n"), record.get("k"), record.get("gram")
    if degree is None or k is None or gram is None:
        raise RecordError("keys n, k and gram are required")
    if degree != defn.degree:
        raise RecordError(f"key n: {defn.name} has the one degree {defn.degree}")
    if not isinstance(k, int) or not 1 <= k <= defn.degree:
        raise RecordError(f"key k: an order of derivative 1..{defn.degree}")
    size = defn.degree + 1
    if len(gram) != size or any(len(row) != size for row in gram):
        raise RecordError(f"key gram: a {size} x {size} matrix")
    scale = cb.A ** (2 * k - 1) if defn.form == "unit" else sp.Integer(1)
    want = F.gram(defn, k)
    diffs = []
    for r, row in enumerate(gram):
        for c, text in enumerate(row):
            diff = _printed_differs(defn, text, f"gram[{r}][{c}]", want[r][c] * scale)
            if diff:
                diffs.append(f"G[{r}][{c}]: {diff}")
    checked = [
        f"the {size} x {size} Gram matrix of E_{k} in {defn.parameter}'s own parameter "
        f"({'u on [0, 1]' if defn.form == 'unit' else 't on [0, ' + defn.parameter + ']'}), "
        f"exact in Q({defn.parameter}, {defn.space} of {defn.parameter})"
    ]
    return Outcome("mismatch" if diffs else "match", diffs, checked)


def _printed_differs(defn: CDefinition, text: str, key: str, derived: sp.Expr) -> str | None:
    """None when the printed constant `text` (record key `key`) equals `derived` exactly in
    the family's field (modulo the circle or the hyperbola), else "printed ..., derived ..."."""
    got, base = _constant(defn, text, key)
    if cb.is_zero(got - _in_base(derived, base, defn.hyperbolic), defn.hyperbolic):
        return None
    return f"printed {text}, derived {F.show(cb.reduce(derived, defn.hyperbolic), defn)}"


def energy(record: dict, defn: CDefinition) -> Outcome:
    """E_k = sum over coordinates of P^T G_k(alpha) P for the record's rational control points,
    from derive's exact Gram matrix (formulas/cbezier.gram, in the family's own parameter as
    in `energy_matrix`), against the printed ``expression``: a function of alpha, sin and cos
    (or sinh and cosh) of alpha, decided exactly modulo the circle (the hyperbola)."""
    k, pts, text = record.get("k"), record.get("control_points"), record.get("expression")
    if k is None or not pts:
        raise RecordError("keys k and control_points are required")
    if not isinstance(k, int) or not 1 <= k <= defn.degree:
        raise RecordError(f"key k: an order of derivative 1..{defn.degree}")
    if len(pts) != defn.degree + 1:
        raise RecordError(f"key control_points: {defn.degree + 1} points for {defn.name}")
    if record.get("parameters"):
        raise RecordError(
            f"key parameters: E_{k} of {defn.name!r} is claimed as a function of "
            f"{defn.parameter} (its {defn.space} functions sit in the field); leave "
            "`parameters` out and write the expression in " + defn.parameter
        )
    if not text:
        raise RecordError(f"key expression: the claimed E_{k} as a function of {defn.parameter}")
    rows = point_rows(pts)
    scale = cb.A ** (2 * k - 1) if defn.form == "unit" else sp.Integer(1)
    gram = F.gram(defn, k)
    derived = sp.Integer(0)
    for dim in range(len(rows[0])):
        for a, ra in enumerate(rows):
            for c, rc in enumerate(rows):
                weight = ra[dim] * rc[dim]
                if weight:
                    derived += sp.Rational(weight.numerator, weight.denominator) * gram[a][c]
    derived *= scale
    diff = _printed_differs(defn, text, "expression", derived)
    diffs = [f"E_{k}: {diff}"] if diff else []
    checked = [
        f"E_{k} of the {len(rows)} control points in {len(rows[0])} coordinates, in "
        f"{defn.parameter}'s own parameter, exact in Q({defn.parameter}, {defn.space} of "
        f"{defn.parameter})"
    ]
    return Outcome("mismatch" if diffs else "match", diffs, checked)


# --------------------------------------------------------------------------- box properties


def _boxed(record: dict, defn: CDefinition) -> CDefinition:
    given = record.get("box")
    if not given:
        return defn
    if not isinstance(given, dict) or set(given) != {defn.parameter}:
        raise RecordError(f"key box: a table {{{defn.parameter} = interval}}")

    def fail(key: str, message: str) -> RecordError:
        return RecordError(f"key {key}: {message}")

    return cb.with_range(defn, str(given[defn.parameter]), f"box.{defn.parameter}", fail)


def nonnegative(record: dict, defn: CDefinition) -> Outcome:
    """b_i >= 0 on [0, alpha] for every alpha of the box: formulas/cbezier.nonnegative (a
    certified counterexample from point balls, or the certificate of cbezier_nonnegative)."""
    claimed = claimed_flag(record, "nonnegative")
    boxed = _boxed(record, defn)
    decided = F.nonnegative(boxed)
    where = f"{defn.parameter} in {boxed.range_text}"
    if decided["verdict"] not in (True, False):
        return Outcome("pending", [f"not decided by derive over {where}: {decided['reason']}"])
    diffs = flag_mismatch("nonnegative", claimed, decided["verdict"], decided)
    how = "certified" if decided["verdict"] else "a certified counterexample"
    return Outcome(
        "mismatch" if diffs else "match",
        diffs,
        [f"b_i >= 0 on [0, {defn.parameter}] for {where}: {how}"],
    )


def independence(record: dict, defn: CDefinition) -> Outcome:
    """The functions are linearly independent at every alpha of the box: the rank of the
    coefficient matrix over Q(alpha, S, C) (exact; the atoms are independent functions of t
    for alpha > 0), and with as many atoms as functions the determinant's numerator certified
    free of zeros on the box (cbezier_nonnegative.nonvanishing), its denominator too (a zero
    there is a singular point, where the basis is not defined)."""
    from ..formulas.cbezier_nonnegative import nonvanishing

    claimed = claimed_flag(record, "independent")
    boxed = _boxed(record, defn)
    where = f"every {defn.parameter} in {boxed.range_text}"
    rank, det = F.rank(boxed)
    size = boxed.degree + 1
    if rank < size:
        derived, how = False, f"rank {rank} of {size} over the field: dependent everywhere"
    elif det is None:
        return Outcome(
            "pending",
            [f"rank {size} over the field, but more atoms than functions: not decided for {where}"],
        )
    else:
        num, den = sp.fraction(sp.cancel(det))
        top, bottom = nonvanishing(boxed, sp.expand(num)), nonvanishing(boxed, sp.expand(den))
        if bottom["verdict"] is not True:
            return Outcome("pending", [f"the determinant's denominator on {where}: {bottom}"])
        if top["verdict"] == "not certified":
            return Outcome("pending", [f"the determinant on {where}: {top['reason']}"])
        derived = top["verdict"]
        how = (
            "the determinant certified free of zeros"
            if derived
            else f"the determinant changes sign between {defn.parameter} = {top['between']}"
        )
    diffs = [] if derived == claimed else [f"printed independent = {claimed}, derived {derived}"]
    return Outcome(
        "mismatch" if diffs else "match", diffs, [f"linear independence for {where}: {how}"]
    )


# --------------------------------------------------------------------------- joins


def _side_value(first: CDefinition, second: CDefinition, text: str, key: str) -> sp.Expr:
    """A join weight as written: n and m (the two degrees), the G constants alpha and d, the
    curves' parameters (first's parameter with suffix 1, second's with suffix 2) and sin/cos
    (sinh/cosh) of integer multiples of those, each in its own curve's field, converted to
    (alpha1, S1, C1, alpha2, S2, C2) exactly."""
    from ..formulas import cbezier_joins as J

    sides = {
        f"{first.parameter}1": (J.A1, J.S1, J.C1, first),
        f"{second.parameter}2": (J.A2, J.S2, J.C2, second),
    }
    symbols = {
        "n": sp.Integer(first.degree),
        "m": sp.Integer(second.degree),
        "alpha": J.G_ALPHA,
        "d": J.G_D,
        **{k: v[0] for k, v in sides.items()},
    }
    try:
        expr = parse_formula(text, symbols, {}, elementary=True, frequency=tuple(sides))
    except ParseError as exc:
        raise RecordError(f"key {key}: {exc}") from None
    swap = {}
    for call in sorted(expr.atoms(sp.sin, sp.cos, sp.sinh, sp.cosh), key=str):
        arg = call.args[0]
        for name, (a, s, c, defn) in sides.items():
            ratio = sp.cancel(arg / a)
            if ratio.is_Integer and 0 < abs(ratio) <= cb.MAX_HARMONIC:
                if isinstance(call, sp.sinh | sp.cosh) != defn.hyperbolic:
                    written = call.func(sp.Symbol(name) * ratio)
                    raise RecordError(
                        f"key {key}: {written} is not in the field of {name} "
                        f"({defn.name!r} is {defn.space})"
                    )
                cm, sm = cb.angle(int(ratio), defn.hyperbolic)
                value = cm if isinstance(call, sp.cos | sp.cosh) else sm
                swap[call] = value.xreplace({cb.C: c, cb.S: s})
                break
        else:
            raise RecordError(
                f"key {key}: {call}: the argument is not an integer multiple of "
                + " or ".join(sides)
            )
    return expr.xreplace(swap)


def _pair(pair: str, defn: CDefinition) -> tuple[CDefinition, CDefinition]:
    """The two C-Bezier families of `pair` ("first>second"), one of them the record's own;
    the other defined in this run (its family file given to verify too)."""
    from .claim_families import SEVERAL_FAMILIES

    names = pair.split(">")
    if len(names) != 2 or defn.name not in names:
        raise RecordError(
            f"key pair: {pair!r}: 'first>second' with {defn.name!r} on one side "
            f"(e.g. {defn.name}>{defn.name})"
        )
    found = []
    for name in names:
        other = SEVERAL_FAMILIES.get(name.strip())
        if not isinstance(other, CDefinition):
            raise RecordError(
                f"key pair: {name.strip()!r}: joins of {defn.name!r} are decided with C-Bezier "
                "families (the parameter is the length of the domain or sits inside sin/cos) "
                "defined in this run, given to verify as FAMILY.toml files; joins with built-in, "
                "polynomial or fixed-domain trigonometric families are not decided for them"
            )
        found.append(other)
    return found[0], found[1]


def join(record: dict, defn: CDefinition) -> Outcome:
    """several_join between two C-Bezier curves, of this family or of this one and another
    C-Bezier family of the run (formulas/cbezier_joins.py): each printed weight against the
    derived one, exactly; a derived weight the record leaves out is a discrepancy too."""
    from ..formulas import cbezier_joins as J

    pair, continuity = record.get("pair"), record.get("continuity")
    claimed = record.get("join_weights")
    if not isinstance(pair, str) or continuity not in J.ORDER:
        raise RecordError("keys pair ('first>second') and continuity (C1, C2, G1, G2) are required")
    first, second = _pair(pair, defn)
    if record.get("n") not in (None, first.degree):
        raise RecordError(f"key n: {first.name} has the one degree {first.degree}")
    if not isinstance(claimed, dict) or not claimed:
        raise RecordError("key join_weights: a table {'row,src,k': formula} is required")
    try:
        derived = J.weights(first, continuity, second)
    except ValueError as exc:
        return Outcome("mismatch", [f"derive finds no {continuity} weights: {exc}"])
    diffs, checked = [], []
    space = (
        f"their {first.space} functions"
        if first.hyperbolic == second.hyperbolic
        else f"the {first.space} and {second.space} functions"
    )
    for key in sorted(set(claimed) | set(derived)):
        want = derived.get(key, sp.Integer(0))
        if key not in claimed:
            diffs.append(
                f"{pair} {continuity} weight {key}: not printed, derived "
                f"{J.show(want, first, second)}"
            )
            continue
        got = _side_value(first, second, claimed[key], f"join_weights.{key}")
        if J.reduce2(got - want, first.hyperbolic, second.hyperbolic) != 0:
            diffs.append(
                f"{pair} {continuity} weight {key}: printed {claimed[key]}, derived "
                f"{J.show(want, first, second)}"
            )
        checked.append(
            f"{pair} {continuity} weight {key}: exact in Q({first.parameter}1, "
            f"{second.parameter}2, {space}, alpha, d)"
        )
    return Outcome("mismatch" if diffs else "match", diffs, checked)
