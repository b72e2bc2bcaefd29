// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_FRAME_FIELD_PIPELINE_REPORT_H
#define CGAL_EXT_FRAME_FIELD_PIPELINE_REPORT_H

// The report of the pipeline (report.json) as a JSON value. Header-only and
// the one part of the package that needs nlohmann-json (Debian
// nlohmann-json3-dev, CMake target nlohmann_json::nlohmann_json): the
// compiled library itself needs only CGAL, Eigen, Boost and TBB.

#include <CGAL_ext/Frame_field_pipeline.h>
#include <CGAL_ext/Frame_field_singularities_3.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <limits>
#include <optional>
#include <string>

namespace CGAL_ext {

namespace internal {

inline nlohmann::ordered_json point_json(const Eigen::Vector3d& p) { return {p(0), p(1), p(2)}; }

// The "singularities" object: counts, the non-meshable edges, the curves and
// the nodes. Vertex numbers are 1-based, as in mesh.mesh.
inline nlohmann::ordered_json pipeline_singularities_json(const Pipeline_frame_field& f) {
  const Singularity_graph& graph = f.graph;
  nlohmann::ordered_json by_type = nlohmann::ordered_json::object();
  for (const auto& [name, n] : count_singular_edges_by_type(f.singular_edges)) by_type[name] = n;
  nlohmann::ordered_json edges = nlohmann::ordered_json::array(), curves = nlohmann::ordered_json::array(),
                         nodes = nlohmann::ordered_json::array(), touches = nlohmann::ordered_json::array(),
                         turns = nlohmann::ordered_json::array();
  for (const Singular_edge& s : f.singular_edges)
    if (!is_meshable(s.type))
      edges.push_back({{"vertices", {s.vertices[0] + 1, s.vertices[1] + 1}},
                       {"midpoint", point_json(s.midpoint)},
                       {"type", singularity_type_name(s.type)},
                       {"turn_deg", s.turn_deg},
                       {"axis_angle_deg", s.axis_angle_deg},
                       {"edge_axis_angle_deg", s.edge_axis_angle_deg}});
  for (const Singular_curve& c : graph.curves)
    curves.push_back({{"edges", c.edges.size()},
                      {"length", c.length},
                      {"metric_length", c.metric_length},
                      {"closed", c.closed},
                      {"ends", {c.vertices.front() + 1, c.vertices.back() + 1}},
                      {"+1/4", c.plus_quarter_edges},
                      {"-1/4", c.minus_quarter_edges},
                      {"non_meshable", c.non_meshable_edges}});
  for (const Singular_node& n : graph.nodes)
    nodes.push_back({{"vertex", n.vertex + 1},
                     {"position", point_json(n.position)},
                     {"degree", n.degree},
                     {"kind", singular_node_kind_name(n.kind)},
                     {"meshable", n.meshable}});
  for (std::size_t k = 0; k < graph.surface_touches.size(); ++k)
    touches.push_back({{"vertex", graph.surface_touches[k] + 1}, {"position", point_json(graph.surface_touch_positions[k])}});
  nlohmann::ordered_json short_curves = nlohmann::ordered_json::array(); // 1-based, as singularities.vtu's `curve`
  for (std::size_t k : graph.short_curves) short_curves.push_back(k + 1);
  for (std::size_t k = 0; k < graph.curve_turns.size(); ++k)
    turns.push_back({{"vertex", graph.curve_turns[k] + 1}, {"position", point_json(graph.curve_turn_positions[k])}});
  return {{"edges", f.singular_edges.size()},
          {"edges_by_type", by_type},
          {"non_meshable_edges", f.non_meshable_edges},
          {"curves", graph.curves.size()},
          {"closed_curves", graph.closed_curves},
          {"nodes", graph.nodes.size()},
          {"junctions", graph.junctions},
          {"boundary_ends", graph.boundary_ends},
          {"interior_ends", graph.interior_ends},
          {"non_meshable_nodes", graph.non_meshable_nodes},
          {"curve_turns", graph.curve_turns.size()},
          {"surface_touches", graph.surface_touches.size()},
          {"short_curves", graph.short_curves.size()},
          {"non_meshable_edge_list", edges},
          {"curve_list", curves},
          {"node_list", nodes},
          {"curve_turn_list", turns},
          {"surface_touch_list", touches},
          {"short_curve_list", short_curves}};
}

// The "repair" object, or null if the repair was not run.
inline nlohmann::ordered_json pipeline_repair_json(const std::optional<Singularity_repair_report>& fix) {
  if (!fix) return nullptr;
  return {{"non_meshable_before", fix->non_meshable_before},
          {"non_meshable_after", fix->non_meshable_after},
          {"non_meshable_nodes_before", fix->non_meshable_nodes_before},
          {"non_meshable_nodes_after", fix->non_meshable_nodes_after},
          {"rounds", fix->rounds},
          {"batches", fix->batches},
          {"regions_tried", fix->regions_tried},
          {"regions_kept", fix->regions_kept},
          {"regions_from_restarts", fix->regions_from_restarts},
          {"regions_released", fix->regions_released},
          {"tets_released", fix->tets_released},
          {"tets_changed", fix->tets_changed},
          {"lbfgs_iterations", fix->lbfgs_iterations},
          {"lbfgs_tet_iterations", fix->lbfgs_tet_iterations},
          {"energy_before", fix->energy_before},
          {"energy_after", fix->energy_after}};
}

// The "straightening" object, or null if it was not run.
inline nlohmann::ordered_json pipeline_straightening_json(const Pipeline_frame_field& frames) {
  if (!frames.straightening) return nullptr;
  const Singular_curve_straightening_report& s = *frames.straightening;
  return {{"curve_vertices", s.curve_vertices},
          {"moved_vertices", s.moved_vertices},
          {"refused_moves", s.refused_moves},
          {"reverted_vertices", s.reverted_vertices},
          {"max_relative_displacement", s.max_relative_displacement},
          {"kept", !frames.positions.empty()},
          {"min_dihedral_before_deg", s.min_dihedral_before_deg},
          {"min_dihedral_with_moved_deg", s.min_dihedral_after_deg},
          {"flat_tets_before", s.flat_tets_before},
          {"flat_tets_with_moved", s.flat_tets_after},
          {"non_meshable_before", frames.non_meshable_edges_unstraightened},
          {"non_meshable_with_moved", frames.non_meshable_edges_straightened},
          {"non_meshable_after", frames.non_meshable_edges},
          {"non_meshable_nodes_before", frames.non_meshable_nodes_unstraightened},
          {"non_meshable_nodes_with_moved", frames.non_meshable_nodes_straightened},
          {"non_meshable_nodes_after", frames.graph.non_meshable_vertices()}};
}

// The "thickness" object (in hex edges), or null if it was not measured.
inline nlohmann::ordered_json pipeline_thickness_json(const std::optional<Pipeline_thickness>& t) {
  if (!t) return nullptr;
  return {{"facets", t->facets},
          {"cap_hex_edges", t->cap},
          {"fraction_below_one_hex_edge", t->fraction_below_hex_edge},
          {"thickness_at_10_percent_hex_edges", t->thickness_at_10_percent}};
}

// The "integer_grid_map" object.
inline nlohmann::ordered_json pipeline_integer_grid_map_json(const Integer_grid_map_report& m) {
  return {{"split_edges", m.split_edges},
          {"split_edges_rejected", m.split_edges_rejected},
          {"map_tets", m.map_tets},
          {"cut_faces_tree", m.cut_faces_tree},
          {"cut_faces", m.cut_faces},
          {"cut_vertices", m.cut_vertices},
          {"singular_edges", m.singular_edges},
          {"singular_edges_on_grid_lines", m.singular_edges_on_grid_lines},
          {"singular_edges_unconstrained", m.singular_edges_unconstrained},
          {"boundary_faces_constrained", m.boundary_faces_constrained},
          {"boundary_faces_free", m.boundary_faces_free},
          {"variables", m.solver.variables},
          {"equalities", m.solver.equalities},
          {"redundant_equalities", m.solver.redundant_equalities},
          {"free_variables", m.solver.free_variables},
          {"integer_variables", m.solver.integer_variables},
          {"free_integer_variables", m.solver.free_integer_variables},
          {"non_integral_eliminated", m.solver.non_integral_eliminated},
          {"solves", m.solver.solves},
          {"fit_error_relaxed", m.fit_error_relaxed},
          {"fit_error", m.fit_error},
          {"parameter_volume", m.parameter_volume},
          {"due_volume", m.due_volume},
          {"inverted_tets_rounded", m.inverted_tets_rounded},
          {"flat_tets_rounded", m.flat_tets_rounded},
          {"untangled", m.untangled},
          {"untangle_rounds", m.untangle_rounds},
          {"untangle_iterations", m.untangle_iterations},
          {"untangle_tets", m.untangle_tets},
          {"min_relative_det_rounded", m.min_relative_det_rounded},
          {"min_relative_det", m.min_relative_det},
          {"inverted_tets", m.inverted_tets},
          {"flat_tets", m.flat_tets},
          {"seconds_setup", m.seconds_setup},
          {"seconds_solve", m.seconds_solve},
          {"seconds_untangle", m.seconds_untangle}};
}

// The "hex_coverage_ceiling" object: numbers, null where not finite; the
// factor is left out when every hex size reaches 0.99 (it is +infinity).
inline nlohmann::ordered_json pipeline_coverage_ceiling_json(const Pipeline_frame_field& frames) {
  auto number = [](double x) { return std::isfinite(x) ? nlohmann::ordered_json(x) : nlohmann::ordered_json(nullptr); };
  nlohmann::ordered_json j = {{"coverage", number(frames.coverage_ceiling)}};
  if (frames.hex_size_factor_for_coverage_99 != std::numeric_limits<double>::infinity())
    j["hex_size_factor_for_0_99"] = number(frames.hex_size_factor_for_coverage_99);
  j["smooth_turning"] = number(frames.frames->statistics().boundary_smooth_turning);
  return j;
}

} // namespace internal

/// \ingroup PkgCGALExtPipeline
/// The report of `report.json` (keys in doc/cli.md, `generate`) as a JSON
/// value whose keys keep their documented order: input and metric, hex size,
/// expected hexes, counts, singular edges, curves and nodes, energies, face
/// angles, alignment, sharp features, coverage ceiling, thickness, repair,
/// straightening, integer-grid map (only if one was computed), iterations
/// and timings. Numbers are written by nlohmann-json, in
/// the shortest form that reads back as the same double; a number that is
/// not finite is `null`. Header-only: it needs nlohmann-json.
///
/// `pipeline_report_json()` gives it as the text that `metric-frames
/// generate` writes.
/// \param mesh the tet mesh (its vertex count is reported)
/// \param metric the metric field and its scaling
/// \param frames the frame field and its singularities
/// \param context the input, the stages' times and the thickness
/// \returns the report, a JSON object
inline nlohmann::ordered_json pipeline_report(const Pipeline_tet_mesh& mesh, const Pipeline_metric& metric,
                                              const Pipeline_frame_field& frames,
                                              const Pipeline_report_context& context) {
  const Frame_field_statistics& st = frames.frames->statistics();
  const Face_angle_statistics& angles = frames.face_angles;
  nlohmann::ordered_json stage_seconds = nlohmann::ordered_json::object();
  for (const auto& [name, s] : context.stage_seconds) stage_seconds[name] = s;
  nlohmann::ordered_json report = {
      {"input", context.input},
      {"metric", metric.name},
      {"hex_size", metric.scaled ? nlohmann::ordered_json(metric.hex_size) : nlohmann::ordered_json(nullptr)},
      {"hex_size_rule", metric.hex_size_rule},
      {"expected_hexes", metric.expected_hexes},
      {"tets", frames.frames->size()},
      {"vertices", mesh.mesh.vertices.size()},
      {"reoriented_tets", mesh.build.reoriented_tets},
      {"unused_vertices", mesh.build.unused_vertices},
      {"interior_faces", st.interior_faces},
      {"boundary_faces", st.boundary_faces},
      {"singular_edges", frames.singular_edges.size()},
      {"singularities", internal::pipeline_singularities_json(frames)},
      {"smoothness_energy", st.smoothness_energy},
      {"smoothness_energy_per_weight", st.smoothness_energy / st.total_face_weight},
      {"projected_energy", st.projected_energy},
      {"diffusion",
       {{"steps", st.diffusion_steps},
        {"length", frames.frames->options().diffusion_length},
        {"iterations", st.diffusion_iterations},
        {"energy", st.diffused_energy}}},
      {"face_angle_deg", {{"mean", angles.mean_deg}, {"median", angles.median_deg}, {"max", angles.max_deg}}},
      {"boundary_alignment_error_deg", {{"mean", st.boundary_error_mean_deg}, {"max", st.boundary_error_max_deg}}},
      {"g_orthonormality_max_error", st.max_orthonormality_error},
      {"hard_boundary_tets", {{"one_axis", st.hard_one_axis}, {"two_axes", st.hard_two_axes}}},
      {"sharp_features",
       {{"angle_deg", frames.frames->options().feature_angle_deg},
        {"edges", st.feature_edges},
        {"curve_vertices", st.feature_curve_vertices},
        {"corners", st.feature_corners},
        {"dropped_edges", st.feature_edges_dropped},
        {"tets", st.feature_tets}}},
      {"hex_coverage_ceiling", internal::pipeline_coverage_ceiling_json(frames)},
      {"thickness", internal::pipeline_thickness_json(context.thickness)},
      {"repair", internal::pipeline_repair_json(frames.repair)},
      {"straightening", internal::pipeline_straightening_json(frames)},
      {"max_transport_angle_deg", st.max_transport_angle * 180 / M_PI},
      {"linear_iterations", st.linear_iterations},
      {"linear_residual", st.linear_residual},
      {"refinement_iterations", st.refinement_iterations},
      {"stage_seconds", stage_seconds}};
  if (!context.integer_grid_map) return report;
  // The map's object after "straightening", only when a map was computed.
  nlohmann::ordered_json with_map;
  for (auto it = report.begin(); it != report.end(); ++it) {
    with_map[it.key()] = it.value();
    if (it.key() == "straightening")
      with_map["integer_grid_map"] = internal::pipeline_integer_grid_map_json(*context.integer_grid_map);
  }
  return with_map;
}

/// \ingroup PkgCGALExtPipeline
/// The text of `report.json`: `pipeline_report()` indented by two spaces,
/// ending with a newline. Bytes of the input's name or the metric's that are
/// not valid UTF-8 are written as U+FFFD (JSON text is UTF-8), never an error
/// at the end of a long run. Write it with `write_pipeline_report()`.
/// \param mesh the tet mesh (its vertex count is reported)
/// \param metric the metric field and its scaling
/// \param frames the frame field and its singularities
/// \param context the input, the stages' times and the thickness
/// \returns the JSON text
inline std::string pipeline_report_json(const Pipeline_tet_mesh& mesh, const Pipeline_metric& metric,
                                        const Pipeline_frame_field& frames, const Pipeline_report_context& context) {
  return pipeline_report(mesh, metric, frames, context)
             .dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) +
         "\n";
}

} // namespace CGAL_ext

#endif
