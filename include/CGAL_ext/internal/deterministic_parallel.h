// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_INTERNAL_DETERMINISTIC_PARALLEL_H
#define CGAL_EXT_INTERNAL_DETERMINISTIC_PARALLEL_H

/// \file
/// Parallel loops whose results do not depend on the number of threads:
/// loops that write per-index data only, and sums over fixed blocks added in
/// block order (floating-point addition is not associative, so a sum split
/// by the scheduler would change its last bits from run to run).

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

namespace CGAL_ext {
namespace internal {

/// The block size of the deterministic sums.
constexpr std::size_t deterministic_block = 2048;

/// The sums of `K` values over `0..n-1`: `f(first, last)` returns the `K`
/// partial sums of a block, and the blocks are added in order.
/// \tparam K the number of sums
/// \tparam F a callable `std::array<double, K>(std::size_t first, std::size_t last)`
/// \param n the number of indices
/// \param f the block sums
template <std::size_t K, class F>
std::array<double, K> deterministic_sums(std::size_t n, F&& f) {
  const std::size_t nb = (n + deterministic_block - 1) / deterministic_block;
  if (nb <= 1) return n == 0 ? std::array<double, K>{} : f(std::size_t(0), n); // no tasks for one block
  std::vector<std::array<double, K>> part(nb);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nb), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t b = r.begin(); b != r.end(); ++b)
      part[b] = f(b * deterministic_block, std::min(n, (b + 1) * deterministic_block));
  });
  std::array<double, K> s{};
  for (const auto& p : part)
    for (std::size_t k = 0; k < K; ++k) s[k] += p[k];
  return s;
}

/// The sum of `f(first, last)` over fixed blocks of `0..n-1`, added in block
/// order: the same bits whatever the number of threads.
/// \tparam F a callable `double(std::size_t first, std::size_t last)`
/// \param n the number of indices
/// \param f the block sum
template <class F>
double deterministic_sum(std::size_t n, F&& f) {
  return deterministic_sums<1>(n, [&](std::size_t first, std::size_t last) {
    return std::array<double, 1>{f(first, last)};
  })[0];
}

/// Below this many blocks, `deterministic_sum_of_terms()` computes the terms
/// in parallel over the indices, not over the blocks.
constexpr std::size_t deterministic_few_blocks = 8;

/// Calls `f(i)` for `i` in `0..n-1` in parallel (`f` must write per-index data only).
/// \tparam F a callable `void(std::size_t)`
/// \param n the number of indices
/// \param f the body
template <class F>
void parallel_for_each_index(std::size_t n, F&& f) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 256), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) f(i);
  });
}

/// The sum over `0..n-1` of `K` terms per index, added one by one in index
/// order into a sum per fixed block (from 0), the blocks in order: the same
/// bits as a `deterministic_sum()` whose block body adds them so, whatever the
/// number of threads. A term left 0 adds nothing (the sums are never -0).
/// With few blocks (a small `n`, as a local re-optimisation's) the terms are
/// computed in parallel over the indices and added after, so that all
/// threads work on them.
/// \tparam K the number of terms per index
/// \tparam Terms a callable `void(std::size_t i, std::array<double, K>& t)`
///         that sets the terms of `i` in `t` (all 0 on entry) and may write
///         other per-index data
/// \param n the number of indices
/// \param terms the terms
template <std::size_t K, class Terms>
double deterministic_sum_of_terms(std::size_t n, Terms&& terms) {
  if (n >= deterministic_few_blocks * deterministic_block)
    return deterministic_sum(n, [&](std::size_t first, std::size_t last) {
      double s = 0;
      for (std::size_t i = first; i < last; ++i) {
        std::array<double, K> t{};
        terms(i, t);
        for (double x : t) s += x;
      }
      return s;
    });
  // The terms' buffer is kept per thread between calls (a region's L-BFGS
  // sums hundreds of times; fewer than 8 blocks of indices here); a
  // call nested in `terms` uses one of its own.
  static thread_local std::vector<std::array<double, K>> kept;
  static thread_local bool kept_in_use = false;
  std::vector<std::array<double, K>> own;
  struct Use {
    bool& flag;
    const bool was;
    ~Use() { flag = was; }
  } use{kept_in_use, kept_in_use};
  std::vector<std::array<double, K>>& all = use.was ? own : kept;
  kept_in_use = true;
  if (all.size() < n) all.resize(n);
  parallel_for_each_index(n, [&](std::size_t i) {
    all[i] = {};
    terms(i, all[i]);
  });
  return deterministic_sum(n, [&](std::size_t first, std::size_t last) {
    double s = 0;
    for (std::size_t i = first; i < last; ++i)
      for (double x : all[i]) s += x;
    return s;
  });
}

} // namespace internal
} // namespace CGAL_ext

#endif // CGAL_EXT_INTERNAL_DETERMINISTIC_PARALLEL_H
