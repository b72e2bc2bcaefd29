// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_MAKE_KUHN_GRID_H
#define CGAL_EXT_MAKE_KUHN_GRID_H

/// \file make_kuhn_grid.h
/// Kuhn (Freudenthal) grids: structured tetrahedral meshes of boxes, and of
/// unions of grid cubes, for tests, examples and benchmarks.

#include <CGAL_ext/IO/Medit_mesh.h>

#include <array>
#include <cstddef>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace CGAL_ext {

/// \ingroup PkgCGALExtMesh
/// The Kuhn (Freudenthal) grid of `cubes[0] x cubes[1] x cubes[2]` cubes of
/// side `spacing` from `origin`: each cube is split into the 6 tetrahedra
/// around its diagonal from `(i, j, k)` to `(i + 1, j + 1, k + 1)` (the
/// monotone lattice paths between them), the same way in every cube, so
/// that the mesh stays conforming when cubes are left out. Leaving cubes out
/// gives non-convex domains, tunnels, and parts that touch along an edge or
/// at a vertex only (`keep`).
///
/// Vertices are numbered with `x` fastest, then `y`, then `z`; vertices of
/// no kept cube are dropped (the others keep their order). Tetrahedra come
/// cube by cube in the same order, six per cube, all positively oriented.
/// References are 0. The result is what `tetrahedralize_builtin()` or
/// `IO::read_medit_mesh()` give: write it with `IO::write_medit_mesh()` or
/// build a triangulation from it (`read_tet_mesh()` does both steps for files).
/// \param cubes the number of cubes along x, y and z (each at least 1)
/// \param spacing the side of a cube (positive)
/// \param origin the corner of the grid with the smallest coordinates
/// \param keep which cubes `(i, j, k)` to keep (all if empty)
/// \returns the mesh
/// \throws std::invalid_argument if a count is below 1, `spacing` is not
///         positive and finite, or no cube is kept
inline IO::Medit_mesh make_kuhn_grid(const std::array<int, 3>& cubes, double spacing = 1,
                                     const std::array<double, 3>& origin = {0, 0, 0},
                                     const std::function<bool(int, int, int)>& keep = {}) {
  const int nx = cubes[0], ny = cubes[1], nz = cubes[2];
  if (nx < 1 || ny < 1 || nz < 1) throw std::invalid_argument("make_kuhn_grid: every cube count must be at least 1");
  if (!(spacing > 0) || !(spacing < 1e300)) throw std::invalid_argument("make_kuhn_grid: spacing must be positive and finite");
  auto id = [&](int i, int j, int k) { return (std::size_t(k) * std::size_t(ny + 1) + std::size_t(j)) * std::size_t(nx + 1) + std::size_t(i); };
  // The 6 paths, and whether each is an odd permutation (a negatively
  // oriented tetrahedron, made positive by swapping its last two vertices).
  static const int paths[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  static const bool odd[6] = {false, true, true, false, false, true};
  IO::Medit_mesh m;
  std::vector<std::size_t> index(std::size_t(nx + 1) * std::size_t(ny + 1) * std::size_t(nz + 1), 0);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        if (keep && !keep(i, j, k)) continue;
        for (int p = 0; p < 6; ++p) {
          std::array<int, 3> c{i, j, k};
          std::array<std::size_t, 4> t;
          t[0] = id(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[paths[p][s]];
            t[std::size_t(s + 1)] = id(c[0], c[1], c[2]);
          }
          if (odd[p]) std::swap(t[2], t[3]);
          for (std::size_t v : t) index[v] = 1;
          m.tetrahedra.push_back(t);
        }
      }
  if (m.tetrahedra.empty()) throw std::invalid_argument("make_kuhn_grid: no cube is kept");
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        std::size_t& v = index[id(i, j, k)];
        if (!v) continue;
        v = m.vertices.size();
        m.vertices.push_back({origin[0] + spacing * i, origin[1] + spacing * j, origin[2] + spacing * k});
      }
  for (auto& t : m.tetrahedra)
    for (std::size_t& v : t) v = index[v];
  m.vertex_references.assign(m.vertices.size(), 0);
  m.tetrahedron_references.assign(m.tetrahedra.size(), 0);
  return m;
}

} // namespace CGAL_ext

#endif // CGAL_EXT_MAKE_KUHN_GRID_H
