// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#include "cli_common.h"
#include "commands.h"

#include <CGAL_ext/IO/read_tet_mesh.h>
#include <CGAL_ext/Tet_mesh_statistics_3.h>

#include <cstdio>
#include <iostream>

namespace CGAL_ext::cli {

namespace {
const char* info_help =
    "Usage: metric-frames info MESH\n\n"
    "Reads a tetrahedral Medit .mesh file and prints its counts (vertices,\n"
    "tetrahedra, boundary facets, connected components), bounding box, total\n"
    "volume, smallest and largest dihedral angle, and how many tetrahedra were\n"
    "given with negative orientation (they are re-oriented in memory; the file\n"
    "is not changed).\n\n"
    "Options:\n  -h, --help   this help\n";
}

int command_info(const std::vector<std::string>& args) {
  Arguments a(args, "info", info_help);
  if (a.help_requested()) return 0;
  const std::string mesh_path = a.positional("MESH");
  a.finish();

  Stage_timer timer;
  Tet_mesh_triangulation_3<> tr;
  IO::Medit_mesh mesh;
  const Tet_mesh_build_report r = IO::read_tet_mesh(mesh_path, tr, &mesh);
  timer.stage("read and build");
  const Tet_mesh_statistics_3 s = compute_tet_mesh_statistics(tr, Is_tet_mesh_domain_cell());
  timer.stage("statistics");

  std::printf("mesh                 %s\n", mesh_path.c_str());
  std::printf("vertices             %zu", mesh.vertices.size());
  if (r.unused_vertices) std::printf(" (%zu not used by any tetrahedron)", r.unused_vertices);
  std::printf("\ntetrahedra           %zu\n", s.cells);
  std::printf("boundary facets      %zu\n", s.boundary_facets);
  std::printf("components           %zu\n", s.components);
  if (r.non_manifold_boundary_edges)
    std::printf("non-manifold edges   %zu (boundary edges shared by more than two boundary facets)\n",
                r.non_manifold_boundary_edges);
  std::printf("bounding box         [%.17g, %.17g] x [%.17g, %.17g] x [%.17g, %.17g]\n", s.bbox.xmin(), s.bbox.xmax(),
              s.bbox.ymin(), s.bbox.ymax(), s.bbox.zmin(), s.bbox.zmax());
  std::printf("volume               %.12Lg\n", s.volume);
  std::printf("edges                %zu, mean length %.6Lg\n", s.edges, s.mean_edge_length);
  std::printf("dihedral angles      min %.6g deg, max %.6g deg\n", s.min_dihedral_angle, s.max_dihedral_angle);
  std::printf("re-oriented tets     %zu", r.reoriented_tets);
  if (r.reoriented_tets) {
    std::printf(" (e.g. tetrahedron");
    for (std::size_t t : r.reoriented_examples) std::printf(" %zu", t + 1);
    std::printf(")");
  }
  std::printf("\n");
  timer.summary();
  return 0;
}

} // namespace CGAL_ext::cli
