// Example: the transport T(a->b) of a metric field between arbitrary points
// of a non-convex tet mesh, with Metric_transport_3.
//
//   transport_example MESH
//
// The shipped input is Gmsh's unit box with a cylindrical hole of radius 0.2
// around the vertical line x = y = 0.5. The metric is the flat metric
// g = J^T J of the map Phi of doc/math.md section 6, sampled at the vertices.
// 1. One transport, and its reversal T(b->a) = T(a->b)^T (within the tolerance).
// 2. A segment across the hole: an error result, never a rotation.
// 3. A threaded batch, equal bit for bit to single transports.
#include <CGAL_ext/IO/read_tet_mesh.h>
#include <CGAL_ext/Metric_field_3.h>
#include <CGAL_ext/Metric_transport_3.h>

#include <Eigen/Core>

#include <cmath>
#include <iostream>
#include <utility>
#include <vector>

using Tr = CGAL_ext::Tet_mesh_triangulation_3<>;
using Point = Tr::Point;
using Field = CGAL_ext::Metric_field_3<Tr>;
using Transport = CGAL_ext::Metric_transport_3<Field>;

// g = J^T J for Phi = (X + 0.4 sin(Y+Z), Y + 0.3 sin(Z X), Z + 0.5 sin X).
Eigen::Matrix3d metric(const Point& p) {
  const double x = p.x(), y = p.y(), z = p.z();
  const double c1 = 0.4 * std::cos(y + z), c2 = 0.3 * std::cos(z * x);
  Eigen::Matrix3d J;
  J << 1, c1, c1, c2 * z, 1, c2 * x, 0.5 * std::cos(x), 0, 1;
  return J.transpose() * J;
}

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: transport_example MESH\n";
    return 2;
  }
  Tr tr;
  try {
    CGAL_ext::IO::read_tet_mesh(argv[1], tr);
  } catch (const CGAL_ext::Input_error& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
  //! [transport]
  const Field field(tr, metric); // A = g^{1/2} per vertex, linear in each tet
  field.precompute();            // the per-cell curls, in parallel
  const Transport transport(field);

  CGAL_ext::Transport_options opt; // Magnus-4, adaptive
  opt.tolerance = 1e-10;           // radians, for the whole segment

  // 1. From a corner region to the opposite one, past the hole.
  const Point a(0.1, 0.1, 0.1), b(0.9, 0.2, 0.8);
  const CGAL_ext::Metric_transport_result ab = transport(a, b, opt), ba = transport(b, a, opt);
  if (!ab.ok || !ba.ok) return 1;
  std::cout << "T(a->b) =\n" << ab.rotation << "\nangle " << ab.angle << " rad, " << ab.pieces << " pieces, "
            << ab.evaluations << " W evaluations\n";
  const double reversal = CGAL_ext::rotation_angle(ba.rotation * ab.rotation); // T(b->a) T(a->b) = I
  std::cout << "|T(b->a) T(a->b) - I| = " << reversal << " rad\n";

  // 2. Across the hole: no rotation, a reason.
  const auto across = transport(Point(0.05, 0.5, 0.51), Point(0.95, 0.5, 0.51), opt);
  std::cout << "across the hole: " << (across.ok ? "ok" : across.message) << "\n";

  // 3. A batch, in parallel: the same bits as single calls, for any thread count.
  std::vector<std::pair<Point, Point>> pairs = {{a, b}, {b, a}, {Point(0.1, 0.1, 0.5), Point(0.9, 0.1, 0.5)}};
  std::vector<CGAL_ext::Metric_transport_result> out;
  transport.transport_batch(pairs, opt, out);
  const bool same = out[0].rotation == ab.rotation && out[1].rotation == ba.rotation;
  //! [transport]
  std::cout << "batch of " << out.size() << ": " << (same ? "equal to single calls" : "DIFFERENT") << "\n";

  return reversal <= 2 * opt.tolerance && !across.ok && same && ab.angle > 1e-3 ? 0 : 1;
}
