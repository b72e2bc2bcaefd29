// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_TEST_WALK_TEST_MESHES_H
#define CGAL_EXT_TEST_WALK_TEST_MESHES_H

// Shared by the segment walk tests: the test mesh type, Kuhn grids with
// cubes left out (non-convex domains, tunnels, cubes touching along an edge
// or at a vertex) and the bit-for-bit comparison of two walks' pieces. The
// degenerate meshes of reference/degenerate_test_meshes.h build on these.

#include <CGAL_ext/make_kuhn_grid.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <functional>
#include <string>
#include <utility>
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

/// Points and tetrahedra of a tetrahedral mesh, with a name for messages.
struct Test_mesh {
  std::string name;
  std::vector<std::array<double, 3>> points;
  std::vector<std::array<std::size_t, 4>> tets; // 0-based, positively oriented
};

/// Kuhn/Freudenthal grid of nx*ny*nz cubes of side `scale`
/// (`make_kuhn_grid()`), with a name for messages.
inline Test_mesh kuhn_grid(int nx, int ny, int nz, double scale = 6,
                           std::function<bool(int, int, int)> keep = nullptr, std::string name = "") {
  Test_mesh m;
  m.name = name.empty() ? "kuhn_" + std::to_string(nx) + "x" + std::to_string(ny) + "x" + std::to_string(nz) : name;
  IO::Medit_mesh g = make_kuhn_grid({nx, ny, nz}, scale, {0, 0, 0}, keep);
  m.points = std::move(g.vertices);
  m.tets = std::move(g.tetrahedra);
  return m;
}

} // namespace testing
} // namespace CGAL_ext

#endif // CGAL_EXT_TEST_WALK_TEST_MESHES_H
