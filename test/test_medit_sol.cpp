// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
// Medit .sol metric files: the MMG layout (lower triangle by rows), scalar
// sizes, free-format syntax, round trip, and every kind of bad input.
#include <CGAL_ext/IO/Medit_sol.h>
#include <CGAL_ext/Input_error.h>

#include "input_error_checks.h"

#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using M3 = Eigen::Matrix3d;
using CGAL_ext::IO::read_medit_sol;

// A fresh directory for this test run's files, removed at exit.
struct Temp_dir {
  fs::path path;
  Temp_dir() {
    std::random_device rd;
    path = fs::temp_directory_path() / ("cgal_ext_test_medit_sol_" + std::to_string(rd()));
    fs::create_directories(path);
  }
  ~Temp_dir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};
fs::path temp_dir() {
  static const Temp_dir dir;
  return dir.path;
}

std::string write_file(const std::string& name, const std::string& text) {
  const fs::path p = temp_dir() / name;
  std::ofstream(p, std::ios::binary) << text;
  return p.string();
}

// Reads and expects an Input_error (see expect_input_error).
void expect_error(const std::string& path, std::size_t expected_count, std::size_t line, const std::string& element,
                  const std::string& words) {
  CGAL_ext::testing::expect_input_error([&] { read_medit_sol(path, expected_count); }, path, line, element, words);
}

const char* header = "MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n";

} // namespace

TEST_CASE("type 3 records are the lower triangle by rows", "[medit_sol]") {
  // m11 m21 m22 m31 m32 m33 with distinct off-diagonal values.
  const std::string p = write_file("order.sol", std::string(header) +
                                                    "2\n1 3\n"
                                                    "4 0.1 5 0.2 0.3 6\n"
                                                    "1 0 1 0 0 1\n"
                                                    "End\n");
  const std::vector<M3> g = read_medit_sol(p, 2);
  REQUIRE(g.size() == 2);
  M3 expected;
  expected << 4, 0.1, 0.2, 0.1, 5, 0.3, 0.2, 0.3, 6;
  CHECK(g[0] == expected);
  CHECK(g[1] == M3::Identity());
}

TEST_CASE("free format: case, comments, indentation, values on the next line, other sections",
          "[medit_sol]") {
  const std::string p = write_file("free.sol",
                                   "# a metric written by hand\n"
                                   "meshversionformatted\n  2\n"
                                   "DIMENSION\n3   # on its own line\n"
                                   "SolAtTetrahedra 2 1 1\n 0.5\n 0.25\n" // skipped: 2 records of 1 value
                                   "  solatvertices\n"
                                   "  3\n"
                                   "  1\n  3\n"
                                   "  2 0 2\n 0 0 2\n" // one record over two lines
                                   "\t1 0 1 0 0 1 # comment after a record\n"
                                   "9 0 4 0 0 1\n"); // no End
  const std::vector<M3> g = read_medit_sol(p, 3);
  REQUIRE(g.size() == 3);
  CHECK(g[0] == 2 * M3::Identity());
  CHECK(g[1] == M3::Identity());
  CHECK(g[2] == Eigen::Vector3d(9, 4, 1).asDiagonal().toDenseMatrix());
  CHECK(read_medit_sol(p).size() == 3); // any count
}

TEST_CASE("type 1 is an isotropic size h: g = I / h^2", "[medit_sol]") {
  const std::string p = write_file("scalar.sol", std::string(header) + "3\n1 1\n0.5\n2\n1e-3\nEnd\n");
  const std::vector<M3> g = read_medit_sol(p, 3);
  REQUIRE(g.size() == 3);
  CHECK(g[0] == 4 * M3::Identity());
  CHECK(g[1] == 0.25 * M3::Identity());
  CHECK((g[2] - 1e6 * M3::Identity()).norm() <= 1e-9);
}

TEST_CASE("write then read gives the same tensors exactly", "[medit_sol]") {
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> U(-1, 1);
  std::vector<M3> g(50);
  for (M3& m : g) {
    const M3 Q = Eigen::Quaterniond(U(rng), U(rng), U(rng), U(rng)).normalized().toRotationMatrix();
    const Eigen::Vector3d l(std::exp(5 * U(rng)), std::exp(5 * U(rng)), std::exp(5 * U(rng)));
    m = Q * l.asDiagonal() * Q.transpose();
    m = 0.5 * (m + m.transpose()).eval(); // exactly symmetric
  }
  const std::string p = (temp_dir() / "roundtrip.sol").string();
  CGAL_ext::IO::write_medit_sol(p, g);
  const std::vector<M3> back = read_medit_sol(p, g.size());
  REQUIRE(back.size() == g.size());
  for (std::size_t i = 0; i < g.size(); ++i) CHECK(back[i] == g[i]);
  CHECK_THROWS_AS(CGAL_ext::IO::write_medit_sol(p, {M3::Constant(std::nan(""))}), std::invalid_argument);
}

TEST_CASE("missing, empty and garbage files", "[medit_sol]") {
  expect_error((temp_dir() / "does_not_exist.sol").string(), 1, 0, "", "cannot open");
  expect_error(write_file("empty.sol", ""), 1, 0, "", "empty");
  expect_error(write_file("blank.sol", "  \n\n # only a comment\n"), 1, 0, "", "no SolAtVertices");
  expect_error(write_file("garbage.sol", "MeshVersionFormatted 2\nDimension 3\nHello world\n"), 1, 3, "",
               "unknown keyword 'Hello'");
  expect_error(write_file("binary.sol", std::string("\x01\x02\xff\xfe", 4)), 1, 1, "", "unknown keyword");
  expect_error(write_file("nosol.sol", "MeshVersionFormatted 2\nDimension 3\nEnd\n"), 1, 0, "", "no SolAtVertices");
  expect_error(write_file("dim2.sol", "MeshVersionFormatted 2\nDimension\n2\n"), 1, 3, "", "Dimension 2");
  expect_error(write_file("badcount.sol", std::string(header) + "two\n1 3\n"), 1, 4, "", "expected the number");
}

TEST_CASE("counts: mismatch, absurd, negative, extra records", "[medit_sol]") {
  const std::string two = "1 0 1 0 0 1\n1 0 1 0 0 1\n";
  expect_error(write_file("mismatch.sol", std::string(header) + "2\n1 3\n" + two), 3, 5, "SolAtVertices",
               "2 vertex metrics but the mesh has 3 vertices");
  // A huge count must be refused before anything is allocated.
  expect_error(write_file("absurd.sol", std::string(header) + "1000000000000000\n1 3\n" + two),
               CGAL_ext::IO::any_vertex_count, 5, "SolAtVertices", "more than the rest of the file can hold");
  expect_error(write_file("absurd_expected.sol", std::string(header) + "1000000000000000\n1 3\n" + two),
               1000000000000000, 5, "SolAtVertices", "more than the rest of the file can hold");
  expect_error(write_file("negative.sol", std::string(header) + "-2\n1 3\n" + two), 2, 4, "SolAtVertices",
               "negative");
  expect_error(write_file("extra.sol", std::string(header) + "1\n1 3\n" + two), 1, 7, "", "unexpected number");
  expect_error(write_file("again.sol", std::string(header) + "1\n1 3\n1 0 1 0 0 1\nSolAtVertices 1 1 3 1 0 1 0 0 1\n"),
               1, 7, "", "a second SolAtVertices");
}

TEST_CASE("truncated files name the vertex", "[medit_sol]") {
  // The last record is cut: the reader gets to it and names it.
  expect_error(write_file("trunc.sol", std::string(header) + "2\n1 3\n1 0 1 0 0 1\n2 0 2 0 0"), 2, 7, "vertex 2",
               "unexpected end of file");
  // Far fewer bytes than the count needs: refused at the section header.
  expect_error(write_file("trunc_many.sol", std::string(header) + "3\n1 3\n1 0 1 0 0 1\n2 0 2 0 0"), 3, 5,
               "SolAtVertices", "more than the rest of the file can hold");
  expect_error(write_file("trunc_types.sol", std::string(header) + "3\n1\n"), 3, 0, "", "unexpected end of file");
}

TEST_CASE("unsupported field types and field counts", "[medit_sol]") {
  const std::string rec = "1 0 1 0 0 1\n";
  expect_error(write_file("vector.sol", std::string(header) + "1\n1 2\n1 2 3\n"), 1, 5, "SolAtVertices",
               "type 2 (vector) is not a metric");
  expect_error(write_file("full.sol", std::string(header) + "1\n1 4\n1 0 0 0 1 0 0 0 1\n"), 1, 5, "SolAtVertices",
               "not a metric");
  expect_error(write_file("unknown.sol", std::string(header) + "1\n1 7\n" + rec), 1, 5, "SolAtVertices",
               "unknown solution field type 7");
  expect_error(write_file("twofields.sol", std::string(header) + "1\n2 3 1\n" + "1 0 1 0 0 1 0.5\n"), 1, 5,
               "SolAtVertices", "2 solution fields");
  expect_error(write_file("zerofields.sol", std::string(header) + "1\n0\n"), 1, 5, "SolAtVertices",
               "number of solution fields");
}

TEST_CASE("bad values name the vertex and its line", "[medit_sol]") {
  const std::string ok = "1 0 1 0 0 1\n";
  expect_error(write_file("nan.sol", std::string(header) + "3\n1 3\n" + ok + ok + "1 0 nan 0 0 1\n"), 3, 8,
               "vertex 3", "not finite");
  expect_error(write_file("inf.sol", std::string(header) + "2\n1 3\n" + ok + "1 0 1 0 0 -inf\n"), 2, 7, "vertex 2",
               "not finite");
  expect_error(write_file("overflow.sol", std::string(header) + "2\n1 3\n" + "1e999 0 1 0 0 1\n" + ok), 2, 6,
               "vertex 1", "overflows");
  expect_error(write_file("text.sol", std::string(header) + "2\n1 3\n" + ok + "1 0 one 0 0 1\n"), 2, 7, "vertex 2",
               "expected a metric coefficient");
  // Symmetric by construction, but indefinite: off-diagonal 2 > sqrt(1 * 1).
  expect_error(write_file("indefinite.sol", std::string(header) + "2\n1 3\n" + ok + "1 2 1 0 0 1\n"), 2, 7,
               "vertex 2", "not positive definite");
  expect_error(write_file("zero.sol", std::string(header) + "2\n1 3\n" + "0 0 0 0 0 0\n" + ok), 2, 6, "vertex 1",
               "not positive definite");
  expect_error(write_file("hneg.sol", std::string(header) + "3\n1 1\n0.1\n-0.2\n0.3\n"), 3, 7, "vertex 2",
               "not positive");
  expect_error(write_file("hzero.sol", std::string(header) + "3\n1 1\n0.1\n0.2\n0\n"), 3, 8, "vertex 3",
               "not positive");
  expect_error(write_file("hnan.sol", std::string(header) + "1\n1 1\nNaN\n"), 1, 6, "vertex 1", "not finite");
}

TEST_CASE("metrics near the ends of the double range: 1e308 I is read and tiny ones name their value", "[medit_sol]") {
  // 1e308 I is SPD and representable: g + g^T overflows, g / 2 + g^T / 2 does not.
  const std::vector<M3> big =
      read_medit_sol(write_file("big.sol", std::string(header) + "1\n1 3\n1e308 0 1e308 0 0 1e308\n"), 1);
  REQUIRE(big.size() == 1);
  CHECK(big[0] == 1e308 * M3::Identity());
  // The inverse of 1e-320 I, 1e320 I, overflows.
  expect_error(write_file("tiny.sol", std::string(header) + "2\n1 3\n1 0 1 0 0 1\n1e-320 0 1e-320 0 0 1e-320\n"), 2,
               7, "vertex 2", "smallest eigenvalue 9.99989e-321");
  // g = I / h^2 overflows for h = 1e-160, and underflows for h = 1e160.
  expect_error(write_file("hsmall.sol", std::string(header) + "2\n1 1\n0.1\n1e-160\n"), 2, 7, "vertex 2",
               "size h = 9.9999999999999999e-161 is too small: g = I / h^2 overflows");
  expect_error(write_file("hlarge.sol", std::string(header) + "2\n1 1\n1e160\n0.1\n"), 2, 6, "vertex 1",
               "size h = 1e+160 is too large: g = I / h^2 underflows");
}
