// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Fuzzes the Medit .sol reader: any input gives metrics that are all valid
// (check_metric_tensor() accepts each), or an Input_error naming the file.
#include "fuzz_input.h"

#include <CGAL_ext/IO/Medit_sol.h>
#include <CGAL_ext/Metric_tensor.h>

#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = fuzz::write_input(data, size, ".sol");
  fuzz::expect_input_error_only(
      [&] {
        const auto metrics = CGAL_ext::IO::read_medit_sol(path, CGAL_ext::IO::any_vertex_count);
        for (const Eigen::Matrix3d& g : metrics)
          if (!CGAL_ext::check_metric_tensor(g).empty()) std::abort();
      },
      path);
  return 0;
}
