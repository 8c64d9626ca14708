"""The derived document of a trigonometric, hyperbolic or mixed family: ``"format": 4``
(issue #30; the contract between derive and the runtime is in docs/guide/own-family.md).

Polynomial families keep format 3 (derive/emit/document.py); this module writes only the
families whose functions use sin, cos, sinh, cosh or exp. Every value is exact: a rational
string, or [["coefficient", exponent], ...] in the document's constant (pi or exp(W)).
"""

from __future__ import annotations

from ..families.definition import Definition
from ..families.spaces import space_of
from ..formulas import atom_family as F
from ..formulas import atom_independence, touching
from ..formulas.joins_several import atom_end_forms, join_table
from .parameters import document_header, parameter_table

FORMAT = 4


def derive(defn: Definition) -> dict:
    space = space_of(defn)
    F.check_partition(defn, space)
    n = len(space.functions) - 1
    atoms, tables = F.coefficient_tables(space)
    swap = F.symmetry(defn, space)
    independence = atom_independence.independence(defn, space)
    checked = [
        f"the functions lie in the {space.name} space (atoms {', '.join(atoms)})",
        "partition of unity, exactly (atom coefficients)",
    ]
    if independence.get("independent") is True:
        checked.append("linearly independent over the whole parameter box")
    names = defn.parameters
    mid = defn.domain_lo + defn.domain_hi
    mirror = f"{mid}{'*pi' if defn.domain_unit == 'pi' and mid != 1 else ''}"
    mirror = f"{'pi' if defn.domain_unit == 'pi' and mid == 1 else mirror} - t"
    singular: dict
    if "reason" in independence:
        singular = {"reason": independence["reason"]}
    else:
        singular = {str(n): independence.get("singular", [])}
        if independence.get("everywhere"):
            singular = {"reason": "linearly dependent for every parameter value"}
    endpoints = {str(n): F.endpoints(space), "constant": space.constant}
    return {
        **document_header(defn, FORMAT),
        "space": space.name,
        "parameters": parameter_table(defn),
        "domain": {
            "lo": str(defn.domain_lo),
            "hi": str(defn.domain_hi),
            "unit": defn.domain_unit,
            "text": defn.domain_text,
        },
        "degrees": [n, n],
        "degree_offset": 0,
        "checked": checked,
        "symmetry": None
        if swap is None
        else {
            "swap": list(swap),
            "text": f"b_i(t; {', '.join(names)}) = b_{{n-i}}({mirror}; {', '.join(swap)})",
        },
        "basis": {str(n): [F.show_elem(b, defn, space) for b in space.functions]},
        "atoms": {str(n): atoms},
        "coefficients": {
            str(n): {
                F.mono_key(mono): [[str(v) for v in row] for row in table]
                for mono, table in sorted(tables.items())
            }
        },
        "rational": F.rational_form(space),
        "endpoints": endpoints,
        "endpoint_closed_orders": -1,
        "endpoint_closed_forms": None,
        "energy": F.energies(space),
        "nonnegative_over_box": touching.nonnegative_over_box(defn, space),
        "linear_independence": independence,
        "singular_parameters": singular,
        "joins": join_table(defn, n, atom_end_forms(defn, space), space.constant),
    }
