// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// A metric tensor field given by formulas in x, y, z (muParser), for the
// `metric` and `generate` subcommands.
#ifndef CGAL_EXT_CLI_METRIC_EXPRESSION_H
#define CGAL_EXT_CLI_METRIC_EXPRESSION_H

#include <Eigen/Core>

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace CGAL_ext::cli {

/// The metric `g(x, y, z)` given by formulas:
/// - a tensor: 6 comma-separated expressions `m11, m21, m22, m31, m32, m33`
///   (the lower triangle by rows, as in Medit `.sol` files), or
/// - a size: 1 expression `h`, meaning `g = I / h^2`.
/// Variables `x`, `y`, `z`; constants `pi` and `e`; muParser's functions
/// (sin, cos, exp, sqrt, abs, min, max, ...) and operators, including `^`.
/// Not thread-safe: one evaluator per thread.
class Metric_expression {
public:
  enum class Kind { tensor, size };
  /// Parses `expression`; throws Usage_error (with the position and the
  /// parser's message) if it does not parse or has the wrong number of
  /// components for `kind`. `option` names the option in messages.
  Metric_expression(const std::string& expression, Kind kind, const std::string& option);
  ~Metric_expression();
  Metric_expression(const Metric_expression&) = delete;
  Metric_expression& operator=(const Metric_expression&) = delete;

  /// `g` at the point. A tensor may be non-finite or not SPD: the caller
  /// validates it (check_metric_tensor) and names the vertex. A size that is
  /// not positive and finite throws std::domain_error.
  Eigen::Matrix3d operator()(double x, double y, double z) const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// `g` at every point, validated (check_metric_tensor) and symmetrised.
/// Throws std::runtime_error naming `option`, the 1-based vertex and its
/// position if a value is not a valid metric.
std::vector<Eigen::Matrix3d> evaluate_metric(const Metric_expression& formula,
                                             const std::vector<std::array<double, 3>>& points,
                                             const std::string& option);

} // namespace CGAL_ext::cli

#endif
