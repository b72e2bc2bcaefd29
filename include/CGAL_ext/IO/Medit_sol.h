// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_IO_MEDIT_SOL_H
#define CGAL_EXT_IO_MEDIT_SOL_H

/// \file Medit_sol.h
/// Reading and writing per-vertex metrics in ASCII Medit `.sol` files (as MMG writes them).

#include <CGAL_ext/Input_error.h>

#include <Eigen/Core>

#include <cstddef>
#include <string>
#include <vector>

namespace CGAL_ext {
namespace IO {

/// \ingroup PkgCGALExtIO
/// Pass as `expected_vertex_count` to `read_medit_sol()` to accept any count.
constexpr std::size_t any_vertex_count = static_cast<std::size_t>(-1);

/// \ingroup PkgCGALExtIO
/// Reads the metric of each vertex from an ASCII Medit `.sol` file.
///
/// Expected content (doc/math.md section 1):
/// \code
/// MeshVersionFormatted 2
/// Dimension 3
/// SolAtVertices
/// <n>
/// 1 3                        # one field, of type 3 (symmetric tensor)
/// m11 m21 m22 m31 m32 m33    # n lines: lower triangle by rows (xx, xy, yy, xz, yz, zz)
/// End
/// \endcode
/// or `1 1` (one scalar field), with one size `h > 0` per vertex, meaning
/// the isotropic metric `g = I / h^2`.
///
/// Accepted syntax: keywords in any case, `#` comments, any white space (a
/// value may be on the next line), `End` optional. Other `SolAt...`
/// sections (e.g. `SolAtTetrahedra`) are skipped, their record size being
/// known from their field types. Every value is checked; nothing is clamped.
///
/// \param path the file
/// \param expected_vertex_count the number of vertices of the mesh (the file
///        must have exactly that many records), or `any_vertex_count`
/// \returns `g` per vertex (0-based, in file order), each symmetric positive definite
/// \throws Input_error naming the file, the line and, where it applies, the
///   vertex (1-based) for: a missing, unreadable or empty file, an unknown
///   keyword or garbage, `Dimension` other than 3, a missing `SolAtVertices`
///   section or a second one, a count that differs from `expected_vertex_count`
///   or that the file cannot hold, a field count other than 1, a field type
///   other than 1 (scalar) or 3 (symmetric tensor), a truncated record, a
///   NaN or Inf, a size `h <= 0`, and a tensor that is not positive definite
///   (see `check_metric_tensor()`).
std::vector<Eigen::Matrix3d> read_medit_sol(const std::string& path,
                                            std::size_t expected_vertex_count = any_vertex_count);

/// \ingroup PkgCGALExtIO
/// Writes per-vertex metrics as an ASCII Medit `.sol` file with one field of
/// type 3, each tensor as its lower triangle by rows (`m11 m21 m22 m31 m32 m33`)
/// with 17 significant digits, so that `read_medit_sol()` gives back the
/// same values exactly (for symmetric tensors).
///
/// \param path the file; written to a temporary file next to it, then renamed
/// \param metrics `g` per vertex (only the lower triangle is written)
/// \throws std::invalid_argument if a tensor has a non-finite entry
/// \throws std::runtime_error if the file cannot be written
void write_medit_sol(const std::string& path, const std::vector<Eigen::Matrix3d>& metrics);

} // namespace IO
} // namespace CGAL_ext

#endif // CGAL_EXT_IO_MEDIT_SOL_H
