"""Join weights between two C-Bezier curves (issue #30), of one family or of two (degrees n
and m, trigonometric or hyperbolic, on [0, alpha] or [0, 1], each side its own): the leading
control points of the second curve that make the joint C1, C2, G1 or G2, solved from the
families' exact end derivatives (formulas/cbezier.end_table), each curve with its own
parameter.

The conventions are derive/formulas/joins.py's, in each curve's own parameter (t on
[0, alpha], or u on [0, 1] for a family written there, whose r-th derivative carries
alpha^r):

    C1:  C1(end) = C2(0),  C1'(end) = C2'(0);   C2: and C1''(end) = C2''(0)
    G1:  C1(end) = C2(0),  C1'(end) = a C2'(0);  G2: and C1''(end) = a^2 C2''(0) + d C2'(0)

with a, d the G constants (named alpha and d in records; the curves' parameters are the
family's parameter with the suffix 1 or 2). A weight is a key "row,src,k": P2_row = sum of
weight * X_k, X_k = P1_(n-k) (src "first") or P2_k (src "second", a point not solved for).
The weights are rational functions of (alpha1, sin alpha1, cos alpha1, alpha2, sin alpha2,
cos alpha2, a, d); a difference is zero exactly when its numerator reduced modulo both
circles (hyperbolas) is zero (two independent angles: the ideal is prime, as in cbezier.py).
"""

from __future__ import annotations

import sympy as sp

from ..families.cbezier import A, C, CDefinition, S
from . import cbezier as F

A1, S1, C1, A2, S2, C2 = sp.symbols("alpha1_ s1_ c1_ alpha2_ s2_ c2_")
G_ALPHA, G_D = sp.symbols("alpha d")
ORDER = {"C1": 1, "C2": 2, "G1": 1, "G2": 2}


def _side(value: sp.Expr, side: int) -> sp.Expr:
    a, s, c = (A1, S1, C1) if side == 1 else (A2, S2, C2)
    return value.xreplace({A: a, S: s, C: c})


def weights(
    defn: CDefinition, continuity: str, other: CDefinition | None = None
) -> dict[str, sp.Expr]:
    """{"row,src,k": weight} for the join of a curve of `defn` (side 1) into a curve of
    `other` (side 2; `defn` again when None); ValueError when the conditions do not determine
    the points. The r-th condition involves P2_0..P2_r (and given points beyond the solved
    ones): solved in order, each point a linear combination {(src, k): weight} (no general
    solver: it is triangular)."""
    other = defn if other is None else other
    order = ORDER[continuity]
    n, m = defn.degree, other.degree
    if order > min(n, m):
        raise ValueError(f"{continuity} needs degree >= {order}, the families have {n} and {m}")
    ends1, ends2 = F.end_table(defn), F.end_table(other)

    def first(r: int) -> dict:  # C1^(r) at its end: X_k = P1_(n-k)
        scale = A1**r if defn.form == "unit" else sp.Integer(1)
        return {("first", n - j): scale * _side(ends1[j][1][r], 1) for j in range(n + 1)}

    def second(r: int) -> dict:  # C2^(r)(0): the coefficients of P2_i
        scale = A2**r if other.form == "unit" else sp.Integer(1)
        return {i: scale * _side(ends2[i][0][r], 2) for i in range(m + 1)}

    def add(out: dict, combo: dict, factor: sp.Expr) -> None:
        for key, w in combo.items():
            out[key] = out.get(key, sp.Integer(0)) + factor * w

    solved: list[dict] = []
    for r in range(order + 1):
        lhs: dict = {}  # coefficients of P2_i on the left: sum g * C2^(r')(0)
        if r == 0 or continuity.startswith("C"):
            parts = [(sp.Integer(1), r)]
        elif r == 1:
            parts = [(G_ALPHA, 1)]
        else:
            parts = [(G_ALPHA**2, 2), (G_D, 1)]
        for factor, rr in parts:
            for i, w in second(rr).items():
                if w != 0:
                    lhs[i] = lhs.get(i, sp.Integer(0)) + factor * w
        pivot = lhs.pop(r, sp.Integer(0))
        if pivot == 0 or any(r < i <= order for i in lhs):
            raise ValueError(f"the {continuity} conditions do not determine P2_{r} in order")
        rhs: dict = {}
        add(rhs, first(r), sp.Integer(1))
        for i, w in lhs.items():
            if i < r:
                add(rhs, solved[i], -w)
            else:  # a point beyond the solved ones: given
                add(rhs, {("second", i): sp.Integer(1)}, -w)
        solved.append({key: w / pivot for key, w in rhs.items()})
    out = {}
    for row, combo in enumerate(solved):
        for (src, k), w in sorted(combo.items()):
            w = sp.together(w)
            if sp.fraction(w)[0] != 0 and reduce2(w, defn.hyperbolic, other.hyperbolic) != 0:
                out[f"{row},{src},{k}"] = w
    return out


def reduce2(expr: sp.Expr, hyperbolic: bool, second_hyperbolic: bool | None = None) -> sp.Expr:
    """The numerator of expr reduced modulo both circles (hyperbolas; side 2's as
    `second_hyperbolic` says, the same as side 1's when None): 0 exactly when expr is zero
    as a function of the two angles."""
    num = sp.fraction(sp.together(expr))[0]
    hyp2 = hyperbolic if second_hyperbolic is None else second_hyperbolic
    for s, c, hyp in ((S1, C1, hyperbolic), (S2, C2, hyp2)):
        square = c**2 - 1 if hyp else 1 - c**2
        poly = sp.Poly(sp.expand(num), s)
        num = sp.expand(
            sum(
                (coeff * square ** (e // 2) * s ** (e % 2) for (e,), coeff in poly.terms()),
                sp.Integer(0),
            )
        )
    return num


def show(expr: sp.Expr, defn: CDefinition, other: CDefinition | None = None) -> str:
    other = defn if other is None else other
    a1, a2 = sp.Symbol(f"{defn.parameter}1"), sp.Symbol(f"{other.parameter}2")
    sin1, cos1 = (sp.sinh, sp.cosh) if defn.hyperbolic else (sp.sin, sp.cos)
    sin2, cos2 = (sp.sinh, sp.cosh) if other.hyperbolic else (sp.sin, sp.cos)
    return str(
        sp.factor(expr).xreplace(
            {S1: sin1(a1), C1: cos1(a1), S2: sin2(a2), C2: cos2(a2), A1: a1, A2: a2}
        )
    )
