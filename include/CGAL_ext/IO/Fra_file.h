// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_IO_FRA_FILE_H
#define CGAL_EXT_IO_FRA_FILE_H

/// \file Fra_file.h
/// Reading and writing per-tetrahedron frame fields in CubeCover's `.fra`
/// format, the input of CubeCover's integer-grid map and hex extraction.

#include <CGAL_ext/Input_error.h>

#include <array>
#include <string>
#include <vector>

namespace CGAL_ext {
namespace IO {

/// \ingroup PkgCGALExtIO
/// Writes one frame (3 vectors) per tetrahedron as a CubeCover `.fra` file.
///
/// The format, as CubeCover reads it (repository `evouga/CubeCover`, file
/// `src/ReadFrameField.cpp`, function `CubeCover::readFrameField()`) and
/// writes it (`src/WriteFrameFIeld.cpp`, `CubeCover::writeFrameField()`):
/// \code
/// FRA 1
/// <nframes> <vpt> <type>
/// x y z
/// ...
/// \endcode
/// that is: the word `FRA` and the version 1; the number of frames (of
/// tetrahedra), the number `vpt` of vectors per frame (3 here) and a type;
/// then `nframes * vpt` lines of 3 coordinates, vector `k` of tetrahedron `t`
/// on line `3 + vpt * t + k`.
///
/// `readFrameField()` reads white-space separated tokens with `operator>>`:
/// `header` must be `"FRA"`, `version` 1, `nframes` the number of tetrahedra
/// of the mesh given with it, `vpt > 0`, then `nframes * vpt * 3` doubles
/// (frame of tet `i` = rows `i * vpt` to `i * vpt + vpt - 1` of its `frames`
/// matrix). The `type` is read and not used; CubeCover's own writer writes 1,
/// and so does `write_fra()`. Frame `t` belongs to tetrahedron `t` (0-based)
/// of the `.mesh` file given to CubeCover with it.
///
/// Values are written with 17 significant digits (`%.17g`), so that reading
/// gives back the same doubles. The file is written to a temporary file next
/// to `path`, then renamed.
///
/// \param path the file (conventionally `*.fra`)
/// \param frames `frames[t][3 * k + i]` is coordinate `i` of vector `k` of the frame of tetrahedron `t`
/// \throws std::invalid_argument (naming `path` and the tetrahedron, 0-based)
///   if a value is NaN or infinite: CubeCover could not read it
/// \throws std::runtime_error if the file cannot be written
void write_fra(const std::string& path, const std::vector<std::array<double, 9>>& frames);

/// \ingroup PkgCGALExtIO
/// Reads a `.fra` file with 3 vectors per frame (see `write_fra()` for the
/// format), e.g. to check a file before giving it to CubeCover.
///
/// It accepts what CubeCover accepts (any white space between tokens, any
/// integer `type`) and is stricter where CubeCover would be silently wrong:
/// values must be finite and the file must end after the last frame.
///
/// \param path the file
/// \returns `frames[t][3 * k + i]` = coordinate `i` of vector `k` of the frame of tetrahedron `t`
/// \throws Input_error naming the file and the line (and, for a value, the
///   frame, 1-based) for: a missing, unreadable or empty file, a first word
///   other than `FRA`, a version other than 1, a missing or negative frame
///   count, a count the rest of the file cannot hold, a number of vectors per
///   frame other than 3, a missing type, a truncated frame, a value that is
///   not a number or not finite, and anything after the last frame.
std::vector<std::array<double, 9>> read_fra(const std::string& path);

} // namespace IO
} // namespace CGAL_ext

#endif // CGAL_EXT_IO_FRA_FILE_H
