#!/usr/bin/env bash
# Installs the dependencies, builds, and runs the whole test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
start=$(date +%s)
bash scripts/install_dependencies.sh
bash scripts/build.sh
ctest --test-dir build --output-on-failure --timeout 900 -j2
echo "[test] wall time $(( $(date +%s) - start )) s" >&2
