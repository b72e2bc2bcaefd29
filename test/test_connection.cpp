// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
// The connection one-form (doc/math.md section 3): the closed form against the
// 9x9 system, the system matrix against its definition, det M = -2 det(A)^3.
#include <CGAL_ext/Connection_3.h>
#include <CGAL_ext/Metric_tensor.h>

#include <catch2/catch.hpp>

#include "test_support.h"

#include <Eigen/Geometry>

#include <cmath>
#include <random>

namespace {

using CGAL_ext::testing::Random;

using M3 = Eigen::Matrix3d;
using V3 = Eigen::Vector3d;


} // namespace

TEST_CASE("cross_product_matrix is the cross product", "[connection]") {
  Random r(1);
  for (int k = 0; k < 20; ++k) {
    const V3 u = r.matrix(2).col(0), v = r.matrix(2).col(1);
    CHECK((CGAL_ext::cross_product_matrix(u) * v - u.cross(v)).norm() <= 1e-15 * (1 + u.norm() * v.norm()));
  }
}

TEST_CASE("connection_system_matrix follows the block definition of doc/math.md", "[connection]") {
  // Block row i of M vec(W) must be A^j x W_k - A^k x W_j for (i, j, k) cyclic,
  // i.e. -[A^3]_x W_2 + [A^2]_x W_3 for the first block row.
  Random r(2);
  for (int k = 0; k < 20; ++k) {
    const M3 A = CGAL_ext::sqrt_spd(r.spd(0.1, 10));
    const M3 W = r.matrix(3);
    Eigen::Matrix<double, 9, 1> w = Eigen::Map<const Eigen::Matrix<double, 9, 1>>(W.data());
    const Eigen::Matrix<double, 9, 1> mw = CGAL_ext::connection_system_matrix(A) * w;
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3, l = (i + 2) % 3;
      const V3 expected = A.col(j).cross(W.col(l)) - A.col(l).cross(W.col(j));
      CHECK((mw.segment<3>(3 * i) - expected).norm() <= 1e-13 * (1 + expected.norm()));
    }
  }
}

TEST_CASE("det M(A) = -2 det(A)^3", "[connection]") {
  Random r(3);
  for (int k = 0; k < 100; ++k) {
    const M3 A = CGAL_ext::sqrt_spd(r.spd(0.01, 100));
    const double detM = CGAL_ext::connection_system_matrix(A).determinant();
    const double expected = -2 * std::pow(A.determinant(), 3);
    CHECK(std::abs(detM - expected) <= 1e-9 * std::abs(expected));
  }
}

TEST_CASE("closed-form connection solves the 9x9 system", "[connection]") {
  Random r(4);
  double worst = 0, worst_residual = 0;
  for (int k = 0; k < 500; ++k) {
    // Up to 1e4 in eigenvalues (1e2 in A) and curls of any size.
    const M3 A = CGAL_ext::sqrt_spd(r.spd(1e-2, 1e2));
    const M3 curl = r.matrix(std::pow(10.0, r.uniform(-3, 3)));
    const M3 W = CGAL_ext::connection_one_form(A, curl);
    const M3 Ws = CGAL_ext::connection_one_form_by_solve(A, curl);
    // Relative to the natural scale |A^{-1}| |curl| of the solution.
    const double scale = A.inverse().norm() * curl.norm();
    worst = std::max(worst, (W - Ws).norm() / scale);
    Eigen::Matrix<double, 9, 1> w = Eigen::Map<const Eigen::Matrix<double, 9, 1>>(W.data());
    Eigen::Matrix<double, 9, 1> c = Eigen::Map<const Eigen::Matrix<double, 9, 1>>(curl.data());
    const double residual = (CGAL_ext::connection_system_matrix(A) * w - c).norm() / (A.norm() * W.norm() + c.norm());
    worst_residual = std::max(worst_residual, residual);
  }
  INFO("worst relative difference to the 9x9 solve " << worst << ", worst residual " << worst_residual);
  CHECK(worst <= 1e-11);
  CHECK(worst_residual <= 1e-14);
}

TEST_CASE("closed-form connection is linear in the curl and zero for zero curl", "[connection]") {
  Random r(5);
  const M3 A = CGAL_ext::sqrt_spd(r.spd(0.3, 3));
  CHECK(CGAL_ext::connection_one_form(A, M3::Zero()) == M3::Zero()); // exactly
  const M3 c1 = r.matrix(1), c2 = r.matrix(1);
  const M3 lhs = CGAL_ext::connection_one_form(A, 2 * c1 - 3 * c2);
  const M3 rhs = 2 * CGAL_ext::connection_one_form(A, c1) - 3 * CGAL_ext::connection_one_form(A, c2);
  CHECK((lhs - rhs).norm() <= 1e-13 * rhs.norm());
}

TEST_CASE("connection of the identity metric", "[connection]") {
  // A = I: M vec(W) = vec(curl) reads W_3 - ... ; the closed form gives
  // W = tr(C)/2 I - C^T, which must satisfy the cyclic equations exactly.
  Random r(6);
  const M3 C = r.matrix(1);
  const M3 W = CGAL_ext::connection_one_form(M3::Identity(), C);
  CHECK((W - (0.5 * C.trace() * M3::Identity() - C.transpose())).norm() <= 1e-15);
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3, l = (i + 2) % 3;
    const V3 lhs = M3::Identity().col(j).cross(W.col(l)) - M3::Identity().col(l).cross(W.col(j));
    CHECK((lhs - C.col(i)).norm() <= 1e-14);
  }
}

TEST_CASE("the connection does not depend on the scale of A, down to 1e-150 I and up to 1e150 I", "[connection]") {
  // W(s A, s curl) = W(A, curl). By a power of two it is the same bits; at
  // scales where det(A) alone would underflow or overflow it stays finite.
  Random r(7);
  for (int k = 0; k < 50; ++k) {
    const M3 A = CGAL_ext::sqrt_spd(r.spd(1e-2, 1e2));
    const M3 curl = r.matrix(1);
    const M3 W = CGAL_ext::connection_one_form(A, curl);
    for (int e : {-500, -60, 3, 60, 500}) {
      const double s = std::ldexp(1.0, e);
      CHECK(CGAL_ext::connection_one_form(s * A, s * curl) == W);
    }
    for (double s : {1e-150, 1e-100, 1e100, 1e150}) {
      const M3 Ws = CGAL_ext::connection_one_form(s * A, s * curl);
      INFO("scale " << s);
      REQUIRE(Ws.allFinite());
      CHECK((Ws - W).norm() <= 1e-13 * W.norm());
    }
  }
}
