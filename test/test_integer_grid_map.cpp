// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The integer-grid map on fields whose exact map is known: constant frames
// on boxes (an affine grid), frames relabelled per tetrahedron (the combing
// and the gluing), and frames turning about an axis (valence-3 and
// valence-5 singular curves). Also its solver and the .hexex file.
#include <CGAL_ext/IO/Hexex_file.h>
#include <CGAL_ext/Integer_grid_map_3.h>
#include <CGAL_ext/Mixed_integer_quadratic_solver.h>
#include <CGAL_ext/Octahedral_frame.h>
#include <CGAL_ext/make_kuhn_grid.h>
#include <CGAL_ext/tet_face_neighbors.h>

#include "integer_grid_map_checks.h"
#include "test_support.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <set>
#include <stdexcept>
#include <string>

using namespace CGAL_ext;
using M3 = Eigen::Matrix3d;
using V3 = Eigen::Vector3d;

namespace {

// A Kuhn grid of boxes, positively oriented, with frames R_t (columns the
// frame vectors) and gradients A R_t / h, matchings from the frames.
Integer_grid_map_input grid_input(const std::array<int, 3>& cubes, double spacing, const std::array<double, 3>& origin,
                                  const std::function<M3(const V3&)>& frame, const M3& A, double h) {
  const IO::Medit_mesh m = make_kuhn_grid(cubes, spacing, origin);
  Integer_grid_map_input in;
  for (const auto& v : m.vertices) in.positions.push_back({v[0], v[1], v[2]});
  for (auto q : m.tetrahedra) {
    M3 D;
    D << in.positions[q[1]] - in.positions[q[0]], in.positions[q[2]] - in.positions[q[0]],
        in.positions[q[3]] - in.positions[q[0]];
    if (D.determinant() < 0) std::swap(q[2], q[3]);
    in.tets.push_back(q);
  }
  in.neighbors = tet_face_neighbors(in.tets);
  std::vector<M3> R;
  for (const auto& q : in.tets) {
    const V3 c = (in.positions[q[0]] + in.positions[q[1]] + in.positions[q[2]] + in.positions[q[3]]) / 4;
    R.push_back(frame(c));
    in.gradients.push_back(A * R.back() / h);
  }
  for (std::size_t t = 0; t < in.tets.size(); ++t) {
    std::array<int, 4> g{-1, -1, -1, -1};
    for (int f = 0; f < 4; ++f)
      if (in.neighbors[t][std::size_t(f)] >= 0)
        g[std::size_t(f)] = closest_octahedral_matching(R[t], R[std::size_t(in.neighbors[t][std::size_t(f)])]).index;
    in.matchings.push_back(g);
  }
  return in;
}

M3 identity_frame(const V3&) { return M3::Identity(); }

bool integral(double x) { return std::abs(x - std::round(x)) < 1e-9; }

// The parameters' extent over the whole map, per coordinate.
V3 extent(const Integer_grid_map& map) {
  V3 lo = V3::Constant(1e300), hi = V3::Constant(-1e300);
  for (const auto& tet : map.parameters)
    for (const V3& u : tet) lo = lo.cwiseMin(u), hi = hi.cwiseMax(u);
  return hi - lo;
}

// The map is u = S (p - p0) for one diagonal S and one p0, in every corner
// of the map's tetrahedra (split edges included) and of the input's.
void require_affine(const Integer_grid_map_input& in, const Integer_grid_map& map, const V3& scale) {
  const V3 p0 = map.positions[map.tets[0][0]] - map.parameters[0][0].cwiseQuotient(scale);
  for (std::size_t t = 0; t < map.tets.size(); ++t)
    for (std::size_t c = 0; c < 4; ++c)
      REQUIRE((map.parameters[t][c] - scale.cwiseProduct(map.positions[map.tets[t][c]] - p0)).norm() < 1e-8);
  for (std::size_t t = 0; t < in.tets.size(); ++t)
    for (std::size_t c = 0; c < 4; ++c)
      REQUIRE((map.input_parameters[t][c] - scale.cwiseProduct(in.positions[in.tets[t][c]] - p0)).norm() < 1e-8);
}

} // namespace

TEST_CASE("integer-grid map: a constant metric on a box whose size is a multiple of h is the exact grid",
          "[integer_grid_map]") {
  const auto in = grid_input({4, 3, 2}, 0.5, {0.25, -1, 3}, identity_frame, M3::Identity(), 0.5);
  const Integer_grid_map map = compute_integer_grid_map(in);
  testing::require_refinement(in, map);
  CHECK(testing::require_seamless(in, map) == 0);
  const auto& rep = map.report;
  CHECK(rep.cut_faces_tree > 0);
  CHECK(rep.cut_faces == 0); // a ball without singularity: every cut face is glued back
  CHECK(rep.singular_edges == 0);
  CHECK(rep.inverted_tets == 0);
  CHECK(rep.flat_tets == 0);
  CHECK(rep.fit_error < 1e-20);
  CHECK(rep.boundary_faces_constrained == 2 * 2 * (4 * 3 + 3 * 2 + 4 * 2));
  CHECK(rep.parameter_volume == Approx(4 * 3 * 2));
  CHECK(rep.due_volume == Approx(4 * 3 * 2));
  require_affine(in, map, V3::Constant(2));
  for (const auto& tet : map.input_parameters) // the grid's vertices; split edges' midpoints are half-integers
    for (const V3& u : tet)
      for (int k = 0; k < 3; ++k) REQUIRE(integral(u[k]));
}

TEST_CASE("integer-grid map: a box of 3.75 hex edges gets 4, its boundary on integer planes, the map affine",
          "[integer_grid_map]") {
  // 5 cubes of 0.3 per side: 1.5 long, h = 0.4.
  const auto in = grid_input({5, 5, 5}, 0.3, {0, 0, 0}, identity_frame, M3::Identity(), 0.4);
  const Integer_grid_map map = compute_integer_grid_map(in);
  testing::require_seamless(in, map);
  CHECK(map.report.inverted_tets == 0);
  CHECK(map.report.flat_tets == 0);
  CHECK(map.report.fit_error_relaxed < 1e-12); // from the objective: rounding errors of 1e-16
  CHECK(map.report.fit_error > 1e-3); // the rounding stretched it
  const V3 e = extent(map);
  CHECK(e.x() == Approx(4).margin(1e-9));
  CHECK(e.y() == Approx(4).margin(1e-9));
  CHECK(e.z() == Approx(4).margin(1e-9));
  // The least-squares fit of a constant gradient between two integer planes is linear.
  require_affine(in, map, V3::Constant(4 / 1.5));
}

TEST_CASE("integer-grid map: the metric diag(1, 4, 1) gives steps in y twice as fine", "[integer_grid_map]") {
  M3 A = M3::Identity();
  A(1, 1) = 2; // A = g^(1/2)
  const auto in = grid_input({4, 4, 4}, 0.25, {0, 0, 0}, identity_frame, A, 0.5);
  const Integer_grid_map map = compute_integer_grid_map(in);
  CHECK(map.report.inverted_tets == 0);
  const V3 e = extent(map);
  CHECK(e.x() == Approx(2).margin(1e-9));
  CHECK(e.y() == Approx(4).margin(1e-9));
  CHECK(e.z() == Approx(2).margin(1e-9));
  require_affine(in, map, V3(2, 4, 2));
}

TEST_CASE("integer-grid map: frames relabelled at random per tetrahedron give the same grid", "[integer_grid_map]") {
  testing::Random rnd(7);
  const auto& group = octahedral_group();
  auto relabel = [&](const V3&) { return group[std::size_t(rnd.uniform(0, 24)) % 24]; };
  const auto in = grid_input({3, 3, 3}, 1.0, {0, 0, 0}, relabel, M3::Identity(), 1.0);
  std::set<int> charts;
  for (const auto& g : in.matchings)
    for (int m : g) charts.insert(m);
  REQUIRE(charts.size() > 10); // the matchings are not the identity
  const Integer_grid_map map = compute_integer_grid_map(in);
  testing::require_seamless(in, map);
  CHECK(map.report.cut_faces == 0);
  CHECK(map.report.singular_edges == 0);
  CHECK(map.report.inverted_tets == 0);
  CHECK(map.report.fit_error < 1e-20);
  // In each tetrahedron's chart the map is a rotation of the grid: its edges
  // map to unit steps along the axes, and every corner to integers.
  for (std::size_t t = 0; t < in.tets.size(); ++t)
    for (std::size_t c = 0; c < 4; ++c)
      for (int k = 0; k < 3; ++k) REQUIRE(integral(map.input_parameters[t][c][k]));
  CHECK(map.report.parameter_volume == Approx(27));
}

TEST_CASE("integer-grid map: valence-3 and valence-5 singular curves lie on grid lines, every tetrahedron positive",
          "[integer_grid_map]") {
  for (const double turn : {0.25, -0.25}) {
    DYNAMIC_SECTION("frames turning by " << turn << " of the angle about the z axis") {
      // Frames Rz(turn * phi) on [-1, 1]^2 x [0, 1]: a singular curve on the z axis.
      auto frame = [turn](const V3& c) {
        return M3(Eigen::AngleAxisd(turn * std::atan2(c.y(), c.x()), V3::UnitZ()));
      };
      auto in = grid_input({8, 8, 2}, 0.25, {-1, -1, 0}, frame, M3::Identity(), 0.25);
      in.free_boundary.assign(in.tets.size(), true); // the sides are not aligned with such frames
      const Integer_grid_map map = compute_integer_grid_map(in);
      const auto& rep = map.report;
      testing::require_refinement(in, map);
      CHECK(testing::require_seamless(in, map) > 0); // the cut ending on the curve
      CHECK(rep.singular_edges == 2);
      CHECK(rep.singular_edges_on_grid_lines == 2);
      CHECK(rep.cut_faces > 0);
      CHECK(rep.inverted_tets == 0);
      CHECK(rep.flat_tets == 0);
      // The axis's vertices: x = y = 0; their coordinates across the curve's axis are integers.
      std::size_t seen = 0;
      for (std::size_t t = 0; t < map.tets.size(); ++t)
        for (std::size_t c = 0; c < 4; ++c) {
          const V3& p = map.positions[map.tets[t][c]];
          if (std::abs(p.x()) > 1e-12 || std::abs(p.y()) > 1e-12) continue;
          ++seen;
          REQUIRE(integral(map.parameters[t][c].x()));
          REQUIRE(integral(map.parameters[t][c].y()));
        }
      CHECK(seen > 0);
    }
  }
}

TEST_CASE("integer-grid map: tetrahedra the rounding inverts are untangled, the seams and integers held",
          "[integer_grid_map]") {
  // A valence-5 and a valence-3 curve on the z axis of [-1, 1]^2 x [0, 2 s]
  // (s the grid's spacing), hexes of about a quarter of the width: the
  // rounding puts the curve's grid line and the sides' planes a few steps
  // apart, and inverts tetrahedra between them.
  struct Case {
    double turn, spacing, h;
    int cubes;
  };
  for (const Case k : {Case{-0.25, 0.25, 0.5, 8}, Case{0.25, 0.2, 0.4, 10}}) {
    DYNAMIC_SECTION("frames turning by " << k.turn << " of the angle, hexes of " << k.h) {
      auto frame = [&](const V3& c) { return M3(Eigen::AngleAxisd(k.turn * std::atan2(c.y(), c.x()), V3::UnitZ())); };
      const auto in = grid_input({k.cubes, k.cubes, 2}, k.spacing, {-1, -1, 0}, frame, M3::Identity(), k.h);
      Integer_grid_map_options no_untangling;
      no_untangling.untangle = false;
      const Integer_grid_map rounded = compute_integer_grid_map(in, no_untangling);
      REQUIRE(rounded.report.inverted_tets > 0);
      CHECK(!rounded.report.untangled);
      const Integer_grid_map map = compute_integer_grid_map(in);
      const auto& rep = map.report;
      CHECK(rep.inverted_tets_rounded == rounded.report.inverted_tets);
      CHECK(rep.untangled);
      CHECK(rep.untangle_tets > 0);
      CHECK(rep.untangle_tets < map.tets.size()); // only around the defects
      CHECK(rep.inverted_tets == 0);
      CHECK(rep.flat_tets == 0);
      CHECK(rep.min_relative_det_rounded < 0);
      CHECK(rep.min_relative_det > 0);
      testing::require_refinement(in, map);
      testing::require_seamless(in, map);
      // The top and bottom still on integer planes.
      const double top = 2 * k.spacing;
      for (std::size_t t = 0; t < map.tets.size(); ++t)
        for (std::size_t c = 0; c < 4; ++c) {
          const double z = map.positions[map.tets[t][c]].z();
          if (std::abs(z) < 1e-12 || std::abs(z - top) < 1e-12) REQUIRE(integral(map.parameters[t][c].z()));
        }
    }
  }
}

TEST_CASE("integer-grid map: inputs that do not agree are refused", "[integer_grid_map]") {
  auto in = grid_input({1, 1, 1}, 1.0, {0, 0, 0}, identity_frame, M3::Identity(), 1.0);
  SECTION("matchings that are not inverse across a face") {
    for (std::size_t t = 0; t < in.tets.size(); ++t)
      for (int f = 0; f < 4; ++f)
        if (in.neighbors[t][std::size_t(f)] >= 0) {
          in.matchings[t][std::size_t(f)] = 5;
          REQUIRE_THROWS_WITH(compute_integer_grid_map(in), Catch::Contains("do not agree on their face"));
          return;
        }
  }
  SECTION("a negatively oriented tetrahedron") {
    std::swap(in.tets[2][0], in.tets[2][1]);
    REQUIRE_THROWS_WITH(compute_integer_grid_map(in), Catch::Contains("tetrahedron 3 is flat or negatively oriented"));
  }
  SECTION("gradients that are not finite") {
    in.gradients[1](0, 0) = std::nan("");
    REQUIRE_THROWS_WITH(compute_integer_grid_map(in), Catch::Contains("tetrahedron 2: its gradients"));
  }
  SECTION("arrays of different sizes") {
    in.matchings.pop_back();
    REQUIRE_THROWS_AS(compute_integer_grid_map(in), std::invalid_argument);
  }
}

TEST_CASE("mixed-integer quadratic solver: elimination, redundancy and greedy rounding", "[integer_grid_map]") {
  Mixed_integer_quadratic_problem pb;
  pb.H.resize(3, 3);
  pb.H.setIdentity();
  pb.b = V3(0.4, 0.8, 2.6);
  SECTION("no equality: the relaxed minimiser is b, the rounded one its nearest integers") {
    pb.integer_variables = {0, 2};
    const auto s = solve_mixed_integer_quadratic(pb);
    CHECK(s.x[0] == 0);
    CHECK(s.x[1] == Approx(0.8));
    CHECK(s.x[2] == 3);
    CHECK(s.report.objective_relaxed == Approx(-(0.16 + 0.64 + 6.76)));
  }
  SECTION("x0 = x1 with x0 integer: the mean 0.6, rounded to 1") {
    pb.equalities.push_back({{{0, 1.0}, {1, -1.0}}, 0.0});
    pb.equalities.push_back({{{1, 2.0}, {0, -2.0}}, 0.0}); // redundant
    pb.integer_variables = {0};
    const auto s = solve_mixed_integer_quadratic(pb);
    CHECK(s.report.redundant_equalities == 1);
    CHECK(s.report.free_variables == 2);
    CHECK(s.x[0] == 1);
    CHECK(s.x[1] == 1);
    const auto relaxed = solve_mixed_integer_quadratic(pb, {false});
    CHECK(relaxed.x[0] == Approx(0.6));
  }
  SECTION("an equality among integers only keeps them integral") {
    pb.equalities.push_back({{{0, 1.0}, {1, 1.0}, {2, -1.0}}, 0.0});
    pb.integer_variables = {0, 1, 2};
    const auto s = solve_mixed_integer_quadratic(pb);
    for (int k = 0; k < 3; ++k) CHECK(integral(s.x[k]));
    CHECK(s.x[0] + s.x[1] == s.x[2]);
    CHECK(s.report.non_integral_eliminated == 0);
  }
  SECTION("contradicting equalities are an error") {
    pb.equalities.push_back({{{0, 1.0}}, 1.0});
    pb.equalities.push_back({{{0, 1.0}}, 2.0});
    REQUIRE_THROWS_WITH(solve_mixed_integer_quadratic(pb), Catch::Contains("equality 2 contradicts"));
  }
  SECTION("an index out of range is an error") {
    pb.integer_variables = {3};
    REQUIRE_THROWS_AS(solve_mixed_integer_quadratic(pb), std::invalid_argument);
  }
}

TEST_CASE(".hexex files: written at full precision, read back, bad files named", "[integer_grid_map][hexex]") {
  IO::Hexex_file map;
  map.positions = {V3(0, 0, 0), V3(1, 0, 0), V3(0, 1, 0), V3(0, 0, 1.0 / 3)};
  map.tets = {{0, 1, 2, 3}};
  map.parameters = {{V3(0, 0, 0), V3(0.1, 0, 0), V3(0, 1e-17, 0), V3(0, 0, 2.0 / 3)}};
  const std::string path = "test_map.hexex";
  IO::write_hexex(path, map);
  const IO::Hexex_file back = IO::read_hexex(path);
  REQUIRE(back.tets == map.tets);
  for (std::size_t v = 0; v < 4; ++v) REQUIRE(back.positions[v] == map.positions[v]);
  for (std::size_t c = 0; c < 4; ++c) REQUIRE(back.parameters[0][c] == map.parameters[0][c]);

  auto write = [&](const std::string& text) {
    std::ofstream(path) << text;
  };
  write("4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1\n0 1 2 4 0 0 0 1 0 0 0 1 0 0 0 1\n");
  REQUIRE_THROWS_WITH(IO::read_hexex(path), Catch::Contains("tetrahedron 1") && Catch::Contains("out of range"));
  write("4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1\n0 1 2 3 0 0 0 1 0 0 0 1\n");
  REQUIRE_THROWS_WITH(IO::read_hexex(path), Catch::Contains("tetrahedron 1"));
  write("4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1\n0 1 2 2 0 0 0 1 0 0 0 1 0 0 0 1\n");
  REQUIRE_THROWS_WITH(IO::read_hexex(path), Catch::Contains("appears twice"));
  write("4\n0 0 0\n1 0 nan\n0 1 0\n0 0 1\n0\n");
  REQUIRE_THROWS_WITH(IO::read_hexex(path), Catch::Contains("vertex 2"));
  write("4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n0\nextra\n");
  REQUIRE_THROWS_WITH(IO::read_hexex(path), Catch::Contains("after the last"));
  map.parameters[0][1].x() = INFINITY;
  REQUIRE_THROWS_AS(IO::write_hexex(path, map), std::invalid_argument);
  std::remove(path.c_str());
}
