// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_TET_FACE_NEIGHBORS_H
#define CGAL_EXT_TET_FACE_NEIGHBORS_H

/// \file tet_face_neighbors.h
/// The face adjacency of an indexed tet mesh.

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace CGAL_ext {

/// \ingroup PkgCGALExtMesh
/// The neighbours of each tetrahedron across its four facets.
/// \param tets the tetrahedra's vertex indices
/// \returns `n[t][f]`: the tetrahedron sharing the facet of `t` opposite
///   `tets[t][f]`, or -1 if no other tetrahedron has that facet
/// \throws Input_error naming the tetrahedra (1-based) for a facet shared by
///   more than two tetrahedra, or a tetrahedron with a repeated vertex
std::vector<std::array<std::int64_t, 4>> tet_face_neighbors(const std::vector<std::array<std::size_t, 4>>& tets);

} // namespace CGAL_ext

#endif // CGAL_EXT_TET_FACE_NEIGHBORS_H
