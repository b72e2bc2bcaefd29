// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_INTERNAL_SH_ROTATION_TABLES_H
#define CGAL_EXT_INTERNAL_SH_ROTATION_TABLES_H

// The rotation D(R) of band-4 spherical harmonics (Octahedral_frame.h) as
// products of exact sparse matrices: D(Rz) from cosines and sines of
// multiples of the angle, Ry(b) = Rx(-90) Rz(b) Rx(90), and the z-y-z Euler
// angles of a rotation without trigonometric calls.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cassert>
#include <cmath>
#include <cstddef>
#include <utility>

namespace CGAL_ext {
namespace internal {

// One nonzero entry of a constant sparse 9x9 matrix.
struct Oct_entry {
  int row, col;
  double value;
};

// X = D(Rx(+90 degrees)), exact entries sqrt(rational) (derived symbolically:
// f(R^T x) = f(x, z, -y) re-expanded in the basis; checked in the tests).
inline constexpr Oct_entry oct_x90[21] = {
    {0, 5, 0.935414346693485346396},  {0, 7, -0.353553390593273762200}, // sqrt(14)/4, -sqrt(2)/4
    {1, 1, -0.75},                    {1, 3, 0.661437827766147647625},  // -3/4, sqrt(7)/4
    {2, 5, 0.353553390593273762200},  {2, 7, 0.935414346693485346396},  // sqrt(2)/4, sqrt(14)/4
    {3, 1, 0.661437827766147647625},  {3, 3, 0.75},                     // sqrt(7)/4, 3/4
    {4, 4, 0.375},                    {4, 6, 0.559016994374947424102},  // 3/8, sqrt(5)/4
    {4, 8, 0.739509972887452005321},                                    // sqrt(35)/8
    {5, 0, -0.935414346693485346396}, {5, 2, -0.353553390593273762200}, // -sqrt(14)/4, -sqrt(2)/4
    {6, 4, 0.559016994374947424102},  {6, 6, 0.5},                      // sqrt(5)/4, 1/2
    {6, 8, -0.661437827766147647625},                                   // -sqrt(7)/4
    {7, 0, 0.353553390593273762200},  {7, 2, -0.935414346693485346396}, // sqrt(2)/4, -sqrt(14)/4
    {8, 4, 0.739509972887452005321},  {8, 6, -0.661437827766147647625}, // sqrt(35)/8, -sqrt(7)/4
    {8, 8, 0.125}};                                                     // 1/8

// The generators L_k = d/dt D(exp(t [e_k]_x)) at t = 0 (skew-symmetric).
inline constexpr Oct_entry oct_lx[14] = {
    {0, 7, -1.41421356237309504880}, {1, 6, -1.87082869338697069279}, {1, 8, -1.41421356237309504880},
    {2, 5, -2.12132034355964257320}, {2, 7, -1.87082869338697069279}, {3, 4, -3.16227766016837933200},
    {3, 6, -2.12132034355964257320}, {4, 3, 3.16227766016837933200},  {5, 2, 2.12132034355964257320},
    {6, 1, 1.87082869338697069279},  {6, 3, 2.12132034355964257320},  {7, 0, 1.41421356237309504880},
    {7, 2, 1.87082869338697069279},  {8, 1, 1.41421356237309504880}};
inline constexpr Oct_entry oct_ly[14] = {
    {0, 1, 1.41421356237309504880},  {1, 0, -1.41421356237309504880}, {1, 2, 1.87082869338697069279},
    {2, 1, -1.87082869338697069279}, {2, 3, 2.12132034355964257320},  {3, 2, -2.12132034355964257320},
    {4, 5, -3.16227766016837933200}, {5, 4, 3.16227766016837933200},  {5, 6, -2.12132034355964257320},
    {6, 5, 2.12132034355964257320},  {6, 7, -1.87082869338697069279}, {7, 6, 1.87082869338697069279},
    {7, 8, -1.41421356237309504880}, {8, 7, 1.41421356237309504880}};
inline constexpr Oct_entry oct_lz[8] = {{0, 8, 4}, {1, 7, 3}, {2, 6, 2}, {3, 5, 1},
                                        {5, 3, -1}, {6, 2, -2}, {7, 1, -3}, {8, 0, -4}};

// cos(m a), sin(m a) for m = 0..4 from cos a, sin a (angle addition, no trig
// calls). T: double, or a vector of doubles whose operations act lane by
// lane (Oct_lanes), so that each lane has the bits of the scalar.
template <class T>
struct Oct_multiples_of {
  T c[5], s[5];
  Oct_multiples_of(const T& c1, const T& s1) {
    c[0] = T{} + 1, s[0] = T{}, c[1] = c1, s[1] = s1;
    c[2] = c1 * c1 - s1 * s1, s[2] = 2 * s1 * c1;
    c[3] = c[2] * c1 - s[2] * s1, s[3] = s[2] * c1 + c[2] * s1;
    c[4] = c[2] * c[2] - s[2] * s[2], s[4] = 2 * s[2] * c[2];
  }
};
using Oct_multiples = Oct_multiples_of<double>;

// x <- D(Rz(a)) x: (D x)_m = cos(ma) x_m - sin(ma) x_-m, (D x)_-m = sin(ma) x_m + cos(ma) x_-m.
template <class T>
inline void oct_rotate_z(const Oct_multiples_of<T>& a, T* x) {
  for (int m = 1; m <= 4; ++m) {
    const T p = x[4 + m], n = x[4 - m];
    x[4 + m] = a.c[m] * p - a.s[m] * n;
    x[4 - m] = a.s[m] * p + a.c[m] * n;
  }
}

// out = A in and out = A^T in for the constant sparse table A, unrolled.
template <const auto& A, class T, std::size_t... I>
inline void oct_mul_into(const T* in, T* out, std::index_sequence<I...>) {
  for (int r = 0; r < 9; ++r) out[r] = T{};
  ((out[A[I].row] += A[I].value * in[A[I].col]), ...);
}
template <const auto& A, class T, std::size_t... I>
inline void oct_mul_transposed_into(const T* in, T* out, std::index_sequence<I...>) {
  for (int r = 0; r < 9; ++r) out[r] = T{};
  ((out[A[I].col] += A[I].value * in[A[I].row]), ...);
}

// out = A in for a 9xN matrix, column by column.
template <const auto& A, class Mat>
inline Mat oct_mul(const Mat& in) {
  Mat out;
  for (Eigen::Index j = 0; j < in.cols(); ++j) {
    double x[9], y[9];
    for (int k = 0; k < 9; ++k) x[k] = in(k, j);
    oct_mul_into<A>(x, y, std::make_index_sequence<std::extent_v<std::remove_reference_t<decltype(A)>>>());
    for (int k = 0; k < 9; ++k) out(k, j) = y[k];
  }
  return out;
}

// x <- D(R) x with D(R) = D(Rz(a)) X^T D(Rz(b)) X D(Rz(g)), since
// Ry(b) = Rx(-90) Rz(b) Rx(90). When beta is exactly 0 (`about_z`: a
// rotation about z, the identity included) only the z rotations are
// applied, so that D(I) = I and D(Rz) are exact.
template <class T>
inline void oct_rotate(const Oct_multiples_of<T>& alpha, const Oct_multiples_of<T>& beta,
                       const Oct_multiples_of<T>& gamma, bool about_z, T* x) {
  oct_rotate_z(gamma, x);
  if (!about_z) {
    constexpr auto n = std::extent_v<decltype(oct_x90)>;
    T y[9];
    oct_mul_into<oct_x90>(x, y, std::make_index_sequence<n>());
    oct_rotate_z(beta, y);
    oct_mul_transposed_into<oct_x90>(y, x, std::make_index_sequence<n>());
  }
  oct_rotate_z(alpha, x);
}

// A rotation exactly about z (beta exactly 0), given beta's cosine and sine.
inline bool oct_is_about_z(double cos_beta, double sin_beta) { return sin_beta == 0 && cos_beta == 1; }

// The z-y-z Euler angles R = Rz(alpha) Ry(beta) Rz(gamma) of a quaternion,
// as cosines and sines, without trigonometric calls and well conditioned
// everywhere (gimbal lock included): with q = (w, x, y, z),
//   w = cos(b/2) cos((a+g)/2), z = cos(b/2) sin((a+g)/2),
//   y = sin(b/2) cos((a-g)/2), x = -sin(b/2) sin((a-g)/2).
// When cos(b/2) (or sin(b/2)) vanishes, (a+g)/2 (or (a-g)/2) is free and 0 is
// taken; its influence on R is proportional to the vanishing factor.
// Oct_euler_angles keeps the cosines and sines of alpha, beta, gamma alone
// (48 bytes), for a rotation applied many times (a face's transport);
// Oct_euler adds their multiples.
struct Oct_euler_angles {
  double c[3], s[3];
  bool about_z() const { return oct_is_about_z(c[1], s[1]); }
};
struct Oct_euler {
  Oct_multiples alpha, beta, gamma;
};
inline Oct_euler_angles oct_euler_angles(double w, double x, double y, double z) {
  const double r1 = std::sqrt(w * w + z * z), r2 = std::sqrt(x * x + y * y);
  double cp = 1, sp = 0, cq = 1, sq = 0;
  if (r1 > 0) cp = w / r1, sp = z / r1;
  if (r2 > 0) cq = y / r2, sq = -x / r2;
  const double n2 = r1 * r1 + r2 * r2;
  return {{cp * cq - sp * sq, (r1 - r2) * (r1 + r2) / n2, cp * cq + sp * sq},
          {sp * cq + cp * sq, 2 * r1 * r2 / n2, sp * cq - cp * sq}};
}
inline Oct_euler_angles oct_euler_angles(const Eigen::Quaterniond& q) {
  return oct_euler_angles(q.w(), q.x(), q.y(), q.z());
}
inline Oct_euler oct_euler(const Oct_euler_angles& e) {
  return {Oct_multiples(e.c[0], e.s[0]), Oct_multiples(e.c[1], e.s[1]), Oct_multiples(e.c[2], e.s[2])};
}
inline Oct_euler oct_euler(const Eigen::Quaterniond& q) { return oct_euler(oct_euler_angles(q)); }
inline Oct_euler oct_euler(const Eigen::Matrix3d& R) { return oct_euler(Eigen::Quaterniond(R)); }

// M <- D(R) M, column by column. Mat: a fixed-size matrix type with 9 rows.
template <class Mat>
inline Mat oct_apply(const Oct_euler& e, Mat M) {
  const bool about_z = oct_is_about_z(e.beta.c[1], e.beta.s[1]);
  for (Eigen::Index j = 0; j < M.cols(); ++j) {
    double x[9];
    for (int k = 0; k < 9; ++k) x[k] = M(k, j);
    oct_rotate(e.alpha, e.beta, e.gamma, about_z, x);
    for (int k = 0; k < 9; ++k) M(k, j) = x[k];
  }
  return M;
}

// Up to four vectors turned at once, each by its own rotation:
// out[k] = D(R(a[k])) v[k] for k < n <= 4, with the bits of oct_apply() on
// each, as each lane does the scalar operations (3 times faster than one by
// one: the lanes' independent chains hide each other's latency). All inputs
// are read before any output is written, so outputs may overlap inputs.
#if defined(__GNUC__)
using Oct_lanes = double __attribute__((vector_size(4 * sizeof(double))));
inline void oct_apply_lanes(int n, const Oct_euler_angles* const* a, const Eigen::Matrix<double, 9, 1>* const* v,
                            Eigen::Matrix<double, 9, 1>* const* out) {
  assert(0 <= n && n <= 4);
  Oct_lanes c[3], s[3], x[9];
  Eigen::Matrix<double, 9, 1> about_z[4];
  int lanes = 0, lane_of[4], z = 0, z_of[4];
  for (int k = 0; k < n; ++k) {
    if (a[k]->about_z()) { // rare: its own exact path (z rotations only)
      about_z[z] = oct_apply(oct_euler(*a[k]), Eigen::Matrix<double, 9, 1>(*v[k]));
      z_of[z++] = k;
      continue;
    }
    for (int j = 0; j < 3; ++j) c[j][lanes] = a[k]->c[j], s[j][lanes] = a[k]->s[j];
    for (int r = 0; r < 9; ++r) x[r][lanes] = (*v[k])[r];
    lane_of[lanes++] = k;
  }
  if (lanes > 0) {
    for (int l = lanes; l < 4; ++l) { // unused lanes repeat lane 0 and are not read back
      for (int j = 0; j < 3; ++j) c[j][l] = c[j][0], s[j][l] = s[j][0];
      for (int r = 0; r < 9; ++r) x[r][l] = x[r][0];
    }
    oct_rotate(Oct_multiples_of<Oct_lanes>(c[0], s[0]), Oct_multiples_of<Oct_lanes>(c[1], s[1]),
               Oct_multiples_of<Oct_lanes>(c[2], s[2]), false, x);
  }
  for (int l = 0; l < lanes; ++l)
    for (int r = 0; r < 9; ++r) (*out[lane_of[l]])[r] = x[r][l];
  for (int k = 0; k < z; ++k) *out[z_of[k]] = about_z[k];
}
#else
inline void oct_apply_lanes(int n, const Oct_euler_angles* const* a, const Eigen::Matrix<double, 9, 1>* const* v,
                            Eigen::Matrix<double, 9, 1>* const* out) {
  assert(0 <= n && n <= 4);
  Eigen::Matrix<double, 9, 1> y[4];
  for (int k = 0; k < n; ++k) y[k] = oct_apply(oct_euler(*a[k]), Eigen::Matrix<double, 9, 1>(*v[k]));
  for (int k = 0; k < n; ++k) *out[k] = y[k];
}
#endif

} // namespace internal
} // namespace CGAL_ext

#endif // CGAL_EXT_INTERNAL_SH_ROTATION_TABLES_H
