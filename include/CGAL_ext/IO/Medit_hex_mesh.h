// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_IO_MEDIT_HEX_MESH_H
#define CGAL_EXT_IO_MEDIT_HEX_MESH_H

/// \file Medit_hex_mesh.h
/// Writing a hexahedral mesh as an ASCII Medit `.mesh` file.

#include <CGAL_ext/Hex_mesh_3.h>

#include <string>

namespace CGAL_ext {
namespace IO {

/// \ingroup PkgCGALExtIO
/// Writes a hexahedral mesh as an ASCII Medit `.mesh` file
/// (`MeshVersionFormatted 2`, `Dimension 3`): `Vertices` (reference 0),
/// `Hexahedra`, and when present `Quadrilaterals` and `Edges`, each element
/// with its reference (0 where the mesh has none), indices 1-based.
///
/// The hexahedra's vertices are written in `Hex_mesh_3`'s (VTK's) order,
/// which is the order Medit, MMG and Gmsh read: vertices 1-4 one face, 5-8
/// the opposite face, vertex `i + 4` above vertex `i`. Coordinates have 17
/// significant digits, so that reading gives back the same doubles. The
/// file is written to a temporary file next to `path`, then renamed.
/// \param path the file (conventionally `*.mesh`)
/// \param mesh the hexahedra, quadrilaterals and edges
/// \throws std::invalid_argument (naming `path` and the element, 1-based)
///   if a point is not finite, an index is out of range, an element repeats
///   a vertex, or a reference array is neither empty nor one per element
/// \throws std::runtime_error if the file cannot be written
void write_medit_hex_mesh(const std::string& path, const Hex_mesh_3& mesh);

} // namespace IO
} // namespace CGAL_ext

#endif // CGAL_EXT_IO_MEDIT_HEX_MESH_H
