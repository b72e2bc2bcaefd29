// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_FRAME_FIELD_PIPELINE_H
#define CGAL_EXT_FRAME_FIELD_PIPELINE_H

// The whole pipeline of `metric-frames generate`, as library functions on the
// default types: a tet mesh (read, or meshed with Mesh_3), the metric scaled
// to the hex size, the frame field with its repair and singularities, and the
// output files. The CLI is a thin layer over these functions; a C++ program
// that calls them with the same arguments gets the same files, bit for bit.
// Compiled in the library (src/pipeline), so that users of these functions
// do not instantiate the frame field themselves.

#include <CGAL_ext/Frame_field_3.h>
#include <CGAL_ext/Frame_field_matchings_3.h>
#include <CGAL_ext/Frame_field_options.h>
#include <CGAL_ext/Frame_field_repair_3.h>
#include <CGAL_ext/Frame_field_singularities_3.h>
#include <CGAL_ext/Singular_curve_straightening_3.h>
#include <CGAL_ext/IO/Medit_mesh.h>
#include <CGAL_ext/Input_error.h>
#include <CGAL_ext/Integer_grid_map_3.h>
#include <CGAL_ext/Metric_field_3.h>
#include <CGAL_ext/Tet_mesh_triangulation_3.h>
#include <CGAL_ext/build_triangulation_from_tets.h>
#include <CGAL_ext/tetrahedralize.h>

#include <Eigen/Core>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace CGAL_ext {

/// \ingroup PkgCGALExtPipeline
/// The triangulation of the pipeline.
using Pipeline_triangulation_3 = Tet_mesh_triangulation_3<>;
/// \ingroup PkgCGALExtPipeline
/// The metric field of the pipeline.
using Pipeline_metric_field_3 = Metric_field_3<Pipeline_triangulation_3>;
/// \ingroup PkgCGALExtPipeline
/// The frame field of the pipeline.
using Pipeline_frame_field_3 = Frame_field_3<Pipeline_metric_field_3>;
/// \ingroup PkgCGALExtPipeline
/// The matchings of the pipeline's frame field.
using Pipeline_matchings_3 = Frame_field_matchings_3<Pipeline_frame_field_3>;

/// \ingroup PkgCGALExtPipeline
/// A stage report: the stage's name, its wall-clock seconds and a one-line
/// detail (counts, sizes). The CLI prints it as a `[stage]` line.
using Pipeline_stage_callback = std::function<void(const std::string& stage, double seconds, const std::string& detail)>;

/// \ingroup PkgCGALExtPipeline
/// The tet mesh of the pipeline: the Medit arrays and the triangulation built
/// from them. Not copyable: the triangulation's address is kept by the
/// metric field made from it.
struct Pipeline_tet_mesh {
  /// The mesh; its tetrahedra positively oriented, as the triangulation holds
  /// them (a negatively oriented tetrahedron of a `.mesh` file is re-oriented
  /// by swapping its vertices 3 and 4, and counted in `build`).
  IO::Medit_mesh mesh;
  /// The triangulation, with the mesh's vertex and tetrahedron indices.
  std::unique_ptr<Pipeline_triangulation_3> triangulation;
  /// What building the triangulation found (re-oriented tetrahedra, unused vertices).
  Tet_mesh_build_report build;
  /// `true` if the mesh was read from a `.mesh` file, `false` if Mesh_3 made it.
  bool from_file = false;
  /// The Mesh_3 size used (0 for a `.mesh` input).
  double mesh_size = 0;
};

/// \ingroup PkgCGALExtPipeline
/// The kinds of pipeline input, told by the name.
enum class Pipeline_input_kind {
  tet_mesh, ///< a Medit `.mesh` file
  surface,  ///< a closed surface: `.off`, `.obj`, `.stl` or `.ply` (any case)
  builtin,  ///< `builtin:NAME`, a shape of `tetrahedralize_builtin()`
  unknown   ///< none of these
};

/// \ingroup PkgCGALExtPipeline
/// The kind of `input`, from its `builtin:` prefix or its extension.
/// \param input a file name or `builtin:NAME`
/// \returns the kind; `unknown` for any other name
Pipeline_input_kind pipeline_input_kind(const std::string& input);

/// \ingroup PkgCGALExtPipeline
/// Reads or makes the tet mesh of `input` and builds its triangulation.
///
/// \param input a Medit `.mesh` file (used as it is), a closed surface
///   (`.off`, `.obj`, `.stl`, `.ply`, meshed with `tetrahedralize_surface()`),
///   or `builtin:NAME` (`tetrahedralize_builtin()`)
/// \param options the Mesh_3 options, for a surface or built-in input
/// \param stage if set, called after the stage `read mesh` or `Mesh_3`, and
///   after `build triangulation`
/// \returns the mesh and its triangulation
/// \throws Input_error for a file that cannot be read, a mesh that is not a
///   valid tet mesh (see `build_triangulation_from_tets()`), or one whose
///   extent does not fit double precision; std::invalid_argument for an input
///   of none of these kinds
Pipeline_tet_mesh load_tet_mesh(const std::string& input, const Tetrahedralize_options& options = {},
                                const Pipeline_stage_callback& stage = {});

/// \ingroup PkgCGALExtPipeline
/// The metric given to the pipeline, before it is scaled to the hex size.
/// At most one of `constant` and `per_vertex` is set; neither means the identity.
struct Pipeline_metric_input {
  /// A constant SPD tensor.
  std::optional<Eigen::Matrix3d> constant;
  /// One SPD tensor per mesh vertex, in the mesh's vertex order (from a `.sol`
  /// file, or from formulas evaluated at the vertices).
  std::optional<std::vector<Eigen::Matrix3d>> per_vertex;
  /// Where the tensors come from, for error messages: a file name, or an
  /// option such as `--metric-expr`.
  std::string source;
  /// How the report names the metric (`identity` if empty).
  std::string name;
  /// The hex edge length h: the metric is divided by h^2, so that unit
  /// length in the metric is one hex edge. Unset: a given metric is used as
  /// it is, and the identity is scaled to the mean edge length of a `.mesh`
  /// input or to the Mesh_3 size.
  std::optional<double> hex_size;
};

/// \ingroup PkgCGALExtPipeline
/// The metric field of the pipeline and how it was scaled.
struct Pipeline_metric {
  /// The metric field g / h^2, cache filled.
  std::unique_ptr<Pipeline_metric_field_3> field;
  /// How the report names the metric.
  std::string name = "identity";
  /// Whether the metric was divided by `hex_size`^2.
  bool scaled = false;
  /// The hex edge length h, if `scaled`.
  double hex_size = 1;
  /// How h was chosen (`--hex-size`, `mean edge length of the mesh`,
  /// `Mesh_3 size`, or `the metric's unit length`).
  std::string hex_size_rule;
  /// The expected number of hexahedra: the metric volume, the integral of sqrt(det g).
  double expected_hexes = 0;
};

/// \ingroup PkgCGALExtPipeline
/// How thin the domain is, in hex edges: `Domain_thickness_3` on the
/// pipeline's metric field, where a hex edge has length 1.
struct Pipeline_thickness {
  /// The largest thickness measured, in hex edges: rays stop there.
  double cap = 0;
  /// The share of the boundary (by metric area) less than one hex edge from
  /// the opposite side of the domain, which hexahedra of this size cannot fill.
  double fraction_below_hex_edge = 0;
  /// The thickness, in hex edges, under which lies 10% of the boundary (at
  /// most `cap`; `Domain_thickness_3::area_quantile()`): hexahedra that many
  /// times as large leave at most 10% of it thinner than one of their edges.
  double thickness_at_10_percent = 0;
  /// The number of boundary facets measured.
  std::size_t facets = 0;
  /// The 10% figure as the stage line and the summary write it.
  /// \returns "10% under T hex edges", or "90% at least C hex edges thick" when T reaches the cap C
  std::string tenth_text() const {
    return thickness_at_10_percent >= cap ? "90% at least " + format_number(cap, 3) + " hex edges thick"
                                          : "10% under " + format_number(thickness_at_10_percent, 3) + " hex edges";
  }
};

/// \ingroup PkgCGALExtPipeline
/// Measures how thin the domain of `metric` is, in hex edges
/// (`Domain_thickness_3` with a cap of 4 hex edges). In the metric's own
/// unit length if it is not scaled (`Pipeline_metric::scaled`).
/// \param metric the metric field
/// \param stage if set, called after the stage `thickness`
/// \returns the shares of the boundary
Pipeline_thickness measure_pipeline_thickness(const Pipeline_metric& metric, const Pipeline_stage_callback& stage = {});

/// \ingroup PkgCGALExtPipeline
/// Makes the metric field of the pipeline on `mesh`: the metric of `input`
/// divided by h^2, every scaled tensor checked.
///
/// \param mesh the tet mesh; it must outlive the result
/// \param input the metric, its source and the hex size
/// \param stage if set, called after the stage `metric`
/// \returns the field and its scaling
/// \throws Input_error naming the source and the vertex (1-based) of a tensor
///   that is not SPD once scaled, for a `per_vertex` of the wrong size, or
///   for an expected number of hexahedra that overflows double precision
/// \throws std::invalid_argument if `input` has both `constant` and
///   `per_vertex`, or if the hex size (given, or the mesh's mean edge length
///   or Mesh_3 size) is not positive and finite
Pipeline_metric make_pipeline_metric(const Pipeline_tet_mesh& mesh, const Pipeline_metric_input& input,
                                     const Pipeline_stage_callback& stage = {});

/// \ingroup PkgCGALExtPipeline
/// The frame field of the pipeline and what was found in it.
struct Pipeline_frame_field {
  /// The frame field (it keeps the metric field's address).
  std::unique_ptr<Pipeline_frame_field_3> frames;
  /// The repair, if it was run.
  std::optional<Singularity_repair_report> repair;
  /// The matchings across the interior faces.
  std::unique_ptr<Pipeline_matchings_3> matchings;
  /// The singular edges.
  std::vector<Singular_edge> singular_edges;
  /// Their curves and nodes.
  Singularity_graph graph;
  /// The angles between neighbouring frames.
  Face_angle_statistics face_angles;
  /// The number of non-meshable singular edges.
  std::size_t non_meshable_edges = 0;
  /// The straightening of the singular curves, if it was run.
  std::optional<Singular_curve_straightening_report> straightening;
  /// The non-meshable singular edges with the mesh's own positions (before
  /// the straightening).
  std::size_t non_meshable_edges_unstraightened = 0;
  /// The non-meshable singular edges with the moved positions (those
  /// written when any vertex moved).
  std::size_t non_meshable_edges_straightened = 0;
  /** @{ */
  /// The non-meshable nodes and curve turns
  /// (`Singularity_graph::non_meshable_vertices()`) with the mesh's own
  /// positions and with the moved ones (`graph` has those of the positions
  /// written).
  std::size_t non_meshable_nodes_unstraightened = 0, non_meshable_nodes_straightened = 0;
  /** @} */
  /// What hexahedra of the size asked for (edge 1 in the metric) can cover
  /// at best where the boundary is curved (`hex_coverage_ceiling()`, with the
  /// boundary measured in the metric and the creases of the feature angle:
  /// `Frame_field_statistics::boundary_smooth_turning`).
  double coverage_ceiling = 0;
  /// The largest hex edge, in units of the size asked for, whose ceiling
  /// reaches a coverage of 0.99 (`hex_edge_for_coverage()`); +infinity when
  /// every size does (a boundary flat or concave overall).
  double hex_size_factor_for_coverage_99 = 0;
  /// The positions of the vertices, by index, that the outputs use: the
  /// straightened ones (NaN at an index no tetrahedron uses), or empty for
  /// the mesh's own (no straightening, or none moved).
  std::vector<Eigen::Vector3d> positions;
};

/// \ingroup PkgCGALExtPipeline
/// The straightening's options for a mesh: the defaults, with the vertices
/// of its triangles and edges of a reference other than 0 (Medit `Triangles`
/// and `Edges`: inside, an interface; TetGen `-f` lists every face, interior
/// ones with 0) and those between tetrahedra of different references
/// (subdomains) fixed, so that the straightening moves no interface.
/// \param mesh the tet mesh
/// \returns the options `metric-frames generate` uses
Singular_curve_straightening_options pipeline_straightening_options(const Pipeline_tet_mesh& mesh);

/// \ingroup PkgCGALExtPipeline
/// Generates the frame field in `metric` (`Frame_field_3::compute()`),
/// repairs its non-meshable singular edges (`repair_singularities()`) if
/// `repair` is set, and finds its matchings, singular edges and their graph.
/// Then, if `straightening` is set, straightens the singular curves
/// (`straighten_singular_curves()`) and types their edges again with the
/// moved vertices; the moved positions are kept when any vertex moved (the
/// straightening's guard leaves no more non-meshable edges than the mesh's
/// own positions, nor as many and more non-meshable nodes).
///
/// \param metric the metric field; it must outlive the result
/// \param options the frame field's options; their `progress` reports the
///   frame field's stages
/// \param repair the repair's options, or none for no repair
/// \param stage if set, called after the stages `repair`, `singularities`
///   and `straightening`
/// \param straightening the straightening's options
///   (`pipeline_straightening_options()` for generate's), or none not to
///   straighten (the default)
/// \returns the frame field, its repair report, matchings and singularities
Pipeline_frame_field generate_pipeline_frame_field(
    const Pipeline_metric& metric, const Frame_field_options& options,
    const std::optional<Singularity_repair_options>& repair, const Pipeline_stage_callback& stage = {},
    const std::optional<Singular_curve_straightening_options>& straightening = std::nullopt);

/// \ingroup PkgCGALExtPipeline
/// The integer-grid map of the pipeline's field and what it was computed on.
struct Pipeline_integer_grid_map {
  /// The mesh and the field as the map took them
  /// (`pipeline_integer_grid_map_input()`).
  Integer_grid_map_input input;
  /// The map.
  Integer_grid_map map;
};

/// \ingroup PkgCGALExtPipeline
/// The map's input from the pipeline's field (`make_integer_grid_map_input()`)
/// with the positions the outputs use: the straightened ones where a vertex
/// moved, else the mesh's. The metric is already scaled to the hex size.
/// \param mesh the tet mesh
/// \param frames the frame field and its matchings
/// \returns the input of `compute_integer_grid_map()`
Integer_grid_map_input pipeline_integer_grid_map_input(const Pipeline_tet_mesh& mesh, const Pipeline_frame_field& frames);

/// \ingroup PkgCGALExtPipeline
/// Computes the integer-grid map of the pipeline's field
/// (`compute_integer_grid_map()` on `pipeline_integer_grid_map_input()`).
/// \param mesh the tet mesh
/// \param frames the frame field and its matchings
/// \param options the map's options
/// \param stage if set, called after the stage `integer-grid map`
/// \returns the map and its input
Pipeline_integer_grid_map compute_pipeline_integer_grid_map(const Pipeline_tet_mesh& mesh,
                                                            const Pipeline_frame_field& frames,
                                                            const Integer_grid_map_options& options = {},
                                                            const Pipeline_stage_callback& stage = {});

/// \ingroup PkgCGALExtPipeline
/// The names of the files that `write_pipeline_outputs()` and
/// `write_pipeline_report()` write into the output directory (`map.hexex`
/// only with an integer-grid map).
/// \returns the file names, `report.json` last
const std::vector<std::string>& pipeline_output_names();

/// \ingroup PkgCGALExtPipeline
/// Checks, before any computation, that the outputs can be written into
/// `directory`: it is a directory or can be created, a file can be made in
/// it, no output would replace one of `inputs`, no output's name is taken
/// by a directory or another non-file (even with `force`), and no output
/// exists unless `force` is set.
/// \param directory the output directory
/// \param inputs the input files, never to be overwritten
/// \param force whether existing output files may be replaced
/// \throws std::runtime_error naming the directory or file and the reason
void check_pipeline_output_directory(const std::string& directory, const std::vector<std::string>& inputs, bool force);

/// \ingroup PkgCGALExtPipeline
/// Writes `frames.fra`, `frames.perm`, `mesh.mesh`, `frames.vtu` and
/// `singularities.vtu` into `directory` (created if missing), each file
/// atomically (see `output_files.md`); with a map, also `map.hexex`
/// (`IO::write_hexex()`: the map's mesh, `mesh.mesh`'s with the split
/// edges' midpoints, and its parameters) and the cell array `parameters` of
/// `frames.vtu` (the map at each tetrahedron's corners,
/// `Integer_grid_map::input_parameters`); without a map, a `map.hexex`
/// already in `directory` (a former run's) is removed, so that the files
/// there are all of one run.
/// \param directory the output directory
/// \param mesh the tet mesh
/// \param frames the frame field and its singularities
/// \param map the integer-grid map, or null
/// \throws std::runtime_error if the directory cannot be created or a file cannot be written
void write_pipeline_outputs(const std::string& directory, const Pipeline_tet_mesh& mesh,
                            const Pipeline_frame_field& frames, const Pipeline_integer_grid_map* map = nullptr);

/// \ingroup PkgCGALExtPipeline
/// What the report names besides the results: the input, the options and the
/// stages' times.
struct Pipeline_report_context {
  /// The input, as given. (The options reported are those the field ran
  /// with, `Frame_field_3::options()`.)
  std::string input;
  /// Seconds per stage: its name and its time, in the order run (the
  /// report keeps that order).
  std::vector<std::pair<std::string, double>> stage_seconds;
  /// How thin the domain is, if it was measured (`measure_pipeline_thickness()`).
  std::optional<Pipeline_thickness> thickness;
  /// The integer-grid map's report, if a map was computed.
  std::optional<Integer_grid_map_report> integer_grid_map;
};

/// \ingroup PkgCGALExtPipeline
/// Writes `json` as `report.json` into `directory`, atomically.
/// \param directory the output directory
/// \param json the report's text, from `pipeline_report_json()` (Frame_field_pipeline_report.h)
/// \returns the file's path
/// \throws std::runtime_error if the file cannot be written
std::string write_pipeline_report(const std::string& directory, const std::string& json);

/// \ingroup PkgCGALExtPipeline
/// The summary of the run as the CLI prints it at the end: a few aligned
/// lines, and the first five non-meshable edges.
/// \param mesh the tet mesh
/// \param metric the metric field and its scaling
/// \param frames the frame field and its singularities
/// \param context the input, the stages' times and the thickness
/// \returns the text, starting with an empty line and ending with a newline
std::string pipeline_summary_text(const Pipeline_tet_mesh& mesh, const Pipeline_metric& metric,
                                  const Pipeline_frame_field& frames, const Pipeline_report_context& context);

} // namespace CGAL_ext

#endif
