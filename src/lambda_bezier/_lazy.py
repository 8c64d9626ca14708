"""Generated modules are imported on first use, so `import lambda_bezier` stays light."""

from __future__ import annotations

import importlib
from collections.abc import Callable
from types import ModuleType
from typing import TYPE_CHECKING, Any, TypeAlias

if TYPE_CHECKING:
    from ._family_document import FamilyData


_PACKAGE = f"{__package__}._generated"


def _import_generated(name: str) -> ModuleType:
    """lambda_bezier._generated or one of its modules, restoring generated/ first when an
    interrupted `lambda-bezier derive` left it aside."""
    try:
        return importlib.import_module(name)
    except ModuleNotFoundError as exc:
        if exc.name not in (_PACKAGE, name):
            raise
    # generated/ is gone: an interrupted `lambda-bezier derive` may have left it aside
    from pathlib import Path

    from ._generated_dir import recover_for_import

    recover_for_import(Path(__file__).parent)  # or an ImportError saying what happened
    importlib.invalidate_caches()
    return importlib.import_module(name)


def builtin_families() -> dict[str, str]:
    """The built-in shape-parameter families, in order, as generated/__init__.py lists them
    (emitted from derive/families/*.toml): family name (= its generated module) -> the name
    of its curve class. Reads only that small module: no tables, no numpy."""
    families: dict[str, str] = _import_generated(_PACKAGE).FAMILIES
    return dict(families)


class generated:  # noqa: N801  (reads as a module reference at the use sites)
    """Stands for lambda_bezier._generated.<name>; attribute access imports it once."""

    def __init__(self, name: str) -> None:
        self._name = f"{_PACKAGE}.{name}"
        self._module: ModuleType | None = None

    def module(self) -> ModuleType:
        # kept after the first import: each table read (several per curve constructed) would
        # otherwise run importlib.import_module (issue #29). sys.modules keeps the module
        # object anyway, so this is the object a fresh import would return
        if self._module is None:
            self._module = _import_generated(self._name)
        return self._module

    def __getattr__(self, attr: str) -> Any:  # a generated table: its type is the module's
        return getattr(self.module(), attr)

    def __repr__(self) -> str:
        return f"<lazy {self._name}>"


# where a family's tables live: a generated module (imported on first use) or the data of a
# user's family (family.py); each has DEGREES, LAMBDA_RANGE, POWER, CENTRED, BERNSTEIN, ...
TableSource: TypeAlias = "ModuleType | generated | FamilyData"


class deferred:  # noqa: N801  (reads as a module at the use sites)
    """Stands for a module that `load` imports on the first attribute access (with an
    ordinary import statement, which the layer checks see). Each attribute read is then kept
    on this object, so a curve method bound to a lower module's function pays one attribute
    lookup per call, not the import machinery (issue #29), and `import lambda_bezier` pays
    nothing for algorithms it has not used."""

    def __init__(self, load: Callable[[], ModuleType]) -> None:
        self._load = load

    def __getattr__(self, attr: str) -> Any:
        value = getattr(self._load(), attr)
        setattr(self, attr, value)  # bound once: later reads skip __getattr__
        return value
