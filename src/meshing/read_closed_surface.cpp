// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#include "read_closed_surface.h"

#include <CGAL_ext/Input_error.h>

#include "../IO/input_file.h"

#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
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

// The whitespace-separated tokens of a line, up to a `#` comment if
// `comments` (OFF, OBJ; a PLY header has no such comments: CGAL reads
// `end_header#` as another keyword).
std::vector<std::string_view> line_tokens(std::string_view rest, bool comments = true) {
  if (comments) rest = rest.substr(0, rest.find('#'));
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

// The lines of an OFF file with tokens, comments removed, and their numbers.
class Off_lines {
public:
  explicit Off_lines(const std::string& path) : path_(path), in_(path, std::ios::binary) {}
  // The next line with tokens; false at the end.
  bool next() {
    while (std::getline(in_, text_)) {
      ++line_;
      tokens_ = line_tokens(text_);
      if (!tokens_.empty()) return true;
    }
    return false;
  }
  const std::vector<std::string_view>& tokens() const { return tokens_; }
  std::size_t line() const { return line_; }
  Input_error error(const std::string& element, const std::string& problem) const {
    return Input_error(path_, line_, element, problem);
  }
  Input_error truncated(const std::string& what) const {
    return error("", "the file ends before " + what + " (truncated file?)");
  }

private:
  std::string path_;
  std::ifstream in_;
  std::string text_;
  std::size_t line_ = 0;
  std::vector<std::string_view> tokens_;
};

// The OFF header: the keyword line (OFF, COFF, 4OFF...) if any, and the
// vertex and face counts. Sets `homogeneous` for 4OFF.
std::array<std::uint64_t, 2> read_off_header(Off_lines& in, bool& homogeneous) {
  if (!in.next()) throw in.error("", "the file is empty");
  std::size_t first = 0;
  homogeneous = false;
  const std::string_view keyword = in.tokens()[0];
  if (keyword.size() >= 3 && keyword.substr(keyword.size() - 3) == "OFF") {
    for (std::string_view t : in.tokens())
      if (t == "BINARY")
        throw in.error("", "binary OFF is not supported (CGAL 5.5's reader overflows on bad binary headers, found by "
                           "fuzz_surface): write ASCII OFF, binary STL or binary PLY");
    if (keyword[0] == 'n' || keyword.find("nOFF") != std::string_view::npos)
      throw in.error("", "an OFF file of another dimension (nOFF) is not supported");
    homogeneous = keyword.find('4') != std::string_view::npos;
    first = 1;
    if (in.tokens().size() == 1) { // the counts on the next line
      if (!in.next()) throw in.truncated("the vertex and face counts");
      first = 0;
    }
  } else if (std::uint64_t count = 0; !parse_count(keyword, count)) {
    throw in.error("", "not an OFF file: expected 'OFF' or the counts, found " + Input_error::quote(keyword));
  }
  const std::vector<std::string_view>& tokens = in.tokens();
  std::array<std::uint64_t, 2> counts{0, 0};
  if (tokens.size() < first + 2 || !parse_count(tokens[first], counts[0]) || !parse_count(tokens[first + 1], counts[1]))
    throw in.error("", "expected the vertex and face counts (non-negative integers), found " +
                           Input_error::quote(tokens[first]) +
                           (tokens.size() > first + 1 ? " " + Input_error::quote(tokens[first + 1]) : ""));
  return counts;
}

// Reads vertex v (1-based) of an OFF file: x y z, or x y z w if homogeneous.
Point read_off_vertex(Off_lines& in, std::uint64_t v, bool homogeneous) {
  if (!in.next()) throw in.truncated("vertex " + std::to_string(v));
  const std::vector<std::string_view>& tokens = in.tokens();
  const std::string element = "vertex " + std::to_string(v);
  const std::size_t coordinates = homogeneous ? 4 : 3;
  double x[4] = {0, 0, 0, 1};
  for (std::size_t k = 0; k < coordinates; ++k) {
    if (k >= tokens.size())
      throw in.error(element, std::to_string(coordinates) + " coordinates expected, " + std::to_string(tokens.size()) +
                                  " found");
    const std::string token(tokens[k]);
    char* stop = nullptr;
    x[k] = std::strtod(token.c_str(), &stop);
    if (*stop != '\0') throw in.error(element, "expected a coordinate, found " + Input_error::quote(token));
    if (!std::isfinite(x[k])) throw in.error(element, "a coordinate is not finite");
  }
  if (homogeneous && x[3] == 0) throw in.error(element, "the homogeneous coordinate w is 0");
  const Point p(x[0] / x[3], x[1] / x[3], x[2] / x[3]);
  if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z()))
    throw in.error(element, "a coordinate divided by w is not finite");
  return p;
}

// Reads face f (1-based) of an OFF file: its vertex count, then the indices, each below `vertices`.
std::vector<std::size_t> read_off_face(Off_lines& in, std::uint64_t f, std::uint64_t vertices) {
  if (!in.next()) throw in.truncated("face " + std::to_string(f));
  const std::vector<std::string_view>& tokens = in.tokens();
  const std::string element = "face " + std::to_string(f);
  std::uint64_t count = 0;
  if (!parse_count(tokens[0], count))
    throw in.error(element, "expected the number of its vertices (a non-negative integer), found " +
                                Input_error::quote(tokens[0]));
  if (tokens.size() - 1 < count)
    throw in.error(element, std::to_string(count) + " vertex indices announced, " + std::to_string(tokens.size() - 1) +
                                " found");
  std::vector<std::size_t> face;
  for (std::uint64_t k = 1; k <= count; ++k) {
    std::uint64_t index = 0;
    if (!parse_count(tokens[k], index) || index >= vertices)
      throw in.error(element, "vertex index " + Input_error::quote(tokens[k]) + " is not in 0.." +
                                  (vertices ? std::to_string(vertices - 1) : std::string("-1")) + " (" +
                                  std::to_string(vertices) + " vertices in the file)");
    face.push_back(static_cast<std::size_t>(index));
  }
  return face;
}

// Reads an ASCII OFF file into a polygon soup, naming the line of any
// defect; a binary file (`OFF BINARY`) is refused.
// Our own reader, because CGAL's (5.5) has undefined behaviour on bad
// files, all found by fuzz_surface: it converts a face's vertex count `-1`,
// read as a double, to size_t; it reads colour entries past the numbers of
// a short line; it converts colours out of 0..255 to unsigned char. Lines
// are read as CGAL reads them, one vertex or face per line, `#` starting a
// comment; the header may be OFF, COFF, NOFF, CNOFF, STOFF and the like
// (what follows the coordinates and the indices, colours, normals, texture
// coordinates, is ignored), or 4OFF (homogeneous: x/w, y/w, z/w).
void read_ascii_off(const std::string& path, std::vector<Point>& points,
                    std::vector<std::vector<std::size_t>>& faces_out) {
  Off_lines in(path);
  bool homogeneous = false;
  const auto [vertices, faces] = read_off_header(in, homogeneous);
  for (std::uint64_t v = 1; v <= vertices; ++v) points.push_back(read_off_vertex(in, v, homogeneous));
  for (std::uint64_t f = 1; f <= faces; ++f) faces_out.push_back(read_off_face(in, f, vertices));
}

std::string number_text(double x) {
  std::ostringstream out;
  out.precision(17);
  out << x;
  return out.str();
}

// The size in bytes of a PLY scalar type, 0 if unknown.
std::size_t ply_type_size(std::string_view type) {
  if (type == "char" || type == "int8" || type == "uchar" || type == "uint8") return 1;
  if (type == "short" || type == "int16" || type == "ushort" || type == "uint16") return 2;
  if (type == "int" || type == "int32" || type == "uint" || type == "uint32" || type == "float" || type == "float32")
    return 4;
  if (type == "double" || type == "float64") return 8;
  return 0;
}

// A binary PLY list count of `type`, as a double (exact for every type).
double ply_binary_count(const unsigned char* b, std::string_view type, bool big_endian) {
  const std::size_t n = ply_type_size(type);
  unsigned char v[8] = {};
  for (std::size_t i = 0; i < n; ++i) v[i] = b[big_endian ? n - 1 - i : i]; // to little-endian
  const auto as = [&v](auto x) {
    std::memcpy(&x, v, sizeof x);
    return static_cast<double>(x);
  };
  if (type == "char" || type == "int8") return as(std::int8_t());
  if (type == "uchar" || type == "uint8") return as(std::uint8_t());
  if (type == "short" || type == "int16") return as(std::int16_t());
  if (type == "ushort" || type == "uint16") return as(std::uint16_t());
  if (type == "int" || type == "int32") return as(std::int32_t());
  if (type == "uint" || type == "uint32") return as(std::uint32_t());
  if (type == "float" || type == "float32") return as(float());
  return as(double());
}

// A PLY header: its format and its elements with their properties.
struct Ply_property {
  bool list;
  std::string count_type, type, name;
};
struct Ply_element {
  std::string name;
  std::uint64_t count;
  std::vector<Ply_property> properties;
};
struct Ply_header {
  std::vector<Ply_element> elements;
  std::string format;
};

// Reads and checks the header of a PLY file from `in`, which is left at the body.
Ply_header read_ply_header(const std::string& path, std::istream& in) {
  Ply_header h;
  std::vector<Ply_element>& elements = h.elements;
  std::string text;
  std::size_t line = 1;
  const auto check_vertex_element = [&](std::size_t element_line) {
    if (elements.empty() || (elements.back().name != "vertex" && elements.back().name != "vertices")) return;
    int coordinates = 0;
    for (const Ply_property& p : elements.back().properties)
      coordinates += !p.list && (p.name == "x" || p.name == "y" || p.name == "z");
    if (coordinates != 3)
      throw Input_error(path, element_line, "",
                        "the vertex element needs the properties x, y and z, of type float or double");
  };
  std::size_t element_line = 0;
  bool header_done = false;
  for (; std::getline(in, text); ++line) {
    const std::vector<std::string_view> t = line_tokens(text, false);
    if (line == 1) {
      if (t.size() != 1 || t[0] != "ply") throw Input_error(path, 1, "", "not a PLY file: the first line is not 'ply'");
      continue;
    }
    if (t.empty() || t[0] == "comment" || t[0] == "obj_info") continue;
    if (t[0] == "end_header") {
      check_vertex_element(element_line);
      header_done = true;
      break;
    }
    if (t[0] == "format") {
      if (t.size() != 3 || (t[1] != "ascii" && t[1] != "binary_little_endian" && t[1] != "binary_big_endian"))
        throw Input_error(path, line, "", "expected 'format ascii|binary_little_endian|binary_big_endian VERSION'");
      h.format = std::string(t[1]);
    } else if (t[0] == "element") {
      std::uint64_t count = 0;
      if (t.size() != 3 || !parse_count(t[2], count))
        throw Input_error(path, line, "", "expected 'element NAME COUNT', COUNT a non-negative integer");
      check_vertex_element(element_line);
      elements.push_back({std::string(t[1]), count, {}});
      element_line = line;
    } else if (t[0] == "property") {
      if (elements.empty()) throw Input_error(path, line, "", "a property before any element");
      const bool list = t.size() == 5 && t[1] == "list" && ply_type_size(t[2]) && ply_type_size(t[3]);
      if (!list && (t.size() != 3 || !ply_type_size(t[1])))
        throw Input_error(path, line, "", "expected 'property TYPE NAME' or 'property list TYPE TYPE NAME'");
      Ply_property p{list, list ? std::string(t[2]) : "", std::string(t[list ? 3 : 1]), std::string(t[list ? 4 : 2])};
      const bool vertex = elements.back().name == "vertex" || elements.back().name == "vertices";
      if (vertex && !list && (p.name == "x" || p.name == "y" || p.name == "z") && p.type != "float" &&
          p.type != "float32" && p.type != "double" && p.type != "float64")
        throw Input_error(path, line, "",
                          "the coordinate " + p.name + " has type " + p.type + ": float or double expected");
      elements.back().properties.push_back(std::move(p));
    } else {
      throw Input_error(path, line, "", "unknown PLY header keyword " + Input_error::quote(t[0]));
    }
  }
  if (!header_done) throw Input_error(path, 0, "", "the PLY header has no 'end_header' line");
  if (h.format.empty()) throw Input_error(path, 0, "", "the PLY header has no 'format' line");
  return h;
}

// Walks the body of a PLY file from `in` without storing it: every item
// present, every list count a non-negative integer whose entries the rest of
// the file can hold.
void check_ply_body(const std::string& path, std::istream& in, const Ply_header& h) {
  // The body. Each item of an element with properties takes at least one
  // byte or token, so the walk ends with the file.
  const bool ascii = h.format == "ascii", big_endian = h.format == "binary_big_endian";
  const std::streamoff body = in.tellg();
  in.seekg(0, std::ios::end);
  const std::streamoff end = in.tellg();
  in.seekg(body);
  std::string token;
  unsigned char bytes[8];
  for (const Ply_element& e : h.elements) {
    if (e.properties.empty()) continue;
    for (std::uint64_t item = 1; item <= e.count; ++item) {
      const auto where = [&] { return "element '" + e.name + "', item " + std::to_string(item); };
      const auto truncated = [&] { return Input_error(path, 0, where(), "the file ends here (truncated file?)"); };
      for (const Ply_property& p : e.properties) {
        if (!p.list) {
          if (ascii ? !(in >> token) : !in.ignore(std::streamsize(ply_type_size(p.type))) ||
                                           in.gcount() != std::streamsize(ply_type_size(p.type)))
            throw truncated();
          continue;
        }
        double count = 0;
        if (ascii) {
          if (!(in >> token)) throw truncated();
          char* stop = nullptr;
          count = std::strtod(token.c_str(), &stop);
          if (*stop != '\0') count = -1;
        } else {
          const std::size_t n = ply_type_size(p.count_type);
          if (!in.read(reinterpret_cast<char*>(bytes), std::streamsize(n))) throw truncated();
          count = ply_binary_count(bytes, p.count_type, big_endian);
        }
        const double left = double(end - in.tellg());
        const double entry = ascii ? 2 : double(ply_type_size(p.type)); // an ASCII entry: a digit and a space
        if (!(count >= 0) || count != std::floor(count) || count * entry > left + 1)
          throw Input_error(path, 0, where(),
                            "the list '" + p.name + "' has " + (ascii ? Input_error::quote(token) : number_text(count)) +
                                " entries, more than the rest of the file can hold, or not a count");
        for (std::uint64_t k = 0; k < std::uint64_t(count); ++k)
          if (ascii ? !(in >> token) : !in.ignore(std::streamsize(ply_type_size(p.type))) ||
                                           in.gcount() != std::streamsize(ply_type_size(p.type)))
            throw truncated();
      }
    }
  }
}

// Checks a PLY file before CGAL's reader, naming the line or the element.
// CGAL's reader (5.5) adds a `property` to the last `element` read without
// checking that there is one (undefined behaviour), reads vertex
// coordinates of a type other than float or double through a null pointer
// (a crash), and resizes a face's index list to the count the file gives
// before reading it (a 300-byte file asked for 7.6 GB); all three were found
// by fuzz_surface. Checked: the header (the `ply` line, the format, element
// counts, properties after an element, with known types, x, y and z of the
// vertices as float or double, `end_header`), then the body, walked without
// storing it: every item present, and every list count a non-negative
// integer whose entries the rest of the file can hold.
void check_ply_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  check_ply_body(path, in, read_ply_header(path, in));
}

// Reads the polygon soup of a surface file (our OFF reader, or CGAL's for
// the other formats), and checks its coordinates and face indices.
void read_checked_soup(const std::string& path, const std::string& ext, std::vector<Point>& points,
                       std::vector<std::vector<std::size_t>>& faces) {
  bool read = false;
  try {
    if (ext == ".off") {
      read_ascii_off(path, points, faces);
      read = true;
    } else {
      read = CGAL::IO::read_polygon_soup(path, points, faces);
    }
  } catch (const Input_error&) {
    throw;
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
}

// Repairs a soup that is not a polygon mesh (an STL soup, duplicated points
// or faces, inconsistent orientations), or throws; the repair is reported.
void make_polygon_mesh_soup(const std::string& path, std::vector<Point>& points,
                            std::vector<std::vector<std::size_t>>& faces, std::vector<std::string>& repairs) {
  if (PMP::is_polygon_soup_a_polygon_mesh(faces)) return;
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

// Splits the polygons of the soup into triangles. Only convex planar
// polygons are accepted (decided with exact predicates) and fanned from
// their first vertex: CGAL 5.5's triangulate_faces() binds null references
// on polygons with coinciding, collinear or crossing vertices (found by
// fuzz_surface), and such faces have no clear meaning anyway.
void triangulate_convex_polygons(const std::string& path, const std::vector<Point>& points,
                                 std::vector<std::vector<std::size_t>>& faces, std::vector<std::string>& repairs) {
  std::size_t polygons = 0;
  std::vector<std::vector<std::size_t>> triangles;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const std::vector<std::size_t>& face = faces[f];
    if (face.size() == 3) {
      triangles.push_back(face);
      continue;
    }
    ++polygons;
    const std::size_t n = face.size();
    const auto P = [&](std::size_t i) -> const Point& { return points[face[i % n]]; };
    bool convex = true;
    for (std::size_t i = 0; i < n && convex; ++i) {
      if (CGAL::collinear(P(i), P(i + 1), P(i + 2))) convex = false;
      for (std::size_t j = 0; j < n && convex; ++j)
        if (j != i && j != (i + 1) % n && j != (i + 2) % n)
          convex = CGAL::coplanar(P(i), P(i + 1), P(i + 2), P(j)) &&
                   CGAL::coplanar_orientation(P(i), P(i + 1), P(i + 2), P(j)) == CGAL::POSITIVE &&
                   CGAL::coplanar_orientation(P(i + 1), P(i + 2), P(i), P(j)) == CGAL::POSITIVE;
    }
    if (!convex)
      throw Input_error(path, 0, "",
                        "a face with " + std::to_string(n) + " vertices, from (" + number_text(P(0).x()) + ", " +
                            number_text(P(0).y()) + ", " + number_text(P(0).z()) +
                            "), is not a convex planar polygon (coinciding, collinear or crossing vertices, or "
                            "not in one plane): triangulate it first");
    for (std::size_t i = 1; i + 1 < n; ++i) triangles.push_back({face[0], face[i], face[i + 1]});
  }
  if (polygons > 0) repairs.push_back(std::to_string(polygons) + " faces with more than 3 vertices triangulated");
  faces.swap(triangles);
}

// The polygon mesh of the soup, closed, without self-intersections, and
// oriented to bound a volume (the faces reversed are reported), or throws.
Surface closed_oriented_surface(const std::string& path, std::vector<Point>& points,
                                std::vector<std::vector<std::size_t>>& faces, std::vector<std::string>& repairs) {
  Surface surface;
  PMP::polygon_soup_to_polygon_mesh(points, faces, surface);
  points.clear();
  faces.clear();
  // Points used by no face become isolated vertices, on which CGAL 5.5's
  // orient_to_bound_a_volume() dereferences a null halfedge (found by
  // fuzz_surface): removed, and reported.
  if (const std::size_t isolated = PMP::remove_isolated_vertices(surface)) {
    surface.collect_garbage();
    repairs.push_back(std::to_string(isolated) + " vertices used by no face removed");
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
  if (!std::ifstream(path, std::ios::binary)) throw Input_error(path, 0, "", IO::internal::cannot_open_for_reading());
  if (ext == ".obj") check_obj_face_indices(path);
  if (ext == ".ply") check_ply_file(path);

  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> faces;
  read_checked_soup(path, ext, points, faces);
  make_polygon_mesh_soup(path, points, faces, repairs);
  triangulate_convex_polygons(path, points, faces, repairs);
  return closed_oriented_surface(path, points, faces, repairs);
}

} // namespace internal
} // namespace CGAL_ext
