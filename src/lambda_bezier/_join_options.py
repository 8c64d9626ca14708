"""The new patch's choices in a surface join (surface_joins.join_surface), one object for
every side's solver."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any


@dataclass(frozen=True)
class JoinOptions:
    """The new patch's choices in a join, as join_surface takes them (its degree across the
    boundary, λ or parameters by name, given rows, G1's alpha or mu, family, range check,
    where the conditions come from): one object for every side's solver (surface_joins,
    surface_sides, param_surface_joins) instead of the same seven arguments in each signature."""

    degree: int
    lam: Any = None
    rest: Any = ()
    alpha: Any = 1
    mu: Any = None
    family: Any = None
    params: Any = None
    check_range: bool = True
    conditions: str = "solve"
