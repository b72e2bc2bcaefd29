// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Benchmark of building a Tet_mesh_triangulation_3 from tetrahedra
// (build_triangulation_from_tets), and of the share of it that the exact
// overlap tests take (internal/Tet_mesh_overlap.h), each timed on its own
// with the same input: the boundary facets meeting, the wedges about the
// edges, the boundary vertices inside tetrahedra. The reference is the whole
// build, of which the tests are a part.
//
// usage: benchmark_mesh_input [n = 55] [jitter = 0.15] [repeats = 3]
//        benchmark_mesh_input FILE.mesh [repeats = 3]
//
// Mesh: a Medit file (read once, not timed), or a Kuhn grid of n^3 unit
// cubes (6 n^3 tets: n = 55 gives 998,250) whose interior vertices are moved
// by up to `jitter` in each coordinate
// (0: the exact grid, where many predicates are degenerate and fall back to
// exact arithmetic). Times are the median of `repeats` runs.
#include <CGAL_ext/IO/Medit_mesh.h>
#include <CGAL_ext/Tet_mesh_triangulation_3.h>
#include <CGAL_ext/build_triangulation_from_tets.h>
#include <CGAL_ext/internal/Tet_mesh_overlap.h>

#include "kuhn_grid.h"
#include "run_reporting_errors.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

namespace {

using Tr = CGAL_ext::Tet_mesh_triangulation_3<>;

double median_seconds(int repeats, const std::function<void()>& f) {
  std::vector<double> t;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

} // namespace

static int run(int argc, char** argv) {
  const bool from_file = argc > 1 && std::string(argv[1]).find(".mesh") != std::string::npos;
  const int n = argc > 1 && !from_file ? std::atoi(argv[1]) : 55;
  const double jitter = argc > 2 && !from_file ? std::atof(argv[2]) : 0.15;
  const int repeats = std::max(1, from_file ? (argc > 2 ? std::atoi(argv[2]) : 3) : (argc > 3 ? std::atoi(argv[3]) : 3));
  if (n < 1) {
    std::fprintf(stderr, "usage: benchmark_mesh_input [n >= 1] [jitter] [repeats]\n"
                         "       benchmark_mesh_input FILE.mesh [repeats]\n");
    return 2;
  }
  std::vector<std::array<double, 3>> points;
  std::vector<std::array<std::size_t, 4>> tets;
  std::string name;
  if (from_file) {
    auto mesh = CGAL_ext::IO::read_medit_mesh(argv[1]);
    points = std::move(mesh.vertices);
    tets = std::move(mesh.tetrahedra);
    name = argv[1];
  } else {
    benchmark_support::kuhn_grid(n, 0, 1, points, tets, jitter);
    char text[64];
    std::snprintf(text, sizeof text, "Kuhn grid %d^3, jitter %g", n, jitter);
    name = text;
  }
  // The overlap tests take positive tetrahedra (the build re-orients first).
  for (auto& t : tets) {
    auto P = [&](std::size_t v) { return Tr::Point(points[v][0], points[v][1], points[v][2]); };
    if (CGAL::orientation(P(t[0]), P(t[1]), P(t[2]), P(t[3])) == CGAL::NEGATIVE) std::swap(t[2], t[3]);
  }

  Tr tr;
  CGAL_ext::Tet_mesh_build_report report;
  const double build = median_seconds(repeats, [&] { report = CGAL_ext::build_triangulation_from_tets(points, tets, {}, tr); });
  // The boundary facets, as the build collects them.
  std::vector<std::array<std::size_t, 3>> triangles;
  std::vector<std::size_t> boundary_vertices;
  for (auto c : tr.finite_cell_handles())
    for (int f = 0; f < 4; ++f)
      if (tr.is_infinite(c->neighbor(f))) {
        std::array<std::size_t, 3> t;
        for (int k = 0; k < 3; ++k) t[std::size_t(k)] = c->vertex((f + 1 + k) & 3)->info();
        triangles.push_back(t);
        boundary_vertices.insert(boundary_vertices.end(), t.begin(), t.end());
      }
  std::sort(boundary_vertices.begin(), boundary_vertices.end());
  boundary_vertices.erase(std::unique(boundary_vertices.begin(), boundary_vertices.end()), boundary_vertices.end());
  bool found = false;
  const double facets = median_seconds(repeats, [&] { found |= bool(CGAL_ext::internal::find_boundary_overlap(points, triangles)); });
  const double edges = median_seconds(repeats, [&] { found |= bool(CGAL_ext::internal::find_overlap_around_edge(points, tets)); });
  const double corners =
      median_seconds(repeats, [&] { found |= bool(CGAL_ext::internal::find_overlap_around_vertex(points, tets, triangles)); });
  const double vertices =
      median_seconds(repeats, [&] { found |= bool(CGAL_ext::internal::find_vertex_inside_tet(points, tets, boundary_vertices)); });
  if (found) {
    std::fprintf(stderr, "error: an overlap test fired on a valid mesh\n");
    return 1;
  }
  const double checks = facets + edges + corners + vertices;
  std::printf("mesh: %s: %zu vertices, %zu tets, %zu boundary facets, %zu boundary vertices\n", name.c_str(),
              points.size(), tets.size(), report.boundary_facets, boundary_vertices.size());
  std::printf("build_triangulation_from_tets: %.3f s (%.2f M tets/s), median of %d\n", build, tets.size() / build / 1e6, repeats);
  std::printf("  boundary facets meeting:        %.3f s (%4.1f%% of the build)\n", facets, 100 * facets / build);
  std::printf("  wedges about the edges:         %.3f s (%4.1f%%)\n", edges, 100 * edges / build);
  std::printf("  corners about boundary vertices: %.3f s (%4.1f%%)\n", corners, 100 * corners / build);
  std::printf("  boundary vertices inside tets:  %.3f s (%4.1f%%)\n", vertices, 100 * vertices / build);
  std::printf("  all overlap tests:              %.3f s (%4.1f%%); the build without them %.3f s (ratio %.2f)\n", checks,
              100 * checks / build, build - checks, build / (build - checks));
  return 0;
}

int main(int argc, char** argv) {
  return benchmark_support::run_reporting_errors("benchmark_mesh_input", [&] { return run(argc, argv); });
}
