// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_INTERNAL_SEGMENT_WALK_3_LOCATION_H
#define CGAL_EXT_INTERNAL_SEGMENT_WALK_3_LOCATION_H

// Point location for Segment_walk_3: a coarse grid of domain cells for a
// start, a visibility walk among domain cells, and the exact walk from a
// vertex when the visibility walk meets the boundary or cycles.
//
// Member definitions of Segment_walk_3, included at the end of
// <CGAL_ext/Segment_walk_3.h>; not a header of its own.

namespace CGAL_ext {

// -------------------------------------------------------------- location
template <class Triangulation, class Domain_predicate>
inline void Segment_walk_3<Triangulation, Domain_predicate>::ensure_grid() const {
  std::call_once(shared_->grid_once, [this] {
    Shared& sh = *shared_;
    std::array<double, 3> lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    std::size_t nc = 0;
    for (auto c : tr_->finite_cell_handles()) {
      if (!is_domain_cell(c)) continue;
      if (sh.any_domain_cell == Cell_handle()) sh.any_domain_cell = c;
      ++nc;
      for (int i = 0; i < 4; ++i) {
        const Point& a = pt(c, i);
        const double xyz[3] = {CGAL::to_double(a.x()), CGAL::to_double(a.y()), CGAL::to_double(a.z())};
        for (int d = 0; d < 3; ++d) {
          lo[d] = std::min(lo[d], xyz[d]);
          hi[d] = std::max(hi[d], xyz[d]);
        }
      }
    }
    if (nc == 0) return;
    const int r = std::max(1, std::min(64, int(std::cbrt(double(nc) / 8.0))));
    for (int d = 0; d < 3; ++d) {
      sh.lo[d] = lo[d];
      sh.n[d] = r;
      sh.step[d] = hi[d] > lo[d] ? (hi[d] - lo[d]) / r : 1.0;
    }
    sh.grid.assign(std::size_t(r) * r * r, Cell_handle());
    for (auto c : tr_->finite_cell_handles()) {
      if (!is_domain_cell(c)) continue;
      double g[3] = {0, 0, 0};
      for (int i = 0; i < 4; ++i) {
        const Point& a = pt(c, i);
        g[0] += 0.25 * CGAL::to_double(a.x());
        g[1] += 0.25 * CGAL::to_double(a.y());
        g[2] += 0.25 * CGAL::to_double(a.z());
      }
      Cell_handle& b = sh.grid[grid_index(g)];
      if (b == Cell_handle()) b = c;
    }
  });
}

template <class Triangulation, class Domain_predicate>
inline int Segment_walk_3<Triangulation, Domain_predicate>::grid_coord(double v, int d) const {
  const Shared& sh = *shared_;
  const double u = (v - sh.lo[d]) / sh.step[d];
  if (!(u >= 0)) return 0;
  return u >= sh.n[d] ? sh.n[d] - 1 : int(u);
}

template <class Triangulation, class Domain_predicate>
inline std::size_t Segment_walk_3<Triangulation, Domain_predicate>::grid_index(const double* g) const {
  const Shared& sh = *shared_;
  return (std::size_t(grid_coord(g[2], 2)) * sh.n[1] + grid_coord(g[1], 1)) * sh.n[0] + grid_coord(g[0], 0);
}

template <class Triangulation, class Domain_predicate>
inline auto Segment_walk_3<Triangulation, Domain_predicate>::grid_start(const Point& x) const -> Cell_handle {
  ensure_grid();
  const Shared& sh = *shared_;
  if (sh.grid.empty()) return Cell_handle();
  const double g[3] = {CGAL::to_double(x.x()), CGAL::to_double(x.y()), CGAL::to_double(x.z())};
  const int ci = grid_coord(g[0], 0), cj = grid_coord(g[1], 1), ck = grid_coord(g[2], 2);
  const int rmax = std::max(sh.n[0], std::max(sh.n[1], sh.n[2]));
  for (int r = 0; r <= rmax; ++r)
    for (int k = std::max(0, ck - r); k <= std::min(sh.n[2] - 1, ck + r); ++k)
      for (int j = std::max(0, cj - r); j <= std::min(sh.n[1] - 1, cj + r); ++j)
        for (int i = std::max(0, ci - r); i <= std::min(sh.n[0] - 1, ci + r); ++i) {
          if (std::max(std::abs(i - ci), std::max(std::abs(j - cj), std::abs(k - ck))) != r) continue;
          const Cell_handle c = sh.grid[(std::size_t(k) * sh.n[1] + j) * sh.n[0] + i];
          if (c != Cell_handle()) return c;
        }
  return sh.any_domain_cell;
}

// The lowest-dimensional domain simplex containing x, or invalid.
template <class Triangulation, class Domain_predicate>
inline auto Segment_walk_3<Triangulation, Domain_predicate>::
    locate_simplex(const Point& x, Cell_handle hint) const -> Simplex {
  Cell_handle c = is_domain_cell(hint) ? hint : grid_start(x);
  if (c == Cell_handle()) return Simplex(); // empty domain
  // Visibility walk among domain cells; it ends in Delaunay triangulations,
  // and is bounded otherwise.
  const std::size_t bound = 64 + 4 * static_cast<std::size_t>(std::cbrt(double(tr_->number_of_cells()))) * 8;
  unsigned rot = 0;
  for (std::size_t step = 0; step < bound; ++step) {
    CGAL::Orientation o[4];
    int neg = -1;
    const unsigned start = rot++ & 3u;
    for (unsigned r = 0; r < 4; ++r) {
      const int i = int((start + r) & 3u);
      o[i] = orient_x(c, i, x);
      if (o[i] == CGAL::NEGATIVE) {
        neg = i;
        break;
      }
    }
    if (neg < 0) {
      unsigned m = 0;
      for (int i = 0; i < 4; ++i)
        if (o[i] == CGAL::POSITIVE) m |= 1u << i;
      return Simplex{c, m};
    }
    const Cell_handle n = c->neighbor(neg);
    if (!is_domain_cell(n)) break;
    c = n;
  }
  // Exact fallback: walk from a vertex of c to x.
  const Point& v = pt(c, 0);
  if (v == x) return Simplex{c, 1u};
  Last_sink sink{this, Simplex()};
  walk(v, x, Simplex{c, 1u}, sink);
  return sink.last;
}

} // namespace CGAL_ext

#endif // CGAL_EXT_INTERNAL_SEGMENT_WALK_3_LOCATION_H
