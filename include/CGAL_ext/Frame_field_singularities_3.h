// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_FRAME_FIELD_SINGULARITIES_3_H
#define CGAL_EXT_FRAME_FIELD_SINGULARITIES_3_H

/// \file Frame_field_singularities_3.h
/// The singularities of an octahedral frame field: the interior mesh edges
/// around which the frames do not come back to themselves (doc/math.md section
/// 5), typed by their holonomy, and grouped into curves and nodes.

#include <CGAL_ext/Frame_field_matchings_3.h>
#include <CGAL_ext/Metric_field_3.h>
#include <CGAL_ext/Octahedral_frame.h>
#include <CGAL_ext/Sharp_features_3.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace CGAL_ext {

/// \ingroup PkgCGALExtFrames
/// The type of an interior edge of a frame field, from the holonomy (the
/// product of the face matchings) around it. Only the two quarter turns about
/// the edge are edges of a hexahedral mesh; the others are defects of the
/// field that an integer-grid map cannot mesh.
enum class Singularity_type {
  regular,        ///< the product of matchings is the identity
  plus_quarter,   ///< a quarter turn about the edge, index +1/4: 3 hexahedra around it
  minus_quarter,  ///< a quarter turn against the edge, index -1/4: 5 hexahedra around it
  quarter_across, ///< a quarter turn about a frame axis other than the one along the edge
  half,           ///< a half turn (about a frame axis or a face diagonal of the frame)
  third           ///< a third of a turn about a diagonal of the frame's cube
};

/// \ingroup PkgCGALExtFrames
/// The name used in outputs: "regular", "+1/4", "-1/4", "1/4 across", "1/2", "1/3".
/// \param t the type
/// \returns the name, a static string
inline const char* singularity_type_name(Singularity_type t) {
  switch (t) {
    case Singularity_type::regular: return "regular";
    case Singularity_type::plus_quarter: return "+1/4";
    case Singularity_type::minus_quarter: return "-1/4";
    case Singularity_type::quarter_across: return "1/4 across";
    case Singularity_type::half: return "1/2";
    default: return "1/3";
  }
}

/// \ingroup PkgCGALExtFrames
/// Whether a singular edge of this type can be an edge of a hexahedral mesh
/// (a quarter turn about the edge: `plus_quarter` or `minus_quarter`).
/// \param t the type
/// \returns true for `plus_quarter` and `minus_quarter`
inline bool is_meshable(Singularity_type t) {
  return t == Singularity_type::plus_quarter || t == Singularity_type::minus_quarter;
}

/// \ingroup PkgCGALExtFrames
/// Whether an interior vertex where `plus_quarter` edges (valence 3) and
/// `minus_quarter` edges (valence 5) meet, all its other edges regular
/// (valence 4), can be a vertex of a hexahedral mesh.
///
/// The hexahedra around a vertex of a hexahedral mesh form a triangulated
/// sphere, its link: one triangle per hexahedron, one vertex per edge, of
/// degree the edge's valence (simplicial where the hexahedra do not
/// overlap). Euler's formula makes the sum of 6 minus the degrees 12: 3 per
/// valence-3 edge, 1 per valence-5 edge, 2 per regular edge. So
/// `3 plus + minus` is even (an even number of singular edges) and at most
/// 12, and with degrees 3 to 5 the link has at most 12 vertices. The
/// triangulated spheres with such degrees are 11 (found by enumerating the
/// simplicial spheres of up to 12 vertices), with `(plus, minus)` =
/// (0, 0) (the octahedron: a regular vertex), (2, 0) and (0, 2) (a curve
/// through it: the triangular and pentagonal bipyramids), (4, 0) (the
/// tetrahedron: the corner of the ball's inner cube), (2, 2), (1, 3),
/// (0, 4), (2, 6), (0, 6), (0, 8) and (0, 12) (the icosahedron); no other
/// count can be met. For instance a junction of three curves, a curve
/// ending inside, three valence-3 curves and one valence-5 curve, or a
/// curve turning from valence 3 to valence 5 fail.
///
/// An integer-grid map puts every node of the singular curves on a grid
/// vertex, which becomes a vertex of the hexahedral mesh; around a node that
/// fails, the map degenerates.
/// \param plus_quarter the number of `plus_quarter` edges at the vertex
/// \param minus_quarter the number of `minus_quarter` edges at the vertex
/// \returns whether a hexahedral-mesh vertex can have these edges
inline bool is_meshable_interior_node(std::size_t plus_quarter, std::size_t minus_quarter) {
  static constexpr std::size_t types[11][2] = {{0, 0}, {2, 0}, {0, 2}, {4, 0}, {2, 2}, {1, 3},
                                               {0, 4}, {2, 6}, {0, 6}, {0, 8}, {0, 12}};
  for (const auto& t : types)
    if (t[0] == plus_quarter && t[1] == minus_quarter) return true;
  return false;
}

/// \ingroup PkgCGALExtFrames
/// Whether a boundary vertex off the sharp features, where `singular_edges`
/// singular edges (`plus_quarter` or `minus_quarter`) meet, can be a vertex
/// of a hexahedral mesh whose boundary is smooth there.
///
/// The hexahedra around a boundary vertex form a triangulated disc: a vertex
/// per edge, of degree the edge's valence inside, its number of hexahedra
/// plus one on the rim. Euler's formula makes the sum of `6 - degree` inside
/// and `4 - degree` on the rim 6. Where the boundary is smooth every rim
/// edge has two hexahedra and gives 1, so `3 plus + minus + 2 regular + m =
/// 6` with `m >= 3` rim edges; of what is left, a single valence-3 edge
/// (3 rim edges) or valence-5 edge (5 rim edges) fits, and two or three
/// valence-5 edges (`m` = 4 or 3, no regular edge) would need more edges
/// between the inner vertices than a simplicial disc has. So at most
/// one singular curve meets a smooth boundary at a vertex: a curve that
/// touches the surface and goes back in, or runs along it, makes the map
/// fold the surface into a crease there (the built-in torus: its cross
/// sections become squares), and a junction on the surface cannot be meshed.
/// \param singular_edges the number of singular edges at the vertex
/// \returns whether it is at most 1
inline bool is_meshable_smooth_boundary_node(std::size_t singular_edges) { return singular_edges <= 1; }

/// \ingroup PkgCGALExtFrames
/// A singular interior edge.
struct Singular_edge {
  /// The 0-based vertex indices of the edge, sorted.
  std::array<std::size_t, 2> vertices{{0, 0}};
  /// The type.
  Singularity_type type = Singularity_type::regular;
  /// The number of hexahedra the edge would have around it (4 - 4 index):
  /// 3 for `plus_quarter`, 5 for `minus_quarter`, 0 otherwise.
  int valence = 0;
  /// The index in `octahedral_group()` of the product of the matchings
  /// around the loop that starts in the tetrahedron of smallest index around
  /// the edge and turns positively about it, from `vertices[0]` to
  /// `vertices[1]` (the product is conjugate to it from any other start, and
  /// inverted the other way round).
  int monodromy = 0;
  /// The number of tetrahedra around the edge.
  int loop_size = 0;
  /// The rotation angle of the holonomy in degrees, signed by the right-hand
  /// rule about the edge's curve: +90 for `plus_quarter`, -90 for
  /// `minus_quarter`, +-90 or +-120 for the others by the side of the curve
  /// their axis lies on, 180 for half turns. It depends neither on the tetrahedron the loop
  /// starts from nor on the orientation of the edge.
  double turn_deg = 0;
  /// The angle between the holonomy's axis and the direction of the edge's
  /// singular curve around it (see `singular_edges()`), measured in the
  /// metric, in degrees in [0, 90].
  double axis_angle_deg = 0;
  /// The angle between the holonomy's axis and the edge alone, in the metric,
  /// in degrees in [0, 90] (larger than `axis_angle_deg` where the curve
  /// zigzags along the mesh edges).
  double edge_axis_angle_deg = 0;
  /// The holonomy's axis as a unit Euclidean direction (a hex edge direction
  /// `A^{-1} R a`), oriented along the edge from `vertices[0]` to `vertices[1]`.
  Eigen::Vector3d axis = Eigen::Vector3d::Zero();
  /// The midpoint of the edge.
  Eigen::Vector3d midpoint = Eigen::Vector3d::Zero();
};

namespace internal {

// For each vertex touched by the edges, the indices of its edges, ordered by
// the other vertex (deterministic traversals).
inline std::map<std::size_t, std::vector<std::size_t>> edges_at_vertices(
    const std::vector<std::array<std::size_t, 2>>& edges) {
  std::map<std::size_t, std::vector<std::size_t>> incident;
  for (std::size_t k = 0; k < edges.size(); ++k)
    for (int s = 0; s < 2; ++s) incident[edges[k][s]].push_back(k);
  for (auto& [v, list] : incident)
    std::sort(list.begin(), list.end(), [&, v = v](std::size_t a, std::size_t b) {
      return edges[a][edges[a][0] == v ? 1 : 0] < edges[b][edges[b][0] == v ? 1 : 0];
    });
  return incident;
}

// The ends of the stretch of curve around edge k: from each end of k, at
// most `steps` edges along the chain of edges through vertices of exactly
// two edges (stopping at nodes). On a closed loop the two sides stop before
// they meet, so the stretch never wraps around: its ends differ.
inline std::array<std::size_t, 2> curve_stretch(const std::vector<std::array<std::size_t, 2>>& edges,
                                                const std::map<std::size_t, std::vector<std::size_t>>& incident,
                                                std::size_t k, int steps) {
  std::array<std::size_t, 2> end = edges[k], edge{{k, k}};
  std::vector<std::size_t> reached{end[0], end[1]};
  std::array<bool, 2> going{{true, true}};
  for (int s = 0; s < steps; ++s)
    for (int side = 0; side < 2; ++side) {
      if (!going[side]) continue;
      const std::vector<std::size_t>& list = incident.at(end[side]);
      if (list.size() != 2) { // a node
        going[side] = false;
        continue;
      }
      const std::size_t next = list[0] == edge[side] ? list[1] : list[0];
      const std::size_t w = edges[next][0] == end[side] ? edges[next][1] : edges[next][0];
      if (std::find(reached.begin(), reached.end(), w) != reached.end()) { // the other side's ground
        going[side] = false;
        continue;
      }
      reached.push_back(w);
      end[side] = w, edge[side] = next;
    }
  return end;
}

} // namespace internal

/// \ingroup PkgCGALExtFrames
/// How many edges on each side of a singular edge `singular_edges()` follows
/// along its singular curve to estimate the curve's direction (see there).
constexpr int singular_curve_direction_span = 2;

namespace internal {

// Pass 1 of singular_edges() for one singular edge: its holonomy and what
// its typing needs.
struct Singular_edge_holonomy {
  Singular_edge edge;                   // vertices, monodromy, loop size, midpoint
  Eigen::Matrix3d P, frame_from_metric; // the loop product; R_0^T A
  Eigen::Vector3d t;                    // the edge, oriented by the circulation
  std::array<Eigen::Vector3d, 2> p;     // positions of edge.vertices
};

// Pass 1 of singular_edges() (same parameters): the singular edges among
// those examined, sorted by their vertex indices. Each depends only on the
// frames of the tetrahedra around it.
template <class Frame_field>
std::vector<Singular_edge_holonomy> singular_edge_holonomies(const Frame_field& ff,
                                                             const Frame_field_matchings_3<Frame_field>& matchings,
                                                             const std::vector<std::size_t>* tets,
                                                             const std::vector<Eigen::Vector3d>* positions) {
  using Cell_handle = typename Frame_field::Cell_handle;
  using Edge = typename Frame_field::Triangulation::Edge;
  const auto& field = ff.metric_field();
  const auto& tr = field.triangulation();
  using Found = Singular_edge_holonomy;
  std::vector<Found> found;
  std::vector<Cell_handle> loop;
  auto examine = [&](const Edge& e) {
    loop.clear();
    bool interior = true;
    auto circ = tr.incident_cells(e), done = circ;
    do {
      const Cell_handle c = circ;
      if (tr.is_infinite(c) || ff.index(c) < 0) {
        interior = false;
        break;
      }
      loop.push_back(c);
    } while (++circ != done);
    if (!interior) return;
    const int n = int(loop.size());
    // The product of the matchings around the loop, from loop[0].
    auto loop_product = [&] {
      Eigen::Matrix3d product = Eigen::Matrix3d::Identity();
      for (int k = 0; k < n; ++k) {
        const Cell_handle a = loop[k], b = loop[(k + 1) % n];
        product = matchings.matching(std::size_t(ff.index(a)), a->index(b)) * product;
      }
      return product;
    };
    if (octahedral_group_index(loop_product(), 0) == 0) return; // regular from any start

    // A canonical loop, from the tetrahedron of smallest index, turning
    // positively about u -> v (u the smaller vertex index): CGAL's edge
    // iterator picks the edge's cell by address, and the typing below
    // compares the curve with the frame of the first tetrahedron, so that
    // an edge whose curve runs between two frame axes would otherwise be
    // typed by the heap layout (found on blobby: run after another model in
    // one process, 2 of 505 singular edges changed type).
    std::rotate(loop.begin(),
                std::min_element(loop.begin(), loop.end(),
                                 [&](Cell_handle a, Cell_handle b) { return ff.index(a) < ff.index(b); }),
                loop.end());
    auto u = e.first->vertex(e.second), v = e.first->vertex(e.third);
    if (ff.vertex_index(u) > ff.vertex_index(v)) std::swap(u, v);
    auto vertex_position = [&](typename Frame_field::Vertex_handle w) -> Eigen::Vector3d {
      return positions ? (*positions)[ff.vertex_index(w)] : internal::to_eigen_vector(w->point());
    };
    // The loop's sense from the mesh's own geometry: moved positions keep
    // every cell's orientation, hence the sense, but a sheared ring could
    // flip this sum.
    const Eigen::Vector3d mu = internal::to_eigen_vector(u->point()), mv = internal::to_eigen_vector(v->point());
    double turn = 0; // orientation of the circulation about u -> v
    for (int k = 0; k < n; ++k) {
      const std::size_t ia = std::size_t(ff.index(loop[k])), ib = std::size_t(ff.index(loop[(k + 1) % n]));
      turn += (ff.centroid(ia) - mu).cross(ff.centroid(ib) - mu).dot(mv - mu);
    }
    const Eigen::Vector3d pu = vertex_position(u), pv = vertex_position(v);
    if (turn < 0) std::reverse(loop.begin() + 1, loop.end());
    const Eigen::Matrix3d P = loop_product();
    const int monodromy = octahedral_group_index(P, 0);

    Found f;
    f.P = P;
    f.t = pv - pu;
    const Eigen::Vector3d mid = 0.5 * (pu + pv);
    // A at the edge's midpoint, whose barycentric coordinates do not depend
    // on the positions: taken at the mesh's own midpoint.
    const Eigen::Vector3d mesh_mid = 0.5 * (mu + mv);
    const Eigen::Matrix3d A = field.A_at(loop[0], typename Frame_field::Point_3(mesh_mid(0), mesh_mid(1), mesh_mid(2)));
    const Eigen::Matrix3d& R0 = matchings.rotation(std::size_t(ff.index(loop[0])));
    f.frame_from_metric = R0.transpose() * A;
    Singular_edge& s = f.edge;
    s.vertices = {ff.vertex_index(u), ff.vertex_index(v)};
    f.p = {pu, pv};
    s.monodromy = monodromy;
    s.loop_size = n;
    s.valence = 0;
    s.midpoint = mid;
    found.push_back(f);
  };
  // The edges to examine: all finite edges, or those of the tetrahedra given (once each).
  if (tets) {
    std::vector<std::pair<std::array<std::size_t, 2>, Edge>> keyed;
    for (std::size_t i : *tets) {
      const Cell_handle c = ff.cell(i);
      for (int a = 0; a < 4; ++a)
        for (int b = a + 1; b < 4; ++b) {
          std::size_t u = ff.vertex_index(c->vertex(a)), v = ff.vertex_index(c->vertex(b));
          keyed.push_back({{std::min(u, v), std::max(u, v)}, Edge(c, a, b)});
        }
    }
    std::sort(keyed.begin(), keyed.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    for (std::size_t k = 0; k < keyed.size(); ++k)
      if (k == 0 || keyed[k].first != keyed[k - 1].first) examine(keyed[k].second);
  } else {
    for (auto e = tr.finite_edges_begin(); e != tr.finite_edges_end(); ++e) examine(*e);
  }
  std::sort(found.begin(), found.end(),
            [](const Found& a, const Found& b) { return a.edge.vertices < b.edge.vertices; });
  return found;
}

// Pass 2 of singular_edges(): the direction of each edge's curve (along the
// edges given, sorted by their vertices), and the types.
inline std::vector<Singular_edge> type_singular_edges(const std::vector<Singular_edge_holonomy>& found) {
  std::vector<std::array<std::size_t, 2>> ends(found.size());
  std::map<std::size_t, Eigen::Vector3d> position;
  for (std::size_t k = 0; k < found.size(); ++k) {
    ends[k] = found[k].edge.vertices;
    for (int s = 0; s < 2; ++s) position[ends[k][s]] = found[k].p[s];
  }
  const auto incident = internal::edges_at_vertices(ends);
  std::vector<Singular_edge> out;
  out.reserve(found.size());
  for (std::size_t k = 0; k < found.size(); ++k) {
    const Singular_edge_holonomy& f = found[k];
    Singular_edge s = f.edge;
    const std::array<std::size_t, 2> stretch =
        internal::curve_stretch(ends, incident, k, singular_curve_direction_span);
    const std::size_t back = stretch[0], ahead = stretch[1];
    // The curve, traversed from vertices[0] to vertices[1] here, and its
    // direction d over a few edges. The loop about t links the curve with
    // the sign of t . (p1 - p0), exactly +-1 (t is +-(p1 - p0)): about the
    // traversal, the holonomy is P^link.
    const Eigen::Vector3d d = position[ahead] - position[back];
    const double link = f.t.dot(f.p[1] - f.p[0]) > 0 ? 1.0 : -1.0;
    const Eigen::Vector3d d_frame = (f.frame_from_metric * d).normalized(); // the curve in c_0's frame space
    const Eigen::Vector3d t_frame = (f.frame_from_metric * f.t).normalized();

    // The axis a of P (frame space of c_0), with P a rotation by angle > 0 about a.
    const Eigen::Matrix3d& P = f.P;
    const double trace = P.trace(); // 1 + 2 cos(angle): exactly 1, 0 or -1
    const double angle = trace == 1 ? 90 : trace == 0 ? 120 : 180;
    Eigen::Vector3d a(P(2, 1) - P(1, 2), P(0, 2) - P(2, 0), P(1, 0) - P(0, 1));
    if (trace == -1) { // half turn: P = 2 a a^T - I, a from the largest column of P + I
      const Eigen::Matrix3d S = P + Eigen::Matrix3d::Identity();
      int c;
      S.colwise().squaredNorm().maxCoeff(&c);
      a = S.col(c);
    }
    a.normalize();
    const double c = link * a.dot(d_frame); // > 0: P turns positively about d
    s.turn_deg = trace == -1 ? 180.0 : (c > 0 ? angle : -angle);
    s.axis_angle_deg = std::acos(std::min(1.0, std::abs(c))) * 180 / M_PI;
    s.edge_axis_angle_deg = std::acos(std::min(1.0, std::abs(a.dot(t_frame)))) * 180 / M_PI;
    const Eigen::Vector3d axis = f.frame_from_metric.inverse() * a; // A^{-1} R_0 a
    s.axis = (axis.dot(f.p[1] - f.p[0]) < 0 ? -1.0 : 1.0) * axis.normalized();
    s.type = trace == 0 ? Singularity_type::third : trace == -1 ? Singularity_type::half : Singularity_type::quarter_across;
    if (trace == 1) {
      int nearest;
      d_frame.cwiseAbs().maxCoeff(&nearest);
      if (std::abs(a(nearest)) == 1) {
        s.type = c > 0 ? Singularity_type::plus_quarter : Singularity_type::minus_quarter;
        s.valence = c > 0 ? 3 : 5;
      }
    }
    out.push_back(s);
  }
  return out;
}

} // namespace internal

/// \ingroup PkgCGALExtFrames
/// Finds and types the singular edges of a frame field from its face matchings.
///
/// For each interior edge (no incident cell outside the domain) with cells
/// `c_0, ..., c_{n-1}` around it, `c_0` the one of smallest index and the
/// loop turning positively about the edge from its smaller vertex index to
/// the larger, the holonomy is
/// the exact product `P = G_{n-1} ... G_0` of the face matchings `G_k` from
/// `c_k` to `c_{k+1}` (`Frame_field_matchings_3`, transports included). The
/// edge is regular iff `P = I`. Otherwise `P` is a rotation by 90, 120 or 180
/// degrees about an axis `a` of the frame space of `c_0`; in space it is the
/// turn `R_0 P R_0^T` about `R_0 a`.
///
/// The singular edges form curves that zigzag along the mesh edges, so a
/// quarter turn is compared with the direction `d` of its curve rather than
/// with the edge alone: the chord from the vertex reached by following the
/// curve `singular_curve_direction_span` edges back to the one reached as
/// many edges forward (the chain stops at nodes, vertices with other than two
/// singular edges, and on a closed loop before the two sides meet). The loop around the edge links the curve once, with the
/// sign of the edge traversed along `d`: about `d`, the holonomy is `P` or
/// `P^{-1}` by that sign (an exact test; an edge may zigzag backwards or
/// across `d`). In the metric (`A` at the edge's midpoint in `c_0`):
/// - a quarter turn whose axis is the frame axis closest to `A d` (the one
///   along which an integer-grid map lays the curve) is `plus_quarter` if it
///   turns positively about `d` and `minus_quarter` otherwise;
/// - a quarter turn about another frame axis is `quarter_across`: the curve
///   runs across its own turn's axis, and no hex edge can follow it;
/// - half turns are `half`, thirds of a turn are `third`.
///
/// A different starting cell conjugates `P` by the matchings and moves the
/// axis with the frames; a reversed loop inverts `P` and reverses `t`; so
/// the type and `turn_deg` do not depend on either, except through the
/// nearest frame axis to `A d`: the frames of the cells around an edge
/// differ by small rotations, and a curve running about halfway between two
/// axes may be nearest to different ones in different cells. Hence the
/// fixed `c_0`, so that the type depends on the field alone (not on how
/// CGAL's iterator represents the edge, which depends on cell addresses).
///
/// The edges are returned sorted by their vertex indices (deterministic).
///
/// \tparam Frame_field a `Frame_field_3` after `compute()`
/// \param ff the frame field
/// \param matchings its face matchings
/// \param tets if given, only the edges of these tetrahedra are examined
///        (and the curves' directions are taken along the singular edges
///        among them): an edge whose curve stays within
///        `singular_curve_direction_span` edges of the set gets the same type
///        as from all edges
/// \param positions if given, the vertices' positions by vertex index, in
///        place of the mesh's (as `straighten_singular_curves()` returns
///        them; one per vertex index at least): the holonomies and the
///        loops' senses are the mesh's, the curves' directions, the edges'
///        midpoints and the metric there those of these positions (the
///        metric at a midpoint is taken at the same barycentric coordinates)
/// \returns the singular edges (regular edges are not listed)
template <class Frame_field>
std::vector<Singular_edge> singular_edges(const Frame_field& ff, const Frame_field_matchings_3<Frame_field>& matchings,
                                          const std::vector<std::size_t>* tets = nullptr,
                                          const std::vector<Eigen::Vector3d>* positions = nullptr) {
  return internal::type_singular_edges(internal::singular_edge_holonomies(ff, matchings, tets, positions));
}

/// \ingroup PkgCGALExtFrames
/// Finds and types the singular edges of a frame field (computes its face
/// matchings first; see the overload taking them).
/// \tparam Frame_field a `Frame_field_3` after `compute()`
/// \param ff the frame field
/// \returns the singular edges, sorted by their vertex indices
template <class Frame_field>
std::vector<Singular_edge> singular_edges(const Frame_field& ff) {
  return singular_edges(ff, Frame_field_matchings_3<Frame_field>(ff));
}

namespace internal {

// Where a vertex lies, for the judgement of the singular edges meeting there.
enum class Vertex_place { interior, smooth_boundary, feature };

// The vertices whose singular edges are all meshable and cannot meet there
// in a hexahedral mesh, sorted: inside, failing is_meshable_interior_node()
// (nodes, and curves turning from +1/4 to -1/4); on the boundary off the
// features, three or more (junctions; two, a curve touching the surface, is
// left out). A vertex with a non-meshable edge is left to that edge.
// `place(v)` tells where vertex v lies.
template <class Place>
std::vector<std::size_t> non_meshable_nodes(const std::vector<Singular_edge>& edges, Place place) {
  std::map<std::size_t, std::array<std::size_t, 3>> count; // +1/4, -1/4, others
  for (const Singular_edge& e : edges)
    for (std::size_t v : e.vertices)
      ++count[v][e.type == Singularity_type::plus_quarter ? 0 : e.type == Singularity_type::minus_quarter ? 1 : 2];
  std::vector<std::size_t> out;
  for (const auto& [v, c] : count) {
    if (c[2] > 0) continue;
    const Vertex_place where = place(v);
    if (where == Vertex_place::interior ? !is_meshable_interior_node(c[0], c[1])
                                        : where == Vertex_place::smooth_boundary && c[0] + c[1] != 2 &&
                                              !is_meshable_smooth_boundary_node(c[0] + c[1]))
      out.push_back(v);
  }
  return out;
}

// Where each vertex of a frame field lies (boundary: a vertex of a boundary face).
template <class Frame_field>
std::vector<Vertex_place> vertex_places(const Frame_field& ff) {
  std::size_t nv = 0;
  for (std::size_t i = 0; i < ff.size(); ++i)
    for (int k = 0; k < 4; ++k) nv = std::max(nv, ff.vertex_index(ff.cell(i)->vertex(k)) + 1);
  std::vector<Vertex_place> place(nv, Vertex_place::interior);
  for (const auto& b : ff.boundary_faces())
    for (int k = 1; k < 4; ++k) {
      const std::size_t v = ff.vertex_index(ff.cell(b.tet)->vertex((b.facet + k) % 4));
      place[v] = ff.feature_vertex_kind(v) == Feature_vertex_kind::none ? Vertex_place::smooth_boundary
                                                                        : Vertex_place::feature;
    }
  return place;
}

} // namespace internal

/// \ingroup PkgCGALExtFrames
/// A vertex where singular edges meet in other than a simple chain: a vertex
/// with 1 or with 3 or more incident singular edges.
struct Singular_node {
  /// What the node is.
  enum class Kind {
    boundary_end, ///< one singular edge, at a boundary vertex: a curve reaching the surface
    interior_end, ///< one singular edge, inside the volume: a curve that stops. Exact
                  ///< matchings cannot give it (the holonomy around that edge is the
                  ///< product of those around the vertex's other edges, all regular),
                  ///< so it is reported as a consistency check
    junction      ///< three or more singular edges
  };
  /// The 0-based vertex index.
  std::size_t vertex;
  /// The vertex's position.
  Eigen::Vector3d position;
  /// The number of incident singular edges.
  int degree;
  /// Whether the vertex is on the boundary of the domain.
  bool on_boundary;
  /// The kind.
  Kind kind;
  /// False where the node's singular edges are all meshable and no
  /// hexahedral mesh has them at such a vertex: inside, by
  /// `is_meshable_interior_node()`; on the boundary off the sharp features,
  /// by `is_meshable_smooth_boundary_node()` (a junction there). True
  /// otherwise (nodes on the features are not judged; a node with a
  /// non-meshable edge is counted by that edge).
  bool meshable = true;
};

/// \ingroup PkgCGALExtFrames
/// The name of a node kind in outputs: "boundary end", "interior end", "junction".
/// \param k the kind
/// \returns the name, a static string
inline const char* singular_node_kind_name(Singular_node::Kind k) {
  return k == Singular_node::Kind::boundary_end ? "boundary end"
         : k == Singular_node::Kind::interior_end ? "interior end"
                                                   : "junction";
}

/// \ingroup PkgCGALExtFrames
/// The singular edges counted by type, every singular type listed (with 0 if
/// absent), keyed by `singularity_type_name()`.
/// \param edges the singular edges
/// \returns the counts of "+1/4", "-1/4", "1/4 across", "1/2" and "1/3"
inline std::map<std::string, std::size_t> count_singular_edges_by_type(const std::vector<Singular_edge>& edges) {
  std::map<std::string, std::size_t> by_type = {{"+1/4", 0}, {"-1/4", 0}, {"1/4 across", 0}, {"1/2", 0}, {"1/3", 0}};
  for (const Singular_edge& s : edges) ++by_type[singularity_type_name(s.type)];
  return by_type;
}

/// \ingroup PkgCGALExtFrames
/// A singular curve: a maximal chain of singular edges whose inner vertices
/// have exactly two singular edges.
struct Singular_curve {
  /// The 0-based vertex indices along the curve; for a closed curve the
  /// first vertex is repeated at the end.
  std::vector<std::size_t> vertices;
  /// The indices of its edges in the array of singular edges, in order.
  std::vector<std::size_t> edges;
  /// Whether the curve is a closed loop without nodes.
  bool closed = false;
  /// Its Euclidean length.
  double length = 0;
  /// Its length in the metric by the midpoint rule: per edge, `|A (p1 - p0)|`
  /// with `A = g^{1/2}` at the edge's midpoint (the mean of its ends', as `A`
  /// is linear along the edge). In hexahedron edges where the metric sets
  /// the hex size, as the pipeline's does.
  double metric_length = 0;
  /** @{ */
  /// The numbers of its edges of each kind.
  std::size_t plus_quarter_edges = 0, minus_quarter_edges = 0, non_meshable_edges = 0;
  /** @} */
};

/// \ingroup PkgCGALExtFrames
/// The singular edges grouped into curves and nodes.
struct Singularity_graph {
  /// The curves, from the nodes in increasing vertex order, then the closed loops.
  std::vector<Singular_curve> curves;
  /// The nodes, in increasing vertex order.
  std::vector<Singular_node> nodes;
  /** @{ */
  /// Counts: curves that are closed loops, nodes of each kind.
  std::size_t closed_curves = 0, boundary_ends = 0, interior_ends = 0, junctions = 0;
  /** @} */
  /** @{ */
  /// Nodes that are not `meshable`.
  std::size_t non_meshable_nodes = 0;
  /// The vertices on the boundary off the sharp features where a curve
  /// touches the surface: two singular edges, both meshable (not nodes; see
  /// `is_meshable_smooth_boundary_node()`), in increasing order.
  std::vector<std::size_t> surface_touches;
  /// Their positions.
  std::vector<Eigen::Vector3d> surface_touch_positions;
  /// The interior vertices where a curve turns from `plus_quarter` to
  /// `minus_quarter` (two singular edges, one of each: a curve folding
  /// back, which no hexahedral-mesh vertex has; see
  /// `is_meshable_interior_node()`), in increasing order.
  std::vector<std::size_t> curve_turns;
  /// Their positions.
  std::vector<Eigen::Vector3d> curve_turn_positions;
  /// The curves (indices in `curves`) from a junction shorter than one unit
  /// in the metric (`Singular_curve::metric_length` < 1), in order. Where
  /// the metric sets the hex size, an integer-grid map puts both ends of a
  /// curve on grid vertices: one hex edge apart or more, or merged, and the
  /// tetrahedra around such a curve are stretched or flattened. Not
  /// counted as non-meshable: the map may still mesh them.
  std::vector<std::size_t> short_curves;
  /// The vertices the repair and the straightening count after the
  /// non-meshable edges: the nodes that are not `meshable` and the curve
  /// turns (not the surface touches).
  /// \returns their number
  std::size_t non_meshable_vertices() const { return non_meshable_nodes + curve_turns.size(); }
  /** @} */
};

/// \ingroup PkgCGALExtFrames
/// The open curves of a graph from a junction whose `Singular_curve::metric_length`
/// is below `unit` (`Singularity_graph::short_curves` for `unit` = 1, a hex
/// edge where the metric sets the hex size; with a metric that does not,
/// the hex edge in its units).
/// \param graph the curves and nodes, as `singularity_graph()` returns them
/// \param unit the length below which a curve is short
/// \returns the indices of those curves in `graph.curves`, in increasing order
inline std::vector<std::size_t> short_singular_curves(const Singularity_graph& graph, double unit) {
  std::vector<std::size_t> junctions;
  for (const Singular_node& n : graph.nodes)
    if (n.kind == Singular_node::Kind::junction) junctions.push_back(n.vertex);
  std::sort(junctions.begin(), junctions.end());
  auto junction = [&](std::size_t v) { return std::binary_search(junctions.begin(), junctions.end(), v); };
  std::vector<std::size_t> out;
  for (std::size_t k = 0; k < graph.curves.size(); ++k) {
    const Singular_curve& c = graph.curves[k];
    if (!c.closed && c.metric_length < unit && (junction(c.vertices.front()) || junction(c.vertices.back())))
      out.push_back(k);
  }
  return out;
}

/// \ingroup PkgCGALExtFrames
/// Groups singular edges into curves and nodes.
///
/// Nodes are the vertices with 1, or 3 or more, incident singular edges;
/// interior ones are judged by `is_meshable_interior_node()`, those on the
/// boundary off the sharp features (`Frame_field_3::feature_vertex_kind()`)
/// by `is_meshable_smooth_boundary_node()`. Vertices with two edges inside
/// where a curve turns from `plus_quarter` to `minus_quarter`, and on the
/// smooth boundary where a curve touches it, are listed apart, as are the
/// curves from a junction shorter than one unit in the metric.
/// Curves run from node to node through vertices with exactly two singular
/// edges; what remains are closed loops. Deterministic: curves start at the
/// nodes in increasing vertex order and leave each along its edges in
/// increasing order of the other vertex; loops start at their smallest vertex.
///
/// \tparam Frame_field a `Frame_field_3` after `compute()` or `set_rotations()`
///         (which find its boundary faces)
/// \param ff the frame field (for the boundary and the positions)
/// \param edges its singular edges, as `singular_edges()` returns them
/// \param positions if given, the vertices' positions by vertex index, in
///        place of the mesh's (for the curves' lengths and the nodes' positions)
/// \returns the curves, the nodes and their counts
template <class Frame_field>
Singularity_graph singularity_graph(const Frame_field& ff, const std::vector<Singular_edge>& edges,
                                    const std::vector<Eigen::Vector3d>* positions = nullptr) {
  using Vertex_handle = typename Frame_field::Vertex_handle;
  std::vector<std::array<std::size_t, 2>> ends(edges.size());
  for (std::size_t k = 0; k < edges.size(); ++k) ends[k] = edges[k].vertices;
  const auto incident = internal::edges_at_vertices(ends);
  // Positions and places of the vertices that singular edges touch.
  std::map<std::size_t, Eigen::Vector3d> position;
  std::map<std::size_t, Eigen::Matrix3d> root; // A = g^{1/2}
  const std::vector<internal::Vertex_place> place = internal::vertex_places(ff);
  for (std::size_t i = 0; i < ff.size(); ++i)
    for (int k = 0; k < 4; ++k) {
      const Vertex_handle v = ff.cell(i)->vertex(k);
      const std::size_t j = ff.vertex_index(v);
      if (incident.count(j) && !position.count(j)) {
        position[j] = positions ? (*positions)[j] : internal::to_eigen_vector(v->point());
        root[j] = ff.metric_field().sqrt_metric(v);
      }
    }
  auto other = [&](std::size_t k, std::size_t v) { return edges[k].vertices[0] == v ? edges[k].vertices[1] : edges[k].vertices[0]; };
  const std::vector<std::size_t> bad_nodes = internal::non_meshable_nodes(edges, [&](std::size_t v) { return place[v]; });

  Singularity_graph g;
  std::vector<char> used(edges.size(), 0);
  auto trace = [&](std::size_t start, std::size_t first_edge) {
    Singular_curve c;
    c.vertices.push_back(start);
    std::size_t v = start, k = first_edge;
    for (;;) {
      used[k] = 1;
      c.edges.push_back(k);
      const Singular_edge& e = edges[k];
      if (e.type == Singularity_type::plus_quarter) ++c.plus_quarter_edges;
      else if (e.type == Singularity_type::minus_quarter) ++c.minus_quarter_edges;
      else ++c.non_meshable_edges;
      const std::size_t w = other(k, v);
      c.length += (position[w] - position[v]).norm();
      c.metric_length += (0.5 * (root[v] + root[w]) * (position[w] - position[v])).norm();
      c.vertices.push_back(w);
      v = w;
      const auto& list = incident.at(v);
      if (list.size() != 2) break; // a node
      k = list[0] == k ? list[1] : list[0];
      if (used[k]) break; // back at the start of a loop
    }
    c.closed = c.vertices.front() == c.vertices.back() && incident.at(start).size() == 2;
    return c;
  };
  for (const auto& [v, list] : incident) {
    if (list.size() == 2) continue;
    Singular_node node;
    node.vertex = v;
    node.position = position[v];
    node.degree = int(list.size());
    node.on_boundary = place[v] != internal::Vertex_place::interior;
    node.kind = list.size() >= 3 ? Singular_node::Kind::junction
                : node.on_boundary ? Singular_node::Kind::boundary_end
                                   : Singular_node::Kind::interior_end;
    node.meshable = !std::binary_search(bad_nodes.begin(), bad_nodes.end(), v);
    g.non_meshable_nodes += !node.meshable;
    g.nodes.push_back(node);
    if (node.kind == Singular_node::Kind::junction) ++g.junctions;
    else if (node.kind == Singular_node::Kind::boundary_end) ++g.boundary_ends;
    else ++g.interior_ends;
    for (std::size_t k : list)
      if (!used[k]) g.curves.push_back(trace(v, k));
  }
  for (std::size_t v : bad_nodes)
    if (incident.at(v).size() == 2) {
      g.curve_turns.push_back(v);
      g.curve_turn_positions.push_back(position[v]);
    }
  for (const auto& [v, list] : incident)
    if (list.size() == 2 && place[v] == internal::Vertex_place::smooth_boundary &&
        is_meshable(edges[list[0]].type) && is_meshable(edges[list[1]].type)) {
      g.surface_touches.push_back(v);
      g.surface_touch_positions.push_back(position[v]);
    }
  for (const auto& [v, list] : incident)
    for (std::size_t k : list)
      if (!used[k]) {
        g.curves.push_back(trace(v, k));
        ++g.closed_curves;
      }
  g.short_curves = short_singular_curves(g, 1);
  return g;
}

} // namespace CGAL_ext

#endif // CGAL_EXT_FRAME_FIELD_SINGULARITIES_3_H
