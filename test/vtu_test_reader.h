// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// A small, strict reader of VTK XML UnstructuredGrid (.vtu) files for the
// tests, with no XML library: it checks that the file is well-formed XML
// (one root, every tag closed and correctly nested, attributes quoted and not
// repeated, no stray '<' or '&' in text), then decodes every DataArray, ASCII
// or inline base64 binary with a UInt64 (or UInt32) header, into doubles.
// Anything unexpected throws std::runtime_error.
#ifndef CGAL_EXT_TEST_VTU_TEST_READER_H
#define CGAL_EXT_TEST_VTU_TEST_READER_H

#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace CGAL_ext {
namespace testing {

/// An XML element: name, attributes, text content (entities decoded,
/// concatenated over the whole element) and children.
struct Xml_element {
  std::string name;
  std::map<std::string, std::string> attributes;
  std::string text;
  std::vector<std::unique_ptr<Xml_element>> children;

  /// The value of an attribute that must exist.
  const std::string& attribute(const std::string& a) const {
    auto it = attributes.find(a);
    if (it == attributes.end()) throw std::runtime_error("<" + name + "> has no attribute " + a);
    return it->second;
  }
  /// The children named `n`.
  std::vector<const Xml_element*> children_named(const std::string& n) const {
    std::vector<const Xml_element*> r;
    for (const auto& c : children)
      if (c->name == n) r.push_back(c.get());
    return r;
  }
  /// The one child named `n`.
  const Xml_element& child(const std::string& n) const {
    const auto r = children_named(n);
    if (r.size() != 1) throw std::runtime_error("<" + name + "> has " + std::to_string(r.size()) + " <" + n + ">");
    return *r[0];
  }
};

namespace detail {

[[noreturn]] inline void fail(std::size_t pos, const std::string& why) {
  throw std::runtime_error("XML error at byte " + std::to_string(pos) + ": " + why);
}

inline bool is_name_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_' || c == ':'; }
inline bool is_name_char(char c) {
  return is_name_start(c) || std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '.';
}

// Decodes &amp; &lt; &gt; &quot; &apos; and numeric references (ASCII only); a
// stray '&' or '<' is an error.
inline std::string decode_entities(const std::string& s, std::size_t pos) {
  std::string r;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '<') fail(pos + i, "'<' in text or attribute value");
    if (s[i] != '&') {
      r += s[i];
      continue;
    }
    const std::size_t semi = s.find(';', i);
    if (semi == std::string::npos) fail(pos + i, "'&' without ';'");
    const std::string ent = s.substr(i + 1, semi - i - 1);
    if (ent == "amp") r += '&';
    else if (ent == "lt") r += '<';
    else if (ent == "gt") r += '>';
    else if (ent == "quot") r += '"';
    else if (ent == "apos") r += '\'';
    else if (ent.size() > 1 && ent[0] == '#') {
      const long v = ent[1] == 'x' ? std::strtol(ent.c_str() + 2, nullptr, 16) : std::strtol(ent.c_str() + 1, nullptr, 10);
      if (v <= 0 || v > 127) fail(pos + i, "unsupported character reference &" + ent + ";");
      r += static_cast<char>(v);
    } else {
      fail(pos + i, "unknown entity &" + ent + ";");
    }
    i = semi;
  }
  return r;
}

class Xml_parser {
public:
  explicit Xml_parser(const std::string& s) : s_(s) {}

  std::unique_ptr<Xml_element> parse() {
    // An XML declaration must be the very first bytes.
    if (s_.compare(0, 5, "<?xml") == 0) {
      const std::size_t e = s_.find("?>", p_);
      if (e == std::string::npos) fail(p_, "unterminated XML declaration");
      p_ = e + 2;
    }
    skip_misc();
    if (p_ >= s_.size() || s_[p_] != '<') fail(p_, "no root element");
    auto root = element();
    skip_misc();
    if (p_ != s_.size()) fail(p_, "content after the root element");
    return root;
  }

private:
  void skip_space() {
    while (p_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[p_]))) ++p_;
  }
  // White space and comments (outside the root).
  void skip_misc() {
    for (;;) {
      skip_space();
      if (s_.compare(p_, 4, "<!--") != 0) return;
      const std::size_t e = s_.find("-->", p_);
      if (e == std::string::npos) fail(p_, "unterminated comment");
      p_ = e + 3;
    }
  }
  std::string name() {
    if (p_ >= s_.size() || !is_name_start(s_[p_])) fail(p_, "expected a name");
    const std::size_t b = p_;
    while (p_ < s_.size() && is_name_char(s_[p_])) ++p_;
    return s_.substr(b, p_ - b);
  }

  // At '<' of a start tag: reads the element up to its end tag.
  std::unique_ptr<Xml_element> element() {
    auto e = std::make_unique<Xml_element>();
    ++p_; // '<'
    e->name = name();
    for (;;) {
      const std::size_t before = p_;
      skip_space();
      if (p_ >= s_.size()) fail(p_, "unterminated start tag <" + e->name + ">");
      if (s_[p_] == '/') {
        if (s_.compare(p_, 2, "/>") != 0) fail(p_, "expected '/>'");
        p_ += 2;
        return e;
      }
      if (s_[p_] == '>') {
        ++p_;
        break;
      }
      if (p_ == before) fail(p_, "no white space before an attribute of <" + e->name + ">");
      const std::string a = name();
      skip_space();
      if (p_ >= s_.size() || s_[p_] != '=') fail(p_, "attribute " + a + " without '='");
      ++p_;
      skip_space();
      if (p_ >= s_.size() || (s_[p_] != '"' && s_[p_] != '\'')) fail(p_, "attribute " + a + " is not quoted");
      const char q = s_[p_++];
      const std::size_t end = s_.find(q, p_);
      if (end == std::string::npos) fail(p_, "unterminated value of attribute " + a);
      const std::string v = decode_entities(s_.substr(p_, end - p_), p_);
      p_ = end + 1;
      if (!e->attributes.emplace(a, v).second) fail(p_, "attribute " + a + " repeated in <" + e->name + ">");
    }
    // Content: text, children, comments, then the matching end tag.
    for (;;) {
      const std::size_t lt = s_.find('<', p_);
      if (lt == std::string::npos) fail(p_, "<" + e->name + "> is never closed");
      e->text += decode_entities(s_.substr(p_, lt - p_), p_);
      p_ = lt;
      if (s_.compare(p_, 4, "<!--") == 0) {
        const std::size_t c = s_.find("-->", p_);
        if (c == std::string::npos) fail(p_, "unterminated comment");
        p_ = c + 3;
      } else if (s_.compare(p_, 2, "</") == 0) {
        p_ += 2;
        const std::string n = name();
        if (n != e->name) fail(p_, "</" + n + "> closes <" + e->name + ">");
        skip_space();
        if (p_ >= s_.size() || s_[p_] != '>') fail(p_, "expected '>' after </" + n);
        ++p_;
        return e;
      } else {
        e->children.push_back(element());
      }
    }
  }

  const std::string& s_;
  std::size_t p_ = 0;
};

} // namespace detail

/// Parses a whole XML document (strict; throws std::runtime_error).
inline std::unique_ptr<Xml_element> parse_xml(const std::string& text) { return detail::Xml_parser(text).parse(); }

/// Decodes base64 (RFC 4648 alphabet, '=' padding only at the end, no white
/// space inside); throws on any other character or a bad length.
inline std::vector<unsigned char> base64_decode(const std::string& s) {
  auto value = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return -1;
  };
  if (s.size() % 4 != 0) throw std::runtime_error("base64: length " + std::to_string(s.size()) + " is not a multiple of 4");
  std::vector<unsigned char> r;
  r.reserve(s.size() / 4 * 3);
  for (std::size_t i = 0; i < s.size(); i += 4) {
    const bool last = i + 4 == s.size();
    int v[4];
    int pad = 0;
    for (int k = 0; k < 4; ++k) {
      const char c = s[i + k];
      if (c == '=' && last && k >= 2) {
        v[k] = 0;
        ++pad;
        continue;
      }
      if (pad > 0) throw std::runtime_error("base64: data after '='");
      v[k] = value(c);
      if (v[k] < 0) throw std::runtime_error(std::string("base64: invalid character '") + c + "'");
    }
    const std::uint32_t w = (std::uint32_t(v[0]) << 18) | (std::uint32_t(v[1]) << 12) | (std::uint32_t(v[2]) << 6) | v[3];
    r.push_back(static_cast<unsigned char>(w >> 16));
    if (pad < 2) r.push_back(static_cast<unsigned char>((w >> 8) & 0xff));
    if (pad < 1) r.push_back(static_cast<unsigned char>(w & 0xff));
  }
  return r;
}

/// One decoded DataArray.
struct Data_array {
  std::string name, type, format;
  int components = 1;
  std::vector<double> values;
};

/// What a .vtu file holds.
struct Vtu_content {
  std::map<std::string, std::string> root_attributes; ///< of <VTKFile>
  std::size_t number_of_points = 0, number_of_cells = 0;
  std::map<std::string, Data_array> point_data, cell_data;
  Data_array points, connectivity, offsets, types;
};

namespace detail {

inline std::string trim(const std::string& s) {
  std::size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return s.substr(b, e - b);
}

inline std::size_t type_size(const std::string& t) {
  if (t == "Float64" || t == "Int64" || t == "UInt64") return 8;
  if (t == "Float32" || t == "Int32" || t == "UInt32") return 4;
  if (t == "Int16" || t == "UInt16") return 2;
  if (t == "Int8" || t == "UInt8") return 1;
  throw std::runtime_error("unknown DataArray type " + t);
}

// Value i of the little-endian bytes `p` of type `t`.
inline double little_endian_value(const unsigned char* p, const std::string& t) {
  unsigned char b[8];
  const std::size_t n = type_size(t);
  const std::uint16_t one = 1;
  const bool little = *reinterpret_cast<const unsigned char*>(&one) == 1;
  for (std::size_t k = 0; k < n; ++k) b[k] = little ? p[k] : p[n - 1 - k];
  auto get = [&b](auto v) {
    std::memcpy(&v, b, sizeof v);
    return static_cast<double>(v);
  };
  if (t == "Float64") return get(double());
  if (t == "Float32") return get(float());
  if (t == "Int64") return get(std::int64_t());
  if (t == "UInt64") return get(std::uint64_t());
  if (t == "Int32") return get(std::int32_t());
  if (t == "UInt32") return get(std::uint32_t());
  if (t == "Int16") return get(std::int16_t());
  if (t == "UInt16") return get(std::uint16_t());
  if (t == "Int8") return get(std::int8_t());
  return get(std::uint8_t());
}

inline Data_array decode(const Xml_element& e, const std::string& header_type) {
  if (e.name != "DataArray") throw std::runtime_error("<" + e.name + "> where a <DataArray> was expected");
  if (!e.children.empty()) throw std::runtime_error("a DataArray has child elements");
  Data_array a;
  a.name = e.attribute("Name");
  a.type = e.attribute("type");
  a.format = e.attribute("format");
  const auto nc = e.attributes.find("NumberOfComponents");
  a.components = nc == e.attributes.end() ? 1 : std::stoi(nc->second);
  if (a.components < 1) throw std::runtime_error(a.name + ": NumberOfComponents < 1");
  const std::size_t size = type_size(a.type);
  if (a.format == "ascii") {
    std::istringstream in(e.text);
    std::string tok;
    while (in >> tok) {
      char* end = nullptr;
      const double v = std::strtod(tok.c_str(), &end);
      if (*end != '\0') throw std::runtime_error(a.name + ": '" + tok + "' is not a number");
      a.values.push_back(v);
    }
  } else if (a.format == "binary") {
    const std::vector<unsigned char> bytes = base64_decode(trim(e.text));
    const std::size_t hs = header_type == "UInt64" ? 8 : 4;
    if (bytes.size() < hs) throw std::runtime_error(a.name + ": binary data shorter than its header");
    const double nbytes = little_endian_value(bytes.data(), hs == 8 ? "UInt64" : "UInt32");
    if (nbytes != static_cast<double>(bytes.size() - hs))
      throw std::runtime_error(a.name + ": the header says " + std::to_string(nbytes) + " bytes, the data has " +
                               std::to_string(bytes.size() - hs));
    if ((bytes.size() - hs) % size != 0) throw std::runtime_error(a.name + ": byte count not a multiple of the type size");
    for (std::size_t i = hs; i < bytes.size(); i += size) a.values.push_back(little_endian_value(bytes.data() + i, a.type));
  } else {
    throw std::runtime_error(a.name + ": unsupported format " + a.format);
  }
  if (a.values.size() % static_cast<std::size_t>(a.components) != 0)
    throw std::runtime_error(a.name + ": the number of values is not a multiple of NumberOfComponents");
  return a;
}

inline std::map<std::string, Data_array> decode_all(const Xml_element& section, const std::string& header_type) {
  std::map<std::string, Data_array> r;
  for (const auto& c : section.children) {
    Data_array a = decode(*c, header_type);
    const std::string n = a.name;
    if (!r.emplace(n, std::move(a)).second) throw std::runtime_error("two arrays named " + n + " in <" + section.name + ">");
  }
  return r;
}

} // namespace detail

/// Parses the text of a .vtu file: one Piece of an UnstructuredGrid, its
/// PointData, CellData, Points and Cells (connectivity, offsets, types).
/// Checks that each array has as many tuples as the Piece says.
inline Vtu_content parse_vtu(const std::string& text) {
  const auto root = parse_xml(text);
  if (root->name != "VTKFile") throw std::runtime_error("the root is <" + root->name + ">, not <VTKFile>");
  Vtu_content v;
  v.root_attributes = root->attributes;
  if (root->attribute("type") != "UnstructuredGrid") throw std::runtime_error("not an UnstructuredGrid");
  if (root->attribute("byte_order") != "LittleEndian") throw std::runtime_error("not LittleEndian");
  const auto ht = root->attributes.find("header_type");
  const std::string header_type = ht == root->attributes.end() ? "UInt32" : ht->second;
  if (header_type != "UInt64" && header_type != "UInt32") throw std::runtime_error("bad header_type " + header_type);
  const Xml_element& piece = root->child("UnstructuredGrid").child("Piece");
  v.number_of_points = std::stoull(piece.attribute("NumberOfPoints"));
  v.number_of_cells = std::stoull(piece.attribute("NumberOfCells"));
  for (const auto* s : piece.children_named("PointData")) v.point_data = detail::decode_all(*s, header_type);
  for (const auto* s : piece.children_named("CellData")) v.cell_data = detail::decode_all(*s, header_type);
  if (piece.children_named("PointData").size() > 1 || piece.children_named("CellData").size() > 1)
    throw std::runtime_error("more than one PointData or CellData");
  auto points = detail::decode_all(piece.child("Points"), header_type);
  if (points.size() != 1) throw std::runtime_error("<Points> must hold one DataArray");
  v.points = points.begin()->second;
  auto cells = detail::decode_all(piece.child("Cells"), header_type);
  for (const char* n : {"connectivity", "offsets", "types"})
    if (!cells.count(n)) throw std::runtime_error(std::string("<Cells> has no ") + n);
  v.connectivity = cells["connectivity"];
  v.offsets = cells["offsets"];
  v.types = cells["types"];
  auto tuples = [](const Data_array& a) { return a.values.size() / static_cast<std::size_t>(a.components); };
  if (v.points.components != 3 || tuples(v.points) != v.number_of_points)
    throw std::runtime_error("Points does not hold NumberOfPoints 3D points");
  if (v.offsets.values.size() != v.number_of_cells || v.types.values.size() != v.number_of_cells)
    throw std::runtime_error("offsets or types do not have NumberOfCells values");
  for (const auto& [n, a] : v.point_data)
    if (tuples(a) != v.number_of_points) throw std::runtime_error("point data " + n + ": wrong number of tuples");
  for (const auto& [n, a] : v.cell_data)
    if (tuples(a) != v.number_of_cells) throw std::runtime_error("cell data " + n + ": wrong number of tuples");
  return v;
}

/// Reads and parses a .vtu file.
inline Vtu_content read_vtu(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot open");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_vtu(ss.str());
}

} // namespace testing
} // namespace CGAL_ext

#endif // CGAL_EXT_TEST_VTU_TEST_READER_H
