#!/usr/bin/env bash
# Configures and builds everything (library, CLI, tests, benchmarks, doc
# examples) in ./build, Release, with two jobs: CGAL units are heavy.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j2
