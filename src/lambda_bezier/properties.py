"""Facts about the bases derived exactly by derive/properties.py: where a basis is singular.

``singular_parameters(family, n)`` reads the emitted table (generated/properties.py); nothing
here computes a root numerically except ``IsolatedRoot.__float__``, which bisects inside the
exact isolating interval.
"""

from __future__ import annotations

from fractions import Fraction

from . import _singular
from ._singular import IsolatedRoot as IsolatedRoot

IsolatedRoot.__module__ = __name__  # documented (and pickled) as lambda_bezier.properties'


def singular_parameters(family: object, n: int) -> tuple[Fraction | IsolatedRoot, ...]:
    """The λ inside the family's range at which its degree-n basis is linearly dependent:
    exact Fractions, or IsolatedRoot intervals with rational ends around irrational roots.

    A curve of that degree and λ has no unique control points for a given shape (and
    ``from_bezier`` refuses it). The classical Bézier basis has no parameter: ``()``.
    `family` is a built-in family's name or a family from ``load_family`` (whose derived
    document carries the same table, from the same exact procedure).
    """
    from .curves import family_class  # numpy: imported when first asked

    if getattr(family, "index_name", None) is not None:  # an IndexedFamily (lam(i))
        # its curve_class is its lowest degree's: the one-parameter table read below is not
        # its own (a KeyError, or "outside the range 2..2" for a degree it has)
        raise TypeError(
            f"the family {family.name!r} has one parameter per index "  # type: ignore[attr-defined]
            f"({family.index_name}(i)): singular_parameters takes one-parameter families; "  # type: ignore[attr-defined]
            "where its basis is dependent over the box is in its derived document, per degree "
            '(by_degree["n"]["singular_parameters"])'
        )
    cls = family_class(family)  # a built-in family's name, a family from load_family, a class
    if not cls._has_lambda:  # the classical Bézier basis
        return ()
    if isinstance(n, bool) or not isinstance(n, int):
        raise TypeError(f"n must be an integer degree, not {type(n).__name__}")
    degrees = tuple(cls._data.DEGREES)
    if n not in degrees:
        raise ValueError(
            f"n: degree {n} is outside the {cls.family} range {degrees[0]}..{degrees[-1]}"
        )
    return _singular.roots(cls.family, cls._data, n)


def is_singular(family: object, n: int, lam: Fraction | float) -> bool:
    """True when the degree-n basis of `family` is linearly dependent at this λ: exact for an
    exact λ; a float λ counts as singular within 1e-12 of a singular parameter."""
    return _singular.is_root(singular_parameters(family, n), lam)
