// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Reading a closed surface (OFF, OBJ, STL, PLY) for Mesh_3: kept apart from
// tetrahedralize.cpp so that the reader compiles, and is fuzzed, without
// instantiating Mesh_3.
#ifndef CGAL_EXT_SRC_MESHING_READ_CLOSED_SURFACE_H
#define CGAL_EXT_SRC_MESHING_READ_CLOSED_SURFACE_H

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <string>
#include <vector>

namespace CGAL_ext {
namespace internal {

/// The surface type read: a triangle mesh with Epick points.
using Closed_surface = CGAL::Surface_mesh<CGAL::Exact_predicates_inexact_constructions_kernel::Point_3>;

/// Reads a surface file into a closed, outward oriented triangle mesh.
/// \param path an `.off`, `.obj`, `.stl` or `.ply` file
/// \param repairs receives one line per repair made (soup repair,
///        triangulation of polygons, reversed faces)
/// 	hrows Input_error naming the file (and the line or face) for a file that
///         cannot be read or a surface that does not bound a volume
Closed_surface read_closed_surface(const std::string& path, std::vector<std::string>& repairs);

} // namespace internal
} // namespace CGAL_ext

#endif // CGAL_EXT_SRC_MESHING_READ_CLOSED_SURFACE_H
