// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_INTERNAL_SEEDED_ROTATION_H
#define CGAL_EXT_INTERNAL_SEEDED_ROTATION_H

// A pseudo-random rotation that is a function of a seed and an element index
// alone, for restarts that must not depend on the thread count or on the
// order of evaluation (no generator state is shared).

#include <CGAL_ext/internal/Octahedral_group.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cmath>
#include <cstddef>
#include <cstdint>

namespace CGAL_ext {
namespace internal {

// The n-th output of SplitMix64 from state `x` (a bijective mixer).
inline std::uint64_t split_mix_64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// A rotation about a direction uniform on the sphere (rejection sampling in
// the cube) by an angle uniform in [0, max_angle], from (seed, index).
inline Eigen::Quaterniond seeded_rotation(std::uint64_t seed, std::size_t index, double max_angle) {
  std::uint64_t state = split_mix_64(seed ^ split_mix_64(std::uint64_t(index)));
  auto uniform = [&] { // in [0, 1)
    state = split_mix_64(state);
    return double(state >> 11) * 0x1.0p-53;
  };
  Eigen::Vector3d d(1, 0, 0);
  for (int attempt = 0; attempt < 64; ++attempt) { // accepted with probability pi/6 each time
    const Eigen::Vector3d c(2 * uniform() - 1, 2 * uniform() - 1, 2 * uniform() - 1);
    const double n2 = c.squaredNorm();
    if (n2 <= 1 && n2 > 1e-6) {
      d = c / std::sqrt(n2);
      break;
    }
  }
  return oct_quaternion_exp(max_angle * uniform() * d);
}

} // namespace internal
} // namespace CGAL_ext

#endif // CGAL_EXT_INTERNAL_SEEDED_ROTATION_H
