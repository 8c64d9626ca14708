"""`derive` writes generated/ atomically: runs killed at injected points, concurrent runs, the
recovery the next run and the importer perform, the directory's mode, an unwritable target."""

from __future__ import annotations

import os
import shutil
import signal
import subprocess
import sys
import textwrap
import types
from pathlib import Path

import pytest
from conftest import ROOT

from lambda_bezier import _derive_runner, _generated_dir

OLD = {"a.py": "old a\n", "b.py": "old b\n", "c.py": "old c\n"}
NEW = {"a.py": "new a\n", "b.py": "new b\n", "c.py": "new c\n", "d.py": "new d\n"}

# Each injection point kills the writing process (SIGKILL: no cleanup handler runs) at one
# moment of replace_tree. `exchange` says whether the atomic swap is available.
KILL = {
    "mid-write": (True, "fsync", 2),  # the second file's flush
    "before-swap": (True, "exchange", 1),
    "after-swap": (True, "rmtree", 1),  # the old tree, now in .generated.new-*, not removed
    "fallback-mid-write": (False, "fsync", 3),
    "fallback-between-renames": (False, "replace", 2),  # old moved aside, new not yet in
    "fallback-after-renames": (False, "rmtree", 1),
}

CHILD = textwrap.dedent(
    """
    import os, shutil, signal, sys
    from pathlib import Path
    from lambda_bezier import _generated_dir as gd

    exchange, where, nth = sys.argv[2] == "1", sys.argv[3], int(sys.argv[4])
    calls = {"n": 0}

    def hit():
        calls["n"] += 1
        if calls["n"] == nth:
            os.kill(os.getpid(), signal.SIGKILL)

    real_fsync, real_replace, real_rmtree, real_exchange = (
        os.fsync, os.replace, shutil.rmtree, gd._exchange)

    def fsync(fd):
        if where == "fsync":
            hit()
        real_fsync(fd)

    def replace(a, b):
        if where == "replace":
            hit()
        real_replace(a, b)

    def rmtree(p, *a, **k):
        if where == "rmtree":
            hit()
        real_rmtree(p, *a, **k)

    def exch(a, b):
        if where == "exchange":
            hit()
        return real_exchange(a, b) if exchange else False

    os.fsync, os.replace, shutil.rmtree, gd._exchange = fsync, replace, rmtree, exch
    files = {"a.py": "new a\\n", "b.py": "new b\\n", "c.py": "new c\\n", "d.py": "new d\\n"}
    gd.replace_tree(files, Path(sys.argv[1]))
    print("finished")
    """
)


def tree(directory: Path) -> dict[str, str]:
    return {p.name: p.read_text() for p in directory.iterdir()}


def make(directory: Path, files: dict[str, str]) -> None:
    directory.mkdir()
    for name, text in files.items():
        (directory / name).write_text(text)


@pytest.mark.parametrize("point", list(KILL))
def test_killed_write_leaves_old_or_new_and_is_recovered(tmp_path, point):
    exchange, where, nth = KILL[point]
    gen = tmp_path / "generated"
    make(gen, OLD)
    proc = subprocess.run(
        [sys.executable, "-c", CHILD, str(gen), "1" if exchange else "0", where, str(nth)],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert proc.returncode == -signal.SIGKILL, proc.stdout + proc.stderr
    if point == "fallback-between-renames":
        # the one non-atomic moment of the fallback: generated/ is aside, and recoverable
        assert not gen.exists() and tree(tmp_path / ".generated.old") == OLD
        assert _generated_dir.recover(gen)[0].startswith("restored")
    assert tree(gen) in (OLD, NEW)  # never a mixture, never half a file
    # the next run cleans up whatever the killed one left, and writes
    messages: list[str] = []
    _generated_dir.replace_tree(NEW, gen, messages.append)
    assert tree(gen) == NEW
    assert sorted(p.name for p in tmp_path.iterdir()) == ["generated"], messages


def test_swap_is_a_single_exchange_here(tmp_path):
    """On this Linux file system the exchange is available, so the atomic path is what runs."""
    a, b = tmp_path / "a", tmp_path / "b"
    make(a, {"x": "1"})
    make(b, {"y": "2"})
    assert _generated_dir._exchange(a, b)
    assert tree(a) == {"y": "2"} and tree(b) == {"x": "1"}


def test_mode_follows_the_umask_not_mkdtemp(tmp_path):
    gen = tmp_path / "generated"
    make(gen, OLD)
    os.chmod(gen, 0o755)
    old_mask = os.umask(0o022)
    try:
        _generated_dir.replace_tree(NEW, gen)
    finally:
        os.umask(old_mask)
    assert gen.stat().st_mode & 0o777 == 0o755


def test_concurrent_writers_are_serialised(tmp_path):
    gen = tmp_path / "generated"
    make(gen, OLD)
    code = textwrap.dedent(
        """
        import sys
        from pathlib import Path
        from lambda_bezier._generated_dir import replace_tree
        tag = sys.argv[2]
        for i in range(15):
            replace_tree({f"{n}.py": f"{tag} {i} {n}\\n" for n in "abcdef"}, Path(sys.argv[1]),
                         lambda m: print(m, flush=True))
        """
    )
    procs = [
        subprocess.Popen(
            [sys.executable, "-c", code, str(gen), tag],
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
        for tag in ("x", "y", "z")
    ]
    outs = [p.communicate(timeout=120) for p in procs]
    assert all(p.returncode == 0 for p in procs), outs
    final = tree(gen)
    assert len({text.rsplit(" ", 1)[0] for text in final.values()}) == 1  # one writer's tree
    assert sorted(p.name for p in tmp_path.iterdir()) == ["generated"]  # lock file removed


def test_unwritable_generated_is_a_clear_error(tmp_path, monkeypatch, capsys):
    """The runner reports an OSError from the write (here a read-only generated/, which root
    would not notice, so os.access is told to say so) in one line and leaves the tree."""
    gen = tmp_path / "generated"
    make(gen, OLD)
    derive_pkg = _derive_runner.load_derive(ROOT)

    fake = types.SimpleNamespace(
        __name__=derive_pkg.__name__,  # its _emit is the real one
        SYMPY_VERSION=derive_pkg.SYMPY_VERSION,
        render_all=lambda progress=None: NEW,
    )
    monkeypatch.setattr(_derive_runner, "load_derive", lambda root: fake)
    monkeypatch.setattr(_generated_dir.os, "access", lambda path, mode: False)
    assert _derive_runner.run(check=False, root=tmp_path, quiet=True) == 1
    err = capsys.readouterr().err
    assert "cannot write" in err and "read-only" in err and "Traceback" not in err
    assert tree(gen) == OLD


def test_check_restores_a_lone_backup_and_names_a_missing_directory(tmp_path, capsys):
    gen = tmp_path / "generated"
    make(tmp_path / ".generated.old", OLD)
    make(tmp_path / ".generated.new-abc", {"a.py": "half"})
    said: list[str] = []
    assert _derive_runner._recover_before_check(gen, said.append) is None
    assert tree(gen) == OLD and sorted(p.name for p in tmp_path.iterdir()) == ["generated"]
    assert any("interrupted" in m for m in said)
    shutil.rmtree(gen)
    message = _derive_runner._recover_before_check(gen, said.append)
    assert message is not None and "does not exist" in message


def _installed_copy(tmp_path: Path) -> Path:
    """lambda_bezier laid out as a wheel installs it (lambda_bezier/_generated)."""
    site = tmp_path / "site"
    shutil.copytree(
        ROOT / "src" / "lambda_bezier",
        site / "lambda_bezier",
        ignore=shutil.ignore_patterns("__pycache__"),
    )
    return site


def _run_installed(site: Path) -> subprocess.CompletedProcess:
    code = (
        "import sys\n"  # an editable install's finder would otherwise win over PYTHONPATH
        "sys.meta_path[:] = [f for f in sys.meta_path if 'editable' not in repr(f).lower()]\n"
        "import lambda_bezier as lb\n"
        f"assert lb.__file__.startswith({str(site)!r}), lb.__file__\n"
        "print(lb.BezierCurve([(0, 0), (2, 2)]).evaluate(0.5))"
    )
    env = {**os.environ, "PYTHONPATH": str(site)}
    return subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=60
    )


@pytest.mark.skipif(not (ROOT / "generated").is_dir(), reason="needs the checkout")
def test_importer_restores_generated_left_aside(tmp_path):
    site = _installed_copy(tmp_path)
    shutil.copytree(
        ROOT / "generated",
        site / "lambda_bezier" / "._generated.old",
        ignore=shutil.ignore_patterns("__pycache__"),
    )
    proc = _run_installed(site)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.strip() == "[1. 1.]"
    assert (site / "lambda_bezier" / "_generated").is_dir()
    assert not (site / "lambda_bezier" / "._generated.old").exists()


def test_importer_names_missing_generated(tmp_path):
    proc = _run_installed(_installed_copy(tmp_path))
    assert proc.returncode == 1
    assert "generated modules are missing" in proc.stderr
    assert proc.stderr.strip().splitlines()[-1].startswith("ImportError")
