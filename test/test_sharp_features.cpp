// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Sharp features (Sharp_features_3) and how the frame field follows them:
// a box with a 45-degree chamfer and a 48-sided cylinder, meshed by Mesh_3
// with their sharp edges protected.
#include <CGAL_ext/Frame_field_3.h>
#include <CGAL_ext/Frame_field_singularities_3.h>
#include <CGAL_ext/IO/read_tet_mesh.h>
#include <CGAL_ext/Metric_field_3.h>
#include <CGAL_ext/Sharp_features_3.h>
#include <CGAL_ext/build_triangulation_from_tets.h>
#include <CGAL_ext/tetrahedralize.h>

#include <catch2/catch.hpp>

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>
#include <vector>

using namespace CGAL_ext;
using Tr = Tet_mesh_triangulation_3<>;
using Field = Metric_field_3<Tr>;
using Frames = Frame_field_3<Field>;
using Features = Sharp_features_3<Field>;
namespace fs = std::filesystem;

namespace {

struct Surface {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<int, 3>> triangles; // outward (counter-clockwise seen from outside)
};

// A prism over a convex polygon (counter-clockwise in xy) from z = 0 to h,
// its faces fanned into triangles.
Surface prism(const std::vector<Eigen::Vector2d>& polygon, double h) {
  Surface s;
  const int n = int(polygon.size());
  for (double z : {0.0, h})
    for (const Eigen::Vector2d& p : polygon) s.points.emplace_back(p(0), p(1), z);
  for (int k = 1; k + 1 < n; ++k) {
    s.triangles.push_back({0, k + 1, k});         // bottom, seen from below
    s.triangles.push_back({n, n + k, n + k + 1}); // top
  }
  for (int k = 0; k < n; ++k) {
    const int a = k, b = (k + 1) % n;
    s.triangles.push_back({a, b, n + b});
    s.triangles.push_back({a, n + b, n + a});
  }
  return s;
}

struct Meshed {
  IO::Medit_mesh mesh;
  Tr tr;
};

std::unique_ptr<Meshed> mesh_surface(const Surface& s, double size, double sharp_angle_deg) {
  const fs::path path = fs::temp_directory_path() / ("cgal_ext_test_sharp_features_" + std::to_string(::getpid()) + ".off");
  {
    std::ofstream out(path);
    out.precision(17);
    out << "OFF\n" << s.points.size() << ' ' << s.triangles.size() << " 0\n";
    for (const Eigen::Vector3d& p : s.points) out << p(0) << ' ' << p(1) << ' ' << p(2) << '\n';
    for (const auto& t : s.triangles) out << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
  }
  Tetrahedralize_options o;
  o.size = size;
  o.sharp_angle_deg = sharp_angle_deg;
  auto m = std::make_unique<Meshed>();
  m->mesh = tetrahedralize_surface(path.string(), o);
  fs::remove(path);
  build_triangulation_from_tets(m->mesh.vertices, m->mesh.tetrahedra, m->mesh.tetrahedron_references, m->tr);
  return m;
}

// The box [0,1]^3 with its edge x = y = 1 cut by a 45-degree chamfer 0.3 wide.
Surface chamfered_box() {
  return prism({{0, 0}, {1, 0}, {1, 0.7}, {0.7, 1}, {0, 1}}, 1);
}

Eigen::Vector3d position(const Tr::Vertex_handle v) { return internal::to_eigen_vector(v->point()); }

// The distance from p to the segment [a, b].
double distance_to_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const double t = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
  return (p - (a + t * (b - a))).norm();
}

// The angle in degrees between the direction d (in the rotation's space)
// and the nearest axis of R.
double axis_error_deg(const Eigen::Matrix3d& R, const Eigen::Vector3d& d) {
  return std::acos(std::min(1.0, (R.transpose() * d.normalized()).cwiseAbs().maxCoeff())) * 180 / M_PI;
}

} // namespace

TEST_CASE("chamfered box: the feature edges are the prism's 15 edges, the corners its 10 vertices",
          "[sharp_features]") {
  const Surface s = chamfered_box();
  const auto m = mesh_surface(s, 0.12, 30); // protect the 45-degree chamfer
  const Field field(m->tr, Eigen::Matrix3d::Identity().eval());
  const Features features(field, 40);
  // The prism's edges: 5 bottom, 5 top, 5 vertical; the chamfer's two
  // vertical edges turn by 45 degrees, all others by 90.
  std::vector<std::array<int, 2>> prism_edges;
  for (int k = 0; k < 5; ++k) {
    prism_edges.push_back({k, (k + 1) % 5});
    prism_edges.push_back({5 + k, 5 + (k + 1) % 5});
    prism_edges.push_back({k, 5 + k});
  }
  std::vector<Tr::Vertex_handle> vertex(m->mesh.vertices.size());
  for (Tr::Vertex_handle v : m->tr.finite_vertex_handles()) vertex[get(Tet_mesh_vertex_index_map<Tr>(), v)] = v;
  std::vector<double> covered(prism_edges.size(), 0);
  for (const Features::Feature_edge& e : features.feature_edges()) {
    const Eigen::Vector3d a = position(vertex[e.source]), b = position(vertex[e.target]);
    int on = -1;
    for (std::size_t k = 0; k < prism_edges.size(); ++k)
      if (distance_to_segment(a, s.points[prism_edges[k][0]], s.points[prism_edges[k][1]]) < 1e-9 &&
          distance_to_segment(b, s.points[prism_edges[k][0]], s.points[prism_edges[k][1]]) < 1e-9)
        on = int(k);
    INFO("feature edge " << e.source << "-" << e.target << " at " << a.transpose() << " / " << b.transpose());
    REQUIRE(on >= 0);
    const bool chamfer = on == 8 || on == 11; // the vertical edges at (1, 0.7) and (0.7, 1)
    CHECK(e.angle_deg == Approx(chamfer ? 45 : 90).margin(1e-6));
    CHECK(e.facets == 2);
    covered[on] += (b - a).norm();
  }
  // Every prism edge is covered by feature edges, end to end.
  for (std::size_t k = 0; k < prism_edges.size(); ++k)
    CHECK(covered[k] == Approx((s.points[prism_edges[k][0]] - s.points[prism_edges[k][1]]).norm()).margin(1e-9));
  // The corners are the 10 vertices of the prism; every other feature
  // vertex is on a straight feature curve.
  CHECK(features.number_of_corners() == 10);
  for (std::size_t v = 0; v < vertex.size(); ++v) {
    if (features.kind(v) != Feature_vertex_kind::corner) continue;
    double nearest = 1e300;
    for (const Eigen::Vector3d& p : s.points) nearest = std::min(nearest, (position(vertex[v]) - p).norm());
    CHECK(nearest < 1e-9);
  }

  SECTION("the angle is measured in the metric") {
    // g = diag(1, 4, 1): the chamfer's metric normals A^{-1} n are (1, 0, 0)
    // and (1, 1/2, 0) up to scale, 26.57 degrees apart; the right angles stay right.
    const Field stretched(m->tr, Eigen::Vector3d(1, 4, 1).asDiagonal().toDenseMatrix().eval());
    const Features f20(stretched, 20), f40(stretched, 40);
    // At the chamfer's edge on x = 1 the faces' metric normals are (1, 0, 0)
    // and (1, 1/2, 0), 26.57 degrees apart; on y = 1, (0, 1, 0) and
    // (1, 1/2, 0), 63.43 degrees apart.
    const double flat = std::atan(0.5) * 180 / M_PI;
    std::size_t flat_edges = 0, steep_edges = 0;
    for (const Features::Feature_edge& e : f20.feature_edges()) {
      if (std::abs(e.angle_deg - 90) < 1e-6) continue;
      const Eigen::Vector3d p = position(vertex[e.source]);
      const bool on_x1 = std::abs(p(0) - 1) < 1e-9;
      CHECK(e.angle_deg == Approx(on_x1 ? flat : 90 - flat).margin(1e-6));
      ++(on_x1 ? flat_edges : steep_edges);
    }
    CHECK(flat_edges > 0);
    CHECK(steep_edges > 0);
    CHECK(f40.feature_edges().size() + flat_edges == f20.feature_edges().size());
  }
}

TEST_CASE("chamfered box: the frames follow the feature edges, and a crease's angle is shared by its faces",
          "[sharp_features][frame_field]") {
  const auto m = mesh_surface(chamfered_box(), 0.12, 30);
  const Field field(m->tr, Eigen::Matrix3d::Identity().eval());
  Frames ff(field);
  const Frame_field_statistics& st = ff.compute();
  CHECK(st.feature_corners == 10);
  CHECK(st.feature_tets > 0);
  const Features features(field, Frame_field_options().feature_angle_deg);
  std::size_t tangent_checks = 0;
  double worst_right_angle_face = 0;
  for (std::size_t i = 0; i < ff.size(); ++i) {
    const Tr::Cell_handle c = ff.cell(i);
    std::array<std::size_t, 4> v;
    bool at_corner = false;
    for (int k = 0; k < 4; ++k) {
      v[k] = ff.vertex_index(c->vertex(k));
      at_corner = at_corner || features.kind(v[k]) == Feature_vertex_kind::corner;
    }
    if (at_corner) continue; // a corner's frame: checked by the alignment on the right-angled box below
    const Eigen::Matrix3d R = ff.rotation(i);
    bool chamfer = false, feature = false;
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b)
        if (features.is_feature_edge(v[a], v[b])) {
          feature = true;
          const Eigen::Vector3d t = position(c->vertex(b)) - position(c->vertex(a));
          CHECK(axis_error_deg(R, t) < 1e-6); // straight edges: the tangent is the edge
          ++tangent_checks;
          const Eigen::Vector3d p = position(c->vertex(a));
          chamfer = chamfer || (std::abs(p(0) + p(1) - 1.7) < 1e-9 && std::abs(t(2)) > 0.99 * t.norm());
        }
    if (!feature) continue;
    std::vector<double> errors;
    for (const auto& b : ff.boundary_faces())
      if (b.tet == i) errors.push_back(ff.alignment_error_deg(b));
    if (!chamfer)
      for (double e : errors) worst_right_angle_face = std::max(worst_right_angle_face, e);
  }
  CHECK(tangent_checks > 50);
  CHECK(worst_right_angle_face < 1e-6); // faces at right-angled edges: exact
}

TEST_CASE("chamfered box: every tetrahedron along a 45-degree crease takes its shared angle, "
          "unless crease_split_deg is above 45",
          "[sharp_features][frame_field]") {
  // Frames turn only about the chamfer's vertical edges there, and the
  // faces' frames differ by 45 degrees about them: shared alike, each face
  // of every tetrahedron along the crease is 22.5 degrees off; with the
  // split off, a tetrahedron with faces on one side follows them exactly.
  const auto m = mesh_surface(chamfered_box(), 0.12, 30);
  const Field field(m->tr, Eigen::Matrix3d::Identity().eval());
  const Features features(field, Frame_field_options().feature_angle_deg);
  for (const double split : {Frame_field_options().crease_split_deg, 46.0}) {
    Frame_field_options options;
    options.crease_split_deg = split;
    Frames ff(field);
    ff.compute(options);
    std::size_t one_side = 0, both_sides = 0;
    for (std::size_t i = 0; i < ff.size(); ++i) {
      const Tr::Cell_handle c = ff.cell(i);
      bool at_corner = false, at_chamfer = false;
      for (int a = 0; a < 4; ++a) {
        at_corner = at_corner || features.kind(ff.vertex_index(c->vertex(a))) == Feature_vertex_kind::corner;
        for (int b = a + 1; b < 4; ++b) {
          const Eigen::Vector3d p = position(c->vertex(a)), t = position(c->vertex(b)) - p;
          at_chamfer = at_chamfer || (features.is_feature_edge(ff.vertex_index(c->vertex(a)), ff.vertex_index(c->vertex(b))) &&
                                      std::abs(p(0) + p(1) - 1.7) < 1e-9 && std::abs(t(2)) > 0.99 * t.norm());
        }
      }
      if (at_corner || !at_chamfer) continue;
      std::vector<const Frames::Boundary_face*> faces;
      for (const auto& b : ff.boundary_faces())
        if (b.tet == i) faces.push_back(&b);
      if (faces.empty()) continue; // free about the tangent
      bool same_side = true;
      for (const auto* f : faces) same_side = same_side && f->normal.dot(faces[0]->normal) > 0.99;
      (same_side ? one_side : both_sides) += 1;
      for (const auto* f : faces) {
        INFO("split " << split << ", tetrahedron " << i << (same_side ? " (one side)" : " (both sides)"));
        CHECK(ff.alignment_error_deg(*f) == Approx(same_side && split > 45 ? 0.0 : 22.5).margin(1e-4));
      }
    }
    CHECK(one_side >= 10);
  }
  for (const double bad : {-1.0, std::nan("")}) {
    Frame_field_options options;
    options.crease_split_deg = bad;
    Frames ff(field);
    CHECK_THROWS_AS(ff.compute(options), std::invalid_argument);
  }
}

TEST_CASE("a tetrahedron with faces on both sides of a 45-degree crease shares its angle between them",
          "[sharp_features][frame_field]") {
  // The chamfered box as a prism mesh: the pentagon cut into the triangles
  // (1, 2, 3), (0, 1, 3), (0, 3, 4), 6 layers, each triangular prism split
  // into 3 tetrahedra by the smallest-index rule (conforming). Unlike
  // Mesh_3's meshes, it has tetrahedra with one face on each side of a
  // chamfer edge (the one at (1, 0.7)).
  const std::vector<Eigen::Vector2d> pentagon = {{0, 0}, {1, 0}, {1, 0.7}, {0.7, 1}, {0, 1}};
  const std::array<std::array<std::size_t, 3>, 3> triangles = {{{1, 2, 3}, {0, 1, 3}, {0, 3, 4}}};
  const int layers = 6;
  std::vector<std::array<double, 3>> points;
  for (int l = 0; l <= layers; ++l)
    for (const Eigen::Vector2d& p : pentagon) points.push_back({p(0), p(1), double(l) / layers});
  std::vector<std::array<std::size_t, 4>> tets;
  for (int l = 0; l < layers; ++l)
    for (const auto& t : triangles) {
      auto a = [&](int m) { return std::size_t(l * 5) + t[m]; };
      auto b = [&](int m) { return std::size_t((l + 1) * 5) + t[m]; };
      for (std::array<std::size_t, 4> tet : {std::array<std::size_t, 4>{a(0), a(1), a(2), b(2)},
                                             std::array<std::size_t, 4>{a(0), a(1), b(1), b(2)},
                                             std::array<std::size_t, 4>{a(0), b(0), b(1), b(2)}}) {
        auto P = [&](std::size_t v) { return Eigen::Vector3d(points[v][0], points[v][1], points[v][2]); };
        if ((P(tet[1]) - P(tet[0])).cross(P(tet[2]) - P(tet[0])).dot(P(tet[3]) - P(tet[0])) < 0)
          std::swap(tet[2], tet[3]);
        tets.push_back(tet);
      }
    }
  Tr tr;
  build_triangulation_from_tets(points, tets, {}, tr);
  const Field field(tr, Eigen::Matrix3d::Identity().eval());
  Frames ff(field);
  ff.compute();
  const Features features(field, Frame_field_options().feature_angle_deg);
  std::size_t shared = 0;
  for (std::size_t i = 0; i < ff.size(); ++i) {
    std::vector<const Frames::Boundary_face*> faces;
    for (const auto& b : ff.boundary_faces())
      if (b.tet == i && std::abs(b.normal(2)) < 0.5) faces.push_back(&b);
    if (faces.size() != 2 || std::abs(faces[0]->normal.dot(faces[1]->normal) - std::sqrt(0.5)) > 1e-9) continue;
    bool at_corner = false;
    for (int k = 0; k < 4; ++k)
      at_corner = at_corner || features.kind(ff.vertex_index(ff.cell(i)->vertex(k))) == Feature_vertex_kind::corner;
    if (at_corner) continue;
    // The frame turns about the edge only, so the two errors add up to 45
    // degrees; the hard rule before features put all of it on one face.
    const double e0 = ff.alignment_error_deg(*faces[0]), e1 = ff.alignment_error_deg(*faces[1]);
    INFO("tetrahedron " << i << ": errors " << e0 << " and " << e1);
    CHECK(e0 + e1 == Approx(45).margin(1e-4));
    CHECK(std::max(e0, e1) < 35);
    ++shared;
  }
  CHECK(shared >= 4); // both chamfer edges, in the 4 layers without a corner
}

TEST_CASE("cylinder: the rims are feature curves without corners, the frames follow them, "
          "and no singular edge runs along the surface at them",
          "[sharp_features][frame_field]") {
  std::vector<Eigen::Vector2d> polygon;
  for (int k = 0; k < 48; ++k) polygon.emplace_back(std::cos(2 * M_PI * k / 48), std::sin(2 * M_PI * k / 48));
  const auto m = mesh_surface(prism(polygon, 1.5), 0.15, 60);
  const Field field(m->tr, Eigen::Matrix3d::Identity().eval());
  const Features features(field, 40);
  std::vector<Tr::Vertex_handle> vertex(m->mesh.vertices.size());
  for (Tr::Vertex_handle v : m->tr.finite_vertex_handles()) vertex[get(Tet_mesh_vertex_index_map<Tr>(), v)] = v;
  REQUIRE(!features.feature_edges().empty());
  for (const Features::Feature_edge& e : features.feature_edges()) {
    const Eigen::Vector3d a = position(vertex[e.source]), b = position(vertex[e.target]);
    // On a rim: both ends at z = 0 or both at z = 1.5 on the polygon's boundary.
    CHECK(a(2) == b(2));
    CHECK((a(2) == 0 || a(2) == 1.5));
    CHECK(std::hypot(a(0), a(1)) > 0.99);
    // Mesh_3's side facets may span the polygon's unprotected 7.5-degree
    // edges: their normals are within a few degrees of radial.
    CHECK(e.angle_deg == Approx(90).margin(3));
  }
  CHECK(features.number_of_corners() == 0);
  CHECK(features.number_of_curve_vertices() == features.feature_edges().size()); // two closed curves

  Frames ff(field);
  ff.compute();
  std::size_t checked = 0;
  for (std::size_t i = 0; i < ff.size(); ++i) {
    const Tr::Cell_handle c = ff.cell(i);
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b)
        if (features.is_feature_edge(ff.vertex_index(c->vertex(a)), ff.vertex_index(c->vertex(b)))) {
          // The curve's smooth tangent is followed: within half the
          // polygon's turn (3.75 degrees) of each edge's own direction.
          CHECK(axis_error_deg(ff.rotation(i), position(c->vertex(b)) - position(c->vertex(a))) < 3.75);
          ++checked;
        }
  }
  CHECK(checked > 100);
  std::vector<char> on_boundary(vertex.size(), 0);
  for (const auto& b : ff.boundary_faces())
    for (int k = 0; k < 4; ++k)
      if (k != b.facet) on_boundary[ff.vertex_index(ff.cell(b.tet)->vertex(k))] = 1;
  std::size_t along = 0;
  for (const Singular_edge& e : singular_edges(ff))
    along += on_boundary[e.vertices[0]] && on_boundary[e.vertices[1]] &&
             (features.kind(e.vertices[0]) != Feature_vertex_kind::none ||
              features.kind(e.vertices[1]) != Feature_vertex_kind::none);
  CHECK(along == 0);
}

TEST_CASE("lone kinks of a coarsely meshed smooth surface are not features", "[sharp_features]") {
  // Mesh_3's torus at its automatic size has a few boundary edges whose
  // facets are more than 40 degrees apart, isolated from each other.
  Tetrahedralize_options o;
  const IO::Medit_mesh mesh = tetrahedralize_builtin("torus", o);
  Tr tr;
  build_triangulation_from_tets(mesh.vertices, mesh.tetrahedra, mesh.tetrahedron_references, tr);
  const Field field(tr, Eigen::Matrix3d::Identity().eval());
  const Features features(field, 40);
  CHECK(features.number_of_dropped_edges() > 0);
  CHECK(features.feature_edges().empty());
  CHECK(features.number_of_corners() == 0);
  // At 20 degrees the kinks join into long curves and are kept.
  CHECK(Features(field, 20).feature_edges().size() > 10);
}

TEST_CASE("spurs: feature curves of fewer than 3 edges that hang from a junction are not features",
          "[sharp_features]") {
  // Gmsh's anchor (CGAL's data/meshes/anchor.off) at a uniform size
  // (data/gmsh_anchor.geo): where its coarsely meshed fillets meet the
  // creases, single facet pairs just beyond 40 degrees branch off them.
  const std::string path = std::string(CGAL_EXT_TEST_DATA_DIR) + "/gmsh_anchor.mesh";
  IO::Medit_mesh mesh;
  Tr tr;
  IO::read_tet_mesh(path, tr, &mesh);
  const Field field(tr, Eigen::Matrix3d::Identity().eval());
  const Features features(field, 40);
  using Graph = std::map<std::size_t, std::vector<std::size_t>>; // the edges at each vertex
  // The edges sharper than 40 degrees, found here from the mesh's boundary
  // facets (those of one tetrahedron, normals away from its fourth vertex).
  std::map<std::array<std::size_t, 3>, std::pair<Eigen::Vector3d, int>> facets;
  auto point = [&](std::size_t v) { return Eigen::Vector3d(mesh.vertices[v][0], mesh.vertices[v][1], mesh.vertices[v][2]); };
  for (const auto& t : mesh.tetrahedra)
    for (int k = 0; k < 4; ++k) {
      std::array<std::size_t, 3> f;
      for (int j = 0, m = 0; j < 4; ++j)
        if (j != k) f[m++] = t[j];
      std::sort(f.begin(), f.end());
      Eigen::Vector3d n = (point(f[1]) - point(f[0])).cross(point(f[2]) - point(f[0])).normalized();
      if (n.dot(point(t[k]) - point(f[0])) > 0) n = -n;
      auto& entry = facets[f];
      entry.first = n, ++entry.second;
    }
  std::map<std::pair<std::size_t, std::size_t>, std::vector<Eigen::Vector3d>> normals_at_edge;
  for (const auto& [f, entry] : facets)
    if (entry.second == 1)
      for (auto [i, j] : {std::pair(0, 1), std::pair(0, 2), std::pair(1, 2)})
        normals_at_edge[{f[i], f[j]}].push_back(entry.first);
  Graph raw, kept;
  for (const auto& [e, n] : normals_at_edge)
    if (n.size() == 2 && n[0].dot(n[1]) < std::cos(40 * M_PI / 180))
      raw[e.first].push_back(e.second), raw[e.second].push_back(e.first);
  for (const auto& e : features.feature_edges()) kept[e.source].push_back(e.target), kept[e.target].push_back(e.source);
  // The free ends whose curve reaches a junction within fewer than 3 edges.
  auto spur_ends = [](Graph& g) {
    std::size_t count = 0;
    for (const auto& [v, nb] : g) {
      if (nb.size() != 1) continue;
      std::size_t previous = v, w = nb[0], length = 1;
      while (g[w].size() == 2 && length < 3) {
        const std::size_t next = g[w][0] == previous ? g[w][1] : g[w][0];
        previous = w, w = next, ++length;
      }
      count += g[w].size() >= 3 && length < 3;
    }
    return count;
  };
  const std::size_t raw_edges = features.feature_edges().size() + features.number_of_dropped_edges();
  std::size_t raw_count = 0;
  for (const auto& [v, nb] : raw) raw_count += nb.size();
  REQUIRE(raw_count / 2 == raw_edges); // the same sharp edges, before the drops
  CHECK(spur_ends(raw) >= 5);
  CHECK(spur_ends(kept) == 0);
  // What is dropped is only those: the creases and their junctions stay.
  CHECK(features.number_of_dropped_edges() < raw_edges / 10);
  CHECK(std::count_if(kept.begin(), kept.end(), [](const auto& v) { return v.second.size() >= 3; }) >= 8);
  for (const auto& [v, nb] : kept) {
    INFO("vertex " << v);
    for (std::size_t w : nb) CHECK(std::find(raw[v].begin(), raw[v].end(), w) != raw[v].end());
  }
}

TEST_CASE("the feature angle must be in [0, 180] degrees", "[sharp_features]") {
  const auto m = mesh_surface(chamfered_box(), 0.3, 60);
  const Field field(m->tr, Eigen::Matrix3d::Identity().eval());
  CHECK_THROWS_AS(Features(field, -1), std::invalid_argument);
  CHECK_THROWS_AS(Features(field, 181), std::invalid_argument);
  CHECK_THROWS_AS(Features(field, std::nan("")), std::invalid_argument);
  // 180: only edges with other than two boundary facets, none on a closed surface.
  CHECK(Features(field, 180).feature_edges().empty());
}
