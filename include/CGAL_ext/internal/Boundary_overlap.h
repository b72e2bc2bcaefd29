// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_INTERNAL_BOUNDARY_OVERLAP_H
#define CGAL_EXT_INTERNAL_BOUNDARY_OVERLAP_H

/// \file
/// Detection of tetrahedra that overlap or touch without sharing vertices,
/// through the boundary facets of the mesh (compiled once, in src/mesh).

#include <array>
#include <cstddef>
#include <optional>
#include <vector>

namespace CGAL_ext {
namespace internal {

/// Two boundary triangles (indices into `triangles`) that share no vertex
/// but meet (cross, overlap in a common plane, or touch at a point), with
/// exact predicates; the lexicographically smallest such pair, so that the
/// answer does not depend on the search order; none for a conforming mesh.
///
/// In a conforming tetrahedral mesh two boundary facets meet only in the
/// vertices, edges they share; any other contact means that two parts of the
/// mesh overlap, or touch along a face, an edge or at a point without sharing
/// its vertices (which the walk would then treat as a boundary). Pairs that
/// share a vertex are not tested: a boundary folding back onto itself near a
/// shared vertex is not detected, nor a component nested inside a cell of
/// another with no boundary contact.
/// \param points the vertex coordinates
/// \param triangles the boundary facets, as vertex indices into `points`
std::optional<std::array<std::size_t, 2>> find_boundary_overlap(const std::vector<std::array<double, 3>>& points,
                                                                 const std::vector<std::array<std::size_t, 3>>& triangles);

} // namespace internal
} // namespace CGAL_ext

#endif // CGAL_EXT_INTERNAL_BOUNDARY_OVERLAP_H
