r"""A certified bound of the distance between a curve over centred atoms (hazmat.atoms) and a
polynomial Bézier piece approximating it on [τa, τb], for export with a chosen tolerance.

With c the middle of the piece and σ = τ − c, the difference E(σ) = B(u(σ)) − C(c + σ),
u = (σ + c − τa) / (τb − τa), is again a curve over atoms about c:

- B's monomial coefficients in σ come from its control points exactly (Fractions: every float
  is a rational), and are rounded once (an error of half an ulp each);
- C's polynomial part is re-centred exactly (binomials in Fractions), rounded once;
- C's harmonics re-centred: α cos(jω(c + σ)) + β sin(jω(c + σ)) = (α cos φ + β sin φ) cos jωσ
  + (β cos φ − α sin φ) sin jωσ, φ = jωc (cosh/sinh alike), with cos φ, sin φ from numpy
  (within 4 ulps, plus the rounding of φ): an error of at most (|α| + |β|)(16 + 4|φ|) u
  (times cosh φ for cosh/sinh).

Then the Taylor-form enclosures of hazmat.atom_bounds (rigorous) on 8, 64 or 512 equal
intervals of the piece, until the bound meets the target, give max|E_c| per coordinate; the
bound adds every rounding above times the atom's largest size on the piece, and is
sqrt(Σ_coordinates max|E_c|²).
"""

from __future__ import annotations

from fractions import Fraction
from math import comb, cosh, sqrt

import numpy as np

from . import atom_bounds as ab

_U = 2.0**-53
COUNTS = (8, 64, 512)  # enclosures per piece, tried in turn until the bound meets the target


def _poly_compose(
    control: list[list[Fraction]], shift: Fraction, width: Fraction
) -> list[list[Fraction]]:
    """Monomial coefficients in σ (per coordinate) of B(u), u = (σ + shift) / width, B with
    Bernstein control points `control` (n+1 rows)."""
    n = len(control) - 1
    dim = len(control[0])
    # Bernstein → monomial in u: B(u) = Σ_k m_k u^k, m_k = C(n,k) Σ_i (-1)^(k-i) C(k,i) P_i
    mono = [
        [
            comb(n, k) * sum((-1) ** (k - i) * comb(k, i) * control[i][d] for i in range(k + 1))
            for d in range(dim)
        ]
        for k in range(n + 1)
    ]
    # u^k = (σ + shift)^k / width^k = Σ_j C(k, j) shift^(k-j) σ^j / width^k
    out = [[Fraction(0)] * dim for _ in range(n + 1)]
    for k in range(n + 1):
        scale = Fraction(1) / width**k
        for j in range(k + 1):
            f = comb(k, j) * shift ** (k - j) * scale
            for d in range(dim):
                out[j][d] += f * mono[k][d]
    return out


def deviation(
    data: ab.AtomCurveData,
    control: np.ndarray,
    tau_a: Fraction,
    tau_b: Fraction,
    target: float = 0.0,
) -> float:
    """A certified upper bound of max over u ∈ [0, 1] of |B(u) − C(τa + u (τb − τa))|, C the
    curve `data` (coefficients over centred atoms in τ), B the Bézier piece with float
    control points `control` (n+1, d), in the same units as data's coefficients. Finer
    enclosures are tried while the bound is above `target`."""
    coeffs = np.asarray(data.coefficients, dtype=float)
    dim = coeffs.shape[1]
    powers, harmonics, omega, hyper = data.powers, data.harmonics, data.omega0, data.hyperbolic
    centre_f = float((tau_a + tau_b) / 2)
    centre = Fraction(centre_f)
    half = max(abs(tau_b - centre), abs(centre - tau_a))
    h = float(half) * (1 + 4 * _U)
    rows = [[Fraction(float(x)) for x in row] for row in control]
    bpoly = _poly_compose(rows, centre - tau_a, tau_b - tau_a)
    deg = max(powers, len(rows) - 1)
    size = 1 + deg + 2 * harmonics
    out = np.zeros((size, dim))
    err = np.zeros(dim)  # the coefficients' rounding times the atoms' largest size
    # the polynomial part of B − C, exact, then rounded once
    for j in range(deg + 1):
        for d in range(dim):
            exact = bpoly[j][d] if j < len(bpoly) else Fraction(0)
            for i in range(j, powers + 1):
                exact -= comb(i, j) * centre ** (i - j) * Fraction(float(coeffs[i, d]))
            out[j, d] = float(exact)
            err[d] += abs(float(exact)) * _U * h**j
    for j in range(1, harmonics + 1):
        phi = j * omega * centre_f
        src = 1 + powers + 2 * (j - 1)
        dst = 1 + deg + 2 * (j - 1)
        alpha, beta = coeffs[src], coeffs[src + 1]
        if hyper:
            ch, sh = np.cosh(phi), np.sinh(phi)
            out[dst] = -(alpha * ch + beta * sh)
            out[dst + 1] = -(alpha * sh + beta * ch)
            grow = cosh(j * omega * h) * cosh(phi)
        else:
            co, si = np.cos(phi), np.sin(phi)
            out[dst] = -(alpha * co + beta * si)
            out[dst + 1] = -(beta * co - alpha * si)
            grow = 1.0
        err += 2 * (np.abs(alpha) + np.abs(beta)) * (16 + 4 * abs(phi)) * _U * grow
    diff = ab.AtomCurveData(out, omega, deg, harmonics, hyper)
    best = np.inf
    for count in COUNTS:
        edges = np.linspace(-h, h, count + 1)
        edges[0], edges[-1] = -h, h
        low, high = diff.enclose(0, edges[:-1], edges[1:])
        top = np.maximum(np.abs(low), np.abs(high)).max(axis=1) + err
        best = min(best, float(sqrt(float(np.sum(top * top)))) * (1 + 8 * _U))
        if best <= target:
            break
    return best
