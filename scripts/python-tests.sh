#!/usr/bin/env bash
# The Python package's tests (python/tests, pytest): build and install the package with
# `pip install ./python` into the virtual environment target/py-venv, then run pytest.
# With --install the venv is created (and Debian's python3-venv installed if needed); without
# it a missing venv skips the tests, except under CI=true, where it fails.
# Needs the release binary (the identity tests compare with `platoonsim run`).
set -euo pipefail
cd "$(dirname "$0")/.."
VENV=target/py-venv
PY_PACKAGES=(pytest gymnasium matplotlib pettingzoo)

if [ "${1:-}" = "--install" ]; then
    scripts/py-venv.sh
fi
if [ ! -x "$VENV/bin/python" ]; then
    if [ "${CI:-}" = "true" ]; then
        echo "error: $VENV is missing (run scripts/test-all.sh --install)" >&2
        exit 1
    fi
    echo "skipped: the Python tests need the venv $VENV; run scripts/test-all.sh --install" >&2
    exit 0
fi
# The package is rebuilt every time (cargo's cache makes an unchanged one quick), so that the
# tests never run an old extension.
start=$(date +%s)
"$VENV/bin/python" -m pip install --quiet ./python "${PY_PACKAGES[@]}"
echo "pip install ./python: $(( $(date +%s) - start )) s"
cargo build --release -p platoonsim --quiet
"$VENV/bin/python" -m pytest -q python/tests
