// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Fuzzes the .ovm reader: any input gives hexahedra of 8 distinct vertices
// in range with finite points, whose quality hex_mesh_quality() measures
// (or refuses as non-manifold with std::invalid_argument), or an
// Input_error naming the file.
#include "fuzz_input.h"

#include <CGAL_ext/Hex_mesh_quality_3.h>
#include <CGAL_ext/IO/Ovm_file.h>

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = fuzz::write_input(data, size, ".ovm");
  fuzz::expect_input_error_only(
      [&] {
        const CGAL_ext::IO::Ovm_hex_mesh r = CGAL_ext::IO::read_ovm_hex_mesh(path);
        for (const auto& p : r.mesh.points)
          if (!p.allFinite()) std::abort();
        for (auto h : r.mesh.hexahedra) {
          std::sort(h.begin(), h.end());
          if (h.back() >= r.mesh.points.size() || std::adjacent_find(h.begin(), h.end()) != h.end()) std::abort();
        }
        try {
          const auto q = CGAL_ext::hex_mesh_quality(r.mesh);
          if (q.hexahedra != r.mesh.hexahedra.size()) std::abort();
        } catch (const std::invalid_argument&) {
          // a face of three or more hexahedra: the mesh is not manifold
        }
      },
      path);
  return 0;
}
