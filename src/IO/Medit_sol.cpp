// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#include <CGAL_ext/IO/Medit_sol.h>
#include <CGAL_ext/IO/Medit_tokenizer.h>
#include <CGAL_ext/Metric_tensor.h>

#include "write_file_atomically.h"

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string_view>

namespace CGAL_ext {
namespace IO {

namespace {

// Number of values of one field of a Medit solution type in 3D:
// 1 scalar, 2 vector, 3 symmetric tensor, 4 full tensor; 0 if unknown.
std::size_t values_per_type(std::int64_t type) {
  switch (type) {
  case 1: return 1;
  case 2: return 3;
  case 3: return 6;
  case 4: return 9;
  default: return 0;
  }
}

bool starts_with_sol_at(std::string_view kw) {
  return kw.size() > 5 && Medit_tokenizer::keyword_equals(kw.substr(0, 5), "SolAt");
}

// Checks that `count` records of `tokens` tokens fit in the rest of the file
// (a token takes at least two bytes), before anything is allocated.
void check_count_fits(const Medit_tokenizer& tk, const std::string& section, std::size_t count, std::size_t tokens) {
  if (tokens > 0 && count > tk.remaining_bytes() / (2 * tokens) + 1)
    tk.fail(section, "the count " + std::to_string(count) + " is more than the rest of the file can hold (" +
                         std::to_string(tk.remaining_bytes()) + " bytes): wrong count or truncated file");
}

// The header of a SolAt... section after its keyword: the record count, the
// number of fields, the tokens per record and the type of the last field.
struct Solution_header {
  std::size_t count;
  std::int64_t fields;
  std::size_t tokens;
  std::int64_t type;
};

Solution_header read_solution_header(Medit_tokenizer& tk, const std::string& section) {
  const std::int64_t c = tk.read_int(("the number of records of " + section).c_str());
  if (c < 0) tk.fail(section, "negative record count " + std::to_string(c));
  Solution_header h{static_cast<std::size_t>(c), tk.read_int("the number of solution fields"), 0, 0};
  if (h.fields <= 0 || h.fields > 64) tk.fail(section, "invalid number of solution fields " + std::to_string(h.fields));
  for (std::int64_t f = 0; f < h.fields; ++f) {
    h.type = tk.read_int("a solution field type");
    const std::size_t n = values_per_type(h.type);
    if (n == 0) tk.fail(section, "unknown solution field type " + std::to_string(h.type));
    h.tokens += n;
  }
  check_count_fits(tk, section, h.count, h.tokens);
  return h;
}

// The metric of vertex i (0-based): a size h (type 1, g = I / h^2) or the
// lower triangle of a tensor (type 3), checked; errors name the vertex.
Eigen::Matrix3d read_vertex_metric(Medit_tokenizer& tk, const std::string& path, std::size_t i, std::int64_t type) {
  const std::string element = "vertex " + std::to_string(i + 1);
  std::size_t line = 0;
  Eigen::Matrix3d g;
  try {
    if (type == 1) {
      const double h = tk.read_double("a size");
      line = tk.line();
      // A size too small or too large would pass as a tensor that is
      // "not finite" or "zero" below: name the size instead.
      const std::string problem = !(h > 0) ? "is not positive" : check_metric_size(h);
      if (!problem.empty()) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "size h = %.17g ", h);
        throw Input_error(path, line, element, buf + problem);
      }
      g = Eigen::Matrix3d::Identity() / (h * h);
    } else {
      double m[6];
      for (int k = 0; k < 6; ++k) {
        m[k] = tk.read_double("a metric coefficient");
        if (k == 0) line = tk.line();
      }
      // Lower triangle by rows: m11 m21 m22 m31 m32 m33.
      g << m[0], m[1], m[3], m[1], m[2], m[4], m[3], m[4], m[5];
    }
  } catch (const Input_error& e) {
    if (!e.element().empty()) throw;
    throw Input_error(path, e.line(), element, e.problem());
  }
  const std::string why = check_metric_tensor(g);
  if (!why.empty()) throw Input_error(path, line, element, why);
  return g;
}

} // namespace

std::vector<Eigen::Matrix3d> read_medit_sol(const std::string& path, std::size_t expected_vertex_count) {
  Medit_tokenizer tk(path);
  std::vector<Eigen::Matrix3d> metrics;
  bool have_solution = false;
  std::string_view kw;
  while (tk.next(kw)) {
    if (Medit_tokenizer::keyword_equals(kw, "MeshVersionFormatted")) {
      const auto v = tk.read_int("the MeshVersionFormatted value");
      if (v < 1 || v > 4) tk.fail("", "unsupported MeshVersionFormatted " + std::to_string(v));
    } else if (Medit_tokenizer::keyword_equals(kw, "Dimension")) {
      const auto d = tk.read_int("the Dimension value");
      if (d != 3) tk.fail("", "Dimension " + std::to_string(d) + ": only 3D metrics are supported");
    } else if (starts_with_sol_at(kw)) {
      const std::string section(kw);
      const bool at_vertices = Medit_tokenizer::keyword_equals(kw, "SolAtVertices");
      if (at_vertices && have_solution) tk.fail("", "a second SolAtVertices section");
      const auto [count, nfields, tokens, type] = read_solution_header(tk, section);
      if (!at_vertices) { // skip the records of a section we do not use
        for (std::size_t i = 0; i < count * tokens; ++i) tk.expect(("a record of " + section).c_str());
        continue;
      }
      if (nfields != 1)
        tk.fail(section, std::to_string(nfields) +
                             " solution fields: only one metric field (type 1, scalar size, or type 3, "
                             "symmetric tensor) is supported");
      if (type != 1 && type != 3)
        tk.fail(section, "solution field type " + std::to_string(type) + (type == 2 ? " (vector)" : " (full tensor)") +
                             " is not a metric: only types 1 (scalar size) and 3 (symmetric tensor) are supported");
      if (expected_vertex_count != any_vertex_count && count != expected_vertex_count)
        tk.fail(section, "the file has " + std::to_string(count) + " vertex metrics but the mesh has " +
                             std::to_string(expected_vertex_count) + " vertices");
      metrics.resize(count);
      for (std::size_t i = 0; i < count; ++i) metrics[i] = read_vertex_metric(tk, path, i, type);
      have_solution = true;
    } else if (Medit_tokenizer::keyword_equals(kw, "End")) {
      break;
    } else {
      const bool numeric =
          !kw.empty() && (std::isdigit(static_cast<unsigned char>(kw[0])) || kw[0] == '-' || kw[0] == '+' || kw[0] == '.');
      tk.fail("", numeric ? "unexpected number " + Input_error::quote(kw) +
                                " where a keyword was expected (more records than the count says?)"
                          : "unknown keyword " + Input_error::quote(kw));
    }
  }
  if (!have_solution) throw Input_error(path, 0, "", "no SolAtVertices section");
  return metrics;
}

void write_medit_sol(const std::string& path, const std::vector<Eigen::Matrix3d>& metrics) {
  for (std::size_t i = 0; i < metrics.size(); ++i)
    if (!metrics[i].allFinite())
      throw std::invalid_argument("write_medit_sol: the metric of vertex " + std::to_string(i + 1) + " is not finite");
  internal::write_file_atomically(path, [&](std::FILE* f) {
    std::fprintf(f, "MeshVersionFormatted 2\n\nDimension 3\n\nSolAtVertices\n%zu\n1 3\n", metrics.size());
    for (const Eigen::Matrix3d& g : metrics)
      std::fprintf(f, "%.17g %.17g %.17g %.17g %.17g %.17g\n", g(0, 0), g(1, 0), g(1, 1), g(2, 0), g(2, 1), g(2, 2));
    std::fprintf(f, "\nEnd\n");
  });
}

} // namespace IO
} // namespace CGAL_ext
