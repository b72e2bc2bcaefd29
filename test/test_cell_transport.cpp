// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
// Transport inside one cell (doc/math.md section 4): accuracy of both schemes
// against an independent high-accuracy integration, evaluation counts, the
// analytic check of doc/math.md section 6, exactness for a constant metric,
// reversal, composition and scale invariance.
#include <CGAL_ext/Cell_transport_3.h>
#include <CGAL_ext/Connection_3.h>
#include <CGAL_ext/Metric_tensor.h>

#include <catch2/catch.hpp>

#include "test_support.h"

#include <Eigen/Geometry>
#include <Eigen/SVD>

#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

namespace {

using CGAL_ext::testing::Random;

using M3 = Eigen::Matrix3d;
using V3 = Eigen::Vector3d;
using CGAL_ext::Transport_options;
using CGAL_ext::Transport_scheme;


// A random tet with random vertex metrics, and the PL field in it, computed
// here with the 4x4 barycentric matrix of doc/math.md section 2 (independently of
// Metric_field_3).
struct Tet_case {
  std::array<V3, 4> p;
  std::array<M3, 4> A;
  M3 curl;
  Eigen::Matrix4d T; // lambda = T [x; 1]

  M3 A_at(const V3& x) const {
    const Eigen::Vector4d l = T * Eigen::Vector4d(x(0), x(1), x(2), 1);
    M3 r = M3::Zero();
    for (int v = 0; v < 4; ++v) r += l(v) * A[v];
    return r;
  }
  V3 random_point(Random& r) const {
    std::array<double, 4> l;
    double s = 0;
    for (double& x : l) s += (x = -std::log(r.uniform(1e-12, 1)));
    V3 q = V3::Zero();
    for (int v = 0; v < 4; ++v) q += (l[v] / s) * p[v];
    return q;
  }
};

Tet_case random_tet(Random& r, double lo, double hi) {
  Tet_case t;
  for (;;) {
    for (V3& x : t.p) x = V3(r.uniform(-1, 1), r.uniform(-1, 1), r.uniform(-1, 1));
    M3 E;
    for (int v = 0; v < 3; ++v) E.col(v) = t.p[v + 1] - t.p[0];
    if (std::abs(E.determinant()) > 0.1) break; // not too flat
  }
  for (M3& a : t.A) a = CGAL_ext::sqrt_spd(r.spd(lo, hi));
  Eigen::Matrix4d P;
  for (int v = 0; v < 4; ++v) P.col(v) << t.p[v], 1;
  t.T = P.inverse();
  std::array<M3, 3> dA;
  for (int k = 0; k < 3; ++k) {
    dA[k].setZero();
    for (int v = 0; v < 4; ++v) dA[k] += t.T(v, k) * t.A[v];
  }
  for (int i = 0; i < 3; ++i)
    t.curl.col(i) = V3(dA[1](2, i) - dA[2](1, i), dA[2](0, i) - dA[0](2, i), dA[0](1, i) - dA[1](0, i));
  return t;
}

// Reference: classical RK4 on R' = [u]_x R with n steps, W from the 9x9
// solve (not the closed form), then projected onto SO(3).
template <class Generator>
M3 reference_transport(Generator&& u, int n) {
  M3 R = M3::Identity();
  const double h = 1.0 / n;
  auto f = [&](double t, const M3& X) -> M3 { return CGAL_ext::cross_product_matrix(u(t)) * X; };
  for (int i = 0; i < n; ++i) {
    const double t = i * h;
    const M3 k1 = f(t, R), k2 = f(t + h / 2, R + (h / 2) * k1), k3 = f(t + h / 2, R + (h / 2) * k2),
             k4 = f(t + h, R + h * k3);
    R += (h / 6) * (k1 + 2 * k2 + 2 * k3 + k4);
  }
  Eigen::JacobiSVD<M3> svd(R, Eigen::ComputeFullU | Eigen::ComputeFullV);
  return svd.matrixU() * svd.matrixV().transpose();
}

double distance(const M3& P, const M3& Q) { return CGAL_ext::rotation_angle(P.transpose() * Q); }

bool is_rotation(const M3& R, double eps) {
  return (R.transpose() * R - M3::Identity()).norm() <= eps && std::abs(R.determinant() - 1) <= eps;
}

} // namespace

TEST_CASE("rotation_exp and rotation_angle", "[transport]") {
  CHECK(CGAL_ext::rotation_exp(V3::Zero()) == M3::Identity()); // exactly
  Random r(11);
  for (double theta : {1e-14, 1e-9, 1e-5, 1e-4, 2e-4, 0.3, 1.0, 2.5, 3.1}) {
    V3 axis(r.uniform(-1, 1), r.uniform(-1, 1), r.uniform(-1, 1));
    axis.normalize();
    const M3 R = CGAL_ext::rotation_exp(theta * axis);
    const M3 expected = Eigen::AngleAxisd(theta, axis).toRotationMatrix();
    CHECK((R - expected).norm() <= 4e-16 * 3);
    CHECK(is_rotation(R, 1e-15));
    CHECK(std::abs(CGAL_ext::rotation_angle(R) - theta) <= 1e-15 * std::max(1.0, theta) + 1e-15 * theta);
  }
  // Tiny angles keep full relative accuracy (acos would return 0 here).
  const M3 R = Eigen::AngleAxisd(3e-12, V3(0, 0, 1)).toRotationMatrix();
  CHECK(std::abs(CGAL_ext::rotation_angle(R) - 3e-12) <= 1e-6 * 3e-12);
}

TEST_CASE("the reference integration is converged", "[transport]") {
  // The reference of the accuracy test is trusted only if halving its step
  // changes it by far less than the smallest tolerance tested (1e-10).
  Random r(12);
  for (int k = 0; k < 3; ++k) {
    const Tet_case t = random_tet(r, 0.2, 5);
    const V3 a = t.random_point(r), b = t.random_point(r);
    auto u = [&](double s) -> V3 {
      return CGAL_ext::connection_one_form_by_solve(t.A_at(a + s * (b - a)), t.curl).transpose() * (b - a);
    };
    CHECK(distance(reference_transport(u, 1 << 13), reference_transport(u, 1 << 14)) <= 1e-12);
  }
}

TEST_CASE("transport error is within the tolerance, and Magnus needs far fewer evaluations", "[transport]") {
  // Random SPD vertex metrics (eigenvalues in [0.2, 5], sizes 0.45..2.2) on
  // random tets of size ~1, segments between random points of the tet.
  Random r(13);
  const int cases = 12;
  const double tols[3] = {1e-6, 1e-8, 1e-10};
  double worst_ratio[2][3] = {};
  std::size_t evals[2][3] = {};
  double mean_angle = 0;
  for (int k = 0; k < cases; ++k) {
    const Tet_case t = random_tet(r, 0.2, 5);
    const V3 a = t.random_point(r), b = t.random_point(r);
    const M3 Aa = t.A_at(a), Ab = t.A_at(b);
    auto u = [&](double s) -> V3 {
      return CGAL_ext::connection_one_form_by_solve(t.A_at(a + s * (b - a)), t.curl).transpose() * (b - a);
    };
    const M3 ref = reference_transport(u, 1 << 14);
    mean_angle += CGAL_ext::rotation_angle(ref) / cases;
    for (int s = 0; s < 2; ++s)
      for (int i = 0; i < 3; ++i) {
        Transport_options opt;
        opt.scheme = s == 0 ? Transport_scheme::trapezoid : Transport_scheme::magnus;
        opt.tolerance = tols[i];
        const CGAL_ext::Transport_result res = CGAL_ext::cell_transport(Aa, Ab, t.curl, b - a, opt);
        const double err = distance(ref, res.rotation);
        INFO("case " << k << " scheme " << s << " tol " << tols[i] << " error " << err << " estimate "
                     << res.error_estimate);
        CHECK(res.converged);
        CHECK(is_rotation(res.rotation, 1e-13));
        CHECK(err <= 10 * tols[i]);
        worst_ratio[s][i] = std::max(worst_ratio[s][i], err / tols[i]);
        evals[s][i] += res.evaluations;
      }
  }
  std::printf("\nTransport inside one cell, %d random cases (mean transport angle %.2f rad)\n", cases, mean_angle);
  std::printf("%-10s %-10s %-18s %-16s\n", "scheme", "tol", "worst error/tol", "mean evaluations");
  for (int s = 0; s < 2; ++s)
    for (int i = 0; i < 3; ++i)
      std::printf("%-10s %-10.0e %-18.3f %-16.1f\n", s == 0 ? "trapezoid" : "magnus", tols[i], worst_ratio[s][i],
                  double(evals[s][i]) / cases);
  // The target: Magnus reaches 1e-8 with at most a tenth of the trapezoid's evaluations.
  CHECK(10 * evals[1][1] <= evals[0][1]);
}

TEST_CASE("a constant metric gives W == 0 and T == I exactly", "[transport]") {
  Random r(14);
  const M3 A = CGAL_ext::sqrt_spd(r.spd(0.1, 10));
  const M3 zero = M3::Zero();
  CHECK(CGAL_ext::connection_one_form(A, zero) == zero);
  for (Transport_scheme s : {Transport_scheme::trapezoid, Transport_scheme::magnus}) {
    Transport_options opt;
    opt.scheme = s;
    const CGAL_ext::Transport_result res = CGAL_ext::cell_transport(A, A, zero, V3(0.3, -2, 1), opt);
    CHECK(res.rotation == M3::Identity());
    CHECK(res.error_estimate == 0);
  }
}

TEST_CASE("reversal, composition and scale invariance", "[transport]") {
  Random r(15);
  for (int k = 0; k < 6; ++k) {
    const Tet_case t = random_tet(r, 0.2, 5);
    const V3 a = t.random_point(r), c = t.random_point(r);
    const V3 b = a + 0.37 * (c - a);
    const M3 Aa = t.A_at(a), Ab = t.A_at(b), Ac = t.A_at(c);
    for (Transport_scheme s : {Transport_scheme::trapezoid, Transport_scheme::magnus}) {
      for (double tol : {1e-6, 1e-9}) {
        Transport_options opt;
        opt.scheme = s;
        opt.tolerance = tol;
        const M3 Tac = CGAL_ext::cell_transport(Aa, Ac, t.curl, c - a, opt).rotation;
        const M3 Tca = CGAL_ext::cell_transport(Ac, Aa, t.curl, a - c, opt).rotation;
        const M3 Tab = CGAL_ext::cell_transport(Aa, Ab, t.curl, b - a, opt).rotation;
        const M3 Tbc = CGAL_ext::cell_transport(Ab, Ac, t.curl, c - b, opt).rotation;
        INFO("case " << k << " scheme " << int(s) << " tol " << tol);
        CHECK(distance(Tca, Tac.transpose()) <= 10 * tol);
        CHECK(distance(Tac, Tbc * Tab) <= 10 * tol);
        // The transport must be a real rotation for the checks to mean anything.
        CHECK(CGAL_ext::rotation_angle(Tac) > 1e3 * tol);

        // Scale the geometry by 1000 and the metric by 1/1000^2: same
        // lengths, hence the same transport and the same work.
        const double L = 1000;
        const CGAL_ext::Transport_result small = CGAL_ext::cell_transport(Aa, Ac, t.curl, c - a, opt);
        const CGAL_ext::Transport_result big =
            CGAL_ext::cell_transport(Aa / L, Ac / L, t.curl / (L * L), L * (c - a), opt);
        CHECK(distance(small.rotation, big.rotation) <= 1e-12);
        CHECK(std::abs(double(big.evaluations) - double(small.evaluations)) <= 0.1 * double(small.evaluations));
      }
    }
  }
}

namespace {

// doc/math.md section 6 (test_support.h).
using CGAL_ext::testing::flat_metric::jacobian;
using CGAL_ext::testing::flat_metric::polar_rotation;
M3 smooth_A(const V3& x) { return CGAL_ext::testing::flat_metric::sqrt_metric(x); }
M3 smooth_curl(const V3& x) { return CGAL_ext::testing::flat_metric::curl(x); }

} // namespace

TEST_CASE("analytic check of doc/math.md section 6: T(a->b) = Q(b)^T Q(a)", "[transport]") {
  const V3 a(0.1, 0.2, -0.3), b(0.9, -0.4, 0.5);
  for (int i = 0; i <= 20; ++i) REQUIRE(jacobian(a + (i / 20.0) * (b - a)).determinant() > 0);
  auto u = [&](double t) -> V3 {
    const V3 x = a + t * (b - a);
    return CGAL_ext::connection_one_form(smooth_A(x), smooth_curl(x)).transpose() * (b - a);
  };
  const M3 Qa = polar_rotation(a), Qb = polar_rotation(b);
  REQUIRE(is_rotation(Qa, 1e-13));
  const M3 exact = Qb.transpose() * Qa;
  for (Transport_scheme s : {Transport_scheme::trapezoid, Transport_scheme::magnus}) {
    Transport_options opt;
    opt.scheme = s;
    opt.tolerance = 1e-9;
    const CGAL_ext::Transport_result res = CGAL_ext::integrate_transport(u, opt);
    const double err = distance(exact, res.rotation);
    std::printf("analytic check, %s: |T - Q(b)^T Q(a)| = %.2e rad (angle of T %.3f), %zu evaluations\n",
                s == Transport_scheme::trapezoid ? "trapezoid" : "magnus", err, CGAL_ext::rotation_angle(exact),
                res.evaluations);
    CHECK(err <= 1e-8);
    // The other orderings are far off: the check does tell them apart.
    CHECK(distance(Qb * Qa.transpose(), res.rotation) > 0.1);
    CHECK(distance(exact.transpose(), res.rotation) > 0.1);
  }
}

TEST_CASE("integrate_transport rejects a bad tolerance", "[transport]") {
  Transport_options opt;
  opt.tolerance = 0;
  auto u = [](double) { return V3(1, 0, 0); };
  CHECK_THROWS_AS(CGAL_ext::integrate_transport(u, opt), std::invalid_argument);
  opt.tolerance = std::nan("");
  CHECK_THROWS_AS(CGAL_ext::integrate_transport(u, opt), std::invalid_argument);
}

TEST_CASE("a constant generator is integrated exactly by both schemes", "[transport]") {
  // u constant: T = exp([u]_x); every piece and step is exact.
  const V3 w(0.4, -1.1, 0.7);
  auto u = [&](double) { return w; };
  for (Transport_scheme s : {Transport_scheme::trapezoid, Transport_scheme::magnus}) {
    Transport_options opt;
    opt.scheme = s;
    const CGAL_ext::Transport_result res = CGAL_ext::integrate_transport(u, opt);
    CHECK(distance(res.rotation, Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix()) <= 1e-14);
    CHECK(res.evaluations <= 6);
  }
}

TEST_CASE("the depth cap is reported", "[transport]") {
  // A fast-spinning generator that cannot meet 1e-12 within depth 3.
  auto u = [](double t) { return V3(10 * std::cos(7 * t), 10 * std::sin(7 * t), 3 * t); };
  Transport_options opt;
  opt.scheme = Transport_scheme::trapezoid;
  opt.tolerance = 1e-12;
  opt.max_depth = 3;
  const CGAL_ext::Transport_result res = CGAL_ext::integrate_transport(u, opt);
  CHECK_FALSE(res.converged);
  CHECK(res.pieces == 16);
  CHECK(res.evaluations == 17);
  opt.scheme = Transport_scheme::magnus;
  opt.min_step = 1.0 / 8;
  CHECK_FALSE(CGAL_ext::integrate_transport(u, opt).converged);
}

TEST_CASE("a generator that is not finite is an error, not an endless loop", "[transport]") {
  // A NaN error estimate used to make the step NaN, and no step was ever accepted.
  for (Transport_scheme s : {Transport_scheme::trapezoid, Transport_scheme::magnus}) {
    Transport_options opt;
    opt.scheme = s;
    auto nan_after_half = [](double t) { return t > 0.5 ? V3(std::nan(""), 0, 0) : V3(1, 2, 3); };
    CHECK_THROWS_AS(CGAL_ext::integrate_transport(nan_after_half, opt), std::domain_error);
    auto infinite = [](double) { return V3(0, HUGE_VAL, 0); };
    CHECK_THROWS_AS(CGAL_ext::integrate_transport(infinite, opt), std::domain_error);
  }
}

TEST_CASE("a tolerance below what double resolves costs a few steps, at the accuracy of double", "[transport]") {
  auto u = [](double t) { return V3(std::cos(3 * t), std::sin(2 * t), 0.5 + t * t); };
  Transport_options fine, absurd;
  fine.tolerance = 1e-12;
  absurd.tolerance = 1e-20;
  const CGAL_ext::Transport_result reference = CGAL_ext::integrate_transport(u, fine);
  const CGAL_ext::Transport_result r = CGAL_ext::integrate_transport(u, absurd);
  INFO(r.evaluations << " evaluations at 1e-20, " << reference.evaluations << " at 1e-12");
  CHECK(r.evaluations < 20 * reference.evaluations); // not 2^22 smallest steps
  CHECK(distance(r.rotation, reference.rotation) <= 1e-12);
  CHECK(r.error_estimate <= 1e-13);
}

TEST_CASE("the number of Magnus steps is bounded, and reaching the bound is reported", "[transport]") {
  // A generator spinning 1e5 times over the segment cannot meet 1e-10 in 100 steps.
  auto u = [](double t) { return V3(1e6 * std::cos(1e6 * t), 1e6 * std::sin(1e6 * t), 1); };
  Transport_options opt;
  opt.tolerance = 1e-10;
  opt.max_steps = 100;
  const CGAL_ext::Transport_result r = CGAL_ext::integrate_transport(u, opt);
  CHECK_FALSE(r.converged);
  CHECK(r.evaluations <= 6 * opt.max_steps);
  CHECK(r.rotation.allFinite());
  CHECK((r.rotation.transpose() * r.rotation - M3::Identity()).norm() < 1e-12);
}
