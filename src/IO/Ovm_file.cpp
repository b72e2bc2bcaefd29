// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#include <CGAL_ext/IO/Medit_tokenizer.h>
#include <CGAL_ext/IO/Ovm_file.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <utility>

namespace CGAL_ext {
namespace IO {

namespace {

using Loop = std::vector<std::size_t>;

std::size_t read_section(Medit_tokenizer& tk, const char* name, std::size_t tokens_per_record) {
  const std::string_view token = tk.expect(name);
  if (!Medit_tokenizer::keyword_equals(token, name))
    tk.fail("", "expected the section '" + std::string(name) + "', found " + Input_error::quote(token));
  return tk.read_count(name, tokens_per_record);
}

// Runs `read`, naming `element` in any Input_error it throws.
template <class Read>
void for_element(const std::string& path, const std::string& element, Read&& read) {
  try {
    read();
  } catch (const Input_error& e) {
    if (!e.element().empty()) throw;
    throw Input_error(path, e.line(), element, e.problem());
  }
}

std::size_t read_index(Medit_tokenizer& tk, const char* what, std::size_t count, const std::string& element) {
  const std::int64_t i = tk.read_int(what);
  if (i < 0 || std::uint64_t(i) >= count)
    tk.fail(element, std::string(what) + " " + std::to_string(i) + " is out of range (0-based, " +
                         std::to_string(count) + " in the file)");
  return std::size_t(i);
}

struct Valence_range {
  const char* what;
  std::size_t least, most;
};

// Reads a record "valence i_1 .. i_valence" of `element`: the valence in
// `valence`'s range (at most the number of things it indexes, so that no
// count allocates beyond what the file holds), each index below `count`.
void read_index_list(Medit_tokenizer& tk, const std::string& element, const Valence_range& valence, const char* what,
                     std::size_t count, std::vector<std::size_t>& indices) {
  for_element(tk.path(), element, [&] {
    const std::int64_t n = tk.read_int(valence.what);
    if (n < std::int64_t(valence.least) || std::uint64_t(n) > valence.most)
      tk.fail(element, "valence " + std::to_string(n) + " is not in [" + std::to_string(valence.least) + ", " +
                           std::to_string(valence.most) + "]");
    indices.resize(std::size_t(n));
    for (std::size_t& i : indices) i = read_index(tk, what, count, element);
  });
}

// The cell as 8 vertices in VTK order, or why it is not a hexahedron.
std::optional<std::array<std::size_t, 8>> cell_to_hex(const std::vector<Loop>& loops, std::string& why) {
  if (loops.size() != 6 || std::any_of(loops.begin(), loops.end(), [](const Loop& l) { return l.size() != 4; })) {
    why = "not 6 quadrilaterals";
    return std::nullopt;
  }
  std::vector<std::pair<std::size_t, std::size_t>> directed;
  for (const Loop& l : loops)
    for (std::size_t j = 0; j < 4; ++j) directed.emplace_back(l[j], l[(j + 1) % 4]);
  std::sort(directed.begin(), directed.end());
  const bool distinct = std::adjacent_find(directed.begin(), directed.end()) == directed.end();
  if (!distinct || std::any_of(directed.begin(), directed.end(), [&](const auto& e) {
        return !std::binary_search(directed.begin(), directed.end(), std::make_pair(e.second, e.first));
      })) {
    why = "faces not closed or not consistently oriented";
    return std::nullopt;
  }
  // 24 distinct directed edges, closed: 12 edges; 8 vertices of out-degree 3 make it cubical.
  std::vector<std::size_t> vertices;
  for (const auto& e : directed) vertices.push_back(e.first);
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  if (vertices.size() != 8) {
    why = "not 8 vertices of valence 3";
    return std::nullopt;
  }
  const Loop& bottom = loops[0];
  std::array<std::size_t, 8> hex{};
  for (std::size_t i = 0; i < 4; ++i) {
    hex[i] = bottom[i];
    std::size_t off = 0, found = 0;
    for (const auto& e : directed)
      if (e.first == bottom[i] && std::find(bottom.begin(), bottom.end(), e.second) == bottom.end()) {
        off = e.second;
        ++found;
      }
    if (found != 1) {
      why = "not 8 vertices of valence 3";
      return std::nullopt;
    }
    hex[i + 4] = off;
  }
  // The loops' vertex sets must be the hexahedron's faces.
  std::vector<std::array<std::size_t, 4>> given, expected;
  for (const Loop& l : loops) given.push_back({l[0], l[1], l[2], l[3]});
  for (const auto& f : hex_faces)
    expected.push_back({hex[std::size_t(f[0])], hex[std::size_t(f[1])], hex[std::size_t(f[2])], hex[std::size_t(f[3])]});
  for (auto* set : {&given, &expected}) {
    for (auto& q : *set) std::sort(q.begin(), q.end());
    std::sort(set->begin(), set->end());
  }
  if (given != expected) {
    why = "not a hexahedron";
    return std::nullopt;
  }
  return hex;
}

} // namespace

Ovm_hex_mesh read_ovm_hex_mesh(const std::string& path) {
  Medit_tokenizer tk(path);
  const std::string_view magic = tk.expect("the header 'OVM ASCII'");
  if (!Medit_tokenizer::keyword_equals(magic, "OVM"))
    tk.fail("", "not an OpenVolumeMesh file: it starts with " + Input_error::quote(magic) + ", not 'OVM ASCII'");
  const std::string_view mode = tk.expect("'ASCII'");
  if (!Medit_tokenizer::keyword_equals(mode, "ASCII"))
    tk.fail("", "only 'OVM ASCII' files are read, not 'OVM " + std::string(mode) + "'");

  Ovm_hex_mesh result;
  std::vector<Eigen::Vector3d>& points = result.mesh.points;
  points.resize(read_section(tk, "Vertices", 3));
  for (std::size_t v = 0; v < points.size(); ++v)
    for_element(path, "vertex " + std::to_string(v + 1), [&] {
      for (int k = 0; k < 3; ++k) points[v][k] = tk.read_double("a vertex coordinate");
    });
  std::vector<std::array<std::size_t, 2>> edges(read_section(tk, "Edges", 2));
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const std::string element = "edge " + std::to_string(e + 1);
    for_element(path, element, [&] {
      for (std::size_t& v : edges[e]) v = read_index(tk, "vertex index", points.size(), element);
    });
    if (edges[e][0] == edges[e][1]) tk.fail(element, "joins vertex " + std::to_string(edges[e][0]) + " to itself");
  }
  // Faces: their vertex loops. A face uses each edge once, so the loops
  // together hold at most 2 entries per edge: no file can make them large.
  std::vector<Loop> faces(read_section(tk, "Faces", 4));
  std::vector<std::size_t> half_edges;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const std::string element = "face " + std::to_string(f + 1);
    read_index_list(tk, element, {"a face valence", 3, edges.size()}, "half-edge index", 2 * edges.size(), half_edges);
    for (std::size_t j = 0; j < half_edges.size(); ++j) {
      const auto& e = edges[half_edges[j] / 2];
      const auto& next = edges[half_edges[(j + 1) % half_edges.size()] / 2];
      const std::size_t to = half_edges[j] % 2 ? e[0] : e[1];
      const std::size_t next_from = half_edges[(j + 1) % half_edges.size()] % 2 ? next[1] : next[0];
      if (to != next_from) tk.fail(element, "its half-edges do not form a closed loop");
      faces[f].push_back(half_edges[j] % 2 ? e[1] : e[0]);
    }
    auto used = half_edges;
    for (std::size_t& h : used) h /= 2;
    std::sort(used.begin(), used.end());
    if (std::adjacent_find(used.begin(), used.end()) != used.end()) tk.fail(element, "uses an edge twice");
  }
  const std::size_t cells = read_section(tk, "Polyhedra", 5);
  std::vector<std::size_t> half_faces;
  for (std::size_t c = 0; c < cells; ++c) {
    const std::string element = "polyhedron " + std::to_string(c + 1);
    read_index_list(tk, element, {"a polyhedron valence", 4, faces.size()}, "half-face index", 2 * faces.size(),
                    half_faces);
    // Only 6 quadrilaterals can make a hexahedron: other cells are not copied.
    if (half_faces.size() != 6 ||
        std::any_of(half_faces.begin(), half_faces.end(), [&](std::size_t h) { return faces[h / 2].size() != 4; })) {
      result.other_cells.push_back({c, "not 6 quadrilaterals"});
      continue;
    }
    std::vector<Loop> loops;
    for (std::size_t h : half_faces) {
      Loop loop = faces[h / 2];
      if (h % 2) std::reverse(loop.begin() + 1, loop.end()); // (v0 v1 .. vk) -> (v0 vk .. v1)
      loops.push_back(std::move(loop));
    }
    std::string why;
    if (const auto hex = cell_to_hex(loops, why))
      result.mesh.hexahedra.push_back(*hex);
    else
      result.other_cells.push_back({c, why});
  }
  return result;
}

} // namespace IO
} // namespace CGAL_ext
