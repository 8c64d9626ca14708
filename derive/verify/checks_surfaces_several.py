"""Surface claims (issue #31) about a family in several shape parameters that a records file
defines: polynomial ones (checks_several.py's families) and trigonometric or hyperbolic ones
(the atoms of checks_elementary.py), plain or indexed (lam(i), polynomial).

The surface is S(u, v) = Σ P_ij b_i(u; x_u) b_j(v; x_v) over the square domain × domain, the
family's basis in both directions with its parameters renamed per direction: `lam` is
`lam_u` along u and `lam_v` along v (independent symbols). A record gives parameter values as
`parameters_u` / `parameters_v` = {lam = "1/2", mu = "0"} in the family's own names
({"lam(0)" = "1/2", ...} for an indexed family, every index of that direction's degree); its
formulas (the energy matrix's entries) use the renamed symbols (lam_0_u for lam(0) along u),
and `pi` or `e` for an atom family. Points `uv` are points of the family's domain ("pi/6");
in `corners` and `side`, 0 and 1 name the start and the end of the domain.

Every quantity is exact: a polynomial family's basis is SymPy polynomials from the family
engine; an atom family's values and integrals are numbers in Q[C, 1/C] (C = pi or e^W, as
checks_elementary.py decides them), written here as polynomials in a symbol C with integer
exponents, faithful because C is transcendental. Identities "for every parameter" use that
the u and v parameters are independent: a product a(x_u)·c(x_v) is zero exactly when a
factor is, and is 1 exactly when both are numbers with product 1.

* ``surface_basis``: `values` at `uv` (with `parameters_u`, `parameters_v`) and/or
  `sums_to_one` (at the record's `degrees`, else at every pair of the family's degrees);
* ``surface_boundary``: `side` and `line`, identically in the free variable and parameters;
* ``surface_corners``: `corners` [u, v, i, j]: S = P_ij there, for every parameter;
* ``surface_energy_matrix``: `energy`, `degrees` and `gram`, the full symmetric matrix Q with
  E = vec(P)ᵀ Q vec(P) (net read row by row), entries formulas, at `parameters_u` /
  `parameters_v` when given (else in the renamed symbols). Derived as the Kronecker sum of
  the curves' Gram matrices; for a polynomial family also by integrating the tensor-product
  basis directly, and the two must agree;
* ``surface_continuity``: `continuity` (C1, G1, C2), `n` (for a family of several degrees),
  `second_family` and `weights` [{row, source, k, weight}] in alpha, lam1, mu1, lam2, mu2
  (the parameters across the boundary of patch 1 and patch 2), against derive's curve join
  (derive/formulas/joins_several.py) applied column by column.
"""

from __future__ import annotations

import re
from fractions import Fraction

import sympy as sp

from ..algebra import atoms as A
from ..families.definition import Definition
from ..families.engine import basis_polys
from ..formulas import joins_several
from ..formulas.surface_energy import ENERGIES
from ..grammar import ParseError, parse_formula
from . import checks_elementary as elementary
from . import checks_joins_several
from .checks_core import Outcome, checker
from .checks_elementary import RecordError
from .checks_surfaces import SIDES
from .claim_families import SEVERAL_FAMILIES

C = sp.Symbol("C")  # the family's transcendental constant (pi or e^W) of an atom family
_X = {"u": sp.Symbol("u"), "v": sp.Symbol("v")}
_E = sp.Symbol("e")


def _several(record: dict) -> bool:
    return record["family"] in SEVERAL_FAMILIES


def _defn(record: dict) -> Definition:
    defn = SEVERAL_FAMILIES[record["family"]]
    if not isinstance(defn, Definition) or (defn.indexed is not None and defn.elementary):
        raise RecordError(f"surface claims are not decided for {defn.name!r}")
    if record.get("family_v", defn.name) != defn.name:
        raise RecordError(
            "key family_v: a surface of a family in several parameters has it in both directions"
        )
    return defn


def _renamed(at: Definition, side: str) -> dict[str, sp.Symbol]:
    """The parameters of one degree's family (lam_0, lam_1, ... for an indexed one) along
    `side`: lam -> lam_u, lam_0 -> lam_0_u."""
    return {name: sp.Symbol(f"{name}_{side}") for name in at.parameters}


class _Direction:
    """The degree-n basis along u or v: values at the ends and points, the sum of the
    functions and the Gram matrices, as exact SymPy in the direction's parameters (and C)."""

    def __init__(self, defn: Definition, degree: int, side: str) -> None:
        if degree not in defn.degrees:
            raise RecordError(
                f"key degrees: {degree} is outside {defn.name}'s degrees "
                f"{elementary.degrees_text(defn.degrees)}"
            )
        self.defn, self.n, self.side = defn, degree, side
        self.at = defn.at_degree(degree)  # an indexed family's degree-n family
        self.names = _renamed(self.at, side)
        self.real = elementary.realiser(defn) if defn.elementary else None
        if self.real is None:
            polys = basis_polys(self.at, degree)
            gens = polys[0].gens  # t, then the parameters
            rename = {g: self.names[g.name] for g in gens[1:]}
            self.t = gens[0]
            self.basis = [sp.expand(p.as_expr().xreplace(rename)) for p in polys]

    # ---- numbers of an atom family
    def _number(self, number: A.Number) -> sp.Expr:
        syms = [self.names[name] for name in self.defn.parameters]
        out = sp.Integer(0)
        for (mono, c), v in number.items():
            term = sp.Rational(v.numerator, v.denominator) * C**c
            for sym, e in zip(syms, mono, strict=False):  # the control points' slots are 0
                term *= sym**e
            out += term
        return sp.expand(out)

    def _point(self, x: Fraction | str, key: str) -> Fraction | sp.Expr:
        """A point of the domain: 0 / 1 are its ends (Fractions), a string is read."""
        defn = self.defn
        if isinstance(x, Fraction):
            return defn.domain_lo + x * (defn.domain_hi - defn.domain_lo)
        if self.real is not None:
            return self.real.point(self.real.parse(x, key))
        e = _formula(x, {}, key)
        if not e.is_Rational:
            raise RecordError(f"key {key}: {x!r} is not an exact number")
        return Fraction(int(e.p), int(e.q))

    def values(self, x: Fraction | str, key: str) -> list[sp.Expr]:
        """b_i(x) for every i, identically in the parameters."""
        at = self._point(x, key)
        if self.real is not None:
            frame = self.real.frame
            return [self._number(A.value(b, frame, at)) for b in self.real.basis]
        value = sp.Rational(at.numerator, at.denominator)
        return [sp.expand(b.xreplace({self.t: value})) for b in self.basis]

    def sum_constant(self) -> tuple[sp.Expr | None, str]:
        """(Σ b_i when it is a number, else None; Σ b_i as shown)."""
        if self.real is None:
            total = sp.expand(sum(self.basis, sp.Integer(0)))
            return (total if not total.free_symbols else None), str(total)
        total_elem: A.Elem = {}
        for b in self.real.basis:
            total_elem = A.add(total_elem, b)
        shown = self.real.show(total_elem)
        if any(any(mono) or k or h or m for (mono, _c, k, h, m, _kind) in total_elem):
            return None, shown
        return self._number(A.value(total_elem, self.real.frame, Fraction(0))), shown

    def nonzero(self) -> list[bool]:
        """Which b_i are not identically zero (in t and the parameters)."""
        if self.real is not None:
            return [bool(b) for b in self.real.basis]
        return [b != 0 for b in self.basis]

    def gram(self, k: int) -> list[list[sp.Expr]]:
        """G_ij = ∫ b_i^(k) b_j^(k) over the domain, identically in the parameters."""
        size = self.n + 1
        if self.real is not None:
            frame = self.real.frame
            ders = [A.diff(b, frame, k) for b in self.real.basis]
            return [
                [self._number(A.integral(A.mul(ders[i], ders[j]), frame)) for j in range(size)]
                for i in range(size)
            ]
        lo, hi = (sp.Rational(x.numerator, x.denominator) for x in self._domain())
        ders = [sp.Poly(sp.diff(b, self.t, k), self.t) for b in self.basis]
        out = []
        for i in range(size):
            row = []
            for j in range(size):
                prim = (ders[i] * ders[j]).integrate()
                row.append(sp.expand(prim.eval(hi).as_expr() - prim.eval(lo).as_expr()))
            out.append(row)
        return out

    def _domain(self) -> tuple[Fraction, Fraction]:
        return self.defn.domain_lo, self.defn.domain_hi


def _formula(text: str, symbols: dict, key: str, *, elementary_: bool = False) -> sp.Expr:
    try:
        return parse_formula(text, symbols, {}, elementary=elementary_)
    except ParseError as exc:
        raise RecordError(f"key {key}: {exc}") from None


def _printed(defn: Definition, text: str, key: str, du: _Direction, dv: _Direction) -> sp.Expr:
    """A printed number or formula in lam_u, ..., lam_v, ... (and pi or e for an atom family),
    with pi / e^W written as C."""
    symbols = {s.name: s for s in (*du.names.values(), *dv.names.values())}
    if not defn.elementary:
        return sp.expand(_formula(text, symbols, key))
    real = elementary.realiser(defn)
    symbols["e"] = _E
    e = _formula(text, symbols, key, elementary_=True)
    if real.space.constant == "pi":
        if e.has(_E):
            raise RecordError(f"key {key}: e in a claim about the trigonometric {defn.name}")
        e = e.xreplace({sp.pi: C})
    else:
        if e.has(sp.pi):
            raise RecordError(f"key {key}: pi in a claim about the hyperbolic {defn.name}")
        unit = real.frame.exp_unit
        e = e.xreplace({_E: C ** sp.Rational(unit.denominator, unit.numerator)})
    e = sp.expand(e)
    for power in e.atoms(sp.Pow):
        if power.base == C and not power.exp.is_Integer:
            raise RecordError(
                f"key {key}: {text!r} is not in Q[C, 1/C] (C = {real.space.constant})"
            )
    if e.free_symbols - set(symbols.values()) - {C}:
        raise RecordError(f"key {key}: {text!r} names something else than the parameters")
    return e


def _constant(defn: Definition) -> str:
    """C as the records write it: pi, e, or e**W."""
    real = elementary.realiser(defn)
    unit = real.frame.exp_unit
    return "pi" if real.space.constant == "pi" else "e" if unit == 1 else f"e**({unit})"


def _show(defn: Definition, expr: sp.Expr) -> str:
    """A derived value as the records write it, C named."""
    if not defn.elementary:
        return str(expr)
    return str(expr.xreplace({C: sp.Symbol(_constant(defn))}))


def _parameter_values(record: dict, direction: _Direction) -> dict[sp.Symbol, sp.Expr]:
    """The record's `parameters_u` (or `_v`): every parameter of the direction's degree, by
    the family's name (`lam(1)` for an indexed family)."""
    key = f"parameters_{direction.side}"
    given = record.get(key)
    if given is None:
        return {}
    names = direction.names
    indexed = direction.defn.indexed
    out = {}
    for text_name, text in given.items():
        name = text_name
        if indexed is not None:
            m = re.fullmatch(rf"{indexed.name}\((\d+)\)", text_name)  # type: ignore[attr-defined]
            name = f"{indexed.name}_{m.group(1)}" if m else text_name  # type: ignore[attr-defined]
        if name not in names:
            raise RecordError(
                f"key {key}.{text_name}: not a parameter at degree {direction.n} "
                f"({', '.join(names)})"
            )
        value = _formula(text, {}, f"{key}.{text_name}")
        if not value.is_Rational:
            raise RecordError(f"key {key}.{text_name}: {text!r} is not an exact rational number")
        out[names[name]] = value
    missing = [name for name, sym in names.items() if sym not in out]
    if missing:
        raise RecordError(f"key {key}: no value of {missing[0]}")
    return out


def _both_values(record: dict, du: _Direction, dv: _Direction, required: bool) -> dict:
    at = _parameter_values(record, du) | _parameter_values(record, dv)
    if (at or required) and len(at) != len(du.names) + len(dv.names):
        raise RecordError(
            "keys parameters_u, parameters_v: give both" + ("" if required else ", or neither")
        )
    return at


def _degrees(record: dict, defn: Definition) -> tuple[_Direction, _Direction]:
    if "degrees" not in record:
        raise RecordError("key degrees: the degrees [m, n] are required")
    m, n = (int(d) for d in record["degrees"])
    return _Direction(defn, m, "u"), _Direction(defn, n, "v")


def _verdict(diffs: list[str], checked: list[str]) -> Outcome:
    shown = diffs[:10] + ([f"... {len(diffs) - 10} more"] if len(diffs) > 10 else [])
    return Outcome("mismatch" if diffs else "match", shown, checked)


def _exactness(defn: Definition) -> str:
    if not defn.elementary:
        return "exact"
    constant = _constant(defn)
    return f"exact in Q[{constant}, 1/{constant}] (atoms)"


# --------------------------------------------------------------------------- the checks
@checker("surface_basis", fits=_several)
def check_surface_basis(record: dict, _context: object) -> Outcome:
    """The tensor-product basis: printed values at a point, and its partition of unity."""
    defn = _defn(record)
    diffs, checked = [], []
    if record.get("sums_to_one"):
        if "degrees" in record:
            pairs = [tuple(int(d) for d in record["degrees"])]
        else:
            pairs = [(m, n) for m in defn.degrees for n in defn.degrees]
        sums = {}
        for d in sorted({d for pair in pairs for d in pair}):
            sums[d] = _Direction(defn, d, "u").sum_constant()
        for m, n in pairs:
            (su, shown_u), (sv, shown_v) = sums[m], sums[n]
            # Σ_ij b_i(u) b_j(v) = (Σ b_i(u)) (Σ b_j(v)), the parameters of u and v apart:
            # identically 1 exactly when both sums are numbers whose product is 1
            if su is None or sv is None or sp.expand(su * sv) != 1:
                diffs.append(
                    f"degrees ({m}, {n}): Σ B_ij = ({shown_u}) * ({shown_v}) along u and v, "
                    "not identically 1"
                )
        checked.append(
            f"Σ B_ij = 1 for degrees {pairs}, every parameter in u and v, {_exactness(defn)}"
        )
    if "values" in record:
        du, dv = _degrees(record, defn)
        if "uv" not in record:
            raise RecordError("key uv: printed `values` need the point `uv`")
        at = _both_values(record, du, dv, required=True)
        a = [x.xreplace(at) for x in du.values(record["uv"][0], "uv[0]")]
        c = [x.xreplace(at) for x in dv.values(record["uv"][1], "uv[1]")]
        printed = record["values"]
        if len(printed) != du.n + 1 or any(len(row) != dv.n + 1 for row in printed):
            raise RecordError(f"key values: a {du.n + 1} x {dv.n + 1} table")
        for i, row in enumerate(printed):
            for j, text in enumerate(row):
                want = sp.expand(a[i] * c[j])
                if sp.expand(_printed(defn, text, f"values[{i}][{j}]", du, dv) - want) != 0:
                    diffs.append(
                        f"B_{i}{j}({', '.join(record['uv'])}): printed {text}, "
                        f"derived {_show(defn, want)}"
                    )
        checked.append(f"values at (u, v) = {tuple(record['uv'])}, {_exactness(defn)}")
    if not checked:
        raise RecordError("a surface_basis record states `values` (with `uv`) or `sums_to_one`")
    return _verdict(diffs, checked)


@checker("surface_boundary", fits=_several)
def check_surface_boundary(record: dict, _context: object) -> Outcome:
    """On a side of the square the surface is the curve of one row (or column) of the net:
    B_ij = b_i(end) c_j(v) there, so the claim holds exactly when b_i(end) = δ_i,row (the c_j
    are not identically zero, and the parameters of u and v are independent)."""
    defn = _defn(record)
    du, dv = _degrees(record, defn)
    var, end = SIDES[record["side"]]
    across, along = (du, dv) if var == "u" else (dv, du)
    kind, text = record["line"].split()
    want_kind = "row" if var == "u" else "column"
    top = across.n
    index = {"m": du.n, "n": dv.n}.get(text)
    index = int(text) if index is None else index
    diffs = []
    if kind != want_kind:
        diffs.append(f"on {record['side']} the surface is a curve of a {want_kind}, not a {kind}")
    ends = across.values(Fraction(end), record["side"])
    for i, value in enumerate(ends):
        target = 1 if (kind == want_kind and i == index and index <= top) else 0
        if sp.expand(value - target) != 0:
            diffs.append(
                f"b_{i} at the {'start' if end == 0 else 'end'} of the domain along {var} is "
                f"{_show(defn, value)}, so B on {record['side']} is not the curve of "
                f"{record['line']}"
            )
    zero = [j for j, ok in enumerate(along.nonzero()) if not ok]
    if zero:  # a vanishing function along the side would make its terms hold trivially
        diffs.append(f"derived: the basis functions {zero} along the side vanish identically")
    checked = [
        f"B_ij on {record['side']} for degrees ({du.n}, {dv.n}), every parameter, "
        + _exactness(defn)
    ]
    return _verdict(diffs, checked)


@checker("surface_corners", fits=_several)
def check_surface_corners(record: dict, _context: object) -> Outcome:
    """S = P_pq at each listed corner for every parameter: B_ij there is b_i(end_u) c_j(end_v),
    a product of factors in independent parameters, compared with δ exactly."""
    defn = _defn(record)
    du, dv = _degrees(record, defn)
    diffs = []
    for number, (u0, v0, p, q) in enumerate(record["corners"]):
        if u0 not in (0, 1) or v0 not in (0, 1):
            raise RecordError(f"key corners[{number}]: ({u0}, {v0}) is not a corner (0 or 1)")
        a = du.values(Fraction(u0), f"corners[{number}]")
        c = dv.values(Fraction(v0), f"corners[{number}]")
        hot = [
            (i, j, sp.expand(a[i] * c[j]))
            for i in range(du.n + 1)
            for j in range(dv.n + 1)
            if sp.expand(a[i] * c[j] - int((i, j) == (p, q))) != 0 or (i, j) == (p, q)
        ]
        if [(i, j) for i, j, w in hot] != [(p, q)] or hot[0][2] != 1:
            at = [(i, j) for i, j, w in hot if w != 0]
            claimed = sp.expand(a[p] * c[q]) if p <= du.n and q <= dv.n else 0
            diffs.append(
                f"S({u0}, {v0}): printed P_{p}{q}, derived weights at {at}; the weight of "
                f"P_{p}{q} is {_show(defn, claimed)}"
            )
    checked = [f"corners for degrees ({du.n}, {dv.n}), every parameter, {_exactness(defn)}"]
    return _verdict(diffs, checked)


def _kronecker(du: _Direction, dv: _Direction, energy: str, at: dict) -> list[list[sp.Expr]]:
    """Q = Σ_terms weight · G_u^(k_u) ⊗ G_v^(k_v), from the curves' Gram matrices (at the
    parameter values `at`, or identically when it is empty)."""
    size = (du.n + 1) * (dv.n + 1)
    out = [[sp.Integer(0)] * size for _ in range(size)]
    for ku, kv, weight in ENERGIES[energy]:
        gu, gv = (
            [[x.xreplace(at) for x in row] for row in d.gram(k)] for d, k in ((du, ku), (dv, kv))
        )
        for i in range(du.n + 1):
            for k in range(du.n + 1):
                for j in range(dv.n + 1):
                    for l_ in range(dv.n + 1):
                        r, c = i * (dv.n + 1) + j, k * (dv.n + 1) + l_
                        out[r][c] += weight * gu[i][k] * gv[j][l_]
    return [[sp.expand(x) for x in row] for row in out]


def _direct(du: _Direction, dv: _Direction, energy: str, at: dict) -> list[list[sp.Expr]]:
    """Q by integrating the products of the tensor-product basis's partials over the square
    (a polynomial family): no separation of the variables."""
    u, v = _X["u"], _X["v"]
    basis = [
        sp.Poly(sp.expand((bu.xreplace({du.t: u}) * bv.xreplace({dv.t: v})).xreplace(at)), u, v)
        for bu in du.basis
        for bv in dv.basis
    ]
    lo, hi = (sp.Rational(x.numerator, x.denominator) for x in du._domain())
    size = len(basis)
    out = [[sp.Integer(0)] * size for _ in range(size)]
    for ku, kv, weight in ENERGIES[energy]:
        parts = [p.diff((u, ku), (v, kv)) if ku or kv else p for p in basis]
        for r in range(size):
            for c in range(r, size):
                prim = (parts[r] * parts[c]).integrate(u).integrate(v)
                inner = prim.eval(u, hi) - prim.eval(u, lo)  # a Poly in v
                whole = sp.sympify(inner.eval(hi) - inner.eval(lo))
                out[r][c] += weight * whole
                if c != r:
                    out[c][r] += weight * whole
    return [[sp.expand(x) for x in row] for row in out]


@checker("surface_energy_matrix", fits=_several)
def check_surface_energy_matrix(record: dict, _context: object) -> Outcome:
    """The printed full matrix Q of a surface energy, E = vec(P)ᵀ Q vec(P)."""
    defn = _defn(record)
    du, dv = _degrees(record, defn)
    energy, gram = record.get("energy"), record.get("gram")
    if energy is None or gram is None:
        raise RecordError("keys energy and gram are required")
    size = (du.n + 1) * (dv.n + 1)
    if len(gram) != size or any(len(row) != size for row in gram):
        raise RecordError(f"key gram: a {size} x {size} matrix")
    at = _both_values(record, du, dv, required=False)
    want = _kronecker(du, dv, energy, at)
    how = "the Kronecker sum of the curves' Gram matrices"
    if not defn.elementary:
        if _direct(du, dv, energy, at) != want:
            raise AssertionError(
                f"{energy} of {defn.name} at degrees ({du.n}, {dv.n}): the direct integration "
                "and the Kronecker form of the curves' Gram matrices differ"
            )
        how += ", equal to the direct integration over the square"
    diffs = []
    for r, row in enumerate(gram):
        for c, text in enumerate(row):
            derived = want[r][c]
            if (
                sp.expand(_printed(defn, text, f"gram[{r}][{c}]", du, dv).xreplace(at) - derived)
                != 0
            ):
                diffs.append(f"Q[{r}][{c}]: printed {text}, derived {_show(defn, derived)}")
    where = " at the printed parameters" if at else ", every parameter"
    checked = [
        f"the {size} x {size} {energy} matrix for degrees ({du.n}, {dv.n}){where}: {how}, "
        + _exactness(defn)
    ]
    return _verdict(diffs, checked)


_CONTINUITY_ORDER = {"C1": 1, "G1": 1, "C2": 2}


@checker("surface_continuity", fits=_several)
def check_surface_continuity(record: dict, _context: object) -> Outcome:
    """Printed weights of patch 2's rows next to the boundary u = 1 of patch 1, against the
    curve join derive solves for the family (derive/formulas/joins_several.py), applied column
    by column; for a polynomial family with itself the reduction is re-proved exactly on the
    tensor-product basis (a patch built with the derived weights meets with the continuity
    along the whole boundary, for every net and parameter)."""
    defn = _defn(record)
    continuity = record.get("continuity")
    if continuity not in _CONTINUITY_ORDER:
        raise RecordError(f"key continuity: one of {', '.join(_CONTINUITY_ORDER)}")
    second = record.get("second_family", defn.name)
    degree = record.get("n")
    if degree is None and not defn.elementary and len(defn.degrees) > 1:
        raise RecordError(f"key n: the degree across the boundary (of {defn.degrees})")
    if degree is not None and degree not in defn.degrees:
        raise RecordError(f"key n: {degree} is not a degree of {defn.name} ({defn.degrees})")
    forms, deg, constant = joins_several.end_forms(defn, degree)
    at = defn.at_degree(deg) if defn.indexed is not None else defn
    derived = joins_several.pair_weights(at, deg, forms, f"{defn.name}>{second}", continuity)
    if isinstance(derived, str):
        return Outcome("mismatch", [f"derive finds no closed-form {continuity} weights: {derived}"])
    symbols = checks_joins_several._symbols(at)
    degrees = {symbols["n"]: deg} | ({symbols["m"]: deg} if second == defn.name else {})
    value = checks_joins_several._constant(constant)
    want = {
        key: w.xreplace({joins_several.C: value}).xreplace(degrees) for key, w in derived.items()
    }
    got = {}
    for number, w in enumerate(record.get("weights") or []):
        try:
            e = parse_formula(w["weight"], {**symbols, "e": sp.E}, {}, elementary=True)
        except ParseError as exc:
            raise RecordError(f"key weights[{number}].weight: {exc}") from None
        got[f"{w['row']},{w['source']},{w['k']}"] = e.xreplace(degrees)
    if not got:
        raise RecordError("key weights: no weight")
    diffs = []
    for key in sorted(set(got) | set(want)):
        printed, wanted = got.get(key, sp.Integer(0)), want.get(key, sp.Integer(0))
        if sp.cancel(sp.together(printed - wanted)) != 0:
            row, src, k = key.split(",")
            diffs.append(f"row {row}, {src} point {k}: printed {printed}, derived {wanted}")
    how = f"{continuity} weights {defn.name} -> {second} at n = {deg}, exact"
    if not defn.elementary and second == defn.name:
        _columnwise(at, deg, want, continuity, symbols)
        how += "; applied column by column on the tensor-product basis (re-proved exactly)"
    else:
        how += "; applied column by column (linearity in the columns)"
    return _verdict(diffs, [how])


def _columnwise(at: Definition, deg: int, weights: dict, continuity: str, symbols: dict) -> None:
    """Raise unless two patches of `at` (degree `deg` both ways, patch 2's rows 0..order from
    the weights) meet with the continuity along u = 1 identically in v, the nets and every
    parameter (patch 1's x1, patch 2's x2, the shared v direction's own)."""
    u, v = _X["u"], _X["v"]
    polys = basis_polys(at, deg)
    gens = polys[0].gens
    side = {s: [symbols[f"{g.name}{k}"] for g in gens[1:]] for k, s in ((1, "1"), (2, "2"))}
    along_v = [sp.Symbol(f"{g.name}_v") for g in gens[1:]]

    def basis(x, params):
        return [
            p.as_expr().xreplace({gens[0]: x, **dict(zip(gens[1:], params, strict=True))})
            for p in polys
        ]

    b1, b2, c = basis(u, side["1"]), basis(u, side["2"]), basis(v, along_v)
    order = _CONTINUITY_ORDER[continuity]
    alpha = symbols["alpha"] if continuity == "G1" else sp.Integer(1)
    p1 = [[sp.Symbol(f"P1_{i}_{j}") for j in range(deg + 1)] for i in range(deg + 1)]
    p2 = [[sp.Symbol(f"P2_{i}_{j}") for j in range(deg + 1)] for i in range(deg + 1)]
    for row in range(order + 1):
        for j in range(deg + 1):
            p2[row][j] = sum(
                (
                    w * (p1[deg - int(k)][j] if src == "first" else p2[int(k)][j])
                    for key, w in weights.items()
                    for r_, src, k in [key.split(",")]
                    if int(r_) == row
                ),
                sp.Integer(0),
            )
    s1 = sum(p1[i][j] * b1[i] * c[j] for i in range(deg + 1) for j in range(deg + 1))
    s2 = sum(p2[i][j] * b2[i] * c[j] for i in range(deg + 1) for j in range(deg + 1))
    for r in range(order + 1):
        gap = sp.diff(s1, u, r).subs(u, 1) - alpha**r * sp.diff(s2, u, r).subs(u, 0)
        if sp.cancel(sp.together(sp.expand(gap))) != 0:
            raise AssertionError(
                f"{continuity} of {at.name} at degree {deg}: the derived weights, applied "
                f"column-wise, leave the order-{r} cross-boundary derivatives apart"
            )
