#!/usr/bin/env bash
# Runs the libFuzzer harnesses of test/fuzz, each for a fixed time, from the
# seed corpora of test/fuzz/seeds (files written by Gmsh, TetGen, MMG-style
# .sol files, small surfaces). Builds them first if needed (Clang, in
# ./build-sanitize, with AddressSanitizer and UBSan; see doc/robustness.md).
#
#   bash scripts/fuzz.sh [SECONDS] [HARNESS...]     (default: 60 s, all nine)
#
# FUZZ_SEED=N fixes libFuzzer's random seed (CI uses 1, so that a run is
# reproducible); the default, 0, lets libFuzzer pick one.
# The corpus grows in build-sanitize/fuzz-corpus/HARNESS (never in the
# sources). A crash, a leak, a UBSan report, a hang (an input running over
# 30 s) or an input using over 2 GB stops the script with the input saved as
# build-sanitize/fuzz-findings/HARNESS/...; replay it with
#   build-sanitize/fuzz/HARNESS FILE
# One summary line per harness: executions, coverage (edges, features),
# corpus size.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
shift || true
harnesses=("$@")
if [ ${#harnesses[@]} -eq 0 ]; then
  harnesses=(fuzz_medit_mesh fuzz_medit_sol fuzz_surface fuzz_point_pairs fuzz_frame_field fuzz_hexex fuzz_ovm fuzz_gmsh_mesh
             fuzz_vtk_legacy_mesh)
fi
build=build-sanitize
if [ "${CGAL_EXT_SKIP_BUILD:-0}" != 1 ]; then
  bash scripts/install_dependencies.sh
  bash scripts/build_sanitize.sh
fi

declare -A max_len=([fuzz_medit_mesh]=8192 [fuzz_medit_sol]=4096 [fuzz_surface]=8192
                    [fuzz_point_pairs]=2048 [fuzz_frame_field]=8192 [fuzz_hexex]=4096 [fuzz_ovm]=4096
                    [fuzz_gmsh_mesh]=8192 [fuzz_vtk_legacy_mesh]=8192)
# The frame-field harness reads .mesh files: it starts from the mesh seeds.
declare -A seeds=([fuzz_medit_mesh]=fuzz_medit_mesh [fuzz_medit_sol]=fuzz_medit_sol [fuzz_surface]=fuzz_surface
                  [fuzz_point_pairs]=fuzz_point_pairs [fuzz_frame_field]=fuzz_medit_mesh [fuzz_hexex]=fuzz_hexex
                  [fuzz_ovm]=fuzz_ovm [fuzz_gmsh_mesh]=fuzz_gmsh_mesh [fuzz_vtk_legacy_mesh]=fuzz_vtk_legacy_mesh)
declare -A dict=([fuzz_medit_mesh]=medit.dict [fuzz_medit_sol]=medit.dict [fuzz_surface]=surface.dict
                 [fuzz_point_pairs]=numbers.dict [fuzz_frame_field]=medit.dict [fuzz_hexex]=numbers.dict
                 [fuzz_ovm]=ovm.dict [fuzz_gmsh_mesh]=gmsh.dict [fuzz_vtk_legacy_mesh]=vtk.dict)
status=0
for h in "${harnesses[@]}"; do
  corpus=$build/fuzz-corpus/$h
  findings=$build/fuzz-findings/$h
  mkdir -p "$corpus" "$findings"
  log=$build/fuzz-findings/$h.log
  start=$(date +%s)
  # Seeds are read, never written: new inputs go to the corpus directory.
  if ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
     "$build/fuzz/$h" -max_total_time="$seconds" -seed="${FUZZ_SEED:-0}" -timeout=30 -rss_limit_mb=2048 \
       -max_len="${max_len[$h]}" -dict="test/fuzz/${dict[$h]}" -print_final_stats=1 \
       -artifact_prefix="$findings/" "$corpus" "test/fuzz/seeds/${seeds[$h]}" >"$log" 2>&1; then
    result=ok
  else
    result="FINDING (see $log and $findings/)"
    status=1
  fi
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  cov=$(grep -o 'cov: [0-9]* ft: [0-9]*' "$log" | tail -1)
  echo "[fuzz] $h: ${execs:-?} executions in $(( $(date +%s) - start )) s, ${cov:-cov: ?}, corpus $(ls "$corpus" | wc -l) files: $result" >&2
  if [ "$result" != ok ]; then grep -m 20 -E 'ERROR|finding|SUMMARY|runtime error|Test unit written' "$log" >&2 || true; fi
done
exit $status
