// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#include "cli_common.h"
#include "commands.h"

#include <CGAL_ext/IO/read_tet_mesh.h>
#include <CGAL_ext/Tet_mesh_statistics_3.h>

#include <cmath>
#include <cstdio>
#include <iostream>

namespace CGAL_ext::cli {

namespace {
const char* info_help =
    "Usage: metric-frames info MESH [--json]\n\n"
    "Reads a tetrahedral Medit .mesh file and prints its counts (vertices,\n"
    "tetrahedra, boundary facets, connected components), bounding box, total\n"
    "volume, smallest and largest dihedral angle, and how many tetrahedra were\n"
    "given with negative orientation (they are re-oriented in memory; the file\n"
    "is not changed).\n\n"
    "Options:\n"
    "  --json       print one JSON object instead (the same figures; coordinates\n"
    "               with 17 significant digits, tetrahedra numbered from 1)\n"
    "  -h, --help   this help\n";

// The figures of info as one JSON object, on one line.
void print_info_json(const std::string& mesh_path, const IO::Medit_mesh& mesh, const Tet_mesh_build_report& r,
                     const Tet_mesh_statistics_3& s) {
  const auto exact = [](double x) { return std::isfinite(x) ? format_number(x, 17) : std::string("null"); };
  std::string examples;
  for (std::size_t t : r.reoriented_examples) examples += (examples.empty() ? "" : ", ") + std::to_string(t + 1);
  std::printf("{\"mesh\": \"%s\", \"vertices\": %zu, \"unused_vertices\": %zu, \"tetrahedra\": %zu, "
              "\"boundary_facets\": %zu, \"components\": %zu, \"non_manifold_boundary_edges\": %zu, "
              "\"bounding_box\": {\"min\": [%s, %s, %s], \"max\": [%s, %s, %s]}, \"volume\": %s, \"edges\": %zu, "
              "\"mean_edge_length\": %s, \"dihedral_angles_deg\": {\"min\": %s, \"max\": %s}, "
              "\"reoriented_tets\": %zu, \"reoriented_examples\": [%s]}\n",
              json_escape(mesh_path).c_str(), mesh.vertices.size(), r.unused_vertices, s.cells, s.boundary_facets,
              s.components, r.non_manifold_boundary_edges, exact(s.bbox.xmin()).c_str(), exact(s.bbox.ymin()).c_str(),
              exact(s.bbox.zmin()).c_str(), exact(s.bbox.xmax()).c_str(), exact(s.bbox.ymax()).c_str(),
              exact(s.bbox.zmax()).c_str(), internal::json_number(double(s.volume)).c_str(), s.edges,
              internal::json_number(double(s.mean_edge_length)).c_str(),
              internal::json_number(s.min_dihedral_angle).c_str(), internal::json_number(s.max_dihedral_angle).c_str(),
              r.reoriented_tets, examples.c_str());
}
}

int command_info(const std::vector<std::string>& args) {
  Arguments a(args, "info", info_help);
  if (a.help_requested()) return 0;
  const bool json = a.flag("--json");
  const std::string mesh_path = a.positional("MESH");
  a.finish();

  Stage_timer timer;
  Tet_mesh_triangulation_3<> tr;
  IO::Medit_mesh mesh;
  const Tet_mesh_build_report r = IO::read_tet_mesh(mesh_path, tr, &mesh);
  timer.stage("read and build");
  const Tet_mesh_statistics_3 s = compute_tet_mesh_statistics(tr, Is_tet_mesh_domain_cell());
  timer.stage("statistics");
  if (json) {
    print_info_json(mesh_path, mesh, r, s);
    timer.summary();
    return 0;
  }

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
