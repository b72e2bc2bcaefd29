// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_METRIC_TRANSPORT_3_H
#define CGAL_EXT_METRIC_TRANSPORT_3_H

/// \file Metric_transport_3.h
/// The transport (rotation coefficient) `T(a->b)` of a piecewise-linear
/// metric field between two arbitrary points of a tetrahedral domain, along
/// the straight segment `[a, b]`, with error control in radians (doc/math.md
/// section 4), one pair at a time or a threaded batch.

#include <CGAL_ext/Cell_transport_3.h>
#include <CGAL_ext/Metric_field_3.h>
#include <CGAL_ext/Segment_walk_3.h>

#include <CGAL/number_utils.h>

#include <Eigen/Core>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <cstddef>
#include <cstdio>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace CGAL_ext {

namespace internal {
// The walk's domain predicate for a cell index map.
template <class CellIndexMap>
struct Domain_predicate_of {
  using type = Is_indexed_domain_cell<CellIndexMap>;
  static type make(CellIndexMap cim) { return type(cim); }
};
template <class Triangulation>
struct Domain_predicate_of<Tet_mesh_cell_index_map<Triangulation>> {
  using type = Is_tet_mesh_domain_cell;
  static type make(Tet_mesh_cell_index_map<Triangulation>) { return type(); }
};
} // namespace internal

/// \ingroup PkgCGALExtTransport
/// The result of `Metric_transport_3`: the transport `T(a->b)`, or the reason
/// why there is none.
struct Metric_transport_result {
  /// False if a part of the segment lies outside the domain or a coordinate
  /// is not finite; `message` then says why, and `rotation` is the identity, not a
  /// guess.
  bool ok = true;
  /// Empty if `ok`; else the reason, e.g. "the segment leaves the domain at
  /// t = 0.42 and re-enters it at t = 0.71".
  std::string message;
  /// `T(a->b)`: a rotation field parallel along the segment satisfies
  /// `R(b) = T(a->b) R(a)` (doc/math.md section 4).
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  /// The rotation angle of `rotation` (`rotation_angle(rotation)`), in radians, in `[0, pi]`.
  double angle = 0;
  /// The number of evaluations of the connection `W` (each with the piece's
  /// curl), summed over the pieces: the measure of the cost.
  std::size_t evaluations = 0;
  /// The number of pieces of positive length that were integrated (inside
  /// cells, facets or along edges).
  std::size_t pieces = 0;
  /// The sum of the pieces' error estimates, in radians.
  double error_estimate = 0;
  /// False if a piece was accepted at the integrator's depth cap or smallest
  /// step with an estimate above its share of the tolerance.
  bool converged = true;
  /// If `!ok` because of the domain: the parameter `t` in `[0, 1]` of
  /// `a + t (b - a)` where the segment first leaves the closed domain (0 if
  /// `a` is outside). NaN otherwise.
  double exit_t = std::numeric_limits<double>::quiet_NaN();
};

/// \ingroup PkgCGALExtTransport
/// The transport `T(a->b)` of a piecewise-linear metric field between two
/// arbitrary points of a tetrahedral domain, along the straight segment
/// `x(t) = a + t (b - a)`, `t` in `[0, 1]`.
///
/// **Pieces.** The exact walk in fast mode (`Segment_walk_3::fast()`) cuts the
/// segment into its pieces of positive length, each with the simplex whose
/// relative interior contains it. On each piece, `A` is linear along the
/// segment and the curl is taken constant, so the piece is integrated by
/// `cell_transport()` (Cell_transport_3.h: trapezoid or Magnus-4, adaptive):
/// - inside a tetrahedron: `A` of the tetrahedron and its (constant) curl;
/// - inside a facet: `A` interpolated from the facet's three vertices (`A` is
///   continuous, so this is the trace of both incident cells' fields), and
///   the mean of the curls of the facet's domain cells (two, or one on the
///   boundary): the curl jumps across the facet, and its mean is the
///   symmetric choice (doc/math.md section 4);
/// - along an edge: `A` interpolated from the edge's two vertices, and the
///   mean of the curls of all the domain cells around the edge, each
///   weighted by its interior dihedral angle at the edge, so that the value
///   is the angular average of the cells' curls around the edge;
/// - a piece of zero length (a crossing of a facet, an edge or a vertex, or
///   `a == b`) contributes nothing.
///
/// **Order.** The pieces are composed left-multiplied in path order,
/// `T(a->b) = T_k ... T_2 T_1` for pieces `1..k` from `a` to `b`, which is
/// doc/math.md section 4's `T(a->c) = T(b->c) T(a->b)`.
///
/// **Tolerance.** `Transport_options::tolerance` `tol` (radians) is shared among
/// the pieces in proportion to their parameter length: a piece
/// `[t_in, t_out]` is integrated with tolerance `tol (t_out - t_in)`, and
/// inside it each accepted step of `cell_transport()` has an error estimate
/// at most its share again. Since the geodesic distance of SO(3) is
/// bi-invariant, the error of a product of rotations is at most the sum of
/// the errors of its factors; so the returned `rotation` is within the sum of the
/// step errors, estimated at most `tol` in total (`error_estimate`), of the
/// exact transport of the piecewise-linear field defined above (plus rounding,
/// about 1e-15 per piece). The step estimates are asymptotic (the difference
/// between one step and two half steps), not rigorous bounds; the tests
/// check `||rotation - exact|| <= tol` against an independent integration for tol
/// in {1e-4, 1e-6, 1e-8}. The piece boundaries are the walk's parameters in
/// double (a few ulps of relative error), far below any usable tolerance.
///
/// **Outside the domain.** If a part of positive length of the segment lies
/// outside the closed domain (an end point outside, or a non-convex domain
/// left and re-entered), or a coordinate is not finite, the result has
/// `ok == false` and a message saying where; no rotation is guessed over a
/// gap. A segment along the boundary (inside the closed domain) is fine.
///
/// **Threads.** The transporter only reads the field and the walk, so one
/// transporter may serve many threads. `Metric_field_3` computes its per-cell
/// data (curl, inverse edge matrix) on first use behind an atomic flag and a
/// striped lock, which is safe under concurrent reads and gives the same bits
/// in any order; calling `Metric_field_3::precompute()` first avoids the
/// locks altogether. The walk builds its location grid and boundary tree
/// lazily and thread-safely. `transport_batch()` computes pairs in parallel,
/// each one alone by the same code into its own slot, so its results are
/// bit-identical for any number of threads and equal to single calls.
///
/// **Domain.** The domain is the metric field's: the cells with a
/// non-negative index in its cell index map (`MetricField_3::cell_index_map()`),
/// so the walk, the field and a frame field on it always agree.
///
/// \tparam Metric_field a model of `MetricField_3` on a model of
///         `TetMeshTriangulation_3` (positively oriented finite cells), by
///         default `Metric_field_3<Tet_mesh_triangulation_3<>>`
template <class Metric_field = Metric_field_3<Tet_mesh_triangulation_3<>>>
class Metric_transport_3 {
public:
  /// The triangulation type.
  using Triangulation = typename Metric_field::Triangulation_3;
  /// The predicate that tells the field's domain cells to the walk:
  /// `Is_tet_mesh_domain_cell` for the default cell index map (the walk that
  /// the other components instantiate), else `Is_indexed_domain_cell`.
  using Domain_predicate = typename internal::Domain_predicate_of<typename Metric_field::Cell_index_map>::type;
  /// The walk type.
  using Walk = Segment_walk_3<Triangulation, Domain_predicate>;
  /// Point type.
  using Point_3 = typename Triangulation::Point;
  /// Cell handle type.
  using Cell_handle = typename Triangulation::Cell_handle;
  /// Vertex handle type.
  using Vertex_handle = typename Triangulation::Vertex_handle;
  /// A piece of the walk.
  using Piece = Segment_walk_piece_3<Triangulation>;

  /// \param field the metric field; it must outlive the transporter and not
  ///        change while the transporter is in use
  /// \throws std::invalid_argument if the triangulation has dimension < 3
  explicit Metric_transport_3(const Metric_field& field)
      : field_(&field), walk_(field.triangulation(), internal::Domain_predicate_of<typename Metric_field::Cell_index_map>::make(field.cell_index_map())) {}

  /// The metric field.
  /// \returns the metric field given to the constructor
  const Metric_field& field() const { return *field_; }

  /// The walk used to cut segments into pieces.
  /// \returns the walk, on the field's triangulation and domain
  const Walk& walk() const { return walk_; }

  /// `T(a->b)` along the segment `[a, b]`.
  /// \param a the start point
  /// \param b the end point
  /// \param opt the scheme and the tolerance in radians for the whole segment
  /// \param hint a domain cell near `a` (speeds up the location), or a null handle
  /// \returns the rotation, or `ok == false` and the reason
  /// \throws std::invalid_argument if the tolerance is not positive and finite
  Metric_transport_result transport(const Point_3& a, const Point_3& b, const Transport_options& opt = {},
                                    Cell_handle hint = Cell_handle()) const {
    check_tolerance(opt);
    Metric_transport_result res;
    const Eigen::Vector3d pa = internal::to_eigen_vector(a), pb = internal::to_eigen_vector(b);
    if (!pa.allFinite() || !pb.allFinite()) return failure(res, "a coordinate is not finite", res.exit_t);

    std::vector<Piece> pieces;
    pieces.reserve(16);
    walk_.fast(a, b, std::back_inserter(pieces), hint);

    // A gap fails the whole segment: find it before integrating anything.
    for (const Piece& piece : pieces)
      if (piece.dimension < 0) return gap_failure(res, piece, a, b, hint);
    const Eigen::Vector3d d = pb - pa;
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    for (const Piece& piece : pieces) {
      const double h = piece.t_out - piece.t_in;
      // a == b gives one piece [0, 1] of zero length; a vertex piece has zero
      // length; a piece shorter than the double resolution of t turns by less
      // than |u| * ulp(t), far below any tolerance.
      if (d.isZero() || piece.dimension == 0 || !(h > 0)) continue;
      const Eigen::Vector3d x0 = pa + piece.t_in * d, x1 = pa + piece.t_out * d;
      Transport_options piece_opt = opt;
      piece_opt.tolerance = opt.tolerance * h; // the share of this piece
      const Transport_result t =
          cell_transport(piece_A(piece, x0), piece_A(piece, x1), piece_curl(piece), x1 - x0, piece_opt);
      R = t.rotation * R; // path order: the later piece acts last (doc/math.md section 4)
      res.error_estimate += t.error_estimate;
      res.evaluations += t.evaluations;
      res.converged = res.converged && t.converged;
      ++res.pieces;
    }
    // A product of many rotations drifts from SO(3) by rounding; one piece is
    // already re-orthonormalized by cell_transport(), and the identity stays exact.
    res.rotation = res.pieces > 1 ? internal::reorthonormalized(R) : R;
    res.angle = rotation_angle(res.rotation);
    return res;
  }

  /// Same as `transport()`.
  /// \param a the start point
  /// \param b the end point
  /// \param opt the scheme and the tolerance in radians for the whole segment
  /// \param hint a domain cell near `a`, or a null handle
  /// \returns `transport(a, b, opt, hint)`
  Metric_transport_result operator()(const Point_3& a, const Point_3& b, const Transport_options& opt = {},
                                     Cell_handle hint = Cell_handle()) const {
    return transport(a, b, opt, hint);
  }

  /// The transports of many pairs, in parallel with TBB: `out[i]` is
  /// `transport(pairs[i].first, pairs[i].second, opt)`, bit for bit, whatever
  /// the number of threads (each pair is computed alone and written to its
  /// own slot).
  /// \tparam Pair_range a random-access range of pairs of `Point_3` (e.g.
  ///         `std::vector<std::pair<Point_3, Point_3>>`)
  /// \param pairs the `(a, b)` pairs
  /// \param opt the scheme and the tolerance in radians, for each pair
  /// \param out resized to `pairs.size()` and filled
  /// \throws std::invalid_argument if the tolerance is not positive and finite
  template <class Pair_range>
  void transport_batch(const Pair_range& pairs, const Transport_options& opt,
                       std::vector<Metric_transport_result>& out) const {
    check_tolerance(opt); // here, not inside the parallel loop
    const std::size_t n = static_cast<std::size_t>(std::size(pairs));
    out.assign(n, Metric_transport_result());
    // Grain 1: a pair costs from a microsecond (a short segment, a smooth
    // field) to a second (a long one in a rough field); the partitioner
    // coarsens cheap ranges itself.
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) out[i] = transport(pairs[i].first, pairs[i].second, opt);
    });
  }

  /// The curl used on a piece of positive length (doc/math.md section 4): the
  /// cell's curl; on a facet the mean of the curls of its domain cells (one
  /// or two); on an edge the mean of the curls of its domain cells, each
  /// weighted by its interior dihedral angle at the edge.
  /// \param piece a piece of dimension 1, 2 or 3 from the walk
  /// \returns the 3x3 curl (column `i` is the curl of column `i` of `A`)
  Eigen::Matrix3d piece_curl(const Piece& piece) const {
    const Cell_handle c = piece.cell;
    if (piece.dimension == 3) return field_->curl(c);
    if (piece.dimension == 2) {
      const int opposite = 6 - c->index(piece.vertices[0]) - c->index(piece.vertices[1]) - c->index(piece.vertices[2]);
      const Cell_handle n = c->neighbor(opposite);
      if (!walk_.is_domain_cell(n)) return field_->curl(c);
      return 0.5 * (field_->curl(c) + field_->curl(n));
    }
    // An edge: every cell around it. build_triangulation_from_tets() closes
    // the boundary with infinite cells paired around the edge, also where the
    // domain touches itself along the edge, so one circulation sees them all.
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

  /// The square root `A` at a point of a piece: the cell's linear field for a
  /// cell piece; for a facet or an edge, the linear interpolation of the
  /// simplex's own vertices only (the point's barycentric coordinates in the
  /// piece's cell, without those of the other vertices, which are zero up to
  /// rounding), so that every cell around the simplex gives the same `A`.
  /// \param piece a piece of dimension 1, 2 or 3 from the walk
  /// \param x a point of the piece
  /// \returns `A` at `x` (3x3, symmetric)
  Eigen::Matrix3d piece_A(const Piece& piece, const Eigen::Vector3d& x) const {
    const Cell_handle c = piece.cell;
    const Point_3 p(x(0), x(1), x(2));
    if (piece.dimension == 3) return field_->A_at(c, p);
    const Eigen::Vector4d l = field_->barycentric_coordinates(c, p);
    const int n = piece.dimension + 1;
    double w[3], sum = 0;
    for (int k = 0; k < n; ++k) sum += (w[k] = l(c->index(piece.vertices[k])));
    if (!(sum > 0.5)) return field_->A_at(c, p); // cannot happen for a point of the simplex
    // Differences from the first vertex, so that a constant field stays exact.
    const Eigen::Matrix3d& A0 = field_->sqrt_metric(piece.vertices[0]);
    Eigen::Matrix3d A = A0;
    for (int k = 1; k < n; ++k) A += (w[k] / sum) * (field_->sqrt_metric(piece.vertices[k]) - A0);
    return A;
  }

private:

  static void check_tolerance(const Transport_options& opt) {
    if (!(opt.tolerance > 0) || !std::isfinite(opt.tolerance))
      throw std::invalid_argument("Metric_transport_3: the tolerance must be positive and finite");
  }

  // The interior dihedral angle of the cell c at its edge (u, v), in (0, pi).
  static double dihedral_angle(Cell_handle c, Vertex_handle u, Vertex_handle v) {
    Vertex_handle w[2];
    int k = 0;
    for (int m = 0; m < 4; ++m)
      if (c->vertex(m) != u && c->vertex(m) != v) w[k++] = c->vertex(m);
    const Eigen::Vector3d o = internal::to_eigen_vector(u->point()), e = internal::to_eigen_vector(v->point()) - o;
    const Eigen::Vector3d n1 = e.cross(internal::to_eigen_vector(w[0]->point()) - o), n2 = e.cross(internal::to_eigen_vector(w[1]->point()) - o);
    return std::atan2(n1.cross(n2).norm(), n1.dot(n2));
  }


  static Metric_transport_result failure(Metric_transport_result& res, std::string why, double exit_t) {
    res = Metric_transport_result();
    res.ok = false;
    res.message = std::move(why);
    res.exit_t = exit_t;
    return res;
  }

  // The first gap of the walk: say where the segment leaves the domain and,
  // if it comes back, where. The end points are located only on this path.
  Metric_transport_result gap_failure(Metric_transport_result& res, const Piece& gap, const Point_3& a,
                                      const Point_3& b, Cell_handle hint) const {
    if (gap.t_in == 0) {
      if (walk_.locate(a, hint).dimension < 0) return failure(res, "the start point is outside the domain", 0.0);
      return failure(res, "the segment leaves the domain at its start point (t = 0)", 0.0);
    }
    const std::string leaves = "the segment leaves the domain at t = " + format_number(gap.t_in, 6);
    if (gap.t_out == 1) {
      if (walk_.locate(b).dimension < 0)
        return failure(res, "the end point is outside the domain (" + leaves + ")", gap.t_in);
      return failure(res, leaves + " and comes back only at its end point", gap.t_in);
    }
    return failure(res, leaves + " and re-enters it at t = " + format_number(gap.t_out, 6), gap.t_in);
  }

  const Metric_field* field_;
  Walk walk_;
};

} // namespace CGAL_ext

#endif // CGAL_EXT_METRIC_TRANSPORT_3_H
