// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#include <CGAL_ext/IO/Medit_tokenizer.h>
#include <CGAL_ext/IO/Perm_file.h>

#include "cubecover_header.h"
#include "write_file_atomically.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <stdexcept>
#include <string_view>
#include <utility>

namespace CGAL_ext {
namespace IO {

namespace {
// Empty if p is a signed permutation of 1, 2, 3; otherwise why not.
std::string signed_permutation_problem(const std::array<int, 3>& p) {
  bool seen[3] = {false, false, false};
  for (int x : p) {
    const int a = std::abs(x);
    if (a < 1 || a > 3) return "entry " + std::to_string(x) + " is not one of +-1, +-2, +-3";
    if (seen[a - 1]) return "vector " + std::to_string(a) + " is the target of two vectors";
    seen[a - 1] = true;
  }
  return {};
}
} // namespace

void write_perm(const std::string& path, const Perm_file& file) {
  std::set<std::pair<std::size_t, std::size_t>> seen; // as read_perm() checks: what it writes reads back
  for (std::size_t k = 0; k < file.faces.size(); ++k) {
    const Perm_face& f = file.faces[k];
    std::string problem = signed_permutation_problem(f.p);
    if (f.tet1 >= file.tets || f.tet2 >= file.tets)
      problem = "tetrahedron index out of range (" + std::to_string(file.tets) + " tetrahedra)";
    else if (f.tet1 == f.tet2)
      problem = "both sides are tetrahedron " + std::to_string(f.tet1);
    else if (!seen.emplace(std::min(f.tet1, f.tet2), std::max(f.tet1, f.tet2)).second)
      problem = "the face between tetrahedra " + std::to_string(f.tet1) + " and " + std::to_string(f.tet2) +
                " is listed twice";
    if (!problem.empty())
      throw std::invalid_argument("write_perm: " + path + ": face " + std::to_string(k) + " (0-based): " + problem);
  }
  internal::write_file_atomically(path, [&](std::FILE* out) {
    std::fprintf(out, "PERM 1\n%zu %zu 3\n", file.tets, file.faces.size());
    for (const Perm_face& f : file.faces)
      std::fprintf(out, "%zu %zu %d %d %d\n", f.tet1, f.tet2, f.p[0], f.p[1], f.p[2]);
  });
}

Perm_file read_perm(const std::string& path) {
  Medit_tokenizer tk(path);
  internal::read_cubecover_header(tk, "PERM", ".perm", "face matching");
  const std::int64_t tets = tk.read_int("the number of tetrahedra");
  if (tets < 0) tk.fail("", "negative number of tetrahedra " + std::to_string(tets));
  const std::int64_t n = tk.read_int("the number of faces");
  if (n < 0) tk.fail("", "negative number of faces " + std::to_string(n));
  const std::int64_t vpf = tk.read_int("the number of vectors per face");
  if (vpf != 3) tk.fail("", std::to_string(vpf) + " vectors per face: only frames of 3 vectors are supported");
  const std::size_t count = static_cast<std::size_t>(n);
  // 5 tokens a face, each taking at least two bytes.
  if (count > tk.remaining_bytes() / 10 + 1)
    tk.fail("", "the count of " + std::to_string(count) + " faces is more than the rest of the file can hold (" +
                    std::to_string(tk.remaining_bytes()) + " bytes): wrong count or truncated file");
  Perm_file out;
  out.tets = static_cast<std::size_t>(tets);
  out.faces.resize(count);
  std::set<std::pair<std::size_t, std::size_t>> seen;
  for (std::size_t k = 0; k < count; ++k) {
    const std::string element = "face " + std::to_string(k + 1);
    Perm_face& f = out.faces[k];
    std::int64_t t[2];
    try {
      t[0] = tk.read_int("a tetrahedron index");
      t[1] = tk.read_int("a tetrahedron index");
      for (int& x : f.p) {
        const std::int64_t v = tk.read_int("a signed vector number");
        if (v < -3 || v > 3 || v == 0) tk.fail(element, "entry " + std::to_string(v) + " is not one of +-1, +-2, +-3");
        x = int(v);
      }
    } catch (const Input_error& e) {
      throw Input_error(path, e.line(), element, e.problem());
    }
    for (int s = 0; s < 2; ++s)
      if (t[s] < 0 || t[s] >= tets)
        tk.fail(element, "tetrahedron index " + std::to_string(t[s]) + " is out of range (0-based, " +
                             std::to_string(tets) + " tetrahedra)");
    if (t[0] == t[1]) tk.fail(element, "both sides are tetrahedron " + std::to_string(t[0]));
    const std::string problem = signed_permutation_problem(f.p);
    if (!problem.empty()) tk.fail(element, problem);
    f.tet1 = static_cast<std::size_t>(t[0]);
    f.tet2 = static_cast<std::size_t>(t[1]);
    if (!seen.emplace(std::min(f.tet1, f.tet2), std::max(f.tet1, f.tet2)).second)
      tk.fail(element, "the face between tetrahedra " + std::to_string(t[0]) + " and " + std::to_string(t[1]) +
                           " is listed twice");
  }
  internal::expect_end_of_records(tk, count, "faces");
  return out;
}

} // namespace IO
} // namespace CGAL_ext
