// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Documentation only (read by Doxygen, never compiled).

/// \ingroup PkgCGALExtMesh
/// \cgalConcept
///
/// What the metric field, the frame field, the walk and the transports need
/// of the triangulation that holds a tetrahedral mesh. It is a CGAL
/// `Triangulation_3` (any triangulation data structure and vertex and cell
/// bases) with these properties:
///
/// - **Dimension 3**, with at least one cell in the domain (the domain is
///   given apart, by a `DomainCellIndexMap_3` or a predicate).
/// - **Positive orientation**: every finite cell of the domain has
///   `orientation(p0, p1, p2, p3) == POSITIVE` in its vertex order. The walk
///   relies on it for its exact side tests; `build_triangulation_from_tets()`
///   re-orients negative input tetrahedra and reports how many.
/// - **Exact predicates**: `Geom_traits` gives exact `Orientation_3` and
///   `Coplanar_orientation_3` (e.g. `Exact_predicates_inexact_constructions_kernel`),
///   so that every combinatorial decision of the walk is exact.
/// - **Double coordinates**: `CGAL::to_double()` of the point coordinates is
///   what the numerical parts (metric, frames, transports) use, and
///   `Point(double, double, double)` constructs a point.
/// - **Closed around the domain**: every facet of a domain cell has a cell
///   on its other side (an infinite cell or a finite cell outside the
///   domain), and one circulation around an edge visits every cell that
///   contains the edge, also where the domain touches itself along it. A
///   Delaunay triangulation has this; `build_triangulation_from_tets()`
///   builds it for any tetrahedral mesh, convex or not, by closing the
///   boundary with infinite cells.
///
/// For a non-convex domain the closing infinite cells are not the
/// geometrically valid infinite cells of CGAL, so CGAL's `locate()` and
/// `segment_traverser_*` must not be used; `Segment_walk_3` and
/// `Point_locator_3` never rely on convexity.
///
/// \cgalHasModel `CGAL_ext::Tet_mesh_triangulation_3` built by `CGAL_ext::build_triangulation_from_tets()`
/// \cgalHasModel `CGAL::Delaunay_triangulation_3` with a cell index map of its finite cells (a convex domain)
class TetMeshTriangulation_3 {
public:
  /// A CGAL 3D kernel with exact predicates.
  typedef unspecified_type Geom_traits;
  /// `Geom_traits::Point_3`.
  typedef unspecified_type Point;
  /// Handle to a vertex.
  typedef unspecified_type Vertex_handle;
  /// Handle to a cell.
  typedef unspecified_type Cell_handle;
};
