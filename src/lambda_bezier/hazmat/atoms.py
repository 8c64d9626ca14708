r"""Curves in a space of atoms: 1, τ^k, cos(jωτ), sin(jωτ) (or cosh, sinh), τ = t − mid.

A family of issue #30 writes its basis functions as exact combinations of atoms (`1`,
`t^K`, `cos(W*t)`, `sin(W*t)`, `cosh(W*t)`, `sinh(W*t)`, W a positive rational or a rational
times π). The classes above parse the atom strings (`parse_atom`), bring every frequency to
integer multiples j of one base frequency ω, and rewrite the curve about the middle of its
domain: its coefficients then form a (A, d) matrix over the *centred atoms* in the order

    1, τ, τ², …, τ^K, cos(ωτ), sin(ωτ), cos(2ωτ), sin(2ωτ), …, cos(Jωτ), sin(Jωτ)

(cosh/sinh for a hyperbolic space). Differentiation is exact on that basis
(`derivative_matrix`), so a derivative of any order is the same evaluation with other
coefficients.

Evaluation (`evaluate`): the values of the centred atoms at every τ (`atom_values`: sin and
cos of ωτ once, then the Chebyshev recurrences c_{j+1} = 2 c_1 c_j − c_{j−1}; e^{ωτ} once for
the hyperbolic ones), then one matrix product. For a purely trigonometric curve whose angle
ωτ stays within ±π/2 there is a faster path (`half_angle_coefficients`, `evaluate_half_angle`):
with u = tan(ωτ/2), e^{ijωτ} = (1 + iu)^{2j} / (1 + u²)^j, so the curve is N(u) / (1 + u²)^J
with N a polynomial of degree 2J, |u| ≤ 1: one tan, Horner's rule in u for the d numerator
coordinates and the denominator, one division (numpy's tan is several times faster than its
sin and cos).
"""

from __future__ import annotations

import re
from fractions import Fraction
from math import comb
from typing import NamedTuple

import numpy as np

from .kernels import cpu_count, on_threads

KINDS = ("1", "t", "cos", "sin", "cosh", "sinh")
_NUMBER = r"[1-9][0-9]{0,30}(?:/[1-9][0-9]{0,30})?"
_ATOM = re.compile(
    rf"^(?:(?P<one>1)|t(?:\^(?P<power>[1-9][0-9]?))?"
    rf"|(?P<kind>cosh|sinh|cos|sin)\((?:(?P<w>{_NUMBER})(?P<pi>\*pi)?\*|(?P<bare_pi>pi)\*)?t\))$"
)


class Atom(NamedTuple):
    """One atom: kind ("1", "t", "cos", "sin", "cosh", "sinh"), the power of t (kind "t"),
    and the frequency W = omega (· π when `pi`)."""

    kind: str
    power: int
    omega: Fraction
    pi: bool


def parse_atom(text: str) -> Atom:
    """The atom a string of the contract's grammar names; ValueError for anything else.
    Accepted: ``1``, ``t``, ``t^K``, ``cos(W*t)``, ``sin(p/q*pi*t)``, ``cos(pi*t)``,
    ``cos(t)`` (W = 1)."""
    m = _ATOM.match(text) if isinstance(text, str) and len(text) < 100 else None
    if m is None:
        raise ValueError(f"{text!r} is not an atom (1, t^K, cos(W*t), sin(W*t), cosh, sinh)")
    if m.group("one"):
        return Atom("1", 0, Fraction(0), False)
    kind = m.group("kind")
    if kind is None:
        return Atom("t", int(m.group("power") or 1), Fraction(0), False)
    w = Fraction(m.group("w")) if m.group("w") else Fraction(1)
    return Atom(kind, 0, w, bool(m.group("pi") or m.group("bare_pi")))


def base_frequency(omegas: list[Fraction]) -> Fraction:
    """The largest ω0 of which every ω is an integer multiple (the gcd of rationals)."""
    from math import gcd, lcm

    num = 0
    den = 1
    for w in omegas:
        num = gcd(num, w.numerator)
        den = lcm(den, w.denominator)
    return Fraction(num, den)


def centring_matrix(
    atoms: list[Atom], omega0: float, powers: int, harmonics: int, hyperbolic: bool, mid: float
) -> np.ndarray:
    """(len(atoms), A): row a gives atom a(t) in the centred atoms about t = mid (floats;
    frequencies are multiples of omega0, given in radians per unit of t)."""
    size = 1 + powers + 2 * harmonics
    out = np.zeros((len(atoms), size))
    for row, atom in enumerate(atoms):
        if atom.kind == "1":
            out[row, 0] = 1.0
        elif atom.kind == "t":
            k = atom.power
            for i in range(k + 1):  # t^k = Σ C(k, i) mid^(k-i) τ^i
                out[row, i] = comb(k, i) * mid ** (k - i)
        else:
            w = float(atom.omega) * (np.pi if atom.pi else 1.0)
            j = int(round(w / omega0))
            phi = j * omega0 * mid
            col = 1 + powers + 2 * (j - 1)
            if hyperbolic:
                ch, sh = np.cosh(phi), np.sinh(phi)
                out[row, col : col + 2] = (ch, sh) if atom.kind == "cosh" else (sh, ch)
            else:
                c, s = np.cos(phi), np.sin(phi)
                out[row, col : col + 2] = (c, -s) if atom.kind == "cos" else (s, c)
    return out


def derivative_matrix(omega0: float, powers: int, harmonics: int, hyperbolic: bool) -> np.ndarray:
    """(A, A): D with coefficients' = D @ coefficients on the centred atoms (d/dτ = d/dt)."""
    size = 1 + powers + 2 * harmonics
    d = np.zeros((size, size))
    for k in range(1, powers + 1):
        d[k - 1, k] = k  # (τ^k)' = k τ^(k-1): the coefficient of τ^k moves to τ^(k-1)
    for j in range(1, harmonics + 1):
        c = 1 + powers + 2 * (j - 1)
        w = j * omega0
        if hyperbolic:  # cosh' = w sinh, sinh' = w cosh
            d[c + 1, c] = w
            d[c, c + 1] = w
        else:  # cos' = -w sin, sin' = w cos
            d[c + 1, c] = -w
            d[c, c + 1] = w
    return d


def atom_values(
    tau: np.ndarray, omega0: float, powers: int, harmonics: int, hyperbolic: bool
) -> np.ndarray:
    """(A, len(tau)): the centred atoms at every τ (rows in the module's order)."""
    size = 1 + powers + 2 * harmonics
    out = np.empty((size, tau.size))
    out[0] = 1.0
    for k in range(1, powers + 1):
        np.multiply(out[k - 1], tau, out=out[k])
    if harmonics:
        base = 1 + powers
        x = omega0 * tau
        if hyperbolic:
            e = np.exp(x)
            inv = 1.0 / e
            up, down = e.copy(), inv.copy()
            for j in range(harmonics):
                c = base + 2 * j
                np.add(up, down, out=out[c])
                out[c] *= 0.5
                np.subtract(up, down, out=out[c + 1])
                out[c + 1] *= 0.5
                if j + 1 < harmonics:
                    up *= e
                    down *= inv
        else:
            np.cos(x, out=out[base])
            np.sin(x, out=out[base + 1])
            two_c = 2.0 * out[base]
            for j in range(1, harmonics):
                c = base + 2 * j
                for off in (0, 1):  # c_{j+1} = 2 c_1 c_j − c_{j−1} (s likewise)
                    np.multiply(two_c, out[c - 2 + off], out=out[c + off])
                    if j == 1:
                        if off == 0:
                            out[c] -= 1.0
                    else:
                        out[c + off] -= out[c - 4 + off]
    return out


def evaluate(
    coefficients: np.ndarray,
    tau: np.ndarray,
    omega0: float,
    powers: int,
    harmonics: int,
    hyperbolic: bool,
) -> np.ndarray:
    """(d, len(tau)): Σ_a coefficients[a] atom_a(τ) for coefficients of shape (A, d)."""
    values = atom_values(tau, omega0, powers, harmonics, hyperbolic)
    out: np.ndarray = coefficients.T @ values
    return out


def half_angle_coefficients(coefficients: np.ndarray, harmonics: int) -> np.ndarray:
    """(2J+1, d+1): the monomial coefficients in u = tan(ωτ/2) of the numerator N(u) (first
    d columns) and of the denominator (1 + u²)^J (last column) of a trigonometric curve with
    (2J+1, d) coefficients on 1, cos(ωτ), sin(ωτ), …: e^{ijωτ} = (1+iu)^{2j} (1+u²)^{J−j} /
    (1+u²)^J."""
    from numpy.polynomial import polynomial as P

    dim = coefficients.shape[1]
    size = 2 * harmonics + 1
    out = np.zeros((size, dim + 1))
    one_plus = np.array([1.0, 0.0, 1.0])
    den = P.polypow(one_plus, harmonics) if harmonics else np.array([1.0])
    out[: den.size, dim] = den
    out[: den.size, :dim] += np.outer(den, coefficients[0])
    for j in range(1, harmonics + 1):
        z: np.ndarray = P.polymul(
            P.polypow(np.array([1.0, 1j]), 2 * j), P.polypow(one_plus, harmonics - j)
        )
        a, b = coefficients[2 * j - 1], coefficients[2 * j]
        # a cos + b sin = Re((a − i b) e^{ijθ})
        part = np.real(np.outer(z, a - 1j * b))
        out[: part.shape[0], :dim] += part
    return out


# parameters per block of evaluate_half_angle: its (2J+1, block) powers of u stay in L2 (1.25
# MiB a core here). Per block about ten numpy calls of ~1.4 µs overhead each; at 1e6
# parameters (han_trig_cubic, J = 3, 2026-11-24, load 2.5-3 on 2 cores, best of 25, wall and
# CPU time) 6144-12288 were within noise of each other and 0.8-2 ms (8-15%) faster than 4096,
# 16384 about 1 ms slower than 8192 (the powers leave L2) and 2048 slower still (the
# per-call overhead); an earlier measurement at a higher load had 4096 ahead of 8192, so the
# choice between them is within what the load moves. Tried and not kept: powers by repeated
# squaring in fewer, 2-D calls (no faster at 8192, slower at 4096), u for the whole array at
# once (an extra full pass), one reciprocal and a product instead of the division (no
# faster: the division streams), the even/odd split N = A(u²) + u B(u²) (3 products for the
# powers instead of 5, a 5x4 product instead of 3x7, two more passes: no faster)
_HALF_ANGLE_BLOCK = 8192


def evaluate_half_angle(
    table: np.ndarray, tau: np.ndarray, omega0: float, harmonics: int, centre: float = 0.0
) -> np.ndarray:
    """(d, len(tau)): the curve N(u)/(1+u²)^J from `half_angle_coefficients`, u = tan(ωτ/2)
    with τ = tau − centre (subtracted per block: no array of τ is made); for |ωτ| <= π/2
    (then |u| <= 1 and the denominator is in [1, 2^J]).

    Blocked over τ (`_HALF_ANGLE_BLOCK` parameters, sized so the powers stay in L2): per
    block one tan, the powers 1, u, …, u^2J (2J − 1 products), then the d numerators and the
    denominator at once as one matrix product of the table's columns with those powers, and
    one division written straight into the (d, len(tau)) result (the caller's transpose is
    the (len(tau), d) Fortran-order array a polynomial curve returns: no copy). numpy runs
    the product in BLAS, so the 2J multiply-add passes of Horner's rule per coordinate (each
    a pass of its own in numpy) become one call: with J = 3, about half the time of Horner's
    rule (issue #30, the evaluation without numba). At 1e6 parameters (J = 3, d = 2) the
    steps cost, relative to a polynomial cubic's whole evaluation: the tan 0.2-0.3x (its
    floor; sin and cos cost 1.5x each), the shift and scale 0.1x, the powers 0.3-0.4x, the
    product 0.4-0.55x, the division 0.2-0.35x, per-call overhead included (2026-11-24).
    With |u| <= 1 every power is at most 1, and the sums are as accurate as Horner's (a few
    ulps of Σ |c_e| |u|^e). The blocks are shared out on threads (`HALF_ANGLE_THREADS`),
    whole blocks each: the answer does not depend on their number."""
    dim = table.shape[1] - 1
    columns = np.ascontiguousarray(table.T)  # (d+1, 2J+1): the numerators, the denominator
    out = np.empty((dim, tau.size))
    block = max(1, min(_HALF_ANGLE_BLOCK, tau.size))
    starts = range(0, tau.size, block)
    workers = min(HALF_ANGLE_THREADS or cpu_count(), len(starts) // _HALF_ANGLE_PER_THREAD)
    if workers <= 1:
        _half_angle_blocks(columns, tau, 0.5 * omega0, centre, starts, block, out)
        return out
    # whole blocks per thread: the same blocks, so the same numbers, at any number of threads
    on_threads(
        lambda a, b: _half_angle_blocks(
            columns, tau, 0.5 * omega0, centre, starts[a:b], block, out
        ),
        len(starts),
        workers,
    )
    return out


# Threads for evaluate_half_angle: None for one per CPU, 1 for none. Each takes a run of
# whole blocks (tan, the products, BLAS's small product and the division release the GIL),
# at least _HALF_ANGLE_PER_THREAD blocks each.
HALF_ANGLE_THREADS: int | None = None
_HALF_ANGLE_PER_THREAD = 8


def _half_angle_blocks(
    columns: np.ndarray,
    tau: np.ndarray,
    half: float,
    centre: float,
    starts: range,
    block: int,
    out: np.ndarray,
) -> None:
    """evaluate_half_angle's blocks starting at `starts`, written into out."""
    dim, size = columns.shape[0] - 1, columns.shape[1]
    powers = np.empty((size, block))
    powers[0] = 1.0
    sums = np.empty((dim + 1, block))
    for start in starts:
        n = min(block, tau.size - start)
        if size > 1:
            u = powers[1, :n]
            np.subtract(tau[start : start + n], centre, out=u)
            u *= half
            np.tan(u, out=u)
            for e in range(2, size):
                np.multiply(powers[e - 1, :n], u, out=powers[e, :n])
        part = sums[:, :n]
        np.matmul(columns, powers[:, :n], out=part)
        np.divide(part[:dim], part[dim], out=out[:, start : start + n])


def exponential_bernstein(harmonics: int, c: float) -> np.ndarray:
    """(2K+1, 2K+1), K = harmonics: row K + k holds the Bernstein coefficients (degree 2K, in
    s ∈ [0, 1]) of e^(k x) (1 − u²)^K = (1 + u)^(K+k) (1 − u)^(K−k), u = tanh(x/2) = c·s,
    0 <= c < 1. Built by multiplying linear factors in Bernstein form, [1, 1 ± c], whose
    coefficients are positive: every step adds positive terms, so each entry has a relative
    error of a few ulps (no cancellation)."""
    size = 2 * harmonics
    out = np.empty((size + 1, size + 1))
    for k in range(-harmonics, harmonics + 1):
        coeffs = np.ones(1)
        for up in [True] * (harmonics + k) + [False] * (harmonics - k):
            end = 1.0 + c if up else 1.0 - c  # the factor's Bernstein coefficients [1, end]
            m = coeffs.size  # the product's degree
            j = np.arange(m + 1)
            nxt = np.zeros(m + 1)
            nxt[:m] += (m - j[:m]) / m * coeffs
            nxt[1:] += j[1:] / m * coeffs * end
            coeffs = nxt
        out[k + harmonics] = coeffs
    return out
