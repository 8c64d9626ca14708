"""The compiled kernels' entry for one pair of curves, or many pairs in one call.

Each pair runs the certificate and, where it declines, the careful path compiled, in one
call (intersect_pairs_compiled): the kernels intersect_certify.certify_one and settle_one
run one after the other, with the same arguments, so the same answers bit for bit. Many
pairs of one dimension go in one call: every curve's float points in one array, the pairs
as two index arrays (issue #29: intersect_many with numba ran each pair through two calls,
so it was never faster than a loop).

The caller checks that the floats are the curves exactly, that the pair needs no
normalisation (intersect.normalised) and that both have one dimension >= 2; pairs the
kernels decline take the careful path in Python. Without numba (or with
intersect_subdivide.USE_COMPILED off) `in_use` is False and nothing here runs.
"""

from __future__ import annotations

import threading
from collections.abc import Sequence
from types import ModuleType

import numpy as np

from . import intersect_certify as cert
from . import intersect_subdivide as sub

Hit = tuple[float, float, float]  # s, t, kind code (refine_compiled: -1, 0, 1)

_kernel: dict[str, ModuleType] = {}  # the compiled module once imported
# the half matrices of every degree seen so far, in one flat table (left then right,
# row-major) at offsets[degree] (-1: not there yet); replaced, never changed in place
_halves_lock = threading.Lock()
_halves: tuple[np.ndarray, np.ndarray, frozenset[int]] = (
    np.zeros(0),
    np.full(0, -1, dtype=np.int64),
    frozenset(),
)


def in_use() -> bool:
    """Whether the compiled kernels run (numba installed, not disabled)."""
    return cert.in_use()


def _compiled() -> ModuleType:
    kernel = _kernel.get("pairs")
    if kernel is None:
        from . import intersect_pairs_compiled

        kernel = _kernel["pairs"] = intersect_pairs_compiled
    return kernel


def _half_table(degrees: Sequence[int]) -> tuple[np.ndarray, np.ndarray]:
    """(table, offsets) holding the half matrices of `degrees` (and of those seen before)."""
    table, offsets, have = _halves
    for n in degrees:
        if n not in have:
            return _grown(degrees)
    return table, offsets


def _grown(degrees: Sequence[int]) -> tuple[np.ndarray, np.ndarray]:
    global _halves
    with _halves_lock:
        table, offsets, have = _halves
        new = sorted(set(degrees) - have)
        if not new:
            return table, offsets
        parts = [table]
        grown_offsets = np.full(max(len(offsets), new[-1] + 1), -1, dtype=np.int64)
        grown_offsets[: len(offsets)] = offsets
        at = table.size
        for n in new:
            left, right = sub.half_matrices(n)
            grown_offsets[n] = at
            parts += [left.ravel(), right.ravel()]
            at += 2 * (n + 1) * (n + 1)
        grown_table = np.ascontiguousarray(np.concatenate(parts), dtype=float)
        _halves = (grown_table, grown_offsets, have | frozenset(new))
        return grown_table, grown_offsets


# which knobs are counts (ints), by position: certify_compiled.Settings, refine_compiled.Knobs
_SETTINGS_COUNTS = (True, True, True) + (False,) * 8
_KNOBS_COUNTS = (False,) * 10 + (True, True, True, False, False)
# the last row packed and what it was packed from, replaced as one tuple (threads)
_packed_last: list[tuple[object, object, float, float, np.ndarray]] = [
    (None, None, 0.0, 0.0, np.zeros(0))
]


def packed(box_slack: float, root_residual: float, knobs: tuple[float | int, ...]) -> np.ndarray:
    """intersect_certify.SETTINGS, knobs (intersect.SETTLE), box_slack and root_residual as
    one float row, as intersect_pairs_compiled takes them (its _settings and _knobs make the
    tuples back, every value exact: the counts are small integers). The last row is kept:
    the knobs are module constants, so a call mostly finds it."""
    settings = cert.SETTINGS
    was_settings, was_knobs, was_slack, was_residual, row = _packed_last[0]
    if (
        was_settings is settings
        and was_knobs is knobs
        and was_slack == box_slack
        and was_residual == root_residual
    ):
        return row
    for name, values, counts in (
        ("intersect_certify.SETTINGS", settings, _SETTINGS_COUNTS),
        ("the knobs (intersect.SETTLE)", knobs, _KNOBS_COUNTS),
    ):
        kinds = tuple(isinstance(v, int) for v in values)
        if kinds != counts:
            raise TypeError(
                f"{name} does not have the layout intersect_pairs_compiled reads: counts at "
                f"{[k for k, c in enumerate(counts) if c]}, got {values!r}"
            )
    row = np.array([*settings, *knobs, box_slack, root_residual], dtype=float)
    row.setflags(write=False)
    _packed_last[0] = (settings, knobs, box_slack, root_residual, row)
    return row


def pair(
    a: np.ndarray,
    b: np.ndarray,
    box_slack: float,
    root_residual: float,
    knobs: tuple[float | int, ...],
    own: bool = False,
) -> list[Hit] | None:
    """One pair (n+1, d), (m+1, d): its hits (s, t, kind code) from the certificate, or
    the careful path compiled where the certificate declines (when intersect_certify's
    USE_SETTLE is on); None where both decline. knobs: intersect.SETTLE. own: a and b are
    curves' own points, float arrays in C order (the kernels are compiled for such arrays
    read-only, intersect_subdivide.read_only: an unpickled curve's are writeable)."""
    if not own or a.flags.writeable or b.flags.writeable:
        a, b = sub.read_only(a), sub.read_only(b)
    table, offsets = _half_table((a.shape[0] - 1, b.shape[0] - 1))
    count, hits = _compiled().pair(
        a, b, packed(box_slack, root_residual, knobs), cert.USE_SETTLE, table, offsets
    )
    if count < 0:
        return None
    found: list[Hit] = hits.tolist()
    return found


def pairs(
    curves: Sequence[np.ndarray],
    first: Sequence[int],
    second: Sequence[int],
    box_slack: float,
    root_residual: float,
    knobs: tuple[float | int, ...],
) -> list[list[Hit] | None]:
    """Pair k is curves[first[k]] against curves[second[k]], every curve (n_c+1, d) of one
    dimension d >= 2: each pair's answer as `pair` gives it, all in one compiled call."""
    if not len(first):
        return []
    sizes = [c.shape[0] for c in curves]
    starts = np.zeros(len(curves) + 1, dtype=np.int64)
    np.cumsum(sizes, out=starts[1:])
    points = sub.read_only(np.concatenate(curves))
    table, offsets = _half_table(sorted({n - 1 for n in sizes}))
    counts, hits = _compiled().pairs(
        points,
        starts,
        np.asarray(first, dtype=np.int64),
        np.asarray(second, dtype=np.int64),
        packed(box_slack, root_residual, knobs),
        cert.USE_SETTLE,
        table,
        offsets,
    )
    rows = hits.tolist()
    found: list[list[Hit] | None] = []
    at = 0
    for count in counts.tolist():
        if count < 0:
            found.append(None)
        else:
            found.append(rows[at : at + count])
            at += count
    return found
