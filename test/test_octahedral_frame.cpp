// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
// Octahedral frames (doc/math.md section 5): the band-4 real SH basis and its
// rotation D(R), checked against an independent evaluator written here from
// the associated Legendre functions (recurrence, not the polynomial table of
// the header), a product quadrature on the sphere, a long-double matrix
// exponential of the generators and finite differences; the reference frame
// s0; the projection onto the octahedral variety against brute force; the
// octahedral group, the matching, the distance and the canonical frame.
#include <CGAL_ext/Octahedral_frame.h>

#include <catch2/catch.hpp>

#include "test_support.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <vector>

// Counting the heap allocations of the whole program (operator new and
// Eigen's aligned allocations both end in malloc): glibc lets the executable
// interpose malloc and forward to __libc_malloc. Elsewhere the allocation test
// is skipped.
#if defined(__GLIBC__) && !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__)
#define CGAL_EXT_TEST_COUNT_MALLOC 1
namespace {
std::atomic<long> malloc_calls{0};
}
extern "C" void* __libc_malloc(std::size_t);
extern "C" void* malloc(std::size_t n) {
  malloc_calls.fetch_add(1, std::memory_order_relaxed);
  return __libc_malloc(n);
}
#endif

namespace {

using CGAL_ext::testing::Random;

using M3 = Eigen::Matrix3d;
using V3 = Eigen::Vector3d;
using CGAL_ext::Sh_matrix;
using CGAL_ext::Sh_vector;

const double pi = 3.14159265358979323846;

// ---------------------------------------------------------------------------
// Independent real SH of band 4: Y_m = sqrt(2) K_m P_4^m(cos t) cos(m phi)
// (m > 0), K_0 P_4 (m = 0), sqrt(2) K_|m| P_4^|m| sin(|m| phi) (m < 0), with
// K_m = sqrt(9/(4 pi) (4-m)!/(4+m)!) and P_l^m without the Condon-Shortley
// phase, by the standard recurrence in l.

double factorial(int n) { return n <= 1 ? 1.0 : n * factorial(n - 1); }

// P_4^m(t), st = sqrt(1 - t^2) >= 0.
double legendre4(int m, double t, double st) {
  double pmm = 1; // P_m^m = (2m-1)!! st^m
  for (int i = 1; i <= m; ++i) pmm *= (2 * i - 1) * st;
  if (m == 4) return pmm;
  double pm1 = t * (2 * m + 1) * pmm; // P_{m+1}^m
  for (int l = m + 2; l <= 4; ++l) {
    const double pl = ((2 * l - 1) * t * pm1 - (l + m - 1) * pmm) / (l - m);
    pmm = pm1;
    pm1 = pl;
  }
  return pm1;
}

double real_sh(int m, const V3& x) {
  const double r = x.norm(), t = x(2) / r, st = std::hypot(x(0), x(1)) / r, phi = std::atan2(x(1), x(0));
  const int a = std::abs(m);
  const double K = std::sqrt(9 / (4 * pi) * factorial(4 - a) / factorial(4 + a));
  const double P = legendre4(a, t, st);
  if (m == 0) return K * P;
  return std::sqrt(2.0) * K * P * (m > 0 ? std::cos(a * phi) : std::sin(a * phi));
}

double f_of(const Sh_vector& s, const V3& x) {
  double v = 0;
  for (int m = -4; m <= 4; ++m) v += s(m + 4) * real_sh(m, x);
  return v;
}

// Product quadrature on the sphere: Gauss-Legendre in cos(theta) (nodes by
// Newton's method on P_n), uniform in phi. Exact for the polynomials of
// degree < min(2 n, n_phi) in (x, y, z).
struct Quadrature {
  std::vector<V3> x;
  std::vector<double> w;
  Quadrature(int n, int n_phi) {
    for (int i = 0; i < n; ++i) {
      double t = std::cos(pi * (i + 0.75) / (n + 0.5)), dp = 0;
      for (int it = 0; it < 100; ++it) {
        double p0 = 1, p1 = t;
        for (int l = 2; l <= n; ++l) {
          const double p2 = ((2 * l - 1) * t * p1 - (l - 1) * p0) / l;
          p0 = p1;
          p1 = p2;
        }
        dp = n * (t * p1 - p0) / (t * t - 1);
        const double dt = p1 / dp;
        t -= dt;
        if (std::abs(dt) < 1e-16) break;
      }
      const double wt = 2 / ((1 - t * t) * dp * dp), st = std::sqrt(1 - t * t);
      for (int j = 0; j < n_phi; ++j) {
        const double phi = 2 * pi * j / n_phi;
        x.emplace_back(st * std::cos(phi), st * std::sin(phi), t);
        w.push_back(wt * 2 * pi / n_phi);
      }
    }
  }
};

V3 random_unit(Random& r) {
  for (;;) {
    const V3 v(r.uniform(-1, 1), r.uniform(-1, 1), r.uniform(-1, 1));
    if (v.norm() > 0.1 && v.norm() <= 1) return v.normalized();
  }
}

Sh_vector random_sh(Random& r) {
  Sh_vector s;
  for (int i = 0; i < 9; ++i) s(i) = r.uniform(-1, 1);
  return s;
}

M3 axis_angle(double angle, const V3& axis) { return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix(); }
M3 rz(double a) { return axis_angle(a, V3(0, 0, 1)); }
M3 ry(double a) { return axis_angle(a, V3(0, 1, 0)); }

// The geodesic distance in SO(3), through Eigen's angle-axis (independent of
// the atan2 formula of the header).
double angle_between(const M3& P, const M3& Q) {
  const Eigen::Quaterniond q(P.transpose() * Q);
  return 2 * std::atan2(q.vec().norm(), std::abs(q.w()));
}

// Hard rotations for D(R): tiny and near-pi angles about random and special
// axes, gimbal lock of the z-y-z angles (beta = 0 or pi exactly and nearly),
// the group elements, plus random ones.
std::vector<M3> test_rotations(Random& r, int random_count) {
  std::vector<M3> out;
  for (double a : {0.0, 1e-15, 1e-12, 1e-8, 1e-4, 0.5, pi / 2, 2.0, pi - 1e-4, pi - 1e-8, pi - 1e-12, pi}) {
    out.push_back(axis_angle(a, random_unit(r)));
    out.push_back(axis_angle(a, V3(0, 0, 1)));                              // beta = 0
    out.push_back(axis_angle(a, V3(r.uniform(-1, 1), r.uniform(-1, 1), 0))); // beta = a
    out.push_back(axis_angle(a, V3(1, 1, 1e-9)));
  }
  for (double b : {0.0, 1e-14, 1e-9, pi - 1e-9, pi - 1e-14, pi})
    out.push_back(rz(r.uniform(-pi, pi)) * ry(b) * rz(r.uniform(-pi, pi)));
  for (const M3& G : CGAL_ext::octahedral_group()) out.push_back(G);
  for (int i = 0; i < random_count; ++i) out.push_back(r.rotation());
  return out;
}

// exp(A) in long double: Taylor series with scaling and squaring.
Sh_matrix expm_reference(const Sh_matrix& A) {
  using ML = Eigen::Matrix<long double, 9, 9>;
  ML a = A.cast<long double>();
  int squarings = 0;
  while (a.cwiseAbs().rowwise().sum().maxCoeff() > 0.25L) a /= 2, ++squarings;
  ML sum = ML::Identity(), term = ML::Identity();
  for (int k = 1; k <= 30; ++k) {
    term = term * a / static_cast<long double>(k);
    sum += term;
  }
  for (int i = 0; i < squarings; ++i) sum = sum * sum;
  return sum.cast<double>();
}

Sh_matrix generator_combination(const V3& w) {
  const auto& L = CGAL_ext::sh_generators();
  return w(0) * L[0] + w(1) * L[1] + w(2) * L[2];
}

double energy(const M3& R, const Sh_vector& t) { return 0.5 * (CGAL_ext::octahedral_sh(R) - t).squaredNorm(); }

bool is_exact_integer_matrix(const M3& G) {
  for (int i = 0; i < 9; ++i)
    if (G.data()[i] != std::round(G.data()[i])) return false;
  return true;
}

} // namespace

// ---------------------------------------------------------------------------
// Basis and normalisation

TEST_CASE("the independent evaluator is orthonormal under the quadrature", "[frames]") {
  const Quadrature Q(12, 20); // exact for degree 8 products
  Eigen::Matrix<double, 9, 9> G = Eigen::Matrix<double, 9, 9>::Zero();
  for (std::size_t k = 0; k < Q.x.size(); ++k) {
    Sh_vector y;
    for (int m = -4; m <= 4; ++m) y(m + 4) = real_sh(m, Q.x[k]);
    G += Q.w[k] * y * y.transpose();
  }
  CHECK((G - Sh_matrix::Identity()).cwiseAbs().maxCoeff() <= 1e-13);
  // The quadrature integrates 1 to 4 pi and z^8 to 4 pi / 9.
  double one = 0, z8 = 0;
  for (std::size_t k = 0; k < Q.x.size(); ++k) one += Q.w[k], z8 += Q.w[k] * std::pow(Q.x[k](2), 8);
  CHECK(std::abs(one - 4 * pi) <= 1e-13);
  CHECK(std::abs(z8 - 4 * pi / 9) <= 1e-13);
}

TEST_CASE("sh_basis matches the Legendre definition (basis and ordering convention)", "[frames]") {
  Random r(1);
  double worst = 0;
  for (int k = 0; k < 2000; ++k) {
    V3 x = random_unit(r);
    if (k < 6) x = V3::Unit(k % 3) * (k < 3 ? 1 : -1); // poles and axes
    const Sh_vector y = CGAL_ext::sh_basis(3.7 * x);    // length is ignored
    for (int m = -4; m <= 4; ++m) worst = std::max(worst, std::abs(y(m + 4) - real_sh(m, x)));
    const Sh_vector s = random_sh(r);
    CHECK(std::abs(CGAL_ext::evaluate_sh(s, x) - f_of(s, x)) <= 1e-14);
  }
  CHECK(worst <= 1e-14);
  // Sign conventions spelled out in the header: Y_4 > 0 on +x, Y_-4 > 0 at 22.5 degrees, Y_1 > 0 on (1, 0, 1).
  CHECK(CGAL_ext::sh_basis(V3(1, 0, 0))(8) > 0);
  CHECK(CGAL_ext::sh_basis(V3(std::cos(pi / 8), std::sin(pi / 8), 0))(0) > 0);
  CHECK(CGAL_ext::sh_basis(V3(1, 0, 1))(5) > 0);
}

// ---------------------------------------------------------------------------
// The reference frame

TEST_CASE("s0 is the normalised x^4 + y^4 + z^4 - 3/5 and is octahedrally invariant", "[frames]") {
  const Sh_vector s0 = CGAL_ext::octahedral_reference_sh();
  CHECK(std::abs(s0.norm() - 1) <= 1e-15);
  CHECK(s0(4) == Approx(std::sqrt(7.0 / 12)).epsilon(1e-15));
  CHECK(s0(8) == Approx(std::sqrt(5.0 / 12)).epsilon(1e-15));
  CHECK(s0.cwiseAbs().sum() == Approx(std::sqrt(7.0 / 12) + std::sqrt(5.0 / 12)).epsilon(1e-15));

  // The normalisation constant c with |c (x^4+y^4+z^4 - mean)|_{L2} = 1, and
  // the mean, by quadrature.
  const Quadrature Q(12, 20);
  double mean = 0, sq = 0;
  auto quartic = [](const V3& x) { return std::pow(x(0), 4) + std::pow(x(1), 4) + std::pow(x(2), 4); };
  for (std::size_t k = 0; k < Q.x.size(); ++k) mean += Q.w[k] * quartic(Q.x[k]) / (4 * pi);
  CHECK(std::abs(mean - 0.6) <= 1e-14);
  for (std::size_t k = 0; k < Q.x.size(); ++k) sq += Q.w[k] * std::pow(quartic(Q.x[k]) - 0.6, 2);
  const double c = 1 / std::sqrt(sq);
  CHECK(std::abs(c - 5 * std::sqrt(21.0) / (8 * std::sqrt(pi))) <= 1e-13); // the documented constant

  Random r(2);
  for (int k = 0; k < 500; ++k) {
    const V3 x = random_unit(r);
    CHECK(std::abs(f_of(s0, x) - c * (quartic(x) - 0.6)) <= 1e-13);
    for (const M3& G : CGAL_ext::octahedral_group()) CHECK(std::abs(f_of(s0, G.transpose() * x) - f_of(s0, x)) <= 1e-13);
  }
  for (const M3& G : CGAL_ext::octahedral_group()) {
    CHECK((CGAL_ext::octahedral_sh(G) - s0).cwiseAbs().maxCoeff() <= 1e-15);
    CHECK((CGAL_ext::sh_rotation(G) * s0 - s0).cwiseAbs().maxCoeff() <= 1e-15);
  }
  // Not invariant under a non-octahedral rotation.
  CHECK((CGAL_ext::octahedral_sh(rz(0.3)) - s0).norm() > 0.1);
}

// ---------------------------------------------------------------------------
// D(R)

TEST_CASE("D(R) s is the function of s turned by R, at random points", "[frames]") {
  Random r(3);
  const std::vector<M3> rotations = test_rotations(r, 300);
  double worst = 0;
  for (const M3& R : rotations) {
    const Sh_matrix D = CGAL_ext::sh_rotation(R);
    for (int k = 0; k < 3; ++k) {
      const Sh_vector s = random_sh(r);
      const Sh_vector Ds = D * s;
      CHECK((CGAL_ext::rotate_sh(R, s) - Ds).cwiseAbs().maxCoeff() <= 1e-14);
      for (int p = 0; p < 20; ++p) {
        const V3 x = random_unit(r);
        worst = std::max(worst, std::abs(f_of(Ds, x) - f_of(s, R.transpose() * x)) / s.norm());
      }
    }
  }
  INFO("worst |f_{D(R)s}(x) - f_s(R^T x)| / |s| = " << worst);
  CHECK(worst <= 1e-14);
}

TEST_CASE("D is an orthogonal representation", "[frames]") {
  Random r(4);
  // Exact for the identity and the rotations about z.
  CHECK(CGAL_ext::sh_rotation(M3::Identity()) == Sh_matrix::Identity());
  const M3 half_turn_z = V3(-1, -1, 1).asDiagonal();
  CHECK(CGAL_ext::sh_rotation(half_turn_z) * CGAL_ext::sh_rotation(half_turn_z) == Sh_matrix::Identity());
  const std::vector<M3> rotations = test_rotations(r, 100);
  double orth = 0, hom = 0, inv = 0;
  for (std::size_t i = 0; i < rotations.size(); ++i) {
    const M3& R1 = rotations[i];
    const M3& R2 = rotations[(7 * i + 3) % rotations.size()];
    const Sh_matrix D1 = CGAL_ext::sh_rotation(R1), D2 = CGAL_ext::sh_rotation(R2);
    orth = std::max(orth, (D1.transpose() * D1 - Sh_matrix::Identity()).cwiseAbs().maxCoeff());
    hom = std::max(hom, (CGAL_ext::sh_rotation(M3(R1 * R2)) - D1 * D2).cwiseAbs().maxCoeff());
    inv = std::max(inv, (CGAL_ext::sh_rotation(M3(R1.transpose())) - D1.transpose()).cwiseAbs().maxCoeff());
    // Quaternion overloads: q and -q.
    const Eigen::Quaterniond q(R1);
    CHECK((CGAL_ext::sh_rotation(q) - D1).cwiseAbs().maxCoeff() <= 1e-15);
    CHECK((CGAL_ext::sh_rotation(Eigen::Quaterniond(-2 * q.coeffs())) - D1).cwiseAbs().maxCoeff() <= 1e-14);
  }
  INFO("orthogonality " << orth << ", homomorphism " << hom << ", transpose " << inv);
  CHECK(orth <= 1e-14);
  CHECK(hom <= 1e-14);
  CHECK(inv <= 1e-14);
  // The trace of D(R) is the band-4 character sin(9 a / 2) / sin(a / 2).
  for (double a : {0.1, 1.0, 2.0, 3.0}) {
    const M3 R = axis_angle(a, random_unit(r));
    CHECK(std::abs(CGAL_ext::sh_rotation(R).trace() - std::sin(4.5 * a) / std::sin(0.5 * a)) <= 1e-13);
  }
}

TEST_CASE("D is continuous through the gimbal lock and near pi", "[frames]") {
  // D(R) against D of a nearby rotation computed along a path that does not
  // pass through the special configuration: |D(R) - D(R')| <= C |R - R'|.
  Random r(5);
  for (double b : {0.0, pi}) {
    for (double eps : {1e-13, 1e-10, 1e-7}) {
      const double a = r.uniform(-pi, pi), g = r.uniform(-pi, pi);
      const M3 R0 = rz(a) * ry(b) * rz(g);
      const M3 R1 = rz(a) * ry(b + eps) * rz(g);
      const double dD = (CGAL_ext::sh_rotation(R0) - CGAL_ext::sh_rotation(R1)).norm();
      // The largest eigenvalue of w.L is 4 |w|: |D(R0) - D(R1)|_F <= 4 sqrt(9) angle.
      CHECK(dD <= 12 * angle_between(R0, R1) + 1e-14);
    }
  }
}

// D(R) M by rows of a 9xN matrix (Eigen row expressions), as rotate_sh() and
// sh_rotation() computed it before they went column by column: a reference
// for the bits of the column path, from the same constant tables.
template <class Mat>
Mat rotate_by_rows(const CGAL_ext::internal::Oct_euler& e, Mat M) {
  auto rotate_z = [&](const CGAL_ext::internal::Oct_multiples& a) {
    for (int m = 1; m <= 4; ++m) {
      const Eigen::Matrix<double, 1, Mat::ColsAtCompileTime> p = M.row(4 + m), n = M.row(4 - m);
      M.row(4 + m) = a.c[m] * p - a.s[m] * n;
      M.row(4 - m) = a.s[m] * p + a.c[m] * n;
    }
  };
  auto x90 = [&](bool transposed) { // the table's entries in order, as rows
    Mat out = Mat::Zero();
    for (const auto& t : CGAL_ext::internal::oct_x90)
      if (transposed)
        out.row(t.col) += t.value * M.row(t.row);
      else
        out.row(t.row) += t.value * M.row(t.col);
    M = out;
  };
  rotate_z(e.gamma);
  if (!(e.beta.s[1] == 0 && e.beta.c[1] == 1)) {
    x90(false);
    rotate_z(e.beta);
    x90(true);
  }
  rotate_z(e.alpha);
  return M;
}

TEST_CASE("a face's transport applied from its stored Euler angles is rotate_sh bit for bit", "[frames]") {
  // The energy keeps each face's transport as the cosines and sines of its
  // Euler angles (internal::Oct_euler_angles) and applies up to four at once
  // (internal::oct_apply_lanes); the field must depend on neither.
  Random r(17);
  std::vector<Eigen::Quaterniond> qs = {Eigen::Quaterniond::Identity(), Eigen::Quaterniond(0, 0, 0, 1),
                                        Eigen::Quaterniond(0, 1, 0, 0), Eigen::Quaterniond(std::sqrt(0.5), 0, std::sqrt(0.5), 0)};
  for (int k = 0; k < 200; ++k) qs.push_back(Eigen::Quaterniond(r.rotation()));
  for (int k = 0; k < 20; ++k) // near the gimbal lock: beta 1e-9 from 0 and from pi
    for (double b : {1e-9, pi - 1e-9}) qs.push_back(Eigen::Quaterniond(rz(r.uniform(-pi, pi)) * ry(b) * rz(r.uniform(-pi, pi))));
  for (int k = 0; k < 6; ++k) // rotations about z (their own path) mixed in among the lanes
    qs.insert(qs.begin() + 7 * k + 5, Eigen::Quaterniond(rz(r.uniform(-pi, pi))));
  const std::size_t n = qs.size();
  std::vector<CGAL_ext::Sh_vector> s(n);
  for (auto& v : s) {
    for (int i = 0; i < 9; ++i) v(i) = r.uniform(-1, 1);
    if (r.uniform(0, 1) < 0.2) v(3) = -0.0, v(6) = 0.0; // signed zeros keep their sign as rotate_sh gives it
  }
  std::vector<CGAL_ext::internal::Oct_euler_angles> angles(n);
  for (std::size_t k = 0; k < n; ++k) angles[k] = CGAL_ext::internal::oct_euler_angles(qs[k]);
  int differ = 0, differ_matrix = 0, differ_lanes = 0, differ_in_place = 0;
  double worst = 0;
  auto same = [](const CGAL_ext::Sh_vector& a, const CGAL_ext::Sh_vector& b) {
    return std::memcmp(a.data(), b.data(), sizeof(double) * 9) == 0;
  };
  for (std::size_t first = 0, width = 1; first < n; first += width, width = width % 4 + 1) {
    const int m = int(std::min(width, n - first));
    const CGAL_ext::internal::Oct_euler_angles* a[4];
    const CGAL_ext::Sh_vector* from[4];
    CGAL_ext::Sh_vector out[4], in_place[4];
    CGAL_ext::Sh_vector *to[4], *to_in_place[4];
    for (int l = 0; l < m; ++l) {
      a[l] = &angles[first + l], from[l] = &s[first + l], to[l] = &out[l];
      in_place[l] = s[first + l], to_in_place[l] = &in_place[l];
    }
    CGAL_ext::internal::oct_apply_lanes(m, a, from, to);
    CGAL_ext::internal::oct_apply_lanes(m, a, to_in_place, to_in_place);
    for (int l = 0; l < m; ++l) {
      const CGAL_ext::Sh_vector expected = CGAL_ext::rotate_sh(qs[first + l], s[first + l]);
      const CGAL_ext::internal::Oct_euler e = CGAL_ext::internal::oct_euler(angles[first + l]);
      differ += !same(expected, rotate_by_rows(e, s[first + l]));
      using Row_major = Eigen::Matrix<double, 9, 9, Eigen::RowMajor>;
      const Row_major D = CGAL_ext::sh_rotation(qs[first + l]), D_rows = rotate_by_rows(e, Row_major(Row_major::Identity()));
      differ_matrix += std::memcmp(D.data(), D_rows.data(), sizeof(double) * 81) != 0;
      differ_lanes += !same(expected, out[l]);
      differ_in_place += !same(expected, in_place[l]);
      worst = std::max({worst, (expected - out[l]).cwiseAbs().maxCoeff(), (expected - in_place[l]).cwiseAbs().maxCoeff()});
    }
  }
  CHECK(worst <= 1e-14);
#if defined(__FMA__) || defined(__FP_FAST_FMA)
  // With FMA instructions (e.g. -march=native) the compiler may fuse the
  // lanes' and the scalar path's products differently: the last bits may
  // differ between them (each is still the same for any thread count).
  WARN("FMA build: lanes and rows compared to 1e-14, not bit for bit (" << differ_lanes << " lanes, " << differ
                                                                         << " rows differ in their last bits)");
#else
  CHECK(differ == 0);
  CHECK(differ_matrix == 0);
  CHECK(differ_lanes == 0);
  CHECK(differ_in_place == 0);
#endif
}

TEST_CASE("generators: skew, commutators, exp(w.L) = D(exp([w]_x)), derivative of functions", "[frames]") {
  const auto& L = CGAL_ext::sh_generators();
  for (int k = 0; k < 3; ++k) CHECK((L[k] + L[k].transpose()).cwiseAbs().maxCoeff() == 0);
  CHECK((L[0] * L[1] - L[1] * L[0] - L[2]).cwiseAbs().maxCoeff() <= 1e-14);
  CHECK((L[1] * L[2] - L[2] * L[1] - L[0]).cwiseAbs().maxCoeff() <= 1e-14);
  CHECK((L[2] * L[0] - L[0] * L[2] - L[1]).cwiseAbs().maxCoeff() <= 1e-14);
  // Casimir: L.L = -l (l + 1) I = -20 I.
  CHECK((L[0] * L[0] + L[1] * L[1] + L[2] * L[2] + 20 * Sh_matrix::Identity()).cwiseAbs().maxCoeff() <= 1e-13);

  Random r(6);
  double worst = 0;
  for (double a : {1e-10, 1e-3, 0.7, 2.0, pi / 2, pi - 1e-6, pi - 1e-12, pi}) {
    for (int k = 0; k < 5; ++k) {
      const V3 w = a * random_unit(r);
      const Sh_matrix E = expm_reference(generator_combination(w));
      const M3 R = axis_angle(w.norm(), w);
      worst = std::max(worst, (CGAL_ext::sh_rotation(R) - E).cwiseAbs().maxCoeff());
    }
  }
  INFO("worst |D(exp(w)) - exp(w.L)| = " << worst);
  CHECK(worst <= 1e-14);

  // L_k s is the derivative of x -> f_s(exp(-t [e_k]_x) x) at t = 0 (central differences).
  for (int k = 0; k < 3; ++k) {
    const Sh_vector s = random_sh(r);
    const Sh_vector Ls = L[k] * s;
    const double h = 1e-4;
    for (int p = 0; p < 20; ++p) {
      const V3 x = random_unit(r);
      const double fd = (f_of(s, axis_angle(-h, V3::Unit(k)) * x) - f_of(s, axis_angle(h, V3::Unit(k)) * x)) / (2 * h);
      CHECK(std::abs(f_of(Ls, x) - fd) <= 1e-7);
    }
  }
}

TEST_CASE("sh_rotation_jacobian is the derivative of D(exp([w]_x)) s", "[frames]") {
  Random r(7);
  for (int k = 0; k < 20; ++k) {
    const Sh_vector s = k % 2 ? random_sh(r) : CGAL_ext::octahedral_sh(r.rotation());
    const Eigen::Matrix<double, 9, 3> J = CGAL_ext::sh_rotation_jacobian(s);
    // Fourth-order central differences, h = 1e-3: truncation about
    // h^4 |L|^5 |s| / 30 <= 1e-12 * 4^5 * 3 / 30 = 1e-10, rounding about 1e-13.
    const double h = 1e-3;
    for (int c = 0; c < 3; ++c) {
      auto at = [&](double a) { return CGAL_ext::rotate_sh(axis_angle(a, V3::Unit(c)), s); };
      const Sh_vector fd = (8 * (at(h) - at(-h)) - (at(2 * h) - at(-2 * h))) / (12 * h);
      CHECK((J.col(c) - fd).cwiseAbs().maxCoeff() <= 1e-9);
    }
    if (k % 2 == 0) CHECK((J.transpose() * J - (20.0 / 3) * M3::Identity()).cwiseAbs().maxCoeff() <= 1e-13);
  }
}

// ---------------------------------------------------------------------------
// The octahedral group, matching, distance, canonical frame

TEST_CASE("the octahedral group: 24 distinct exact rotations, closed, identity first", "[frames]") {
  const auto& G = CGAL_ext::octahedral_group();
  CHECK(G[0] == M3::Identity());
  std::set<std::vector<double>> distinct;
  for (const M3& g : G) {
    CHECK(is_exact_integer_matrix(g));
    CHECK(g.determinant() == 1);
    CHECK(g.transpose() * g == M3::Identity());
    CHECK(g.cwiseAbs().sum() == 3); // a signed permutation
    distinct.insert(std::vector<double>(g.data(), g.data() + 9));
  }
  CHECK(distinct.size() == 24);
  for (int i = 0; i < 24; ++i) {
    CHECK(CGAL_ext::octahedral_group_index(G[i]) == i);
    CHECK(CGAL_ext::octahedral_group_index(M3(G[i].transpose())) >= 0);
    for (int j = 0; j < 24; ++j) {
      const M3 p = G[i] * G[j];
      CHECK(is_exact_integer_matrix(p));
      CHECK(CGAL_ext::octahedral_group_index(p, 0.0) >= 0);
    }
  }
  Random r(8);
  CHECK(CGAL_ext::octahedral_group_index(r.rotation()) == -1);
  // The rotation angles of the group: 1 x 0, 9 x 90/180 about the axes (6 x 90,
  // 3 x 180), 6 x 180 about face diagonals, 8 x 120 about the body diagonals.
  std::array<int, 4> angles{}; // 0, 90, 120, 180
  for (const M3& g : G) {
    const double a = angle_between(M3::Identity(), g) * 180 / pi;
    for (int k = 0; k < 4; ++k)
      if (std::abs(a - std::array<double, 4>{0, 90, 120, 180}[k]) < 1e-9) ++angles[k];
  }
  CHECK(angles == std::array<int, 4>{1, 6, 8, 9});
}

TEST_CASE("closest_octahedral_matching recovers G and the residual angle", "[frames]") {
  Random r(9);
  const auto& G = CGAL_ext::octahedral_group();
  for (int k = 0; k < 50; ++k) {
    const M3 Ri = r.rotation();
    for (int g = 0; g < 24; ++g) {
      // R_j = R_i G^T exactly: the matching is G, the angle ~0.
      const M3 Rj = Ri * G[g].transpose();
      const CGAL_ext::Octahedral_matching m = CGAL_ext::closest_octahedral_matching(Ri, Rj);
      CHECK(m.index == g);
      CHECK(m.G == G[g]);
      CHECK(m.angle <= 1e-15);
      // With a perturbation E of angle < 45 degrees: R_j = R_i E G^T.
      const double a = r.uniform(0, 0.75);
      const M3 E = axis_angle(a, random_unit(r));
      const CGAL_ext::Octahedral_matching mp = CGAL_ext::closest_octahedral_matching(Ri, M3(Ri * E * G[g].transpose()));
      CHECK(mp.index == g);
      CHECK(std::abs(mp.angle - a) <= 1e-14);
    }
  }
}

TEST_CASE("octahedral_distance: brute force, symmetry, invariance, maximum", "[frames]") {
  Random r(10);
  const auto& G = CGAL_ext::octahedral_group();
  double largest = 0;
  for (int k = 0; k < 2000; ++k) {
    const M3 A = r.rotation(), B = r.rotation(), Q = r.rotation();
    const double d = CGAL_ext::octahedral_distance(A, B);
    double brute = 10;
    for (const M3& g : G) brute = std::min(brute, angle_between(A, B * g));
    CHECK(std::abs(d - brute) <= 1e-14);
    CHECK(std::abs(CGAL_ext::octahedral_distance(B, A) - d) <= 1e-14);
    CHECK(std::abs(CGAL_ext::octahedral_distance(M3(Q * A), M3(Q * B)) - d) <= 1e-13);
    CHECK(std::abs(CGAL_ext::octahedral_distance(M3(A * G[k % 24]), M3(B * G[(5 * k) % 24])) - d) <= 1e-14);
    CHECK(d <= CGAL_ext::octahedral_max_distance + 1e-15);
    largest = std::max(largest, d);
  }
  CHECK(largest > 1.0); // random pairs come close to the maximum
  // The corner of the cubic fundamental zone, Rodrigues vector
  // (sqrt2 - 1, sqrt2 - 1, (sqrt2 - 1)^2), is at the maximal distance.
  const double t = std::sqrt(2.0) - 1;
  const V3 rod(t, t, t * t);
  const M3 corner = axis_angle(2 * std::atan(rod.norm()), rod);
  CHECK(std::abs(CGAL_ext::octahedral_distance(M3::Identity(), corner) - CGAL_ext::octahedral_max_distance) <= 1e-14);
  // 2 atan(sqrt(23 - 16 sqrt2)), written without the cancellation of 23 - 16 sqrt2.
  CHECK(std::abs(CGAL_ext::octahedral_max_distance - 2 * std::atan(t * std::sqrt(2 + t * t))) <= 5e-16);
}

TEST_CASE("matchings around a loop: the product is the monodromy, up to conjugation", "[frames]") {
  // Frames R_k = Q_base Rz(k pi / (2 n)) G'_k, k = 0..n-1, with arbitrary
  // relabelings G'_k of the group: the loop closes on Q_base Rz(pi/2) = Q_0 H
  // with H = Rz(pi/2), a quarter-turn singularity about the frame's z axis.
  // With G_k = matching(R_k, R_{k+1}) (R_{k+1} G_k ~ R_k), the product
  // G_{n-1} ... G_1 G_0 telescopes to G'_0^T H G'_0, exactly; a regular loop
  // (H = I) gives the identity.
  Random r(17);
  const auto& G = CGAL_ext::octahedral_group();
  const int n = 12;
  const M3 H = (M3() << 0, -1, 0, 1, 0, 0, 0, 0, 1).finished();
  for (int quarter : {1, 0}) {
    for (int trial = 0; trial < 20; ++trial) {
      const M3 base = r.rotation();
      std::vector<int> label(n);
      std::vector<M3> frames;
      for (int k = 0; k < n; ++k) {
        label[k] = static_cast<int>(r.uniform(0, 24)) % 24;
        frames.push_back(base * rz(quarter * 0.5 * pi * k / n) * G[label[k]]);
      }
      M3 product = M3::Identity();
      for (int k = 0; k < n; ++k) product = CGAL_ext::closest_octahedral_matching(frames[k], frames[(k + 1) % n]).G * product;
      CHECK(is_exact_integer_matrix(product));
      const M3 expected = quarter ? M3(G[label[0]].transpose() * H * G[label[0]]) : M3::Identity();
      CHECK(product == expected);
    }
  }
}

TEST_CASE("canonicalize_frame: exact coset invariance, closest to the identity", "[frames]") {
  Random r(11);
  const auto& G = CGAL_ext::octahedral_group();
  for (int k = 0; k < 500; ++k) {
    const M3 R = k < 24 ? G[k] : (k < 30 ? rz(pi / 4) * G[k % 24] : r.rotation()); // includes exact ties
    const M3 C = CGAL_ext::canonicalize_frame(R);
    const int g = CGAL_ext::octahedral_group_index(R.transpose() * C, 1e-12);
    CHECK(g >= 0);
    CHECK(C == R * G[std::max(g, 0)]); // exactly in the coset
    for (const M3& h : G) {
      CHECK(CGAL_ext::canonicalize_frame(M3(R * h)) == C); // bit for bit
      CHECK(C.trace() >= (R * h).trace());
    }
    CHECK(angle_between(M3::Identity(), C) <= CGAL_ext::octahedral_max_distance + 1e-14);
  }
  for (const M3& g : G) CHECK(CGAL_ext::canonicalize_frame(g) == M3::Identity());
}

// ---------------------------------------------------------------------------
// Projection onto the octahedral variety

TEST_CASE("projection round trip: exact frames are recovered to machine precision", "[frames]") {
  Random r(12);
  const std::vector<M3> rotations = test_rotations(r, 1000);
  double worst_distance = 0, worst_residual = 0;
  for (const M3& R : rotations) {
    const Sh_vector s = CGAL_ext::octahedral_sh(R);
    const CGAL_ext::Octahedral_projection p = CGAL_ext::rotation_from_octahedral_sh(s);
    worst_distance = std::max(worst_distance, CGAL_ext::octahedral_distance(p.rotation, R));
    worst_residual = std::max(worst_residual, p.residual);
    CHECK(p.converged);
    CHECK(p.rotation == CGAL_ext::canonicalize_frame(p.rotation));
    CHECK((p.rotation.transpose() * p.rotation - M3::Identity()).cwiseAbs().maxCoeff() <= 1e-15);
    CHECK(std::abs(p.rotation.determinant() - 1) <= 1e-15);
    CHECK((p.sh - CGAL_ext::octahedral_sh(p.rotation)).cwiseAbs().maxCoeff() <= 1e-15);
  }
  INFO("worst octahedral distance " << worst_distance << ", worst residual " << worst_residual);
  CHECK(worst_distance <= 1e-13);
  CHECK(worst_residual <= 1e-14);
}

TEST_CASE("projection of noisy and arbitrary vectors: local minimum, no worse than brute force", "[frames]") {
  // Fine grid over all of SO(3) in z-y-z Euler angles (independent of the
  // grid inside the header): 72 x 36 x 72 rotations, spacing 5 degrees.
  std::vector<Sh_vector> grid;
  for (int i = 0; i < 72; ++i)
    for (int j = 0; j < 36; ++j)
      for (int k = 0; k < 72; ++k)
        grid.push_back(CGAL_ext::octahedral_sh(M3(rz(2 * pi * i / 72) * ry(pi * (j + 0.5) / 36) * rz(2 * pi * k / 72))));
  Random r(13);
  for (double sigma : {1e-3, 1e-2, 0.1, 0.3, 1.0, 100.0}) {
    for (int trial = 0; trial < 12; ++trial) {
      Sh_vector t = CGAL_ext::octahedral_sh(r.rotation());
      for (int i = 0; i < 9; ++i) t(i) += sigma * r.uniform(-1.7320508, 1.7320508);
      const CGAL_ext::Octahedral_projection p = CGAL_ext::rotation_from_octahedral_sh(t);
      CHECK(p.converged);
      CHECK(std::abs(p.residual - (CGAL_ext::octahedral_sh(p.rotation) - t).norm()) <= 1e-14 * (1 + t.norm()));
      // Gradient by central differences of the energy: zero.
      const double h = 1e-5;
      V3 g;
      for (int c = 0; c < 3; ++c)
        g(c) = (energy(M3(axis_angle(h, V3::Unit(c)) * p.rotation), t) -
                energy(M3(axis_angle(-h, V3::Unit(c)) * p.rotation), t)) / (2 * h);
      CHECK(g.norm() <= 1e-8 * (1 + t.norm()));
      CHECK(p.gradient_norm <= 1e-9 * (1 + t.norm()));
      // Local minimum: no small rotation lowers the energy.
      const double e0 = energy(p.rotation, t);
      for (int k = 0; k < 20; ++k)
        CHECK(energy(M3(axis_angle(1e-3, random_unit(r)) * p.rotation), t) >= e0);
      // No worse than the fine grid, nor than Newton from 40 random starts.
      double brute = 1e300;
      for (const Sh_vector& v : grid) brute = std::min(brute, (v - t).norm());
      CHECK(p.residual <= brute + 1e-12);
      for (int k = 0; k < 40; ++k)
        CHECK(p.residual <= CGAL_ext::rotation_from_octahedral_sh(t, r.rotation()).residual + 1e-12 * (1 + t.norm()));
    }
  }
}

TEST_CASE("projection: scale invariance, determinism, warm start, degenerate input", "[frames]") {
  Random r(14);
  for (int k = 0; k < 50; ++k) {
    const M3 R = r.rotation();
    Sh_vector t = CGAL_ext::octahedral_sh(R);
    for (int i = 0; i < 9; ++i) t(i) += 0.2 * r.uniform(-1, 1);
    const CGAL_ext::Octahedral_projection p = CGAL_ext::rotation_from_octahedral_sh(t);
    const CGAL_ext::Octahedral_projection again = CGAL_ext::rotation_from_octahedral_sh(t);
    CHECK(again.rotation == p.rotation); // bit for bit
    CHECK(CGAL_ext::octahedral_distance(CGAL_ext::rotation_from_octahedral_sh(Sh_vector(3.5 * t)).rotation, p.rotation) <= 1e-12);
    // Warm start from any representative of the true frame, 0.45 rad off.
    const M3 start = axis_angle(0.45, random_unit(r)) * R * CGAL_ext::octahedral_group()[k % 24];
    const CGAL_ext::Octahedral_projection w = CGAL_ext::rotation_from_octahedral_sh(t, start);
    CHECK(w.converged);
    CHECK(CGAL_ext::octahedral_distance(w.rotation, p.rotation) <= 1e-12);
    CHECK(std::abs(w.residual - p.residual) <= 1e-14);
  }
  const CGAL_ext::Octahedral_projection z = CGAL_ext::rotation_from_octahedral_sh(Sh_vector::Zero());
  CHECK(z.rotation == M3::Identity());
  CHECK(z.residual == 1);
  Sh_vector bad = Sh_vector::Zero();
  bad(3) = std::numeric_limits<double>::quiet_NaN();
  const CGAL_ext::Octahedral_projection n = CGAL_ext::rotation_from_octahedral_sh(bad);
  CHECK_FALSE(n.converged);
  CHECK(std::isnan(n.residual));
}

// ---------------------------------------------------------------------------
// No heap allocation (after the first calls, which build the constant tables).

TEST_CASE("the frame algebra does not allocate", "[frames]") {
#ifdef CGAL_EXT_TEST_COUNT_MALLOC
  Random r(16);
  std::vector<M3> R(50);
  std::vector<Sh_vector> t(50);
  for (int i = 0; i < 50; ++i) {
    R[i] = r.rotation();
    t[i] = CGAL_ext::octahedral_sh(R[i]) + 0.3 * random_sh(r);
  }
  const long probe = malloc_calls.load();
  void* p = std::malloc(16); // the counter works
  std::free(p);
  CHECK(malloc_calls.load() == probe + 1);
  CGAL_ext::rotation_from_octahedral_sh(t[0]); // builds the tables
  CGAL_ext::sh_generators();
  double sink = 0;
  const long before = malloc_calls.load();
  for (int i = 0; i < 50; ++i) {
    const M3& Q = R[i];
    sink += CGAL_ext::sh_rotation(Q)(1, 2) + CGAL_ext::sh_rotation(Eigen::Quaterniond(Q))(2, 1);
    sink += CGAL_ext::rotate_sh(Q, t[i])(0) + CGAL_ext::octahedral_sh(Q)(3);
    sink += CGAL_ext::sh_rotation_jacobian(t[i])(4, 1) + CGAL_ext::sh_generators()[1](0, 1);
    sink += CGAL_ext::evaluate_sh(t[i], Q.col(0)) + CGAL_ext::sh_basis(Q.col(1))(2);
    sink += CGAL_ext::rotation_from_octahedral_sh(t[i]).residual;
    CGAL_ext::Octahedral_projection_options many;
    many.seeds = 8;
    many.seed_margin = 10;
    sink += CGAL_ext::rotation_from_octahedral_sh(t[i], many).residual;
    sink += CGAL_ext::rotation_from_octahedral_sh(t[i], R[i]).residual;
    sink += CGAL_ext::closest_octahedral_matching(Q, R[(i + 1) % 50]).angle;
    sink += CGAL_ext::octahedral_distance(Q, R[(i + 1) % 50]) + CGAL_ext::canonicalize_frame(Q)(0, 0);
    sink += CGAL_ext::octahedral_group_index(CGAL_ext::octahedral_group()[i % 24]);
  }
  const long after = malloc_calls.load();
  CHECK(std::isfinite(sink));
  CHECK(after == before);
#else
  WARN("malloc interposition not available here: allocation test skipped");
#endif
}

// ---------------------------------------------------------------------------
// Measured accuracy and timings for doc/octahedral_frames.md (hidden: run
// `test_octahedral_frame "[report]"`). Prints, asserts nothing.

TEST_CASE("octahedral frame accuracy and timings report", "[.][report]") {
  Random r(15);
  {
    const std::vector<M3> rotations = test_rotations(r, 2000);
    double fun = 0, orth = 0, expo = 0, trip_d = 0, trip_r = 0;
    for (const M3& R : rotations) {
      const Sh_matrix D = CGAL_ext::sh_rotation(R);
      const Sh_vector s = random_sh(r), Ds = D * s;
      for (int p = 0; p < 10; ++p) {
        const V3 x = random_unit(r);
        fun = std::max(fun, std::abs(f_of(Ds, x) - f_of(s, R.transpose() * x)) / s.norm());
      }
      orth = std::max(orth, (D.transpose() * D - Sh_matrix::Identity()).cwiseAbs().maxCoeff());
      const Eigen::AngleAxisd aa(R);
      expo = std::max(expo, (D - expm_reference(generator_combination(aa.angle() * aa.axis()))).cwiseAbs().maxCoeff());
      const CGAL_ext::Octahedral_projection p = CGAL_ext::rotation_from_octahedral_sh(CGAL_ext::octahedral_sh(R));
      trip_d = std::max(trip_d, CGAL_ext::octahedral_distance(p.rotation, R));
      trip_r = std::max(trip_r, p.residual);
    }
    std::printf("accuracy over %zu rotations (incl. near 0, near pi, gimbal lock):\n", rotations.size());
    std::printf("  max |f_{D(R)s}(x) - f_s(R^T x)| / |s|  %.2e\n", fun);
    std::printf("  max |D(R) - exp(w.L)| (long double)    %.2e\n", expo);
    std::printf("  max |D^T D - I|                        %.2e\n", orth);
    std::printf("  round trip: max octahedral distance    %.2e rad, max residual %.2e\n", trip_d, trip_r);
  }
  const int n = 20000;
  std::vector<M3> R(n);
  std::vector<Sh_vector> s(n), noisy(n);
  for (int i = 0; i < n; ++i) {
    R[i] = r.rotation();
    s[i] = CGAL_ext::octahedral_sh(R[i]);
    noisy[i] = s[i];
    for (int k = 0; k < 9; ++k) noisy[i](k) += 0.1 * r.uniform(-1, 1);
  }
  long iterations[3] = {0, 0, 0};
  for (int i = 0; i < n; ++i) {
    iterations[0] += CGAL_ext::rotation_from_octahedral_sh(s[i]).iterations;
    iterations[1] += CGAL_ext::rotation_from_octahedral_sh(noisy[i]).iterations;
    iterations[2] += CGAL_ext::rotation_from_octahedral_sh(noisy[i], R[i]).iterations;
  }
  std::printf("mean Newton iterations: exact %.2f, noise 0.1 %.2f, warm start %.2f\n", double(iterations[0]) / n,
              double(iterations[1]) / n, double(iterations[2]) / n);
  auto time = [&](const char* name, auto&& f) {
    double sink = 0;
    const auto t0 = std::chrono::steady_clock::now();
    for (int rep = 0; rep < 5; ++rep)
      for (int i = 0; i < n; ++i) sink += f(i);
    const double ns = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count() / (5.0 * n);
    std::printf("%-44s %8.1f ns   (%g)\n", name, ns, sink);
  };
  time("sh_rotation(R) (9x9 D(R))", [&](int i) { return CGAL_ext::sh_rotation(R[i])(3, 5); });
  time("rotate_sh(R, s)", [&](int i) { return CGAL_ext::rotate_sh(R[i], s[(i + 1) % n])(3); });
  time("octahedral_sh(R)", [&](int i) { return CGAL_ext::octahedral_sh(R[i])(3); });
  time("sh_rotation_jacobian(s)", [&](int i) { return CGAL_ext::sh_rotation_jacobian(s[i])(3, 1); });
  time("rotation_from_octahedral_sh, exact", [&](int i) { return CGAL_ext::rotation_from_octahedral_sh(s[i]).residual; });
  time("rotation_from_octahedral_sh, noise 0.1", [&](int i) { return CGAL_ext::rotation_from_octahedral_sh(noisy[i]).residual; });
  time("  same, warm start from the true R", [&](int i) { return CGAL_ext::rotation_from_octahedral_sh(noisy[i], R[i]).residual; });
  time("closest_octahedral_matching", [&](int i) { return CGAL_ext::closest_octahedral_matching(R[i], R[(i + 1) % n]).angle; });
  time("canonicalize_frame", [&](int i) { return CGAL_ext::canonicalize_frame(R[i])(0, 0); });
}
