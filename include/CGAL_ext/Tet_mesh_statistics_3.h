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
#include <array>
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
  long double volume = 0;           ///< total volume of the domain cells
  long double mean_edge_length = 0; ///< mean length of the edges of the domain cells
  double min_dihedral_angle = 0;   ///< smallest dihedral angle of a domain cell, in degrees
  double max_dihedral_angle = 0;   ///< largest dihedral angle of a domain cell, in degrees
};

namespace internal {
// Coordinate differences, volumes and angles in long double: on x86-64 its
// exponent range (about 1e+-4932) holds the volume of any mesh with double
// coordinates (up to (2e308)^3), so the figures are right at every scale,
// from subnormal coordinates to 1e308. (Where long double is double, the
// extreme scales overflow to inf or underflow to 0, as double does.)
using Stat_vector = std::array<long double, 3>;
template <class Point>
Stat_vector stat_difference(const Point& a, const Point& b) {
  return {static_cast<long double>(CGAL::to_double(a.x())) - static_cast<long double>(CGAL::to_double(b.x())),
          static_cast<long double>(CGAL::to_double(a.y())) - static_cast<long double>(CGAL::to_double(b.y())),
          static_cast<long double>(CGAL::to_double(a.z())) - static_cast<long double>(CGAL::to_double(b.z()))};
}
inline Stat_vector stat_cross(const Stat_vector& a, const Stat_vector& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline long double stat_dot(const Stat_vector& a, const Stat_vector& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
// Dihedral angle in degrees at edge (p, q) between the facets (p, q, r) and (p, q, s).
template <class Point>
double stat_dihedral_angle(const Point& p, const Point& q, const Point& r, const Point& s) {
  const Stat_vector e = stat_difference(q, p);
  const Stat_vector n1 = stat_cross(e, stat_difference(r, p)), n2 = stat_cross(e, stat_difference(s, p));
  // atan2(|n1 x n2|, n1 . n2): accurate near 0 and 180 degrees too
  const Stat_vector c = stat_cross(n1, n2);
  return static_cast<double>(std::atan2(std::sqrt(stat_dot(c, c)), stat_dot(n1, n2)) * 180.0L / 3.141592653589793238462643383279502884L);
}
// The six dihedral angles of the tetrahedron (p0, p1, p2, p3), in degrees:
// the one at edge (i, j) is between the facets (i, j, k) and (i, j, l).
template <class Point>
std::array<double, 6> stat_dihedral_angles(const std::array<Point, 4>& p) {
  static const int edge_others[6][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2}, {1, 2, 0, 3}, {1, 3, 0, 2}, {2, 3, 0, 1}};
  std::array<double, 6> angles;
  for (int k = 0; k < 6; ++k) {
    const int* e = edge_others[k];
    angles[std::size_t(k)] = stat_dihedral_angle(p[std::size_t(e[0])], p[std::size_t(e[1])], p[std::size_t(e[2])], p[std::size_t(e[3])]);
  }
  return angles;
}
} // namespace internal

/// \ingroup PkgCGALExtMesh
/// Computes the figures of the domain of `tr`. Volumes, lengths and angles
/// are computed in `long double` from the double coordinates, so that they
/// are right at every coordinate scale (on x86-64).
///
/// \tparam Triangulation a CGAL `Triangulation_3`
/// \tparam Domain_predicate a unary predicate on `Triangulation::Cell_handle`,
///         true for the cells of the domain (it is never called on infinite cells)
/// \param tr the triangulation, of dimension 3
/// \param in_domain the domain predicate
/// \returns the counts, bounding box, volume, mean edge length and dihedral angles of the domain
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
    {
      const internal::Stat_vector a = internal::stat_difference(p[1], p[0]), b = internal::stat_difference(p[2], p[0]),
                                  c = internal::stat_difference(p[3], p[0]);
      s.volume += std::abs(internal::stat_dot(a, internal::stat_cross(b, c))) / 6;
    }
    for (const double a : internal::stat_dihedral_angles(p)) {
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
  long double length_sum = 0;
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
    const internal::Stat_vector d = internal::stat_difference(e->first->vertex(e->second)->point(), e->first->vertex(e->third)->point());
    length_sum += std::sqrt(internal::stat_dot(d, d));
  }
  s.mean_edge_length = s.edges ? length_sum / static_cast<long double>(s.edges) : 0;
  s.min_dihedral_angle = s.cells ? min_angle : 0;
  s.max_dihedral_angle = s.cells ? max_angle : 0;
  return s;
}

} // namespace CGAL_ext

#endif // CGAL_EXT_TET_MESH_STATISTICS_3_H
