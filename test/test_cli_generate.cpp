// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// metric-frames generate: the five output files (read back with our own VTU
// reader and the .fra reader), the report, thread-count independence, and
// clear errors for bad input, with nothing overwritten.
#include <catch2/catch.hpp>

#include "cli_test_support.h"
#include "vtu_test_reader.h"

#include <CGAL_ext/IO/Fra_file.h>
#include <CGAL_ext/IO/Medit_mesh.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <string>

using namespace cgal_ext_cli_test;

namespace {

const std::string cube = data_dir + "/cube_kuhn_2.mesh";   // [0,2]^3, Kuhn tets of unit cubes
const std::string l_shape = data_dir + "/l_shape.mesh";    // [0,2]^3 without x, y > 1

double number_after(const std::string& text, const std::string& key) {
  const auto k = text.find("\"" + key + "\": ");
  REQUIRE(k != std::string::npos);
  return std::stod(text.substr(k + key.size() + 4));
}

// Whether v is +-s e_k for some k, to 1e-9.
int axis_of(const double* v, double s) {
  for (int k = 0; k < 3; ++k) {
    bool ok = std::abs(std::abs(v[k]) - s) < 1e-9;
    for (int m = 0; m < 3; ++m)
      if (m != k) ok = ok && std::abs(v[m]) < 1e-9;
    if (ok) return k;
  }
  return -1;
}

} // namespace

TEST_CASE("generate writes the five files; identity metric on a cube gives axis frames", "[cli][generate]") {
  const auto out = work / "cube_out";
  const Run r = run("generate " + cube + " -o " + out.string());
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(r.err.find("[stage] linear initialisation") != std::string::npos);
  CHECK(r.err.find("singular edges") != std::string::npos);
  const CGAL_ext::IO::Medit_mesh input = CGAL_ext::IO::read_medit_mesh(cube);
  const std::size_t nt = input.tetrahedra.size();

  const std::string report = slurp(out / "report.json");
  CHECK(number_after(report, "tets") == nt);
  CHECK(number_after(report, "singular_edges") == 0);
  CHECK(number_after(report, "smoothness_energy") < 1e-9);
  CHECK(report.find("\"boundary_alignment_error_deg\"") != std::string::npos);
  CHECK(report.find("\"g_orthonormality_max_error\"") != std::string::npos);
  CHECK(report.find("\"stage_seconds\"") != std::string::npos);

  const auto frames = CGAL_ext::IO::read_fra((out / "frames.fra").string());
  REQUIRE(frames.size() == nt);
  for (const auto& f : frames) {
    std::array<int, 3> axes{axis_of(&f[0], 1), axis_of(&f[3], 1), axis_of(&f[6], 1)};
    std::sort(axes.begin(), axes.end());
    CHECK(axes == (std::array<int, 3>{0, 1, 2}));
  }

  const auto vtu = cgal_ext_vtu_test::read_vtu((out / "frames.vtu").string());
  CHECK(vtu.number_of_cells == nt);
  CHECK(vtu.number_of_points == input.vertices.size());
  for (const char* name : {"frame_1", "frame_2", "frame_3"}) {
    REQUIRE(vtu.cell_data.count(name));
    CHECK(vtu.cell_data.at(name).components == 3);
    CHECK(vtu.cell_data.at(name).values.size() == 3 * nt);
  }
  REQUIRE(vtu.cell_data.count("metric"));
  CHECK(vtu.cell_data.at("metric").values.size() == 9 * nt);
  for (const char* name : {"energy_density", "boundary", "alignment_error_deg"}) {
    REQUIRE(vtu.cell_data.count(name));
    CHECK(vtu.cell_data.at(name).values.size() == nt);
  }
  // frame_1 of tet 0 is the first vector of its .fra frame.
  for (int c = 0; c < 3; ++c) CHECK(vtu.cell_data.at("frame_1").values[c] == frames[0][c]);
  // "boundary" flags exactly the tets with a facet that no other tet shares.
  std::map<std::array<std::size_t, 3>, int> facet_count;
  auto facet = [&](std::size_t t, int skip) {
    std::array<std::size_t, 3> f;
    for (int k = 0, m = 0; k < 4; ++k)
      if (k != skip) f[m++] = input.tetrahedra[t][k];
    std::sort(f.begin(), f.end());
    return f;
  };
  for (std::size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 4; ++k) ++facet_count[facet(t, k)];
  const auto& b = vtu.cell_data.at("boundary").values;
  for (std::size_t t = 0; t < nt; ++t) {
    bool on_boundary = false;
    for (int k = 0; k < 4; ++k) on_boundary = on_boundary || facet_count[facet(t, k)] == 1;
    CHECK(b[t] == (on_boundary ? 1.0 : 0.0));
  }

  const auto sing = cgal_ext_vtu_test::read_vtu((out / "singularities.vtu").string());
  CHECK(sing.number_of_cells == 0);
  CHECK(CGAL_ext::IO::read_medit_mesh((out / "mesh.mesh").string()).tetrahedra == input.tetrahedra);
}

TEST_CASE("generate with a constant metric gives F = A^-1 up to the group", "[cli][generate]") {
  const auto out = work / "aniso_out";
  const Run r = run("generate " + l_shape + " --metric-const '1 0 16 0 0 4' -o " + out.string());
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const auto frames = CGAL_ext::IO::read_fra((out / "frames.fra").string());
  REQUIRE(!frames.empty());
  for (const auto& f : frames) {
    // Each column is +-(1,0,0), +-(0,1/4,0) or +-(0,0,1/2).
    int found = 0;
    for (int k = 0; k < 3; ++k) {
      const double* v = &f[3 * k];
      found += axis_of(v, 1) == 0 || axis_of(v, 0.25) == 1 || axis_of(v, 0.5) == 2;
    }
    CHECK(found == 3);
  }
  const std::string report = slurp(out / "report.json");
  CHECK(number_after(report, "singular_edges") == 0);
  CHECK(number_after(report, "g_orthonormality_max_error") < 1e-12);
}

TEST_CASE("generate output does not depend on the thread count", "[cli][generate]") {
  const std::string expr = "'1 + x^2, 0.3 * x * y, 2 + y, 0, 0.1 * z, 1 + z^2'";
  const Run a = run("generate " + l_shape + " --metric-expr " + expr + " --threads 1 -o " + (work / "t1").string());
  const Run b = run("generate " + l_shape + " --metric-expr " + expr + " --threads 2 -o " + (work / "t2").string());
  INFO(a.err << b.err);
  REQUIRE(a.exit_code == 0);
  REQUIRE(b.exit_code == 0);
  CHECK(slurp(work / "t1" / "frames.fra") == slurp(work / "t2" / "frames.fra"));
  CHECK(slurp(work / "t1" / "frames.vtu") == slurp(work / "t2" / "frames.vtu"));
  CHECK(slurp(work / "t1" / "singularities.vtu") == slurp(work / "t2" / "singularities.vtu"));
}

TEST_CASE("generate refuses to overwrite outputs without --force", "[cli][generate]") {
  const auto out = work / "keep_out";
  std::filesystem::create_directories(out);
  const std::string mine = file_with("keep_out/report.json", "my notes\n");
  const Run r = run("generate " + cube + " -o " + out.string());
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("exists") != std::string::npos);
  CHECK(r.err.find("--force") != std::string::npos);
  CHECK(slurp(mine) == "my notes\n");
  CHECK(!std::filesystem::exists(out / "frames.fra"));
  const Run f = run("generate " + cube + " --force -o " + out.string());
  CHECK(f.exit_code == 0);
  CHECK(slurp(mine) != "my notes\n");
}

TEST_CASE("generate rejects bad input with a clear message", "[cli][generate]") {
  const auto out = (work / "bad_out").string();
  SECTION("a metric that is not positive definite") {
    const Run r = run("generate " + cube + " --metric-const '1 0 -1 0 0 1' -o " + out);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("--metric-const") != std::string::npos);
    CHECK(r.err.find("positive definite") != std::string::npos);
  }
  SECTION("a constant metric with NaN") {
    const Run r = run("generate " + cube + " --metric-const '1 0 nan 0 0 1' -o " + out);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("--metric-const") != std::string::npos);
  }
  SECTION("a constant metric with the wrong count") {
    const Run r = run("generate " + cube + " --metric-const '1 2 3 4' -o " + out);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("expected 6 numbers") != std::string::npos);
  }
  SECTION("a .sol file for another mesh") {
    const std::string sol = file_with("short.sol", "MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n2\n1 3\n"
                                                   "1 0 1 0 0 1\n1 0 1 0 0 1\nEnd\n");
    const Run r = run("generate " + cube + " --metric " + sol + " -o " + out);
    CHECK(r.exit_code == 1);
    CHECK(r.err.find("short.sol") != std::string::npos);
  }
  SECTION("a metric formula that is not SPD at a vertex") {
    const Run r = run("generate " + cube + " --metric-expr '1, 0, x - 1, 0, 0, 1' -o " + out);
    CHECK(r.exit_code == 1);
    CHECK(r.err.find("vertex") != std::string::npos);
  }
  SECTION("a missing input file") {
    const Run r = run("generate " + (work / "nothing.mesh").string() + " -o " + out);
    CHECK(r.exit_code == 1);
    CHECK(r.err.find("nothing.mesh") != std::string::npos);
  }
  SECTION("an unknown input kind") {
    const Run r = run("generate " + file_with("model.xyz", "1 2 3\n") + " -o " + out);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("model.xyz") != std::string::npos);
  }
  SECTION("a .sol metric with a generated mesh") {
    const Run r = run("generate builtin:ball --metric " + cube + " -o " + out);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("--metric SOL needs a .mesh") != std::string::npos);
  }
  SECTION("meshing options with a tet mesh input") {
    const Run r = run("generate " + cube + " --size 0.1 -o " + out);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("--size") != std::string::npos);
    const Run s = run("generate " + cube + " --smooth-surface -o " + out);
    CHECK(s.exit_code == 2);
  }
  SECTION("an unknown builtin shape") {
    const Run r = run("generate builtin:teapot -o " + out);
    CHECK(r.exit_code == 1);
    CHECK(r.err.find("teapot") != std::string::npos);
    CHECK(r.err.find("ball") != std::string::npos);
  }
  CHECK(!std::filesystem::exists(work / "bad_out" / "frames.fra"));
}

TEST_CASE("generate meshes a built-in shape with Mesh_3", "[cli][generate]") {
  const auto out = work / "ball_out";
  const Run r = run("generate builtin:ball --size 0.35 -o " + out.string());
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(r.err.find("[stage] Mesh_3") != std::string::npos);
  const std::string report = slurp(out / "report.json");
  const auto mesh = CGAL_ext::IO::read_medit_mesh((out / "mesh.mesh").string());
  CHECK(number_after(report, "tets") == mesh.tetrahedra.size());
  CHECK(CGAL_ext::IO::read_fra((out / "frames.fra").string()).size() == mesh.tetrahedra.size());
  CHECK(number_after(report, "g_orthonormality_max_error") < 1e-9);
}
