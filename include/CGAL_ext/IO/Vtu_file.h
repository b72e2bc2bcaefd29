// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_IO_VTU_FILE_H
#define CGAL_EXT_IO_VTU_FILE_H

/// \file Vtu_file.h
/// Writing tetrahedra, hexahedra and segments with named data arrays as VTK XML
/// UnstructuredGrid (`.vtu`) files, for ParaView.

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace CGAL_ext {
namespace IO {

/// \ingroup PkgCGALExtIO
/// One named data array of a VTU file: point data (one tuple per point) or
/// cell data (one tuple per cell).
///
/// The tuples are stored one after the other: `values[components * i + c]`
/// is component `c` of the tuple of element `i`. ParaView shows 1 component
/// as a scalar, 3 as a vector (glyphs, streamlines) and 9 as a 3x3 tensor
/// (row-major: `values[9 * i + 3 * r + c]` is entry `(r, c)`).
struct Vtu_array {
  /// The array's name in ParaView; not empty, unique among the point (or cell) arrays of a file.
  std::string name;
  /// Number of components per tuple (at least 1): 1 scalar, 3 vector, 9 tensor...
  int components = 1;
  /// `count * components` values, `count` being the number of points or of cells.
  std::vector<double> values;
  /// Write as `Int32` instead of `Float64`; every value must then be an
  /// integer in the range of `Int32` (no NaN).
  bool integer = false;
};

/// \ingroup PkgCGALExtIO
/// How a VTU file is encoded.
struct Vtu_options {
  /// `true`: every DataArray is `format="binary"`, inline base64 of a
  /// `UInt64` byte count followed by the little-endian values (compact and
  /// exact); `false`: `format="ascii"` (readable; doubles with the shortest
  /// decimal form that reads back to the same value).
  bool binary = true;
};

/// \ingroup PkgCGALExtIO
/// Writes a tetrahedral mesh and its data arrays as a VTK XML UnstructuredGrid
/// file (version 1.0, `header_type="UInt64"`, `byte_order="LittleEndian"`),
/// cell type 10 (`VTK_TETRA`). See doc/output_files.md for the layout.
///
/// Points are `Float64`, connectivity and offsets `Int64`, cell types
/// `UInt8`. A mesh without cells (or without points) still gives a valid
/// file, which ParaView opens as an empty grid.
///
/// Everything is checked before the file is opened; the file is written to a
/// temporary file next to `path`, then renamed, so that an error never leaves
/// a partial file nor changes an existing `path`.
///
/// \param path the file (conventionally `*.vtu`)
/// \param points the vertices, all coordinates finite
/// \param tets 0-based vertex indices of each tetrahedron (VTK vertex order)
/// \param cell_data arrays with one tuple per tetrahedron
/// \param point_data arrays with one tuple per point
/// \param options the encoding
/// \throws std::invalid_argument, with a message that names `path` and the
///   problem, for: a non-finite point coordinate (with the point's 0-based
///   index), a vertex index out of range (with the 0-based number of the
///   tetrahedron), an array whose number of values is not the number of
///   points/cells times its components (with the array's name), an empty or
///   duplicate array name, a name with a control character, fewer than one
///   component, an `integer` array with a value that is not an `Int32`, and,
///   in ASCII mode only, a NaN or infinite value (VTK's ASCII parsing of
///   them is unreliable: VTK 9.1 reads `-inf` as `inf`, older versions stop
///   reading the array at `nan`; use binary, where NaN and infinities are
///   kept bit for bit and ParaView shows NaN as such)
/// \throws std::runtime_error if the file cannot be written
void write_vtu_tetrahedra(const std::string& path, const std::vector<std::array<double, 3>>& points,
                          const std::vector<std::array<std::size_t, 4>>& tets, const std::vector<Vtu_array>& cell_data,
                          const std::vector<Vtu_array>& point_data = {}, const Vtu_options& options = {});

/// \ingroup PkgCGALExtIO
/// Writes line segments (e.g. singular edges of a frame field, streamlines)
/// and their data arrays as a VTK XML UnstructuredGrid file, cell type 3
/// (`VTK_LINE`). Same layout, checks and atomic write as `write_vtu_tetrahedra()`.
///
/// \param path the file (conventionally `*.vtu`)
/// \param points the vertices, all coordinates finite
/// \param segments 0-based vertex indices of each segment
/// \param cell_data arrays with one tuple per segment
/// \param point_data arrays with one tuple per point
/// \param options the encoding
/// \throws std::invalid_argument as `write_vtu_tetrahedra()` (naming the segment)
/// \throws std::runtime_error if the file cannot be written
void write_vtu_segments(const std::string& path, const std::vector<std::array<double, 3>>& points,
                        const std::vector<std::array<std::size_t, 2>>& segments,
                        const std::vector<Vtu_array>& cell_data, const std::vector<Vtu_array>& point_data = {},
                        const Vtu_options& options = {});

/// \ingroup PkgCGALExtIO
/// Writes a hexahedral mesh and its data arrays as a VTK XML UnstructuredGrid
/// file, cell type 12 (`VTK_HEXAHEDRON`), the vertices in VTK's order
/// (`Hex_mesh_3`). Same layout, checks and atomic write as `write_vtu_tetrahedra()`.
///
/// \param path the file (conventionally `*.vtu`)
/// \param points the vertices, all coordinates finite
/// \param hexahedra 0-based vertex indices of each hexahedron, VTK order
/// \param cell_data arrays with one tuple per hexahedron
/// \param point_data arrays with one tuple per point
/// \param options the encoding
/// \throws std::invalid_argument as `write_vtu_tetrahedra()` (naming the hexahedron)
/// \throws std::runtime_error if the file cannot be written
void write_vtu_hexahedra(const std::string& path, const std::vector<std::array<double, 3>>& points,
                         const std::vector<std::array<std::size_t, 8>>& hexahedra,
                         const std::vector<Vtu_array>& cell_data, const std::vector<Vtu_array>& point_data = {},
                         const Vtu_options& options = {});

} // namespace IO
} // namespace CGAL_ext

#endif // CGAL_EXT_IO_VTU_FILE_H
