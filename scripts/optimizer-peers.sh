#!/usr/bin/env bash
# CMA-ES (pycma), pymoo's GA and nevergrad's NGOpt against the model refiner on one of the
# optimizer benchmark's cases at equal simulations (scripts/optimizer_peers.py says how);
# needs the case's results/optimizer/<case>.json (scripts/optimizer-bench.sh). Installs the
# Python package the README's way into target/py-venv with cma, pymoo and nevergrad from
# the package index. Writes results/optimizer/peers.{json,md} (ten) or
# peers-<case>.{json,md}. Usage: scripts/optimizer-peers.sh [ten|twenty|forty]
# (default ten; about 12, 20 and 60 min on 2 cores).
set -euo pipefail
cd "$(dirname "$0")/.."
venv=target/py-venv
if [ ! -x "$venv/bin/python" ]; then
    python3 -m venv "$venv"
fi
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check "maturin>=1.9.4,<2" numpy cma pymoo nevergrad
"$venv/bin/python" -c "import slipload" 2>/dev/null \
    || "$venv/bin/python" -m pip install --quiet --disable-pip-version-check ./crates/py
exec "$venv/bin/python" scripts/optimizer_peers.py "${1:-ten}"
