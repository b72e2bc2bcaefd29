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
#include <CGAL_ext/IO/Medit_sol.h>
#include <CGAL_ext/Metric_tensor.h>

#include <CGAL/Real_timer.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <optional>
#include <sstream>

namespace CGAL_ext::cli {

namespace {
const char* generate_help =
    "Usage: metric-frames generate INPUT [--metric SOL | --metric-const \"M\" | --metric-expr \"E\"]\n"
    "                              [--hex-size h] [--size h] -o OUTDIR [--force] [options]\n\n"
    "Generates a smooth octahedral frame field, aligned with the boundary, in a\n"
    "Riemannian metric g (one frame per tetrahedron, F = A^-1 R with A = g^1/2),\n"
    "finds its singularities, and writes into OUTDIR the input of CubeCover's\n"
    "integer-grid map (integergrid mesh.mesh frames.fra frames.perm OUT.hexex):\n"
    "  frames.fra          per tet (in mesh.mesh's order) the 3 parameter gradients\n"
    "                      A R e_k (rows of F^-1), of length 1/h for hexes of edge h\n"
    "  frames.perm         the frames' matchings across the interior faces\n"
    "  mesh.mesh           the tet mesh used (Medit)\n"
    "  frames.vtu          for ParaView: tets with cell data hex_edge_1..3 (columns\n"
    "                      of F), parameter_gradient_1..3, metric, energy_density,\n"
    "                      boundary, alignment_error_deg\n"
    "  singularities.vtu   singular edges as lines: type, index, valence, meshable,\n"
    "                      turn and axis angles, curve; nodes as point data\n"
    "  report.json         counts, hex size, expected hexes, singular curves and\n"
    "                      nodes, non-meshable edges, energies, face angles,\n"
    "                      alignment, timings\n\n"
    "INPUT is a Medit .mesh tet mesh, a closed surface (.off .obj .stl .ply) meshed\n"
    "with CGAL Mesh_3 at size --size, or builtin:NAME (ball, torus, box_with_hole, ...).\n\n"
    "Metric (default: the identity) and hex size. Unit length in the metric is one\n"
    "hex edge: g = I/h^2 asks for hexes of edge h, diag(1,4,1)/h^2 for h, h/2, h.\n"
    "  --metric SOL          one tensor per vertex (Medit .sol, type 3 or type 1);\n"
    "                        needs a .mesh INPUT with the same vertices\n"
    "  --metric-const M      a constant tensor: 6 numbers m11 m21 m22 m31 m32 m33\n"
    "                        (Medit order) or 3 numbers (the diagonal)\n"
    "  --metric-expr E       6 formulas in x, y, z, comma-separated, as for\n"
    "                        metric-frames metric --expr\n"
    "  --hex-size h          scale the metric to g / h^2 (hexes of edge h where g\n"
    "                        is the identity). Without it, a given metric is used\n"
    "                        as it is; with no metric at all, h is the --size of a\n"
    "                        surface or builtin input (default: bounding-box\n"
    "                        diagonal / 20) or the mean edge length of a .mesh\n\n"
    "Options:\n"
    "  -o OUTDIR             output directory (created if missing)\n"
    "  --force               replace output files that exist (never the input)\n"
    "  --size h              Mesh_3 size for surface and builtin inputs: it bounds\n"
    "                        the tetrahedra's circumradii; edges come out about\n"
    "                        1.2-1.35 h (default: bounding-box diagonal / 20)\n"
    "  --max-memory GB       refuse a --size whose estimated mesh would need more\n"
    "                        (about 5 tets per size^3 of volume, 1.6 KB each),\n"
    "                        and stop Mesh_3 where its mesh reaches that (default:\n"
    "                        this machine's memory; 0: no limit)\n"
    "  --smooth-surface      do not protect the surface's sharp edges (creases\n"
    "                        above the feature angle) in Mesh_3: for organic models\n"
    "  --boundary-weight W   weight of the soft boundary term (default 100)\n"
    "  --soft-boundary       no hard boundary constraint after the projection\n"
    "  --feature-angle A     boundary edges whose faces' normals differ by more than\n"
    "                        A degrees (in the metric) are sharp features: the frames\n"
    "                        follow them, and Mesh_3 keeps them sharp (default 40;\n"
    "                        180: no features)\n"
    "  --no-repair           keep the non-meshable singular edges the optimiser\n"
    "                        leaves (default: re-optimise the regions around them)\n"
    "  --max-iterations N    L-BFGS iterations at most (default 1000)\n"
    "  --tol T               face transport tolerance in radians (default 1e-6)\n"
    "  --threads N           worker threads (default: all); outputs do not depend on N\n"
    "  -h, --help            this help\n";

Eigen::Matrix3d parse_constant_metric(Arguments& a, const std::string& text) {
  std::string t = text;
  std::replace(t.begin(), t.end(), ',', ' ');
  std::istringstream in(t);
  std::vector<double> v;
  std::string word;
  while (in >> word) {
    char* end = nullptr;
    const double x = std::strtod(word.c_str(), &end);
    if (end == word.c_str() || *end != '\0')
      a.fail("--metric-const '" + text + "': '" + word + "' is not a number");
    v.push_back(x);
  }
  Eigen::Matrix3d g = Eigen::Matrix3d::Zero();
  if (v.size() == 3) g = Eigen::Vector3d(v[0], v[1], v[2]).asDiagonal();
  else if (v.size() == 6) g << v[0], v[1], v[3], v[1], v[2], v[4], v[3], v[4], v[5];
  else a.fail("--metric-const '" + text + "': expected 6 numbers (m11 m21 m22 m31 m32 m33) or 3 (the diagonal), got " +
              std::to_string(v.size()));
  const std::string problem = check_metric_tensor(g);
  if (!problem.empty()) a.fail("--metric-const '" + text + "': " + problem);
  return g;
}

// The generate command line, parsed and checked (usage errors) before any work.
struct Generate_request {
  std::string input, out_dir;
  bool force = false, repair = true;
  std::optional<std::string> sol_path, metric_const, metric_expr;
  std::optional<Eigen::Matrix3d> constant_metric;
  std::unique_ptr<Metric_expression> formula;
  std::optional<double> hex_size;
  Tetrahedralize_options mesh_options;
  Frame_field_options options;
  std::unique_ptr<tbb::global_control> threads;
};

Generate_request parse_generate_request(Arguments& a) {
  Generate_request r;
  r.sol_path = a.option("--metric");
  r.metric_const = a.option("--metric-const");
  r.metric_expr = a.option("--metric-expr");
  const auto hex_size_option = a.option("--hex-size");
  r.out_dir = a.required_option("-o");
  r.force = a.flag("--force");
  const auto size = a.option("--size");
  if (size) r.mesh_options.size = parse_positive(a, "--size", *size);
  r.mesh_options.sharp_features = !a.flag("--smooth-surface");
  if (const auto m = a.option("--max-memory")) {
    // 0: no limit; otherwise GB (the default is this machine's memory)
    const double gb = *m == "0" ? 0 : parse_positive(a, "--max-memory", *m);
    r.mesh_options.memory_limit = gb > 0 ? gb * 1e9 : -1;
  }
  r.mesh_options.progress = [](std::size_t vertices, std::size_t expected, double seconds) {
    std::fprintf(stderr, "[progress] Mesh_3: %zu vertices of about %zu expected, %.1f s\n", vertices, expected,
                 seconds);
  };
  if (const auto w = a.option("--boundary-weight")) r.options.boundary_weight = parse_positive(a, "--boundary-weight", *w);
  r.options.hard_boundary = !a.flag("--soft-boundary");
  if (const auto f = a.option("--feature-angle")) {
    char* end = nullptr;
    const double v = std::strtod(f->c_str(), &end);
    if (end == f->c_str() || *end != '\0' || !(v > 0 && v <= 180))
      a.fail("--feature-angle '" + *f + "': expected an angle in degrees in (0, 180]");
    r.options.feature_angle_deg = v;
  }
  r.mesh_options.sharp_angle_deg = r.options.feature_angle_deg; // the mesh keeps the creases the frames follow
  r.repair = !a.flag("--no-repair");
  if (const auto n = a.option("--max-iterations")) {
    char* end = nullptr;
    const long v = std::strtol(n->c_str(), &end, 10);
    if (end == n->c_str() || *end != '\0' || v < 0 || v > 100000000)
      a.fail("--max-iterations '" + *n + "': expected a whole number >= 0");
    r.options.max_refinement_iterations = int(v);
  }
  if (const auto t = a.option("--tol")) r.options.transport_tolerance = parse_positive(a, "--tol", *t);
  if (hex_size_option) r.hex_size = parse_positive(a, "--hex-size", *hex_size_option);
  r.threads = thread_limit(a);
  r.input = a.positional("INPUT");
  a.finish();
  if (int(bool(r.sol_path)) + int(bool(r.metric_const)) + int(bool(r.metric_expr)) > 1)
    a.fail("give at most one of --metric, --metric-const and --metric-expr");
  const Pipeline_input_kind kind = pipeline_input_kind(r.input);
  if (kind == Pipeline_input_kind::unknown)
    a.fail("INPUT '" + r.input + "': expected a .mesh tet mesh, a surface (.off .obj .stl .ply) or builtin:NAME");
  const bool is_mesh = kind == Pipeline_input_kind::tet_mesh;
  if ((size || !r.mesh_options.sharp_features || r.mesh_options.memory_limit != 0) && is_mesh)
    a.fail("--size, --smooth-surface and --max-memory apply to surface and builtin inputs; a .mesh input is used as it is");
  if (r.sol_path && !is_mesh)
    a.fail("--metric SOL needs a .mesh INPUT: a generated mesh has no vertices the .sol could match");
  if (r.metric_expr) r.formula = std::make_unique<Metric_expression>(*r.metric_expr, Metric_expression::Kind::tensor, "--metric-expr");
  if (r.metric_const) r.constant_metric = parse_constant_metric(a, *r.metric_const);
  return r;
}

// The metric of the request on `mesh`, not yet scaled.
Pipeline_metric_input metric_input(const Generate_request& r, const Pipeline_tet_mesh& mesh) {
  Pipeline_metric_input metric;
  metric.hex_size = r.hex_size;
  if (r.sol_path) {
    metric.per_vertex = IO::read_medit_sol(*r.sol_path, mesh.mesh.vertices.size());
    metric.source = metric.name = *r.sol_path;
  } else if (r.formula) {
    metric.per_vertex = evaluate_metric(*r.formula, mesh.mesh.vertices, "--metric-expr");
    metric.source = "--metric-expr";
    metric.name = "expression " + *r.metric_expr;
  } else if (r.constant_metric) {
    metric.constant = r.constant_metric;
    metric.source = "--metric-const";
    metric.name = "constant " + *r.metric_const;
  }
  return metric;
}

} // namespace

int command_generate(const std::vector<std::string>& args) {
  Arguments a(args, "generate", generate_help);
  if (a.help_requested()) return 0;
  Generate_request r = parse_generate_request(a);
  // Nothing is written before every check passed; nothing the user gave is replaced.
  std::vector<std::string> inputs = {r.input};
  if (r.sol_path) inputs.push_back(*r.sol_path);
  check_pipeline_output_directory(r.out_dir, inputs, r.force); // before the computation, which can take long

  Stage_timer timer;
  Pipeline_report_context context;
  context.input = r.input;
  context.options = r.options;
  auto stage = [&](const std::string& name, double seconds, const std::string& detail) {
    std::fprintf(stderr, "[stage] %-22s %8.3f s  %s\n", name.c_str(), seconds, detail.c_str());
    context.stage_seconds[name] = seconds;
  };
  const Pipeline_tet_mesh mesh = load_tet_mesh(r.input, r.mesh_options, stage);
  if (mesh.build.reoriented_tets)
    std::fprintf(stderr,
                 "[note] %zu negatively oriented tetrahedra were re-oriented (first: tetrahedron %zu); mesh.mesh "
                 "has them positive, as CubeCover and HexEx need\n",
                 mesh.build.reoriented_tets, mesh.build.reoriented_examples.front() + 1);
  if (mesh.build.unused_vertices)
    std::fprintf(stderr, "[note] %zu vertices are used by no tetrahedron\n", mesh.build.unused_vertices);

  const Pipeline_metric field = make_pipeline_metric(mesh, metric_input(r, mesh), stage);

  r.options.progress = stage;
  // Long iterations report at most once per second.
  CGAL::Real_timer since_report;
  since_report.start();
  r.options.iteration_progress = [&](const std::string& name, int iteration, double measure) {
    if (since_report.time() < 1) return;
    since_report.reset();
    std::fprintf(stderr, "[progress] %s: iteration %d, %s %.4g\n", name.c_str(), iteration,
                 name == "refinement" ? "energy" : "relative residual", measure);
  };
  std::optional<Singularity_repair_options> repair_options;
  if (r.repair) {
    repair_options.emplace();
    repair_options->progress = [](int round, int radius, std::size_t tried, std::size_t accepted, std::size_t left) {
      std::fprintf(stderr, "[progress] repair round %d (radius %d): %zu regions, %zu kept, %zu non-meshable edges left\n",
                   round, radius, tried, accepted, left);
    };
  }
  const Pipeline_frame_field frames = generate_pipeline_frame_field(field, r.options, repair_options, stage);

  CGAL::Real_timer write_timer;
  write_timer.start();
  write_pipeline_outputs(r.out_dir, mesh, frames);
  stage("write outputs", write_timer.time(), r.out_dir);
  write_timer.reset();
  const std::string report = write_pipeline_report(r.out_dir, pipeline_report_json(mesh, field, frames, context));
  stage("write report", write_timer.time(), report);
  std::fprintf(stderr, "%s  %-32s %s\n", pipeline_summary_text(mesh, field, frames, context).c_str(), "outputs",
               r.out_dir.c_str());
  timer.summary();
  return 0;
}

} // namespace CGAL_ext::cli
