"""Curve classes: one shared base, the classical Bézier curve, and the built-in families.

Every family is a polynomial curve p(t) = Σ_i P_i b_i(t; λ) whose basis functions are given,
per degree, as exact matrices in generated/ (power and Bernstein coefficients, split by powers
of λ). The base class (_curve_base.py) turns those matrices into the curve's power
coefficients once, and all evaluation is Horner's rule vectorised over t.

BezierCurve, the classical Bézier curve (no λ, ``_has_lambda = False``), is the reference
every curve converts to (``to_bezier``). The shape-parameter families are those generated/
lists; `FAMILIES` gives their classes (see builtin_curves for the ones with code of their own).
This module assembles that registry; it sits above the base classes and builtin_curves.
"""

from __future__ import annotations

import threading
from typing import TYPE_CHECKING

from . import builtin_curves
from ._curve_base import BezierCurve as BezierCurve
from ._curve_base import Curve as Curve
from ._curve_base import Matrix as Matrix
from ._curve_base import _bernstein as _bernstein
from ._curve_base import _combine_exact as _combine_exact
from ._curve_base import _float_hodograph as _float_hodograph
from ._curve_base import _float_matrix as _float_matrix
from ._curve_base import _identity as _identity
from ._curve_base import _tables as _tables
from ._lazy import builtin_families, generated

# ---------------------------------------------------------------------- the families
# FAMILIES is assembled on first use (module __getattr__ below): it reads generated/'s list of
# families, which `import lambda_bezier.curves` need not.
if TYPE_CHECKING:
    FAMILIES: dict[str, type[Curve]]

_families_lock = threading.RLock()
_families: dict[str, type[Curve]] = {}


def _families_by_name() -> dict[str, type[Curve]]:
    """FAMILIES: the reference family (BezierCurve), then each built-in family that
    generated/__init__.py lists, in its order. A family's class is the one builtin_curves
    defines under the class name generated/ gives, or else one made here from the generated
    module alone: a family added to generated/ needs no edit of the runtime."""
    if _families:
        return _families
    with _families_lock:
        if _families:
            return _families
        found: dict[str, type[Curve]] = {BezierCurve.family: BezierCurve}
        for family, class_name in builtin_families().items():
            cls = getattr(builtin_curves, class_name, None)
            if cls is None:
                cls = _generated_family_class(family, class_name)
            elif not (isinstance(cls, type) and issubclass(cls, Curve)) or cls.family != family:
                raise TypeError(
                    f"builtin_curves.{class_name} is not the curve class of the family {family!r} "
                    "that generated/__init__.py gives it to"
                )
            found[family] = cls
        _families.update(found)
        return _families


def data_curve_class(
    family: str,
    class_name: str,
    data: object,
    doc: str,
    module: str = __name__,
    parameter_name: str = "lam",
) -> type[Curve]:
    """The curve class of a family that is data only: its name and its tables (a generated
    module, or a derived document read by lambda_bezier.family); the engine is Curve.
    `parameter_name`: the shape parameter's own name (what repr and messages show)."""
    return type(
        class_name,
        (Curve,),
        {
            "family": family,
            "_data": data,
            "__doc__": doc,
            "__module__": module,
            "parameter_name": parameter_name,
        },
    )


def _generated_family_class(family: str, class_name: str) -> type[Curve]:
    """The curve class of a built-in family from its generated module alone (nothing of the
    module is read until a curve needs it). Picklable: it is an attribute of this module."""
    doc = f"A curve of the built-in family {family!r} (generated/{family}.py)."
    return data_curve_class(family, class_name, generated(family), doc)


def __getattr__(name: str) -> object:
    """FAMILIES, and each built-in family's class by its name (e.g. for `pickle`)."""
    if name == "FAMILIES":
        return _families_by_name()
    if name.endswith("Curve"):
        for cls in _families_by_name().values():
            if cls.__name__ == name:
                return cls
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def elsewhere(obj: object) -> str | None:
    """What a loaded family (or a curve of one) that the shared functions do not take says
    about where its own API is, or None: the family object carries the sentence, so no shared
    module names it."""
    fam = getattr(obj, "family_object", obj)
    text = getattr(fam, "elsewhere", None)
    return f"the family {getattr(fam, 'name', '?')!r} {text}" if isinstance(text, str) else None


def family_class(family: object) -> type[Curve]:
    """The curve class of `family`: a built-in family's name, a family defined by data
    (lambda_bezier.load_family), or a Curve subclass."""
    families = _families_by_name()
    if isinstance(family, str):
        if family in families:
            return families[family]
        raise ValueError(
            f"unknown family {family!r}: choose one of {', '.join(map(repr, families))}, or "
            "pass a family from lambda_bezier.load_family"
        )
    index = getattr(family, "index_name", None)
    if index is not None:  # an IndexedFamily: its curve_class is only its lowest degree's
        raise TypeError(
            f"the family {getattr(family, 'name', '?')!r} has one parameter per index "
            f"({index}(i)): one curve class per degree and values; use fam.curve(points, "
            f"{index}=[...]), optimal_parameters, evaluate_many(..., params={{...}}) or "
            f"join(..., {index}=[...])"
        )
    several = getattr(family, "several", None)
    if several is not None:
        names = ", ".join(several.NAMES)
        raise TypeError(
            f"the family {several.FAMILY!r} has several parameters ({names}): one curve class "
            f"per parameter values; use fam.curve(points, {names.replace(', ', '=..., ')}=...), "
            "optimal_parameters, evaluate_many(..., params={...}) or join(..., "
            f"{names.replace(', ', '=..., ')}=...)"
        )
    atoms = getattr(family, "atom_data", None)
    if atoms is not None:  # atom_family: curves that are not polynomial, no tables here
        raise TypeError(
            f"the family {atoms.FAMILY!r} is {atoms.SPACE} (not polynomial): this function "
            "takes polynomial families only; its curves come from fam.curve(points, ...), and "
            "optimal_parameters, evaluate_many(..., params={...}), join and export take it"
        )
    cls = getattr(family, "curve_class", family)
    if isinstance(cls, type) and issubclass(cls, Curve) and cls is not Curve:
        return cls
    told = elsewhere(family)
    if told is not None:
        raise TypeError(told)
    raise ValueError(
        f"unknown family {family!r}: family must be a family name "
        f"({', '.join(map(repr, families))}) or a family from lambda_bezier.load_family"
    )
