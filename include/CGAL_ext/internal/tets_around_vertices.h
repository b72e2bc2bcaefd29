// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_INTERNAL_TETS_AROUND_VERTICES_H
#define CGAL_EXT_INTERNAL_TETS_AROUND_VERTICES_H

/// \file tets_around_vertices.h
/// The tetrahedra around each vertex of a frame field's mesh, in compressed
/// rows (shared by the repair and the straightening).

#include <cstddef>
#include <vector>

namespace CGAL_ext::internal {

// The tetrahedra of `ff` around each vertex: those of vertex v are
// star[first[v]] .. star[first[v + 1] - 1], in increasing order. `vertices`
// exceeds every vertex index.
template <class Frame_field>
void tets_around_vertices(const Frame_field& ff, std::size_t vertices, std::vector<std::size_t>& first,
                          std::vector<std::size_t>& star) {
  const std::size_t n = ff.size();
  first.assign(vertices + 1, 0);
  star.resize(4 * n);
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < 4; ++k) ++first[ff.vertex_index(ff.cell(i)->vertex(k)) + 1];
  for (std::size_t v = 0; v < vertices; ++v) first[v + 1] += first[v];
  std::vector<std::size_t> fill(first.begin(), first.end() - 1);
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < 4; ++k) star[fill[ff.vertex_index(ff.cell(i)->vertex(k))]++] = i;
}

} // namespace CGAL_ext::internal

#endif // CGAL_EXT_INTERNAL_TETS_AROUND_VERTICES_H
