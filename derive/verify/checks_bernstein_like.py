"""Verify's checkers of the claims only 001 (the bernstein_like family's paper) makes.

001 prints the general-n explicit form of its basis (eq. 5), which no generic rule gives, and
its quadratic seed (eq. 1). derive/families/bernstein_like.toml names this module under
`checks`; verify/registry.py imports it with the shared checkers.
"""

from __future__ import annotations

import sympy as sp

from .. import algebra as _algebra
from ..families import bernstein_like as bl
from .checks_core import (
    Outcome,
    T,
    checker,
)
from .checks_equations import (
    check_equations,
)
from .claim_families import (
    symbolic_zero,
    to_derive,
)
from .context import (
    Context,
    equations_outcome,
)
from .expr_parse import (
    parse,
)

NAME = bl.DEFINITION.name

# 001's seed (eq. 1), checked by the shared models, is about this family only.
checker("seed_basis", family=NAME, only="it is 001's quadratic seed of the recursion")(
    check_equations
)


@checker("basis_explicit", family=NAME)
def check_explicit(record: dict, ctx: Context) -> Outcome:
    """Eq. 5: the printed factor q_i(t) = b_{i,n}/B_{i,n} against explicit_factor()
    symbolically, and the whole formula for every n and i."""
    eq = record["equations"][0]
    rhs = to_derive(parse(eq["rhs"]))
    n, i = _algebra.n, _algebra.i
    bern = sp.binomial(n, i) * T**i * (1 - T) ** (n - i)
    q_printed = sp.powsimp(sp.expand_power_base(rhs / bern), force=True)
    q_derived = bl.explicit_factor()
    diffs = []
    diff = sp.expand(sp.combsimp(sp.expand_func(q_printed - q_derived)))
    if not symbolic_zero(diff):
        for e in range(3):
            a = sp.factor(sp.combsimp(sp.expand_func(sp.expand(q_printed).coeff(T, e))))
            b = sp.factor(sp.expand(q_derived).coeff(T, e))
            if not symbolic_zero(a - b):
                diffs.append(f"symbolic: coefficient of t^{e} in b/B: printed {a}, derived {b}")
        if not diffs:
            diffs.append(f"symbolic: printed/B - derived factor = {sp.factor(diff)}")
    out = equations_outcome(record, ctx, record["equations"], extra_lines=diffs)
    out.checked.insert(0, "symbolic: factor vs explicit_factor()")
    return out
