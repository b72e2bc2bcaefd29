// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_METRIC_TENSOR_H
#define CGAL_EXT_METRIC_TENSOR_H

/// \file Metric_tensor.h
/// Validation and symmetric square root of one 3x3 metric tensor `g`.

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include <cmath>
#include <iomanip>
#include <limits>
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

namespace internal {

// The even exponent e with max |g_ij| < 2^e <= 4 max |g_ij|: g 2^-e has
// entries below 1, so that g + g^T and the eigenvalues cannot overflow, and
// its square root is exactly that of g times 2^(-e/2).
inline int metric_scale_exponent(const Eigen::Matrix3d& g) {
  int e = 0;
  std::frexp(g.cwiseAbs().maxCoeff(), &e);
  return e + (e & 1);
}

// g 2^k, exactly (entries far below the largest may lose bits as subnormals).
inline Eigen::Matrix3d times_power_of_two(const Eigen::Matrix3d& g, int k) {
  return g.unaryExpr([k](double x) { return std::ldexp(x, k); });
}

// x 2^k in words, also where it is not a double, e.g. "4.76e+308".
inline std::string power_of_two_text(double x, int k) {
  std::ostringstream s;
  const double y = std::ldexp(x, k);
  if (std::isfinite(y) && (y != 0 || x == 0)) {
    s << y;
    return s.str();
  }
  const double l = std::log10(std::abs(x)) + k * std::log10(2.0);
  double exponent = std::floor(l), mantissa = std::pow(10.0, l - exponent);
  if (mantissa >= 9.995) mantissa /= 10, exponent += 1; // "10e+308" is "1e+309"
  s << (x < 0 ? "-" : "") << std::setprecision(3) << mantissa << (exponent < 0 ? "e-" : "e+")
    << std::abs(exponent);
  return s.str();
}

} // namespace internal

/// \ingroup PkgCGALExtMetric
/// Checks that `g` is a usable metric tensor: finite, symmetric within a
/// relative `metric_tensor_symmetry_tolerance`, positive definite with a
/// condition number at most `metric_tensor_max_condition`, and with
/// eigenvalues that are normal doubles, so that `g`, its square root and
/// their inverses are all representable (1e308 I is accepted, 1e-320 I not).
/// It works on `g` scaled by a power of two: large entries cannot overflow.
///
/// \param g the 3x3 tensor; an edge `e` has length `sqrt(e^T g e)` (doc/math.md section 1)
/// \returns an empty string if `g` is valid, else the reason, in words,
///          suitable as the `problem` of an `Input_error`
inline std::string check_metric_tensor(const Eigen::Matrix3d& g) {
  if (!g.allFinite()) return "the metric tensor has a non-finite entry (NaN or Inf)";
  if (g.cwiseAbs().maxCoeff() == 0) return "the metric tensor is zero: not positive definite";
  const int e = internal::metric_scale_exponent(g);
  const Eigen::Matrix3d gs = internal::times_power_of_two(g, -e);
  const double scale = gs.cwiseAbs().maxCoeff();
  const double asym = (gs - gs.transpose()).cwiseAbs().maxCoeff();
  if (asym > metric_tensor_symmetry_tolerance * scale) {
    std::ostringstream s;
    s << "the metric tensor is not symmetric (|g_ij - g_ji| = " << internal::power_of_two_text(asym, e)
      << " for max |g_ij| = " << internal::power_of_two_text(scale, e) << ")";
    return s.str();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(0.5 * (gs + gs.transpose()), Eigen::EigenvaluesOnly);
  if (es.info() != Eigen::Success) return "the eigenvalues of the metric tensor could not be computed";
  const double lmin = es.eigenvalues()(0), lmax = es.eigenvalues()(2); // of g 2^-e
  if (!(lmin > 0))
    return "the metric tensor is not positive definite (smallest eigenvalue " + internal::power_of_two_text(lmin, e) +
           ")";
  if (lmax > metric_tensor_max_condition * lmin) {
    std::ostringstream s;
    s << "the metric tensor is numerically not positive definite (condition number " << lmax / lmin << " > "
      << metric_tensor_max_condition << ")";
    return s.str();
  }
  if (!std::isfinite(std::ldexp(lmax, e)))
    return "the metric tensor is too large for double precision (largest eigenvalue " +
           internal::power_of_two_text(lmax, e) + ")";
  if (std::ldexp(lmin, e) < std::numeric_limits<double>::min()) {
    std::ostringstream s;
    s << "the metric tensor is too small for double precision (smallest eigenvalue "
      << internal::power_of_two_text(lmin, e) << ", below " << std::numeric_limits<double>::min()
      << ": its inverse is not representable)";
    return s.str();
  }
  return {};
}

/// \ingroup PkgCGALExtMetric
/// Checks that an isotropic size `h` gives a usable metric `g = I / h^2`:
/// `h` positive and finite, and `1 / h^2` a normal double (as
/// `check_metric_tensor()` asks), so that a size is named rather than a
/// tensor that overflowed to Inf or underflowed to zero.
///
/// \param h the size (the length of a unit edge)
/// \returns an empty string if `I / h^2` is valid, else the reason, to follow
///          "size h = ..." in a message
inline std::string check_metric_size(double h) {
  if (!(h > 0) || !std::isfinite(h)) return "is not a positive finite number";
  const double g = 1 / (h * h);
  if (!std::isfinite(g)) return "is too small: g = I / h^2 overflows";
  if (g < std::numeric_limits<double>::min()) return "is too large: g = I / h^2 underflows";
  return {};
}

/// \ingroup PkgCGALExtMetric
/// The symmetric positive-definite square root `A = g^{1/2}` (so `A A = g`),
/// from the eigendecomposition `g = V diag(l) V^T`: `A = V diag(sqrt(l)) V^T`.
///
/// The result is symmetrized, so that it is exactly symmetric. The same
/// input always gives the same bits (no randomness), so equal vertex
/// tensors give equal roots, which is what makes a constant metric field
/// have a curl of exactly zero. It is computed for `g` scaled by an even
/// power of two `2^e` and scaled back by `2^(e/2)`: exact, and no overflow
/// for entries up to the largest double.
///
/// \pre `check_metric_tensor(g)` is empty (only the symmetric part of `g` is used)
/// \param g a symmetric positive-definite 3x3 matrix
/// \returns the symmetric positive-definite root of `g`
inline Eigen::Matrix3d sqrt_spd(const Eigen::Matrix3d& g) {
  const int e = internal::metric_scale_exponent(g);
  const Eigen::Matrix3d gs = internal::times_power_of_two(g, -e);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(0.5 * (gs + gs.transpose()));
  const Eigen::Vector3d s = es.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  const Eigen::Matrix3d& V = es.eigenvectors();
  const Eigen::Matrix3d A = V * s.asDiagonal() * V.transpose();
  return internal::times_power_of_two(0.5 * (A + A.transpose()), e / 2);
}

} // namespace CGAL_ext

#endif // CGAL_EXT_METRIC_TENSOR_H
