#!/usr/bin/env bash
# The README's test command. On a fresh machine with only Rust installed it first installs
# what the tests need, then runs every test of the workspace:
#   - DejaVu Sans (PNG figures render their text with it; Debian's fonts-dejavu-core),
#   - Debian's chromium, and Node.js with npm when missing (the report test loads a page in
#     a real headless browser),
#   - the check script's npm packages (`npm ci` in scripts/check-report, from its lock file),
#   - for the Python package's tests: a virtual environment it creates (target/py-venv)
#     with maturin, pytest, numpy, pandas, matplotlib, nbclient, ipykernel, tqdm and
#     openseespy (which runs the scripts `slipload opensees` writes) from the package index,
#     into which it installs the package the README's way (`pip install ./crates/py`, built
#     from this checkout).
# Installing needs root or sudo and Debian's apt-get; without them it stops and says what
# to install. Arguments are passed to `cargo test` (e.g. `scripts/test.sh -p slipload-sim`).
# Usage: bash scripts/test.sh   (from anywhere)
set -euo pipefail
cd "$(dirname "$0")/.."

if ! command -v cargo >/dev/null 2>&1; then
    echo "scripts/test.sh: cargo is required (the Rust toolchain, 1.89 or newer)" >&2
    exit 1
fi
if [ ! -f records/index.csv ]; then
    echo "scripts/test.sh: records/ is incomplete: the tests read the repository's earthquake records by path" >&2
    exit 1
fi

# Debian packages still missing, installed in one apt-get call.
pkgs=()
if [ ! -f /usr/share/fonts/truetype/dejavu/DejaVuSans.ttf ] && [ -z "${SLIPLOAD_FONT:-}" ]; then
    pkgs+=(fonts-dejavu-core)
fi
if [ ! -x "${CHROMIUM:-/usr/bin/chromium}" ]; then
    pkgs+=(chromium)
fi
if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
    pkgs+=(nodejs npm)
fi
python=${PYTHON:-python3}
if ! command -v "$python" >/dev/null 2>&1; then
    pkgs+=(python3 python3-venv)
elif ! "$python" -c "import venv, ensurepip" >/dev/null 2>&1; then
    pkgs+=(python3-venv)
fi
if [ ${#pkgs[@]} -gt 0 ]; then
    if [ "$(id -u)" -eq 0 ]; then
        as_root=()
    elif command -v sudo >/dev/null 2>&1; then
        as_root=(sudo)
    else
        echo "scripts/test.sh: missing ${pkgs[*]}; install them (apt-get install -y ${pkgs[*]}) or run as root" >&2
        exit 1
    fi
    if ! command -v apt-get >/dev/null 2>&1; then
        echo "scripts/test.sh: missing ${pkgs[*]} and no apt-get to install them with" >&2
        exit 1
    fi
    echo "== installing ${pkgs[*]}" >&2
    "${as_root[@]}" apt-get update -qq
    DEBIAN_FRONTEND=noninteractive "${as_root[@]}" apt-get install -y -qq --no-install-recommends "${pkgs[@]}" >/dev/null
fi

# The browser check's packages, exactly as locked: installed when missing or when the
# lock file is newer than the installed tree.
check=scripts/check-report
if [ ! -d "$check/node_modules/playwright-core" ] \
    || [ "$check/package-lock.json" -nt "$check/node_modules/.package-lock.json" ]; then
    echo "== npm ci in $check" >&2
    (cd "$check" && npm ci --no-audit --no-fund --loglevel=error)
fi

# The real-browser report test runs here, never skipped.
unset SLIPLOAD_SKIP_BROWSER
echo "== cargo test --workspace $*" >&2
cargo test --workspace "$@"

# The Python package: installed as the README says into a virtual environment of its
# own, then its tests, which compare it with the release command line.
venv=target/py-venv
if [ ! -x "$venv/bin/python" ]; then
    echo "== creating $venv" >&2
    "$python" -m venv "$venv"
fi
echo "== pip install the test tools and ./crates/py into $venv" >&2
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check \
    "maturin>=1.9.4,<2" pytest numpy pandas matplotlib nbclient nbformat ipykernel tqdm openseespy
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check ./crates/py
echo "== cargo build --release -p slipload (the command line the Python tests compare with)" >&2
cargo build --release -p slipload --quiet
echo "== pytest crates/py/tests" >&2
SLIPLOAD_BIN="$PWD/target/release/slipload" exec "$venv/bin/python" -m pytest -q crates/py/tests
