// Example: a frame field in an anisotropic metric on a non-convex tet mesh,
// with Frame_field_3, its singularities, and the files of CubeCover's
// integer-grid map.
//
//   frame_field_example MESH [OUTDIR]
//
// The shipped input is Gmsh's unit box with a cylindrical hole around the
// vertical line x = y = 0.5. Unit length in the metric is one hex edge; the
// metric asks for hexes of edge h / (1 + z) along x and z and half that
// along y, h = 0.1, smaller towards the top: g = diag(1, 4, 1) (1 + z)^2 / h^2.
// 1. compute() runs set-up, face transports, linear initialisation,
//    projection and L-BFGS refinement, printing one line per stage.
// 2. The frames F = A^-1 R are g-orthonormal: F^T g F = I; the parameter
//    gradients A R are their dual basis, of length 1/h.
// 3. The singular edges by type, grouped into curves and nodes.
// 4. With OUTDIR: frames.fra (the gradients) and frames.perm (the face
//    matchings), which CubeCover reads with MESH.
#include <CGAL_ext/Frame_field_3.h>
#include <CGAL_ext/Frame_field_matchings_3.h>
#include <CGAL_ext/Frame_field_singularities_3.h>
#include <CGAL_ext/IO/Fra_file.h>
#include <CGAL_ext/IO/Perm_file.h>
#include <CGAL_ext/IO/read_tet_mesh.h>
#include <CGAL_ext/Metric_field_3.h>

#include <Eigen/Core>

#include <cstdio>
#include <iostream>
#include <array>
#include <map>
#include <string>
#include <vector>

using Tr = CGAL_ext::Tet_mesh_triangulation_3<>;
using Field = CGAL_ext::Metric_field_3<Tr>;

int main(int argc, char** argv) {
  if (argc != 2 && argc != 3) {
    std::cerr << "usage: frame_field_example MESH [OUTDIR]\n";
    return 2;
  }
  Tr tr;
  CGAL_ext::IO::read_tet_mesh(argv[1], tr);
  const double h = 0.1;
  //! [frame_field]
  const Field field(tr, [h](const Tr::Point& p) {
    const double s = (1 + p.z()) * (1 + p.z()) / (h * h);
    return Eigen::Matrix3d(Eigen::Vector3d(s, 4 * s, s).asDiagonal());
  });
  std::printf("the metric asks for about %.0f hexahedra\n", field.metric_volume());

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

  // The parameter gradients A R = F^-T: F^-1 F = I.
  const Eigen::Matrix3d G = ff.parameter_gradients(0);
  std::printf("tet 0: gradient lengths %.3f %.3f %.3f, |G^T F - I| = %.2e\n", G.col(0).norm(), G.col(1).norm(),
              G.col(2).norm(), (G.transpose() * F - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff());

  const CGAL_ext::Frame_field_matchings_3<CGAL_ext::Frame_field_3<Field>> matchings(ff);
  const auto singular = CGAL_ext::singular_edges(ff, matchings);
  const CGAL_ext::Singularity_graph graph = CGAL_ext::singularity_graph(ff, singular);
  //! [frame_field]
  std::map<std::string, int> types;
  for (const CGAL_ext::Singular_edge& s : singular) ++types[singularity_type_name(s.type)];
  std::printf("singular edges:");
  for (const auto& [name, n] : types) std::printf(" %s: %d", name.c_str(), n);
  std::printf("\n%zu curves, %zu nodes (%zu junctions, %zu curve ends inside the volume)\n", graph.curves.size(),
              graph.nodes.size(), graph.junctions, graph.interior_ends);

  if (argc == 3) {
    // CubeCover: integergrid MESH frames.fra frames.perm out.hexex
    std::vector<std::array<double, 9>> gradients(ff.size());
    for (std::size_t i = 0; i < ff.size(); ++i)
      for (int k = 0; k < 3; ++k)
        for (int c = 0; c < 3; ++c) gradients[i][3 * k + c] = ff.parameter_gradients(i)(c, k);
    const std::string dir = argv[2];
    CGAL_ext::IO::write_fra(dir + "/frames.fra", gradients);
    CGAL_ext::IO::write_perm(dir + "/frames.perm", matchings.perm_file(ff));
    std::printf("wrote %s/frames.fra and %s/frames.perm\n", dir.c_str(), dir.c_str());
  }
  return st.max_orthonormality_error < 1e-9 ? 0 : 1;
}
