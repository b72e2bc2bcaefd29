// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_INTERNAL_FRAME_FIELD_DIFFUSION_3_H
#define CGAL_EXT_INTERNAL_FRAME_FIELD_DIFFUSION_3_H

/// \file
/// One implicit heat step of the frame field's SH vectors: the diffusion of
/// the diffusion-projection (MBO) stage between the projection and the
/// refinement.

#include <CGAL_ext/Octahedral_frame.h>
#include <CGAL_ext/internal/Frame_field_coarse_level_3.h>
#include <CGAL_ext/internal/deterministic_parallel.h>
#include <CGAL_ext/internal/preconditioned_conjugate_gradient.h>

#include <Eigen/Core>
#include <Eigen/LU>

#include <cmath>
#include <cstddef>
#include <vector>

namespace CGAL_ext {
namespace internal {

/// Replaces `s` by the solution `x` of `(M + tau H) x = M s + tau b`: one
/// implicit Euler step of time `tau` of the gradient flow of the relaxed
/// quadratic energy `x^T H x - 2 b.x` (the linear initialisation's, soft
/// boundary terms included) in the metric's L2 product (`M`: each
/// tetrahedron's volume in the metric, `sqrt(det g)` times its volume). So
/// `x` minimises `x^T H x - 2 b.x + |x - s|_M^2 / tau`: as `tau` goes to 0 it
/// is `s`, as `tau` grows it tends to the linear initialisation's solution,
/// and in between the field is smoothed over a length of about `sqrt(tau)`.
/// Solved by conjugate gradients from `s` (plus a coarse correction if
/// `coarse` is given) with the block-Jacobi preconditioner of `M + tau H`.
///
/// \tparam Energy a `Frame_field_energy_3`
/// \param e the energy (set up, with its transports)
/// \param s the SH vectors, replaced by the step's result
/// \param tau the time step, in squared units of the metric's length
/// \param tolerance the relative residual at which the iterations stop
/// \param max_iterations the largest number of iterations
/// \param relative_residual gets the final relative residual
/// \param coarse the coarse level of the linear initialisation, or null
/// \returns the fine conjugate-gradient iterations
template <class Energy>
int implicit_diffusion_step(const Energy& e, std::vector<Sh_vector>& s, double tau, double tolerance,
                            int max_iterations, double& relative_residual,
                            const Frame_field_coarse_level* coarse = nullptr) {
  const std::size_t n = e.size();
  // H and b are stored in units of 2^E (`weight_exponent`, degree 1 in A);
  // M is of degree 3 and tau of degree 2, so both are taken in those units
  // too (the system divided by 2^(3E)), and no metric scale overflows them.
  const double unit = std::ldexp(1.0, -e.weight_exponent);
  tau = std::ldexp(tau, -2 * e.weight_exponent);
  std::vector<double> mass(n);
  std::vector<Sh_vector> rhs(n);
  std::vector<Sh_matrix> constrained_block(e.constraints.size());
  parallel_for_each_index(n, [&](std::size_t i) {
    mass[i] = e.volume[i] * (unit * e.sqrt_metric[i]).determinant();
    rhs[i] = mass[i] * s[i];
    if (e.constraint_of[i] >= 0) {
      const auto& C = e.constraints[std::size_t(e.constraint_of[i])];
      rhs[i] += tau * C.b;
      constrained_block[std::size_t(e.constraint_of[i])] =
          ((mass[i] + tau * e.diagonal[i]) * Sh_matrix::Identity() + tau * C.B).inverse();
    }
  });
  auto apply = [&](const std::vector<Sh_vector>& v, std::vector<Sh_vector>& y) {
    e.apply_linear(v, y);
    parallel_for_each_index(n, [&](std::size_t i) { y[i] = mass[i] * v[i] + tau * y[i]; });
  };
  std::vector<Sh_vector> x = s;
  if (coarse) {
    // Two-level start: s plus the coarse correction P c, with
    // (P^T K P) c = P^T (rhs - K s) and K = M + tau H. A long step is smooth,
    // which the fine iterations alone reach slowly; the correction keeps s's
    // fine detail, which a short step hardly changes. P^T M P is diagonal
    // (each aggregate's mass: the D(U_t) are orthogonal).
    std::vector<Sh_vector> Ks(n);
    apply(s, Ks);
    const std::size_t na = coarse->rows.size();
    std::vector<double> coarse_mass(na, 0.0);
    std::vector<Sh_vector> rc(na, Sh_vector::Zero()), c(na, Sh_vector::Zero());
    std::vector<Sh_matrix> coarse_block(na);
    parallel_for_each_index(na, [&](std::size_t a) {
      for (std::size_t m = coarse->first[a]; m < coarse->first[a + 1]; ++m) {
        const std::size_t t = coarse->members[m];
        coarse_mass[a] += mass[t];
        rc[a] += rotate_sh(coarse->U[t].conjugate(), Sh_vector(rhs[t] - Ks[t]));
      }
      coarse_block[a] = (coarse_mass[a] * Sh_matrix::Identity() + tau * coarse->rows[a].front().second).inverse();
    });
    double coarse_residual = 0;
    preconditioned_conjugate_gradient(
        c, rc,
        [&](const std::vector<Sh_vector>& v, std::vector<Sh_vector>& y) {
          coarse->apply(v, y);
          parallel_for_each_index(na, [&](std::size_t a) { y[a] = coarse_mass[a] * v[a] + tau * y[a]; });
        },
        [&](std::size_t a, const Sh_vector& r) { return Sh_vector(coarse_block[a] * r); }, 0.01 * tolerance,
        max_iterations, [](int, double) {}, coarse_residual);
    parallel_for_each_index(n, [&](std::size_t t) { x[t] += rotate_sh(coarse->U[t], c[coarse->aggregate_of[t]]); });
  }
  const int iterations = preconditioned_conjugate_gradient(
      x, rhs, apply,
      [&](std::size_t i, const Sh_vector& r) {
        if (e.constraint_of[i] >= 0) return Sh_vector(constrained_block[std::size_t(e.constraint_of[i])] * r);
        const double d = mass[i] + tau * e.diagonal[i];
        return d > 0 ? Sh_vector(r / d) : r;
      },
      tolerance, max_iterations, [](int, double) {}, relative_residual);
  s = std::move(x);
  return iterations;
}

} // namespace internal
} // namespace CGAL_ext

#endif // CGAL_EXT_INTERNAL_FRAME_FIELD_DIFFUSION_3_H
