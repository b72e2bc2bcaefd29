#!/usr/bin/env bash
# Runs Doxygen over the public headers and doc/ (build/Doxyfile, made from
# doc/Doxyfile.in by CMake, configured again here so that it is current) and fails if it
# prints any warning: every public function documents its parameters and
# return value, every public member is documented, and the Markdown pages
# parse. The warnings are kept in build/doxygen_warnings.log; the HTML goes
# to build/doc/html. Needs doxygen only (no LaTeX, no Graphviz).
set -euo pipefail
cd "$(dirname "$0")/.."

if ! command -v doxygen >/dev/null 2>&1; then
  echo "[docs] doxygen is not installed (Debian: apt-get install doxygen)" >&2
  exit 1
fi
cmake -S . -B build >/dev/null
if [ ! -f build/Doxyfile ]; then
  echo "[docs] build/Doxyfile was not generated (CMake did not find doxygen?)" >&2
  exit 1
fi

log=build/doxygen_warnings.log
# Doxygen writes its warnings and errors (and those of the tools it runs) on
# stderr; QUIET = YES leaves stdout almost empty.
status=0
doxygen build/Doxyfile >/dev/null 2>"$log" || status=$?
if [ "$status" -ne 0 ] || [ -s "$log" ]; then
  cat "$log" >&2
  count=$(grep -c . "$log" || true)
  echo "[docs] Doxygen: $count line(s) of warnings (exit status $status); see $log" >&2
  exit 1
fi
echo "[docs] Doxygen: no warnings" >&2
