// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#include <CGAL_ext/IO/Vtk_legacy_mesh.h>

#include "text_binary_cursor.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <set>
#include <vector>

namespace CGAL_ext {
namespace IO {

namespace {

// VTK cell types (vtkCellType.h) that are volumes, other than VTK_TETRA.
const std::set<std::int64_t> volume_cell_types = {11, 12, 13, 14, 15, 16, 24, 25, 26, 27, 29, 31, 32, 33, 37,
                                                  41, 42, 64, 65, 66, 67, 71, 72, 73, 74, 78, 79, 80, 81};
// Cell types of dimension 0 to 2 (and the empty cell) that are not read.
const std::set<std::int64_t> dropped_cell_types = {0,  1,  2,  4,  6,  7,  8,  9,  21, 22, 23, 28, 30,
                                                   34, 35, 36, 60, 61, 62, 63, 68, 69, 70, 75, 76, 77};

// Bytes per value of a VTK data type name in binary files (0: not skippable).
std::size_t type_size(std::string_view type) {
  if (type == "bit") return 0;
  if (type == "unsigned_char" || type == "char") return 1;
  if (type == "unsigned_short" || type == "short") return 2;
  if (type == "unsigned_int" || type == "int" || type == "float" || type == "vtktypeint32" || type == "vtktypeuint32")
    return 4;
  if (type == "unsigned_long" || type == "long" || type == "double" || type == "vtktypeint64" ||
      type == "vtktypeuint64" || type == "vtkIdType")
    return 8;
  return 0;
}

struct Reader {
  internal::Text_binary_cursor cursor;
  bool binary = false;
  bool classic = true; // the CELLS layout of versions before 5
  Medit_mesh mesh;
  std::vector<std::int64_t> offsets, connectivity; // cell c: connectivity[offsets[c] .. offsets[c + 1])
  std::vector<std::size_t> cell_lines, type_lines; // ASCII: the line of each cell's ids and of its type

  explicit Reader(const std::string& path) : cursor(path) { cursor.set_big_endian(true); }

  std::size_t count(const char* what, std::size_t bytes) {
    const std::int64_t n = cursor.integer(what);
    if (n < 0 || std::uint64_t(n) > cursor.remaining() / bytes)
      cursor.fail("", std::string("the count of ") + what + " " + std::to_string(n) +
                          " is more than the rest of the file can hold: wrong count or truncated file");
    return std::size_t(n);
  }

  std::int64_t id(bool wide, const char* what) {
    if (!binary) return cursor.integer(what);
    return wide ? static_cast<std::int64_t>(cursor.raw<8>(what))
                : static_cast<std::int32_t>(static_cast<std::uint32_t>(cursor.raw<4>(what)));
  }

  void skip_field_data();
  void read_header();
  void read_points();
  void read_cells();
  void read_connectivity_arrays(std::size_t offsets_count, std::size_t connectivity_count);
  std::vector<std::int64_t> read_cell_types();
  void assemble(const std::vector<std::int64_t>& types);
};

void Reader::read_header() {
  for (const char* word : {"#", "vtk", "DataFile", "Version"}) {
    const std::string_view t = cursor.token("the header '# vtk DataFile Version'");
    if (!internal::Text_binary_cursor::equal_ignoring_case(t, word))
      cursor.fail("", "not a legacy VTK file: it does not start with '# vtk DataFile Version'");
  }
  const std::string_view version = cursor.token("the version");
  classic = !(version.size() >= 1 && version[0] >= '5' && version[0] <= '9');
  cursor.skip_line_end(); // the end of the header line
  cursor.skip_line_end(); // the title line
  const std::string_view format = cursor.token("ASCII or BINARY");
  if (internal::Text_binary_cursor::equal_ignoring_case(format, "BINARY"))
    binary = true;
  else if (!internal::Text_binary_cursor::equal_ignoring_case(format, "ASCII"))
    cursor.fail("", "expected ASCII or BINARY, found " + Input_error::quote(format));
  cursor.expect("DATASET");
  const std::string_view dataset = cursor.token("the dataset type");
  if (!internal::Text_binary_cursor::equal_ignoring_case(dataset, "UNSTRUCTURED_GRID"))
    cursor.fail("", "dataset " + Input_error::quote(dataset) + " is not read: only UNSTRUCTURED_GRID holds tetrahedra");
}

// A FIELD block (VTK writes the dataset's field data, e.g. a time value,
// before the points): its arrays are read over.
void Reader::skip_field_data() {
  cursor.token("the field's name");
  const std::size_t arrays = count("field arrays", 8);
  for (std::size_t a = 0; a < arrays; ++a) {
    std::string_view name = cursor.token("a field array's name");
    if (name == "METADATA") {
      cursor.skip_past_empty_line();
      name = cursor.token("a field array's name");
    }
    const std::size_t components = count("a field array's components", 1);
    const std::size_t tuples = count("a field array's tuples", 1);
    const std::string_view type = cursor.token("a field array's data type");
    const std::size_t bytes = type_size(type);
    if (!bytes) cursor.fail("", "field array of type " + Input_error::quote(type) + " is not read");
    if (components && tuples > cursor.remaining() / components)
      cursor.fail("", "a field array larger than the rest of the file");
    const std::size_t values = components * tuples;
    if (binary) {
      cursor.skip_line_end();
      if (values > cursor.remaining() / bytes) cursor.fail("", "a field array larger than the rest of the file");
      cursor.skip_bytes(values * bytes, "a field array's values");
    } else {
      for (std::size_t i = 0; i < values; ++i) cursor.token("a field value");
    }
  }
}

void Reader::read_points() {
  const std::size_t n = count("points", binary ? 12 : 6);
  const std::string_view type = cursor.token("the points' data type");
  const bool is_double = type == "double";
  if (!is_double && type != "float")
    cursor.fail("", "points of type " + Input_error::quote(type) + " are not read: float or double");
  if (binary) {
    cursor.skip_line_end();
    cursor.start_binary();
  }
  mesh.vertices.resize(n);
  for (std::size_t v = 0; v < n; ++v) {
    try {
      for (double& c : mesh.vertices[v])
        c = binary ? (is_double ? cursor.real("a coordinate") : cursor.real32("a coordinate"))
                   : (is_double ? cursor.number("a coordinate") : double(float(cursor.number("a coordinate"))));
    } catch (const Input_error& e) {
      throw Input_error(e.file(), e.line(), "point " + std::to_string(v), e.problem());
    }
    if (!binary) mesh.vertex_lines.push_back(cursor.line());
  }
  mesh.vertex_references.assign(n, 0);
}

void Reader::read_connectivity_arrays(std::size_t offsets_count, std::size_t connectivity_count) {
  for (auto* array : {&offsets, &connectivity}) {
    const bool is_offsets = array == &offsets;
    std::string_view keyword = cursor.token(is_offsets ? "OFFSETS" : "CONNECTIVITY");
    if (keyword == "METADATA") { // information keys of the offsets, not read
      cursor.skip_past_empty_line();
      keyword = cursor.token("CONNECTIVITY");
    }
    if (keyword != (is_offsets ? "OFFSETS" : "CONNECTIVITY"))
      cursor.fail("", std::string("expected ") + (is_offsets ? "OFFSETS" : "CONNECTIVITY") + ", found " +
                          Input_error::quote(keyword));
    const std::string_view type = cursor.token("the array's data type");
    if (type != "vtktypeint64" && type != "vtktypeint32")
      cursor.fail("", "cell arrays of type " + Input_error::quote(type) + " are not read: vtktypeint64 or vtktypeint32");
    if (binary) cursor.skip_line_end();
    array->resize(is_offsets ? offsets_count : connectivity_count);
    for (std::int64_t& x : *array) x = id(type == "vtktypeint64", is_offsets ? "an offset" : "a point id");
  }
  if (offsets.empty() || offsets.front() != 0 || offsets.back() != std::int64_t(connectivity.size()))
    cursor.fail("", "the offsets do not start at 0 and end at the connectivity's size");
  for (std::size_t c = 0; c + 1 < offsets.size(); ++c)
    if (offsets[c + 1] < offsets[c]) cursor.fail("cell " + std::to_string(c), "the offsets decrease");
}

void Reader::read_cells() {
  if (!classic) {
    const std::size_t n_offsets = count("cell offsets", binary ? 4 : 2);
    const std::size_t n_connectivity = count("cell point ids", binary ? 4 : 2);
    if (n_offsets + n_connectivity > cursor.remaining() / (binary ? 4 : 2))
      cursor.fail("", "the cell arrays' counts are more than the rest of the file can hold");
    read_connectivity_arrays(n_offsets, n_connectivity);
    return;
  }
  const std::size_t n = count("cells", binary ? 4 : 2);
  const std::size_t size = count("cell list entries", binary ? 4 : 2);
  if (binary) cursor.skip_line_end();
  offsets.assign(1, 0);
  for (std::size_t c = 0; c < n; ++c) {
    const std::string element = "cell " + std::to_string(c);
    try {
      const std::int64_t k = id(false, "a cell's point count");
      if (k < 0 || std::uint64_t(k) > size - std::min<std::size_t>(size, connectivity.size() + c + 1))
        cursor.fail(element, "point count " + std::to_string(k) + " goes beyond the cell list's size");
      if (!binary) cell_lines.push_back(cursor.line());
      for (std::int64_t j = 0; j < k; ++j) connectivity.push_back(id(false, "a point id"));
    } catch (const Input_error& e) {
      if (!e.element().empty()) throw;
      throw Input_error(e.file(), e.line(), element, e.problem());
    }
    offsets.push_back(std::int64_t(connectivity.size()));
  }
  if (connectivity.size() + n != size)
    cursor.fail("", "the cell list has " + std::to_string(connectivity.size() + n) + " entries, not " +
                        std::to_string(size));
}

std::vector<std::int64_t> Reader::read_cell_types() {
  const std::size_t n = count("cell types", binary ? 4 : 2);
  if (n + 1 != offsets.size())
    cursor.fail("", std::to_string(n) + " cell types for " + std::to_string(offsets.size() - 1) + " cells");
  if (binary) cursor.skip_line_end();
  std::vector<std::int64_t> types(n);
  for (std::int64_t& t : types) {
    t = id(false, "a cell type");
    if (!binary) type_lines.push_back(cursor.line());
  }
  return types;
}

void Reader::assemble(const std::vector<std::int64_t>& types) {
  for (std::size_t c = 0; c < types.size(); ++c) {
    const std::string element = "cell " + std::to_string(c);
    const std::size_t line = c < cell_lines.size() ? cell_lines[c] : 0;
    auto fail = [&](const std::string& problem) { throw Input_error(cursor.path(), line, element, problem); };
    auto type_fail = [&](const std::string& problem) {
      throw Input_error(cursor.path(), c < type_lines.size() ? type_lines[c] : 0, element, problem);
    };
    const std::int64_t type = types[c];
    if (volume_cell_types.count(type))
      type_fail("cell type " + std::to_string(type) + " is a volume other than the tetrahedron (10): only tetrahedra are "
           "read; leaving it out would change the domain");
    if (dropped_cell_types.count(type)) continue;
    const std::size_t expected = type == 10 ? 4 : type == 5 ? 3 : type == 3 ? 2 : 0;
    if (!expected) type_fail("unknown cell type " + std::to_string(type));
    const std::size_t begin = std::size_t(offsets[c]), size = std::size_t(offsets[c + 1] - offsets[c]);
    if (size != expected)
      fail("a cell of type " + std::to_string(type) + " with " + std::to_string(size) + " points, not " +
           std::to_string(expected));
    std::array<std::size_t, 4> v{};
    for (std::size_t j = 0; j < size; ++j) {
      const std::int64_t i = connectivity[begin + j];
      if (i < 0 || std::uint64_t(i) >= mesh.vertices.size())
        fail("point id " + std::to_string(i) + " is out of range (0-based, " + std::to_string(mesh.vertices.size()) +
             " points)");
      for (std::size_t k = 0; k < j; ++k)
        if (v[k] == std::size_t(i)) fail("point id " + std::to_string(i) + " appears twice");
      v[j] = std::size_t(i);
    }
    if (type == 10) {
      mesh.tetrahedra.push_back(v);
      mesh.tetrahedron_references.push_back(0);
      if (line) mesh.tetrahedron_lines.push_back(line);
    } else if (type == 5) {
      mesh.triangles.push_back({v[0], v[1], v[2]});
      mesh.triangle_references.push_back(0);
    } else {
      mesh.edges.push_back({v[0], v[1]});
      mesh.edge_references.push_back(0);
    }
  }
  if (mesh.tetrahedra.empty()) throw Input_error(cursor.path(), 0, "", "no tetrahedra (cell type 10): not a tetrahedral mesh");
  if (mesh.tetrahedron_lines.size() != mesh.tetrahedra.size()) mesh.tetrahedron_lines.clear();
}

} // namespace

Medit_mesh read_vtk_legacy_mesh(const std::string& path) {
  Reader r(path);
  r.read_header();
  bool points = false, cells = false;
  std::string_view keyword;
  while (r.cursor.next(keyword)) {
    if (keyword == "FIELD" && !points) {
      r.skip_field_data();
    } else if (keyword == "POINTS" && !points) {
      r.read_points();
      points = true;
    } else if (keyword == "METADATA") {
      r.cursor.skip_past_empty_line(); // information keys of the last array, not read
    } else if (keyword == "CELLS" && points && !cells) {
      r.read_cells();
      cells = true;
    } else if (keyword == "CELL_TYPES" && cells) {
      r.assemble(r.read_cell_types());
      return std::move(r.mesh); // cell and point data follow: not read
    } else {
      r.cursor.fail("", "expected " + std::string(!points ? "POINTS" : !cells ? "CELLS" : "CELL_TYPES") + ", found " +
                            Input_error::quote(keyword));
    }
  }
  r.cursor.fail("", std::string("unexpected end of file: no ") + (!points ? "POINTS" : !cells ? "CELLS" : "CELL_TYPES"));
}

} // namespace IO
} // namespace CGAL_ext
