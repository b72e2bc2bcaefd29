// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The subcommands of the metric-frames tool: what each one's command line
// holds once parsed (metric_frames.cpp declares the options with CLI11, in
// that one unit, since CLI11 is header-only and costs seconds per unit), and
// the function that runs it. A run function prints its output on stdout and
// its progress on stderr and returns the exit code; it throws Usage_error for
// a command line that CLI11 cannot reject by itself (exit 2) and anything
// else for bad input or a failure (exit 1).
#ifndef CGAL_EXT_CLI_COMMANDS_H
#define CGAL_EXT_CLI_COMMANDS_H

#include <CGAL_ext/Cell_transport_3.h>
#include <CGAL_ext/Frame_field_options.h>

#include <cstddef>
#include <optional>
#include <string>

namespace CGAL_ext::cli {

/// `metric-frames info MESH [--json]`.
struct Info_request {
  std::string mesh;
  bool json = false;
};
/// Prints the counts, bounding box, volume and dihedral angles of the mesh.
int run_info(const Info_request& request);

/// `metric-frames walk MESH --segments FILE [--fast]`.
struct Walk_request {
  std::string mesh, segments;
  bool fast = false;
};
/// Prints the simplices met by the segments, as JSON lines.
int run_walk(const Walk_request& request);

/// `metric-frames transport MESH --metric SOL --pairs FILE [--tol T] [--scheme S] [--threads N]`.
struct Transport_request {
  std::string mesh, metric, pairs;
  double tolerance = Transport_options().tolerance;
  std::string scheme = "magnus"; ///< magnus or trapezoid
  std::size_t threads = 0;       ///< 0: all cores
};
/// Prints the transports between the point pairs, as JSON lines.
int run_transport(const Transport_request& request);

/// `metric-frames metric MESH (--expr EXPRS | --size EXPR) -o OUT.sol [--force]`.
struct Metric_request {
  std::string mesh, out;
  std::optional<std::string> expr, size;
  bool force = false;
};
/// Writes the .sol file of the formulas.
int run_metric(const Metric_request& request);

/// `metric-frames generate INPUT [--metric SOL | --metric-const M | --metric-expr E] -o OUTDIR [options]`.
struct Generate_request {
  std::string input, out_dir;
  bool force = false, no_repair = false, smooth_surface = false, soft_boundary = false, keep_vertices = false,
       hexes = false;
  std::optional<std::string> sol_path, metric_const, metric_expr;
  std::optional<double> hex_size, size, max_memory;
  std::size_t threads = 0; ///< 0: all cores
  /// The frame field's options that the command line sets.
  Frame_field_options options;
  /// The restarts of the repair's second round (unless `no_repair`).
  int repair_restarts = Singularity_repair_options().restarts.at(1);
  /// The repair's further rounds at most, and its released rounds (unless `no_repair`).
  int repair_rounds = Singularity_repair_options().max_further_rounds;
};
/// Writes the frame field, its singularities and the output files.
int run_generate(const Generate_request& request);

} // namespace CGAL_ext::cli

#endif
