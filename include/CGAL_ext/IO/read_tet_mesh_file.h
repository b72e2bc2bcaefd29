// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_IO_READ_TET_MESH_FILE_H
#define CGAL_EXT_IO_READ_TET_MESH_FILE_H

/// \file read_tet_mesh_file.h
/// Reads a tetrahedral mesh file, Medit, Gmsh or legacy VTK by its extension.

#include <CGAL_ext/IO/Gmsh_mesh.h>
#include <CGAL_ext/IO/Medit_mesh.h>
#include <CGAL_ext/IO/Vtk_legacy_mesh.h>

#include <string>

namespace CGAL_ext {
namespace IO {

/// \ingroup PkgCGALExtIO
/// The extension of a path's file name, in lower case, with its dot.
/// \param path the file
/// \returns e.g. ".msh" for "dir/Mesh.MSH"; empty without an extension
inline std::string lower_case_extension(const std::string& path) {
  const std::size_t dot = path.find_last_of("./");
  if (dot == std::string::npos || path[dot] != '.') return {};
  std::string e = path.substr(dot);
  for (char& c : e) c = char(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
  return e;
}

/// \ingroup PkgCGALExtIO
/// Whether a path names a Gmsh mesh: its extension is `.msh` (in any case).
/// \param path the file
/// \returns true for `read_gmsh_mesh()`
inline bool is_gmsh_mesh_path(const std::string& path) { return lower_case_extension(path) == ".msh"; }

/// \ingroup PkgCGALExtIO
/// Reads a tetrahedral mesh file by its extension: `.msh` with
/// `read_gmsh_mesh()`, `.vtk` with `read_vtk_legacy_mesh()`, any other with
/// `read_medit_mesh()`.
/// \param path the file
/// \returns its vertices, tetrahedra, triangles and edges with their references
/// \throws Input_error as the reader does
inline Medit_mesh read_tet_mesh_file(const std::string& path) {
  const std::string e = lower_case_extension(path);
  return e == ".msh" ? read_gmsh_mesh(path) : e == ".vtk" ? read_vtk_legacy_mesh(path) : read_medit_mesh(path);
}

} // namespace IO
} // namespace CGAL_ext

#endif // CGAL_EXT_IO_READ_TET_MESH_FILE_H
