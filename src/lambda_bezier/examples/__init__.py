"""Example files shipped with the package, usable anywhere (no source checkout needed).

- ``nouri_saeidian.toml``: a family of the user's own (Nouri and Saeidian's enhanced Bernstein
  basis, arXiv:2405.07086) with records about it; ``nouri_saeidian.derived.json`` is what
  ``lambda-bezier derive --family`` makes of it, so ``load_family`` works at once.
- ``han_trig_cubic.toml`` (the cubic trigonometric basis of Han, Ma and Huang, two
  parameters on [0, pi/2]) and ``two_shape_cubic.toml`` (a polynomial cubic with two
  parameters), each with its ``.derived.json``: families as issue #30 writes them.
- ``c_bezier_cubic.toml`` (Zhang's C-Bezier cubic on [0, alpha]: the parameter is the length
  of the domain and sits inside sin and cos), with its ``.derived.json``.
- ``c_bezier_orders.toml`` (Chen and Wang's C-Bezier bases of degrees 2 and 3 from the
  order-2 trigonometric basis by an integral recursion), with its ``.derived.json``.
- ``user_paper.toml``: a records file about the built-in families, with true and
  deliberately misprinted records.

``path(name)`` gives a file's path (read it, or pass it to ``load_family``); ``copy(kind,
directory)``, also ``lambda-bezier example family|records DIR``, copies the files out, e.g.
to edit them or to run ``lambda-bezier derive --family`` on them (which refuses to write into
the installed package).

>>> from lambda_bezier import examples
>>> examples.names()
('c_bezier_cubic.derived.json', 'c_bezier_cubic.toml', 'c_bezier_orders.derived.json',
 'c_bezier_orders.toml', 'han_trig_cubic.derived.json', 'han_trig_cubic.toml',
 'nouri_saeidian.derived.json', 'nouri_saeidian.toml', 'two_shape_cubic.derived.json',
 'two_shape_cubic.toml', 'user_paper.toml')
>>> examples.path("nouri_saeidian.toml").name
'nouri_saeidian.toml'
"""

from __future__ import annotations

import shutil
from pathlib import Path

_HERE = Path(__file__).resolve().parent

# what `lambda-bezier example KIND DIR` copies
KINDS: dict[str, tuple[str, ...]] = {
    "family": ("nouri_saeidian.toml", "nouri_saeidian.derived.json"),
    "records": ("user_paper.toml",),
}


def names() -> tuple[str, ...]:
    """The example files, by name."""
    return tuple(sorted(p.name for p in _HERE.iterdir() if p.suffix in (".toml", ".json")))


def path(name: str) -> Path:
    """The installed path of the example file `name` (one of names())."""
    if not isinstance(name, str):
        raise TypeError(f"name must be a file name (str), got {type(name).__name__}")
    if name not in names():
        raise ValueError(f"name must be one of {', '.join(names())}, got {name!r}")
    return _HERE / name


def copy(kind: str, directory: str | Path) -> list[Path]:
    """Copy the example files of `kind` ("family" or "records") into `directory` (created if
    missing); an existing file of the same name is not overwritten (ValueError)."""
    if kind not in KINDS:
        raise ValueError(f"kind must be one of {', '.join(KINDS)}, got {kind!r}")
    target = Path(directory)
    if target.exists() and not target.is_dir():
        raise ValueError(f"directory: {target} exists and is not a directory")
    clashes = [target / n for n in KINDS[kind] if (target / n).exists()]
    if clashes:
        raise ValueError(f"directory: {', '.join(map(str, clashes))} exists; not overwritten")
    target.mkdir(parents=True, exist_ok=True)
    out = []
    for name in KINDS[kind]:
        shutil.copyfile(path(name), target / name)
        out.append(target / name)
    return out
