// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_FRAME_FIELD_OPTIONS_H
#define CGAL_EXT_FRAME_FIELD_OPTIONS_H

/// \file Frame_field_options.h
/// The plain data of `Frame_field_3`: the options of `compute()`, the
/// statistics it returns, the boundary faces, and the options of
/// `repair_singularities()`.

#include <CGAL_ext/Cell_transport_3.h>

#include <Eigen/Core>

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace CGAL_ext {

/// \ingroup PkgCGALExtFrames
/// Options of `Frame_field_3::compute()`.
struct Frame_field_options {
  /// Weight `lambda` of the soft boundary-alignment term relative to the
  /// smoothness term (see `Frame_field_3`). Used by the linear
  /// initialisation, and in the refinement for the boundary faces that are
  /// not hard constraints.
  double boundary_weight = 100;
  /// Whether boundary tetrahedra are constrained exactly after the
  /// projection (their frame keeps an axis on `A^{-1} n`; see `Frame_field_3`).
  bool hard_boundary = true;
  /// The feature angle in degrees (`Sharp_features_3`): boundary edges whose
  /// facets' normals differ by more than this, in the metric, are feature
  /// edges. With `hard_boundary`, the tetrahedra at a feature edge keep an
  /// axis on its smooth tangent, and those at a corner the corner's frame.
  /// 40 degrees keeps 45-degree chamfers; on Mesh_3's smooth models at the
  /// default size the few facets more than 40 degrees apart form lone kinks,
  /// which are dropped (doc/sharp_features.md). 180 turns feature detection
  /// off (except where parts of the domain meet along an edge).
  double feature_angle_deg = 40;
  /// With `hard_boundary`: a crease (a feature edge between two boundary
  /// facets) whose faces' frames differ, about its tangent, by at least this
  /// many degrees modulo a quarter turn (folded into [0, 45]: 30 covers
  /// creases of 30 to 60 degrees modulo 90, such as 45-degree chamfers) is
  /// shared alike by all the tetrahedra along it: each takes the frame
  /// midway between the faces' frames, even with its own boundary faces on
  /// one side only (the faces are then off by half the difference). Below
  /// it, such a tetrahedron follows its own face exactly. Why: on a
  /// 45-degree chamfer the two faces' frames differ by 45 degrees, so the
  /// matching between a tetrahedron that follows one face and a neighbour
  /// that follows the other is a near tie between turning +45 and -45
  /// degrees; where the choice flips along the crease, a singular curve runs
  /// across its own axis (CGAL's anchor: 12 non-meshable edges after the
  /// repair instead of 7; doc/benchmarks.md, "Creases shared alike"). Above
  /// 45: never.
  double crease_split_deg = 30;
  /// Diffusion-projection (MBO) steps between the projection and the
  /// refinement: each replaces the SH vectors by one implicit heat step of
  /// the linear initialisation's energy, of length `diffusion_length`, and
  /// projects them again, so that the refinement starts from a field smoothed
  /// over that length. Each step's system is solved to 10 times
  /// `linear_tolerance` (the projection that follows needs no more), from
  /// the initialisation's coarse level and then on the tetrahedra. They run
  /// only on domains without feature edges, unless `diffusion_with_features`.
  /// Off by default: with hexes of the diagonal / 15 they lowered the energy
  /// of the built-in ball by 13-15% and of blobby by 6%, but raised the torus'
  /// by 1% and made one of its fields unmeshable, and on CAD parts they left
  /// more non-meshable edges (doc/benchmarks.md, "Diffusion at the hex
  /// scale"). 0: none.
  int diffusion_steps = 0;
  /// The length `sqrt(tau)` of each diffusion step, in the metric's unit
  /// length: hex edges, as `metric-frames generate` scales the metric. A
  /// length far above the hex size (a metric of the model's units, say)
  /// smooths towards the initialisation's solution, which the steps then
  /// merely approximate.
  double diffusion_length = 2;
  /// Whether the diffusion steps run on domains with feature edges too.
  bool diffusion_with_features = false;
  /// Tolerance in radians of each face transport `T(i->j)`.
  double transport_tolerance = 1e-6;
  /// The transport scheme.
  Transport_scheme transport_scheme = Transport_scheme::magnus;
  /// Relative residual at which the conjugate gradients of the linear
  /// initialisation stop (the coarse level, if any, is solved to 1/100 of
  /// it). The smooth part of the solution comes from the coarse level, so a
  /// loose fine tolerance suffices: on fandisk (10^5 tets) the final energy
  /// was within 0.4% of the one reached with 1e-6.
  double linear_tolerance = 1e-4;
  /// The largest number of conjugate-gradient iterations.
  int max_linear_iterations = 5000;
  /// The initialisation first solves a coarse problem on aggregates of about
  /// this many neighbouring tetrahedra, whose solution starts the fine
  /// iteration (fewer fine iterations on large meshes). 0 or 1: no coarse level.
  int aggregate_size = 24;
  /// The refinement stops when an iteration lowers the energy by less than
  /// `energy_tolerance` times the energy, three times in a row, or when the
  /// energy is below `1e-14` times the total face weight.
  double energy_tolerance = 1e-5;
  /// The largest number of L-BFGS iterations (0 skips the refinement).
  int max_refinement_iterations = 1000;
  /// The number of (step, gradient change) pairs kept by L-BFGS.
  int lbfgs_memory = 8;
  /// If set, called at the end of each stage with its name, its duration in
  /// seconds and a short detail line (for progress output).
  std::function<void(const std::string& stage, double seconds, const std::string& detail)> progress;
  /// If set, called after each iteration of the two iterative stages with the
  /// stage name, the iteration number and its measure (the relative residual
  /// of the conjugate gradients; the objective of L-BFGS, which is the
  /// smoothness energy plus the weighted boundary terms, so above the
  /// energy that the statistics report), for progress display.
  std::function<void(const std::string& stage, int iteration, double measure)> iteration_progress;
};

/// \ingroup PkgCGALExtFrames
/// Figures of a `Frame_field_3::compute()` run.
struct Frame_field_statistics {
  /// Tetrahedra (frames).
  std::size_t tets = 0;
  /** @{ */
  /// Interior faces (smoothness terms) and boundary faces (alignment terms).
  std::size_t interior_faces = 0, boundary_faces = 0;
  /** @} */
  /** @{ */
  /// Boundary tetrahedra with one hard axis, and with two (a frame fixed by
  /// two non-parallel boundary faces, e.g. along a sharp edge).
  std::size_t hard_one_axis = 0, hard_two_axes = 0;
  /** @} */
  /** @{ */
  /// Feature edges, vertices on feature curves and corners (`Sharp_features_3`).
  std::size_t feature_edges = 0, feature_curve_vertices = 0, feature_corners = 0;
  /** @} */
  /// Edges sharper than the feature angle that are not features: curves of
  /// fewer than 3 edges, below the mesh's resolution (lone kinks and spurs,
  /// `Sharp_features_3::number_of_dropped_edges()`).
  std::size_t feature_edges_dropped = 0;
  /// Tetrahedra whose hard axes come from a feature: a corner's frame or a
  /// feature edge's tangent.
  std::size_t feature_tets = 0;
  /// The turning of the boundary's smooth part in the metric
  /// (`Sharp_features_3::smooth_turning()`), for `hex_coverage_ceiling()`.
  double boundary_smooth_turning = 0;
  /// Face transports that are exactly the identity (constant metric).
  std::size_t identity_transports = 0;
  /// Largest transport angle over the faces, in radians.
  double max_transport_angle = 0;
  /** @{ */
  /// Conjugate-gradient iterations of the initialisation and its final relative residual.
  int linear_iterations = 0;
  double linear_residual = 0;
  /** @} */
  /** @{ */
  /// Conjugate-gradient iterations and unknowns of the coarse level (0 without one).
  int coarse_iterations = 0;
  std::size_t coarse_unknowns = 0;
  /** @} */
  /// Tetrahedra whose initial SH vector was (near) zero and got the identity.
  std::size_t degenerate_projections = 0;
  /** @{ */
  /// L-BFGS iterations and energy evaluations.
  int refinement_iterations = 0, energy_evaluations = 0;
  /** @} */
  /** @{ */
  /// The diffusion steps made (0 if none, or skipped on a domain with
  /// feature edges) and their conjugate-gradient iterations in all.
  int diffusion_steps = 0, diffusion_iterations = 0;
  /** @} */
  /// The energy after the diffusion steps (the projected energy if none).
  double diffused_energy = 0;
  /** @{ */
  /// Whether an iteration bound stopped a stage (`max_linear_iterations`
  /// before the CG residual reached `linear_tolerance`, or
  /// `max_refinement_iterations` while L-BFGS still made progress): reached
  /// only on pathological input, and said in the stage's progress line.
  bool linear_iteration_limit_reached = false, refinement_iteration_limit_reached = false;
  /** @} */
  /** @{ */
  /// Smoothness energy `sum_f w_f |s_j - D(T_ij) s_i|^2` after the
  /// projection and at the end.
  double projected_energy = 0, smoothness_energy = 0;
  /** @} */
  /// The sum of the face weights (the energy of the worst field is about
  /// twice this; `smoothness_energy / total_face_weight` is a mean).
  double total_face_weight = 0;
  /** @{ */
  /// Boundary alignment: angle between `A^{-1} n` and the nearest frame
  /// vector `F e_k`, in degrees, over the boundary faces.
  double boundary_error_mean_deg = 0, boundary_error_max_deg = 0;
  /** @} */
  /// `max |F^T g F - I|` over the tetrahedra (entry-wise), `g` at the centroid.
  double max_orthonormality_error = 0;
  /** @{ */
  /// Seconds per stage: set-up (geometry, weights), face transports, linear
  /// initialisation, projection, diffusion, refinement.
  double seconds_setup = 0, seconds_transports = 0, seconds_linear = 0, seconds_projection = 0,
         seconds_diffusion = 0, seconds_refinement = 0;
  /** @} */
};

/// \ingroup PkgCGALExtFrames
/// One boundary face of a frame field's domain: tetrahedron, local facet,
/// Euclidean outward unit normal, the aligned direction
/// `d = A^{-1} n / |A^{-1} n|` and the metric area.
struct Frame_field_boundary_face {
  std::size_t tet;           ///< tetrahedron index
  int facet;                 ///< the facet's index in the cell (its opposite vertex)
  Eigen::Vector3d normal;    ///< outward unit normal
  Eigen::Vector3d direction; ///< `A^{-1} n / |A^{-1} n|`, in the frame's (rotation) space
  double metric_area;        ///< area measured in the metric
};

/// \ingroup PkgCGALExtFrames
/// Options of `repair_singularities()`.
struct Singularity_repair_options {
  /// The radii of the regions re-optimised around the non-meshable edges
  /// and nodes, in rings of tetrahedra sharing a vertex: one round per
  /// radius, in order, while any remain. A larger region gives the
  /// re-optimisation more room and other boundary values.
  std::vector<int> radii = {2, 3, 4};
  /// Restarts per region in each round, in the order of `radii` (none in
  /// the rounds past the end of the list): after the relaxed and the
  /// propagated starts, for the regions that still have defects,
  /// the relaxed start with every frame turned by a pseudo-random rotation
  /// (`Frame_field_3::reoptimize()` with a seed), which leads L-BFGS to
  /// other local minima. The seeds depend on the round, the start and the
  /// region, never on the thread count. By default only the second round
  /// restarts (chosen by measurement, doc/benchmarks.md): restarts in the
  /// first round kept frames that the later rounds could not improve, and
  /// in the last round, whose regions are the largest, they cost more for
  /// less.
  std::vector<int> restarts = {0, 6, 0};
  /// After the rounds of `radii`, while non-meshable edges or nodes remain: further
  /// rounds, at most `max_further_rounds`, whose radii are taken in turn from
  /// `further_radii`, each with `further_restarts` restarts per region (new
  /// seeds every round). They stop early when a whole turn of
  /// `further_radii` kept no region. Each round starts from the frames the
  /// previous ones left, so a defect that moved or shrank is attacked again
  /// from there. Measured with `metric-frames generate` (doc/benchmarks.md),
  /// non-meshable edges left by the repair without and with them: CGAL's
  /// anchor 7 and 2, TetGen's anchor 12 and 0, TetGen's fandisk 1 and 0.
  /// They cost time only where defects remain (at 10^6
  /// tetrahedra about 12 s of their own, for 19 -> 8). 0 turns them off.
  int max_further_rounds = 8;
  /// The radii of the further rounds, taken in turn.
  std::vector<int> further_radii = {3, 2};
  /// Then, while defects remain: released rounds, at most
  /// `max_released_rounds`, as the further rounds (their radii and
  /// restarts, the same stop) but with the hard boundary constraints of the
  /// regions' tetrahedra released (`Frame_field_3::release_hard_constraints()`):
  /// those keep their soft boundary terms only, so that frames pinned to
  /// faces and feature curves that force a defect (a crease between
  /// frames 45 degrees apart, say) can turn. The regions kept stay released;
  /// the others are held again. Measured with `metric-frames generate`
  /// (doc/benchmarks.md): CGAL's anchor at hexes of the diagonal / 15,
  /// non-meshable edges and nodes 1 and 2 -> 0 and 0; the Gmsh anchor of
  /// the tests 16 edges -> 0. 0 turns them off.
  int max_released_rounds = 8;
  /// Restarts per region in each further round.
  int further_restarts = 24;
  /// The largest angle of a restart's turns, in degrees.
  double restart_angle_deg = 90;
  /// The (step, gradient change) pairs that the L-BFGS of the regions'
  /// re-optimisations keeps (`Frame_field_3::reoptimize()`); 0 takes the
  /// field's `Frame_field_options::lbfgs_memory` (8). Measured
  /// (doc/benchmarks.md, "The repair's L-BFGS memory"): from the restarts'
  /// scrambled starts L-BFGS needs as many iterations with 4 pairs as with
  /// 8 (103 and 107 per start on TetGen's anchor), and each costs a fifth
  /// less (the two-loop recursion makes two passes over the region per
  /// pair); with 4, no defect is left on the 13 meshes of issue 15's
  /// benchmark, against three with 8.
  int lbfgs_memory = 4;
  /// If set, called after each round with its number (from 1), the radius,
  /// the regions tried and accepted, and the non-meshable edges and nodes left.
  std::function<void(int round, int radius, std::size_t tried, std::size_t accepted, std::size_t left)> progress;
};

} // namespace CGAL_ext

#endif // CGAL_EXT_FRAME_FIELD_OPTIONS_H
