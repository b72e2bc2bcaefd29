// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_POINT_LOCATOR_3_H
#define CGAL_EXT_POINT_LOCATOR_3_H

/// \file Point_locator_3.h
/// Exact point location in the domain of a triangulation, valid for
/// non-convex `Tet_mesh_triangulation_3` domains (where CGAL's `locate()`
/// must not be used).

#include <CGAL_ext/Segment_walk_3.h>

#include <utility>

namespace CGAL_ext {

/// \ingroup PkgCGALExtWalk
/// Exact point location: the lowest-dimensional simplex of the domain
/// containing a point, or "outside".
///
/// It is the location step of `Segment_walk_3` (a visibility walk from a hint
/// or from a coarse grid of cells, with an exact segment walk from a vertex
/// as fallback when the visibility walk meets the boundary of a non-convex
/// domain); no cell is ever scanned linearly.
///
/// \tparam Triangulation a model of `TetMeshTriangulation_3`, as for `Segment_walk_3`
/// \tparam Domain_predicate a unary predicate on `Cell_handle`, true for the domain cells
template <class Triangulation, class Domain_predicate = Is_finite_cell<Triangulation>>
class Point_locator_3 {
public:
  /// The point type.
  using Point = typename Triangulation::Point;
  /// Cell handle type.
  using Cell_handle = typename Triangulation::Cell_handle;
  /// The result: `dimension` -1 (outside the closed domain), 0, 1, 2 or 3,
  /// the simplex's vertices and a domain cell incident to it; `t_in == t_out == 0`.
  using Location = Segment_walk_piece_3<Triangulation>;

  /// \param tr the triangulation; it must outlive the locator and not change
  /// \param in_domain the domain predicate
  /// \throws std::invalid_argument if `tr.dimension() < 3`
  Point_locator_3(const Triangulation& tr, Domain_predicate in_domain) : walk_(tr, std::move(in_domain)) {}

  /// Locates `x`.
  /// \param x the point
  /// \param hint a cell near `x` (ignored if null or not a domain cell)
  /// \returns the location of `x` (see `Location`)
  /// \throws std::invalid_argument if a coordinate of `x` is not finite
  Location operator()(const Point& x, Cell_handle hint = Cell_handle()) const { return walk_.locate(x, hint); }

private:
  Segment_walk_3<Triangulation, Domain_predicate> walk_;
};

} // namespace CGAL_ext

#endif // CGAL_EXT_POINT_LOCATOR_3_H
