// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_CELL_TRANSPORT_3_H
#define CGAL_EXT_CELL_TRANSPORT_3_H

/// \file Cell_transport_3.h
/// The transport (rotation coefficient) `T(a->b)` along a straight segment
/// inside one cell, where `A` is linear and `curl A` is constant (doc/math.md
/// section 4), with adaptive error control in radians.

#include <CGAL_ext/Connection_3.h>

#include <CGAL/number_utils.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>

namespace CGAL_ext {

/// \ingroup PkgCGALExtTransport
/// The rotation `exp([v]_x)` by Rodrigues' formula: the rotation by the
/// angle `|v|` about the axis `v / |v|`. `v == 0` gives exactly the identity.
/// \param v the rotation vector
/// \returns a 3x3 rotation matrix
inline Eigen::Matrix3d rotation_exp(const Eigen::Vector3d& v) {
  const double theta = v.norm();
  if (theta == 0) return Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d K = cross_product_matrix(v);
  // sin(t)/t and (1-cos t)/t^2, written to stay accurate for small t.
  double a, b;
  if (theta < 1e-4) {
    const double t2 = theta * theta;
    a = 1 - t2 / 6 * (1 - t2 / 20);
    b = 0.5 * (1 - t2 / 12 * (1 - t2 / 30));
  } else {
    a = std::sin(theta) / theta;
    const double s = std::sin(0.5 * theta) / theta;
    b = 2 * s * s; // (1 - cos t) / t^2 = 2 sin^2(t/2) / t^2, without cancellation
  }
  return Eigen::Matrix3d::Identity() + a * K + b * K * K;
}

/// \ingroup PkgCGALExtTransport
/// The rotation angle of a rotation matrix, in `[0, pi]`: the geodesic
/// distance from `R` to the identity in SO(3). So `rotation_angle(P.transpose() * Q)`
/// is the distance between two rotations `P` and `Q`.
///
/// Computed as `atan2(|vee(R - R^T)| / 2, (tr R - 1) / 2)`, accurate to about
/// 1e-16 radians also for tiny angles (where `acos` would lose half the digits).
/// \param R a 3x3 rotation matrix (approximately orthogonal)
/// \returns the angle in radians
inline double rotation_angle(const Eigen::Matrix3d& R) {
  const Eigen::Vector3d s(R(2, 1) - R(1, 2), R(0, 2) - R(2, 0), R(1, 0) - R(0, 1));
  return std::atan2(0.5 * s.norm(), 0.5 * (R.trace() - 1));
}

/// \ingroup PkgCGALExtTransport
/// The integration scheme of a transport along a segment.
enum class Transport_scheme {
  /// The thesis scheme: trapezoid rule on each piece, `exp([(u_0 + u_1) h / 2]_x)`
  /// by Rodrigues' formula, with recursive midpoint subdivision. Second order.
  trapezoid,
  /// Fourth-order Magnus method on the two Gauss-Legendre points of each
  /// step, with adaptive steps (step doubling). Much fewer evaluations for
  /// the same accuracy; the default.
  magnus
};

/// \ingroup PkgCGALExtTransport
/// Options of a transport along a segment.
struct Transport_options {
  /// The scheme.
  Transport_scheme scheme = Transport_scheme::magnus;
  /// The wanted accuracy in radians: the returned rotation is within about
  /// `tolerance` radians (geodesic distance in SO(3)) of the exact transport
  /// of the given field along the segment. It is an absolute angle and does
  /// not depend on the length or the units of the segment (scale invariant).
  /// Each accepted piece of relative length `h` (a fraction of the segment)
  /// must have an estimated error of at most `tolerance * h`, so the errors
  /// of the pieces add up to at most about `tolerance`.
  /// When a path is made of several segments, give each segment the
  /// tolerance times its share of the path to bound the total.
  ///
  /// The estimates are asymptotic (the difference between one piece and two
  /// half pieces), not rigorous bounds: on random metrics with eigenvalues in
  /// [0.01, 100] the measured error stayed below `tolerance` at 1e-6, 1e-8 and
  /// 1e-10 (see test_cell_transport). Below about 1e-13 rounding dominates.
  double tolerance = 1e-8;
  /// Trapezoid: the maximal subdivision depth (at most `2^(max_depth + 1)`
  /// pieces: a piece accepted at depth `d` counts as its two halves).
  /// A piece at this depth is accepted whatever its error, and
  /// `Transport_result::converged` is then false.
  int max_depth = 22;
  /// Magnus: the smallest step, as a fraction of the segment. A step of this
  /// size is accepted whatever its error, and `converged` is then false.
  double min_step = 1.0 / (1 << 22);
  /// Magnus: the largest number of steps tried (accepted or not). A smooth
  /// generator needs a handful; only a metric that changes by orders of
  /// magnitude inside one cell needs more. When they are used up, the rest
  /// of the segment is one step and `converged` is false, so that the time
  /// of a transport is bounded (at most `6 * max_steps` evaluations: each
  /// try is three Magnus steps of two evaluations each).
  std::size_t max_steps = 10000;
};

/// \ingroup PkgCGALExtTransport
/// The result of a transport along a segment.
struct Transport_result {
  /// The transport `T(a->b)`, a rotation: a rotation field that is parallel
  /// along the segment satisfies `R(b) = T(a->b) R(a)` (doc/math.md section 4).
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  /// The sum of the estimated errors of the accepted pieces, in radians.
  double error_estimate = 0;
  /// The number of evaluations of the generator `u(t)` (for a cell: of the
  /// connection `W`), the measure of the cost.
  std::size_t evaluations = 0;
  /// The number of accepted pieces (trapezoid) or steps (Magnus).
  std::size_t pieces = 0;
  /// False if a piece was accepted at the depth cap or smallest step with an
  /// estimated error above its share of the tolerance.
  bool converged = true;
};

namespace internal {

// Products of many rotations drift from SO(3) by rounding (about sqrt(n) eps);
// one Newton-Schulz step R (3I - R^T R) / 2 squares the drift away.
// The identity stays exactly the identity.
inline Eigen::Matrix3d reorthonormalized(const Eigen::Matrix3d& R) {
  return 0.5 * R * (3 * Eigen::Matrix3d::Identity() - R.transpose() * R);
}

// The angle between two computations of the same rotation of angle `theta`
// that rounding alone can produce: a few ulps of `theta`, and of the unit
// entries. An error estimate below it says nothing more, so a step is
// accepted there whatever the tolerance: tolerances below what double
// resolves (1e-20, or a tiny share of a long path) end in a few steps at
// the accuracy of double instead of shrinking steps to the smallest one.
inline double rounding_floor(double theta) { return 16 * std::numeric_limits<double>::epsilon() * (1 + theta); }

// A NaN error estimate means a NaN or infinite generator: no step size can help.
inline void check_finite_generator(double estimate, double t0, double t1) {
  if (!std::isfinite(estimate))
    throw std::domain_error("integrate_transport: the rotation generator is not finite on [" + std::to_string(t0) +
                            ", " + std::to_string(t1) + "]");
}

// Thesis scheme: T(t0->t1) against T(tm->t1) T(t0->tm). Local error of the
// trapezoid piece is O(h^3), so the two-piece product is about 4 times better
// than the one-piece one, and its error is about |difference| / 3.
template <class Generator>
Eigen::Matrix3d trapezoid_piece(Generator& u, double t0, double t1, const Eigen::Vector3d& u0,
                                const Eigen::Vector3d& u1, const Eigen::Matrix3d& T01, int depth,
                                const Transport_options& opt, Transport_result& res) {
  const double h = t1 - t0;
  const double tm = 0.5 * (t0 + t1);
  const Eigen::Vector3d um = u(tm);
  ++res.evaluations;
  const Eigen::Matrix3d T0m = rotation_exp((0.25 * h) * (u0 + um));
  const Eigen::Matrix3d Tm1 = rotation_exp((0.25 * h) * (um + u1));
  const Eigen::Matrix3d fine = Tm1 * T0m;
  const double estimate = rotation_angle(T01.transpose() * fine) / 3;
  check_finite_generator(estimate, t0, t1);
  const bool ok = estimate <= std::max(opt.tolerance * h, rounding_floor(rotation_angle(fine)) / 3);
  if (ok || depth >= opt.max_depth) {
    if (!ok) res.converged = false;
    res.error_estimate += estimate;
    res.pieces += 2;
    return fine;
  }
  // Composed left-multiplied in path order: the first half acts first.
  const Eigen::Matrix3d first = trapezoid_piece(u, t0, tm, u0, um, T0m, depth + 1, opt, res);
  const Eigen::Matrix3d second = trapezoid_piece(u, tm, t1, um, u1, Tm1, depth + 1, opt, res);
  return second * first;
}

// One Magnus-4 step on [t, t + h] with the two Gauss-Legendre points:
// Omega = h/2 (A1 + A2) + sqrt(3) h^2 / 12 [A2, A1], with A_i = [u_i]_x, so that
// [A2, A1] = [u2 x u1]_x. Two evaluations.
template <class Generator>
Eigen::Matrix3d magnus4_step(Generator& u, double t, double h, Transport_result& res) {
  constexpr double c = 0.28867513459481288225; // sqrt(3) / 6
  constexpr double k = 0.14433756729740644113; // sqrt(3) / 12
  const Eigen::Vector3d u1 = u(t + (0.5 - c) * h);
  const Eigen::Vector3d u2 = u(t + (0.5 + c) * h);
  res.evaluations += 2;
  return rotation_exp((0.5 * h) * (u1 + u2) + (k * h * h) * u2.cross(u1));
}

} // namespace internal

/// \ingroup PkgCGALExtTransport
/// Integrates ``R'(t) = [u(t)]_x R(t)``, `R(0) = I`, over `t` in `[0, 1]` and
/// returns `R(1)`: the transport along a path whose rotation generator is
/// ``u(t) = W(x(t))^T x'(t)`` (doc/math.md section 4).
///
/// - `Transport_scheme::trapezoid`: the thesis scheme. The piece `[t0, t1]`
///   gives `exp([(u(t0) + u(t1)) (t1 - t0) / 2]_x)`; it is compared with the
///   product of its two halves `T(m->t1) T(t0->m)`; the error of the product
///   is estimated as a third of the angle between the two; the halves are
///   subdivided recursively until the estimate is at most
///   `tolerance * (t1 - t0)` or the depth reaches `max_depth`. The accepted
///   (finer) products are composed left-multiplied in path order.
/// - `Transport_scheme::magnus`: steps of the fourth-order Magnus method on
///   the Gauss-Legendre points. Each step of size `h` is done once and as two
///   half steps; the error of the two half steps is estimated as 1/15 of the
///   angle between the results (the local error is O(h^5)); the step is
///   accepted when the estimate is at most `tolerance * h`, and the next step
///   size is chosen from the estimate. The first step is the whole segment.
///
/// The generator is smooth inside a cell, where the Magnus scheme reaches a
/// given accuracy with far fewer evaluations.
///
/// \tparam Generator a callable `Eigen::Vector3d(double t)`
/// \param u the rotation generator, evaluated for `t` in `[0, 1]` only
/// \param opt the scheme and the tolerance in radians (see `Transport_options`)
/// A step whose estimate is at the level of rounding (a few ulps of its
/// rotation angle) is accepted whatever the tolerance, so a tolerance below
/// what double resolves costs a few steps, not the smallest step everywhere.
///
/// \returns the rotation `R(1)`, the error estimate and the evaluation count
/// \throws std::invalid_argument if the tolerance is not positive and finite
/// \throws std::domain_error if the generator is not finite (NaN or infinite)
template <class Generator>
Transport_result integrate_transport(Generator&& u, const Transport_options& opt = {}) {
  if (!(opt.tolerance > 0) || !std::isfinite(opt.tolerance))
    throw std::invalid_argument("integrate_transport: the tolerance must be positive and finite");
  Transport_result res;
  if (opt.scheme == Transport_scheme::trapezoid) {
    const Eigen::Vector3d u0 = u(0.0), u1 = u(1.0);
    res.evaluations = 2;
    const Eigen::Matrix3d T01 = rotation_exp(0.5 * (u0 + u1));
    res.rotation = internal::reorthonormalized(internal::trapezoid_piece(u, 0.0, 1.0, u0, u1, T01, 0, opt, res));
    return res;
  }

  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  double t = 0, h = 1;
  const double min_step = std::max(opt.min_step, 1e-300);
  std::size_t tried = 0;
  while (t < 1) {
    const bool last_chance = ++tried >= opt.max_steps; // the rest in one step
    // Avoid a sliver step at the end: stretch to the end if close.
    if (last_chance || t + 1.05 * h >= 1) h = 1 - t;
    const Eigen::Matrix3d coarse = internal::magnus4_step(u, t, h, res);
    const Eigen::Matrix3d first = internal::magnus4_step(u, t, 0.5 * h, res);
    const Eigen::Matrix3d second = internal::magnus4_step(u, t + 0.5 * h, 0.5 * h, res);
    const Eigen::Matrix3d fine = second * first;
    const double estimate = rotation_angle(coarse.transpose() * fine) / 15;
    internal::check_finite_generator(estimate, t, t + h);
    const double allowed = std::max(opt.tolerance * h, internal::rounding_floor(rotation_angle(fine)) / 15);
    const bool ok = estimate <= allowed;
    if (ok || h <= min_step || last_chance) {
      if (!ok) res.converged = false;
      R = fine * R;
      t = (h == 1 - t) ? 1.0 : t + h;
      res.error_estimate += estimate;
      ++res.pieces;
    }
    // Error per step ~ h^5 against an allowance ~ h: the ratio goes with h^4.
    const double factor =
        estimate == 0 ? 4.0 : std::clamp(0.9 * std::pow(allowed / estimate, 0.25), 0.2, 4.0);
    h = std::max(h * factor, min_step);
  }
  res.rotation = internal::reorthonormalized(R);
  return res;
}

/// \ingroup PkgCGALExtTransport
/// The transport `T(a->b)` along the straight segment `[a, b]` inside one
/// cell, where the metric square root is linear along the segment and the
/// curl is constant: `A(t) = (1 - t) A_a + t A_b`,
/// `u(t) = W(A(t), curlA)^T (b - a)` with `W` from `connection_one_form()`.
///
/// For a piece inside a facet or along an edge, pass the averaged curl of
/// doc/math.md section 4. A constant metric (`A_a == A_b`, `curlA == 0`) gives
/// exactly the identity.
///
/// \param A_a the metric square root at `a` (3x3, symmetric positive definite)
/// \param A_b the metric square root at `b`
/// \param curlA the curl of `A` in the cell (3x3, column `i` is the curl of column `i`)
/// \param d the segment vector `b - a`
/// \param opt the scheme and the tolerance in radians
/// \returns the rotation, its error estimate and the number of `W` evaluations
inline Transport_result cell_transport(const Eigen::Matrix3d& A_a, const Eigen::Matrix3d& A_b,
                                       const Eigen::Matrix3d& curlA, const Eigen::Vector3d& d,
                                       const Transport_options& opt = {}) {
  const Eigen::Matrix3d dA = A_b - A_a;
  auto u = [&](double t) -> Eigen::Vector3d {
    return connection_one_form(A_a + t * dA, curlA).transpose() * d;
  };
  return integrate_transport(u, opt);
}

/// \ingroup PkgCGALExtTransport
/// The transport `T(a->b)` along the segment `[a, b]` inside the cell `c` of
/// a metric field (for instance `Metric_field_3`).
///
/// \tparam Metric_field a model of `MetricField_3` (only `A_at(c, p)` and
///         `curl(c)` are used)
/// \tparam Cell_handle the cell handle type of the field's triangulation
/// \tparam Point_3 a point type with `x()`, `y()`, `z()`
/// \param field the metric field
/// \param c the cell that contains the segment (the field is extrapolated
///        linearly outside it, which is not what is wanted)
/// \param a the start point
/// \param b the end point
/// \param opt the scheme and the tolerance in radians
/// \returns the rotation, its error estimate and the number of `W` evaluations
template <class Metric_field, class Cell_handle, class Point_3>
auto cell_transport(const Metric_field& field, const Cell_handle& c, const Point_3& a, const Point_3& b,
                    const Transport_options& opt = {})
    -> decltype(field.A_at(c, a), field.curl(c), Transport_result()) { // only for fields

  const Eigen::Vector3d d(CGAL::to_double(b.x()) - CGAL::to_double(a.x()), CGAL::to_double(b.y()) - CGAL::to_double(a.y()),
                          CGAL::to_double(b.z()) - CGAL::to_double(a.z()));
  return cell_transport(field.A_at(c, a), field.A_at(c, b), field.curl(c), d, opt);
}

} // namespace CGAL_ext

#endif // CGAL_EXT_CELL_TRANSPORT_3_H
