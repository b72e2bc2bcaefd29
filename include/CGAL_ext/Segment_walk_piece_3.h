// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_SEGMENT_WALK_PIECE_3_H
#define CGAL_EXT_SEGMENT_WALK_PIECE_3_H

/// \file Segment_walk_piece_3.h
/// A simplex of a tetrahedral domain (or a gap outside it) with a parameter
/// interval: a piece of the output of `Segment_walk_3`, and the result of
/// `Point_locator_3`.

#include <array>

namespace CGAL_ext {

/// \ingroup PkgCGALExtWalk
/// One piece of the output of `Segment_walk_3`: a simplex of the domain (or a
/// gap outside it) and the parameter interval where the segment
/// \f$x(t) = q + t (p - q)\f$ lies in its relative interior.
///
/// \tparam Triangulation a CGAL `Triangulation_3`
template <class Triangulation>
struct Segment_walk_piece_3 {
  /// -1 for a gap outside the domain, 0 vertex, 1 edge, 2 facet, 3 cell.
  int dimension = -1;
  /// The first `dimension + 1` entries are the vertices of the simplex (in no
  /// particular order); the others are default-constructed.
  std::array<typename Triangulation::Vertex_handle, 4> vertices{};
  /// A domain cell incident to the simplex (the cell itself for dimension 3);
  /// default-constructed for a gap.
  typename Triangulation::Cell_handle cell{};
  /// Start of the parameter interval.
  double t_in = 0;
  /// End of the parameter interval (`t_in == t_out` for a transversal crossing).
  double t_out = 0;
};

} // namespace CGAL_ext

#endif // CGAL_EXT_SEGMENT_WALK_PIECE_3_H
