// Reads a mesh through the installed CGAL_ext package and prints its tet count.
#include <CGAL_ext/IO/read_tet_mesh.h>

#include <iostream>

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  CGAL_ext::Tet_mesh_triangulation_3<> tr;
  CGAL_ext::IO::read_tet_mesh(argv[1], tr);
  std::cout << "tetrahedra " << tr.number_of_finite_cells() << "\n";
  return tr.is_valid() ? 0 : 1;
}
