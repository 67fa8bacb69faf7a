#!/usr/bin/env bash
# Create the virtual environment target/py-venv if it is missing (with Debian's python3-venv,
# from apt, if the system Python lacks venv or ensurepip). Shared by .ci/python-deps and
# scripts/python-tests.sh --install.
set -euo pipefail
cd "$(dirname "$0")/.."
VENV=target/py-venv
if [ ! -x "$VENV/bin/python" ]; then
    if ! python3 -m venv --help >/dev/null 2>&1 || ! python3 -c "import ensurepip" 2>/dev/null; then
        apt-get update
        DEBIAN_FRONTEND=noninteractive apt-get install -y python3-venv
    fi
    python3 -m venv "$VENV"
fi
