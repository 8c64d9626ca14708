"""Every record of the current run by id, for cross-references (a formula record names the
matrix records it uses; a join record the records of its curves).

The report (report.py) installs the loader of the built-in records when it is imported, so
the checkers, which sit below the report, never import it.
"""

from __future__ import annotations

from collections.abc import Callable

_INDEX: dict[str, dict] = {}
_LOADER: list[Callable[[], list[dict]]] = []


def set_loader(load: Callable[[], list[dict]]) -> None:
    """The function that loads the run's records when one is first looked up."""
    _LOADER[:] = [load]


def records_by_id() -> dict[str, dict]:
    """Every record by id (loaded on first use by the installed loader)."""
    if not _INDEX:
        if not _LOADER:
            raise RuntimeError("no records loader installed (derive/verify/report.py does)")
        _INDEX.update({r["id"]: r for r in _LOADER[0]()})
    return _INDEX


def replace(records) -> None:
    """The run's records are exactly `records` (a run over other files than the built-in)."""
    _INDEX.clear()
    _INDEX.update({r["id"]: r for r in records})
