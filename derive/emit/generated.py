"""generated/ as a whole: the formula groups in order, each printed by its emit module."""

from __future__ import annotations

from collections.abc import Callable

from ..families.registry import builtin_families
from . import bernstein, energy, families, joins, printing, properties, surface_energy, workers

# The groups over every family, after the reference basis and the built-in families.
_SHARED = {
    "energy": energy,
    "joins": joins,
    "properties": properties,
    "surface_energy": surface_energy,
}


def groups() -> tuple[str, ...]:
    """The formula groups: the reference Bernstein basis, each built-in family (in the
    families' order, from derive/families/*.toml), then the groups over every family."""
    return ("bernstein", *(b.name for b in builtin_families()), *_SHARED)


def _renderer(name: str) -> tuple[str, Callable[[], str]]:
    """(file name in generated/, the function printing it) of one group."""
    if name == "bernstein":
        return bernstein.OUTPUT, bernstein.render
    for b in builtin_families():
        if b.name == name:
            module = b.module()  # the family's derivation module, or the engine's own
            return module.OUTPUT, lambda module=module: families.render(module.module_data())
    return _SHARED[name].OUTPUT, _SHARED[name].render


def render_all(progress: Callable[[str], object] | None = None) -> dict[str, str]:
    """{file name: text} of every file of generated/."""
    curve_classes = {b.name: b.curve_class for b in builtin_families()}
    files = {
        "__init__.py": printing.package_init(groups(), curve_classes),
        "_exact.py": printing.exact_helpers(),
    }
    names = groups()
    texts = workers.render_groups(
        names, lambda name: _renderer(name)[1](), progress, joins.shared_inputs
    )
    for name in names:  # in the groups' order, as a serial run adds them
        files[_renderer(name)[0]] = texts[name]
    return files
