"""The continuity between two patches when either is a surface of a trigonometric, hyperbolic
or mixed family (atom_surfaces): what `CompositeSurface.report` says at their boundary.

Polynomial patches (every `Surface`, `ParamSurface` included) are compared on their exact
Bézier forms (surface_joins). An `AtomSurface` has none, so the boundary is compared in the
families' own parameters, as `join_surface` joins them: across the boundary each patch's
derivatives in its own t (A at the end of its domain, B at the start of its), along it the
common direction. With a across-direction basis b_i and the net P, the r-th cross
derivative on the boundary is Σ_j c^r_j b_j(v), c^r_j = Σ_i P_ij b_i^(r)(end).

- When both patches have the same family, degree and parameters along the boundary, the two
  sides are combinations of the same linearly independent functions, so they agree exactly
  when their coefficients c^r_j do (the columns of join_surface). The end derivatives
  b_i^(r)(end) are exact where the atoms' values there are rational: 1 and t^k at 0, and
  cos, sin, cosh, sinh at 0, and cos, sin at a multiple of a quarter period (a
  trigonometric family on [0, π/2]); for exact patches the comparison is then exact, as for
  polynomial patches. Otherwise it is in floats, within `tol` times the coefficients' size
  (10·tol for the first derivative, 100·tol for the second, as for polynomial patches).
- Otherwise (another family or other parameters along the boundary, or a polynomial patch
  next to an atom patch) the functions are compared at 33 points along the boundary, spread
  over it as Chebyshev points, in floats with the same tolerances: a sampled verdict, enough
  to tell continuity from its absence for the small bases here, not a proof.

G1 is A_u = α B_u with one constant α > 0 along the boundary (join_surface's G1), or in
general tangent planes that agree along it, B_u = μ A_u + ν A_v with μ(v) > 0 (`g1_sampled`,
_tangent_planes: at the 33 points, a sampled verdict).
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

import numpy as np

from . import _poly_direction as pd
from ._atom_joins import _atom_at_zero
from ._family_document import combine

Number = Fraction | float
SAMPLES = 33


def is_atom_patch(surf: object) -> bool:
    """Whether `surf` is a surface of trigonometric, hyperbolic or mixed families."""
    return hasattr(surf, "_probes") and hasattr(surf, "to_rational_bezier")


def _domain(surf: Any, axis: int) -> tuple[float, float]:
    if is_atom_patch(surf):
        out: tuple[float, float] = surf.domain_u if axis == 0 else surf.domain_v
        return out
    return (0.0, 1.0)


def _atom_at(atom: Any, r: int, where: Fraction, unit: str) -> Fraction | None:
    """The r-th derivative of one document atom at t = where·(π if unit == "pi" else 1),
    exactly, or None where it is irrational (or not decided here)."""
    if atom.pi and r and atom.kind not in ("1", "t"):
        return None  # a frequency ωπ: the derivative carries a power of π
    if where == 0:
        return _atom_at_zero(atom, r)
    if atom.kind == "1":
        return Fraction(1 if r == 0 else 0)
    if atom.kind == "t":
        return None if r <= atom.power else Fraction(0)
    if atom.kind not in ("cos", "sin") or atom.pi or unit != "pi":
        return None
    quarters = 2 * atom.omega * where  # the phase ω·t in units of π/2
    if quarters.denominator != 1:
        return None
    # d^r/dt^r cos(ωt) = ω^r cos(ωt + rπ/2), sin likewise: a quarter turn per derivative
    turn = (int(quarters) + r + (3 if atom.kind == "sin" else 0)) % 4
    out: Fraction = atom.omega**r * (1, 0, -1, 0)[turn]
    return out


def _end_weights(surf: Any, axis: int, at_end: bool, order: int) -> list[list[Number]]:
    """w[r][i] = b_i^(r) at the end (at_end) or start of direction `axis`: exact Fractions
    where the atoms' values there are rational and the parameters exact, else floats."""
    probe = surf._probes[axis]
    if isinstance(probe, pd.PolyProbe):  # a polynomial direction: its Bernstein form's ends
        out_poly: list[list[Number]] = probe.end_derivatives(order, at_end)
        return out_poly
    data = probe.data
    lo, hi, unit = data.DOMAIN_EXACT
    where = hi if at_end else lo
    basis = combine(data.COEFFICIENTS[probe.degree], surf._values[axis])
    exact_params = surf._exact_params[axis]
    out: list[list[Number]] = []
    for r in range(order + 1):
        found = [_atom_at(a, r, Fraction(where), unit) for a in probe.shape.atoms]
        at = [x for x in found if x is not None]
        if exact_params and len(at) == len(found):
            out.append(
                [sum((c * x for c, x in zip(b, at, strict=True)), Fraction(0)) for b in basis]
            )
        else:
            t = probe.domain[1] if at_end else probe.domain[0]
            out.append([float(x) for x in probe.basis(t, r)])
    return out


def _coefficients(surf: Any, axis: int, at_end: bool, order: int) -> list[list[Any]]:
    """c[r][j] = Σ_i P_ij b_i^(r)(end) (axis 0; rows and columns swapped for axis 1): the
    coefficients along the boundary of the r-th cross derivative, exact where all is."""
    weights = _end_weights(surf, axis, at_end, order)
    exact = surf.is_exact and all(isinstance(w, Fraction) for row in weights for w in row)
    rows: Any = surf.control_net() if exact else surf.net.tolist()
    lines = [[rows[i][j] for i in range(len(rows))] for j in range(len(rows[0]))]
    if axis == 1:
        lines = [list(r) for r in rows]
    out = []
    for w in weights:
        coeffs = []
        for line in lines:
            dim = len(line[0])
            coeffs.append(
                tuple(
                    sum(
                        ((x if exact else float(x)) * p[c] for x, p in zip(w, line, strict=True)),
                        0 * line[0][c],
                    )
                    for c in range(dim)
                )
            )
        out.append(coeffs)
    return out


def _same_along(a: Any, b: Any, axis: int) -> bool:
    if not (is_atom_patch(a) and is_atom_patch(b)):
        return False
    along = 1 - axis
    fa = a.family_v if axis == 0 else a.family_u
    fb = b.family_v if axis == 0 else b.family_u
    return bool(
        pd.family_name(fa) == pd.family_name(fb)
        and a.net.shape[along] == b.net.shape[along]
        and tuple(a._values[along]) == tuple(b._values[along])
    )


def _sampled(surf: Any, axis: int, at_end: bool, order: int) -> list[list[Any]]:
    """The r-th cross derivative at SAMPLES Chebyshev points along the boundary."""
    lo, hi = _domain(surf, 1 - axis)
    k = np.arange(SAMPLES)
    along = lo + (hi - lo) * 0.5 * (1 - np.cos(np.pi * k / (SAMPLES - 1)))
    across = _domain(surf, axis)[1 if at_end else 0]
    out = []
    for r in range(order + 1):
        if axis == 0:
            vals = surf.derivative(np.full(SAMPLES, across), along, r, 0)
        else:
            vals = surf.derivative(along, np.full(SAMPLES, across), 0, r)
        out.append([tuple(float(x) for x in p) for p in vals])
    return out


def g1_sampled(a: Any, b: Any, axis: int, eps: float) -> bool:
    """Whether the tangent planes of `a` (at the end of direction `axis`) and `b` (at its
    start) agree at the SAMPLES points along the boundary, B's side continuing A's (see
    _tangent_planes.span_sampled; `eps` the tolerance on a first derivative)."""
    from ._tangent_planes import span_sampled

    lo, hi = _domain(a, 1 - axis)
    k = np.arange(SAMPLES)
    along = lo + (hi - lo) * 0.5 * (1 - np.cos(np.pi * k / (SAMPLES - 1)))
    across = np.full(SAMPLES, _domain(a, axis)[1])
    uv = (across, along) if axis == 0 else (along, across)
    cross, tangent = ((1, 0), (0, 1)) if axis == 0 else ((0, 1), (1, 0))
    first = np.asarray(a.derivative(*uv, *cross), dtype=float)
    along_a = np.asarray(a.derivative(*uv, *tangent), dtype=float)
    other = np.array(_sampled(b, axis, False, 1)[1], dtype=float)
    return span_sampled(first, along_a, other, eps)


def _close(a: list[Any], b: list[Any], tol: float) -> bool:
    return all(
        abs(x - y) <= tol for p, q in zip(a, b, strict=True) for x, y in zip(p, q, strict=True)
    )


def proportional(a: list[Any], b: list[Any], tol: float) -> bool:
    """a = α b with one α > 0, coordinate by coordinate within `tol` (the G1 test of
    surface_joins' report too)."""
    flat_a = [x for p in a for x in p]
    flat_b = [x for p in b for x in p]
    k = max(range(len(flat_b)), key=lambda i: abs(flat_b[i]))
    if not flat_b[k] or not flat_a[k]:
        return False
    alpha = flat_a[k] / flat_b[k]
    return bool(alpha > 0) and all(
        abs(x - alpha * y) <= tol for x, y in zip(flat_a, flat_b, strict=True)
    )


def continuity(a: Any, b: Any, axis: int, tol: float) -> str:
    """ "none", "C0", "G1", "C1" or "C2" between `a` and the next patch `b` across the end of
    direction `axis` (0: u) of `a`; see the module's doc."""
    if _same_along(a, b, axis):
        da, db = _coefficients(a, axis, True, 2), _coefficients(b, axis, False, 2)
    else:
        if a.net.shape[2] != b.net.shape[2]:
            return "none"
        da, db = _sampled(a, axis, True, 2), _sampled(b, axis, False, 2)
    exact = all(
        isinstance(x, Fraction) for side in (da, db) for row in side for p in row for x in p
    )
    size = max((abs(float(x)) for row in da[0] + db[0] for x in row), default=0.0)
    scale = [
        max(size, max((abs(float(x)) for p in da[r] + db[r] for x in p), default=0.0), 1.0)
        for r in range(3)
    ]
    eps = [0.0, 0.0, 0.0] if exact else [tol * scale[0], 10 * tol * scale[1], 100 * tol * scale[2]]
    if not _close(da[0], db[0], eps[0]):
        return "none"
    if not _close(da[1], db[1], eps[1]):
        # the tangent planes are compared at sample points, in floats also for exact
        # patches: the float tolerance on a first derivative
        if proportional(da[1], db[1], eps[1]) or g1_sampled(a, b, axis, 10 * tol * scale[1]):
            return "G1"
        return "C0"
    return "C2" if _close(da[2], db[2], eps[2]) else "C1"


def local(surf: Any, fu: float, fv: float) -> tuple[float, float]:
    """A patch's own parameters at the fractions (fu, fv) of its domain (atom patches live on
    their families' domains, polynomial ones on [0, 1]²)."""
    (a, b), (c, d) = _domain(surf, 0), _domain(surf, 1)
    return a + (b - a) * fu, c + (d - c) * fv
