// The segment walk against an independent exact brute force, on meshes and
// segments built to be degenerate; and the brute force itself against
// hand-computed answers and CGAL's exact predicates.
#include "reference/Exact_simplex_reference_3.h"
#include "reference/degenerate_test_meshes.h"
#include "walk_test_meshes.h"

#include <CGAL_ext/Point_locator_3.h>
#include <CGAL_ext/Segment_walk_3.h>
#include <CGAL_ext/Tet_mesh_triangulation_3.h>
#include <CGAL_ext/build_triangulation_from_tets.h>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <cstdio>
#include <iterator>
#include <sstream>

using namespace CGAL_ext;
using namespace CGAL_ext::testing;
using Tr = Tet_mesh_triangulation_3<>;
using Q = Exact_rational;
using P3 = std::array<double, 3>;

namespace {

struct Vertex_info_id {
  std::size_t operator()(Tr::Vertex_handle v) const { return v->info(); }
};
using Reference = Exact_simplex_reference_3<Tr, Is_tet_mesh_domain_cell, Vertex_info_id>;

void build(const Test_mesh& m, Tr& tr) { build_triangulation_from_tets(m.points, m.tets, {}, tr); }

std::vector<Reference_piece> ref_of(const Tr& tr, const P3& q, const P3& p) {
  return Reference(tr, Is_tet_mesh_domain_cell(), Vertex_info_id())(q, p);
}

Reference_piece piece(int dim, std::vector<std::size_t> ids, Q a, Q b) { return {dim, std::move(ids), a, b}; }

void check_same(const std::vector<Reference_piece>& got, const std::vector<Reference_piece>& expected) {
  INFO("got:\n" << to_string(got) << "expected:\n" << to_string(expected));
  REQUIRE(got.size() == expected.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    CHECK(got[i].dimension == expected[i].dimension);
    CHECK(got[i].vertices == expected[i].vertices);
    CHECK(got[i].t_in == expected[i].t_in);
    CHECK(got[i].t_out == expected[i].t_out);
  }
}

std::string fmt(const P3& a) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "(%.17g, %.17g, %.17g)", a[0], a[1], a[2]);
  return buf;
}

// --- Independent check of the reference with CGAL's exact predicates ------

using EK = CGAL::Simple_cartesian<Q>;

EK::Point_3 ek_point(const Tr::Point& p) { return {Q(p.x()), Q(p.y()), Q(p.z())}; }

// Whether x lies in the relative interior of the simplex of the given mesh vertices.
bool in_relative_interior(const std::vector<EK::Point_3>& v, const EK::Point_3& x) {
  switch (v.size()) {
  case 1: return x == v[0];
  case 2: return EK::Segment_3(v[0], v[1]).has_on(x) && x != v[0] && x != v[1];
  case 3:
    if (!EK::Triangle_3(v[0], v[1], v[2]).has_on(x)) return false;
    for (int i = 0; i < 3; ++i)
      if (EK::Segment_3(v[i], v[(i + 1) % 3]).has_on(x)) return false;
    return true;
  default: return EK::Tetrahedron_3(v[0], v[1], v[2], v[3]).has_on_bounded_side(x);
  }
}

// Every piece's representative point (the point of a zero-length piece, the
// midpoint otherwise) lies in the relative interior of its simplex, and a
// gap's in no closed domain cell.
void check_with_predicates(const Tr& tr, const std::vector<Tr::Vertex_handle>& vh, const P3& q, const P3& p,
                           const std::vector<Reference_piece>& ref) {
  const EK::Point_3 eq{Q{q[0]}, Q{q[1]}, Q{q[2]}}, ep{Q{p[0]}, Q{p[1]}, Q{p[2]}};
  for (const auto& r : ref) {
    const Q t = (r.t_in + r.t_out) / Q(2);
    const EK::Point_3 x = eq + (ep - eq) * t;
    INFO("segment " << fmt(q) << " -> " << fmt(p) << "\n" << to_string(ref) << "piece at t = " << t);
    if (r.dimension < 0) {
      for (auto c : tr.finite_cell_handles())
        CHECK(EK::Tetrahedron_3(ek_point(c->vertex(0)->point()), ek_point(c->vertex(1)->point()),
                                ek_point(c->vertex(2)->point()), ek_point(c->vertex(3)->point()))
                  .has_on_unbounded_side(x));
    } else {
      std::vector<EK::Point_3> v;
      for (auto id : r.vertices) v.push_back(ek_point(vh[id]->point()));
      CHECK(in_relative_interior(v, x));
    }
  }
}

// --- Walk against reference ------------------------------------------------

// Generic over the triangulation, its domain predicate and vertex ids, so
// that a CGAL Delaunay triangulation with `Is_finite_cell` is covered too.
template <class T, class Id>
std::string to_string(const std::vector<Segment_walk_piece_3<T>>& w, const Id& id) {
  std::ostringstream os;
  for (const auto& x : w) {
    std::vector<std::size_t> ids;
    for (int i = 0; i <= x.dimension; ++i) ids.push_back(id(x.vertices[i]));
    std::sort(ids.begin(), ids.end());
    char buf[96];
    std::snprintf(buf, sizeof buf, "[%.17g, %.17g]", x.t_in, x.t_out);
    os << "  dim " << x.dimension << " {";
    for (std::size_t i = 0; i < ids.size(); ++i) os << (i ? "," : "") << ids[i];
    os << "} " << buf << (x.cell == typename T::Cell_handle() ? " no cell" : " cell") << "\n";
  }
  return os.str();
}

// Empty if the walk's pieces match the reference's.
template <class T, class Pred, class Id>
std::string mismatch(const std::vector<Segment_walk_piece_3<T>>& w, const std::vector<Reference_piece>& ref, double tol,
                     const Pred& in_domain, const Id& id) {
  if (w.size() != ref.size()) return "different number of pieces";
  for (std::size_t i = 0; i < w.size(); ++i) {
    const auto& x = w[i];
    const std::string at = "piece " + std::to_string(i) + ": ";
    if (x.dimension != ref[i].dimension) return at + "dimension";
    std::vector<std::size_t> ids;
    for (int k = 0; k <= x.dimension; ++k) {
      if (x.vertices[k] == typename T::Vertex_handle()) return at + "null vertex";
      ids.push_back(id(x.vertices[k]));
    }
    std::sort(ids.begin(), ids.end());
    if (ids != ref[i].vertices) return at + "vertices";
    if (!(std::abs(x.t_in - CGAL::to_double(ref[i].t_in)) <= tol)) return at + "t_in";
    if (!(std::abs(x.t_out - CGAL::to_double(ref[i].t_out)) <= tol)) return at + "t_out";
    // (Only pieces starting within a few ulps of 1 cannot all be separated in double.)
    if (ref[i].t_in != ref[i].t_out && !(x.t_in < x.t_out) && ref[i].t_in < Q(1) - Q(std::ldexp(1.0, -48)))
      return at + "positive length reported as zero";
    if (x.dimension < 0) {
      if (x.cell != typename T::Cell_handle()) return at + "a gap with a cell";
    } else {
      if (x.cell == typename T::Cell_handle() || !in_domain(x.cell)) return at + "cell not in the domain";
      for (int k = 0; k <= x.dimension; ++k)
        if (!x.cell->has_vertex(x.vertices[k])) return at + "cell not incident to the simplex";
    }
  }
  return {};
}

struct Family_result {
  std::size_t segments = 0, full_disagreements = 0, fast_disagreements = 0, reference_failures = 0;
  // the batch walks, against the reference and against the per-segment walks
  std::size_t batch_disagreements = 0, batch_not_identical = 0;
};

// Runs both modes of the walk on every segment and compares with the
// reference; then walks all the segments again in one batch per mode, and
// compares each query's pieces with the reference and with the per-segment
// walk (which they must equal bit for bit).
template <class T, class Pred, class Id>
void compare_walk(const std::string& name, const T& tr, const Pred& in_domain, const Id& id,
                  const std::vector<Test_segment>& segs, Family_result& res, int max_prints = 4) {
  using Cell_handle = typename T::Cell_handle;
  using Point = typename T::Point;
  const Exact_simplex_reference_3<T, Pred, Id> ref(tr, in_domain, id);
  const Segment_walk_3<T, Pred> walk(tr, in_domain);
  const double tol = 1e-12;
  std::vector<Cell_handle> domain_cells;
  for (auto c : tr.finite_cell_handles())
    if (in_domain(c)) domain_cells.push_back(c);
  int printed = 0;
  using Piece = Segment_walk_piece_3<T>;
  std::vector<typename Segment_walk_3<T, Pred>::Query> queries;
  std::vector<std::vector<Reference_piece>> expected_of[2]; // full, fast
  std::vector<std::vector<Piece>> single_of[2];
  std::vector<bool> has_reference;
  for (std::size_t si = 0; si < segs.size(); ++si) {
    const auto& s = segs[si];
    // One query in three passes a hint cell, arbitrary but deterministic; one
    // in three the domain cell found by locate(q), which sends q strictly
    // inside a cell through the walk's fast start in its cell array (and q on
    // a face through its refusal of that start).
    Cell_handle hint;
    if (si % 3 == 1) hint = domain_cells[(si * 7919) % domain_cells.size()];
    if (si % 3 == 2) hint = walk.locate(Point(s.q[0], s.q[1], s.q[2])).cell;
    ++res.segments;
    queries.push_back({Point(s.q[0], s.q[1], s.q[2]), Point(s.p[0], s.p[1], s.p[2]), hint});
    for (int mode = 0; mode < 2; ++mode) {
      expected_of[mode].emplace_back();
      single_of[mode].emplace_back();
    }
    has_reference.push_back(false);
    std::vector<Reference_piece> expected;
    try {
      expected = ref(s.q, s.p);
    } catch (const std::exception& e) {
      ++res.reference_failures;
      std::printf("REFERENCE FAILURE on %s, segment [%s] %s -> %s: %s\n", name.c_str(), s.kind.c_str(), fmt(s.q).c_str(),
                  fmt(s.p).c_str(), e.what());
      continue;
    }
    std::vector<Reference_piece> expected_fast;
    for (const auto& r : expected)
      if (r.t_in != r.t_out || s.q == s.p) expected_fast.push_back(r);

    has_reference.back() = true;
    expected_of[0].back() = expected;
    expected_of[1].back() = expected_fast;

    auto run = [&](bool fast, const std::vector<Reference_piece>& exp, std::size_t& counter) {
      std::vector<Piece>& got = single_of[fast].back();
      std::string why;
      try {
        const Point q(s.q[0], s.q[1], s.q[2]), p(s.p[0], s.p[1], s.p[2]);
        if (hint == Cell_handle()) {
          if (fast) walk.fast(q, p, std::back_inserter(got));
          else walk(q, p, std::back_inserter(got));
        } else {
          if (fast) walk.fast(q, p, std::back_inserter(got), hint);
          else walk(q, p, std::back_inserter(got), hint);
        }
        why = mismatch(got, exp, tol, in_domain, id);
      } catch (const std::exception& e) {
        why = std::string("exception: ") + e.what();
      }
      if (why.empty()) return;
      ++counter;
      if (printed++ < max_prints)
        std::printf("DISAGREEMENT (%s mode%s) on %s, segment [%s]\n  q = %s\n  p = %s\n  %s\nwalk:\n%sreference:\n%s\n",
                    fast ? "fast" : "full", hint == Cell_handle() ? "" : ", with hint", name.c_str(), s.kind.c_str(),
                    fmt(s.q).c_str(), fmt(s.p).c_str(), why.c_str(), to_string(got, id).c_str(), to_string(exp).c_str());
    };
    run(false, expected, res.full_disagreements);
    run(true, expected_fast, res.fast_disagreements);
  }

  for (const bool fast : {false, true}) {
    std::vector<std::vector<Piece>> got(queries.size());
    std::string failure;
    try {
      auto keep = [&](std::size_t i, const Piece& x) { got.at(i).push_back(x); };
      if (fast) walk.fast_batch(queries, keep);
      else walk.batch(queries, keep);
    } catch (const std::exception& e) {
      failure = e.what();
    }
    if (!failure.empty()) {
      res.batch_disagreements += queries.size();
      std::printf("BATCH (%s) EXCEPTION on %s: %s\n", fast ? "fast" : "full", name.c_str(), failure.c_str());
      continue;
    }
    for (std::size_t i = 0; i < queries.size(); ++i) {
      if (!has_reference[i]) continue;
      const std::string why = mismatch(got[i], expected_of[fast][i], tol, in_domain, id);
      if (!why.empty()) {
        ++res.batch_disagreements;
        if (printed++ < max_prints)
          std::printf("BATCH DISAGREEMENT (%s) on %s, segment [%s]\n  q = %s\n  p = %s\n  %s\n", fast ? "fast" : "full",
                      name.c_str(), segs[i].kind.c_str(), fmt(segs[i].q).c_str(), fmt(segs[i].p).c_str(), why.c_str());
      }
      if (!testing::identical_pieces(got[i], single_of[fast][i])) ++res.batch_not_identical;
    }
  }
}

void compare_on(const Test_mesh& m, const std::vector<Test_segment>& segs, Family_result& res, int max_prints = 4) {
  Tr tr;
  build(m, tr);
  compare_walk(m.name, tr, Is_tet_mesh_domain_cell(), Vertex_info_id(), segs, res, max_prints);
}

void report(const std::string& family, const Family_result& r) {
  std::printf("%-22s segments %6zu  full disagreements %5zu  fast disagreements %5zu  batch disagreements %5zu  "
              "batch not identical %5zu  reference failures %zu\n",
              family.c_str(), r.segments, r.full_disagreements, r.fast_disagreements, r.batch_disagreements,
              r.batch_not_identical, r.reference_failures);
  CHECK(r.reference_failures == 0);
  CHECK(r.full_disagreements == 0);
  CHECK(r.fast_disagreements == 0);
  CHECK(r.batch_disagreements == 0);
  CHECK(r.batch_not_identical == 0);
}

Test_mesh single_tet() {
  return {"single_tet", {{0, 0, 0}, {6, 0, 0}, {0, 6, 0}, {0, 0, 6}}, {{0, 1, 2, 3}}};
}

// The location of x by brute force, independent of Point_locator_3: every
// domain cell whose bounding box holds x (a comparison of doubles, exact) is
// tested with orientations in exact rational arithmetic. All the cells that
// contain x must agree on the simplex; dimension -1 if none contains it.
Reference_piece exact_location(const Tr& tr, const P3& x) {
  const EK::Point_3 ex{Q{x[0]}, Q{x[1]}, Q{x[2]}};
  Reference_piece r{-1, {}, Q(0), Q(0)};
  bool found = false;
  for (auto c : tr.finite_cell_handles()) {
    if (!c->info().in_domain()) continue;
    bool in_box = true;
    for (int d = 0; d < 3 && in_box; ++d) {
      double lo = c->vertex(0)->point()[d], hi = lo;
      for (int i = 1; i < 4; ++i) lo = std::min(lo, c->vertex(i)->point()[d]), hi = std::max(hi, c->vertex(i)->point()[d]);
      in_box = lo <= x[d] && x[d] <= hi;
    }
    if (!in_box) continue;
    std::array<EK::Point_3, 4> v;
    for (int i = 0; i < 4; ++i) v[i] = ek_point(c->vertex(i)->point());
    std::vector<std::size_t> ids;
    bool inside = true;
    for (int i = 0; i < 4 && inside; ++i) {
      std::array<EK::Point_3, 4> w = v;
      w[i] = ex;
      const CGAL::Orientation o = CGAL::orientation(w[0], w[1], w[2], w[3]);
      inside = o != CGAL::NEGATIVE;
      if (o == CGAL::POSITIVE) ids.push_back(c->vertex(i)->info());
    }
    if (!inside) continue;
    std::sort(ids.begin(), ids.end());
    if (found) REQUIRE(ids == r.vertices); // the simplex does not depend on the cell
    r.dimension = int(ids.size()) - 1;
    r.vertices = ids;
    found = true;
  }
  return r;
}

} // namespace

// --- The reference on hand-computed cases -----------------------------------

TEST_CASE("reference: single tetrahedron", "[reference]") {
  Tr tr;
  build(single_tet(), tr);
  const Q h(1, 2), z(0), o(1);
  SECTION("from inside out through a facet") {
    check_same(ref_of(tr, {1, 1, 1}, {1, 1, -5}),
               {piece(3, {0, 1, 2, 3}, z, Q(1, 6)), piece(2, {0, 1, 2}, Q(1, 6), Q(1, 6)), piece(-1, {}, Q(1, 6), o)});
  }
  SECTION("through a vertex and out through the opposite facet") {
    check_same(ref_of(tr, {-3, -3, -3}, {3, 3, 3}),
               {piece(-1, {}, z, h), piece(0, {0}, h, h), piece(3, {0, 1, 2, 3}, h, Q(5, 6)),
                piece(2, {1, 2, 3}, Q(5, 6), Q(5, 6)), piece(-1, {}, Q(5, 6), o)});
  }
  SECTION("along an edge, beyond both ends") {
    check_same(ref_of(tr, {-6, 0, 0}, {12, 0, 0}),
               {piece(-1, {}, z, Q(1, 3)), piece(0, {0}, Q(1, 3), Q(1, 3)), piece(1, {0, 1}, Q(1, 3), Q(2, 3)),
                piece(0, {1}, Q(2, 3), Q(2, 3)), piece(-1, {}, Q(2, 3), o)});
  }
  SECTION("from a vertex along an edge to the other vertex") {
    check_same(ref_of(tr, {0, 0, 0}, {0, 6, 0}),
               {piece(0, {0}, z, z), piece(1, {0, 2}, z, o), piece(0, {2}, o, o)});
  }
  SECTION("inside a facet, entering through an edge") {
    check_same(ref_of(tr, {-2, 1, 0}, {4, 1, 0}),
               {piece(-1, {}, z, Q(1, 3)), piece(1, {0, 2}, Q(1, 3), Q(1, 3)), piece(2, {0, 1, 2}, Q(1, 3), o)});
  }
  SECTION("across a facet through its interior vertex-free part, from outside to outside") {
    // Line x = 1, z = 1 crosses the tet for y in (0, 4).
    check_same(ref_of(tr, {1, -2, 1}, {1, 6, 1}),
               {piece(-1, {}, z, Q(1, 4)), piece(2, {0, 1, 3}, Q(1, 4), Q(1, 4)), piece(3, {0, 1, 2, 3}, Q(1, 4), Q(3, 4)),
                piece(2, {1, 2, 3}, Q(3, 4), Q(3, 4)), piece(-1, {}, Q(3, 4), o)});
  }
  SECTION("touching a vertex from outside") {
    check_same(ref_of(tr, {6, 0, -1}, {6, 0, 1}), {piece(-1, {}, z, h), piece(0, {1}, h, h), piece(-1, {}, h, o)});
  }
  SECTION("starting on a boundary vertex, leaving the domain") {
    check_same(ref_of(tr, {6, 0, 0}, {7, 0, 0}), {piece(0, {1}, z, z), piece(-1, {}, z, o)});
  }
  SECTION("q == p") {
    check_same(ref_of(tr, {1, 1, 1}, {1, 1, 1}), {piece(3, {0, 1, 2, 3}, z, o)});
    check_same(ref_of(tr, {0, 0, 0}, {0, 0, 0}), {piece(0, {0}, z, o)});
    check_same(ref_of(tr, {3, 0, 0}, {3, 0, 0}), {piece(1, {0, 1}, z, o)});
    check_same(ref_of(tr, {2, 2, 2}, {2, 2, 2}), {piece(2, {1, 2, 3}, z, o)});
    check_same(ref_of(tr, {7, 7, 7}, {7, 7, 7}), {piece(-1, {}, z, o)});
  }
  SECTION("fully outside") {
    check_same(ref_of(tr, {10, 10, 10}, {20, 0, 0}), {piece(-1, {}, z, o)});
    check_same(ref_of(tr, {-1, 7, 0}, {7, 7, 0}), {piece(-1, {}, z, o)}); // in the facet plane, missing the facet
  }
}

TEST_CASE("reference: one Kuhn cube, along the diagonal shared by its 6 tetrahedra", "[reference]") {
  Tr tr;
  const Test_mesh m = kuhn_grid(1, 1, 1);
  REQUIRE(m.tets.size() == 6);
  build(m, tr);
  const Reference ref(tr, Is_tet_mesh_domain_cell(), Vertex_info_id());
  CHECK(ref.number_of_simplices(0) == 8);
  CHECK(ref.number_of_simplices(1) == 19); // 12 cube edges, 6 face diagonals, 1 main diagonal
  CHECK(ref.number_of_simplices(2) == 18); // 12 on the faces, 6 inside
  CHECK(ref.number_of_simplices(3) == 6);
  // Vertex (i, j, k) has id i + 2 j + 4 k.
  check_same(ref({-3, -3, -3}, {9, 9, 9}), {piece(-1, {}, Q(0), Q(1, 4)), piece(0, {0}, Q(1, 4), Q(1, 4)),
                                             piece(1, {0, 7}, Q(1, 4), Q(3, 4)), piece(0, {7}, Q(3, 4), Q(3, 4)),
                                             piece(-1, {}, Q(3, 4), Q(1))});
  // Across the inner facet {0, 1, 7} between the tets {0,1,3,7} and {0,1,5,7}: y = z.
  check_same(ref({4, 2, 1}, {4, 1, 2}), {piece(3, {0, 1, 3, 7}, Q(0), Q(1, 2)), piece(2, {0, 1, 7}, Q(1, 2), Q(1, 2)),
                                         piece(3, {0, 1, 5, 7}, Q(1, 2), Q(1))});
  // Inside the boundary face z = 0, across its diagonal {0, 3}.
  check_same(ref({4, 1, 0}, {1, 4, 0}), {piece(2, {0, 1, 3}, Q(0), Q(1, 2)), piece(1, {0, 3}, Q(1, 2), Q(1, 2)),
                                         piece(2, {0, 2, 3}, Q(1, 2), Q(1))});
  // From the center of the face x = 0, (0, 3, 3) on its diagonal {0, 6}, across the cube to (6, 3, 3) on {1, 7}.
  check_same(ref({0, 3, 3}, {6, 3, 3}), {piece(1, {0, 6}, Q(0), Q(0)), piece(2, {0, 6, 7}, Q(0), Q(1, 2)),
                                         piece(1, {0, 7}, Q(1, 2), Q(1, 2)), piece(2, {0, 1, 7}, Q(1, 2), Q(1)),
                                         piece(1, {1, 7}, Q(1), Q(1))});
}

TEST_CASE("reference: reversal symmetry and agreement with CGAL predicates", "[reference]") {
  for (const Test_mesh& m : {single_tet(), kuhn_grid(2, 2, 2), jittered_kuhn_grid(2, 7), l_shape_grid(2), tunnel_grid(3),
                             edge_touching_blocks(1), checkerboard_blocks(), delaunay_cospherical({25})}) {
    Tr tr;
    std::vector<Tr::Vertex_handle> vh;
    build_triangulation_from_tets(m.points, m.tets, {}, tr, {}, &vh);
    const Reference ref(tr, Is_tet_mesh_domain_cell(), Vertex_info_id());
    INFO("mesh " << m.name);
    for (const auto& s : degenerate_segments(m, 150, 11)) {
      const auto fw = ref(s.q, s.p), bw = ref(s.p, s.q);
      INFO("segment [" << s.kind << "] " << fmt(s.q) << " -> " << fmt(s.p));
      REQUIRE(fw.size() == bw.size());
      for (std::size_t i = 0, n = fw.size(); i < n; ++i) {
        const auto& b = bw[n - 1 - i];
        CHECK(fw[i].dimension == b.dimension);
        CHECK(fw[i].vertices == b.vertices);
        if (s.q != s.p) {
          CHECK(fw[i].t_in == Q(1) - b.t_out);
          CHECK(fw[i].t_out == Q(1) - b.t_in);
        }
      }
      check_with_predicates(tr, vh, s.q, s.p, fw);
    }
  }
}

TEST_CASE("generators: meshes are valid and positively oriented", "[generators]") {
  for (const Test_mesh& m : {kuhn_grid(3, 3, 3), jittered_kuhn_grid(3, 1), tunnel_grid(3), cavity_grid(3), l_shape_grid(4),
                             edge_touching_blocks(), vertex_touching_blocks(), checkerboard_blocks(), delaunay_cospherical({25}),
                             delaunay_cospherical({50})}) {
    INFO("mesh " << m.name);
    Tr tr;
    const auto rep = build_triangulation_from_tets(m.points, m.tets, {}, tr);
    CHECK(rep.reoriented_tets == 0);
    CHECK(rep.unused_vertices == 0);
    for (const auto& t : m.tets) CHECK(testing::internal::tet_orientation(m.points, t) == CGAL::POSITIVE);
  }
  CHECK(kuhn_grid(2, 2, 2).tets.size() == 48);
  CHECK(tunnel_grid(3).tets.size() == 6 * 24);
  CHECK(delaunay_cospherical({25}).points.size() == 31);
  // Same seed, same data.
  const auto a = degenerate_segments(kuhn_grid(2, 2, 2), 50, 5), b = degenerate_segments(kuhn_grid(2, 2, 2), 50, 5);
  for (std::size_t i = 0; i < a.size(); ++i) CHECK((a[i].q == b[i].q && a[i].p == b[i].p));
}

// --- The walk against the reference -----------------------------------------

TEST_CASE("walk vs reference: Kuhn grids", "[walk][reference]") {
  Family_result r;
  compare_on(single_tet(), degenerate_segments(single_tet(), 300, 1), r);
  const std::pair<int, std::size_t> sizes[] = {{1, 600}, {2, 2500}, {3, 1500}, {4, 400}};
  for (const auto& ns : sizes) {
    const Test_mesh m = kuhn_grid(ns.first, ns.first, ns.first);
    compare_on(m, degenerate_segments(m, ns.second, 1 + ns.first), r);
  }
  report("Kuhn grids", r);
}

TEST_CASE("walk vs reference: jittered grids", "[walk][reference]") {
  Family_result r;
  for (std::uint64_t seed : {1, 2, 3, 4}) {
    const Test_mesh m = jittered_kuhn_grid(2 + static_cast<int>(seed % 2), seed);
    compare_on(m, degenerate_segments(m, 800, 100 + seed), r);
  }
  report("jittered grids", r);
}

TEST_CASE("walk vs reference: non-convex and non-manifold grids", "[walk][reference]") {
  Family_result r;
  for (const Test_mesh& m : {tunnel_grid(3), cavity_grid(3), l_shape_grid(3), l_shape_grid(2), edge_touching_blocks(2),
                             vertex_touching_blocks(), checkerboard_blocks()})
    compare_on(m, degenerate_segments(m, 700, 7), r);
  report("holes / non-manifold", r);
}

TEST_CASE("walk vs reference: Delaunay of cospherical points", "[walk][reference]") {
  Family_result r;
  for (const Test_mesh& m : {delaunay_cospherical({25}), delaunay_cospherical({50}), delaunay_cospherical({9, 25})})
    compare_on(m, degenerate_segments(m, 1000, 13), r);
  // All integer points of a ball: cospherical and coplanar everywhere.
  const Test_mesh ball = delaunay_cospherical({1, 2, 3, 4, 5, 6});
  compare_on(ball, degenerate_segments(ball, 800, 19), r);
  report("Delaunay cospherical", r);
}

TEST_CASE("walk vs reference: CGAL Delaunay triangulation with Is_finite_cell", "[walk][reference]") {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Dt = CGAL::Delaunay_triangulation_3<
      K, CGAL::Triangulation_data_structure_3<CGAL::Triangulation_vertex_base_with_info_3<std::size_t, K>>>;
  struct Dt_id {
    std::size_t operator()(Dt::Vertex_handle v) const { return v->info(); }
  };
  Family_result r;
  for (const Test_mesh& m : {delaunay_cospherical({25}), delaunay_cospherical({9, 25}), kuhn_grid(2, 2, 2)}) {
    // The Delaunay triangulation of the mesh's points (for the grid: its
    // cospherical cubes are split as CGAL decides), walked directly.
    std::vector<std::pair<K::Point_3, std::size_t>> pts;
    for (std::size_t i = 0; i < m.points.size(); ++i) pts.push_back({K::Point_3(m.points[i][0], m.points[i][1], m.points[i][2]), i});
    const Dt dt(pts.begin(), pts.end());
    compare_walk("cgal_dt_of_" + m.name, dt, Is_finite_cell<Dt>(dt), Dt_id(), degenerate_segments(m, 700, 31), r);
  }
  report("CGAL Delaunay", r);
}

TEST_CASE("walk vs reference: scaled, translated, anisotropic and mirrored grids", "[walk][reference]") {
  Family_result r;
  const double tiny = std::ldexp(1.0, -20), huge = std::ldexp(1.0, 20), big_offset = 3 * std::ldexp(1.0, 18);
  const Test_mesh k2 = kuhn_grid(2, 2, 2), j2 = jittered_kuhn_grid(2, 21);
  for (const Test_mesh& m : {transformed(k2, {tiny, tiny, tiny}, {0, 0, 0}, "_tiny"),
                             transformed(k2, {huge, huge, huge}, {0, 0, 0}, "_huge"),
                             transformed(k2, {1, 1, 1}, {big_offset, -big_offset, big_offset}, "_far"),
                             transformed(k2, {1, 1, 1.0 / 1024}, {0, 0, 0}, "_flat"),
                             transformed(k2, {-1, 1, 1}, {0, 0, 0}, "_mirrored"),
                             transformed(j2, {0.5, 2, 1.0 / 64}, {-big_offset, 0, 3}, "_flat_far")})
    compare_on(m, degenerate_segments(m, 500, 17), r);
  // The ends of double: coordinates near 1e300 (the cell array's filters do
  // not apply: the general path, in interval and exact arithmetic), near
  // 1e-300, and subnormal.
  const double e995 = std::ldexp(1.0, 995), em995 = std::ldexp(1.0, -995), em1060 = std::ldexp(1.0, -1060);
  for (const Test_mesh& m : {transformed(k2, {e995, e995, e995}, {0, 0, 0}, "_2^995"),
                             transformed(k2, {em995, em995, em995}, {0, 0, 0}, "_2^-995"),
                             transformed(k2, {em1060, em1060, em1060}, {0, 0, 0}, "_2^-1060")})
    compare_on(m, degenerate_segments(m, 200, 19), r);
  report("transformed grids", r);
}

TEST_CASE("walk vs reference: near-degenerate (ulp-nudged) segments", "[walk][reference]") {
  Family_result r;
  for (const Test_mesh& m : {kuhn_grid(2, 2, 2), jittered_kuhn_grid(2, 5), tunnel_grid(3), edge_touching_blocks(2),
                             delaunay_cospherical({25})})
    compare_on(m, nudged(degenerate_segments(m, 800, 23), 29), r);
  report("ulp-nudged segments", r);
}

TEST_CASE("walk vs reference: nearly degenerate segments (moved by up to 2^40 ulps)", "[walk][reference]") {
  Family_result r;
  const Test_mesh flat = transformed(jittered_kuhn_grid(3, 2002), {1, 1, 1.0 / 4096}, {0, 0, 0}, "_flat");
  for (const Test_mesh& m : {kuhn_grid(3, 3, 3), jittered_kuhn_grid(3, 41), flat, l_shape_grid(3), delaunay_cospherical({50})})
    compare_on(m, nudged(degenerate_segments(m, 800, 43), 47, 40), r);
  // Found by larger sweeps (t of an edge crossing off by 1e-9 .. 1e-4 in an
  // earlier version of the walk): segments nearly in the plane of flat tets.
  compare_on(flat, {{{19.3125, 6.5625, 0.0031585693359375}, {10.875010371208191, 6.5625, 0.002872467041015625}, "found"}}, r);
  const double f12 = std::ldexp(1.0, -12), f20 = std::ldexp(1.0, -20);
  compare_on(transformed(jittered_kuhn_grid(3, 502), {1, 1, f12}, {0, 0, 0}, "_flat12"),
             {{{4.5, 7.875, 0.0040280818939208984}, {4.5, 19.125, 0.0040283203125}, "found"}}, r);
  compare_on(transformed(jittered_kuhn_grid(3, 502), {1, 1, f20}, {0, 0, 0}, "_flat20"),
             {{{4.5, 7.875, 1.573469489812851e-05}, {4.5, 19.125, 1.5735626220703125e-05}, "found"}}, r);
  compare_on(transformed(jittered_kuhn_grid(3, 501), {1, 1, f20}, {0, 0, 0}, "_flat20"),
             {{{6.65625, 0.09375, 1.3947515981271863e-05}, {7.21875, 0.65625, 7.5101852416992188e-06}, "found"}}, r);
  const Test_mesh flat20 = transformed(jittered_kuhn_grid(3, 500), {1, 1, f20}, {0, 0, 0}, "_flat20");
  compare_on(flat20, nudged(degenerate_segments(flat20, 1000, 53), 59, 44), r);
  report("nearly degenerate", r);
}

// Segments degenerate only up to rounding (end points computed in double on
// edge lines and in facet planes, with arbitrary coefficients), on meshes
// written by Gmsh and TetGen and on jittered grids with non-dyadic
// coordinates: every crossing parameter within 1e-12 of the exact one (the
// tolerance of every comparison here), and no piece of positive length
// reported with zero length.
TEST_CASE("walk vs reference: rounded segments along edge lines and in facet planes", "[walk][reference]") {
  Family_result r;
  const Test_mesh jittered = transformed(jittered_kuhn_grid(3, 77), {0.1, 1.0 / 3, 0.7}, {0.01, -0.2, 1.0 / 7}, "_nondyadic");
  for (const Test_mesh& m : {medit_test_mesh("gmsh_box_with_hole.mesh"), medit_test_mesh("tetgen_cube.mesh"), jittered})
    compare_on(m, rounded_degenerate_segments(m, 600, 61), r);
  report("rounded degenerate", r);
}

// Minimal reproducers of the disagreements found by the families above, kept
// as named cases: two Kuhn cubes [0,6]^3 and [6,12]^3 touching at the vertex
// 7 = (6,6,6) only.
TEST_CASE("walk vs reference: through the vertex where two cubes touch", "[walk][reference]") {
  const Test_mesh m = vertex_touching_blocks();
  Tr tr;
  build(m, tr);
  const Reference ref(tr, Is_tet_mesh_domain_cell(), Vertex_info_id());
  const Segment_walk_3<Tr, Is_tet_mesh_domain_cell> walk(tr, Is_tet_mesh_domain_cell());
  Tr::Cell_handle upper; // a cell of the cube [6,12]^3
  for (auto c : tr.finite_cell_handles())
    if (c->vertex(0)->point().x() + c->vertex(1)->point().x() + c->vertex(2)->point().x() + c->vertex(3)->point().x() > 24) upper = c;
  const std::pair<P3, P3> segs[] = {
      {{3, 4, 5}, {9, 8, 7}}, // lower cube to upper cube, through vertex 7
      {{9, 8, 7}, {3, 4, 5}}, // the same, reversed
      {{9, 6, 6}, {3, 6, 6}}, // along edge {7,8}, through 7, along edge {6,7}
      {{9, 9, 9}, {3, 3, 3}}, // along the two main diagonals
  };
  for (const auto& s : segs)
    for (bool fast : {false, true}) {
      INFO((fast ? "fast: " : "full: ") << fmt(s.first) << " -> " << fmt(s.second));
      std::vector<Segment_walk_piece_3<Tr>> got;
      const Tr::Point q(s.first[0], s.first[1], s.first[2]), p(s.second[0], s.second[1], s.second[2]);
      if (fast) walk.fast(q, p, std::back_inserter(got));
      else walk(q, p, std::back_inserter(got));
      auto exp = ref(s.first, s.second);
      if (fast) exp.erase(std::remove_if(exp.begin(), exp.end(), [](const Reference_piece& r) { return r.t_in == r.t_out; }), exp.end());
      INFO("walk:\n" << to_string(got, Vertex_info_id()) << "reference:\n" << to_string(exp));
      CHECK(mismatch(got, exp, 1e-9, Is_tet_mesh_domain_cell(), Vertex_info_id()) == "");
    }
  // Point location with a hint in the other component.
  for (const P3& x : {P3{3, 1.5, 4.5}, P3{1, 2, 3}}) {
    INFO("q == p = " << fmt(x) << ", hint in the upper cube");
    std::vector<Segment_walk_piece_3<Tr>> got;
    walk(Tr::Point(x[0], x[1], x[2]), Tr::Point(x[0], x[1], x[2]), std::back_inserter(got), upper);
    const auto exp = ref(x, x);
    INFO("walk:\n" << to_string(got, Vertex_info_id()) << "reference:\n" << to_string(exp));
    CHECK(mismatch(got, exp, 1e-9, Is_tet_mesh_domain_cell(), Vertex_info_id()) == "");
  }
}

TEST_CASE("point locator vs reference: every special point, from hints and by the buckets alone", "[locate][reference]") {
  // Point_locator_3 against an exact brute force (exact_location, checked
  // against the walk reference on a sample): the vertices, edge midpoints, facet and cell
  // centroids, and points around and outside each mesh, from no hint and
  // from every 37th cell, and the exact bucket test alone (the fallback where
  // the visibility walk meets the boundary) on every point. The Delaunay
  // triangulation of points on a sphere has only long cells: its bucket grid
  // is coarsened to keep the cell references bounded.
  std::size_t located = 0;
  for (const Test_mesh& m : {tunnel_grid(3), cavity_grid(3), l_shape_grid(3), edge_touching_blocks(2),
                             vertex_touching_blocks(), checkerboard_blocks(), delaunay_cospherical({25})}) {
    INFO(m.name);
    Tr tr;
    build(m, tr);
    const Point_locator_3<Tr, Is_tet_mesh_domain_cell> locate(tr, Is_tet_mesh_domain_cell());
    const Segment_walk_3<Tr, Is_tet_mesh_domain_cell> walk(tr, Is_tet_mesh_domain_cell());
    std::vector<P3> points(m.points.begin(), m.points.end());
    for (const auto& t : m.tets)
      for (int a = 0; a < 4; ++a) {
        const P3 &u = m.points[t[a]], &v = m.points[t[(a + 1) % 4]], &w = m.points[t[(a + 2) % 4]];
        points.push_back({(u[0] + v[0]) / 2, (u[1] + v[1]) / 2, (u[2] + v[2]) / 2});
        points.push_back({(u[0] + v[0] + w[0]) / 3, (u[1] + v[1] + w[1]) / 3, (u[2] + v[2] + w[2]) / 3});
        if (a == 0) {
          const P3& z = m.points[t[3]];
          points.push_back({(u[0] + v[0] + w[0] + z[0]) / 4, (u[1] + v[1] + w[1] + z[1]) / 4, (u[2] + v[2] + w[2] + z[2]) / 4});
        }
      }
    std::mt19937 rng(17);
    std::uniform_real_distribution<double> u(-0.2, 1.2);
    P3 lo = m.points[0], hi = m.points[0];
    for (const P3& p : m.points)
      for (int d = 0; d < 3; ++d) lo[d] = std::min(lo[d], p[d]), hi[d] = std::max(hi[d], p[d]);
    for (int i = 0; i < 300; ++i) {
      P3 p;
      for (int d = 0; d < 3; ++d) p[d] = lo[d] + u(rng) * (hi[d] - lo[d]);
      points.push_back(p);
    }
    std::vector<Tr::Cell_handle> hints = {Tr::Cell_handle(), tr.infinite_cell()};
    std::size_t k = 0;
    for (auto c : tr.finite_cell_handles())
      if (k++ % 37 == 0) hints.push_back(c);
    for (std::size_t i = 0; i < points.size(); ++i) {
      const P3& x = points[i];
      const Reference_piece ref = exact_location(tr, x);
      if (i % 50 == 0) { // a zero-length segment of the walk reference is exactly the location
        const Reference_piece walk_ref = ref_of(tr, x, x).front();
        CHECK(walk_ref.dimension == ref.dimension);
        CHECK(walk_ref.vertices == ref.vertices);
      }
      const Tr::Point px(x[0], x[1], x[2]);
      // The exact fallback alone, on every point.
      const auto bucket = locate.locate_by_buckets(px);
      INFO("point " << fmt(x) << ", buckets only");
      std::vector<std::size_t> bucket_ids;
      for (int j = 0; j < 4; ++j)
        if (bucket.second & (1u << j)) bucket_ids.push_back(bucket.first->vertex(j)->info());
      std::sort(bucket_ids.begin(), bucket_ids.end());
      CHECK(int(bucket_ids.size()) - 1 == ref.dimension);
      CHECK(bucket_ids == ref.vertices);
      for (std::size_t h = i % 5; h < hints.size(); h += 5) {
        INFO("point " << fmt(x) << " hint " << h << ", reference:\n" << to_string(std::vector<Reference_piece>{ref}));
        const auto l = locate(px, hints[h]);
        std::vector<std::size_t> ids;
        for (int j = 0; j <= l.dimension; ++j) ids.push_back(l.vertices[j]->info());
        std::sort(ids.begin(), ids.end());
        REQUIRE(l.dimension == ref.dimension);
        CHECK(ids == ref.vertices);
        CHECK((l.cell != Tr::Cell_handle()) == (ref.dimension >= 0));
        if (l.cell != Tr::Cell_handle()) CHECK(l.cell->info().in_domain());
        CHECK(walk.locate(px, hints[h]).dimension == ref.dimension);
        ++located;
      }
    }
  }
  CHECK(located >= 7 * 300); // at least one hint per random point of each mesh
}
