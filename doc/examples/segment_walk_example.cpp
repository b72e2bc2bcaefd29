// Example: walk segments through a non-convex tet mesh with Segment_walk_3.
//
//   segment_walk_example MESH
//
// The shipped input is Gmsh's unit box with a cylindrical hole of radius 0.2
// around the vertical line x = y = 0.5. A segment across the box at mid-height
// leaves the domain into the hole and re-enters it: the walk reports the gap.
// A second segment runs along a mesh edge, from one vertex to another.
#include <CGAL_ext/IO/read_tet_mesh.h>
#include <CGAL_ext/Segment_walk_3.h>

#include <cmath>
#include <iostream>
#include <iterator>
#include <vector>

using Tr = CGAL_ext::Tet_mesh_triangulation_3<>;
using Walk = CGAL_ext::Segment_walk_3<Tr, CGAL_ext::Is_tet_mesh_domain_cell>;
using Piece = CGAL_ext::Segment_walk_piece_3<Tr>;

void print(const std::vector<Piece>& pieces) {
  const char* names[] = {"outside", "vertex", "edge", "facet", "tet"};
  for (const Piece& piece : pieces) {
    std::cout << "  " << names[piece.dimension + 1] << " [" << piece.t_in << ", " << piece.t_out << "]";
    if (piece.dimension == 3) std::cout << " tetrahedron " << piece.cell->info().index;
    for (int i = 0; i <= piece.dimension && piece.dimension < 3; ++i) std::cout << " v" << piece.vertices[i]->info();
    std::cout << "\n";
  }
}

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: segment_walk_example MESH\n";
    return 2;
  }
  Tr tr;
  try {
    CGAL_ext::IO::read_tet_mesh(argv[1], tr);
  } catch (const CGAL_ext::Input_error& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
  const Walk walk(tr, CGAL_ext::Is_tet_mesh_domain_cell());

  // 1. Across the hole: the fast mode gives the pieces of positive length,
  //    i.e. what a transport along the segment integrates, and the gap.
  std::vector<Piece> pieces;
  walk.fast(Tr::Point(0.05, 0.5, 0.51), Tr::Point(0.95, 0.5, 0.51), std::back_inserter(pieces));
  std::cout << "across the hole, " << pieces.size() << " pieces of positive length:\n";
  print(pieces);
  int gaps = 0;
  for (const Piece& piece : pieces) gaps += piece.dimension == -1;

  // 2. Along the first edge of the first tet: the full output is the two
  //    end vertices with the open edge between them.
  const Tr::Cell_handle c = *tr.finite_cell_handles().begin();
  pieces.clear();
  walk(c->vertex(0)->point(), c->vertex(1)->point(), std::back_inserter(pieces));
  std::cout << "along an edge, the full output:\n";
  print(pieces);

  // 3. Many segments at once: vertical segments on a 10 x 10 grid, each
  //    with the cell of its start point as the hint. fast_batch interleaves
  //    their walks (which pays on meshes larger than the cache) and calls
  //    back with the query index; the pieces of each query come in order.
  //! [batch]
  std::vector<Walk::Query> queries;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j) {
      const Tr::Point q(0.05 + 0.1 * i, 0.05 + 0.1 * j, 0.02);
      queries.push_back({q, Tr::Point(q.x(), q.y(), 0.98), walk.locate(q).cell});
    }
  std::vector<double> inside(queries.size(), 0.0);
  walk.fast_batch(queries, [&](std::size_t i, const Piece& piece) {
    if (piece.dimension >= 0) inside[i] += piece.t_out - piece.t_in;
  });
  //! [batch]
  int in_hole = 0, in_solid = 0;
  for (double x : inside) {
    in_hole += x == 0.0;
    in_solid += std::abs(x - 1.0) < 1e-12;
  }
  std::cout << "vertical segments: " << in_hole << " in the hole, " << in_solid << " in the solid\n";

  // The gap is the hole: one gap, and three pieces vertex-edge-vertex; the
  // 12 grid points within 0.16 of the axis are in the hole, the others in
  // the solid (the polygonal hole is inscribed in the cylinder of radius 0.2).
  return gaps == 1 && pieces.size() == 3 && pieces[1].dimension == 1 && in_hole == 12 && in_solid == 88 ? 0 : 1;
}
