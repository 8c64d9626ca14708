"""The ``closed_n`` section of a derived document: end forms in closed form in n of a family
in several parameters over a range of degrees or of an indexed family, and the join weights
derived from them (derive/families/closed_n.py, derive/formulas/joins_closed_n.py)."""

from __future__ import annotations

from ..families.closed_n import closed_forms
from ..families.definition import Definition
from ..formulas.joins_closed_n import table_of

PROOF = (
    "Derived for a general n from the basis formula: the order of vanishing of b(i, n, t) at "
    "t = 0 (t = 1) is bounded below by i + c (n - i + c) for a symbolic i, so only the "
    "indices near each end contribute; at those, binomials and indices are decided with the "
    "papers' convention for every n >= proven_from, and the derivatives are taken "
    "symbolically in t with n a symbol. Every degree from the start of the range up to "
    "proven_from is checked against its own basis: the forms of orders 0..r hold for every "
    "n >= valid_from[r]. A polynomial fit in n per parameter monomial (the last two degrees "
    "held out) gives the same forms."
)
NOTATION = (
    "Index-relative parameters: name(k) is the parameter of index k (near the start), "
    "name(n) and name(n-k) those of index n and n - k (near the end), at every degree n."
)


def section(defn: Definition) -> tuple[dict, dict]:
    """(the ``closed_n`` section, the ``joins`` table in n and m): each a reason where the
    family has no closed forms in n."""
    closed = closed_forms(defn)
    if isinstance(closed, str):
        reason = {"reason": f"{closed}; the runtime joins per degree"}
        return {"reason": closed}, reason
    out: dict = {
        "proof": PROOF,
        "proven_from": closed.proven_from,
        "valid_from": {str(r): v for r, v in enumerate(closed.valid_from)},
        "checked": list(closed.checked),
        "symbols": [s.name for s in closed.symbols],
    }
    if defn.indexed is not None:
        out["notation"] = NOTATION
    out["forms"] = {f"{e},{r},{j}": str(v) for (e, r, j), v in sorted(closed.forms.items())}
    return out, table_of(defn, closed)
