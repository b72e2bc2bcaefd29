// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_INTERNAL_FRAME_FIELD_ENERGY_3_H
#define CGAL_EXT_INTERNAL_FRAME_FIELD_ENERGY_3_H

/// \file
/// The discrete energy of `Frame_field_3`: per tetrahedron its neighbours,
/// face weights and face transports, `A` at its centroid, its boundary faces
/// and boundary terms (soft terms and hard constraints, from the faces and
/// the sharp features), and the products the solvers need (`H x`, the
/// block preconditioner). `Frame_field_3` owns one and optimises the frames
/// against it; the formulas are in its class documentation.

#include <CGAL_ext/Cell_transport_3.h>
#include <CGAL_ext/Frame_field_options.h>
#include <CGAL_ext/Input_error.h>
#include <CGAL_ext/Octahedral_frame.h>
#include <CGAL_ext/Sharp_features_3.h>
#include <CGAL_ext/internal/deterministic_parallel.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/SVD>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

namespace CGAL_ext {

namespace internal {

/// The discrete energy of a frame field (see the file comment). The data
/// are public: `Frame_field_3` and the coarse level read them directly.
/// \tparam Metric_field as in `Frame_field_3`
template <class Metric_field>
class Frame_field_energy_3 {
public:
  using Triangulation = typename Metric_field::Triangulation_3;
  using Cell_handle = typename Triangulation::Cell_handle;
  using Point_3 = typename Triangulation::Point;

  /// Per tetrahedron and local facet (opposite vertex `f` of the cell).
  struct Links {
    std::array<std::int64_t, 4> nb;         ///< the neighbour's index, -1 on the boundary
    std::array<double, 4> w;                ///< the face weight (soft boundary weight on the boundary)
    std::array<bool, 4> identity;           ///< whether that transport is exactly the identity
    std::array<internal::Oct_euler_angles, 4> T_in_euler; ///< `transport_in` as the energy applies it to SH vectors
  };
  /// A boundary tetrahedron's terms: the soft term `s^T B s - 2 b.s + c`,
  /// the inverse of its preconditioner block, and the hard constraint.
  struct Constraint {
    Sh_matrix B = Sh_matrix::Zero();                                       ///< quadratic part
    Sh_vector b = Sh_vector::Zero();                                       ///< linear part
    double c = 0;                                                          ///< constant part
    Sh_matrix preconditioner;                                              ///< `((sum w) I + B)^{-1}`
    int axes = 0;                                                          ///< hard axes: 0, 1 or 2
    Eigen::Vector3d d1 = Eigen::Vector3d::Zero(), d2 = Eigen::Vector3d::Zero(); ///< the hard axes
  };

  /// \param field the metric field (kept by address)
  /// \param domain_cells the domain's cells, in index order
  Frame_field_energy_3(const Metric_field& field, std::vector<Cell_handle> domain_cells)
      : cells(std::move(domain_cells)), field_(&field), vim_(field.vertex_index_map()), cim_(field.cell_index_map()) {}

  /// The metric field.
  /// \returns the field given to the constructor
  const Metric_field& field() const { return *field_; }

  /// The number of tetrahedra.
  std::size_t size() const { return cells.size(); }

  /// Computes everything but the face transports: the geometry and weights,
  /// then the boundary faces and terms, and the preconditioner. Fills the
  /// face, constraint and feature counts of `stats`.
  /// \param opt the options (boundary weight, hard boundary, feature angle)
  /// \param stats the statistics to fill
  void set_up(const Frame_field_options& opt, Frame_field_statistics& stats) {
    set_up_geometry();
    set_up_boundary(opt, stats);
    set_up_preconditioner();
  }

  /// Computes the face transports `T(i->j)` (identity where they are
  /// exactly so) and their counts in `stats`.
  /// \param opt the options (transport tolerance and scheme)
  /// \param stats the statistics to fill
  /// \throws Input_error naming the two tetrahedra if a transport does not converge
  void compute_transports(const Frame_field_options& opt, Frame_field_statistics& stats) {
    const std::size_t n = size();
    Transport_options topt;
    topt.tolerance = opt.transport_tolerance;
    topt.scheme = opt.transport_scheme;
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
      const Cell_handle c = cells[i];
      try {
      for (int f = 0; f < 4; ++f) {
        const std::int64_t j = links[i].nb[f];
        if (j < 0 || std::size_t(j) < i) continue;
        const Cell_handle cj = cells[j];
        Eigen::Vector3d fc, nrm;
        double area;
        internal::boundary_facet_geometry(c, f, fc, nrm, area);
        const Point_3 pf = point(fc);
        const Transport_result a = cell_transport(*field_, c, point(centroid[i]), pf, topt);
        const Transport_result b = cell_transport(*field_, cj, pf, point(centroid[j]), topt);
        if (!a.converged || !b.converged) {
          unconverged[i] = j;
          failed(i);
          return;
        }
        const Eigen::Matrix3d T = b.rotation * a.rotation; // T(i->j), pieces left-multiplied
        const int fj = cj->index(c);
        if (T == Eigen::Matrix3d::Identity()) continue; // both slots stay identity
        const Eigen::Quaterniond q(T);
        transport_in[j][fj] = q.normalized();
        links[j].T_in_euler[fj] = internal::oct_euler_angles(transport_in[j][fj]);
        links[j].identity[fj] = false;
        transport_in[i][f] = q.conjugate().normalized();
        links[i].T_in_euler[f] = internal::oct_euler_angles(transport_in[i][f]);
        links[i].identity[f] = false;
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
      for (const Cell_handle a : {cells[i], cells[j]})
        for (const Cell_handle b : {cells[i], cells[j]})
          for (int u = 0; u < 4; ++u)
            for (int v = 0; v < 4; ++v) {
              const Eigen::Matrix3d M = field_->sqrt_metric(a->vertex(u)).inverse() * field_->sqrt_metric(b->vertex(v));
              change = std::max(change, Eigen::JacobiSVD<Eigen::Matrix3d>(M).singularValues()(0));
            }
      throw Input_error("", 0, "tetrahedra " + std::to_string(i + 1) + " and " + std::to_string(j + 1),
                        "the transport across their shared face does not converge: the metric changes too fast "
                        "there (its square root by a factor of up to " + format_number(change) +
                            " between their vertices); refine the mesh there or smooth the metric");
    }
    stats.identity_transports = 0;
    stats.max_transport_angle = 0;
    for (std::size_t i = 0; i < n; ++i) {
      stats.max_transport_angle = std::max(stats.max_transport_angle, max_angle[i]);
      for (int f = 0; f < 4; ++f)
        if (links[i].nb[f] > std::int64_t(i) && links[i].identity[f]) ++stats.identity_transports;
    }
  }

  // D(T(j->i)) s_j for the neighbour across facet f of i.
  Sh_vector neighbour_sh(std::size_t i, int f, const std::vector<Sh_vector>& s) const {
    const Links& L = links[i];
    const Sh_vector& sj = s[L.nb[f]];
    return L.identity[f] ? sj : internal::oct_apply(internal::oct_euler(L.T_in_euler[f]), sj);
  }
  // out[f] = D(T(f)) *v[f] for the faces f of i with a v[f] (the others
  // left alone), the transports applied together (oct_apply_lanes(): the
  // bits of neighbour_sh(), in a third of the time).
  void transported(std::size_t i, const Sh_vector* const (&v)[4], Sh_vector (&out)[4]) const {
    const Links& L = links[i];
    const internal::Oct_euler_angles* a[4];
    const Sh_vector* from[4];
    Sh_vector* to[4];
    int n = 0;
    for (int f = 0; f < 4; ++f) {
      if (!v[f]) continue;
      if (L.identity[f]) {
        out[f] = *v[f];
      } else {
        a[n] = &L.T_in_euler[f], from[n] = v[f], to[n] = &out[f];
        ++n;
      }
    }
    internal::oct_apply_lanes(n, a, from, to);
  }
  // out[f] = neighbour_sh(i, f, s) for the interior faces f of i.
  void neighbour_shs(std::size_t i, const std::vector<Sh_vector>& s, Sh_vector (&out)[4]) const {
    const Sh_vector* v[4];
    for (int f = 0; f < 4; ++f) v[f] = links[i].nb[f] >= 0 ? &s[std::size_t(links[i].nb[f])] : nullptr;
    transported(i, v, out);
  }

  // y = H x for the linear initialisation (half the Hessian of the quadratic energy).
  void apply_linear(const std::vector<Sh_vector>& x, std::vector<Sh_vector>& y) const {
    internal::parallel_for_each_index(size(), [&](std::size_t i) {
      const Links& L = links[i];
      Sh_vector r = diagonal[i] * x[i], t[4];
      neighbour_shs(i, x, t);
      for (int f = 0; f < 4; ++f)
        if (L.nb[f] >= 0) r -= L.w[f] * t[f];
      if (constraint_of[i] >= 0) r += constraints[constraint_of[i]].B * x[i];
      y[i] = r;
    });
  }
  // Block i of the block-Jacobi preconditioner applied to r.
  Sh_vector precondition(std::size_t i, const Sh_vector& r) const {
    if (constraint_of[i] >= 0) return constraints[constraint_of[i]].preconditioner * r;
    return diagonal[i] > 0 ? Sh_vector(r / diagonal[i]) : r;
  }
  // sum_f w_f |s_i - D(T(j->i)) s_j|^2 over the interior faces of i.
  double local_smoothness(std::size_t i, const std::vector<Sh_vector>& s) const {
    double e = 0;
    Sh_vector t[4];
    neighbour_shs(i, s, t);
    for (int f = 0; f < 4; ++f)
      if (links[i].nb[f] >= 0) e += links[i].w[f] * (s[i] - t[f]).squaredNorm();
    return e;
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

  std::vector<Cell_handle> cells;                 ///< the domain's cells, in index order
  std::vector<Links> links;                       ///< neighbours, weights and transports
  /// Per tetrahedron and face, the transport from the neighbour into the
  /// tetrahedron (apart from `links`, which the energy reads on every
  /// evaluation and which is kept small).
  std::vector<std::array<Eigen::Quaterniond, 4>> transport_in;
  std::vector<Eigen::Matrix3d> sqrt_metric;       ///< `A` at the centroids
  std::vector<Eigen::Vector3d> centroid;          ///< the centroids
  std::vector<double> volume;                     ///< the volumes
  std::vector<double> diagonal;                   ///< the sum of the face weights of each tetrahedron
  std::vector<Frame_field_boundary_face> boundary; ///< the boundary faces, in tetrahedron order
  std::vector<Constraint> constraints;            ///< the boundary tetrahedra's terms
  std::vector<std::int64_t> constraint_of;        ///< per tetrahedron, its constraint or -1
  std::vector<Feature_vertex_kind> feature_kind;  ///< per vertex, its place on the sharp features
  int weight_exponent = 0;                        ///< the face weights are in units of 2^weight_exponent
  double total_weight = 0;                        ///< the sum of the interior face weights, in that unit

private:
  static Point_3 point(const Eigen::Vector3d& v) { return Point_3(v(0), v(1), v(2)); }
  static double metric_area(const Eigen::Matrix3d& A, const Eigen::Vector3d& n, double area) {
    // Nanson: the image of the area vector a n under x -> A x is det(A) A^{-T} a n.
    return A.determinant() * (A.inverse().transpose() * n).norm() * area;
  }

  // Neighbours, A at the centroids, volumes, and the interior face weights.
  void set_up_geometry() {
    const std::size_t n = size();
    links.assign(n, Links());
    transport_in.assign(n, {});
    sqrt_metric.assign(n, Eigen::Matrix3d::Identity());
    centroid.assign(n, Eigen::Vector3d::Zero());
    volume.assign(n, 0.0);
    internal::parallel_for_each_index(n, [&](std::size_t i) {
      const Cell_handle c = cells[i];
      Eigen::Vector3d p[4];
      for (int k = 0; k < 4; ++k) p[k] = internal::to_eigen_vector(c->vertex(k)->point());
      centroid[i] = (p[0] + p[1] + p[2] + p[3]) / 4;
      volume[i] = std::abs((p[1] - p[0]).dot((p[2] - p[0]).cross(p[3] - p[0]))) / 6;
      sqrt_metric[i] = field_->A_at(c, point(centroid[i]));
    });
    // The weights are homogeneous of degree 1 in A: they are computed with A
    // divided by an even power of two 2^E near its largest entry, exactly,
    // so that no metric scale (1e-300 I as well as 1e300 I) under- or
    // overflows them, and the field is the same bits as without; the
    // energies are reported multiplied back by 2^E.
    double largest = 0;
    for (const Eigen::Matrix3d& A : sqrt_metric) largest = std::max(largest, A.cwiseAbs().maxCoeff());
    std::frexp(largest, &weight_exponent);
    weight_exponent += weight_exponent & 1; // even: square roots of the weights scale exactly too
    const double unit = std::ldexp(1.0, -weight_exponent);
    internal::parallel_for_each_index(n, [&](std::size_t i) {
      const Cell_handle c = cells[i];
      Links& L = links[i];
      for (int f = 0; f < 4; ++f) {
        const Cell_handle nc = c->neighbor(f);
        const std::int64_t j = field_->triangulation().is_infinite(nc) ? -1 : get(cim_, nc);
        L.nb[f] = j;
        L.identity[f] = true;
        transport_in[i][f] = Eigen::Quaterniond::Identity();
        L.T_in_euler[f] = internal::oct_euler_angles(transport_in[i][f]);
        L.w[f] = 0;
        // Each interior face's weight is computed by its smaller index and
        // copied to the other side below (symmetric bit for bit); boundary
        // weights come with the boundary data.
        if (j < 0 || std::size_t(j) < i) continue;
        Eigen::Vector3d fc, nrm;
        double area;
        internal::boundary_facet_geometry(c, f, fc, nrm, area);
        const Eigen::Matrix3d Af = unit * field_->A_at(c, point(fc));
        L.w[f] = metric_area(Af, nrm, area) / (Af * (centroid[j] - centroid[i])).norm();
      }
    });
    for (std::size_t i = 0; i < n; ++i)
      for (int f = 0; f < 4; ++f) {
        const std::int64_t j = links[i].nb[f];
        if (j >= 0 && std::size_t(j) < i) links[i].w[f] = links[j].w[cells[j]->index(cells[i])];
      }
  }

  // The boundary faces and each boundary tetrahedron's terms, in tetrahedron order.
  void set_up_boundary(const Frame_field_options& opt, Frame_field_statistics& stats) {
    const std::size_t n = size();
    const double unit = std::ldexp(1.0, -weight_exponent);
    constraint_of.assign(n, -1);
    boundary.clear();
    constraints.clear();
    stats.interior_faces = stats.boundary_faces = stats.hard_one_axis = stats.hard_two_axes = 0;
    const Sharp_features_3<Metric_field> features(*field_, opt.feature_angle_deg);
    stats.feature_edges = features.feature_edges().size();
    stats.feature_curve_vertices = features.number_of_curve_vertices();
    stats.feature_corners = features.number_of_corners();
    stats.feature_edges_dropped = features.number_of_dropped_edges();
    stats.boundary_smooth_turning = features.smooth_turning();
    feature_kind = features.kinds();
    stats.feature_tets = 0;
    const double cos_feature = std::cos(opt.feature_angle_deg * M_PI / 180);
    if (!(opt.crease_split_deg >= 0))
      throw std::invalid_argument("the crease split angle must be a number >= 0 degrees (got " +
                                  std::to_string(opt.crease_split_deg) + ")");
    total_weight = 0;
    std::vector<double> scaled_area; // metric areas in the weights' unit, per boundary face
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t first = boundary.size();
      add_faces(i, unit, opt, stats, scaled_area);
      const Feature_axes fa = feature_axes(i, features, unit, cos_feature);
      if (boundary.size() == first && fa.axes == 0) continue;
      Constraint C = soft_terms(i, first);
      // The boundary faces by decreasing metric area.
      std::vector<std::size_t> order;
      for (std::size_t k = first; k < boundary.size(); ++k) order.push_back(k);
      std::stable_sort(order.begin(), order.end(),
                       [&](std::size_t a, std::size_t b) { return scaled_area[a] > scaled_area[b]; });
      if (fa.axes > 0) {
        // The feature's axes, mapped by A into the rotation's space (the
        // frame's axes are A^{-1} R e_k). They are hard constraints only:
        // as soft terms in the linear initialisation, next to the faces'
        // terms, they raised the energy and the non-meshable edges of
        // CGAL's anchor (doc/benchmarks.md).
        C.d1 = (unit * sqrt_metric[i] * fa.u1).normalized();
        C.axes = 1;
        if (fa.axes == 2) {
          C.d2 = (unit * sqrt_metric[i] * fa.u2).normalized();
          C.d2 = (C.d2 - C.d2.dot(C.d1) * C.d1).normalized();
          C.axes = 2;
        } else {
          std::vector<Eigen::Vector3d> crease;
          if (fa.crease) {
            const Eigen::Matrix3d A_inv = (unit * sqrt_metric[i]).inverse();
            for (const Eigen::Vector3d& nrm : fa.crease->normals) crease.push_back((A_inv * nrm).normalized());
          }
          hard_axes_about_tangent(C, order, crease, cos_feature, opt.crease_split_deg);
        }
        if (opt.hard_boundary) ++stats.feature_tets;
      } else {
        // Hard axes: the largest metric area first, then a face more than
        // 30 degrees away from it (two faces of one tetrahedron meet at an
        // edge: beyond the feature angle it is a feature edge, handled above).
        C.d1 = boundary[order[0]].direction;
        C.axes = 1;
        for (std::size_t k = 1; k < order.size(); ++k) {
          const Eigen::Vector3d& d = boundary[order[k]].direction;
          if (std::abs(d.dot(C.d1)) < std::cos(M_PI / 6)) {
            C.d2 = (d - d.dot(C.d1) * C.d1).normalized();
            C.axes = 2;
            break;
          }
        }
      }
      if (opt.hard_boundary) ++(C.axes == 2 ? stats.hard_two_axes : stats.hard_one_axis);
      constraint_of[i] = std::int64_t(constraints.size());
      constraints.push_back(C);
    }
    stats.boundary_faces = boundary.size();
    stats.total_face_weight = std::ldexp(total_weight, weight_exponent);
  }

  // The faces of tetrahedron i: counts and total weight of the interior
  // ones, and the boundary ones with their weights and metric areas.
  void add_faces(std::size_t i, double unit, const Frame_field_options& opt, Frame_field_statistics& stats,
                 std::vector<double>& scaled_area) {
    for (int f = 0; f < 4; ++f) {
      if (links[i].nb[f] >= 0) {
        if (std::size_t(links[i].nb[f]) > i) {
          ++stats.interior_faces;
          total_weight += links[i].w[f];
        }
        continue;
      }
      Eigen::Vector3d fc, nrm;
      double area;
      internal::boundary_facet_geometry(cells[i], f, fc, nrm, area);
      const Eigen::Matrix3d Af = unit * field_->A_at(cells[i], point(fc));
      Frame_field_boundary_face bf;
      bf.tet = i;
      bf.facet = f;
      bf.normal = nrm;
      bf.direction = Af.inverse() * nrm;
      bf.direction.normalize();
      scaled_area.push_back(metric_area(Af, nrm, area));
      bf.metric_area = std::ldexp(scaled_area.back(), 2 * weight_exponent); // degree 2 in A
      links[i].w[f] = opt.boundary_weight * scaled_area.back() / (Af * (fc - centroid[i])).norm();
      boundary.push_back(bf);
    }
  }

  // The soft terms of tetrahedron i's boundary faces (from `first` on):
  // the frame should have an axis on each face's d (rotation about d free).
  Constraint soft_terms(std::size_t i, std::size_t first) const {
    const Sh_vector s0 = octahedral_reference_sh();
    Constraint C;
    for (std::size_t k = first; k < boundary.size(); ++k) {
      const Eigen::Vector3d& d = boundary[k].direction;
      const double w = links[i].w[boundary[k].facet];
      const Sh_matrix D = sh_rotation(Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), d));
      Sh_matrix M = Sh_matrix::Identity();
      M(0, 0) = M(8, 8) = 0; // m = +-4 are free (rotation about d)
      C.B += w * D * M * D.transpose();
      C.b += w * s0(4) * D.col(4);
      C.c += w * s0(4) * s0(4);
    }
    return C;
  }

  // C has one hard axis, a feature curve's tangent d1; adds the second.
  // `crease`: the metric normals of the two facets of the feature edge
  // (empty if it has other than two).
  void hard_axes_about_tangent(Constraint& C, const std::vector<std::size_t>& order,
                               const std::vector<Eigen::Vector3d>& crease, double cos_feature,
                               double crease_split_deg) const {
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
    // depend on the rotation. On a crease whose faces' frames differ by at
    // least `crease_split_deg` (modulo a quarter turn), a tetrahedron whose
    // faces agree takes the crease's shared angle too
    // (`Frame_field_options::crease_split_deg`).
    // The signed angle from u to v about the tangent (both orthogonal to it).
    auto angle = [&](const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
      return std::atan2(v.dot(C.d1.cross(u)), v.dot(u));
    };
    Eigen::Vector3d p1 = Eigen::Vector3d::Zero();
    std::size_t face1 = 0; // the face p1 comes from
    bool agree = true;
    std::complex<double> sum = 0;
    for (std::size_t k : order) {
      const Eigen::Vector3d& d = boundary[k].direction;
      Eigen::Vector3d p = d - d.dot(C.d1) * C.d1;
      if (p.norm() < 0.5) continue; // within 30 degrees of the tangent: says nothing about the rotation
      p.normalize();
      if (p1.isZero()) p1 = p, face1 = k;
      sum += std::polar(1.0, 4 * angle(p1, p));
      agree = agree && std::max(std::abs(p.dot(p1)), std::abs(p.dot(C.d1.cross(p1)))) >= cos_feature;
    }
    if (!p1.isZero() && agree && crease.size() == 2) {
      // The crease's faces, projected orthogonally to the tangent.
      std::array<Eigen::Vector3d, 2> pc;
      bool usable = true;
      std::complex<double> crease_sum = 0;
      for (int k = 0; k < 2; ++k) {
        pc[k] = crease[k] - crease[k].dot(C.d1) * C.d1;
        usable = usable && pc[k].norm() >= 0.5;
        crease_sum += std::polar(1.0, 4 * angle(p1, pc[k]));
      }
      // The angle halfway between the faces' frames, from p1: their mean
      // modulo a quarter turn, as for a tetrahedron with faces on both sides
      // (halfway between the normals themselves, which differs beyond 45
      // degrees, taken by every tetrahedron on the crease left 12
      // non-meshable edges on anchor instead of 7, 4 on fandisk instead of
      // 1). On an exact 45-degree crease both means are halfway; the one
      // between the normals is taken.
      double half = std::arg(crease_sum) / 4;
      if (std::abs(crease_sum) < 1e-9 && usable) {
        const Eigen::Vector3d mid = Eigen::AngleAxisd(angle(pc[0], pc[1]) / 2, C.d1) * pc[0].normalized();
        half = angle(p1, mid);
      }
      if (usable && 2 * std::abs(half) * 180 / M_PI >= crease_split_deg) {
        C.d2 = Eigen::AngleAxisd(half, C.d1) * p1;
        C.axes = 2;
        return;
      }
    }
    if (!p1.isZero() && agree) {
      const Eigen::Vector3d t = C.d1;
      C.d1 = boundary[face1].direction;
      C.d2 = (t - t.dot(C.d1) * C.d1).normalized();
      C.axes = 2;
    } else if (!p1.isZero()) {
      C.d2 = Eigen::AngleAxisd(std::arg(sum) / 4, C.d1) * p1;
      C.axes = 2;
    }
  }

  // Block-Jacobi preconditioner: (sum of the face weights) I + B.
  void set_up_preconditioner() {
    const std::size_t n = size();
    diagonal.assign(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      double s = 0;
      for (int f = 0; f < 4; ++f)
        if (links[i].nb[f] >= 0) s += links[i].w[f];
      diagonal[i] = s;
      if (constraint_of[i] >= 0) {
        Constraint& C = constraints[constraint_of[i]];
        const Sh_matrix H = s * Sh_matrix::Identity() + C.B;
        C.preconditioner = H.llt().solve(Sh_matrix::Identity());
      }
    }
  }

  // The axes a feature imposes on tetrahedron i (Euclidean directions; 0, 1
  // or 2 of them): the frame of its corner of smallest index if it has a
  // corner, else the tangent of its first feature edge (and a second one's
  // if it turns by more than the feature angle: two creases of a thin part).
  struct Feature_axes {
    int axes = 0;
    Eigen::Vector3d u1 = Eigen::Vector3d::Zero(), u2 = Eigen::Vector3d::Zero();
    const typename Sharp_features_3<Metric_field>::Feature_edge* crease = nullptr; // u1's, if two facets
  };
  template <class Features>
  Feature_axes feature_axes(std::size_t i, const Features& features, double unit, double cos_feature) const {
    Feature_axes out;
    const Cell_handle c = cells[i];
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
          const auto* e = features.feature_edge(p, q);
          if (e->facets == 2) out.crease = e;
        } else if (out.axes == 1 &&
                   std::abs((unit * sqrt_metric[i] * t).normalized().dot((unit * sqrt_metric[i] * out.u1).normalized())) < cos_feature) {
          out.axes = 2;
          out.u2 = t;
        }
      }
    return out;
  }

  const Metric_field* field_;
  typename Metric_field::Vertex_index_map vim_;
  typename Metric_field::Cell_index_map cim_;
};

} // namespace internal
} // namespace CGAL_ext

#endif // CGAL_EXT_INTERNAL_FRAME_FIELD_ENERGY_3_H
