// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The domain's thickness behind its boundary facets (Domain_thickness_3.h)
// against values worked out by hand: slabs of Kuhn grids in the identity, a
// diagonal, an anisotropic and a varying metric, the cap, and a non-convex
// domain whose rays leave and re-enter it.
#include <CGAL_ext/Domain_thickness_3.h>
#include <CGAL_ext/Metric_field_3.h>
#include <CGAL_ext/build_triangulation_from_tets.h>
#include <CGAL_ext/make_kuhn_grid.h>

#include <catch2/catch.hpp>

#include <tbb/global_control.h>

#include <cmath>
#include <memory>
#include <stdexcept>
#include <vector>

using namespace CGAL_ext;

namespace {

using Tr = Tet_mesh_triangulation_3<>;
using Field = Metric_field_3<Tr>;
using Thickness = Domain_thickness_3<Field>;

struct Grid {
  IO::Medit_mesh mesh;
  Tr tr;
  explicit Grid(IO::Medit_mesh m) : mesh(std::move(m)) {
    build_triangulation_from_tets(mesh.vertices, mesh.tetrahedra, mesh.tetrahedron_references, tr);
  }
};

// The facet's centroid and outward unit normal, from its tetrahedron.
void facet_frame(const Field& field, const Thickness::Facet& f, Eigen::Vector3d& centroid, Eigen::Vector3d& normal) {
  Tr::Cell_handle c;
  for (auto it = field.triangulation().finite_cells_begin(); it != field.triangulation().finite_cells_end(); ++it)
    if (std::size_t(get(field.cell_index_map(), it)) == f.tet) c = it;
  double area;
  CGAL_ext::internal::boundary_facet_geometry(c, f.facet, centroid, normal, area);
}

} // namespace

TEST_CASE("a slab's thickness: its height behind its faces, its width behind its sides, and the cap",
          "[thickness]") {
  // [0, 1] x [0, 1] x [0, 0.25]: 4 x 4 x 1 cubes of side 0.25.
  Grid g(make_kuhn_grid({4, 4, 1}, 0.25));
  const Field field(g.tr, Eigen::Matrix3d::Identity().eval());
  const Thickness t(field, 2);
  REQUIRE(t.facets().size() == 2 * 32 + 4 * 8);
  for (const Thickness::Facet& f : t.facets()) {
    Eigen::Vector3d c, n;
    facet_frame(field, f, c, n);
    INFO("facet at " << c.transpose() << ", normal " << n.transpose());
    CHECK(f.thickness == Approx(std::abs(n.z()) > 0.5 ? 0.25 : 1.0).margin(1e-10));
  }
  CHECK(t.total_area() == Approx(2 + 4 * 0.25).margin(1e-10));
  // By area: the two faces (2) are thin, the four sides (1) are not.
  CHECK(t.area_fraction_below(0.5) == Approx(2.0 / 3).margin(1e-10));
  CHECK(t.area_fraction_below(0.2) == 0);
  CHECK(t.area_fraction_below(1.5) == Approx(1).margin(1e-10));
  CHECK(t.area_quantile(0.1) == Approx(0.25).margin(1e-10));
  CHECK(t.area_quantile(0.9) == Approx(1).margin(1e-10));
  CHECK(std::isnan(t.area_quantile(1.5)));

  // A cap below the width: the sides count as the cap.
  const Thickness capped(field, 0.5);
  for (const Thickness::Facet& f : capped.facets()) CHECK((f.thickness == Approx(0.25).margin(1e-10) || f.thickness == 0.5));
  CHECK(capped.area_quantile(0.9) == 0.5);

  for (double bad : {0.0, -1.0, std::nan(""), HUGE_VAL})
    CHECK_THROWS_AS(Thickness(field, bad), std::invalid_argument);
}

TEST_CASE("a slab's thickness in the metrics 2^-1000 I and 2^1000 I: the same fractions, lengths scaled exactly",
          "[thickness]") {
  // g = s^2 I with s a power of two: every metric length is s times the
  // Euclidean one. A^{-1} of 2^-500 I through a determinant (2^-1500)
  // would be infinite.
  Grid g(make_kuhn_grid({4, 4, 1}, 0.25));
  for (const int k : {-500, 500}) {
    const double s = std::ldexp(1.0, k);
    INFO("s = 2^" << k);
    const Field field(g.tr, (s * s * Eigen::Matrix3d::Identity()).eval());
    const Thickness t(field, 2 * s);
    for (const Thickness::Facet& f : t.facets()) {
      Eigen::Vector3d c, n;
      facet_frame(field, f, c, n);
      CHECK(f.thickness / s == Approx(std::abs(n.z()) > 0.5 ? 0.25 : 1.0).margin(1e-10));
    }
    CHECK(t.total_area() / (s * s) == Approx(2 + 4 * 0.25).margin(1e-10));
    CHECK(t.area_fraction_below(0.5 * s) == Approx(2.0 / 3).margin(1e-10));
  }
}

TEST_CASE("thickness in a metric: measured in it, along the metric normal", "[thickness]") {
  SECTION("diag(1, 1, 4): the slab is twice as thick, its sides as wide, and its sides' areas double") {
    Grid g(make_kuhn_grid({4, 4, 1}, 0.25));
    const Field field(g.tr, Eigen::Vector3d(1, 1, 4).asDiagonal().toDenseMatrix().eval());
    const Thickness t(field, 2);
    for (const Thickness::Facet& f : t.facets()) {
      Eigen::Vector3d c, n;
      facet_frame(field, f, c, n);
      CHECK(f.thickness == Approx(std::abs(n.z()) > 0.5 ? 0.5 : 1.0).margin(1e-10));
    }
    // Faces: det(A) |A^{-T} n| = 2 * 1/2; sides: 2 * 1.
    CHECK(t.total_area() == Approx(2 * 1 + 4 * 0.25 * 2).margin(1e-10));
  }
  SECTION("an anisotropic metric: the distance between the planes, t / sqrt((g^-1)_zz), not t sqrt(g_zz)") {
    // [0, 2] x [0, 0.5] x [0, 0.25]. g^-1 e_z is along (-1/2, 0, 1): from
    // the faces the rays drift by 1/8 in x, so those 1/4 from the ends stay
    // in the slab.
    Grid g(make_kuhn_grid({8, 2, 1}, 0.25));
    Eigen::Matrix3d m;
    m << 1, 0, 0.5, 0, 1, 0, 0.5, 0, 1;
    const Field field(g.tr, m);
    const Thickness t(field, 2);
    const double expected = 0.25 / std::sqrt(m.inverse()(2, 2)); // 0.2165...
    int checked = 0;
    for (const Thickness::Facet& f : t.facets()) {
      Eigen::Vector3d c, n;
      facet_frame(field, f, c, n);
      if (std::abs(n.z()) < 0.5 || c.x() < 0.25 || c.x() > 1.75) continue;
      INFO("facet at " << c.transpose());
      CHECK(f.thickness == Approx(expected).margin(1e-10));
      ++checked;
    }
    CHECK(checked == 2 * 6 * 2 * 2); // two faces, 6 x 2 cubes, 2 triangles each
    CHECK(std::abs(expected - 0.25 * std::sqrt(m(2, 2))) > 0.03); // the Euclidean normal would be far off
  }
  SECTION("a metric that varies: A = (1 + 4z) on z, integrated exactly") {
    Grid g(make_kuhn_grid({4, 4, 1}, 0.25));
    std::vector<Eigen::Matrix3d> per_vertex;
    for (const auto& p : g.mesh.vertices) {
      const double a = 1 + 4 * p[2];
      per_vertex.push_back(Eigen::Vector3d(1, 1, a * a).asDiagonal().toDenseMatrix());
    }
    const Field field(g.tr, per_vertex);
    const Thickness t(field, 2);
    for (const Thickness::Facet& f : t.facets()) {
      Eigen::Vector3d c, n;
      facet_frame(field, f, c, n);
      if (std::abs(n.z()) > 0.5) CHECK(f.thickness == Approx(0.25 + 2 * 0.25 * 0.25).margin(1e-10)); // int_0^1/4 (1 + 4z) dz
    }
  }
}

TEST_CASE("a metric that shrinks inward: the rays go on to the cap, exactly", "[thickness]") {
  // [0, 1]^2 x [0, 1], A = diag(1, 1, a) with a = 8, 4, 2, 1, 0.5 at z = 0, 1/4, ..., 1
  // (hexes growing upwards): the metric height is 1/4 (6 + 3 + 1.5 + 0.75) = 2.8125.
  Grid g(make_kuhn_grid({4, 4, 4}, 0.25));
  std::vector<Eigen::Matrix3d> per_vertex;
  for (const auto& p : g.mesh.vertices) {
    const double a = 8 / std::pow(2.0, std::round(p[2] * 4));
    per_vertex.push_back(Eigen::Vector3d(1, 1, a * a).asDiagonal().toDenseMatrix());
  }
  const Field field(g.tr, per_vertex);
  // A cap of 2.5: from the bottom, where the metric is largest, the first leg
  // (planned in the centroid's metric, 8) falls short of it; the ray must go on
  // and reach the cap itself, not a length just below it.
  const Thickness capped(field, 2.5);
  // A cap of 4: every ray leaves, from the bottom and from the top alike.
  const Thickness full(field, 4);
  int bottom = 0, top = 0;
  for (std::size_t k = 0; k < capped.facets().size(); ++k) {
    Eigen::Vector3d c, n;
    facet_frame(field, capped.facets()[k], c, n);
    if (std::abs(n.z()) < 0.5) continue;
    INFO("facet at " << c.transpose());
    CHECK(capped.facets()[k].thickness == 2.5);
    CHECK(full.facets()[k].thickness == Approx(2.8125).margin(1e-10));
    ++(n.z() < 0 ? bottom : top);
  }
  CHECK(bottom == 32);
  CHECK(top == 32);
}

TEST_CASE("thickness of a non-convex domain: up to where the ray first leaves it, not where it leaves for good",
          "[thickness]") {
  // A U: three cubes of side 1 at the bottom, the left and right ones above;
  // from the left arm's outer side, rays at z > 1 cross the arm (1), the
  // notch, then the right arm: the thickness is 1. Below, the bottom is 3 wide.
  Grid g(make_kuhn_grid({3, 1, 2}, 1, {0, 0, 0}, [](int i, int, int k) { return !(i == 1 && k == 1); }));
  const Field field(g.tr, Eigen::Matrix3d::Identity().eval());
  const Thickness t(field, 4);
  int arm = 0, base = 0;
  for (const Thickness::Facet& f : t.facets()) {
    Eigen::Vector3d c, n;
    facet_frame(field, f, c, n);
    if (n.x() > -0.5 || c.x() > 1e-9) continue; // the outer side x = 0
    INFO("facet at " << c.transpose());
    if (c.z() > 1) {
      CHECK(f.thickness == Approx(1).margin(1e-10));
      ++arm;
    } else {
      CHECK(f.thickness == Approx(3).margin(1e-10));
      ++base;
    }
  }
  CHECK(arm == 2);
  CHECK(base == 2);
}

TEST_CASE("the thickness does not depend on the number of threads", "[thickness]") {
  Grid g(make_kuhn_grid({6, 5, 2}, 0.2, {0, 0, 0}, [](int i, int j, int) { return !(i == 2 && j >= 1 && j <= 3); }));
  Eigen::Matrix3d m;
  m << 2, 0.3, 0.1, 0.3, 1, 0.2, 0.1, 0.2, 1.5;
  const Field field(g.tr, m);
  std::vector<double> one, all;
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
    const Thickness t(field, 3);
    for (const auto& f : t.facets()) one.push_back(f.thickness);
  }
  const Thickness t(field, 3);
  for (const auto& f : t.facets()) all.push_back(f.thickness);
  CHECK(one == all);
  CHECK(t.area_fraction_below(3) == 1); // no width reaches 3 in this metric: every ray leaves before the cap
}
