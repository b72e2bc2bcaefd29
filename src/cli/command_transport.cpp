// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#include "cli_common.h"
#include "commands.h"
#include "json_output.h"
#include "point_pairs_file.h"

#include <CGAL_ext/IO/Medit_mesh.h>
#include <CGAL_ext/IO/Medit_sol.h>
#include <CGAL_ext/IO/read_tet_mesh.h>
#include <CGAL_ext/Metric_field_3.h>
#include <CGAL_ext/Metric_transport_3.h>

#include <cstdio>

namespace CGAL_ext::cli {

namespace {

using Tr = Tet_mesh_triangulation_3<>;

// A transport as one JSON line: the rotation, its angle and its cost, or the error.
Json transport_json(std::size_t i, const Metric_transport_result& r) {
  if (!r.ok) return {{"pair", i}, {"error", r.message}};
  Json R = Json::array();
  for (int k = 0; k < 9; ++k) R.push_back(r.rotation(k / 3, k % 3));
  Json line = {{"pair", i}, {"R", R}, {"angle", r.angle}, {"evaluations", r.evaluations}};
  if (!r.converged) { // the tolerance is not met: say so on the line itself
    line["converged"] = false;
    line["error_estimate"] = r.error_estimate;
  }
  return line;
}

} // namespace

int run_transport(const Transport_request& request) {
  const auto threads = thread_limit(request.threads);
  Stage_timer timer;
  Tr tr;
  IO::Medit_mesh mesh;
  print_build_notes(IO::read_tet_mesh(request.mesh, tr, &mesh), "the transports are the same on either orientation");
  timer.stage("read and build mesh");
  const std::vector<Eigen::Matrix3d> metrics = IO::read_medit_sol(request.metric, mesh.vertices.size());
  Metric_field_3<Tr>::check_extent(tr, request.mesh);
  const Metric_field_3<Tr> field(tr, metrics, request.metric);
  field.precompute();
  timer.stage("read metric");
  const std::vector<Point_pair> input = read_point_pairs(request.pairs, "ax ay az bx by bz");
  std::vector<std::pair<Tr::Point, Tr::Point>> pairs;
  pairs.reserve(input.size());
  for (const Point_pair& p : input)
    pairs.emplace_back(Tr::Point(p.a[0], p.a[1], p.a[2]), Tr::Point(p.b[0], p.b[1], p.b[2]));
  timer.stage("read pairs");

  const Metric_transport_3<Metric_field_3<Tr>> transport(field);
  std::vector<Metric_transport_result> results;
  Transport_options opt;
  opt.tolerance = request.tolerance;
  opt.scheme = request.scheme == "magnus" ? Transport_scheme::magnus : Transport_scheme::trapezoid;
  transport.transport_batch(pairs, opt, results);
  timer.stage("transport");

  std::size_t failed = 0, evaluations = 0, unconverged = 0;
  for (std::size_t i = 0; i < results.size(); ++i) {
    const Metric_transport_result& r = results[i];
    failed += !r.ok;
    evaluations += r.ok ? r.evaluations : 0;
    unconverged += r.ok && !r.converged;
    print_json_line(transport_json(i, r));
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
