// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// metric-frames generate: the six output files (read back with our own VTU
// reader and the .fra and .perm readers), the hex size and its default
// rules, the report, thread-count independence, and clear errors for bad
// input, with nothing overwritten; and the pipeline's library functions,
// which write the same files.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <catch2/catch.hpp>

#include "cli_test_support.h"
#include "integer_grid_map_checks.h"
#include "test_support.h"
#include "vtu_test_reader.h"

#include <CGAL_ext/Frame_field_pipeline.h>
#include <CGAL_ext/Frame_field_pipeline_report.h>
#include <CGAL_ext/IO/Fra_file.h>
#include <CGAL_ext/IO/Hexex_file.h>
#include <CGAL_ext/IO/Medit_sol.h>
#include <CGAL_ext/IO/Medit_mesh.h>
#include <CGAL_ext/IO/Perm_file.h>
#include <CGAL_ext/make_kuhn_grid.h>

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

using namespace CGAL_ext::testing;

namespace {

const std::string cube = data_dir + "/cube_kuhn_2.mesh";   // [0,2]^3, Kuhn tets of unit cubes
const std::string l_shape = data_dir + "/l_shape.mesh";    // [0,2]^3 without x, y > 1

// report.json, parsed.
nlohmann::json read_report(const std::filesystem::path& dir) { return nlohmann::json::parse(slurp(dir / "report.json")); }

// The number at a JSON pointer ("/singularities/curves") of the report.
double number(const nlohmann::json& report, const std::string& pointer) {
  const nlohmann::json& v = report.at(nlohmann::json::json_pointer(pointer));
  REQUIRE(v.is_number());
  return v.get<double>();
}

// The report without its timings, which differ from run to run.
nlohmann::json without_timings(nlohmann::json report) {
  report.erase("stage_seconds");
  if (report.contains("integer_grid_map"))
    for (const char* key : {"seconds_setup", "seconds_solve", "seconds_untangle"}) report["integer_grid_map"].erase(key);
  return report;
}

// The mean length of the distinct edges of a tet mesh.
double mean_edge_length(const CGAL_ext::IO::Medit_mesh& m) {
  std::map<std::array<std::size_t, 2>, double> edges;
  for (const auto& t : m.tetrahedra)
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) {
        const auto& p = m.vertices[t[a]];
        const auto& q = m.vertices[t[b]];
        edges[{std::min(t[a], t[b]), std::max(t[a], t[b])}] =
            std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
      }
  double sum = 0;
  for (const auto& [e, l] : edges) sum += l;
  return sum / double(edges.size());
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

TEST_CASE("generate writes the six files, and the identity metric on a cube gives axis gradients of length 1/h", "[cli][generate]") {
  const auto out = work / "cube_out";
  const Run r = run("generate " + cube + " -o " + out.string());
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(r.err.find("[stage] linear initialisation") != std::string::npos);
  CHECK(r.err.find("singular edges") != std::string::npos);
  CHECK(r.err.find("expected hexahedra") != std::string::npos);
  const CGAL_ext::IO::Medit_mesh input = CGAL_ext::IO::read_medit_mesh(cube);
  const std::size_t nt = input.tetrahedra.size();

  // No metric, no --hex-size: the hex edge is the mesh's mean edge length.
  const nlohmann::json report = read_report(out);
  const double h = number(report, "/hex_size");
  CHECK(h == Approx(mean_edge_length(input)).epsilon(1e-9));
  CHECK(report["hex_size_rule"] == "mean edge length of the mesh");
  // [0,2]^3; the report's numbers read back as the doubles computed.
  CHECK(number(report, "/expected_hexes") == Approx(8 / (h * h * h)).epsilon(1e-14));
  CHECK(number(report, "/tets") == nt);
  CHECK(number(report, "/singular_edges") == 0);
  CHECK(number(report, "/singularities/non_meshable_edges") == 0);
  CHECK(number(report, "/singularities/curves") == 0);
  CHECK(number(report, "/smoothness_energy") < 1e-9);
  CHECK(report.contains("boundary_alignment_error_deg"));
  CHECK(number(report, "/face_angle_deg/mean") < 1e-6); // a constant field
  CHECK(report.contains("g_orthonormality_max_error"));
  CHECK(report["stage_seconds"].contains("refinement"));
  { // The stages in the order they ran.
    const nlohmann::ordered_json ordered = nlohmann::ordered_json::parse(slurp(out / "report.json"));
    std::vector<std::string> stages;
    for (const auto& item : ordered["stage_seconds"].items()) stages.push_back(item.key());
    INFO(nlohmann::json(stages).dump());
    const auto at = [&](const char* name) { return std::find(stages.begin(), stages.end(), name) - stages.begin(); };
    CHECK(at("read mesh") == 0);
    CHECK(at("build triangulation") == 1);
    CHECK(at("set-up") < at("refinement"));
    CHECK(at("refinement") < at("straightening"));
    CHECK(at("write outputs") == std::ptrdiff_t(stages.size()) - 1);
  }
  // The cube's 12 edges are feature curves meeting at its 8 corners.
  CHECK(number(report, "/sharp_features/angle_deg") == 40);
  CHECK(number(report, "/sharp_features/corners") == 8);
  CHECK(number(report, "/sharp_features/curve_vertices") > 0);
  CHECK(number(report, "/sharp_features/dropped_edges") == 0);
  CHECK(r.err.find("sharp features") != std::string::npos);
  CHECK(r.err.find("sharp edges dropped") == std::string::npos);
  // Flat faces and right-angled edges: hexes can cover it all at any size.
  CHECK(number(report, "/hex_coverage_ceiling/coverage") == 1);
  CHECK(number(report, "/hex_coverage_ceiling/smooth_turning") == 0);
  CHECK(!report["hex_coverage_ceiling"].contains("hex_size_factor_for_0_99")); // every size reaches 0.99
  CHECK(r.err.find("coverage ceiling (curvature)     1.000 at this hex size; 0.99 within reach") != std::string::npos);

  // .fra: the parameter gradients, +-e_k / h.
  const auto frames = CGAL_ext::IO::read_fra((out / "frames.fra").string());
  REQUIRE(frames.size() == nt);
  for (const auto& f : frames) {
    std::array<int, 3> axes{axis_of(&f[0], 1 / h), axis_of(&f[3], 1 / h), axis_of(&f[6], 1 / h)};
    std::sort(axes.begin(), axes.end());
    CHECK(axes == (std::array<int, 3>{0, 1, 2}));
  }
  // .perm: all frames are the same axes, so every matching is the identity.
  const CGAL_ext::IO::Perm_file perm = CGAL_ext::IO::read_perm((out / "frames.perm").string());
  CHECK(perm.tets == nt);
  CHECK(perm.faces.empty());

  const auto vtu = CGAL_ext::testing::read_vtu((out / "frames.vtu").string());
  CHECK(vtu.number_of_cells == nt);
  CHECK(vtu.number_of_points == input.vertices.size());
  for (const char* name : {"hex_edge_1", "hex_edge_2", "hex_edge_3", "parameter_gradient_1", "parameter_gradient_2",
                           "parameter_gradient_3"}) {
    REQUIRE(vtu.cell_data.count(name));
    CHECK(vtu.cell_data.at(name).components == 3);
    CHECK(vtu.cell_data.at(name).values.size() == 3 * nt);
  }
  REQUIRE(vtu.cell_data.count("metric"));
  CHECK(vtu.cell_data.at("metric").values.size() == 9 * nt);
  CHECK(vtu.cell_data.at("metric").values[0] == Approx(1 / (h * h)));
  for (const char* name : {"energy_density", "boundary", "alignment_error_deg", "hard_axes", "hard_constraint_released"}) {
    REQUIRE(vtu.cell_data.count(name));
    CHECK(vtu.cell_data.at(name).values.size() == nt);
  }
  // parameter_gradient_k is vector k of the .fra frame; hex_edge_k = h^2 times it (F = h R, F^-T = R / h).
  for (std::size_t t = 0; t < nt; t += 7)
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) {
        const std::string kk = std::to_string(k + 1);
        CHECK(vtu.cell_data.at("parameter_gradient_" + kk).values[3 * t + c] == frames[t][3 * k + c]);
        CHECK(vtu.cell_data.at("hex_edge_" + kk).values[3 * t + c] == Approx(h * h * frames[t][3 * k + c]).margin(1e-12));
      }
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
  // "hard_axes": an axis on the face's normal for every tet with a boundary
  // face, the whole frame for those with faces on two sides of the cube (at
  // its edges and corners); nothing released (nothing to repair).
  const auto& hard = vtu.cell_data.at("hard_axes").values;
  std::size_t whole_frames = 0;
  for (std::size_t t = 0; t < nt; ++t) {
    std::set<std::pair<int, double>> planes; // the cube's faces that t has a facet on
    for (int k = 0; k < 4; ++k) {
      if (facet_count[facet(t, k)] != 1) continue;
      const auto f = facet(t, k);
      for (int c = 0; c < 3; ++c)
        if (input.vertices[f[0]][c] == input.vertices[f[1]][c] && input.vertices[f[0]][c] == input.vertices[f[2]][c])
          planes.emplace(c, input.vertices[f[0]][c]);
    }
    INFO("tet " << t);
    CHECK((hard[t] == 0 || hard[t] == 1 || hard[t] == 2));
    if (planes.size() == 1) CHECK(hard[t] >= 1);
    if (planes.size() >= 2) CHECK(hard[t] == 2);
    whole_frames += hard[t] == 2;
  }
  CHECK(whole_frames > 0);
  const auto& released = vtu.cell_data.at("hard_constraint_released").values;
  CHECK(std::count(released.begin(), released.end(), 0.0) == std::ptrdiff_t(nt));

  const auto sing = CGAL_ext::testing::read_vtu((out / "singularities.vtu").string());
  CHECK(sing.number_of_cells == 0);
  CHECK(CGAL_ext::IO::read_medit_mesh((out / "mesh.mesh").string()).tetrahedra == input.tetrahedra);
}

TEST_CASE("generate with a constant metric: gradients are the rows of A, scaled by --hex-size", "[cli][generate]") {
  // g = diag(1, 16, 4) on the L-shape (volume 6): A = diag(1, 4, 2).
  for (const double h : {0.0, 0.5}) {
    const auto out = work / (h > 0 ? "aniso_h" : "aniso_out");
    const Run r = run("generate " + l_shape + " --metric-const '1 0 16 0 0 4'" +
                      (h > 0 ? std::string(" --hex-size 0.5 --no-repair") : std::string()) + " -o " + out.string());
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    const double s = h > 0 ? 1 / h : 1; // a given metric is used as it is without --hex-size
    const auto frames = CGAL_ext::IO::read_fra((out / "frames.fra").string());
    REQUIRE(!frames.empty());
    for (const auto& f : frames) {
      // Each vector is +-(1,0,0), +-(0,4,0) or +-(0,0,2), times 1/h.
      std::array<int, 3> axes{};
      for (int k = 0; k < 3; ++k) {
        const double* v = &f[3 * k];
        axes[k] = axis_of(v, s) == 0 ? 0 : axis_of(v, 4 * s) == 1 ? 1 : axis_of(v, 2 * s) == 2 ? 2 : -1;
      }
      std::sort(axes.begin(), axes.end());
      CHECK(axes == (std::array<int, 3>{0, 1, 2}));
    }
    const nlohmann::json report = read_report(out);
    CHECK(number(report, "/singular_edges") == 0);
    CHECK(number(report, "/g_orthonormality_max_error") < 1e-12);
    CHECK(number(report, "/expected_hexes") == Approx(6 * 8 * s * s * s).epsilon(1e-12));
    if (h > 0) CHECK(number(report, "/hex_size") == 0.5);
    else CHECK(report["hex_size"].is_null());
    CHECK(report["repair"].is_null() == (h > 0)); // --no-repair
    CHECK((r.err.find("[stage] repair") != std::string::npos) == (h == 0));
  }
}

TEST_CASE("generate writes negatively oriented input tets positive into mesh.mesh", "[cli][generate]") {
  // CubeCover and HexEx need positive tetrahedra with right-handed frames.
  const auto out = work / "reoriented_out";
  const std::string input = data_dir + "/reoriented.mesh";
  const Run r = run("generate " + input + " -o " + out.string());
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(r.err.find("re-oriented") != std::string::npos);
  const auto in = CGAL_ext::IO::read_medit_mesh(input);
  const auto written = CGAL_ext::IO::read_medit_mesh((out / "mesh.mesh").string());
  REQUIRE(written.tetrahedra.size() == in.tetrahedra.size());
  CHECK(written.vertices == in.vertices);
  auto volume = [](const CGAL_ext::IO::Medit_mesh& m, std::size_t t) {
    const auto& a = m.vertices[m.tetrahedra[t][0]];
    double e[3][3];
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) e[k][c] = m.vertices[m.tetrahedra[t][k + 1]][c] - a[c];
    return e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) - e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
           e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
  };
  std::size_t negative_in = 0;
  for (std::size_t t = 0; t < in.tetrahedra.size(); ++t) {
    negative_in += volume(in, t) < 0;
    CHECK(volume(written, t) > 0);
    auto a = in.tetrahedra[t], b = written.tetrahedra[t];
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    CHECK(a == b); // the same tetrahedron, in the same place
  }
  CHECK(negative_in > 0);
}

TEST_CASE("generate output does not depend on the thread count", "[cli][generate]") {
  const std::string expr = "'1 + x^2, 0.3 * x * y, 2 + y, 0, 0.1 * z, 1 + z^2'";
  const Run a = run("generate " + l_shape + " --metric-expr " + expr + " --hexes --threads 1 -o " + (work / "t1").string());
  const Run b = run("generate " + l_shape + " --metric-expr " + expr + " --hexes --threads 2 -o " + (work / "t2").string());
  INFO(a.err << b.err);
  REQUIRE(a.exit_code == 0);
  REQUIRE(b.exit_code == 0);
  CHECK(slurp(work / "t1" / "frames.fra") == slurp(work / "t2" / "frames.fra"));
  CHECK(slurp(work / "t1" / "frames.vtu") == slurp(work / "t2" / "frames.vtu"));
  CHECK(slurp(work / "t1" / "singularities.vtu") == slurp(work / "t2" / "singularities.vtu"));
  CHECK(slurp(work / "t1" / "frames.perm") == slurp(work / "t2" / "frames.perm"));
  CHECK(!slurp(work / "t1" / "map.hexex").empty());
  CHECK(slurp(work / "t1" / "map.hexex") == slurp(work / "t2" / "map.hexex"));
  // The report too, but for the timings.
  CHECK(without_timings(read_report(work / "t1")) == without_timings(read_report(work / "t2")));
}

TEST_CASE("generate on a Gmsh .msh gives the files it gives on the same mesh in Medit", "[cli][generate][gmsh]") {
  // mesh.mesh, written from the .msh at full precision (and with the vertices
  // kept where they are), is that same mesh as a Medit file.
  const std::string msh = data_dir + "/gmsh/box_41_binary.msh";
  REQUIRE(run("generate " + msh + " --hex-size 0.2 --keep-vertices -o " + (work / "from_msh").string()).exit_code == 0);
  const std::string medit = (work / "from_msh" / "mesh.mesh").string();
  REQUIRE(run("generate " + medit + " --hex-size 0.2 --keep-vertices -o " + (work / "from_mesh").string()).exit_code == 0);
  for (const char* f : {"frames.fra", "frames.perm", "mesh.mesh", "frames.vtu", "singularities.vtu"}) {
    INFO(f);
    CHECK(slurp(work / "from_msh" / f) == slurp(work / "from_mesh" / f));
  }
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
  // An output name taken by a directory: refused before any computation,
  // even with --force, so that no output is replaced.
  const std::string before = slurp(out / "frames.fra");
  std::filesystem::remove(out / "frames.vtu");
  std::filesystem::create_directory(out / "frames.vtu");
  const Run d = run("generate " + cube + " --force --metric-const '4 0 4 0 0 4' -o " + out.string());
  CHECK(d.exit_code == 1);
  CHECK(d.err.find("frames.vtu: is a directory or another non-file") != std::string::npos);
  CHECK(d.err.find("[stage]") == std::string::npos);
  CHECK(slurp(out / "frames.fra") == before);
  CHECK(run("generate " + cube + " -o ''").exit_code == 2); // an empty output path
}

TEST_CASE("generate rejects bad input with a clear message", "[cli][generate]") {
  const auto out = (work / "bad_out").string();
  SECTION("a metric that is not positive definite") {
    const Run r = run("generate " + cube + " --metric-const '1 0 -1 0 0 1' -o " + out);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("--metric-const") != std::string::npos);
    CHECK(r.err.find("positive definite") != std::string::npos);
  }
  SECTION("a feature angle out of range") {
    for (const char* bad : {"0", "-5", "181", "nan", "40deg"}) {
      const Run r = run("generate " + cube + " --feature-angle " + bad + " -o " + out);
      INFO(bad << ": " << r.err);
      CHECK(r.exit_code == 2);
      CHECK(r.err.find("--feature-angle") != std::string::npos);
    }
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
    CHECK(r.err.find("--metric SOL needs a tet mesh INPUT") != std::string::npos);
  }
  SECTION("meshing options with a tet mesh input") {
    const Run r = run("generate " + cube + " --size 0.1 -o " + out);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("--size") != std::string::npos);
    const Run s = run("generate " + cube + " --smooth-surface -o " + out);
    CHECK(s.exit_code == 2);
  }
  SECTION("a hex size that is not a positive number") {
    for (const char* h : {"0", "-0.1", "nan", "inf", "0.1x"}) {
      const Run r = run("generate " + cube + " --hex-size " + h + " -o " + out);
      CHECK(r.exit_code == 2);
      CHECK(r.err.find("--hex-size") != std::string::npos);
    }
  }
  SECTION("repair restarts and rounds that are not whole numbers, or without the repair") {
    for (const std::string option : {"--repair-restarts", "--repair-rounds"}) {
      for (const char* n : {"-1", "1.5", "x"}) {
        const Run r = run("generate " + cube + " " + option + " " + n + " -o " + out);
        CHECK(r.exit_code == 2);
        CHECK(r.err.find(option) != std::string::npos);
      }
      const Run r = run("generate " + cube + " --no-repair " + option + " 2 -o " + out);
      CHECK(r.exit_code == 2);
      CHECK(r.err.find("--no-repair excludes " + option) != std::string::npos);
    }
  }
  SECTION("a hex size so small that the scaled metric overflows") {
    const Run r = run("generate " + cube + " --metric-const '1e300 0 1e300 0 0 1e300' --hex-size 1e-100 -o " + out);
    CHECK(r.exit_code == 1);
    CHECK(r.err.find("hex size") != std::string::npos);
    const Run e = run("generate " + cube + " --metric-expr '1e200, 0, 1e200, 0, 0, 1e200' --hex-size 1e-100 -o " + out);
    CHECK(e.exit_code == 1);
    CHECK(e.err.find("vertex 1") != std::string::npos);
    CHECK(e.err.find("scaled to the hex size") != std::string::npos);
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
  const nlohmann::json report = read_report(out);
  const auto mesh = CGAL_ext::IO::read_medit_mesh((out / "mesh.mesh").string());
  CHECK(number(report, "/tets") == mesh.tetrahedra.size());
  CHECK(CGAL_ext::IO::read_fra((out / "frames.fra").string()).size() == mesh.tetrahedra.size());
  CHECK(number(report, "/g_orthonormality_max_error") < 1e-9);
  // No metric: hexes of the Mesh_3 size; gradients of length 1/h.
  CHECK(number(report, "/hex_size") == 0.35);
  CHECK(report["hex_size_rule"] == "Mesh_3 size");
  const double volume = 4.0 / 3 * M_PI; // the unit ball, approximated from inside
  CHECK(number(report, "/expected_hexes") < volume / (0.35 * 0.35 * 0.35));
  CHECK(number(report, "/expected_hexes") > 0.9 * volume / (0.35 * 0.35 * 0.35));
  // Hexes of 0.35 on the unit sphere: the integral of 2H is 8 pi, 8 pi / 0.35
  // in the metric; the ceiling follows from the report's own numbers.
  const double turning = number(report, "/hex_coverage_ceiling/smooth_turning");
  CHECK(turning == Approx(8 * M_PI / 0.35).epsilon(0.03));
  const double ceiling = number(report, "/hex_coverage_ceiling/coverage");
  CHECK(ceiling < 1);
  CHECK(ceiling == Approx(1 - turning / 12 / number(report, "/expected_hexes")));
  const double factor = number(report, "/hex_coverage_ceiling/hex_size_factor_for_0_99");
  CHECK(factor < 1); // 0.99 needs smaller hexes than 0.35 on a sphere of radius 1
  CHECK(r.err.find("0.99 needs hexes " + CGAL_ext::format_number(factor, 2) + " times as large") != std::string::npos);
  for (const auto& f : CGAL_ext::IO::read_fra((out / "frames.fra").string()))
    for (int k = 0; k < 3; ++k) CHECK(std::hypot(f[3 * k], f[3 * k + 1], f[3 * k + 2]) == Approx(1 / 0.35));
  // The ball's field is singular; every singular edge is in singularities.vtu
  // with its type, and the report's counts agree.
  const double edges = number(report, "/singular_edges");
  CHECK(edges > 0);
  CHECK(number(report, "/singularities/interior_ends") == 0);
  const auto sing = CGAL_ext::testing::read_vtu((out / "singularities.vtu").string());
  CHECK(sing.number_of_cells == edges);
  for (const char* name : {"type", "index", "valence", "meshable", "turn_deg", "axis_angle_deg", "edge_axis_angle_deg",
                           "curve"})
    CHECK(sing.cell_data.at(name).values.size() == edges);
  CHECK(sing.cell_data.at("axis").values.size() == 3 * edges);
  double meshable = 0;
  for (double m : sing.cell_data.at("meshable").values) meshable += m;
  CHECK(edges - meshable == number(report, "/singularities/non_meshable_edges"));
  // The repair ran and its report agrees with the field written.
  CHECK(r.err.find("[stage] repair") != std::string::npos);
  CHECK(number(report, "/repair/non_meshable_after") == number(report, "/straightening/non_meshable_before"));
  CHECK(number(report, "/repair/non_meshable_after") <= number(report, "/repair/non_meshable_before"));
  CHECK(number(report, "/repair/regions_from_restarts") <= number(report, "/repair/regions_kept"));
  CHECK(number(report, "/repair/lbfgs_tet_iterations") >= number(report, "/repair/lbfgs_iterations"));
  CHECK((number(report, "/repair/lbfgs_iterations") > 0) == (number(report, "/repair/regions_tried") > 0));
  for (double c : sing.cell_data.at("curve").values) CHECK(c >= 1);
  CHECK(sing.point_data.at("node").values.size() == sing.number_of_points);
  CHECK(sing.point_data.at("vertex_index").values.size() == sing.number_of_points);
  // Nodes: each judged in report.json and singularities.vtu alike.
  double bad_nodes = 0, vtu_bad_nodes = 0;
  for (const auto& n : report.at(nlohmann::json::json_pointer("/singularities/node_list"))) bad_nodes += !n.at("meshable").get<bool>();
  const auto& node_kind = sing.point_data.at("node").values;
  const auto& vertex_meshable = sing.point_data.at("vertex_meshable").values;
  REQUIRE(vertex_meshable.size() == sing.number_of_points);
  double vtu_touches = 0;
  for (std::size_t p = 0; p < node_kind.size(); ++p)
    (node_kind[p] > 0 ? vtu_bad_nodes : vtu_touches) += vertex_meshable[p] == 0;
  const double touches = number(report, "/singularities/surface_touches"),
               turns = number(report, "/singularities/curve_turns");
  CHECK(bad_nodes == number(report, "/singularities/non_meshable_nodes"));
  CHECK(vtu_bad_nodes == bad_nodes);
  CHECK(vtu_touches == touches + turns); // the vertices on curves that no hex mesh has
  CHECK(number(report, "/straightening/non_meshable_nodes_after") == bad_nodes + turns);
  CHECK(report.at(nlohmann::json::json_pointer("/singularities/curve_turn_list")).size() == turns);
  CHECK(number(report, "/repair/non_meshable_nodes_after") == number(report, "/straightening/non_meshable_nodes_before"));
  CHECK(r.err.find("non-meshable nodes") != std::string::npos);
  CHECK(r.err.find("curves touching the surface") != std::string::npos);
  CHECK(report.at(nlohmann::json::json_pointer("/singularities/surface_touch_list")).size() ==
        number(report, "/singularities/surface_touches"));
  // .perm: vector k of tet1 continues as sign(p_k) times vector |p_k| of tet2
  // (identity metric: no transport; neighbouring frames differ little).
  const CGAL_ext::IO::Perm_file perm = CGAL_ext::IO::read_perm((out / "frames.perm").string());
  CHECK(perm.tets == mesh.tetrahedra.size());
  REQUIRE(!perm.faces.empty());
  const auto frames = CGAL_ext::IO::read_fra((out / "frames.fra").string());
  // The matching is the nearest one: no other rotation of the octahedral
  // group (a signed permutation of determinant 1) gives a larger sum of dot
  // products between tet1's vectors and tet2's (neighbouring frames near a
  // singular edge of this coarse mesh can be more than 45 degrees apart).
  auto sum_of_dots = [&](const CGAL_ext::IO::Perm_face& face, const std::array<int, 3>& p) {
    double sum = 0;
    for (int k = 0; k < 3; ++k) {
      const double* a = &frames[face.tet1][3 * k];
      const double* b = &frames[face.tet2][3 * (std::abs(p[k]) - 1)];
      sum += (p[k] > 0 ? 1 : -1) * (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
    }
    return sum;
  };
  for (const auto& face : perm.faces) {
    const std::array<int, 3> matched = {face.p[0], face.p[1], face.p[2]};
    const double best = sum_of_dots(face, matched);
    CHECK(best > 0);
    std::array<int, 3> q = {1, 2, 3};
    do {
      for (int signs = 0; signs < 8; ++signs) {
        std::array<int, 3> p = q;
        int determinant = (q[0] > q[1]) + (q[0] > q[2]) + (q[1] > q[2]) & 1 ? -1 : 1; // the parity of q
        for (int k = 0; k < 3; ++k)
          if (signs >> k & 1) p[k] = -p[k], determinant = -determinant;
        if (determinant < 0) continue; // not a rotation
        CHECK(sum_of_dots(face, p) <= best + 1e-9 / (0.35 * 0.35));
      }
    } while (std::next_permutation(q.begin(), q.end()));
  }
}

TEST_CASE("generate meshes at the hex size or finer: Mesh_3's automatic size is capped by --hex-size",
          "[cli][generate]") {
  // The built-in cube [-1, 1]^3: the automatic size is its diagonal / 20, 0.173205.
  // Each run: its stderr, and Mesh_3's stage line.
  auto cube = [](const std::string& options, const std::string& dir) {
    const Run r = run("generate builtin:cube " + options + " --no-repair -o " + (work / dir).string());
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    const std::size_t at = r.err.find("[stage] Mesh_3");
    REQUIRE(at != std::string::npos);
    return std::make_pair(r.err, r.err.substr(at, r.err.find('\n', at) - at));
  };
  CHECK(cube("--hex-size 0.4", "cap_coarse").second.find("size 0.173205,") != std::string::npos);
  CHECK(cube("--hex-size 0.15", "cap_fine").second.find("size 0.15,") != std::string::npos);
  CHECK(number(read_report(work / "cap_fine"), "/tets") > 1.3 * number(read_report(work / "cap_coarse"), "/tets"));
  // A constant metric asking for hexes of 0.3 / sqrt(4) along y: the cap is that edge.
  CHECK(cube("--hex-size 0.3 --metric-const '1 0 4 0 0 1'", "cap_metric").second.find("size 0.15,") !=
        std::string::npos);
  // A given --size is used as it is, with a note when it is larger than the hex edge, none when smaller.
  const auto [given, given_line] = cube("--hex-size 0.15 --size 0.5", "cap_given");
  CHECK(given_line.find("size 0.5,") != std::string::npos);
  CHECK(given.find("[note] --size 0.5 is larger than the hex edge 0.15") != std::string::npos);
  const auto [smaller, smaller_line] = cube("--hex-size 0.15 --size 0.14", "cap_smaller");
  CHECK(smaller_line.find("size 0.14,") != std::string::npos);
  CHECK(smaller.find("[note] --size") == std::string::npos);
}

TEST_CASE("generate warns before the long stages when much of the domain is thinner than a hex edge",
          "[cli][generate]") {
  // A slab [0, 1]^2 x [0, 0.125]: its faces (area 2) are 0.125 thick, its sides (area 0.5) 1 wide.
  const std::string slab = (work / "slab.mesh").string();
  std::filesystem::create_directories(work);
  CGAL_ext::IO::write_medit_mesh(slab, CGAL_ext::make_kuhn_grid({8, 8, 1}, 0.125));
  auto generate = [&](const std::string& hex_size, const std::string& dir) {
    const Run r = run("generate " + slab + " --hex-size " + hex_size + " --no-repair -o " + (work / dir).string());
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    return r.err;
  };
  // Hexes of 0.25: the faces are half a hex edge thick, 80% of the boundary
  // by area; 10% of it is under 0.5 hex edges, so hexes of 0.125 leave 10%.
  const std::string thin = generate("0.25", "slab_thin");
  const std::size_t warning = thin.find("[warning] 80% of the boundary is less than one hex edge (h = 0.25) from the opposite side");
  CHECK(warning != std::string::npos);
  CHECK(thin.find("meshable. With --hex-size 0.125, at most 10% of it would be.") != std::string::npos);
  CHECK(warning < thin.find("[stage] refinement")); // before the long stages
  CHECK(thin.find("thin parts                       80.0% of the boundary under one hex edge") != std::string::npos);
  const nlohmann::json report = read_report(work / "slab_thin");
  CHECK(number(report, "/thickness/facets") == 2 * 128 + 4 * 16);
  CHECK(number(report, "/thickness/cap_hex_edges") == 4);
  CHECK(number(report, "/thickness/fraction_below_one_hex_edge") == Approx(0.8).epsilon(1e-12));
  CHECK(number(report, "/thickness/thickness_at_10_percent_hex_edges") == Approx(0.5).epsilon(1e-12));
  // The same hexes from a metric used as it is (16 I: edges of 0.25): the advice scales the metric.
  const Run unscaled = run("generate " + slab + " --metric-const '16 16 16' --no-repair -o " + (work / "slab_metric").string());
  INFO(unscaled.err);
  REQUIRE(unscaled.exit_code == 0);
  CHECK(unscaled.err.find("[warning] 80% of the boundary is less than one hex edge from the opposite side") != std::string::npos);
  CHECK(unscaled.err.find("With hexahedra 0.5 times as large (the metric times 4), at most 10% of it would be.") !=
        std::string::npos);
  // Hexes of 0.1: the faces are 1.25 hex edges thick, and nothing is said.
  const std::string thick = generate("0.1", "slab_thick");
  CHECK(thick.find("[warning]") == std::string::npos);
  CHECK(thick.find("0.0% of the boundary under one hex edge from the opposite side; 10% under 1.25 hex edges") !=
        std::string::npos);
  CHECK(number(read_report(work / "slab_thick"), "/thickness/fraction_below_one_hex_edge") == 0);
}

TEST_CASE("generate lists the curves from a junction shorter than a hex edge", "[cli][generate]") {
  // The ball at two hex sizes (the same field, identity metric scaled to each): the larger has short curves.
  std::size_t most = 0;
  for (const double hex : {0.35, 0.45}) {
    const auto out = work / ("ball_short_" + std::to_string(int(hex * 100)));
    const Run r = run("generate builtin:ball --size 0.35 --hex-size " + std::to_string(hex) + " -o " + out.string());
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    const nlohmann::json report = read_report(out);
    // Exactly the open curves from a junction under one hex edge in the metric (g scaled to the hex size).
    std::set<double> junctions;
    for (const auto& n : report.at(nlohmann::json::json_pointer("/singularities/node_list")))
      if (n.at("kind") == "junction") junctions.insert(n.at("vertex").get<double>());
    const auto& curve_list = report.at(nlohmann::json::json_pointer("/singularities/curve_list"));
    std::vector<double> short_curves; // 1-based, as singularities.vtu's curve numbers
    for (std::size_t k = 0; k < curve_list.size(); ++k) {
      const auto& c = curve_list[k];
      CHECK(c.at("metric_length").get<double>() == Approx(c.at("length").get<double>() / hex)); // identity metric
      if (!c.at("closed").get<bool>() && c.at("metric_length").get<double>() < 1 &&
          (junctions.count(c.at("ends")[0].get<double>()) || junctions.count(c.at("ends")[1].get<double>())))
        short_curves.push_back(double(k + 1));
    }
    std::vector<double> listed;
    for (const auto& k : report.at(nlohmann::json::json_pointer("/singularities/short_curve_list")))
      listed.push_back(k.get<double>());
    CHECK(listed == short_curves);
    CHECK(number(report, "/singularities/short_curves") == short_curves.size());
    const std::string label = "short curves from junctions";
    const std::size_t line = r.err.rfind(label); // the summary's line, after the stage's
    REQUIRE(line != std::string::npos);
    CHECK(std::stoul(r.err.substr(line + label.size())) == short_curves.size());
    most = std::max(most, short_curves.size());
  }
  CHECK(most > 0); // the rule is exercised
}

TEST_CASE("generate straightens the singular curves: only their interior vertices move, and --keep-vertices keeps all",
          "[cli][generate][straightening]") {
  const auto moved_out = work / "ball_straightened", kept_out = work / "ball_kept";
  const Run a = run("generate builtin:ball --size 0.25 -o " + moved_out.string());
  const Run b = run("generate builtin:ball --size 0.25 --keep-vertices -o " + kept_out.string());
  INFO(a.err << b.err);
  REQUIRE(a.exit_code == 0);
  REQUIRE(b.exit_code == 0);
  CHECK(a.err.find("[stage] straightening") != std::string::npos);
  CHECK(b.err.find("[stage] straightening") == std::string::npos);
  const nlohmann::json ra = read_report(moved_out), rb = read_report(kept_out);
  CHECK(rb["straightening"].is_null());
  REQUIRE(ra["straightening"].is_object());
  CHECK(ra["straightening"]["kept"] == true);
  const auto ma = CGAL_ext::IO::read_medit_mesh((moved_out / "mesh.mesh").string());
  const auto mb = CGAL_ext::IO::read_medit_mesh((kept_out / "mesh.mesh").string());
  REQUIRE(ma.tetrahedra == mb.tetrahedra);
  REQUIRE(ma.vertices.size() == mb.vertices.size());
  // The frames are the same (the straightening follows the field's computation).
  CHECK(slurp(moved_out / "frames.fra") == slurp(kept_out / "frames.fra"));
  CHECK(number(ra, "/straightening/non_meshable_before") == number(rb, "/singularities/non_meshable_edges"));
  CHECK(number(ra, "/straightening/non_meshable_after") == number(ra, "/singularities/non_meshable_edges"));

  // The moved vertices: as many as reported, none on the boundary, each on a singular curve.
  const std::vector<char> boundary = CGAL_ext::testing::boundary_vertices(mb.vertices.size(), mb.tetrahedra);
  std::set<std::size_t> on_curves;
  const auto kept_singularities = CGAL_ext::testing::read_vtu((kept_out / "singularities.vtu").string());
  for (double v : kept_singularities.point_data.at("vertex_index").values) on_curves.insert(std::size_t(v) - 1);
  std::size_t moved = 0;
  for (std::size_t v = 0; v < ma.vertices.size(); ++v) {
    if (ma.vertices[v] == mb.vertices[v]) continue;
    ++moved;
    CHECK(boundary[v] == 0);
    CHECK(on_curves.count(v) == 1);
  }
  CHECK(moved > 0);
  CHECK(number(ra, "/straightening/moved_vertices") == moved);
  CHECK(number(ra, "/straightening/curve_vertices") >= moved);
  // Every tetrahedron of the written mesh is still positive (exact predicate), as CubeCover and HexEx need.
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  auto point = [&](std::size_t v) { return K::Point_3(ma.vertices[v][0], ma.vertices[v][1], ma.vertices[v][2]); };
  std::size_t positive = 0;
  for (const auto& t : ma.tetrahedra)
    positive += CGAL::orientation(point(t[0]), point(t[1]), point(t[2]), point(t[3])) == CGAL::POSITIVE;
  CHECK(positive == ma.tetrahedra.size());
  // singularities.vtu and frames.vtu show the moved vertices.
  const auto vtu = CGAL_ext::testing::read_vtu((moved_out / "frames.vtu").string());
  REQUIRE(vtu.points.values.size() == 3 * ma.vertices.size());
  for (std::size_t v = 0; v < ma.vertices.size(); ++v)
    for (int c = 0; c < 3; ++c) CHECK(vtu.points.values[3 * v + std::size_t(c)] == ma.vertices[v][std::size_t(c)]);
  const auto moved_singularities = CGAL_ext::testing::read_vtu((moved_out / "singularities.vtu").string());
  const auto& index = moved_singularities.point_data.at("vertex_index").values;
  REQUIRE(moved_singularities.points.values.size() == 3 * index.size());
  for (std::size_t k = 0; k < index.size(); ++k)
    for (std::size_t c = 0; c < 3; ++c)
      CHECK(moved_singularities.points.values[3 * k + c] == ma.vertices[std::size_t(index[k]) - 1][c]);

  // The guard: no edge is non-meshable with the moved vertices that was not without them. The torus at
  // this size has moves that would make some (2 vertices put back, measured in the Release build).
  const auto torus_moved = work / "torus_straightened", torus_kept = work / "torus_kept";
  const Run t1 = run("generate builtin:torus --hex-size 0.2681876 -o " + torus_moved.string());
  const Run t2 = run("generate builtin:torus --hex-size 0.2681876 --keep-vertices -o " + torus_kept.string());
  INFO(t1.err << t2.err);
  REQUIRE(t1.exit_code == 0);
  REQUIRE(t2.exit_code == 0);
  auto non_meshable = [](const nlohmann::json& report) {
    std::set<std::pair<double, double>> out;
    for (const auto& e : report["singularities"]["non_meshable_edge_list"])
      out.insert({e["vertices"][0].get<double>(), e["vertices"][1].get<double>()});
    return out;
  };
  const nlohmann::json t1r = read_report(torus_moved), t2r = read_report(torus_kept);
  for (const auto& e : non_meshable(t1r)) CHECK(non_meshable(t2r).count(e) == 1);
  CHECK(number(t1r, "/straightening/non_meshable_after") <= number(t1r, "/straightening/non_meshable_before"));
  CHECK(number(t1r, "/straightening/non_meshable_with_moved") == number(t1r, "/straightening/non_meshable_after"));
  // Every non-meshable node or curve turn after the moves was one before, or the end of a non-meshable edge.
  auto bad_vertices = [](const nlohmann::json& report) {
    std::set<double> out;
    for (const auto& n : report["singularities"]["node_list"])
      if (!n["meshable"].get<bool>()) out.insert(n["vertex"].get<double>());
    for (const auto& t : report["singularities"]["curve_turn_list"]) out.insert(t["vertex"].get<double>());
    return out;
  };
  std::set<double> judged = bad_vertices(t2r);
  for (const auto& e : non_meshable(t2r)) judged.insert({e.first, e.second});
  for (double v : bad_vertices(t1r)) CHECK(judged.count(v) == 1);
  // Nor more non-meshable nodes with as many edges (the guard keeps both).
  CHECK(std::make_pair(number(t1r, "/straightening/non_meshable_after"), number(t1r, "/straightening/non_meshable_nodes_after")) <=
        std::make_pair(number(t1r, "/straightening/non_meshable_before"), number(t1r, "/straightening/non_meshable_nodes_before")));
  CHECK(t1r["straightening"]["kept"] == true);

  // A vertex that no tetrahedron uses, first in the file, shifts every index; it is written where it was.
  CGAL_ext::IO::Medit_mesh shifted;
  shifted.vertices.push_back({9, 9, 9});
  shifted.vertices.insert(shifted.vertices.end(), mb.vertices.begin(), mb.vertices.end());
  for (auto t : mb.tetrahedra) {
    for (auto& v : t) ++v;
    shifted.tetrahedra.push_back(t);
  }
  const std::string shifted_path = (work / "ball_unused_vertex.mesh").string();
  CGAL_ext::IO::write_medit_mesh(shifted_path, shifted);
  const auto shifted_out = work / "ball_unused_vertex_out";
  const Run c = run("generate " + shifted_path + " --hex-size 0.25 -o " + shifted_out.string());
  INFO(c.err);
  REQUIRE(c.exit_code == 0);
  CHECK(c.err.find("1 vertices are used by no tetrahedron") != std::string::npos);
  const nlohmann::json rc = read_report(shifted_out);
  CHECK(rc["straightening"]["kept"] == true);
  const auto mc = CGAL_ext::IO::read_medit_mesh((shifted_out / "mesh.mesh").string());
  REQUIRE(mc.vertices.size() == shifted.vertices.size());
  CHECK(mc.vertices[0] == shifted.vertices[0]);
  std::size_t moved_here = 0;
  for (std::size_t v = 1; v < mc.vertices.size(); ++v) moved_here += mc.vertices[v] != shifted.vertices[v];
  CHECK(moved_here == number(rc, "/straightening/moved_vertices"));
  CHECK(moved_here > 0);
}

namespace {

// The mesh of `file` with every coordinate multiplied by 2^e (exactly, for
// normal results), written to the work directory.
std::string scaled_mesh(const std::string& file, int e, const std::string& name) {
  CGAL_ext::IO::Medit_mesh m = CGAL_ext::IO::read_medit_mesh(file);
  for (auto& p : m.vertices)
    for (double& x : p) x = std::ldexp(x, e);
  std::filesystem::create_directories(work);
  const std::string path = (work / name).string();
  CGAL_ext::IO::write_medit_mesh(path, m);
  return path;
}

} // namespace

// The unit of length does not matter: a mesh scaled by 2^+-150 gives the same
// field (the same energies, alignment, singularities), with every length
// scaled exactly; a mesh whose size double cannot handle is refused before
// any work, naming the file and the size.
TEST_CASE("generate's --diffusion-steps reach the field: off by default, on the ball when asked, skipped on a box",
          "[cli][generate][diffusion]") {
  // The diffusion length is in hex edges: the same steps at two hex sizes
  // with the length in proportion give the same field.
  std::map<std::string, nlohmann::json> report;
  for (const std::string& args :
       {"builtin:ball --size 0.35 --hex-size 0.35", "builtin:ball --size 0.35 --hex-size 0.35 --diffusion-steps 2",
        "builtin:ball --size 0.35 --hex-size 0.7 --diffusion-steps 2 --diffusion-length 1",
        "builtin:cube --size 0.35 --diffusion-steps 2"}) {
    const auto out = work / ("diffusion_" + std::to_string(report.size()));
    const Run r = run("generate " + args + " -o " + out.string());
    INFO(args << "\n" << r.err);
    REQUIRE(r.exit_code == 0);
    report[args] = read_report(out);
  }
  const auto& off = report["builtin:ball --size 0.35 --hex-size 0.35"];
  const auto& on = report["builtin:ball --size 0.35 --hex-size 0.35 --diffusion-steps 2"];
  const auto& half = report["builtin:ball --size 0.35 --hex-size 0.7 --diffusion-steps 2 --diffusion-length 1"];
  const auto& cube = report["builtin:cube --size 0.35 --diffusion-steps 2"];
  CHECK(number(off, "/diffusion/steps") == 0);
  CHECK(number(off, "/diffusion/energy") == number(off, "/projected_energy"));
  CHECK(number(on, "/diffusion/steps") == 2);
  CHECK(number(on, "/diffusion/length") == 2);
  CHECK(number(on, "/diffusion/iterations") > 0);
  CHECK(number(on, "/diffusion/energy") != number(on, "/projected_energy"));
  CHECK(number(half, "/diffusion/steps") == 2);
  CHECK(number(half, "/smoothness_energy_per_weight") ==
        Approx(number(on, "/smoothness_energy_per_weight")).epsilon(1e-6)); // 0.7 is 2 x 0.35 up to its last bit
  CHECK(number(half, "/singular_edges") == number(on, "/singular_edges"));
  CHECK(number(cube, "/sharp_features/edges") > 0);
  CHECK(number(cube, "/diffusion/steps") == 0);
}

TEST_CASE("generate reports the sharp edges it drops as below the mesh's resolution", "[cli][generate]") {
  // Gmsh's anchor at a uniform size: spurs where its coarse fillets meet the creases.
  const auto out = work / "gmsh_anchor";
  const Run r = run("generate " + data_dir + "/gmsh_anchor.mesh --no-repair -o " + out.string());
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const nlohmann::json report = read_report(out);
  const double dropped = number(report, "/sharp_features/dropped_edges");
  CHECK(dropped > 0);
  CHECK(number(report, "/sharp_features/edges") > 10 * dropped);
  CHECK(r.err.find("; " + std::to_string(int(dropped)) + " sharp edges dropped (curves of 1 or 2 edges)") !=
        std::string::npos);
}

TEST_CASE("generate's --repair-rounds reaches the repair: its further rounds remove edges the first three leave",
          "[cli][generate][repair]") {
  // Without restarts in the second round, the first three rounds leave
  // non-meshable edges on blobby (2 with GCC -O3); the further rounds go on.
  std::map<int, nlohmann::json> report;
  for (int rounds : {0, 8}) {
    const auto out = work / ("blobby_rounds_" + std::to_string(rounds));
    const Run r = run("generate builtin:blobby --repair-restarts 0 --repair-rounds " + std::to_string(rounds) +
                      " -o " + out.string());
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    report[rounds] = read_report(out);
  }
  CHECK(number(report[0], "/repair/non_meshable_before") == number(report[8], "/repair/non_meshable_before"));
  CHECK(number(report[0], "/repair/rounds") == 3);
  CHECK(number(report[0], "/repair/regions_from_restarts") == 0);
  CHECK(number(report[0], "/repair/regions_released") == 0); // --repair-rounds 0: no released round either
  if (number(report[0], "/repair/non_meshable_after") == 0) { // other last bits: nothing left to go on with
    CHECK(number(report[8], "/repair/rounds") == 3);
    CHECK(number(report[8], "/repair/non_meshable_after") == 0);
    return;
  }
  CHECK(number(report[8], "/repair/rounds") > 3);
  CHECK(number(report[8], "/repair/rounds") <= 19); // 3, then 8 further and 8 released at most
  CHECK(number(report[8], "/repair/non_meshable_after") < number(report[0], "/repair/non_meshable_after"));
  CHECK(number(report[8], "/repair/regions_from_restarts") > 0); // only the further and released rounds restart
}

TEST_CASE("generate does not depend on the unit of length and refuses sizes beyond 1e60", "[cli][generate]") {
  const std::string gmsh = data_dir + "/gmsh_box_with_hole.mesh";
  std::map<int, nlohmann::json> report;
  for (int e : {0, 150, -150}) {
    const std::string mesh = scaled_mesh(gmsh, e, "scaled_" + std::to_string(e) + ".mesh");
    const auto out = work / ("scaled_out_" + std::to_string(e));
    const Run r = run("generate " + mesh + " -o " + out.string());
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    report[e] = read_report(out);
  }
  for (int e : {150, -150}) {
    INFO("scale 2^" << e);
    CHECK(number(report[e], "/hex_size") == Approx(std::ldexp(number(report[0], "/hex_size"), e)).epsilon(1e-9));
    for (const char* key : {"/smoothness_energy", "/projected_energy", "/expected_hexes", "/singular_edges",
                            "/face_angle_deg/mean", "/face_angle_deg/median", "/face_angle_deg/max",
                            "/boundary_alignment_error_deg/mean", "/g_orthonormality_max_error",
                            "/max_transport_angle_deg", "/refinement_iterations"})
      CHECK(number(report[e], key) == number(report[0], key));
  }
  CHECK(number(report[0], "/singular_edges") > 0);
  for (int e : {333, -333, -1040}) { // 1e100, 1e-100 and subnormal coordinates
    INFO("scale 2^" << e);
    const std::string mesh = scaled_mesh(data_dir + "/cube_kuhn_2.mesh", e, "extreme_" + std::to_string(e) + ".mesh");
    const Run r = run("generate " + mesh + " -o " + (work / "extreme_out").string());
    CHECK(r.exit_code == 1);
    CHECK(r.err.find(mesh + ": the mesh: spans ") != std::string::npos);
    CHECK(r.err.find("between 1e-60 and 1e+60") != std::string::npos);
    CHECK(!std::filesystem::exists(work / "extreme_out" / "report.json"));
  }
}

TEST_CASE("generate checks the output directory before any computation", "[cli][generate]") {
  const std::string file = file_with("not_a_directory", "my notes\n");
  for (const std::string& input : {cube, std::string("builtin:ball")}) {
    INFO(input);
    const Run r = run("generate " + input + " -o " + file);
    CHECK(r.exit_code == 1);
    CHECK(r.err == "metric-frames generate: error: " + file + ": the output directory exists and is not a directory\n");
  }
  CHECK(slurp(file) == "my notes\n");
  const Run below = run("generate " + cube + " -o " + file + "/out");
  CHECK(below.exit_code == 1);
  CHECK(below.err == "metric-frames generate: error: " + file + "/out: cannot create the output directory: " + file +
                         " is not a directory\n");
  // /proc takes no new directories, not even from root.
  const Run proc = run("generate " + cube + " -o /proc/cgal_ext_no_such_dir/out");
  CHECK(proc.exit_code == 1);
  CHECK(proc.err.find("metric-frames generate: error: /proc/cgal_ext_no_such_dir/out: cannot create the output "
                      "directory: cannot create files in /proc: ") == 0);
  CHECK(lines(proc.err) == 1);
  if (::geteuid() != 0) { // root writes into read-only directories
    const auto read_only = work / "read_only";
    std::filesystem::create_directories(read_only);
    std::filesystem::permissions(read_only, std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
    const Run r = run("generate " + cube + " -o " + (read_only / "out").string());
    std::filesystem::permissions(read_only, std::filesystem::perms::owner_all);
    CHECK(r.exit_code == 1);
    CHECK(r.err.find("cannot create files in " + read_only.string()) != std::string::npos);
    CHECK(r.err.find("[stage]") == std::string::npos);
  }
  // The check leaves nothing behind when a later step fails.
  const auto fresh = work / "fresh_parent";
  std::filesystem::create_directories(fresh);
  CHECK(run("generate " + (work / "nothing.mesh").string() + " -o " + (fresh / "out").string()).exit_code == 1);
  CHECK(std::filesystem::is_empty(fresh));
}

TEST_CASE("generate with a metric of 1e308 I is a clear error naming the vertex and the value", "[cli][generate][extreme]") {
  std::string sol = "MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n27\n1 3\n";
  for (int i = 0; i < 27; ++i) sol += "1e308 0 1e308 0 0 1e308\n";
  const std::string path = file_with("big.sol", sol + "End\n");
  const std::string out = (work / "big_metric_out").string();
  // sqrt(det g) = 1e462: the metric volume, the expected number of hexahedra, overflows.
  const Run r = run("generate " + cube + " --metric " + path + " -o " + out);
  CHECK(r.exit_code == 1);
  const std::string error = r.err.substr(std::min(r.err.size(), r.err.find("metric-frames generate: error: ")));
  CHECK(lines(error) == 1);
  CHECK(error.find("error: " + path + ": vertex 1: ") != std::string::npos);
  CHECK(error.find("sqrt(det g) = 1e+462") != std::string::npos);
  CHECK(error.find("nan") == std::string::npos);
  const Run c = run("generate " + cube + " --metric-const '1e308 1e308 1e308' -o " + out);
  CHECK(c.exit_code == 1);
  CHECK(c.err.find("sqrt(det g) = 1e+462") != std::string::npos);
  CHECK(!std::filesystem::exists(work / "big_metric_out" / "frames.fra"));
  // Scaled to a hex size that brings it in range: a clean result, g / h^2 = 1e8 I.
  const Run h = run("generate " + cube + " --metric " + path + " --hex-size 1e150 -o " + out);
  INFO(h.err);
  REQUIRE(h.exit_code == 0);
  const nlohmann::json report = read_report(work / "big_metric_out");
  CHECK(report.dump().find("null") == std::string::npos);
  CHECK(number(report, "/expected_hexes") == Approx(8e12).epsilon(1e-12));
}

TEST_CASE("generate's straightening keeps interior surfaces, edges and subdomain interfaces in place",
          "[cli][generate][straightening]") {
  // The L-shape [0,2]^3 without x, y > 1; tetrahedra left of the plane x = 1 are subdomain 2.
  CGAL_ext::Pipeline_tet_mesh mesh = CGAL_ext::load_tet_mesh(l_shape);
  CGAL_ext::IO::Medit_mesh& m = mesh.mesh;
  m.triangles.clear();
  m.triangle_references.clear();
  m.edges.clear();
  m.edge_references.clear();
  m.tetrahedron_references.assign(m.tetrahedra.size(), 1);
  CHECK(CGAL_ext::pipeline_straightening_options(mesh).fixed_vertices == std::vector<char>(m.vertices.size(), 0));
  std::size_t interface = 0;
  for (std::size_t t = 0; t < m.tetrahedra.size(); ++t) {
    double x = 0;
    for (std::size_t v : m.tetrahedra[t]) x += m.vertices[v][0] / 4;
    if (x < 1) m.tetrahedron_references[t] = 2;
  }
  auto options = CGAL_ext::pipeline_straightening_options(mesh);
  REQUIRE(options.fixed_vertices.size() == m.vertices.size());
  for (std::size_t v = 0; v < m.vertices.size(); ++v) {
    // On the plane x = 1 where both sides are inside (y <= 1); not on the notch's face (y > 1).
    const bool expected = m.vertices[v][0] == 1 && m.vertices[v][1] <= 1;
    interface += expected;
    CHECK(bool(options.fixed_vertices[v]) == expected);
  }
  CHECK(interface > 0);
  // A triangle's and an edge's vertices are fixed too, unless their reference is 0 (as TetGen's interior faces).
  m.tetrahedron_references.assign(m.tetrahedra.size(), 1);
  m.triangles.push_back({m.tetrahedra[0][0], m.tetrahedra[0][1], m.tetrahedra[0][2]});
  m.triangle_references.push_back(3);
  m.edges.push_back({m.tetrahedra[5][2], m.tetrahedra[5][3]});
  m.edge_references.push_back(4);
  m.triangles.push_back({m.tetrahedra[9][0], m.tetrahedra[9][1], m.tetrahedra[9][3]});
  m.triangle_references.push_back(0);
  m.edges.push_back({m.tetrahedra[12][0], m.tetrahedra[12][1]});
  m.edge_references.push_back(0);
  options = CGAL_ext::pipeline_straightening_options(mesh);
  std::vector<char> expected(m.vertices.size(), 0);
  for (std::size_t v : m.triangles[0]) expected[v] = 1;
  for (std::size_t v : m.edges[0]) expected[v] = 1;
  CHECK(options.fixed_vertices == expected);
  CHECK(std::count(expected.begin(), expected.end(), 1) >= 3);
}

TEST_CASE("the pipeline's library functions write the files of generate, bit for bit", "[cli][generate][pipeline]") {
  // A metric per vertex, varying in space: the .sol the CLI reads is what the library is given.
  const CGAL_ext::IO::Medit_mesh m = CGAL_ext::IO::read_medit_mesh(l_shape);
  std::vector<Eigen::Matrix3d> g;
  for (const auto& p : m.vertices) {
    Eigen::Matrix3d t;
    t << 1 + p[0] * p[0], 0.3 * p[0] * p[1], 0, 0.3 * p[0] * p[1], 2 + p[1], 0.1 * p[2], 0, 0.1 * p[2], 1 + p[2] * p[2];
    g.push_back(t);
  }
  std::filesystem::create_directories(work);
  const std::string sol = (work / "pipeline_metric.sol").string();
  CGAL_ext::IO::write_medit_sol(sol, g);
  const Run cli =
      run("generate " + l_shape + " --metric " + sol + " --hex-size 0.5 --hexes --force -o " + (work / "cli").string());
  INFO(cli.err);
  REQUIRE(cli.exit_code == 0);

  const std::string dir = (work / "library").string();
  CGAL_ext::check_pipeline_output_directory(dir, {l_shape, sol}, true);
  CGAL_ext::Pipeline_report_context context;
  context.input = l_shape;
  const CGAL_ext::Pipeline_tet_mesh mesh = CGAL_ext::load_tet_mesh(l_shape);
  CGAL_ext::Pipeline_metric_input input;
  input.per_vertex = CGAL_ext::IO::read_medit_sol(sol, mesh.mesh.vertices.size());
  input.source = input.name = sol;
  input.hex_size = 0.5;
  const CGAL_ext::Pipeline_metric metric = CGAL_ext::make_pipeline_metric(mesh, input);
  context.thickness = CGAL_ext::measure_pipeline_thickness(metric);
  const CGAL_ext::Pipeline_frame_field frames =
      CGAL_ext::generate_pipeline_frame_field(metric, CGAL_ext::Frame_field_options(), CGAL_ext::Singularity_repair_options(), {},
                                              CGAL_ext::pipeline_straightening_options(mesh));
  const CGAL_ext::Pipeline_integer_grid_map map = CGAL_ext::compute_pipeline_integer_grid_map(mesh, frames);
  context.integer_grid_map = map.map.report;
  CGAL_ext::write_pipeline_outputs(dir, mesh, frames, &map);
  CGAL_ext::write_pipeline_report(dir, CGAL_ext::pipeline_report_json(mesh, metric, frames, context));

  CHECK(metric.hex_size == 0.5);
  CHECK(frames.frames->size() == m.tetrahedra.size());
  for (const std::string& name : CGAL_ext::pipeline_output_names()) {
    INFO(name);
    std::string a = slurp(work / "cli" / name), b = slurp(work / "library" / name);
    REQUIRE(!a.empty());
    if (name == "report.json") { // but for the timings: the map's, and the last key
      for (std::string* text : {&a, &b}) {
        std::istringstream lines(text->substr(0, text->find("\"stage_seconds\"")));
        text->clear();
        for (std::string line; std::getline(lines, line);)
          if (line.find("\"seconds_") == std::string::npos)
            *text += line + "\n";
      }
    }
    CHECK(a == b);
  }
  // The library refuses what the CLI refuses: a tensor count that does not match the mesh.
  input.per_vertex->pop_back();
  CHECK_THROWS_WITH(CGAL_ext::make_pipeline_metric(mesh, input),
                    Catch::Contains(sol) && Catch::Contains("mesh vertices"));
}

TEST_CASE("frames.vtu marks the tetrahedra whose hard constraints the repair released", "[cli][generate][pipeline]") {
  // Gmsh's coarse anchor: the released rounds keep regions (as in the
  // repair's own test, with fewer rounds than by default for the time).
  const std::string anchor = data_dir + "/gmsh_anchor.mesh";
  const CGAL_ext::Pipeline_tet_mesh mesh = CGAL_ext::load_tet_mesh(anchor);
  CGAL_ext::Pipeline_metric_input input;
  input.hex_size = 1;
  const CGAL_ext::Pipeline_metric metric = CGAL_ext::make_pipeline_metric(mesh, input);
  CGAL_ext::Singularity_repair_options repair;
  repair.radii = {2, 3};
  repair.restarts = {0, 0};
  repair.max_further_rounds = 2;
  repair.further_restarts = 4;
  repair.max_released_rounds = 2;
  const CGAL_ext::Pipeline_frame_field frames =
      CGAL_ext::generate_pipeline_frame_field(metric, CGAL_ext::Frame_field_options(), repair);
  REQUIRE(frames.repair);
  REQUIRE(frames.repair->tets_released > 0);
  const std::string dir = (work / "released_vtu").string();
  CGAL_ext::write_pipeline_outputs(dir, mesh, frames);
  const auto vtu = CGAL_ext::testing::read_vtu(dir + "/frames.vtu");
  const auto& ff = *frames.frames;
  const auto& released = vtu.cell_data.at("hard_constraint_released").values;
  const auto& hard = vtu.cell_data.at("hard_axes").values;
  REQUIRE(released.size() == ff.size());
  REQUIRE(hard.size() == ff.size());
  std::size_t count = 0;
  for (std::size_t t = 0; t < ff.size(); ++t) {
    INFO("tet " << t);
    CHECK(released[t] == (ff.hard_constraint_released(t) ? 1.0 : 0.0));
    CHECK(hard[t] == ff.hard_constraint_axes(t));
    CHECK((ff.has_hard_constraint(t) ? hard[t] >= 1 && hard[t] <= 2 : hard[t] == 0));
    if (released[t] != 0) CHECK(hard[t] >= 1); // only a hard constraint can be released
    count += released[t] != 0;
  }
  CHECK(count == frames.repair->tets_released);
  CHECK_THROWS_AS(ff.hard_constraint_axes(ff.size()), std::out_of_range);
}

TEST_CASE("generate --hexes: an integer-grid map of the box with a hole, seamless, its flat tetrahedra split",
          "[cli][generate][integer_grid_map]") {
  const CGAL_ext::Pipeline_tet_mesh mesh = CGAL_ext::load_tet_mesh("builtin:box_with_hole");
  const CGAL_ext::Pipeline_metric metric = CGAL_ext::make_pipeline_metric(mesh, {});
  const CGAL_ext::Pipeline_frame_field frames = CGAL_ext::generate_pipeline_frame_field(
      metric, CGAL_ext::Frame_field_options(), CGAL_ext::Singularity_repair_options(), {},
      CGAL_ext::pipeline_straightening_options(mesh));
  const CGAL_ext::Pipeline_integer_grid_map map = CGAL_ext::compute_pipeline_integer_grid_map(mesh, frames);
  const CGAL_ext::Integer_grid_map_report& r = map.map.report;
  // Its singular curves run on grid lines; three consecutive vertices of a
  // curve in one tetrahedron make it flat, which a split edge lifts.
  CHECK(r.singular_edges == frames.singular_edges.size());
  CHECK(r.singular_edges_on_grid_lines == r.singular_edges);
  CHECK(r.boundary_faces_constrained == frames.frames->boundary_faces().size());
  REQUIRE(r.flat_tets_rounded > 0);
  CHECK(r.split_edges > 0);
  CHECK(r.map_tets > r.tets);
  CHECK(r.flat_tets < r.flat_tets_rounded);
  CHECK(r.inverted_tets <= r.inverted_tets_rounded);
  CHECK(r.parameter_volume == Approx(r.due_volume).epsilon(0.1)); // hexes of about the size asked for
  CGAL_ext::testing::require_refinement(map.input, map.map);
  CHECK(CGAL_ext::testing::require_seamless(map.input, map.map) > 0);

  // The files: map.hexex is the map's mesh and parameters; frames.vtu holds
  // the map at the input's corners.
  const std::string dir = (work / "hexes_box").string();
  CGAL_ext::write_pipeline_outputs(dir, mesh, frames, &map);
  const CGAL_ext::IO::Hexex_file file = CGAL_ext::IO::read_hexex(dir + "/map.hexex");
  REQUIRE(file.tets == map.map.tets);
  for (std::size_t t = 0; t < file.tets.size(); ++t)
    for (std::size_t c = 0; c < 4; ++c) REQUIRE(file.parameters[t][c] == map.map.parameters[t][c]);
  const auto vtu = CGAL_ext::testing::read_vtu(dir + "/frames.vtu");
  const auto& u = vtu.cell_data.at("parameters");
  REQUIRE(u.components == 12);
  REQUIRE(u.values.size() == 12 * mesh.mesh.tetrahedra.size());
  for (std::size_t t = 0; t < mesh.mesh.tetrahedra.size(); ++t)
    for (std::size_t c = 0; c < 4; ++c)
      for (std::size_t l = 0; l < 4; ++l)
        if (map.input.tets[t][l] == mesh.mesh.tetrahedra[t][c])
          for (int k = 0; k < 3; ++k) REQUIRE(u.values[12 * t + 3 * c + std::size_t(k)] == map.map.input_parameters[t][l][k]);
}

TEST_CASE("generate --force without --hexes removes a former run's map.hexex", "[cli][generate][integer_grid_map]") {
  const std::string out = (work / "stale_map").string();
  const Run a = run("generate " + l_shape + " --hexes --force -o " + out);
  INFO(a.err);
  REQUIRE(a.exit_code == 0);
  REQUIRE(std::filesystem::exists(out + "/map.hexex"));
  CHECK(read_report(out).contains("integer_grid_map"));
  const Run b = run("generate " + l_shape + " --force -o " + out);
  INFO(b.err);
  REQUIRE(b.exit_code == 0);
  CHECK(!std::filesystem::exists(out + "/map.hexex")); // not a map of these frames
  CHECK(!read_report(out).contains("integer_grid_map"));
  // Without --force, a map.hexex there is an existing output like the others.
  const Run c = run("generate " + l_shape + " --hexes --force -o " + out);
  REQUIRE(c.exit_code == 0);
  for (const std::string& name : CGAL_ext::pipeline_output_names())
    if (name != "map.hexex") std::filesystem::remove(out + "/" + name);
  const Run d = run("generate " + l_shape + " -o " + out);
  CHECK(d.exit_code == 1);
  CHECK(d.err.find("map.hexex") != std::string::npos);
}
