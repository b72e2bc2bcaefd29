// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// JSON lines on stdout, written with nlohmann-json, for the subcommands that
// print JSON (info --json, walk, transport).
#ifndef CGAL_EXT_CLI_JSON_OUTPUT_H
#define CGAL_EXT_CLI_JSON_OUTPUT_H

#include <nlohmann/json.hpp>

#include <cstdio>
#include <string>

namespace CGAL_ext::cli {

/// JSON objects with their keys in the order they were written (the documented order).
using Json = nlohmann::ordered_json;

/// Prints `value` as one line of compact JSON on stdout. Bytes of its strings
/// that are not valid UTF-8 (a Latin-1 file name) are written as U+FFFD.
inline void print_json_line(const Json& value) {
  const std::string line = value.dump(-1, ' ', false, Json::error_handler_t::replace) + "\n";
  std::fputs(line.c_str(), stdout);
}

} // namespace CGAL_ext::cli

#endif
