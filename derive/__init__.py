"""SymPy derivations of every lambda-bezier formula, emitted as Python modules into generated/.

Layers, top to bottom (imports only go downward; tests/test_layers.py and import-linter
check it): emit | verify, formulas, families, algebra | grammar. See
docs/guide/architecture.md. ``render_all`` is what ``lambda-bezier derive`` writes and
``lambda-bezier derive --check`` compares.
"""

from __future__ import annotations

from collections.abc import Callable

SYMPY_VERSION = "1.14.0"  # the SymPy whose printing the committed generated/ comes from


# emit is imported when asked for: `lambda-bezier verify` loads this package too, and needs
# none of the emitters (nor the formulas they import).


def groups() -> tuple[str, ...]:
    """The formula groups, in the order generated/ lists them (derive/emit/generated.py)."""
    from .emit import generated

    return generated.groups()


def render_all(progress: Callable[[str], object] | None = None) -> dict[str, str]:
    """{file name: text} of every file of generated/ (derive/emit/generated.py)."""
    from .emit import generated

    return generated.render_all(progress)
