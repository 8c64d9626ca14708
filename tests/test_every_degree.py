"""Issue #28: every public curve method, on every degree and dimension the constructors accept.

For each family class: degree 0, 1, the smallest and the largest tabled degree and one above
it; dimensions 1, 2, 3 and 5. The constructor either refuses a degree with a ValueError that
names it, or every public method gives a finite result (checked against an independent
computation where cheap: the basis straight from its definition in tests/reference.py,
de Casteljau in Fractions, finite differences) or the ValueError its documentation states.

The methods are enumerated by introspection: a new public method fails `test_every_method_
has_arguments` until it gets a row in METHODS.
"""

from __future__ import annotations

import inspect
from collections.abc import Callable
from dataclasses import dataclass
from fractions import Fraction

import numpy as np
import pytest
from reference import FAMILIES as REFERENCE

import lambda_bezier as lb

DIMENSIONS = (1, 2, 3, 5)
LAM = Fraction(1, 2)


def _degrees(cls) -> list[int]:
    lo, hi = cls._data.DEGREES[0], cls._data.DEGREES[-1]
    return sorted({0, 1, lo, hi, hi + 1})


def _points(degree: int, dim: int) -> list[tuple[Fraction, ...]]:
    rng = np.random.default_rng(100 * degree + dim)
    return [
        tuple(Fraction(int(v), 4) for v in rng.integers(-12, 13, size=dim))
        for _ in range(degree + 1)
    ]


def _make(cls, pts):
    return cls(pts) if not cls._has_lambda else cls(pts, LAM)


def _reference_point(curve, pts, t: float) -> np.ndarray:
    """p(t) from the family's basis computed from its definition (tests/reference.py)."""
    fam = REFERENCE[curve.family]
    n = len(pts) - 1
    if n == 0:
        return np.array([float(v) for v in pts[0]])
    basis = fam.basis(n, np.array([t]), None if curve.lam is None else float(curve.lam))
    basis = np.asarray(basis, dtype=float).reshape(n + 1, -1)[:, 0]
    return basis @ np.array([[float(v) for v in p] for p in pts])


def _casteljau(rows, t: Fraction) -> list[Fraction]:
    work = [list(map(Fraction, r)) for r in rows]
    while len(work) > 1:
        work = [
            [(1 - t) * a + t * b for a, b in zip(p, q, strict=True)]
            for p, q in zip(work, work[1:], strict=False)
        ]
    return work[0]


# --------------------------------------------------------------------------- the table


@dataclass(frozen=True)
class Method:
    args: Callable  # curve -> (args, kwargs)
    # when the documented refusal applies (ValueError expected), else None: must succeed
    refuses: Callable | None = None
    check: Callable | None = None  # (curve, pts, result) -> None, asserts
    may_refuse: str | None = None  # a documented ValueError that depends on the data


def _check_evaluate(curve, pts, out):
    want = np.array([_reference_point(curve, pts, t) for t in (0.0, 0.3, 1.0)])
    np.testing.assert_allclose(out, want, rtol=1e-9, atol=1e-9)


def _check_derivative(curve, pts, out):
    h = 1e-5
    t = 0.3
    fd = (_reference_point(curve, pts, t + h) - _reference_point(curve, pts, t - h)) / (2 * h)
    scale = 1 + np.abs(fd).max()
    np.testing.assert_allclose(out, fd, rtol=0, atol=1e-5 * scale * max(1, curve.degree) ** 2)


def _check_de_casteljau(curve, pts, out):
    want = [float(v) for v in _casteljau(pts, Fraction(3, 10))]
    np.testing.assert_allclose(out, want, rtol=1e-12, atol=1e-12)


def _check_to_bezier(curve, pts, out):
    for t in (Fraction(0), Fraction(2, 7), Fraction(1)):
        got = [float(v) for v in _casteljau(out.control_points(), t)]
        np.testing.assert_allclose(got, _reference_point(curve, pts, float(t)), atol=1e-9)


def _check_arc_length(curve, pts, out):
    xs = np.linspace(0, 1, 4001)
    ys = np.array([_reference_point(curve, pts, x) for x in xs[:: 4000 // 4000]])
    chord = float(np.linalg.norm(np.diff(ys, axis=0), axis=1).sum())  # a lower bound
    assert chord - 1e-9 <= out <= chord * 1.001 + 1e-9


def _check_box(curve, pts, out):
    lo, hi = out
    for t in np.linspace(0, 1, 33):
        p = _reference_point(curve, pts, t)
        assert (p >= lo - 1e-9).all() and (p <= hi + 1e-9).all()


def _check_closest(curve, pts, out):
    q = np.array([float(v) for v in pts[0]]) + 0.5
    for t in np.linspace(0, 1, 33):
        assert out.distance <= np.linalg.norm(_reference_point(curve, pts, t) - q) + 1e-9


def _check_locate(curve, pts, out):
    assert out is not None
    np.testing.assert_allclose(_reference_point(curve, pts, out), curve.evaluate(0.37), atol=1e-9)


def _line(curve) -> bool:
    return curve.dimension == 1


def _planar(curve) -> bool:
    return curve.dimension != 2


def _is_constant(curve) -> bool:
    return curve.degree == 0


METHODS: dict[str, Method] = {
    "evaluate": Method(lambda c: (([0.0, 0.3, 1.0],), {}), check=_check_evaluate),
    "derivative": Method(lambda c: ((0.3,), {}), check=_check_derivative),
    "basis": Method(lambda c: ((0.3,), {})),
    # documented: ValueError outside 2D/3D and where p' = 0 (a point: everywhere)
    "curvature": Method(
        lambda c: ((0.3,), {}),
        refuses=lambda c: c.dimension not in (2, 3) or _is_constant(c),
        check=lambda c, pts, out: None,
    ),
    "torsion": Method(
        lambda c: ((0.3,), {}), refuses=lambda c: c.dimension != 3 or c.polynomial_degree < 3
    ),
    "energy": Method(lambda c: ((2,), {})),
    "arc_length": Method(lambda c: ((), {}), check=_check_arc_length),
    "parameter_at_length": Method(lambda c: ((0.0,), {}), refuses=_is_constant),
    "bounding_box": Method(lambda c: ((), {}), check=_check_box),
    "closest_point": Method(
        lambda c: ((np.array([float(v) for v in c.control_points()[0]]) + 0.5,), {}),
        check=_check_closest,
    ),
    "from_bezier": Method(lambda c: ((c.to_bezier(),), {"lam": c.lam})),
    "to_bezier": Method(lambda c: ((), {}), check=_check_to_bezier),
    "control_points": Method(lambda c: ((), {})),
    "intersect": Method(lambda c: ((c,), {}), refuses=lambda c: _is_constant(c) or _line(c)),
    "self_intersections": Method(lambda c: ((), {}), refuses=_line),
    "locate": Method(
        lambda c: ((c.evaluate(0.37),), {}),
        refuses=_is_constant,
        check=_check_locate,
        may_refuse="several parameters",  # documented: a point the curve passes twice
    ),
    "implicitize": Method(lambda c: ((), {}), refuses=lambda c: _planar(c) or _is_constant(c)),
    "basis_bernstein_matrix": Method(lambda c: ((), {})),
    "basis_power_matrix": Method(lambda c: ((), {})),
    # BezierCurve's own
    "de_casteljau": Method(lambda c: ((0.3,), {}), check=_check_de_casteljau),
    "split": Method(lambda c: ((0.5,), {})),
    "segment": Method(lambda c: ((0.25, 0.75), {})),
    "elevate": Method(lambda c: ((), {})),
    "hodograph": Method(lambda c: ((), {}), refuses=_is_constant),
    "reduce": Method(lambda c: ((), {}), refuses=_is_constant),
    "full_reduce": Method(lambda c: ((), {})),
    # SameDegreeCurve's own
    "evaluate_geometric": Method(
        lambda c: ((0.3,), {}),
        check=lambda c, pts, out: np.testing.assert_allclose(
            out, _reference_point(c, pts, 0.3), atol=1e-9
        ),
    ),
    "geometric_levels": Method(lambda c: ((Fraction(3, 10),), {})),
}


def _public_methods(cls) -> list[str]:
    return sorted(
        name
        for name in dir(cls)
        if not name.startswith("_")
        and isinstance(
            inspect.getattr_static(cls, name), (type(lambda: 0), classmethod, staticmethod)
        )
    )


CLASSES = dict(lb.FAMILIES)


@pytest.mark.parametrize("name", list(CLASSES))
def test_every_method_has_arguments(name):
    missing = [m for m in _public_methods(CLASSES[name]) if m not in METHODS]
    assert not missing, f"add a row to METHODS for {missing}"


def _finite(result) -> None:
    if isinstance(result, np.ndarray):
        assert np.isfinite(result).all()
    elif isinstance(result, float):
        assert np.isfinite(result)
    elif isinstance(result, tuple | list):
        for item in result:
            _finite(item)


CASES = [
    (name, degree, dim)
    for name, cls in CLASSES.items()
    for degree in _degrees(cls)
    for dim in DIMENSIONS
]

# what is too slow to run at every case (SymPy's resultant at degree 12+): degree limits
SLOW = {"implicitize": 5}


@pytest.mark.parametrize(("name", "degree", "dim"), CASES)
def test_every_method_at_every_degree_and_dimension(name, degree, dim):
    cls = CLASSES[name]
    pts = _points(degree, dim)
    accepted = cls._any_degree or degree in cls._data.DEGREES
    if not accepted:
        with pytest.raises(ValueError, match=r"degree|control points"):
            _make(cls, pts)
        return
    failures = []
    for exact in (True, False):
        curve = _make(cls, pts if exact else [tuple(map(float, p)) for p in pts])
        for method in _public_methods(cls):
            if degree > SLOW.get(method, degree):
                continue
            row = METHODS[method]
            args, kwargs = row.args(curve)
            fn = getattr(curve, method)
            where = f"{method} (exact={exact})"
            if row.refuses is not None and row.refuses(curve):
                try:
                    fn(*args, **kwargs)
                except ValueError as exc:
                    assert str(exc), where
                else:
                    failures.append(f"{where}: no ValueError where the documentation says one")
                continue
            try:
                try:
                    result = fn(*args, **kwargs)
                except ValueError as exc:
                    if row.may_refuse and row.may_refuse in str(exc):
                        continue
                    raise
                _finite(result)
                if row.check is not None:
                    row.check(curve, pts, result)
            except Exception as exc:  # noqa: BLE001 - collected, then reported together
                failures.append(f"{where}: {type(exc).__name__}: {str(exc)[:200]}")
    assert not failures, "\n".join(failures)
