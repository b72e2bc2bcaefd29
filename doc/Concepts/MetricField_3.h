// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Documentation only (read by Doxygen, never compiled).

/// \ingroup PkgCGALExtMetric
/// \cgalConcept
///
/// A metric field on a CGAL 3D triangulation: what `Frame_field_3`,
/// `Sharp_features_3`, `Metric_transport_3` and `cell_transport()` read of a
/// metric. The metric `g` is symmetric positive definite; `A = g^{1/2}` is
/// given per vertex and, inside each cell, as a function whose derivatives
/// give a constant `curl A` per cell (doc/math.md sections 1 and 2). The
/// frame field measures lengths and angles with `A`, and the transports
/// integrate the connection of `A` and its curl.
///
/// The field also defines the **domain**: the cells with a non-negative
/// index in its cell index map. The frame field, the sharp features and the
/// transports take the domain and both index maps from the field, never
/// from a second argument, so that they cannot disagree.
///
/// `test/metric_field_archetype.h` is a model with exactly these members
/// (and no other), with archetypes of the two index maps; the tests compile
/// and run the frame field, the sharp features, the singular edges, the
/// repair and the transport with it.
///
/// \cgalHasModel `CGAL_ext::Metric_field_3`
/// \cgalHasModel `CGAL_ext::Property_map_metric_field_3`
class MetricField_3 {
public:
  /// The triangulation type, a CGAL `Triangulation_3` (for a tet mesh,
  /// `Tet_mesh_triangulation_3<Geom_traits>`).
  typedef unspecified_type Triangulation_3;
  /// `Triangulation_3::Vertex_handle`.
  typedef unspecified_type Vertex_handle;
  /// `Triangulation_3::Cell_handle`.
  typedef unspecified_type Cell_handle;
  /// `Triangulation_3::Point`.
  typedef unspecified_type Point_3;

  /// A model of `VertexIndexMap_3` on `Vertex_handle`.
  typedef unspecified_type Vertex_index_map;
  /// A model of `DomainCellIndexMap_3` on `Cell_handle`: it defines the domain.
  typedef unspecified_type Cell_index_map;

  /// The triangulation the metric lives on; it outlives the field.
  /// \returns the triangulation
  const Triangulation_3& triangulation() const;

  /// The vertex indices (they name vertices in messages and outputs).
  /// \returns the vertex index map
  Vertex_index_map vertex_index_map() const;

  /// The cell indices, non-negative exactly on the domain cells.
  /// \returns the cell index map
  Cell_index_map cell_index_map() const;

  /// `A = g^{1/2}` at a finite vertex of the domain (symmetric positive definite).
  /// \param v the vertex
  /// \returns `A` at `v` (3x3)
  Eigen::Matrix3d sqrt_metric(Vertex_handle v) const;

  /// `A` at a point of a domain cell (inside it or on its boundary), the
  /// cell's interpolation of its vertices' values.
  /// \param c the cell
  /// \param p the point
  /// \returns `A(p)` (3x3, symmetric)
  Eigen::Matrix3d A_at(Cell_handle c, const Point_3& p) const;

  /// The curl of `A` in a domain cell (column `i` is the curl of column `i`
  /// of `A`), constant in the cell.
  /// \param c the cell
  /// \returns the 3x3 matrix of the curls of the columns of `A`
  Eigen::Matrix3d curl(Cell_handle c) const;

  /// The barycentric coordinates of a point in a cell, in the order of the
  /// cell's vertices (summing to 1).
  /// \param c the cell
  /// \param p the point
  /// \returns the four coordinates, summing to 1
  Eigen::Vector4d barycentric_coordinates(Cell_handle c, const Point_3& p) const;
};
