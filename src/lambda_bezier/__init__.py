"""lambda-bezier: Bézier curves with a shape parameter λ, derived symbolically, evaluated fast.

Three curve families share one API::

    >>> from fractions import Fraction
    >>> from lambda_bezier import SameDegreeCurve
    >>> c = SameDegreeCurve([(0, 0), (1, 2), (3, 2), (4, 0)], lam=Fraction(1, 2))
    >>> c.evaluate(0.5).tolist()
    [2.0, 1.25]
    >>> c.to_bezier().control_points()[1]
    (Fraction(5, 6), Fraction(5, 3))

The formulas behind them live in generated/ (emitted by derive/); this package is the numeric
runtime and never imports SymPy.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from .atom_family import AtomCurve
    from .batch import evaluate_many
    from .builtin_curves import BernsteinLikeCurve, SameDegreeCurve
    from .builtin_families import BuiltinFamily, builtin_family
    from .builtin_surfaces import BernsteinLikeSurface, SameDegreeSurface
    from .composite import CompositeCurve, JointReport
    from .curves import FAMILIES, BezierCurve, Curve
    from .energy import (
        OptimalLambda,
        energy_coefficients,
        energy_matrices,
        optimal_lambda,
    )
    from .family import Family, load_family
    from .hazmat.constants import ConstantFraction
    from .intersection import intersect_exact, intersect_many
    from .joins import Joint, join
    from .parameter_optimum import OptimalParameters
    from .properties import IsolatedRoot, singular_parameters
    from .rational import RationalBezierCurve
    from .surface_energies import SurfaceOptimalParameters
    from .surface_joins import CompositeSurface, join_surface
    from .surface_optimum import optimal_parameters, surface_energy, surface_energy_matrices
    from .surfaces import BezierSurface, Surface

__version__ = "0.1.0"

# The public names, each imported from its module on first access (PEP 562): the command line
# (`lambda-bezier verify`, `derive`) runs without numpy, and importing it costs a tenth of a
# second, about as long as everything else before the first record.
_EXPORTS = {
    "evaluate_many": "batch",
    "CompositeCurve": "composite",
    "JointReport": "composite",
    "FAMILIES": "curves",
    "BernsteinLikeCurve": "curves",
    "BezierCurve": "curves",
    "Curve": "curves",
    "SameDegreeCurve": "curves",
    "OptimalLambda": "energy",
    "energy_coefficients": "energy",
    "energy_matrices": "energy",
    "optimal_lambda": "energy",
    "OptimalParameters": "parameter_optimum",
    "Family": "family",
    "load_family": "family",
    "BuiltinFamily": "builtin_families",
    "builtin_family": "builtin_families",
    "intersect_exact": "intersection",
    "intersect_many": "intersection",
    "Joint": "joins",
    "join": "joins",
    "IsolatedRoot": "properties",
    "singular_parameters": "properties",
    "SurfaceOptimalParameters": "surface_energies",
    "optimal_parameters": "surface_optimum",  # curves (k an int) and surfaces
    # every surface and family: param_surface_energy (the several-parameter engine) is
    # imported on the first call that needs it, surface_energies otherwise
    "surface_energy": "surface_optimum",
    "surface_energy_matrices": "surface_optimum",
    "CompositeSurface": "surface_joins",
    "join_surface": "surface_joins",
    "BernsteinLikeSurface": "builtin_surfaces",
    "BezierSurface": "surfaces",
    "SameDegreeSurface": "builtin_surfaces",
    "Surface": "surfaces",
    "RationalBezierCurve": "rational",
    "AtomCurve": "atom_family",
    "ConstantFraction": "hazmat.constants",
}
__all__ = [
    "FAMILIES",
    "AtomCurve",
    "BernsteinLikeCurve",
    "BernsteinLikeSurface",
    "BezierCurve",
    "BezierSurface",
    "BuiltinFamily",
    "CompositeCurve",
    "CompositeSurface",
    "ConstantFraction",
    "Curve",
    "Family",
    "IsolatedRoot",
    "Joint",
    "JointReport",
    "OptimalLambda",
    "OptimalParameters",
    "RationalBezierCurve",
    "SameDegreeCurve",
    "SameDegreeSurface",
    "Surface",
    "SurfaceOptimalParameters",
    "energy_coefficients",
    "energy_matrices",
    "builtin_family",
    "evaluate_many",
    "intersect_exact",
    "intersect_many",
    "join",
    "join_surface",
    "load_family",
    "optimal_lambda",
    "optimal_parameters",
    "singular_parameters",
    "surface_energy",
    "surface_energy_matrices",
]


def __getattr__(name: str) -> object:  # the names above, typed by their imports
    module = _EXPORTS.get(name)
    if module is not None:
        value = getattr(importlib.import_module(f".{module}", __name__), name)
    else:  # the class of a built-in family that generated/ lists (curves.FAMILIES), or nothing
        curves = importlib.import_module(".curves", __name__) if name.endswith("Curve") else None
        value = getattr(curves, name, None)
        if value is None:
            raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    globals()[name] = value  # later accesses skip this function
    return value


def __dir__() -> list[str]:
    # the public names and the module's dunders, not the helpers this file imports for itself
    # (importlib, TYPE_CHECKING, annotations) nor the submodules loaded so far
    return sorted({*__all__, *(name for name in globals() if name.startswith("__"))})
