// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_TEST_WALK_TEST_MESHES_H
#define CGAL_EXT_TEST_WALK_TEST_MESHES_H

// Shared by the segment walk tests: Kuhn (Freudenthal) grids, each unit
// cube split into 6 tetrahedra around its main diagonal, so that the grid
// stays conforming when cubes are removed (non-convex domains, tunnels,
// cubes touching along an edge or at a vertex); and the bit-for-bit
// comparison of two walks' pieces.

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
/// (i, j, k) for which keep(i, j, k) is true. Only used vertices are output;
/// all tetrahedra are positively oriented.
/// \param keep callable (int, int, int) -> bool
template <class Keep>
Walk_test_mesh make_kuhn_grid(int nx, int ny, int nz, Keep keep, double scale = 1.0) {
  Walk_test_mesh m;
  const auto vid = [&](int i, int j, int k) { return (std::size_t(i) * (ny + 1) + j) * (nz + 1) + k; };
  std::vector<std::array<std::size_t, 4>> raw;
  static const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  static const bool odd[6] = {false, true, true, false, false, true};
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j)
      for (int k = 0; k < nz; ++k) {
        if (!keep(i, j, k)) continue;
        for (int p = 0; p < 6; ++p) {
          int c[3] = {i, j, k};
          std::array<std::size_t, 4> t;
          t[0] = vid(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[perms[p][s]];
            t[s + 1] = vid(c[0], c[1], c[2]);
          }
          if (odd[p]) std::swap(t[0], t[1]);
          raw.push_back(t);
        }
      }
  std::vector<std::size_t> remap(std::size_t(nx + 1) * (ny + 1) * (nz + 1), std::size_t(-1));
  for (auto& t : raw)
    for (auto& v : t) {
      if (remap[v] == std::size_t(-1)) {
        remap[v] = m.points.size();
        const int k = int(v % (nz + 1)), j = int((v / (nz + 1)) % (ny + 1)), i = int(v / ((nz + 1) * (ny + 1)));
        m.points.push_back({i * scale, j * scale, k * scale});
      }
      v = remap[v];
    }
  m.tets = std::move(raw);
  return m;
}

} // namespace testing
} // namespace CGAL_ext

#endif // CGAL_EXT_TEST_WALK_TEST_MESHES_H
