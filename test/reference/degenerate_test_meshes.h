// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_TEST_REFERENCE_DEGENERATE_TEST_MESHES_H
#define CGAL_EXT_TEST_REFERENCE_DEGENERATE_TEST_MESHES_H

// Small tetrahedral meshes and segments built to hit degenerate cases of a
// segment walk (test only). Everything is seeded and deterministic: the
// random numbers come from std::mt19937_64, whose output is specified, and
// are mapped to values without the implementation-defined distributions.
//
// Coordinates are chosen so that the special points (edge midpoints, facet
// centroids, cell centroids) and the points built from them are exact in
// double: grids are scaled by 6, and jitter is a multiple of 3/16.

#include "../walk_test_meshes.h"

#include <CGAL_ext/IO/Medit_mesh.h>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <algorithm>
#include <cmath>
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace CGAL_ext {
namespace testing {

struct Test_segment {
  std::array<double, 3> q, p;
  std::string kind; // how it was built, for messages
};

namespace internal {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

inline K::Point_3 to_point(const std::array<double, 3>& a) { return K::Point_3(a[0], a[1], a[2]); }

inline CGAL::Orientation tet_orientation(const std::vector<std::array<double, 3>>& pts, const std::array<std::size_t, 4>& t) {
  return CGAL::orientation(to_point(pts[t[0]]), to_point(pts[t[1]]), to_point(pts[t[2]]), to_point(pts[t[3]]));
}

// Uniform integer in [lo, hi] (modulo bias is irrelevant for tests).
inline long uniform_int(std::mt19937_64& rng, long lo, long hi) {
  return lo + static_cast<long>(rng() % static_cast<std::uint64_t>(hi - lo + 1));
}
// Uniform double in [lo, hi) from 53 random bits.
inline double uniform_real(std::mt19937_64& rng, double lo, double hi) {
  return lo + (hi - lo) * (static_cast<double>(rng() >> 11) * 0x1.0p-53);
}

// Drops unused points and renumbers.
inline void orient_positively(Test_mesh& m) {
  for (auto& t : m.tets)
    if (tet_orientation(m.points, t) == CGAL::NEGATIVE) std::swap(t[2], t[3]);
}

} // namespace internal

/// A Kuhn grid whose vertices are moved by multiples of 3/16 (at most
/// `max_steps` of them per coordinate, spacing 6), redrawn until every
/// incident tetrahedron stays positively oriented.
inline Test_mesh jittered_kuhn_grid(int n, std::uint64_t seed, int max_steps = 8) {
  Test_mesh m = kuhn_grid(n, n, n);
  m.name = "jittered_kuhn_" + std::to_string(n) + "_seed" + std::to_string(seed);
  std::mt19937_64 rng(seed);
  std::vector<std::vector<std::size_t>> incident(m.points.size());
  for (std::size_t t = 0; t < m.tets.size(); ++t)
    for (auto v : m.tets[t]) incident[v].push_back(t);
  for (std::size_t v = 0; v < m.points.size(); ++v) {
    const auto orig = m.points[v];
    for (int attempt = 0; attempt < 20; ++attempt) {
      for (int i = 0; i < 3; ++i) m.points[v][i] = orig[i] + 3.0 / 16 * internal::uniform_int(rng, -max_steps, max_steps);
      bool ok = true;
      for (auto t : incident[v]) ok = ok && internal::tet_orientation(m.points, m.tets[t]) == CGAL::POSITIVE;
      if (ok) break;
      m.points[v] = orig; // fall back to the unmoved vertex
    }
  }
  return m;
}

/// n^3 Kuhn grid with a column of cubes removed along z through the whole
/// block (a tunnel; the domain has genus 1). n >= 3.
inline Test_mesh tunnel_grid(int n) {
  const int c = n / 2;
  return kuhn_grid(n, n, n, 6, [c](int i, int j, int) { return !(i == c && j == c); }, "tunnel_" + std::to_string(n));
}

/// L-shaped (non-convex) block: the n^3 grid without the cubes with i, j >= n/2.
inline Test_mesh l_shape_grid(int n) {
  const int h = n / 2;
  return kuhn_grid(n, n, n, 6, [h](int i, int j, int) { return !(i >= h && j >= h); }, "l_shape_" + std::to_string(n));
}

/// Two 1x1xn columns of cubes touching along a vertical edge (non-manifold).
inline Test_mesh edge_touching_blocks(int n = 2) {
  return kuhn_grid(2, 2, n, 6, [](int i, int j, int) { return i == j; }, "edge_touching_" + std::to_string(n));
}

/// Two cubes touching at one vertex only (non-manifold vertex).
inline Test_mesh vertex_touching_blocks() {
  return kuhn_grid(2, 2, 2, 6, [](int i, int j, int k) { return i == j && j == k; }, "vertex_touching");
}

/// n^3 grid without its central cube: a closed cavity, the boundary has two components. n odd >= 3.
inline Test_mesh cavity_grid(int n) {
  const int c = n / 2;
  return kuhn_grid(n, n, n, 6, [c](int i, int j, int k) { return !(i == c && j == c && k == c); },
                   "cavity_" + std::to_string(n));
}

/// Checkerboard of cubes in a 2x2x2 block: cubes meet along edges and at a vertex only.
inline Test_mesh checkerboard_blocks() {
  return kuhn_grid(2, 2, 2, 6, [](int i, int j, int k) { return (i + j + k) % 2 == 0; }, "checkerboard_2");
}

/// Finite tetrahedra of the Delaunay triangulation of all integer points with
/// x^2 + y^2 + z^2 == r2 (one per radius in `radii2`), plus the center,
/// scaled by `scale`. Massively cospherical: the tetrahedralization is the
/// one CGAL's symbolic perturbation picks.
inline Test_mesh delaunay_cospherical(const std::vector<int>& radii2, double scale = 6) {
  using K = internal::K;
  using Vb = CGAL::Triangulation_vertex_base_with_info_3<std::size_t, K>;
  using Tds = CGAL::Triangulation_data_structure_3<Vb>;
  using Dt = CGAL::Delaunay_triangulation_3<K, Tds>;
  Test_mesh m;
  m.name = "delaunay_sphere";
  std::vector<std::pair<K::Point_3, std::size_t>> in;
  m.points.push_back({0, 0, 0});
  for (int r2 : radii2) {
    m.name += "_" + std::to_string(r2);
    for (int x = -10; x <= 10; ++x)
      for (int y = -10; y <= 10; ++y)
        for (int z = -10; z <= 10; ++z)
          if (x * x + y * y + z * z == r2) m.points.push_back({scale * x, scale * y, scale * z});
  }
  for (std::size_t i = 0; i < m.points.size(); ++i) in.push_back({internal::to_point(m.points[i]), i});
  Dt dt(in.begin(), in.end());
  for (auto c : dt.finite_cell_handles())
    m.tets.push_back({c->vertex(0)->info(), c->vertex(1)->info(), c->vertex(2)->info(), c->vertex(3)->info()});
  internal::orient_positively(m);
  return m;
}

/// The mesh scaled per axis and translated. With powers of two as scales and
/// offsets that are multiples of 3 (and not too large), the special points
/// of `degenerate_segments()` stay exact in double.
inline Test_mesh transformed(Test_mesh m, const std::array<double, 3>& scale, const std::array<double, 3>& offset,
                             const std::string& suffix) {
  m.name += suffix;
  for (auto& p : m.points)
    for (int i = 0; i < 3; ++i) p[i] = p[i] * scale[i] + offset[i];
  internal::orient_positively(m); // a negative scale mirrors the tets
  return m;
}

/// Near-degenerate variants: each segment with one end point moved in one
/// coordinate by 2^k ulps, k uniform in [0, max_exponent] (seeded), so that
/// predicates that were zero become tiny and parameters computed in double
/// are ill-conditioned.
inline std::vector<Test_segment> nudged(const std::vector<Test_segment>& segs, std::uint64_t seed, int max_exponent = 1) {
  std::mt19937_64 rng(seed);
  std::vector<Test_segment> out;
  for (auto s : segs) {
    auto& x = internal::uniform_int(rng, 0, 1) ? s.q : s.p;
    double& c = x[static_cast<std::size_t>(internal::uniform_int(rng, 0, 2))];
    const int k = static_cast<int>(internal::uniform_int(rng, 0, max_exponent));
    const double ulp = std::nextafter(std::abs(c), HUGE_VAL) - std::abs(c);
    c += (internal::uniform_int(rng, 0, 1) ? 1 : -1) * std::ldexp(ulp, k);
    s.kind += "+nudged_2^" + std::to_string(k) + "ulp";
    out.push_back(s);
  }
  return out;
}

/// The vertex index pairs of the mesh edges.
inline std::vector<std::array<std::size_t, 2>> mesh_edges(const Test_mesh& m) {
  std::set<std::array<std::size_t, 2>> s;
  for (const auto& t : m.tets)
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) s.insert({std::min(t[a], t[b]), std::max(t[a], t[b])});
  return {s.begin(), s.end()};
}

/// The facets (sorted vertex triples), each with the number of its tets (1 on the boundary).
inline std::map<std::array<std::size_t, 3>, int> mesh_facets(const Test_mesh& m) {
  std::map<std::array<std::size_t, 3>, int> n;
  for (const auto& t : m.tets)
    for (int a = 0; a < 4; ++a) {
      std::array<std::size_t, 3> f;
      for (int k = 0, j = 0; k < 4; ++k)
        if (k != a) f[j++] = t[k];
      std::sort(f.begin(), f.end());
      ++n[f];
    }
  return n;
}

/// `count` segments, most of them degenerate with respect to the mesh:
/// end points at vertices, edge midpoints, facet and cell centroids, lattice
/// points, points outside the mesh and far away; segments along edge lines,
/// inside facet planes, through a special point, through a point of the
/// boundary (often touching the domain only there), parallel to an edge;
/// q == p; and random ones.
inline std::vector<Test_segment> degenerate_segments(const Test_mesh& m, std::size_t count, std::uint64_t seed) {
  using P3 = std::array<double, 3>;
  std::mt19937_64 rng(seed);
  const auto edges = mesh_edges(m);
  std::vector<std::array<std::size_t, 3>> facets, boundary;
  for (const auto& f : mesh_facets(m)) {
    facets.push_back(f.first);
    if (f.second == 1) boundary.push_back(f.first);
  }
  P3 lo = m.points[0], hi = m.points[0];
  for (const auto& p : m.points)
    for (int i = 0; i < 3; ++i) lo[i] = std::min(lo[i], p[i]), hi[i] = std::max(hi[i], p[i]);
  const double margin = 0.25 * std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  // Whether [a, b] converts to long (not at 1e300: converting it would be
  // undefined behaviour, which UBSan reports).
  const auto long_range = [](double a, double b) { return std::abs(a) < 0x1p62 && std::abs(b) < 0x1p62; };

  auto pick = [&](std::size_t n) { return static_cast<std::size_t>(internal::uniform_int(rng, 0, static_cast<long>(n) - 1)); };
  auto comb = [&](const std::vector<std::size_t>& ids, const std::vector<double>& w) {
    P3 r{0, 0, 0};
    for (std::size_t k = 0; k < ids.size(); ++k)
      for (int i = 0; i < 3; ++i) r[i] += w[k] * m.points[ids[k]][i];
    return r;
  };
  auto axpy = [](const P3& a, double s, const P3& b, const P3& c) { // a + s (b - c)
    return P3{a[0] + s * (b[0] - c[0]), a[1] + s * (b[1] - c[1]), a[2] + s * (b[2] - c[2])};
  };
  // A special point and its kind.
  auto special = [&](std::string& kind) -> P3 {
    switch (internal::uniform_int(rng, 0, 7)) {
    case 0: kind = "vertex"; return m.points[pick(m.points.size())];
    case 1: {
      kind = "edge_mid";
      const auto& e = edges[pick(edges.size())];
      return comb({e[0], e[1]}, {0.5, 0.5});
    }
    case 2: {
      kind = "facet_centroid";
      const auto& f = facets[pick(facets.size())];
      // (a + b + c) / 3 with a division, exact because coordinates are multiples of 3 (or 3/16)
      P3 r = comb({f[0], f[1], f[2]}, {1, 1, 1});
      for (auto& x : r) x /= 3;
      return r;
    }
    case 3: {
      kind = "cell_centroid";
      const auto& t = m.tets[pick(m.tets.size())];
      return comb({t[0], t[1], t[2], t[3]}, {0.25, 0.25, 0.25, 0.25});
    }
    case 4: {
      kind = "lattice";
      P3 r;
      for (int i = 0; i < 3; ++i)
        r[i] = long_range(lo[i] - margin, hi[i] + margin)
                   ? 3.0 * internal::uniform_int(rng, static_cast<long>((lo[i] - margin) / 3),
                                                 static_cast<long>((hi[i] + margin) / 3))
                   : internal::uniform_real(rng, lo[i] - margin, hi[i] + margin); // every such double is an integer
      return r;
    }
    case 5: {
      kind = "outside";
      P3 r;
      const int axis = static_cast<int>(internal::uniform_int(rng, 0, 2));
      for (int i = 0; i < 3; ++i)
        r[i] = long_range(2 * (lo[i] - margin), 2 * (hi[i] + margin))
                   ? 0.5 * internal::uniform_int(rng, static_cast<long>(2 * (lo[i] - margin)),
                                                 static_cast<long>(2 * (hi[i] + margin)))
                   : internal::uniform_real(rng, lo[i] - margin, hi[i] + margin);
      r[axis] = internal::uniform_int(rng, 0, 1) ? hi[axis] + margin : lo[axis] - margin;
      return r;
    }
    case 6: { // far away, on a line through a vertex and a cell centroid
      kind = "far";
      const auto& t = m.tets[pick(m.tets.size())];
      const P3 c = comb({t[0], t[1], t[2], t[3]}, {0.25, 0.25, 0.25, 0.25});
      return axpy(c, 1024.0 * internal::uniform_int(rng, 1, 1000), m.points[t[0]], c);
    }
    default: {
      kind = "random";
      P3 r;
      for (int i = 0; i < 3; ++i) r[i] = internal::uniform_real(rng, lo[i] - margin, hi[i] + margin);
      return r;
    }
    }
  };
  const double steps[] = {-1.5, -1, -0.5, -0.25, 0, 0.25, 0.5, 1, 1.5, 2};
  auto step = [&] { return steps[pick(10)]; };

  std::vector<Test_segment> out;
  while (out.size() < count) {
    std::string k1, k2;
    Test_segment s;
    switch (internal::uniform_int(rng, 0, 8)) {
    case 8: { // through a point of the boundary (vertex, edge midpoint, centroid): often grazing
      const auto& f = boundary[pick(boundary.size())];
      const int which = static_cast<int>(internal::uniform_int(rng, 0, 2));
      P3 c = which == 0 ? m.points[f[0]] : which == 1 ? comb({f[0], f[1]}, {0.5, 0.5}) : comb({f[0], f[1], f[2]}, {1, 1, 1});
      if (which == 2)
        for (auto& x : c) x /= 3;
      P3 u;
      for (auto& x : u) x = 1.5 * internal::uniform_int(rng, -3, 3);
      const double k = 0.5 * internal::uniform_int(rng, 1, 4);
      s = {axpy(c, 1, u, P3{0, 0, 0}), axpy(c, -k, u, P3{0, 0, 0}), "through-boundary"};
      break;
    }
    case 0: case 1: {
      const P3 a = special(k1), b = special(k2);
      s = {a, b, k1 + "->" + k2};
      break;
    }
    case 2: { // on an edge's line
      const auto& e = edges[pick(edges.size())];
      const P3 &a = m.points[e[0]], &b = m.points[e[1]];
      s = {axpy(a, step(), b, a), axpy(a, step(), b, a), "edge_line"};
      break;
    }
    case 3: { // in a facet's plane
      const auto& f = facets[pick(facets.size())];
      const P3 &a = m.points[f[0]], &b = m.points[f[1]], &c = m.points[f[2]];
      s = {axpy(axpy(a, step(), b, a), step(), c, a), axpy(axpy(a, step(), b, a), step(), c, a), "facet_plane"};
      break;
    }
    case 4: { // through a special point: reflect a special point about it
      const P3 c = special(k1), a = special(k2);
      s = {a, axpy(c, 1, c, a), k2 + "-through-" + k1};
      break;
    }
    case 5: { // parallel to an edge, from a special point
      const auto& e = edges[pick(edges.size())];
      const P3 a = special(k1);
      double t = step();
      if (t == 0) t = 1;
      s = {a, axpy(a, t, m.points[e[1]], m.points[e[0]]), k1 + "-along-edge"};
      break;
    }
    case 6: { // q == p
      const P3 a = special(k1);
      s = {a, a, "point-" + k1};
      break;
    }
    default: {
      std::string dummy;
      P3 a, b;
      for (int i = 0; i < 3; ++i) {
        a[i] = internal::uniform_real(rng, lo[i] - margin, hi[i] + margin);
        b[i] = internal::uniform_real(rng, lo[i] - margin, hi[i] + margin);
      }
      s = {a, b, "random"};
    }
    }
    out.push_back(s);
  }
  return out;
}

/// A mesh of the test data directory (a Medit file written by Gmsh or
/// TetGen), its tetrahedra oriented positively.
inline Test_mesh medit_test_mesh(const std::string& file) {
  const IO::Medit_mesh mm = IO::read_medit_mesh(std::string(CGAL_EXT_TEST_DATA_DIR) + "/" + file);
  Test_mesh m{file, mm.vertices, mm.tetrahedra};
  internal::orient_positively(m);
  return m;
}

/// `count` segments that are degenerate only up to rounding: end points
/// computed in double on an edge's line or in a facet's plane, with
/// arbitrary (non-dyadic) coefficients, so that the segment passes within
/// rounding distance of that edge or facet and of every facet around it,
/// without being exactly on it. Kinds: along an edge line extended beyond
/// both ends ("edge_line_rounded"), from inside the edge out
/// ("edge_line_rounded_half"), in a facet plane extended beyond the facet
/// ("facet_plane_rounded"), through a point of a facet plane from outside the
/// facet ("facet_plane_through"), and nearly parallel to an edge at a tiny
/// offset ("edge_offset").
inline std::vector<Test_segment> rounded_degenerate_segments(const Test_mesh& m, std::size_t count, std::uint64_t seed) {
  using P3 = std::array<double, 3>;
  std::mt19937_64 rng(seed);
  const auto edges = mesh_edges(m);
  std::vector<std::array<std::size_t, 3>> facets;
  for (const auto& f : mesh_facets(m)) facets.push_back(f.first);
  auto pick = [&](std::size_t n) { return static_cast<std::size_t>(internal::uniform_int(rng, 0, static_cast<long>(n) - 1)); };
  auto on_line = [](const P3& a, const P3& b, double s) { // a + s (b - a), rounded
    return P3{a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1]), a[2] + s * (b[2] - a[2])};
  };
  auto in_plane = [](const P3& a, const P3& b, const P3& c, double u, double v) { // a + u (b - a) + v (c - a), rounded
    P3 r;
    for (int i = 0; i < 3; ++i) r[i] = a[i] + u * (b[i] - a[i]) + v * (c[i] - a[i]);
    return r;
  };
  auto U = [&](double lo, double hi) { return internal::uniform_real(rng, lo, hi); };
  std::vector<Test_segment> out;
  while (out.size() < count) {
    switch (internal::uniform_int(rng, 0, 4)) {
    case 0: {
      const auto& e = edges[pick(edges.size())];
      const P3 &a = m.points[e[0]], &b = m.points[e[1]];
      out.push_back({on_line(a, b, U(-3, -0.01)), on_line(a, b, U(1.01, 4)), "edge_line_rounded"});
      break;
    }
    case 1: {
      const auto& e = edges[pick(edges.size())];
      const P3 &a = m.points[e[0]], &b = m.points[e[1]];
      out.push_back({on_line(a, b, U(0.01, 0.99)), on_line(a, b, U(-3, 4)), "edge_line_rounded_half"});
      break;
    }
    case 2: {
      const auto& f = facets[pick(facets.size())];
      const P3 &a = m.points[f[0]], &b = m.points[f[1]], &c = m.points[f[2]];
      out.push_back({in_plane(a, b, c, U(-2, 2), U(-2, 2)), in_plane(a, b, c, U(-2, 2), U(-2, 2)), "facet_plane_rounded"});
      break;
    }
    case 3: {
      const auto& f = facets[pick(facets.size())];
      const P3 &a = m.points[f[0]], &b = m.points[f[1]], &c = m.points[f[2]];
      const double u = U(0.05, 0.9), v = U(0.05, 0.95 - u), s = U(1.5, 3);
      // from outside the facet, through an interior point of it, and beyond
      out.push_back({in_plane(a, b, c, -u, -v), in_plane(a, b, c, s * u, s * v), "facet_plane_through"});
      break;
    }
    default: {
      const auto& e = edges[pick(edges.size())];
      const P3 &a = m.points[e[0]], &b = m.points[e[1]];
      P3 q = on_line(a, b, U(-2, -0.1)), p = on_line(a, b, U(1.1, 3));
      // a shift of a few units in the last place, in one coordinate
      const int i = static_cast<int>(internal::uniform_int(rng, 0, 2));
      q[i] = std::nextafter(q[i], q[i] + 1);
      p[i] = std::nextafter(p[i], p[i] - 1);
      out.push_back({q, p, "edge_offset"});
    }
    }
  }
  return out;
}

} // namespace testing
} // namespace CGAL_ext

#endif // CGAL_EXT_TEST_REFERENCE_DEGENERATE_TEST_MESHES_H
