// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
// Metric tensors (validation, square root) and the piecewise-linear metric
// field on a tet mesh: interpolation of A, curl per cell, connection,
// caching and threads, property maps, input errors.
#include <CGAL_ext/Cell_transport_3.h>
#include <CGAL_ext/Connection_3.h>
#include <CGAL_ext/Input_error.h>
#include <CGAL_ext/Metric_field_3.h>
#include <CGAL_ext/Metric_tensor.h>
#include <CGAL_ext/Property_map_metric_field_3.h>
#include <CGAL_ext/build_triangulation_from_tets.h>
#include <CGAL_ext/make_kuhn_grid.h>

#include <catch2/catch.hpp>

#include "test_support.h"

#include <boost/property_map/property_map.hpp>

#include <Eigen/Geometry>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <vector>

namespace {

using CGAL_ext::testing::Random;

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Tr = CGAL_ext::Tet_mesh_triangulation_3<K>;
using Field = CGAL_ext::Metric_field_3<Tr>;
using Point = Tr::Point;
using M3 = Eigen::Matrix3d;
using V3 = Eigen::Vector3d;


struct Mesh {
  std::vector<std::array<double, 3>> points;
  std::vector<std::array<std::size_t, 4>> tets;
};

// The unit cube cut into n^3 cubes, each into 6 Kuhn tets around its main diagonal.
Mesh kuhn_grid(int n) {
  CGAL_ext::IO::Medit_mesh g = CGAL_ext::make_kuhn_grid({n, n, n}, 1.0 / n);
  return Mesh{std::move(g.vertices), std::move(g.tetrahedra)};
}

// kuhn_grid(n) in tr, built by build_triangulation_from_tets().
Mesh kuhn_triangulation(int n, Tr& tr) {
  Mesh m = kuhn_grid(n);
  CGAL_ext::build_triangulation_from_tets(m.points, m.tets, {}, tr);
  return m;
}

V3 vec(const Point& p) { return V3(p.x(), p.y(), p.z()); }

// A field whose A is exactly linear in space: A(x) = A0 + x B0 + y B1 + z B2
// (symmetric, SPD on the unit cube), and its exact curl.
struct Linear_A {
  M3 A0;
  std::array<M3, 3> B;
  M3 A(const V3& x) const { return A0 + x(0) * B[0] + x(1) * B[1] + x(2) * B[2]; }
  M3 curl() const {
    M3 c;
    for (int i = 0; i < 3; ++i)
      c.col(i) = V3(B[1](2, i) - B[2](1, i), B[2](0, i) - B[0](2, i), B[0](1, i) - B[1](0, i));
    return c;
  }
};

Linear_A random_linear_A(Random& r) {
  Linear_A f;
  f.A0 = 2 * M3::Identity();
  for (M3& b : f.B) {
    M3 m;
    for (int i = 0; i < 9; ++i) m.data()[i] = r.uniform(-0.3, 0.3);
    b = m + m.transpose();
  }
  return f;
}

} // namespace

TEST_CASE("check_metric_tensor names what is wrong", "[metric]") {
  using CGAL_ext::check_metric_tensor;
  CHECK(check_metric_tensor(M3::Identity()).empty());
  M3 g = M3::Identity();
  g(1, 2) = g(2, 1) = 0.3;
  CHECK(check_metric_tensor(g).empty());
  M3 nan = g;
  nan(0, 1) = std::numeric_limits<double>::quiet_NaN();
  CHECK(check_metric_tensor(nan).find("non-finite") != std::string::npos);
  M3 inf = g;
  inf(2, 2) = std::numeric_limits<double>::infinity();
  CHECK(check_metric_tensor(inf).find("non-finite") != std::string::npos);
  M3 asym = g;
  asym(0, 1) = 1e-9; // g(1,0) == 0
  CHECK(check_metric_tensor(asym).find("not symmetric") != std::string::npos);
  M3 nearly = g;
  nearly(0, 1) = 1e-14; // within the relative 1e-12
  CHECK(check_metric_tensor(nearly).empty());
  CHECK(check_metric_tensor(V3(1, -1, 1).asDiagonal().toDenseMatrix()).find("not positive definite") != std::string::npos);
  CHECK(check_metric_tensor(V3(1, 0, 1).asDiagonal().toDenseMatrix()).find("not positive definite") != std::string::npos);
  CHECK(check_metric_tensor(M3::Zero()).find("not positive definite") != std::string::npos);
  CHECK(check_metric_tensor(V3(1, 1e-15, 1).asDiagonal().toDenseMatrix()).find("condition") != std::string::npos);
  CHECK(check_metric_tensor(V3(1, 1e-13, 1).asDiagonal().toDenseMatrix()).empty());
}

TEST_CASE("sqrt_spd is the symmetric positive-definite root", "[metric]") {
  Random r(21);
  for (int k = 0; k < 100; ++k) {
    const M3 g = r.spd(1e-4, 1e4);
    const M3 A = CGAL_ext::sqrt_spd(g);
    CHECK(A == A.transpose()); // exactly symmetric
    CHECK((A * A - g).norm() <= 1e-12 * g.norm());
    CHECK(Eigen::SelfAdjointEigenSolver<M3>(A).eigenvalues().minCoeff() > 0);
  }
  CHECK((CGAL_ext::sqrt_spd(V3(4, 9, 16).asDiagonal().toDenseMatrix()) - V3(2, 3, 4).asDiagonal().toDenseMatrix())
            .norm() <= 1e-15);
}

TEST_CASE("check_metric_tensor and sqrt_spd work up to the ends of the double range", "[metric]") {
  using CGAL_ext::check_metric_tensor;
  using CGAL_ext::sqrt_spd;
  // g + g^T overflows for 1e308 I: neither the check nor the root may.
  const M3 big = 1e308 * M3::Identity();
  CHECK(check_metric_tensor(big).empty());
  const M3 A = sqrt_spd(big);
  REQUIRE(A.allFinite());
  CHECK((A - 1e154 * M3::Identity()).norm() <= 1e-15 * 1e154);
  // A power of two 2^(2k) scales the root by exactly 2^k.
  M3 g = M3::Identity();
  g(1, 2) = g(2, 1) = 0.3;
  CHECK(check_metric_tensor(std::ldexp(1.0, 1020) * g).empty());
  CHECK(sqrt_spd(std::ldexp(1.0, 1020) * g) == std::ldexp(1.0, 510) * sqrt_spd(g));
  CHECK(sqrt_spd(std::ldexp(1.0, -1020) * g) == std::ldexp(1.0, -510) * sqrt_spd(g));
  // Indefinite with huge entries: the eigenvalue, not NaN.
  CHECK(check_metric_tensor(V3(1e308, -1e308, 1e308).asDiagonal().toDenseMatrix()) ==
        "the metric tensor is not positive definite (smallest eigenvalue -1e+308)");
  // SPD, but the largest eigenvalue, 1.7e308 (1 + 2 * 0.9), is not a double.
  M3 over = M3::Constant(0.9 * 1.7e308);
  over.diagonal().setConstant(1.7e308);
  const std::string too_large = check_metric_tensor(over);
  CHECK(too_large.find("too large for double precision (largest eigenvalue 4.76e+308") != std::string::npos);
  // The inverse of 1e-320 I overflows; 1e-300 I is fine.
  CHECK(check_metric_tensor(1e-320 * M3::Identity())
            .find("too small for double precision (smallest eigenvalue 9.99989e-321") != std::string::npos);
  CHECK(check_metric_tensor(1e-300 * M3::Identity()).empty());
}

TEST_CASE("A is interpolated linearly and the curl matches doc/math.md section 2", "[metric_field]") {
  Random r(22);
  Tr tr;
  const Mesh m = kuhn_triangulation(2, tr);
  std::vector<M3> g(m.points.size());
  for (M3& x : g) x = r.spd(0.2, 5);
  const Field field(tr, g);
  REQUIRE(field.number_of_domain_cells() == m.tets.size());
  for (auto v : tr.finite_vertex_handles())
    CHECK((field.metric(v) - g[v->info()]).norm() <= 1e-12 * g[v->info()].norm());
  for (auto c : tr.finite_cell_handles()) {
    // Independent formula: lambda = T [x; 1] with T the inverse of the 4x4
    // matrix of homogeneous vertex coordinates, d_k A = sum_v T[v][k] A_v.
    Eigen::Matrix4d P;
    std::array<M3, 4> Av;
    for (int v = 0; v < 4; ++v) {
      P.col(v) << vec(c->vertex(v)->point()), 1;
      Av[v] = field.sqrt_metric(c->vertex(v));
    }
    const Eigen::Matrix4d T = P.inverse();
    std::array<M3, 3> dA;
    for (int k = 0; k < 3; ++k) {
      dA[k].setZero();
      for (int v = 0; v < 4; ++v) dA[k] += T(v, k) * Av[v];
    }
    M3 curl;
    for (int i = 0; i < 3; ++i)
      curl.col(i) = V3(dA[1](2, i) - dA[2](1, i), dA[2](0, i) - dA[0](2, i), dA[0](1, i) - dA[1](0, i));
    CHECK((field.curl(c) - curl).norm() <= 1e-12 * (1 + curl.norm()));

    // At the vertices, A_at is the vertex value; inside, the barycentric mean.
    for (int v = 0; v < 4; ++v) CHECK((field.A_at(c, c->vertex(v)->point()) - Av[v]).norm() <= 1e-14 * Av[v].norm());
    const std::array<double, 4> l{0.1, 0.2, 0.3, 0.4};
    V3 x = V3::Zero();
    M3 Ax = M3::Zero();
    for (int v = 0; v < 4; ++v) {
      x += l[v] * vec(c->vertex(v)->point());
      Ax += l[v] * Av[v];
    }
    const Point px(x(0), x(1), x(2));
    CHECK((field.A_at(c, px) - Ax).norm() <= 1e-14 * Ax.norm());
    const Eigen::Vector4d bl = field.barycentric_coordinates(c, px);
    CHECK((bl - Eigen::Vector4d(l[0], l[1], l[2], l[3])).norm() <= 1e-14);
    // The connection at the point is the closed form at A(x).
    CHECK((field.connection(c, px) - CGAL_ext::connection_one_form_by_solve(Ax, curl)).norm() <=
          1e-10 * (1 + field.connection(c, px).norm()));
  }
}

TEST_CASE("an exactly linear A is reproduced, with its exact curl in every cell", "[metric_field]") {
  Random r(23);
  const Linear_A lin = random_linear_A(r);
  const Mesh m = kuhn_grid(3);
  // A must be SPD at the cube's corners (then everywhere in it, A being linear),
  // or the root of A^2 would not give A back.
  for (double x : {0.0, 1.0})
    for (double y : {0.0, 1.0})
      for (double z : {0.0, 1.0})
        REQUIRE(Eigen::SelfAdjointEigenSolver<M3>(lin.A(V3(x, y, z))).eigenvalues().minCoeff() > 0.1);
  Tr tr;
  CGAL_ext::build_triangulation_from_tets(m.points, m.tets, {}, tr);
  // g = A(x)^2 at the vertices, through the callable constructor.
  const Field field(tr, [&](const Point& p) -> M3 {
    const M3 A = lin.A(vec(p));
    return A * A;
  });
  const M3 exact = lin.curl();
  REQUIRE(exact.norm() > 0.1);
  for (auto c : tr.finite_cell_handles()) {
    CHECK((field.curl(c) - exact).norm() <= 1e-12);
    const V3 centroid = 0.25 * (vec(c->vertex(0)->point()) + vec(c->vertex(1)->point()) + vec(c->vertex(2)->point()) +
                                vec(c->vertex(3)->point()));
    CHECK((field.A_at(c, Point(centroid(0), centroid(1), centroid(2))) - lin.A(centroid)).norm() <= 1e-13);
  }
}

TEST_CASE("a constant metric field has zero curl, zero connection and identity transport, exactly",
          "[metric_field]") {
  Random r(24);
  Tr tr;
  const Mesh m = kuhn_triangulation(2, tr);
  const M3 g = r.spd(0.1, 10);
  const Field field(tr, g);
  for (auto c : tr.finite_cell_handles()) {
    CHECK(field.curl(c) == M3::Zero());
    const Point a = CGAL::centroid(c->vertex(0)->point(), c->vertex(1)->point(), c->vertex(2)->point(),
                                   c->vertex(3)->point());
    const Point b = CGAL::midpoint(c->vertex(0)->point(), c->vertex(2)->point());
    CHECK(field.connection(c, a) == M3::Zero());
    for (CGAL_ext::Transport_scheme s : {CGAL_ext::Transport_scheme::trapezoid, CGAL_ext::Transport_scheme::magnus}) {
      CGAL_ext::Transport_options opt;
      opt.scheme = s;
      CHECK(CGAL_ext::cell_transport(field, c, a, b, opt).rotation == M3::Identity());
    }
  }
}

TEST_CASE("transport through the field matches the transport from vertex data", "[metric_field]") {
  Random r(25);
  const std::vector<std::array<double, 3>> pts{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const std::vector<std::array<std::size_t, 4>> tets{{0, 1, 2, 3}};
  Tr tr;
  CGAL_ext::build_triangulation_from_tets(pts, tets, {}, tr);
  std::vector<M3> g(4);
  for (M3& x : g) x = r.spd(0.2, 5);
  const Field field(tr, g);
  const auto c = *tr.finite_cell_handles().begin();
  const Point a(0.1, 0.1, 0.1), b(0.5, 0.2, 0.25);
  const CGAL_ext::Transport_result res = CGAL_ext::cell_transport(field, c, a, b);
  // Same thing by hand: A at a and b from the vertex roots (the unit tet's
  // barycentric coordinates are (1-x-y-z, x, y, z)).
  auto A_of = [&](const Point& p) -> M3 { // a matrix, not an expression of temporaries
    return (1 - p.x() - p.y() - p.z()) * CGAL_ext::sqrt_spd(g[0]) + p.x() * CGAL_ext::sqrt_spd(g[1]) +
           p.y() * CGAL_ext::sqrt_spd(g[2]) + p.z() * CGAL_ext::sqrt_spd(g[3]);
  };
  const CGAL_ext::Transport_result ref =
      CGAL_ext::cell_transport(A_of(a), A_of(b), field.curl(c), vec(b) - vec(a));
  CHECK(CGAL_ext::rotation_angle(res.rotation.transpose() * ref.rotation) <= 1e-12);
  CHECK(CGAL_ext::rotation_angle(res.rotation) > 1e-3); // a real rotation
}

TEST_CASE("precompute and concurrent lazy evaluation give the same bits", "[metric_field]") {
  Random r(26);
  Tr tr;
  const Mesh m = kuhn_triangulation(4, tr);
  std::vector<M3> g(m.points.size());
  for (M3& x : g) x = r.spd(0.2, 5);
  const Field sequential(tr, g), pre(tr, g), lazy(tr, g);
  pre.precompute();
  std::vector<Tr::Cell_handle> cells(tr.finite_cell_handles().begin(), tr.finite_cell_handles().end());
  std::shuffle(cells.begin(), cells.end(), r.rng);
  std::vector<M3> from_threads(cells.size());
  tbb::parallel_for(std::size_t(0), cells.size(), [&](std::size_t i) {
    // Several threads ask for the same cells at the same time.
    from_threads[i] = lazy.curl(cells[i]);
    (void)lazy.curl(cells[(i * 7919) % cells.size()]);
  });
  for (std::size_t i = 0; i < cells.size(); ++i) {
    CHECK(sequential.curl(cells[i]) == pre.curl(cells[i]));
    CHECK(from_threads[i] == sequential.curl(cells[i]));
  }
}

TEST_CASE("property maps and set_metric", "[metric_field]") {
  Random r(27);
  Tr tr;
  const Mesh m = kuhn_triangulation(1, tr);
  std::vector<M3> g(m.points.size());
  for (M3& x : g) x = r.spd(0.2, 5);
  Field field(tr, g);
  const auto roots = field.sqrt_metric_map();
  for (auto v : tr.finite_vertex_handles()) CHECK(&get(roots, v) == &field.sqrt_metric(v));

  // Change one vertex through the read-write map: the cached curls of its
  // cells must follow, and equal those of a field built with the new data.
  field.precompute();
  auto v = *tr.finite_vertex_handles().begin();
  const M3 new_g = r.spd(0.2, 5);
  auto metrics = field.metric_map();
  put(metrics, v, new_g);
  CHECK((get(metrics, v) - new_g).norm() <= 1e-12 * new_g.norm());
  g[v->info()] = new_g;
  const Field rebuilt(tr, g);
  for (auto c : tr.finite_cell_handles()) CHECK(field.curl(c) == rebuilt.curl(c));

  M3 bad = M3::Identity();
  bad(1, 1) = -1;
  try {
    put(metrics, v, bad);
    FAIL("no exception");
  } catch (const CGAL_ext::Input_error& e) {
    CHECK(e.element() == "vertex " + std::to_string(v->info() + 1));
  }
}

TEST_CASE("a field read from the user's property map of g or of A equals Metric_field_3, bit for bit",
          "[metric_field]") {
  Random r(41);
  Tr tr;
  const Mesh m = kuhn_triangulation(3, tr);
  std::vector<M3> g(m.points.size()), A(m.points.size());
  for (std::size_t i = 0; i < g.size(); ++i) {
    g[i] = r.spd(0.2, 5);
    A[i] = CGAL_ext::sqrt_spd(g[i]);
  }
  const Field stored(tr, g);
  // The user's arrays through their vertex indices, and a std::map keyed by
  // vertex handle: two kinds of readable maps.
  using Array_map = boost::iterator_property_map<std::vector<M3>::iterator, CGAL_ext::Tet_mesh_vertex_index_map<Tr>>;
  using Handle_map = boost::associative_property_map<std::map<Tr::Vertex_handle, M3>>;
  std::map<Tr::Vertex_handle, M3> by_handle;
  for (auto v : tr.finite_vertex_handles()) by_handle[v] = g[v->info()];
  const CGAL_ext::Property_map_metric_field_3<Tr, Array_map> of_g(tr, Array_map(g.begin()), CGAL_ext::Vertex_metric_kind::metric);
  const CGAL_ext::Property_map_metric_field_3<Tr, Array_map> of_A(tr, Array_map(A.begin()),
                                                                  CGAL_ext::Vertex_metric_kind::sqrt_metric);
  const CGAL_ext::Property_map_metric_field_3<Tr, Handle_map> of_handles(tr, Handle_map(by_handle),
                                                                         CGAL_ext::Vertex_metric_kind::metric);
  CHECK(of_g.number_of_domain_cells() == stored.number_of_domain_cells());
  for (auto c : tr.finite_cell_handles()) {
    const Point p(r.uniform(0, 1), r.uniform(0, 1), r.uniform(0, 1));
    for (const auto* f : {&of_g, &of_A}) {
      CHECK(f->A_at(c, p) == stored.A_at(c, p));
      CHECK(f->curl(c) == stored.curl(c));
      CHECK(f->connection(c, p) == stored.connection(c, p));
      CHECK(f->metric_volume(c) == stored.metric_volume(c));
    }
    CHECK(of_handles.curl(c) == stored.curl(c));
  }
  for (auto v : tr.finite_vertex_handles()) {
    CHECK(of_g.sqrt_metric(v) == stored.sqrt_metric(v));
    CHECK(of_A.metric(v) == stored.metric(v));
  }
  CHECK(of_g.metric_volume() == stored.metric_volume());
}

TEST_CASE("a property-map field checks the user's values, names the vertex, and follows metric_changed",
          "[metric_field]") {
  Random r(43);
  Tr tr;
  const Mesh m = kuhn_triangulation(2, tr);
  using Array_map = boost::iterator_property_map<std::vector<M3>::iterator, CGAL_ext::Tet_mesh_vertex_index_map<Tr>>;
  using Map_field = CGAL_ext::Property_map_metric_field_3<Tr, Array_map>;
  std::vector<M3> g(m.points.size());
  for (M3& x : g) x = r.spd(0.2, 5);

  // A value that is not SPD, as g and as A; an asymmetric A.
  std::vector<M3> bad = g;
  bad[5](2, 2) = -1;
  for (auto kind : {CGAL_ext::Vertex_metric_kind::metric, CGAL_ext::Vertex_metric_kind::sqrt_metric}) {
    try {
      const Map_field f(tr, Array_map(bad.begin()), kind);
      FAIL("no exception");
    } catch (const CGAL_ext::Input_error& e) {
      CHECK(e.element() == "vertex 6");
      CHECK_THAT(e.problem(), Catch::Contains("not positive definite"));
      CHECK_THAT(e.problem(), Catch::Contains(kind == CGAL_ext::Vertex_metric_kind::sqrt_metric ? "square root A" : "metric tensor"));
    }
  }
  bad = g;
  bad[2](0, 1) += 1e-3;
  CHECK_THROWS_AS(Map_field(tr, Array_map(bad.begin()), CGAL_ext::Vertex_metric_kind::sqrt_metric), CGAL_ext::Input_error);
  // Roots that pass the checks made for g, while g = A A does not: it
  // overflows, underflows, or squares a condition number of 1e10.
  for (const M3& A : {M3(1e200 * M3::Identity()), M3(1e-160 * M3::Identity()), M3(M3(V3(1, 1, 1e-10).asDiagonal()))}) {
    INFO(A.diagonal().transpose());
    REQUIRE(CGAL_ext::check_metric_tensor(A).empty());
    bad = g;
    bad[3] = A;
    try {
      const Map_field f(tr, Array_map(bad.begin()), CGAL_ext::Vertex_metric_kind::sqrt_metric);
      FAIL("no exception");
    } catch (const CGAL_ext::Input_error& e) {
      CHECK(e.element() == "vertex 4");
      CHECK_THAT(e.problem(), Catch::StartsWith("g = A A of its square root A: "));
    }
  }

  // The user changes g in place: after metric_changed() every cached curl
  // equals that of a field built on the new values; an invalid new value
  // is refused with the vertex named.
  Map_field field(tr, Array_map(g.begin()), CGAL_ext::Vertex_metric_kind::metric);
  field.precompute();
  const Field old(tr, g);
  const auto v = *std::next(tr.finite_vertex_handles().begin(), 7);
  g[v->info()] = r.spd(0.2, 5);
  field.metric_changed(v);
  const Field rebuilt(tr, g);
  std::size_t changed = 0;
  for (auto c : tr.finite_cell_handles()) {
    CHECK(field.curl(c) == rebuilt.curl(c));
    changed += field.curl(c) != old.curl(c);
  }
  CHECK(changed > 0); // the cells around v, whose cached curls were forgotten
  g[v->info()](0, 0) = std::numeric_limits<double>::quiet_NaN();
  try {
    field.metric_changed(v);
    FAIL("no exception");
  } catch (const CGAL_ext::Input_error& e) {
    CHECK(e.element() == "vertex " + std::to_string(v->info() + 1));
    CHECK_THAT(e.problem(), Catch::Contains("non-finite"));
  }
}

TEST_CASE("bad metrics are input errors that name the vertex", "[metric_field]") {
  Tr tr;
  const Mesh m = kuhn_triangulation(1, tr);
  std::vector<M3> g(m.points.size(), M3::Identity());

  auto expect_error = [&](const std::vector<M3>& metrics, const std::string& element, const std::string& words) {
    try {
      Field f(tr, metrics, "metric.sol");
      FAIL("no exception");
    } catch (const CGAL_ext::Input_error& e) {
      CHECK(e.element() == element);
      CHECK(e.file() == "metric.sol");
      CHECK(e.problem().find(words) != std::string::npos);
    }
  };
  std::vector<M3> bad = g;
  bad[2](0, 0) = -3;
  expect_error(bad, "vertex 3", "not positive definite");
  bad = g;
  bad[5](1, 2) = std::numeric_limits<double>::quiet_NaN();
  expect_error(bad, "vertex 6", "non-finite");
  bad = g;
  bad[0](0, 1) = 0.5; // not symmetric
  expect_error(bad, "vertex 1", "not symmetric");
  bad = g;
  bad.pop_back();
  expect_error(bad, "vertex " + std::to_string(g.size()), "no metric");

  // The callable constructor names the vertex too.
  try {
    Field f(tr, [](const Point& p) -> M3 { return (p.x() > 0.5 && p.y() > 0.5 ? -1.0 : 1.0) * M3::Identity(); });
    FAIL("no exception");
  } catch (const CGAL_ext::Input_error& e) {
    CHECK(e.element().rfind("vertex ", 0) == 0);
    CHECK(e.problem().find("not positive definite") != std::string::npos);
  }
  CHECK_THROWS_AS(Field(tr, M3::Zero().eval()), CGAL_ext::Input_error);
}

TEST_CASE("cells outside the domain are refused", "[metric_field]") {
  Tr tr;
  const Mesh m = kuhn_triangulation(1, tr);
  const Field field(tr, M3::Identity().eval());
  Tr::Cell_handle outside;
  for (auto c : tr.all_cell_handles())
    if (tr.is_infinite(c)) outside = c;
  REQUIRE(outside != Tr::Cell_handle());
  CHECK_THROWS_AS(field.curl(outside), std::invalid_argument);
}

namespace {

// doc/math.md section 6 (test_support.h).
using CGAL_ext::testing::flat_metric::jacobian;
M3 phi_metric(const V3& x) { return CGAL_ext::testing::flat_metric::metric(x); }
M3 phi_A(const V3& x) { return CGAL_ext::testing::flat_metric::sqrt_metric(x); }
M3 phi_curl(const V3& x) { return CGAL_ext::testing::flat_metric::curl(x); }

} // namespace

TEST_CASE("the PL transport in a shrinking tet converges to the smooth transport", "[metric_field]") {
  // A tet of size eps around a = (0.1, 0.2, -0.3), g = J^T J at its vertices,
  // a segment of length ~0.3 eps towards b = (0.9, -0.4, 0.5). The transport
  // angle is O(eps); the PL curl is O(eps) off, so the PL transport is off by
  // O(eps^2): halving eps must divide the error by about 4.
  const V3 a(0.1, 0.2, -0.3), dir = (V3(0.9, -0.4, 0.5) - a).normalized();
  const std::array<V3, 4> ref{V3(0, 0, 0), V3(1, 0, 0), V3(0, 1, 0), V3(0, 0, 1)};
  const V3 c(0.2, 0.2, 0.2); // a's position in the reference tet
  std::vector<double> errors, angles;
  for (double eps : {0.2, 0.1, 0.05, 0.025}) {
    std::vector<std::array<double, 3>> pts;
    for (const V3& r : ref) {
      const V3 p = a + eps * (r - c);
      pts.push_back({p(0), p(1), p(2)});
    }
    Tr tr;
    CGAL_ext::build_triangulation_from_tets(pts, {{0, 1, 2, 3}}, {}, tr);
    const Field field(tr, [](const Point& p) { return phi_metric(vec(p)); });
    const auto cell = *tr.finite_cell_handles().begin();
    const V3 b = a + 0.3 * eps * dir;
    REQUIRE(field.barycentric_coordinates(cell, Point(b(0), b(1), b(2))).minCoeff() > 0);
    CGAL_ext::Transport_options opt;
    opt.tolerance = 1e-13;
    const M3 pl = CGAL_ext::cell_transport(field, cell, Point(a(0), a(1), a(2)), Point(b(0), b(1), b(2)), opt).rotation;
    auto u = [&](double t) -> V3 {
      const V3 x = a + t * (b - a);
      return CGAL_ext::connection_one_form(phi_A(x), phi_curl(x)).transpose() * (b - a);
    };
    const M3 smooth = CGAL_ext::integrate_transport(u, opt).rotation;
    errors.push_back(CGAL_ext::rotation_angle(pl.transpose() * smooth));
    angles.push_back(CGAL_ext::rotation_angle(smooth));
  }
  for (std::size_t i = 0; i < errors.size(); ++i) {
    INFO("eps level " << i << ": transport angle " << angles[i] << ", PL error " << errors[i]);
    CHECK(errors[i] < 0.1 * angles[i]); // the PL field is a fair approximation
    if (i > 0) CHECK(errors[i - 1] / errors[i] > 3.0); // second order locally
    if (i > 0) CHECK(angles[i - 1] / angles[i] > 1.8); // and the angle is first order
  }
}

TEST_CASE("a tet that is flat in double precision is an input error naming it", "[metric_field]") {
  // Exactly positively oriented, but its volume (1e-330 / 6) underflows; a
  // second component of unit size keeps the mesh within the supported sizes.
  const double e = 1e-110;
  const std::vector<std::array<double, 3>> points{{0, 0, 0}, {e, 0, 0}, {0, e, 0}, {0, 0, e}, {e, e, e},
                                                  {10, 0, 0}, {11, 0, 0}, {10, 1, 0}, {10, 0, 1}};
  const std::vector<std::array<std::size_t, 4>> tets{{0, 1, 2, 3}, {1, 2, 3, 4}, {5, 6, 7, 8}};
  Tr tr;
  CGAL_ext::build_triangulation_from_tets(points, tets, {}, tr);
  const CGAL_ext::Metric_field_3<Tr> field(tr, Eigen::Matrix3d::Identity().eval());
  try {
    field.precompute();
    FAIL("no error for a tetrahedron of volume 1e-330");
  } catch (const CGAL_ext::Input_error& err) {
    INFO(err.what());
    CHECK(err.element().rfind("tetrahedron ", 0) == 0);
    CHECK(err.problem().find("too flat for double precision") != std::string::npos);
  }
}

// The unit of length does not matter within the supported sizes: scaled by
// 2^e, the curl and the connection are scaled by exactly 2^-e; beyond 1e60
// (or below 1e-60) the constructors refuse the mesh, naming its size.
TEST_CASE("the field is exact under scalings by powers of two and refuses meshes beyond its supported sizes",
          "[metric_field]") {
  Random r(5);
  const Linear_A f = random_linear_A(r);
  const Mesh m = kuhn_grid(2);
  auto build = [&](int e, Tr& tr) {
    std::vector<std::array<double, 3>> pts = m.points;
    for (auto& p : pts)
      for (double& x : p) x = std::ldexp(x, e);
    CGAL_ext::build_triangulation_from_tets(pts, m.tets, {}, tr);
  };
  // the same metric at the same (unscaled) positions
  auto g_at = [&](int e) {
    return [&f, e](const Point& p) {
      const M3 A = f.A(V3(std::ldexp(p.x(), -e), std::ldexp(p.y(), -e), std::ldexp(p.z(), -e)));
      return M3(A * A);
    };
  };
  Tr tr0;
  build(0, tr0);
  const Field f0(tr0, g_at(0));
  for (int e : {150, -150}) {
    INFO("scale 2^" << e);
    Tr tr;
    build(e, tr);
    const Field fe(tr, g_at(e));
    auto c0 = tr0.finite_cells_begin();
    for (auto c = tr.finite_cells_begin(); c != tr.finite_cells_end(); ++c, ++c0) {
      CHECK((fe.curl(c) * std::ldexp(1.0, e) - f0.curl(c0)).cwiseAbs().maxCoeff() <= 1e-13);
      const Point pe = CGAL::centroid(tr.tetrahedron(c)), p0 = CGAL::centroid(tr0.tetrahedron(c0));
      CHECK((fe.connection(c, pe) * std::ldexp(1.0, e) - f0.connection(c0, p0)).cwiseAbs().maxCoeff() <= 1e-13);
    }
  }
  for (int e : {333, -333, -1040}) {
    INFO("scale 2^" << e);
    Tr tr;
    build(e, tr);
    try {
      const Field fe(tr, M3(M3::Identity()));
      FAIL("no error");
    } catch (const CGAL_ext::Input_error& x) {
      CHECK(x.element() == "the mesh");
      CHECK(x.problem().find("spans ") == 0);
    }
  }
}
