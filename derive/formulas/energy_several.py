"""E_k of a family in several parameters whose basis is not affine in them (issue #30 item 3).

Write the degree-n functions by parameter monomials, b_i = sum_a x^a c_{a,i}(t). Then
E_k = int |C^(k)|^2 dt = sum_{a, b} x^(a + b) tr(P^T G_ab P), where
G_ab[i][l] = int_0^1 c_{a,i}^(k) c_{b,l}^(k) dt. The sum runs over ordered pairs; the document
stores a <= b, and the runtime counts a < b twice. E_k is then a polynomial in the parameters,
and lambda_bezier.energy minimises it over the box by certified branch and bound. A basis
that is affine in the parameters keeps derive/formulas/family.py's Gram matrices of its
affine parts.
"""

from __future__ import annotations

import sympy as sp

from ..families.definition import ENERGY_ORDERS, Definition
from ..families.engine import monomial_split


def _inner(p: sp.Poly, q: sp.Poly, k: int, t: sp.Symbol) -> sp.Rational:
    prod = (p.diff((t, k)) * q.diff((t, k))).integrate()
    return prod.eval(1) - prod.eval(0)


def monomial_grams(defn: Definition) -> dict:
    """{"n,k": {"a;b": G}} with a <= b the parameter monomials as "e_1,...,e_J" (sorted), G
    as exact strings."""
    t = sp.Symbol("t")
    out: dict = {}
    for deg in defn.degrees:
        split = monomial_split(defn, deg)
        monos = sorted(split)
        parts = {m: [sp.Poly(p.as_expr(), t) for p in split[m]] for m in monos}
        for k in ENERGY_ORDERS:
            entry = {}
            for ia, a in enumerate(monos):
                for b in monos[ia:]:
                    gram = [[str(_inner(pa, pb, k, t)) for pb in parts[b]] for pa in parts[a]]
                    entry[f"{','.join(map(str, a))};{','.join(map(str, b))}"] = gram
            out[f"{deg},{k}"] = entry
    return out
