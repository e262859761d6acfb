#!/usr/bin/env bash
# Regenerates results/pareto/pymoo.{json,txt}: slipload's front search against pymoo's
# NSGA-II driving slipload's own evaluations (through the Python package) at 500, 1000
# and 2000 simulations, 5 seeds each (scripts/pareto_pymoo.py says how). Installs the
# package the README's way and pymoo into the virtual environment scripts/test.sh uses.
# Needs results/pareto/grid-check.json (scripts/pareto.sh) for the reference point.
# Usage: bash scripts/pareto-pymoo.sh   (a few minutes)
set -euo pipefail
cd "$(dirname "$0")/.."
python=${PYTHON:-python3}
venv=target/py-venv
if [ ! -x "$venv/bin/python" ]; then
    "$python" -m venv "$venv"
fi
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check "maturin>=1.9.4,<2" numpy "pymoo==0.6.2"
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check ./crates/py
"$venv/bin/python" scripts/pareto_pymoo.py results/pareto
