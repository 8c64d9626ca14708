"""Checkers of tensor-product surface claims (issue #31), against derive/formulas/surface_energy.py
(the tensor-product basis, the energy matrices) and derive/formulas/surface_joins.py.

A surface record names its degrees `[m, n]`; its family is the record's family in the u
direction and `family_v` (default: the same) in the v direction. Claim kinds:

- ``surface_basis``: the tensor-product basis B_ij(u, v) = b_i(u; λ_u) b_j(v; λ_v): `values`
  printed at `uv` (with `lam_u`, `lam_v`), and/or `sums_to_one` (identically in u, v, λ_u, λ_v);
- ``surface_boundary``: the boundary curve on `side` ("u=0", …) is the family's curve of the net
  `line` ("row 0", "row m", "column 0", "column n"), identically in the free variable and λ;
- ``surface_corners``: S(u, v) = P_ij at the corners listed as [u, v, i, j] (u, v in {0, 1});
- ``surface_continuity``: the printed `weights` of the second patch's rows for `continuity`
  (C1, G1, C2) across u = 1, patch 2 of `second_family` (default: the record's family); each
  compared with the derived conditions, whose column-wise reduction is re-proved exactly;
- ``surface_energy_matrix``: the printed `scale` and upper-triangular integer `matrix` of the
  coefficient of λ_u^a λ_v^b (`term` = [a, b]) of the `energy` ("membrane", "thin_plate").
"""

from __future__ import annotations

from fractions import Fraction

import flint
import sympy as sp

from ..grammar import SYMBOLS
from .checks_core import Outcome, checker, derive_module
from .checks_elementary import RecordError, degrees_text
from .checks_examples import _frac
from .claim_families import FAMILIES, SEVERAL_FAMILIES
from .context import Context
from .expr_parse import parse


def _one_parameter(record: dict) -> bool:
    """The records these checkers take: a family in several parameters has its surface claims
    decided by checks_surfaces_several.py."""
    return record["family"] not in SEVERAL_FAMILIES


def _surface_energy():
    return derive_module("surface_energy")


def _families(record: dict, ctx: Context) -> tuple[str, str]:
    fam_u = ctx.family.name
    fam_v = record.get("family_v", fam_u)
    for name in (fam_u, fam_v):
        if not _surface_energy().known(name):
            raise ValueError(
                f"surface claims know the built-in families and one-parameter families a "
                f"records file defines, not {name!r}"
            )
    return fam_u, fam_v


def _degrees(record: dict, fams: tuple[str, str]) -> tuple[int, int]:
    m, n = (int(d) for d in record["degrees"])
    for fam, deg in zip(fams, (m, n), strict=True):
        if deg not in FAMILIES[fam].degrees:
            raise ValueError(
                f"degree {deg} is outside the {fam} degrees {degrees_text(FAMILIES[fam].degrees)}"
            )
    return m, n


def _basis(record: dict, ctx: Context):
    fams = _families(record, ctx)
    m, n = _degrees(record, fams)
    return fams, m, n, _surface_energy().tensor_basis(*fams, m, n)


def _fmpq(x: Fraction) -> flint.fmpq:
    return flint.fmpq(x.numerator, x.denominator)


def _numbers(items: object, key: str, count: int) -> list[Fraction]:
    """`count` exact numbers of a record's list under `key` (a RecordError naming it)."""
    if not isinstance(items, list) or len(items) != count:
        raise RecordError(f"key {key}: a list of {count} numbers")
    try:
        return [_frac(x) for x in items]
    except (ValueError, TypeError, ZeroDivisionError) as exc:
        raise RecordError(f"key {key}: {exc}") from None


def _mismatch_or_match(diffs: list[str], checked: list[str]) -> Outcome:
    return Outcome("mismatch" if diffs else "match", diffs, checked)


# What each key a claim cannot do without holds: a record leaving one out is malformed (the
# verdict "error", naming the key, as checks_surfaces_several does), never a bare KeyError.
_KEYS = {
    "degrees": "the degrees [m, n]",
    "side": 'the side ("u=0", "u=1", "v=0" or "v=1")',
    "line": 'the row or column of the net ("row 0", "column n", ...)',
    "corners": "the corners [[u, v, i, j], ...]",
    "continuity": "the continuity (C1, G1 or C2)",
    "weights": "the printed weights [{row, source, k, weight}, ...]",
    "energy": 'the energy ("membrane" or "thin_plate")',
    "term": "the term [a, b] of λ_u^a λ_v^b",
    "scale": "the printed scale",
    "matrix": "the printed upper-triangular integer matrix",
}


def _guard(*required: str):
    """A record outside what the derivation covers is a mismatch with the reason, not a crash;
    one without a `required` key is malformed (a RecordError naming the key)."""

    def wrap(fn):
        def run(record: dict, ctx: Context) -> Outcome:
            for key in required:
                if key not in record:
                    raise RecordError(f"key {key} is required: {_KEYS[key]}")
            try:
                return fn(record, ctx)
            except RecordError:
                raise  # malformed: the verdict "error", naming the key
            except ValueError as exc:
                return Outcome("mismatch", [str(exc)])

        run.__doc__ = fn.__doc__
        return run

    return wrap


@checker("surface_basis", requires=("surface_energy",), fits=_one_parameter)
@_guard()
def check_surface_basis(record: dict, ctx: Context) -> Outcome:
    """Printed values of the tensor-product basis at a point; its partition of unity (at the
    record's `degrees`, or at every degree pair derive emits when it gives none)."""
    fu, fv = _families(record, ctx)
    diffs, checked = [], []
    if record.get("sums_to_one"):
        if "degrees" in record:
            pairs = [_degrees(record, (fu, fv))]
        else:
            se = _surface_energy()
            pairs = [(m, n) for m in se.degrees(fu) for n in se.degrees(fv)]
        for m, n in pairs:
            basis = _surface_energy().tensor_basis(fu, fv, m, n)
            total = sum(basis[1:], basis[0])
            if total != 1:
                diffs.append(f"degrees ({m}, {n}): the derived basis sums to {total}, not 1")
        checked.append(f"Σ B_ij = 1 for {fu} x {fv}, degrees {pairs}, every λ_u, λ_v")
    if "values" in record:
        (fu, fv), m, n, basis = _basis(record, ctx)
        if "uv" not in record:
            raise RecordError("key uv is required with `values`: the point [u, v]")
        u, v = _numbers(record["uv"], "uv", 2)
        subs = {"u": _fmpq(u), "v": _fmpq(v)}
        for slot, name in ((2, "lam_u"), (3, "lam_v")):
            if name in record:
                subs[name] = _fmpq(_numbers([record[name]], name, 1)[0])
            elif any(int(e[slot]) for b in basis for e in b.to_dict()):
                raise RecordError(f"key {name} is required with `values`: the basis depends on it")
            else:
                subs[name] = _fmpq(Fraction(0))  # the basis does not depend on it
        rows = record["values"]
        if not isinstance(rows, list) or not all(isinstance(row, list) for row in rows):
            raise RecordError(f"key values: {m + 1} rows of {n + 1} numbers")
        printed = [_numbers(row, "values", n + 1) for row in rows]
        if len(printed) != m + 1:
            raise RecordError(f"key values: {m + 1} rows of {n + 1} numbers, got {len(printed)}")
        for i in range(m + 1):
            for j in range(n + 1):
                got = basis[i * (n + 1) + j].subs(subs)
                if got != _fmpq(printed[i][j]):
                    diffs.append(f"B_{i}{j}({u}, {v}): printed {printed[i][j]}, derived {got}")
        checked.append(f"values at (u, v) = ({u}, {v})")
    if not checked:
        raise RecordError("a surface_basis record states `values` (with `uv`) or `sums_to_one`")
    return _mismatch_or_match(diffs, checked)


SIDES = {"u=0": ("u", 0), "u=1": ("u", 1), "v=0": ("v", 0), "v=1": ("v", 1)}  # a record's side


def _line(text: str, m: int, n: int) -> tuple[str, int]:
    kind, idx = text.split()
    top = m if kind == "row" else n
    index = {"m": m, "n": n}.get(idx)
    return kind, int(idx) if index is None else index if index <= top else -1


@checker("surface_boundary", requires=("surface_energy",), fits=_one_parameter)
@_guard("degrees", "side", "line")
def check_surface_boundary(record: dict, ctx: Context) -> Outcome:
    """On a side of the square the surface is the curve of one row (or column) of the net."""
    (fu, fv), m, n, basis = _basis(record, ctx)
    var, at = SIDES[record["side"]]
    want_kind = "row" if var == "u" else "column"
    want_index = (m if var == "u" else n) if at else 0
    kind, index = _line(record["line"], m, n)
    diffs = []
    if (kind, index) != (want_kind, want_index):
        diffs.append(
            f"on {record['side']} the surface is the curve of {want_kind} {want_index}, "
            f"printed {record['line']}"
        )
    # the derived side of the claim: B_ij restricted to the side is δ · (the other basis)
    for i in range(m + 1):
        for j in range(n + 1):
            got = basis[i * (n + 1) + j].subs({var: at})
            on_line = (i if var == "u" else j) == want_index
            along = _curve(fv, n, j, "v") if var == "u" else _curve(fu, m, i, "u")
            if got != (along if on_line else 0 * along):
                diffs.append(f"derived B_{i}{j} on {record['side']} is not as stated")
    return _mismatch_or_match(
        diffs, [f"B_ij on {record['side']} for {fu} x {fv}, degrees ({m}, {n}), every λ"]
    )


def _curve(family: str, degree: int, index: int, var: str) -> flint.fmpq_mpoly:
    """The curve basis function b_index of `family` in the variable `var` (u or v)."""
    se = _surface_energy()
    # a tensor basis with the trivial degree-0 Bézier factor is the curve basis itself
    if var == "u":
        return se.tensor_basis(family, "bezier", degree, 0)[index]
    return se.tensor_basis("bezier", family, 0, degree)[index]


@checker("surface_corners", requires=("surface_energy",), fits=_one_parameter)
@_guard("degrees", "corners")
def check_surface_corners(record: dict, ctx: Context) -> Outcome:
    """S(u, v) = P_ij at the listed corners, for every λ_u, λ_v."""
    (fu, fv), m, n, basis = _basis(record, ctx)
    diffs = []
    for u, v, pi, pj in record["corners"]:
        if u not in (0, 1) or v not in (0, 1):
            raise ValueError(f"corner ({u}, {v}) is not a corner of the unit square")
        values = [b.subs({"u": u, "v": v}) for b in basis]
        hot = [divmod(k, n + 1) for k, x in enumerate(values) if x != 0]
        if hot != [(pi, pj)] or values[pi * (n + 1) + pj] != 1:
            diffs.append(f"S({u}, {v}): printed P_{pi}{pj}, derived weights at {hot}")
    return _mismatch_or_match(diffs, [f"corners of {fu} x {fv}, degrees ({m}, {n}), every λ"])


@checker("surface_continuity", requires=("surface_joins",), fits=_one_parameter)
@_guard("continuity", "weights")
def check_surface_continuity(record: dict, ctx: Context) -> Outcome:
    """Printed weights of patch 2's rows next to the boundary, against the derived ones: in
    closed form in the degrees n, m where both families have closed end forms, else at every
    pair of the families' degrees (solved from the bases at those degrees)."""
    sj = derive_module("surface_joins")
    first = ctx.family.name
    second = record.get("second_family", first)
    cont = record["continuity"]
    if cont not in sj.CONTINUITIES:
        raise ValueError(f"surface continuity {cont} is not derived (only {sj.CONTINUITIES})")
    printed = {(w["row"], w["source"], w["k"]): parse(w["weight"]) for w in record["weights"]}
    try:
        derived = _by_name(sj.conditions(first, second, cont))
    except KeyError:  # no closed end forms in n: every pair of degrees
        return _continuity_per_degree(record, first, second, cont, printed)
    sj.check_pair(first, second, cont)  # the reduction to column-wise curve joins
    diffs = _weight_diffs(printed, derived, "")
    return _mismatch_or_match(
        diffs,
        [f"{cont} weights {first} -> {second}, applied column by column (checked exactly)"],
    )


def _by_name(weights: dict) -> dict:
    """The derived weights in the records grammar's symbols, by name."""
    return {
        key: sp.sympify(w).xreplace({s: SYMBOLS[s.name] for s in sp.sympify(w).free_symbols})
        for key, w in weights.items()
    }


def _weight_diffs(printed: dict, derived: dict, where: str) -> list[str]:
    diffs = []
    for key in sorted(set(derived) | set(printed), key=str):
        got, want = printed.get(key, sp.Integer(0)), derived.get(key, sp.Integer(0))
        if sp.cancel(sp.together(got - want)) != 0:
            diffs.append(
                f"{where}row {key[0]}, {key[1]} point {key[2]}: printed {got}, derived {want}"
            )
    return diffs


def _continuity_per_degree(
    record: dict, first: str, second: str, cont: str, printed: dict
) -> Outcome:
    sj = derive_module("surface_joins")
    degree_symbols = {SYMBOLS["n"], SYMBOLS["m"]}
    diffs, pairs = [], []
    for n in FAMILIES[first].degrees:
        for m in FAMILIES[second].degrees:
            at = {SYMBOLS["n"]: n, SYMBOLS["m"]: m}
            derived = _by_name(sj.conditions_at(first, second, cont, n, m))
            here = {
                key: w.xreplace(at) if w.free_symbols & degree_symbols else w
                for key, w in printed.items()
            }
            diffs += _weight_diffs(here, derived, f"n = {n}, m = {m}: ")
            pairs.append((n, m))
    sj.check_columnwise_at(first, second, cont, *pairs[0])  # the reduction, re-proved
    shown = diffs[:10] + ([f"... {len(diffs) - 10} more"] if len(diffs) > 10 else [])
    return _mismatch_or_match(
        shown,
        [
            f"{cont} weights {first} -> {second} at every degree pair {pairs} (no closed end "
            "forms in n: solved from the bases at each pair, exactly; applied column by column "
            f"on the tensor-product basis at {pairs[0]})"
        ],
    )


@checker("surface_energy_matrix", requires=("surface_energy",), fits=_one_parameter)
@_guard("degrees", "energy", "term", "scale", "matrix")
def check_surface_energy_matrix(record: dict, ctx: Context) -> Outcome:
    """A printed coefficient matrix (scale · upper-triangular integers) of a surface energy."""
    fams = _families(record, ctx)
    m, n = _degrees(record, fams)
    a, b = (int(x) for x in record["term"])
    forms = _surface_energy().surface_forms(*fams, m, n, record["energy"])
    size = (m + 1) * (n + 1)
    printed = record["matrix"]
    if len(printed) != size or any(len(row) != size for row in printed):
        return Outcome("mismatch", [f"printed matrix is not {size} x {size}"])
    scale = _frac(record["scale"])
    got = [[scale * int(x) for x in row] for row in printed]
    d_scale, d_upper = forms.get((a, b), (Fraction(0), [[0] * size for _ in range(size)]))
    want = [[d_scale * int(x) for x in row] for row in d_upper]
    diffs = [
        f"entry [{r}][{c}]: printed {got[r][c]}, derived {want[r][c]}"
        for r in range(size)
        for c in range(size)
        if got[r][c] != want[r][c]
    ]
    return _mismatch_or_match(
        diffs[:10] + ([f"... {len(diffs) - 10} more"] if len(diffs) > 10 else []),
        [f"{record['energy']} λ_u^{a} λ_v^{b} for {fams[0]} x {fams[1]}, degrees ({m}, {n})"],
    )
