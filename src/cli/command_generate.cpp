// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// metric-frames generate: the whole pipeline, from a tet mesh (or a surface,
// or a built-in shape, meshed with Mesh_3) and a metric to the frame field,
// its singular edges and the files for ParaView and hex meshing.
#include "cli_common.h"
#include "commands.h"
#include "metric_expression.h"
#include "../IO/write_file_atomically.h"

#include <CGAL_ext/Frame_field_3.h>
#include <CGAL_ext/Frame_field_matchings_3.h>
#include <CGAL_ext/Frame_field_repair_3.h>
#include <CGAL_ext/Frame_field_singularities_3.h>
#include <CGAL_ext/IO/Fra_file.h>
#include <CGAL_ext/IO/Medit_mesh.h>
#include <CGAL_ext/IO/Medit_sol.h>
#include <CGAL_ext/IO/Perm_file.h>
#include <CGAL_ext/IO/Vtu_file.h>
#include <CGAL_ext/Metric_field_3.h>
#include <CGAL_ext/Metric_tensor.h>
#include <CGAL_ext/Tet_mesh_statistics_3.h>
#include <CGAL_ext/build_triangulation_from_tets.h>
#include <CGAL_ext/tetrahedralize.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
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

const char* const output_names[] = {"frames.fra", "frames.perm", "mesh.mesh", "frames.vtu", "singularities.vtu",
                                    "report.json"};

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

bool has_extension(const std::string& path, std::initializer_list<const char*> exts) {
  std::string e = std::filesystem::path(path).extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  for (const char* x : exts)
    if (e == x) return true;
  return false;
}

std::string number(double x) {
  char buf[32];
  if (!std::isfinite(x)) return "null";
  std::snprintf(buf, sizeof buf, "%.10g", x);
  return buf;
}

std::string point_json(const Eigen::Vector3d& p) {
  return "[" + number(p(0)) + ", " + number(p(1)) + ", " + number(p(2)) + "]";
}

using Tr = Tet_mesh_triangulation_3<>;
using Field = Metric_field_3<Tr>;
using Frames = Frame_field_3<Field>;
using Matchings = Frame_field_matchings_3<Frames>;

// The VTK cell type code of a singular edge in singularities.vtu.
int type_code(Singularity_type t) {
  switch (t) {
    case Singularity_type::plus_quarter: return 1;
    case Singularity_type::minus_quarter: return -1;
    case Singularity_type::half: return 2;
    case Singularity_type::third: return 3;
    default: return 4; // quarter_across
  }
}

// How the hex size was chosen: the value and the rule, for the report.
struct Hex_size {
  double h = 1;      // the metric is divided by h^2
  bool scaled = false;
  std::string rule;  // how h was chosen
};

// frames.fra, frames.perm, frames.vtu: per tet, the gradients, matchings and edges.
void write_frame_files(const std::filesystem::path& dir, const IO::Medit_mesh& mesh, const Frames& ff,
                       const Matchings& matchings) {
  const std::size_t nt = ff.size();
  std::vector<std::array<double, 9>> gradients(nt);
  std::array<IO::Vtu_array, 3> edge{{{"hex_edge_1", 3, {}}, {"hex_edge_2", 3, {}}, {"hex_edge_3", 3, {}}}};
  std::array<IO::Vtu_array, 3> grad{{{"parameter_gradient_1", 3, {}}, {"parameter_gradient_2", 3, {}},
                                     {"parameter_gradient_3", 3, {}}}};
  IO::Vtu_array gm{"metric", 9, {}}, density{"energy_density", 1, {}}, boundary{"boundary", 1, {}, true},
      align{"alignment_error_deg", 1, {}};
  std::vector<double> alignment(nt, 0.0);
  std::vector<char> on_boundary(nt, 0);
  for (const auto& b : ff.boundary_faces()) {
    on_boundary[b.tet] = 1;
    alignment[b.tet] = std::max(alignment[b.tet], ff.alignment_error_deg(b));
  }
  for (std::size_t i = 0; i < nt; ++i) {
    const Eigen::Matrix3d F = ff.frame(i), G = ff.parameter_gradients(i); // hex edges, parameter gradients
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) {
        gradients[i][3 * k + c] = G(c, k);
        edge[k].values.push_back(F(c, k));
        grad[k].values.push_back(G(c, k));
      }
    const Eigen::Matrix3d g = ff.sqrt_metric(i) * ff.sqrt_metric(i);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) gm.values.push_back(g(r, c));
    density.values.push_back(ff.energy_density(i));
    boundary.values.push_back(on_boundary[i]);
    align.values.push_back(alignment[i]);
  }
  IO::write_fra((dir / "frames.fra").string(), gradients);
  IO::write_perm((dir / "frames.perm").string(), matchings.perm_file(ff));
  IO::write_medit_mesh((dir / "mesh.mesh").string(), mesh);
  IO::write_vtu_tetrahedra((dir / "frames.vtu").string(), mesh.vertices, mesh.tetrahedra,
                           {edge[0], edge[1], edge[2], grad[0], grad[1], grad[2], gm, density, boundary, align});
}

// singularities.vtu: the singular edges as lines, nodes as point data.
void write_singularities_vtu(const std::string& path, const IO::Medit_mesh& mesh, const std::vector<Singular_edge>& sing,
                             const Singularity_graph& graph) {
  std::vector<std::array<double, 3>> points;
  std::vector<std::array<std::size_t, 2>> lines;
  std::map<std::size_t, std::size_t> local;
  IO::Vtu_array type{"type", 1, {}, true}, index{"index", 1, {}}, valence{"valence", 1, {}, true},
      meshable{"meshable", 1, {}, true}, turn{"turn_deg", 1, {}}, axis_angle{"axis_angle_deg", 1, {}},
      edge_axis_angle{"edge_axis_angle_deg", 1, {}},
      axis{"axis", 3, {}}, curve{"curve", 1, std::vector<double>(sing.size(), -1), true};
  for (const Singular_edge& s : sing) {
    std::array<std::size_t, 2> l;
    for (int k = 0; k < 2; ++k) {
      auto it = local.find(s.vertices[k]);
      if (it == local.end()) {
        it = local.emplace(s.vertices[k], points.size()).first;
        points.push_back(mesh.vertices[s.vertices[k]]);
      }
      l[k] = it->second;
    }
    lines.push_back(l);
    type.values.push_back(type_code(s.type));
    index.values.push_back(s.type == Singularity_type::plus_quarter    ? 0.25
                           : s.type == Singularity_type::minus_quarter ? -0.25
                                                                       : std::nan(""));
    valence.values.push_back(s.valence);
    meshable.values.push_back(is_meshable(s.type) ? 1 : 0);
    turn.values.push_back(s.turn_deg);
    axis_angle.values.push_back(s.axis_angle_deg);
    edge_axis_angle.values.push_back(s.edge_axis_angle_deg);
    for (int c = 0; c < 3; ++c) axis.values.push_back(s.axis(c));
  }
  for (std::size_t c = 0; c < graph.curves.size(); ++c)
    for (std::size_t e : graph.curves[c].edges) curve.values[e] = double(c + 1);
  IO::Vtu_array vertex_id{"vertex_index", 1, std::vector<double>(points.size()), true},
      node{"node", 1, std::vector<double>(points.size(), 0), true};
  for (const auto& [global, l] : local) vertex_id.values[l] = double(global + 1);
  for (const Singular_node& n : graph.nodes)
    node.values[local.at(n.vertex)] = n.kind == Singular_node::Kind::boundary_end   ? 1
                                      : n.kind == Singular_node::Kind::interior_end ? 2
                                                                                    : 3;
  IO::write_vtu_segments(path, points, lines, {type, index, valence, meshable, turn, axis_angle, edge_axis_angle, axis, curve},
                         {vertex_id, node});
}

// The singular edges counted by type (every type listed) and the non-meshable ones.
struct Singularity_counts {
  std::map<std::string, std::size_t> by_type = {{"+1/4", 0}, {"-1/4", 0}, {"1/4 across", 0}, {"1/2", 0}, {"1/3", 0}};
  std::size_t non_meshable = 0;
  explicit Singularity_counts(const std::vector<Singular_edge>& sing) {
    for (const Singular_edge& s : sing) {
      ++by_type[singularity_type_name(s.type)];
      non_meshable += !is_meshable(s.type);
    }
  }
};

// The "singularities" object of report.json. Vertex numbers are 1-based, as in mesh.mesh.
std::string singularities_json(const std::vector<Singular_edge>& sing, const Singularity_counts& counts,
                               const Singularity_graph& graph) {
  const auto& by_type = counts.by_type;
  const std::size_t non_meshable = counts.non_meshable;
  std::ostringstream js;
  js << "{\n    \"edges\": " << sing.size() << ",\n    \"edges_by_type\": {";
  bool first = true;
  for (const auto& [name, n] : by_type) js << (first ? "" : ", ") << "\"" << name << "\": " << n, first = false;
  js << "},\n    \"non_meshable_edges\": " << non_meshable << ",\n    \"curves\": " << graph.curves.size()
     << ",\n    \"closed_curves\": " << graph.closed_curves << ",\n    \"nodes\": " << graph.nodes.size()
     << ",\n    \"junctions\": " << graph.junctions << ",\n    \"boundary_ends\": " << graph.boundary_ends
     << ",\n    \"interior_ends\": " << graph.interior_ends << ",\n    \"non_meshable_edge_list\": [";
  first = true;
  for (const Singular_edge& s : sing) {
    if (is_meshable(s.type)) continue;
    js << (first ? "\n" : ",\n") << "      {\"vertices\": [" << s.vertices[0] + 1 << ", " << s.vertices[1] + 1
       << "], \"midpoint\": " << point_json(s.midpoint) << ", \"type\": \"" << singularity_type_name(s.type)
       << "\", \"turn_deg\": " << number(s.turn_deg) << ", \"axis_angle_deg\": " << number(s.axis_angle_deg)
       << ", \"edge_axis_angle_deg\": " << number(s.edge_axis_angle_deg) << "}";
    first = false;
  }
  js << (first ? "" : "\n    ") << "],\n    \"curve_list\": [";
  first = true;
  for (const Singular_curve& c : graph.curves) {
    js << (first ? "\n" : ",\n") << "      {\"edges\": " << c.edges.size() << ", \"length\": " << number(c.length)
       << ", \"closed\": " << (c.closed ? "true" : "false") << ", \"ends\": [" << c.vertices.front() + 1 << ", "
       << c.vertices.back() + 1 << "], \"+1/4\": " << c.plus_quarter_edges << ", \"-1/4\": " << c.minus_quarter_edges
       << ", \"non_meshable\": " << c.non_meshable_edges << "}";
    first = false;
  }
  js << (first ? "" : "\n    ") << "],\n    \"node_list\": [";
  first = true;
  for (const Singular_node& n : graph.nodes) {
    js << (first ? "\n" : ",\n") << "      {\"vertex\": " << n.vertex + 1 << ", \"position\": " << point_json(n.position)
       << ", \"degree\": " << n.degree << ", \"kind\": \"" << singular_node_kind_name(n.kind) << "\"}";
    first = false;
  }
  js << (first ? "" : "\n    ") << "]\n  }";
  return js.str();
}

} // namespace

int command_generate(const std::vector<std::string>& args) {
  Arguments a(args, "generate", generate_help);
  if (a.help_requested()) return 0;
  const auto sol_path = a.option("--metric");
  const auto metric_const = a.option("--metric-const");
  const auto metric_expr = a.option("--metric-expr");
  const auto hex_size_option = a.option("--hex-size");
  const std::string out_dir = a.required_option("-o");
  const bool force = a.flag("--force");
  Tetrahedralize_options mesh_opt;
  const auto size = a.option("--size");
  if (size) mesh_opt.size = parse_positive(a, "--size", *size);
  mesh_opt.sharp_features = !a.flag("--smooth-surface");
  if (const auto m = a.option("--max-memory")) {
    // 0: no limit; otherwise GB (the default is this machine's memory)
    const double gb = *m == "0" ? 0 : parse_positive(a, "--max-memory", *m);
    mesh_opt.memory_limit = gb > 0 ? gb * 1e9 : -1;
  }
  mesh_opt.progress = [](std::size_t vertices, std::size_t expected, double seconds) {
    std::fprintf(stderr, "[progress] Mesh_3: %zu vertices of about %zu expected, %.1f s\n", vertices, expected,
                 seconds);
  };
  Frame_field_options opt;
  if (const auto w = a.option("--boundary-weight")) opt.boundary_weight = parse_positive(a, "--boundary-weight", *w);
  opt.hard_boundary = !a.flag("--soft-boundary");
  if (const auto f = a.option("--feature-angle")) {
    char* end = nullptr;
    const double v = std::strtod(f->c_str(), &end);
    if (end == f->c_str() || *end != '\0' || !(v > 0 && v <= 180))
      a.fail("--feature-angle '" + *f + "': expected an angle in degrees in (0, 180]");
    opt.feature_angle_deg = v;
  }
  mesh_opt.sharp_angle_deg = opt.feature_angle_deg; // the mesh keeps the creases the frames follow
  const bool repair = !a.flag("--no-repair");
  if (const auto n = a.option("--max-iterations")) {
    char* end = nullptr;
    const long v = std::strtol(n->c_str(), &end, 10);
    if (end == n->c_str() || *end != '\0' || v < 0 || v > 100000000)
      a.fail("--max-iterations '" + *n + "': expected a whole number >= 0");
    opt.max_refinement_iterations = int(v);
  }
  if (const auto t = a.option("--tol")) opt.transport_tolerance = parse_positive(a, "--tol", *t);
  Hex_size hex;
  if (hex_size_option) {
    hex.h = parse_positive(a, "--hex-size", *hex_size_option);
    hex.scaled = true;
    hex.rule = "--hex-size";
  }
  const auto threads = thread_limit(a);
  const std::string input = a.positional("INPUT");
  a.finish();
  if (int(bool(sol_path)) + int(bool(metric_const)) + int(bool(metric_expr)) > 1)
    a.fail("give at most one of --metric, --metric-const and --metric-expr");
  const bool is_builtin = input.rfind("builtin:", 0) == 0;
  const bool is_mesh = !is_builtin && has_extension(input, {".mesh"});
  const bool is_surface = !is_builtin && has_extension(input, {".off", ".obj", ".stl", ".ply"});
  if (!is_builtin && !is_mesh && !is_surface)
    a.fail("INPUT '" + input + "': expected a .mesh tet mesh, a surface (.off .obj .stl .ply) or builtin:NAME");
  if ((size || !mesh_opt.sharp_features || mesh_opt.memory_limit != 0) && is_mesh)
    a.fail("--size, --smooth-surface and --max-memory apply to surface and builtin inputs; a .mesh input is used as it is");
  if (sol_path && !is_mesh)
    a.fail("--metric SOL needs a .mesh INPUT: a generated mesh has no vertices the .sol could match");
  std::unique_ptr<Metric_expression> formula;
  if (metric_expr) formula = std::make_unique<Metric_expression>(*metric_expr, Metric_expression::Kind::tensor, "--metric-expr");
  const bool has_metric = sol_path || metric_const || metric_expr;
  const Eigen::Matrix3d g_const = metric_const ? parse_constant_metric(a, *metric_const) : Eigen::Matrix3d::Identity();

  // Nothing is written before every check passed; nothing the user gave is replaced.
  namespace fs = std::filesystem;
  std::error_code ec;
  IO::internal::check_output_directory(out_dir); // before the computation, which can take long
  for (const char* name : output_names) {
    const fs::path p = fs::path(out_dir) / name;
    if (!fs::exists(p, ec)) continue;
    if (fs::equivalent(p, input, ec) || (sol_path && fs::equivalent(p, *sol_path, ec)))
      throw std::runtime_error(p.string() + ": the output would overwrite an input file");
    if (!force) throw std::runtime_error(p.string() + ": the file exists; give --force to replace the outputs");
  }

  Stage_timer timer;
  std::map<std::string, double> stage_seconds;
  auto stage = [&](const std::string& name, double seconds, const std::string& detail) {
    std::fprintf(stderr, "[stage] %-22s %8.3f s  %s\n", name.c_str(), seconds, detail.c_str());
    stage_seconds[name] = seconds;
  };
  auto clock = std::chrono::steady_clock::now();
  auto lap = [&] {
    const auto now = std::chrono::steady_clock::now();
    const double s = std::chrono::duration<double>(now - clock).count();
    clock = now;
    return s;
  };

  // 1. The tet mesh.
  IO::Medit_mesh mesh;
  double mesh_size = 0;
  if (is_mesh) {
    mesh = IO::read_medit_mesh(input);
    stage("read mesh", lap(), std::to_string(mesh.tetrahedra.size()) + " tets, " +
                                   std::to_string(mesh.vertices.size()) + " vertices");
  } else {
    Tetrahedralize_report mr;
    mesh = is_builtin ? tetrahedralize_builtin(input.substr(8), mesh_opt, &mr) : tetrahedralize_surface(input, mesh_opt, &mr);
    mesh_size = mr.size;
    stage("Mesh_3", lap(), std::to_string(mr.tets) + " tets, " + std::to_string(mr.vertices) + " vertices (" +
                               mr.domain + ")");
  }
  Tr tr;
  Tet_soup_source src;
  src.file = is_mesh ? input : std::string("generated mesh");
  src.tet_lines = mesh.tetrahedron_lines;
  src.vertex_lines = mesh.vertex_lines;
  const Tet_mesh_build_report build =
      build_triangulation_from_tets(mesh.vertices, mesh.tetrahedra, mesh.tetrahedron_references, tr, src);
  if (build.reoriented_tets) {
    std::fprintf(stderr,
                 "[note] %zu negatively oriented tetrahedra were re-oriented (first: tetrahedron %zu); mesh.mesh "
                 "has them positive, as CubeCover and HexEx need\n",
                 build.reoriented_tets, build.reoriented_examples.front() + 1);
    // As the triangulation holds them: vertices 3 and 4 swapped.
    const auto orientation = Tr::Geom_traits().orientation_3_object();
    for (auto& t : mesh.tetrahedra) {
      auto P = [&](int k) { return Tr::Point(mesh.vertices[t[k]][0], mesh.vertices[t[k]][1], mesh.vertices[t[k]][2]); };
      if (orientation(P(0), P(1), P(2), P(3)) == CGAL::NEGATIVE) std::swap(t[2], t[3]);
    }
  }
  if (build.unused_vertices) std::fprintf(stderr, "[note] %zu vertices are used by no tetrahedron\n", build.unused_vertices);
  stage("build triangulation", lap(), std::to_string(build.boundary_facets) + " boundary facets");
  // A mesh too large or too small for double is refused here, before the
  // hex size and the metric are derived from its lengths.
  Metric_field_3<Tr>::check_extent(tr, input);

  // 2. The metric, scaled to the hex size: g / h^2.
  if (!has_metric && !hex.scaled) {
    hex.scaled = true;
    if (is_mesh) {
      hex.h = static_cast<double>(compute_tet_mesh_statistics(tr, Is_tet_mesh_domain_cell()).mean_edge_length);
      hex.rule = "mean edge length of the mesh";
    } else {
      hex.h = mesh_size;
      hex.rule = "Mesh_3 size";
    }
  }
  if (!hex.scaled) hex.rule = "the metric's unit length";
  const double scale = 1 / (hex.h * hex.h);
  // g / h^2, each tensor checked again: a valid g can overflow once scaled.
  auto scaled = [&](std::vector<Eigen::Matrix3d> g, const std::string& source) {
    for (std::size_t i = 0; i < g.size(); ++i) {
      g[i] *= scale;
      const std::string problem = check_metric_tensor(g[i]);
      if (!problem.empty())
        throw Input_error(source, 0, "vertex " + std::to_string(i + 1),
                          "the metric scaled to the hex size (g / h^2, h = " + number(hex.h) + "): " + problem);
    }
    return g;
  };
  std::unique_ptr<Field> field;
  std::string metric_name = "identity";
  if (sol_path) {
    field = std::make_unique<Field>(tr, scaled(IO::read_medit_sol(*sol_path, mesh.vertices.size()), *sol_path), *sol_path);
    metric_name = *sol_path;
  } else if (formula) {
    field = std::make_unique<Field>(tr, scaled(evaluate_metric(*formula, mesh.vertices, "--metric-expr"), "--metric-expr"),
                                    "--metric-expr");
    metric_name = "expression " + *metric_expr;
  } else {
    const Eigen::Matrix3d g = g_const * scale;
    const std::string problem = check_metric_tensor(g);
    if (!problem.empty())
      throw Input_error("", 0, "the metric scaled to the hex size (g / h^2, h = " + number(hex.h) + ")", problem);
    field = std::make_unique<Field>(tr, g);
    if (metric_const) metric_name = "constant " + *metric_const;
  }
  field->precompute();
  const double expected_hexes = field->metric_volume();
  if (!std::isfinite(expected_hexes)) {
    // It would be Inf or NaN in the report: name the vertex where
    // sqrt(det g) = det A is largest instead, computed without overflow.
    std::size_t vertex = 0;
    double largest = -std::numeric_limits<double>::infinity(), det = 0;
    int exponent = 0;
    for (Tr::Vertex_handle v : tr.finite_vertex_handles()) {
      const Eigen::Matrix3d& A = field->sqrt_metric(v);
      const int e = internal::metric_scale_exponent(A);
      const double d = internal::times_power_of_two(A, -e).determinant();
      const double log_det = std::log2(d) + 3 * e;
      if (log_det > largest) {
        largest = log_det;
        det = d;
        exponent = 3 * e;
        vertex = v->info();
      }
    }
    throw Input_error(sol_path ? *sol_path : formula ? "--metric-expr" : metric_const ? "--metric-const" : "", 0,
                      "vertex " + std::to_string(vertex + 1),
                      "sqrt(det g) = " + internal::power_of_two_text(det, exponent) +
                          (hex.scaled ? " (g scaled to the hex size h = " + number(hex.h) + ")" : std::string()) +
                          ": the expected number of hexahedra, int sqrt(det g) dV, overflows double precision; give a "
                          "smaller metric or a larger --hex-size");
  }
  stage("metric", lap(),
        metric_name + (hex.scaled ? "; hex size " + number(hex.h) + " (" + hex.rule + ")" : std::string()) +
            "; about " + number(std::round(expected_hexes)) + " hexahedra");

  // 3. The frame field and its singularities.
  opt.progress = stage;
  // Long iterations report at most once per second.
  auto last_report = std::chrono::steady_clock::now();
  opt.iteration_progress = [&](const std::string& name, int iteration, double measure) {
    const auto now = std::chrono::steady_clock::now();
    if (std::chrono::duration<double>(now - last_report).count() < 1) return;
    last_report = now;
    std::fprintf(stderr, "[progress] %s: iteration %d, %s %.4g\n", name.c_str(), iteration,
                 name == "refinement" ? "energy" : "relative residual", measure);
  };
  Frames ff(*field);
  const Frame_field_statistics& st = ff.compute(opt);
  lap(); // compute() reports its own stages
  Singularity_repair_report fix;
  if (repair) {
    Singularity_repair_options ropt;
    ropt.progress = [](int round, int radius, std::size_t tried, std::size_t accepted, std::size_t left) {
      std::fprintf(stderr, "[progress] repair round %d (radius %d): %zu regions, %zu kept, %zu non-meshable edges left\n",
                   round, radius, tried, accepted, left);
    };
    fix = repair_singularities(ff, ropt);
    stage("repair", lap(),
          std::to_string(fix.non_meshable_before) + " -> " + std::to_string(fix.non_meshable_after) +
              " non-meshable edges; " + std::to_string(fix.regions_accepted) + " of " +
              std::to_string(fix.regions_tried) + " regions kept, energy " + number(fix.energy_before) + " -> " +
              number(fix.energy_after));
  }
  const Matchings matchings(ff);
  const std::vector<Singular_edge> sing = singular_edges(ff, matchings);
  const Face_angle_statistics angles = matchings.face_angle_statistics(ff);
  const Singularity_graph graph = singularity_graph(ff, sing);
  const Singularity_counts counts(sing);
  const std::size_t non_meshable = counts.non_meshable;
  stage("singularities", lap(),
        std::to_string(sing.size()) + " singular edges in " + std::to_string(graph.curves.size()) + " curves, " +
            std::to_string(graph.nodes.size()) + " nodes; " + std::to_string(non_meshable) + " non-meshable edges");

  // 4. The files.
  fs::create_directories(out_dir, ec);
  if (ec) throw std::runtime_error(out_dir + ": cannot create the output directory: " + ec.message());
  const fs::path dir(out_dir);
  write_frame_files(dir, mesh, ff, matchings);
  write_singularities_vtu((dir / "singularities.vtu").string(), mesh, sing, graph);
  stage("write outputs", lap(), out_dir);

  const std::size_t nt = ff.size();
  std::ostringstream js;
  js << "{\n"
     << "  \"input\": \"" << json_escape(input) << "\",\n"
     << "  \"metric\": \"" << json_escape(metric_name) << "\",\n"
     << "  \"hex_size\": " << (hex.scaled ? number(hex.h) : "null") << ",\n"
     << "  \"hex_size_rule\": \"" << json_escape(hex.rule) << "\",\n"
     << "  \"expected_hexes\": " << number(expected_hexes) << ",\n"
     << "  \"tets\": " << nt << ",\n"
     << "  \"vertices\": " << mesh.vertices.size() << ",\n"
     << "  \"interior_faces\": " << st.interior_faces << ",\n"
     << "  \"boundary_faces\": " << st.boundary_faces << ",\n"
     << "  \"singular_edges\": " << sing.size() << ",\n"
     << "  \"singularities\": " << singularities_json(sing, counts, graph) << ",\n"
     << "  \"smoothness_energy\": " << number(st.smoothness_energy) << ",\n"
     << "  \"smoothness_energy_per_weight\": " << number(st.smoothness_energy / st.total_face_weight) << ",\n"
     << "  \"projected_energy\": " << number(st.projected_energy) << ",\n"
     << "  \"face_angle_deg\": {\"mean\": " << number(angles.mean_deg) << ", \"median\": " << number(angles.median_deg)
     << ", \"max\": " << number(angles.max_deg) << "},\n"
     << "  \"boundary_alignment_error_deg\": {\"mean\": " << number(st.boundary_error_mean_deg)
     << ", \"max\": " << number(st.boundary_error_max_deg) << "},\n"
     << "  \"g_orthonormality_max_error\": " << number(st.max_orthonormality_error) << ",\n"
     << "  \"hard_boundary_tets\": {\"one_axis\": " << st.hard_one_axis << ", \"two_axes\": " << st.hard_two_axes << "},\n"
     << "  \"sharp_features\": {\"angle_deg\": " << number(opt.feature_angle_deg) << ", \"edges\": " << st.feature_edges
     << ", \"curve_vertices\": " << st.feature_curve_vertices << ", \"corners\": " << st.feature_corners
     << ", \"tets\": " << st.feature_tets << "},\n"
     << "  \"repair\": " << (repair ? "{\"non_meshable_before\": " + std::to_string(fix.non_meshable_before) +
                                   ", \"non_meshable_after\": " + std::to_string(fix.non_meshable_after) +
                                   ", \"rounds\": " + std::to_string(fix.rounds) +
                                   ", \"batches\": " + std::to_string(fix.batches) +
                                   ", \"regions_tried\": " + std::to_string(fix.regions_tried) +
                                   ", \"regions_kept\": " + std::to_string(fix.regions_accepted) +
                                   ", \"tets_changed\": " + std::to_string(fix.tets_changed) +
                                   ", \"energy_before\": " + number(fix.energy_before) +
                                   ", \"energy_after\": " + number(fix.energy_after) + "}"
                                 : std::string("null"))
     << ",\n"
     << "  \"max_transport_angle_deg\": " << number(st.max_transport_angle * 180 / M_PI) << ",\n"
     << "  \"linear_iterations\": " << st.linear_iterations << ",\n"
     << "  \"linear_residual\": " << number(st.linear_residual) << ",\n"
     << "  \"refinement_iterations\": " << st.refinement_iterations << ",\n"
     << "  \"stage_seconds\": {";
  bool first = true;
  for (const auto& [name, s] : stage_seconds) {
    js << (first ? "" : ", ") << "\"" << json_escape(name) << "\": " << number(s);
    first = false;
  }
  js << "}\n}\n";
  const std::string report_path = (dir / "report.json").string();
  const std::string text = js.str();
  IO::internal::write_file_atomically(report_path, [&](std::FILE* f) {
    if (std::fwrite(text.data(), 1, text.size(), f) != text.size()) throw std::runtime_error(report_path + ": write failed");
  });
  stage("write report", lap(), report_path);

  std::string types;
  for (const auto& [name, n] : counts.by_type)
    if (n) types += (types.empty() ? "" : ", ") + name + ": " + std::to_string(n);
  std::fprintf(stderr,
               "\n  %-32s %zu (%zu vertices)\n  %-32s %s\n  %-32s %s\n  %-32s %.0f\n"
               "  %-32s %.6g (per unit weight %.3g)\n  %-32s mean %.3g, median %.3g\n  %-32s mean %.3g, max %.3g\n"
               "  %-32s %.3g\n  %-32s %zu edges, %zu corners (%.3g degrees), %zu tetrahedra follow them\n"
               "  %-32s %zu%s%s%s\n  %-32s %zu (%zu closed), nodes %zu (junctions %zu, boundary ends %zu, interior ends %zu)\n"
               "  %-32s %zu\n",
               "tetrahedra", nt, mesh.vertices.size(), "metric", metric_name.c_str(), "hex size",
               hex.scaled ? (number(hex.h) + " (" + hex.rule + ")").c_str() : "the metric's unit length",
               "expected hexahedra", expected_hexes, "smoothness energy", st.smoothness_energy,
               st.smoothness_energy / st.total_face_weight, "face angle (deg)", angles.mean_deg, angles.median_deg,
               "boundary alignment error (deg)", st.boundary_error_mean_deg,
               st.boundary_error_max_deg, "max |F^T g F - I|", st.max_orthonormality_error, "sharp features", st.feature_edges,
               st.feature_corners, opt.feature_angle_deg, st.feature_tets, "singular edges", sing.size(),
               types.empty() ? "" : " (", types.c_str(), types.empty() ? "" : ")", "singular curves", graph.curves.size(),
               graph.closed_curves, graph.nodes.size(), graph.junctions, graph.boundary_ends, graph.interior_ends,
               "non-meshable singular edges", non_meshable);
  std::size_t listed = 0;
  for (const Singular_edge& s : sing) {
    if (is_meshable(s.type) || listed == 5) continue;
    std::fprintf(stderr, "    %s edge %zu-%zu at (%.6g, %.6g, %.6g)\n", singularity_type_name(s.type), s.vertices[0] + 1,
                 s.vertices[1] + 1, s.midpoint(0), s.midpoint(1), s.midpoint(2));
    ++listed;
  }
  if (non_meshable > listed) std::fprintf(stderr, "    ... (all in report.json)\n");
  std::fprintf(stderr, "  %-32s %s\n", "outputs", out_dir.c_str());
  timer.summary();
  return 0;
}

} // namespace CGAL_ext::cli
