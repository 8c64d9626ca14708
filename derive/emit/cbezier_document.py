"""The derived document (``"format": 5``) of a family whose parameter is the length of the
domain or sits inside sin/cos (derive/families/cbezier.py, derive/formulas/cbezier.py).

Data only: the basis as coefficients over the atoms (1, t^k, cos(m t), sin(m t) or cosh, sinh)
of the family's t on [0, alpha], each coefficient a rational function of alpha, sin(alpha),
cos(alpha) as exponent/rational terms the runtime evaluates in floats
(lambda_bezier.cbezier_family); below a threshold of alpha, where those coefficients cancel,
the basis as an exact series in alpha with polynomials in u = t/alpha as coefficients
(formulas/cbezier_series.py); the Gram matrices of E_1..E_3 in the same form; every verdict
with its closed forms as text.
"""

from __future__ import annotations

import json
from pathlib import Path

from ..families.cbezier import CDefinition, read_table
from ..families.cbezier_recursion import COrders, is_recursion_table, read_orders
from ..families.definition import DefinitionError
from ..formulas import cbezier as F
from ..formulas.cbezier_nonnegative import nonvanishing
from ..formulas.cbezier_series import small_alpha

FORMAT = 5


def derive(defn: CDefinition) -> dict:
    doc = _derive(defn)
    series = small_alpha(defn)
    if series is not None:  # (absent where nothing cancels: the documents stay as they were)
        doc["small_alpha"] = series
    return doc


def _derive(defn: CDefinition) -> dict:
    atoms, matrix = F.coefficient_matrix(defn)
    rank, det = F.rank(defn)
    ends = F.end_table(defn)
    n = defn.degree
    return {
        "format": FORMAT,
        "family": defn.name,
        "definition_sha256": defn.digest,
        "title": defn.title,
        "kind": "frequency",
        "parameter": defn.parameter,
        "range": {
            "text": defn.range_text,
            "lo": str(defn.lo),
            "hi": str(defn.hi),
            "lo_float": float(defn.lo),
            "hi_float": float(defn.hi),
            "lo_closed": defn.lo_closed,
            "hi_closed": defn.hi_closed,
        },
        "form": defn.form,
        "domain": defn.domain_text,
        "space": defn.space,
        "degree": n,
        "atoms": [list(a) for a in atoms],
        "coefficients": [[F.ratfn(matrix[i, j]) for j in range(len(atoms))] for i in range(n + 1)],
        "functions": [{str(a): F.show(v, defn) for a, v in f} for f in defn.functions],
        "energies": {
            str(k): [[F.ratfn(x) for x in row] for row in F.gram(defn, k)] for k in F.ENERGY_ORDERS
        },
        "verdicts": {
            "partition_of_unity": F.partition_of_unity(defn),
            "bernstein_end_conditions": F.bernstein_end_conditions(defn),
            "symmetric": F.symmetric(defn),
            "independent": {
                "rank": rank,
                "of": n + 1,
                "determinant": F.show(det, defn) if det is not None else None,
            },
            "singular_points": F.singular_points(defn),
            "singular_scan": f"no other zero of a denominator in [{F.scan_start(defn)}, "
            f"{defn.hi}] (arb, mean-value form)"
            + (
                f"; (0, {F.SCAN_FLOOR}) not scanned (the series' leading terms are given)"
                if defn.lo == 0
                else ""
            ),
            "nonnegative": F.nonnegative(defn),
        },
        "ends": [
            {
                "t=0": [F.show(x, defn) for x in lo],
                f"t={defn.parameter}": [F.show(x, defn) for x in hi],
            }
            for lo, hi in ends
        ],
    }


def derive_orders(family: COrders) -> dict:
    """A family of several degrees (a seed and an integral recursion): one document per
    degree under "orders", each what `derive` gives for that degree alone."""
    first = family.orders[0]
    return {
        "format": FORMAT,
        "family": family.name,
        "definition_sha256": family.digest,
        "title": first.title,
        "kind": "frequency-orders",
        "parameter": first.parameter,
        "degrees": [o.degree for o in family.orders],
        "orders": {str(o.degree): _derive_order(o) for o in family.orders},
    }


def _derive_order(defn: CDefinition) -> dict:
    try:
        return derive(defn)
    except ValueError as exc:  # formulas/cbezier.py's refusal, as the definition's error
        if isinstance(exc, DefinitionError):
            raise
        raise DefinitionError(
            f"[family], key degrees: at degree {defn.degree}: {exc} (the recursion itself "
            "evaluates; the document is derived for the degrees below this one)"
        ) from None


def render(defn: CDefinition | COrders) -> str:
    doc = derive_orders(defn) if isinstance(defn, COrders) else derive(defn)
    return json.dumps(doc, indent=1, ensure_ascii=False) + "\n"


def read(table: dict, where: str) -> CDefinition | COrders:
    if is_recursion_table(table):
        orders = read_orders(table, where, nonvanishing)
        return COrders(orders[0].name, orders[0].digest, orders)
    return read_table(table, where)


def summary(doc: dict) -> str:
    """The verdicts as `derive --family` prints them (each degree's in turn)."""
    if "orders" in doc:
        return "\n".join(_summary(doc["orders"][str(n)]) for n in doc["degrees"])
    return _summary(doc)


def _summary(doc: dict) -> str:
    v = doc["verdicts"]
    ind = v["independent"]
    non = v["nonnegative"]
    lines = [
        f"family {doc['family']!r}: {doc['space']} space, degree {doc['degree']}, "
        f"{doc['parameter']} in {doc['range']['text']}, t in {doc['domain']}",
        f"  partition of unity: {v['partition_of_unity']} (exact)",
        f"  Bernstein end conditions: {v['bernstein_end_conditions']} (exact)",
        f"  symmetric t <-> {doc['parameter']} - t: {v['symmetric']} (exact)",
        f"  linearly independent: rank {ind['rank']} of {ind['of']} (exact)",
        f"  non-negative: {non['verdict']} ({non['method']}"
        + (f"; {non['sampled']})" if "sampled" in non else ")"),
    ]
    if "counterexample" in non:
        lines.append(f"    counterexample: {non['counterexample']}")
    if "reason" in non:
        lines.append(f"    not certified: {non['reason']}")
    for row in v["singular_points"]:
        lead = f", ~ {row['leading_term']}" if "leading_term" in row else ""
        lines.append(
            f"  singular: {doc['parameter']} = {row['at']} ({row['denominator']} = 0{lead}; "
            f"{row['where']})"
        )
    lines.append(f"  singular points scan: {v['singular_scan']}")
    if "small_alpha" in doc:
        sa = doc["small_alpha"]
        lines.append(
            f"  small {doc['parameter']}: exact series to {doc['parameter']}^{sa['order']} "
            f"used below {sa['below']} (largest omitted term there "
            f"{sa['omitted_at_threshold']:.2g}, measured)"
        )
    return "\n".join(lines)


def derived_path(definition_file: Path, name: str, out_dir: Path | None = None) -> Path:
    return (out_dir or Path(definition_file).resolve().parent) / f"{name}.derived.json"
