// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_IO_PERM_FILE_H
#define CGAL_EXT_IO_PERM_FILE_H

/// \file Perm_file.h
/// Reading and writing the face matchings of a frame field in CubeCover's
/// `.perm` format, which goes with a `.fra` file.

#include <CGAL_ext/Input_error.h>

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace CGAL_ext {
namespace IO {

/// \ingroup PkgCGALExtIO
/// The matching across one interior face, as a `.perm` line holds it.
struct Perm_face {
  /** @{ */
  /// The 0-based indices of the two tetrahedra sharing the face.
  std::size_t tet1 = 0, tet2 = 0;
  /** @} */
  /// The signed, 1-based vector correspondence: vector `k` of `tet1` times
  /// `sign(p[k])` is vector `|p[k]| - 1` of `tet2` (vectors numbered from 0
  /// here, as in the `.fra` file's order).
  std::array<int, 3> p{{1, 2, 3}};
};

/// \ingroup PkgCGALExtIO
/// The contents of a `.perm` file.
struct Perm_file {
  /// The number of tetrahedra of the mesh the file belongs to.
  std::size_t tets = 0;
  /// The faces with a matching other than the identity.
  std::vector<Perm_face> faces;
};

/// \ingroup PkgCGALExtIO
/// Writes face matchings as a CubeCover `.perm` file.
///
/// The format, as CubeCover reads it (`evouga/CubeCover`, `src/ReadFrameField.cpp`,
/// `readFrameField()`, then `fromFramesAndAssignments()` in `src/FrameField.cpp`)
/// and writes it (`src/WriteFrameFIeld.cpp`):
/// \code
/// PERM 1
/// <ntets> <nfaces> 3
/// t1 t2 p1 p2 p3
/// ...
/// \endcode
/// the number of tetrahedra of the mesh, the number of face lines and the
/// number of vectors per frame; then one line per interior face whose
/// matching is not the identity, with the 0-based indices of its two
/// tetrahedra and the signed permutation (see `Perm_face`). Faces not listed
/// have the identity matching; each face is listed at most once, in either
/// orientation (CubeCover inverts the permutation for the other one).
/// The file is written to a temporary file next to `path`, then renamed.
///
/// \param path the file (conventionally `*.perm`, next to the `.fra` file)
/// \param file the number of tetrahedra and the faces
/// \throws std::invalid_argument (naming `path` and the face, 0-based) if a
///   tetrahedron index is out of range, a face joins a tetrahedron to itself,
///   a face is listed twice (in either orientation) or `p` is not a signed
///   permutation of 1, 2, 3: the file would not read back
/// \throws std::runtime_error if the file cannot be written
void write_perm(const std::string& path, const Perm_file& file);

/// \ingroup PkgCGALExtIO
/// Reads a `.perm` file with 3 vectors per frame (see `write_perm()`).
///
/// It accepts what CubeCover accepts and is stricter where CubeCover would
/// fail later or be silently wrong: the file must end after the last face.
/// It does not know the mesh, so it cannot check that the two tetrahedra of
/// a line share a face; CubeCover does.
///
/// \param path the file
/// \returns the number of tetrahedra and the faces, in the file's order
/// \throws Input_error naming the file and the line (and, for a face line,
///   the face, 1-based) for: a missing, unreadable or empty file, a first word
///   other than `PERM`, a version other than 1, a negative or missing count,
///   a face count the rest of the file cannot hold, a number of vectors per
///   face other than 3, a tetrahedron index out of range, a face joining a
///   tetrahedron to itself, a face listed twice (in either orientation), an
///   entry that is not a signed permutation of 1, 2, 3, a truncated line and
///   anything after the last face.
Perm_file read_perm(const std::string& path);

} // namespace IO
} // namespace CGAL_ext

#endif // CGAL_EXT_IO_PERM_FILE_H
