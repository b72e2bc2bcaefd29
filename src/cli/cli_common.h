// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// What the subcommands of metric-frames share when they run: usage errors
// (exit 2), the thread limit and stage timing on stderr. Light on purpose:
// CLI11 stays in metric_frames.cpp, nlohmann-json in json_output.h.
#ifndef CGAL_EXT_CLI_COMMON_H
#define CGAL_EXT_CLI_COMMON_H

#include <CGAL_ext/build_triangulation_from_tets.h>

#include <CGAL/Real_timer.h>

#include <tbb/global_control.h>

#include <cstddef>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>

namespace CGAL_ext::cli {

/// A mistake in the command line found after parsing (options that exclude
/// each other in a way CLI11 cannot say, a malformed tensor); main() prints
/// it with a pointer to the subcommand's help and exits with 2, as for
/// CLI11's own parse errors.
struct Usage_error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// A limit on TBB's worker threads for the command's lifetime, or null (all
/// cores) for 0, the value of an absent --threads.
inline std::unique_ptr<tbb::global_control> thread_limit(std::size_t threads) {
  if (threads == 0) return nullptr;
  return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
}

// The notes on what building the triangulation changed or left out, on
// stderr: re-oriented tetrahedra (with what that means for the command's
// outputs) and vertices used by no tetrahedron.
inline void print_build_notes(const Tet_mesh_build_report& r, const char* reoriented_consequence) {
  if (r.reoriented_tets)
    std::fprintf(stderr, "[note] %zu negatively oriented tetrahedra were re-oriented (first: tetrahedron %zu); %s\n",
                 r.reoriented_tets, r.reoriented_examples.front() + 1, reoriented_consequence);
  if (r.unused_vertices) std::fprintf(stderr, "[note] %zu vertices are used by no tetrahedron\n", r.unused_vertices);
}

/// Prints "[stage] name  1.23 s" lines on stderr, and a total at the end
/// (wall-clock time, CGAL::Real_timer).
class Stage_timer {
public:
  Stage_timer() {
    total_.start();
    lap_.start();
  }
  void stage(const char* name) {
    std::fprintf(stderr, "[stage] %-22s %8.3f s\n", name, lap_.time());
    lap_.reset();
  }
  void summary() const { std::fprintf(stderr, "[done]  %-22s %8.3f s\n", "total", total_.time()); }

private:
  CGAL::Real_timer total_, lap_;
};

} // namespace CGAL_ext::cli

#endif
