// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_INTERNAL_WALK_CROSSING_PARAMETER_H
#define CGAL_EXT_INTERNAL_WALK_CROSSING_PARAMETER_H

/// \file
/// Certified crossing parameters for `Segment_walk_3`: the parameter t of
/// the point where the line x(t) = q + t (p - q) meets a plane, a line or a
/// point, computed in double with an error bound (or in interval
/// arithmetic), so that the walk uses a double value only when it is within
/// `crossing_tolerance` of the exact one and otherwise falls back on exact
/// rational arithmetic. The combinatorial decisions are not made here (the
/// caller knows, from exact predicates, which face the segment crosses).

#include <CGAL/Interval_nt.h>

#include <algorithm>
#include <cmath>

namespace CGAL_ext {
namespace internal {

/// Largest error accepted on a parameter computed in floating point (t is in
/// [0, 1]); a value that cannot be certified within it is computed exactly.
/// Below the walk's promise of 1e-12, with room for the one-ulp adjustments
/// of `walk_exit_parameter()`.
constexpr double walk_crossing_tolerance = 2e-13;

/// The exit parameter of a piece of exact positive length that ends before
/// p, from a parameter t within `walk_crossing_tolerance` of its exact value
/// and the (double) start lo of the piece: at least the next double after lo
/// and at most the last double below 1, so that a piece of positive length is
/// never reported with zero length and the piece that reaches p keeps a
/// positive length (both up to ties within one unit in the last place of
/// 1: pieces closer together than that cannot all be separated in double).
inline double walk_exit_parameter(double t, double lo) {
  constexpr double below_one = 0x1.fffffffffffffp-1;
  if (!(t > lo)) t = std::nextafter(lo, 1.0); // also NaN
  if (t > below_one) t = std::max(below_one, lo);
  return t;
}

/// Parameter where the line q + t d meets the plane of (a, b, c), from the
/// normal n = (b - a) x (c - a): t = n.(a - q) / n.d, computed in double.
/// Returns false if the forward error bound exceeds the tolerance (the line
/// nearly parallel to the plane, or a segment much shorter than the facet),
/// true and sets t otherwise. `wa` is a - q, computed in double.
///
/// Error analysis (u = 2^-53, each rounding a factor (1 + delta), |delta| <= u):
/// the components of b - a and c - a carry one rounding, those of n three, so
/// |n~_i - n_i| <= gamma_3 N_i with N_i the sum of the absolute values of the
/// two products; the two dot products carry seven roundings per term (the
/// factors' and their own), and their exact counterparts use the exact n,
/// a - q and d. With |n_i| <= N_i:
///   |num~ - num| <= gamma_7 sum N_i |wa_i|,   |den~ - den| <= gamma_7 sum N_i |d_i|,
/// and |t| <= 1 on the crossings the walk asks about, so
///   |t~ - t| <= (dnum + dden) / (|den~| - dden) (1 + u) + u.
inline bool walk_plane_parameter(const double* q, const double* d, const double* a, const double* b, const double* c,
                                 double& t) {
  const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
  const double N[3] = {std::fabs(e1[1] * e2[2]) + std::fabs(e1[2] * e2[1]), std::fabs(e1[2] * e2[0]) + std::fabs(e1[0] * e2[2]),
                       std::fabs(e1[0] * e2[1]) + std::fabs(e1[1] * e2[0])};
  const double w[3] = {a[0] - q[0], a[1] - q[1], a[2] - q[2]};
  const double num = n[0] * w[0] + n[1] * w[1] + n[2] * w[2];
  const double den = n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
  // gamma_7 (1 + u)^2 < 7.1 u, for the bounds computed from rounded factors
  constexpr double g7 = 7.1 * 0x1p-53;
  const double dnum = g7 * (N[0] * std::fabs(w[0]) + N[1] * std::fabs(w[1]) + N[2] * std::fabs(w[2]));
  const double dden = g7 * (N[0] * std::fabs(d[0]) + N[1] * std::fabs(d[1]) + N[2] * std::fabs(d[2]));
  const double margin = std::fabs(den) - dden;
  // (All products finite and not subnormal: otherwise the bound is not valid.)
  if (!(margin > 0) || !std::isnormal(den) || !std::isfinite(dnum + dden) || !(dnum + dden > 0)) return false;
  // bound <= tolerance, written without dividing: (dnum + dden)(1 + u) + u margin <= tol margin
  if (!((dnum + dden) * 1.0000001 <= (walk_crossing_tolerance - 0x1p-52) * margin)) return false;
  t = num / den;
  return std::isfinite(t);
}

/// The same parameters in interval arithmetic, for the general (degenerate)
/// steps of the walk: k = 1 (a vertex v[0], through which the line passes),
/// 2 (the line through v[0], v[1], which the segment's line crosses) or 3 (the
/// plane of v[0], v[1], v[2]). Returns false if the interval is wider than
/// the tolerance (or not finite), true and sets t to its midpoint otherwise.
/// For a plane, the normal form n.(v0 - q) / n.d is tried first, then the
/// barycentric form, which keeps its precision for segments much shorter than
/// the facet.
inline bool walk_interval_parameter(const double* q, const double* p, int k, const double (*v)[3], double& t) {
  using I = CGAL::Interval_nt<false>;
  CGAL::Protect_FPU_rounding<true> protect;
  const I Q[3] = {I(q[0]), I(q[1]), I(q[2])};
  const I D[3] = {I(p[0]) - Q[0], I(p[1]) - Q[1], I(p[2]) - Q[2]};
  auto sub = [&](const double* a, const I* b, I* r) {
    for (int i = 0; i < 3; ++i) r[i] = I(a[i]) - b[i];
  };
  auto dot = [](const I* a, const I* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
  auto cross = [](const I* a, const I* b, I* r) {
    r[0] = a[1] * b[2] - a[2] * b[1];
    r[1] = a[2] * b[0] - a[0] * b[2];
    r[2] = a[0] * b[1] - a[1] * b[0];
  };
  auto accept = [&](const I& x) {
    if (!(x.inf() > -1e300 && x.sup() < 1e300)) return false; // also infinite or NaN ends
    if (!(x.sup() - x.inf() <= walk_crossing_tolerance)) return false;
    t = 0.5 * (x.inf() + x.sup());
    return true;
  };
  I w0[3];
  sub(v[0], Q, w0);
  if (k == 1) return accept(dot(w0, D) / dot(D, D));
  if (k == 2) {
    // q + t D = a + s e: t (D x e) = (a - q) x e
    const I A[3] = {I(v[0][0]), I(v[0][1]), I(v[0][2])};
    I e[3], c1[3], c2[3];
    sub(v[1], A, e);
    cross(D, e, c1);
    cross(w0, e, c2);
    return accept(dot(c2, c1) / dot(c1, c1));
  }
  const I A[3] = {I(v[0][0]), I(v[0][1]), I(v[0][2])};
  I e1[3], e2[3], n[3];
  sub(v[1], A, e1);
  sub(v[2], A, e2);
  cross(e1, e2, n);
  if (accept(dot(n, w0) / dot(n, D))) return true;
  // barycentric: lambda_i = det[D, w_{i+1}, w_{i+2}], t = sum lambda_i (w_i . D) / (|D|^2 sum lambda_i)
  I w[3][3];
  for (int i = 0; i < 3; ++i) sub(v[i], Q, w[i]);
  I lam[3], tau[3];
  for (int i = 0; i < 3; ++i) {
    I c[3];
    cross(w[(i + 1) % 3], w[(i + 2) % 3], c);
    lam[i] = dot(D, c);
    tau[i] = dot(w[i], D);
  }
  return accept((lam[0] * tau[0] + lam[1] * tau[1] + lam[2] * tau[2]) / ((lam[0] + lam[1] + lam[2]) * dot(D, D)));
}

} // namespace internal
} // namespace CGAL_ext

#endif // CGAL_EXT_INTERNAL_WALK_CROSSING_PARAMETER_H
