// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_IO_HEXEX_FILE_H
#define CGAL_EXT_IO_HEXEX_FILE_H

/// \file Hexex_file.h
/// Integer-grid maps in HexEx's `.hexex` format: a tet mesh with the
/// parameters of each tetrahedron's four corners, the input of HexEx's hex
/// extraction (and what CubeCover's `integergrid` writes).

#include <CGAL_ext/Input_error.h>

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace CGAL_ext {
namespace IO {

/// \ingroup PkgCGALExtIO
/// A tet mesh with per-corner parameters, as a `.hexex` file holds it.
struct Hexex_file {
  /// The vertex positions.
  std::vector<Eigen::Vector3d> positions;
  /// The tetrahedra's vertex indices, 0-based.
  std::vector<std::array<std::size_t, 4>> tets;
  /// `parameters[t][c]`: the parameters of corner `c` of tetrahedron `t`.
  std::vector<std::array<Eigen::Vector3d, 4>> parameters;
};

/// \ingroup PkgCGALExtIO
/// Writes a `.hexex` file, as HexEx reads it and CubeCover writes it
/// (repository `evouga/CubeCover`, `src/WriteHexEx.cpp`):
/// \code
/// <number of vertices>
/// x y z                                (one line per vertex)
/// <number of tetrahedra>
/// v0 v1 v2 v3 u0 v0 w0 ... u3 v3 w3     (one line per tetrahedron)
/// \endcode
/// the vertex indices 0-based, then the parameters `(u, v, w)` of the four
/// corners in that order. Values are written with 17 significant digits, so
/// that reading gives back the same doubles (CubeCover writes 6). The file is
/// written to a temporary file next to `path`, then renamed.
/// \param path the file (conventionally `*.hexex`)
/// \param map the mesh and its parameters
/// \throws std::invalid_argument (naming `path`) if the arrays' sizes differ,
///   an index is out of range, a tetrahedron repeats a vertex, or a value is
///   not finite
/// \throws std::runtime_error if the file cannot be written
void write_hexex(const std::string& path, const Hexex_file& map);

/// \ingroup PkgCGALExtIO
/// Reads a `.hexex` file (see `write_hexex()` for the format): any white
/// space between tokens, `#` comments to the end of a line.
/// \param path the file
/// \returns the mesh and its parameters
/// \throws Input_error naming the file, the line and the vertex or
///   tetrahedron (1-based) for: a missing or unreadable file, a missing or
///   negative count, a count the rest of the file cannot hold, a truncated
///   record, a value that is not a number or not finite, a vertex index out
///   of range, a tetrahedron with a repeated vertex, and anything after the
///   last tetrahedron.
Hexex_file read_hexex(const std::string& path);

} // namespace IO
} // namespace CGAL_ext

#endif // CGAL_EXT_IO_HEXEX_FILE_H
