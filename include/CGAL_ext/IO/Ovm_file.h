// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_IO_OVM_FILE_H
#define CGAL_EXT_IO_OVM_FILE_H

/// \file Ovm_file.h
/// Reading the hexahedra of an OpenVolumeMesh ASCII file (`.ovm`), as HexEx writes them.

#include <CGAL_ext/Hex_mesh_3.h>
#include <CGAL_ext/Input_error.h>

#include <cstddef>
#include <string>
#include <vector>

namespace CGAL_ext {
namespace IO {

/// \ingroup PkgCGALExtIO
/// A cell of an `.ovm` file that is not a hexahedron.
struct Ovm_other_cell {
  std::size_t cell = 0; ///< its 0-based index among the file's polyhedra (messages say `polyhedron cell + 1`)
  std::string reason;   ///< why it is not a hexahedron, e.g. "not 6 quadrilaterals"
};

/// \ingroup PkgCGALExtIO
/// The hexahedra of an `.ovm` file, and the cells that are not hexahedra.
struct Ovm_hex_mesh {
  /// All the file's vertices, and its hexahedral cells in VTK order
  /// (quadrilaterals and edges are left empty).
  Hex_mesh_3 mesh;
  /// The polyhedra that are not hexahedra (HexEx leaves such cells where
  /// its extraction fails), in file order.
  std::vector<Ovm_other_cell> other_cells;
};

/// \ingroup PkgCGALExtIO
/// Reads an OpenVolumeMesh ASCII file: `OVM ASCII`, then the sections
/// `Vertices` (`x y z` each), `Edges` (two vertex indices), `Faces` (a
/// valence, then that many half-edge indices) and `Polyhedra` (a valence,
/// then that many half-face indices), each with its count first; all
/// indices are 0-based. Whatever follows the polyhedra (property blocks) is
/// not read. Half-edge `2e` runs along edge `e` as listed, `2e + 1`
/// backwards; half-face `2f` is face `f` as listed, `2f + 1` the reverse.
/// OpenVolumeMesh orients a cell's half-faces with their normals (right-hand
/// rule) into the cell, which is what HexEx writes.
///
/// A cell is a hexahedron when its 6 half-faces are quadrilaterals that
/// form a closed, consistently oriented surface with 8 vertices of valence
/// 3 and the faces of a hexahedron. Its vertices are put in VTK order:
/// `0 1 2 3` the loop of its first half-face, `i + 4` the neighbour of `i`
/// off that face; so a cell whose half-faces point into it is positively
/// oriented when its geometry is.
/// \param path the file
/// \returns the hexahedra and the other cells
/// \throws Input_error naming the file, the line and the vertex, edge, face
///   or polyhedron (1-based) for: a missing or unreadable file, a missing
///   header (`OVM BINARY` is not read), a missing section or count, a count
///   the rest of the file cannot hold, a value that is not a number or not
///   finite, an index out of range, an edge from a vertex to itself, a face
///   of fewer than 3 half-edges, whose half-edges do not form a closed
///   loop or that uses an edge twice, and a polyhedron of fewer than 4
///   half-faces (or more than the file's faces).
Ovm_hex_mesh read_ovm_hex_mesh(const std::string& path);

} // namespace IO
} // namespace CGAL_ext

#endif // CGAL_EXT_IO_OVM_FILE_H
