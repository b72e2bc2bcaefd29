// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Fuzzes the Gmsh .msh reader: any input gives a mesh record that
// check_tet_mesh_record() accepts, or an Input_error naming the file.
#include "fuzz_input.h"
#include "tet_mesh_record_checks.h"

#include <CGAL_ext/IO/Gmsh_mesh.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = fuzz::write_input(data, size, ".msh");
  fuzz::expect_input_error_only([&] { fuzz::check_tet_mesh_record(CGAL_ext::IO::read_gmsh_mesh(path)); }, path);
  return 0;
}
