// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_CONNECTION_3_H
#define CGAL_EXT_CONNECTION_3_H

/// \file Connection_3.h
/// The connection one-form `W` of a metric square root `A` (doc/math.md section 3):
/// the solution of `M(A) vec(W) = vec(curl A)`, in closed form.

#include <Eigen/Core>
#include <Eigen/LU>

#include <cmath>

namespace CGAL_ext {

/// \ingroup PkgCGALExtMetric
/// The cross-product matrix: `cross_product_matrix(u) * v == u.cross(v)`.
/// \param u a 3-vector
/// \returns `[u]_x = [[0, -u3, u2], [u3, 0, -u1], [-u2, u1, 0]]`
inline Eigen::Matrix3d cross_product_matrix(const Eigen::Vector3d& u) {
  Eigen::Matrix3d m;
  m << 0, -u(2), u(1), u(2), 0, -u(0), -u(1), u(0), 0;
  return m;
}

/// \ingroup PkgCGALExtMetric
/// The 9x9 matrix `M(A)` of doc/math.md section 3,
/// `M(A) = [[0, -[A^3]_x, [A^2]_x], [[A^3]_x, 0, -[A^1]_x], [-[A^2]_x, [A^1]_x, 0]]`,
/// where `A^i` is column `i` of `A`. It acts on `vec(W) = [W_1; W_2; W_3]`
/// (columns stacked). `det M(A) = -2 det(A)^3`.
///
/// Only needed to check `connection_one_form()`; the library uses the closed form.
/// \param A the metric square root at a point (3x3, symmetric positive definite)
/// \returns the 9x9 matrix
inline Eigen::Matrix<double, 9, 9> connection_system_matrix(const Eigen::Matrix3d& A) {
  Eigen::Matrix<double, 9, 9> M = Eigen::Matrix<double, 9, 9>::Zero();
  const Eigen::Matrix3d X1 = cross_product_matrix(A.col(0));
  const Eigen::Matrix3d X2 = cross_product_matrix(A.col(1));
  const Eigen::Matrix3d X3 = cross_product_matrix(A.col(2));
  M.block<3, 3>(0, 3) = -X3;
  M.block<3, 3>(0, 6) = X2;
  M.block<3, 3>(3, 0) = X3;
  M.block<3, 3>(3, 6) = -X1;
  M.block<3, 3>(6, 0) = -X2;
  M.block<3, 3>(6, 3) = X1;
  return M;
}

/// \ingroup PkgCGALExtMetric
/// The connection one-form `W` at a point, from the metric square root `A`
/// and its curl there (doc/math.md section 3), in closed form.
///
/// `W` is the unique solution of `M(A) vec(W) = vec(curl A)`. Column `W_k`
/// holds the (dx, dy, dz) coefficients of the k-th of
/// `(omega_23, omega_31, omega_12)`, so that along a path the rotation
/// generator is ``u = W^T x'``.
///
/// Closed form (derived with the Koszul formula in the coframe `theta = A dp`,
/// whose dual frame is `A^{-1}`; checked against the 9x9 solve in the tests):
/// \code
///   N = curlA^T A / det(A)          // N(i,m) = (curl A)^i . A^m / det A
///   W = A (tr(N)/2 I - N)
/// \endcode
/// About 80 flops, against about 500 for a 9x9 LU. A zero curl gives exactly
/// `W == 0`.
///
/// `W` does not change when `A` and its curl are scaled together (`N`
/// scales by `1/s`, `A` by `s`), so both are first divided by the power of
/// two nearest their largest entry: exact, so the result is the same bits
/// where `det(A)` is in double's range, and it stays finite for any finite
/// `A`, `1e-150 I` and `1e150 I` included (where `det(A)` alone would
/// underflow or overflow).
///
/// \param A the metric square root `g^{1/2}` at the point (3x3, symmetric positive definite)
/// \param curlA the 3x3 matrix whose column `i` is `curl` of column `i` of `A` (doc/math.md section 2)
/// \returns `W` (3x3)
inline Eigen::Matrix3d connection_one_form(const Eigen::Matrix3d& A, const Eigen::Matrix3d& curlA) {
  int e = 0;
  std::frexp(A.cwiseAbs().maxCoeff(), &e);
  const Eigen::Matrix3d As = A * std::ldexp(1.0, -e), Cs = curlA * std::ldexp(1.0, -e);
  const Eigen::Matrix3d N = (Cs.transpose() * As) / As.determinant();
  return As * (0.5 * N.trace() * Eigen::Matrix3d::Identity() - N);
}

/// \ingroup PkgCGALExtMetric
/// The connection one-form by solving the 9x9 system `M(A) vec(W) = vec(curl A)`
/// with partial-pivoting LU. A reference for `connection_one_form()`; slower.
/// \param A the metric square root (3x3, symmetric positive definite)
/// \param curlA the curl of `A`, column by column
/// \returns `W` (3x3)
inline Eigen::Matrix3d connection_one_form_by_solve(const Eigen::Matrix3d& A, const Eigen::Matrix3d& curlA) {
  const Eigen::Matrix<double, 9, 1> rhs = Eigen::Map<const Eigen::Matrix<double, 9, 1>>(curlA.data());
  const Eigen::Matrix<double, 9, 1> w = connection_system_matrix(A).partialPivLu().solve(rhs);
  return Eigen::Map<const Eigen::Matrix3d>(w.data()); // Eigen is column-major: vec stacks columns
}

} // namespace CGAL_ext

#endif // CGAL_EXT_CONNECTION_3_H
