// Property tests of the exact segment walk: tiling of [0, 1], incidence of
// consecutive pieces, fast mode against full output, gaps of non-convex
// domains, agreement with point location and, on generic segments, with
// CGAL's segment traverser. The exact brute-force comparison is in
// test_segment_walk_reference.cpp.
#include "walk_test_meshes.h"

#include <CGAL_ext/Point_locator_3.h>
#include <CGAL_ext/internal/Huge_page_allocator.h>
#include <CGAL_ext/Segment_walk_3.h>
#include <CGAL_ext/Tet_mesh_triangulation_3.h>
#include <CGAL_ext/build_triangulation_from_tets.h>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <catch2/catch.hpp>

#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <memory>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

using namespace CGAL_ext;
using namespace CGAL_ext::testing;

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh_tr = Tet_mesh_triangulation_3<K>;
using Mesh_walk = Segment_walk_3<Mesh_tr, Is_tet_mesh_domain_cell>;
using DT = CGAL::Delaunay_triangulation_3<K>;

// The Delaunay triangulation of n points drawn uniformly in the unit cube
// with u and rng (which the caller may go on using).
template <class Rng>
DT random_delaunay(int n, Rng& rng, std::uniform_real_distribution<double>& u) {
  std::vector<DT::Point> pts;
  for (int i = 0; i < n; ++i) pts.emplace_back(u(rng), u(rng), u(rng));
  return DT(pts.begin(), pts.end());
}

// Domain of a Delaunay triangulation: the cells whose centroid is not in the
// column x < 0.5, y < 0.5.
struct Outside_column {
  const DT* dt;
  bool operator()(DT::Cell_handle c) const {
    const auto g = CGAL::centroid(dt->tetrahedron(c));
    return !(g.x() < 0.5 && g.y() < 0.5);
  }
};


template <class Tr>
std::string describe(const std::vector<Segment_walk_piece_3<Tr>>& w) {
  std::ostringstream os;
  os.precision(17);
  for (const auto& x : w) {
    os << "  dim " << x.dimension << " {";
    for (int i = 0; i <= x.dimension; ++i) os << (i ? " " : "") << x.vertices[i]->point();
    os << "} [" << x.t_in << ", " << x.t_out << "]\n";
  }
  return os.str();
}

template <class Tr>
std::set<const void*> vset(const Segment_walk_piece_3<Tr>& x) {
  std::set<const void*> s;
  for (int i = 0; i <= x.dimension; ++i) s.insert(&*x.vertices[i]);
  return s;
}

// Every structural property of a full output; returns an empty string or the first violation.
template <class Tr, class Walk>
std::string full_violation(const Tr& tr, const Walk& walk, const std::vector<Segment_walk_piece_3<Tr>>& w,
                           bool degenerate_segment) {
  if (w.empty()) return "no piece";
  if (w.front().t_in != 0.0) return "first t_in is not 0";
  if (w.back().t_out != 1.0) return "last t_out is not 1";
  if (degenerate_segment && w.size() != 1) return "q == p but several pieces";
  for (std::size_t i = 0; i < w.size(); ++i) {
    const auto& x = w[i];
    const std::string at = "piece " + std::to_string(i) + ": ";
    if (!(x.t_in <= x.t_out)) return at + "t_in > t_out";
    if (i + 1 < w.size() && x.t_out != w[i + 1].t_in) return at + "not adjacent to the next piece";
    if (x.dimension < -1 || x.dimension > 3) return at + "bad dimension";
    if (x.dimension < 0) {
      if (x.cell != typename Tr::Cell_handle()) return at + "a gap with a cell";
      if (i + 1 < w.size() && w[i + 1].dimension < 0) return at + "two consecutive gaps in full output";
      // Leaving or entering the domain happens at a point of a boundary simplex.
      if (i > 0 && (w[i - 1].t_in != w[i - 1].t_out || w[i - 1].dimension > 2)) return at + "gap after a piece of positive length";
      if (i + 1 < w.size() && (w[i + 1].t_in != w[i + 1].t_out || w[i + 1].dimension > 2))
        return at + "gap before a piece of positive length";
      continue;
    }
    if (!walk.is_domain_cell(x.cell)) return at + "cell not in the domain";
    for (int k = 0; k <= x.dimension; ++k) {
      if (x.vertices[k] == typename Tr::Vertex_handle()) return at + "null vertex";
      if (!x.cell->has_vertex(x.vertices[k])) return at + "cell not incident to the simplex";
      for (int l = 0; l < k; ++l)
        if (x.vertices[k] == x.vertices[l]) return at + "repeated vertex";
    }
    for (int k = x.dimension + 1; k < 4; ++k)
      if (x.vertices[k] != typename Tr::Vertex_handle()) return at + "extra vertex";
    if (x.dimension == 3 && x.vertices[0] == x.vertices[1]) return at + "bad cell";
    if (i + 1 < w.size() && w[i + 1].dimension >= 0) {
      // Consecutive simplices: one is a proper face of the other.
      const auto a = vset(x), b = vset(w[i + 1]);
      const bool a_in_b = std::includes(b.begin(), b.end(), a.begin(), a.end());
      const bool b_in_a = std::includes(a.begin(), a.end(), b.begin(), b.end());
      if (!(a_in_b || b_in_a) || a == b) return at + "not a proper face of the next piece, nor the converse";
      // A zero-length piece between two pieces is a face of both of lower dimension.
      if (x.t_in == x.t_out && i > 0 && w[i - 1].dimension >= 0 && !degenerate_segment &&
          !(x.dimension < w[i - 1].dimension && x.dimension < w[i + 1].dimension))
        return at + "zero-length piece of dimension not below its neighbours'";
    }
    (void)tr;
  }
  return {};
}

// fast(q, p) is the full output without its zero-length pieces.
template <class Tr>
std::string fast_violation(const std::vector<Segment_walk_piece_3<Tr>>& full, const std::vector<Segment_walk_piece_3<Tr>>& fast,
                           bool degenerate_segment) {
  std::vector<Segment_walk_piece_3<Tr>> expected;
  for (const auto& x : full)
    if (degenerate_segment || x.t_in != x.t_out || x.dimension == 3) expected.push_back(x);
  // A cell is never a zero-length structural piece; other zero-length pieces are.
  if (!degenerate_segment) {
    expected.clear();
    for (std::size_t i = 0; i < full.size(); ++i) {
      const auto& x = full[i];
      if (x.t_in != x.t_out || x.dimension == 3 || x.dimension == -1) expected.push_back(x);
    }
  }
  if (expected.size() != fast.size()) return "fast has " + std::to_string(fast.size()) + " pieces, expected " + std::to_string(expected.size());
  for (std::size_t i = 0; i < fast.size(); ++i) {
    if (expected[i].dimension != fast[i].dimension || vset(expected[i]) != vset(fast[i]) ||
        expected[i].t_in != fast[i].t_in || expected[i].t_out != fast[i].t_out)
      return "fast piece " + std::to_string(i) + " differs";
  }
  return {};
}

// Midpoints of pieces of positive length lie in the located simplex (cells)
// or outside the domain (gaps): walk and location agree.
template <class Tr, class Walk>
std::string location_violation(const Walk& walk, const typename Tr::Point& q, const typename Tr::Point& p,
                               const std::vector<Segment_walk_piece_3<Tr>>& w) {
  for (std::size_t i = 0; i < w.size(); ++i) {
    const auto& x = w[i];
    if (x.t_out - x.t_in < 1e-6 || (x.dimension != 3 && x.dimension != -1)) continue;
    const double t = 0.5 * (x.t_in + x.t_out);
    const typename Tr::Point m(q.x() + t * (p.x() - q.x()), q.y() + t * (p.y() - q.y()), q.z() + t * (p.z() - q.z()));
    const auto l = walk.locate(m);
    if (x.dimension == -1 && l.dimension != -1) return "midpoint of gap " + std::to_string(i) + " is in the domain";
    if (x.dimension == 3 && (l.dimension != 3 || l.cell != x.cell))
      return "midpoint of cell piece " + std::to_string(i) + " is located elsewhere";
  }
  return {};
}

template <class Tr, class Walk>
void check_segment(const Tr& tr, const Walk& walk, const typename Tr::Point& q, const typename Tr::Point& p,
                   bool check_location = true, std::vector<Segment_walk_piece_3<Tr>>* out = nullptr) {
  std::vector<Segment_walk_piece_3<Tr>> full, fast;
  walk(q, p, std::back_inserter(full));
  walk.fast(q, p, std::back_inserter(fast));
  const bool deg = q == p;
  std::string why = full_violation(tr, walk, full, deg);
  if (why.empty()) why = fast_violation(full, fast, deg);
  if (why.empty() && check_location) why = location_violation<Tr>(walk, q, p, full);
  if (!why.empty()) {
    INFO("segment (" << q << ") -> (" << p << ")\n" << why << "\nfull:\n" << describe(full) << "fast:\n" << describe(fast));
    CHECK(why.empty());
  } else {
    CHECK(why.empty());
  }
  if (out) *out = full;
}

Mesh_tr build(const Test_mesh& m) {
  Mesh_tr tr;
  build_triangulation_from_tets(m.points, m.tets, {}, tr);
  return tr;
}

int count_dim(const std::vector<Segment_walk_piece_3<Mesh_tr>>& w, int d) {
  return int(std::count_if(w.begin(), w.end(), [d](const auto& x) { return x.dimension == d; }));
}

} // namespace

TEST_CASE("segment walk: errors", "[segment_walk]") {
  DT flat;
  flat.insert(DT::Point(0, 0, 0));
  flat.insert(DT::Point(1, 0, 0));
  flat.insert(DT::Point(0, 1, 0));
  flat.insert(DT::Point(1, 1, 0));
  REQUIRE(flat.dimension() == 2);
  CHECK_THROWS_AS(Segment_walk_3<DT>(flat), std::invalid_argument);
  try {
    Segment_walk_3<DT> w(flat);
  } catch (const std::invalid_argument& e) {
    CHECK(std::string(e.what()).find("dimension 2") != std::string::npos);
  }

  const Mesh_tr tr = build(kuhn_grid(1, 1, 1, 1.0));
  const Mesh_walk walk(tr, Is_tet_mesh_domain_cell());
  std::vector<Segment_walk_piece_3<Mesh_tr>> out;
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  CHECK_THROWS_AS(walk(Mesh_tr::Point(nan, 0, 0), Mesh_tr::Point(0.5, 0.5, 0.5), std::back_inserter(out)), std::invalid_argument);
  CHECK_THROWS_AS(walk.fast(Mesh_tr::Point(0, 0, 0), Mesh_tr::Point(0.5, inf, 0.5), std::back_inserter(out)), std::invalid_argument);
  CHECK_THROWS_AS(walk.locate(Mesh_tr::Point(0, -inf, 0)), std::invalid_argument);
}

TEST_CASE("segment walk: q == p gives exactly one piece", "[segment_walk]") {
  const Mesh_tr tr = build(kuhn_grid(2, 2, 2, 12.0, [](int i, int j, int k) { return !(i == 1 && j == 1 && k == 1); }));
  const Mesh_walk walk(tr, Is_tet_mesh_domain_cell());
  struct Case { double x, y, z; int dim; };
  const Case cases[] = {
      {0, 0, 0, 0},    {12, 12, 12, 0}, {24, 24, 12, 0}, {6, 0, 0, 1},   {6, 6, 6, 1}, // main diagonal
      {6, 6, 0, 1},    {8, 4, 0, 2},    {9, 6, 3, 3},    {18, 18, 18, -1}, {30, 0, 0, -1}, {24, 24, 24, -1},
      {18, 18, 12, 1}, // face diagonal on the boundary of the removed cube
  };
  for (const Case& c : cases) {
    const Mesh_tr::Point x(c.x, c.y, c.z);
    std::vector<Segment_walk_piece_3<Mesh_tr>> full, fast;
    walk(x, x, std::back_inserter(full));
    walk.fast(x, x, std::back_inserter(fast));
    INFO("point " << x);
    REQUIRE(full.size() == 1);
    REQUIRE(fast.size() == 1);
    CHECK(full[0].dimension == c.dim);
    CHECK(fast[0].dimension == c.dim);
    CHECK(full[0].t_in == 0.0);
    CHECK(full[0].t_out == 1.0);
    CHECK(walk.locate(x).dimension == c.dim);
  }
}

TEST_CASE("segment walk: a single cube, hand-checked sequences", "[segment_walk]") {
  const Mesh_tr tr = build(kuhn_grid(1, 1, 1, 1.0));
  const Mesh_walk walk(tr, Is_tet_mesh_domain_cell());
  std::vector<Segment_walk_piece_3<Mesh_tr>> w;
  // Along the main diagonal, an edge of all 6 tets, from outside to outside.
  check_segment(tr, walk, Mesh_tr::Point(-1, -1, -1), Mesh_tr::Point(2, 2, 2), true, &w);
  REQUIRE(w.size() == 5);
  CHECK(w[0].dimension == -1);
  CHECK(w[1].dimension == 0);
  CHECK(w[2].dimension == 1);
  CHECK(w[3].dimension == 0);
  CHECK(w[4].dimension == -1);
  CHECK(w[1].t_in == Approx(1.0 / 3));
  CHECK(w[3].t_in == Approx(2.0 / 3));
  // In the plane z = 0 (a boundary face), across the face diagonal (0,0,0)-(1,1,0).
  check_segment(tr, walk, Mesh_tr::Point(0.75, 0.25, 0), Mesh_tr::Point(0.25, 0.75, 0), true, &w);
  REQUIRE(w.size() == 3);
  CHECK(w[0].dimension == 2);
  CHECK(w[1].dimension == 1);
  CHECK(w[2].dimension == 2);
  CHECK(w[1].t_in == Approx(0.5));
  // Ending exactly at a vertex, starting inside.
  check_segment(tr, walk, Mesh_tr::Point(0.5, 0.25, 0.125), Mesh_tr::Point(1, 0, 0), true, &w);
  CHECK(w.back().dimension == 0);
  CHECK(w.back().t_in == 1.0);
  // Segment outside, missing the cube: one gap.
  check_segment(tr, walk, Mesh_tr::Point(2, 0, 0), Mesh_tr::Point(2, 3, 1), true, &w);
  REQUIRE(w.size() == 1);
  CHECK(w[0].dimension == -1);
  // Touching the cube at a vertex only: gap, vertex, gap.
  check_segment(tr, walk, Mesh_tr::Point(2, 0, 0), Mesh_tr::Point(0, 2, 0), true, &w);
  REQUIRE(w.size() == 3);
  CHECK(w[1].dimension == 0);
  CHECK(w[1].t_in == Approx(0.5));
  // Grazing along a boundary edge: gap, vertex, edge, vertex, gap.
  check_segment(tr, walk, Mesh_tr::Point(-1, 0, 0), Mesh_tr::Point(2, 0, 0), true, &w);
  REQUIRE(w.size() == 5);
  CHECK(w[2].dimension == 1);
}

TEST_CASE("segment walk: L-shape, the segment leaves and re-enters", "[segment_walk]") {
  const Mesh_tr tr = build(kuhn_grid(2, 2, 1, 1.0, [](int i, int j, int) { return !(i == 1 && j == 1); }));
  const Mesh_walk walk(tr, Is_tet_mesh_domain_cell());
  std::vector<Segment_walk_piece_3<Mesh_tr>> w;
  check_segment(tr, walk, Mesh_tr::Point(0.5, 1.75, 0.5), Mesh_tr::Point(1.75, 0.5, 0.5), true, &w);
  REQUIRE(count_dim(w, -1) == 1);
  const auto g = std::find_if(w.begin(), w.end(), [](const auto& x) { return x.dimension == -1; });
  CHECK(g->t_in == Approx(0.4));
  CHECK(g->t_out == Approx(0.6));
  CHECK(std::prev(g)->dimension == 2);
  CHECK(std::next(g)->dimension == 2);
  // Through the re-entrant edge x = y = 1: no gap, an edge crossing.
  check_segment(tr, walk, Mesh_tr::Point(0.5, 1.5, 0.25), Mesh_tr::Point(1.5, 0.5, 0.75), true, &w);
  CHECK(count_dim(w, -1) == 0);
  CHECK(std::count_if(w.begin(), w.end(), [](const auto& x) { return x.dimension == 1 && x.t_in == Approx(0.5); }) == 1);
  // Along the re-entrant edge, from outside: gap, vertex, edge, vertex, gap.
  check_segment(tr, walk, Mesh_tr::Point(1, 1, -1), Mesh_tr::Point(1, 1, 2), true, &w);
  REQUIRE(w.size() == 5);
  CHECK(w[2].dimension == 1);
  // Starting in the notch, ending in the domain.
  check_segment(tr, walk, Mesh_tr::Point(1.5, 1.5, 0.5), Mesh_tr::Point(0.2, 0.3, 0.45), true, &w);
  CHECK(w.front().dimension == -1);
  CHECK(w.back().dimension == 3);
}

TEST_CASE("segment walk: grid with a tunnel, several gaps", "[segment_walk]") {
  // 5 x 3 x 3 cubes; the middle column (j = 1, k = 1) is removed for 1 <= i <= 3,
  // and the slab i = 2 keeps only its border ring: the tunnel crosses it.
  const auto keep = [](int i, int j, int k) { return !(j == 1 && k == 1 && i >= 1 && i <= 3); };
  const Mesh_tr tr = build(kuhn_grid(5, 3, 3, 1.0, keep));
  const Mesh_walk walk(tr, Is_tet_mesh_domain_cell());
  std::vector<Segment_walk_piece_3<Mesh_tr>> w;
  // Across the tunnel, perpendicular to it.
  check_segment(tr, walk, Mesh_tr::Point(2.3, 0.2, 1.4), Mesh_tr::Point(2.6, 2.9, 1.6), true, &w);
  CHECK(count_dim(w, -1) == 1);
  // Through the tunnel, entering the domain at both ends.
  check_segment(tr, walk, Mesh_tr::Point(0.5, 1.4, 1.6), Mesh_tr::Point(4.5, 1.6, 1.3), true, &w);
  CHECK(count_dim(w, -1) == 1);
  // In and out of the whole grid, crossing the tunnel twice-removed slabs.
  check_segment(tr, walk, Mesh_tr::Point(-1, 1.5, 1.5), Mesh_tr::Point(6, 1.5, 1.5), true, &w);
  CHECK(count_dim(w, -1) == 3);
  // Zig-zag outside and inside the grid.
  check_segment(tr, walk, Mesh_tr::Point(2.5, -1, 1.5), Mesh_tr::Point(2.5, 4, 1.5), true, &w);
  CHECK(count_dim(w, -1) == 3);
}

TEST_CASE("segment walk: components touching along an edge and at a vertex", "[segment_walk]") {
  {
    const Mesh_tr tr = build(kuhn_grid(2, 2, 1, 1.0, [](int i, int j, int) { return i == j; }));
    const Mesh_walk walk(tr, Is_tet_mesh_domain_cell());
    std::vector<Segment_walk_piece_3<Mesh_tr>> w;
    check_segment(tr, walk, Mesh_tr::Point(0.5, 0.5, 0.2), Mesh_tr::Point(1.5, 1.5, 0.8), true, &w);
    CHECK(count_dim(w, -1) == 0);
    // Across the shared edge from the outside: gap, edge, gap.
    check_segment(tr, walk, Mesh_tr::Point(0.5, 1.5, 0.5), Mesh_tr::Point(1.5, 0.5, 0.5), true, &w);
    REQUIRE(w.size() == 3);
    CHECK(w[1].dimension == 1);
  }
  {
    const Mesh_tr tr = build(kuhn_grid(2, 2, 2, 1.0, [](int i, int j, int k) { return i == j && j == k; }));
    const Mesh_walk walk(tr, Is_tet_mesh_domain_cell());
    std::vector<Segment_walk_piece_3<Mesh_tr>> w;
    // Along the main diagonal through the touching vertex: edge, vertex, edge.
    check_segment(tr, walk, Mesh_tr::Point(0.5, 0.5, 0.5), Mesh_tr::Point(1.5, 1.5, 1.5), true, &w);
    REQUIRE(w.size() == 3);
    CHECK(w[0].dimension == 1);
    CHECK(w[1].dimension == 0);
    CHECK(w[2].dimension == 1);
    // Through the touching vertex off the diagonal: no gap.
    check_segment(tr, walk, Mesh_tr::Point(0.5, 0.625, 0.75), Mesh_tr::Point(1.5, 1.375, 1.25), true, &w);
    CHECK(count_dim(w, -1) == 0);
    CHECK(count_dim(w, 0) == 1);
    // The same in the other direction (the vertex star is searched from the second component).
    check_segment(tr, walk, Mesh_tr::Point(1.5, 1.375, 1.25), Mesh_tr::Point(0.5, 0.625, 0.75), true, &w);
    CHECK(count_dim(w, -1) == 0);
    CHECK(count_dim(w, 0) == 1);
    // Along a cube edge of the second component, through the touching vertex,
    // then along a cube edge of the first one: edge, vertex, edge.
    check_segment(tr, walk, Mesh_tr::Point(1.5, 1, 1), Mesh_tr::Point(0.5, 1, 1), true, &w);
    REQUIRE(w.size() == 3);
    CHECK(w[1].dimension == 0);
    CHECK(w[2].dimension == 1);
    // Starting at the touching vertex, into the second component.
    check_segment(tr, walk, Mesh_tr::Point(1, 1, 1), Mesh_tr::Point(1.5, 1.375, 1.25), true, &w);
    CHECK(w.front().dimension == 0);
    CHECK(w.back().dimension == 3);
  }
}

TEST_CASE("segment walk: thousands of exactly degenerate segments on Kuhn grids", "[segment_walk]") {
  std::mt19937 rng(12345);
  const int n = 4;
  const double s = 12.0; // midpoints and centroids of grid simplices are integers
  for (int mesh = 0; mesh < 3; ++mesh) {
    std::uniform_real_distribution<double> u01(0, 1);
    std::vector<char> kept(n * n * n);
    for (auto& k : kept) k = mesh == 0 ? 1 : (u01(rng) < 0.7);
    kept[0] = 1;
    const Mesh_tr tr = build(kuhn_grid(n, n, n, s, [&](int i, int j, int k) { return kept[(i * n + j) * n + k] != 0; }));
    const Mesh_walk walk(tr, Is_tet_mesh_domain_cell());
    // Special points: vertices, edge midpoints, facet and cell centroids of the
    // mesh simplices, and integer points inside and around the grid.
    std::vector<Mesh_tr::Point> pts;
    for (auto c : tr.finite_cell_handles()) {
      if (!c->info().in_domain()) continue;
      const Mesh_tr::Point* v[4] = {&c->vertex(0)->point(), &c->vertex(1)->point(), &c->vertex(2)->point(), &c->vertex(3)->point()};
      pts.push_back(*v[0]);
      for (int a = 0; a < 4; ++a)
        for (int b = a + 1; b < 4; ++b) pts.push_back(CGAL::midpoint(*v[a], *v[b]));
      for (int a = 0; a < 4; ++a) {
        double x = 0, y = 0, z = 0;
        for (int b = 0; b < 4; ++b)
          if (b != a) x += v[b]->x() / 3, y += v[b]->y() / 3, z += v[b]->z() / 3;
        pts.push_back(Mesh_tr::Point(std::round(x), std::round(y), std::round(z)));
      }
      pts.push_back(CGAL::centroid(*v[0], *v[1], *v[2], *v[3]));
    }
    std::uniform_int_distribution<int> coord(-6, int(n * s) + 6);
    for (int i = 0; i < 200; ++i) pts.push_back(Mesh_tr::Point(coord(rng), coord(rng), coord(rng)));
    std::uniform_int_distribution<std::size_t> pick(0, pts.size() - 1);
    const int segments = mesh == 0 ? 2500 : 1500;
    for (int i = 0; i < segments; ++i) {
      const Mesh_tr::Point q = pts[pick(rng)];
      Mesh_tr::Point p = pts[pick(rng)];
      if (i % 10 == 0) p = q;
      check_segment(tr, walk, q, p, i % 5 == 0);
    }
    // Segments along grid lines and face/cube diagonals, through many vertices.
    std::uniform_int_distribution<int> g(-1, n + 1);
    for (int i = 0; i < 500; ++i) {
      const int a[3] = {g(rng), g(rng), g(rng)};
      int d[3] = {g(rng) % 2, g(rng) % 2, g(rng) % 2};
      if (d[0] == 0 && d[1] == 0 && d[2] == 0) d[0] = 1;
      const int len = 1 + i % (n + 2);
      const Mesh_tr::Point q(a[0] * s, a[1] * s, a[2] * s), p((a[0] + len * d[0]) * s, (a[1] + len * d[1]) * s, (a[2] + len * d[2]) * s);
      check_segment(tr, walk, q, p, false);
    }
  }
}

TEST_CASE("segment walk: Delaunay of random points, against CGAL's traverser on generic segments", "[segment_walk]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  DT dt = random_delaunay(3000, rng, u);
  const Segment_walk_3<DT> walk(dt);
  std::size_t compared = 0;
  for (int i = 0; i < 1000; ++i) {
    const DT::Point q(u(rng), u(rng), u(rng));
    const DT::Point p = i % 3 == 0 ? DT::Point(2 * u(rng) - 0.5, 2 * u(rng) - 0.5, 2 * u(rng) - 0.5) : DT::Point(u(rng), u(rng), u(rng));
    std::vector<Segment_walk_piece_3<DT>> full;
    check_segment(dt, walk, q, p, i % 10 == 0, &full);
    // Random segments between points inside the hull are generic: CGAL's
    // traverser is reliable there, and must visit the same cells.
    DT::Locate_type lq, lp;
    int li, lj;
    dt.locate(q, lq, li, lj);
    dt.locate(p, lp, li, lj);
    if (lq != DT::CELL || lp != DT::CELL) continue;
    std::vector<DT::Cell_handle> ours, cgal;
    for (const auto& x : full)
      if (x.dimension == 3) ours.push_back(x.cell);
    for (DT::Cell_handle c : dt.segment_traverser_cell_handles(q, p)) cgal.push_back(c);
    CHECK(ours == cgal);
    ++compared;
  }
  CHECK(compared > 500);
  // Segments between vertices of the triangulation: degenerate at both ends.
  std::vector<DT::Vertex_handle> vs;
  for (auto v : dt.finite_vertex_handles()) vs.push_back(v);
  std::uniform_int_distribution<std::size_t> pick(0, vs.size() - 1);
  for (int i = 0; i < 300; ++i) check_segment(dt, walk, vs[pick(rng)]->point(), vs[pick(rng)]->point(), i % 10 == 0);
}

TEST_CASE("segment walk: Delaunay with an excluded pocket", "[segment_walk]") {
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> u(0, 1);
  DT dt = random_delaunay(2000, rng, u);
  // Domain: finite cells whose centroid is outside a ball: a cavity inside.
  const auto in_domain = [&dt](DT::Cell_handle c) {
    if (dt.is_infinite(c)) return false;
    const DT::Point g = CGAL::centroid(c->vertex(0)->point(), c->vertex(1)->point(), c->vertex(2)->point(), c->vertex(3)->point());
    return CGAL::squared_distance(g, DT::Point(0.5, 0.5, 0.5)) > 0.3 * 0.3;
  };
  using Walk = Segment_walk_3<DT, decltype(in_domain)>;
  const Walk walk(dt, in_domain);
  int with_gap = 0;
  for (int i = 0; i < 400; ++i) {
    const DT::Point q(u(rng), u(rng), 0.05 + 0.1 * u(rng)), p(u(rng), u(rng), 0.85 + 0.1 * u(rng));
    std::vector<Segment_walk_piece_3<DT>> full;
    check_segment(dt, walk, q, p, true, &full);
    for (const auto& x : full)
      if (x.dimension == -1) {
        ++with_gap;
        break;
      }
  }
  CHECK(with_gap > 50);

  // An empty domain: every segment is one gap, every point outside.
  const auto none = [](DT::Cell_handle) { return false; };
  const Segment_walk_3<DT, decltype(none)> empty(dt, none);
  std::vector<Segment_walk_piece_3<DT>> w;
  empty(DT::Point(0.2, 0.2, 0.2), DT::Point(0.8, 0.7, 0.6), std::back_inserter(w));
  REQUIRE(w.size() == 1);
  CHECK(w[0].dimension == -1);
  CHECK(w[0].t_in == 0.0);
  CHECK(w[0].t_out == 1.0);
  CHECK(empty.locate(DT::Point(0.5, 0.5, 0.5)).dimension == -1);
}

TEST_CASE("segment walk: hints, point locator, concurrent use of one walker", "[segment_walk]") {
  // A tunnel grid: the lazy structures (boundary AABB tree, vertex stars,
  // location grid) are built on first use, here by two threads at once.
  const auto keep = [](int i, int j, int k) { return !(j == 1 && k == 1 && i >= 1 && i <= 2) && !(i == 0 && j == 2); };
  const Mesh_tr tr = build(kuhn_grid(4, 3, 3, 12.0, keep));
  const Mesh_walk walk(tr, Is_tet_mesh_domain_cell());
  std::vector<Mesh_tr::Cell_handle> cells;
  for (auto c : tr.finite_cell_handles()) cells.push_back(c);
  std::vector<std::pair<Mesh_tr::Point, Mesh_tr::Point>> segs;
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> coord(-6, 54);
  for (int i = 0; i < 400; ++i)
    segs.push_back({Mesh_tr::Point(coord(rng), coord(rng), coord(rng)), Mesh_tr::Point(coord(rng), coord(rng), coord(rng))});
  using Out = std::vector<std::vector<Segment_walk_piece_3<Mesh_tr>>>;
  Out a(segs.size()), b(segs.size());
  auto run = [&](Out& out, int which) {
    for (std::size_t i = 0; i < segs.size(); ++i) {
      if (which == 0) walk(segs[i].first, segs[i].second, std::back_inserter(out[i]));
      else walk(segs[i].first, segs[i].second, std::back_inserter(out[i]), cells[(i * 7919) % cells.size()]);
    }
  };
  std::thread t1(run, std::ref(a), 0), t2(run, std::ref(b), 1);
  t1.join();
  t2.join();
  // The hint changes neither the simplices nor their order. It can change
  // the last bits of a parameter, as the walk may reach the first cell by
  // another path (a location from the hint or from the grid, the cell array
  // or the generic traversal), whose certified crossing formulas differ
  // (found under Clang: one segment of 400, t = 2/15 as 0.13333333333333336
  // and 0.1333333333333333). Each is within walk_crossing_tolerance of the
  // exact value, so two differ by at most twice that.
  std::size_t same = 0;
  for (std::size_t i = 0; i < segs.size(); ++i) {
    bool eq = a[i].size() == b[i].size();
    for (std::size_t k = 0; eq && k < a[i].size(); ++k)
      eq = a[i][k].dimension == b[i][k].dimension && vset(a[i][k]) == vset(b[i][k]) &&
           std::abs(a[i][k].t_in - b[i][k].t_in) <= 2 * internal::walk_crossing_tolerance &&
           std::abs(a[i][k].t_out - b[i][k].t_out) <= 2 * internal::walk_crossing_tolerance;
    same += eq;
    if (i % 20 == 0) check_segment(tr, walk, segs[i].first, segs[i].second);
  }
  CHECK(same == segs.size());

  const Point_locator_3<Mesh_tr, Is_tet_mesh_domain_cell> locate(tr, Is_tet_mesh_domain_cell());
  CHECK(locate(Mesh_tr::Point(0, 0, 0)).dimension == 0);
  CHECK(locate(Mesh_tr::Point(6, 0, 0)).dimension == 1);
  CHECK(locate(Mesh_tr::Point(18, 18, 18)).dimension == -1); // in the tunnel
  CHECK(locate(Mesh_tr::Point(6, 30, 18)).dimension == -1);  // in the removed column
  CHECK(locate(Mesh_tr::Point(9, 6, 3), cells.back()).dimension == 3);
  const auto l = locate(Mesh_tr::Point(8, 4, 0));
  REQUIRE(l.dimension == 2);
  CHECK(l.cell->info().in_domain());
}

// For every link of the cell array: the walk's table of vertex
// correspondences across a facet (internal::walk_facet_map, which assumes
// that neighbouring cells see their common facet in reverse cyclic order)
// maps each shared vertex of the neighbour to the same vertex of the cell.
// Returns the number of links checked.
template <class Array>
std::size_t check_facet_maps(const Array& a) {
  std::size_t links = 0;
  for (const auto& r : a.records)
    for (int k = 0; k < 4; ++k) {
      if (r.n[k] == a.outside) continue;
      const auto& rn = a.records[r.n[k] >> 2];
      const int m = int(r.n[k] & 3u);
      const auto& g = internal::walk_inner_facet(k);
      const std::int32_t id0 = rn.v[internal::walk_inner_facet(m)[0]];
      const int matches = int(r.v[g[0]] == id0) + int(r.v[g[1]] == id0) + int(r.v[g[2]] == id0);
      REQUIRE(matches == 1);
      const unsigned rho = unsigned(r.v[g[1]] == id0) + 2u * unsigned(r.v[g[2]] == id0);
      const unsigned map = internal::walk_facet_map[std::size_t((4 * k + m) * 3) + rho];
      CHECK(int((map >> (2 * m)) & 3u) == k);
      for (int i = 0; i < 4; ++i)
        if (i != m) CHECK(rn.v[i] == r.v[(map >> (2 * i)) & 3u]);
      ++links;
    }
  return links;
}

TEST_CASE("cell array of the walk: handle index and adjacency copy", "[segment_walk]") {
  // Handle_index on pointers into one buffer, visited in an order that
  // interleaves "blocks": a small block inside the gap between two others
  // (the case where merging runs across gaps must not hide elements), a
  // block far away, and free slots inside blocks.
  std::vector<int> buffer(10000);
  std::vector<int*> handles;
  for (int i = 0; i < 100; ++i)
    if (i % 7 != 3) handles.push_back(&buffer[i]);
  for (int i = 1000; i < 1100; ++i) handles.push_back(&buffer[i]);
  for (int i = 300; i < 310; ++i) handles.push_back(&buffer[i]);
  for (int i = 9000; i < 9050; ++i) handles.push_back(&buffer[i]);
  internal::Handle_index<int*> index;
  for (int* h : handles) index.push_back(h);
  index.finish();
  std::set<std::uint32_t> seen;
  for (int* h : handles) {
    const std::uint32_t i = index(h);
    REQUIRE(i != internal::Handle_index<int*>::none);
    CHECK(i < index.size());
    CHECK(seen.insert(i).second);
  }
  CHECK(index.number_of_runs() == 2); // [0, 1100) merged across gaps of < 1024 slots; [9000, 9050)
  CHECK(index(&buffer[5000]) == internal::Handle_index<int*>::none);
  CHECK(index(&buffer[9999]) == internal::Handle_index<int*>::none);
  {
    // Many runs of random lengths and gaps in a 16 MiB buffer, so that 64
    // KiB chunks hold several runs (with gaps on either side of the merge
    // limit) and runs span several chunks; pushed in shuffled blocks.
    // Every element gets its own slot; addresses far from every element,
    // ones between elements and ones out of the buffer get none. (8-byte
    // elements aligned to 1: an address between two is a valid pointer.)
    struct E {
      char bytes[8];
    };
    std::vector<E> big(std::size_t(1) << 21);
    std::mt19937_64 g(11);
    std::vector<std::pair<std::size_t, std::size_t>> blocks; // [begin, end) of big
    std::vector<std::uint8_t> member(big.size(), 0);
    for (std::size_t at = 0; at < big.size();) {
      const std::size_t len = std::size_t(1) + g() % (g() % 8 == 0 ? 20000 : 300);
      const std::size_t e = std::min(big.size(), at + len);
      blocks.push_back({at, e});
      for (std::size_t i = at; i < e; ++i) member[i] = 1;
      at = e + (g() % 3 == 0 ? 2000 + g() % 8000 : g() % 1100);
    }
    std::shuffle(blocks.begin(), blocks.end(), g);
    internal::Handle_index<E*> bi;
    std::size_t n_members = 0;
    for (const auto& b : blocks)
      for (std::size_t i = b.first; i < b.second; ++i, ++n_members) bi.push_back(&big[i]);
    bi.finish();
    CHECK(bi.number_of_runs() > 100);
    std::vector<std::uint8_t> slot_seen(bi.size(), 0);
    std::size_t unique = 0;
    for (std::size_t i = 0; i < big.size(); ++i) {
      if (!member[i]) continue;
      const std::uint32_t s = bi(&big[i]);
      REQUIRE(s < bi.size());
      unique += slot_seen[s] == 0;
      slot_seen[s] = 1;
    }
    CHECK(unique == n_members);
    // Slots follow addresses: consecutive elements of a run (merged across
    // gaps of at most 1024 slots) have consecutive slots, gap included;
    // across a larger gap they only increase, and the gap's ends get none.
    std::size_t prev = big.size(), wrong_slots = 0, wrong_gaps = 0, big_gaps = 0;
    for (std::size_t i = 0; i < big.size(); ++i) {
      if (!member[i]) continue;
      if (prev != big.size()) {
        const std::uint32_t a = bi(&big[prev]), b = bi(&big[i]);
        if (i - prev - 1 <= 1024) wrong_slots += b - a != i - prev;
        else {
          ++big_gaps;
          wrong_slots += !(b > a);
          wrong_gaps += bi(&big[prev + 1]) != internal::Handle_index<E*>::none;
          wrong_gaps += bi(&big[i - 1]) != internal::Handle_index<E*>::none;
        }
      }
      prev = i;
    }
    CHECK(big_gaps > 50);
    CHECK(wrong_slots == 0);
    CHECK(wrong_gaps == 0);
    // Distance of each element of big to the nearest member, capped.
    std::vector<std::size_t> dist(big.size(), big.size());
    for (std::size_t i = 0, last = big.size(); i < big.size(); ++i) {
      if (member[i]) last = i;
      if (last != big.size()) dist[i] = i - last;
    }
    for (std::size_t i = big.size(), last = big.size(); i-- > 0;) {
      if (member[i]) last = i;
      if (last != big.size()) dist[i] = std::min(dist[i], last - i);
    }
    std::size_t far = 0;
    for (std::size_t i = 0; i < big.size(); i += 97)
      if (dist[i] > 1100) {
        ++far;
        CHECK(bi(&big[i]) == internal::Handle_index<E*>::none);
      }
    CHECK(far > 100);
    auto misaligned = [&](std::size_t i) { return reinterpret_cast<E*>(big[i].bytes + 3); };
    for (std::size_t i = 0; i + 1 < big.size(); i += 1009) CHECK(bi(misaligned(i)) == internal::Handle_index<E*>::none);
    std::vector<E> other(1000);
    CHECK(bi(&other[500]) == internal::Handle_index<E*>::none);
    CHECK(internal::Handle_index<E*>()(&other[0]) == internal::Handle_index<E*>::none);
    internal::Handle_index<E*> empty_index;
    empty_index.finish();
    CHECK(empty_index.size() == 0);
    CHECK(empty_index(&other[0]) == internal::Handle_index<E*>::none);
    // Many more runs than the table's 512 chunks (one element every 1030):
    // the chunks stay at 64 KiB (two per run are allowed), and every
    // element is found.
    internal::Handle_index<E*> many;
    std::size_t n_many = 0;
    for (std::size_t i = 0; i < big.size(); i += 1030, ++n_many) many.push_back(&big[i]);
    many.finish();
    CHECK(many.number_of_runs() == n_many);
    CHECK(n_many > 2000);
    CHECK(many.chunk_bits() == 16);
    std::size_t found = 0;
    for (std::size_t i = 0; i < big.size(); i += 1030) found += many(&big[i]) == std::uint32_t(i / 1030);
    CHECK(found == n_many);
    CHECK(many(&big[1]) == internal::Handle_index<E*>::none);
  }

  // The copy of a Delaunay triangulation with an excluded pocket: records
  // reproduce vertices, neighbours and mirror indices; non-domain
  // neighbours are links to outside.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  DT dt = random_delaunay(3000, rng, u);
  const Outside_column in_domain{&dt};
  const internal::Walk_cell_array_3<DT> a(dt, in_domain);
  REQUIRE(a.valid());
  std::size_t n_domain = 0;
  for (DT::Cell_handle c : dt.finite_cell_handles()) {
    const std::uint32_t ci = a.index(c);
    if (!in_domain(c)) {
      CHECK(ci == a.outside);
      continue;
    }
    ++n_domain;
    REQUIRE(ci < a.records.size());
    CHECK(a.cell_handles[ci] == c);
    const auto& r = a.records[ci];
    for (int l = 0; l < 4; ++l) {
      CHECK(a.vertex_handle(r.v[l]) == c->vertex(l));
      const double* x = a.point(r.v[l]);
      CHECK((x[0] == c->vertex(l)->point().x() && x[1] == c->vertex(l)->point().y() && x[2] == c->vertex(l)->point().z()));
      const DT::Cell_handle n = c->neighbor(l);
      if (dt.is_infinite(n) || !in_domain(n)) {
        CHECK(r.n[l] == a.outside);
      } else {
        REQUIRE(r.n[l] != a.outside);
        CHECK(a.cell_handles[r.n[l] >> 2] == n);
        CHECK(int(r.n[l] & 3u) == n->index(c));
      }
    }
  }
  CHECK(a.records.size() == n_domain);
  CHECK(check_facet_maps(a) > 3 * n_domain);
  // The same on a mesh built from a tet list (re-oriented tets, grid with a tunnel).
  const Mesh_tr mt = build(kuhn_grid(4, 3, 3, 1.0, [](int i, int j, int) { return !(i == 1 && j == 1); }));
  const internal::Walk_cell_array_3<Mesh_tr> am(mt, Is_tet_mesh_domain_cell());
  REQUIRE(am.valid());
  CHECK(check_facet_maps(am) > 2 * am.records.size());
  for (DT::Cell_handle c : dt.all_cell_handles())
    if (dt.is_infinite(c)) CHECK(a.index(c) == a.outside);
  CHECK(a.index(DT::Cell_handle()) == a.outside);
}

TEST_CASE("cell array of the walk: the same with one thread and with all", "[segment_walk]") {
  // Its construction runs in parallel: the arrays must not depend on it.
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(0, 1);
  DT dt = random_delaunay(30000, rng, u);
  const Outside_column in_domain{&dt};
  auto build_with = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
    return std::make_unique<internal::Walk_cell_array_3<DT>>(dt, in_domain);
  };
  const auto one = build_with(1);
  const auto all = build_with(8);
  REQUIRE(one->valid());
  REQUIRE(one->records.size() == all->records.size());
  REQUIRE(one->vertices.size() == all->vertices.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < one->records.size(); ++i) {
    const auto &a = one->records[i], &b = all->records[i];
    for (int l = 0; l < 4; ++l) differ += a.v[l] != b.v[l] || a.n[l] != b.n[l];
    differ += one->cell_handles[i] != all->cell_handles[i];
  }
  for (std::size_t i = 0; i < one->vertices.size(); ++i) differ += one->vertices[i].handle != all->vertices[i].handle;
  for (DT::Cell_handle c : dt.all_cell_handles()) differ += one->index(c) != all->index(c);
  CHECK(differ == 0);
}

TEST_CASE("cell array of the walk: its huge-page allocator", "[segment_walk]") {
  using A = internal::Huge_page_allocator<std::uint64_t>;
  constexpr std::size_t huge = A::huge_page;
  A alloc;
  // Below 2 MiB: plain storage; from 2 MiB: 2 MiB aligned.
  std::uint64_t* small = alloc.allocate(100);
  std::uint64_t* large = alloc.allocate(huge / 8 + 1);
  CHECK(reinterpret_cast<std::uintptr_t>(large) % huge == 0);
  for (std::size_t i = 0; i < huge / 8 + 1; ++i) large[i] = i * 3;
  for (std::size_t i = 0; i < 100; ++i) small[i] = i;
  std::size_t wrong = 0;
  for (std::size_t i = 0; i < huge / 8 + 1; ++i) wrong += large[i] != i * 3;
  CHECK(wrong == 0);
  alloc.deallocate(small, 100);
  alloc.deallocate(large, huge / 8 + 1);
  // A vector growing across the threshold keeps its elements; copies and
  // rebinds compare equal (the allocator is stateless).
  std::vector<std::uint32_t, internal::Huge_page_allocator<std::uint32_t>> v;
  for (std::uint32_t i = 0; i < 3000000; ++i) v.push_back(i ^ 0x5a5a5a5au);
  wrong = 0;
  for (std::uint32_t i = 0; i < 3000000; ++i) wrong += v[i] != (i ^ 0x5a5a5a5au);
  CHECK(wrong == 0);
  CHECK(reinterpret_cast<std::uintptr_t>(v.data()) % huge == 0);
  CHECK(internal::Huge_page_allocator<char>(alloc) == alloc);
  CHECK_THROWS_AS(alloc.allocate(std::size_t(-1) / 4), std::bad_alloc);
  CHECK_THROWS_AS(alloc.allocate(std::size_t(-1) / 8), std::bad_alloc); // n * 8 fits, its rounding up would not
  // Over-aligned elements (as the cell array's records) keep their
  // alignment below 2 MiB too.
  struct alignas(64) Wide {
    double x[8];
  };
  internal::Huge_page_allocator<Wide> wide;
  std::size_t misaligned_blocks = 0;
  for (std::size_t n : {std::size_t(1), std::size_t(10000), std::size_t(20000)}) {
    Wide* w = wide.allocate(n);
    misaligned_blocks += reinterpret_cast<std::uintptr_t>(w) % alignof(Wide) != 0;
    wide.deallocate(w, n);
  }
  CHECK(misaligned_blocks == 0);
}

TEST_CASE("segment walk: tiny segments keep their parameters", "[segment_walk]") {
  // A Kuhn cube (six tets around the diagonal from (0,0,0) to (1,1,1)); a
  // segment across the diagonal near the corner (0,0,0), at scales from 1e-3
  // down to 1e-110: below 1e-50 the walk leaves its cell array (products of
  // its step would underflow), and a parameter computed as n.(a - q) / n.D
  // from a far vertex a would lose q's offset entirely. The facets around the diagonal and the cube's faces at that
  // corner are planes through the origin, so scaling about it changes
  // neither the simplices met nor their parameters.
  const Mesh_tr tr = build(kuhn_grid(1, 1, 1, 1.0));
  const Mesh_walk walk(tr, Is_tet_mesh_domain_cell());
  auto run = [&](double s, bool fast) {
    const Mesh_tr::Point q(s * 11.0, s * 9.1, s * 10.35), p(s * 8.9, s * 10.8, s * 9.75);
    std::vector<Segment_walk_piece_3<Mesh_tr>> w;
    const Mesh_tr::Cell_handle hint = walk.locate(q).cell;
    if (fast) walk.fast(q, p, std::back_inserter(w), hint);
    else walk(q, p, std::back_inserter(w), hint);
    return w;
  };
  for (bool fast : {true, false}) {
    const auto ref = run(1e-3, fast);
    REQUIRE(ref.size() >= (fast ? 3u : 5u)); // at least three tets
    for (double s : {1e-30, 1e-45, 1e-52, 1e-80, 1e-110}) {
      const auto w = run(s, fast);
      INFO("scale " << s << (fast ? ", fast" : ", full"));
      REQUIRE(w.size() == ref.size());
      for (std::size_t i = 0; i < w.size(); ++i) {
        CHECK(w[i].dimension == ref[i].dimension);
        CHECK(w[i].t_in == Approx(ref[i].t_in).margin(1e-9));
        CHECK(w[i].t_out == Approx(ref[i].t_out).margin(1e-9));
      }
    }
  }
}

// Walks the queries in one batch per mode and compares each query's pieces
// with those of single calls, bit for bit. Returns the number of queries
// whose pieces differ; counts the pieces and tells whether the queries'
// outputs interleaved.
template <class Walk, class Query>
std::size_t batch_differences(const Walk& walk, const std::vector<Query>& queries, std::size_t* pieces = nullptr,
                              bool* interleaved = nullptr) {
  using Piece = typename Walk::Piece;
  std::size_t differ = 0;
  for (const bool fast : {false, true}) {
    std::vector<std::vector<Piece>> got(queries.size());
    std::vector<std::size_t> first_call;
    auto keep = [&](std::size_t i, const Piece& x) {
      if (got.at(i).empty()) first_call.push_back(i);
      got[i].push_back(x);
    };
    if (fast) walk.fast_batch(queries, keep);
    else walk.batch(queries, keep);
    if (interleaved && fast) *interleaved = !std::is_sorted(first_call.begin(), first_call.end());
    for (std::size_t i = 0; i < queries.size(); ++i) {
      std::vector<Piece> one;
      if (fast) walk.fast(queries[i].q, queries[i].p, std::back_inserter(one), queries[i].hint);
      else walk(queries[i].q, queries[i].p, std::back_inserter(one), queries[i].hint);
      if (pieces) *pieces += one.size();
      differ += one.empty() || !identical_pieces(one, got[i]);
    }
  }
  return differ;
}

// A domain with a pocket of excluded cells: finite non-domain hints.
struct Outside_pocket {
  const DT* dt;
  bool operator()(DT::Cell_handle c) const {
    const auto g = CGAL::centroid(dt->tetrahedron(c));
    return !(g.x() < 0.4 && g.y() < 0.4 && g.z() < 0.4);
  }
};

TEST_CASE("segment walk: batches give the per-segment pieces", "[segment_walk]") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  DT dt = random_delaunay(20000, rng, u);
  const Segment_walk_3<DT> walk(dt);
  using Query = Segment_walk_3<DT>::Query;
  using Piece = Segment_walk_piece_3<DT>;
  std::vector<DT::Vertex_handle> vs;
  for (auto v : dt.finite_vertex_handles()) vs.push_back(v);
  std::uniform_int_distribution<std::size_t> pick(0, vs.size() - 1);
  std::vector<DT::Cell_handle> infinite_cells;
  for (auto c : dt.all_cell_handles())
    if (dt.is_infinite(c)) infinite_cells.push_back(c);
  // Generic, short, leaving the hull, q == p, vertex to vertex; hints
  // located, null, infinite, or arbitrary domain cells.
  std::vector<Query> queries;
  for (int i = 0; i < 3000; ++i) {
    const DT::Point q(u(rng), u(rng), u(rng));
    DT::Point p;
    switch (i % 6) {
    case 0: p = DT::Point(u(rng), u(rng), u(rng)); break;
    case 1: p = DT::Point(q.x() + 0.02 * (u(rng) - 0.5), q.y() + 0.02 * (u(rng) - 0.5), q.z() + 0.02 * (u(rng) - 0.5)); break;
    case 2: p = DT::Point(3 * u(rng) - 1, 3 * u(rng) - 1, 3 * u(rng) - 1); break;
    case 3: p = q; break;
    default: p = vs[pick(rng)]->point();
    }
    const DT::Point qq = i % 6 == 4 ? vs[pick(rng)]->point() : q;
    DT::Cell_handle hint = dt.locate(qq);
    if (i % 8 == 3) hint = DT::Cell_handle();
    if (i % 8 == 5) hint = infinite_cells[std::size_t(i) % infinite_cells.size()];
    if (i % 8 == 7) hint = vs[pick(rng)]->cell();
    queries.push_back({qq, p, hint});
  }
  std::size_t pieces = 0;
  bool interleaved = false;
  CHECK(batch_differences(walk, queries, &pieces, &interleaved) == 0);
  CHECK(pieces > 20 * queries.size());
  CHECK(interleaved); // the batch is not a loop over the queries
  // Fewer queries than lanes, and around multiples of the 8 lanes.
  for (std::size_t n : {0, 1, 2, 7, 8, 9, 15, 16, 17, 33}) {
    INFO("batch of " << n);
    CHECK(batch_differences(walk, std::vector<Query>(queries.begin() + 100, queries.begin() + 100 + std::ptrdiff_t(n))) == 0);
  }
  // A domain with a pocket: hints in the pocket are finite cells outside the domain.
  const Outside_pocket pocket{&dt};
  const Segment_walk_3<DT, Outside_pocket> pocket_walk(dt, pocket);
  std::vector<Query> pocket_queries(queries.begin(), queries.begin() + 1000);
  std::size_t pocket_hints = 0;
  for (Query& x : pocket_queries)
    if (x.hint != DT::Cell_handle() && !dt.is_infinite(x.hint) && !pocket(x.hint)) ++pocket_hints;
  CHECK(pocket_hints > 20);
  CHECK(batch_differences(pocket_walk, pocket_queries) == 0);

  // A callback that throws ends the call; the walker stays usable.
  std::size_t calls = 0;
  struct Stop {};
  CHECK_THROWS_AS(walk.fast_batch(queries,
                                  [&](std::size_t, const Piece&) {
                                    if (++calls == 500) throw Stop();
                                  }),
                  Stop);
  CHECK(calls == 500);
  CHECK(batch_differences(walk, std::vector<Query>(queries.begin(), queries.begin() + 200)) == 0);

  // A non-finite point is reported, with its query, before any output.
  std::vector<Query> bad(queries.begin(), queries.begin() + 100);
  bad[97].p = DT::Point(0.5, std::numeric_limits<double>::quiet_NaN(), 0.5);
  calls = 0;
  for (const bool fast : {false, true}) {
    try {
      if (fast) walk.fast_batch(bad, [&](std::size_t, const Piece&) { ++calls; });
      else walk.batch(bad, [&](std::size_t, const Piece&) { ++calls; });
      FAIL("no exception");
    } catch (const std::invalid_argument& e) {
      CHECK(std::string(e.what()).find("query 97") != std::string::npos);
    }
  }
  CHECK(calls == 0);
}
