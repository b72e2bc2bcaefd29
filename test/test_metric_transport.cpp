// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
// Transport between arbitrary points (Metric_transport_3): exactness for a
// constant metric; the order of composition (doc/math.md section 4) on one cell
// split in two; reversal and composition; the tolerance against an
// independent reference (exact pieces from the brute-force rational simplex
// reference, A and the curls recomputed here from the tets with the 4x4
// barycentric matrix of doc/math.md section 2, the averaged curls of section 4,
// RK4 with the 9x9 solve for W); leaving a non-convex domain; determinism of
// the threaded batch; and convergence to the analytic transport of doc/math.md
// section 6 under refinement.
#include <CGAL_ext/Connection_3.h>
#include <CGAL_ext/Metric_field_3.h>
#include <CGAL_ext/Metric_tensor.h>
#include <CGAL_ext/Metric_transport_3.h>
#include <CGAL_ext/Tet_mesh_triangulation_3.h>
#include <CGAL_ext/build_triangulation_from_tets.h>

#include <catch2/catch.hpp>

#include "reference/Exact_simplex_reference_3.h"
#include "reference/degenerate_test_meshes.h"
#include "test_support.h"

#include <Eigen/LU>

#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iterator>
#include <memory>
#include <vector>

namespace {

using namespace CGAL_ext;
using namespace CGAL_ext::testing;
using CGAL_ext::testing::M3;
using CGAL_ext::testing::Random;
using CGAL_ext::testing::V3;
using Tr = Tet_mesh_triangulation_3<>;
using Point = Tr::Point;
using Field = Metric_field_3<Tr>;
using Transport = Metric_transport_3<Field>;

V3 vec(const std::array<double, 3>& p) { return V3(p[0], p[1], p[2]); }
V3 vec(const Point& p) { return V3(p.x(), p.y(), p.z()); }
Point point(const std::array<double, 3>& p) { return Point(p[0], p[1], p[2]); }
Point point(const V3& p) { return Point(p(0), p(1), p(2)); }

double distance(const M3& P, const M3& Q) { return rotation_angle(P.transpose() * Q); }

// A mesh, its triangulation and a field built from one metric per vertex.
struct Setup {
  Test_mesh mesh;
  std::vector<M3> metrics; // per vertex
  Tr tr;
  std::unique_ptr<Field> field;

  Setup(Test_mesh m, std::vector<M3> g) : mesh(std::move(m)), metrics(std::move(g)) {
    build_triangulation_from_tets(mesh.points, mesh.tets, {}, tr);
    field = std::make_unique<Field>(tr, metrics);
  }
};

// Random SPD metrics per vertex: a rough PL field with large rotations.
std::vector<M3> random_metrics(std::size_t n, unsigned seed) {
  Random r(seed);
  std::vector<M3> g(n);
  for (auto& x : g) x = r.spd(0.2, 5);
  return g;
}

// ---------------------------------------------------------------- reference
// The PL field recomputed from the mesh alone: A = sqrt(g) per vertex, and in
// each tet the 4x4 barycentric matrix lambda = T [x; 1], d_k A = sum_v T(v, k) A_v
// (doc/math.md section 2), independently of Metric_field_3.
struct Reference_field {
  const Test_mesh* mesh;
  std::vector<M3> A;                    // per vertex
  std::vector<Eigen::Matrix4d> T;       // per tet
  std::vector<M3> curl;                 // per tet

  Reference_field(const Test_mesh& m, const std::vector<M3>& g) : mesh(&m) {
    for (const M3& x : g) A.push_back(sqrt_spd(x));
    for (const auto& t : m.tets) {
      Eigen::Matrix4d P;
      for (int v = 0; v < 4; ++v) P.col(v) << vec(m.points[t[v]]), 1;
      T.push_back(P.inverse());
      std::array<M3, 3> dA;
      for (int k = 0; k < 3; ++k) {
        dA[k].setZero();
        for (int v = 0; v < 4; ++v) dA[k] += T.back()(v, k) * A[t[v]];
      }
      M3 c;
      for (int i = 0; i < 3; ++i)
        c.col(i) = V3(dA[1](2, i) - dA[2](1, i), dA[2](0, i) - dA[0](2, i), dA[0](1, i) - dA[1](0, i));
      curl.push_back(c);
    }
  }
  M3 A_at(std::size_t tet, const V3& x) const {
    const Eigen::Vector4d l = T[tet] * Eigen::Vector4d(x(0), x(1), x(2), 1);
    M3 r = M3::Zero();
    for (int v = 0; v < 4; ++v) r += l(v) * A[mesh->tets[tet][v]];
    return r;
  }
};

// The interior dihedral angle of tet t at its edge (u, v), from the points.
double dihedral(const Test_mesh& m, const std::array<std::size_t, 4>& t, std::size_t u, std::size_t v) {
  std::vector<std::size_t> w;
  for (auto x : t)
    if (x != u && x != v) w.push_back(x);
  const V3 o = vec(m.points[u]), e = vec(m.points[v]) - o;
  const V3 n1 = e.cross(vec(m.points[w[0]]) - o), n2 = e.cross(vec(m.points[w[1]]) - o);
  return std::atan2(n1.cross(n2).norm(), n1.dot(n2));
}

// Classical RK4 on R' = [u]_x R over [0, 1] with n fixed steps.
template <class Generator>
M3 rk4(Generator&& u, int n) {
  M3 R = M3::Identity();
  const double h = 1.0 / n;
  for (int i = 0; i < n; ++i) {
    const double t = i * h;
    const V3 u0 = u(t), um = u(t + h / 2), u1 = u(t + h);
    const M3 k1 = cross_product_matrix(u0) * R;
    const M3 k2 = cross_product_matrix(um) * (R + h / 2 * k1);
    const M3 k3 = cross_product_matrix(um) * (R + h / 2 * k2);
    const M3 k4 = cross_product_matrix(u1) * (R + h * k3);
    R += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
  }
  return R;
}

// The reference transport of the PL field along [q, p]: the pieces of the
// exact reference, the averaged curls of doc/math.md section 4 from the tets that
// contain each piece's simplex (found by brute force), and RK4 with `steps`
// steps per piece, W by the 9x9 solve. Counts the pieces by dimension.
// Returns false if the segment has a gap.
bool reference_transport(const Reference_field& f, const std::vector<Reference_piece>& pieces, const V3& q,
                         const V3& p, int steps, M3& R, std::array<std::size_t, 4>* dims = nullptr) {
  const Test_mesh& m = *f.mesh;
  R = M3::Identity();
  for (const Reference_piece& piece : pieces) {
    if (piece.dimension < 0) return false;
    if (!(piece.t_out > piece.t_in)) continue;
    std::vector<std::size_t> tets; // the tets having the piece's simplex as a face
    for (std::size_t t = 0; t < m.tets.size(); ++t) {
      const auto& tv = m.tets[t];
      if (std::all_of(piece.vertices.begin(), piece.vertices.end(),
                      [&](std::size_t v) { return std::find(tv.begin(), tv.end(), v) != tv.end(); }))
        tets.push_back(t);
    }
    REQUIRE(!tets.empty());
    if (dims) ++(*dims)[std::size_t(piece.dimension)];
    M3 curl = M3::Zero();
    double weight = 0;
    for (std::size_t t : tets) {
      const double w = piece.dimension == 1 ? dihedral(m, m.tets[t], piece.vertices[0], piece.vertices[1]) : 1.0;
      curl += w * f.curl[t];
      weight += w;
    }
    curl /= weight;
    const double t0 = CGAL::to_double(piece.t_in), t1 = CGAL::to_double(piece.t_out);
    const V3 x0 = q + t0 * (p - q), x1 = q + t1 * (p - q);
    // A is continuous: any tet of the simplex gives the same A on it.
    const M3 A0 = f.A_at(tets[0], x0), A1 = f.A_at(tets[0], x1);
    R = rk4([&](double t) { return V3(connection_one_form_by_solve(A0 + t * (A1 - A0), curl).transpose() * (x1 - x0)); },
            steps) *
        R;
  }
  return true;
}

} // namespace

TEST_CASE("a constant metric gives exactly the identity on every segment", "[metric_transport]") {
  const M3 g = Random(3).spd(0.1, 10);
  for (const Test_mesh& m : {jittered_kuhn_grid(3, 11), l_shape_grid(4)}) {
    const Setup s(m, std::vector<M3>(m.points.size(), g));
    const Transport transport(*s.field);
    std::size_t inside = 0, degenerate = 0;
    for (const Test_segment& seg : degenerate_segments(s.mesh, 800, 5)) {
      for (const Transport_scheme scheme : {Transport_scheme::magnus, Transport_scheme::trapezoid}) {
        Transport_options opt;
        opt.scheme = scheme;
        const Metric_transport_result r = transport(point(seg.q), point(seg.p), opt);
        if (!r.ok) continue;
        ++inside;
        INFO(m.name << " " << seg.kind);
        CHECK(r.rotation == M3::Identity());
        CHECK(r.angle == 0);
        CHECK(r.error_estimate == 0);
      }
      std::vector<Transport::Piece> pieces;
      transport.walk().fast(point(seg.q), point(seg.p), std::back_inserter(pieces));
      degenerate += std::any_of(pieces.begin(), pieces.end(), [](const auto& p) { return p.dimension == 1 || p.dimension == 2; });
    }
    CHECK(inside > 200);
    CHECK(degenerate > 50); // segments along edges and inside facets were among them
  }
}

TEST_CASE("pieces compose left-multiplied in path order: one cell split in two halves", "[metric_transport]") {
  // A segment inside one tet: T(a->c) of the transporter is the one-piece
  // cell integration, and equals T(b->c) T(a->b) for the midpoint b (doc/math.md
  // section 4), not T(a->b) T(b->c).
  const Test_mesh m = jittered_kuhn_grid(2, 7);
  const Setup s(m, random_metrics(m.points.size(), 13));
  const Transport transport(*s.field);
  Transport_options opt;
  opt.tolerance = 1e-11;
  Random r(5);
  std::size_t non_commuting = 0;
  for (Tr::Cell_handle c : s.tr.finite_cell_handles()) {
    if (!c->info().in_domain()) continue;
    V3 p[4];
    for (int v = 0; v < 4; ++v) p[v] = vec(c->vertex(v)->point());
    auto inner = [&] {
      double w[4], sum = 0;
      for (double& x : w) sum += (x = r.uniform(0.05, 1));
      V3 x = V3::Zero();
      for (int v = 0; v < 4; ++v) x += w[v] / sum * p[v];
      return x;
    };
    const V3 a = inner(), cc = inner(), b = 0.5 * (a + cc);
    const auto ac = transport(point(a), point(cc), opt), ab = transport(point(a), point(b), opt),
               bc = transport(point(b), point(cc), opt);
    REQUIRE(ac.ok);
    REQUIRE(ac.pieces == 1);
    const M3 cell = cell_transport(*s.field, c, point(a), point(cc), opt).rotation;
    CHECK(distance(ac.rotation, cell) <= 2 * opt.tolerance);
    CHECK(distance(bc.rotation * ab.rotation, ac.rotation) <= 3 * opt.tolerance);
    if ((ab.rotation * bc.rotation - bc.rotation * ab.rotation).norm() > 1e-6) {
      ++non_commuting;
      CHECK(distance(ab.rotation * bc.rotation, ac.rotation) > 100 * opt.tolerance);
    }
  }
  CHECK(non_commuting > 20);
}

TEST_CASE("reversal and composition hold within the tolerance", "[metric_transport]") {
  const Test_mesh m = jittered_kuhn_grid(3, 5);
  const Setup s(m, random_metrics(m.points.size(), 29));
  const Transport transport(*s.field);
  for (const Transport_scheme scheme : {Transport_scheme::magnus, Transport_scheme::trapezoid}) {
    Transport_options opt;
    opt.scheme = scheme;
    opt.tolerance = scheme == Transport_scheme::magnus ? 1e-9 : 1e-8; // the trapezoid scheme is slow at 1e-9
    std::size_t checked = 0, multi = 0;
    for (const Test_segment& seg : degenerate_segments(m, 500, 31)) {
      // b on [a, c]: at 3/8 (exact in binary) of the way.
      const V3 a = vec(seg.q), c = vec(seg.p), b = a + 0.375 * (c - a);
      const auto ac = transport(point(a), point(c), opt);
      if (!ac.ok) continue;
      INFO(seg.kind);
      const auto ca = transport(point(c), point(a), opt);
      const auto ab = transport(point(a), point(b), opt), bc = transport(point(b), point(c), opt);
      REQUIRE(ca.ok);
      REQUIRE(ab.ok);
      REQUIRE(bc.ok);
      CHECK(distance(ca.rotation, ac.rotation.transpose()) <= 2 * opt.tolerance);
      CHECK(distance(bc.rotation * ab.rotation, ac.rotation) <= 3 * opt.tolerance);
      // The other order is not the composition (doc/math.md section 4) unless the
      // rotations commute: this is what makes the check above meaningful.
      if (ab.angle > 1e-3 && bc.angle > 1e-3 && (ab.rotation * bc.rotation - bc.rotation * ab.rotation).norm() > 1e-6) {
        CHECK(distance(ab.rotation * bc.rotation, ac.rotation) > 10 * opt.tolerance);
        ++multi;
      }
      ++checked;
    }
    CHECK(checked > 50);
    CHECK(multi > 20);
  }
}

// Transports of the segments on mesh m (random metrics) against the
// reference, at each tolerance and with both schemes; counts the pieces
// compared by dimension, prints a summary and returns the number of
// transports compared.
std::size_t compare_with_reference(const Test_mesh& m, const std::vector<Test_segment>& segments,
                                   std::array<std::size_t, 4>& all_dims, std::initializer_list<double> tolerances) {
  const std::vector<M3> g = random_metrics(m.points.size(), 17);
  const Setup s(m, g);
  const Reference_field ref_field(m, g);
  const Transport transport(*s.field);
  const auto reference = make_exact_simplex_reference(s.tr, Is_tet_mesh_domain_cell(),
                                                      [](Tr::Vertex_handle v) { return v->info(); });
  std::size_t compared = 0, gaps = 0;
  std::array<std::size_t, 4> dims{};
  double worst_ratio = 0;
  for (const Test_segment& seg : segments) {
    INFO(m.name << " " << seg.kind);
    const V3 q = vec(seg.q), p = vec(seg.p);
    M3 ref;
    const auto pieces = reference(seg.q, seg.p);
    const bool inside = reference_transport(ref_field, pieces, q, p, 1024, ref, &dims);
    if (inside) { // RK4 is converged far below the smallest tolerance
      M3 finer;
      reference_transport(ref_field, pieces, q, p, 2048, finer);
      INFO("reference\n" << ref << "\nfiner\n" << finer << "\npieces\n" << to_string(pieces));
      REQUIRE(distance(ref, finer) <= 1e-10);
    }
    for (const Transport_scheme scheme : {Transport_scheme::magnus, Transport_scheme::trapezoid})
      for (const double tol : tolerances) {
        Transport_options opt;
        opt.scheme = scheme;
        opt.tolerance = tol;
        const Metric_transport_result r = transport(point(q), point(p), opt);
        REQUIRE(r.ok == inside);
        if (!inside) {
          CHECK(!r.message.empty());
          CHECK(r.rotation == M3::Identity());
          continue;
        }
        const double err = distance(r.rotation, ref);
        INFO("scheme " << int(scheme) << " tol " << tol << " error " << err << " estimate " << r.error_estimate);
        CHECK(err <= tol);
        CHECK(r.error_estimate <= tol);
        worst_ratio = std::max(worst_ratio, err / tol);
        CHECK(r.converged);
        ++compared;
      }
    gaps += !inside;
  }
  std::printf("%-24s %4zu transports compared (pieces: %zu edge, %zu facet, %zu cell), %3zu segments with a gap, "
              "worst error / tol %.3f\n",
              m.name.c_str(), compared, dims[1], dims[2], dims[3], gaps, worst_ratio);
  for (int d : {1, 2, 3}) all_dims[std::size_t(d)] += dims[std::size_t(d)];
  return compared;
}

TEST_CASE("the tolerance is honoured against an independent reference, on degenerate segments",
          "[metric_transport]") {
  // Kuhn grid, jittered Kuhn grid, the L-shape (gaps, re-entrant edge) and
  // two blocks touching along an edge (a non-manifold edge, whose curl
  // average takes the cells of both blocks).
  const Test_mesh meshes[] = {kuhn_grid(3, 3, 3), jittered_kuhn_grid(3, 7), l_shape_grid(4),
                              edge_touching_blocks(2)};
  std::array<std::size_t, 4> all_dims{};
  for (const Test_mesh& m : meshes) {
    const bool touching = m.name.rfind("edge_touching", 0) == 0; // most of its segments have gaps
    std::vector<Test_segment> segments = degenerate_segments(m, touching ? 300 : 150, 23);
    if (touching) // along the shared edge x = y = 6, and across it
      segments.insert(segments.begin(), {{{6, 6, 0}, {6, 6, 12}, "shared-edge"},
                                         {{6, 6, 3}, {6, 6, 9}, "shared-edge-inner"},
                                         {{3, 3, 2}, {9, 9, 7}, "through-shared-edge"}});
    CHECK(compare_with_reference(m, segments, all_dims, {1e-4, 1e-6, 1e-8}) >= 6 * 30);
  }
  CHECK(all_dims[1] >= 50); // edge pieces were compared
  CHECK(all_dims[2] >= 50); // facet pieces were compared
}

// Segments degenerate up to rounding (along edge lines and in facet planes,
// end points rounded to double) on meshes written by Gmsh and TetGen: the
// crossing parameters are exact to 1e-12, so the transport integrates each
// cell's curl over the right stretch and meets its tolerance.
TEST_CASE("the tolerance is honoured on segments degenerate up to rounding, on Gmsh and TetGen meshes",
          "[metric_transport]") {
  std::array<std::size_t, 4> all_dims{};
  for (const char* file : {"gmsh_box_with_hole.mesh", "tetgen_cube.mesh"}) {
    const Test_mesh m = medit_test_mesh(file);
    CHECK(compare_with_reference(m, rounded_degenerate_segments(m, 240, 67), all_dims, {1e-6, 1e-9}) >= 4 * 40);
  }
  CHECK(all_dims[2] >= 100); // facet pieces were compared
}

TEST_CASE("leaving a non-convex domain, or starting outside, is an error, never a rotation", "[metric_transport]") {
  // l_shape_grid(4): cubes of side 6 in [0, 24]^3 without those with x, y >= 12.
  const Test_mesh m = l_shape_grid(4);
  const Setup s(m, random_metrics(m.points.size(), 41));
  const Transport transport(*s.field);
  // Through the notch: leaves at x + y = ... the plane y = 12 at t = 3/7, comes back at x = 12, t = 4/7.
  const auto across = transport(Point(20, 6, 5), Point(6, 20, 5));
  CHECK(!across.ok);
  CHECK(across.message == "the segment leaves the domain at t = 0.428571 and re-enters it at t = 0.571429");
  CHECK(across.exit_t == Approx(3.0 / 7).epsilon(1e-14));
  CHECK(across.rotation == M3::Identity());
  CHECK(across.evaluations == 0);
  const auto from_outside = transport(Point(20, 20, 5), Point(6, 6, 5));
  CHECK(!from_outside.ok);
  CHECK(from_outside.message == "the start point is outside the domain");
  CHECK(from_outside.exit_t == 0);
  const auto to_outside = transport(Point(6, 6, 5), Point(20, 20, 5));
  CHECK(!to_outside.ok);
  CHECK(to_outside.message == "the end point is outside the domain (the segment leaves the domain at t = 0.428571)");
  const auto far = transport(Point(6, 6, 5), Point(6, 6, 500));
  CHECK(!far.ok);
  CHECK(far.message.find("the end point is outside the domain") == 0);
  // A gap fails the segment before anything is integrated, however far out
  // the end point (the in-domain stretch of a pair reaching 1e150 used to be
  // integrated at a tolerance share below what double resolves).
  CHECK(to_outside.evaluations == 0);
  CHECK(far.evaluations == 0);
  const auto very_far = transport(Point(6, 6, 5), Point(-2, 10, 1e150));
  CHECK(!very_far.ok);
  CHECK(very_far.evaluations == 0);
  CHECK(very_far.message.find("the end point is outside the domain") == 0);
  // Along the re-entrant edge x = y = 12 (on the boundary, inside the closed domain): fine.
  const auto along = transport(Point(12, 12, 1), Point(12, 12, 23));
  CHECK(along.ok);
  CHECK(along.pieces >= 4);
  CHECK(along.angle > 0);
  // Non-finite input is an error result; an invalid tolerance is a misuse.
  const double nan = std::nan(""), inf = HUGE_VAL;
  CHECK(transport(Point(nan, 0, 0), Point(1, 1, 1)).message == "a coordinate is not finite");
  CHECK(!transport(Point(1, 1, 1), Point(1, inf, 1)).ok);
  Transport_options bad;
  bad.tolerance = 0;
  CHECK_THROWS_AS(transport(Point(1, 1, 1), Point(2, 2, 2), bad), std::invalid_argument);
  bad.tolerance = nan;
  std::vector<Metric_transport_result> out;
  CHECK_THROWS_AS(transport.transport_batch(std::vector<std::pair<Point, Point>>(1), bad, out), std::invalid_argument);
}

TEST_CASE("the batch is bit-identical for 1 and 2 threads and to single transports", "[metric_transport]") {
  const Test_mesh m = jittered_kuhn_grid(4, 3);
  const Setup s(m, random_metrics(m.points.size(), 43));
  s.field->precompute();
  const Transport transport(*s.field);
  std::vector<std::pair<Point, Point>> pairs;
  for (const Test_segment& seg : degenerate_segments(m, 600, 47)) pairs.emplace_back(point(seg.q), point(seg.p));
  for (const Transport_scheme scheme : {Transport_scheme::magnus, Transport_scheme::trapezoid}) {
    Transport_options opt;
    opt.scheme = scheme;
    opt.tolerance = scheme == Transport_scheme::magnus ? 1e-8 : 1e-6;
    std::vector<Metric_transport_result> one, two;
    {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
      transport.transport_batch(pairs, opt, one);
    }
    {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
      transport.transport_batch(pairs, opt, two);
    }
    REQUIRE(one.size() == pairs.size());
    REQUIRE(two.size() == pairs.size());
    std::size_t ok = 0;
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      const auto single = transport(pairs[i].first, pairs[i].second, opt);
      CHECK(one[i].ok == two[i].ok);
      CHECK(one[i].message == two[i].message);
      CHECK(one[i].ok == single.ok);
      CHECK(one[i].message == single.message);
      for (int k = 0; k < 9; ++k) { // exact equality of all 9 entries
        CHECK(one[i].rotation.data()[k] == two[i].rotation.data()[k]);
        CHECK(one[i].rotation.data()[k] == single.rotation.data()[k]);
      }
      CHECK(one[i].evaluations == two[i].evaluations);
      CHECK(one[i].evaluations == single.evaluations);
      ok += one[i].ok;
    }
    CHECK(ok > 100);
  }
}

namespace {

// Least-squares slope of log(error) against log(h).
double observed_order(const std::vector<double>& hs, const std::vector<double>& errors) {
  double mx = 0, my = 0;
  const double n = double(hs.size());
  for (std::size_t i = 0; i < hs.size(); ++i) mx += std::log(hs[i]) / n, my += std::log(errors[i]) / n;
  double sxy = 0, sxx = 0;
  for (std::size_t i = 0; i < hs.size(); ++i) {
    sxy += (std::log(hs[i]) - mx) * (std::log(errors[i]) - my);
    sxx += (std::log(hs[i]) - mx) * (std::log(hs[i]) - mx);
  }
  return sxy / sxx;
}

// The doc/math.md section 6 convergence table on meshes of [-0.5, 1]^3 with n^3
// cubes; returns the max error over the pairs per level.
template <class Make_mesh>
std::vector<double> convergence_table(const char* title, Make_mesh make_mesh) {
  namespace flat = CGAL_ext::testing::flat_metric;
  // Fixed pairs in the box; the first is the one of doc/math.md section 6.
  const std::pair<V3, V3> pairs[] = {{V3(0.1, 0.2, -0.3), V3(0.9, -0.4, 0.5)},
                                     {V3(-0.4, -0.3, 0.9), V3(0.8, 0.7, -0.2)},
                                     {V3(0.0, 0.5, 0.5), V3(0.6, -0.2, 0.1)},
                                     {V3(-0.35, 0.85, -0.35), V3(0.85, -0.35, 0.85)}};
  std::printf("\n%s, tol 1e-11;\nerror = angle between T(a->b) and Q(b)^T Q(a), for %zu fixed pairs, and their max\n",
              title, std::size(pairs));
  std::printf("%6s %10s %11s %11s %11s %11s %11s %8s\n", "n", "tets", "pair 1", "pair 2", "pair 3", "pair 4",
              "max error", "order");
  std::vector<double> errors;
  for (const int n : {4, 8, 16, 32}) {
    const Test_mesh m = make_mesh(n);
    std::vector<M3> g;
    for (const auto& p : m.points) {
      REQUIRE(flat::jacobian(vec(p)).determinant() > 0.2); // Phi is a diffeomorphism around the box
      g.push_back(flat::metric(vec(p)));
    }
    const Setup s(m, g);
    const Transport transport(*s.field);
    Transport_options opt;
    opt.tolerance = 1e-11;
    double worst = 0;
    std::printf("%6d %10zu", n, m.tets.size());
    for (const auto& [a, b] : pairs) {
      const auto r = transport(point(a), point(b), opt);
      REQUIRE(r.ok);
      CHECK(r.converged);
      const M3 exact = flat::polar_rotation(b).transpose() * flat::polar_rotation(a);
      const double e = distance(r.rotation, exact);
      std::printf(" %11.3e", e);
      worst = std::max(worst, e);
    }
    errors.push_back(worst);
    const double order = errors.size() > 1 ? std::log2(errors[errors.size() - 2] / errors.back()) : 0;
    std::printf(" %11.3e %8.2f\n", worst, order);
  }
  return errors;
}

} // namespace

TEST_CASE("doc/math.md section 6: the PL transport converges to Q(b)^T Q(a) under refinement", "[metric_transport]") {
  const std::vector<double> hs = {1.5 / 4, 1.5 / 8, 1.5 / 16, 1.5 / 32};
  const std::vector<double> kuhn =
      convergence_table("Convergence to the analytic transport (doc/math.md section 6), Kuhn grids of [-0.5, 1]^3", [](int n) {
        return transformed(kuhn_grid(n, n, n, 1.5 / n), {1, 1, 1}, {-0.5, -0.5, -0.5}, "");
      });
  const double kuhn_order = observed_order(hs, kuhn);
  std::printf("least-squares observed order (max error): %.2f\n", kuhn_order);
  // On the translation-invariant Kuhn grid the O(h) error of the PL curl
  // oscillates with the grid and cancels along a segment that crosses many
  // cells, leaving O(h^2): the observed order is about 2. Ask for a decrease
  // at every level and an overall order above 1.5 (a first-order error would
  // give 1).
  for (std::size_t i = 1; i < kuhn.size(); ++i) CHECK(kuhn[i] < kuhn[i - 1]);
  CHECK(kuhn_order > 1.5);

  // Jittered grids (vertices moved by up to 1/4 of the spacing): the
  // cancellation is lost, and doc/math.md section 6's "about first order" is what
  // remains. Reported, and only checked to converge.
  const std::vector<double> jittered = convergence_table(
      "The same on jittered Kuhn grids (vertices moved by up to h/4)", [](int n) {
        return transformed(jittered_kuhn_grid(n, 1000 + unsigned(n)), {1.5 / (6 * n), 1.5 / (6 * n), 1.5 / (6 * n)},
                           {-0.5, -0.5, -0.5}, "");
      });
  const double jittered_order = observed_order(hs, jittered);
  std::printf("least-squares observed order (max error): %.2f\n", jittered_order);
  CHECK(jittered.back() < jittered.front() / 4);
}
