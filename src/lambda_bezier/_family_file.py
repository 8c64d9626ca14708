"""A family definition file's [family] table, its fingerprint and the error both raise.

Standard library only: `lambda-bezier derive` reads every built-in definition through
`read_family_table`, and importing `lambda_bezier.family` for it (numpy, jsonschema, the
curve classes) cost a tenth of a `derive --check` (issue #29). `lambda_bezier.family`
re-exports all three names.
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any


class FamilyFileError(ValueError):
    """A definition or derived file that cannot be used (the message says what to run)."""


FamilyFileError.__module__ = "lambda_bezier.family"


def definition_digest(table: dict[str, Any]) -> str:
    """The fingerprint derive/families/engine.py stores (the same canonical JSON, SHA-256)."""
    import hashlib
    import json

    text = json.dumps(table, sort_keys=True, ensure_ascii=True, separators=(",", ":"))
    return hashlib.sha256(text.encode()).hexdigest()


def read_family_table(path: str | Path) -> dict[str, Any]:
    """The [family] table of a TOML file (a family file, or a records file that defines one);
    derive/families/engine.py reads definitions through this too, so both fingerprint the same
    table."""
    if sys.version_info >= (3, 11):
        import tomllib
    else:  # pragma: no cover - Python 3.10
        import tomli as tomllib

    try:
        data = tomllib.loads(Path(path).read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise FamilyFileError(f"{path}: no such file") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise FamilyFileError(f"{path}: cannot be read ({exc})") from None
    except tomllib.TOMLDecodeError as exc:
        if str(path).endswith(".json"):  # a derived document, or a curve's JSON form
            raise FamilyFileError(
                f"{path}: a JSON file, not a family definition: a family is defined by a TOML "
                "file with a [family] table (NAME.toml); NAME.derived.json is what `lambda-bezier "
                "derive --family NAME.toml` writes beside it and is found from it, so pass the "
                "TOML definition"
            ) from None
        raise FamilyFileError(f"{path}: not valid TOML: {exc}") from None
    except RecursionError:  # the decoder recurses on nested arrays and tables
        raise FamilyFileError(f"{path}: not valid TOML: nested too deeply") from None
    table = data.get("family")
    if not isinstance(table, dict):
        raise FamilyFileError(f"{path}: no [family] table (a family definition starts with one)")
    return table
