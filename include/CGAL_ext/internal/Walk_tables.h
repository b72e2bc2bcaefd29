// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_INTERNAL_WALK_TABLES_H
#define CGAL_EXT_INTERNAL_WALK_TABLES_H

// Small tables and helpers of Segment_walk_3: the facets of a positively
// oriented cell, the vertex map across a facet, a face mask's dimension,
// and the in-place output into a std::vector.

#include <array>
#include <cstdint>
#include <iterator>
#include <type_traits>
#include <vector>

// The parts of the walk's inner loop (array_step and the functions it
// calls once per step) are split for reading, not for the compiler: they
// must be inlined, or the step's sums go through memory (measured: 6-8 %
// fewer cells per second with GCC 12 -O3 when they were not).
#if defined(__GNUC__)
#define CGAL_EXT_WALK_INLINE inline __attribute__((always_inline))
#else
#define CGAL_EXT_WALK_INLINE inline
#endif

namespace CGAL_ext {
namespace internal {

// Vertex indices of facet i of a positively oriented cell, ordered so that
// orientation(facet, vertex i) is positive (the cell is on the positive side).
inline constexpr std::array<int, 3> walk_inner_facet_table[4] = {{2, 1, 3}, {2, 3, 0}, {0, 3, 1}, {0, 1, 2}};
inline const std::array<int, 3>& walk_inner_facet(int i) { return walk_inner_facet_table[i]; }
// Moving from a cell r across its facet k into the neighbour n (whose facet
// m it is): for each local vertex i of n, the local index in r of the same
// vertex (2 bits per i; the vertex i = m, new, gets k), at entry
// (4 k + m) * 3 + rho, where n's vertex f[0] (f: inner facet m) is r's
// vertex g[rho] (g: inner facet k). A valid triangulation data structure
// orients neighbouring cells consistently, so the two cells see the shared
// facet in reverse cyclic order: f = (g[rho], g[rho - 1], g[rho + 1]).
constexpr std::array<std::uint8_t, 48> make_walk_facet_map() {
  std::array<std::uint8_t, 48> t{};
  for (int k = 0; k < 4; ++k)
    for (int m = 0; m < 4; ++m)
      for (int rho = 0; rho < 3; ++rho) {
        const std::array<int, 3>& g = walk_inner_facet_table[k];
        const std::array<int, 3>& f = walk_inner_facet_table[m];
        int l[4] = {0, 0, 0, 0};
        l[m] = k;
        l[f[0]] = g[rho];
        l[f[1]] = g[(rho + 2) % 3];
        l[f[2]] = g[(rho + 1) % 3];
        t[std::size_t((4 * k + m) * 3 + rho)] = std::uint8_t(l[0] | l[1] << 2 | l[2] << 4 | l[3] << 6);
      }
  return t;
}
inline constexpr std::array<std::uint8_t, 48> walk_facet_map = make_walk_facet_map();
// Output iterators that are std::back_inserter of a std::vector<Piece> get
// the pieces built in place: building a piece in a temporary and copying it
// makes the wide loads of the copy wait for the narrow stores that built it
// (a store-forwarding stall: a fifth of the samples of the full walk in a
// profile before this).
template <class It, class Piece>
struct Is_vector_back_inserter : std::false_type {};
template <class Piece, class Alloc>
struct Is_vector_back_inserter<std::back_insert_iterator<std::vector<Piece, Alloc>>, Piece> : std::true_type {};
template <class C>
C& back_inserter_container(std::back_insert_iterator<C>& it) {
  struct Access : std::back_insert_iterator<C> {
    static C* get(std::back_insert_iterator<C>& i) { return i.*(&Access::container); }
  };
  return *Access::get(it);
}

inline int walk_popcount(unsigned m) { return int(m & 1u) + int((m >> 1) & 1u) + int((m >> 2) & 1u) + int((m >> 3) & 1u); }

} // namespace internal

} // namespace CGAL_ext

#endif // CGAL_EXT_INTERNAL_WALK_TABLES_H
