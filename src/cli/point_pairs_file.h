// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The input of `walk --segments` and `transport --pairs`: one pair of points
// per line, `ax ay az bx by bz`.
#ifndef CGAL_EXT_CLI_POINT_PAIRS_FILE_H
#define CGAL_EXT_CLI_POINT_PAIRS_FILE_H

#include <array>
#include <string>
#include <vector>

namespace CGAL_ext::cli {

/// One line of a point-pair file: the two points and the line number.
struct Point_pair {
  std::array<double, 3> a, b;
  std::size_t line;
};

/// Reads a file of lines of 6 finite numbers. A `#` starts a comment that
/// runs to the end of the line; blank lines are skipped. Throws Input_error
/// naming the file and line for anything else (too few or too many numbers,
/// a word, NaN or Inf); "-" reads standard input.
/// \param path the file, or "-"
/// \param layout the names of the 6 numbers, for messages (e.g. "qx qy qz px py pz")
std::vector<Point_pair> read_point_pairs(const std::string& path, const char* layout);

} // namespace CGAL_ext::cli

#endif
