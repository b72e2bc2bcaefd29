// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Fuzzes the Medit .mesh reader and the triangulation built from its
// tetrahedra (read_tet_mesh): any input must give a triangulation that
// passes CGAL's validity check, or an Input_error naming the file.
#include "fuzz_input.h"

#include <CGAL_ext/IO/read_tet_mesh.h>

#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = fuzz::write_input(data, size, ".mesh");
  fuzz::expect_input_error_only(
      [&] {
        CGAL_ext::Tet_mesh_triangulation_3<> tr;
        CGAL_ext::IO::Medit_mesh mesh;
        const CGAL_ext::Tet_mesh_build_report report = CGAL_ext::IO::read_tet_mesh(path, tr, &mesh);
        // Every tetrahedron of the file is a cell of the triangulation, and
        // the triangulation is combinatorially and geometrically valid.
        if (tr.number_of_finite_cells() < mesh.tetrahedra.size() || !tr.is_valid()) std::abort();
        (void)report;
      },
      path);
  return 0;
}
