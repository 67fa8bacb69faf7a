#!/usr/bin/env bash
# Every test: the Rust workspace, a smoke run of the fuzz targets (fuzz/, scripts/fuzz.sh), the
# Python package's tests (python/tests: pytest in the venv
# target/py-venv, scripts/python-tests.sh), then the viewer's browser tests (tests/browser:
# headless Chromium from Debian's package driven by playwright-core). README and .ci/run call
# this. With --install it first installs what the tests need (Debian's chromium, the npm
# packages of tests/browser/package-lock.json, the venv target/py-venv with the Python packages
# of .ci/python-deps); without it a missing browser, venv or package skips those tests, except under
# CI=true, where it fails.
set -euo pipefail
cd "$(dirname "$0")/.."

if [ "${1:-}" = "--install" ]; then
    if ! command -v chromium >/dev/null 2>&1; then
        apt-get update
        DEBIAN_FRONTEND=noninteractive apt-get install -y chromium
    fi
    (cd tests/browser && PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD=1 npm ci --no-audit --no-fund)
    # The Python packages that tests drive (HyperQueue, pyarrow, SUMO's netconvert), into the
    # venv target/py-venv.
    bash .ci/python-deps
fi
# The tests call python3, hq and netconvert: those of the venv when there is one.
if [ -x target/py-venv/bin/python ]; then
    export PATH="$PWD/target/py-venv/bin:$PATH"
fi

echo "== cargo test --workspace --release"
cargo test --workspace --release

echo "== fuzz smoke (scripts/fuzz.sh: every fuzz target for 3 s)"
scripts/fuzz.sh 3

echo "== Python tests (python/tests)"
scripts/python-tests.sh ${1:+"$1"}

echo "== browser tests (tests/browser)"
if ! command -v node >/dev/null 2>&1 || [ ! -d tests/browser/node_modules ]; then
    if [ "${CI:-}" = "true" ]; then
        echo "error: node or tests/browser/node_modules is missing (run scripts/test-all.sh --install)" >&2
        exit 1
    fi
    echo "skipped: needs node and npm; run scripts/test-all.sh --install (or npm ci in tests/browser)" >&2
    exit 0
fi
# The tests start the release binary built above.
cargo build --release -p platoonsim --quiet
(cd tests/browser && node --test)
