// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#include "read_closed_surface.h"

#include <CGAL_ext/Input_error.h>

#include "../IO/input_file.h"

#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

namespace CGAL_ext {
namespace internal {

namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using Point = Closed_surface::Point;
using Surface = Closed_surface;

std::string lower_extension(const std::string& path) {
  std::string e = std::filesystem::path(path).extension().string();
  for (char& ch : e) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return e;
}

// The whitespace-separated tokens of a line, up to a `#` comment.
std::vector<std::string_view> line_tokens(std::string_view rest) {
  rest = rest.substr(0, rest.find('#'));
  std::vector<std::string_view> tokens;
  for (;;) {
    const std::size_t begin = rest.find_first_not_of(" \t\r\f\v");
    if (begin == std::string_view::npos) return tokens;
    const std::size_t end = std::min(rest.size(), rest.find_first_of(" \t\r\f\v", begin));
    tokens.push_back(rest.substr(begin, end - begin));
    rest.remove_prefix(end);
  }
}

// Checks the vertex indices of the faces of an OBJ file, naming the line.
// CGAL's reader (5.5) turns an index 0 into the one after the last vertex,
// and accepts that index: the error that follows named the wrong index and
// no line.
void check_obj_face_indices(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  struct Reference { // an index beyond the vertices read so far: allowed if defined further down
    std::size_t line, face;
    std::int64_t index;
  };
  std::vector<Reference> forward;
  std::size_t vertices = 0, faces = 0;
  std::string text;
  for (std::size_t line = 1; std::getline(in, text); ++line) {
    const std::vector<std::string_view> tokens = line_tokens(text);
    if (tokens.empty()) continue;
    if (tokens[0] == "v") ++vertices;
    if (tokens[0] != "f") continue;
    const std::string element = "face " + std::to_string(++faces);
    for (std::size_t k = 1; k < tokens.size(); ++k) {
      const std::string_view token = tokens[k];
      std::string_view digits = token.substr(0, token.find('/')); // v/vt/vn
      if (!digits.empty() && digits[0] == '+') digits.remove_prefix(1);
      std::int64_t index = 0;
      const auto r = std::from_chars(digits.data(), digits.data() + digits.size(), index);
      if (r.ec != std::errc() || r.ptr != digits.data() + digits.size() || digits.empty())
        throw Input_error(path, line, element, "expected a vertex index, found " + Input_error::quote(token));
      if (index == 0)
        throw Input_error(path, line, element,
                          "vertex index 0 is not valid: OBJ indices start at 1 (negative ones count back)");
      if (index < 0 && std::uint64_t(-(index + 1)) >= vertices)
        throw Input_error(path, line, element,
                          "vertex index " + std::to_string(index) + " is out of range " +
                              (vertices ? "-" + std::to_string(vertices) + "..-1 (" + std::to_string(vertices) +
                                              " vertices before it)"
                                        : std::string("(no vertex before it)")));
      if (index > 0 && std::uint64_t(index) > vertices) forward.push_back({line, faces, index});
    }
  }
  for (const Reference& r : forward)
    if (std::uint64_t(r.index) > vertices)
      throw Input_error(path, r.line, "face " + std::to_string(r.face),
                        "vertex index " + std::to_string(r.index) + " is out of range 1.." + std::to_string(vertices) +
                            " (" + std::to_string(vertices) + " vertices in the file)");
}

// A non-negative integer token ('+' allowed), or false.
bool parse_count(std::string_view token, std::uint64_t& value) {
  if (!token.empty() && token[0] == '+') token.remove_prefix(1);
  const auto r = std::from_chars(token.data(), token.data() + token.size(), value);
  return !token.empty() && r.ec == std::errc() && r.ptr == token.data() + token.size();
}

// Checks the counts and the faces of an ASCII OFF file before CGAL's reader,
// naming the line. CGAL's reader (5.5) converts the vertex count of a face,
// read as a double, to size_t: a negative or huge count is undefined
// behaviour (found by fuzz_surface), and a face with fewer indices than its
// count or an index out of range was reported without a line. Lines are read
// as CGAL reads them: one vertex or face per line, `#` starting a comment.
// Binary and non-3D files (`OFF BINARY`, `4OFF`, `nOFF`) are left to CGAL.
void check_off_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string text;
  std::size_t line = 0;
  std::vector<std::string_view> tokens;
  // The next line with tokens, comments removed; false at the end.
  const auto next_line = [&]() {
    while (std::getline(in, text)) {
      ++line;
      tokens = line_tokens(text);
      if (!tokens.empty()) return true;
    }
    return false;
  };
  if (!next_line()) return; // empty: CGAL's reader fails, and says so below
  std::size_t first = 0;
  const std::string_view keyword = tokens[0];
  if (keyword.size() >= 3 && keyword.substr(keyword.size() - 3) == "OFF") {
    if (keyword.find('4') != std::string_view::npos || keyword[0] == 'n') return;
    for (std::string_view t : tokens)
      if (t == "BINARY") return;
    first = 1;
    if (tokens.size() == 1) { // the counts on the next line
      if (!next_line()) throw Input_error(path, line, "", "the vertex and face counts are missing");
      first = 0;
    }
  } else if (std::uint64_t count = 0; !parse_count(keyword, count)) {
    throw Input_error(path, line, "", "not an OFF file: expected 'OFF' or the counts, found " + Input_error::quote(keyword));
  }
  std::uint64_t vertices = 0, faces = 0;
  if (tokens.size() < first + 2 || !parse_count(tokens[first], vertices) || !parse_count(tokens[first + 1], faces))
    throw Input_error(path, line, "",
                      "expected the vertex and face counts (non-negative integers), found " +
                          Input_error::quote(tokens[first]) + (tokens.size() > first + 1 ? " " + Input_error::quote(tokens[first + 1]) : ""));
  for (std::uint64_t v = 0; v < vertices; ++v)
    if (!next_line()) return; // truncated: CGAL's reader fails
  for (std::uint64_t f = 1; f <= faces; ++f) {
    if (!next_line()) return;
    const std::string element = "face " + std::to_string(f);
    std::uint64_t count = 0;
    if (!parse_count(tokens[0], count))
      throw Input_error(path, line, element,
                        "expected the number of its vertices (a non-negative integer), found " +
                            Input_error::quote(tokens[0]));
    if (tokens.size() - 1 < count)
      throw Input_error(path, line, element,
                        std::to_string(count) + " vertex indices announced, " + std::to_string(tokens.size() - 1) +
                            " found");
    for (std::uint64_t k = 1; k <= count; ++k) {
      std::uint64_t index = 0;
      if (!parse_count(tokens[k], index) || index >= vertices)
        throw Input_error(path, line, element,
                          "vertex index " + Input_error::quote(tokens[k]) + " is not in 0.." +
                              (vertices ? std::to_string(vertices - 1) : std::string("-1")) + " (" +
                              std::to_string(vertices) + " vertices in the file)");
    }
  }
}

} // namespace

// Reads a surface file into a closed, outward oriented triangle mesh, or throws.
// Appends the repairs made to `repairs`.
Surface read_closed_surface(const std::string& path, std::vector<std::string>& repairs) {
  const std::string ext = lower_extension(path);
  if (ext != ".off" && ext != ".obj" && ext != ".stl" && ext != ".ply")
    throw Input_error(path, 0, "",
                      (ext.empty() ? std::string("no file extension") : "unsupported extension '" + ext + "'") +
                          ": expected .off, .obj, .stl or .ply");
  IO::internal::check_input_file(path);
  if (!std::ifstream(path, std::ios::binary)) throw Input_error(path, 0, "", "cannot open the file for reading");
  if (ext == ".obj") check_obj_face_indices(path);
  if (ext == ".off") check_off_file(path);

  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> faces;
  bool read = false;
  try {
    read = CGAL::IO::read_polygon_soup(path, points, faces);
  } catch (const std::exception& e) {
    throw Input_error(path, 0, "", std::string("cannot read the file: ") + e.what());
  }
  std::string format = ext.substr(1);
  for (char& ch : format) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  if (!read) throw Input_error(path, 0, "", "cannot read the file as " + format + " (malformed or truncated file?)");
  if (faces.empty()) throw Input_error(path, 0, "", "the surface is empty (no faces)");
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!std::isfinite(points[i].x()) || !std::isfinite(points[i].y()) || !std::isfinite(points[i].z()))
      throw Input_error(path, 0, "vertex " + std::to_string(i + 1), "a coordinate is not finite");
  for (std::size_t i = 0; i < faces.size(); ++i) {
    if (faces[i].size() < 3)
      throw Input_error(path, 0, "face " + std::to_string(i + 1),
                        "has " + std::to_string(faces[i].size()) + " vertices (at least 3 needed)");
    for (std::size_t v : faces[i])
      if (v >= points.size())
        throw Input_error(path, 0, "face " + std::to_string(i + 1),
                          "vertex index " + std::to_string(v) + " is out of range (" +
                              std::to_string(points.size()) + " vertices)");
  }

  if (!PMP::is_polygon_soup_a_polygon_mesh(faces)) {
    // A soup (STL), duplicated points or faces, or inconsistent orientations.
    const std::size_t points_before = points.size(), faces_before = faces.size();
    PMP::repair_polygon_soup(points, faces);
    const bool oriented = PMP::orient_polygon_soup(points, faces);
    if (!oriented || faces.empty() || !PMP::is_polygon_soup_a_polygon_mesh(faces))
      throw Input_error(path, 0, "",
                        "the faces do not form a 2-manifold surface (an edge with more than two faces, a vertex "
                        "where sheets meet, or a non-orientable surface), even after polygon soup repair");
    repairs.push_back("polygon soup repaired and oriented consistently (" +
                      std::to_string(points_before - std::min(points_before, points.size())) +
                      " duplicate or unused points and " +
                      std::to_string(faces_before - std::min(faces_before, faces.size())) +
                      " degenerate or duplicate faces removed)");
  }
  Surface surface;
  PMP::polygon_soup_to_polygon_mesh(points, faces, surface);
  points.clear();
  faces.clear();

  if (!CGAL::is_triangle_mesh(surface)) {
    std::size_t polygons = 0;
    for (auto f : surface.faces())
      if (surface.degree(f) != 3) ++polygons;
    if (!PMP::triangulate_faces(surface))
      throw Input_error(path, 0, "", "a face with more than 3 vertices could not be triangulated");
    repairs.push_back(std::to_string(polygons) + " faces with more than 3 vertices triangulated");
  }

  std::size_t border_edges = 0;
  for (auto h : surface.halfedges())
    if (surface.is_border(h)) ++border_edges;
  if (border_edges > 0)
    throw Input_error(path, 0, "",
                      "the surface is not closed (" + std::to_string(border_edges) +
                          " border edges): it does not enclose a volume");
  if (PMP::does_self_intersect(surface))
    throw Input_error(path, 0, "",
                      "the surface is self-intersecting (two triangles intersect, or a triangle is degenerate)");
  // PMP::does_bound_a_volume() also accepts a surface that is inside-out
  // everywhere (the volume then contains infinity): orient always, and count
  // the faces that this reversed.
  const auto successor_of_smallest = [&surface](Surface::Face_index f) {
    auto h = surface.halfedge(f), best = h;
    for (auto g = surface.next(h); g != h; g = surface.next(g))
      if (surface.target(g) < surface.target(best)) best = g;
    return surface.target(surface.next(best));
  };
  std::vector<Surface::Vertex_index> before(surface.number_of_faces());
  for (auto f : surface.faces()) before[f.idx()] = successor_of_smallest(f);
  PMP::orient_to_bound_a_volume(surface);
  if (!PMP::does_bound_a_volume(surface))
    throw Input_error(path, 0, "", "the surface does not bound a volume, even after reorientation");
  std::size_t reversed = 0;
  for (auto f : surface.faces()) reversed += before[f.idx()] != successor_of_smallest(f);
  if (reversed > 0)
    repairs.push_back(std::to_string(reversed) + " of " + std::to_string(surface.number_of_faces()) +
                      " faces reversed to bound a volume (the surface, or some of its components, was inside-out)");
  return surface;
}

} // namespace internal
} // namespace CGAL_ext
