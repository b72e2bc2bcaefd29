// Example: read a Medit mesh into a CGAL triangulation and inspect its domain.
//
//   read_mesh_example MESH
//
// Prints the number of tetrahedra, the boundary facets, and for the first
// boundary facet the file indices of its vertices.
#include <CGAL_ext/IO/read_tet_mesh.h>
#include <CGAL_ext/Tet_mesh_statistics_3.h>

#include <iostream>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: read_mesh_example MESH\n";
    return 2;
  }
  using Tr = CGAL_ext::Tet_mesh_triangulation_3<>;
  Tr tr;
  try {
    const CGAL_ext::Tet_mesh_build_report report = CGAL_ext::IO::read_tet_mesh(argv[1], tr);
    std::cout << "re-oriented tetrahedra: " << report.reoriented_tets << "\n";
  } catch (const CGAL_ext::Input_error& e) {
    std::cerr << e.what() << "\n"; // "FILE:LINE: element: problem"
    return 1;
  }
  // Domain cells carry their tetrahedron index; the infinite cells close the boundary.
  const CGAL_ext::Is_tet_mesh_domain_cell in_domain;
  const auto stats = CGAL_ext::compute_tet_mesh_statistics(tr, in_domain);
  std::cout << "tetrahedra: " << stats.cells << ", components: " << stats.components << "\n";
  for (Tr::Cell_handle c : tr.finite_cell_handles())
    for (int i = 0; i < 4; ++i)
      if (!in_domain(c->neighbor(i))) {
        std::cout << "first boundary facet: tetrahedron " << c->info().index << ", vertices";
        for (int k = 1; k < 4; ++k) std::cout << " " << c->vertex((i + k) % 4)->info();
        std::cout << "\n";
        return stats.components == 2 ? 0 : 1; // the shipped input is two cubes
      }
  return 1;
}
