// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Internal to the readers of files that mix text and binary data (Gmsh .msh,
// legacy VTK .vtk): a cursor over the whole file.
#ifndef CGAL_EXT_SRC_IO_TEXT_BINARY_CURSOR_H
#define CGAL_EXT_SRC_IO_TEXT_BINARY_CURSOR_H

#include "input_file.h"

#include <CGAL_ext/Input_error.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

namespace CGAL_ext::IO::internal {

// The file's bytes, read as whitespace-separated tokens (ASCII parts) or as
// binary values, little-endian (Gmsh) or big-endian (legacy VTK). Errors name the line while the data
// is text, the byte offset once binary data has started.
class Text_binary_cursor {
public:
  explicit Text_binary_cursor(std::string path) : path_(std::move(path)), data_(internal::read_input_file(path_)) {}

  const std::string& path() const { return path_; }
  std::size_t line() const { return binary_ ? 0 : line_; }
  std::size_t remaining() const { return data_.size() - pos_; }
  void start_binary() { binary_ = true; }
  void set_big_endian(bool big) { big_endian_ = big; }

  [[noreturn]] void fail(const std::string& element, const std::string& problem) const { fail_at(line(), element, problem); }
  // At a given line: an element's first line, when reading it went further.
  [[noreturn]] void fail_at(std::size_t line, const std::string& element, const std::string& problem) const {
    throw Input_error(path_, binary_ ? 0 : line, element,
                      binary_ ? problem + " (at byte " + std::to_string(pos_) + ")" : problem);
  }

  bool next(std::string_view& token) {
    while (pos_ < data_.size() && std::isspace(static_cast<unsigned char>(data_[pos_]))) {
      if (data_[pos_] == '\n') ++line_;
      ++pos_;
    }
    if (pos_ == data_.size()) return false;
    const std::size_t start = pos_;
    while (pos_ < data_.size() && !std::isspace(static_cast<unsigned char>(data_[pos_]))) ++pos_;
    token = std::string_view(data_).substr(start, pos_ - start);
    return true;
  }

  std::string_view token(const char* what) {
    std::string_view t;
    if (!next(t)) fail("", std::string("unexpected end of file, expected ") + what);
    return t;
  }

  std::int64_t integer(const char* what) {
    const std::string_view t = token(what);
    std::int64_t v = 0;
    const auto r = std::from_chars(t.data(), t.data() + t.size(), v);
    if (r.ec != std::errc() || r.ptr != t.data() + t.size())
      fail("", std::string("expected ") + what + " (an integer), found " + Input_error::quote(t));
    return v;
  }

  double number(const char* what) {
    const std::string_view t = token(what);
    double v = 0;
    if (!internal::parse_double(t, v)) fail("", std::string("expected ") + what + ", found " + Input_error::quote(t));
    if (!std::isfinite(v)) fail("", std::string(what) + " " + Input_error::quote(t) + " is not finite");
    return v;
  }

  // A value of N bytes in the file's byte order, as an unsigned integer.
  template <std::size_t N>
  std::uint64_t raw(const char* what) {
    if (remaining() < N) fail("", std::string("unexpected end of file, expected ") + what);
    std::uint64_t v = 0;
    for (std::size_t i = 0; i < N; ++i) {
      const std::size_t shift = 8 * (big_endian_ ? N - 1 - i : i);
      v |= std::uint64_t(static_cast<unsigned char>(data_[pos_ + i])) << shift;
    }
    pos_ += N;
    return v;
  }
  std::int64_t int32(const char* what) { return static_cast<std::int32_t>(static_cast<std::uint32_t>(raw<4>(what))); }
  std::uint64_t size(const char* what) { return raw<8>(what); }
  double real(const char* what) {
    const std::uint64_t bits = raw<8>(what);
    double v;
    std::memcpy(&v, &bits, 8);
    if (!std::isfinite(v)) fail("", std::string(what) + " is not finite");
    return v;
  }

  void skip_bytes(std::size_t n, const char* what) {
    if (remaining() < n) fail("", std::string("unexpected end of file in ") + what);
    pos_ += n;
  }

  double real32(const char* what) {
    const auto bits = static_cast<std::uint32_t>(raw<4>(what));
    float v;
    std::memcpy(&v, &bits, 4);
    if (!std::isfinite(v)) fail("", std::string(what) + " is not finite");
    return double(v);
  }

  // Skips to the end of the next empty line (the end of a VTK METADATA block).
  void skip_past_empty_line() {
    for (bool blank = false; pos_ < data_.size(); ++pos_) {
      if (data_[pos_] == '\n') {
        ++line_;
        if (blank) {
          ++pos_;
          return;
        }
        blank = true;
      } else if (data_[pos_] != '\r' && data_[pos_] != ' ' && data_[pos_] != '\t') {
        blank = false;
      }
    }
  }

  // Binary data starts after the end of the current line.
  void skip_line_end() {
    while (pos_ < data_.size() && data_[pos_] != '\n') ++pos_;
    if (pos_ == data_.size()) fail("", "unexpected end of file before binary data");
    ++pos_;
    ++line_;
  }

  // Skips an unknown section: to the token after `$End<name>`.
  void skip_section(std::string_view name) {
    const std::string end = "$End" + std::string(name.substr(1));
    std::size_t at = pos_;
    for (;;) {
      at = data_.find(end, at);
      if (at == std::string::npos) fail("", "section " + Input_error::quote(name) + " has no " + Input_error::quote(end));
      const bool starts = at == 0 || data_[at - 1] == '\n' || data_[at - 1] == '\r';
      if (starts) break;
      at += end.size();
    }
    for (; pos_ < at; ++pos_)
      if (data_[pos_] == '\n') ++line_;
    pos_ += end.size();
  }

  static bool equal_ignoring_case(std::string_view a, std::string_view b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
             return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
           });
  }

  void expect(std::string_view keyword) {
    const std::string_view t = token(std::string(keyword).c_str());
    if (t != keyword) fail("", "expected " + std::string(keyword) + ", found " + Input_error::quote(t));
  }

private:
  std::string path_, data_;
  std::size_t pos_ = 0, line_ = 1;
  bool binary_ = false, big_endian_ = false;
};

} // namespace CGAL_ext::IO::internal

#endif
