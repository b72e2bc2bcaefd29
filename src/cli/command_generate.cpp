// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// metric-frames generate: the whole pipeline, from a tet mesh (or a surface,
// or a built-in shape, meshed with Mesh_3) and a metric to the frame field,
// its singular edges and the files for ParaView and hex meshing. A thin layer
// over the library's Frame_field_pipeline.h: arguments, progress lines and
// the metric's sources (a .sol file, formulas).
#include "cli_common.h"
#include "commands.h"
#include "metric_expression.h"

#include <CGAL_ext/Frame_field_pipeline.h>
#include <CGAL_ext/Frame_field_pipeline_report.h>
#include <CGAL_ext/IO/Medit_sol.h>
#include <CGAL_ext/Metric_tensor.h>

#include <CGAL/Real_timer.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <sstream>

namespace CGAL_ext::cli {

namespace {

Eigen::Matrix3d parse_constant_metric(const std::string& text) {
  std::string t = text;
  std::replace(t.begin(), t.end(), ',', ' ');
  std::istringstream in(t);
  std::vector<double> v;
  std::string word;
  while (in >> word) {
    char* end = nullptr;
    const double x = std::strtod(word.c_str(), &end);
    if (end == word.c_str() || *end != '\0')
      throw Usage_error("--metric-const '" + text + "': '" + word + "' is not a number");
    v.push_back(x);
  }
  Eigen::Matrix3d g = Eigen::Matrix3d::Zero();
  if (v.size() == 3) g = Eigen::Vector3d(v[0], v[1], v[2]).asDiagonal();
  else if (v.size() == 6) g << v[0], v[1], v[3], v[1], v[2], v[4], v[3], v[4], v[5];
  else throw Usage_error("--metric-const '" + text + "': expected 6 numbers (m11 m21 m22 m31 m32 m33) or 3 (the diagonal), got " +
                         std::to_string(v.size()));
  const std::string problem = check_metric_tensor(g);
  if (!problem.empty()) throw Usage_error("--metric-const '" + text + "': " + problem);
  return g;
}

// What the command line implies, checked (usage errors) before any work.
struct Generate_plan {
  Frame_field_options options;
  Tetrahedralize_options mesh_options;
  std::optional<Eigen::Matrix3d> constant_metric;
  std::unique_ptr<Metric_expression> formula;
};

// What the parsed options imply, and the checks CLI11 cannot make.
Generate_plan plan_generate(const Generate_request& r) {
  const Pipeline_input_kind kind = pipeline_input_kind(r.input);
  if (kind == Pipeline_input_kind::unknown)
    throw Usage_error("INPUT '" + r.input + "': expected a tet mesh (.mesh .msh .vtk), a surface (.off .obj .stl .ply) or builtin:NAME");
  const bool is_mesh = kind == Pipeline_input_kind::tet_mesh;
  if ((r.size || r.smooth_surface || r.max_memory) && is_mesh)
    throw Usage_error("--size, --smooth-surface and --max-memory apply to surface and builtin inputs; a tet mesh input is used as it is");
  if (r.sol_path && !is_mesh)
    throw Usage_error("--metric SOL needs a tet mesh INPUT (.mesh .msh .vtk): a generated mesh has no vertices the .sol could match");
  Generate_plan plan;
  plan.options = r.options;
  plan.options.hard_boundary = !r.soft_boundary;
  if (r.size) plan.mesh_options.size = *r.size;
  plan.mesh_options.sharp_features = !r.smooth_surface;
  if (r.max_memory) plan.mesh_options.memory_limit = *r.max_memory > 0 ? *r.max_memory * 1e9 : -1; // 0: no limit
  plan.mesh_options.sharp_angle_deg = r.options.feature_angle_deg; // the mesh keeps the creases the frames follow
  plan.mesh_options.progress = [](std::size_t vertices, std::size_t expected, double seconds) {
    std::fprintf(stderr, "[progress] Mesh_3: %zu vertices of about %zu expected, %.1f s\n", vertices, expected,
                 seconds);
  };
  if (r.metric_expr)
    plan.formula = std::make_unique<Metric_expression>(*r.metric_expr, Metric_expression::Kind::tensor, "--metric-expr");
  if (r.metric_const) plan.constant_metric = parse_constant_metric(*r.metric_const);
  // Tetrahedra about the size of the smallest hex edge or smaller: a field,
  // and the integer-grid map on it, resolve nothing finer than a
  // tetrahedron. That edge is h / sqrt(largest eigenvalue) for a constant
  // metric, h for a formula (whose sizes vary: --size meshes finer), where
  // h is --hex-size, or 1 for a metric given without it (its unit length is
  // the hex edge): --metric-const '100 100 100' and --hex-size 0.1 mesh alike.
  if (r.hex_size || plan.constant_metric || plan.formula) {
    double cap = r.hex_size.value_or(1.0);
    if (plan.constant_metric) // valid: parse_constant_metric() checked it
      cap /= std::sqrt(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(*plan.constant_metric, Eigen::EigenvaluesOnly)
                           .eigenvalues()
                           .maxCoeff());
    plan.mesh_options.max_automatic_size = cap;
  }
  return plan;
}

// The metric of the request on `mesh`, not yet scaled.
Pipeline_metric_input metric_input(const Generate_request& r, const Generate_plan& plan, const Pipeline_tet_mesh& mesh) {
  Pipeline_metric_input metric;
  metric.hex_size = r.hex_size;
  if (r.sol_path) {
    metric.per_vertex = IO::read_medit_sol(*r.sol_path, mesh.mesh.vertices.size());
    metric.source = metric.name = *r.sol_path;
  } else if (plan.formula) {
    metric.per_vertex = evaluate_metric(*plan.formula, mesh.mesh.vertices, "--metric-expr");
    metric.source = "--metric-expr";
    metric.name = "expression " + *r.metric_expr;
  } else if (plan.constant_metric) {
    metric.constant = plan.constant_metric;
    metric.source = "--metric-const";
    metric.name = "constant " + *r.metric_const;
  }
  return metric;
}

} // namespace

int run_generate(const Generate_request& r) {
  Generate_plan plan = plan_generate(r);
  const auto threads = thread_limit(r.threads);
  // Nothing is written before every check passed; nothing the user gave is replaced.
  std::vector<std::string> inputs = {r.input};
  if (r.sol_path) inputs.push_back(*r.sol_path);
  check_pipeline_output_directory(r.out_dir, inputs, r.force); // before the computation, which can take long

  if (r.size && plan.mesh_options.max_automatic_size > 0 && *r.size > plan.mesh_options.max_automatic_size)
    std::fprintf(stderr,
                 "[note] --size %.6g is larger than the hex edge %.6g (the metric, and --hex-size): the tetrahedra "
                 "will be coarser than the hexahedra, and the field resolves nothing finer than a tetrahedron "
                 "(without --size, Mesh_3 meshes at the hex edge or finer)\n",
                 *r.size, plan.mesh_options.max_automatic_size);
  Stage_timer timer;
  Pipeline_report_context context;
  context.input = r.input;
  auto stage = [&](const std::string& name, double seconds, const std::string& detail) {
    std::fprintf(stderr, "[stage] %-22s %8.3f s  %s\n", name.c_str(), seconds, detail.c_str());
    context.stage_seconds.emplace_back(name, seconds);
  };
  const Pipeline_tet_mesh mesh = load_tet_mesh(r.input, plan.mesh_options, stage);
  print_build_notes(mesh.build, "mesh.mesh has them positive (two vertices swapped), as CubeCover and HexEx need");

  const Pipeline_metric field = make_pipeline_metric(mesh, metric_input(r, plan, mesh), stage);
  // Said before the long stages: parts thinner than a hex edge are a cause of
  // non-meshable singularities that the optimisation and the repair rarely remove.
  context.thickness = measure_pipeline_thickness(field, stage);
  if (context.thickness->fraction_below_hex_edge > 0.1) {
    const double t10 = context.thickness->thickness_at_10_percent;
    const std::string edge = field.scaled ? " (h = " + format_number(field.hex_size, 6) + ")" : std::string();
    const std::string advice =
        !(t10 > 0)     ? std::string("A smaller hex size would leave less")
        : field.scaled ? "With --hex-size " + format_number(field.hex_size * t10, 3) + ", at most 10% of it would be"
                     : "With hexahedra " + format_number(t10, 3) + " times as large (the metric times " +
                           format_number(1 / (t10 * t10), 3) + "), at most 10% of it would be";
    std::fprintf(stderr,
                 "[warning] %.0f%% of the boundary is less than one hex edge%s from the opposite side of the domain: "
                 "hexahedra of this size cannot fill those parts, and the singular curves there are rarely "
                 "meshable. %s.\n",
                 100 * context.thickness->fraction_below_hex_edge, edge.c_str(), advice.c_str());
  }

  plan.options.progress = stage;
  // Long iterations report at most once per second.
  CGAL::Real_timer since_report;
  since_report.start();
  plan.options.iteration_progress = [&](const std::string& name, int iteration, double measure) {
    if (since_report.time() < 1) return;
    since_report.reset();
    std::fprintf(stderr, "[progress] %s: iteration %d, %s %.4g\n", name.c_str(), iteration,
                 name == "refinement" ? "objective (energy + boundary terms)" : "relative residual", measure);
  };
  std::optional<Singularity_repair_options> repair_options;
  if (!r.no_repair) {
    repair_options.emplace();
    repair_options->restarts = {0, r.repair_restarts}; // the second round restarts, as by default
    repair_options->max_further_rounds = repair_options->max_released_rounds = r.repair_rounds;
    repair_options->progress = [](int round, int radius, std::size_t tried, std::size_t accepted, std::size_t left) {
      std::fprintf(stderr, "[progress] repair round %d (radius %d): %zu regions, %zu kept, %zu non-meshable edges and nodes left\n",
                   round, radius, tried, accepted, left);
    };
  }
  std::optional<Singular_curve_straightening_options> straightening;
  if (!r.keep_vertices) straightening = pipeline_straightening_options(mesh);
  const Pipeline_frame_field frames =
      generate_pipeline_frame_field(field, plan.options, repair_options, stage, straightening);

  std::optional<Pipeline_integer_grid_map> map;
  if (r.hexes) {
    map = compute_pipeline_integer_grid_map(mesh, frames, {}, stage);
    context.integer_grid_map = map->map.report;
  }

  CGAL::Real_timer write_timer;
  write_timer.start();
  write_pipeline_outputs(r.out_dir, mesh, frames, map ? &*map : nullptr);
  stage("write outputs", write_timer.time(), r.out_dir);
  write_timer.reset();
  const std::string report =
      write_pipeline_report(r.out_dir, pipeline_report_json(mesh, field, frames, context));
  stage("write report", write_timer.time(), report);
  std::fprintf(stderr, "%s  %-32s %s\n", pipeline_summary_text(mesh, field, frames, context).c_str(), "outputs",
               r.out_dir.c_str());
  timer.summary();
  return 0;
}

} // namespace CGAL_ext::cli
