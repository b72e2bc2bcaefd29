// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#include <CGAL_ext/Hex_mesh_quality_3.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

namespace CGAL_ext {

namespace {

using Hex_points = std::array<Eigen::Vector3d, 8>;

// Verdict's corner frames: (corner, a, b, c), the frame (p_a - p_corner, ...).
constexpr std::array<std::array<int, 4>, 8> corner_frames = {{{{0, 1, 3, 4}}, {{1, 2, 0, 5}}, {{2, 3, 1, 6}},
                                                              {{3, 0, 2, 7}}, {{4, 7, 5, 0}}, {{5, 4, 6, 1}},
                                                              {{6, 5, 7, 2}}, {{7, 6, 4, 3}}}};

// det(a, b, c) / (|a| |b| |c|), or 0 and degenerate when a vector has length
// 0 or is not finite. Each vector is normalised first, its length by
// stableNorm (no underflow on tiny edges), so the value is in [-1, 1].
double scaled_frame(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, bool& degenerate) {
  const double la = a.stableNorm(), lb = b.stableNorm(), lc = c.stableNorm();
  const bool usable = la > 0 && lb > 0 && lc > 0 && std::isfinite(la) && std::isfinite(lb) && std::isfinite(lc);
  if (!usable) {
    degenerate = true;
    return 0;
  }
  return (a / la).dot((b / lb).cross(c / lc));
}

// The Jacobian of the trilinear map of the unit cube onto the hexahedron at (u, v, w).
Eigen::Matrix3d trilinear_jacobian(const Hex_points& p, double u, double v, double w) {
  // Corner k of the unit cube in VTK order: (u, v, w) of vertex k.
  static constexpr int cube[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                     {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const double t[3] = {u, v, w};
  Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
  for (int k = 0; k < 8; ++k)
    for (int d = 0; d < 3; ++d) {
      double weight = cube[k][d] ? 1.0 : -1.0; // d/dt_d of the shape function
      for (int e = 0; e < 3; ++e)
        if (e != d) weight *= cube[k][e] ? t[e] : 1 - t[e];
      J.col(d) += weight * p[std::size_t(k)];
    }
  return J;
}

Eigen::Vector3d trilinear_point(const Hex_points& p, double u, double v, double w) {
  const Eigen::Vector3d bottom = (1 - v) * ((1 - u) * p[0] + u * p[1]) + v * ((1 - u) * p[3] + u * p[2]);
  const Eigen::Vector3d top = (1 - v) * ((1 - u) * p[4] + u * p[5]) + v * ((1 - u) * p[7] + u * p[6]);
  return (1 - w) * bottom + w * top;
}

// The points scaled by a power of two (exact) so that the largest
// coordinate is below 2: differences and products then cannot overflow,
// whatever the scale. Returns the exponent e: p = 2^e * scaled.
int scale_to_unit(Hex_points& p) {
  double largest = 0;
  for (const Eigen::Vector3d& x : p) largest = std::max(largest, x.cwiseAbs().maxCoeff());
  if (!(largest > 0) || !std::isfinite(largest)) return 0;
  const int e = std::ilogb(largest);
  for (Eigen::Vector3d& x : p) x = x.unaryExpr([e](double c) { return std::ldexp(c, -e); });
  return e;
}

// The two Gauss-Legendre points on [0, 1]; weights 1/2 each.
const std::array<double, 2> gauss2 = {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)};

Eigen::Matrix3d checked_metric(const Hex_mesh_quality_options& options, const Eigen::Vector3d& x, std::size_t hex) {
  const Eigen::Matrix3d g = options.metric(x);
  if (!g.allFinite() || !g.isApprox(g.transpose()) || Eigen::LLT<Eigen::Matrix3d>(g).info() != Eigen::Success)
    throw std::invalid_argument("hex_mesh_quality: the metric at a point of hexahedron " + std::to_string(hex + 1) +
                                " is not finite, not symmetric or not positive definite");
  return g;
}

// The length in the metric of the segment a-b: 3-point Gauss-Legendre.
double metric_length(const Hex_mesh_quality_options& options, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                     std::size_t hex) {
  static constexpr double s = 0.7745966692414834; // sqrt(3/5)
  static constexpr std::array<std::pair<double, double>, 3> rule = {
      {{0.5 * (1 - s), 5.0 / 18}, {0.5, 8.0 / 18}, {0.5 * (1 + s), 5.0 / 18}}};
  const Eigen::Vector3d e = b - a;
  double length = 0;
  for (const auto& [t, weight] : rule) {
    const Eigen::Matrix3d g = checked_metric(options, a + t * e, hex);
    length += weight * std::sqrt(std::max(0.0, e.dot(g * e)));
  }
  return length;
}

double share_within_25_percent(const std::vector<double>& values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  const auto n = std::count_if(values.begin(), values.end(), [](double x) { return 0.8 <= x && x <= 1.25; });
  return double(n) / double(values.size());
}

} // namespace

Hex_scaled_jacobian hex_scaled_jacobian(const Hex_points& points) {
  Hex_points p = points;
  scale_to_unit(p); // the value does not depend on the scale
  Hex_scaled_jacobian r;
  r.corners = std::numeric_limits<double>::infinity();
  for (const auto& f : corner_frames) {
    const Eigen::Vector3d& o = p[std::size_t(f[0])];
    r.corners = std::min(r.corners, scaled_frame(p[std::size_t(f[1])] - o, p[std::size_t(f[2])] - o,
                                                 p[std::size_t(f[3])] - o, r.degenerate));
  }
  std::array<Eigen::Vector3d, 3> axes;
  for (std::size_t d = 0; d < 3; ++d) {
    axes[d].setZero();
    for (const auto& e : hex_edge_families[d]) axes[d] += p[std::size_t(e[1])] - p[std::size_t(e[0])];
  }
  r.value = std::min(r.corners, scaled_frame(axes[0], axes[1], axes[2], r.degenerate));
  return r;
}

double hex_volume(const Hex_points& points) {
  Hex_points p = points;
  const int e = scale_to_unit(p);
  double volume = 0;
  for (double u : gauss2)
    for (double v : gauss2)
      for (double w : gauss2) volume += trilinear_jacobian(p, u, v, w).determinant();
  return std::ldexp(volume / 8, 3 * e); // +-inf only where the volume itself is beyond the doubles
}

Hex_quality_summary hex_quality_summary(std::vector<double> values) {
  Hex_quality_summary s;
  s.count = values.size();
  if (values.empty()) return s;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  s.min = values.front();
  s.max = values.back();
  s.median = n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
  s.mean = std::accumulate(values.begin(), values.end(), 0.0) / double(n);
  return s;
}

Hex_mesh_quality_3 hex_mesh_quality(const Hex_mesh_3& mesh, const Hex_mesh_quality_options& options) {
  Hex_mesh_quality_3 r;
  r.hexahedra = mesh.hexahedra.size();
  std::vector<char> used(mesh.points.size(), 0);
  std::vector<std::pair<std::size_t, std::size_t>> edges;
  std::vector<double> corner_values, metric_sizes;
  std::vector<std::size_t> edge_hex; // the hexahedron each entry of edges comes from (for messages)
  for (std::size_t h = 0; h < mesh.hexahedra.size(); ++h) {
    Hex_points p;
    for (std::size_t k = 0; k < 8; ++k) {
      const std::size_t v = mesh.hexahedra[h][k];
      if (v >= mesh.points.size() || !mesh.points[v].allFinite())
        throw std::invalid_argument("hex_mesh_quality: hexahedron " + std::to_string(h + 1) + ": vertex " +
                                    std::to_string(v) + (v >= mesh.points.size() ? " is out of range (0-based, " +
                                                             std::to_string(mesh.points.size()) + " points)"
                                                                                : " is not finite"));
      p[k] = mesh.points[v];
      used[v] = 1;
    }
    const Hex_scaled_jacobian sj = hex_scaled_jacobian(p);
    r.scaled_jacobians.push_back(sj.value);
    corner_values.push_back(sj.corners);
    r.scaled_jacobian_at_most_0 += sj.value <= 0;
    r.scaled_jacobian_below_0_2 += sj.value < 0.2;
    r.scaled_jacobian_below_0_5 += sj.value < 0.5;
    r.degenerate += sj.degenerate;
    // Bin k holds [-1 + k / 10, -1 + (k + 1) / 10); the bounds as the doubles of those decimals.
    std::size_t bin = 0;
    while (bin < 19 && sj.value >= double(int(bin) - 9) / 10) ++bin;
    ++r.scaled_jacobian_histogram[bin];
    const double volume = hex_volume(p);
    r.volume += volume;
    r.negative_volume_hexes += volume < 0;
    for (const auto& family : hex_edge_families)
      for (const auto& e : family) {
        const std::size_t a = mesh.hexahedra[h][std::size_t(e[0])], b = mesh.hexahedra[h][std::size_t(e[1])];
        edges.emplace_back(std::min(a, b), std::max(a, b));
        edge_hex.push_back(h);
      }
    if (options.metric) {
      double metric_volume = 0;
      for (double u : gauss2)
        for (double v : gauss2)
          for (double w : gauss2)
            metric_volume += trilinear_jacobian(p, u, v, w).determinant() *
                             std::sqrt(checked_metric(options, trilinear_point(p, u, v, w), h).determinant());
      metric_sizes.push_back(std::cbrt(metric_volume / 8));
    }
  }
  r.vertices = std::size_t(std::count(used.begin(), used.end(), 1));
  r.scaled_jacobian = hex_quality_summary(r.scaled_jacobians);
  r.scaled_jacobian_corners = hex_quality_summary(corner_values);
  r.coverage = r.volume / options.domain_volume;

  // Each edge once: sort (edge, hex) and keep the first hexahedron of each edge.
  std::vector<std::size_t> order(edges.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) {
    return std::tie(edges[i], i) < std::tie(edges[j], j);
  });
  std::vector<double> lengths, metric_lengths;
  for (std::size_t k = 0; k < order.size(); ++k) {
    const auto& e = edges[order[k]];
    if (k > 0 && edges[order[k - 1]] == e) continue;
    const Eigen::Vector3d& a = mesh.points[e.first];
    const Eigen::Vector3d& b = mesh.points[e.second];
    lengths.push_back((b - a).norm());
    if (options.metric) metric_lengths.push_back(metric_length(options, a, b, edge_hex[order[k]]));
  }
  r.edge_length = hex_quality_summary(std::move(lengths));

  const auto quads = hex_mesh_boundary_quadrilaterals(mesh.hexahedra);
  r.boundary_quadrilaterals = quads.size();
  std::vector<std::pair<std::size_t, std::size_t>> quad_edges;
  for (const auto& q : quads)
    for (std::size_t i = 0; i < 4; ++i)
      quad_edges.emplace_back(std::min(q[i], q[(i + 1) % 4]), std::max(q[i], q[(i + 1) % 4]));
  std::sort(quad_edges.begin(), quad_edges.end());
  quad_edges.erase(std::unique(quad_edges.begin(), quad_edges.end()), quad_edges.end());
  if (!quad_edges.empty()) {
    double sum = 0;
    for (const auto& [a, b] : quad_edges) sum += (mesh.points[b] - mesh.points[a]).squaredNorm();
    r.boundary_edge_rms = std::sqrt(sum / double(quad_edges.size()));
  }
  if (options.metric) {
    r.metric_edges_within_25_percent = share_within_25_percent(metric_lengths);
    r.metric_sizes_within_25_percent = share_within_25_percent(metric_sizes);
    r.metric_edge_length = hex_quality_summary(std::move(metric_lengths));
    r.metric_size = hex_quality_summary(std::move(metric_sizes));
  }
  return r;
}

} // namespace CGAL_ext
