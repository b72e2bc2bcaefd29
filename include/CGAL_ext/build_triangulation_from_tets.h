// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_BUILD_TRIANGULATION_FROM_TETS_H
#define CGAL_EXT_BUILD_TRIANGULATION_FROM_TETS_H

/// \file build_triangulation_from_tets.h
/// Builds a `Tet_mesh_triangulation_3` from a list of points and tetrahedra.

#include <CGAL_ext/Input_error.h>
#include <CGAL_ext/internal/Angle_around_edge_3.h>
#include <CGAL_ext/internal/Tet_mesh_overlap.h>
#include <CGAL_ext/Tet_mesh_triangulation_3.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace CGAL_ext {

/// \ingroup PkgCGALExtMesh
/// Where the tetrahedra came from, so that errors can name the file and line.
struct Tet_soup_source {
  /// The file name, or empty for in-memory data.
  std::string file;
  /// Optional: the 1-based line of each tetrahedron in `file` (same size as the tet list), or empty.
  std::vector<std::size_t> tet_lines;
  /// Optional: the 1-based line of each vertex in `file`, or empty.
  std::vector<std::size_t> vertex_lines;
};

/// \ingroup PkgCGALExtMesh
/// What `build_triangulation_from_tets()` did beyond copying the input.
struct Tet_mesh_build_report {
  /// Number of tetrahedra given with negative orientation, and re-oriented
  /// (two vertices swapped in the cell; the tet index is kept).
  std::size_t reoriented_tets = 0;
  /// Indices of the first (at most 10) re-oriented tetrahedra.
  std::vector<std::size_t> reoriented_examples;
  /// Number of vertices that no tetrahedron uses. They are not in the
  /// triangulation (a CGAL vertex needs an incident cell), and their handle
  /// in `vertex_handles` (if given) is null.
  std::size_t unused_vertices = 0;
  /// Number of boundary facets (each closed by one infinite cell).
  std::size_t boundary_facets = 0;
  /// Number of boundary edges shared by more than two boundary facets
  /// (the domain touches itself along the edge).
  std::size_t non_manifold_boundary_edges = 0;
};

namespace internal {

inline std::string tet_name(const Tet_soup_source&, std::size_t t) {
  return "tetrahedron " + std::to_string(t + 1);
}
inline std::size_t tet_line(const Tet_soup_source& src, std::size_t t) {
  return t < src.tet_lines.size() ? src.tet_lines[t] : 0;
}

// A facet key: the sorted vertex indices, with the cell and the facet index.
struct Facet_record {
  std::array<std::size_t, 3> key;
  std::size_t cell; // index into the cell handle vector
  int facet;        // index of the opposite vertex in the cell
  bool operator<(const Facet_record& o) const {
    return key != o.key ? key < o.key : (cell != o.cell ? cell < o.cell : facet < o.facet);
  }
};

} // namespace internal

/// \ingroup PkgCGALExtMesh
/// Builds the triangulation of a tetrahedral mesh, combinatorially.
///
/// The finite cells of `tr` are the tetrahedra, with `info().index` their
/// 0-based position in `tets` and `info().reference` the matching entry of
/// `references` (0 if empty). Finite vertices carry their 0-based position in
/// `points` as info. Each boundary facet is closed by an infinite cell. Where
/// more than two boundary facets share an edge, the infinite cells around it
/// are paired in the angular order around the edge, decided with exact
/// orientation predicates, so that adjacency follows the geometry.
///
/// Negatively oriented tetrahedra are re-oriented (two vertices swapped) and
/// counted in the report.
///
/// \tparam Geom_traits the kernel of the triangulation
/// \param points the vertex coordinates
/// \param tets 0-based vertex indices of each tetrahedron
/// \param references the Medit reference of each tetrahedron, or empty
/// \param tr the output; cleared first
/// \param src file and line information for error messages
/// \param vertex_handles if not null, receives the handle of each point (null for unused points)
/// \returns what was repaired or found
/// \throws Input_error for an index out of range, a repeated vertex in a
///         tetrahedron, a non-finite coordinate, a zero-volume tetrahedron, a
///         facet shared by more than two tetrahedra, two tetrahedra on the
///         same side of their common facet, parts of the mesh that overlap or
///         touch where they share no vertex (two boundary facets that meet
///         elsewhere than in their common vertices, tetrahedra that turn more
///         than once about their common edge, a boundary edge inside the
///         corner of a tetrahedron at its end, or a boundary vertex inside a
///         tetrahedron that does not use it; all decided exactly, see
///         internal/Tet_mesh_overlap.h), or an empty tet list.
template <class Geom_traits>
Tet_mesh_build_report build_triangulation_from_tets(
    const std::vector<std::array<double, 3>>& points, const std::vector<std::array<std::size_t, 4>>& tets,
    const std::vector<int>& references, Tet_mesh_triangulation_3<Geom_traits>& tr, const Tet_soup_source& src = {},
    std::vector<typename Tet_mesh_triangulation_3<Geom_traits>::Vertex_handle>* vertex_handles = nullptr) {
  using Tr = Tet_mesh_triangulation_3<Geom_traits>;
  using Vertex_handle = typename Tr::Vertex_handle;
  using Cell_handle = typename Tr::Cell_handle;
  using Point = typename Tr::Point;
  using internal::Facet_record;

  Tet_mesh_build_report report;
  if (tets.empty()) throw Input_error(src.file, 0, "", "the mesh has no tetrahedra");
  if (!references.empty() && references.size() != tets.size())
    throw Input_error(src.file, 0, "", "the number of tetrahedron references does not match the number of tetrahedra");

  const std::size_t nv = points.size();
  for (std::size_t i = 0; i < nv; ++i)
    for (double x : points[i])
      if (!std::isfinite(x))
        throw Input_error(src.file, i < src.vertex_lines.size() ? src.vertex_lines[i] : 0,
                          "vertex " + std::to_string(i + 1), "coordinate is not finite (NaN or Inf)");

  // Validate the tets and fix their orientation before touching the TDS.
  const auto orientation = tr.geom_traits().orientation_3_object();
  std::vector<std::array<std::size_t, 4>> oriented(tets);
  std::vector<char> used(nv, 0);
  for (std::size_t t = 0; t < tets.size(); ++t) {
    auto& v = oriented[t];
    for (int j = 0; j < 4; ++j) {
      if (v[j] >= nv)
        throw Input_error(src.file, internal::tet_line(src, t), internal::tet_name(src, t),
                          "vertex index " + std::to_string(v[j] + 1) + " is out of range 1.." + std::to_string(nv));
      for (int k = 0; k < j; ++k)
        if (v[k] == v[j])
          throw Input_error(src.file, internal::tet_line(src, t), internal::tet_name(src, t),
                            "vertex " + std::to_string(v[j] + 1) + " appears twice");
    }
    auto P = [&](int j) { return Point(points[v[j]][0], points[v[j]][1], points[v[j]][2]); };
    const CGAL::Orientation o = orientation(P(0), P(1), P(2), P(3));
    if (o == CGAL::COPLANAR)
      throw Input_error(src.file, internal::tet_line(src, t), internal::tet_name(src, t),
                        "zero volume (its four vertices are coplanar)");
    if (o == CGAL::NEGATIVE) {
      std::swap(v[2], v[3]);
      if (report.reoriented_examples.size() < 10) report.reoriented_examples.push_back(t);
      ++report.reoriented_tets;
    }
    for (int j = 0; j < 4; ++j) used[v[j]] = 1;
  }

  tr.clear();
  auto& tds = tr.tds();
  tds.clear();
  tds.set_dimension(3);
  const Vertex_handle inf = tds.create_vertex();
  tr.set_infinite_vertex(inf);

  std::vector<Vertex_handle> vh(nv);
  for (std::size_t i = 0; i < nv; ++i) {
    if (!used[i]) {
      ++report.unused_vertices;
      continue;
    }
    vh[i] = tds.create_vertex();
    vh[i]->set_point(Point(points[i][0], points[i][1], points[i][2]));
    vh[i]->info() = i;
  }

  // Finite cells, and their facets keyed by sorted vertex indices.
  std::vector<Cell_handle> cells;
  cells.reserve(tets.size() + tets.size() / 2);
  std::vector<Facet_record> facets;
  facets.reserve(4 * tets.size());
  for (std::size_t t = 0; t < oriented.size(); ++t) {
    const auto& v = oriented[t];
    Cell_handle c = tds.create_cell(vh[v[0]], vh[v[1]], vh[v[2]], vh[v[3]]);
    c->info().index = static_cast<std::int64_t>(t);
    c->info().reference = references.empty() ? 0 : references[t];
    for (int j = 0; j < 4; ++j) vh[v[j]]->set_cell(c);
    for (int j = 0; j < 4; ++j) {
      std::array<std::size_t, 3> k{v[(j + 1) % 4], v[(j + 2) % 4], v[(j + 3) % 4]};
      std::sort(k.begin(), k.end());
      facets.push_back({k, t, j});
    }
    cells.push_back(c);
  }
  std::sort(facets.begin(), facets.end());

  // Pair interior facets; collect boundary facets.
  std::vector<std::pair<std::size_t, int>> boundary; // (cell, facet)
  for (std::size_t i = 0; i < facets.size();) {
    std::size_t j = i + 1;
    while (j < facets.size() && facets[j].key == facets[i].key) ++j;
    if (j - i > 2) {
      std::string list;
      for (std::size_t k = i; k < j && k < i + 4; ++k) list += (k > i ? ", " : "") + std::to_string(facets[k].cell + 1);
      throw Input_error(src.file, internal::tet_line(src, facets[i + 2].cell), internal::tet_name(src, facets[i + 2].cell),
                        "the facet (" + std::to_string(facets[i].key[0] + 1) + ", " + std::to_string(facets[i].key[1] + 1) +
                            ", " + std::to_string(facets[i].key[2] + 1) + ") is shared by " + std::to_string(j - i) +
                            " tetrahedra (" + list + "): tetrahedra overlap");
    }
    if (j - i == 2) {
      Cell_handle a = cells[facets[i].cell], b = cells[facets[i + 1].cell];
      // Two tets on the same side of their common facet overlap.
      if (a->vertex(facets[i].facet) == b->vertex(facets[i + 1].facet))
        throw Input_error(src.file, internal::tet_line(src, facets[i + 1].cell), internal::tet_name(src, facets[i + 1].cell),
                          "duplicates tetrahedron " + std::to_string(facets[i].cell + 1));
      tds.set_adjacency(a, facets[i].facet, b, facets[i + 1].facet);
    } else {
      boundary.push_back({facets[i].cell, facets[i].facet});
    }
    i = j;
  }
  // Both cells of an interior facet must lie on opposite sides of it.
  for (std::size_t t = 0; t < cells.size(); ++t) {
    Cell_handle c = cells[t];
    for (int j = 0; j < 4; ++j) {
      Cell_handle n = c->neighbor(j);
      if (n == Cell_handle() || n->info().index < static_cast<std::int64_t>(t)) continue;
      const int jn = n->index(c);
      // With both cells positively oriented, the mirror vertex is on the other
      // side exactly when orientation(facet of c as seen from c, mirror) < 0.
      std::array<Point, 4> p;
      for (int k = 0; k < 4; ++k) p[k] = c->vertex(k)->point();
      p[j] = n->vertex(jn)->point();
      if (orientation(p[0], p[1], p[2], p[3]) != CGAL::NEGATIVE)
        throw Input_error(src.file, internal::tet_line(src, static_cast<std::size_t>(n->info().index)),
                          internal::tet_name(src, static_cast<std::size_t>(n->info().index)),
                          "overlaps tetrahedron " + std::to_string(t + 1) + " across their common facet");
    }
  }

  // Parts of the mesh that overlap, or touch where they share no vertex
  // (internal/Tet_mesh_overlap.h): tetrahedra turning about an edge more
  // than once (a fold, named by its edge), ...
  if (const auto hit = internal::find_overlap_around_edge(points, oriented)) {
    const std::size_t t = hit->tets[1];
    throw Input_error(src.file, internal::tet_line(src, t), internal::tet_name(src, t),
                      "overlaps tetrahedron " + std::to_string(hit->tets[0] + 1) + " about their common edge (" +
                          std::to_string(hit->edge[0] + 1) + ", " + std::to_string(hit->edge[1] + 1) +
                          "): the tetrahedra around this edge turn about it more than once (the mesh folds over itself)");
  }
  // ... the boundary meeting itself, ...
  auto facet_text = [&](std::array<std::size_t, 3> t) {
    std::sort(t.begin(), t.end());
    return "(" + std::to_string(t[0] + 1) + ", " + std::to_string(t[1] + 1) + ", " + std::to_string(t[2] + 1) + ")";
  };
  std::vector<std::array<std::size_t, 3>> triangles;
  triangles.reserve(boundary.size());
  for (const auto& bf : boundary) {
    std::array<std::size_t, 3> t;
    for (int k = 0; k < 3; ++k) t[std::size_t(k)] = cells[bf.first]->vertex((bf.second + 1 + k) & 3)->info();
    triangles.push_back(t);
  }
  if (const auto hit = internal::find_boundary_overlap(points, triangles)) {
    const std::size_t ta = boundary[(*hit)[0]].first, tb = boundary[(*hit)[1]].first;
    // Two distinct vertices at one point, the commonest cause, said as such.
    std::string same_point;
    for (std::size_t a : triangles[(*hit)[0]])
      for (std::size_t b : triangles[(*hit)[1]])
        if (a != b && same_point.empty() && points[a] == points[b])
          same_point = "; vertices " + std::to_string(std::min(a, b) + 1) + " and " + std::to_string(std::max(a, b) + 1) +
                       " have the same coordinates: a duplicated vertex, to be merged";
    throw Input_error(src.file, internal::tet_line(src, std::max(ta, tb)), internal::tet_name(src, std::max(ta, tb)),
                      "overlaps or touches tetrahedron " + std::to_string(std::min(ta, tb) + 1) +
                          " where they share no vertex: their boundary facets " + facet_text(triangles[(*hit)[ta < tb ? 1 : 0]]) +
                          " and " + facet_text(triangles[(*hit)[ta < tb ? 0 : 1]]) +
                          " meet elsewhere than in their common vertices (parts of a mesh must share the vertices where "
                          "they touch)" + same_point);
  }
  // ... the corners around a boundary vertex overlapping, ...
  if (const auto hit = internal::find_overlap_around_vertex(points, oriented, triangles)) {
    // The tetrahedron of the boundary edge (the first that uses both ends).
    std::size_t edge_tet = 0;
    while (std::count(oriented[edge_tet].begin(), oriented[edge_tet].end(), hit->vertex) == 0 ||
           std::count(oriented[edge_tet].begin(), oriented[edge_tet].end(), hit->edge_end) == 0)
      ++edge_tet;
    const std::size_t t = std::max(edge_tet, hit->tet);
    const std::string p = std::to_string(hit->vertex + 1), q = std::to_string(hit->edge_end + 1);
    throw Input_error(src.file, internal::tet_line(src, t), internal::tet_name(src, t),
                      "overlaps tetrahedron " + std::to_string(std::min(edge_tet, hit->tet) + 1) +
                          " near their common vertex " + p + ": the boundary edge (" + p + ", " + q + ") of tetrahedron " +
                          std::to_string(edge_tet + 1) + " lies in the corner of tetrahedron " +
                          std::to_string(hit->tet + 1) + " at vertex " + p +
                          " (parts of the mesh that meet at a vertex overlap there)");
  }
  // ... and a part inside another one, with no boundary contact.
  {
    std::vector<std::size_t> boundary_vertices;
    for (const auto& t : triangles) boundary_vertices.insert(boundary_vertices.end(), t.begin(), t.end());
    std::sort(boundary_vertices.begin(), boundary_vertices.end());
    boundary_vertices.erase(std::unique(boundary_vertices.begin(), boundary_vertices.end()), boundary_vertices.end());
    if (const auto hit = internal::find_vertex_inside_tet(points, oriented, boundary_vertices))
      throw Input_error(src.file, internal::tet_line(src, hit->tet), internal::tet_name(src, hit->tet),
                        "contains vertex " + std::to_string(hit->vertex + 1) +
                            ", which it does not use: parts of the mesh overlap (a mesh must share the vertices where "
                            "its parts touch)");
  }

  // Close every boundary facet with an infinite cell (inf, then the facet
  // seen from outside, so that the cell is positively oriented in CGAL's sense).
  report.boundary_facets = boundary.size();
  std::vector<Cell_handle> inf_cells;
  inf_cells.reserve(boundary.size());
  for (const auto& bf : boundary) {
    Cell_handle c = cells[bf.first];
    const int i = bf.second;
    // Vertices of facet i in the orientation induced by c; an infinite cell
    // (inf, a, b, c) mirrors a finite one with inf in place of the apex.
    Vertex_handle a = c->vertex((i + 1) & 3), b = c->vertex((i + 2) & 3), d = c->vertex((i + 3) & 3);
    Cell_handle ic = (i % 2 == 0) ? tds.create_cell(inf, b, a, d) : tds.create_cell(inf, a, b, d);
    tds.set_adjacency(ic, 0, c, i);
    inf_cells.push_back(ic);
    inf->set_cell(ic);
  }

  // Pair the infinite cells across the facets that contain the infinite
  // vertex, keyed by the boundary edge.
  struct Edge_record {
    std::array<std::size_t, 2> key;
    std::size_t cell; // index in inf_cells
    int facet;
    bool operator<(const Edge_record& o) const {
      return key != o.key ? key < o.key : (cell != o.cell ? cell < o.cell : facet < o.facet);
    }
  };
  std::vector<Edge_record> edges;
  edges.reserve(3 * inf_cells.size());
  for (std::size_t k = 0; k < inf_cells.size(); ++k)
    for (int j = 1; j < 4; ++j) {
      std::array<std::size_t, 2> e{inf_cells[k]->vertex(j == 1 ? 2 : 1)->info(),
                                   inf_cells[k]->vertex(j == 3 ? 2 : 3)->info()};
      if (e[1] < e[0]) std::swap(e[0], e[1]);
      edges.push_back({e, k, j});
    }
  std::sort(edges.begin(), edges.end());
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i + 1;
    while (j < edges.size() && edges[j].key == edges[i].key) ++j;
    const std::size_t n = j - i;
    if (n % 2 != 0)
      throw Input_error(src.file, 0, "edge (" + std::to_string(edges[i].key[0] + 1) + ", " + std::to_string(edges[i].key[1] + 1) + ")",
                        "an odd number of boundary facets meet at this edge: the boundary is not closed");
    if (n == 2) {
      tds.set_adjacency(inf_cells[edges[i].cell], edges[i].facet, inf_cells[edges[i + 1].cell], edges[i + 1].facet);
    } else {
      ++report.non_manifold_boundary_edges;
      // Sort the boundary facets around the edge (a, b) by angle, exactly, and
      // pair each facet with the next one across every outside sector.
      const Point pa = vh[edges[i].key[0]]->point(), pb = vh[edges[i].key[1]]->point();
      struct Around {
        Point apex;   // third vertex of the boundary triangle
        int half;     // 0: [0, pi) from the reference, 1: [pi, 2 pi)
        bool outside_ccw; // the sector that follows it counterclockwise is outside
        std::size_t rec;
      };
      std::vector<Around> around;
      for (std::size_t k = i; k < j; ++k) {
        Cell_handle ic = inf_cells[edges[k].cell];
        Cell_handle fc = ic->neighbor(0);
        // apex: the vertex of the boundary triangle that is not on the edge
        Point apex;
        for (int m = 1; m < 4; ++m) {
          const std::size_t id = ic->vertex(m)->info();
          if (id != edges[i].key[0] && id != edges[i].key[1]) apex = ic->vertex(m)->point();
        }
        const Point inner = fc->vertex(fc->index(ic))->point();
        // The domain cell lies clockwise of the triangle iff inner is on the negative side.
        const bool outside_ccw = orientation(pa, pb, apex, inner) == CGAL::NEGATIVE;
        around.push_back({apex, 0, outside_ccw, k});
      }
      const internal::Angle_around_edge_3<Geom_traits> angle(pa, pb, around.front().apex, tr.geom_traits());
      for (auto& x : around) x.half = angle.half(x.apex);
      std::sort(around.begin(), around.end(),
                [&](const Around& u, const Around& w) { return angle.less(u.apex, u.half, w.apex, w.half); });
      for (std::size_t m = 0; m < around.size(); ++m) {
        const Around& u = around[m];
        const Around& w = around[(m + 1) % around.size()];
        if (!u.outside_ccw) continue;
        if (w.outside_ccw) // cannot happen after find_overlap_around_edge()
          throw Input_error(src.file, 0, "edge (" + std::to_string(edges[i].key[0] + 1) + ", " + std::to_string(edges[i].key[1] + 1) + ")",
                            "the tetrahedra around this edge overlap");
        tds.set_adjacency(inf_cells[edges[u.rec].cell], edges[u.rec].facet, inf_cells[edges[w.rec].cell], edges[w.rec].facet);
      }
    }
    i = j;
  }

  if (vertex_handles) *vertex_handles = std::move(vh);
  return report;
}

} // namespace CGAL_ext

#endif // CGAL_EXT_BUILD_TRIANGULATION_FROM_TETS_H
