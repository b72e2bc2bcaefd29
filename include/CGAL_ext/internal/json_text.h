// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_INTERNAL_JSON_TEXT_H
#define CGAL_EXT_INTERNAL_JSON_TEXT_H

// The pieces of JSON text our writers share: escaped strings and numbers.

#include <CGAL_ext/Input_error.h>

#include <cmath>
#include <cstdio>
#include <string>

namespace CGAL_ext::internal {

/// The JSON string-literal body of `s` (quotes, backslashes and control characters escaped).
inline std::string json_escape(const std::string& s) {
  std::string out;
  for (char ch : s) {
    if (ch == '"' || ch == '\\') out += '\\';
    if (static_cast<unsigned char>(ch) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", ch);
      out += buf;
    } else {
      out += ch;
    }
  }
  return out;
}

/// A JSON number with 10 significant digits; `null` if `x` is not finite.
inline std::string json_number(double x) { return std::isfinite(x) ? format_number(x, 10) : "null"; }

} // namespace CGAL_ext::internal

#endif
