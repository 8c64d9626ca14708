"""Claims about a trigonometric, hyperbolic or mixed family (issue #30), checked exactly in
the atom representation of derive/algebra/atoms.py: no SymPy trigonometric simplification
decides anything here.

A records file that defines such a family (functions with sin, cos, sinh, cosh, exp) writes
its claims with the ``several_*`` kinds of checks_several.py, which hand them to this module,
and with three kinds of its own:

* ``several_rational``: ``substitution`` ("tan(t/2)"), ``rational_weights`` (the Bernstein
  coefficients of the common denominator in s) and ``rational_numerators`` (per basis function, the
  Bernstein coefficients in s of b_i * denominator, formulas in the parameters), compared
  with derive's exact rational Bezier form (derive/formulas/atom_family.py);
* ``several_nonnegative``: ``nonnegative`` (true or false) over the family's parameter box or
  over ``box`` = {parameter: interval}, compared with derive's exact decision;
* ``several_independence``: ``independent`` (true or false) over the parameter box.

Formulas in a record are read by derive's grammar with ``elementary=True`` (``pi``, and sin,
cos, sinh, cosh, exp of a rational multiple of t), plus the name ``e`` (Euler's number) for
the energies of a hyperbolic family. Each side is turned into an exact element: the control
points P(j) are extra parameters, b(j, n, x) and p(x) are the derived functions at x = t,
at x = lo + hi - t (the mirror) or at a number, ``Derivative`` is exact differentiation and
``Subs`` an exact value at an end (or a parameter set to a number). Two sides are equal when
their elements are equal: pi and e^W are transcendental, so numbers in Q[C, 1/C] are equal
exactly when their coefficients are.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from fractions import Fraction

import sympy as sp

from ..algebra import atoms as A
from ..families.definition import ENERGY_ORDERS, Definition, Parameter
from ..families.spaces import HYP, TRIG, _convert, _rate, space_of
from ..formulas import atom_family as F
from ..formulas import atom_independence, touching
from ..grammar import SYMBOLS, ParseError, parse_formula
from ..grammar.interval import Interval

_I, _N, _T, _K = (SYMBOLS[x] for x in ("i", "n", "t", "k"))
_E = sp.Symbol("e")  # Euler's number, in records about a hyperbolic family
_FUNCTIONS = {name: sp.Function(name) for name in ("P", "b", "p")}


class RecordError(ValueError):
    """A record that cannot be read as a claim about this family (names the key)."""


def integer_index(e: sp.Basic, what: str) -> int:
    """An index of a record's function once n and i are set (RecordError otherwise)."""
    if not e.is_Integer:
        raise RecordError(f"{what} {e} is not an integer once n and i are set")
    return int(e)


def curve_call(
    call: sp.Basic, degree: int, basis: Callable[[int, sp.Expr], sp.Expr]
) -> sp.Basic | None:
    """P(j), b(j, n, x) and p(x) of a claim about one degree's curve, in SymPy: the points as
    symbols P_j, b_j(x) from `basis` (0 outside 0..degree), p(x) = sum P_j b_j(x); None for
    any other function (the caller's own, such as an indexed parameter)."""
    name, args = call.func.__name__, call.args
    if name == "P":
        j = integer_index(args[0], "the index of P(...)")
        if not 0 <= j <= degree:
            raise RecordError(f"P({j}) at n = {degree}: no such control point")
        return sp.Symbol(f"P_{j}")
    if name == "b":
        j, deg = (integer_index(a, "an index of b(...)") for a in args[:2])
        if deg != degree:
            raise RecordError(f"b({j}, {deg}, ...) at n = {degree}: one degree per claim")
        return basis(j, args[2])
    if name == "p":
        terms = (sp.Symbol(f"P_{j}") * basis(j, args[0]) for j in range(degree + 1))
        return sum(terms, sp.Integer(0))
    return None


def walk_equations(
    record: dict,
    degrees: tuple[int, ...] | list[int],
    prepare: Callable[[int, dict], tuple[object, bool]],
    gap: Callable[[object, int, int | None], str | None],
    refusal: str,
    exactness: str,
) -> tuple[list[str], list[str]]:
    """The walk every `equations` claim shares: refuse `given`/`where` (refusal says why),
    prepare each equation once (prepare(number, eq) -> (parsed, mentions i)), then check it at
    every degree and, when it mentions i, every index i = 0..n: gap(parsed, n, i) is the
    difference shown, None when it is zero. The first failing index of a degree is reported.
    Returns (diffs, checked); RecordError when there is no equation."""
    diffs, checked = [], []
    for number, eq in enumerate(record.get("equations") or []):
        if "given" in eq or "where" in eq:
            raise RecordError(f"equations[{number}]: `given` and `where` are not read {refusal}")
        parsed, per_index = prepare(number, eq)
        count = 0
        for degree in degrees:
            for idx in range(degree + 1) if per_index else (None,):
                count += 1
                shown = gap(parsed, degree, idx)
                if shown is not None:
                    where = f"n = {degree}" + (f", i = {idx}" if idx is not None else "")
                    diffs.append(f"{eq['lhs']} = {eq['rhs']} fails at {where}: lhs - rhs = {shown}")
                    break
        checked.append(f"{eq['lhs']} = {eq['rhs']}: {count} instances, {exactness}")
    if not checked:
        raise RecordError("key equations: no equation")
    return diffs, checked


class Realiser:
    """A family's derived functions over a frame whose parameters are the family's, then the
    control points P_0 .. P_n (so a curve is an element too)."""

    def __init__(self, defn: Definition) -> None:
        self.defn = defn
        self.space = space_of(defn)
        F.check_partition(defn, self.space)
        self.n = len(self.space.functions) - 1
        self.nparams = len(defn.parameters)
        self.frame = dataclasses.replace(self.space.frame, nparams=self.nparams + self.n + 1)
        self.basis = [self.pad(b) for b in self.space.functions]
        self.names = list(defn.parameters) + [f"P_{j}" for j in range(self.n + 1)]
        self.index = {sp.Symbol(name): j for j, name in enumerate(defn.parameters)}

    @property
    def zero(self) -> A.Mono:
        return self.frame.zero_mono

    def pad(self, elem: A.Elem) -> A.Elem:
        extra = (0,) * (self.n + 1)
        return {(key[0] + extra, *key[1:]): v for key, v in elem.items()}  # type: ignore[misc]

    def number(self, value: A.Number) -> A.Elem:
        """A value (a polynomial in the parameters over Q[C, 1/C]) as a constant element."""
        out: A.Elem = {}
        for (mono, c), v in value.items():
            A.add_into(out, (mono, c, 0, 0, 0, A.COS), v)
        return out

    # ---- reading a formula
    def parse(self, text: str, key: str) -> sp.Basic:
        symbols = {"i": _I, "n": _N, "t": _T, "k": _K}
        symbols.update({name: sp.Symbol(name) for name in self.defn.parameters})
        if self.space.constant != "pi":
            symbols.setdefault("e", _E)
        try:
            return parse_formula(text, symbols, dict(_FUNCTIONS), elementary=True)
        except ParseError as exc:
            raise RecordError(f"key {key}: {exc}") from None

    def element(self, text: str, key: str, idx: int | None = None) -> A.Elem:
        env = {_N: sp.Integer(self.n)}
        if idx is not None:
            env[_I] = sp.Integer(idx)
        expr = self.parse(text, key).xreplace(env)
        try:
            return self.convert(expr)
        except A.AtomError as exc:
            raise RecordError(f"key {key}: {exc}") from None
        except RecordError as exc:
            raise RecordError(f"key {key}: {exc}") from None

    def point(self, x: sp.Basic) -> Fraction:
        """A point of t as a multiple of the domain's unit (pi or 1)."""
        q = x / sp.pi if self.frame.dom_pi else x
        if x == 0:
            return Fraction(0)
        if not q.is_Rational:
            unit = "a rational multiple of pi" if self.frame.dom_pi else "a rational number"
            raise RecordError(
                f"the point {x} is not {unit} (the domain is {self.defn.domain_text})"
            )
        return Fraction(int(q.p), int(q.q))

    def convert(self, e: sp.Basic) -> A.Elem:  # noqa: C901 - one case per kind of node
        frame = self.frame
        if isinstance(e, sp.Subs):
            body = self.convert(e.expr)
            # SymPy merges nested Subs into one; the values are numbers, so the order is free
            for var, at in zip(e.variables, e.point, strict=True):
                if var == _T:
                    body = self.number(A.value(body, frame, self.point(at)))
                elif var in self.index:
                    body = self.set_parameter(body, self.index[var], self.convert(at))
                else:
                    raise RecordError(f"{e}: Subs of {var}, neither t nor a parameter")
            return body
        if isinstance(e, sp.Derivative):
            body = self.convert(e.expr)
            for var, count in e.variable_count:
                if var != _T:
                    raise RecordError(f"{e}: a derivative in {var}, not in t")
                body = A.diff(body, frame, int(count))
            return body
        if isinstance(e, sp.Sum):
            return self.sum(e)
        if isinstance(e, sp.core.function.AppliedUndef):
            return self.call(e)
        if e == _T:
            return A.atom(frame, k=1)
        if e in self.index:
            return A.parameter(frame, self.index[e])
        if e == _E:
            return self.exp_power(Fraction(1), e)
        if e == sp.pi:
            return self.pi_power(1)
        if e.is_Rational:
            return A.constant(frame, Fraction(int(e.p), int(e.q)))
        if e.is_Add:
            out: A.Elem = {}
            for a in e.args:
                out = A.add(out, self.convert(a))
            return out
        if e.is_Mul:
            out = A.constant(frame)
            for a in e.args:
                out = A.mul(out, self.convert(a))
            return out
        if e.is_Pow:
            base, ex = e.base, e.exp
            if base == _E and ex.is_Rational:
                return self.exp_power(Fraction(int(ex.p), int(ex.q)), e)
            if base == sp.pi and ex.is_Integer:
                return self.pi_power(int(ex))
            if ex.is_Integer and ex >= 0:
                return A.power(self.convert(base), int(ex), frame)
            if ex.is_Integer and base.is_Rational:
                return A.constant(frame, Fraction(int(e.p), int(e.q)))
            raise RecordError(f"{e}: a division by a function of t or of a parameter")
        if isinstance(e, TRIG + HYP):
            return self.elementary(e)
        if e in (_N, _I, _K):
            raise RecordError(f"{e} is not set here (n is the family's degree, i an index)")
        raise RecordError(f"{e} is not a formula of these claims")

    def elementary(self, call: sp.Basic) -> A.Elem:
        space, frame = self.space, self.frame
        trig = isinstance(call, TRIG)
        if trig != space.trigonometric:
            kind = "trigonometric" if space.trigonometric else "hyperbolic"
            raise RecordError(f"{call}: not in the {kind} space of {self.defn.name}")
        rate, unit = _rate(call)
        mult = rate / frame.rate
        if unit != frame.rate_pi or mult.denominator != 1:
            w = f"{frame.rate}{'*pi' if frame.rate_pi else ''}"
            raise RecordError(f"{call}: its rate is not a multiple of the base rate {w}")
        return _convert(call, frame, {}, frame.rate)

    def pi_power(self, c: int) -> A.Elem:
        if self.space.constant != "pi":
            raise RecordError(f"pi in a claim about the {self.space.name} family {self.defn.name}")
        return {(self.zero, c, 0, 0, 0, A.COS): Fraction(1)}

    def exp_power(self, x: Fraction, e: sp.Basic) -> A.Elem:
        """e^x as a power of the family's constant C = e^W."""
        unit = self.frame.exp_unit
        if unit is None:
            raise RecordError(f"{e}: e enters only a claim about a hyperbolic family")
        ratio = x / unit
        if ratio.denominator != 1:
            raise RecordError(f"{e}: not an integer power of the constant exp({unit})")
        return {(self.zero, int(ratio), 0, 0, 0, A.COS): Fraction(1)}

    def set_parameter(self, elem: A.Elem, j: int, value: A.Elem) -> A.Elem:
        """The element with parameter j replaced by another element (a number, usually)."""
        out: A.Elem = {}
        for (mono, *rest), v in elem.items():
            e = mono[j]
            bare = tuple(0 if q == j else x for q, x in enumerate(mono))
            term = {(bare, *rest): v}  # type: ignore[dict-item]
            if e:
                term = A.mul(term, A.power(value, e, self.frame))
            out = A.add(out, term)
        return out

    def integer(self, e: sp.Basic, what: str) -> int:
        if not e.is_Integer:
            raise RecordError(f"{what} {e} is not an integer once n and i are set")
        return int(e)

    def at(self, elem: A.Elem, x: sp.Basic) -> A.Elem:
        """A function of t at x: t itself, the mirror lo + hi - t, or a number."""
        if x == _T:
            return elem
        if not x.has(_T):
            return self.number(A.value(elem, self.frame, self.point(x)))
        unit = sp.pi if self.frame.dom_pi else sp.Integer(1)
        mid = self.frame.lo + self.frame.hi
        if sp.expand(x - (sp.Rational(mid.numerator, mid.denominator) * unit - _T)) == 0:
            return A.reflect(elem, self.frame)
        raise RecordError(f"{x}: a function is read at t, at {mid * unit} - t or at a number")

    def call(self, app: sp.Basic) -> A.Elem:
        name, args = app.func.__name__, app.args
        if name == "P":
            j = self.integer(args[0], "the index of P(...)")
            if not 0 <= j <= self.n:
                raise RecordError(f"P({j}): no such control point (n = {self.n})")
            return A.parameter(self.frame, self.nparams + j)
        if name == "b":
            if len(args) != 3:
                raise RecordError(f"{app}: b takes (i, n, t)")
            j, deg = (self.integer(a, "an index of b(...)") for a in args[:2])
            if deg != self.n:
                raise RecordError(f"{app}: {self.defn.name} has the one degree {self.n}")
            return self.at(self.basis[j], args[2]) if 0 <= j <= self.n else {}
        if name == "p" and len(args) == 1:
            out: A.Elem = {}
            for j in range(self.n + 1):
                point = A.parameter(self.frame, self.nparams + j)
                out = A.add(out, A.mul(point, self.at(self.basis[j], args[0])))
            return out
        raise RecordError(f"{app}: not a function of these claims (P, b, p)")

    def sum(self, e: sp.Sum) -> A.Elem:
        body, limits = e.function, list(e.limits)
        var, lo, hi = limits[-1]
        lo_, hi_ = (self.integer(x, "a summation limit") for x in (lo, hi))
        inner = sp.Sum(body, *limits[:-1]) if len(limits) > 1 else body
        out: A.Elem = {}
        for value in range(lo_, hi_ + 1):
            out = A.add(out, self.convert(inner.xreplace({var: sp.Integer(value)})))
        return out

    def show(self, elem: A.Elem) -> str:
        terms = []
        for (mono, c, k, h, m, kind), v in sorted(elem.items()):
            parts = [str(v)]
            parts += [
                f"{x}**{e}" if e > 1 else x for x, e in zip(self.names, mono, strict=True) if e
            ]
            if c:
                parts.append(f"{self.space.constant}**{c}")
            if k:
                parts.append(f"t**{k}" if k > 1 else "t")
            w = f"{self.frame.rate}{'*pi' if self.frame.rate_pi else ''}"
            if h:
                parts.append(f"exp({h}*{w}*t)")
            if m:
                parts.append(f"{'cos' if kind == A.COS else 'sin'}({m}*{w}*t)")
            terms.append("*".join(parts))
        return " + ".join(terms) or "0"

    # ---- derived quantities
    def gram(self, k: int) -> list[list[A.Elem]]:
        """derive's Gram matrix of E_k (the document's energy table), summed over the
        parameter monomials: G_ij as an element, a polynomial in the parameters."""
        if k not in ENERGY_ORDERS:
            raise RecordError(f"key k: derive computes E_k for k in {ENERGY_ORDERS}")
        table = F.energies(self.space)[f"{self.n},{k}"]["gram"]
        size = self.n + 1
        out: list[list[A.Elem]] = [[{} for _ in range(size)] for _ in range(size)]
        extra = (0,) * (self.n + 1)
        for pair, mat in table.items():
            m1, m2 = (tuple(int(x) for x in part.split(",")) for part in pair.split("|"))
            mono = tuple(a + b for a, b in zip(m1, m2, strict=True)) + extra
            for r, row in enumerate(mat):
                for c, entry in enumerate(row):
                    items = [(entry, 0)] if isinstance(entry, str) else entry
                    for coef, power in items:
                        A.add_into(out[r][c], (mono, int(power), 0, 0, 0, A.COS), Fraction(coef))
        return out


_REALISERS: dict[str, Realiser] = {}


def realiser(defn: Definition) -> Realiser:
    if defn.name not in _REALISERS or _REALISERS[defn.name].defn != defn:
        _REALISERS[defn.name] = Realiser(defn)
    return _REALISERS[defn.name]


def _verdict(diffs: list[str], checked: list[str]):
    from .checks_core import Outcome

    return Outcome("mismatch" if diffs else "match", diffs, checked)


# --------------------------------------------------------------------------- the checks


def equations(record: dict, defn: Definition):
    real = realiser(defn)

    def prepare(number: int, eq: dict) -> tuple[object, bool]:
        keys = (f"equations[{number}].lhs", f"equations[{number}].rhs")
        mentions = any(
            _I in real.parse(eq[side], key).free_symbols
            for side, key in zip(("lhs", "rhs"), keys, strict=True)
        )
        return (eq["lhs"], eq["rhs"], keys), mentions

    def gap(parsed: object, _degree: int, idx: int | None) -> str | None:
        lhs_text, rhs_text, (lhs_key, rhs_key) = parsed  # type: ignore[misc]
        diff = A.add(real.element(lhs_text, lhs_key, idx), real.element(rhs_text, rhs_key, idx), -1)
        return real.show(diff) if diff else None

    diffs, checked = walk_equations(record, (real.n,), prepare, gap, "here", "exact (atoms)")
    return _verdict(diffs, checked)


def symmetry(record: dict, defn: Definition):
    """b_i(t; x) = b_(n-i)(lo + hi - t; swap(x)), with any substitution of the parameters."""
    real = realiser(defn)
    swap = record.get("swap")
    if not swap:
        raise RecordError("key swap: the parameter substitution {name: formula} is required")
    images = {}
    for key, text in swap.items():
        if key not in defn.parameters:
            raise RecordError(f"key swap.{key}: not a parameter ({', '.join(defn.parameters)})")
        images[defn.parameters.index(key)] = real.element(text, f"swap.{key}")
    missing = [name for j, name in enumerate(defn.parameters) if j not in images]
    if missing:
        raise RecordError(f"key swap: no image of {missing[0]}")
    diffs = []
    for i in range(real.n + 1):
        mirrored = A.reflect(real.basis[real.n - i], real.frame)
        out: A.Elem = {}
        for (mono, *rest), v in mirrored.items():  # all parameters replaced at once
            term: A.Elem = {(real.zero, *rest): v}  # type: ignore[dict-item]
            for j, e in enumerate(mono[: real.nparams]):
                if e:
                    term = A.mul(term, A.power(images[j], e, real.frame))
            out = A.add(out, term)
        gap = A.add(real.basis[i], out, -1)
        if gap:
            diffs.append(f"i = {i}: b_i(t; x) - b_(n-i)(mirror; swap(x)) = {real.show(gap)}")
            break
    checked = [f"b_i(t; x) = b_(n-i)({defn.domain_text} mirrored; swap(x)): exact (atoms)"]
    return _verdict(diffs, checked)


def energy_matrix(record: dict, defn: Definition):
    real = realiser(defn)
    degree, k, gram = record.get("n"), record.get("k"), record.get("gram")
    if degree is None or k is None or gram is None:
        raise RecordError("keys n, k and gram are required")
    if degree != real.n:
        raise RecordError(f"key n: {defn.name} has the one degree {real.n}")
    size = real.n + 1
    if len(gram) != size or any(len(row) != size for row in gram):
        raise RecordError(f"key gram: a {size} x {size} matrix")
    want = real.gram(k)
    diffs = []
    for r, row in enumerate(gram):
        for c, text in enumerate(row):
            got = real.element(text, f"gram[{r}][{c}]")
            if got != want[r][c]:
                diffs.append(f"G[{r}][{c}]: printed {text}, derived {real.show(want[r][c])}")
    checked = [
        f"the {size} x {size} Gram matrix of E_{k}, entries in Q[{real.space.constant}, "
        f"1/{real.space.constant}] and the parameters, exact"
    ]
    return _verdict(diffs, checked)


def _energy_at(record: dict, real: Realiser, values: list[Fraction]) -> A.Elem:
    """E_k of the record's control points at parameter values, an exact constant."""
    pts = record.get("control_points")
    k = record.get("k")
    if k is None or not pts:
        raise RecordError("keys k and control_points are required")
    if len(pts) != real.n + 1:
        raise RecordError(f"key control_points: {real.n + 1} points for {real.defn.name}")
    rows = _point_rows(pts)
    gram = real.gram(k)
    point = tuple(values) + (Fraction(0),) * (real.n + 1)
    total: A.Elem = {}
    for dim in range(len(rows[0])):
        for a, ra in enumerate(rows):
            for c, rc in enumerate(rows):
                total = A.add(total, A.at_parameters(gram[a][c], point), ra[dim] * rc[dim])
    return total


def _point_rows(pts: list) -> list[list[Fraction]]:
    rows = [
        [_rational(v, f"control_points[{j}][{d}]") for d, v in enumerate(row)]
        for j, row in enumerate(pts)
    ]
    if not rows[0] or any(len(row) != len(rows[0]) for row in rows):
        raise RecordError("key control_points: every point has the same number of coordinates")
    return rows


def _rational(text: str, key: str) -> Fraction:
    try:
        e = parse_formula(text, {}, {})
    except ParseError as exc:
        raise RecordError(f"key {key}: {exc}") from None
    if not e.is_Rational:
        raise RecordError(f"key {key}: {text!r} is not an exact rational number")
    return Fraction(int(e.p), int(e.q))


def _values(record: dict, defn: Definition) -> list[Fraction]:
    given = record.get("parameters")
    if not given:
        raise RecordError("key parameters: the parameter values {name: value} are required")
    unknown = [key for key in given if key not in defn.parameters]
    if unknown:
        raise RecordError(f"key parameters.{unknown[0]}: not a parameter")
    missing = [name for name in defn.parameters if name not in given]
    if missing:
        raise RecordError(f"key parameters: no value of {missing[0]}")
    return [_rational(given[name], f"parameters.{name}") for name in defn.parameters]


def energy(record: dict, defn: Definition):
    real = realiser(defn)
    got = _energy_at(record, real, _values(record, defn))
    if not record.get("expression"):
        raise RecordError("key expression: the claimed value of E_k is required")
    claimed = real.element(record["expression"], "expression")
    diffs = (
        []
        if got == claimed
        else [f"E_{record['k']}: printed {record['expression']}, derived {real.show(got)}"]
    )
    return _verdict(
        diffs, [f"E_{record['k']} in Q[{real.space.constant}, 1/{real.space.constant}], exact"]
    )


def _approximate(elem: A.Elem, real: Realiser, digits: int = 60) -> sp.Poly:
    """E(params) with C replaced by a rational within 10^-digits of it: rational coefficients
    for derive's exact Bernstein branch and bound."""
    import mpmath

    with mpmath.workdps(digits + 20):
        if real.space.constant == "pi":
            value = mpmath.pi
        else:
            unit = real.frame.exp_unit
            assert unit is not None
            value = mpmath.exp(mpmath.mpf(unit.numerator) / unit.denominator)
        approx = Fraction(int(mpmath.nint(value * 10**digits)), 10**digits)
    syms = sp.symbols(f"x0:{real.nparams}")
    expr = sp.Integer(0)
    for (mono, c, k, h, m, _), v in elem.items():
        assert not (k or h or m)
        term = sp.Rational(v.numerator, v.denominator) * sp.Rational(
            (approx**c).numerator, (approx**c).denominator
        )
        for s, e in zip(syms, mono[: real.nparams], strict=True):
            term *= s**e
        expr += term
    return sp.Poly(expr, *syms)


def degrees_text(degrees: range) -> str:
    """A family's degrees as its definition writes them ("2..8"), for messages."""
    return f"{degrees.start}..{degrees.stop - 1}"


def claimed_flag(record: dict, key: str) -> bool:
    """A record's printed true/false claim under `key` (refused if it is anything else)."""
    claimed = record.get(key)
    if not isinstance(claimed, bool):
        raise RecordError(f"key {key}: true or false is required")
    return claimed


def flag_mismatch(key: str, claimed: bool, derived: object, decided: dict) -> list[str]:
    """The mismatch line of a true/false claim the derivation decided otherwise, with the
    derivation's counterexample when it gives one."""
    if derived == claimed:
        return []
    extra = f": counterexample {decided['counterexample']}" if "counterexample" in decided else ""
    return [f"printed {key} = {claimed}, derived {derived}{extra}"]


def outside_box(params, values) -> list[str]:
    """The claimed parameter values outside their closed ranges, one line each."""
    return [
        f"{q.name} = {v} is outside [{q.lo}, {q.hi}]"
        for q, v in zip(params, values, strict=True)
        if not q.lo <= v <= q.hi
    ]


def certified_box_minimum(
    energy: sp.Poly, params, at_claim: Fraction, shown: str, k: object
) -> tuple[dict, list[str]]:
    """E_k (an exact polynomial in the parameters) at the claimed point against its certified
    minimum over the closed box of `params` (exact Bernstein branch and bound to 1e-12
    relative): the minimum, and the mismatch line if the claim is above it by more."""
    from lambda_bezier.hazmat import box_bernstein

    from ..formulas import box

    boxed = [(q.lo, q.hi) for q in params]
    best = box_bernstein.minimum(box.dense(energy), boxed, Fraction(1, 10**12), 20_000)
    if not best["certified"]:
        raise RecordError("the minimum over the box was not certified within the budget")
    tol = Fraction(1, 10**12) * max(Fraction(1), abs(best["value"]))
    if at_claim - best["lower"] <= tol:
        return best, []
    where = ", ".join(f"{q.name} = {v}" for q, v in zip(params, best["point"], strict=True))
    return best, [
        f"E_{k} at the printed parameters is {shown}; the certified minimum over the box is "
        f"{float(best['value']):.12g} at {where}"
    ]


def optimum(record: dict, defn: Definition):
    """The claimed minimiser of E_k over the closed box: E_k there against the certified
    minimum (derive's exact Bernstein branch and bound on E_k with pi or e^W to 60 digits;
    that approximation moves E_k by far less than the 1e-12 tolerance)."""
    real = realiser(defn)
    values = _values(record, defn)
    diffs = outside_box(defn.params, values)
    pts = record.get("control_points") or []
    k = record.get("k")
    if k is None or not pts:
        raise RecordError("keys k and control_points are required")
    rows = _point_rows(pts)
    if len(rows) != real.n + 1:
        raise RecordError(f"key control_points: {real.n + 1} points for {defn.name}")
    gram = real.gram(k)
    total: A.Elem = {}
    for dim in range(len(rows[0])):
        for a, ra in enumerate(rows):
            for c, rc in enumerate(rows):
                total = A.add(total, gram[a][c], ra[dim] * rc[dim])
    poly = _approximate(total, real)
    at_claim = Fraction(
        str(poly.eval(tuple(sp.Rational(v.numerator, v.denominator) for v in values)))
    )
    best, gap = certified_box_minimum(poly, defn.params, at_claim, f"{float(at_claim):.12g}", k)
    diffs += gap
    if record.get("expression"):
        claimed = real.element(record["expression"], "expression")
        got = _energy_at(record, real, values)
        if claimed != got:
            diffs.append(f"E_{k}: printed {record['expression']}, derived {real.show(got)}")
    checked = [
        f"E_{k} over the closed box: certified lower bound {float(best['lower']):.15g} "
        f"(exact Bernstein branch and bound, 1e-12, {real.space.constant} to 60 digits)"
    ]
    return _verdict(diffs, checked)


def rational(record: dict, defn: Definition):
    real = realiser(defn)
    form = F.rational_form(real.space)
    if "reason" in form:
        return _verdict([f"derive finds no exact rational Bezier form: {form['reason']}"], [])
    n = str(real.n)
    diffs, checked = [], []
    if record.get("substitution", form["substitution"]) != form["substitution"]:
        diffs.append(
            f"substitution: printed {record['substitution']}, derived {form['substitution']}"
        )
    weights = record.get("rational_weights")
    numerators = record.get("rational_numerators")
    if weights is None and numerators is None:
        raise RecordError("keys rational_weights and/or rational_numerators are required")
    if weights is not None:
        want = [Fraction(w) for w in form["weights"][n]]
        got = [_rational(w, f"rational_weights[{j}]") for j, w in enumerate(weights)]
        if got != want:
            diffs.append(f"weights: printed {weights}, derived {[str(w) for w in want]}")
        checked.append(f"the {len(want)} weights of the degree-{form['degree'][n]} form, exact")
    if numerators is not None:
        table = form["numerators"][n]
        size = form["degree"][n] + 1
        if len(numerators) != real.n + 1 or any(len(row) != size for row in numerators):
            raise RecordError(f"key rational_numerators: a {real.n + 1} x {size} matrix")
        extra = (0,) * (real.n + 1)
        for i, row in enumerate(numerators):
            for j, text in enumerate(row):
                want_e: A.Elem = {}
                for key, mat in table.items():
                    mono = tuple(int(x) for x in key.split(",")) + extra
                    A.add_into(want_e, (mono, 0, 0, 0, 0, A.COS), Fraction(mat[i][j]))
                got_e = real.element(text, f"rational_numerators[{i}][{j}]")
                if got_e != want_e:
                    diffs.append(
                        f"rational_numerators[{i}][{j}]: printed {text}, "
                        f"derived {real.show(want_e)}"
                    )
        checked.append(f"the {real.n + 1} x {size} numerator coefficients, exact")
    return _verdict(diffs, checked)


def _boxed(record: dict, defn: Definition) -> Definition:
    """The definition with the record's `box` (a table {parameter: interval}) as its ranges."""
    given = record.get("box")
    if not given:
        return defn
    if not isinstance(given, dict):
        raise RecordError("key box: a table {parameter: interval}")
    params = []
    for q in defn.params:
        text = given.get(q.name)
        if text is None:
            params.append(q)
            continue
        try:
            iv = Interval.parse(text)
        except ValueError as exc:
            raise RecordError(f"key box.{q.name}: {exc}") from None
        params.append(
            Parameter(q.name, text, iv.lo, iv.hi, not iv.lo_open, not iv.hi_open, q.bernstein_at)
        )
    unknown = [key for key in given if key not in defn.parameters]
    if unknown:
        raise RecordError(f"key box.{unknown[0]}: not a parameter")
    return dataclasses.replace(defn, params=tuple(params))


def nonnegative(record: dict, defn: Definition):
    claimed = claimed_flag(record, "nonnegative")
    boxed = _boxed(record, defn)
    decided = touching.nonnegative_over_box(boxed, space_of(boxed))
    where = ", ".join(f"{q.name} in {q.range_text}" for q in boxed.params)
    if "reason" in decided:
        from .checks_core import Outcome

        return Outcome("pending", [f"not decided by derive: {decided['reason']}"])
    diffs = flag_mismatch("nonnegative", claimed, decided["nonnegative"], decided)
    how = (
        "certified (arb ball branch and bound)"
        if F.nonnegative_is_certified(space_of(boxed))
        and not decided.get("method", "").startswith("exact")
        else "exact"
    )
    return _verdict(diffs, [f"b_i >= 0 on {defn.domain_text} for {where}: {how}"])


def independence(record: dict, defn: Definition):
    claimed = claimed_flag(record, "independent")
    boxed = _boxed(record, defn)
    decided = atom_independence.independence(boxed, space_of(boxed))
    if "reason" in decided:
        from .checks_core import Outcome

        return Outcome("pending", [f"not decided by derive: {decided['reason']}"])
    diffs = []
    if decided["independent"] != claimed:
        diffs.append(
            f"printed independent = {claimed}, derived {decided['independent']} "
            f"(singular parameters: {decided.get('singular')})"
        )
    where = ", ".join(f"{q.name} in {q.range_text}" for q in boxed.params)
    return _verdict(diffs, [f"linear independence for every {where}: exact"])
