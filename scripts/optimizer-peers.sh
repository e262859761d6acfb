#!/usr/bin/env bash
# CMA-ES (pycma) and pymoo's GA against the model refiner on the ten-storey check example
# at equal simulations (scripts/optimizer_peers.py says how); needs
# results/optimizer/ten-story-check.json (scripts/optimizer-bench.sh). Installs the Python
# package the README's way into target/py-venv with cma and pymoo from the package index.
# Writes results/optimizer/peers.{json,md}. Usage: scripts/optimizer-peers.sh (about 8 min).
set -euo pipefail
cd "$(dirname "$0")/.."
venv=target/py-venv
if [ ! -x "$venv/bin/python" ]; then
    python3 -m venv "$venv"
fi
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check "maturin>=1.9.4,<2" numpy cma pymoo
"$venv/bin/python" -c "import slipload" 2>/dev/null \
    || "$venv/bin/python" -m pip install --quiet --disable-pip-version-check ./crates/py
exec "$venv/bin/python" scripts/optimizer_peers.py
