// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_FRAME_FIELD_3_H
#define CGAL_EXT_FRAME_FIELD_3_H

/// \file Frame_field_3.h
/// Metric-driven octahedral frame fields on a tetrahedral mesh (doc/math.md
/// section 5; Fang et al., "Metric-Driven 3D Frame Field Generation", TVCG
/// 2023): one frame per tetrahedron, smooth after transport by the metric's
/// connection, aligned with the boundary in the metric.

#include <CGAL_ext/Frame_field_options.h>
#include <CGAL_ext/Input_error.h>
#include <CGAL_ext/Metric_field_3.h>
#include <CGAL_ext/Octahedral_frame.h>
#include <CGAL_ext/Tet_mesh_triangulation_3.h>
#include <CGAL_ext/internal/Frame_field_coarse_level_3.h>
#include <CGAL_ext/internal/Frame_field_diffusion_3.h>
#include <CGAL_ext/internal/Frame_field_energy_3.h>
#include <CGAL_ext/internal/deterministic_parallel.h>
#include <CGAL_ext/internal/lbfgs_on_rotations.h>
#include <CGAL_ext/internal/preconditioned_conjugate_gradient.h>
#include <CGAL_ext/internal/seeded_rotation.h>

#include <CGAL/Real_timer.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace CGAL_ext {

/// \ingroup PkgCGALExtFrames
/// An octahedral frame field in a metric: one rotation `R_i` per
/// tetrahedron, and the frame `F_i = A_i^{-1} R_i` (`A_i = g^{1/2}` at the
/// centroid), whose columns are the hex edge vectors, of unit length in the
/// metric (`F^T g F = I`).
///
/// **Energy.** With `s_i = D(R_i) s0` the band-4 SH vector of frame `i`
/// (Octahedral_frame.h) and, for each interior face `f` between tetrahedra
/// `i` and `j`, the transport `T(i->j)`,
/// `E = sum_f w_f |s_j - D(T(i->j)) s_i|^2` (doc/math.md section 5). The weight
/// is the face's area over the distance between the two centroids, both
/// measured in the metric at the face centroid: `w_f = det(A) |A^{-1} n| a /
/// |A (c_j - c_i)|` (`a`, `n` the Euclidean area and unit normal). It is the
/// usual two-point flux discretisation of the Dirichlet energy, in the metric.
///
/// **Transport path.** `T(i->j)` is taken along the broken line from the
/// centroid of `i` to the centroid of the shared face, then to the centroid of
/// `j`: two pieces, each inside one tetrahedron, integrated by
/// `cell_transport()` with the tetrahedron's linear `A` and constant curl.
/// No walk is needed, and the path stays in the closed domain even where the
/// straight segment between the centroids would leave it (non-convex corners).
/// `T(j->i) = T(i->j)^T` is used for the reverse direction.
///
/// **Boundary alignment.** On a boundary face with outward unit normal `n`,
/// the frame must have an axis along `d = A^{-1} n / |A^{-1} n|` (`A` at the
/// face centroid): `R e_k = +-d` (doc/math.md section 5). In SH terms,
/// `D(R_d)^T s` (with `R_d e_z = d`) must have coefficients `m = -3..3` equal
/// to `(0, 0, 0, sqrt(7/12), 0, 0, 0)`: a linear condition, used as the soft
/// term `lambda w_b |P D(R_d)^T s - c|^2` with `w_b` the face's metric area over
/// the metric distance from the tetrahedron's centroid to the face centroid.
/// With `hard_boundary`, after the projection each boundary tetrahedron is
/// turned so that an axis is exactly on `d` of its largest boundary face (and
/// a second axis on a second face whose `d` is more than 30 degrees from
/// the first, projected orthogonally to it), and the refinement only
/// turns it about that axis (or not at all) unless its constraint is
/// released (`release_hard_constraints()`, which the repair uses).
///
/// **Sharp features** (`Sharp_features_3`, `feature_angle_deg`). With
/// `hard_boundary`, a tetrahedron with a corner of the boundary takes the
/// corner's frame (two hard axes). One with a feature edge keeps an axis on
/// the feature curve's tangent `A t`; its rotation about it comes from its
/// boundary faces: if they agree, the largest face is followed exactly (and
/// the tangent as far as it allows); if they lie on both sides of a crease,
/// the frame takes the mean of their directions modulo a quarter turn, so
/// that they share the crease's angle; without boundary faces it is free.
/// On a crease whose faces' frames differ by at least
/// `Frame_field_options::crease_split_deg` modulo a quarter turn (45-degree
/// chamfers), a tetrahedron with faces on one side shares the angle too.
///
/// **Method.** (1) Sparse linear initialisation: the quadratic energy plus
/// the soft boundary terms, minimised over unconstrained 9-vectors by
/// conjugate gradients with block-Jacobi preconditioning (matrix-free: the
/// 9x9 blocks `D(T)` are applied from the stored transports, so memory stays
/// linear with a small constant); (2) projection of each `s_i` onto the
/// octahedral variety (`rotation_from_octahedral_sh()`: coarse search plus
/// Newton on SO(3)); optionally, diffusion-projection steps
/// (`Frame_field_options::diffusion_steps`, off by default: implicit heat
/// steps of the initialisation's energy, each projected again); (3) L-BFGS
/// on local rotations `R_i <- exp([w_i]_x) R_i` with Armijo backtracking,
/// until the energy converges.
///
/// **Determinism.** Every parallel loop writes per-tetrahedron data only, and
/// every sum is made of fixed blocks added in order, so the result does not
/// depend on the number of threads.
///
/// \tparam Metric_field a model of `MetricField_3`, such as `Metric_field_3<Tr>`
///
/// The domain (the cells with a non-negative index) and the vertex and cell
/// indices are the metric field's (`MetricField_3::cell_index_map()`), so
/// the frames, the field and its transports always agree on them; the
/// domain's cell indices must be exactly `0..n-1` (the tetrahedron order of
/// the mesh file for the default maps).
template <class Metric_field>
class Frame_field_3 {
public:
  /// The triangulation type.
  using Triangulation = typename Metric_field::Triangulation_3;
  /// Cell handle type.
  using Cell_handle = typename Triangulation::Cell_handle;
  /// Vertex handle type.
  using Vertex_handle = typename Triangulation::Vertex_handle;
  /// Point type.
  using Point_3 = typename Triangulation::Point;

  /// One boundary face (`Frame_field_boundary_face`).
  using Boundary_face = Frame_field_boundary_face;

  /// Prepares the field: cells, neighbours, weights and boundary data.
  /// \param field the metric field; it and its triangulation must outlive this object
  /// \throws Input_error if the domain's cell indices are not `0..n-1`, or
  ///         the domain is empty
  explicit Frame_field_3(const Metric_field& field) : e_(field, domain_cells(field)) {
    stats_.tets = e_.size();
  }

  /// Computes the field: set-up, face transports, linear initialisation,
  /// projection, refinement (see the class documentation). Every hard
  /// constraint is held again (see `release_hard_constraints()`).
  /// \param options the options
  /// \returns the statistics (also kept, see `statistics()`)
  const Frame_field_statistics& compute(const Frame_field_options& options = {}) {
    released_.clear();
    prepare(options);
    Timer t;
    linear_initialisation();
    stats_.seconds_linear = t.lap();
    report("linear initialisation", stats_.seconds_linear,
           std::to_string(stats_.linear_iterations) + " CG iterations, residual " + format_number(stats_.linear_residual) +
               (stats_.coarse_unknowns ? " (after " + std::to_string(stats_.coarse_iterations) + " on a coarse level of " +
                                             std::to_string(stats_.coarse_unknowns / 9) + " aggregates)"
                                       : std::string()) +
               (stats_.linear_iteration_limit_reached ? "; stopped by the iteration limit" : ""));
    project();
    stats_.projected_energy = smoothness_energy();
    stats_.seconds_projection = t.lap();
    report("projection", stats_.seconds_projection, "energy " + format_number(stats_.projected_energy));
    const std::string diffusion = diffuse();
    stats_.seconds_diffusion = t.lap();
    if (!diffusion.empty()) report("diffusion", stats_.seconds_diffusion, diffusion);
    coarse_.reset();
    refine();
    stats_.smoothness_energy = smoothness_energy();
    stats_.seconds_refinement = t.lap();
    report("refinement", stats_.seconds_refinement,
           std::to_string(stats_.refinement_iterations) + " L-BFGS iterations, energy " +
               format_number(stats_.smoothness_energy) +
               (stats_.refinement_iteration_limit_reached ? "; stopped by the iteration limit" : ""));
    measure();
    return stats_;
  }

  /// The first two stages of `compute()`: the geometry, weights and boundary
  /// data, and the face transports. `compute()` calls it; call it directly
  /// only before `set_rotations()`. Does nothing if already done with the
  /// same set-up options (those listed below); redoes both stages if any of
  /// them changed, so that a second `compute()` with, say, another feature
  /// angle uses it.
  /// \param options the options; the set-up uses `boundary_weight`,
  ///        `hard_boundary`, `feature_angle_deg` and `crease_split_deg`, the
  ///        transports `transport_tolerance` and `transport_scheme`
  void prepare(const Frame_field_options& options = {}) {
    opt_ = options;
    if (prepared_ && same_set_up(prepared_with_, options)) return;
    // Marked done only at the end: a set-up or transport that throws (a
    // negative crease angle, a transport that does not converge) leaves its
    // data half-made, and the next call must redo it, not use it.
    prepared_ = false;
    coarse_.reset(); // made from the weights and constraints
    Timer t;
    e_.set_up(opt_, stats_);
    stats_.seconds_setup = t.lap();
    report("set-up", stats_.seconds_setup,
           std::to_string(stats_.tets) + " tets, " + std::to_string(stats_.interior_faces) + " interior and " +
               std::to_string(stats_.boundary_faces) + " boundary faces");
    e_.compute_transports(opt_, stats_);
    stats_.seconds_transports = t.lap();
    report("face transports", stats_.seconds_transports,
           std::to_string(stats_.identity_transports) + " exactly identity, largest angle " +
               format_number(stats_.max_transport_angle * 180 / M_PI) + " deg");
    prepared_with_ = options;
    prepared_ = true;
  }

  /// Replaces the frames by given rotations (e.g. to analyse a field made
  /// elsewhere with `singular_edges()` and the measures here), without any
  /// optimisation, and updates the energy and alignment statistics.
  /// \tparam Rotation_of a callable `Eigen::Matrix3d(std::size_t i)`
  /// \param rotation_of the rotation `R_i` of each tetrahedron (a rotation matrix)
  template <class Rotation_of>
  void set_rotations(Rotation_of rotation_of) {
    prepare(opt_);
    q_.assign(size(), Eigen::Quaterniond::Identity());
    s_.assign(size(), Sh_vector::Zero());
    for (std::size_t i = 0; i < size(); ++i)
      set_rotation(i, Eigen::Quaterniond(Eigen::Matrix3d(rotation_of(i))).normalized());
    update_statistics();
  }

  /// Where a vertex lies on the sharp features found by the set-up
  /// (`Sharp_features_3` with `Frame_field_options::feature_angle_deg`).
  /// \param v a vertex index
  /// \returns its kind; `none` off the features, inside the volume, or
  ///          before `prepare()`
  Feature_vertex_kind feature_vertex_kind(std::size_t v) const {
    return v < e_.feature_kind.size() ? e_.feature_kind[v] : Feature_vertex_kind::none;
  }

  /// The statistics of the last `compute()`.
  /// \returns the statistics (their energy and alignment figures refreshed by
  ///          `update_statistics()`)
  const Frame_field_statistics& statistics() const { return stats_; }

  /// The options of the last `compute()` or `prepare()` (the defaults before).
  /// \returns the options
  const Frame_field_options& options() const { return opt_; }

  /// The number of tetrahedra (frames).
  /// \returns the number of tetrahedra, indexed `0..size()-1`
  std::size_t size() const { return e_.cells.size(); }
  /// The metric field.
  /// \returns the metric field given to the constructor
  const Metric_field& metric_field() const { return e_.field(); }
  /// The cell of tetrahedron `i`.
  /// \param i a tetrahedron index
  /// \returns the domain cell of index `i`
  Cell_handle cell(std::size_t i) const { return e_.cells[i]; }
  /// The tetrahedron index of a domain cell, or -1.
  /// \param c a cell
  /// \returns the index in `0..size()-1`, or -1 outside the domain
  std::int64_t index(Cell_handle c) const { return get(e_.field().cell_index_map(), c); }
  /// The 0-based index of a vertex.
  /// \param v a finite vertex
  /// \returns the index, from the vertex index map
  std::size_t vertex_index(Vertex_handle v) const { return get(e_.field().vertex_index_map(), v); }

  /// The rotation `R_i`, as `canonicalize_frame()` (a deterministic
  /// representative of `{R_i G}`).
  /// \param i a tetrahedron index
  /// \returns the canonical rotation matrix
  Eigen::Matrix3d rotation(std::size_t i) const { return canonicalize_frame(q_[i].toRotationMatrix()); }
  /// The frame `F_i = A_i^{-1} R_i`: columns are the three hex edge vectors,
  /// of unit length in the metric at the centroid.
  /// \param i a tetrahedron index
  /// \returns `F_i` (3x3, column `k` the `k`-th hex edge vector)
  Eigen::Matrix3d frame(std::size_t i) const { return e_.sqrt_metric[i].inverse() * rotation(i); }
  /// The parameter gradients `A_i R_i = F_i^{-T}`: column `k` is the
  /// gradient that the `k`-th parameter of an integer-grid map should have
  /// in tetrahedron `i` (row `k` of `F_i^{-1}`, the dual basis of the hex
  /// edges: `F^{-1} F = I`). Its length is the number of hex layers per
  /// unit length across that direction; for `g = I / h^2` it is `1 / h`.
  /// This is what CubeCover's `.fra` file holds.
  /// \param i a tetrahedron index
  /// \returns `A_i R_i` (3x3, column `k` the gradient of parameter `k`)
  Eigen::Matrix3d parameter_gradients(std::size_t i) const { return e_.sqrt_metric[i] * rotation(i); }
  /// `A = g^{1/2}` at the centroid of tetrahedron `i`.
  /// \param i a tetrahedron index
  /// \returns `A_i` (3x3, symmetric positive definite)
  const Eigen::Matrix3d& sqrt_metric(std::size_t i) const { return e_.sqrt_metric[i]; }
  /// The SH vector `s_i = D(R_i) s0` of tetrahedron `i`.
  /// \param i a tetrahedron index
  /// \returns the band-4 SH 9-vector `s_i`
  const Sh_vector& sh(std::size_t i) const { return s_[i]; }
  /// The centroid of tetrahedron `i`.
  /// \param i a tetrahedron index
  /// \returns the centroid's coordinates
  const Eigen::Vector3d& centroid(std::size_t i) const { return e_.centroid[i]; }
  /// The neighbour of tetrahedron `i` across its facet `f` (opposite
  /// `cell(i)->vertex(f)`), or -1 on the boundary.
  /// \param i a tetrahedron index
  /// \param f a facet index in 0..3
  /// \returns the neighbour's tetrahedron index, or -1
  std::int64_t neighbor(std::size_t i, int f) const { return e_.links[i].nb[f]; }
  /// The transport `T(j->i)` from the neighbour `j = neighbor(i, f)` into
  /// tetrahedron `i` (identity on the boundary).
  /// \param i a tetrahedron index
  /// \param f a facet index in 0..3
  /// \returns the 3x3 rotation `T(j->i)`
  Eigen::Matrix3d transport_into(std::size_t i, int f) const {
    return e_.links[i].identity[f] ? Eigen::Matrix3d::Identity() : e_.transport_in[i][f].toRotationMatrix();
  }
  /// Half the smoothness energy density at tetrahedron `i`:
  /// `sum_f w_f |s_i - D(T(j->i)) s_j|^2 / 2` over its interior faces, divided
  /// by its volume (so that it sums, times the volumes, to the energy).
  /// \param i a tetrahedron index
  /// \returns the density, an energy per unit volume
  double energy_density(std::size_t i) const {
    return std::ldexp(0.5 * e_.local_smoothness(i, s_) / e_.volume[i], e_.weight_exponent);
  }
  /// Half the smoothness energy of the interior faces of tetrahedron `i`:
  /// `sum_f w_f |s_i - D(T(j->i)) s_j|^2 / 2`. Summed over all tetrahedra it
  /// is `smoothness_energy()`; summed over a set that holds some changed
  /// tetrahedra and their face neighbours, its change is the change of
  /// `smoothness_energy()`.
  /// \param i a tetrahedron index
  /// \returns the energy, in the units of `smoothness_energy()`
  double local_smoothness_energy(std::size_t i) const {
    return std::ldexp(0.5 * e_.local_smoothness(i, s_), e_.weight_exponent);
  }
  /// The boundary faces, in tetrahedron order.
  /// \returns one `Frame_field_boundary_face` per boundary face of the domain
  const std::vector<Boundary_face>& boundary_faces() const { return e_.boundary; }
  /// The alignment error of a boundary face in degrees: the angle between
  /// `d` and the nearest of `+-R e_k`.
  /// \param b a boundary face
  /// \returns the angle in degrees, at most `acos(1 / sqrt(3))` (about 54.7)
  double alignment_error_deg(const Boundary_face& b) const {
    const Eigen::Matrix3d R = q_[b.tet].toRotationMatrix();
    const double c = (R.transpose() * b.direction).cwiseAbs().maxCoeff();
    return std::acos(std::min(1.0, c)) * 180 / M_PI;
  }
  /// The smoothness energy `sum_f w_f |s_j - D(T(i->j)) s_i|^2` of the current frames.
  /// \returns `E`, as `Frame_field_statistics::smoothness_energy` reports it
  double smoothness_energy() const {
    const double internal_units = 0.5 * internal::deterministic_sum(size(), [&](std::size_t b, std::size_t e) {
                                    double s = 0;
                                    for (std::size_t i = b; i < e; ++i) s += e_.local_smoothness(i, s_);
                                    return s;
                                  });
    return std::ldexp(internal_units, e_.weight_exponent);
  }

  /// How `reoptimize()` starts.
  enum class Reoptimize_start {
    /// As `compute()`: the linear initialisation of the SH vectors (the
    /// quadratic energy with the other frames as boundary values, solved to
    /// a relative residual of 1e-8), projected onto rotations.
    relaxed,
    /// Each frame transported from its neighbour nearest to the outside
    /// (breadth-first through faces from all the fixed neighbours at once),
    /// so that the mismatches start on the seams where the fronts meet.
    propagated,
    /// The frames the tetrahedra have (e.g. a start that `start_frames()`
    /// made and the caller saved, to turn it by several seeds without
    /// solving for it again).
    current
  };

  /// Sets the frames of some tetrahedra to a start of `reoptimize()`, all
  /// others fixed, without optimising: `reoptimize(tets, start, seed, a)` is
  /// `start_frames(tets, start)` then `reoptimize(tets, Reoptimize_start::current, seed, a)`.
  /// The statistics are not updated.
  /// \param tets the tetrahedron indices (distinct)
  /// \param start how the frames start (`current` leaves them)
  void start_frames(const std::vector<std::size_t>& tets, Reoptimize_start start) {
    prepare(opt_);
    if (tets.empty() || start == Reoptimize_start::current) return;
    const Marked marked(*this, tets);
    if (start != Reoptimize_start::propagated || !propagate(tets, local_)) relax(tets, marked.set, local_);
  }

  /// Re-optimises the frames of some tetrahedra, all others fixed, as
  /// `compute()` does globally: a start (see `Reoptimize_start`), turned
  /// if `seed` is not 0, with the held hard constraints applied, then L-BFGS on
  /// their rotations. The result depends on the surrounding frames, the
  /// start and the seed, not on the previous frames of the tetrahedra given
  /// (except from the `current` start) nor on the thread count. The
  /// statistics are not updated (see `update_statistics()`). Time goes
  /// with the tetrahedra given, not with the mesh (the first call keeps 9
  /// bytes per tetrahedron of scratch for all the later ones). Used by
  /// `repair_singularities()`, which restarts from several seeds to leave a
  /// local minimum.
  /// \param tets the tetrahedron indices to re-optimise (distinct)
  /// \param start how the frames start
  /// \param seed if not 0, each start frame is turned by a pseudo-random
  ///        rotation that depends on `seed` and the tetrahedron index only:
  ///        about a direction uniform on the sphere, by an angle uniform in
  ///        [0, `max_angle`]
  /// \param max_angle the largest angle of those rotations, in radians
  /// \param lbfgs_memory the (step, gradient change) pairs L-BFGS keeps; 0
  ///        takes `Frame_field_options::lbfgs_memory`
  /// \returns the L-BFGS iterations
  /// \throws std::invalid_argument for a negative `lbfgs_memory`
  int reoptimize(const std::vector<std::size_t>& tets, Reoptimize_start start = Reoptimize_start::relaxed,
                 std::uint64_t seed = 0, double max_angle = 0, int lbfgs_memory = 0) {
    if (lbfgs_memory < 0) throw std::invalid_argument("Frame_field_3::reoptimize: lbfgs_memory must not be negative");
    const std::size_t m = tets.size();
    if (m == 0) return 0;
    start_frames(tets, start);
    if (seed != 0)
      internal::parallel_for_each_index(m, [&](std::size_t k) {
        q_[tets[k]] = (internal::seeded_rotation(seed, tets[k], max_angle) * q_[tets[k]]).normalized();
      });
    internal::parallel_for_each_index(m, [&](std::size_t k) { constrain(tets[k]); });
    int evaluations = 0;
    bool limit = false;
    const Marked marked(*this, tets);
    return lbfgs(marked.set, evaluations, limit, nullptr, lbfgs_memory > 0 ? lbfgs_memory : opt_.lbfgs_memory);
  }

  /// The rotation `R_i` as the unit quaternion the optimiser holds (any
  /// representative of `{R_i G}`; `rotation()` gives the canonical one).
  /// \param i a tetrahedron index
  /// \returns the unit quaternion of `R_i`
  const Eigen::Quaterniond& rotation_quaternion(std::size_t i) const { return q_[i]; }

  /// Sets the rotation of one tetrahedron (e.g. to restore a value of
  /// `rotation_quaternion()`). The statistics are not updated (see
  /// `update_statistics()`).
  /// \param i a tetrahedron index
  /// \param q a unit quaternion
  void set_rotation(std::size_t i, const Eigen::Quaterniond& q) {
    q_[i] = q;
    s_[i] = rotate_sh(q_[i], octahedral_reference_sh());
  }

  /// The objective that the L-BFGS of `compute()` and `reoptimize()`
  /// minimises, with the frames of the other tetrahedra fixed: the
  /// smoothness terms of the faces of the tetrahedra given (each face once)
  /// plus their soft boundary terms; and its gradient in their left rotation
  /// increments `w` (`R <- exp([w]_x) R`), projected on the axes that the
  /// held hard constraints leave free. Its norm after `compute()` tells how far
  /// from a stationary point the optimiser stopped.
  /// \param tets the tetrahedron indices (distinct), or empty for all
  /// \param gradient receives the gradient, one vector per tetrahedron of
  ///        `tets` in its order (per tetrahedron index if `tets` is empty)
  /// \returns the objective, in the units of `smoothness_energy()`
  double refinement_objective(const std::vector<std::size_t>& tets, std::vector<Eigen::Vector3d>& gradient) {
    prepare(opt_);
    const Marked marked(*this, tets);
    Active_set all;
    all.n = size();
    const Active_set& set = tets.empty() ? all : marked.set;
    gradient.assign(set.n, Eigen::Vector3d::Zero());
    const double e = energy_and_gradient(set, &gradient);
    for (Eigen::Vector3d& g : gradient) g = std::ldexp(1.0, e_.weight_exponent) * g;
    return std::ldexp(e, e_.weight_exponent);
  }

  /// Whether tetrahedron `i` has a hard constraint: a boundary face, a
  /// feature edge or a corner (`Frame_field_options::hard_boundary` on).
  /// Known once the field is set up (by `compute()`, `set_rotations()` or
  /// `reoptimize()`); false before.
  /// \param i a tetrahedron index
  /// \returns whether `i` has one
  /// \throws std::out_of_range for an index of no tetrahedron
  bool has_hard_constraint(std::size_t i) const {
    if (i >= size()) throw std::out_of_range("has_hard_constraint: no tetrahedron " + std::to_string(i));
    return opt_.hard_boundary && i < e_.constraint_of.size() && e_.constraint_of[i] >= 0;
  }

  /// The number of frame axes that the hard constraint of tetrahedron `i`
  /// fixes, whether held or released (`hard_constraint_released()`): 0 (no
  /// hard constraint), 1 (an axis on a face's normal or a feature edge's
  /// tangent) or 2 (the whole frame: two boundary faces more than 30 degrees
  /// apart, a feature edge's tangent and a face, or a corner).
  /// \param i a tetrahedron index
  /// \returns 0, 1 or 2
  /// \throws std::out_of_range for an index of no tetrahedron
  int hard_constraint_axes(std::size_t i) const {
    if (!has_hard_constraint(i)) return 0; // checks the index
    return e_.constraints[std::size_t(e_.constraint_of[i])].axes;
  }

  /// Releases or holds again the hard constraints of some tetrahedra. A
  /// released tetrahedron keeps the soft terms of its boundary faces only,
  /// so that `reoptimize()` turns it freely: at a feature curve or a corner
  /// nothing holds the curve's tangent or the corner's frame any more.
  /// `repair_singularities()` releases the regions whose re-optimisation
  /// needs it. All are held at construction and by `compute()`;
  /// `set_rotation()` and `set_rotations()` leave the flags as they are.
  /// \param tets the tetrahedron indices
  /// \param released `true` to release them, `false` to hold them again
  ///        (their frames are not snapped back: call `reoptimize()` or
  ///        `set_rotation()`)
  /// \throws std::out_of_range for an index of no tetrahedron (nothing is changed)
  void release_hard_constraints(const std::vector<std::size_t>& tets, bool released) {
    for (std::size_t i : tets)
      if (i >= size()) throw std::out_of_range("release_hard_constraints: no tetrahedron " + std::to_string(i));
    if (released_.size() != size()) released_.assign(size(), 0);
    for (std::size_t i : tets) released_[i] = released ? 1 : 0;
  }

  /// Whether the hard constraint of tetrahedron `i` (if any) is released
  /// (`release_hard_constraints()`).
  /// \param i a tetrahedron index
  /// \returns whether it is released
  /// \throws std::out_of_range for an index of no tetrahedron
  bool hard_constraint_released(std::size_t i) const {
    if (i >= size()) throw std::out_of_range("hard_constraint_released: no tetrahedron " + std::to_string(i));
    return !released_.empty() && released_[i] != 0;
  }

  /// Recomputes the smoothness energy, boundary alignment and
  /// orthonormality of the statistics from the current frames.
  void update_statistics() {
    stats_.smoothness_energy = smoothness_energy();
    measure();
  }

private:
  using Energy = internal::Frame_field_energy_3<Metric_field>;

  // Whether tetrahedron i's hard constraint (if any) applies.
  bool hard_constraint_held(std::size_t i) const { return opt_.hard_boundary && (released_.empty() || !released_[i]); }

  // The domain's cells in index order; throws if the indices are not 0..n-1.
  static std::vector<Cell_handle> domain_cells(const Metric_field& field) {
    const Triangulation& tr = field.triangulation();
    const auto cim = field.cell_index_map();
    if (tr.dimension() != 3) throw Input_error("", 0, "", "the triangulation is not three-dimensional");
    std::size_t n = 0;
    for (Cell_handle c : tr.finite_cell_handles())
      if (get(cim, c) >= 0) ++n;
    if (n == 0) throw Input_error("", 0, "", "the mesh has no tetrahedra in its domain");
    std::vector<Cell_handle> cells(n, Cell_handle());
    for (Cell_handle c : tr.finite_cell_handles()) {
      const std::int64_t k = get(cim, c);
      if (k < 0) continue;
      if (std::size_t(k) >= n || cells[k] != Cell_handle())
        throw Input_error("", 0, "tetrahedron " + std::to_string(k + 1),
                          "cell indices of the domain must be exactly 0.." + std::to_string(n - 1));
      cells[k] = c;
    }
    return cells;
  }

  // Wall-clock seconds per stage.
  struct Timer {
    CGAL::Real_timer timer;
    Timer() { timer.start(); }
    double lap() {
      const double s = timer.time();
      timer.reset();
      return s;
    }
  };
  void report(const char* stage, double seconds, const std::string& detail) const {
    if (opt_.progress) opt_.progress(stage, seconds, detail);
  }
  // Preconditioned conjugate gradients on H x = b from the given x, until
  // |r| <= tol |b| (or max_linear_iterations). Returns the iterations;
  // `relres` gets |r| / |b|. `stage` names the iterations for the progress
  // callback (or null).
  template <class Apply, class Precondition>
  int pcg(std::vector<Sh_vector>& x, const std::vector<Sh_vector>& b, Apply apply, Precondition precondition,
          double tol, const char* stage, double& relres) const {
    return internal::preconditioned_conjugate_gradient(
        x, b, apply, precondition, tol, opt_.max_linear_iterations,
        [&](int it, double r) {
          if (stage && opt_.iteration_progress) opt_.iteration_progress(stage, it, r);
        },
        relres);
  }

  bool use_coarse_level() const { return opt_.aggregate_size > 1 && size() >= std::size_t(8 * opt_.aggregate_size); }
  // The coarse level, built once for the initialisation and the diffusion
  // steps; compute() frees it before the refinement.
  const internal::Frame_field_coarse_level& coarse_level() {
    if (!coarse_) coarse_ = internal::build_coarse_level(e_, opt_.aggregate_size);
    return *coarse_;
  }

  void linear_initialisation() {
    const std::size_t n = size();
    std::vector<Sh_vector> x(n, Sh_vector::Zero()), b(n, Sh_vector::Zero());
    for (std::size_t i = 0; i < n; ++i)
      if (e_.constraint_of[i] >= 0) b[i] = e_.constraints[e_.constraint_of[i]].b;
    stats_.linear_iterations = stats_.coarse_iterations = 0;
    stats_.linear_iteration_limit_reached = false;
    stats_.linear_residual = 0;
    stats_.coarse_unknowns = 0;
    if (internal::block_dot(b, b) > 0) {
      if (use_coarse_level()) {
        // Nested iteration: the coarse solution, prolonged, starts the fine
        // iteration with the smooth part of the solution already in place.
        const internal::Frame_field_coarse_level& c = coarse_level();
        const std::size_t na = c.rows.size();
        std::vector<Sh_vector> xc(na, Sh_vector::Zero()), bc(na, Sh_vector::Zero());
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, na, 16), [&](const tbb::blocked_range<std::size_t>& r) {
          for (std::size_t a = r.begin(); a != r.end(); ++a)
            for (std::size_t m = c.first[a]; m < c.first[a + 1]; ++m) {
              const std::size_t t = c.members[m];
              if (e_.constraint_of[t] >= 0) bc[a] += rotate_sh(c.U[t].conjugate(), b[t]);
            }
        });
        auto apply_coarse = [&](const std::vector<Sh_vector>& v, std::vector<Sh_vector>& y) { c.apply(v, y); };
        double coarse_residual = 0;
        stats_.coarse_iterations =
            pcg(xc, bc, apply_coarse, [&](std::size_t a, const Sh_vector& r) { return Sh_vector(c.diagonal_inverse[a] * r); },
                0.01 * opt_.linear_tolerance, nullptr, coarse_residual); // cheap: solve it well
        stats_.coarse_unknowns = 9 * na;
        internal::parallel_for_each_index(n, [&](std::size_t t) { x[t] = rotate_sh(c.U[t], xc[c.aggregate_of[t]]); });
      }
      stats_.linear_iterations =
          pcg(x, b, [&](const std::vector<Sh_vector>& v, std::vector<Sh_vector>& y) { e_.apply_linear(v, y); },
              [&](std::size_t i, const Sh_vector& r) { return e_.precondition(i, r); }, opt_.linear_tolerance,
              "linear initialisation", stats_.linear_residual);
      stats_.linear_iteration_limit_reached =
          stats_.linear_iterations >= opt_.max_linear_iterations && stats_.linear_residual > opt_.linear_tolerance;
    }
    s_ = std::move(x);
  }

  // Snaps the rotation of tetrahedron i to its hard constraint (if any) and
  // sets its SH vector: the last step of every start.
  void constrain(std::size_t i) {
    if (hard_constraint_held(i) && e_.constraint_of[i] >= 0) q_[i] = Energy::snap(q_[i], e_.constraints[e_.constraint_of[i]]);
    s_[i] = rotate_sh(q_[i], octahedral_reference_sh());
  }

  // The diffusion-projection (MBO) stage (Frame_field_options::diffusion_steps).
  // Returns what it did or why it did nothing, for the stage line; empty when off.
  std::string diffuse() {
    stats_.diffusion_steps = stats_.diffusion_iterations = 0;
    stats_.diffused_energy = stats_.projected_energy;
    if (opt_.diffusion_steps <= 0) return {};
    if (!(opt_.diffusion_length > 0) || !std::isfinite(opt_.diffusion_length))
      throw std::invalid_argument("the diffusion length must be a positive finite number (got " +
                                  format_number(opt_.diffusion_length) + ")");
    if (stats_.feature_edges > 0 && !opt_.diffusion_with_features)
      return "skipped: the domain has " + std::to_string(stats_.feature_edges) + " feature edges";
    const internal::Frame_field_coarse_level* coarse = use_coarse_level() ? &coarse_level() : nullptr;
    for (int k = 0; k < opt_.diffusion_steps; ++k) {
      double residual = 0;
      stats_.diffusion_iterations +=
          internal::implicit_diffusion_step(e_, s_, opt_.diffusion_length * opt_.diffusion_length,
                                            10 * opt_.linear_tolerance, opt_.max_linear_iterations, residual,
                                            coarse);
      project();
      ++stats_.diffusion_steps;
    }
    stats_.diffused_energy = smoothness_energy();
    return std::to_string(stats_.diffusion_steps) + " steps of length " + format_number(opt_.diffusion_length) + ", " +
           std::to_string(stats_.diffusion_iterations) + " CG iterations, energy " +
           format_number(stats_.diffused_energy);
  }

  void project() {
    const std::size_t n = size();
    q_.assign(n, Eigen::Quaterniond::Identity());
    std::vector<char> degenerate(n, 0);
    internal::parallel_for_each_index(n, [&](std::size_t i) {
      if (!(s_[i].norm() > 1e-9)) {
        degenerate[i] = 1;
      } else {
        q_[i] = Eigen::Quaterniond(rotation_from_octahedral_sh(s_[i]).rotation);
      }
      constrain(i);
    });
    stats_.degenerate_projections = std::count(degenerate.begin(), degenerate.end(), 1);
  }

  bool propagate(const std::vector<std::size_t>& tets, const std::vector<std::size_t>& local);

  // The tetrahedra an L-BFGS run turns: all of them, or a list (the others
  // fixed, their faces with the list counted once, from the list's side).
  struct Active_set {
    const std::vector<std::size_t>* list = nullptr; // null: all
    const std::vector<char>* marked = nullptr;      // per tetrahedron, with a list
    std::size_t n = 0;
    std::size_t tet(std::size_t k) const { return list ? (*list)[k] : k; }
    bool active(std::int64_t j) const { return !list || (*marked)[std::size_t(j)]; }
  };

  // The active set of a list, with marked_ and local_ (the position in the
  // list) set for its tetrahedra while it lives and cleared after (also on
  // an exception), so that a local re-optimisation costs time in proportion
  // to its list, not to the mesh.
  struct Marked {
    Frame_field_3& ff;
    const std::vector<std::size_t>& tets;
    Active_set set;
    Marked(Frame_field_3& f, const std::vector<std::size_t>& list) : ff(f), tets(list) {
      // The scratch is made on the first list (an empty one, all frames, needs none).
      if (!tets.empty() && ff.marked_.size() != ff.size())
        ff.marked_.assign(ff.size(), 0), ff.local_.assign(ff.size(), std::size_t(-1));
      for (std::size_t k = 0; k < tets.size(); ++k) ff.marked_[tets[k]] = 1, ff.local_[tets[k]] = k;
      set.list = &tets;
      set.marked = &ff.marked_;
      set.n = tets.size();
    }
    ~Marked() {
      for (std::size_t i : tets) ff.marked_[i] = 0, ff.local_[i] = std::size_t(-1);
    }
    Marked(const Marked&) = delete;
    Marked& operator=(const Marked&) = delete;
  };

  void relax(const std::vector<std::size_t>& tets, const Active_set& set, const std::vector<std::size_t>& local);

  double energy_and_gradient(const Active_set& set, std::vector<Eigen::Vector3d>* g) const;

  void refine();

  int lbfgs(const Active_set& set, int& evaluations, bool& limit, const char* stage, int memory);

  // Whether two option sets give the same set-up and face transports.
  static bool same_set_up(const Frame_field_options& a, const Frame_field_options& b) {
    return a.boundary_weight == b.boundary_weight && a.hard_boundary == b.hard_boundary &&
           a.feature_angle_deg == b.feature_angle_deg && a.crease_split_deg == b.crease_split_deg &&
           a.transport_tolerance == b.transport_tolerance && a.transport_scheme == b.transport_scheme;
  }

  void measure() {
    double sum = 0, mx = 0;
    for (const Boundary_face& b : e_.boundary) {
      const double e = alignment_error_deg(b);
      sum += e;
      mx = std::max(mx, e);
    }
    stats_.boundary_error_mean_deg = e_.boundary.empty() ? 0 : sum / double(e_.boundary.size());
    stats_.boundary_error_max_deg = mx;
    double worst = 0;
    for (std::size_t i = 0; i < size(); ++i) {
      const Eigen::Matrix3d F = frame(i);
      const Eigen::Matrix3d g = e_.sqrt_metric[i] * e_.sqrt_metric[i];
      worst = std::max(worst, (F.transpose() * g * F - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff());
    }
    stats_.max_orthonormality_error = worst;
  }

  Frame_field_options opt_;
  Frame_field_options prepared_with_; // the options of the last set-up
  Frame_field_statistics stats_;
  Energy e_;
  std::vector<Sh_vector> s_;
  std::vector<Eigen::Quaterniond> q_;
  std::vector<char> released_;     // per tetrahedron: hard constraint released (empty: none)
  std::vector<char> marked_;       // scratch of Marked: all 0 between calls
  std::optional<internal::Frame_field_coarse_level> coarse_; // between the initialisation and the refinement
  std::vector<std::size_t> local_; // scratch of Marked: all size_t(-1) between calls
  bool prepared_ = false;
};

} // namespace CGAL_ext

#include <CGAL_ext/internal/Frame_field_3_refinement.h>

#endif // CGAL_EXT_FRAME_FIELD_3_H
