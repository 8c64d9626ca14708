"""Issue 32: every page's and tutorial's examples run from an installed wheel, in an empty
directory (not the checkout): the README's and docs/*.md's doctest blocks, the `lambda-bezier`
lines of their bash and console blocks (where safe), and the tutorials' scripts.

One wheel per session (`pip wheel . --no-deps`), installed with `--no-deps` into a throwaway
venv; the dependencies come from this test run's own environment (a .pth line naming its
site-packages: in CI that is a plain venv, whose packages `--system-site-packages` would not
reach). The tests check that `lambda_bezier` is imported from that venv, not from the checkout.
"""

from __future__ import annotations

import json
import os
import re
import shlex
import subprocess
import sys
import sysconfig
import venv
from pathlib import Path

import pytest
from conftest import ROOT

pytestmark = [
    pytest.mark.wheel,
    pytest.mark.skipif(
        not (ROOT / "pyproject.toml").is_file(), reason="builds the wheel from the checkout"
    ),
]

PAGES = [
    ROOT / "README.md",
    *sorted(p for p in (ROOT / "docs").rglob("*.md") if "_build" not in p.parts),
]
TUTORIALS = sorted((ROOT / "docs" / "tutorials").glob("*.py"))

# `lambda-bezier` lines the docs show that cannot run from an installation in an empty
# directory, each with the reason; every other line is run
NOT_RUNNABLE = {
    "lambda-bezier derive": "rewrites a source checkout's generated/ (refused outside one)",
    "--errata": "rewrites a source checkout's ERRATA.md",
    "my_paper.toml": "a placeholder for the reader's own records file",
    "my_family.toml": "a placeholder for the reader's own family file",
    "CURVE.json": "a placeholder for the reader's curve",
}


def _clean_env(**extra: str) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME")}
    # the wheel's examples on the numpy fallbacks: its numba kernels would compile anew in
    # the throwaway venv (minutes of CPU, nothing the checkout's own doctests do not run
    # compiled already), and the fallbacks' answers are the documented ones too
    return {**env, "MPLBACKEND": "Agg", "LAMBDA_BEZIER_NO_NUMBA": "1", **extra}


@pytest.fixture(scope="session")
def installed(tmp_path_factory) -> Path:
    """The bin/ directory of a throwaway venv with the wheel of this checkout installed."""
    base = tmp_path_factory.mktemp("wheel")
    dist = base / "dist"
    build = subprocess.run(
        [sys.executable, "-m", "pip", "wheel", str(ROOT), "--no-deps", "-q", "-w", str(dist)],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert build.returncode == 0, build.stdout[-2000:] + build.stderr[-4000:]
    (wheel,) = dist.glob("lambda_bezier-*.whl")
    env_dir = base / "venv"
    venv.EnvBuilder(system_site_packages=True, with_pip=False).create(env_dir)
    python = env_dir / "bin" / "python"
    site = subprocess.run(
        [str(python), "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
        capture_output=True,
        text=True,
        check=True,
    ).stdout.strip()
    install = subprocess.run(
        [
            sys.executable,
            "-m",
            "pip",
            "--python",
            str(python),
            "install",
            "--no-deps",
            "-q",
            str(wheel),
        ],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert install.returncode == 0, install.stdout[-2000:] + install.stderr[-4000:]
    # Only now the dependencies: this run's site-packages, appended after the venv's own, so
    # the wheel's lambda_bezier comes first (a path line does not run the .pth files of an
    # editable install found there). Written before the install, they would hold this run's
    # own lambda-bezier (CI installs it non-editable), and pip would skip the wheel as
    # already installed.
    ours = {sysconfig.get_paths()[k] for k in ("purelib", "platlib")}
    (Path(site) / "_test_dependencies.pth").write_text("\n".join(sorted(ours)) + "\n")
    where = subprocess.run(
        [str(python), "-c", "import lambda_bezier; print(lambda_bezier.__file__)"],
        cwd=base,
        env=_clean_env(),
        capture_output=True,
        text=True,
        check=True,
    ).stdout.strip()
    assert Path(where).is_relative_to(env_dir), f"lambda_bezier imported from {where}"
    return env_dir / "bin"


_DOCTEST_SCRIPT = """
import doctest, io, json, sys, contextlib
out = {}
for page in sys.argv[1:]:
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        r = doctest.testfile(page, module_relative=False,
                             optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    out[page] = [r.attempted, r.failed, buf.getvalue()[-6000:]]
print(json.dumps(out))
"""


@pytest.fixture(scope="session")
def doctest_results(installed, tmp_path_factory) -> dict[str, list]:
    """Every page's doctests, run by the installed package in one empty directory each run."""
    proc = subprocess.run(
        [str(installed / "python"), "-c", _DOCTEST_SCRIPT, *map(str, PAGES)],
        cwd=tmp_path_factory.mktemp("empty"),
        env=_clean_env(),
        capture_output=True,
        text=True,
        timeout=900,
    )
    assert proc.returncode == 0, proc.stderr[-4000:]
    return json.loads(proc.stdout.splitlines()[-1])


@pytest.mark.parametrize("page", PAGES, ids=[p.relative_to(ROOT).as_posix() for p in PAGES])
def test_page_doctests_run_from_the_wheel(page, doctest_results):
    attempted, failed, report = doctest_results[str(page)]
    assert failed == 0, report


def test_the_pages_have_doctests(doctest_results):
    """The run above saw the examples (a broken fence would pass it vacuously)."""
    ran = {Path(p).relative_to(ROOT).as_posix() for p, r in doctest_results.items() if r[0]}
    assert {"README.md", "docs/guide/own-family.md", "docs/guide/geometry.md"} <= ran


def _command_lines(page: Path) -> list[str]:
    lines = []
    for lang, body in re.findall(r"```(\w*)\n(.*?)```", page.read_text(encoding="utf-8"), re.S):
        if lang not in ("bash", "console"):
            continue
        for line in body.splitlines():
            line = line.removeprefix("$ ").split("  #")[0].strip()
            if line.startswith("lambda-bezier "):
                lines.append(line)
    return lines


def _runnable(line: str) -> bool:
    if line.startswith("lambda-bezier derive") and "--family" not in line:
        return line.endswith("--check")  # compares the installed copy outside a checkout
    return not any(key in line for key in NOT_RUNNABLE if key != "lambda-bezier derive")


_PASSED: set[str] = set()  # command lines that ran, with exit 0, in this session
COMMAND_PAGES = [p for p in PAGES if any(map(_runnable, _command_lines(p)))]


@pytest.mark.parametrize(
    "page", COMMAND_PAGES, ids=[p.relative_to(ROOT).as_posix() for p in COMMAND_PAGES]
)
def test_page_commands_run_from_the_wheel(page, installed, tmp_path):
    """A page's `lambda-bezier` lines, in order, in one empty directory (a line may use what
    an earlier one made, as `example family DIR` then `derive --family DIR/...`)."""
    lines = [line for line in _command_lines(page) if _runnable(line)]
    for line in lines:
        argv = shlex.split(line)
        uses_files = any("/" in a or a.endswith((".toml", ".json")) for a in argv)
        if line in _PASSED and not uses_files:
            continue  # the same command on another page, already run from an empty directory
        proc = subprocess.run(
            [str(installed / "lambda-bezier"), *argv[1:]],
            cwd=tmp_path,
            env=_clean_env(),
            capture_output=True,
            text=True,
            timeout=600,
        )
        assert proc.returncode == 0, f"{line}\n{proc.stdout[-2000:]}\n{proc.stderr[-3000:]}"
        _PASSED.add(line)


@pytest.mark.parametrize("tutorial", TUTORIALS, ids=[p.stem for p in TUTORIALS])
def test_tutorial_runs_from_the_wheel(tutorial, installed, tmp_path):
    figures = tmp_path / "figures"
    work = tmp_path / "work"
    work.mkdir()
    proc = subprocess.run(
        [str(installed / "python"), str(tutorial.resolve())],
        cwd=work,
        env=_clean_env(LAMBDA_BEZIER_FIGURES=str(figures)),
        capture_output=True,
        text=True,
        timeout=900,
    )
    assert proc.returncode == 0, proc.stdout[-2000:] + proc.stderr[-4000:]
    assert list(figures.glob("*.png")), "the tutorial wrote no figure"
