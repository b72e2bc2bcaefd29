// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#include <CGAL_ext/IO/Fra_file.h>
#include <CGAL_ext/IO/Medit_tokenizer.h>

#include "cubecover_header.h"
#include "write_file_atomically.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string_view>

namespace CGAL_ext {
namespace IO {

void write_fra(const std::string& path, const std::vector<std::array<double, 9>>& frames) {
  for (std::size_t t = 0; t < frames.size(); ++t)
    for (double x : frames[t])
      if (!std::isfinite(x))
        throw std::invalid_argument("write_fra: " + path + ": the frame of tetrahedron " + std::to_string(t) +
                                    " (0-based) is not finite");
  internal::write_file_atomically(path, [&](std::FILE* f) {
    // CubeCover's writeFrameField() writes type 1; readFrameField() ignores it.
    std::fprintf(f, "FRA 1\n%zu 3 1\n", frames.size());
    for (const std::array<double, 9>& F : frames)
      for (int k = 0; k < 3; ++k) std::fprintf(f, "%.17g %.17g %.17g\n", F[3 * k], F[3 * k + 1], F[3 * k + 2]);
  });
}

std::vector<std::array<double, 9>> read_fra(const std::string& path) {
  Medit_tokenizer tk(path);
  internal::read_cubecover_header(tk, "FRA", ".fra", "frame field");
  const std::int64_t n = tk.read_int("the number of frames");
  if (n < 0) tk.fail("", "negative number of frames " + std::to_string(n));
  const std::int64_t vpt = tk.read_int("the number of vectors per frame");
  if (vpt != 3) tk.fail("", std::to_string(vpt) + " vectors per frame: only frames of 3 vectors are supported");
  tk.read_int("the frame type");
  const std::size_t count = static_cast<std::size_t>(n);
  // 9 values a frame, each taking at least two bytes: refuse an absurd count
  // before allocating.
  if (count > tk.remaining_bytes() / 18 + 1)
    tk.fail("", "the count of " + std::to_string(count) + " frames is more than the rest of the file can hold (" +
                    std::to_string(tk.remaining_bytes()) + " bytes): wrong count or truncated file");
  std::vector<std::array<double, 9>> frames(count);
  for (std::size_t t = 0; t < count; ++t) {
    try {
      for (double& x : frames[t]) x = tk.read_double("a frame coordinate");
    } catch (const Input_error& e) {
      throw Input_error(path, e.line(), "frame " + std::to_string(t + 1), e.problem());
    }
  }
  internal::expect_end_of_records(tk, count, "frames");
  return frames;
}

} // namespace IO
} // namespace CGAL_ext
