"""Join weights in closed form in n and m of a family in several parameters over a range of
degrees, or of an indexed family (issue #30).

The end forms come from derive/families/closed_n.py, derived for a general n (with the
least degree from which they hold); the solve is derive/formulas/joins.py's, unchanged, with
n on the first curve and m on the second, and it checks every solution against its
conditions for general symbols. An indexed family's forms are in index-relative symbols:
lam(n) and lam(n-1) are the first curve's last parameters (``lam(n)1`` in the table), lam(1)
and lam(2) the second curve's first ones (``lam(1)2``). The table's ``valid_from`` gives,
per order (1 for C1/G1, 2 for C2/G2), the least degree from which the weights hold: the
family's curves on either side must have at least that degree.
"""

from __future__ import annotations

from ..families.closed_n import ClosedForms, closed_forms
from ..families.definition import Definition
from .joins_several import join_table


def closed_join_table(defn: Definition) -> dict:
    """The document's ``joins`` in closed form in n, m, or a reason."""
    closed = closed_forms(defn)
    if isinstance(closed, str):
        return {"reason": f"{closed}; the runtime joins per degree"}
    return table_of(defn, closed)


def table_of(defn: Definition, closed: ClosedForms) -> dict:
    forms = {k: v for k, v in closed.forms.items() if k[1] <= 2}
    table = join_table(defn, defn.degrees.start, forms, symbols=closed.symbols)
    pairs = table.pop("pairs")
    table["valid_from"] = {"1": closed.valid_from[1], "2": closed.valid_from[2]}
    table["pairs"] = pairs
    return table
