// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_INTERNAL_PRECONDITIONED_CONJUGATE_GRADIENT_H
#define CGAL_EXT_INTERNAL_PRECONDITIONED_CONJUGATE_GRADIENT_H

/// \file
/// Matrix-free preconditioned conjugate gradients on block vectors (one
/// small fixed-size Eigen vector per unknown), with deterministic parallel
/// dot products: the frame field's linear initialisation, its coarse level
/// and the local re-optimisation use it.

#include <CGAL_ext/internal/deterministic_parallel.h>

#include <cmath>
#include <cstddef>
#include <vector>

namespace CGAL_ext {
namespace internal {

/// `sum_i a_i . b_i`, deterministic (`deterministic_sum()`).
/// \tparam Block a fixed-size Eigen vector type
/// \param a the first block vector
/// \param b the second block vector, of the same size
template <class Block>
double block_dot(const std::vector<Block>& a, const std::vector<Block>& b) {
  return deterministic_sum(a.size(), [&](std::size_t first, std::size_t last) {
    double s = 0;
    for (std::size_t i = first; i < last; ++i) s += a[i].dot(b[i]);
    return s;
  });
}

/// Preconditioned conjugate gradients on `H x = b` (`H` symmetric positive
/// definite, given by its product) from the given `x`, until
/// `|r| <= tolerance |b|` or `max_iterations`.
/// \tparam Block a fixed-size Eigen vector type
/// \tparam Apply a callable `void(const std::vector<Block>& v, std::vector<Block>& y)`, `y = H v`
/// \tparam Precondition a callable `Block(std::size_t i, const Block& r)`, block `i` of `M^{-1} r`
/// \tparam On_iteration a callable `void(int iteration, double relative_residual)`
/// \param x the start, then the solution
/// \param b the right-hand side
/// \param apply the product with `H`
/// \param precondition the block preconditioner
/// \param tolerance the relative residual at which to stop
/// \param max_iterations the largest number of iterations
/// \param on_iteration called after each iteration
/// \param relative_residual gets `|r| / |b|` (0 if `b = 0`)
/// \returns the iterations
template <class Block, class Apply, class Precondition, class On_iteration>
int preconditioned_conjugate_gradient(std::vector<Block>& x, const std::vector<Block>& b, Apply&& apply,
                                      Precondition&& precondition, double tolerance, int max_iterations,
                                      On_iteration&& on_iteration, double& relative_residual) {
  const std::size_t n = x.size();
  std::vector<Block> r(n), z(n), p(n), Ap(n);
  apply(x, Ap);
  parallel_for_each_index(n, [&](std::size_t i) {
    r[i] = b[i] - Ap[i];
    z[i] = precondition(i, r[i]);
    p[i] = z[i];
  });
  const double bnorm = std::sqrt(block_dot(b, b));
  double rnorm = std::sqrt(block_dot(r, r)), rz = block_dot(r, z);
  int it = 0;
  for (; it < max_iterations && rnorm > tolerance * bnorm; ++it) {
    apply(p, Ap);
    const double alpha = rz / block_dot(p, Ap);
    parallel_for_each_index(n, [&](std::size_t i) {
      x[i] += alpha * p[i];
      r[i] -= alpha * Ap[i];
      z[i] = precondition(i, r[i]);
    });
    const double rz_new = block_dot(r, z);
    const double beta = rz_new / rz;
    rz = rz_new;
    parallel_for_each_index(n, [&](std::size_t i) { p[i] = z[i] + beta * p[i]; });
    rnorm = std::sqrt(block_dot(r, r));
    on_iteration(it + 1, rnorm / bnorm);
  }
  relative_residual = bnorm > 0 ? rnorm / bnorm : 0;
  return it;
}

} // namespace internal
} // namespace CGAL_ext

#endif // CGAL_EXT_INTERNAL_PRECONDITIONED_CONJUGATE_GRADIENT_H
