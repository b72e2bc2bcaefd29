// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Hexahedral meshes: the scaled Jacobian and volume of a hexahedron, the
// boundary, the mesh's quality report, and the .ovm reader, Medit and VTU
// writers. test/compare_hex_mesh_quality.py checks the same figures against
// scripts/hex_mesh_quality.py and VTK on random hexahedra.
#include <CGAL_ext/Hex_mesh_quality_3.h>
#include <CGAL_ext/IO/Medit_hex_mesh.h>
#include <CGAL_ext/IO/Medit_tokenizer.h>
#include <CGAL_ext/IO/Ovm_file.h>
#include <CGAL_ext/IO/Vtu_file.h>

#include "input_error_checks.h"
#include "vtu_test_reader.h"

#include <catch2/catch.hpp>

#include <Eigen/Dense>

#include <cmath>
#include <fstream>
#include <random>

using namespace CGAL_ext;
using Hex_points = std::array<Eigen::Vector3d, 8>;

namespace {

const int unit_cube[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};

Hex_points affine_cube(const Eigen::Matrix3d& M, const Eigen::Vector3d& t = Eigen::Vector3d::Zero()) {
  Hex_points p;
  for (int k = 0; k < 8; ++k) p[std::size_t(k)] = M * Eigen::Vector3d(unit_cube[k][0], unit_cube[k][1], unit_cube[k][2]) + t;
  return p;
}

// The trilinear map of a hexahedron, written from its definition.
Eigen::Vector3d trilinear(const Hex_points& p, double u, double v, double w) {
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  for (int k = 0; k < 8; ++k)
    x += (unit_cube[k][0] ? u : 1 - u) * (unit_cube[k][1] ? v : 1 - v) * (unit_cube[k][2] ? w : 1 - w) * p[std::size_t(k)];
  return x;
}

// An nx x ny x nz block of unit cubes scaled by (hx, hy, hz).
Hex_mesh_3 grid(int nx, int ny, int nz, double hx = 1, double hy = 1, double hz = 1) {
  Hex_mesh_3 m;
  auto id = [&](int i, int j, int k) { return std::size_t(i + (nx + 1) * (j + (ny + 1) * k)); };
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) m.points.emplace_back(i * hx, j * hy, k * hz);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        std::array<std::size_t, 8> h;
        for (int c = 0; c < 8; ++c) h[std::size_t(c)] = id(i + unit_cube[c][0], j + unit_cube[c][1], k + unit_cube[c][2]);
        m.hexahedra.push_back(h);
      }
  return m;
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
}

} // namespace

TEST_CASE("Scaled Jacobian: 1 on a cuboid, the frame's on a parallelepiped, -1 mirrored, 0 collapsed",
          "[hex_mesh][quality]") {
  const Hex_scaled_jacobian cube = hex_scaled_jacobian(affine_cube(Eigen::Vector3d(2, 0.5, 3).asDiagonal()));
  CHECK(cube.value == Approx(1).epsilon(1e-15));
  CHECK(cube.corners == Approx(1).epsilon(1e-15));
  CHECK_FALSE(cube.degenerate);

  // Every frame of a parallelepiped is the matrix's columns (or their negatives, in the same order).
  Eigen::Matrix3d M;
  M << 1, 0.4, -0.3, 0.2, 1.5, 0.1, 0, 0.3, 0.8;
  const double expected = M.determinant() / (M.col(0).norm() * M.col(1).norm() * M.col(2).norm());
  const Hex_scaled_jacobian sheared = hex_scaled_jacobian(affine_cube(M, Eigen::Vector3d(5, -2, 1)));
  CHECK(sheared.value == Approx(expected).epsilon(1e-13));
  CHECK(sheared.corners == Approx(expected).epsilon(1e-13));
  CHECK(hex_volume(affine_cube(M)) == Approx(M.determinant()).epsilon(1e-13));

  Hex_points mirrored = affine_cube(Eigen::Matrix3d::Identity());
  std::swap_ranges(mirrored.begin(), mirrored.begin() + 4, mirrored.begin() + 4); // top <-> bottom
  CHECK(hex_scaled_jacobian(mirrored).value == Approx(-1));
  CHECK(hex_volume(mirrored) == Approx(-1));

  Hex_points collapsed = affine_cube(Eigen::Matrix3d::Identity());
  collapsed[1] = collapsed[0];
  const Hex_scaled_jacobian c = hex_scaled_jacobian(collapsed);
  CHECK(c.degenerate);
  CHECK(c.value == 0);

  // Corner 6 pushed inside, to (0.3, 0.3, 0.3): its frame (p5 - p6, p7 - p6,
  // p2 - p6) = ((0.7, -0.3, 0.7), (-0.3, 0.7, 0.7), (0.7, 0.7, -0.3)) turns
  // negative; the other corners' and the centre's stay positive.
  Hex_points dented = affine_cube(Eigen::Matrix3d::Identity());
  dented[6] = Eigen::Vector3d(0.3, 0.3, 0.3);
  const Hex_scaled_jacobian d = hex_scaled_jacobian(dented);
  Eigen::Matrix3d F;
  F << 0.7, -0.3, 0.7, -0.3, 0.7, 0.7, 0.7, 0.7, -0.3;
  const double corner6 = F.determinant() / std::pow(std::sqrt(0.49 + 0.09 + 0.49), 3);
  CHECK(corner6 < 0);
  CHECK(d.corners == Approx(corner6).epsilon(1e-13)); // the least corner
  CHECK(d.value == Approx(corner6).epsilon(1e-13));   // the centre frame is better

  // The scale does not matter, up to the largest and smallest doubles:
  // no overflow (inf / inf) nor underflow (a frame taken as collapsed).
  for (double scale : {1e-300, 1e-200, 1e200, 1e300}) {
    Hex_points s = dented;
    for (auto& x : s) x *= scale;
    const Hex_scaled_jacobian ds = hex_scaled_jacobian(s);
    CHECK_FALSE(ds.degenerate);
    CHECK(ds.value == Approx(corner6).epsilon(1e-13));
  }
  for (double scale : {1e-100, 1e100}) { // volumes of 1e-300 and 1e300: still doubles
    Hex_points s = dented;
    for (auto& x : s) x *= scale;
    CHECK(hex_volume(s) / (scale * scale * scale) == Approx(hex_volume(dented)).epsilon(1e-13));
  }
  Hex_points huge = affine_cube(Eigen::Matrix3d::Identity() * 1e300);
  CHECK(hex_volume(huge) == std::numeric_limits<double>::infinity()); // 1e900: beyond the doubles, not NaN
}

TEST_CASE("Hex volume: exact for the trilinear hexahedron, additive over its 8 octants", "[hex_mesh][quality]") {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> jitter(-0.35, 0.35);
  for (int trial = 0; trial < 50; ++trial) {
    Hex_points p;
    for (int k = 0; k < 8; ++k)
      for (int d = 0; d < 3; ++d) p[std::size_t(k)][d] = unit_cube[k][d] + jitter(rng);
    // The trilinear map restricted to an octant of the unit cube is the
    // trilinear map of the octant's 8 images: the volumes add up exactly.
    double sum = 0;
    for (int o = 0; o < 8; ++o) {
      Hex_points q;
      for (int k = 0; k < 8; ++k)
        q[std::size_t(k)] = trilinear(p, 0.5 * (unit_cube[o][0] + unit_cube[k][0]),
                                      0.5 * (unit_cube[o][1] + unit_cube[k][1]), 0.5 * (unit_cube[o][2] + unit_cube[k][2]));
      sum += hex_volume(q);
    }
    CHECK(sum == Approx(hex_volume(p)).epsilon(1e-13));
  }
  // A hexahedron with planar faces whose volume is known: a frustum of a
  // square pyramid (bases 2 x 2 and 1 x 1, height 1): 7/3.
  Hex_points frustum = affine_cube(Eigen::Vector3d(2, 2, 1).asDiagonal());
  for (int k = 4; k < 8; ++k) frustum[std::size_t(k)].head<2>() = 0.5 * frustum[std::size_t(k)].head<2>() + Eigen::Vector2d(0.5, 0.5);
  CHECK(hex_volume(frustum) == Approx(7.0 / 3).epsilon(1e-14));
}

TEST_CASE("Boundary quadrilaterals: faces of one hexahedron, outward, and a non-manifold face is refused",
          "[hex_mesh]") {
  const Hex_mesh_3 m = grid(3, 2, 1);
  const auto quads = hex_mesh_boundary_quadrilaterals(m.hexahedra);
  CHECK(quads.size() == 2 * (3 * 2 + 3 * 1 + 2 * 1));
  const Eigen::Vector3d centre(1.5, 1, 0.5);
  for (const auto& q : quads) {
    const Eigen::Vector3d n = (m.points[q[1]] - m.points[q[0]]).cross(m.points[q[2]] - m.points[q[1]]);
    const Eigen::Vector3d mid = 0.25 * (m.points[q[0]] + m.points[q[1]] + m.points[q[2]] + m.points[q[3]]);
    CHECK(n.dot(mid - centre) > 0);
  }
  Hex_mesh_3 three = grid(2, 1, 1);
  three.hexahedra.push_back(three.hexahedra[0]);
  three.hexahedra.push_back(three.hexahedra[0]);
  REQUIRE_THROWS_WITH(hex_mesh_boundary_quadrilaterals(three.hexahedra), Catch::Contains("not manifold"));
}

TEST_CASE("Hex mesh quality: counts, histogram, coverage, and sizes against a metric", "[hex_mesh][quality]") {
  Hex_mesh_3 m = grid(4, 2, 2, 0.5, 0.25, 0.5); // hexes of 0.5 x 0.25 x 0.5
  // Mirror the last hexahedron (top and bottom swapped): inverted.
  auto& last = m.hexahedra.back();
  std::swap_ranges(last.begin(), last.begin() + 4, last.begin() + 4);
  Hex_mesh_quality_options options;
  options.domain_volume = 2 * 0.5 * 1;
  options.metric = [](const Eigen::Vector3d&) -> Eigen::Matrix3d {
    return Eigen::Vector3d(4, 16, 4).asDiagonal(); // asks for 0.5 x 0.25 x 0.5
  };
  const Hex_mesh_quality_3 q = hex_mesh_quality(m, options);
  CHECK(q.hexahedra == 16);
  CHECK(q.vertices == 5 * 3 * 3);
  CHECK(q.scaled_jacobian_at_most_0 == 1);
  CHECK(q.negative_volume_hexes == 1);
  CHECK(q.scaled_jacobian.min == Approx(-1));
  CHECK(q.scaled_jacobian.max == Approx(1));
  CHECK(q.scaled_jacobian.median == Approx(1));
  CHECK(q.scaled_jacobian_histogram[0] == 1);
  CHECK(q.scaled_jacobian_histogram[19] == 15);

  CHECK(q.volume == Approx(0.0625 * 14)); // 15 positive hexahedra, 1 negative
  CHECK(q.coverage == Approx(0.875));
  CHECK(q.edge_length.count == 4 * 3 * 3 + 5 * 2 * 3 + 5 * 3 * 2);
  CHECK(q.boundary_quadrilaterals == 2 * (4 * 2 + 4 * 2 + 2 * 2));
  CHECK(q.metric_edge_length.min == Approx(1));
  CHECK(q.metric_edge_length.max == Approx(1));
  CHECK(q.metric_edges_within_25_percent == 1);
  CHECK(q.metric_size.median == Approx(1));
  CHECK(q.metric_size.min == Approx(-1)); // the inverted hexahedron's signed size
  CHECK(q.metric_sizes_within_25_percent == Approx(15.0 / 16));
  CHECK(q.scaled_jacobians.size() == 16);

  // A metric varying along x: the metric length of an edge is the integral of its density.
  Hex_mesh_3 bar = grid(1, 1, 1);
  options.metric = [](const Eigen::Vector3d& x) -> Eigen::Matrix3d {
    return (1 + x.x()) * (1 + x.x()) * Eigen::Matrix3d::Identity();
  };
  const Hex_mesh_quality_3 b = hex_mesh_quality(bar, options);
  CHECK(b.metric_edge_length.max == Approx(2)); // the edges at x = 1
  CHECK(b.metric_edge_length.min == Approx(1)); // at x = 0
  CHECK(b.metric_edge_length.median == Approx(1.5)); // along x: integral of 1 + x over [0, 1]
  // The metric volume: the integral of sqrt(det g) = (1 + x)^3 over the cube, 15/4.
  CHECK(b.metric_size.median == Approx(std::cbrt(15.0 / 4)).epsilon(1e-13));
}

TEST_CASE("Hex mesh quality: bad input is named", "[hex_mesh][quality]") {
  Hex_mesh_3 m = grid(1, 1, 1);
  m.hexahedra[0][3] = 99;
  REQUIRE_THROWS_WITH(hex_mesh_quality(m), Catch::Contains("hexahedron 1") && Catch::Contains("out of range"));
  m = grid(1, 1, 1);
  m.points[2].x() = std::nan("");
  REQUIRE_THROWS_WITH(hex_mesh_quality(m), Catch::Contains("hexahedron 1") && Catch::Contains("not finite"));
  m = grid(1, 1, 1);
  Hex_mesh_quality_options options;
  options.metric = [](const Eigen::Vector3d&) -> Eigen::Matrix3d { return -Eigen::Matrix3d::Identity(); };
  REQUIRE_THROWS_WITH(hex_mesh_quality(m, options), Catch::Contains("not positive definite"));
  // A positive determinant is not enough: diag(-1, -1, 1).
  options.metric = [](const Eigen::Vector3d&) -> Eigen::Matrix3d { return Eigen::Vector3d(-1, -1, 1).asDiagonal(); };
  REQUIRE_THROWS_WITH(hex_mesh_quality(m, options), Catch::Contains("hexahedron 1"));
}

namespace {

// Two unit cubes sharing a face, as HexEx writes them (half-faces pointing
// into their cells; the shared face's second use reversed), a tetrahedron,
// and a cell of 5 quads (written by scripts/test_hex_mesh_quality.py's ovm_text).
const char* two_cubes_ovm = R"(OVM ASCII
# two hexahedra, a tetrahedron, an open cell
Vertices
12
0 0 0
1 0 0
2 0 0
0 1 0
1 1 0
2 1 0
0 0 1
1 0 1
2 0 1
0 1 1
1 1 1
2 1 1
Edges
23
9 10
10 7
7 6
6 9
1 4
4 3
3 0
0 1
10 4
1 7
3 9
6 0
10 11
11 8
8 7
2 5
5 4
1 2
11 5
2 8
0 2
4 0
2 4
Faces
15
4 0 2 4 6
4 8 10 12 14
4 3 16 9 18
4 13 20 7 22
4 19 15 23 5
4 1 21 11 17
4 24 26 28 3
4 30 32 9 34
4 27 36 31 38
4 39 35 18 29
4 25 16 33 37
3 40 35 15
3 14 8 42
3 34 44 9
3 43 45 41
Polyhedra
4
6 0 2 4 6 8 10
6 12 14 16 5 18 20
4 22 24 26 28
5 0 2 4 6 8
)";

} // namespace

TEST_CASE(".ovm files: hexahedra in VTK order, other cells reported, bad files named", "[hex_mesh][ovm]") {
  const std::string path = "test_two_cubes.ovm";
  write_text(path, two_cubes_ovm);
  const IO::Ovm_hex_mesh r = IO::read_ovm_hex_mesh(path);
  REQUIRE(r.mesh.points.size() == 12);
  REQUIRE(r.mesh.hexahedra.size() == 2);
  // Both positively oriented unit cubes, whatever vertex starts them.
  for (const auto& h : r.mesh.hexahedra) {
    Hex_points p;
    for (std::size_t k = 0; k < 8; ++k) p[k] = r.mesh.points[h[k]];
    CHECK(hex_scaled_jacobian(p).value == Approx(1));
    CHECK(hex_volume(p) == Approx(1));
  }
  REQUIRE(r.other_cells.size() == 2);
  CHECK(r.other_cells[0].cell == 2);
  CHECK(r.other_cells[0].reason == "not 6 quadrilaterals");
  CHECK(r.other_cells[1].cell == 3);
  CHECK(r.other_cells[1].reason == "not 6 quadrilaterals");
  CHECK(hex_mesh_quality(r.mesh).boundary_quadrilaterals == 10);

  // The first cell with its first face reversed: not consistently oriented.
  std::string flipped = two_cubes_ovm;
  flipped.replace(flipped.find("6 0 2 4 6 8 10"), 14, "6 1 2 4 6 8 10");
  write_text(path, flipped);
  const IO::Ovm_hex_mesh f = IO::read_ovm_hex_mesh(path);
  CHECK(f.mesh.hexahedra.size() == 1);
  REQUIRE(f.other_cells.size() == 3);
  CHECK(f.other_cells[0].cell == 0);
  CHECK(f.other_cells[0].reason == "faces not closed or not consistently oriented");

  const testing::Edited_file_errors expect_error{path, [&] { IO::read_ovm_hex_mesh(path); }};
  expect_error(two_cubes_ovm, "OVM ASCII", "OVM BINARY", 1, "", "only 'OVM ASCII'");
  expect_error(two_cubes_ovm, "OVM ASCII", "MeshVersionFormatted 2", 1, "", "not an OpenVolumeMesh file");
  expect_error(two_cubes_ovm, "2 1 1\nEdges", "2 1 nan\nEdges", 16, "vertex 12", "");
  expect_error(two_cubes_ovm, "Edges\n23\n9 10", "Edges\n23\n9 12", 19, "edge 1", "out of range");
  expect_error(two_cubes_ovm, "Edges\n23\n9 10", "Edges\n23\n9 9", 19, "edge 1", "to itself");
  expect_error(two_cubes_ovm, "Edges\n23\n9 10", "Edges\n23\n9 x", 19, "edge 1", "'x'");
  expect_error(two_cubes_ovm, "4 0 2 4 6\n4 8", "4 0 2 4 x\n4 8", 44, "face 1", "'x'");
  expect_error(two_cubes_ovm, "4 0 2 4 6\n4 8", "4 0 1 0 1\n4 8", 44, "face 1", "uses an edge twice");
  expect_error(two_cubes_ovm, "6 0 2 4 6 8 10", "6 0 2 4 6 8 y", 61, "polyhedron 1", "'y'");
  expect_error(two_cubes_ovm, "6 0 2 4 6 8 10", "60 0 2 4 6 8 10", 61, "polyhedron 1", "valence 60");
  expect_error(two_cubes_ovm, "4 0 2 4 6\n4 8", "4 0 2 4 7\n4 8", 44, "face 1", "closed loop");
  expect_error(two_cubes_ovm, "4 0 2 4 6\n4 8", "2 0 1\n4 8", 44, "face 1", "valence 2");
  expect_error(two_cubes_ovm, "6 0 2 4 6 8 10", "6 0 2 4 6 8 30", 61, "polyhedron 1", "out of range");
  expect_error(two_cubes_ovm, "Polyhedra\n4", "Polyhedra\n400000", 60, "Polyhedra", "more than the rest of the file");
  expect_error(two_cubes_ovm, "Polyhedra", "Cells", 59, "", "expected the section 'Polyhedra'");
}

TEST_CASE("Medit hex meshes: hexahedra in VTK order, boundary quads, edges, references", "[hex_mesh][medit]") {
  Hex_mesh_3 m = grid(2, 1, 1);
  m.hexahedron_references = {3, 4};
  m.quadrilaterals = hex_mesh_boundary_quadrilaterals(m.hexahedra);
  m.edges = {{0, 1}, {1, 2}};
  const std::string path = "test_hexes.mesh";
  IO::write_medit_hex_mesh(path, m);
  // Read back with the Medit tokenizer: the sections, counts, 1-based indices and references.
  IO::Medit_tokenizer tk(path);
  auto keyword = [&](const char* k) { CHECK(IO::Medit_tokenizer::keyword_equals(tk.expect(k), k)); };
  keyword("MeshVersionFormatted");
  CHECK(tk.read_int("version") == 2);
  keyword("Dimension");
  CHECK(tk.read_int("dimension") == 3);
  keyword("Vertices");
  REQUIRE(tk.read_int("count") == 12);
  for (std::size_t v = 0; v < 12; ++v) {
    for (int d = 0; d < 3; ++d) CHECK(tk.read_double("x") == m.points[v][d]);
    CHECK(tk.read_int("ref") == 0);
  }
  keyword("Hexahedra");
  REQUIRE(tk.read_int("count") == 2);
  for (std::size_t h = 0; h < 2; ++h) {
    for (std::size_t k = 0; k < 8; ++k) CHECK(std::size_t(tk.read_int("v")) == m.hexahedra[h][k] + 1);
    CHECK(tk.read_int("ref") == m.hexahedron_references[h]);
  }
  keyword("Quadrilaterals");
  REQUIRE(tk.read_int("count") == 10);
  for (std::size_t i = 0; i < 10 * 5; ++i) tk.read_int("quad");
  keyword("Edges");
  REQUIRE(tk.read_int("count") == 2);
  for (std::size_t i = 0; i < 2 * 3; ++i) tk.read_int("edge");
  keyword("End");

  Hex_mesh_3 bad = m;
  bad.quadrilateral_references = {1};
  REQUIRE_THROWS_WITH(IO::write_medit_hex_mesh(path, bad), Catch::Contains("1 references for 10 quadrilaterals"));
  bad = m;
  bad.hexahedra[1][5] = bad.hexahedra[1][4];
  REQUIRE_THROWS_WITH(IO::write_medit_hex_mesh(path, bad), Catch::Contains("hexahedron 2 repeats a vertex"));
  bad = m;
  bad.edges[1][0] = 12;
  REQUIRE_THROWS_WITH(IO::write_medit_hex_mesh(path, bad), Catch::Contains("edge 2: vertex index 12"));
  // Nothing the user had is overwritten by a refused write.
  CHECK(IO::Medit_tokenizer(path).remaining_bytes() > 0);
}

TEST_CASE("VTU hexahedra: cell type 12, 8 vertices each, cell data", "[hex_mesh][vtu]") {
  const Hex_mesh_3 m = grid(2, 1, 1);
  std::vector<std::array<double, 3>> points;
  for (const auto& p : m.points) points.push_back({p.x(), p.y(), p.z()});
  const std::string path = "test_hexes.vtu";
  IO::write_vtu_hexahedra(path, points, m.hexahedra, {{"scaled_jacobian", 1, {1.0, 0.5}, false}});
  const auto v = testing::read_vtu(path);
  REQUIRE(v.number_of_cells == 2);
  CHECK(v.types.values == std::vector<double>{12, 12});
  CHECK(v.offsets.values == std::vector<double>{8, 16});
  for (std::size_t i = 0; i < 16; ++i) CHECK(v.connectivity.values[i] == double(m.hexahedra[i / 8][i % 8]));
  CHECK(v.cell_data.at("scaled_jacobian").values == std::vector<double>{1.0, 0.5});
  auto bad = m.hexahedra;
  bad[1][7] = 40;
  REQUIRE_THROWS_WITH(IO::write_vtu_hexahedra(path, points, bad, {}), Catch::Contains("hexahedron 1 (0-based)"));
}
