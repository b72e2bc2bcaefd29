// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_INTERNAL_LBFGS_ON_ROTATIONS_H
#define CGAL_EXT_INTERNAL_LBFGS_ON_ROTATIONS_H

/// \file
/// L-BFGS on a product of rotation groups: one rotation per element, moved
/// by left-trivialised increments `R_i <- exp([step p_i]_x) R_i`, so that
/// the search directions and gradients are one 3-vector per element. The
/// caller owns the rotations and the energy; this is the two-loop
/// recursion, the Armijo backtracking and the stopping rule, with every
/// reduction deterministic.

#include <CGAL_ext/internal/deterministic_parallel.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

namespace CGAL_ext {
namespace internal {

/// Stopping rule and memory of `lbfgs_on_rotations()`.
struct Lbfgs_settings {
  /// The largest number of iterations (0: none).
  int max_iterations = 1000;
  /// The number of (step, gradient change) pairs kept.
  int memory = 8;
  /// Stop when an iteration lowers the energy by less than this times the
  /// energy, three times in a row.
  double energy_tolerance = 1e-5;
  /// Stop when the energy is at or below this.
  double floor_energy = 0;
};

/// What `lbfgs_on_rotations()` did.
struct Lbfgs_outcome {
  int iterations = 0;  ///< accepted steps
  int evaluations = 0; ///< energy and gradient evaluations
  bool limit = false;  ///< whether `max_iterations` stopped it while it still made progress
};

// One pass over n elements: update(k), then the sum of value(k) on the
// updated data (fixed blocks: deterministic).
template <class Update, class Value>
double fused_pass(std::size_t n, Update&& update, Value&& value) {
  return deterministic_sum(n, [&](std::size_t first, std::size_t last) {
    double sum = 0;
    for (std::size_t k = first; k < last; ++k) {
      update(k);
      sum += value(k);
    }
    return sum;
  });
}

// The (step, gradient change) pairs of L-BFGS in a ring of `memory`
// preallocated slots, oldest first in `order`; per pair rho = 1 / (s.y) and
// gamma = (s.y) / (y.Dinv.y).
class Lbfgs_history {
public:
  Lbfgs_history(const std::vector<double>& inverse_diagonal, int memory)
      : inverse_diagonal_(inverse_diagonal), n_(inverse_diagonal.size()), m_(std::max(1, memory)), rho_(m_),
        gamma_of_(m_) {}

  bool empty() const { return order_.empty(); }
  void clear() { order_.clear(); }

  // p = -H g by the two-loop recursion, each axpy fused with the next dot
  // product; the initial inverse Hessian is gamma diag(inverse_diagonal),
  // gamma from the newest pair. Returns the slope g.p.
  double direction(const std::vector<Eigen::Vector3d>& g, std::vector<Eigen::Vector3d>& p) const {
    const auto& S = S_;
    const auto& Y = Y_;
    const auto& order = order_;
    const int h = int(order.size());
    std::vector<double> alpha(h);
    double d = fused_pass(n_, [&](std::size_t i) { p[i] = -g[i]; },
                          [&](std::size_t i) { return h > 0 ? S[order[h - 1]][i].dot(p[i]) : 0.0; });
    for (int k = h - 1; k >= 0; --k) {
      const int o = order[k];
      alpha[k] = rho_[o] * d;
      const double a = alpha[k];
      d = fused_pass(n_, [&](std::size_t i) { p[i] -= a * Y[o][i]; },
                     [&](std::size_t i) { return k > 0 ? S[order[k - 1]][i].dot(p[i]) : 0.0; });
    }
    const double gamma = h > 0 ? gamma_of_[order[h - 1]] : 1.0;
    double slope = 0;
    d = fused_pass(n_, [&](std::size_t i) { p[i] *= gamma * inverse_diagonal_[i]; },
                   [&](std::size_t i) { return h > 0 ? Y[order[0]][i].dot(p[i]) : g[i].dot(p[i]); });
    if (h == 0) slope = d;
    for (int k = 0; k < h; ++k) {
      const int o = order[k];
      const double a = alpha[k] - rho_[o] * d;
      d = fused_pass(n_, [&](std::size_t i) { p[i] += a * S[o][i]; },
                     [&](std::size_t i) { return k + 1 < h ? Y[order[k + 1]][i].dot(p[i]) : g[i].dot(p[i]); });
      if (k + 1 == h) slope = d;
    }
    return slope;
  }

  // The pair of an accepted step (step p, from gradient g to g_new) goes
  // into a free slot (or the oldest one's), kept only if the curvature s.y
  // is positive.
  void add(double step, const std::vector<Eigen::Vector3d>& p, const std::vector<Eigen::Vector3d>& g,
           const std::vector<Eigen::Vector3d>& g_new) {
    int slot;
    if (int(S_.size()) < m_) {
      slot = int(S_.size());
      S_.emplace_back(n_), Y_.emplace_back(n_);
    } else if (int(order_.size()) < m_) {
      slot = 0;
      while (std::find(order_.begin(), order_.end(), slot) != order_.end()) ++slot;
    } else {
      slot = order_.front();
    }
    std::vector<Eigen::Vector3d>& sk = S_[slot];
    std::vector<Eigen::Vector3d>& yk = Y_[slot];
    const std::array<double, 4> sums = // s.y, s.s, y.y, y.Dinv.y
        deterministic_sums<4>(n_, [&](std::size_t first, std::size_t last) {
          std::array<double, 4> acc{0, 0, 0, 0};
          for (std::size_t i = first; i < last; ++i) {
            sk[i] = step * p[i];
            yk[i] = g_new[i] - g[i];
            acc[0] += sk[i].dot(yk[i]), acc[1] += sk[i].squaredNorm(), acc[2] += yk[i].squaredNorm();
            acc[3] += inverse_diagonal_[i] * yk[i].squaredNorm();
          }
          return acc;
        });
    if (int(order_.size()) == m_ && order_.front() == slot) order_.erase(order_.begin());
    if (sums[0] > 1e-12 * std::sqrt(sums[1] * sums[2])) {
      rho_[slot] = 1 / sums[0];
      gamma_of_[slot] = sums[0] / sums[3];
      order_.push_back(slot);
    }
  }

private:
  const std::vector<double>& inverse_diagonal_;
  std::size_t n_;
  int m_;
  std::vector<std::vector<Eigen::Vector3d>> S_, Y_;
  std::vector<int> order_;
  std::vector<double> rho_, gamma_of_;
};

/// Minimises an energy of per-element rotations by L-BFGS with Armijo
/// backtracking. The initial inverse Hessian is `gamma diag(inverse_diagonal)`
/// (per-element scales, as the weights vary by orders of magnitude), `gamma`
/// from the newest pair. The first step (no curvature information) turns no
/// element by more than 0.1 rad. A direction that is not a descent restarts
/// from the scaled gradient.
/// \tparam Energy_and_gradient a callable `double(std::vector<Eigen::Vector3d>& g)`:
///         the energy at the current rotations, and its gradient in the increments
/// \tparam Move a callable `void(const std::vector<Eigen::Vector3d>& p, double step)`:
///         sets the current rotations to the accepted ones turned by `step p`
///         (`step == 0`: the accepted ones)
/// \tparam Accept a callable `void()`: the current rotations become the accepted ones
/// \tparam On_iteration a callable `void(int iteration, double energy)`
/// \param inverse_diagonal per element, the scale of the initial inverse Hessian
/// \param energy_and_gradient the energy
/// \param move the trial step
/// \param accept the acceptance of a step
/// \param on_iteration called after each iteration
/// \param settings the stopping rule and memory
/// \returns the iterations, evaluations and whether the bound stopped it
template <class Energy_and_gradient, class Move, class Accept, class On_iteration>
Lbfgs_outcome lbfgs_on_rotations(const std::vector<double>& inverse_diagonal, Energy_and_gradient&& energy_and_gradient,
                                 Move&& move, Accept&& accept, On_iteration&& on_iteration,
                                 const Lbfgs_settings& settings) {
  Lbfgs_outcome out;
  const std::size_t n = inverse_diagonal.size();
  if (settings.max_iterations <= 0 || n == 0) return out;
  std::vector<Eigen::Vector3d> g(n), g_new(n), p(n);
  double E = energy_and_gradient(g);
  ++out.evaluations;
  Lbfgs_history history(inverse_diagonal, settings.memory);
  int small_steps = 0;
  for (int it = 0; it < settings.max_iterations; ++it) {
    if (E <= settings.floor_energy) break;
    double slope = history.direction(g, p);
    if (!(slope < 0)) { // not a descent direction: restart from the gradient
      history.clear();
      slope = fused_pass(n, [&](std::size_t i) { p[i] = -inverse_diagonal[i] * g[i]; },
                         [&](std::size_t i) { return g[i].dot(p[i]); });
      if (!(slope < 0)) break; // zero gradient
    }
    double step = 1;
    if (history.empty()) {
      double pmax = 0;
      for (std::size_t i = 0; i < n; ++i) pmax = std::max(pmax, p[i].norm());
      step = std::min(1.0, 0.1 / pmax);
    }
    double E_new = E;
    bool accepted = false;
    for (int ls = 0; ls < 40 && !accepted; ++ls) {
      if (ls > 0) step *= 0.5;
      move(p, step);
      E_new = energy_and_gradient(g_new);
      ++out.evaluations;
      accepted = E_new <= E + 1e-4 * step * slope;
    }
    if (!accepted) {
      move(p, 0);
      break;
    }
    ++out.iterations;
    history.add(step, p, g, g_new);
    accept();
    std::swap(g, g_new);
    const double decrease = E - E_new;
    E = E_new;
    on_iteration(it + 1, E);
    small_steps = decrease <= settings.energy_tolerance * E ? small_steps + 1 : 0;
    if (small_steps >= 3) break;
    if (it + 1 == settings.max_iterations) out.limit = true;
  }
  return out;
}

} // namespace internal
} // namespace CGAL_ext

#endif // CGAL_EXT_INTERNAL_LBFGS_ON_ROTATIONS_H
