// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Fuzzes the surface reader that `generate SURFACE` meshes from (OFF, OBJ,
// STL and PLY through CGAL's readers, then soup repair, orientation and the
// closedness and self-intersection checks). The first byte picks the format.
// Any input gives a closed triangle mesh that bounds a volume, or an
// Input_error naming the file.
#include "fuzz_input.h"

#include "../../src/meshing/read_closed_surface.h"

#include <CGAL/Polygon_mesh_processing/orientation.h>

#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static const char* const extensions[] = {".off", ".obj", ".stl", ".ply"};
  const std::string path = fuzz::write_input(data + 1, size - 1, extensions[data[0] % 4]);
  fuzz::expect_input_error_only(
      [&] {
        std::vector<std::string> repairs;
        const CGAL_ext::internal::Closed_surface s = CGAL_ext::internal::read_closed_surface(path, repairs);
        if (!CGAL::is_closed(s) || !CGAL::is_triangle_mesh(s) ||
            !CGAL::Polygon_mesh_processing::does_bound_a_volume(s))
          std::abort();
      },
      path);
  return 0;
}
