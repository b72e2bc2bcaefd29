// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Prints what read_ovm_hex_mesh() and hex_mesh_quality() give for an .ovm
// file, for test/compare_hex_mesh_quality.py, which checks it against
// scripts/hex_mesh_quality.py (an independent implementation in Python):
//   hex_mesh_quality_dump HEX.ovm HEX_SIZE
// One line per hexahedron: "hex <8 vertices> <sj> <corners> <degenerate> <volume>",
// one per other cell: "other <0-based cell> <reason>", then "summary <name> <value>" lines.
#include <CGAL_ext/Hex_mesh_quality_3.h>
#include <CGAL_ext/IO/Ovm_file.h>

#include <cstdio>
#include <cstdlib>
#include <exception>

namespace {

void print_summary(const char* name, const CGAL_ext::Hex_quality_summary& s) {
  std::printf("summary %s.count %zu\n", name, s.count);
  std::printf("summary %s.min %.17g\nsummary %s.median %.17g\n", name, s.min, name, s.median);
  std::printf("summary %s.mean %.17g\nsummary %s.max %.17g\n", name, s.mean, name, s.max);
}

} // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: hex_mesh_quality_dump HEX.ovm HEX_SIZE\n");
    return 2;
  }
  try {
    const auto ovm = CGAL_ext::IO::read_ovm_hex_mesh(argv[1]);
    const double h = std::atof(argv[2]);
    CGAL_ext::Hex_mesh_quality_options options;
    options.metric = [h](const Eigen::Vector3d&) -> Eigen::Matrix3d { return Eigen::Matrix3d::Identity() / (h * h); };
    const auto q = CGAL_ext::hex_mesh_quality(ovm.mesh, options);
    for (std::size_t i = 0; i < ovm.mesh.hexahedra.size(); ++i) {
      std::array<Eigen::Vector3d, 8> p;
      std::printf("hex");
      for (std::size_t k = 0; k < 8; ++k) {
        p[k] = ovm.mesh.points[ovm.mesh.hexahedra[i][k]];
        std::printf(" %zu", ovm.mesh.hexahedra[i][k]);
      }
      const auto sj = CGAL_ext::hex_scaled_jacobian(p);
      std::printf(" %.17g %.17g %d %.17g\n", sj.value, sj.corners, int(sj.degenerate), CGAL_ext::hex_volume(p));
    }
    for (const auto& c : ovm.other_cells) std::printf("other %zu %s\n", c.cell, c.reason.c_str());
    std::printf("summary vertices %zu\nsummary volume %.17g\nsummary negative_volume_hexes %zu\n", q.vertices,
                q.volume, q.negative_volume_hexes);
    std::printf("summary scaled_jacobian_at_most_0 %zu\nsummary scaled_jacobian_below_0_2 %zu\n",
                q.scaled_jacobian_at_most_0, q.scaled_jacobian_below_0_2);
    std::printf("summary scaled_jacobian_below_0_5 %zu\nsummary degenerate %zu\n", q.scaled_jacobian_below_0_5,
                q.degenerate);
    std::printf("summary boundary_quadrilaterals %zu\nsummary boundary_edge_rms %.17g\n", q.boundary_quadrilaterals,
                q.boundary_edge_rms);
    std::printf("summary metric_sizes_within_25_percent %.17g\n", q.metric_sizes_within_25_percent);
    print_summary("scaled_jacobian", q.scaled_jacobian);
    print_summary("scaled_jacobian_corners", q.scaled_jacobian_corners);
    print_summary("edge_length", q.edge_length);
    print_summary("metric_size", q.metric_size);
    print_summary("metric_edge_length", q.metric_edge_length);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hex_mesh_quality_dump: %s\n", e.what());
    return 1;
  }
  return 0;
}
