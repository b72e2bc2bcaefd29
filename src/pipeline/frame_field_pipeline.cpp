// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The computing steps of the generate pipeline (Frame_field_pipeline.h): the
// tet mesh, the scaled metric, the frame field and its singularities. The
// one translation unit that instantiates the frame field on the default types.
#include <CGAL_ext/Frame_field_pipeline.h>
#include <CGAL_ext/Hex_coverage_ceiling_3.h>

#include <CGAL_ext/IO/Medit_mesh.h>
#include <CGAL_ext/IO/read_tet_mesh_file.h>
#include <CGAL_ext/Input_error.h>
#include <CGAL_ext/Metric_tensor.h>
#include <CGAL_ext/Tet_mesh_statistics_3.h>

#include <CGAL/Real_timer.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <utility>

namespace CGAL_ext {

namespace {

using Tr = Pipeline_triangulation_3;

bool has_extension(const std::string& path, std::initializer_list<const char*> exts) {
  std::string e = std::filesystem::path(path).extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  for (const char* x : exts)
    if (e == x) return true;
  return false;
}

// Calls `stage` (if set) with the seconds since the last call, and restarts the timer.
class Stage_clock {
public:
  explicit Stage_clock(const Pipeline_stage_callback& stage) : stage_(stage) { timer_.start(); }
  void operator()(const std::string& name, const std::string& detail) {
    const double s = timer_.time();
    timer_.reset();
    if (stage_) stage_(name, s, detail);
  }
  void restart() { timer_.reset(); }

private:
  const Pipeline_stage_callback& stage_;
  CGAL::Real_timer timer_;
};

// The tetrahedra of `mesh` as the triangulation holds them: a negatively
// oriented one with its vertices 3 and 4 swapped.
void orient_positively(IO::Medit_mesh& mesh) {
  const auto orientation = Tr::Geom_traits().orientation_3_object();
  for (auto& t : mesh.tetrahedra) {
    auto P = [&](int k) { return Tr::Point(mesh.vertices[t[k]][0], mesh.vertices[t[k]][1], mesh.vertices[t[k]][2]); };
    if (orientation(P(0), P(1), P(2), P(3)) == CGAL::NEGATIVE) std::swap(t[2], t[3]);
  }
}

// The vertex where sqrt(det g) = det A is largest, and that determinant as
// text, computed without overflow: for the error on an infinite metric volume.
std::pair<std::size_t, std::string> largest_metric_determinant(const Tr& tr, const Pipeline_metric_field_3& field) {
  std::size_t vertex = 0;
  double largest = -std::numeric_limits<double>::infinity(), det = 0;
  int exponent = 0;
  for (Tr::Vertex_handle v : tr.finite_vertex_handles()) {
    const Eigen::Matrix3d& A = field.sqrt_metric(v);
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
  return {vertex, internal::power_of_two_text(det, exponent)};
}

// The hex size h of the pipeline and its rule (see Pipeline_metric_input::hex_size).
void choose_hex_size(const Pipeline_tet_mesh& mesh, const Pipeline_metric_input& input, Pipeline_metric& m) {
  const bool has_metric = input.constant || input.per_vertex;
  if (input.hex_size) {
    m.scaled = true;
    m.hex_size = *input.hex_size;
    m.hex_size_rule = "--hex-size";
  } else if (!has_metric) {
    m.scaled = true;
    if (mesh.from_file) {
      m.hex_size = static_cast<double>(
          compute_tet_mesh_statistics(*mesh.triangulation, Is_tet_mesh_domain_cell()).mean_edge_length);
      m.hex_size_rule = "mean edge length of the mesh";
    } else {
      m.hex_size = mesh.mesh_size;
      m.hex_size_rule = "Mesh_3 size";
    }
  } else {
    m.hex_size_rule = "the metric's unit length";
  }
  if (!(m.hex_size > 0) || !std::isfinite(m.hex_size))
    throw std::invalid_argument("the hex size must be a positive finite number, not " + format_number(m.hex_size, 10));
}

} // namespace

Pipeline_input_kind pipeline_input_kind(const std::string& input) {
  if (input.rfind("builtin:", 0) == 0) return Pipeline_input_kind::builtin;
  if (has_extension(input, {".mesh", ".msh", ".vtk"})) return Pipeline_input_kind::tet_mesh;
  if (has_extension(input, {".off", ".obj", ".stl", ".ply"})) return Pipeline_input_kind::surface;
  return Pipeline_input_kind::unknown;
}

Pipeline_tet_mesh load_tet_mesh(const std::string& input, const Tetrahedralize_options& options,
                                const Pipeline_stage_callback& stage) {
  Stage_clock clock(stage);
  const Pipeline_input_kind kind = pipeline_input_kind(input);
  if (kind == Pipeline_input_kind::unknown)
    throw std::invalid_argument("'" + input + "': expected a tet mesh (.mesh .msh .vtk), a surface (.off .obj .stl .ply) or builtin:NAME");
  Pipeline_tet_mesh m;
  m.from_file = kind == Pipeline_input_kind::tet_mesh;
  if (m.from_file) {
    m.mesh = IO::read_tet_mesh_file(input);
    clock("read mesh", std::to_string(m.mesh.tetrahedra.size()) + " tets, " + std::to_string(m.mesh.vertices.size()) +
                           " vertices");
  } else {
    Tetrahedralize_report report;
    m.mesh = kind == Pipeline_input_kind::builtin ? tetrahedralize_builtin(input.substr(8), options, &report)
                        : tetrahedralize_surface(input, options, &report);
    m.mesh_size = report.size;
    clock("Mesh_3", std::to_string(report.tets) + " tets, " + std::to_string(report.vertices) + " vertices (" +
                        report.domain + ")");
  }
  m.triangulation = std::make_unique<Tr>();
  Tet_soup_source src;
  src.file = m.from_file ? input : std::string("generated mesh");
  src.tet_lines = m.mesh.tetrahedron_lines;
  src.vertex_lines = m.mesh.vertex_lines;
  m.build = build_triangulation_from_tets(m.mesh.vertices, m.mesh.tetrahedra, m.mesh.tetrahedron_references,
                                          *m.triangulation, src);
  if (m.build.reoriented_tets) orient_positively(m.mesh);
  clock("build triangulation", std::to_string(m.build.boundary_facets) + " boundary facets");
  // A mesh too large or too small for double is refused here, before the
  // hex size and the metric are derived from its lengths.
  Pipeline_metric_field_3::check_extent(*m.triangulation, input);
  return m;
}

Pipeline_metric make_pipeline_metric(const Pipeline_tet_mesh& mesh, const Pipeline_metric_input& input,
                                     const Pipeline_stage_callback& stage) {
  Stage_clock clock(stage);
  if (input.constant && input.per_vertex)
    throw std::invalid_argument("a pipeline metric is constant or per vertex, not both");
  Pipeline_metric m;
  if (!input.name.empty()) m.name = input.name;
  choose_hex_size(mesh, input, m);
  const double scale = 1 / (m.hex_size * m.hex_size);
  const std::string scaled_text = "the metric scaled to the hex size (g / h^2, h = " + format_number(m.hex_size, 10) + ")";
  const Tr& tr = *mesh.triangulation;
  if (input.per_vertex) {
    std::vector<Eigen::Matrix3d> g = *input.per_vertex;
    if (g.size() != mesh.mesh.vertices.size())
      throw Input_error(input.source, 0, "", std::to_string(g.size()) + " tensors for " +
                                                 std::to_string(mesh.mesh.vertices.size()) + " mesh vertices");
    // Each tensor checked again: a valid g can overflow once scaled.
    for (std::size_t i = 0; i < g.size(); ++i) {
      g[i] *= scale;
      const std::string problem = check_metric_tensor(g[i]);
      if (!problem.empty()) throw Input_error(input.source, 0, "vertex " + std::to_string(i + 1), scaled_text + ": " + problem);
    }
    m.field = std::make_unique<Pipeline_metric_field_3>(tr, g, input.source);
  } else {
    const Eigen::Matrix3d g = input.constant.value_or(Eigen::Matrix3d::Identity()) * scale;
    const std::string problem = check_metric_tensor(g);
    if (!problem.empty()) throw Input_error(input.source, 0, scaled_text, problem);
    m.field = std::make_unique<Pipeline_metric_field_3>(tr, g);
  }
  m.field->precompute();
  m.expected_hexes = m.field->metric_volume();
  if (!std::isfinite(m.expected_hexes)) {
    const auto [vertex, det] = largest_metric_determinant(tr, *m.field);
    throw Input_error(input.source, 0, "vertex " + std::to_string(vertex + 1),
                      "sqrt(det g) = " + det +
                          (m.scaled ? " (g scaled to the hex size h = " + format_number(m.hex_size, 10) + ")" : std::string()) +
                          ": the expected number of hexahedra, int sqrt(det g) dV, overflows double precision; give a "
                          "smaller metric or a larger --hex-size");
  }
  clock("metric", m.name + (m.scaled ? "; hex size " + format_number(m.hex_size, 10) + " (" + m.hex_size_rule + ")" : std::string()) +
                      "; about " + format_number(std::round(m.expected_hexes), 10) + " hexahedra");
  return m;
}

Singular_curve_straightening_options pipeline_straightening_options(const Pipeline_tet_mesh& mesh) {
  const IO::Medit_mesh& m = mesh.mesh;
  Singular_curve_straightening_options options;
  options.fixed_vertices.assign(m.vertices.size(), 0);
  // Triangles and edges with a reference other than 0 (boundary vertices
  // stay anyway; TetGen -f lists every interior face, with 0), and the
  // vertices whose tetrahedra carry more than one reference.
  for (std::size_t i = 0; i < m.triangles.size(); ++i)
    if (i >= m.triangle_references.size() || m.triangle_references[i] != 0)
      for (std::size_t v : m.triangles[i]) options.fixed_vertices.at(v) = 1;
  for (std::size_t i = 0; i < m.edges.size(); ++i)
    if (i >= m.edge_references.size() || m.edge_references[i] != 0)
      for (std::size_t v : m.edges[i]) options.fixed_vertices.at(v) = 1;
  if (m.tetrahedron_references.size() == m.tetrahedra.size()) {
    std::vector<int> reference(m.vertices.size());
    std::vector<char> seen(m.vertices.size(), 0);
    for (std::size_t t = 0; t < m.tetrahedra.size(); ++t)
      for (std::size_t v : m.tetrahedra[t]) {
        if (!seen[v]) seen[v] = 1, reference[v] = m.tetrahedron_references[t];
        else if (reference[v] != m.tetrahedron_references[t]) options.fixed_vertices[v] = 1;
      }
  }
  return options;
}

Pipeline_frame_field generate_pipeline_frame_field(const Pipeline_metric& metric, const Frame_field_options& options,
                                                   const std::optional<Singularity_repair_options>& repair,
                                                   const Pipeline_stage_callback& stage,
                                                   const std::optional<Singular_curve_straightening_options>& straightening) {
  Pipeline_frame_field r;
  r.frames = std::make_unique<Pipeline_frame_field_3>(*metric.field);
  Pipeline_frame_field_3& ff = *r.frames;
  ff.compute(options); // it reports its own stages
  const double turning = ff.statistics().boundary_smooth_turning; // hexes of edge 1 in the metric
  r.coverage_ceiling = hex_coverage_ceiling(turning, metric.expected_hexes, 1);
  r.hex_size_factor_for_coverage_99 = hex_edge_for_coverage(turning, metric.expected_hexes, 0.99);
  Stage_clock clock(stage);
  if (repair) {
    r.repair = repair_singularities(ff, *repair);
    const Singularity_repair_report& fix = *r.repair;
    clock("repair", std::to_string(fix.non_meshable_before) + " -> " + std::to_string(fix.non_meshable_after) +
                        " non-meshable edges, " + std::to_string(fix.non_meshable_nodes_before) + " -> " +
                        std::to_string(fix.non_meshable_nodes_after) + " nodes; " + std::to_string(fix.regions_kept) + " of " +
                        std::to_string(fix.regions_tried) + " regions kept (" +
                        std::to_string(fix.regions_from_restarts) + " from restarts, " +
                        std::to_string(fix.regions_released) + " with hard constraints released), energy " +
                        format_number(fix.energy_before, 10) + " -> " + format_number(fix.energy_after, 10));
  }
  r.matchings = std::make_unique<Pipeline_matchings_3>(ff);
  r.singular_edges = singular_edges(ff, *r.matchings);
  r.face_angles = r.matchings->face_angle_statistics(ff);
  auto non_meshable = [](const std::vector<Singular_edge>& edges) {
    return std::size_t(std::count_if(edges.begin(), edges.end(), [](const Singular_edge& s) { return !is_meshable(s.type); }));
  };
  r.non_meshable_edges = r.non_meshable_edges_unstraightened = non_meshable(r.singular_edges);
  r.graph = singularity_graph(ff, r.singular_edges);
  r.non_meshable_nodes_unstraightened = r.non_meshable_nodes_straightened = r.graph.non_meshable_vertices();
  clock("singularities", std::to_string(r.singular_edges.size()) + " singular edges in " +
                             std::to_string(r.graph.curves.size()) + " curves, " + std::to_string(r.graph.nodes.size()) +
                             " nodes; " + std::to_string(r.non_meshable_edges) + " non-meshable edges, " +
                             std::to_string(r.graph.non_meshable_nodes) + " non-meshable nodes, " +
                             (r.graph.curve_turns.empty() ? std::string()
                                                          : std::to_string(r.graph.curve_turns.size()) + " curve turns, ") +
                             std::to_string(r.graph.surface_touches.size()) + " surface touches, " +
                             std::to_string(r.graph.short_curves.size()) + " short curves from junctions");
  if (straightening) {
    Singular_curve_straightening_report report;
    std::vector<Eigen::Vector3d> moved =
        straighten_singular_curves(ff, *r.matchings, r.singular_edges, *straightening, &report);
    std::vector<Singular_edge> edges = singular_edges(ff, *r.matchings, nullptr, &moved);
    const std::size_t bad = non_meshable(edges);
    Singularity_graph graph = singularity_graph(ff, edges, &moved);
    const std::size_t bad_nodes_before = r.graph.non_meshable_vertices(), bad_nodes = graph.non_meshable_vertices();
    r.non_meshable_nodes_straightened = bad_nodes;
    // The straightening's guard leaves no more non-meshable edges, nor as many and more nodes.
    const bool keep = report.moved_vertices > 0;
    r.non_meshable_edges_straightened = bad;
    if (keep) {
      r.positions = std::move(moved);
      r.singular_edges = std::move(edges);
      r.non_meshable_edges = bad;
      r.graph = std::move(graph);
    }
    r.straightening = report;
    char moves[200];
    std::snprintf(moves, sizeof moves,
                  "%zu of %zu curve vertices moved (at most %.3g of their edges' length; %zu put back); ",
                  report.moved_vertices, report.curve_vertices, report.max_relative_displacement,
                  report.reverted_vertices);
    const std::string before = std::to_string(r.non_meshable_edges_unstraightened) + " non-meshable edges and " +
                               std::to_string(bad_nodes_before) + " nodes",
                      after = std::to_string(bad) + " and " + std::to_string(bad_nodes);
    char shape[200];
    std::snprintf(shape, sizeof shape, "; smallest dihedral angle %.3g -> %.3g deg, tets below %g deg %zu -> %zu",
                  report.min_dihedral_before_deg, report.min_dihedral_after_deg, straightening_flat_angle_deg,
                  report.flat_tets_before, report.flat_tets_after);
    const std::string detail = moves + (keep ? before + " -> " + after + shape : "nothing changed");
    clock("straightening", detail);
  }
  return r;
}

} // namespace CGAL_ext
