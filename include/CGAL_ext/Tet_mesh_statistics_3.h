// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_TET_MESH_STATISTICS_3_H
#define CGAL_EXT_TET_MESH_STATISTICS_3_H

/// \file Tet_mesh_statistics_3.h
/// Counts and quality figures of the domain of a triangulation.

#include <CGAL/Bbox_3.h>
#include <CGAL/Kernel/global_functions_3.h>
#include <CGAL/Unique_hash_map.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace CGAL_ext {

/// \ingroup PkgCGALExtMesh
/// Figures of the domain of a triangulation, as `metric-frames info` prints them.
struct Tet_mesh_statistics_3 {
  std::size_t vertices = 0;        ///< vertices incident to a domain cell
  std::size_t cells = 0;           ///< domain cells (tetrahedra)
  std::size_t boundary_facets = 0; ///< facets between a domain cell and a non-domain cell
  std::size_t edges = 0;           ///< edges of the domain cells
  std::size_t components = 0;      ///< connected components of domain cells, through shared facets
  CGAL::Bbox_3 bbox;               ///< bounding box of the domain's vertices
  double volume = 0;               ///< total volume of the domain cells
  double mean_edge_length = 0;     ///< mean length of the edges of the domain cells
  double min_dihedral_angle = 0;   ///< smallest dihedral angle of a domain cell, in degrees
  double max_dihedral_angle = 0;   ///< largest dihedral angle of a domain cell, in degrees
};

/// \ingroup PkgCGALExtMesh
/// Computes the figures of the domain of `tr`.
///
/// \tparam Triangulation a CGAL `Triangulation_3`
/// \tparam Domain_predicate a unary predicate on `Triangulation::Cell_handle`,
///         true for the cells of the domain (it is never called on infinite cells)
/// \param tr the triangulation, of dimension 3
/// \param in_domain the domain predicate
template <class Triangulation, class Domain_predicate>
Tet_mesh_statistics_3 compute_tet_mesh_statistics(const Triangulation& tr, Domain_predicate in_domain) {
  using Cell_handle = typename Triangulation::Cell_handle;
  using Vertex_handle = typename Triangulation::Vertex_handle;
  Tet_mesh_statistics_3 s;
  auto domain = [&](Cell_handle c) { return !tr.is_infinite(c) && in_domain(c); };

  CGAL::Unique_hash_map<Cell_handle, std::size_t> component(std::numeric_limits<std::size_t>::max());
  CGAL::Unique_hash_map<Vertex_handle, bool> seen(false);
  double min_angle = 180, max_angle = 0;
  std::vector<Cell_handle> stack;
  for (Cell_handle c : tr.finite_cell_handles()) {
    if (!domain(c)) continue;
    ++s.cells;
    std::array<typename Triangulation::Point, 4> p;
    for (int i = 0; i < 4; ++i) {
      p[i] = c->vertex(i)->point();
      if (!seen[c->vertex(i)]) {
        seen[c->vertex(i)] = true;
        ++s.vertices;
        s.bbox += p[i].bbox();
      }
    }
    s.volume += CGAL::to_double(CGAL::volume(p[0], p[1], p[2], p[3]));
    // The dihedral angle at edge (i, j) is between the facets (i, j, k) and (i, j, l).
    static const int edge_others[6][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2}, {1, 2, 0, 3}, {1, 3, 0, 2}, {2, 3, 0, 1}};
    for (const auto& e : edge_others) {
      const double a = std::abs(CGAL::to_double(CGAL::approximate_dihedral_angle(p[e[0]], p[e[1]], p[e[2]], p[e[3]])));
      min_angle = std::min(min_angle, a);
      max_angle = std::max(max_angle, a);
    }
    for (int i = 0; i < 4; ++i)
      if (!domain(c->neighbor(i))) ++s.boundary_facets;
    if (component[c] != std::numeric_limits<std::size_t>::max()) continue;
    // Flood the new component through facets shared by two domain cells.
    const std::size_t id = s.components++;
    component[c] = id;
    stack.assign(1, c);
    while (!stack.empty()) {
      Cell_handle x = stack.back();
      stack.pop_back();
      for (int i = 0; i < 4; ++i) {
        Cell_handle n = x->neighbor(i);
        if (domain(n) && component[n] == std::numeric_limits<std::size_t>::max()) {
          component[n] = id;
          stack.push_back(n);
        }
      }
    }
  }
  double length_sum = 0;
  for (auto e = tr.finite_edges_begin(); e != tr.finite_edges_end(); ++e) {
    auto circ = tr.incident_cells(*e), done = circ;
    bool in = false;
    do {
      if (domain(circ)) {
        in = true;
        break;
      }
    } while (++circ != done);
    if (!in) continue;
    ++s.edges;
    length_sum += std::sqrt(CGAL::to_double(
        CGAL::squared_distance(e->first->vertex(e->second)->point(), e->first->vertex(e->third)->point())));
  }
  s.mean_edge_length = s.edges ? length_sum / double(s.edges) : 0;
  s.min_dihedral_angle = s.cells ? min_angle : 0;
  s.max_dihedral_angle = s.cells ? max_angle : 0;
  return s;
}

} // namespace CGAL_ext

#endif // CGAL_EXT_TET_MESH_STATISTICS_3_H
