// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#include <CGAL_ext/IO/Medit_tokenizer.h>

#include "input_file.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iterator>
#include <sstream>

namespace CGAL_ext {
namespace IO {

Medit_tokenizer::Medit_tokenizer(std::string path)
    : path_(std::move(path)), data_(internal::read_input_file(path_)) {}

bool Medit_tokenizer::next(std::string_view& token) {
  const std::size_t n = data_.size();
  for (;;) {
    while (pos_ < n && std::isspace(static_cast<unsigned char>(data_[pos_]))) {
      if (data_[pos_] == '\n') ++line_;
      ++pos_;
    }
    if (pos_ < n && data_[pos_] == '#') {
      while (pos_ < n && data_[pos_] != '\n') ++pos_;
      continue;
    }
    break;
  }
  if (pos_ == n) return false;
  const std::size_t start = pos_;
  while (pos_ < n && !std::isspace(static_cast<unsigned char>(data_[pos_])) && data_[pos_] != '#') ++pos_;
  token = std::string_view(data_).substr(start, pos_ - start);
  return true;
}

std::string_view Medit_tokenizer::expect(const char* what) {
  std::string_view t;
  if (!next(t)) fail("", std::string("unexpected end of file: expected ") + what + " (truncated file?)");
  return t;
}

std::int64_t Medit_tokenizer::read_int(const char* what) {
  std::string_view t = expect(what);
  std::string_view s = t;
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (!s.empty() && (s.front() == '+' || s.front() == '-') && s.size() < t.size()) // "+-1"
    fail("", std::string("expected ") + what + ", found " + Input_error::quote(t));
  std::int64_t v = 0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  if (r.ec == std::errc::result_out_of_range)
    fail("", std::string(what) + " " + Input_error::quote(t) + " is out of range");
  if (r.ec != std::errc() || r.ptr != s.data() + s.size())
    fail("", std::string("expected ") + what + ", found " + Input_error::quote(t));
  return v;
}

double Medit_tokenizer::read_double(const char* what) {
  const std::string_view t = expect(what);
  double v = 0;
  if (!internal::parse_double(t, v)) fail("", std::string("expected ") + what + ", found " + Input_error::quote(t));
  if (std::isinf(v) && t.find_first_of("iI") == std::string_view::npos)
    fail("", std::string(what) + " " + Input_error::quote(t) + " overflows a double");
  if (!std::isfinite(v)) fail("", std::string(what) + " is not finite (" + Input_error::quote(t) + ")");
  return v;
}

std::size_t Medit_tokenizer::read_count(const std::string& section, std::size_t tokens_per_record) {
  const std::int64_t c = read_int(("the number of records of " + section).c_str());
  if (c < 0) fail(section, "negative record count " + std::to_string(c));
  const std::size_t count = static_cast<std::size_t>(c);
  // Each token takes at least one character and one separator.
  if (tokens_per_record > 0 && count > remaining_bytes() / (2 * tokens_per_record) + 1)
    fail(section, "the count " + std::to_string(count) + " is more than the rest of the file can hold (" +
                      std::to_string(remaining_bytes()) + " bytes): wrong count or truncated file");
  return count;
}

bool Medit_tokenizer::keyword_equals(std::string_view token, std::string_view keyword) {
  if (token.size() != keyword.size()) return false;
  for (std::size_t i = 0; i < token.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(token[i])) != std::tolower(static_cast<unsigned char>(keyword[i])))
      return false;
  return true;
}

} // namespace IO
} // namespace CGAL_ext
