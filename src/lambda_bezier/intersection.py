"""intersect_many: the intersections of many pairs of curves, their subdivision done together.

Each curve's exact Bézier form is prepared once (a curve in several pairs is not prepared
again); the pairs' end points and shared stretches are found pair by pair, then every pair of
the same degrees and dimension is subdivided in one set of arrays
(hazmat.intersect_subdivide.isolate), and the roots are refined pair by pair. The answers are those
of Curve.intersect, pair for pair.
"""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction
from typing import TYPE_CHECKING, Literal

if TYPE_CHECKING:
    from .curves import Curve
    from .hazmat.intersect import Intersection
    from .hazmat.intersect_exact import ExactCrossing
    from .rational import RationalBezierCurve


def __getattr__(name: str) -> object:
    # the engines load on first use: naming intersect_many or intersect_exact (as `import
    # lambda_bezier` with every public name does) does not need them (issue #29's import row)
    if name == "Intersection":
        from .hazmat.intersect import Intersection

        return Intersection
    if name == "ExactCrossing":
        from .hazmat.intersect_exact import ExactCrossing

        return ExactCrossing
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def _curves(curves: object, name: str) -> list[Curve]:
    from .curves import Curve

    if (
        isinstance(curves, Curve)
        or getattr(type(curves), "intersects_curves", False)
        or not isinstance(curves, Sequence)
    ):
        raise TypeError(f"{name} must be a sequence of curves, got {type(curves).__name__}")
    for k, c in enumerate(curves):
        # rational Bézier and trigonometric/hyperbolic/mixed curves take their own engine
        if not isinstance(c, Curve) and not getattr(type(c), "intersects_curves", False):
            raise TypeError(f"{name}[{k}] must be a curve, got {type(c).__name__}")
    return list(curves)


def intersect_many(
    curves_a: Sequence[Curve],
    curves_b: Sequence[Curve],
    mode: Literal["pairs", "all"] = "pairs",
) -> list[list[Intersection]] | list[list[list[Intersection]]]:
    """Intersections of many curve pairs at once.

    Any curve class: polynomial families together, rational Bézier and trigonometric,
    hyperbolic or mixed curves through their own intersect, pair by pair.
    mode "pairs": curves_a[k] against curves_b[k] (equal lengths); returns one list of
    Intersection(s, t, kind) per pair, as curves_a[k].intersect(curves_b[k]) gives it.
    mode "all": every curve of curves_a against every curve of curves_b; returns
    result[i][j] = curves_a[i].intersect(curves_b[j]).

    >>> from lambda_bezier import BezierCurve, intersect_many
    >>> arch = BezierCurve([(0, 0), (1, 2), (2, 0)])
    >>> lines = [BezierCurve([(0, y), (2, y)]) for y in (0.5, 1, 2)]
    >>> [len(hits) for hits in intersect_many([arch] * 3, lines)]
    [2, 1, 0]
    >>> intersect_many([arch], lines, mode="all")[0][1]
    [Intersection(s=0.5, t=0.5, kind='tangent')]
    """
    a = _curves(curves_a, "curves_a")
    b = _curves(curves_b, "curves_b")
    if mode == "pairs":
        if len(a) != len(b):
            raise ValueError(
                f"mode 'pairs' needs curves_a and curves_b of equal length, got {len(a)} "
                f"and {len(b)}"
            )
        index = [(k, k) for k in range(len(a))]
    elif mode == "all":
        index = [(i, j) for i in range(len(a)) for j in range(len(b))]
    else:
        raise ValueError(f"mode must be 'pairs' or 'all', got {mode!r}")
    from .curves import Curve
    from .hazmat import intersect as engine

    # polynomial pairs together; a pair with a rational or trigonometric/hyperbolic/mixed
    # curve through that curve's own intersect
    poly = [
        k for k, (i, j) in enumerate(index) if isinstance(a[i], Curve) and isinstance(b[j], Curve)
    ]
    found: list[list[Intersection]] = [[] for _ in index]
    answered, declined = _float_batch(a, b, index, poly)
    for k, hits in answered.items():
        found[k] = hits
    rest = [k for k in poly if k not in answered]
    # the others, and those the kernels declined, the careful way (each curve prepared once)
    prepared_a = {i: a[i]._prepared for i, _ in (index[k] for k in rest)}
    prepared_b = {j: b[j]._prepared for _, j in (index[k] for k in rest)}
    together = engine.intersect_pairs(
        [(prepared_a[index[k][0]], prepared_b[index[k][1]]) for k in rest],
        [k not in declined for k in rest],
    )
    for k, hits in zip(rest, together, strict=True):
        found[k] = hits
    for k in sorted(set(range(len(index))) - set(poly)):
        found[k] = a[index[k][0]].intersect(b[index[k][1]])
    if mode == "pairs":
        return found
    return [found[i * len(b) : (i + 1) * len(b)] for i in range(len(a))]


def _float_batch(
    a: list[Curve], b: list[Curve], index: list[tuple[int, int]], poly: list[int]
) -> tuple[dict[int, list[Intersection]], set[int]]:
    """The pairs of float Bézier curves the compiled kernels take as they are (as
    Curve.intersect takes them: engine.float_pair), all of one dimension in one
    compiled call (engine.float_pairs): (answers by pair, pairs both kernels declined)."""
    from .curves import Curve
    from .hazmat import intersect as engine

    answered: dict[int, list[Intersection]] = {}
    declined: set[int] = set()
    if not engine.compiled_in_use():
        return answered, declined
    # float Bézier curves of an ordinary size, as Curve.intersect gives them to float_pair
    # (a rational or trigonometric curve is none of them)
    ready = {
        id(c): isinstance(c, Curve) and c._bezier_form and c._exact_points is None and c._ordinary
        for c in (*a, *b)
    }
    groups: dict[int, tuple[list[int], list[int], list[int], dict[int, int]]] = {}
    for k in poly:
        i, j = index[k]
        if not (ready[id(a[i])] and ready[id(b[j])]):
            continue
        dim = a[i].dimension
        if dim != b[j].dimension or dim < 2:
            continue
        pairs, lefts, rights, slots = groups.setdefault(dim, ([], [], [], {}))
        pairs.append(k)
        lefts.append(slots.setdefault(id(a[i]), len(slots)))
        rights.append(slots.setdefault(id(b[j]), len(slots)))
    curves = {id(c): c for c in (*a, *b)}
    for pairs, lefts, rights, slots in groups.values():
        points = [curves[key].points for key in slots]  # in slot order (dicts keep it)
        for k, hits in zip(pairs, engine.float_pairs(points, lefts, rights), strict=True):
            if hits is None:
                declined.add(k)
            else:
                answered[k] = hits
    return answered, declined


def intersect_exact(
    curve_a: Curve | RationalBezierCurve, curve_b: Curve | RationalBezierCurve
) -> list[ExactCrossing]:
    """The crossings of two planar curves with exact (int or Fraction) control points and
    shape parameter (or weights, for rational Bézier curves: then on the cross-multiplied
    system X_a W_b − X_b W_a = 0), isolated exactly: boxes s in [s0, s1], t in [t0, t1]
    with Fraction ends, each holding exactly one crossing when ``certified`` (Krawczyk's
    test in rational interval arithmetic on the isolated roots of the two resultants; see
    ``lambda_bezier.hazmat.intersect_exact``); a box Krawczyk cannot prove (a tangency) is
    decided algebraically, certified with ``tangent`` True when the curves touch there and
    dropped when they do not. A box left uncertified holds two common points over one s and
    over one t. Sorted by s.

    >>> from fractions import Fraction as F
    >>> from lambda_bezier import BezierCurve, intersect_exact
    >>> arch = BezierCurve([(0, 0), (1, 2), (2, 0)])
    >>> line = BezierCurve([(0, F(1, 2)), (2, F(1, 2))])
    >>> boxes = intersect_exact(arch, line)
    >>> [(c.certified, c.tangent) for c in boxes]
    [(True, False), (True, False)]
    >>> def g(s):  # the arch's height minus 1/2, over 2: zero at s = (2 ∓ √2)/4
    ...     return (2 * s - 1) ** 2 - F(1, 2)
    >>> [g(c.s[0]) * g(c.s[1]) < 0 for c in boxes]  # each box brackets one of them, exactly
    [True, True]
    """
    from .curves import Curve
    from .rational import RationalBezierCurve

    rows, weights = [], []
    for name, c in (("curve_a", curve_a), ("curve_b", curve_b)):
        if not isinstance(c, Curve | RationalBezierCurve):
            raise TypeError(f"{name} must be a curve, got {type(c).__name__}")
        if not c.is_exact:
            raise ValueError(
                f"{name} is not exact: intersect_exact needs int or Fraction control points "
                "(and shape parameter, or weights); Curve.intersect handles floats"
            )
        if c.dimension != 2:
            raise ValueError(
                f"intersect_exact needs planar curves, {name} has dimension {c.dimension}"
            )
        exact_rows = c._exact_points if isinstance(c, RationalBezierCurve) else None
        exact_weights = c._exact_weights if isinstance(c, RationalBezierCurve) else None
        if not isinstance(c, RationalBezierCurve):
            exact_rows = c.to_bezier()._exact_points
            exact_weights = tuple(Fraction(1) for _ in range(c.degree + 1))
        assert exact_rows is not None and exact_weights is not None  # an exact curve's
        rows.append(exact_rows)
        weights.append(exact_weights)
    from .hazmat.intersect_exact import isolate

    if isinstance(curve_a, Curve) and isinstance(curve_b, Curve):
        return isolate(rows[0], rows[1])
    return isolate(rows[0], rows[1], weights=(weights[0], weights[1]))
