// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#include <CGAL_ext/Hex_mesh_3.h>

#include <algorithm>
#include <stdexcept>
#include <tuple>

namespace CGAL_ext {

std::vector<std::array<std::size_t, 4>> hex_mesh_boundary_quadrilaterals(
    const std::vector<std::array<std::size_t, 8>>& hexahedra) {
  // (sorted vertices, hexahedron, local face): equal keys are the same face.
  struct Face {
    std::array<std::size_t, 4> key;
    std::size_t hex;
    int local;
  };
  std::vector<Face> faces;
  faces.reserve(6 * hexahedra.size());
  for (std::size_t h = 0; h < hexahedra.size(); ++h)
    for (int f = 0; f < 6; ++f) {
      Face face{{}, h, f};
      for (int i = 0; i < 4; ++i) face.key[std::size_t(i)] = hexahedra[h][std::size_t(hex_faces[std::size_t(f)][std::size_t(i)])];
      std::sort(face.key.begin(), face.key.end());
      faces.push_back(face);
    }
  std::sort(faces.begin(), faces.end(), [](const Face& a, const Face& b) {
    return std::tie(a.key, a.hex, a.local) < std::tie(b.key, b.hex, b.local);
  });
  std::vector<std::pair<std::size_t, int>> once; // (hex, local face) of the faces met once
  for (std::size_t i = 0; i < faces.size();) {
    std::size_t j = i + 1;
    while (j < faces.size() && faces[j].key == faces[i].key) ++j;
    if (j - i > 2) {
      const auto& k = faces[i].key;
      throw std::invalid_argument("hex_mesh_boundary_quadrilaterals: the face with vertices " + std::to_string(k[0]) +
                                  " " + std::to_string(k[1]) + " " + std::to_string(k[2]) + " " +
                                  std::to_string(k[3]) + " (0-based) belongs to " + std::to_string(j - i) +
                                  " hexahedra: the mesh is not manifold");
    }
    if (j - i == 1) once.emplace_back(faces[i].hex, faces[i].local);
    i = j;
  }
  std::sort(once.begin(), once.end());
  std::vector<std::array<std::size_t, 4>> quads;
  quads.reserve(once.size());
  for (const auto& [h, f] : once) {
    std::array<std::size_t, 4> q;
    for (int i = 0; i < 4; ++i) q[std::size_t(i)] = hexahedra[h][std::size_t(hex_faces[std::size_t(f)][std::size_t(i)])];
    quads.push_back(q);
  }
  return quads;
}

} // namespace CGAL_ext
