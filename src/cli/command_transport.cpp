// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#include "cli_common.h"
#include "commands.h"
#include "point_pairs_file.h"

#include <CGAL_ext/IO/Medit_mesh.h>
#include <CGAL_ext/IO/Medit_sol.h>
#include <CGAL_ext/IO/read_tet_mesh.h>
#include <CGAL_ext/Metric_field_3.h>
#include <CGAL_ext/Metric_transport_3.h>

#include <cmath>
#include <cstdio>
#include <memory>

namespace CGAL_ext::cli {

namespace {
const char* transport_help =
    "Usage: metric-frames transport MESH --metric SOL --pairs FILE [--tol T]\n"
    "                               [--scheme magnus|trapezoid] [--threads N]\n\n"
    "For each pair a -> b of FILE (one per line: ax ay az bx by bz; blank lines\n"
    "and lines starting with # are skipped), computes the transport T(a->b) of\n"
    "the metric of SOL (one tensor per vertex of MESH, Medit SolAtVertices)\n"
    "along the straight segment, and prints one JSON object per line, in order:\n\n"
    "  {\"pair\": i, \"R\": [9 numbers, row-major], \"angle\": radians, \"evaluations\": n}\n"
    "  {\"pair\": i, \"error\": \"the segment leaves the domain at t = 0.42 ...\"}\n\n"
    "A rotation field parallel along the segment satisfies R(b) = T(a->b) R(a).\n"
    "R is within about T radians of the exact transport of the piecewise-linear\n"
    "metric field, or its line ends with \"converged\": false and its error estimate\n"
    "(a metric that changes by orders of magnitude inside a cell); a segment\n"
    "with a part outside the mesh gets an error line.\n\n"
    "Options:\n"
    "  --metric SOL          the metric (.sol, type 3 tensors or type 1 sizes)\n"
    "  --pairs FILE          the pairs (- for standard input)\n"
    "  --tol T               tolerance in radians per pair (default 1e-8)\n"
    "  --scheme S            magnus (4th order, adaptive; default) or trapezoid\n"
    "                        (the thesis scheme, with recursive subdivision)\n"
    "  --threads N           worker threads (default: all cores); the output does\n"
    "                        not depend on N\n"
    "  -h, --help            this help\n";

} // namespace

int command_transport(const std::vector<std::string>& args) {
  Arguments a(args, "transport", transport_help);
  if (a.help_requested()) return 0;
  const std::string metric_path = a.required_option("--metric");
  const std::string pairs_path = a.required_option("--pairs");
  Transport_options opt;
  if (const auto tol = a.option("--tol")) opt.tolerance = parse_positive(a, "--tol", *tol);
  if (const auto scheme = a.option("--scheme")) {
    if (*scheme == "magnus") opt.scheme = Transport_scheme::magnus;
    else if (*scheme == "trapezoid") opt.scheme = Transport_scheme::trapezoid;
    else a.fail("--scheme '" + *scheme + "': expected magnus or trapezoid");
  }
  const auto threads = thread_limit(a);
  const std::string mesh_path = a.positional("MESH");
  a.finish();

  Stage_timer timer;
  using Tr = Tet_mesh_triangulation_3<>;
  Tr tr;
  IO::Medit_mesh mesh;
  IO::read_tet_mesh(mesh_path, tr, &mesh);
  timer.stage("read and build mesh");
  const std::vector<Eigen::Matrix3d> metrics = IO::read_medit_sol(metric_path, mesh.vertices.size());
  Metric_field_3<Tr>::check_extent(tr, mesh_path);
  const Metric_field_3<Tr> field(tr, metrics, metric_path);
  field.precompute();
  timer.stage("read metric");
  const std::vector<Point_pair> input = read_point_pairs(pairs_path);
  std::vector<std::pair<Tr::Point, Tr::Point>> pairs;
  pairs.reserve(input.size());
  for (const Point_pair& p : input)
    pairs.emplace_back(Tr::Point(p.a[0], p.a[1], p.a[2]), Tr::Point(p.b[0], p.b[1], p.b[2]));
  timer.stage("read pairs");

  const Metric_transport_3<Metric_field_3<Tr>> transport(field);
  std::vector<Metric_transport_result> results;
  transport.transport_batch(pairs, opt, results);
  timer.stage("transport");

  std::size_t failed = 0, evaluations = 0, unconverged = 0;
  std::string line;
  for (std::size_t i = 0; i < results.size(); ++i) {
    const Metric_transport_result& r = results[i];
    if (!r.ok) {
      ++failed;
      line = "{\"pair\": " + std::to_string(i) + ", \"error\": \"" + json_escape(r.message) + "\"}\n";
    } else {
      evaluations += r.evaluations;
      unconverged += !r.converged;
      char buf[64];
      line = "{\"pair\": " + std::to_string(i) + ", \"R\": [";
      for (int k = 0; k < 9; ++k) {
        std::snprintf(buf, sizeof buf, "%s%.17g", k ? ", " : "", r.rotation(k / 3, k % 3));
        line += buf;
      }
      std::snprintf(buf, sizeof buf, "], \"angle\": %.17g, \"evaluations\": %zu", r.angle, r.evaluations);
      line += buf;
      if (!r.converged) { // the tolerance is not met: say so on the line itself
        std::snprintf(buf, sizeof buf, ", \"converged\": false, \"error_estimate\": %.3g", r.error_estimate);
        line += buf;
      }
      line += "}\n";
    }
    std::fputs(line.c_str(), stdout);
  }
  timer.stage("write");
  std::fprintf(stderr, "[summary] %zu pairs: %zu transported (%zu W evaluations), %zu outside the domain%s\n",
               results.size(), results.size() - failed, evaluations, failed,
               unconverged ? (", " + std::to_string(unconverged) +
                              " not converged (the metric changes too fast along them: \"converged\": false)")
                                 .c_str()
                           : "");
  timer.summary();
  return 0;
}

} // namespace CGAL_ext::cli
