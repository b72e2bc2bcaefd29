// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The integer-grid map step of the generate pipeline (Frame_field_pipeline.h):
// the map's plain arrays from the pipeline's field, and the map.
#include <CGAL_ext/Frame_field_pipeline.h>
#include <CGAL_ext/make_integer_grid_map_input.h>

#include <CGAL/Real_timer.h>

#include <cstdio>
#include <string>

namespace CGAL_ext {

Integer_grid_map_input pipeline_integer_grid_map_input(const Pipeline_tet_mesh& mesh, const Pipeline_frame_field& frames) {
  const auto& vertices = mesh.mesh.vertices;
  std::vector<Eigen::Vector3d> positions(vertices.size());
  for (std::size_t v = 0; v < vertices.size(); ++v) {
    const bool moved = v < frames.positions.size() && frames.positions[v].allFinite();
    positions[v] = moved ? frames.positions[v] : Eigen::Vector3d(vertices[v][0], vertices[v][1], vertices[v][2]);
  }
  return make_integer_grid_map_input(*frames.frames, *frames.matchings, positions);
}

Pipeline_integer_grid_map compute_pipeline_integer_grid_map(const Pipeline_tet_mesh& mesh,
                                                            const Pipeline_frame_field& frames,
                                                            const Integer_grid_map_options& options,
                                                            const Pipeline_stage_callback& stage) {
  CGAL::Real_timer timer;
  timer.start();
  Pipeline_integer_grid_map out;
  out.input = pipeline_integer_grid_map_input(mesh, frames);
  out.map = compute_integer_grid_map(out.input, options);
  if (stage) {
    const Integer_grid_map_report& r = out.map.report;
    char buf[512];
    std::snprintf(buf, sizeof buf,
                  "%zu cut faces, %zu singular edges on grid lines (%zu not), %zu integer variables, %zu solves; "
                  "inverted and flat tetrahedra %zu and %zu after rounding, %zu and %zu after untangling (%d "
                  "iterations); fit error %.3g (%.3g before rounding)",
                  r.cut_faces, r.singular_edges_on_grid_lines, r.singular_edges_unconstrained,
                  r.solver.free_integer_variables, r.solver.solves, r.inverted_tets_rounded, r.flat_tets_rounded,
                  r.inverted_tets, r.flat_tets, r.untangle_iterations, r.fit_error, r.fit_error_relaxed);
    stage("integer-grid map", timer.time(), buf);
  }
  return out;
}

} // namespace CGAL_ext
