// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// metric-frames transport: one JSON line per pair (the rotation, or why there
// is none), exit codes, and one clear error line for bad input.
#include <catch2/catch.hpp>

#include "cli_test_support.h"

#include <CGAL_ext/IO/Medit_mesh.h>

#include <cmath>
#include <cstdlib>
#include <chrono>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

using namespace CGAL_ext::testing;

namespace {

// [0,2]^3 without the cube x, y > 1 (Kuhn tets of unit cubes); 24 vertices.
const std::string l_shape = data_dir + "/l_shape.mesh";

// A .sol file of the L-shape from formulas, made by `metric-frames metric`.
std::string metric_file(const std::string& name, const std::string& expr) {
  const std::string path = (work / name).string();
  const Run r = run("metric " + l_shape + " --expr '" + expr + "' -o " + path + " --force");
  REQUIRE(r.exit_code == 0);
  return path;
}

// Whether a transport line holds exactly the identity, reached without error.
bool is_identity(const nlohmann::json& line) {
  return line["R"] == nlohmann::json::parse("[1, 0, 0, 0, 1, 0, 0, 0, 1]") && line["angle"] == 0 &&
         line["evaluations"].is_number_unsigned() && !line.contains("converged");
}

const std::string pairs_content = "# ax ay az bx by bz\n"
                                  "0.2 0.3 0.4 1.8 0.6 1.7\n" // inside
                                  "1.8 0.5 1 0.5 1.8 1\n"     // across the notch: leaves and re-enters
                                  "\n"
                                  "1.5 1.5 1 0.5 0.5 1\n"     // from the notch: starts outside
                                  "0.5 0.5 0.5 0.5 0.5 0.5\n" // a == b
                                  "0 0 0 2 0 2\n";            // along two boundary edges (face diagonals)

// Gmsh's box with a hole, and a .sol giving 1e-30 I and 1e30 I to its
// vertices of even and odd index.
const std::string gmsh_box = data_dir + "/gmsh_box_with_hole.mesh";
std::string jumping_metric_file() {
  const std::size_t n = CGAL_ext::IO::read_medit_mesh(gmsh_box).vertices.size();
  std::string sol = "MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n" + std::to_string(n) + "\n1 3\n";
  for (std::size_t i = 0; i < n; ++i) sol += i % 2 ? "1e30 0 1e30 0 0 1e30\n" : "1e-30 0 1e-30 0 0 1e-30\n";
  return file_with("jumping.sol", sol + "End\n");
}

} // namespace

TEST_CASE("transport: a constant metric gives exactly the identity, and outside pairs an error line",
          "[cli][transport]") {
  const std::string constant = metric_file("constant.sol", "1, 0, 16, 0, 0, 4");
  const std::string pairs = file_with("pairs.txt", pairs_content);
  const Run c = run("transport " + l_shape + " --metric " + constant + " --pairs " + pairs);
  REQUIRE(c.exit_code == 0);
  const auto out = json_lines(c.out);
  REQUIRE(out.size() == 5);
  for (std::size_t i = 0; i < 5; ++i) CHECK(out[i]["pair"] == i);
  CHECK(is_identity(out[0]));
  CHECK(out[1] == nlohmann::json::parse(R"({"pair": 1, "error": "the segment leaves the domain at t = 0.384615 and )"
                                        R"(re-enters it at t = 0.615385"})"));
  CHECK(out[2] == nlohmann::json::parse(R"({"pair": 2, "error": "the start point is outside the domain"})"));
  CHECK(is_identity(out[3]));
  CHECK(out[3]["evaluations"] == 0); // a = b
  CHECK(is_identity(out[4]));
  CHECK(c.out.find("{\"pair\":0,\"R\":[1.0,0.0,0.0,") == 0); // keys in the documented order
  CHECK(c.err.find("[summary] 5 pairs: 3 transported") != std::string::npos);
  CHECK(c.err.find("2 outside the domain") != std::string::npos);
  CHECK(c.err.find("[stage] transport") != std::string::npos);
}

TEST_CASE("transport: a varying metric gives a rotation, the same for any thread count", "[cli][transport]") {
  const std::string varying = metric_file("varying.sol", "1 + x^2, 0.2 * y, 1 + z, 0, 0.1 * x, 2 + y");
  const std::string pairs = file_with("pairs.txt", pairs_content);
  const std::string base = "transport " + l_shape + " --metric " + varying + " --pairs " + pairs;
  const Run m1 = run(base + " --threads 1");
  const Run m2 = run(base + " --threads=2");
  const Run tr = run(base + " --scheme trapezoid --tol 1e-6");
  REQUIRE(m1.exit_code == 0);
  REQUIRE(tr.exit_code == 0);
  CHECK(m1.out == m2.out);
  const auto magnus = json_lines(m1.out), trapezoid = json_lines(tr.out);
  REQUIRE(magnus.size() == 5);
  REQUIRE(trapezoid.size() == 5);
  for (int i : {0, 4}) {
    INFO(magnus[i].dump());
    CHECK(magnus[i]["pair"] == i);
    CHECK(magnus[i]["R"][0].get<double>() > 0.99);
    CHECK(magnus[i]["R"][0].get<double>() < 1);
    // Both schemes are within their tolerance of the same transport.
    const double a = magnus[i]["angle"], b = trapezoid[i]["angle"];
    CHECK(a > 0.01);
    CHECK(std::abs(a - b) <= 1e-8 + 1e-6);
    CHECK(a != b); // but computed by different schemes
    CHECK(magnus[i]["evaluations"] > 0);
  }
  CHECK(is_identity(magnus[3]));
  CHECK(magnus[3]["evaluations"] == 0);
}

TEST_CASE("transport: bad input is one error naming the file with exit 1, bad usage exits with 2", "[cli][transport][bad-input]") {
  const std::string varying = metric_file("varying.sol", "1 + x^2, 0.2 * y, 1 + z, 0, 0.1 * x, 2 + y");
  const std::string pairs = file_with("pairs.txt", pairs_content);
  const std::string bad_pairs = file_with("bad_pairs.txt", "0 0 0 1 1 1\n# comment\n0 0 0 1 1\n");
  const std::string short_sol = file_with("short.sol", "MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n2\n1 3\n"
                                                       "1 0 1 0 0 1\n1 0 1 0 0 1\nEnd\n");
  struct Case {
    std::string args;
    int exit_code;
    std::string expected;
    std::string also_expected = {};
  };
  const Case cases[] = {
      {"--metric " + varying + " --pairs " + pairs + " --scheme euler", 2,
       "metric-frames transport: --scheme: euler not in {magnus,trapezoid}"},
      {"--metric " + varying + " --pairs " + pairs + " --tol 0", 2, "--tol: '0' is not a positive finite number"},
      {"--metric " + varying + " --pairs " + pairs + " --tol -1e-8", 2, "--tol: '-1e-8' is not a positive"},
      {"--metric " + varying + " --pairs " + pairs + " --tol nan", 2, "--tol: 'nan' is not a positive finite number"},
      {"--metric " + varying + " --pairs " + pairs + " --tol inf", 2, "--tol: 'inf' is not a positive finite number"},
      {"--metric " + varying + " --pairs " + pairs + " --tol 1e-8x", 2, "--tol: '1e-8x' is not a positive"},
      {"--metric " + varying + " --pairs " + pairs + " --threads 1.5", 2, "--threads: '1.5' is not a whole number from 1 to 1024"},
      {"--metric " + varying + " --pairs " + pairs + " --threads 0", 2, "--threads: '0' is not a whole number from 1 to 1024"},
      {"--pairs " + pairs, 2, "--metric is required"},
      {"--metric " + varying, 2, "--pairs is required"},
      {"--metric " + varying + " --pairs " + pairs + " extra.mesh", 2, "The following argument was not expected: extra.mesh"},
      {"--metric " + varying + " --pairs " + bad_pairs, 1,
       "metric-frames transport: error: " + bad_pairs + ":3: expected 6 numbers (ax ay az bx by bz), found 5"},
      {"--metric " + varying + " --pairs " + (work / "none.txt").string(), 1,
       "none.txt: cannot open the file for reading"},
      {"--metric " + short_sol + " --pairs " + pairs, 1, "metric-frames transport: error: " + short_sol + ":",
       "SolAtVertices: the file has 2 vertex metrics but the mesh has 24 vertices"},
  };
  for (const Case& k : cases) {
    INFO(k.args);
    const Run e = run("transport " + l_shape + " " + k.args);
    INFO(e.err);
    CHECK(e.exit_code == k.exit_code);
    CHECK(e.out.empty());
    CHECK(e.err.find(k.expected) != std::string::npos);
    CHECK(e.err.find(k.also_expected) != std::string::npos);
  }
  CHECK(run("transport --metric " + varying + " --pairs " + pairs).exit_code == 2); // no MESH
  const Run help = run("transport --help");
  CHECK(help.exit_code == 0);
  CHECK(help.out.find("Usage: metric-frames transport [OPTIONS] MESH\n") == 0);
  for (const char* option : {"--metric SOL", "--pairs FILE", "--tol T", "--scheme S", "--threads N"})
    CHECK(help.out.find(option) != std::string::npos);
}

TEST_CASE("transport: a metric that jumps by 1e30 between vertices ends quickly, and its lines say not converged",
          "[cli][transport][extreme]") {
  // 1e-30 I and 1e30 I at alternate vertices of the L-shape: inside a cell the
  // metric changes by orders of magnitude, and no step size resolves it. The
  // step budget bounds the work (this used to run for minutes); the rotations
  // are flagged on their lines.
  const std::string jumping = jumping_metric_file();
  // Inside the unit box, away from the hole around x = y = 0.5; the second from outside.
  const std::string pairs = file_with("pairs.txt", "0.05 0.05 0.1 0.95 0.1 0.9\n2 2 2 0.1 0.1 0.1\n");
  const auto start = std::chrono::steady_clock::now();
  const Run r = run("transport " + gmsh_box + " --metric " + jumping + " --pairs " + pairs);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(seconds < 60);
  const auto out = json_lines(r.out);
  REQUIRE(out.size() == 2);
  CHECK(out[0]["converged"] == false);
  CHECK(out[0]["error_estimate"].get<double>() > 1e-8);
  CHECK(out[1] == nlohmann::json::parse(R"({"pair": 1, "error": "the start point is outside the domain"})"));
  CHECK(r.err.find("not converged (the metric changes too fast along them") != std::string::npos);
}

TEST_CASE("generate: a metric that jumps by 1e30 between vertices is an error naming two tetrahedra", "[cli][generate][extreme]") {
  const std::string jumping = jumping_metric_file();
  std::string message;
  for (const char* threads : {"1", "2"}) {
    const Run r = run("generate " + gmsh_box + " --metric " + jumping + " --threads " + threads + " -o " +
                      (work / "jumping_out").string() + " --force");
    INFO(r.err);
    CHECK(r.exit_code == 1);
    CHECK(r.err.find("tetrahedra ") != std::string::npos);
    CHECK(r.err.find("does not converge: the metric changes too fast") != std::string::npos);
    const std::string m = r.err.substr(r.err.find("error:"));
    if (message.empty()) message = m;
    CHECK(m == message); // the same tetrahedra whatever the thread count
  }
  CHECK(!std::filesystem::exists(work / "jumping_out" / "frames.fra"));
}

// A mesh whose size double cannot handle (coordinates scaled to 1e100, or
// subnormal) is refused before any transport, naming the mesh file.
TEST_CASE("transport: a mesh beyond the supported sizes is one error naming the mesh", "[cli][transport][extreme]") {
  CGAL_ext::IO::Medit_mesh m = CGAL_ext::IO::read_medit_mesh(gmsh_box);
  std::string sol = "MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n" + std::to_string(m.vertices.size()) + "\n1 3\n";
  for (std::size_t i = 0; i < m.vertices.size(); ++i) sol += "1 0 1 0 0 1\n";
  const std::string identity = file_with("identity_box.sol", sol + "End\n");
  for (int e : {333, -1040}) {
    INFO("scale 2^" << e);
    CGAL_ext::IO::Medit_mesh s = m;
    for (auto& p : s.vertices)
      for (double& x : p) x = std::ldexp(x, e);
    const std::string path = (work / ("box_2^" + std::to_string(e) + ".mesh")).string();
    CGAL_ext::IO::write_medit_mesh(path, s);
    const std::string pairs = file_with("scaled_pairs.txt", "0 0 0 0 0 0\n");
    const Run r = run("transport " + path + " --metric " + identity + " --pairs " + pairs);
    CHECK(r.exit_code == 1);
    CHECK(r.out.empty());
    CHECK(r.err.find(path + ": the mesh: spans ") != std::string::npos);
  }
}
