// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_METRIC_TENSOR_H
#define CGAL_EXT_METRIC_TENSOR_H

/// \file Metric_tensor.h
/// Validation and symmetric square root of one 3x3 metric tensor `g`.

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include <cmath>
#include <sstream>
#include <string>

namespace CGAL_ext {

/// \ingroup PkgCGALExtMetric
/// Largest accepted condition number (ratio of the extreme eigenvalues) of a
/// metric tensor. Beyond it the square root and the connection lose all
/// significant digits, so such a tensor is reported as not positive definite.
constexpr double metric_tensor_max_condition = 1e14;

/// \ingroup PkgCGALExtMetric
/// Relative tolerance on `|g(i,j) - g(j,i)|`, relative to `max |g(i,j)|`.
constexpr double metric_tensor_symmetry_tolerance = 1e-12;

/// \ingroup PkgCGALExtMetric
/// Checks that `g` is a usable metric tensor: finite, symmetric within a
/// relative `metric_tensor_symmetry_tolerance`, and positive definite with
/// a condition number at most `metric_tensor_max_condition`.
///
/// \param g the 3x3 tensor; an edge `e` has length `sqrt(e^T g e)` (MATH.md section 1)
/// \returns an empty string if `g` is valid, else the reason, in words,
///          suitable as the `problem` of an `Input_error`
inline std::string check_metric_tensor(const Eigen::Matrix3d& g) {
  if (!g.allFinite()) return "the metric tensor has a non-finite entry (NaN or Inf)";
  const double scale = g.cwiseAbs().maxCoeff();
  if (scale == 0) return "the metric tensor is zero: not positive definite";
  const double asym = (g - g.transpose()).cwiseAbs().maxCoeff();
  if (asym > metric_tensor_symmetry_tolerance * scale) {
    std::ostringstream s;
    s << "the metric tensor is not symmetric (|g_ij - g_ji| = " << asym << " for max |g_ij| = " << scale << ")";
    return s.str();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(0.5 * (g + g.transpose()), Eigen::EigenvaluesOnly);
  if (es.info() != Eigen::Success) return "the eigenvalues of the metric tensor could not be computed";
  const double lmin = es.eigenvalues()(0), lmax = es.eigenvalues()(2);
  if (!(lmin > 0)) {
    std::ostringstream s;
    s << "the metric tensor is not positive definite (smallest eigenvalue " << lmin << ")";
    return s.str();
  }
  if (lmax > metric_tensor_max_condition * lmin) {
    std::ostringstream s;
    s << "the metric tensor is numerically not positive definite (condition number " << lmax / lmin << " > "
      << metric_tensor_max_condition << ")";
    return s.str();
  }
  return {};
}

/// \ingroup PkgCGALExtMetric
/// The symmetric positive-definite square root `A = g^{1/2}` (so `A A = g`),
/// from the eigendecomposition `g = V diag(l) V^T`: `A = V diag(sqrt(l)) V^T`.
///
/// The result is symmetrized, so that it is exactly symmetric. The same
/// input always gives the same bits (no randomness), so equal vertex
/// tensors give equal roots, which is what makes a constant metric field
/// have a curl of exactly zero.
///
/// \pre `check_metric_tensor(g)` is empty (only the symmetric part of `g` is used)
/// \param g a symmetric positive-definite 3x3 matrix
/// \returns the symmetric positive-definite root of `g`
inline Eigen::Matrix3d sqrt_spd(const Eigen::Matrix3d& g) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(0.5 * (g + g.transpose()));
  const Eigen::Vector3d s = es.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  const Eigen::Matrix3d& V = es.eigenvectors();
  const Eigen::Matrix3d A = V * s.asDiagonal() * V.transpose();
  return 0.5 * (A + A.transpose());
}

} // namespace CGAL_ext

#endif // CGAL_EXT_METRIC_TENSOR_H
