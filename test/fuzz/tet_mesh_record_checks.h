// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// What every tet mesh reader promises of the record it returns (the Gmsh and
// legacy VTK harnesses): aborts, so that libFuzzer keeps the input, unless
// the coordinates are finite, every index is in range, each tetrahedron has
// 4 distinct vertices and each element one reference.
#ifndef CGAL_EXT_TEST_FUZZ_TET_MESH_RECORD_CHECKS_H
#define CGAL_EXT_TEST_FUZZ_TET_MESH_RECORD_CHECKS_H

#include <CGAL_ext/IO/Medit_mesh.h>

#include <cmath>
#include <cstdlib>

namespace fuzz {

inline void check_tet_mesh_record(const CGAL_ext::IO::Medit_mesh& m) {
  const std::size_t n = m.vertices.size();
  for (const auto& p : m.vertices)
    for (double c : p)
      if (!std::isfinite(c)) std::abort();
  if (m.tetrahedra.empty() || m.tetrahedron_references.size() != m.tetrahedra.size() ||
      m.triangle_references.size() != m.triangles.size() || m.edge_references.size() != m.edges.size())
    std::abort();
  for (const auto& t : m.tetrahedra)
    for (std::size_t a = 0; a < 4; ++a) {
      if (t[a] >= n) std::abort();
      for (std::size_t b = a + 1; b < 4; ++b)
        if (t[a] == t[b]) std::abort();
    }
  for (const auto& t : m.triangles)
    for (std::size_t v : t)
      if (v >= n) std::abort();
  for (const auto& e : m.edges)
    for (std::size_t v : e)
      if (v >= n) std::abort();
}

} // namespace fuzz

#endif
