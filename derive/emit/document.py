"""The derived family document (``<name>.derived.json``): every artifact of a family defined
by data, as one deterministic JSON text (data, never code: ``lambda_bezier.load_family``
reads it without running anything).
"""

from __future__ import annotations

import json
from fractions import Fraction
from pathlib import Path

from ..algebra import expansion_tables
from ..families.definition import FORMAT, Definition
from ..families.engine import (
    basis_polys,
    check,
    closed_endpoint_forms,
    closed_endpoint_order,
    endpoint_table,
    monomial_split,
    symmetry,
)
from ..formulas.energy_several import monomial_grams
from ..formulas.family import (
    energy_artifacts,
    join_artifacts,
    singular_artifacts,
    surface_join_artifacts,
)
from ..formulas.joins_several import join_table, polynomial_end_forms
from ..formulas.several_box import independence_over_box, nonnegativity
from .closed_n import section
from .parameters import document_header, parameter_table

# --------------------------------------------------------------------------- the document


def _matrices(mats) -> list:
    return [[[str(Fraction(v)) for v in row] for row in mat] for mat in mats]


def _several(defn: Definition, checked: list[str]) -> dict:
    """The document of a family in several parameters: the tables split by parameter
    monomials ("e_1,...,e_k" -> matrix), the end values and derivatives per degree by
    monomial, the symmetry with the parameter permutation it needs, and E_k as Gram
    matrices of the affine parts (derive/formulas/family.py)."""
    tables: dict[str, dict] = {"power": {}, "bernstein": {}, "centred": {}}
    for deg in defn.degrees:
        split = monomial_split(defn, deg)
        for kind in tables:
            tables[kind][str(deg)] = {}
        for mono, polys in split.items():
            got = expansion_tables(lambda _d, polys=polys: polys, (deg,), defn.offset)
            for kind in tables:
                tables[kind][str(deg)][",".join(map(str, mono))] = _matrices(got[kind][deg])[0]
    swap = symmetry(defn)
    energy = energy_artifacts(defn)
    low = defn.degrees.start
    closed, closed_joins = section(defn) if len(defn.degrees) > 1 else ({}, {})
    return {
        **document_header(defn, FORMAT),
        "parameters": parameter_table(defn),
        "domain": {"lo": str(defn.domain.lo), "hi": str(defn.domain.hi)},
        "degrees": [defn.degrees.start, defn.degrees.stop - 1],
        "degree_offset": defn.offset,
        "checked": checked,
        "symmetry": None
        if swap is None
        else {
            "swap": list(swap),
            "text": "b_i(t; "
            + ", ".join(defn.parameters)
            + ") = b_{n-i}(1 - t; "
            + ", ".join(swap)
            + ")",
        },
        "basis": {
            str(deg): [str(p.as_expr()) for p in basis_polys(defn, deg)] for deg in defn.degrees
        },
        **tables,
        "endpoints": endpoint_table(defn),
        "endpoint_closed_orders": -1,
        "endpoint_closed_forms": None,
        **({"closed_n": closed} if closed else {}),
        "energy": energy,
        **({"energy_monomials": monomial_grams(defn)} if "reason" in energy else {}),
        "nonnegative_over_box": nonnegativity(defn),
        "singular_parameters": independence_over_box(defn),
        "joins": join_table(defn, low, polynomial_end_forms(defn, low))
        if len(defn.degrees) == 1
        else closed_joins,
        "surface_joins": {"reason": "several parameters: the runtime joins per degree"},
    }


def _indexed(defn: Definition) -> dict:
    """An indexed family (lam(i)): per degree, the several-parameter document of that
    degree's expansion into lam_a .. lam_b (derive/families/indexed.py)."""
    spec = defn.indexed
    by_degree = {}
    for deg in defn.degrees:
        at = defn.at_degree(deg)
        by_degree[str(deg)] = _several(at, check(at))
    return {
        **document_header(defn, FORMAT),
        "indexed": {
            "name": spec.name,  # type: ignore[attr-defined]
            "symbols": {str(deg): list(defn.at_degree(deg).parameters) for deg in defn.degrees},
        },
        "degrees": [defn.degrees.start, defn.degrees.stop - 1],
        "degree_offset": defn.offset,
        "by_degree": by_degree,
        **(
            dict(zip(("closed_n", "joins"), section(defn), strict=True))
            if len(defn.degrees) > 1
            else {}
        ),
    }


def derive(defn: Definition, *, with_joins: bool = True) -> dict:
    """Every artifact of the family, as one JSON-able document (exact numbers as strings)."""
    if defn.elementary:  # sin, cos, sinh, cosh, exp: format 4 (issue #30)
        from .atom_document import derive as derive_atoms

        return derive_atoms(defn)
    if defn.indexed is not None:
        return _indexed(defn)
    checked = check(defn)
    if defn.several:
        return _several(defn, checked)
    tables = expansion_tables(lambda deg: basis_polys(defn, deg), tuple(defn.degrees), defn.offset)
    closed = closed_endpoint_forms(defn)
    doc = {
        **document_header(defn, FORMAT),
        "parameter": defn.parameter,
        "range": {
            "text": defn.range_text,
            "lo": str(defn.lo),
            "hi": str(defn.hi),
            "closed": [defn.lo_closed, defn.hi_closed],
        },
        "degrees": [defn.degrees.start, defn.degrees.stop - 1],
        "degree_offset": defn.offset,
        "bernstein_at": None if defn.bernstein_at is None else str(defn.bernstein_at),
        "checked": checked,
        "basis": {
            str(deg): [str(p.as_expr()) for p in basis_polys(defn, deg)] for deg in defn.degrees
        },
        "power": {str(k): _matrices(v) for k, v in tables["power"].items()},
        "bernstein": {str(k): _matrices(v) for k, v in tables["bernstein"].items()},
        "centred": {str(k): _matrices(v) for k, v in tables["centred"].items()},
        "endpoints": endpoint_table(defn),
        "endpoint_closed_orders": closed_endpoint_order(defn),
        "endpoint_closed_forms": None
        if closed is None
        else {f"{e},{r},{j}": str(v) for (e, r, j), v in sorted(closed.items())},
        "energy": energy_artifacts(defn),
        "singular_parameters": singular_artifacts(defn),
    }
    if with_joins:
        doc["joins"] = (
            {"reason": "no closed end forms in n: the runtime joins per degree"}
            if closed is None
            else join_artifacts(defn, closed)
        )
        doc["surface_joins"] = (
            {"reason": "no closed end forms in n: the runtime joins per degree"}
            if closed is None
            else surface_join_artifacts(defn, closed)
        )
    return doc


def render(defn: Definition) -> str:
    """The derived document as deterministic text (sorted keys, fixed separators)."""
    # keys in the order derive() builds them (every loop there runs over sorted keys), so the
    # banner comes first; the text does not depend on PYTHONHASHSEED
    return json.dumps(derive(defn), indent=1, ensure_ascii=False) + "\n"


def derived_path(definition_file: Path, name: str, out_dir: Path | None = None) -> Path:
    return (out_dir or Path(definition_file).resolve().parent) / f"{name}.derived.json"
