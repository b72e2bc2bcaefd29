// Example: a metric kept in the user's own per-vertex array drives a
// transport and a frame field, through a property map, without copying.
//
//   metric_property_map_example MESH
//
// The shipped input is Gmsh's unit box with a cylindrical hole around the
// vertical line x = y = 0.5. The user's array holds g per vertex (as a
// simulation would produce it): hexes of edge h = 0.1, twice as fine along y
// near the top. Property_map_metric_field_3 reads it through a Boost
// iterator property map keyed by vertex handle.
// 1. The transport T(a->b) and a frame field on the user's values.
// 2. The same field read from an array of A = g^{1/2} gives the same bits.
// 3. The user changes g in place near the hole; after metric_changed() the
//    field sees the new values (nothing was copied).
#include <CGAL_ext/Frame_field_3.h>
#include <CGAL_ext/IO/read_tet_mesh.h>
#include <CGAL_ext/Metric_transport_3.h>
#include <CGAL_ext/Property_map_metric_field_3.h>

#include <boost/property_map/property_map.hpp>

#include <Eigen/Core>

#include <cstdio>
#include <iostream>
#include <vector>

using Tr = CGAL_ext::Tet_mesh_triangulation_3<>;
using Point = Tr::Point;
// The user's array, seen as a map Vertex_handle -> Eigen::Matrix3d through
// the vertices' file indices.
using Array_map = boost::iterator_property_map<std::vector<Eigen::Matrix3d>::iterator,
                                               CGAL_ext::Tet_mesh_vertex_index_map<Tr>>;
using Field = CGAL_ext::Property_map_metric_field_3<Tr, Array_map>;

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: metric_property_map_example MESH\n";
    return 2;
  }
  Tr tr;
  CGAL_ext::IO::Medit_mesh mesh;
  try {
    CGAL_ext::IO::read_tet_mesh(argv[1], tr, &mesh);
  } catch (const CGAL_ext::Input_error& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }

  // The user's data: g at every vertex of the file.
  const double h = 0.1;
  std::vector<Eigen::Matrix3d> g(mesh.vertices.size());
  for (std::size_t i = 0; i < g.size(); ++i) {
    const double z = mesh.vertices[i][2];
    g[i] = Eigen::Vector3d(1, 1 + 3 * z, 1).asDiagonal() * (1 / (h * h));
  }
  //! [property_map]
  const CGAL_ext::Tet_mesh_vertex_index_map<Tr> vim;
  Field field(tr, Array_map(g.begin(), vim), CGAL_ext::Vertex_metric_kind::metric); // checks g, copies nothing

  // 1. A transport and a frame field, both on the field's domain.
  const CGAL_ext::Metric_transport_3<Field> transport(field);
  const Point a(0.1, 0.1, 0.1), b(0.9, 0.2, 0.8);
  const CGAL_ext::Metric_transport_result before = transport(a, b);
  if (!before.ok) return 1;
  std::printf("T(a->b): angle %.6f rad, %zu pieces\n", before.angle, before.pieces);

  CGAL_ext::Frame_field_3<Field> ff(field);
  const CGAL_ext::Frame_field_statistics& st = ff.compute();
  std::printf("frame field on %zu tets: energy %.6g, boundary alignment error max %.3g deg, "
              "max |F^T g F - I| %.2e\n",
              ff.size(), st.smoothness_energy, st.boundary_error_max_deg, st.max_orthonormality_error);

  // 2. The same metric given as A = g^{1/2}: the roots are the same bits, so
  //    is the transport.
  std::vector<Eigen::Matrix3d> A(g.size());
  for (std::size_t i = 0; i < g.size(); ++i) A[i] = CGAL_ext::sqrt_spd(g[i]);
  const Field from_roots(tr, Array_map(A.begin(), vim), CGAL_ext::Vertex_metric_kind::sqrt_metric);
  const bool same = CGAL_ext::Metric_transport_3<Field>(from_roots)(a, b).rotation == before.rotation;
  std::printf("from A instead of g: %s\n", same ? "the same transport, bit for bit" : "DIFFERENT");

  // 3. The user refines the metric near the hole (hexes half as large), in
  //    place, and tells the field which vertices changed.
  std::size_t changed = 0;
  for (Tr::Vertex_handle v : tr.finite_vertex_handles()) {
    const double dx = v->point().x() - 0.5, dy = v->point().y() - 0.5;
    if (dx * dx + dy * dy > 0.35 * 0.35) continue;
    g[v->info()] *= 4;
    field.metric_changed(v); // checks it, forgets the cached curls around v
    ++changed;
  }
  const CGAL_ext::Metric_transport_result after = transport(a, b);
  //! [property_map]
  std::printf("after refining g at %zu vertices: angle %.6f rad (was %.6f)\n", changed, after.angle, before.angle);

  return same && after.ok && changed > 0 && after.rotation != before.rotation && st.max_orthonormality_error < 1e-9
             ? 0
             : 1;
}
