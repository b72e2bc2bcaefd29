// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#include <CGAL_ext/IO/Vtu_file.h>

#include "write_file_atomically.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <set>
#include <stdexcept>
#include <string_view>
#include <type_traits>

namespace CGAL_ext {
namespace IO {

namespace {

// VTK cell types.
constexpr unsigned char vtk_line = 3;
constexpr unsigned char vtk_tetra = 10;
constexpr unsigned char vtk_hexahedron = 12;

bool host_is_little_endian() {
  const std::uint16_t one = 1;
  unsigned char first;
  std::memcpy(&first, &one, 1);
  return first == 1;
}

// Stores `v` at `p` in little-endian byte order.
template <class T>
void store_little_endian(unsigned char* p, T v, bool little) {
  std::memcpy(p, &v, sizeof(T));
  if (!little) std::reverse(p, p + sizeof(T));
}

// A large output buffer in front of fwrite: values are formatted or encoded
// straight into it, and it goes to the file 1 MiB at a time.
class Buffered_output {
public:
  static constexpr std::size_t capacity = std::size_t(1) << 20;

  Buffered_output(std::FILE* f, const std::string& path) : f_(f), path_(path), buf_(capacity) {}

  // Room for `k <= capacity` bytes; `commit()` then says how many were used.
  char* reserve(std::size_t k) {
    if (n_ + k > capacity) flush();
    return buf_.data() + n_;
  }
  void commit(std::size_t k) { n_ += k; }

  void put(std::string_view s) {
    if (s.size() > capacity) {
      flush();
      write(s.data(), s.size());
      return;
    }
    std::memcpy(reserve(s.size()), s.data(), s.size());
    commit(s.size());
  }
  void put(char c) {
    *reserve(1) = c;
    commit(1);
  }

  void flush() {
    write(buf_.data(), n_);
    n_ = 0;
  }

private:
  void write(const char* p, std::size_t k) {
    if (k > 0 && std::fwrite(p, 1, k, f_) != k) throw std::runtime_error(path_ + ": write error");
  }

  std::FILE* f_;
  const std::string& path_;
  std::vector<char> buf_;
  std::size_t n_ = 0;
};

// Streaming base64 (RFC 4648, with padding, no line breaks): bytes are fed in
// pieces of any size; `finish()` writes the last, padded quadruple.
class Base64_encoder {
public:
  explicit Base64_encoder(Buffered_output& out) : out_(out) {}

  void feed(const unsigned char* p, std::size_t n) {
    if (pending_ > 0) { // complete the triplet begun by the previous piece
      const std::size_t take = std::min(3 - pending_, n);
      std::memcpy(carry_ + pending_, p, take);
      pending_ += take;
      p += take;
      n -= take;
      if (pending_ < 3) return;
      encode(carry_, out_.reserve(4), 1);
      out_.commit(4);
      pending_ = 0;
    }
    std::size_t triplets = n / 3;
    while (triplets > 0) {
      const std::size_t k = std::min(triplets, Buffered_output::capacity / 4);
      encode(p, out_.reserve(4 * k), k);
      out_.commit(4 * k);
      p += 3 * k;
      n -= 3 * k;
      triplets -= k;
    }
    std::memcpy(carry_, p, n); // n < 3
    pending_ = n;
  }

  void finish() {
    if (pending_ == 0) return;
    char* o = out_.reserve(4);
    const unsigned b0 = carry_[0], b1 = pending_ == 2 ? carry_[1] : 0;
    o[0] = alphabet[b0 >> 2];
    o[1] = alphabet[((b0 & 0x3u) << 4) | (b1 >> 4)];
    o[2] = pending_ == 2 ? alphabet[(b1 & 0xfu) << 2] : '=';
    o[3] = '=';
    out_.commit(4);
    pending_ = 0;
  }

private:
  static constexpr const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

  static void encode(const unsigned char* p, char* o, std::size_t triplets) {
    for (std::size_t t = 0; t < triplets; ++t, p += 3, o += 4) {
      const std::uint32_t v = (std::uint32_t(p[0]) << 16) | (std::uint32_t(p[1]) << 8) | p[2];
      o[0] = alphabet[v >> 18];
      o[1] = alphabet[(v >> 12) & 0x3f];
      o[2] = alphabet[(v >> 6) & 0x3f];
      o[3] = alphabet[v & 0x3f];
    }
  }

  Buffered_output& out_;
  unsigned char carry_[3] = {0, 0, 0};
  std::size_t pending_ = 0;
};

// The name as an XML attribute value.
std::string xml_escaped(const std::string& s) {
  std::string r;
  r.reserve(s.size());
  for (char c : s) {
    switch (c) {
    case '&': r += "&amp;"; break;
    case '<': r += "&lt;"; break;
    case '>': r += "&gt;"; break;
    case '"': r += "&quot;"; break;
    case '\'': r += "&apos;"; break;
    default: r += c;
    }
  }
  return r;
}

// VTK's name of the element type T.
template <class T>
const char* vtk_type_name() {
  if constexpr (std::is_same_v<T, double>) return "Float64";
  else if constexpr (std::is_same_v<T, std::int64_t>) return "Int64";
  else if constexpr (std::is_same_v<T, std::int32_t>) return "Int32";
  else {
    static_assert(std::is_same_v<T, std::uint8_t>, "unsupported VTK type");
    return "UInt8";
  }
}

// Writes DataArrays, in the encoding of the options.
class Data_array_writer {
public:
  Data_array_writer(Buffered_output& out, bool binary) : out_(out), binary_(binary), little_(host_is_little_endian()) {}

  // One DataArray of `n` values of type T (n / components tuples), value i
  // being `get(i)`; in ASCII, `per_line` values a line.
  template <class T, class Get>
  void write(const std::string& name, int components, std::size_t n, std::size_t per_line, Get get) {
    const std::string_view indent = "          ";
    out_.put("        <DataArray type=\"");
    out_.put(vtk_type_name<T>());
    out_.put("\" Name=\"");
    out_.put(xml_escaped(name));
    out_.put("\" NumberOfComponents=\"");
    out_.put(std::to_string(components));
    out_.put(binary_ ? "\" format=\"binary\">\n" : "\" format=\"ascii\">\n");
    if (binary_) {
      out_.put(indent);
      Base64_encoder enc(out_);
      // Uncompressed inline binary: one base64 stream of the byte count
      // (UInt64, the header_type) followed by the values.
      unsigned char header[8];
      store_little_endian<std::uint64_t>(header, std::uint64_t(n) * sizeof(T), little_);
      enc.feed(header, sizeof header);
      constexpr std::size_t chunk = 8192;
      bytes_.resize(chunk * sizeof(T));
      for (std::size_t i0 = 0; i0 < n; i0 += chunk) {
        const std::size_t k = std::min(chunk, n - i0);
        for (std::size_t j = 0; j < k; ++j) store_little_endian<T>(bytes_.data() + j * sizeof(T), get(i0 + j), little_);
        enc.feed(bytes_.data(), k * sizeof(T));
      }
      enc.finish();
      out_.put('\n');
    } else {
      for (std::size_t i = 0; i < n; ++i) {
        if (i % per_line == 0) {
          if (i > 0) out_.put('\n');
          out_.put(indent);
        } else {
          out_.put(' ');
        }
        char* p = out_.reserve(32);
        const T v = get(i);
        std::to_chars_result r;
        if constexpr (std::is_same_v<T, std::uint8_t>) r = std::to_chars(p, p + 32, int(v));
        else r = std::to_chars(p, p + 32, v); // doubles: the shortest form that reads back exactly
        out_.commit(static_cast<std::size_t>(r.ptr - p));
      }
      if (n > 0) out_.put('\n');
    }
    out_.put("        </DataArray>\n");
  }

  // A user's array: Float64, or Int32 if asked.
  void write(const Vtu_array& a) {
    const std::size_t per_line = a.components >= 3 ? static_cast<std::size_t>(a.components) : 6;
    const double* v = a.values.data();
    if (a.integer)
      write<std::int32_t>(a.name, a.components, a.values.size(), per_line,
                          [v](std::size_t i) { return static_cast<std::int32_t>(v[i]); });
    else
      write<double>(a.name, a.components, a.values.size(), per_line, [v](std::size_t i) { return v[i]; });
  }

private:
  Buffered_output& out_;
  bool binary_;
  bool little_;
  std::vector<unsigned char> bytes_;
};

// Checks the arrays of one section ("point" or "cell" data) against the
// element count; `where` is "function: path".
void check_arrays(const std::string& where, const char* section, std::size_t count, const char* elements,
                  const std::vector<Vtu_array>& arrays, bool binary) {
  std::set<std::string> names;
  for (const Vtu_array& a : arrays) {
    const std::string which = std::string(section) + " data array '" + a.name + "'";
    if (a.name.empty()) throw std::invalid_argument(where + ": a " + section + " data array has an empty name");
    for (char c : a.name)
      if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
        throw std::invalid_argument(where + ": " + which + ": the name has a control character");
    if (!names.insert(a.name).second)
      throw std::invalid_argument(where + ": two " + section + " data arrays are named '" + a.name + "'");
    if (a.components < 1)
      throw std::invalid_argument(where + ": " + which + ": " + std::to_string(a.components) +
                                  " components (at least 1 needed)");
    const std::size_t c = static_cast<std::size_t>(a.components);
    if (a.values.size() % c != 0 || a.values.size() / c != count)
      throw std::invalid_argument(where + ": " + which + " has " + std::to_string(a.values.size()) +
                                  " values, expected " + std::to_string(count) + " " + elements + " x " +
                                  std::to_string(c) + " components = " + std::to_string(count * c));
    for (std::size_t i = 0; i < a.values.size(); ++i) {
      const double v = a.values[i];
      if (a.integer && !(v == std::trunc(v) && v >= -2147483648.0 && v <= 2147483647.0)) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.17g", v);
        throw std::invalid_argument(where + ": " + which + " is integer (Int32) but value " + std::to_string(i) +
                                    " is " + buf);
      }
      if (!binary && !std::isfinite(v))
        throw std::invalid_argument(where + ": " + which + ": value " + std::to_string(i) + " is " +
                                    (std::isnan(v) ? "NaN" : "infinite") +
                                    ": VTK does not read non-finite ASCII values reliably; write the file in binary");
    }
  }
}

template <std::size_t N>
void write_vtu_cells(const char* function, const char* element, const char* elements, unsigned char vtk_type,
                     const std::string& path, const std::vector<std::array<double, 3>>& points,
                     const std::vector<std::array<std::size_t, N>>& cells, const std::vector<Vtu_array>& cell_data,
                     const std::vector<Vtu_array>& point_data, const Vtu_options& options) {
  const std::string where = std::string(function) + ": " + path;
  for (std::size_t i = 0; i < points.size(); ++i)
    for (double x : points[i])
      if (!std::isfinite(x))
        throw std::invalid_argument(where + ": point " + std::to_string(i) + " (0-based) has a non-finite coordinate");
  for (std::size_t t = 0; t < cells.size(); ++t)
    for (std::size_t v : cells[t])
      if (v >= points.size())
        throw std::invalid_argument(where + ": " + element + " " + std::to_string(t) + " (0-based): vertex index " +
                                    std::to_string(v) + " is out of range (" + std::to_string(points.size()) +
                                    " points)");
  check_arrays(where, "cell", cells.size(), elements, cell_data, options.binary);
  check_arrays(where, "point", points.size(), "points", point_data, options.binary);

  internal::write_file_atomically(path, [&](std::FILE* f) {
    Buffered_output out(f, path);
    out.put("<?xml version=\"1.0\"?>\n"
            "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
            "header_type=\"UInt64\">\n"
            "  <UnstructuredGrid>\n");
    out.put("    <Piece NumberOfPoints=\"" + std::to_string(points.size()) + "\" NumberOfCells=\"" +
            std::to_string(cells.size()) + "\">\n");
    Data_array_writer w(out, options.binary);
    out.put("      <PointData>\n");
    for (const Vtu_array& a : point_data) w.write(a);
    out.put("      </PointData>\n"
            "      <CellData>\n");
    for (const Vtu_array& a : cell_data) w.write(a);
    out.put("      </CellData>\n"
            "      <Points>\n");
    const auto* p = points.data();
    w.write<double>("Points", 3, 3 * points.size(), 3, [p](std::size_t i) { return p[i / 3][i % 3]; });
    out.put("      </Points>\n"
            "      <Cells>\n");
    const auto* c = cells.data();
    w.write<std::int64_t>("connectivity", 1, N * cells.size(), N,
                          [c](std::size_t i) { return static_cast<std::int64_t>(c[i / N][i % N]); });
    w.write<std::int64_t>("offsets", 1, cells.size(), 10,
                          [](std::size_t i) { return static_cast<std::int64_t>(N * (i + 1)); });
    w.write<std::uint8_t>("types", 1, cells.size(), 20, [vtk_type](std::size_t) { return vtk_type; });
    out.put("      </Cells>\n"
            "    </Piece>\n"
            "  </UnstructuredGrid>\n"
            "</VTKFile>\n");
    out.flush();
  });
}

} // namespace

void write_vtu_tetrahedra(const std::string& path, const std::vector<std::array<double, 3>>& points,
                          const std::vector<std::array<std::size_t, 4>>& tets, const std::vector<Vtu_array>& cell_data,
                          const std::vector<Vtu_array>& point_data, const Vtu_options& options) {
  write_vtu_cells<4>("write_vtu_tetrahedra", "tetrahedron", "tetrahedra", vtk_tetra, path, points, tets, cell_data,
                     point_data, options);
}

void write_vtu_segments(const std::string& path, const std::vector<std::array<double, 3>>& points,
                        const std::vector<std::array<std::size_t, 2>>& segments,
                        const std::vector<Vtu_array>& cell_data, const std::vector<Vtu_array>& point_data,
                        const Vtu_options& options) {
  write_vtu_cells<2>("write_vtu_segments", "segment", "segments", vtk_line, path, points, segments, cell_data,
                     point_data, options);
}

void write_vtu_hexahedra(const std::string& path, const std::vector<std::array<double, 3>>& points,
                         const std::vector<std::array<std::size_t, 8>>& hexahedra,
                         const std::vector<Vtu_array>& cell_data, const std::vector<Vtu_array>& point_data,
                         const Vtu_options& options) {
  write_vtu_cells<8>("write_vtu_hexahedra", "hexahedron", "hexahedra", vtk_hexahedron, path, points, hexahedra,
                     cell_data, point_data, options);
}

} // namespace IO
} // namespace CGAL_ext
