// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_POINT_LOCATOR_3_H
#define CGAL_EXT_POINT_LOCATOR_3_H

/// \file Point_locator_3.h
/// Exact point location in the domain of a triangulation, valid for
/// non-convex `Tet_mesh_triangulation_3` domains (where CGAL's `locate()`
/// must not be used).

#include <CGAL_ext/Segment_walk_piece_3.h>
#include <CGAL_ext/Tet_mesh_triangulation_3.h>

#include <CGAL/number_utils.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace CGAL_ext {

/// \ingroup PkgCGALExtWalk
/// Exact point location: the lowest-dimensional simplex of the domain
/// containing a point, or "outside".
///
/// A hint cell that contains the point answers at once (4 orientation
/// tests). Otherwise a visibility walk among domain cells, from the hint or
/// from the cell of a coarse grid nearest to the point (whichever is nearer),
/// finds the cell in the common case. Where it cannot (it meets the boundary
/// of a non-convex domain, or cycles in a triangulation that is not
/// Delaunay), the point is tested against the cells whose bounding boxes
/// cover its bucket of a uniform grid: exact, and independent of the shape of
/// the domain. The bucket grid holds at most about 8 cell references per
/// domain cell: on meshes of long cells it is coarsened, down to one bucket
/// (a scan of every cell). The buckets' exactness needs `double` coordinates
/// (their bounding boxes are then exact); with another number type the
/// fallback scans every domain cell. Every side test is the traits' exact
/// `Orientation_3`. The grids are built lazily, once, thread-safely, and are
/// shared by copies of the locator; the bucket grid only on the first point
/// the visibility walk cannot locate. `Segment_walk_3` locates the start of
/// its segments with it.
///
/// \tparam Triangulation a model of `TetMeshTriangulation_3`, as for `Segment_walk_3`
/// \tparam Domain_predicate a unary predicate on `Cell_handle`, true for the domain cells
template <class Triangulation, class Domain_predicate = Is_finite_cell<Triangulation>>
class Point_locator_3 {
public:
  /// The point type.
  using Point = typename Triangulation::Point;
  /// Cell handle type.
  using Cell_handle = typename Triangulation::Cell_handle;
  /// The result: `dimension` -1 (outside the closed domain), 0, 1, 2 or 3,
  /// the simplex's vertices and a domain cell incident to it; `t_in == t_out == 0`.
  using Location = Segment_walk_piece_3<Triangulation>;
  /// A simplex as a face of a domain cell: the cell and the bit mask of the
  /// cell's vertices that span the simplex (bit `i` for vertex `i`); mask 0
  /// and a null cell for a point outside the closed domain.
  using Cell_face = std::pair<Cell_handle, unsigned>;

  /// \param tr the triangulation; it must outlive the locator and not change
  /// \param in_domain the domain predicate
  /// \throws std::invalid_argument if `tr.dimension() < 3`
  Point_locator_3(const Triangulation& tr, Domain_predicate in_domain)
      : tr_(&tr), in_domain_(std::move(in_domain)), orient_(tr.geom_traits().orientation_3_object()),
        grids_(std::make_shared<Grids>()) {
    if (tr.dimension() < 3)
      throw std::invalid_argument("Point_locator_3: the triangulation has dimension " + std::to_string(tr.dimension()) +
                                  "; point location needs a 3-dimensional triangulation");
  }

  /// Locator whose domain is every finite cell (only for `Is_finite_cell`).
  /// \tparam D the domain predicate (deduced; must be `Is_finite_cell<Triangulation>`)
  /// \param tr the triangulation
  template <class D = Domain_predicate,
            std::enable_if_t<std::is_same<D, Is_finite_cell<Triangulation>>::value, int> = 0>
  explicit Point_locator_3(const Triangulation& tr) : Point_locator_3(tr, Is_finite_cell<Triangulation>(tr)) {}

  /// Locates `x`.
  /// \param x the point
  /// \param hint a cell near `x` (ignored if null or not a domain cell)
  /// \returns the location of `x` (see `Location`)
  /// \throws std::invalid_argument if a coordinate of `x` is not finite
  Location operator()(const Point& x, Cell_handle hint = Cell_handle()) const {
    const Cell_face f = locate_face(x, hint);
    Location r;
    if (f.second == 0) return r;
    r.cell = f.first;
    for (int i = 0; i < 4; ++i)
      if (f.second & (1u << i)) r.vertices[++r.dimension] = f.first->vertex(i);
    return r;
  }

  /// Locates `x` as a face of a domain cell containing it.
  /// \param x the point
  /// \param hint a cell near `x` (ignored if null or not a domain cell)
  /// \returns the cell and the mask of the vertices spanning the simplex (see `Cell_face`)
  /// \throws std::invalid_argument if a coordinate of `x` is not finite
  Cell_face locate_face(const Point& x, Cell_handle hint = Cell_handle()) const {
    for (const auto& v : {x.x(), x.y(), x.z()})
      if (!std::isfinite(CGAL::to_double(v)))
        throw std::invalid_argument("Point_locator_3: a coordinate of the point is not finite");
    Cell_handle c;
    if (is_domain_cell(hint)) {
      if (const unsigned m = containment_mask(hint, x)) return {hint, m};
      // The hint, unless the start grid has a nearer cell in x's bucket (a
      // far hint would only lengthen the visibility walk).
      const Cell_handle g = bucket_start_cell(x);
      c = g != Cell_handle() && squared_distance_to(g, x) < squared_distance_to(hint, x) ? g : hint;
    } else {
      c = start_cell(x);
      if (c == Cell_handle()) return {}; // empty domain
    }
    bool stopped = false;
    const Cell_face f = visibility_walk(x, c, stopped);
    return stopped ? locate_by_buckets(x) : f;
  }

  /// Locates `x` with the exact fallback alone: the cells whose bounding
  /// boxes cover `x`'s bucket, each tested exactly, without the visibility
  /// walk. For tests, and for points where the walk is known to be useless.
  /// \param x the point
  /// \returns the first such cell that contains `x` and its face (see `Cell_face`), or none
  Cell_face locate_by_buckets(const Point& x) const {
    ensure_buckets();
    const Grids& gs = *grids_;
    if (!double_coordinates) { // bounding boxes in double would not be exact: every domain cell
      for (auto c : tr_->finite_cell_handles())
        if (is_domain_cell(c))
          if (const unsigned m = containment_mask(c, x)) return {c, m};
      return {};
    }
    if (gs.bucket_cells.empty()) return {};
    const Grid& g = gs.buckets;
    const std::array<double, 3> p = coords(x);
    const std::size_t b = g.index(g.coord(p[0], 0), g.coord(p[1], 1), g.coord(p[2], 2));
    for (std::size_t k = gs.bucket_begin[b]; k < gs.bucket_begin[b + 1]; ++k) {
      const Cell_handle c = gs.bucket_cells[k];
      if (const unsigned m = containment_mask(c, x)) return {c, m};
    }
    return {}; // outside the closed domain
  }

  /// Whether `c` is a cell of the domain (finite and accepted by the predicate).
  /// \param c the cell
  /// \returns true for a finite cell that the predicate accepts; false for a null handle
  bool is_domain_cell(Cell_handle c) const {
    if (c == Cell_handle() || tr_->is_infinite(c)) return false;
    if (std::is_same<Domain_predicate, Is_finite_cell<Triangulation>>::value) return true; // already decided
    return in_domain_(c);
  }

private:
  // A uniform grid over the domain's bounding box: n[d] buckets of size step[d] from lo[d].
  struct Grid {
    std::array<double, 3> lo{}, step{1, 1, 1};
    std::array<int, 3> n{1, 1, 1};
    // The bucket of coordinate v along axis d, clamped to the grid; monotone in v.
    int coord(double v, int d) const {
      const double u = (v - lo[d]) / step[d];
      if (!(u >= 0)) return 0;
      return u >= n[d] ? n[d] - 1 : int(u);
    }
    std::size_t index(int i, int j, int k) const { return (std::size_t(k) * n[1] + j) * n[0] + i; }
    std::size_t size() const { return std::size_t(n[0]) * n[1] * n[2]; }
  };
  // The lazily built grids, shared by copies of the locator.
  struct Grids {
    std::once_flag start_once, bucket_once;
    Grid box;                       // the domain's bounding box, with the start grid's resolution
    std::vector<Cell_handle> start; // per bucket of `box`: a domain cell whose centroid is in it, or null
    Cell_handle any_domain_cell;
    Grid buckets;                            // the bucket grid of the exact fallback
    std::vector<std::size_t> bucket_begin;   // per bucket, its range in bucket_cells (CSR)
    std::vector<Cell_handle> bucket_cells;   // the domain cells whose bounding box meets the bucket
  };

  const Point& pt(Cell_handle c, int i) const { return c->vertex(i)->point(); }
  static std::array<double, 3> coords(const Point& p) {
    return {CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())};
  }

  // The squared distance from x to the first vertex of c, in double: only
  // the choice of the start depends on it.
  double squared_distance_to(Cell_handle c, const Point& x) const {
    const std::array<double, 3> a = coords(pt(c, 0)), b = coords(x);
    return (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]);
  }

  // Orientation of cell c with vertex i replaced by x: positive iff x is
  // strictly on the same side of facet i as vertex i.
  CGAL::Orientation orient_x(Cell_handle c, int i, const Point& x) const {
    switch (i) {
    case 0: return orient_(x, pt(c, 1), pt(c, 2), pt(c, 3));
    case 1: return orient_(pt(c, 0), x, pt(c, 2), pt(c, 3));
    case 2: return orient_(pt(c, 0), pt(c, 1), x, pt(c, 3));
    default: return orient_(pt(c, 0), pt(c, 1), pt(c, 2), x);
    }
  }

  // The visibility walk from c towards x among domain cells. It ends in
  // Delaunay triangulations and is bounded otherwise; `stopped` is set if it
  // meets the boundary of the domain or reaches the bound.
  Cell_face visibility_walk(const Point& x, Cell_handle c, bool& stopped) const {
    const std::size_t bound = 64 + 32 * static_cast<std::size_t>(std::cbrt(double(tr_->number_of_cells())));
    unsigned rot = 0; // rotating the first facet tested avoids cycles
    for (std::size_t step = 0; step < bound; ++step) {
      int neg = -1;
      unsigned positive = 0;
      const unsigned first = rot++ & 3u;
      for (unsigned r = 0; r < 4 && neg < 0; ++r) {
        const int i = int((first + r) & 3u);
        const CGAL::Orientation o = orient_x(c, i, x);
        if (o == CGAL::NEGATIVE) neg = i;
        else if (o == CGAL::POSITIVE) positive |= 1u << i;
      }
      if (neg < 0) return {c, positive};
      const Cell_handle n = c->neighbor(neg);
      if (!is_domain_cell(n)) break;
      c = n;
    }
    stopped = true;
    return {};
  }

  // The mask of the vertices of c spanning the face whose relative interior
  // holds x, or 0 if x is outside the closed cell c.
  unsigned containment_mask(Cell_handle c, const Point& x) const {
    unsigned positive = 0;
    for (int i = 0; i < 4; ++i) {
      const CGAL::Orientation o = orient_x(c, i, x);
      if (o == CGAL::NEGATIVE) return 0;
      if (o == CGAL::POSITIVE) positive |= 1u << i;
    }
    return positive;
  }

  // Why the bucket fallback is exact: a cell containing x has x in its
  // bounding box, hence in one of its buckets (Grid::coord is monotone, and
  // the boxes and x are rounded alike, not at all for double coordinates).
  static constexpr bool double_coordinates =
      std::is_same<typename Triangulation::Geom_traits::FT, double>::value;

  // The start grid's cell in x's own bucket, or null (O(1): for a hint's rival).
  Cell_handle bucket_start_cell(const Point& x) const {
    ensure_start_grid();
    const Grids& gs = *grids_;
    if (gs.start.empty()) return Cell_handle();
    const std::array<double, 3> p = coords(x);
    return gs.start[gs.box.index(gs.box.coord(p[0], 0), gs.box.coord(p[1], 1), gs.box.coord(p[2], 2))];
  }

  // A domain cell near x: from the start grid, searching outwards from x's bucket.
  Cell_handle start_cell(const Point& x) const {
    ensure_start_grid();
    const Grids& gs = *grids_;
    if (gs.start.empty()) return gs.any_domain_cell;
    const Grid& g = gs.box;
    const std::array<double, 3> p = coords(x);
    const int ci = g.coord(p[0], 0), cj = g.coord(p[1], 1), ck = g.coord(p[2], 2);
    const int rmax = std::max(g.n[0], std::max(g.n[1], g.n[2]));
    for (int r = 0; r <= rmax; ++r)
      for (int k = std::max(0, ck - r); k <= std::min(g.n[2] - 1, ck + r); ++k)
        for (int j = std::max(0, cj - r); j <= std::min(g.n[1] - 1, cj + r); ++j)
          for (int i = std::max(0, ci - r); i <= std::min(g.n[0] - 1, ci + r); ++i) {
            if (std::max(std::abs(i - ci), std::max(std::abs(j - cj), std::abs(k - ck))) != r) continue;
            const Cell_handle c = gs.start[g.index(i, j, k)];
            if (c != Cell_handle()) return c;
          }
    return gs.any_domain_cell;
  }

  // The bounding box of the domain, and per bucket of a grid of about 8
  // domain cells per bucket (at most 64 per axis), one cell whose centroid is in it.
  void ensure_start_grid() const {
    std::call_once(grids_->start_once, [this] {
      Grids& gs = *grids_;
      std::array<double, 3> lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
      std::size_t cells = 0;
      for (auto c : tr_->finite_cell_handles()) {
        if (!is_domain_cell(c)) continue;
        if (gs.any_domain_cell == Cell_handle()) gs.any_domain_cell = c;
        ++cells;
        for (int i = 0; i < 4; ++i) {
          const std::array<double, 3> a = coords(pt(c, i));
          for (int d = 0; d < 3; ++d) {
            lo[d] = std::min(lo[d], a[d]);
            hi[d] = std::max(hi[d], a[d]);
          }
        }
      }
      if (cells == 0) return;
      gs.box = grid_over(lo, hi, std::max(1, std::min(64, int(std::cbrt(double(cells) / 8.0)))));
      gs.start.assign(gs.box.size(), Cell_handle());
      for (auto c : tr_->finite_cell_handles()) {
        if (!is_domain_cell(c)) continue;
        std::array<double, 3> g{0, 0, 0};
        for (int i = 0; i < 4; ++i) {
          const std::array<double, 3> a = coords(pt(c, i));
          for (int d = 0; d < 3; ++d) g[d] += 0.25 * a[d];
        }
        Cell_handle& b = gs.start[gs.box.index(gs.box.coord(g[0], 0), gs.box.coord(g[1], 1), gs.box.coord(g[2], 2))];
        if (b == Cell_handle()) b = c;
      }
    });
  }

  static Grid grid_over(const std::array<double, 3>& lo, const std::array<double, 3>& hi, int r) {
    Grid g;
    for (int d = 0; d < 3; ++d) {
      g.lo[d] = lo[d];
      g.n[d] = r;
      g.step[d] = hi[d] > lo[d] ? (hi[d] - lo[d]) / r : 1.0;
    }
    return g;
  }

  // The bucket range [lo, hi] of a domain cell's bounding box in g.
  void cell_buckets(const Grid& g, Cell_handle c, std::array<int, 3>& lo, std::array<int, 3>& hi) const {
    std::array<double, 3> mn{HUGE_VAL, HUGE_VAL, HUGE_VAL}, mx{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (int i = 0; i < 4; ++i) {
      const std::array<double, 3> a = coords(pt(c, i));
      for (int d = 0; d < 3; ++d) {
        mn[d] = std::min(mn[d], a[d]);
        mx[d] = std::max(mx[d], a[d]);
      }
    }
    for (int d = 0; d < 3; ++d) {
      lo[d] = g.coord(mn[d], d);
      hi[d] = g.coord(mx[d], d);
    }
  }

  // The bucket grid: the start grid's resolution, halved until the cell
  // references number at most 8 per cell (plus 2^20), so that long cells
  // (a Delaunay triangulation of points on a sphere) cannot exhaust memory.
  void ensure_buckets() const {
    ensure_start_grid();
    std::call_once(grids_->bucket_once, [this] {
      Grids& gs = *grids_;
      if (gs.start.empty() || !double_coordinates) return;
      std::vector<Cell_handle> cells;
      for (auto c : tr_->finite_cell_handles())
        if (is_domain_cell(c)) cells.push_back(c);
      const std::array<double, 3> lo = gs.box.lo;
      std::array<double, 3> hi;
      for (int d = 0; d < 3; ++d) hi[d] = lo[d] + gs.box.step[d] * gs.box.n[d];
      std::array<int, 3> a, b;
      for (int r = gs.box.n[0];; r = std::max(1, r / 2)) {
        gs.buckets = grid_over(lo, hi, r);
        std::size_t total = 0;
        for (Cell_handle c : cells) {
          cell_buckets(gs.buckets, c, a, b);
          total += std::size_t(b[0] - a[0] + 1) * (b[1] - a[1] + 1) * (b[2] - a[2] + 1);
        }
        if (r == 1 || total <= 8 * cells.size() + (std::size_t(1) << 20)) break;
      }
      fill_buckets(cells);
    });
  }

  // The bucket lists (CSR), in the triangulation's cell order: deterministic.
  void fill_buckets(const std::vector<Cell_handle>& cells) const {
    Grids& gs = *grids_;
    const Grid& g = gs.buckets;
    gs.bucket_begin.assign(g.size() + 1, 0);
    std::array<int, 3> a, b;
    for (int pass = 0; pass < 2; ++pass) {
      if (pass == 1) {
        for (std::size_t i = 0; i < g.size(); ++i) gs.bucket_begin[i + 1] += gs.bucket_begin[i];
        gs.bucket_cells.resize(gs.bucket_begin.back());
      }
      std::vector<std::size_t> next(gs.bucket_begin.begin(), gs.bucket_begin.end() - 1);
      for (Cell_handle c : cells) {
        cell_buckets(g, c, a, b);
        for (int k = a[2]; k <= b[2]; ++k)
          for (int j = a[1]; j <= b[1]; ++j)
            for (int i = a[0]; i <= b[0]; ++i) {
              if (pass == 0) ++gs.bucket_begin[g.index(i, j, k) + 1];
              else gs.bucket_cells[next[g.index(i, j, k)]++] = c;
            }
      }
    }
  }

  const Triangulation* tr_;
  Domain_predicate in_domain_;
  typename Triangulation::Geom_traits::Orientation_3 orient_;
  std::shared_ptr<Grids> grids_;
};

} // namespace CGAL_ext

#endif // CGAL_EXT_POINT_LOCATOR_3_H
