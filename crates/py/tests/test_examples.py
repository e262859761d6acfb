"""The examples run as a newcomer runs them: the notebook is executed (nbclient) from
examples/ and its optimum is the command line's, byte for byte; the OpenSeesPy-user
script runs to its end."""

import subprocess
import sys

import pytest

from conftest import ROOT, run_cli

EXAMPLES = ROOT / "examples"


def test_the_notebook_runs_and_finds_the_cli_optimum(tmp_path):
    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")
    nb = nbformat.read(EXAMPLES / "slipload-in-python.ipynb", as_version=4)
    nbclient.NotebookClient(
        nb, timeout=900, kernel_name="python3", resources={"metadata": {"path": str(EXAMPLES)}}
    ).execute()
    errors = [o for c in nb.cells if c.cell_type == "code" for o in c.outputs if o.get("output_type") == "error"]
    assert not errors, errors
    figures = [o for c in nb.cells if c.cell_type == "code" for o in c.outputs if "image/png" in o.get("data", {})]
    assert len(figures) >= 3, "displacements, hysteresis and the sweep are drawn"
    cli = tmp_path / "cli"
    printed = run_cli("optimize", "--out", cli, "--quiet").stdout
    mine = EXAMPLES / "out" / "optimize"
    for name in ["optimum.json", "design-table.json", "candidates.json"]:
        assert (mine / name).read_bytes() == (cli / name).read_bytes(), name
    # the optimum the notebook prints is the one the command line prints
    text = "".join(o.get("text", "") for c in nb.cells if c.cell_type == "code" for o in c.outputs)
    line = next(l for l in text.splitlines() if l.startswith("optimal slip loads (kN):"))
    loads = line.split(":", 1)[1].strip()
    assert f"optimal slip loads, floors 1 / 2 / 3 (kN): {loads}" in printed


def test_the_opensees_user_example_runs():
    out = subprocess.run([sys.executable, str(EXAMPLES / "own_building_and_record.py")], capture_output=True, text=True, cwd=ROOT)
    assert out.returncode == 0, out.stderr
    assert "lowest peak drift ratio" in out.stdout
