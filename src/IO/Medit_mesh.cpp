// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#include <CGAL_ext/IO/Medit_mesh.h>
#include <CGAL_ext/IO/Medit_tokenizer.h>

#include "write_file_atomically.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <limits>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string_view>

namespace CGAL_ext {
namespace IO {

namespace {

// Sections we read over: name and number of tokens per record.
struct Skipped_section {
  const char* name;
  std::size_t tokens;
};
constexpr Skipped_section skipped_sections[] = {
    {"Corners", 1},          {"RequiredVertices", 1},   {"Ridges", 1},
    {"RequiredEdges", 1},    {"RequiredTriangles", 1},  {"RequiredQuadrilaterals", 1},
    {"RequiredTetrahedra", 1}, {"RequiredHexahedra", 1}, {"Quadrilaterals", 5},
    {"Normals", 3},          {"NormalAtVertices", 2},   {"Tangents", 3},
    {"TangentAtVertices", 2}, {"NormalAtTriangleVertices", 3}, {"NormalAtQuadrilateralVertices", 3},
    {"TangentAtEdgeVertices", 3}, {"Crack", 2}, {"Identifier", 0}, {"Geometry", 0}};

// A reference as an int, or an error naming the element: references wider
// than int would otherwise come back changed in the written mesh.
int reference_of(Medit_tokenizer& tk, const std::string& element, const char* what) {
  std::int64_t r = 0;
  try {
    r = tk.read_int(what);
  } catch (const Input_error& e) {
    throw Input_error(tk.path(), e.line(), element, e.problem());
  }
  if (r < std::numeric_limits<int>::min() || r > std::numeric_limits<int>::max())
    tk.fail(element, std::string(what) + " " + std::to_string(r) + " is out of the range of a 32-bit int");
  return static_cast<int>(r);
}

// Reads `count` records of N vertex indices and a reference, checking each
// index's sign (the upper bound is checked once all sections are read).
template <std::size_t N>
void read_cells(Medit_tokenizer& tk, const char* section, const char* element, std::size_t count,
                std::vector<std::array<std::size_t, N>>& cells, std::vector<int>& refs,
                std::vector<std::size_t>& lines) {
  cells.resize(count);
  refs.resize(count);
  lines.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    const std::string name = std::string(element) + " " + std::to_string(i + 1);
    for (std::size_t j = 0; j < N; ++j) {
      std::int64_t v = 0;
      try {
        v = tk.read_int("a vertex index");
      } catch (const Input_error& e) {
        throw Input_error(tk.path(), e.line(), name, e.problem());
      }
      if (j == 0) lines[i] = tk.line();
      if (v <= 0)
        tk.fail(name, "vertex index " + std::to_string(v) + " is not positive (" + section + " indices are 1-based)");
      cells[i][j] = static_cast<std::size_t>(v - 1);
    }
    refs[i] = reference_of(tk, name, "the reference");
  }
}

// Reads the Vertices section after its keyword: the count, then x y z and a reference per vertex.
void read_vertices(Medit_tokenizer& tk, const std::string& path, Medit_mesh& m) {
  const std::size_t n = tk.read_count("Vertices", 4);
  m.vertices.resize(n);
  m.vertex_references.resize(n);
  m.vertex_lines.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) {
      try {
        m.vertices[i][k] = tk.read_double("a coordinate");
      } catch (const Input_error& e) {
        throw Input_error(path, e.line(), "vertex " + std::to_string(i + 1), e.problem());
      }
      if (k == 0) m.vertex_lines[i] = tk.line();
    }
    m.vertex_references[i] = reference_of(tk, "vertex " + std::to_string(i + 1), "the reference");
  }
}

// Reads over a section we do not use (skipped_sections); any other keyword is an error.
void skip_section(Medit_tokenizer& tk, std::string_view kw) {
  const Skipped_section* s = nullptr;
  for (const auto& candidate : skipped_sections)
    if (Medit_tokenizer::keyword_equals(kw, candidate.name)) s = &candidate;
  for (const char* other : {"Hexahedra", "Prisms", "Pyramids"})
    if (Medit_tokenizer::keyword_equals(kw, other)) {
      const std::size_t n = tk.read_count(other, 1);
      if (n == 0) return;
      tk.fail("", std::to_string(n) + " " + other + " (" + other +
                      " section): only tetrahedral meshes are read, and leaving them out would change the domain; "
                      "split them into tetrahedra first");
    }
  if (!s) {
    if (std::any_of(kw.begin(), kw.end(), [](char c) { return c != '\t' && std::iscntrl(static_cast<unsigned char>(c)); }))
      tk.fail("", "binary data where a keyword was expected: only ASCII Medit files are read (a binary .meshb or "
                  ".solb file? convert it to ASCII first)");
    if (kw.substr(0, 3) == "\xEF\xBB\xBF")
      tk.fail("", "the file starts with a UTF-8 byte-order mark (bytes EF BB BF), which Medit files do not have: "
                  "save it without one");
    const std::size_t p = kw.find_last_of("PQpq");
    if (p != std::string_view::npos && p > 0 && p + 1 < kw.size() &&
        std::all_of(kw.begin() + p + 1, kw.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); })) {
      if (tk.read_count(std::string(kw), 1) == 0) return; // an empty section changes nothing
      tk.fail("", "section " + Input_error::quote(kw) + ": high-order elements are not read (mesh at order 1)");
    }
    const bool numeric = !kw.empty() && (std::isdigit(static_cast<unsigned char>(kw[0])) || kw[0] == '-' || kw[0] == '.');
    tk.fail("", numeric ? "unexpected number " + Input_error::quote(kw) +
                              " where a section keyword was expected (a count does not match its section?)"
                        : "unknown keyword " + Input_error::quote(kw));
  }
  if (s->tokens == 0) { // a string value (Identifier, Geometry): a word, or a quoted string with spaces
    std::string_view t = tk.expect("a value");
    if (t.size() > 0 && t.front() == '"')
      while (t.size() < 2 || t.back() != '"') t = tk.expect("the end of a quoted string");
    return;
  }
  const std::size_t n = tk.read_count(s->name, s->tokens);
  const std::string what = std::string("a record of ") + s->name;
  for (std::size_t i = 0; i < n * s->tokens; ++i) tk.expect(what.c_str());
}

// Every vertex index of `cells` is below `nv`, or an error naming the cell (1-based) and its line.
template <std::size_t N>
void check_index_range(const std::string& path, const std::vector<std::array<std::size_t, N>>& cells,
                       const char* element, const std::vector<std::size_t>& lines, std::size_t nv) {
  for (std::size_t i = 0; i < cells.size(); ++i)
    for (std::size_t v : cells[i])
      if (v >= nv)
        throw Input_error(path, lines[i], std::string(element) + " " + std::to_string(i + 1),
                          "vertex index " + std::to_string(v + 1) + " is out of range 1.." + std::to_string(nv) +
                              " (" + std::to_string(nv) + (nv == 1 ? " vertex" : " vertices") + " in the file)");
}

} // namespace

Medit_mesh read_medit_mesh(const std::string& path) {
  Medit_tokenizer tk(path);
  Medit_mesh m;
  bool have_vertices = false, have_tets = false, have_triangles = false, have_edges = false;
  std::vector<std::size_t> triangle_lines, edge_lines;
  std::size_t tet_section_line = 0;
  std::string_view kw;
  while (tk.next(kw)) {
    if (Medit_tokenizer::keyword_equals(kw, "MeshVersionFormatted")) {
      const auto v = tk.read_int("the MeshVersionFormatted value");
      if (v < 1 || v > 4) tk.fail("", "unsupported MeshVersionFormatted " + std::to_string(v));
      m.version = static_cast<int>(v);
    } else if (Medit_tokenizer::keyword_equals(kw, "Dimension")) {
      const auto d = tk.read_int("the Dimension value");
      if (d != 3)
        tk.fail("", "Dimension " + std::to_string(d) + ": only 3D tetrahedral meshes are supported");
    } else if (Medit_tokenizer::keyword_equals(kw, "Vertices")) {
      if (have_vertices) tk.fail("", "a second Vertices section");
      read_vertices(tk, path, m);
      have_vertices = true;
    } else if (Medit_tokenizer::keyword_equals(kw, "Tetrahedra")) {
      if (have_tets) tk.fail("", "a second Tetrahedra section");
      tet_section_line = tk.line();
      const std::size_t n = tk.read_count("Tetrahedra", 5);
      read_cells<4>(tk, "Tetrahedra", "tetrahedron", n, m.tetrahedra, m.tetrahedron_references, m.tetrahedron_lines);
      have_tets = true;
    } else if (Medit_tokenizer::keyword_equals(kw, "Triangles")) {
      if (have_triangles) tk.fail("", "a second Triangles section");
      const std::size_t n = tk.read_count("Triangles", 4);
      read_cells<3>(tk, "Triangles", "triangle", n, m.triangles, m.triangle_references, triangle_lines);
      have_triangles = true;
    } else if (Medit_tokenizer::keyword_equals(kw, "Edges")) {
      if (have_edges) tk.fail("", "a second Edges section");
      const std::size_t n = tk.read_count("Edges", 3);
      read_cells<2>(tk, "Edges", "edge", n, m.edges, m.edge_references, edge_lines);
      have_edges = true;
    } else if (Medit_tokenizer::keyword_equals(kw, "End")) {
      break;
    } else {
      skip_section(tk, kw);
    }
  }
  if (!have_vertices) throw Input_error(path, 0, "", "no Vertices section");
  if (!have_tets)
    throw Input_error(path, 0, "", "no Tetrahedra section: this is not a volume mesh (a surface or 2D mesh?)");
  if (m.tetrahedra.empty()) throw Input_error(path, tet_section_line, "", "the Tetrahedra section is empty");

  // Indices were checked to be positive; check the upper bound now that all sections are read.
  check_index_range(path, m.tetrahedra, "tetrahedron", m.tetrahedron_lines, m.vertices.size());
  check_index_range(path, m.triangles, "triangle", triangle_lines, m.vertices.size());
  check_index_range(path, m.edges, "edge", edge_lines, m.vertices.size());
  return m;
}

void write_medit_mesh(const std::string& path, const Medit_mesh& m) {
  internal::write_file_atomically(path, [&](std::FILE* f) {
    std::fprintf(f, "MeshVersionFormatted 2\n\nDimension 3\n\nVertices\n%zu\n", m.vertices.size());
    for (std::size_t i = 0; i < m.vertices.size(); ++i)
      std::fprintf(f, "%.17g %.17g %.17g %d\n", m.vertices[i][0], m.vertices[i][1], m.vertices[i][2],
                   i < m.vertex_references.size() ? m.vertex_references[i] : 0);
    std::fprintf(f, "\nTetrahedra\n%zu\n", m.tetrahedra.size());
    for (std::size_t i = 0; i < m.tetrahedra.size(); ++i) {
      const auto& t = m.tetrahedra[i];
      std::fprintf(f, "%zu %zu %zu %zu %d\n", t[0] + 1, t[1] + 1, t[2] + 1, t[3] + 1,
                   i < m.tetrahedron_references.size() ? m.tetrahedron_references[i] : 0);
    }
    if (!m.triangles.empty()) {
      std::fprintf(f, "\nTriangles\n%zu\n", m.triangles.size());
      for (std::size_t i = 0; i < m.triangles.size(); ++i) {
        const auto& t = m.triangles[i];
        std::fprintf(f, "%zu %zu %zu %d\n", t[0] + 1, t[1] + 1, t[2] + 1,
                     i < m.triangle_references.size() ? m.triangle_references[i] : 0);
      }
    }
    if (!m.edges.empty()) {
      std::fprintf(f, "\nEdges\n%zu\n", m.edges.size());
      for (std::size_t i = 0; i < m.edges.size(); ++i)
        std::fprintf(f, "%zu %zu %d\n", m.edges[i][0] + 1, m.edges[i][1] + 1,
                     i < m.edge_references.size() ? m.edge_references[i] : 0);
    }
    std::fprintf(f, "\nEnd\n");
  });
}

} // namespace IO
} // namespace CGAL_ext
