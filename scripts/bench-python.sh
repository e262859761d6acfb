#!/usr/bin/env bash
# Regenerates results/performance/python.{json,txt}: what the Python package costs beside
# the command line, measured in one run (crates/py/bench/bench_python.py): simulate per
# call against `slipload simulate --repeat`, batch_designs against `slipload sweep` on the
# same designs × records, fidelity and threads, two batches from two Python threads, and
# the RSS over 10,000 simulate calls with histories. Run it on a quiet machine: the figures
# are times. It builds the release command line and installs the package the README's way
# (pip install ./crates/py) into the virtual environment scripts/test.sh uses.
# Usage: bash scripts/bench-python.sh
set -euo pipefail
cd "$(dirname "$0")/.."
python=${PYTHON:-python3}
venv=target/py-venv
cargo build --release -p slipload --quiet
if [ ! -x "$venv/bin/python" ]; then
    "$python" -m venv "$venv"
fi
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check "maturin>=1.9.4,<2" numpy
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check ./crates/py
out=results/performance
SLIPLOAD_BIN="$PWD/target/release/slipload" "$venv/bin/python" crates/py/bench/bench_python.py "$out"
{ echo; echo "machine: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) CPUs; load average before: $(cut -d' ' -f1-3 /proc/loadavg)"; } >> "$out/python.txt"
