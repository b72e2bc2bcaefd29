#!/usr/bin/env bash
# Configures and builds the sanitized build in ./build-sanitize: Clang with
# AddressSanitizer and UndefinedBehaviorSanitizer (-fno-sanitize-recover:
# any report fails), the library, the CLI, the tests and the libFuzzer
# harnesses; no benchmarks, no doc examples. -O1: sanitizers want little
# inlining, and it compiles faster than -O2.
set -euo pipefail
cd "$(dirname "$0")/.."
CXX=clang++ cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_CXX_FLAGS_RELEASE="-O1 -g1 -DNDEBUG" \
  -DCGAL_EXT_SANITIZE=ON -DCGAL_EXT_BUILD_FUZZERS=ON \
  -DCGAL_EXT_BUILD_BENCHMARKS=OFF -DCGAL_EXT_BUILD_EXAMPLES=OFF >/dev/null
cmake --build build-sanitize -j2
