// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_HEX_MESH_3_H
#define CGAL_EXT_HEX_MESH_3_H

/// \file Hex_mesh_3.h
/// A hexahedral mesh as an indexed array, and its boundary quadrilaterals.

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace CGAL_ext {

/// \ingroup PkgCGALExtHex
/// A hexahedral mesh: points, hexahedra, and optionally the boundary
/// quadrilaterals and feature edges, each with an integer reference (Medit's
/// "ref", a physical group in Gmsh).
///
/// All indices are 0-based. Each hexahedron lists its vertices in VTK's
/// order, which Gmsh and Medit use too: `0 1 2 3` go around one face,
/// counter-clockwise seen from inside the hexahedron, and vertex `i + 4` is
/// the neighbour of vertex `i` on the opposite face. A hexahedron is
/// positively oriented when `(p1 - p0, p3 - p0, p4 - p0)` is a direct frame.
/// The reference arrays are either empty (all references 0) or have one
/// entry per element.
struct Hex_mesh_3 {
  std::vector<Eigen::Vector3d> points;                   ///< vertex positions
  std::vector<std::array<std::size_t, 8>> hexahedra;     ///< 8 vertex indices each, VTK order
  std::vector<int> hexahedron_references;                ///< one per hexahedron, or empty
  std::vector<std::array<std::size_t, 4>> quadrilaterals; ///< boundary quads, outward (counter-clockwise seen from outside)
  std::vector<int> quadrilateral_references;             ///< one per quadrilateral, or empty
  std::vector<std::array<std::size_t, 2>> edges;         ///< feature edges
  std::vector<int> edge_references;                      ///< one per edge, or empty
};

/// \ingroup PkgCGALExtHex
/// The local vertices of the 6 faces of a hexahedron in VTK order, each
/// counter-clockwise seen from outside when the hexahedron is positively
/// oriented.
inline constexpr std::array<std::array<int, 4>, 6> hex_faces = {{
    {{0, 3, 2, 1}}, {{4, 5, 6, 7}}, {{0, 1, 5, 4}}, {{1, 2, 6, 5}}, {{2, 3, 7, 6}}, {{3, 0, 4, 7}}}};

/// \ingroup PkgCGALExtHex
/// The local vertices of the 12 edges of a hexahedron in VTK order, as three
/// families of four parallel edges, each edge oriented like the others of
/// its family (along the local `u`, `v` and `w` axes).
inline constexpr std::array<std::array<std::array<int, 2>, 4>, 3> hex_edge_families = {{
    {{{{0, 1}}, {{3, 2}}, {{4, 5}}, {{7, 6}}}},
    {{{{0, 3}}, {{1, 2}}, {{4, 7}}, {{5, 6}}}},
    {{{{0, 4}}, {{1, 5}}, {{2, 6}}, {{3, 7}}}}}};

/// \ingroup PkgCGALExtHex
/// The faces of a hexahedral mesh that belong to exactly one hexahedron,
/// oriented outward from it (counter-clockwise seen from outside when the
/// hexahedron is positively oriented), in the order of the hexahedra and
/// then of `hex_faces`. Faces are matched by their vertex sets, so the
/// result does not depend on the hexahedra's orientation.
/// \param hexahedra 8 vertex indices per hexahedron, VTK order
/// \returns the boundary faces
/// \throws std::invalid_argument if a face belongs to more than two
///   hexahedra (a non-manifold mesh), naming the face's vertices
std::vector<std::array<std::size_t, 4>> hex_mesh_boundary_quadrilaterals(
    const std::vector<std::array<std::size_t, 8>>& hexahedra);

} // namespace CGAL_ext

#endif // CGAL_EXT_HEX_MESH_3_H
