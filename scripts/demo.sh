#!/usr/bin/env bash
# Installs the dependencies, builds, and runs the main job on the built-in
# default input: the summary of a Gmsh-meshed box with a cylindrical hole.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_dependencies.sh
bash scripts/build.sh
./build/bin/metric-frames info doc/examples/data/gmsh_box_with_hole.mesh
