// Reading Medit .mesh files: files written by Gmsh and TetGen, free-format
// syntax, and every kind of bad input with a message naming file and line.
#include <CGAL_ext/IO/Medit_mesh.h>

#include <catch2/catch.hpp>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <iterator>
#include <fstream>
#include <string>

using CGAL_ext::Input_error;
using CGAL_ext::IO::Medit_mesh;
using CGAL_ext::IO::read_medit_mesh;
using CGAL_ext::IO::write_medit_mesh;

namespace {

const std::string data_dir = CGAL_EXT_TEST_DATA_DIR;

std::string temp_file(const std::string& name, const std::string& content) {
  const auto dir = std::filesystem::temp_directory_path() / "cgal_ext_test_medit_mesh";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / name).string();
  std::ofstream(path, std::ios::binary) << content;
  return path;
}

// The message of the Input_error thrown by reading `content`.
Input_error read_error(const std::string& name, const std::string& content) {
  const std::string path = temp_file(name, content);
  try {
    read_medit_mesh(path);
  } catch (const Input_error& e) {
    CHECK(e.file() == path);
    CHECK(std::string(e.what()).find(path) == 0); // the message starts with the file
    return e;
  }
  FAIL("no error for " << name);
  throw;
}

const char* one_tet = "MeshVersionFormatted 2\nDimension 3\nVertices\n4\n"
                      "0 0 0 1\n1 0 0 1\n0 1 0 1\n0 0 1 1\nTetrahedra\n1\n1 2 3 4 7\nEnd\n";

} // namespace

TEST_CASE("a minimal file reads with 0-based indices and references", "[medit]") {
  const Medit_mesh m = read_medit_mesh(temp_file("one.mesh", one_tet));
  REQUIRE(m.vertices.size() == 4);
  REQUIRE(m.tetrahedra.size() == 1);
  CHECK(m.tetrahedra[0] == std::array<std::size_t, 4>{0, 1, 2, 3});
  CHECK(m.tetrahedron_references[0] == 7);
  CHECK(m.vertices[1] == std::array<double, 3>{1, 0, 0});
  CHECK(m.tetrahedron_lines[0] == 11);
}

TEST_CASE("free format: comments, case, indentation, values on the next line, skipped sections", "[medit]") {
  const std::string text = "# written by hand\n  meshversionformatted\n 1\n\n DIMENSION\n   3 # three\n"
                           "Corners 2\n 1\n 2\nRequiredVertices\n1\n3\nGeometry \"my part.mesh\"\nIdentifier\nplain\n"
                           "vertices\n4\n  0 0 0 1\n1 0 0 1 # comment after a record\n0 1 0 1\n0 0 1 1\n"
                           "Ridges\n1\n1\nNormals\n1\n0 0 1\nNormalAtVertices\n1\n1 1\n"
                           "Triangles\n2\n1 2 3 5\n1 2 4 5\nEdges 1 1 2 9\nTETRAHEDRA\n1\n1 2 3 4 0\n";
  const Medit_mesh m = read_medit_mesh(temp_file("free.mesh", text));
  CHECK(m.version == 1);
  CHECK(m.vertices.size() == 4);
  CHECK(m.tetrahedra.size() == 1);
  CHECK(m.triangles.size() == 2);
  REQUIRE(m.edges.size() == 1);
  CHECK(m.edge_references[0] == 9);
}

TEST_CASE("a file written by Gmsh reads", "[medit][gmsh]") {
  // gmsh -3 box.geo -format mesh: Dimension's value on the next line,
  // right-aligned columns, Edges and Triangles sections.
  const Medit_mesh m = read_medit_mesh(data_dir + "/gmsh_box_with_hole.mesh");
  CHECK(m.vertices.size() == 380);
  CHECK(m.tetrahedra.size() == 1175);
  CHECK(m.triangles.size() == 682);
  CHECK(m.edges.size() == 94);
}

TEST_CASE("a file written by TetGen -g reads", "[medit][tetgen]") {
  // tetgen -pq1.5a0.01gfe: comments, Corners, Edges, and interior Triangles.
  const Medit_mesh m = read_medit_mesh(data_dir + "/tetgen_cube.mesh");
  CHECK(m.version == 1);
  CHECK(m.vertices.size() == 201);
  CHECK(m.tetrahedra.size() == 518);
  CHECK(m.triangles.size() == 1218); // all faces, interior ones included
}

TEST_CASE("writing and reading back gives the same mesh", "[medit]") {
  Medit_mesh m = read_medit_mesh(data_dir + "/gmsh_box_with_hole.mesh");
  m.vertices[0][0] = 0.1 + 0.2; // not representable in a short decimal
  const std::string out = temp_file("roundtrip.mesh", "");
  write_medit_mesh(out, m);
  const Medit_mesh r = read_medit_mesh(out);
  CHECK(r.vertices == m.vertices);
  CHECK(r.vertex_references == m.vertex_references);
  CHECK(r.tetrahedra == m.tetrahedra);
  CHECK(r.tetrahedron_references == m.tetrahedron_references);
  CHECK(r.triangles == m.triangles);
  CHECK(r.edges == m.edges);
  // No temporary file of this process is left next to it.
  const std::string temporary = ".mf-tmp-" + std::to_string(::getpid()) + "-";
  for (const auto& e : std::filesystem::directory_iterator(std::filesystem::path(out).parent_path()))
    CHECK(e.path().filename().string().rfind(temporary, 0) == std::string::npos);
  // A write that cannot happen names the path and leaves the old file as it was.
  const std::string before = [&] {
    std::ifstream in(out);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }();
  CHECK_THROWS_WITH(write_medit_mesh("/nonexistent/dir/x.mesh", m), Catch::Contains("/nonexistent/dir/x.mesh"));
  write_medit_mesh(out, m);
  std::ifstream in(out);
  CHECK(std::string(std::istreambuf_iterator<char>(in), {}) == before);
}

TEST_CASE("bad files give one clear error naming file and line", "[medit][bad-input]") {
  SECTION("missing file") {
    try {
      read_medit_mesh("/nonexistent/dir/x.mesh");
      FAIL("no error");
    } catch (const Input_error& e) {
      CHECK(std::string(e.what()) == "/nonexistent/dir/x.mesh: cannot open the file for reading: No such file or directory");
    }
  }
  SECTION("empty file") { CHECK(read_error("empty.mesh", "  \n\n").problem() == "the file is empty"); }
  SECTION("garbage") {
    const Input_error e = read_error("garbage.mesh", "\x7f" "ELF\x02\x01 binary junk\n");
    CHECK(e.line() == 1);
    CHECK(e.problem().find("binary data where a keyword was expected") != std::string::npos);
    CHECK(read_error("word.mesh", "Dimension 3\nVerticies\n").problem() == "unknown keyword 'Verticies'");
  }
  SECTION("truncated vertex section") {
    const Input_error e = read_error("trunc.mesh", "MeshVersionFormatted 2\nDimension 3\nVertices\n4\n0 0 0 1\n1 0 0 1\n0 1");
    CHECK(e.problem().find("the rest of the file") != std::string::npos);
  }
  SECTION("truncated inside a record") {
    const Input_error e = read_error("trunc2.mesh", "Dimension 3\nVertices\n2\n0 0 0 1\n1 0 0 1\nTetrahedra\n1\n1 2 3\n");
    CHECK(e.element() == "tetrahedron 1");
    CHECK(e.problem() == "unexpected end of file: expected a vertex index (truncated file?)");
  }
  SECTION("counts that do not match the records") {
    const Input_error e = read_error("count.mesh", "Dimension 3\nVertices\n5\n0 0 0 1\n1 0 0 1\n0 1 0 1\n0 0 1 1\n"
                                                   "Tetrahedra\n1\n1 2 3 4 1\nEnd\n");
    CHECK(e.line() == 8);
    CHECK(e.element() == "vertex 5");
    CHECK(e.problem().find("'Tetrahedra'") != std::string::npos);
  }
  SECTION("more records than the count") {
    const Input_error e = read_error("count2.mesh", "Dimension 3\nVertices\n3\n0 0 0 1\n1 0 0 1\n0 1 0 1\n0 0 1 1\n"
                                                    "Tetrahedra\n1\n1 2 3 4 1\nEnd\n");
    CHECK(e.line() == 7);
    CHECK(e.problem().find("a count does not match") != std::string::npos);
  }
  SECTION("absurd count is not allocated") {
    const Input_error e = read_error("absurd.mesh", "Dimension 3\nVertices\n1000000000000\n0 0 0 1\n");
    CHECK(e.line() == 3);
    CHECK(e.problem().find("more than the rest of the file can hold") != std::string::npos);
  }
  SECTION("negative count") {
    CHECK(read_error("neg.mesh", "Dimension 3\nVertices\n-4\n").problem().find("negative") != std::string::npos);
  }
  SECTION("zero index") {
    const Input_error e = read_error("zero.mesh", "Dimension 3\nVertices\n4\n0 0 0 1\n1 0 0 1\n0 1 0 1\n0 0 1 1\n"
                                                  "Tetrahedra\n1\n0 2 3 4 1\n");
    CHECK(e.line() == 10);
    CHECK(e.element() == "tetrahedron 1");
    CHECK(e.problem().find("1-based") != std::string::npos);
  }
  SECTION("index out of range") {
    const Input_error e = read_error("range.mesh", "Dimension 3\nVertices\n4\n0 0 0 1\n1 0 0 1\n0 1 0 1\n0 0 1 1\n"
                                                   "Tetrahedra\n2\n1 2 3 4 1\n1 2 3 5 1\n");
    CHECK(e.line() == 11);
    CHECK(e.element() == "tetrahedron 2");
    CHECK(e.problem() == "vertex index 5 is out of range 1..4 (4 vertices in the file)");
  }
  SECTION("NaN coordinate") {
    const Input_error e = read_error("nan.mesh", "Dimension 3\nVertices\n4\n0 0 0 1\n1 nan 0 1\n0 1 0 1\n0 0 1 1\n");
    CHECK(e.line() == 5);
    CHECK(e.element() == "vertex 2");
    CHECK(e.problem().find("not finite") != std::string::npos);
  }
  SECTION("a sign after a plus sign") {
    CHECK(read_error("plusminus.mesh", "Dimension 3\nVertices\n1\n+-1 0 0 1\n").problem() ==
          "expected a coordinate, found '+-1'");
    CHECK(read_error("plusminus2.mesh", "Dimension 3\nVertices\n1\n1 0 0 +-1\n").problem() ==
          "expected the reference, found '+-1'");
  }
  SECTION("Inf coordinate and overflow") {
    CHECK(read_error("inf.mesh", "Dimension 3\nVertices\n1\n0 -inf 0 1\n").problem().find("not finite") != std::string::npos);
    CHECK(read_error("ovf.mesh", "Dimension 3\nVertices\n1\n0 1e999 0 1\n").problem().find("overflows") != std::string::npos);
  }
  SECTION("a coordinate below the smallest double reads as 0, as strtod reads it") {
    const Medit_mesh m = read_medit_mesh(temp_file("underflow.mesh", "Dimension 3\nVertices\n4\n0 1e-400 -1e-400 1\n"
                                                                     "1 0 0 1\n0 1 0 1\n0 0 1 1\nTetrahedra\n1\n1 2 3 4 1\n"));
    CHECK(m.vertices[0][1] == 0.0);
    CHECK(m.vertices[0][2] == 0.0);
    CHECK(std::signbit(m.vertices[0][2]));
    // Beyond long double too, and a subnormal that double holds.
    const Medit_mesh far = read_medit_mesh(temp_file("underflow2.mesh", "Dimension 3\nVertices\n4\n-1e-6000 4e-320 0 1\n"
                                                                        "1 0 0 1\n0 1 0 1\n0 0 1 1\nTetrahedra\n1\n1 2 3 4 1\n"));
    CHECK(far.vertices[0][0] == 0.0);
    CHECK(std::signbit(far.vertices[0][0]));
    CHECK(far.vertices[0][1] == Approx(4e-320).epsilon(1e-3));
    CHECK(read_error("ovf2.mesh", "Dimension 3\nVertices\n1\n0 -1e6000 0 1\n").problem().find("overflows") !=
          std::string::npos);
  }
  SECTION("a 2D mesh") {
    const Input_error e = read_error("2d.mesh", "MeshVersionFormatted 2\nDimension 2\nVertices\n3\n0 0 1\n1 0 1\n0 1 1\n");
    CHECK(e.line() == 2);
    CHECK(e.problem().find("Dimension 2") != std::string::npos);
  }
  SECTION("a surface mesh without tetrahedra") {
    const Input_error e = read_error("surf.mesh", "Dimension 3\nVertices\n3\n0 0 0 1\n1 0 0 1\n0 1 0 1\nTriangles\n1\n1 2 3 1\nEnd\n");
    CHECK(e.problem().find("no Tetrahedra section") != std::string::npos);
  }
  SECTION("an index out of range in Triangles and Edges names the line") {
    const std::string head = "Dimension 3\nVertices\n4\n0 0 0 1\n1 0 0 1\n0 1 0 1\n0 0 1 1\nTetrahedra\n1\n1 2 3 4 1\n";
    const Input_error t = read_error("trirange.mesh", head + "Triangles\n2\n1 2 3 1\n1 2 9 1\n");
    CHECK(t.line() == 14);
    CHECK(t.element() == "triangle 2");
    const Input_error e = read_error("edgerange.mesh", head + "Edges\n1\n 7 1 1\n");
    CHECK(e.line() == 13);
    CHECK(e.element() == "edge 1");
  }
  SECTION("a reference beyond a 32-bit int is not narrowed") {
    const Input_error t = read_error("bigref.mesh", "Dimension 3\nVertices\n4\n0 0 0 1\n1 0 0 1\n0 1 0 1\n0 0 1 1\n"
                                                    "Tetrahedra\n1\n1 2 3 4 4294967297\n");
    CHECK(t.line() == 10);
    CHECK(t.element() == "tetrahedron 1");
    CHECK(t.problem() == "the reference 4294967297 is out of the range of a 32-bit int");
    const Input_error v = read_error("bigvref.mesh", "Dimension 3\nVertices\n1\n0 0 0 -4294967295\n");
    CHECK(v.element() == "vertex 1");
    CHECK(v.problem().find("out of the range of a 32-bit int") != std::string::npos);
    CHECK(read_error("wordref.mesh", "Dimension 3\nVertices\n1\n0 0 0 x\n").element() == "vertex 1");
  }
  SECTION("hexahedra, prisms and pyramids are refused, not dropped") {
    const std::string head = "Dimension 3\nVertices\n4\n0 0 0 1\n1 0 0 1\n0 1 0 1\n0 0 1 1\nTetrahedra\n1\n1 2 3 4 1\n";
    for (const char* section : {"Hexahedra", "Prisms", "Pyramids"}) {
      INFO(section);
      const Input_error e = read_error("mixed.mesh", head + section + "\n1\n1 2 3 4 1 2 3 4 1\n");
      CHECK(e.line() == 12);
      CHECK(e.problem().find(std::string("1 ") + section + " (" + section + " section): only tetrahedral meshes") == 0);
      CHECK(read_medit_mesh(temp_file("none.mesh", head + section + "\n0\n")).tetrahedra.size() == 1);
    }
  }
  SECTION("high-order sections and a second Triangles or Edges section") {
    const std::string head = "Dimension 3\nVertices\n4\n0 0 0 1\n1 0 0 1\n0 1 0 1\n0 0 1 1\nTetrahedra\n1\n1 2 3 4 1\n";
    CHECK(read_error("p2.mesh", head + "EdgesP2\n1\n1 2 3 1\n").problem() ==
          "section 'EdgesP2': high-order elements are not read (mesh at order 1)");
    CHECK(read_error("p2lower.mesh", head + "tetrahedrap2\n1\n1 2 3 4 1 2 3 4 1 2 1\n").problem().find("high-order") !=
          std::string::npos);
    CHECK(read_medit_mesh(temp_file("p2empty.mesh", head + "EdgesP2\n0\n")).edges.empty());
    CHECK(read_error("bom.mesh", "\xEF\xBB\xBF" + head).problem().find("byte-order mark") != std::string::npos);
    CHECK(read_error("tri2.mesh", head + "Triangles\n1\n1 2 3 1\nTriangles\n1\n1 2 4 1\n").problem() ==
          "a second Triangles section");
    CHECK(read_error("edge2.mesh", head + "Edges\n0\nEdges\n0\n").problem() == "a second Edges section");
  }
  SECTION("non-integer index") {
    const Input_error e = read_error("float.mesh", "Dimension 3\nVertices\n4\n0 0 0 1\n1 0 0 1\n0 1 0 1\n0 0 1 1\n"
                                                   "Tetrahedra\n1\n1 2.5 3 4 1\n");
    CHECK(e.problem() == "expected a vertex index, found '2.5'");
  }
}

TEST_CASE("a 10 MB token is quoted by its first 40 characters and its length", "[medit][bad-input]") {
  const std::string digits(10000000, '1');
  const std::string quoted = "'" + std::string(40, '1') + "...' (10000000 characters)";
  SECTION("a coordinate that overflows") {
    const Input_error e = read_error("long_coordinate.mesh", "Dimension 3\nVertices\n4\n0 0 0 1\n1 0 " + digits +
                                                                 " 1\n0 1 0 1\n0 0 1 1\n");
    CHECK(e.line() == 5);
    CHECK(e.element() == "vertex 2");
    REQUIRE(std::string(e.what()).size() < 300); // else Catch would print 10 MB
    CHECK(e.problem() == "a coordinate " + quoted + " overflows a double");
  }
  SECTION("an index that overflows") {
    const Input_error e = read_error("long_index.mesh", "Dimension 3\nVertices\n4\n0 0 0 1\n1 0 0 1\n0 1 0 1\n0 0 1 1\n"
                                                        "Tetrahedra\n1\n1 2 3 " + digits + " 1\n");
    REQUIRE(std::string(e.what()).size() < 300);
    CHECK(e.problem() == "a vertex index " + quoted + " is out of range");
  }
  SECTION("a garbage token") {
    const Input_error e = read_error("long_garbage.mesh", "Dimension 3\n" + std::string(10000000, 'x') + "\n");
    REQUIRE(std::string(e.what()).size() < 300);
    CHECK(e.problem() == "unknown keyword '" + std::string(40, 'x') + "...' (10000000 characters)");
  }
}

TEST_CASE("a NUL byte in a token is shown escaped and does not cut the message", "[medit][bad-input]") {
  const Input_error e = read_error("nul.mesh", std::string("Dimension 3\nVertices\n4\n0 0 0 1\n1 0 0") + '\0' +
                                                      "zz 1\n0 1 0 1\n0 0 1 1\n");
  CHECK(e.line() == 5);
  CHECK(e.problem() == "expected a coordinate, found '0\\x00zz'");
  const std::string what = e.what(); // what() is a C string: cut at the first NUL
  CHECK(what == e.file() + ":5: vertex 2: expected a coordinate, found '0\\x00zz'");
}

TEST_CASE("a directory is reported as a directory and not as an empty file", "[medit][bad-input]") {
  const auto dir = std::filesystem::temp_directory_path() / "cgal_ext_test_medit_mesh" / "a_directory.mesh";
  std::filesystem::create_directories(dir);
  try {
    read_medit_mesh(dir.string());
    FAIL("no error");
  } catch (const Input_error& e) {
    CHECK(std::string(e.what()) == dir.string() + ": is a directory, not a file");
  }
}
