// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Shared by the numerical tests: seeded random matrices, the analytic flat
// metric of doc/math.md section 6, and the boundary vertices of a tet list.
#ifndef CGAL_EXT_TEST_SUPPORT_H
#define CGAL_EXT_TEST_SUPPORT_H

#include <CGAL_ext/Metric_tensor.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <vector>

namespace CGAL_ext {
namespace testing {

using M3 = Eigen::Matrix3d;
using V3 = Eigen::Vector3d;

/// Seeded random numbers, rotations and matrices (deterministic per seed).
struct Random {
  std::mt19937 rng;
  explicit Random(unsigned seed) : rng(seed) {}
  double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); }
  M3 rotation() {
    Eigen::Quaterniond q(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
    return q.normalized().toRotationMatrix();
  }
  /// SPD with eigenvalues log-uniform in [lo, hi] and random eigenvectors.
  M3 spd(double lo, double hi) {
    V3 l;
    for (int i = 0; i < 3; ++i) l(i) = std::exp(uniform(std::log(lo), std::log(hi)));
    const M3 Q = rotation();
    return Q * l.asDiagonal() * Q.transpose();
  }
  /// Entries uniform in [-s, s].
  M3 matrix(double s) {
    M3 m;
    for (int i = 0; i < 9; ++i) m.data()[i] = uniform(-s, s);
    return m;
  }
};

/// doc/math.md section 6: Phi = (X + 0.4 sin(Y+Z), Y + 0.3 sin(Z X), Z + 0.5 sin X),
/// its Jacobian J, the metric g = J^T J, A = g^{1/2}, the curl of A and the
/// polar rotation Q = J A^{-1}; the exact transport is T(a->b) = Q(b)^T Q(a).
namespace flat_metric {

/// The map Phi itself.
inline V3 map(const V3& x) {
  return {x(0) + 0.4 * std::sin(x(1) + x(2)), x(1) + 0.3 * std::sin(x(2) * x(0)), x(2) + 0.5 * std::sin(x(0))};
}
inline M3 jacobian(const V3& x);
/// Phi^{-1}(X) by Newton's method (to 1e-15).
inline V3 map_inverse(const V3& X) {
  V3 x = X;
  for (int it = 0; it < 50; ++it) {
    const V3 r = map(x) - X;
    if (r.norm() < 1e-15) break;
    x -= jacobian(x).lu().solve(r);
  }
  return x;
}
/// Its Jacobian J.
inline M3 jacobian(const V3& x) {
  M3 J;
  const double c1 = 0.4 * std::cos(x(1) + x(2)), c2 = 0.3 * std::cos(x(2) * x(0));
  J << 1, c1, c1, c2 * x(2), 1, c2 * x(0), 0.5 * std::cos(x(0)), 0, 1;
  return J;
}
inline M3 metric(const V3& x) {
  const M3 J = jacobian(x);
  return J.transpose() * J;
}
inline M3 sqrt_metric(const V3& x) { return CGAL_ext::sqrt_spd(metric(x)); }
/// curl of the smooth A (column i is the curl of column i) by fourth-order
/// central differences (error ~ 1e-12).
inline M3 curl(const V3& x) {
  const double h = 1e-3;
  std::array<M3, 3> d;
  for (int k = 0; k < 3; ++k) {
    V3 e = V3::Zero();
    e(k) = h;
    d[k] = (-sqrt_metric(x + 2 * e) + 8 * sqrt_metric(x + e) - 8 * sqrt_metric(x - e) + sqrt_metric(x - 2 * e)) /
           (12 * h);
  }
  M3 c;
  for (int i = 0; i < 3; ++i)
    c.col(i) = V3(d[1](2, i) - d[2](1, i), d[2](0, i) - d[0](2, i), d[0](1, i) - d[1](0, i));
  return c;
}
inline M3 polar_rotation(const V3& x) { return jacobian(x) * sqrt_metric(x).inverse(); }

} // namespace flat_metric
/// The vertices of the facets that only one tetrahedron of `tets` has (1)
/// and the others (0), found from the tets alone.
inline std::vector<char> boundary_vertices(std::size_t vertices, const std::vector<std::array<std::size_t, 4>>& tets) {
  std::map<std::array<std::size_t, 3>, int> facets;
  for (const auto& t : tets)
    for (std::size_t k = 0; k < 4; ++k) {
      std::array<std::size_t, 3> f;
      for (std::size_t i = 0, j = 0; i < 4; ++i)
        if (i != k) f[j++] = t[i];
      std::sort(f.begin(), f.end());
      ++facets[f];
    }
  std::vector<char> boundary(vertices, 0);
  for (const auto& [f, count] : facets)
    if (count == 1)
      for (std::size_t v : f) boundary[v] = 1;
  return boundary;
}

} // namespace testing
} // namespace CGAL_ext

#endif
