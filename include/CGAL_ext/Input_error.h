// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_INPUT_ERROR_H
#define CGAL_EXT_INPUT_ERROR_H

/// \file Input_error.h
/// The one exception type for bad user input (files, indices, values).

#include <cstddef>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <string_view>

namespace CGAL_ext {

/// \ingroup PkgCGALExtIO
/// Thrown for every defect of user input: a malformed or truncated file, an
/// index out of range, a NaN, a degenerate tetrahedron, a non-SPD metric...
///
/// `what()` is a complete, human-readable message of the form
/// `FILE:LINE: element: problem` (parts that are unknown are left out),
/// so that a command-line tool can print it as it is. Control characters
/// in it are written `\xHH`: `what()` is one line, and a NUL byte from a
/// file cannot cut it short.
class Input_error : public std::runtime_error {
public:
  /// \param file the file the input came from (empty for in-memory input)
  /// \param line 1-based line number in `file`, 0 when not applicable
  /// \param element the element concerned, e.g. "tetrahedron 17" (may be empty)
  /// \param problem what is wrong
  Input_error(std::string file, std::size_t line, std::string element, std::string problem)
      : std::runtime_error(compose(file, line, element, problem)),
        file_(std::move(file)), line_(line), element_(std::move(element)), problem_(std::move(problem)) {}

  /// The file name, or empty.
  /// \returns the file name as given to the constructor (unlike `what()`, not escaped)
  const std::string& file() const noexcept { return file_; }
  /// The 1-based line number, or 0.
  /// \returns the line in `file()`, from 1; 0 when not applicable
  std::size_t line() const noexcept { return line_; }
  /// The element concerned, or empty.
  /// \returns the element as given to the constructor (unlike `what()`, not escaped)
  const std::string& element() const noexcept { return element_; }
  /// The problem alone, without location.
  /// \returns the problem as given to the constructor (unlike `what()`, not escaped)
  const std::string& problem() const noexcept { return problem_; }

  /// Longest part of a token that `quote()` shows.
  static constexpr std::size_t quoted_token_length = 40;

  /// A token of an input file as messages show it: in single quotes, with
  /// bytes that are not printable ASCII written `\xHH`, and cut after
  /// `quoted_token_length` characters, then followed by its length, so that
  /// a 10 MB token gives a short message, e.g.
  /// ``'1111111111111111111111111111111111111111...' (10000000 characters)``.
  /// \param token the token, as read
  /// \returns the quoted token, with its length if it was cut
  static std::string quote(std::string_view token) {
    std::string s = "'" + escaped(token.substr(0, quoted_token_length), true) + "'";
    if (token.size() > quoted_token_length)
      s.insert(s.size() - 1, "...").append(" (" + std::to_string(token.size()) + " characters)");
    return s;
  }

private:
  // `s` with control characters, and with `non_ascii` every byte outside
  // printable ASCII, written \xHH.
  static std::string escaped(std::string_view s, bool non_ascii) {
    std::string out;
    out.reserve(s.size());
    for (const char ch : s) {
      const unsigned char c = static_cast<unsigned char>(ch);
      if (c < 0x20 || c == 0x7f || (non_ascii && c > 0x7f)) {
        char buf[5];
        std::snprintf(buf, sizeof buf, "\\x%02x", c);
        out += buf;
      } else {
        out += ch;
      }
    }
    return out;
  }

  static std::string compose(const std::string& file, std::size_t line, const std::string& element,
                             const std::string& problem) {
    std::string s;
    if (!file.empty()) s += file;
    if (line > 0) s += (s.empty() ? "line " : ":") + std::to_string(line);
    if (!s.empty()) s += ": ";
    if (!element.empty()) s += element + ": ";
    return escaped(s + problem, false); // UTF-8 file names stay readable
  }

  std::string file_;
  std::size_t line_;
  std::string element_;
  std::string problem_;
};

/// \ingroup PkgCGALExtIO
/// A number as messages and progress lines write it: `%.*g`, short.
/// \param x the number
/// \param significant_digits the significant digits (4 for figures, 6 for parameters)
/// \returns `x` printed with `%.*g`, e.g. `0.0994` or `1.235e+06`
inline std::string format_number(double x, int significant_digits = 4) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.*g", significant_digits, x);
  return buf;
}

} // namespace CGAL_ext

#endif // CGAL_EXT_INPUT_ERROR_H
