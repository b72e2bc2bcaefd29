// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#include <CGAL_ext/IO/Medit_hex_mesh.h>

#include "write_file_atomically.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

namespace CGAL_ext {
namespace IO {

namespace {

template <std::size_t N>
void check_elements(const std::string& path, const char* name, const std::vector<std::array<std::size_t, N>>& elements,
                    const std::vector<int>& references, std::size_t points) {
  const std::string where = "write_medit_hex_mesh: " + path + ": ";
  if (!references.empty() && references.size() != elements.size())
    throw std::invalid_argument(where + std::to_string(references.size()) + " references for " +
                                std::to_string(elements.size()) + " " + name + "s");
  for (std::size_t i = 0; i < elements.size(); ++i) {
    auto sorted = elements[i];
    std::sort(sorted.begin(), sorted.end());
    const std::string element = std::string(name) + " " + std::to_string(i + 1);
    if (sorted.back() >= points)
      throw std::invalid_argument(where + element + ": vertex index " + std::to_string(sorted.back()) +
                                  " is out of range (0-based, " + std::to_string(points) + " points)");
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
      throw std::invalid_argument(where + element + " repeats a vertex");
  }
}

template <std::size_t N>
void write_section(std::FILE* f, const char* keyword, const std::vector<std::array<std::size_t, N>>& elements,
                   const std::vector<int>& references) {
  if (elements.empty()) return;
  std::fprintf(f, "\n%s\n%zu\n", keyword, elements.size());
  for (std::size_t i = 0; i < elements.size(); ++i) {
    for (std::size_t v : elements[i]) std::fprintf(f, "%zu ", v + 1);
    std::fprintf(f, "%d\n", references.empty() ? 0 : references[i]);
  }
}

} // namespace

void write_medit_hex_mesh(const std::string& path, const Hex_mesh_3& mesh) {
  for (std::size_t v = 0; v < mesh.points.size(); ++v)
    if (!mesh.points[v].allFinite())
      throw std::invalid_argument("write_medit_hex_mesh: " + path + ": vertex " + std::to_string(v + 1) +
                                  " is not finite");
  check_elements(path, "hexahedron", mesh.hexahedra, mesh.hexahedron_references, mesh.points.size());
  check_elements(path, "quadrilateral", mesh.quadrilaterals, mesh.quadrilateral_references, mesh.points.size());
  check_elements(path, "edge", mesh.edges, mesh.edge_references, mesh.points.size());
  internal::write_file_atomically(path, [&](std::FILE* f) {
    std::fprintf(f, "MeshVersionFormatted 2\n\nDimension 3\n\nVertices\n%zu\n", mesh.points.size());
    for (const Eigen::Vector3d& p : mesh.points) std::fprintf(f, "%.17g %.17g %.17g 0\n", p.x(), p.y(), p.z());
    write_section(f, "Hexahedra", mesh.hexahedra, mesh.hexahedron_references);
    write_section(f, "Quadrilaterals", mesh.quadrilaterals, mesh.quadrilateral_references);
    write_section(f, "Edges", mesh.edges, mesh.edge_references);
    std::fprintf(f, "\nEnd\n");
  });
}

} // namespace IO
} // namespace CGAL_ext
