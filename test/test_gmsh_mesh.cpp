// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The Gmsh .msh reader: one mesh written by Gmsh 4.8.4 in MSH 4.1 and 2.2,
// ASCII and binary, with node tags with gaps, against Gmsh's own Medit
// export of it (test/data/gmsh/make_files.sh); physical groups as
// references; every kind of bad file.
#include <CGAL_ext/IO/Gmsh_mesh.h>
#include <CGAL_ext/IO/read_tet_mesh.h>

#include "input_error_checks.h"

#include <catch2/catch.hpp>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <set>

using namespace CGAL_ext;

namespace {

const std::string gmsh_dir = std::string(CGAL_EXT_TEST_DATA_DIR) + "/gmsh/";

// A mesh's tetrahedra as sets of corner coordinates (rounded to 1e-9:
// Gmsh's Medit export has 14 digits), whatever the vertex numbering.
using Corner = std::array<long long, 3>;
std::multiset<std::vector<Corner>> tet_shapes(const IO::Medit_mesh& m) {
  std::multiset<std::vector<Corner>> shapes;
  for (const auto& t : m.tetrahedra) {
    std::vector<Corner> c;
    for (std::size_t v : t)
      c.push_back({std::llround(m.vertices[v][0] * 1e9), std::llround(m.vertices[v][1] * 1e9),
                   std::llround(m.vertices[v][2] * 1e9)});
    std::sort(c.begin(), c.end());
    shapes.insert(c);
  }
  return shapes;
}


void write_text(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

} // namespace

TEST_CASE("Gmsh .msh: MSH 4.1 and 2.2, ASCII and binary, give Gmsh's Medit mesh", "[gmsh]") {
  const IO::Medit_mesh medit = IO::read_medit_mesh(gmsh_dir + "box.mesh");
  const auto expected = tet_shapes(medit);
  REQUIRE(medit.tetrahedra.size() == 1175);
  const IO::Medit_mesh first = IO::read_gmsh_mesh(gmsh_dir + "box_41.msh");
  for (const char* name : {"box_41.msh", "box_41_binary.msh", "box_22.msh", "box_22_binary.msh", "box_41_gaps.msh"}) {
    INFO(name);
    const IO::Medit_mesh m = IO::read_gmsh_mesh(gmsh_dir + name);
    CHECK(m.vertices.size() == medit.vertices.size());
    CHECK(m.tetrahedra.size() == 1175); // MSH 2.2 lists each twice (two physical volumes): once here
    CHECK(tet_shapes(m) == expected);
    // The physical volumes are 7 and 9: the first is the reference.
    CHECK(std::all_of(m.tetrahedron_references.begin(), m.tetrahedron_references.end(), [](int r) { return r == 7; }));
    // Only the physical surface 3 was saved, with its tag.
    CHECK(m.triangles.size() == first.triangles.size());
    CHECK(!m.triangles.empty());
    CHECK(std::all_of(m.triangle_references.begin(), m.triangle_references.end(), [](int r) { return r == 3; }));
    const bool ascii = std::string(name).find("binary") == std::string::npos;
    CHECK(m.tetrahedron_lines.size() == (ascii ? m.tetrahedra.size() : 0));
    CHECK(m.vertex_lines.size() == (ascii ? m.vertices.size() : 0));
    if (std::string(name) != "box_41_gaps.msh") { // same node order; binary doubles exact, ASCII 16 digits
      for (std::size_t v = 0; v < m.vertices.size(); ++v)
        for (int k = 0; k < 3; ++k) REQUIRE(std::abs(m.vertices[v][k] - first.vertices[v][k]) <= 1e-15);
      CHECK(m.tetrahedra == first.tetrahedra);
    }
  }
  // The gaps file lists each block's nodes in reverse: the vertices follow the file's order.
  const IO::Medit_mesh gaps = IO::read_gmsh_mesh(gmsh_dir + "box_41_gaps.msh");
  CHECK(gaps.vertices != first.vertices);
  auto sorted = [](std::vector<std::array<double, 3>> v) {
    std::sort(v.begin(), v.end());
    return v;
  };
  CHECK(sorted(gaps.vertices) == sorted(first.vertices));
}

TEST_CASE("Gmsh .msh: read_tet_mesh builds the same triangulation as from the Medit file", "[gmsh]") {
  using Tr = Tet_mesh_triangulation_3<CGAL::Exact_predicates_inexact_constructions_kernel>;
  Tr from_msh, from_mesh;
  const Tet_mesh_build_report a = IO::read_tet_mesh(gmsh_dir + "box_41_binary.msh", from_msh);
  const Tet_mesh_build_report b = IO::read_tet_mesh(gmsh_dir + "box.mesh", from_mesh);
  CHECK(a.boundary_facets == b.boundary_facets);
  CHECK(a.reoriented_tets == b.reoriented_tets);
  CHECK(from_msh.number_of_vertices() == from_mesh.number_of_vertices());
  CHECK(IO::is_gmsh_mesh_path("dir.x/a.MSH"));
  CHECK_FALSE(IO::is_gmsh_mesh_path("dir.msh/a"));
  CHECK_FALSE(IO::is_gmsh_mesh_path("a.mesh"));
}

TEST_CASE("Gmsh .msh: bad files are named with their line or byte and element", "[gmsh][bad-input]") {
  const std::string ascii41 = testing::read_file_bytes(gmsh_dir + "box_41.msh");
  const std::string ascii22 = testing::read_file_bytes(gmsh_dir + "box_22.msh");
  const std::string path = "test_bad.msh";
  const testing::Edited_file_errors expect_error{path, [&] { IO::read_gmsh_mesh(path); }};
  expect_error(ascii41, "4.1 0 8", "4 0 8", 2, "", "MSH version '4' is not read");
  expect_error(ascii41, "4.1 0 8", "4.1 0 4", 2, "", "data size 4");
  expect_error(ascii41, "$MeshFormat", "$Format", 1, "", "expected $MeshFormat");
  expect_error(ascii41, "$Entities", "$PartitionedEntities", 4, "", "partitioned");
  // MSH 2.2: a tetrahedron made a hexahedron, a node tag that is not a node, one repeated, a NaN.
  const auto tet = ascii22.find(" 4 2 7 1 ");
  REQUIRE(tet != std::string::npos);
  const std::size_t tet_line = std::size_t(std::count(ascii22.begin(), ascii22.begin() + std::ptrdiff_t(tet), '\n')) + 1;
  const std::string tet_tag = ascii22.substr(ascii22.rfind('\n', tet) + 1, tet - ascii22.rfind('\n', tet) - 1);
  expect_error(ascii22, " 4 2 7 1 ", " 5 2 7 1 ", tet_line, "element " + tet_tag, "only linear tetrahedra");
  expect_error(ascii22, " 4 2 7 1 ", " 99 2 7 1 ", tet_line, "element " + tet_tag, "unknown element type 99");
  const std::size_t end_of_tet = ascii22.find('\n', tet);
  std::string broken = ascii22;
  const std::size_t last_space = broken.rfind(' ', end_of_tet);
  broken.replace(last_space + 1, end_of_tet - last_space - 1, "999999");
  write_text(path, broken);
  testing::expect_input_error([&] { IO::read_gmsh_mesh(path); }, path, tet_line, "element " + tet_tag,
                              "node tag 999999 is not a node");
  expect_error(ascii22, "\n2 0 0 0\n", "\n1 0 0 0\n", 7, "node 1", "given twice");
  expect_error(ascii22, "$EndElements", "", 0, "", "unexpected end of file");
  // A count beyond the file.
  const auto nodes = ascii41.find("$Nodes\n");
  const std::size_t count_end = ascii41.find(' ', nodes + 7);
  expect_error(ascii41, ascii41.substr(nodes, count_end - nodes), "$Nodes\n999999999", 41, "",
               "more than the rest of the file");
  // Binary data cut short: the block and the byte offset are named.
  const std::string binary = testing::read_file_bytes(gmsh_dir + "box_41_binary.msh");
  write_text(path, binary.substr(0, binary.size() / 2));
  try {
    IO::read_gmsh_mesh(path);
    FAIL("a truncated file was read");
  } catch (const Input_error& e) {
    INFO(e.what());
    CHECK(e.line() == 0);
    CHECK(e.element().find(" block ") != std::string::npos);
    CHECK(e.problem().find("(at byte ") != std::string::npos);
  }
  // A coordinate that is not a number names its node record.
  expect_error(ascii22, "\n2 0 0 0\n", "\n2 0 zero 0\n", 7, "node record 2", "'zero'");
  // $Entities after $Nodes would leave the references unread.
  const std::size_t entities_end = ascii41.find("$EndEntities\n") + 13;
  const std::size_t nodes_end = ascii41.find("$EndNodes\n") + 10;
  std::string moved = ascii41.substr(0, ascii41.find("$Entities")) + ascii41.substr(entities_end, nodes_end - entities_end) +
                      ascii41.substr(ascii41.find("$Entities"), entities_end - ascii41.find("$Entities")) +
                      ascii41.substr(nodes_end);
  write_text(path, moved);
  testing::expect_input_error([&] { IO::read_gmsh_mesh(path); }, path, 0, "", "$Entities after $Nodes");
  // A big-endian file: the check value 1 reads as 2^24.
  std::string big = binary;
  const auto one = big.find("\x01\x00\x00\x00", big.find("4.1 1 8"), 4);
  REQUIRE(one != std::string::npos);
  big.replace(one, 4, std::string("\x00\x00\x00\x01", 4));
  write_text(path, big);
  testing::expect_input_error([&] { IO::read_gmsh_mesh(path); }, path, 0, "", "not little-endian");
  // Surfaces only: no tetrahedra.
  write_text(path, "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n$EndNodes\n"
                   "$Elements\n1\n1 2 0 1 2 3\n$EndElements\n");
  testing::expect_input_error([&] { IO::read_gmsh_mesh(path); }, path, 0, "", "no tetrahedra");
}
