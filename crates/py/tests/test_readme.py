"""The README's Python example runs as written (in a scratch folder where configs/ and
records/ are the repository's), and the optimum it computes is the command line's."""

import json
import os
import re

from conftest import ROOT, run_cli


def python_blocks(text):
    return re.findall(r"```python\n(.*?)```", text, re.S)


def test_the_readme_python_example_runs(tmp_path, capsys):
    blocks = python_blocks((ROOT / "README.md").read_text())
    assert blocks, "the README has a Python example"
    for name in ["configs", "records"]:
        os.symlink(ROOT / name, tmp_path / name)
    cwd = os.getcwd()
    os.chdir(tmp_path)
    try:
        for code in blocks:
            exec(compile(code, "README.md", "exec"), {"__name__": "readme"})
    finally:
        os.chdir(cwd)
    mine = json.loads((tmp_path / "out" / "optimize-py" / "optimum.json").read_text())
    run_cli("optimize", "--out", tmp_path / "cli", "--quiet")
    cli = json.loads((tmp_path / "cli" / "optimum.json").read_text())
    assert mine == cli
