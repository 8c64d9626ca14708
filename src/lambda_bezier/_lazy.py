"""Generated modules are imported on first use, so `import lambda_bezier` stays light."""

from __future__ import annotations

import importlib
from types import ModuleType


class generated:  # noqa: N801  (reads as a module reference at the use sites)
    """Stands for lambda_bezier._generated.<name>; attribute access imports it once."""

    def __init__(self, name: str) -> None:
        self._name = f"{__package__}._generated.{name}"

    def module(self) -> ModuleType:
        return importlib.import_module(self._name)

    def __getattr__(self, attr: str):
        return getattr(self.module(), attr)

    def __repr__(self) -> str:
        return f"<lazy {self._name}>"
