// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_DOMAIN_THICKNESS_3_H
#define CGAL_EXT_DOMAIN_THICKNESS_3_H

/// \file Domain_thickness_3.h
/// How thick a tetrahedral domain is behind each boundary facet, in a
/// metric: the parts thinner than a hex edge, which hexahedra of that size
/// cannot fill.

#include <CGAL_ext/Metric_transport_3.h>
#include <CGAL_ext/Segment_walk_3.h>
#include <CGAL_ext/Sharp_features_3.h>
#include <CGAL_ext/internal/deterministic_parallel.h>

#include <Eigen/Core>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace CGAL_ext {

/// \ingroup PkgCGALExtFrames
/// The thickness of a domain behind each of its boundary facets, measured
/// in a metric: from the facet's centroid along the inward metric normal
/// (`-g^{-1} n`, the direction of the shortest way to a parallel plane in
/// the metric), the metric length inside the domain until the ray first
/// leaves it, up to a cap.
///
/// Hexahedra of edge `l` cannot fill a part thinner than `l`: an
/// integer-grid map rounds such a part to zero or one layer of hexahedra,
/// and its singular curves, squeezed between the two sides' boundary
/// conditions, are rarely meshable. For the pipeline's fields (the metric
/// scaled so that a hex edge is 1) `area_fraction_below(1)` is the share of
/// the boundary where that happens, and `area_quantile(q)` the factor by
/// which the hex edge must shrink for only a share `q` of it to remain.
///
/// The rays are walked with `Segment_walk_3` (exact predicates, re-entries
/// of non-convex domains found), on the domain of the metric field; the
/// length of each piece is integrated in the metric of a tetrahedron that
/// holds it (Simpson's rule on the linear `A`: exact where `|A d|` varies
/// linearly along the piece, as in a constant metric; otherwise its error
/// falls with the fifth power of the piece's length). A ray is walked in
/// legs sized from the metric met so far, until it leaves the domain or its
/// length reaches the cap; one that reaches the cap counts as the cap. The
/// result does not depend on the number of threads.
///
/// \tparam Metric_field a model of `MetricField_3`, such as `Metric_field_3<Tr>`
template <class Metric_field>
class Domain_thickness_3 {
public:
  /// The triangulation type.
  using Triangulation = typename Metric_field::Triangulation_3;
  /// Cell handle type.
  using Cell_handle = typename Triangulation::Cell_handle;
  /// The walk type (the one `Metric_transport_3` uses on this field).
  using Walk = typename Metric_transport_3<Metric_field>::Walk;

  /// A boundary facet and the domain's thickness behind it.
  struct Facet {
    std::size_t tet = 0;   ///< the index of its tetrahedron (`MetricField_3::cell_index_map()`)
    int facet = 0;         ///< its local index in that tetrahedron (opposite vertex)
    double metric_area = 0; ///< its area in the metric at its centroid
    double thickness = 0;  ///< the thickness behind it in the metric, at most `max_thickness()`
  };

  /// Measures the thickness behind every boundary facet of the field's domain.
  /// \param field the metric field; only read during the construction
  /// \param max_thickness the cap, in the metric: positive and finite
  /// \throws std::invalid_argument if `max_thickness` is not positive and finite
  Domain_thickness_3(const Metric_field& field, double max_thickness) : max_(max_thickness) {
    if (!(max_thickness > 0) || !std::isfinite(max_thickness))
      throw std::invalid_argument("Domain_thickness_3: the largest thickness must be positive and finite (got " +
                                  std::to_string(max_thickness) + ")");
    const Triangulation& tr = field.triangulation();
    const auto cim = field.cell_index_map();
    const Walk walk(tr, internal::Domain_predicate_of<typename Metric_field::Cell_index_map>::make(cim));
    std::vector<Cell_handle> cells, facet_cells;
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (auto c = tr.finite_cells_begin(); c != tr.finite_cells_end(); ++c)
      if (get(cim, c) >= 0) {
        cells.push_back(c);
        for (int v = 0; v < 4; ++v) {
          const Eigen::Vector3d p = internal::to_eigen_vector(c->vertex(v)->point());
          lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
        }
      }
    diagonal_ = cells.empty() ? 0 : (hi - lo).norm();
    std::sort(cells.begin(), cells.end(), [&](Cell_handle a, Cell_handle b) { return get(cim, a) < get(cim, b); });
    for (Cell_handle c : cells)
      for (int f = 0; f < 4; ++f) {
        const Cell_handle n = c->neighbor(f);
        if (tr.is_infinite(n) || get(cim, n) < 0) {
          facets_.push_back({std::size_t(get(cim, c)), f, 0, 0});
          facet_cells.push_back(c);
        }
      }
    internal::parallel_for_each_index(facets_.size(),
                                      [&](std::size_t k) { measure(field, walk, facet_cells[k], facets_[k]); });
    for (const Facet& f : facets_) total_area_ += f.metric_area;
  }

  /// The boundary facets with their thickness, by tetrahedron index, then local facet.
  /// \returns the facets
  const std::vector<Facet>& facets() const { return facets_; }

  /// The cap given to the constructor.
  /// \returns the cap: no facet's thickness exceeds it
  double max_thickness() const { return max_; }

  /// The metric area of the boundary.
  /// \returns the sum of the facets' metric areas
  double total_area() const { return total_area_; }

  /// The share of the boundary (by metric area) whose thickness is below `t`.
  /// \param t a thickness in the metric
  /// \returns a number in [0, 1]; 0 for an empty boundary
  double area_fraction_below(double t) const {
    double a = 0;
    for (const Facet& f : facets_)
      if (f.thickness < t) a += f.metric_area;
    return total_area_ > 0 ? a / total_area_ : 0;
  }

  /// The thickness under which lies a share `q` of the boundary (by metric
  /// area): the smallest facet thickness `t` such that the facets of
  /// thickness at most `t` hold at least `q` of the area. Hexahedra `t`
  /// times as large as the metric's unit leave at most `q` of the boundary
  /// thinner than one of their edges.
  /// \param q the share, in [0, 1]
  /// \returns the thickness, at most `max_thickness()`; NaN for an empty
  ///          boundary or a `q` outside [0, 1]
  double area_quantile(double q) const {
    if (facets_.empty() || !(q >= 0 && q <= 1)) return std::numeric_limits<double>::quiet_NaN();
    std::vector<const Facet*> order;
    for (const Facet& f : facets_) order.push_back(&f);
    std::stable_sort(order.begin(), order.end(), [](const Facet* a, const Facet* b) { return a->thickness < b->thickness; });
    double a = 0;
    for (const Facet* f : order) {
      a += f->metric_area;
      if (a >= q * total_area_) return f->thickness;
    }
    return order.back()->thickness;
  }

private:
  using Point = typename Triangulation::Point;
  using Piece = Segment_walk_piece_3<Triangulation>;

  static Point point(const Eigen::Vector3d& v) { return Point(v(0), v(1), v(2)); }

  // The metric length of [a, b] inside cell c: Simpson's rule on |A(x) (b - a)|.
  static double metric_length(const Metric_field& field, Cell_handle c, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    const Eigen::Vector3d d = b - a;
    return ((field.A_at(c, point(a)) * d).norm() + 4 * (field.A_at(c, point((a + b) / 2)) * d).norm() +
            (field.A_at(c, point(b)) * d).norm()) /
           6;
  }

  void measure(const Metric_field& field, const Walk& walk, Cell_handle c, Facet& f) const {
    Eigen::Vector3d centroid, n; // n: the outward unit normal
    double area;
    internal::boundary_facet_geometry(c, f.facet, centroid, n, area);
    // A = As 2^e with As's entries below 1: the inverse and determinant of a
    // metric of scale 1e-300 (hexes of 1e150) or 1e300 would under- or
    // overflow (a determinant of 1e-450), powers of two change no bit.
    const Eigen::Matrix3d A = field.A_at(c, point(centroid));
    int e = 0;
    std::frexp(A.cwiseAbs().maxCoeff(), &e);
    const Eigen::Matrix3d As = A * std::ldexp(1.0, -e);
    const Eigen::Matrix3d As_inv = As.inverse();
    const Eigen::Vector3d m = As_inv.transpose() * n; // A^{-T} n 2^e
    // Nanson: the metric area vector is det(A) A^{-T} (area n).
    f.metric_area = std::ldexp(As.determinant() * m.norm() * area, 2 * e);
    // The inward metric normal g^{-1} n = A^{-1} A^{-T} n, of unit length in
    // the metric at the centroid: -(As^{-1} m) / |m| 2^-e.
    const Eigen::Vector3d inward = -(As_inv * m) * (std::ldexp(1.0, -e) / m.norm());
    // Walk on in legs until the ray leaves the domain or its length reaches
    // the cap. Each leg is a quarter longer than the length left needs at
    // the metric's rate on the last leg (at first, the centroid's), at
    // most 16 times the last: a metric that shrinks inward (hexes growing)
    // takes a few more legs, never a length short of the cap. 64 legs
    // would be a growth of 16^63; no leg is longer than twice the domain's
    // bounding-box diagonal, which any ray still inside leaves.
    const double longest = 2 * diagonal_ / inward.norm();
    double length = 0, leg_length = std::min(1.25 * max_, longest); // in multiples of `inward` (unit length in the centroid's metric)
    bool entered = false;
    Eigen::Vector3d from = centroid;
    Cell_handle hint = c;
    std::vector<Piece> pieces;
    for (int leg = 0; leg < 64; ++leg) {
      const Eigen::Vector3d to = from + leg_length * inward;
      pieces.clear();
      walk.fast(point(from), point(to), std::back_inserter(pieces), hint);
      const double before = length;
      for (const Piece& piece : pieces) {
        if (piece.dimension < 0) {
          if (entered) { // left the domain
            f.thickness = length >= max_ * (1 - 1e-12) ? max_ : length;
            return;
          }
          continue; // the centroid rounded to just outside its facet
        }
        entered = true;
        // A piece along a facet or an edge (dimension < 3) is measured in
        // one of its cells: A is continuous, so any gives the same up to rounding.
        const Eigen::Vector3d a = from + piece.t_in * (to - from), b = from + piece.t_out * (to - from);
        length += metric_length(field, piece.cell, a, b);
        hint = piece.cell;
      }
      if (!entered) { // only possible for a facet too flat to have an inside: nothing behind it
        f.thickness = 0;
        return;
      }
      if (length >= max_ * (1 - 1e-12)) break; // (not a last leg of a few ulps)
      const double gained = length - before; // 0 only for a leg below an ulp
      leg_length = std::min(longest, gained > 0 ? std::min(16 * leg_length, 1.25 * (max_ - length) * leg_length / gained)
                                                : 16 * leg_length);
      from = to;
    }
    f.thickness = max_;
  }

  double max_;
  double diagonal_ = 0; // of the domain's bounding box: a longer leg leaves the domain
  std::vector<Facet> facets_;
  double total_area_ = 0;
};

} // namespace CGAL_ext

#endif // CGAL_EXT_DOMAIN_THICKNESS_3_H
