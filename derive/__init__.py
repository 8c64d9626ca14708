"""SymPy derivations of every lambda-bezier formula, emitted as Python modules into generated/.

Each formula-group module starts from its basis definition (the axiom) and exposes
``OUTPUT`` (file name in generated/) and ``render() -> str``. ``render_all`` is what
``lambda-bezier derive`` writes and ``lambda-bezier derive --check`` compares.
"""

from __future__ import annotations

import importlib

SYMPY_VERSION = "1.14.0"  # the SymPy whose printing the committed generated/ comes from


def groups() -> tuple[str, ...]:
    """The formula groups: the reference Bernstein basis, each built-in family (in the
    families' order, from derive/families/*.toml), then the groups over every family."""
    from .family_engine import builtin_families

    return ("bernstein", *(b.name for b in builtin_families()), "energy", "joins", "properties")


def _group_module(name: str):
    from .family_engine import builtin_families

    for b in builtin_families():
        if b.name == name:
            return b.module()  # the family's derivation module, or the engine's own
    return importlib.import_module(f"{__name__}.{name}")


def render_all(progress=None) -> dict[str, str]:
    from . import _emit
    from .family_engine import builtin_families

    families = {b.name: b.curve_class for b in builtin_families()}
    files = {
        "__init__.py": _emit.package_init(groups(), families),
        "_exact.py": _emit.exact_helpers(),
    }
    for name in groups():
        if progress:
            progress(name)
        module = _group_module(name)
        files[module.OUTPUT] = module.render()
    return files
