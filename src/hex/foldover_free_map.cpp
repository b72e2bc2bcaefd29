// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#include "foldover_free_map.h"

#include <CGAL_ext/internal/deterministic_parallel.h>

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>

namespace CGAL_ext::internal {
namespace {

// chi(D, eps) = (D + sqrt(eps^2 + D^2)) / 2 > 0, and its derivative in D.
double chi(double D, double eps) { return 0.5 * (D + std::sqrt(eps * eps + D * D)); }
double chi_derivative(double D, double eps) { return 0.5 * (1 + D / std::sqrt(eps * eps + D * D)); }

Eigen::Matrix3d cofactor(const Eigen::Matrix3d& K) { // d det(K) / dK
  Eigen::Matrix3d C;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      const int r1 = (r + 1) % 3, r2 = (r + 2) % 3, c1 = (c + 1) % 3, c2 = (c + 2) % 3;
      C(r, c) = K(r1, c1) * K(r2, c2) - K(r1, c2) * K(r2, c1);
    }
  return C;
}

Eigen::Matrix<double, 3, 4> corners(const Foldover_free_problem& pb, const Eigen::VectorXd& x, std::size_t t) {
  Eigen::Matrix<double, 3, 4> U;
  for (int c = 0; c < 4; ++c) U.col(c) = x.segment<3>(Eigen::Index(pb.corner[t][std::size_t(c)]));
  return U;
}

// The energy sum_t vol_t ((1 - theta) tr(K^T K) / chi^(2/3) + theta (det^2 + 1) / chi), and its gradient in y.
// The tetrahedra's terms are computed in parallel and added in their order:
// the same bits whatever the number of threads.
double energy(const Foldover_free_problem& pb, const Eigen::VectorXd& y, double eps, double theta,
              Eigen::VectorXd* gradient) {
  const Eigen::VectorXd x = *pb.E * y + *pb.c;
  const std::size_t n = pb.corner.size();
  std::vector<double> e(n);
  std::vector<Eigen::Matrix<double, 3, 4>> dU(gradient ? n : 0);
  parallel_for_each_index(n, [&](std::size_t t) {
    const Eigen::Matrix<double, 3, 4> U = corners(pb, x, t);
    const Eigen::Matrix3d K = U * pb.B[t].transpose() * pb.M[t];
    const double D = K.determinant(), X = chi(D, eps), trace = K.squaredNorm();
    const double X23 = std::cbrt(X * X);
    e[t] = pb.volume[t] * ((1 - theta) * trace / X23 + theta * (D * D + 1) / X);
    if (!gradient) return;
    const double dX = chi_derivative(D, eps);
    const double df_dD = -2.0 / 3.0 * trace / (X23 * X) * dX, dg_dD = 2 * D / X - (D * D + 1) / (X * X) * dX;
    const Eigen::Matrix3d dK = (1 - theta) * (2 * K / X23) + ((1 - theta) * df_dD + theta * dg_dD) * cofactor(K);
    dU[t] = pb.volume[t] * dK * pb.M[t].transpose() * pb.B[t];
  });
  double sum = 0;
  for (double v : e) sum += v;
  if (gradient) {
    Eigen::VectorXd gx = Eigen::VectorXd::Zero(x.size());
    for (std::size_t t = 0; t < n; ++t)
      for (int c = 0; c < 4; ++c) gx.segment<3>(Eigen::Index(pb.corner[t][std::size_t(c)])) += dU[t].col(c);
    *gradient = pb.E->transpose() * gx;
    for (Eigen::Index k = 0; k < gradient->size(); ++k)
      if (pb.fixed[std::size_t(k)]) (*gradient)[k] = 0;
  }
  return sum;
}

// L-BFGS with Armijo backtracking on the energy at eps; returns the iterations.
int minimise(const Foldover_free_problem& pb, Eigen::VectorXd& y, double eps, const Foldover_free_settings& s) {
  std::deque<std::pair<Eigen::VectorXd, Eigen::VectorXd>> pairs; // (step, gradient change)
  Eigen::VectorXd g, g_new;
  double e = energy(pb, y, eps, s.volume_weight, &g);
  int quiet = 0, it = 0;
  for (; it < s.max_iterations; ++it) {
    Eigen::VectorXd q = g;
    std::vector<double> alpha(pairs.size());
    for (std::size_t k = pairs.size(); k-- > 0;) {
      alpha[k] = pairs[k].first.dot(q) / pairs[k].second.dot(pairs[k].first);
      q -= alpha[k] * pairs[k].second;
    }
    if (!pairs.empty()) q *= pairs.back().first.dot(pairs.back().second) / pairs.back().second.squaredNorm();
    for (std::size_t k = 0; k < pairs.size(); ++k)
      q += pairs[k].first * (alpha[k] - pairs[k].second.dot(q) / pairs[k].second.dot(pairs[k].first));
    Eigen::VectorXd d = -q;
    double slope = g.dot(d);
    if (!(slope < 0)) {
      pairs.clear();
      d = -g;
      slope = -g.squaredNorm();
    }
    if (slope == 0) break;
    double step = 1, e_new = 0;
    Eigen::VectorXd y_new;
    for (int b = 0; b < 40; ++b, step *= 0.5) {
      y_new = y + step * d;
      e_new = energy(pb, y_new, eps, s.volume_weight, nullptr);
      if (e_new <= e + 1e-4 * step * slope) break;
    }
    if (!(e_new <= e)) break;
    energy(pb, y_new, eps, s.volume_weight, &g_new);
    pairs.emplace_back(y_new - y, g_new - g);
    if (pairs.back().second.dot(pairs.back().first) <= 1e-300) pairs.pop_back();
    if (int(pairs.size()) > s.memory) pairs.pop_front();
    quiet = (e - e_new) < s.energy_tolerance * 1e-2 * std::abs(e) ? quiet + 1 : 0;
    y.swap(y_new);
    g.swap(g_new);
    e = e_new;
    if (quiet >= 3) break;
  }
  return it;
}

} // namespace

double min_relative_det(const Foldover_free_problem& pb, const Eigen::VectorXd& y) {
  const Eigen::VectorXd x = *pb.E * y + *pb.c;
  double m = std::numeric_limits<double>::infinity();
  for (std::size_t t = 0; t < pb.corner.size(); ++t)
    m = std::min(m, (corners(pb, x, t) * pb.B[t].transpose() * pb.M[t]).determinant());
  return m;
}

Foldover_free_outcome untangle(const Foldover_free_problem& pb, Eigen::VectorXd& y, const Foldover_free_settings& s) {
  Foldover_free_outcome out;
  double D = out.min_det_before = min_relative_det(pb, y);
  double eps = D > 0 ? 1e-10 : std::sqrt(1e-10 + 0.04 * D * D); // the paper's start
  double e_prev = energy(pb, y, eps, s.volume_weight, nullptr), best = D;
  int stalled = 0;
  for (; out.rounds < s.max_rounds; ++out.rounds) {
    out.iterations += minimise(pb, y, eps, s);
    const double e = energy(pb, y, eps, s.volume_weight, nullptr);
    D = min_relative_det(pb, y);
    // Rounds that leave a negative least determinant no higher stop after a few.
    stalled = D > best ? 0 : stalled + 1;
    best = std::max(best, D);
    if (D <= 0 && stalled >= s.stall_rounds) {
      ++out.rounds;
      break;
    }
    const double sigma = std::max(1 - e / e_prev, 0.1);
    const double mu = (1 - sigma) * chi(D, eps);
    eps = D < mu ? 2 * std::sqrt(mu * (mu - D)) : 1e-10;
    const bool settled = std::abs(e_prev - e) <= s.energy_tolerance * std::abs(e);
    e_prev = e;
    if (D > 0 && settled) {
      ++out.rounds;
      break;
    }
  }
  out.min_det_after = min_relative_det(pb, y);
  return out;
}

} // namespace CGAL_ext::internal
