// The concepts' archetypes drive the components that require them: the
// MetricField_3 archetype (test/metric_field_archetype.h, a constant metric
// with exactly the concept's members) through the frame field, its sharp
// features, matchings, singular edges and repair, the transport between
// points and the transport in a cell; and the results equal those of the
// default model, Metric_field_3, with the same constant metric. The other
// model, Property_map_metric_field_3 on the user's array, gives the frame
// field of Metric_field_3 bit for bit.
#include <CGAL_ext/Frame_field_3.h>
#include <CGAL_ext/Frame_field_matchings_3.h>
#include <CGAL_ext/Frame_field_repair_3.h>
#include <CGAL_ext/Frame_field_singularities_3.h>
#include <CGAL_ext/Metric_field_3.h>
#include <CGAL_ext/Metric_transport_3.h>
#include <CGAL_ext/Property_map_metric_field_3.h>
#include <CGAL_ext/build_triangulation_from_tets.h>
#include <CGAL_ext/make_kuhn_grid.h>

#include "metric_field_archetype.h"

#include <catch2/catch.hpp>

#include <boost/property_map/property_map.hpp>

#include <vector>

using namespace CGAL_ext;
using Tr = Tet_mesh_triangulation_3<>;
using Archetype = testing::Metric_field_archetype_3<Tr>;

TEST_CASE("MetricField_3: its archetype drives the frame field, singularities, repair and transports like Metric_field_3",
          "[concepts]") {
  // A 4 x 3 x 2 box with a cube left out (a non-convex domain with feature
  // edges), and a constant anisotropic metric g = A^2.
  const IO::Medit_mesh g = make_kuhn_grid({4, 3, 2}, 0.25, {0, 0, 0}, [](int i, int j, int k) { return !(i == 3 && j == 2 && k == 1); });
  Tr tr;
  build_triangulation_from_tets(g.vertices, g.tetrahedra, {}, tr);
  Eigen::Matrix3d A;
  A << 3, 0.5, 0, 0.5, 2, 0.25, 0, 0.25, 4;
  const Archetype archetype(tr, A);
  const Metric_field_3<Tr> model(tr, [&](const Tr::Point&) { return Eigen::Matrix3d(A * A); });

  Frame_field_3<Archetype> ff(archetype);
  Frame_field_3<Metric_field_3<Tr>> reference(model);
  const Frame_field_statistics& s = ff.compute();
  const Frame_field_statistics& r = reference.compute();
  REQUIRE(ff.size() == 6 * 23);
  CHECK(s.feature_edges == r.feature_edges);
  CHECK(s.feature_corners == r.feature_corners);
  CHECK(s.hard_two_axes == r.hard_two_axes);
  CHECK(s.smoothness_energy == Approx(r.smoothness_energy).margin(1e-9));
  CHECK(s.max_transport_angle == 0); // constant metric: every face transport is the identity
  double worst = 0;
  for (std::size_t i = 0; i < ff.size(); ++i)
    worst = std::max(worst, octahedral_distance(ff.rotation(i), reference.rotation(i)));
  CHECK(worst < 1e-6);

  const Frame_field_matchings_3<Frame_field_3<Archetype>> matchings(ff);
  const auto edges = singular_edges(ff, matchings);
  CHECK(edges.size() == singular_edges(reference).size());
  const Singularity_repair_report repair = repair_singularities(ff);
  CHECK(repair.non_meshable_after <= repair.non_meshable_before);

  // Transports: the identity for a constant metric, along any segment in the
  // domain; a segment that ends in the missing cube (outside the domain) is refused.
  const Metric_transport_3<Archetype> transport(archetype);
  const Metric_transport_result inside = transport(Tr::Point(0.1, 0.1, 0.1), Tr::Point(0.9, 0.2, 0.45));
  INFO(inside.message);
  REQUIRE(inside.ok);
  CHECK(inside.rotation.isApprox(Eigen::Matrix3d::Identity(), 1e-14));
  const Metric_transport_result across = transport(Tr::Point(0.7, 0.3, 0.4), Tr::Point(0.9, 0.7, 0.4));
  CHECK_FALSE(across.ok);
  const Tr::Cell_handle c = ff.cell(0);
  const Transport_result in_cell = cell_transport(archetype, c, Tr::Point(ff.centroid(0)(0), ff.centroid(0)(1), ff.centroid(0)(2)),
                                                  c->vertex(0)->point());
  CHECK(in_cell.rotation.isApprox(Eigen::Matrix3d::Identity(), 1e-14));
}

TEST_CASE("MetricField_3: a frame field on the user's property map of g equals the one on Metric_field_3, bit for bit",
          "[concepts]") {
  // A varying metric on a non-convex box: the frames depend on every
  // value the field reads (A, curls, transports, metric normals).
  const IO::Medit_mesh g = make_kuhn_grid({3, 3, 2}, 1.0 / 3, {0, 0, 0}, [](int i, int j, int) { return !(i == 2 && j == 2); });
  Tr tr;
  build_triangulation_from_tets(g.vertices, g.tetrahedra, {}, tr);
  std::vector<Eigen::Matrix3d> metrics(g.vertices.size());
  for (std::size_t i = 0; i < metrics.size(); ++i) {
    const auto& p = g.vertices[i];
    Eigen::Matrix3d m;
    m << 4 + p[2], 0.5 * p[0], 0, 0.5 * p[0], 9 - 2 * p[1], 0.3, 0, 0.3, 5 + p[0] * p[1];
    metrics[i] = m;
  }
  using Array_map = boost::iterator_property_map<std::vector<Eigen::Matrix3d>::iterator, Tet_mesh_vertex_index_map<Tr>>;
  using Map_field = Property_map_metric_field_3<Tr, Array_map>;
  const Map_field user(tr, Array_map(metrics.begin()), Vertex_metric_kind::metric);
  const Metric_field_3<Tr> stored(tr, metrics);
  Frame_field_3<Map_field> ff(user);
  Frame_field_3<Metric_field_3<Tr>> reference(stored);
  const Frame_field_statistics& s = ff.compute();
  const Frame_field_statistics& r = reference.compute();
  REQUIRE(ff.size() == reference.size());
  CHECK(s.max_transport_angle > 0); // a varying metric: the transports are not all the identity
  CHECK(s.max_transport_angle == r.max_transport_angle);
  CHECK(s.smoothness_energy == r.smoothness_energy);
  std::size_t differ = 0;
  for (std::size_t i = 0; i < ff.size(); ++i) differ += ff.rotation(i) != reference.rotation(i);
  CHECK(differ == 0);
  const Metric_transport_3<Map_field> transport(user);
  const Metric_transport_3<Metric_field_3<Tr>> stored_transport(stored);
  const Tr::Point a(0.05, 0.1, 0.2), b(0.6, 0.95, 0.5);
  CHECK(transport(a, b).rotation == stored_transport(a, b).rotation);
}
