// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_INTERNAL_FRAME_FIELD_COARSE_LEVEL_3_H
#define CGAL_EXT_INTERNAL_FRAME_FIELD_COARSE_LEVEL_3_H

/// \file
/// The coarse level of the frame field's linear initialisation (a two-level
/// nested iteration: the coarse solution, prolonged, starts the fine
/// conjugate gradients with the smooth part of the solution in place).

#include <CGAL_ext/Octahedral_frame.h>
#include <CGAL_ext/internal/deterministic_parallel.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Geometry>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace CGAL_ext {
namespace internal {

/// The coarse level of the initialisation: aggregates of neighbouring
/// tetrahedra (connected parts of the cells of a uniform grid), each with
/// one SH vector s_a, and s_i = D(U_i) s_a on its tetrahedra, U_i the
/// composed face transports from the aggregate's first tetrahedron along a
/// breadth-first tree. So a field parallel along the tree is represented
/// exactly, and the Galerkin operator P^T H P has the same structure as H,
/// with blocks -w D(U_i^T T(j->i) U_j) between aggregates.
struct Frame_field_coarse_level {
  /// Per tetrahedron its aggregate; per aggregate the start of its members
  /// in `members` (and the end, as `first[a + 1]`).
  std::vector<std::size_t> aggregate_of, first, members;
  /// Per tetrahedron, `U_i`.
  std::vector<Eigen::Quaterniond> U;
  /// Per aggregate, the blocks of its row of `P^T H P` (the diagonal block first).
  std::vector<std::vector<std::pair<std::size_t, Sh_matrix>>> rows;
  /// Per aggregate, the inverse of its diagonal block (the preconditioner).
  std::vector<Sh_matrix> diagonal_inverse;

  /// `y = P^T H P v`, over the aggregates in parallel.
  /// \param v one SH vector per aggregate
  /// \param y gets the product, one per aggregate (sized by the caller)
  void apply(const std::vector<Sh_vector>& v, std::vector<Sh_vector>& y) const {
    parallel_for_each_index(rows.size(), [&](std::size_t a) {
      Sh_vector sum = Sh_vector::Zero();
      for (const auto& [J, B] : rows[a]) sum += B * v[J];
      y[a] = sum;
    });
  }
};

/// Builds the coarse level of an energy.
/// \tparam Energy a `Frame_field_energy_3`
/// \param e the energy (set up, with its transports)
/// \param aggregate_size the mean number of tetrahedra per aggregate
template <class Energy>
Frame_field_coarse_level build_coarse_level(const Energy& e, int aggregate_size) {
  const std::size_t n = e.size();
  Frame_field_coarse_level c;
  // Grid cells holding about `aggregate_size` tetrahedra on average.
  Eigen::Vector3d lo = e.centroid[0], hi = e.centroid[0];
  double total_volume = 0;
  for (std::size_t i = 0; i < n; ++i) {
    lo = lo.cwiseMin(e.centroid[i]), hi = hi.cwiseMax(e.centroid[i]);
    total_volume += e.volume[i];
  }
  const double edge = std::cbrt(total_volume * aggregate_size / double(n));
  auto key = [&](std::size_t i) {
    const Eigen::Vector3d g = (e.centroid[i] - lo) / edge;
    const std::uint64_t m = 1 << 20;
    return (std::uint64_t(g(0)) * m + std::uint64_t(g(1))) * m + std::uint64_t(g(2));
  };
  const std::size_t none = std::size_t(-1);
  c.aggregate_of.assign(n, none);
  c.U.assign(n, Eigen::Quaterniond::Identity());
  c.members.reserve(n);
  for (std::size_t seed = 0; seed < n; ++seed) {
    if (c.aggregate_of[seed] != none) continue;
    const std::size_t a = c.first.size();
    c.first.push_back(c.members.size());
    const std::uint64_t k = key(seed);
    c.aggregate_of[seed] = a;
    c.members.push_back(seed);
    for (std::size_t head = c.first.back(); head < c.members.size(); ++head) {
      const std::size_t t = c.members[head];
      for (int f = 0; f < 4; ++f) {
        const std::int64_t j = e.links[t].nb[f];
        if (j < 0 || c.aggregate_of[j] != none || key(j) != k) continue;
        c.aggregate_of[j] = a;
        const int fj = e.cells[j]->index(e.cells[t]);
        const auto& L = e.links[j];
        c.U[j] = L.identity[fj] ? c.U[t] : (e.transport_in[j][fj] * c.U[t]).normalized(); // U_j = T(t->j) U_t
        c.members.push_back(j);
      }
    }
  }
  const std::size_t na = c.first.size();
  c.first.push_back(n);
  c.rows.assign(na, {});
  c.diagonal_inverse.assign(na, Sh_matrix::Identity());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, na, 16), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t a = r.begin(); a != r.end(); ++a) {
      auto& row = c.rows[a];
      row.emplace_back(a, Sh_matrix::Zero());
      for (std::size_t m = c.first[a]; m < c.first[a + 1]; ++m) {
        const std::size_t t = c.members[m];
        row[0].second.diagonal().array() += e.diagonal[t];
        if (e.constraint_of[t] >= 0) {
          const Sh_matrix D = sh_rotation(c.U[t]);
          row[0].second += D.transpose() * e.constraints[e.constraint_of[t]].B * D;
        }
        for (int f = 0; f < 4; ++f) {
          const std::int64_t j = e.links[t].nb[f];
          if (j < 0) continue;
          const Eigen::Quaterniond T = e.links[t].identity[f] ? Eigen::Quaterniond::Identity() : e.transport_in[t][f];
          const Sh_matrix block = -e.links[t].w[f] * sh_rotation(Eigen::Quaterniond(c.U[t].conjugate() * T * c.U[j]));
          const std::size_t J = c.aggregate_of[j];
          std::size_t k = 0;
          while (k < row.size() && row[k].first != J) ++k;
          if (k == row.size()) row.emplace_back(J, Sh_matrix::Zero());
          row[k].second += block;
        }
      }
      c.diagonal_inverse[a] = row[0].second.llt().solve(Sh_matrix::Identity());
    }
  });
  return c;
}


} // namespace internal
} // namespace CGAL_ext

#endif // CGAL_EXT_INTERNAL_FRAME_FIELD_COARSE_LEVEL_3_H
