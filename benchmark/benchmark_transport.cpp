// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Benchmark of the transport between arbitrary points (Metric_transport_3):
// the Magnus scheme against the thesis' trapezoid scheme, in one run.
//
// usage: benchmark_transport [n1 = 12] [n2 = 55] [pairs = 2000] [seed = 1]
//
// Meshes: Kuhn grids of n^3 cubes (6 n^3 tets: n = 12 gives 10,368, n = 55
// gives 998,250) of the box [-0.5, 1]^3, with the smooth metric g = J^T J of
// doc/math.md section 6 sampled at the vertices. Pairs: "neighbour" (b at one
// mean edge length from a, random direction) and "crossing" (a and b uniform
// in the box, so the segment crosses about 2.5 n cells). For each scheme and
// tolerance it reports transports per second (wall time of the TBB batch,
// 1 and 2 threads) and W evaluations per transport, and the ratio of the
// evaluations of Magnus to those of the trapezoid scheme. A third run uses the
// n1 mesh with a rough metric (an independent random SPD tensor per vertex,
// eigenvalues in [0.01, 100]), where each piece turns far more. A last
// section compares where the per-vertex metric lives, on the n1 mesh:
// Metric_field_3 (its own array of roots A) against Property_map_metric_field_3
// reading the user's array of A or of g (a root per read), for the field's
// set-up with precompute() and for crossing transports (Magnus, 1e-8).
#include <CGAL_ext/Metric_field_3.h>
#include <CGAL_ext/Property_map_metric_field_3.h>
#include <CGAL_ext/Metric_transport_3.h>
#include <CGAL_ext/Tet_mesh_triangulation_3.h>
#include <CGAL_ext/build_triangulation_from_tets.h>

#include "kuhn_grid.h"

#include <boost/property_map/property_map.hpp>

#include <tbb/global_control.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

namespace {

using Tr = CGAL_ext::Tet_mesh_triangulation_3<>;
using Point = Tr::Point;
using Field = CGAL_ext::Metric_field_3<Tr>;
using Transport = CGAL_ext::Metric_transport_3<Field>;
using Pairs = std::vector<std::pair<Point, Point>>;

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// doc/math.md section 6.
Eigen::Matrix3d flat_metric(const Point& p) {
  const double x = p.x(), y = p.y(), z = p.z();
  Eigen::Matrix3d J;
  const double c1 = 0.4 * std::cos(y + z), c2 = 0.3 * std::cos(z * x);
  J << 1, c1, c1, c2 * z, 1, c2 * x, 0.5 * std::cos(x), 0, 1;
  return J.transpose() * J;
}

Pairs make_pairs(int n, std::size_t count, bool crossing, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-0.5, 1.0), dir(-1, 1);
  const double edge = 1.5 / n * 1.3; // mean Kuhn edge length: (1 + sqrt2 + sqrt3) / 3 ~ 1.38 h
  Pairs pairs;
  while (pairs.size() < count) {
    const Eigen::Vector3d a(u(rng), u(rng), u(rng));
    Eigen::Vector3d b(u(rng), u(rng), u(rng));
    if (!crossing) {
      Eigen::Vector3d d(dir(rng), dir(rng), dir(rng));
      if (d.norm() < 1e-3) continue;
      b = a + edge * d.normalized();
      if (b.minCoeff() < -0.5 || b.maxCoeff() > 1.0) continue;
    }
    pairs.emplace_back(Point(a(0), a(1), a(2)), Point(b(0), b(1), b(2)));
  }
  return pairs;
}

struct Measure {
  double per_second;
  double evaluations;
  std::size_t failed;
};

template <class Transport_type>
Measure run(const Transport_type& transport, const Pairs& pairs, const CGAL_ext::Transport_options& opt, int threads) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  std::vector<CGAL_ext::Metric_transport_result> out;
  double best = 1e300;
  double total = 0;
  for (int round = 0; round < 3 && total < 2; ++round) { // best of 3, or of fewer if slow
    const auto t0 = std::chrono::steady_clock::now();
    transport.transport_batch(pairs, opt, out);
    const double t = seconds_since(t0);
    best = std::min(best, t);
    total += t;
  }
  std::size_t evaluations = 0, failed = 0;
  for (const auto& r : out) {
    evaluations += r.evaluations;
    failed += !r.ok;
  }
  return {double(pairs.size()) / best, double(evaluations) / double(pairs.size()), failed};
}

// The per-vertex metric in Metric_field_3 and in the user's arrays read
// through Property_map_metric_field_3: set-up and transport throughput.
void compare_metric_storage(int n, std::size_t npairs, unsigned seed) {
  using Array_map = boost::iterator_property_map<std::vector<Eigen::Matrix3d>::iterator,
                                                 CGAL_ext::Tet_mesh_vertex_index_map<Tr>>;
  using Map_field = CGAL_ext::Property_map_metric_field_3<Tr, Array_map>;
  std::vector<std::array<double, 3>> points;
  std::vector<std::array<std::size_t, 4>> tets;
  benchmark_support::kuhn_grid(n, -0.5, 1.5 / n, points, tets);
  Tr tr;
  CGAL_ext::build_triangulation_from_tets(points, tets, {}, tr);
  std::vector<Eigen::Matrix3d> g(points.size()), A(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    g[i] = flat_metric(Point(points[i][0], points[i][1], points[i][2]));
    A[i] = CGAL_ext::sqrt_spd(g[i]);
  }
  const Pairs pairs = make_pairs(n, std::max<std::size_t>(npairs / 10, 1), true, seed);
  CGAL_ext::Transport_options opt;
  opt.tolerance = 1e-8;
  std::printf("\nwhere the per-vertex metric lives (%zu tets, smooth metric, %zu crossing pairs, magnus 1e-8, 1 thread):\n"
              "%-44s %12s %14s %8s\n",
              tets.size(), pairs.size(), "field", "set-up s", "transports /s", "ratio");
  double reference = 0;
  const auto report = [&](const char* name, double setup, const Measure& m) {
    if (reference == 0) reference = m.per_second;
    std::printf("%-44s %12.3f %14.0f %8.3f\n", name, setup, m.per_second, m.per_second / reference);
    std::fflush(stdout);
  };
  {
    const auto t0 = std::chrono::steady_clock::now();
    const Field field(tr, g);
    field.precompute();
    const double setup = seconds_since(t0);
    report("Metric_field_3 (stores A, from g)", setup, run(CGAL_ext::Metric_transport_3<Field>(field), pairs, opt, 1));
  }
  for (const bool roots : {true, false}) {
    const auto t0 = std::chrono::steady_clock::now();
    const Map_field field(tr, Array_map(roots ? A.begin() : g.begin()),
                          roots ? CGAL_ext::Vertex_metric_kind::sqrt_metric : CGAL_ext::Vertex_metric_kind::metric);
    field.precompute();
    const double setup = seconds_since(t0);
    report(roots ? "Property_map_metric_field_3, user's array of A" : "Property_map_metric_field_3, user's array of g",
           setup, run(CGAL_ext::Metric_transport_3<Map_field>(field), pairs, opt, 1));
  }
}

} // namespace

int main(int argc, char** argv) {
  const int n1 = argc > 1 ? std::atoi(argv[1]) : 12;
  const int n2 = argc > 2 ? std::atoi(argv[2]) : 55;
  const std::size_t npairs = argc > 3 ? std::size_t(std::atol(argv[3])) : 2000;
  const unsigned seed = argc > 4 ? unsigned(std::atoi(argv[4])) : 1;
  if (n1 < 1 || n2 < 1 || npairs < 1) {
    std::fprintf(stderr, "usage: benchmark_transport [n1 = 12] [n2 = 55] [pairs = 2000] [seed = 1]\n");
    return 2;
  }
  std::printf("Transport T(a->b) of the doc/math.md section 6 metric on Kuhn grids of [-0.5, 1]^3; %zu pairs per class\n"
              "(crossing: %zu; 20x fewer on the rough metric); wall time of the TBB batch, best of up to 3;\n"
              "W evaluations per transport.\n\n",
              npairs, std::max<std::size_t>(npairs / 10, 1));
  std::printf("%9s %-10s %-10s %7s %14s %14s %10s %9s\n", "tets", "pairs", "scheme", "tol", "1 thread /s",
              "2 threads /s", "W evals", "failed");
  for (const int run_index : {0, 1, 2}) {
    const int n = run_index == 1 ? n2 : n1;
    const bool rough = run_index == 2;
    std::vector<std::array<double, 3>> points;
    std::vector<std::array<std::size_t, 4>> tets;
    benchmark_support::kuhn_grid(n, -0.5, 1.5 / n, points, tets);
    Tr tr;
    const auto t0 = std::chrono::steady_clock::now();
    CGAL_ext::build_triangulation_from_tets(points, tets, {}, tr);
    std::vector<Eigen::Matrix3d> metrics(points.size());
    std::mt19937_64 rng(seed + 7);
    std::uniform_real_distribution<double> u(-1, 1), log_eig(std::log(0.01), std::log(100.0));
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (!rough) {
        metrics[i] = flat_metric(Point(points[i][0], points[i][1], points[i][2]));
        continue;
      }
      const Eigen::Matrix3d Q = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().toRotationMatrix();
      const Eigen::Vector3d l(std::exp(log_eig(rng)), std::exp(log_eig(rng)), std::exp(log_eig(rng)));
      metrics[i] = Q * l.asDiagonal() * Q.transpose();
    }
    const Field field(tr, metrics);
    field.precompute();
    const double setup = seconds_since(t0);
    const Transport transport(field);
    std::fprintf(stderr, "[stage] mesh n = %d: %zu tets, triangulation and %s metric field in %.2f s\n", n,
                 tets.size(), rough ? "rough" : "smooth", setup);
    if (rough) std::printf("rough metric (random SPD per vertex, eigenvalues in [0.01, 100]):\n");
    for (const bool crossing : {false, true}) {
      // The trapezoid scheme is ~100x slower on the rough metric: fewer pairs there.
      const std::size_t count = std::max<std::size_t>(npairs / (crossing ? 10 : 1) / (rough ? 20 : 1), 1);
      const Pairs pairs = make_pairs(n, count, crossing, seed);
      double evals_1e8[2] = {0, 0};
      for (const double tol : {1e-6, 1e-8, 1e-10})
        for (const auto scheme : {CGAL_ext::Transport_scheme::trapezoid, CGAL_ext::Transport_scheme::magnus}) {
          CGAL_ext::Transport_options opt;
          opt.scheme = scheme;
          opt.tolerance = tol;
          const Measure m1 = run(transport, pairs, opt, 1), m2 = run(transport, pairs, opt, 2);
          const bool magnus = scheme == CGAL_ext::Transport_scheme::magnus;
          if (tol == 1e-8) evals_1e8[magnus] = m1.evaluations;
          std::printf("%9zu %-10s %-10s %7.0e %14.0f %14.0f %10.1f %9zu\n", tets.size(),
                      crossing ? "crossing" : "neighbour", magnus ? "magnus" : "trapezoid", tol, m1.per_second,
                      m2.per_second, m1.evaluations, m1.failed);
          std::fflush(stdout);
        }
      std::printf("%9zu %-10s magnus / trapezoid W evaluations at tol 1e-8: %.3f (1/%.1f)\n", tets.size(),
                  crossing ? "crossing" : "neighbour", evals_1e8[1] / evals_1e8[0], evals_1e8[0] / evals_1e8[1]);
    }
  }
  compare_metric_storage(n1, npairs, seed);
  return 0;
}
