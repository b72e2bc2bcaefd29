// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Fuzzes the .hexex reader: any input gives a map whose indices are in
// range, whose tetrahedra have 4 distinct vertices and whose values are all
// finite, or an Input_error naming the file.
#include "fuzz_input.h"

#include <CGAL_ext/IO/Hexex_file.h>

#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = fuzz::write_input(data, size, ".hexex");
  fuzz::expect_input_error_only(
      [&] {
        const CGAL_ext::IO::Hexex_file map = CGAL_ext::IO::read_hexex(path);
        if (map.parameters.size() != map.tets.size()) std::abort();
        for (const auto& p : map.positions)
          if (!p.allFinite()) std::abort();
        for (std::size_t t = 0; t < map.tets.size(); ++t) {
          const auto& q = map.tets[t];
          for (std::size_t a = 0; a < 4; ++a) {
            if (q[a] >= map.positions.size() || !map.parameters[t][a].allFinite()) std::abort();
            for (std::size_t b = a + 1; b < 4; ++b)
              if (q[a] == q[b]) std::abort();
          }
        }
      },
      path);
  return 0;
}
