// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_IO_MEDIT_MESH_H
#define CGAL_EXT_IO_MEDIT_MESH_H

/// \file Medit_mesh.h
/// Reading and writing ASCII Medit `.mesh` files (as MMG, Gmsh and TetGen write them).

#include <CGAL_ext/Input_error.h>

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace CGAL_ext {
namespace IO {

/// \ingroup PkgCGALExtIO
/// The content of a Medit `.mesh` file that this package uses.
///
/// All indices are 0-based (the file's are 1-based). Sections other than the
/// ones below (Corners, Ridges, RequiredVertices, Quadrilaterals, Normals...)
/// are read over and dropped. `Triangles` and `Edges` are kept as given,
/// which may include interior faces (TetGen and Gmsh write those). Volume
/// elements other than tetrahedra (non-empty `Hexahedra`, `Prisms`,
/// `Pyramids`) are an error, since leaving them out would change the domain.
struct Medit_mesh {
  std::vector<std::array<double, 3>> vertices;          ///< coordinates
  std::vector<int> vertex_references;                   ///< one per vertex
  std::vector<std::array<std::size_t, 4>> tetrahedra;   ///< 0-based vertex indices
  std::vector<int> tetrahedron_references;              ///< one per tetrahedron
  std::vector<std::array<std::size_t, 3>> triangles;    ///< 0-based vertex indices
  std::vector<int> triangle_references;                 ///< one per triangle
  std::vector<std::array<std::size_t, 2>> edges;        ///< 0-based vertex indices
  std::vector<int> edge_references;                     ///< one per edge
  std::vector<std::size_t> vertex_lines;                ///< 1-based line of each vertex record
  std::vector<std::size_t> tetrahedron_lines;           ///< 1-based line of each tetrahedron record
  int version = 2;                                      ///< the MeshVersionFormatted value
};

/// \ingroup PkgCGALExtIO
/// Reads an ASCII Medit `.mesh` file with a 3D tetrahedral mesh.
///
/// Accepted syntax: keywords in any case, `#` comments to the end of the
/// line, any white space (a keyword's value may be on the next line), the
/// sections in any order, `End` optional. Known sections whose records are
/// not used are skipped.
///
/// \param path the file to read
/// \returns the mesh, with every index checked to be in range
/// \throws Input_error naming the file, the line and the element for: a
///   missing or unreadable file, an empty file, an unknown keyword, a
///   truncated section, a count that the file cannot hold, an index that is
///   zero or out of range, a non-finite coordinate, `Dimension` other than
///   3, and a file without tetrahedra (a surface or 2D mesh).
Medit_mesh read_medit_mesh(const std::string& path);

/// \ingroup PkgCGALExtIO
/// Writes an ASCII Medit `.mesh` file (`MeshVersionFormatted 2`, `Dimension 3`,
/// Vertices, Tetrahedra, then Triangles and Edges when present), with
/// coordinates printed with 17 significant digits so that they read back exactly.
///
/// \param path the file to write; it is written to a temporary file next to
///   it first and renamed, so that a failure never leaves a partial file
/// \param mesh the mesh to write
/// \throws std::runtime_error if the file cannot be written
void write_medit_mesh(const std::string& path, const Medit_mesh& mesh);

} // namespace IO
} // namespace CGAL_ext

#endif // CGAL_EXT_IO_MEDIT_MESH_H
