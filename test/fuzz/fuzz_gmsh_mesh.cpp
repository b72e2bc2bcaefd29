// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Fuzzes the Gmsh .msh reader: any input gives a mesh whose indices are all
// in range, with finite coordinates, tetrahedra of 4 distinct vertices and
// one reference per element, or an Input_error naming the file.
#include "fuzz_input.h"

#include <CGAL_ext/IO/Gmsh_mesh.h>

#include <cmath>
#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = fuzz::write_input(data, size, ".msh");
  fuzz::expect_input_error_only(
      [&] {
        const CGAL_ext::IO::Medit_mesh m = CGAL_ext::IO::read_gmsh_mesh(path);
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
      },
      path);
  return 0;
}
