r"""A curve over the centred atoms (`hazmat.atoms`) as a piecewise polynomial in t, with a
certified bound on the truncation error (issue #30: evaluation at the cost of a polynomial).

Every coordinate of such a curve is an entire function f(τ), τ = t − mid, so on a piece of
half-width h about a centre c its Taylor polynomial of degree p differs from it by at most
(Lagrange's remainder)

    |f(t) − T_p(t)| <= max |f^(p+1)| · h^(p+1) / (p+1)!   on the piece,

and the atoms bound f^(p+1) without sampling (`remainder_bound`):

- a pair a·cos(νt) + b·sin(νt), ν = jω: the derivative is a sinusoid of amplitude
  hypot(a, b)·ν^(p+1);
- a pair a·cosh(νt) + b·sinh(νt): at most (|a| + |b|)·ν^(p+1)·cosh(ν R), R the largest |τ|
  on the domain;
- a power a·τ^i: zero when i <= p, else |a|·i!/(i−p−1)!·R^(i−p−1).

`choose_pieces` takes the lowest degree p (from `DEGREES`) for which some number of equal
pieces m <= MAX_PIECES brings that bound below half a unit in the last place of the curve's
coordinate scale (its largest coordinate magnitude, sampled on the domain: a chosen target,
the bound itself is certified) with a table of at most `TABLE_BYTES` (in the L2 cache); the
least such m is found by bisection, the bound growing with the piece's width. Degree 4 is the
lowest tried: measured on han_trig_cubic, degrees 3 and 4 cost the same (degree 3 needs ~9000
pieces, a 570 KB table) and 5–7 more (more passes of Horner's rule). `piece_table` builds
the Taylor coefficients of every piece from the exact derivatives of the atoms;
`evaluate_pieces` evaluates it: the piece of t by one multiplication, Horner's rule in
t − centre, |t − centre| <= h. The certificate covers the truncation (for the curve's float
coefficients over the atoms, which the atom evaluation uses too); the table's own rounding is
that of the atom evaluation at the centres (the coefficient of degree 0 is the curve's value
there), and Horner's rule with |t − c| <= h adds about one rounding of the value, so the
result is within a few ulps of the coordinate scale, as the evaluation by the atoms is.

`evaluate_pieces` is numpy, blocked so each pass stays in cache; `atom_pieces_compiled` (numba,
the `fast` extra) runs the same operations in the same order, so the two agree bit for bit (no
fused multiply-add in either). Only the compiled kernel is used for speed: in numpy, one
gather per coefficient and parameter made the piecewise form 4-7x a polynomial cubic's
evaluation at 10^6 parameters (also with the piece's row gathered at once, and with a
row-wise product on the powers of t − centre), slower than the atoms (issue #30).
"""

from __future__ import annotations

import math
from types import ModuleType
from typing import NamedTuple

import numpy as np

from . import atoms as ak
from . import kernels

DEGREES = tuple(range(4, 14))  # the degrees of the pieces tried, lowest first
MAX_PIECES = 1 << 14
TABLE_BYTES = 1 << 18  # the largest table preferred: it stays in the L2 cache
_BLOCK = 4096  # parameters per block of the numpy path: each pass runs in cache
_SAFETY = 1.0 + 2.0**-30  # covers the rounding of the bound's own float arithmetic
PIECES_FROM = 1024  # parameters from which a curve goes through its pieces (atom_family)
_COMPILED_FROM = 256  # below this the numpy path is as fast, and numba is not imported


class PieceTable(NamedTuple):
    """m pieces of width `width` from `lo`; `table[c, e, k]` is the coefficient of
    (t − centres[k])^e of coordinate c on piece k (pieces along the last axis, so that one
    pass of Horner's rule gathers from one contiguous row); `bound` the certified truncation
    bound (largest over the coordinates), `tolerance` what it was chosen against."""

    lo: float
    width: float
    inv_width: float
    centres: np.ndarray
    table: np.ndarray
    bound: float
    tolerance: float

    @property
    def degree(self) -> int:
        return int(self.table.shape[1]) - 1

    @property
    def pieces(self) -> int:
        return int(self.table.shape[2])


class CentredCurve(NamedTuple):
    """A curve over the centred atoms (`hazmat.atoms`) on its domain [lo, hi]: the
    coefficients (A, d) of 1, τ, …, τ^powers, then cos/sin (or cosh/sinh) of jω0τ for
    j = 1..harmonics, in τ = t − mid. What every step here reads of the curve."""

    coefficients: np.ndarray
    lo: float
    hi: float
    mid: float
    omega0: float
    powers: int
    harmonics: int
    hyperbolic: bool


class Amplitudes(NamedTuple):
    """What the remainder bound needs of a curve's coefficients (per coordinate c): the
    powers' |a_i| (K+1, d), each harmonic's amplitude (J, d) (hypot(a, b) for a sinusoid,
    |a| + |b| for cosh and sinh), the frequencies jω (J,), and whether they are hyperbolic."""

    powers: np.ndarray
    waves: np.ndarray
    frequencies: np.ndarray
    hyperbolic: bool


def amplitudes(curve: CentredCurve) -> Amplitudes:
    """The `Amplitudes` of the curve's coefficients."""
    coefficients, harmonics = curve.coefficients, curve.harmonics
    base = 1 + curve.powers
    cos_like = coefficients[base::2][:harmonics]
    sin_like = coefficients[base + 1 :: 2][:harmonics]
    if curve.hyperbolic:
        waves = np.abs(cos_like) + np.abs(sin_like)
    else:
        waves = np.hypot(cos_like, sin_like)
    return Amplitudes(
        np.abs(coefficients[:base]),
        waves,
        curve.omega0 * np.arange(1, harmonics + 1, dtype=float),
        curve.hyperbolic,
    )


def remainder_bound(amp: Amplitudes, degree: int, half_width: float, radius: float) -> np.ndarray:
    """(d,): for each coordinate, a bound on |f − T_degree| over any piece of half-width
    `half_width` lying within |τ| <= radius (the module docstring's bounds); inf where it
    overflows."""
    q = degree + 1
    total = np.zeros(amp.waves.shape[1] if amp.waves.size else amp.powers.shape[1])
    with np.errstate(over="ignore", invalid="ignore", under="ignore"):
        for i in range(q, amp.powers.shape[0]):
            # d^q τ^i = i!/(i−q)! τ^(i−q); times h^q/q! it is C(i, q) h^q R^(i−q)
            total += amp.powers[i] * (math.comb(i, q) * half_width**q * radius ** (i - q))
        if amp.frequencies.size:
            # (ν h)^q / q! as a product of q factors, so that no factor overflows on its own
            x = amp.frequencies * half_width
            weight = np.ones_like(x)
            for s in range(1, q + 1):
                weight *= x / s
            if amp.hyperbolic:
                arg = amp.frequencies * radius
                weight = weight * np.where(arg < 700.0, np.cosh(np.minimum(arg, 700.0)), np.inf)
            total += weight @ amp.waves
    return np.where(np.isnan(total), np.inf, total * _SAFETY)


def coordinate_scale(curve: CentredCurve, samples: int = 257) -> float:
    """The largest coordinate magnitude of the curve at `samples` equally spaced t of the
    domain (ends included): the scale the tolerance is taken against."""
    c = curve
    tau = np.linspace(c.lo, c.hi, samples) - c.mid
    values = ak.evaluate(c.coefficients, tau, c.omega0, c.powers, c.harmonics, c.hyperbolic)
    return float(np.abs(values).max()) if values.size else 0.0


def choose_pieces(curve: CentredCurve) -> tuple[int, int, float, float] | None:
    """(degree, pieces, bound, tolerance) of the cheapest piecewise form whose certified
    truncation bound is at most half an ulp of the coordinate scale, or None when no degree
    in DEGREES reaches it with at most MAX_PIECES pieces (or the values are not finite)."""
    lo, hi = curve.lo, curve.hi
    if not np.isfinite(curve.coefficients).all() or not hi > lo:
        return None
    scale = coordinate_scale(curve)
    if not math.isfinite(scale):
        return None
    tolerance = scale * 2.0**-54
    span = hi - lo
    # a parameter may sit a few ulps outside its piece (the index is computed in floats, and
    # the domain's rounded ends are accepted to 4 ulps): the bound covers a slightly wider piece
    slack = 8.0 * float(np.spacing(max(abs(lo), abs(hi), 1.0)))
    radius = 0.5 * span + slack
    dim = curve.coefficients.shape[1]
    amp = amplitudes(curve)
    fallback: tuple[int, int, float, float] | None = None
    for degree in DEGREES:

        def bound(m: int, degree: int = degree) -> float:
            h = 0.5 * span / m * (1.0 + 2.0**-30) + slack
            return float(remainder_bound(amp, degree, h, radius).max())

        if bound(MAX_PIECES) > tolerance:
            continue
        small, big = 1, MAX_PIECES  # the bound grows with the width: bisect on m
        while small < big:
            m = (small + big) // 2
            if bound(m) <= tolerance:
                big = m
            else:
                small = m + 1
        found = (degree, small, bound(small), tolerance)
        if small * dim * (degree + 1) * 8 <= TABLE_BYTES:
            return found
        if fallback is None:
            fallback = found
    return fallback


def piece_table(
    curve: CentredCurve,
    derivative: np.ndarray,
    degree: int,
    pieces: int,
    bound: float = math.nan,
    tolerance: float = math.nan,
) -> PieceTable:
    """The Taylor coefficients f^(e)(c_k)/e!, e <= degree, of every piece's centre c_k, from
    the exact derivatives of the atoms (`derivative`, hazmat.atoms.derivative_matrix)."""
    c = curve
    width = (c.hi - c.lo) / pieces
    centres = c.lo + (np.arange(pieces) + 0.5) * width
    values = ak.atom_values(centres - c.mid, c.omega0, c.powers, c.harmonics, c.hyperbolic)
    dim = c.coefficients.shape[1]
    table = np.empty((dim, degree + 1, pieces))
    current = c.coefficients
    factorial = 1.0
    for e in range(degree + 1):
        if e:
            current = derivative @ current
            factorial *= e
        table[:, e, :] = (current.T @ values) / factorial
    return PieceTable(c.lo, width, 1.0 / width, centres, table, bound, tolerance)


def evaluate_pieces(pieces: PieceTable, t: np.ndarray) -> np.ndarray:
    """(d, len(t)): the piecewise polynomial at every t (numpy; t within the domain up to a
    few ulps). The piece is int((t − lo)/width) clamped to [0, m − 1]; Horner's rule in
    t − centre, one multiplication and one addition per degree, blocked over t so that every
    pass runs in cache (the compiled kernel's operations in its order)."""
    table, centres = pieces.table, pieces.centres
    dim, size, m = table.shape
    out = np.empty((dim, t.size))
    for start in range(0, t.size, _BLOCK):
        x = t[start : start + _BLOCK]
        k = ((x - pieces.lo) * pieces.inv_width).astype(np.intp)
        np.clip(k, 0, m - 1, out=k)
        u = x - centres[k]
        for c in range(dim):
            acc = out[c, start : start + _BLOCK]
            np.take(table[c, size - 1], k, out=acc)
            for e in range(size - 2, -1, -1):
                acc *= u
                acc += table[c, e, k]
    return out


def build(curve: CentredCurve, derivative: np.ndarray) -> PieceTable | None:
    """`choose_pieces` then `piece_table`; None when no piecewise form is certified, or when
    its values could approach the float range (the caller then evaluates the atoms)."""
    chosen = choose_pieces(curve)
    if chosen is None:
        return None
    degree, count, bound, tolerance = chosen
    pieces = piece_table(curve, derivative, degree, count, bound, tolerance)
    with np.errstate(over="ignore", invalid="ignore"):
        # |value| <= Σ_e |c_e| h^e on a piece (h <= width): far below overflow, so the
        # caller need not check the result
        powers_of_h = pieces.width ** np.arange(degree + 1)
        largest = float((np.abs(pieces.table) * powers_of_h[:, None]).sum(axis=1).max())
    if not largest < 2.0**1000:
        return None
    return pieces


def compiled() -> ModuleType | None:
    """hazmat.atom_pieces_compiled when kernels.USE_COMPILED, else None (the numpy path)."""
    if not kernels.USE_COMPILED:
        return None
    from . import atom_pieces_compiled  # numba compiles (or loads its cache) on first use

    return atom_pieces_compiled


def evaluate(pieces: PieceTable, t: np.ndarray) -> np.ndarray:
    """(d, len(t)): `evaluate_pieces`, by the compiled kernel when there is one (same
    values, bit for bit)."""
    fast = compiled() if t.size >= _COMPILED_FROM else None
    if fast is None:
        return evaluate_pieces(pieces, t)
    out = np.empty((pieces.table.shape[0], t.size))
    fast.evaluate_pieces(
        np.ascontiguousarray(t, dtype=float),
        pieces.lo,
        pieces.inv_width,
        pieces.centres,
        pieces.table,
        out,
    )
    return out
