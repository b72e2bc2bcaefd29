// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#include "cli_common.h"
#include "commands.h"
#include "json_output.h"

#include <CGAL_ext/IO/read_tet_mesh.h>
#include <CGAL_ext/Tet_mesh_statistics_3.h>

#include <cstdio>

namespace CGAL_ext::cli {

namespace {

// The figures of info as one JSON object, on one line.
void print_info_json(const std::string& mesh_path, const IO::Medit_mesh& mesh, const Tet_mesh_build_report& r,
                     const Tet_mesh_statistics_3& s) {
  Json examples = Json::array();
  for (std::size_t t : r.reoriented_examples) examples.push_back(t + 1);
  print_json_line({{"mesh", mesh_path},
                   {"vertices", mesh.vertices.size()},
                   {"unused_vertices", r.unused_vertices},
                   {"tetrahedra", s.cells},
                   {"boundary_facets", s.boundary_facets},
                   {"components", s.components},
                   {"non_manifold_boundary_edges", r.non_manifold_boundary_edges},
                   {"bounding_box",
                    {{"min", {s.bbox.xmin(), s.bbox.ymin(), s.bbox.zmin()}},
                     {"max", {s.bbox.xmax(), s.bbox.ymax(), s.bbox.zmax()}}}},
                   {"volume", double(s.volume)},
                   {"edges", s.edges},
                   {"mean_edge_length", double(s.mean_edge_length)},
                   {"dihedral_angles_deg", {{"min", s.min_dihedral_angle}, {"max", s.max_dihedral_angle}}},
                   {"reoriented_tets", r.reoriented_tets},
                   {"reoriented_examples", examples}});
}

void print_info_text(const std::string& mesh_path, const IO::Medit_mesh& mesh, const Tet_mesh_build_report& r,
                     const Tet_mesh_statistics_3& s) {
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
}

} // namespace

int run_info(const Info_request& request) {
  Stage_timer timer;
  Tet_mesh_triangulation_3<> tr;
  IO::Medit_mesh mesh;
  const Tet_mesh_build_report r = IO::read_tet_mesh(request.mesh, tr, &mesh);
  timer.stage("read and build");
  const Tet_mesh_statistics_3 s = compute_tet_mesh_statistics(tr, Is_tet_mesh_domain_cell());
  timer.stage("statistics");
  if (request.json) print_info_json(request.mesh, mesh, r, s);
  else print_info_text(request.mesh, mesh, r, s);
  timer.summary();
  return 0;
}

} // namespace CGAL_ext::cli
