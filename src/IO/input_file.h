// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Internal to the readers that open a path: the check made before opening it,
// and the parsing of a number token.
#ifndef CGAL_EXT_SRC_IO_INPUT_FILE_H
#define CGAL_EXT_SRC_IO_INPUT_FILE_H

#include <CGAL_ext/Input_error.h>

#include <charconv>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>

namespace CGAL_ext::IO::internal {

// Throws an Input_error naming `path` if it is a directory or not a regular
// file (after following links). A directory opens and reads as an empty
// file, /dev/zero or a FIFO would be read until memory runs out, and a FIFO
// without a writer blocks the open: all are refused before opening. A
// missing or unreadable file is left to the open, which reports it.
inline void check_input_file(const std::string& path) {
  std::error_code ec;
  const std::filesystem::file_status s = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(s)) return;
  if (std::filesystem::is_directory(s)) throw Input_error(path, 0, "", "is a directory, not a file");
  if (!std::filesystem::is_regular_file(s))
    throw Input_error(path, 0, "", "is not a regular file (a device, a FIFO or a socket)");
}

// The message for a file that did not open, with the system's reason (right
// after the failed open, while errno holds it).
inline std::string cannot_open_for_reading() {
  return std::string("cannot open the file for reading: ") + std::strerror(errno);
}

// The whole content of a file for a reader: checked first
// (check_input_file), then read in binary; an empty (or all white space)
// file is an error, since no reader can take it.
inline std::string read_input_file(const std::string& path) {
  check_input_file(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Input_error(path, 0, "", cannot_open_for_reading());
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw Input_error(path, 0, "", "read error");
  std::string data = std::move(ss).str();
  if (data.find_first_not_of(" \t\r\n\f\v") == std::string::npos) throw Input_error(path, 0, "", "the file is empty");
  return data;
}

// Parses a whole token as a double (an optional leading `+` accepted) into
// `v`; false if it is not a number. A magnitude beyond the doubles gives an
// infinity, which the callers refuse as not finite; one below them gives 0
// or a subnormal, as strtod (and so MMG's and Gmsh's readers) would: a
// coordinate of 1e-400 is 0 to double precision, not an error.
inline bool parse_double(std::string_view token, double& v) {
  if (!token.empty() && token.front() == '+') {
    token.remove_prefix(1);
    if (!token.empty() && (token.front() == '+' || token.front() == '-')) return false; // "+-1"
  }
  const char* const end = token.data() + token.size();
  const auto r = std::from_chars(token.data(), end, v);
  if (r.ptr != end) return false;
  if (r.ec != std::errc::result_out_of_range) return r.ec == std::errc();
  // Out of the doubles' range: in long double (to 1e+-4932) it rounds to
  // +-inf or to 0 or a subnormal; from_chars, unlike strtod, ignores the
  // locale (a comma-decimal LC_NUMERIC would cut "1.5e-400" to 1).
  long double x = 0;
  const auto rl = std::from_chars(token.data(), end, x);
  if (rl.ptr != end) return false;
  if (rl.ec == std::errc()) {
    v = static_cast<double>(x);
    return true;
  }
  // Beyond even long double: the sign of the exponent tells which way.
  const std::size_t e = token.find_last_of("eE");
  const bool tiny = e != std::string_view::npos && e + 1 < token.size() && token[e + 1] == '-';
  const bool negative = token.front() == '-';
  v = tiny ? (negative ? -0.0 : 0.0) : (negative ? -HUGE_VAL : HUGE_VAL);
  return true;
}

} // namespace CGAL_ext::IO::internal

#endif
