// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The quality of the frame fields that `metric-frames generate` makes with
// its default options (identity metric, Mesh_3 at the bounding-box diagonal
// / 20 for surfaces and built-in shapes), model by model: what decides
// whether an integer-grid map can mesh the field (singular edges of each
// kind, curves, nodes, curves ending inside the volume, non-meshable nodes,
// curves touching the surface, curves from a junction shorter than a hex
// edge of H times the diagonal) and how smooth it
// is (face angles, energy, boundary alignment), and how it follows the
// sharp features (the direction error of the feature edges, singular edges
// at feature vertices). Side by side on the same mesh: generate's field
// before the repair of non-meshable edges ("no repair", default options),
// after it ("repaired"), after it with the singular curves straightened
// ("straightened", generate's output: the curves' interior vertices moved,
// the curves typed and the hex pipeline run with the moved vertices), and
// with feature detection off (feature_angle_deg = 180, the boundary rule
// before features, no repair: "no features").
//
//   benchmark_frame_quality [size_fraction=F] [hex_fraction=H] [hex_sizes=N] [diffusion_steps=N]
//                           [variants=generate] [INPUT ...]
//
// variants=generate: only generate's output ("straightened"), not the
// three other variants.
//
// Hex columns: when the environment gives CubeCover's integer-grid tool and
// HexEx's command-line tool, CGAL_EXT_INTEGERGRID=/path/to/integergrid and
// CGAL_EXT_HEXEX=/path/to/hexex (built outside this project, see
// doc/hex_meshing.md), every field is also written as generate writes it
// (mesh.mesh, frames.fra at hexes of H times the bounding-box diagonal,
// default 1/15, frames.perm) into a temporary directory, run through both,
// and the hex mesh measured by scripts/hex_mesh_quality.py (python3): hexes,
// their sizes against the edge h asked for (the hexes made over the tet
// volume / h^3 that hexes of edge h would need, and the median over the
// hexes of the cube root of their volume over h: a map that coarsens, with
// hexes larger than asked, shows there even where the coverage is high),
// scaled Jacobian min and median, hexes with a scaled Jacobian <= 0, and the
// coverage (hex volume over tet volume), with its ceiling: what hexes of the
// mesh's boundary edge length, and hexes of the size asked for, can cover at
// best where the boundary is curved (their bilinear quads cut below it). "MIP" marks a failed mixed-integer
// solve of integergrid (it then writes zeros and exits 0). hex_sizes=N
// (default 1) runs the pipeline on each field at N hex sizes spread evenly
// over H times 0.97 to 1.03 (the same field, its gradients scaled): the
// integer-grid map of a field with defects changes a lot with a 1% change of
// size, so one run is one sample. The row then gives the median, least and
// largest coverage and hex count, the median size ratios, the median ceiling, the least scaled Jacobian, the most
// inverted hexes, and how many runs meet issue 15's target (every hex's
// scaled Jacobian > 0, coverage >= 0.99), flagged out of reach where the
// ceiling at the sizes asked for is below 0.99.
//
// diffusion_steps=N: N diffusion-projection steps of the default length in
// hex edges (Frame_field_options::diffusion_steps; generate --hex-size h
// --diffusion-steps N), on the models without feature edges.
//
// INPUT: builtin:NAME, a closed surface (.off .obj .stl .ply) meshed by
// Mesh_3, or a tet mesh (.mesh, e.g. written by TetGen or Gmsh). Without
// INPUT: the built-in ball, torus, box_with_hole and blobby, then CGAL's
// fandisk, anchor, joint, rotor and elephant from the directory
// $CGAL_DATA_MESHES if it is set (see doc/benchmarks.md for unpacking
// Debian's libcgal-demo data). size_fraction: Mesh_3 size as a fraction of
// the bounding-box diagonal (default 1/20, or hex_fraction if smaller, as
// generate caps its automatic size by the hex size).
#include <CGAL_ext/Frame_field_3.h>
#include <CGAL_ext/Frame_field_matchings_3.h>
#include <CGAL_ext/Frame_field_repair_3.h>
#include <CGAL_ext/Frame_field_singularities_3.h>
#include <CGAL_ext/Singular_curve_straightening_3.h>
#include <CGAL_ext/IO/Fra_file.h>
#include <CGAL_ext/IO/Hexex_file.h>
#include <CGAL_ext/Integer_grid_map_3.h>
#include <CGAL_ext/make_integer_grid_map_input.h>
#include <CGAL_ext/IO/Medit_mesh.h>
#include <CGAL_ext/IO/Perm_file.h>
#include <CGAL_ext/Metric_field_3.h>
#include <CGAL_ext/Sharp_features_3.h>
#include <CGAL_ext/build_triangulation_from_tets.h>
#include <CGAL_ext/tetrahedralize.h>

#include <nlohmann/json.hpp>
#include <tbb/info.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using Tr = CGAL_ext::Tet_mesh_triangulation_3<>;
using Field = CGAL_ext::Metric_field_3<Tr>;
using Frames = CGAL_ext::Frame_field_3<Field>;

namespace {

double since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

double diagonal(const std::vector<std::array<double, 3>>& points) {
  std::array<double, 3> lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (const auto& p : points)
    for (std::size_t k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
  return std::hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
}

// The mesh of an input, as generate makes it.
CGAL_ext::IO::Medit_mesh mesh_of(const std::string& input, double size_fraction) {
  namespace fs = std::filesystem;
  if (fs::path(input).extension() == ".mesh") return CGAL_ext::IO::read_medit_mesh(input);
  CGAL_ext::Tetrahedralize_options mo;
  mo.sharp_angle_deg = CGAL_ext::Frame_field_options().feature_angle_deg; // as generate
  if (size_fraction > 0) {
    // The size is a fraction of the domain's diagonal: mesh coarsely once
    // to find it (Mesh_3's own automatic size is the diagonal / 20).
    CGAL_ext::Tetrahedralize_options coarse = mo;
    const bool builtin = input.rfind("builtin:", 0) == 0;
    const auto m = builtin ? CGAL_ext::tetrahedralize_builtin(input.substr(8), coarse)
                           : CGAL_ext::tetrahedralize_surface(input, coarse);
    mo.size = diagonal(m.vertices) * size_fraction;
  }
  return input.rfind("builtin:", 0) == 0 ? CGAL_ext::tetrahedralize_builtin(input.substr(8), mo)
                                         : CGAL_ext::tetrahedralize_surface(input, mo);
}

// One run of the hex pipeline.
struct Hex_run {
  std::string error; // empty if a hex mesh was measured
  bool mip_failed = false;
  std::size_t hexes = 0, inverted = 0;
  double sj_min = 0, sj_median = 0, coverage = 0;
  // The coverage the boundary's curvature allows (hex_mesh_quality.py): with
  // the hex mesh's boundary edges, and with edges of the hex size asked for.
  double ceiling = 0, ceiling_at_h = 0;
  // The sizes against the edge h asked for: the median over the hexes of
  // the cube root of their volume over h, and the hexes made over those
  // that hexes of edge h would need to fill the volume.
  double size_ratio = 0, count_ratio = 0;
  // The map's tetrahedra: with a negative parameter volume, and flat (below
  // 1e-3 of the volume due, vol / h^3, the identity metric scaled).
  std::size_t map_inverted = 0, map_flat = 0;
  double map_seconds = 0; // the map's own time (integergrid's, or ours)
  bool meets_target() const { return error.empty() && inverted == 0 && coverage >= 0.99; }
};

struct Quality {
  std::size_t tets = 0, singular = 0, plus = 0, minus = 0, non_meshable = 0, curves = 0, nodes = 0,
              interior_ends = 0, non_meshable_nodes = 0, surface_touches = 0, short_curves = 0;
  double angle_mean = 0, angle_median = 0, energy_per_weight = 0, align_mean = 0, align_max = 0;
  // The features found at the default angle (whether the field used them or not).
  std::size_t feature_edges = 0, corners = 0;
  // The angle between a feature edge's direction (in the metric) and the
  // nearest frame axis, over the (tetrahedron, feature edge) pairs.
  double tangent_error_mean = 0, tangent_error_max = 0;
  // Singular edges with a vertex on a feature edge, and those of them that
  // run along the surface (both vertices on the boundary).
  std::size_t singular_at_features = 0, singular_along_features = 0;
  double seconds_field = 0;
  // The hex meshes of CubeCover and HexEx, one per hex size (hex columns only).
  // and of our integer-grid map and HexEx.
  std::vector<Hex_run> hex_runs, our_runs;
};

// The hex tools, if the environment names them.
struct Hex_tools {
  std::string integergrid, hexex;
  double fraction = 1.0 / 15; // hex edge over the bounding-box diagonal
  int sizes = 1;              // hex sizes per field, spread over fraction * [1 - spread, 1 + spread]
  static constexpr double spread = 0.03;
  bool enabled() const { return !integergrid.empty() && !hexex.empty(); }
  // The hex edge of run k of `sizes` for a field whose target edge is h.
  double size(double h, int k) const { return sizes == 1 ? h : h * (1 + spread * (2.0 * k / (sizes - 1) - 1)); }
};

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The number at `key` of a JSON object (NaN if absent or null).
double json_number(const nlohmann::json& object, const char* key) {
  const auto it = object.find(key);
  return it != object.end() && it->is_number() ? it->get<double>() : std::nan("");
}

std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// The tetrahedra of a .hexex map that are inverted or flat in parameter space.
void count_map_tets(const std::filesystem::path& file, double h, Hex_run& q) {
  const CGAL_ext::IO::Hexex_file map = CGAL_ext::IO::read_hexex(file.string());
  for (std::size_t t = 0; t < map.tets.size(); ++t) {
    const auto& p = map.positions;
    const auto& v = map.tets[t];
    const auto& u = map.parameters[t];
    Eigen::Matrix3d D, P;
    D << p[v[1]] - p[v[0]], p[v[2]] - p[v[0]], p[v[3]] - p[v[0]];
    P << u[1] - u[0], u[2] - u[0], u[3] - u[0];
    const double pv = P.determinant(), due = D.determinant() / (h * h * h);
    q.map_inverted += pv < 0;
    q.map_flat += pv >= 0 && pv <= 1e-3 * due;
  }
}

// HexEx on the map `dir/map_name`, then the quality script on its hexes.
void extract_and_measure(const Hex_tools& tools, const std::filesystem::path& dir, const std::string& map_name, double h,
                         Hex_run& q) {
  auto path = [&](const std::string& name) { return shell_quote((dir / name).string()); };
  if (q.error.empty()) count_map_tets(dir / map_name, h, q);
  const std::string hx = shell_quote(tools.hexex) + " " + path(map_name) + " " + path(map_name + ".ovm") + " > " +
                         path(map_name + ".log") + " 2>&1";
  if (q.error.empty() && std::system(hx.c_str()) != 0) q.error = "hexex failed";
  char hex_size[32];
  std::snprintf(hex_size, sizeof hex_size, "%.17g", h);
  const std::string json = map_name + ".quality.json";
  const std::string qs = std::string("python3 ") + shell_quote(CGAL_EXT_HEX_QUALITY_SCRIPT) + " " +
                         path(map_name + ".ovm") + " --tets " + path("mesh.mesh") + " --hex-size " + hex_size +
                         " --json > " + path(json) + " 2> " + path(map_name + ".quality.log");
  if (q.error.empty() && std::system(qs.c_str()) != 0) q.error = "no hex mesh";
  if (!q.error.empty()) return;
  const nlohmann::json j = nlohmann::json::parse(slurp(dir / json), nullptr, /*allow_exceptions=*/false);
  const nlohmann::json& sj = j.is_object() ? j.value("scaled_jacobian", nlohmann::json::object()) : j;
  if (!j.is_object() || !sj.is_object()) {
    q.error = "unreadable " + json;
    return;
  }
  q.hexes = std::size_t(json_number(j, "hexahedra"));
  q.sj_min = json_number(sj, "min");
  q.sj_median = json_number(sj, "median");
  q.inverted = std::size_t(json_number(sj, "count_le_0"));
  q.coverage = json_number(j, "coverage");
  const auto c = j.find("coverage_ceiling");
  q.ceiling = q.ceiling_at_h = std::nan("");
  if (c != j.end() && c->is_object()) {
    q.ceiling = json_number(*c, "estimate");
    const auto at = c->find("at_hex_size");
    if (at != c->end() && at->is_object()) q.ceiling_at_h = json_number(*at, "estimate");
  }
  q.size_ratio = q.count_ratio = std::nan("");
  const auto z = j.find("size");
  if (z != j.end() && z->is_object()) {
    const auto e = z->find("edge_ratio");
    if (e != z->end() && e->is_object()) q.size_ratio = json_number(*e, "median");
    q.count_ratio = json_number(*z, "hexes_over_expected");
  }
}

// Writes the field as generate does (hexes of edge h), runs integergrid and
// HexEx, and our integer-grid map and HexEx, and measures both hex meshes.
// `matchings`: the field's, computed once for all sizes.
std::pair<Hex_run, Hex_run> hex_pipeline(const Hex_tools& tools, const CGAL_ext::IO::Medit_mesh& mesh, const Frames& ff,
                                         const CGAL_ext::Frame_field_matchings_3<Frames>& matchings, double h,
                                         const std::vector<Eigen::Vector3d>* positions) {
  namespace fs = std::filesystem;
  static int counter = 0;
  const fs::path dir = fs::temp_directory_path() /
                       ("cgal_ext_hex_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
  fs::create_directories(dir);
  Hex_run q, ours;
  CGAL_ext::IO::Medit_mesh tets;
  tets.vertices = mesh.vertices;
  if (positions) // unused vertices have none (NaN)
    for (std::size_t v = 0; v < std::min(tets.vertices.size(), positions->size()); ++v)
      if ((*positions)[v].allFinite())
        for (int c = 0; c < 3; ++c) tets.vertices[v][std::size_t(c)] = (*positions)[v](c);
  tets.tetrahedra = mesh.tetrahedra;
  CGAL_ext::IO::write_medit_mesh((dir / "mesh.mesh").string(), tets);
  std::vector<std::array<double, 9>> gradients(ff.size());
  for (std::size_t i = 0; i < ff.size(); ++i) {
    const Eigen::Matrix3d G = ff.parameter_gradients(i) / h; // the identity metric scaled to g = I / h^2
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) gradients[i][3 * k + c] = G(c, k);
  }
  CGAL_ext::IO::write_fra((dir / "frames.fra").string(), gradients);
  CGAL_ext::IO::write_perm((dir / "frames.perm").string(),
                           matchings.perm_file(ff));
  auto path = [&](const char* name) { return shell_quote((dir / name).string()); };
  const std::string ig = shell_quote(tools.integergrid) + " " + path("mesh.mesh") + " " + path("frames.fra") + " " +
                         path("frames.perm") + " " + path("param.hexex") + " > " + path("integergrid.log") + " 2>&1";
  auto t = std::chrono::steady_clock::now();
  if (std::system(ig.c_str()) != 0) q.error = "integergrid failed";
  q.map_seconds = since(t);
  q.mip_failed = slurp(dir / "integergrid.log").find("Problem with MIP solve") != std::string::npos;
  extract_and_measure(tools, dir, "param.hexex", h, q);

  // Ours, on the same mesh (the vertices written) and field.
  t = std::chrono::steady_clock::now();
  std::vector<Eigen::Vector3d> points;
  for (const auto& v : tets.vertices) points.push_back({v[0], v[1], v[2]});
  const CGAL_ext::Integer_grid_map_input in = CGAL_ext::make_integer_grid_map_input(ff, matchings, points, h);
  const CGAL_ext::Integer_grid_map map = CGAL_ext::compute_integer_grid_map(in);
  ours.map_seconds = since(t);
  CGAL_ext::IO::write_hexex((dir / "ours.hexex").string(), {map.positions, map.tets, map.parameters});
  extract_and_measure(tools, dir, "ours.hexex", h, ours);

  if (q.error.empty() && ours.error.empty()) fs::remove_all(dir);
  for (Hex_run* r : {&q, &ours})
    if (!r->error.empty()) r->error += " (files in " + dir.string() + ")";
  return {q, ours};
}

// The measures of a computed field; `seconds`: the time it took (the time
// of the matchings and singular curves is added). With `straighten`, those
// of generate's output: the curves straightened.
Quality measure(const Tr& tr, const Field& field, const Frames& ff, double seconds, const Hex_tools& tools,
                const CGAL_ext::IO::Medit_mesh& mesh, double h, bool straighten = false) {
  Quality q;
  const auto t = std::chrono::steady_clock::now();
  const CGAL_ext::Frame_field_statistics& st = ff.statistics();
  const CGAL_ext::Frame_field_matchings_3<Frames> matchings(ff);
  auto edges = CGAL_ext::singular_edges(ff, matchings);
  std::vector<Eigen::Vector3d> positions;
  if (straighten) { // kept when any vertex moved, as generate does
    CGAL_ext::Singular_curve_straightening_report report;
    positions = CGAL_ext::straighten_singular_curves(ff, matchings, edges, {}, &report);
    if (report.moved_vertices > 0) edges = CGAL_ext::singular_edges(ff, matchings, nullptr, &positions);
    else positions.clear();
  }
  const std::vector<Eigen::Vector3d>* moved = positions.empty() ? nullptr : &positions;
  const CGAL_ext::Singularity_graph graph = CGAL_ext::singularity_graph(ff, edges, moved);
  q.seconds_field = seconds + since(t);

  q.tets = ff.size();
  q.singular = edges.size();
  for (const auto& e : edges) {
    q.plus += e.type == CGAL_ext::Singularity_type::plus_quarter;
    q.minus += e.type == CGAL_ext::Singularity_type::minus_quarter;
    q.non_meshable += !CGAL_ext::is_meshable(e.type);
  }
  q.curves = graph.curves.size();
  q.nodes = graph.nodes.size();
  q.interior_ends = graph.interior_ends;
  q.non_meshable_nodes = graph.non_meshable_nodes;
  q.surface_touches = graph.surface_touches.size();
  q.short_curves = CGAL_ext::short_singular_curves(graph, h).size(); // the identity metric: lengths in the model's units
  const CGAL_ext::Face_angle_statistics angles = matchings.face_angle_statistics(ff);
  q.angle_mean = angles.mean_deg;
  q.angle_median = angles.median_deg;
  q.energy_per_weight = st.smoothness_energy / st.total_face_weight;
  q.align_mean = st.boundary_error_mean_deg;
  q.align_max = st.boundary_error_max_deg;

  // The features at the default angle, measured on both fields alike.
  const CGAL_ext::Sharp_features_3<Field> features(field, CGAL_ext::Frame_field_options().feature_angle_deg);
  q.feature_edges = features.feature_edges().size();
  q.corners = features.number_of_corners();
  std::size_t pairs = 0;
  for (std::size_t i = 0; i < ff.size(); ++i) {
    const auto c = ff.cell(i);
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) {
        if (!features.is_feature_edge(ff.vertex_index(c->vertex(a)), ff.vertex_index(c->vertex(b)))) continue;
        const Eigen::Vector3d d =
            ff.sqrt_metric(i) *
            (CGAL_ext::internal::to_eigen_vector(c->vertex(b)->point()) - CGAL_ext::internal::to_eigen_vector(c->vertex(a)->point()));
        const double cosine = (ff.rotation(i).transpose() * d.normalized()).cwiseAbs().maxCoeff();
        const double error = std::acos(std::min(1.0, cosine)) * 180 / M_PI;
        q.tangent_error_mean += error;
        q.tangent_error_max = std::max(q.tangent_error_max, error);
        ++pairs;
      }
  }
  if (pairs > 0) q.tangent_error_mean /= double(pairs);
  std::vector<char> on_boundary(tr.number_of_vertices(), 0);
  for (std::size_t i = 0; i < ff.size(); ++i)
    for (int f = 0; f < 4; ++f)
      if (ff.neighbor(i, f) < 0)
        for (int k = 0; k < 4; ++k)
          if (k != f) on_boundary[ff.vertex_index(ff.cell(i)->vertex(k))] = 1;
  for (const auto& e : edges) {
    const bool at = features.kind(e.vertices[0]) != CGAL_ext::Feature_vertex_kind::none ||
                    features.kind(e.vertices[1]) != CGAL_ext::Feature_vertex_kind::none;
    q.singular_at_features += at;
    q.singular_along_features += at && on_boundary[e.vertices[0]] && on_boundary[e.vertices[1]];
  }
  if (tools.enabled())
    for (int k = 0; k < tools.sizes; ++k) {
      const auto [theirs, ours] = hex_pipeline(tools, mesh, ff, matchings, tools.size(h, k), moved);
      q.hex_runs.push_back(theirs);
      q.our_runs.push_back(ours);
    }
  return q;
}

// The hex meshes of one map (integergrid's or ours) over the sizes.
void print_hex_runs(const std::string& name, const char* variant, const char* map, const std::vector<Hex_run>& runs) {
  if (runs.size() == 1) {
    const Hex_run& r = runs[0];
    if (!r.error.empty())
      std::printf("%-22s %-12s   %s: hex pipeline: %s\n", name.c_str(), variant, map, r.error.c_str());
    else
      std::printf("%-22s %-12s   %s (%.2f s): %zu inverted and %zu flat tets; hexes %zu (%.2f of the count asked "
                  "for, median size %.2f h), scaled Jacobian min %.3f median %.3f, <= 0: %zu, coverage %.4f (ceiling "
                  "%.4f, at the size asked for %.4f%s)%s\n",
                  name.c_str(), variant, map, r.map_seconds, r.map_inverted, r.map_flat, r.hexes, r.count_ratio, r.size_ratio, r.sj_min, r.sj_median, r.inverted,
                  r.coverage, r.ceiling, r.ceiling_at_h, r.ceiling_at_h < 0.99 ? ": 0.99 out of reach" : "",
                  r.mip_failed ? " (MIP)" : "");
  } else if (runs.size() > 1) {
    std::vector<double> coverage, hexes, ceiling, ceiling_at_h, size_ratio, count_ratio;
    double sj_min = 1;
    std::size_t inverted = 0, met = 0, mip = 0, map_inverted = 0, map_flat = 0;
    for (const Hex_run& r : runs) {
      mip += r.mip_failed;
      map_inverted = std::max(map_inverted, r.map_inverted);
      map_flat = std::max(map_flat, r.map_flat);
      if (!r.error.empty()) continue;
      coverage.push_back(r.coverage);
      if (std::isfinite(r.ceiling)) ceiling.push_back(r.ceiling);
      if (std::isfinite(r.ceiling_at_h)) ceiling_at_h.push_back(r.ceiling_at_h);
      hexes.push_back(double(r.hexes));
      if (std::isfinite(r.size_ratio)) size_ratio.push_back(r.size_ratio);
      if (std::isfinite(r.count_ratio)) count_ratio.push_back(r.count_ratio);
      sj_min = std::min(sj_min, r.sj_min);
      inverted = std::max(inverted, r.inverted);
      met += r.meets_target();
    }
    const std::size_t n = runs.size();
    if (coverage.empty()) {
      std::printf("%-22s %-12s   %s: hex pipeline: no hex mesh at any of %zu sizes (first: %s)\n", name.c_str(),
                  variant, map, n, runs[0].error.c_str());
      return;
    }
    auto median = [](std::vector<double> v) {
      if (v.empty()) return std::nan(""); // no run gave the figure
      std::sort(v.begin(), v.end());
      return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
    };
    const double c = median(ceiling), c_at_h = median(ceiling_at_h);
    const double size = median(size_ratio), count = median(count_ratio);
    std::printf("%-22s %-12s   %s: most inverted and flat tets %zu and %zu; %zu sizes, %zu hex meshes: hexes %.0f (%.0f-%.0f; %.2f of the count asked for, "
                "median size %.2f h), coverage %.4f (%.4f-%.4f), ceiling %.4f (at the sizes asked for %.4f), "
                "scaled Jacobian min %.3f, most <= 0: %zu, target met %zu of %zu%s%s\n",
                name.c_str(), variant, map, map_inverted, map_flat, n, coverage.size(), median(hexes),
                *std::min_element(hexes.begin(), hexes.end()), *std::max_element(hexes.begin(), hexes.end()), count, size,
                median(coverage), *std::min_element(coverage.begin(), coverage.end()),
                *std::max_element(coverage.begin(), coverage.end()), c, c_at_h, sj_min, inverted, met, n,
                c_at_h < 0.99 ? " (coverage 0.99 out of reach at these sizes)" : "",
                mip ? (" (" + std::to_string(mip) + " MIP)").c_str() : "");
  }
}

void print_row(const std::string& name, const char* variant, const Quality& q, double seconds_mesh) {
  std::printf("%-22s %-12s %8zu %6zu %5zu %5zu %5zu %6zu %5zu %6zu %5zu %5zu %5zu %8.3f %8.3f %8.4f %7.3f %7.2f %6zu %6zu "
              "%7.2f %7.2f %5zu %5zu %7.1f %7.1f\n",
              name.c_str(), variant, q.tets, q.singular, q.plus, q.minus, q.non_meshable, q.curves, q.nodes,
              q.interior_ends, q.non_meshable_nodes, q.surface_touches, q.short_curves, q.angle_mean, q.angle_median,
              q.energy_per_weight, q.align_mean, q.align_max,
              q.feature_edges, q.corners, q.tangent_error_mean, q.tangent_error_max, q.singular_at_features,
              q.singular_along_features, seconds_mesh, q.seconds_field);
  print_hex_runs(name, variant, "integergrid", q.hex_runs);
  print_hex_runs(name, variant, "our map", q.our_runs);
}

// The four variants of one model: no repair, repaired, straightened (generate's output), no features.
void benchmark_model(const std::string& input, const std::string& name, double size_fraction, const Hex_tools& tools,
                     int diffusion_steps, bool all_variants) {
  const auto t = std::chrono::steady_clock::now();
  const CGAL_ext::IO::Medit_mesh mesh = mesh_of(input, size_fraction);
  Tr tr;
  CGAL_ext::build_triangulation_from_tets(mesh.vertices, mesh.tetrahedra, mesh.tetrahedron_references, tr);
  const Field field(tr, Eigen::Matrix3d::Identity().eval());
  const double seconds_mesh = since(t);
  const double h = diagonal(mesh.vertices) * tools.fraction;
  // Generate's default: features, then the repair of non-meshable edges.
  auto t_field = std::chrono::steady_clock::now();
  // The identity metric in the model's units: the diffusion length in hex
  // edges becomes h times it, as generate --hex-size h scales the metric.
  CGAL_ext::Frame_field_options defaults;
  defaults.diffusion_steps = diffusion_steps;
  defaults.diffusion_length *= h;
  Frames ff(field);
  ff.compute(defaults);
  const double seconds_compute = since(t_field);
  if (all_variants) print_row(name, "no repair", measure(tr, field, ff, seconds_compute, tools, mesh, h), seconds_mesh);
  t_field = std::chrono::steady_clock::now();
  CGAL_ext::repair_singularities(ff);
  const double seconds_repaired = seconds_compute + since(t_field);
  if (all_variants) print_row(name, "repaired", measure(tr, field, ff, seconds_repaired, tools, mesh, h), seconds_mesh);
  print_row(name, "straightened", measure(tr, field, ff, seconds_repaired, tools, mesh, h, true), seconds_mesh);
  if (!all_variants) return;
  t_field = std::chrono::steady_clock::now();
  Frames plain(field);
  CGAL_ext::Frame_field_options options = defaults;
  options.feature_angle_deg = 180;
  plain.compute(options);
  print_row(name, "no features", measure(tr, field, plain, since(t_field), tools, mesh, h), seconds_mesh);
}

} // namespace

int main(int argc, char** argv) {
  double size_fraction = 0;
  int diffusion_steps = CGAL_ext::Frame_field_options().diffusion_steps;
  bool all_variants = true;
  Hex_tools tools;
  if (const char* p = std::getenv("CGAL_EXT_INTEGERGRID")) tools.integergrid = p;
  if (const char* p = std::getenv("CGAL_EXT_HEXEX")) tools.hexex = p;
  std::vector<std::string> inputs;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg.rfind("size_fraction=", 0) == 0) {
      size_fraction = std::atof(arg.c_str() + 14);
      if (!(size_fraction > 0 && size_fraction < 1)) {
        std::fprintf(stderr, "size_fraction must be in (0, 1), got '%s'\n", arg.c_str() + 14);
        return 2;
      }
    } else if (arg.rfind("hex_fraction=", 0) == 0) {
      tools.fraction = std::atof(arg.c_str() + 13);
      if (!(tools.fraction > 0 && tools.fraction < 1)) {
        std::fprintf(stderr, "hex_fraction must be in (0, 1), got '%s'\n", arg.c_str() + 13);
        return 2;
      }
    } else if (arg.rfind("hex_sizes=", 0) == 0) {
      tools.sizes = std::atoi(arg.c_str() + 10);
      if (!(tools.sizes >= 1 && tools.sizes <= 101)) {
        std::fprintf(stderr, "hex_sizes must be in [1, 101], got '%s'\n", arg.c_str() + 10);
        return 2;
      }
    } else if (arg.rfind("diffusion_steps=", 0) == 0) {
      diffusion_steps = std::atoi(arg.c_str() + 16);
      if (!(diffusion_steps >= 0 && diffusion_steps <= 1000)) {
        std::fprintf(stderr, "diffusion_steps must be in [0, 1000], got '%s'\n", arg.c_str() + 16);
        return 2;
      }
    } else if (arg == "variants=generate") {
      all_variants = false;
    } else if (arg == "-h" || arg == "--help") {
      std::printf("usage: benchmark_frame_quality [size_fraction=F] [hex_fraction=H] [hex_sizes=N] [diffusion_steps=N]\n"
                  "                               [variants=generate] [INPUT ...]\n"
                  "hex columns: set CGAL_EXT_INTEGERGRID and CGAL_EXT_HEXEX to the tools' paths\n"
                  "INPUT: builtin:NAME, a closed surface (.off .obj .stl .ply), or a tet mesh (.mesh)\n");
      return 0;
    } else {
      inputs.push_back(arg);
    }
  }
  if (inputs.empty()) {
    inputs = {"builtin:ball", "builtin:torus", "builtin:box_with_hole", "builtin:blobby"};
    if (const char* dir = std::getenv("CGAL_DATA_MESHES"))
      for (const char* model : {"fandisk", "anchor", "joint", "rotor", "elephant"})
        inputs.push_back(std::string(dir) + "/" + model + ".off");
  }
  std::printf("Frame-field quality with generate's default options (identity metric, Frame_field_options(), %d\n"
              "diffusion steps of %g hex edges of the size below, as generate --hex-size scales them), %d threads,\n"
              "before and after the repair of non-meshable edges and nodes (no repair, repaired), after it with the\n"
              "singular curves straightened (straightened: generate's output, typed and meshed with the moved vertices),\n"
              "and with features off and no repair (no features), on the same mesh.\n"
              "Singular edges: all, +1/4, -1/4, non-meshable (neither quarter turn about the edge); curves, nodes, curves\n"
              "ending inside the volume, non-meshable nodes (nm.nd), vertices where a curve touches the smooth surface\n"
              "(touch), curves from a junction shorter than the middle hex size (short); face angle between matched\n"
              "neighbouring frames (deg); energy per unit face weight; boundary alignment error (deg); feature edges\n"
              "and corners (at the default angle); angle between a feature edge and the nearest frame axis (deg, mean\n"
              "and max over tetrahedra at feature edges); singular edges at a feature vertex (f.sing) and, of them,\n"
              "along the surface (f.surf); seconds for the mesh (Mesh_3 or reading) and for the field (frames, repair,\n"
              "matchings, singular curves).\n",
              diffusion_steps, CGAL_ext::Frame_field_options().diffusion_length, tbb::info::default_concurrency());
  if (tools.enabled())
    std::printf("Hex meshes: CubeCover's integergrid (%s) and HexEx (%s), hexes of %.4g times the bounding-box\n"
                "diagonal (%d sizes from %.4g to %.4g times it: median (least-largest)), measured by\n"
                "scripts/hex_mesh_quality.py (Verdict's scaled Jacobian; coverage: hex volume over tet volume; its\n"
                "ceiling: what the boundary's curvature leaves to hexes with the hex mesh's boundary edges and with\n"
                "edges of the size asked for; target: every scaled Jacobian > 0 and coverage >= 0.99).\n",
                tools.integergrid.c_str(), tools.hexex.c_str(), tools.fraction, tools.sizes, tools.size(1, 0),
                tools.size(1, tools.sizes - 1));
  std::printf("\n");
  std::printf("%-22s %-12s %8s %6s %5s %5s %5s %6s %5s %6s %5s %5s %5s %8s %8s %8s %7s %7s %6s %6s %7s %7s %5s %5s %7s %7s\n",
              "model", "variant", "tets", "sing", "+1/4", "-1/4", "nonm", "curves", "nodes", "in-end", "nm.nd", "touch", "short",
              "ang.mean",
              "ang.med", "E/w", "al.mean", "al.max", "f.edge", "corner", "tan.mean", "tan.max", "f.sing", "f.surf",
              "mesh s", "field s");
  int failures = 0;
  for (const std::string& input : inputs) {
    const std::string name = input.rfind("builtin:", 0) == 0 ? input : std::filesystem::path(input).filename().string();
    try {
      benchmark_model(input, name, size_fraction > 0 ? size_fraction : tools.fraction < 1.0 / 20 ? tools.fraction : 0,
                      tools, diffusion_steps, all_variants);
    } catch (const std::exception& e) {
      std::printf("%-22s error: %s\n", name.c_str(), e.what());
      ++failures;
    }
    std::fflush(stdout);
  }
  return failures == 0 ? 0 : 1;
}
