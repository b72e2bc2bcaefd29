// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_INTERNAL_OCTAHEDRAL_GROUP_H
#define CGAL_EXT_INTERNAL_OCTAHEDRAL_GROUP_H

// The 24 rotations of the octahedral group as signed permutations, products
// with them, and the rotation helpers of Octahedral_frame.h (angle,
// quaternion exponential).

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <cmath>

namespace CGAL_ext {
namespace internal {

// The rotation angle in [0, pi], accurate also near 0 (atan2 form).
inline double oct_rotation_angle(const Eigen::Matrix3d& R) {
  const Eigen::Vector3d s(R(2, 1) - R(1, 2), R(0, 2) - R(2, 0), R(1, 0) - R(0, 1));
  return std::atan2(0.5 * s.norm(), 0.5 * (R.trace() - 1));
}

// One octahedral rotation as a signed permutation: G e_j = sign[j] e_{perm[j]}.
struct Oct_element {
  int perm[3];
  double sign[3];
};

// The 24 elements: permutations in lexicographic order, then the sign
// patterns (bit j set = column j negated) in increasing order, keeping det +1.
// Element 0 is the identity.
inline const std::array<Oct_element, 24>& oct_elements() {
  static const std::array<Oct_element, 24> table = [] {
    std::array<Oct_element, 24> t{};
    int p[3] = {0, 1, 2}, n = 0;
    do {
      const int inversions = (p[0] > p[1]) + (p[0] > p[2]) + (p[1] > p[2]);
      for (int bits = 0; bits < 8; ++bits) {
        const int negatives = (bits & 1) + ((bits >> 1) & 1) + ((bits >> 2) & 1);
        if ((inversions + negatives) % 2 != 0) continue; // det = (-1)^(inversions + negatives)
        for (int j = 0; j < 3; ++j) {
          t[n].perm[j] = p[j];
          t[n].sign[j] = ((bits >> j) & 1) ? -1.0 : 1.0;
        }
        ++n;
      }
    } while (std::next_permutation(p, p + 3));
    return t;
  }();
  return table;
}

// R G for the element g: column j of R G is sign[j] R.col(perm[j]). Exact.
inline Eigen::Matrix3d oct_times(const Eigen::Matrix3d& R, const Oct_element& g) {
  Eigen::Matrix3d out;
  for (int j = 0; j < 3; ++j) out.col(j) = g.sign[j] * R.col(g.perm[j]);
  return out;
}

// trace(M G) = sum_j sign[j] M(j, perm[j]).
inline double oct_trace_times(const Eigen::Matrix3d& M, const Oct_element& g) {
  return g.sign[0] * M(0, g.perm[0]) + g.sign[1] * M(1, g.perm[1]) + g.sign[2] * M(2, g.perm[2]);
}

// exp([d]_x) as a unit quaternion.
inline Eigen::Quaterniond oct_quaternion_exp(const Eigen::Vector3d& d) {
  const double t2 = d.squaredNorm();
  double c, k; // cos(t/2), sin(t/2)/t; the series are exact in double for t < 1e-3
  if (t2 < 1e-6) {
    c = 1 - t2 / 8 * (1 - t2 / 48);
    k = 0.5 - t2 / 48 * (1 - t2 / 80);
  } else {
    const double t = std::sqrt(t2);
    c = std::cos(0.5 * t), k = std::sin(0.5 * t) / t;
  }
  return Eigen::Quaterniond(c, k * d(0), k * d(1), k * d(2));
}

} // namespace internal
} // namespace CGAL_ext

#endif // CGAL_EXT_INTERNAL_OCTAHEDRAL_GROUP_H
