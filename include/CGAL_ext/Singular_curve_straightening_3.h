// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_SINGULAR_CURVE_STRAIGHTENING_3_H
#define CGAL_EXT_SINGULAR_CURVE_STRAIGHTENING_3_H

/// \file Singular_curve_straightening_3.h
/// Moves the interior vertices of a frame field's singular curves so that
/// the curves zigzag less: an integer-grid map lays every curve on a straight
/// grid line, and the tetrahedra along a zigzag must shear to follow it.

#include <CGAL_ext/Frame_field_matchings_3.h>
#include <CGAL_ext/Frame_field_singularities_3.h>
#include <CGAL_ext/Tet_mesh_statistics_3.h>
#include <CGAL_ext/internal/tets_around_vertices.h>

#include <CGAL/enum.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>
#include <vector>

namespace CGAL_ext {

namespace internal {

// The defects that moved vertices made, for the straightening's guard: the
// ends of the edges non-meshable in `after` and not in `before`, and the
// non-meshable nodes and curve turns of `after` (with their edges' other
// ends, since their types depend on those edges) that were neither that
// nor the end of a non-meshable edge in `before`. `before` and `after` are
// the same edges (by their vertices) typed with other positions; `place(v)`
// tells where vertex v lies. Unsorted, with repeats.
template <class Place>
std::vector<std::size_t> new_non_meshable_vertices(const std::vector<Singular_edge>& before,
                                                   const std::vector<Singular_edge>& after, Place place) {
  std::set<std::array<std::size_t, 2>> bad_before;
  std::set<std::size_t> judged; // non-meshable before, or left to a non-meshable edge
  for (const Singular_edge& e : before)
    if (!is_meshable(e.type)) {
      bad_before.insert(e.vertices);
      judged.insert(e.vertices.begin(), e.vertices.end());
    }
  for (std::size_t v : non_meshable_nodes(before, place)) judged.insert(v);
  std::vector<std::size_t> out;
  for (const Singular_edge& e : after)
    if (!is_meshable(e.type) && !bad_before.count(e.vertices)) out.insert(out.end(), e.vertices.begin(), e.vertices.end());
  std::map<std::size_t, std::vector<std::size_t>> others; // the other ends of each vertex's edges
  for (const Singular_edge& e : after) {
    others[e.vertices[0]].push_back(e.vertices[1]);
    others[e.vertices[1]].push_back(e.vertices[0]);
  }
  for (std::size_t v : non_meshable_nodes(after, place)) {
    if (judged.count(v)) continue;
    out.push_back(v);
    out.insert(out.end(), others.at(v).begin(), others.at(v).end());
  }
  return out;
}

} // namespace internal

/// \ingroup PkgCGALExtFrames
/// Options of `straighten_singular_curves()`.
struct Singular_curve_straightening_options {
  /// Sweeps over the curves' vertices, in increasing vertex order.
  int sweeps = 5;
  /// The fraction of the way to the midpoint of its two curve neighbours
  /// that a vertex moves in one sweep (halved, then halved again, where a
  /// tetrahedron would turn over; the vertex stays where all three fail).
  double step = 0.5;
  /// Vertices that stay, by vertex index (1: fixed), besides the boundary's
  /// and the nodes: those of an interior surface or edge of the input, or
  /// between subdomains. Empty, or shorter than the vertex indices: none
  /// (past its end).
  std::vector<char> fixed_vertices;
};

/// \ingroup PkgCGALExtFrames
/// What `straighten_singular_curves()` did.
struct Singular_curve_straightening_report {
  /// Interior vertices with exactly two singular edges: those that may move.
  std::size_t curve_vertices = 0;
  /// Of them, those away from where they were in the end.
  std::size_t moved_vertices = 0;
  /// Moves refused because a tetrahedron would have turned over.
  std::size_t refused_moves = 0;
  /// Moved vertices put back where they were, near an edge or a node that
  /// the moves made non-meshable (and where that would turn a tetrahedron
  /// over).
  std::size_t reverted_vertices = 0;
  /** @{ */
  /// Non-meshable singular edges with the mesh's positions and with the
  /// returned ones.
  std::size_t non_meshable_before = 0, non_meshable_after = 0;
  /** @} */
  /** @{ */
  /// Non-meshable nodes and curve turns (`Singularity_graph::non_meshable_vertices()`)
  /// with the mesh's positions and with the returned ones.
  std::size_t non_meshable_nodes_before = 0, non_meshable_nodes_after = 0;
  /** @} */
  /// The largest displacement of a vertex, over the mean length of its two
  /// curve edges before.
  double max_relative_displacement = 0;
  /** @{ */
  /// The smallest dihedral angle of the tetrahedra, in degrees, with the
  /// mesh's positions and with the returned ones. The guard refuses
  /// inversions only, not flat tetrahedra: straight curves give fewer
  /// inverted hexes (`doc/frame_fields.md`), at the cost of tetrahedra
  /// that these figures show.
  double min_dihedral_before_deg = 0, min_dihedral_after_deg = 0;
  /** @} */
  /** @{ */
  /// The tetrahedra with a dihedral angle below
  /// `straightening_flat_angle_deg`, with the mesh's positions and with the
  /// returned ones.
  std::size_t flat_tets_before = 0, flat_tets_after = 0;
  /** @} */
};

/// \ingroup PkgCGALExtFrames
/// The dihedral angle, in degrees, below which
/// `Singular_curve_straightening_report` counts a tetrahedron as flat.
constexpr double straightening_flat_angle_deg = 1;

/// \ingroup PkgCGALExtFrames
/// Straightens the singular curves of a frame field by moving their interior
/// vertices: each vertex with exactly two singular edges and not on the
/// domain's boundary moves, in `options.sweeps` Gauss-Seidel sweeps in
/// increasing vertex order, `options.step` of the way towards the midpoint
/// of its two curve neighbours. A move is refused where a tetrahedron around
/// the vertex would change its orientation, decided by CGAL's exact
/// `orientation()` predicate on the rounded candidate point (exact with a
/// kernel of exact predicates, as the default one); the step is then halved
/// twice before the vertex stays. Nodes (ends and junctions), boundary
/// vertices, `options.fixed_vertices` and all other vertices stay, so the
/// boundary, its features and the mesh's connectivity are unchanged. A
/// closed loop has no node to hold it: each sweep shrinks it a little.
///
/// Then no edge and no node may become non-meshable: while the edges, typed
/// with the moved positions, include a non-meshable one that was meshable,
/// or a vertex becomes a non-meshable node or curve turn (see
/// `Singularity_graph::non_meshable_vertices()`) that was neither that nor
/// the end of a non-meshable edge, the moved vertices within
/// `singular_curve_direction_span + 1` edges of it along the curves (those
/// its types depend on) go back where they were, as do moved vertices of a
/// tetrahedron that a put-back turned over. This ends at the latest with
/// every vertex back. So the result never has more non-meshable edges than
/// the mesh, and where it has as many (the same ones), no more non-meshable
/// nodes: a node may only show where a non-meshable edge that hid it became
/// meshable.
///
/// The field's frames and matchings are kept, not recomputed: with a metric
/// that varies in space, the transports and energies of the moved cells
/// would differ slightly, which this ignores (the metric's tensors stay with
/// their vertices). The curves' directions change, hence their types
/// (`singular_edges()` with these positions). Deterministic: sequential, in
/// vertex order.
///
/// \tparam Frame_field a `Frame_field_3` after `compute()` or `set_rotations()`
/// \param ff the frame field (for the mesh, its boundary and its positions)
/// \param matchings its matchings (to type the edges with moved positions)
/// \param edges its singular edges, as `singular_edges(ff, matchings)`
///        returns them (the guard compares the moved positions' types with
///        these; other edges void its guarantee, and the mesh's positions
///        are then returned where it cannot put moves back)
/// \param options the options
/// \param report if not null, receives what was done
/// \returns the positions of all vertices, by vertex index (those of the
///          mesh where nothing moved; NaN at an index that no vertex has,
///          such as an input vertex that no tetrahedron uses)
/// \throws std::invalid_argument for `sweeps` < 0 or a `step` outside (0, 1]
template <class Frame_field>
std::vector<Eigen::Vector3d> straighten_singular_curves(const Frame_field& ff,
                                                        const Frame_field_matchings_3<Frame_field>& matchings,
                                                        const std::vector<Singular_edge>& edges,
                                                        const Singular_curve_straightening_options& options = {},
                                                        Singular_curve_straightening_report* report = nullptr) {
  using Point_3 = typename Frame_field::Point_3;
  if (options.sweeps < 0) throw std::invalid_argument("straighten_singular_curves: sweeps must be >= 0");
  if (!(options.step > 0 && options.step <= 1))
    throw std::invalid_argument("straighten_singular_curves: step must be in (0, 1]");
  Singular_curve_straightening_report r;
  // Indexed like the vertices, which may skip indices (a mesh's unused vertices).
  const auto& tr = ff.metric_field().triangulation();
  std::size_t size = 0;
  for (auto v = tr.finite_vertices_begin(); v != tr.finite_vertices_end(); ++v)
    size = std::max(size, ff.vertex_index(v) + 1);
  std::vector<Eigen::Vector3d> p(size, Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN()));
  for (auto v = tr.finite_vertices_begin(); v != tr.finite_vertices_end(); ++v)
    p[ff.vertex_index(v)] = internal::to_eigen_vector(v->point());
  const std::size_t n = p.size(), m = ff.size();

  // The tetrahedra's vertices, and the tetrahedra around each vertex.
  std::vector<std::array<std::size_t, 4>> tet(m);
  for (std::size_t i = 0; i < m; ++i)
    for (int k = 0; k < 4; ++k) tet[i][k] = ff.vertex_index(ff.cell(i)->vertex(k));
  std::vector<std::size_t> first, star;
  internal::tets_around_vertices(ff, n, first, star);
  std::vector<char> on_boundary(n, 0);
  for (const auto& b : ff.boundary_faces())
    for (int k = 1; k < 4; ++k) on_boundary[tet[b.tet][(b.facet + k) % 4]] = 1;

  // The curves' interior vertices and their two neighbours along the curve.
  std::vector<std::vector<std::size_t>> neighbours(n);
  for (const Singular_edge& e : edges) {
    neighbours.at(e.vertices[0]).push_back(e.vertices[1]);
    neighbours.at(e.vertices[1]).push_back(e.vertices[0]);
  }
  std::vector<std::size_t> movable;
  for (std::size_t v = 0; v < n; ++v)
    if (neighbours[v].size() == 2 && !on_boundary[v] && first[v + 1] > first[v] &&
        !(v < options.fixed_vertices.size() && options.fixed_vertices[v]))
      movable.push_back(v);
  r.curve_vertices = movable.size();

  auto point = [](const Eigen::Vector3d& x) { return Point_3(x(0), x(1), x(2)); };
  auto orientation = [&](std::size_t i) {
    return CGAL::orientation(point(p[tet[i][0]]), point(p[tet[i][1]]), point(p[tet[i][2]]), point(p[tet[i][3]]));
  };
  // Each tetrahedron keeps the orientation it has in the mesh.
  std::vector<CGAL::Orientation> sign(m);
  for (std::size_t i = 0; i < m; ++i) sign[i] = orientation(i);
  // The smallest dihedral angle and the flat tetrahedra, at the positions p.
  auto shape = [&](double& min_angle, std::size_t& flat) {
    min_angle = m ? 180 : 0;
    flat = 0;
    for (std::size_t i = 0; i < m; ++i) {
      const std::array<Eigen::Vector3d, 4> corners{p[tet[i][0]], p[tet[i][1]], p[tet[i][2]], p[tet[i][3]]};
      const std::array<double, 6> angles = internal::stat_dihedral_angles(corners);
      const double least = *std::min_element(angles.begin(), angles.end());
      min_angle = std::min(min_angle, least);
      if (least < straightening_flat_angle_deg) ++flat;
    }
  };
  shape(r.min_dihedral_before_deg, r.flat_tets_before);

  std::vector<Eigen::Vector3d> start(movable.size());
  for (std::size_t k = 0; k < movable.size(); ++k) start[k] = p[movable[k]];
  for (int sweep = 0; sweep < options.sweeps; ++sweep)
    for (std::size_t k = 0; k < movable.size(); ++k) {
      const std::size_t v = movable[k];
      const Eigen::Vector3d old = p[v];
      const Eigen::Vector3d target = 0.5 * (p[neighbours[v][0]] + p[neighbours[v][1]]);
      bool done = false;
      for (double step = options.step; !done && step >= options.step / 4; step /= 2) {
        p[v] = old + step * (target - old);
        done = std::all_of(star.begin() + first[v], star.begin() + first[v + 1],
                           [&](std::size_t i) { return orientation(i) == sign[i]; });
      }
      if (!done) {
        p[v] = old;
        ++r.refused_moves;
      }
    }

  // The guard. The edges are typed on the tetrahedra around the curves,
  // which hold every singular edge and the curves' stretches.
  auto index_of = [&](std::size_t v) { // in `movable`, or its size
    const auto it = std::lower_bound(movable.begin(), movable.end(), v);
    return it != movable.end() && *it == v ? std::size_t(it - movable.begin()) : movable.size();
  };
  std::vector<std::size_t> around;
  for (std::size_t v = 0; v < n; ++v)
    if (!neighbours[v].empty()) around.insert(around.end(), star.begin() + first[v], star.begin() + first[v + 1]);
  std::sort(around.begin(), around.end());
  around.erase(std::unique(around.begin(), around.end()), around.end());
  r.non_meshable_before = std::size_t(
      std::count_if(edges.begin(), edges.end(), [](const Singular_edge& e) { return !is_meshable(e.type); }));
  // Nodes are judged where the field's features put them, as `singularity_graph()` does.
  const std::vector<internal::Vertex_place> place = internal::vertex_places(ff);
  auto where = [&](std::size_t v) { return place[v]; };
  r.non_meshable_nodes_before = internal::non_meshable_nodes(edges, where).size();
  auto put_back = [&](std::vector<std::size_t> queue) { // then the moved vertices of turned-over tetrahedra
    while (!queue.empty()) {
      for (std::size_t v : queue) p[v] = start[index_of(v)];
      r.reverted_vertices += queue.size();
      std::vector<std::size_t> next;
      for (std::size_t v : queue)
        for (auto i = star.begin() + first[v]; i != star.begin() + first[v + 1]; ++i)
          if (orientation(*i) != sign[*i])
            for (std::size_t w : tet[*i]) {
              const std::size_t k = index_of(w);
              if (k < movable.size() && p[w] != start[k]) next.push_back(w);
            }
      std::sort(next.begin(), next.end());
      next.erase(std::unique(next.begin(), next.end()), next.end());
      queue.swap(next);
    }
  };
  for (;;) {
    const std::vector<Singular_edge> typed = singular_edges(ff, matchings, &around, &p);
    std::vector<std::size_t> reached, ring = internal::new_non_meshable_vertices(edges, typed, where);
    r.non_meshable_after = std::size_t(
        std::count_if(typed.begin(), typed.end(), [](const Singular_edge& e) { return !is_meshable(e.type); }));
    r.non_meshable_nodes_after = internal::non_meshable_nodes(typed, where).size();
    if (ring.empty()) break;
    // The vertices within reach along the curves.
    for (int depth = 0; depth <= singular_curve_direction_span + 1 && !ring.empty(); ++depth) {
      reached.insert(reached.end(), ring.begin(), ring.end());
      std::vector<std::size_t> next;
      for (std::size_t v : ring) next.insert(next.end(), neighbours[v].begin(), neighbours[v].end());
      ring.swap(next);
    }
    std::vector<std::size_t> back;
    for (std::size_t v : reached) {
      const std::size_t k = index_of(v);
      if (k < movable.size() && p[v] != start[k]) back.push_back(v);
    }
    std::sort(back.begin(), back.end());
    back.erase(std::unique(back.begin(), back.end()), back.end());
    if (back.empty()) { // only for `edges` other than the mesh's: every vertex back, the mesh as it is
      for (std::size_t k = 0; k < movable.size(); ++k) p[movable[k]] = start[k];
      break;
    }
    put_back(back);
  }

  for (std::size_t k = 0; k < movable.size(); ++k) {
    if (p[movable[k]] == start[k]) continue;
    ++r.moved_vertices;
    const std::size_t v = movable[k];
    // The curve edges' lengths before: the neighbours may have moved too.
    double length = 0;
    for (std::size_t w : neighbours[v]) {
      const auto it = std::lower_bound(movable.begin(), movable.end(), w);
      const Eigen::Vector3d& q = (it != movable.end() && *it == w) ? start[std::size_t(it - movable.begin())] : p[w];
      length += 0.5 * (q - start[k]).norm();
    }
    if (length > 0) r.max_relative_displacement = std::max(r.max_relative_displacement, (p[v] - start[k]).norm() / length);
  }
  shape(r.min_dihedral_after_deg, r.flat_tets_after);
  if (report) *report = r;
  return p;
}

} // namespace CGAL_ext

#endif // CGAL_EXT_SINGULAR_CURVE_STRAIGHTENING_3_H
