r"""Tensor-product surfaces of trigonometric, hyperbolic and mixed families (issues #30, #31).

S(u, v) = Σ_i Σ_j P_ij b_i(u; x_u) b_j(v; x_v), with each direction's family on its own
domain (u and v are the families' own t, e.g. [0, π/2]) and its own parameters x_u, x_v.
Made by ``AtomFamily.surface(net, params_u={...}, params_v={...})``.

Values and partial derivatives of any order are the curves' exact atom derivatives
(`AtomCurve.basis(t, order)`), contracted with the net. A direction with a rational form
(u = tan(t/2) for trigonometric families, exact; tanh for hyperbolic ones, in floats) makes
the surface a tensor-product **rational** Bézier surface: with b_i(t(s)) = Σ_k N_ik B_k(s) /
Σ_k w_k B_k(s) in each direction, the homogeneous net (Σ_ij N^u_ik N^v_jl P_ij, w^u_k w^v_l)
is Nᵀ_u [P | 1] N_v (the weight column because Σ_i b_i = 1 gives Σ_i N_ik = w_k).
`to_rational_bezier` gives it (exact for exact trigonometric input), and splitting, the
bounding box, the closest point and STEP export go through it, with parameters reported in
the families' t. The box and the closest point are certified as for polynomial surfaces: a
branch and bound in which a patch's bound is the least ratio of the numerator's and the
(positive) denominator's Bernstein coefficients. Mixed families have no rational form; their
box and closest point are certified by a branch and bound over (u, v) on rigorous Taylor
enclosures of S and its partial derivatives (hazmat.atom_surface_bounds, built on each
direction's enclosures of its basis functions, hazmat.atom_bounds).

One direction may be a polynomial family instead (`_poly_direction.PolyProbe`: its basis on
[0, 1], and its Bernstein form as a rational form with every weight 1 and s = t), so that a
trigonometric or hyperbolic family across a polynomial one goes through the rational form as
above. A mixed family across a polynomial one has no rational form: its box and closest
point go through hazmat.atom_surface_bounds with the polynomial direction's basis written
over the centred powers of t − 1/2 (`asb.bernstein_direction`: a polynomial basis is in the
algebraic part of an atom space), so the two-atom enclosures apply unchanged.
"""

from __future__ import annotations

import math
from dataclasses import astuple
from fractions import Fraction
from typing import Any, NoReturn

import numpy as np
import numpy.typing as npt

from . import _poly_direction as pd
from . import _validate as val
from ._surface_results import SurfaceClosestPoint
from ._validate import ParamLike
from .atom_family import AtomCurve
from .hazmat import atom_bounds as ab
from .hazmat import atom_surface_bounds as asb
from .hazmat import surface_kernels as ker
from .surfaces import (
    BezierSurface,
    NetLike,
    Surface,
    _as_net,
    _distance_gap,
    _exact_net,
    no_queries,
    paired,
)


class RationalBezierSurface:
    r"""A tensor-product rational Bézier surface Σ w_kl Q_kl B_k(s) B_l(t) / Σ w_kl B_k(s) B_l(t)
    on [0, 1]², held as the Bézier surface of its homogeneous points (w Q, w) (`homogeneous`,
    dimension d + 1); exact when that net is."""

    def __init__(self, homogeneous: BezierSurface) -> None:
        if not isinstance(homogeneous, BezierSurface) or homogeneous.dimension < 2:
            raise TypeError("homogeneous must be a BezierSurface of (w·Q, w) points")
        weights = homogeneous.net[:, :, -1]
        if not (weights > 0).all():
            raise ValueError("a rational Bézier surface here needs every weight > 0")
        self.homogeneous = homogeneous

    @property
    def degrees(self) -> tuple[int, int]:
        return self.homogeneous.degrees

    @property
    def dimension(self) -> int:
        return self.homogeneous.dimension - 1

    def control_weights(self) -> Any:
        """The weights w_kl (Fractions when exact)."""
        return tuple(tuple(p[-1] for p in row) for row in self.homogeneous.control_net())

    def control_net(self) -> Any:
        """The control points Q_kl (Fractions when exact)."""
        return tuple(
            tuple(tuple(c / p[-1] for c in p[:-1]) for p in row)
            for row in self.homogeneous.control_net()
        )

    def __repr__(self) -> str:
        m, n = self.degrees
        return f"RationalBezierSurface(degrees=({m}, {n}), dimension={self.dimension})"

    def evaluate(self, s: ParamLike, t: ParamLike) -> np.ndarray:
        """S(s, t) at paired parameters in [0, 1]."""
        h = self.homogeneous.evaluate(s, t)
        out: np.ndarray = h[..., :-1] / h[..., -1:]
        return out

    def split_u(self, s: Fraction | float) -> tuple[RationalBezierSurface, RationalBezierSurface]:
        """The pieces over [0, s] and [s, 1] in the first parameter, each on [0, 1]."""
        a, b = self.homogeneous.split_u(s)
        return RationalBezierSurface(a), RationalBezierSurface(b)

    def split_v(self, t: Fraction | float) -> tuple[RationalBezierSurface, RationalBezierSurface]:
        a, b = self.homogeneous.split_v(t)
        return RationalBezierSurface(a), RationalBezierSurface(b)


def _identity_curve(family: Any, degree: int, values: tuple[Fraction, ...]) -> AtomCurve:
    """The curve whose control points are the unit vectors: its values are the basis."""
    rows = [tuple(Fraction(int(i == j)) for j in range(degree + 1)) for i in range(degree + 1)]
    curve: AtomCurve = family.atom_curve_class(family, rows, values, True)
    return curve


def _on_domain(curve: AtomCurve, t: ParamLike, name: str) -> tuple[np.ndarray, bool]:
    tt, scalar = val.as_parameters(t, extrapolate=True, name=name)
    lo, hi = curve.domain
    slack = 4 * np.spacing(max(abs(lo), abs(hi), 1.0))
    if tt.size and (float(tt.min()) < lo - slack or float(tt.max()) > hi + slack):
        bad = float(tt.min()) if float(tt.min()) < lo - slack else float(tt.max())
        raise ValueError(
            f"{name} = {bad} is outside the {curve.family} domain {curve.data.DOMAIN_TEXT}"
        )
    return np.clip(tt, lo, hi), scalar


class AtomSurface(Surface):
    """A tensor-product surface of trigonometric, hyperbolic or mixed families (one per
    direction), u and v in the families' own domains; see the module's doc."""

    def __init__(
        self,
        net: NetLike,
        family_u: Any,
        params_u: dict[str, object],
        family_v: Any,
        params_v: dict[str, object],
        *,
        check_range: bool = True,
    ) -> None:
        check_range = val.flag(check_range, "check_range")
        self.net = _as_net(net)
        self._exact = _exact_net(net)
        if self._exact is not None and len(self._exact[0][0]) != self.net.shape[2]:
            self._exact = None
        self.family_u, self.family_v = family_u, family_v
        self.lam_u = self.lam_v = None
        self.params_u, self.params_v = dict(params_u), dict(params_v)
        self._values = []
        self._exact_params = []
        self._probes: list[Any] = []
        for axis, (fam, given) in enumerate(((family_u, params_u), (family_v, params_v))):
            name = "u" if axis == 0 else "v"
            degree = self.net.shape[axis] - 1
            if not pd.is_atom(fam):  # a polynomial direction across an atom one
                pd.checked_degree(fam, degree, name)
                try:
                    probe = pd.PolyProbe(fam, dict(given), degree, check_range)
                except (TypeError, ValueError) as exc:
                    raise type(exc)(f"params_{name}: {exc}") from None
                self._values.append(tuple(given.values()))
                self._exact_params.append(all(pd.exact_value(x) for x in given.values()))
                self._probes.append(probe)
                continue
            if degree not in fam.degrees:
                raise ValueError(
                    f"net, direction {name}: {degree + 1} control points make degree {degree}; "
                    f"the family {fam.name!r} has degrees {fam.degrees[0]}..{fam.degrees[-1]}"
                )
            try:
                values = fam.exact_values(given, check_range)
            except (TypeError, ValueError) as exc:
                raise type(exc)(f"params_{name}: {exc}") from None
            self._values.append(values)
            self._exact_params.append(all(val.is_exact_scalar(x) for x in given.values()))
            self._probes.append(_identity_curve(fam, degree, values))

    # ------------------------------------------------------------------ description
    @property
    def family(self) -> str | tuple[str, str]:
        fu, fv = pd.family_name(self.family_u), pd.family_name(self.family_v)
        return fu if fu == fv else (fu, fv)

    @property
    def domain_u(self) -> tuple[float, float]:
        out: tuple[float, float] = self._probes[0].domain
        return out

    @property
    def domain_v(self) -> tuple[float, float]:
        out: tuple[float, float] = self._probes[1].domain
        return out

    @property
    def is_exact(self) -> bool:
        return self._exact is not None and all(self._exact_params)

    def parameters(self) -> dict[str, Fraction | float]:
        """Every parameter by direction: ``{"lam_u": .., "mu_u": .., "lam_v": ..}``."""
        out: dict[str, Fraction | float] = {}
        for suffix, given in (("u", self.params_u), ("v", self.params_v)):
            for k, x in given.items():
                if isinstance(x, list | tuple):  # an indexed polynomial direction
                    out[f"{k}_{suffix}"] = tuple(pd.shown(y) for y in x)  # type: ignore[assignment]
                else:
                    out[f"{k}_{suffix}"] = pd.shown(x)
        return out

    def __repr__(self) -> str:
        m, n = self.degrees
        shown = ", ".join(f"{k}={v}" for k, v in self.parameters().items())
        fu, fv = pd.family_name(self.family_u), pd.family_name(self.family_v)
        return f"AtomSurface({fu} x {fv}, degrees=({m}, {n}), dimension={self.dimension}, {shown})"

    # ------------------------------------------------------------------ evaluation
    def _pair(self, u: ParamLike, v: ParamLike) -> tuple[np.ndarray, np.ndarray, bool]:
        uu, su = _on_domain(self._probes[0], u, "u")
        vv, sv = _on_domain(self._probes[1], v, "v")
        return paired(uu, su, vv, sv)

    def _basis(self, axis: int, tt: np.ndarray, order: int) -> np.ndarray:
        out: np.ndarray = self._probes[axis].basis(tt, order, extrapolate=True)
        return out.reshape(tt.size, self.net.shape[axis])  # -1 fails on no parameters

    def _partial(self, uu: np.ndarray, vv: np.ndarray, du: int, dv: int) -> np.ndarray:
        bu, bv = self._basis(0, uu, du), self._basis(1, vv, dv)
        with val.overflow_allowed():
            out: np.ndarray = np.einsum("ki,ijd,kj->kd", bu, self.net, bv, optimize=True)
        return out

    def _partial_magnitude(self, uu: np.ndarray, vv: np.ndarray, du: int, dv: int) -> np.ndarray:
        # the basis values carry their own rounding, relative to the largest of them (a
        # value that is zero at an end comes out as noise of that size), so each is bounded
        # by its size plus the largest
        bu, bv = (
            np.abs(b) + np.abs(b).max(axis=1, keepdims=True)
            for b in (self._basis(0, uu, du), self._basis(1, vv, dv))
        )
        with val.overflow_allowed():
            terms = np.einsum("ki,ijd,kj->kd", bu, np.abs(self.net), bv, optimize=True)
        out: np.ndarray = terms.max(axis=-1)
        return out

    def derivative(
        self, u: ParamLike, v: ParamLike, du: int = 1, dv: int = 0, *, extrapolate: bool = False
    ) -> np.ndarray:
        """∂^(du+dv) S / ∂u^du ∂v^dv at paired parameters, in the families' t (exact atom
        derivatives of the basis)."""
        if extrapolate:
            raise ValueError("extrapolate: an atom surface is evaluated on its domain only")
        du, dv = val.as_order(du, "du"), val.as_order(dv, "dv")
        uu, vv, scalar = self._pair(u, v)
        out = val.finite_result(self._partial(uu, vv, du, dv), "the surface value")
        return out[0] if scalar else out

    def evaluate_grid(
        self, us: ParamLike, vs: ParamLike, du: int = 0, dv: int = 0, *, extrapolate: bool = False
    ) -> np.ndarray:
        """S (or a partial derivative) on the grid us × vs: (len(us), len(vs), d)."""
        if extrapolate:
            raise ValueError("extrapolate: an atom surface is evaluated on its domain only")
        du, dv = val.as_order(du, "du"), val.as_order(dv, "dv")
        uu, _ = _on_domain(self._probes[0], us, "us")
        vv, _ = _on_domain(self._probes[1], vs, "vs")
        bu, bv = self._basis(0, uu, du), self._basis(1, vv, dv)
        with val.overflow_allowed():
            out: np.ndarray = np.einsum("ki,ijd,lj->kld", bu, self.net, bv, optimize=True)
        return val.finite_result(out, "the surface value")

    # ------------------------------------------------------------------ isoparametric curves
    def _weights_at(self, axis: int, t: object, s: object) -> tuple[Any, ...]:
        name = "u" if axis == 0 else "v"
        probe = self._probes[axis]
        if (t is None) == (s is None):
            raise TypeError(f"give {name} (the family's t) or s= (the rational form's), once")
        if s is None and isinstance(probe, pd.PolyProbe) and val.is_exact_scalar(t):
            s = t  # a polynomial direction's rational form has s = t: exact at exact t
        if s is not None:
            rat = probe.to_rational_bezier()
            x: Any = Fraction(val.real_number(s, "s"))
            if not val.is_exact_scalar(s):
                x = float(x)
            if not 0 <= x <= 1:
                raise ValueError(f"s = {s} is outside [0, 1]")
            pts: Any = rat.control_points()
            weights: Any = rat.control_weights()
            big = len(weights) - 1
            bern: Any = ker.bernstein_values(big, x)
            den = sum((w * b for w, b in zip(weights, bern, strict=True)), 0 * x)
            return tuple(
                sum((pts[k][i] * weights[k] * bern[k] for k in range(big + 1)), 0 * x) / den
                for i in range(probe.degree + 1)
            )
        tt, scalar = _on_domain(probe, t, name)  # type: ignore[arg-type]
        if not scalar:
            raise ValueError(f"{name} must be a single number")
        return tuple(float(x) for x in self._basis(axis, tt, 0)[0])

    def _iso_curve(self, axis: int, t: object, s: object = None) -> AtomCurve:  # type: ignore[override]
        weights = self._weights_at(axis, t, s)
        exact = self._exact is not None and all(isinstance(w, Fraction) for w in weights)
        pts = self._contract(axis, weights, exact)
        fam, given = (self.family_v, self.params_v) if axis == 0 else (self.family_u, self.params_u)
        other = self._probes[1 - axis]
        if isinstance(other, pd.PolyProbe):
            return other.make_curve(pts)  # type: ignore[return-value]
        curve: AtomCurve = fam.curve(pts, params=given, check_range=False)
        return curve

    def curve_at_u(self, u: Fraction | float | None = None, *, s: object = None) -> AtomCurve:  # type: ignore[override]
        """v ↦ S(u, v): a curve of the v family at its parameters. Exact for an exact net at
        ``s=`` (a rational value of the u direction's rational form, t = t_of_s(s)); u itself
        (the family's t) gives float control points (b_i(u) is irrational at most u)."""
        return self._iso_curve(0, u, s)

    def curve_at_v(self, v: Fraction | float | None = None, *, s: object = None) -> AtomCurve:  # type: ignore[override]
        """u ↦ S(u, v): a curve of the u family; as curve_at_u."""
        return self._iso_curve(1, v, s)

    # ------------------------------------------------------------------ the rational form
    def _direction_form(self, axis: int) -> tuple[Any, bool]:
        """(Nᵀ as rows (n+1) x (D+1), exact?) of one direction's rational form."""
        probe = self._probes[axis]
        rat = probe.to_rational_bezier()  # ValueError naming the reason when there is none
        pts, weights = rat.control_points(), rat.control_weights()
        exact = all(isinstance(w, Fraction) for w in weights)
        rows = tuple(
            tuple(pts[k][i] * weights[k] for k in range(len(weights)))
            for i in range(probe.degree + 1)
        )
        return rows, exact

    def to_rational_bezier(self) -> RationalBezierSurface:
        """The surface as a tensor-product rational Bézier surface in (s_u, s_v) ∈ [0, 1]²
        (s = tan(t/2)/scale per direction, `s_of_t`): exact for an exact net and parameters of
        trigonometric families, in floats for hyperbolic ones (their forms are float). A
        ValueError for a mixed family, which has none."""
        cached: RationalBezierSurface | None = self.__dict__.get("_rational")
        if cached is not None:
            return cached
        (nu, eu), (nv, ev) = self._direction_form(0), self._direction_form(1)
        if self.is_exact and eu and ev:
            assert self._exact is not None
            aug = tuple(tuple((*p, Fraction(1)) for p in row) for row in self._exact)
            homog = BezierSurface(ker.exact_transform(nu, aug, nv))
        else:
            aug_f = np.concatenate([self.net, np.ones((*self.net.shape[:2], 1))], axis=2)
            with val.overflow_allowed():
                h = np.einsum(
                    "ia,ijd,jb->abd",
                    np.array(nu, dtype=float),
                    aug_f,
                    np.array(nv, dtype=float),
                    optimize=True,
                )
            homog = BezierSurface(val.finite_result(h, "the rational form's net"))
        out = RationalBezierSurface(homog)
        self.__dict__["_rational"] = out
        return out

    def s_of_t(self, axis: int, t: npt.ArrayLike) -> Any:
        """The rational form's parameter of direction `axis` (0: u, 1: v) at the family's t."""
        return self._probes[axis].s_of_t(t)

    def t_of_s(self, axis: int, s: npt.ArrayLike) -> Any:
        return self._probes[axis].t_of_s(s)

    def to_bezier(self) -> NoReturn:
        spaces = sorted({p.data.SPACE for p in self._probes})
        hint = (
            "to_rational_bezier() gives its rational Bézier form (exact for trigonometric "
            "families, in floats for hyperbolic ones)"
            if self._has_form()
            else "a mixed algebraic-trigonometric/hyperbolic family has no rational form "
            "either: evaluate it, or mesh it (surface_export.mesh)"
        )
        raise ValueError(
            f"to_bezier: a surface of {' and '.join(spaces)} families is not a polynomial "
            f"surface; {hint}"
        )

    def elevate_u(self) -> NoReturn:
        raise ValueError(
            "elevate_u: degree elevation is of polynomial surfaces; an atom surface "
            "has its family's degree (elevate to_rational_bezier().homogeneous)"
        )

    def elevate_v(self) -> NoReturn:
        raise ValueError("elevate_v: as elevate_u")

    def split_u(self, u: Fraction | float) -> tuple[RationalBezierSurface, RationalBezierSurface]:  # type: ignore[override]
        """The pieces over [lo, u] and [u, hi] as **rational Bézier surfaces** (the rational
        form split at s(u), in floats: s(u) is irrational at most u), each on [0, 1]²."""
        return self._split(0, u)

    def split_v(self, v: Fraction | float) -> tuple[RationalBezierSurface, RationalBezierSurface]:  # type: ignore[override]
        return self._split(1, v)

    def _split(self, axis: int, t: object) -> tuple[RationalBezierSurface, RationalBezierSurface]:
        name = "u" if axis == 0 else "v"
        tt, scalar = _on_domain(self._probes[axis], t, name)  # type: ignore[arg-type]
        if not scalar:
            raise ValueError(f"{name} must be a single number")
        lo, hi = self._probes[axis].domain
        if not lo < float(tt[0]) < hi:
            raise ValueError(f"splitting needs {name} strictly inside the domain, got {t}")
        if not self._has_form():
            spaces = sorted({p.data.SPACE for p in self._probes if hasattr(p, "data")})
            raise ValueError(
                f"split_{name}: a surface of {' and '.join(spaces)} families has no rational "
                "form, and its piece over a sub-interval is no surface of its family (the "
                "family's basis is defined on its whole domain; stretched onto a piece, its "
                "trigonometric or hyperbolic part changes frequency): evaluate the surface on "
                "the sub-domain in its own t, or approximate it within a tolerance "
                "(surface_approx.hermite_bspline: a polynomial B-spline) or mesh it"
            )
        rat = self.to_rational_bezier()
        s = float(self.s_of_t(axis, float(tt[0])))
        return rat.split_u(s) if axis == 0 else rat.split_v(s)

    def derivative_bounds(self, samples: int = 257) -> tuple[float, float, float]:
        """(M_uu, M_uv, M_vv): bounds of |S_uu|, |S_uv|, |S_vv| over the domain (the mesh's
        deviation bound). On a grid of `samples`² points of spacing (Δu, Δv), every point is
        within Δu/2, Δv/2 of a node, so |S^(a,b)| <= max over the nodes + Δu/2 · sup
        |S^(a+1,b)| + Δv/2 · sup |S^(a,b+1)|, the sups bounded crudely by Σ_ij B^a_i |P_ij|
        B^b_j with B^k_i = Σ_atoms |coefficient| · sup |atom| >= |b_i^(k)| (sup |cos| = 1,
        |τ^p| <= h^p, |cosh|, |sinh| <= cosh(m ω0 h) on the centred domain |τ| <= h)."""
        crude = []
        for probe in self._probes:
            if isinstance(probe, pd.PolyProbe):
                crude.append([probe.crude_sup(k) for k in range(4)])
                continue
            sh = probe.shape
            lo, hi = probe.domain
            half = 0.5 * (hi - lo)
            sup = [1.0, *(half**k for k in range(1, sh.powers + 1))]
            for j in range(1, sh.harmonics + 1):
                wave = math.cosh(j * sh.omega0 * half) if sh.hyperbolic else 1.0
                sup += [wave, wave]
            weights = np.array(sup)
            crude.append([np.abs(probe._coefficients(k)).T @ weights for k in range(4)])
        size = np.linalg.norm(self.net, axis=-1)
        (a0, a1), (b0, b1) = self.domain_u, self.domain_v
        us, vs = np.linspace(a0, a1, samples), np.linspace(b0, b1, samples)
        step_u, step_v = (a1 - a0) / (samples - 1), (b1 - b0) / (samples - 1)

        def bound(a: int, b: int) -> float:
            nodes = float(np.linalg.norm(self.evaluate_grid(us, vs, a, b), axis=-1).max())
            up_u = float(crude[0][a + 1] @ size @ crude[1][b])
            up_v = float(crude[0][a] @ size @ crude[1][b + 1])
            return nodes + 0.5 * step_u * up_u + 0.5 * step_v * up_v

        return bound(2, 0), bound(1, 1), bound(0, 2)

    # ------------------------------------------------------------------ global queries
    def _has_form(self) -> bool:
        return all(p.has_rational_form or p.data.SPACE == "hyperbolic" for p in self._probes)

    def bounding_box(self, tol: float = 1e-12) -> tuple[np.ndarray, np.ndarray]:
        """(lo, hi): the axis-aligned box of the surface over its domain. Through the rational
        form: each bound certified within `tol` times the net's size (branch and bound on the
        ratio of the homogeneous net's coordinate and weight). A mixed family (across an atom
        or a polynomial family): certified by a branch and bound on Taylor enclosures
        (hazmat.atom_surface_bounds), each bound within
        `tol` times the net's size of the extreme (or a few hundred ulps, if more)."""
        tol = val.tolerance(tol)
        if not self._has_form():
            return self._certified_box(tol)
        h = self.to_rational_bezier().homogeneous.net
        w = h[:, :, -1]
        size = float(np.abs(h[:, :, :-1] / w[:, :, None]).max()) or 1.0
        rat = self.to_rational_bezier()
        lo, hi = np.empty(self.dimension), np.empty(self.dimension)
        for c in range(self.dimension):
            for sign, out in ((1.0, lo), (-1.0, hi)):

                def value(s: np.ndarray, t: np.ndarray, c: int = c, sign: float = sign) -> Any:
                    return sign * rat.evaluate(s, t)[:, c]

                *_, bound = ker.minimise_scalar_net(
                    sign * h[:, :, c], value, _no_polish, tol * size, denominator=w
                )
                out[c] = sign * bound
        return lo, hi

    def closest_point(self, q: npt.ArrayLike, tol: float = 1e-12) -> SurfaceClosestPoint:
        """The global nearest point to q ((d,), or a batch (k, d)), u and v in the families' t.
        Through the rational form: certified as for polynomial surfaces (``lower_bound``),
        the squared distance's bound on a patch being the least ratio of the Bernstein
        coefficients of Σ_c (X_c − q_c W)² and W². A mixed family (across an atom or a
        polynomial family): certified by a branch and
        bound on Taylor enclosures (hazmat.atom_surface_bounds), the distance within `tol`
        times the size (the net's and q's) of ``lower_bound`` (or a few hundred ulps, if
        more), refined by Newton; a batch's queries are searched together."""
        if self._has_form():
            return super().closest_point(q, tol)
        tol = val.tolerance(tol)
        arr = np.asarray(val.real_array(q, "q"), dtype=float)
        if arr.ndim == 2 and arr.shape[0] == 0:
            return no_queries(arr, self.dimension)
        if arr.ndim == 2:
            return self._certified_closest(
                np.array([val.as_point(r, self.dimension, "q") for r in arr]), tol
            )
        one = self._certified_closest(val.as_point(q, self.dimension, "q")[None, :], tol)
        u, v, at, dist, low = (np.asarray(x)[0] for x in astuple(one))
        return SurfaceClosestPoint(float(u), float(v), at, float(dist), float(low))

    def _closest(self, q: object, tol: float) -> SurfaceClosestPoint:
        point = val.as_point(q, self.dimension, "q")
        h = self.to_rational_bezier().homogeneous.net
        w = h[:, :, -1]
        # in coordinates centred on q, as for polynomial surfaces (surfaces.Surface._closest):
        # the tolerance and the rounding floor scale with the net seen from q
        moved = h[:, :, :-1] - point * w[:, :, None]
        size = float(np.abs(moved / w[:, :, None]).max()) or 1.0
        num = sum(
            ker.bernstein_product(moved[:, :, c], moved[:, :, c]) for c in range(self.dimension)
        )
        den = ker.bernstein_product(w, w)
        rat = RationalBezierSurface(BezierSurface(np.concatenate([moved, w[:, :, None]], axis=2)))

        def value(s: np.ndarray, t: np.ndarray) -> np.ndarray:
            diff = rat.evaluate(s, t)
            out: np.ndarray = (diff * diff).sum(axis=1)
            return out

        floor = 256 * np.finfo(float).eps * size * size

        s, t, best, lower = ker.minimise_scalar_net(
            np.asarray(num),
            value,
            self._newton_polish(point),
            _distance_gap(tol * size, floor),
            denominator=den,
        )
        u, v = float(self.t_of_s(0, s)), float(self.t_of_s(1, t))
        at = self.evaluate(u, v)
        lower = min(max(lower, 0.0), best)  # rounded at a corner: never above the value (surfaces)
        return SurfaceClosestPoint(u, v, at, float(np.sqrt(best)), float(np.sqrt(lower)))

    def _newton_polish(self, point: np.ndarray) -> Any:
        """Newton on the gradient of |S − q|² in the families' own (u, v), from a point of
        the rational form's square and back: the branch and bound's bound of the squared
        distance stops at a rounding floor (about 1e-13 of the size squared), so without this
        a query on the surface came back about 3e-7 of the size away from itself. The search
        only uses the values a polish reaches, so a poor step costs nothing but time."""
        (ua, ub), (va, vb) = self.domain_u, self.domain_v

        def polish(s: float, t: float) -> tuple[float, float]:
            u, v = float(self.t_of_s(0, s)), float(self.t_of_s(1, t))
            for _ in range(asb.NEWTON_STEPS):
                uu, vv = np.array([u]), np.array([v])
                partials = (self._partial(uu, vv, a, b) for a, b in asb.NEWTON_PARTIALS)
                du, dv = asb.distance_newton_step(self._partial(uu, vv, 0, 0) - point, *partials)
                nu = min(max(u - float(du[0]), ua), ub)
                nv = min(max(v - float(dv[0]), va), vb)
                if nu == u and nv == v:
                    break
                u, v = nu, nv
            s_new, t_new = float(self.s_of_t(0, u)), float(self.s_of_t(1, v))
            return min(max(s_new, 0.0), 1.0), min(max(t_new, 0.0), 1.0)

        return polish

    # no rational form (a mixed family): hazmat.atom_surface_bounds; a polynomial direction
    # across is an atom direction there (its basis over the centred powers of t − 1/2)
    def _surface_data(self) -> asb.SurfaceData:
        cached: asb.SurfaceData | None = self.__dict__.get("_surface_bounds")
        if cached is None:
            (du, one_u, mu, su), (dv, one_v, mv, sv) = (_direction_data(p) for p in self._probes)
            (ua, ub), (va, vb) = self.domain_u, self.domain_v
            cached = asb.SurfaceData(
                du,
                dv,
                (ua - mu, ub - mu),
                (va - mv, vb - mv),
                self.net * (su * sv),
                one_u and one_v,
            )
            self.__dict__["_surface_bounds"] = cached
            self.__dict__["_surface_scale"] = su * sv
        return cached

    def _closest_data(self) -> tuple[asb.SurfaceData, np.ndarray]:
        """The surface moved by the centre c of its net's box, and c, where the bases sum to
        one exactly (S − c = Σ (P_ij − c) b_i b_j): the distance search's tolerance and
        rounding then scale with the net seen from the queries near it, not with how far both
        are from the origin (at 1e6 the search ran 37 s to a gap of 80% of the patch's size,
        tests/test_acceptance_31d.py)."""
        cached: tuple[asb.SurfaceData, np.ndarray] | None = self.__dict__.get("_closest_data_")
        if cached is None:
            data = self._surface_data()
            origin = np.zeros(self.dimension)
            if data.unity:
                net = np.asarray(self.net, dtype=float)
                flat = net.reshape(-1, net.shape[-1])
                origin = flat.min(axis=0) / 2 + flat.max(axis=0) / 2
                moved = (net - origin) * self.__dict__["_surface_scale"]
                data = asb.SurfaceData(
                    data.basis_u, data.basis_v, data.domain_u, data.domain_v, moved, data.unity
                )
            cached = (data, origin)
            self.__dict__["_closest_data_"] = cached
        return cached

    def _certified_box(self, tol: float) -> tuple[np.ndarray, np.ndarray]:
        *_, lo, hi = asb.coordinate_extremes(self._surface_data(), tol)
        return lo, hi

    def _certified_closest(self, points: np.ndarray, tol: float) -> SurfaceClosestPoint:
        """The nearest points to every query of points (k, d), as arrays over the batch."""
        if not points.size:
            empty = np.empty(0)
            return SurfaceClosestPoint(empty, empty, np.empty((0, self.dimension)), empty, empty)
        data, origin = self._closest_data()
        moved = points - origin
        plain = self._surface_data()
        # moved only where that shrinks every query's size (the search's tolerance is tol
        # times it): a net far from the origin, never a net about it
        if not np.all(
            data.size() + np.abs(moved).max(axis=1) <= plain.size() + np.abs(points).max(axis=1)
        ):
            data, moved = plain, points
        tu, tv, _, lower = asb.closest(data, moved, tol)
        (ua, ub), (va, vb) = self.domain_u, self.domain_v
        mid_u, mid_v = (_centre(p) for p in self._probes)
        u, v = np.clip(tu + mid_u, ua, ub), np.clip(tv + mid_v, va, vb)
        at = self.evaluate(u, v)
        dist = np.linalg.norm(at - points, axis=1)
        return SurfaceClosestPoint(
            u, v, at, dist, np.minimum(np.sqrt(np.maximum(lower, 0.0)), dist)
        )


def _direction_data(probe: Any) -> tuple[ab.AtomCurveData, bool, float, float]:
    """(the direction's basis over centred atoms, whether it sums to one exactly, the centre
    of its domain, the power-of-two scale its coefficients are divided by) for
    hazmat.atom_surface_bounds: an atom direction's own (`_bounds_data`), or a polynomial
    direction's Bernstein form over the powers of t − 1/2 (`asb.bernstein_direction`)."""
    if isinstance(probe, pd.PolyProbe):
        data, unity = asb.bernstein_direction(probe.bernstein())
        return data, unity, _centre(probe), 1.0
    # imported here, not at the top: _atom_geometry pulls in the curves' geometry and
    # intersection engines, which naming a surface class does not need (import time, #29)
    from ._atom_geometry import _bounds_data

    return _bounds_data(probe), _sums_to_one(probe), _centre(probe), probe._scale


def _centre(probe: Any) -> float:
    """The centre of a direction's domain, where its centred atoms have τ = 0."""
    return 0.5 if isinstance(probe, pd.PolyProbe) else float(probe._mid)


def _sums_to_one(probe: AtomCurve) -> bool:
    """Whether the direction's basis functions sum to one exactly (their exact atom
    coefficients summed: 1 on the constant atom, 0 on every other)."""
    rows = probe.basis_coefficients
    try:
        sums = [sum(col) for col in zip(*rows, strict=True)]
        return all(
            s == (1 if a.kind == "1" else 0) for s, a in zip(sums, probe.shape.atoms, strict=True)
        )
    except (TypeError, ValueError):
        return False


def _no_polish(u: float, v: float) -> tuple[float, float]:
    return u, v
