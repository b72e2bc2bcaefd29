// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_INTERNAL_TET_MESH_OVERLAP_H
#define CGAL_EXT_INTERNAL_TET_MESH_OVERLAP_H

/// \file
/// Exact detection of tetrahedra that overlap, or touch where they share no
/// vertex, in a list of positively oriented tetrahedra (compiled once, in
/// src/mesh). `build_triangulation_from_tets()` runs the three tests after it
/// has checked that every tetrahedron is positive and that the two cells of
/// each shared facet lie on opposite sides of it.
///
/// They look for the four signs of a mesh that is not embedded: its
/// boundary crossing or touching itself (`find_boundary_overlap()`), the
/// cells around an edge turning about it more than once
/// (`find_overlap_around_edge()`), the corners of the cells around a
/// boundary vertex overlapping (`find_overlap_around_vertex()`), and a part
/// of the mesh lying inside another one with no boundary contact
/// (`find_vertex_inside_tet()` on the boundary vertices). Together they are
/// complete: a mesh that passes all four covers no point twice.
///
/// Why (the degree argument). A generic point x is covered by deg(x)
/// tetrahedra; with every tetrahedron positive and the two cells of each
/// shared facet on opposite sides, deg changes only across boundary facets,
/// by one. Suppose deg = 2 somewhere. Some boundary facet F, of tetrahedron
/// T, has deg = 2 on its inner side; as no boundary facet crosses F, this
/// holds along all of F. Take a vertex p of F. If p lies in a tetrahedron
/// that does not use it, the fourth test finds it. Otherwise the second cover
/// near p comes from a tetrahedron T' that uses p, and in the sphere of
/// directions at p the corners of T and T' overlap next to the arc of F. The
/// same argument on that sphere (its boundary arcs are the boundary facets
/// through p, which do not cross either) leads to an end of the arc, the
/// direction of a boundary edge (p, q): either a corner at p of a
/// tetrahedron that does not use q contains that direction (the third test),
/// or two tetrahedra around the edge (p, q) overlap next to it (the second).

#include <array>
#include <cstddef>
#include <optional>
#include <vector>

namespace CGAL_ext {
namespace internal {

/// Two boundary triangles (indices into `triangles`) that meet elsewhere than
/// in the vertices and edge they share, decided with exact predicates; the
/// lexicographically smallest such pair, so that the answer does not depend
/// on the search order; none if the boundary is embedded.
///
/// In a conforming tetrahedral mesh two boundary facets meet only in their
/// common vertices and edge. Any other contact means that two parts of the
/// mesh overlap, fold back onto each other, or touch along a face, an edge or
/// at a point without sharing its vertices (which the walk would then treat
/// as a boundary):
/// - triangles with no common vertex must not meet;
/// - triangles with one common vertex p, (p, a, b) and (p, c, d), meet
///   elsewhere exactly when the segment (a, b) meets the second triangle or
///   the segment (c, d) the first one (their intersection is convex and
///   contains p, so it contains a segment from p, whose ray through the
///   cones of both triangles crosses (a, b) or (c, d) first);
/// - triangles with a common edge must not lie in one plane on the same side
///   of it.
/// \param points the vertex coordinates
/// \param triangles the boundary facets, as vertex indices into `points`
std::optional<std::array<std::size_t, 2>> find_boundary_overlap(const std::vector<std::array<double, 3>>& points,
                                                                 const std::vector<std::array<std::size_t, 3>>& triangles);

/// Two tetrahedra around a common edge whose wedges about the edge overlap.
struct Edge_overlap {
  /// The edge, as vertex indices, the smaller first.
  std::array<std::size_t, 2> edge;
  /// The two tetrahedra, as indices into the tet list, the smaller first.
  std::array<std::size_t, 2> tets;
};

/// The first edge (in the order of its vertex indices) about which two of
/// its tetrahedra overlap, decided with exact predicates; none if the
/// tetrahedra around every edge occupy disjoint wedges.
///
/// Each tetrahedron (a, b, c, d) occupies, about its edge (a, b), the wedge
/// between the half-planes through c and d (less than half a turn). The
/// wedges around an edge are sorted by angle exactly (`Angle_around_edge_3`)
/// and must not overlap: around an interior edge they then turn exactly once,
/// and around a boundary or non-manifold edge less than once. A mesh folded
/// over itself near a vertex has such an edge, even where its boundary
/// facets do not cross.
/// \param points the vertex coordinates
/// \param tets positively oriented tetrahedra, as vertex indices into `points`
std::optional<Edge_overlap> find_overlap_around_edge(const std::vector<std::array<double, 3>>& points,
                                                     const std::vector<std::array<std::size_t, 4>>& tets);

/// A boundary edge whose direction from one end lies in the corner at that
/// end of a tetrahedron that does not use the edge.
struct Vertex_overlap {
  /// The vertex p where the corners overlap, as an index into the points.
  std::size_t vertex;
  /// The other end q of the boundary edge (p, q).
  std::size_t edge_end;
  /// The tetrahedron whose corner at p contains the direction of q.
  std::size_t tet;
};

/// The smallest (p, q, tetrahedron) such that (p, q) is an edge of a
/// boundary triangle and the tetrahedron uses p but not q and its closed
/// corner at p (the cone of its three facets through p) contains q, decided
/// with exact orientation predicates; none otherwise.
///
/// Around an embedded boundary vertex the corners of the tetrahedra tile
/// the directions from p without overlap, and the direction of a boundary
/// edge is a vertex of that tiling, in no other corner. This finds parts of
/// a mesh that share a vertex and overlap around it without sharing an edge
/// (a fold about a vertex, or a tetrahedron inside a corner of a block that
/// touches it only at its vertices), which neither the boundary facets nor
/// the edges reveal.
/// \param points the vertex coordinates
/// \param tets positively oriented tetrahedra, as vertex indices into `points`
/// \param triangles the boundary facets, as vertex indices into `points`
std::optional<Vertex_overlap> find_overlap_around_vertex(const std::vector<std::array<double, 3>>& points,
                                                         const std::vector<std::array<std::size_t, 4>>& tets,
                                                         const std::vector<std::array<std::size_t, 3>>& triangles);

/// A vertex inside, or on, a tetrahedron that does not use it.
struct Vertex_in_tet {
  /// The vertex, as an index into the points.
  std::size_t vertex;
  /// The tetrahedron, as an index into the tet list.
  std::size_t tet;
};

/// The smallest (vertex, tetrahedron) pair such that the vertex, one of
/// `vertices`, lies in the closed tetrahedron without being one of its
/// vertices, decided with exact orientation predicates; none otherwise.
///
/// With the boundary vertices as `vertices`, this finds a part of the mesh
/// nested inside another part without touching its boundary (a second
/// component inside a cell of the first), which no boundary facet, edge or
/// vertex reveals.
/// \param points the vertex coordinates
/// \param tets positively oriented tetrahedra, as vertex indices into `points`
/// \param vertices the vertices to test, as indices into `points`
std::optional<Vertex_in_tet> find_vertex_inside_tet(const std::vector<std::array<double, 3>>& points,
                                                    const std::vector<std::array<std::size_t, 4>>& tets,
                                                    const std::vector<std::size_t>& vertices);

} // namespace internal
} // namespace CGAL_ext

#endif // CGAL_EXT_INTERNAL_TET_MESH_OVERLAP_H
