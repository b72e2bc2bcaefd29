// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_BENCHMARK_RUN_REPORTING_ERRORS_H
#define CGAL_EXT_BENCHMARK_RUN_REPORTING_ERRORS_H

// The main function of a benchmark that reads the user's files: an error
// (an `Input_error` names the file, the line and the problem) is one line on
// stderr and exit code 1, not an abort.

#include <cstdio>
#include <exception>

namespace benchmark_support {

/// Runs `body` and returns its exit code, or prints `name: what` and
/// returns 1 if it throws.
template <class Body>
int run_reporting_errors(const char* name, Body body) {
  try {
    return body();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", name, e.what());
    return 1;
  }
}

} // namespace benchmark_support

#endif // CGAL_EXT_BENCHMARK_RUN_REPORTING_ERRORS_H
