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

from .batch import evaluate_many
from .composite import CompositeCurve, JointReport
from .curves import FAMILIES, BernsteinLikeCurve, BezierCurve, Curve, SameDegreeCurve
from .energy import OptimalLambda, energy_coefficients, energy_matrices, optimal_lambda
from .joins import Joint, join

__version__ = "0.1.0"
__all__ = [
    "FAMILIES",
    "BernsteinLikeCurve",
    "BezierCurve",
    "CompositeCurve",
    "Curve",
    "Joint",
    "JointReport",
    "OptimalLambda",
    "SameDegreeCurve",
    "energy_coefficients",
    "energy_matrices",
    "evaluate_many",
    "join",
    "optimal_lambda",
]
