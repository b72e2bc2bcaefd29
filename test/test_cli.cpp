// The metric-frames command line: help, info output, exit codes, and one
// clear error line (never a crash) for every kind of bad input.
#include <catch2/catch.hpp>

#include "cli_test_support.h"

#include <sys/stat.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>

using namespace CGAL_ext::testing;

TEST_CASE("help documents every subcommand", "[cli]") {
  const Run r = run("--help");
  CHECK(r.exit_code == 0);
  for (const char* sub : {"generate", "info", "walk", "transport", "metric", "help"})
    CHECK(r.out.find(std::string("\n  ") + sub + " ") != std::string::npos);
  const Run i = run("info --help");
  CHECK(i.exit_code == 0);
  CHECK(i.out.find("Usage: metric-frames info [OPTIONS] MESH") == 0);
  CHECK(i.out.find("--json") != std::string::npos);
  const Run none = run("");
  CHECK(none.exit_code == 2);
  CHECK(none.err.find("Usage: metric-frames") == 0); // the help, on stderr
  CHECK(run("frobnicate").exit_code == 2);
  const Run missing = run("info");
  CHECK(missing.exit_code == 2);
  CHECK(missing.err == "metric-frames info: MESH is required (see metric-frames info --help)\n");
  const Run extra = run("info a.mesh b.mesh");
  CHECK(extra.exit_code == 2);
  CHECK(extra.err.find("b.mesh") != std::string::npos);
  const Run option = run("info --frobnicate a.mesh");
  CHECK(option.exit_code == 2);
  CHECK(option.err.find("--frobnicate") != std::string::npos);
  const Run version = run("--version");
  CHECK(version.exit_code == 0);
  CHECK(version.out.find("metric-frames ") == 0);

  // help SUBCOMMAND is SUBCOMMAND --help.
  const Run h = run("help generate");
  CHECK(h.exit_code == 0);
  CHECK(h.out == run("generate --help").out);
  CHECK(h.out.find("Usage: metric-frames generate [OPTIONS] INPUT") == 0);
  CHECK(run("help").out == r.out);
  const Run unknown = run("help frobnicate");
  CHECK(unknown.exit_code == 2);
  CHECK(unknown.err.find("metric-frames help: ") == 0);
  CHECK(unknown.err.find("frobnicate") != std::string::npos);
  CHECK(run("help info walk").exit_code == 2);
}

TEST_CASE("bad option values are usage errors naming the option", "[cli]") {
  const std::string mesh = data_dir + "/cube_kuhn_2.mesh";
  const std::string pairs = file_with("one_pair.txt", "0 0 0 1 1 1\n");
  for (const char* bad : {"0", "-1", "nan", "inf", "1e-8x", ""}) {
    const Run r = run("transport " + mesh + " --metric x.sol --pairs " + pairs + " --tol '" + bad + "'");
    INFO(bad << ": " << r.err);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("metric-frames transport: --tol: ") == 0);
  }
  const Run scheme = run("transport " + mesh + " --metric x.sol --pairs " + pairs + " --scheme euler");
  CHECK(scheme.exit_code == 2);
  CHECK(scheme.err.find("--scheme") != std::string::npos);
  for (const char* bad : {"0", "1025", "2.5", "x"}) {
    const Run r = run("transport " + mesh + " --metric x.sol --pairs " + pairs + " --threads " + bad);
    INFO(bad << ": " << r.err);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("--threads") != std::string::npos);
  }
  // Whole numbers in decimal, whatever their spelling (010 is ten, not octal eight).
  for (const char* good : {"010", "4.0", "1e1"}) {
    const Run r = run("transport " + mesh + " --metric " + (work / "none.sol").string() + " --pairs " + pairs +
                      " --threads " + good);
    INFO(good << ": " << r.err);
    CHECK(r.exit_code == 1); // past the command line: the missing .sol
    CHECK(r.err.find("none.sol") != std::string::npos);
  }
  // -o=PATH would be a path starting with '='.
  const Run equals = run("metric " + mesh + " --size 1 -o=x.sol");
  CHECK(equals.exit_code == 2);
  CHECK(equals.err.find("write -o PATH or --output=PATH") != std::string::npos);
  const Run both = run("metric " + mesh + " --expr '1,0,1,0,0,1' --size 1 -o x.sol");
  CHECK(both.exit_code == 2);
  CHECK(both.err.find("--expr") != std::string::npos);
  const Run neither = run("metric " + mesh + " -o x.sol");
  CHECK(neither.exit_code == 2);
  CHECK(neither.err.find("give exactly one of --expr and --size") != std::string::npos);
  CHECK(!std::filesystem::exists("x.sol"));
}

TEST_CASE("info prints counts, box, volume, angles and re-orientations", "[cli]") {
  const Run r = run(data_dir + "/cube_kuhn_2.mesh");
  CHECK(r.exit_code == 2); // a file is not a subcommand
  const Run i = run("info " + data_dir + "/cube_kuhn_2.mesh");
  REQUIRE(i.exit_code == 0);
  CHECK(i.out.find("vertices             27\n") != std::string::npos);
  CHECK(i.out.find("tetrahedra           48\n") != std::string::npos);
  CHECK(i.out.find("boundary facets      48\n") != std::string::npos);
  CHECK(i.out.find("components           1\n") != std::string::npos);
  CHECK(i.out.find("bounding box         [0, 2] x [0, 2] x [0, 2]\n") != std::string::npos);
  CHECK(i.out.find("volume               8\n") != std::string::npos);
  CHECK(i.out.find("dihedral angles      min 45 deg, max 90 deg\n") != std::string::npos);
  CHECK(i.out.find("re-oriented tets     0\n") != std::string::npos);
  CHECK(i.err.find("[done]") != std::string::npos); // stage timings on stderr

  const Run o = run("info " + data_dir + "/reoriented.mesh");
  REQUIRE(o.exit_code == 0);
  CHECK(o.out.find("re-oriented tets     16 (e.g. tetrahedron 1 4 7") != std::string::npos);

  const Run e = run("info " + data_dir + "/two_cubes_sharing_edge.mesh");
  REQUIRE(e.exit_code == 0);
  CHECK(e.out.find("components           2\n") != std::string::npos);
  CHECK(e.out.find("non-manifold edges   1") != std::string::npos);
}

TEST_CASE("info --json prints the same figures as one JSON object", "[cli]") {
  const Run j = run("info --json " + data_dir + "/cube_kuhn_2.mesh");
  REQUIRE(j.exit_code == 0);
  CHECK(j.out.find('\n') == j.out.size() - 1); // one line
  const nlohmann::json info = nlohmann::json::parse(j.out);
  CHECK(info == nlohmann::json::parse(R"({"mesh": ")" + data_dir + R"(/cube_kuhn_2.mesh", "vertices": 27,
      "unused_vertices": 0, "tetrahedra": 48, "boundary_facets": 48, "components": 1, "non_manifold_boundary_edges": 0,
      "bounding_box": {"min": [0, 0, 0], "max": [2, 2, 2]}, "volume": 8, "edges": 98, "mean_edge_length": )" +
                                          info["mean_edge_length"].dump() + R"(,
      "dihedral_angles_deg": {"min": 45, "max": 90}, "reoriented_tets": 0, "reoriented_examples": []})"));
  // The keys in the documented order.
  CHECK(j.out.find("{\"mesh\":") == 0);
  CHECK(j.out.find("\"reoriented_examples\":[]}") != std::string::npos);
  CHECK(j.err.find("[done]") != std::string::npos);

  const Run o = run("info " + data_dir + "/reoriented.mesh --json");
  REQUIRE(o.exit_code == 0);
  const nlohmann::json reoriented = nlohmann::json::parse(o.out);
  CHECK(reoriented["reoriented_tets"] == 16);
  CHECK(reoriented["reoriented_examples"][0] == 1);
  CHECK(reoriented["reoriented_examples"][1] == 4);
  CHECK(reoriented["reoriented_examples"][2] == 7);
  // A mesh path with a quote and a backslash stays valid JSON.
  const std::string odd = file_with("a\"b\\c.mesh", "");
  std::filesystem::copy_file(data_dir + "/cube_kuhn_2.mesh", odd, std::filesystem::copy_options::overwrite_existing);
  const Run q = run("info --json '" + odd + "'");
  REQUIRE(q.exit_code == 0);
  CHECK(nlohmann::json::parse(q.out)["mesh"] == odd);
}

TEST_CASE("info reads Gmsh .msh and legacy VTK files: the same figures as the Medit file of the same mesh", "[cli][gmsh][vtk]") {
  // Gmsh's Medit export has 14 digits, its .msh files 16 or all (binary):
  // the lengths and volume agree to 1e-12, the counts exactly.
  const Run medit = run("info --json " + data_dir + "/gmsh/box.mesh");
  REQUIRE(medit.exit_code == 0);
  const nlohmann::json expected = nlohmann::json::parse(medit.out);
  for (const char* name : {"box_41.msh", "box_41_binary.msh", "box_22.msh", "box_22_binary.msh", "box_41_gaps.msh"}) {
    INFO(name);
    const Run r = run("info --json " + data_dir + "/gmsh/" + name);
    REQUIRE(r.exit_code == 0);
    const nlohmann::json info = nlohmann::json::parse(r.out);
    for (const char* key : {"vertices", "unused_vertices", "tetrahedra", "boundary_facets", "components",
                            "non_manifold_boundary_edges", "edges", "reoriented_tets"})
      CHECK(info[key] == expected[key]);
    for (const char* key : {"volume", "mean_edge_length"})
      CHECK(info[key].get<double>() == Approx(expected[key].get<double>()).epsilon(1e-12));
  }
  // Legacy VTK files of the same mesh (VTK's ASCII has 10 digits).
  for (const char* name : {"box_51.vtk", "box_51_binary.vtk", "box_42.vtk", "box_42_binary.vtk", "box_gmsh.vtk"}) {
    INFO(name);
    const Run r = run("info --json " + data_dir + "/vtk/" + name);
    REQUIRE(r.exit_code == 0);
    const nlohmann::json info = nlohmann::json::parse(r.out);
    for (const char* key : {"vertices", "tetrahedra", "boundary_facets", "components", "edges", "reoriented_tets"})
      CHECK(info[key] == expected[key]);
    CHECK(info["volume"].get<double>() == Approx(expected["volume"].get<double>()).epsilon(1e-8));
  }
  const Run bad = run("info " + file_with("bad.msh", "$MeshFormat\n4.0 0 8\n$EndMeshFormat\n"));
  CHECK(bad.exit_code == 1);
  CHECK(bad.err.find("bad.msh:2: MSH version '4.0' is not read") != std::string::npos);
}

TEST_CASE("bad input: one error line naming the file and the line, exit code 1, no crash", "[cli][bad-input]") {
  struct Case {
    const char* name;
    const char* content;
    const char* expected; // what the message must contain after the file name
  };
  const Case cases[] = {
      {"empty.mesh", "", ": the file is empty"},
      {"garbage.mesh", "\x01\x02garbage here\n", ":1: binary data where a keyword was expected"},
      {"truncated.mesh", "Dimension 3\nVertices\n4\n0 0 0 1\n1 0", ":3: Vertices: the count 4 is more than the rest"},
      {"count.mesh", "Dimension 3\nVertices\n5\n0 0 0 1\n1 0 0 1\n0 1 0 1\n0 0 1 1\nTetrahedra\n1\n1 2 3 4 1\n",
       ":8: vertex 5: expected a coordinate, found 'Tetrahedra'"},
      {"absurd.mesh", "Dimension 3\nVertices\n999999999999\n", ":3: Vertices: the count 999999999999 is more"},
      {"range.mesh", "Dimension 3\nVertices\n4\n0 0 0 1\n1 0 0 1\n0 1 0 1\n0 0 1 1\nTetrahedra\n1\n1 2 3 7 1\n",
       ":10: tetrahedron 1: vertex index 7 is out of range 1..4"},
      {"zero.mesh", "Dimension 3\nVertices\n4\n0 0 0 1\n1 0 0 1\n0 1 0 1\n0 0 1 1\nTetrahedra\n1\n1 2 0 4 1\n",
       ":10: tetrahedron 1: vertex index 0 is not positive"},
      {"nan.mesh", "Dimension 3\nVertices\n4\n0 0 0 1\n1 0 NaN 1\n0 1 0 1\n0 0 1 1\n", ":5: vertex 2: a coordinate is not finite"},
      {"inf.mesh", "Dimension 3\nVertices\n4\n0 0 0 1\n1 0 inf 1\n0 1 0 1\n0 0 1 1\n", ":5: vertex 2: a coordinate is not finite"},
      {"flat.mesh", "Dimension 3\nVertices\n4\n0 0 0 1\n1 0 0 1\n0 1 0 1\n1 1 0 1\nTetrahedra\n1\n1 2 3 4 1\n",
       ":10: tetrahedron 1: zero volume"},
      {"2d.mesh", "MeshVersionFormatted 2\nDimension\n2\nVertices\n3\n0 0 1\n1 0 1\n0 1 1\nTriangles\n1\n1 2 3 1\n",
       ":3: Dimension 2: only 3D tetrahedral meshes are supported"},
  };
  for (const Case& c : cases) {
    INFO(c.name);
    const std::string path = file_with(c.name, c.content);
    const Run r = run("info " + path);
    CHECK(r.exit_code == 1);
    CHECK(r.out.empty());
    CHECK(lines(r.err) == 1);
    CHECK(r.err.find("metric-frames info: error: " + path + c.expected) == 0);
  }
  const Run missing = run("info " + (work / "does_not_exist.mesh").string());
  CHECK(missing.exit_code == 1);
  CHECK(missing.err.find("does_not_exist.mesh: cannot open the file for reading") != std::string::npos);
}

TEST_CASE("walk prints one JSON line per segment, in order, with exact simplices", "[cli][walk]") {
  const std::string mesh = data_dir + "/cube_kuhn_2.mesh";
  // Line 2: along the x axis through the cube centre, starting and ending outside.
  // Line 4: the main diagonal, from vertex to vertex through the centre.
  const std::string segments = file_with("segments.txt", "# q -> p\n-1 1 1 3 1 1\n\n0 0 0 2 2 2\n");
  const Run r = run("walk " + mesh + " --segments " + segments);
  REQUIRE(r.exit_code == 0);
  CHECK(json_lines(r.out) == json_lines(
        R"({"segment": 0, "pieces": [{"dim": -1, "vertices": [], "t": [0, 0.25]}, )"
        R"({"dim": 0, "vertices": [4], "t": [0.25, 0.25]}, {"dim": 1, "vertices": [4, 13], "t": [0.25, 0.5]}, )"
        R"({"dim": 0, "vertices": [13], "t": [0.5, 0.5]}, {"dim": 1, "vertices": [13, 22], "t": [0.5, 0.75]}, )"
        R"({"dim": 0, "vertices": [22], "t": [0.75, 0.75]}, {"dim": -1, "vertices": [], "t": [0.75, 1]}]})" "\n"
        R"({"segment": 1, "pieces": [{"dim": 0, "vertices": [0], "t": [0, 0]}, )"
        R"({"dim": 1, "vertices": [0, 13], "t": [0, 0.5]}, {"dim": 0, "vertices": [13], "t": [0.5, 0.5]}, )"
        R"({"dim": 1, "vertices": [13, 26], "t": [0.5, 1]}, {"dim": 0, "vertices": [26], "t": [1, 1]}]})" "\n"));
  CHECK(r.out.find("{\"segment\":0,\"pieces\":[{\"dim\":-1,") == 0); // keys in the documented order
  CHECK(r.err.find("[summary] 2 segments, 12 pieces") != std::string::npos);

  const Run f = run("walk " + mesh + " --segments " + segments + " --fast");
  REQUIRE(f.exit_code == 0);
  CHECK(json_lines(f.out) == json_lines(
        R"({"segment": 0, "pieces": [{"dim": -1, "vertices": [], "t": [0, 0.25]}, )"
        R"({"dim": 1, "vertices": [4, 13], "t": [0.25, 0.5]}, {"dim": 1, "vertices": [13, 22], "t": [0.5, 0.75]}, )"
        R"({"dim": -1, "vertices": [], "t": [0.75, 1]}]})" "\n"
        R"({"segment": 1, "pieces": [{"dim": 1, "vertices": [0, 13], "t": [0, 0.5]}, )"
        R"({"dim": 1, "vertices": [13, 26], "t": [0.5, 1]}]})" "\n"));

  // A segment inside one tet: one cell piece covering [0, 1].
  const std::string inside = file_with("inside.txt", "0.1 0.05 0.02 0.2 0.1 0.05\n");
  const Run c = run("walk " + mesh + " --segments " + inside);
  REQUIRE(c.exit_code == 0);
  const std::vector<nlohmann::json> one = json_lines(c.out);
  REQUIRE(one.size() == 1);
  REQUIRE(one[0]["pieces"].size() == 1);
  CHECK(one[0]["pieces"][0]["dim"] == 3);
  CHECK(one[0]["pieces"][0]["vertices"].size() == 4);
  CHECK(one[0]["pieces"][0]["t"] == nlohmann::json::parse("[0, 1]"));
}

TEST_CASE("walk: a malformed segment line is an error naming the file and the line", "[cli][walk][bad-input]") {
  const std::string mesh = data_dir + "/cube_kuhn_2.mesh";
  struct Case {
    const char* content;
    const char* expected;
  };
  const Case cases[] = {
      {"0 0 0 1 1 1\n\n1 2 3 4 5\n", ":3: expected 6 numbers (qx qy qz px py pz), found 5"},
      {"0 0 0 1 1 1 # a comment\n1 2 3 4 5 # 6\n", ":2: expected 6 numbers (qx qy qz px py pz), found 5"},
      {"0 0 0 1 1 1 1\n", ":1: more than 6 numbers on the line"},
      {"0 0 0 1 1 nan\n", ":1: 'nan' is not a finite number"},
      {"0 0 0 1 one 1\n", ":1: 'one' is not a finite number"},
  };
  for (const Case& c : cases) {
    INFO(c.content);
    const std::string path = file_with("bad_segments.txt", c.content);
    const Run r = run("walk " + mesh + " --segments " + path);
    CHECK(r.exit_code == 1);
    CHECK(r.out.empty()); // the whole file is read before any output
    CHECK(r.err.find("metric-frames walk: error: " + path + c.expected) != std::string::npos);
  }
  const Run commented = run("walk " + mesh + " --segments " + file_with("commented.txt", "0.1 0.2 0.3 0.9 0.8 0.7 # q -> p\n"));
  CHECK(commented.exit_code == 0);
  CHECK(!commented.out.empty());
  CHECK(run("walk " + mesh).exit_code == 2);                                   // no --segments
  CHECK(run("walk --segments " + file_with("one.txt", "0 0 0 1 1 1\n")).exit_code == 2); // no MESH
  const Run missing = run("walk " + mesh + " --segments " + (work / "none.txt").string());
  CHECK(missing.exit_code == 1);
  CHECK(missing.err.find("none.txt: cannot open the file for reading") != std::string::npos);
}

TEST_CASE("metric writes a .sol from formulas, and rejects bad formulas and non-SPD values", "[cli][metric]") {
  const std::string mesh = data_dir + "/cube_kuhn_2.mesh"; // 27 vertices, vertex 1 at the origin
  const std::string out = (work / "metric.sol").string();
  std::filesystem::remove(out);
  const Run r = run("metric " + mesh + " --expr '1 + x, 0.5 * y, 16, 0, 0, 4' -o " + out);
  REQUIRE(r.exit_code == 0);
  CHECK(r.err.find("[summary] 27 vertices") != std::string::npos);
  const std::string sol = slurp(out);
  CHECK(sol.find("SolAtVertices\n27\n1 3\n1 0 16 0 0 4\n") != std::string::npos); // vertex 1 = (0, 0, 0)
  CHECK(sol.find("\n3 0 16 0 0 4\n") != std::string::npos);                       // x = 2, y = 0
  CHECK(sol.find("\n3 1 16 0 0 4\n") != std::string::npos);                       // x = 2, y = 2

  // The output is never replaced without --force, and never the mesh.
  const Run again = run("metric " + mesh + " --size 0.5 -o " + out);
  CHECK(again.exit_code == 1);
  CHECK(again.err.find("the file exists; give --force") != std::string::npos);
  CHECK(slurp(out) == sol);
  const Run sized = run("metric " + mesh + " --size 0.5 -o " + out + " --force");
  REQUIRE(sized.exit_code == 0);
  CHECK(slurp(out).find("\n1 3\n4 0 4 0 0 4\n") != std::string::npos); // g = I / 0.5^2
  const std::string mesh_copy = file_with("copy.mesh", slurp(mesh));
  CHECK(run("metric " + mesh_copy + " --size 1 -o " + mesh_copy + " --force").exit_code == 1);
  CHECK(slurp(mesh_copy) == slurp(mesh));
  const auto dir = work / "a_directory.sol";
  std::filesystem::create_directories(dir);
  const Run on_dir = run("metric " + mesh + " --size 1 -o " + dir.string() + " --force");
  CHECK(on_dir.exit_code == 1);
  CHECK(on_dir.err.find("a_directory.sol: is a directory or another non-file") != std::string::npos);
  CHECK(on_dir.err.find("[stage]") == std::string::npos); // refused before reading the mesh

  struct Case {
    std::string args;
    int exit_code;
    const char* expected;
  };
  const Case cases[] = {
      {"--expr '1, 0, 1, 0, 0, sin(' -o x.sol", 2, "--expr '1, 0, 1, 0, 0, sin(': Unexpected end of expression"},
      {"--expr '1, 0, 1' -o x.sol", 2, "expected 6 comma-separated expressions"},
      {"--expr '1, 0, 1, 0, 0, w' -o x.sol", 2, "Unexpected token \"w\""},
      {"--size 1 --expr '1, 0, 1, 0, 0, 1' -o x.sol", 2, "--expr excludes --size"},
      {"--size 1", 2, "--output is required"},
      {"--expr '1, 2, 1, 0, 0, 1' -o x.sol", 1, "--expr at vertex 1 (0, 0, 0): the metric tensor is not positive definite"},
      {"--expr '1, 0, 1, 0, 0, 1/(z-1)^2' -o x.sol", 1, "--expr at vertex 2 (0, 0, 1): the metric tensor has a non-finite entry"},
      {"--size '1 - z' -o x.sol", 1, "--size at vertex 2 (0, 0, 1): the size h = 0 is not a positive finite number"},
  };
  for (const Case& c : cases) {
    INFO(c.args);
    const Run e = run("metric " + mesh + " " + c.args);
    CHECK(e.exit_code == c.exit_code);
    CHECK(e.err.find(c.expected) != std::string::npos);
    CHECK(!std::filesystem::exists("x.sol"));
  }
}

TEST_CASE("a 10 MB token is echoed as its first 40 characters and its length", "[cli][bad-input]") {
  const std::string cube = data_dir + "/cube_kuhn_2.mesh";
  const std::string digits(10000000, '1');
  const std::string quoted = "'" + std::string(40, '1') + "...' (10000000 characters)";
  const std::string mesh =
      file_with("long_number.mesh", "Dimension 3\nVertices\n4\n0 0 0 1\n1 0 " + digits + " 1\n0 1 0 1\n0 0 1 1\n");
  const Run r = run("info " + mesh);
  CHECK(r.exit_code == 1);
  REQUIRE(r.err.size() < 1000); // else Catch would print 10 MB
  CHECK(r.err ==
        "metric-frames info: error: " + mesh + ":5: vertex 2: a coordinate " + quoted + " overflows a double\n");
  const std::string segments = file_with("long_number.txt", "0 0 0 1 1 " + digits + "\n");
  const Run w = run("walk " + cube + " --segments " + segments);
  CHECK(w.exit_code == 1);
  REQUIRE(w.err.size() < 1000);
  CHECK(w.err.find("metric-frames walk: error: " + segments + ":1: " + quoted + " is not a finite number\n") !=
        std::string::npos);
}

TEST_CASE("a NUL byte in an input file is shown escaped and the whole message reaches stderr", "[cli][bad-input]") {
  const std::string cube = data_dir + "/cube_kuhn_2.mesh";
  const std::string mesh = file_with("nul.mesh", std::string("Dimension 3\nVertices\n4\n0 0 0 1\n1 0 0") + '\0' +
                                                     "zz 1\n0 1 0 1\n0 0 1 1\n");
  const Run r = run("info " + mesh);
  CHECK(r.exit_code == 1);
  CHECK(r.err == "metric-frames info: error: " + mesh + ":5: vertex 2: expected a coordinate, found '0\\x00zz'\n");
  const std::string segments = file_with("nul.txt", std::string("0 0 0 1 1 1") + '\0' + "\n");
  const Run w = run("walk " + cube + " --segments " + segments);
  CHECK(w.exit_code == 1);
  CHECK(w.err.find("metric-frames walk: error: " + segments + ":1: '1\\x00' is not a finite number\n") !=
        std::string::npos);
}

TEST_CASE("a directory given as an input file is reported as a directory", "[cli][bad-input]") {
  const std::string cube = data_dir + "/cube_kuhn_2.mesh";
  const std::string dir = (work / "a_directory.mesh").string();
  std::filesystem::create_directories(dir);
  const std::string message = "error: " + dir + ": is a directory, not a file\n";
  const Run i = run("info " + dir);
  CHECK(i.exit_code == 1);
  CHECK(i.err == "metric-frames info: " + message);
  const Run w = run("walk " + cube + " --segments " + dir);
  CHECK(w.exit_code == 1);
  CHECK(w.err.find(message) != std::string::npos);
  const Run t = run("transport " + cube + " --metric " + dir + " --pairs " + file_with("pairs.txt", "0 0 0 1 1 1\n"));
  CHECK(t.exit_code == 1);
  CHECK(t.err.find(message) != std::string::npos);
  const std::string obj = (work / "a_directory.obj").string();
  std::filesystem::create_directories(obj);
  const Run g = run("generate " + obj + " -o " + (work / "directory_out").string());
  CHECK(g.exit_code == 1);
  CHECK(g.err.find("error: " + obj + ": is a directory, not a file\n") != std::string::npos);
}

TEST_CASE("an endless device or a FIFO as input is refused at once with exit status 1", "[cli][bad-input]") {
  const std::string cube = data_dir + "/cube_kuhn_2.mesh";
  const auto start = std::chrono::steady_clock::now();
  const std::string message = "error: /dev/zero: is not a regular file (a device, a FIFO or a socket)\n";
  const Run i = run_bounded("info /dev/zero");
  CHECK(i.exit_code == 1);
  CHECK(i.err == "metric-frames info: " + message);
  const std::string pairs = file_with("pairs.txt", "0.5 0.5 0.5 1.5 1.5 1.5\n");
  const Run t = run_bounded("transport " + cube + " --metric /dev/zero --pairs " + pairs);
  CHECK(t.exit_code == 1);
  CHECK(t.err.find(message) != std::string::npos);
  const Run g = run_bounded("generate " + cube + " --metric /dev/zero -o " + (work / "zero_out").string());
  CHECK(g.exit_code == 1);
  CHECK(g.err.find(message) != std::string::npos);
  const Run w = run_bounded("walk " + cube + " --segments /dev/zero");
  CHECK(w.exit_code == 1);
  CHECK(w.err.find(message) != std::string::npos);
  // A FIFO without a writer: opening it would wait forever.
  const std::string fifo = (work / "fifo.mesh").string();
  std::filesystem::remove(fifo);
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  const Run f = run_bounded("info " + fifo, 10);
  CHECK(f.exit_code == 1);
  CHECK(f.err.find(fifo + ": is not a regular file") != std::string::npos);
  CHECK(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < 20);
}

TEST_CASE("metric accepts 1e308 I and names the value of a tensor whose inverse overflows", "[cli][metric]") {
  const std::string cube = data_dir + "/cube_kuhn_2.mesh";
  const std::string out = (work / "big.sol").string();
  std::filesystem::remove(out);
  const Run r = run("metric " + cube + " --expr '1e308, 0, 1e308, 0, 0, 1e308' -o " + out);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(r.err.find("sizes 1/sqrt(eigenvalue) in [1e-154, 1e-154]; max anisotropy 1;") != std::string::npos);
  const std::string sol = slurp(out);
  CHECK(sol.find("SolAtVertices\n27\n1 3\n1e+308 0 1e+308 0 0 1e+308\n") != std::string::npos);
  CHECK(sol.find("nan") == std::string::npos);
  CHECK(sol.find("inf") == std::string::npos);
  const Run t = run("metric " + cube + " --expr '1e-320, 0, 1e-320, 0, 0, 1e-320' --force -o " + out);
  CHECK(t.exit_code == 1);
  CHECK(t.err.find("vertex 1") != std::string::npos);
  CHECK(t.err.find("smallest eigenvalue 9.99989e-321") != std::string::npos);
}

TEST_CASE("metric writes a .sol whose file name has 250 characters", "[cli][metric]") {
  const std::string out = (work / (std::string(246, 'g') + ".sol")).string();
  const Run r = run("metric " + data_dir + "/cube_kuhn_2.mesh --expr '1, 0, 1, 0, 0, 1' -o " + out);
  INFO(r.err);
  CHECK(r.exit_code == 0);
  CHECK(slurp(out).find("SolAtVertices\n27\n1 3\n") != std::string::npos);
}
