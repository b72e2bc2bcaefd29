#!/usr/bin/env bash
# Configures and builds in ./build, Release, with two jobs (CGAL units are
# heavy): everything (library, CLI, tests, benchmarks, doc examples), or
# only the targets given, e.g. `bash scripts/build.sh metric-frames` (the
# demo builds only what it runs).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
if [ $# -eq 0 ]; then
  cmake --build build -j2
else
  for target in "$@"; do cmake --build build -j2 --target "$target"; done
fi
