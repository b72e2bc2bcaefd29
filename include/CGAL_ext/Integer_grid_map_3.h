// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_INTEGER_GRID_MAP_3_H
#define CGAL_EXT_INTEGER_GRID_MAP_3_H

/// \file Integer_grid_map_3.h
/// The integer-grid map of a frame field: per tetrahedron corner, parameters
/// `u` in R^3 whose gradients fit the field's parameter gradients, seamless
/// across the faces (a matching's rotation plus an integer translation),
/// with the singular curves on integer grid lines and the boundary on
/// integer planes. Its integer grid is the hex mesh (doc/hex_meshing.md).

#include <CGAL_ext/Mixed_integer_quadratic_solver.h>

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace CGAL_ext {

/// \ingroup PkgCGALExtHex
/// A tet mesh with a frame field, as the map needs it: plain indexed arrays.
/// `make_integer_grid_map_input()` fills it from a `Frame_field_3`, and
/// `pipeline_integer_grid_map_input()` from the pipeline's field.
struct Integer_grid_map_input {
  /// The vertex positions.
  std::vector<Eigen::Vector3d> positions;
  /// The tetrahedra's vertex indices (0-based), positively oriented.
  std::vector<std::array<std::size_t, 4>> tets;
  /// `neighbors[t][f]`: the tetrahedron across the facet opposite
  /// `tets[t][f]`, or -1 on the boundary.
  std::vector<std::array<std::int64_t, 4>> neighbors;
  /// `matchings[t][f]`: the index in `octahedral_group()` of the matching `G`
  /// across that facet (`Frame_field_matchings_3::index()`: vector `k` of `t`
  /// continues as `G e_k` of the neighbour, so the neighbour's parameters
  /// are `G u + t` with `t` integer), or -1 on the boundary. The two sides of
  /// a face hold inverse elements.
  std::vector<std::array<int, 4>> matchings;
  /// `gradients[t]`: column `k` is the gradient that `u_k` should have in
  /// tetrahedron `t` (`Frame_field_3::parameter_gradients()`, `A R`, the
  /// vectors of `frames.fra`); unit length in the metric is one grid step.
  std::vector<Eigen::Matrix3d> gradients;
  /// Optional (empty, or one per tetrahedron): `true` for a tetrahedron whose
  /// boundary faces are not put on integer planes (those whose hard
  /// constraint the repair released: their frames are not aligned).
  std::vector<bool> free_boundary;
};

/// \ingroup PkgCGALExtHex
/// The map's options.
struct Integer_grid_map_options {
  /// Whether to quantize: `false` gives the seamless map before rounding
  /// (translations and constrained coordinates real), for inspection.
  bool quantize = true;
  /// Whether the untangling may split edges of the tetrahedra that the
  /// rounded map makes flat (see `compute_integer_grid_map()`).
  bool split_edges = true;
  /// The rounding of the integer variables.
  Mixed_integer_quadratic_options rounding;
  /// Whether to untangle a map with inverted or flat tetrahedra after the
  /// rounding (the integers and the seams held).
  bool untangle = true;
  /** @{ */
  /// The untangling's rounds of its barrier (each lowers its
  /// regularisation), and L-BFGS iterations per round.
  int untangle_rounds = 40, untangle_iterations = 300;
  /** @} */
};

/// \ingroup PkgCGALExtHex
/// What the map found and how good it is.
struct Integer_grid_map_report {
  /** @{ */
  /// The tetrahedra of the input, the edges split, and the tetrahedra of
  /// the map (each split edge splits the tetrahedra around it in two).
  std::size_t tets = 0, split_edges = 0, map_tets = 0;
  /** @} */
  /// The edges split for an untangling that was not kept.
  std::size_t split_edges_rejected = 0;
  /** @{ */
  /// The interior faces cut by the dual spanning tree, and those still cut
  /// after gluing back every face a regular interior edge determines: the
  /// faces that carry transition functions.
  std::size_t cut_faces_tree = 0, cut_faces = 0;
  /** @} */
  /// The vertices of the cut mesh (corners joined across uncut faces): the
  /// map's unknown points.
  std::size_t cut_vertices = 0;
  /** @{ */
  /// The interior edges whose holonomy is not the identity, those among them
  /// put on an integer grid line (a rotation about a coordinate axis), and
  /// the others (a rotation about no axis of the frame: non-meshable edges),
  /// which no constraint can put on a grid line.
  std::size_t singular_edges = 0, singular_edges_on_grid_lines = 0, singular_edges_unconstrained = 0;
  /** @} */
  /** @{ */
  /// The boundary faces put on integer planes, and those left free
  /// (`Integer_grid_map_input::free_boundary`).
  std::size_t boundary_faces_constrained = 0, boundary_faces_free = 0;
  /** @} */
  /// The solver's report (variables, equalities, integer variables, solves).
  Mixed_integer_quadratic_report solver;
  /** @{ */
  /// The fitting error `sum_t vol_t |grad u - G_t|^2 / sum_t vol_t |G_t|^2`
  /// of the seamless map before rounding and of the map returned.
  double fit_error_relaxed = 0, fit_error = 0;
  /** @} */
  /** @{ */
  /// The parameter volume (the sum of the tetrahedra's signed volumes in
  /// parameter space), and the volume due, `sum_t vol_t det(G_t)`, which is
  /// `V / h^3` for hexes of edge `h` in a constant metric: about the number
  /// of hexahedra.
  double parameter_volume = 0, due_volume = 0;
  /** @} */
  /// The tetrahedra with a negative parameter volume.
  std::size_t inverted_tets = 0;
  /// The tetrahedra with a parameter volume in `[0, 1e-3]` times its due
  /// (`vol_t det(G_t)`): flat in parameter space.
  std::size_t flat_tets = 0;
  /** @{ */
  /// The same counts after the rounding, before the untangling.
  std::size_t inverted_tets_rounded = 0, flat_tets_rounded = 0;
  /** @} */
  /// Whether the untangled map was kept: the untangling runs when the
  /// rounded map has inverted or flat tetrahedra, and its result is kept
  /// only if it has fewer of them.
  bool untangled = false;
  /** @{ */
  /// The untangling's rounds and L-BFGS iterations (kept or not).
  int untangle_rounds = 0, untangle_iterations = 0;
  /** @} */
  /// The tetrahedra the untangling moved (kept or not): those within three
  /// vertex rings of an inverted or flat one.
  std::size_t untangle_tets = 0;
  /** @{ */
  /// The least `det(J G^-T)` (the parameter Jacobian against the target's)
  /// over the tetrahedra the untangling moved, before and after it:
  /// positive when every one of them is.
  double min_relative_det_rounded = 0, min_relative_det = 0;
  /** @} */
  /** @{ */
  /// Seconds: the cut and the constraints, the solve and the rounding, the untangling.
  double seconds_setup = 0, seconds_solve = 0, seconds_untangle = 0;
  /** @} */
};

/// \ingroup PkgCGALExtHex
/// An integer-grid map, on the input's mesh with some edges split.
struct Integer_grid_map {
  /// The vertices of the map's mesh: the input's, then the midpoints of the
  /// split edges.
  std::vector<Eigen::Vector3d> positions;
  /// The map's tetrahedra (positively oriented): the input's, those around
  /// a split edge halved (the half at the edge's first vertex keeps the
  /// input's index, the other is appended).
  std::vector<std::array<std::size_t, 4>> tets;
  /// `parent[t]`: the input tetrahedron that map tetrahedron `t` is part of.
  std::vector<std::size_t> parent;
  /// `parameters[t][c]`: the parameters of corner `c` (vertex `tets[t][c]`)
  /// of map tetrahedron `t`, in its chart (its parent's frame vectors'
  /// order and signs after the combing along the spanning tree).
  std::vector<std::array<Eigen::Vector3d, 4>> parameters;
  /// `input_parameters[t][c]`: the parameters of corner `c` of input
  /// tetrahedron `t` (vertex `input.tets[t][c]`), in its chart: the map at
  /// the input's vertices, e.g. to show it on the input mesh.
  std::vector<std::array<Eigen::Vector3d, 4>> input_parameters;
  /// `chart[t]`: the index in `octahedral_group()` of the rotation `C` from
  /// the field's chart of map tetrahedron `t` (its parent's) to the map's:
  /// the gradients the map fits are the rows of `C G_t^T`.
  std::vector<int> chart;
  /// The report.
  Integer_grid_map_report report;
};

/// \ingroup PkgCGALExtHex
/// Computes the integer-grid map of a frame field.
///
/// 1. **Cut.** The frames are combed along a dual spanning tree (breadth
///    first from the lowest tetrahedron of each component), so that the
///    matchings across its faces are the identity. The other interior faces
///    are cut, then glued back wherever a regular interior edge (holonomy the
///    identity) has a single cut face around it, until none has (CubeCover's
///    reduction): what stays cut are the surfaces that end on the singular
///    curves and those that cut the domain's loops.
/// 2. **Unknowns.** Three parameters per vertex of the cut mesh (the corners
///    of a vertex joined across uncut faces) and an integer translation per
///    cut face.
/// 3. **Equalities.** Across each cut face, the neighbour's parameters are
///    `G u + t` at the face's three vertices. On a boundary face, the
///    coordinate along the axis nearest its normal (in parameter space) is
///    the same integer at its three vertices: the face is on an integer
///    plane, and where faces of different axes meet (creases, corners) the
///    vertices are on grid lines and points. At both vertices of a singular
///    edge whose holonomy is a rotation about a frame axis, the two
///    coordinates across that axis are integers: the edge is on a grid line,
///    and so are the curves it makes; their nodes, where curves of different
///    axes meet, on grid points.
/// 4. **Fit and quantization.** The parameters minimise
///    `sum_t vol_t |grad u - G_t|^2` under the equalities, the integer
///    variables rounded greedily with re-solves, cheapest first (the rise
///    of the fit's energy, `solve_mixed_integer_quadratic()`). One
///    coordinate per axis and component is pinned at 0: one that must be an
///    integer anyway where there is one, so that the pin biases nothing.
/// 5. **Untangling.** If tetrahedra are inverted or flat, the real unknowns
///    (the equalities and the rounded integers held) minimise the
///    foldover-free energy of Garanzha et al. 2021 on `K = J G^-T` (the
///    map's Jacobian against the target's), shape `tr(K^T K) / chi^(2/3)`
///    and volume `(det^2 + 1) / chi` in equal parts, `chi` the regularised
///    determinant whose regularisation goes to 0 over the rounds; only the
///    points within three vertex rings of an inverted or flat tetrahedron
///    move. Where the integers hold all four vertices of a tetrahedron on one
///    integer plane (its vertices all on one boundary sheet) or three on one
///    grid line (three vertices of a singular curve, or of a crease), no
///    unknown of the map can lift it. So before the untangling, each such
///    flat tetrahedron has an interior edge split that is not singular, has
///    no cut face around it, and whose midpoint, moved off that plane or
///    line, can leave both halves positive: the tetrahedra around it are
///    halved (keeping their parent's gradients and chart), and the midpoint
///    is a new free point, started at the middle of the edge's parameters.
///    The untangled map, on that mesh, is kept if it has fewer inverted
///    tetrahedra, or as many and fewer flat ones; the rounded map otherwise.
///
/// The result is a map HexEx reads (`IO::write_hexex()`).
///
/// \param input the mesh and the field
/// \param options whether to quantize, and how
/// \returns the parameters per corner and the report
/// \throws std::invalid_argument for arrays of the wrong sizes, indices out
///   of range, neighbours or matchings that do not agree across a face,
///   gradients that are not finite or not positively oriented, or a
///   tetrahedron that is flat or negatively oriented
/// \throws std::runtime_error if the fit's system is not positive definite
///   (`solve_mixed_integer_quadratic()`)
Integer_grid_map compute_integer_grid_map(const Integer_grid_map_input& input,
                                          const Integer_grid_map_options& options = {});

} // namespace CGAL_ext

#endif // CGAL_EXT_INTEGER_GRID_MAP_3_H
