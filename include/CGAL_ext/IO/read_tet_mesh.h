// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_IO_READ_TET_MESH_H
#define CGAL_EXT_IO_READ_TET_MESH_H

/// \file read_tet_mesh.h
/// Reads a tetrahedral mesh file (Medit, Gmsh or legacy VTK) into a `Tet_mesh_triangulation_3`.

#include <CGAL_ext/IO/read_tet_mesh_file.h>
#include <CGAL_ext/Tet_mesh_triangulation_3.h>
#include <CGAL_ext/build_triangulation_from_tets.h>

#include <string>

namespace CGAL_ext {
namespace IO {

/// \ingroup PkgCGALExtIO
/// Reads a tetrahedral mesh file and builds its triangulation.
///
/// Equivalent to `read_tet_mesh_file()` followed by
/// `build_triangulation_from_tets()`, with errors that name the file and the
/// line of the offending tetrahedron.
///
/// \tparam Geom_traits the kernel of the triangulation
/// \param path a Medit `.mesh`, Gmsh `.msh` or legacy VTK `.vtk` file (by its extension)
/// \param tr the output triangulation; vertex info is the 0-based file index,
///        cell info the 0-based tetrahedron index and reference
/// \param mesh if not null, receives the file content (e.g. to write it back
///        or to keep unused vertices)
/// \returns the build report (re-oriented tetrahedra, boundary facets...)
/// \throws Input_error for any defect of the file or of the mesh
template <class Geom_traits>
Tet_mesh_build_report read_tet_mesh(const std::string& path, Tet_mesh_triangulation_3<Geom_traits>& tr,
                                    Medit_mesh* mesh = nullptr) {
  Medit_mesh m = read_tet_mesh_file(path);
  Tet_soup_source src;
  src.file = path;
  src.tet_lines = m.tetrahedron_lines;
  src.vertex_lines = m.vertex_lines;
  Tet_mesh_build_report r = build_triangulation_from_tets(m.vertices, m.tetrahedra, m.tetrahedron_references, tr, src);
  if (mesh) *mesh = std::move(m);
  return r;
}

} // namespace IO
} // namespace CGAL_ext

#endif // CGAL_EXT_IO_READ_TET_MESH_H
