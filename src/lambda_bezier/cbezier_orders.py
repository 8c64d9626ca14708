"""A C-Bézier family of several orders (a seed and an integral recursion, Chen and Wang
2003: derive/families/cbezier_recursion.py): one ``"format": 5`` document per degree inside
one document (``"orders"``), each read by lambda_bezier.cbezier_family.

`CBezierOrders.curve(points, alpha=...)` takes the degree from the number of control points;
`at_degree(n)` is the family of one degree (a CBezierFamily, with everything it offers).
"""

from __future__ import annotations

from typing import Any

from ._validate import PointsLike
from .cbezier_family import CBezierCurve, CBezierError, CBezierFamily


class CBezierOrders:
    """A family of ``"format": 5`` with ``"orders"`` (made by `load_family`)."""

    def __init__(self, doc: dict[str, Any], path: str, title: str, table: dict[str, Any]):
        orders = doc.get("orders")
        if not isinstance(orders, dict) or not orders:
            raise CBezierError(f"{path}: 'orders' is not a table of degrees")
        try:
            self.orders = {
                int(k): CBezierFamily(sub, f"{path} (degree {k})", title, table)
                for k, sub in orders.items()
            }
        except (TypeError, ValueError) as exc:
            raise CBezierError(f"{path}: not a document of orders ({exc})") from None
        for k, fam in self.orders.items():
            if fam.degree != k:
                raise CBezierError(f"{path}: the order under {k} has degree {fam.degree}")
        self.degrees = tuple(sorted(self.orders))
        first = self.orders[self.degrees[0]]
        self.family = self.name = first.name
        self.parameter = first.parameter
        self.range_text = first.range_text
        self.title = title
        self.definition = table
        self.table = table
        self.digest = first.digest
        self.elsewhere = first.elsewhere

    def __repr__(self) -> str:
        lo, hi = self.degrees[0], self.degrees[-1]
        return (
            f"CBezierOrders({self.name}, degrees {lo}..{hi}, {self.parameter} in {self.range_text})"
        )

    def at_degree(self, degree: object) -> CBezierFamily:
        """The family of one degree (its basis, energies, curves)."""
        if isinstance(degree, bool) or not isinstance(degree, int):
            raise TypeError(f"degree must be an int, got {type(degree).__name__}")
        if degree not in self.orders:
            raise ValueError(
                f"degree = {degree}: {self.name!r} has degrees {self.degrees[0]}.."
                f"{self.degrees[-1]}"
            )
        return self.orders[degree]

    def _for_points(self, points: PointsLike) -> CBezierFamily:
        try:
            count = len(points)  # type: ignore[arg-type]
        except TypeError:
            raise TypeError("control points must be a sequence of points") from None
        degree = count - 1
        if degree not in self.orders:
            raise ValueError(
                f"control points: {count} points make a curve of degree {degree}; "
                f"{self.name!r} has degrees {self.degrees[0]}..{self.degrees[-1]} "
                f"({self.degrees[0] + 1}..{self.degrees[-1] + 1} points)"
            )
        return self.orders[degree]

    def curve(
        self, points: PointsLike, value: object = None, /, *, params: object = None, **named: object
    ) -> CBezierCurve:
        """The curve of the degree its points give, at the parameter (``alpha=2.0``)."""
        return self._for_points(points).curve(points, value, params=params, **named)

    def start_coefficients(self, alpha: object, orders: int) -> list[list[float]]:
        raise TypeError(
            f"{self.name!r} has several degrees: take one with at_degree(n) (a join into it "
            "is solved in one degree)"
        )

    @property
    def curve_class(self) -> type[CBezierCurve]:
        """CBezierCurve with this family as its class's `family_object` (what from_json
        builds a curve of this family through: `curve` picks the degree)."""
        return type(f"{self.name}Curve", (CBezierCurve,), {"family_object": self})
