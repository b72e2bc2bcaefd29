// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Frame-field generation at growing sizes: a surface (or a built-in shape)
// meshed by Mesh_3 at decreasing sizes, then the whole generation with an
// anisotropic, varying metric; wall time per stage and the process's peak
// memory (resident set high-water mark, so run the sizes in increasing order).
// Then the field's integer-grid map (generate --hexes) with hexes of the
// Mesh_3 size where the metric is the identity, timed apart and set against
// the field's time.
//
//   benchmark_frame_field INPUT SIZE [SIZE ...] [linear_tolerance=X] [energy_tolerance=X]
//                         [aggregate_size=N] [trace]
//
// INPUT: a closed surface (.off .obj .stl .ply) or builtin:NAME.
// There is no reference implementation to compare against; the figures are
// time per tetrahedron, which should stay flat for linear growth.
#include <CGAL_ext/Frame_field_3.h>
#include <CGAL_ext/Frame_field_repair_3.h>
#include <CGAL_ext/Frame_field_singularities_3.h>
#include <CGAL_ext/Integer_grid_map_3.h>
#include <CGAL_ext/Metric_field_3.h>
#include <CGAL_ext/make_integer_grid_map_input.h>
#include <CGAL_ext/build_triangulation_from_tets.h>
#include <CGAL_ext/tetrahedralize.h>

#include "run_reporting_errors.h"

#include <sys/resource.h>
#include <tbb/info.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

using Tr = CGAL_ext::Tet_mesh_triangulation_3<>;
using Field = CGAL_ext::Metric_field_3<Tr>;

namespace {
double peak_gb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_maxrss) / (1024.0 * 1024.0); // ru_maxrss is in KiB on Linux
}
double since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}
} // namespace

static int run(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: benchmark_frame_field INPUT SIZE [SIZE ...] [linear_tolerance=T] [energy_tolerance=T]\n"
                         "       [aggregate_size=N] [repair_rounds=N] [repair_restarts=N] [repair_lbfgs_memory=N] [trace]\n"
                         "       (INPUT: surface file or builtin:NAME)\n");
    return 2;
  }
  const std::string input = argv[1];
  CGAL_ext::Frame_field_options options;
  CGAL_ext::Singularity_repair_options repair_options; // as generate
  std::vector<double> sizes;
  for (int a = 2; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg.rfind("linear_tolerance=", 0) == 0) options.linear_tolerance = std::atof(arg.c_str() + 17);
    else if (arg.rfind("energy_tolerance=", 0) == 0) options.energy_tolerance = std::atof(arg.c_str() + 17);
    else if (arg.rfind("aggregate_size=", 0) == 0) options.aggregate_size = std::atoi(arg.c_str() + 15);
    else if (arg.rfind("repair_rounds=", 0) == 0) // as generate's --repair-rounds
      repair_options.max_further_rounds = repair_options.max_released_rounds = std::atoi(arg.c_str() + 14);
    else if (arg.rfind("repair_restarts=", 0) == 0) // as generate's --repair-restarts
      repair_options.restarts = {0, std::atoi(arg.c_str() + 16)};
    else if (arg.rfind("repair_lbfgs_memory=", 0) == 0)
      repair_options.lbfgs_memory = std::atoi(arg.c_str() + 20);
    else if (arg == "trace")
      options.iteration_progress = [](const std::string& stage, int it, double value) {
        if (it % 10 == 0) std::printf("%8s %s %d: %.8g\n", "", stage.c_str(), it, value);
      };
    else sizes.push_back(std::atof(arg.c_str()));
  }
  std::printf("Frame-field generation on %s, %d threads; metric g = diag(1, 4, 1) (1 + |x|^2 / d^2)^2 with d the\n"
              "bounding-box diagonal (anisotropic, varying: non-trivial transports). Seconds per stage.\n\n",
              input.c_str(), tbb::info::default_concurrency());
  std::printf("%8s %9s %8s %8s %8s %8s %8s %8s %8s %8s %8s %8s %9s %8s %8s %8s\n", "size", "tets", "Mesh_3", "build",
              "setup", "transp", "linear", "project", "refine", "repair", "singul", "total*", "us/tet*", "map", "map/tot",
              "peak GB");
  std::printf("linear_tolerance %g, energy_tolerance %g, aggregate_size %d; repair: %d restarts in the second round, "
              "at most %d further rounds and %d released ones, L-BFGS memory %d\n",
              options.linear_tolerance, options.energy_tolerance, options.aggregate_size,
              repair_options.restarts.size() > 1 ? repair_options.restarts[1] : 0, repair_options.max_further_rounds,
              repair_options.max_released_rounds, repair_options.lbfgs_memory);
  for (const double size : sizes) {
    CGAL_ext::Tetrahedralize_options mo;
    mo.size = size;
    if (!(mo.size > 0)) {
      std::fprintf(stderr, "bad size %g\n", size);
      return 2;
    }
    auto t = std::chrono::steady_clock::now();
    const CGAL_ext::IO::Medit_mesh mesh = input.rfind("builtin:", 0) == 0
                                              ? CGAL_ext::tetrahedralize_builtin(input.substr(8), mo)
                                              : CGAL_ext::tetrahedralize_surface(input, mo);
    const double t_mesh = since(t);
    const auto start = std::chrono::steady_clock::now();
    t = start;
    Tr tr;
    CGAL_ext::build_triangulation_from_tets(mesh.vertices, mesh.tetrahedra, mesh.tetrahedron_references, tr);
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (const auto& p : mesh.vertices)
      for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
    const double d2 = (hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]);
    const Field field(tr, [&](const Tr::Point& p) {
      const double s = 1 + (p.x() * p.x() + p.y() * p.y() + p.z() * p.z()) / d2;
      return Eigen::Matrix3d(Eigen::Vector3d(s * s, 4 * s * s, s * s).asDiagonal());
    });
    field.precompute();
    const double t_build = since(t);
    CGAL_ext::Frame_field_3<Field> ff(field);
    const CGAL_ext::Frame_field_statistics& st = ff.compute(options);
    const CGAL_ext::Singularity_repair_report repair = CGAL_ext::repair_singularities(ff, repair_options);
    t = std::chrono::steady_clock::now();
    const auto sing = CGAL_ext::singular_edges(ff);
    const double t_sing = since(t);
    const double total = since(start);
    t = std::chrono::steady_clock::now();
    std::vector<Eigen::Vector3d> positions;
    for (const auto& p : mesh.vertices) positions.push_back({p[0], p[1], p[2]});
    const CGAL_ext::Frame_field_matchings_3<CGAL_ext::Frame_field_3<Field>> matchings(ff);
    // Hexes of the Mesh_3 size where the metric is the identity (y edges half as long).
    const CGAL_ext::Integer_grid_map map =
        CGAL_ext::compute_integer_grid_map(CGAL_ext::make_integer_grid_map_input(ff, matchings, positions, mo.size));
    const double t_map = since(t);
    std::printf("%8.4g %9zu %8.2f %8.2f %8.2f %8.2f %8.2f %8.2f %8.2f %8.2f %8.2f %8.2f %9.2f %8.2f %8.2f %8.2f\n",
                mo.size, ff.size(), t_mesh, t_build, st.seconds_setup, st.seconds_transports, st.seconds_linear,
                st.seconds_projection, st.seconds_refinement, repair.seconds, t_sing, total,
                1e6 * total / double(ff.size()), t_map, t_map / total, peak_gb());
    const CGAL_ext::Integer_grid_map_report& mr = map.report;
    std::printf("%8s map: setup %.2f s, solve %.2f s (%zu free variables, %zu integer, %zu solves), untangling %.2f s "
                "(%zu tetrahedra); inverted and flat tetrahedra %zu and %zu, rounded %zu and %zu; parameter volume "
                "%.0f of %.0f due\n",
                "", mr.seconds_setup, mr.seconds_solve, mr.solver.free_variables, mr.solver.free_integer_variables,
                mr.solver.solves, mr.seconds_untangle, mr.untangle_tets, mr.inverted_tets, mr.flat_tets,
                mr.inverted_tets_rounded, mr.flat_tets_rounded, mr.parameter_volume, mr.due_volume);
    std::printf("%8s CG %d (residual %.1e; coarse: %d on %zu aggregates), L-BFGS %d, energy %.4g -> %.4g, %zu singular edges (repair: %zu -> %zu "
                "non-meshable, %zu rounds, %zu of %zu regions kept, %zu L-BFGS iterations of %.0f tetrahedra on average), boundary error mean %.3g max %.3g deg\n",
                "", st.linear_iterations, st.linear_residual, st.coarse_iterations, st.coarse_unknowns / 9,
                st.refinement_iterations, st.projected_energy,
                st.smoothness_energy, sing.size(), repair.non_meshable_before, repair.non_meshable_after,
                repair.rounds, repair.regions_kept, repair.regions_tried, repair.lbfgs_iterations,
                double(repair.lbfgs_tet_iterations) / double(std::max<std::size_t>(repair.lbfgs_iterations, 1)),
                st.boundary_error_mean_deg, st.boundary_error_max_deg);
    std::fflush(stdout);
  }
  std::printf("\n* total: from the mesh to the singular edges (triangulation, metric, frame field, repair of\n"
              "  non-meshable edges, singular edges), without Mesh_3, without the map and without writing files.\n"
              "  map: the integer-grid map (matchings, cut, solve, rounding, untangling); map/tot: its time over total.\n");
  return 0;
}

int main(int argc, char** argv) {
  return benchmark_support::run_reporting_errors("benchmark_frame_field", [&] { return run(argc, argv); });
}
