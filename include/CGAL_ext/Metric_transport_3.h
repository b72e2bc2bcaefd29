// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_METRIC_TRANSPORT_3_H
#define CGAL_EXT_METRIC_TRANSPORT_3_H

/// \file Metric_transport_3.h
/// The transport (rotation coefficient) `T(a->b)` of a piecewise-linear
/// metric field between two arbitrary points of a tetrahedral domain, along
/// the straight segment, with error control (MATH.md section 4).

#include <CGAL_ext/Cell_transport_3.h>
#include <CGAL_ext/Segment_walk_3.h>

#include <Eigen/Core>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <cstddef>
#include <cstdio>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

namespace CGAL_ext {

/// \ingroup PkgCGALExtTransport
/// The result of `Metric_transport_3`: a rotation, or the reason why there
/// is none.
struct Metric_transport_result {
  /// False if the segment is not inside the domain (or the input is not
  /// finite); `error` says why and `rotation` is the identity, not a guess.
  bool ok = true;
  /// Empty if `ok`; else, e.g. "the segment leaves the domain at t = 0.42".
  std::string error;
  /// `T(a->b)`: a rotation field parallel along the segment satisfies
  /// `R(b) = T(a->b) R(a)` (MATH.md section 4).
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  /// The rotation angle of `rotation`, in radians, in `[0, pi]`.
  double angle = 0;
  /// The sum of the pieces' error estimates, in radians.
  double error_estimate = 0;
  /// Evaluations of the connection `W`, summed over the pieces: the cost.
  std::size_t evaluations = 0;
  /// The number of pieces of positive length integrated (cells, facets, edges).
  std::size_t pieces = 0;
  /// False if a piece hit the depth cap or smallest step above its tolerance.
  bool converged = true;
};

/// \ingroup PkgCGALExtTransport
/// The transport `T(a->b)` of a metric field between two arbitrary points
/// of a tetrahedral domain, along the straight segment `[a, b]`.
///
/// The segment is cut by the exact walk (`Segment_walk_3::fast`) into its
/// pieces of positive length; each is integrated by `cell_transport()` with
/// `A` linear along it and a constant curl, and the pieces are composed
/// left-multiplied in path order, `T(a->b) = T_k ... T_2 T_1` (MATH.md
/// section 4, `T(a->c) = T(b->c) T(a->b)`):
/// - a piece inside a tetrahedron uses the tetrahedron's curl;
/// - a piece inside a facet (`A` is continuous, so linear on the facet) uses
///   the mean of the curls of the facet's domain cells (one on the boundary);
/// - a piece along an edge uses the mean of the curls of the edge's domain
///   cells, each weighted by its dihedral angle at the edge;
/// - pieces of zero length (crossings of facets, edges, vertices) contribute
///   nothing.
///
/// **Tolerance.** `Transport_options::tolerance` (radians) is shared among
/// the pieces in proportion to their parameter length, so that the
/// estimated errors add up to at most about `tolerance`: the returned
/// rotation is within about `tolerance` of the exact transport of the
/// piecewise-linear field along the segment (see `Transport_options` for
/// the nature of the estimates). The reported parameters of the pieces are
/// computed in double, so the piece boundaries carry a relative error of a
/// few ulps, far below any usable tolerance.
///
/// **Outside the domain.** If any part of the segment of positive length lies
/// outside the domain (an end point outside, or a non-convex domain left and
/// re-entered), the result has `ok == false` and says where; no rotation is
/// guessed over a gap. A segment that only touches the boundary from inside
/// is fine.
///
/// **Threads.** The transporter, the walk and the field are only read: one
/// transporter serves many threads. `transport_batch()` runs pairs in
/// parallel with TBB; each pair is computed alone, by the same code, so the
/// results are bit-identical for any number of threads.
///
/// \tparam Metric_field a metric field such as `Metric_field_3`: `A_at(c, p)`
///         and `curl(c)` for the domain cells `c`, and `triangulation()`
/// \tparam Domain_predicate the domain predicate of the walk (e.g.
///         `Is_tet_mesh_domain_cell`)
template <class Metric_field, class Domain_predicate>
class Metric_transport_3 {
public:
  /// The triangulation type.
  using Triangulation = std::decay_t<decltype(std::declval<const Metric_field&>().triangulation())>;
  /// The walk type.
  using Walk = Segment_walk_3<Triangulation, Domain_predicate>;
  /// Point type.
  using Point_3 = typename Triangulation::Point;
  /// Cell handle type.
  using Cell_handle = typename Triangulation::Cell_handle;

  /// \param field the metric field; it must outlive the transporter
  /// \param in_domain the domain predicate (the same as the field's domain)
  /// \throws std::invalid_argument if the triangulation has dimension < 3
  Metric_transport_3(const Metric_field& field, Domain_predicate in_domain)
      : field_(&field), walk_(field.triangulation(), std::move(in_domain)) {}

  /// The walk used to cut segments into pieces.
  const Walk& walk() const { return walk_; }

  /// `T(a->b)` along the segment `[a, b]`.
  /// \param a the start point
  /// \param b the end point
  /// \param opt the scheme and the tolerance in radians for the whole segment
  /// \param hint a domain cell near `a`, or a null handle
  /// \returns the rotation, or `ok == false` and the reason
  /// \throws std::invalid_argument if the tolerance is not positive and finite
  Metric_transport_result operator()(const Point_3& a, const Point_3& b, const Transport_options& opt = {},
                                     Cell_handle hint = Cell_handle()) const {
    if (!(opt.tolerance > 0) || !std::isfinite(opt.tolerance))
      throw std::invalid_argument("Metric_transport_3: the tolerance must be positive and finite");
    Metric_transport_result res;
    const double ax = CGAL::to_double(a.x()), ay = CGAL::to_double(a.y()), az = CGAL::to_double(a.z());
    const double bx = CGAL::to_double(b.x()), by = CGAL::to_double(b.y()), bz = CGAL::to_double(b.z());
    if (!std::isfinite(ax) || !std::isfinite(ay) || !std::isfinite(az) || !std::isfinite(bx) || !std::isfinite(by) ||
        !std::isfinite(bz))
      return failure(res, "a coordinate is not finite");

    // The walk gives few pieces; a small local buffer avoids heap traffic
    // in the common case.
    std::vector<Piece> pieces;
    pieces.reserve(16);
    walk_.fast(a, b, std::back_inserter(pieces), hint);

    const Eigen::Vector3d pa(ax, ay, az), d(bx - ax, by - ay, bz - az);
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    for (const Piece& piece : pieces) {
      if (piece.dimension < 0) {
        if (piece.t_in == 0)
          return failure(res, walk_.locate(a, hint).dimension < 0 ? "the start point is outside the domain"
                                                                  : "the segment leaves the domain at its start point");
        if (piece.t_out == 1)
          return failure(res, walk_.locate(b).dimension < 0
                                  ? "the end point is outside the domain (the segment leaves it at t = " +
                                        format(piece.t_in) + ")"
                                  : "the segment leaves the domain at t = " + format(piece.t_in) +
                                        " and comes back only at its end point");
        return failure(res, "the segment leaves the domain at t = " + format(piece.t_in) + " and re-enters it at t = " +
                                format(piece.t_out));
      }
      const double h = piece.t_out - piece.t_in;
      // If a == b, the one piece has the interval [0, 1] but no length; a
      // vertex piece has zero length; so may a piece below double resolution.
      if (d.isZero() || piece.dimension == 0 || !(h > 0)) continue;
      const Eigen::Vector3d x0 = pa + piece.t_in * d, x1 = pa + piece.t_out * d;
      const Point_3 p0(x0(0), x0(1), x0(2)), p1(x1(0), x1(1), x1(2));
      Transport_options piece_opt = opt;
      piece_opt.tolerance = opt.tolerance * h;
      const Transport_result t = cell_transport(field_->A_at(piece.cell, p0), field_->A_at(piece.cell, p1),
                                                piece_curl(piece), x1 - x0, piece_opt);
      R = t.rotation * R;
      res.error_estimate += t.error_estimate;
      res.evaluations += t.evaluations;
      res.converged = res.converged && t.converged;
      ++res.pieces;
    }
    res.rotation = res.pieces > 1 ? internal::reorthonormalized(R) : R;
    res.angle = rotation_angle(res.rotation);
    return res;
  }

  /// Transports of many pairs, in parallel with TBB: `out[i]` is
  /// `(*this)(pairs[i].first, pairs[i].second, opt)`, bit for bit, whatever
  /// the number of threads.
  /// \tparam Pair_range a random-access range of `std::pair<Point_3, Point_3>`
  /// \param pairs the `(a, b)` pairs
  /// \param opt the scheme and the tolerance in radians, for each pair
  /// \param out resized to `pairs.size()` and filled
  template <class Pair_range>
  void transport_batch(const Pair_range& pairs, const Transport_options& opt,
                       std::vector<Metric_transport_result>& out) const {
    out.assign(pairs.size(), Metric_transport_result());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pairs.size()), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) out[i] = (*this)(pairs[i].first, pairs[i].second, opt);
    });
  }

  /// The curl used for a piece of positive length: the cell's curl, the
  /// mean over the domain cells of a facet, or the dihedral-angle-weighted
  /// mean over the domain cells around an edge (MATH.md section 4).
  /// \param piece a piece of dimension 1, 2 or 3 from the walk
  /// \returns the 3x3 curl (column `i` is the curl of column `i` of `A`)
  Eigen::Matrix3d piece_curl(const Segment_walk_piece_3<Triangulation>& piece) const {
    const Cell_handle c = piece.cell;
    if (piece.dimension == 3) return field_->curl(c);
    if (piece.dimension == 2) {
      int opposite = 0; // the vertex of c not on the facet
      while (opposite < 3 && (c->vertex(opposite) == piece.vertices[0] || c->vertex(opposite) == piece.vertices[1] ||
                              c->vertex(opposite) == piece.vertices[2]))
        ++opposite;
      const Cell_handle n = c->neighbor(opposite);
      if (!walk_.is_domain_cell(n)) return field_->curl(c);
      return 0.5 * (field_->curl(c) + field_->curl(n));
    }
    // An edge: circulate around it (the triangulation closes the boundary
    // with infinite cells, so the circulation is complete).
    const Triangulation& tr = field_->triangulation();
    const int i = c->index(piece.vertices[0]), j = c->index(piece.vertices[1]);
    Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
    double weight = 0;
    auto circ = tr.incident_cells(typename Triangulation::Edge(c, i, j)), done = circ;
    do {
      const Cell_handle cc = circ;
      if (walk_.is_domain_cell(cc)) {
        const double w = dihedral_angle(cc, piece.vertices[0], piece.vertices[1]);
        sum += w * field_->curl(cc);
        weight += w;
      }
    } while (++circ != done);
    return sum / weight;
  }

private:
  using Piece = Segment_walk_piece_3<Triangulation>;
  using Vertex_handle = typename Triangulation::Vertex_handle;

  static Eigen::Vector3d vec(const Point_3& p) {
    return Eigen::Vector3d(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
  }
  // The interior dihedral angle of cell c at its edge (u, v), in (0, pi).
  static double dihedral_angle(Cell_handle c, Vertex_handle u, Vertex_handle v) {
    Vertex_handle w[2];
    int k = 0;
    for (int m = 0; m < 4; ++m)
      if (c->vertex(m) != u && c->vertex(m) != v) w[k++] = c->vertex(m);
    const Eigen::Vector3d o = vec(u->point()), e = vec(v->point()) - o;
    const Eigen::Vector3d n1 = e.cross(vec(w[0]->point()) - o), n2 = e.cross(vec(w[1]->point()) - o);
    return std::atan2(n1.cross(n2).norm(), n1.dot(n2));
  }
  static std::string format(double t) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", t);
    return buf;
  }
  static Metric_transport_result& failure(Metric_transport_result& res, std::string why) {
    res = Metric_transport_result();
    res.ok = false;
    res.error = std::move(why);
    return res;
  }

  const Metric_field* field_;
  Walk walk_;
};

} // namespace CGAL_ext

#endif // CGAL_EXT_METRIC_TRANSPORT_3_H
