"""The content-addressed cache of `lambda-bezier derive` (derive/emit/cache.py): a hit only for
the same bytes of derive/ and the runtime, the same libraries; a damaged entry is derived
again; --no-cache and LAMBDA_BEZIER_DERIVE_CACHE=off derive afresh."""

from __future__ import annotations

import importlib
import json
import os
import shutil
import subprocess
import sys
import types
from pathlib import Path

import pytest
from conftest import ROOT

from lambda_bezier import _derive_runner

pytestmark = pytest.mark.skipif(
    not (ROOT / "derive").is_dir(), reason="needs the source checkout (derive/ and generated/)"
)

RUNTIME = Path(_derive_runner.__file__).parent


@pytest.fixture
def cache_dir(tmp_path, monkeypatch):
    where = tmp_path / "cache"
    monkeypatch.setenv("LAMBDA_BEZIER_CACHE_DIR", str(where))
    monkeypatch.delenv("LAMBDA_BEZIER_DERIVE_CACHE", raising=False)
    return where / "derive"


@pytest.fixture(scope="module")
def cache():
    return importlib.import_module(f"{_derive_runner.load_derive(ROOT).__name__}.emit.cache")


def _derive_copy(tmp_path: Path) -> Path:
    copy = tmp_path / "derive"
    shutil.copytree(ROOT / "derive", copy, ignore=shutil.ignore_patterns("__pycache__"))
    return copy


def test_key_is_the_content_not_the_place(tmp_path, cache):
    copy = _derive_copy(tmp_path)
    ours = cache.key(ROOT / "derive", RUNTIME)
    assert cache.key(copy, RUNTIME) == ours  # another checkout, the same bytes
    (copy / "formulas" / "energy.py").write_text(
        (copy / "formulas" / "energy.py").read_text() + "\n# one more line\n"
    )
    assert cache.key(copy, RUNTIME) != ours
    other = _derive_copy(tmp_path / "b")
    (other / "families" / "same_degree.toml").write_bytes(
        (other / "families" / "same_degree.toml").read_bytes() + b"\n"
    )
    assert cache.key(other, RUNTIME) != ours
    (other / "families" / "same_degree.toml").write_bytes(
        (ROOT / "derive" / "families" / "same_degree.toml").read_bytes()
    )
    (other / "families" / "new.toml").write_text("[family]\n")  # a file added
    assert cache.key(other, RUNTIME) != ours


def test_key_follows_the_libraries(cache, monkeypatch):
    before = cache.key(ROOT / "derive", RUNTIME)
    real = cache._version
    monkeypatch.setattr(cache, "_version", lambda dist: "0.0" if dist == "sympy" else real(dist))
    assert cache.key(ROOT / "derive", RUNTIME) != before
    monkeypatch.setattr(cache, "_version", real)
    monkeypatch.setenv("SYMPY_GROUND_TYPES", "python")
    assert cache.key(ROOT / "derive", RUNTIME) != before


def _fake_derive(tmp_path: Path, files: dict[str, str], calls: list[int]):
    """A derive package whose render_all counts its calls (the real emit modules, the files
    of a copy of derive/ as its sources)."""
    real = _derive_runner.load_derive(ROOT)
    copy = _derive_copy(tmp_path)

    def render_all(progress=None):
        calls.append(1)
        return dict(files)

    return types.SimpleNamespace(
        __name__=real.__name__,
        __file__=str(copy / "__init__.py"),
        SYMPY_VERSION=real.SYMPY_VERSION,
        render_all=render_all,
    ), copy


def test_second_run_reads_back_and_no_cache_derives(tmp_path, cache_dir, monkeypatch, capsys):
    files = {"a.py": "one\n", "b.py": "two\n"}
    calls: list[int] = []
    fake, copy = _fake_derive(tmp_path, files, calls)
    monkeypatch.setattr(_derive_runner, "load_derive", lambda root: fake)
    gen = tmp_path / "generated"
    gen.mkdir()
    for name, text in files.items():
        (gen / name).write_text(text)
    assert _derive_runner.run(check=True, root=tmp_path, quiet=True) == 0
    assert len(calls) == 1 and len(list(cache_dir.glob("*.json"))) == 1
    assert _derive_runner.run(check=True, root=tmp_path) == 0
    assert len(calls) == 1  # read back
    assert "derived before" in capsys.readouterr().err
    assert _derive_runner.run(check=True, root=tmp_path, quiet=True, cache=False) == 0
    assert len(calls) == 2
    monkeypatch.setenv("LAMBDA_BEZIER_DERIVE_CACHE", "off")
    assert _derive_runner.run(check=True, root=tmp_path, quiet=True) == 0
    assert len(calls) == 3
    monkeypatch.delenv("LAMBDA_BEZIER_DERIVE_CACHE")
    # a hand edit of generated/ is caught on a cache hit as on a derivation
    (gen / "a.py").write_text("edited\n")
    assert _derive_runner.run(check=True, root=tmp_path, quiet=True) == 1
    assert len(calls) == 3
    # an edit of the derivation's sources is a miss: derived again
    (copy / "emit" / "printing.py").write_text((copy / "emit" / "printing.py").read_text() + "#\n")
    assert _derive_runner.run(check=True, root=tmp_path, quiet=True) == 1
    assert len(calls) == 4


@pytest.mark.parametrize("damage", ["truncate", "edit", "other_key", "not_json"])
def test_a_damaged_entry_is_derived_again(tmp_path, cache_dir, cache, damage):
    key = cache.key(ROOT / "derive", RUNTIME)
    files = {"a.py": "one\n"}
    cache.store(key, files)
    assert cache.load(key) == files
    path = cache_dir / f"{key}.json"
    text = path.read_text()
    if damage == "truncate":
        path.write_text(text[: len(text) // 2])
    elif damage == "edit":
        path.write_text(text.replace("one", "two"))
    elif damage == "other_key":
        entry = json.loads(text)
        entry["key"] = "0" * 64
        path.write_text(json.dumps(entry))
    else:
        path.write_text("[1, 2]")
    assert cache.load(key) is None


def test_a_failed_derivation_stores_nothing(tmp_path, cache_dir, monkeypatch):
    real = _derive_runner.load_derive(ROOT)
    copy = _derive_copy(tmp_path)

    def render_all(progress=None):
        raise ArithmeticError("a check inside the derivation failed")

    fake = types.SimpleNamespace(
        __name__=real.__name__,
        __file__=str(copy / "__init__.py"),
        SYMPY_VERSION=real.SYMPY_VERSION,
        render_all=render_all,
    )
    monkeypatch.setattr(_derive_runner, "load_derive", lambda root: fake)
    (tmp_path / "generated").mkdir()
    with pytest.raises(ArithmeticError):
        _derive_runner.run(check=True, root=tmp_path, quiet=True)
    assert not cache_dir.exists() or not list(cache_dir.glob("*.json"))


def test_an_unwritable_cache_only_costs_time(tmp_path, monkeypatch, cache):
    blocker = tmp_path / "file"
    blocker.write_text("not a directory")
    monkeypatch.setenv("LAMBDA_BEZIER_CACHE_DIR", str(blocker))
    cache.store("k" * 64, {"a.py": "x"})  # no error
    assert cache.load("k" * 64) is None


def test_command_warm_run_matches_and_skips_sympy(tmp_path):
    """The real command twice: derived (and stored), then read back without importing SymPy;
    both pass --check on the checkout."""
    env = {
        **os.environ,
        "LAMBDA_BEZIER_CACHE_DIR": str(tmp_path),
        "PYTHONHASHSEED": "17",
    }
    env.pop("LAMBDA_BEZIER_DERIVE_CACHE", None)
    cold = subprocess.run(
        [sys.executable, "-m", "lambda_bezier", "derive", "--check"],
        cwd=ROOT,
        env=env,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert cold.returncode == 0, cold.stdout + cold.stderr
    assert "deriving joins" in cold.stderr
    code = (
        "import sys; from lambda_bezier.cli import main; rc = main(['derive', '--check']); "
        "print('sympy' in sys.modules); sys.exit(rc)"
    )
    warm = subprocess.run(
        [sys.executable, "-c", code],
        cwd=ROOT,
        env={**env, "PYTHONHASHSEED": "99"},
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert warm.returncode == 0, warm.stdout + warm.stderr
    assert "derived before" in warm.stderr and "deriving" not in warm.stderr.replace(
        "derived before", ""
    )
    assert warm.stdout.strip() == "False"
