"""SymPy derivations of every lambda-bezier formula, emitted as Python modules into generated/.

Each formula-group module starts from its basis definition (the axiom) and exposes
``OUTPUT`` (file name in generated/) and ``render() -> str``. ``render_all`` is what
``lambda-bezier derive`` writes and ``lambda-bezier derive --check`` compares.
"""

from __future__ import annotations

import importlib

# Order matters only for readability of progress output; files are independent.
GROUPS = ("bernstein", "same_degree", "bernstein_like", "energy", "joins", "properties")
SYMPY_VERSION = "1.14.0"  # the SymPy whose printing the committed generated/ comes from


def render_all(progress=None) -> dict[str, str]:
    from . import _emit

    files = {"__init__.py": _emit.package_init(GROUPS), "_exact.py": _emit.exact_helpers()}
    for name in GROUPS:
        if progress:
            progress(name)
        module = importlib.import_module(f"{__name__}.{name}")
        files[module.OUTPUT] = module.render()
    return files
