// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_TET_MESH_TRIANGULATION_3_H
#define CGAL_EXT_TET_MESH_TRIANGULATION_3_H

/// \file Tet_mesh_triangulation_3.h
/// The triangulation type that holds a tetrahedral mesh read from a file,
/// with the file's vertex and tetrahedron numbering, and the predicate that
/// tells the cells of the domain from the others.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_3.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_data_structure_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <CGAL/property_map.h>

#include <cstddef>
#include <cstdint>

namespace CGAL_ext {

/// \ingroup PkgCGALExtMesh
/// Per-cell data of a `Tet_mesh_triangulation_3`.
///
/// A cell of the domain carries the 0-based index of its tetrahedron in the
/// mesh file and the file's reference (subdomain label). Every other cell
/// (the infinite cells, which close the boundary) has `index == -1`.
struct Tet_mesh_cell_info {
  /// 0-based tetrahedron index in the source file, or -1 outside the domain.
  std::int64_t index = -1;
  /// The Medit reference of the tetrahedron (0 outside the domain).
  int reference = 0;
  /// Whether the cell belongs to the domain.
  /// \returns true if `index >= 0`
  bool in_domain() const { return index >= 0; }
};

/// \ingroup PkgCGALExtMesh
/// A CGAL `Triangulation_3` whose vertices carry their 0-based index in the
/// mesh file (`std::size_t` info) and whose cells carry a `Tet_mesh_cell_info`.
///
/// It is built from a tetrahedron list by `build_triangulation_from_tets()`,
/// not by insertion: its finite cells are exactly the input tetrahedra, and
/// every boundary facet of the domain is closed by an infinite cell. For a
/// non-convex domain the infinite cells are therefore not geometrically
/// valid CGAL infinite cells, and CGAL functions that rely on the convex-hull
/// property (`locate()`, `segment_traverser_*`) must not be used on it; use
/// `Segment_walk_3` and `Point_locator_3` instead.
///
/// \tparam Geom_traits a CGAL 3D kernel; the default,
///         `Exact_predicates_inexact_constructions_kernel`, gives exact
///         predicates on double coordinates.
template <class Geom_traits = CGAL::Exact_predicates_inexact_constructions_kernel>
using Tet_mesh_triangulation_3 = CGAL::Triangulation_3<
    Geom_traits,
    CGAL::Triangulation_data_structure_3<
        CGAL::Triangulation_vertex_base_with_info_3<std::size_t, Geom_traits>,
        CGAL::Triangulation_cell_base_with_info_3<Tet_mesh_cell_info, Geom_traits>>>;

/// \ingroup PkgCGALExtMesh
/// Unary predicate on cell handles: `true` for the cells of the domain of a
/// `Tet_mesh_triangulation_3` (those with a tetrahedron index).
///
/// Pass it to `Segment_walk_3` and `Point_locator_3` for a tet mesh (their
/// default, `Is_finite_cell`, takes every finite cell: right for a convex
/// Delaunay triangulation only). The metric and frame fields recognise the
/// domain by `Tet_mesh_cell_index_map` instead, which is negative exactly
/// where this predicate is false. `Metric_transport_3` takes no predicate:
/// its walk uses this one when the field has that map.
struct Is_tet_mesh_domain_cell {
  /// \tparam Cell_handle a handle to a cell with `Tet_mesh_cell_info` info
  /// \param c the cell
  /// \returns true if `c` is a cell of the domain (`c->info().in_domain()`)
  template <class Cell_handle>
  bool operator()(const Cell_handle& c) const { return c->info().in_domain(); }
};

/// \ingroup PkgCGALExtMesh
/// Domain predicate for any triangulation: every finite cell is in the domain.
/// Use it for a Delaunay triangulation of a convex domain.
///
/// \tparam Triangulation a CGAL `Triangulation_3`
template <class Triangulation>
class Is_finite_cell {
public:
  /// \param tr the triangulation whose finite cells form the domain
  explicit Is_finite_cell(const Triangulation& tr) : tr_(&tr) {}
  /// \param c the cell
  /// \returns true if `c` is a finite cell of the triangulation
  bool operator()(typename Triangulation::Cell_handle c) const { return !tr_->is_infinite(c); }

private:
  const Triangulation* tr_;
};

/// \ingroup PkgCGALExtMesh
/// Read-only property map from a vertex handle to its 0-based file index
/// (`v->info()`).
/// \tparam Triangulation a `Tet_mesh_triangulation_3`
template <class Triangulation>
struct Tet_mesh_vertex_index_map {
  using key_type = typename Triangulation::Vertex_handle; ///< the vertex handle
  using value_type = std::size_t;                          ///< the index type
  using reference = std::size_t;                           ///< returned by value
  using category = boost::readable_property_map_tag;       ///< read-only
  /// \param v the vertex
  friend std::size_t get(const Tet_mesh_vertex_index_map&, const key_type& v) { return v->info(); }
};

/// \ingroup PkgCGALExtMesh
/// Read-only property map from a cell handle to its 0-based tetrahedron index
/// (-1 outside the domain).
/// \tparam Triangulation a `Tet_mesh_triangulation_3`
template <class Triangulation>
struct Tet_mesh_cell_index_map {
  using key_type = typename Triangulation::Cell_handle; ///< the cell handle
  using value_type = std::int64_t;                       ///< the index type
  using reference = std::int64_t;                        ///< returned by value
  using category = boost::readable_property_map_tag;     ///< read-only
  /// \param c the cell
  friend std::int64_t get(const Tet_mesh_cell_index_map&, const key_type& c) { return c->info().index; }
};

/// \ingroup PkgCGALExtMesh
/// Unary predicate on cell handles: `true` for the cells of the domain that
/// a cell index map defines (a model of `DomainCellIndexMap_3`: non-negative
/// index). `Metric_transport_3` walks the metric field's domain with it, so
/// that the walk and the field agree by construction.
/// \tparam CellIndexMap a model of `DomainCellIndexMap_3`
template <class CellIndexMap>
class Is_indexed_domain_cell {
public:
  /// \param cim the cell index map
  explicit Is_indexed_domain_cell(CellIndexMap cim = CellIndexMap()) : cim_(cim) {}
  /// \tparam Cell_handle the map's key type
  /// \param c the cell
  /// \returns true if the index of `c` is non-negative
  template <class Cell_handle>
  bool operator()(const Cell_handle& c) const { return get(cim_, c) >= 0; }

private:
  CellIndexMap cim_;
};

} // namespace CGAL_ext

#endif // CGAL_EXT_TET_MESH_TRIANGULATION_3_H
