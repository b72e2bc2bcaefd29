// Example: the quality of a hex mesh that HexEx wrote, and the mesh as
// Medit and VTU files.
//
//   hex_mesh_quality_example HEX.ovm HEX_SIZE DOMAIN_VOLUME OUTDIR
//
// 1. read_ovm_hex_mesh() reads the hexahedra (in VTK order) and lists the
//    cells that are not hexahedra.
// 2. hex_mesh_quality() measures them: Verdict's scaled Jacobian (a mesh is
//    valid when every value is positive), the coverage of the domain, and
//    the sizes against hexes of edge HEX_SIZE (the metric I / HEX_SIZE^2).
// 3. write_medit_hex_mesh() writes OUTDIR/hexes.mesh with the boundary
//    quadrilaterals; write_vtu_hexahedra() writes OUTDIR/hexes.vtu with the
//    scaled Jacobian per hexahedron, for ParaView.
// The data: HexEx on the map of `metric-frames generate builtin:box_with_hole
// --hexes --hex-size 0.35`; the domain's volume is 4 minus the 96-gon hole's.
#include <CGAL_ext/Hex_mesh_quality_3.h>
#include <CGAL_ext/IO/Medit_hex_mesh.h>
#include <CGAL_ext/IO/Ovm_file.h>
#include <CGAL_ext/IO/Vtu_file.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>

int main(int argc, char** argv) {
  if (argc != 5) {
    std::cerr << "usage: hex_mesh_quality_example HEX.ovm HEX_SIZE DOMAIN_VOLUME OUTDIR\n";
    return 2;
  }
  const double h = std::atof(argv[2]);
  const std::string out_dir = argv[4];
  CGAL_ext::IO::Ovm_hex_mesh ovm;
  try {
    ovm = CGAL_ext::IO::read_ovm_hex_mesh(argv[1]);
  } catch (const CGAL_ext::Input_error& e) {
    std::cerr << e.what() << '\n';
    return 1;
  }
  for (const auto& c : ovm.other_cells)
    std::printf("polyhedron %zu is not a hexahedron: %s\n", c.cell + 1, c.reason.c_str());

  CGAL_ext::Hex_mesh_quality_options options;
  options.domain_volume = std::atof(argv[3]);
  options.metric = [h](const Eigen::Vector3d&) -> Eigen::Matrix3d { return Eigen::Matrix3d::Identity() / (h * h); };
  const CGAL_ext::Hex_mesh_quality_3 q = CGAL_ext::hex_mesh_quality(ovm.mesh, options);
  std::printf("%zu hexahedra, %zu vertices, %zu boundary quadrilaterals\n", q.hexahedra, q.vertices,
              q.boundary_quadrilaterals);
  std::printf("scaled Jacobian: min %.4f, median %.4f; %zu at most 0, %zu below 0.5\n", q.scaled_jacobian.min,
              q.scaled_jacobian.median, q.scaled_jacobian_at_most_0, q.scaled_jacobian_below_0_5);
  std::printf("coverage of the domain %.4f\n", q.coverage);
  std::printf("size over the size asked for: median %.3f (edges %.3f); %.0f%% of the hexahedra within 0.8-1.25\n",
              q.metric_size.median, q.metric_edge_length.median, 100 * q.metric_sizes_within_25_percent);

  CGAL_ext::Hex_mesh_3 mesh = ovm.mesh;
  mesh.quadrilaterals = CGAL_ext::hex_mesh_boundary_quadrilaterals(mesh.hexahedra);
  std::filesystem::create_directories(out_dir);
  CGAL_ext::IO::write_medit_hex_mesh(out_dir + "/hexes.mesh", mesh);
  std::vector<std::array<double, 3>> points;
  for (const Eigen::Vector3d& p : mesh.points) points.push_back({p.x(), p.y(), p.z()});
  CGAL_ext::IO::write_vtu_hexahedra(out_dir + "/hexes.vtu", points, mesh.hexahedra,
                                    {{"scaled_jacobian", 1, q.scaled_jacobians, false}});
  // A valid mesh: the exit status says so, as a script would check it.
  return q.scaled_jacobian_at_most_0 == 0 ? 0 : 3;
}
