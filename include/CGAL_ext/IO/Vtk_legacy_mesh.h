// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_IO_VTK_LEGACY_MESH_H
#define CGAL_EXT_IO_VTK_LEGACY_MESH_H

/// \file Vtk_legacy_mesh.h
/// Reading tetrahedral meshes from legacy VTK `.vtk` files (unstructured grids).

#include <CGAL_ext/IO/Medit_mesh.h>
#include <CGAL_ext/Input_error.h>

#include <string>

namespace CGAL_ext {
namespace IO {

/// \ingroup PkgCGALExtIO
/// Reads a legacy VTK file (`# vtk DataFile Version 2.0` to `5.1`, ASCII or
/// binary) holding an `UNSTRUCTURED_GRID` of tetrahedra, into the same record
/// as `read_medit_mesh()`.
///
/// - `POINTS` in `float` or `double` (VTK 9 and ParaView write `double` for
///   double data; `float` points are rounded to single precision, in ASCII
///   files too);
/// - `CELLS` in both layouts: the classic one (`n size`, then per cell its
///   point count and ids; files up to version 4.2, and Gmsh's) and VTK 9's
///   (version 5.1: `OFFSETS` and `CONNECTIVITY` arrays, `vtktypeint64` or
///   `vtktypeint32`); then `CELL_TYPES`;
/// - tetrahedra (`VTK_TETRA`, 10) are kept; triangles (5) and lines (3) are
///   kept as Medit's `Triangles` and `Edges`; vertices, polygons, quads and
///   higher-order cells of dimension 0 to 2 are not read; other volume
///   cells (hexahedra, wedges, pyramids, polyhedra, higher-order ones) are an
///   error naming the cell and, in ASCII, the line of its type, since
///   leaving them out would change the domain;
/// - references are 0 (cell and point data, after the cells, are not read);
/// - a `FIELD` block before the points (VTK writes the dataset's field data
///   there, e.g. a time value) and `METADATA` blocks are read over.
///
/// Binary data are big-endian, as the format requires. The lines of the
/// vertices are recorded for ASCII files, those of the tetrahedra for ASCII
/// files in the classic layout; they are left empty otherwise.
/// \param path the file
/// \returns the mesh
/// \throws Input_error naming the file, the line (ASCII) or byte offset
///   (binary) and the point or cell (0-based, as VTK numbers them) for: a
///   missing or unreadable file, a missing header, another dataset than an
///   unstructured grid, a point type other than `float` or `double`, a
///   non-finite coordinate, a count the file cannot hold, a truncated
///   array, offsets that do not increase, a point id out of range or
///   repeated in a cell, a cell with the wrong number of points for its
///   type, an unknown cell type, another volume cell than the tetrahedron,
///   and a file without tetrahedra.
Medit_mesh read_vtk_legacy_mesh(const std::string& path);

} // namespace IO
} // namespace CGAL_ext

#endif // CGAL_EXT_IO_VTK_LEGACY_MESH_H
