// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The legacy VTK .vtk reader: one mesh written by VTK 9.1 in file versions
// 5.1 and 4.2, ASCII and binary, and by Gmsh 4.8.4 (version 2.0), against
// the Medit file it came from (test/data/vtk/make_files.py); bad files.
#include <CGAL_ext/IO/Vtk_legacy_mesh.h>
#include <CGAL_ext/IO/read_tet_mesh_file.h>

#include "input_error_checks.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <iterator>

using namespace CGAL_ext;

namespace {
const std::string data = std::string(CGAL_EXT_TEST_DATA_DIR) + "/";
} // namespace

TEST_CASE("Legacy VTK: VTK 9's 5.1 and 4.2 layouts, ASCII and binary, and Gmsh's, give the Medit mesh",
          "[vtk]") {
  const IO::Medit_mesh medit = IO::read_medit_mesh(data + "gmsh/box.mesh");
  for (const char* name : {"box_51.vtk", "box_51_binary.vtk", "box_42.vtk", "box_42_binary.vtk"}) {
    INFO(name);
    const IO::Medit_mesh m = IO::read_tet_mesh_file(data + "vtk/" + name);
    // VTK wrote the Medit file's points and cells in their order: in binary
    // the same doubles, in ASCII with 10 significant digits.
    const bool binary = std::string(name).find("binary") != std::string::npos;
    REQUIRE(m.vertices.size() == medit.vertices.size());
    if (binary) CHECK(m.vertices == medit.vertices);
    for (std::size_t v = 0; v < m.vertices.size(); ++v)
      for (int k = 0; k < 3; ++k) CHECK(std::abs(m.vertices[v][k] - medit.vertices[v][k]) <= 1e-9);
    CHECK(m.tetrahedra == medit.tetrahedra);
    CHECK(m.triangles == medit.triangles);
    CHECK(m.tetrahedron_references == std::vector<int>(m.tetrahedra.size(), 0));
    const bool lines = std::string(name) == "box_42.vtk"; // ASCII, classic layout
    CHECK(m.tetrahedron_lines.size() == (lines ? m.tetrahedra.size() : 0));
  }
  // Gmsh's export of the .msh the Medit file came from: 16 digits against 14.
  const IO::Medit_mesh g = IO::read_tet_mesh_file(data + "vtk/box_gmsh.vtk");
  REQUIRE(g.vertices.size() == medit.vertices.size());
  for (std::size_t v = 0; v < g.vertices.size(); ++v)
    for (int k = 0; k < 3; ++k) CHECK(std::abs(g.vertices[v][k] - medit.vertices[v][k]) <= 1e-13);
  CHECK(g.tetrahedra == medit.tetrahedra);
}

TEST_CASE("Legacy VTK: field data before the points, METADATA after arrays, float points", "[vtk]") {
  const IO::Medit_mesh reference = IO::read_vtk_legacy_mesh(data + "vtk/box_51_binary.vtk");
  const std::string path = "test_extra.vtk";
  auto read_edited = [&](std::string text, const std::string& at, const std::string& insert) {
    const auto where = text.find(at);
    REQUIRE(where != std::string::npos);
    text.insert(where, insert);
    std::ofstream(path, std::ios::binary) << text;
    return IO::read_vtk_legacy_mesh(path);
  };
  // What VTK 9 writes: a time value as field data, information keys after an array.
  const std::string metadata = "METADATA\nINFORMATION 1\nNAME L2_NORM_RANGE LOCATION vtkDataArray\nDATA 2 0 1.7\n\n";
  const std::string ascii = testing::read_file_bytes(data + "vtk/box_51.vtk");
  for (const auto& [at, insert] : {std::pair<std::string, std::string>{"POINTS", "FIELD FieldData 2\nTIME 1 1 double\n0.5\n"
                                                                                "CYCLE 1 1 int\n3\n"},
                                   {"CELLS", metadata}, {"CONNECTIVITY", metadata}, {"CELL_TYPES", metadata}}) {
    INFO(at);
    const IO::Medit_mesh m = read_edited(ascii, at, insert);
    CHECK(m.tetrahedra == reference.tetrahedra);
  }
  // In binary: the field's values are big-endian bytes.
  const std::string binary = testing::read_file_bytes(data + "vtk/box_51_binary.vtk");
  const std::string time = std::string("FIELD FieldData 1\nTIME 1 1 double\n") + std::string("\x3f\xe0\0\0\0\0\0\0", 8) + "\n";
  CHECK(read_edited(binary, "POINTS", time).vertices == reference.vertices);
  // Points in float, in ASCII: rounded to single precision as in binary.
  std::string single = ascii;
  single.replace(single.find("POINTS 380 double"), 17, "POINTS 380 float");
  std::ofstream(path, std::ios::binary) << single;
  const IO::Medit_mesh f = IO::read_vtk_legacy_mesh(path);
  for (std::size_t v = 0; v < f.vertices.size(); ++v)
    for (int k = 0; k < 3; ++k) CHECK(f.vertices[v][k] == double(float(f.vertices[v][k])));
}

TEST_CASE("Legacy VTK: bad files are named with their line or byte and cell", "[vtk][bad-input]") {
  const std::string v51 = testing::read_file_bytes(data + "vtk/box_51.vtk");
  const std::string v42 = testing::read_file_bytes(data + "vtk/box_42.vtk");
  const std::string path = "test_bad.vtk";
  const testing::Edited_file_errors expect_error{path, [&] { IO::read_vtk_legacy_mesh(path); }};
  expect_error(v51, "# vtk DataFile", "# vtk Data", 1, "", "not a legacy VTK file");
  expect_error(v51, "ASCII", "TEXT", 3, "", "expected ASCII or BINARY");
  expect_error(v51, "UNSTRUCTURED_GRID", "POLYDATA", 4, "", "only UNSTRUCTURED_GRID");
  expect_error(v51, "POINTS 380 double", "POINTS 380 int", 5, "", "float or double");
  expect_error(v51, "POINTS 380 double", "POINTS 380000 double", 5, "", "more than the rest of the file");
  expect_error(v51, "OFFSETS vtktypeint64", "OFFSETS vtktypeint16", 134, "", "vtktypeint64 or vtktypeint32");
  // The 4.2 layout: a cell type misspelt, the last tetrahedron made a hexahedron, a point id out of range.
  const std::size_t types = v42.find("CELL_TYPES");
  const std::size_t last_ten = v42.rfind("\n10", v42.size()) + 1;
  REQUIRE(last_ten > types);
  expect_error(v42, "CELL_TYPES", "CELL_TYPE", 1588, "", "expected CELL_TYPES");
  std::string hex = v42;
  hex.replace(last_ten, 2, "12");
  std::ofstream(path, std::ios::binary) << hex;
  testing::expect_input_error([&] { IO::read_vtk_legacy_mesh(path); }, path, 3041, "cell 1452", "only tetrahedra"); // the line of its type
  // The first tetrahedron (cell 278, after the triangles) given point 380166.
  expect_error(v42, "\n4 ", "\n4 380", 412, "cell 278", "out of range");
  const std::string bin = testing::read_file_bytes(data + "vtk/box_51_binary.vtk");
  std::ofstream(path, std::ios::binary) << bin.substr(0, bin.size() / 2);
  testing::expect_input_error([&] { IO::read_vtk_legacy_mesh(path); }, path, 0, "", "(at byte");
}
