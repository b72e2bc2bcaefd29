// The metric-frames command line: help, info output, exit codes, and one
// clear error line (never a crash) for every kind of bad input.
#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <algorithm>
#include <sstream>
#include <string>

namespace {

const std::string data_dir = CGAL_EXT_TEST_DATA_DIR;
// CTest runs the test cases of this file as parallel processes: each process
// gets its own scratch directory so that their outputs never mix.
const std::filesystem::path work =
    std::filesystem::temp_directory_path() / ("cgal_ext_test_cli_" + std::to_string(::getpid()));
struct Remove_work_at_exit {
  ~Remove_work_at_exit() {
    std::error_code ec;
    std::filesystem::remove_all(work, ec);
  }
} remove_work_at_exit;

struct Run {
  int exit_code; // -1 if killed by a signal
  std::string out, err;
};

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

Run run(const std::string& args) {
  std::filesystem::create_directories(work);
  const std::string cmd = std::string(CGAL_EXT_CLI) + " " + args + " >" + (work / "out").string() + " 2>" +
                          (work / "err").string() + " </dev/null";
  const int status = std::system(cmd.c_str());
  Run r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(work / "out");
  r.err = slurp(work / "err");
  return r;
}

std::string file_with(const std::string& name, const std::string& content) {
  std::filesystem::create_directories(work);
  const auto p = work / name;
  std::ofstream(p, std::ios::binary) << content;
  return p.string();
}

std::size_t lines(const std::string& s) { return static_cast<std::size_t>(std::count(s.begin(), s.end(), '\n')); }

} // namespace

TEST_CASE("help documents every subcommand", "[cli]") {
  const Run r = run("--help");
  CHECK(r.exit_code == 0);
  CHECK(r.out.find("info") != std::string::npos);
  const Run i = run("info --help");
  CHECK(i.exit_code == 0);
  CHECK(i.out.find("Usage: metric-frames info MESH") != std::string::npos);
  CHECK(run("").exit_code == 2);
  CHECK(run("frobnicate").exit_code == 2);
  const Run missing = run("info");
  CHECK(missing.exit_code == 2);
  CHECK(missing.err.find("missing argument MESH") != std::string::npos);
  CHECK(run("info a.mesh b.mesh").exit_code == 2);
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

TEST_CASE("bad input: one error line naming the file and the line, exit code 1, no crash", "[cli][bad-input]") {
  struct Case {
    const char* name;
    const char* content;
    const char* expected; // what the message must contain after the file name
  };
  const Case cases[] = {
      {"empty.mesh", "", ": the file is empty"},
      {"garbage.mesh", "\x01\x02garbage here\n", ":1: unknown keyword"},
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
