// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_TEST_WALK_TEST_MESHES_H
#define CGAL_EXT_TEST_WALK_TEST_MESHES_H

// Shared by the segment walk tests: Kuhn grids with cubes left out
// (non-convex domains, tunnels, cubes touching along an edge or at a
// vertex) and the bit-for-bit comparison of two walks' pieces.

#include <CGAL_ext/make_kuhn_grid.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

namespace CGAL_ext {
namespace testing {

/// Whether two sequences of walk pieces are the same, bit for bit (same
/// simplices in the same vertex order, same cells, same parameters).
template <class Piece>
bool identical_pieces(const std::vector<Piece>& a, const std::vector<Piece>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].dimension != b[i].dimension || a[i].vertices != b[i].vertices || a[i].cell != b[i].cell ||
        a[i].t_in != b[i].t_in || a[i].t_out != b[i].t_out)
      return false;
  return true;
}

/// Points and tetrahedra (0-based vertex indices) of a tetrahedral mesh.
struct Walk_test_mesh {
  std::vector<std::array<double, 3>> points;
  std::vector<std::array<std::size_t, 4>> tets;
};

/// The Kuhn grid of nx * ny * nz cubes of side `scale`, keeping the cubes
/// (i, j, k) for which keep(i, j, k) is true (`CGAL_ext::make_kuhn_grid()`).
/// \param keep callable (int, int, int) -> bool
template <class Keep>
Walk_test_mesh make_kuhn_grid(int nx, int ny, int nz, Keep keep, double scale = 1.0) {
  IO::Medit_mesh g = CGAL_ext::make_kuhn_grid({nx, ny, nz}, scale, {0, 0, 0}, keep);
  return Walk_test_mesh{std::move(g.vertices), std::move(g.tetrahedra)};
}

} // namespace testing
} // namespace CGAL_ext

#endif // CGAL_EXT_TEST_WALK_TEST_MESHES_H
