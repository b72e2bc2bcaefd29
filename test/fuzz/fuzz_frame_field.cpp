// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Fuzzes the whole computation on a small fuzzed mesh: the .mesh reader, the
// triangulation, a metric field, the frame field with its matchings and
// singularities, a segment walk and a transport. The metric is picked from
// the vertex count (constant, constant anisotropic, smooth, strongly
// varying), in coordinates normalised by the bounding box, so that seeds
// written by Gmsh and TetGen need no extra byte.
//
// Properties checked beyond "no crash, no hang, Input_error only": frames
// that are g-orthonormal with finite statistics, walk pieces in order inside
// [0, 1], and rotations for every transport that succeeds.
#include "fuzz_input.h"

#include <CGAL_ext/Frame_field_3.h>
#include <CGAL_ext/Frame_field_matchings_3.h>
#include <CGAL_ext/Frame_field_singularities_3.h>
#include <CGAL_ext/IO/read_tet_mesh.h>
#include <CGAL_ext/Metric_field_3.h>
#include <CGAL_ext/Metric_transport_3.h>
#include <CGAL_ext/Segment_walk_3.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <iterator>
#include <vector>

namespace {

using Tr = CGAL_ext::Tet_mesh_triangulation_3<>;
using Point = Tr::Point;
using Field = CGAL_ext::Metric_field_3<Tr>;

// Small meshes only: a run must take milliseconds.
constexpr std::size_t max_tets = 128;

void check(bool property, const char* what) {
  if (!property) {
    std::fprintf(stderr, "finding: %s\n", what);
    std::abort();
  }
}

Eigen::Matrix3d metric(int kind, const Eigen::Vector3d& q) {
  switch (kind) {
  case 0:
    return Eigen::Matrix3d::Identity();
  case 1: { // diag(1, 4, 9) rotated
    const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    return R * Eigen::Vector3d(1, 4, 9).asDiagonal() * R.transpose();
  }
  case 2: { // smooth, as in the transport example
    Eigen::Matrix3d J;
    J << 1, 0.4 * std::cos(q.y() + q.z()), 0, 0.3 * q.z(), 1, 0.3 * q.x(), 0.5 * std::cos(q.x()), 0, 1;
    return J.transpose() * J;
  }
  default: // sizes varying by 100 across the mesh
    return Eigen::Vector3d(1 + 99 * q.x() * q.x(), 1, 1 + 99 * q.z()).asDiagonal();
  }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = fuzz::write_input(data, size, ".mesh");
  fuzz::expect_input_error_only([&] {
    Tr tr;
    // As read_tet_mesh(), with a size limit before the build: runs stay short.
    const CGAL_ext::IO::Medit_mesh mesh = CGAL_ext::IO::read_medit_mesh(path);
    if (mesh.tetrahedra.empty() || mesh.tetrahedra.size() > max_tets) return;
    CGAL_ext::Tet_soup_source source;
    source.file = path;
    source.tet_lines = mesh.tetrahedron_lines;
    source.vertex_lines = mesh.vertex_lines;
    CGAL_ext::build_triangulation_from_tets(mesh.vertices, mesh.tetrahedra, mesh.tetrahedron_references, tr, source);
    Field::check_extent(tr, path);

    std::array<double, 3> lo{}, hi{};
    bool first = true;
    for (auto v : tr.finite_vertex_handles())
      for (int k = 0; k < 3; ++k) {
        lo[k] = first ? v->point()[k] : std::min(lo[k], v->point()[k]);
        hi[k] = first ? v->point()[k] : std::max(hi[k], v->point()[k]);
        first = k < 2 && first;
      }
    const int kind = static_cast<int>(mesh.vertices.size() % 4);
    const Field field(tr, [&](const Point& p) {
      Eigen::Vector3d q;
      for (int k = 0; k < 3; ++k) q[k] = hi[k] > lo[k] ? (p[k] - lo[k]) / (hi[k] - lo[k]) : 0.0;
      return metric(kind, q);
    });
    field.precompute();

    CGAL_ext::Frame_field_options options;
    options.max_linear_iterations = 500;
    options.max_refinement_iterations = 100;
    CGAL_ext::Frame_field_3<Field> ff(field);
    const CGAL_ext::Frame_field_statistics& st = ff.compute(options);
    check(std::isfinite(st.smoothness_energy) && std::isfinite(st.boundary_error_max_deg),
          "non-finite frame field statistics");
    check(st.max_orthonormality_error < 1e-6, "frames not g-orthonormal");
    for (std::size_t i = 0; i < ff.size(); ++i) check(ff.frame(i).allFinite(), "a frame is not finite");

    const CGAL_ext::Frame_field_matchings_3<CGAL_ext::Frame_field_3<Field>> matchings(ff);
    const auto singular = CGAL_ext::singular_edges(ff, matchings);
    const CGAL_ext::Singularity_graph graph = CGAL_ext::singularity_graph(ff, singular);
    (void)graph;

    // From the centroid of the first tetrahedron to the centroid of the last,
    // then on beyond the bounding box.
    const auto centroid = [](Tr::Cell_handle c) {
      return CGAL::centroid(c->vertex(0)->point(), c->vertex(1)->point(), c->vertex(2)->point(),
                            c->vertex(3)->point());
    };
    Tr::Cell_handle c0, c1;
    for (Tr::Cell_handle c : tr.finite_cell_handles())
      if (c->info().in_domain()) {
        if (c0 == Tr::Cell_handle()) c0 = c;
        c1 = c;
      }
    const Point a = centroid(c0), b = centroid(c1);
    const Point far(hi[0] + (hi[0] - lo[0]) + 1, b.y(), b.z());
    const CGAL_ext::Segment_walk_3<Tr, CGAL_ext::Is_tet_mesh_domain_cell> walk(tr, CGAL_ext::Is_tet_mesh_domain_cell());
    for (const Point& end : {b, far}) {
      std::vector<CGAL_ext::Segment_walk_piece_3<Tr>> pieces;
      walk(a, end, std::back_inserter(pieces));
      double t = 0;
      for (const auto& piece : pieces) {
        check(piece.t_in >= t && piece.t_out >= piece.t_in && piece.t_out <= 1, "walk pieces out of order");
        t = piece.t_out;
      }
    }
    const CGAL_ext::Metric_transport_3<Field> transport(field);
    CGAL_ext::Transport_options topt;
    topt.tolerance = 1e-8;
    for (const Point& end : {b, far}) {
      const CGAL_ext::Metric_transport_result r = transport(a, end, topt);
      if (r.ok)
        check(r.rotation.allFinite() && (r.rotation.transpose() * r.rotation - Eigen::Matrix3d::Identity()).norm() < 1e-9 &&
                  r.rotation.determinant() > 0,
              "a transport is not a rotation");
      else
        check(!r.message.empty(), "a failed transport without a reason");
    }
  });
  return 0;
}
