// Example: a structured test mesh without input files. An L-shaped domain
// (a Kuhn grid with a quarter of its cubes left out), its triangulation,
// and a check of what was built.
//
//   kuhn_grid_example
#include <CGAL_ext/Tet_mesh_statistics_3.h>
#include <CGAL_ext/build_triangulation_from_tets.h>
#include <CGAL_ext/make_kuhn_grid.h>

#include <cmath>
#include <iostream>

int main() {
  // 10 x 10 x 10 cubes of side 0.1 from the origin, without those where x and y are both above 0.5.
  const CGAL_ext::IO::Medit_mesh l = CGAL_ext::make_kuhn_grid(
      {10, 10, 10}, 0.1, {0, 0, 0}, [](int i, int j, int) { return i < 5 || j < 5; });
  CGAL_ext::Tet_mesh_triangulation_3<> tr;
  const CGAL_ext::Tet_mesh_build_report report =
      CGAL_ext::build_triangulation_from_tets(l.vertices, l.tetrahedra, l.tetrahedron_references, tr);
  const auto stats = CGAL_ext::compute_tet_mesh_statistics(tr, CGAL_ext::Is_tet_mesh_domain_cell());
  std::cout << "tetrahedra: " << stats.cells << ", vertices: " << stats.vertices
            << ", boundary facets: " << stats.boundary_facets << ", volume: " << double(stats.volume)
            << ", re-oriented: " << report.reoriented_tets << "\n";
  // 750 cubes of 6 tetrahedra; volume 3/4; every tetrahedron given positively oriented.
  const bool ok = stats.cells == 4500 && std::abs(double(stats.volume) - 0.75) < 1e-12 && report.reoriented_tets == 0 &&
                  stats.components == 1;
  return ok ? 0 : 1;
}
