// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The coverage ceiling of hexahedra on a curved boundary
// (Hex_coverage_ceiling_3.h) and the boundary measures behind it
// (Sharp_features_3::smooth_turning()), against values worked out by hand,
// in a metric and without.
#include <CGAL_ext/Hex_coverage_ceiling_3.h>
#include <CGAL_ext/Metric_field_3.h>
#include <CGAL_ext/Sharp_features_3.h>
#include <CGAL_ext/build_triangulation_from_tets.h>
#include <CGAL_ext/tetrahedralize.h>

#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <limits>
#include <vector>

using namespace CGAL_ext;
using Tr = Tet_mesh_triangulation_3<>;
using Field = Metric_field_3<Tr>;
using Features = Sharp_features_3<Field>;

namespace {

// Two unit boxes [0,2]x[0,1]x[0,1] whose top edge x = 1, z = 1 is moved up
// by d (a ridge) or down (a valley), each box in the six tetrahedra around
// its diagonal from (x0, 0, 0) to (x0 + 1, 1, 1).
void ridge(double d, Tr& tr) {
  std::vector<std::array<double, 3>> points;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 3; ++i) points.push_back({double(i), double(j), k + (i == 1 && k == 1 ? d : 0.0)});
  auto id = [](int i, int j, int k) { return std::size_t(i + 3 * (j + 2 * k)); };
  std::vector<std::array<std::size_t, 4>> tets;
  for (int x = 0; x < 2; ++x) {
    // the box's corners in VTK order: 0..3 at z = 0, 4..7 above them
    const std::array<std::size_t, 8> c = {id(x, 0, 0),     id(x + 1, 0, 0), id(x + 1, 1, 0), id(x, 1, 0),
                                          id(x, 0, 1),     id(x + 1, 0, 1), id(x + 1, 1, 1), id(x, 1, 1)};
    for (const auto& t : {std::array<int, 4>{0, 1, 2, 6}, {0, 5, 1, 6}, {0, 2, 3, 6}, {0, 3, 7, 6}, {0, 4, 5, 6},
                          {0, 7, 4, 6}})
      tets.push_back({c[t[0]], c[t[1]], c[t[2]], c[t[3]]});
  }
  build_triangulation_from_tets(points, tets, std::vector<int>(tets.size(), 0), tr);
}

} // namespace

TEST_CASE("coverage ceiling of a ridge and a valley: the turning, its sign and the formula", "[coverage_ceiling]") {
  for (double d : {0.1, -0.1}) {
    Tr tr;
    ridge(d, tr);
    const Field field(tr, Eigen::Matrix3d::Identity().eval());
    const Features f(field, 40);
    // the only edge turning by less than 40 degrees: 2 atan(d) over length 1
    CHECK(f.smooth_turning() == Approx(2 * std::atan(d)).epsilon(1e-13));
    const double volume = field.metric_volume();
    REQUIRE(volume == Approx(2 + d).epsilon(1e-13));
    for (double l : {0.5, 1.0, 2.0}) {
      const double expected = 1 - l * l / 12 * 2 * std::atan(d) / (2 + d);
      CHECK(hex_coverage_ceiling(f, volume, l) == Approx(expected).epsilon(1e-13));
    }
    // convex: below 1; concave, where quads bulge out: above 1
    if (d > 0) CHECK(hex_coverage_ceiling(f, volume, 1.0) < 1);
    else CHECK(hex_coverage_ceiling(f, volume, 1.0) > 1);
    // hexes far too large for the curvature: 0, not below
    if (d > 0) CHECK(hex_coverage_ceiling(f, volume, 100.0) == 0.0);
    // at 5 degrees the ridge is a crease that hex edges follow
    const Features sharp(field, 5);
    CHECK(sharp.smooth_turning() == 0.0);
    CHECK(hex_coverage_ceiling(sharp, volume, 1.0) == 1.0);
  }
}

TEST_CASE("coverage ceiling in a metric: g = I / h^2 with hexes of 1 is the identity with hexes of h",
          "[coverage_ceiling]") {
  Tr tr;
  ridge(0.15, tr);
  const double h = 0.37;
  const Field euclid(tr, Eigen::Matrix3d::Identity().eval());
  const Field scaled(tr, (Eigen::Matrix3d::Identity() / (h * h)).eval());
  const Features fe(euclid, 40), fs(scaled, 40);
  CHECK(fs.smooth_turning() == Approx(fe.smooth_turning() / h).epsilon(1e-12));
  CHECK(scaled.metric_volume() == Approx(euclid.metric_volume() / (h * h * h)).epsilon(1e-12));
  CHECK(hex_coverage_ceiling(fs, scaled.metric_volume()) ==
        Approx(hex_coverage_ceiling(fe, euclid.metric_volume(), h)).epsilon(1e-12));
  // A stretch keeps the top's faces flat and the ridge convex. Along y (the
  // ridge's direction) it lengthens the edge: s times the turning. Along x
  // (across the ridge) it flattens the slopes, whose metric normals
  // A^-1 n = (-+0.15 / s, 0, 1) make an angle of 2 atan(0.15 / s).
  const double s = 3;
  const Field along(tr, Eigen::Vector3d(1, s * s, 1).asDiagonal().toDenseMatrix());
  CHECK(Features(along, 40).smooth_turning() == Approx(s * 2 * std::atan(0.15)).epsilon(1e-12));
  CHECK(along.metric_volume() == Approx(s * (2 + 0.15)).epsilon(1e-12));
  const Field across(tr, Eigen::Vector3d(s * s, 1, 1).asDiagonal().toDenseMatrix());
  CHECK(Features(across, 40).smooth_turning() == Approx(2 * std::atan(0.15 / s)).epsilon(1e-12));
}

TEST_CASE("hex edge for a coverage: the inverse of the ceiling", "[coverage_ceiling]") {
  const double turning = 8 * M_PI, volume = 4 * M_PI / 3; // the unit ball
  // 0.99 on the unit ball: l^2 / 12 * 8 pi / (4 pi / 3) = 0.01, l = sqrt(0.02)
  CHECK(hex_edge_for_coverage(turning, volume, 0.99) == Approx(std::sqrt(0.02)).epsilon(1e-14));
  for (double c : {0.0, 0.9, 0.99, 0.999}) {
    const double l = hex_edge_for_coverage(turning, volume, c);
    CHECK(hex_coverage_ceiling(turning, volume, l) == Approx(c).margin(1e-14));
    CHECK(hex_coverage_ceiling(turning, volume, 1.01 * l) < std::max(c, 1e-300));
  }
  // a flat or concave boundary: every size reaches it
  CHECK(hex_edge_for_coverage(0, volume, 0.99) == std::numeric_limits<double>::infinity());
  CHECK(hex_edge_for_coverage(-1, volume, 0.99) == std::numeric_limits<double>::infinity());
  // what cannot be answered
  CHECK(std::isnan(hex_edge_for_coverage(turning, volume, 1)));
  CHECK(std::isnan(hex_edge_for_coverage(turning, volume, -0.5)));
  CHECK(std::isnan(hex_edge_for_coverage(turning, 0, 0.99)));
  CHECK(std::isnan(hex_coverage_ceiling(turning, 0, 1)));
  CHECK(std::isnan(hex_coverage_ceiling(std::numeric_limits<double>::quiet_NaN(), volume, 1)));
}

TEST_CASE("coverage ceiling of the built-in ball: its turning is 8 pi, its ceiling falls with the hex size",
          "[coverage_ceiling]") {
  const IO::Medit_mesh m = tetrahedralize_builtin("ball");
  Tr tr;
  build_triangulation_from_tets(m.vertices, m.tetrahedra, m.tetrahedron_references, tr);
  const Field field(tr, Eigen::Matrix3d::Identity().eval());
  const Features f(field, 40);
  CHECK(f.feature_edges().empty());
  // the faceted unit sphere: the integral of 2H = 2 over the area 4 pi, within its faceting
  CHECK(f.smooth_turning() == Approx(8 * M_PI).epsilon(0.01));
  double previous = 2;
  for (double l : {0.1, 0.2, 0.3, 0.4}) {
    const double c = hex_coverage_ceiling(f, field.metric_volume(), l);
    CHECK(c < previous);
    CHECK(c <= 1);
    previous = c;
  }
  // the edge for 0.99 gives 0.99
  const double l99 = hex_edge_for_coverage(f.smooth_turning(), field.metric_volume(), 0.99);
  CHECK(hex_coverage_ceiling(f, field.metric_volume(), l99) == Approx(0.99).epsilon(1e-12));
}
