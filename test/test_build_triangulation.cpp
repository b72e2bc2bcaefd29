// Building a Tet_mesh_triangulation_3 from tetrahedra: adjacency, boundary
// closure (also around non-manifold edges), re-orientation, and errors.
#include <CGAL_ext/IO/read_tet_mesh.h>
#include <CGAL_ext/Tet_mesh_statistics_3.h>

#include "reference/degenerate_test_meshes.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <map>
#include <random>
#include <set>

using namespace CGAL_ext;
using Tr = Tet_mesh_triangulation_3<>;

namespace {

const std::string data_dir = CGAL_EXT_TEST_DATA_DIR;

// Combinatorial validity that does not assume one connected component
// (CGAL's TDS check also tests the Euler relation of a 3-sphere).
void check_adjacency(const Tr& tr) {
  std::size_t finite = 0;
  for (auto c : tr.all_cell_handles()) {
    for (int i = 0; i < 4; ++i) {
      auto n = c->neighbor(i);
      REQUIRE(n != Tr::Cell_handle());
      REQUIRE(n->has_neighbor(c));
      const int j = n->index(c);
      CHECK(n->neighbor(j) == c);
      for (int k = 1; k < 4; ++k) CHECK(n->has_vertex(c->vertex((i + k) % 4)));
      CHECK_FALSE(n->has_vertex(c->vertex(i)));
    }
    if (!tr.is_infinite(c)) {
      ++finite;
      CHECK(CGAL::orientation(c->vertex(0)->point(), c->vertex(1)->point(), c->vertex(2)->point(),
                              c->vertex(3)->point()) == CGAL::POSITIVE);
      CHECK(c->info().in_domain());
    } else {
      CHECK_FALSE(c->info().in_domain());
    }
  }
  for (auto v : tr.finite_vertex_handles()) CHECK(v->cell()->has_vertex(v));
  CHECK(finite == tr.number_of_finite_cells());
}

Tet_mesh_build_report build(const std::vector<std::array<double, 3>>& p, const std::vector<std::array<std::size_t, 4>>& t,
                            Tr& tr) {
  return build_triangulation_from_tets(p, t, {}, tr);
}

} // namespace

TEST_CASE("a Kuhn-subdivided cube builds into a valid CGAL triangulation", "[build]") {
  Tr tr;
  IO::Medit_mesh m;
  const auto r = IO::read_tet_mesh(data_dir + "/cube_kuhn_2.mesh", tr, &m);
  CHECK(r.reoriented_tets == 0);
  CHECK(r.boundary_facets == 48);
  CHECK(r.non_manifold_boundary_edges == 0);
  CHECK(tr.is_valid()); // convex: CGAL's own full check applies
  check_adjacency(tr);
  CHECK(tr.number_of_finite_cells() == 48);
  CHECK(tr.number_of_vertices() == 27);
  // Cells keep their file index and vertices theirs.
  std::set<std::int64_t> indices;
  for (auto c : tr.finite_cell_handles()) {
    indices.insert(c->info().index);
    CHECK(c->info().reference == 1);
    std::multiset<std::size_t> file(m.tetrahedra[c->info().index].begin(), m.tetrahedra[c->info().index].end());
    std::multiset<std::size_t> cell;
    for (int i = 0; i < 4; ++i) cell.insert(c->vertex(i)->info());
    CHECK(file == cell);
  }
  CHECK(indices.size() == 48);
  for (auto v : tr.finite_vertex_handles()) {
    const auto& p = m.vertices[v->info()];
    CHECK(v->point() == Tr::Point(p[0], p[1], p[2]));
  }
  const auto s = compute_tet_mesh_statistics(tr, Is_tet_mesh_domain_cell());
  CHECK(s.components == 1);
  CHECK(static_cast<double>(s.volume) == Approx(8.0).epsilon(1e-14));
  CHECK(s.boundary_facets == 48);
  CHECK(s.min_dihedral_angle == Approx(45.0));
  CHECK(s.max_dihedral_angle == Approx(90.0));
}

// info's figures at every scale double holds: a volume of 8e900 or 8e-930
// (long double), angles from normalised products, never inf, NaN or 0.
TEST_CASE("mesh statistics are right at every coordinate scale, up to 1e300 and down to subnormal", "[build]") {
  const IO::Medit_mesh m0 = IO::read_medit_mesh(data_dir + "/cube_kuhn_2.mesh");
  double mean0 = 0;
  for (int e : {0, 995, -995, -1060}) {
    INFO("coordinates scaled by 2^" << e);
    IO::Medit_mesh m = m0;
    for (auto& p : m.vertices)
      for (double& x : p) x = std::ldexp(x, e); // exact: the cube's coordinates are 0, 1, 2
    Tr tr;
    build_triangulation_from_tets(m.vertices, m.tetrahedra, {}, tr);
    const auto s = compute_tet_mesh_statistics(tr, Is_tet_mesh_domain_cell());
    if (e == 0) mean0 = static_cast<double>(s.mean_edge_length);
    const long double volume = std::ldexp(8.0L, 3 * e);
    CHECK(std::abs(s.volume / volume - 1) < 1e-15L);
    CHECK(std::abs(s.mean_edge_length / std::ldexp(static_cast<long double>(mean0), e) - 1) < 1e-15L);
    CHECK(s.min_dihedral_angle == Approx(45.0).epsilon(1e-12));
    CHECK(s.max_dihedral_angle == Approx(90.0).epsilon(1e-12));
  }
}

TEST_CASE("negatively oriented tetrahedra are re-oriented and reported", "[build]") {
  Tr tr;
  const auto r = IO::read_tet_mesh(data_dir + "/reoriented.mesh", tr);
  CHECK(r.reoriented_tets == 16); // every third of 48
  REQUIRE(r.reoriented_examples.size() == 10);
  CHECK(r.reoriented_examples[1] == 3);
  check_adjacency(tr);
  CHECK(tr.is_valid());
}

TEST_CASE("a non-convex L-shape and Gmsh's box with a hole build", "[build]") {
  Tr tr;
  IO::read_tet_mesh(data_dir + "/l_shape.mesh", tr);
  check_adjacency(tr);
  auto s = compute_tet_mesh_statistics(tr, Is_tet_mesh_domain_cell());
  CHECK(s.cells == 36);
  CHECK(s.components == 1);
  CHECK(static_cast<double>(s.volume) == Approx(6.0));

  const auto r = IO::read_tet_mesh(data_dir + "/gmsh_box_with_hole.mesh", tr);
  check_adjacency(tr);
  s = compute_tet_mesh_statistics(tr, Is_tet_mesh_domain_cell());
  CHECK(s.components == 1);
  CHECK(r.non_manifold_boundary_edges == 0);
  // A faceted cylinder hole removes a bit less than pi r^2 h.
  CHECK(s.volume > 1 - 0.04 * M_PI);
  CHECK(s.volume < 1 - 0.9 * 0.04 * M_PI);
}

TEST_CASE("two cubes touching along an edge: infinite cells are paired across the outside sectors", "[build]") {
  Tr tr;
  const auto r = IO::read_tet_mesh(data_dir + "/two_cubes_sharing_edge.mesh", tr);
  CHECK(r.non_manifold_boundary_edges == 1);
  check_adjacency(tr);
  const auto s = compute_tet_mesh_statistics(tr, Is_tet_mesh_domain_cell());
  CHECK(s.components == 2);
  CHECK(static_cast<double>(s.volume) == Approx(2.0));
  // Around the shared edge: 2 tets of each cube, separated by 2 outside sectors
  // of 2 infinite cells each. A wrong pairing closes a cycle of 4 on one cube.
  Tr::Vertex_handle a, b;
  for (auto v : tr.finite_vertex_handles()) {
    if (v->point() == Tr::Point(1, 1, 0)) a = v;
    if (v->point() == Tr::Point(1, 1, 1)) b = v;
  }
  REQUIRE(a != Tr::Vertex_handle());
  REQUIRE(b != Tr::Vertex_handle());
  Tr::Cell_handle c;
  int i = 0, j = 0;
  REQUIRE(tr.is_edge(a, b, c, i, j));
  auto circ = tr.incident_cells(c, i, j), done = circ;
  std::size_t n = 0, finite = 0;
  do {
    ++n;
    if (!tr.is_infinite(circ)) ++finite;
  } while (++circ != done && n < 100);
  CHECK(n == 8);
  CHECK(finite == 4);
}

TEST_CASE("two cubes touching at a vertex build with two components", "[build]") {
  Tr tr;
  const auto r = IO::read_tet_mesh(data_dir + "/two_cubes_sharing_vertex.mesh", tr);
  CHECK(r.non_manifold_boundary_edges == 0);
  check_adjacency(tr);
  CHECK(compute_tet_mesh_statistics(tr, Is_tet_mesh_domain_cell()).components == 2);
}

TEST_CASE("unused vertices are reported and left out", "[build]") {
  Tr tr;
  std::vector<Tr::Vertex_handle> vh;
  const auto r = build_triangulation_from_tets<CGAL::Epick>({{0, 0, 0}, {1, 0, 0}, {5, 5, 5}, {0, 1, 0}, {0, 0, 1}},
                                                            {{0, 1, 3, 4}}, {}, tr, {}, &vh);
  CHECK(r.unused_vertices == 1);
  CHECK(vh[2] == Tr::Vertex_handle());
  CHECK(vh[4]->info() == 4);
  CHECK(tr.number_of_vertices() == 4);
  CHECK(tr.is_valid());
}

TEST_CASE("degenerate and inconsistent tetrahedra are errors naming the tetrahedron", "[build][bad-input]") {
  Tr tr;
  const std::vector<std::array<double, 3>> p{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {1, 1, 1}};
  auto error = [&](const std::vector<std::array<std::size_t, 4>>& t) -> std::string {
    Tet_soup_source src;
    src.file = "in.mesh";
    for (std::size_t k = 0; k < t.size(); ++k) src.tet_lines.push_back(100 + k);
    try {
      build_triangulation_from_tets(p, t, {}, tr, src);
    } catch (const Input_error& e) {
      return e.what();
    }
    return "no error";
  };
  CHECK(error({{0, 1, 2, 3}, {0, 1, 2, 4}}) == "in.mesh:101: tetrahedron 2: zero volume (its four vertices are coplanar)");
  CHECK(error({{0, 1, 2, 2}}) == "in.mesh:100: tetrahedron 1: vertex 3 appears twice");
  CHECK(error({{0, 1, 2, 9}}) == "in.mesh:100: tetrahedron 1: vertex index 10 is out of range 1..6");
  CHECK(error({}) == "in.mesh: the mesh has no tetrahedra");
  CHECK(error({{0, 1, 2, 3}, {0, 2, 1, 3}}) == "in.mesh:101: tetrahedron 2: duplicates tetrahedron 1");
  // Both on the same side of facet (0,1,2): they overlap.
  CHECK(error({{0, 1, 2, 3}, {0, 1, 2, 5}}).find("overlaps tetrahedron 1") != std::string::npos);
  // Three tets on one facet.
  const std::vector<std::array<double, 3>> q{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, -1}, {0.2, 0.2, 2}};
  try {
    build_triangulation_from_tets(q, {{0, 1, 2, 3}, {0, 1, 2, 4}, {0, 1, 2, 5}}, {}, tr);
    FAIL("no error");
  } catch (const Input_error& e) {
    CHECK(std::string(e.what()).find("is shared by 3 tetrahedra") != std::string::npos);
  }
  std::vector<std::array<double, 3>> nan_points = p;
  nan_points[3][2] = std::nan("");
  CHECK_THROWS_WITH(build_triangulation_from_tets(nan_points, {{0, 1, 2, 3}}, {}, tr),
                    "vertex 4: coordinate is not finite (NaN or Inf)");
}

TEST_CASE("write and read back round-trips vertices and tetrahedra", "[build][medit]") {
  Tr tr;
  IO::Medit_mesh m;
  IO::read_tet_mesh(data_dir + "/tetgen_cube.mesh", tr, &m);
  const auto out = (std::filesystem::temp_directory_path() / "cgal_ext_roundtrip_tetgen.mesh").string();
  IO::write_medit_mesh(out, m);
  Tr tr2;
  IO::Medit_mesh m2;
  IO::read_tet_mesh(out, tr2, &m2);
  CHECK(m2.vertices == m.vertices);
  CHECK(m2.tetrahedra == m.tetrahedra);
  CHECK(tr2.number_of_finite_cells() == tr.number_of_finite_cells());
  CHECK(tr2.is_valid());
}

namespace {

// Adds the cube of side `side` at `origin`, with 8 new vertices, as 6 Kuhn tetrahedra.
void add_cube(std::vector<std::array<double, 3>>& p, std::vector<std::array<std::size_t, 4>>& t,
              const std::array<double, 3>& origin, double side = 1) {
  const std::size_t base = p.size();
  for (int v = 0; v < 8; ++v)
    p.push_back({origin[0] + side * (v & 1), origin[1] + side * ((v >> 1) & 1), origin[2] + side * ((v >> 2) & 1)});
  static const int perms[6][3] = {{1, 2, 4}, {1, 4, 2}, {2, 1, 4}, {2, 4, 1}, {4, 1, 2}, {4, 2, 1}};
  for (const auto& q : perms) {
    const std::size_t a = 0, b = std::size_t(q[0]), c = b + std::size_t(q[1]), d = 7;
    t.push_back({base + a, base + b, base + c, base + d});
  }
}

} // namespace

// Two cubes that touch along a face, an edge or a corner, or overlap, each
// with its own vertices: the walk would take their contact for a boundary
// and the volume would count the overlap twice. Refused, naming both tets.
TEST_CASE("parts that overlap or touch without sharing vertices are errors naming two tetrahedra", "[build][bad-input]") {
  const std::pair<std::array<double, 3>, const char*> cases[] = {{{1, 0, 0}, "touching along a face"},
                                                                   {{1, 1, 0}, "touching along an edge"},
                                                                   {{1, 1, 1}, "touching at a corner"},
                                                                   {{0.5, 0.25, 0.125}, "overlapping"},
                                                                   {{0.25, 0.25, 1}, "a face inside a face"}};
  for (const auto& c : cases) {
    INFO(c.second);
    std::vector<std::array<double, 3>> p;
    std::vector<std::array<std::size_t, 4>> t;
    add_cube(p, t, {0, 0, 0});
    add_cube(p, t, c.first);
    Tr tr;
    try {
      build_triangulation_from_tets(p, t, {}, tr, Tet_soup_source{"two_cubes.mesh", {}, {}});
      FAIL("accepted");
    } catch (const Input_error& e) {
      INFO(e.what());
      CHECK(e.file() == "two_cubes.mesh");
      CHECK(e.element().rfind("tetrahedron ", 0) == 0);
      CHECK(std::stoi(e.element().substr(12)) > 6); // a tet of the second cube
      CHECK(e.problem().find("overlaps or touches tetrahedron ") == 0);
      CHECK(e.problem().find("where they share no vertex") != std::string::npos);
    }
  }
  // Apart, or sharing the vertices where they touch: accepted.
  std::vector<std::array<double, 3>> p;
  std::vector<std::array<std::size_t, 4>> t;
  add_cube(p, t, {0, 0, 0});
  add_cube(p, t, {1.5, 0, 0});
  Tr tr;
  build_triangulation_from_tets(p, t, {}, tr);
  CHECK(compute_tet_mesh_statistics(tr, Is_tet_mesh_domain_cell()).components == 2);
  for (const char* f : {"two_cubes_sharing_edge.mesh", "two_cubes_sharing_vertex.mesh", "gmsh_box_with_hole.mesh", "tetgen_cube.mesh"})
    CHECK_NOTHROW(IO::read_tet_mesh(data_dir + "/" + f, tr));
}

namespace {

// The error that building reports, or "accepted".
std::string build_error(const std::vector<std::array<double, 3>>& p, const std::vector<std::array<std::size_t, 4>>& t) {
  Tr tr;
  try {
    build_triangulation_from_tets(p, t, {}, tr, Tet_soup_source{"m.mesh", {}, {}});
  } catch (const Input_error& e) {
    return e.what();
  }
  return "accepted";
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// Which test rejected a mesh: the shared facet, the boundary, an edge or a vertex.
std::string overlap_kind(const std::string& error) {
  for (const char* k : {"zero volume", "across their common facet", "where they share no vertex", "about their common edge",
                        "near their common vertex", "which it does not use", "duplicates tetrahedron", "appears twice", "is shared by"})
    if (contains(error, k)) return k;
  return "other: " + error;
}

} // namespace

// Found by fuzz_medit_mesh: one vertex index changed in the 2x2x2 Kuhn cube
// (tetrahedron 34, (11, 14, 15, 24) -> (11, 14, 18, 24)). Every tet is
// positive and every shared facet separates its two tets, but the new tet
// folds over its neighbours around vertex 14, where all the boundary facets
// that meet share a vertex.
TEST_CASE("a mesh folded over itself near a shared vertex is an error", "[build][bad-input]") {
  IO::Medit_mesh m = IO::read_medit_mesh(data_dir + "/cube_kuhn_2.mesh");
  REQUIRE(m.tetrahedra[33] == std::array<std::size_t, 4>{10, 13, 14, 23});
  m.tetrahedra[33][2] = 17;
  const std::string e = build_error(m.vertices, m.tetrahedra);
  INFO(e);
  CHECK(contains(e, "m.mesh: tetrahedron "));
  CHECK(contains(e, "overlap"));
}

// Two tetrahedra with one common vertex, and two with a common edge, in
// every relative position that the shared-vertex and shared-edge tests of
// find_boundary_overlap() distinguish.
TEST_CASE("tetrahedra sharing a vertex or an edge may touch only there", "[build][bad-input]") {
  const std::array<double, 3> o{0, 0, 0};
  // One common vertex (the origin).
  const std::vector<std::array<double, 3>> p{o, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, // tet 1 in the positive octant
                                             {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}};
  CHECK(build_error(p, {{0, 1, 2, 3}, {0, 4, 5, 6}}) == "accepted"); // opposite octants
  // A second tet turned into the first: its edges cross the first's facets.
  std::vector<std::array<double, 3>> q = p;
  q[4] = {1, 1, 0.2};
  q[5] = {0.2, 1, 1};
  q[6] = {1, 0.2, 1};
  CHECK(contains(build_error(q, {{0, 1, 2, 3}, {0, 4, 5, 6}}), "where they share no vertex"));
  // A small tet inside the first one's corner: no boundary facets meet, but
  // its edges from the common vertex point into the first.
  q[4] = {0.3, 0.3, 0.3};
  q[5] = {0.35, 0.3, 0.3};
  q[6] = {0.3, 0.35, 0.3};
  CHECK(build_error(q, {{0, 1, 2, 3}, {0, 4, 5, 6}}) ==
        "m.mesh: tetrahedron 2: overlaps tetrahedron 1 near their common vertex 1: the boundary edge (1, 5) of "
        "tetrahedron 2 lies in the corner of tetrahedron 1 at vertex 1 (parts of the mesh that meet at a vertex overlap "
        "there)");
  // Touching along a segment from the common vertex: facet (0,1,2) and a
  // facet of the second tet through the segment (0, (1,1,0)) below it.
  q[4] = {1, 1, 0};
  q[5] = {1, 1, -1};
  q[6] = {2, 1, -1};
  const std::string touch = build_error(q, {{0, 1, 2, 3}, {0, 4, 5, 6}});
  INFO(touch);
  CHECK(contains(touch, "where they share no vertex"));
  // Touching only at the common vertex, their facets in one plane: accepted.
  q[4] = {-1, 0, 0};
  q[5] = {0, -1, 0};
  q[6] = {-1, -1, 1};
  CHECK(build_error(q, {{0, 1, 2, 3}, {0, 4, 5, 6}}) == "accepted");

  // One common edge (0, 1): facets (0, 1, 2) and (0, 1, 4) in the plane z = 0.
  std::vector<std::array<double, 3>> r{o, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.5, 2, 0}, {0, 0, -1}};
  // On the same side of the edge, the tets on either side of the plane: the
  // facets overlap in a triangle, which no edge and no vertex reveals.
  const std::string same = build_error(r, {{0, 1, 2, 3}, {0, 1, 4, 5}});
  INFO(same);
  CHECK(contains(same, "tetrahedron 2: overlaps or touches tetrahedron 1 where they share no vertex"));
  CHECK(contains(same, "(1, 2, 5) and (1, 2, 3)"));
  // On opposite sides of the edge: they touch along the edge only.
  r[4] = {0.5, -2, 0};
  CHECK(build_error(r, {{0, 1, 2, 3}, {0, 1, 4, 5}}) == "accepted");

  // Two tetrahedra on either side of one triangle, the second with copies
  // of its vertices: the message says that vertices coincide.
  std::vector<std::array<double, 3>> d{o, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
  const std::string dup = build_error(d, {{0, 1, 2, 3}, {7, 4, 5, 6}});
  INFO(dup);
  CHECK(contains(dup, "where they share no vertex"));
  CHECK(contains(dup, "have the same coordinates: a duplicated vertex, to be merged"));
  CHECK(!contains(same, "same coordinates"));
}

// Five tets around one edge, each turning 100 degrees about it: 500 degrees
// in all, the last one inside the first two. The edge test runs before the
// boundary test (whose facets cross here too), so that a fold is named by
// its edge.
TEST_CASE("tetrahedra turning more than once about an edge are an error naming the edge", "[build][bad-input]") {
  std::vector<std::array<double, 3>> p{{0, 0, -1}, {0, 0, 1}};
  const double pi = std::acos(-1.0);
  for (int k = 0; k <= 5; ++k) {
    const double a = k * 100 * pi / 180, radius = k == 5 ? 0.3 : 1;
    p.push_back({radius * std::cos(a), radius * std::sin(a), 0});
  }
  std::vector<std::array<std::size_t, 4>> t;
  for (std::size_t k = 0; k < 5; ++k) t.push_back({0, 1, 2 + k, 3 + k});
  const std::string e = build_error(p, t);
  INFO(e);
  CHECK(contains(e, "m.mesh: tetrahedron 5: overlaps tetrahedron "));
  CHECK(contains(e, " about their common edge (1, 2)"));
  // Four of them (400 degrees) still fold; three (300 degrees) do not.
  t.pop_back();
  p[6] = {0.3 * std::cos(4 * 100 * pi / 180), 0.3 * std::sin(4 * 100 * pi / 180), 0};
  CHECK(contains(build_error(p, t), "about their common edge (1, 2)"));
  t.pop_back();
  CHECK(build_error(p, t) == "accepted");
}

// Found by fuzz_medit_mesh (8.4 million runs): a tetrahedron added inside
// a block whose vertices are all boundary vertices of the block. Its facets
// meet the block's boundary only at those shared vertices, its edges are no
// edges of the block, and no vertex lies inside a tetrahedron that does not
// use it: only the corners around a shared vertex reveal the overlap.
TEST_CASE("a tetrahedron inside a block touching it at boundary vertices is an error", "[build][bad-input]") {
  IO::Medit_mesh m = IO::read_medit_mesh(data_dir + "/cube_kuhn_2.mesh");
  // The face centres (1, 0, 1), (1, 1, 0), (0, 1, 1) and the corner (2, 2, 2).
  m.tetrahedra.push_back({10, 12, 4, 26});
  const std::string e = build_error(m.vertices, m.tetrahedra);
  INFO(e);
  CHECK(contains(e, "m.mesh: tetrahedron 49: overlaps tetrahedron "));
  CHECK(contains(e, "near their common vertex "));
  CHECK(contains(e, ") of tetrahedron 49 lies in the corner of tetrahedron "));
  // The fuzzer's file: a distorted block of 99 tets and tetrahedron 98
  // spanning it from a corner to three points on its faces.
  const std::string path = data_dir + "/fuzz/tet_inside_block_at_boundary_vertices.mesh";
  Tet_mesh_triangulation_3<> tr;
  try {
    IO::read_tet_mesh(path, tr);
    FAIL("accepted");
  } catch (const Input_error& error) {
    const std::string what = error.what();
    INFO(what);
    CHECK(contains(what, "tet_inside_block_at_boundary_vertices.mesh"));
    CHECK(contains(what, "tetrahedron 98: overlaps tetrahedron "));
    CHECK(contains(what, " near their common vertex "));
  }
}

// A small cube inside a cell of a larger one, with no boundary contact:
// only a vertex inside a tetrahedron reveals it.
TEST_CASE("a part of the mesh nested inside another is an error", "[build][bad-input]") {
  std::vector<std::array<double, 3>> p;
  std::vector<std::array<std::size_t, 4>> t;
  add_cube(p, t, {0, 0, 0}, 8);
  add_cube(p, t, {5, 2, 1}, 0.5); // inside the Kuhn tet (0, x, x+y, x+y+z) of the big cube
  const std::string e = build_error(p, t);
  INFO(e);
  CHECK(contains(e, "m.mesh: tetrahedron "));
  CHECK(contains(e, "contains vertex "));
  CHECK(contains(e, "which it does not use"));
  // The same small cube beside the big one: two components, accepted.
  p.resize(8);
  t.resize(6);
  add_cube(p, t, {9, 2, 1}, 0.5);
  CHECK(build_error(p, t) == "accepted");
}

// Moving interior vertices of a Kuhn grid, whose boundary stays in place:
// the mesh stays embedded exactly when every tetrahedron stays positive (the
// degree argument), which CGAL's orientation predicate decides independently
// of the overlap tests. Displacements on a 1/8 lattice make many tets flat
// or coplanar with their neighbours' facets.
TEST_CASE("moved interior vertices: accepted exactly when every tetrahedron stays positive", "[build][bad-input][randomized]") {
  const auto grid = testing::kuhn_grid(4, 4, 4, 1.0);
  std::vector<std::size_t> interior;
  for (std::size_t v = 0; v < grid.points.size(); ++v) {
    bool inside = true;
    for (double x : grid.points[v]) inside = inside && x > 0 && x < 4;
    if (inside) interior.push_back(v);
  }
  REQUIRE(interior.size() == 27);
  std::mt19937_64 rng(20261202);
  std::map<std::string, int> outcomes;
  for (int trial = 0; trial < 2000; ++trial) {
    auto points = grid.points;
    const int moved = 1 + trial % 3;
    for (int k = 0; k < moved; ++k) {
      const std::size_t v = interior[std::uniform_int_distribution<std::size_t>(0, interior.size() - 1)(rng)];
      for (double& x : points[v]) x += 0.125 * std::uniform_int_distribution<int>(-6, 6)(rng);
    }
    bool positive = true, flat = false;
    for (const auto& c : grid.tets) {
      const auto o = CGAL::orientation(Tr::Point(points[c[0]][0], points[c[0]][1], points[c[0]][2]),
                                       Tr::Point(points[c[1]][0], points[c[1]][1], points[c[1]][2]),
                                       Tr::Point(points[c[2]][0], points[c[2]][1], points[c[2]][2]),
                                       Tr::Point(points[c[3]][0], points[c[3]][1], points[c[3]][2]));
      positive = positive && o == CGAL::POSITIVE;
      flat = flat || o == CGAL::ZERO;
    }
    const std::string e = build_error(points, grid.tets);
    INFO("trial " << trial << ": " << e);
    if (positive) {
      REQUIRE(e == "accepted");
      ++outcomes["accepted"];
    } else if (flat) {
      REQUIRE(contains(e, "zero volume"));
      ++outcomes["zero volume"];
    } else {
      REQUIRE(e != "accepted");
      ++outcomes[overlap_kind(e)];
    }
  }
  for (const auto& [k, n] : outcomes) UNSCOPED_INFO(k << ": " << n);
  CHECK(outcomes["accepted"] > 300);
  CHECK(outcomes["zero volume"] > 300);
  CHECK(outcomes["across their common facet"] > 300);
}

// One vertex index of one tetrahedron changed, as the fuzzer does: the mesh
// then has a hole and, mostly, an overlap. Whatever is accepted must cover
// no sample point twice (exact point-in-tetrahedron tests at the centroids
// of the tets and at random points). The tally shows which test finds what.
TEST_CASE("a changed vertex index: no accepted mesh covers a point twice", "[build][bad-input][randomized]") {
  const auto grid = testing::kuhn_grid(3, 3, 3, 1.0);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> coordinate(0, 3);
  std::map<std::string, int> outcomes;
  for (int trial = 0; trial < 1000; ++trial) {
    auto tets = grid.tets;
    const std::size_t t = std::uniform_int_distribution<std::size_t>(0, tets.size() - 1)(rng);
    const std::size_t j = std::uniform_int_distribution<std::size_t>(0, 3)(rng);
    tets[t][j] = std::uniform_int_distribution<std::size_t>(0, grid.points.size() - 1)(rng);
    const std::string e = build_error(grid.points, tets);
    INFO("trial " << trial << ": tet " << t + 1 << ", vertex " << j << " -> " << tets[t][j] + 1 << ": " << e);
    if (e != "accepted") {
      ++outcomes[overlap_kind(e)];
      continue;
    }
    ++outcomes["accepted"];
    auto P = [&](std::size_t v) { return Tr::Point(grid.points[v][0], grid.points[v][1], grid.points[v][2]); };
    std::vector<Tr::Point> samples;
    for (const auto& c : tets) samples.push_back(CGAL::centroid(P(c[0]), P(c[1]), P(c[2]), P(c[3])));
    for (int k = 0; k < 200; ++k) samples.emplace_back(coordinate(rng), coordinate(rng), coordinate(rng));
    for (const auto& x : samples) {
      int covering = 0;
      for (const auto& c : tets) {
        std::array<Tr::Point, 4> q{P(c[0]), P(c[1]), P(c[2]), P(c[3])};
        if (CGAL::orientation(q[0], q[1], q[2], q[3]) == CGAL::NEGATIVE) std::swap(q[2], q[3]);
        bool inside = true;
        for (std::size_t m = 0; m < 4 && inside; ++m) {
          auto r = q;
          r[m] = x;
          inside = CGAL::orientation(r[0], r[1], r[2], r[3]) == CGAL::POSITIVE;
        }
        covering += inside;
      }
      REQUIRE(covering <= 1);
    }
  }
  for (const auto& [k, n] : outcomes) UNSCOPED_INFO(k << ": " << n);
  CHECK(outcomes["accepted"] > 0);
  CHECK(outcomes["about their common edge"] > 100);
}

// Every tetrahedron added on four boundary vertices of a filled cube lies in
// the cube, so it overlaps the mesh (or has zero volume): never accepted,
// whatever the tests that find it.
TEST_CASE("a tetrahedron added on boundary vertices of a block is never accepted", "[build][bad-input][randomized]") {
  const auto grid = testing::kuhn_grid(4, 4, 4, 1.0);
  std::vector<std::size_t> boundary;
  for (std::size_t v = 0; v < grid.points.size(); ++v)
    for (double x : grid.points[v])
      if (x == 0 || x == 4) {
        boundary.push_back(v);
        break;
      }
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<std::size_t> pick(0, boundary.size() - 1);
  std::map<std::string, int> outcomes;
  for (int trial = 0; trial < 500; ++trial) {
    auto tets = grid.tets;
    tets.push_back({boundary[pick(rng)], boundary[pick(rng)], boundary[pick(rng)], boundary[pick(rng)]});
    const std::string e = build_error(grid.points, tets);
    INFO("trial " << trial << ": " << e);
    REQUIRE(e != "accepted");
    ++outcomes[overlap_kind(e)];
  }
  for (const auto& [k, n] : outcomes) UNSCOPED_INFO(k << ": " << n);
  CHECK(outcomes["near their common vertex"] > 10);
}

// make_kuhn_grid(): the counts of a Kuhn grid, positive orientation checked
// exactly, a conforming mesh (every interior facet shared, the boundary the
// box's 2 * 2 * (xy + yz + zx) triangles), unused vertices dropped when
// cubes are left out, and its errors.
TEST_CASE("make_kuhn_grid: counts, exact orientation, conformity, dropped cubes and errors", "[build][kuhn]") {
  const IO::Medit_mesh g = make_kuhn_grid({3, 2, 4}, 0.5, {1, -2, 0.25});
  CHECK(g.vertices.size() == 4 * 3 * 5);
  CHECK(g.tetrahedra.size() == 6 * 3 * 2 * 4);
  CHECK(g.vertex_references.size() == g.vertices.size());
  CHECK(g.tetrahedron_references.size() == g.tetrahedra.size());
  CHECK(g.vertices.front() == std::array<double, 3>{1, -2, 0.25});
  CHECK(g.vertices[1] == std::array<double, 3>{1.5, -2, 0.25}); // x fastest
  CHECK(g.vertices.back() == std::array<double, 3>{2.5, -1, 2.25});
  Tr tr;
  const Tet_mesh_build_report report = build_triangulation_from_tets(g.vertices, g.tetrahedra, {}, tr);
  CHECK(report.reoriented_tets == 0); // every tetrahedron given positively oriented
  CHECK(report.unused_vertices == 0);
  CHECK(report.boundary_facets == 2 * 2 * (3 * 2 + 2 * 4 + 4 * 3));
  check_adjacency(tr);

  // The centre cube of 3^3 left out: a cavity; its 8 vertices stay (other cubes use them).
  const IO::Medit_mesh hollow = make_kuhn_grid({3, 3, 3}, 1, {0, 0, 0}, [](int i, int j, int k) { return !(i == 1 && j == 1 && k == 1); });
  CHECK(hollow.vertices.size() == 64);
  CHECK(hollow.tetrahedra.size() == 6 * 26);
  // Only the cubes (0,0,0) and (1,1,1), touching at one vertex: 8 + 8 - 1 vertices.
  const IO::Medit_mesh touching = make_kuhn_grid({2, 2, 2}, 1, {0, 0, 0}, [](int i, int j, int k) { return i == j && j == k; });
  CHECK(touching.vertices.size() == 15);
  for (const auto& t : touching.tetrahedra)
    for (std::size_t v : t) CHECK(v < touching.vertices.size());
  Tr tr2;
  CHECK(build_triangulation_from_tets(touching.vertices, touching.tetrahedra, {}, tr2).reoriented_tets == 0);

  CHECK_THROWS_AS(make_kuhn_grid({0, 1, 1}), std::invalid_argument);
  CHECK_THROWS_AS(make_kuhn_grid({1, 1, 1}, 0.0), std::invalid_argument);
  CHECK_THROWS_AS(make_kuhn_grid({1, 1, 1}, std::nan("")), std::invalid_argument);
  CHECK_THROWS_AS(make_kuhn_grid({2, 2, 2}, 1, {0, 0, 0}, [](int, int, int) { return false; }), std::invalid_argument);
}
