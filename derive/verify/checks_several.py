"""Claims about a family in several shape parameters, plain or indexed (lam(i)) (issue #30).

Records about such a family use the claim kinds below. Their formulas are in the family's own
names: the parameters (``lam``, ``mu``), or ``lam(k)`` for an indexed family, where an
index outside the family's indices reads as 0. They may also use the control points
``P(j)``, the basis ``b(j, n, x)`` and the curve ``p(x)``, with ``Derivative`` and ``Subs``.
Each equation is instantiated at every degree of the family, and at every index i = 0..n
when it mentions i. Both sides are then evaluated from the derived basis
(derive/families/engine.py, at the degree's expansion for an indexed family) and compared
exactly. The record gives the claim; nothing in it is trusted.

* ``several_basis``: ``equations``, e.g. ``b(i, n, t) = ...``;
* ``several_end_conditions``: ``equations`` about p and its derivatives at t = 0, 1;
* ``several_symmetry``: ``swap`` = {parameter: formula} (``"lam(k)" = "lam(n + 1 - k)"``
  for an indexed family), claiming b_i(t; x) = b_{n-i}(1 - t; swap(x));
* ``several_energy_matrix``: ``n``, ``k`` and ``gram``, the matrix
  G_ij = int_0^1 b_i^(k) b_j^(k) dt with entries formulas in the parameters (E_k = sum
  G_ij P_i . P_j);
* ``several_energy``: ``k``, ``control_points``, ``parameters`` {name: value} and
  ``expression``, the value of E_k there;
* ``several_optimum``: ``k``, ``control_points`` and ``parameters``, the claimed minimiser of
  E_k over the closed box. It is checked against the certified minimum, which is exact
  Bernstein branch and bound (derive/formulas/box.py). With ``expression``, the claimed
  least energy is checked too.
"""

from __future__ import annotations

import re
from fractions import Fraction

import sympy as sp

from ..families.cbezier import CDefinition
from ..families.definition import Definition
from ..families.engine import basis_polys
from ..grammar import SYMBOLS, ParseError, parse_formula
from . import checks_cbezier as cbezier_checks
from . import checks_closed_n as closed_n
from . import checks_elementary as elementary
from .checks_core import KIND_FAMILIES, Outcome, checker
from .checks_elementary import RecordError
from .claim_families import SEVERAL_FAMILIES

KINDS = (
    "several_basis",
    "several_end_conditions",
    "several_symmetry",
    "several_energy_matrix",
    "several_energy",
    "several_optimum",
    # trigonometric, hyperbolic and mixed families only (checks_elementary.py)
    "several_rational",
    "several_nonnegative",
    "several_independence",
)
for _kind in KINDS:
    KIND_FAMILIES[_kind] = (
        ("(families in several parameters)",),
        "it is about a family in several shape parameters (a records file defining one with "
        "`parameters = [...]`)",
    )

_I, _N, _T, _K = (SYMBOLS[x] for x in ("i", "n", "t", "k"))
_FUNCTIONS = {name: sp.Function(name) for name in ("P", "b", "p")}


def _defn(record: dict) -> Definition:
    return SEVERAL_FAMILIES[record["family"]]  # type: ignore[return-value]


def _parse(defn: Definition, text: str, key: str, extra: tuple[str, ...] = ()) -> sp.Basic:
    symbols = {"i": _I, "n": _N, "t": _T, "k": _K}
    functions = dict(_FUNCTIONS)
    if defn.indexed is not None:
        name = defn.indexed.name  # type: ignore[attr-defined]
        functions[name] = sp.Function(name)
    else:
        symbols.update({x: sp.Symbol(x) for x in defn.parameters})
    symbols.update({x: sp.Symbol(x) for x in extra})
    try:
        return parse_formula(text, symbols, functions)
    except ParseError as exc:
        raise RecordError(f"key {key}: {exc}") from None


def _realise(defn: Definition, expr: sp.Basic, degree: int, idx: int | None) -> sp.Expr:
    """expr at degree n (and index i): parameters, points, b and p from the derivation."""
    at = defn.at_degree(degree)
    params = at.symbols
    env = {_N: sp.Integer(degree)}
    if idx is not None:
        env[_I] = sp.Integer(idx)
    e = expr.xreplace(env)
    polys = basis_polys(at, degree)
    gens = polys[0].gens  # t, then the parameters

    def basis(j: int, x: sp.Expr) -> sp.Expr:
        if not 0 <= j <= degree:
            return sp.Integer(0)
        return polys[j].as_expr().xreplace({gens[0]: x}) if x != _T else polys[j].as_expr()

    def model(call: sp.Basic) -> sp.Basic:
        name = call.func.__name__
        args = call.args
        if defn.indexed is not None and name == defn.indexed.name:  # type: ignore[attr-defined]
            k = elementary.integer_index(args[0], f"the index of {name}(...)")
            return sp.Symbol(f"{name}_{k}") if sp.Symbol(f"{name}_{k}") in params else sp.Integer(0)
        got = elementary.curve_call(call, degree, basis)
        if got is not None:
            return got
        raise RecordError(f"{call}: not a function of these claims")  # pragma: no cover

    e = e.replace(lambda x: isinstance(x, sp.core.function.AppliedUndef), model)
    return sp.expand(e.doit())


def _equations(record: dict) -> Outcome:
    defn = _defn(record)
    parsed = []

    def prepare(number: int, eq: dict) -> tuple[object, bool]:
        lhs = _parse(defn, eq["lhs"], f"equations[{number}].lhs")
        rhs = _parse(defn, eq["rhs"], f"equations[{number}].rhs")
        parsed.append((eq["lhs"], eq["rhs"], lhs, rhs))
        return (lhs, rhs), _I in (lhs.free_symbols | rhs.free_symbols)

    def gap(sides: object, degree: int, idx: int | None) -> str | None:
        lhs, rhs = sides  # type: ignore[misc]
        diff = sp.expand(_realise(defn, lhs, degree, idx) - _realise(defn, rhs, degree, idx))
        return str(diff) if diff != 0 else None

    diffs, checked = elementary.walk_equations(
        record,
        defn.degrees,
        prepare,
        gap,
        "for a family in several parameters; the equation is checked at every degree (and index i)",
        "exact",
    )
    if record["claim"].endswith("several_end_conditions") and closed_n.has_closed_forms(defn):
        more, also = closed_n.general_equations(defn, parsed)  # and for a general n
        diffs, checked = diffs + more, checked + also
    return Outcome("mismatch" if diffs else "match", diffs, checked)


@checker("several_basis", fits=lambda rec: "equations" in rec)
def check_several_basis(record: dict, _context: object) -> Outcome:
    if isinstance(SEVERAL_FAMILIES[record["family"]], CDefinition):  # checks_cbezier.py
        return cbezier_checks.equations(record, SEVERAL_FAMILIES[record["family"]])
    if _defn(record).elementary:  # sin, cos, ...: exact atoms (checks_elementary.py)
        return elementary.equations(record, _defn(record))
    return _equations(record)


@checker("several_end_conditions", fits=lambda rec: "equations" in rec)
def check_several_end_conditions(record: dict, _context: object) -> Outcome:
    if isinstance(SEVERAL_FAMILIES[record["family"]], CDefinition):  # checks_cbezier.py
        return cbezier_checks.equations(record, SEVERAL_FAMILIES[record["family"]])
    if _defn(record).elementary:  # sin, cos, ...: exact atoms (checks_elementary.py)
        return elementary.equations(record, _defn(record))
    return _equations(record)


_ONE = re.compile(r"^([A-Za-z][A-Za-z0-9_]*)(?:\(k\))?$")


@checker("several_symmetry")
def check_several_symmetry(record: dict, _context: object) -> Outcome:
    if isinstance(SEVERAL_FAMILIES[record["family"]], CDefinition):  # checks_cbezier.py
        return cbezier_checks.symmetry(record, SEVERAL_FAMILIES[record["family"]])
    if _defn(record).elementary:  # sin, cos, ...: exact atoms (checks_elementary.py)
        return elementary.symmetry(record, _defn(record))
    defn = _defn(record)
    swap = record.get("swap")
    if not swap:
        raise RecordError("key swap: the parameter substitution {name: formula} is required")
    diffs, count = [], 0
    for degree in defn.degrees:
        at = defn.at_degree(degree)
        subs = {}
        for key, text in swap.items():
            m = _ONE.match(key)
            name = m.group(1) if m else key
            if defn.indexed is not None:
                if key != f"{name}(k)" or name != defn.indexed.name:  # type: ignore[attr-defined]
                    raise RecordError(f"key swap.{key}: write {defn.indexed.name}(k)")  # type: ignore[attr-defined]
                expr = _parse(defn, text, f"swap.{key}")
                for sym in at.symbols:
                    k = int(sym.name.rsplit("_", 1)[1])
                    subs[sym] = _realise(defn, expr.xreplace({_K: k}), degree, None)
            else:
                if key not in defn.parameters:
                    raise RecordError(f"key swap.{key}: not a parameter ({defn.parameters})")
                subs[sp.Symbol(key)] = _realise(
                    defn, _parse(defn, text, f"swap.{key}"), degree, None
                )
        missing = [s.name for s in at.symbols if s not in subs]
        if missing:
            raise RecordError(f"key swap: no image of {missing[0]}")
        polys = basis_polys(at, degree)
        for j, p in enumerate(polys):
            q = polys[degree - j].as_expr().subs({**subs, _T: 1 - _T}, simultaneous=True)
            count += 1
            gap = sp.expand(p.as_expr() - q)
            if gap != 0:
                diffs.append(f"n = {degree}, i = {j}: b_i(t; x) - b_(n-i)(1 - t; swap(x)) = {gap}")
                break
    checked = [f"b_i(t; x) = b_(n-i)(1 - t; swap(x)): {count} functions, exact"]
    return Outcome("mismatch" if diffs else "match", diffs, checked)


def _gram(at: Definition, degree: int, k: int) -> list[list[sp.Expr]]:
    polys = [sp.Poly(p.as_expr(), _T) for p in basis_polys(at, degree)]
    out = []
    for p in polys:
        row = []
        for q in polys:
            prim = (p.diff((_T, k)) * q.diff((_T, k))).integrate()
            row.append(sp.expand((prim.eval(1) - prim.eval(0)).as_expr()))
        out.append(row)
    return out


@checker("several_energy_matrix")
def check_several_energy_matrix(record: dict, _context: object) -> Outcome:
    if isinstance(SEVERAL_FAMILIES[record["family"]], CDefinition):  # checks_cbezier.py
        return cbezier_checks.energy_matrix(record, SEVERAL_FAMILIES[record["family"]])
    if _defn(record).elementary:  # sin, cos, ...: exact atoms (checks_elementary.py)
        return elementary.energy_matrix(record, _defn(record))
    defn = _defn(record)
    degree, k = record.get("n"), record.get("k")
    gram = record.get("gram")
    if degree is None or k is None or gram is None:
        raise RecordError("keys n, k and gram are required")
    if degree not in defn.degrees:
        raise RecordError(
            f"key n: degree {degree} is outside {elementary.degrees_text(defn.degrees)}"
        )
    want = _gram(defn.at_degree(degree), degree, k)
    if len(gram) != degree + 1 or any(len(row) != degree + 1 for row in gram):
        raise RecordError(f"key gram: a {degree + 1} x {degree + 1} matrix")
    diffs = []
    for r, row in enumerate(gram):
        for c, text in enumerate(row):
            got = _realise(defn, _parse(defn, text, f"gram[{r}][{c}]"), degree, None)
            if sp.expand(got - want[r][c]) != 0:
                diffs.append(f"G[{r}][{c}]: printed {text}, derived {want[r][c]}")
    checked = [f"the {degree + 1} x {degree + 1} Gram matrix of E_{k} at n = {degree}, exact"]
    return Outcome("mismatch" if diffs else "match", diffs, checked)


def _energy_setup(record: dict):
    defn = _defn(record)
    k, pts = record.get("k"), record.get("control_points")
    if k is None or not pts:
        raise RecordError("keys k and control_points are required")
    degree = len(pts) - 1
    if degree not in defn.degrees:
        raise RecordError(
            f"key control_points: degree {degree} is outside "
            f"{elementary.degrees_text(defn.degrees)}"
        )
    rows = [[Fraction(_number(v, "control_points")) for v in row] for row in pts]
    at = defn.at_degree(degree)
    gram = _gram(at, degree, k)
    energy = sp.Integer(0)
    for dim in range(len(rows[0])):
        for a, ra in enumerate(rows):
            for c, rc in enumerate(rows):
                energy += sp.Rational(ra[dim] * rc[dim]) * gram[a][c]
    return defn, at, degree, sp.Poly(sp.expand(energy), *at.symbols)


def _number(text: str, key: str) -> sp.Rational:
    e = parse_formula(text, {}, {})
    if not e.is_Rational:
        raise RecordError(f"key {key}: {text!r} is not an exact number")
    return e


def _parameters(record: dict, defn: Definition, at: Definition, degree: int) -> dict:
    given = record.get("parameters")
    if not given:
        raise RecordError("key parameters: the parameter values {name: value} are required")
    values = {}
    for key, text in given.items():
        if defn.indexed is not None:
            m = re.match(rf"^{defn.indexed.name}\((\d+)\)$", key)  # type: ignore[attr-defined]
            name = f"{defn.indexed.name}_{m.group(1)}" if m else key  # type: ignore[attr-defined]
        else:
            name = key
        sym = sp.Symbol(name)
        if sym not in at.symbols:
            raise RecordError(f"key parameters.{key}: not a parameter at n = {degree}")
        values[sym] = _number(text, f"parameters.{key}")
    missing = [s.name for s in at.symbols if s not in values]
    if missing:
        raise RecordError(f"key parameters: no value of {missing[0]}")
    return values


@checker("several_energy")
def check_several_energy(record: dict, _context: object) -> Outcome:
    if isinstance(SEVERAL_FAMILIES[record["family"]], CDefinition):  # checks_cbezier.py
        return cbezier_checks.energy(record, SEVERAL_FAMILIES[record["family"]])
    if _defn(record).elementary:  # sin, cos, ...: exact atoms (checks_elementary.py)
        return elementary.energy(record, _defn(record))
    defn, at, degree, energy = _energy_setup(record)
    values = _parameters(record, defn, at, degree)
    claimed = (
        _number(record.get("expression", ""), "expression") if record.get("expression") else None
    )
    if claimed is None:
        raise RecordError("key expression: the claimed value of E_k is required")
    got = energy.as_expr().xreplace(values)
    ok = got == claimed
    diffs = [] if ok else [f"E_{record['k']}: printed {claimed}, derived {got}"]
    return Outcome(
        "match" if ok else "mismatch", diffs, [f"E_{record['k']} at n = {degree}, exact"]
    )


@checker("several_optimum")
def check_several_optimum(record: dict, _context: object) -> Outcome:
    if _defn(record).elementary:  # sin, cos, ...: exact atoms (checks_elementary.py)
        return elementary.optimum(record, _defn(record))
    defn, at, degree, energy = _energy_setup(record)
    values = _parameters(record, defn, at, degree)
    claimed_at = [Fraction(str(values[sp.Symbol(q.name)])) for q in at.params]
    diffs = elementary.outside_box(at.params, claimed_at)
    got = energy.as_expr().xreplace(values)
    at_claim = Fraction(str(got))
    best, gap = elementary.certified_box_minimum(
        energy, at.params, at_claim, f"{at_claim} ≈ {float(at_claim):.12g}", record["k"]
    )
    diffs += gap
    if record.get("expression"):
        claimed = _number(record["expression"], "expression")
        if claimed != got:
            diffs.append(f"E_{record['k']}: printed {claimed}, derived {got}")
    checked = [
        f"E_{record['k']} over the closed box at n = {degree}: certified lower bound "
        f"{float(best['lower']):.15g} (exact Bernstein branch and bound, 1e-12)"
    ]
    return Outcome("mismatch" if diffs else "match", diffs, checked)


def _elementary_only(kind: str, record: dict) -> Definition:
    defn = _defn(record)
    if not defn.elementary:
        raise RecordError(
            f"claim kind {kind!r} is about a trigonometric, hyperbolic or mixed family; "
            f"{defn.name!r} is polynomial (its derived document decides this)"
        )
    return defn


@checker("several_rational")
def check_several_rational(record: dict, _context: object) -> Outcome:
    return elementary.rational(record, _elementary_only("several_rational", record))


@checker("several_nonnegative")
def check_several_nonnegative(record: dict, _context: object) -> Outcome:
    if isinstance(SEVERAL_FAMILIES[record["family"]], CDefinition):  # checks_cbezier.py
        return cbezier_checks.nonnegative(record, SEVERAL_FAMILIES[record["family"]])
    return elementary.nonnegative(record, _elementary_only("several_nonnegative", record))


@checker("several_independence")
def check_several_independence(record: dict, _context: object) -> Outcome:
    if isinstance(SEVERAL_FAMILIES[record["family"]], CDefinition):  # checks_cbezier.py
        return cbezier_checks.independence(record, SEVERAL_FAMILIES[record["family"]])
    return elementary.independence(record, _elementary_only("several_independence", record))
