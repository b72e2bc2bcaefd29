// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Documentation only (read by Doxygen, never compiled).

/// \ingroup PkgCGALExtMesh
/// \cgalConcept
///
/// The domain of a tetrahedral mesh held in a triangulation, as a cell
/// index map: a readable property map (Boost property map concept) from
/// `Cell_handle` to a signed integer.
///
/// - A cell belongs to the domain if and only if its index is non-negative;
///   every other cell, the infinite cells included, has a negative index.
/// - The domain's indices are exactly `0..n-1`, each once, for its `n`
///   cells: they number the frames of `Frame_field_3`, the per-cell data of
///   the metric field and the tetrahedra of the outputs. `Frame_field_3`
///   throws `Input_error` if they are not.
///
/// A metric field (`MetricField_3::cell_index_map()`) carries the map, and
/// every component on the field takes the domain from it;
/// `Is_indexed_domain_cell` turns it into the predicate `Segment_walk_3` and
/// `Point_locator_3` take.
///
/// `test/metric_field_archetype.h` holds an archetype (the four types and
/// `get()` only), compiled and run in `test/test_concepts.cpp`.
///
/// \cgalHasModel `CGAL_ext::Tet_mesh_cell_index_map`
class DomainCellIndexMap_3 {
public:
  /// `Triangulation_3::Cell_handle`.
  typedef unspecified_type key_type;
  /// A signed integral type (`std::int64_t` for the default model).
  typedef unspecified_type value_type;
  /// `value_type` or a reference to it.
  typedef unspecified_type reference;
  /// `boost::readable_property_map_tag` or a refinement.
  typedef unspecified_type category;
};

/// The index of a cell.
/// \param map the map
/// \param c a cell of the triangulation (finite or infinite)
/// \returns its index in `0..n-1` in the domain, negative outside
reference get(const DomainCellIndexMap_3& map, key_type c);
