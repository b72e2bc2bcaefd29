// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_SHARP_FEATURES_3_H
#define CGAL_EXT_SHARP_FEATURES_3_H

/// \file Sharp_features_3.h
/// The sharp features of a tetrahedral mesh's boundary, measured in a
/// metric: feature edges (creases), the curves they form, and corners, with
/// the directions a boundary-aligned frame must follow there.

#include <CGAL_ext/Metric_field_3.h>
#include <CGAL_ext/Tet_mesh_triangulation_3.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace CGAL_ext {

namespace internal {

// The centroid, the outward unit normal (away from the cell's vertex f) and
// the area of the facet f of a cell.
template <class Cell_handle>
void boundary_facet_geometry(Cell_handle c, int f, Eigen::Vector3d& centroid, Eigen::Vector3d& normal,
                             double& area) {
  Eigen::Vector3d p[3];
  for (int k = 0, m = 0; k < 4; ++k)
    if (k != f) p[m++] = to_eigen_vector(c->vertex(k)->point());
  centroid = (p[0] + p[1] + p[2]) / 3;
  const Eigen::Vector3d a = (p[1] - p[0]).cross(p[2] - p[0]);
  area = 0.5 * a.norm();
  normal = a.normalized();
  if (normal.dot(to_eigen_vector(c->vertex(f)->point()) - p[0]) > 0) normal = -normal; // outward
}

} // namespace internal

/// \ingroup PkgCGALExtFrames
/// What a boundary vertex is for the sharp features.
enum class Feature_vertex_kind {
  none,  ///< not on a feature edge
  curve, ///< on a feature curve: two feature edges that continue each other
  corner ///< a corner: one feature edge (a crease that fades out), three or more, or two that turn by more than the feature angle
};

/// \ingroup PkgCGALExtFrames
/// The sharp features of the boundary of a tetrahedral mesh in a metric.
///
/// **Feature edges.** A boundary edge is a feature edge when the metric
/// normals `A^{-1} n / |A^{-1} n|` of its two boundary facets (`A = g^{1/2}`
/// at the edge's midpoint, `n` the Euclidean outward normals) make an angle
/// larger than `feature_angle_deg`: this is the dihedral angle's deviation
/// from flat as the metric measures it (for `g = I`, the Euclidean one). A
/// boundary edge with other than two boundary facets (where parts of the
/// domain meet along an edge) is always a feature edge.
///
/// Feature curves of fewer than 3 edges are below the mesh's resolution and
/// are dropped (see `number_of_dropped_edges()`): those that meet no other
/// feature curve (lone kinks of a coarsely meshed smooth surface), and those
/// with a free end that hang from a junction of curves (spurs, where a
/// coarsely meshed fillet meets a crease), until none is left.
///
/// **Vertices.** A boundary vertex on no feature edge is `none`. A vertex on
/// exactly two feature edges that turn by at most `feature_angle_deg` (in the
/// metric at the vertex) is on a feature `curve`; its tangent is the mean of
/// the two edge directions. Every other vertex on a feature edge is a
/// `corner`, with a full frame: the orthonormal frame (in the metric) that
/// fits the vertex's boundary facets best, chosen among the frames spanned
/// by pairs of its facet normals and feature edge directions, by the
/// area-weighted sum of `sin^2` of the facets' alignment errors.
///
/// Everything is decided from the mesh in a fixed order, so the result does
/// not depend on the order of the triangulation's cells in memory.
///
/// \tparam Metric_field a model of `MetricField_3`, such as `Metric_field_3<Tr>`
///         (its triangulation, `sqrt_metric(v)` and its index maps, which
///         give the domain and name the vertices)
template <class Metric_field>
class Sharp_features_3 {
public:
  /// The triangulation type.
  using Triangulation = typename Metric_field::Triangulation_3;
  /// Cell handle type.
  using Cell_handle = typename Triangulation::Cell_handle;
  /// Vertex handle type.
  using Vertex_handle = typename Triangulation::Vertex_handle;

  /// One feature edge.
  struct Feature_edge {
    std::size_t source; ///< the smaller vertex index
    std::size_t target; ///< the larger vertex index
    double angle_deg;   ///< the angle between the two facets' metric normals (180 if not two facets)
    int facets;         ///< the number of boundary facets on the edge (2 on a manifold boundary)
    /// the outward Euclidean unit normals of its two boundary facets (that of
    /// smaller sorted vertex indices first); zero if not two facets
    std::array<Eigen::Vector3d, 2> normals = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
    /// its length in the metric times its signed turning angle in radians
    /// (positive where the boundary is convex); 0 if not two facets
    double turning = 0;
  };

  /// Finds the features.
  /// \param field the metric field
  /// \param feature_angle_deg the threshold in degrees, in `[0, 180]`; 180 finds only the edges where
  ///        parts of the domain meet (other than two boundary facets)
  /// \throws std::invalid_argument if the angle is not in `[0, 180]`
  Sharp_features_3(const Metric_field& field, double feature_angle_deg) : angle_deg_(feature_angle_deg) {
    if (!(feature_angle_deg >= 0 && feature_angle_deg <= 180))
      throw std::invalid_argument("the feature angle must be in [0, 180] degrees (got " +
                                  std::to_string(feature_angle_deg) + ")");
    const Triangulation& tr = field.triangulation();
    const auto vim = field.vertex_index_map();
    std::size_t nv = 0;
    for (Vertex_handle v : tr.finite_vertex_handles()) nv = std::max<std::size_t>(nv, get(vim, v) + 1);
    vertices_.assign(nv, Vertex_handle());
    for (Vertex_handle v : tr.finite_vertex_handles()) vertices_[get(vim, v)] = v;
    kind_.assign(nv, Feature_vertex_kind::none);
    axes_.assign(nv, Eigen::Matrix3d::Zero());
    const double cos_angle = std::cos(feature_angle_deg * M_PI / 180);
    find_boundary_facets(field);
    find_feature_edges(field, cos_angle);
    drop_short_curves();
    classify_vertices(field, cos_angle);
  }

  /// The feature angle in degrees.
  /// \returns the angle given to the constructor, in `[0, 180]`
  double feature_angle_deg() const { return angle_deg_; }
  /// The feature edges, sorted by (source, target).
  /// \returns the feature edges, each with `source < target`
  const std::vector<Feature_edge>& feature_edges() const { return edges_; }
  /// Whether the edge between two vertices is a feature edge.
  /// \param a a vertex index
  /// \param b a vertex index
  /// \returns true if `(a, b)` or `(b, a)` is a feature edge
  bool is_feature_edge(std::size_t a, std::size_t b) const { return feature_edge(a, b) != nullptr; }
  /// The feature edge between two vertices.
  /// \param a a vertex index
  /// \param b a vertex index
  /// \returns the feature edge `(min(a, b), max(a, b))`, or null if it is not one
  const Feature_edge* feature_edge(std::size_t a, std::size_t b) const {
    if (a > b) std::swap(a, b);
    const auto it = std::lower_bound(edges_.begin(), edges_.end(), std::make_pair(a, b),
                                     [](const Feature_edge& e, const std::pair<std::size_t, std::size_t>& k) {
                                       return std::make_pair(e.source, e.target) < k;
                                     });
    return it != edges_.end() && it->source == a && it->target == b ? &*it : nullptr;
  }
  /// The tangent of the feature curve along the feature edge from `a` to
  /// `b` (Euclidean, unit, oriented from `a` to `b`): the mean of the curve's
  /// tangents at its two ends, each the edge's own direction at a corner.
  /// On a curve with few edges per turn it turns smoothly from one edge to
  /// the next, where the edges' own directions jump.
  /// \param a a vertex index
  /// \param b a vertex index, `(a, b)` a feature edge
  /// \returns the unit tangent, oriented from `a` to `b`
  Eigen::Vector3d edge_tangent(std::size_t a, std::size_t b) const {
    const Eigen::Vector3d chord =
        (internal::to_eigen_vector(vertices_[b]->point()) - internal::to_eigen_vector(vertices_[a]->point())).normalized();
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (std::size_t v : {a, b}) {
      if (kind(v) != Feature_vertex_kind::curve) {
        sum += chord;
      } else {
        const Eigen::Vector3d t = tangent(v);
        sum += t.dot(chord) < 0 ? Eigen::Vector3d(-t) : t;
      }
    }
    return sum.norm() > 0 ? sum.normalized() : chord;
  }
  /// The kind of a vertex.
  /// \param v a vertex index
  /// \returns the kind; `none` for an index beyond the vertices
  Feature_vertex_kind kind(std::size_t v) const { return v < kind_.size() ? kind_[v] : Feature_vertex_kind::none; }
  /// The kinds of all vertices.
  /// \returns the kind of each vertex, by vertex index
  const std::vector<Feature_vertex_kind>& kinds() const { return kind_; }
  /// The unit tangent (Euclidean) of the feature curve at a `curve` vertex.
  /// \param v a vertex index of kind `curve`
  /// \returns the unit tangent, in either orientation
  Eigen::Vector3d tangent(std::size_t v) const { return axes_[v].col(0); }
  /// The frame of a `corner` vertex: three Euclidean unit columns, the
  /// directions of the hex edges there (orthonormal in the metric at the
  /// vertex, up to their lengths).
  /// \param v a vertex index of kind `corner`
  /// \returns the 3x3 matrix of the three directions
  const Eigen::Matrix3d& corner_axes(std::size_t v) const { return axes_[v]; }
  /// The number of vertices on feature curves (not corners).
  /// \returns the number of vertices of kind `curve`
  std::size_t number_of_curve_vertices() const { return curve_vertices_; }
  /// The number of corners.
  /// \returns the number of vertices of kind `corner`
  std::size_t number_of_corners() const { return corners_; }
  /// The number of edges sharper than the angle that were dropped: lone
  /// kinks (feature curves of fewer than 3 edges meeting no other feature)
  /// and spurs (curves of fewer than 3 edges from a free end to a junction).
  /// \returns the number of dropped edges (not in `feature_edges()`)
  std::size_t number_of_dropped_edges() const { return dropped_; }
  /// The number of boundary facets.
  /// \returns the number of facets between a domain cell and a cell outside it
  std::size_t number_of_boundary_facets() const { return facets_.size(); }
  /// The turning of the boundary's smooth part: over the boundary edges with
  /// two facets that are not feature edges (dropped kinks and spurs included), the
  /// edge's length in the metric times the angle between the facets' metric
  /// normals, signed (negative where the boundary is concave). On a faceted
  /// surface this is the integral of twice the mean curvature, `k1 + k2`, over
  /// its smooth part, as the metric measures it (`A` at the edge's midpoint
  /// for both, the metric's derivatives left out); `hex_coverage_ceiling()`
  /// uses it.
  /// \returns the sum, in units of metric length
  double smooth_turning() const { return smooth_turning_; }

private:
  // The boundary facets of the domain, in the order of their sorted vertex triples.
  void find_boundary_facets(const Metric_field& field) {
    const Triangulation& tr = field.triangulation();
    const auto vim = field.vertex_index_map();
    const auto cim = field.cell_index_map();
    for (Cell_handle c : tr.finite_cell_handles()) {
      if (get(cim, c) < 0) continue;
      for (int f = 0; f < 4; ++f) {
        const Cell_handle nc = c->neighbor(f);
        if (!tr.is_infinite(nc) && get(cim, nc) >= 0) continue;
        Facet b;
        for (int k = 0, m = 0; k < 4; ++k)
          if (k != f) b.v[m++] = get(vim, c->vertex(k));
        std::sort(b.v.begin(), b.v.end());
        Eigen::Vector3d centroid;
        internal::boundary_facet_geometry(c, f, centroid, b.normal, b.area);
        facets_.push_back(b);
      }
    }
    std::sort(facets_.begin(), facets_.end(), [](const Facet& a, const Facet& b) { return a.v < b.v; });
  }

  // The boundary edges with their facets; the feature edges among them.
  void find_feature_edges(const Metric_field& field, double cos_angle) {
    std::vector<std::tuple<std::size_t, std::size_t, std::size_t>> edge_facet; // (a, b, facet)
    for (std::size_t i = 0; i < facets_.size(); ++i)
      for (int k = 0; k < 3; ++k)
        for (int m = k + 1; m < 3; ++m) edge_facet.emplace_back(facets_[i].v[k], facets_[i].v[m], i);
    std::sort(edge_facet.begin(), edge_facet.end());
    for (std::size_t first = 0; first < edge_facet.size();) {
      std::size_t last = first;
      while (last < edge_facet.size() && std::get<0>(edge_facet[last]) == std::get<0>(edge_facet[first]) &&
             std::get<1>(edge_facet[last]) == std::get<1>(edge_facet[first]))
        ++last;
      const std::size_t a = std::get<0>(edge_facet[first]), b = std::get<1>(edge_facet[first]);
      Feature_edge e{a, b, 180, int(last - first)};
      bool feature = e.facets != 2;
      if (!feature) {
        // A is linear along the edge: its value at the midpoint is the mean.
        const Eigen::Matrix3d A = 0.5 * (field.sqrt_metric(vertices_[a]) + field.sqrt_metric(vertices_[b]));
        const Facet& f0 = facets_[std::get<2>(edge_facet[first])];
        const Facet& f1 = facets_[std::get<2>(edge_facet[first + 1])];
        e.normals = {f0.normal, f1.normal};
        const Eigen::Matrix3d A_inv = scaled_inverse(A);
        const Eigen::Vector3d d0 = (A_inv * f0.normal).normalized();
        const Eigen::Vector3d d1 = (A_inv * f1.normal).normalized();
        const double c = std::max(-1.0, std::min(1.0, d0.dot(d1)));
        e.angle_deg = std::acos(c) * 180 / M_PI;
        feature = c < cos_angle;
        // Convex where f1 bends away from f0's outward normal (a linear map
        // with det > 0 keeps convexity, so the Euclidean test serves).
        const std::size_t w = f1.v[0] != a && f1.v[0] != b ? f1.v[0] : f1.v[1] != a && f1.v[1] != b ? f1.v[1] : f1.v[2];
        const Eigen::Vector3d pa = internal::to_eigen_vector(vertices_[a]->point());
        const double sign = f0.normal.dot(internal::to_eigen_vector(vertices_[w]->point()) - pa) > 0 ? -1 : 1;
        const double length = (A * (internal::to_eigen_vector(vertices_[b]->point()) - pa)).norm();
        e.turning = sign * length * std::atan2(d0.cross(d1).norm(), d0.dot(d1)); // exact 0 where flat
        if (!feature) smooth_turning_ += e.turning;
      }
      if (feature) edges_.push_back(e);
      first = last;
    }
  }

  // Feature curves of fewer than 3 edges are below the mesh's resolution:
  // those that meet no other feature (a lone kink between two facets of a
  // coarsely meshed smooth surface, e.g. Mesh_3's torus at the diagonal /
  // 20) and those with a free end that hang from a junction of curves (a
  // spur: where a coarsely meshed fillet meets a crease, a facet pair just
  // beyond the angle, e.g. Gmsh's anchor at a uniform size) are dropped,
  // until none is left (dropping two spurs of a junction can turn its third
  // curve into a spur): every tetrahedron around their ends would take a
  // corner's frame that fits none of the surface. Edges where parts of the
  // domain meet are always kept.
  void drop_short_curves() {
    const std::size_t nv = vertices_.size();
    std::vector<std::size_t> parent(nv), size(nv);
    std::vector<std::vector<std::size_t>> at(nv);
    auto root = [&](std::size_t v) {
      while (parent[v] != v) v = parent[v] = parent[parent[v]];
      return v;
    };
    for (bool dropping = true; dropping;) {
      for (std::size_t v = 0; v < nv; ++v) parent[v] = v, size[v] = 0, at[v].clear();
      for (const Feature_edge& e : edges_) parent[root(e.source)] = root(e.target);
      for (std::size_t k = 0; k < edges_.size(); ++k) {
        ++size[root(edges_[k].source)];
        at[edges_[k].source].push_back(k), at[edges_[k].target].push_back(k);
      }
      std::vector<char> drop(edges_.size(), 0);
      for (std::size_t k = 0; k < edges_.size(); ++k) drop[k] = edges_[k].facets == 2 && size[root(edges_[k].source)] < 3;
      for (std::size_t v = 0; v < nv; ++v) { // spurs from their free end v
        if (at[v].size() != 1 || drop[at[v][0]]) continue;
        std::size_t path[2], length = 0, w = v, k = at[v][0];
        bool manifold = true;
        while (length < 2) {
          path[length++] = k;
          manifold = manifold && edges_[k].facets == 2;
          w = edges_[k].source == w ? edges_[k].target : edges_[k].source;
          if (at[w].size() != 2) break;
          k = at[w][0] == k ? at[w][1] : at[w][0];
        }
        if (manifold && at[w].size() >= 3)
          for (std::size_t j = 0; j < length; ++j) drop[path[j]] = 1;
      }
      std::vector<Feature_edge> kept;
      for (std::size_t k = 0; k < edges_.size(); ++k)
        if (!drop[k]) kept.push_back(edges_[k]);
        else ++dropped_, smooth_turning_ += edges_[k].turning;
      dropping = kept.size() < edges_.size();
      edges_.swap(kept);
    }
  }

  // Vertices: the feature edges at each vertex, and its incident facets,
  // make it a curve vertex (with its tangent) or a corner (with its axes).
  void classify_vertices(const Metric_field& field, double cos_angle) {
    const std::size_t nv = vertices_.size();
    std::vector<std::vector<std::size_t>> edges_at(nv), facets_at(nv);
    for (std::size_t k = 0; k < edges_.size(); ++k) {
      edges_at[edges_[k].source].push_back(k);
      edges_at[edges_[k].target].push_back(k);
    }
    for (std::size_t i = 0; i < facets_.size(); ++i)
      for (std::size_t v : facets_[i].v) facets_at[v].push_back(i);
    for (std::size_t v = 0; v < nv; ++v) {
      const std::vector<std::size_t>& at = edges_at[v];
      if (at.empty()) continue;
      const Eigen::Matrix3d A = scaled(field.sqrt_metric(vertices_[v])); // only directions are used
      if (at.size() == 2) {
        const Eigen::Vector3d e0 = direction_from(v, edges_[at[0]]), e1 = direction_from(v, edges_[at[1]]);
        // Turning angle in the metric: between -A e0 and A e1.
        if (-(A * e0).normalized().dot((A * e1).normalized()) >= cos_angle) {
          kind_[v] = Feature_vertex_kind::curve;
          axes_[v].col(0) = (e1 - e0).normalized();
          ++curve_vertices_;
          continue;
        }
      }
      kind_[v] = Feature_vertex_kind::corner;
      ++corners_;
      axes_[v] = corner_axes(v, A, at, facets_at[v]);
    }
  }

  struct Facet {
    std::array<std::size_t, 3> v;
    Eigen::Vector3d normal;
    double area;
  };

  // A and A^{-1} up to a power-of-two factor: A divided exactly by the power
  // of two nearest its largest entry, so that no product or determinant of
  // a metric of scale 1e-300 or 1e300 under- or overflows (and a power of
  // two changes no bit of a direction). Only directions are taken from them.
  static Eigen::Matrix3d scaled(const Eigen::Matrix3d& A) {
    int e = 0;
    std::frexp(A.cwiseAbs().maxCoeff(), &e);
    return A * std::ldexp(1.0, -e);
  }
  static Eigen::Matrix3d scaled_inverse(const Eigen::Matrix3d& A) { return scaled(A).inverse(); }

  // The Euclidean unit direction of a feature edge, away from its vertex v.
  Eigen::Vector3d direction_from(std::size_t v, const Feature_edge& e) const {
    const std::size_t w = e.source == v ? e.target : e.source;
    return (internal::to_eigen_vector(vertices_[w]->point()) - internal::to_eigen_vector(vertices_[v]->point())).normalized();
  }

  // The best-fitting frame at a corner (see the class documentation), as
  // Euclidean unit hex-edge directions.
  Eigen::Matrix3d corner_axes(std::size_t v, const Eigen::Matrix3d& A, const std::vector<std::size_t>& edges,
                              const std::vector<std::size_t>& facets) const {
    const Eigen::Matrix3d A_inv = scaled_inverse(A);
    std::vector<Eigen::Vector3d> candidates, normals; // in the metric's orthonormal space
    std::vector<double> weights;
    for (std::size_t k : edges) candidates.push_back((A * direction_from(v, edges_[k])).normalized());
    for (std::size_t i : facets) {
      normals.push_back((A_inv * facets_[i].normal).normalized());
      weights.push_back(facets_[i].area);
      candidates.push_back(normals.back());
    }
    Eigen::Matrix3d best = Eigen::Matrix3d::Identity();
    double best_score = std::numeric_limits<double>::infinity();
    for (std::size_t a = 0; a < candidates.size(); ++a)
      for (std::size_t b = 0; b < candidates.size(); ++b) {
        const Eigen::Vector3d u = candidates[a];
        Eigen::Vector3d w = candidates[b] - candidates[b].dot(u) * u;
        if (w.norm() < 0.5) continue; // closer than 30 degrees to u (or opposite): no second axis
        w.normalize();
        Eigen::Matrix3d R;
        R << u, w, u.cross(w);
        double score = 0;
        for (std::size_t i = 0; i < normals.size(); ++i) {
          const double c = (R.transpose() * normals[i]).cwiseAbs().maxCoeff();
          score += weights[i] * (1 - c * c);
        }
        // Strictly better (beyond rounding) than the first frame found: ties
        // keep the earlier pair, so the choice does not depend on the last bits.
        if (!(best_score < std::numeric_limits<double>::infinity()) || score < best_score - 1e-12 * best_score)
          best_score = score, best = R;
      }
    // Back to Euclidean directions: the hex edges are A^{-1} R e_k.
    Eigen::Matrix3d axes = A_inv * best;
    for (int k = 0; k < 3; ++k) axes.col(k).normalize();
    return axes;
  }

  double angle_deg_;
  std::vector<Vertex_handle> vertices_;
  std::vector<Facet> facets_;
  std::vector<Feature_edge> edges_;
  std::vector<Feature_vertex_kind> kind_;
  std::vector<Eigen::Matrix3d> axes_; // tangent in column 0 (curve) or the corner's axes
  std::size_t curve_vertices_ = 0, corners_ = 0, dropped_ = 0;
  double smooth_turning_ = 0;
};

} // namespace CGAL_ext

#endif // CGAL_EXT_SHARP_FEATURES_3_H
