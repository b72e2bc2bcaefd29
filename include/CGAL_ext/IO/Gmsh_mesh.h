// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_IO_GMSH_MESH_H
#define CGAL_EXT_IO_GMSH_MESH_H

/// \file Gmsh_mesh.h
/// Reading Gmsh `.msh` tetrahedral meshes (formats 2.2 and 4.1, ASCII and binary).

#include <CGAL_ext/IO/Medit_mesh.h>
#include <CGAL_ext/Input_error.h>

#include <string>

namespace CGAL_ext {
namespace IO {

/// \ingroup PkgCGALExtIO
/// Reads a Gmsh `.msh` file with a 3D tetrahedral mesh: MSH 2.2 (2.0 to
/// 2.2) or 4.1, ASCII or binary (little-endian, as Gmsh writes it on x86
/// and ARM), into the same record as `read_medit_mesh()`.
///
/// - The vertices are the file's nodes in the order the file lists them
///   (so a `.sol` or a data array in that order matches them); their
///   references are 0. Node tags may be any positive integers, in any
///   order and with gaps (MSH 4.1 writes them per entity).
/// - Linear tetrahedra (element type 4) are kept, with their physical
///   group as reference: in MSH 2.2 the element's first tag, in MSH 4.1
///   the first physical tag of the element's entity (0 if it has none). An
///   entity in several physical groups gives each element once, with the
///   first group, not once per group (MSH 2.2 lists such an element once
///   per group, with each group's tag and the same elementary tag: the
///   later listings, same type, nodes and elementary tag and another
///   physical tag, are left out; any other repeat is kept, for the
///   triangulation to report).
/// - Triangles (type 2) and lines (type 1) are kept as Medit's `Triangles`
///   and `Edges`, with their references likewise; points (type 15) and other
///   elements of dimension 0 to 2 (quadrangles, higher-order ones) are not
///   read.
/// - Other volume elements (hexahedra, prisms, pyramids, higher-order
///   tetrahedra) are an error, as in `read_medit_mesh()`: leaving them out
///   would change the domain.
/// - Sections other than `$MeshFormat`, `$Entities`, `$Nodes` and
///   `$Elements` (`$PhysicalNames`, `$NodeData`, `$Periodic`...) are skipped.
///
/// The line of each vertex and tetrahedron is recorded for ASCII files
/// (`Medit_mesh::vertex_lines`, `tetrahedron_lines`), and left empty for
/// binary ones.
/// \param path the file
/// \returns the mesh, with every node reference resolved to a 0-based index
/// \throws Input_error naming the file, the line (ASCII; the byte offset in
///   the message for binary data) and the node or element tag for: a missing
///   or unreadable file, a missing `$MeshFormat`, a version other than 2.x
///   or 4.1 (4.0 is not read: Gmsh saves 4.1 by default), a data size other
///   than 8, a big-endian binary file, a partitioned mesh, a truncated
///   section, a count the file cannot hold, a non-finite coordinate, a node
///   tag given twice, an element that uses an unknown node tag or repeats a
///   node, an unknown element type, another volume element than the linear
///   tetrahedron, and a file without tetrahedra.
Medit_mesh read_gmsh_mesh(const std::string& path);

} // namespace IO
} // namespace CGAL_ext

#endif // CGAL_EXT_IO_GMSH_MESH_H
