// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#include "point_pairs_file.h"
#include "../IO/input_file.h"

#include <CGAL_ext/Input_error.h>

#include <charconv>
#include <cmath>
#include <fstream>
#include <iostream>
#include <string_view>

namespace CGAL_ext::cli {

std::vector<Point_pair> read_point_pairs(const std::string& path, const char* layout) {
  std::ifstream file;
  std::istream* in = &std::cin;
  if (path != "-") {
    IO::internal::check_input_file(path);
    file.open(path);
    if (!file) throw Input_error(path, 0, "", IO::internal::cannot_open_for_reading());
    in = &file;
  }
  std::vector<Point_pair> pairs;
  std::string line;
  for (std::size_t number = 1; std::getline(*in, line); ++number) {
    std::string_view s(line);
    s = s.substr(0, s.find('#')); // a comment runs to the end of the line
    const auto first = s.find_first_not_of(" \t\r");
    if (first == std::string_view::npos) continue;
    double v[6];
    int n = 0;
    std::size_t pos = first;
    while (pos < s.size()) {
      const auto end = s.find_first_of(" \t\r,", pos);
      std::string_view tok = s.substr(pos, end == std::string_view::npos ? std::string_view::npos : end - pos);
      if (!tok.empty()) {
        if (n == 6) throw Input_error(path, number, "", "more than 6 numbers on the line");
        if (!IO::internal::parse_double(tok, v[n]) || !std::isfinite(v[n]))
          throw Input_error(path, number, "", Input_error::quote(tok) + " is not a finite number");
        ++n;
      }
      if (end == std::string_view::npos) break;
      pos = end + 1;
    }
    if (n != 6) throw Input_error(path, number, "", std::string("expected 6 numbers (") + layout + "), found " + std::to_string(n));
    pairs.push_back({{v[0], v[1], v[2]}, {v[3], v[4], v[5]}, number});
  }
  if (in->bad()) throw Input_error(path, 0, "", "read error");
  return pairs;
}

} // namespace CGAL_ext::cli
