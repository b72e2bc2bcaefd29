// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#include "metric_expression.h"

#include "cli_common.h"

#include <CGAL_ext/Metric_tensor.h>

#include <muParser.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace CGAL_ext::cli {

namespace {
std::string format_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}
} // namespace

struct Metric_expression::Impl {
  mu::Parser parser;
  Kind kind;
  // muParser reads the variables through these addresses at each Eval.
  mutable double x = 0, y = 0, z = 0;
};

Metric_expression::Metric_expression(const std::string& expression, Kind kind, const std::string& option)
    : impl_(std::make_unique<Impl>()) {
  impl_->kind = kind;
  const int wanted = kind == Kind::tensor ? 6 : 1;
  try {
    impl_->parser.DefineVar("x", &impl_->x);
    impl_->parser.DefineVar("y", &impl_->y);
    impl_->parser.DefineVar("z", &impl_->z);
    impl_->parser.DefineConst("pi", M_PI);
    impl_->parser.DefineConst("e", M_E);
    impl_->parser.SetExpr(expression);
    int n = 0;
    impl_->parser.Eval(n); // parses; evaluating at the origin reports the component count
    if (n != wanted)
      throw Usage_error(option + " '" + expression + "': expected " +
                        (wanted == 6 ? std::string("6 comma-separated expressions m11, m21, m22, m31, m32, m33")
                                     : std::string("1 expression (the size h)")) +
                        ", found " + std::to_string(n));
  } catch (const mu::Parser::exception_type& e) {
    throw Usage_error(option + " '" + expression + "': " + e.GetMsg()); // the message gives the position
  }
}

Metric_expression::~Metric_expression() = default;

Eigen::Matrix3d Metric_expression::operator()(double x, double y, double z) const {
  impl_->x = x;
  impl_->y = y;
  impl_->z = z;
  int n = 0;
  const double* v = impl_->parser.Eval(n);
  Eigen::Matrix3d g;
  if (impl_->kind == Kind::size) {
    const std::string problem = check_metric_size(v[0]);
    if (!problem.empty()) throw std::domain_error("the size h = " + format_number(v[0]) + " " + problem);
    g = Eigen::Matrix3d::Identity() / (v[0] * v[0]);
  } else {
    g << v[0], v[1], v[3], v[1], v[2], v[4], v[3], v[4], v[5];
  }
  return g;
}

std::vector<Eigen::Matrix3d> evaluate_metric(const Metric_expression& formula,
                                             const std::vector<std::array<double, 3>>& points,
                                             const std::string& option) {
  std::vector<Eigen::Matrix3d> metrics(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& p = points[i];
    auto where = [&] {
      char buf[160];
      std::snprintf(buf, sizeof buf, "vertex %zu (%.17g, %.17g, %.17g)", i + 1, p[0], p[1], p[2]);
      return option + " at " + buf + ": ";
    };
    try {
      metrics[i] = formula(p[0], p[1], p[2]);
    } catch (const std::domain_error& e) {
      throw std::runtime_error(where() + e.what());
    }
    const std::string problem = check_metric_tensor(metrics[i]);
    if (!problem.empty()) throw std::runtime_error(where() + problem);
    metrics[i] = (0.5 * metrics[i] + 0.5 * metrics[i].transpose()).eval(); // g + g^T overflows for 1e308
  }
  return metrics;
}

} // namespace CGAL_ext::cli
