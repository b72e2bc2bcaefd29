// Example: a frame field in an anisotropic metric on a non-convex tet mesh,
// with Frame_field_3, and its singular edges.
//
//   frame_field_example MESH
//
// The shipped input is Gmsh's unit box with a cylindrical hole around the
// vertical line x = y = 0.5. The metric asks for edges half as long along y as
// along x and z, and grows with z: g = diag(1, 4, 1) (1 + z)^2.
// 1. compute() runs set-up, face transports, linear initialisation,
//    projection and L-BFGS refinement, printing one line per stage.
// 2. The frames F = A^-1 R are g-orthonormal: F^T g F = I.
// 3. The singular edges, by type.
#include <CGAL_ext/Frame_field_3.h>
#include <CGAL_ext/Frame_field_singularities_3.h>
#include <CGAL_ext/IO/read_tet_mesh.h>
#include <CGAL_ext/Metric_field_3.h>

#include <Eigen/Core>

#include <cstdio>
#include <iostream>
#include <map>

using Tr = CGAL_ext::Tet_mesh_triangulation_3<>;
using Field = CGAL_ext::Metric_field_3<Tr>;

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: frame_field_example MESH\n";
    return 2;
  }
  Tr tr;
  CGAL_ext::IO::read_tet_mesh(argv[1], tr);
  const Field field(tr, [](const Tr::Point& p) {
    const double s = (1 + p.z()) * (1 + p.z());
    return Eigen::Matrix3d(Eigen::Vector3d(s, 4 * s, s).asDiagonal());
  });

  CGAL_ext::Frame_field_options options;
  options.progress = [](const std::string& stage, double seconds, const std::string& detail) {
    std::printf("%-22s %7.3f s  %s\n", stage.c_str(), seconds, detail.c_str());
  };
  CGAL_ext::Frame_field_3<Field> ff(field);
  const CGAL_ext::Frame_field_statistics& st = ff.compute(options);

  // F^T g F = I at every centroid: the columns of F are unit hex edges in g.
  const Eigen::Matrix3d F = ff.frame(0), A = ff.sqrt_metric(0);
  std::printf("tet 0: |F^T g F - I| = %.2e, edge lengths %.4f %.4f %.4f\n",
              (F.transpose() * A * A * F - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), F.col(0).norm(),
              F.col(1).norm(), F.col(2).norm());
  std::printf("energy %.6g, boundary alignment error mean %.3g max %.3g deg\n", st.smoothness_energy,
              st.boundary_error_mean_deg, st.boundary_error_max_deg);

  std::map<std::string, int> types;
  for (const CGAL_ext::Singular_edge& s : CGAL_ext::singular_edges(ff)) ++types[singularity_type_name(s.type)];
  std::printf("singular edges:");
  for (const auto& [name, n] : types) std::printf(" %s: %d", name.c_str(), n);
  std::printf("\n");
  return st.max_orthonormality_error < 1e-9 ? 0 : 1;
}
