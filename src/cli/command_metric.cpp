// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#include "cli_common.h"
#include "commands.h"
#include "metric_expression.h"

#include <CGAL_ext/IO/Medit_mesh.h>
#include <CGAL_ext/IO/Medit_sol.h>
#include <CGAL_ext/Metric_tensor.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>

namespace CGAL_ext::cli {

namespace {
const char* metric_help =
    "Usage: metric-frames metric MESH (--expr EXPRS | --size EXPR) -o OUT.sol [--force]\n\n"
    "Evaluates a metric given by formulas at the vertices of the Medit mesh MESH\n"
    "and writes it as a Medit .sol file (SolAtVertices, one symmetric tensor per\n"
    "vertex, lower triangle by rows: m11 m21 m22 m31 m32 m33), as MMG reads it.\n"
    "An edge e has length sqrt(e^T g e) in the metric g.\n\n"
    "Options:\n"
    "  --expr EXPRS   6 comma-separated expressions of x, y, z: m11, m21, m22, m31, m32, m33\n"
    "                 e.g. --expr '1, 0, 16, 0, 0, 4' (constant diag(1, 16, 4)) or\n"
    "                 --expr '1 + x^2, 0, 1, 0, 0, exp(z)'\n"
    "  --size EXPR    an isotropic size h(x, y, z) > 0, meaning g = I / h^2,\n"
    "                 e.g. --size '0.05 + 0.1 * sqrt(x^2 + y^2)'\n"
    "  -o OUT.sol     the output file (written to a temporary file, then renamed)\n"
    "  --force        replace OUT.sol if it exists (never the mesh itself)\n"
    "  -h, --help     this help\n\n"
    "Expressions use muParser: + - * / ^, sin cos tan exp log sqrt abs min max\n"
    "and more, the constants pi and e. Every tensor must be finite, symmetric and\n"
    "positive definite: the first vertex where it is not is an error naming it.\n";

} // namespace

int command_metric(const std::vector<std::string>& args) {
  Arguments a(args, "metric", metric_help);
  if (a.help_requested()) return 0;
  const auto expr = a.option("--expr");
  const auto size = a.option("--size");
  const std::string out_path = a.required_option("-o");
  const bool force = a.flag("--force");
  const std::string mesh_path = a.positional("MESH");
  a.finish();
  if (bool(expr) == bool(size)) a.fail("give exactly one of --expr and --size");
  // Parse before reading anything: a typo is a usage error, found at once.
  const Metric_expression formula(expr ? *expr : *size,
                                  expr ? Metric_expression::Kind::tensor : Metric_expression::Kind::size,
                                  expr ? "--expr" : "--size");
  std::error_code ec;
  if (std::filesystem::exists(out_path, ec) && std::filesystem::equivalent(out_path, mesh_path, ec))
    throw std::runtime_error(out_path + ": the output would overwrite the input mesh");
  if (std::filesystem::exists(out_path, ec) && !force)
    throw std::runtime_error(out_path + ": the file exists; give --force to replace it");

  Stage_timer timer;
  const IO::Medit_mesh mesh = IO::read_medit_mesh(mesh_path);
  timer.stage("read mesh");

  const std::vector<Eigen::Matrix3d> metrics = evaluate_metric(formula, mesh.vertices, expr ? "--expr" : "--size");
  double min_size = std::numeric_limits<double>::infinity(), max_size = 0, max_condition = 1;
  for (const Eigen::Matrix3d& g : metrics) {
    const Eigen::Vector3d l = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(g, Eigen::EigenvaluesOnly).eigenvalues();
    min_size = std::min(min_size, 1 / std::sqrt(l(2)));
    max_size = std::max(max_size, 1 / std::sqrt(l(0)));
    max_condition = std::max(max_condition, l(2) / l(0));
  }
  timer.stage("evaluate");
  IO::write_medit_sol(out_path, metrics);
  timer.stage("write");
  std::fprintf(stderr, "[summary] %zu vertices; sizes 1/sqrt(eigenvalue) in [%.6g, %.6g]; max anisotropy %.6g; wrote %s\n",
               metrics.size(), min_size, max_size, std::sqrt(max_condition), out_path.c_str());
  timer.summary();
  return 0;
}

} // namespace CGAL_ext::cli
