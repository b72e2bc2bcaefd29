// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_BENCHMARK_KUHN_GRID_H
#define CGAL_EXT_BENCHMARK_KUHN_GRID_H

// The benchmarks' structured mesh: CGAL_ext::make_kuhn_grid() of n^3 cubes
// of side h from (lo, lo, lo), with its interior vertices jittered.

#include <CGAL_ext/make_kuhn_grid.h>

#include <array>
#include <cstddef>
#include <random>
#include <vector>

namespace benchmark_support {

/// Appends the grid's (n+1)^3 vertices and 6 n^3 tetrahedra; interior
/// vertices are moved by up to `jitter` (in units of h) in each coordinate,
/// from a fixed seed (below 0.25 every tetrahedron keeps its orientation).
inline void kuhn_grid(int n, double lo, double h, std::vector<std::array<double, 3>>& points,
                      std::vector<std::array<std::size_t, 4>>& tets, double jitter = 0) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> move(-jitter, jitter);
  const std::size_t base = points.size();
  const CGAL_ext::IO::Medit_mesh g = CGAL_ext::make_kuhn_grid({n, n, n}, h, {lo, lo, lo});
  // Vertices come x fastest, as (i, j, k) below.
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        std::array<int, 3> c{i, j, k};
        std::array<double, 3> p;
        for (std::size_t d = 0; d < 3; ++d) {
          const double shift = jitter > 0 && c[d] > 0 && c[d] < n ? move(rng) : 0.0;
          p[d] = lo + h * (c[d] + shift);
        }
        points.push_back(p);
      }
  for (std::array<std::size_t, 4> t : g.tetrahedra) {
    for (std::size_t& v : t) v += base;
    tets.push_back(t);
  }
}

} // namespace benchmark_support

#endif // CGAL_EXT_BENCHMARK_KUHN_GRID_H
