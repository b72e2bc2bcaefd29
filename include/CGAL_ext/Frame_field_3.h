// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_FRAME_FIELD_3_H
#define CGAL_EXT_FRAME_FIELD_3_H

/// \file Frame_field_3.h
/// Metric-driven octahedral frame fields on a tetrahedral mesh (MATH.md
/// section 5; Fang et al., "Metric-Driven 3D Frame Field Generation", TVCG
/// 2023): one frame per tetrahedron, smooth after transport by the metric's
/// connection, aligned with the boundary in the metric.

#include <CGAL_ext/Cell_transport_3.h>
#include <CGAL_ext/Input_error.h>
#include <CGAL_ext/Metric_field_3.h>
#include <CGAL_ext/Octahedral_frame.h>
#include <CGAL_ext/Sharp_features_3.h>
#include <CGAL_ext/Tet_mesh_triangulation_3.h>
#include <CGAL_ext/internal/deterministic_parallel.h>
#include <CGAL_ext/internal/lbfgs_on_rotations.h>
#include <CGAL_ext/internal/preconditioned_conjugate_gradient.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/SVD>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <limits>
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
  /// of the conjugate gradients, the energy of L-BFGS), for progress display.
  std::function<void(const std::string& stage, int iteration, double measure)> iteration_progress;
};

/// \ingroup PkgCGALExtFrames
/// Figures of a `Frame_field_3::compute()` run.
struct Frame_field_statistics {
  /// Tetrahedra (frames).
  std::size_t tets = 0;
  /// Interior faces (smoothness terms) and boundary faces (alignment terms).
  std::size_t interior_faces = 0, boundary_faces = 0;
  /// Boundary tetrahedra with one hard axis, and with two (a frame fixed by
  /// two non-parallel boundary faces, e.g. along a sharp edge).
  std::size_t hard_one_axis = 0, hard_two_axes = 0;
  /// Feature edges, vertices on feature curves and corners (`Sharp_features_3`).
  std::size_t feature_edges = 0, feature_curve_vertices = 0, feature_corners = 0;
  /// Tetrahedra whose hard axes come from a feature: a corner's frame or a
  /// feature edge's tangent.
  std::size_t feature_tets = 0;
  /// Face transports that are exactly the identity (constant metric).
  std::size_t identity_transports = 0;
  /// Largest transport angle over the faces, in radians.
  double max_transport_angle = 0;
  /// Conjugate-gradient iterations of the initialisation and its final relative residual.
  int linear_iterations = 0;
  double linear_residual = 0;
  /// Conjugate-gradient iterations and unknowns of the coarse level (0 without one).
  int coarse_iterations = 0;
  std::size_t coarse_unknowns = 0;
  /// Tetrahedra whose initial SH vector was (near) zero and got the identity.
  std::size_t degenerate_projections = 0;
  /// L-BFGS iterations and energy evaluations.
  int refinement_iterations = 0, energy_evaluations = 0;
  /// Whether an iteration bound stopped a stage (`max_linear_iterations`
  /// before the CG residual reached `linear_tolerance`, or
  /// `max_refinement_iterations` while L-BFGS still made progress): reached
  /// only on pathological input, and said in the stage's progress line.
  bool linear_iteration_limit_reached = false, refinement_iteration_limit_reached = false;
  /// Smoothness energy `sum_f w_f |s_j - D(T_ij) s_i|^2` after the
  /// projection and at the end.
  double projected_energy = 0, smoothness_energy = 0;
  /// The sum of the face weights (the energy of the worst field is about
  /// twice this; `smoothness_energy / total_face_weight` is a mean).
  double total_face_weight = 0;
  /// Boundary alignment: angle between `A^{-1} n` and the nearest frame
  /// vector `F e_k`, in degrees, over the boundary faces.
  double boundary_error_mean_deg = 0, boundary_error_max_deg = 0;
  /// `max |F^T g F - I|` over the tetrahedra (entry-wise), `g` at the centroid.
  double max_orthonormality_error = 0;
  /// Seconds per stage: set-up (geometry, weights), face transports, linear
  /// initialisation, projection, refinement.
  double seconds_setup = 0, seconds_transports = 0, seconds_linear = 0, seconds_projection = 0,
         seconds_refinement = 0;
};

/// \ingroup PkgCGALExtFrames
/// An octahedral frame field in a metric: one rotation `R_i` per
/// tetrahedron, and the frame `F_i = A_i^{-1} R_i` (`A_i = g^{1/2}` at the
/// centroid), whose columns are the hex edge vectors, of unit length in the
/// metric (`F^T g F = I`).
///
/// **Energy.** With `s_i = D(R_i) s0` the band-4 SH vector of frame `i`
/// (Octahedral_frame.h) and, for each interior face `f` between tetrahedra
/// `i` and `j`, the transport `T(i->j)`,
/// `E = sum_f w_f |s_j - D(T(i->j)) s_i|^2` (MATH.md section 5). The weight
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
/// face centroid): `R e_k = +-d` (MATH.md section 5). In SH terms,
/// `D(R_d)^T s` (with `R_d e_z = d`) must have coefficients `m = -3..3` equal
/// to `(0, 0, 0, sqrt(7/12), 0, 0, 0)`: a linear condition, used as the soft
/// term `lambda w_b |P D(R_d)^T s - c|^2` with `w_b` the face's metric area over
/// the metric distance from the tetrahedron's centroid to the face centroid.
/// With `hard_boundary`, after the projection each boundary tetrahedron is
/// turned so that an axis is exactly on `d` of its largest boundary face (and
/// a second axis on a second face whose `d` is more than 30 degrees from
/// the first, projected orthogonally to it), and the refinement only
/// turns it about that axis (or not at all).
///
/// **Sharp features** (`Sharp_features_3`, `feature_angle_deg`). With
/// `hard_boundary`, a tetrahedron with a corner of the boundary takes the
/// corner's frame (two hard axes). One with a feature edge keeps an axis on
/// the feature curve's tangent `A t`; its rotation about it comes from its
/// boundary faces: if they agree, the largest face is followed exactly (and
/// the tangent as far as it allows); if they lie on both sides of a crease,
/// the frame takes the mean of their directions modulo a quarter turn, so
/// that they share the crease's angle; without boundary faces it is free.
///
/// **Method.** (1) Sparse linear initialisation: the quadratic energy plus
/// the soft boundary terms, minimised over unconstrained 9-vectors by
/// conjugate gradients with block-Jacobi preconditioning (matrix-free: the
/// 9x9 blocks `D(T)` are applied from the stored transports, so memory stays
/// linear with a small constant); (2) projection of each `s_i` onto the
/// octahedral variety (`rotation_from_octahedral_sh()`: coarse search plus
/// Newton on SO(3)); (3) L-BFGS on local rotations `R_i <- exp([w_i]_x) R_i`
/// with Armijo backtracking, until the energy converges.
///
/// **Determinism.** Every parallel loop writes per-tetrahedron data only, and
/// every sum is made of fixed blocks added in order, so the result does not
/// depend on the number of threads.
///
/// \tparam Metric_field a metric field such as `Metric_field_3<Tr>`: it
///         provides `triangulation()`, `A_at(c, p)`, `curl(c)` and `sqrt_metric(v)`
/// \tparam CellIndexMap a readable property map from cell handle to a 0-based
///         index, negative outside the domain; the domain's indices must be
///         exactly `0..n-1` (the tetrahedron order of the mesh file)
/// \tparam VertexIndexMap a readable property map from vertex handle to its
///         0-based index
template <class Metric_field, class CellIndexMap = Tet_mesh_cell_index_map,
          class VertexIndexMap = Tet_mesh_vertex_index_map>
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

  /// One boundary face: tetrahedron, local facet, Euclidean outward unit
  /// normal, the aligned direction `d = A^{-1} n / |A^{-1} n|` and the
  /// metric area.
  struct Boundary_face {
    std::size_t tet;           ///< tetrahedron index
    int facet;                 ///< the facet's index in the cell (its opposite vertex)
    Eigen::Vector3d normal;    ///< outward unit normal
    Eigen::Vector3d direction; ///< `A^{-1} n / |A^{-1} n|`, in the frame's (rotation) space
    double metric_area;        ///< area measured in the metric
  };

  /// Prepares the field: cells, neighbours, weights and boundary data.
  /// \param field the metric field; it and its triangulation must outlive this object
  /// \param cim the cell index map
  /// \param vim the vertex index map
  /// \throws Input_error if the domain's cell indices are not `0..n-1`, or
  ///         the domain is empty
  explicit Frame_field_3(const Metric_field& field, CellIndexMap cim = CellIndexMap(),
                         VertexIndexMap vim = VertexIndexMap())
      : field_(&field), cim_(cim), vim_(vim) {
    const Triangulation& tr = field.triangulation();
    if (tr.dimension() != 3) throw Input_error("", 0, "", "the triangulation is not three-dimensional");
    std::size_t n = 0;
    for (Cell_handle c : tr.finite_cell_handles())
      if (get(cim_, c) >= 0) ++n;
    if (n == 0) throw Input_error("", 0, "", "the mesh has no tetrahedra in its domain");
    cells_.assign(n, Cell_handle());
    for (Cell_handle c : tr.finite_cell_handles()) {
      const std::int64_t k = get(cim_, c);
      if (k < 0) continue;
      if (std::size_t(k) >= n || cells_[k] != Cell_handle())
        throw Input_error("", 0, "tetrahedron " + std::to_string(k + 1),
                          "cell indices of the domain must be exactly 0.." + std::to_string(n - 1));
      cells_[k] = c;
    }
    stats_.tets = n;
  }

  /// Computes the field: set-up, face transports, linear initialisation,
  /// projection, refinement (see the class documentation).
  /// \param options the options
  /// \returns the statistics (also kept, see `statistics()`)
  const Frame_field_statistics& compute(const Frame_field_options& options = {}) {
    prepare(options);
    Timer t;
    linear_initialisation();
    stats_.seconds_linear = t.lap();
    report("linear initialisation", stats_.seconds_linear,
           std::to_string(stats_.linear_iterations) + " CG iterations, residual " + format(stats_.linear_residual) +
               (stats_.coarse_unknowns ? " (after " + std::to_string(stats_.coarse_iterations) + " on a coarse level of " +
                                             std::to_string(stats_.coarse_unknowns / 9) + " aggregates)"
                                       : std::string()) +
               (stats_.linear_iteration_limit_reached ? "; stopped by the iteration limit" : ""));
    project();
    stats_.projected_energy = smoothness_energy();
    stats_.seconds_projection = t.lap();
    report("projection", stats_.seconds_projection, "energy " + format(stats_.projected_energy));
    refine();
    stats_.smoothness_energy = smoothness_energy();
    stats_.seconds_refinement = t.lap();
    report("refinement", stats_.seconds_refinement,
           std::to_string(stats_.refinement_iterations) + " L-BFGS iterations, energy " +
               format(stats_.smoothness_energy) +
               (stats_.refinement_iteration_limit_reached ? "; stopped by the iteration limit" : ""));
    measure();
    return stats_;
  }

  /// The first two stages of `compute()`: the geometry, weights and boundary
  /// data, and the face transports. `compute()` calls it; call it directly
  /// only before `set_rotations()`. Does nothing if already done.
  /// \param options the options (boundary weight and transport tolerance are used)
  void prepare(const Frame_field_options& options = {}) {
    opt_ = options;
    if (prepared_) return;
    Timer t;
    setup();
    stats_.seconds_setup = t.lap();
    report("set-up", stats_.seconds_setup,
           std::to_string(stats_.tets) + " tets, " + std::to_string(stats_.interior_faces) + " interior and " +
               std::to_string(stats_.boundary_faces) + " boundary faces");
    compute_transports();
    stats_.seconds_transports = t.lap();
    report("face transports", stats_.seconds_transports,
           std::to_string(stats_.identity_transports) + " exactly identity, largest angle " +
               format(stats_.max_transport_angle * 180 / M_PI) + " deg");
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

  /// The statistics of the last `compute()`.
  const Frame_field_statistics& statistics() const { return stats_; }

  /// The number of tetrahedra (frames).
  std::size_t size() const { return cells_.size(); }
  /// The metric field.
  const Metric_field& metric_field() const { return *field_; }
  /// The cell of tetrahedron `i`.
  /// \param i a tetrahedron index
  Cell_handle cell(std::size_t i) const { return cells_[i]; }
  /// The tetrahedron index of a domain cell, or -1.
  /// \param c a cell
  std::int64_t index(Cell_handle c) const { return get(cim_, c); }
  /// The 0-based index of a vertex.
  /// \param v a finite vertex
  std::size_t vertex_index(Vertex_handle v) const { return get(vim_, v); }

  /// The rotation `R_i`, as `canonicalize_frame()` (a deterministic
  /// representative of `{R_i G}`).
  /// \param i a tetrahedron index
  Eigen::Matrix3d rotation(std::size_t i) const { return canonicalize_frame(q_[i].toRotationMatrix()); }
  /// The frame `F_i = A_i^{-1} R_i`: columns are the three hex edge vectors,
  /// of unit length in the metric at the centroid.
  /// \param i a tetrahedron index
  Eigen::Matrix3d frame(std::size_t i) const { return A_[i].inverse() * rotation(i); }
  /// The parameter gradients `A_i R_i = F_i^{-T}`: column `k` is the
  /// gradient that the `k`-th parameter of an integer-grid map should have
  /// in tetrahedron `i` (row `k` of `F_i^{-1}`, the dual basis of the hex
  /// edges: `F^{-1} F = I`). Its length is the number of hex layers per
  /// unit length across that direction; for `g = I / h^2` it is `1 / h`.
  /// This is what CubeCover's `.fra` file holds.
  /// \param i a tetrahedron index
  Eigen::Matrix3d parameter_gradients(std::size_t i) const { return A_[i] * rotation(i); }
  /// `A = g^{1/2}` at the centroid of tetrahedron `i`.
  /// \param i a tetrahedron index
  const Eigen::Matrix3d& sqrt_metric(std::size_t i) const { return A_[i]; }
  /// The SH vector `s_i = D(R_i) s0` of tetrahedron `i`.
  /// \param i a tetrahedron index
  const Sh_vector& sh(std::size_t i) const { return s_[i]; }
  /// The centroid of tetrahedron `i`.
  /// \param i a tetrahedron index
  const Eigen::Vector3d& centroid(std::size_t i) const { return centroid_[i]; }
  /// The neighbour of tetrahedron `i` across its facet `f` (opposite
  /// `cell(i)->vertex(f)`), or -1 on the boundary.
  /// \param i a tetrahedron index
  /// \param f a facet index in 0..3
  std::int64_t neighbor(std::size_t i, int f) const { return links_[i].nb[f]; }
  /// The transport `T(j->i)` from the neighbour `j = neighbor(i, f)` into
  /// tetrahedron `i` (identity on the boundary).
  /// \param i a tetrahedron index
  /// \param f a facet index in 0..3
  Eigen::Matrix3d transport_into(std::size_t i, int f) const {
    return links_[i].identity[f] ? Eigen::Matrix3d::Identity() : links_[i].T_in[f].toRotationMatrix();
  }
  /// Half the smoothness energy density at tetrahedron `i`:
  /// `sum_f w_f |s_i - D(T(j->i)) s_j|^2 / 2` over its interior faces, divided
  /// by its volume (so that it sums, times the volumes, to the energy).
  /// \param i a tetrahedron index
  double energy_density(std::size_t i) const {
    return std::ldexp(0.5 * local_smoothness(i) / volume_[i], weight_exponent_);
  }
  /// The boundary faces, in tetrahedron order.
  const std::vector<Boundary_face>& boundary_faces() const { return boundary_; }
  /// The alignment error of a boundary face in degrees: the angle between
  /// `d` and the nearest of `+-R e_k`.
  /// \param b a boundary face
  double alignment_error_deg(const Boundary_face& b) const {
    const Eigen::Matrix3d R = q_[b.tet].toRotationMatrix();
    const double c = (R.transpose() * b.direction).cwiseAbs().maxCoeff();
    return std::acos(std::min(1.0, c)) * 180 / M_PI;
  }
  /// The smoothness energy `sum_f w_f |s_j - D(T(i->j)) s_i|^2` of the current frames.
  double smoothness_energy() const {
    const double internal_units = 0.5 * internal::deterministic_sum(size(), [&](std::size_t b, std::size_t e) {
                                    double s = 0;
                                    for (std::size_t i = b; i < e; ++i) s += local_smoothness(i);
                                    return s;
                                  });
    return std::ldexp(internal_units, weight_exponent_);
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
    propagated
  };

  /// Re-optimises the frames of some tetrahedra, all others fixed, as
  /// `compute()` does globally: a start (see `Reoptimize_start`) with the
  /// hard constraints applied, then L-BFGS on their rotations. The result
  /// depends on the surrounding frames, not on the previous frames of the
  /// tetrahedra given. The statistics are not updated (see
  /// `update_statistics()`). Used by `repair_singularities()`.
  /// \param tets the tetrahedron indices to re-optimise (distinct)
  /// \param start how the frames start
  /// \returns the L-BFGS iterations
  int reoptimize(const std::vector<std::size_t>& tets, Reoptimize_start start = Reoptimize_start::relaxed) {
    prepare(opt_);
    const std::size_t m = tets.size();
    if (m == 0) return 0;
    Active_set set;
    set.list = &tets;
    set.n = m;
    set.marked.assign(size(), 0);
    std::vector<std::size_t> local(size(), std::size_t(-1));
    for (std::size_t k = 0; k < m; ++k) set.marked[tets[k]] = 1, local[tets[k]] = k;
    if (start != Reoptimize_start::propagated || !propagate(tets, local)) relax(tets, set, local);
    internal::parallel_for_each_index(m, [&](std::size_t k) { constrain(tets[k]); });
    int evaluations = 0;
    bool limit = false;
    return lbfgs(set, evaluations, limit, nullptr);
  }

  /// The rotation `R_i` as the unit quaternion the optimiser holds (any
  /// representative of `{R_i G}`; `rotation()` gives the canonical one).
  /// \param i a tetrahedron index
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

  /// Recomputes the smoothness energy, boundary alignment and
  /// orthonormality of the statistics from the current frames.
  void update_statistics() {
    stats_.smoothness_energy = smoothness_energy();
    measure();
  }

private:
  struct Timer {
    std::chrono::steady_clock::time_point last = std::chrono::steady_clock::now();
    double lap() {
      const auto now = std::chrono::steady_clock::now();
      const double s = std::chrono::duration<double>(now - last).count();
      last = now;
      return s;
    }
  };
  // Per tetrahedron and local facet: neighbour (-1 on the boundary), face
  // weight, and the transport from the neighbour into this tetrahedron.
  struct Links {
    std::array<std::int64_t, 4> nb;
    std::array<double, 4> w;
    std::array<Eigen::Quaterniond, 4> T_in;
    std::array<bool, 4> identity;
  };
  // A boundary tetrahedron: the soft term s^T B s - 2 b.s + c, the block
  // preconditioner's inverse, and the hard constraint (0, 1 or 2 axes).
  struct Constraint {
    Sh_matrix B = Sh_matrix::Zero();
    Sh_vector b = Sh_vector::Zero();
    double c = 0;
    Sh_matrix preconditioner;
    int axes = 0;
    Eigen::Vector3d d1 = Eigen::Vector3d::Zero(), d2 = Eigen::Vector3d::Zero();
  };

  static std::string format(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", x);
    return buf;
  }
  void report(const char* stage, double seconds, const std::string& detail) const {
    if (opt_.progress) opt_.progress(stage, seconds, detail);
  }
  static Point_3 point(const Eigen::Vector3d& v) { return Point_3(v(0), v(1), v(2)); }
  static double metric_area(const Eigen::Matrix3d& A, const Eigen::Vector3d& n, double area) {
    // Nanson: the image of the area vector a n under x -> A x is det(A) A^{-T} a n.
    return A.determinant() * (A.inverse().transpose() * n).norm() * area;
  }

  // The axes a feature imposes on tetrahedron i (Euclidean directions; 0, 1
  // or 2 of them): the frame of its corner of smallest index if it has a
  // corner, else the tangent of its first feature edge (and a second one's
  // if it turns by more than the feature angle: two creases of a thin part).
  struct Feature_axes {
    int axes = 0;
    Eigen::Vector3d u1 = Eigen::Vector3d::Zero(), u2 = Eigen::Vector3d::Zero();
  };
  template <class Features>
  Feature_axes feature_axes(std::size_t i, const Features& features, double unit, double cos_feature) const {
    Feature_axes out;
    const Cell_handle c = cells_[i];
    std::array<std::size_t, 4> v;
    for (int k = 0; k < 4; ++k) v[k] = get(vim_, c->vertex(k));
    std::array<int, 4> by_index = {0, 1, 2, 3};
    std::sort(by_index.begin(), by_index.end(), [&](int a, int b) { return v[a] < v[b]; });
    for (int k : by_index)
      if (features.kind(v[k]) == Feature_vertex_kind::corner) {
        out.axes = 2;
        out.u1 = features.corner_axes(v[k]).col(0);
        out.u2 = features.corner_axes(v[k]).col(1);
        return out;
      }
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) {
        const std::size_t p = v[by_index[a]], q = v[by_index[b]];
        if (!features.is_feature_edge(p, q)) continue;
        const Eigen::Vector3d t = features.edge_tangent(p, q);
        if (out.axes == 0) {
          out.axes = 1;
          out.u1 = t;
        } else if (out.axes == 1 &&
                   std::abs((unit * A_[i] * t).normalized().dot((unit * A_[i] * out.u1).normalized())) < cos_feature) {
          out.axes = 2;
          out.u2 = t;
        }
      }
    return out;
  }

  void setup() {
    const std::size_t n = size();
    links_.assign(n, Links());
    A_.assign(n, Eigen::Matrix3d::Identity());
    centroid_.assign(n, Eigen::Vector3d::Zero());
    volume_.assign(n, 0.0);
    constraint_of_.assign(n, -1);
    internal::parallel_for_each_index(n, [&](std::size_t i) {
      const Cell_handle c = cells_[i];
      Eigen::Vector3d p[4];
      for (int k = 0; k < 4; ++k) p[k] = internal::to_eigen_vector(c->vertex(k)->point());
      centroid_[i] = (p[0] + p[1] + p[2] + p[3]) / 4;
      volume_[i] = std::abs((p[1] - p[0]).dot((p[2] - p[0]).cross(p[3] - p[0]))) / 6;
      A_[i] = field_->A_at(c, point(centroid_[i]));
    });
    // The weights are homogeneous of degree 1 in A: they are computed with A
    // divided by an even power of two 2^E near its largest entry, exactly,
    // so that no metric scale (1e-300 I as well as 1e300 I) under- or
    // overflows them, and the field is the same bits as without; the
    // energies are reported multiplied back by 2^E.
    double largest = 0;
    for (const Eigen::Matrix3d& A : A_) largest = std::max(largest, A.cwiseAbs().maxCoeff());
    std::frexp(largest, &weight_exponent_);
    weight_exponent_ += weight_exponent_ & 1; // even: square roots of the weights scale exactly too
    const double unit = std::ldexp(1.0, -weight_exponent_);
    internal::parallel_for_each_index(n, [&](std::size_t i) {
      const Cell_handle c = cells_[i];
      Links& L = links_[i];
      for (int f = 0; f < 4; ++f) {
        const Cell_handle nc = c->neighbor(f);
        const std::int64_t j = field_->triangulation().is_infinite(nc) ? -1 : get(cim_, nc);
        L.nb[f] = j;
        L.identity[f] = true;
        L.T_in[f] = Eigen::Quaterniond::Identity();
        L.w[f] = 0;
        // Each interior face's weight is computed by its smaller index and
        // copied to the other side below (symmetric bit for bit); boundary
        // weights come with the boundary data.
        if (j < 0 || std::size_t(j) < i) continue;
        Eigen::Vector3d fc, nrm;
        double area;
        internal::boundary_facet_geometry(c, f, fc, nrm, area);
        const Eigen::Matrix3d Af = unit * field_->A_at(c, point(fc));
        L.w[f] = metric_area(Af, nrm, area) / (Af * (centroid_[j] - centroid_[i])).norm();
      }
    });
    for (std::size_t i = 0; i < n; ++i)
      for (int f = 0; f < 4; ++f) {
        const std::int64_t j = links_[i].nb[f];
        if (j >= 0 && std::size_t(j) < i) links_[i].w[f] = links_[j].w[cells_[j]->index(cells_[i])];
      }
    // Boundary faces and constraints, in tetrahedron order.
    boundary_.clear();
    constraints_.clear();
    stats_.interior_faces = stats_.boundary_faces = stats_.hard_one_axis = stats_.hard_two_axes = 0;
    const Sharp_features_3<Metric_field, CellIndexMap, VertexIndexMap> features(*field_, opt_.feature_angle_deg, cim_,
                                                                               vim_);
    stats_.feature_edges = features.feature_edges().size();
    stats_.feature_curve_vertices = features.number_of_curve_vertices();
    stats_.feature_corners = features.number_of_corners();
    stats_.feature_tets = 0;
    const double cos_feature = std::cos(opt_.feature_angle_deg * M_PI / 180);
    total_weight_ = 0;
    std::vector<double> scaled_area; // metric areas in the weights' unit, per boundary face
    const Sh_vector s0 = octahedral_reference_sh();
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t first = boundary_.size();
      for (int f = 0; f < 4; ++f) {
        if (links_[i].nb[f] >= 0) {
          if (std::size_t(links_[i].nb[f]) > i) {
            ++stats_.interior_faces;
            total_weight_ += links_[i].w[f];
          }
          continue;
        }
        Eigen::Vector3d fc, nrm;
        double area;
        internal::boundary_facet_geometry(cells_[i], f, fc, nrm, area);
        const Eigen::Matrix3d Af = unit * field_->A_at(cells_[i], point(fc));
        Boundary_face bf;
        bf.tet = i;
        bf.facet = f;
        bf.normal = nrm;
        bf.direction = Af.inverse() * nrm;
        bf.direction.normalize();
        scaled_area.push_back(metric_area(Af, nrm, area));
        bf.metric_area = std::ldexp(scaled_area.back(), 2 * weight_exponent_); // degree 2 in A
        links_[i].w[f] = opt_.boundary_weight * scaled_area.back() / (Af * (fc - centroid_[i])).norm();
        boundary_.push_back(bf);
      }
      const Feature_axes fa = feature_axes(i, features, unit, cos_feature);
      if (boundary_.size() == first && fa.axes == 0) continue;
      Constraint C;
      // A soft term: the frame should have an axis on d (rotation about d free).
      auto add_soft_term = [&](const Eigen::Vector3d& d, double w) {
        const Sh_matrix D = sh_rotation(Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), d));
        Sh_matrix M = Sh_matrix::Identity();
        M(0, 0) = M(8, 8) = 0; // m = +-4 are free (rotation about d)
        C.B += w * D * M * D.transpose();
        C.b += w * s0(4) * D.col(4);
        C.c += w * s0(4) * s0(4);
      };
      for (std::size_t k = first; k < boundary_.size(); ++k)
        add_soft_term(boundary_[k].direction, links_[i].w[boundary_[k].facet]);
      // The boundary faces by decreasing metric area.
      std::vector<std::size_t> order;
      for (std::size_t k = first; k < boundary_.size(); ++k) order.push_back(k);
      std::stable_sort(order.begin(), order.end(),
                       [&](std::size_t a, std::size_t b) { return scaled_area[a] > scaled_area[b]; });
      if (fa.axes > 0) {
        // The feature's axes, mapped by A into the rotation's space (the
        // frame's axes are A^{-1} R e_k). They are hard constraints only:
        // as soft terms in the linear initialisation, next to the faces'
        // terms, they raised the energy and the non-meshable edges of
        // CGAL's anchor (doc/benchmarks.md).
        C.d1 = (unit * A_[i] * fa.u1).normalized();
        C.axes = 1;
        if (fa.axes == 2) {
          C.d2 = (unit * A_[i] * fa.u2).normalized();
          C.d2 = (C.d2 - C.d2.dot(C.d1) * C.d1).normalized();
          C.axes = 2;
        } else {
          // The rotation about the tangent, from the boundary faces: their
          // normals, projected orthogonally to the tangent, at angles
          // theta_k from the largest one's (faces within 30 degrees of the
          // tangent say nothing and are skipped). If they agree (each within
          // the feature angle of an axis of that face's frame), that face is
          // followed exactly and the tangent as far as it allows. Faces on both sides of a crease disagree: the frame then
          // takes the mean of the theta_k modulo a quarter turn, arg(sum
          // e^{4 i theta_k}) / 4, which shares the crease's angle between
          // them (22.5 degrees each on a 45-degree crease, where following
          // the largest face put all 45 on the other one). The faces' soft
          // terms cannot decide it: on a 45-degree crease their sum does not
          // depend on the rotation.
          Eigen::Vector3d p1 = Eigen::Vector3d::Zero();
          std::size_t face1 = 0; // the face p1 comes from
          bool agree = true;
          std::complex<double> sum = 0;
          for (std::size_t k : order) {
            const Eigen::Vector3d& d = boundary_[k].direction;
            Eigen::Vector3d p = d - d.dot(C.d1) * C.d1;
            if (p.norm() < 0.5) continue; // within 30 degrees of the tangent: says nothing about the rotation
            p.normalize();
            if (p1.isZero()) p1 = p, face1 = k;
            const double theta = std::atan2(p.dot(C.d1.cross(p1)), p.dot(p1));
            sum += std::polar(1.0, 4 * theta);
            agree = agree && std::max(std::abs(p.dot(p1)), std::abs(p.dot(C.d1.cross(p1)))) >= cos_feature;
          }
          if (!p1.isZero() && agree) {
            const Eigen::Vector3d t = C.d1;
            C.d1 = boundary_[face1].direction;
            C.d2 = (t - t.dot(C.d1) * C.d1).normalized();
            C.axes = 2;
          } else if (!p1.isZero()) {
            C.d2 = Eigen::AngleAxisd(std::arg(sum) / 4, C.d1) * p1;
            C.axes = 2;
          }
        }
        if (opt_.hard_boundary) ++stats_.feature_tets;
      } else {
        // Hard axes: the largest metric area first, then a face more than
        // 30 degrees away from it (two faces of one tetrahedron meet at an
        // edge: beyond the feature angle it is a feature edge, handled above).
        C.d1 = boundary_[order[0]].direction;
        C.axes = 1;
        for (std::size_t k = 1; k < order.size(); ++k) {
          const Eigen::Vector3d& d = boundary_[order[k]].direction;
          if (std::abs(d.dot(C.d1)) < std::cos(M_PI / 6)) {
            C.d2 = (d - d.dot(C.d1) * C.d1).normalized();
            C.axes = 2;
            break;
          }
        }
      }
      if (opt_.hard_boundary) ++(C.axes == 2 ? stats_.hard_two_axes : stats_.hard_one_axis);
      constraint_of_[i] = std::int64_t(constraints_.size());
      constraints_.push_back(C);
    }
    stats_.boundary_faces = boundary_.size();
    stats_.total_face_weight = std::ldexp(total_weight_, weight_exponent_);
    // Block-Jacobi preconditioner: (sum of the face weights) I + B.
    diagonal_.assign(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      double s = 0;
      for (int f = 0; f < 4; ++f)
        if (links_[i].nb[f] >= 0) s += links_[i].w[f];
      diagonal_[i] = s;
      if (constraint_of_[i] >= 0) {
        Constraint& C = constraints_[constraint_of_[i]];
        const Sh_matrix H = s * Sh_matrix::Identity() + C.B;
        C.preconditioner = H.llt().solve(Sh_matrix::Identity());
      }
    }
  }

  void compute_transports() {
    const std::size_t n = size();
    Transport_options topt;
    topt.tolerance = opt_.transport_tolerance;
    topt.scheme = opt_.transport_scheme;
    std::vector<double> max_angle(n, 0.0);
    // Failures are kept per tetrahedron and the first one in index order is
    // reported: the same error whatever the number of threads. Indices above
    // a failure found are skipped; those below are all done, so that first
    // one is the same.
    std::vector<std::exception_ptr> failure(n);
    std::vector<std::int64_t> unconverged(n, -1); // the neighbour across a face whose transport did not converge
    std::atomic<std::size_t> first_failure(n);
    auto failed = [&](std::size_t i) {
      for (std::size_t f = first_failure.load(); i < f && !first_failure.compare_exchange_weak(f, i);) {
      }
    };
    // The smaller index of each face computes T(i->j) and writes both sides;
    // no other thread touches those two slots.
    internal::parallel_for_each_index(n, [&](std::size_t i) {
      if (i > first_failure.load(std::memory_order_relaxed)) return;
      const Cell_handle c = cells_[i];
      try {
      for (int f = 0; f < 4; ++f) {
        const std::int64_t j = links_[i].nb[f];
        if (j < 0 || std::size_t(j) < i) continue;
        const Cell_handle cj = cells_[j];
        Eigen::Vector3d fc, nrm;
        double area;
        internal::boundary_facet_geometry(c, f, fc, nrm, area);
        const Point_3 pf = point(fc);
        const Transport_result a = cell_transport(*field_, c, point(centroid_[i]), pf, topt);
        const Transport_result b = cell_transport(*field_, cj, pf, point(centroid_[j]), topt);
        if (!a.converged || !b.converged) {
          unconverged[i] = j;
          failed(i);
          return;
        }
        const Eigen::Matrix3d T = b.rotation * a.rotation; // T(i->j), pieces left-multiplied
        const int fj = cj->index(c);
        if (T == Eigen::Matrix3d::Identity()) continue; // both slots stay identity
        const Eigen::Quaterniond q(T);
        links_[j].T_in[fj] = q.normalized();
        links_[j].identity[fj] = false;
        links_[i].T_in[f] = q.conjugate().normalized();
        links_[i].identity[f] = false;
        max_angle[i] = std::max(max_angle[i], rotation_angle(T));
      }
      } catch (...) {
        failure[i] = std::current_exception();
        failed(i);
      }
    });
    for (std::size_t i = 0; i < n; ++i) {
      if (failure[i]) std::rethrow_exception(failure[i]);
      if (unconverged[i] < 0) continue;
      const std::size_t j = std::size_t(unconverged[i]);
      // The largest change of A between two of their vertices: |A_u^{-1} A_v| (spectral norm).
      double change = 1;
      for (const Cell_handle a : {cells_[i], cells_[j]})
        for (const Cell_handle b : {cells_[i], cells_[j]})
          for (int u = 0; u < 4; ++u)
            for (int v = 0; v < 4; ++v) {
              const Eigen::Matrix3d M = field_->sqrt_metric(a->vertex(u)).inverse() * field_->sqrt_metric(b->vertex(v));
              change = std::max(change, Eigen::JacobiSVD<Eigen::Matrix3d>(M).singularValues()(0));
            }
      throw Input_error("", 0, "tetrahedra " + std::to_string(i + 1) + " and " + std::to_string(j + 1),
                        "the transport across their shared face does not converge: the metric changes too fast "
                        "there (its square root by a factor of up to " + format(change) +
                            " between their vertices); refine the mesh there or smooth the metric");
    }
    stats_.identity_transports = 0;
    stats_.max_transport_angle = 0;
    for (std::size_t i = 0; i < n; ++i) {
      stats_.max_transport_angle = std::max(stats_.max_transport_angle, max_angle[i]);
      for (int f = 0; f < 4; ++f)
        if (links_[i].nb[f] > std::int64_t(i) && links_[i].identity[f]) ++stats_.identity_transports;
    }
  }

  // D(T(j->i)) s_j for the neighbour across facet f of i.
  Sh_vector neighbour_sh(std::size_t i, int f, const std::vector<Sh_vector>& s) const {
    const Links& L = links_[i];
    const Sh_vector& sj = s[L.nb[f]];
    return L.identity[f] ? sj : rotate_sh(L.T_in[f], sj);
  }

  // y = H x for the linear initialisation (half the Hessian of the quadratic energy).
  void apply_linear(const std::vector<Sh_vector>& x, std::vector<Sh_vector>& y) const {
    internal::parallel_for_each_index(size(), [&](std::size_t i) {
      const Links& L = links_[i];
      Sh_vector r = diagonal_[i] * x[i];
      for (int f = 0; f < 4; ++f)
        if (L.nb[f] >= 0) r -= L.w[f] * neighbour_sh(i, f, x);
      if (constraint_of_[i] >= 0) r += constraints_[constraint_of_[i]].B * x[i];
      y[i] = r;
    });
  }
  Sh_vector precondition(std::size_t i, const Sh_vector& r) const {
    if (constraint_of_[i] >= 0) return constraints_[constraint_of_[i]].preconditioner * r;
    return diagonal_[i] > 0 ? Sh_vector(r / diagonal_[i]) : r;
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

  // The coarse level of the initialisation: aggregates of neighbouring
  // tetrahedra (connected parts of the cells of a uniform grid), each with
  // one SH vector s_a, and s_i = D(U_i) s_a on its tetrahedra, U_i the
  // composed face transports from the aggregate's first tetrahedron along a
  // breadth-first tree. So a field parallel along the tree is represented
  // exactly, and the Galerkin operator P^T H P has the same structure as H,
  // with blocks -w D(U_i^T T(j->i) U_j) between aggregates.
  struct Coarse_level {
    std::vector<std::size_t> aggregate_of, first, members;
    std::vector<Eigen::Quaterniond> U;
    std::vector<std::vector<std::pair<std::size_t, Sh_matrix>>> rows; // the diagonal block first
    std::vector<Sh_matrix> diagonal_inverse;
  };

  Coarse_level build_coarse_level(int aggregate_size) const {
    const std::size_t n = size();
    Coarse_level c;
    // Grid cells holding about `aggregate_size` tetrahedra on average.
    Eigen::Vector3d lo = centroid_[0], hi = centroid_[0];
    double volume = 0;
    for (std::size_t i = 0; i < n; ++i) {
      lo = lo.cwiseMin(centroid_[i]), hi = hi.cwiseMax(centroid_[i]);
      volume += volume_[i];
    }
    const double edge = std::cbrt(volume * aggregate_size / double(n));
    auto key = [&](std::size_t i) {
      const Eigen::Vector3d g = (centroid_[i] - lo) / edge;
      const std::uint64_t m = 1 << 20;
      return (std::uint64_t(g(0)) * m + std::uint64_t(g(1))) * m + std::uint64_t(g(2));
    };
    const std::size_t none = std::size_t(-1);
    c.aggregate_of.assign(n, none);
    c.U.assign(n, Eigen::Quaterniond::Identity());
    c.members.reserve(n);
    for (std::size_t seed = 0; seed < n; ++seed) {
      if (c.aggregate_of[seed] != none) continue;
      const std::size_t a = c.first.size();
      c.first.push_back(c.members.size());
      const std::uint64_t k = key(seed);
      c.aggregate_of[seed] = a;
      c.members.push_back(seed);
      for (std::size_t head = c.first.back(); head < c.members.size(); ++head) {
        const std::size_t t = c.members[head];
        for (int f = 0; f < 4; ++f) {
          const std::int64_t j = links_[t].nb[f];
          if (j < 0 || c.aggregate_of[j] != none || key(j) != k) continue;
          c.aggregate_of[j] = a;
          const int fj = cells_[j]->index(cells_[t]);
          const Links& L = links_[j];
          c.U[j] = L.identity[fj] ? c.U[t] : (L.T_in[fj] * c.U[t]).normalized(); // U_j = T(t->j) U_t
          c.members.push_back(j);
        }
      }
    }
    const std::size_t na = c.first.size();
    c.first.push_back(n);
    c.rows.assign(na, {});
    c.diagonal_inverse.assign(na, Sh_matrix::Identity());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, na, 16), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t a = r.begin(); a != r.end(); ++a) {
        auto& row = c.rows[a];
        row.emplace_back(a, Sh_matrix::Zero());
        for (std::size_t m = c.first[a]; m < c.first[a + 1]; ++m) {
          const std::size_t t = c.members[m];
          row[0].second.diagonal().array() += diagonal_[t];
          if (constraint_of_[t] >= 0) {
            const Sh_matrix D = sh_rotation(c.U[t]);
            row[0].second += D.transpose() * constraints_[constraint_of_[t]].B * D;
          }
          for (int f = 0; f < 4; ++f) {
            const std::int64_t j = links_[t].nb[f];
            if (j < 0) continue;
            const Eigen::Quaterniond T = links_[t].identity[f] ? Eigen::Quaterniond::Identity() : links_[t].T_in[f];
            const Sh_matrix block = -links_[t].w[f] * sh_rotation(Eigen::Quaterniond(c.U[t].conjugate() * T * c.U[j]));
            const std::size_t J = c.aggregate_of[j];
            std::size_t k = 0;
            while (k < row.size() && row[k].first != J) ++k;
            if (k == row.size()) row.emplace_back(J, Sh_matrix::Zero());
            row[k].second += block;
          }
        }
        c.diagonal_inverse[a] = row[0].second.llt().solve(Sh_matrix::Identity());
      }
    });
    return c;
  }

  void linear_initialisation() {
    const std::size_t n = size();
    std::vector<Sh_vector> x(n, Sh_vector::Zero()), b(n, Sh_vector::Zero());
    for (std::size_t i = 0; i < n; ++i)
      if (constraint_of_[i] >= 0) b[i] = constraints_[constraint_of_[i]].b;
    stats_.linear_iterations = stats_.coarse_iterations = 0;
    stats_.linear_iteration_limit_reached = false;
    stats_.linear_residual = 0;
    stats_.coarse_unknowns = 0;
    if (internal::block_dot(b, b) > 0) {
      if (opt_.aggregate_size > 1 && n >= std::size_t(8 * opt_.aggregate_size)) {
        // Nested iteration: the coarse solution, prolonged, starts the fine
        // iteration with the smooth part of the solution already in place.
        const Coarse_level c = build_coarse_level(opt_.aggregate_size);
        const std::size_t na = c.rows.size();
        std::vector<Sh_vector> xc(na, Sh_vector::Zero()), bc(na, Sh_vector::Zero());
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, na, 16), [&](const tbb::blocked_range<std::size_t>& r) {
          for (std::size_t a = r.begin(); a != r.end(); ++a)
            for (std::size_t m = c.first[a]; m < c.first[a + 1]; ++m) {
              const std::size_t t = c.members[m];
              if (constraint_of_[t] >= 0) bc[a] += rotate_sh(c.U[t].conjugate(), b[t]);
            }
        });
        auto apply_coarse = [&](const std::vector<Sh_vector>& v, std::vector<Sh_vector>& y) {
          internal::parallel_for_each_index(na, [&](std::size_t a) {
            Sh_vector sum = Sh_vector::Zero();
            for (const auto& [J, B] : c.rows[a]) sum += B * v[J];
            y[a] = sum;
          });
        };
        double coarse_residual = 0;
        stats_.coarse_iterations =
            pcg(xc, bc, apply_coarse, [&](std::size_t a, const Sh_vector& r) { return Sh_vector(c.diagonal_inverse[a] * r); },
                0.01 * opt_.linear_tolerance, nullptr, coarse_residual); // cheap: solve it well
        stats_.coarse_unknowns = 9 * na;
        internal::parallel_for_each_index(n, [&](std::size_t t) { x[t] = rotate_sh(c.U[t], xc[c.aggregate_of[t]]); });
      }
      stats_.linear_iterations =
          pcg(x, b, [&](const std::vector<Sh_vector>& v, std::vector<Sh_vector>& y) { apply_linear(v, y); },
              [&](std::size_t i, const Sh_vector& r) { return precondition(i, r); }, opt_.linear_tolerance,
              "linear initialisation", stats_.linear_residual);
      stats_.linear_iteration_limit_reached =
          stats_.linear_iterations >= opt_.max_linear_iterations && stats_.linear_residual > opt_.linear_tolerance;
    }
    s_ = std::move(x);
  }

  // Turns R so that its axes satisfy the hard constraint C exactly.
  static Eigen::Quaterniond snap(const Eigen::Quaterniond& q, const Constraint& C) {
    Eigen::Matrix3d R = q.toRotationMatrix();
    const Eigen::Vector3d c1 = R.transpose() * C.d1;
    int k;
    c1.cwiseAbs().maxCoeff(&k);
    const Eigen::Vector3d a = (c1(k) < 0 ? -1.0 : 1.0) * R.col(k);
    Eigen::Quaterniond out = Eigen::Quaterniond::FromTwoVectors(a, C.d1) * q;
    if (C.axes == 2) {
      R = out.toRotationMatrix();
      int k2 = -1;
      double best = -1;
      for (int m = 0; m < 3; ++m) {
        if (m == k) continue;
        const double v = std::abs(R.col(m).dot(C.d2));
        if (v > best) best = v, k2 = m;
      }
      const Eigen::Vector3d b = (R.col(k2).dot(C.d2) < 0 ? -1.0 : 1.0) * R.col(k2);
      const double angle = std::atan2(b.cross(C.d2).dot(C.d1), b.dot(C.d2));
      out = Eigen::Quaterniond(Eigen::AngleAxisd(angle, C.d1)) * out;
    }
    return out.normalized();
  }

  // Snaps the rotation of tetrahedron i to its hard constraint (if any) and
  // sets its SH vector: the last step of every start.
  void constrain(std::size_t i) {
    if (opt_.hard_boundary && constraint_of_[i] >= 0) q_[i] = snap(q_[i], constraints_[constraint_of_[i]]);
    s_[i] = rotate_sh(q_[i], octahedral_reference_sh());
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

  // sum_f w_f |s_i - D(T(j->i)) s_j|^2 over the interior faces of i.
  double local_smoothness(std::size_t i) const {
    double e = 0;
    for (int f = 0; f < 4; ++f)
      if (links_[i].nb[f] >= 0) e += links_[i].w[f] * (s_[i] - neighbour_sh(i, f, s_)).squaredNorm();
    return e;
  }

  // The `propagated` start of reoptimize(): breadth-first from the fixed
  // neighbours, each frame transported from the tetrahedron that reached it
  // (its first facet towards one). False, with nothing changed, if no fixed
  // neighbour reaches some of the tetrahedra.
  // `local` gives the position of a tetrahedron in `tets`, or size_t(-1).
  bool propagate(const std::vector<std::size_t>& tets, const std::vector<std::size_t>& local) {
    const std::size_t none = std::size_t(-1);
    std::vector<std::size_t> queue;
    std::vector<char> done(tets.size(), 0);
    std::vector<Eigen::Quaterniond> q(tets.size());
    auto reach = [&](std::size_t k, std::size_t i, int f, const Eigen::Quaterniond& from) {
      q[k] = links_[i].identity[f] ? from : (links_[i].T_in[f] * from).normalized();
      done[k] = 1;
      queue.push_back(k);
    };
    for (std::size_t k = 0; k < tets.size(); ++k)
      for (int f = 0; f < 4; ++f) {
        const std::int64_t j = links_[tets[k]].nb[f];
        if (j >= 0 && local[j] == none) {
          reach(k, tets[k], f, q_[j]);
          break;
        }
      }
    for (std::size_t head = 0; head < queue.size(); ++head) {
      const std::size_t i = tets[queue[head]];
      for (int f = 0; f < 4; ++f) {
        const std::int64_t j = links_[i].nb[f];
        if (j < 0 || local[j] == none || done[local[j]]) continue;
        const int fj = cells_[j]->index(cells_[i]);
        reach(local[j], std::size_t(j), fj, q[queue[head]]);
      }
    }
    if (queue.size() < tets.size()) return false;
    for (std::size_t k = 0; k < tets.size(); ++k) q_[tets[k]] = q[k];
    return true;
  }

  // The tetrahedra an L-BFGS run turns: all of them, or a list (the others
  // fixed, their faces with the list counted once, from the list's side).
  struct Active_set {
    const std::vector<std::size_t>* list = nullptr; // null: all
    std::vector<char> marked;                        // per tetrahedron, with a list
    std::size_t n = 0;
    std::size_t tet(std::size_t k) const { return list ? (*list)[k] : k; }
    bool active(std::int64_t j) const { return !list || marked[std::size_t(j)]; }
  };

  // The `relaxed` start of reoptimize(): the linear initialisation on the
  // list (H x = b with the frames outside on the right-hand side), projected
  // onto rotations. `local` as in propagate().
  void relax(const std::vector<std::size_t>& tets, const Active_set& set, const std::vector<std::size_t>& local) {
    const std::size_t m = tets.size();
    std::vector<Sh_vector> x(m, Sh_vector::Zero()), b(m, Sh_vector::Zero());
    internal::parallel_for_each_index(m, [&](std::size_t k) {
      const std::size_t i = tets[k];
      if (constraint_of_[i] >= 0) b[k] = constraints_[constraint_of_[i]].b;
      for (int f = 0; f < 4; ++f)
        if (links_[i].nb[f] >= 0 && !set.marked[links_[i].nb[f]]) b[k] += links_[i].w[f] * neighbour_sh(i, f, s_);
    });
    auto apply = [&](const std::vector<Sh_vector>& v, std::vector<Sh_vector>& y) {
      internal::parallel_for_each_index(m, [&](std::size_t k) {
        const std::size_t i = tets[k];
        const Links& L = links_[i];
        Sh_vector r = diagonal_[i] * v[k];
        for (int f = 0; f < 4; ++f) {
          if (L.nb[f] < 0 || !set.marked[L.nb[f]]) continue;
          const Sh_vector& vj = v[local[L.nb[f]]];
          r -= L.w[f] * (L.identity[f] ? vj : Sh_vector(rotate_sh(L.T_in[f], vj)));
        }
        if (constraint_of_[i] >= 0) r += constraints_[constraint_of_[i]].B * v[k];
        y[k] = r;
      });
    };
    double residual = 0;
    pcg(x, b, apply, [&](std::size_t k, const Sh_vector& r) { return precondition(tets[k], r); }, 1e-8, nullptr,
        residual);
    internal::parallel_for_each_index(m, [&](std::size_t k) {
      if (x[k].norm() > 1e-9) q_[tets[k]] = Eigen::Quaterniond(rotation_from_octahedral_sh(x[k]).rotation);
    });
  }

  // The refinement energy (smoothness + soft boundary terms) of the active
  // tetrahedra and its gradient in their left-trivialised rotation
  // increments, projected on the free axes; the frames are s_.
  double energy_and_gradient(const Active_set& set, std::vector<Eigen::Vector3d>* g) const {
    return internal::deterministic_sum(set.n, [&](std::size_t first, std::size_t last) {
      double e = 0;
      for (std::size_t k = first; k < last; ++k) {
        const std::size_t i = set.tet(k);
        const Links& L = links_[i];
        Sh_vector grad = Sh_vector::Zero();
        for (int f = 0; f < 4; ++f) {
          if (L.nb[f] < 0) continue;
          const Sh_vector r = s_[i] - neighbour_sh(i, f, s_);
          // A face between two active tetrahedra is seen from both sides.
          e += (set.active(L.nb[f]) ? 0.5 : 1.0) * L.w[f] * r.squaredNorm();
          grad += (2 * L.w[f]) * r;
        }
        const std::int64_t c = constraint_of_[i];
        if (c >= 0) {
          const Constraint& C = constraints_[c];
          const Sh_vector Bs = C.B * s_[i];
          e += s_[i].dot(Bs) - 2 * C.b.dot(s_[i]) + C.c;
          grad += 2 * (Bs - C.b);
        }
        if (g) {
          Eigen::Vector3d gi = sh_rotation_jacobian(s_[i]).transpose() * grad;
          if (opt_.hard_boundary && c >= 0) {
            const Constraint& C = constraints_[c];
            gi = C.axes == 2 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(gi.dot(C.d1) * C.d1);
          }
          (*g)[k] = gi;
        }
      }
      return e;
    });
  }

  void refine() {
    Active_set all;
    all.n = size();
    int evaluations = 0;
    stats_.refinement_iterations = lbfgs(all, evaluations, stats_.refinement_iteration_limit_reached, "refinement");
    stats_.energy_evaluations = evaluations;
  }

  // L-BFGS on the rotations of the active tetrahedra, until the energy
  // converges (see `energy_tolerance`). Returns the iterations; `evaluations`
  // gets the energy evaluations, `limit` whether the iteration bound stopped
  // it. `stage` names the iterations for the progress callback (or null).
  int lbfgs(const Active_set& set, int& evaluations, bool& limit, const char* stage) {
    const std::size_t n = set.n;
    evaluations = 0;
    limit = false;
    if (opt_.max_refinement_iterations <= 0 || n == 0) return 0;
    const Sh_vector s0 = octahedral_reference_sh();
    // d^2 E / dw_i^2 ~ 2 (sum of the weights of i) J^T J, and J^T J = (20/3) I.
    std::vector<double> inverse_diagonal(n);
    for (std::size_t k = 0; k < n; ++k) {
      double sum = 0;
      for (int f = 0; f < 4; ++f) sum += links_[set.tet(k)].w[f];
      inverse_diagonal[k] = sum > 0 ? 3 / (40 * sum) : 1;
    }
    // The accepted rotations; trial steps are written into q_ and s_.
    std::vector<Eigen::Quaterniond> q_old(n);
    for (std::size_t k = 0; k < n; ++k) q_old[k] = q_[set.tet(k)];
    internal::Lbfgs_settings settings;
    settings.max_iterations = opt_.max_refinement_iterations;
    settings.memory = opt_.lbfgs_memory;
    settings.energy_tolerance = opt_.energy_tolerance;
    settings.floor_energy = 1e-14 * std::max(total_weight_, 1e-300);
    const internal::Lbfgs_outcome out = internal::lbfgs_on_rotations(
        inverse_diagonal, [&](std::vector<Eigen::Vector3d>& g) { return energy_and_gradient(set, &g); },
        [&](const std::vector<Eigen::Vector3d>& p, double step) {
          internal::parallel_for_each_index(n, [&](std::size_t k) {
            const std::size_t i = set.tet(k);
            q_[i] = step == 0 ? q_old[k] : (internal::oct_quaternion_exp(step * p[k]) * q_old[k]).normalized();
            s_[i] = rotate_sh(q_[i], s0);
          });
        },
        [&] { internal::parallel_for_each_index(n, [&](std::size_t k) { q_old[k] = q_[set.tet(k)]; }); },
        [&](int it, double E) {
          if (stage && opt_.iteration_progress) opt_.iteration_progress(stage, it, std::ldexp(E, weight_exponent_));
        },
        settings);
    evaluations = out.evaluations;
    limit = out.limit;
    if (opt_.hard_boundary) // undo the rounding drift of the constrained axes
      internal::parallel_for_each_index(n, [&](std::size_t k) {
        const std::size_t i = set.tet(k);
        if (constraint_of_[i] >= 0) constrain(i);
      });
    return out.iterations;
  }

  void measure() {
    double sum = 0, mx = 0;
    for (const Boundary_face& b : boundary_) {
      const double e = alignment_error_deg(b);
      sum += e;
      mx = std::max(mx, e);
    }
    stats_.boundary_error_mean_deg = boundary_.empty() ? 0 : sum / double(boundary_.size());
    stats_.boundary_error_max_deg = mx;
    double worst = 0;
    for (std::size_t i = 0; i < size(); ++i) {
      const Eigen::Matrix3d F = frame(i);
      const Eigen::Matrix3d g = A_[i] * A_[i];
      worst = std::max(worst, (F.transpose() * g * F - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff());
    }
    stats_.max_orthonormality_error = worst;
  }

  const Metric_field* field_;
  CellIndexMap cim_;
  VertexIndexMap vim_;
  Frame_field_options opt_;
  Frame_field_statistics stats_;
  std::vector<Cell_handle> cells_;
  std::vector<Links> links_;
  std::vector<Eigen::Matrix3d> A_;
  std::vector<Eigen::Vector3d> centroid_;
  std::vector<double> volume_, diagonal_;
  std::vector<Boundary_face> boundary_;
  std::vector<Constraint> constraints_;
  std::vector<std::int64_t> constraint_of_;
  std::vector<Sh_vector> s_;
  std::vector<Eigen::Quaterniond> q_;
  bool prepared_ = false;
  int weight_exponent_ = 0; // the face weights are in units of 2^weight_exponent_
  double total_weight_ = 0; // the sum of the interior face weights, in that unit
};

} // namespace CGAL_ext

#endif // CGAL_EXT_FRAME_FIELD_3_H
