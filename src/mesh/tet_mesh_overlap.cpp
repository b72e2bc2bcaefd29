// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#include <CGAL_ext/internal/Angle_around_edge_3.h>
#include <CGAL_ext/internal/Tet_mesh_overlap.h>

#include <CGAL/Box_intersection_d/Box_with_info_d.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>

#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <utility>

namespace CGAL_ext {
namespace internal {
namespace {

// Double coordinates are exact inputs of Epick's filtered predicates.
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::size_t>;
using IK = CGAL::Simple_cartesian<CGAL::Interval_nt_advanced>; // needs Protect_FPU_rounding

Point point_of(const std::vector<std::array<double, 3>>& points, std::size_t v) {
  return Point(points[v][0], points[v][1], points[v][2]);
}

// Whether two boundary triangles meet elsewhere than in what they share.
bool triangles_overlap(const std::vector<std::array<double, 3>>& points, const std::array<std::size_t, 3>& s,
                       const std::array<std::size_t, 3>& t) {
  auto P = [&](std::size_t v) { return point_of(points, v); };
  // Positions in s and t of the shared vertices.
  int shared = 0, is[3] = {}, it[3] = {};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (s[std::size_t(i)] == t[std::size_t(j)]) {
        is[shared] = i;
        it[shared] = j;
        ++shared;
      }
  const K::Triangle_3 ts(P(s[0]), P(s[1]), P(s[2])), tt(P(t[0]), P(t[1]), P(t[2]));
  switch (shared) {
  case 0:
    return CGAL::do_intersect(ts, tt); // closed triangles: a touch counts
  case 1: {
    // (p, a, b) and (p, c, d): see find_boundary_overlap().
    const std::size_t a = s[std::size_t((is[0] + 1) % 3)], b = s[std::size_t((is[0] + 2) % 3)];
    const std::size_t c = t[std::size_t((it[0] + 1) % 3)], d = t[std::size_t((it[0] + 2) % 3)];
    return CGAL::do_intersect(K::Segment_3(P(a), P(b)), tt) || CGAL::do_intersect(K::Segment_3(P(c), P(d)), ts);
  }
  case 2: {
    // (u, v, a) and (u, v, b) overlap iff coplanar with a and b on the same side of (u, v).
    const std::size_t u = s[std::size_t(is[0])], v = s[std::size_t(is[1])];
    const std::size_t a = s[std::size_t(3 - is[0] - is[1])], b = t[std::size_t(3 - it[0] - it[1])];
    return CGAL::orientation(P(u), P(v), P(a), P(b)) == CGAL::COPLANAR &&
           CGAL::coplanar_orientation(P(u), P(v), P(a), P(b)) == CGAL::POSITIVE;
  }
  default:
    return false; // the same facet twice cannot be two boundary facets
  }
}

// The tetrahedra around each vertex, in increasing order (compressed rows:
// those of v are around[first[v]] to around[first[v + 1] - 1]); only around
// the vertices v with wanted[v], if `wanted` is not empty.
struct Stars {
  std::vector<std::size_t> first, around;
  Stars(std::size_t nv, const std::vector<std::array<std::size_t, 4>>& tets, const std::vector<char>& wanted = {})
      : first(nv + 1, 0) {
    auto in = [&](std::size_t v) { return wanted.empty() || wanted[v]; };
    for (const auto& t : tets)
      for (std::size_t v : t) first[v + 1] += in(v);
    std::partial_sum(first.begin(), first.end(), first.begin());
    around.resize(first[nv]);
    std::vector<std::size_t> next(first.begin(), first.end() - 1);
    for (std::size_t t = 0; t < tets.size(); ++t)
      for (std::size_t v : tets[t])
        if (in(v)) around[next[v]++] = t;
  }
};

// Whether x lies on the inner side, or on the plane, of each facet j of the
// positive tetrahedron q whose bit is set in `facets` (facet j is opposite
// q[j]). An interval pass comes first: one facet with x certainly on its
// outer side settles it, before x on the plane of another facet (common on
// planar boundaries) sends the filtered predicate to exact arithmetic.
bool inside_facets(const std::array<Point, 4>& q, const Point& x, unsigned facets) {
  auto with_x = [&](std::size_t j) {
    std::array<Point, 4> r = q;
    r[j] = x;
    return r;
  };
  {
    CGAL::Protect_FPU_rounding<true> rounding;
    auto I = [](const Point& y) { return IK::Point_3(y.x(), y.y(), y.z()); };
    for (std::size_t j = 0; j < 4; ++j) {
      if (!(facets >> j & 1u)) continue;
      const auto r = with_x(j);
      if (CGAL::certainly(CGAL::orientation(I(r[0]), I(r[1]), I(r[2]), I(r[3])) == CGAL::NEGATIVE)) return false;
    }
  }
  for (std::size_t j = 0; j < 4; ++j) {
    if (!(facets >> j & 1u)) continue;
    const auto r = with_x(j);
    if (CGAL::orientation(r[0], r[1], r[2], r[3]) == CGAL::NEGATIVE) return false;
  }
  return true;
}

// The hit of search(k, state) (a std::optional) with the smallest k in
// [0, n), searched in parallel: the same whatever the thread count. Each
// task has its own State (scratch space) and stops past the smallest hit
// found so far.
template <class State, class Search>
auto smallest_hit(std::size_t n, std::size_t grain, Search search) {
  using Hit = decltype(search(std::size_t(0), std::declval<State&>()));
  std::atomic<std::size_t> first_found{n};
  tbb::combinable<std::pair<std::size_t, Hit>> found([n] { return std::make_pair(n, Hit()); });
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, grain), [&](const tbb::blocked_range<std::size_t>& range) {
    State state;
    for (std::size_t k = range.begin(); k < range.end() && k < first_found.load(); ++k)
      if (Hit hit = search(k, state)) {
        auto& mine = found.local();
        if (k < mine.first) mine = std::make_pair(k, std::move(hit));
        std::size_t seen = first_found.load();
        while (k < seen && !first_found.compare_exchange_weak(seen, k)) {}
        return;
      }
  });
  std::pair<std::size_t, Hit> best(n, Hit());
  found.combine_each([&](const std::pair<std::size_t, Hit>& mine) {
    if (mine.first < best.first) best = mine;
  });
  return best.second;
}

} // namespace

std::optional<std::array<std::size_t, 2>>
find_boundary_overlap(const std::vector<std::array<double, 3>>& points,
                      const std::vector<std::array<std::size_t, 3>>& triangles) {
  std::vector<Box> boxes;
  boxes.reserve(triangles.size());
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const auto& t = triangles[i];
    boxes.emplace_back(point_of(points, t[0]).bbox() + point_of(points, t[1]).bbox() + point_of(points, t[2]).bbox(),
                       i);
  }
  std::optional<std::array<std::size_t, 2>> found;
  auto test = [&](const Box& a, const Box& b) {
    std::array<std::size_t, 2> pair{std::min(a.info(), b.info()), std::max(a.info(), b.info())};
    if (found && !(pair < *found)) return;
    if (triangles_overlap(points, triangles[pair[0]], triangles[pair[1]])) found = pair;
  };
  // (closed boxes: triangles that only touch are found too)
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), test);
  return found;
}

std::optional<Edge_overlap> find_overlap_around_edge(const std::vector<std::array<double, 3>>& points,
                                                     const std::vector<std::array<std::size_t, 4>>& tets) {
  const std::size_t nv = points.size();
  const Stars stars(nv, tets);
  const auto& first = stars.first;
  const auto& around = stars.around;
  // For the edge (i, j) of a positive tet, the vertices (k, l) such that
  // (i, j, k, l) is an even permutation: the wedge turns from k to l.
  static constexpr int wedge[4][4][2] = {{{0, 0}, {2, 3}, {3, 1}, {1, 2}},
                                         {{3, 2}, {0, 0}, {0, 3}, {2, 0}},
                                         {{1, 3}, {3, 0}, {0, 0}, {0, 1}},
                                         {{2, 1}, {0, 2}, {1, 0}, {0, 0}}};
  struct Wedge {
    std::size_t b, tet, from, to;
  };
  struct End {
    Point from, to;
    int half_from, half_to; // Angle_around_edge_3::half()
  };
  struct Scratch {
    std::vector<Wedge> wedges;
    std::vector<End> ends;
    std::vector<std::size_t> order;
  };
  // The first overlap about an edge (a, b) with b > a.
  auto at_vertex = [&](std::size_t a, Scratch& scratch) -> std::optional<Edge_overlap> {
    std::vector<Wedge>& wedges = scratch.wedges;
    std::vector<End>& ends = scratch.ends;
    std::vector<std::size_t>& order = scratch.order;
    wedges.clear();
    for (std::size_t k = first[a]; k < first[a + 1]; ++k) {
      const std::size_t t = around[k];
      const auto& v = tets[t];
      const int i = int(std::find(v.begin(), v.end(), a) - v.begin());
      for (int j = 0; j < 4; ++j)
        if (v[std::size_t(j)] > a)
          wedges.push_back({v[std::size_t(j)], t, v[std::size_t(wedge[i][j][0])], v[std::size_t(wedge[i][j][1])]});
    }
    std::sort(wedges.begin(), wedges.end(),
              [](const Wedge& x, const Wedge& y) { return x.b != y.b ? x.b < y.b : x.tet < y.tet; });
    for (std::size_t g = 0; g < wedges.size();) {
      std::size_t h = g + 1;
      while (h < wedges.size() && wedges[h].b == wedges[g].b) ++h;
      const std::size_t m = h - g;
      if (m > 1) {
        // Vertex indices decide equal directions: a predicate on a repeated
        // point is degenerate, and would leave the fast filter for exact arithmetic.
        const std::size_t ref_vertex = wedges[g].from;
        const Point pa = point_of(points, a), pb = point_of(points, wedges[g].b);
        const Angle_around_edge_3<K> angle(pa, pb, point_of(points, ref_vertex));
        ends.resize(m);
        for (std::size_t k = 0; k < m; ++k) {
          const Wedge& w = wedges[g + k];
          End& e = ends[k];
          e.from = point_of(points, w.from);
          e.to = point_of(points, w.to);
          e.half_from = w.from == ref_vertex ? 0 : angle.half(e.from);
          e.half_to = w.to == ref_vertex ? 0 : angle.half(e.to);
        }
        // Whether the direction of vertex u (point pu, half hu) precedes that of w.
        auto less = [&](std::size_t u, const Point& pu, int hu, std::size_t w, const Point& pw, int hw) {
          return u != w && angle.less(pu, hu, pw, hw);
        };
        order.resize(m);
        std::iota(order.begin(), order.end(), std::size_t(0));
        // Insertion sort: stable (ties keep the tet order, so that the
        // reported pair is deterministic), and the groups are small.
        for (std::size_t r = 1; r < m; ++r) {
          const std::size_t x = order[r];
          std::size_t q = r;
          for (; q > 0; --q) {
            const std::size_t y = order[q - 1];
            if (!less(wedges[g + x].from, ends[x].from, ends[x].half_from, wedges[g + y].from, ends[y].from,
                      ends[y].half_from))
              break;
            order[q] = y;
          }
          order[q] = x;
        }
        for (std::size_t r = 0; r < m; ++r) {
          const std::size_t x = order[r];
          const Wedge& w = wedges[g + x];
          const End& e = ends[x];
          // The wedge passes angle 0 (2 pi) iff its end does not follow its start.
          const bool wraps = !less(w.from, e.from, e.half_from, w.to, e.to, e.half_to);
          bool overlap;
          if (r + 1 < m) {
            const std::size_t y = order[r + 1];
            overlap = wraps || less(wedges[g + y].from, ends[y].from, ends[y].half_from, w.to, e.to, e.half_to);
          } else {
            // The last wedge may end exactly at angle 0, where the first begins.
            const std::size_t start = order[0];
            overlap = wraps && (e.half_to != 0 || less(wedges[g + start].from, ends[start].from, 0, w.to, e.to, 0));
          }
          if (overlap) {
            const std::size_t t0 = w.tet, t1 = wedges[g + order[(r + 1) % m]].tet;
            return Edge_overlap{{a, wedges[g].b}, {std::min(t0, t1), std::max(t0, t1)}};
          }
        }
      }
      g = h;
    }
    return std::nullopt;
  };
  // The overlap at the smallest vertex, whatever the thread count.
  return smallest_hit<Scratch>(nv, 1024, at_vertex);
}

std::optional<Vertex_in_tet> find_vertex_inside_tet(const std::vector<std::array<double, 3>>& points,
                                                    const std::vector<std::array<std::size_t, 4>>& tets,
                                                    const std::vector<std::size_t>& vertices) {
  if (vertices.empty() || tets.empty()) return std::nullopt;
  // The vertices in a uniform grid whose cell is the mean extent of the
  // tetrahedra's boxes; each tetrahedron visits the cells its box covers.
  // (CGAL's box_intersection_d sorts all the tets' boxes: several times slower.)
  CGAL::Bbox_3 all;
  for (std::size_t v : vertices) all += point_of(points, v).bbox();
  auto tet_box = [&](const std::array<std::size_t, 4>& c) {
    return point_of(points, c[0]).bbox() + point_of(points, c[1]).bbox() + point_of(points, c[2]).bbox() +
           point_of(points, c[3]).bbox();
  };
  // Quarter coordinates: no difference of two doubles overflows; every step
  // is monotone, so that a vertex in a box falls in a cell the box covers.
  double extent = 0;
  for (const auto& c : tets) {
    const CGAL::Bbox_3 b = tet_box(c);
    extent += std::max({b.xmax() / 4 - b.xmin() / 4, b.ymax() / 4 - b.ymin() / 4, b.zmax() / 4 - b.zmin() / 4}) /
              double(tets.size());
  }
  const double span =
      std::max({all.xmax() / 4 - all.xmin() / 4, all.ymax() / 4 - all.ymin() / 4, all.zmax() / 4 - all.zmin() / 4});
  // At most 2^20 cells per axis, so that a cell key fits 64 bits.
  const double cell = std::max({extent, span * 0x1p-20, std::numeric_limits<double>::min()});
  auto index = [&](double x, double lo) {
    const double i = std::floor((x / 4 - lo / 4) / cell);
    return static_cast<std::uint64_t>(i > 0 ? std::min(i, 0x1p20) : 0.0);
  };
  auto key = [](std::uint64_t i, std::uint64_t j, std::uint64_t k) { return (i << 42) | (j << 21) | k; };
  std::vector<std::pair<std::uint64_t, std::size_t>> grid;
  grid.reserve(vertices.size());
  for (std::size_t v : vertices)
    grid.push_back(
        {key(index(points[v][0], all.xmin()), index(points[v][1], all.ymin()), index(points[v][2], all.zmin())), v});
  std::sort(grid.begin(), grid.end());

  // Each thread keeps its smallest (vertex, tet) pair; the smallest of all is reported.
  tbb::combinable<std::optional<Vertex_in_tet>> found_by_thread;
  auto test = [&](std::size_t v, std::size_t t, const CGAL::Bbox_3& box) {
    std::optional<Vertex_in_tet>& found = found_by_thread.local();
    if (found && std::make_pair(found->vertex, found->tet) < std::make_pair(v, t)) return;
    const auto& c = tets[t];
    if (std::find(c.begin(), c.end(), v) != c.end()) return;
    const Point p = point_of(points, v);
    if (!CGAL::do_overlap(p.bbox(), box)) return;
    if (!inside_facets({point_of(points, c[0]), point_of(points, c[1]), point_of(points, c[2]), point_of(points, c[3])},
                       p, 0xFu))
      return;
    found = Vertex_in_tet{v, t};
  };
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, tets.size(), 4096), [&](const tbb::blocked_range<std::size_t>& range) {
        for (std::size_t t = range.begin(); t < range.end(); ++t) {
          const CGAL::Bbox_3 box = tet_box(tets[t]);
          if (!CGAL::do_overlap(box, all)) continue;
          const std::uint64_t i0 = index(box.xmin(), all.xmin()), i1 = index(box.xmax(), all.xmin());
          const std::uint64_t j0 = index(box.ymin(), all.ymin()), j1 = index(box.ymax(), all.ymin());
          const std::uint64_t k0 = index(box.zmin(), all.zmin()), k1 = index(box.zmax(), all.zmin());
          const double cells = double(i1 - i0 + 1) * double(j1 - j0 + 1) * double(k1 - k0 + 1);
          if (cells > double(vertices.size())) { // a huge tetrahedron: every vertex
            for (std::size_t v : vertices) test(v, t, box);
            continue;
          }
          for (std::uint64_t i = i0; i <= i1; ++i)
            for (std::uint64_t j = j0; j <= j1; ++j)
              for (std::uint64_t k = k0; k <= k1; ++k) {
                const std::uint64_t key_ijk = key(i, j, k);
                auto it = std::lower_bound(grid.begin(), grid.end(), std::make_pair(key_ijk, std::size_t(0)));
                for (; it != grid.end() && it->first == key_ijk; ++it) test(it->second, t, box);
              }
        }
      });
  std::optional<Vertex_in_tet> found;
  found_by_thread.combine_each([&](const std::optional<Vertex_in_tet>& hit) {
    if (hit && (!found || std::make_pair(hit->vertex, hit->tet) < std::make_pair(found->vertex, found->tet)))
      found = hit;
  });
  return found;
}

std::optional<Vertex_overlap> find_overlap_around_vertex(const std::vector<std::array<double, 3>>& points,
                                                         const std::vector<std::array<std::size_t, 4>>& tets,
                                                         const std::vector<std::array<std::size_t, 3>>& triangles) {
  std::vector<char> on_boundary(points.size(), 0);
  for (const auto& t : triangles)
    for (std::size_t v : t) on_boundary[v] = 1;
  const Stars stars(points.size(), tets, on_boundary);
  // The boundary edges (p, q), both ways, sorted.
  std::vector<std::array<std::size_t, 2>> edges;
  edges.reserve(6 * triangles.size());
  for (const auto& t : triangles)
    for (std::size_t k = 0; k < 3; ++k) {
      edges.push_back({t[k], t[(k + 1) % 3]});
      edges.push_back({t[(k + 1) % 3], t[k]});
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  std::vector<std::size_t> groups; // where each vertex's edges start
  for (std::size_t e = 0; e < edges.size(); ++e)
    if (e == 0 || edges[e][0] != edges[e - 1][0]) groups.push_back(e);
  groups.push_back(edges.size());

  // The first (q, tet) at the vertex p of group g, both in increasing order.
  struct No_scratch {};
  auto at_vertex = [&](std::size_t g, No_scratch&) -> std::optional<Vertex_overlap> {
    const std::size_t p = edges[groups[g]][0];
    for (std::size_t e = groups[g]; e < groups[g + 1]; ++e) {
      const std::size_t q = edges[e][1];
      const Point pq = point_of(points, q);
      for (std::size_t k = stars.first[p]; k < stars.first[p + 1]; ++k) {
        const std::size_t t = stars.around[k];
        const auto& c = tets[t];
        if (std::find(c.begin(), c.end(), q) != c.end()) continue;
        const std::size_t i = std::size_t(std::find(c.begin(), c.end(), p) - c.begin());
        // The corner at p is bounded by the three facets through p.
        if (inside_facets({point_of(points, c[0]), point_of(points, c[1]), point_of(points, c[2]), point_of(points, c[3])},
                          pq, 0xFu & ~(1u << i)))
          return Vertex_overlap{p, q, t};
      }
    }
    return std::nullopt;
  };
  // The overlap at the smallest vertex, whatever the thread count.
  return smallest_hit<No_scratch>(groups.size() - 1, 256, at_vertex);
}

} // namespace internal
} // namespace CGAL_ext
