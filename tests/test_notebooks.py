"""Every notebook (jupytext percent scripts in notebooks/) runs top to bottom and writes its
figures; the notebooks assert the facts they show, so a regression fails here."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest
from conftest import ROOT

NOTEBOOKS = sorted((ROOT / "notebooks").glob("*.py")) if (ROOT / "notebooks").is_dir() else []


@pytest.mark.skipif(not NOTEBOOKS, reason="needs the checkout's notebooks/")
@pytest.mark.parametrize("notebook", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
def test_notebook_runs(notebook, tmp_path):
    env = {**os.environ, "MPLBACKEND": "Agg", "LAMBDA_BEZIER_FIGURES": str(tmp_path)}
    proc = subprocess.run(
        [sys.executable, str(notebook)],
        cwd=notebook.parent,
        env=env,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert proc.returncode == 0, proc.stdout[-2000:] + proc.stderr[-4000:]
    assert list(tmp_path.glob("*.png")), "the notebook wrote no figure"
