#!/usr/bin/env bash
# Installs the dependencies, builds, and runs the whole test suite (what CI
# runs): the Release build in ./build, Doxygen without warnings
# (scripts/check_docs.sh), then the suite under AddressSanitizer
# and UndefinedBehaviorSanitizer in ./build-sanitize with the libFuzzer
# harnesses run for a fixed time (scripts/test_sanitize.sh,
# doc/robustness.md). CGAL_EXT_SKIP_SANITIZE=1 runs the Release part only.
set -euo pipefail
cd "$(dirname "$0")/.."
start=$(date +%s)
bash scripts/install_dependencies.sh
bash scripts/build.sh
ctest --test-dir build --output-on-failure --timeout 900 -j2
echo "[test] Release build and tests: $(( $(date +%s) - start )) s" >&2
bash scripts/check_docs.sh
if [ "${CGAL_EXT_SKIP_SANITIZE:-0}" != 1 ]; then
  bash scripts/test_sanitize.sh
fi
echo "[test] wall time $(( $(date +%s) - start )) s" >&2
