// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The output steps of the generate pipeline (Frame_field_pipeline.h): the
// files for CubeCover, HexEx and ParaView, report.json's file and the summary
// (the report's JSON value is header-only: Frame_field_pipeline_report.h).
#include <CGAL_ext/Frame_field_pipeline.h>

#include "../IO/write_file_atomically.h"

#include <CGAL_ext/IO/Fra_file.h>
#include <CGAL_ext/IO/Hexex_file.h>
#include <CGAL_ext/IO/Medit_mesh.h>
#include <CGAL_ext/IO/Perm_file.h>
#include <CGAL_ext/IO/Vtu_file.h>
#include <CGAL_ext/Input_error.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>

namespace CGAL_ext {

namespace {

using Frames = Pipeline_frame_field_3;
using Matchings = Pipeline_matchings_3;

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

// The map at the corners of `mesh`'s tetrahedra, in their order (the map's
// input has the triangulation's order, an even permutation of it: both are
// positively oriented).
std::vector<std::array<Eigen::Vector3d, 4>> parameters_in_mesh_order(const IO::Medit_mesh& mesh,
                                                                      const Pipeline_integer_grid_map& map) {
  std::vector<std::array<Eigen::Vector3d, 4>> out(mesh.tetrahedra.size());
  for (std::size_t t = 0; t < out.size(); ++t)
    for (std::size_t c = 0; c < 4; ++c)
      for (std::size_t l = 0; l < 4; ++l)
        if (map.input.tets[t][l] == mesh.tetrahedra[t][c]) out[t][c] = map.map.input_parameters[t][l];
  return out;
}

// frames.fra, frames.perm, frames.vtu: per tet, the gradients, matchings and
// edges (and the map's parameters, if any).
void write_frame_files(const std::filesystem::path& dir, const IO::Medit_mesh& mesh, const Frames& ff,
                       const Matchings& matchings, const std::vector<std::array<Eigen::Vector3d, 4>>* parameters) {
  const std::size_t nt = ff.size();
  std::vector<std::array<double, 9>> gradients(nt);
  std::array<IO::Vtu_array, 3> edge{{{"hex_edge_1", 3, {}}, {"hex_edge_2", 3, {}}, {"hex_edge_3", 3, {}}}};
  std::array<IO::Vtu_array, 3> grad{{{"parameter_gradient_1", 3, {}}, {"parameter_gradient_2", 3, {}},
                                     {"parameter_gradient_3", 3, {}}}};
  IO::Vtu_array gm{"metric", 9, {}}, density{"energy_density", 1, {}}, boundary{"boundary", 1, {}, true},
      align{"alignment_error_deg", 1, {}}, hard_axes{"hard_axes", 1, {}, true},
      released{"hard_constraint_released", 1, {}, true};
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
    hard_axes.values.push_back(ff.hard_constraint_axes(i));
    released.values.push_back(ff.hard_constraint_released(i) ? 1 : 0);
  }
  IO::write_fra((dir / "frames.fra").string(), gradients);
  IO::write_perm((dir / "frames.perm").string(), matchings.perm_file(ff));
  IO::write_medit_mesh((dir / "mesh.mesh").string(), mesh);
  std::vector<IO::Vtu_array> cell_data = {edge[0], edge[1], edge[2], grad[0], grad[1], grad[2],
                                          gm,      density, boundary, align,   hard_axes, released};
  if (parameters) {
    IO::Vtu_array u{"parameters", 12, {}};
    for (const auto& tet : *parameters)
      for (const Eigen::Vector3d& p : tet) u.values.insert(u.values.end(), {p(0), p(1), p(2)});
    cell_data.push_back(std::move(u));
  }
  IO::write_vtu_tetrahedra((dir / "frames.vtu").string(), mesh.vertices, mesh.tetrahedra, cell_data);
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
      node{"node", 1, std::vector<double>(points.size(), 0), true},
      vertex_meshable{"vertex_meshable", 1, std::vector<double>(points.size(), 1), true};
  for (const auto& [global, l] : local) vertex_id.values[l] = double(global + 1);
  for (const Singular_node& n : graph.nodes)
    node.values[local.at(n.vertex)] = n.kind == Singular_node::Kind::boundary_end   ? 1
                                      : n.kind == Singular_node::Kind::interior_end ? 2
                                                                                    : 3;
  for (const Singular_node& n : graph.nodes) vertex_meshable.values[local.at(n.vertex)] = n.meshable ? 1 : 0;
  for (std::size_t v : graph.surface_touches) vertex_meshable.values[local.at(v)] = 0;
  for (std::size_t v : graph.curve_turns) vertex_meshable.values[local.at(v)] = 0;
  IO::write_vtu_segments(path, points, lines, {type, index, valence, meshable, turn, axis_angle, edge_axis_angle, axis, curve},
                         {vertex_id, node, vertex_meshable});
}

} // namespace

const std::vector<std::string>& pipeline_output_names() {
  static const std::vector<std::string> names = {"frames.fra",        "frames.perm", "mesh.mesh", "frames.vtu",
                                                 "singularities.vtu", "map.hexex",   "report.json"};
  return names;
}

void check_pipeline_output_directory(const std::string& directory, const std::vector<std::string>& inputs, bool force) {
  namespace fs = std::filesystem;
  IO::internal::check_output_directory(directory);
  std::error_code ec;
  for (const std::string& name : pipeline_output_names()) {
    const fs::path p = fs::path(directory) / name;
    if (!fs::exists(p, ec)) continue;
    for (const std::string& input : inputs)
      if (fs::equivalent(p, input, ec)) throw std::runtime_error(p.string() + ": the output would overwrite an input file");
    // Checked now, not when the file is written after the computation: with
    // --force, the outputs before it would be replaced and the rest not.
    if (!fs::is_regular_file(p, ec))
      throw std::runtime_error(p.string() + ": is a directory or another non-file; an output cannot replace it (remove it, "
                                            "or choose another output directory)");
    if (!force) throw std::runtime_error(p.string() + ": the file exists; give --force to replace the outputs");
  }
}

void write_pipeline_outputs(const std::string& directory, const Pipeline_tet_mesh& mesh,
                            const Pipeline_frame_field& frames, const Pipeline_integer_grid_map* map) {
  std::error_code ec;
  std::filesystem::create_directories(directory, ec);
  if (ec) throw std::runtime_error(directory + ": cannot create the output directory: " + ec.message());
  const std::filesystem::path dir(directory);
  // With straightened curves, every file shows the moved vertices.
  std::optional<IO::Medit_mesh> moved;
  if (!frames.positions.empty()) {
    moved = mesh.mesh;
    // Unused vertices (no position: NaN, or past the end) stay where they are.
    for (std::size_t v = 0; v < std::min(moved->vertices.size(), frames.positions.size()); ++v)
      if (frames.positions[v].allFinite())
        for (int c = 0; c < 3; ++c) moved->vertices[v][std::size_t(c)] = frames.positions[v](c);
  }
  const IO::Medit_mesh& written = moved ? *moved : mesh.mesh;
  std::optional<std::vector<std::array<Eigen::Vector3d, 4>>> parameters;
  if (map) parameters = parameters_in_mesh_order(written, *map);
  write_frame_files(dir, written, *frames.frames, *frames.matchings, parameters ? &*parameters : nullptr);
  write_singularities_vtu((dir / "singularities.vtu").string(), written, frames.singular_edges, frames.graph);
  if (map) IO::write_hexex((dir / "map.hexex").string(), {map->map.positions, map->map.tets, map->map.parameters});
  else if (std::filesystem::is_regular_file(dir / "map.hexex", ec)) // a former run's: not a map of these frames
    std::filesystem::remove(dir / "map.hexex", ec);
}

std::string write_pipeline_report(const std::string& directory, const std::string& json) {
  const std::string path = (std::filesystem::path(directory) / "report.json").string();
  IO::internal::write_file_atomically(path, [&](std::FILE* f) {
    if (std::fwrite(json.data(), 1, json.size(), f) != json.size()) throw std::runtime_error(path + ": write failed");
  });
  return path;
}

std::string pipeline_summary_text(const Pipeline_tet_mesh& mesh, const Pipeline_metric& metric,
                                  const Pipeline_frame_field& frames, const Pipeline_report_context& context) {
  const Frame_field_statistics& st = frames.frames->statistics();
  const Face_angle_statistics& angles = frames.face_angles;
  const Singularity_graph& graph = frames.graph;
  std::string types;
  for (const auto& [name, n] : count_singular_edges_by_type(frames.singular_edges))
    if (n) types += (types.empty() ? "" : ", ") + name + ": " + std::to_string(n);
  const std::string hex = metric.scaled ? format_number(metric.hex_size, 10) + " (" + metric.hex_size_rule + ")"
                                        : std::string("the metric's unit length");
  char buf[4096];
  std::snprintf(buf, sizeof buf, "\n  %-32s %zu (%zu vertices)\n  %-32s %s\n  %-32s %s\n  %-32s %.0f\n", "tetrahedra",
                frames.frames->size(), mesh.mesh.vertices.size(), "metric", metric.name.c_str(), "hex size", hex.c_str(),
                "expected hexahedra", metric.expected_hexes);
  std::string text = buf;
  // What hexes of this size can cover of the curved boundary, and the size for 0.99.
  const double ceiling = frames.coverage_ceiling, factor = frames.hex_size_factor_for_coverage_99;
  if (std::isfinite(ceiling)) {
    std::snprintf(buf, sizeof buf, "  %-32s %.3f at this hex size; %s\n", "coverage ceiling (curvature)", ceiling,
                  ceiling >= 0.99 ? "0.99 within reach"
                  : std::isfinite(factor)
                      ? ("0.99 needs hexes " + format_number(factor, 2) + " times as large").c_str()
                      : "0.99 out of reach");
    text += buf;
  }
  if (context.thickness) {
    const Pipeline_thickness& t = *context.thickness;
    std::snprintf(buf, sizeof buf, "  %-32s %.1f%% of the boundary under one hex edge from the opposite side; %s\n",
                  "thin parts", 100 * t.fraction_below_hex_edge, t.tenth_text().c_str());
    text += buf;
  }
  // Sharp edges on curves of 1 or 2 edges are not features (Sharp_features_3): say how many.
  const std::string dropped = st.feature_edges_dropped == 0 ? ""
                              : "; " + std::to_string(st.feature_edges_dropped) +
                                    " sharp edges dropped (curves of 1 or 2 edges)";
  std::snprintf(buf, sizeof buf,
                "  %-32s %.6g (per unit weight %.3g)\n  %-32s mean %.3g, median %.3g\n  %-32s mean %.3g, max %.3g\n"
                "  %-32s %.3g\n  %-32s %zu edges, %zu corners (%.3g degrees), %zu tetrahedra follow them%s\n"
                "  %-32s %zu%s%s%s\n  %-32s %zu (%zu closed), nodes %zu (junctions %zu, boundary ends %zu, interior "
                "ends %zu)\n  %-32s %zu\n",
                "smoothness energy", st.smoothness_energy, st.smoothness_energy / st.total_face_weight,
                "face angle (deg)", angles.mean_deg, angles.median_deg, "boundary alignment error (deg)",
                st.boundary_error_mean_deg,
                st.boundary_error_max_deg, "max |F^T g F - I|", st.max_orthonormality_error, "sharp features",
                st.feature_edges, st.feature_corners, frames.frames->options().feature_angle_deg, st.feature_tets, dropped.c_str(),
                "singular edges", frames.singular_edges.size(), types.empty() ? "" : " (", types.c_str(),
                types.empty() ? "" : ")", "singular curves", graph.curves.size(), graph.closed_curves,
                graph.nodes.size(), graph.junctions, graph.boundary_ends, graph.interior_ends,
                "non-meshable singular edges", frames.non_meshable_edges);
  text += buf;
  std::size_t listed = 0;
  for (const Singular_edge& s : frames.singular_edges) {
    if (is_meshable(s.type) || listed == 5) continue;
    std::snprintf(buf, sizeof buf, "    %s edge %zu-%zu at (%.6g, %.6g, %.6g)\n", singularity_type_name(s.type),
                  s.vertices[0] + 1, s.vertices[1] + 1, s.midpoint(0), s.midpoint(1), s.midpoint(2));
    text += buf;
    ++listed;
  }
  if (frames.non_meshable_edges > listed) text += "    ... (all in report.json)\n";
  const std::string turns =
      graph.curve_turns.empty() ? "" : " (and " + std::to_string(graph.curve_turns.size()) + " curve turns)";
  std::snprintf(buf, sizeof buf, "  %-32s %zu%s\n", "non-meshable nodes", graph.non_meshable_nodes, turns.c_str());
  text += buf;
  listed = 0;
  for (const Singular_node& n : graph.nodes) {
    if (n.meshable || listed == 5) continue;
    std::snprintf(buf, sizeof buf, "    %s of %d singular edges %s at vertex %zu (%.6g, %.6g, %.6g)\n",
                  singular_node_kind_name(n.kind), n.degree, n.on_boundary ? "on the surface" : "inside", n.vertex + 1,
                  n.position(0), n.position(1), n.position(2));
    text += buf;
    ++listed;
  }
  if (graph.non_meshable_nodes > listed) text += "    ... (all in report.json)\n";
  for (std::size_t k = 0; k < graph.curve_turns.size() && k < 5; ++k) { // none on the models measured
    const Eigen::Vector3d& p = graph.curve_turn_positions[k];
    std::snprintf(buf, sizeof buf, "    curve turning from +1/4 to -1/4 at vertex %zu (%.6g, %.6g, %.6g)\n",
                  graph.curve_turns[k] + 1, p(0), p(1), p(2));
    text += buf;
  }
  if (graph.curve_turns.size() > 5) text += "    ... (all in report.json)\n";
  std::snprintf(buf, sizeof buf, "  %-32s %zu\n", "curves touching the surface", graph.surface_touches.size());
  text += buf;
  for (std::size_t k = 0; k < graph.surface_touches.size() && k < 5; ++k) {
    const Eigen::Vector3d& p = graph.surface_touch_positions[k];
    std::snprintf(buf, sizeof buf, "    at vertex %zu (%.6g, %.6g, %.6g)\n", graph.surface_touches[k] + 1, p(0), p(1), p(2));
    text += buf;
  }
  if (graph.surface_touches.size() > 5) text += "    ... (all in report.json)\n";
  std::snprintf(buf, sizeof buf, "  %-32s %zu\n", "short curves from junctions", graph.short_curves.size());
  text += buf;
  for (std::size_t k = 0; k < graph.short_curves.size() && k < 5; ++k) {
    const Singular_curve& c = graph.curves[graph.short_curves[k]];
    std::snprintf(buf, sizeof buf, "    %.3g hex edges long, vertex %zu to %zu\n", c.metric_length, c.vertices.front() + 1,
                  c.vertices.back() + 1);
    text += buf;
  }
  if (graph.short_curves.size() > 5) text += "    ... (all in report.json)\n";
  if (context.integer_grid_map) {
    const Integer_grid_map_report& m = *context.integer_grid_map;
    std::snprintf(buf, sizeof buf,
                  "  %-32s %zu inverted, %zu flat tetrahedra; parameter volume %.6g of %.6g due; fit error %.3g\n",
                  "integer-grid map", m.inverted_tets, m.flat_tets, m.parameter_volume, m.due_volume, m.fit_error);
    text += buf;
  }
  return text;
}

} // namespace CGAL_ext
