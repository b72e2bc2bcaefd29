// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// metric-frames: the command-line tool of CGAL Metric Frames. This unit is
// its command line: the CLI11 parser of every subcommand (options, checks,
// help texts), the dispatch to the run functions of commands.h, and the exit
// codes: 1 for bad input or a failure, 2 for bad usage. CLI11 is header-only
// and costs seconds per unit: it is included here only.
#include "cli_common.h"
#include "commands.h"

#include <CGAL_ext/Input_error.h>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <functional>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace CGAL_ext::cli {
namespace {

// CLI11's help with the usage line first, then the description, the
// arguments, the subcommands and the details (the footer); descriptions
// wrapped to 80 columns.
class Help_formatter : public CLI::Formatter {
public:
  static constexpr std::size_t width = 80, column = 26;
  Help_formatter() { column_width(column); }
  std::string make_option_desc(const CLI::Option* opt) const override { return wrap(CLI::Formatter::make_option_desc(opt)); }
  std::string make_option_opts(const CLI::Option* opt) const override {
    // A positional's name says what it is: no type, only whether it is required.
    if (opt->get_positional()) return opt->get_required() ? " (required)" : "";
    return CLI::Formatter::make_option_opts(opt);
  }
  std::string make_subcommand(const CLI::App* sub) const override {
    std::stringstream out;
    CLI::detail::format_help(out, sub->get_name(), wrap(sub->get_description()), column);
    return out.str();
  }
  std::string make_help(const CLI::App* app, std::string name, CLI::AppFormatMode mode) const override {
    if (mode == CLI::AppFormatMode::Sub) return make_expanded(app);
    std::stringstream out;
    out << make_usage(app, name) << "\n"
        << make_description(app) << make_positionals(app) << make_groups(app, mode) << make_subcommands(app, mode);
    const std::string footer = make_footer(app);
    if (!footer.empty()) out << "\n" << footer;
    return out.str();
  }

private:
  // `text` with its words on lines of at most width - column characters.
  static std::string wrap(const std::string& text) {
    std::istringstream words(text);
    std::string out, line, word;
    while (words >> word) {
      if (!line.empty() && line.size() + 1 + word.size() > width - column) {
        out += line + "\n";
        line.clear();
      }
      line += (line.empty() ? "" : " ") + word;
    }
    return out + line;
  }
};

// The help of `app`, named `name` on its usage line.
std::string help_text(const CLI::App& app, const std::string& name) {
  return app.get_formatter()->make_help(&app, name, CLI::AppFormatMode::Normal);
}

// A check that the value is a number (all of it) for which `accept` holds;
// the error says "'VALUE' is not " followed by `what`; `name` names the
// check in the help.
CLI::Validator number_check(std::function<bool(double)> accept, const std::string& what, const std::string& name) {
  return CLI::Validator(
      [accept, what](std::string& s) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(s.c_str(), &end);
        return s.empty() || *end != '\0' || !accept(v) ? Input_error::quote(s) + " is not " + what : std::string();
      },
      name);
}

// A positive finite number: CLI::PositiveNumber lets NaN and infinity through.
const CLI::Validator positive_finite =
    number_check([](double v) { return v > 0 && std::isfinite(v); }, "a positive finite number", "POSITIVE");

// A finite number >= 0.
const CLI::Validator non_negative_finite =
    number_check([](double v) { return v >= 0 && std::isfinite(v); }, "a finite number >= 0", "NON-NEGATIVE");

// A whole number in [lo, hi], written in decimal (4, 4.0 and 1e1 alike);
// the value is rewritten in plain digits, so that CLI11's conversion (base 0)
// does not read 010 as octal.
CLI::Validator whole_number(double lo, double hi) {
  const std::string what = "a whole number from " + std::to_string(long(lo)) + " to " + std::to_string(long(hi));
  return CLI::Validator(
      [lo, hi, what](std::string& s) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(s.c_str(), &end);
        if (s.empty() || *end != '\0' || !(v >= lo && v <= hi) || v != std::floor(v))
          return Input_error::quote(s) + " is not " + what;
        s = std::to_string(static_cast<long long>(v));
        return std::string();
      },
      "INT in [" + std::to_string(long(lo)) + " - " + std::to_string(long(hi)) + "]"); // as CLI::Range shows it
}

// The `--threads N` option of the subcommands that run in parallel.
void add_threads_option(CLI::App& app, std::size_t& threads) {
  app.add_option("--threads", threads, "worker threads (default: all cores); the output does not depend on N")
      ->type_name("N")
      ->transform(whole_number(1, 1024));
}

// The output option -o (or --output): CLI11 would keep the '=' of -o=PATH.
CLI::Option* add_output_option(CLI::App& app, std::string& path, const std::string& type, const std::string& help) {
  return app.add_option("-o,--output", path, help)
      ->type_name(type)
      ->required()
      ->check(CLI::Validator(
          [](std::string& s) -> std::string {
            if (s.empty()) return "the output path is empty";
            return s[0] == '=' ? Input_error::quote(s) + ": write -o PATH or --output=PATH" : "";
          },
          ""));
}

// The positional MESH of info, walk and transport.
void add_mesh_argument(CLI::App& app, std::string& mesh) {
  app.add_option("MESH", mesh, "a tetrahedral mesh: Medit .mesh, Gmsh .msh or legacy VTK .vtk")->required();
}

// info, its options bound to `r`.
CLI::App* add_info(CLI::App& app, Info_request& r) {
  CLI::App* sub = app.add_subcommand("info", "print counts, bounding box, volume and dihedral angles of a tet mesh");
  add_mesh_argument(*sub, r.mesh);
  sub->add_flag("--json", r.json,
                "print one JSON object instead: the same figures, numbers that read back exactly, "
                "tetrahedra numbered from 1");
  sub->footer("Reads MESH and prints its counts (vertices, tetrahedra, boundary facets,\n"
              "connected components), bounding box, total volume, smallest and largest\n"
              "dihedral angle, and how many tetrahedra were given with negative\n"
              "orientation (they are re-oriented in memory; the file is not changed).");
  return sub;
}

// walk, its options bound to `r`.
CLI::App* add_walk(CLI::App& app, Walk_request& r) {
  CLI::App* sub = app.add_subcommand("walk", "list every vertex, edge, facet and tet that segments meet, as JSON lines");
  add_mesh_argument(*sub, r.mesh);
  sub->add_option("--segments", r.segments, "the segments, one per line: qx qy qz px py pz (- for standard input)")
      ->type_name("FILE")
      ->required();
  sub->add_flag("--fast", r.fast, "only the pieces of positive length");
  sub->footer("For each segment q -> p of FILE (blank lines and lines starting with # are\n"
              "skipped), prints one JSON object per line on stdout, in order:\n\n"
              "  {\"segment\":i,\"pieces\":[{\"dim\":d,\"vertices\":[...],\"t\":[t_in,t_out]},...]}\n\n"
              "i counts the segments from 0. The pieces are every vertex (dim 0), edge (1),\n"
              "facet (2) and tetrahedron (3) of the mesh whose relative interior meets the\n"
              "closed segment x(t) = q + t (p - q), t in [0, 1], in order along it, and the\n"
              "parts outside the mesh (dim -1, \"vertices\": []). \"vertices\" are the sorted\n"
              "0-based vertex indices of the mesh file. A crossing of a facet, an edge or a\n"
              "vertex has t_in = t_out; the pieces tile [0, 1]. Which simplex is met is\n"
              "decided with exact predicates; t is computed in double.");
  return sub;
}

// transport, its options bound to `r`.
CLI::App* add_transport(CLI::App& app, Transport_request& r) {
  CLI::App* sub = app.add_subcommand("transport", "transport T(a->b) of a metric between point pairs, as JSON lines");
  add_mesh_argument(*sub, r.mesh);
  sub->add_option("--metric", r.metric, "the metric: one tensor per vertex of MESH (.sol, type 3 tensors or type 1 sizes)")
      ->type_name("SOL")
      ->required();
  sub->add_option("--pairs", r.pairs, "the pairs, one per line: ax ay az bx by bz (- for standard input)")
      ->type_name("FILE")
      ->required();
  sub->add_option("--tol", r.tolerance, "tolerance in radians per pair")
      ->type_name("T")
      ->check(positive_finite)
      ->capture_default_str();
  sub->add_option("--scheme", r.scheme,
                  "magnus (4th order, adaptive) or trapezoid (the thesis scheme, with recursive subdivision)")
      ->type_name("S")
      ->check(CLI::IsMember({"magnus", "trapezoid"}))
      ->capture_default_str();
  add_threads_option(*sub, r.threads);
  sub->footer("For each pair a -> b of FILE (blank lines and lines starting with # are\n"
              "skipped), computes the transport T(a->b) of the metric along the straight\n"
              "segment, and prints one JSON object per line, in order:\n\n"
              "  {\"pair\":i,\"R\":[9 numbers, row-major],\"angle\":radians,\"evaluations\":n}\n"
              "  {\"pair\":i,\"error\":\"the segment leaves the domain at t = 0.42 ...\"}\n\n"
              "A rotation field parallel along the segment satisfies R(b) = T(a->b) R(a).\n"
              "R is within about T radians of the exact transport of the piecewise-linear\n"
              "metric field, or its line ends with \"converged\":false and its error estimate\n"
              "(a metric that changes by orders of magnitude inside a cell); a segment\n"
              "with a part outside the mesh gets an error line.");
  return sub;
}

// metric, its options bound to `r`.
CLI::App* add_metric(CLI::App& app, Metric_request& r) {
  CLI::App* sub = app.add_subcommand("metric", "write a metric .sol file from formulas in x, y, z (constant formulas for a constant tensor)");
  sub->add_option("MESH", r.mesh, "a tet mesh (Medit .mesh, Gmsh .msh, VTK .vtk): the metric is evaluated at its vertices")->required();
  CLI::Option* expr =
      sub->add_option("--expr", r.expr,
                      "6 comma-separated expressions of x, y, z: m11, m21, m22, m31, m32, m33, e.g. "
                      "'1, 0, 16, 0, 0, 4' (constant diag(1, 16, 4)) or '1 + x^2, 0, 1, 0, 0, exp(z)'")
          ->type_name("EXPRS");
  sub->add_option("--size", r.size,
                                      "an isotropic size h(x, y, z) > 0, meaning g = I / h^2, e.g. "
                                      "'0.05 + 0.1 * sqrt(x^2 + y^2)'")
                          ->type_name("EXPR")
                          ->excludes(expr);
  add_output_option(*sub, r.out, "OUT.sol", "the output file (written to a temporary file, then renamed)");
  sub->add_flag("--force", r.force, "replace OUT.sol if it exists (never the mesh itself)");
  sub->footer("Evaluates a metric given by formulas at the vertices of MESH and writes it\n"
              "as a Medit .sol file (SolAtVertices, one symmetric tensor per vertex, lower\n"
              "triangle by rows: m11 m21 m22 m31 m32 m33), as MMG reads it. An edge e has\n"
              "length sqrt(e^T g e) in the metric g. Give exactly one of --expr and --size.\n\n"
              "Expressions use muParser: + - * / ^, sin cos tan exp log sqrt abs min max\n"
              "and more, the constants pi and e. Every tensor must be finite, symmetric and\n"
              "positive definite: the first vertex where it is not is an error naming it.");
  return sub;
}

// The details of `generate --help` after the options.
const char* generate_details =
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
    "                      boundary, alignment_error_deg, hard_axes,\n"
    "                      hard_constraint_released\n"
    "  singularities.vtu   singular edges as lines: type, index, valence, meshable,\n"
    "                      turn and axis angles, curve; nodes as point data\n"
    "  report.json         counts, hex size, expected hexes, singular curves and\n"
    "                      nodes, non-meshable edges, energies, face angles,\n"
    "                      alignment, timings\n\n"
    "INPUT is a tet mesh (Medit .mesh, Gmsh .msh, legacy VTK .vtk), a closed\n"
    "surface (.off .obj .stl .ply) meshed with CGAL Mesh_3 at size --size, or\n"
    "builtin:NAME (ball, torus, box_with_hole, ...).\n\n"
    "Metric (default: the identity) and hex size: unit length in the metric is one\n"
    "hex edge, so g = I/h^2 asks for hexes of edge h, diag(1,4,1)/h^2 for h, h/2, h.\n"
    "Without --hex-size, a given metric is used as it is; with no metric at all, h\n"
    "is the --size of a surface or builtin input (default: bounding-box diagonal /\n"
    "20) or the mean edge length of a tet mesh.";

// generate, its options bound to `r`.
CLI::App* add_generate(CLI::App& app, Generate_request& r) {
  CLI::App& sub = *app.add_subcommand("generate", "frame field in a metric: frames.fra, mesh, VTU files, singular edges, report");
  sub.add_option("INPUT", r.input, "a tet mesh (.mesh .msh .vtk), a closed surface (.off .obj .stl .ply) or builtin:NAME")->required();
  add_output_option(sub, r.out_dir, "OUTDIR", "output directory (created if missing)");
  sub.add_flag("--force", r.force, "replace output files that exist (never the input)");
  CLI::Option* sol = sub.add_option("--metric", r.sol_path,
                                    "one tensor per vertex (Medit .sol, type 3 or type 1); needs a tet mesh INPUT "
                                    "with the same vertices")
                         ->type_name("SOL");
  CLI::Option* constant = sub.add_option("--metric-const", r.metric_const,
                                         "a constant tensor: 6 numbers m11 m21 m22 m31 m32 m33 (Medit order) or 3 "
                                         "numbers (the diagonal)")
                              ->type_name("M")
                              ->excludes(sol);
  sub.add_option("--metric-expr", r.metric_expr,
                 "6 formulas in x, y, z, comma-separated, as for metric-frames metric --expr")
      ->type_name("E")
      ->excludes(sol)
      ->excludes(constant);
  sub.add_option("--hex-size", r.hex_size, "scale the metric to g / h^2: hexes of edge h where g is the identity")
      ->type_name("h")
      ->check(positive_finite);
  sub.add_option("--size", r.size,
                 "Mesh_3 size for surface and builtin inputs: it bounds the tetrahedra's circumradii; edges come out "
                 "about 1.2-1.35 h (default: bounding-box diagonal / 20, or the smallest hex edge that the metric and --hex-size ask for if smaller)")
      ->type_name("h")
      ->check(positive_finite);
  sub.add_option("--max-memory", r.max_memory,
                 "refuse a --size (or the hex edge it defaults to) whose estimated mesh would need more (about 5 tets per size^3 of volume, 1.6 KB "
                 "each), and stop Mesh_3 where its mesh reaches that (default: this machine's memory; 0: no limit)")
      ->type_name("GB")
      ->check(non_negative_finite);
  sub.add_flag("--smooth-surface", r.smooth_surface,
               "do not protect the surface's sharp edges (creases above the feature angle) in Mesh_3: for organic "
               "models");
  sub.add_option("--boundary-weight", r.options.boundary_weight, "weight of the soft boundary term")
      ->type_name("W")
      ->check(positive_finite)
      ->capture_default_str();
  sub.add_flag("--soft-boundary", r.soft_boundary, "no hard boundary constraint after the projection");
  sub.add_option("--diffusion-steps", r.options.diffusion_steps,
                 "diffusion-projection steps before the refinement, on domains without sharp features (see "
                 "--diffusion-with-features): the field smoothed over --diffusion-length first; on smooth shapes "
                 "a lower energy, not always a better hex mesh (0: none)")
      ->type_name("N")
      ->transform(whole_number(0, 1000))
      ->capture_default_str();
  sub.add_option("--diffusion-length", r.options.diffusion_length,
                 "length of each diffusion step, in hex edges (the metric's unit length)")
      ->type_name("L")
      ->check(positive_finite)
      ->capture_default_str();
  sub.add_flag("--diffusion-with-features", r.options.diffusion_with_features,
               "run the diffusion steps on domains with sharp features too");
  sub.add_option("--feature-angle", r.options.feature_angle_deg,
                 "boundary edges whose faces' normals differ by more than A degrees (in the metric) are sharp "
                 "features: the frames follow them, and Mesh_3 keeps them sharp (180: no features)")
      ->type_name("A")
      ->check(number_check([](double v) { return v > 0 && v <= 180; }, "an angle in degrees in (0, 180]",
                           "ANGLE"))
      ->capture_default_str();
  CLI::Option* no_repair = sub.add_flag("--no-repair", r.no_repair,
               "keep the non-meshable singular edges and nodes the optimiser leaves (default: re-optimise the regions around "
               "them)");
  sub.add_option("--repair-restarts", r.repair_restarts,
                 "random restarts per region in the repair's second round (radius 3), after its two deterministic "
                 "starts: more can find more meshable minima, at more time (0: none)")
      ->type_name("N")
      ->transform(whole_number(0, 1e6))
      ->excludes(no_repair)
      ->capture_default_str();
  sub.add_option("--repair-rounds", r.repair_rounds,
                 "further repair rounds at most, after the three of radius 2, 3 and 4, while non-meshable edges or "
                 "nodes remain: radius 3 and 2 in turn, 24 random restarts per region each; they stop when two in a row "
                 "fix nothing; then as many again with the regions' hard boundary constraints released (0: none)")
      ->type_name("N")
      ->transform(whole_number(0, 1e6))
      ->excludes(no_repair)
      ->capture_default_str();
  sub.add_flag("--hexes", r.hexes,
               "also compute the integer-grid map of the field (map.hexex: HexEx's input; the parameters in "
               "frames.vtu; report.json's integer_grid_map)");
  sub.add_flag("--keep-vertices", r.keep_vertices,
               "write the mesh's vertices where they are (default: move the singular curves' interior vertices "
               "towards straight curves, which an integer-grid map meshes with fewer inverted hexes)");
  sub.add_option("--max-iterations", r.options.max_refinement_iterations, "L-BFGS iterations at most")
      ->type_name("N")
      ->transform(whole_number(0, 1e8))
      ->capture_default_str();
  sub.add_option("--tol", r.options.transport_tolerance, "face transport tolerance in radians")
      ->type_name("T")
      ->check(positive_finite)
      ->capture_default_str();
  add_threads_option(sub, r.threads);
  sub.footer(generate_details);
  return &sub;
}

} // namespace
} // namespace CGAL_ext::cli

int main(int argc, char** argv) {
  using namespace CGAL_ext::cli;
  CLI::App app("metric-driven 3D frame fields on tetrahedral meshes (CGAL Metric Frames)", "metric-frames");
  app.formatter(std::make_shared<Help_formatter>());
  app.set_version_flag("--version", std::string("metric-frames ") + CGAL_EXT_VERSION, "print the version and exit");
  app.require_subcommand(1);
  app.footer("Tet meshes are ASCII Medit .mesh files (as MMG, Gmsh and TetGen -g write\n"
             "them), Gmsh .msh files (MSH 2.2 or 4.1, ASCII or binary) or legacy VTK .vtk\n"
             "unstructured grids, told apart by their extension.\n"
             "metric-frames SUBCOMMAND --help, or metric-frames help SUBCOMMAND, gives a\n"
             "subcommand's arguments. Exit codes: 0 success, 1 bad input or failure, 2 bad usage.");
  Generate_request generate;
  Info_request info;
  Walk_request walk;
  Transport_request transport;
  Metric_request metric;
  const std::vector<std::pair<CLI::App*, std::function<int()>>> subcommands = {
      {add_generate(app, generate), [&] { return run_generate(generate); }},
      {add_info(app, info), [&] { return run_info(info); }},
      {add_walk(app, walk), [&] { return run_walk(walk); }},
      {add_transport(app, transport), [&] { return run_transport(transport); }},
      {add_metric(app, metric), [&] { return run_metric(metric); }}};
  std::vector<std::string> names;
  for (const auto& s : subcommands) names.push_back(s.first->get_name());
  std::string topic;
  CLI::App* help = app.add_subcommand("help", "print the help of SUBCOMMAND (the same as SUBCOMMAND --help), or this help");
  help->add_option("SUBCOMMAND", topic, "a subcommand")->check(CLI::IsMember(names));

  if (argc == 1) {
    std::cerr << help_text(app, "metric-frames");
    return 2;
  }
  const std::string first = argv[1];
  if (!first.empty() && first[0] != '-' && first != "help" && std::find(names.begin(), names.end(), first) == names.end()) {
    std::cerr << "metric-frames: unknown subcommand '" << first << "' (see metric-frames --help)\n";
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e); // --help, --version
    const std::vector<CLI::App*> selected = app.get_subcommands();
    const std::string command = "metric-frames" + (selected.empty() ? "" : " " + selected.front()->get_name());
    std::cerr << command << ": " << e.what() << " (see " << command << " --help)\n";
    return 2;
  }
  if (help->parsed()) {
    std::cout << (topic.empty() ? help_text(app, "metric-frames")
                                : help_text(*app.get_subcommand(topic), "metric-frames " + topic));
    return 0;
  }
  for (const auto& [sub, run] : subcommands) {
    if (!sub->parsed()) continue;
    const std::string command = "metric-frames " + sub->get_name();
    try {
      return run();
    } catch (const Usage_error& e) {
      std::cerr << command << ": " << e.what() << " (see " << command << " --help)\n";
      return 2;
    } catch (const std::exception& e) {
      std::cerr << command << ": error: " << e.what() << "\n";
      return 1;
    }
  }
  return 2; // unreachable: CLI11 requires one subcommand
}
