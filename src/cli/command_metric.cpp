// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#include "cli_common.h"
#include "commands.h"
#include "metric_expression.h"

#include <CGAL_ext/IO/Medit_mesh.h>
#include <CGAL_ext/IO/read_tet_mesh_file.h>
#include <CGAL_ext/IO/Medit_sol.h>
#include <CGAL_ext/Metric_tensor.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>

namespace CGAL_ext::cli {

int run_metric(const Metric_request& request) {
  if (bool(request.expr) == bool(request.size)) throw Usage_error("give exactly one of --expr and --size");
  const bool tensor = bool(request.expr);
  const char* option = tensor ? "--expr" : "--size";
  // Parse before reading anything: a typo is a usage error, found at once.
  const Metric_expression formula(tensor ? *request.expr : *request.size,
                                  tensor ? Metric_expression::Kind::tensor : Metric_expression::Kind::size, option);
  std::error_code ec;
  if (std::filesystem::exists(request.out, ec) && std::filesystem::equivalent(request.out, request.mesh, ec))
    throw std::runtime_error(request.out + ": the output would overwrite the input mesh");
  if (std::filesystem::exists(request.out, ec) && !std::filesystem::is_regular_file(request.out, ec))
    throw std::runtime_error(request.out + ": is a directory or another non-file; the output cannot replace it");
  if (std::filesystem::exists(request.out, ec) && !request.force)
    throw std::runtime_error(request.out + ": the file exists; give --force to replace it");

  Stage_timer timer;
  const IO::Medit_mesh mesh = IO::read_tet_mesh_file(request.mesh);
  timer.stage("read mesh");

  const std::vector<Eigen::Matrix3d> metrics = evaluate_metric(formula, mesh.vertices, option);
  double min_size = std::numeric_limits<double>::infinity(), max_size = 0, max_condition = 1;
  for (const Eigen::Matrix3d& g : metrics) {
    const Eigen::Vector3d l = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(g, Eigen::EigenvaluesOnly).eigenvalues();
    min_size = std::min(min_size, 1 / std::sqrt(l(2)));
    max_size = std::max(max_size, 1 / std::sqrt(l(0)));
    max_condition = std::max(max_condition, l(2) / l(0));
  }
  timer.stage("evaluate");
  IO::write_medit_sol(request.out, metrics);
  timer.stage("write");
  std::fprintf(stderr, "[summary] %zu vertices; sizes 1/sqrt(eigenvalue) in [%.6g, %.6g]; max anisotropy %.6g; wrote %s\n",
               metrics.size(), min_size, max_size, std::sqrt(max_condition), request.out.c_str());
  timer.summary();
  return 0;
}

} // namespace CGAL_ext::cli
