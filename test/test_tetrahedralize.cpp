// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Tetrahedral meshing with Mesh_3: closed surfaces from files and built-in
// shapes. Checks orientation (exact predicate), volume, the boundary as a
// closed oriented 2-manifold, its Euler characteristic, determinism, and
// every kind of bad input.
#include <CGAL_ext/tetrahedralize.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <catch2/catch.hpp>

#include <unistd.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using CGAL_ext::Input_error;
using CGAL_ext::Tetrahedralize_options;
using CGAL_ext::Tetrahedralize_report;
using CGAL_ext::IO::Medit_mesh;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;

const double pi = 3.14159265358979323846;

// The scratch directory of this test process (CTest runs test cases as
// parallel processes), named after the pid and removed at exit.
struct Scratch {
  fs::path path = fs::temp_directory_path() / ("cgal_ext_test_tetrahedralize_" + std::to_string(::getpid()));
  ~Scratch() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};
const fs::path& scratch() {
  static const Scratch s;
  fs::create_directories(s.path);
  return s.path;
}

std::string write_file(const std::string& name, const std::string& content) {
  const fs::path p = scratch() / name;
  std::ofstream(p, std::ios::binary) << content;
  return p.string();
}

// A closed polygonal surface in memory.
struct Surface {
  std::vector<std::array<double, 3>> points;
  std::vector<std::vector<int>> faces;

  std::string off() const {
    std::ostringstream s;
    s.precision(17);
    s << "OFF\n" << points.size() << " " << faces.size() << " 0\n";
    for (const auto& p : points) s << p[0] << " " << p[1] << " " << p[2] << "\n";
    for (const auto& f : faces) {
      s << f.size();
      for (int v : f) s << " " << v;
      s << "\n";
    }
    return s.str();
  }
  std::string stl() const { // triangles only
    std::ostringstream s;
    s.precision(17);
    s << "solid test\n";
    for (const auto& f : faces) {
      s << "facet normal 0 0 0\nouter loop\n";
      for (int v : f) s << "vertex " << points[v][0] << " " << points[v][1] << " " << points[v][2] << "\n";
      s << "endloop\nendfacet\n";
    }
    s << "endsolid test\n";
    return s.str();
  }
  // The enclosed volume (divergence theorem, faces fanned from their first vertex).
  double volume() const {
    double v = 0;
    for (const auto& f : faces)
      for (std::size_t i = 1; i + 1 < f.size(); ++i) {
        const auto &a = points[f[0]], &b = points[f[i]], &c = points[f[i + 1]];
        v += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
              a[2] * (b[0] * c[1] - b[1] * c[0])) /
             6;
      }
    return v;
  }
};

// The octahedron |x| + |y| + |z| <= r, outward oriented (volume 4 r^3 / 3).
Surface octahedron(double r = 1, double shift = 0) {
  Surface s;
  s.points = {{r + shift, 0, 0}, {-r + shift, 0, 0}, {shift, r, 0}, {shift, -r, 0}, {shift, 0, r}, {shift, 0, -r}};
  s.faces = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  return s;
}

// The cube [-1,1]^3 with quadrilateral faces, outward oriented.
Surface quad_cube() {
  Surface s;
  for (int i = 0; i < 8; ++i) s.points.push_back({i & 1 ? 1. : -1., i & 2 ? 1. : -1., i & 4 ? 1. : -1.});
  s.faces = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  return s;
}

K::Point_3 point(const Medit_mesh& m, std::size_t i) {
  return K::Point_3(m.vertices[i][0], m.vertices[i][1], m.vertices[i][2]);
}

double tet_volume(const Medit_mesh& m, const std::array<std::size_t, 4>& t) {
  return CGAL::volume(point(m, t[0]), point(m, t[1]), point(m, t[2]), point(m, t[3]));
}

double mesh_volume(const Medit_mesh& m) {
  double v = 0;
  for (const auto& t : m.tetrahedra) v += tet_volume(m, t);
  return v;
}

// The volume enclosed by the boundary triangles, by the divergence theorem:
// equal to the tets' volume only if the triangles are oriented outwards.
double boundary_volume(const Medit_mesh& m) {
  double v = 0;
  const K::Point_3 o(0, 0, 0);
  for (const auto& f : m.triangles) v += CGAL::volume(o, point(m, f[0]), point(m, f[1]), point(m, f[2]));
  return v;
}

// Checks the invariants that every mesh must satisfy; returns the Euler
// characteristic of the boundary.
long check_mesh(const Medit_mesh& m) {
  REQUIRE(!m.tetrahedra.empty());
  REQUIRE(m.vertex_references.size() == m.vertices.size());
  REQUIRE(m.tetrahedron_references.size() == m.tetrahedra.size());
  REQUIRE(m.triangle_references.size() == m.triangles.size());
  REQUIRE(m.edge_references.size() == m.edges.size());

  // Every tetrahedron positively oriented (exact predicate), every index in range.
  std::size_t not_positive = 0;
  std::vector<char> used(m.vertices.size(), 0);
  for (const auto& t : m.tetrahedra) {
    for (std::size_t v : t) {
      REQUIRE(v < m.vertices.size());
      used[v] = 1;
    }
    if (CGAL::orientation(point(m, t[0]), point(m, t[1]), point(m, t[2]), point(m, t[3])) != CGAL::POSITIVE)
      ++not_positive;
  }
  CHECK(not_positive == 0);
  // Every vertex used.
  CHECK(std::count(used.begin(), used.end(), 0) == 0);

  // The boundary: every undirected edge in exactly two triangles, every
  // directed edge in exactly one (a closed, consistently oriented surface).
  std::map<std::pair<std::size_t, std::size_t>, int> directed;
  std::set<std::size_t> boundary_vertices;
  for (const auto& f : m.triangles)
    for (int i = 0; i < 3; ++i) {
      REQUIRE(f[i] < m.vertices.size());
      boundary_vertices.insert(f[i]);
      ++directed[{f[i], f[(i + 1) % 3]}];
    }
  std::size_t bad_edges = 0, edges = 0;
  for (const auto& [e, n] : directed) {
    if (e.first < e.second) ++edges;
    const auto twin = directed.find({e.second, e.first});
    if (n != 1 || twin == directed.end() || twin->second != 1) ++bad_edges;
  }
  CHECK(bad_edges == 0);
  CHECK(edges * 2 == directed.size());
  // Outward orientation.
  CHECK(boundary_volume(m) == Approx(mesh_volume(m)).epsilon(1e-9));
  // Vertex references: 2 or less on the boundary, 3 inside.
  for (std::size_t i = 0; i < m.vertices.size(); ++i)
    if (!boundary_vertices.count(i)) CHECK(m.vertex_references[i] == 3);
  // Sharp edges are edges of the boundary.
  for (const auto& e : m.edges) CHECK(directed.count({e[0], e[1]}) + directed.count({e[1], e[0]}) == 2);

  return static_cast<long>(boundary_vertices.size()) - static_cast<long>(edges) +
         static_cast<long>(m.triangles.size());
}

bool same(const Medit_mesh& a, const Medit_mesh& b) {
  return a.vertices == b.vertices && a.vertex_references == b.vertex_references && a.tetrahedra == b.tetrahedra &&
         a.tetrahedron_references == b.tetrahedron_references && a.triangles == b.triangles &&
         a.triangle_references == b.triangle_references && a.edges == b.edges && a.edge_references == b.edge_references;
}

Tetrahedralize_options with_size(double size) {
  Tetrahedralize_options o;
  o.size = size;
  return o;
}

// The Input_error of `f`, whose message must contain every one of `words`.
template <class F>
void expect_error(F f, const std::vector<std::string>& words) {
  try {
    f();
    FAIL("no Input_error");
  } catch (const Input_error& e) {
    const std::string what = e.what();
    INFO(what);
    for (const std::string& w : words) CHECK(what.find(w) != std::string::npos);
  }
}

// tetrahedralize_surface(path) must throw an Input_error with these parts
// (an element of nullptr is not checked).
void expect_surface_error(const std::string& path, std::size_t line, const char* element, const std::string& problem) {
  try {
    CGAL_ext::tetrahedralize_surface(path);
    FAIL("no Input_error for " << path);
  } catch (const Input_error& e) {
    INFO(e.what());
    CHECK(e.file() == path);
    CHECK(e.line() == line);
    if (element) CHECK(e.element() == element);
    CHECK(e.problem() == problem);
  }
}

} // namespace

TEST_CASE("an octahedron: orientation, volume, closed boundary, sharp edges", "[tetrahedralize]") {
  const Surface s = octahedron();
  const std::string path = write_file("octahedron.off", s.off());
  Tetrahedralize_report report;
  const Medit_mesh m = CGAL_ext::tetrahedralize_surface(path, with_size(0.25), &report);
  CHECK(check_mesh(m) == 2); // a sphere
  // The faces are flat and the 12 edges sharp (109 degrees) and protected:
  // the volume is the octahedron's up to rounding.
  CHECK(mesh_volume(m) == Approx(s.volume()).epsilon(1e-6));
  CHECK(!m.edges.empty());
  CHECK(report.vertices == m.vertices.size());
  CHECK(report.tets == m.tetrahedra.size());
  CHECK(report.boundary_triangles == m.triangles.size());
  CHECK(report.seconds > 0);
  CHECK(report.domain.find("octahedron.off") != std::string::npos);
  CHECK(report.domain.find("size 0.25") != std::string::npos);
  CHECK(report.domain.find("repaired") == std::string::npos);
  // The 6 corners are vertices with reference 0.
  std::size_t corners = 0;
  for (int r : m.vertex_references) corners += r == 0;
  CHECK(corners == 6);
  for (int r : m.tetrahedron_references) CHECK(r == 1);
  for (int r : m.triangle_references) CHECK(r >= 1);
}

TEST_CASE("same input and options give the same mesh, and another seed still a valid mesh", "[tetrahedralize]") {
  const std::string path = write_file("octahedron_det.off", octahedron().off());
  const Medit_mesh a = CGAL_ext::tetrahedralize_surface(path, with_size(0.3));
  const Medit_mesh b = CGAL_ext::tetrahedralize_surface(path, with_size(0.3));
  CHECK(same(a, b));
  Tetrahedralize_options o = with_size(0.3);
  o.seed = 7;
  const Medit_mesh c = CGAL_ext::tetrahedralize_surface(path, o);
  CHECK(check_mesh(c) == 2);
  const Medit_mesh d = CGAL_ext::tetrahedralize_surface(path, o);
  CHECK(same(c, d));
  // Without optimization and without sharp features, still a valid mesh.
  o.optimize = false;
  o.sharp_features = false;
  const Medit_mesh e = CGAL_ext::tetrahedralize_surface(path, o);
  CHECK(check_mesh(e) == 2);
  CHECK(e.edges.empty());
  CHECK(mesh_volume(e) == Approx(octahedron().volume()).epsilon(0.05));
}

TEST_CASE("Mesh_3 in rounds: progress after each round, and a valid deterministic mesh", "[tetrahedralize]") {
  struct Call {
    std::size_t vertices, expected;
    double seconds;
  };
  const auto run = [](auto&& mesh, std::size_t round, std::vector<Call>& calls) {
    Tetrahedralize_options o = with_size(0.08);
    o.round_vertices = round;
    o.progress = [&calls](std::size_t v, std::size_t e, double t) { calls.push_back({v, e, t}); };
    return mesh(o);
  };
  SECTION("polyhedral domain with protected sharp edges") {
    const Surface s = octahedron();
    const std::string path = write_file("octahedron_rounds.off", s.off());
    const auto mesh = [&](const Tetrahedralize_options& o) { return CGAL_ext::tetrahedralize_surface(path, o); };
    std::vector<Call> one, rounds, again;
    const Medit_mesh m1 = run(mesh, 0, one), mr = run(mesh, 400, rounds), ma = run(mesh, 400, again);
    CHECK(one.empty()); // a small mesh: one call, no progress
    REQUIRE(rounds.size() >= 2);
    // The first round also holds the protection of the sharp edges (it has
    // room for it); each next one stops at its cap, 400 vertices further.
    CHECK(rounds[0].vertices > 400);
    for (std::size_t i = 1; i < rounds.size(); ++i) {
      CHECK(rounds[i].vertices == rounds[i - 1].vertices + 400);
      CHECK(rounds[i].expected == rounds[0].expected);
      CHECK(rounds[i].seconds >= rounds[i - 1].seconds);
    }
    CHECK(mr.vertices.size() > rounds.back().vertices);
    CHECK(check_mesh(mr) == 2);
    // The sharp edges stay protected across rounds: the volume is exact.
    CHECK(mesh_volume(mr) == Approx(s.volume()).epsilon(1e-6));
    CHECK(!mr.edges.empty());
    CHECK(same(mr, ma));
    CHECK(again.size() == rounds.size());
    // About the mesh of one call.
    CHECK(double(mr.tetrahedra.size()) == Approx(double(m1.tetrahedra.size())).epsilon(0.15));
  }
  SECTION("implicit domain") {
    const auto mesh = [&](const Tetrahedralize_options& o) { return CGAL_ext::tetrahedralize_builtin("ball", o); };
    std::vector<Call> rounds, again;
    const Medit_mesh mr = run(mesh, 500, rounds), ma = run(mesh, 500, again);
    REQUIRE(rounds.size() >= 2);
    for (std::size_t i = 0; i < rounds.size(); ++i) CHECK(rounds[i].vertices == 500 * (i + 1));
    CHECK(check_mesh(mr) == 2);
    CHECK(mesh_volume(mr) == Approx(4 * pi / 3).epsilon(0.03));
    CHECK(same(mr, ma));
  }
}

TEST_CASE("the memory limit stops Mesh_3 where the estimate is too low", "[tetrahedralize][errors]") {
  // A thin slab, 10 x 1 x 0.05: volume 0.5, so 5 * 0.5 / 0.5^3 = 20
  // tetrahedra are expected, but its sharp edges and faces need hundreds.
  Surface s = quad_cube();
  for (auto& p : s.points) p = {p[0] * 5, p[1] * 0.5, p[2] * 0.025};
  const std::string path = write_file("slab.off", s.off());
  Tetrahedralize_options o = with_size(0.5);
  // 3x the estimate: 10 vertices. The protection of the sharp edges stops
  // there (it does not stop exactly at the cap: it is reported as it is).
  o.memory_limit = 20 * CGAL_ext::bytes_per_tetrahedron * 3;
  expect_error([&] { CGAL_ext::tetrahedralize_surface(path, o); },
               {path, "meshing stopped at", "vertices (about", "the most that the memory limit of 9.6e-05 GB allows",
                "about 20 tetrahedra were expected", "larger memory limit"});
  o.memory_limit = -1;
  CHECK(CGAL_ext::tetrahedralize_surface(path, o).vertices.size() > 10);
}

TEST_CASE("the automatic size gives a mesh of a sensible size", "[tetrahedralize]") {
  const Surface s = octahedron(1);
  const std::string path = write_file("octahedron_auto.off", s.off());
  Tetrahedralize_report report;
  const Medit_mesh m = CGAL_ext::tetrahedralize_surface(path, {}, &report);
  check_mesh(m);
  // Bounding box diagonal 2 sqrt(3): size 0.173.
  CHECK(report.domain.find("size 0.173205") != std::string::npos);
  CHECK(report.domain.find("facet distance 0.0173205") != std::string::npos);
  CHECK(m.tetrahedra.size() > 500);
  CHECK(m.tetrahedra.size() < 20000);

  // A cap below the diagonal / 20 is the size; one above it, and a cap
  // with a size given, change nothing.
  Tetrahedralize_options capped;
  capped.max_automatic_size = 0.25;
  Tetrahedralize_report coarse;
  CHECK(same(CGAL_ext::tetrahedralize_surface(path, capped, &coarse), m));
  CHECK(coarse.size == report.size);
  capped.max_automatic_size = 0.1;
  Tetrahedralize_report fine;
  const Medit_mesh finer = CGAL_ext::tetrahedralize_surface(path, capped, &fine);
  check_mesh(finer);
  CHECK(fine.size == 0.1);
  CHECK(fine.domain.find("size 0.1,") != std::string::npos);
  CHECK(finer.tetrahedra.size() > 2 * m.tetrahedra.size()); // (0.173 / 0.1)^3 = 5.2 times the density
  capped.size = 0.3;
  Tetrahedralize_report given;
  CGAL_ext::tetrahedralize_surface(path, capped, &given);
  CHECK(given.size == 0.3);
  // The memory refusal says where a capped size came from.
  capped.size = 0;
  capped.max_automatic_size = 1e-4;
  capped.memory_limit = 1e9;
  expect_error([&] { CGAL_ext::tetrahedralize_surface(path, capped); },
               {path, "the size 0.0001 (automatic: the diagonal / 20 capped at 0.0001) is too small",
                "give a larger size or cap"});
}

TEST_CASE("STL, inside-out and quadrilateral inputs are meshed and their repairs reported", "[tetrahedralize]") {
  SECTION("STL") {
    const Surface s = octahedron(1, 0.5);
    const Medit_mesh m = CGAL_ext::tetrahedralize_surface(write_file("octahedron.STL", s.stl()), with_size(0.3));
    CHECK(check_mesh(m) == 2);
    CHECK(mesh_volume(m) == Approx(s.volume()).epsilon(1e-6));
  }
  SECTION("inside-out") {
    Surface s = octahedron();
    for (auto& f : s.faces) std::reverse(f.begin(), f.end());
    Tetrahedralize_report report;
    const Medit_mesh m =
        CGAL_ext::tetrahedralize_surface(write_file("inside_out.off", s.off()), with_size(0.3), &report);
    CHECK(check_mesh(m) == 2);
    CHECK(mesh_volume(m) == Approx(-s.volume()).epsilon(1e-6));
    CHECK(report.domain.find("repaired") != std::string::npos);
    CHECK(report.domain.find("inside-out") != std::string::npos);
  }
  SECTION("one face flipped: the soup is reoriented") {
    Surface s = octahedron();
    std::reverse(s.faces[3].begin(), s.faces[3].end());
    Tetrahedralize_report report;
    const Medit_mesh m =
        CGAL_ext::tetrahedralize_surface(write_file("one_flipped.off", s.off()), with_size(0.3), &report);
    CHECK(check_mesh(m) == 2);
    CHECK(report.domain.find("repaired: polygon soup") != std::string::npos);
  }
  SECTION("quadrilaterals") {
    const Surface s = quad_cube();
    Tetrahedralize_report report;
    const Medit_mesh m = CGAL_ext::tetrahedralize_surface(write_file("quad_cube.obj", [&] {
      std::ostringstream o;
      for (const auto& p : s.points) o << "v " << p[0] << " " << p[1] << " " << p[2] << "\n";
      for (const auto& f : s.faces) o << "f " << f[0] + 1 << " " << f[1] + 1 << " " << f[2] + 1 << " " << f[3] + 1 << "\n";
      return o.str();
    }()), with_size(0.5), &report);
    CHECK(check_mesh(m) == 2);
    CHECK(mesh_volume(m) == Approx(8).epsilon(1e-9));
    CHECK(report.domain.find("6 faces with more than 3 vertices triangulated") != std::string::npos);
  }
}

TEST_CASE("built-in ball: volume close to 4/3 pi", "[tetrahedralize][builtin]") {
  Tetrahedralize_report report;
  const Medit_mesh m = CGAL_ext::tetrahedralize_builtin("ball", with_size(0.25), &report);
  CHECK(check_mesh(m) == 2);
  // The boundary is inscribed: slightly less, within the facet distance.
  CHECK(mesh_volume(m) < 4 * pi / 3);
  CHECK(mesh_volume(m) == Approx(4 * pi / 3).epsilon(0.04));
  CHECK(m.edges.empty());
  CHECK(report.domain.find("ball") != std::string::npos);
}

TEST_CASE("built-in torus: genus 1 (boundary Euler characteristic 0), volume 2 pi^2 R r^2", "[tetrahedralize][builtin]") {
  const Medit_mesh m = CGAL_ext::tetrahedralize_builtin("torus", with_size(0.2));
  CHECK(check_mesh(m) == 0);
  CHECK(mesh_volume(m) == Approx(2 * pi * pi * 0.16).epsilon(0.05));
}

TEST_CASE("built-in box_with_hole: volume 4 - 0.16 pi, genus 1, sharp edges kept", "[tetrahedralize][builtin]") {
  Tetrahedralize_report report;
  const Medit_mesh m = CGAL_ext::tetrahedralize_builtin("box_with_hole", with_size(0.3), &report);
  CHECK(check_mesh(m) == 0);
  CHECK(mesh_volume(m) == Approx(4 - 0.16 * pi).epsilon(0.01));
  CHECK(!m.edges.empty());
  // The 8 corners of the box.
  std::size_t corners = 0;
  for (int r : m.vertex_references) corners += r == 0;
  CHECK(corners == 8);
  // Every vertex of the box's vertical edges is on a protected edge.
  std::set<std::size_t> on_edges;
  for (const auto& e : m.edges) on_edges.insert(e.begin(), e.end());
  for (std::size_t i = 0; i < m.vertices.size(); ++i) {
    const auto& p = m.vertices[i];
    if (std::abs(std::abs(p[0]) - 1) < 1e-12 && std::abs(std::abs(p[1]) - 1) < 1e-12) CHECK(on_edges.count(i) == 1);
  }
}

TEST_CASE("built-in cube and blobby", "[tetrahedralize][builtin]") {
  const Medit_mesh cube = CGAL_ext::tetrahedralize_builtin("cube", with_size(0.5));
  CHECK(check_mesh(cube) == 2);
  CHECK(mesh_volume(cube) == Approx(8).epsilon(1e-9));
  const Medit_mesh blobby = CGAL_ext::tetrahedralize_builtin("blobby", with_size(0.2));
  CHECK(check_mesh(blobby) == 2);
  CHECK(mesh_volume(blobby) > 4 * pi / 3 * 0.8 * 0.8 * 0.8); // more than the central ball
  // Deterministic too.
  CHECK(same(blobby, CGAL_ext::tetrahedralize_builtin("blobby", with_size(0.2))));
}

TEST_CASE("builtin_shape_names lists the shapes", "[tetrahedralize][builtin]") {
  const auto names = CGAL_ext::builtin_shape_names();
  for (const char* n : {"ball", "torus", "box_with_hole", "blobby", "cube"})
    CHECK(std::find(names.begin(), names.end(), n) != names.end());
}

TEST_CASE("bad input: a clear Input_error", "[tetrahedralize][errors]") {
  using CGAL_ext::tetrahedralize_builtin;
  using CGAL_ext::tetrahedralize_surface;
  const std::string good = write_file("good.off", octahedron().off());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();

  SECTION("a cap of the automatic size that is negative or not finite") {
    for (double cap : {-1.0, nan, inf}) {
      Tetrahedralize_options o;
      o.max_automatic_size = cap;
      expect_error([&] { tetrahedralize_builtin("ball", o); }, {"the cap of the automatic size must be positive"});
    }
  }
  SECTION("missing file") {
    const std::string path = (scratch() / "no_such_file.off").string();
    expect_error([&] { tetrahedralize_surface(path); }, {path, "cannot open"});
  }
  SECTION("unsupported extension") {
    const std::string path = write_file("octahedron.mesh", octahedron().off());
    expect_error([&] { tetrahedralize_surface(path); }, {path, "unsupported extension '.mesh'", ".off", ".stl"});
    const std::string none = write_file("octahedron", octahedron().off());
    expect_error([&] { tetrahedralize_surface(none); }, {"no file extension"});
  }
  SECTION("garbage and empty files") {
    expect_error([&] { tetrahedralize_surface(write_file("garbage.off", "this is not OFF\n")); },
                 {"garbage.off:1: not an OFF file: expected 'OFF' or the counts, found 'this'"});
    expect_error([&] { tetrahedralize_surface(write_file("empty.off", "OFF\n0 0 0\n")); }, {"empty"});
  }
  SECTION("open surface") {
    Surface s = octahedron();
    s.faces.pop_back();
    expect_error([&] { tetrahedralize_surface(write_file("open.off", s.off())); },
                 {"the surface is not closed (3 border edges)"});
  }
  SECTION("self-intersecting surface") {
    Surface s = octahedron();
    const Surface t = octahedron(1, 0.5);
    for (const auto& p : t.points) s.points.push_back(p);
    for (auto f : t.faces) {
      for (int& v : f) v += 6;
      s.faces.push_back(f);
    }
    expect_error([&] { tetrahedralize_surface(write_file("two.off", s.off())); }, {"self-intersecting"});
  }
  SECTION("non-manifold surface") {
    // Two octahedra sharing a vertex: the soup repair cannot make it a manifold.
    Surface s = octahedron();
    Surface t = octahedron(1, 2); // its vertex 1 is (1, 0, 0), vertex 0 of the first
    for (const auto& p : t.points) s.points.push_back(p);
    for (auto f : t.faces) {
      for (int& v : f) v = v == 1 ? 0 : v + 6;
      s.faces.push_back(f);
    }
    expect_error([&] { tetrahedralize_surface(write_file("pinched.off", s.off())); }, {"2-manifold"});
  }
  SECTION("bad sizes") {
    for (double size : {-1.0, nan, inf})
      expect_error([&] { tetrahedralize_surface(good, with_size(size)); }, {good, "size", "positive and finite"});
    expect_error([&] { tetrahedralize_builtin("ball", with_size(-0.5)); }, {"ball", "size", "(got -0.5)"});
    Tetrahedralize_options o;
    o.facet_distance = nan;
    expect_error([&] { tetrahedralize_surface(good, o); }, {"facet distance", "nan"});
    expect_error([&] { tetrahedralize_builtin("torus", with_size(1e-4)); }, {"too small", "tetrahedra"});
  }
  SECTION("a size whose mesh would not fit in memory is refused before Mesh_3, with the estimate") {
    // A unit cube at size 0.004: about 7.8e7 tetrahedra, 125 GB.
    REQUIRE(CGAL_ext::physical_memory_bytes() > 1e9);
    REQUIRE(CGAL_ext::physical_memory_bytes() < 1e14);
    expect_error([&] { tetrahedralize_builtin("cube", with_size(0.004)); },
                 {"cube", "too small", "tetrahedra would be made, needing about", "GB, more than the memory of this machine"});
    Tetrahedralize_options o = with_size(0.3);
    o.memory_limit = 1e5; // 0.1 MB: a few dozen tetrahedra
    expect_error([&] { tetrahedralize_builtin("ball", o); }, {"ball", "more than the memory limit of 0.0001 GB"});
    o.memory_limit = -1; // no limit
    CHECK(!tetrahedralize_builtin("ball", o).tetrahedra.empty());
    o.memory_limit = nan;
    expect_error([&] { tetrahedralize_builtin("ball", o); }, {"memory limit must be finite"});
  }
  SECTION("unknown built-in shape") {
    expect_error([&] { tetrahedralize_builtin("dodecahedron"); },
                 {"dodecahedron", "unknown", "ball", "torus", "box_with_hole", "blobby", "cube"});
  }
}

TEST_CASE("OBJ face indices 0 and out of range are reported with the file and the line", "[tetrahedralize][errors]") {
  using CGAL_ext::tetrahedralize_surface;
  // A tetrahedron with its third face (line 7) given as `bad`.
  const auto tetrahedron = [](const std::string& bad) {
    return "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\n" + bad + "\nf 2 3 4\n";
  };
  const auto expect = [&](const std::string& name, const std::string& bad, const std::string& problem) {
    expect_surface_error(write_file(name, tetrahedron(bad)), 7, "face 3", problem);
  };
  expect("zero.obj", "f 1 0 3", "vertex index 0 is not valid: OBJ indices start at 1 (negative ones count back)");
  expect("zero_slashes.obj", "f 1/1/1 0/2/2 3/3/3",
         "vertex index 0 is not valid: OBJ indices start at 1 (negative ones count back)");
  expect("five.obj", "f 1 5 3", "vertex index 5 is out of range 1..4 (4 vertices in the file)");
  expect("minus_seven.obj", "f 1 -7 3", "vertex index -7 is out of range -4..-1 (4 vertices before it)");
  expect("word.obj", "f 1 two 3", "expected a vertex index, found 'two'");
  expect("long.obj", "f 1 " + std::string(10000000, 'x') + " 3",
         "expected a vertex index, found '" + std::string(40, 'x') + "...' (10000000 characters)");
  // Vertices used by no face (found by fuzz_surface: CGAL's orientation
  // crashed on them) are removed, and the repair reported.
  Tetrahedralize_report report;
  const Medit_mesh unused = tetrahedralize_surface(
      write_file("unused.obj", tetrahedron("f 1 4 3") + "v 0 0 0\nv 5 5 5\n"), with_size(0.3), &report);
  CHECK(!unused.tetrahedra.empty());
  CHECK(report.domain.find("2 vertices used by no face removed") != std::string::npos);
  // Found by fuzz_surface: a polygon with a repeated point, or all its
  // points on a line, made CGAL's triangulation bind a null reference.
  const std::string fuzzed = std::string(CGAL_EXT_TEST_DATA_DIR) + "/fuzz/degenerate_polygon.obj";
  expect_error([&] { tetrahedralize_surface(fuzzed); }, {fuzzed, "is not a convex planar polygon"});
  expect_error([&] { tetrahedralize_surface(write_file("line.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 3 0 0\nf 1 2 3 4\nf 4 3 2 1\n")); },
               {"line.obj", "a face with 4 vertices, from (0, 0, 0), is not a convex planar polygon", "triangulate it first"});
  // A non-convex (L-shaped) hexagon is refused too.
  expect_error([&] { tetrahedralize_surface(write_file("l.obj", "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\nv 0 0 1\nf 1 2 3 4 5 6\nf 1 7 2\n")); },
               {"l.obj", "a face with 6 vertices, from (0, 0, 0), is not a convex planar polygon"});
  // Relative indices in range still work: -1 is the last vertex read.
  const Medit_mesh m = tetrahedralize_surface(write_file("relative.obj", tetrahedron("f -4 -1 -2")), with_size(0.3));
  CHECK(!m.tetrahedra.empty());
}

TEST_CASE("OFF counts and faces are checked with the file and the line before CGAL's reader", "[tetrahedralize][errors]") {
  using CGAL_ext::tetrahedralize_surface;
  // A tetrahedron, with a comment line, its third face (line 10) given as `face`.
  const auto tetrahedron = [](const std::string& counts, const std::string& face) {
    return "OFF\n" + counts + "\n# vertices\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n" + face + "\n3 1 2 3\n";
  };
  const auto expect = [&](const std::string& name, const std::string& counts, const std::string& face,
                          std::size_t line, const char* element, const std::string& problem) {
    expect_surface_error(write_file(name, tetrahedron(counts, face)), line, element, problem);
  };
  // Found by fuzz_surface: CGAL converts a face's vertex count -1, read as a
  // double, to size_t (undefined behaviour).
  expect("minus_one.off", "4 4 0", "-1 0 3 2", 10, "face 3",
         "expected the number of its vertices (a non-negative integer), found '-1'");
  expect("huge.off", "4 4 0", "1e30 0 3 2", 10, "face 3",
         "expected the number of its vertices (a non-negative integer), found '1e30'");
  expect("short.off", "4 4 0", "4 0 3 2", 10, "face 3", "4 vertex indices announced, 3 found");
  expect("index.off", "4 4 0", "3 0 4 2", 10, "face 3", "vertex index '4' is not in 0..3 (4 vertices in the file)");
  expect("negative_index.off", "4 4 0", "3 0 -1 2", 10, "face 3",
         "vertex index '-1' is not in 0..3 (4 vertices in the file)");
  expect("counts.off", "4 -4 0", "3 0 3 2", 2, "",
         "expected the vertex and face counts (non-negative integers), found '4' '-4'");
  expect("short_vertex.off", "4 4 0\n0 0", "3 0 3 2", 3, "vertex 1", "3 coordinates expected, 2 found");
  expect("word_vertex.off", "4 4 0\n0 zero 0", "3 0 3 2", 3, "vertex 1", "expected a coordinate, found 'zero'");
  expect("nan_vertex.off", "4 4 0\n0 nan 0", "3 0 3 2", 3, "vertex 1", "a coordinate is not finite");
  // Colours after the indices, and comments, are still read; colours out of
  // range (undefined behaviour in CGAL's reader, found by fuzz_surface) are
  // ignored, as all colours are.
  const Medit_mesh m = tetrahedralize_surface(write_file("colours.off", tetrahedron("4 4 0", "3 0 3 2 255 0 0 # red")),
                                              with_size(0.3));
  CHECK(!m.tetrahedra.empty());
  const Medit_mesh c = tetrahedralize_surface(
      write_file("coff.off", "COFF\n4 4 0\n0 0 0 1e10 -1 7\n1 0 0 1 1 1\n0 1 0 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2 "
                             "9999 1\n3 1 2 3\n"),
      with_size(0.3));
  CHECK(!c.tetrahedra.empty());
  // Homogeneous coordinates: the same tetrahedron, scaled by w = 2.
  const Medit_mesh h = tetrahedralize_surface(
      write_file("homogeneous.off", "4OFF\n4 4 0\n0 0 0 2\n2 0 0 2\n0 2 0 2\n0 0 2 2\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 "
                                    "2 3\n"),
      with_size(0.3));
  CHECK(mesh_volume(h) == Approx(1.0 / 6).epsilon(1e-9));
  expect_error([&] { tetrahedralize_surface(write_file("binary.off", "OFF BINARY\n\x62\x6c\x00\x20")); },
               {"binary.off:1: binary OFF is not supported", "write ASCII OFF, binary STL or binary PLY"});
  expect_error([&] { tetrahedralize_surface(write_file("n.off", "nOFF\n3\n4 4 0\n")); },
               {"n.off:1: an OFF file of another dimension (nOFF) is not supported"});
}

TEST_CASE("PLY headers are checked with the file and the line before CGAL's reader", "[tetrahedralize][errors]") {
  using CGAL_ext::tetrahedralize_surface;
  const std::string body = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  const std::string vertex = "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n";
  const std::string face = "element face 4\nproperty list uchar int vertex_indices\n";
  const auto expect = [&](const std::string& name, const std::string& header, std::size_t line,
                          const std::string& problem, bool then_body = true) {
    expect_surface_error(write_file(name, then_body ? header + body : header), line, nullptr, problem);
  };
  // Found by fuzz_surface: CGAL adds a property to the last element, which
  // does not exist yet (undefined behaviour).
  expect("property_first.ply", "ply\nformat ascii 1.0\nproperty float x\n" + vertex + face + "end_header\n", 3,
         "a property before any element");
  expect("count.ply", "ply\nformat ascii 1.0\nelement vertex -4\n", 3,
         "expected 'element NAME COUNT', COUNT a non-negative integer");
  expect("format.ply", "ply\nformat text 1.0\n" + vertex, 2,
         "expected 'format ascii|binary_little_endian|binary_big_endian VERSION'");
  expect("type.ply", "ply\nformat ascii 1.0\nelement vertex 4\nproperty real x\n", 4,
         "expected 'property TYPE NAME' or 'property list TYPE TYPE NAME'");
  expect("keyword.ply", "ply\nformat ascii 1.0\nvertices 4\n", 3, "unknown PLY header keyword 'vertices'");
  expect("magic.ply", "plx\nformat ascii 1.0\n", 1, "not a PLY file: the first line is not 'ply'");
  // Found by fuzz_surface: '#' starts no comment in a PLY header; CGAL read
  // on past `end_header#0` into a property before any element.
  expect("hash.ply", "ply\nformat ascii 1.0\nend_header#0\n", 3, "unknown PLY header keyword 'end_header#0'", false);
  expect("no_end.ply", "ply\nformat ascii 1.0\n" + vertex + face, 0, "the PLY header has no 'end_header' line", false);
  expect("no_end_then_body.ply", "ply\nformat ascii 1.0\n" + vertex + face, 9, "unknown PLY header keyword '0'");
  // Found by fuzz_surface: CGAL reads coordinates of another type through a
  // null pointer (a crash in Release builds too).
  expect("uint16.ply",
         "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty uint16 z\n" + face +
             "end_header\n",
         6, "the coordinate z has type uint16: float or double expected");
  expect("no_z.ply", "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n" + face +
                         "end_header\n",
         3, "the vertex element needs the properties x, y and z, of type float or double");
  // Found by fuzz_surface: CGAL resizes a face's list to the count read
  // before reading it (a 300-byte file asked for 7.6 GB).
  expect("huge_list.ply", "ply\nformat ascii 1.0\n" + vertex + face + "end_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n" +
                              "1900000000 0 2 1\n",
         0, "the list 'vertex_indices' has '1900000000' entries, more than the rest of the file can hold, or not a count",
         false);
  expect("truncated.ply", "ply\nformat ascii 1.0\n" + vertex + face + "end_header\n0 0 0\n1 0 0\n0 1 0\n0 0\n",
         0, "the file ends here (truncated file?)", false);
  {
    std::string binary = "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty double x\nproperty double "
                         "y\nproperty double z\nelement face 1\nproperty list int int vertex_indices\nend_header\n";
    binary += std::string(24, '\0');                      // the vertex (0, 0, 0)
    binary += std::string("\x00\x00\x00\x72", 4);        // a count of 1912602624, little-endian
    binary += std::string(12, '\0');
    expect("huge_list_binary.ply", binary, 0,
           "the list 'vertex_indices' has 1912602624 entries, more than the rest of the file can hold, or not a count",
           false);
  }
  // A good header, with a comment, is read.
  const Medit_mesh m = tetrahedralize_surface(
      write_file("good.ply", "ply\nformat ascii 1.0\ncomment made by hand\n" + vertex + face + "end_header\n" + body),
      with_size(0.3));
  CHECK(!m.tetrahedra.empty());
}

TEST_CASE("a directory given as a surface file is reported as a directory", "[tetrahedralize][errors]") {
  const fs::path dir = scratch() / "a_directory.off";
  fs::create_directories(dir);
  expect_error([&] { CGAL_ext::tetrahedralize_surface(dir.string()); },
               {dir.string() + ": is a directory, not a file"});
}
