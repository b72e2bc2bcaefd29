// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Documentation only (read by Doxygen, never compiled).

/// \ingroup PkgCGALExtMesh
/// \cgalConcept
///
/// Vertex indices of a tetrahedral mesh held in a triangulation: a readable
/// property map (Boost property map concept) from `Vertex_handle` to a
/// 0-based `std::size_t`, distinct for distinct finite vertices. The
/// indices name vertices in messages (1-based there, as in Medit files) and
/// in the outputs; they need not be contiguous (the per-vertex arrays are
/// sized by the largest index).
///
/// `test/metric_field_archetype.h` holds an archetype (the four types and
/// `get()` only), compiled and run in `test/test_concepts.cpp`.
///
/// \cgalHasModel `CGAL_ext::Tet_mesh_vertex_index_map`
class VertexIndexMap_3 {
public:
  /// `Triangulation_3::Vertex_handle`.
  typedef unspecified_type key_type;
  /// `std::size_t`.
  typedef unspecified_type value_type;
  /// `value_type` or a reference to it.
  typedef unspecified_type reference;
  /// `boost::readable_property_map_tag` or a refinement.
  typedef unspecified_type category;
};

/// The index of a vertex.
/// \param map the map
/// \param v a finite vertex
/// \returns its 0-based index
reference get(const VertexIndexMap_3& map, key_type v);
