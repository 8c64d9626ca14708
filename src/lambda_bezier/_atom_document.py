"""Reading format-4 derived documents: families of trigonometric, hyperbolic and mixed
basis functions (issue #30; the contract is docs' own-family guide and atom_family).

Every key is checked and named in the error; nothing is evaluated: numbers are exact
rationals matched by a regular expression or the [["coefficient", exponent], ...] sums of
hazmat.constants, atoms go through hazmat.atoms.parse_atom. Keys this reader does not know
are ignored (a newer writer may add some).
"""

from __future__ import annotations

import math
import re
from fractions import Fraction
from typing import Any, NamedTuple

import numpy as np

from ._family_file import FamilyFileError
from .hazmat import atoms as ak
from .hazmat.constants import ConstantFraction, check_constant, parse_exact

FORMAT = 4
SPACES = ("trigonometric", "hyperbolic", "mixed-trigonometric", "mixed-hyperbolic")
_EXACT = re.compile(r"^-?[0-9]{1,400}(/[0-9]{1,400})?$")
Matrix = tuple[tuple[Fraction, ...], ...]
Mono = tuple[int, ...]
Exact = Fraction | ConstantFraction


def _fraction(text: object, where: str) -> Fraction:
    if not isinstance(text, str) or not _EXACT.match(text):
        raise FamilyFileError(f"{where}: {text!r} is not an exact number")
    try:
        return Fraction(text)
    except ZeroDivisionError:
        raise FamilyFileError(f"{where}: {text!r} divides by zero") from None


def _table(doc: dict[str, Any], key: str, where: str) -> Any:
    if key not in doc:
        raise FamilyFileError(f"{where}: the key {key!r} is missing")
    return doc[key]


def _dict(value: object, where: str) -> dict[str, Any]:
    if not isinstance(value, dict):
        raise FamilyFileError(f"{where}: expected a table, got {type(value).__name__}")
    return value


def _monomial(key: object, size: int, where: str) -> Mono:
    parts = key.split(",") if isinstance(key, str) else []
    if len(parts) != size or not all(x.isdigit() and len(x) < 4 for x in parts):
        raise FamilyFileError(f"{where}: {key!r} is not a monomial of {size} parameters")
    return tuple(int(x) for x in parts)


def _matrix(value: object, rows: int, cols: int, where: str) -> Matrix:
    if (
        not isinstance(value, list)
        or len(value) != rows
        or not all(isinstance(r, list) and len(r) == cols for r in value)
    ):
        raise FamilyFileError(f"{where}: expected a {rows} x {cols} matrix")
    return tuple(tuple(_fraction(v, where) for v in row) for row in value)


def _degree_key(key: object, degrees: tuple[int, ...], where: str) -> int:
    if not isinstance(key, str) or not key.isdigit() or int(key) not in degrees:
        raise FamilyFileError(f"{where}: {key!r} is not one of the degrees {list(degrees)}")
    return int(key)


class RationalForm(NamedTuple):
    """The exact rational Bézier form of one degree: s = sub(W·(t − offset)/2) / scale."""

    hyperbolic: bool
    omega: Fraction  # W of the substitution tan(W*t/2)
    scale: Fraction
    offset: float  # in t
    weights: tuple[Fraction, ...]
    numerators: dict[Mono, Matrix]

    def s_of_t(self, t: np.ndarray | float) -> np.ndarray | float:
        x = 0.5 * float(self.omega) * (np.asarray(t, dtype=float) - self.offset)
        out = (np.tanh(x) if self.hyperbolic else np.tan(x)) / float(self.scale)
        return float(out) if np.ndim(out) == 0 else out

    def t_of_s(self, s: np.ndarray | float) -> np.ndarray | float:
        x = float(self.scale) * np.asarray(s, dtype=float)
        out = self.offset + 2.0 * (np.arctanh(x) if self.hyperbolic else np.arctan(x)) / float(
            self.omega
        )
        return float(out) if np.ndim(out) == 0 else out


class Shape(NamedTuple):
    """One degree's atoms, brought to a common base frequency and centred (hazmat.atoms)."""

    atoms: tuple[ak.Atom, ...]
    omega0: float
    powers: int
    harmonics: int
    hyperbolic: bool
    centring: np.ndarray  # (len(atoms), A)
    derivative: np.ndarray  # (A, A)


def _shape(atoms: list[ak.Atom], mid: float, space: str, where: str) -> Shape:
    hyper = space.endswith("hyperbolic")
    waves = [a for a in atoms if a.kind not in ("1", "t")]
    if any((a.kind in ("cosh", "sinh")) != hyper for a in waves):
        raise FamilyFileError(f"{where}: an atom is not of the {space} space")
    if not space.startswith("mixed") and any(a.kind == "t" for a in atoms):
        raise FamilyFileError(f"{where}: powers of t are only in the mixed spaces, not {space}")
    if len({a.pi for a in waves}) > 1:
        raise FamilyFileError(f"{where}: the frequencies have no common base (some are times pi)")
    omega = ak.base_frequency([a.omega for a in waves]) if waves else Fraction(1)
    omega0 = float(omega) * (math.pi if waves and waves[0].pi else 1.0)
    powers = max((a.power for a in atoms if a.kind == "t"), default=0)
    harmonics = max((int(a.omega / omega) for a in waves), default=0)
    if powers > 40 or harmonics > 200:
        raise FamilyFileError(f"{where}: too many atoms (t^{powers}, harmonic {harmonics})")
    return Shape(
        tuple(atoms),
        omega0,
        powers,
        harmonics,
        hyper,
        ak.centring_matrix(atoms, omega0, powers, harmonics, hyper, mid),
        ak.derivative_matrix(omega0, powers, harmonics, hyper),
    )


class AtomData:
    """A format-4 derived document, checked key by key (unknown keys are ignored)."""

    def __init__(self, doc: dict[str, Any], where: str):
        try:
            self._read(doc, where)
        except FamilyFileError:
            raise
        except (KeyError, TypeError, ValueError, AttributeError, IndexError) as exc:
            raise FamilyFileError(f"{where}: not a format-4 family document ({exc})") from None

    def _read(self, doc: dict[str, Any], where: str) -> None:
        self.FAMILY: str = _table(doc, "family", where)
        if not isinstance(self.FAMILY, str):
            raise FamilyFileError(f"{where}: family: not a name")
        self.SPACE: str = _table(doc, "space", where)
        if self.SPACE not in SPACES:
            raise FamilyFileError(f"{where}: space: {self.SPACE!r} is not one of {SPACES}")
        degrees = _table(doc, "degrees", where)
        if not (
            isinstance(degrees, list)
            and len(degrees) == 2
            and all(isinstance(x, int) and 0 <= x <= 60 for x in degrees)
            and degrees[0] <= degrees[1]
        ):
            raise FamilyFileError(f"{where}: degrees: expected [lo, hi], got {degrees!r}")
        self.DEGREES = tuple(range(degrees[0], degrees[1] + 1))
        offset = doc.get("degree_offset", 0)
        if not isinstance(offset, int):
            raise FamilyFileError(f"{where}: degree_offset: not an integer")
        self.DEGREE_OFFSET = offset
        self._read_parameters(doc, where)
        dom = _dict(_table(doc, "domain", where), f"{where}: domain")
        unit = dom.get("unit", "1")
        if unit not in ("1", "pi"):
            raise FamilyFileError(f"{where}: domain unit {unit!r} is not '1' or 'pi'")
        lo = _fraction(dom.get("lo"), f"{where}: domain lo")
        hi = _fraction(dom.get("hi"), f"{where}: domain hi")
        if not lo < hi:
            raise FamilyFileError(f"{where}: domain: lo {lo} is not below hi {hi}")
        factor = math.pi if unit == "pi" else 1.0
        self.DOMAIN = (float(lo) * factor, float(hi) * factor)
        self.DOMAIN_EXACT = (lo, hi, unit)
        self.DOMAIN_TEXT = str(dom.get("text", f"[{lo}, {hi}]{'·pi' if unit == 'pi' else ''}"))
        mid = 0.5 * (self.DOMAIN[0] + self.DOMAIN[1])
        atoms = _dict(_table(doc, "atoms", where), f"{where}: atoms")
        coeffs = _dict(_table(doc, "coefficients", where), f"{where}: coefficients")
        self.SHAPES: dict[int, Shape] = {}
        self.COEFFICIENTS: dict[int, dict[Mono, Matrix]] = {}
        size = len(self.NAMES)
        for n in self.DEGREES:
            here = f"{where}: atoms[{n}]"
            listed = atoms.get(str(n))
            if not isinstance(listed, list) or not listed or len(listed) > 500:
                raise FamilyFileError(f"{here}: expected a list of atoms")
            try:
                parsed = [ak.parse_atom(a) for a in listed]
            except ValueError as exc:
                raise FamilyFileError(f"{here}: {exc}") from None
            if len(set(parsed)) != len(parsed):
                raise FamilyFileError(f"{here}: an atom is listed twice")
            self.SHAPES[n] = _shape(parsed, mid, self.SPACE, here)
            by_mono = _dict(coeffs.get(str(n)), f"{where}: coefficients[{n}]")
            if not by_mono:
                raise FamilyFileError(f"{where}: coefficients[{n}]: no monomial")
            self.COEFFICIENTS[n] = {
                _monomial(m, size, f"{where}: coefficients[{n}]"): _matrix(
                    mat, n + 1, len(parsed), f"{where}: coefficients[{n}][{m}]"
                )
                for m, mat in by_mono.items()
            }
        for key in atoms:
            _degree_key(key, self.DEGREES, f"{where}: atoms")
        for key in coeffs:
            _degree_key(key, self.DEGREES, f"{where}: coefficients")
        self._read_rational(_dict(_table(doc, "rational", where), f"{where}: rational"), where)
        self._read_energy(_dict(_table(doc, "energy", where), f"{where}: energy"), where)
        self._read_endpoints(doc.get("endpoints"), where)
        # the derived join weights (read by _derived_joins when a join asks for them)
        self.JOINS: Any = doc.get("joins")

    def _read_parameters(self, doc: dict[str, Any], where: str) -> None:
        params = doc.get("parameters")
        if params is None and "parameter" in doc:  # the one-parameter layout of format 2
            params = [{"name": doc["parameter"], "range": doc.get("range")}]
        if not isinstance(params, list) or not params or len(params) > 16:
            raise FamilyFileError(f"{where}: parameters: expected a list of parameters")
        self.NAMES: tuple[str, ...] = ()
        self.RANGES: dict[str, tuple[Fraction, Fraction, bool, bool, str]] = {}
        for q in params:
            q = _dict(q, f"{where}: parameters")
            name = q.get("name")
            if not isinstance(name, str) or not re.match(r"^[a-z][a-z0-9_]{0,31}$", name):
                raise FamilyFileError(f"{where}: parameters: {name!r} is not a parameter name")
            rng = _dict(q.get("range"), f"{where}: parameters: {name} range")
            closed = rng.get("closed", [True, True])
            if not (isinstance(closed, list) and len(closed) == 2):
                raise FamilyFileError(f"{where}: parameters: {name} range closed: not [a, b]")
            lo = _fraction(rng.get("lo"), f"{where}: parameters: {name} range lo")
            hi = _fraction(rng.get("hi"), f"{where}: parameters: {name} range hi")
            if not lo <= hi:
                raise FamilyFileError(f"{where}: parameters: {name} range is empty")
            text = rng.get("text", f"[{lo}, {hi}]")
            self.NAMES += (name,)
            self.RANGES[name] = (lo, hi, bool(closed[0]), bool(closed[1]), str(text))
        if len(set(self.NAMES)) != len(self.NAMES):
            raise FamilyFileError(f"{where}: parameters: a name is given twice")

    def _read_rational(self, table: dict[str, Any], where: str) -> None:
        self.RATIONAL: dict[int, RationalForm] = {}
        self.RATIONAL_REASON: str | None = None
        here = f"{where}: rational"
        if "reason" in table:
            self.RATIONAL_REASON = str(table["reason"])
            return
        sub = table.get("substitution")
        m = re.match(r"^(tanh|tan)\((?:([1-9][0-9]{0,9}(?:/[1-9][0-9]{0,9})?)\*)?t/2\)$", str(sub))
        if m is None:
            raise FamilyFileError(f"{here}: substitution {sub!r} is not tan(t/2) or tanh(t/2)")
        hyper = m.group(1) == "tanh"
        if hyper != self.SPACE.endswith("hyperbolic") or self.SPACE.startswith("mixed"):
            raise FamilyFileError(f"{here}: substitution {sub} does not fit the {self.SPACE} space")
        omega = Fraction(m.group(2) or 1)
        scale = _fraction(table.get("scale", "1"), f"{here}: scale")
        if scale <= 0:
            raise FamilyFileError(f"{here}: scale must be positive")
        off = _fraction(table.get("t_offset", "0"), f"{here}: t_offset")
        unit = math.pi if self.DOMAIN_EXACT[2] == "pi" else 1.0
        degree = _dict(table.get("degree"), f"{here}: degree")
        weights = _dict(table.get("weights"), f"{here}: weights")
        numerators = _dict(table.get("numerators"), f"{here}: numerators")
        for n in self.DEGREES:
            deg = degree.get(str(n))
            if not isinstance(deg, int) or not 0 <= deg <= 400:
                raise FamilyFileError(f"{here}: degree[{n}]: not a degree")
            w = weights.get(str(n))
            if not isinstance(w, list) or len(w) != deg + 1:
                raise FamilyFileError(f"{here}: weights[{n}]: expected {deg + 1} weights")
            wq = tuple(_fraction(x, f"{here}: weights[{n}]") for x in w)
            if not all(x > 0 for x in wq):
                raise FamilyFileError(f"{here}: weights[{n}]: the weights must be positive")
            nums = _dict(numerators.get(str(n)), f"{here}: numerators[{n}]")
            form = RationalForm(
                hyper,
                omega,
                scale,
                float(off) * unit,
                wq,
                {
                    _monomial(k, len(self.NAMES), f"{here}: numerators[{n}]"): _matrix(
                        v, n + 1, deg + 1, f"{here}: numerators[{n}][{k}]"
                    )
                    for k, v in nums.items()
                },
            )
            lo, hi = self.DOMAIN
            s_lo, s_hi = form.s_of_t(lo), form.s_of_t(hi)
            if not (abs(s_lo) < 1e-12 and abs(s_hi - 1.0) < 1e-12):  # type: ignore[operator]
                raise FamilyFileError(
                    f"{here}: {sub} / {scale} maps the domain {self.DOMAIN_TEXT} onto "
                    f"[{s_lo:.6g}, {s_hi:.6g}], not [0, 1]"
                )
            self.RATIONAL[n] = form

    def _read_energy(self, table: dict[str, Any], where: str) -> None:
        self.ENERGY_REASON: str | None = None
        self.GRAM: dict[tuple[int, int], dict[tuple[Mono, Mono], tuple[tuple[Exact, ...], ...]]]
        self.GRAM = {}
        if "reason" in table:
            self.ENERGY_REASON = str(table["reason"])
        size = len(self.NAMES)
        for key, entry in table.items():
            if key == "reason":
                continue
            here = f"{where}: energy[{key}]"
            parts = key.split(",")
            if len(parts) != 2 or not all(p.isdigit() for p in parts):
                raise FamilyFileError(f"{here}: not a key 'n,k'")
            n, k = int(parts[0]), int(parts[1])
            if n not in self.DEGREES or not 0 <= k <= 10:
                raise FamilyFileError(f"{here}: no such degree or order")
            entry = _dict(entry, here)
            constant = entry.get("constant")
            if constant is not None:
                try:
                    check_constant(constant)
                except ValueError as exc:
                    raise FamilyFileError(f"{here}: constant: {exc}") from None
            gram = _dict(entry.get("gram"), f"{here}: gram")
            out = {}
            for pair, mat in gram.items():
                halves = pair.split("|") if isinstance(pair, str) else []
                if len(halves) != 2:
                    raise FamilyFileError(f"{here}: {pair!r} is not a monomial pair 'm1|m2'")
                m1, m2 = (_monomial(h, size, here) for h in halves)
                if not (
                    isinstance(mat, list)
                    and len(mat) == n + 1
                    and all(isinstance(r, list) and len(r) == n + 1 for r in mat)
                ):
                    raise FamilyFileError(f"{here}: gram[{pair}]: expected a square matrix")
                try:
                    out[(m1, m2)] = tuple(
                        tuple(parse_exact(v, constant, f"{here}: gram[{pair}]") for v in row)
                        for row in mat
                    )
                except ValueError as exc:
                    raise FamilyFileError(str(exc)) from None
            self.GRAM[(n, k)] = out

    def _read_endpoints(self, table: object, where: str) -> None:
        """Checked for form only: the runtime takes end derivatives from the atoms."""
        if table is None:
            return
        table = _dict(table, f"{where}: endpoints")
        if "reason" in table:
            return
        constant = table.get("constant")
        size = len(self.NAMES)
        for key, by_end in table.items():
            if key == "constant":
                continue
            here = f"{where}: endpoints[{key}]"
            _degree_key(key, self.DEGREES, f"{where}: endpoints")
            for end, values in _dict(by_end, here).items():
                if not re.match(r"^(start|end),[0-9]{1,2},[0-9]{1,3}$", str(end)):
                    raise FamilyFileError(f"{here}: {end!r} is not 'start|end,r,j'")
                for mono, v in _dict(values, f"{here}[{end}]").items():
                    _monomial(mono, size, f"{here}[{end}]")
                    try:
                        parse_exact(v, constant, f"{here}[{end}]")
                    except ValueError as exc:
                        raise FamilyFileError(str(exc)) from None
