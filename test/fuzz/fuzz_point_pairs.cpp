// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Fuzzes the point-pair reader of `walk --segments` and `transport --pairs`:
// any input gives pairs of finite coordinates on increasing lines, or an
// Input_error naming the file.
#include "fuzz_input.h"

#include "../../src/cli/point_pairs_file.h"

#include <cmath>
#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = fuzz::write_input(data, size, ".txt");
  fuzz::expect_input_error_only(
      [&] {
        std::size_t previous_line = 0;
        for (const CGAL_ext::cli::Point_pair& p : CGAL_ext::cli::read_point_pairs(path, "ax ay az bx by bz")) {
          for (int k = 0; k < 3; ++k)
            if (!std::isfinite(p.a[k]) || !std::isfinite(p.b[k])) std::abort();
          if (p.line <= previous_line) std::abort();
          previous_line = p.line;
        }
      },
      path);
  return 0;
}
