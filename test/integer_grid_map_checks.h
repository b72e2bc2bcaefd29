// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Checks of an integer-grid map against its input, independent of how the
// map was made: across every interior face of the map's mesh, the
// neighbour's parameters are G u + t at the face's three vertices, with G
// the input's matching in the two charts and t one integer vector; and the
// map's mesh covers the input's tetrahedra, each split in positive halves.
#ifndef CGAL_EXT_TEST_INTEGER_GRID_MAP_CHECKS_H
#define CGAL_EXT_TEST_INTEGER_GRID_MAP_CHECKS_H

#include <CGAL_ext/Integer_grid_map_3.h>
#include <CGAL_ext/Octahedral_frame.h>
#include <CGAL_ext/tet_face_neighbors.h>

#include <catch2/catch.hpp>

#include <Eigen/LU>

#include <cmath>
#include <vector>

namespace CGAL_ext {
namespace testing {

inline double signed_volume(const std::vector<Eigen::Vector3d>& p, const std::array<std::size_t, 4>& q) {
  Eigen::Matrix3d D;
  D << p[q[1]] - p[q[0]], p[q[2]] - p[q[0]], p[q[3]] - p[q[0]];
  return D.determinant() / 6;
}

/// Every interior face of the map is a seam of the grid: `u_j = G u_i + t`
/// with `G = C_j M C_i^T` (`M` the input's matching between the parents,
/// the identity inside a parent; `C` the map's charts) and one integer `t`
/// at its three vertices, to `tolerance` (relative to the parameters' size).
/// Returns the number of seams: faces whose transition is not the identity
/// (`G` or `t`).
inline std::size_t require_seamless(const Integer_grid_map_input& in, const Integer_grid_map& map,
                                    double tolerance = 1e-8) {
  const auto& group = octahedral_group();
  const auto nb = tet_face_neighbors(map.tets);
  std::size_t seams = 0;
  for (std::size_t t = 0; t < map.tets.size(); ++t)
    for (std::size_t f = 0; f < 4; ++f) {
      const std::int64_t u = nb[t][f];
      if (u <= std::int64_t(t)) continue;
      const std::size_t p = map.parent[t], q = map.parent[std::size_t(u)];
      int matching = 0;
      if (p != q)
        for (std::size_t g = 0; g < 4; ++g)
          if (in.neighbors[p][g] == std::int64_t(q)) matching = in.matchings[p][g];
      const Eigen::Matrix3d G = group[std::size_t(map.chart[std::size_t(u)])] * group[std::size_t(matching)] *
                                group[std::size_t(map.chart[t])].transpose();
      Eigen::Vector3d first = Eigen::Vector3d::Zero();
      bool have = false;
      for (std::size_t c = 0; c < 4; ++c) {
        if (c == f) continue;
        std::size_t d = 0;
        while (map.tets[std::size_t(u)][d] != map.tets[t][c]) ++d;
        const Eigen::Vector3d a = map.parameters[t][c], b = map.parameters[std::size_t(u)][d];
        const Eigen::Vector3d shift = b - G * a;
        const double scale = 1 + a.norm() + b.norm();
        INFO("map tetrahedra " << t << " and " << u << ", vertex " << map.tets[t][c]);
        for (int k = 0; k < 3; ++k) REQUIRE(std::abs(shift[k] - std::round(shift[k])) <= tolerance * scale);
        if (have) REQUIRE((shift - first).norm() <= tolerance * scale);
        first = shift;
        have = true;
      }
      seams += first.norm() > 0.5 || !G.isIdentity();
    }
  return seams;
}

/// The map's mesh refines the input's: each map tetrahedron is positive and
/// inside its parent, and the children's volumes add up to their parent's.
inline void require_refinement(const Integer_grid_map_input& in, const Integer_grid_map& map) {
  REQUIRE(map.parent.size() == map.tets.size());
  REQUIRE(map.parameters.size() == map.tets.size());
  REQUIRE(map.input_parameters.size() == in.tets.size());
  std::vector<double> sum(in.tets.size(), 0.0);
  for (std::size_t t = 0; t < map.tets.size(); ++t) {
    REQUIRE(map.parent[t] < in.tets.size());
    const double v = signed_volume(map.positions, map.tets[t]);
    REQUIRE(v > 0);
    sum[map.parent[t]] += v;
  }
  for (std::size_t t = 0; t < in.tets.size(); ++t)
    REQUIRE(sum[t] == Approx(signed_volume(in.positions, in.tets[t])).epsilon(1e-9));
  for (std::size_t v = 0; v < in.positions.size(); ++v) REQUIRE(map.positions[v] == in.positions[v]);
}

} // namespace testing
} // namespace CGAL_ext

#endif
