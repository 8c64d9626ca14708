"""Surfaces of families with several shape parameters, indexed parameters, or a
trigonometric, hyperbolic or mixed basis (issues #30, #31): what ``fam.surface(net, ...)``
returns for them.

Each direction takes the family's parameters by name, ``params_u={"lam": .., "mu": ..}``
(one-parameter families keep ``lam_u, lam_v`` and take ``params_u`` too; an indexed family
takes one sequence per direction, ``lam_u=[...]`` or ``params_u={"lam": [...]}``). A
polynomial family at fixed parameter values is a family without a parameter (the fixed
curve class of `Family.curve`), so its surface is a `ParamSurface`: the generic `Surface`
on those classes, with every method of the polynomial surfaces (the exact Bézier form,
certified box and closest point, iso-curves of the family) and the parameters kept by name.
Atom families give an `AtomSurface` (atom_surfaces), also with a polynomial family in the
other direction (a pair ``(family_u, family_v)``, a built-in family by name;
``fam.surface(..., family_v=...)``).
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

from . import _poly_direction as pd
from . import _validate as val
from .atom_surfaces import AtomSurface
from .curves import elsewhere
from .surfaces import NetLike, Surface, _as_net

_is_atom, _is_indexed = pd.is_atom, pd.is_indexed


def _given(family: Any, lam: object, params: object, name: str) -> dict[str, object]:
    """{parameter name: value} of one direction, as given (TypeError naming the argument)."""
    if params is not None and not isinstance(params, dict):
        raise TypeError(
            f"params_{name} must be a dict {{name: value}}, not {type(params).__name__}"
        )
    try:
        if pd.is_class(family):  # a built-in family across an atom one
            given = pd.builtin_given(family, lam, params)
            return {k: _normalised(v) for k, v in given.items()}
        if _is_indexed(family):
            index = family.index_name
            given = dict(params or {})
            unknown = sorted(set(given) - {index})
            if unknown:
                raise TypeError(
                    f"{unknown[0]!r} is not a parameter of {family.name!r} (its parameter: "
                    f"{index}, one value per index)"
                )
            if lam is not None:
                if index in given:
                    raise TypeError(f"{index} is given twice; give it once")
                given[index] = lam
            if index not in given:
                raise TypeError(f"the {family.name} direction needs {index}=[...] (a sequence)")
            return {k: _normalised(v) for k, v in given.items()}
        out: dict[str, object] = family.parameter_values(lam, params)
        return {k: _normalised(v) for k, v in out.items()}
    except TypeError as exc:
        raise TypeError(f"params_{name}: {str(exc).removeprefix('params: ')}") from None


def _normalised(v: object) -> object:
    """An exact value (int, numpy integer) as the Fraction it is, so that the surface keeps
    and writes it exactly; sequences element by element; anything else as given (checked
    where it is used)."""
    if isinstance(v, list | tuple):
        return [_normalised(x) for x in v]
    if val.is_exact_scalar(v):
        return Fraction(int(v.numerator), int(v.denominator))
    return v


class ParamSurface(Surface):
    """A tensor-product surface of polynomial families with several (or indexed) parameters:
    the generic Surface on each direction's curve class at its parameter values; the values
    are kept by name (`parameters`)."""

    def __init__(
        self,
        net: NetLike,
        family_u: Any,
        given_u: dict[str, object],
        family_v: Any,
        given_v: dict[str, object],
        *,
        check_range: bool = True,
    ) -> None:
        check_range = val.flag(check_range, "check_range")
        grid = _as_net(net)
        self.family_u, self.family_v = family_u, family_v
        self.params_u, self.params_v = dict(given_u), dict(given_v)
        classes: list[Any] = []
        lams: list[Any] = []
        for axis, (fam, given) in enumerate(((family_u, given_u), (family_v, given_v))):
            name = "u" if axis == 0 else "v"
            degree = int(grid.shape[axis]) - 1
            try:
                cls, lam = pd.direction_class(fam, given, degree, check_range)
            except (TypeError, ValueError) as exc:
                raise type(exc)(f"params_{name}: {exc}") from None
            classes.append(cls)
            lams.append(lam)
        super().__init__(net, lams[0], lams[1], family=tuple(classes), check_range=check_range)

    @property
    def family(self) -> str | tuple[str, str]:
        fu, fv = pd.family_name(self.family_u), pd.family_name(self.family_v)
        return fu if fu == fv else (fu, fv)

    @property
    def is_exact(self) -> bool:
        return super().is_exact and all(
            pd.exact_value(x) for x in (*self.params_u.values(), *self.params_v.values())
        )

    def parameters(self) -> dict[str, Any]:
        """Every parameter by direction: ``{"lam_u": .., "mu_u": .., "lam_v": ..}`` (an
        indexed family's as one tuple)."""
        out: dict[str, Any] = {}
        for suffix, given in (("u", self.params_u), ("v", self.params_v)):
            for k, x in given.items():
                if isinstance(x, list | tuple):
                    out[f"{k}_{suffix}"] = tuple(pd.shown(y) for y in x)
                else:
                    out[f"{k}_{suffix}"] = pd.shown(x)
        return out

    def __repr__(self) -> str:
        m, n = self.degrees
        shown = ", ".join(
            f"{k}=({', '.join(map(str, v))})" if isinstance(v, tuple) else f"{k}={v}"
            for k, v in self.parameters().items()
        )
        dims = f"degrees=({m}, {n}), dimension={self.dimension}"
        return f"ParamSurface({self.family!r}, {dims}, {shown})"


def family_surface(
    net: NetLike,
    family: Any,
    lam_u: object = None,
    lam_v: object = None,
    *,
    params_u: object = None,
    params_v: object = None,
    check_range: bool = True,
) -> Surface:
    """The surface of `family` (or a pair (family_u, family_v) of families from load_family)
    with each direction's parameters by name; see the module's doc."""
    fu, fv = family if isinstance(family, tuple | list) else (family, family)
    if isinstance(family, tuple | list) and len(family) != 2:
        raise ValueError(f"family must be one family or a pair (u, v), got {len(family)} items")
    for f in (fu, fv):
        told = elsewhere(f)  # a C-Bézier family: no surfaces; what it does take, named
        if told is not None:
            raise TypeError(told)
    if any(_is_atom(f) or isinstance(f, str) or pd.is_class(f) for f in (fu, fv)):
        # a built-in direction by name (or class), across an atom family or any other
        fu, fv = pd.polynomial_family(fu), pd.polynomial_family(fv)
    given_u = _given(fu, lam_u, params_u, "u")
    given_v = _given(fv, lam_v, params_v, "v")
    if _is_atom(fu) or _is_atom(fv):  # both atom families, or one across a polynomial one
        return AtomSurface(net, fu, given_u, fv, given_v, check_range=check_range)
    return ParamSurface(net, fu, given_u, fv, given_v, check_range=check_range)
