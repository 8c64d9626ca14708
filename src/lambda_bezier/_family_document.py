"""Reading the derived document of a family of the user's own (formats 2 and 3, in one or
several parameters): the tables a `Family`'s curves read, with the attributes of a generated
family module (`FamilyData`, `SeveralData`, and `FixedData` for several parameters at fixed
values). Nothing is evaluated: every number is an exact rational matched by _atom_document's
reader; a missing or malformed key is a FamilyFileError naming the file.
"""

from __future__ import annotations

from collections.abc import Mapping
from fractions import Fraction
from typing import TYPE_CHECKING, Any

from ._atom_document import Matrix, Mono, _fraction
from ._family_file import FamilyFileError
from ._singular import IsolatedRoot

if TYPE_CHECKING:
    from .energy import Form


def _matrices(value: object, where: str) -> tuple[Matrix, ...]:
    if not isinstance(value, list):
        raise FamilyFileError(f"{where}: expected a list of matrices")
    return tuple(tuple(tuple(_fraction(v, where) for v in row) for row in mat) for mat in value)


def _ints(value: object, where: str) -> tuple[tuple[int, ...], ...]:
    if not isinstance(value, list) or not all(
        isinstance(row, list) and all(isinstance(v, int) for v in row) for row in value
    ):
        raise FamilyFileError(f"{where}: expected a matrix of integers")
    return tuple(tuple(row) for row in value)


def monomial_value(values: tuple[Fraction, ...], mono: Mono) -> Fraction:
    """The monomial with exponents `mono` at the parameter values."""
    w = Fraction(1)
    for v, e in zip(values, mono, strict=True):
        w *= v**e
    return w


def combine(by_mono: Mapping[Mono, Matrix], values: tuple[Fraction, ...]) -> Matrix:
    """Σ_mono mono(values) · matrix, exactly: the basis of a several-parameter (or atom)
    family at fixed parameter values from its matrices per parameter monomial."""
    acc: list[list[Fraction]] | None = None
    for mono, mat in by_mono.items():
        w = monomial_value(values, mono)
        if acc is None:
            acc = [[Fraction(0)] * len(mat[0]) for _ in mat]
        if w:
            for r, row in enumerate(mat):
                for c, x in enumerate(row):
                    acc[r][c] += w * x
    assert acc is not None
    return tuple(tuple(row) for row in acc)


def _header(doc: dict[str, Any]) -> tuple[str, tuple[int, ...], int]:
    """(family, degrees, degree offset) of a document; KeyError/TypeError/ValueError when
    malformed (the readers name the file)."""
    lo, hi = doc["degrees"]
    return doc["family"], tuple(range(int(lo), int(hi) + 1)), int(doc["degree_offset"])


class FamilyData:
    """The tables of one family, with the attributes of a generated family module (what the
    Curve base class and the energy and batch code read)."""

    def __init__(self, doc: dict[str, Any], where: str):
        try:
            self.FAMILY, self.DEGREES, self.DEGREE_OFFSET = _header(doc)
            rng = doc["range"]
            self.LAMBDA_RANGE = (_fraction(rng["lo"], where), _fraction(rng["hi"], where))
            self.LAMBDA_CLOSED = (bool(rng["closed"][0]), bool(rng["closed"][1]))
            self.LAMBDA_RANGE_TEXT: str = rng["text"]
            at = doc["bernstein_at"]
            self.BERNSTEIN_LAMBDA = None if at is None else _fraction(at, where)
            self.POWER = {int(k): _matrices(v, where) for k, v in doc["power"].items()}
            self.CENTRED = {int(k): _matrices(v, where) for k, v in doc["centred"].items()}
            self.BERNSTEIN = {int(k): _matrices(v, where) for k, v in doc["bernstein"].items()}
            energy = doc["energy"]
        except (KeyError, TypeError, ValueError) as exc:
            if isinstance(exc, FamilyFileError):
                raise
            raise FamilyFileError(f"{where}: not a derived family document ({exc!r})") from None
        # C1/G1/C2 between surface patches, as data (read by surface_joins when asked to)
        self.SURFACE_JOINS: Any = doc.get("surface_joins")
        self.ENERGY_REASON: str | None = energy.get("reason")
        self.ENERGY: dict[tuple[int, int], tuple[Form, ...]] = {}
        for key, entry in energy.items():
            if key == "reason":
                continue
            n, k = (int(x) for x in key.split(","))
            self.ENERGY[(n, k)] = tuple(
                (_fraction(entry[part][0], where), _ints(entry[part][1], where))
                for part in ("ff", "fg", "gg")
            )
        self.SINGULAR: dict[int, tuple[Fraction | IsolatedRoot, ...]] = {}
        for key, roots in doc.get("singular_parameters", {}).items():
            self.SINGULAR[int(key)] = tuple(
                _fraction(r, where)
                if isinstance(r, str)
                else IsolatedRoot(
                    _fraction(r[0][0], where), _fraction(r[0][1], where), tuple(map(int, r[1]))
                )
                for r in roots
            )
        for n in self.DEGREES:
            for table in (self.POWER, self.CENTRED, self.BERNSTEIN):
                if n not in table:
                    raise FamilyFileError(f"{where}: no table for degree {n}")


def _monomial(key: str, size: int, where: str) -> tuple[int, ...]:
    parts = key.split(",")
    if len(parts) != size or not all(x.isdigit() for x in parts):
        raise FamilyFileError(f"{where}: {key!r} is not a monomial of {size} parameters")
    return tuple(int(x) for x in parts)


class SeveralData:
    """The tables of a family in several parameters: per degree, a matrix per parameter
    monomial (exponent tuple); E_k as Gram matrices of the affine parts."""

    def __init__(self, doc: dict[str, Any], where: str):
        try:
            self.FAMILY, self.DEGREES, self.DEGREE_OFFSET = _header(doc)
            params = doc["parameters"]
            self.NAMES: tuple[str, ...] = tuple(str(q["name"]) for q in params)
            self.RANGES = {
                str(q["name"]): (
                    _fraction(q["range"]["lo"], where),
                    _fraction(q["range"]["hi"], where),
                    bool(q["range"]["closed"][0]),
                    bool(q["range"]["closed"][1]),
                    str(q["range"]["text"]),
                )
                for q in params
            }
            size = len(self.NAMES)
            self.TABLES: dict[str, dict[int, dict[tuple[int, ...], Matrix]]] = {
                kind: {
                    int(deg): {
                        _monomial(key, size, where): _matrices([mat], where)[0]
                        for key, mat in by_mono.items()
                    }
                    for deg, by_mono in doc[kind].items()
                }
                for kind in ("power", "centred", "bernstein")
            }
            energy = doc["energy"]
            self.JOINS: Any = doc.get("joins")  # derived join weights (_derived_joins)
            self.ENERGY_REASON: str | None = energy.get("reason")
            self.GRAM: dict[tuple[int, int], dict[tuple[int, int], Matrix]] = {}
            for key, entry in energy.items():
                if key == "reason":
                    continue
                n, k = (int(x) for x in key.split(","))
                self.GRAM[(n, k)] = {
                    _monomial(pair, 2, where): _matrices([mat], where)[0]  # type: ignore[misc]
                    for pair, mat in entry.items()
                }
            # E_k of a basis not affine in the parameters: Gram matrices per monomial pair
            self.MONOMIAL_GRAM: dict[tuple[int, int], dict[tuple[tuple[int, ...], ...], Matrix]]
            self.MONOMIAL_GRAM = {}
            for key, entry in doc.get("energy_monomials", {}).items():
                n, k = (int(x) for x in key.split(","))
                self.MONOMIAL_GRAM[(n, k)] = {
                    tuple(_monomial(m, size, where) for m in pair.split(";")): _matrices(
                        [mat], where
                    )[0]
                    for pair, mat in entry.items()
                }
        except (KeyError, TypeError, ValueError, AttributeError) as exc:
            if isinstance(exc, FamilyFileError):
                raise
            raise FamilyFileError(f"{where}: not a derived family document ({exc!r})") from None
        for n in self.DEGREES:
            for kind, table in self.TABLES.items():
                if n not in table:
                    raise FamilyFileError(f"{where}: no {kind} table for degree {n}")


class FixedData:
    """A family in several parameters at fixed parameter values: the tables of one basis
    (what the Curve engine reads of a family without a parameter)."""

    def __init__(self, several: SeveralData, values: tuple[Fraction, ...]):
        self.FAMILY = several.FAMILY
        self.DEGREES = several.DEGREES
        self.DEGREE_OFFSET = several.DEGREE_OFFSET
        self.SINGULAR: dict[int, tuple[Fraction, ...]] = {}
        for kind, table in several.TABLES.items():
            combined = {deg: (combine(by_mono, values),) for deg, by_mono in table.items()}
            setattr(self, kind.upper(), combined)
