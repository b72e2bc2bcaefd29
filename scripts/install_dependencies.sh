#!/usr/bin/env bash
# Installs the Debian packages that CGAL Metric Frames needs to build and
# test (or those given as arguments). Idempotent: apt-get runs only if a
# package is missing. Needs root (or sudo) on Debian bookworm.
set -euo pipefail

# libmuparser-dev, libcli11-dev and nlohmann-json3-dev: the metric-frames
# tool (formulas, argument parsing, JSON output); the library alone needs
# CGAL, Eigen, Boost and TBB. clang and libclang-rt-14-dev: the sanitized build and the libFuzzer
# harnesses (scripts/test_sanitize.sh, doc/robustness.md). doxygen: the API
# documentation, checked without warnings by CI (scripts/check_docs.sh).
packages=(build-essential cmake libcgal-dev libeigen3-dev libboost-dev catch2 libtbb-dev libgmp-dev libmpfr-dev
          libmuparser-dev libcli11-dev nlohmann-json3-dev python3 clang libclang-rt-14-dev doxygen)
# Other packages given as arguments are installed instead, the same way
# (scripts/make_benchmark_meshes.sh: libcgal-demo, tetgen, gmsh).
if [ $# -gt 0 ]; then packages=("$@"); fi

missing=()
for p in "${packages[@]}"; do
  if [ "$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null)" != "install ok installed" ]; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "[deps] all dependencies are installed" >&2
  exit 0
fi
echo "[deps] installing: ${missing[*]}" >&2
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
