"""A SymPy expression of the C-Bezier forms evaluated over arb balls: the one enclosure that the
sampled and the certified non-negativity (cbezier.py, cbezier_nonnegative.py) both use."""

from __future__ import annotations

import flint
import sympy as sp


def enclose(expr: sp.Expr, env: dict) -> flint.arb:
    """expr (Add, Mul, integer Pow, rationals and the symbols of env) over arb balls."""
    if expr.is_Rational:
        return flint.arb(flint.fmpq(int(expr.p), int(expr.q)))
    if expr.is_Symbol:
        return env[expr]
    if expr.is_Add:
        out = flint.arb(0)
        for a in expr.args:
            out += enclose(a, env)
        return out
    if expr.is_Mul:
        out = flint.arb(1)
        for a in expr.args:
            out *= enclose(a, env)
        return out
    if expr.is_Pow and expr.exp.is_Integer:
        base = enclose(expr.base, env)
        return base ** int(expr.exp) if expr.exp > 0 else 1 / base ** int(-expr.exp)
    if isinstance(expr, sp.sin | sp.cos | sp.sinh | sp.cosh):
        arg = enclose(expr.args[0], env)
        return getattr(arg, type(expr).__name__)()
    raise TypeError(f"cannot enclose {expr}")  # pragma: no cover - the reader's forms only
