// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#include <CGAL_ext/IO/Hexex_file.h>
#include <CGAL_ext/IO/Medit_tokenizer.h>

#include "cubecover_header.h"
#include "write_file_atomically.h"

#include <cstdint>
#include <cstdio>
#include <stdexcept>

namespace CGAL_ext {
namespace IO {

void write_hexex(const std::string& path, const Hexex_file& map) {
  auto fail = [&](const std::string& what) { throw std::invalid_argument("write_hexex: " + path + ": " + what); };
  if (map.parameters.size() != map.tets.size()) fail("one set of parameters per tetrahedron is needed");
  for (std::size_t v = 0; v < map.positions.size(); ++v)
    if (!map.positions[v].allFinite()) fail("vertex " + std::to_string(v + 1) + " is not finite");
  for (std::size_t t = 0; t < map.tets.size(); ++t) {
    const auto& q = map.tets[t];
    for (std::size_t v : q)
      if (v >= map.positions.size()) fail("tetrahedron " + std::to_string(t + 1) + " has a vertex out of range");
    for (std::size_t a = 0; a < 4; ++a)
      for (std::size_t b = a + 1; b < 4; ++b)
        if (q[a] == q[b]) fail("tetrahedron " + std::to_string(t + 1) + " has a repeated vertex, which no reader accepts");
    for (const Eigen::Vector3d& u : map.parameters[t])
      if (!u.allFinite()) fail("the parameters of tetrahedron " + std::to_string(t + 1) + " are not finite");
  }
  internal::write_file_atomically(path, [&](std::FILE* f) {
    std::fprintf(f, "%zu\n", map.positions.size());
    for (const Eigen::Vector3d& p : map.positions) std::fprintf(f, "%.17g %.17g %.17g\n", p.x(), p.y(), p.z());
    std::fprintf(f, "%zu\n", map.tets.size());
    for (std::size_t t = 0; t < map.tets.size(); ++t) {
      const auto& q = map.tets[t];
      std::fprintf(f, "%zu %zu %zu %zu", q[0], q[1], q[2], q[3]);
      for (const Eigen::Vector3d& u : map.parameters[t]) std::fprintf(f, " %.17g %.17g %.17g", u.x(), u.y(), u.z());
      std::fputc('\n', f);
    }
  });
}

Hexex_file read_hexex(const std::string& path) {
  Medit_tokenizer tk(path);
  Hexex_file map;
  map.positions.resize(tk.read_count("vertices", 3));
  for (std::size_t v = 0; v < map.positions.size(); ++v) {
    try {
      for (int k = 0; k < 3; ++k) map.positions[v][k] = tk.read_double("a vertex coordinate");
    } catch (const Input_error& e) {
      throw Input_error(path, e.line(), "vertex " + std::to_string(v + 1), e.problem());
    }
  }
  const std::size_t n = tk.read_count("tetrahedra", 16);
  map.tets.resize(n);
  map.parameters.resize(n);
  for (std::size_t t = 0; t < n; ++t) {
    const std::string element = "tetrahedron " + std::to_string(t + 1);
    try {
      for (std::size_t& v : map.tets[t]) {
        const std::int64_t i = tk.read_int("a vertex index");
        if (i < 0 || std::uint64_t(i) >= map.positions.size())
          tk.fail(element, "vertex index " + std::to_string(i) + " is out of range (0-based, " +
                               std::to_string(map.positions.size()) + " vertices)");
        v = std::size_t(i);
      }
      for (Eigen::Vector3d& u : map.parameters[t])
        for (int k = 0; k < 3; ++k) u[k] = tk.read_double("a parameter");
    } catch (const Input_error& e) {
      throw Input_error(path, e.line(), element, e.problem());
    }
    const auto& q = map.tets[t];
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b)
        if (q[std::size_t(a)] == q[std::size_t(b)])
          throw Input_error(path, tk.line(), element, "vertex " + std::to_string(q[std::size_t(a)]) + " appears twice");
  }
  internal::expect_end_of_records(tk, n, "tetrahedra");
  return map;
}

} // namespace IO
} // namespace CGAL_ext
