// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_INPUT_ERROR_H
#define CGAL_EXT_INPUT_ERROR_H

/// \file Input_error.h
/// The one exception type for bad user input (files, indices, values).

#include <cstddef>
#include <stdexcept>
#include <string>

namespace CGAL_ext {

/// \ingroup PkgCGALExtIO
/// Thrown for every defect of user input: a malformed or truncated file, an
/// index out of range, a NaN, a degenerate tetrahedron, a non-SPD metric...
///
/// `what()` is a complete, human-readable message of the form
/// `FILE:LINE: element: problem` (parts that are unknown are left out),
/// so that a command-line tool can print it as it is.
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
  const std::string& file() const noexcept { return file_; }
  /// The 1-based line number, or 0.
  std::size_t line() const noexcept { return line_; }
  /// The element concerned, or empty.
  const std::string& element() const noexcept { return element_; }
  /// The problem alone, without location.
  const std::string& problem() const noexcept { return problem_; }

private:
  static std::string compose(const std::string& file, std::size_t line, const std::string& element,
                             const std::string& problem) {
    std::string s;
    if (!file.empty()) s += file;
    if (line > 0) s += (s.empty() ? "line " : ":") + std::to_string(line);
    if (!s.empty()) s += ": ";
    if (!element.empty()) s += element + ": ";
    return s + problem;
  }

  std::string file_;
  std::size_t line_;
  std::string element_;
  std::string problem_;
};

} // namespace CGAL_ext

#endif // CGAL_EXT_INPUT_ERROR_H
